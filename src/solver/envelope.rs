//! The stress envelope's per-step work (issue 30): every station's stress from the modal state,
//! its running largest |value| and when it was reached.
//!
//! A station's stress is (s_k . Phi q + s_k^T R f) / divisor: its functional over its beam's modes
//! plus the discarded modes' static response to the step's loads (the correction's coefficients
//! times the load coefficients c of [`super::static_correction::Correction`]). Each beam's
//! stations are one dense matrix-vector product per step, stored column by column (a mode's or a
//! load's values at every station of the beam, contiguous), so that the product runs down the
//! stations four columns at a time in vector registers: about 1.5 us a step for the converged
//! printed rung's 344 stations x 33 modes and 7 loads per beam (`beam-impact bench`), cheaper than
//! proving stations unable to rise (the bound-and-skip scheme this replaced cost 4-7 us a step),
//! and every station's envelope value exact at every step. The stations are evaluated at the
//! internal steps' ends; over the exact advance's contact steps, which grow long (the bar's force
//! a cubic over them), also at the largest |value| of each station's cubic through its values and
//! rates at the step's ends ([`StationRows::observe_step`]: a second product, the rates), as the
//! five probes of Table 1 take theirs over every step (see [`crate::model::stations`] for where
//! the stations sit).
//!
//! A run that needs each envelope's peak only (an answer's check runs, a sweep's rows:
//! [`EnvelopeScope::Peaks`]) tests a bound first, sum_j max_k |column_jk| |w_j| over an
//! envelope's stations and then over chunks of [`CHUNK`] of them, against the envelope's peak and
//! worst utilisation so far, and evaluates only the chunks that could raise them: about one chunk
//! in ten a step, 3.9x fewer instructions in the products and 17 % fewer in whole runs
//! (callgrind, the default scenario at damping 0.03), the same peaks to the bit.

use std::ops::Range;

use super::modal::ModalSystem;
use super::static_correction::LOADS;

/// Multiply-adds per step the envelope may take before it is sampled at a stride instead of
/// every step (or [`ENVELOPE_PER_MODE`] per mode, if more): the converged printed rung (344
/// stations x 40 columns of their beams, 13 760) stays below it; a full basis of hundreds of
/// elements (a test of the stepper, O(n^2) stations x modes against the stepper's O(n)) samples
/// every k-th step, and says so.
pub const ENVELOPE_BUDGET: usize = 1 << 15;

/// Multiply-adds per mode and step the envelope may take on a large basis: about the stepper's
/// own work per mode.
pub const ENVELOPE_PER_MODE: usize = 8;

/// Stations a chunk holds at most: the unit a step's bound may skip (with
/// [`EnvelopeScope::Peaks`]). Measured on the default scenario's rungs (drop heights 0.16-2.06 m,
/// damping 0.01 and 0.03): about 1 chunk in 10 is evaluated a step.
pub const CHUNK: usize = 16;

/// Relative margin on a bound: a computed sum of ~50 products may exceed the exact sum of their
/// magnitudes by ~1e-14 relative (round-off); the margin covers that ten thousand times.
const BOUND_MARGIN: f64 = 1.0 + 1e-10;

/// Which of a run's running largest stresses must be exact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvelopeScope {
    /// Every station's largest |stress| and when it was reached: the envelope a log and
    /// `report` draw along the beams. Every station is evaluated every step.
    #[default]
    Stations,
    /// Each envelope's peak (its largest |stress| and worst utilisation, where and when), what
    /// an answer's check runs and a sweep's rows take: stations whose bound stays below them are
    /// skipped, and a skipped station keeps a smaller running value.
    Peaks,
}

/// One beam's stations as a dense block: its modes' and loads' columns.
#[derive(Clone, Debug, Default)]
struct Block {
    /// The block's stations (indices into the station order).
    stations: Range<usize>,
    /// The beam's modes (indices into q).
    modes: Range<usize>,
    /// Column-major, (modes + [`LOADS`]) columns of `stations.len()` values: a mode's stress per
    /// unit q (Pa), then a load's per unit load coefficient, each already divided by the
    /// station's divisor.
    columns: Vec<f64>,
}

impl Block {
    /// Column `j`'s values at the block's stations.
    fn column(&self, j: usize) -> &[f64] {
        let m = self.stations.len();
        &self.columns[j * m..(j + 1) * m]
    }

    /// Each column's weight's magnitude under the state `q` (its beam's kept modes) and `loads`
    /// (0 for a column neither weights), into `out` (one per column).
    /// Every entry is written once (no clearing pass: it runs twice a step).
    fn magnitudes(&self, q: &[f64], loads: Option<&[f64; LOADS]>, out: &mut Vec<f64>) {
        out.resize(self.modes.len() + LOADS, 0.0);
        let (modes, load_columns) = out.split_at_mut(self.modes.len());
        let kept = &q[self.modes.start.min(q.len())..self.modes.end.min(q.len())];
        let (weighted, unweighted) = modes.split_at_mut(kept.len());
        for (o, w) in weighted.iter_mut().zip(kept) {
            *o = w.abs();
        }
        unweighted.fill(0.0);
        match loads {
            Some(loads) => {
                for (o, w) in load_columns.iter_mut().zip(loads) {
                    *o = w.abs();
                }
            }
            None => load_columns.fill(0.0),
        }
    }
}

/// Stations of one block and one envelope with each column's largest |value| over them:
/// sum_j colmax_j |w_j| bounds |stress| at each of them for the weights w.
#[derive(Clone, Debug, Default)]
struct Span {
    /// Its block.
    block: usize,
    /// Its stations within the block.
    local: Range<usize>,
    /// The same stations in the station order.
    stations: Range<usize>,
    /// Its envelope ([`groups`]).
    group: u8,
    /// Per column of its block, the largest |value| over its stations.
    column_max: Vec<f64>,
    /// The smallest allowable stress among its stations, Pa (infinite: none given).
    smallest_allowable: f64,
}

impl Span {
    /// The span of `block` (number `index`) over its stations `local`.
    fn new(block: &Block, index: usize, local: Range<usize>, groups: &[u8], allowables: &[f64]) -> Span {
        let stations = block.stations.start + local.start..block.stations.start + local.end;
        let columns = block.modes.len() + LOADS;
        let column_max =
            (0..columns).map(|j| block.column(j)[local.clone()].iter().fold(0.0f64, |a, v| a.max(v.abs()))).collect();
        let smallest_allowable =
            allowables[stations.clone()].iter().filter(|a| **a > 0.0).fold(f64::INFINITY, |a, v| a.min(*v));
        Span { block: index, local, group: groups[stations.start], stations, column_max, smallest_allowable }
    }

    /// The bound of |stress| over the span's stations at the weights' magnitudes `magnitudes`
    /// (one per column of its block, [`Block::magnitudes`]), with the round-off margin.
    fn bound(&self, magnitudes: &[f64]) -> f64 {
        magnitude_sum(&self.column_max, magnitudes) * BOUND_MARGIN
    }

    /// [`Self::bound`] straight from the state `q` and `loads` of its block `block`, without
    /// their magnitudes (an envelope's bound: most steps need no chunk's, nor the magnitudes).
    fn bound_at(&self, block: &Block, q: &[f64], loads: Option<&[f64; LOADS]>) -> f64 {
        let kept = &q[block.modes.start.min(q.len())..block.modes.end.min(q.len())];
        weighted_magnitude_sum(&self.column_max, block.modes.len(), kept, loads) * BOUND_MARGIN
    }

    /// The stress its bound must reach for any of its stations to raise its envelope's peak
    /// `peak` or worst utilisation `utilisation`. The bound's margin keeps a skipped station's
    /// utilisation below the worst by far more than a division's rounding.
    fn floor(&self, peak: f64, utilisation: f64) -> f64 {
        if self.smallest_allowable.is_finite() {
            peak.min(utilisation * self.smallest_allowable)
        } else {
            peak
        }
    }
}

/// One envelope's stations (one beam's bending or shear) and its chunks.
#[derive(Clone, Debug, Default)]
struct Envelope {
    span: Span,
    /// Its chunks (indices into [`StationRows::chunks`]).
    chunks: Range<usize>,
}

/// The stations' rows in modal coordinates, ready for the per-step products.
#[derive(Clone, Debug, Default)]
pub struct StationRows {
    /// One block per beam with stations (the arrestor's first).
    blocks: Vec<Block>,
    /// Each envelope's stations, in the station order.
    envelopes: Vec<Envelope>,
    /// Every envelope's stations in chunks of at most [`CHUNK`], in the station order.
    chunks: Vec<Span>,
    /// Each station's allowable stress, Pa (0: none given).
    allowables: Vec<f64>,
    /// Number of stations.
    count: usize,
    /// Evaluated every this many steps (1: every step; see [`ENVELOPE_BUDGET`]).
    pub stride: u64,
}

/// A run's own scratch for the envelope's work: the stations' values of the step, and for the
/// exact advance's contact steps their rates, kept as the next step's start; with
/// [`EnvelopeScope::Peaks`] each envelope's peak and worst utilisation and the bounds the
/// stations are skipped by.
#[derive(Clone, Debug, Default)]
pub struct EnvelopeWork {
    scope: EnvelopeScope,
    values: Vec<f64>,
    rates: Vec<f64>,
    start_values: Vec<f64>,
    start_rates: Vec<f64>,
    /// Per chunk: whether `start_values` and `start_rates` hold its stations.
    start_held: Vec<bool>,
    /// Per chunk, the bounds of its values and rates at the held start (NaN: its envelope's).
    start_bounds: Vec<(f64, f64)>,
    /// Per envelope, the same.
    envelope_start_bounds: Vec<(f64, f64)>,
    /// The correction's load coefficients and their rates at the held start.
    start_loads: Option<[f64; LOADS]>,
    start_load_rates: Option<[f64; LOADS]>,
    /// The step (number, end time in ns) whose end is held as the next step's start.
    end_of: Option<(u64, u64)>,
    /// Whether `peak` and `utilisation` describe the running values.
    summarised: bool,
    /// Per envelope ([`groups`]): its largest running value, Pa, and its worst utilisation.
    peak: [f64; 4],
    utilisation: [f64; 4],
    /// Scratch: each block's weights' magnitudes (values, rates; taken where a chunk's bound is
    /// needed), the step end's held chunks and bounds being built.
    magnitudes: [Vec<Vec<f64>>; 2],
    end_held: Vec<bool>,
    end_bounds: Vec<(f64, f64)>,
    envelope_end_bounds: Vec<(f64, f64)>,
    /// Chunk evaluations asked for (a chunk a step) and skipped by a bound, since the run began.
    pub asked: u64,
    /// See `asked`.
    pub skipped: u64,
}

impl EnvelopeWork {
    /// True when the stations' values and rates at the end of step `step`, at `time_ns`, are
    /// held (the next step's start).
    pub fn holds_end_of(&self, step: u64, time_ns: u64) -> bool {
        self.end_of == Some((step, time_ns))
    }

    /// Forgets the held step end (a step observed without rates).
    pub fn release_end(&mut self) {
        self.end_of = None;
    }

    /// Forgets the held end and the running values' summaries (a restored state).
    pub fn forget(&mut self) {
        self.end_of = None;
        self.summarised = false;
    }

    /// Sets which running values are kept exact (from the next step on).
    pub fn set_scope(&mut self, scope: EnvelopeScope) {
        self.scope = scope;
        self.forget();
    }

    /// Which running values are kept exact.
    pub fn scope(&self) -> EnvelopeScope {
        self.scope
    }

    /// Each envelope's peak, Pa ([`groups`]' order), where the peaks-only scope keeps it: the
    /// largest running value of its stations (a state restored forgets it, [`Self::forget`], or a
    /// step left untaken would leave its own peaks to skip stations by). None with every
    /// station's scope, or until a step takes it.
    pub fn peaks(&self) -> Option<&[f64; 4]> {
        (self.scope == EnvelopeScope::Peaks && self.summarised).then_some(&self.peak)
    }

    /// Every station's stress, Pa, at the end of the step [`StationRows::observe`] took last with
    /// [`EnvelopeScope::Stations`] (issue 44: the stations' histories for fatigue).
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Every station's stress and its rate (Pa, Pa/s) at the start and at the end of the step
    /// [`StationRows::observe_step`] took last with [`EnvelopeScope::Stations`]: ((start values,
    /// start rates), (end values, end rates)). The end is held as the next step's start.
    #[allow(clippy::type_complexity)]
    pub fn step_ends(&self) -> ((&[f64], &[f64]), (&[f64], &[f64])) {
        ((&self.values, &self.rates), (&self.start_values, &self.start_rates))
    }
}

/// One end of a step as the envelope's cubic takes it: the own coordinates and their rates, the
/// correction's load coefficients and their rates (None: a full basis).
#[derive(Clone, Copy, Debug)]
pub struct StationState<'a> {
    /// Own (modal) coordinates.
    pub q: &'a [f64],
    /// Their rates.
    pub v: &'a [f64],
    /// The static correction's load coefficients.
    pub loads: Option<&'a [f64; LOADS]>,
    /// Their rates.
    pub load_rates: Option<&'a [f64; LOADS]>,
}

/// A run's running largest |stress| at every station, Pa, and when, s.
pub struct Running<'a> {
    /// Largest |stress| so far.
    pub max: &'a mut [f64],
    /// When it was reached.
    pub times: &'a mut [f64],
}

impl StationRows {
    /// The rows of `system`'s stations with `divisors` (m^3 or m^2 per station, in order) and
    /// `allowables` (Pa, 0: none), each station's envelope in `groups` (0 lower bending, 1 lower
    /// shear, 2 upper bending, 3 upper shear: [`groups`]); a beam's stations are contiguous.
    pub fn new(system: &ModalSystem, divisors: &[f64], allowables: &[f64], groups: Vec<u8>) -> StationRows {
        let (count, modes) = (system.stations.nrows(), system.stations.ncols());
        debug_assert_eq!(count, divisors.len());
        debug_assert_eq!(count, allowables.len());
        debug_assert_eq!(count, groups.len());
        let lower_modes = system.lower_dofs.min(modes);
        let mut rows = StationRows { allowables: allowables.to_vec(), count, stride: 1, ..Default::default() };
        let mut start = 0;
        while start < count {
            let upper = groups[start] >= 2;
            let end = (start..count).find(|&k| (groups[k] >= 2) != upper).unwrap_or(count);
            let beam_modes = if upper { lower_modes..modes } else { 0..lower_modes };
            let m = end - start;
            let mut columns = Vec::with_capacity((beam_modes.len() + LOADS) * m);
            for i in beam_modes.clone() {
                columns.extend((start..end).map(|k| system.stations[(k, i)] / divisors[k]));
            }
            for a in 0..LOADS {
                columns.extend(
                    (start..end).map(|k| system.correction.stations.get(k).map_or(0.0, |c| c[a]) / divisors[k]),
                );
            }
            let block = Block { stations: start..end, modes: beam_modes, columns };
            let index = rows.blocks.len();
            // Its envelopes, each in chunks.
            let mut first = start;
            while first < end {
                let last = (first..end).find(|&k| groups[k] != groups[first]).unwrap_or(end);
                let chunks_start = rows.chunks.len();
                for from in (first..last).step_by(CHUNK) {
                    let local = from - start..(from + CHUNK).min(last) - start;
                    rows.chunks.push(Span::new(&block, index, local, &groups, allowables));
                }
                let span = Span::new(&block, index, first - start..last - start, &groups, allowables);
                rows.envelopes.push(Envelope { span, chunks: chunks_start..rows.chunks.len() });
                first = last;
            }
            rows.blocks.push(block);
            start = end;
        }
        rows.stride = rows.work().div_ceil(ENVELOPE_BUDGET.max(ENVELOPE_PER_MODE * modes)).max(1) as u64;
        rows
    }

    /// Number of stations.
    pub fn len(&self) -> usize {
        self.count
    }

    /// True without stations.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Raises each station's running largest |stress| by the state `q` at `time` s under the
    /// correction's load coefficients `loads` (None: a full basis). With
    /// [`EnvelopeScope::Peaks`], an envelope or chunk whose bound stays below its envelope's
    /// peak and worst utilisation is skipped: each envelope's peak is that of evaluating every
    /// station, to the bit.
    pub fn observe(
        &self,
        work: &mut EnvelopeWork,
        q: &[f64],
        loads: Option<&[f64; LOADS]>,
        time: f64,
        running: Running,
    ) {
        work.values.resize(self.count, 0.0);
        if work.scope == EnvelopeScope::Stations {
            self.stresses(q, loads, &mut work.values);
            for from in (0..self.count).step_by(CHUNK) {
                let to = (from + CHUNK).min(self.count);
                raise(&work.values[from..to], &mut running.max[from..to], &mut running.times[from..to], time);
            }
            return;
        }
        self.summarise(work, running.max);
        work.magnitudes[0].resize_with(self.blocks.len(), Vec::new);
        // The blocks whose magnitudes this step took (at most 64 blocks: one per beam).
        let mut taken = 0u64;
        for envelope in &self.envelopes {
            let (g, b) = (envelope.span.group as usize, envelope.span.block);
            let (peak, utilisation) = (work.peak[g], work.utilisation[g]);
            work.asked += envelope.chunks.len() as u64;
            if envelope.span.bound_at(&self.blocks[b], q, loads) < envelope.span.floor(peak, utilisation) {
                work.skipped += envelope.chunks.len() as u64;
                continue;
            }
            if taken & (1 << b) == 0 {
                self.blocks[b].magnitudes(q, loads, &mut work.magnitudes[0][b]);
                taken |= 1 << b;
            }
            for chunk in &self.chunks[envelope.chunks.clone()] {
                if chunk.bound(&work.magnitudes[0][chunk.block]) < chunk.floor(work.peak[g], work.utilisation[g]) {
                    work.skipped += 1;
                    continue;
                }
                let values = &mut work.values[chunk.stations.clone()];
                chunk_product(&self.blocks[chunk.block], chunk.local.clone(), q, loads, values);
                let stations = chunk.stations.clone();
                let raised = raise(values, &mut running.max[stations.clone()], &mut running.times[stations], time);
                self.summarise_raised(work, chunk, raised, running.max);
            }
        }
    }

    /// Sets the start of the next [`Self::observe_step`] (when the previous step's end is not
    /// held): the stations' values and rates at `start` (with [`EnvelopeScope::Peaks`], its load
    /// coefficients and the bounds, the stations' values when a step needs them).
    pub fn set_start(&self, work: &mut EnvelopeWork, start: StationState) {
        work.start_values.resize(self.count, 0.0);
        work.start_rates.resize(self.count, 0.0);
        work.start_loads = start.loads.copied();
        work.start_load_rates = start.load_rates.copied();
        let held = work.scope == EnvelopeScope::Stations;
        work.start_held.clear();
        work.start_held.resize(self.chunks.len(), held);
        if held {
            self.stresses(start.q, start.loads, &mut work.start_values);
            self.stresses(start.v, start.load_rates, &mut work.start_rates);
            return;
        }
        work.start_bounds.clear();
        work.start_bounds.resize(self.chunks.len(), (f64::NAN, f64::NAN));
        work.envelope_start_bounds.clear();
        for envelope in &self.envelopes {
            let (span, block) = (&envelope.span, &self.blocks[envelope.span.block]);
            let bounds = (span.bound_at(block, start.q, start.loads), span.bound_at(block, start.v, start.load_rates));
            work.envelope_start_bounds.push(bounds);
        }
    }

    /// Raises each station's running largest |stress| over one step from `start_time` to
    /// `end_time` s (`h` s long): its end `end` and the largest |value| of the cubic through each
    /// station's values and rates at the step's ends (the start's coordinates `start_q`,
    /// `start_v`, its loads from [`Self::set_start`] or the previous step's end), so that a crest
    /// between two long steps' ends is not missed (the exact advance's contact steps). With
    /// [`EnvelopeScope::Peaks`], an envelope or chunk whose bound over the step (its ends' values
    /// and the cubic's largest rise by their rates) stays below its envelope's peak and worst
    /// utilisation is skipped, as in [`Self::observe`]. Holds the end as the next step's start
    /// (`step`, `end_ns`).
    #[allow(clippy::too_many_arguments)]
    pub fn observe_step(
        &self,
        work: &mut EnvelopeWork,
        (start_q, start_v): (&[f64], &[f64]),
        end: StationState,
        (step, end_ns): (u64, u64),
        (start_time, end_time): (f64, f64),
        h: f64,
        running: Running,
    ) {
        work.values.resize(self.count, 0.0);
        work.rates.resize(self.count, 0.0);
        let mut end_held = std::mem::take(&mut work.end_held);
        end_held.clear();
        if work.scope == EnvelopeScope::Stations {
            self.stresses(end.q, end.loads, &mut work.values);
            self.stresses(end.v, end.load_rates, &mut work.rates);
            let (y0, r0, y1, r1) = (&work.start_values, &work.start_rates, &work.values, &work.rates);
            raise_over_step(y0, r0, y1, r1, running, (start_time, end_time), h, 0.0);
            end_held.resize(self.chunks.len(), true);
        } else {
            end_held.resize(self.chunks.len(), false);
            self.observe_step_peaks(work, (start_q, start_v), end, &mut end_held, (start_time, end_time), h, running);
        }
        std::mem::swap(&mut work.values, &mut work.start_values);
        std::mem::swap(&mut work.rates, &mut work.start_rates);
        work.end_held = std::mem::replace(&mut work.start_held, end_held);
        work.start_loads = end.loads.copied();
        work.start_load_rates = end.load_rates.copied();
        work.end_of = Some((step, end_ns));
    }

    /// [`Self::observe_step`] with [`EnvelopeScope::Peaks`]: marks in `end_held` the chunks whose
    /// end values it evaluated, and keeps every chunk's and envelope's bounds at the end as the
    /// next step's start.
    #[allow(clippy::too_many_arguments)]
    fn observe_step_peaks(
        &self,
        work: &mut EnvelopeWork,
        (start_q, start_v): (&[f64], &[f64]),
        end: StationState,
        end_held: &mut [bool],
        (start_time, end_time): (f64, f64),
        h: f64,
        running: Running,
    ) {
        self.summarise(work, running.max);
        for magnitudes in &mut work.magnitudes {
            magnitudes.resize_with(self.blocks.len(), Vec::new);
        }
        // The blocks whose magnitudes this step took (at most 64 blocks: one per beam).
        let mut taken = 0u64;
        let mut end_bounds = std::mem::take(&mut work.end_bounds);
        end_bounds.clear();
        end_bounds.resize(self.chunks.len(), (f64::NAN, f64::NAN));
        let mut envelope_end_bounds = std::mem::take(&mut work.envelope_end_bounds);
        envelope_end_bounds.clear();
        // |H00 y0 + H01 y1| <= max(|y0|, |y1|) and |H10|, |H11| <= 4/27 on [0, 1].
        let reach = |start: (f64, f64), end: (f64, f64)| {
            (start.0.max(end.0) + 4.0 / 27.0 * h * (start.1 + end.1)) * BOUND_MARGIN
        };
        for (e, envelope) in self.envelopes.iter().enumerate() {
            let (span, b) = (&envelope.span, envelope.span.block);
            let g = span.group as usize;
            let block = &self.blocks[b];
            let ends = (span.bound_at(block, end.q, end.loads), span.bound_at(block, end.v, end.load_rates));
            envelope_end_bounds.push(ends);
            let starts = work.envelope_start_bounds[e];
            work.asked += envelope.chunks.len() as u64;
            if reach(starts, ends) < span.floor(work.peak[g], work.utilisation[g]) {
                work.skipped += envelope.chunks.len() as u64;
                continue;
            }
            if taken & (1 << b) == 0 {
                block.magnitudes(end.q, end.loads, &mut work.magnitudes[0][b]);
                block.magnitudes(end.v, end.load_rates, &mut work.magnitudes[1][b]);
                taken |= 1 << b;
            }
            for c in envelope.chunks.clone() {
                let chunk = &self.chunks[c];
                let ends = (chunk.bound(&work.magnitudes[0][b]), chunk.bound(&work.magnitudes[1][b]));
                end_bounds[c] = ends;
                // A chunk's start bounds are its envelope's when its own were not taken.
                let own = work.start_bounds[c];
                let starts = if own.0.is_nan() { starts } else { own };
                if reach(starts, ends) < chunk.floor(work.peak[g], work.utilisation[g]) {
                    work.skipped += 1;
                    continue;
                }
                let (block, local, stations) = (&self.blocks[b], chunk.local.clone(), chunk.stations.clone());
                if !work.start_held[c] {
                    let (loads, rates) = (work.start_loads, work.start_load_rates);
                    let outs = (&mut work.start_values[stations.clone()], &mut work.start_rates[stations.clone()]);
                    chunk_product_pair(
                        block,
                        local.clone(),
                        (start_q, loads.as_ref()),
                        (start_v, rates.as_ref()),
                        outs,
                    );
                }
                let outs = (&mut work.values[stations.clone()], &mut work.rates[stations.clone()]);
                chunk_product_pair(block, local, (end.q, end.loads), (end.v, end.load_rates), outs);
                end_held[c] = true;
                let running_chunk =
                    Running { max: &mut running.max[stations.clone()], times: &mut running.times[stations.clone()] };
                let (y0, r0) = (&work.start_values[stations.clone()], &work.start_rates[stations.clone()]);
                let (y1, r1) = (&work.values[stations.clone()], &work.rates[stations]);
                let floor = chunk.floor(work.peak[g], work.utilisation[g]);
                let raised = raise_chunk_over_step(y0, r0, y1, r1, running_chunk, (start_time, end_time), h, floor);
                self.summarise_raised(work, chunk, raised, running.max);
            }
        }
        work.end_bounds = std::mem::replace(&mut work.start_bounds, end_bounds);
        work.envelope_end_bounds = std::mem::replace(&mut work.envelope_start_bounds, envelope_end_bounds);
    }

    /// Sets each envelope's peak and worst utilisation from the running values `max` unless
    /// they are current.
    fn summarise(&self, work: &mut EnvelopeWork, max: &[f64]) {
        if work.summarised {
            return;
        }
        (work.peak, work.utilisation) = ([0.0; 4], [0.0; 4]);
        for envelope in &self.envelopes {
            self.summarise_chunk(work, &envelope.span, max);
        }
        work.summarised = true;
    }

    /// [`Self::summarise_chunk`] after the chunk `span`'s running values were raised at the
    /// stations `raised` marks: by those only. The others' values and utilisations are within the
    /// summary already (it covers every station since [`Self::summarise`], and a division is
    /// monotone), so it is the same to the bit, without a division per station (a fifth of the
    /// envelope's own work a step).
    fn summarise_raised(&self, work: &mut EnvelopeWork, span: &Span, raised: [bool; CHUNK], max: &[f64]) {
        let g = span.group as usize;
        for i in marked(raised) {
            let k = span.stations.start + i;
            work.peak[g] = work.peak[g].max(max[k]);
            if self.allowables[k] > 0.0 {
                work.utilisation[g] = work.utilisation[g].max(max[k] / self.allowables[k]);
            }
        }
    }

    /// Raises its envelope's peak and worst utilisation by `span`'s running values.
    fn summarise_chunk(&self, work: &mut EnvelopeWork, span: &Span, max: &[f64]) {
        let g = span.group as usize;
        for k in span.stations.clone() {
            work.peak[g] = work.peak[g].max(max[k]);
            if self.allowables[k] > 0.0 {
                // As [`crate::results::StationEnvelope::peak`] divides.
                work.utilisation[g] = work.utilisation[g].max(max[k] / self.allowables[k]);
            }
        }
    }

    /// Every station's signed stress, Pa, at the state `q` under the correction's load
    /// coefficients `loads` (None: a full basis), into `out` (one value per station, in the order
    /// of [`crate::model::stations::Stations::all`]). Each station's sum runs over its beam's
    /// modes in order, then over the loads: the order of a plain loop, to the bit.
    pub fn stresses(&self, q: &[f64], loads: Option<&[f64; LOADS]>, out: &mut [f64]) {
        for block in &self.blocks {
            if let Some(out) = out.get_mut(block.stations.clone()) {
                product(block, 0..block.stations.len(), q, loads, out);
            }
        }
    }

    /// Multiply-adds of one [`Self::stresses`] call (stations x columns of their beams).
    pub fn work(&self) -> usize {
        self.blocks.iter().map(|b| b.columns.len()).sum()
    }
}

/// The stations (indices into a chunk) that `flags` marks, in order: one byte each of a word,
/// so that a chunk's sixteen flags are tested at once.
fn marked(flags: [bool; CHUNK]) -> impl Iterator<Item = usize> {
    const { assert!(CHUNK <= 16) };
    let mut bytes = [0u8; 16];
    for (byte, flag) in bytes.iter_mut().zip(flags) {
        *byte = flag.into();
    }
    let mut word = u128::from_le_bytes(bytes);
    std::iter::from_fn(move || {
        let i = (word != 0).then(|| word.trailing_zeros() as usize / 8)?;
        word &= !(0xff << (8 * i));
        Some(i)
    })
}

/// Raises each running value (`max`, with `times`) of at most [`CHUNK`] stations by its
/// station's `values` at `time` s, branch-free in the CPU's widest vectors: which it raised.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn raise(values: &[f64], max: &mut [f64], times: &mut [f64], time: f64) -> [bool; CHUNK] {
    let mut raised = [false; CHUNK];
    for (((value, max), at), raised) in values.iter().zip(max.iter_mut()).zip(times.iter_mut()).zip(&mut raised) {
        *raised = value.abs() > *max;
        *max = if *raised { value.abs() } else { *max };
        *at = if *raised { time } else { *at };
    }
    raised
}

/// Raises each running value over a step `h` s long by its station's end value `y1` and the
/// largest |value| of the cubic through its values `y0`, `y1` and rates `r0`, `r1` at the ends.
/// The cubic's largest value is sought only where its bound reaches the running value and
/// `floor` (0 for every station's envelope; with the peaks only, the stress below which no
/// station raises its envelope's peak or worst utilisation, [`Span::floor`]).
#[allow(clippy::too_many_arguments)]
fn raise_over_step(
    y0: &[f64],
    r0: &[f64],
    y1: &[f64],
    r1: &[f64],
    running: Running,
    (start_time, end_time): (f64, f64),
    h: f64,
    floor: f64,
) {
    let m =
        [y0.len(), r0.len(), y1.len(), r1.len(), running.max.len(), running.times.len()].into_iter().min().unwrap_or(0);
    for from in (0..m).step_by(CHUNK) {
        let to = (from + CHUNK).min(m);
        let chunk = Running { max: &mut running.max[from..to], times: &mut running.times[from..to] };
        let ends = (&y0[from..to], &r0[from..to], &y1[from..to], &r1[from..to]);
        raise_chunk_over_step(ends.0, ends.1, ends.2, ends.3, chunk, (start_time, end_time), h, floor);
    }
}

/// [`raise_over_step`] over at most [`CHUNK`] stations: which it raised.
#[allow(clippy::too_many_arguments)]
fn raise_chunk_over_step(
    y0: &[f64],
    r0: &[f64],
    y1: &[f64],
    r1: &[f64],
    running: Running,
    (start_time, end_time): (f64, f64),
    h: f64,
    floor: f64,
) -> [bool; CHUNK] {
    // The floor less the bounds' round-off margin: a cubic left unsought stays below it by more
    // than a division's rounding.
    let floor = floor / BOUND_MARGIN;
    let (mut raised, reaches) =
        raise_ends((y0, r0, y1, r1), (&mut *running.max, &mut *running.times), end_time, h, floor);
    for k in marked(reaches) {
        let (d0, d1) = (h * r0[k], h * r1[k]);
        let (value, s) = crate::solver::step_extrema::cubic_extremum(y0[k], y1[k], d0, d1, 1.0);
        if value > running.max[k] {
            running.max[k] = value;
            // Never past the step's end by round-off (a restored state's times are checked).
            running.times[k] = (start_time + s * h).min(end_time);
            raised[k] = true;
        }
    }
    raised
}

/// [`raise_chunk_over_step`]'s first pass over at most [`CHUNK`] stations, branch-free in the
/// CPU's widest vectors: raises each running value (`max`, with `times`) by its station's end
/// value `y1` at `end_time`, and says which it raised and whose cubic's bound reaches the raised
/// value and `floor` (the cubic then sought).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn raise_ends(
    (y0, r0, y1, r1): (&[f64], &[f64], &[f64], &[f64]),
    (max, times): (&mut [f64], &mut [f64]),
    end_time: f64,
    h: f64,
    floor: f64,
) -> ([bool; CHUNK], [bool; CHUNK]) {
    let (mut raised, mut reaches) = ([false; CHUNK], [false; CHUNK]);
    let ends = y1.iter().zip(r1).zip(y0.iter().zip(r0));
    let flags = raised.iter_mut().zip(reaches.iter_mut());
    for ((((&y1, &r1), (&y0, &r0)), (max, at)), (raised, reach)) in
        ends.zip(max.iter_mut().zip(times.iter_mut())).zip(flags)
    {
        *raised = y1.abs() > *max;
        *max = if *raised { y1.abs() } else { *max };
        *at = if *raised { end_time } else { *at };
        let (d0, d1) = (h * r0, h * r1);
        // |H00 y0 + H01 y1| <= max(|y0|, |y1|) and |H10|, |H11| <= 4/27 on [0, 1].
        *reach = y0.abs().max(y1.abs()) + 4.0 / 27.0 * (d0.abs() + d1.abs()) > max.max(floor);
    }
    (raised, reaches)
}

/// Each station's envelope index (see [`StationRows::new`]) in the order of
/// [`crate::model::stations::Stations::all`].
pub fn groups(model: &crate::model::Model) -> Vec<u8> {
    let st = &model.stations;
    let counts = [st.lower.bending.len(), st.lower.shear.len(), st.upper.bending.len(), st.upper.shear.len()];
    counts.iter().enumerate().flat_map(|(g, &n)| std::iter::repeat_n(g as u8, n)).collect()
}

/// sum_j a_j b_j of non-negative terms over the common length, in eight lanes in the CPU's widest
/// vectors: a bound's sum, whose order only moves it by round-off (~1e-15 relative; no terms
/// cancel), far inside [`BOUND_MARGIN`].
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn magnitude_sum(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut lanes = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca.remainder().iter().zip(cb.remainder()).map(|(x, y)| x * y).sum();
    for (x, y) in ca.zip(cb) {
        for l in 0..8 {
            lanes[l] += x[l] * y[l];
        }
    }
    lanes.iter().sum::<f64>() + tail
}

/// [`magnitude_sum`] of a block's column maxima `a` (`modes` modes' columns, then the loads')
/// and its weights' magnitudes, taken from the weights themselves: the modes' coordinates `q`
/// (its kept ones; a column past them weighs 0) and the load coefficients `loads` (none: 0). A
/// bound's sum in the same eight lanes, the loads added to the tail.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn weighted_magnitude_sum(a: &[f64], modes: usize, q: &[f64], loads: Option<&[f64; LOADS]>) -> f64 {
    let (a, load_columns) = a.split_at(modes.min(a.len()));
    let n = a.len().min(q.len());
    let (a, q) = (&a[..n], &q[..n]);
    let mut lanes = [0.0f64; 8];
    let (ca, cq) = (a.chunks_exact(8), q.chunks_exact(8));
    let mut tail: f64 = ca.remainder().iter().zip(cq.remainder()).map(|(x, y)| x * y.abs()).sum();
    if let Some(loads) = loads {
        let columns: &[f64; LOADS] = load_columns.try_into().expect("a column per load");
        tail += columns.iter().zip(loads).map(|(x, y)| x * y.abs()).sum::<f64>();
    }
    for (x, y) in ca.zip(cq) {
        for l in 0..8 {
            lanes[l] += x[l] * y[l].abs();
        }
    }
    lanes.iter().sum::<f64>() + tail
}

/// [`product`] over a chunk's stations (at most [`CHUNK`]) for `N` states at once (a step's
/// values and rates: `inputs`, each its own coordinates and load coefficients, of the same
/// length and the same basis), into `outs` (one value per station each): the same sums to the
/// bit (each station's terms added one after the other from 0, the modes' columns in order,
/// then the loads'), but each sixteen (then eight) stations' sums held in registers over all
/// the columns, and each column read once for the `N` states (the envelope's products were a
/// tenth of a campaign's time).
#[inline(always)]
fn chunk_products<const N: usize>(
    block: &Block,
    local: Range<usize>,
    inputs: [(&[f64], Option<&[f64; LOADS]>); N],
    mut outs: [&mut [f64]; N],
) {
    let length = inputs[0].0.len();
    let kept = block.modes.start.min(length)..block.modes.end.min(length);
    let loads = inputs[0].1.is_some();
    let m = local.len();
    let mut k = 0;
    while k + 16 <= m {
        let sums = station_sums::<N, 16>(block, local.start + k, kept.clone(), inputs, loads);
        for (out, sum) in outs.iter_mut().zip(&sums) {
            out[k..k + 16].copy_from_slice(sum);
        }
        k += 16;
    }
    while k + 8 <= m {
        let sums = station_sums::<N, 8>(block, local.start + k, kept.clone(), inputs, loads);
        for (out, sum) in outs.iter_mut().zip(&sums) {
            out[k..k + 8].copy_from_slice(sum);
        }
        k += 8;
    }
    while k < m {
        let sums = station_sums::<N, 1>(block, local.start + k, kept.clone(), inputs, loads);
        for (out, sum) in outs.iter_mut().zip(&sums) {
            out[k] = sum[0];
        }
        k += 1;
    }
}

/// The sums of [`chunk_products`] at `W` stations of `block` from its station `from` on, for
/// each of the `N` states: the modes `kept` (indices into the states' coordinates) column by
/// column, then the loads' (if `loads`), each column's `W` values read once.
#[inline(always)]
fn station_sums<const N: usize, const W: usize>(
    block: &Block,
    from: usize,
    kept: Range<usize>,
    inputs: [(&[f64], Option<&[f64; LOADS]>); N],
    loads: bool,
) -> [[f64; W]; N] {
    let rows = block.stations.len();
    let mut sums = [[0.0f64; W]; N];
    let weights = inputs.map(|(x, _)| &x[kept.clone()]);
    let column = |j: usize| -> &[f64; W] { block.columns[j * rows + from..][..W].try_into().expect("W stations") };
    // Column j weighs each state's coordinate j (of its kept ones).
    #[allow(clippy::needless_range_loop)]
    for j in 0..kept.len() {
        add_column(&mut sums, column(j), std::array::from_fn(|s| weights[s][j]));
    }
    if loads {
        for a in 0..LOADS {
            add_column(&mut sums, column(block.modes.len() + a), inputs.map(|(_, c)| c.map_or(0.0, |c| c[a])));
        }
    }
    sums
}

/// Adds a column's `W` values times each state's weight `w` to its `W` sums.
#[inline(always)]
fn add_column<const N: usize, const W: usize>(sums: &mut [[f64; W]; N], column: &[f64; W], w: [f64; N]) {
    for (sum, w) in sums.iter_mut().zip(w) {
        for i in 0..W {
            sum[i] += column[i] * w;
        }
    }
}

/// [`chunk_products`] of one state, compiled for the widest vectors the CPU has.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn chunk_product(block: &Block, local: Range<usize>, q: &[f64], loads: Option<&[f64; LOADS]>, out: &mut [f64]) {
    chunk_products(block, local, [(q, loads)], [out]);
}

/// [`chunk_products`] of a state's values and rates (`(q, loads)`, `(v, rates)`) into
/// `(values, rate_values)`; two [`chunk_product`]s where they do not share a basis.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn chunk_product_pair(
    block: &Block,
    local: Range<usize>,
    (q, loads): (&[f64], Option<&[f64; LOADS]>),
    (v, rates): (&[f64], Option<&[f64; LOADS]>),
    (values, rate_values): (&mut [f64], &mut [f64]),
) {
    if q.len() == v.len() && loads.is_some() == rates.is_some() {
        chunk_products(block, local, [(q, loads), (v, rates)], [values, rate_values]);
    } else {
        chunk_products(block, local.clone(), [(q, loads)], [values]);
        chunk_products(block, local, [(v, rates)], [rate_values]);
    }
}

/// The stresses of `block`'s stations `local` (`out`: one value each): compiled for the widest
/// vectors the CPU has (chosen once at run time; no fused multiply-add, so the same bits
/// whichever runs), each station's sum over the modes' columns in order, then the loads'.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn product(block: &Block, local: Range<usize>, q: &[f64], loads: Option<&[f64; LOADS]>, out: &mut [f64]) {
    out.fill(0.0);
    let m = out.len();
    let kept = block.modes.start.min(q.len())..block.modes.end.min(q.len());
    let weights = &q[kept.clone()];
    let mode_columns = kept.len();
    let load_count = if loads.is_some() { LOADS } else { 0 };
    // Column j's weight: the mode's coordinate, then the load's coefficient.
    let weight = |j: usize| if j < mode_columns { weights[j] } else { loads.map_or(0.0, |c| c[j - mode_columns]) };
    let column = |j: usize| {
        let c = if j < mode_columns { block.column(j) } else { block.column(block.modes.len() + j - mode_columns) };
        &c[local.clone()]
    };
    let total = mode_columns + load_count;
    let mut j = 0;
    // Four columns a pass: each station's sum still adds one term after the other.
    while j + 4 <= total {
        let (c0, c1, c2, c3) = (&column(j)[..m], &column(j + 1)[..m], &column(j + 2)[..m], &column(j + 3)[..m]);
        let (w0, w1, w2, w3) = (weight(j), weight(j + 1), weight(j + 2), weight(j + 3));
        if m >= 32 {
            // A long run of stations (a whole beam's): the compiler's vector loop.
            for (k, o) in out.iter_mut().enumerate() {
                let mut sum = *o;
                sum += c0[k] * w0;
                sum += c1[k] * w1;
                sum += c2[k] * w2;
                sum += c3[k] * w3;
                *o = sum;
            }
        } else {
            // A chunk's few: eight at a time as fixed arrays, or that loop would go scalar below
            // 32 of them.
            let lanes = m - m % 8;
            for k in (0..lanes).step_by(8) {
                let o: &mut [f64; 8] = (&mut out[k..k + 8]).try_into().expect("eight stations");
                let a: [&[f64; 8]; 4] =
                    [c0, c1, c2, c3].map(|c| <&[f64; 8]>::try_from(&c[k..k + 8]).expect("eight stations"));
                let mut sum = *o;
                for (column, w) in a.iter().zip([w0, w1, w2, w3]) {
                    for i in 0..8 {
                        sum[i] += column[i] * w;
                    }
                }
                *o = sum;
            }
            for k in lanes..m {
                let mut sum = out[k];
                sum += c0[k] * w0;
                sum += c1[k] * w1;
                sum += c2[k] * w2;
                sum += c3[k] * w3;
                out[k] = sum;
            }
        }
        j += 4;
    }
    while j < total {
        let (c, w) = (column(j), weight(j));
        for (o, v) in out.iter_mut().zip(c) {
            *o += v * w;
        }
        j += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Model, Scenario};

    /// A reproducible uniform source on [0, 1) (a 64-bit linear congruential generator's top 53
    /// bits) for the random states of the tests below.
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The dense product is the stations' functionals summed term by term: every station's value
    /// equals a plain loop over its beam's modes (s_ki / divisor q_i) and then the loads
    /// (C_ka / divisor c_a), to the bit, on the paper model (full basis: no loads) and on the
    /// converged printed rung's truncated basis (with loads), for random states.
    #[test]
    fn the_dense_product_is_each_stations_plain_sum() {
        let mut uniform = uniform(4242);
        let mut random = || uniform() - 0.5;
        let mut checked = 0;
        for scenario in [Scenario::paper(), Scenario::default()] {
            let resolved = crate::discretise::printed(&scenario).unwrap();
            let model = Model::new(&resolved).unwrap();
            let system = ModalSystem::new(&model).unwrap().for_run(&model).unwrap();
            assert_eq!(system.is_truncated(), scenario.method == crate::model::Method::Converged);
            let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
            let groups = groups(&model);
            let rows = StationRows::new(&system, &divisors, &vec![0.0; divisors.len()], groups.clone());
            let n = system.dofs();
            let mut out = vec![0.0; rows.len()];
            for _ in 0..20 {
                let q: Vec<f64> = (0..n).map(|_| random()).collect();
                let c: [f64; LOADS] = std::array::from_fn(|_| 1e4 * random());
                let loads = system.is_truncated().then_some(&c);
                rows.stresses(&q, loads, &mut out);
                for (k, value) in out.iter().enumerate() {
                    let beam = if groups[k] >= 2 { system.lower_dofs..n } else { 0..system.lower_dofs };
                    let mut sum = 0.0;
                    for i in beam {
                        sum += system.stations[(k, i)] / divisors[k] * q[i];
                    }
                    if let Some(c) = loads {
                        for (a, load) in c.iter().enumerate() {
                            sum += system.correction.stations[k][a] / divisors[k] * load;
                        }
                    }
                    assert_eq!(value.to_bits(), sum.to_bits(), "station {k}");
                    checked += 1;
                }
            }
        }
        // 20 states of both models: the paper mesh's stations and the printed rung's (258 in all).
        assert!(checked >= 5_000, "{checked}");
    }

    /// A chunk's products ([`chunk_product`], and [`chunk_product_pair`] of a state's values and
    /// rates) are [`product`]'s sums to the bit, on every chunk of the paper model (full basis:
    /// no loads) and of the converged printed rung (with loads, chunks of 16 stations and shorter
    /// tails), for random states; and a pair whose two states do not share a basis falls back to
    /// one product each.
    #[test]
    fn a_chunks_products_are_the_dense_products_to_the_bit() {
        let mut uniform = uniform(777);
        let mut random = || uniform() - 0.5;
        let mut checked = 0;
        for scenario in [Scenario::paper(), Scenario::default()] {
            let resolved = crate::discretise::printed(&scenario).unwrap();
            let model = Model::new(&resolved).unwrap();
            let system = ModalSystem::new(&model).unwrap().for_run(&model).unwrap();
            let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
            let rows = StationRows::new(&system, &divisors, &vec![0.0; divisors.len()], groups(&model));
            let n = system.dofs();
            for _ in 0..5 {
                let (q, v): (Vec<f64>, Vec<f64>) = (0..n).map(|_| (random(), 1e3 * random())).unzip();
                let (c, r): ([f64; LOADS], [f64; LOADS]) =
                    (std::array::from_fn(|_| 1e4 * random()), std::array::from_fn(|_| 1e7 * random()));
                let (loads, rates) = (system.is_truncated().then_some(&c), system.is_truncated().then_some(&r));
                for chunk in &rows.chunks {
                    let (block, local) = (&rows.blocks[chunk.block], chunk.local.clone());
                    let m = local.len();
                    let (mut expected, mut expected_rates) = (vec![0.0; m], vec![0.0; m]);
                    product(block, local.clone(), &q, loads, &mut expected);
                    product(block, local.clone(), &v, rates, &mut expected_rates);
                    let (mut one, mut values, mut value_rates) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
                    chunk_product(block, local.clone(), &q, loads, &mut one);
                    chunk_product_pair(block, local.clone(), (&q, loads), (&v, rates), (&mut values, &mut value_rates));
                    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&one), bits(&expected), "chunk {:?}", chunk.stations);
                    assert_eq!(bits(&values), bits(&expected), "chunk {:?}", chunk.stations);
                    assert_eq!(bits(&value_rates), bits(&expected_rates), "chunk {:?}", chunk.stations);
                    // The rates without their loads: two products, each its own.
                    let mut alone = vec![0.0; m];
                    product(block, local.clone(), &v, None, &mut alone);
                    chunk_product_pair(block, local, (&q, loads), (&v, None), (&mut values, &mut value_rates));
                    assert_eq!(bits(&values), bits(&expected), "chunk {:?}", chunk.stations);
                    assert_eq!(bits(&value_rates), bits(&alone), "chunk {:?}", chunk.stations);
                    checked += m;
                }
            }
        }
        assert!(checked >= 1_000, "{checked}");
    }

    /// An envelope's bound straight from the weights ([`Span::bound_at`]) is its bound from their
    /// magnitudes ([`Span::bound`]) but for the order of the sum (within 1e-14 relative, far
    /// inside the margin), on every envelope and chunk of the converged printed rung, for random
    /// states with and without loads and with fewer coordinates than the basis (columns that
    /// weigh 0).
    #[test]
    fn a_bound_from_the_weights_is_the_bound_from_their_magnitudes() {
        let mut uniform = uniform(31);
        let mut random = || uniform() - 0.5;
        let resolved = crate::discretise::printed(&Scenario::default()).unwrap();
        let model = Model::new(&resolved).unwrap();
        let system = ModalSystem::new(&model).unwrap().for_run(&model).unwrap();
        let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
        let rows = StationRows::new(&system, &divisors, &vec![0.0; divisors.len()], groups(&model));
        let n = system.dofs();
        let mut magnitudes = Vec::new();
        let mut checked = 0;
        for length in [n, n - 3, system.lower_dofs - 2] {
            for with_loads in [true, false] {
                let q: Vec<f64> = (0..length).map(|_| random()).collect();
                let c: [f64; LOADS] = std::array::from_fn(|_| 1e4 * random());
                let loads = with_loads.then_some(&c);
                let spans = rows.envelopes.iter().map(|e| &e.span).chain(&rows.chunks);
                for span in spans {
                    let block = &rows.blocks[span.block];
                    block.magnitudes(&q, loads, &mut magnitudes);
                    let (from_weights, from_magnitudes) = (span.bound_at(block, &q, loads), span.bound(&magnitudes));
                    let difference = (from_weights - from_magnitudes).abs();
                    assert!(
                        difference <= 1e-14 * from_magnitudes,
                        "{:?}: {from_weights} {from_magnitudes}",
                        span.stations
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked >= 100, "{checked}");
    }

    /// A chunk's branch-free raise over a step ([`raise_chunk_over_step`]) and at its end alone
    /// ([`raise`]) give the running values and times of the plain loops, to the bit, and mark
    /// exactly the stations whose values changed; for random values, rates and floors, chunks of
    /// every length up to [`CHUNK`], and running values both below and above the values.
    #[test]
    fn a_chunks_raise_is_the_plain_loops_and_marks_the_raised_stations() {
        let mut random = uniform(5);
        let (start_time, end_time, h) = (0.25, 0.25 + 1e-3, 1e-3);
        for length in 0..=CHUNK {
            for _ in 0..50 {
                let mut draw = |scale: f64| -> Vec<f64> { (0..length).map(|_| scale * (random() - 0.5)).collect() };
                let (y0, y1, r0, r1) = (draw(2.0), draw(2.0), draw(4e3), draw(4e3));
                let (max, times) = (draw(1.6).iter().map(|m| m.abs()).collect::<Vec<_>>(), draw(0.2));
                let floor = 0.5 * random();
                // The plain loops.
                let (mut plain_max, mut plain_times) = (max.clone(), times.clone());
                for k in 0..length {
                    if y1[k].abs() > plain_max[k] {
                        (plain_max[k], plain_times[k]) = (y1[k].abs(), end_time);
                    }
                    let (d0, d1) = (h * r0[k], h * r1[k]);
                    let bound = y0[k].abs().max(y1[k].abs()) + 4.0 / 27.0 * (d0.abs() + d1.abs());
                    if bound > plain_max[k].max(floor / BOUND_MARGIN) {
                        let (value, s) = crate::solver::step_extrema::cubic_extremum(y0[k], y1[k], d0, d1, 1.0);
                        if value > plain_max[k] {
                            (plain_max[k], plain_times[k]) = (value, (start_time + s * h).min(end_time));
                        }
                    }
                }
                let (mut new_max, mut new_times) = (max.clone(), times.clone());
                let running = Running { max: &mut new_max, times: &mut new_times };
                let raised = raise_chunk_over_step(&y0, &r0, &y1, &r1, running, (start_time, end_time), h, floor);
                let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!((bits(&new_max), bits(&new_times)), (bits(&plain_max), bits(&plain_times)), "{length}");
                let changed: Vec<usize> = (0..length).filter(|&k| plain_max[k] != max[k]).collect();
                assert_eq!(marked(raised).collect::<Vec<_>>(), changed, "{length}");
                // The end alone.
                let (mut end_max, mut end_times) = (max.clone(), times.clone());
                let raised = raise(&y1, &mut end_max, &mut end_times, end_time);
                let changed: Vec<usize> = (0..length).filter(|&k| y1[k].abs() > max[k]).collect();
                for k in 0..length {
                    let expected = if changed.contains(&k) { (y1[k].abs(), end_time) } else { (max[k], times[k]) };
                    assert_eq!(
                        (end_max[k].to_bits(), end_times[k].to_bits()),
                        (expected.0.to_bits(), expected.1.to_bits())
                    );
                }
                assert_eq!(marked(raised).collect::<Vec<_>>(), changed, "{length}");
            }
        }
    }

    /// Each envelope's (value, first station, time) and worst (utilisation, first station) from
    /// running values, as [`crate::results::StationEnvelope::peak`] takes them.
    fn envelope_peaks(
        groups: &[u8],
        allowables: &[f64],
        max: &[f64],
        times: &[f64],
    ) -> Vec<(f64, usize, f64, f64, usize)> {
        (0..4u8)
            .map(|g| {
                let mut p = (0.0, usize::MAX, 0.0, 0.0, usize::MAX);
                for k in (0..max.len()).filter(|&k| groups[k] == g) {
                    if p.1 == usize::MAX || max[k] > p.0 {
                        (p.0, p.1, p.2) = (max[k], k, times[k]);
                    }
                    if allowables[k] > 0.0 && (p.4 == usize::MAX || max[k] / allowables[k] > p.3) {
                        (p.3, p.4) = (max[k] / allowables[k], k);
                    }
                }
                p
            })
            .collect()
    }

    /// The peaks-only scope skips chunks of stations by a bound, over end-only and cubic steps
    /// alike, and keeps each envelope's peak and worst utilisation (value, station, time) to the
    /// bit of evaluating every station; a skipped station only keeps a smaller running value.
    /// Random states whose size swings by a factor of five step to step (so that bounds fall
    /// below and rise above the peaks), each mode's coordinate within 1/(1 + omega^2) (the low
    /// modes dominate, so that the stresses fade towards the free ends as a beam's do), and
    /// large rates (so that crests inside the steps matter), on the converged printed rung with
    /// allowables that change along each beam. Checked after every step; it fails when the
    /// bound of a step's crest leaves out the rates, or when the utilisation's floor is dropped.
    #[test]
    fn the_peaks_scope_skips_chunks_and_keeps_each_envelopes_peak_to_the_bit() {
        let mut random = uniform(99);
        let resolved = crate::discretise::printed(&Scenario::default()).unwrap();
        let model = Model::new(&resolved).unwrap();
        let system = ModalSystem::new(&model).unwrap().for_run(&model).unwrap();
        let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
        let groups = groups(&model);
        // Allowables that change along each beam: a fiftieth at some stations, so that the worst
        // utilisation is theirs and not the peak's, and none given at others; along the last 24
        // of the bridge's bending stations (towards its free end, where the moment fades) a
        // five-hundredth, so that only the utilisation's floor keeps their chunks evaluated.
        let last_bending = groups.iter().rposition(|g| *g == 2).unwrap();
        let allowables: Vec<f64> = (0..divisors.len())
            .map(|k| match (groups[k], k % 13) {
                (2, _) if k + 24 > last_bending => 1e6,
                (_, 0) => 0.0,
                (_, 5) => 1e7,
                _ => 5e8,
            })
            .collect();
        let rows = StationRows::new(&system, &divisors, &allowables, groups.clone());
        let n = system.dofs();
        let count = rows.len();
        let mut works = [EnvelopeWork::default(), EnvelopeWork::default()];
        works[1].set_scope(EnvelopeScope::Peaks);
        let mut running = [(vec![0.0; count], vec![0.0; count]), (vec![0.0; count], vec![0.0; count])];
        // The previous step's end: coordinates, rates, loads and their rates.
        type End = (Vec<f64>, Vec<f64>, [f64; LOADS], [f64; LOADS]);
        let mut previous: Option<End> = None;
        for step in 1..=600u64 {
            let size = 0.2 + 0.8 * random();
            let q: Vec<f64> = (0..n).map(|i| size * (random() - 0.5) / (1.0 + system.omega2[i])).collect();
            let v: Vec<f64> = (0..n).map(|_| size * 50.0 * (random() - 0.5)).collect();
            let loads: [f64; LOADS] = std::array::from_fn(|_| size * 1e-3 * (random() - 0.5));
            let load_rates: [f64; LOADS] = std::array::from_fn(|_| size * 1e5 * (random() - 0.5));
            let (time, h) = (step as f64 * 1e-3, 1e-3);
            let end = StationState { q: &q, v: &v, loads: Some(&loads), load_rates: Some(&load_rates) };
            for (work, (max, times)) in works.iter_mut().zip(running.iter_mut()) {
                let running = Running { max, times };
                match &previous {
                    // Every third step observes its end alone, as a free step does.
                    Some((q0, v0, l0, r0)) if step % 3 != 0 => {
                        if !work.holds_end_of(step - 1, step - 1) {
                            let start = StationState { q: q0, v: v0, loads: Some(l0), load_rates: Some(r0) };
                            rows.set_start(work, start);
                        }
                        rows.observe_step(work, (q0, v0), end, (step, step), (time - h, time), h, running);
                    }
                    _ => {
                        work.release_end();
                        rows.observe(work, &q, Some(&loads), time, running);
                    }
                }
            }
            previous = Some((q, v, loads, load_rates));
            // After every step, not only the last: a skip that misses a rise later overtaken
            // would not show at the end.
            let every = envelope_peaks(&groups, &allowables, &running[0].0, &running[0].1);
            let peaks = envelope_peaks(&groups, &allowables, &running[1].0, &running[1].1);
            for (g, (e, p)) in every.iter().zip(&peaks).enumerate() {
                assert_eq!((e.0.to_bits(), e.1, e.2.to_bits()), (p.0.to_bits(), p.1, p.2.to_bits()), "step {step} {g}");
                assert_eq!((e.3.to_bits(), e.4), (p.3.to_bits(), p.4), "step {step}, envelope {g}'s utilisation");
            }
            for k in 0..count {
                assert!(running[1].0[k] <= running[0].0[k], "step {step}, station {k}");
            }
            // The peaks-only scope's own peaks are the envelopes' (what the tangent reads).
            let own = works[1].peaks().expect("kept by the peaks-only scope");
            for (g, p) in peaks.iter().enumerate() {
                assert_eq!(own[g].to_bits(), p.0.to_bits(), "step {step}, envelope {g}'s peak");
            }
            assert_eq!(works[0].peaks(), None);
        }
        // Both ways taken: chunks skipped and chunks evaluated (every station's scope asks none).
        let work = &works[1];
        assert!(work.skipped > work.asked / 10 && work.skipped < work.asked, "{} of {}", work.skipped, work.asked);
        assert_eq!(works[0].asked, 0);
    }

    /// A restored state forgets the peaks-only scope's kept peaks ([`EnvelopeWork::forget`]): a
    /// step left untaken raised them ten thousand times above the restored running values, and a
    /// later step three times above them must still raise each envelope's peak to its largest
    /// station's value (that station examined again, not skipped against the untaken step's
    /// peaks), the kept peaks then those of the running values. Converged printed rung, a random
    /// state.
    #[test]
    fn a_forgotten_peak_leaves_no_station_skipped_by_an_untaken_step() {
        let mut uniform = uniform(4343);
        let resolved = crate::discretise::printed(&Scenario::default()).unwrap();
        let model = Model::new(&resolved).unwrap();
        let system = ModalSystem::new(&model).unwrap().for_run(&model).unwrap();
        let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
        let rows = StationRows::new(&system, &divisors, &vec![0.0; divisors.len()], groups(&model));
        let q: Vec<f64> = (0..system.dofs()).map(|i| (uniform() - 0.5) / (1.0 + system.omega2[i])).collect();
        let loads: [f64; LOADS] = std::array::from_fn(|_| 1e-3 * (uniform() - 0.5));
        let scaled = |s: f64| (q.iter().map(|x| s * x).collect::<Vec<f64>>(), loads.map(|c| s * c));
        let mut work = EnvelopeWork::default();
        work.set_scope(EnvelopeScope::Peaks);
        let (mut max, mut times) = (vec![0.0; rows.len()], vec![0.0; rows.len()]);
        rows.observe(&mut work, &q, Some(&loads), 1.0, Running { max: &mut max, times: &mut times });
        let saved = (max.clone(), times.clone());
        let (untaken, untaken_loads) = scaled(1e4);
        rows.observe(&mut work, &untaken, Some(&untaken_loads), 2.0, Running { max: &mut max, times: &mut times });
        (max, times) = saved;
        work.forget();
        assert_eq!(work.peaks(), None);
        let (later, later_loads) = scaled(3.0);
        rows.observe(&mut work, &later, Some(&later_loads), 2.0, Running { max: &mut max, times: &mut times });
        let mut values = vec![0.0; rows.len()];
        rows.stresses(&later, Some(&later_loads), &mut values);
        let groups = groups(&model);
        let largest = |g: usize, of: &[f64]| {
            (0..of.len()).filter(|&k| groups[k] as usize == g).map(|k| of[k].abs()).fold(0.0, f64::max)
        };
        let own = work.peaks().expect("taken again by the step");
        for (g, peak) in own.iter().enumerate() {
            assert_eq!(largest(g, &max).to_bits(), largest(g, &values).to_bits(), "envelope {g}'s stations");
            assert_eq!(peak.to_bits(), largest(g, &max).to_bits(), "envelope {g}'s kept peak");
        }
    }

    /// A log's per-step stresses are the envelope's values: their running largest |value| over
    /// random states of the paper model (with and without the static correction's loads) is the
    /// envelope's, to the bit (the same sums in the same order).
    #[test]
    fn per_step_stresses_raise_the_same_envelope() {
        let model = Model::new(&Scenario::paper()).unwrap();
        let system = ModalSystem::new(&model).unwrap();
        let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
        let allowables = vec![0.0; divisors.len()];
        let rows = StationRows::new(&system, &divisors, &allowables, groups(&model));
        let mut work = EnvelopeWork::default();
        let n = system.dofs();
        let (mut max, mut times) = (vec![0.0; rows.len()], vec![0.0; rows.len()]);
        let mut running = vec![0.0f64; rows.len()];
        let mut values = vec![0.0; rows.len()];
        let mut uniform = uniform(777);
        let mut random = || uniform() - 0.5;
        for step in 0..200 {
            let q: Vec<f64> = (0..n).map(|i| random() / (1.0 + system.omega2[i].sqrt())).collect();
            let loads: [f64; LOADS] = std::array::from_fn(|_| 1e3 * random());
            let loads = (step % 2 == 0).then_some(&loads);
            rows.observe(&mut work, &q, loads, step as f64, Running { max: &mut max, times: &mut times });
            rows.stresses(&q, loads, &mut values);
            for (r, v) in running.iter_mut().zip(&values) {
                *r = r.max(v.abs());
            }
        }
        assert_eq!(running, max);
        // Every station times its beam's modes and the loads.
        let lower = groups(&model).iter().filter(|g| **g < 2).count();
        let upper = rows.len() - lower;
        let lower_modes = system.lower_dofs;
        assert_eq!(rows.work(), lower * (lower_modes + LOADS) + upper * (n - lower_modes + LOADS));
    }
}

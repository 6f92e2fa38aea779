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
}

/// The stations' rows in modal coordinates, ready for the per-step products.
#[derive(Clone, Debug, Default)]
pub struct StationRows {
    /// One block per beam with stations (the arrestor's first).
    blocks: Vec<Block>,
    /// Number of stations.
    count: usize,
    /// Evaluated every this many steps (1: every step; see [`ENVELOPE_BUDGET`]).
    pub stride: u64,
}

/// A run's own scratch for the envelope's work: the stations' values of the step, and for the
/// exact advance's contact steps their rates, kept as the next step's start.
#[derive(Clone, Debug, Default)]
pub struct EnvelopeWork {
    values: Vec<f64>,
    rates: Vec<f64>,
    start_values: Vec<f64>,
    start_rates: Vec<f64>,
    /// The step (number, end time in ns) whose end `start_values` and `start_rates` hold.
    end_of: Option<(u64, u64)>,
}

impl EnvelopeWork {
    /// True when the stations' values and rates at the end of step `step`, at `time_ns`, are
    /// held (the next step's start).
    pub fn holds_end_of(&self, step: u64, time_ns: u64) -> bool {
        self.end_of == Some((step, time_ns))
    }

    /// Forgets the held values and rates (a restored state, a step observed without rates).
    pub fn forget(&mut self) {
        self.end_of = None;
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

impl StationRows {
    /// The rows of `system`'s stations with `divisors` (m^3 or m^2 per station, in order), each
    /// station's envelope in `groups` (0 lower bending, 1 lower shear, 2 upper bending, 3 upper
    /// shear: [`groups`]); a beam's stations are contiguous.
    pub fn new(system: &ModalSystem, divisors: &[f64], groups: Vec<u8>) -> StationRows {
        let (count, modes) = (system.stations.nrows(), system.stations.ncols());
        debug_assert_eq!(count, divisors.len());
        debug_assert_eq!(count, groups.len());
        let lower_modes = system.lower_dofs.min(modes);
        let mut blocks = Vec::new();
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
            blocks.push(Block { stations: start..end, modes: beam_modes, columns });
            start = end;
        }
        let mut rows = StationRows { blocks, count, stride: 1 };
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

    /// Raises each station's running largest |stress| (`max`, with `times`) by the state `q`
    /// at `time` s under the correction's load coefficients `loads` (None: a full basis).
    pub fn observe(
        &self,
        work: &mut EnvelopeWork,
        q: &[f64],
        loads: Option<&[f64; LOADS]>,
        time: f64,
        max: &mut [f64],
        times: &mut [f64],
    ) {
        work.values.resize(self.count, 0.0);
        self.stresses(q, loads, &mut work.values);
        for ((value, max), at) in work.values.iter().zip(max.iter_mut()).zip(times.iter_mut()) {
            if value.abs() > *max {
                *max = value.abs();
                *at = time;
            }
        }
    }

    /// Sets the start of the next [`Self::observe_step`]: the stations' values and rates at
    /// `start` (when the previous step's end is not held).
    pub fn set_start(&self, work: &mut EnvelopeWork, start: StationState) {
        work.start_values.resize(self.count, 0.0);
        work.start_rates.resize(self.count, 0.0);
        self.stresses(start.q, start.loads, &mut work.start_values);
        self.stresses(start.v, start.load_rates, &mut work.start_rates);
    }

    /// Raises each station's running largest |stress| over one step from `start_time` to
    /// `end_time` s (`h` s long): its end `end` and the largest |value| of the cubic through each station's values and
    /// rates at the step's ends (the start from [`Self::set_start`] or the previous step's end),
    /// so that a crest between two long steps' ends is not missed (the exact advance's contact
    /// steps). Holds the end as the next step's start (`step`, `end_ns`).
    #[allow(clippy::too_many_arguments)]
    pub fn observe_step(
        &self,
        work: &mut EnvelopeWork,
        end: StationState,
        (step, end_ns): (u64, u64),
        (start_time, end_time): (f64, f64),
        h: f64,
        max: &mut [f64],
        times: &mut [f64],
    ) {
        work.values.resize(self.count, 0.0);
        work.rates.resize(self.count, 0.0);
        self.stresses(end.q, end.loads, &mut work.values);
        self.stresses(end.v, end.load_rates, &mut work.rates);
        let ends = work.values.iter().zip(&work.rates).zip(work.start_values.iter().zip(&work.start_rates));
        for (((&y1, &r1), (&y0, &r0)), (max, at)) in ends.zip(max.iter_mut().zip(times.iter_mut())) {
            if y1.abs() > *max {
                *max = y1.abs();
                *at = end_time;
            }
            let (d0, d1) = (h * r0, h * r1);
            // |H00 y0 + H01 y1| <= max(|y0|, |y1|) and |H10|, |H11| <= 4/27 on [0, 1].
            if y0.abs().max(y1.abs()) + 4.0 / 27.0 * (d0.abs() + d1.abs()) > *max {
                let (value, s) = crate::solver::step_extrema::cubic_extremum(y0, y1, d0, d1, 1.0);
                if value > *max {
                    *max = value;
                    // Never past the step's end by round-off (a restored state's times are checked).
                    *at = (start_time + s * h).min(end_time);
                }
            }
        }
        std::mem::swap(&mut work.values, &mut work.start_values);
        std::mem::swap(&mut work.rates, &mut work.start_rates);
        work.end_of = Some((step, end_ns));
    }

    /// Every station's signed stress, Pa, at the state `q` under the correction's load
    /// coefficients `loads` (None: a full basis), into `out` (one value per station, in the order
    /// of [`crate::model::stations::Stations::all`]). Each station's sum runs over its beam's
    /// modes in order, then over the loads: the order of a plain loop, to the bit.
    pub fn stresses(&self, q: &[f64], loads: Option<&[f64; LOADS]>, out: &mut [f64]) {
        product(&self.blocks, q, loads, out);
    }

    /// Multiply-adds of one [`Self::stresses`] call (stations x columns of their beams).
    pub fn work(&self) -> usize {
        self.blocks.iter().map(|b| b.columns.len()).sum()
    }
}

/// Each station's envelope index (see [`StationRows::new`]) in the order of
/// [`crate::model::stations::Stations::all`].
pub fn groups(model: &crate::model::Model) -> Vec<u8> {
    let st = &model.stations;
    let counts = [st.lower.bending.len(), st.lower.shear.len(), st.upper.bending.len(), st.upper.shear.len()];
    counts.iter().enumerate().flat_map(|(g, &n)| std::iter::repeat_n(g as u8, n)).collect()
}

/// [`StationRows::stresses`]: each block's product, compiled for the widest vectors the CPU has
/// (chosen once at run time; no fused multiply-add, so the same bits whichever runs).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn product(blocks: &[Block], q: &[f64], loads: Option<&[f64; LOADS]>, out: &mut [f64]) {
    for block in blocks {
        let Some(out) = out.get_mut(block.stations.clone()) else { continue };
        out.fill(0.0);
        let kept = block.modes.start.min(q.len())..block.modes.end.min(q.len());
        let weights = &q[kept.clone()];
        let mode_columns = kept.len();
        let load_count = if loads.is_some() { LOADS } else { 0 };
        // Column j's weight: the mode's coordinate, then the load's coefficient.
        let weight = |j: usize| if j < mode_columns { weights[j] } else { loads.map_or(0.0, |c| c[j - mode_columns]) };
        let column = |j: usize| {
            if j < mode_columns {
                block.column(j)
            } else {
                block.column(block.modes.len() + j - mode_columns)
            }
        };
        let total = mode_columns + load_count;
        let mut j = 0;
        // Four columns a pass: each station's sum still adds one term after the other.
        while j + 4 <= total {
            let m = out.len();
            let (c0, c1, c2, c3) = (&column(j)[..m], &column(j + 1)[..m], &column(j + 2)[..m], &column(j + 3)[..m]);
            let (w0, w1, w2, w3) = (weight(j), weight(j + 1), weight(j + 2), weight(j + 3));
            for (k, o) in out.iter_mut().enumerate() {
                let mut sum = *o;
                sum += c0[k] * w0;
                sum += c1[k] * w1;
                sum += c2[k] * w2;
                sum += c3[k] * w3;
                *o = sum;
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Model, Scenario};

    /// The dense product is the stations' functionals summed term by term: every station's value
    /// equals a plain loop over its beam's modes (s_ki / divisor q_i) and then the loads
    /// (C_ka / divisor c_a), to the bit, on the paper model (full basis: no loads) and on the
    /// converged printed rung's truncated basis (with loads), for random states.
    #[test]
    fn the_dense_product_is_each_stations_plain_sum() {
        let mut seed = 4242u64;
        let mut random = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut checked = 0;
        for scenario in [Scenario::paper(), Scenario::default()] {
            let resolved = crate::discretise::printed(&scenario).unwrap();
            let model = Model::new(&resolved).unwrap();
            let system = ModalSystem::new(&model).unwrap().for_run(&model).unwrap();
            assert_eq!(system.is_truncated(), scenario.method == crate::model::Method::Converged);
            let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
            let groups = groups(&model);
            let rows = StationRows::new(&system, &divisors, groups.clone());
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

    /// A log's per-step stresses are the envelope's values: their running largest |value| over
    /// random states of the paper model (with and without the static correction's loads) is the
    /// envelope's, to the bit (the same sums in the same order).
    #[test]
    fn per_step_stresses_raise_the_same_envelope() {
        let model = Model::new(&Scenario::paper()).unwrap();
        let system = ModalSystem::new(&model).unwrap();
        let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
        let rows = StationRows::new(&system, &divisors, groups(&model));
        let mut work = EnvelopeWork::default();
        let n = system.dofs();
        let (mut max, mut times) = (vec![0.0; rows.len()], vec![0.0; rows.len()]);
        let mut running = vec![0.0f64; rows.len()];
        let mut values = vec![0.0; rows.len()];
        let mut seed = 777u64;
        let mut random = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for step in 0..200 {
            let q: Vec<f64> = (0..n).map(|i| random() / (1.0 + system.omega2[i].sqrt())).collect();
            let loads: [f64; LOADS] = std::array::from_fn(|_| 1e3 * random());
            let loads = (step % 2 == 0).then_some(&loads);
            rows.observe(&mut work, &q, loads, step as f64, &mut max, &mut times);
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

//! The twin's sensitivity from the printed run's tangent (issue 43).
//!
//! The reproducibility twin (drop height x (1 + 1e-9): [`crate::answer::twin_scenario`]) is a
//! finite-difference derivative of the peaks. With the linear bar the converged method's exact
//! step is affine in the state for a given stage and step size, and the model's vector field is
//! continuous across a contact change (the bar's force is 0 at the touch): so between contact
//! changes the twin's difference from the printed run evolves by the same step as the state
//! itself under no load (gravity, the tip forces, the supports' motion and the static gap shift
//! cancel in a difference), and across a change the difference needs no jump to first order
//! (the twin touches a little earlier or later; the force it carries meanwhile is of the second
//! order). The printed run carries that difference, `delta`, alongside its own state
//! ([`crate::solver::stepper::ModalStepper::exact_tangent_step`]: the very coefficients of each
//! accepted step); `delta` at t = 0 is the difference of the twin's and the printed run's
//! initial states (a finite difference at t = 0 only).
//!
//! What it gives, for each of the five peaks, the first contact's and the four envelopes':
//! - the **linearised spread** |dv(t*)| / |v(t*)|, dv the output's difference at the instant t*
//!   the peak was raised (inside a step: the Hermite cubic of the difference's values and rates
//!   at the step's ends, as the peak's own instant is found): the twin's peak |v + dv| there, to
//!   first order; the envelopes' from their bound below;
//! - a **bound** on the twin's spread whichever instant or station carries its peak:
//!   sup_t |dv(t)| / peak (|max |v + dv| - max |v|| <= sup |dv|), each step's sup bounded by the
//!   Hermite cubic's (|H00 y0 + H01 y1| <= max(|y0|, |y1|), |H10|, |H11| <= 4/27), an envelope's
//!   by sum_i max_station |row_i| |dq_i| over its stations.
//!
//! The answer skips the real twin where every bound is below a tenth of the sensitivity
//! tolerance ([`SCREEN_FRACTION`]) and no gap came near the contact's threshold within a tenth
//! of its own difference (a graze the twin could take otherwise: [`GRAZE_FRACTION`]); else the
//! twin runs as before, so every flagged figure is the real twin's.

use super::{initial_physical_state_with, Simulation, StepResult};
use crate::error::Result;
use crate::model::system::PROBES;
use crate::model::{Probe, Scenario};
use crate::results::{Peaks, Summary};
use crate::solver::contact::{self, Stage};
use crate::solver::static_correction::CONTACT;
use crate::solver::step_extrema::cubic_coefficients;
use crate::solver::{Kinematics, ModalCache, Stepper};

/// The screen: the real twin is skipped where every bound on a spread is below this fraction of
/// the sensitivity tolerance (0.1 % of the default 1 %): the linearisation's own error is of
/// the order of the nudge (1e-9) times the spread's growth, far inside this margin wherever the
/// bound is; a chaotic run's bound grows past it and the twin runs.
pub const SCREEN_FRACTION: f64 = 0.1;

/// A step end whose gap is within this fraction of the difference's gap from the contact's
/// threshold, in the stage it goes on in, is a graze the twin might take the other way: the
/// twin runs.
pub const GRAZE_FRACTION: f64 = 0.1;

/// The first-order spreads of an answer's peaks against its twin, from the printed run's tangent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Linearised {
    /// Each whole-run peak's linearised spread (a fraction).
    pub whole: Peaks,
    /// Each first-contact peak's.
    pub first_contact: Peaks,
    /// Each envelope peak's (its bound), in the order of [`crate::results::ENVELOPE_PEAK_NAMES`].
    pub envelope: [Option<f64>; 4],
    /// The largest bound on any spread (whole run, first contact, envelopes), a fraction.
    pub bound: f64,
    /// The largest gap difference against a step end's distance from the contact threshold.
    pub graze: f64,
}

impl Linearised {
    /// True when the real twin need not run: every bound below [`SCREEN_FRACTION`] of
    /// `tolerance` and no graze.
    pub fn screens(&self, tolerance: f64) -> bool {
        self.bound <= SCREEN_FRACTION * tolerance && self.graze <= GRAZE_FRACTION
    }
}

/// What the tangent keeps of the run: restored with it where a step is left untaken.
#[derive(Clone, Copy, Debug, Default)]
struct Record {
    /// The time of `delta`, ns.
    time_ns: u64,
    /// Each whole-run peak as raised and the output's difference at its instant.
    whole: [(f64, f64); 5],
    /// Each first-contact peak the same.
    first: [(f64, f64); 5],
    /// The first contact's pending values (free steps after a contact, raised if another contact
    /// follows) and their differences.
    pending: [(f64, f64); 5],
    /// A step in contact was seen.
    seen_contact: bool,
    /// sup |dv| over the run, per output.
    whole_bound: [f64; 5],
    /// sup |dv| up to the first contact's end, per output.
    first_bound: [f64; 5],
    /// Each envelope's bound of sup |d sigma| over its stations, in the stations' group order
    /// (lower bending, lower shear, upper bending, upper shear).
    envelope_bound: [f64; 4],
    /// The largest |d gap| / (distance of a step end's gap from the threshold).
    graze: f64,
    /// A raised first-contact peak whose instant was not found (its bound stands in).
    lost_first: [bool; 5],
    /// `delta`'s measure at `time_ns` (the next step's start).
    measure: Measure,
    /// Each envelope's peak as raised (the stations' group order) and its station's difference
    /// at its instant.
    envelope: [(f64, f64); 4],
}

/// What the outputs and the envelopes' bounds read of a difference `delta`, whatever the stage:
/// the probes of its displacement and velocity (the kept modes' alone), and each envelope
/// group's sum_i max |row_i| |x_i| of both.
#[derive(Clone, Copy, Debug, Default)]
struct Measure {
    q: [f64; PROBES],
    v: [f64; PROBES],
    envelope_q: [f64; 4],
    envelope_v: [f64; 4],
}

/// The tangent a printed run carries.
#[derive(Clone, Debug)]
pub(super) struct Tangent<W> {
    delta: Kinematics,
    work: W,
    record: Record,
    /// The state and record before the latest step (a step left untaken is undone; the step's
    /// start, from which [`Simulation::tangent_advance`] steps `delta`).
    before: Option<(Kinematics, Record)>,
    /// Per envelope group (stations' order), per kept mode: the largest |row| / divisor over its
    /// stations; then the largest |correction row of the contact load| / divisor.
    envelope_rows: Vec<[f64; 4]>,
    envelope_loads: [f64; 4],
    /// Each group's stations (the stations' order: lower bending, lower shear, upper bending,
    /// upper shear).
    groups: [std::ops::Range<usize>; 4],
    /// Why the tangent cannot stand for the twin (a step it could not follow).
    broken: bool,
    /// The latest step was advanced and not yet followed: between [`Simulation::tangent_advance`]
    /// and [`Simulation::tangent_after_step`] (its start's measure is `before`'s, its end's
    /// `record`'s).
    advanced: bool,
}

impl<S: Stepper> Simulation<S> {
    /// Carries the tangent towards `twin` (the answer's twin scenario: [`crate::answer::twin_scenario`])
    /// from here (t = 0, before any step) on. False, and nothing carried, where the tangent is
    /// not the twin's derivative: not the exact advance, a nonlinear contact law, a rigid
    /// impactor or support, a far support, a twin of another discretisation, a run already
    /// stepped.
    pub fn follow_tangent(&mut self, twin: &Scenario, cache: &ModalCache) -> Result<bool> {
        let s = &self.model.scenario;
        let covered = self.stepper.adapts_steps()
            && self.stepper.modal_coordinates()
            && self.modal.law.is_none()
            && self.far_support.is_none()
            && s.upper.kind == crate::model::scenario::ImpactorKind::Beam
            && s.lower.kind == crate::model::scenario::SupportKind::Beam
            && self.state.result.step == 0
            && self.state.result.time_ns == 0;
        if !covered {
            return Ok(false);
        }
        // The reference mesh's modes from the cache: the same scenario to the bit.
        let resolved = crate::discretise::printed_with(twin, Some(cache))?;
        let same_mesh =
            [resolved.lower.elements, resolved.upper.elements_to_contact, resolved.upper.elements_beyond_contact]
                == [s.lower.elements, s.upper.elements_to_contact, s.upper.elements_beyond_contact]
                && resolved.modal_cutoff == s.modal_cutoff;
        if !same_mesh {
            return Ok(false);
        }
        // The twin's model, modes and initial factors from the cache (the printed run put them
        // there; the same bits).
        let model = cache.model(&resolved)?;
        let (full, factors) = if cache.is_enabled() {
            let (full, factors) = cache.initial_modes(&model)?;
            (full, Some(factors))
        } else {
            (std::sync::Arc::new(crate::solver::ModalSystem::new(&model)?), None)
        };
        let physical = initial_physical_state_with(&model, &full, &self.state.motion, factors.as_deref())?;
        let start = self.stepper.own_coordinates(&physical);
        let own = &self.state.kinematics;
        let delta = Kinematics {
            displacement: &start.displacement - &own.displacement,
            velocity: &start.velocity - &own.velocity,
            acceleration: &start.acceleration - &own.acceleration,
        };
        let (envelope_rows, envelope_loads) = self.envelope_rows();
        let st = &self.model.stations;
        let counts = [st.lower.bending.len(), st.lower.shear.len(), st.upper.bending.len(), st.upper.shear.len()];
        let mut from = 0;
        let groups = counts.map(|c| {
            from += c;
            from - c..from
        });
        let mut tangent = Tangent {
            delta,
            work: S::TangentWork::default(),
            record: Record::default(),
            before: None,
            envelope_rows,
            envelope_loads,
            groups,
            broken: false,
            advanced: false,
        };
        tangent.record.measure = self.tangent_measure(&tangent, &tangent.delta);
        let (values, _) = self.tangent_outputs(&tangent.record.measure, Stage::Free);
        let peaks = self.state.result.peaks.as_array();
        let first = self.state.first_contact.peaks.as_array();
        let r = &mut tangent.record;
        for k in 0..5 {
            r.whole[k] = (peaks[k], values[k]);
            r.first[k] = (first[k], values[k]);
            r.whole_bound[k] = values[k].abs();
            r.first_bound[k] = values[k].abs();
        }
        let bounds = self.envelope_bounds(&tangent, &tangent.record.measure, Stage::Free);
        tangent.record.envelope_bound = bounds.map(|(q, _)| q);
        for g in 0..4 {
            if let Some((station, value)) = self.group_peak(tangent.groups[g].clone()) {
                let d = self.station_difference(station, &tangent.delta, Stage::Free).0;
                tangent.record.envelope[g] = (value, d);
            }
        }
        self.tangent = Some(Box::new(tangent));
        Ok(true)
    }

    /// The linearised spreads against the twin, once the run is over; `None` without a tangent
    /// or where a step could not be followed.
    pub fn linearised(&self, summary: &Summary) -> Option<Linearised> {
        let t = self.tangent.as_ref()?;
        if t.broken {
            return None;
        }
        let record = if t.record.time_ns == self.state.result.time_ns {
            &t.record
        } else {
            match &t.before {
                Some((_, r)) if r.time_ns == self.state.result.time_ns => r,
                _ => return None,
            }
        };
        let ratio = |d: f64, peak: f64| if d == 0.0 { 0.0 } else { d.abs() / peak.abs() };
        let mut bound: f64 = 0.0;
        let (whole, first) = (summary.peaks.as_array(), summary.first_contact_peaks.as_array());
        let spreads =
            |peaks: [f64; 5], raised: &[(f64, f64); 5], bounds: &[f64; 5], lost: [bool; 5], bound: &mut f64| {
                let v: [f64; 5] = std::array::from_fn(|k| {
                    let b = ratio(bounds[k], peaks[k]);
                    *bound = bound.max(b);
                    // A peak raised at an instant the tangent saw: its difference there; else (a
                    // stop point inside a step, an instant not found) its bound.
                    if raised[k].0 == peaks[k] && !lost[k] {
                        ratio(raised[k].1, peaks[k])
                    } else {
                        b
                    }
                });
                Peaks::from_array(v)
            };
        let whole = spreads(whole, &record.whole, &record.whole_bound, [false; 5], &mut bound);
        let first = spreads(first, &record.first, &record.first_bound, record.lost_first, &mut bound);
        // The envelopes in the order of ENVELOPE_PEAK_NAMES (upper bending, upper shear, lower
        // bending, lower shear); the bounds in the stations' (lower first).
        let values = summary.envelope.peak_values();
        let group = [2, 3, 0, 1];
        let envelope: [Option<f64>; 4] = std::array::from_fn(|k| {
            values[k].map(|v| {
                let g = group[k];
                let b = ratio(record.envelope_bound[g], v);
                bound = bound.max(b);
                // The peak raised at an instant the tangent saw; else (a paper point standing for
                // its station, a stop point) its bound.
                // A paper point (the clamp's bending and shear, the bridge's contact node) stands
                // with its probe's peak: that peak's spread.
                let paper = [Some(3), None, Some(1), Some(2)][k];
                if record.envelope[g].0 == v {
                    ratio(record.envelope[g].1, v)
                } else if let Some(p) = paper.filter(|&p| summary.peaks.as_array()[p] == v) {
                    whole.as_array()[p]
                } else {
                    b
                }
            })
        });
        Some(Linearised { whole, first_contact: first, envelope, bound, graze: record.graze })
    }

    /// Advances the difference over the step just taken (from `start_ns`, `step_ns` long, in
    /// `stage`), right after it (the stepper's coefficients of its size are at hand).
    pub(super) fn tangent_advance(&mut self, stage: Stage, start_ns: u64, step_ns: u64) {
        let Some(mut t) = self.tangent.take() else { return };
        if t.broken {
            self.tangent = Some(t);
            return;
        }
        // A step left untaken (an output point inside it) was undone with the state: so is the
        // tangent's.
        if t.record.time_ns != start_ns {
            match t.before.take() {
                Some((delta, record)) if record.time_ns == start_ns => {
                    t.delta = delta;
                    t.record = record;
                }
                _ => {
                    t.broken = true;
                    self.tangent = Some(t);
                    return;
                }
            }
        }
        // The start kept as `before`: its difference by a swap (the step writes the end into the
        // other state, all of it), its record by a copy.
        match &mut t.before {
            Some((delta, record)) => {
                std::mem::swap(delta, &mut t.delta);
                *record = t.record;
            }
            None => t.before = Some((t.delta.clone(), t.record)),
        }
        let h = seconds_of(step_ns);
        let start = &t.before.as_ref().expect("just kept").0;
        if !self.stepper.tangent_step(start, &mut t.delta, stage, h, &mut t.work) {
            t.broken = true;
            self.tangent = Some(t);
            return;
        }
        t.record.measure = self.tangent_measure(&t, &t.delta);
        t.record.time_ns = start_ns + step_ns;
        t.advanced = true;
        self.tangent = Some(t);
    }

    /// Follows the step just taken (from `previous`, `step_ns` long, in `stage`; the peaks'
    /// in-step extremes `extremes` and the first contact's peaks and end before it,
    /// `first_before`), which [`Self::tangent_advance`] advanced the difference over: raises the
    /// bounds, and takes the difference at every raised peak's instant.
    #[inline(never)]
    pub(super) fn tangent_after_step(
        &mut self,
        stage: Stage,
        previous: &StepResult,
        step_ns: u64,
        extremes: Option<&[(f64, f64); 5]>,
        first_before: (Peaks, bool),
    ) {
        let Some(mut t) = self.tangent.take() else { return };
        let advanced = std::mem::take(&mut t.advanced);
        let start = t.before.as_ref().map(|(_, record)| &record.measure);
        let Some(start) = start.filter(|_| advanced && !t.broken && t.record.time_ns == previous.time_ns + step_ns)
        else {
            t.broken = true;
            self.tangent = Some(t);
            return;
        };
        let end = &t.record.measure;
        let h = seconds_of(step_ns);
        // The start's outputs in this step's stage (its q and v are the measure's).
        let (d0, r0) = self.tangent_outputs(start, stage);
        let (d1, r1) = self.tangent_outputs(end, stage);
        let start_bounds = self.envelope_bounds(&t, start, stage);
        let end_bounds = self.envelope_bounds(&t, end, stage);
        let dgap = end.q[Probe::Gap as usize];
        let t0 = seconds_of(previous.time_ns);
        let at = |k: usize, time: f64| {
            let s = ((time - t0) / h).clamp(0.0, 1.0);
            let (c2, c3) = cubic_coefficients(d0[k], d1[k], r0[k] * h, r1[k] * h);
            d0[k] + s * (r0[k] * h + s * (c2 + s * c3))
        };
        let r = &mut t.record;
        let first_open = !first_before.1;
        for k in 0..5 {
            let reach = d0[k].abs().max(d1[k].abs()) + 4.0 / 27.0 * h * (r0[k].abs() + r1[k].abs());
            r.whole_bound[k] = r.whole_bound[k].max(reach);
            if first_open {
                r.first_bound[k] = r.first_bound[k].max(reach);
            }
        }
        for g in 0..4 {
            let (y0, v0) = start_bounds[g];
            let (y1, v1) = end_bounds[g];
            r.envelope_bound[g] = r.envelope_bound[g].max(y0.max(y1) + 4.0 / 27.0 * h * (v0 + v1));
        }
        for g in 0..4 {
            // The envelope only rises: its group's peak is the one taken unless a station of
            // the group now exceeds it. The peaks-only envelope's own peak first (never below its
            // stations' largest value, which is never below the one taken: where they are equal,
            // so is that largest value), else a vectorised maximum; the station only then.
            let range = t.groups[g].clone();
            let largest = match self.envelope_work.peaks() {
                Some(peaks) => Some(peaks[g]),
                None => self.state.envelope.get(range.clone()).map(largest),
            };
            if largest == Some(r.envelope[g].0) {
                continue;
            }
            match self.group_peak(range) {
                Some((station, value)) if value != r.envelope[g].0 => {
                    let time = self.state.envelope_times[station];
                    let start_delta = &t.before.as_ref().expect("kept by the advance").0;
                    let (y0, v0) = self.station_difference(station, start_delta, stage);
                    let (y1, v1) = self.station_difference(station, &t.delta, stage);
                    let x = ((time - t0) / h).clamp(0.0, 1.0);
                    let (c2, c3) = cubic_coefficients(y0, y1, v0 * h, v1 * h);
                    r.envelope[g] = (value, y0 + x * (v0 * h + x * (c2 + x * c3)));
                }
                _ => {}
            }
        }
        let result = &self.state.result;
        let (peaks, times) = (result.peaks.as_array(), self.state.peak_times.as_array());
        let previous_peaks = previous.peaks.as_array();
        for k in 0..5 {
            if peaks[k] != previous_peaks[k] {
                r.whole[k] = (peaks[k], at(k, times[k]));
            }
        }
        if first_open {
            // The step's largest values and their differences (the first contact's alone reads them).
            let step_values: [(f64, f64); 5] = std::array::from_fn(|k| match extremes {
                Some(e) => (e[k].0, at(k, e[k].1)),
                None => (peaks[k], d1[k]),
            });
            let now = self.state.first_contact.peaks.as_array();
            let before = first_before.0.as_array();
            let raising = result.contact || !r.seen_contact;
            for k in 0..5 {
                if now[k] != before[k] {
                    r.first[k] = if now[k] == step_values[k].0 {
                        (now[k], step_values[k].1)
                    } else if raising && now[k] == r.pending[k].0 {
                        (now[k], r.pending[k].1)
                    } else {
                        r.lost_first[k] = true;
                        (now[k], f64::NAN)
                    };
                }
            }
            if raising {
                r.pending = Default::default();
                r.seen_contact |= result.contact;
            } else {
                for (pending, value) in r.pending.iter_mut().zip(step_values) {
                    if value.0 > pending.0 {
                        *pending = value;
                    }
                }
            }
        }
        // A step end close to the threshold in the stage it goes on in: a graze.
        let gap = self.state.gap;
        if contact::stage(gap) == stage {
            let margin = (gap + contact::GAP_TOLERANCE).abs();
            let graze = if dgap == 0.0 { 0.0 } else { dgap.abs() / margin };
            r.graze = r.graze.max(graze);
        }
        self.tangent = Some(t);
    }

    /// The probes and the envelopes' mode sums of a difference `delta`.
    fn tangent_measure(&self, t: &Tangent<S::TangentWork>, delta: &Kinematics) -> Measure {
        let (envelope_q, envelope_v) =
            envelope_sums(&t.envelope_rows, delta.displacement.as_slice(), delta.velocity.as_slice());
        Measure {
            q: self.stepper.probes(&delta.displacement),
            v: self.stepper.probes(&delta.velocity),
            envelope_q,
            envelope_v,
        }
    }

    /// The five peak outputs' differences and their rates from `m` in `stage` (the truncated
    /// basis's static correction moving with the contact load's difference, -k_eff b^T delta q).
    fn tangent_outputs(&self, m: &Measure, stage: Stage) -> ([f64; 5], [f64; 5]) {
        let (mut p, mut r) = (m.q, m.v);
        let contact = stage.is_contact();
        if self.modal.is_truncated() && contact {
            let k = self.modal.bar_stiffness;
            let gap = Probe::Gap as usize;
            let (load, load_rate) = (-k * m.q[gap], -k * m.v[gap]);
            for (j, row) in self.modal.correction.probes.iter().enumerate() {
                p[j] += row[CONTACT] * load;
                r[j] += row[CONTACT] * load_rate;
            }
        }
        let s = &self.model.scenario;
        let scales = [
            1.0,
            1.0 / s.lower.section_modulus,
            1.0 / s.lower.shear_area,
            1.0 / self.model.contact_section_modulus,
            if contact { self.model.bar_stiffness } else { 0.0 },
        ];
        let probes =
            [Probe::LowerTipDeflection, Probe::ClampMoment, Probe::ClampShear, Probe::UpperContactMoment, Probe::Gap];
        (
            std::array::from_fn(|k| p[probes[k] as usize] * scales[k].abs()),
            std::array::from_fn(|k| r[probes[k] as usize] * scales[k].abs()),
        )
    }

    /// The running peak of the envelope group of stations `range`: its station and value (None without stations).
    fn group_peak(&self, range: std::ops::Range<usize>) -> Option<(usize, f64)> {
        let values = self.state.envelope.get(range.clone())?;
        let mut best: Option<(usize, f64)> = None;
        for (i, &v) in values.iter().enumerate() {
            if best.is_none_or(|(_, b)| v > b) {
                best = Some((range.start + i, v));
            }
        }
        best
    }

    /// Station `station`'s stress difference and its rate at the difference `delta` in `stage`.
    fn station_difference(&self, station: usize, delta: &Kinematics, stage: Stage) -> (f64, f64) {
        let m = &self.modal;
        let Some(divisor) = self.model.stations.all().nth(station).map(|s| s.divisor) else { return (0.0, 0.0) };
        if station >= m.stations.nrows() {
            return (0.0, 0.0);
        }
        let row = m.stations.row(station);
        let n = row.len().min(delta.displacement.len());
        let (mut y, mut v) = (0.0, 0.0);
        for i in 0..n {
            y += row[i] * delta.displacement[i];
            v += row[i] * delta.velocity[i];
        }
        if m.is_truncated() && stage.is_contact() {
            if let Some(c) = m.correction.stations.get(station) {
                let k = m.bar_stiffness;
                y += c[CONTACT] * -k * self.modal_gap(delta.displacement.as_slice());
                v += c[CONTACT] * -k * self.modal_gap(delta.velocity.as_slice());
            }
        }
        (y / divisor, v / divisor)
    }

    /// Per kept mode, each envelope group's largest |row| / divisor over its stations; and each
    /// group's largest |correction row of the contact load| / divisor.
    fn envelope_rows(&self) -> (Vec<[f64; 4]>, [f64; 4]) {
        let groups = crate::solver::envelope::groups(&self.model);
        let divisors: Vec<f64> = self.model.stations.all().map(|s| s.divisor).collect();
        let modes = self.modal.stations.ncols();
        let mut rows = vec![[0.0f64; 4]; modes];
        let mut loads = [0.0f64; 4];
        for (station, (&g, &divisor)) in groups.iter().zip(&divisors).enumerate() {
            let g = usize::from(g).min(3);
            if station >= self.modal.stations.nrows() {
                break;
            }
            for (i, row) in rows.iter_mut().enumerate() {
                row[g] = row[g].max((self.modal.stations[(station, i)] / divisor).abs());
            }
            if let Some(c) = self.modal.correction.stations.get(station) {
                loads[g] = loads[g].max((c[CONTACT] / divisor).abs());
            }
        }
        (rows, loads)
    }

    /// Each envelope group's bound of |d sigma| over its stations and of its rate, from `m` in
    /// `stage`.
    fn envelope_bounds(&self, t: &Tangent<S::TangentWork>, m: &Measure, stage: Stage) -> [(f64, f64); 4] {
        let gap = Probe::Gap as usize;
        let (load, load_rate) = if self.modal.is_truncated() && stage.is_contact() {
            let k = self.modal.bar_stiffness;
            ((k * m.q[gap]).abs(), (k * m.v[gap]).abs())
        } else {
            (0.0, 0.0)
        };
        std::array::from_fn(|g| {
            (m.envelope_q[g] + t.envelope_loads[g] * load, m.envelope_v[g] + t.envelope_loads[g] * load_rate)
        })
    }
}

/// Each envelope group's sum_i rows[i][g] |q_i| and sum_i rows[i][g] |v_i|, the modes in their
/// order, the four groups side by side in one vector (the CPU's widest: the same bits whichever
/// runs, the same as one group after the other).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn envelope_sums(rows: &[[f64; 4]], q: &[f64], v: &[f64]) -> ([f64; 4], [f64; 4]) {
    let n = q.len().min(v.len()).min(rows.len());
    let (rows, q, v) = (&rows[..n], &q[..n], &v[..n]);
    let (mut envelope_q, mut envelope_v) = ([0.0; 4], [0.0; 4]);
    let mut add = |row: &[f64; 4], a: f64, b: f64| {
        for g in 0..4 {
            envelope_q[g] += row[g] * a;
            envelope_v[g] += row[g] * b;
        }
    };
    // Two modes an iteration (in their order: the same sums), half the loop's own instructions.
    let (pairs, q_pairs, v_pairs) = (rows.chunks_exact(2), q.chunks_exact(2), v.chunks_exact(2));
    let rest = (pairs.remainder(), q_pairs.remainder(), v_pairs.remainder());
    for ((row, q), v) in pairs.zip(q_pairs).zip(v_pairs) {
        add(&row[0], q[0].abs(), v[0].abs());
        add(&row[1], q[1].abs(), v[1].abs());
    }
    for ((row, q), v) in rest.0.iter().zip(rest.1).zip(rest.2) {
        add(row, q.abs(), v.abs());
    }
    (envelope_q, envelope_v)
}

/// The largest of `values` (-inf for none, NaN where one is NaN), in four lanes of the CPU's
/// widest vectors (the maximum is exact: the same whichever order).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn largest(values: &[f64]) -> f64 {
    let mut lanes = [f64::NEG_INFINITY; 4];
    let mut nan = false;
    let chunks = values.chunks_exact(4);
    let rest = chunks.remainder();
    for chunk in chunks {
        for l in 0..4 {
            let v = chunk[l];
            nan |= v.is_nan();
            lanes[l] = if v > lanes[l] { v } else { lanes[l] };
        }
    }
    let mut best = lanes.into_iter().chain(rest.iter().copied()).fold(f64::NEG_INFINITY, |b, v| {
        nan |= v.is_nan();
        if v > b {
            v
        } else {
            b
        }
    });
    if nan {
        best = f64::NAN;
    }
    best
}

fn seconds_of(ns: u64) -> f64 {
    crate::results::seconds(ns)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`envelope_sums`] is the plain loop over the modes, one group after the other, to the bit
    /// (lengths with and without a tail of the vectors', rows longer than the state).
    #[test]
    fn the_envelope_sums_are_the_plain_loops_to_the_bit() {
        for (modes, n) in [(65, 65), (46, 46), (9, 7), (3, 3)] {
            let rows: Vec<[f64; 4]> =
                (0..modes).map(|i| std::array::from_fn(|g| ((i * 31 + g * 7) % 17) as f64 / 3.0 + 0.1)).collect();
            let q: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin() * 1e-9).collect();
            let v: Vec<f64> = (0..n).map(|i| (i as f64 * 1.3).cos() * 1e-6).collect();
            let (eq, ev) = envelope_sums(&rows, &q, &v);
            for g in 0..4 {
                let (mut sq, mut sv) = (0.0, 0.0);
                for i in 0..n {
                    sq += rows[i][g] * q[i].abs();
                    sv += rows[i][g] * v[i].abs();
                }
                assert_eq!((eq[g].to_bits(), ev[g].to_bits()), (sq.to_bits(), sv.to_bits()), "{modes} {n} group {g}");
            }
        }
    }

    /// [`largest`] is the maximum of the values (whatever their position among the lanes and the
    /// tail), -inf of none, NaN where one is NaN.
    #[test]
    fn the_largest_value_is_the_maximum_wherever_it_stands() {
        for len in [1, 3, 4, 5, 8, 11] {
            for at in 0..len {
                let mut values: Vec<f64> = (0..len).map(|i| i as f64 * 0.25 - 3.0).collect();
                values[at] = 7.5;
                assert_eq!(largest(&values), 7.5, "len {len} at {at}");
                values[at] = f64::NAN;
                assert!(largest(&values).is_nan(), "len {len} NaN at {at}");
            }
        }
        assert_eq!(largest(&[]), f64::NEG_INFINITY);
    }
}

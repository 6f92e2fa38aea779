//! The stress envelope's per-step work (issue 30): every station's stress from the modal state,
//! its running largest |value| and when it was reached.
//!
//! A station's stress is (s_k . Phi q + s_k^T R f) / divisor: its functional over the kept modes
//! plus the discarded modes' static response to the step's loads (the correction's coefficients
//! times the load coefficients c of [`super::static_correction::Correction`]). The stations are
//! evaluated at the internal steps' ends (the peaks' within-step cubic is kept for the five
//! probes of Table 1: see [`crate::model::stations`] for where the stations sit).
//!
//! A station is skipped at a step when a bound proves it cannot exceed its running largest
//! value. Every station is evaluated at an anchor state q_a (loads c_a); at a later state q,
//! |s . q + C . c| is at most |s . q_a + C . c_a| plus ||s_i / omega_i|| ||omega_i (q_i - q_a,i)||
//! plus sum_a |C_a| max_a |c_a - c_a,a| plus the rigid modes' share: Cauchy-Schwarz in the energy
//! norm over the elastic modes of its beam (an element's end forces of a rigid motion are zero to
//! round-off, which [`StationRows::new`] bounds separately). While the state stays near the
//! anchor most stations are proven below their largest value for the cost of one norm; when more
//! than a [`REANCHOR_FRACTION`] of them must be evaluated, all are, and that state is the new
//! anchor. The envelope is the same with or without the skipping: only stations that cannot rise
//! are skipped.

use super::modal::ModalSystem;

/// A step that must evaluate more than this fraction of the stations evaluates them all and
/// becomes the anchor of the bounds (see the module documentation).
pub const REANCHOR_FRACTION: f64 = 0.125;

/// Multiply-adds per step the envelope may take before it is sampled at a stride instead of
/// every step (or [`ENVELOPE_PER_MODE`] per mode, if more): the converged printed rung (344
/// stations x 65 modes on the paper scenario, 22 360) stays below it; a full basis of hundreds
/// of elements (a test of the stepper, O(n^2) stations x modes against the stepper's O(n))
/// samples every k-th step, and says so.
pub const ENVELOPE_BUDGET: usize = 1 << 15;

/// Multiply-adds per mode and step the envelope may take on a large basis: about the stepper's
/// own work per mode.
pub const ENVELOPE_PER_MODE: usize = 8;
use super::static_correction::LOADS;

/// The stations' rows in modal coordinates, ready for the per-step products.
#[derive(Clone, Debug, Default)]
pub struct StationRows {
    /// Row-major, stations x modes, already divided by each station's divisor (Pa per unit q).
    rows: Vec<f64>,
    /// The static correction's coefficients per station, divided likewise (Pa per unit load).
    correction: Vec<[f64; LOADS]>,
    /// Modes per row.
    modes: usize,
    /// The first mode of the bridge (the arrestor's modes come first).
    lower_modes: usize,
    /// Per station: whether it is the bridge's.
    upper: Vec<bool>,
    /// Per station: its envelope (0 lower bending, 1 lower shear, 2 upper bending, 3 upper
    /// shear), for [`Self::worst_only`].
    groups: Vec<u8>,

    /// Per station: ||s_i / omega_i|| over the elastic modes of its beam.
    energy_norm: Vec<f64>,
    /// Per station: sum over the loads of |coefficient|, Pa per unit load.
    correction_norm: Vec<f64>,
    /// Per station: sum of |s_i| over the rigid modes (round-off only).
    rigid_norm: Vec<f64>,
    /// omega_i^2 of the modes (for each beam's strain energy).
    omega2: Vec<f64>,
    /// Evaluated every this many steps (1: every step; see [`ENVELOPE_BUDGET`]).
    pub stride: u64,
}

/// A run's own side of the envelope's work (the rows are shared with the recorder's thread): the
/// anchor of the bounds, its modal state, load coefficients and every station's value there
/// (empty: none yet, or forgotten for a restored state), and whether only each envelope's worst
/// is kept exact.
#[derive(Clone, Debug, Default)]
pub struct EnvelopeWork {
    anchor_q: Vec<f64>,
    anchor_loads: [f64; LOADS],
    anchor_values: Vec<f64>,
    /// Keep only each envelope's worst value exact (a check rung's or a twin's run, whose
    /// figures and spreads compare the beams' worst stresses): a station is skipped wherever its
    /// bound is below its envelope's running worst, not only below its own running largest
    /// value. The other stations' values are then lower bounds of theirs.
    pub worst_only: bool,
}

impl EnvelopeWork {
    /// Forgets the anchor (a restored state is not near it): the next observation evaluates
    /// every station.
    pub fn invalidate(&mut self) {
        self.anchor_q.clear();
        self.anchor_values.clear();
    }
}

impl StationRows {
    /// The rows of `system`'s stations with `divisors` (m^3 or m^2 per station, in order).
    pub fn new(system: &ModalSystem, divisors: &[f64], groups: Vec<u8>) -> StationRows {
        let upper: Vec<bool> = groups.iter().map(|g| *g >= 2).collect();
        let (count, modes) = (system.stations.nrows(), system.stations.ncols());
        debug_assert_eq!(count, divisors.len());
        let mut rows = Vec::with_capacity(count * modes);
        let mut energy_norm = Vec::with_capacity(count);
        let mut rigid_norm = Vec::with_capacity(count);
        for (k, divisor) in divisors.iter().enumerate().take(count) {
            let scale = 1.0 / divisor;
            let (mut squares, mut rigid) = (0.0, 0.0);
            for i in 0..modes {
                let value = system.stations[(k, i)] * scale;
                rows.push(value);
                if system.omega2[i] > 0.0 {
                    squares += value * value / system.omega2[i];
                } else {
                    rigid += value.abs();
                }
            }
            energy_norm.push(squares.sqrt());
            rigid_norm.push(rigid);
        }
        let correction: Vec<[f64; LOADS]> = (0..count)
            .map(|k| {
                let c = system.correction.stations.get(k).copied().unwrap_or([0.0; LOADS]);
                c.map(|v| v / divisors[k])
            })
            .collect();
        let correction_norm = correction.iter().map(|c| c.iter().map(|v| v.abs()).sum()).collect();
        StationRows {
            rows,
            correction,
            modes,
            lower_modes: system.lower_dofs,
            upper,
            groups,
            energy_norm,
            correction_norm,
            rigid_norm,
            omega2: system.omega2.iter().copied().collect(),
            stride: (count * modes).div_ceil(ENVELOPE_BUDGET.max(ENVELOPE_PER_MODE * modes)).max(1) as u64,
        }
    }

    /// Number of stations.
    pub fn len(&self) -> usize {
        self.energy_norm.len()
    }

    /// True without stations.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// One station's stress at `q` under `loads`, Pa (signed).
    fn value(&self, k: usize, q: &[f64], loads: Option<&[f64; LOADS]>) -> f64 {
        let n = self.modes.min(q.len());
        let row = &self.rows[k * self.modes..k * self.modes + n];
        let (start, end) = if self.upper[k] { (self.lower_modes.min(n), n) } else { (0, self.lower_modes.min(n)) };
        let mut value = dot(&row[start..end], &q[start..end]);
        if let Some(c) = loads {
            let coefficients = &self.correction[k];
            value += (0..LOADS).map(|a| coefficients[a] * c[a]).sum::<f64>();
        }
        value
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
        if self.is_empty() {
            return;
        }
        let n = self.modes.min(q.len());
        let count = self.len();
        // Each envelope's running worst (only when only the worst is kept exact).
        let mut worst = [0.0f64; 4];
        if work.worst_only {
            for (k, m) in max.iter().enumerate() {
                let g = usize::from(self.groups[k]);
                worst[g] = worst[g].max(*m);
            }
        }
        let groups = &self.groups;
        let raise = |k: usize, value: f64, worst: &mut [f64; 4], max: &mut [f64], times: &mut [f64]| {
            if value.abs() > max[k] {
                max[k] = value.abs();
                times[k] = time;
                let g = usize::from(groups[k]);
                worst[g] = worst[g].max(max[k]);
            }
        };
        let anchored = work.anchor_q.len() == q.len() && work.anchor_values.len() == count;
        if anchored {
            // The distance from the anchor in each beam's energy norm, the rigid modes' largest
            // move and the loads' largest change.
            let lower = self.lower_modes.min(n);
            let (mut distance, mut rigid) = ([0.0f64; 2], 0.0f64);
            for i in 0..n {
                let d = q[i] - work.anchor_q[i];
                if self.omega2[i] > 0.0 {
                    distance[usize::from(i >= lower)] += self.omega2[i] * d * d;
                } else {
                    rigid = rigid.max(d.abs());
                }
            }
            let distance = distance.map(f64::sqrt);
            let load_change = match loads {
                Some(c) => (0..LOADS).fold(0.0f64, |m, a| m.max((c[a] - work.anchor_loads[a]).abs())),
                None => 0.0,
            };
            let budget = (REANCHOR_FRACTION * count as f64) as usize;
            let mut evaluated = 0;
            let mut skipped_all = true;
            for k in 0..count {
                let bound = work.anchor_values[k].abs()
                    + self.energy_norm[k] * distance[usize::from(self.upper[k])]
                    + self.correction_norm[k] * load_change
                    + self.rigid_norm[k] * rigid;
                let threshold = if work.worst_only { worst[usize::from(self.groups[k])] } else { max[k] };
                // The bound's own arithmetic is loose by round-off only: a margin of 1e-9.
                if bound * (1.0 + 1e-9) + 1e-300 < threshold {
                    continue;
                }
                evaluated += 1;
                if evaluated > budget {
                    skipped_all = false;
                    break;
                }
                let value = self.value(k, q, loads);
                raise(k, value, &mut worst, max, times);
            }
            if skipped_all {
                return;
            }
        }
        // No anchor, or the state has moved too far from it: every station, and a new anchor.
        let mut values = std::mem::take(&mut work.anchor_values);
        values.clear();
        for k in 0..count {
            let value = self.value(k, q, loads);
            raise(k, value, &mut worst, max, times);
            values.push(value);
        }
        work.anchor_values = values;
        work.anchor_q.clear();
        work.anchor_q.extend_from_slice(q);
        work.anchor_loads = loads.copied().unwrap_or([0.0; LOADS]);
    }

    /// [`Self::observe`] evaluating every station (the skipping's reference in the tests).
    #[cfg(test)]
    fn observe_all(&self, q: &[f64], loads: Option<&[f64; LOADS]>, time: f64, max: &mut [f64], times: &mut [f64]) {
        for k in 0..self.len() {
            let value = self.value(k, q, loads);
            if value.abs() > max[k] {
                max[k] = value.abs();
                times[k] = time;
            }
        }
    }
}

/// Each station's envelope index (see [`StationRows::new`]) in the order of
/// [`crate::model::stations::Stations::all`].
pub fn groups(model: &crate::model::Model) -> Vec<u8> {
    let st = &model.stations;
    let counts = [st.lower.bending.len(), st.lower.shear.len(), st.upper.bending.len(), st.upper.shear.len()];
    counts.iter().enumerate().flat_map(|(g, &n)| std::iter::repeat_n(g as u8, n)).collect()
}

impl StationRows {
    /// Every station's signed stress, Pa, at the state `q` under the correction's load
    /// coefficients `loads` (None: a full basis), into `out` (one value per station, in the order
    /// of [`crate::model::stations::Stations::all`]): the same sums as [`Self::observe`], without
    /// the bound that skips stations (a log's per-step stresses, issue 30).
    pub fn stresses(&self, q: &[f64], loads: Option<&[f64; LOADS]>, out: &mut [f64]) {
        let (len, n) = (self.len().min(out.len()), self.modes.min(q.len()));
        let mut k = 0;
        // Four stations of one beam at a time (sixteen independent sums: the short products are
        // latency-bound one by one), each summed as `dot` sums it, so the values are `value`'s.
        while k + 4 <= len && self.upper[k] == self.upper[k + 3] {
            let (start, end) = if self.upper[k] { (self.lower_modes.min(n), n) } else { (0, self.lower_modes.min(n)) };
            let row = |j: usize| &self.rows[(k + j) * self.modes + start..(k + j) * self.modes + end];
            let sums = dot4([row(0), row(1), row(2), row(3)], &q[start..end]);
            for (j, sum) in sums.into_iter().enumerate() {
                out[k + j] = match loads {
                    Some(c) => {
                        let coefficients = &self.correction[k + j];
                        sum + (0..LOADS).map(|a| coefficients[a] * c[a]).sum::<f64>()
                    }
                    None => sum,
                };
            }
            k += 4;
        }
        while k < len {
            out[k] = self.value(k, q, loads);
            k += 1;
        }
    }

    /// Multiply-adds of one [`Self::stresses`] call (stations x modes of their beams, about).
    pub fn work(&self) -> usize {
        self.len() * self.modes
    }
}

/// [`dot`] of four rows with one vector at once, each summed in `dot`'s order (the same bits).
fn dot4(rows: [&[f64]; 4], b: &[f64]) -> [f64; 4] {
    let n = rows.iter().map(|r| r.len()).fold(b.len(), usize::min);
    let full = n - n % 4;
    let mut lanes = [[0.0f64; 4]; 4];
    for i in (0..full).step_by(4) {
        for (row, lane) in rows.iter().zip(lanes.iter_mut()) {
            for l in 0..4 {
                lane[l] += row[i + l] * b[i + l];
            }
        }
    }
    let mut out = [0.0; 4];
    for (j, row) in rows.iter().enumerate() {
        let tail: f64 = (full..n).map(|i| row[i] * b[i]).sum();
        let lane = &lanes[j];
        out[j] = (lane[0] + lane[1]) + (lane[2] + lane[3]) + tail;
    }
    out
}

/// sum a_i b_i in four lanes (the compiler vectorises it), as the stepper's products.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut lanes = [0.0f64; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for l in 0..4 {
            lanes[l] += x[l] * y[l];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(&x, &y)| x * y).sum();
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Model, Scenario};

    /// The skipping never hides a rise: the envelope with the anchored bounds equals the envelope
    /// of every station evaluated at every state, on a smooth trajectory of the paper model's
    /// modes (most steps near their anchor: the skipping path) with jumps (the re-anchoring),
    /// and with each envelope's worst only, the worst values alike.
    #[test]
    fn skipping_by_the_anchored_bound_changes_no_envelope_value() {
        let model = Model::new(&Scenario::paper()).unwrap();
        let system = ModalSystem::new(&model).unwrap();
        let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
        let n = system.dofs();
        let mut seed = 12345u64;
        let mut random = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let phases: Vec<f64> = (0..n).map(|_| 6.0 * random()).collect();
        let amplitudes: Vec<f64> = (0..n).map(|i| random() / (1.0 + system.omega2[i])).collect();
        for worst_only in [false, true] {
            let rows = StationRows::new(&system, &divisors, groups(&model));
            let mut work = EnvelopeWork { worst_only, ..EnvelopeWork::default() };
            let count = rows.len();
            let (mut max, mut times) = (vec![0.0; count], vec![0.0; count]);
            let (mut all, mut all_times) = (vec![0.0; count], vec![0.0; count]);
            for step in 0..3000 {
                let t = step as f64 * 2e-5;
                let jump = if step % 700 == 350 { 3.0 } else { 1.0 };
                let q: Vec<f64> = (0..n)
                    .map(|i| jump * amplitudes[i] * (system.omega2[i].sqrt() * t + phases[i]).sin() * (1.0 + t))
                    .collect();
                rows.observe(&mut work, &q, None, t, &mut max, &mut times);
                rows.observe_all(&q, None, t, &mut all, &mut all_times);
            }
            if worst_only {
                for g in 0..4u8 {
                    let of = |v: &[f64]| {
                        groups(&model).iter().zip(v).filter(|(h, _)| **h == g).map(|(_, v)| *v).fold(0.0, f64::max)
                    };
                    assert_eq!(of(&max), of(&all), "envelope {g}'s worst");
                }
            } else {
                assert_eq!(max, all);
                assert_eq!(times, all_times);
            }
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
        assert_eq!(rows.work(), rows.len() * n);
    }
}

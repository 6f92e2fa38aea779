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
//! value: by Cauchy-Schwarz in the energy norm, |s . Phi q| <= ||s_i / omega_i|| ||omega_i q_i||
//! over the elastic modes of its beam (its functional vanishes on the rigid modes: an element's
//! end forces of a rigid motion are zero to round-off, which [`StationRows::new`] bounds
//! separately), and ||omega q||^2 is twice the kept modes' strain energy of that beam. The
//! envelope is the same with or without the skipping: only stations that cannot rise are skipped.

use super::modal::ModalSystem;

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
    /// Per station: ||s_i / omega_i|| over the elastic modes of its beam, plus the rigid modes'
    /// share (|s_i| times a bound on |q_i|, see [`Self::bound`]).
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

impl StationRows {
    /// The rows of `system`'s stations with `divisors` (m^3 or m^2 per station, in order).
    pub fn new(system: &ModalSystem, divisors: &[f64], upper: Vec<bool>) -> StationRows {
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

    /// Raises each station's running largest |stress| (`max`, with `times`) by the state `q`
    /// at `time` s under the correction's load coefficients `loads` (None: a full basis).
    pub fn observe(&self, q: &[f64], loads: Option<&[f64; LOADS]>, time: f64, max: &mut [f64], times: &mut [f64]) {
        if self.is_empty() {
            return;
        }
        let n = self.modes.min(q.len());
        let lower = self.lower_modes.min(n);
        let strain = |range: std::ops::Range<usize>| 0.5 * weighted_squares(&self.omega2[range.clone()], &q[range]);
        self.observe_with(q, loads, (strain(0..lower), strain(lower..n)), time, max, times);
    }

    /// [`Self::observe`] with each beam's kept modes' strain energy 1/2 sum omega_i^2 q_i^2
    /// given (lower, upper); infinite: every station evaluated.
    fn observe_with(
        &self,
        q: &[f64],
        loads: Option<&[f64; LOADS]>,
        strain: (f64, f64),
        time: f64,
        max: &mut [f64],
        times: &mut [f64],
    ) {
        let n = self.modes.min(q.len());
        let load_size = loads.map_or(0.0, |c| c.iter().fold(0.0, |m: f64, v| m.max(v.abs())));
        // The rigid modes' coordinates (the bridge's rotation) enter through round-off only.
        let rigid_size = q.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        let energy = [(2.0 * strain.0).max(0.0).sqrt(), (2.0 * strain.1).max(0.0).sqrt()];
        for k in 0..self.len() {
            let beam = usize::from(self.upper[k]);
            let bound = self.energy_norm[k] * energy[beam]
                + self.correction_norm[k] * load_size
                + self.rigid_norm[k] * rigid_size;
            // The bound is loose by round-off only in its own arithmetic: a margin of 1e-9.
            if bound * (1.0 + 1e-9) < max[k] {
                continue;
            }
            let row = &self.rows[k * self.modes..k * self.modes + n];
            let (range_start, range_end) =
                if self.upper[k] { (self.lower_modes, n) } else { (0, self.lower_modes.min(n)) };
            let mut value = dot(&row[range_start..range_end], &q[range_start..range_end]);
            if let Some(c) = loads {
                let coefficients = &self.correction[k];
                value += (0..LOADS).map(|a| coefficients[a] * c[a]).sum::<f64>();
            }
            if value.abs() > max[k] {
                max[k] = value.abs();
                times[k] = time;
            }
        }
    }
}

impl StationRows {
    /// Every station's signed stress, Pa, at the state `q` under the correction's load
    /// coefficients `loads` (None: a full basis), into `out` (one value per station, in the order
    /// of [`crate::model::stations::Stations::all`]): the same sums as [`Self::observe`], without
    /// the bound that skips stations (a log's per-step stresses, issue 30).
    pub fn stresses(&self, q: &[f64], loads: Option<&[f64; LOADS]>, out: &mut [f64]) {
        let n = self.modes.min(q.len());
        for (k, value) in out.iter_mut().enumerate().take(self.len()) {
            let row = &self.rows[k * self.modes..k * self.modes + n];
            let (start, end) = if self.upper[k] { (self.lower_modes.min(n), n) } else { (0, self.lower_modes.min(n)) };
            let mut sum = dot(&row[start..end], &q[start..end]);
            if let Some(c) = loads {
                let coefficients = &self.correction[k];
                sum += (0..LOADS).map(|a| coefficients[a] * c[a]).sum::<f64>();
            }
            *value = sum;
        }
    }

    /// Multiply-adds of one [`Self::stresses`] call (stations x modes of their beams, about).
    pub fn work(&self) -> usize {
        self.len() * self.modes
    }
}

/// sum w_i x_i^2 in four lanes.
fn weighted_squares(w: &[f64], x: &[f64]) -> f64 {
    let n = w.len().min(x.len());
    let mut lanes = [0.0f64; 4];
    let (cw, cx) = (w[..n].chunks_exact(4), x[..n].chunks_exact(4));
    let (rw, rx) = (cw.remainder(), cx.remainder());
    for (a, b) in cw.zip(cx) {
        for l in 0..4 {
            lanes[l] += a[l] * b[l] * b[l];
        }
    }
    let tail: f64 = rw.iter().zip(rx).map(|(&a, &b)| a * b * b).sum();
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
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

    /// The skipping bound never hides a rise: the envelope with the bound equals the envelope
    /// of every station evaluated at every state, on random states of the paper model.
    #[test]
    fn skipping_by_the_energy_bound_changes_no_envelope_value() {
        let model = Model::new(&Scenario::paper()).unwrap();
        let system = ModalSystem::new(&model).unwrap();
        let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
        let upper: Vec<bool> = (0..divisors.len()).map(|k| k >= model.stations.lower.len()).collect();
        let rows = StationRows::new(&system, &divisors, upper);
        let n = system.dofs();
        let (mut max, mut times) = (vec![0.0; rows.len()], vec![0.0; rows.len()]);
        let (mut all, mut all_times) = (vec![0.0; rows.len()], vec![0.0; rows.len()]);
        let mut seed = 12345u64;
        let mut random = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for step in 0..400 {
            // Amplitudes falling like 1 / omega (the modes of an impact), scaled per step.
            let size = 1.0 + (step % 37) as f64;
            let q: Vec<f64> = (0..n).map(|i| size * random() / (1.0 + system.omega2[i].sqrt())).collect();
            rows.observe(&q, None, step as f64, &mut max, &mut times);
            // Every station, no bound: the reference.
            let infinite = (f64::INFINITY, f64::INFINITY);
            rows.observe_with(&q, None, infinite, step as f64, &mut all, &mut all_times);
        }
        assert_eq!(max, all);
        assert_eq!(times, all_times);
    }

    /// A log's per-step stresses are the envelope's values: their running largest |value| over
    /// random states of the paper model (with and without the static correction's loads) is the
    /// envelope's, to the bit (the same sums in the same order).
    #[test]
    fn per_step_stresses_raise_the_same_envelope() {
        let model = Model::new(&Scenario::paper()).unwrap();
        let system = ModalSystem::new(&model).unwrap();
        let divisors: Vec<f64> = model.stations.all().map(|s| s.divisor).collect();
        let upper: Vec<bool> = (0..divisors.len()).map(|k| k >= model.stations.lower.len()).collect();
        let rows = StationRows::new(&system, &divisors, upper);
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
            rows.observe(&q, loads, step as f64, &mut max, &mut times);
            rows.stresses(&q, loads, &mut values);
            for (r, v) in running.iter_mut().zip(&values) {
                *r = r.max(v.abs());
            }
        }
        assert_eq!(running, max);
        assert_eq!(rows.work(), rows.len() * n);
    }
}

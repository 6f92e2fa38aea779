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
//!
//! The per-station bound is not even computed for most stations: at the anchor each station's
//! headroom h_k = threshold_k - |value_k| is split between the two ways its value can move, the
//! modes (E_k d + R_k r <= E_k (d + rho r), rho the beam's largest R_k / E_k) and the loads
//! (C_k dc), and h_k / (2 E_k) and h_k / (2 C_k) are sorted into octave buckets; a step looks only
//! at the stations whose share is below its distance or its load change (any other station's
//! bound is below its threshold). The bound of a station looked at takes its load term exactly.

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
    /// Per station: the allowable stress there, Pa (0: none; empty: none anywhere), so that a
    /// worst-only run keeps each envelope's worst utilisation exact too.
    allowable: Vec<f64>,
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
    /// Per station: its modal part s_k . q_a at the anchor (the load term is taken exactly).
    anchor_modal: Vec<f64>,
    /// Per beam: its stations by their modes' share of the headroom, and by the loads' share.
    by_modes: [Buckets; 2],
    by_loads: [Buckets; 2],
    /// Per beam: the largest R_k / E_k of its stations (the rigid move's weight).
    rigid_ratio: [f64; 2],
    /// Per station: the observation it was last looked at (a station in both screens is looked
    /// at once), and the observation count.
    seen: Vec<u32>,
    observation: u32,
    /// Each envelope's running worst |stress| and worst utilisation (of stations with an
    /// allowable).
    worst: [f64; 4],
    worst_utilisation: [f64; 4],
    /// Keep only each envelope's worst value exact (a check rung's or a twin's run, whose
    /// figures and spreads compare the beams' worst stresses): a station is skipped wherever its
    /// bound is below its envelope's running worst, not only below its own running largest
    /// value. The other stations' values are then lower bounds of theirs.
    pub worst_only: bool,
}

/// Octave buckets of a share lambda: bucket 0 holds stations always looked at (lambda <= 0),
/// buckets 1..BUCKETS-2 one octave each from the smallest positive lambda, bucket BUCKETS-2
/// everything above, bucket BUCKETS-1 the stations that cannot move this way (lambda infinite).
const BUCKETS: usize = 31;

/// Stations sorted into octave buckets of their share lambda.
#[derive(Clone, Debug, Default)]
struct Buckets {
    order: Vec<u32>,
    /// Where bucket j starts in `order` (`starts[BUCKETS]` its length).
    starts: [u32; BUCKETS + 1],
    /// The smallest positive lambda: bucket 1's lower edge.
    base: f64,
}

impl Buckets {
    /// Sorts `(station, lambda)` into the buckets.
    fn fill(&mut self, members: &[(u32, f64)]) {
        self.base = members.iter().map(|m| m.1).filter(|l| *l > 0.0 && l.is_finite()).fold(f64::INFINITY, f64::min);
        if !self.base.is_finite() {
            self.base = 1.0;
        }
        let base = self.base;
        let bucket = |l: f64| -> usize {
            if l <= 0.0 || l.is_nan() {
                0
            } else if l.is_infinite() {
                BUCKETS - 1
            } else {
                // The octave above base: the exponent of l / base (>= 1 up to round-off).
                let octave = ((l / base).max(1.0).to_bits() >> 52) as usize - 1023;
                (1 + octave).min(BUCKETS - 2)
            }
        };
        let mut counts = [0u32; BUCKETS + 1];
        for (_, l) in members {
            counts[bucket(*l) + 1] += 1;
        }
        for j in 1..=BUCKETS {
            counts[j] += counts[j - 1];
        }
        self.starts = counts;
        self.order.clear();
        self.order.resize(members.len(), 0);
        let mut next = counts;
        for (k, l) in members {
            let b = bucket(*l);
            self.order[next[b] as usize] = *k;
            next[b] += 1;
        }
    }

    /// The stations whose lambda may be at or below `reach` (bucket j >= 1 holds lambdas from
    /// base 2^(j-1) up, to the bucketing's round-off: 1e-12 here).
    fn below(&self, reach: f64) -> &[u32] {
        let edge = |j: usize| self.base * (1u64 << (j - 1)) as f64 * (1.0 - 1e-12);
        let last = (1..BUCKETS - 1).find(|&j| edge(j) > reach).unwrap_or(BUCKETS - 1);
        // Bucket 0 starts at 0: the prefix of `order`.
        &self.order[..self.starts[last] as usize]
    }
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
            allowable: Vec::new(),
            stride: (count * modes).div_ceil(ENVELOPE_BUDGET.max(ENVELOPE_PER_MODE * modes)).max(1) as u64,
        }
    }

    /// The stations' allowable stresses, Pa (0: none), in station order: a worst-only run then
    /// keeps each envelope's worst utilisation exact as well as its worst stress.
    pub fn with_allowables(mut self, allowable: Vec<f64>) -> StationRows {
        debug_assert_eq!(allowable.len(), self.len());
        self.allowable = allowable;
        self
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
            let mut complete = true;
            work.observation = work.observation.wrapping_add(1);
            'beams: for (beam, &beam_distance) in distance.iter().enumerate() {
                let moved = beam_distance + work.rigid_ratio[beam] * rigid;
                let (modes, loaded) = (work.by_modes[beam].below(moved), work.by_loads[beam].below(load_change));
                let (modes, loaded) = (modes.len(), loaded.len());
                for index in 0..modes + loaded {
                    let k = if index < modes {
                        work.by_modes[beam].order[index]
                    } else {
                        work.by_loads[beam].order[index - modes]
                    } as usize;
                    if work.seen[k] == work.observation {
                        continue;
                    }
                    work.seen[k] = work.observation;
                    let load_term = match loads {
                        Some(c) => {
                            let coefficients = &self.correction[k];
                            (0..LOADS).map(|a| coefficients[a] * c[a]).sum::<f64>()
                        }
                        None => 0.0,
                    };
                    let bound = (work.anchor_modal[k] + load_term).abs()
                        + self.energy_norm[k] * beam_distance
                        + self.rigid_norm[k] * rigid;
                    // The bound's own arithmetic is loose by round-off only: a margin of 1e-9.
                    // At the threshold the station cannot exceed it (a station at rest at its
                    // largest value, 0 before the impact, stays skipped).
                    if bound * (1.0 + 1e-9) <= self.threshold(work, k, max) {
                        continue;
                    }
                    evaluated += 1;
                    if evaluated > budget {
                        complete = false;
                        break 'beams;
                    }
                    let value = self.value(k, q, loads);
                    self.raise(work, k, value, time, max, times);
                }
            }
            if complete {
                return;
            }
        }
        // No anchor, or the state has moved too far from it: every station, and a new anchor.
        let mut values = std::mem::take(&mut work.anchor_values);
        let mut modal = std::mem::take(&mut work.anchor_modal);
        values.clear();
        modal.clear();
        for k in 0..count {
            let modal_part = self.value(k, q, None);
            let value = self.value(k, q, loads);
            if value.abs() > max[k] {
                max[k] = value.abs();
                times[k] = time;
            }
            values.push(value);
            modal.push(modal_part);
        }
        (work.anchor_values, work.anchor_modal) = (values, modal);
        work.anchor_q.clear();
        work.anchor_q.extend_from_slice(q);
        work.anchor_loads = loads.copied().unwrap_or([0.0; LOADS]);
        self.anchor(work, max);
    }

    /// The level station `k`'s bound must stay below for it to be skipped: its own running
    /// largest value, or (worst only) the lower of its envelope's worst stress and the stress at
    /// which it would reach its envelope's worst utilisation.
    fn threshold(&self, work: &EnvelopeWork, k: usize, max: &[f64]) -> f64 {
        if !work.worst_only {
            return max[k];
        }
        let g = usize::from(self.groups[k]);
        match self.allowable.get(k) {
            Some(&a) if a > 0.0 => work.worst[g].min(work.worst_utilisation[g] * a),
            _ => work.worst[g],
        }
    }

    /// Raises station `k`'s running largest |value| and its envelope's worst.
    fn raise(&self, work: &mut EnvelopeWork, k: usize, value: f64, time: f64, max: &mut [f64], times: &mut [f64]) {
        if value.abs() > max[k] {
            max[k] = value.abs();
            times[k] = time;
            let g = usize::from(self.groups[k]);
            work.worst[g] = work.worst[g].max(max[k]);
            if let Some(&a) = self.allowable.get(k).filter(|a| **a > 0.0) {
                work.worst_utilisation[g] = work.worst_utilisation[g].max(max[k] / a);
            }
        }
    }

    /// Sets up the screening at a new anchor (its values in `work`): each envelope's worst, and
    /// every station's lambda sorted into its beam's octave buckets.
    fn anchor(&self, work: &mut EnvelopeWork, max: &[f64]) {
        let count = self.len();
        (work.worst, work.worst_utilisation) = ([0.0; 4], [0.0; 4]);
        for (k, m) in max.iter().enumerate().take(count) {
            let g = usize::from(self.groups[k]);
            work.worst[g] = work.worst[g].max(*m);
            if let Some(&a) = self.allowable.get(k).filter(|a| **a > 0.0) {
                work.worst_utilisation[g] = work.worst_utilisation[g].max(*m / a);
            }
        }
        // Each station's headroom (the margin of 1e-9 of the per-station test taken off), half
        // of it for the modes' move and half for the loads' change.
        let headroom: Vec<f64> = (0..count)
            .map(|k| 0.5 * (self.threshold(work, k, max) - work.anchor_values[k].abs() * (1.0 + 1e-9)))
            .collect();
        // A station with no such term: that way it cannot move (infinite share), else its share.
        let share = |h: f64, norm: f64| if norm > 0.0 { h / (norm * (1.0 + 1e-9)) } else { f64::INFINITY };
        if work.seen.len() != count {
            work.seen = vec![0; count];
        }
        for beam in 0..2 {
            let in_beam = || (0..count).filter(move |&k| usize::from(self.upper[k]) == beam);
            let rigid_ratio = in_beam()
                .filter(|&k| self.energy_norm[k] > 0.0)
                .map(|k| self.rigid_norm[k] / self.energy_norm[k])
                .fold(0.0f64, f64::max);
            // Rounded up so that R_k <= ratio E_k holds after the multiplication's round-off; a
            // station moved by the rigid modes only is looked at whenever the modes move.
            work.rigid_ratio[beam] = rigid_ratio * (1.0 + 1e-12);
            let modes: Vec<(u32, f64)> = in_beam()
                .map(|k| {
                    let l = if self.energy_norm[k] == 0.0 && self.rigid_norm[k] > 0.0 {
                        0.0
                    } else {
                        share(headroom[k], self.energy_norm[k])
                    };
                    (k as u32, l)
                })
                .collect();
            work.by_modes[beam].fill(&modes);
            let loaded: Vec<(u32, f64)> =
                in_beam().map(|k| (k as u32, share(headroom[k], self.correction_norm[k]))).collect();
            work.by_loads[beam].fill(&loaded);
        }
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
    /// and with each envelope's worst only, the worst values and worst utilisations alike.
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
        // Allowables that vary along each beam (and none at some stations), so that a station
        // below its envelope's worst stress can hold its worst utilisation.
        let allowables: Vec<f64> =
            (0..divisors.len()).map(|k| if k % 7 == 3 { 0.0 } else { 1.0 + (k % 5) as f64 }).collect();
        for worst_only in [false, true] {
            let rows = StationRows::new(&system, &divisors, groups(&model)).with_allowables(allowables.clone());
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
                // The correction's loads (a contact force and inertia loads) vary smoothly over
                // the second half, with the jumps: the loads' screen and the exact load term.
                let loads: [f64; LOADS] =
                    std::array::from_fn(|a| jump * 1e4 * (a as f64 + 1.0) * (300.0 * t + a as f64).sin());
                let loads = (step >= 1500).then_some(&loads);
                rows.observe(&mut work, &q, loads, t, &mut max, &mut times);
                rows.observe_all(&q, loads, t, &mut all, &mut all_times);
            }
            if worst_only {
                for g in 0..4u8 {
                    let of = |v: &[f64]| {
                        groups(&model).iter().zip(v).filter(|(h, _)| **h == g).map(|(_, v)| *v).fold(0.0, f64::max)
                    };
                    assert_eq!(of(&max), of(&all), "envelope {g}'s worst");
                    let utilisation = |v: &[f64]| {
                        let pairs = groups(&model).into_iter().zip(v.iter().zip(&allowables));
                        pairs.filter(|(h, (_, a))| *h == g && **a > 0.0).map(|(_, (v, a))| v / a).fold(0.0, f64::max)
                    };
                    assert_eq!(utilisation(&max), utilisation(&all), "envelope {g}'s worst utilisation");
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

//! The linear model's range over every node of both beams (issue 40): the Euler-Bernoulli
//! elements, the contact at fixed points of each beam and the linear-elastic stresses hold for
//! small deflections, small rotations and elastic strains only. A run that leaves that range
//! anywhere (not just at the arrestor's tip) is outside the model, whatever its mesh and steps.
//!
//! Every node's deflection and rotation is a row of the basis's shapes times the coordinates,
//! plus the discarded modes' static part (the correction's rows times its load coefficients).
//! Evaluating all of them every step would cost as much as the step itself, so each step first
//! takes a bound, sum_j max_r |phi_rj| |q_j| + sum_a max_r |R_ra| |c_a| (O(modes)), and evaluates
//! the rows only where the bound reaches the limit: a value below the bound is below the limit,
//! and every value that could exceed it is computed exactly.

use std::ops::Range;

use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

use super::static_correction::LOADS;
use crate::model::Model;

/// Largest deflection of any node, as a fraction of its beam's length, within the linear model's
/// small-deflection range: where the linear tip deflection of a cantilever under a tip load is
/// 0.1 L (P L^2 / EI = 0.3), the large-deflection elastica (Bisshopp and Drucker 1945; solved by
/// shooting: 0.0990 L) is 1.0 % less; the gap grows about as (w/L)^2 beyond it.
pub const SMALL_DEFLECTION: f64 = 0.1;

/// Largest rotation of any node, rad, within the small-rotation range: the same cantilever's tip
/// slope where its deflection is [`SMALL_DEFLECTION`] (theta = P L^2 / 2EI = 0.15 at
/// P L^2 / EI = 0.3), where sin(theta) and tan(theta) differ from theta by 0.4 % and 0.8 %: the
/// contact points, fixed on each beam, have moved along it by L (1 - cos 0.15) = 1.1 % of a length.
pub const SMALL_ROTATION: f64 = 0.15;

/// Largest strain (the extreme fibre's bending stress, or sqrt(3) times the shear stress, over E)
/// within the linear-elastic range whatever the material: the elastic strain of structural metals
/// ends below it (yield over E: S355 0.17 %, S960 0.46 %, aluminium 7075-T6 0.7 %, Ti-6Al-4V
/// 0.8 %). A stated `yield_stress` checks the material's own, lower limit.
pub const ELASTIC_STRAIN: f64 = 0.01;

/// One beam's largest value of one range quantity so far.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RangePeak {
    /// An upper bound of the largest |value| at the steps' ends (exact wherever it reaches the
    /// limit): m for deflections, rad for rotations, a fraction for strains.
    pub value: f64,
    /// Where the largest exact value is, m from the beam's support (null: no node's value needed
    /// evaluating, the bound stayed below the limit).
    pub position: Option<f64>,
    /// When, s.
    pub time: f64,
}

impl RangePeak {
    /// Raises the peak by `value` at `time` (and `position` where exact).
    fn raise(&mut self, value: f64, position: Option<f64>, time: f64) {
        if value > self.value || value.is_nan() {
            *self = RangePeak { value, position, time };
        }
    }
}

/// The range quantities of a run so far, per beam.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ModelRange {
    /// The arrestor's largest |deflection| of any node, m (its bending; the arrestor has no
    /// rigid-body motion of its own).
    pub lower_deflection: RangePeak,
    /// The bridge's, m (its bending: from its position at the first touch, less its rigid pitching
    /// about the hinge, which the rotations bound).
    pub upper_deflection: RangePeak,
    /// The arrestor's largest |rotation| of any node, rad.
    pub lower_rotation: RangePeak,
    /// The bridge's, rad.
    pub upper_rotation: RangePeak,
}

impl ModelRange {
    /// Every value finite and >= 0, every time within `[0, end]` s (a restored state's check).
    pub fn is_plausible(&self, end: f64) -> bool {
        [self.lower_deflection, self.upper_deflection, self.lower_rotation, self.upper_rotation].iter().all(|p| {
            p.value.is_finite()
                && p.value >= 0.0
                && p.time.is_finite()
                && (0.0..=end).contains(&p.time)
                && p.position.is_none_or(f64::is_finite)
        })
    }
}

/// One kind of row (deflections or rotations) of one beam.
#[derive(Clone, Debug, Default)]
struct Rows {
    /// One row per node with that DOF, over the beam's own coordinates.
    shapes: DMatrix<f64>,
    /// Each row's static correction over the load coefficients (empty: a full basis).
    correction: Vec<[f64; LOADS]>,
    /// The nodes' positions, m from the support.
    positions: Vec<f64>,
    /// The value the rows are evaluated above (the range's limit).
    limit: f64,
}

impl Rows {
    /// max_r |shapes[r, j]| per coordinate.
    fn bound(&self) -> Vec<f64> {
        self.shapes.column_iter().map(|c| c.amax()).collect()
    }

    /// max_r |correction[r][a]| per load.
    fn correction_bound(&self) -> [f64; LOADS] {
        std::array::from_fn(|a| self.correction.iter().map(|r| r[a].abs()).fold(0.0, f64::max))
    }

    /// Raises `peak` by the rows at `q` (the beam's coordinates) with the load coefficients `loads`,
    /// whose bound on every row's |value| is `bound` ([`BeamRows::bounds`]): the bound itself
    /// below the limit, else the exact largest row.
    fn observe(&self, bound: f64, q: &[f64], loads: Option<&[f64; LOADS]>, time: f64, peak: &mut RangePeak) {
        if self.positions.is_empty() {
            return;
        }
        if bound.is_nan() || bound < self.limit {
            // Below the limit: the bound is an upper bound of every row (NaN: carried as it is).
            peak.raise(bound, None, time);
            return;
        }
        let mut largest = (0.0, 0usize);
        for r in 0..self.positions.len() {
            let mut value: f64 = self.shapes.row(r).iter().zip(q).map(|(s, q)| s * q).sum();
            if let (Some(c), Some(row)) = (loads, self.correction.get(r)) {
                value += row.iter().zip(c).map(|(a, b)| a * b).sum::<f64>();
            }
            let value = value.abs();
            if value > largest.0 || value.is_nan() {
                largest = (value, r);
            }
        }
        peak.raise(largest.0, Some(self.positions[largest.1]), time);
    }
}

/// One beam's rows and the coordinates they read.
#[derive(Clone, Debug, Default)]
struct BeamRows {
    coordinates: Range<usize>,
    deflection: Rows,
    rotation: Rows,
    /// The deflections' and the rotations' max_r |shapes[r, j]| per coordinate, side by side
    /// (one pass over the coordinates takes both bounds).
    bound: Vec<[f64; 2]>,
    /// Their max_r |correction[r][a]| per load.
    correction_bound: [[f64; 2]; LOADS],
}

impl BeamRows {
    fn new(coordinates: Range<usize>, deflection: Rows, rotation: Rows) -> BeamRows {
        let bound = deflection.bound().into_iter().zip(rotation.bound()).map(|(d, r)| [d, r]).collect();
        let (d, r) = (deflection.correction_bound(), rotation.correction_bound());
        let correction_bound = std::array::from_fn(|a| [d[a], r[a]]);
        BeamRows { coordinates, deflection, rotation, bound, correction_bound }
    }

    /// The deflections' and the rotations' bounds on every row's |value| at `q` (the beam's
    /// coordinates) with the load coefficients `loads`: sum_j max_r |phi_rj| |q_j| + sum_a max_r
    /// |R_ra| |c_a| (O(modes)). Each is the sum of its own terms in order, as a pass of its own
    /// would take it (from -0.0, as `Iterator::sum`).
    fn bounds(&self, q: &[f64], loads: Option<&[f64; LOADS]>) -> [f64; 2] {
        self.add_correction_bounds(coordinate_bounds(&self.bound, q), loads)
    }

    /// `bound` (the coordinates' terms) plus the load coefficients' `loads`, as
    /// [`Self::bounds`] adds them.
    fn add_correction_bounds(&self, mut bound: [f64; 2], loads: Option<&[f64; LOADS]>) -> [f64; 2] {
        if let Some(c) = loads {
            let mut correction = [-0.0; 2];
            for (b, c) in self.correction_bound.iter().zip(c) {
                let c = c.abs();
                correction = [correction[0] + b[0] * c, correction[1] + b[1] * c];
            }
            bound = [bound[0] + correction[0], bound[1] + correction[1]];
        }
        bound
    }
}

/// The coordinates' terms of [`BeamRows::bounds`]: sum_j bound_j |q_j| for the deflections and
/// the rotations side by side, each from -0.0 in order.
fn coordinate_bounds(bound: &[[f64; 2]], q: &[f64]) -> [f64; 2] {
    let mut sums = [-0.0; 2];
    for (b, q) in bound.iter().zip(q) {
        let q = q.abs();
        sums = [sums[0] + b[0] * q, sums[1] + b[1] * q];
    }
    sums
}

/// [`coordinate_bounds`] of both beams (`lower`, `ql`; `upper`, `qu`) at once, in the CPU's
/// widest vectors: their four sums side by side over the coordinates both beams have, then each
/// beam's own on; each sum's terms in the same order, to the bit.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn both_coordinate_bounds(lower: &[[f64; 2]], ql: &[f64], upper: &[[f64; 2]], qu: &[f64]) -> [[f64; 2]; 2] {
    let (n, m) = (lower.len().min(ql.len()), upper.len().min(qu.len()));
    let common = n.min(m);
    let mut sums = [-0.0f64; 4];
    for (((l, a), u), b) in lower[..common].iter().zip(&ql[..common]).zip(&upper[..common]).zip(&qu[..common]) {
        let (a, b) = (a.abs(), b.abs());
        let (bounds, weights) = ([l[0], l[1], u[0], u[1]], [a, a, b, b]);
        for i in 0..4 {
            sums[i] += bounds[i] * weights[i];
        }
    }
    let mut out = [[sums[0], sums[1]], [sums[2], sums[3]]];
    for (out, (bound, q)) in
        out.iter_mut().zip([(&lower[common..n], &ql[common..n]), (&upper[common..m], &qu[common..m])])
    {
        for (b, q) in bound.iter().zip(q) {
            let q = q.abs();
            *out = [out[0] + b[0] * q, out[1] + b[1] * q];
        }
    }
    out
}

/// Every node's deflection and rotation rows of both beams in the run's coordinates.
#[derive(Clone, Debug, Default)]
pub struct RangeRows {
    beams: [BeamRows; 2],
}

impl RangeRows {
    /// The rows of `model` in coordinates whose shapes are `total` (one row per physical DOF, the
    /// arrestor's then the bridge's; one column per coordinate, the arrestor's first, its
    /// `lower_coordinates` of them), with the discarded modes' rows `correction` (one per physical
    /// DOF, or none for a full basis). The deflections are read from `elastic`, the same shapes
    /// without the rigid-body motion (the bridge's pitching about its hinge, which
    /// [`SMALL_ROTATION`] bounds through the rotations: a rigid rotation of 0.12 rad swings a 29 m
    /// bridge's tip 3.5 m, 12 % of its length, and bends nothing).
    pub fn new(
        model: &Model,
        total: &DMatrix<f64>,
        elastic: &DMatrix<f64>,
        lower_coordinates: usize,
        correction: &[[f64; LOADS]],
    ) -> RangeRows {
        let coordinates = [0..lower_coordinates, lower_coordinates..total.ncols()];
        let offsets = [0, model.lower.dofs()];
        let lengths = [model.scenario.lower.length, model.scenario.upper.length];
        let beams = [&model.lower, &model.upper];
        let beam_rows = |b: usize| {
            let nodes = &beams[b].mesh.nodes;
            let range = coordinates[b].clone();
            let rows = |shapes: &DMatrix<f64>, dof: fn(&crate::model::mesh::Node) -> Option<usize>, limit: f64| {
                let picked: Vec<(usize, f64)> =
                    nodes.iter().filter_map(|n| dof(n).map(|i| (offsets[b] + i, n.x))).collect();
                let block = DMatrix::from_fn(picked.len(), range.len(), |r, c| shapes[(picked[r].0, range.start + c)]);
                let correction = if correction.is_empty() {
                    Vec::new()
                } else {
                    picked.iter().map(|(i, _)| correction[*i]).collect()
                };
                Rows { shapes: block, correction, positions: picked.iter().map(|p| p.1).collect(), limit }
            };
            BeamRows::new(
                range.clone(),
                rows(elastic, |n| n.w, SMALL_DEFLECTION * lengths[b]),
                rows(total, |n| n.theta, SMALL_ROTATION),
            )
        };
        RangeRows { beams: [beam_rows(0), beam_rows(1)] }
    }

    /// Raises `range` by the state `q` (own coordinates) with the correction's load coefficients
    /// `loads` (None: a full basis), at `time` s.
    pub fn observe(&self, q: &[f64], loads: Option<&[f64; LOADS]>, time: f64, range: &mut ModelRange) {
        let [lower, upper] = &self.beams;
        let coordinates = [lower, upper].map(|beam| q.get(beam.coordinates.clone()));
        // Both beams' bounds in one pass where both have coordinates (each its own sums).
        let bounds = match coordinates {
            [Some(ql), Some(qu)] => {
                let [l, u] = both_coordinate_bounds(&lower.bound, ql, &upper.bound, qu);
                [Some(lower.add_correction_bounds(l, loads)), Some(upper.add_correction_bounds(u, loads))]
            }
            _ => [0, 1].map(|b| coordinates[b].map(|q| self.beams[b].bounds(q, loads))),
        };
        for ((beam, (deflection, rotation)), (q, bounds)) in [lower, upper]
            .into_iter()
            .zip([
                (&mut range.lower_deflection, &mut range.lower_rotation),
                (&mut range.upper_deflection, &mut range.upper_rotation),
            ])
            .zip(coordinates.into_iter().zip(bounds))
        {
            let (Some(q), Some([deflection_bound, rotation_bound])) = (q, bounds) else { continue };
            beam.deflection.observe(deflection_bound, q, loads, time, deflection);
            beam.rotation.observe(rotation_bound, q, loads, time, rotation);
        }
    }
}

/// A beam's largest strain: its stress envelope's worst over E.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StrainPeak {
    /// sigma / E, or sqrt(3) tau / E where the shear's is larger.
    pub value: f64,
    /// The stress it comes from, Pa (sigma, or sqrt(3) tau).
    pub stress: f64,
    /// Where, m from the beam's support.
    pub position: f64,
    /// When, s.
    pub time: f64,
    /// True when the shear's equivalent is the larger.
    pub shear: bool,
}

/// The model's range of a run (issue 40): every node's largest deflection and rotation, and each
/// beam's largest strain, with the check against the linear model's limits.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RangeCheck {
    /// Deflections and rotations.
    pub range: ModelRange,
    /// The arrestor's largest strain (null: a rigid support, no stress).
    pub lower_strain: Option<StrainPeak>,
    /// The bridge's.
    pub upper_strain: Option<StrainPeak>,
    /// The beams' lengths, m (arrestor, bridge).
    pub lengths: [f64; 2],
}

impl RangeCheck {
    /// The worst quantity's fraction of its limit (1: at the limit; NaN when a value is NaN).
    pub fn worst_ratio(&self) -> f64 {
        let r = &self.range;
        let ratios = [
            r.lower_deflection.value / (SMALL_DEFLECTION * self.lengths[0]),
            r.upper_deflection.value / (SMALL_DEFLECTION * self.lengths[1]),
            r.lower_rotation.value / SMALL_ROTATION,
            r.upper_rotation.value / SMALL_ROTATION,
            self.lower_strain.map_or(0.0, |p| p.value / ELASTIC_STRAIN),
            self.upper_strain.map_or(0.0, |p| p.value / ELASTIC_STRAIN),
        ];
        if ratios.iter().any(|r| r.is_nan()) {
            return f64::NAN;
        }
        ratios.into_iter().fold(0.0, f64::max)
    }

    /// One line per quantity beyond its limit, naming the beam, the value, where and when.
    pub fn reasons(&self) -> Vec<String> {
        let r = &self.range;
        let mut reasons = Vec::new();
        // Positions are from the arrestor's first support, a clamp or a pin (issue 45), and from
        // the bridge's hinge; a rigid impactor has no range of its own to report.
        let beams = [("the arrestor", "first support"), ("the bridge", "hinge")];
        let at = |position: Option<f64>, support: &str, time: f64| match position {
            Some(x) => format!(" at {x:.3} m from its {support} (t = {time:.4} s)"),
            None => format!(" (t = {time:.4} s)"),
        };
        let beyond = |value: f64, limit: f64| value.is_nan() || value > limit;
        for (b, deflection, rotation) in
            [(0, r.lower_deflection, r.lower_rotation), (1, r.upper_deflection, r.upper_rotation)]
        {
            let (name, support) = beams[b];
            let length = self.lengths[b];
            if beyond(deflection.value, SMALL_DEFLECTION * length) {
                reasons.push(format!(
                    "small deflection: {name} deflects {:.4} m{}, {:.1} % of its {length} m length, beyond the \
                     linear beam model's small-deflection range ({} % of the length; a smaller impact or a stiffer \
                     beam stays in it)",
                    deflection.value,
                    at(deflection.position, support, deflection.time),
                    100.0 * deflection.value / length,
                    100.0 * SMALL_DEFLECTION
                ));
            }
            if beyond(rotation.value, SMALL_ROTATION) {
                reasons.push(format!(
                    "small rotation: {name} rotates {:.4} rad{}, beyond the linear beam model's small-rotation \
                     range ({SMALL_ROTATION} rad)",
                    rotation.value,
                    at(rotation.position, support, rotation.time)
                ));
            }
        }
        for (b, strain) in [(0, self.lower_strain), (1, self.upper_strain)] {
            let Some(p) = strain else { continue };
            if beyond(p.value, ELASTIC_STRAIN) {
                let (name, support) = beams[b];
                let stress = if p.shear {
                    format!("sqrt(3) tau = {:.1} MPa", p.stress * 1e-6)
                } else {
                    format!("sigma = {:.1} MPa", p.stress * 1e-6)
                };
                reasons.push(format!(
                    "elastic strain: {name}'s strain reaches {:.2} % ({stress} over E){}, beyond the \
                     linear-elastic range of any structural material ({} %)",
                    100.0 * p.value,
                    at(Some(p.position), support, p.time),
                    100.0 * ELASTIC_STRAIN
                ));
            }
        }
        reasons
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::sea::components::SplitMix64;

    /// `rows` observed as the range observes them: their bound from a beam's pass.
    fn observe(rows: &Rows, q: &[f64], loads: Option<&[f64; LOADS]>, time: f64, peak: &mut RangePeak) {
        let beam = BeamRows::new(0..q.len(), rows.clone(), rows.clone());
        let [bound, _] = beam.bounds(q, loads);
        rows.observe(bound, q, loads, time, peak);
    }

    /// A beam's one pass gives each block's bound to the bit of that block's own sums
    /// (sum_j b_j |q_j|, plus sum_a R_a |c_a|), on random shapes, coordinates and loads.
    #[test]
    fn one_pass_bounds_are_each_blocks_own_sums_to_the_bit() {
        let mut rng = SplitMix64::new(43);
        let mut random = |scale: f64| (rng.next_f64() - 0.5) * scale;
        for (nodes, coordinates) in [(1, 1), (7, 13), (31, 64), (12, 3)] {
            let mut block = || Rows {
                shapes: DMatrix::from_fn(nodes, coordinates, |_, _| random(2.0)),
                correction: (0..nodes).map(|_| std::array::from_fn(|_| random(1e-3))).collect(),
                positions: vec![0.0; nodes],
                limit: 1.0,
            };
            let (deflection, rotation) = (block(), block());
            let q: Vec<f64> = (0..coordinates).map(|_| random(1e-2)).collect();
            let loads: [f64; LOADS] = std::array::from_fn(|_| random(1e4));
            let beam = BeamRows::new(0..coordinates, deflection.clone(), rotation.clone());
            for loads in [None, Some(&loads)] {
                let bounds = beam.bounds(&q, loads);
                for (rows, bound) in [(&deflection, bounds[0]), (&rotation, bounds[1])] {
                    let mut own: f64 = rows.bound().iter().zip(&q).map(|(b, q)| b * q.abs()).sum();
                    if let Some(c) = loads {
                        own += rows.correction_bound().iter().zip(c).map(|(b, c)| b * c.abs()).sum::<f64>();
                    }
                    assert_eq!(bound.to_bits(), own.to_bits(), "{nodes} x {coordinates}");
                }
            }
        }
    }

    /// Both beams' bounds in one pass ([`both_coordinate_bounds`]) are each beam's own
    /// ([`coordinate_bounds`]) to the bit, on random bounds and coordinates, with the arrestor's
    /// coordinates fewer, as many and more than the bridge's (and none).
    #[test]
    fn both_beams_bounds_in_one_pass_are_each_beams_own_to_the_bit() {
        let mut rng = SplitMix64::new(44);
        let mut random = |scale: f64| (rng.next_f64() - 0.5) * scale;
        for (n, m) in [(0, 5), (1, 1), (13, 40), (40, 40), (41, 9), (3, 0)] {
            let lower: Vec<[f64; 2]> = (0..n).map(|_| [random(2.0).abs(), random(2.0).abs()]).collect();
            let upper: Vec<[f64; 2]> = (0..m).map(|_| [random(2.0).abs(), random(2.0).abs()]).collect();
            let ql: Vec<f64> = (0..n).map(|_| random(1e-2)).collect();
            let qu: Vec<f64> = (0..m).map(|_| random(1e-2)).collect();
            let both = both_coordinate_bounds(&lower, &ql, &upper, &qu);
            let own = [coordinate_bounds(&lower, &ql), coordinate_bounds(&upper, &qu)];
            assert_eq!(both.map(|b| b.map(f64::to_bits)), own.map(|b| b.map(f64::to_bits)), "{n} and {m}");
        }
    }

    /// The arrestor's positions are from its first support, a clamp or a pin (issue 45): a
    /// deflection of 1.2 m on a 6 m beam (20 %, beyond the 10 % limit) at midspan is reported "at
    /// 3.000 m from its first support", never "from its clamp"; a beam whose range stays zero
    /// (a rigid impactor's) is not named.
    #[test]
    fn reasons_place_the_arrestors_peaks_from_its_first_support() {
        let peak = |value: f64, position: Option<f64>| RangePeak { value, position, time: 0.01 };
        let check = RangeCheck {
            range: ModelRange {
                lower_deflection: peak(1.2, Some(3.0)),
                upper_deflection: peak(0.0, None),
                lower_rotation: peak(0.0, None),
                upper_rotation: peak(0.0, None),
            },
            lower_strain: None,
            upper_strain: None,
            lengths: [6.0, 29.0],
        };
        let reasons = check.reasons();
        assert_eq!(reasons.len(), 1, "{reasons:?}");
        assert!(reasons[0].contains("the arrestor deflects 1.2000 m at 3.000 m from its first support"), "{reasons:?}");
        assert!(!reasons[0].contains("clamp") && !reasons[0].contains("bridge"), "{reasons:?}");
    }

    /// A row block whose bound is below the limit reports the bound (an upper bound of every
    /// row's value), and one whose bound reaches it reports the exact largest row and where.
    #[test]
    fn rows_report_the_bound_below_the_limit_and_the_exact_value_above() {
        // Two rows over two coordinates: values 0.5 q0 + 0.25 q1 and -q0 + 0.5 q1.
        let shapes = DMatrix::from_row_slice(2, 2, &[0.5, 0.25, -1.0, 0.5]);
        let rows = Rows { shapes, correction: Vec::new(), positions: vec![1.0, 2.0], limit: 1.0 };
        let mut peak = RangePeak::default();
        observe(&rows, &[0.2, 0.4], None, 0.5, &mut peak);
        // Bound: 1.0 * 0.2 + 0.5 * 0.4 = 0.4 (< 1): the bound, no position.
        assert_eq!(peak, RangePeak { value: 0.4, position: None, time: 0.5 });
        observe(&rows, &[1.0, -1.0], None, 0.75, &mut peak);
        // Bound 1.5 >= 1: exact rows 0.25 and 1.5 (at x = 2).
        assert_eq!(peak, RangePeak { value: 1.5, position: Some(2.0), time: 0.75 });
        // A smaller later value leaves the peak.
        observe(&rows, &[0.1, 0.0], None, 1.0, &mut peak);
        assert_eq!(peak.time, 0.75);
    }

    /// The correction's rows add to the exact values and to the bound.
    #[test]
    fn the_static_correction_counts_in_the_bound_and_the_values() {
        let shapes = DMatrix::from_row_slice(1, 1, &[1.0]);
        let mut row = [0.0; LOADS];
        row[3] = 2.0;
        let rows = Rows { shapes, correction: vec![row], positions: vec![3.0], limit: 1.0 };
        let mut loads = [0.0; LOADS];
        loads[3] = -0.5;
        let mut peak = RangePeak::default();
        // 0.9 - 1.0 = -0.1 exactly, bound 0.9 + 1.0 = 1.9 >= 1: the exact |value| 0.1.
        observe(&rows, &[0.9], Some(&loads), 0.1, &mut peak);
        assert!((peak.value - 0.1).abs() < 1e-15 && peak.position == Some(3.0), "{peak:?}");
    }
}

//! How the struck beam (the arrestor, `[lower]`) is held at its two ends (issue 45, item 2):
//! the paper's cantilever (`"clamped-free"`, the default), or a beam on two supports such as a
//! deck beam (`"pinned-pinned"`, `"clamped-clamped"`, `"clamped-pinned"`; the first named end
//! is at x = 0). The natural frequencies of each condition, lambda_i L of Blevins, *Formulas for
//! Natural Frequency and Mode Shape* (1979), Table 8-1, are [`Supports::blevins_lambda`].

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use super::mesh::{FarEnd, Support};
use super::section::Segment;

/// The struck beam's supports, first end (x = 0) then far end (x = `lower.length`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Supports {
    /// Clamped at x = 0, free at the far end: the paper's arrestor (the default).
    #[default]
    ClampedFree,
    /// Pinned (simply supported) at both ends.
    PinnedPinned,
    /// Clamped at both ends.
    ClampedClamped,
    /// Clamped at x = 0, pinned at the far end.
    ClampedPinned,
}

/// The names of [`Supports`] in the scenario file, by FMU index.
pub const SUPPORTS_NAMES: [&str; 4] = ["clamped-free", "pinned-pinned", "clamped-clamped", "clamped-pinned"];

impl Supports {
    /// The FMU's Integer parameter: 0 clamped-free, 1 pinned-pinned, 2 clamped-clamped, 3 clamped-pinned.
    pub fn index(self) -> u32 {
        match self {
            Supports::ClampedFree => 0,
            Supports::PinnedPinned => 1,
            Supports::ClampedClamped => 2,
            Supports::ClampedPinned => 3,
        }
    }

    /// From the FMU's Integer parameter; `None` outside 0..=3.
    pub fn from_index(value: f64) -> Option<Supports> {
        match value {
            0.0 => Some(Supports::ClampedFree),
            1.0 => Some(Supports::PinnedPinned),
            2.0 => Some(Supports::ClampedClamped),
            3.0 => Some(Supports::ClampedPinned),
            _ => None,
        }
    }

    /// The name as the scenario file writes it.
    pub fn name(self) -> &'static str {
        SUPPORTS_NAMES[self.index() as usize]
    }

    /// True for the default (skipped when a scenario is written).
    pub fn is_clamped_free(&self) -> bool {
        *self == Supports::ClampedFree
    }

    /// True when the far end is supported too (a beam on two supports).
    pub fn has_far_support(self) -> bool {
        self != Supports::ClampedFree
    }

    /// How the first end (x = 0) is held.
    pub fn first(self) -> Support {
        match self {
            Supports::PinnedPinned => Support::Hinged,
            _ => Support::Clamped,
        }
    }

    /// How the far end (x = `lower.length`) is held.
    pub fn far(self) -> FarEnd {
        match self {
            Supports::ClampedFree => FarEnd::Free,
            Supports::PinnedPinned | Supports::ClampedPinned => FarEnd::Pinned,
            Supports::ClampedClamped => FarEnd::Clamped,
        }
    }

    /// True when the first end resists rotation (a clamp: its moment reaction is not zero).
    pub fn first_is_clamped(self) -> bool {
        self.first() == Support::Clamped
    }

    /// True when the far end resists rotation.
    pub fn far_is_clamped(self) -> bool {
        self.far() == FarEnd::Clamped
    }

    /// The first four lambda_i L of the uniform Euler-Bernoulli beam with these supports, from
    /// Blevins (1979), Table 8-1: omega_i = (lambda_i L)^2 / L^2 sqrt(E I / m), m the mass per
    /// length. Pinned-pinned: i pi; clamped-clamped and clamped-pinned: the roots of
    /// cos cosh = 1 and tan = tanh; clamped-free: cos cosh = -1.
    pub fn blevins_lambda(self) -> [f64; 4] {
        match self {
            Supports::ClampedFree => [1.87510407, 4.69409113, 7.85475744, 10.99554073],
            Supports::PinnedPinned => [PI, 2.0 * PI, 3.0 * PI, 4.0 * PI],
            Supports::ClampedClamped => [4.73004074, 7.85320462, 10.99560784, 14.13716549],
            Supports::ClampedPinned => [3.92660231, 7.06858275, 10.21017612, 13.35176878],
        }
    }
}

/// A uniform beam's static response to a unit point load at `a` (m from the first support), per
/// newton: what the energy method and the crane-style psi take as the struck beam's spring and
/// the first support's reactions, and the closed forms the tests hold the finite elements to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLoad {
    /// Deflection under the load per unit load, m/N.
    pub flexibility: f64,
    /// |Bending moment| at the first support per unit load, m (0 at a pin).
    pub first_moment: f64,
    /// |Shear force| at the first support per unit load (its force reaction's share).
    pub first_shear: f64,
}

impl Supports {
    /// The closed forms of Roark's *Formulas for Stress and Strain* (7th ed., Table 8.1, cases
    /// 1a, 1e, 1c and 1d) for a point load at `a` on a uniform beam of `length` L and bending
    /// stiffness `ei`, b = L - a: clamped-free a^3 / 3EI, moment a, shear 1; pinned-pinned
    /// a^2 b^2 / 3EIL, moment 0, shear b / L; clamped-clamped a^3 b^3 / 3EIL^3, moment a b^2 / L^2,
    /// shear b^2 (3a + b) / L^3; clamped-pinned a^3 b^2 (3L + b) / 12EIL^3, moment
    /// a b (L + b) / 2L^2, shear b (3L^2 - b^2) / 2L^3.
    pub fn point_load(self, ei: f64, length: f64, a: f64) -> PointLoad {
        let l = length;
        let b = l - a;
        let (flexibility, first_moment, first_shear) = match self {
            Supports::ClampedFree => (a.powi(3) / (3.0 * ei), a, 1.0),
            Supports::PinnedPinned => (a * a * b * b / (3.0 * ei * l), 0.0, b / l),
            Supports::ClampedClamped => {
                (a.powi(3) * b.powi(3) / (3.0 * ei * l.powi(3)), a * b * b / (l * l), b * b * (3.0 * a + b) / l.powi(3))
            }
            Supports::ClampedPinned => (
                a.powi(3) * b * b * (3.0 * l + b) / (12.0 * ei * l.powi(3)),
                a * b * (l + b) / (2.0 * l * l),
                b * (3.0 * l * l - b * b) / (2.0 * l.powi(3)),
            ),
        };
        PointLoad { flexibility, first_moment, first_shear }
    }
}

impl Supports {
    /// The static response to a unit point load at `a` (m from the first support) of a beam of
    /// piecewise-uniform `segments` (each with its own E I) on these supports: [`PointLoad`] for
    /// a beam of sections, where Roark's uniform closed forms ([`Self::point_load`]) do not hold.
    ///
    /// A static finite-element solve with Euler-Bernoulli cubic (Hermite) elements, one per
    /// piece between the sections' joints and the load point: their shape functions are the
    /// exact solutions of E I w'''' = 0 between point loads on a uniform piece, so the nodal
    /// deflections, and with them the flexibility and the first support's end forces, are exact
    /// (to round-off) for every support condition, the redundants of the indeterminate ones
    /// included (Przemieniecki, *Theory of Matrix Structural Analysis*, 1968, Sec. 5.4). Degenerate
    /// input (no segment, `a` off the beam, a mechanism) gives NaN, never a panic.
    pub fn stepped_point_load(self, segments: &[Segment], a: f64) -> PointLoad {
        let nan = PointLoad { flexibility: f64::NAN, first_moment: f64::NAN, first_shear: f64::NAN };
        let Some(length) = segments.last().map(|g| g.end) else { return nan };
        if !(a > 0.0 && a <= length && length.is_finite()) {
            return nan;
        }
        // Nodes: the ends, every joint and the load point, in order, without repeats.
        let mut nodes: Vec<f64> = segments.iter().flat_map(|g| [g.start, g.end]).chain([0.0, a]).collect();
        nodes.sort_by(f64::total_cmp);
        nodes.dedup_by(|x, y| (*x - *y).abs() <= 1e-12 * length);
        let n = nodes.len();
        let dofs = 2 * n;
        let mut k = nalgebra::DMatrix::<f64>::zeros(dofs, dofs);
        let ei_at =
            |x: f64| segments.iter().find(|g| x >= g.start && x <= g.end).map_or(f64::NAN, |g| g.bending_stiffness);
        let element = |e: usize| {
            let l = nodes[e + 1] - nodes[e];
            let c = ei_at(0.5 * (nodes[e] + nodes[e + 1])) / l.powi(3);
            let l2 = l * l;
            nalgebra::Matrix4::new(
                12.0,
                6.0 * l,
                -12.0,
                6.0 * l,
                6.0 * l,
                4.0 * l2,
                -6.0 * l,
                2.0 * l2,
                -12.0,
                -6.0 * l,
                12.0,
                -6.0 * l,
                6.0 * l,
                2.0 * l2,
                -6.0 * l,
                4.0 * l2,
            ) * c
        };
        for e in 0..n - 1 {
            let ke = element(e);
            for r in 0..4 {
                for c in 0..4 {
                    k[(2 * e + r, 2 * e + c)] += ke[(r, c)];
                }
            }
        }
        // The supports' constraints: w = 0 at a held end, theta = 0 at a clamped one.
        let mut held = vec![0];
        if self.first_is_clamped() {
            held.push(1);
        }
        match self.far() {
            FarEnd::Free => {}
            FarEnd::Pinned => held.push(dofs - 2),
            FarEnd::Clamped => held.extend([dofs - 2, dofs - 1]),
        }
        let free: Vec<usize> = (0..dofs).filter(|d| !held.contains(d)).collect();
        let Some(load_node) = nodes.iter().position(|x| (x - a).abs() <= 1e-12 * length) else { return nan };
        let kff = k.select_rows(&free).select_columns(&free);
        let mut f = nalgebra::DVector::<f64>::zeros(free.len());
        if let Some(i) = free.iter().position(|&d| d == 2 * load_node) {
            f[i] = 1.0;
        }
        let Some(solution) = kff.lu().solve(&f) else { return nan };
        let mut u = nalgebra::DVector::<f64>::zeros(dofs);
        for (i, &d) in free.iter().enumerate() {
            u[d] = solution[i];
        }
        // The first element's end forces k_e u_e at x = 0: its shear and moment there.
        let ends = element(0) * nalgebra::Vector4::new(u[0], u[1], u[2], u[3]);
        // A pin carries no moment by construction (its end force is the solve's round-off).
        let first_moment = if self.first_is_clamped() { ends[1].abs() } else { 0.0 };
        PointLoad { flexibility: u[2 * load_node], first_moment, first_shear: ends[0].abs() }
    }
}

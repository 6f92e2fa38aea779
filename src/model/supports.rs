//! How the struck beam (the arrestor, `[lower]`) is held at its two ends (issue 45, item 2):
//! the paper's cantilever (`"clamped-free"`, the default), or a beam on two supports such as a
//! deck beam (`"pinned-pinned"`, `"clamped-clamped"`, `"clamped-pinned"`; the first named end
//! is at x = 0). The natural frequencies of each condition, lambda_i L of Blevins, *Formulas for
//! Natural Frequency and Mode Shape* (1979), Table 8-1, are [`Supports::blevins_lambda`].

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use super::mesh::{FarEnd, Support};

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

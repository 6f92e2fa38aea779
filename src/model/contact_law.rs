//! Contact laws beyond the paper's linear bar (issue 28): a power law F = k delta^n (Hertz:
//! n = 3/2) with Hunt and Crossley's damping F = k delta^n (1 + c delta'), for the elastomer
//! buffers and steel-on-steel contacts an arrestor's designer states. delta > 0 is the
//! compression (the penetration beyond the clearance), delta' its rate; the force never pulls.

use serde::{Deserialize, Serialize};

/// The law's kind, `[contact] law`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LawKind {
    /// The paper's bar, F = k delta (the default).
    #[default]
    Linear,
    /// F = k delta^n, n = `exponent`.
    Power,
}

impl LawKind {
    /// The FMU's Integer parameter: 0 linear, 1 power.
    pub fn index(self) -> u32 {
        match self {
            LawKind::Linear => 0,
            LawKind::Power => 1,
        }
    }

    /// From the FMU's Integer parameter; `None` outside 0..=1.
    pub fn from_index(value: f64) -> Option<LawKind> {
        match value {
            0.0 => Some(LawKind::Linear),
            1.0 => Some(LawKind::Power),
            _ => None,
        }
    }

    /// True for the default (serde leaves it out of a scenario file).
    pub fn is_linear(&self) -> bool {
        *self == LawKind::Linear
    }
}

/// Smallest and largest exponent n supported: 1 (linear) to 3 (beyond, the law's tangent
/// stiffness rises so steeply that the automatic steps would need the peak compression far
/// ahead; elastomers fit 1-2.5, Hertz is 1.5).
pub const EXPONENT_RANGE: (f64, f64) = (1.0, 3.0);

/// A contact law that the stepper solves as a scalar equation each step (a power law, or any
/// law with Hunt-Crossley damping): the compression force P >= 0, N.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactLaw {
    /// k, N/m^n.
    pub stiffness: f64,
    /// n, 1 to 3.
    pub exponent: f64,
    /// Hunt-Crossley c, s/m.
    pub damping: f64,
}

impl ContactLaw {
    /// The elastic part k delta^n, N (0 without compression).
    pub fn elastic(&self, delta: f64) -> f64 {
        if delta > 0.0 {
            self.stiffness * libm::pow(delta, self.exponent)
        } else {
            0.0
        }
    }

    /// The compression force P = max(0, k delta^n (1 + c delta')), N.
    pub fn force(&self, delta: f64, rate: f64) -> f64 {
        (self.elastic(delta) * (1.0 + self.damping * rate)).max(0.0)
    }

    /// The energy stored at compression `delta`, k delta^(n+1) / (n + 1), J.
    pub fn energy(&self, delta: f64) -> f64 {
        if delta > 0.0 {
            self.elastic(delta) * delta / (self.exponent + 1.0)
        } else {
            0.0
        }
    }

    /// The power the damping dissipates, (P - k delta^n) delta', W (>= 0).
    pub fn dissipation_rate(&self, delta: f64, rate: f64) -> f64 {
        (self.force(delta, rate) - self.elastic(delta)) * rate
    }

    /// The step-end force of the implicit step: the P >= 0 with P = force(delta_0 - a P,
    /// rate_0 - r P), where the step's end compression and its rate fall by `a` (m/N) and `r`
    /// (m/s/N) per newton of contact force (the linear acceleration method's b^T S^-1 b terms).
    /// h(P) = P - force(...) rises monotonically from h(0) <= 0, so the root is unique in
    /// [0, force(delta_0, rate_0)]; Newton's steps inside that bracket, bisection where one
    /// leaves it, to the last bit.
    pub fn solve(&self, delta_0: f64, a: f64, rate_0: f64, r: f64) -> f64 {
        let at = |p: f64| (delta_0 - a * p, rate_0 - r * p);
        let upper = {
            let (d, v) = at(0.0);
            self.force(d, v)
        };
        if upper <= 0.0 || !upper.is_finite() {
            return if upper.is_finite() { 0.0 } else { upper };
        }
        let (mut lo, mut hi) = (0.0, upper);
        let mut p = upper;
        for _ in 0..200 {
            let (d, v) = at(p);
            // One power per iteration: the force and its slope from the elastic part.
            let e = self.elastic(d);
            let force = (e * (1.0 + self.damping * v)).max(0.0);
            let h = p - force;
            if h > 0.0 {
                hi = p;
            } else if h < 0.0 {
                lo = p;
            } else {
                return p;
            }
            // dh/dP = 1 + a dF/ddelta + r dF/drate (where the force is positive).
            let slope = if d > 0.0 && force > 0.0 {
                1.0 + a * self.exponent * e / d * (1.0 + self.damping * v) + r * e * self.damping
            } else {
                1.0
            };
            let newton = p - h / slope;
            let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
            if next == p || hi - lo <= f64::EPSILON * hi {
                return next;
            }
            p = next;
        }
        p
    }

    /// The largest tangent stiffness n k delta^(n-1) the contact can reach when `energy` J is
    /// stored in it at most, N/m: what the automatic contact step is chosen for (the linear
    /// acceleration method is stable up to omega dt = 2 sqrt(3), and the steps hold omega dt <= 1,
    /// so a compression beyond this estimate by a factor 12^(1/(n-1)) is still stable).
    pub fn tangent_stiffness(&self, energy: f64) -> f64 {
        let n = self.exponent;
        let delta = libm::pow((n + 1.0) * energy.max(0.0) / self.stiffness, 1.0 / (n + 1.0));
        (n * self.stiffness * libm::pow(delta, n - 1.0)).max(self.stiffness * 1e-12)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_implicit_force_solves_its_equation_to_round_off() {
        let law = ContactLaw { stiffness: 1e9, exponent: 1.5, damping: 0.4 };
        for (d0, a, v0, r) in [(1e-3, 1e-9, 0.5, 1e-6), (2e-4, 5e-8, -0.3, 2e-5), (1e-5, 0.0, 0.0, 0.0)] {
            let p = law.solve(d0, a, v0, r);
            let back = law.force(d0 - a * p, v0 - r * p);
            assert!((p - back).abs() <= 1e-12 * p.max(1.0), "{p} against {back}");
        }
        assert_eq!(law.solve(-1e-3, 1e-9, 1.0, 1e-6), 0.0, "no compression, no force");
        // A linear law without damping: P = k d0 / (1 + k a), the Sherman-Morrison form.
        let linear = ContactLaw { stiffness: 2.8e10, exponent: 1.0, damping: 0.0 };
        let p = linear.solve(1e-5, 3e-11, 0.0, 0.0);
        let exact = 2.8e10 * 1e-5 / (1.0 + 2.8e10 * 3e-11);
        assert!((p - exact).abs() <= 1e-13 * exact, "{p} against {exact}");
    }

    #[test]
    fn energy_is_the_integral_of_the_elastic_force() {
        // Trapezoid of k d^1.5 from 0 to 1e-3 m on 1e5 intervals against k d^2.5 / 2.5.
        let law = ContactLaw { stiffness: 3e9, exponent: 1.5, damping: 0.0 };
        let n = 100_000;
        let h = 1e-3 / n as f64;
        let integral: f64 =
            (0..n).map(|i| 0.5 * h * (law.elastic(i as f64 * h) + law.elastic((i + 1) as f64 * h))).sum();
        assert!((integral - law.energy(1e-3)).abs() <= 1e-8 * law.energy(1e-3));
    }
}

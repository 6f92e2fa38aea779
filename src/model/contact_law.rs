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
    /// Hertz's sphere on a flat face (issue 45): F = k delta^(3/2) with k = 4/3 E* sqrt(R) from
    /// `upper.radius`, both bodies' moduli and Poisson's ratios (see [`hertz_stiffness`]).
    Hertz,
}

impl LawKind {
    /// The FMU's Integer parameter: 0 linear, 1 power, 2 hertz.
    pub fn index(self) -> u32 {
        match self {
            LawKind::Linear => 0,
            LawKind::Power => 1,
            LawKind::Hertz => 2,
        }
    }

    /// From the FMU's Integer parameter; `None` outside 0..=2.
    pub fn from_index(value: f64) -> Option<LawKind> {
        match value {
            0.0 => Some(LawKind::Linear),
            1.0 => Some(LawKind::Power),
            2.0 => Some(LawKind::Hertz),
            _ => None,
        }
    }

    /// True for the default (serde leaves it out of a scenario file).
    pub fn is_linear(&self) -> bool {
        *self == LawKind::Linear
    }
}

/// Hertz's constant of a sphere of radius `radius` (m) on a flat face, k = 4/3 E* sqrt(R),
/// N/m^1.5, with the contact modulus 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson, Contact
/// Mechanics, 1985, Eqs. 4.22-4.23: P = 4/3 E* R^(1/2) delta^(3/2)). `struck` is the struck
/// body's (E2, nu2), or `None` for a rigid one (its term vanishes).
pub fn hertz_stiffness(radius: f64, striker: (f64, f64), struck: Option<(f64, f64)>) -> f64 {
    4.0 / 3.0 * contact_modulus(striker, struck) * radius.sqrt()
}

/// The contact modulus E*, Pa: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson 1985, Eq. 4.22),
/// the second term left out for a rigid struck body (`None`).
pub fn contact_modulus(striker: (f64, f64), struck: Option<(f64, f64)>) -> f64 {
    let compliance = |(e, nu): (f64, f64)| (1.0 - nu * nu) / e;
    1.0 / (compliance(striker) + struck.map_or(0.0, compliance))
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
            self.stiffness * power(delta, self.exponent)
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
    /// leaves it, to round-off. [`Self::solve_in_series`] without a residual flexibility.
    pub fn solve(&self, delta_0: f64, a: f64, rate_0: f64, r: f64) -> f64 {
        self.solve_in_series(delta_0, a, rate_0, r, 0.0)
    }

    /// [`Self::solve`] for the law in series with a residual flexibility `f_r` (m/N, >= 0): the
    /// static response b^T R b of a truncated basis's discarded modes at the contact
    /// ([`crate::solver::truncation`]). The kept modes' compression D = `delta_0` - a P and its
    /// rate V = `rate_0` - r P split between the contact and the residual spring: the contact's
    /// own compression is x = D - f_r P, and its rate the quasi-static share
    /// x' = V / (1 + f_r n k x^(n-1)) (the residual spring follows the elastic force; the
    /// dropped term f_r k x^n c x'' is of relative order f_r c P / T_contact, below 1e-4 for
    /// the examples). With f_r = 0 this is the law itself. h(P) = P - force(x, x') is bracketed
    /// from h(0) <= 0 (the bracket widened if the damping's share makes h fall at its end).
    pub fn solve_in_series(&self, delta_0: f64, a: f64, rate_0: f64, r: f64, f_r: f64) -> f64 {
        self.series_root(delta_0, a, rate_0, r, f_r).0
    }

    /// The root of [`Self::solve_in_series`] and the law's terms at the contact's compression it
    /// gives (`None` where the root was not evaluated: no force, or a bisection's last midpoint).
    /// Newton's method starts from its first step from P = 0 (the linearised force
    /// F / (1 + (a + f_r) F_x + r F_V) at the start's compression, the Sherman-Morrison force of
    /// the law's tangent: the root itself for a linear law without damping) and stops when its
    /// correction is below 8 ulp of P (the law's x^n carries a few ulp of its own,
    /// [`power`]); the bracket [lo, hi] guards it, its upper end checked only when a step would
    /// pass it. Each evaluation costs one x^n.
    fn series_root(&self, delta_0: f64, a: f64, rate_0: f64, r: f64, f_r: f64) -> (f64, Option<SeriesTerms>) {
        let a_total = a + f_r;
        let start = self.series_terms(delta_0, rate_0, f_r);
        let upper = start.force;
        if upper <= 0.0 || !upper.is_finite() {
            return (if upper.is_finite() { 0.0 } else { upper }, None);
        }
        let h = |p: f64| {
            let t = self.series_terms(delta_0 - a_total * p, rate_0 - r * p, f_r);
            (p - t.force, t)
        };
        let (mut lo, mut hi) = (0.0, upper);
        // h(upper) >= 0 holds without a residual flexibility or without damping; with both the
        // damping's share can make h dip past the elastic bound (by O(f_r^2)): checked, and the
        // bracket widened until h(hi) >= 0, only when Newton's method would step past it.
        let mut hi_checked = false;
        let first = 1.0 + a_total * start.by_compression + r * start.by_rate;
        let mut p = if first.is_finite() && first >= 1.0 { upper / first } else { upper };
        for _ in 0..200 {
            let (value, t) = h(p);
            if value > 0.0 {
                hi = p;
                hi_checked = true;
            } else if value < 0.0 {
                lo = p;
            } else {
                return (p, Some(t));
            }
            // dh/dP = 1 + (a + f_r) dF/dx + r dF/dV (where the force is positive).
            let slope = if t.force > 0.0 { 1.0 + a_total * t.by_compression + r * t.by_rate } else { 1.0 };
            let correction = value / slope;
            if correction.abs() <= 8.0 * f64::EPSILON * p {
                return (p, Some(t));
            }
            let newton = p - correction;
            // Where h bends little over the correction (its curvature relative to its slope,
            // (n - 1) / (2n) (a + f_r) F_x / P at most, times the correction, below 1e-8 of the
            // correction's own size), the Newton step is the root to round-off: taken without a
            // further evaluation, the law's terms kept from P (their compression off by
            // (a + f_r) times the correction: below 1e-8 relative for in_series's f_r).
            if correction.abs() <= 1e-8 * p && slope <= 2.0 && newton > lo && newton < hi {
                return (newton, Some(t));
            }
            if newton >= hi && !hi_checked {
                let mut widen = 0;
                while h(hi).0 < 0.0 && widen < 60 {
                    lo = hi;
                    hi *= 2.0;
                    widen += 1;
                }
                hi_checked = true;
            }
            let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
            if next == p || hi - lo <= f64::EPSILON * hi {
                return (next, (next == p).then_some(t));
            }
            p = next;
        }
        (p, None)
    }

    /// The force and its partial derivatives at the contact's own compression x (m) under the
    /// kept modes' compression rate `rate` (m/s), in series with `f_r` (see
    /// [`Self::solve_in_series`]): one x^n. With e = k x^n, s = 1 + f_r e' (the rate's share) and
    /// phi = e / s the force is F = e + c V phi, so F_x = e' + c V phi', F_V = c phi,
    /// F_xx = e'' + c V phi'', F_xV = c phi', F_VV = 0 (e's derivatives from e: e' = n e / x,
    /// e'' = (n - 1) e' / x, e^(3) = (n - 2) e'' / x).
    fn series_terms(&self, x: f64, rate: f64, f_r: f64) -> SeriesTerms {
        if x <= 0.0 {
            return SeriesTerms::default();
        }
        let (n, c) = (self.exponent, self.damping);
        let e = self.elastic(x);
        // The elastic tangent n k x^(n-1) and its slopes.
        let tangent = n * e / x;
        let curvature = (n - 1.0) * tangent / x;
        let third = (n - 2.0) * curvature / x;
        let share = 1.0 + f_r * tangent;
        let own_rate = rate / share;
        let force = e * (1.0 + c * own_rate);
        if force <= 0.0 {
            return SeriesTerms::default();
        }
        let (s1, s2) = (f_r * curvature, f_r * third);
        let share2 = share * share;
        let phi1 = tangent / share - e * s1 / share2;
        let phi2 =
            curvature / share - 2.0 * tangent * s1 / share2 - e * s2 / share2 + 2.0 * e * s1 * s1 / (share2 * share);
        SeriesTerms {
            force,
            by_compression: tangent * (1.0 + c * own_rate) - e * c * rate * f_r * curvature / share2,
            by_rate: e * c / share,
            elastic: e,
            own_rate,
            by_compression2: curvature + c * rate * phi2,
            by_both: c * phi1,
            share,
            psi1: tangent / share2 - 2.0 * e * s1 / (share2 * share),
        }
    }

    /// The force P = G(D, V) of the law in series with `f_r` at the kept modes' compression `D`
    /// and rate `V` ([`Self::solve_in_series`] with a = r = 0), and its partial derivatives
    /// G_D = F_x / u, G_V = F_V / u with u = 1 + f_r F_x (from D - x - f_r P(x, V) = 0), and the
    /// second ones by differentiating these again (x_D = 1 / u, x_V = -f_r G_V):
    /// G_DD = F_xx / u^3, G_DV = (F_xx x_V + F_xV) / u^2,
    /// G_VV = (F_xV x_V u - F_V f_r (F_xx x_V + F_xV)) / u^2; the dissipation W = c V^2 psi(x)
    /// (psi = e / s^2) with W_D = c V^2 psi' x_D, W_V = 2 c V psi + c V^2 psi' x_V.
    pub fn in_series(&self, delta: f64, rate: f64, f_r: f64) -> SeriesForce {
        let (force, terms) = self.series_root(delta, 0.0, rate, 0.0, f_r);
        if force <= 0.0 {
            return SeriesForce::default();
        }
        let t = terms.unwrap_or_else(|| self.series_terms(delta - f_r * force, rate, f_r));
        let u = 1.0 + f_r * t.by_compression;
        let scale = 1.0 / u;
        let (by_compression, by_rate) = (t.by_compression * scale, t.by_rate * scale);
        let x_rate = -f_r * by_rate;
        let mixed = t.by_compression2 * x_rate + t.by_both;
        let c = self.damping;
        let psi = t.elastic / (t.share * t.share);
        SeriesForce {
            force,
            by_compression,
            by_rate,
            dissipation: (t.force - t.elastic) * t.own_rate,
            by_compression2: t.by_compression2 * scale * scale * scale,
            by_both: mixed * scale * scale,
            by_rate2: (t.by_both * x_rate * u - t.by_rate * f_r * mixed) * scale * scale,
            dissipation_by_compression: c * rate * rate * t.psi1 * scale,
            dissipation_by_rate: 2.0 * c * rate * psi + c * rate * rate * t.psi1 * x_rate,
        }
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

/// The law's force at the contact's own compression and its partial derivatives (private to
/// the solve).
#[derive(Clone, Copy, Debug, Default)]
struct SeriesTerms {
    force: f64,
    /// dP/dx at the kept modes' rate, N/m.
    by_compression: f64,
    /// dP/dV, N s/m.
    by_rate: f64,
    /// k x^n, N.
    elastic: f64,
    /// The contact's own rate x', m/s.
    own_rate: f64,
    /// d2P/dx2, N/m^2.
    by_compression2: f64,
    /// d2P/dx dV, N s/m^2.
    by_both: f64,
    /// The rate's share s = 1 + f_r n k x^(n-1).
    share: f64,
    /// d/dx (k x^n / s^2), N/m.
    psi1: f64,
}

/// x^n for x > 0 (m, the exponent 1 to 3): exact for n = 1, x sqrt(x) for n = 3/2 (Hertz), x^2,
/// x^2 sqrt(x) and x^3 for 2, 5/2 and 3 (each within 2 ulp), else exp(n ln x) (within
/// |n ln x| + 1 ulp: 2.7e-15 for n = 1.3 at 1e-7 to 4e-2 m; libm's exp and ln, the same bits on
/// every platform, 0.6 of libm's pow's time).
pub fn power(x: f64, n: f64) -> f64 {
    if n == 1.0 {
        x
    } else if n == 1.5 {
        x * x.sqrt()
    } else if n == 2.0 {
        x * x
    } else if n == 2.5 {
        x * x * x.sqrt()
    } else if n == 3.0 {
        x * x * x
    } else {
        libm::exp(n * libm::log(x))
    }
}

/// The contact force as a function of the kept modes' compression D and its rate V
/// ([`ContactLaw::in_series`]), with its partial derivatives (all 0 without force).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SeriesForce {
    /// P, N (>= 0).
    pub force: f64,
    /// dP/dD, N/m.
    pub by_compression: f64,
    /// dP/dV, N s/m.
    pub by_rate: f64,
    /// The power the damping dissipates, (P - k x^n) x' (x the contact's own compression, x' its
    /// quasi-static rate), W.
    pub dissipation: f64,
    /// d2P/dD2, N/m^2.
    pub by_compression2: f64,
    /// d2P/dD dV, N s/m^2.
    pub by_both: f64,
    /// d2P/dV2, N s^2/m^2.
    pub by_rate2: f64,
    /// dW/dD, W/m.
    pub dissipation_by_compression: f64,
    /// dW/dV, W s/m.
    pub dissipation_by_rate: f64,
}

impl SeriesForce {
    /// dP/dt from the rates of D and V, N/s.
    pub fn rate(&self, delta_rate: f64, rate_rate: f64) -> f64 {
        self.by_compression * delta_rate + self.by_rate * rate_rate
    }

    /// d2P/dt2 and dW/dt (the dissipation's rate) along a state whose compression D moves at
    /// `rate` V, V at -`acceleration` A and A at `jerk` J: G_DD V^2 - 2 G_DV V A + G_VV A^2 -
    /// G_D A - G_V J, and W_D V - W_V A.
    pub fn second_rates(&self, rate: f64, acceleration: f64, jerk: f64) -> (f64, f64) {
        let (v, a) = (rate, acceleration);
        let second = self.by_compression2 * v * v - 2.0 * self.by_both * v * a + self.by_rate2 * a * a
            - self.by_compression * a
            - self.by_rate * jerk;
        (second, self.dissipation_by_compression * v - self.dissipation_by_rate * a)
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

    /// [`power`] against libm's pow: exact for n = 1, within 2 ulp for the square-root and
    /// integer exponents (one rounding each of sqrt and of at most two products), and within
    /// 4e-15 for exp(n ln x) (ln x's rounding scaled by |n ln x| <= 3 x 16.2 at 1e-7 m: 1.1e-14 at
    /// worst; measured 2.7e-15 for n = 1.3), over compressions of 1e-7 to 1e-1 m.
    #[test]
    fn the_laws_power_is_libms_pow_to_round_off() {
        for n in [1.0, 1.5, 2.0, 2.5, 3.0, 1.3, 1.05, 2.9] {
            for i in 0..=600 {
                let x = 1e-7 * 10f64.powf(i as f64 / 100.0);
                let (ours, pow) = (power(x, n), libm::pow(x, n));
                let tolerance = if n == 1.0 {
                    0.0
                } else if n.fract() == 0.0 || n.fract() == 0.5 {
                    4.5e-16
                } else {
                    1.2e-14
                };
                assert!((ours - pow).abs() <= tolerance * pow, "{x}^{n}: {ours} against {pow}");
            }
        }
    }

    /// The series force's first and second partial derivatives and the dissipation's against
    /// central differences of [`ContactLaw::in_series`] over 1e-5 of D and of V: the differences'
    /// truncation error (h^2/6 of the third derivative, ~1e-10 relative here) and their round-off
    /// (1e-16 / 1e-5 of the values, ~1e-11 relative) within 1e-5 relative, for a Hertz law, the
    /// buffer's n = 1.3 with damping (opening and closing), a stiff residual flexibility, and
    /// n = 2.5 with damping alone.
    #[test]
    fn the_series_forces_derivatives_are_its_differences() {
        for (law, d, v, f_r) in [
            (ContactLaw { stiffness: 1e9, exponent: 1.5, damping: 0.0 }, 1e-3, 0.5, 2e-9),
            (ContactLaw { stiffness: 7.5e7, exponent: 1.3, damping: 0.2 }, 1.2e-2, -1.5, 4e-9),
            (ContactLaw { stiffness: 7.5e7, exponent: 1.3, damping: 0.2 }, 3e-3, 2.0, 1e-7),
            (ContactLaw { stiffness: 2e8, exponent: 2.5, damping: 0.4 }, 5e-3, 0.7, 0.0),
        ] {
            let g = law.in_series(d, v, f_r);
            let (hd, hv) = (1e-5 * d, 1e-5 * v.abs());
            let (gp, gm) = (law.in_series(d + hd, v, f_r), law.in_series(d - hd, v, f_r));
            let (vp, vm) = (law.in_series(d, v + hv, f_r), law.in_series(d, v - hv, f_r));
            let close = |analytic: f64, difference: f64, what: &str| {
                let scale = analytic.abs().max(difference.abs()).max(1e-300);
                assert!(
                    (analytic - difference).abs() <= 1e-5 * scale,
                    "{law:?} {what}: {analytic} against {difference}"
                );
            };
            close(g.by_compression, (gp.force - gm.force) / (2.0 * hd), "G_D");
            close(g.by_rate, (vp.force - vm.force) / (2.0 * hv), "G_V");
            close(g.by_compression2, (gp.by_compression - gm.by_compression) / (2.0 * hd), "G_DD");
            close(g.by_both, (vp.by_compression - vm.by_compression) / (2.0 * hv), "G_DV");
            close(g.by_both, (gp.by_rate - gm.by_rate) / (2.0 * hd), "G_VD");
            if law.damping > 0.0 && f_r > 0.0 {
                close(g.by_rate2, (vp.by_rate - vm.by_rate) / (2.0 * hv), "G_VV");
            }
            if law.damping > 0.0 {
                close(g.dissipation_by_compression, (gp.dissipation - gm.dissipation) / (2.0 * hd), "W_D");
                close(g.dissipation_by_rate, (vp.dissipation - vm.dissipation) / (2.0 * hv), "W_V");
            }
        }
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

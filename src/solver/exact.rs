//! Exact modal advance (issue 29): each modal coordinate of a stage is a damped oscillator
//! q'' + c q' + omega^2 q = f(t), and over one step the converged method's stepper takes f linear
//! in time (the loads and the contact bar's force at the step's two ends). For such a forcing the
//! oscillator's state at the step's end is a closed form, exact for any step, so the steps are set
//! by resolving the contact force and the peaks, not by the highest kept frequency (the linear
//! acceleration method of Eqs. (7)-(11) needs omega_max dt <= 1 for its phase and energy errors,
//! see [`super::step_plan`]).
//!
//! For one coordinate and a step h, with f(t) = f0 + r t:
//!
//! ```text
//! q(h)   = A q0 + B v0 + Gf f0 + Gr r
//! v(h)   = C q0 + D v0 + Hf f0 + Hr r
//! int q  = Ix q0 + Iv v0 + If f0 + Ir r      (over the step: the damping's exact work)
//! ```
//!
//! [`ModeStep::new`] gives the twelve coefficients: from the underdamped closed form
//! (sigma = c/2, omega_d = sqrt(omega^2 - sigma^2)) where omega h >= [`SERIES_BELOW`], else from the
//! Taylor series of the solution, whose derivatives follow from the equation itself
//! (q^(k+2) = f^(k) - c q^(k+1) - omega^2 q^(k)): the closed form's differences such as h - B
//! lose every digit as omega h -> 0 (a 1 ns step that locates a contact change; the bridge's rigid
//! mode, omega = 0), the series is exact there.

/// omega h below which the coefficients come from the Taylor series.
pub const SERIES_BELOW: f64 = 0.5;

/// The twelve coefficients of one coordinate for one step (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ModeStep {
    /// q(h) per q0, v0, f0, r.
    pub q: [f64; 4],
    /// v(h) per q0, v0, f0, r.
    pub v: [f64; 4],
    /// The integral of q over the step per q0, v0, f0, r.
    pub integral: [f64; 4],
}

impl ModeStep {
    /// The coefficients of q'' + `damping` q' + `omega2` q = f0 + r t over a step `h` > 0, s
    /// (`damping` < 2 omega: every mode of the model is underdamped, damping ratios < 1).
    pub fn new(omega2: f64, damping: f64, h: f64) -> ModeStep {
        let omega = libm::sqrt(omega2.max(0.0));
        if omega * h < SERIES_BELOW || omega2 <= 0.0 || damping >= 2.0 * omega {
            return Self::series(omega2, damping, h);
        }
        let (w2, c) = (omega2, damping);
        let sigma = 0.5 * c;
        let wd = libm::sqrt(w2 - sigma * sigma);
        let e = libm::exp(-sigma * h);
        let (sn, cs) = (libm::sin(wd * h), libm::cos(wd * h));
        let a = e * (cs + sigma / wd * sn);
        let b = e * sn / wd;
        let cc = -e * w2 / wd * sn;
        let d = e * (cs - sigma / wd * sn);
        let gf = (1.0 - a) / w2;
        let hf = -cc / w2;
        let gr = (a - 1.0) * c / (w2 * w2) + (h - b) / w2;
        let hr = cc * c / (w2 * w2) + (1.0 - d) / w2;
        // omega^2 int q = int f - (v(h) - v0) - c (q(h) - q0), from the equation.
        let ix = (-cc - c * (a - 1.0)) / w2;
        let iv = (1.0 - d - c * b) / w2;
        let i_f = (h - hf - c * gf) / w2;
        let ir = (0.5 * h * h - hr - c * gr) / w2;
        ModeStep { q: [a, b, gf, gr], v: [cc, d, hf, hr], integral: [ix, iv, i_f, ir] }
    }

    /// The coefficients from the Taylor series at t = 0, summed until its terms fall below 1e-17
    /// of the first (omega h < [`SERIES_BELOW`] or c h small: at most ~15 terms).
    fn series(omega2: f64, damping: f64, h: f64) -> ModeStep {
        // Derivatives q^(k), q^(k+1) of the four unit responses (q0, v0, f0, r), and the forcing's
        // derivatives f^(k) (f0: k = 0, r: k = 1).
        let mut d0 = [1.0, 0.0, 0.0, 0.0];
        let mut d1 = [0.0, 1.0, 0.0, 0.0];
        let mut out = ModeStep::default();
        let scale = libm::sqrt(omega2.abs()).max(damping.abs()) * h;
        let mut term = 1.0; // h^k / k!
        let mut bound = 1.0; // scale^(k+1) / (k+1)!
        for k in 0..64 {
            let forcing = |j: usize| match (j, k) {
                (2, 0) | (3, 1) => 1.0,
                _ => 0.0,
            };
            for j in 0..4 {
                out.q[j] += d0[j] * term;
                out.v[j] += d1[j] * term;
                out.integral[j] += d0[j] * term * h / (k as f64 + 1.0);
                let d2 = forcing(j) - damping * d1[j] - omega2 * d0[j];
                d0[j] = d1[j];
                d1[j] = d2;
            }
            term *= h / (k as f64 + 1.0);
            // The next terms are of order scale^(k+1) / (k+1)! of the first (the derivatives
            // grow by omega or c per order); the forcing's terms are in once k >= 3.
            // (A running product, not powi: every platform's binary must stop at the same term.)
            bound *= scale / (k as f64 + 1.0);
            if k >= 3 && bound < 1e-17 {
                break;
            }
        }
        out
    }

    /// q(h), v(h) and the integral of q from the start state and forcing f0 + r t.
    #[inline(always)]
    pub fn apply(&self, q0: f64, v0: f64, f0: f64, r: f64) -> (f64, f64, f64) {
        let dot = |c: &[f64; 4]| c[0] * q0 + c[1] * v0 + c[2] * f0 + c[3] * r;
        (dot(&self.q), dot(&self.v), dot(&self.integral))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The free undamped oscillator: q = q0 cos(wt) + v0/w sin(wt) (closed form).
    #[test]
    fn an_undamped_mode_turns_exactly_at_any_step() {
        for (w, h) in [(10.0, 0.01), (10.0, 1.0), (4e4, 1e-4), (4e4, 1e-9), (0.1, 1e-3)] {
            let s = ModeStep::new(w * w, 0.0, h);
            let (q, v, _) = s.apply(0.3, -2.0, 0.0, 0.0);
            let exact_q = 0.3 * (w * h).cos() - 2.0 / w * (w * h).sin();
            let exact_v = -0.3 * w * (w * h).sin() - 2.0 * (w * h).cos();
            // Round-off of a handful of operations on O(1) numbers: 1e-12 of the amplitude.
            let amplitude = (0.3f64.powi(2) + (2.0 / w).powi(2)).sqrt();
            assert!((q - exact_q).abs() < 1e-12 * amplitude, "w {w} h {h}: {q} vs {exact_q}");
            assert!((v - exact_v).abs() < 1e-12 * amplitude * w, "w {w} h {h}: {v} vs {exact_v}");
        }
    }

    /// The rigid mode (omega = 0, c = 0) under f0 + r t: q0 + v0 h + f0 h^2/2 + r h^3/6.
    #[test]
    fn the_rigid_mode_follows_the_polynomial() {
        for h in [1e-9, 1e-3, 2.0] {
            let s = ModeStep::new(0.0, 0.0, h);
            let (q, v, i) = s.apply(1.0, 2.0, 3.0, 4.0);
            let eq = 1.0 + 2.0 * h + 1.5 * h * h + 4.0 * h.powi(3) / 6.0;
            let ev = 2.0 + 3.0 * h + 2.0 * h * h;
            let ei = h + h * h + 0.5 * h.powi(3) + h.powi(4) / 6.0;
            assert!((q - eq).abs() < 1e-14 * eq.abs(), "{q} {eq}");
            assert!((v - ev).abs() < 1e-14 * ev.abs(), "{v} {ev}");
            assert!((i - ei).abs() < 1e-14 * ei.abs(), "{i} {ei}");
        }
    }

    /// A damped mode under a ramp: the closed form and the series agree where both apply
    /// (omega h = 0.5, the switch), and each satisfies the equation's integral identity
    /// omega^2 int q = int f - dv - c dq to round-off.
    #[test]
    fn closed_form_and_series_agree_at_the_switch_and_keep_the_identity() {
        let (w, zeta) = (200.0, 0.05);
        let (w2, c) = (w * w, 2.0 * zeta * w);
        let h = SERIES_BELOW / w;
        let closed = ModeStep::new(w2, c, h * (1.0 + 1e-12));
        let series = ModeStep::series(w2, c, h * (1.0 + 1e-12));
        for j in 0..4 {
            for (a, b) in
                [(closed.q[j], series.q[j]), (closed.v[j], series.v[j]), (closed.integral[j], series.integral[j])]
            {
                // The closed form's differences (h - B, 1 - A) lose ~(omega h)^2 / 12 of their
                // digits at the switch: 1e-11 relative is far above the loss.
                assert!((a - b).abs() <= 1e-11 * a.abs().max(b.abs()).max(1e-30), "j {j}: {a} vs {b}");
            }
        }
        for s in [closed, series] {
            let (q0, v0, f0, r) = (0.01, -0.5, 30.0, 1e4);
            let (q, v, i) = s.apply(q0, v0, f0, r);
            let hh = h * (1.0 + 1e-12);
            let lhs = w2 * i;
            let rhs = f0 * hh + 0.5 * r * hh * hh - (v - v0) - c * (q - q0);
            assert!((lhs - rhs).abs() < 1e-10 * (f0 * hh).abs(), "{lhs} vs {rhs}");
        }
    }

    /// The damped free decay against the textbook solution (Clough & Penzien, Eq. 2-46):
    /// q = e^(-zeta w t) (q0 cos wd t + (v0 + zeta w q0)/wd sin wd t).
    #[test]
    fn a_damped_mode_decays_as_the_textbook_solution() {
        let (w, zeta, h) = (50.0, 0.03, 0.7);
        let wd = w * (1.0f64 - zeta * zeta).sqrt();
        let s = ModeStep::new(w * w, 2.0 * zeta * w, h);
        let (q, _, _) = s.apply(1.0, 3.0, 0.0, 0.0);
        let exact = (-zeta * w * h).exp() * ((wd * h).cos() + (3.0 + zeta * w) / wd * (wd * h).sin());
        assert!((q - exact).abs() < 1e-13, "{q} vs {exact}");
    }
}

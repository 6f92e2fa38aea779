//! The largest |value| of an output over one internal step. The linear acceleration method's
//! displacement is a cubic in time within a step (Eq. 11 with a linear acceleration), and every
//! output is a linear functional of it, so each output is a cubic too: fixed by its values and
//! rates at the step's ends (Hermite), its maximum found where its derivative vanishes.

/// The Hermite cubic p(s) = p0 + d0 s + c2 s^2 + c3 s^3 on s in [0, 1] through p(0) = `p0`,
/// p(1) = `p1`, p'(0) = `d0`, p'(1) = `d1`: (c2, c3) = (3(p1 - p0) - 2 d0 - d1, 2(p0 - p1) + d0 + d1).
pub fn cubic_coefficients(p0: f64, p1: f64, d0: f64, d1: f64) -> (f64, f64) {
    (3.0 * (p1 - p0) - 2.0 * d0 - d1, 2.0 * (p0 - p1) + d0 + d1)
}

/// max |p(s)| over s in [0, `until`] (0 < until <= 1, a fraction of the step) of the cubic with
/// p(0) = `p0`, p(1) = `p1`, p'(0) = `d0`, p'(1) = `d1` (rates times the step length), and the
/// fraction of the step where it is reached.
pub fn cubic_extremum(p0: f64, p1: f64, d0: f64, d1: f64, until: f64) -> (f64, f64) {
    let (c2, c3) = cubic_coefficients(p0, p1, d0, d1);
    let value = |s: f64| p0 + s * (d0 + s * (c2 + s * c3));
    let mut best = (value(0.0).abs(), 0.0);
    let mut consider = |s: f64| {
        if s > 0.0 && s <= until {
            let v = value(s).abs();
            if v > best.0 {
                best = (v, s);
            }
        }
    };
    consider(until);
    // p'(s) = d0 + 2 c2 s + 3 c3 s^2 = 0.
    let (a, b, c) = (3.0 * c3, 2.0 * c2, d0);
    if a.abs() <= 1e-14 * (b.abs() + c.abs()) {
        if b != 0.0 {
            consider(-c / b);
        }
    } else {
        let discriminant = b * b - 4.0 * a * c;
        if discriminant >= 0.0 {
            // The numerically stable pair of roots.
            let q = -0.5 * (b + b.signum() * discriminant.sqrt());
            if q != 0.0 {
                consider(q / a);
                consider(c / q);
            }
        }
    }
    best
}

/// The largest force of a damped contact `law` over s in [0, `until`] of a step of `dt` s: the
/// cubic through the force's values and rates at the step's ends, from the gap's values, rates
/// (times the step: `p0`, `p1`, `d0`, `d1`) and accelerations (`a0`, `a1`, m/s^2) there:
/// P' = k n x^(n-1) x' (1 + c x') + k x^n c x'' with x = -gap. With damping the force crests
/// before the largest compression, inside a long step. Returns the force, N, and the fraction of
/// the step where it is reached.
pub fn law_force_extremum(
    law: &crate::model::contact_law::ContactLaw,
    (p0, p1, d0, d1): (f64, f64, f64, f64),
    (a0, a1): (f64, f64),
    dt: f64,
    until: f64,
) -> (f64, f64) {
    let end = |gap: f64, rate: f64, acceleration: f64| {
        let (x, v) = (-gap, -rate);
        let force = law.force(x, v);
        if force <= 0.0 || x <= 0.0 {
            return (force, 0.0);
        }
        let e = law.elastic(x);
        let rate = law.exponent * e / x * v * (1.0 + law.damping * v) - e * law.damping * acceleration;
        (force, rate)
    };
    let (f0, g0) = end(p0, d0 / dt, a0);
    let (f1, g1) = end(p1, d1 / dt, a1);
    cubic_extremum(f0, f1, g0 * dt, g1 * dt, until)
}

#[cfg(test)]
mod tests {
    use super::cubic_extremum;

    /// p(s) = s (1 - s) (p0 = p1 = 0, p'(0) = 1, p'(1) = -1): the maximum 1/4 at s = 1/2, which
    /// the step's ends (0 and 0) miss entirely.
    #[test]
    fn an_interior_maximum_is_found_between_equal_ends() {
        let (v, s) = cubic_extremum(0.0, 0.0, 1.0, -1.0, 1.0);
        assert!((v - 0.25).abs() < 1e-15 && (s - 0.5).abs() < 1e-15);
        // Only the first 40 % of the step: the maximum is at its end, 0.4 * 0.6.
        let (v, s) = cubic_extremum(0.0, 0.0, 1.0, -1.0, 0.4);
        assert!((v - 0.24).abs() < 1e-15 && (s - 0.4).abs() < 1e-15);
    }

    /// A monotone cubic's largest |value| is at an end; a negative extremum counts by magnitude.
    #[test]
    fn ends_and_magnitudes() {
        assert_eq!(cubic_extremum(1.0, 2.0, 1.0, 1.0, 1.0), (2.0, 1.0));
        let (v, s) = cubic_extremum(0.0, 0.0, -1.0, 1.0, 1.0);
        assert!((v - 0.25).abs() < 1e-15 && (s - 0.5).abs() < 1e-15);
        // p(s) = s^3 - s on [0, 1]: |min| = 2 / (3 sqrt 3) at s = 1/sqrt 3.
        let (v, s) = cubic_extremum(0.0, 0.0, -1.0, 2.0, 1.0);
        assert!((v - 2.0 / (3.0 * 3f64.sqrt())).abs() < 1e-15 && (s - 1.0 / 3f64.sqrt()).abs() < 1e-12);
    }
}

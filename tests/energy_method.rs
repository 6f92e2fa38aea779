//! The energy approach for the bridge (paper Section 3, Eqs. 27-36; the steps the paper leaves
//! out are in `../shared/paper/SCENARIO.md`, last section): the bridge taken as a rigid body about
//! its hinge, stopped by F_din at d, loaded by gravity and its d'Alembert inertia.
//!
//! Sketch (x from the hinge, loads down positive):
//!
//! ```text
//!   hinge R (up)              F_din (up)
//!   o=========================^=========================  free end
//!   x = 0                     x = d                      x = l
//!   p(x) = m g / l + (m alpha / l) x   (down, whole length)
//! ```

use beam_impact::model::Scenario;
use beam_impact::solver::energy_method::DeceleratedBridge;
use beam_impact::solver::EnergyMethod;

/// The grid of scenarios: drop heights 0.1-2 m, contact positions 10-16 m, bridge masses 6-24 t.
fn grid() -> Vec<Scenario> {
    let mut out = Vec::new();
    for h in [0.1, 0.567, 1.0, 2.0] {
        for d in [10.0, 13.0, 16.0] {
            for m in [6_000.0, 12_000.0, 24_000.0] {
                let mut s = Scenario { drop_height: h, contact_position: d, ..Scenario::default() };
                s.upper.mass = m;
                out.push(s);
            }
        }
    }
    out
}

fn bridge(s: &Scenario) -> DeceleratedBridge {
    let e = EnergyMethod::new(s);
    DeceleratedBridge::new(s.upper.mass, s.upper.length, s.gravity, s.contact_position, e.force)
}

/// Composite Simpson over [a, b] with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n).map(|i| f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 }).sum();
    h / 3.0 * (f(a) + inner + f(b))
}

/// Source: SCENARIO.md, last section, and Table 1 / Eq. (36) of the paper: on the paper scenario
/// sigma_b = 219.0 MPa (the paper's 219; tolerance 0.5 MPa, the paper prints 3 digits) and
/// E_def,b = 4.41 kJ (SCENARIO.md's digits, +-5 J). The ratio E_def,b / E_def,a is 4408.4 J /
/// 149 216 J = 2.954 % (an independent evaluation of the same closed form, +-0.001 %);
/// SCENARIO.md's "2.96 %" is the already rounded 4.41 / 149.2. Both are the paper's 4.4 kJ and
/// "3,0 %" to its printed digits (half a unit of the last).
#[test]
fn paper_scenario_bridge_stress_219_mpa_and_strain_energy_4_41_kj() {
    let e = EnergyMethod::new(&Scenario::default());
    assert!((e.bridge_bending_stress - 219.0e6).abs() <= 0.5e6, "sigma_b {}", e.bridge_bending_stress);
    assert!((e.bridge_strain_energy - 4.41e3).abs() <= 5.0, "E_def,b {}", e.bridge_strain_energy);
    assert!((e.bridge_strain_ratio - 0.02954).abs() <= 0.00001, "ratio {}", e.bridge_strain_ratio);
    assert!((e.bridge_strain_energy - 4.4e3).abs() <= 50.0, "paper 4.4 kJ: {}", e.bridge_strain_energy);
    assert!((e.bridge_strain_ratio - 0.030).abs() <= 0.0005, "paper 3.0 %: {}", e.bridge_strain_ratio);
    assert!(e.bridge_contact_moment < 0.0, "hogging over the contact point: {}", e.bridge_contact_moment);
}

/// Eq. (36) integrated in closed form equals a fine numerical quadrature of M(x)^2: composite
/// Simpson with 10^5 intervals on each side of d (M' jumps at d, so the pieces are integrated
/// apart). M^2 is a polynomial of degree 6, Simpson's error is ~ (h/L)^4 ~ 1e-20 relative, so the
/// 1e-9 tolerance only has to absorb round-off in the 2 * 10^5 terms.
#[test]
fn closed_form_bridge_strain_energy_equals_simpson_quadrature_on_a_grid() {
    for s in grid() {
        let e = EnergyMethod::new(&s);
        let b = bridge(&s);
        let (l, d, u) = (s.upper.length, s.contact_position, &s.upper);
        let m2 = |x: f64| b.moment(x).powi(2);
        let numeric = simpson(m2, 0.0, d, 100_000) + simpson(m2, d, l, 100_000);
        let closed = b.moment_squared_integral();
        assert!(
            (closed - numeric).abs() <= 1e-9 * numeric,
            "h {} d {d} m {}: {closed} vs {numeric}",
            s.drop_height,
            u.mass
        );
        let energy = 0.5 * numeric / (u.elastic_modulus * u.second_moment);
        assert!((e.bridge_strain_energy - energy).abs() <= 1e-9 * energy);
        assert!((e.bridge_strain_ratio - e.bridge_strain_energy / e.strain_energy).abs() <= 1e-15);
        assert!(
            (e.bridge_bending_stress - b.moment(d).abs() / u.section_modulus).abs() <= 1e-9 * e.bridge_bending_stress
        );
    }
}

/// M(x) satisfies the equilibrium of the decelerated bridge, on the grid. The test rebuilds the
/// loads from the paper's quantities only (alpha = (F d - m g l / 2) / (m l^2 / 3), R from the
/// vertical equilibrium) and takes moments of the free bodies on either side of a cut (the
/// distributed load by one Simpson panel, exact for its quadratic moment arm integrand):
/// the free body from the hinge gives M = 0 at the free end, the one from the free end gives
/// M = 0 at the hinge, both equal the code's M(x) everywhere (1e-9 of max |M|: round-off), and
/// the shear dM/dx (one-sided second-order differences, h = 1e-3 m: truncation h^2 M''' ~ 1e-3 N
/// against F ~ 1e5 N) jumps by F_din at d (1e-6 relative).
#[test]
fn bridge_bending_moment_satisfies_equilibrium_on_a_grid() {
    for s in grid() {
        let b = bridge(&s);
        let (m, l, g, d) = (s.upper.mass, s.upper.length, s.gravity, s.contact_position);
        let f = EnergyMethod::new(&s).force;
        let alpha = (f * d - m * g * l / 2.0) / (m * l * l / 3.0);
        assert!((b.deceleration - alpha).abs() <= 1e-12 * alpha.abs(), "{} vs {alpha}", b.deceleration);
        assert!(alpha > 0.0, "Eq. (30) gives F d >= m g l, so the fall always slows down");
        let p = |x: f64| m * g / l + m * alpha / l * x;
        let r = m * g + m * alpha * l / 2.0 - f;
        let panel = |h: &dyn Fn(f64) -> f64, a: f64, c: f64| (c - a) / 6.0 * (h(a) + 4.0 * h((a + c) / 2.0) + h(c));
        let from_hinge = |x: f64| r * x - panel(&|t| p(t) * (x - t), 0.0, x) + if x > d { f * (x - d) } else { 0.0 };
        let from_free_end = |x: f64| -panel(&|t| p(t) * (t - x), x, l) + if x < d { f * (d - x) } else { 0.0 };
        let scale = b.moment(d).abs();
        let case = format!("h {} d {d} m {m}", s.drop_height);
        assert!(from_hinge(l).abs() <= 1e-9 * scale, "{case}: M at the free end {}", from_hinge(l));
        assert!(from_free_end(0.0).abs() <= 1e-9 * scale, "{case}: M at the hinge {}", from_free_end(0.0));
        assert!(b.moment(0.0).abs() <= 1e-9 * scale && b.moment(l).abs() <= 1e-9 * scale, "{case}");
        for i in 0..=290 {
            let x = l * i as f64 / 290.0;
            let mx = b.moment(x);
            assert!((mx - from_hinge(x)).abs() <= 1e-9 * scale, "{case} x {x}: {mx} vs {}", from_hinge(x));
            assert!((mx - from_free_end(x)).abs() <= 1e-9 * scale, "{case} x {x}: {mx} vs {}", from_free_end(x));
        }
        let h = 1e-3;
        let left = (3.0 * b.moment(d) - 4.0 * b.moment(d - h) + b.moment(d - 2.0 * h)) / (2.0 * h);
        let right = (-3.0 * b.moment(d) + 4.0 * b.moment(d + h) - b.moment(d + 2.0 * h)) / (2.0 * h);
        assert!(((right - left) - f).abs() <= 1e-6 * f, "{case}: shear jump {} vs F_din {f}", right - left);
    }
}

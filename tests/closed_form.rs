//! Finite-element building blocks against closed-form beam theory.
//!
//! Sources: Euler-Bernoulli frequency equations (cantilever: cos(bL) cosh(bL) = -1; hinged-free:
//! tan(bL) = tanh(bL)), e.g. Blevins, "Formulas for Natural Frequency and Mode Shape", Table 8-1;
//! the cantilever tip deflection P L^3 / 3 E I (any strength-of-materials text).

use beam_impact::model::mesh::{Mesh, Support};
use beam_impact::model::Beam;
use beam_impact::solver::natural_modes;
use nalgebra::{DMatrix, DVector};

const EI: f64 = 2.1e11 * 0.002075;
const MASS: f64 = 10_124.0;
const LENGTH: f64 = 12.0;

fn omega(beta_l: f64) -> f64 {
    beta_l * beta_l * (EI / (MASS / LENGTH * LENGTH.powi(4))).sqrt()
}

/// Cantilever, 20 Hermite elements, first four modes. Hermite cubics converge as h^4 in the
/// eigenvalues; at 20 elements the 4th mode is within 2e-5, so 1e-4 leaves room and still
/// catches any wrong matrix entry (which shifts frequencies by percents).
#[test]
fn cantilever_frequencies_match_euler_bernoulli() {
    let beam = Beam::assemble(Mesh::cantilever(LENGTH, 20), EI, MASS, 0.0, 9.81);
    let modes = natural_modes(&beam.stiffness, &beam.mass, beam.mesh.rigid_modes()).unwrap();
    for (n, beta_l) in [1.875_104_07, 4.694_091_13, 7.854_757_44, 10.995_540_73].iter().enumerate() {
        let exact = omega(*beta_l);
        let rel = (modes.omega[n] - exact) / exact;
        assert!(rel.abs() < 1e-4, "mode {}: FE {} vs exact {exact} ({rel:e})", n + 1, modes.omega[n]);
        assert!(rel > -1e-12, "consistent-mass FE frequencies converge from above");
    }
}

/// Hinged-free beam: one rigid-body mode, then tan(bL) = tanh(bL). 40 elements, because its
/// 5th mode (bL = 13.35) is a shorter wave than the cantilever's 4th: within 1e-5 there.
#[test]
fn hinged_free_frequencies_match_euler_bernoulli() {
    let x: Vec<f64> = (0..=40).map(|i| LENGTH * i as f64 / 40.0).collect();
    let beam = Beam::assemble(Mesh::new(&x, Support::Hinged), EI, MASS, 0.0, 9.81);
    let modes = natural_modes(&beam.stiffness, &beam.mass, beam.mesh.rigid_modes()).unwrap();
    assert_eq!(modes.omega[0], 0.0, "rigid rotation about the hinge");
    for (n, beta_l) in [3.926_602_31, 7.068_582_75, 10.210_176_12, 13.351_768_78].iter().enumerate() {
        let exact = omega(*beta_l);
        let rel = (modes.omega[n + 1] - exact) / exact;
        assert!(rel.abs() < 1e-4, "mode {}: FE {} vs exact {exact} ({rel:e})", n + 2, modes.omega[n + 1]);
    }
}

/// Hermite elements are exact for nodal point loads: w = P L^3 / 3EI to round-off (1e-12),
/// at any element count; clamp moment -P L and shear P from the element end forces.
#[test]
fn static_tip_deflection_is_pl3_over_3ei() {
    let load = -10_000.0;
    for elements in [1, 3, 7] {
        let beam = Beam::assemble(Mesh::cantilever(LENGTH, elements), EI, MASS, 0.0, 9.81);
        let mut f = DVector::zeros(beam.dofs());
        let tip = beam.mesh.tip().w.unwrap();
        f[tip] = load;
        let u = beam.stiffness.clone().lu().solve(&f).unwrap();
        let exact = load * LENGTH.powi(3) / (3.0 * EI);
        assert!(((u[tip] - exact) / exact).abs() < 1e-12, "{elements} elements: {} vs {exact}", u[tip]);
        let moment = beam.start_moment_functional(0).dot(&u);
        let shear = beam.start_shear_functional(0).dot(&u);
        assert!((moment - load * LENGTH).abs() < 1e-6 * (load * LENGTH).abs(), "clamp moment {moment}");
        assert!((shear + load).abs() < 1e-6 * load.abs(), "clamp shear {shear}");
    }
}

/// Uniform load: w_tip = q L^4 / 8EI, exact at the nodes with consistent loads (Eqs. 12-13).
#[test]
fn self_weight_tip_deflection_is_ql4_over_8ei() {
    let beam = Beam::assemble(Mesh::cantilever(LENGTH, 7), EI, MASS, 0.0, 9.81);
    let u = beam.stiffness.clone().lu().solve(&beam.gravity_load).unwrap();
    let q = -MASS / LENGTH * 9.81;
    let exact = q * LENGTH.powi(4) / (8.0 * EI);
    let tip = u[beam.mesh.tip().w.unwrap()];
    assert!(((tip - exact) / exact).abs() < 1e-12, "{tip} vs {exact}");
}

/// Invariants of the hinged bridge: K symmetric, the rigid rotation in K's null space, its
/// inertia exactly J_u = m l^2 / 3 (Eq. 15), its gravity moment -m g l / 2 (Eq. 16).
#[test]
fn rigid_rotation_of_hinged_beam_has_paper_inertia_and_weight_moment() {
    let (l, m, g) = (29.0, 12_000.0, 9.81);
    let beam = Beam::assemble(Mesh::hinged_free(l, 13.0, 7, 7), 2.1e11 * 0.01831, m, 0.0, g);
    assert!((&beam.stiffness - beam.stiffness.transpose()).amax() < 1e-6, "K symmetric");
    let mut r = DVector::zeros(beam.dofs());
    for node in &beam.mesh.nodes {
        if let Some(i) = node.w {
            r[i] = node.x;
        }
        if let Some(i) = node.theta {
            r[i] = 1.0;
        }
    }
    let kr = &beam.stiffness * &r;
    assert!(kr.amax() < 1e-6 * beam.stiffness.amax(), "rigid rotation is strain-free");
    let inertia = r.dot(&(&beam.mass * &r));
    assert!((inertia / (m * l * l / 3.0) - 1.0).abs() < 1e-12, "J = {inertia}");
    let moment = r.dot(&beam.gravity_load);
    assert!((moment / (-m * g * l / 2.0) - 1.0).abs() < 1e-12, "M_G = {moment}");
}

/// Mass-normalised modes: Phi^T M Phi = I and Phi^T K Phi = diag(omega^2), to round-off relative
/// to the largest entry (1e-9 of omega_max^2 for K, where the reduction loses ~1e-13).
#[test]
fn modes_are_mass_normalised_and_diagonalise_stiffness() {
    let beam = Beam::assemble(Mesh::cantilever(LENGTH, 7), EI, MASS, 1_576.0, 9.81);
    let modes = natural_modes(&beam.stiffness, &beam.mass, beam.mesh.rigid_modes()).unwrap();
    let phi = &modes.shapes;
    let n = phi.ncols();
    let mm = phi.transpose() * &beam.mass * phi;
    assert!((mm - DMatrix::<f64>::identity(n, n)).amax() < 1e-10);
    let kk = phi.transpose() * &beam.stiffness * phi;
    let w2 = DMatrix::from_diagonal(&modes.omega.map(|w| w * w));
    assert!((kk - &w2).amax() < 1e-9 * w2.amax());
}

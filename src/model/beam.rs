//! The 4-DOF Euler-Bernoulli (Hermite) beam element: stiffness, consistent mass and the
//! consistent nodal loads of a uniform distributed load (paper Section 2, Eqs. 12-13).
//!
//! Element DOFs: (w1, theta1, w2, theta2), w up positive, theta = dw/dx counter-clockwise.

use nalgebra::{Matrix4, Vector4};

/// Uniform beam section and material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Section {
    /// Bending stiffness E I, N m^2.
    pub bending_stiffness: f64,
    /// Mass per unit length, kg/m.
    pub mass_per_length: f64,
}

/// Element stiffness matrix, `EI/L^3 [12 6L -12 6L; 6L 4L^2 -6L 2L^2; ...]`.
pub fn stiffness(section: &Section, length: f64) -> Matrix4<f64> {
    let l = length;
    let k = section.bending_stiffness / (l * l * l);
    Matrix4::new(
        12.0,
        6.0 * l,
        -12.0,
        6.0 * l,
        6.0 * l,
        4.0 * l * l,
        -6.0 * l,
        2.0 * l * l,
        -12.0,
        -6.0 * l,
        12.0,
        -6.0 * l,
        6.0 * l,
        2.0 * l * l,
        -6.0 * l,
        4.0 * l * l,
    ) * k
}

/// Consistent mass matrix, `m L / 420 [156 22L 54 -13L; ...]`.
pub fn consistent_mass(section: &Section, length: f64) -> Matrix4<f64> {
    let l = length;
    let m = section.mass_per_length * l / 420.0;
    Matrix4::new(
        156.0,
        22.0 * l,
        54.0,
        -13.0 * l,
        22.0 * l,
        4.0 * l * l,
        13.0 * l,
        -3.0 * l * l,
        54.0,
        13.0 * l,
        156.0,
        -22.0 * l,
        -13.0 * l,
        -3.0 * l * l,
        -22.0 * l,
        4.0 * l * l,
    ) * m
}

/// Consistent nodal loads of a uniform load q (N/m, up positive): `q L [1/2, L/12, 1/2, -L/12]`.
pub fn uniform_load(q: f64, length: f64) -> Vector4<f64> {
    let l = length;
    Vector4::new(q * l / 2.0, q * l * l / 12.0, q * l / 2.0, -q * l * l / 12.0)
}

/// Internal bending moment at the element's two ends, N m, sagging positive (M = EI w''),
/// from the end forces `f = k u`: `M(0) = -f[1]`, `M(L) = f[3]`.
pub fn end_moments(k: &Matrix4<f64>, u: &Vector4<f64>) -> (f64, f64) {
    let f = k * u;
    (-f[1], f[3])
}

/// Internal shear force at the element's first end, N (Q = dM/dx), from `f = k u`: `Q(0) = f[0]`.
pub fn start_shear(k: &Matrix4<f64>, u: &Vector4<f64>) -> f64 {
    (k * u)[0]
}

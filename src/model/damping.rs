//! Damping per beam: modal (paper Eq. 34) plus optional Rayleigh terms, both diagonal in the
//! beam's own mass-normalised modes.

use nalgebra::{DMatrix, DVector};

/// Modal damping coefficients c_i = 2 gamma omega_i + alpha + beta omega_i^2, 1/s, for
/// mass-normalised modes (m_i = 1 in Eq. 34). A rigid mode (omega = 0) is damped only by alpha.
pub fn modal_coefficients(omega: &DVector<f64>, damping_ratio: f64, alpha: f64, beta: f64) -> DVector<f64> {
    omega.map(|w| 2.0 * damping_ratio * w + alpha + beta * w * w)
}

/// Physical damping matrix of Eq. (34), C = Phi^-T diag(c) Phi^-1, written with Phi^-1 = Phi^T M
/// for mass-normalised modes: C = M Phi diag(c) Phi^T M.
pub fn physical_matrix(mass: &DMatrix<f64>, shapes: &DMatrix<f64>, coefficients: &DVector<f64>) -> DMatrix<f64> {
    let mphi = mass * shapes;
    let scaled = DMatrix::from_fn(mphi.nrows(), mphi.ncols(), |i, j| mphi[(i, j)] * coefficients[j]);
    &scaled * mphi.transpose()
}

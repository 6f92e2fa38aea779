//! Natural frequencies and mass-normalised mode shapes: the generalised symmetric problem
//! K phi = omega^2 M phi, reduced with the Cholesky factor of M (M = L L^T).

use nalgebra::{DMatrix, DVector, SymmetricEigen};

use crate::error::{Error, Result};

/// Natural modes of a structure, ascending in frequency.
#[derive(Clone, Debug, PartialEq)]
pub struct Modes {
    /// Natural circular frequencies omega_i, rad/s (rigid-body modes are exactly 0).
    pub omega: DVector<f64>,
    /// Mode shapes as columns, mass-normalised: Phi^T M Phi = I, Phi^T K Phi = diag(omega^2).
    pub shapes: DMatrix<f64>,
}

impl Modes {
    /// Largest natural frequency, rad/s.
    pub fn omega_max(&self) -> f64 {
        self.omega.iter().copied().fold(0.0, f64::max)
    }

    /// Natural periods 2 pi / omega, s (infinite for a rigid-body mode).
    pub fn periods(&self) -> Vec<f64> {
        self.omega.iter().map(|w| if *w > 0.0 { 2.0 * std::f64::consts::PI / w } else { f64::INFINITY }).collect()
    }
}

/// Relative size below which an eigenvalue omega^2 is a rigid-body mode: round-off in the
/// reduction is of order 1e-16 * omega_max^2, far below this.
const RIGID_TOLERANCE: f64 = 1e-11;

/// Solves K phi = omega^2 M phi for symmetric K (positive semi-definite) and M (positive definite).
pub fn natural_modes(stiffness: &DMatrix<f64>, mass: &DMatrix<f64>) -> Result<Modes> {
    let n = mass.nrows();
    let cholesky = mass.clone().cholesky().ok_or_else(|| Error::Numerical {
        what: "natural modes",
        detail: format!("the {n}x{n} mass matrix is not positive definite"),
    })?;
    let l = cholesky.l();
    // A = L^-1 K L^-T, symmetric.
    let y = l.solve_lower_triangular(stiffness).ok_or_else(|| singular("L^-1 K"))?;
    let a = l.solve_lower_triangular(&y.transpose()).ok_or_else(|| singular("L^-1 K L^-T"))?;
    let a = (&a + a.transpose()) * 0.5;
    let eigen = SymmetricEigen::new(a);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    let lambda_max = eigen.eigenvalues.iter().copied().fold(0.0, f64::max);
    let omega = DVector::from_iterator(
        n,
        order.iter().map(|&i| {
            let lambda = eigen.eigenvalues[i];
            if lambda <= RIGID_TOLERANCE * lambda_max {
                0.0
            } else {
                lambda.sqrt()
            }
        }),
    );
    let mut vectors = DMatrix::zeros(n, n);
    for (column, &i) in order.iter().enumerate() {
        vectors.set_column(column, &eigen.eigenvectors.column(i));
    }
    // Phi = L^-T Y.
    let mut shapes = l.transpose().solve_upper_triangular(&vectors).ok_or_else(|| singular("L^-T Y"))?;
    // Sign convention: the largest component of each shape is positive, so that shapes are reproducible.
    for mut column in shapes.column_iter_mut() {
        let imax = column.iamax();
        if column[imax] < 0.0 {
            column.neg_mut();
        }
    }
    Ok(Modes { omega, shapes })
}

fn singular(step: &str) -> Error {
    Error::Numerical { what: "natural modes", detail: format!("triangular solve {step} failed") }
}

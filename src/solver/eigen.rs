//! Natural frequencies and mass-normalised mode shapes: the generalised symmetric problem
//! K phi = omega^2 M phi, reduced with the Cholesky factor of M (M = L L^T), with as many
//! rigid-body modes as the supports give. The coupled problem, a rank-one update of the beams'
//! own modes, has its own solver in [`super::secular`].

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

/// Solves K phi = omega^2 M phi for symmetric K (positive semi-definite) and M (positive definite)
/// with exactly `rigid_modes` rigid-body modes, the count the supports give
/// ([`crate::model::mesh::Mesh::rigid_modes`]): that many lowest eigenvalues are set to 0.
///
/// No size threshold decides what is rigid: the dense solver's absolute error is about
/// eps * omega_max^2, and omega_max^2 grows like N^4 with the element count N, so on fine meshes
/// a threshold relative to omega_max^2 swallows real elastic modes. A count that the eigenvalues
/// contradict (more than the DOFs; the lowest elastic eigenvalue not positive or not above those
/// taken as rigid) is an [`Error::RigidModeCount`] or [`Error::RigidModeMismatch`].
pub fn natural_modes(stiffness: &DMatrix<f64>, mass: &DMatrix<f64>, rigid_modes: usize) -> Result<Modes> {
    let n = mass.nrows();
    if rigid_modes > n {
        return Err(Error::RigidModeCount { what: "natural modes", expected: rigid_modes, dofs: n });
    }
    // A structure without free DOFs (a rigid support) has no modes.
    if n == 0 {
        return Ok(Modes { omega: DVector::zeros(0), shapes: DMatrix::zeros(0, 0) });
    }
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
    let eigenvalues: Vec<f64> = order.iter().map(|&i| eigen.eigenvalues[i]).collect();
    let omega = frequencies("natural modes", &eigenvalues, rigid_modes)?;
    let mut vectors = DMatrix::zeros(n, n);
    for (column, &i) in order.iter().enumerate() {
        vectors.set_column(column, &eigen.eigenvectors.column(i));
    }
    // Phi = L^-T Y.
    let mut shapes = l.transpose().solve_upper_triangular(&vectors).ok_or_else(|| singular("L^-T Y"))?;
    orient(&mut shapes);
    Ok(Modes { omega, shapes })
}

/// Natural frequencies from eigenvalues omega^2 in ascending order, the first `rigid_modes` of
/// them set to exactly 0. Errors if the count exceeds the eigenvalues, or if the lowest elastic
/// eigenvalue is not positive or not above every eigenvalue taken as rigid (in magnitude): the
/// count and the structure then disagree (a mechanism the supports do not explain, or a rigid
/// mode that is not there).
pub(crate) fn frequencies(what: &'static str, eigenvalues: &[f64], rigid_modes: usize) -> Result<DVector<f64>> {
    let n = eigenvalues.len();
    if rigid_modes > n {
        return Err(Error::RigidModeCount { what, expected: rigid_modes, dofs: n });
    }
    if let Some(&lowest_elastic) = eigenvalues.get(rigid_modes) {
        let largest_rigid = eigenvalues[..rigid_modes].iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        if !(lowest_elastic > 0.0 && lowest_elastic > largest_rigid) {
            return Err(Error::RigidModeMismatch { what, expected: rigid_modes, lowest_elastic, largest_rigid });
        }
    }
    Ok(DVector::from_iterator(
        n,
        eigenvalues.iter().enumerate().map(|(i, l)| if i < rigid_modes { 0.0 } else { l.sqrt() }),
    ))
}

/// Sign convention: the largest component of each column is positive, so that shapes are reproducible.
pub(crate) fn orient(shapes: &mut DMatrix<f64>) {
    for mut column in shapes.column_iter_mut() {
        let imax = column.iamax();
        if column[imax] < 0.0 {
            column.neg_mut();
        }
    }
}

fn singular(step: &str) -> Error {
    Error::Numerical { what: "natural modes", detail: format!("triangular solve {step} failed") }
}

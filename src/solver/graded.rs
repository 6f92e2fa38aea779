//! Natural modes of a graded beam: one whose elements differ in length by orders of magnitude
//! (issue 28, item 6), such as a sub-millimetre overhang element beyond the contact node of a
//! 29 m bridge, or a contact a few centimetres from the hinge.
//!
//! **Why the ordinary solve fails there.** A Hermite element of length h has stiffness entries of
//! order EI/h^3 and mass entries of order m h (m per unit length): it adds eigenvalues up to
//! [`ELEMENT_EIGENVALUE_BOUND`] EI/(m h^4), the largest of the free-free element, which bounds the
//! mesh's largest (the element eigenvalue theorem). The dense solver of [`super::natural_modes`]
//! reduces K with the Cholesky factor of M and has an absolute error of about eps * omega_max^2, so
//! the lowest elastic eigenvalue lambda_1 = (beta_1 / l)^4 EI/m keeps a relative error of about
//! eps * 8400 / beta_1^4 * (l/h)^4 = 23.5 eps (l/h)^4 on a hinged-free beam (beta_1 l = 3.9266):
//! 1e-6 at l/h = 120, and 1 (nothing left) at l/h = 1.5e4, a 2 mm element on the 29 m bridge. The
//! rigid mode count check then fails ("the lowest elastic eigenvalue is not positive"), or the
//! frequencies and shapes are quietly wrong.
//!
//! **What is done instead** on a graded beam (longest / shortest element above
//! [`GRADED_RATIO`]; every other beam takes the ordinary solve, bit for bit):
//!
//! 1. The inverse problem G_e M phi = phi / omega^2, with G the flexibility of the beam held at its
//!    support (a cantilever; the hinge's rotation held too) in closed form: for Euler-Bernoulli
//!    beams the Hermite element's nodal displacements under nodal loads are exact, so G = K^-1
//!    exactly, and its entries are polynomials in the node positions (no difference of element
//!    stiffnesses of order EI/h^3, whatever h). A hinged beam's rigid rotation r (w = x, theta = 1)
//!    is taken out by the M-orthogonal projector P = I - r r^T M / (r^T M r): G_e = P G P^T. The
//!    symmetric form L^T G_e L (M = L L^T) has an absolute error of about eps / lambda_1: the low
//!    modes, which the impact excites, come out to round-off relative to themselves.
//! 2. The rigid mode is exactly r, deflated before the dense solve (it would otherwise mix with
//!    the short elements' eigenvalues, which the inverse problem sees as round-off around 0).
//! 3. The modes the inverse problem cannot resolve (1/omega^2 below [`SPLIT`] times that of the
//!    spurious limit, [`spurious_limit`]) are found by Rayleigh-Ritz with K in their subspace: they
//!    are the short elements' own, far above anything a step or a cut-off follows, and their
//!    frequencies are those of K, accurate relative to themselves.
//!
//! The modes above [`spurious_limit`] are the short elements' own: [`super::ModalSystem::for_run`]
//! replaces them by their static response in every method, so that neither the automatic cut-off
//! nor the automatic steps follow them.
//!
//! **Beyond [`MAX_ELEMENT_RATIO`]** a beam is refused with a one-line message naming the beam and
//! the element: past it the contact moment recovered from a short element (its end moment,
//! EI/h^2 times differences of nodal values) loses its digits, eps (l/h)^2 relative, and the
//! element's rotation DOF, whose mass m h^3 / 105 is tiny, is resolved only to eps / sqrt(m h^3)
//! by the mass-normalised shapes.

use nalgebra::{DMatrix, DVector, SymmetricEigen};

use super::eigen::{natural_modes, orient, Modes};
use crate::error::{Error, Result};
use crate::model::mesh::{Mesh, Support};
use crate::model::Beam;

/// A beam whose longest element is more than this many times its shortest is graded: its modes
/// come from the inverse problem, and the modes above [`spurious_limit`] are the short elements'
/// own. At this ratio the ordinary solve still holds the lowest eigenvalue to about
/// 23.5 eps (l/h)^4 <= 1e-6 on any mesh of up to 12 elements of the longest length (a finer
/// uniform part is not graded and keeps the ordinary solve, as it always did).
pub const GRADED_RATIO: f64 = 10.0;

/// The largest ratio of the longest to the shortest element of a beam that is accepted: beyond
/// it the modes are refused (see the module documentation). At this ratio on the 29 m bridge's
/// 7-element paper mesh (4.1 m elements, a 0.41 mm overhang) the first frequencies hold the
/// closed form to the mesh's own discretisation error (`tests/robust_meshes.rs`), and the contact
/// moment recovered from the short element keeps eps (l/h)^2 < 1e-6 of its value.
pub const MAX_ELEMENT_RATIO: f64 = 1e4;

/// The largest generalised eigenvalue of the free-free Hermite beam element with consistent
/// mass, in units of EI / (m h^4): its eigenvalues are 0, 0, 720 and 8400. By the element
/// eigenvalue theorem no mesh of such elements has a natural frequency above
/// sqrt(8400 EI / m) / h_min^2.
pub const ELEMENT_EIGENVALUE_BOUND: f64 = 8400.0;

/// The split between the modes of the inverse problem and those found by Rayleigh-Ritz with K:
/// a mode is taken from the inverse problem when its 1/omega^2 exceeds this fraction of the
/// spurious limit's, i.e. up to twice the spurious limit in frequency.
pub const SPLIT: f64 = 0.25;

/// The element lengths of a mesh at their extremes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grading {
    /// The longest element (index from the support, 0-based) and its length, m.
    pub longest: (usize, f64),
    /// The shortest element and its length, m.
    pub shortest: (usize, f64),
}

impl Grading {
    /// The extremes of `mesh`'s element lengths (the first element of equal ones).
    pub fn of(mesh: &Mesh) -> Grading {
        let mut longest = (0, mesh.element_length(0));
        let mut shortest = longest;
        for e in 1..mesh.elements() {
            let h = mesh.element_length(e);
            if h > longest.1 {
                longest = (e, h);
            }
            if h < shortest.1 {
                shortest = (e, h);
            }
        }
        Grading { longest, shortest }
    }

    /// Longest over shortest element length.
    pub fn ratio(&self) -> f64 {
        self.longest.1 / self.shortest.1
    }

    /// True above [`GRADED_RATIO`].
    pub fn is_graded(&self) -> bool {
        self.ratio() > GRADED_RATIO
    }
}

/// The frequency above which a graded beam's modes are its short elements' own, rad/s: the
/// element eigenvalue bound of its mean element, sqrt(8400 EI / m) (N / l)^2 for N elements over
/// the length l, which no uniform mesh of the beam with as many elements exceeds. A graded beam
/// follows the frequencies of its uniform counterpart; the modes above them live in its short
/// elements (a 0.1 m overhang element on the bridge's 7-element paper mesh, 4.1 m elements: its
/// own lowest mode is 1.2e6 rad/s, the limit 2.1e4 rad/s, the longer elements' highest mode 1.0e4
/// rad/s). `None` for a beam that is not graded.
pub fn spurious_limit(beam: &Beam) -> Option<f64> {
    let mesh = &beam.mesh;
    if mesh.elements() == 0 || !Grading::of(mesh).is_graded() {
        return None;
    }
    let h = (mesh.tip().x - mesh.nodes[0].x) / mesh.elements() as f64;
    // A beam of sections: its stiffest section per mass sets the highest wave speed.
    let stiffest = beam.sections.iter().map(|s| s.bending_stiffness / s.mass_per_length).fold(0.0, f64::max);
    Some((ELEMENT_EIGENVALUE_BOUND * stiffest).sqrt() / (h * h))
}

/// Refuses a beam whose elements differ in length by more than [`MAX_ELEMENT_RATIO`], with a
/// one-line message naming the beam (`name`, e.g. "the bridge (upper)") and the element.
pub fn check_grading(beam: &Beam, name: &str) -> Result<()> {
    if beam.mesh.elements() == 0 {
        return Ok(());
    }
    let g = Grading::of(&beam.mesh);
    let ratio = g.ratio();
    if ratio.is_finite() && ratio <= MAX_ELEMENT_RATIO {
        return Ok(());
    }
    let (e, h) = g.shortest;
    let (x1, x2) = (beam.mesh.nodes[e].x, beam.mesh.nodes[e + 1].x);
    Err(Error::Other(format!(
        "{name}: element {} of {} (x = {x1:.6} to {x2:.6} m) is {h:.4e} m long, 1/{ratio:.0} of the longest (element \
         {}, {:.4} m); the elements of one beam may differ in length by at most {MAX_ELEMENT_RATIO:e} (the natural \
         modes and the stresses recovered from so short an element lose their digits beyond it): make it at least \
         {:.4e} m (move contact_position), or change the element counts",
        e + 1,
        beam.mesh.elements(),
        g.longest.0 + 1,
        g.longest.1,
        g.longest.1 / MAX_ELEMENT_RATIO,
    )))
}

/// The natural modes of one beam: the ordinary solve ([`natural_modes`]) unless the beam is
/// graded, then the inverse problem of the module documentation; refused beyond
/// [`MAX_ELEMENT_RATIO`] ([`check_grading`]).
pub fn beam_modes(beam: &Beam, name: &str) -> Result<Modes> {
    let rigid = beam.mesh.rigid_modes();
    if beam.mesh.far != crate::model::mesh::FarEnd::Free {
        // Issue 45: the inverse problem's closed-form flexibility is the cantilever's; a beam on
        // two supports takes the ordinary solve, within its own grading limit.
        check_two_support_grading(beam, name)?;
        return natural_modes(&beam.stiffness, &beam.mass, rigid);
    }
    match spurious_limit(beam) {
        None => natural_modes(&beam.stiffness, &beam.mass, rigid),
        Some(limit) => {
            check_grading(beam, name)?;
            graded_modes(beam, limit)
        }
    }
}

/// The largest ratio of the longest to the shortest element of a beam on two supports (issue
/// 45), whose modes take the ordinary solve: there the lowest eigenvalue keeps a relative error
/// of about 23.5 eps (l/h)^4 (module documentation), 8e-6 at 200.
pub const MAX_TWO_SUPPORT_RATIO: f64 = 200.0;

/// Refuses a beam on two supports whose elements differ in length by more than
/// [`MAX_TWO_SUPPORT_RATIO`] (a contact node very near a support), in one line.
fn check_two_support_grading(beam: &Beam, name: &str) -> Result<()> {
    if beam.mesh.elements() == 0 {
        return Ok(());
    }
    let g = Grading::of(&beam.mesh);
    let ratio = g.ratio();
    if ratio.is_finite() && ratio <= MAX_TWO_SUPPORT_RATIO {
        return Ok(());
    }
    Err(Error::Other(format!(
        "{name}: element {} is {:.4e} m long, 1/{ratio:.0} of the longest ({:.4} m); on two supports the elements \
         may differ in length by at most {MAX_TWO_SUPPORT_RATIO} (the natural modes lose their digits beyond it): \
         move lower.contact_position at least {:.4e} m from a support, or change lower.elements",
        g.shortest.0 + 1,
        g.shortest.1,
        g.longest.1,
        g.longest.1 / MAX_TWO_SUPPORT_RATIO,
    )))
}

/// What a nodal DOF is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Deflection,
    Rotation,
}

/// The response of kind `response` at `x` to a unit load of kind `load` (a force, or a couple
/// conjugate to theta = dw/dx) at `a`, times EI, on a cantilever clamped at 0 (Euler-Bernoulli,
/// uniform EI). Symmetric (Maxwell) by construction.
fn influence(response: Kind, x: f64, load: Kind, a: f64) -> f64 {
    use Kind::{Deflection, Rotation};
    let (lo, hi) = (x.min(a), x.max(a));
    match (response, load) {
        (Deflection, Deflection) => lo * lo * (3.0 * hi - lo) / 6.0,
        (Rotation, Rotation) => lo,
        (Rotation, Deflection) => {
            if x <= a {
                x * (2.0 * a - x) / 2.0
            } else {
                a * a / 2.0
            }
        }
        (Deflection, Rotation) => {
            if x <= a {
                x * x / 2.0
            } else {
                a * (2.0 * x - a) / 2.0
            }
        }
    }
}

/// [`influence`] / EI on a beam whose EI changes from element to element: the unit-load integral
/// of m_r m_l / EI(xi) from the support to min(x, a), with the unit moments m = p - xi for a
/// force at p and m = 1 for a couple, element by element (x measured from node 0).
fn stepped_influence(beam: &Beam, response: Kind, x: f64, load: Kind, a: f64) -> f64 {
    let mesh = &beam.mesh;
    let x0 = mesh.nodes[0].x;
    let upto = x.min(a);
    // The moment of a unit load as c0 + c1 xi: a force at p gives p - xi, a couple 1.
    let linear = |kind: Kind, p: f64| match kind {
        Kind::Deflection => (p, -1.0),
        Kind::Rotation => (1.0, 0.0),
    };
    let ((r0, r1), (l0, l1)) = (linear(response, x), linear(load, a));
    // The product's antiderivative: r0 l0 xi + (r0 l1 + r1 l0) xi^2 / 2 + r1 l1 xi^3 / 3.
    let antiderivative = |xi: f64| r0 * l0 * xi + (r0 * l1 + r1 * l0) * xi * xi / 2.0 + r1 * l1 * xi * xi * xi / 3.0;
    let mut sum = 0.0;
    for e in 0..mesh.elements() {
        let (s, t) = (mesh.nodes[e].x - x0, (mesh.nodes[e + 1].x - x0).min(upto));
        if s >= upto {
            break;
        }
        sum += (antiderivative(t) - antiderivative(s)) / beam.sections[e].bending_stiffness;
    }
    sum
}

/// The flexibility of the beam held at its support: a cantilever from node 0, with a hinge's
/// rotation held as well (its row and column are zero). Exact at the nodes for Hermite elements,
/// so it is the inverse of the stiffness matrix of a clamped beam.
pub fn flexibility(beam: &Beam) -> DMatrix<f64> {
    let mesh = &beam.mesh;
    let x0 = mesh.nodes[0].x;
    let mut dofs: Vec<(usize, Kind, f64)> = Vec::with_capacity(mesh.dofs);
    for node in mesh.nodes.iter().skip(1) {
        let x = node.x - x0;
        if let Some(i) = node.w {
            dofs.push((i, Kind::Deflection, x));
        }
        if let Some(i) = node.theta {
            dofs.push((i, Kind::Rotation, x));
        }
    }
    let ei = beam.sections[0].bending_stiffness;
    let uniform = beam.sections.iter().all(|s| s.bending_stiffness == ei);
    let mut g = DMatrix::zeros(mesh.dofs, mesh.dofs);
    for &(i, ki, x) in &dofs {
        for &(j, kj, a) in &dofs {
            g[(i, j)] = if uniform { influence(ki, x, kj, a) / ei } else { stepped_influence(beam, ki, x, kj, a) };
        }
    }
    g
}

/// The rigid rotation about the hinge (w = x, theta = 1), mass-normalised.
fn hinge_rotation(beam: &Beam) -> DVector<f64> {
    let mut r = DVector::zeros(beam.dofs());
    let x0 = beam.mesh.nodes[0].x;
    for node in &beam.mesh.nodes {
        if let Some(i) = node.w {
            r[i] = node.x - x0;
        }
        if let Some(i) = node.theta {
            r[i] = 1.0;
        }
    }
    let norm = r.dot(&(&beam.mass * &r)).sqrt();
    r / norm
}

fn numerical(detail: String) -> Error {
    Error::Numerical { what: "natural modes of a graded beam", detail }
}

/// The modes of a graded beam (module documentation, steps 1-3); `limit` is its
/// [`spurious_limit`].
fn graded_modes(beam: &Beam, limit: f64) -> Result<Modes> {
    let n = beam.dofs();
    let rigid = beam.mesh.rigid_modes();
    let mut g = flexibility(beam);
    let r = match beam.mesh.support {
        Support::Hinged => {
            let r = hinge_rotation(beam);
            // G_e = P G P^T with P = I - r (M r)^T (r^T M r = 1): four rank-one terms.
            let mr = &beam.mass * &r;
            let gm = &g * &mr;
            let c = mr.dot(&gm);
            g -= &r * gm.transpose() + &gm * r.transpose();
            g += &r * r.transpose() * c;
            Some(r)
        }
        Support::Clamped | Support::Rigid | Support::Mass => None,
    };
    if rigid != usize::from(r.is_some()) {
        return Err(Error::RigidModeCount { what: "natural modes of a graded beam", expected: rigid, dofs: n });
    }
    let cholesky = beam
        .mass
        .clone()
        .cholesky()
        .ok_or_else(|| numerical(format!("the {n}x{n} mass matrix is not positive definite")))?;
    let l = cholesky.l();
    let b = l.transpose() * &g * &l;
    let b = (&b + b.transpose()) * 0.5;
    // An orthonormal basis Q of the directions M-orthogonal to the rigid mode (y_r = L^T r is a
    // unit vector): a Householder reflector taking e_k to y_r, without its column k.
    let q = match &r {
        Some(r) => {
            let y = l.transpose() * r;
            let k = y.iamax();
            let s = if y[k] >= 0.0 { -1.0 } else { 1.0 };
            let mut w = y.clone();
            w[k] -= s;
            let w = w.normalize();
            let mut h = DMatrix::<f64>::identity(n, n) - &w * w.transpose() * 2.0;
            h = h.remove_column(k);
            h
        }
        None => DMatrix::identity(n, n),
    };
    let reduced = q.transpose() * &b * &q;
    let reduced = (&reduced + reduced.transpose()) * 0.5;
    let eigen = SymmetricEigen::new(reduced);
    let m = eigen.eigenvalues.len();
    let mu_max = eigen.eigenvalues.iter().copied().fold(0.0, f64::max);
    if mu_max <= 0.0 {
        return Err(numerical("the flexibility has no positive eigenvalue".into()));
    }
    // 1/omega^2 above the split comes from the inverse problem; the rest by Rayleigh-Ritz.
    let split = (SPLIT / (limit * limit)).max(1e3 * f64::EPSILON * mu_max);
    let (resolved, ritz): (Vec<usize>, Vec<usize>) = (0..m).partition(|&i| eigen.eigenvalues[i] > split);
    let lt = l.transpose();
    let shapes_of = |columns: &[usize]| -> Result<DMatrix<f64>> {
        let y = DMatrix::from_fn(m, columns.len(), |a, c| eigen.eigenvectors[(a, columns[c])]);
        let y = &q * y;
        lt.solve_upper_triangular(&y).ok_or_else(|| numerical("triangular solve L^-T Y failed".into()))
    };
    let mut modes: Vec<(f64, DVector<f64>)> = Vec::with_capacity(n);
    if let Some(r) = r {
        modes.push((0.0, r));
    }
    let phi = shapes_of(&resolved)?;
    for (c, &i) in resolved.iter().enumerate() {
        modes.push((1.0 / eigen.eigenvalues[i].sqrt(), phi.column(c).into_owned()));
    }
    if !ritz.is_empty() {
        let phi = shapes_of(&ritz)?;
        let ks = phi.transpose() * &beam.stiffness * &phi;
        let ks = (&ks + ks.transpose()) * 0.5;
        let local = SymmetricEigen::new(ks);
        let rotated = &phi * &local.eigenvectors;
        for (c, &lambda) in local.eigenvalues.iter().enumerate() {
            if lambda.is_nan() || lambda <= 0.0 {
                return Err(numerical(format!(
                    "a short element's mode has omega^2 = {lambda:e} 1/s^2 (Rayleigh-Ritz with K)"
                )));
            }
            modes.push((lambda.sqrt(), rotated.column(c).into_owned()));
        }
    }
    modes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let omega = DVector::from_iterator(n, modes.iter().map(|(w, _)| *w));
    let mut shapes = DMatrix::zeros(n, n);
    for (c, (_, v)) in modes.iter().enumerate() {
        shapes.set_column(c, v);
    }
    orient(&mut shapes);
    Ok(Modes { omega, shapes })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::mesh::Mesh;

    fn bridge(x: &[f64]) -> Beam {
        // The paper's bridge: EI = 210e9 * 0.01831, 12 000 kg over 29 m.
        Beam::assemble(Mesh::new(x, Support::Hinged), 210e9 * 0.01831, 12_000.0, 0.0, 9.81)
    }

    fn uniform(length: f64, n: usize) -> Vec<f64> {
        (0..=n).map(|i| length * i as f64 / n as f64).collect()
    }

    #[test]
    fn flexibility_is_the_inverse_of_a_clamped_beams_stiffness() {
        // Hermite elements are nodally exact for point loads on Euler-Bernoulli beams, so the
        // closed-form influence coefficients are K^-1 to round-off (cond(K) ~ 1e5 here, tolerance 1e-9).
        let beam = Beam::assemble(Mesh::cantilever(12.0, 9), 4.3575e8, 10_124.0, 1576.0, 9.81);
        let product = &beam.stiffness * flexibility(&beam);
        let error = (product - DMatrix::<f64>::identity(beam.dofs(), beam.dofs())).amax();
        assert!(error < 1e-9, "K G - I = {error:e}");
    }

    #[test]
    fn free_free_hermite_element_has_eigenvalues_720_and_8400() {
        // Closed form: the consistent-mass Hermite element's generalised eigenvalues are 0, 0,
        // 720 and 8400 EI/(m h^4) (symmetric and antisymmetric bending). Tolerance 1e-9: a 4x4
        // solve of entries of order 1.
        let section = crate::model::beam::Section { bending_stiffness: 1.0, mass_per_length: 1.0 };
        let k = DMatrix::from_column_slice(4, 4, crate::model::beam::stiffness(&section, 1.0).as_slice());
        let m = DMatrix::from_column_slice(4, 4, crate::model::beam::consistent_mass(&section, 1.0).as_slice());
        let modes = natural_modes(&k, &m, 2).unwrap();
        let lambda: Vec<f64> = modes.omega.iter().map(|w| w * w).collect();
        assert!((lambda[2] / 720.0 - 1.0).abs() < 1e-9, "{lambda:?}");
        assert!((lambda[3] / ELEMENT_EIGENVALUE_BOUND - 1.0).abs() < 1e-9, "{lambda:?}");
    }

    #[test]
    fn uniform_and_mildly_graded_beams_are_not_graded() {
        let beam = bridge(&uniform(29.0, 14));
        assert_eq!(spurious_limit(&beam), None);
        // The paper's 7 + 7 bridge mesh with the contact at 13 m: 1.86 and 2.29 m elements.
        let mut x = uniform(13.0, 7);
        x.extend((1..=7).map(|i| 13.0 + 16.0 * i as f64 / 7.0));
        assert_eq!(spurious_limit(&bridge(&x)), None);
    }
}

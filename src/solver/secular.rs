//! Eigen decomposition of a diagonal matrix plus a rank-one term, D + rho z z^T, through the
//! secular equation. This is the coupled problem of Table 2, column 3, in the beams' own
//! mass-normalised modal coordinates: M = I and K = diag(omega_i^2) + k_c b b^T.
//!
//! Method (Golub, "Some modified matrix eigenvalue problems", SIAM Review 15, 1973; Bunch,
//! Nielsen and Sorensen, "Rank-one modification of the symmetric eigenproblem", Numer. Math. 31,
//! 1978): for rho > 0, d sorted ascending and every z_i != 0 with distinct d_i, the eigenvalues are
//! the roots of
//!
//! ```text
//! f(lambda) = 1 + rho sum_i z_i^2 / (d_i - lambda) = 0,
//! ```
//!
//! one in each interval (d_i, d_i+1) and the last in (d_n, d_n + rho |z|^2]; the eigenvector of a
//! root is (D - lambda I)^-1 z, normalised. Components with a negligible z_i, and all but one of a
//! group of equal d_i (after a Givens rotation that gathers the group's z into one component),
//! are deflated: they keep d_i and a unit vector.
//!
//! Accuracy, which is why this replaces the dense solver for the coupled modes: each root is
//! sought as lambda = d_o + tau, tau relative to the nearer pole d_o of its interval, so lambda -
//! d_j = (d_j - d_o) - tau keeps its relative precision even where |d_j| is 1e13 times lambda (the
//! dense solver's absolute error, eps * lambda_max, reaches the first coupled eigenvalue 31 1/s^2
//! once the mesh is fine). The root finder is the "middle way" of Li (1993, LAPACK dlaed4): the
//! two poles around the root are kept, the rest of f is matched in value and slope, and the
//! quadratic that results is solved; each step stays inside a bracket that bisection falls back
//! on. The vectors use the z that makes the computed roots exact (Loewner's formula, Gu and
//! Eisenstat, SIAM J. Matrix Anal. Appl. 15, 1994), so they are orthogonal to round-off however
//! close the roots. Cost O(n^2) instead of the dense O(n^3).

use nalgebra::{DMatrix, DVector};

use super::eigen::{frequencies, orient, Modes};
use crate::error::{Error, Result};

/// Eigenvalues (ascending) and orthonormal eigenvectors (columns) of D + rho z z^T.
#[derive(Clone, Debug, PartialEq)]
pub struct RankOneEigen {
    /// Eigenvalues, ascending.
    pub eigenvalues: DVector<f64>,
    /// Eigenvectors as columns, in the order of `eigenvalues`: V^T V = I.
    pub eigenvectors: DMatrix<f64>,
}

/// Most root-finder iterations for one root: the middle way converges in a handful; bisection
/// (after `MODEL_STEPS`) reaches adjacent floats of the bracket in at most ~2100.
const MAX_ITERATIONS: usize = 2200;
/// Rational-model steps before the root finder bisects only.
const MODEL_STEPS: usize = 40;

/// Natural modes of the coupled system in modal coordinates: K = diag(`omega2`) + `stiffness`
/// `contact` `contact`^T, M = I, with `rigid_modes` rigid-body modes expected (0 when the bar
/// holds every rigid motion of the beams). Ascending frequencies, unit-norm shapes (mass-normalised
/// for M = I) with their largest component positive.
pub fn coupled_modes(
    omega2: &DVector<f64>,
    contact: &DVector<f64>,
    stiffness: f64,
    rigid_modes: usize,
) -> Result<Modes> {
    let eigen = rank_one_update(omega2, contact, stiffness)?;
    let omega = frequencies("coupled modes", eigen.eigenvalues.as_slice(), rigid_modes)?;
    let mut shapes = eigen.eigenvectors;
    orient(&mut shapes);
    Ok(Modes { omega, shapes })
}

/// Eigenvalues and eigenvectors of diag(`d`) + `rho` `z` `z`^T, for any order of `d` and any sign
/// of `rho` (rho < 0 is solved as the negated problem -D + |rho| z z^T).
pub fn rank_one_update(d: &DVector<f64>, z: &DVector<f64>, rho: f64) -> Result<RankOneEigen> {
    let n = d.len();
    if z.len() != n {
        return Err(numerical(format!("{n} diagonal entries but {} in the rank-one vector", z.len())));
    }
    if !rho.is_finite() || d.iter().chain(z.iter()).any(|v| !v.is_finite()) {
        return Err(numerical(format!("non-finite input (rho = {rho})")));
    }
    if rho < 0.0 {
        let mut negated = rank_one_update(&-d, z, -rho)?;
        // -(ascending) is descending: reverse both.
        negated.eigenvalues = DVector::from_iterator(n, negated.eigenvalues.iter().rev().map(|l| -l));
        let columns: Vec<_> = (0..n).rev().map(|j| negated.eigenvectors.column(j).into_owned()).collect();
        negated.eigenvectors = DMatrix::from_columns(&columns);
        return Ok(negated);
    }
    // Sorted copies: position i holds d[order[i]].
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| d[i].total_cmp(&d[j]));
    let mut ds: Vec<f64> = order.iter().map(|&i| d[i]).collect();
    let mut zs: Vec<f64> = order.iter().map(|&i| z[i]).collect();
    let rotations = deflate(&mut ds, &mut zs, rho);
    let kept: Vec<usize> = (0..n).filter(|&i| zs[i] != 0.0).collect();

    // Eigenpairs in sorted coordinates: (eigenvalue, column).
    let mut pairs: Vec<(f64, DVector<f64>)> = Vec::with_capacity(n);
    for i in (0..n).filter(|i| zs[*i] == 0.0) {
        let mut e = DVector::zeros(n);
        e[i] = 1.0;
        pairs.push((ds[i], e));
    }
    let dk: Vec<f64> = kept.iter().map(|&i| ds[i]).collect();
    let zk: Vec<f64> = kept.iter().map(|&i| zs[i]).collect();
    for (lambda, v) in secular_pairs(&dk, &zk, rho)? {
        let mut column = DVector::zeros(n);
        for (k, &i) in kept.iter().enumerate() {
            column[i] = v[k];
        }
        pairs.push((lambda, column));
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));

    let eigenvalues = DVector::from_iterator(n, pairs.iter().map(|p| p.0));
    let mut sorted = DMatrix::zeros(n, n);
    for (j, (_, v)) in pairs.iter().enumerate() {
        sorted.set_column(j, v);
    }
    // Undo the deflating rotations (last first) as row operations, then the sort.
    for &Rotation { p, q, c, s } in rotations.iter().rev() {
        for j in 0..n {
            let (vp, vq) = (sorted[(p, j)], sorted[(q, j)]);
            sorted[(p, j)] = c * vp + s * vq;
            sorted[(q, j)] = -s * vp + c * vq;
        }
    }
    let mut eigenvectors = DMatrix::zeros(n, n);
    for (i, &row) in order.iter().enumerate() {
        eigenvectors.set_row(row, &sorted.row(i));
    }
    Ok(RankOneEigen { eigenvalues, eigenvectors })
}

/// A plane rotation of the deflation: new basis vectors u_p = c e_p - s e_q (which z no longer
/// touches) and u_q = s e_p + c e_q.
#[derive(Clone, Copy, Debug)]
struct Rotation {
    p: usize,
    q: usize,
    c: f64,
    s: f64,
}

/// Deflates in place (d ascending): a z_i negligible against |z| (below eps |z|, where it moves
/// an eigenvalue by at most rho eps^2 |z|^2) is set to 0; of two neighbours with (nearly) equal d,
/// a rotation moves the weight of z into the later one, when the off-diagonal term it neglects,
/// |(d_q - d_p) c s|, is below 8 eps max(|d_p|, |d_q|) (a relative perturbation of the pair, not
/// one relative to the largest d). Deflated components are those with z_i = 0 afterwards.
fn deflate(d: &mut [f64], z: &mut [f64], rho: f64) -> Vec<Rotation> {
    let norm = z.iter().map(|v| v * v).sum::<f64>().sqrt();
    let negligible = f64::EPSILON * norm;
    for zi in z.iter_mut() {
        if rho == 0.0 || zi.abs() <= negligible {
            *zi = 0.0;
        }
    }
    let mut rotations = Vec::new();
    let mut last: Option<usize> = None;
    for q in 0..d.len() {
        if z[q] == 0.0 {
            continue;
        }
        if let Some(p) = last {
            let r = libm::hypot(z[p], z[q]);
            let (c, s) = (z[q] / r, z[p] / r);
            let t = d[q] - d[p];
            if t <= 0.0 || (t * c * s).abs() <= 8.0 * f64::EPSILON * d[p].abs().max(d[q].abs()) {
                let (dp, dq) = (d[p], d[q]);
                d[p] = c * c * dp + s * s * dq;
                d[q] = s * s * dp + c * c * dq;
                z[p] = 0.0;
                z[q] = r;
                rotations.push(Rotation { p, q, c, s });
            }
        }
        last = Some(q);
    }
    rotations
}

/// One root of the secular equation: lambda = d[origin] + tau.
#[derive(Clone, Copy, Debug)]
struct Root {
    origin: usize,
    tau: f64,
}

/// Eigenpairs of diag(d) + rho z z^T for d strictly ascending, every z_i != 0, rho > 0: the roots
/// of the secular equation and their eigenvectors, in ascending order.
fn secular_pairs(d: &[f64], z: &[f64], rho: f64) -> Result<Vec<(f64, DVector<f64>)>> {
    let m = d.len();
    if m == 0 {
        return Ok(Vec::new());
    }
    if let Some(i) = (1..m).find(|&i| d[i] <= d[i - 1]) {
        return Err(numerical(format!("deflation left d[{}] = {:e} >= d[{i}] = {:e}", i - 1, d[i - 1], d[i])));
    }
    let roots: Vec<Root> = (0..m).map(|i| find_root(d, z, rho, i)).collect::<Result<_>>()?;
    // lambda_r - d_j, from the shifted representation (exact up to one rounding each).
    let gap = |j: usize, r: &Root| (d[r.origin] - d[j]) + r.tau;
    // Loewner: the z-hat for which the computed roots are the exact eigenvalues (rho > 0):
    //   z-hat_j^2 = prod_r (lambda_r - d_j) / (rho prod_{i != j} (d_i - d_j)),
    // as a product of ratios in (0, 1] by interlacing, so nothing overflows.
    let zhat: Vec<f64> = (0..m)
        .map(|j| {
            let mut p = gap(j, &roots[m - 1]) / rho;
            for (i, di) in d.iter().enumerate() {
                if i < j {
                    p *= gap(j, &roots[i]) / (di - d[j]);
                } else if i > j {
                    p *= gap(j, &roots[i - 1]) / (di - d[j]);
                }
            }
            p.max(0.0).sqrt().copysign(z[j])
        })
        .collect();
    let mut pairs = Vec::with_capacity(m);
    for root in &roots {
        // v_j = z-hat_j / (d_j - lambda), normalised.
        let mut v = DVector::from_iterator(m, (0..m).map(|j| zhat[j] / -gap(j, root)));
        let norm = v.norm();
        if !(norm.is_finite() && norm > 0.0) {
            return Err(numerical(format!("eigenvector of the root near d[{}] has norm {norm:e}", root.origin)));
        }
        v /= norm;
        pairs.push((d[root.origin] + root.tau, v));
    }
    Ok(pairs)
}

/// Value, slope and error bound of the secular function, scaled by 1/rho, at d[origin] + tau:
/// w = 1/rho + sum_j z_j^2 / (delta_j - tau) with delta_j = d_j - d[origin], split into the part
/// psi of the poles j <= `split` and phi of those above.
struct Secular {
    w: f64,
    dpsi: f64,
    dphi: f64,
    bound: f64,
}

fn evaluate(d: &[f64], z: &[f64], rho: f64, origin: usize, split: usize, tau: f64) -> Secular {
    let (mut w, mut dpsi, mut dphi, mut sum_abs) = (1.0 / rho, 0.0, 0.0, 1.0 / rho);
    for j in 0..d.len() {
        let delta = (d[j] - d[origin]) - tau;
        let t = z[j] / delta;
        w += z[j] * t;
        sum_abs += (z[j] * t).abs();
        if j <= split {
            dpsi += t * t;
        } else {
            dphi += t * t;
        }
    }
    // Rounding of the sum (n terms, each with a few roundings) and of delta_j - tau.
    let bound = 8.0 * f64::EPSILON * (sum_abs + tau.abs() * (dpsi + dphi));
    Secular { w, dpsi, dphi, bound }
}

/// Root number `i` (0-based) of the secular equation, d strictly ascending.
fn find_root(d: &[f64], z: &[f64], rho: f64, i: usize) -> Result<Root> {
    let m = d.len();
    if m == 1 {
        return Ok(Root { origin: 0, tau: rho * z[0] * z[0] });
    }
    let norm2: f64 = z.iter().map(|v| v * v).sum();
    // The bracket (lo, hi) in tau, the origin, and the two poles that bound the root: `split` is
    // the last pole at or below the root's interval.
    let (origin, split, mut lo, mut hi, start) = if i + 1 == m {
        // Last root: in (d_m, d_m + rho |z|^2], where f >= 0; both model poles lie below.
        let hi = rho * norm2;
        (i, i.saturating_sub(1), 0.0, hi, hi)
    } else {
        let half = (d[i + 1] - d[i]) / 2.0;
        let mid = evaluate(d, z, rho, i, i, half);
        if mid.w >= 0.0 {
            (i, i, 0.0, half, half)
        } else {
            (i + 1, i, -half, 0.0, -half)
        }
    };
    // The two model poles, relative to the origin.
    let (pole_lo, pole_hi) = (d[split] - d[origin], d[split + 1] - d[origin]);
    let mut tau = start;
    for iteration in 0..MAX_ITERATIONS {
        let s = evaluate(d, z, rho, origin, split, tau);
        if s.w.abs() <= s.bound || s.w == 0.0 {
            return Ok(Root { origin, tau });
        }
        if s.w < 0.0 {
            lo = lo.max(tau);
        } else {
            hi = hi.min(tau);
        }
        let inside = |t: f64| t > lo && t < hi;
        let mut next = f64::NAN;
        if iteration < MODEL_STEPS {
            // Middle way: w(tau + eta) ~ c + s_lo / (dl - eta) + s_hi / (dh - eta) with dl, dh the
            // distances to the two poles, s_lo = dl^2 psi', s_hi = dh^2 phi', c fixing the value;
            // the root of c eta^2 - a eta + b = 0 that keeps tau inside the bracket.
            let (dl, dh) = (pole_lo - tau, pole_hi - tau);
            let slope = s.dpsi + s.dphi;
            let c = s.w - dl * s.dpsi - dh * s.dphi;
            let a = (dl + dh) * s.w - dl * dh * slope;
            let b = dl * dh * s.w;
            let candidates = if c == 0.0 {
                [b / a, f64::NAN]
            } else {
                let q = 0.5 * (a + a.signum() * (a * a - 4.0 * b * c).max(0.0).sqrt());
                [q / c, b / q]
            };
            next = candidates
                .into_iter()
                .map(|eta| tau + eta)
                .filter(|t| inside(*t))
                .min_by(|x, y| (x - tau).abs().total_cmp(&(y - tau).abs()))
                .unwrap_or(f64::NAN);
            if !inside(next) {
                next = tau - s.w / slope; // Newton
            }
        }
        if !inside(next) {
            next = 0.5 * (lo + hi);
            if !inside(next) {
                // tau is lo or hi, and they are adjacent floats: resolved to the last bit.
                return Ok(Root { origin, tau });
            }
        }
        if (next - tau).abs() <= 2.0 * f64::EPSILON * tau.abs() {
            // A step below round-off in tau: converged.
            return Ok(Root { origin, tau: next });
        }
        tau = next;
    }
    Err(numerical(format!("secular root {i} of {m} did not converge in {MAX_ITERATIONS} iterations")))
}

fn numerical(detail: String) -> Error {
    Error::Numerical { what: "coupled modes (secular equation)", detail }
}

#[cfg(test)]
mod tests {
    use nalgebra::{DMatrix, DVector, SymmetricEigen};

    use super::*;

    /// A small deterministic generator (64-bit LCG, Knuth's MMIX constants): the tests need no
    /// statistical quality, only reproducible spread-out numbers in [0, 1).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    fn dense(d: &DVector<f64>, z: &DVector<f64>, rho: f64) -> DMatrix<f64> {
        DMatrix::from_diagonal(d) + z * z.transpose() * rho
    }

    /// Checks a decomposition against the dense matrix A = D + rho z z^T and nalgebra's
    /// SymmetricEigen: eigenvalues within `tol` of max |lambda| (the dense solver's own error is
    /// ~1e-15 of it on these well-scaled 2..12 sized problems), V^T V = I and V diag(lambda) V^T = A
    /// to the same relative tolerance.
    fn check_against_dense(d: &DVector<f64>, z: &DVector<f64>, rho: f64, tol: f64) {
        let n = d.len();
        let a = dense(d, z, rho);
        let ours = rank_one_update(d, z, rho).unwrap();
        let mut reference: Vec<f64> = SymmetricEigen::new(a.clone()).eigenvalues.iter().copied().collect();
        reference.sort_by(f64::total_cmp);
        let scale = reference.iter().fold(0.0, |m: f64, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
        for (k, (x, y)) in ours.eigenvalues.iter().zip(&reference).enumerate() {
            assert!((x - y).abs() <= tol * scale, "eigenvalue {k}: secular {x:e} vs dense {y:e} (d {d}, z {z})");
        }
        let v = &ours.eigenvectors;
        let orthogonality = (v.transpose() * v - DMatrix::<f64>::identity(n, n)).amax();
        assert!(orthogonality <= tol, "V^T V - I = {orthogonality:e}");
        let rebuilt = v * DMatrix::from_diagonal(&ours.eigenvalues) * v.transpose();
        let residual = (rebuilt - &a).amax();
        assert!(residual <= tol * scale, "V L V^T - A = {residual:e} of {scale:e}");
    }

    /// Source: the dense symmetric eigen solver (nalgebra). Goal: the secular solution of random
    /// D + rho z z^T (n = 2..12, d in [-5, 5) unsorted, z in [-1, 1), rho in (0, 3)) has the same
    /// eigenvalues and a true orthonormal eigenbasis. Tolerance 1e-12 relative to max |lambda|:
    /// both methods are backward stable to a few eps * n, so 1e-12 leaves two orders of margin and
    /// still catches a wrong root or a wrong vector (errors of order 1e-3 or larger).
    #[test]
    fn random_rank_one_updates_match_dense_eigen() {
        let mut rng = Lcg(7);
        for case in 0..200 {
            let n = 2 + case % 11;
            let d = DVector::from_fn(n, |_, _| 10.0 * rng.next() - 5.0);
            let z = DVector::from_fn(n, |_, _| 2.0 * rng.next() - 1.0);
            let rho = 3.0 * rng.next() + 1e-3;
            check_against_dense(&d, &z, rho, 1e-12);
        }
    }

    /// Source: as above. Goal: the deflated cases keep their d_i and still give an orthonormal
    /// eigenbasis: a zero z_i, repeated d_i (two and three equal, gathered by Givens rotations), a
    /// zero d_i (the bridge's rigid mode in the coupled problem), all of them at once, a zero z,
    /// rho < 0. Tolerance 1e-12 as above.
    #[test]
    fn deflated_rank_one_updates_match_dense_eigen() {
        let v = |x: &[f64]| DVector::from_column_slice(x);
        let cases = [
            (v(&[1.0, 2.0, 3.0, 4.0]), v(&[0.5, 0.0, -0.3, 0.7]), 1.5),
            (v(&[1.0, 2.0, 2.0, 4.0]), v(&[0.5, 0.4, -0.3, 0.7]), 1.5),
            (v(&[2.0, 1.0, 2.0, 2.0, 0.5]), v(&[0.5, 0.4, -0.3, 0.7, 0.2]), 0.8),
            (v(&[0.0, 3.0, 1.0, 7.0]), v(&[0.9, -0.5, 0.3, 0.7]), 2.0),
            (v(&[0.0, 3.0, 3.0, 0.0, 5.0, 1.0]), v(&[0.0, -0.5, 0.3, 0.7, 0.0, 0.2]), 2.0),
            (v(&[1.0, 2.0, 3.0]), v(&[0.0, 0.0, 0.0]), 2.0),
            (v(&[1.0, 2.0, 2.0, 4.0]), v(&[0.5, 0.4, -0.3, 0.7]), -1.5),
            (v(&[5.0]), v(&[2.0]), 0.25),
        ];
        for (d, z, rho) in &cases {
            check_against_dense(d, z, *rho, 1e-12);
        }
        // The zero d with a zero z stays an exact 0 eigenvalue (a rigid mode the bar does not hold).
        let (d, z, rho) = &cases[4];
        let eigen = rank_one_update(d, z, *rho).unwrap();
        assert_eq!(eigen.eigenvalues[0], 0.0);
        // Random problems with deflations mixed in.
        let mut rng = Lcg(11);
        for case in 0..200 {
            let n = 3 + case % 10;
            let mut d = DVector::from_fn(n, |_, _| (6.0 * rng.next()).floor() - 1.0); // repeats and zeros
            let z = DVector::from_fn(n, |_, _| if rng.next() < 0.25 { 0.0 } else { 2.0 * rng.next() - 1.0 });
            d[0] = 0.0;
            check_against_dense(&d, &z, 0.1 + rng.next(), 1e-12);
        }
    }

    /// Source: the closed form of a 2x2 problem, lambda_min = det / lambda_max. Goal: the reason
    /// for this solver. With d = (0, 1e12), z = (1, 1), rho = 1 the small eigenvalue (~1) is found
    /// to 1e-14 relative, where a dense solver's absolute error eps * 1e12 ~ 1e-4 leaves it ~1e-4
    /// relative. The coupled beams have the same grading (31 against 1e15 at 32x the mesh).
    #[test]
    fn small_eigenvalue_of_graded_problem_to_relative_precision() {
        let (d0, d1, rho): (f64, f64, f64) = (0.0, 1e12, 1.0);
        let z = DVector::from_column_slice(&[1.0, 1.0]);
        let trace = d0 + d1 + 2.0 * rho;
        let det = d0 * d1 + rho * (d0 + d1);
        let large = 0.5 * (trace + (trace * trace - 4.0 * det).sqrt());
        let small = det / large;
        let eigen = rank_one_update(&DVector::from_column_slice(&[d0, d1]), &z, rho).unwrap();
        assert!((eigen.eigenvalues[0] / small - 1.0).abs() < 1e-14, "{} vs {small}", eigen.eigenvalues[0]);
        assert!((eigen.eigenvalues[1] / large - 1.0).abs() < 1e-14, "{} vs {large}", eigen.eigenvalues[1]);
        // A graded 40x40 (d_i = i^4 * 1e3, like beam eigenvalues ~ N^4): the smallest eigenvalue from
        // the Rayleigh quotient of its own vector (an independent check, to 1e-12 relative).
        let n = 40;
        let d = DVector::from_fn(n, |i, _| 1e3 * (i as f64).powi(4) * if i == 0 { 0.0 } else { 1.0 });
        let z = DVector::from_fn(n, |i, _| 0.1 * (1.0 + 0.5 * (i as f64).sin()));
        let eigen = rank_one_update(&d, &z, 50.0).unwrap();
        let v = eigen.eigenvectors.column(0);
        let av = DMatrix::from_diagonal(&d) * v + &z * (50.0 * z.dot(&v));
        let quotient = v.dot(&av);
        assert!((eigen.eigenvalues[0] / quotient - 1.0).abs() < 1e-12, "{} vs {quotient}", eigen.eigenvalues[0]);
        let residual = (av - v * eigen.eigenvalues[0]).norm();
        assert!(residual < 1e-12 * eigen.eigenvalues[0], "|A v - lambda v| = {residual:e}");
    }

    /// Goal: the counts of the supports are enforced. A 0 eigenvalue where none is expected, or
    /// more rigid modes than DOFs, are typed errors; a declared one sets exactly one to 0.
    #[test]
    fn rigid_mode_count_is_checked() {
        let d = DVector::from_column_slice(&[0.0, 3.0, 5.0]);
        let z = DVector::from_column_slice(&[0.0, 1.0, 1.0]);
        assert!(matches!(coupled_modes(&d, &z, 1.0, 0), Err(Error::RigidModeMismatch { expected: 0, .. })));
        assert!(matches!(coupled_modes(&d, &z, 1.0, 4), Err(Error::RigidModeCount { expected: 4, dofs: 3, .. })));
        let modes = coupled_modes(&d, &z, 1.0, 1).unwrap();
        assert_eq!(modes.omega[0], 0.0);
        assert!(modes.omega[1] > 0.0);
    }
}

//! Exact modal advance (issue 29): each modal coordinate of a stage is a damped oscillator
//! q'' + c q' + omega^2 q = f(t), and over one step the converged method's stepper takes f a
//! polynomial in time (linear out of contact; in contact the bar's force a cubic, see below). For
//! such a forcing the oscillator's state at the step's end is a closed form, exact for any step,
//! so the steps are set by resolving the contact force and the peaks, not by the highest kept
//! frequency (the linear
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
//! mode, omega = 0), the series is exact there. A mode at or beyond critical damping (Rayleigh's
//! stiffness-proportional term makes the high modes so: zeta = beta omega / 2) over a step with
//! c h >= [`SERIES_BELOW`] takes the series over h / 2^m and m exact doublings
//! (`overdamped_responses`).
//!
//! In contact the bar's force is not taken linear over a step but as the cubic through its values
//! and rates at both ends (Hermite; [`super::stepper`]): its departure from the chord,
//! alpha H10(s) + beta H11(s) with s = t/h, adds the forcings s^2 and s^3. [`CubicStep`] holds
//! each coordinate's response to them and the moments int q s dt and int q s^2 dt that the
//! damping's exact work then needs. All follow from one sequence: psi_k, the response from rest
//! to t^k/k!, with psi_k' = psi_(k-1) (so psi_-1 = B, psi_-2 = D) and, from the equation,
//! omega^2 psi_k = t^k/k! - c psi_(k-1) - psi_(k-2).

/// omega h below which the coefficients come from the Taylor series.
pub const SERIES_BELOW: f64 = 0.5;

/// max(omega, c) h below which the contact stage's [`CubicStep`] coefficients come from the
/// Taylor series: the recurrence of [`CubicStep::new`] divides by omega^2 at every order and
/// loses about (k + 1)(k + 2) / (omega h)^2 of the k-th response's digits, compounding: at
/// omega h = 2 some 200 eps at k = 6, at 0.5 about 1e7 eps.
pub const CUBIC_SERIES_BELOW: f64 = 2.0;

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
    /// The coefficients of q'' + `damping` q' + `omega2` q = f0 + r t over a step `h` > 0, s:
    /// the underdamped closed form, the Taylor series, or for a mode at or beyond critical
    /// damping (as stiffness-proportional damping makes the high modes) over a step the series
    /// cannot take, `overdamped_responses`.
    pub fn new(omega2: f64, damping: f64, h: f64) -> ModeStep {
        Self::with_responses(omega2, damping, h).0
    }

    /// [`Self::new`], and the responses psi_-2 ..= psi_6 at `h` (index k + 2; module
    /// documentation) where they came with the coefficients (the series, an overdamped mode), for
    /// the contact stage's [`CubicStep::from_responses`]: a step cut at a contact change or a
    /// motion row takes both for one new step size, from one series.
    #[inline(always)]
    pub fn with_responses(omega2: f64, damping: f64, h: f64) -> (ModeStep, Option<[f64; 9]>) {
        let omega = libm::sqrt(omega2.max(0.0));
        if overdamped_beyond_series(omega2, damping, h) {
            let psi = overdamped_responses(omega2, damping, h);
            return (Self::from_responses(omega2, damping, &psi), Some(psi));
        }
        if omega * h < SERIES_BELOW || omega2 <= 0.0 || damping >= 2.0 * omega {
            let psi = series_responses(omega2, damping, h);
            return (Self::from_responses(omega2, damping, &psi), Some(psi));
        }
        (Self::closed_form(omega2, damping, h), None)
    }

    /// The underdamped closed form (omega h >= [`SERIES_BELOW`], c < 2 omega).
    #[inline(always)]
    fn closed_form(omega2: f64, damping: f64, h: f64) -> ModeStep {
        let (w2, c) = (omega2, damping);
        let sigma = 0.5 * c;
        let wd = libm::sqrt(w2 - sigma * sigma);
        let e = libm::exp(-sigma * h);
        // One argument reduction for both (the same bits as libm's sin and cos apart).
        let (sn, cs) = libm::sincos(wd * h);
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

    /// The coefficients from the responses psi_-2 ..= psi_6 at the step's end (module
    /// documentation): B = psi_-1, D = psi_-2, A = D + c B, C = -omega^2 B; the forced ones
    /// psi_0 and psi_1, and each integral the next psi (psi_k' = psi_(k-1)).
    #[inline(always)]
    fn from_responses(omega2: f64, damping: f64, psi: &[f64; 9]) -> ModeStep {
        let p = |k: i32| psi[(k + 2) as usize];
        let (b, d) = (p(-1), p(-2));
        let a = d + damping * b;
        ModeStep {
            q: [a, b, p(0), p(1)],
            v: [-omega2 * b, d, b, p(0)],
            integral: [b + damping * p(0), p(0), p(1), p(2)],
        }
    }

    /// The coefficients from the Taylor series of each unit response at t = 0, summed until its
    /// terms fall below 1e-17 of each response's first (omega h < [`SERIES_BELOW`] or c h small:
    /// at most ~20 terms). The stepper takes [`series_responses`] instead (one series for all
    /// twelve and the contact stage's, without a division a term); this one, term by term, is its
    /// check. (The stepper's series until issue 43 stopped at 1e-17 of the q0 response's first
    /// term, which left the ramp's response (omega h)^2 / 20 short: 2e-9 of it on a 1 ns retake
    /// of a 2e5 rad/s mode.)
    #[cfg(test)]
    fn series(omega2: f64, damping: f64, h: f64) -> ModeStep {
        // Derivatives q^(k), q^(k+1) of the four unit responses (q0, v0, f0, r), and the forcing's
        // derivatives f^(k) (f0: k = 0, r: k = 1).
        let mut d0 = [1.0, 0.0, 0.0, 0.0];
        let mut d1 = [0.0, 1.0, 0.0, 0.0];
        let mut out = ModeStep::default();
        let scale = libm::sqrt(omega2.abs()).max(damping.abs()) * h;
        let mut term = 1.0; // h^k / k!
        let mut bound = 1.0; // scale^(k+1) / (k+1)!
        let ramp_first = scale * scale * scale / 6.0;
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
            // The next terms are of order scale^(k+1) / (k+1)! of the q0 response's first (the
            // derivatives grow by omega or c per order); the forcing's terms are in once k >= 3,
            // and the ramp's response, whose first term is scale^3 / 3! of that, is summed to
            // 1e-17 of its own first term too. (A running product, not powi.)
            bound *= scale / (k as f64 + 1.0);
            if k >= 3 && bound < 1e-17 * ramp_first {
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

/// The contact stage's extra coefficients of one coordinate for one step (module
/// documentation): the responses to the forcings s^2 and s^3 (s = t/h), and the moments of the
/// whole response.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CubicStep {
    /// q(h) per unit of s^2 and of s^3.
    pub q: [f64; 2],
    /// v(h) per unit of s^2 and of s^3.
    pub v: [f64; 2],
    /// int q dt over the step per unit of s^2 and of s^3.
    pub integral: [f64; 2],
    /// int q s dt (row 0) and int q s^2 dt (row 1) over the step per q0, v0, f0, r (the ramp
    /// f = r t), s^2 and s^3.
    pub moments: [[f64; 6]; 2],
}

/// 1/n! for n < [`INVERSE_FACTORIALS`]`.len()`, by a running product (the same bits everywhere).
const INVERSE_FACTORIALS: [f64; 48] = {
    let mut table = [1.0; 48];
    let mut n = 1;
    while n < 48 {
        table[n] = table[n - 1] / n as f64;
        n += 1;
    }
    table
};

/// Orders of the series of [`CubicStep`]: below [`CUBIC_SERIES_BELOW`] a term is at most
/// 2^n n / (n + 4)! of the first, below 1e-20 by n = 30.
const CUBIC_SERIES_TERMS: usize = 30;

impl CubicStep {
    /// The coefficients of q'' + `damping` q' + `omega2` q = f(t) over a step `h` > 0, from the
    /// same step's [`ModeStep`] (`linear`: its B = psi_-1, D = psi_-2, psi_0 and psi_1 seed the
    /// recurrence).
    #[inline(always)]
    pub fn new(omega2: f64, damping: f64, h: f64, linear: &ModeStep) -> CubicStep {
        Self::from_responses(damping, h, &Self::responses(omega2, damping, h, linear))
    }

    /// psi_-2 ..= psi_6 at `h` (index k + 2) of q'' + `damping` q' + `omega2` q: the first four
    /// from the same step's [`ModeStep`] (`linear`), the rest by the recurrence, the series or
    /// the overdamped forms (module documentation).
    #[inline(always)]
    fn responses(omega2: f64, damping: f64, h: f64, linear: &ModeStep) -> [f64; 9] {
        let (w2, c) = (omega2, damping);
        // psi[k + 2] = psi_k for k = -2..=6.
        let mut psi = [0.0; 9];
        psi[0] = linear.v[1];
        psi[1] = linear.q[1];
        psi[2] = linear.q[2];
        psi[3] = linear.q[3];
        let scale = libm::sqrt(w2.abs()).max(c.abs()) * h;
        if overdamped_beyond_series(w2, c, h) {
            psi = overdamped_responses(w2, c, h);
        } else if scale >= CUBIC_SERIES_BELOW && w2 > 0.0 {
            // h^k / k! as a running product (the same bits on every platform).
            let mut power = h;
            for k in 2..=6usize {
                power *= h / k as f64;
                psi[k + 2] = (power - c * psi[k + 1] - psi[k]) / w2;
            }
        } else {
            // psi_k(h) = h^(k+2) sum_n u_n / (n + k + 2)!, u_n = h^n D^(n)(0): u_0 = 1, u_1 = -c h,
            // u_(n+2) = -c h u_(n+1) - (omega h)^2 u_n.
            let (ch, wh2) = (c * h, w2 * h * h);
            let mut sums = [0.0; 5];
            let (mut u0, mut u1) = (1.0, -ch);
            // |u_n| <= (2 scale)^n (the recurrence's roots are at most 2 scale): once that bound
            // over (n + 4)! is below 1e-20 the rest adds nothing (a 1 ns retake: four terms).
            let mut bound = 1.0;
            for n in 0..CUBIC_SERIES_TERMS {
                let factorials = INVERSE_FACTORIALS[n + 4..].first_chunk::<5>().expect("n + 9 <= 48");
                for (sum, factorial) in sums.iter_mut().zip(factorials) {
                    *sum += u0 * factorial;
                }
                let u2 = -ch * u1 - wh2 * u0;
                u0 = u1;
                u1 = u2;
                bound *= 2.0 * scale;
                if bound * INVERSE_FACTORIALS[n + 5] < 1e-20 {
                    break;
                }
            }
            let mut power = h * h * h * h;
            for (j, sum) in sums.iter().enumerate() {
                psi[j + 4] = power * sum;
                power *= h;
            }
        }
        psi
    }

    /// The coefficients of q'' + `damping` q' + omega^2 q = f(t) over a step `h` > 0 from its
    /// responses psi_-2 ..= psi_6 at `h` (index k + 2; [`ModeStep::with_responses`] or
    /// [`Self::new`]).
    #[inline(always)]
    pub fn from_responses(damping: f64, h: f64, psi: &[f64; 9]) -> CubicStep {
        let c = damping;
        let p = |k: i32| psi[(k + 2) as usize];
        let (s2, s3) = (2.0 / (h * h), 6.0 / (h * h * h));
        // The antiderivatives Y1, Y2, Y3 of each input's response at h.
        let antiderivatives: [[f64; 3]; 6] = [
            [p(-1) + c * p(0), p(0) + c * p(1), p(1) + c * p(2)],
            [p(0), p(1), p(2)],
            [p(1), p(2), p(3)],
            [p(2), p(3), p(4)],
            [s2 * p(3), s2 * p(4), s2 * p(5)],
            [s3 * p(4), s3 * p(5), s3 * p(6)],
        ];
        let mut moments = [[0.0; 6]; 2];
        for (j, [y1, y2, y3]) in antiderivatives.into_iter().enumerate() {
            // int y t dt = h Y1 - Y2, int y t^2 dt = h^2 Y1 - 2 h Y2 + 2 Y3 (by parts).
            moments[0][j] = y1 - y2 / h;
            moments[1][j] = y1 - 2.0 * y2 / h + 2.0 * y3 / (h * h);
        }
        CubicStep { q: [s2 * p(2), s3 * p(3)], v: [s2 * p(1), s3 * p(2)], integral: [s2 * p(3), s3 * p(4)], moments }
    }
}

/// The largest number of terms [`series_responses`] sums: with max(omega, c) h < 1/2 (where it is
/// used) its terms fall below 1e-18 of the first by n = 17.
const SERIES_TERMS: usize = 39;

/// 1/n for n < 40, each correctly rounded (the same bits everywhere).
const INVERSE_INTEGERS: [f64; 40] = {
    let mut table = [0.0; 40];
    let mut n = 1;
    while n < 40 {
        table[n] = 1.0 / n as f64;
        n += 1;
    }
    table
};

/// psi_-2 ..= psi_6 at `h` (index k + 2; module documentation) from one Taylor series, for a
/// step short against the mode (max(omega, c) h < [`SERIES_BELOW`]: the series' regime of
/// [`ModeStep::new`]): psi_k(h) = h^(k+2) sum_n u_n / (n + k + 2)!, u_n = h^n D^(n)(0), with
/// u_0 = 1, u_1 = -c h, u_(n+2) = -c h u_(n+1) - (omega h)^2 u_n (D = psi_-2 the free response's
/// velocity to a unit start velocity, whose derivatives follow from the equation). D^(n)(0) =
/// sum_j lambda_1^j lambda_2^(n-j) over the characteristic roots, |lambda| <= max(omega, c),
/// so |u_n| <= (n + 1) s^n with s = max(omega, c) h, and each sum's n-th term is at most
/// (n + 1) s^n / n! of its first (1 / (k + 2)!): summed until that bound falls below 1e-18
/// (the rest, geometric with ratio below 1/2 from there, adds less than 2e-18), at most
/// [`SERIES_TERMS`] terms; no division a term (the reciprocals are tables). One series serves
/// the twelve coefficients of [`ModeStep`] and the five further responses of [`CubicStep`]: a
/// step cut at a contact change or at a motion row (a new step size) pays for it once.
#[inline(always)]
fn series_responses(omega2: f64, damping: f64, h: f64) -> [f64; 9] {
    let (ch, wh2) = (damping * h, omega2 * h * h);
    let scale = libm::sqrt(omega2.abs()).max(damping.abs()) * h;
    let mut sums = [0.0; 9];
    let (mut u0, mut u1) = (1.0, -ch);
    // s^n / n!, a running product.
    let mut power = 1.0;
    // n + 2 as a float, counted (exact: the same value as the integer's conversion).
    let mut weight = 2.0;
    for n in 0..SERIES_TERMS {
        // 1 / (n + j)! for j = 0..9 as one array: the nine sums side by side in the CPU's vectors.
        let factorials = INVERSE_FACTORIALS[n..].first_chunk::<9>().expect("n + 9 <= 48");
        for (sum, factorial) in sums.iter_mut().zip(factorials) {
            *sum += u0 * factorial;
        }
        let u2 = -ch * u1 - wh2 * u0;
        u0 = u1;
        u1 = u2;
        power *= scale * INVERSE_INTEGERS[n + 1];
        if weight * power < 1e-18 {
            break;
        }
        weight += 1.0;
    }
    let mut step_power = 1.0;
    for sum in &mut sums {
        *sum *= step_power;
        step_power *= h;
    }
    sums
}

/// True for a mode at or beyond critical damping (c >= 2 omega: its roots real) over a step
/// the series cannot take (c h >= [`SERIES_BELOW`]): there the underdamped closed form does not
/// apply, the series' alternating terms grow as (c h)^k / k! (at c h = 40, 1e16: nothing left;
/// Rayleigh's beta = 1e-3 puts c h = 1.8e6 h on the paper mesh's top mode), and the recurrence of
/// [`CubicStep::new`] loses 1 / (|lambda_slow| h) per order (lambda_slow ~ -omega^2 / c).
#[inline(always)]
fn overdamped_beyond_series(omega2: f64, damping: f64, h: f64) -> bool {
    damping >= 2.0 * libm::sqrt(omega2.max(0.0)) && damping * h >= SERIES_BELOW
}

/// psi_-2 ..= psi_6 at `h` (index k + 2; module documentation) of a mode at or beyond critical
/// damping, from its real roots l1 >= l2 (l2 = -(c/2 + s), l1 = omega^2 / l2, s = sqrt(c^2/4 -
/// omega^2), each without cancellation).
///
/// Roots apart ((l1 - l2) h >= 1): the equation splits into x_j' = l_j x_j + f (x1 = v - l2 q,
/// x2 = v - l1 q, q = (x1 - x2) / (l1 - l2)), each a first-order equation whose response from rest
/// to t^k / k! is h^(k+1) phi_(k+1)(l_j h) (the phi functions of exponential integrators,
/// [`phi_functions`]), so
///
/// ```text
/// psi_k = h^(k+2) (phi_(k+1)(z1) - phi_(k+1)(z2)) / (z1 - z2)   (k >= -1, z_j = l_j h)
/// psi_-2 = D = (z1 e^z1 - z2 e^z2) / (z1 - z2)
/// ```
///
/// exact to a few eps however small the slow root's l1 h (1e-5 for Rayleigh's beta = 1 on a
/// 2e-5 s step: the creep the closed form's differences lose, each of h / omega^2 and (A - 1) c /
/// omega^4 being 1 / (|l1| h) times their sum) and however large the fast one's.
///
/// Roots close (below 1 / h apart, critical damping among them): the Taylor series over h / 2^m
/// (c h / 2^m < [`SERIES_BELOW`]), then m doublings, each exact algebra: from rest under t^k / k!
/// the state at h is (psi_k, psi_(k-1)) and the forcing over the second half is
/// sum_i h^(k-i) / (k-i)! t'^i / i!, so
///
/// ```text
/// psi_k(2h)  = A psi_k + B psi_(k-1) + sum_(i=0..k) h^(k-i) / (k-i)! psi_i      (k >= 0)
/// psi_-1(2h) = B (A + D),    psi_-2(2h) = D^2 - omega^2 B^2
/// ```
///
/// (A = D + c B). With real roots B and every psi_k (k >= 0) are positive, and so is A (no
/// overshoot): the sums add positive terms. Squaring doubles the relative error of the
/// exponentials, so m doublings cost about 2^m eps = c h eps / SERIES_BELOW: small here, where
/// close roots bound c h by 1 + 2 |l1| h and the loss is the exponential's own |l1 h| eps.
fn overdamped_responses(omega2: f64, damping: f64, h: f64) -> [f64; 9] {
    let (w2, c) = (omega2.max(0.0), damping);
    let sigma = 0.5 * c;
    let omega = libm::sqrt(w2);
    let s = libm::sqrt(((sigma - omega) * (sigma + omega)).max(0.0));
    if 2.0 * s * h >= 1.0 {
        let l2 = -(sigma + s);
        let l1 = w2 / l2;
        let (z1, z2) = (l1 * h, l2 * h);
        let (p1, p2) = (phi_functions(z1), phi_functions(z2));
        let gap = z1 - z2;
        let mut psi = [0.0; 9];
        psi[0] = (z1 * p1[0] - z2 * p2[0]) / gap;
        let mut power = h;
        for k in 1..9 {
            psi[k] = power * (p1[k - 1] - p2[k - 1]) / gap;
            power *= h;
        }
        return psi;
    }
    let mut doublings = 0;
    let mut step = h;
    // Halving is exact in binary: h = step 2^m to the bit.
    while c * step >= SERIES_BELOW && doublings < 1100 {
        step *= 0.5;
        doublings += 1;
    }
    // psi_k(step) = step^(k+2) sum_n u_n / (n + k + 2)!, u_n = step^n D^(n)(0): u_0 = 1,
    // u_1 = -c step, u_(n+2) = -c step u_(n+1) - (omega step)^2 u_n. The roots of the recurrence
    // are lambda step, |lambda step| <= c step < 1/2, so |u_n| <= (n + 1) / 2^n: 24 terms leave
    // less than 1e-23 of the first.
    let (ch, wh2) = (c * step, w2 * step * step);
    let mut psi = [0.0; 9];
    let (mut u0, mut u1) = (1.0, -ch);
    for n in 0..24 {
        for (j, sum) in psi.iter_mut().enumerate() {
            *sum += u0 * INVERSE_FACTORIALS[n + j];
        }
        let u2 = -ch * u1 - wh2 * u0;
        u0 = u1;
        u1 = u2;
    }
    let mut power = 1.0;
    for value in &mut psi {
        *value *= power;
        power *= step;
    }
    for _ in 0..doublings {
        let (d, b) = (psi[0], psi[1]);
        let a = d + c * b;
        let mut next = [0.0; 9];
        next[0] = d * d - w2 * b * b;
        next[1] = b * (a + d);
        for k in 0..=6 {
            let mut sum = a * psi[k + 2] + b * psi[k + 1];
            // step^(k-i) / (k-i)!, from i = k down.
            let mut power = 1.0;
            for i in (0..=k).rev() {
                sum += power * psi[i + 2];
                power *= step / (k - i + 1) as f64;
            }
            next[k + 2] = sum;
        }
        psi = next;
        step *= 2.0;
    }
    psi
}

/// phi_0 ..= phi_7 at a real z <= 0: phi_0 = e^z, phi_(n+1)(z) = (phi_n(z) - 1/n!) / z, i.e.
/// phi_n(z) = sum_j z^j / (j + n)! (Hochbruck & Ostermann, Exponential integrators, Acta Numerica
/// 19 (2010), Eq. 2.10), each positive. For z <= -8 by that recurrence, whose error shrinks by
/// n / |z| < 1 a step; nearer 0 by the series at z / 2^m (|z / 2^m| <= 1/2, alternating terms at
/// most 1/2^j of the first) and m doublings phi_k(2z) = 2^-k (phi_0 phi_k + sum_(j=1..k)
/// phi_j / (k-j)!) (ibid., Eq. 2.14 in their notation), sums of positive terms.
pub fn phi_functions(z: f64) -> [f64; 8] {
    let mut phi = [0.0; 8];
    if z <= -8.0 {
        phi[0] = libm::exp(z);
        for n in 1..8 {
            phi[n] = (phi[n - 1] - INVERSE_FACTORIALS[n - 1]) / z;
        }
        return phi;
    }
    let mut doublings = 0;
    let mut x = z;
    while x < -0.5 {
        x *= 0.5;
        doublings += 1;
    }
    // 20 terms: |x|^20 / 20! < 1e-24.
    let mut power = 1.0;
    for j in 0..20 {
        for (n, value) in phi.iter_mut().enumerate() {
            *value += power * INVERSE_FACTORIALS[j + n];
        }
        power *= x;
    }
    for _ in 0..doublings {
        let mut next = [0.0; 8];
        let mut scale = 1.0;
        for k in 0..8 {
            let mut sum = phi[0] * phi[k];
            for j in 1..=k {
                sum += phi[j] * INVERSE_FACTORIALS[k - j];
            }
            next[k] = scale * sum;
            scale *= 0.5;
        }
        phi = next;
    }
    phi
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

    /// An overdamped mode's free motion, the two real exponentials (Clough & Penzien, Eq. 2-53
    /// in the form q = ((v0 - l2 q0) e^(l1 t) - (v0 - l1 q0) e^(l2 t)) / (l1 - l2), l1,2 = -zeta
    /// omega +- omega sqrt(zeta^2 - 1)), and critical damping's q = e^(-omega t) (q0 + (v0 + omega
    /// q0) t), for damping ratios from 1 to the 1.4e6 that rayleigh_beta = 1 gives the full
    /// basis's top mode (2.8e6 rad/s) and steps far beyond the series' reach (c h up to 1e13).
    /// The roots are taken without cancellation (l1 = omega^2 / l2); 1e-12 of the start's
    /// amplitude covers the doublings' round-off (about 45 of them, a few eps each).
    #[test]
    fn an_overdamped_mode_creeps_as_its_two_exponentials_at_any_step() {
        let cases = [(50.0, 1.0, 0.7), (50.0, 1.5, 0.7), (4e4, 22.0, 2.3e-5), (4e4, 1e3, 1e-3), (2.8e6, 1.4e6, 3e-4)];
        for (w, zeta, h) in cases {
            let (q0, v0) = (0.3, -2.0);
            let s = ModeStep::new(w * w, 2.0 * zeta * w, h);
            let (q, v, _) = s.apply(q0, v0, 0.0, 0.0);
            let (exact_q, exact_v) = if zeta == 1.0 {
                let e = (-w * h).exp();
                (e * (q0 + (v0 + w * q0) * h), e * (v0 - w * (v0 + w * q0) * h))
            } else {
                let l2 = -w * (zeta + (zeta * zeta - 1.0).sqrt());
                let l1 = w * w / l2;
                let (e1, e2) = ((l1 * h).exp(), (l2 * h).exp());
                let (k1, k2) = ((v0 - l2 * q0) / (l1 - l2), (v0 - l1 * q0) / (l1 - l2));
                (k1 * e1 - k2 * e2, k1 * l1 * e1 - k2 * l2 * e2)
            };
            let amplitude = q0.abs() + v0.abs() / w;
            assert!((q - exact_q).abs() < 1e-12 * amplitude, "w {w} zeta {zeta} h {h}: {q} vs {exact_q}");
            assert!((v - exact_v).abs() < 1e-12 * amplitude * w, "w {w} zeta {zeta} h {h}: {v} vs {exact_v}");
        }
    }

    /// An overdamped mode under a constant force creeps to its static deflection f / omega^2:
    /// psi_0 = (1 - A) / omega^2 with A from the exponentials (where |l1| h >= 0.5, so that
    /// 1 - A keeps its digits), and every coefficient keeps the equation's integral identity
    /// omega^2 int q = int f - dv - c dq; both to 1e-12 relative (round-off of the doublings).
    #[test]
    fn an_overdamped_mode_under_a_force_creeps_to_its_static_deflection() {
        for (w, zeta, h) in [(1e4f64, 1e3f64, 0.1f64), (1e4, 3.0, 1e-3), (2.8e6, 1.4e6, 0.5)] {
            let (w2, c) = (w * w, 2.0 * zeta * w);
            let l2 = -w * (zeta + (zeta * zeta - 1.0).sqrt());
            let l1 = w2 / l2;
            let a = (-l2 * (l1 * h).exp() + l1 * (l2 * h).exp()) / (l1 - l2);
            let s = ModeStep::new(w2, c, h);
            let expected = (1.0 - a) / w2;
            assert!((s.q[2] - expected).abs() < 1e-12 * expected, "w {w} zeta {zeta}: {} vs {expected}", s.q[2]);
            let (q0, v0, f0, r) = (0.01, -0.5, 30.0, 1e4);
            let (q, v, i) = s.apply(q0, v0, f0, r);
            let lhs = w2 * i;
            let rhs = f0 * h + 0.5 * r * h * h - (v - v0) - c * (q - q0);
            let scale = (f0 * h).abs() + 0.5 * r * h * h + c * (q.abs() + q0.abs());
            assert!((lhs - rhs).abs() < 1e-12 * scale, "w {w} zeta {zeta}: {lhs} vs {rhs}");
        }
    }

    /// The phi functions against their closed forms phi_1 = (e^z - 1) / z and phi_2 = (e^z - 1 -
    /// z) / z^2 (with exp_m1: no cancellation for |z| >= 1, where phi_2's own is below 2 eps) on
    /// both sides of the switch at z = -8, and each phi_n against phi_n(0) = 1/n! at z -> 0;
    /// 1e-14 relative.
    #[test]
    fn the_phi_functions_match_their_closed_forms() {
        for z in [-1.0, -3.0, -7.99, -8.01, -50.0, -1e6, -1e13] {
            let phi = phi_functions(z);
            let phi1 = z.exp_m1() / z;
            let phi2 = (z.exp_m1() - z) / (z * z);
            assert!((phi[1] - phi1).abs() <= 1e-14 * phi1, "z {z}: {} vs {phi1}", phi[1]);
            assert!((phi[2] - phi2).abs() <= 1e-14 * phi2, "z {z}: {} vs {phi2}", phi[2]);
            assert!(phi.iter().all(|p| *p >= 0.0 && p.is_finite()), "z {z}: {phi:?}");
        }
        let phi = phi_functions(-1e-9);
        for (n, p) in phi.iter().enumerate() {
            let exact = INVERSE_FACTORIALS[n];
            assert!((p - exact).abs() <= 1e-8 * exact, "n {n}: {p} vs {exact}");
        }
    }

    /// Where the roots part by 1 / h, the two forms of an overdamped mode's responses (the
    /// roots apart, and the doublings) agree: all nine psi to 1e-13 relative (the doublings'
    /// loss here, c h = 7, is about 2^4 eps; a 80-digit series gave both to 3e-16).
    #[test]
    fn the_overdamped_forms_agree_where_the_roots_part() {
        let (w, zeta) = (100.0f64, 1.01f64);
        let (w2, c) = (w * w, 2.0 * zeta * w);
        // s as overdamped_responses takes it, so that the two calls fall either side.
        let s = ((0.5 * c - w) * (0.5 * c + w)).sqrt();
        let h = 1.0 / (2.0 * s);
        // Two ulps either side of the switch (psi_6 ~ h^8 moves by 4e-15 between them).
        let (above, below) = (f64::from_bits(h.to_bits() + 2), f64::from_bits(h.to_bits() - 2));
        assert!(2.0 * s * above >= 1.0 && 2.0 * s * below < 1.0);
        let apart = overdamped_responses(w2, c, above);
        let close = overdamped_responses(w2, c, below);
        for (k, (a, b)) in apart.iter().zip(close).enumerate() {
            assert!((a - b).abs() <= 1e-13 * a.abs().max(b.abs()), "psi_{}: {a} vs {b}", k as i32 - 2);
        }
    }

    /// q'' + c q' + omega^2 q = f(t) integrated by the classical Runge-Kutta method at h / 20 000,
    /// with int q, int q s and int q s^2 (s = t/h) alongside: (q, v, int q, int q s, int q s^2).
    fn runge_kutta(w2: f64, c: f64, h: f64, q0: f64, v0: f64, f: impl Fn(f64) -> f64) -> [f64; 5] {
        let n = 20_000;
        let dt = h / n as f64;
        let rate = |t: f64, y: &[f64; 5]| {
            let s = t / h;
            [y[1], f(t) - c * y[1] - w2 * y[0], y[0], y[0] * s, y[0] * s * s]
        };
        let mut y = [q0, v0, 0.0, 0.0, 0.0];
        for i in 0..n {
            let t = i as f64 * dt;
            let add = |y: &[f64; 5], k: &[f64; 5], a: f64| std::array::from_fn::<f64, 5, _>(|j| y[j] + a * k[j]);
            let k1 = rate(t, &y);
            let k2 = rate(t + dt / 2.0, &add(&y, &k1, dt / 2.0));
            let k3 = rate(t + dt / 2.0, &add(&y, &k2, dt / 2.0));
            let k4 = rate(t + dt, &add(&y, &k3, dt));
            y = std::array::from_fn(|j| y[j] + dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]));
        }
        y
    }

    /// The contact stage's coefficients against a direct integration of the equation (classical
    /// Runge-Kutta at h / 20 000: its error (omega dt)^4 is below 1e-12 of the values here), for
    /// every input at once (q0, v0, f0 + r t + g2 s^2 + g3 s^3), on both sides of the switch
    /// between the series and the recurrence, far above it (omega h = 40), and for the rigid mode.
    /// Tolerance 1e-9 of each quantity's own scale: the recurrence's loss at the switch is ~200 eps.
    #[test]
    fn the_cubic_forcings_responses_and_moments_match_a_direct_integration() {
        let cases = [
            (10.0, 0.02, 0.01),
            (10.0, 0.02, 0.3),
            (200.0, 0.05, 0.99 * CUBIC_SERIES_BELOW / 200.0),
            (200.0, 0.05, 1.01 * CUBIC_SERIES_BELOW / 200.0),
            (4e4, 0.01, 1e-3),
            (0.0, 0.0, 0.5),
            // Overdamped (Rayleigh's stiffness-proportional damping): critical, and beyond, with
            // c h up to 400 (Runge-Kutta's own step takes c dt = 0.02).
            (200.0, 1.0, 0.05),
            (200.0, 3.0, 0.05),
            (200.0, 50.0, 0.02),
        ];
        for (w, zeta, h) in cases {
            let (w2, c) = (w * w, 2.0 * zeta * w);
            let linear = ModeStep::new(w2, c, h);
            let cubic = CubicStep::new(w2, c, h, &linear);
            let (q0, v0, f0, r, g2, g3) = (0.3, -2.0, 5.0, 40.0 / h, -7.0, 3.0);
            let inputs = [q0, v0, f0, r, g2, g3];
            let expected = runge_kutta(w2, c, h, q0, v0, |t| {
                let s = t / h;
                f0 + r * t + g2 * s * s + g3 * s * s * s
            });
            let (q, v, integral) = linear.apply(q0, v0, f0, r);
            let q = q + g2 * cubic.q[0] + g3 * cubic.q[1];
            let v = v + g2 * cubic.v[0] + g3 * cubic.v[1];
            let integral = integral + g2 * cubic.integral[0] + g3 * cubic.integral[1];
            let moment = |row: usize| cubic.moments[row].iter().zip(inputs).map(|(m, x)| m * x).sum::<f64>();
            let got = [q, v, integral, moment(0), moment(1)];
            // Scales: the largest term of each quantity.
            let amplitude = expected[0].abs().max(q0.abs()).max(f0.abs().max(g2.abs()) / w2.max(1.0 / (h * h)));
            let scales = [amplitude, amplitude / h, amplitude * h, amplitude * h, amplitude * h];
            for (k, ((g, e), scale)) in got.iter().zip(expected).zip(scales).enumerate() {
                assert!((g - e).abs() <= 1e-9 * scale, "w {w} h {h}, quantity {k}: {g} vs {e}");
            }
        }
    }

    /// Where both apply, just past the switch, the series and the recurrence give the same
    /// coefficients (1e-12 relative: the recurrence's loss there is ~200 eps).
    #[test]
    fn the_cubic_series_and_recurrence_agree_at_the_switch() {
        let (w, zeta) = (200.0, 0.05);
        let (w2, c) = (w * w, 2.0 * zeta * w);
        let h = CUBIC_SERIES_BELOW / w;
        let above = CubicStep::new(w2, c, h * (1.0 + 1e-12), &ModeStep::new(w2, c, h * (1.0 + 1e-12)));
        let below = CubicStep::new(w2, c, h * (1.0 - 1e-12), &ModeStep::new(w2, c, h * (1.0 - 1e-12)));
        let flat = |x: &CubicStep| {
            let mut v = vec![x.q[0], x.q[1], x.v[0], x.v[1], x.integral[0], x.integral[1]];
            v.extend(x.moments.iter().flatten());
            v
        };
        for (k, (a, b)) in flat(&above).into_iter().zip(flat(&below)).enumerate() {
            assert!((a - b).abs() <= 1e-10 * a.abs().max(b.abs()), "coefficient {k}: {a} vs {b}");
        }
    }

    /// The one series of the stepper (`series_responses`: nine responses from one sequence,
    /// reciprocals from tables) against the term-by-term series of each unit response
    /// (`ModeStep::series`, its divisions kept) for the twelve coefficients, and against the
    /// contact stage's own series ([`CubicStep::new`] from the same [`ModeStep`]) for the rest:
    /// undamped, damped, critically damped and the rigid mode, from a 1 ns retake to the switch
    /// (omega h = 1/2), agree to 1e-14 of each coefficient's own scale (a few eps of sums of
    /// alternating terms at most 1 in size; both series stop below 1e-17 of the first term).
    #[test]
    fn one_series_gives_every_response_of_a_short_step() {
        let cases = [
            (2e5, 0.03, 1e-9),
            (2e5, 0.03, 1e-6),
            (2e5, 0.03, 0.499 / 2e5),
            (1e3, 0.0, 3e-4),
            (50.0, 1.0, 0.004),
            (50.0, 5.0, 0.001),
            (0.0, 0.0, 0.02),
        ];
        for (w, zeta, h) in cases {
            let (w2, c) = (w * w, 2.0 * zeta * w);
            let (fast, psi) = ModeStep::with_responses(w2, c, h);
            let psi = psi.expect("a short step's coefficients come from the series");
            let reference = ModeStep::series(w2, c, h);
            // Each coefficient's natural size (its series' first term): q per q0, v0, f0, r: 1, h,
            // h^2/2, h^3/6; v: omega^2 h, 1, h, h^2/2; int q: h, h^2/2, h^3/6, h^4/24.
            let natural = [
                [1.0, h, h * h / 2.0, h * h * h / 6.0],
                [w2 * h, 1.0, h, h * h / 2.0],
                [h, h * h / 2.0, h * h * h / 6.0, h * h * h * h / 24.0],
            ];
            let rows = [(&fast.q, &reference.q), (&fast.v, &reference.v), (&fast.integral, &reference.integral)];
            for (row, (got, want)) in rows.into_iter().enumerate() {
                for j in 0..4 {
                    let tolerance = 1e-14 * want[j].abs().max(natural[row][j]);
                    assert!(
                        (got[j] - want[j]).abs() <= tolerance,
                        "w {w} zeta {zeta} h {h}, coefficient {row}/{j}: {} vs {}",
                        got[j],
                        want[j]
                    );
                }
            }
            let from_responses = CubicStep::from_responses(c, h, &psi);
            let own = CubicStep::new(w2, c, h, &reference);
            let flat = |x: &CubicStep| {
                let mut v = vec![x.q[0], x.q[1], x.v[0] * h, x.v[1] * h, x.integral[0] / h, x.integral[1] / h];
                v.extend(x.moments.iter().flat_map(|row| {
                    // Per q0, v0, f0, r, s^2, s^3: scaled to O(1) by h, 1, h^-1, h^-2, 1, 1 (times 1/h for
                    // the integral).
                    [
                        row[0] / h,
                        row[1] / (h * h),
                        row[2] / (h * h * h),
                        row[3] / (h * h * h * h),
                        row[4] / h,
                        row[5] / h,
                    ]
                }));
                v
            };
            let (a, b) = (flat(&from_responses), flat(&own));
            let size = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (k, (x, y)) in a.iter().zip(&b).enumerate() {
                assert!((x - y).abs() <= 1e-14 * size, "w {w} zeta {zeta} h {h}, cubic coefficient {k}: {x} vs {y}");
            }
        }
    }
}

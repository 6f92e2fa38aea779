//! The production stepper: the modified linear acceleration method (Eqs. 7-11) in the beams'
//! own modal coordinates. Out of contact S, P, Q and R are diagonal; in contact the bar adds
//! k_c b b^T to K, and S^-1 follows from Sherman-Morrison. Every step costs O(n).
//!
//! The converged method's runs with the linear bar advance each mode exactly instead
//! ([`super::exact`]): out of contact under its loads, in contact under the bar's force taken as
//! the cubic through its values and rates at the step's ends, the end force and rate from one
//! 2x2 system (the same rank-one structure), O(n) per step at any step size.

use nalgebra::DVector;

use super::contact::Stage;
use super::exact::{CubicStep, ModeStep};
use super::kinematics::{Energies, Excitation, Kinematics, Stepper, SupportAndTips};
use super::modal::ModalSystem;
use super::static_correction::CONTACT;
use crate::model::contact_law::SeriesForce;
use crate::model::system::PROBES;
use crate::model::{Model, Probe, REACTIONS};

/// S^-1 of one (stage, dt): diagonal part and the Sherman-Morrison correction.
#[derive(Clone, Debug)]
struct StageInverse {
    dt: f64,
    /// 1 / (1 + dt/2 c_i + dt^2/6 omega_i^2).
    diagonal_inverse: DVector<f64>,
    /// D^-1 b.
    corrected: DVector<f64>,
    /// beta / (1 + beta b^T D^-1 b), beta = k_c dt^2 / 6 (0 out of contact).
    factor: f64,
    /// b^T D^-1 b (a nonlinear contact law's response of the gap to its force).
    flexibility: f64,
}

/// Linear acceleration method in modal coordinates, O(n) per step.
#[derive(Clone, Debug)]
pub struct ModalStepper {
    system: ModalSystem,
    /// Phi^T M: physical to modal coordinates.
    projector: std::sync::Arc<nalgebra::DMatrix<f64>>,
    /// The probe functionals as contiguous columns (modal probes transposed), for O(n) dots.
    probe_columns: nalgebra::DMatrix<f64>,
    /// The same functionals per coordinate, the probes side by side (padded to eight), for
    /// [`probe_dots`].
    probe_rows: Vec<[f64; 8]>,
    /// The three support reactions' rows and the two tip-velocity probes, interleaved per
    /// coordinate, for one pass over q, v and a (see [`DetailRow`]).
    detail_rows: Vec<DetailRow>,
    /// The most recent S^-1 of each stage (index 0 free, 1 contact).
    cache: [Option<StageInverse>; 2],
    /// Modal load for `load_excitation`.
    load: DVector<f64>,
    /// The supports' combined modal inertia load sum_j a_j Phi^T x_j for `load_excitation` (its
    /// potential is the energy account's inertial potential).
    support_load: DVector<f64>,
    /// The static correction's gap shift b^T R f_ext for `load_excitation`, m (0 for a full basis).
    shift: f64,
    load_excitation: Option<Excitation>,
    /// The modal load and the supports' load of `next_excitation`, computed ahead of the steps
    /// under it ([`Stepper::equilibrium_acceleration`] where the load jumps: a sea's record
    /// row): the next step's [`ModalStepper::refresh_load`] takes them instead of computing
    /// them again, and a measurement under it reads the supports' load from here.
    next_load: DVector<f64>,
    next_support_load: DVector<f64>,
    next_excitation: Option<Excitation>,
    /// Work vectors: z of Eq. (8) and D^-1 f.
    z: DVector<f64>,
    y: DVector<f64>,
    /// A third work vector: each mode's share of the end's gap acceleration in a nonlinear law's
    /// exact contact step.
    w: DVector<f64>,
    /// Exact modal advance (the converged method with the linear bar) instead of Eqs. (7)-(11).
    exact: bool,
    /// Measurements take the energy terms (see [`Stepper::keep_energies`]).
    energies: bool,
    /// Exact coefficients of the step sizes met (the stages' own, a located contact change's, a
    /// landing on an output time), with how often and when each was last used: [`EXACT_SLOTS`]
    /// of them, boxed (the stepper moves with its run).
    exact_cache: Box<[ExactStage]>,
    /// The step size of each slot of `exact_cache` (NaN: none yet), side by side for the lookup.
    exact_sizes: [f64; EXACT_SLOTS],
    /// The slot of the last exact step (the next takes the same size as a rule).
    exact_last: usize,
    /// Exact steps taken so far: the clock of [`ExactStage::last_used`].
    exact_clock: u64,
    /// The damping's work over the last exact step, J (None for the linear acceleration method;
    /// 0 without an energy account, but for a nonlinear law's contact steps).
    last_dissipation: Option<f64>,
    /// The estimated departure of the bar's force from the cubic the last exact contact step
    /// assumed, N.
    last_force_error: Option<f64>,
    /// |probe row| omega_i^4 per coordinate and probe (the exact advance's bound on the fourth
    /// derivative of each probe out of contact, per unit of modal amplitude).
    fourth_derivative: Vec<[f64; 8]>,
}

/// The exact coefficients of every mode for one step size (dt = NaN: none yet).
#[derive(Clone, Debug)]
struct ExactStage {
    dt: f64,
    /// Each mode's coefficients as twelve columns (q(h), v(h), int q; per q0, v0, f0, r), so that
    /// the step's loop over the modes runs in the CPU's vectors.
    columns: [Vec<f64>; 12],
    /// The contact stage's [`CubicStep`]s as eighteen columns (q(h), v(h), int q per s^2 and
    /// s^3; the two moments per q0, v0, f0, r, s^2, s^3): empty until a contact step takes this
    /// size.
    cubic_columns: [Vec<f64>; 18],
    /// The contact step's 2x2 system for the bar's end force and rate (see `BarSolve`).
    bar: BarSolve,
    /// Steps taken with them.
    hits: u64,
    /// The stepper's exact step count at their last use (0: never), for the eviction.
    last_used: u64,
}

impl Default for ExactStage {
    fn default() -> Self {
        ExactStage {
            dt: f64::NAN,
            columns: Default::default(),
            cubic_columns: Default::default(),
            bar: BarSolve::default(),
            hits: 0,
            last_used: 0,
        }
    }
}

/// The end force P1 and Y = dt P1' of an exact contact step solve
/// `[m11 m12; m21 m22] [P1; Y] = [k (g + o + ag (dt P0' + P0) + bg P0); dt k (gv + o' + av (dt P0' + P0) + bv P0)]`
/// (g, gv: the gap and its rate at the end without the bar's change; o, o': the gap's offset and
/// its rate), from the bar's cubic force: its departure from the chord alpha H10 + beta H11 with
/// alpha = dt P0' - (P1 - P0), beta = Y - (P1 - P0) forces mode i by -b_i (alpha s + (-2 alpha -
/// beta) s^2 + (alpha + beta) s^3).
#[derive(Clone, Copy, Debug, Default)]
struct BarSolve {
    /// The end gap's response to alpha and to beta (through the chord's -alpha s and the s^2,
    /// s^3 forcings), m/N, and the end gap rate's, m/(N s).
    ag: f64,
    bg: f64,
    av: f64,
    bv: f64,
    /// The end gap's and its rate's response to the end force through the chord, m/N, m/(N s).
    ramp: f64,
    vramp: f64,
    /// The end gap acceleration b^T a1's response to the end force (its own -b^T b and the
    /// modes' -c v1 - omega^2 q1), to alpha and to beta, 1/(kg): a nonlinear law's step
    /// ([`ModalStepper::law_contact_step`]).
    af: f64,
    aa: f64,
    ab: f64,
    /// b^T b, 1/kg.
    bb: f64,
    m11: f64,
    m12: f64,
    m21: f64,
    m22: f64,
    determinant: f64,
}

/// The sums over the modes behind a [`BarSolve`], added mode by mode in the modes' order.
#[derive(Clone, Copy, Debug, Default)]
struct BarSums {
    /// sum b^2 of the ramp's q(h) and v(h), of the s^2 and s^3 forcings' q(h) and v(h).
    fr: f64,
    vr: f64,
    f2: f64,
    f3: f64,
    v2: f64,
    v3: f64,
    /// sum b^2 (c v + omega^2 q) of the ramp's, the s^2 and the s^3 responses, and b^T b.
    ar: f64,
    a2: f64,
    a3: f64,
    bb: f64,
}

impl BarSums {
    /// Adds one mode (contact coefficient `b`, omega^2 `w2`, damping `damping`) with its step's
    /// coefficients.
    fn add(&mut self, b: f64, (w2, damping): (f64, f64), m: &ModeStep, c: &CubicStep) {
        let b2 = b * b;
        self.fr += b2 * m.q[3];
        self.vr += b2 * m.v[3];
        self.f2 += b2 * c.q[0];
        self.f3 += b2 * c.q[1];
        self.v2 += b2 * c.v[0];
        self.v3 += b2 * c.v[1];
        self.ar += b2 * (damping * m.v[3] + w2 * m.q[3]);
        self.a2 += b2 * (damping * c.v[0] + w2 * c.q[0]);
        self.a3 += b2 * (damping * c.v[1] + w2 * c.q[1]);
        self.bb += b2;
    }
}

impl BarSolve {
    fn new(s: &ModalSystem, dt: f64, sums: &BarSums) -> BarSolve {
        let BarSums { fr, vr, f2, f3, v2, v3, ar, a2, a3, bb } = *sums;
        let (ramp, vramp) = (fr / dt, vr / dt);
        // The end gap (rate) per alpha and per beta: -alpha s through the ramp, and the s^2, s^3
        // forcings.
        let (ag, bg) = (2.0 * f2 - f3 - ramp, f2 - f3);
        let (av, bv) = (2.0 * v2 - v3 - vramp, v2 - v3);
        let k = s.bar_stiffness;
        let m11 = 1.0 + k * (ramp + ag + bg);
        let m12 = -k * bg;
        let m21 = dt * k * (vramp + av + bv);
        let m22 = 1.0 - dt * k * bv;
        // The end acceleration a1 = f1 - c v1 - omega^2 q1 with f1 = F - b P1: per P1 its own -b^T b
        // and the ramp's response; per alpha and beta the chord's and the cubic's.
        let af = -bb + ar / dt;
        let (aa, ab) = (-(2.0 * a2 - a3 - ar / dt), -(a2 - a3));
        BarSolve { ag, bg, av, bv, ramp, vramp, af, aa, ab, bb, m11, m12, m21, m22, determinant: m11 * m22 - m12 * m21 }
    }
}

impl ExactStage {
    /// The coefficients of step `dt` in place, with the contact stage's when `contact`: one pass
    /// over the modes, each mode's responses computed once for both ([`ModeStep::with_responses`]:
    /// a step cut at a contact change, at a motion row or at a peak's instant is a new size, and
    /// its coefficients cost more than the step).
    fn reset(&mut self, s: &ModalSystem, dt: f64, contact: bool) {
        let n = s.omega2.len().min(s.damping.len()).min(s.contact.len());
        for column in &mut self.columns {
            column.resize(n, 0.0);
        }
        // Each value is written below: a column already of the length keeps it (no zero fill).
        for column in &mut self.cubic_columns {
            column.resize(if contact { n } else { 0 }, 0.0);
        }
        let modes = (&s.omega2.as_slice()[..n], &s.damping.as_slice()[..n], &s.contact.as_slice()[..n]);
        let sums = mode_coefficients(modes, dt, &mut self.columns, &mut self.cubic_columns);
        if contact {
            self.bar = BarSolve::new(s, dt, &sums);
        }
        self.dt = dt;
        self.hits = 0;
        self.last_used = 0;
    }

    /// Books one step taken with these coefficients at `clock` (the stepper's exact steps so far).
    fn used(&mut self, clock: u64) {
        self.hits += 1;
        self.last_used = clock;
    }

    /// Mode `i`'s coefficients back from the twelve columns (the same numbers).
    fn mode(&self, i: usize) -> ModeStep {
        let c = |k: usize| self.columns[k][i];
        ModeStep { q: [c(0), c(1), c(2), c(3)], v: [c(4), c(5), c(6), c(7)], integral: [c(8), c(9), c(10), c(11)] }
    }

    /// Mode `i`'s contact coefficients into the eighteen columns.
    #[inline(always)]
    fn set_cubic(&mut self, i: usize, c: &CubicStep) {
        set_cubic(&mut self.cubic_columns, i, c);
    }

    /// The contact stage's coefficients of this step size where a free step's reset left them
    /// out (a step size both stages take): the very numbers a contact step's [`Self::reset`]
    /// gives (a series mode's from the same series, [`ModeStep::with_responses`]), so that the
    /// coefficients of a size never depend on which stage met it first or on what the cache
    /// evicted in between.
    fn prepare_contact(&mut self, s: &ModalSystem) {
        let n = self.columns[0].len();
        if self.cubic_columns[0].len() == n || n == 0 {
            return;
        }
        let dt = self.dt;
        for column in &mut self.cubic_columns {
            column.resize(n, 0.0);
        }
        let mut sums = BarSums::default();
        for i in 0..n {
            let (w2, c) = (s.omega2[i], s.damping[i]);
            let mode = self.mode(i);
            let cubic = match ModeStep::with_responses(w2, c, dt).1 {
                Some(psi) => CubicStep::from_responses(c, dt, &psi),
                None => CubicStep::new(w2, c, dt, &mode),
            };
            self.set_cubic(i, &cubic);
            sums.add(s.contact[i], (w2, c), &mode, &cubic);
        }
        self.bar = BarSolve::new(s, dt, &sums);
    }
}

impl ModalStepper {
    /// A stepper over the modal form of `model`.
    pub fn new(model: &Model, system: ModalSystem) -> ModalStepper {
        let projector = std::sync::Arc::new(projector(model, &system));
        Self::with_projector(system, projector)
    }

    /// [`Self::new`] with `system`'s [`projector`] for its model already at hand (a sweep's runs
    /// of one geometry share it).
    pub fn with_projector(system: ModalSystem, projector: std::sync::Arc<nalgebra::DMatrix<f64>>) -> ModalStepper {
        let n = system.dofs();
        let probe_columns = system.probes.transpose();
        let [r0, r1, r2] = &system.reactions;
        let detail_rows = (0..n)
            .map(|i| DetailRow {
                displacement: [r0.displacement[i], r1.displacement[i], r2.displacement[i], 0.0],
                velocity: [
                    r0.velocity[i],
                    r1.velocity[i],
                    r2.velocity[i],
                    probe_columns[(i, 0)],
                    probe_columns[(i, 2)],
                    0.0,
                ],
                acceleration: [r0.acceleration[i], r1.acceleration[i], r2.acceleration[i], 0.0],
            })
            .collect();
        let probe_rows =
            (0..n).map(|i| std::array::from_fn(|k| if k < PROBES { probe_columns[(i, k)] } else { 0.0 })).collect();
        ModalStepper {
            system,
            projector,
            probe_columns,
            probe_rows,
            detail_rows,
            cache: [None, None],
            load: DVector::zeros(n),
            support_load: DVector::zeros(n),
            shift: 0.0,
            load_excitation: None,
            next_load: DVector::zeros(n),
            next_support_load: DVector::zeros(n),
            next_excitation: None,
            z: DVector::zeros(n),
            y: DVector::zeros(n),
            w: DVector::zeros(n),
            exact: false,
            energies: true,
            exact_cache: (0..EXACT_SLOTS).map(|_| ExactStage::default()).collect(),
            exact_sizes: [f64::NAN; EXACT_SLOTS],
            exact_last: 0,
            exact_clock: 0,
            last_dissipation: None,
            last_force_error: None,
            fourth_derivative: Vec::new(),
        }
    }

    /// The same stepper advancing each mode exactly ([`super::exact`]) when `exact` (the
    /// converged method), whatever the contact law.
    pub fn with_exact(mut self, exact: bool) -> ModalStepper {
        self.exact = exact;
        if self.exact {
            let s = &self.system;
            self.fourth_derivative = (0..s.dofs())
                .map(|i| {
                    std::array::from_fn(|k| {
                        if k < PROBES {
                            self.probe_columns[(i, k)].abs() * (s.omega2[i] * s.omega2[i])
                        } else {
                            0.0
                        }
                    })
                })
                .collect();
        }
        self
    }

    /// True when the stepper advances each mode exactly.
    pub fn is_exact(&self) -> bool {
        self.exact
    }

    /// The modal system (modes, damping, modal probes).
    pub fn system(&self) -> &ModalSystem {
        &self.system
    }
}

/// Phi^T M: a physical state's modal coordinates in `system`'s basis of `model`.
pub fn projector(model: &Model, system: &ModalSystem) -> nalgebra::DMatrix<f64> {
    system.shapes().transpose() * model.mass()
}

/// The stage's modal loads and the modes' parameters (omega^2, damping, contact coefficient b),
/// each `n` long.
#[derive(Clone, Copy)]
struct ModeInputs<'a> {
    load: &'a [f64],
    omega2: &'a [f64],
    damping: &'a [f64],
    contact: &'a [f64],
}

/// One state's modal arrays and the stage's [`ModeInputs`], each `n` long. The kernels that
/// write q, v and a take them as arguments of their own, never inside a struct: a `&mut`
/// argument overlaps nothing else, so the compiler needs no run-time check of the written arrays
/// against the read ones (on the contact step's 34 arrays a thousand instructions a call, a
/// third of its cost).
struct ModeArrays<'a> {
    q: &'a mut [f64],
    v: &'a mut [f64],
    a: &'a mut [f64],
    inputs: ModeInputs<'a>,
}

impl<'a> ModeArrays<'a> {
    /// The arrays of `state` with the modal `load` and `system`'s parameters, the state's length.
    fn new(state: &'a mut Kinematics, load: &'a DVector<f64>, system: &'a ModalSystem) -> ModeArrays<'a> {
        let n = state.displacement.len();
        ModeArrays {
            q: &mut state.displacement.as_mut_slice()[..n],
            v: &mut state.velocity.as_mut_slice()[..n],
            a: &mut state.acceleration.as_mut_slice()[..n],
            inputs: ModeInputs {
                load: &load.as_slice()[..n],
                omega2: &system.omega2.as_slice()[..n],
                damping: &system.damping.as_slice()[..n],
                contact: &system.contact.as_slice()[..n],
            },
        }
    }
}

/// One exact step out of contact ([`ModalStepper::exact_step`]) over every mode, in the widest
/// vectors the CPU has (chosen once at run time; no fused multiply-add, so the same bits whichever
/// runs): each mode under the forcing linear from its start's f0 = a + c v + omega^2 q to its end
/// load; with `WORK`, `dissipated[i]` gets mode i's damping work over the step (0 for an undamped
/// mode; without, `dissipated` is left alone and the integral of q is not formed).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn free_exact_step<const WORK: bool>(
    q: &mut [f64],
    v: &mut [f64],
    a: &mut [f64],
    dissipated: &mut [f64],
    m: ModeInputs,
    columns: &[Vec<f64>; 12],
    dt: f64,
) {
    let n = q.len();
    let (v, a) = (&mut v[..n], &mut a[..n]);
    let (load, omega2, damping) = (&m.load[..n], &m.omega2[..n], &m.damping[..n]);
    let dissipated = &mut dissipated[..if WORK { n } else { 0 }];
    let c: [&[f64]; 12] = std::array::from_fn(|k| &columns[k][..n]);
    let inv_dt = 1.0 / dt;
    for i in 0..n {
        let (q0, v0) = (q[i], v[i]);
        let f0 = a[i] + damping[i] * v0 + omega2[i] * q0;
        let f1 = load[i];
        let r = (f1 - f0) * inv_dt;
        // ModeStep::apply, term by term in its order.
        let q1 = c[0][i] * q0 + c[1][i] * v0 + c[2][i] * f0 + c[3][i] * r;
        let v1 = c[4][i] * q0 + c[5][i] * v0 + c[6][i] * f0 + c[7][i] * r;
        if WORK {
            let integral = c[8][i] * q0 + c[9][i] * v0 + c[10][i] * f0 + c[11][i] * r;
            // The mode's energy balance: c int v^2 = -(E1 - E0) + int v f, with
            // int v f = f0 (q1 - q0) + r (dt q1 - int q).
            let energy_change = 0.5 * (v1 * v1 - v0 * v0) + 0.5 * omega2[i] * (q1 * q1 - q0 * q0);
            let work = -energy_change + f0 * (q1 - q0) + r * (dt * q1 - integral);
            dissipated[i] = if damping[i] != 0.0 { work } else { 0.0 };
        }
        q[i] = q1;
        v[i] = v1;
        a[i] = f1 - damping[i] * v1 - omega2[i] * q1;
    }
}

/// The shares of each mode in the end's gap and gap rate of an exact contact step without the
/// bar's change over it (`gap[i]`, `rate[i]`; see [`ModalStepper::contact_step`]), in the CPU's
/// widest vectors (no fused multiply-add: the same bits whichever runs).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn contact_free_response(m: &ModeArrays, columns: &[Vec<f64>; 12], inv_dt: f64, gap: &mut [f64], rate: &mut [f64]) {
    let n = m.q.len();
    let (q, v, a) = (&m.q[..n], &m.v[..n], &m.a[..n]);
    let ModeInputs { load, omega2, damping, contact: b } = m.inputs;
    let (load, omega2, damping, b) = (&load[..n], &omega2[..n], &damping[..n], &b[..n]);
    let (gap, rate) = (&mut gap[..n], &mut rate[..n]);
    let c: [&[f64]; 8] = std::array::from_fn(|k| &columns[k][..n]);
    for i in 0..n {
        let f0 = a[i] + damping[i] * v[i] + omega2[i] * q[i];
        let r = (load[i] - f0) * inv_dt;
        gap[i] = b[i] * (c[0][i] * q[i] + c[1][i] * v[i] + c[2][i] * f0 + c[3][i] * r);
        rate[i] = b[i] * (c[4][i] * q[i] + c[5][i] * v[i] + c[6][i] * f0 + c[7][i] * r);
    }
}

/// [`contact_free_response`] with each mode's share of the end's gap acceleration too,
/// b_i (F_i - c_i v_i - omega_i^2 q_i) (`acceleration[i]`; a nonlinear law's step).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn contact_free_response_accelerated(
    m: &ModeArrays,
    columns: &[Vec<f64>; 12],
    inv_dt: f64,
    gap: &mut [f64],
    rate: &mut [f64],
    acceleration: &mut [f64],
) {
    let n = m.q.len();
    let (q, v, a) = (&m.q[..n], &m.v[..n], &m.a[..n]);
    let ModeInputs { load, omega2, damping, contact: b } = m.inputs;
    let (load, omega2, damping, b) = (&load[..n], &omega2[..n], &damping[..n], &b[..n]);
    let (gap, rate, acceleration) = (&mut gap[..n], &mut rate[..n], &mut acceleration[..n]);
    let c: [&[f64]; 8] = std::array::from_fn(|k| &columns[k][..n]);
    for i in 0..n {
        let f0 = a[i] + damping[i] * v[i] + omega2[i] * q[i];
        let r = (load[i] - f0) * inv_dt;
        let q1 = c[0][i] * q[i] + c[1][i] * v[i] + c[2][i] * f0 + c[3][i] * r;
        let v1 = c[4][i] * q[i] + c[5][i] * v[i] + c[6][i] * f0 + c[7][i] * r;
        gap[i] = b[i] * q1;
        rate[i] = b[i] * v1;
        acceleration[i] = b[i] * (load[i] - damping[i] * v1 - omega2[i] * q1);
    }
}

/// The bar's force over an exact contact step: its end value, N, and its cubic's departure from
/// the chord (alpha, and the s^2 and s^3 coefficients g2, g3; see [`ModalStepper::contact_step`]).
#[derive(Clone, Copy)]
struct BarForce {
    force: f64,
    alpha: f64,
    g2: f64,
    g3: f64,
}

/// Every mode's exact advance over a contact step of `stage`'s size under `bar`'s force, in the
/// CPU's widest vectors (no fused multiply-add: the same bits whichever runs); with `WORK`,
/// `dissipated[i]` gets mode i's damping work over the step (0 for an undamped mode; without,
/// `dissipated` is left alone and neither the integral of q nor its moments are formed).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn contact_advance<const WORK: bool>(
    q: &mut [f64],
    v: &mut [f64],
    a: &mut [f64],
    dissipated: &mut [f64],
    m: ModeInputs,
    stage: &ExactStage,
    bar: BarForce,
) {
    let n = q.len();
    let (v, a, dissipated) = (&mut v[..n], &mut a[..n], &mut dissipated[..if WORK { n } else { 0 }]);
    let (load, omega2, damping, b) = (&m.load[..n], &m.omega2[..n], &m.damping[..n], &m.contact[..n]);
    let c: [&[f64]; 12] = std::array::from_fn(|k| &stage.columns[k][..n]);
    let cu: [&[f64]; 18] = std::array::from_fn(|k| &stage.cubic_columns[k][..n]);
    let dt = stage.dt;
    let inv_dt = 1.0 / dt;
    for i in 0..n {
        let (q0, v0) = (q[i], v[i]);
        let f0 = a[i] + damping[i] * v0 + omega2[i] * q0;
        let f1 = load[i] - b[i] * bar.force;
        let r = (f1 - f0 - b[i] * bar.alpha) * inv_dt;
        let (c2, c3) = (b[i] * bar.g2, b[i] * bar.g3);
        // ModeStep::apply, term by term in its order, then the cubic's s^2 and s^3 forcings.
        let q1 = c[0][i] * q0 + c[1][i] * v0 + c[2][i] * f0 + c[3][i] * r;
        let v1 = c[4][i] * q0 + c[5][i] * v0 + c[6][i] * f0 + c[7][i] * r;
        let q1 = q1 + c2 * cu[0][i] + c3 * cu[1][i];
        let v1 = v1 + c2 * cu[2][i] + c3 * cu[3][i];
        if WORK {
            // The mode's energy balance: c int v^2 = -(E1 - E0) + int v f, with
            // int v f = f0 (q1 - q0) + r (dt q1 - int q) + c2 (q1 - 2/dt int q s)
            //         + c3 (q1 - 3/dt int q s^2).
            let integral = c[8][i] * q0 + c[9][i] * v0 + c[10][i] * f0 + c[11][i] * r;
            let integral = integral + c2 * cu[4][i] + c3 * cu[5][i];
            let m1 = cu[6][i] * q0 + cu[7][i] * v0 + cu[8][i] * f0 + cu[9][i] * r + cu[10][i] * c2 + cu[11][i] * c3;
            let m2 = cu[12][i] * q0 + cu[13][i] * v0 + cu[14][i] * f0 + cu[15][i] * r + cu[16][i] * c2 + cu[17][i] * c3;
            let energy_change = 0.5 * (v1 * v1 - v0 * v0) + 0.5 * omega2[i] * (q1 * q1 - q0 * q0);
            let work = f0 * (q1 - q0)
                + r * (dt * q1 - integral)
                + c2 * (q1 - 2.0 * inv_dt * m1)
                + c3 * (q1 - 3.0 * inv_dt * m2);
            dissipated[i] = if damping[i] != 0.0 { -energy_change + work } else { 0.0 };
        }
        q[i] = q1;
        v[i] = v1;
        a[i] = f1 - damping[i] * v1 - omega2[i] * q1;
    }
}

/// One coordinate's coefficients in the support reactions (clamp force, clamp moment, hinge
/// force: their displacement, velocity and acceleration rows) and in the tip velocities (arrestor
/// end, bridge end), padded to even lengths so each pair of lanes is one vector operation.
#[derive(Clone, Copy, Debug, Default)]
struct DetailRow {
    displacement: [f64; 4],
    velocity: [f64; 6],
    acceleration: [f64; 4],
}

/// Accumulators of one pass over the [`DetailRow`]s.
#[derive(Clone, Copy, Default)]
struct DetailSums {
    displacement: [f64; 4],
    velocity: [f64; 6],
    acceleration: [f64; 4],
}

impl DetailSums {
    fn add(&mut self, row: &DetailRow, q: f64, v: f64, a: f64) {
        for k in 0..4 {
            self.displacement[k] += row.displacement[k] * q;
            self.acceleration[k] += row.acceleration[k] * a;
        }
        for k in 0..6 {
            self.velocity[k] += row.velocity[k] * v;
        }
    }
}

impl StageInverse {
    /// S^-1 of Eq. (9) for one stage and step: diagonal plus, in contact, the rank-one bar term.
    fn new(s: &ModalSystem, contact: bool, dt: f64) -> StageInverse {
        let diagonal_inverse = s.omega2.zip_map(&s.damping, |w2, c| 1.0 / (1.0 + 0.5 * dt * c + dt * dt / 6.0 * w2));
        let corrected = diagonal_inverse.component_mul(&s.contact);
        let beta = if contact { s.bar_stiffness * dt * dt / 6.0 } else { 0.0 };
        let flexibility = s.contact.dot(&corrected);
        let factor = beta / (1.0 + beta * flexibility);
        StageInverse { dt, diagonal_inverse, corrected, factor, flexibility }
    }
}

impl ModalStepper {
    /// The modal load F = Phi^T (F_g + F_ext + sum_j a_j x_j), the supports' share and the
    /// static correction's gap shift of `excitation`, computed anew only when the tip forces or
    /// the supports' accelerations changed, into the stepper's own vectors (or taken from those
    /// computed ahead for it: `next_load`, the same bits).
    fn refresh_load(&mut self, excitation: &Excitation) {
        if !self.load_excitation.is_some_and(|e| e.same_load(excitation)) {
            let s = &self.system;
            if self.next_excitation.take().is_some_and(|e| e.same_load(excitation)) {
                std::mem::swap(&mut self.load, &mut self.next_load);
                std::mem::swap(&mut self.support_load, &mut self.next_support_load);
            } else {
                s.load_into(excitation, &mut self.load);
                s.support_load_into(excitation, &mut self.support_load);
            }
            self.shift = s.correction.gap_shift(excitation);
            self.load_excitation = Some(*excitation);
        }
    }

    /// Eqs. (7)-(11) for one step; with `MEASURE`, the probes and energies of the new state too
    /// (otherwise zero), summed four lanes at a time.
    fn advance<const MEASURE: bool>(
        &mut self,
        state: &mut Kinematics,
        stage: Stage,
        dt: f64,
        excitation: &Excitation,
    ) -> ([f64; PROBES], Energies) {
        // The modal load F = Phi^T (F_g + F_ext + sum_j a_j x_j) changes only when the tip forces
        // or the supports' accelerations do.
        self.refresh_load(excitation);
        if self.exact {
            self.exact_step(state, stage, dt, excitation);
        } else {
            self.linear_acceleration_step(state, stage, dt, excitation);
        }
        if MEASURE {
            self.measure_state(state, stage, excitation)
        } else {
            ([0.0; PROBES], Energies::default())
        }
    }

    /// Eqs. (7)-(11) for one step.
    fn linear_acceleration_step(&mut self, state: &mut Kinematics, stage: Stage, dt: f64, excitation: &Excitation) {
        // The damping's work is the rate's trapezoid (also between the exact advance's free steps).
        self.last_dissipation = None;
        self.last_force_error = None;
        let contact = stage.is_contact();
        let s = &self.system;
        // S^-1 is recomputed (O(n)) only when the stage's step size changes.
        let slot = &mut self.cache[usize::from(contact)];
        let inv = match slot {
            Some(c) if c.dt == dt => c,
            _ => slot.insert(StageInverse::new(s, contact, dt)),
        };
        // The bar acts on the absolute gap: the beams' relative one plus the supports' offset.
        let gap_offset = excitation.gap_offset;
        let n = state.displacement.len();
        let (dt2_3, dt_2, dt2_6) = (dt * dt / 3.0, 0.5 * dt, dt * dt / 6.0);
        // Plain slices of one length: the loops below run without bounds checks.
        let q = &mut state.displacement.as_mut_slice()[..n];
        let v = &mut state.velocity.as_mut_slice()[..n];
        let a = &mut state.acceleration.as_mut_slice()[..n];
        let z = &mut self.z.as_mut_slice()[..n];
        let y = &mut self.y.as_mut_slice()[..n];
        let d_inv = &inv.diagonal_inverse.as_slice()[..n];
        let load = &self.load.as_slice()[..n];
        let omega2 = &s.omega2.as_slice()[..n];
        let damping = &s.damping.as_slice()[..n];
        let b = &s.contact.as_slice()[..n];

        // Eq. (8): f = F - (P q + Q v + R a) = F - K z - C (v + dt/2 a), z = q + dt v + dt^2/3 a,
        // with K = diag(omega^2) + kappa b b^T (kappa = k_c in contact, 0 out of it).
        for i in 0..n {
            z[i] = q[i] + dt * v[i] + dt2_3 * a[i];
            y[i] = d_inv[i] * (load[i] - omega2[i] * z[i] - damping[i] * (v[i] + dt_2 * a[i]));
        }
        // Eq. (7): a+ = S^-1 f. Out of contact S is diagonal: a+ = D^-1 f = y. In contact the bar
        // adds kappa b b^T to K: f loses kappa b (b . z), and Sherman-Morrison corrects D^-1.
        if let (true, Some(law)) = (contact, s.law) {
            // A nonlinear law (issue 28): a+ = D^-1 (f + b P) with the step-end compression force
            // P = P(delta+, delta+'), where delta+ = -(b^T q+ + s + d) and its rate fall by
            // dt^2/6 b^T D^-1 b and dt/2 b^T D^-1 b per newton: one scalar equation
            // (ContactLaw::solve_in_series), the rank-one structure kept; a truncated basis puts
            // its residual flexibility f_r = b^T R b in series with the law.
            let mut bz = 0.0;
            let mut by = 0.0;
            let mut bw = 0.0;
            for i in 0..n {
                bz += b[i] * z[i];
                by += b[i] * y[i];
                bw += b[i] * (v[i] + dt_2 * a[i]);
            }
            let delta = -(bz + self.shift + gap_offset + dt2_6 * by);
            let rate = -(bw + excitation.gap_offset_rate + dt_2 * by);
            let f_r = s.correction.gram[CONTACT][CONTACT];
            let force = law.solve_in_series(delta, dt2_6 * inv.flexibility, rate, dt_2 * inv.flexibility, f_r);
            let corrected = &inv.corrected.as_slice()[..n];
            for i in 0..n {
                y[i] += force * corrected[i];
            }
        } else if contact {
            // The truncated basis's bar acts on b^T z + s (the discarded modes' static gap).
            let bz: f64 = b.iter().zip(z.iter()).map(|(bi, zi)| bi * zi).sum::<f64>() + self.shift + gap_offset;
            let kbz = s.bar_stiffness * bz;
            let mut by = 0.0;
            for i in 0..n {
                y[i] -= d_inv[i] * kbz * b[i];
                by += b[i] * y[i];
            }
            let corrected = &inv.corrected.as_slice()[..n];
            let scale = inv.factor * by;
            for i in 0..n {
                y[i] -= scale * corrected[i];
            }
        }
        // Eq. (11).
        for i in 0..n {
            let a_next = y[i];
            q[i] += dt * v[i] + dt2_3 * a[i] + dt2_6 * a_next;
            v[i] += dt_2 * (a[i] + a_next);
            a[i] = a_next;
        }
    }

    /// One exact step ([`super::exact`]): each mode under a forcing linear over the step, from
    /// the start's total modal force f0 = a + c v + omega^2 q (the state's own, so a retaken step
    /// starts alike) to the end's loads; in contact `contact_step` (the bar's force a cubic).
    /// Books the damping's exact work over the step (the modes' energy balance).
    fn exact_step(&mut self, state: &mut Kinematics, stage: Stage, dt: f64, excitation: &Excitation) {
        let s = &self.system;
        let slot = match exact_slot(&self.exact_sizes, self.exact_last, dt) {
            Some(j) => j,
            None => {
                let j = evicted(&self.exact_cache);
                self.exact_cache[j].reset(s, dt, stage.is_contact());
                self.exact_sizes[j] = dt;
                j
            }
        };
        self.exact_last = slot;
        self.exact_clock += 1;
        self.exact_cache[slot].used(self.exact_clock);
        if stage.is_contact() {
            self.exact_cache[slot].prepare_contact(s);
            match s.law {
                Some(law) => self.law_contact_step(state, slot, dt, excitation, law),
                None => self.contact_step(state, slot, dt, excitation),
            }
            return;
        }
        let n = state.displacement.len();
        let work = &mut self.z.as_mut_slice()[..n];
        let m = ModeArrays::new(state, &self.load, s);
        let columns = &self.exact_cache[slot].columns;
        // The modes' dissipated work in their order (the same sum as one mode after the other);
        // none without an energy account (neither the work's terms nor a chain of additions as
        // long as the modes).
        self.last_dissipation = Some(if self.energies {
            free_exact_step::<true>(m.q, m.v, m.a, work, m.inputs, columns, dt);
            work.iter().fold(0.0, |sum, w| sum + w)
        } else {
            free_exact_step::<false>(m.q, m.v, m.a, work, m.inputs, columns, dt);
            0.0
        });
        self.last_force_error = None;
    }

    /// One exact step in contact. The bar's force P = k (b^T q + s + d) over the step is taken as
    /// the cubic through its values and rates at both ends: the chord from the start's modal
    /// forces to the end's, F - b P1, and the cubic's departure from it, alpha H10(s) +
    /// beta H11(s) (s = t/dt, alpha = dt P0' - (P1 - P0), beta = dt P1' - (P1 - P0)). P1 and P1'
    /// depend linearly on the end's gap and gap rate, which are linear in them through each mode's
    /// exact response: one 2x2 system ([`BarSolve`]), the rank-one structure kept, O(n). The
    /// force's error is then of order dt^4 (the chord's dt^2): measured over the paper grid's
    /// contacts a third to a fifth of the chord's steps for the same tolerance. The step's error
    /// estimate is the quintic through the force's second derivatives (k (b^T a + d'')) at both
    /// ends against the cubic: at most max(|u0|, |u1|) / 16 with u = (dt^2 P'' - C'') / 2 at each
    /// end. The supports' offset d moves with constant acceleration over the step (a motion
    /// table's row, a sea's record): its start value and rate are its end's taken back along that
    /// quadratic. (Taken back along a line, as before, the start's force was off by
    /// k dt^2 d'' / 2: in the sea example 840 N at level 5 for the record's median d'' of
    /// 0.1 m/s^2, the force-ramp tolerance's size (1e-4 of 9 MN): the force jumped at every step,
    /// the error estimate held the steps short, and a run under a 0.5 m/s^2 relative acceleration
    /// took 56 % more steps than at rest; tests/support_motion.rs.)
    fn contact_step(&mut self, state: &mut Kinematics, slot: usize, dt: f64, excitation: &Excitation) {
        let s = &self.system;
        let coefficients = &self.exact_cache[slot];
        let bar = coefficients.bar;
        let n = state.displacement.len();
        let b = &s.contact.as_slice()[..n];
        let inv_dt = 1.0 / dt;
        let k = s.bar_stiffness;
        // The gap's offset (the discarded modes' static gap and the supports') at the end, and at
        // the start from its rate.
        let (offset, offset_rate) = (self.shift + excitation.gap_offset, excitation.gap_offset_rate);
        let offset_acceleration = excitation.gap_offset_acceleration;
        let (gap_terms, rate_terms) = (&mut self.z.as_mut_slice()[..n], &mut self.y.as_mut_slice()[..n]);
        let m = ModeArrays::new(state, &self.load, s);
        // The end's gap and gap rate without the bar's change over the step (each mode's share
        // in the vectors, summed in the modes' order), and the start's gap, rate and acceleration.
        contact_free_response(&m, &coefficients.columns, inv_dt, gap_terms, rate_terms);
        let (mut gap, mut gap_rate) = (0.0, 0.0);
        let (mut start_gap, mut start_rate, mut start_acceleration) = (0.0, 0.0, 0.0);
        for i in 0..n {
            gap += gap_terms[i];
            gap_rate += rate_terms[i];
            start_gap += b[i] * m.q[i];
            start_rate += b[i] * m.v[i];
            start_acceleration += b[i] * m.a[i];
        }
        // The offset at the start from its end value, rate and (constant) acceleration.
        let start_offset_rate = offset_rate - dt * offset_acceleration;
        let p0 = k * (start_gap + offset - dt * offset_rate + 0.5 * dt * dt * offset_acceleration);
        let p0_step = dt * k * (start_rate + start_offset_rate);
        let start = p0_step + p0;
        let r1 = k * (gap + offset + bar.ag * start + bar.bg * p0);
        let r2 = dt * k * (gap_rate + offset_rate + bar.av * start + bar.bv * p0);
        let force = (r1 * bar.m22 - bar.m12 * r2) / bar.determinant;
        let force_step = (bar.m11 * r2 - bar.m21 * r1) / bar.determinant;
        let change = force - p0;
        let (alpha, beta) = (p0_step - change, force_step - change);
        // Mode i's forcing beyond the chord: -b_i alpha s + b_i g2 s^2 + b_i g3 s^3.
        let (g2, g3) = (2.0 * alpha + beta, -(alpha + beta));
        let work = gap_terms;
        let bar_force = BarForce { force, alpha, g2, g3 };
        // The modes' dissipated work as the free step's: none without an energy account.
        let mut dissipated = 0.0;
        if self.energies {
            contact_advance::<true>(m.q, m.v, m.a, work, m.inputs, coefficients, bar_force);
            for w in work.iter() {
                dissipated += w;
            }
        } else {
            contact_advance::<false>(m.q, m.v, m.a, work, m.inputs, coefficients, bar_force);
        }
        let mut end_acceleration = 0.0;
        for (bi, ai) in b.iter().zip(m.a.iter()) {
            end_acceleration += bi * ai;
        }
        self.last_dissipation = Some(dissipated);
        // The quintic through the force's second derivatives at the ends against the cubic.
        let curvature = |end: f64| dt * dt * k * (end + offset_acceleration);
        let u0 = 0.5 * (curvature(start_acceleration) - (6.0 * change - 4.0 * p0_step - 2.0 * force_step));
        let u1 = 0.5 * (curvature(end_acceleration) - (-6.0 * change + 2.0 * p0_step + 4.0 * force_step));
        self.last_force_error = Some(u0.abs().max(u1.abs()) / 16.0);
    }

    /// One exact step in contact under a nonlinear law (issue 40): as [`Self::contact_step`], the
    /// contact force a cubic through its values and rates at the step's ends, but the end's force
    /// and rate follow the law, P1 = G(D1, V1) and P1' = G_D V1 - G_V A1
    /// ([`crate::model::contact_law::ContactLaw::in_series`]: the law in series with the basis's
    /// residual flexibility; D the kept modes' compression, V its rate, A the gap's acceleration),
    /// where D1, V1 and A1 are affine in (P1, P1') through each mode's exact response
    /// ([`BarSolve`]): two scalar equations, solved by Newton's method from the start's Taylor
    /// expansion to P'' (the Jacobian by differences, the step halved where the residual would
    /// grow; two iterations a step on the hertz-buffer example's long contact steps, 3.4 on
    /// average with the retakes that locate a separation), O(1) on top of the bar's O(n). The
    /// start's force and rate are the same functions of the start's state. The
    /// contact's damping dissipates the trapezoid of its power (P - k x^n) x' over the step; the
    /// error estimate is the bar's, the force's second derivative at each end from G along the
    /// state (a central difference of P' over 1e-4 of the step).
    fn law_contact_step(
        &mut self,
        state: &mut Kinematics,
        slot: usize,
        dt: f64,
        excitation: &Excitation,
        law: crate::model::contact_law::ContactLaw,
    ) {
        let s = &self.system;
        let coefficients = &self.exact_cache[slot];
        let bar = coefficients.bar;
        let n = state.displacement.len();
        let b = &s.contact.as_slice()[..n];
        let inv_dt = 1.0 / dt;
        let f_r = s.correction.gram[CONTACT][CONTACT];
        let (offset, offset_rate) = (self.shift + excitation.gap_offset, excitation.gap_offset_rate);
        let offset_acceleration = excitation.gap_offset_acceleration;
        let gap_terms = &mut self.z.as_mut_slice()[..n];
        let rate_terms = &mut self.y.as_mut_slice()[..n];
        let acceleration_terms = &mut self.w.as_mut_slice()[..n];
        let m = ModeArrays::new(state, &self.load, s);
        let terms = (&mut *gap_terms, &mut *rate_terms, &mut *acceleration_terms);
        contact_free_response_accelerated(&m, &coefficients.columns, inv_dt, terms.0, terms.1, terms.2);
        let (mut gap, mut gap_rate, mut gap_acceleration) = (0.0, 0.0, 0.0);
        let (mut start_gap, mut start_rate, mut start_acceleration, mut start_turn) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..n {
            gap += gap_terms[i];
            gap_rate += rate_terms[i];
            gap_acceleration += acceleration_terms[i];
            start_gap += b[i] * m.q[i];
            start_rate += b[i] * m.v[i];
            start_acceleration += b[i] * m.a[i];
            start_turn += b[i] * (m.inputs.damping[i] * m.a[i] + m.inputs.omega2[i] * m.v[i]);
        }
        // The offset's (constant) acceleration belongs to the gap's at both ends.
        let start_acceleration = start_acceleration + offset_acceleration;
        let gap_acceleration = gap_acceleration + offset_acceleration;
        // The bar's sign convention: F = -P (negative in compression); D' = V, V' = -A.
        // The offset at the start from its end value, rate and (constant) acceleration.
        let start_offset = offset - dt * offset_rate + 0.5 * dt * dt * offset_acceleration;
        let (d0, v0) = (-(start_gap + start_offset), -(start_rate + offset_rate - dt * offset_acceleration));
        let g0 = law.in_series(d0, v0, f_r);
        let p0 = -g0.force;
        let p0_rate = -g0.rate(v0, -start_acceleration);
        let p0_step = dt * p0_rate;
        let start = p0_step + p0;
        // The end's D, V and A for an end force and Y = dt F1'.
        let end = |force: f64, force_step: f64| {
            let (alpha, beta) = (start - force, force_step - (force - p0));
            let g = gap + offset - bar.ramp * force + bar.ag * alpha + bar.bg * beta;
            let gv = gap_rate + offset_rate - bar.vramp * force + bar.av * alpha + bar.bv * beta;
            let ga = gap_acceleration + bar.af * force + bar.aa * alpha + bar.ab * beta;
            (-g, -gv, ga)
        };
        let residual = |force: f64, force_step: f64| {
            let (d, v, a) = end(force, force_step);
            let g = law.in_series(d, v, f_r);
            (force + g.force, force_step + dt * g.rate(v, -a), g)
        };
        // The gap's jerk: b^T (F' - c a - omega^2 v) with F' = -b P' (the load constant over the step).
        let start_jerk = -bar.bb * p0_rate - start_turn;
        // The rates of the force's rate and of the damping's power along the state: P'' and W'.
        let (second0, power_rate0) = g0.second_rates(v0, start_acceleration, start_jerk);
        // From the start's Taylor expansion to the force's second derivative (never pulling):
        // P1 = P0 + dt P0' + dt^2/2 P0'', dt P1' = dt P0' + dt^2 P0'' (P = -G).
        let curvature0 = -dt * dt * second0;
        let (mut force, mut force_step) = ((start + 0.5 * curvature0).min(0.0), p0_step + curvature0);
        let (mut r1, mut r2, mut g) = residual(force, force_step);
        // The end's D, V and A per newton of end force and of Y (the affine `end`).
        let (d_f, d_y) = (bar.ramp + bar.ag + bar.bg, -bar.bg);
        let (v_f, v_y) = (bar.vramp + bar.av + bar.bv, -bar.bv);
        let (a_f, a_y) = (bar.af - bar.aa - bar.ab, bar.ab);
        for _ in 0..50 {
            let scale = force.abs().max(force_step.abs()).max(p0.abs()).max(f64::MIN_POSITIVE);
            // The Jacobian from G's partial derivatives at the iterate: R1 = F1 + G(D1, V1),
            // R2 = Y + dt (G_D V1 - G_V A1).
            let (_, v1, a1) = end(force, force_step);
            let second = |d: f64, v: f64, a: f64| {
                let by_compression = g.by_compression2 * d + g.by_both * v;
                let by_rate = g.by_both * d + g.by_rate2 * v;
                dt * (by_compression * v1 + g.by_compression * v - by_rate * a1 - g.by_rate * a)
            };
            let (j11, j12) = (1.0 + g.by_compression * d_f + g.by_rate * v_f, g.by_compression * d_y + g.by_rate * v_y);
            let (j21, j22) = (second(d_f, v_f, a_f), 1.0 + second(d_y, v_y, a_y));
            let determinant = j11 * j22 - j12 * j21;
            let df = -(r1 * j22 - j12 * r2) / determinant;
            let dy = -(j11 * r2 - j21 * r1) / determinant;
            if !(df.is_finite() && dy.is_finite()) {
                break;
            }
            // Converged when Newton's correction is at the force's round-off; or, after the full
            // step taken, when the correction was below 1e-9 of the scale: the next one is then
            // at most C e^2, C ~ 1e3 / scale from the law's curvature (measured on the
            // hertz-buffer example: 4.5e-4 -> 1.3e-10 -> round-off), below 1e-15 of the scale.
            let correction = df.abs().max(dy.abs());
            let small = correction <= 1e-13 * scale;
            let final_step = correction <= 1e-9 * scale;
            let norm = r1.abs().max(r2.abs());
            let mut t = 1.0;
            let accepted = loop {
                let (f_try, y_try) = (force + t * df, force_step + t * dy);
                let (a1, a2, g_try) = residual(f_try, y_try);
                if small || a1.abs().max(a2.abs()) < norm {
                    break Some((f_try, y_try, a1, a2, g_try));
                }
                t *= 0.5;
                if t < 1e-3 {
                    break None;
                }
            };
            // No decrease: the residual is at round-off.
            let Some(next) = accepted else { break };
            (force, force_step, r1, r2, g) = next;
            if small || (final_step && t == 1.0) {
                break;
            }
        }
        let change = force - p0;
        let (alpha, beta) = (p0_step - change, force_step - change);
        let (g2, g3) = (2.0 * alpha + beta, -(alpha + beta));
        let work = gap_terms;
        let bar_force = BarForce { force, alpha, g2, g3 };
        contact_advance::<true>(m.q, m.v, m.a, work, m.inputs, coefficients, bar_force);
        let (mut end_acceleration, mut end_turn, mut dissipated) = (0.0, 0.0, 0.0);
        for i in 0..n {
            end_acceleration += b[i] * m.a[i];
            end_turn += b[i] * (m.inputs.damping[i] * m.a[i] + m.inputs.omega2[i] * m.v[i]);
            dissipated += work[i];
        }
        let end_jerk = -bar.bb * (force_step * inv_dt) - end_turn;
        let (_, v1, _) = end(force, force_step);
        let (second1, power_rate1) = g.second_rates(v1, end_acceleration + offset_acceleration, end_jerk);
        // The contact's damping: its power's trapezoid with the end correction (Euler-Maclaurin,
        // exact for a cubic).
        let power = 0.5 * dt * (g0.dissipation + g.dissipation) + dt * dt / 12.0 * (power_rate0 - power_rate1);
        self.last_dissipation = Some(dissipated + power);
        let curvature1 = -dt * dt * second1;
        let u0 = 0.5 * (curvature0 - (6.0 * change - 4.0 * p0_step - 2.0 * force_step));
        let u1 = 0.5 * (curvature1 - (-6.0 * change + 2.0 * p0_step + 4.0 * force_step));
        self.last_force_error = Some(u0.abs().max(u1.abs()) / 16.0);
    }

    /// The probes and energies of the state just reached, as lane-wise sums (vectorised; the
    /// order of the additions differs from a plain loop only by round-off).
    fn measure_state(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> ([f64; PROBES], Energies) {
        let s = &self.system;
        let n = state.displacement.len();
        let (q, v) = (&state.displacement.as_slice()[..n], &state.velocity.as_slice()[..n]);
        let (omega2, damping) = (&s.omega2.as_slice()[..n], &s.damping.as_slice()[..n]);
        let mut probes = probe_dots(&self.probe_rows, q);
        let mut e = Energies::default();
        probes[Probe::Gap as usize] += excitation.gap_offset;
        if !self.energies {
            if s.is_truncated() {
                let rate = self.law_rate(state, stage, excitation);
                let loads = s.correction.loads(probes[Probe::Gap as usize], rate, stage.is_contact(), excitation);
                s.correction.correct_probes_by(&mut probes, &loads);
            }
            return (probes, e);
        }
        let lower = s.lower_dofs.min(n);
        let sums = energy_sums(q, v, omega2, damping, &s.gravity.as_slice()[..n], lower);
        let lower_strain = 0.5 * sums.lower_strain;
        e.upper_strain = 0.5 * sums.upper_strain;
        e.beam_strain = lower_strain + e.upper_strain;
        e.kinetic = 0.5 * sums.kinetic;
        e.gravity_potential = -sums.gravity;
        if excitation.moves() {
            // The support load of the last step's excitation, or this one's (a state measured at
            // another instant: a step's start, an output time).
            e.inertial_potential = if self.load_excitation.is_some_and(|l| l.same_load(excitation)) {
                -dot(&self.support_load.as_slice()[..n], q)
            } else if self.next_excitation.is_some_and(|l| l.same_load(excitation)) {
                -self.next_support_load.dot(&state.displacement)
            } else {
                -s.support_load(excitation).dot(&state.displacement)
            };
        }
        e.dissipation_rate = sums.dissipation;
        if s.is_truncated() {
            let rate = self.law_rate(state, stage, excitation);
            apply_correction(s, &mut probes, &mut e, (stage.is_contact(), rate), excitation);
        }
        (probes, e)
    }

    /// A nonlinear law's contact force at `state` in contact, with its partial derivatives
    /// ([`crate::model::contact_law::ContactLaw::in_series`] with the basis's residual
    /// flexibility and static gap shift; both 0 for the full basis); `None` for the linear bar
    /// or out of contact.
    fn law_force(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> Option<SeriesForce> {
        let s = &self.system;
        let law = s.law.filter(|_| stage.is_contact())?;
        let gap = self.probes(&state.displacement)[Probe::Gap as usize]
            + excitation.gap_offset
            + s.correction.gap_shift(excitation);
        let rate = self.probes(&state.velocity)[Probe::Gap as usize] + excitation.gap_offset_rate;
        Some(law.in_series(-gap, -rate, s.correction.gram[CONTACT][CONTACT]))
    }

    /// The kept modes' gap rate b^T Phi_k q' + d' of `state` where the static correction reads it
    /// (a nonlinear law with damping, in contact), else 0.
    fn law_rate(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> f64 {
        match self.system.law {
            Some(law) if law.damping > 0.0 && stage.is_contact() => {
                let n = state.velocity.len().min(self.probe_columns.nrows());
                let column = self.probe_columns.column(Probe::Gap as usize);
                dot(&column.as_slice()[..n], &state.velocity.as_slice()[..n]) + excitation.gap_offset_rate
            }
            _ => 0.0,
        }
    }
}

/// Adds the discarded modes' static response to measurements taken from the kept modes.
/// `contact`: the stage and the kept modes' gap rate ([`ModalStepper::law_rate`]).
fn apply_correction(
    s: &ModalSystem,
    probes: &mut [f64; PROBES],
    e: &mut Energies,
    (contact, rate): (bool, f64),
    ex: &Excitation,
) {
    let c = s.correction.evaluate(probes[Probe::Gap as usize], rate, contact, ex);
    s.correction.correct_probes(probes, &c);
    e.beam_strain += c.strain;
    e.upper_strain += c.upper_strain;
    e.gravity_potential += c.gravity_potential;
    e.inertial_potential += c.inertial_potential;
}

impl Stepper for ModalStepper {
    type TangentWork = TangentWork;

    fn step(&mut self, state: &mut Kinematics, stage: Stage, dt: f64, excitation: &Excitation) {
        self.advance::<false>(state, stage, dt, excitation);
    }

    fn step_measured(
        &mut self,
        state: &mut Kinematics,
        stage: Stage,
        dt: f64,
        excitation: &Excitation,
    ) -> ([f64; PROBES], Energies) {
        self.advance::<true>(state, stage, dt, excitation)
    }

    fn step_aside(&mut self, state: &mut Kinematics, stage: Stage, dt: f64, excitation: &Excitation) {
        let kept = (self.last_dissipation, self.last_force_error);
        self.advance::<false>(state, stage, dt, excitation);
        (self.last_dissipation, self.last_force_error) = kept;
    }

    fn step_dissipation(&self) -> Option<f64> {
        self.last_dissipation
    }

    fn force_ramp_error(&self) -> Option<f64> {
        self.last_force_error
    }

    fn adapts_steps(&self) -> bool {
        self.exact
    }

    fn keep_energies(&mut self, keep: bool) {
        self.energies = keep;
    }

    fn modal_coordinates(&self) -> bool {
        true
    }

    fn tangent_step(
        &self,
        start: &Kinematics,
        delta: &mut Kinematics,
        stage: Stage,
        dt: f64,
        work: &mut TangentWork,
    ) -> bool {
        self.exact_tangent_step(start, delta, stage, dt, work)
    }

    fn free_fourth_derivatives(&mut self, state: &Kinematics) -> Option<[f64; PROBES]> {
        if !self.exact {
            return None;
        }
        // The amplitudes go to the step's work vector (free between steps): no allocation per
        // step.
        let n = state.displacement.len().min(self.fourth_derivative.len());
        let amplitude = &mut self.y.as_mut_slice()[..n];
        Some(first_probes(fourth_derivative_bounds(
            &state.displacement.as_slice()[..n],
            &state.velocity.as_slice()[..n],
            &self.load.as_slice()[..n],
            &self.system.omega2.as_slice()[..n],
            amplitude,
            &self.fourth_derivative,
        )))
    }

    fn equilibrium_acceleration(&mut self, state: &mut Kinematics, stage: Stage, excitation: &Excitation) {
        // In modal coordinates M = I: a = F - diag(omega^2) q - diag(c) v - kappa b (b . q + s + d),
        // or + b P for a nonlinear law.
        let law = self.law_force(state, stage, excitation);
        // The load, and the supports' share, ahead into their own vectors, not the stepper's: the
        // energies measured before the next step keep reading the last step's where it is the
        // same (the same bits), and the next step takes them ([`Self::refresh_load`]).
        let s = &self.system;
        s.load_into(excitation, &mut self.next_load);
        s.support_load_into(excitation, &mut self.next_support_load);
        self.next_excitation = Some(*excitation);
        let load = &self.next_load;
        let bar = if let Some(law) = law {
            -law.force
        } else if stage.is_contact() {
            s.bar_stiffness
                * (s.contact.dot(&state.displacement) + s.correction.gap_shift(excitation) + excitation.gap_offset)
        } else {
            0.0
        };
        // Plain slices of one length: the loop runs in vectors, without bounds checks.
        let n = state.displacement.len();
        let (q, v) = (&state.displacement.as_slice()[..n], &state.velocity.as_slice()[..n]);
        let a = &mut state.acceleration.as_mut_slice()[..n];
        let (load, omega2, damping, b) =
            (&load.as_slice()[..n], &s.omega2.as_slice()[..n], &s.damping.as_slice()[..n], &s.contact.as_slice()[..n]);
        for i in 0..n {
            a[i] = load[i] - omega2[i] * q[i] - damping[i] * v[i] - bar * b[i];
        }
    }

    fn probes(&self, displacement: &DVector<f64>) -> [f64; PROBES] {
        probe_dots(&self.probe_rows, displacement.as_slice())
    }

    fn measure(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> ([f64; PROBES], Energies) {
        // The same sums as a measured step's, so that a state measured again (a step's start,
        // a restored state) gives the very same numbers.
        self.measure_state(state, stage, excitation)
    }

    fn rates(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> [f64; PROBES] {
        let mut rates = self.probes(&state.velocity);
        rates[Probe::Gap as usize] += excitation.gap_offset_rate;
        let s = &self.system;
        if s.is_truncated() && stage.is_contact() {
            // The static correction's contact load -F_c = -k_eff (b . q + s + d) moves at
            // -k_eff (b . v + d'); a nonlinear law's P = G(D, V) at G_D D' + G_V V' (D and V the
            // kept modes' compression and its rate, V' = -(b . a) without the supports' jerk).
            let load_rate = if s.law.is_some() {
                let gap = self.probes(&state.displacement)[Probe::Gap as usize] + excitation.gap_offset;
                let acceleration = self.probes(&state.acceleration)[Probe::Gap as usize];
                let law_rate = s.correction.law_load_rate(gap, (rates[Probe::Gap as usize], acceleration), excitation);
                law_rate.unwrap_or(0.0)
            } else {
                -s.bar_stiffness * rates[Probe::Gap as usize]
            };
            for (rate, row) in rates.iter_mut().zip(&s.correction.probes) {
                *rate += row[super::static_correction::CONTACT] * load_rate;
            }
        }
        rates
    }

    fn support_and_tips(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> SupportAndTips {
        let s = &self.system;
        let (q, v, a) = (&state.displacement, &state.velocity, &state.acceleration);
        let [r0, r1, r2] = &s.reactions;
        let (q, v, a) = (q.as_slice(), v.as_slice(), a.as_slice());
        // One pass over the coordinates with two sets of accumulators (even and odd coordinates):
        // eleven dot products in a few vector operations per coordinate, and addition chains
        // half as long (separate dots cost ~2 300 instructions a step on the paper mesh, half
        // of a step; this pass about half of that).
        let mut even = DetailSums::default();
        let mut odd = DetailSums::default();
        let n = q.len().min(v.len()).min(a.len()).min(self.detail_rows.len());
        let mut i = 0;
        while i + 1 < n {
            even.add(&self.detail_rows[i], q[i], v[i], a[i]);
            odd.add(&self.detail_rows[i + 1], q[i + 1], v[i + 1], a[i + 1]);
            i += 2;
        }
        if i < n {
            even.add(&self.detail_rows[i], q[i], v[i], a[i]);
        }
        let row = |k: usize| {
            (even.displacement[k] + odd.displacement[k])
                + (even.velocity[k] + odd.velocity[k])
                + (even.acceleration[k] + odd.acceleration[k])
        };
        let mut sums = [row(0), row(1), row(2), even.velocity[3] + odd.velocity[3], even.velocity[4] + odd.velocity[4]];
        if s.is_truncated() {
            // The discarded modes' static displacement loads the supports through their stiffness rows.
            let gap = self.probe_columns.column(Probe::Gap as usize).dot(&state.displacement) + excitation.gap_offset;
            let rate = self.law_rate(state, stage, excitation);
            let c = s.correction.evaluate(gap, rate, stage.is_contact(), excitation);
            for (k, sum) in sums.iter_mut().take(REACTIONS).enumerate() {
                *sum += s.correction.reaction(k, &c);
            }
        }
        if excitation.moves() {
            // The supports' own inertia: the support rows of M r_j a_j.
            for (sum, row) in sums.iter_mut().zip(&s.support_reactions) {
                *sum += row.iter().zip(excitation.support_acceleration).map(|(m, a)| m * a).sum::<f64>();
            }
        }
        SupportAndTips {
            clamp_force: sums[0] - r0.load,
            clamp_moment: sums[1] - r1.load,
            hinge_force: sums[2] - r2.load,
            lower_tip_velocity: sums[3],
            upper_tip_velocity: sums[4],
        }
    }

    fn energies(&self, state: &Kinematics, excitation: &Excitation) -> Energies {
        let s = &self.system;
        let (q, v) = (&state.displacement, &state.velocity);
        let mut e = Energies::default();
        if excitation.moves() {
            e.inertial_potential = -s.support_load(excitation).dot(q);
        }
        for i in 0..q.len() {
            let strain = 0.5 * s.omega2[i] * q[i] * q[i];
            e.beam_strain += strain;
            if i >= s.lower_dofs {
                e.upper_strain += strain;
            }
            e.kinetic += 0.5 * v[i] * v[i];
            e.gravity_potential -= s.gravity[i] * q[i];
            e.dissipation_rate += s.damping[i] * v[i] * v[i];
        }
        e
    }

    fn own_coordinates(&self, physical: &Kinematics) -> Kinematics {
        Kinematics {
            displacement: &*self.projector * &physical.displacement,
            velocity: &*self.projector * &physical.velocity,
            acceleration: &*self.projector * &physical.acceleration,
        }
    }
}

/// Each mode's coefficients of a step `dt` into `columns`, and the contact stage's into `cubic`
/// when it is not empty (then with the bar's sums over the modes, in the modes' order): one pass
/// over the modes, each mode's responses computed once for both ([`ModeStep::with_responses`]).
/// `modes`: omega^2, damping and contact coefficient per mode. Compiled for the CPU's widest
/// vectors too (the nine sums of a series term side by side; no fused multiply-add: the same bits
/// whichever runs).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn mode_coefficients(
    (omega2, damping, b): (&[f64], &[f64], &[f64]),
    dt: f64,
    columns: &mut [Vec<f64>; 12],
    cubic: &mut [Vec<f64>; 18],
) -> BarSums {
    let n = omega2.len();
    let contact = cubic[0].len() == n;
    let mut sums = BarSums::default();
    // A whole chunk of modes' coefficients as [column][mode], then stored a column at a time
    // (one index check a column and chunk, not one a value); the last modes short of a chunk
    // each straight into the columns.
    let mut values = [[0.0; CHUNK]; 12];
    let mut contact_values = [[0.0; CHUNK]; 18];
    for start in (0..n).step_by(CHUNK) {
        let modes = (n - start).min(CHUNK);
        let whole = modes == CHUNK;
        for l in 0..modes {
            let i = start + l;
            let (w2, c) = (omega2[i], damping[i]);
            let (mode, responses) = ModeStep::with_responses(w2, c, dt);
            if whole {
                for (column, value) in values.iter_mut().zip(mode_values(&mode)) {
                    column[l] = value;
                }
            } else {
                for (column, value) in columns.iter_mut().zip(mode_values(&mode)) {
                    column[i] = value;
                }
            }
            if contact {
                let step = match responses {
                    Some(psi) => CubicStep::from_responses(c, dt, &psi),
                    None => CubicStep::new(w2, c, dt, &mode),
                };
                if whole {
                    for (column, value) in contact_values.iter_mut().zip(cubic_values(&step)) {
                        column[l] = value;
                    }
                } else {
                    set_cubic(cubic, i, &step);
                }
                sums.add(b[i], (w2, c), &mode, &step);
            }
        }
        if whole {
            store_chunk(columns, start, &values);
            if contact {
                store_chunk(cubic, start, &contact_values);
            }
        }
    }
    sums
}

/// Modes whose coefficients [`mode_coefficients`] gathers before it stores them.
const CHUNK: usize = 4;

/// `values` ([column][mode]) of the [`CHUNK`] modes from `start` on into `columns`.
#[inline(always)]
fn store_chunk<const K: usize>(columns: &mut [Vec<f64>; K], start: usize, values: &[[f64; CHUNK]; K]) {
    for (column, chunk) in columns.iter_mut().zip(values) {
        column[start..start + CHUNK].copy_from_slice(chunk);
    }
}

/// A mode's coefficients in the order of [`ExactStage::columns`].
#[inline(always)]
fn mode_values(m: &ModeStep) -> [f64; 12] {
    let [q, v, i] = [m.q, m.v, m.integral];
    [q[0], q[1], q[2], q[3], v[0], v[1], v[2], v[3], i[0], i[1], i[2], i[3]]
}

/// A mode's contact coefficients in the order of [`ExactStage::cubic_columns`].
#[inline(always)]
fn cubic_values(c: &CubicStep) -> [f64; 18] {
    let [m0, m1] = c.moments;
    [
        c.q[0],
        c.q[1],
        c.v[0],
        c.v[1],
        c.integral[0],
        c.integral[1],
        m0[0],
        m0[1],
        m0[2],
        m0[3],
        m0[4],
        m0[5],
        m1[0],
        m1[1],
        m1[2],
        m1[3],
        m1[4],
        m1[5],
    ]
}

/// Mode `i`'s contact coefficients into the eighteen columns of [`ExactStage::cubic_columns`].
#[inline(always)]
fn set_cubic(columns: &mut [Vec<f64>; 18], i: usize, c: &CubicStep) {
    for (column, value) in columns.iter_mut().zip(cubic_values(c)) {
        column[i] = value;
    }
}

/// The slot of the exact cache holding the coefficients of step `dt`, from the slots' `sizes`:
/// `last`, the last step's, first (a run's steps take the same size as a rule).
fn exact_slot(sizes: &[f64; EXACT_SLOTS], last: usize, dt: f64) -> Option<usize> {
    if sizes.get(last) == Some(&dt) {
        return Some(last);
    }
    sizes.iter().position(|&size| size == dt)
}

/// The step sizes whose coefficients a stepper keeps. A campaign event's runs meet some 380
/// distinct sizes each (issue 43, the sea example: about 250 retakes locating contact changes, 75
/// peaks' instants, 50 motion rows' cuts, and the stages' own few), of which only the stages' own
/// and the rows' remainders recur: 32 slots keep those (382 resets a run, 64 slots 379). A run
/// that writes its samples meets more sizes that recur (each sample inside a contact step an
/// advance from the step's start): the printed run of `run examples/vessel-sea.toml` resets
/// 18 300 times with 32 slots, 16 600 with 64 (21 000 before issue 43). A slot of the printed
/// mesh's 65 modes is 16 kB.
const EXACT_SLOTS: usize = 64;

/// Single-use entries the exact cache keeps apart before it evicts a reused one (see [`evicted`]).
const EXACT_PROBATION: usize = 4;

/// The slot of the exact cache whose coefficients give way to a new step size: an empty one,
/// else the least recently used of the sizes met once so far (a located change's retakes, a
/// peak's instant, a landing) while at least [`EXACT_PROBATION`] of them are held, else the least
/// recently used of all. The stages' own sizes recur every step and a motion row's remainder every
/// row: they stay. (Until issue 43 the least used went, the first of equals: the new size after a
/// row's cut then took the slot of the size before it, and the two evicted each other at every
/// row, 260 of a run's 600 resets on the sea example. Measured over the 40 runs of 20 campaign
/// events: 543 resets a run before, 379 now, against 377 distinct sizes.)
fn evicted(cache: &[ExactStage]) -> usize {
    // One pass: the count of sizes met once, the least recently used of them and of all (the
    // first of equals: the empty slots, never used, in their order).
    let (mut once, mut oldest_once, mut oldest) = (0, None::<(u64, usize)>, None::<(u64, usize)>);
    for (j, c) in cache.iter().enumerate() {
        if c.hits <= 1 {
            once += 1;
            if oldest_once.is_none_or(|(used, _)| c.last_used < used) {
                oldest_once = Some((c.last_used, j));
            }
        }
        if oldest.is_none_or(|(used, _)| c.last_used < used) {
            oldest = Some((c.last_used, j));
        }
    }
    let chosen = if once >= EXACT_PROBATION { oldest_once } else { oldest };
    chosen.map_or(0, |(_, j)| j)
}

/// The scratch of [`ModalStepper::exact_tangent_step`]: coefficients of its own for a step size
/// the stepper's cache no longer holds (so that the tangent never touches the stepper's cache or
/// its hit counts), and where in that cache the latest step's were (the next step's are most
/// often the same: the stages' own sizes recur).
#[derive(Clone, Debug, Default)]
pub struct TangentWork {
    own: Option<Box<ExactStage>>,
    slot: usize,
    /// Per slot of the stepper's cache, the step size and [`ramp_sums`] of its coefficients
    /// (functions of the step size alone: the same numbers whenever they are computed).
    ramps: Vec<(f64, [f64; 4])>,
}

impl ModalStepper {
    /// Advances `start`, a difference of two states (the derivative of the state times a
    /// nudge), into `delta` (both of the modes' size: all of it written) over the step of `dt` in
    /// `stage` that the stepper has just taken: the exact
    /// advance's very coefficients applied to `delta` under no load, no support offset and no
    /// static gap shift (they cancel in a difference), the bar's force in contact the cubic of
    /// its own difference. The exact step is affine in the state for a given stage and step,
    /// so this is the step's derivative. `delta` starts at the equilibrium of the stage (zero
    /// load; the bar's k_eff b b^T delta q in contact): at a contact change the difference's
    /// force is the bar's at once (the printed run's own bar force is 0 at the touch, to the gap
    /// tolerance); so each mode's start force is -P0 b_i (0 out of contact), whatever `delta`'s
    /// acceleration, which is set to the end's equilibrium. Only what the difference needs is
    /// computed: no damping work, no force error (out of contact two products per coordinate;
    /// in contact one pass for the gap's sums and one for the advance). Nothing the stepper
    /// keeps of its steps changes (its dissipation, its force error, its coefficients' cache and
    /// hit counts). Returns false where there is no such tangent: the linear acceleration
    /// method, or a nonlinear contact law.
    pub fn exact_tangent_step(
        &self,
        start: &Kinematics,
        delta: &mut Kinematics,
        stage: Stage,
        dt: f64,
        work: &mut TangentWork,
    ) -> bool {
        let s = &self.system;
        if !self.exact || s.law.is_some() {
            return false;
        }
        let n = delta.displacement.len().min(s.omega2.len()).min(s.damping.len()).min(s.contact.len());
        let contact = stage.is_contact();
        let ready =
            |c: &ExactStage| c.dt == dt && c.columns[0].len() == n && (!contact || c.cubic_columns[0].len() == n);
        if !self.exact_cache.get(work.slot).is_some_and(ready) {
            if let Some(j) = self.exact_cache.iter().position(ready) {
                work.slot = j;
            }
        }
        if work.ramps.len() != EXACT_SLOTS {
            work.ramps = vec![(f64::NAN, [0.0; 4]); EXACT_SLOTS];
        }
        let (coefficients, ramp) = match self.exact_cache.get(work.slot).filter(|c| ready(c)) {
            Some(c) => (c, work.ramps.get_mut(work.slot)),
            None => {
                let own = work.own.get_or_insert_with(Default::default);
                if !ready(own) {
                    own.reset(s, dt, contact);
                }
                (work.own.as_deref().expect("just set"), None)
            }
        };
        let (q0, v0) = (&start.displacement.as_slice()[..n], &start.velocity.as_slice()[..n]);
        let q = &mut delta.displacement.as_mut_slice()[..n];
        let v = &mut delta.velocity.as_mut_slice()[..n];
        let a = &mut delta.acceleration.as_mut_slice()[..n];
        let modes = TangentModes {
            omega2: &s.omega2.as_slice()[..n],
            damping: &s.damping.as_slice()[..n],
            b: &s.contact.as_slice()[..n],
        };
        if !contact {
            free_tangent_advance(q0, v0, q, v, a, modes, &coefficients.columns);
            return true;
        }
        // `contact_step` with no load and no offset: the bar's force is k b^T delta q at both
        // ends, and each mode's start force f0 = -P0 b_i.
        let k = s.bar_stiffness;
        let bar = coefficients.bar;
        let inv_dt = 1.0 / dt;
        let [free_gap, free_rate, start_gap, start_rate] = tangent_contact_sums(q0, v0, modes.b, &coefficients.columns);
        let ramps = match ramp {
            Some((at, sums)) if *at == dt => *sums,
            Some((at, sums)) => {
                (*at, *sums) = (dt, ramp_sums(modes.b, &coefficients.columns));
                *sums
            }
            None => ramp_sums(modes.b, &coefficients.columns),
        };
        let p0 = k * start_gap;
        let p0_step = dt * k * start_rate;
        // The end's gap and rate without the bar's change: the modes' free response, and their
        // response to the start's force as the chord to no load (f0 = -P0 b_i, r = P0 b_i / dt).
        let gap = free_gap + p0 * (ramps[1] * inv_dt - ramps[0]);
        let gap_rate = free_rate + p0 * (ramps[3] * inv_dt - ramps[2]);
        let start = p0_step + p0;
        let r1 = k * (gap + bar.ag * start + bar.bg * p0);
        let r2 = dt * k * (gap_rate + bar.av * start + bar.bv * p0);
        let force = (r1 * bar.m22 - bar.m12 * r2) / bar.determinant;
        let force_step = (bar.m11 * r2 - bar.m21 * r1) / bar.determinant;
        let change = force - p0;
        let (alpha, beta) = (p0_step - change, force_step - change);
        // Mode i's forcing per b_i: -P0 at the start, the chord's and the cubic's departure from it.
        let forcing = [-p0, (p0 - force - alpha) * inv_dt, 2.0 * alpha + beta, -(alpha + beta), -force];
        contact_tangent_advance(q0, v0, q, v, a, modes, &coefficients.columns, &coefficients.cubic_columns, forcing);
        true
    }
}

/// The modes' parameters a tangent step reads, each `n` long (the difference's arrays are the
/// kernels' own arguments, as [`ModeArrays`]' are).
#[derive(Clone, Copy)]
struct TangentModes<'a> {
    omega2: &'a [f64],
    damping: &'a [f64],
    b: &'a [f64],
}

/// The tangent's exact step out of contact ([`ModalStepper::exact_tangent_step`]): under no
/// force each mode's end is q(h) = C0 q0 + C1 v0, v(h) = C4 q0 + C5 v0 (the step's own columns;
/// `free_exact_step`'s terms in f0 and r vanish), its acceleration the free equilibrium. In the
/// CPU's widest vectors (no fused multiply-add: the same bits whichever runs). From the start
/// `q0`, `v0` into `q`, `v` and `a` (another state: the start stays as it was, no copy of it;
/// each array an argument of its own, as [`ModeArrays`] says why).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn free_tangent_advance(
    q0: &[f64],
    v0: &[f64],
    q: &mut [f64],
    v: &mut [f64],
    a: &mut [f64],
    m: TangentModes,
    columns: &[Vec<f64>; 12],
) {
    let n = q.len();
    let (q0, v0, v, a) = (&q0[..n], &v0[..n], &mut v[..n], &mut a[..n]);
    let (omega2, damping) = (&m.omega2[..n], &m.damping[..n]);
    let (c0, c1, c4, c5) = (&columns[0][..n], &columns[1][..n], &columns[4][..n], &columns[5][..n]);
    for i in 0..n {
        let (q0, v0) = (q0[i], v0[i]);
        let q1 = c0[i] * q0 + c1[i] * v0;
        let v1 = c4[i] * q0 + c5[i] * v0;
        q[i] = q1;
        v[i] = v1;
        a[i] = -damping[i] * v1 - omega2[i] * q1;
    }
}

/// The sums over the modes behind the tangent's contact step, each in four lanes: b^T of the
/// free response's end q and v (C0 q + C1 v, C4 q + C5 v), b^T q and b^T v at the start. One
/// pass each: a single pass for all, its accumulators side by side, vectorises across the sums
/// instead of the modes (twice the instructions, measured).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn tangent_contact_sums(q: &[f64], v: &[f64], b: &[f64], columns: &[Vec<f64>; 12]) -> [f64; 4] {
    let n = q.len();
    let (v, b) = (&v[..n], &b[..n]);
    let c: [&[f64]; 6] = std::array::from_fn(|k| &columns[[0, 1, 4, 5, 2, 3][k]][..n]);
    [response_dot(b, [c[0], c[1]], q, v), response_dot(b, [c[2], c[3]], q, v), dot(b, q), dot(b, v)]
}

/// sum C b^2 over the modes of C2, C3, C6 and C7 (the end's q and v per start force and per
/// ramp), each in four lanes: the end gap's and gap rate's response to the start force.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn ramp_sums(b: &[f64], columns: &[Vec<f64>; 12]) -> [f64; 4] {
    [
        weighted_squares(&columns[2], b),
        weighted_squares(&columns[3], b),
        weighted_squares(&columns[6], b),
        weighted_squares(&columns[7], b),
    ]
}

/// sum b_i (c0_i q_i + c1_i v_i) in four lanes (as [`four_lanes`]).
#[inline(always)]
fn response_dot(b: &[f64], [c0, c1]: [&[f64]; 2], q: &[f64], v: &[f64]) -> f64 {
    let n = b.len().min(c0.len()).min(c1.len()).min(q.len()).min(v.len());
    let (b, c0, c1, q, v) = (&b[..n], &c0[..n], &c1[..n], &q[..n], &v[..n]);
    let mut lanes = [0.0f64; 4];
    let whole = n - n % 4;
    let chunks = b[..whole]
        .chunks_exact(4)
        .zip(c0[..whole].chunks_exact(4))
        .zip(c1[..whole].chunks_exact(4))
        .zip(q[..whole].chunks_exact(4).zip(v[..whole].chunks_exact(4)));
    for (((b, c0), c1), (q, v)) in chunks {
        for l in 0..4 {
            lanes[l] += b[l] * (c0[l] * q[l] + c1[l] * v[l]);
        }
    }
    let mut tail = 0.0;
    for i in whole..n {
        tail += b[i] * (c0[i] * q[i] + c1[i] * v[i]);
    }
    lanes_total(lanes, tail)
}

/// The tangent's exact step in contact: each mode under b_i times the forcing `f` = [start
/// value, ramp per second, s^2 and s^3 coefficients, end value] (see
/// [`ModalStepper::exact_tangent_step`]; `contact_advance`'s terms without the damping's work),
/// its acceleration the end's equilibrium. In the CPU's widest vectors (no fused multiply-add:
/// the same bits whichever runs). From the start `q0`, `v0` into `q`, `v` and `a`.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
#[allow(clippy::too_many_arguments)]
fn contact_tangent_advance(
    q0: &[f64],
    v0: &[f64],
    q: &mut [f64],
    v: &mut [f64],
    a: &mut [f64],
    m: TangentModes,
    columns: &[Vec<f64>; 12],
    cubic: &[Vec<f64>; 18],
    f: [f64; 5],
) {
    let n = q.len();
    let (q0, v0, v, a) = (&q0[..n], &v0[..n], &mut v[..n], &mut a[..n]);
    let (omega2, damping, b) = (&m.omega2[..n], &m.damping[..n], &m.b[..n]);
    let c: [&[f64]; 8] = std::array::from_fn(|k| &columns[k][..n]);
    let cu: [&[f64]; 4] = std::array::from_fn(|k| &cubic[k][..n]);
    let [start, ramp, g2, g3, end] = f;
    for i in 0..n {
        let (q0, v0) = (q0[i], v0[i]);
        let x = start * c[2][i] + ramp * c[3][i] + g2 * cu[0][i] + g3 * cu[1][i];
        let y = start * c[6][i] + ramp * c[7][i] + g2 * cu[2][i] + g3 * cu[3][i];
        let q1 = c[0][i] * q0 + c[1][i] * v0 + b[i] * x;
        let v1 = c[4][i] * q0 + c[5][i] * v0 + b[i] * y;
        q[i] = q1;
        v[i] = v1;
        a[i] = b[i] * end - damping[i] * v1 - omega2[i] * q1;
    }
}

/// sum a_i b_i in four lanes.
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    four_lanes(a, b, |x, y| x * y)
}

/// sum w_i x_i^2 in four lanes.
#[inline(always)]
fn weighted_squares(w: &[f64], x: &[f64]) -> f64 {
    four_lanes(w, x, |u, y| u * y * y)
}

/// x's [`dot`] with each probe's functional (`rows`: per coordinate, the probes side by side),
/// over the common length, in the CPU's widest vectors: the same four lanes in the same order as
/// [`dot`] of each probe's column, and so the same bits, but the probes' lanes side by side in
/// one pass over x (a tenth of a campaign's time was these seven dots, each a chain of additions
/// waiting on the one before).
#[inline(always)]
fn probe_dots(rows: &[[f64; 8]], x: &[f64]) -> [f64; PROBES] {
    first_probes(padded_probe_dots(rows, x))
}

/// [`probe_dots`] with the padding's lane too.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn padded_probe_dots(rows: &[[f64; 8]], x: &[f64]) -> [f64; 8] {
    dots_side_by_side(rows, x)
}

/// The probes' sums of eight lanes (the last the padding's).
#[inline(always)]
fn first_probes(dots: [f64; 8]) -> [f64; PROBES] {
    std::array::from_fn(|k| dots[k])
}

/// [`probe_dots`]' sums, inlined into each vectorised caller, the padding's lane too: returned
/// out of the vectorised function, so that the compiler keeps it, and with it every row two whole
/// vectors (without it the seventh probe's lanes went into shuffles: a third more instructions).
#[inline(always)]
fn dots_side_by_side(rows: &[[f64; 8]], x: &[f64]) -> [f64; 8] {
    let n = x.len().min(rows.len());
    let (rows, x) = (&rows[..n], &x[..n]);
    let mut lanes = [[0.0f64; 8]; 4];
    let (chunks, xs) = (rows.chunks_exact(4), x.chunks_exact(4));
    let (rest, rest_x) = (chunks.remainder(), xs.remainder());
    for (r, x) in chunks.zip(xs) {
        for l in 0..4 {
            for k in 0..8 {
                lanes[l][k] += r[l][k] * x[l];
            }
        }
    }
    // The tail's terms added in order from -0.0, as `Iterator::sum` adds them, every probe's
    // side by side.
    let mut tail = [-0.0f64; 8];
    for (r, &x) in rest.iter().zip(rest_x) {
        for k in 0..8 {
            tail[k] += r[k] * x;
        }
    }
    std::array::from_fn(|k| (lanes[0][k] + lanes[1][k]) + (lanes[2][k] + lanes[3][k]) + tail[k])
}

/// The sums behind a modal state's energies ([`ModalStepper::measure_state`]): sum omega^2 q^2
/// of the arrestor's coordinates (the first `lower`) and of the bridge's, sum v^2, sum g q and
/// sum c v^2.
struct EnergySums {
    lower_strain: f64,
    upper_strain: f64,
    kinetic: f64,
    gravity: f64,
    dissipation: f64,
}

/// [`EnergySums`] in four lanes each, in the CPU's widest vectors (the same bits whichever runs).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn energy_sums(q: &[f64], v: &[f64], omega2: &[f64], damping: &[f64], gravity: &[f64], lower: usize) -> EnergySums {
    EnergySums {
        lower_strain: weighted_squares(&omega2[..lower], &q[..lower]),
        upper_strain: weighted_squares(&omega2[lower..], &q[lower..]),
        kinetic: dot(v, v),
        gravity: dot(gravity, q),
        dissipation: weighted_squares(damping, v),
    }
}

/// Out of contact each elastic mode swings about its static deflection F_i / omega_i^2 with
/// amplitude A_i = sqrt(d^2 + (v / omega)^2) (into `amplitude`); its share of a probe's fourth
/// derivative is at most |P_ki| omega_i^4 A_i (`fourth`: those weights per coordinate, the
/// probes side by side as [`probe_dots`] takes them; the rigid mode's motion is a quadratic:
/// none). In the CPU's widest vectors (the same bits whichever runs), the padding's lane too
/// (see [`dots_side_by_side`]).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn fourth_derivative_bounds(
    q: &[f64],
    v: &[f64],
    load: &[f64],
    omega2: &[f64],
    amplitude: &mut [f64],
    fourth: &[[f64; 8]],
) -> [f64; 8] {
    let n = amplitude.len();
    let (q, v, load, omega2) = (&q[..n], &v[..n], &load[..n], &omega2[..n]);
    for i in 0..n {
        let w2 = omega2[i];
        let d = q[i] - load[i] / w2;
        let swing = (d * d + v[i] * v[i] / w2).sqrt();
        amplitude[i] = if w2 <= 0.0 { 0.0 } else { swing };
    }
    dots_side_by_side(fourth, amplitude)
}

/// sum term(a_i, b_i) over the common length, in four lanes (the compiler vectorises it; a plain
/// loop's single accumulator cannot be reordered), the lanes added pairwise and then the tail.
#[inline(always)]
fn four_lanes(a: &[f64], b: &[f64], term: impl Fn(f64, f64) -> f64) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut lanes = [0.0f64; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for l in 0..4 {
            lanes[l] += term(x[l], y[l]);
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(&x, &y)| term(x, y)).sum();
    lanes_total(lanes, tail)
}

/// Four lanes' sums added pairwise, then the tail's ([`four_lanes`]' order). Out of line: inlined,
/// the compiler kept the lanes in pairs of halves for this order, two shuffles a vector of terms.
#[inline(never)]
fn lanes_total(lanes: [f64; 4], tail: f64) -> f64 {
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The resets of the exact cache over a sequence of step sizes, replayed through its
    /// bookkeeping as `exact_step` does (a reset here only sets the size: the coefficients do not
    /// matter to which slot goes).
    fn resets_over(sizes: &[f64]) -> usize {
        let mut cache: Vec<ExactStage> = (0..EXACT_SLOTS).map(|_| ExactStage::default()).collect();
        let mut slots = [f64::NAN; EXACT_SLOTS];
        let (mut clock, mut resets, mut last) = (0, 0, 0);
        for &dt in sizes {
            let slot = exact_slot(&slots, last, dt).unwrap_or_else(|| {
                let j = evicted(&cache);
                cache[j] = ExactStage { dt, ..ExactStage::default() };
                slots[j] = dt;
                resets += 1;
                j
            });
            last = slot;
            clock += 1;
            cache[slot].used(clock);
        }
        resets
    }

    /// The sea example's pattern (issue 43): a contact's steps and the retakes that located its
    /// changes, then the free stage's long step cut at every motion row into the step and its
    /// remainder, with a few sizes met once (a peak's instant, a landing) now and then. Every
    /// recurring size is computed once: the resets are the distinct sizes. (The least used
    /// evicted, the first of equals, the row's two sizes took one slot in turn: 2 resets a row.)
    #[test]
    fn recurring_step_sizes_keep_their_coefficients_among_sizes_met_once() {
        let mut once = (1..).map(|k| 1e-6 + k as f64 * 1e-9);
        let mut sizes = Vec::new();
        let contact = [23.601e-6, 47.202e-6, 94.404e-6];
        for _ in 0..3 {
            for level in [0, 1, 2, 2, 1, 0, 0] {
                sizes.extend(std::iter::repeat_n(contact[level], 5));
            }
            sizes.extend(once.by_ref().take(40));
        }
        let (step, remainder) = (3.020928e-3, 1.979072e-3);
        for row in 0..300 {
            sizes.extend([step, remainder]);
            if row % 7 == 0 {
                sizes.extend(once.by_ref().take(3));
            }
        }
        sizes.extend(contact);
        let mut distinct = sizes.clone();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        assert_eq!(resets_over(&sizes), distinct.len());
    }

    /// A step size met first out of contact and then in contact gets the very contact
    /// coefficients (to the bit) of one met first in contact: the cache's history cannot move an
    /// answer. Sizes from a 1 ns retake (every mode in the series) to a long free step (every mode
    /// but the lowest in the closed form), on the default scenario's printed mesh with its modal
    /// damping and with Rayleigh's beta = 1e-3 (the high modes overdamped).
    #[test]
    fn a_sizes_contact_coefficients_do_not_depend_on_the_stage_that_met_it_first() {
        let overdamped = crate::model::Scenario { rayleigh_beta: 1e-3, ..Default::default() };
        for scenario in [crate::model::Scenario::default(), overdamped] {
            let scenario = crate::discretise::printed(&scenario).unwrap();
            let model = Model::new(&scenario).unwrap();
            let system = ModalSystem::new(&model).unwrap().with_damping(&scenario);
            for dt in [1e-9, 7.3e-7, 23.601e-6, 90.992e-6, 1.510464e-3] {
                let mut first_in_contact = ExactStage::default();
                first_in_contact.reset(&system, dt, true);
                let mut first_free = ExactStage::default();
                first_free.reset(&system, dt, false);
                first_free.prepare_contact(&system);
                let bits = |stage: &ExactStage| {
                    let columns = stage.columns.iter().chain(&stage.cubic_columns).flatten().map(|x| x.to_bits());
                    let bar = stage.bar;
                    let bar =
                        [bar.ag, bar.bg, bar.av, bar.bv, bar.ramp, bar.vramp, bar.af, bar.aa, bar.ab, bar.m11, bar.m22];
                    columns.chain(bar.map(f64::to_bits)).collect::<Vec<_>>()
                };
                assert_eq!(bits(&first_in_contact), bits(&first_free), "dt {dt}");
                assert_eq!(first_in_contact.cubic_columns[0].len(), system.omega2.len());
            }
        }
    }

    /// The contact step's sums of the ramp's responses are functions of the step size alone:
    /// the tangent's step with them kept from an earlier step (the second step of one scratch)
    /// gives the same bits as with them computed afresh (a new scratch), and the same as with
    /// the tangent's own coefficients (the stepper's cache without this size). And the step is
    /// the exact advance's derivative: out of contact each undamped mode turns by its angle
    /// omega dt (q1 = cos q0 + sin / omega v0), to 1e-12 of the difference (the cosine and sine
    /// series' round-off).
    #[test]
    fn the_tangent_steps_kept_sums_give_the_same_bits_as_fresh_ones() {
        use crate::solver::kinematics::TipForces;
        let scenario = crate::Scenario { damping_ratio: 0.0, ..crate::Scenario::default() };
        let sim = crate::Simulation::new(&scenario).expect("the default scenario runs");
        let mut stepper = ModalStepper::new(sim.model(), sim.modal().clone()).with_exact(true);
        let excitation = Excitation::forces(TipForces { upper: 0.0, lower: 0.0 });
        let mut state = sim.state().kinematics.clone();
        let n = state.displacement.len();
        let delta = Kinematics {
            displacement: DVector::from_fn(n, |i, _| 1e-9 * (1.0 + i as f64).sin()),
            velocity: DVector::from_fn(n, |i, _| 1e-7 * (2.0 + i as f64).cos()),
            acceleration: DVector::zeros(n),
        };
        let dt = 3.0e-5;
        stepper.step(&mut state, Stage::Contact, dt, &excitation);
        let bits = |k: &Kinematics| -> Vec<u64> {
            k.displacement.iter().chain(k.velocity.iter()).map(|x| x.to_bits()).collect()
        };
        let mut kept = TangentWork::default();
        let (mut first, mut second, mut fresh) = (delta.clone(), delta.clone(), delta.clone());
        assert!(stepper.exact_tangent_step(&delta, &mut first, Stage::Contact, dt, &mut kept));
        assert!(stepper.exact_tangent_step(&delta, &mut second, Stage::Contact, dt, &mut kept));
        assert!(stepper.exact_tangent_step(&delta, &mut fresh, Stage::Contact, dt, &mut TangentWork::default()));
        assert_eq!(bits(&first), bits(&second));
        assert_eq!(bits(&first), bits(&fresh));
        // A size the stepper never took: the tangent's own coefficients.
        let mut own = delta.clone();
        let unseen = 1.7e-5;
        assert!(stepper.exact_tangent_step(&delta, &mut own, Stage::Free, unseen, &mut kept));
        let s = stepper.system();
        let scale = delta.displacement.amax() + delta.velocity.amax() / s.omega2.max().sqrt();
        for i in 0..n {
            let w = s.omega2[i].sqrt();
            let (q0, v0) = (delta.displacement[i], delta.velocity[i]);
            let q1 = if w > 0.0 { (w * unseen).cos() * q0 + (w * unseen).sin() / w * v0 } else { q0 + unseen * v0 };
            assert!(
                (own.displacement[i] - q1).abs() <= 1e-12 * scale,
                "mode {i}: {} against {q1}",
                own.displacement[i]
            );
        }
    }

    /// The coefficients gathered a chunk of modes at a time and stored a column at a time are
    /// each mode's own ([`ModeStep::with_responses`], [`CubicStep`]) in its place, to the bit,
    /// and the bar's sums those added mode by mode: counts of modes with and without a tail
    /// short of a chunk, modes in the series, the closed form and overdamped, free and contact.
    #[test]
    fn the_chunked_coefficients_are_each_modes_own_in_its_place() {
        let dt = 2e-5;
        for n in [1, 3, 4, 5, 8, 9, 46] {
            let omega2: Vec<f64> =
                (0..n).map(|i| (1e2 * 1.9f64.powi(i as i32)).powi(2) * (i > 0) as u8 as f64).collect();
            let damping: Vec<f64> = (0..n).map(|i| [0.0, 3.0, 1e-3 * omega2[i], 4e5][i % 4]).collect();
            let b: Vec<f64> = (0..n).map(|i| 0.3 + (i as f64 * 0.7).sin()).collect();
            for contact in [false, true] {
                let mut columns: [Vec<f64>; 12] = std::array::from_fn(|_| vec![f64::NAN; n]);
                let mut cubic: [Vec<f64>; 18] = std::array::from_fn(|_| vec![f64::NAN; if contact { n } else { 0 }]);
                let sums = mode_coefficients((&omega2, &damping, &b), dt, &mut columns, &mut cubic);
                let mut own = BarSums::default();
                for i in 0..n {
                    let (w2, c) = (omega2[i], damping[i]);
                    let (mode, responses) = ModeStep::with_responses(w2, c, dt);
                    for (k, value) in mode_values(&mode).into_iter().enumerate() {
                        assert_eq!(columns[k][i].to_bits(), value.to_bits(), "n {n}, mode {i}, column {k}");
                    }
                    if contact {
                        let step = match responses {
                            Some(psi) => CubicStep::from_responses(c, dt, &psi),
                            None => CubicStep::new(w2, c, dt, &mode),
                        };
                        for (k, value) in cubic_values(&step).into_iter().enumerate() {
                            assert_eq!(cubic[k][i].to_bits(), value.to_bits(), "n {n}, mode {i}, contact column {k}");
                        }
                        own.add(b[i], (w2, c), &mode, &step);
                    }
                }
                let bits = |s: &BarSums| [s.fr, s.vr, s.f2, s.f3, s.v2, s.v3, s.ar, s.a2, s.a3, s.bb].map(f64::to_bits);
                assert_eq!(bits(&sums), bits(&own), "n {n}, contact {contact}");
            }
        }
    }

    #[test]
    fn the_probes_dots_side_by_side_are_each_columns_dot_to_the_bit() {
        // Lengths with and without a tail of the four lanes, x shorter than the rows.
        for (rows, n) in [(65, 65), (46, 46), (9, 7), (4, 4), (3, 3), (12, 10)] {
            let columns: Vec<f64> = (0..rows * PROBES).map(|i| ((i * 7919) % 1013) as f64 / 97.0 - 5.1).collect();
            let probe_rows: Vec<[f64; 8]> = (0..rows)
                .map(|i| std::array::from_fn(|k| if k < PROBES { columns[k * rows + i] } else { 0.0 }))
                .collect();
            let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin() * 1e-3 + 1.0 / (i as f64 + 3.0)).collect();
            let dots = probe_dots(&probe_rows, &x);
            for (k, d) in dots.iter().enumerate() {
                let one = dot(&columns[k * rows..k * rows + n], &x);
                assert_eq!(d.to_bits(), one.to_bits(), "rows {rows}, n {n}, probe {k}: {d} against {one}");
            }
        }
    }
}

//! Initial conditions at the instant of impact (paper Eqs. 14-26) with the compatibility
//! convention of docs/scenario.md: time 0 is the impact, the bridge is horizontal and rotating
//! rigidly, the arrestor rests in its self-weight deflection, and the beams touch.

use nalgebra::{Cholesky, DMatrix, DVector, Dyn};

use super::kinematics::{Excitation, Kinematics};
use super::modal::ModalSystem;
use crate::error::{Error, Result};
use crate::model::scenario::ImpactorKind;
use crate::model::{damping, Model, Probe};

/// What [`initial_state`] computes from a geometry alone, whatever the
/// run's speed, supports' motion or tip forces: computed once per geometry, the same bits as
/// computed per run.
#[derive(Debug)]
pub struct InitialFactors {
    /// The arrestor's stiffness factored (Cholesky); `None` when it has no DOF or is not
    /// positive definite (the initial state then meets its own error).
    pub lower_stiffness: Option<Cholesky<f64, Dyn>>,
    /// The full system's bridge shapes transposed, Phi_u^T.
    pub upper_shapes_transposed: DMatrix<f64>,
}

impl InitialFactors {
    /// The factors of `model` with its full modal system `full`.
    pub fn new(model: &Model, full: &ModalSystem) -> InitialFactors {
        let lower_stiffness = if model.lower.dofs() == 0 { None } else { model.lower.stiffness.clone().cholesky() };
        InitialFactors { lower_stiffness, upper_shapes_transposed: full.upper.shapes.transpose() }
    }
}

/// The rigid pitching of the bridge before impact (Eqs. 15-22).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pitching {
    /// Initial inclination alpha_u0 = atan(h / (l_u / 2)), rad (Eq. 20).
    pub initial_angle: f64,
    /// Angular acceleration epsilon_u = 3 g / (2 l_u), rad/s^2 (Eq. 17).
    pub angular_acceleration: f64,
    /// Time t_0 from release to the horizontal position, s (Eq. 21).
    pub fall_time: f64,
    /// Angular velocity omega_u0 at impact, rad/s (Eq. 22).
    pub angular_velocity: f64,
}

impl Pitching {
    /// Eqs. (17), (20)-(22).
    pub fn new(drop_height: f64, length: f64, gravity: f64) -> Pitching {
        let initial_angle = libm::atan(drop_height / (length / 2.0));
        let angular_acceleration = 1.5 * gravity / length;
        let fall_time = (4.0 / 3.0 * length / gravity * initial_angle).sqrt();
        Pitching { initial_angle, angular_acceleration, fall_time, angular_velocity: angular_acceleration * fall_time }
    }

    /// The pitching at impact of a bridge stated by its angular velocity `angular_velocity` at
    /// first contact (horizontal there): Eq. (17)'s angular acceleration under `gravity` (0 with
    /// none); the release angle and fall time are those of a fall from rest to that speed under
    /// `gravity` (Eqs. 21-22 inverted; 0 and infinite without gravity).
    pub fn at_speed(angular_velocity: f64, length: f64, gravity: f64) -> Pitching {
        let angular_acceleration = 1.5 * gravity / length;
        let fall_time = angular_velocity / angular_acceleration;
        let initial_angle = 0.75 * gravity / length * fall_time * fall_time;
        Pitching { initial_angle, angular_acceleration, fall_time, angular_velocity }
    }

    /// The pitching of a bridge whose mass is not uniform along it (sections, issue 30): mass
    /// `mass`, first and second moments `first` (int mu x dx) and `second` (int mu x^2 dx) about
    /// the hinge. Eq. (17) becomes epsilon = g S / J, Eq. (20) alpha = atan(h / x_g) with the
    /// centre of gravity at x_g = S / m, and Eqs. (21)-(22) t_0 = sqrt(2 alpha / epsilon),
    /// omega = epsilon t_0: the uniform bar's (S = m l / 2, J = m l^2 / 3) in general form.
    pub fn distributed(drop_height: f64, moments: (f64, f64, f64), gravity: f64) -> Pitching {
        let (mass, first, second) = moments;
        let initial_angle = libm::atan(drop_height / (first / mass));
        let angular_acceleration = gravity * first / second;
        let fall_time = (2.0 * initial_angle / angular_acceleration).sqrt();
        Pitching { initial_angle, angular_acceleration, fall_time, angular_velocity: angular_acceleration * fall_time }
    }

    /// [`Self::at_speed`] for a bridge of sections (see [`Self::distributed`]).
    pub fn distributed_at_speed(angular_velocity: f64, moments: (f64, f64, f64), gravity: f64) -> Pitching {
        let (_, first, second) = moments;
        let angular_acceleration = gravity * first / second;
        let fall_time = angular_velocity / angular_acceleration;
        let initial_angle = 0.5 * angular_acceleration * fall_time * fall_time;
        Pitching { initial_angle, angular_acceleration, fall_time, angular_velocity }
    }

    /// The pitching of scenario `s` under `gravity` (g plus the hinge's acceleration): from its
    /// impact speed when stated, else from its drop height.
    pub fn of(s: &crate::model::Scenario, gravity: f64) -> Pitching {
        if !s.upper.sections.is_empty() {
            let moments = crate::model::section::mass_moments(&s.upper_segments());
            return match s.impact_angular_velocity {
                Some(omega) => Pitching::distributed_at_speed(omega, moments, gravity),
                None => Pitching::distributed(s.drop_height, moments, gravity),
            };
        }
        match s.impact_angular_velocity {
            Some(omega) => Pitching::at_speed(omega, s.upper.length, gravity),
            None => Pitching::new(s.drop_height, s.upper.length, gravity),
        }
    }
}

/// Physical displacements, velocities and accelerations at t = 0 (global DOFs), relative to the
/// supports, under the excitation at t = 0: the fall before it happened under the supports'
/// accelerations at t = 0 (the bridge pitches under g + a_hinge, the arrestor rests under its
/// self-weight and its clamp's inertia loads), and the beams touch, the supports' offset included.
/// So supports sharing one constant vertical acceleration a give the run with gravity g + a.
pub fn initial_state(model: &Model, modal: &ModalSystem, excitation: &Excitation) -> Result<Kinematics> {
    initial_state_with(model, modal, excitation, None)
}

/// [`initial_state`] with what it takes from the geometry alone given (`factors`, made for
/// `model`'s geometry and `modal`: [`crate::solver::ModalCache`] keeps them per geometry): the
/// same operations on the same bits, so the same state to the bit, without factoring the
/// arrestor's stiffness and transposing the bridge's shapes each run.
pub fn initial_state_with(
    model: &Model,
    modal: &ModalSystem,
    excitation: &Excitation,
    factors: Option<&InitialFactors>,
) -> Result<Kinematics> {
    let s = &model.scenario;
    let forces = excitation.forces;
    let (upper_tip, lower_tip) = model.tip_force_vectors();
    let mut external = &upper_tip * forces.upper + &lower_tip * forces.lower;
    for (x, a) in model.support_loads().iter().zip(excitation.support_acceleration) {
        if a != 0.0 {
            external += x * a;
        }
    }
    let hinge_gravity = s.gravity + excitation.support_acceleration[0];
    // A drop needs a fall; a stated speed does not (gravity may be 0).
    let mass = s.upper.kind == ImpactorKind::Mass;
    let falls = if mass { s.impact_speed == 0.0 && s.drop_height > 0.0 } else { s.impact_angular_velocity.is_none() };
    if hinge_gravity.is_nan() || (falls && hinge_gravity <= 0.0) {
        return Err(Error::invalid(
            "upper.hinge_heave_acceleration",
            format!(
                "> -gravity = {} m/s^2 at t = 0 (the bridge falls onto the arrestor under gravity plus its \
                 hinge's acceleration)",
                -s.gravity
            ),
            excitation.support_acceleration[0],
        ));
    }
    let nl = model.lower.dofs();
    let nu = model.upper.dofs();
    let load_lower = model.lower.gravity_load.clone() + external.rows(0, nl);
    let load_upper = model.upper.gravity_load.clone() + external.rows(nl, nu);

    // Arrestor, Eqs. (25)-(26): at rest in its static deflection (a rigid support: none).
    let lower_displacement = if nl == 0 {
        DVector::zeros(0)
    } else if let Some(factor) = factors.and_then(|f| f.lower_stiffness.as_ref()) {
        factor.solve(&load_lower)
    } else {
        model.lower.stiffness.clone().cholesky().map(|c| c.solve(&load_lower)).ok_or_else(|| Error::Numerical {
            what: "initial conditions",
            detail: "the arrestor's stiffness matrix is singular".into(),
        })?
    };

    // Bridge, Eq. (23): rigid rotation about the hinge, pitching down (w = -x alpha, theta = -alpha).
    // A rigid impactor (issue 45): its one DOF translating down at its impact speed, its
    // acceleration (gravity and any tip force) from its rigid mode's out-of-balance load below.
    let (speed, angular_acceleration) = if mass {
        let fall = if s.impact_speed != 0.0 { s.impact_speed } else { (2.0 * hinge_gravity * s.drop_height).sqrt() };
        (fall, 0.0)
    } else {
        let pitching = Pitching::of(s, hinge_gravity);
        (pitching.angular_velocity, pitching.angular_acceleration)
    };
    let mut rotation = DVector::zeros(nu);
    for node in &model.upper.mesh.nodes {
        if let Some(i) = node.w {
            rotation[i] = if mass { -1.0 } else { -node.x };
        }
        if let Some(i) = node.theta {
            rotation[i] = -1.0;
        }
    }
    let upper_velocity = &rotation * speed;
    let mut upper_acceleration = &rotation * angular_acceleration;

    // Eq. (24) in the bridge's modes: each elastic mode is in quasi-static balance with
    // F - C v - M a. The rigid mode (omega = 0) takes the out-of-balance moment of any tip force
    // into its acceleration, and its amplitude is set so that the contact node meets the arrestor's end.
    // C v through the bridge's modes (Eq. 34: C = M Phi diag(c) Phi^T M), without forming C.
    let phi = &modal.upper.shapes;
    let transposed;
    let phi_t = match factors {
        Some(f) => &f.upper_shapes_transposed,
        None => {
            transposed = phi.transpose();
            &transposed
        }
    };
    let coefficients =
        damping::modal_coefficients(&modal.upper.omega, s.damping_ratio, s.rayleigh_alpha, s.rayleigh_beta);
    let modal_velocity = phi_t * (&model.upper.mass * &upper_velocity);
    let damping_force = &model.upper.mass * (phi * modal_velocity.component_mul(&coefficients));
    let residual = &load_upper - damping_force - &model.upper.mass * &upper_acceleration;
    let modal_residual = phi_t * residual;
    let mut q = DVector::zeros(nu);
    for i in 0..nu {
        let omega = modal.upper.omega[i];
        if omega > 0.0 {
            q[i] = modal_residual[i] / (omega * omega);
        } else {
            upper_acceleration += phi.column(i) * modal_residual[i];
        }
    }
    let no_dof =
        |what: &str| Error::Numerical { what: "initial conditions", detail: format!("{what} has no deflection DOF") };
    let contact_w = model.upper.mesh.nodes[model.contact_node].w.ok_or_else(|| no_dof("the bridge's contact node"))?;
    // The beams touch: the bridge's relative deflection there is the arrestor's (0 for a rigid
    // support) less the supports' offset.
    // (Issue 45: the arrestor's contact node, its free end by default.)
    let lower_tip = match model.lower.mesh.nodes[model.lower_contact_node].w {
        Some(w) => lower_displacement[w],
        None if nl == 0 => 0.0,
        None => return Err(no_dof("the arrestor's end")),
    };
    // (The excitation's offset holds the contact's clearance too: the beams touch
    // geometrically, the clearance still to close.)
    let clearance = s.contact.clearance;
    let supports = if clearance == 0.0 { excitation.gap_offset } else { excitation.gap_offset - clearance };
    let target = lower_tip - supports;
    let rigid = (0..nu).find(|&i| modal.upper.omega[i] == 0.0).ok_or_else(|| Error::Numerical {
        what: "initial conditions",
        detail: "the hinged bridge has no rigid-body mode".into(),
    })?;
    let elastic_at_contact = (phi.row(contact_w) * &q)[0];
    q[rigid] = (target - elastic_at_contact) / phi[(contact_w, rigid)];
    let upper_displacement = phi * q;

    let state = Kinematics {
        displacement: model.stack(&lower_displacement, &upper_displacement),
        velocity: model.stack(&DVector::zeros(nl), &upper_velocity),
        acceleration: model.stack(&DVector::zeros(nl), &upper_acceleration),
    };
    // The beams touch at t = 0, to round-off relative to the deflections (the fuzzer found
    // valid scenarios with large deflections for which an absolute 1e-9 m failed).
    debug_assert!({
        let gap = (model.probes.row(Probe::Gap as usize) * &state.displacement)[0] + supports;
        gap.abs() <= 1e-9 * (1.0 + state.displacement.amax() + supports.abs())
    });
    Ok(state)
}

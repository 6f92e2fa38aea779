//! The integrator's state and the interface shared by the production stepper and the dense oracle.

use nalgebra::DVector;
use serde::{Deserialize, Serialize};

use super::contact::Stage;
use crate::model::system::PROBES;

/// Displacements, velocities and accelerations at one instant (delta, delta', delta'' of Eq. 11),
/// in the stepper's own coordinates (modal for the production stepper, physical for the oracle).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Kinematics {
    /// Displacements, m and rad (or modal coordinates).
    pub displacement: DVector<f64>,
    /// Velocities.
    pub velocity: DVector<f64>,
    /// Accelerations.
    pub acceleration: DVector<f64>,
}

impl Kinematics {
    /// Copies `other` into `self` without allocating (same sizes).
    pub fn copy_from(&mut self, other: &Kinematics) {
        self.displacement.as_mut_slice().copy_from_slice(other.displacement.as_slice());
        self.velocity.as_mut_slice().copy_from_slice(other.velocity.as_slice());
        self.acceleration.as_mut_slice().copy_from_slice(other.acceleration.as_slice());
    }
}

/// The two external vertical forces for co-simulation, N, up positive.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TipForces {
    /// At the bridge's free end.
    pub upper: f64,
    /// At the arrestor's free end.
    pub lower: f64,
}

/// What drives the beams besides gravity at one instant: the tip forces, the supports'
/// accelerations (each constant between two instants at which the motion is given: the load of
/// the moving-base form, sum_j a_j x_j with x_j = -M r_j) and the supports' relative displacement,
/// which the contact gap adds to the beams' relative deflections (issue 17). The default is the
/// fixed supports of the paper.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Excitation {
    /// The tip forces, N.
    pub forces: TipForces,
    /// Hinge heave, clamp heave (m/s^2) and clamp rotation (rad/s^2) accelerations.
    pub support_acceleration: [f64; 3],
    /// h - c - theta l_l at the instant, m: added to the beams' relative gap.
    pub gap_offset: f64,
    /// Its rate, m/s.
    pub gap_offset_rate: f64,
    /// Its acceleration, m/s^2 (constant between the supports' motion changes): an exact contact
    /// step takes the offset as the quadratic it is, not as a line through its end.
    pub gap_offset_acceleration: f64,
}

impl Excitation {
    /// The fixed supports under `forces`.
    pub fn forces(forces: TipForces) -> Excitation {
        Excitation { forces, ..Excitation::default() }
    }

    /// True when the loads (tip forces, support accelerations) equal `other`'s: the modal load
    /// is the same, whatever the gap offset.
    pub fn same_load(&self, other: &Excitation) -> bool {
        self.forces == other.forces && self.support_acceleration == other.support_acceleration
    }

    /// True when a support accelerates.
    pub fn moves(&self) -> bool {
        self.support_acceleration.iter().any(|a| *a != 0.0)
    }
}

/// Energy terms that depend on the state alone.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energies {
    /// 1/2 v^T M v, J.
    pub kinetic: f64,
    /// 1/2 delta^T K delta of both beams (bar excluded), J.
    pub beam_strain: f64,
    /// 1/2 delta_u^T K_u delta_u of the bridge alone (Eq. 36), J.
    pub upper_strain: f64,
    /// -F_g^T delta: potential of gravity from the undeformed horizontal position, J.
    pub gravity_potential: f64,
    /// -(sum_j a_j x_j)^T delta: potential of the supports' inertia loads at the excitation's
    /// accelerations, J (zero for fixed supports). Constant accelerations make it a potential
    /// between two given instants; the simulation books its change as the supports' work.
    pub inertial_potential: f64,
    /// v^T C v: power dissipated by damping, W.
    pub dissipation_rate: f64,
}

/// Support reactions and tip velocities at one instant: what a platform or a spring on a tip
/// couples to.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SupportAndTips {
    /// Vertical force of the clamp on the arrestor, N, up positive.
    pub clamp_force: f64,
    /// Moment of the clamp on the arrestor, N m, counter-clockwise positive (x from the clamp).
    pub clamp_moment: f64,
    /// Vertical force of the hinge on the bridge, N, up positive.
    pub hinge_force: f64,
    /// Vertical velocity of the arrestor's end, m/s.
    pub lower_tip_velocity: f64,
    /// Vertical velocity of the bridge's free end, m/s.
    pub upper_tip_velocity: f64,
}

/// One integration method for Eqs. (7)-(11) over a model.
pub trait Stepper {
    /// The scratch a tangent step keeps between steps ([`Self::tangent_step`]; `()` for a
    /// stepper without one).
    type TangentWork: Clone + std::fmt::Debug + Default + Send + Sync;

    /// Advances `state` by `dt` in `stage`, with the excitation at the end of the step (F_{i+1}).
    fn step(&mut self, state: &mut Kinematics, stage: Stage, dt: f64, excitation: &Excitation);
    /// [`Stepper::step`], then the probes and energies of the new state (a stepper may sum them
    /// in its update pass).
    fn step_measured(
        &mut self,
        state: &mut Kinematics,
        stage: Stage,
        dt: f64,
        excitation: &Excitation,
    ) -> ([f64; PROBES], Energies) {
        self.step(state, stage, dt, excitation);
        self.measure(state, stage, excitation)
    }
    /// [`Stepper::step`] to a point inside the step just taken (a dense output's sample, a
    /// peak's instant), leaving what the stepper says of that step ([`Stepper::step_dissipation`],
    /// [`Stepper::force_ramp_error`]) as it was.
    fn step_aside(&mut self, state: &mut Kinematics, stage: Stage, dt: f64, excitation: &Excitation) {
        self.step(state, stage, dt, excitation);
    }
    /// Sets the acceleration that Eq. (1) gives for the state's displacement and velocity under
    /// `excitation` (gravity included): M a = F - K delta - C delta', with the bar in contact.
    /// Used where the load jumps, so that the next step starts from equilibrium.
    fn equilibrium_acceleration(&mut self, state: &mut Kinematics, stage: Stage, excitation: &Excitation);
    /// The damping's work over the last step taken, J, where the stepper computes it exactly
    /// (the exact modal advance); `None`: the simulation books the trapezoid of the dissipation
    /// rate.
    fn step_dissipation(&self) -> Option<f64> {
        None
    }
    /// After an exact contact step: the estimated departure of the bar's force from the cubic
    /// the step assumed, N (the step-size control's measure); `None` otherwise.
    fn force_ramp_error(&self) -> Option<f64> {
        None
    }
    /// True when the stepper's steps may grow beyond the stability-bound plan (exact advance).
    fn adapts_steps(&self) -> bool {
        false
    }
    /// Out of contact, a bound on each probe's fourth time derivative over the coming free
    /// motion (the exact advance: the step-size control's measure of what a cubic through a
    /// step's ends can miss); `None` for other steppers.
    fn free_fourth_derivatives(&mut self, _state: &Kinematics) -> Option<[f64; PROBES]> {
        None
    }
    /// The model's probes (see [`crate::model::Probe`]) applied to a displacement vector (or to
    /// a velocity vector, for rates), in the stepper's coordinates: the beams' relative
    /// deflections (the gap without the supports' offset).
    fn probes(&self, displacement: &DVector<f64>) -> [f64; PROBES];
    /// The rates of the probes at a state in `stage` (the probes of the velocity, with a truncated
    /// basis's static correction moving with the contact force), the gap's with the supports'.
    fn rates(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> [f64; PROBES] {
        let _ = stage;
        let mut rates = self.probes(&state.velocity);
        rates[crate::model::Probe::Gap as usize] += excitation.gap_offset_rate;
        rates
    }
    /// Support reactions (the supports' rows of the unconstrained equations of motion: stiffness,
    /// damping, consistent mass and loads) and tip velocities of the state,
    /// in `stage` under `excitation` (a truncated basis adds its discarded modes' static response;
    /// the supports' own inertia is included).
    fn support_and_tips(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> SupportAndTips;
    /// The probes and energy terms of a state in `stage` under `excitation`: [`Stepper::probes`]
    /// (the gap with the supports' offset) and [`Stepper::energies`], with a truncated basis's
    /// static correction.
    fn measure(&self, state: &Kinematics, stage: Stage, excitation: &Excitation) -> ([f64; PROBES], Energies) {
        let _ = stage;
        let mut probes = self.probes(&state.displacement);
        probes[crate::model::Probe::Gap as usize] += excitation.gap_offset;
        (probes, self.energies(state, excitation))
    }
    /// Energy terms of the state (the inertial potential at the excitation's accelerations).
    fn energies(&self, state: &Kinematics, excitation: &Excitation) -> Energies;
    /// The stepper's state from physical kinematics.
    fn own_coordinates(&self, physical: &Kinematics) -> Kinematics;

    /// Whether measurements take the energy terms (default); without, [`Stepper::measure`] and a
    /// measured step leave them 0 (a run whose energies nobody reads: an answer's check runs).
    fn keep_energies(&mut self, keep: bool) {
        let _ = keep;
    }

    /// True when the state's coordinates are the modal system's (the stress envelope is
    /// evaluated from them); the dense oracle's are physical.
    fn modal_coordinates(&self) -> bool {
        false
    }

    /// Advances a difference of two states, `start`, over the step just taken into `delta` (of
    /// the same size; see the modal stepper's `exact_tangent_step`); false where the stepper has
    /// no such tangent (the default: the twin runs instead).
    fn tangent_step(
        &self,
        start: &Kinematics,
        delta: &mut Kinematics,
        stage: Stage,
        dt: f64,
        work: &mut Self::TangentWork,
    ) -> bool {
        let _ = (start, delta, stage, dt, work);
        false
    }
}

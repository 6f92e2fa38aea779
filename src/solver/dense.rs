//! The test oracle: Eqs. (7)-(11) exactly as printed, on dense physical matrices. Each step
//! assembles K for its stage (Eq. 2 or 4), forms S, P, Q, R (Eqs. 9-10) and solves Eq. (7)
//! with an LU factorisation. O(n^3) per step; the production stepper must agree to round-off.

use nalgebra::{DMatrix, DVector};

use super::contact::Stage;
use super::kinematics::{Energies, Excitation, Kinematics, Stepper, SupportAndTips};
use super::modal::ModalSystem;
use crate::model::contact_law::ContactLaw;
use crate::model::system::PROBES;
use crate::model::{damping, Model, Probe};

/// Literal dense linear acceleration method in physical coordinates.
#[derive(Clone, Debug)]
pub struct DenseStepper {
    mass: DMatrix<f64>,
    damping: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    coupled_stiffness: DMatrix<f64>,
    upper_stiffness_offset: usize,
    gravity: DVector<f64>,
    upper_tip: DVector<f64>,
    lower_tip: DVector<f64>,
    /// The supports' unit inertia loads x_j = -M r_j.
    support_loads: [DVector<f64>; 3],
    /// The supports' own inertia in each reaction per unit acceleration.
    support_reactions: [[f64; 3]; crate::model::REACTIONS],
    /// The contact vector b.
    contact: DVector<f64>,
    bar_stiffness: f64,
    /// A nonlinear contact law (issue 28), solved each step; `None`: the linear bar.
    law: Option<crate::model::contact_law::ContactLaw>,
    probes: DMatrix<f64>,
    /// Support reactions in physical coordinates.
    reactions: Vec<PhysicalReaction>,
}

/// A support reaction's rows over the physical DOFs: R = k . q + c . v + m . a - load.
#[derive(Clone, Debug)]
struct PhysicalReaction {
    stiffness: DVector<f64>,
    damping: DVector<f64>,
    mass: DVector<f64>,
    load: f64,
}

impl DenseStepper {
    /// Assembles M, C (Eq. 34 per beam, from the beams' modes) and K of `model`.
    pub fn new(model: &Model, modal: &ModalSystem) -> DenseStepper {
        let s = &model.scenario;
        let beam_damping = |beam: &crate::model::Beam, modes: &super::eigen::Modes| {
            let c = damping::modal_coefficients(&modes.omega, s.damping_ratio, s.rayleigh_alpha, s.rayleigh_beta);
            damping::physical_matrix(&beam.mass, &modes.shapes, &c)
        };
        let c =
            model.block_diagonal(&beam_damping(&model.lower, &modal.lower), &beam_damping(&model.upper, &modal.upper));
        let (upper_tip, lower_tip) = model.tip_force_vectors();
        let mass_shapes = model.mass() * modal.shapes();
        DenseStepper {
            mass: model.mass(),
            damping: c,
            stiffness: model.stiffness(),
            coupled_stiffness: model.coupled_stiffness(),
            upper_stiffness_offset: model.lower.dofs(),
            gravity: model.gravity_load(),
            upper_tip,
            lower_tip,
            support_loads: model.support_loads(),
            support_reactions: model.support_reaction_inertia(),
            contact: model.contact_vector(),
            bar_stiffness: model.bar_stiffness,
            law: s.contact_law(),
            probes: model.probes.clone(),
            // Physical rows from the modal ones: d = Phi^-T Phi^T k = M Phi (Phi^T k) (mass-normalised
            // modes), and the same for the damping and mass rows.
            reactions: modal
                .reactions
                .iter()
                .map(|r| {
                    let back = |modal_row: &DVector<f64>| &mass_shapes * modal_row;
                    PhysicalReaction {
                        stiffness: back(&r.displacement),
                        damping: back(&r.velocity),
                        mass: back(&r.acceleration),
                        load: r.load,
                    }
                })
                .collect(),
        }
    }
}

impl DenseStepper {
    /// F of Eq. (8) at the step's end: gravity, the tip forces, the supports' inertia
    /// sum_j a_j x_j, and in contact the bar's pull from the supports' offset, -k_c b d.
    fn load(&self, stage: Stage, excitation: &Excitation) -> DVector<f64> {
        let forces = excitation.forces;
        let mut load = &self.gravity + &self.upper_tip * forces.upper + &self.lower_tip * forces.lower;
        for (x, a) in self.support_loads.iter().zip(excitation.support_acceleration) {
            load += x * a;
        }
        if stage.is_contact() && self.law.is_none() {
            load -= &self.contact * (self.bar_stiffness * excitation.gap_offset);
        }
        load
    }
}

impl DenseStepper {
    /// Eqs. (7)-(11) in contact under a nonlinear law (issue 28), written out: the beams' own
    /// S a+ = f + b P, with P = law(delta+, delta+') and delta+ = -(b^T q+ + d) solved as one
    /// scalar equation.
    fn step_with_law(&self, state: &mut Kinematics, law: &ContactLaw, dt: f64, excitation: &Excitation) {
        let (k, c) = (&self.stiffness, &self.damping);
        let s = &self.mass + c * (dt / 2.0) + k * (dt * dt / 6.0);
        let q = c + k * dt;
        let r = c * (dt / 2.0) + k * (dt * dt / 3.0);
        let load = self.load(Stage::Free, excitation);
        let f = load - (k * &state.displacement + q * &state.velocity + r * &state.acceleration);
        let n = f.len();
        let lu = s.lu();
        let nan = || DVector::from_element(n, f64::NAN);
        let free = lu.solve(&f).unwrap_or_else(nan);
        let unit = lu.solve(&self.contact).unwrap_or_else(nan);
        let (d, v, a) = (&state.displacement, &state.velocity, &state.acceleration);
        let b = &self.contact;
        let flexibility = b.dot(&unit);
        let z = d + v * dt + a * (dt * dt / 3.0);
        let delta = -(b.dot(&z) + excitation.gap_offset + dt * dt / 6.0 * b.dot(&free));
        let rate = -(b.dot(&(v + a * (dt / 2.0))) + excitation.gap_offset_rate + dt / 2.0 * b.dot(&free));
        let force = law.solve(delta, dt * dt / 6.0 * flexibility, rate, dt / 2.0 * flexibility);
        let a_next = free + unit * force;
        let a = &state.acceleration;
        state.displacement += &state.velocity * dt + a * (dt * dt / 3.0) + &a_next * (dt * dt / 6.0);
        state.velocity += (a + &a_next) * (dt / 2.0);
        state.acceleration = a_next;
    }
}

impl Stepper for DenseStepper {
    type TangentWork = ();

    fn step(&mut self, state: &mut Kinematics, stage: Stage, dt: f64, excitation: &Excitation) {
        if let (true, Some(law)) = (stage.is_contact(), self.law) {
            return self.step_with_law(state, &law, dt, excitation);
        }
        let k = if stage.is_contact() { &self.coupled_stiffness } else { &self.stiffness };
        let c = &self.damping;
        // Eq. (9) and (10).
        let s = &self.mass + c * (dt / 2.0) + k * (dt * dt / 6.0);
        let p = k;
        let q = c + k * dt;
        let r = c * (dt / 2.0) + k * (dt * dt / 3.0);
        // Eq. (8).
        let load = self.load(stage, excitation);
        let f = load - (p * &state.displacement + q * &state.velocity + r * &state.acceleration);
        // Eq. (7). S is symmetric positive definite for any dt > 0; LU keeps the oracle literal.
        // A failed solve (only with non-finite input) yields NaN, which the simulation reports.
        let n = f.len();
        let a_next = s.lu().solve(&f).unwrap_or_else(|| DVector::from_element(n, f64::NAN));
        // Eq. (11).
        let a = &state.acceleration;
        state.displacement += &state.velocity * dt + a * (dt * dt / 3.0) + &a_next * (dt * dt / 6.0);
        state.velocity += (a + &a_next) * (dt / 2.0);
        state.acceleration = a_next;
    }

    fn equilibrium_acceleration(&mut self, state: &mut Kinematics, stage: Stage, excitation: &Excitation) {
        let k = if stage.is_contact() { &self.coupled_stiffness } else { &self.stiffness };
        let load = self.load(stage, excitation);
        let f = load - k * &state.displacement - &self.damping * &state.velocity;
        let n = f.len();
        state.acceleration = self.mass.clone().lu().solve(&f).unwrap_or_else(|| DVector::from_element(n, f64::NAN));
    }

    fn probes(&self, displacement: &DVector<f64>) -> [f64; PROBES] {
        let values = &self.probes * displacement;
        let mut out = [0.0; PROBES];
        out.copy_from_slice(values.as_slice());
        out
    }

    fn support_and_tips(&self, state: &Kinematics, _stage: Stage, excitation: &Excitation) -> SupportAndTips {
        let (q, v, a) = (&state.displacement, &state.velocity, &state.acceleration);
        let r: Vec<f64> = self
            .reactions
            .iter()
            .zip(&self.support_reactions)
            .map(|(r, inertia)| {
                let support: f64 = inertia.iter().zip(excitation.support_acceleration).map(|(m, a)| m * a).sum();
                r.stiffness.dot(q) + r.damping.dot(v) + r.mass.dot(a) - r.load + support
            })
            .collect();
        let rates = &self.probes * v;
        SupportAndTips {
            clamp_force: r[0],
            clamp_moment: r[1],
            hinge_force: r[2],
            lower_tip_velocity: rates[Probe::LowerTipDeflection as usize],
            upper_tip_velocity: rates[Probe::UpperTipDeflection as usize],
        }
    }

    fn energies(&self, state: &Kinematics, excitation: &Excitation) -> Energies {
        let (d, v) = (&state.displacement, &state.velocity);
        let n0 = self.upper_stiffness_offset;
        let nu = d.len() - n0;
        let du = d.rows(n0, nu);
        let ku = self.stiffness.view((n0, n0), (nu, nu));
        Energies {
            kinetic: 0.5 * v.dot(&(&self.mass * v)),
            beam_strain: 0.5 * d.dot(&(&self.stiffness * d)),
            upper_strain: 0.5 * du.dot(&(ku * du)),
            gravity_potential: -self.gravity.dot(d),
            inertial_potential: -self
                .support_loads
                .iter()
                .zip(excitation.support_acceleration)
                .map(|(x, a)| a * x.dot(d))
                .sum::<f64>(),
            dissipation_rate: v.dot(&(&self.damping * v)),
        }
    }

    fn own_coordinates(&self, physical: &Kinematics) -> Kinematics {
        physical.clone()
    }
}

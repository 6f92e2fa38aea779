//! The two-beam system in the beams' own mass-normalised modal coordinates: out of contact
//! M = I, C and K are diagonal; the contact bar adds k_c b b^T, a rank-one term.

use nalgebra::{DMatrix, DVector};

use super::eigen::Modes;
use super::graded::beam_modes;
use super::secular::coupled_modes;
use super::static_correction::StaticCorrection;
use crate::error::Result;
use crate::model::{damping, Model, Scenario, REACTIONS};

/// Largest stable step of the linear acceleration method: dt * omega_max <= sqrt(12).
pub const STABILITY_LIMIT: f64 = 3.464_101_615_137_754_6;

/// Modes of each beam, of the coupled system, and the modal form of the model.
#[derive(Clone, Debug)]
pub struct ModalSystem {
    /// Arrestor alone (clamped-free with tip mass): Table 2, column 1.
    pub lower: Modes,
    /// Bridge alone (hinged-free): Table 2, column 2.
    pub upper: Modes,
    /// Both beams joined by an always-active bar: Table 2, column 3.
    pub coupled: Modes,
    /// omega_i^2 of all modal coordinates (arrestor's first), 1/s^2.
    pub omega2: DVector<f64>,
    /// Modal damping coefficients c_i, 1/s.
    pub damping: DVector<f64>,
    /// Contact vector in modal coordinates, Phi^T b.
    pub contact: DVector<f64>,
    /// Gravity load in modal coordinates, Phi^T F_g.
    pub gravity: DVector<f64>,
    /// Unit upper tip force in modal coordinates.
    pub upper_tip: DVector<f64>,
    /// Unit lower tip force in modal coordinates.
    pub lower_tip: DVector<f64>,
    /// The supports' unit inertia loads in modal coordinates, Phi^T x_j (hinge heave, clamp heave,
    /// clamp rotation; see [`Model::support_loads`]).
    pub support_loads: [DVector<f64>; 3],
    /// The supports' own inertia in each reaction per unit support acceleration
    /// ([`Model::support_reaction_inertia`]).
    pub support_reactions: [[f64; 3]; REACTIONS],
    /// Probe functionals in modal coordinates (probes Phi).
    pub probes: DMatrix<f64>,
    /// The stress envelope's station functionals in modal coordinates (rows in the order of
    /// [`crate::model::stations::Stations::all`]; issue 30).
    pub stations: DMatrix<f64>,
    /// Number of arrestor modes (the first block of coordinates).
    pub lower_dofs: usize,
    /// Contact bar stiffness, N/m.
    pub bar_stiffness: f64,
    /// The support reactions (clamp force, clamp moment, hinge force) in modal coordinates.
    pub reactions: [ModalReaction; REACTIONS],
    /// The discarded modes' static response (all zero for the full basis); with it
    /// `bar_stiffness` is the effective k_c / (1 + k_c f_r) (see [`super::truncation`]).
    pub correction: StaticCorrection,
    /// The cut-off frequency the basis was truncated at, rad/s (`None`: every mode of the mesh).
    pub cutoff: Option<f64>,
    /// Modal coordinates of the full basis (= physical DOFs of the mesh).
    pub full_dofs: usize,
    /// A contact law solved each step (a power law or Hunt-Crossley damping; issue 28), or `None`
    /// for the paper's linear bar; with one, `bar_stiffness` is only the coupled modes' rate.
    pub law: Option<crate::model::contact_law::ContactLaw>,
}

/// A support reaction in modal coordinates: R = d . q + v . q' + a . q'' - load.
#[derive(Clone, Debug)]
pub struct ModalReaction {
    /// Phi^T k_s: the stiffness row.
    pub displacement: DVector<f64>,
    /// The damping row. Modal damping (Eq. 34) defines damping forces on the free DOFs only,
    /// M Phi (c o q'); the support row takes the same field through its mass row, M_s Phi (c o q'),
    /// except the Rayleigh beta K part, which is beta K_s v as the physics has it.
    pub velocity: DVector<f64>,
    /// Phi^T m_s: the consistent mass row.
    pub acceleration: DVector<f64>,
    /// Consistent self-weight load on the support DOF, N (N m).
    pub load: f64,
}

impl ModalSystem {
    /// Computes the modes of both beams and of the coupled system and the modal damping (the
    /// time steps are resolved and checked by [`super::StepPlan`]). Every mode of the mesh is
    /// kept; [`ModalSystem::for_run`] gives the basis a run steps in.
    pub fn new(model: &Model) -> Result<ModalSystem> {
        let s = &model.scenario;
        // Rigid-body modes by count, from the supports: the clamped arrestor none, the hinged bridge one.
        let (lower_rigid, upper_rigid) = (model.lower.mesh.rigid_modes(), model.upper.mesh.rigid_modes());
        // A graded beam (elements differing in length by more than 10:1) takes the inverse
        // problem of [`super::graded`]; every other beam the ordinary solve, as it always did.
        let lower = beam_modes(&model.lower, "the arrestor (lower)")?;
        let upper = beam_modes(&model.upper, "the bridge (upper)")?;
        let shapes = model.block_diagonal(&lower.shapes, &upper.shapes);
        let omega: Vec<f64> = lower.omega.iter().chain(upper.omega.iter()).copied().collect();
        let omega = DVector::from_vec(omega);
        let omega2 = omega.map(|w| w * w);
        let damping = damping::modal_coefficients(&omega, s.damping_ratio, s.rayleigh_alpha, s.rayleigh_beta);
        let contact = shapes.transpose() * model.contact_vector();
        let (upper_tip, lower_tip) = model.tip_force_vectors();
        let bar_stiffness = model.bar_stiffness;
        // Coupled modes: in modal coordinates M = I and K = diag(omega^2) + k b b^T, a rank-one
        // update solved through its secular equation (exact to round-off in each eigenvalue, where
        // a dense solver's error eps * omega_max^2 swamps the low modes of fine meshes). The bar,
        // away from the hinge, holds the bridge's rotation: one rigid motion fewer than the beams.
        let coupled_rigid = (lower_rigid + upper_rigid).saturating_sub(1);
        let coupled_modal = coupled_modes(&omega2, &contact, bar_stiffness, coupled_rigid)?;
        let coupled = Modes { shapes: &shapes * &coupled_modal.shapes, omega: coupled_modal.omega };
        let system = ModalSystem {
            gravity: shapes.transpose() * model.gravity_load(),
            upper_tip: shapes.transpose() * upper_tip,
            lower_tip: shapes.transpose() * lower_tip,
            support_loads: model.support_loads().map(|x| shapes.transpose() * x),
            support_reactions: model.support_reaction_inertia(),
            probes: &model.probes * &shapes,
            stations: model.station_rows() * &shapes,
            reactions: model.reactions().map(|r| {
                let displacement = shapes.transpose() * &r.stiffness;
                let acceleration = shapes.transpose() * &r.mass;
                let velocity = reaction_velocity(&displacement, &acceleration, &damping, &omega2, s.rayleigh_beta);
                ModalReaction { displacement, velocity, acceleration, load: r.load }
            }),
            lower_dofs: lower.omega.len(),
            lower,
            upper,
            coupled,
            omega2,
            damping,
            contact,
            bar_stiffness,
            correction: StaticCorrection::default(),
            cutoff: None,
            full_dofs: model.dofs(),
            law: s.contact_law(),
        };
        Ok(system)
    }

    /// The system with the damping of `scenario` (its damping ratio and Rayleigh terms): the modal
    /// coefficients and the reactions' damping rows, the only parts that depend on it, computed
    /// per coordinate as [`ModalSystem::new`] computes them, so a system built for another damping
    /// (and truncated or not) becomes, to the bit, the one built for this damping
    /// ([`super::modal_cache::ModalCache`] shares the rest between runs).
    pub fn with_damping(mut self, scenario: &Scenario) -> ModalSystem {
        let omega: Vec<f64> = self.lower.omega.iter().chain(self.upper.omega.iter()).copied().collect();
        let s = scenario;
        self.damping =
            damping::modal_coefficients(&DVector::from_vec(omega), s.damping_ratio, s.rayleigh_alpha, s.rayleigh_beta);
        for r in &mut self.reactions {
            r.velocity =
                reaction_velocity(&r.displacement, &r.acceleration, &self.damping, &self.omega2, s.rayleigh_beta);
        }
        self
    }

    /// Number of modal coordinates (= physical DOFs).
    pub fn dofs(&self) -> usize {
        self.omega2.len()
    }

    /// Highest natural frequency of a stage, rad/s.
    pub fn omega_max(&self, contact: bool) -> f64 {
        if contact {
            self.coupled.omega_max()
        } else {
            self.lower.omega_max().max(self.upper.omega_max())
        }
    }

    /// Global block-diagonal matrix of mode shapes (physical = shapes * modal): one row per
    /// physical DOF, one column per kept mode.
    pub fn shapes(&self) -> DMatrix<f64> {
        block_columns(&self.lower.shapes, &self.upper.shapes)
    }

    /// The modal load Phi^T (F_g + F_tips + sum_j a_j x_j) of an excitation.
    pub fn load(&self, excitation: &super::kinematics::Excitation) -> DVector<f64> {
        let mut load = DVector::zeros(self.dofs());
        self.load_into(excitation, &mut load);
        load
    }

    /// [`Self::load`] into `load` (resized to the modes): no allocation for a stepper that keeps
    /// it (a sea's load changes every 5 ms).
    pub fn load_into(&self, excitation: &super::kinematics::Excitation, load: &mut DVector<f64>) {
        let f = excitation.forces;
        let n = self.dofs();
        if load.len() != n {
            *load = DVector::zeros(n);
        }
        let (g, u, l) =
            (&self.gravity.as_slice()[..n], &self.upper_tip.as_slice()[..n], &self.lower_tip.as_slice()[..n]);
        for (i, out) in load.as_mut_slice().iter_mut().enumerate() {
            *out = (g[i] + u[i] * f.upper) + l[i] * f.lower;
        }
        self.add_support_loads(excitation, load);
    }

    /// The combined support inertia load sum_j a_j Phi^T x_j of an excitation (zero when no support
    /// accelerates).
    pub fn support_load(&self, excitation: &super::kinematics::Excitation) -> DVector<f64> {
        let mut load = DVector::zeros(self.dofs());
        self.support_load_into(excitation, &mut load);
        load
    }

    /// [`Self::support_load`] into `load` (resized to the modes).
    pub fn support_load_into(&self, excitation: &super::kinematics::Excitation, load: &mut DVector<f64>) {
        if load.len() == self.dofs() {
            load.fill(0.0);
        } else {
            *load = DVector::zeros(self.dofs());
        }
        self.add_support_loads(excitation, load);
    }

    /// Adds a_j Phi^T x_j of each accelerating support to `load`, one support after the other:
    /// in one pass, each coordinate's terms added in the supports' order (the bits of a pass per
    /// support).
    fn add_support_loads(&self, excitation: &super::kinematics::Excitation, load: &mut DVector<f64>) {
        let mut active = [(&[][..], 0.0); 3];
        let mut count = 0;
        for (x, a) in self.support_loads.iter().zip(excitation.support_acceleration) {
            if a != 0.0 {
                active[count] = (x.as_slice(), a);
                count += 1;
            }
        }
        let load = load.as_mut_slice();
        match active[..count] {
            [] => {}
            [(x, a)] => {
                for (l, x) in load.iter_mut().zip(x) {
                    *l += a * x;
                }
            }
            [(x, a), (y, b)] => {
                for ((l, x), y) in load.iter_mut().zip(x).zip(y) {
                    *l = (*l + a * x) + b * y;
                }
            }
            [(x, a), (y, b), (z, c)] => {
                for (((l, x), y), z) in load.iter_mut().zip(x).zip(y).zip(z) {
                    *l = ((*l + a * x) + b * y) + c * z;
                }
            }
            _ => unreachable!("three supports at most"),
        }
    }

    /// True when modes were discarded (the static correction is in use).
    pub fn is_truncated(&self) -> bool {
        self.dofs() < self.full_dofs
    }
}

/// A support reaction's damping row (see [`ModalReaction::velocity`]): per coordinate
/// a_i (c_i - beta omega_i^2) + beta d_i.
fn reaction_velocity(
    displacement: &DVector<f64>,
    acceleration: &DVector<f64>,
    damping: &DVector<f64>,
    omega2: &DVector<f64>,
    beta: f64,
) -> DVector<f64> {
    DVector::from_fn(acceleration.len(), |i, _| {
        acceleration[i] * (damping[i] - beta * omega2[i]) + beta * displacement[i]
    })
}

/// [lower 0; 0 upper] for blocks of any shape.
pub(crate) fn block_columns(lower: &DMatrix<f64>, upper: &DMatrix<f64>) -> DMatrix<f64> {
    let (rl, cl) = lower.shape();
    let (ru, cu) = upper.shape();
    let mut a = DMatrix::zeros(rl + ru, cl + cu);
    a.view_mut((0, 0), (rl, cl)).copy_from(lower);
    a.view_mut((rl, cl), (ru, cu)).copy_from(upper);
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::sea::components::SplitMix64;
    use crate::solver::kinematics::Excitation;

    /// The supports' loads in one pass ([`ModalSystem::add_support_loads`]) are a pass per
    /// accelerating support's, to the bit, on the default scenario's modes, for random loads and
    /// accelerations with every pattern of zeros (none to all three supports accelerating).
    #[test]
    fn the_support_loads_in_one_pass_are_a_pass_per_support_to_the_bit() {
        let model = Model::new(&crate::discretise::printed(&Scenario::default()).unwrap()).unwrap();
        let system = ModalSystem::new(&model).unwrap();
        assert!(system.support_loads.iter().all(|x| x.iter().any(|v| *v != 0.0)));
        let mut rng = SplitMix64::new(45);
        let mut random = || rng.next_f64() - 0.5;
        for pattern in 0..8 {
            let support_acceleration = std::array::from_fn(|j| if pattern & (1 << j) != 0 { random() } else { 0.0 });
            let excitation = Excitation { support_acceleration, ..Excitation::default() };
            let start = DVector::from_fn(system.dofs(), |_, _| random());
            let mut load = start.clone();
            system.add_support_loads(&excitation, &mut load);
            let mut expected = start;
            for (x, a) in system.support_loads.iter().zip(support_acceleration) {
                if a != 0.0 {
                    for (l, xi) in expected.iter_mut().zip(x.iter()) {
                        *l += a * xi;
                    }
                }
            }
            assert_eq!(load.map(f64::to_bits), expected.map(f64::to_bits), "pattern {pattern}");
        }
    }
}

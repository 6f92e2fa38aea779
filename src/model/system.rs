//! The two beams and the contact bar as one model (paper Eqs. 2-4). Global DOFs: the arrestor's
//! first, then the bridge's. Outputs are linear functionals of the global displacement vector.

use std::sync::Arc;

use nalgebra::{DMatrix, DVector};

use super::assembly::Beam;
use super::mesh::{FarEnd, Mesh};
use super::scenario::{ImpactorKind, Scenario, SupportKind};
use super::section::{self, Segment};
use super::stations::{BeamStations, Stations};
use super::stress_recovery::StressRecovery;
use crate::error::Result;

/// Index of each probe (a linear functional of the displacements) in [`Model::probes`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Probe {
    /// Deflection of the arrestor's contact point y_k,l (node 8 in the paper: its free end; issue
    /// 45: the node at `lower.contact_position`), m.
    LowerTipDeflection = 0,
    /// Deflection of the bridge's contact node y_k,u (node 16), m.
    UpperContactDeflection = 1,
    /// Deflection of the bridge's free end, m.
    UpperTipDeflection = 2,
    /// y_k,u - y_k,l: the contact bar's shortening with sign (Eq. 6); negative means contact.
    Gap = 3,
    /// Internal bending moment at the clamp (node 1), N m, sagging positive.
    ClampMoment = 4,
    /// Internal shear force at the clamp, N.
    ClampShear = 5,
    /// Internal bending moment at the bridge's contact node (from the elements the scenario's
    /// `stress_recovery` names; the mean of the two adjacent ones by default), N m.
    UpperContactMoment = 6,
}

/// Number of probes.
pub const PROBES: usize = 7;

/// A support reaction as linear functionals over the global DOFs: the support's row of the
/// unconstrained equations of motion, R = k . delta + m . delta'' (+ damping) - load, the force
/// (or moment) the support exerts on the beam, up (counter-clockwise) positive.
#[derive(Clone, Debug)]
pub struct Reaction {
    /// Stiffness row K_s (the first element's, over the free DOFs), N/m.
    pub stiffness: DVector<f64>,
    /// Consistent mass row M_s, kg.
    pub mass: DVector<f64>,
    /// Consistent self-weight load on the support DOF, N (N m), up positive.
    pub load: f64,
}

/// The reactions of [`Model::reactions`], in order.
pub const REACTIONS: usize = 3;

/// The assembled two-beam model.
#[derive(Clone, Debug)]
pub struct Model {
    /// The validated scenario it was built from.
    pub scenario: Scenario,
    /// The arrestor (shared by the clones of a model: a cached model's runs, issue 43; no one
    /// changes an assembled beam).
    pub lower: Arc<Beam>,
    /// The bridge (shared likewise).
    pub upper: Arc<Beam>,
    /// Index of the bridge's contact node in `upper.mesh.nodes`.
    pub contact_node: usize,
    /// Index of the arrestor's contact node in `lower.mesh.nodes` (issue 45: its free end by
    /// default; `lower.contact_position` from its first support). [`Probe::LowerTipDeflection`]
    /// and the gap take its deflection.
    pub lower_contact_node: usize,
    /// Contact bar stiffness E A_c / l_c, N/m (Eq. 3).
    pub bar_stiffness: f64,
    /// Probe functionals as rows over the global DOFs, indexed by [`Probe`].
    pub probes: DMatrix<f64>,
    /// The bridge's section modulus at the contact node, m^3 (`upper.section_modulus` on a
    /// uniform bridge; at a section change the smaller side's).
    pub contact_section_modulus: f64,
    /// Where the stress envelope is taken along each beam (issue 30).
    pub stations: Stations,
}

impl Model {
    /// Validates the scenario and assembles both beams.
    pub fn new(scenario: &Scenario) -> Result<Model> {
        scenario.validate()?;
        for (name, count) in [
            ("lower.elements", scenario.lower.elements),
            ("upper.elements_to_contact", scenario.upper.elements_to_contact),
            ("upper.elements_beyond_contact", scenario.upper.elements_beyond_contact),
        ] {
            let none_beyond = name == "upper.elements_beyond_contact" && scenario.contact_at_free_end();
            if count == 0 && !none_beyond {
                return Err(crate::error::Error::invalid(
                    name,
                    "resolved before a model is assembled (crate::discretise::printed resolves \"auto\")",
                    "auto",
                ));
            }
        }
        let s = scenario;
        let lower_segments = s.lower_segments();
        let upper_segments = s.upper_segments();
        let breaks = |segments: &[Segment]| -> Vec<f64> { segments.iter().skip(1).map(|g| g.start).collect() };
        // Issue 45: the arrestor held by `lower.supports` at both ends, with a node where it is
        // struck (the free end by default: the paper's cantilever, bit for bit).
        let supports = s.lower.supports;
        let (lower_mesh, lower_contact) = Mesh::struck_beam(
            s.lower.length,
            s.lower.elements as usize,
            &breaks(&lower_segments),
            supports.first(),
            supports.far(),
            s.lower_contact_position(),
        );
        let lower = match s.lower.kind {
            SupportKind::Beam if s.lower.sections.is_empty() => Beam::assemble(
                lower_mesh,
                s.lower.elastic_modulus * s.lower.second_moment,
                s.lower.mass,
                s.lower.tip_mass,
                s.gravity,
            ),
            SupportKind::Beam => Beam::assemble_segments(lower_mesh, &lower_segments, s.lower.tip_mass, s.gravity),
            // A rigid point: no free DOF, no mass; every functional of it is empty.
            SupportKind::Rigid => Beam::assemble(Mesh::rigid(s.lower.length), 1.0, 0.0, 0.0, s.gravity),
        };
        let lower_contact = if s.lower.kind == SupportKind::Rigid { lower.mesh.nodes.len() - 1 } else { lower_contact };
        let (upper_mesh, inner) = Mesh::hinged_free_sections(
            s.upper.length,
            s.contact_position,
            s.upper.elements_to_contact as usize,
            s.upper.elements_beyond_contact as usize,
            &breaks(&upper_segments),
        );
        let mass = s.upper.kind == ImpactorKind::Mass;
        let (upper_mesh, inner) = if mass { (Mesh::mass(1.0), 1) } else { (upper_mesh, inner) };
        let upper = if mass {
            // A rigid body (issue 45): no stiffness, its mass lumped on its one DOF.
            Beam::assemble(upper_mesh, 0.0, 0.0, s.upper.mass, s.gravity)
        } else if s.upper.sections.is_empty() {
            Beam::assemble(upper_mesh, s.upper.elastic_modulus * s.upper.second_moment, s.upper.mass, 0.0, s.gravity)
        } else {
            Beam::assemble_segments(upper_mesh, &upper_segments, 0.0, s.gravity)
        };
        let (nl, nu) = (lower.dofs(), upper.dofs());
        let n = nl + nu;
        let mut probes = DMatrix::zeros(PROBES, n);
        let mut put = |probe: Probe, lower_part: Option<DVector<f64>>, upper_part: Option<DVector<f64>>| {
            if let Some(r) = lower_part {
                probes.view_mut((probe as usize, 0), (1, nl)).copy_from(&r.transpose());
            }
            if let Some(r) = upper_part {
                probes.view_mut((probe as usize, nl), (1, nu)).copy_from(&r.transpose());
            }
        };
        let lower_tip = lower_contact;
        let upper_tip = upper.mesh.nodes.len() - 1;
        put(Probe::LowerTipDeflection, Some(lower.deflection_functional(lower_tip)), None);
        put(Probe::UpperContactDeflection, None, Some(upper.deflection_functional(inner)));
        put(Probe::UpperTipDeflection, None, Some(upper.deflection_functional(upper_tip)));
        put(Probe::Gap, Some(-lower.deflection_functional(lower_tip)), Some(upper.deflection_functional(inner)));
        // A pinned first support (issue 45) has no moment: zero, as a free end's.
        let pinned_first = s.lower.supports.has_far_support() && !s.lower.supports.first_is_clamped();
        let clamp_moment = lower.start_moment_functional(0) * if pinned_first { 0.0 } else { 1.0 };
        put(Probe::ClampMoment, Some(clamp_moment), None);
        put(Probe::ClampShear, Some(lower.start_shear_functional(0)), None);
        let left = upper.end_moment_functional(inner - 1);
        // At the bridge's free end the moment is zero (the boundary condition M(l_u) = 0; the
        // element's end moment there is only its inertia's share, which vanishes with the mesh).
        let contact_moment = if inner == upper_tip {
            left * 0.0
        } else {
            let right = upper.start_moment_functional(inner);
            match s.stress_recovery {
                StressRecovery::Mean => (left + right) * 0.5,
                StressRecovery::Left => left,
                StressRecovery::Right => right,
            }
        };
        put(Probe::UpperContactMoment, None, Some(contact_moment));
        let contact_section_modulus = if s.upper.sections.is_empty() || mass {
            s.upper.section_modulus
        } else {
            section::bending_check_at(&upper_segments, s.contact_position).0
        };
        let stations = Stations {
            lower: if s.lower.kind == SupportKind::Rigid {
                BeamStations::default()
            } else {
                // A contact inside the beam is a point load: its shear jumps there.
                let inside = lower_contact + 1 < lower.mesh.nodes.len();
                let point_loads: Vec<usize> = if inside { vec![lower_contact] } else { Vec::new() };
                BeamStations::new(&lower, &lower_segments, &point_loads, None)
            },
            upper: if mass {
                BeamStations::default()
            } else {
                BeamStations::new(&upper, &upper_segments, &[inner], Some((inner, s.stress_recovery)))
            },
        };
        Ok(Model {
            stations,
            contact_section_modulus,
            scenario: scenario.clone(),
            bar_stiffness: contact_rate(s),
            contact_node: inner,
            lower_contact_node: lower_contact,
            lower: Arc::new(lower),
            upper: Arc::new(upper),
            probes,
        })
    }

    /// The support reactions: the clamp's vertical force and moment on the arrestor, and the
    /// hinge's vertical force on the bridge. The supports sit at node 0 of each beam, so only the
    /// first element contributes to their rows.
    pub fn reactions(&self) -> [Reaction; REACTIONS] {
        let g = self.scenario.gravity;
        // A pinned first support (issue 45) leaves the rotation free: no moment reaction.
        let pinned = self.lower.mesh.nodes.first().is_some_and(|n| n.theta.is_some());
        let lower = |row: usize| {
            if row == 1 && pinned {
                self.no_reaction()
            } else {
                Reaction {
                    stiffness: self
                        .stack(&self.lower.element_force_functional(0, row, 1.0), &DVector::zeros(self.upper.dofs())),
                    mass: self
                        .stack(&self.lower.element_inertia_functional(0, row), &DVector::zeros(self.upper.dofs())),
                    load: self.lower.element_gravity_load(0, row, g),
                }
            }
        };
        let upper = Reaction {
            stiffness: self.stack(&DVector::zeros(self.lower.dofs()), &self.upper.element_force_functional(0, 0, 1.0)),
            mass: self.stack(&DVector::zeros(self.lower.dofs()), &self.upper.element_inertia_functional(0, 0)),
            load: self.upper.element_gravity_load(0, 0, g),
        };
        [lower(0), lower(1), upper]
    }

    /// A reaction that is identically zero (a free DOF's).
    fn no_reaction(&self) -> Reaction {
        Reaction { stiffness: DVector::zeros(self.dofs()), mass: DVector::zeros(self.dofs()), load: 0.0 }
    }

    /// The arrestor's far support's reactions (issue 45): its vertical force and its moment
    /// (up and counter-clockwise positive, on the beam), as [`Self::reactions`] gives the first
    /// support's, from the last element's rows 2 and 3. Zero for a free far end (the paper's
    /// cantilever) and the moment for a pinned one.
    pub fn far_reactions(&self) -> [Reaction; 2] {
        let g = self.scenario.gravity;
        let mesh = &self.lower.mesh;
        let last = mesh.nodes.len() - 1;
        let held = |row: usize| match row {
            2 => mesh.far != FarEnd::Free,
            _ => mesh.far == FarEnd::Clamped,
        };
        let e = mesh.elements().saturating_sub(1);
        let reaction = |row: usize| {
            if !held(row) || last == 0 || self.lower.dofs() == 0 {
                return self.no_reaction();
            }
            Reaction {
                stiffness: self
                    .stack(&self.lower.element_force_functional(e, row, 1.0), &DVector::zeros(self.upper.dofs())),
                mass: self.stack(&self.lower.element_inertia_functional(e, row), &DVector::zeros(self.upper.dofs())),
                load: self.lower.element_gravity_load(e, row, g),
            }
        };
        [reaction(2), reaction(3)]
    }

    /// The supports' unit inertia loads x_j = -M r_j over the global DOFs, in the order of
    /// [`super::support_motion::SupportMotion::accelerations`]: hinge heave (the bridge
    /// translating), clamp heave (the arrestor translating), clamp rotation (the arrestor rotating
    /// about its clamp). In the moving-base form the supports' motion loads the beams with
    /// sum_j a_j x_j (issue 17); gravity is -g times the sum of the two translations' M r.
    pub fn support_loads(&self) -> [DVector<f64>; 3] {
        let zeros = |n: usize| DVector::<f64>::zeros(n);
        let (nl, nu) = (self.lower.dofs(), self.upper.dofs());
        [
            -self.stack(&zeros(nl), &self.upper.rigid_inertia(false)),
            -self.stack(&self.lower.rigid_inertia(false), &zeros(nu)),
            -self.stack(&self.lower.rigid_inertia(true), &zeros(nu)),
        ]
    }

    /// The supports' own inertia in each reaction of [`Self::reactions`] per unit acceleration of
    /// each support motion: reaction k gains `[k][j] * a_j` (the support row of M r_j).
    pub fn support_reaction_inertia(&self) -> [[f64; 3]; REACTIONS] {
        let lower = |row: usize| {
            [0.0, self.lower.support_rigid_inertia(row, false), self.lower.support_rigid_inertia(row, true)]
        };
        [lower(0), lower(1), [self.upper.support_rigid_inertia(0, false), 0.0, 0.0]]
    }

    /// Number of global DOFs.
    pub fn dofs(&self) -> usize {
        self.lower.dofs() + self.upper.dofs()
    }

    /// The contact vector b with y_k,u - y_k,l = b . delta; the bar adds k_c b b^T to K (Eq. 4).
    pub fn contact_vector(&self) -> DVector<f64> {
        self.probes.row(Probe::Gap as usize).transpose()
    }

    /// Block-diagonal global matrix of two per-beam matrices (Eq. 2).
    pub fn block_diagonal(&self, lower: &DMatrix<f64>, upper: &DMatrix<f64>) -> DMatrix<f64> {
        let (nl, n) = (self.lower.dofs(), self.dofs());
        let mut a = DMatrix::zeros(n, n);
        a.view_mut((0, 0), (nl, nl)).copy_from(lower);
        a.view_mut((nl, nl), (n - nl, n - nl)).copy_from(upper);
        a
    }

    /// Stacks per-beam vectors into a global one.
    pub fn stack(&self, lower: &DVector<f64>, upper: &DVector<f64>) -> DVector<f64> {
        let mut v = DVector::zeros(self.dofs());
        v.rows_mut(0, self.lower.dofs()).copy_from(lower);
        v.rows_mut(self.lower.dofs(), self.upper.dofs()).copy_from(upper);
        v
    }

    /// Global mass matrix.
    pub fn mass(&self) -> DMatrix<f64> {
        self.block_diagonal(&self.lower.mass, &self.upper.mass)
    }

    /// Global stiffness of the two beams without the bar (out of contact, Eq. 2).
    pub fn stiffness(&self) -> DMatrix<f64> {
        self.block_diagonal(&self.lower.stiffness, &self.upper.stiffness)
    }

    /// Global stiffness with the bar (in contact, Eq. 4).
    pub fn coupled_stiffness(&self) -> DMatrix<f64> {
        let b = self.contact_vector();
        self.stiffness() + &b * b.transpose() * self.bar_stiffness
    }

    /// Global gravity load vector, N.
    pub fn gravity_load(&self) -> DVector<f64> {
        self.stack(&self.lower.gravity_load, &self.upper.gravity_load)
    }

    /// Global load vector of unit vertical forces at the bridge's free end and the arrestor's end:
    /// F_ext = upper_tip * `.0` + lower_tip * `.1`. The arrestor's force (`lower.tip_force`) acts
    /// where its lumped mass sits: its free end, or on two supports its contact node (issue 45).
    pub fn tip_force_vectors(&self) -> (DVector<f64>, DVector<f64>) {
        let lower = self.lower.deflection_functional(self.lower.mesh.lumped);
        (
            self.probes.row(Probe::UpperTipDeflection as usize).transpose(),
            self.stack(&lower, &DVector::zeros(self.upper.dofs())),
        )
    }

    /// Every envelope station's functional as a row over the global DOFs, in the order of
    /// [`Stations::all`].
    pub fn station_rows(&self) -> DMatrix<f64> {
        let (nl, nu) = (self.lower.dofs(), self.upper.dofs());
        let mut rows = DMatrix::zeros(self.stations.len(), nl + nu);
        let lower = self.stations.lower.bending.iter().chain(&self.stations.lower.shear);
        let upper = self.stations.upper.bending.iter().chain(&self.stations.upper.shear);
        for (r, station) in lower.enumerate() {
            rows.view_mut((r, 0), (1, nl)).copy_from(&station.functional.transpose());
        }
        for (r, station) in upper.enumerate() {
            rows.view_mut((self.stations.lower.len() + r, nl), (1, nu)).copy_from(&station.functional.transpose());
        }
        rows
    }

    /// Positions of the bridge's nodes and of the arrestor's nodes, m, from each beam's support.
    pub fn node_positions(&self) -> (Vec<f64>, Vec<f64>) {
        (self.lower.mesh.nodes.iter().map(|n| n.x).collect(), self.upper.mesh.nodes.iter().map(|n| n.x).collect())
    }
}

/// The contact's rate in the coupled modes, N/m: the linear bar's k, or for a nonlinear law its
/// largest tangent stiffness when it stores four times the impact's energy, or twice the static
/// compression under the bridge's weight share (m_u g l_u / 2d), whichever is more: what the
/// automatic contact step and Table 2's coupled column use. The law itself is solved each step.
pub fn contact_rate(s: &Scenario) -> f64 {
    match s.contact_law() {
        None => s.contact_stiffness(),
        Some(law) => {
            let weight_share = if s.upper.kind == ImpactorKind::Mass {
                s.upper.mass * s.gravity
            } else {
                s.upper.mass * s.gravity * s.upper.length / (2.0 * s.contact_position)
            };
            let static_energy = law.energy(2.0 * libm::pow(weight_share / law.stiffness, 1.0 / law.exponent));
            law.tangent_stiffness((4.0 * s.impact_energy()).max(static_energy))
        }
    }
}

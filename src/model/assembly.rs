//! Global mass and stiffness matrices and gravity loads of one beam (paper Eqs. 1-2, 12-13).

use nalgebra::{DMatrix, DVector, RowVector4};

use super::beam::{self, Section};
use super::mesh::Mesh;
use super::section::Segment;

/// One assembled beam: mesh, section and its global matrices over the free DOFs.
#[derive(Clone, Debug)]
pub struct Beam {
    /// Nodes and DOF numbering.
    pub mesh: Mesh,
    /// Section and material of each element (one value repeated on a uniform beam).
    pub sections: Vec<Section>,
    /// Consistent mass matrix M, kg (kg m^2 on rotations), lumped tip mass included.
    pub mass: DMatrix<f64>,
    /// Stiffness matrix K, N/m.
    pub stiffness: DMatrix<f64>,
    /// Consistent nodal loads of the self-weight (Eqs. 12-13) and of a lumped tip mass, N (up positive).
    pub gravity_load: DVector<f64>,
    /// Total mass, kg (distributed plus lumped).
    pub total_mass: f64,
    /// The lumped mass at the free end, kg.
    pub tip_mass: f64,
}

impl Beam {
    /// Assembles a beam of `mass` kg spread uniformly over the mesh, with `tip_mass` kg lumped
    /// on the free end's deflection DOF, under gravity `gravity` m/s^2 (acting downward).
    pub fn assemble(mesh: Mesh, bending_stiffness: f64, mass: f64, tip_mass: f64, gravity: f64) -> Beam {
        let length = mesh.tip().x - mesh.nodes[0].x;
        let section = Section { bending_stiffness, mass_per_length: mass / length };
        let sections = vec![section; mesh.elements()];
        Self::assemble_sections(mesh, sections, mass, tip_mass, gravity)
    }

    /// Assembles a beam whose section changes along it (issue 30): each element takes the
    /// segment its midpoint lies in (the mesh has a node at every change, so each element lies
    /// in one segment).
    pub fn assemble_segments(mesh: Mesh, segments: &[Segment], tip_mass: f64, gravity: f64) -> Beam {
        let sections: Vec<Section> = (0..mesh.elements())
            .map(|e| {
                let middle = 0.5 * (mesh.nodes[e].x + mesh.nodes[e + 1].x);
                let s = segments.iter().find(|s| middle < s.end).unwrap_or(&segments[segments.len() - 1]);
                Section { bending_stiffness: s.bending_stiffness, mass_per_length: s.mass_per_length }
            })
            .collect();
        let mass = (0..mesh.elements()).map(|e| sections[e].mass_per_length * mesh.element_length(e)).sum();
        Self::assemble_sections(mesh, sections, mass, tip_mass, gravity)
    }

    fn assemble_sections(mesh: Mesh, sections: Vec<Section>, mass: f64, tip_mass: f64, gravity: f64) -> Beam {
        let n = mesh.dofs;
        let mut m = DMatrix::zeros(n, n);
        let mut k = DMatrix::zeros(n, n);
        let mut f = DVector::zeros(n);
        for (e, section) in sections.iter().enumerate() {
            let le = mesh.element_length(e);
            let ke = beam::stiffness(section, le);
            let me = beam::consistent_mass(section, le);
            let fe = beam::uniform_load(-section.mass_per_length * gravity, le);
            let dofs = mesh.element_dofs(e);
            for (a, da) in dofs.iter().enumerate() {
                let Some(i) = *da else { continue };
                f[i] += fe[a];
                for (b, db) in dofs.iter().enumerate() {
                    let Some(j) = *db else { continue };
                    m[(i, j)] += me[(a, b)];
                    k[(i, j)] += ke[(a, b)];
                }
            }
        }
        if let Some(tip) = mesh.lumped_node().w {
            m[(tip, tip)] += tip_mass;
            f[tip] -= tip_mass * gravity;
        }
        Beam { mesh, sections, mass: m, stiffness: k, gravity_load: f, total_mass: mass + tip_mass, tip_mass }
    }

    /// The section of element `e`.
    pub fn section(&self, e: usize) -> &Section {
        &self.sections[e]
    }

    /// M r over the free DOFs for a rigid motion r of the whole beam, support DOFs included
    /// (translation: w = 1, theta = 0; `rotation`: about the support at x = 0, w = x, theta = 1),
    /// lumped tip mass included: -(M r) a is the load of a support accelerating at a in the
    /// moving-base form (issue 17). For the translation it is -gravity_load / g.
    pub fn rigid_inertia(&self, rotation: bool) -> DVector<f64> {
        let mut f = DVector::zeros(self.dofs());
        for e in 0..self.mesh.elements() {
            let me = beam::consistent_mass(self.section(e), self.mesh.element_length(e));
            let r = self.rigid_field(e, rotation);
            for (a, d) in self.mesh.element_dofs(e).iter().enumerate() {
                if let Some(i) = *d {
                    f[i] += (0..4).map(|b| me[(a, b)] * r[b]).sum::<f64>();
                }
            }
        }
        if let Some(tip) = self.mesh.lumped_node().w {
            let r_tip = if rotation { self.mesh.lumped_node().x } else { 1.0 };
            f[tip] += self.tip_mass * r_tip;
        }
        f
    }

    /// The support DOF `row` (0: deflection, 1: rotation) of M r for the rigid motion of
    /// [`Self::rigid_inertia`]: the support's own inertia force per unit acceleration, which the
    /// support reaction carries (only the first element touches the support).
    pub fn support_rigid_inertia(&self, row: usize, rotation: bool) -> f64 {
        let me = beam::consistent_mass(self.section(0), self.mesh.element_length(0));
        let r = self.rigid_field(0, rotation);
        (0..4).map(|b| me[(row, b)] * r[b]).sum()
    }

    /// Element `e`'s end values (w1, theta1, w2, theta2) of the unit rigid motion.
    fn rigid_field(&self, e: usize, rotation: bool) -> [f64; 4] {
        let (x1, x2) = (self.mesh.nodes[e].x, self.mesh.nodes[e + 1].x);
        if rotation {
            [x1, 1.0, x2, 1.0]
        } else {
            [1.0, 0.0, 1.0, 0.0]
        }
    }

    /// Number of free DOFs.
    pub fn dofs(&self) -> usize {
        self.mesh.dofs
    }

    /// Unit functional picking the deflection of `node` (zero vector if the node is supported).
    pub fn deflection_functional(&self, node: usize) -> DVector<f64> {
        let mut r = DVector::zeros(self.dofs());
        if let Some(i) = self.mesh.nodes[node].w {
            r[i] = 1.0;
        }
        r
    }

    /// The linear functional `row . (k_e u_e)` of element `e` over the beam's DOFs: an element
    /// end force as a dot product with the global displacement vector.
    pub fn element_force_functional(&self, e: usize, row: usize, scale: f64) -> DVector<f64> {
        let ke = beam::stiffness(self.section(e), self.mesh.element_length(e));
        let kr: RowVector4<f64> = ke.row(row).into_owned();
        let mut r = DVector::zeros(self.dofs());
        for (a, d) in self.mesh.element_dofs(e).iter().enumerate() {
            if let Some(i) = *d {
                r[i] += scale * kr[a];
            }
        }
        r
    }

    /// The linear functional `row . (m_e a_e)` of element `e` over the beam's DOFs: the element's
    /// consistent inertia force on one of its end DOFs as a dot product with the accelerations.
    pub fn element_inertia_functional(&self, e: usize, row: usize) -> DVector<f64> {
        let me = beam::consistent_mass(self.section(e), self.mesh.element_length(e));
        let mut r = DVector::zeros(self.dofs());
        for (a, d) in self.mesh.element_dofs(e).iter().enumerate() {
            if let Some(i) = *d {
                r[i] += me[(row, a)];
            }
        }
        r
    }

    /// The consistent self-weight load of element `e` on its end DOF `row`, N (N m), up positive.
    pub fn element_gravity_load(&self, e: usize, row: usize, gravity: f64) -> f64 {
        beam::uniform_load(-self.section(e).mass_per_length * gravity, self.mesh.element_length(e))[row]
    }

    /// Internal bending moment (sagging positive) at the start of element `e`, as a functional: `-f[1]`.
    pub fn start_moment_functional(&self, e: usize) -> DVector<f64> {
        self.element_force_functional(e, 1, -1.0)
    }

    /// Internal bending moment (sagging positive) at the end of element `e`, as a functional: `f[3]`.
    pub fn end_moment_functional(&self, e: usize) -> DVector<f64> {
        self.element_force_functional(e, 3, 1.0)
    }

    /// Internal shear force (dM/dx) at the start of element `e`, as a functional: `f[0]`.
    pub fn start_shear_functional(&self, e: usize) -> DVector<f64> {
        self.element_force_functional(e, 0, 1.0)
    }

    /// Bending strain energy 1/2 u^T K u of a displacement vector, J (Eq. 36 for the Hermite field).
    pub fn strain_energy(&self, u: &DVector<f64>) -> f64 {
        0.5 * u.dot(&(&self.stiffness * u))
    }
}

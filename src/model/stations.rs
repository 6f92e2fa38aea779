//! Where the stress envelope is taken (issue 30): the stations along each beam at which the
//! bending and shear stresses are recovered every step, each a linear functional of the beam's
//! displacements (an element end force, Eq. 12's k_e u_e) divided by its section's modulus or
//! shear area, with that section's allowable.
//!
//! One bending station per node: the mean of the two adjacent elements' end moments (the
//! moment is continuous where no couple acts; each cubic element carries its own linear moment),
//! the bridge's contact node by the scenario's `stress_recovery` (the paper's sigma_b), the
//! arrestor's clamp by its first element (the paper's sigma_a). One shear station per node as
//! well, the mean of the two sides' shears, but both sides where a point load makes the shear
//! jump (the contact node, the arrestor's tip mass) and the clamp by its first element (tau_a).
//! Where the section changes, each side is its own station with its own section (two at one x).

use nalgebra::DVector;

use super::assembly::Beam;
use super::mesh::FarEnd;
use super::section::Segment;
use super::stress_recovery::StressRecovery;

/// Which stress a station gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stress {
    /// Bending, M / W.
    Bending,
    /// Shear, Q / A_s.
    Shear,
}

/// One station: a stress at a node as a functional of the beam's displacements.
#[derive(Clone, Debug)]
pub struct Station {
    /// Position along the beam, m from its support.
    pub x: f64,
    /// The node it sits at.
    pub node: usize,
    /// The internal force (N m or N) as a functional over the beam's free DOFs.
    pub functional: DVector<f64>,
    /// The section modulus (m^3) or shear area (m^2) the force is divided by.
    pub divisor: f64,
    /// The allowable stress there, Pa (0: none given).
    pub allowable: f64,
}

/// The stations of one beam, bending and shear.
#[derive(Clone, Debug, Default)]
pub struct BeamStations {
    /// Bending stress stations, from the support to the free end.
    pub bending: Vec<Station>,
    /// Shear stress stations (none for a beam without a shear area).
    pub shear: Vec<Station>,
}

impl BeamStations {
    /// The stations of `beam` with its `segments` (the sections, in the mesh's order), its
    /// point-load nodes `point_loads` and the node whose moment the paper reads by the
    /// `recovery` rule (`contact`, the bridge's contact node), if any. The first node's values
    /// are the first element's (the arrestor's clamp: the paper's sigma_a and tau_a).
    pub fn new(
        beam: &Beam,
        segments: &[Segment],
        point_loads: &[usize],
        contact: Option<(usize, StressRecovery)>,
    ) -> BeamStations {
        let mesh = &beam.mesh;
        let elements = mesh.elements();
        if elements == 0 || mesh.dofs == 0 {
            return BeamStations::default();
        }
        let segment_of = |e: usize| {
            let middle = 0.5 * (mesh.nodes[e].x + mesh.nodes[e + 1].x);
            segments.iter().find(|s| middle < s.end).unwrap_or(&segments[segments.len() - 1])
        };
        let with_shear = segments.iter().all(|s| s.shear_area > 0.0);
        let two_supports = mesh.far != FarEnd::Free;
        let mut stations = BeamStations::default();
        for node in 0..=elements {
            let x = mesh.nodes[node].x;
            // The elements on each side: (element, its start (true) or end).
            let left = (node > 0).then(|| node - 1);
            let right = (node < elements).then_some(node);
            let (sl, sr) = (left.map(segment_of), right.map(segment_of));
            let change = matches!((sl, sr), (Some(a), Some(b)) if a != b);
            let moment_left = left.map(|e| beam.end_moment_functional(e));
            let moment_right = right.map(|e| beam.start_moment_functional(e));
            let shear_left = left.map(|e| beam.element_force_functional(e, 2, -1.0));
            let shear_right = right.map(|e| beam.start_shear_functional(e));
            let station = |functional: DVector<f64>, segment: &Segment, stress: Stress| Station {
                x,
                node,
                functional,
                divisor: match stress {
                    Stress::Bending => segment.section_modulus,
                    Stress::Shear => segment.shear_area,
                },
                allowable: match stress {
                    Stress::Bending => segment.allowable_bending_stress,
                    Stress::Shear => segment.allowable_shear_stress,
                },
            };
            // Bending.
            match (moment_left, moment_right) {
                (Some(l), Some(r)) if change => {
                    stations.bending.push(station(l, sl.unwrap(), Stress::Bending));
                    stations.bending.push(station(r, sr.unwrap(), Stress::Bending));
                }
                (Some(l), Some(r)) => {
                    let rule = contact.filter(|(c, _)| *c == node).map_or(StressRecovery::Mean, |(_, r)| r);
                    let m = match rule {
                        StressRecovery::Mean => (l + r) * 0.5,
                        StressRecovery::Left => l,
                        StressRecovery::Right => r,
                    };
                    stations.bending.push(station(m, sl.unwrap(), Stress::Bending));
                }
                // A pin of a beam on two supports (issue 45): its moment vanishes as a free end's.
                (None, Some(r)) if two_supports && mesh.nodes[node].theta.is_some() => {
                    stations.bending.push(station(r * 0.0, sr.unwrap(), Stress::Bending))
                }
                (None, Some(r)) => stations.bending.push(station(r, sr.unwrap(), Stress::Bending)),
                // A clamped far end (issue 45) carries its moment: the last element's.
                (Some(l), None) if mesh.far == FarEnd::Clamped => {
                    stations.bending.push(station(l, sl.unwrap(), Stress::Bending))
                }
                // The free end: its moment vanishes (M(l) = 0; the element's end moment there is
                // only its inertia's share), as the paper's contact probe takes it at a free end;
                // so does a pinned far end's.
                (Some(l), None) => stations.bending.push(station(l * 0.0, sl.unwrap(), Stress::Bending)),
                (None, None) => {}
            }
            if !with_shear {
                continue;
            }
            let jump = point_loads.contains(&node) || change;
            match (shear_left, shear_right) {
                (Some(l), Some(r)) if jump => {
                    stations.shear.push(station(l, sl.unwrap(), Stress::Shear));
                    stations.shear.push(station(r, sr.unwrap(), Stress::Shear));
                }
                (Some(l), Some(r)) => stations.shear.push(station((l + r) * 0.5, sl.unwrap(), Stress::Shear)),
                (None, Some(r)) => stations.shear.push(station(r, sr.unwrap(), Stress::Shear)),
                (Some(l), None) => stations.shear.push(station(l, sl.unwrap(), Stress::Shear)),
                (None, None) => {}
            }
        }
        stations
    }

    /// Number of stations, bending and shear.
    pub fn len(&self) -> usize {
        self.bending.len() + self.shear.len()
    }

    /// True without stations (a rigid support).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The stations of both beams.
#[derive(Clone, Debug, Default)]
pub struct Stations {
    /// The arrestor's.
    pub lower: BeamStations,
    /// The bridge's.
    pub upper: BeamStations,
}

impl Stations {
    /// Every station in the order lower bending, lower shear, upper bending, upper shear.
    pub fn all(&self) -> impl Iterator<Item = &Station> {
        self.lower.bending.iter().chain(&self.lower.shear).chain(&self.upper.bending).chain(&self.upper.shear)
    }

    /// Number of stations.
    pub fn len(&self) -> usize {
        self.lower.len() + self.upper.len()
    }

    /// True without any.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

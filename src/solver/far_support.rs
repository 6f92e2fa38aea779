//! The struck beam's far support's reactions during a run (issue 45): on a beam on two supports
//! the force (and on a clamped far end the moment) the far support exerts on the beam, each the
//! support's row of the unconstrained equations of motion as [`crate::model::Model::far_reactions`]
//! states it, R = k . delta + c . delta' + m . delta'' - load, evaluated in the stepper's
//! coordinates: the modal ones (with the discarded modes' static response of a truncated basis,
//! through its physical DOF rows) or the dense oracle's physical ones.

use nalgebra::DVector;

use super::modal::ModalSystem;
use super::static_correction::LOADS;
use crate::model::{Model, Reaction};

/// The far support's two reactions (force N, moment N m) as rows over the run's coordinates.
#[derive(Clone, Debug)]
pub struct FarSupport {
    /// Phi^T k_s of each reaction over the modal coordinates.
    displacement: [DVector<f64>; 2],
    /// The damping row (as the first support's: M_s Phi (c o q') plus Rayleigh's beta K_s v).
    velocity: [DVector<f64>; 2],
    /// Phi^T m_s.
    acceleration: [DVector<f64>; 2],
    /// k_s^T R x_a over the static correction's loads (zero for a full basis).
    correction: [[f64; LOADS]; 2],
    /// The reactions over the physical DOFs (the dense oracle's coordinates).
    physical: [Reaction; 2],
}

impl FarSupport {
    /// The far support's rows for `model` stepped in `modal`'s basis; `None` for a beam whose far
    /// end is free (the paper's cantilever: its reactions are 0).
    pub fn new(model: &Model, modal: &ModalSystem) -> Option<FarSupport> {
        if !model.scenario.lower.supports.has_far_support() || model.lower.dofs() == 0 {
            return None;
        }
        let physical = model.far_reactions();
        let shapes = modal.shapes();
        let beta = model.scenario.rayleigh_beta;
        let row = |r: &Reaction| {
            let displacement = shapes.transpose() * &r.stiffness;
            let acceleration = shapes.transpose() * &r.mass;
            let velocity = DVector::from_fn(acceleration.len(), |i, _| {
                acceleration[i] * (modal.damping[i] - beta * modal.omega2[i]) + beta * displacement[i]
            });
            (displacement, velocity, acceleration)
        };
        let [(d0, v0, a0), (d1, v1, a1)] = [row(&physical[0]), row(&physical[1])];
        let correction = std::array::from_fn(|k| {
            let mut c = [0.0; LOADS];
            for (r, dof) in modal.correction.dofs.iter().enumerate() {
                let weight = physical[k].stiffness.get(r).copied().unwrap_or(0.0);
                if weight != 0.0 {
                    for a in 0..LOADS {
                        c[a] += weight * dof[a];
                    }
                }
            }
            c
        });
        Some(FarSupport { displacement: [d0, d1], velocity: [v0, v1], acceleration: [a0, a1], correction, physical })
    }

    /// The reactions (force N, moment N m; up and counter-clockwise positive) of a state in the
    /// stepper's coordinates: modal ones (`modal`, with a truncated basis's correction `loads`),
    /// or physical.
    pub fn evaluate(&self, modal: bool, q: &[f64], v: &[f64], a: &[f64], loads: Option<&[f64; LOADS]>) -> [f64; 2] {
        let dot = |row: &DVector<f64>, x: &[f64]| row.iter().zip(x).map(|(r, x)| r * x).sum::<f64>();
        std::array::from_fn(|k| {
            if modal {
                let mut sum = dot(&self.displacement[k], q) + dot(&self.velocity[k], v) + dot(&self.acceleration[k], a);
                if let Some(loads) = loads {
                    sum += self.correction[k].iter().zip(loads).map(|(c, l)| c * l).sum::<f64>();
                }
                sum - self.physical[k].load
            } else {
                let r = &self.physical[k];
                dot(&r.stiffness, q) + dot(&r.mass, a) - r.load
            }
        })
    }
}

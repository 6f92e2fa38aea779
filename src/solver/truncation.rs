//! A truncated modal basis with a static (mode-acceleration) correction.
//!
//! A fine mesh resolves the stresses near the contact point and the clamp, but its highest modes
//! (omega_max grows with the square of the element count) set the energy-safe time step, so the
//! cost of a run grows like n^3. The modes above a cut-off frequency omega_c barely move
//! dynamically during an impact whose contact lasts tens of milliseconds: they follow their loads
//! quasi-statically. Keeping the modes up to omega_c and adding the discarded modes' static
//! response to the loads (the mode-acceleration method) gives the fine mesh's stresses at the
//! coarse mesh's time step.
//!
//! With Phi_k the kept modes and R = sum over the discarded (elastic) modes of
//! phi_i phi_i^T / omega_i^2 (the residual flexibility), the displacement is
//! u = Phi_k q + R f, f = F_g + F_upper e_upper + F_lower e_lower - F_c b. The contact force
//! F_c = k_c b^T u is then rank-one in q: with f_r = b^T R b and s = b^T R (F_g + F_t),
//! F_c = k_eff (b^T Phi_k q + s), k_eff = k_c / (1 + k_c f_r), so the production stepper keeps its
//! O(n) Sherman-Morrison form with k_eff and a constant load shift. Every output is a linear
//! functional of u, so it takes R f through precomputed rows over the four load vectors. The
//! energy account stays exact: the residual strain energy 1/2 f^T R f, the bar's 1/2 k_c gap^2 and
//! gravity's -F_g^T R f add up to 1/2 k_eff (b^T Phi_k q + s)^2 up to a constant, the potential of
//! the truncated equations of motion. Statics are exact whatever the cut (a test checks the
//! cantilever's P L^3 / 3 E I with two modes kept).
//!
//! A nonlinear contact law (a power law, Hunt-Crossley damping; issue 40) takes the same basis:
//! the discarded modes' static response to the contact force P is the residual spring f_r in
//! series with the law, so the contact's own compression is delta = -(b^T Phi_k q + s + d) - f_r P,
//! still one monotone scalar equation per step ([`crate::model::contact_law::ContactLaw::solve_in_series`]),
//! and out of contact the law plays no part: the same basis, correction and steps as the bar's.

use nalgebra::{DMatrix, DVector};

use super::eigen::Modes;
use super::graded;
use super::modal::{block_columns, ModalReaction, ModalSystem};
use super::secular::coupled_modes;
pub use super::static_correction::{
    Correction, StaticCorrection, CLAMP_HEAVE, CLAMP_ROTATION, CONTACT, GRAVITY, HINGE_HEAVE, LOADS, LOWER_TIP,
    UPPER_TIP,
};
use crate::error::Result;
use crate::model::system::PROBES;
use crate::model::{Method, Model, REACTIONS};

impl ModalSystem {
    /// The system with each beam's modes above `cutoff` (rad/s) discarded and their static
    /// response kept as a [`StaticCorrection`]; rigid-body modes are always kept. A cut-off at or
    /// above every frequency returns the full system unchanged.
    pub fn truncated(&self, cutoff: f64) -> Result<ModalSystem> {
        self.truncated_where(cutoff, |_, omega| omega <= cutoff)
    }

    /// The basis a run steps in ([`crate::Simulation::new`]): the modes of a graded beam above its
    /// [`graded::spurious_limit`] (its short elements' own) replaced by their static response in
    /// every method, and for the converged method with a cut-off every mode above it too. A model
    /// with no graded beam gets exactly what it always did: the converged method's truncation at
    /// its cut-off, or the full basis.
    pub fn for_run(self, model: &Model) -> Result<ModalSystem> {
        let s = &model.scenario;
        let cutoff = (s.method == Method::Converged && s.modal_cutoff > 0.0).then_some(s.modal_cutoff);
        let limits = [graded::spurious_limit(&model.lower), graded::spurious_limit(&model.upper)];
        if limits == [None, None] {
            return match cutoff {
                Some(c) => self.truncated(c),
                None => Ok(self),
            };
        }
        let reported = cutoff.or(limits.iter().flatten().copied().reduce(f64::min)).unwrap_or(f64::INFINITY);
        let lower_dofs = self.lower_dofs;
        self.truncated_where(reported, |i, omega| {
            let limit = if i < lower_dofs { limits[0] } else { limits[1] };
            omega <= cutoff.unwrap_or(f64::INFINITY) && omega <= limit.unwrap_or(f64::INFINITY)
        })
    }

    /// The highest natural frequency a run out of contact follows, rad/s: [`Self::omega_max`]
    /// without the short elements' own modes of a graded beam (see [`Self::for_run`]).
    pub fn resolved_omega_max(&self, model: &Model) -> f64 {
        let limits = [graded::spurious_limit(&model.lower), graded::spurious_limit(&model.upper)];
        let lower = self.lower.omega.iter().copied().filter(|w| limits[0].is_none_or(|l| *w <= l));
        let upper = self.upper.omega.iter().copied().filter(|w| limits[1].is_none_or(|l| *w <= l));
        lower.chain(upper).fold(0.0, f64::max)
    }

    /// The system with the modal coordinates `keep(i, omega_i)` rejects discarded and their
    /// static response kept; `cutoff` is the cut-off reported.
    fn truncated_where(&self, cutoff: f64, keep: impl Fn(usize, f64) -> bool) -> Result<ModalSystem> {
        let n = self.dofs();
        let (keep, discarded): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| keep(i, self.omega2[i].sqrt()));
        if keep.len() == n {
            return Ok(self.clone());
        }
        let loads = [
            &self.gravity,
            &self.upper_tip,
            &self.lower_tip,
            &self.contact,
            &self.support_loads[0],
            &self.support_loads[1],
            &self.support_loads[2],
        ];
        let mut correction = StaticCorrection {
            bar_stiffness: self.bar_stiffness,
            stations: vec![[0.0; LOADS]; self.stations.nrows()],
            dofs: vec![[0.0; LOADS]; self.full_dofs],
            law: self.law,
            ..StaticCorrection::default()
        };
        // Each physical DOF's row of the discarded modes' shapes (the block-diagonal basis: a
        // mode moves its own beam's DOFs only).
        let (lower_rows, lower_modes) = self.lower.shapes.shape();
        for &i in &discarded {
            let w = 1.0 / self.omega2[i];
            let x: [f64; LOADS] = std::array::from_fn(|a| loads[a][i]);
            for a in 0..LOADS {
                for b in 0..LOADS {
                    correction.gram[a][b] += w * x[a] * x[b];
                    if i >= self.lower_dofs {
                        correction.gram_upper[a][b] += w * x[a] * x[b];
                    }
                }
                for k in 0..PROBES {
                    correction.probes[k][a] += w * self.probes[(k, i)] * x[a];
                }
                for (k, row) in correction.stations.iter_mut().enumerate() {
                    row[a] += w * self.stations[(k, i)] * x[a];
                }
                for (s, reaction) in self.reactions.iter().enumerate() {
                    correction.reactions[s][a] += w * reaction.displacement[i] * x[a];
                }
            }
            let (shapes, column, offset) = if i < lower_modes {
                (&self.lower.shapes, i, 0)
            } else {
                (&self.upper.shapes, i - lower_modes, lower_rows)
            };
            for (r, value) in shapes.column(column).iter().enumerate() {
                if *value != 0.0 {
                    let row = &mut correction.dofs[offset + r];
                    for a in 0..LOADS {
                        row[a] += w * value * x[a];
                    }
                }
            }
        }
        // The discarded modes already carried by this system (a truncation of a truncation).
        add_into(&mut correction, &self.correction);
        let k_c = correction.bar_stiffness;
        let bar_stiffness = k_c / (1.0 + k_c * correction.gram[CONTACT][CONTACT]);
        let pick = |v: &DVector<f64>| DVector::from_iterator(keep.len(), keep.iter().map(|&i| v[i]));
        let omega2 = pick(&self.omega2);
        let contact = pick(&self.contact);
        let lower_keep: Vec<usize> = keep.iter().copied().filter(|&i| i < self.lower_dofs).collect();
        let upper_keep: Vec<usize> =
            keep.iter().copied().filter(|&i| i >= self.lower_dofs).map(|i| i - self.lower_dofs).collect();
        let coupled_rigid = self.coupled.omega.iter().filter(|w| **w == 0.0).count();
        let coupled_modal = coupled_modes(&omega2, &contact, bar_stiffness, coupled_rigid)?;
        let lower = columns(&self.lower, &lower_keep);
        let upper = columns(&self.upper, &upper_keep);
        let physical = block_columns(&lower.shapes, &upper.shapes);
        Ok(ModalSystem {
            coupled: Modes { shapes: &physical * &coupled_modal.shapes, omega: coupled_modal.omega },
            lower_dofs: lower_keep.len(),
            lower,
            upper,
            damping: pick(&self.damping),
            gravity: pick(&self.gravity),
            upper_tip: pick(&self.upper_tip),
            lower_tip: pick(&self.lower_tip),
            support_loads: std::array::from_fn(|j| pick(&self.support_loads[j])),
            support_reactions: self.support_reactions,
            probes: DMatrix::from_fn(PROBES, keep.len(), |k, j| self.probes[(k, keep[j])]),
            stations: DMatrix::from_fn(self.stations.nrows(), keep.len(), |k, j| self.stations[(k, keep[j])]),
            reactions: std::array::from_fn(|s| {
                let r = &self.reactions[s];
                ModalReaction {
                    displacement: pick(&r.displacement),
                    velocity: pick(&r.velocity),
                    acceleration: pick(&r.acceleration),
                    load: r.load,
                }
            }),
            omega2,
            contact,
            bar_stiffness,
            correction,
            cutoff: Some(cutoff),
            full_dofs: self.full_dofs,
            law: self.law,
        })
    }
}

fn add_into(into: &mut StaticCorrection, from: &StaticCorrection) {
    for a in 0..LOADS {
        for b in 0..LOADS {
            into.gram[a][b] += from.gram[a][b];
            into.gram_upper[a][b] += from.gram_upper[a][b];
        }
        for k in 0..PROBES {
            into.probes[k][a] += from.probes[k][a];
        }
        for s in 0..REACTIONS {
            into.reactions[s][a] += from.reactions[s][a];
        }
        for (row, from_row) in into.stations.iter_mut().zip(&from.stations) {
            row[a] += from_row[a];
        }
        for (row, from_row) in into.dofs.iter_mut().zip(&from.dofs) {
            row[a] += from_row[a];
        }
    }
    if from.bar_stiffness > 0.0 {
        into.bar_stiffness = from.bar_stiffness;
    }
}

/// The modes `keep` of `modes`.
fn columns(modes: &Modes, keep: &[usize]) -> Modes {
    let rows = modes.shapes.nrows();
    Modes {
        omega: DVector::from_iterator(keep.len(), keep.iter().map(|&i| modes.omega[i])),
        shapes: DMatrix::from_fn(rows, keep.len(), |r, c| modes.shapes[(r, keep[c])]),
    }
}

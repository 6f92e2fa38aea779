//! The discarded modes' static response R f of a truncated basis (see [`super::truncation`] for
//! the method): its bilinear forms over the four load vectors and what a state's measurements
//! add from them. Its own file because [`super::modal::ModalSystem`] holds one and
//! [`super::truncation`] builds it from a `ModalSystem`.

use crate::model::system::PROBES;
use crate::model::REACTIONS;

/// Index of the gravity load in the correction's load vectors.
pub const GRAVITY: usize = 0;
/// Index of the unit upper tip force.
pub const UPPER_TIP: usize = 1;
/// Index of the unit lower tip force.
pub const LOWER_TIP: usize = 2;
/// Index of the contact vector b (gap = b^T u).
pub const CONTACT: usize = 3;
/// Number of load vectors.
pub const LOADS: usize = 4;

/// The discarded modes' static response, as bilinear forms over the four load vectors
/// (gravity, unit upper tip force, unit lower tip force, contact vector). All zero for a full basis.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StaticCorrection {
    /// x_a^T R x_b over both beams.
    pub gram: [[f64; LOADS]; LOADS],
    /// x_a^T R_u x_b over the bridge's discarded modes (its strain energy, Eq. 36).
    pub gram_upper: [[f64; LOADS]; LOADS],
    /// p_k^T R x_a for each probe functional p_k.
    pub probes: [[f64; LOADS]; PROBES],
    /// k_s^T R x_a for each support reaction's stiffness row k_s.
    pub reactions: [[f64; LOADS]; REACTIONS],
    /// The physical contact bar's stiffness k_c, N/m (the stepper's is k_eff).
    pub bar_stiffness: f64,
}

/// The static correction's part of a state's measurements.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Correction {
    /// The load coefficients c of f = sum c_a x_a: (1, F_upper, F_lower, -F_c).
    pub loads: [f64; LOADS],
    /// 1/2 c^T R c, J.
    pub strain: f64,
    /// The bridge's part of it, J.
    pub upper_strain: f64,
    /// -F_g^T R f, J.
    pub gravity_potential: f64,
}

impl StaticCorrection {
    /// b^T R (F_g + F_t): the discarded modes' static part of the gap under the external loads, m.
    pub fn gap_shift(&self, upper: f64, lower: f64) -> f64 {
        let g = &self.gram[CONTACT];
        g[GRAVITY] + upper * g[UPPER_TIP] + lower * g[LOWER_TIP]
    }

    /// The correction for a state whose kept modes give the gap `modal_gap` = b^T Phi_k q, in the
    /// given stage, under the given tip forces.
    pub fn evaluate(&self, modal_gap: f64, contact: bool, upper: f64, lower: f64) -> Correction {
        let gram = &self.gram;
        let shifted = modal_gap + self.gap_shift(upper, lower);
        // In contact F_c = k_c gap with gap = shifted - F_c f_r: F_c = k_c shifted / (1 + k_c f_r).
        let force = if contact {
            self.bar_stiffness * shifted / (1.0 + self.bar_stiffness * gram[CONTACT][CONTACT])
        } else {
            0.0
        };
        let loads = [1.0, upper, lower, -force];
        let quadratic = |g: &[[f64; LOADS]; LOADS]| {
            let mut sum = 0.0;
            for a in 0..LOADS {
                for b in 0..LOADS {
                    sum += loads[a] * g[a][b] * loads[b];
                }
            }
            0.5 * sum
        };
        Correction {
            loads,
            strain: quadratic(gram),
            upper_strain: quadratic(&self.gram_upper),
            gravity_potential: -row_dot(&gram[GRAVITY], &loads),
        }
    }

    /// Adds the static part R f to probe values computed from the kept modes.
    pub fn correct_probes(&self, probes: &mut [f64; PROBES], correction: &Correction) {
        for (value, row) in probes.iter_mut().zip(&self.probes) {
            *value += row_dot(row, &correction.loads);
        }
    }

    /// The static part of each support reaction, k_s^T R f.
    pub fn reaction(&self, index: usize, correction: &Correction) -> f64 {
        row_dot(&self.reactions[index], &correction.loads)
    }
}

fn row_dot(row: &[f64; LOADS], loads: &[f64; LOADS]) -> f64 {
    row.iter().zip(loads).map(|(r, c)| r * c).sum()
}

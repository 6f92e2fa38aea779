//! The discarded modes' static response R f of a truncated basis (see [`super::truncation`] for
//! the method): its bilinear forms over the four load vectors and what a state's measurements
//! add from them. Its own file because [`super::modal::ModalSystem`] holds one and
//! [`super::truncation`] builds it from a `ModalSystem`.

use super::kinematics::Excitation;
use crate::model::contact_law::ContactLaw;
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
/// Index of the hinge heave's unit inertia load (-M r of the bridge translating).
pub const HINGE_HEAVE: usize = 4;
/// Index of the clamp heave's unit inertia load.
pub const CLAMP_HEAVE: usize = 5;
/// Index of the clamp rotation's unit inertia load.
pub const CLAMP_ROTATION: usize = 6;
/// Number of load vectors.
pub const LOADS: usize = 7;

/// The discarded modes' static response, as bilinear forms over the seven load vectors
/// (gravity, unit upper tip force, unit lower tip force, contact vector, the three supports'
/// unit inertia loads). All zero for a full basis.
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
    /// s_k^T R x_a for each stress envelope station s_k (issue 30).
    pub stations: Vec<[f64; LOADS]>,
    /// e_d^T R x_a for each physical DOF d of both beams (the arrestor's, then the bridge's): the
    /// discarded modes' static deflections and rotations, which the model's range check reads
    /// ([`super::model_range`]; issue 40).
    pub dofs: Vec<[f64; LOADS]>,
    /// The physical contact bar's stiffness k_c, N/m (the stepper's is k_eff).
    pub bar_stiffness: f64,
    /// A nonlinear contact law (issue 28), in series with the residual flexibility
    /// f_r = b^T R b at the contact: its force follows [`ContactLaw::in_series`] instead of the
    /// bar's k_eff.
    pub law: Option<ContactLaw>,
}

/// The static correction's part of a state's measurements.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Correction {
    /// The load coefficients c of f = sum c_a x_a: (1, F_upper, F_lower, -F_c, a_hinge,
    /// a_clamp, alpha_clamp).
    pub loads: [f64; LOADS],
    /// 1/2 c^T R c, J.
    pub strain: f64,
    /// The bridge's part of it, J.
    pub upper_strain: f64,
    /// -F_g^T R f, J.
    pub gravity_potential: f64,
    /// -(sum_j a_j x_j)^T R f, J.
    pub inertial_potential: f64,
}

impl StaticCorrection {
    /// b^T R f_ext: the discarded modes' static part of the gap under the external loads
    /// (gravity, tip forces, the supports' inertia), m.
    pub fn gap_shift(&self, excitation: &Excitation) -> f64 {
        row_dot(&self.gram[CONTACT], &external_loads(excitation))
    }

    /// The correction for a state whose kept modes give the gap `modal_gap` = b^T Phi_k q (with the
    /// supports' offset) closing at `modal_rate` = b^T Phi_k q' + d' (read by a damped law only),
    /// in the given stage, under `excitation`.
    pub fn evaluate(&self, modal_gap: f64, modal_rate: f64, contact: bool, excitation: &Excitation) -> Correction {
        let gram = &self.gram;
        let loads = self.loads(modal_gap, modal_rate, contact, excitation);
        Correction {
            loads,
            strain: quadratic(gram, &loads),
            upper_strain: quadratic(&self.gram_upper, &loads),
            gravity_potential: -row_dot(&gram[GRAVITY], &loads),
            inertial_potential: -[HINGE_HEAVE, CLAMP_HEAVE, CLAMP_ROTATION]
                .iter()
                .map(|&j| loads[j] * row_dot(&gram[j], &loads))
                .sum::<f64>(),
        }
    }

    /// [`Self::evaluate`]'s load coefficients alone (the probes' and stresses' correction, without
    /// the energies' quadratic forms).
    pub fn loads(&self, modal_gap: f64, modal_rate: f64, contact: bool, excitation: &Excitation) -> [f64; LOADS] {
        let gram = &self.gram;
        let mut loads = external_loads(excitation);
        let shifted = modal_gap + row_dot(&gram[CONTACT], &loads);
        // In contact F_c = k_c gap with gap = shifted - F_c f_r: F_c = k_c shifted / (1 + k_c f_r).
        let force = match (contact, self.law) {
            (false, _) => 0.0,
            (true, None) => self.bar_stiffness * shifted / (1.0 + self.bar_stiffness * gram[CONTACT][CONTACT]),
            (true, Some(law)) => -law.in_series(-shifted, -modal_rate, gram[CONTACT][CONTACT]).force,
        };
        loads[CONTACT] = -force;
        loads
    }

    /// The rate of a nonlinear law's contact load P = G(D, V) (N/s; `None` for the linear bar) at
    /// the kept modes' gap `modal_gap` (with the supports' offset), its rate `modal_rate` and
    /// acceleration `modal_acceleration` (without the supports' offset's: the supports' jerk is
    /// not modelled): G_D D' + G_V V' with D = -gap, V = -rate.
    pub fn law_load_rate(
        &self,
        modal_gap: f64,
        (modal_rate, modal_acceleration): (f64, f64),
        excitation: &Excitation,
    ) -> Option<f64> {
        let law = self.law?;
        let shifted = modal_gap + self.gap_shift(excitation);
        let force = law.in_series(-shifted, -modal_rate, self.gram[CONTACT][CONTACT]);
        Some(force.rate(-modal_rate, -modal_acceleration))
    }

    /// Adds the static part R f to probe values computed from the kept modes.
    pub fn correct_probes(&self, probes: &mut [f64; PROBES], correction: &Correction) {
        self.correct_probes_by(probes, &correction.loads);
    }

    /// [`Self::correct_probes`] from the load coefficients alone ([`Self::loads`]).
    pub fn correct_probes_by(&self, probes: &mut [f64; PROBES], loads: &[f64; LOADS]) {
        for (value, row) in probes.iter_mut().zip(&self.probes) {
            *value += row_dot(row, loads);
        }
    }

    /// The static part of each support reaction, k_s^T R f.
    pub fn reaction(&self, index: usize, correction: &Correction) -> f64 {
        row_dot(&self.reactions[index], &correction.loads)
    }
}

/// The load coefficients of the external loads (the contact's left at 0).
fn external_loads(excitation: &Excitation) -> [f64; LOADS] {
    let (f, a) = (excitation.forces, excitation.support_acceleration);
    [1.0, f.upper, f.lower, 0.0, a[0], a[1], a[2]]
}

/// 1/2 c^T G c over the load coefficients `loads`: the terms c_a G_ab c_b in the order a, then b,
/// less the rows of a zero coefficient (a free flight's contact load, a fixed tip's force). Their
/// terms are each +-0 (finite G and c), which leave the sum as it is (it starts at +0 and a sum
/// of terms never turns -0): the full double sum to the bit.
fn quadratic(g: &[[f64; LOADS]; LOADS], loads: &[f64; LOADS]) -> f64 {
    let mut sum = 0.0;
    for a in 0..LOADS {
        if loads[a] == 0.0 {
            continue;
        }
        for b in 0..LOADS {
            sum += loads[a] * g[a][b] * loads[b];
        }
    }
    0.5 * sum
}

fn row_dot(row: &[f64; LOADS], loads: &[f64; LOADS]) -> f64 {
    row.iter().zip(loads).map(|(r, c)| r * c).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::sea::components::SplitMix64;

    /// The quadratic forms without the zero load coefficients' rows are the full double sums to the
    /// bit, on random forms and coefficients with random zeros (signed too).
    #[test]
    fn quadratic_forms_without_the_zero_loads_are_the_full_sums_to_the_bit() {
        let mut rng = SplitMix64::new(28);
        for _ in 0..2000 {
            let mut random = |scale: f64| (rng.next_f64() - 0.5) * scale;
            let g: [[f64; LOADS]; LOADS] = std::array::from_fn(|_| std::array::from_fn(|_| random(2e-6)));
            let mut loads: [f64; LOADS] = std::array::from_fn(|_| random(1e5));
            let mask = (random(2.0) + 1.0) * 128.0;
            for (a, load) in loads.iter_mut().enumerate() {
                if (mask as u32 >> a) & 1 == 1 {
                    *load = if a % 2 == 0 { 0.0 } else { -0.0 };
                }
            }
            let mut full = 0.0;
            for a in 0..LOADS {
                for b in 0..LOADS {
                    full += loads[a] * g[a][b] * loads[b];
                }
            }
            assert_eq!(quadratic(&g, &loads).to_bits(), (0.5 * full).to_bits(), "{loads:?}");
        }
    }
}

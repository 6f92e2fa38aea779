//! The energy-conservation cross-check (paper Section 3, Eqs. 27-35): the bridge's potential
//! energy becomes the strain energy of the arrestor, a spring of stiffness k_f = 3 E I / l^3.

use serde::{Deserialize, Serialize};

use crate::model::Scenario;

/// Results of the energy approach (Table 1, column 2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EnergyMethod {
    /// Flexion coefficient k_f = 3 E I / l^3 of the arrestor, N/m.
    pub flexion_stiffness: f64,
    /// Dynamic deflection of the arrestor's end w_din, m (Eq. 33).
    pub tip_deflection: f64,
    /// Dynamic contact force F_din = k_f w_din, N (Eq. 29).
    pub force: f64,
    /// Bending stress at the clamp F_din l / W, Pa.
    pub clamp_bending_stress: f64,
    /// Shear stress at the clamp F_din / A_s, Pa.
    pub clamp_shear_stress: f64,
    /// Strain energy of the arrestor E_def,a = F_din w_din / 2, J (Eq. 35).
    pub strain_energy: f64,
}

impl EnergyMethod {
    /// Eqs. (29), (33), (35) for a scenario.
    pub fn new(s: &Scenario) -> EnergyMethod {
        let l = &s.lower;
        let k_f = 3.0 * l.elastic_modulus * l.second_moment / l.length.powi(3);
        let weight = s.upper.mass * s.gravity;
        let (lu, d, h) = (s.upper.length, s.contact_position, s.drop_height);
        let w = (weight * lu + (weight * (8.0 * d * d * h * k_f + weight * lu * lu)).sqrt()) / (2.0 * d * k_f);
        let force = k_f * w;
        EnergyMethod {
            flexion_stiffness: k_f,
            tip_deflection: w,
            force,
            clamp_bending_stress: force * l.length / l.section_modulus,
            clamp_shear_stress: force / l.shear_area,
            strain_energy: 0.5 * force * w,
        }
    }
}

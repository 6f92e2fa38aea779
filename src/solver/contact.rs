//! The contact stage (paper Eqs. 5-6): the bar carries compression only, so the beams are
//! coupled while y_k,u - y_k,l < 0 and independent otherwise.

use serde::{Deserialize, Serialize};

/// Which system of equations holds during a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Stage {
    /// Two independent beams (Eq. 2).
    Free,
    /// Beams coupled through the contact bar (Eq. 4).
    Contact,
}

impl Stage {
    /// True in contact.
    pub fn is_contact(self) -> bool {
        self == Stage::Contact
    }
}

/// Dead band on Eq. (6), m. The beams touch exactly at t = 0 (gap 0 by construction); without
/// a dead band, round-off of order 1e-17 m would decide the first stage. 1 nm of penetration
/// is 28 N in the paper's bar, nothing against its 10^5 N forces.
pub const GAP_TOLERANCE: f64 = 1e-9;

/// Eq. (6): contact while the bridge's contact node is below the arrestor's end.
pub fn stage(gap: f64) -> Stage {
    if gap < -GAP_TOLERANCE {
        Stage::Contact
    } else {
        Stage::Free
    }
}

/// Axial force of the contact bar F_c = k (y_k,u - y_k,l), N (Eq. 5): negative in compression,
/// zero when the beams are apart.
pub fn bar_force(stiffness: f64, gap: f64, stage: Stage) -> f64 {
    if stage.is_contact() {
        stiffness * gap
    } else {
        0.0
    }
}

/// Strain energy of the compression-only bar, J: 1/2 k min(gap, 0)^2.
pub fn bar_energy(stiffness: f64, gap: f64) -> f64 {
    let g = gap.min(0.0);
    0.5 * stiffness * g * g
}

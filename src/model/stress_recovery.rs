//! How the bridge's bending moment at the contact node is recovered from the element end forces
//! (element stiffness times element displacements). The two elements that meet at the node give
//! different moments, because the contact force is a point load there: the moment is continuous
//! in the exact solution, but each cubic element carries its own linear moment.

use serde::{Deserialize, Serialize};

/// Which element(s) give the bridge's bending moment at the contact node.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StressRecovery {
    /// Mean of the two adjacent elements (the default: 292.1 MPa peak on the paper scenario).
    #[default]
    Mean,
    /// The element on the hinge side (296.0 MPa on the paper scenario).
    Left,
    /// The element on the free-end side.
    Right,
}

impl StressRecovery {
    /// The FMU's Integer parameter form: 0 mean, 1 left, 2 right.
    pub fn index(self) -> u32 {
        match self {
            StressRecovery::Mean => 0,
            StressRecovery::Left => 1,
            StressRecovery::Right => 2,
        }
    }

    /// From the FMU's Integer parameter form; `None` outside 0..=2.
    pub fn from_index(index: f64) -> Option<StressRecovery> {
        match index {
            0.0 => Some(StressRecovery::Mean),
            1.0 => Some(StressRecovery::Left),
            2.0 => Some(StressRecovery::Right),
            _ => None,
        }
    }
}

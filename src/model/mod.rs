//! The physical model: beams, mesh, assembly, damping and the scenario. No I/O, no unsafe.

pub mod assembly;
pub mod beam;
pub mod contact_law;
pub mod contact_range;
pub mod damping;
pub mod discretisation;
pub mod fatigue_fields;
pub mod fatigue_settings;
pub mod load_case;
pub mod mesh;
pub mod motion_table;
pub mod parameters;
pub mod rigid_impactor;
pub mod scenario;
pub mod sea;
pub mod section;
pub mod stations;
pub mod stress_recovery;
pub mod support_motion;
pub mod supports;
pub mod system;
pub mod time_step;

pub use assembly::Beam;
pub use discretisation::Method;
pub use scenario::Scenario;
pub use stress_recovery::StressRecovery;
pub use support_motion::{SupportMotion, Track};
pub use system::{Model, Probe, Reaction, REACTIONS};
pub use time_step::TimeStep;

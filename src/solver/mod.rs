//! Solution methods: natural modes, the linear acceleration stepper (production and dense
//! oracle), the truncated basis and its static correction, the contact stage, initial conditions
//! and the energy approach. No I/O, no unsafe.

pub mod contact;
pub mod dense;
pub mod eigen;
pub mod energy_method;
pub mod envelope;
pub mod exact;
pub mod far_support;
pub mod graded;
pub mod initial;
pub mod kinematics;
pub mod modal;
pub mod modal_cache;
pub mod model_range;
pub mod secular;
pub mod static_contact;
pub mod static_correction;
pub mod step_extrema;
pub mod step_plan;
pub mod stepper;
pub mod truncation;
pub mod turning_points;

pub use contact::Stage;
pub use dense::DenseStepper;
pub use eigen::{natural_modes, Modes};
pub use energy_method::EnergyMethod;
pub use kinematics::{Energies, Excitation, Kinematics, Stepper, SupportAndTips, TipForces};
pub use modal::ModalSystem;
pub use modal_cache::ModalCache;
pub use step_plan::StepPlan;
pub use stepper::ModalStepper;

//! beam-impact: the elastic impact of two beams (Čatipović, Vladimir, Reljić, "Numerical
//! Procedure for Two Beam Elastic Impact Analysis", Brodogradnja 2008), solved with
//! Euler-Bernoulli finite elements and the modified linear acceleration method, exported
//! as an FMI 2.0 / 3.0 co-simulation FMU that records every step to MCAP.
//!
//! Data flows one way: [`model::Scenario`] -> [`model::Model`] -> [`solver`] ->
//! [`results::StepResult`] -> [`record::Recorder`] and the FMI getters.

#![warn(missing_docs)]

pub mod amplification;
pub mod answer;
pub mod compare;
pub mod discretise;
pub mod error;
pub mod fatigue;
pub mod fmi;
pub mod load_cases;
pub mod model;
pub mod one_run;
pub mod paper;
pub mod record;
pub mod replay;
pub mod results;
pub mod run_document;
pub mod run_fatigue;
pub mod scenario_file;
pub mod simulation;
pub mod solver;
pub mod ssp;
pub mod studies;
pub mod sub_impacts;
pub mod vocabulary;
pub mod wording;

pub use error::{Error, Result};
pub use model::Scenario;
pub use simulation::Simulation;

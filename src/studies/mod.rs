//! The studies built on single runs: design sweeps over a grid of scenarios ([`sweep`]), the
//! convergence check of a scenario's peaks ([`verify`]), the damping study of the paper's
//! Appendix A ([`damping`]), campaigns of impacts in a sea state with their statistics and the
//! operability table ([`campaign`], [`statistics`]) and the solver's benchmarks ([`mod@bench`]). Each takes a validated
//! scenario and runs the simulation (or the answer with its checks) as many times as it needs;
//! none of them reads or writes files (the CLI does).

pub mod bench;
pub mod campaign;
pub mod damping;
pub mod statistics;
pub mod sweep;
pub mod sweep_governing;
pub mod verify;

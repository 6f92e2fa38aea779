//! Fatigue of a stress history (issue 44 item 3): rainflow counting after ASTM E1049-85
//! (reapproved 2017) Sec. 5.4.4 ([`rainflow`]), the S-N curves of DNV-RP-C203 ([`sn_curve`]) and
//! the Palmgren-Miner sum over the counted cycles ([`miner`]). Pure numbers: no I/O, no `unsafe`;
//! the CLI's `beam-impact fatigue` and the runs' per-station fatigue read their histories and call
//! these.

pub mod history;
pub mod miner;
pub mod rainflow;
pub mod sn_curve;
pub mod summary;

pub use miner::{damage, life_years, SnOptions};
pub use rainflow::{
    count, count_history, reversals, turning_points, Cycle, NonFiniteSample, RainflowCounter, ReversalTracker,
};
pub use sn_curve::{Environment, SnCurve};

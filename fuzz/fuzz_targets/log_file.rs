//! Any bytes as an MCAP log: `read_log_bytes`, then the summary from the steps it holds (against
//! the default scenario's model, built once: building the log's own is `report`'s business and
//! bounded by the scenario limits).
#![no_main]

use std::path::Path;
use std::sync::OnceLock;

use beam_impact::replay::report::{read_log_bytes, summary_from_log};
use beam_impact::{Scenario, Simulation};
use libfuzzer_sys::fuzz_target;

fn simulation() -> &'static Simulation {
    static SIMULATION: OnceLock<Simulation> = OnceLock::new();
    SIMULATION.get_or_init(|| Simulation::new(&Scenario::default()).expect("the default scenario builds"))
}

fuzz_target!(|data: &[u8]| {
    match read_log_bytes(data, Path::new("fuzz.mcap")) {
        Err(e) => assert!(!e.to_string().contains('\n')),
        Ok(log) => {
            assert!(log.problem.as_deref().is_none_or(|p| !p.contains('\n')));
            assert!(log.steps.windows(2).all(|w| w[0].step < w[1].step));
            let _ = log.scenario();
            let _ = summary_from_log(&log, simulation());
        }
    }
});

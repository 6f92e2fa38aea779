//! Issue 43 (cost): what a batch run leaves out changes nothing it answers. A run into a
//! recorder that wants no details (a campaign's, a sweep's: `NullRecorder`) computes no support
//! reactions and tip velocities at its motion rows, and an applied row hands its measured probes
//! to the next step: the same summary, state and outputs, to the bit, as a run into a recorder
//! that takes every step with its details.

use beam_impact::record::{MemoryRecorder, NullRecorder};
use beam_impact::scenario_file::read_file;
use beam_impact::Simulation;

use crate::sea_scenario::{folder, sea_toml};

/// A sea's run (Hs 1 m, a motion row every 5 ms, 0.3 s: the first contact and its bounces).
#[test]
fn a_batch_sea_run_ends_as_a_detailed_one_to_the_bit() {
    let dir = folder(&sea_toml("").replace("duration = 1.0", "duration = 0.3"));
    let scenario = read_file(&dir.path().join("s.toml"), &mut Vec::new()).unwrap();
    assert!(scenario.motion_changes(scenario.duration_ns()).unwrap().len() > 50);
    let mut batch = Simulation::new(&scenario).unwrap();
    let mut detailed = Simulation::new(&scenario).unwrap();
    let mut memory = MemoryRecorder::default();
    let (a, b) = (batch.run(&mut NullRecorder).unwrap(), detailed.run(&mut memory).unwrap());
    assert!(!a.contact_windows.is_empty());
    // The detailed run's records carry the details the batch run left out.
    assert!(memory.steps.iter().all(|s| s.lower_clamp_reaction_force != 0.0));
    assert_eq!(serde_json::to_string(&a).unwrap(), serde_json::to_string(&b).unwrap());
    assert_eq!(batch.state(), detailed.state());
    assert_eq!(batch.output(), detailed.output());
}

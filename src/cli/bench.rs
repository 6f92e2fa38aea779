//! `beam-impact bench`: the stepper's and the recorder's benchmarks.

use beam_impact::Result;

use super::common::emit;

/// `runs`: 1 to 1000, clap's range (so never the silent single run that `--runs 0` was).
pub fn bench(runs: u16) -> Result<()> {
    let runs = usize::from(runs);
    super::common::note(&format!(
        "beam-impact bench: 1/2 production stepper vs dense oracle, per-step cost ({runs} runs each)..."
    ));
    emit(&beam_impact::studies::bench::stepper_benchmark(runs)?)?;
    super::common::note(&format!("beam-impact bench: 2/2 recorded vs unrecorded paper run ({runs} runs each)..."));
    emit(&format!("\n{}", beam_impact::record::bench::recording_benchmark(runs)?))
}

//! `beam-impact bench`: the stepper's and the recorder's benchmarks.

use beam_impact::Result;

use super::common::emit;

pub fn bench(runs: usize) -> Result<()> {
    let runs = runs.max(1);
    super::common::note(&format!(
        "beam-impact bench: 1/2 production stepper vs dense oracle, per-step cost ({runs} runs each)..."
    ));
    emit(&beam_impact::studies::bench::stepper_benchmark(runs)?)?;
    super::common::note(&format!("beam-impact bench: 2/2 recorded vs unrecorded paper run ({runs} runs each)..."));
    emit(&format!("\n{}", beam_impact::record::bench::recording_benchmark(runs)?))
}

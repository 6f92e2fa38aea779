//! `beam-impact bench`: the paper run with every step recorded to MCAP, against the same run
//! unrecorded. Each recorded run is timed from building the simulation to a finished file; the
//! recorder's own clocks split it into solve, encode (protobuf) and compress + write (chunking,
//! zstd, CRCs, file writes, flushes, finish).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use super::mcap::{McapRecorder, RecorderOptions};
use super::{NullRecorder, Recorder};
use crate::error::{Error, Result};
use crate::model::Scenario;
use crate::simulation::Simulation;

#[derive(Clone, Copy, Debug, Default)]
struct Sample {
    total: Duration,
    encode: Duration,
    write: Duration,
    messages: u64,
    bytes: u64,
    steps: u64,
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// A scratch directory removed on drop.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn recorded_run(scenario: &Scenario, path: &std::path::Path) -> Result<Sample> {
    let started = Instant::now();
    let options = RecorderOptions { timing: true, ..RecorderOptions::default() };
    let mut recorder = McapRecorder::with_options(path, options)?;
    let mut simulation = Simulation::new(scenario)?;
    let summary = simulation.run(&mut recorder)?;
    let total = started.elapsed();
    let timing = recorder.timing();
    let bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    Ok(Sample {
        total,
        encode: timing.encode,
        write: timing.write,
        messages: timing.messages,
        bytes,
        steps: summary.steps,
    })
}

/// Runs the paper scenario `runs` times recorded and `runs` times unrecorded; returns the table
/// of medians (the CLI prints it).
pub fn recording_benchmark(runs: usize) -> Result<String> {
    let runs = runs.max(1);
    let scenario = Scenario::paper();
    let dir = std::env::temp_dir().join(format!("beam-impact-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|source| Error::Io {
        action: "cannot create benchmark directory",
        path: dir.display().to_string(),
        source,
    })?;
    let scratch = Scratch(dir);
    let mut plain = Vec::with_capacity(runs);
    let mut samples = Vec::with_capacity(runs);
    for run in 0..runs {
        let started = Instant::now();
        let mut simulation = Simulation::new(&scenario)?;
        let mut null = NullRecorder;
        simulation.run(&mut null as &mut dyn Recorder)?;
        plain.push(started.elapsed());
        samples.push(recorded_run(&scenario, &scratch.0.join(format!("run{run}.mcap")))?);
    }
    let total = crate::bench::median(samples.iter().map(|s| s.total).collect());
    let encode = crate::bench::median(samples.iter().map(|s| s.encode).collect());
    let write = crate::bench::median(samples.iter().map(|s| s.write).collect());
    let solve = crate::bench::median(samples.iter().map(|s| s.total.saturating_sub(s.encode + s.write)).collect());
    let unrecorded = crate::bench::median(plain);
    let last = samples[samples.len() - 1];
    let mut out = String::new();
    let build =
        if cfg!(debug_assertions) { "debug build: use --release for meaningful times" } else { "release build" };
    let _ = writeln!(
        out,
        "recording benchmark: paper scenario, {} internal steps, median of {runs} runs ({build})",
        last.steps
    );
    let _ = writeln!(out, "  unrecorded run                 {:8.1} ms", ms(unrecorded));
    let _ = writeln!(out, "  recorded run, start to file    {:8.1} ms", ms(total));
    let _ = writeln!(out, "    solve (simulation)           {:8.1} ms", ms(solve));
    let _ = writeln!(out, "    encode (protobuf)            {:8.1} ms", ms(encode));
    let _ = writeln!(out, "    compress + write (zstd, io)  {:8.1} ms", ms(write));
    let _ = writeln!(
        out,
        "  {} messages, {:.2} MB file ({:.1} B per step), recording overhead {:.1} ms",
        last.messages,
        last.bytes as f64 / 1e6,
        last.bytes as f64 / last.steps.max(1) as f64,
        ms(total.saturating_sub(unrecorded))
    );
    let _ = writeln!(
        out,
        "  recorded / unrecorded: {:.2}x",
        total.as_secs_f64() / unrecorded.as_secs_f64().max(f64::MIN_POSITIVE)
    );
    Ok(out)
}

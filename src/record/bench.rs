//! `beam-impact bench`: the paper run recorded to MCAP as `run --mcap` records it (the default
//! options), against the same run unrecorded (`run --no-mcap`), measured side by side
//! (alternating runs), with the ratio and the log's size first (issue 41 item 2); then each other chunk compression and the smallest channel set. Each
//! recorded run is timed from building the simulation to a finished file; the recorder's clocks
//! give the writer thread's work, encode (protobuf, the stations' stresses) and compress + write
//! (chunking, compression, CRCs, file writes, flushes, finish), and how long the solver's thread
//! waited for the queue.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use super::mcap::{LogChannels, LogCompression, McapRecorder, RecorderOptions};
use super::{NullRecorder, Recorder};
use crate::error::{Error, Result};
use crate::model::Scenario;
use crate::simulation::Simulation;

#[derive(Clone, Copy, Debug, Default)]
struct Sample {
    total: Duration,
    encode: Duration,
    write: Duration,
    queue_wait: Duration,
    solver_cpu: Duration,
    writer_cpu: Duration,
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

/// One way of recording: its label and options.
struct Variant {
    label: String,
    options: RecorderOptions,
}

/// The default recording first (what `run --mcap` writes), then the other compressions and the
/// smallest channel set.
fn variants() -> Vec<Variant> {
    let default = RecorderOptions::default();
    let with = |label: &str, options: RecorderOptions| Variant { label: label.to_string(), options };
    vec![
        with(&format!("default ({} {})", default.compression, default.compression_level), default),
        with("zstd level 1", RecorderOptions { compression_level: 1, ..default }),
        with("lz4", RecorderOptions { compression: LogCompression::Lz4, ..default }),
        with("none", RecorderOptions { compression: LogCompression::None, ..default }),
        with(
            &format!("default, --log-channels {}", LogChannels::REQUIRED),
            RecorderOptions { channels: LogChannels::REQUIRED, ..default },
        ),
    ]
}

fn recorded_run(scenario: &Scenario, path: &std::path::Path, options: RecorderOptions, timing: bool) -> Result<Sample> {
    let started = Instant::now();
    let cpu = cpu_time::ThreadTime::now();
    let options = RecorderOptions { timing, ..options };
    let mut recorder = McapRecorder::with_options(path, options)?;
    let mut simulation = Simulation::new(scenario)?;
    let summary = simulation.run(&mut recorder)?;
    // run() finished the log: the writer thread has ended and the file is complete.
    let total = started.elapsed();
    let solver_cpu = cpu.elapsed();
    let timing = recorder.timing();
    let bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    Ok(Sample {
        total,
        encode: timing.encode,
        write: timing.write,
        queue_wait: timing.queue_wait,
        solver_cpu,
        writer_cpu: timing.writer_cpu,
        messages: timing.messages,
        bytes,
        steps: summary.steps,
    })
}

/// Runs the paper scenario `runs` times unrecorded and `runs` times recorded in each way
/// (the default options, zstd 1, lz4, none, the required topics alone), alternating, so every ratio compares runs made under the same machine load;
/// returns the table of medians (the CLI prints it), the default recording's ratio and size first.
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
    let kinds = variants();
    let mut plain = Vec::with_capacity(runs);
    let mut plain_cpu = Vec::with_capacity(runs);
    let mut samples: Vec<Vec<Sample>> = vec![Vec::with_capacity(runs); kinds.len()];
    for run in 0..runs {
        let started = Instant::now();
        let cpu = cpu_time::ThreadTime::now();
        let mut simulation = Simulation::new(&scenario)?;
        let mut null = NullRecorder;
        simulation.run(&mut null as &mut dyn Recorder)?;
        plain.push(started.elapsed());
        plain_cpu.push(cpu.elapsed());
        for (k, kind) in kinds.iter().enumerate() {
            samples[k].push(recorded_run(
                &scenario,
                &scratch.0.join(format!("run{run}-{k}.mcap")),
                kind.options,
                false,
            )?);
        }
    }
    // One more run each with every message clocked, for where the writer's time goes (the clock
    // reads slow it: these runs are not in the ratios).
    let mut clocked = Vec::with_capacity(kinds.len());
    for (k, kind) in kinds.iter().enumerate() {
        clocked.push(recorded_run(&scenario, &scratch.0.join(format!("clocked-{k}.mcap")), kind.options, true)?);
    }
    let unrecorded = crate::studies::bench::median(plain);
    let unrecorded_cpu = crate::studies::bench::median(plain_cpu);
    let ratio = |d: Duration| d.as_secs_f64() / unrecorded.as_secs_f64().max(f64::MIN_POSITIVE);
    let mut out = String::new();
    let build =
        if cfg!(debug_assertions) { "debug build: use --release for meaningful times" } else { "release build" };
    let steps = samples[0][0].steps;
    let default_total = crate::studies::bench::median(samples[0].iter().map(|s| s.total).collect());
    let _ = writeln!(
        out,
        "recording benchmark: paper scenario, {steps} internal steps, median of {runs} runs ({build}); the writer \
         thread encodes and writes while the solver's thread steps"
    );
    let _ = writeln!(
        out,
        "  run --mcap over run --no-mcap: {:.2}x ({:.1} ms over {:.1} ms), the log {:.1} MB (the default options: \
         zstd chunks, every topic)",
        ratio(default_total),
        ms(default_total),
        ms(unrecorded),
        samples[0][samples[0].len() - 1].bytes as f64 / 1e6
    );
    let _ = writeln!(
        out,
        "  unrecorded run                              {:8.1} ms   (CPU {:.1} ms)",
        ms(unrecorded),
        ms(unrecorded_cpu)
    );
    for ((kind, samples), clocked) in kinds.iter().zip(&samples).zip(&clocked) {
        let median = |f: &dyn Fn(&Sample) -> Duration| crate::studies::bench::median(samples.iter().map(f).collect());
        let total = median(&|s| s.total);
        let wait = median(&|s| s.queue_wait);
        let solver_cpu = median(&|s| s.solver_cpu);
        let writer_cpu = median(&|s| s.writer_cpu);
        let last = samples[samples.len() - 1];
        let _ = writeln!(out, "  recorded run, {}, start to file   {:8.1} ms", kind.label, ms(total));
        let _ = writeln!(out, "    recorded / unrecorded: {:.2}x", ratio(total));
        let _ = writeln!(
            out,
            "    CPU: solver thread {:.1} ms, writer thread {:.1} ms (the busier over unrecorded: {:.2}x, the \
             ratio on two idle cores); the solver waited {:.1} ms for the queue",
            ms(solver_cpu),
            ms(writer_cpu),
            solver_cpu.max(writer_cpu).as_secs_f64() / unrecorded_cpu.as_secs_f64().max(f64::MIN_POSITIVE),
            ms(wait)
        );
        let _ = writeln!(
            out,
            "    {} messages, {:.2} MB file ({:.1} B per step); writer throughput {:.0} messages/s of writer CPU",
            last.messages,
            last.bytes as f64 / 1e6,
            last.bytes as f64 / last.steps.max(1) as f64,
            last.messages as f64 / writer_cpu.as_secs_f64().max(f64::MIN_POSITIVE)
        );
        let _ = writeln!(
            out,
            "    one run with every message clocked: encode (protobuf, stations) {:.1} ms, compress + write {:.1} ms",
            ms(clocked.encode),
            ms(clocked.write)
        );
    }
    Ok(out)
}

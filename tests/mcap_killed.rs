//! A process killed mid-run leaves a log whose complete chunks `report` still reads (issue 4).
//!
//! Goal: kill (SIGKILL, no destructors, no `finish`) a process while it records a long run,
//! then read the log: every complete chunk is there, the steps read are consecutive from 0, and
//! the report says the log was cut short while reporting what it holds.
//! Sketch: this test binary re-runs itself as the child (`child_records_a_long_run`, which does
//! nothing unless `BEAM_IMPACT_KILL_TEST_LOG` is set), waits until the file has grown past a few
//! chunks, kills it, and reads what is left.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use beam_impact::record::mcap::McapRecorder;
use beam_impact::replay::report::{read_log, report};
use beam_impact::{Scenario, Simulation};

const CHILD_ENV: &str = "BEAM_IMPACT_KILL_TEST_LOG";

/// The child: records a run long enough (1000 s simulated, minutes of wall time) to be killed.
#[test]
fn child_records_a_long_run() {
    let Ok(path) = std::env::var(CHILD_ENV) else { return };
    let scenario = Scenario { duration: 1000.0, ..Scenario::paper() };
    let mut recorder = McapRecorder::create(Path::new(&path)).unwrap();
    Simulation::new(&scenario).unwrap().run(&mut recorder).unwrap();
}

#[test]
fn killed_run_leaves_a_readable_log() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("killed.mcap");
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "mcap_killed::child_records_a_long_run", "--nocapture", "--test-threads", "1"])
        .env(CHILD_ENV, &path)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Wait for a few flushed chunks (a chunk is ~256 KiB before compression, ~150 KiB after).
    // The log is written to `NAME.partial` and takes its name only when finished (issue 16).
    let partial = beam_impact::record::output::partial_path(&path);
    let started = Instant::now();
    let grown = loop {
        let size = std::fs::metadata(&partial).map(|m| m.len()).unwrap_or(0);
        if size > 2_000_000 {
            break true;
        }
        if child.try_wait().unwrap().is_some() || started.elapsed() > Duration::from_secs(300) {
            break false;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(grown, "the child never wrote 2 MB (it exited or stalled)");

    assert!(!path.exists(), "a killed run never takes the log's name");
    let path = partial;
    let log = read_log(&path).unwrap();
    assert!(!log.complete);
    assert!(log.problem.is_some());
    assert!(log.steps.len() > 1000, "only {} steps read", log.steps.len());
    // The paper method's log (issue 41): its step ends, one at least every sample interval, in
    // order, without a gap longer than the interval but where a step's end falls after it.
    assert_eq!(log.steps[0].step, 0);
    assert!(log.steps.windows(2).all(|w| w[1].step > w[0].step && w[1].time_ns > w[0].time_ns), "rows out of order");
    let longest = log.steps.windows(2).map(|w| w[1].time_ns - w[0].time_ns).max().unwrap();
    assert!(longest < 2 * beam_impact::record::options::DEFAULT_SAMPLE_INTERVAL_NS, "rows {longest} ns apart");
    assert!(log.monotonic);
    assert_eq!(log.scenario().unwrap().duration, 1000.0);

    let mut out = Vec::new();
    report(&path, &dir.path().join("figures"), &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.contains("CUT SHORT"), "{text}");
    assert!(text.contains(&format!("{} complete step messages", log.steps.len())), "{text}");
    assert!(dir.path().join("figures").join("fig6-deflection.png").exists());
}

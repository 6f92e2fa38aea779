//! The MCAP log of the paper run (issue 4).
//!
//! Goal: the log holds exactly what the simulation produced: one `beam_impact.Step` message per
//! internal step (about 92 000 for the paper's 3 s), equal field for field to the in-memory
//! recorder's copy, contact events on their own channel and as `foxglove.Log` lines, a scene
//! every 1 ms of simulated time, the scenario as Metadata and attachment, time stamps that never
//! decrease; and the summary rebuilt from the log alone equals the simulation's own.
//! Tolerances: step values are compared exactly (f64 round-trips through protobuf); E_def,b is
//! rebuilt from the stored f64 modal coordinates in another summation order (1e-5 relative is
//! far above that round-off; it held f32 coordinates in log format 1).

use beam_impact::record::mcap::{McapRecorder, RecorderOptions};
use beam_impact::record::{MemoryRecorder, Recorder};
use beam_impact::replay::report::{read_log, report, summary_from_log};
use beam_impact::results::StepResult;
use beam_impact::{Scenario, Simulation};

use crate::recording_support;
use recording_support::Tee;

#[test]
fn paper_run_log_holds_every_step_and_rebuilds_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("paper.mcap");
    let scenario = Scenario::paper();
    let mut simulation = Simulation::new(&scenario).unwrap();
    let mut memory = MemoryRecorder::default();
    // A log of every internal step (without the dense output, issue 41).
    let every_step = RecorderOptions { sample_interval_ns: 0, ..RecorderOptions::default() };
    let mut mcap = McapRecorder::with_options(&path, every_step).unwrap();
    let summary = simulation.run(&mut Tee(&mut memory, &mut mcap)).unwrap();

    let log = read_log(&path).unwrap();
    assert!(log.complete, "{:?}", log.problem);
    assert!(log.monotonic);
    // One message per internal step, plus step 0 (the initial state).
    assert_eq!(log.steps.len() as u64, summary.steps + 1);
    assert_eq!(log.steps.len(), memory.steps.len());
    assert!((85_000..100_000).contains(&log.steps.len()), "{} steps", log.steps.len());
    for (k, (logged, kept)) in log.steps.iter().zip(&memory.steps).enumerate() {
        assert_eq!(logged, kept, "step {k}");
        assert_eq!(logged.step, k as u64);
    }
    assert_eq!(log.events, memory.events);
    assert!(!log.events.is_empty());
    assert_eq!(log.log_lines.len(), log.events.len());
    assert_eq!(log.messages["/beam/contact"], log.events.len() as u64);
    // A scene at t = 0 and every 1 ms to 3 s.
    assert_eq!(log.messages["/beam/scene"], 3001);
    assert_eq!(log.messages["/beam/model"], 1);
    assert_eq!(log.metadata["upper.length"], "29.0");
    assert_eq!(log.metadata["paper"], "true");
    assert_eq!(log.scenario().unwrap(), scenario);
    assert!(log.attachments.iter().any(|(name, media, _)| name == "scenario.toml" && media == "application/toml"));

    // The nodal shapes stored once redraw the probes of any step: the arrestor's end is the
    // last arrestor node.
    let model = log.model.as_ref().unwrap();
    let shapes = memory.nodal_shapes.as_ref().unwrap();
    assert_eq!((model.shape_rows as usize, model.shape_cols as usize), shapes.shape());
    let tip_row = model.lower_nodes.len() - 1;
    let k = memory.steps.len() / 3;
    let row = &model.nodal_shapes[tip_row * shapes.ncols()..(tip_row + 1) * shapes.ncols()];
    let tip: f64 = row.iter().zip(&memory.coordinates[k]).map(|(s, q)| s * (*q as f32) as f64).sum();
    let expected = memory.steps[k].lower_tip_deflection;
    assert!((tip - expected).abs() <= 1e-6 * expected.abs().max(0.01), "{tip} vs {expected}");

    let rebuilt = summary_from_log(&log, &simulation).unwrap();
    assert_eq!(rebuilt.steps, summary.steps);
    assert_eq!(rebuilt.time, summary.time);
    assert_eq!(rebuilt.peaks, summary.peaks);
    assert_eq!(rebuilt.peak_times, summary.peak_times);
    assert_eq!(rebuilt.contact_windows, summary.contact_windows);
    assert_eq!(rebuilt.final_energy_residual, summary.final_energy_residual);
    assert_eq!(rebuilt.max_energy_residual, summary.max_energy_residual);
    assert_eq!(rebuilt.modes, summary.modes);
    let (a, b) = (rebuilt.upper_strain_at_peak_deflection, summary.upper_strain_at_peak_deflection);
    assert!((a - b).abs() <= 1e-5 * b.abs(), "E_def,b {a} vs {b}");

    // The report reprints Table 1 and writes the four figures.
    let figures = dir.path().join("figures");
    let mut out = Vec::new();
    report(&path, &figures, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.contains("status: complete"), "{text}");
    assert!(text.contains("Table 1"), "{text}");
    for stem in ["fig6-deflection", "fig7-bending-stress", "fig8-shear-stress", "fig9-contact-stress"] {
        for ext in ["svg", "png"] {
            let file = figures.join(format!("{stem}.{ext}"));
            let size = std::fs::metadata(&file).map(|m| m.len()).unwrap_or(0);
            assert!(size > 10_000, "{} is {size} bytes", file.display());
        }
    }
}

#[test]
fn writer_settings_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no-such-dir").join("x.mcap");
    let err = McapRecorder::create(&missing).unwrap_err().to_string();
    assert!(err.contains("no-such-dir"), "{err}");

    // finish() is idempotent; writing after it is an error naming the file.
    let path = dir.path().join("short.mcap");
    let scenario = Scenario { duration: 0.01, ..Scenario::paper() };
    let mut recorder =
        McapRecorder::with_options(&path, RecorderOptions { scene_interval_ns: 0, ..RecorderOptions::default() })
            .unwrap();
    recorder.attach("notes.txt", "text/plain", b"hello").unwrap();
    let summary = Simulation::new(&scenario).unwrap().run(&mut recorder).unwrap();
    recorder.finish().unwrap();
    let err = recorder.step(&StepResult::default(), &[]).unwrap_err().to_string();
    assert!(err.contains("short.mcap"), "{err}");
    let log = read_log(&path).unwrap();
    assert!(log.complete);
    assert_eq!(log.steps.len() as u64, summary.steps + 1);
    assert_eq!(log.messages.get("/beam/scene"), None);
    assert!(log.attachments.iter().any(|(n, _, size)| n == "notes.txt" && *size == 5));
}

/// Two writers given the same path (two FMU instances with the default log.path, a sweep in
/// one directory): the second gets an error naming the file instead of interleaving records.
#[test]
fn second_writer_on_the_same_log_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("shared.mcap");
    let first = beam_impact::record::mcap::McapRecorder::create(&path).unwrap();
    let message = beam_impact::record::mcap::McapRecorder::create(&path).unwrap_err().to_string();
    assert!(message.contains("shared.mcap") && message.contains("another run or instance"), "{message}");
    drop(first);
    beam_impact::record::mcap::McapRecorder::create(&path).expect("free again once the first writer is gone");
}

/// A rollback (an FMU state restored, then stepped again): the log keeps every record and a
/// warning line, and the reader drops the superseded branch, so the steps read back are those
/// of a run without the rollback, and so are the summary's peaks and windows.
#[test]
fn rolled_back_steps_are_superseded_in_the_log() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rollback.mcap");
    let scenario = Scenario { duration: 1.0, ..Scenario::paper() };
    let every_step = RecorderOptions { sample_interval_ns: 0, ..RecorderOptions::default() };
    let mut recorder = McapRecorder::with_options(&path, every_step).unwrap();
    let mut simulation = Simulation::new(&scenario).unwrap();
    simulation.start_recording(&mut recorder).unwrap();
    simulation.advance_to(400_000_000, &mut recorder, false).unwrap();
    let saved = simulation.state().clone();
    simulation.advance_to(900_000_000, &mut recorder, false).unwrap();
    simulation.restore(saved).unwrap();
    recorder.rollback(simulation.result()).unwrap();
    simulation.advance_to(1_000_000_000, &mut recorder, false).unwrap();
    recorder.finish().unwrap();

    // The same run without the superseded branch: to 0.4 s, then to 1.0 s.
    let mut plain = MemoryRecorder::default();
    let mut straight = Simulation::new(&scenario).unwrap();
    straight.start_recording(&mut plain).unwrap();
    straight.advance_to(400_000_000, &mut plain, false).unwrap();
    straight.advance_to(1_000_000_000, &mut plain, false).unwrap();
    let reference = straight.summary();
    let data = read_log(&path).unwrap();
    assert_eq!(data.rollbacks, 1);
    assert!(data.log_lines.iter().any(|l| l.starts_with("rolled back to t = 0.400000 s")), "{:?}", data.log_lines);
    assert!(data.monotonic, "a rollback is not a disorder");
    assert_eq!(data.steps.len(), plain.steps.len());
    assert!(data.steps == plain.steps, "the steps read back differ from the straight run's");
    assert_eq!(data.events, plain.events);
    let summary = summary_from_log(&data, &Simulation::new(&scenario).unwrap()).unwrap();
    assert_eq!(summary.peaks, reference.peaks);
    assert_eq!(summary.contact_windows, reference.contact_windows);
}

/// A rolled-back run's log with the dense output (issue 41): the converged method's samples of
/// the superseded branch go with it, and the log reads as the straight run's, row for row.
#[test]
fn rolled_back_samples_are_superseded_in_the_log() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = Scenario { duration: 0.6, ..Scenario::default() };
    let path = dir.path().join("rollback.mcap");
    let mut recorder = McapRecorder::create(&path).unwrap();
    let mut simulation = Simulation::new(&scenario).unwrap();
    simulation.start_recording(&mut recorder).unwrap();
    simulation.advance_outputs_to(200_000_000, &mut recorder, false).unwrap();
    let saved = simulation.state().clone();
    simulation.advance_outputs_to(500_000_000, &mut recorder, false).unwrap();
    simulation.restore(saved).unwrap();
    recorder.rollback(simulation.result()).unwrap();
    simulation.finish_at(600_000_000, &mut recorder, false).unwrap();
    recorder.finish().unwrap();

    let straight_path = dir.path().join("straight.mcap");
    let mut straight_recorder = McapRecorder::create(&straight_path).unwrap();
    let mut straight = Simulation::new(&scenario).unwrap();
    straight.start_recording(&mut straight_recorder).unwrap();
    straight.advance_outputs_to(200_000_000, &mut straight_recorder, false).unwrap();
    straight.finish_at(600_000_000, &mut straight_recorder, false).unwrap();
    straight_recorder.finish().unwrap();

    let (data, reference) = (read_log(&path).unwrap(), read_log(&straight_path).unwrap());
    assert_eq!(data.rollbacks, 1);
    assert!(reference.steps.len() > 6000, "{} rows: the dense output every 0.1 ms", reference.steps.len());
    assert_eq!(data.steps.len(), reference.steps.len());
    assert!(data.steps == reference.steps, "the rows read back differ from the straight run's");
    assert_eq!(data.stations.times_ns, reference.stations.times_ns);
    assert_eq!(data.stations.values, reference.stations.values);
}

/// Issue 16 item 9: the size cap was checked on the log's path, so renaming the log mid-run
/// disabled it (a 30 MB cap gave 96.5 MB). It counts what the open file holds: renamed after its
/// first steps, the log still ends at its cap (checked at every flush: one flush beyond at most).
#[test]
fn a_log_renamed_mid_run_keeps_its_size_cap() {
    let dir = tempfile::tempdir().unwrap();
    let (path, moved) = (dir.path().join("run.mcap"), dir.path().join("moved.mcap"));
    let options = RecorderOptions { max_bytes: 400_000, ..RecorderOptions::default() };
    let mut recorder = McapRecorder::with_options(&path, options).unwrap();
    let mut simulation = Simulation::new(&Scenario { duration: 3.0, ..Scenario::paper() }).unwrap();
    simulation.start_recording(&mut recorder).unwrap();
    simulation.advance_to(10_000_000, &mut recorder, false).unwrap();
    std::fs::rename(recorder.file_being_written(), &moved).unwrap();
    simulation.advance_to(3_000_000_000, &mut recorder, false).unwrap();
    // The log was moved away under its writer: it cannot take its name, and says so.
    let finished = recorder.finish().unwrap_err().to_string();
    assert!(finished.contains("cannot rename the finished MCAP log"), "{finished}");
    assert!(recorder.capped().is_some(), "the cap was reached");
    let size = std::fs::metadata(&moved).unwrap().len();
    assert!((400_000..1_000_000).contains(&size), "{size} bytes for a cap of 400 000");
}

//! Log format 2 (issue 11): the modal coordinates on `/beam/modes`, peaks left out when
//! unchanged, decimation, the writer thread, the chunk compressions, and format 1 logs still read.
//!
//! Tolerances: every value is compared exactly: f64 round-trips through protobuf, and format 2
//! stores the modal coordinates as f64, so E_def,b rebuilt from the log equals the run's.

use std::path::Path;

use beam_impact::record::mcap::{LogCompression, McapRecorder, RecorderOptions, LOG_FORMAT, MODES_TOPIC};
use beam_impact::record::MemoryRecorder;
use beam_impact::replay::report::{read_log, summary_from_log};
use beam_impact::results::StepResult;
use beam_impact::{Scenario, Simulation};

use crate::recording_support;
use recording_support::Tee;

/// Runs `scenario` into a log with `options` and into memory.
fn record(scenario: &Scenario, path: &Path, options: RecorderOptions) -> (MemoryRecorder, Simulation) {
    let mut simulation = Simulation::new(scenario).unwrap();
    let mut memory = MemoryRecorder::default();
    let mut mcap = McapRecorder::with_options(path, options).unwrap();
    simulation.run(&mut Tee(&mut memory, &mut mcap)).unwrap();
    (memory, simulation)
}

/// A short run with a contact: 0.3 s of the paper scenario (the impact at 0 and bounces).
fn short() -> Scenario {
    Scenario { duration: 0.3, ..Scenario::paper() }
}

#[test]
fn every_compression_logs_the_same_steps_and_the_shape_at_the_peak_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = short();
    let mut sizes = Vec::new();
    for compression in [LogCompression::None, LogCompression::Lz4, LogCompression::Zstd] {
        let path = dir.path().join(format!("{compression}.mcap"));
        let (memory, simulation) = record(&scenario, &path, RecorderOptions { compression, ..Default::default() });
        let log = read_log(&path).unwrap();
        assert!(log.complete && log.monotonic, "{compression}: {:?}", log.problem);
        assert_eq!(log.log_format, LOG_FORMAT);
        assert!(log.steps == memory.steps, "{compression}: the logged steps differ from the run's");
        // The shape at the arrestor's peak deflection is in the log, as the run had it.
        let peak = memory.steps.last().unwrap().peaks.lower_tip_deflection;
        let k = memory.steps.iter().position(|r| r.peaks.lower_tip_deflection == peak).unwrap();
        assert_eq!(log.peak_deflection_step, k as u64);
        assert_eq!(log.peak_deflection_coordinates, memory.coordinates[k], "{compression}");
        let rebuilt = summary_from_log(&log, &simulation).unwrap();
        let own = simulation.summary();
        // The same coordinates summed in another order (the run's four lanes): round-off.
        let (a, b) = (rebuilt.upper_strain_at_peak_deflection, own.upper_strain_at_peak_deflection);
        assert!((a - b).abs() <= 1e-12 * b.abs(), "E_def,b {a} vs {b}");
        assert_eq!(rebuilt.peaks, own.peaks);
        // Modes at step 0, every 1 ms (300), at contact changes and at peaks: far fewer than steps.
        let modes = log.messages[MODES_TOPIC];
        assert!(modes > 300 && modes < log.steps.len() as u64 / 4, "{modes} modes messages");
        sizes.push(std::fs::metadata(&path).unwrap().len());
    }
    // Each compression makes the file smaller than none.
    assert!(sizes[1] < sizes[0] && sizes[2] < sizes[0], "{sizes:?}");
}

#[test]
fn decimation_keeps_step_0_the_last_step_contact_changes_and_every_peak() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("every10.mcap");
    // 1.5 s: the first sustained contact (to 0.75 s, where the peaks rise) and the bounces after.
    let scenario = Scenario { duration: 1.5, ..Scenario::paper() };
    let options = RecorderOptions { record_every: 10, sample_interval_ns: 0, ..Default::default() };
    let (memory, simulation) = record(&scenario, &path, options);
    let log = read_log(&path).unwrap();
    assert!(log.complete);
    let all = &memory.steps;
    // Exactly the steps the rule names, in order, each equal to the run's.
    let expected: Vec<StepResult> = all
        .iter()
        .enumerate()
        .filter(|&(k, r)| {
            let changed = k == 0 || all[k - 1].peaks != r.peaks || all[k - 1].contact != r.contact;
            // The step a contact event follows (the last of the old stage) and its first.
            let event_follows = all.get(k + 1).is_some_and(|next| next.contact != r.contact);
            changed || event_follows || r.step % 10 == 0 || k == all.len() - 1
        })
        .map(|(_, r)| *r)
        .collect();
    let steps = |v: &[StepResult]| v.iter().map(|r| r.step).collect::<Vec<_>>();
    assert_eq!(steps(&log.steps), steps(&expected));
    assert!(log.steps == expected, "the decimated steps differ from the run's");
    assert!(log.steps.len() < all.len() / 2, "{} of {} steps", log.steps.len(), all.len());
    assert_eq!(log.steps.last(), all.last());
    // Every contact event's first step is in the log, and the summary's peaks are the run's.
    for e in &log.events {
        assert!(log.steps.iter().any(|r| r.step == e.step), "contact change at step {} missing", e.step);
    }
    let rebuilt = summary_from_log(&log, &simulation).unwrap();
    let own = simulation.summary();
    assert_eq!(rebuilt.peaks, own.peaks);
    assert_eq!(rebuilt.peak_times, own.peak_times);
    let (a, b) = (rebuilt.upper_strain_at_peak_deflection, own.upper_strain_at_peak_deflection);
    assert!((a - b).abs() <= 1e-12 * b.abs(), "E_def,b {a} vs {b}");
}

#[test]
fn without_modal_coordinates_the_modes_topic_is_empty_and_the_scene_stays() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no-modes.mcap");
    let options = RecorderOptions { modal_coordinates: false, ..Default::default() };
    let (memory, _) = record(&Scenario { duration: 0.05, ..Scenario::paper() }, &path, options);
    let log = read_log(&path).unwrap();
    assert_eq!(log.messages.get(MODES_TOPIC), None);
    assert_eq!(log.messages["/beam/scene"], 51);
    assert!(log.steps == memory.steps, "the logged steps differ from the run's");
    assert!(log.peak_deflection_coordinates.is_empty());
    // The report says why the bridge's strain energy at the peak is missing (it printed NaN).
    let mut out = Vec::new();
    beam_impact::replay::report::report(&path, &dir.path().join("fig"), &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.contains("at the largest arrestor deflection: n/a (the log holds no modal"), "{text}");
    assert!(!text.contains("NaN"), "{text}");
}

/// A writer error (the disk full) is returned by a later call of the recorder, naming the file,
/// instead of being lost on the writer thread; the failed log stays `NAME.partial` and an earlier
/// log under NAME is left as it was. The full disk is a file-size limit (`ulimit -f`, SIGXFSZ
/// ignored: writes beyond it fail with EFBIG) on a child `beam-impact run`; /dev/full is no
/// longer accepted as a log (a device other than /dev/null).
#[test]
fn a_full_disk_is_reported_by_the_recorder() {
    let refused = McapRecorder::with_options(
        Path::new("/dev/full"),
        RecorderOptions { allow_devices: true, ..Default::default() },
    );
    assert!(refused.unwrap_err().to_string().contains("device other than /dev/null"));
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("full.mcap");
    std::fs::write(&log, "an earlier log").unwrap();
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 200; exec '{}' run --set duration=0.5 --mcap '{}'",
            env!("CARGO_BIN_EXE_beam-impact"),
            log.display()
        ))
        .output()
        .unwrap();
    let message = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{message}");
    assert!(message.contains("full.mcap"), "{message}");
    assert!(message.to_lowercase().contains("too large"), "{message}");
    assert_eq!(std::fs::read_to_string(&log).unwrap(), "an earlier log");
    assert!(beam_impact::record::output::partial_path(&log).is_file());
}

/// A recorder dropped without `finish` (an FMU freed without Terminate) ends its writer thread
/// and completes the file.
#[test]
fn a_dropped_recorder_completes_its_log() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dropped.mcap");
    let scenario = Scenario { duration: 0.05, ..Scenario::paper() };
    let mut simulation = Simulation::new(&scenario).unwrap();
    let mut recorder = McapRecorder::create(&path).unwrap();
    simulation.start_recording(&mut recorder).unwrap();
    simulation.advance_to(20_000_000, &mut recorder, false).unwrap();
    let last = simulation.result().step;
    drop(recorder);
    let log = read_log(&path).unwrap();
    assert!(log.complete, "{:?}", log.problem);
    assert_eq!(log.steps.last().map(|r| r.step), Some(last));
}

/// A format 1 log (written before the change: modal coordinates as f32 in every step message,
/// zstd chunks) from the regression corpus still reads, with the shape at the peak.
#[test]
fn a_format_1_log_still_reads() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/logs/real-2ms.mcap");
    let log = read_log(&path).unwrap();
    assert_eq!(log.log_format, 1);
    assert!(log.complete, "{:?}", log.problem);
    assert!(log.steps.len() > 50);
    assert!(log.steps.iter().enumerate().all(|(k, r)| r.step == k as u64));
    // Format 1 stored the time in seconds; format 2 derives it: both agree.
    assert!(log.steps.iter().all(|r| r.time == beam_impact::results::seconds(r.time_ns)));
    assert!(!log.peak_deflection_coordinates.is_empty());
    let simulation = Simulation::new(&log.scenario().unwrap()).unwrap();
    let summary = summary_from_log(&log, &simulation).unwrap();
    assert!(summary.upper_strain_at_peak_deflection.is_finite());
}

/// A log of a newer format than this reader knows is refused, naming the format.
#[test]
fn a_log_of_a_newer_format_is_refused_naming_its_format() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("format-99.mcap");
    {
        let file = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        let mut writer = mcap::WriteOptions::new().profile("beam-impact").create(file).unwrap();
        let metadata = [("log_format".to_string(), "99".to_string())].into_iter().collect();
        writer.write_metadata(&mcap::records::Metadata { name: "scenario".into(), metadata }).unwrap();
        writer.finish().unwrap();
    }
    let message = read_log(&path).unwrap_err().to_string();
    assert!(message.contains("log format \"99\""), "{message}");
}

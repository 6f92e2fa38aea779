//! Issue 30, item 3: the stress envelope is shown, not only printed; the log stores it and
//! `report` replays it.
//!
//! Goal: a stepped run's log (both examples: a tapered arrestor, a three-section gangway) holds
//! the run's envelope as `envelope.json`, equal to the run's own `summary.envelope`, and on
//! `/beam/stations` the stress at every station, with the run's envelope so far, every 1 ms (issue
//! 41: the first row at or after each multiple, the rows where contact changes, the last row); the
//! stations of the paper's points are the step messages' stresses; `report` reads the attachment,
//! and rebuilds the envelope from the last stations row's when the attachment is missing (a killed
//! run) and says so; a log written before either still replays, without an envelope; the figure
//! `envelope.svg`/`.png` is written; the FMU's log carries the envelope too; decimation keeps the
//! stresses of the recorded steps.
//! Tolerances: the attachment is JSON of f64 written with round-trip precision, compared exactly;
//! the recorded stresses are single precision (relative 2^-24 = 6e-8 each), so a station against
//! its step's f64 value, and a rebuilt envelope against the run's, are compared to 1e-6 of the
//! beam's largest stress (see `assert_rebuilt`).

use std::path::Path;
use std::process::Command;
use std::sync::Arc;

use beam_impact::record::mcap::{McapRecorder, RecorderOptions, ENVELOPE_ATTACHMENT};
use beam_impact::record::stations::StationFeed;
use beam_impact::record::{Recorder, RunInfo};
use beam_impact::replay::report::{envelope_of_log, read_log, read_log_bytes, EnvelopeSource, LogData};
use beam_impact::results::{ContactEvent, StationEnvelope, StepResult, StressEnvelope};
use beam_impact::{Scenario, Simulation};

fn example(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)
}

/// `beam-impact` with `args`; panics unless it exits 0; its standard output.
fn cli(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact")).args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "beam-impact {args:?}: {stderr}");
    String::from_utf8(out.stdout).unwrap()
}

/// The largest stress of each of an envelope's four lists (for tolerances).
fn largest(e: &StressEnvelope) -> [f64; 4] {
    let m = |s: &StationEnvelope| s.max.iter().fold(0.0f64, |a, &b| a.max(b));
    [m(&e.lower.bending), m(&e.lower.shear), m(&e.upper.bending), m(&e.upper.shear)]
}

fn lists(e: &StressEnvelope) -> [&StationEnvelope; 4] {
    [&e.lower.bending, &e.lower.shear, &e.upper.bending, &e.upper.shear]
}

/// A rebuilt envelope against the run's `run`: below it by at most `below` of the beam's largest
/// stress ([`REBUILD_MISS`]), positions and allowables equal; and above it by at most [`ENVELOPE_CUBIC_MISS`] of the
/// beam's largest: the run's envelope takes each station's crest inside a step from the cubic
/// through the step's ends, while the log's dense output (issue 41) records the exact solution,
/// which the cubic undershoots at stations with fast content.
fn assert_rebuilt(rebuilt: &StressEnvelope, run: &StressEnvelope, below: f64, what: &str) {
    for (k, ((x, y), scale)) in lists(rebuilt).into_iter().zip(lists(run)).zip(largest(run)).enumerate() {
        assert_eq!(x.positions, y.positions, "{what}: list {k}");
        assert_eq!(x.allowable, y.allowable, "{what}: list {k}");
        for (i, (u, v)) in x.max.iter().zip(&y.max).enumerate() {
            assert!(
                u - v <= ENVELOPE_CUBIC_MISS * scale && v - u <= below * scale,
                "{what}: list {k} station {i}: {u} vs {v} ({:.2e} of the largest)",
                (u - v) / scale
            );
        }
    }
}

/// The rebuild below the run's envelope, as a fraction of the beam's largest stress: the rows with
/// stations carry the run's envelope so far (issue 41), so the rebuild is the run's to their
/// single precision (6e-8 relative), whatever the stations' interval. Before they carried it the
/// rebuild from the rows' own stresses missed the crests between them: 2.2e-2 with stations at
/// every row, 3.9e-1 (a bridge shear station of the three-section gangway) at every 1 ms.
const REBUILD_MISS: f64 = 1e-6;

/// The envelope's in-step cubic below the exact solution at a station, as a fraction of the
/// beam's largest stress: measured 2.3e-3 (the tapered arrestor's second shear station, 61.67
/// against 61.50 MPa) and 3.1e-3 (the three-section gangway's bridge, bending station 98, 249.94
/// against 248.85 MPa), with single precision's 1e-6 on top. A limit of the envelope's in-step
/// estimate the dense output showed (issue 41's note), not of the log.
const ENVELOPE_CUBIC_MISS: f64 = 5e-3;

/// What the recorded stresses of `data` must rebuild: the run's envelope `run`, raised by the last
/// recorded row when the run ended inside an internal step (the converged method records that
/// point, interpolated, as its last record; the run's envelope is taken at internal steps' ends).
fn expected_rebuild(run: &StressEnvelope, data: &LogData) -> StressEnvelope {
    let mut expected = run.clone();
    let stations = &data.stations;
    let width = stations.width();
    let last = &stations.values[stations.values.len() - width..];
    let mut k = 0;
    for list in
        [&mut expected.lower.bending, &mut expected.lower.shear, &mut expected.upper.bending, &mut expected.upper.shear]
    {
        for max in list.max.iter_mut() {
            *max = max.max(f64::from(last[k]).abs());
            k += 1;
        }
    }
    expected
}

/// The file cut just before its envelope attachment: what a run killed after its last step and
/// before its log was finished leaves (every chunk, no attachment, no summary).
fn without_envelope(bytes: &[u8]) -> Vec<u8> {
    let name = ENVELOPE_ATTACHMENT.as_bytes();
    // Its first mention is the attachment record (the summary's index names it again).
    let at = bytes.windows(name.len()).position(|w| w == name).expect("the log holds envelope.json");
    // The attachment record: opcode, length (8), log and create time (16), the name's length (4).
    bytes[..at - 4 - 16 - 8 - 1].to_vec()
}

/// The stations' rule with the default options (issue 41): every row with stations is a row of
/// `/beam/step` (its step and time), one comes in every millisecond of the rows (the first row at
/// or after each multiple), and the last row has them.
fn assert_stations_every_millisecond(data: &LogData, what: &str) {
    let stations = &data.stations;
    let rows: std::collections::BTreeSet<(u64, u64)> = data.steps.iter().map(|r| (r.step, r.time_ns)).collect();
    for (&step, &time_ns) in stations.steps.iter().zip(&stations.times_ns) {
        assert!(rows.contains(&(step, time_ns)), "{what}: stations at step {step}, {time_ns} ns, not a row");
    }
    let last = data.steps.last().unwrap();
    assert_eq!(stations.times_ns.last(), Some(&last.time_ns), "{what}: the last row has stations");
    let with: std::collections::BTreeSet<u64> = stations.times_ns.iter().copied().collect();
    let mut next = 0;
    for r in &data.steps {
        if r.time_ns >= next {
            assert!(
                with.contains(&r.time_ns),
                "{what}: the first row at or after {next} ns ({} ns) has none",
                r.time_ns
            );
            next = (r.time_ns / 1_000_000 + 1) * 1_000_000;
        }
    }
    assert!(stations.rows() * 5 < data.steps.len(), "{what}: {} of {} rows", stations.rows(), data.steps.len());
}

/// A stepped example run by the CLI: its log holds the run's envelope as `--json` prints it,
/// `report` replays it from the attachment and draws the figure; without the attachment the
/// envelope is rebuilt from the recorded stresses, within their single precision, and said so.
fn stepped_example_replays(file: &str) {
    let dir = tempfile::tempdir().unwrap();
    let (log, json) = (dir.path().join("run.mcap"), dir.path().join("run.json"));
    let scenario = example(file);
    cli(&[
        "run",
        scenario.to_str().unwrap(),
        "--set",
        "duration=0.6",
        "--mcap",
        log.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let run: StressEnvelope = serde_json::from_value(doc["summary"]["envelope"].clone()).unwrap();
    assert!(run.lower.bending.max.len() > 20 && run.upper.bending.max.len() > 20);

    let data = read_log(&log).unwrap();
    assert!(data.complete, "{:?}", data.problem);
    let (stored, source) = envelope_of_log(&data);
    assert_eq!(source, EnvelopeSource::Attachment);
    assert_eq!(stored, run, "{file}: the log's envelope.json is the run's summary.envelope");
    // Every recorded step's stresses, one per station.
    let stations = &data.stations;
    let layout = stations.layout.as_ref().unwrap();
    assert_eq!(layout.len(), lists(&run).iter().map(|l| l.max.len()).sum::<usize>());
    assert_eq!(data.messages["/beam/stations"], stations.rows() as u64);
    assert_stations_every_millisecond(&data, file);
    // The station at the clamp is the step message's clamp bending stress (signs and the static
    // correction's loads: the converged method's truncated basis).
    let width = layout.len();
    let scale = largest(&run)[0];
    for (row, (&step, &time_ns)) in stations.steps.iter().zip(&stations.times_ns).enumerate() {
        let r = data.steps.iter().find(|r| (r.step, r.time_ns) == (step, time_ns)).unwrap();
        let clamp = f64::from(stations.values[row * width]);
        let expected = r.lower_clamp_bending_stress;
        assert!((clamp - expected).abs() <= 1e-6 * scale, "{file}: step {}: {clamp} vs {expected}", r.step);
    }

    let figures = dir.path().join("figures");
    let text = cli(&["report", log.to_str().unwrap(), "--out", figures.to_str().unwrap()]);
    assert!(text.contains("stress envelope: from the log's envelope.json"), "{text}");
    assert!(text.contains("arrestor bending") && text.contains("bridge bending"), "{text}");
    for ext in ["svg", "png"] {
        let figure = figures.join(format!("envelope.{ext}"));
        assert!(std::fs::metadata(&figure).map(|m| m.len()).unwrap_or(0) > 10_000, "{}", figure.display());
        assert!(text.contains(&figure.display().to_string()), "report lists {}: {text}", figure.display());
    }

    // A run killed before its log was finished: the envelope from the recorded stresses.
    let cut = dir.path().join("killed.mcap");
    std::fs::write(&cut, without_envelope(&std::fs::read(&log).unwrap())).unwrap();
    let killed = read_log(&cut).unwrap();
    assert!(!killed.complete && killed.envelope_json.is_none());
    let (rebuilt, source) = envelope_of_log(&killed);
    assert!(matches!(source, EnvelopeSource::Rebuilt { rows, .. } if rows == data.stations.rows()), "{source:?}");
    assert_rebuilt(&rebuilt, &expected_rebuild(&run, &killed), REBUILD_MISS, file);
    let text = cli(&["report", cut.to_str().unwrap(), "--out", figures.to_str().unwrap()]);
    assert!(text.contains("stress envelope: REBUILT from the") && text.contains("rows of /beam/stations"), "{text}");
    assert!(text.contains("the log holds no envelope.json"), "{text}");
}

#[test]
fn a_tapered_arrestors_log_replays_its_envelope() {
    stepped_example_replays("tapered-arrestor.toml");
}

#[test]
fn a_three_section_gangways_log_replays_its_envelope() {
    stepped_example_replays("three-section-gangway.toml");
}

/// A log written before logs carried the stations replays as it did, with no envelope and no
/// envelope figure, and says why.
#[test]
fn an_old_log_without_stations_or_envelope_still_replays() {
    // Held as written before issue 30 (the corpus's copy is rewritten with the builders).
    let old = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/log-before-stations.mcap");
    let data = read_log(&old).unwrap();
    assert!(data.stations.layout.is_none() && data.envelope_json.is_none());
    let (envelope, source) = envelope_of_log(&data);
    assert_eq!(envelope, StressEnvelope::default());
    assert!(matches!(source, EnvelopeSource::Absent { .. }));
    let dir = tempfile::tempdir().unwrap();
    let text = cli(&["report", old.to_str().unwrap(), "--out", dir.path().to_str().unwrap()]);
    assert!(text.contains("stress envelope: not in this log"), "{text}");
    assert!(text.contains("written before logs carried the envelope"), "{text}");
    assert!(text.contains("fig7-bending-stress.svg") && !text.contains("envelope.svg"), "{text}");
}

/// Forwards everything to the log and keeps the stations' feed, so that a test can change what
/// the log will attach.
struct Keep<'a> {
    inner: &'a mut McapRecorder,
    feed: Option<Arc<StationFeed>>,
}

impl Recorder for Keep<'_> {
    fn start(&mut self, info: &RunInfo<'_>) -> beam_impact::Result<()> {
        self.feed = info.stations.map(|p| Arc::clone(&p.feed));
        self.inner.start(info)
    }
    fn step(&mut self, result: &StepResult, q: &[f64]) -> beam_impact::Result<()> {
        self.inner.step(result, q)
    }
    fn contact_event(&mut self, event: &ContactEvent) -> beam_impact::Result<()> {
        self.inner.contact_event(event)
    }
    fn finish(&mut self) -> beam_impact::Result<()> {
        Ok(())
    }
}

/// A short converged run of the tapered arrestor recorded with `options`, whose attached envelope
/// is `edit`ed before the log is finished; the log's bytes and the run's envelope.
pub fn recorded_run(
    duration: f64,
    options: RecorderOptions,
    edit: &dyn Fn(&mut StressEnvelope),
) -> (Vec<u8>, StressEnvelope) {
    let text = std::fs::read_to_string(example("tapered-arrestor.toml")).unwrap();
    let scenario = Scenario { duration, ..Scenario::from_toml(&text, "tapered-arrestor.toml").unwrap() };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    let mut recorder = McapRecorder::with_options(&path, options).unwrap();
    let mut simulation = Simulation::new(&scenario).unwrap();
    let mut keep = Keep { inner: &mut recorder, feed: None };
    let summary = simulation.run(&mut keep).unwrap();
    let feed = keep.feed.take().unwrap();
    let mut envelope = feed.envelope().unwrap();
    assert_eq!(envelope, summary.envelope, "the feed holds the run's envelope at its end");
    edit(&mut envelope);
    feed.set_envelope(envelope);
    recorder.finish().unwrap();
    (std::fs::read(&path).unwrap(), summary.envelope)
}

/// With `--record-every N` the stresses are those of the recorded steps (step 0, every Nth, the
/// steps where a peak rises or contact changes, the last); the attachment is the whole run's.
#[test]
fn decimation_keeps_the_stresses_of_the_recorded_steps_and_the_whole_envelope() {
    let options =
        RecorderOptions { record_every: 50, sample_interval_ns: 0, scene_interval_ns: 0, ..RecorderOptions::default() };
    let (bytes, run) = recorded_run(1.0, options, &|_| {});
    let data = read_log_bytes(&bytes, Path::new("decimated.mcap")).unwrap();
    assert_eq!(data.stations.steps, data.steps.iter().map(|r| r.step).collect::<Vec<_>>());
    // Peaks rise at most steps of the impact, then stop rising: fewer steps recorded.
    let last = data.steps.last().unwrap().step;
    assert!(data.steps.len() * 10 < (last as usize) * 9, "{} of {last} steps recorded", data.steps.len());
    assert_eq!(envelope_of_log(&data), (run, EnvelopeSource::Attachment));
    let off = RecorderOptions { station_stresses: false, ..options };
    let (bytes, _) = recorded_run(0.05, off, &|_| {});
    let data = read_log_bytes(&bytes, Path::new("no-stations.mcap")).unwrap();
    assert!(data.stations.steps.is_empty() && data.stations.layout.is_some());
    assert_eq!(data.messages.get("/beam/stations"), None);
    assert_eq!(envelope_of_log(&data).1, EnvelopeSource::Attachment);
}

/// A stored envelope that is not the log's (a list of another length, a value that is not a
/// number, written as null) is refused in one line, and the envelope rebuilt from the stresses.
#[test]
fn a_malformed_envelope_attachment_is_refused_in_one_line_and_rebuilt() {
    // Stations at every row: the rebuild is held to the recorded steps' own stresses.
    let options = RecorderOptions { scene_interval_ns: 0, stations_interval_ns: 0, ..RecorderOptions::default() };
    type Edit<'a> = &'a dyn Fn(&mut StressEnvelope);
    let cases: [(Edit, &str); 3] = [
        (&|e| e.lower.bending.max.pop().map(|_| ()).unwrap(), "lower.bending has"),
        (&|e| e.upper.bending.max[3] = f64::NAN, "does not parse"),
        (&|e| e.lower.shear.positions.push(1.0), "lower.shear has"),
    ];
    for (edit, expected) in cases {
        let (bytes, run) = recorded_run(0.05, options, edit);
        let data: LogData = read_log_bytes(&bytes, Path::new("bad.mcap")).unwrap();
        let (rebuilt, source) = envelope_of_log(&data);
        let EnvelopeSource::Rebuilt { why, .. } = &source else { panic!("{source:?}") };
        assert!(why.contains(expected) && !source.describe().contains('\n'), "{why}");
        assert_rebuilt(&rebuilt, &expected_rebuild(&run, &data), REBUILD_MISS, expected);
    }
}

/// The FMU's log carries the envelope as the CLI's does (the simulation hands it to the log's
/// feed at the end of every step call), through an FMU state restored on the way: the attachment
/// is the envelope of the run as the importer left it, equal to the library's run to the same time
/// with the same communication points, and the recorded stresses (the superseded ones dropped)
/// rebuild it.
#[test]
fn the_fmus_log_carries_the_envelope_of_the_run_it_ended_with() {
    use crate::fmi_common::importer::{load, Fmu2, OK};
    let lib = load();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fmu.mcap");
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.set_string("log.path", path.to_str().unwrap()), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    fmu.run(0.0, 0.05, 1e-2);
    let state = fmu.get_state();
    fmu.run(0.05, 0.12, 1e-2);
    assert_eq!(fmu.set_state(state), OK, "{}", fmu.log.text());
    fmu.free_state(state);
    fmu.run(0.05, 0.1, 1e-2);
    assert_eq!(fmu.call0("fmi2Terminate"), OK, "{}", fmu.log.text());

    let mut simulation = Simulation::new(&Scenario::default()).unwrap();
    for k in 1..=10u64 {
        simulation.advance_outputs_to(k * 10_000_000, &mut beam_impact::record::NullRecorder, false).unwrap();
    }
    let expected = simulation.envelope();
    let bytes = std::fs::read(&path).unwrap();
    let data = read_log_bytes(&bytes, &path).unwrap();
    assert!(data.complete && data.rollbacks == 1, "{:?}", data.problem);
    let (stored, source) = envelope_of_log(&data);
    assert_eq!(source, EnvelopeSource::Attachment);
    assert_eq!(stored, expected, "the FMU's envelope.json is the run's to 0.1 s");
    let killed = read_log_bytes(&without_envelope(&bytes), &path).unwrap();
    let (rebuilt, source) = envelope_of_log(&killed);
    assert!(matches!(source, EnvelopeSource::Rebuilt { .. }), "{source:?}");
    // The run ended at 0.1 s inside an internal step, which the FMU's log does not hold (it
    // records internal steps): the run's envelope has the paper's three points raised by the
    // peak outputs at 0.1 s (the step's first part), the log's rebuild by its last step's. At those
    // three stations the rebuild is at most the run's; everywhere else the same.
    let contact =
        expected.upper.bending.positions.iter().position(|x| *x == Scenario::default().contact_position).unwrap();
    let (mut rebuilt_rest, mut expected_rest) = (rebuilt.clone(), expected.clone());
    for e in [&mut rebuilt_rest, &mut expected_rest] {
        (e.lower.bending.max[0], e.lower.shear.max[0], e.upper.bending.max[contact]) = (0.0, 0.0, 0.0);
    }
    assert_rebuilt(&rebuilt_rest, &expected_rest, REBUILD_MISS, "the FMU's log rebuilt");
    for (r, e) in [
        (rebuilt.lower.bending.max[0], expected.lower.bending.max[0]),
        (rebuilt.lower.shear.max[0], expected.lower.shear.max[0]),
        (rebuilt.upper.bending.max[contact], expected.upper.bending.max[contact]),
    ] {
        assert!(r <= e * (1.0 + 1e-12) && r > 0.9 * e, "a paper point rebuilt {r} against the run's {e}");
    }
}

//! The FEM bridge strain energy at the largest arrestor deflection (E_def,b of Eq. 36 from the
//! FEM): the run takes it at the instant where the deflection peaks (inside an internal step for
//! the converged method, the state its log's row there holds), and `report` replays the printed
//! value from the log to the bit, for both methods, with and without the dense output, and from
//! the CLI's own log.

use std::path::Path;
use std::process::Command;

use beam_impact::model::{Method, Scenario};
use beam_impact::record::mcap::{McapRecorder, RecorderOptions};
use beam_impact::replay::report::{read_log, summary_from_log, LogData};
use beam_impact::results::Summary;
use beam_impact::Simulation;

fn example(name: &str) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name);
    Scenario::from_toml(&std::fs::read_to_string(path).unwrap(), name).unwrap()
}

/// Runs `scenario` into a log at `path` with `options`: the run's summary, the log read back and
/// the simulation (the model `report` rebuilds from the log's scenario).
fn run_logged(scenario: &Scenario, path: &Path, options: RecorderOptions) -> (Summary, LogData, Simulation) {
    let mut recorder = McapRecorder::with_options(path, options).unwrap();
    let mut simulation = Simulation::new(scenario).unwrap();
    let summary = simulation.run(&mut recorder).unwrap();
    let log = read_log(path).unwrap();
    assert!(log.complete, "{:?}", log.problem);
    (summary, log, simulation)
}

#[test]
fn report_replays_the_printed_bridge_strain_at_the_largest_deflection_to_the_bit() {
    let dir = tempfile::tempdir().unwrap();
    // The converged method on a truncated basis (its deflection peaks inside a step), without
    // the dense output (the log then holds no row at that instant), and the paper's method.
    let arrestor = Scenario { duration: 0.45, ..example("arrestor.toml") };
    let no_samples = RecorderOptions { sample_interval_ns: 0, ..Default::default() };
    let paper = Scenario { duration: 0.8, ..Scenario::paper() };
    let cases = [
        ("arrestor", &arrestor, RecorderOptions::default()),
        ("arrestor, step ends only", &arrestor, no_samples),
        ("paper", &paper, RecorderOptions::default()),
    ];
    for (k, (case, scenario, options)) in cases.into_iter().enumerate() {
        let path = dir.path().join(format!("case{k}.mcap"));
        let (printed, log, simulation) = run_logged(scenario, &path, options);
        let replayed = summary_from_log(&log, &simulation).unwrap();
        let (a, b) = (replayed.upper_strain_at_peak_deflection, printed.upper_strain_at_peak_deflection);
        assert!(b > 0.0, "{case}: E_def,b {b}");
        assert_eq!(a.to_bits(), b.to_bits(), "{case}: report's E_def,b {a} J, the run's {b} J");
    }
}

#[test]
fn the_printed_bridge_strain_is_the_bridges_at_the_instant_of_the_largest_deflection() {
    let dir = tempfile::tempdir().unwrap();
    // A full basis (no discarded modes, whose static correction the coordinates leave out), so
    // that the bridge's strain energy is sum 1/2 omega^2 q^2 of its modes alone.
    let scenario = Scenario { duration: 0.45, modal_cutoff: 1e12, ..example("arrestor.toml") };
    assert_eq!(scenario.method, Method::Converged);
    let path = dir.path().join("full.mcap");
    let (printed, log, simulation) = run_logged(&scenario, &path, RecorderOptions::default());
    let modal = simulation.modal();
    assert!(!modal.is_truncated());
    // The row where the deflection peaks lies inside an internal step, at the printed instant.
    let at_ns = (printed.peak_times.lower_tip_deflection * 1e9).round() as u64;
    assert_eq!(log.peak_deflection_time_ns, at_ns);
    let row = log.steps.iter().rev().find(|r| r.time_ns == at_ns).unwrap();
    let end = log.steps.iter().find(|r| r.step == row.step && r.time_ns > at_ns).unwrap();
    assert!(end.time_ns > at_ns, "the peak is not inside its step");
    let q = &log.peak_deflection_coordinates;
    let strain: f64 = (modal.lower_dofs..q.len()).map(|i| 0.5 * modal.omega2[i] * q[i] * q[i]).sum();
    let value = printed.upper_strain_at_peak_deflection;
    assert!((strain - value).abs() <= 1e-9 * value, "the run's E_def,b {value} J, the bridge's at the peak {strain} J");
}

/// The line `run` prints and the one `report` prints from its log, for the CLI's own log.
#[test]
fn report_prints_the_bridge_strain_line_that_run_printed() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("arr.mcap");
    let scenario = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/arrestor.toml");
    let exe = env!("CARGO_BIN_EXE_beam-impact");
    let run = Command::new(exe)
        .args(["run", scenario.to_str().unwrap(), "--set", "duration=0.45", "--mcap", log.to_str().unwrap()])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let report = Command::new(exe).args(["report", log.to_str().unwrap()]).current_dir(dir.path()).output().unwrap();
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    let line = |out: &[u8]| {
        let text = String::from_utf8_lossy(out).into_owned();
        let found = text.lines().find(|l| l.contains("at the largest arrestor deflection")).map(str::to_string);
        found.unwrap_or_else(|| panic!("no E_def,b line in\n{text}"))
    };
    assert_eq!(line(&report.stdout), line(&run.stdout));
}

/// A log written before logs held the printed value replays it from the coordinates at that
/// step, as before.
#[test]
fn a_log_without_the_stored_bridge_strain_still_replays_it_from_its_coordinates() {
    let old = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/log-before-stations.mcap");
    let data = read_log(&old).unwrap();
    assert_eq!(data.peak_deflection_strain, None);
    assert!(!data.peak_deflection_coordinates.is_empty());
    let dir = tempfile::tempdir().unwrap();
    let exe = env!("CARGO_BIN_EXE_beam-impact");
    let out = Command::new(exe)
        .args(["report", old.to_str().unwrap(), "--out", dir.path().to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("FEM bridge strain energy at the largest arrestor deflection = 1.66 kJ"), "{text}");
}

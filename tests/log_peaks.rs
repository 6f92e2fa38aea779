//! Logs that hold the printed peaks (issue 41, item 1): every peak a run prints is a value its
//! log holds, at the printed time, across the tests' grid (drop heights 0.1-2 m, damping 0-0.05,
//! contact positions to the free end, meshes to 32x the paper's, the nonlinear laws, both
//! methods) and in the CLI's and the FMU's logs; the log's other rows never exceed it.
//!
//! Why the comparisons are exact: the converged method's peak inside a step is taken from the
//! exact advance's own solution at its instant (to the nanosecond), and the log's dense output
//! records the state at that very instant by the same computation, so the row equals the
//! printed value to the bit; the paper method's peaks are its step ends, which its log keeps.
//! Every other row is the same solution at another instant, so it lies below the peak but for
//! the peak instant's rounding to a nanosecond (|f''| dt^2 / 2 relative to f: below 1e-10 for
//! frequencies up to 2e4 rad/s), hence the 1e-9 allowance above it.

use std::path::Path;
use std::process::Command;

use beam_impact::model::{Method, Scenario};
use beam_impact::record::mcap::{McapRecorder, RecorderOptions};
use beam_impact::record::options::DEFAULT_SAMPLE_INTERVAL_NS;
use beam_impact::replay::report::read_log;
use beam_impact::results::{Peaks, StepResult, Summary};
use beam_impact::Simulation;

use crate::fmi_common;

/// The five peak outputs of a row, |value|, in the order of `Peaks::as_array`.
fn values(r: &StepResult) -> [f64; 5] {
    r.peak_magnitudes()
}

const NAMES: [&str; 5] = [
    "lower.tip_deflection",
    "lower.clamp_bending_stress",
    "lower.clamp_shear_stress",
    "upper.contact_bending_stress",
    "contact.force",
];

/// Rounding the peak's instant to a nanosecond (see the module documentation).
const ABOVE: f64 = 1e-9;

/// Checks that each of `peaks` (reached at `times`, s) is a row of `rows` to the bit, at its
/// time to the nanosecond, and that no row exceeds it by more than [`ABOVE`].
fn assert_log_holds(rows: &[StepResult], peaks: &Peaks, times: &Peaks, case: &str) {
    let (peaks, times) = (peaks.as_array(), times.as_array());
    for k in 0..5 {
        let largest = rows.iter().map(|r| values(r)[k]).fold(0.0, f64::max);
        assert!(
            largest <= peaks[k] * (1.0 + ABOVE),
            "{case}: the log's {} reaches {largest:e}, above the printed {:e}",
            NAMES[k],
            peaks[k]
        );
        let at = (times[k] * 1e9).round() as u64;
        let held = rows.iter().any(|r| values(r)[k] == peaks[k] && r.time_ns == at);
        assert!(
            held,
            "{case}: no row holds the printed {} {:e} at t = {} s (the log's largest: {largest:e})",
            NAMES[k], peaks[k], times[k]
        );
    }
}

fn run_logged(scenario: &Scenario, path: &Path) -> (Summary, Vec<StepResult>) {
    let mut recorder = McapRecorder::create(path).unwrap();
    let summary = Simulation::new(scenario).unwrap().run(&mut recorder).unwrap();
    let log = read_log(path).unwrap();
    assert!(log.complete && log.monotonic, "{:?}", log.problem);
    (summary, log.steps)
}

fn with(sets: &[(&str, String)]) -> Scenario {
    let mut s = Scenario { duration: 0.6, ..Scenario::default() };
    let texts: Vec<String> = sets.iter().map(|(n, v)| format!("{n}={v}")).collect();
    let settings = beam_impact::studies::sweep::parse_settings(&texts).unwrap();
    beam_impact::studies::sweep::apply_settings(&mut s, &settings).unwrap();
    s
}

#[test]
fn every_printed_peak_is_a_row_of_the_log_across_the_grid() {
    let dir = tempfile::tempdir().unwrap();
    let mut cases: Vec<Vec<(&str, String)>> = Vec::new();
    for drop in [0.1, 0.6, 2.0] {
        for damping in [0.0, 0.05] {
            cases.push(vec![("drop_height", drop.to_string()), ("damping_ratio", damping.to_string())]);
        }
    }
    for position in [9.0, 20.0, 29.0] {
        cases.push(vec![("contact_position", position.to_string())]);
    }
    // Meshes to 32x the paper's 7 + 7/7 elements.
    for factor in [4, 32] {
        cases.push(vec![
            ("lower.elements", (7 * factor).to_string()),
            ("upper.elements_to_contact", (7 * factor).to_string()),
            ("upper.elements_beyond_contact", (7 * factor).to_string()),
        ]);
    }
    // The nonlinear laws, undamped and damped (Hunt and Crossley).
    for damping in [0.0, 0.5] {
        cases.push(vec![
            ("contact.law", "power".into()),
            ("contact.exponent", "1.5".into()),
            // 3e11 N/m^1.5: within every law's rate (4e10 N/m at 4 times the impact's energy).
            ("contact.stiffness", "3e11".into()),
            ("contact.damping", damping.to_string()),
        ]);
    }
    cases.push(vec![("method", "paper".into())]);
    for (k, sets) in cases.iter().enumerate() {
        let scenario = with(sets);
        let path = dir.path().join(format!("case-{k}.mcap"));
        let (summary, rows) = run_logged(&scenario, &path);
        let case = format!("{sets:?}");
        assert_log_holds(&rows, &summary.peaks, &summary.peak_times, &case);
        // The dense output: a row at least every sample interval (but where a step's end falls
        // just after a multiple of it).
        if scenario.method == Method::Converged {
            let longest = rows.windows(2).map(|w| w[1].time_ns - w[0].time_ns).max().unwrap();
            assert!(longest <= DEFAULT_SAMPLE_INTERVAL_NS, "{case}: rows {longest} ns apart");
        }
    }
}

#[test]
fn a_log_of_every_internal_step_misses_the_peaks_between_them() {
    // Without the dense output (`--log-sample-interval 0`) the converged method's long steps
    // step over the crests: the 2.4 % low contact force.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("steps.mcap");
    let scenario = Scenario { duration: 0.6, ..Scenario::default() };
    let options = RecorderOptions { sample_interval_ns: 0, ..RecorderOptions::default() };
    let mut recorder = McapRecorder::with_options(&path, options).unwrap();
    let summary = Simulation::new(&scenario).unwrap().run(&mut recorder).unwrap();
    let rows = read_log(&path).unwrap().steps;
    let largest = rows.iter().map(|r| r.contact_force.abs()).fold(0.0, f64::max);
    assert!(largest < summary.peaks.contact_force * (1.0 - 1e-3), "{largest} vs {}", summary.peaks.contact_force);
}

/// The arrestor example through the CLI: the JSON's peaks are rows of its log as `report --csv`
/// writes it.
#[test]
fn the_cli_s_printed_peaks_are_rows_of_its_log() {
    let dir = tempfile::tempdir().unwrap();
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/arrestor.toml");
    let (log, json) = (dir.path().join("arrestor.mcap"), dir.path().join("arrestor.json"));
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .arg("run")
        .arg(&example)
        .args(["--set", "duration=0.8", "--mcap"])
        .arg(&log)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let answer: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let (peaks, times) = (&answer["summary"]["peaks"], &answer["summary"]["peak_times"]);
    let get = |v: &serde_json::Value, k: usize| v[NAMES[k]].as_f64().unwrap();
    let (mut printed, mut when) = (Peaks::default(), Peaks::default());
    printed.raise(&std::array::from_fn(|k| get(peaks, k)));
    when.raise(&std::array::from_fn(|k| get(times, k)));
    let (peaks, times) = (printed, when);
    let rows = read_log(&log).unwrap().steps;
    assert_log_holds(&rows, &peaks, &times, "examples/arrestor.toml");
    // And `report --csv`, the reader users plot from, holds them too (shortest round-trip text).
    let csv = dir.path().join("steps.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .arg("report")
        .arg(&log)
        .arg("--csv")
        .arg(&csv)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for (k, name) in NAMES.iter().enumerate() {
        let c = column(name);
        let largest = text
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(c).unwrap().parse::<f64>().unwrap().abs())
            .fold(0.0, f64::max);
        assert_eq!(largest, peaks.as_array()[k], "{name} in report --csv");
    }
    let _ = lines;
}

/// The FMU's log (FMI 2.0, communication step 1 ms) holds its final peak outputs.
#[test]
fn the_fmu_s_peak_outputs_are_rows_of_its_log() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("fmu.mcap");
    let lib = fmi_common::importer::load();
    let fmu = fmi_common::importer::Fmu2::new(&lib);
    const OK: i32 = 0;
    assert_eq!(fmu.setup(0.0, Some(0.6)), OK);
    assert_eq!(fmu.set_string("log.path", log.to_str().unwrap()), OK);
    // `log.sample_interval`: bounded when set (the error names it), read back as set.
    assert_ne!(fmu.set("log.sample_interval", 2.0), OK);
    assert!(fmu
        .log
        .text()
        .contains("log.sample_interval must be 0 (every internal step) or between 1e-6 and 1 s, got 2"));
    assert_eq!(fmu.set("log.sample_interval", 5e-4), OK);
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.get("log.sample_interval"), 5e-4);
    fmu.run(0.0, 0.6, 1e-3);
    let peaks: Vec<f64> = NAMES.iter().map(|n| fmu.get(&format!("peak.{n}"))).collect();
    assert_eq!(fmu.call0("fmi2Terminate"), OK);
    let rows = read_log(&log).unwrap().steps;
    let longest = rows.windows(2).map(|w| w[1].time_ns - w[0].time_ns).max().unwrap();
    assert!(longest <= 500_000, "rows {longest} ns apart with log.sample_interval = 5e-4 s");
    for (k, peak) in peaks.iter().enumerate() {
        let held = rows.iter().any(|r| values(r)[k] == *peak);
        let largest = rows.iter().map(|r| values(r)[k]).fold(0.0, f64::max);
        assert!(
            held && largest <= peak * (1.0 + ABOVE),
            "FMU {}: output {peak:e}, log's largest {largest:e}",
            NAMES[k]
        );
    }
}

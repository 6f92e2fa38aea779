//! The FMU driven by support motions (issue 17): the nine inputs, the mismatch warning, results
//! independent of the communication step for motions the constant-acceleration form represents
//! exactly, and the FMU against `run --motion` on the same samples.

use std::path::Path;

use crate::fmi_common;

use beam_impact::model::support_motion::MOTION_NAMES;
use beam_impact::model::{SupportMotion, Track};
use fmi_common::importer::{Fmu2, Fmu3, OK, WARNING};

const PEAKS: [&str; 5] = [
    "peak.lower.tip_deflection",
    "peak.lower.clamp_bending_stress",
    "peak.lower.clamp_shear_stress",
    "peak.upper.contact_bending_stress",
    "peak.contact.force",
];

fn set_motion2(fmu: &Fmu2, motion: &SupportMotion) {
    for (name, value) in MOTION_NAMES.iter().zip(motion.values()) {
        assert_eq!(fmu.set(name, value), OK, "{name}: {}", fmu.log.text());
    }
}

/// An FMI 2 run of `stop` s at communication step `interval`, the supports' motion at each point
/// from `motion(t)`; returns the peaks and the statuses' worst.
fn fmi2_run(stop: f64, interval: f64, motion: impl Fn(f64) -> SupportMotion) -> ([f64; 5], i32, Fmu2) {
    let lib = fmi_common::importer::load();
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.setup(0.0, Some(stop)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    set_motion2(&fmu, &motion(0.0));
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    let mut worst = OK;
    let steps = (stop / interval).round() as u64;
    for n in 0..steps {
        let t = n as f64 * interval;
        if n > 0 {
            set_motion2(&fmu, &motion(t));
        }
        let next = if n + 1 == steps { stop } else { (n + 1) as f64 * interval };
        let status = fmu.do_step(t, next - t);
        assert!(status == OK || status == WARNING, "step at {t}: {status}: {}", fmu.log.text());
        worst = worst.max(status);
    }
    (PEAKS.map(|p| fmu.get(p)), worst, fmu)
}

/// The hinge and the clamp under constant accelerations from t = 0 (with velocities, and the clamp
/// rotating): a motion the constant-acceleration form represents exactly, sent as its exact values
/// at every communication point. Communication steps of 1, 7 and 100 ms give the same peaks to
/// 1e-12 relative (the internal step grid is not broken: the inputs continue the motion to
/// round-off), and no step warns.
#[test]
fn exact_motions_give_results_independent_of_the_communication_step() {
    let start = SupportMotion {
        hinge_heave: Track { displacement: 0.0, velocity: 0.2, acceleration: -1.0 },
        clamp_heave: Track { displacement: 0.0, velocity: -0.1, acceleration: 0.5 },
        clamp_rotation: Track { displacement: 0.0, velocity: 0.002, acceleration: -0.01 },
    };
    let motion = |t: f64| start.after(t);
    let (reference, status, _) = fmi2_run(0.7, 1e-3, motion);
    assert_eq!(status, OK);
    for interval in [7e-3, 0.1] {
        let (peaks, status, fmu) = fmi2_run(0.7, interval, motion);
        assert_eq!(status, OK, "{}", fmu.log.text());
        for (k, (a, b)) in peaks.iter().zip(reference).enumerate() {
            assert!((a - b).abs() <= 1e-12 * b.abs(), "{} at {interval} s: {a} vs {b}", PEAKS[k]);
        }
    }
    // The motion changes the answer (the test can fail): fixed supports give other peaks.
    let (fixed, _, _) = fmi2_run(0.7, 0.1, |_| SupportMotion::default());
    assert!((fixed[1] - reference[1]).abs() > 1e-3 * reference[1]);
}

/// A master that sends positions without velocities and accelerations gets a warning naming the
/// input and the values (fmi2DoStep returns fmi2Warning), and the run goes on with the values as
/// given.
#[test]
fn inconsistent_motion_inputs_are_warned_by_name() {
    let heave = |t: f64| SupportMotion {
        hinge_heave: Track { displacement: 0.05 * t, ..Track::default() },
        ..SupportMotion::default()
    };
    let (_, status, fmu) = fmi2_run(0.05, 0.01, heave);
    assert_eq!(status, WARNING);
    let log = fmu.log.text();
    assert!(log.contains("upper.hinge_heave = 5e-4 disagrees with 0e0"), "{log}");
    assert!(log.contains("must describe one motion"), "{log}");
}

/// The nine inputs exist in FMI 3 too, read back what was set, and the tips' positions add the
/// supports' displacements to the deflections.
#[test]
fn fmi3_takes_the_motion_and_reports_absolute_positions() {
    let lib = fmi_common::importer::load();
    let fmu = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu.set_string("log.path", ""), OK);
    let values = [0.3, 0.0, 0.0, -0.2, 0.0, 0.0, 0.01, 0.0, 0.0];
    for (name, value) in MOTION_NAMES.iter().zip(values) {
        assert_eq!(fmu.set(name, value), OK);
    }
    assert_eq!(fmu.initialize_until(Some(1.0)), OK, "{}", fmu.log.text());
    for (name, value) in MOTION_NAMES.iter().zip(values) {
        assert_eq!(fmu.get(name), value, "{name}");
    }
    let length = beam_impact::Scenario::default().lower.length;
    let upper = fmu.get("upper.tip_deflection") + 0.3;
    let lower = fmu.get("lower.tip_deflection") - 0.2 + 0.01 * length;
    assert!((fmu.get("upper.tip_position") - upper).abs() < 1e-12);
    assert!((fmu.get("lower.tip_position") - lower).abs() < 1e-12);
}

/// The FMU and `beam-impact run --motion` on the same samples (a 0.5 m, 0.15 Hz hinge heave
/// sampled every 10 ms: the file's rows are the master's communication points) give the same
/// peaks to 1e-9 relative (issue 17): the CLI applies each row as an FMU input at its time.
#[test]
fn the_fmu_and_run_motion_agree_on_the_same_samples() {
    let omega = 2.0 * std::f64::consts::PI * 0.15;
    let heave = |t: f64| SupportMotion {
        hinge_heave: Track {
            displacement: 0.5 * (omega * t).sin(),
            velocity: 0.5 * omega * (omega * t).cos(),
            acceleration: -0.5 * omega * omega * (omega * t).sin(),
        },
        ..SupportMotion::default()
    };
    let (interval, stop) = (0.01, 1.0);
    let (fmu_peaks, _, _) = fmi2_run(stop, interval, heave);
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("heave.csv");
    let mut text = format!("time,{}\n", MOTION_NAMES.join(","));
    for n in 0..=100 {
        let t = n as f64 * interval;
        let values: Vec<String> = heave(t).values().iter().map(|v| format!("{v:e}")).collect();
        text.push_str(&format!("{t:e},{}\n", values.join(",")));
    }
    std::fs::write(&csv, text).unwrap();
    let json = dir.path().join("run.json");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_beam-impact"))
        .args(["run", "--no-mcap", "--set", "duration=1", "--motion"])
        .arg(&csv)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(out.status.code().is_some_and(|c| c <= 1), "{}", String::from_utf8_lossy(&out.stderr));
    let summary: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    for (k, name) in PEAKS.iter().enumerate() {
        let quantity = name.trim_start_matches("peak.");
        let cli = peak(&summary, quantity).unwrap_or_else(|| panic!("{quantity} in {summary}"));
        let relative = (cli - fmu_peaks[k]).abs() / cli.abs();
        assert!(relative <= 1e-9, "{name}: CLI {cli}, FMU {} ({relative:e})", fmu_peaks[k]);
    }
    assert!(Path::new(&csv).exists());
}

/// A peak of `run --json` by its FMU name.
fn peak(summary: &serde_json::Value, quantity: &str) -> Option<f64> {
    summary["summary"]["peaks"][quantity]["value"].as_f64().or_else(|| summary["summary"]["peaks"][quantity].as_f64())
}

/// A master that sets the motion at t = 0 only after ExitInitializationMode (the initial state was
/// computed with the supports at rest) is warned that the support jumps, by name: the fall before
/// t = 0 happens under the motion given in Initialization Mode.
#[test]
fn a_motion_changed_after_the_initial_state_is_warned() {
    let lib = fmi_common::importer::load();
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.setup(0.0, Some(0.1)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK);
    assert_eq!(fmu.set("lower.clamp_heave", -0.167), OK);
    assert_eq!(fmu.do_step(0.0, 0.01), WARNING, "{}", fmu.log.text());
    let log = fmu.log.text();
    assert!(log.contains("lower.clamp_heave = -1.67e-1 changes the value 0e0 given at the same instant"), "{log}");
}

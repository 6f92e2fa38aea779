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

/// `fmi3EnterInitializationMode` alone (start 0, stop `stop`).
fn fmi3_enter_initialization(fmu: &Fmu3, stop: f64) -> std::ffi::c_int {
    type Enter = unsafe extern "C" fn(*mut std::ffi::c_void, bool, f64, f64, bool, f64) -> std::ffi::c_int;
    // SAFETY: the signature of fmi3EnterInitializationMode.
    let enter: libloading::Symbol<Enter> = unsafe { fmu.lib.get(b"fmi3EnterInitializationMode\0") }.unwrap();
    // SAFETY: a live instance.
    unsafe { enter(fmu.c, false, 0.0, 0.0, true, stop) }
}

/// Issue 27 item 6: a support-motion input beyond its range (a clamp rotation of 1.5 rad or
/// 1000 rad, past the model's small-angle range; a heave acceleration of 1e5 m/s^2), NaN or inf is
/// refused with an error status and a message naming the input, the value and the bound, in FMI 2
/// and FMI 3 and in every state inputs are set in (before, 1.5 rad ran to results identical to
/// none, "trusted"). The value before is kept, the instance stays in its state and steps on.
#[test]
fn out_of_range_motion_inputs_are_errors_naming_the_bound_in_every_state() {
    use beam_impact::model::support_motion::{MOTION_LIMITS, MOTION_UNITS};
    use fmi_common::importer::ERROR;
    let cases = [
        ("lower.clamp_rotation", 1.5),
        ("lower.clamp_rotation", -1000.0),
        ("upper.hinge_heave_acceleration", 1e5),
        ("lower.clamp_heave_acceleration", -1e6),
        ("lower.clamp_rotation_velocity", 0.6),
        ("lower.clamp_heave", f64::NAN),
        ("upper.hinge_heave_velocity", f64::INFINITY),
    ];
    // Sets each case through `set`, checks the refusal and the message; `get` reads the value kept
    // (None where the state has no getters).
    let refuse = |set: &dyn Fn(&str, f64) -> i32, get: &dyn Fn(&str) -> Option<f64>, log: &dyn Fn() -> String| {
        for (name, value) in cases {
            let k = MOTION_NAMES.iter().position(|n| *n == name).unwrap();
            let before = get(name);
            assert_eq!(set(name, value), ERROR, "{name} = {value:e} accepted");
            let text = log();
            let line = text.lines().last().unwrap_or_default();
            assert!(line.starts_with("[logStatusError]") && line.contains(name), "{line}");
            assert!(line.contains(&format!("|value| <= {} {}", MOTION_LIMITS[k], MOTION_UNITS[k])), "{line}");
            assert!(line.contains(&format!("got {value:.6e}")), "{line}");
            assert!(line.len() < 250, "{line}");
            assert_eq!(get(name).map(f64::to_bits), before.map(f64::to_bits), "{name} changed");
        }
    };
    let lib = fmi_common::importer::load();

    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.setup(0.0, Some(0.1)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    let set2 = |name: &str, value: f64| fmu.set(name, value);
    let log2 = || fmu.log.text();
    refuse(&set2, &|_| None, &log2);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    refuse(&set2, &|name| Some(fmu.get(name)), &log2);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    assert_eq!(fmu.do_step(0.0, 0.01), OK);
    refuse(&set2, &|name| Some(fmu.get(name)), &log2);
    assert_eq!(fmu.do_step(0.01, 0.01), OK, "still in Step Mode: {}", fmu.log.text());

    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu3.set_string("log.path", ""), OK);
    let set3 = |name: &str, value: f64| fmu3.set(name, value);
    let get3 = |name: &str| Some(fmu3.get(name));
    let log3 = || fmu3.log.text();
    refuse(&set3, &get3, &log3);
    assert_eq!(fmi3_enter_initialization(&fmu3, 0.1), OK);
    refuse(&set3, &get3, &log3);
    assert_eq!(fmu3.call0("fmi3ExitInitializationMode"), OK, "{}", fmu3.log.text());
    assert_eq!(fmu3.do_step(0.0, 0.01).0, OK);
    refuse(&set3, &get3, &log3);
    assert_eq!(fmu3.do_step(0.01, 0.01).0, OK, "still in Step Mode: {}", fmu3.log.text());
}

/// Issue 27 item 8: `energy.external_work` books the supports' work, and its description says so
/// (before: "work done by the two input tip forces since t = 0", while -52.6 kJ stood under a
/// 0.3 m heave with no tip force). Under a clamp heave with no tip force the work is not zero,
/// and the energy balance closes with it: the residual is a small part of it.
#[test]
fn external_work_books_the_supports_work_and_says_so() {
    let heave = SupportMotion {
        clamp_heave: Track { displacement: 0.0, velocity: 0.0, acceleration: -2.0 },
        ..SupportMotion::default()
    };
    let (_, _, fmu) = fmi2_run(0.5, 0.01, |t| heave.after(t));
    assert_eq!((fmu.get("upper.tip_force"), fmu.get("lower.tip_force")), (0.0, 0.0));
    let (work, residual) = (fmu.get("energy.external_work"), fmu.get("energy.residual"));
    assert!(work != 0.0, "no work booked under a moving support");
    assert!(residual.abs() < 1e-2 * work.abs(), "the balance misses {residual} J of {work} J");
    let description = beam_impact::fmi::variables::table()
        .into_iter()
        .find(|v| v.name == "energy.external_work")
        .unwrap()
        .description;
    assert!(description.contains("tip forces") && description.contains("supports"), "{description}");
    assert!(description.contains("inertia loads") && description.contains("contact bar"), "{description}");
}

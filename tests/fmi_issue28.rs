//! Issue 28 through the FMU (FMI 2 and FMI 3, the C API loaded with libloading): the impact's
//! outputs, the refusal of contradictory or out-of-range new parameters, the new capabilities
//! giving what the CLI gives, and a serialized state that carries them.
//!
//! Oracle: the library run of the same scenario (what `beam-impact run` runs), `Simulation::run`
//! and `answer::run`, its scenario built from the FMU's defaults with each parameter set through
//! the same parameter table the FMU's setters use, its duration the FMU's stop time. With
//! constant inputs the FMU takes the very same internal steps (`tests/fmi_grid.rs`), so peaks and
//! impact agree to the bit; a refusal's message is the one `Scenario::validate` gives.

use crate::fmi_common;

use beam_impact::fmi::state::Snapshot;
use beam_impact::model::parameters::{self, find, Kind};
use beam_impact::record::NullRecorder;
use beam_impact::results::Impact;
use beam_impact::{answer, Scenario, Simulation};
use fmi_common::importer::{load, Fmu2, Fmu3, ERROR, OK, WARNING};

/// A parameter as an importer sets it: name and value (an Integer's as a whole number).
type Setting = (&'static str, f64);

/// Issue 28's benchmark shape: a pinned bridge rotating at 3.8 rad/s, no gravity, strikes a rigid
/// support through an 18 kN/m spring at its free end (the paper method's mesh of 40 elements).
const RIGID_AT_SPEED: &[Setting] = &[
    ("upper.length", 0.783),
    ("upper.mass", 0.3683232),
    ("upper.elastic_modulus", 6.7e10),
    ("upper.second_moment", 3.2013333333333333e-9),
    ("upper.section_modulus", 4.573333333333333e-7),
    ("contact_position", 0.783),
    ("damping_ratio", 0.01),
    ("method", 1.0),
    ("upper.elements_to_contact", 40.0),
    ("lower.kind", 1.0),
    ("contact.stiffness", 18000.0),
    ("gravity", 0.0),
    ("drop_height", 0.0),
    ("impact_angular_velocity", 3.8),
];

/// The rigid benchmark's run, s (its contact lasts a few milliseconds).
const RIGID_STOP: f64 = 0.012;

/// The paper's scenario (the FMU's defaults) with a 10 mm clearance.
const PAPER_WITH_CLEARANCE: &[Setting] = &[("contact.clearance", 0.01)];

/// The clearance run, s: the first contact (closed after 0.01 m / 2.59 m/s = 3.9 ms) and its
/// rebounds.
const PAPER_STOP: f64 = 0.3;

const PEAKS: [&str; 5] = [
    "peak.lower.tip_deflection",
    "peak.lower.clamp_bending_stress",
    "peak.lower.clamp_shear_stress",
    "peak.upper.contact_bending_stress",
    "peak.contact.force",
];

fn integer(name: &str) -> bool {
    find(name).unwrap().kind == Kind::Integer
}

/// The scenario an FMU runs with `settings` and stop time `stop`.
fn scenario(settings: &[Setting], stop: f64) -> Scenario {
    let mut s = Scenario::default();
    for &(name, value) in settings {
        parameters::set(&mut s, find(name).unwrap(), value).unwrap();
    }
    s.duration = stop;
    s
}

/// The message `Scenario::validate` gives for `settings` (which it must refuse).
fn refusal(settings: &[Setting]) -> String {
    let mut s = Scenario::default();
    for &(name, value) in settings {
        parameters::set(&mut s, find(name).unwrap(), value).unwrap();
    }
    s.validate().unwrap_err().to_string()
}

fn set2(fmu: &Fmu2, settings: &[Setting]) {
    for &(name, value) in settings {
        let status = if integer(name) { fmu.set_integer(name, value as i32) } else { fmu.set(name, value) };
        assert_eq!(status, OK, "{name} = {value}: {}", fmu.log.text());
    }
}

fn set3(fmu: &Fmu3, settings: &[Setting]) {
    for &(name, value) in settings {
        let status = if integer(name) { fmu.set_integer(name, value as i32) } else { fmu.set(name, value) };
        assert_eq!(status, OK, "{name} = {value}: {}", fmu.log.text());
    }
}

/// A step's status: OK, or at the stop time a warning that the results are not trusted (the
/// verdict the CLI prints beside the same peaks).
fn assert_step(status: i32, end: f64, stop: f64, log: &str) {
    if status == WARNING {
        assert!(end >= stop - 1e-12 && log.contains("no longer trusted"), "step to {end}: {log}");
    } else {
        assert_eq!(status, OK, "step to {end}: {log}");
    }
}

/// An FMI 2 instance without a log, `settings` set, initialized for [0, stop].
fn fmi2_initialized(settings: &[Setting], stop: f64) -> Fmu2 {
    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.setup(0.0, Some(stop)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    set2(&fmu, settings);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    fmu
}

/// Peaks and impact (angular velocity, closing speed) at the stop time of an FMI 2 run at
/// communication steps `interval`.
fn fmi2_run(settings: &[Setting], stop: f64, interval: f64) -> ([f64; 5], [f64; 2]) {
    let fmu = fmi2_initialized(settings, stop);
    let mut t = 0.0;
    let mut n = 0u64;
    while t < stop - 1e-12 {
        let next = ((n + 1) as f64 * interval).min(stop);
        assert_step(fmu.do_step(t, next - t), next, stop, &fmu.log.text());
        t = next;
        n += 1;
    }
    (PEAKS.map(|p| fmu.get(p)), [fmu.get("impact.angular_velocity"), fmu.get("impact.closing_speed")])
}

/// The same through FMI 3.
fn fmi3_run(settings: &[Setting], stop: f64, interval: f64) -> ([f64; 5], [f64; 2]) {
    let fmu = Fmu3::try_new(&load(), None, false).0.unwrap();
    assert_eq!(fmu.set_string("log.path", ""), OK);
    set3(&fmu, settings);
    assert_eq!(fmu.initialize_until(Some(stop)), OK, "{}", fmu.log.text());
    let mut t = 0.0;
    let mut n = 0u64;
    while t < stop - 1e-12 {
        let next = ((n + 1) as f64 * interval).min(stop);
        assert_step(fmu.do_step(t, next - t).0, next, stop, &fmu.log.text());
        t = next;
        n += 1;
    }
    (PEAKS.map(|p| fmu.get(p)), [fmu.get("impact.angular_velocity"), fmu.get("impact.closing_speed")])
}

fn bits<const N: usize>(values: [f64; N]) -> [u64; N] {
    values.map(f64::to_bits)
}

fn impact_array(i: Impact) -> [f64; 2] {
    [i.angular_velocity, i.closing_speed]
}

/// FMI 2 (1 ms) and FMI 3 (`interval`) runs of `settings` to `stop` give the CLI's peaks and
/// impact bit for bit: `answer::run`'s printed run, `Simulation::run` and `Simulation::impact`.
fn assert_fmu_equals_cli(settings: &[Setting], stop: f64, interval: f64) {
    let s = scenario(settings, stop);
    let cli = answer::run(&s, &mut NullRecorder, Default::default()).unwrap();
    let library = Simulation::new(&s).unwrap();
    let impact = library.impact();
    let summary = Simulation::new(&s).unwrap().run(&mut NullRecorder).unwrap();
    assert_eq!(bits(summary.peaks.as_array()), bits(cli.summary.peaks.as_array()), "Simulation::run = answer::run");
    assert_eq!(summary.impact, impact);
    assert_eq!(cli.summary.impact, impact);
    assert!(summary.peaks.contact_force > 0.0, "the run has a contact: {:?}", summary.peaks);
    for (version, (peaks, fmu_impact)) in
        [("FMI 2", fmi2_run(settings, stop, 1e-3)), ("FMI 3", fmi3_run(settings, stop, interval))]
    {
        assert_eq!(
            bits(peaks),
            bits(cli.summary.peaks.as_array()),
            "{version} peaks {peaks:?} vs {:?}",
            cli.summary.peaks
        );
        assert_eq!(bits(fmu_impact), bits(impact_array(impact)), "{version} impact {fmu_impact:?} vs {impact:?}");
    }
}

/// Item 4 (a): a rigid support with a given contact rate, struck at a stated speed without
/// gravity at the bridge's free end.
#[test]
fn a_rigid_support_struck_at_a_stated_speed_gives_the_clis_peaks_and_impact_to_the_bit() {
    assert_fmu_equals_cli(RIGID_AT_SPEED, RIGID_STOP, 1e-4);
    // The stated speed is the output's, and the free end closes at omega l_u.
    let fmu = fmi2_initialized(RIGID_AT_SPEED, RIGID_STOP);
    assert_eq!(fmu.get("impact.angular_velocity"), 3.8);
    let closing = fmu.get("impact.closing_speed");
    assert!((closing / (3.8 * 0.783) - 1.0).abs() < 1e-12, "{closing}");
    assert_eq!(fmu.get_integer("lower.kind"), 1);
}

/// Item 4 (b): the paper's scenario with a 10 mm clearance (the FMU's default converged method,
/// its check rungs in lockstep).
#[test]
fn the_paper_scenario_with_a_clearance_gives_the_clis_peaks_and_impact_to_the_bit() {
    assert_fmu_equals_cli(PAPER_WITH_CLEARANCE, PAPER_STOP, 1e-2);
    // The clearance is the FMU's: the contact starts once the gap is closed, after about
    // clearance / closing speed (gravity shortens it by a little).
    let fmu = fmi2_initialized(PAPER_WITH_CLEARANCE, PAPER_STOP);
    fmu.run(0.0, 0.01, 1e-3);
    let log = fmu.log.text();
    let first = log.lines().find(|l| l.contains("contact starts")).unwrap_or_else(|| panic!("{log}"));
    let t: f64 = first.split("t = ").nth(1).and_then(|r| r.split(' ').next()).unwrap().parse().unwrap();
    let expected = 0.01 / fmu.get("impact.closing_speed");
    assert!(t <= expected && t > 0.95 * expected, "{first}: expected about {expected} s");
}

/// Item 1: from the drop height the output is Eqs. 20-22's omega_0 = sqrt(3 g alpha_0 / l_u),
/// alpha_0 = atan(2 h / l_u) (0.1992 rad/s for the paper's 0.567 m), the closing speed omega_0 d;
/// a clamp rising at 0.5 m/s at t = 0 (an input set before initialization) adds its speed to the
/// closing speed, not to the angular velocity. Both equal `Simulation::impact` bit for bit.
#[test]
fn impact_outputs_follow_the_drop_height_formula_and_add_the_supports_closing_speed() {
    let (h, l, g, d) = (0.567_f64, 29.0_f64, 9.81_f64, 13.0_f64);
    let omega = (3.0 * g * (2.0 * h / l).atan() / l).sqrt();
    let fmu = fmi2_initialized(&[], 3.0);
    let (w, v) = (fmu.get("impact.angular_velocity"), fmu.get("impact.closing_speed"));
    assert!((w / omega - 1.0).abs() < 1e-12 && (w - 0.1992).abs() < 5e-5, "{w} vs {omega}");
    assert!((v / (w * d) - 1.0).abs() < 1e-12, "{v} vs {}", w * d);
    let expected = Simulation::new(&scenario(&[], 3.0)).unwrap().impact();
    assert_eq!(bits([w, v]), bits(impact_array(expected)));

    let lib = load();
    let moving = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(moving.set_string("log.path", ""), OK);
    assert_eq!(moving.set("lower.clamp_heave_velocity", 0.5), OK);
    assert_eq!(moving.initialize_until(Some(3.0)), OK, "{}", moving.log.text());
    let (w3, v3) = (moving.get("impact.angular_velocity"), moving.get("impact.closing_speed"));
    assert_eq!(w3, w, "the clamp's speed does not change the bridge's");
    assert!((v3 - (v + 0.5)).abs() < 1e-12, "{v3} vs {v} + 0.5");
    let mut motion = beam_impact::model::SupportMotion::default();
    motion.clamp_heave.velocity = 0.5;
    let expected = Simulation::starting_with(&scenario(&[], 3.0), motion).unwrap().impact();
    assert_eq!(bits([w3, v3]), bits(impact_array(expected)));
    // After steps through contact the outputs still say how the run started.
    fmu.run(0.0, 0.05, 1e-2);
    assert!(fmu.get("peak.contact.force") > 0.0);
    assert_eq!(bits([fmu.get("impact.angular_velocity"), fmu.get("impact.closing_speed")]), bits([w, v]));
}

/// Item 3: what the scenario refuses, the FMU refuses at `ExitInitializationMode` with an error
/// status and the scenario's one-line message in the log (FMI 2 and FMI 3); the setters take the
/// values (finite Reals), so that each contradiction is judged as a whole.
#[test]
fn contradictory_or_out_of_range_issue_28_parameters_fail_initialization_with_the_scenarios_message() {
    let cases: [(&[Setting], &str); 5] = [
        (
            &[("impact_angular_velocity", 3.8)],
            "drop_height = 0.567 m and impact_angular_velocity = 3.8 rad/s are both given",
        ),
        (&[("gravity", 0.0)], "gravity = 0 needs impact_angular_velocity"),
        (&[("contact.clearance", -0.01)], "contact.clearance must be >= 0 m, got -0.01"),
        (&[("contact.stiffness", -5.0)], "contact.stiffness"),
        (
            &[("drop_height", 0.0), ("impact_angular_velocity", 60.0)],
            "impact_angular_velocity must be between 0 and 50",
        ),
    ];
    let lib = load();
    for (settings, names) in cases {
        let message = refusal(settings);
        assert!(message.contains(names), "the scenario's message: {message}");
        assert!(!message.contains('\n'), "one line: {message}");

        let two = Fmu2::new(&lib);
        assert_eq!(two.set_string("log.path", ""), OK);
        set2(&two, settings);
        assert_eq!(two.setup(0.0, Some(1.0)), OK);
        assert_eq!(two.call0("fmi2EnterInitializationMode"), OK);
        assert_eq!(two.call0("fmi2ExitInitializationMode"), ERROR, "{settings:?}");
        let three = Fmu3::try_new(&lib, None, false).0.unwrap();
        assert_eq!(three.set_string("log.path", ""), OK);
        set3(&three, settings);
        assert_eq!(three.initialize_until(Some(1.0)), ERROR, "{settings:?}");
        for (version, log) in [("fmi2", &two.log), ("fmi3", &three.log)] {
            let errors: Vec<_> = log.all().into_iter().filter(|m| m.status == ERROR).collect();
            let expected = format!("{version}ExitInitializationMode: invalid parameter: {message}");
            assert_eq!(errors.len(), 1, "{version}: {}", log.text());
            assert_eq!(errors[0].text, expected, "{version}");
            assert_eq!(errors[0].category, "logStatusError");
        }
    }
}

/// Item 3: `lower.kind` takes 0 (beam) or 1 (rigid); 2 is refused by the setter (FMI 2
/// `SetInteger`, FMI 3 `SetInt32`) with the parameter's message; the old value is kept and a
/// valid one is still taken.
#[test]
fn a_support_kind_other_than_beam_or_rigid_is_refused_when_set() {
    let mut s = Scenario::default();
    let message = parameters::set(&mut s, find("lower.kind").unwrap(), 2.0).unwrap_err().to_string();
    assert!(message.contains("lower.kind") && message.contains("0 (beam) or 1 (rigid)"), "{message}");
    let lib = load();
    let two = Fmu2::new(&lib);
    assert_eq!(two.set_string("log.path", ""), OK);
    assert_eq!(two.set_integer("lower.kind", 2), ERROR);
    assert!(two.log.text().contains(&format!("[logStatusError] fmi2SetInteger: {message}")), "{}", two.log.text());
    assert_eq!(two.setup(0.0, Some(1.0)), OK);
    assert_eq!(two.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(two.get_integer("lower.kind"), 0, "the old value is kept");
    assert_eq!(two.set_integer("lower.kind", 1), OK, "the instance still takes a valid value");
    assert_eq!(two.get_integer("lower.kind"), 1);
    let three = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(three.set_integer("lower.kind", 2), ERROR);
    assert!(three.log.text().contains(&format!("[logStatusError] fmi3SetInt32: {message}")), "{}", three.log.text());
}

/// Item 5: a state of the rigid benchmark (with a clearance too) saved mid-run, serialized,
/// restored into fresh FMI 2 and FMI 3 instances, carries the new parameters and continues bit
/// for bit, the impact outputs included.
#[test]
fn a_serialized_state_with_issue_28_parameters_restores_and_continues_bit_for_bit() {
    let mut settings = RIGID_AT_SPEED.to_vec();
    settings.push(("contact.clearance", 0.0005));
    let outputs: Vec<u32> = beam_impact::fmi::variables::table()
        .iter()
        .filter(|v| v.causality.name() == "output" && v.ty == beam_impact::fmi::variables::Type::Real)
        .map(|v| v.vr)
        .collect();
    // A stop time beyond the end compared: every instance ends its last step alike (the stop time
    // ends a run inside its step grid, and a fresh instance that restores a state has none).
    let first = fmi2_initialized(&settings, 1.0);
    first.run(0.0, 0.006, 1e-3);
    let state = first.get_state();
    let bytes = first.serialize(state);
    first.free_state(state);
    let saved = Snapshot::from_bytes(&bytes).unwrap();
    for (name, value) in [
        ("impact_angular_velocity", 3.8),
        ("lower.kind", 1.0),
        ("contact.stiffness", 18000.0),
        ("contact.clearance", 0.0005),
    ] {
        assert_eq!(saved.parameters[name], value, "{name} in the state");
    }
    let at_save = first.get_reals(&outputs).1;

    let lib = load();
    let two = Fmu2::new(&lib);
    assert_eq!(two.set_string("log.path", ""), OK);
    let (status, restored) = two.deserialize(&bytes);
    assert_eq!(status, OK, "{}", two.log.text());
    assert_eq!(two.set_state(restored), OK, "{}", two.log.text());
    two.free_state(restored);
    let three = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(three.set_string("log.path", ""), OK);
    let (status, restored) = three.deserialize(&bytes);
    assert_eq!(status, OK, "{}", three.log.text());
    assert_eq!(three.set_state(restored), OK, "{}", three.log.text());
    three.free_state(restored);

    assert_eq!(two.get_integer("lower.kind"), 1);
    assert_eq!((two.get("contact.stiffness"), two.get("contact.clearance")), (18000.0, 0.0005));
    assert_eq!(three.get("impact_angular_velocity"), 3.8);
    let as_bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect::<Vec<_>>();
    assert_eq!(as_bits(two.get_reals(&outputs).1), as_bits(at_save.clone()), "FMI 2 at the saved time");
    assert_eq!(as_bits(three.get_reals(&outputs).1), as_bits(at_save), "FMI 3 at the saved time");
    first.run(0.006, RIGID_STOP, 1e-3);
    two.run(0.006, RIGID_STOP, 1e-3);
    three.run(0.006, RIGID_STOP, 1e-3);
    let end = as_bits(first.get_reals(&outputs).1);
    assert_eq!(as_bits(two.get_reals(&outputs).1), end, "FMI 2 at the stop time");
    assert_eq!(as_bits(three.get_reals(&outputs).1), end, "FMI 3 at the stop time");
    assert!(first.get("peak.contact.force") > 0.0, "the clearance was closed");
}

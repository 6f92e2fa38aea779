//! Issue 45 through the FMU (FMI 2 and FMI 3): `lower.supports` and `lower.contact_position` as
//! parameters (their value references appended), a deck beam on two pins struck off-centre giving
//! the CLI's peaks to the bit, and the refusals `Scenario::validate` gives.
//!
//! Oracle: the library run of the same scenario (`answer::run`, what `beam-impact run` runs), its
//! scenario built from the FMU's defaults through the same parameter table the FMU's setters use;
//! with constant inputs the FMU takes the very same internal steps (`tests/fmi_grid.rs`).

use crate::fmi_common;

use beam_impact::fmi::variables::table;
use beam_impact::model::parameters::{self, find, Kind};
use beam_impact::record::NullRecorder;
use beam_impact::{answer, Scenario};
use fmi_common::importer::{load, Fmu2, Fmu3, ERROR, OK, WARNING};

type Setting = (&'static str, f64);

/// A pinned-pinned deck beam struck 4 m along its 12 m span on the paper's mesh and method.
const DECK: &[Setting] = &[
    ("method", 1.0),
    ("lower.supports", 1.0),
    ("lower.contact_position", 4.0),
    ("lower.tip_mass", 0.0),
    ("drop_height", 0.3),
];

const STOP: f64 = 0.2;

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

fn scenario(settings: &[Setting]) -> Scenario {
    let mut s = Scenario::default();
    for &(name, value) in settings {
        parameters::set(&mut s, find(name).unwrap(), value).unwrap();
    }
    s.duration = STOP;
    s
}

fn settled(status: i32, end: f64, log: &str) {
    if status == WARNING {
        assert!(end >= STOP - 1e-12 && log.contains("no longer trusted"), "step to {end}: {log}");
    } else {
        assert_eq!(status, OK, "step to {end}: {log}");
    }
}

/// Issue 45's variables follow every older variable (`solver.max_steps` the last of those): the
/// supports' two parameters, the rigid impactor's five, then the far support's two reactions, the
/// last value references.
#[test]
fn the_supports_parameters_and_outputs_are_appended_after_every_older_variable() {
    let t = table();
    let names: Vec<&str> = t.iter().skip(t.len() - 10).map(|v| v.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "solver.max_steps",
            "lower.supports",
            "lower.contact_position",
            "upper.kind",
            "impact_speed",
            "upper.radius",
            "upper.poisson_ratio",
            "lower.poisson_ratio",
            "lower.far_reaction_force",
            "lower.far_reaction_moment"
        ]
    );
}

/// FMI 2 and FMI 3 runs of the deck beam give the CLI's peaks to the bit, the pin's bending 0.
#[test]
fn a_deck_beam_through_the_fmu_gives_the_clis_peaks_to_the_bit() {
    let cli = answer::run(&scenario(DECK), &mut NullRecorder, Default::default()).unwrap();
    let expected = cli.summary.peaks.as_array().map(f64::to_bits);
    assert!(cli.summary.peaks.contact_force > 0.0 && cli.summary.peaks.lower_clamp_bending_stress == 0.0);

    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.setup(0.0, Some(STOP)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    for &(name, value) in DECK {
        let status = if integer(name) { fmu.set_integer(name, value as i32) } else { fmu.set(name, value) };
        assert_eq!(status, OK, "{name}: {}", fmu.log.text());
    }
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    let mut t = 0.0;
    while t < STOP - 1e-12 {
        let next = (t + 0.01_f64).min(STOP);
        settled(fmu.do_step(t, next - t), next, &fmu.log.text());
        t = next;
    }
    assert_eq!(PEAKS.map(|p| fmu.get(p).to_bits()), expected, "FMI 2");
    assert_eq!(fmu.get_integer("lower.supports"), 1);
    // The far pin carries a force and no moment.
    assert!(fmu.get("lower.far_reaction_force").abs() > 0.0, "{}", fmu.get("lower.far_reaction_force"));
    assert_eq!(fmu.get("lower.far_reaction_moment"), 0.0);

    let fmu = Fmu3::try_new(&load(), None, false).0.unwrap();
    assert_eq!(fmu.set_string("log.path", ""), OK);
    for &(name, value) in DECK {
        let status = if integer(name) { fmu.set_integer(name, value as i32) } else { fmu.set(name, value) };
        assert_eq!(status, OK, "{name}: {}", fmu.log.text());
    }
    assert_eq!(fmu.initialize_until(Some(STOP)), OK, "{}", fmu.log.text());
    let mut t = 0.0;
    while t < STOP - 1e-12 {
        let next = (t + 0.05_f64).min(STOP);
        settled(fmu.do_step(t, next - t).0, next, &fmu.log.text());
        t = next;
    }
    assert_eq!(PEAKS.map(|p| fmu.get(p).to_bits()), expected, "FMI 3");
}

/// An unknown support code is refused by its setter, and a contact on the far pin at
/// initialization, each with the message naming the field.
#[test]
fn bad_supports_and_contact_positions_are_refused_naming_the_field() {
    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.setup(0.0, Some(STOP)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.set_integer("lower.supports", 4), ERROR);
    assert!(fmu.log.text().contains("lower.supports"), "{}", fmu.log.text());

    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.setup(0.0, Some(STOP)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.set_integer("lower.supports", 2), OK);
    assert_eq!(fmu.set("lower.contact_position", 12.0), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), ERROR);
    let log = fmu.log.text();
    assert!(log.contains("lower.contact_position") && log.contains("clamped-clamped"), "{log}");
}

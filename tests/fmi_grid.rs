//! Grid-independent co-simulation (issue 7): the FMU's internal step grid is broken only where it
//! must be (an input change, a located contact change, the stop time); outputs at communication
//! points inside an internal step come from that step's polynomial.
//!
//! Oracle: the library run of the same scenario (what the CLI runs), `Simulation::run`.
//! Tolerance 1e-9 relative on the peaks, as the issue asks: with constant inputs the FMU takes the
//! very same internal steps as the library run, so the peaks are in practice bit-identical; the
//! tolerance only leaves room for nothing. The same holds for each beam's worst stress along it
//! and where it sits (issue 30's envelope outputs), which are evaluated at the internal steps'
//! ends and so must not depend on where the communication points fall. Scenarios span drop heights 0.1-2 m, damping
//! 0.01-0.05 and contact positions 11-15 m (each with automatic steps, the FMU's default).

use crate::fmi_common;

use beam_impact::record::NullRecorder;
use beam_impact::solver::TipForces;
use beam_impact::{Scenario, Simulation};
use fmi_common::importer::{Fmu2, Fmu3, OK, WARNING};

const PEAKS: [&str; 4] = [
    "peak.lower.tip_deflection",
    "peak.lower.clamp_bending_stress",
    "peak.lower.clamp_shear_stress",
    "peak.upper.contact_bending_stress",
];

/// Each beam's worst stress along it and its position (the shear of the bridge: none here, 0).
const ENVELOPE: [&str; 7] = [
    "peak.upper.bending_stress",
    "peak.lower.bending_stress",
    "peak.lower.shear_stress",
    "peak.upper.shear_stress",
    "peak_position.upper.bending_stress",
    "peak_position.lower.bending_stress",
    "peak_position.lower.shear_stress",
];

const INTERVALS: [f64; 4] = [1e-4, 1e-3, 1e-2, 0.1];

/// (drop height m, damping ratio, contact position m).
const SCENARIOS: [(f64, f64, f64); 4] = [(0.1, 0.01, 13.0), (0.4, 0.01, 11.0), (1.0, 0.03, 15.0), (2.0, 0.05, 13.0)];

const STOP: f64 = 1.5;

fn scenario(h: f64, gamma: f64, d: f64) -> Scenario {
    Scenario { drop_height: h, damping_ratio: gamma, contact_position: d, duration: STOP, ..Scenario::default() }
}

fn library_peaks(scenario: &Scenario) -> ([f64; 4], [f64; 7]) {
    let summary = Simulation::new(scenario).unwrap().run(&mut NullRecorder).unwrap();
    let p = summary.peaks;
    let [upper_bending, upper_shear, lower_bending, lower_shear] = summary.envelope.peaks();
    let value = |peak: Option<beam_impact::results::EnvelopePeak>| peak.map_or(0.0, |p| p.value);
    let position = |peak: Option<beam_impact::results::EnvelopePeak>| peak.map_or(0.0, |p| p.position);
    (
        [
            p.lower_tip_deflection,
            p.lower_clamp_bending_stress,
            p.lower_clamp_shear_stress,
            p.upper_contact_bending_stress,
        ],
        [
            value(upper_bending),
            value(lower_bending),
            value(lower_shear),
            value(upper_shear),
            position(upper_bending),
            position(lower_bending),
            position(lower_shear),
        ],
    )
}

fn assert_close(what: &str, got: f64, expected: f64) {
    let relative = ((got - expected) / expected).abs();
    assert!(relative <= 1e-9, "{what}: FMU {got}, library {expected} (relative {relative:e})");
}

/// Every step returns OK, except that the step reaching the FMU's stop time warns when the
/// discretisation check does not vouch for the whole run's peaks (the lightly damped low drop here:
/// its late peaks move by several percent between rungs), as the FMU's output says.
fn assert_step_status(status: i32, end: f64, figure: f64, log: &str) {
    if status == WARNING {
        assert!(end >= STOP && figure > 0.01, "step to {end}, figure {figure}: {log}");
        assert!(log.contains("against the discretisation check"), "{log}");
    } else {
        assert_eq!(status, OK, "step to {end}: {log}");
    }
}

fn fmi2(h: f64, gamma: f64, d: f64, interval: f64, input: Option<(f64, f64)>) -> ([f64; 4], [f64; 7]) {
    let lib = fmi_common::importer::load();
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.setup(0.0, Some(STOP)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    for (name, value) in [("drop_height", h), ("damping_ratio", gamma), ("contact_position", d)] {
        assert_eq!(fmu.set(name, value), OK);
    }
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    let mut t = 0.0;
    let mut n = 0u64;
    while t < STOP - 1e-12 {
        if let Some((at, force)) = input {
            if (t - at).abs() < 1e-9 {
                assert_eq!(fmu.set("upper.tip_force", force), OK);
            }
        }
        let next = (((n + 1) as f64) * interval).min(STOP);
        let status = fmu.do_step(t, next - t);
        assert_step_status(status, next, fmu.get("quality.discretisation_error"), &fmu.log.text());
        t = next;
        n += 1;
    }
    (PEAKS.map(|name| fmu.get(name)), ENVELOPE.map(|name| fmu.get(name)))
}

fn fmi3(h: f64, gamma: f64, d: f64, interval: f64) -> ([f64; 4], [f64; 7]) {
    let lib = fmi_common::importer::load();
    let fmu = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu.set_string("log.path", ""), OK);
    for (name, value) in [("drop_height", h), ("damping_ratio", gamma), ("contact_position", d)] {
        assert_eq!(fmu.set(name, value), OK);
    }
    assert_eq!(fmu.initialize_until(Some(STOP)), OK, "{}", fmu.log.text());
    let mut t = 0.0;
    let mut n = 0u64;
    while t < STOP - 1e-12 {
        let next = (((n + 1) as f64) * interval).min(STOP);
        let (status, _, _) = fmu.do_step(t, next - t);
        assert_step_status(status, next, fmu.get("quality.discretisation_error"), &fmu.log.text());
        t = next;
        n += 1;
    }
    (PEAKS.map(|name| fmu.get(name)), ENVELOPE.map(|name| fmu.get(name)))
}

/// With zero inputs, FMI 2 and FMI 3 at communication intervals 1e-4, 1e-3, 1e-2 and 0.1 s give
/// the library run's peaks to 1e-9 relative, across drop heights, damping and contact positions;
/// so do each beam's worst stress along it (the envelope's peaks) and its position, which must
/// sit at the same station whatever the interval (the bridge has no shear area here: 0 both ways).
#[test]
fn fmu_peaks_equal_the_library_run_at_every_communication_interval() {
    for (h, gamma, d) in SCENARIOS {
        let (expected, envelope) = library_peaks(&scenario(h, gamma, d));
        assert!(envelope[..3].iter().all(|v| *v > 0.0) && envelope[3] == 0.0, "{envelope:?}");
        for interval in INTERVALS {
            let ((two, two_envelope), (three, three_envelope)) =
                (fmi2(h, gamma, d, interval, None), fmi3(h, gamma, d, interval));
            for k in 0..4 {
                let what = format!("{} at h = {h}, gamma = {gamma}, d = {d}, interval {interval} s", PEAKS[k]);
                assert_close(&format!("FMI 2 {what}"), two[k], expected[k]);
                assert_close(&format!("FMI 3 {what}"), three[k], expected[k]);
            }
            for k in 0..ENVELOPE.len() {
                let what = format!("{} at h = {h}, gamma = {gamma}, d = {d}, interval {interval} s", ENVELOPE[k]);
                for (fmi, got) in [("FMI 2", two_envelope[k]), ("FMI 3", three_envelope[k])] {
                    if envelope[k] == 0.0 || ENVELOPE[k].starts_with("peak_position.") {
                        assert_eq!(got, envelope[k], "{fmi} {what}");
                    } else {
                        assert_close(&format!("{fmi} {what}"), got, envelope[k]);
                    }
                }
            }
        }
    }
}

/// A stepped input lands at its communication point as a true step: the internal step ends at
/// 0.5 s, where the force is applied. The oracle is the library run that lands a step on 0.5 s,
/// sets the force and goes on; whatever the communication interval around it, the FMU matches it
/// to 1e-9, and the same force applied 10 ms earlier or later gives other peaks (the test can fail).
#[test]
fn stepped_input_takes_effect_at_its_communication_point() {
    let (h, gamma, d) = (0.567, 0.03, 13.0);
    let force = -150_000.0;
    let landed = |at_ns: u64| {
        let mut simulation = Simulation::new(&scenario(h, gamma, d)).unwrap();
        simulation.advance_to(at_ns, &mut NullRecorder, false).unwrap();
        simulation.set_tip_forces(TipForces { upper: force, lower: 0.0 });
        simulation.advance_to((STOP * 1e9) as u64, &mut NullRecorder, false).unwrap();
        let p = simulation.result().peaks;
        [
            p.lower_tip_deflection,
            p.lower_clamp_bending_stress,
            p.lower_clamp_shear_stress,
            p.upper_contact_bending_stress,
        ]
    };
    let expected = landed(500_000_000);
    for interval in [1e-3, 1e-2, 0.1] {
        let (got, _) = fmi2(h, gamma, d, interval, Some((0.5, force)));
        for k in 0..4 {
            assert_close(
                &format!("{} with the input stepped at 0.5 s, interval {interval} s", PEAKS[k]),
                got[k],
                expected[k],
            );
        }
    }
    for other in [490_000_000, 510_000_000] {
        let shifted = landed(other);
        assert!(
            (0..4).any(|k| ((shifted[k] - expected[k]) / expected[k]).abs() > 1e-6),
            "moving the input by 10 ms should change the peaks: {shifted:?} vs {expected:?}"
        );
    }
}

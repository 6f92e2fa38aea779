//! The FMU as a host program sees it: the shared library loaded with libloading and driven
//! through the C API (FMI 2.0 mostly, FMI 3.0 for early return).
//!
//! Oracle: `Simulation::new(&Scenario::paper())` run in-process (what the CLI runs). The FMU
//! cuts the internal steps at every communication point, so after a contact change (located to
//! the nanosecond) its step sequence differs from the single CLI run: peaks agree to 1e-3, not
//! bit for bit. Rollback, deserialization and threads repeat the same calls, so those compare
//! bit for bit.

use crate::fmi_common;

use std::sync::Arc;

use beam_impact::record::NullRecorder;
use beam_impact::{Scenario, Simulation};
use fmi_common::importer::{Fmu2, Fmu3, OK};

const PEAKS: [&str; 4] = [
    "peak.lower.tip_deflection",
    "peak.lower.clamp_bending_stress",
    "peak.lower.clamp_shear_stress",
    "peak.upper.contact_bending_stress",
];

fn outputs() -> Vec<u32> {
    beam_impact::fmi::variables::table()
        .iter()
        .filter(|v| v.causality.name() == "output" && v.ty == beam_impact::fmi::variables::Type::Real)
        .map(|v| v.vr)
        .collect()
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn fmi2_call_sequence_reproduces_the_library_run() {
    let lib = fmi_common::importer::load();
    let fmu = Fmu2::new(&lib);
    // fmpy's order: SetupExperiment, start values, Enter/Exit initialization.
    assert_eq!(fmu.setup(0.0, Some(3.0)), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.set("drop_height", 0.567), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    assert_eq!(fmu.get("time"), 0.0);
    assert!(fmu.get("modes.coupled.omega[1]") > 0.0);
    fmu.run(0.0, 3.0, 1e-3);
    assert_eq!(fmu.get("time"), 3.0);

    // The FMU's defaults are the default scenario's: the converged method.
    let mut simulation = Simulation::new(&Scenario::default()).unwrap();
    simulation.advance_to(3_000_000_000, &mut NullRecorder, false).unwrap();
    let peaks = simulation.result().peaks;
    let expected = [
        peaks.lower_tip_deflection,
        peaks.lower_clamp_bending_stress,
        peaks.lower_clamp_shear_stress,
        peaks.upper_contact_bending_stress,
    ];
    for (name, expected) in PEAKS.iter().zip(expected) {
        let got = fmu.get(name);
        assert!(((got - expected) / expected).abs() < 1e-3, "{name}: FMU {got}, library {expected}");
    }
    let method = simulation.energy_method();
    assert_eq!(fmu.get("energy_method.tip_deflection"), method.tip_deflection);
    assert_eq!(fmu.get("modes.lower.omega[2]"), simulation.mode_table(5).lower[1]);

    // Contact changes reach logEvents; every FMI 2 log call used the "%s" format.
    let log = fmu.log.all();
    assert!(log.iter().any(|m| m.category == "logEvents" && m.text.contains("contact starts")), "{}", fmu.log.text());
    assert!(log.iter().any(|m| m.category == "logEvents" && m.text.contains("contact ends")), "{}", fmu.log.text());
    assert!(log.iter().all(|m| m.format == "%s"));

    // The status queries fmpy makes after fmi2Discard.
    let real_status = sym_real_status(&fmu);
    assert_eq!(real_status, (OK, 3.0));
    assert_eq!(sym_boolean_status(&fmu), (OK, 0));
    assert_eq!(fmu.call0("fmi2Terminate"), OK);
}

fn sym_real_status(fmu: &Fmu2) -> (i32, f64) {
    // SAFETY: the signature of fmi2GetRealStatus.
    let f: libloading::Symbol<unsafe extern "C" fn(*mut std::ffi::c_void, i32, *mut f64) -> i32> =
        unsafe { fmu.lib.get(b"fmi2GetRealStatus\0") }.unwrap();
    let mut value = f64::NAN;
    // SAFETY: fmi2LastSuccessfulTime = 2, an out-pointer.
    let status = unsafe { f(fmu.c, 2, &mut value) };
    (status, value)
}

fn sym_boolean_status(fmu: &Fmu2) -> (i32, i32) {
    // SAFETY: the signature of fmi2GetBooleanStatus.
    let f: libloading::Symbol<unsafe extern "C" fn(*mut std::ffi::c_void, i32, *mut i32) -> i32> =
        unsafe { fmu.lib.get(b"fmi2GetBooleanStatus\0") }.unwrap();
    let mut value = -1;
    // SAFETY: fmi2Terminated = 3, an out-pointer.
    let status = unsafe { f(fmu.c, 3, &mut value) };
    (status, value)
}

#[test]
fn start_values_before_setup_experiment_and_no_stop_time_are_accepted() {
    let lib = fmi_common::importer::load();
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.set("damping_ratio", 0.05), OK);
    assert_eq!(fmu.setup(0.0, None), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    assert_eq!(fmu.get("damping_ratio"), 0.05);
    // Steps of 0.009999999999999998 (fmpy's drift) and a step that is not a multiple of anything.
    assert_eq!(fmu.do_step(0.0, 0.009999999999999998), OK, "{}", fmu.log.text());
    assert_eq!(fmu.do_step(0.009999999999999998, 1.0 / 3.0), OK, "{}", fmu.log.text());
    assert!((fmu.get("time") - (0.01 + 1.0 / 3.0)).abs() < 1e-9);
}

#[test]
fn rollback_gives_identical_outputs() {
    let lib = fmi_common::importer::load();
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    fmu.run(0.0, 0.2, 1e-3);
    let state = fmu.get_state();
    assert_eq!(fmu.set("upper.tip_force", -5e4), OK);
    fmu.run(0.2, 0.5, 1e-2);
    let first = fmu.get_reals(&outputs()).1;
    assert_eq!(fmu.set_state(state), OK, "{}", fmu.log.text());
    assert_eq!(fmu.get("time"), 0.2);
    assert_eq!(fmu.get("upper.tip_force"), 0.0, "the inputs are part of the state");
    assert_eq!(fmu.set("upper.tip_force", -5e4), OK);
    fmu.run(0.2, 0.5, 1e-2);
    let second = fmu.get_reals(&outputs()).1;
    assert_eq!(bits(&first), bits(&second));
    assert!(fmu.get("energy.external_work") != 0.0);
    fmu.free_state(state);
}

#[test]
fn serialized_state_continues_identically_in_a_second_instance() {
    let lib = fmi_common::importer::load();
    let first = Fmu2::new(&lib);
    assert_eq!(first.set_string("log.path", ""), OK);
    assert_eq!(first.initialize(), OK);
    first.run(0.0, 0.3, 1e-3);
    let state = first.get_state();
    let bytes = first.serialize(state);
    assert_eq!(&bytes[..8], b"BEAMFMU\0");
    first.free_state(state);

    let second = Fmu2::new(&lib);
    assert_eq!(second.set_string("log.path", ""), OK);
    assert_eq!(second.initialize(), OK);
    let (status, restored) = second.deserialize(&bytes);
    assert_eq!(status, OK, "{}", second.log.text());
    assert_eq!(second.set_state(restored), OK, "{}", second.log.text());
    second.free_state(restored);
    assert_eq!(second.get("time"), 0.3);

    first.run(0.3, 1.0, 1e-3);
    second.run(0.3, 1.0, 1e-3);
    assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&second.get_reals(&outputs()).1));

    // An instance with other parameters restores the state's scenario: the state carries its
    // parameters (issue 8; before, the instance refused it as "another scenario").
    let other = Fmu2::new(&lib);
    assert_eq!(other.set_string("log.path", ""), OK);
    assert_eq!(other.set("drop_height", 0.3), OK);
    assert_eq!(other.initialize(), OK);
    let (status, foreign) = other.deserialize(&bytes);
    assert_eq!(status, OK);
    assert_eq!(other.set_state(foreign), OK, "{}", other.log.text());
    assert_eq!(other.get("drop_height"), 0.567);
    assert_eq!(other.get("time"), 0.3);
    other.free_state(foreign);
    // Damaged bytes are refused.
    let (status, _) = other.deserialize(&bytes[..bytes.len() - 3]);
    assert_eq!(status, 3);
    assert!(other.log.text().contains("payload should be"), "{}", other.log.text());
}

#[test]
fn four_instances_on_four_threads_give_identical_results() {
    let lib = fmi_common::importer::load();
    let run = |lib: Arc<libloading::Library>| {
        let fmu = Fmu2::new(&lib);
        assert_eq!(fmu.set_string("log.path", ""), OK);
        assert_eq!(fmu.initialize(), OK);
        let mut trace = Vec::new();
        let mut t = 0.0;
        for n in 1..=1500 {
            let next = n as f64 * 1e-3;
            assert_eq!(fmu.do_step(t, next - t), OK);
            t = next;
            trace.extend(bits(&fmu.get_reals(&outputs()).1));
        }
        trace
    };
    let handles: Vec<_> = (0..4)
        .map(|_| {
            let lib = lib.clone();
            std::thread::spawn(move || run(lib))
        })
        .collect();
    let traces: Vec<Vec<u64>> = handles.into_iter().map(|h| h.join().unwrap()).collect();
    assert!(traces.iter().all(|t| *t == traces[0]));
    assert_eq!(traces[0], run(lib), "a lone instance gives the same results");
}

#[test]
fn fmi3_returns_early_at_contact_changes() {
    let lib = fmi_common::importer::load();
    let fmu = Fmu3::try_new(&lib, None, true).0.unwrap();
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    let (mut t, mut n, mut early_returns) = (0.0, 0u64, 0);
    while t < 3.0 - 1e-12 {
        let next = (n + 1) as f64 * 1e-2;
        let (status, early, last) = fmu.do_step(t, next - t);
        assert_eq!(status, OK, "{}", fmu.log.text());
        if early {
            assert!(last < next, "early return at {last} before {next}");
            // It returns at the contact change itself: the logged event has that time.
            let event = format!("t = {last:.9} s (step");
            assert!(fmu.log.text().contains(&event), "no event at {last}: {}", fmu.log.text());
            early_returns += 1;
            t = last;
        } else {
            assert!((last - next).abs() < 1e-9, "lastSuccessfulTime {last} for the point {next}");
            t = next;
            n += 1;
        }
    }
    assert!(early_returns >= 2, "contact starts and ends at least once: {early_returns} early returns");
    assert!(fmu.log.text().contains("early return"), "{}", fmu.log.text());
    // The peaks are those of the run without early returns.
    let lone = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(lone.set_string("log.path", ""), OK);
    assert_eq!(lone.initialize(), OK);
    let mut t = 0.0;
    for n in 1..=300 {
        let (status, early, _) = lone.do_step(t, n as f64 * 1e-2 - t);
        assert_eq!((status, early), (OK, false));
        t = n as f64 * 1e-2;
    }
    for name in PEAKS {
        let (a, b) = (fmu.get(name), lone.get(name));
        assert!(((a - b) / b).abs() < 5e-3, "{name}: {a} with early returns, {b} without");
    }
}

/// The stop time is the importer's business, not the scenario's: a state saved by an instance
/// running to 3 s restores in one running to 5 s, or to 1e6 s (the FMU's limit on times since
/// issue 16: beyond it a step of microseconds is lost in the absolute time's rounding).
#[test]
fn a_state_restores_across_different_stop_times() {
    let lib = fmi_common::importer::load();
    let first = Fmu2::new(&lib);
    assert_eq!(first.set_string("log.path", ""), OK);
    assert_eq!(first.initialize(), OK);
    first.run(0.0, 0.2, 1e-2);
    let state = first.get_state();
    let bytes = first.serialize(state);
    first.free_state(state);

    for stop in [5.0, 1e6] {
        let second = Fmu2::new(&lib);
        assert_eq!(second.set_string("log.path", ""), OK);
        assert_eq!(second.setup(0.0, Some(stop)), OK, "{}", second.log.text());
        assert_eq!(second.call0("fmi2EnterInitializationMode"), OK);
        assert_eq!(second.call0("fmi2ExitInitializationMode"), OK, "stop {stop}: {}", second.log.text());
        let (status, restored) = second.deserialize(&bytes);
        assert_eq!(status, OK);
        assert_eq!(second.set_state(restored), OK, "stop {stop}: {}", second.log.text());
        second.free_state(restored);
        assert_eq!(second.get("time"), 0.2);
        second.run(0.2, 0.3, 1e-2);
        if stop == 5.0 {
            first.run(0.2, 0.3, 1e-2);
            assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&second.get_reals(&outputs()).1));
        }
    }
}

/// SetFMUstate with an MCAP log open tells the recorder (Recorder::rollback), and the log stays
/// a complete file.
#[test]
fn rollback_with_an_mcap_log() {
    let lib = fmi_common::importer::load();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rollback.mcap");
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.set_string("log.path", path.to_str().unwrap()), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    fmu.run(0.0, 0.1, 1e-2);
    let state = fmu.get_state();
    fmu.run(0.1, 0.2, 1e-2);
    assert_eq!(fmu.set_state(state), OK, "{}", fmu.log.text());
    fmu.free_state(state);
    assert_eq!(fmu.get("time"), 0.1);
    fmu.run(0.1, 0.2, 1e-2);
    assert_eq!(fmu.call0("fmi2Terminate"), OK, "{}", fmu.log.text());
    let log = beam_impact::replay::report::read_log(&path).unwrap();
    assert!(log.complete, "{:?}", log.problem);
}

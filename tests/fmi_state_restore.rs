//! FMU states restored as importers restore them (issue 8 items 1, 2; issue 9's checksum and
//! validation), through the C API loaded with libloading.
//!
//! - fmpy's `simulate_fmu(fmu, fmu_state=bytes, start_time=...)` and fmusim's
//!   `--initial-fmu-state-file`: instantiate, deserialize, SetFMUState, no initialization calls,
//!   then the getters and DoStep. The state holds the FMI state (parameters, absolute time, the
//!   stepping state), so the fresh instance is in Step Mode and continues the saved run.
//! - Oracle: the instance that saved the state, continuing. Both take the same internal steps
//!   (communication points do not break the step grid), so the outputs agree bit for bit.
//! - A state of another scenario restores that scenario; damaged bytes (every single-bit flip)
//!   and forged contents (a valid checksum over impossible values) are refused with the reason.

use crate::fmi_common;

use beam_impact::fmi::state::Snapshot;
use fmi_common::importer::{load, Fmu2, Fmu3, ERROR, OK};

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

/// An FMI 2 instance without a log, initialized over [start, start + 3] s (stop time set, as
/// fmpy does), run to `save` at 1 ms communication steps; returns it and its serialized state.
fn saved_fmi2(start: f64, save: f64, drop_height: f64) -> (Fmu2, Vec<u8>) {
    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.set("drop_height", drop_height), OK);
    assert_eq!(fmu.setup(start, Some(start + 3.0)), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.call0("fmi2ExitInitializationMode"), OK, "{}", fmu.log.text());
    fmu.run(start, save, 1e-3);
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    fmu.free_state(state);
    (fmu, bytes)
}

/// fmpy's restore flow on a fresh FMI 2 instance: instantiate, deserialize, SetFMUstate, FreeFMUstate.
fn restored_fmi2(bytes: &[u8], log_path: &str) -> (Fmu2, i32) {
    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.set_string("log.path", log_path), OK);
    let (status, state) = fmu.deserialize(bytes);
    assert_eq!(status, OK, "{}", fmu.log.text());
    let status = fmu.set_state(state);
    fmu.free_state(state);
    (fmu, status)
}

/// Item 1 (failed before: "fmi2GetReal is not allowed in state Instantiated"): a state restored
/// into a fresh instance, without any initialization call, is in Step Mode at the saved time with
/// the saved outputs, and continues the run bit for bit.
#[test]
fn fmi2_state_restores_into_a_fresh_instance_without_initialization() {
    let (first, bytes) = saved_fmi2(0.0, 1.5, 0.567);
    let (second, status) = restored_fmi2(&bytes, "");
    assert_eq!(status, OK, "{}", second.log.text());
    assert!(second.log.text().contains("restored a state into Step Mode (t = 1.5 s, step "), "{}", second.log.text());
    assert_eq!(second.get("time"), 1.5);
    assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&second.get_reals(&outputs()).1), "outputs at 1.5 s");
    // fmpy's loop goes on from start_time = 1.5 (communication points 1.5 + n * interval).
    first.run(1.5, 2.7, 1e-3);
    second.run(1.5, 2.7, 1e-3);
    assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&second.get_reals(&outputs()).1), "outputs at 2.7 s");
    assert_eq!(second.call0("fmi2Terminate"), OK);
}

#[test]
fn fmi3_state_restores_into_a_fresh_instance_without_initialization() {
    let lib = load();
    let first = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(first.set_string("log.path", ""), OK);
    assert_eq!(first.initialize_at(0.0, Some(3.0)), OK, "{}", first.log.text());
    first.run(0.0, 1.5, 1e-3);
    let state = first.get_state();
    let bytes = first.serialize(state);
    first.free_state(state);

    let second = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(second.set_string("log.path", ""), OK);
    let (status, restored) = second.deserialize(&bytes);
    assert_eq!(status, OK, "{}", second.log.text());
    assert_eq!(second.set_state(restored), OK, "{}", second.log.text());
    second.free_state(restored);
    assert_eq!(second.get("time"), 1.5);
    assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&second.get_reals(&outputs()).1));
    first.run(1.5, 2.7, 1e-3);
    second.run(1.5, 2.7, 1e-3);
    assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&second.get_reals(&outputs()).1));
    // FMI 2 bytes and FMI 3 bytes are the same format: an FMI 3 state restores in FMI 2.
    let (fmi2, status) = restored_fmi2(&bytes, "");
    assert_eq!(status, OK, "{}", fmi2.log.text());
    assert_eq!(fmi2.get("time"), 1.5);
}

/// Item 2 (failed before: an instance initialized at 0 s restored the state at 1.5 s, a fresh one
/// not at all): a state saved at 11.5 s of a run started at 10 s restores at 11.5 s, into an
/// instance initialized at 0 s and into a fresh one, and continues identically.
#[test]
fn the_state_holds_absolute_time() {
    let (first, bytes) = saved_fmi2(10.0, 11.5, 0.567);
    assert_eq!(first.get("time"), 11.5);
    let initialized = Fmu2::new(&load());
    assert_eq!(initialized.set_string("log.path", ""), OK);
    assert_eq!(initialized.initialize(), OK);
    let (status, state) = initialized.deserialize(&bytes);
    assert_eq!(status, OK);
    assert_eq!(initialized.set_state(state), OK, "{}", initialized.log.text());
    initialized.free_state(state);
    assert_eq!(initialized.get("time"), 11.5);

    let (fresh, status) = restored_fmi2(&bytes, "");
    assert_eq!(status, OK, "{}", fresh.log.text());
    assert_eq!(fresh.get("time"), 11.5);
    first.run(11.5, 12.5, 1e-2);
    fresh.run(11.5, 12.5, 1e-2);
    assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&fresh.get_reals(&outputs()).1));
    // The instance initialized with stop time 3 s keeps it (the stop time is not in the state).
    assert_eq!(initialized.do_step(11.5, 0.01), ERROR);
    assert!(initialized.log.text().contains("after stopTime = 3 s"), "{}", initialized.log.text());
}

/// The state's parameters win (before, an instance of other parameters refused the state: "the
/// state belongs to another scenario"): restored into an instance initialized with another drop
/// height, or into a fresh one, the run is the saved scenario's, parameters included.
#[test]
fn a_state_of_another_scenario_restores_that_scenario() {
    let (first, bytes) = saved_fmi2(0.0, 0.3, 0.8);
    let other = Fmu2::new(&load());
    assert_eq!(other.set_string("log.path", ""), OK);
    assert_eq!(other.set("drop_height", 0.3), OK);
    assert_eq!(other.set("damping_ratio", 0.05), OK);
    assert_eq!(other.initialize(), OK);
    other.run(0.0, 0.1, 1e-2);
    let (status, state) = other.deserialize(&bytes);
    assert_eq!(status, OK);
    assert_eq!(other.set_state(state), OK, "{}", other.log.text());
    other.free_state(state);
    assert_eq!((other.get("drop_height"), other.get("damping_ratio")), (0.8, first.get("damping_ratio")));
    assert_eq!(other.get("time"), 0.3);
    first.run(0.3, 0.6, 1e-3);
    other.run(0.3, 0.6, 1e-3);
    assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&other.get_reals(&outputs()).1));
}

/// A state taken before initialization holds the parameters and step 0: restored into a fresh
/// instance it sets them, and initialization follows as usual.
#[test]
fn a_state_taken_before_initialization_sets_the_parameters_only() {
    let lib = load();
    let first = Fmu2::new(&lib);
    assert_eq!(first.set("drop_height", 0.4), OK);
    let state = first.get_state();
    let bytes = first.serialize(state);
    first.free_state(state);
    let (second, status) = restored_fmi2(&bytes, "");
    assert_eq!(status, OK, "{}", second.log.text());
    let (status, _) = second.get_reals(&[fmi_common::importer::vr("time")]);
    assert_eq!(status, ERROR, "still Instantiated: FMI 2 getters start at initialization");
    assert_eq!(second.initialize(), OK, "{}", second.log.text());
    assert_eq!(second.get("drop_height"), 0.4);
}

/// A state restored into a fresh instance logs to that instance's `log.path`, starting with the
/// restored step; the log is complete after Terminate.
#[test]
fn the_restored_run_logs_from_the_restored_step() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("restored.mcap");
    let (first, bytes) = saved_fmi2(0.0, 0.2, 0.567);
    let (second, status) = restored_fmi2(&bytes, path.to_str().unwrap());
    assert_eq!(status, OK, "{}", second.log.text());
    assert!(second.log.text().contains(&format!("MCAP log of the run: {}", path.display())));
    second.run(0.2, 0.3, 1e-2);
    assert_eq!(second.call0("fmi2Terminate"), OK, "{}", second.log.text());
    let log = beam_impact::replay::report::read_log(&path).unwrap();
    assert!(log.complete, "{:?}", log.problem);
    let first_step = log.steps.first().unwrap();
    assert!(first_step.step > 0 && first_step.time <= 0.2 && first_step.time > 0.19, "{first_step:?}");
    assert!(log.steps.last().unwrap().time >= 0.29);
    drop(first);
}

/// Issue 9: no single-bit corruption of a real state restores. Every bit of a state serialized
/// after 0.3 s (FMI 2) is flipped in turn and handed to fmi2DeSerializeFMUstate (and, should it be
/// accepted, to fmi2SetFMUstate): each is refused with fmi2Error and a logged reason.
#[test]
fn no_single_bit_corruption_of_a_state_restores() {
    let (_first, bytes) = saved_fmi2(0.0, 0.3, 0.567);
    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.set_string("log.path", ""), OK);
    let mut copy = bytes.clone();
    for bit in 0..bytes.len() * 8 {
        copy[bit / 8] ^= 1 << (bit % 8);
        fmu.log.clear();
        let (status, state) = fmu.deserialize(&copy);
        let status = if status == OK {
            let set = fmu.set_state(state);
            fmu.free_state(state);
            set
        } else {
            status
        };
        assert_eq!(status, ERROR, "bit {bit} of {} restored", bytes.len() * 8);
        assert!(fmu.log.text().contains("FMU state: "), "bit {bit}: {}", fmu.log.text());
        copy[bit / 8] ^= 1 << (bit % 8);
    }
    // FMI 3, every 7th bit (the same code path).
    let lib = load();
    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    for bit in (0..bytes.len() * 8).step_by(7) {
        copy[bit / 8] ^= 1 << (bit % 8);
        fmu3.log.clear();
        let (status, _) = fmu3.deserialize(&copy);
        assert_eq!(status, ERROR, "FMI 3: bit {bit} accepted");
        assert!(fmu3.log.text().contains("FMU state: "), "bit {bit}: {}", fmu3.log.text());
        copy[bit / 8] ^= 1 << (bit % 8);
    }
    // The undamaged bytes still restore.
    let (_, status) = restored_fmi2(&bytes, "");
    assert_eq!(status, OK);
}

/// Issue 9: forged contents (a valid checksum over impossible values) are refused by
/// SetFMUState with the field named, and the instance is left as it was.
#[test]
fn forged_states_are_refused_naming_the_field() {
    let (first, bytes) = saved_fmi2(0.0, 0.3, 0.567);
    let good = Snapshot::from_bytes(&bytes).unwrap();
    type Forge = fn(&mut Snapshot);
    let forgeries: [(&str, Forge, &str); 14] = [
        ("a wrapped step counter", |s| s.run.result.step = u64::MAX, "result.step"),
        ("a NaN gap", |s| s.run.gap = f64::NAN, "gap = NaN is not finite"),
        ("an infinite velocity", |s| s.run.kinematics.velocity[3] = f64::INFINITY, "kinematics.velocity[3]"),
        ("a time that is not its nanoseconds", |s| s.run.result.time += 1e-3, "result.time"),
        ("an output far ahead of the step", |s| s.run.output_ns += 1_000_000_000, "output_ns"),
        ("an output before the step", |s| s.run.output_ns = s.run.result.time_ns - 1, "output_ns"),
        ("windows out of order", |s| s.run.contact_windows.reverse(), "contact_windows[1]"),
        ("a window after the run", |s| s.run.contact_windows[0].end = 10.0, "contact_windows[0]"),
        ("a huge tip force", |s| s.run.input_forces.upper = 1e30, "input_forces.upper"),
        // Issue 27: the support-motion inputs' range holds for a restored state too.
        (
            "a clamp rotation beyond the small-angle range",
            |s| s.run.input_motion.clamp_rotation.displacement = 1.5,
            "input_motion.lower.clamp_rotation is out of range",
        ),
        ("too many elements", |s| _ = s.parameters.insert("lower.elements".into(), 1e6), "lower.elements"),
        ("a NaN start time", |s| s.start_time = f64::NAN, "start_time"),
        // Issue 16 item 11: at 1e300 s doStep returned OK without advancing time.
        ("a start time of 1e300 s", |s| s.start_time = 1e300, "start_time = 1e300 s is not within +-1e6 s"),
        (
            "one coordinate too many",
            |s| s.run.kinematics.displacement = s.run.kinematics.displacement.push(0.0),
            "coordinates",
        ),
    ];
    assert!(good.run.contact_windows.len() >= 2, "the forgeries need two contact windows");
    let (fresh, status) = restored_fmi2(&bytes, "");
    assert_eq!(status, OK);
    for (what, forge, reason) in forgeries {
        let mut forged = good.clone();
        forge(&mut forged);
        let forged = forged.to_bytes().unwrap();
        for fmu in [&first, &fresh] {
            fmu.log.clear();
            let (status, state) = fmu.deserialize(&forged);
            assert_eq!(status, OK, "{what}: the checksum is valid, the contents are checked on restore");
            assert_eq!(fmu.set_state(state), ERROR, "{what} restored");
            fmu.free_state(state);
            let log = fmu.log.text();
            assert!(log.contains("fmi2SetFMUstate: ") && log.contains(reason), "{what}: {log}");
        }
    }
    // Both instances are as they were: at 0.3 s, stepping on.
    for fmu in [&first, &fresh] {
        assert_eq!(fmu.get("time"), 0.3);
        fmu.run(0.3, 0.35, 1e-2);
    }
    assert_eq!(bits(&first.get_reals(&outputs()).1), bits(&fresh.get_reals(&outputs()).1));
}

/// A state of another scenario restored while an explicit log is open: that log (which describes
/// the previous scenario) is completed, the run goes on without one, and SetFMUState says so
/// with a warning.
#[test]
fn another_scenario_completes_an_explicit_log_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("explicit.mcap");
    let (_first, bytes) = saved_fmi2(0.0, 0.2, 0.8);
    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.set_string("log.path", path.to_str().unwrap()), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    fmu.run(0.0, 0.1, 1e-2);
    let (status, state) = fmu.deserialize(&bytes);
    assert_eq!(status, OK);
    assert_eq!(fmu.set_state(state), fmi_common::importer::WARNING, "{}", fmu.log.text());
    fmu.free_state(state);
    assert!(
        fmu.log.text().contains("belongs to another scenario: the MCAP log")
            && fmu.log.text().contains("no log from here on"),
        "{}",
        fmu.log.text()
    );
    assert_eq!(fmu.get("drop_height"), 0.8);
    fmu.run(0.2, 0.3, 1e-2);
    assert_eq!(fmu.call0("fmi2Terminate"), OK, "{}", fmu.log.text());
    let log = beam_impact::replay::report::read_log(&path).unwrap();
    assert!(log.complete, "{:?}", log.problem);
    assert!(log.steps.last().unwrap().time < 0.11, "the log ends where its scenario did");
}

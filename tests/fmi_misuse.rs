//! Misuse of the C API: every case returns an error status (or null) with the reason logged,
//! and the host process survives. One test per case of issue 3.

use crate::fmi_common;

use std::ffi::{c_char, c_int, c_void};

use fmi_common::importer::{load, vr, Fmu2, Fmu3, ERROR, OK};

fn fresh() -> Fmu2 {
    let fmu = Fmu2::new(&load());
    assert_eq!(fmu.set_string("log.path", ""), OK);
    fmu
}

#[test]
fn do_step_before_initialization() {
    let fmu = fresh();
    assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
    assert!(fmu.log.text().contains("fmi2DoStep is not allowed in state Instantiated"), "{}", fmu.log.text());
    // The instance is still usable.
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
}

#[test]
fn unknown_value_reference() {
    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.get_reals(&[100_000]).0, ERROR);
    assert!(fmu.log.text().contains("unknown value reference 100000"), "{}", fmu.log.text());
    // A Real getter on the Boolean variable names it.
    assert_eq!(fmu.get_reals(&[vr("contact.active")]).0, ERROR);
    assert!(fmu.log.text().contains("`contact.active`, a Boolean variable, not Real"), "{}", fmu.log.text());
}

#[test]
fn nan_parameter_is_refused_when_set() {
    let fmu = fresh();
    assert_eq!(fmu.set("upper.mass", f64::NAN), ERROR);
    assert!(fmu.log.text().contains("upper.mass must be a finite number, got NaN"), "{}", fmu.log.text());
    assert_eq!(fmu.setup(0.0, None), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.get("upper.mass"), 12_000.0, "the old value is kept");
}

#[test]
fn negative_parameters_are_each_named_at_initialization() {
    let fmu = fresh();
    assert_eq!(fmu.set("upper.length", -3.0), OK);
    assert_eq!(fmu.set("lower.shear_area", -0.1), OK);
    assert_eq!(fmu.initialize(), ERROR);
    let log = fmu.log.text();
    assert!(log.contains("upper.length must be > 0 m, got -3"), "{log}");
    assert!(log.contains("lower.shear_area must be > 0 m^2, got -0.1"), "{log}");
    // The failed ExitInitializationMode left the instance in Error: parameters can no longer be
    // set; Reset brings it back, and with valid parameters it initializes.
    assert_eq!(fmu.set("upper.length", 29.0), ERROR);
    assert!(fmu.log.text().contains("fmi2SetReal is not allowed in state Error"), "{}", fmu.log.text());
    assert_eq!(fmu.get("upper.length"), -3.0, "getters are allowed in Error");
    assert_eq!(fmu.get_reals(&[vr("lower.tip_deflection")]).0, ERROR, "no model to read outputs from");
    assert!(fmu.log.text().contains("the model could not be built"), "{}", fmu.log.text());
    assert_eq!(fmu.call0("fmi2Reset"), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.set("upper.length", 29.0), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
}

#[test]
fn contact_position_beyond_the_upper_beam() {
    let fmu = fresh();
    assert_eq!(fmu.set("contact_position", 35.0), OK);
    assert_eq!(fmu.initialize(), ERROR);
    assert!(
        fmu.log.text().contains("contact_position must be on the upper beam, 0 < d <= upper.length = 29 m, got 35"),
        "{}",
        fmu.log.text()
    );
}

#[test]
fn step_above_the_stability_limit() {
    let fmu = fresh();
    assert_eq!(fmu.set("step_contact", 1e-3), OK);
    assert_eq!(fmu.initialize(), ERROR);
    let log = fmu.log.text();
    assert!(log.contains("step_contact = 1e-3 s is above the stability limit"), "{log}");
}

#[test]
fn a_wrong_integer_is_refused() {
    let fmu = fresh();
    let f: libloading::Symbol<unsafe extern "C" fn(*mut c_void, *const u32, usize, *const c_int) -> c_int> =
        // SAFETY: the signature of fmi2SetInteger.
        unsafe { fmu.lib.get(b"fmi2SetInteger\0") }.unwrap();
    // SAFETY: one value reference and one value.
    assert_eq!(unsafe { f(fmu.c, [vr("lower.elements")].as_ptr(), 1, [-2].as_ptr()) }, ERROR);
    assert!(fmu.log.text().contains("lower.elements must be a whole number >= 0, got -2"), "{}", fmu.log.text());
    // SAFETY: as above (0 is "auto", accepted; 257 is beyond the element limit).
    assert_eq!(unsafe { f(fmu.c, [vr("lower.elements")].as_ptr(), 1, [257].as_ptr()) }, OK);
    assert_eq!(fmu.initialize(), ERROR);
    assert!(
        fmu.log.text().contains("lower.elements must be between 1 and 256, or \"auto\" (0 in the FMU), got 257"),
        "{}",
        fmu.log.text()
    );
}

#[test]
fn null_pointers() {
    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    let get: libloading::Symbol<unsafe extern "C" fn(*mut c_void, *const u32, usize, *mut f64) -> c_int> =
        // SAFETY: the signature of fmi2GetReal.
        unsafe { fmu.lib.get(b"fmi2GetReal\0") }.unwrap();
    // SAFETY: null arrays are what is being tested; the FMU checks them before use.
    assert_eq!(unsafe { get(fmu.c, [1u32].as_ptr(), 1, std::ptr::null_mut()) }, ERROR);
    assert!(fmu.log.text().contains("argument `value` is a null pointer"), "{}", fmu.log.text());
    // SAFETY: as above.
    assert_eq!(unsafe { get(fmu.c, std::ptr::null(), 1, [0.0].as_mut_ptr()) }, ERROR);
    assert!(fmu.log.text().contains("argument `vr` is a null pointer"), "{}", fmu.log.text());
    // Zero-length arrays may be null.
    // SAFETY: as above.
    assert_eq!(unsafe { get(fmu.c, std::ptr::null(), 0, std::ptr::null_mut()) }, OK);
    // A null instance.
    // SAFETY: as above.
    assert_eq!(unsafe { get(std::ptr::null_mut(), [1u32].as_ptr(), 1, [0.0].as_mut_ptr()) }, ERROR);
    let free: libloading::Symbol<unsafe extern "C" fn(*mut c_void)> =
        // SAFETY: the signature of fmi2FreeInstance.
        unsafe { fmu.lib.get(b"fmi2FreeInstance\0") }.unwrap();
    // SAFETY: freeing null is a no-op.
    unsafe { free(std::ptr::null_mut()) };
    // fmi2Instantiate without callbacks.
    let instantiate: libloading::Symbol<
        unsafe extern "C" fn(*const c_char, c_int, *const c_char, *const c_char, *const c_void, c_int, c_int) -> *mut c_void,
    > =
        // SAFETY: the signature of fmi2Instantiate.
        unsafe { fmu.lib.get(b"fmi2Instantiate\0") }.unwrap();
    // SAFETY: null arguments are what is being tested.
    let c = unsafe { instantiate(c"x".as_ptr(), 1, std::ptr::null(), std::ptr::null(), std::ptr::null(), 0, 0) };
    assert!(c.is_null());
    // FMI 3 doStep with null out-arguments.
    let lib = load();
    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu3.set_string("log.path", ""), OK);
    assert_eq!(fmu3.initialize(), OK);
    let step: libloading::Symbol<
        unsafe extern "C" fn(*mut c_void, f64, f64, bool, *mut bool, *mut bool, *mut bool, *mut f64) -> c_int,
    > =
        // SAFETY: the signature of fmi3DoStep.
        unsafe { lib.get(b"fmi3DoStep\0") }.unwrap();
    let mut flag = false;
    // SAFETY: a null out-pointer is what is being tested.
    let status = unsafe { step(fmu3.c, 0.0, 1e-3, true, &mut flag, &mut flag, &mut flag, std::ptr::null_mut()) };
    assert_eq!(status, ERROR);
    assert!(fmu3.log.text().contains("argument `lastSuccessfulTime` is a null pointer"), "{}", fmu3.log.text());
}

#[test]
fn wrong_instantiation_token() {
    let lib = load();
    let (fmu, log) = Fmu2::try_new(&lib, Some("{00000000-0000-0000-0000-000000000000}"), true);
    assert!(fmu.is_none());
    assert!(log.text().contains("does not match this binary's"), "{}", log.text());
    let (fmu, log) = Fmu3::try_new(&lib, Some("wrong"), false);
    assert!(fmu.is_none());
    assert!(log.text().contains("instantiationToken \"wrong\" does not match"), "{}", log.text());
}

#[test]
fn unwritable_log_path() {
    let fmu = Fmu2::new(&load());
    let path = "/nonexistent-directory/sub/BeamImpact.mcap";
    assert_eq!(fmu.set_string("log.path", path), OK);
    assert_eq!(fmu.initialize(), ERROR);
    assert!(fmu.log.text().contains(path), "{}", fmu.log.text());
}

/// Two instances given the same log file: the second one's initialization fails with the path
/// in the log, and the first one's log stays whole.
#[test]
fn two_instances_on_one_log_path() {
    let lib = load();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("shared.mcap");
    let path = path.to_str().unwrap();
    let (a, b) = (Fmu2::new(&lib), Fmu2::new(&lib));
    assert_eq!(a.set_string("log.path", path), OK);
    assert_eq!(b.set_string("log.path", path), OK);
    assert_eq!(a.initialize(), OK, "{}", a.log.text());
    assert_eq!(b.initialize(), ERROR);
    assert!(b.log.text().contains(path) && b.log.text().contains("another run or instance"), "{}", b.log.text());
    assert_eq!(a.do_step(0.0, 1e-2), OK);
    assert_eq!(a.call0("fmi2Terminate"), OK, "{}", a.log.text());
    let log = beam_impact::replay::report::read_log(std::path::Path::new(path)).unwrap();
    assert!(log.complete, "{:?}", log.problem);
}

#[test]
fn calls_after_terminate() {
    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    assert_eq!(fmu.call0("fmi2Terminate"), OK);
    assert_eq!(fmu.do_step(1e-3, 1e-3), ERROR);
    assert!(fmu.log.text().contains("fmi2DoStep is not allowed in state Terminated"), "{}", fmu.log.text());
    assert_eq!(fmu.set("upper.tip_force", 1.0), ERROR);
    assert_eq!(fmu.call0("fmi2Terminate"), ERROR);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), ERROR);
    // Outputs can still be read, and Reset brings the instance back.
    assert!(fmu.get("peak.contact.force") > 0.0);
    assert_eq!(fmu.call0("fmi2Reset"), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.initialize(), OK);
}

#[test]
fn parameters_are_fixed_after_initialization() {
    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.set("drop_height", 1.0), ERROR);
    assert!(
        fmu.log.text().contains(
            "fmi2SetReal: setting `drop_height` (parameter) is not allowed in state Step Mode (illegal call sequence"
        ),
        "{}",
        fmu.log.text()
    );
    // Every Integer and String variable is a parameter: the functions themselves are refused.
    assert_eq!(fmu.set_integer("lower.elements", 7), ERROR);
    assert!(fmu.log.text().contains("fmi2SetInteger is not allowed in state Step Mode"), "{}", fmu.log.text());
    assert_eq!(fmu.set_string("log.path", "x.mcap"), ERROR);
    assert!(fmu.log.text().contains("fmi2SetString is not allowed in state Step Mode"), "{}", fmu.log.text());
    // Inputs are set in step mode; a refused setter did not change the state.
    assert_eq!(fmu.set("upper.tip_force", -1e3), OK, "{}", fmu.log.text());
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    assert_eq!(fmu.set("contact.force", 1.0), ERROR);
    assert!(fmu.log.text().contains("`contact.force` is an output and cannot be set"), "{}", fmu.log.text());
}

/// A failed doStep puts the instance in Error, where doStep is refused until SetFMUstate (or Reset).
fn refused_step(t: f64, h: f64, reason: &str) {
    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    let state = fmu.get_state();
    assert_eq!(fmu.do_step(t, h), ERROR);
    assert!(fmu.log.text().contains(reason), "{reason}: {}", fmu.log.text());
    assert_eq!(fmu.do_step(1e-3, 1e-3), ERROR);
    assert!(fmu.log.text().contains("fmi2DoStep is not allowed in state Error"), "{}", fmu.log.text());
    assert_eq!(fmu.set_state(state), OK, "{}", fmu.log.text());
    fmu.free_state(state);
    assert_eq!(fmu.do_step(1e-3, 1e-3), OK, "back in step mode: {}", fmu.log.text());
}

#[test]
fn a_communication_point_that_is_not_the_fmus_time() {
    refused_step(0.5, 1e-3, "currentCommunicationPoint = 0.5 s is not the FMU's time 0.001 s");
}

#[test]
fn a_step_beyond_the_stop_time() {
    refused_step(1e-3, 3.5, "after stopTime = 3 s");
}

#[test]
fn a_communication_step_size_that_is_not_positive() {
    for h in [0.0, -1e-3, f64::NAN] {
        refused_step(1e-3, h, &format!("the communication step must be finite and > 0 s, got currentCommunicationPoint = 0.001, communicationStepSize = {h}"));
    }
}

/// FMI 2.0 allows fmi2GetReal & co. from initialization mode on; FMI 3.0 in Instantiated, where
/// the parameters have values but outputs and calculated parameters need the model.
#[test]
fn getters_before_initialization() {
    let fmu = fresh();
    assert_eq!(fmu.get_reals(&[vr("drop_height")]).0, ERROR);
    assert!(fmu.log.text().contains("fmi2GetReal is not allowed in state Instantiated"), "{}", fmu.log.text());
    assert_eq!(fmu.setup(0.0, None), OK);
    assert_eq!(fmu.call0("fmi2EnterInitializationMode"), OK);
    assert_eq!(fmu.get("drop_height"), 0.567);
    assert!(fmu.get("modes.coupled.omega[1]") > 0.0, "computed in initialization mode");

    let lib = load();
    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu3.set("drop_height", 0.6), OK);
    assert_eq!(fmu3.get("drop_height"), 0.6, "a parameter's current value");
    assert_eq!(fmu3.get("upper.tip_force"), 0.0);
    for name in ["lower.tip_deflection", "modes.lower.omega[1]", "energy_method.tip_deflection"] {
        let (status, _) = fmu3.try_get(name);
        assert_eq!(status, ERROR, "{name}");
        assert!(
            fmu3.log.text().contains(&format!("fmi3GetFloat64: `{name}` is available after initialization")),
            "{}",
            fmu3.log.text()
        );
    }
    assert_eq!(fmu3.set_string("log.path", ""), OK);
    assert_eq!(fmu3.initialize(), OK, "{}", fmu3.log.text());
    let w = fmu3.get("energy_method.tip_deflection");
    assert!(w.is_finite() && w != 0.0, "{w}");
}

/// In Error (here after a failed doStep) only getters, FMU state, (de)serialization, Reset and
/// FreeInstance are allowed.
#[test]
fn error_state_allows_getters_fmu_state_and_reset_only() {
    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.do_step(0.0, 0.0), ERROR);
    for (status, function) in [
        (fmu.do_step(0.0, 1e-3), "fmi2DoStep"),
        (fmu.set("upper.tip_force", 1.0), "fmi2SetReal"),
        (fmu.call0("fmi2Terminate"), "fmi2Terminate"),
        (fmu.call0("fmi2EnterInitializationMode"), "fmi2EnterInitializationMode"),
    ] {
        assert_eq!(status, ERROR, "{function}");
        assert!(fmu.log.text().contains(&format!("{function} is not allowed in state Error")), "{}", fmu.log.text());
    }
    assert_eq!(fmu.get("time"), 0.0);
    assert!(fmu.get("modes.coupled.omega[1]") > 0.0);
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    let (status, copy) = fmu.deserialize(&bytes);
    assert_eq!(status, OK);
    fmu.free_state(copy);
    fmu.free_state(state);
    assert_eq!(fmu.call0("fmi2Reset"), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
}

/// Get/set FMU state are allowed in every state after instantiation (FMI 2.0 and 3.0).
#[test]
fn fmu_state_in_instantiated_and_terminated() {
    let fmu = fresh();
    let initial = fmu.get_state();
    assert_eq!(fmu.initialize(), OK);
    fmu.run(0.0, 0.1, 1e-2);
    let at_01 = fmu.get_state();
    assert_eq!(fmu.call0("fmi2Terminate"), OK);
    assert_eq!(fmu.set_state(initial), OK, "{}", fmu.log.text());
    assert_eq!(fmu.get("time"), 0.0);
    let terminated = fmu.get_state();
    assert_eq!(fmu.set_state(at_01), OK);
    assert_eq!(fmu.get("time"), 0.1);
    for state in [initial, at_01, terminated] {
        fmu.free_state(state);
    }
}

#[test]
fn unsupported_functions_log_why() {
    let fmu = fresh();
    assert_eq!(fmu.call0("fmi2CancelStep"), ERROR);
    assert!(
        fmu.log.text().contains("fmi2CancelStep (fmi2DoStep never returns fmi2Pending) is not supported"),
        "{}",
        fmu.log.text()
    );
    let lib = load();
    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    let f: libloading::Symbol<unsafe extern "C" fn(*mut c_void, f64) -> c_int> =
        // SAFETY: the signature of fmi3SetTime.
        unsafe { lib.get(b"fmi3SetTime\0") }.unwrap();
    // SAFETY: a live instance.
    assert_eq!(unsafe { f(fmu3.c, 1.0) }, ERROR);
    assert!(fmu3.log.text().contains("fmi3SetTime (model exchange) is not supported"), "{}", fmu3.log.text());
}

/// FMI 3: a failed fmi3ExitInitializationMode is the Error state too; fmi3Reset leaves it.
#[test]
fn fmi3_error_state_after_a_failed_initialization() {
    let lib = load();
    let fmu = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.set("upper.length", -3.0), OK);
    assert_eq!(fmu.initialize(), ERROR);
    assert!(fmu.log.text().contains("upper.length must be > 0 m, got -3"), "{}", fmu.log.text());
    assert_eq!(fmu.set("upper.length", 29.0), ERROR);
    assert!(fmu.log.text().contains("fmi3SetFloat64 is not allowed in state Error"), "{}", fmu.log.text());
    assert_eq!(fmu.get("upper.length"), -3.0);
    assert_eq!(fmu.call0("fmi3Reset"), OK);
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    assert_eq!(fmu.do_step(0.0, 0.0).0, ERROR);
    assert!(fmu.log.text().contains("communicationStepSize = 0"), "{}", fmu.log.text());
}

/// Issue 8 item 5 (failed before: fmi2Error, "argument `FMUstate` is a null pointer"): freeing a
/// null state, or through a pointer to a null state, is ignored with OK, as FMI 2.0 and 3.0 say.
#[test]
fn free_of_a_null_state_is_ignored() {
    let fmu = fresh();
    type Free = unsafe extern "C" fn(*mut c_void, *mut *mut c_void) -> c_int;
    let free2: libloading::Symbol<Free> =
        // SAFETY: the signature of fmi2FreeFMUstate.
        unsafe { fmu.lib.get(b"fmi2FreeFMUstate\0") }.unwrap();
    let mut null_state: *mut c_void = std::ptr::null_mut();
    // SAFETY: null pointers are what is being tested; the FMU ignores them.
    assert_eq!(unsafe { free2(fmu.c, std::ptr::null_mut()) }, OK, "{}", fmu.log.text());
    // SAFETY: as above.
    assert_eq!(unsafe { free2(fmu.c, &mut null_state) }, OK, "{}", fmu.log.text());
    assert!(null_state.is_null());
    let lib = load();
    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    let free3: libloading::Symbol<Free> =
        // SAFETY: the signature of fmi3FreeFMUState.
        unsafe { lib.get(b"fmi3FreeFMUState\0") }.unwrap();
    // SAFETY: as above.
    assert_eq!(unsafe { free3(fmu3.c, std::ptr::null_mut()) }, OK, "{}", fmu3.log.text());
    // SAFETY: as above.
    assert_eq!(unsafe { free3(fmu3.c, &mut null_state) }, OK, "{}", fmu3.log.text());
    assert!(fmu.log.all().iter().chain(fmu3.log.all().iter()).all(|m| m.status == OK), "nothing but OK logged");
}

/// Issue 9: the tip-force bound |F| <= 1e9 N holds in every state (before, 1e30 N in Step mode
/// was accepted and the next step reported a 6e21 m deflection); a non-UTF-8 `log.path` is
/// refused, never rewritten to U+FFFD characters.
#[test]
fn input_bound_in_step_mode_and_non_utf8_paths_are_errors() {
    let fmu = fresh();
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    assert_eq!(fmu.do_step(0.0, 0.01), OK);
    assert_eq!(fmu.set("upper.tip_force", 1e30), ERROR);
    assert!(
        fmu.log.text().contains("upper.tip_force must be finite with |F| <= 1e9 N, got 1e30"),
        "{}",
        fmu.log.text()
    );
    assert_eq!(fmu.set("lower.tip_force", -2e5), OK, "a sane force is still accepted");
    let bad = std::ffi::CString::new(vec![0xff, 0xfe, b'x']).unwrap();
    let other = fresh();
    let f: libloading::Symbol<unsafe extern "C" fn(*mut c_void, *const u32, usize, *const *const c_char) -> c_int> =
        // SAFETY: the signature of fmi2SetString.
        unsafe { other.lib.get(b"fmi2SetString\0") }.unwrap();
    // SAFETY: one value reference and one NUL-terminated string.
    let status = unsafe { f(other.c, [vr("log.path")].as_ptr(), 1, [bad.as_ptr()].as_ptr()) };
    assert_eq!(status, ERROR);
    assert!(other.log.text().contains("not valid UTF-8"), "{}", other.log.text());
}

/// Issue 16 item 11: start and stop times beyond 1e6 s (where a step of microseconds is lost in
/// the absolute time's rounding) are refused when the experiment is set up, naming the limit.
#[test]
fn absurd_experiment_times_are_refused() {
    let lib = load();
    for (start, stop) in [(1e300, None), (-2e6, None), (0.0, Some(1e7)), (f64::NAN, None)] {
        let fmu = Fmu2::new(&lib);
        assert_eq!(fmu.setup(start, stop), ERROR, "start {start}, stop {stop:?}");
        assert!(fmu.log.text().contains("1e6 s"), "{}", fmu.log.text());
    }
    let fmu = Fmu2::new(&lib);
    assert_eq!(fmu.setup(-1e6, Some(1e6)), OK, "the limits themselves are accepted");
}

/// The longest run of digits in `text`.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit()).map(str::len).max().unwrap_or(0)
}

/// Issue 27 item 8: no logged message carries hundreds of digits (before: a bad tip force was
/// printed as a 301-digit number, `{}` of 1e300). A tip force of 1e300 N set in FMI 2 and FMI 3,
/// a forged state holding one, a parameter of 1e300 at initialization and a communication point
/// of 1e300 s are each refused with a short message that writes the value as 1e300.
#[test]
fn huge_numbers_in_error_messages_are_short() {
    use beam_impact::fmi::logger::MAX_MESSAGE_DIGITS;
    let short = |text: &str, what: &str| {
        let errors: Vec<&str> = text.lines().filter(|l| l.starts_with("[logStatusError]")).collect();
        assert!(!errors.is_empty(), "{what}: nothing logged");
        for line in errors {
            assert!(line.contains("1e300"), "{what}: {line}");
            assert!(longest_digit_run(line) <= MAX_MESSAGE_DIGITS, "{what}: {line}");
            assert!(line.len() < 400, "{what}: {} characters: {line}", line.len());
        }
    };
    let lib = load();
    let fmu = fresh();
    assert_eq!(fmu.set("upper.tip_force", 1e300), ERROR);
    short(&fmu.log.text(), "FMI 2 tip force");
    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu3.set("lower.tip_force", -1e300), ERROR);
    short(&fmu3.log.text(), "FMI 3 tip force");

    let fmu = fresh();
    assert_eq!(fmu.set("upper.mass", 1e300), OK);
    assert_eq!(fmu.initialize(), ERROR);
    short(&fmu.log.text(), "a parameter of 1e300");

    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.do_step(1e300, 1e-3), ERROR);
    short(&fmu.log.text(), "a communication point of 1e300 s");

    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    assert_eq!(fmu.do_step(0.0, 1e-2), OK);
    let state = fmu.get_state();
    let mut snapshot = beam_impact::fmi::state::Snapshot::from_bytes(&fmu.serialize(state)).unwrap();
    fmu.free_state(state);
    snapshot.run.input_forces.upper = 1e300;
    let (status, forged) = fmu.deserialize(&snapshot.to_bytes().unwrap());
    assert_eq!(status, OK);
    fmu.log.clear();
    assert_eq!(fmu.set_state(forged), ERROR);
    fmu.free_state(forged);
    short(&fmu.log.text(), "a forged state's tip force");
}

/// Issue 40 (part 5) item 7: a setter called where it is not allowed was refused as
/// "fmi2SetInteger is not allowed in state Step Mode", naming no variable: an importer's log did
/// not say which of its settings was lost. Now the refusal names the variable (its name and value
/// reference) and the value, in FMI 2 and FMI 3, for each setter.
#[test]
fn a_refused_setter_names_the_variable_and_the_value() {
    let fmu = fresh();
    assert_eq!(fmu.initialize(), OK);
    let before = fmu.get_integer("lower.elements");
    let elements = vr("lower.elements");
    assert_eq!(fmu.set_integer("lower.elements", 7), ERROR);
    let log = fmu.log.text();
    let line = log.lines().find(|l| l.contains("fmi2SetInteger is not allowed in state Step Mode")).unwrap();
    assert!(line.contains(&format!("`lower.elements` (value reference {elements}) = 7")), "{log}");
    assert_eq!(fmu.set_string("log.path", "x.mcap"), ERROR);
    let log = fmu.log.text();
    let line = log.lines().find(|l| l.contains("fmi2SetString is not allowed in state Step Mode")).unwrap();
    assert!(line.contains(&format!("`log.path` (value reference {}) = \"x.mcap\"", vr("log.path"))), "{log}");
    // A per-variable refusal names the value reference and the value too.
    assert_eq!(fmu.set("drop_height", 1.0), ERROR);
    let log = fmu.log.text();
    let refused = format!(
        "illegal call sequence: parameters are fixed at ExitInitializationMode): value reference {} = 1 is not set",
        vr("drop_height")
    );
    assert!(log.contains(&refused), "{log}");
    // Refused, the value is not set.
    assert_eq!(fmu.get_integer("lower.elements"), before);

    let lib = load();
    let fmu3 = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu3.set_string("log.path", ""), OK);
    assert_eq!(fmu3.initialize(), OK, "{}", fmu3.log.text());
    assert_eq!(fmu3.set_integer("upper.elements_to_contact", 9), ERROR);
    let log = fmu3.log.text();
    let line = log.lines().find(|l| l.contains("fmi3SetInt32 is not allowed in state Step Mode")).unwrap();
    let named = format!("`upper.elements_to_contact` (value reference {}) = 9", vr("upper.elements_to_contact"));
    assert!(line.contains(&named), "{log}");
}

/// Issue 40 item 3: the FMU's own step limit, `solver.max_steps` (an Integer parameter, 1 to
/// 2^31 - 1, start 1e8: the CLI's), is enforced inside doStep: a run that reaches it stops there
/// with fmi2Error and the reason in the importer's log (before, only a built-in 1e8 held, and
/// the 1e13 N/m contact's doStep to 0.8 s took 318 s). 0 is refused naming the variable; FMI 3
/// alike.
#[test]
fn a_do_step_stops_at_solver_max_steps_with_the_reason_logged() {
    let fmu = fresh();
    assert_eq!(fmu.set_integer("solver.max_steps", 0), ERROR);
    let log = fmu.log.text();
    assert!(log.contains("solver.max_steps must be a whole number >= 1 (internal steps), got 0"), "{log}");
    assert_eq!(fmu.set_integer("solver.max_steps", 50), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    assert_eq!(fmu.get_integer("solver.max_steps"), 50);
    // 0.5 ms: some 21 steps of the plan's 2.36e-5 s, within the limit.
    assert_eq!(fmu.do_step(0.0, 5e-4), OK, "{}", fmu.log.text());
    assert_eq!(fmu.do_step(5e-4, 0.3), ERROR);
    let log = fmu.log.text();
    assert!(log.contains("max_steps = 50 internal steps reached at t = "), "{log}");
    assert!(log.contains("solver.max_steps"), "{log}");

    let lib = load();
    let fmu = Fmu3::try_new(&lib, None, false).0.unwrap();
    assert_eq!(fmu.set_string("log.path", ""), OK);
    assert_eq!(fmu.set_integer("solver.max_steps", -1), ERROR);
    assert!(fmu.log.text().contains("solver.max_steps must be a whole number >= 1"), "{}", fmu.log.text());
    assert_eq!(fmu.set_integer("solver.max_steps", 50), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    assert_eq!(fmu.do_step(0.0, 0.3).0, ERROR);
    assert!(fmu.log.text().contains("max_steps = 50 internal steps reached"), "{}", fmu.log.text());
}

/// Issue 40: `solver.max_steps` through fmi2SetInteger on every edge of an Int32 and seeded
/// random ones (`BEAM_IMPACT_FUZZ_ITERATIONS` sets how many): accepted from 1 up, anything else
/// refused with fmi2Error and one line naming the variable and the value, never a panic; the
/// last accepted value is the one the run takes.
#[test]
fn solver_max_steps_takes_any_whole_number_from_one_and_refuses_the_rest_in_one_line() {
    let fmu = fresh();
    let mut values = vec![i32::MIN, -1, 0, 1, 2, 100_000_000, i32::MAX - 1, i32::MAX];
    let mut rng = crate::fuzz_support::Rng(40);
    values.extend((0..crate::fuzz_support::iterations(2_000)).map(|_| rng.next_u64() as u32 as i32));
    let mut last = 100_000_000;
    for value in values {
        fmu.log.clear();
        let status = fmu.set_integer("solver.max_steps", value);
        if value >= 1 {
            assert_eq!(status, OK, "{value}: {}", fmu.log.text());
            last = value;
        } else {
            assert_eq!(status, ERROR, "{value}");
            let log = fmu.log.text();
            let line = log.lines().find(|l| l.contains("solver.max_steps")).unwrap_or_else(|| panic!("{log}"));
            assert!(line.ends_with(&format!("must be a whole number >= 1 (internal steps), got {value}")), "{line}");
        }
    }
    assert_eq!(fmu.set_integer("solver.max_steps", last), OK);
    assert_eq!(fmu.initialize(), OK, "{}", fmu.log.text());
    assert_eq!(fmu.get_integer("solver.max_steps"), last);
}

//! The FMI 3.0 API: all 75 functions (fmpy looks every one up). Co-simulation is supported,
//! with event mode (nothing happens in it) and early return at contact changes; model exchange,
//! scheduled execution, clocks, binaries, derivatives and configuration mode exist, log why they
//! are not supported, and return `fmi3Error`.

#![allow(clippy::missing_safety_doc)] // The safety contract is the FMI 3.0 standard.

use std::ffi::{c_char, c_int, c_void};

use super::boundary::{out, slice, slice_mut, string, utf8_string};
use super::instance::{Instance, Shown, Version};
pub use super::logger::Fmi3LogMessageCallback;
use super::logger::{log_with, Logger};
use super::resource;
use super::slots;
use super::state::Snapshot;
use super::status::{allowed, Mask, Status};
use crate::ffi_boundary;

/// `fmi3Instance`: the opaque instance handle.
pub type Fmi3Instance = *mut Instance;
/// `fmi3FMUState`: an opaque saved state.
pub type Fmi3FmuState = *mut Snapshot;
/// `fmi3ValueReference`.
pub type Fmi3ValueReference = u32;

/// `fmi3IntermediateUpdateCallback` (accepted, not called: providesIntermediateUpdate is false).
pub type Fmi3IntermediateUpdateCallback = Option<
    unsafe extern "C" fn(
        instance_environment: *mut c_void,
        intermediate_update_time: f64,
        intermediate_variable_set_requested: bool,
        intermediate_variable_get_allowed: bool,
        intermediate_step_finished: bool,
        can_return_early: bool,
        early_return_requested: *mut bool,
        early_return_time: *mut f64,
    ),
>;

/// `fmi3ClockUpdateCallback` (scheduled execution, not supported).
pub type Fmi3ClockUpdateCallback = Option<unsafe extern "C" fn(instance_environment: *mut c_void)>;
/// `fmi3LockPreemptionCallback` (scheduled execution, not supported).
pub type Fmi3LockPreemptionCallback = Option<unsafe extern "C" fn()>;
/// `fmi3UnlockPreemptionCallback` (scheduled execution, not supported).
pub type Fmi3UnlockPreemptionCallback = Option<unsafe extern "C" fn()>;

fn with(
    c: Fmi3Instance,
    function: &str,
    mask: Mask,
    work: impl FnOnce(&mut Instance) -> Result<Status, String>,
) -> Status {
    // SAFETY: a non-null instance is the pointer fmi3InstantiateCoSimulation returned, used by
    // one thread at a time (FMI 3.0, section 2.2.1).
    match unsafe { c.as_mut() } {
        Some(instance) => instance.guard(function, mask, work),
        None => Status::Error,
    }
}

/// [`with`] for a setter: a call in a state where it is not allowed names what it was to set,
/// `refused` ([`Instance::guard_set`]).
fn with_set(
    c: Fmi3Instance,
    function: &str,
    mask: Mask,
    refused: impl FnOnce(&Instance) -> String,
    work: impl FnOnce(&mut Instance) -> Result<Status, String>,
) -> Status {
    // SAFETY: as in `with`.
    match unsafe { c.as_mut() } {
        Some(instance) => instance.guard_set(function, mask, refused, work),
        None => Status::Error,
    }
}

/// [`with`] for the calls after which an error is the Error state (DoStep, Terminate,
/// ExitInitializationMode).
fn with_run(
    c: Fmi3Instance,
    function: &str,
    mask: Mask,
    work: impl FnOnce(&mut Instance) -> Result<Status, String>,
) -> Status {
    // SAFETY: as in `with`.
    match unsafe { c.as_mut() } {
        Some(instance) => instance.guard_run(function, mask, work),
        None => Status::Error,
    }
}

fn unsupported(c: Fmi3Instance, what: &str) -> Status {
    with(c, what, Mask::NONE, |_| Ok(Status::Error))
}

fn e(err: impl ToString) -> String {
    err.to_string()
}

/// `fmi3GetVersion`: "3.0".
#[no_mangle]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    ffi_boundary! { c"3.0".as_ptr() }
}

/// `fmi3SetDebugLogging`: an empty category list switches every category.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    instance: Fmi3Instance,
    logging_on: bool,
    n_categories: usize,
    categories: *const *const c_char,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3SetDebugLogging", allowed::SET_DEBUG_LOGGING, |inst| {
            let pointers = unsafe { slice(categories, n_categories, "categories") }.map_err(e)?;
            let names = pointers
                .iter()
                .map(|&p| unsafe { string(p, "categories[i]") }.map_err(e))
                .collect::<Result<Vec<_>, _>>()?;
            inst.set_debug_logging(logging_on, &names)
        })
    }
}

fn refuse_instantiation(
    instance_name: *const c_char,
    instance_environment: *mut c_void,
    log_message: Fmi3LogMessageCallback,
    message: &str,
) -> Fmi3Instance {
    let logger = Logger::Fmi3 { callback: log_message, environment: instance_environment };
    let name = unsafe { string(instance_name, "instanceName") }.unwrap_or_default();
    log_with(logger, &name, Status::Error, "logStatusError", message);
    std::ptr::null_mut()
}

/// `fmi3InstantiateModelExchange`: not supported (co-simulation only); logs why, returns null.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    instance_name: *const c_char,
    _instantiation_token: *const c_char,
    _resource_path: *const c_char,
    _visible: bool,
    _logging_on: bool,
    instance_environment: *mut c_void,
    log_message: Fmi3LogMessageCallback,
) -> Fmi3Instance {
    ffi_boundary! {
        refuse_instantiation(instance_name, instance_environment, log_message,
            "fmi3InstantiateModelExchange: this FMU supports co-simulation only")
    }
}

/// `fmi3InstantiateCoSimulation`: checks the instantiation token against this binary's.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instance_name: *const c_char,
    instantiation_token: *const c_char,
    resource_path: *const c_char,
    _visible: bool,
    logging_on: bool,
    event_mode_used: bool,
    early_return_allowed: bool,
    _required_intermediate_variables: *const Fmi3ValueReference,
    _n_required_intermediate_variables: usize,
    instance_environment: *mut c_void,
    log_message: Fmi3LogMessageCallback,
    _intermediate_update: Fmi3IntermediateUpdateCallback,
) -> Fmi3Instance {
    ffi_boundary! {
        let refuse = |message: &str| {
            refuse_instantiation(instance_name, instance_environment, log_message,
                &format!("fmi3InstantiateCoSimulation: {message}"))
        };
        let name = match unsafe { string(instance_name, "instanceName") } {
            Ok(n) => n,
            Err(err) => return refuse(&err.to_string()),
        };
        let token = match unsafe { string(instantiation_token, "instantiationToken") } {
            Ok(t) => t,
            Err(err) => return refuse(&err.to_string()),
        };
        let location = unsafe { string(resource_path, "resourcePath") }.ok();
        let resources = location.as_deref().and_then(resource::parse_path);
        // The starting scenario packed into the resources (issue 30), which the token covers.
        let packed = match resources.as_deref().map(resource::read_scenario).transpose() {
            Ok(packed) => packed.flatten(),
            Err(message) => return refuse(&message),
        };
        if let Err(message) = resource::check_token("instantiationToken", &token, packed.as_ref()) {
            return refuse(&message);
        }
        let logger = Logger::Fmi3 { callback: log_message, environment: instance_environment };
        let mut instance = Instance::starting_from(&name, Version::Fmi3, logger, logging_on, packed);
        instance.set_cosimulation_options(event_mode_used, early_return_allowed);
        instance.log_resources(location.as_deref(), resources);
        Box::into_raw(Box::new(instance))
    }
}

/// `fmi3InstantiateScheduledExecution`: not supported; logs why, returns null.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    instance_name: *const c_char,
    _instantiation_token: *const c_char,
    _resource_path: *const c_char,
    _visible: bool,
    _logging_on: bool,
    instance_environment: *mut c_void,
    log_message: Fmi3LogMessageCallback,
    _clock_update: Fmi3ClockUpdateCallback,
    _lock_preemption: Fmi3LockPreemptionCallback,
    _unlock_preemption: Fmi3UnlockPreemptionCallback,
) -> Fmi3Instance {
    ffi_boundary! {
        refuse_instantiation(instance_name, instance_environment, log_message,
            "fmi3InstantiateScheduledExecution: this FMU supports co-simulation only")
    }
}

/// `fmi3FreeInstance`: completes the MCAP log if not terminated, then frees the instance.
#[no_mangle]
pub unsafe extern "C" fn fmi3FreeInstance(instance: Fmi3Instance) {
    ffi_boundary! {
        if !instance.is_null() {
            // SAFETY: from Box::into_raw in fmi3InstantiateCoSimulation, freed once.
            let mut instance = unsafe { Box::from_raw(instance) };
            instance.free();
        }
    }
}

/// `fmi3EnterInitializationMode`.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    instance: Fmi3Instance,
    _tolerance_defined: bool,
    _tolerance: f64,
    start_time: f64,
    stop_time_defined: bool,
    stop_time: f64,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3EnterInitializationMode", allowed::ENTER_INITIALIZATION, |inst| {
            inst.setup_experiment(start_time, stop_time_defined.then_some(stop_time))?;
            inst.enter_initialization()
        })
    }
}

/// `fmi3ExitInitializationMode`: validates the parameters, builds the model, opens the log.
#[no_mangle]
pub unsafe extern "C" fn fmi3ExitInitializationMode(instance: Fmi3Instance) -> Status {
    ffi_boundary! { with_run(instance, "fmi3ExitInitializationMode", allowed::EXIT_INITIALIZATION, Instance::exit_initialization) }
}

/// `fmi3EnterEventMode` (with eventModeUsed; there are no events to handle).
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterEventMode(instance: Fmi3Instance) -> Status {
    ffi_boundary! { with(instance, "fmi3EnterEventMode", allowed::ENTER_EVENT_MODE, Instance::enter_event_mode) }
}

/// `fmi3Terminate`: completes the MCAP log.
#[no_mangle]
pub unsafe extern "C" fn fmi3Terminate(instance: Fmi3Instance) -> Status {
    ffi_boundary! { with_run(instance, "fmi3Terminate", allowed::TERMINATE, Instance::terminate) }
}

/// `fmi3Reset`.
#[no_mangle]
pub unsafe extern "C" fn fmi3Reset(instance: Fmi3Instance) -> Status {
    ffi_boundary! { with(instance, "fmi3Reset", allowed::RESET, Instance::reset) }
}

fn check_counts(nvr: usize, n_values: usize) -> Result<(), String> {
    if nvr != n_values {
        Err(format!("nValues = {n_values} differs from nValueReferences = {nvr} (every variable is a scalar)"))
    } else {
        Ok(())
    }
}

macro_rules! getter {
    ($i:expr, $function:literal, $vr:expr, $nvr:expr, $values:expr, $nv:expr, $get:ident, $convert:expr) => {
        with($i, $function, allowed::FMI3_GET, |inst| {
            check_counts($nvr, $nv)?;
            let vrs = unsafe { slice($vr, $nvr, "valueReferences") }.map_err(e)?;
            let values = unsafe { slice_mut($values, $nvr, "values") }.map_err(e)?;
            for (value, &vr) in values.iter_mut().zip(vrs) {
                *value = $convert(inst.$get(vr)?);
            }
            Ok(Status::Ok)
        })
    };
}

macro_rules! setter {
    ($i:expr, $function:literal, $mask:expr, $vr:expr, $nvr:expr, $values:expr, $nv:expr, $set:ident, $convert:expr) => {
        with_set($i, $function, $mask, |inst: &Instance| {
            // Read only to name what a call in the wrong state was to set (issue 40).
            let vrs = unsafe { slice($vr, $nvr, "valueReferences") }.unwrap_or(&[]);
            let first = unsafe { slice($values, $nvr.min($nv), "values") }.ok().and_then(|v| v.first().copied());
            inst.to_be_set(vrs, first.map(|v| $convert(v).map_or_else(|e| e, |x| Shown::shown(&x))))
        }, |inst| {
            check_counts($nvr, $nv)?;
            let vrs = unsafe { slice($vr, $nvr, "valueReferences") }.map_err(e)?;
            let values = unsafe { slice($values, $nvr, "values") }.map_err(e)?;
            for (&value, &vr) in values.iter().zip(vrs) {
                inst.$set(vr, $convert(value)?)?;
            }
            Ok(Status::Ok)
        })
    };
}

/// A get or set of a type this FMU has no variables of: nValueReferences = 0 is fine, any value
/// reference is an error naming the type.
fn absent(
    instance: Fmi3Instance,
    function: &str,
    mask: Mask,
    type_name: &str,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
) -> Status {
    with(instance, function, mask, |inst| {
        let vrs = unsafe { slice(value_references, n_value_references, "valueReferences") }.map_err(e)?;
        inst.no_variables_of(type_name, vrs)
    })
}

/// `fmi3GetFloat32`: this FMU has no Float32 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetFloat32(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut f32,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3GetFloat32", allowed::FMI3_GET, "Float32", value_references, n_value_references) }
}

/// `fmi3SetFloat32`: this FMU has no Float32 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetFloat32(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const f32,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3SetFloat32", allowed::SET_ABSENT, "Float32", value_references, n_value_references) }
}

/// `fmi3GetInt8`: this FMU has no Int8 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt8(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut i8,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3GetInt8", allowed::FMI3_GET, "Int8", value_references, n_value_references) }
}

/// `fmi3SetInt8`: this FMU has no Int8 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt8(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const i8,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3SetInt8", allowed::SET_ABSENT, "Int8", value_references, n_value_references) }
}

/// `fmi3GetUInt8`: this FMU has no UInt8 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt8(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut u8,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3GetUInt8", allowed::FMI3_GET, "UInt8", value_references, n_value_references) }
}

/// `fmi3SetUInt8`: this FMU has no UInt8 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt8(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const u8,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3SetUInt8", allowed::SET_ABSENT, "UInt8", value_references, n_value_references) }
}

/// `fmi3GetInt16`: this FMU has no Int16 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt16(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut i16,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3GetInt16", allowed::FMI3_GET, "Int16", value_references, n_value_references) }
}

/// `fmi3SetInt16`: this FMU has no Int16 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt16(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const i16,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3SetInt16", allowed::SET_ABSENT, "Int16", value_references, n_value_references) }
}

/// `fmi3GetUInt16`: this FMU has no UInt16 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt16(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut u16,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3GetUInt16", allowed::FMI3_GET, "UInt16", value_references, n_value_references) }
}

/// `fmi3SetUInt16`: this FMU has no UInt16 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt16(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const u16,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3SetUInt16", allowed::SET_ABSENT, "UInt16", value_references, n_value_references) }
}

/// `fmi3GetUInt32`: this FMU has no UInt32 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt32(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut u32,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3GetUInt32", allowed::FMI3_GET, "UInt32", value_references, n_value_references) }
}

/// `fmi3SetUInt32`: this FMU has no UInt32 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt32(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const u32,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3SetUInt32", allowed::SET_ABSENT, "UInt32", value_references, n_value_references) }
}

/// `fmi3GetInt64`: this FMU has no Int64 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt64(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut i64,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3GetInt64", allowed::FMI3_GET, "Int64", value_references, n_value_references) }
}

/// `fmi3SetInt64`: this FMU has no Int64 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt64(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const i64,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3SetInt64", allowed::SET_ABSENT, "Int64", value_references, n_value_references) }
}

/// `fmi3GetUInt64`: this FMU has no UInt64 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt64(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut u64,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3GetUInt64", allowed::FMI3_GET, "UInt64", value_references, n_value_references) }
}

/// `fmi3SetUInt64`: this FMU has no UInt64 variables (nValueReferences = 0 is fine).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt64(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const u64,
    _n_values: usize,
) -> Status {
    ffi_boundary! { absent(instance, "fmi3SetUInt64", allowed::SET_ABSENT, "UInt64", value_references, n_value_references) }
}

/// `fmi3GetFloat64`.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetFloat64(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    values: *mut f64,
    n_values: usize,
) -> Status {
    ffi_boundary! {
        getter!(instance, "fmi3GetFloat64", value_references, n_value_references, values, n_values, get_real, |x: f64| x)
    }
}

/// `fmi3SetFloat64`: parameters before ExitInitializationMode, inputs until Terminate.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetFloat64(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    values: *const f64,
    n_values: usize,
) -> Status {
    ffi_boundary! {
        setter!(instance, "fmi3SetFloat64", allowed::SET_REAL, value_references, n_value_references, values, n_values, set_real,
            |x: f64| Ok::<f64, String>(x))
    }
}

/// `fmi3GetInt32`: the element counts.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt32(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    values: *mut i32,
    n_values: usize,
) -> Status {
    ffi_boundary! {
        getter!(instance, "fmi3GetInt32", value_references, n_value_references, values, n_values, get_integer, |x: i32| x)
    }
}

/// `fmi3SetInt32`: the element counts.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt32(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    values: *const i32,
    n_values: usize,
) -> Status {
    ffi_boundary! {
        setter!(instance, "fmi3SetInt32", allowed::SET_INTEGER, value_references, n_value_references, values, n_values, set_integer,
            |x: i32| Ok::<i32, String>(x))
    }
}

/// `fmi3GetBoolean`: `contact.active`.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetBoolean(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    values: *mut bool,
    n_values: usize,
) -> Status {
    ffi_boundary! {
        getter!(instance, "fmi3GetBoolean", value_references, n_value_references, values, n_values, get_boolean, |x: bool| x)
    }
}

/// `fmi3SetBoolean`: there is no settable Boolean.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetBoolean(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    values: *const bool,
    n_values: usize,
) -> Status {
    ffi_boundary! {
        setter!(instance, "fmi3SetBoolean", allowed::SET_BOOLEAN, value_references, n_value_references, values, n_values, set_boolean,
            |x: bool| Ok::<bool, String>(x))
    }
}

/// `fmi3GetString`: the strings stay valid until the next `fmi3GetString` on this instance.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetString(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    values: *mut *const c_char,
    n_values: usize,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3GetString", allowed::FMI3_GET, |inst| {
            check_counts(n_value_references, n_values)?;
            let vrs = unsafe { slice(value_references, n_value_references, "valueReferences") }.map_err(e)?;
            let values = unsafe { slice_mut(values, n_value_references, "values") }.map_err(e)?;
            let strings = inst.get_strings(vrs)?;
            values.copy_from_slice(&strings);
            Ok(Status::Ok)
        })
    }
}

/// `fmi3SetString`: `log.path`, `log.channels`.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetString(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    values: *const *const c_char,
    n_values: usize,
) -> Status {
    ffi_boundary! {
        setter!(instance, "fmi3SetString", allowed::SET_STRING, value_references, n_value_references, values, n_values, set_string,
            |p: *const c_char| unsafe { utf8_string(p, "values[i]") })
    }
}

/// `fmi3GetBinary`: this FMU has no Binary variables.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetBinary(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _value_sizes: *mut usize,
    _values: *mut *const u8,
    _n_values: usize,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3GetBinary", allowed::FMI3_GET, |inst| {
            let vrs = unsafe { slice(value_references, n_value_references, "valueReferences") }.map_err(e)?;
            inst.no_variables_of("Binary", vrs)
        })
    }
}

/// `fmi3SetBinary`: this FMU has no Binary variables.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetBinary(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _value_sizes: *const usize,
    _values: *const *const u8,
    _n_values: usize,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3SetBinary", allowed::SET_ABSENT, |inst| {
            let vrs = unsafe { slice(value_references, n_value_references, "valueReferences") }.map_err(e)?;
            inst.no_variables_of("Binary", vrs)
        })
    }
}

/// `fmi3GetClock`: this FMU has no clocks.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetClock(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *mut bool,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3GetClock", allowed::FMI3_GET, |inst| {
            let vrs = unsafe { slice(value_references, n_value_references, "valueReferences") }.map_err(e)?;
            inst.no_variables_of("Clock", vrs)
        })
    }
}

/// `fmi3SetClock`: this FMU has no clocks.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetClock(
    instance: Fmi3Instance,
    value_references: *const Fmi3ValueReference,
    n_value_references: usize,
    _values: *const bool,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3SetClock", allowed::SET_ABSENT, |inst| {
            let vrs = unsafe { slice(value_references, n_value_references, "valueReferences") }.map_err(e)?;
            inst.no_variables_of("Clock", vrs)
        })
    }
}

/// `fmi3GetNumberOfVariableDependencies`: not supported (no Dependencies in the description).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(
    instance: Fmi3Instance,
    _value_reference: Fmi3ValueReference,
    _n_dependencies: *mut usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetNumberOfVariableDependencies (providesPerElementDependencies is false)") }
}

/// `fmi3GetVariableDependencies`: not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetVariableDependencies(
    instance: Fmi3Instance,
    _dependent: Fmi3ValueReference,
    _element_indices_of_dependent: *mut usize,
    _independents: *mut Fmi3ValueReference,
    _element_indices_of_independents: *mut usize,
    _dependency_kinds: *mut c_int,
    _n_dependencies: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetVariableDependencies (providesPerElementDependencies is false)") }
}

/// `fmi3GetFMUState`: a new snapshot, or overwrites `*state` if it is one.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetFMUState(instance: Fmi3Instance, state: *mut Fmi3FmuState) -> Status {
    ffi_boundary! {
        with(instance, "fmi3GetFMUState", allowed::GET_STATE, |inst| {
            let snapshot = inst.snapshot()?;
            unsafe { slots::store(state, "FMUState", snapshot) }
        })
    }
}

/// `fmi3SetFMUState`.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetFMUState(instance: Fmi3Instance, state: Fmi3FmuState) -> Status {
    ffi_boundary! {
        with(instance, "fmi3SetFMUState", allowed::SET_STATE, |inst| {
            inst.restore(unsafe { slots::borrow(state, "FMUState") }?)
        })
    }
}

/// `fmi3FreeFMUState`: frees `*state` and sets it to null; a null `state` or `*state` is ignored (OK).
#[no_mangle]
pub unsafe extern "C" fn fmi3FreeFMUState(instance: Fmi3Instance, state: *mut Fmi3FmuState) -> Status {
    ffi_boundary! {
        with(instance, "fmi3FreeFMUState", allowed::STATE_MEMORY, |_| {
            unsafe { slots::free(state) }
        })
    }
}

/// `fmi3SerializedFMUStateSize`.
#[no_mangle]
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
    instance: Fmi3Instance,
    state: Fmi3FmuState,
    size: *mut usize,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3SerializedFMUStateSize", allowed::STATE_MEMORY, |_| {
            unsafe { slots::serialized_size(state, "FMUState", size) }
        })
    }
}

/// `fmi3SerializeFMUState`: the portable byte format of [`super::state`].
#[no_mangle]
pub unsafe extern "C" fn fmi3SerializeFMUState(
    instance: Fmi3Instance,
    state: Fmi3FmuState,
    serialized_state: *mut u8,
    size: usize,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3SerializeFMUState", allowed::STATE_MEMORY, |_| {
            unsafe { slots::serialize(state, "FMUState", serialized_state, size, "fmi3SerializedFMUStateSize") }
        })
    }
}

/// `fmi3DeserializeFMUState`: a state serialized by any process running this binary.
#[no_mangle]
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    instance: Fmi3Instance,
    serialized_state: *const u8,
    size: usize,
    state: *mut Fmi3FmuState,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3DeserializeFMUState", allowed::STATE_MEMORY, |_| {
            unsafe { slots::deserialize(serialized_state, size, state, "FMUState") }
        })
    }
}

/// `fmi3GetDirectionalDerivative`: not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetDirectionalDerivative(
    instance: Fmi3Instance,
    _unknowns: *const Fmi3ValueReference,
    _n_unknowns: usize,
    _knowns: *const Fmi3ValueReference,
    _n_knowns: usize,
    _seed: *const f64,
    _n_seed: usize,
    _sensitivity: *mut f64,
    _n_sensitivity: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetDirectionalDerivative (providesDirectionalDerivatives is false)") }
}

/// `fmi3GetAdjointDerivative`: not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetAdjointDerivative(
    instance: Fmi3Instance,
    _unknowns: *const Fmi3ValueReference,
    _n_unknowns: usize,
    _knowns: *const Fmi3ValueReference,
    _n_knowns: usize,
    _seed: *const f64,
    _n_seed: usize,
    _sensitivity: *mut f64,
    _n_sensitivity: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetAdjointDerivative (providesAdjointDerivatives is false)") }
}

/// `fmi3EnterConfigurationMode`: not supported (no structural parameters).
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterConfigurationMode(instance: Fmi3Instance) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3EnterConfigurationMode (there are no structural parameters)") }
}

/// `fmi3ExitConfigurationMode`: not supported (no structural parameters).
#[no_mangle]
pub unsafe extern "C" fn fmi3ExitConfigurationMode(instance: Fmi3Instance) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3ExitConfigurationMode (there are no structural parameters)") }
}

/// `fmi3GetIntervalDecimal`: not supported (no clocks).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetIntervalDecimal(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _intervals: *mut f64,
    _qualifiers: *mut c_int,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetIntervalDecimal (this FMU has no clocks)") }
}

/// `fmi3GetIntervalFraction`: not supported (no clocks).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetIntervalFraction(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _counters: *mut u64,
    _resolutions: *mut u64,
    _qualifiers: *mut c_int,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetIntervalFraction (this FMU has no clocks)") }
}

/// `fmi3GetShiftDecimal`: not supported (no clocks).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetShiftDecimal(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _shifts: *mut f64,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetShiftDecimal (this FMU has no clocks)") }
}

/// `fmi3GetShiftFraction`: not supported (no clocks).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetShiftFraction(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _counters: *mut u64,
    _resolutions: *mut u64,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetShiftFraction (this FMU has no clocks)") }
}

/// `fmi3SetIntervalDecimal`: not supported (no clocks).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetIntervalDecimal(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _intervals: *const f64,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3SetIntervalDecimal (this FMU has no clocks)") }
}

/// `fmi3SetIntervalFraction`: not supported (no clocks).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetIntervalFraction(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _counters: *const u64,
    _resolutions: *const u64,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3SetIntervalFraction (this FMU has no clocks)") }
}

/// `fmi3SetShiftDecimal`: not supported (no clocks).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetShiftDecimal(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _shifts: *const f64,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3SetShiftDecimal (this FMU has no clocks)") }
}

/// `fmi3SetShiftFraction`: not supported (no clocks).
#[no_mangle]
pub unsafe extern "C" fn fmi3SetShiftFraction(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _counters: *const u64,
    _resolutions: *const u64,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3SetShiftFraction (this FMU has no clocks)") }
}

/// `fmi3EvaluateDiscreteStates`: there are no discrete states; nothing to do.
#[no_mangle]
pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(instance: Fmi3Instance) -> Status {
    ffi_boundary! { with(instance, "fmi3EvaluateDiscreteStates", allowed::UPDATE_DISCRETE_STATES, |_| Ok(Status::Ok)) }
}

/// `fmi3UpdateDiscreteStates`: there are no discrete states; reports nothing to update.
#[no_mangle]
pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
    instance: Fmi3Instance,
    discrete_states_need_update: *mut bool,
    terminate_simulation: *mut bool,
    nominals_of_continuous_states_changed: *mut bool,
    values_of_continuous_states_changed: *mut bool,
    next_event_time_defined: *mut bool,
    next_event_time: *mut f64,
) -> Status {
    ffi_boundary! {
        with(instance, "fmi3UpdateDiscreteStates", allowed::UPDATE_DISCRETE_STATES, |_| {
            for (flag, name) in [
                (discrete_states_need_update, "discreteStatesNeedUpdate"),
                (terminate_simulation, "terminateSimulation"),
                (nominals_of_continuous_states_changed, "nominalsOfContinuousStatesChanged"),
                (values_of_continuous_states_changed, "valuesOfContinuousStatesChanged"),
                (next_event_time_defined, "nextEventTimeDefined"),
            ] {
                *unsafe { out(flag, name) }.map_err(e)? = false;
            }
            *unsafe { out(next_event_time, "nextEventTime") }.map_err(e)? = 0.0;
            Ok(Status::Ok)
        })
    }
}

/// `fmi3EnterContinuousTimeMode`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterContinuousTimeMode(instance: Fmi3Instance) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3EnterContinuousTimeMode (model exchange)") }
}

/// `fmi3CompletedIntegratorStep`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3CompletedIntegratorStep(
    instance: Fmi3Instance,
    _no_set_fmu_state_prior_to_current_point: bool,
    _enter_event_mode: *mut bool,
    _terminate_simulation: *mut bool,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3CompletedIntegratorStep (model exchange)") }
}

/// `fmi3SetTime`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetTime(instance: Fmi3Instance, _time: f64) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3SetTime (model exchange)") }
}

/// `fmi3SetContinuousStates`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetContinuousStates(
    instance: Fmi3Instance,
    _continuous_states: *const f64,
    _n_continuous_states: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3SetContinuousStates (model exchange)") }
}

/// `fmi3GetContinuousStateDerivatives`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(
    instance: Fmi3Instance,
    _derivatives: *mut f64,
    _n_continuous_states: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetContinuousStateDerivatives (model exchange)") }
}

/// `fmi3GetEventIndicators`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetEventIndicators(
    instance: Fmi3Instance,
    _event_indicators: *mut f64,
    _n_event_indicators: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetEventIndicators (model exchange)") }
}

/// `fmi3GetContinuousStates`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetContinuousStates(
    instance: Fmi3Instance,
    _continuous_states: *mut f64,
    _n_continuous_states: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetContinuousStates (model exchange)") }
}

/// `fmi3GetNominalsOfContinuousStates`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(
    instance: Fmi3Instance,
    _nominals: *mut f64,
    _n_continuous_states: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetNominalsOfContinuousStates (model exchange)") }
}

/// `fmi3GetNumberOfEventIndicators`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(
    instance: Fmi3Instance,
    _n_event_indicators: *mut usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetNumberOfEventIndicators (model exchange)") }
}

/// `fmi3GetNumberOfContinuousStates`: model exchange, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(
    instance: Fmi3Instance,
    _n_continuous_states: *mut usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetNumberOfContinuousStates (model exchange)") }
}

/// `fmi3EnterStepMode`: leaves event mode.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterStepMode(instance: Fmi3Instance) -> Status {
    ffi_boundary! { with(instance, "fmi3EnterStepMode", allowed::ENTER_STEP_MODE, Instance::enter_step_mode) }
}

/// `fmi3GetOutputDerivatives`: not supported (maxOutputDerivativeOrder is 0).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetOutputDerivatives(
    instance: Fmi3Instance,
    _value_references: *const Fmi3ValueReference,
    _n_value_references: usize,
    _orders: *const i32,
    _values: *mut f64,
    _n_values: usize,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3GetOutputDerivatives (maxOutputDerivativeOrder is 0)") }
}

/// `fmi3DoStep`: advances to `currentCommunicationPoint + communicationStepSize` exactly, or,
/// with earlyReturnAllowed, to the first contact change before it (`earlyReturn`,
/// `lastSuccessfulTime`).
#[no_mangle]
pub unsafe extern "C" fn fmi3DoStep(
    instance: Fmi3Instance,
    current_communication_point: f64,
    communication_step_size: f64,
    _no_set_fmu_state_prior_to_current_point: bool,
    event_handling_needed: *mut bool,
    terminate_simulation: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> Status {
    ffi_boundary! {
        with_run(instance, "fmi3DoStep", allowed::DO_STEP, |inst| {
            let event_handling_needed = unsafe { out(event_handling_needed, "eventHandlingNeeded") }.map_err(e)?;
            let terminate_simulation = unsafe { out(terminate_simulation, "terminateSimulation") }.map_err(e)?;
            let early_return = unsafe { out(early_return, "earlyReturn") }.map_err(e)?;
            let last_successful_time = unsafe { out(last_successful_time, "lastSuccessfulTime") }.map_err(e)?;
            *event_handling_needed = false;
            *terminate_simulation = false;
            *early_return = false;
            let outcome = inst.do_step(current_communication_point, communication_step_size);
            *last_successful_time = inst.last_successful_time();
            let outcome = outcome?;
            *early_return = outcome.early_return;
            Ok(if outcome.warned { Status::Warning } else { Status::Ok })
        })
    }
}

/// `fmi3ActivateModelPartition`: scheduled execution, not supported.
#[no_mangle]
pub unsafe extern "C" fn fmi3ActivateModelPartition(
    instance: Fmi3Instance,
    _clock_reference: Fmi3ValueReference,
    _activation_time: f64,
) -> Status {
    ffi_boundary! { unsupported(instance, "fmi3ActivateModelPartition (scheduled execution)") }
}

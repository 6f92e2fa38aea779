//! The FMI 2.0 co-simulation API: every function fmpy looks up (the 25 common and 9
//! co-simulation ones). Each body is inside [`ffi_boundary!`](crate::ffi_boundary), checks its
//! pointers and delegates to [`Instance`] through [`Instance::guard`] with the function's entry of
//! the allowed-states table. Unsupported functions log why and return `fmi2Error`.

#![allow(clippy::missing_safety_doc)] // The safety contract is the FMI 2.0 standard.

use std::ffi::{c_char, c_int, c_uint, c_void};

use super::boundary::{out, slice, slice_mut, string, utf8_string};
use super::instance::{Instance, Shown, Version};
pub use super::logger::Fmi2CallbackLogger;
use super::logger::{log_with, Logger};
use super::resource;
use super::slots;
use super::state::Snapshot;
use super::status::{allowed, Mask, Status};
use crate::ffi_boundary;

/// `fmi2Component`: the opaque instance handle.
pub type Fmi2Component = *mut Instance;
/// `fmi2FMUstate`: an opaque saved state.
pub type Fmi2FmuState = *mut Snapshot;
/// `fmi2ValueReference`.
pub type Fmi2ValueReference = c_uint;
/// `fmi2Boolean`: a 4-byte C int.
pub type Fmi2Boolean = c_int;

/// `fmi2CallbackFunctions`, as passed to [`fmi2Instantiate`].
#[repr(C)]
pub struct Fmi2CallbackFunctions {
    /// Logger (may be null: then nothing is logged).
    pub logger: Fmi2CallbackLogger,
    /// Not used (canNotUseMemoryManagementFunctions).
    pub allocate_memory: Option<unsafe extern "C" fn(nobj: usize, size: usize) -> *mut c_void>,
    /// Not used.
    pub free_memory: Option<unsafe extern "C" fn(obj: *mut c_void)>,
    /// Not used (no asynchronous steps).
    pub step_finished: Option<unsafe extern "C" fn(component_environment: *mut c_void, status: Status)>,
    /// Handed back to the logger untouched.
    pub component_environment: *mut c_void,
}

const FMI2_CO_SIMULATION: c_int = 1;
const FMI2_DO_STEP_STATUS: c_int = 0;
const FMI2_PENDING_STATUS: c_int = 1;
const FMI2_LAST_SUCCESSFUL_TIME: c_int = 2;
const FMI2_TERMINATED: c_int = 3;

/// Runs `work` on the instance behind `c` (null: `fmi2Error`, nothing to log to).
fn with(
    c: Fmi2Component,
    function: &str,
    mask: Mask,
    work: impl FnOnce(&mut Instance) -> Result<Status, String>,
) -> Status {
    // SAFETY: a non-null component is the pointer fmi2Instantiate returned and the importer
    // does not use it from two threads at once (FMI 2.0, section 2.1.5).
    match unsafe { c.as_mut() } {
        Some(instance) => instance.guard(function, mask, work),
        None => Status::Error,
    }
}

/// [`with`] for a setter: a call in a state where it is not allowed names what it was to set,
/// `refused` ([`Instance::guard_set`]).
fn with_set(
    c: Fmi2Component,
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
    c: Fmi2Component,
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

fn kind_name(kind: c_int) -> &'static str {
    match kind {
        FMI2_DO_STEP_STATUS => "fmi2DoStepStatus",
        FMI2_PENDING_STATUS => "fmi2PendingStatus",
        FMI2_LAST_SUCCESSFUL_TIME => "fmi2LastSuccessfulTime",
        FMI2_TERMINATED => "fmi2Terminated",
        _ => "an unknown fmi2StatusKind",
    }
}

/// `fmi2GetTypesPlatform`: "default".
#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    ffi_boundary! { c"default".as_ptr() }
}

/// `fmi2GetVersion`: "2.0".
#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    ffi_boundary! { c"2.0".as_ptr() }
}

/// `fmi2SetDebugLogging`: an empty category list switches every category.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: Fmi2Component,
    logging_on: Fmi2Boolean,
    n_categories: usize,
    categories: *const *const c_char,
) -> Status {
    ffi_boundary! {
        with(c, "fmi2SetDebugLogging", allowed::SET_DEBUG_LOGGING, |inst| {
            let pointers = unsafe { slice(categories, n_categories, "categories") }.map_err(|e| e.to_string())?;
            let names = pointers
                .iter()
                .map(|&p| unsafe { string(p, "categories[i]") }.map_err(|e| e.to_string()))
                .collect::<Result<Vec<_>, _>>()?;
            inst.set_debug_logging(logging_on != 0, &names)
        })
    }
}

/// `fmi2Instantiate`: co-simulation only; checks the GUID against this binary's.
#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: *const c_char,
    fmu_type: c_int,
    fmu_guid: *const c_char,
    fmu_resource_location: *const c_char,
    functions: *const Fmi2CallbackFunctions,
    _visible: Fmi2Boolean,
    logging_on: Fmi2Boolean,
) -> Fmi2Component {
    ffi_boundary! {
        // SAFETY: a non-null callback struct is valid for the call (FMI 2.0).
        let Some(functions) = (unsafe { functions.as_ref() }) else { return std::ptr::null_mut() };
        let logger = Logger::Fmi2 { callback: functions.logger, environment: functions.component_environment };
        let name = unsafe { string(instance_name, "instanceName") }.unwrap_or_default();
        let fail = |message: &str| {
            log_with(logger, &name, Status::Error, "logStatusError", &format!("fmi2Instantiate: {message}"));
            std::ptr::null_mut()
        };
        if instance_name.is_null() {
            return fail("argument `instanceName` is a null pointer");
        }
        if fmu_type != FMI2_CO_SIMULATION {
            return fail("this FMU supports co-simulation only (fmuType = fmi2CoSimulation)");
        }
        let guid = match unsafe { string(fmu_guid, "fmuGUID") } {
            Ok(g) => g,
            Err(e) => return fail(&e.to_string()),
        };
        let location = unsafe { string(fmu_resource_location, "fmuResourceLocation") }.ok();
        let resources = location.as_deref().and_then(resource::parse_uri);
        // The starting scenario packed into the resources (issue 30), which the GUID covers.
        let packed = match resources.as_deref().map(resource::read_scenario).transpose() {
            Ok(packed) => packed.flatten(),
            Err(message) => return fail(&message),
        };
        if let Err(message) = resource::check_token("fmuGUID", &guid, packed.as_ref()) {
            return fail(&message);
        }
        let instance = Instance::starting_from(&name, Version::Fmi2, logger, logging_on != 0, packed);
        instance.log_resources(location.as_deref(), resources);
        Box::into_raw(Box::new(instance))
    }
}

/// `fmi2FreeInstance`: completes the MCAP log if not terminated, then frees the instance.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: Fmi2Component) {
    ffi_boundary! {
        if !c.is_null() {
            // SAFETY: the pointer came from Box::into_raw in fmi2Instantiate and is freed once.
            let mut instance = unsafe { Box::from_raw(c) };
            instance.free();
        }
    }
}

/// `fmi2SetupExperiment`.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: Fmi2Component,
    _tolerance_defined: Fmi2Boolean,
    _tolerance: f64,
    start_time: f64,
    stop_time_defined: Fmi2Boolean,
    stop_time: f64,
) -> Status {
    ffi_boundary! {
        with(c, "fmi2SetupExperiment", allowed::SETUP_EXPERIMENT, |inst| {
            inst.setup_experiment(start_time, (stop_time_defined != 0).then_some(stop_time))
        })
    }
}

/// `fmi2EnterInitializationMode`.
#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Fmi2Component) -> Status {
    ffi_boundary! { with(c, "fmi2EnterInitializationMode", allowed::ENTER_INITIALIZATION, Instance::enter_initialization) }
}

/// `fmi2ExitInitializationMode`: validates the parameters, builds the model, opens the log.
#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Fmi2Component) -> Status {
    ffi_boundary! { with_run(c, "fmi2ExitInitializationMode", allowed::EXIT_INITIALIZATION, Instance::exit_initialization) }
}

/// `fmi2Terminate`: completes the MCAP log.
#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: Fmi2Component) -> Status {
    ffi_boundary! { with_run(c, "fmi2Terminate", allowed::TERMINATE, Instance::terminate) }
}

/// `fmi2Reset`.
#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: Fmi2Component) -> Status {
    ffi_boundary! { with(c, "fmi2Reset", allowed::RESET, Instance::reset) }
}

macro_rules! getter {
    ($c:expr, $function:literal, $vr:expr, $nvr:expr, $values:expr, $get:ident, $convert:expr) => {
        with($c, $function, allowed::FMI2_GET, |inst| {
            let vrs = unsafe { slice($vr, $nvr, "vr") }.map_err(|e| e.to_string())?;
            let values = unsafe { slice_mut($values, $nvr, "value") }.map_err(|e| e.to_string())?;
            for (value, &vr) in values.iter_mut().zip(vrs) {
                *value = $convert(inst.$get(vr)?);
            }
            Ok(Status::Ok)
        })
    };
}

macro_rules! setter {
    ($c:expr, $function:literal, $mask:expr, $vr:expr, $nvr:expr, $values:expr, $set:ident, $convert:expr) => {
        with_set(
            $c,
            $function,
            $mask,
            |inst: &Instance| {
                // Read only to name what a call in the wrong state was to set (issue 40).
                let vrs = unsafe { slice($vr, $nvr, "vr") }.unwrap_or(&[]);
                let first = unsafe { slice($values, $nvr, "value") }.ok().and_then(|v| v.first().copied());
                inst.to_be_set(vrs, first.map(|v| $convert(v).map_or_else(|e| e, |x| Shown::shown(&x))))
            },
            |inst| {
                let vrs = unsafe { slice($vr, $nvr, "vr") }.map_err(|e| e.to_string())?;
                let values = unsafe { slice($values, $nvr, "value") }.map_err(|e| e.to_string())?;
                for (&value, &vr) in values.iter().zip(vrs) {
                    inst.$set(vr, $convert(value)?)?;
                }
                Ok(Status::Ok)
            },
        )
    };
}

/// `fmi2GetReal`.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(c: Fmi2Component, vr: *const c_uint, nvr: usize, value: *mut f64) -> Status {
    ffi_boundary! { getter!(c, "fmi2GetReal", vr, nvr, value, get_real, |x: f64| x) }
}

/// `fmi2GetInteger`.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(c: Fmi2Component, vr: *const c_uint, nvr: usize, value: *mut c_int) -> Status {
    ffi_boundary! { getter!(c, "fmi2GetInteger", vr, nvr, value, get_integer, |x: i32| x) }
}

/// `fmi2GetBoolean`.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: Fmi2Component,
    vr: *const c_uint,
    nvr: usize,
    value: *mut Fmi2Boolean,
) -> Status {
    ffi_boundary! { getter!(c, "fmi2GetBoolean", vr, nvr, value, get_boolean, |x: bool| x as Fmi2Boolean) }
}

/// `fmi2GetString`: the strings stay valid until the next `fmi2GetString` on this instance.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(
    c: Fmi2Component,
    vr: *const c_uint,
    nvr: usize,
    value: *mut *const c_char,
) -> Status {
    ffi_boundary! {
        with(c, "fmi2GetString", allowed::FMI2_GET, |inst| {
            let vrs = unsafe { slice(vr, nvr, "vr") }.map_err(|e| e.to_string())?;
            let values = unsafe { slice_mut(value, nvr, "value") }.map_err(|e| e.to_string())?;
            let strings = inst.get_strings(vrs)?;
            values.copy_from_slice(&strings);
            Ok(Status::Ok)
        })
    }
}

/// `fmi2SetReal`: parameters before ExitInitializationMode, inputs until Terminate.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(c: Fmi2Component, vr: *const c_uint, nvr: usize, value: *const f64) -> Status {
    ffi_boundary! { setter!(c, "fmi2SetReal", allowed::SET_REAL, vr, nvr, value, set_real, |x: f64| Ok::<f64, String>(x)) }
}

/// `fmi2SetInteger`: the element counts.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(
    c: Fmi2Component,
    vr: *const c_uint,
    nvr: usize,
    value: *const c_int,
) -> Status {
    ffi_boundary! { setter!(c, "fmi2SetInteger", allowed::SET_INTEGER, vr, nvr, value, set_integer, |x: i32| Ok::<i32, String>(x)) }
}

/// `fmi2SetBoolean`: there is no settable Boolean.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: Fmi2Component,
    vr: *const c_uint,
    nvr: usize,
    value: *const Fmi2Boolean,
) -> Status {
    ffi_boundary! { setter!(c, "fmi2SetBoolean", allowed::SET_BOOLEAN, vr, nvr, value, set_boolean, |x: Fmi2Boolean| Ok::<bool, String>(x != 0)) }
}

/// `fmi2SetString`: `log.path`, `log.channels`.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: Fmi2Component,
    vr: *const c_uint,
    nvr: usize,
    value: *const *const c_char,
) -> Status {
    ffi_boundary! {
        setter!(c, "fmi2SetString", allowed::SET_STRING, vr, nvr, value, set_string, |p: *const c_char| {
            unsafe { utf8_string(p, "value[i]") }
        })
    }
}

/// `fmi2GetFMUstate`: a new snapshot, or overwrites `*state` if it is one.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: Fmi2Component, state: *mut Fmi2FmuState) -> Status {
    ffi_boundary! {
        with(c, "fmi2GetFMUstate", allowed::GET_STATE, |inst| {
            let snapshot = inst.snapshot()?;
            unsafe { slots::store(state, "FMUstate", snapshot) }
        })
    }
}

/// `fmi2SetFMUstate`.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: Fmi2Component, state: Fmi2FmuState) -> Status {
    ffi_boundary! {
        with(c, "fmi2SetFMUstate", allowed::SET_STATE, |inst| {
            inst.restore(unsafe { slots::borrow(state, "FMUstate") }?)
        })
    }
}

/// `fmi2FreeFMUstate`: frees `*state` and sets it to null; a null `state` or `*state` is ignored (OK).
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: Fmi2Component, state: *mut Fmi2FmuState) -> Status {
    ffi_boundary! {
        with(c, "fmi2FreeFMUstate", allowed::STATE_MEMORY, |_| {
            unsafe { slots::free(state) }
        })
    }
}

/// `fmi2SerializedFMUstateSize`.
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(c: Fmi2Component, state: Fmi2FmuState, size: *mut usize) -> Status {
    ffi_boundary! {
        with(c, "fmi2SerializedFMUstateSize", allowed::STATE_MEMORY, |_| {
            unsafe { slots::serialized_size(state, "FMUstate", size) }
        })
    }
}

/// `fmi2SerializeFMUstate`: the portable byte format of [`super::state`].
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: Fmi2Component,
    state: Fmi2FmuState,
    serialized_state: *mut c_char,
    size: usize,
) -> Status {
    ffi_boundary! {
        with(c, "fmi2SerializeFMUstate", allowed::STATE_MEMORY, |_| {
            unsafe { slots::serialize(state, "FMUstate", serialized_state.cast::<u8>(), size, "fmi2SerializedFMUstateSize") }
        })
    }
}

/// `fmi2DeSerializeFMUstate`: a state serialized by any process running this binary.
#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: Fmi2Component,
    serialized_state: *const c_char,
    size: usize,
    state: *mut Fmi2FmuState,
) -> Status {
    ffi_boundary! {
        with(c, "fmi2DeSerializeFMUstate", allowed::STATE_MEMORY, |_| {
            unsafe { slots::deserialize(serialized_state.cast::<u8>(), size, state, "FMUstate") }
        })
    }
}

/// `fmi2GetDirectionalDerivative`: not supported (logs why, returns fmi2Error).
#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: Fmi2Component,
    _v_unknown_ref: *const c_uint,
    _n_unknown: usize,
    _v_known_ref: *const c_uint,
    _n_known: usize,
    _dv_known: *const f64,
    _dv_unknown: *mut f64,
) -> Status {
    ffi_boundary! { with(c, "fmi2GetDirectionalDerivative (providesDirectionalDerivative is false)", Mask::NONE, |_| Ok(Status::Error)) }
}

/// `fmi2SetRealInputDerivatives`: not supported (canInterpolateInputs is false).
#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: Fmi2Component,
    _vr: *const c_uint,
    _nvr: usize,
    _order: *const c_int,
    _value: *const f64,
) -> Status {
    ffi_boundary! { with(c, "fmi2SetRealInputDerivatives (canInterpolateInputs is false)", Mask::NONE, |_| Ok(Status::Error)) }
}

/// `fmi2GetRealOutputDerivatives`: not supported (maxOutputDerivativeOrder is 0).
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: Fmi2Component,
    _vr: *const c_uint,
    _nvr: usize,
    _order: *const c_int,
    _value: *mut f64,
) -> Status {
    ffi_boundary! { with(c, "fmi2GetRealOutputDerivatives (maxOutputDerivativeOrder is 0)", Mask::NONE, |_| Ok(Status::Error)) }
}

/// `fmi2DoStep`: advances to `currentCommunicationPoint + communicationStepSize` exactly.
#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: Fmi2Component,
    current_communication_point: f64,
    communication_step_size: f64,
    _no_set_fmu_state_prior_to_current_point: Fmi2Boolean,
) -> Status {
    ffi_boundary! {
        with_run(c, "fmi2DoStep", allowed::DO_STEP, |inst| {
            let outcome = inst.do_step(current_communication_point, communication_step_size)?;
            Ok(if outcome.warned { Status::Warning } else { Status::Ok })
        })
    }
}

/// `fmi2CancelStep`: not supported (doStep never returns fmi2Pending).
#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: Fmi2Component) -> Status {
    ffi_boundary! { with(c, "fmi2CancelStep (fmi2DoStep never returns fmi2Pending)", Mask::NONE, |_| Ok(Status::Error)) }
}

/// `fmi2GetStatus`: no asynchronous steps, so there is no status to ask for.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(c: Fmi2Component, s: c_int, value: *mut Status) -> Status {
    ffi_boundary! {
        with(c, "fmi2GetStatus", allowed::STATUS, |inst| {
            let _ = unsafe { out(value, "value") }.map_err(|e| e.to_string())?;
            inst.log(Status::Discard, "logStatusDiscard", &format!(
                "fmi2GetStatus({}): fmi2DoStep never returns fmi2Pending, so there is no status to report",
                kind_name(s)
            ));
            Ok(Status::Discard)
        })
    }
}

/// `fmi2GetRealStatus`: `fmi2LastSuccessfulTime`.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: Fmi2Component, s: c_int, value: *mut f64) -> Status {
    ffi_boundary! {
        with(c, "fmi2GetRealStatus", allowed::STATUS, |inst| {
            let value = unsafe { out(value, "value") }.map_err(|e| e.to_string())?;
            if s != FMI2_LAST_SUCCESSFUL_TIME {
                return Err(format!("{} is not a Real status (only fmi2LastSuccessfulTime is)", kind_name(s)));
            }
            *value = inst.last_successful_time();
            Ok(Status::Ok)
        })
    }
}

/// `fmi2GetIntegerStatus`: there is no Integer status.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(c: Fmi2Component, s: c_int, _value: *mut c_int) -> Status {
    ffi_boundary! {
        with(c, "fmi2GetIntegerStatus", allowed::STATUS, |_| {
            Err(format!("{} is not an Integer status (FMI 2.0 defines none)", kind_name(s)))
        })
    }
}

/// `fmi2GetBooleanStatus`: `fmi2Terminated` (this FMU never asks to stop: false).
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(c: Fmi2Component, s: c_int, value: *mut Fmi2Boolean) -> Status {
    ffi_boundary! {
        with(c, "fmi2GetBooleanStatus", allowed::STATUS, |_| {
            let value = unsafe { out(value, "value") }.map_err(|e| e.to_string())?;
            if s != FMI2_TERMINATED {
                return Err(format!("{} is not a Boolean status (only fmi2Terminated is)", kind_name(s)));
            }
            *value = 0;
            Ok(Status::Ok)
        })
    }
}

/// `fmi2GetStringStatus`: no asynchronous steps, so no pending-status text.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(c: Fmi2Component, s: c_int, _value: *mut *const c_char) -> Status {
    ffi_boundary! {
        with(c, "fmi2GetStringStatus", allowed::STATUS, |_| {
            Err(format!("{}: fmi2DoStep never returns fmi2Pending, so there is no status text", kind_name(s)))
        })
    }
}

//! A minimal FMI importer over libloading, as a host program would drive the FMU: FMI 2.0 and
//! FMI 3.0 co-simulation calls, a logger that records every message, value references looked up
//! by name in the variable table.

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::sync::{Arc, Mutex};

use libloading::Library;

pub const OK: c_int = 0;
pub const WARNING: c_int = 1;
pub const ERROR: c_int = 3;

/// One logged message.
#[derive(Clone, Debug)]
pub struct Message {
    pub status: c_int,
    pub category: String,
    pub text: String,
    /// The FMI 2 format argument (must be "%s").
    pub format: String,
}

/// Where a logger callback writes (the instance environment points to it).
#[derive(Default)]
pub struct Log {
    pub messages: Mutex<Vec<Message>>,
}

impl Log {
    pub fn all(&self) -> Vec<Message> {
        self.messages.lock().unwrap().clone()
    }

    /// Every message text joined, for `contains` checks.
    pub fn text(&self) -> String {
        self.all().iter().map(|m| format!("[{}] {}\n", m.category, m.text)).collect()
    }

    pub fn clear(&self) {
        self.messages.lock().unwrap().clear();
    }
}

fn text(ptr: *const c_char) -> String {
    if ptr.is_null() {
        "<null>".into()
    } else {
        // SAFETY: the FMU passes NUL-terminated strings valid for the call.
        unsafe { CStr::from_ptr(ptr) }.to_string_lossy().into_owned()
    }
}

/// The FMI 2 logger. The C type is variadic; this FMU always calls it with the format "%s" and
/// exactly one string, which the x86-64 System V ABI passes in the same register as a sixth
/// fixed argument (how ctypes-based importers such as fmpy receive it too). The format is
/// recorded so the tests can check it is "%s".
pub unsafe extern "C" fn fmi2_logger(
    env: *mut c_void,
    _name: *const c_char,
    status: c_int,
    category: *const c_char,
    format: *const c_char,
    message: *const c_char,
) {
    // SAFETY: env is the &Log the test passed as componentEnvironment.
    let log = unsafe { &*(env as *const Log) };
    let (format, category) = (text(format), text(category));
    let text = if format == "%s" { text(message) } else { format.clone() };
    log.messages.lock().unwrap().push(Message { status, category, text, format });
}

pub unsafe extern "C" fn fmi3_logger(env: *mut c_void, status: c_int, category: *const c_char, message: *const c_char) {
    // SAFETY: env is the &Log the test passed as instanceEnvironment.
    let log = unsafe { &*(env as *const Log) };
    log.messages.lock().unwrap().push(Message {
        status,
        category: text(category),
        text: text(message),
        format: String::new(),
    });
}

#[repr(C)]
pub struct Fmi2Callbacks {
    pub logger:
        Option<unsafe extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char, *const c_char)>,
    pub allocate_memory: *const c_void,
    pub free_memory: *const c_void,
    pub step_finished: *const c_void,
    pub environment: *mut c_void,
}

pub fn vr(name: &str) -> u32 {
    beam_impact::fmi::variables::table()
        .iter()
        .find(|v| v.name == name)
        .unwrap_or_else(|| panic!("no variable {name}"))
        .vr
}

pub fn load() -> Arc<Library> {
    // SAFETY: loading the crate's own cdylib, whose initializers are Rust's (none of ours).
    Arc::new(unsafe { Library::new(super::library()) }.unwrap())
}

macro_rules! sym {
    ($lib:expr, $name:expr, $t:ty) => {{
        // SAFETY: the symbol has this signature (include/beam_impact.h).
        let f: libloading::Symbol<$t> = unsafe { $lib.get(format!("{}\0", $name).as_bytes()) }.unwrap();
        *f
    }};
}

/// The FMU-state functions of one FMI version: the calls are the same, the names differ
/// (FMI 2 writes `FMUstate` and `DeSerialize`, FMI 3 `FMUState` and `Deserialize`).
struct StateNames {
    get: &'static str,
    set: &'static str,
    free: &'static str,
    size: &'static str,
    serialize: &'static str,
    deserialize: &'static str,
}

const FMI2_STATES: StateNames = StateNames {
    get: "fmi2GetFMUstate",
    set: "fmi2SetFMUstate",
    free: "fmi2FreeFMUstate",
    size: "fmi2SerializedFMUstateSize",
    serialize: "fmi2SerializeFMUstate",
    deserialize: "fmi2DeSerializeFMUstate",
};

const FMI3_STATES: StateNames = StateNames {
    get: "fmi3GetFMUState",
    set: "fmi3SetFMUState",
    free: "fmi3FreeFMUState",
    size: "fmi3SerializedFMUStateSize",
    serialize: "fmi3SerializeFMUState",
    deserialize: "fmi3DeserializeFMUState",
};

/// The FMU-state methods of [`Fmu2`] and [`Fmu3`] (fields `lib`, `c`, `log`), written once for
/// the names of one version.
macro_rules! state_calls {
    ($names:expr) => {
        pub fn get_state(&self) -> *mut c_void {
            let f = sym!(self.lib, $names.get, unsafe extern "C" fn(*mut c_void, *mut *mut c_void) -> c_int);
            let mut state = std::ptr::null_mut();
            // SAFETY: an out-pointer.
            assert_eq!(unsafe { f(self.c, &mut state) }, OK, "{}", self.log.text());
            state
        }

        pub fn set_state(&self, state: *mut c_void) -> c_int {
            let f = sym!(self.lib, $names.set, unsafe extern "C" fn(*mut c_void, *mut c_void) -> c_int);
            // SAFETY: a state from this FMU.
            unsafe { f(self.c, state) }
        }

        pub fn free_state(&self, mut state: *mut c_void) {
            let f = sym!(self.lib, $names.free, unsafe extern "C" fn(*mut c_void, *mut *mut c_void) -> c_int);
            // SAFETY: a state from this FMU.
            assert_eq!(unsafe { f(self.c, &mut state) }, OK);
            assert!(state.is_null());
        }

        pub fn serialize(&self, state: *mut c_void) -> Vec<u8> {
            let size_of =
                sym!(self.lib, $names.size, unsafe extern "C" fn(*mut c_void, *mut c_void, *mut usize) -> c_int);
            let serialize = sym!(
                self.lib,
                $names.serialize,
                unsafe extern "C" fn(*mut c_void, *mut c_void, *mut u8, usize) -> c_int
            );
            let mut size = 0usize;
            // SAFETY: out-pointer, then a buffer of that size.
            assert_eq!(unsafe { size_of(self.c, state, &mut size) }, OK);
            let mut bytes = vec![0u8; size];
            assert_eq!(unsafe { serialize(self.c, state, bytes.as_mut_ptr(), size) }, OK);
            bytes
        }

        pub fn deserialize(&self, bytes: &[u8]) -> (c_int, *mut c_void) {
            let f = sym!(
                self.lib,
                $names.deserialize,
                unsafe extern "C" fn(*mut c_void, *const u8, usize, *mut *mut c_void) -> c_int
            );
            let mut state = std::ptr::null_mut();
            // SAFETY: a byte buffer and an out-pointer.
            let status = unsafe { f(self.c, bytes.as_ptr(), bytes.len(), &mut state) };
            (status, state)
        }
    };
}

/// An FMI 2.0 co-simulation instance.
pub struct Fmu2 {
    pub lib: Arc<Library>,
    pub c: *mut c_void,
    pub log: Box<Log>,
    _callbacks: Box<Fmi2Callbacks>,
}

type Call0 = unsafe extern "C" fn(*mut c_void) -> c_int;

impl Fmu2 {
    /// `fmi2Instantiate` with the given GUID (`None`: the right one); null on refusal.
    pub fn try_new(lib: &Arc<Library>, guid: Option<&str>, logging_on: bool) -> (Option<Fmu2>, Box<Log>) {
        Self::try_new_named(lib, guid, logging_on, "beam")
    }

    /// [`Fmu2::try_new`] with the instance name.
    pub fn try_new_named(
        lib: &Arc<Library>,
        guid: Option<&str>,
        logging_on: bool,
        instance_name: &str,
    ) -> (Option<Fmu2>, Box<Log>) {
        Self::try_new_in(lib, guid, logging_on, instance_name, "file:///tmp/some%20dir/resources")
    }

    /// [`Fmu2::try_new_named`] with the resource location (a `file:` URI, as FMI 2 gives it).
    pub fn try_new_in(
        lib: &Arc<Library>,
        guid: Option<&str>,
        logging_on: bool,
        instance_name: &str,
        resource_location: &str,
    ) -> (Option<Fmu2>, Box<Log>) {
        let log = Box::new(Log::default());
        let callbacks = Box::new(Fmi2Callbacks {
            logger: Some(fmi2_logger),
            allocate_memory: std::ptr::null(),
            free_memory: std::ptr::null(),
            step_finished: std::ptr::null(),
            environment: &*log as *const Log as *mut c_void,
        });
        let token = guid.map(String::from).unwrap_or_else(beam_impact::fmi::description::token);
        let (name, guid, resources) = (
            CString::new(instance_name).unwrap(),
            CString::new(token).unwrap(),
            CString::new(resource_location).unwrap(),
        );
        let instantiate = sym!(
            lib,
            "fmi2Instantiate",
            unsafe extern "C" fn(
                *const c_char,
                c_int,
                *const c_char,
                *const c_char,
                *const Fmi2Callbacks,
                c_int,
                c_int,
            ) -> *mut c_void
        );
        // SAFETY: valid strings and callbacks that outlive the instance.
        let c = unsafe {
            instantiate(name.as_ptr(), 1, guid.as_ptr(), resources.as_ptr(), &*callbacks, 0, logging_on as c_int)
        };
        if c.is_null() {
            return (None, log);
        }
        let log2 = Box::new(Log::default());
        // The instance keeps the environment pointer of `log`: hand that box to the instance.
        let fmu = Fmu2 { lib: lib.clone(), c, log, _callbacks: callbacks };
        (Some(fmu), log2)
    }

    pub fn new(lib: &Arc<Library>) -> Fmu2 {
        Self::try_new(lib, None, true).0.expect("fmi2Instantiate returned null")
    }

    /// A logging instance named `instance_name`.
    pub fn new_named(lib: &Arc<Library>, instance_name: &str) -> Fmu2 {
        Self::try_new_named(lib, None, true, instance_name).0.expect("fmi2Instantiate returned null")
    }

    pub fn call0(&self, name: &str) -> c_int {
        let symbol = format!("{name}\0");
        // SAFETY: every fmi2 function taking only the component has this signature.
        let f: libloading::Symbol<Call0> = unsafe { self.lib.get(symbol.as_bytes()) }.unwrap();
        // SAFETY: a live component.
        unsafe { f(self.c) }
    }

    pub fn setup(&self, start: f64, stop: Option<f64>) -> c_int {
        let f = sym!(
            self.lib,
            "fmi2SetupExperiment",
            unsafe extern "C" fn(*mut c_void, c_int, f64, f64, c_int, f64) -> c_int
        );
        // SAFETY: a live component.
        unsafe { f(self.c, 0, 0.0, start, stop.is_some() as c_int, stop.unwrap_or(0.0)) }
    }

    /// SetupExperiment(0, stop 3), Enter/ExitInitializationMode.
    pub fn initialize(&self) -> c_int {
        let statuses = [self.setup(0.0, Some(3.0)), self.call0("fmi2EnterInitializationMode")];
        if statuses.iter().any(|&s| s != OK) {
            return ERROR;
        }
        self.call0("fmi2ExitInitializationMode")
    }

    pub fn get_reals(&self, vrs: &[u32]) -> (c_int, Vec<f64>) {
        let f = sym!(self.lib, "fmi2GetReal", unsafe extern "C" fn(*mut c_void, *const u32, usize, *mut f64) -> c_int);
        let mut values = vec![f64::NAN; vrs.len()];
        // SAFETY: arrays of the given length.
        let status = unsafe { f(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        (status, values)
    }

    pub fn get(&self, name: &str) -> f64 {
        let (status, values) = self.get_reals(&[vr(name)]);
        assert_eq!(status, OK, "fmi2GetReal({name}): {}", self.log.text());
        values[0]
    }

    pub fn set_reals(&self, vrs: &[u32], values: &[f64]) -> c_int {
        let f =
            sym!(self.lib, "fmi2SetReal", unsafe extern "C" fn(*mut c_void, *const u32, usize, *const f64) -> c_int);
        assert_eq!(vrs.len(), values.len());
        // SAFETY: arrays of the given length.
        unsafe { f(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr()) }
    }

    pub fn set(&self, name: &str, value: f64) -> c_int {
        self.set_reals(&[vr(name)], &[value])
    }

    pub fn set_string(&self, name: &str, value: &str) -> c_int {
        let f = sym!(
            self.lib,
            "fmi2SetString",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *const *const c_char) -> c_int
        );
        let value = CString::new(value).unwrap();
        let pointers = [value.as_ptr()];
        // SAFETY: one value reference and one string.
        unsafe { f(self.c, [vr(name)].as_ptr(), 1, pointers.as_ptr()) }
    }

    pub fn set_boolean(&self, name: &str, value: bool) -> c_int {
        let f = sym!(
            self.lib,
            "fmi2SetBoolean",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *const c_int) -> c_int
        );
        // SAFETY: one value reference and one value.
        unsafe { f(self.c, [vr(name)].as_ptr(), 1, &c_int::from(value)) }
    }

    pub fn get_boolean(&self, name: &str) -> bool {
        let f =
            sym!(self.lib, "fmi2GetBoolean", unsafe extern "C" fn(*mut c_void, *const u32, usize, *mut c_int) -> c_int);
        let mut value: c_int = -1;
        // SAFETY: one value.
        assert_eq!(unsafe { f(self.c, [vr(name)].as_ptr(), 1, &mut value) }, OK);
        value != 0
    }

    pub fn set_integer(&self, name: &str, value: c_int) -> c_int {
        let f = sym!(
            self.lib,
            "fmi2SetInteger",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *const c_int) -> c_int
        );
        // SAFETY: one value reference and one value.
        unsafe { f(self.c, [vr(name)].as_ptr(), 1, &value) }
    }

    pub fn get_integer(&self, name: &str) -> c_int {
        let f =
            sym!(self.lib, "fmi2GetInteger", unsafe extern "C" fn(*mut c_void, *const u32, usize, *mut c_int) -> c_int);
        let mut value: c_int = -1;
        // SAFETY: one value.
        assert_eq!(unsafe { f(self.c, [vr(name)].as_ptr(), 1, &mut value) }, OK, "{}", self.log.text());
        value
    }

    pub fn do_step(&self, t: f64, h: f64) -> c_int {
        let f = sym!(self.lib, "fmi2DoStep", unsafe extern "C" fn(*mut c_void, f64, f64, c_int) -> c_int);
        // SAFETY: a live component.
        unsafe { f(self.c, t, h, 1) }
    }

    /// fmpy's loop: communication points start + (n + 1) * interval, steps next - t.
    pub fn run(&self, start: f64, stop: f64, interval: f64) {
        let mut t = start;
        let mut n = 0u64;
        while t < stop && (stop - t).abs() > 1e-12 {
            let next = (start + (n + 1) as f64 * interval).min(stop);
            assert_eq!(self.do_step(t, next - t), OK, "fmi2DoStep at {t}: {}", self.log.text());
            t = next;
            n += 1;
        }
    }

    state_calls!(FMI2_STATES);
}

impl Drop for Fmu2 {
    fn drop(&mut self) {
        let f = sym!(self.lib, "fmi2FreeInstance", unsafe extern "C" fn(*mut c_void));
        // SAFETY: freed once.
        unsafe { f(self.c) }
    }
}

/// An FMI 3.0 co-simulation instance.
pub struct Fmu3 {
    pub lib: Arc<Library>,
    pub c: *mut c_void,
    pub log: Box<Log>,
}

impl Fmu3 {
    pub fn try_new(lib: &Arc<Library>, token: Option<&str>, early_return: bool) -> (Option<Fmu3>, Box<Log>) {
        Self::try_new_in(lib, token, early_return, "/tmp/x/resources/")
    }

    /// [`Fmu3::try_new`] with the resource path (a plain path, as FMI 3 gives it).
    pub fn try_new_in(
        lib: &Arc<Library>,
        token: Option<&str>,
        early_return: bool,
        resource_path: &str,
    ) -> (Option<Fmu3>, Box<Log>) {
        let log = Box::new(Log::default());
        let token = token.map(String::from).unwrap_or_else(beam_impact::fmi::description::token);
        let (name, token, resources) =
            (CString::new("beam3").unwrap(), CString::new(token).unwrap(), CString::new(resource_path).unwrap());
        let instantiate = sym!(
            lib,
            "fmi3InstantiateCoSimulation",
            unsafe extern "C" fn(
                *const c_char,
                *const c_char,
                *const c_char,
                bool,
                bool,
                bool,
                bool,
                *const u32,
                usize,
                *mut c_void,
                Option<unsafe extern "C" fn(*mut c_void, c_int, *const c_char, *const c_char)>,
                *const c_void,
            ) -> *mut c_void
        );
        // SAFETY: valid strings; the environment outlives the instance.
        let c = unsafe {
            instantiate(
                name.as_ptr(),
                token.as_ptr(),
                resources.as_ptr(),
                false,
                true,
                false,
                early_return,
                std::ptr::null(),
                0,
                &*log as *const Log as *mut c_void,
                Some(fmi3_logger),
                std::ptr::null(),
            )
        };
        if c.is_null() {
            return (None, log);
        }
        (Some(Fmu3 { lib: lib.clone(), c, log }), Box::new(Log::default()))
    }

    pub fn initialize(&self) -> c_int {
        self.initialize_until(None)
    }

    /// Enter and exit initialization mode at t = 0, with the stop time if given.
    pub fn initialize_until(&self, stop: Option<f64>) -> c_int {
        self.initialize_at(0.0, stop)
    }

    pub fn set_string(&self, name: &str, value: &str) -> c_int {
        let f = sym!(
            self.lib,
            "fmi3SetString",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *const *const c_char, usize) -> c_int
        );
        let value = CString::new(value).unwrap();
        let pointers = [value.as_ptr()];
        // SAFETY: one value reference and one string.
        unsafe { f(self.c, [vr(name)].as_ptr(), 1, pointers.as_ptr(), 1) }
    }

    /// `fmi3GetFloat64` of one variable: (status, value).
    pub fn try_get(&self, name: &str) -> (c_int, f64) {
        let f = sym!(
            self.lib,
            "fmi3GetFloat64",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *mut f64, usize) -> c_int
        );
        let mut value = f64::NAN;
        // SAFETY: one value.
        let status = unsafe { f(self.c, [vr(name)].as_ptr(), 1, &mut value, 1) };
        (status, value)
    }

    pub fn get(&self, name: &str) -> f64 {
        let (status, value) = self.try_get(name);
        assert_eq!(status, OK, "fmi3GetFloat64({name}): {}", self.log.text());
        value
    }

    pub fn set(&self, name: &str, value: f64) -> c_int {
        let f = sym!(
            self.lib,
            "fmi3SetFloat64",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *const f64, usize) -> c_int
        );
        // SAFETY: one value reference and one value.
        unsafe { f(self.c, [vr(name)].as_ptr(), 1, &value, 1) }
    }

    pub fn get_boolean(&self, name: &str) -> bool {
        let f = sym!(
            self.lib,
            "fmi3GetBoolean",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *mut bool, usize) -> c_int
        );
        let mut value = false;
        // SAFETY: one value.
        assert_eq!(unsafe { f(self.c, [vr(name)].as_ptr(), 1, &mut value, 1) }, OK, "{}", self.log.text());
        value
    }

    pub fn set_integer(&self, name: &str, value: i32) -> c_int {
        let f = sym!(
            self.lib,
            "fmi3SetInt32",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *const i32, usize) -> c_int
        );
        // SAFETY: one value reference and one value.
        unsafe { f(self.c, [vr(name)].as_ptr(), 1, &value, 1) }
    }

    pub fn call0(&self, name: &str) -> c_int {
        let symbol = format!("{name}\0");
        // SAFETY: every fmi3 function taking only the instance has this signature.
        let f: libloading::Symbol<Call0> = unsafe { self.lib.get(symbol.as_bytes()) }.unwrap();
        // SAFETY: a live instance.
        unsafe { f(self.c) }
    }

    state_calls!(FMI3_STATES);

    /// Enter and exit initialization mode at `start`, with the stop time if given.
    pub fn initialize_at(&self, start: f64, stop: Option<f64>) -> c_int {
        let enter = sym!(
            self.lib,
            "fmi3EnterInitializationMode",
            unsafe extern "C" fn(*mut c_void, bool, f64, f64, bool, f64) -> c_int
        );
        let exit = sym!(self.lib, "fmi3ExitInitializationMode", unsafe extern "C" fn(*mut c_void) -> c_int);
        // SAFETY: a live instance.
        let status = unsafe { enter(self.c, false, 0.0, start, stop.is_some(), stop.unwrap_or(0.0)) };
        if status != OK {
            return status;
        }
        // SAFETY: a live instance.
        unsafe { exit(self.c) }
    }

    /// fmpy's loop from `start` to `stop` at `interval`, without early return.
    pub fn run(&self, start: f64, stop: f64, interval: f64) {
        let mut t = start;
        let mut n = 0u64;
        while t < stop && (stop - t).abs() > 1e-12 {
            let next = (start + (n + 1) as f64 * interval).min(stop);
            let (status, _, _) = self.do_step(t, next - t);
            assert_eq!(status, OK, "fmi3DoStep at {t}: {}", self.log.text());
            t = next;
            n += 1;
        }
    }

    /// `fmi3GetFloat64` of several variables.
    pub fn get_reals(&self, vrs: &[u32]) -> (c_int, Vec<f64>) {
        let f = sym!(
            self.lib,
            "fmi3GetFloat64",
            unsafe extern "C" fn(*mut c_void, *const u32, usize, *mut f64, usize) -> c_int
        );
        let mut values = vec![f64::NAN; vrs.len()];
        // SAFETY: arrays of the given length.
        let status = unsafe { f(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr(), vrs.len()) };
        (status, values)
    }

    /// `fmi3DoStep`: (status, earlyReturn, lastSuccessfulTime).
    pub fn do_step(&self, t: f64, h: f64) -> (c_int, bool, f64) {
        let f = sym!(
            self.lib,
            "fmi3DoStep",
            unsafe extern "C" fn(*mut c_void, f64, f64, bool, *mut bool, *mut bool, *mut bool, *mut f64) -> c_int
        );
        let (mut event, mut terminate, mut early, mut last) = (false, false, false, f64::NAN);
        // SAFETY: out-pointers.
        let status = unsafe { f(self.c, t, h, true, &mut event, &mut terminate, &mut early, &mut last) };
        (status, early, last)
    }
}

impl Drop for Fmu3 {
    fn drop(&mut self) {
        let f = sym!(self.lib, "fmi3FreeInstance", unsafe extern "C" fn(*mut c_void));
        // SAFETY: freed once.
        unsafe { f(self.c) }
    }
}

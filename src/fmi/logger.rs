//! The importer's logging callbacks (the C types of FMI 2 and FMI 3) and the one place that
//! calls them. Here, below `instance.rs`, `fmi2.rs` and `fmi3.rs`, so that the instance needs
//! neither of the two API files that use it.

use std::ffi::{c_char, c_void, CString};

use super::status::Status;

/// `fmi2CallbackLogger`: printf-style; this FMU always passes the format `"%s"` and one string.
pub type Fmi2CallbackLogger = Option<
    unsafe extern "C" fn(
        component_environment: *mut c_void,
        instance_name: *const c_char,
        status: Status,
        category: *const c_char,
        message: *const c_char,
        ...
    ),
>;

/// `fmi3LogMessageCallback`.
pub type Fmi3LogMessageCallback = Option<
    unsafe extern "C" fn(
        instance_environment: *mut c_void,
        status: Status,
        category: *const c_char,
        message: *const c_char,
    ),
>;

/// The importer's logging callback, handed back its environment pointer untouched.
#[derive(Clone, Copy, Debug)]
pub enum Logger {
    /// FMI 2: printf-style, always called with the format `"%s"`.
    Fmi2 {
        /// The callback.
        callback: Fmi2CallbackLogger,
        /// `componentEnvironment`.
        environment: *mut c_void,
    },
    /// FMI 3: `logMessage(env, status, category, message)`.
    Fmi3 {
        /// The callback.
        callback: Fmi3LogMessageCallback,
        /// `instanceEnvironment`.
        environment: *mut c_void,
    },
}

/// Turns text into a C string, replacing interior NULs.
pub fn c_string(text: &str) -> CString {
    CString::new(text.replace('\0', "\u{fffd}")).unwrap_or_default()
}

/// Logs a message through a logger without an instance (failed instantiation).
pub fn log_with(logger: Logger, instance_name: &str, status: Status, category: &str, message: &str) {
    let (name, category, message) = (c_string(instance_name), c_string(category), c_string(message));
    match logger {
        Logger::Fmi2 { callback: Some(f), environment } => {
            // SAFETY: the importer's callback with NUL-terminated strings that outlive the call;
            // the format is always "%s" with exactly one string argument.
            unsafe {
                f(environment, name.as_ptr(), status, category.as_ptr(), c"%s".as_ptr(), message.as_ptr());
            }
        }
        Logger::Fmi3 { callback: Some(f), environment } => {
            // SAFETY: the importer's callback with NUL-terminated strings that outlive the call.
            unsafe { f(environment, status, category.as_ptr(), message.as_ptr()) }
        }
        _ => {}
    }
}

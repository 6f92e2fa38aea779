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

/// A number for a message, bounded in length (issue 27: `{}` of 1e300 is 301 digits, of 1e-300
/// 302 characters): as Rust prints it (the shortest text that reads back to the same number) for
/// magnitudes from 1e-4 to below 1e7, and 0, NaN and inf; in exponent form (`1e300`) beyond.
pub fn number(x: f64) -> String {
    crate::error::number(x)
}

/// `x` to `digits` significant digits (at least 1), bounded in length like [`number`]: fixed
/// decimals for magnitudes from 1e-4 to below 1e7, exponent form beyond.
pub fn significant(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    if (1e-4..1e7).contains(&x.abs()) {
        let magnitude = libm::log10(x.abs()).floor() as i32;
        let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.*e}", digits - 1)
    }
}

/// The most digits a number keeps in a logged message; a longer run is rewritten by
/// [`bound_numbers`]. 21 digits hold every f64 that `{}` prints below 1e21 and any integer of the
/// FMU's (a u64 has 20).
pub const MAX_MESSAGE_DIGITS: usize = 21;

/// `text` with every number of more than [`MAX_MESSAGE_DIGITS`] digits (a run of digits, with a
/// fraction if any) rewritten in exponent form: the last guard for numbers the library formats
/// with `{}` into the errors the FMU logs (a forged state's tip force of 1e300 N, a parameter of
/// 1e300), so that no logged message carries hundreds of digits.
pub fn bound_numbers(text: &str) -> std::borrow::Cow<'_, str> {
    let bytes = text.as_bytes();
    let digits_from = |mut i: usize| {
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut out = String::new();
    let (mut copied, mut i) = (0, 0);
    while i < bytes.len() {
        if !bytes[i].is_ascii_digit() {
            i += 1;
            continue;
        }
        let start = i;
        i = digits_from(i);
        if i + 1 < bytes.len() && bytes[i] == b'.' && bytes[i + 1].is_ascii_digit() {
            i = digits_from(i + 1);
        }
        // ASCII digits and one '.': a char boundary on both sides.
        let token = &text[start..i];
        if token.len() - usize::from(token.contains('.')) > MAX_MESSAGE_DIGITS {
            if let Ok(value) = token.parse::<f64>() {
                out.push_str(&text[copied..start]);
                out.push_str(&format!("{value:e}"));
                copied = i;
            }
        }
    }
    if copied == 0 {
        return std::borrow::Cow::Borrowed(text);
    }
    out.push_str(&text[copied..]);
    std::borrow::Cow::Owned(out)
}

/// Logs a message through a logger without an instance (failed instantiation). Numbers of more
/// than [`MAX_MESSAGE_DIGITS`] digits are shortened ([`bound_numbers`]), and control characters
/// (a hostile `log.path`'s escape sequences and newlines) are escaped, never sent to the
/// importer's log (issue 40's re-test; docs/security.md).
pub fn log_with(logger: Logger, instance_name: &str, status: Status, category: &str, message: &str) {
    let message = crate::record::output::escape_controls(message);
    let message = bound_numbers(&message);
    let (name, category, message) = (c_string(instance_name), c_string(category), c_string(&message));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_plain_in_the_usual_range_and_exponents_beyond() {
        assert_eq!(number(0.5), "0.5");
        assert_eq!(number(-1e-3), "-0.001");
        assert_eq!(number(3.0), "3");
        assert_eq!(number(1e300), "1e300");
        assert_eq!(number(-1e-300), "-1e-300");
        assert_eq!(number(f64::NAN), "NaN");
        for x in [f64::MAX, f64::MIN_POSITIVE, 1.2345678901234567e7, 9.87654321e-5] {
            assert!(number(x).len() <= 24, "{x}: {}", number(x));
            assert_eq!(number(x).parse::<f64>().unwrap(), x);
        }
    }

    #[test]
    fn significant_digits_are_fixed_and_bounded() {
        assert_eq!(significant(-2.34567, 5), "-2.3457");
        assert_eq!(significant(0.05, 3), "0.0500");
        assert_eq!(significant(1234.4, 3), "1234");
        assert_eq!(significant(1.5e154, 5), "1.5000e154");
        assert_eq!(significant(-3e-9, 2), "-3.0e-9");
        assert_eq!(significant(0.0, 5), "0");
    }

    #[test]
    fn long_numbers_in_a_message_are_rewritten_and_the_rest_kept() {
        let huge = format!("got {} N, step 12345, path /a/b-20261123T000000Z-1.mcap", 1e300);
        assert_eq!(bound_numbers(&huge), "got 1e300 N, step 12345, path /a/b-20261123T000000Z-1.mcap");
        let velocity = format!("relative velocity {:.4} m/s", -1.234e154);
        let bounded = bound_numbers(&velocity);
        assert!(bounded.len() < 50 && bounded.contains("e154 m/s") && bounded.contains("-1.234"), "{bounded}");
        let tiny = format!("at {} s", 1e-300);
        assert_eq!(bound_numbers(&tiny), "at 1e-300 s");
        let untouched = format!("u64 {} and {}", u64::MAX, 1e20);
        assert!(matches!(bound_numbers(&untouched), std::borrow::Cow::Borrowed(_)));
    }
}

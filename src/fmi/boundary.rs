//! The panic boundary and the pointer checks every exported function goes through.
//!
//! A panic that unwinds out of an `extern "C"` function aborts the host process, so every
//! exported body runs inside [`ffi_boundary!`](crate::ffi_boundary), which turns a panic into
//! the fallback value of the function's return type ([`Fallback`]): `Fatal` for a status, a null
//! pointer for an instance, nothing for `()`. Panics inside an instance's own work are caught
//! one level deeper by [`super::instance::Instance::guard`], which also logs them.

use std::any::Any;
use std::ffi::{c_char, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};

use super::status::Status;

/// What an exported function returns when its body panicked.
pub trait Fallback {
    /// The value returned after a panic.
    const PANICKED: Self;
}

impl Fallback for Status {
    const PANICKED: Self = Status::Fatal;
}

impl<T> Fallback for *mut T {
    const PANICKED: Self = std::ptr::null_mut();
}

impl<T> Fallback for *const T {
    const PANICKED: Self = std::ptr::null();
}

impl Fallback for () {
    const PANICKED: Self = ();
}

/// Runs `body`, returning [`Fallback::PANICKED`] if it panics. Use it through
/// [`ffi_boundary!`](crate::ffi_boundary).
pub fn catch<R: Fallback>(body: impl FnOnce() -> R) -> R {
    catch_unwind(AssertUnwindSafe(body)).unwrap_or(R::PANICKED)
}

/// The message of a caught panic.
pub fn panic_message(payload: &(dyn Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".to_string()
    }
}

/// Wraps the body of an exported function: a panic becomes the return type's fallback
/// (see [`Fallback`]) instead of unwinding into C.
#[macro_export]
macro_rules! ffi_boundary {
    ($($body:tt)*) => {
        $crate::fmi::boundary::catch(move || { $($body)* })
    };
}

/// Why a pointer argument was refused.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NullArgument(pub &'static str);

impl std::fmt::Display for NullArgument {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "argument `{}` is a null pointer", self.0)
    }
}

/// A C array as a slice: zero length first (any pointer, even null, gives an empty slice), then
/// null.
///
/// # Safety
/// When `len > 0` and `ptr` is not null, `ptr` must point to `len` readable values that stay
/// valid and unaliased by writes for `'a`.
pub unsafe fn slice<'a, T>(ptr: *const T, len: usize, name: &'static str) -> Result<&'a [T], NullArgument> {
    if len == 0 {
        Ok(&[])
    } else if ptr.is_null() {
        Err(NullArgument(name))
    } else {
        // SAFETY: non-null, and the caller guarantees `len` valid values.
        Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
    }
}

/// A writable C array as a mutable slice: zero length first, then null.
///
/// # Safety
/// When `len > 0` and `ptr` is not null, `ptr` must point to `len` writable values that no one
/// else accesses for `'a`.
pub unsafe fn slice_mut<'a, T>(ptr: *mut T, len: usize, name: &'static str) -> Result<&'a mut [T], NullArgument> {
    if len == 0 {
        Ok(&mut [])
    } else if ptr.is_null() {
        Err(NullArgument(name))
    } else {
        // SAFETY: non-null, and the caller guarantees `len` exclusive values.
        Ok(unsafe { std::slice::from_raw_parts_mut(ptr, len) })
    }
}

/// One writable value (an out-parameter).
///
/// # Safety
/// A non-null `ptr` must be valid for writes for `'a`.
pub unsafe fn out<'a, T>(ptr: *mut T, name: &'static str) -> Result<&'a mut T, NullArgument> {
    // SAFETY: the caller guarantees validity when non-null.
    unsafe { ptr.as_mut() }.ok_or(NullArgument(name))
}

/// A NUL-terminated C string as UTF-8 text (invalid UTF-8 is replaced).
///
/// # Safety
/// A non-null `ptr` must point to a NUL-terminated string valid for `'a`.
pub unsafe fn string(ptr: *const c_char, name: &'static str) -> Result<String, NullArgument> {
    if ptr.is_null() {
        return Err(NullArgument(name));
    }
    // SAFETY: non-null and NUL-terminated by the caller's contract.
    Ok(unsafe { CStr::from_ptr(ptr) }.to_string_lossy().into_owned())
}

/// A NUL-terminated C string that must be UTF-8 (a value such as a path: rewriting invalid bytes
/// would silently name another file).
///
/// # Safety
/// A non-null `ptr` must point to a NUL-terminated string valid for `'a`.
pub unsafe fn utf8_string(ptr: *const c_char, name: &'static str) -> Result<String, String> {
    if ptr.is_null() {
        return Err(NullArgument(name).to_string());
    }
    // SAFETY: non-null and NUL-terminated by the caller's contract.
    let bytes = unsafe { CStr::from_ptr(ptr) };
    bytes
        .to_str()
        .map(str::to_owned)
        .map_err(|e| format!("{name} is not valid UTF-8 ({e}): a path is taken as given or refused, never rewritten"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_length_accepts_null_then_null_is_refused() {
        // SAFETY: zero length never dereferences.
        let empty: &[f64] = unsafe { slice(std::ptr::null(), 0, "values") }.unwrap();
        assert!(empty.is_empty());
        // SAFETY: null is refused before any dereference.
        let err = unsafe { slice::<f64>(std::ptr::null(), 3, "values") }.unwrap_err();
        assert_eq!(err.to_string(), "argument `values` is a null pointer");
    }

    #[test]
    fn a_panic_becomes_the_fallback() {
        let status: Status = catch(|| panic!("boom"));
        assert_eq!(status, Status::Fatal);
        let ptr: *mut u8 = catch(|| panic!("boom"));
        assert!(ptr.is_null());
    }
}

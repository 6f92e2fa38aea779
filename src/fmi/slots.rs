//! The importer's FMU state handles (`fmi2FMUstate`, `fmi3FMUState`): boxed [`Snapshot`]s the
//! importer holds between calls. One implementation for the FMI 2 and FMI 3 functions, which
//! differ only in names.

use super::boundary::{out, slice, slice_mut};
use super::instance::Outcome;
use super::state::Snapshot;
use super::status::Status;

/// Puts `snapshot` into the importer's slot: overwrites the snapshot a non-null `*slot` points
/// to (the standard's "update an existing state"), or allocates a new one.
///
/// # Safety
/// `slot` is null or valid for writes; a non-null `*slot` is a snapshot allocated here and not
/// yet freed.
pub unsafe fn store(slot: *mut *mut Snapshot, name: &'static str, snapshot: Snapshot) -> Outcome<Status> {
    let slot = unsafe { out(slot, name) }.map_err(|e| e.to_string())?;
    // SAFETY: a non-null *slot is a snapshot allocated here and not yet freed (caller's contract).
    match unsafe { slot.as_mut() } {
        Some(existing) => *existing = snapshot,
        None => *slot = Box::into_raw(Box::new(snapshot)),
    }
    Ok(Status::Ok)
}

/// Frees the snapshot `*slot` points to (if any) and sets `*slot` to null. A null `slot` or a null
/// `*slot` is ignored (FMI 2.0 and 3.0: "If a null pointer is provided, the call is ignored").
///
/// # Safety
/// As for [`store`].
pub unsafe fn free(slot: *mut *mut Snapshot) -> Outcome<Status> {
    // SAFETY: null or valid for writes (caller's contract).
    let Some(slot) = (unsafe { slot.as_mut() }) else { return Ok(Status::Ok) };
    if !slot.is_null() {
        // SAFETY: allocated by Box::into_raw in `store` and not yet freed.
        drop(unsafe { Box::from_raw(*slot) });
        *slot = std::ptr::null_mut();
    }
    Ok(Status::Ok)
}

/// The snapshot a handle points to.
///
/// # Safety
/// A non-null `state` is a snapshot allocated by [`store`] and not yet freed.
pub unsafe fn borrow<'a>(state: *const Snapshot, name: &'static str) -> Outcome<&'a Snapshot> {
    // SAFETY: the caller's contract.
    unsafe { state.as_ref() }.ok_or_else(|| format!("argument `{name}` is a null pointer"))
}

/// Writes the size of the snapshot's portable bytes to `*size`.
///
/// # Safety
/// As for [`borrow`]; `size` is null or valid for writes.
pub unsafe fn serialized_size(state: *const Snapshot, name: &'static str, size: *mut usize) -> Outcome<Status> {
    let size = unsafe { out(size, "size") }.map_err(|e| e.to_string())?;
    *size = unsafe { borrow(state, name) }?.to_bytes().map_err(|e| e.to_string())?.len();
    Ok(Status::Ok)
}

/// Writes the snapshot's portable bytes to `target`, which must hold exactly `size` bytes (the
/// size `size_function` reported).
///
/// # Safety
/// As for [`borrow`]; a non-null `target` is valid for `size` byte writes.
pub unsafe fn serialize(
    state: *const Snapshot,
    name: &'static str,
    target: *mut u8,
    size: usize,
    size_function: &str,
) -> Outcome<Status> {
    let bytes = unsafe { borrow(state, name) }?.to_bytes().map_err(|e| e.to_string())?;
    if size != bytes.len() {
        return Err(format!("size = {size}, the state needs {} bytes ({size_function})", bytes.len()));
    }
    let target = unsafe { slice_mut(target, size, "serializedState") }.map_err(|e| e.to_string())?;
    target.copy_from_slice(&bytes);
    Ok(Status::Ok)
}

/// Reads portable bytes (from any process running this binary) into the importer's slot.
///
/// # Safety
/// A non-null `bytes` is valid for `size` byte reads; `slot` as for [`store`].
pub unsafe fn deserialize(
    bytes: *const u8,
    size: usize,
    slot: *mut *mut Snapshot,
    name: &'static str,
) -> Outcome<Status> {
    let bytes = unsafe { slice(bytes, size, "serializedState") }.map_err(|e| e.to_string())?;
    let snapshot = Snapshot::from_bytes(bytes).map_err(|e| e.to_string())?;
    unsafe { store(slot, name, snapshot) }
}

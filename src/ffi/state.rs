//! FMU states (FMI 2.0.4 §2.1.8): get/set/free and (de)serialisation. An `fmi2FMUstate` is a
//! `Box<Snapshot>`; serialised bytes follow the format documented in `fmu::snapshot`.

use super::guard::{ffi_fn, non_null, slice, with_instance};
use super::types::*;
use crate::fmu::{FmuError, Op, Snapshot, Status};

/// The snapshot behind an FMU state pointer.
///
/// # Safety
/// `s` must be NULL or a pointer produced by `fmi2GetFMUstate`/`fmi2DeSerializeFMUstate` and
/// not yet freed.
unsafe fn snapshot<'a>(s: fmi2FMUstate) -> Result<&'a Snapshot, FmuError> {
    non_null!(s, "FMUstate");
    // SAFETY: non-NULL, a live Box<Snapshot> per the caller's contract.
    Ok(unsafe { &*s.cast::<Snapshot>() })
}

/// Stores `snap` in `*state`: overwrites the existing snapshot if `*state` is non-NULL
/// (FMI 2.0.4: a previously returned state may be reused), else allocates.
///
/// # Safety
/// `state` non-NULL and valid for writes; `*state` NULL or a live snapshot of ours.
unsafe fn store(state: *mut fmi2FMUstate, snap: Snapshot) {
    // SAFETY: state is valid for reads/writes per the caller.
    let slot = unsafe { &mut *state };
    if slot.is_null() {
        *slot = Box::into_raw(Box::new(snap)).cast();
    } else {
        // SAFETY: a live Box<Snapshot> from an earlier call, per the caller.
        unsafe { *slot.cast::<Snapshot>() = snap };
    }
}

ffi_fn! {
    /// `fmi2GetFMUstate` (FMI 2.0.4 §2.1.8): a complete copy of the instance's state.
    fn fmi2GetFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c and FMUstate (checked for NULL).
        unsafe {
            with_instance(c, "fmi2GetFMUstate", |i| {
                non_null!(FMUstate, "FMUstate");
                let snap = i.get_fmu_state()?;
                store(FMUstate, snap);
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2SetFMUstate` (FMI 2.0.4 §2.1.8): restores a state of the same model (GUID checked);
    /// the continuation is bit-identical to the original run.
    fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c and FMUstate.
        unsafe {
            with_instance(c, "fmi2SetFMUstate", |i| {
                let snap = snapshot(FMUstate)?;
                i.set_fmu_state(snap)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2FreeFMUstate` (FMI 2.0.4 §2.1.8): frees `*FMUstate` and sets it to NULL (NULL: no-op).
    fn fmi2FreeFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c and FMUstate.
        unsafe {
            with_instance(c, "fmi2FreeFMUstate", |i| {
                i.check(Op::FmuState, "fmi2FreeFMUstate")?;
                if FMUstate.is_null() || (*FMUstate).is_null() {
                    return Ok(Status::Ok);
                }
                drop(Box::from_raw((*FMUstate).cast::<Snapshot>()));
                *FMUstate = std::ptr::null_mut();
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2SerializedFMUstateSize` (FMI 2.0.4 §2.1.8).
    fn fmi2SerializedFMUstateSize(c: fmi2Component, FMUstate: fmi2FMUstate, size: *mut usize) -> fmi2Status {
        // SAFETY: FMI contract on c, FMUstate and size (checked for NULL).
        unsafe {
            with_instance(c, "fmi2SerializedFMUstateSize", |i| {
                i.check(Op::FmuState, "fmi2SerializedFMUstateSize")?;
                non_null!(size, "size");
                *size = snapshot(FMUstate)?.to_bytes().len();
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2SerializeFMUstate` (FMI 2.0.4 §2.1.8): pointer-free, versioned little-endian bytes.
    fn fmi2SerializeFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate, serializedState: *mut fmi2Byte, size: usize) -> fmi2Status {
        // SAFETY: FMI contract on c, FMUstate and the buffer of `size` bytes.
        unsafe {
            with_instance(c, "fmi2SerializeFMUstate", |i| {
                i.check(Op::FmuState, "fmi2SerializeFMUstate")?;
                let bytes = snapshot(FMUstate)?.to_bytes();
                if size < bytes.len() {
                    return Err(FmuError::rejected(format!("buffer of {size} bytes is too small for {} bytes", bytes.len())));
                }
                non_null!(serializedState, "serializedState");
                std::ptr::copy_nonoverlapping(bytes.as_ptr(), serializedState.cast::<u8>(), bytes.len());
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2DeSerializeFMUstate` (FMI 2.0.4 §2.1.8): parses and checks the bytes (magic, version,
    /// GUID of this model) into a newly allocated FMU state (`*FMUstate` is output only).
    fn fmi2DeSerializeFMUstate(c: fmi2Component, serializedState: *const fmi2Byte, size: usize, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c, the buffer of `size` bytes and FMUstate.
        unsafe {
            with_instance(c, "fmi2DeSerializeFMUstate", |i| {
                i.check(Op::FmuState, "fmi2DeSerializeFMUstate")?;
                non_null!(FMUstate, "FMUstate");
                let bytes = slice(serializedState.cast::<u8>(), size, "serializedState")?;
                let snap = Snapshot::from_bytes(bytes).map_err(FmuError::Rejected)?;
                if snap.guid() != i.guid() {
                    return Err(FmuError::rejected(format!("serialized FMU state belongs to model {} (this is {})", snap.guid(), i.guid())));
                }
                *FMUstate = Box::into_raw(Box::new(snap)).cast();
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

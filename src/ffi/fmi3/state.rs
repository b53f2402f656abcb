//! FMU states (FMI 3.0 §2.3.6): the same snapshots and process-wide registry as FMI 2
//! (`ffi::state`, `ffi::registry`), so a state moves between instances of a model, FMI 2 or 3.

use super::types::*;
use crate::ffi::guard::{ffi_fn, non_null, slice, with_component};
use crate::ffi::registry;
use crate::ffi::state::{owner, same_model, store, with_snapshot, NOT_LIVE};
use crate::fmu::{FmuError, Op, Snapshot, Status};

ffi_fn! {
    /// `fmi3GetFMUState`: a complete copy of the instance's state (a live state of this model
    /// in `*FMUState` is overwritten).
    fn fmi3GetFMUState(instance: fmi3Instance, FMUState: *mut fmi3FMUState) -> fmi3Status {
        // SAFETY: FMI contract on the instance and FMUState (checked for NULL).
        unsafe {
            with_component(instance, "fmi3GetFMUState", |comp| {
                non_null!(FMUState, "FMUState");
                let snap = comp.instance.get_fmu_state()?;
                store(comp, FMUState, snap);
                Ok(Status::Ok)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3SetFMUState`: restores a live state of the same model, from this or any other live
    /// instance in the process; the continuation is bit-identical.
    fn fmi3SetFMUState(instance: fmi3Instance, FMUState: fmi3FMUState) -> fmi3Status {
        // SAFETY: FMI contract on the instance; FMUState is looked up, never dereferenced raw.
        unsafe {
            with_component(instance, "fmi3SetFMUState", |comp| {
                comp.instance.check(Op::FmuState, "fmi3SetFMUState")?;
                let snap = with_snapshot(FMUState, |s| s.clone())?;
                comp.instance.set_fmu_state(&snap)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3FreeFMUState`: frees `*FMUState` and sets it to NULL (NULL: no-op).
    fn fmi3FreeFMUState(instance: fmi3Instance, FMUState: *mut fmi3FMUState) -> fmi3Status {
        // SAFETY: FMI contract on the instance and FMUState (NULL checked before reading).
        unsafe {
            with_component(instance, "fmi3FreeFMUState", |comp| {
                comp.instance.check(Op::FmuState, "fmi3FreeFMUState")?;
                if FMUState.is_null() || (*FMUState).is_null() {
                    return Ok(Status::Ok);
                }
                registry::free(*FMUState as usize, |snap| same_model(comp, snap))
                    .ok_or_else(|| FmuError::rejected(NOT_LIVE))??;
                *FMUState = std::ptr::null_mut();
                Ok(Status::Ok)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3SerializedFMUStateSize`.
    fn fmi3SerializedFMUStateSize(instance: fmi3Instance, FMUState: fmi3FMUState, size: *mut usize) -> fmi3Status {
        // SAFETY: FMI contract on the instance, FMUState and size (checked for NULL).
        unsafe {
            with_component(instance, "fmi3SerializedFMUStateSize", |comp| {
                comp.instance.check(Op::FmuState, "fmi3SerializedFMUStateSize")?;
                non_null!(size, "size");
                *size = with_snapshot(FMUState, |s| same_model(comp, s).map(|()| s.to_bytes().len()))??;
                Ok(Status::Ok)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3SerializeFMUState`: the same pointer-free, versioned bytes as FMI 2.
    fn fmi3SerializeFMUState(instance: fmi3Instance, FMUState: fmi3FMUState, serializedState: *mut fmi3Byte, size: usize) -> fmi3Status {
        // SAFETY: FMI contract on the instance, FMUState and the buffer of `size` bytes.
        unsafe {
            with_component(instance, "fmi3SerializeFMUState", |comp| {
                comp.instance.check(Op::FmuState, "fmi3SerializeFMUState")?;
                let bytes = with_snapshot(FMUState, |s| same_model(comp, s).map(|()| s.to_bytes()))??;
                if size < bytes.len() {
                    return Err(FmuError::rejected(format!("buffer of {size} bytes is too small for {} bytes", bytes.len())));
                }
                non_null!(serializedState, "serializedState");
                std::ptr::copy_nonoverlapping(bytes.as_ptr(), serializedState, bytes.len());
                Ok(Status::Ok)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3DeserializeFMUState`: verifies the bytes (magic, version, checksum, this model's
    /// token, every field) into a newly allocated FMU state; any other buffer is refused.
    fn fmi3DeserializeFMUState(instance: fmi3Instance, serializedState: *const fmi3Byte, size: usize, FMUState: *mut fmi3FMUState) -> fmi3Status {
        // SAFETY: FMI contract on the instance, the buffer of `size` bytes and FMUState.
        unsafe {
            with_component(instance, "fmi3DeserializeFMUState", |comp| {
                comp.instance.check(Op::FmuState, "fmi3DeserializeFMUState")?;
                non_null!(FMUState, "FMUState");
                let bytes = slice(serializedState, size, "serializedState")?;
                let snap = Snapshot::from_bytes(bytes).map_err(FmuError::Rejected)?;
                comp.instance.verify_fmu_state(&snap)?;
                *FMUState = registry::insert(owner(comp), snap).cast();
                Ok(Status::Ok)
            })
        }
    } ?= fmi3Fatal
}

//! FMU states (FMI 2.0.4 §2.1.8): get/set/free and (de)serialisation. An `fmi2FMUstate` is a
//! `Box<Snapshot>` in the process-wide `registry`; serialised bytes follow the format documented in `fmu::snapshot`.

use super::guard::{ffi_fn, non_null, slice, with_component, Component};
use super::registry;
use super::types::*;
use crate::fmu::{FmuError, Op, Snapshot, Status};

pub(crate) const NOT_LIVE: &str =
    "FMUstate is not a live FMU state of this process (freed, its instance freed, or never handed out)";

/// The address that owns the states `comp` allocates.
pub(crate) fn owner(comp: &Component) -> usize {
    std::ptr::from_ref(comp) as usize
}

/// Runs `f` on the live FMU state `s` (any live instance's, see `registry`), or refuses a NULL
/// or unknown pointer without dereferencing it.
pub(crate) fn with_snapshot<R>(
    s: fmi2FMUstate,
    f: impl FnOnce(&mut Snapshot) -> R,
) -> Result<R, FmuError> {
    non_null!(s, "FMUstate");
    registry::with_state(s as usize, f).ok_or_else(|| FmuError::rejected(NOT_LIVE))
}

/// Refuses a state of another model loaded in the same process (another GUID).
pub(crate) fn same_model(comp: &Component, snap: &Snapshot) -> Result<(), FmuError> {
    let guid = comp.instance.guid();
    if snap.guid() == guid {
        Ok(())
    } else {
        Err(FmuError::rejected(format!(
            "FMU state belongs to model {} (this is {guid})",
            snap.guid()
        )))
    }
}

/// Stores `snap` in `*state`: overwrites the existing snapshot if `*state` is a live state of
/// this model (FMI 2.0.4: a previously returned state may be reused), else allocates and
/// registers a new one owned by `comp`.
///
/// # Safety
/// `state` non-NULL and valid for reads and writes.
pub(crate) unsafe fn store(comp: &Component, state: *mut fmi2FMUstate, snap: Snapshot) {
    // SAFETY: state is valid for reads/writes per the caller.
    let slot = unsafe { &mut *state };
    let mut snap = Some(snap);
    let guid = comp.instance.guid();
    let reused = !slot.is_null()
        && registry::with_state(*slot as usize, |old| {
            if old.guid() == guid {
                *old = snap.take().expect("moved once");
            }
        })
        .is_some()
        && snap.is_none();
    if !reused {
        let snap = snap.take().expect("not moved");
        *slot = registry::insert(owner(comp), snap).cast();
    }
}

ffi_fn! {
    /// `fmi2GetFMUstate` (FMI 2.0.4 §2.1.8): a complete copy of the instance's state.
    fn fmi2GetFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c and FMUstate (checked for NULL).
        unsafe {
            with_component(c, "fmi2GetFMUstate", |comp| {
                non_null!(FMUstate, "FMUstate");
                let snap = comp.instance.get_fmu_state()?;
                store(comp, FMUstate, snap);
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2SetFMUstate` (FMI 2.0.4 §2.1.8): restores a live state of the same model, got from
    /// this or any other live instance in the process (GUID and sizes checked); the continuation
    /// is bit-identical to the original run.
    fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c and FMUstate.
        unsafe {
            with_component(c, "fmi2SetFMUstate", |comp| {
                comp.instance.check(Op::FmuState, "fmi2SetFMUstate")?;
                // a copy, so the registry is not held while the model is rebuilt
                let snap = with_snapshot(FMUstate, |s| s.clone())?;
                comp.instance.set_fmu_state(&snap)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2FreeFMUstate` (FMI 2.0.4 §2.1.8): frees `*FMUstate` and sets it to NULL (NULL: no-op).
    /// Any live instance of the same model may free it (FMI does not say which must); a state of
    /// another model, or a pointer that is not a live state: `fmi2Error`, nothing freed.
    fn fmi2FreeFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c and FMUstate.
        unsafe {
            with_component(c, "fmi2FreeFMUstate", |comp| {
                comp.instance.check(Op::FmuState, "fmi2FreeFMUstate")?;
                if FMUstate.is_null() || (*FMUstate).is_null() {
                    return Ok(Status::Ok);
                }
                registry::free(*FMUstate as usize, |snap| same_model(comp, snap))
                    .ok_or_else(|| FmuError::rejected(NOT_LIVE))??;
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
            with_component(c, "fmi2SerializedFMUstateSize", |comp| {
                comp.instance.check(Op::FmuState, "fmi2SerializedFMUstateSize")?;
                non_null!(size, "size");
                *size = with_snapshot(FMUstate, |s| same_model(comp, s).map(|()| s.to_bytes().len()))??;
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
            with_component(c, "fmi2SerializeFMUstate", |comp| {
                comp.instance.check(Op::FmuState, "fmi2SerializeFMUstate")?;
                let bytes = with_snapshot(FMUstate, |s| same_model(comp, s).map(|()| s.to_bytes()))??;
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
    /// `fmi2DeSerializeFMUstate` (FMI 2.0.4 §2.1.8): parses and verifies the bytes (magic,
    /// version, checksum, GUID of this model, every field: see `fmu::snapshot`) into a newly
    /// allocated FMU state (`*FMUstate` is output only); any other buffer is refused.
    fn fmi2DeSerializeFMUstate(c: fmi2Component, serializedState: *const fmi2Byte, size: usize, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c, the buffer of `size` bytes and FMUstate.
        unsafe {
            with_component(c, "fmi2DeSerializeFMUstate", |comp| {
                comp.instance.check(Op::FmuState, "fmi2DeSerializeFMUstate")?;
                non_null!(FMUstate, "FMUstate");
                let bytes = slice(serializedState.cast::<u8>(), size, "serializedState")?;
                let snap = Snapshot::from_bytes(bytes).map_err(FmuError::Rejected)?;
                comp.instance.verify_fmu_state(&snap)?;
                *FMUstate = registry::insert(owner(comp), snap).cast();
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

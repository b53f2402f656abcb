//! FMU states (FMI 2.0.4 §2.1.8): get/set/free and (de)serialisation. An `fmi2FMUstate` is a
//! `Box<Snapshot>`; serialised bytes follow the format documented in `fmu::snapshot`.

use super::guard::{ffi_fn, non_null, slice, with_component, Component};
use super::types::*;
use crate::fmu::{FmuError, Op, Snapshot, Status};
use std::collections::HashSet;

/// The snapshot behind an FMU state pointer, if this instance handed it out and it is not freed.
/// `states` is the component's registry; the snapshot is borrowed for as long as it is.
fn snapshot(states: &HashSet<usize>, s: fmi2FMUstate) -> Result<&Snapshot, FmuError> {
    non_null!(s, "FMUstate");
    if !states.contains(&(s as usize)) {
        return Err(FmuError::rejected(
            "FMUstate is not a live FMU state of this instance (freed, or from elsewhere)",
        ));
    }
    // SAFETY: a registered address is a live Box<Snapshot> owned by this component.
    Ok(unsafe { &*s.cast::<Snapshot>() })
}

/// Stores `snap` in `*state`: overwrites the existing snapshot if `*state` is one of this
/// instance's live states (FMI 2.0.4: a previously returned state may be reused), else
/// allocates and registers a new one.
///
/// # Safety
/// `state` non-NULL and valid for reads and writes.
unsafe fn store(comp: &mut Component, state: *mut fmi2FMUstate, snap: Snapshot) {
    // SAFETY: state is valid for reads/writes per the caller.
    let slot = unsafe { &mut *state };
    if comp.states.contains(&(*slot as usize)) {
        // SAFETY: a registered address is a live Box<Snapshot> owned by this component.
        unsafe { *slot.cast::<Snapshot>() = snap };
    } else {
        let p = Box::into_raw(Box::new(snap));
        comp.states.insert(p as usize);
        *slot = p.cast();
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
    /// `fmi2SetFMUstate` (FMI 2.0.4 §2.1.8): restores a state of the same model (GUID checked);
    /// the continuation is bit-identical to the original run.
    fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c and FMUstate.
        unsafe {
            with_component(c, "fmi2SetFMUstate", |comp| {
                comp.instance.check(Op::FmuState, "fmi2SetFMUstate")?;
                // the registry and the instance are distinct fields: no copy of the state needed
                let Component { instance, states, .. } = comp;
                let snap = snapshot(states, FMUstate)?;
                instance.set_fmu_state(snap)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2FreeFMUstate` (FMI 2.0.4 §2.1.8): frees `*FMUstate` and sets it to NULL (NULL: no-op;
    /// a pointer this instance did not hand out, or freed already: `fmi2Error`).
    fn fmi2FreeFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: FMI contract on c and FMUstate.
        unsafe {
            with_component(c, "fmi2FreeFMUstate", |comp| {
                comp.instance.check(Op::FmuState, "fmi2FreeFMUstate")?;
                if FMUstate.is_null() || (*FMUstate).is_null() {
                    return Ok(Status::Ok);
                }
                snapshot(&comp.states, *FMUstate)?;
                comp.states.remove(&(*FMUstate as usize));
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
            with_component(c, "fmi2SerializedFMUstateSize", |comp| {
                comp.instance.check(Op::FmuState, "fmi2SerializedFMUstateSize")?;
                non_null!(size, "size");
                *size = snapshot(&comp.states, FMUstate)?.to_bytes().len();
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
                let bytes = snapshot(&comp.states, FMUstate)?.to_bytes();
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
                let p = Box::into_raw(Box::new(snap));
                comp.states.insert(p as usize);
                *FMUstate = p.cast();
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

//! The process-wide registry of live FMU states (FMI 2.0.4 §2.1.8).
//!
//! An `fmi2FMUstate` is the address of a `Box<Snapshot>`. Every state handed out by
//! `fmi2GetFMUstate` or `fmi2DeSerializeFMUstate` is entered here with the instance that made
//! it (its owner), and leaves when it is freed, through any instance, or when its owner is freed
//! (`fmi2FreeInstance` frees everything an instance allocated). So:
//! - a state may be set into, serialised by or freed through **any** live instance of the same
//!   model in the process (hosts move runs to fresh instances and keep pools of instances);
//!   the model check (GUID, sizes) is `Instance::set_fmu_state`'s;
//! - an address that is not in the registry (never handed out, freed already, or owned by an
//!   instance freed since) is refused **without being dereferenced**;
//! - the registry is one `Mutex`, and every read or write of a registered snapshot happens under
//!   it, so instances on different threads may share states without a data race (the host still
//!   must not use one *instance* from two threads at once).

use crate::fmu::Snapshot;
use std::collections::HashMap;
use std::sync::{Mutex, MutexGuard};

/// A live state: the box (as `Box::into_raw` gave it) and the address of the component that
/// allocated it.
struct Entry {
    snap: *mut Snapshot,
    owner: usize,
}

// SAFETY: an `Entry` is only reached through the registry's lock, and `Snapshot` is `Send`.
unsafe impl Send for Entry {}

/// Snapshot address → its entry.
type Map = HashMap<usize, Entry>;

static LIVE: Mutex<Option<Map>> = Mutex::new(None);

/// The registry, locked. A panic while it was held (none is expected: nothing in here panics)
/// leaves it consistent, so a poisoned lock is taken over.
fn live() -> MutexGuard<'static, Option<Map>> {
    LIVE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Runs `f` on the live snapshot at `addr`, holding the registry; `None` if `addr` is not a
/// live FMU state.
pub(crate) fn with_state<R>(addr: usize, f: impl FnOnce(&mut Snapshot) -> R) -> Option<R> {
    let guard = live();
    let entry = guard.as_ref()?.get(&addr)?;
    // SAFETY: a registered entry is a live `Box<Snapshot>` (made by `insert`, removed from the
    // registry before it is dropped), and the registry lock held here is taken by every access.
    let out = f(unsafe { &mut *entry.snap });
    drop(guard);
    Some(out)
}

/// Enters a new live state made by the component at `owner`; returns its address.
pub(crate) fn insert(owner: usize, snap: Snapshot) -> *mut Snapshot {
    let snap = Box::into_raw(Box::new(snap));
    live()
        .get_or_insert_with(HashMap::new)
        .insert(snap as usize, Entry { snap, owner });
    snap
}

/// Frees the live state at `addr` after `check` accepted it; `None` if it is not live, else
/// `check`'s verdict (the state is freed only on `Ok`).
pub(crate) fn free<E>(
    addr: usize,
    check: impl FnOnce(&Snapshot) -> Result<(), E>,
) -> Option<Result<(), E>> {
    let mut guard = live();
    let map = guard.as_mut()?;
    let entry = map.get(&addr)?;
    // SAFETY: registered, hence a live `Box<Snapshot>`; the lock is held.
    if let Err(e) = check(unsafe { &*entry.snap }) {
        return Some(Err(e));
    }
    let entry = map.remove(&addr)?;
    drop(guard);
    // SAFETY: made by `Box::into_raw` in `insert` and just removed from the registry, so no
    // other call can reach it; freed once.
    drop(unsafe { Box::from_raw(entry.snap) });
    Some(Ok(()))
}

/// Frees every live state that the component at `owner` allocated (`fmi2FreeInstance`).
pub(crate) fn free_owned_by(owner: usize) {
    let owned: Vec<Entry> = {
        let mut guard = live();
        let Some(map) = guard.as_mut() else {
            return;
        };
        let keys: Vec<usize> = map
            .iter()
            .filter(|(_, e)| e.owner == owner)
            .map(|(&a, _)| a)
            .collect();
        keys.iter().filter_map(|a| map.remove(a)).collect()
    };
    for e in owned {
        // SAFETY: as in `free`: removed from the registry, so unreachable, and freed once.
        drop(unsafe { Box::from_raw(e.snap) });
    }
}

/// The number of live states (tests).
#[doc(hidden)]
#[must_use]
pub fn live_count() -> usize {
    live().as_ref().map_or(0, HashMap::len)
}

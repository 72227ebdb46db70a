//! Opaque handles: each is an `Arc` given to C as a raw pointer, and listed
//! in a registry so a handle that was never created, or already destroyed,
//! is reported as GLS_ERROR_INVALID_HANDLE instead of being dereferenced.

use crate::sync::LockRecover;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use crate::error::{Error, Result};

/// The kinds of handle, so one kind is never taken for another.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Display,
    Config,
    Surface,
}

fn registry() -> &'static Mutex<HashMap<usize, Kind>> {
    static R: OnceLock<Mutex<HashMap<usize, Kind>>> = OnceLock::new();
    R.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Gives `value` to C: the pointer stays valid until [`release`].
pub(crate) fn publish<T, C>(value: Arc<T>, kind: Kind) -> *mut C {
    let p = Arc::into_raw(value);
    registry().recover().insert(p as usize, kind);
    p as *mut C
}

/// A new reference to the object behind a live handle.
pub(crate) fn get<T, C>(ptr: *const C, kind: Kind, name: &'static str) -> Result<Arc<T>> {
    if ptr.is_null() {
        return Err(Error::NullPointer(name));
    }
    let reg = registry().recover();
    if reg.get(&(ptr as usize)) != Some(&kind) {
        return Err(Error::InvalidHandle(name));
    }
    let p = ptr as *const T;
    // SAFETY: the registry holds exactly the pointers made by `publish` for
    // `T` (checked by kind) that were not yet released; the lock keeps a
    // concurrent `release` from dropping the last reference meanwhile.
    unsafe {
        Arc::increment_strong_count(p);
        Ok(Arc::from_raw(p))
    }
}

/// Takes back the reference given to C; None if the handle is not live.
pub(crate) fn release<T, C>(ptr: *const C, kind: Kind) -> Option<Arc<T>> {
    if ptr.is_null() {
        return None;
    }
    let mut reg = registry().recover();
    if reg.get(&(ptr as usize)) != Some(&kind) {
        return None;
    }
    reg.remove(&(ptr as usize));
    // SAFETY: a live handle made by `publish` for `T`; removed from the
    // registry, so this reference is taken back exactly once.
    Some(unsafe { Arc::from_raw(ptr as *const T) })
}

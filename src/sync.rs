//! Locks that survive a caught panic.
//!
//! Every export catches panics at the C boundary and the process goes on; a
//! panic while a lock was held must not make the object unusable for every
//! later call (a poisoned `Mutex` would). The state behind the library's
//! locks is updated in single assignments or re-derived on use, so taking
//! the guard of a poisoned lock is sound here.

use std::sync::{Mutex, MutexGuard, PoisonError};

/// `lock()` that takes the guard even when a panic poisoned the lock.
pub(crate) trait LockRecover<T> {
    /// Locks, recovering from poisoning.
    fn recover(&self) -> MutexGuard<'_, T>;
}

impl<T> LockRecover<T> for Mutex<T> {
    fn recover(&self) -> MutexGuard<'_, T> {
        self.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

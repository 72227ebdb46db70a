//! One thread of the layer's that takes half of a window's composite
//! ([`super::rows::Frame::write_split`]), made once per process at the
//! first frame that wants it and kept: a frame hands it work through a
//! slot guarded by a mutex and a condition variable (futexes: neither
//! allocates, where a channel's first blocking receive on a thread does)
//! and waits for its answer, so a steady frame makes no thread and
//! allocates nothing.
//!
//! It starts with every signal blocked (as Mesa's threads do), so the
//! program's signals never run on it. One frame at a time uses it: a
//! frame of another thread that finds it busy composes alone. A child
//! made with fork() has none of its parent's threads: it makes its own at
//! its first frame (and where the parent was using the helper at the
//! fork, the child composes alone).

use std::sync::{Arc, Condvar, Mutex, MutexGuard};

/// Work for the helper: a closure borrowed by [`both`], which waits for
/// it before its borrows end.
struct Task(*mut (dyn FnMut() + Send + 'static));

// SAFETY: the closure is Send, and only the helper touches it between the
// hand-over and the answer `both` waits for.
unsafe impl Send for Task {}

/// What the frame and the helper pass each other.
#[derive(Default)]
struct Slot {
    /// Work handed over, not yet taken.
    task: Option<Task>,
    /// The helper's answer to the last task: whether it ran to its end
    /// (false: it panicked).
    answer: Option<bool>,
}

#[derive(Default)]
struct Shared {
    slot: Mutex<Slot>,
    /// Signalled at each hand-over and each answer.
    changed: Condvar,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Slot> {
        self.slot.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn wait<'a>(&self, guard: MutexGuard<'a, Slot>) -> MutexGuard<'a, Slot> {
        self.changed.wait(guard).unwrap_or_else(|e| e.into_inner())
    }
}

struct Helper {
    /// The process that made it (a forked child has another id).
    pid: u32,
    shared: Arc<Shared>,
}

static HELPER: Mutex<Option<Helper>> = Mutex::new(None);

/// Runs `here` on this thread and `there` on the helper at once, and
/// returns when both are done: true when `there` ran to its end, false
/// when it did not run (no helper could be had: busy with another
/// thread's frame, or none can be made) or did not finish (it panicked).
pub(crate) fn both(here: impl FnOnce(), there: &mut (dyn FnMut() + Send)) -> bool {
    let Ok(mut slot) = HELPER.try_lock() else {
        here();
        return false;
    };
    let pid = std::process::id();
    if slot.as_ref().is_none_or(|h| h.pid != pid) {
        *slot = start(pid);
    }
    let Some(helper) = slot.as_ref() else {
        here();
        return false;
    };
    // SAFETY: only the lifetime is erased; `Answer` below waits for the
    // helper to be done with the closure before this function returns
    // (or unwinds), so the borrow outlives every use.
    let task = Task(unsafe {
        std::mem::transmute::<*mut (dyn FnMut() + Send + '_), *mut (dyn FnMut() + Send + 'static)>(
            there,
        )
    });
    let shared = &*helper.shared;
    {
        let mut s = shared.lock();
        s.answer = None;
        s.task = Some(task);
    }
    shared.changed.notify_all();
    /// Waits for the helper's answer when dropped.
    struct Answer<'a>(&'a Shared, Option<bool>);
    impl Answer<'_> {
        fn get(&mut self) -> bool {
            if self.1.is_none() {
                let mut s = self.0.lock();
                while s.answer.is_none() {
                    s = self.0.wait(s);
                }
                self.1 = s.answer.take();
            }
            self.1 == Some(true)
        }
    }
    impl Drop for Answer<'_> {
        fn drop(&mut self) {
            self.get();
        }
    }
    let mut answer = Answer(shared, None);
    here();
    answer.get()
}

/// A new helper thread, started with every signal blocked; None where
/// no thread can be made.
fn start(pid: u32) -> Option<Helper> {
    let shared = Arc::new(Shared::default());
    let theirs = Arc::clone(&shared);
    let blocked = SignalsBlocked::now();
    let made = std::thread::Builder::new()
        .name("glstereo compose".into())
        .spawn(move || {
            let shared = &*theirs;
            loop {
                let Task(f) = {
                    let mut s = shared.lock();
                    loop {
                        if let Some(task) = s.task.take() {
                            break task;
                        }
                        s = shared.wait(s);
                    }
                };
                let ran = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    // SAFETY: `both` keeps the closure alive and untouched
                    // until it has the answer given below.
                    unsafe { (*f)() }
                }))
                .is_ok();
                shared.lock().answer = Some(ran);
                shared.changed.notify_all();
            }
        });
    drop(blocked);
    made.ok().map(|_| Helper { pid, shared })
}

/// Every signal blocked on this thread until dropped, when its mask is
/// put back (a thread made meanwhile starts with all blocked).
struct SignalsBlocked(Option<libc::sigset_t>);

impl SignalsBlocked {
    fn now() -> SignalsBlocked {
        // SAFETY: plain libc calls on sets owned here.
        unsafe {
            let mut all: libc::sigset_t = std::mem::zeroed();
            let mut was: libc::sigset_t = std::mem::zeroed();
            libc::sigfillset(&mut all);
            let ok = libc::pthread_sigmask(libc::SIG_BLOCK, &all, &mut was) == 0;
            SignalsBlocked(ok.then_some(was))
        }
    }
}

impl Drop for SignalsBlocked {
    fn drop(&mut self) {
        if let Some(was) = self.0.take() {
            // SAFETY: the mask this thread had.
            unsafe { libc::pthread_sigmask(libc::SIG_SETMASK, &was, std::ptr::null_mut()) };
        }
    }
}

/// The helper is one per process: tests that count on having it take
/// turns (a busy helper is a frame composed alone).
#[cfg(test)]
pub(crate) fn turn() -> std::sync::MutexGuard<'static, ()> {
    static TURNS: Mutex<()> = Mutex::new(());
    TURNS.lock().unwrap_or_else(|e| e.into_inner())
}

/// A value alone on its cache lines (two of x86's 64-byte lines, which
/// its prefetcher fetches in pairs): what each of the two threads of a
/// frame writes for itself, so that one thread's writes never take the
/// other's line away (false sharing).
#[derive(Debug, Default)]
#[repr(align(128))]
pub(crate) struct Alone<T>(pub T);

impl<T> std::ops::Deref for Alone<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.0
    }
}

impl<T> std::ops::DerefMut for Alone<T> {
    fn deref_mut(&mut self) -> &mut T {
        &mut self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_halves_run_and_the_helper_is_kept_from_call_to_call() {
        let _turn = turn();
        let mut names = Vec::new();
        for i in 0..50u32 {
            let mut there_ran = None;
            let mut here_ran = false;
            let ok = both(|| here_ran = true, &mut || {
                there_ran = Some((i, std::thread::current().name().map(str::to_owned)))
            });
            assert!(ok && here_ran);
            let (j, name) = there_ran.expect("the helper ran its half");
            assert_eq!(j, i);
            names.push(name);
        }
        assert!(
            names
                .iter()
                .all(|n| n.as_deref() == Some("glstereo compose"))
        );
    }

    #[test]
    fn a_panicking_half_says_so_and_the_next_call_still_works() {
        let _turn = turn();
        let ok = both(|| (), &mut || panic!("a kernel that panics"));
        assert!(!ok);
        let mut ran = false;
        assert!(both(|| (), &mut || ran = true));
        assert!(ran);
    }

    #[test]
    fn the_helper_takes_no_signals() {
        let _turn = turn();
        let mut mask_all = false;
        assert!(both(|| (), &mut || {
            // SAFETY: reading this thread's mask into a set owned here.
            unsafe {
                let mut set: libc::sigset_t = std::mem::zeroed();
                libc::pthread_sigmask(libc::SIG_BLOCK, std::ptr::null(), &mut set);
                mask_all = libc::sigismember(&set, libc::SIGINT) == 1
                    && libc::sigismember(&set, libc::SIGTERM) == 1
                    && libc::sigismember(&set, libc::SIGALRM) == 1;
            }
        }));
        assert!(
            mask_all,
            "the helper thread must start with every signal blocked"
        );
    }
}

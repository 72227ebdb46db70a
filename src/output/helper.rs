//! One thread of the layer's that takes half of a window's composite
//! ([`super::rows::Frame::write_split`]), made once per process at the
//! first frame that wants it and kept: a frame hands it work through a
//! channel of one slot and waits for its answer, so a steady frame makes
//! no thread and allocates nothing.
//!
//! It starts with every signal blocked (as Mesa's threads do), so the
//! program's signals never run on it. One frame at a time uses it: a
//! frame of another thread that finds it busy composes alone. A child
//! made with fork() has none of its parent's threads: it makes its own at
//! its first frame (and where the parent was using the helper at the
//! fork, the child composes alone).

use std::sync::Mutex;
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};

/// Work for the helper: a closure borrowed by [`both`], which waits for
/// it before its borrows end.
struct Task(*mut (dyn FnMut() + Send + 'static));

// SAFETY: the closure is Send, and only the helper touches it between the
// send and the answer `both` waits for.
unsafe impl Send for Task {}

struct Helper {
    /// The process that made it (a forked child has another id).
    pid: u32,
    work: SyncSender<Task>,
    /// Whether the task ran to its end (false: it panicked).
    answers: Receiver<bool>,
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
    if helper.work.send(task).is_err() {
        *slot = None;
        here();
        return false;
    }
    /// Waits for the helper's answer when dropped.
    struct Answer<'a>(&'a Receiver<bool>, Option<bool>);
    impl Answer<'_> {
        fn get(&mut self) -> bool {
            *self.1.get_or_insert_with(|| self.0.recv().unwrap_or(false))
        }
    }
    impl Drop for Answer<'_> {
        fn drop(&mut self) {
            self.get();
        }
    }
    let mut answer = Answer(&helper.answers, None);
    here();
    answer.get()
}

/// A new helper thread, started with every signal blocked; None where
/// no thread can be made.
fn start(pid: u32) -> Option<Helper> {
    let (work, tasks) = sync_channel::<Task>(1);
    let (done, answers) = sync_channel::<bool>(1);
    let blocked = SignalsBlocked::now();
    let made = std::thread::Builder::new()
        .name("glstereo compose".into())
        .spawn(move || {
            while let Ok(Task(f)) = tasks.recv() {
                let ran = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    // SAFETY: `both` keeps the closure alive and untouched
                    // until it has the answer sent below.
                    unsafe { (*f)() }
                }))
                .is_ok();
                if done.send(ran).is_err() {
                    break;
                }
            }
        });
    drop(blocked);
    made.ok().map(|_| Helper { pid, work, answers })
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

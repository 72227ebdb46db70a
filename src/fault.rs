//! Faults: a panic inside glstereo is a bug in glstereo, and inside
//! someone else's program it must cost no more than the call it happened
//! in. Every place that catches one ([`crate::ffi::boundary`], the
//! layer's present) runs its body through [`contain`], which
//!
//! - keeps the panic quiet while it unwinds: Rust's default hook would
//!   print a message and, with `RUST_BACKTRACE`, a whole backtrace on the
//!   program's stderr. Only with `RUST_BACKTRACE` or `GLSTEREO_VERBOSE`
//!   set is the panic and its backtrace printed (for a bug report);
//! - turns it into [`Error::Panic`] naming where it happened
//!   (`panicked at src/output/rows.rs:773:41: index out of bounds …`), for
//!   the caller's one line on stderr or `gls_last_error_message()`.
//!
//! Panics outside [`contain`] (a Rust program's own) go to the hook that
//! was installed before glstereo's, untouched.
//!
//! For tests, `GLSTEREO_TEST_FAULT=compose:K[,K…]` makes the K-th
//! composition of a frame for a window in the process (counted from 1)
//! panic, as a bug in a compose kernel would ([`inject`]).

use std::cell::{Cell, RefCell};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Once;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::Error;

/// Environment: `compose:K[,K…]` — the compositions that panic (tests).
pub const ENV_TEST_FAULT: &str = "GLSTEREO_TEST_FAULT";

thread_local! {
    /// How many [`contain`] calls this thread is inside.
    static DEPTH: Cell<u32> = const { Cell::new(0) };
    /// What the hook saw of the last contained panic: location and message.
    static SEEN: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Runs `f`; a panic inside it becomes `Err(Error::Panic(where and what))`
/// without a word on stderr (unless `RUST_BACKTRACE` or
/// `GLSTEREO_VERBOSE` asks for the panic and its backtrace).
pub(crate) fn contain<T>(f: impl FnOnce() -> T) -> Result<T, Error> {
    install_hook();
    let _inside = Inside::enter();
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        let seen = SEEN.try_with(|s| s.borrow_mut().take()).ok().flatten();
        Error::Panic(seen.unwrap_or_else(|| payload_text(payload.as_ref())))
    })
}

/// Marks this thread as inside [`contain`] while alive (unwinding included).
struct Inside;

impl Inside {
    fn enter() -> Inside {
        let _ = DEPTH.try_with(|d| d.set(d.get() + 1));
        Inside
    }
}

impl Drop for Inside {
    fn drop(&mut self) {
        let _ = DEPTH.try_with(|d| d.set(d.get().saturating_sub(1)));
    }
}

fn payload_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_owned()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic with a non-string payload".to_owned()
    }
}

/// Whether a contained panic is printed with its backtrace.
fn verbose() -> bool {
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty() && v != "0");
    set("RUST_BACKTRACE") || set(crate::report::ENV_VERBOSE)
}

/// Puts glstereo's hook in front of the one installed before (once per
/// process). Never called while this thread panics (std refuses that).
fn install_hook() {
    static HOOK: Once = Once::new();
    if std::thread::panicking() {
        return;
    }
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let inside = DEPTH.try_with(|d| d.get() > 0).unwrap_or(false);
            if !inside {
                return previous(info);
            }
            let at = info
                .location()
                .map(|l| format!("panicked at {}:{}:{}: ", l.file(), l.line(), l.column()))
                .unwrap_or_default();
            let text = format!("{at}{}", payload_text(info.payload()));
            if verbose() {
                let trace = std::backtrace::Backtrace::force_capture();
                eprintln!("glstereo: {text}\n{trace}");
            }
            let _ = SEEN.try_with(|s| *s.borrow_mut() = Some(text));
        }));
    });
}

/// Where [`inject`] may be asked to fail.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Site {
    /// A frame's composition for a window (pixels or GL).
    Compose,
}

/// Panics when `GLSTEREO_TEST_FAULT` names this call of `site`: a switch
/// for the tests that prove a fault costs at most its own frame. Costs an
/// atomic add and, the first time, one look at the environment. The
/// panic is located at the caller, as a fault of its own would be.
#[track_caller]
pub(crate) fn inject(site: Site) {
    static COMPOSES: AtomicU64 = AtomicU64::new(0);
    static PLAN: std::sync::OnceLock<Vec<u64>> = std::sync::OnceLock::new();
    let plan = PLAN.get_or_init(|| {
        std::env::var(ENV_TEST_FAULT)
            .ok()
            .and_then(|v| {
                v.trim().strip_prefix("compose:").map(|list| {
                    list.split(',')
                        .filter_map(|k| k.trim().parse().ok())
                        .collect()
                })
            })
            .unwrap_or_default()
    });
    if plan.is_empty() {
        return;
    }
    let k = match site {
        Site::Compose => COMPOSES.fetch_add(1, Ordering::Relaxed) + 1,
    };
    if plan.contains(&k) {
        panic!("{ENV_TEST_FAULT} asked composition {k} to fail");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_contained_panic_names_where_it_happened_and_the_thread_goes_on() {
        let e = contain(|| -> u32 { panic!("kernel fell over") }).unwrap_err();
        let text = e.to_string();
        assert!(text.contains("kernel fell over"), "{text}");
        assert!(text.contains("src/fault.rs:"), "the location: {text}");
        assert_eq!(contain(|| 7).unwrap(), 7);
        // Nested: the inner one is caught, the outer goes on.
        let outer = contain(|| contain(|| panic!("inner")).is_err());
        assert!(outer.unwrap());
        assert_eq!(DEPTH.with(|d| d.get()), 0);
    }
}

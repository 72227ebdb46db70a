//! The one boundary every export goes through: panics are caught (quietly,
//! as [`crate::fault`] says), errors become result codes, and the message is kept per thread for
//! `gls_last_error_message()`.

use std::cell::RefCell;
use std::ffi::CString;

use crate::error::{Error, Result};
use crate::ffi::types::{GLS_OK, gls_result};

thread_local! {
    /// The message of the most recent failing call on this thread.
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Records `err` as this thread's last error, prefixed by the function name.
pub(crate) fn set_last_error(function: &str, err: &Error) {
    let text = format!("{function}: {err}");
    // Interior NULs cannot occur in our messages, but a user-supplied string
    // (a path, a mode name) could carry one: replace rather than lose the message.
    let c = CString::new(text.replace('\0', "\\0")).unwrap_or_default();
    // try_with: while the process exits (atexit handlers calling in after
    // thread-local destructors ran) the message is dropped, never a panic.
    let _ = LAST_ERROR.try_with(|slot| *slot.borrow_mut() = c);
}

/// A pointer to this thread's last error message. Valid until the next
/// failing call on this thread; an empty string before any failure.
pub(crate) fn last_error_ptr() -> *const std::ffi::c_char {
    LAST_ERROR
        .try_with(|slot| slot.borrow().as_ptr())
        .unwrap_or(c"".as_ptr())
}

/// Runs the body of a `gls_result`-returning export.
pub(crate) fn run(function: &'static str, body: impl FnOnce() -> Result<()>) -> gls_result {
    match crate::fault::contain(body).and_then(|r| r) {
        Ok(()) => GLS_OK,
        Err(e) => {
            set_last_error(function, &e);
            e.code()
        }
    }
}

/// Runs the body of an export that returns a plain value; on failure the
/// error is recorded and `on_error` is returned.
pub(crate) fn run_value<T>(
    function: &'static str,
    on_error: T,
    body: impl FnOnce() -> Result<T>,
) -> T {
    match crate::fault::contain(body).and_then(|r| r) {
        Ok(v) => v,
        Err(e) => {
            set_last_error(function, &e);
            on_error
        }
    }
}

/// Runs the body of a gls_glx_* / gls_gl_* function (the stereo layer's GLX
/// and GL entry points): as [`run_value`], and since a program under the
/// LD_PRELOAD library cannot read gls_last_error_message(), the message also
/// goes to stderr, once, naming the GLX or GL function the program called
/// (`glstereo: glXChooseVisual refused: …`).
pub(crate) fn run_layer<T>(
    function: &'static str,
    legacy: &'static str,
    on_error: T,
    body: impl FnOnce() -> Result<T>,
) -> T {
    let e = match crate::fault::contain(body).and_then(|r| r) {
        Ok(v) => return v,
        Err(e) => e,
    };
    set_last_error(function, &e);
    crate::interpose::warn(&format!("{legacy} refused: {e}"));
    on_error
}

/// Wraps the body of every export. `ffi_boundary!("name", { ... Ok(()) })`
/// for calls returning `gls_result`; `ffi_boundary!("name", default => { ... Ok(v) })`
/// for calls returning a value (`default` on failure);
/// `ffi_boundary!("gls_glx_name" for "glXName", default => { ... Ok(v) })`
/// for the stereo layer's GLX/GL entry points ([`run_layer`]).
macro_rules! ffi_boundary {
    ($name:literal, $body:block) => {
        $crate::ffi::boundary::run($name, || -> $crate::error::Result<()> { $body })
    };
    ($name:literal, $default:expr => $body:block) => {
        $crate::ffi::boundary::run_value($name, $default, || $body)
    };
    ($name:literal for $legacy:literal, $default:expr => $body:block) => {
        $crate::ffi::boundary::run_layer($name, $legacy, $default, || $body)
    };
}
pub(crate) use ffi_boundary;

/// Borrows a required input pointer.
///
/// # Safety
/// `ptr` must be NULL or point to a valid, initialised `T` that outlives `'a`.
pub(crate) unsafe fn arg_ref<'a, T>(ptr: *const T, name: &'static str) -> Result<&'a T> {
    // SAFETY: the caller guarantees validity when non-NULL.
    unsafe { ptr.as_ref() }.ok_or(Error::NullPointer(name))
}

/// Checks a required output pointer; the value is written later, on success only.
pub(crate) fn arg_out<T>(ptr: *mut T, name: &'static str) -> Result<*mut T> {
    if ptr.is_null() {
        Err(Error::NullPointer(name))
    } else {
        Ok(ptr)
    }
}

/// Writes an output value through a pointer checked by [`arg_out`].
///
/// # Safety
/// `ptr` must be valid for a write of `T` (it may be uninitialised).
pub(crate) unsafe fn write_out<T>(ptr: *mut T, value: T) {
    // SAFETY: the caller guarantees `ptr` is valid for writes.
    unsafe { ptr.write(value) }
}

/// Reads a C string argument as UTF-8.
///
/// # Safety
/// `ptr` must be NULL or point to a NUL-terminated string.
pub(crate) unsafe fn arg_str<'a>(
    ptr: *const std::ffi::c_char,
    name: &'static str,
) -> Result<&'a str> {
    if ptr.is_null() {
        return Err(Error::NullPointer(name));
    }
    // SAFETY: non-NULL and NUL-terminated by the caller's contract.
    unsafe { std::ffi::CStr::from_ptr(ptr) }
        .to_str()
        .map_err(|_| Error::invalid_value(format!("{name} is not valid UTF-8")))
}

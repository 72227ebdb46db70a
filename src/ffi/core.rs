//! Version, result codes and error messages.

use std::ffi::c_char;

use super::boundary::{ffi_boundary, last_error_ptr};
use super::types::gls_result;
use crate::error::{Error, result_string};

const VERSION: &std::ffi::CStr = {
    // CARGO_PKG_VERSION plus a NUL, checked at compile time.
    match std::ffi::CStr::from_bytes_with_nul(concat!(env!("CARGO_PKG_VERSION"), "\0").as_bytes()) {
        Ok(s) => s,
        Err(_) => panic!("the package version contains a NUL"),
    }
};

/// The library's version, "MAJOR.MINOR.PATCH", equal to GLSTEREO_VERSION_STRING
/// of the header it was built with.
///
/// @return a static string; never NULL. Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_version() -> *const c_char {
    VERSION.as_ptr()
}

/// The message of the most recent failing call on the calling thread, prefixed
/// with the function's name; it says what went wrong and what to do.
///
/// @return a library-owned string, valid until the next failing call on this
/// thread; an empty string if no call has failed on this thread. Never NULL.
/// A successful call does not clear it. Thread-safe: each thread has its own.
#[unsafe(no_mangle)]
pub extern "C" fn gls_last_error_message() -> *const c_char {
    last_error_ptr()
}

/// A fixed description of a result code, e.g.
/// "GLS_ERROR_NULL_POINTER: a required pointer argument was NULL".
///
/// @param result any value; unknown codes give "unknown gls_result code".
/// @return a static string; never NULL. Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_result_string(result: gls_result) -> *const c_char {
    result_string(result).as_ptr()
}

/// Raises an internal panic inside the library and catches it at the
/// boundary, so a program (or a test) can check its handling of
/// GLS_ERROR_PANIC. Nothing else happens; the library stays usable.
///
/// @return GLS_ERROR_PANIC, always.
#[unsafe(no_mangle)]
pub extern "C" fn gls_debug_force_panic() -> gls_result {
    ffi_boundary!("gls_debug_force_panic", {
        let forced: Result<(), Error> = Err(Error::invalid_operation("unreachable"));
        if forced.is_err() {
            panic!("forced by gls_debug_force_panic");
        }
        forced
    })
}

//! The one error type of the crate, and its mapping to the C result codes.
//!
//! Every fallible operation returns [`Result<T>`]. The C boundary turns an
//! [`Error`] into a `gls_result` with [`Error::code`] and keeps its message for
//! `gls_last_error_message()`. Messages say what to do, not just what failed.

use crate::ffi::types::*;

/// Result of every fallible operation in the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong, one variant per C result code.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A required pointer argument was NULL.
    #[error("{0} must not be NULL")]
    NullPointer(&'static str),
    /// A value that must be one of a set of enumerants was not.
    #[error("{what}: {value:#x} ({value}) is not a valid value; {expected}")]
    InvalidEnum {
        /// The parameter or attribute that was wrong.
        what: &'static str,
        /// The value received.
        value: u32,
        /// What would have been accepted.
        expected: String,
    },
    /// A numeric or string value out of its valid range.
    #[error("{0}")]
    InvalidValue(String),
    /// A call that is not allowed in the current state.
    #[error("{0}")]
    InvalidOperation(String),
    /// A call that needs a current surface on this thread found none.
    #[error("no surface is current on this thread: call gls_make_current(surface) first")]
    NoCurrentSurface,
    /// A backend library could not be loaded or initialised.
    #[error("{0}")]
    BackendUnavailable(String),
    /// No configuration matches the requested attributes.
    #[error("{0}")]
    NoMatchingConfig(String),
    /// An allocation (host or GL) failed.
    #[error("{0}")]
    OutOfMemory(String),
    /// Reading or writing a file failed.
    #[error("{0}")]
    Io(String),
    /// A panic inside the library was caught (`src/fault.rs`): where it
    /// happened and what it said.
    #[error(
        "internal error, a bug in glstereo ({0}); please report it with what \
         GLSTEREO_VERBOSE=1 prints"
    )]
    Panic(String),
    /// A handle that is not (or no longer) a live object of the expected kind.
    #[error("{0} is not a live handle: it was never created, or was already destroyed")]
    InvalidHandle(&'static str),
    /// The connection to the display server was lost.
    #[error("{0}")]
    DisplayLost(String),
    /// The GL driver reported an error that the library could not handle.
    #[error("{0}")]
    Gl(String),
}

impl Error {
    /// The C result code of this error.
    pub fn code(&self) -> gls_result {
        match self {
            Error::NullPointer(_) => GLS_ERROR_NULL_POINTER,
            Error::InvalidEnum { .. } => GLS_ERROR_INVALID_ENUM,
            Error::InvalidValue(_) => GLS_ERROR_INVALID_VALUE,
            Error::InvalidOperation(_) => GLS_ERROR_INVALID_OPERATION,
            Error::NoCurrentSurface => GLS_ERROR_NO_CURRENT_SURFACE,
            Error::BackendUnavailable(_) => GLS_ERROR_BACKEND_UNAVAILABLE,
            Error::NoMatchingConfig(_) => GLS_ERROR_NO_MATCHING_CONFIG,
            Error::OutOfMemory(_) => GLS_ERROR_OUT_OF_MEMORY,
            Error::Io(_) => GLS_ERROR_IO,
            Error::Panic(_) => GLS_ERROR_PANIC,
            Error::InvalidHandle(_) => GLS_ERROR_INVALID_HANDLE,
            Error::DisplayLost(_) => GLS_ERROR_DISPLAY_LOST,
            Error::Gl(_) => GLS_ERROR_GL,
        }
    }

    /// Shorthand for [`Error::InvalidValue`].
    pub fn invalid_value(msg: impl Into<String>) -> Self {
        Error::InvalidValue(msg.into())
    }

    /// Shorthand for [`Error::InvalidOperation`].
    pub fn invalid_operation(msg: impl Into<String>) -> Self {
        Error::InvalidOperation(msg.into())
    }

    /// Shorthand for [`Error::InvalidEnum`].
    pub fn invalid_enum(what: &'static str, value: u32, expected: impl Into<String>) -> Self {
        Error::InvalidEnum {
            what,
            value,
            expected: expected.into(),
        }
    }
}

/// The fixed description of a result code, as `gls_result_string` returns it.
pub fn result_string(code: gls_result) -> &'static std::ffi::CStr {
    match code {
        GLS_OK => c"GLS_OK: success",
        GLS_ERROR_NULL_POINTER => c"GLS_ERROR_NULL_POINTER: a required pointer argument was NULL",
        GLS_ERROR_INVALID_ENUM => {
            c"GLS_ERROR_INVALID_ENUM: a value is not one of the accepted enumerants"
        }
        GLS_ERROR_INVALID_VALUE => c"GLS_ERROR_INVALID_VALUE: a value is out of its valid range",
        GLS_ERROR_INVALID_OPERATION => {
            c"GLS_ERROR_INVALID_OPERATION: the call is not allowed in the current state"
        }
        GLS_ERROR_NO_CURRENT_SURFACE => {
            c"GLS_ERROR_NO_CURRENT_SURFACE: no surface is current on this thread"
        }
        GLS_ERROR_BACKEND_UNAVAILABLE => {
            c"GLS_ERROR_BACKEND_UNAVAILABLE: the requested GL backend could not be loaded"
        }
        GLS_ERROR_NO_MATCHING_CONFIG => {
            c"GLS_ERROR_NO_MATCHING_CONFIG: no configuration matches the requested attributes"
        }
        GLS_ERROR_OUT_OF_MEMORY => c"GLS_ERROR_OUT_OF_MEMORY: an allocation failed",
        GLS_ERROR_IO => c"GLS_ERROR_IO: reading or writing a file failed",
        GLS_ERROR_PANIC => c"GLS_ERROR_PANIC: an internal error was caught (please report it)",
        GLS_ERROR_INVALID_HANDLE => {
            c"GLS_ERROR_INVALID_HANDLE: a handle is not live (never created or already destroyed)"
        }
        GLS_ERROR_DISPLAY_LOST => c"GLS_ERROR_DISPLAY_LOST: the connection to the display was lost",
        GLS_ERROR_GL => c"GLS_ERROR_GL: the GL driver reported an error",
        _ => c"unknown gls_result code",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_error_has_a_distinct_nonzero_code_and_a_description() {
        let all = [
            Error::NullPointer("x"),
            Error::invalid_enum("x", 1, "y"),
            Error::invalid_value("x"),
            Error::invalid_operation("x"),
            Error::NoCurrentSurface,
            Error::BackendUnavailable("x".into()),
            Error::NoMatchingConfig("x".into()),
            Error::OutOfMemory("x".into()),
            Error::Io("x".into()),
            Error::Panic("x".into()),
            Error::InvalidHandle("x"),
            Error::DisplayLost("x".into()),
            Error::Gl("x".into()),
        ];
        let mut codes: Vec<_> = all.iter().map(Error::code).collect();
        assert!(codes.iter().all(|&c| c != GLS_OK));
        for &c in &codes {
            let s = result_string(c).to_str().unwrap();
            assert!(
                s.starts_with("GLS_ERROR_"),
                "code {c} has description {s:?}"
            );
        }
        codes.sort();
        codes.dedup();
        assert_eq!(codes.len(), all.len(), "codes must be distinct");
    }
}

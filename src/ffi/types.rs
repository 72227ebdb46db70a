//! Types and constants shared by every part of the C ABI.
//!
//! Enumerations cross the boundary as `uint32_t` constants and are converted
//! with a checked `TryFrom` inside the library, so a bad value is
//! `GLS_ERROR_INVALID_ENUM` and never undefined behaviour.
#![allow(non_camel_case_types)]

/// Result code of every fallible call. `GLS_OK` (0) is success; every other
/// value is one of the `GLS_ERROR_*` codes, and the call left a message for
/// gls_last_error_message() on the calling thread.
pub type gls_result = u32;

/// Success.
pub const GLS_OK: gls_result = 0;
/// A required pointer argument was NULL.
pub const GLS_ERROR_NULL_POINTER: gls_result = 1;
/// A value that must be one of a set of enumerants was not (a bad GLS_* or GL_* value).
pub const GLS_ERROR_INVALID_ENUM: gls_result = 2;
/// A numeric or string value is out of its valid range.
pub const GLS_ERROR_INVALID_VALUE: gls_result = 3;
/// The call is not allowed in the current state (e.g. a buffer the config lacks).
pub const GLS_ERROR_INVALID_OPERATION: gls_result = 4;
/// The call needs a current surface on this thread and there is none.
pub const GLS_ERROR_NO_CURRENT_SURFACE: gls_result = 5;
/// The GL backend (EGL, OSMesa, GLX) could not be loaded or initialised; the message names the package to install.
pub const GLS_ERROR_BACKEND_UNAVAILABLE: gls_result = 6;
/// No configuration matches the requested attributes (as when glXChooseVisual returns NULL).
pub const GLS_ERROR_NO_MATCHING_CONFIG: gls_result = 7;
/// A host or GL allocation failed.
pub const GLS_ERROR_OUT_OF_MEMORY: gls_result = 8;
/// Reading or writing a file failed.
pub const GLS_ERROR_IO: gls_result = 9;
/// An internal error (a Rust panic) was caught at the boundary; the process goes on.
pub const GLS_ERROR_PANIC: gls_result = 10;
/// A handle is not live: it was never created, or it was already destroyed.
pub const GLS_ERROR_INVALID_HANDLE: gls_result = 11;
/// The connection to the display (X server) was lost.
pub const GLS_ERROR_DISPLAY_LOST: gls_result = 12;
/// The GL driver reported an error the library could not handle.
pub const GLS_ERROR_GL: gls_result = 13;

/// The left eye.
pub const GLS_EYE_LEFT: u32 = 0;
/// The right eye.
pub const GLS_EYE_RIGHT: u32 = 1;

/// A perspective frustum: exactly the six arguments of glFrustum().
///
/// `left`/`right` and `bottom`/`top` are the edges of the view window on the
/// near clipping plane; `near_clip` and `far_clip` are positive distances
/// from the camera (near_clip > 0, far_clip > near_clip).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gls_frustum {
    /// Left edge of the view window at the near plane.
    pub left: f64,
    /// Right edge of the view window at the near plane.
    pub right: f64,
    /// Bottom edge of the view window at the near plane.
    pub bottom: f64,
    /// Top edge of the view window at the near plane.
    pub top: f64,
    /// Distance to the near clipping plane (> 0).
    pub near_clip: f64,
    /// Distance to the far clipping plane (> near_clip).
    pub far_clip: f64,
}

/// The HP stereo settings of seed 000 §7.
///
/// - `zero_parallax_distance`: distance from the camera to the plane that
///   appears at the screen surface (> 0), usually the centre of interest.
/// - `offset_adjustment`: the user's stereo strength (UserOffsetAdjustment).
///   Scales both the camera offset and the frustum asymmetry. Default: 1.0;
///   0 gives identical eyes; the seed suggests 2.0 as the upper limit.
/// - `balance_adjustment`: the user's parallax balance (UserBalanceAdjustment).
///   Scales only the asymmetry. Default: 1.0; 0 gives all-negative parallax.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gls_stereo_adjust {
    /// Distance from the camera to the zero-parallax plane (> 0).
    pub zero_parallax_distance: f64,
    /// Stereo strength; default 1.0, range 0 and up (2.0 is the usual limit).
    pub offset_adjustment: f64,
    /// Parallax balance; default 1.0, range 0 and up (2.0 is the usual limit).
    pub balance_adjustment: f64,
}

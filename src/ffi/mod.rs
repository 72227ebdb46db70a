//! The C ABI: the only place with `extern "C"`. One module per handle or
//! topic; every export goes through `boundary`'s `ffi_boundary!`.
//!
//! Conventions (see the README): functions are `gls_<object>_<verb>`, return
//! a `gls_result`, write outputs through trailing `*_out` pointers only on
//! success, and leave a per-thread message for `gls_last_error_message()`.
//!
//! Safety contract of every `unsafe extern "C"` export, stated once here
//! rather than on each: every pointer argument is NULL (reported as
//! `GLS_ERROR_NULL_POINTER` where it is required) or valid for the access the
//! function's documentation describes (arrays hold the stated count); handles
//! come from this library.
#![allow(clippy::missing_safety_doc, non_camel_case_types)]

pub(crate) mod boundary;
pub mod core;
pub mod display;
pub mod egl;
pub(crate) mod handles;
pub mod irisgl;
pub mod math;
pub mod nv3dvision;
pub mod output;
pub mod screen;
pub mod starbase;
pub mod surface;
pub mod types;
// Measurement of rendered frames: after the surface calls in the header.
pub mod analysis;
// Legacy GLX/GL names for unmodified programs (glstereo-run, compat.h).
pub mod interpose;
// Captures off the rendering thread.
pub mod capture;

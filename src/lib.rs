//! glstereo: stereo OpenGL for machines without stereo visuals.
//!
//! Legacy stereo programs (HP, SGI, quad-buffer workstations) ask for a stereo
//! visual, draw each eye into `GL_BACK_LEFT` / `GL_BACK_RIGHT` and swap once.
//! glstereo emulates that on any GL (Mesa EGL, OSMesa, GLX under any X
//! server), computes correct per-eye projections, and shows the two eyes as
//! something a person can see today.
//!
//! The data flow is one line: input framing → two eye images → output format.
//!
//! Modules, from the inside out (dependencies point inward):
//! - [`math`]: pure projection and parallax math (f64, no GL);
//! - [`image`]: RGBA8 images, rows top first;
//! - [`output`]: output formats (mode names, geometry, CPU reference);
//! - [`error`]: the one error type and its C result codes;
//! - [`ffi`]: the C ABI (the only `extern "C"` code).
#![warn(missing_docs)]

pub mod error;
pub mod ffi;
pub mod image;
pub mod math;
pub mod output;

pub use error::{Error, Result};

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
//! - [`config`], [`stereo::buffers`]: attribute lists and draw-buffer rules (pure);
//! - [`gl`]: the GL function table, loaded from the backend;
//! - [`backend`]: EGL, OSMesa (and GLX) contexts, chosen at run time;
//! - [`stereo::emulated`]: the emulated quad buffer;
//! - [`shims`]: legacy and vendor APIs (NV_3dvision_settings);
//! - [`framing`]: how programs deliver eyes (automatic stereo of mono frames);
//! - [`display`], [`surface`]: the objects a program uses;
//! - [`capture`]: PNG files;
//! - [`analysis`]: measured parallax and auto-convergence from the depth buffer;
//! - [`auto`]: automatic stereo of unmodified mono programs (draws in both eyes);
//! - [`image`]: RGBA8 images, rows top first;
//! - [`framing`]: input framings (quad buffer, sync-doubled, STR_RECT, side-by-side);
//! - [`output`]: output formats (mode names, geometry, CPU reference, GL compositor);
//! - [`shims`]: the period APIs (HP Starbase, SGI IRIS GL, NVIDIA 3D Vision);
//! - [`error`]: the one error type and its C result codes;
//! - [`ffi`]: the C ABI (the only `extern "C"` code).
#![warn(missing_docs)]

pub mod analysis;
pub mod auto;
pub mod backend;
pub mod capture;
pub mod config;
pub mod display;
pub mod error;
mod fault;
pub mod ffi;
pub mod framing;
pub mod gl;
pub mod image;
pub mod interpose;
pub mod math;
pub mod output;
mod profile;
pub mod report;
pub mod reproject;
pub mod shims;
pub mod stereo;
pub mod surface;
mod sync;
#[cfg(test)]
mod testing;

pub use error::{Error, Result};

//! Output formats: how the two eye images become something a person can see.
//!
//! Most of it is pure (no GL): the mode names, the options and their
//! environment variables, the geometry of every mode, the anaglyph colour
//! math, and the CPU reference of every composite ([`cpu::compose`]), which
//! is the oracle the GL compositor is tested against and the production path
//! for headless capture.
//!
//! - [`mode`]: [`OutputMode`], canonical names, VirtualGL/OSG aliases.
//! - [`options`]: [`OutputOptions`] (swap, crosstalk, saturation) and
//!   [`OutputSettings::from_env_with`] for `GLSTEREO_*`.
//! - [`layout`]: [`composite_size`] and where each eye goes.
//! - [`anaglyph`]: luminance weights, sRGB curves, Dubois matrices.
//! - [`cpu`]: [`compose`] of every mode, and [`cpu::reference`], the oracle.
//! - [`pattern`]: deterministic gradient and noise test images.
//! - [`gl`]: [`GlCompositor`], the same modes drawn by GL in a surface's
//!   compositor context (captures and windows).

pub mod anaglyph;
#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
mod avx512;
pub mod cpu;
mod dubois_lut;
#[cfg(test)]
pub(crate) mod fits;
pub mod gl;
pub(crate) mod helper;
pub(crate) mod kernels;
pub mod layout;
pub mod mode;
pub mod options;
pub mod pattern;
mod rows;
mod window;

pub use cpu::{compose, compose_fitted, compose_into};
pub use gl::{ComposePath, GlCompositor};
pub use layout::{Placement, composite_size, placements};
pub use mode::{ALIASES, Alias, AliasSource, AnaglyphColors, AnaglyphMethod, OutputMode};
pub use options::{OutputOptions, OutputSettings};
pub use rows::MakeEyes;

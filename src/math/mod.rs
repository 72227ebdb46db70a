//! Pure stereo projection math: f64, glam, no GL.
//!
//! Every formulation in the seed documents describes the same parallel-axis,
//! asymmetric-frustum stereo camera. Each produces an [`EyeProjection`]: the
//! eye's frustum (glFrustum arguments) and the camera offset to undo with
//! `glTranslated(-camera_offset, 0, 0)` after the projection.
//!
//! - [`hp`]: HP's method (seed 000 §6–7), the library's default.
//! - [`seeds`]: SGI `window()`/`translate()` (seed 002 §7), Xinerama/Bourke
//!   (seed 001), the anaglyph tutorial's StereoCamera (seed 003), and
//!   NVIDIA's clip-space shift (seed 004).
//! - [`points`]: Equations 1–5 of seed 000 §5 for single points.
//! - [`parallax`]: on-screen parallax and comfort budgets.
//! - [`camera`]: view matrices for cameras with any orientation.
//! - [`adjust`]: the user's strength and balance adjustments.

pub mod adjust;
pub mod camera;
pub mod frustum;
pub mod hp;
pub mod parallax;
pub mod points;
pub mod seeds;

pub use frustum::{EyeProjection, Frustum};
pub use hp::{StereoAdjust, hp_eye};

use crate::error::{Error, Result};

/// One of the two eyes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Eye {
    /// The left eye: camera offset to the left (negative).
    Left,
    /// The right eye: camera offset to the right (positive).
    Right,
}

impl Eye {
    /// Both eyes, left first.
    pub const BOTH: [Eye; 2] = [Eye::Left, Eye::Right];

    /// -1 for the left eye, +1 for the right: the direction of its camera offset.
    pub fn sign(self) -> f64 {
        match self {
            Eye::Left => -1.0,
            Eye::Right => 1.0,
        }
    }

    /// The other eye.
    pub fn other(self) -> Eye {
        match self {
            Eye::Left => Eye::Right,
            Eye::Right => Eye::Left,
        }
    }
}

impl TryFrom<u32> for Eye {
    type Error = Error;
    fn try_from(v: u32) -> Result<Eye> {
        use crate::ffi::types::{GLS_EYE_LEFT, GLS_EYE_RIGHT};
        match v {
            GLS_EYE_LEFT => Ok(Eye::Left),
            GLS_EYE_RIGHT => Ok(Eye::Right),
            _ => Err(Error::invalid_enum(
                "eye",
                v,
                "use GLS_EYE_LEFT (0) or GLS_EYE_RIGHT (1)",
            )),
        }
    }
}

/// Checks that a parameter is a finite number.
pub(crate) fn finite(name: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid_value(format!(
            "{name} must be a finite number, got {v}"
        )))
    }
}

/// Checks that every element of a matrix parameter is finite (the message
/// names the element, e.g. `projection[12]`).
pub(crate) fn finite_matrix_param(name: &str, m: &glam::DMat4) -> Result<()> {
    for (i, v) in m.to_cols_array().iter().enumerate() {
        finite(&format!("{name}[{i}]"), *v)?;
    }
    Ok(())
}

/// Checks that a parameter is finite and > 0.
pub(crate) fn positive(name: &str, v: f64) -> Result<f64> {
    finite(name, v)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid_value(format!("{name} must be > 0, got {v}")))
    }
}

/// Checks that a computed number is finite: inputs that are each finite can
/// still overflow (or divide by a difference that rounds to zero).
pub(crate) fn finite_result(what: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid_value(format!(
            "{what} is not a finite number ({v}): the inputs are too large, too small or too \
             close together; use values of ordinary magnitude"
        )))
    }
}

/// Checks that a computed matrix is finite (see [`finite_result`]).
pub(crate) fn finite_matrix(what: &str, m: glam::DMat4) -> Result<glam::DMat4> {
    for v in m.to_cols_array() {
        finite_result(what, v)?;
    }
    Ok(m)
}

/// Checks a field of view in degrees: finite, above 0 and below 180 (tan of
/// half of it is the frustum's slope; at 180 it has none, beyond it flips).
pub(crate) fn field_of_view(name: &str, degrees: f64) -> Result<f64> {
    positive(name, degrees)?;
    if degrees < 180.0 {
        Ok(degrees)
    } else {
        Err(Error::invalid_value(format!(
            "{name} must be below 180 degrees, got {degrees}"
        )))
    }
}

/// Checks that a parameter is finite and >= 0.
pub(crate) fn non_negative(name: &str, v: f64) -> Result<f64> {
    finite(name, v)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid_value(format!(
            "{name} must be >= 0, got {v}"
        )))
    }
}

#[cfg(test)]
pub(crate) mod testutil {
    use glam::DMat4;

    /// Asserts two matrices agree element-wise within a relative tolerance
    /// (relative to the larger magnitude of each pair, absolute near zero).
    pub fn assert_mat_close(a: &DMat4, b: &DMat4, rel: f64, what: &str) {
        let (a, b) = (a.to_cols_array(), b.to_cols_array());
        for i in 0..16 {
            let scale = a[i].abs().max(b[i].abs()).max(1.0);
            assert!(
                (a[i] - b[i]).abs() <= rel * scale,
                "{what}: element {i} (col {}, row {}) is {} vs {} (tolerance {rel} relative)\n  a = {a:?}\n  b = {b:?}",
                i / 4,
                i % 4,
                a[i],
                b[i]
            );
        }
    }
}

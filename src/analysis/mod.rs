//! Measurements of what a program rendered.
//!
//! - [`depth`]: depth-buffer samples and the map from window depth back to
//!   eye-space distance (pure);
//! - [`parallax`]: the measured on-screen parallax range against the
//!   comfort budget, and the centre of interest for auto-convergence (pure);
//! - [`capture_current`]: reads the depth buffer and the GL state that
//!   interprets it from the surface current on this thread.

pub mod depth;
pub mod parallax;

use std::sync::Arc;

pub use depth::{DepthCapture, DepthImage, DepthMapping, Viewport};
pub use parallax::{CentreOfInterest, ParallaxReport, centre_of_interest, hp_measure_parallax};

use crate::error::{Error, Result};
use crate::gl::enums::*;
use crate::surface::{self, Surface};

/// Reads what a measurement needs from the surface current on this thread:
/// its depth buffer (shared by both eyes, so it holds the eye drawn last),
/// and the application context's viewport, glDepthRange and glClearDepth.
///
/// The program's rendering is finished first. Errors: `NoCurrentSurface`;
/// `InvalidOperation` when the configuration has no depth buffer.
pub fn capture_current() -> Result<DepthCapture> {
    let s: Arc<Surface> = surface::require_current()?;
    let gl = s.gl();
    let mut vp = [0i32; 4];
    let mut range = [0f64; 2];
    let mut clear = 0f64;
    // SAFETY: require_current() returned the surface whose application
    // context is current on this thread; each query writes as many values
    // as its array holds.
    unsafe {
        gl.GetIntegerv(GL_VIEWPORT, vp.as_mut_ptr());
        gl.GetDoublev(GL_DEPTH_RANGE, range.as_mut_ptr());
        gl.GetDoublev(GL_DEPTH_CLEAR_VALUE, &mut clear);
    }
    if vp[2] <= 0 || vp[3] <= 0 {
        return Err(Error::invalid_operation(format!(
            "the viewport is {}x{}: it holds no pixels to measure",
            vp[2], vp[3]
        )));
    }
    Ok(DepthCapture {
        depth: s.read_depth()?,
        viewport: Viewport {
            x: vp[0],
            y: vp[1],
            width: vp[2],
            height: vp[3],
        },
        depth_range: (range[0], range[1]),
        clear_depth: clear,
    })
}

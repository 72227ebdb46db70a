//! Test helpers shared by the unit tests of several modules.

use std::sync::Arc;

use crate::backend::{BackendChoice, BackendKind, ContextRole, PlatformSurface};
use crate::config::glx::GLX_RGBA;
use crate::display::Display;
use crate::gl::Gl;

/// A compositor context of its own on EGL (llvmpipe on the machines this
/// project runs on), current on this thread while alive.
pub(crate) struct EglContext {
    pub gl: Arc<Gl>,
    pub display: Arc<Display>,
    surface: Box<dyn PlatformSurface>,
}

impl Drop for EglContext {
    fn drop(&mut self) {
        let _ = self.surface.release_current();
    }
}

/// Opens EGL and makes a 1x1 surface's compositor context current.
pub(crate) fn egl_context() -> EglContext {
    let display = Display::open(BackendChoice::Only(BackendKind::Egl)).expect("EGL");
    let config = display.choose_config(&[GLX_RGBA]).unwrap();
    let surface = display.platform().create_surface(&config, 1, 1).unwrap();
    surface.make_current(ContextRole::Compositor).unwrap();
    let gl = display.gl().unwrap();
    EglContext {
        gl,
        display,
        surface,
    }
}

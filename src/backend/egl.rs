//! EGL on Mesa's surfaceless platform: headless contexts with no window
//! system at all. libEGL is loaded at run time (khronos-egl, `dynamic`).
//!
//! The EGL display is initialised once per process and kept: EGL returns
//! the same display for every `eglGetPlatformDisplay` of the surfaceless
//! platform, so terminating it for one gls_display would destroy the
//! contexts of every other.

use std::ffi::{CStr, c_void};
use std::sync::{Arc, OnceLock};

use khronos_egl as egl;

use super::{BackendKind, ContextRole, Platform, PlatformSurface};
use crate::config::Config;
use crate::error::{Error, Result};

const EGL_PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;

type EglInstance = egl::DynamicInstance<egl::EGL1_5>;

/// The loaded library and the initialised surfaceless display, shared by
/// every EGL gls_display of the process.
struct EglShared {
    egl: EglInstance,
    display: egl::Display,
    config: egl::Config,
}

// SAFETY: EGL display and config handles are opaque, immutable identifiers
// that EGL allows any thread to use; the instance holds function pointers.
unsafe impl Send for EglShared {}
// SAFETY: as above; EGL entry points are thread-safe.
unsafe impl Sync for EglShared {}

fn install_hint() -> &'static str {
    "install libegl1 and libegl-mesa0 (Debian), or set GLSTEREO_BACKEND=osmesa"
}

fn shared() -> Result<Arc<EglShared>> {
    static SHARED: OnceLock<std::result::Result<Arc<EglShared>, String>> = OnceLock::new();
    SHARED
        .get_or_init(|| init().map(Arc::new).map_err(|e| e.to_string()))
        .clone()
        .map_err(Error::BackendUnavailable)
}

fn init() -> Result<EglShared> {
    // SAFETY: loads libEGL.so.1; khronos-egl checks every required symbol.
    let egl = unsafe { EglInstance::load_required() }.map_err(|e| {
        Error::BackendUnavailable(format!(
            "libEGL.so.1 could not be loaded ({e}): {}",
            install_hint()
        ))
    })?;
    let client_ext = egl
        .query_string(None, egl::EXTENSIONS)
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    if !client_ext.contains("EGL_MESA_platform_surfaceless") {
        return Err(Error::BackendUnavailable(format!(
            "this EGL has no surfaceless platform (EGL_MESA_platform_surfaceless): {}",
            install_hint()
        )));
    }
    // SAFETY: the surfaceless platform takes EGL_DEFAULT_DISPLAY and no attributes.
    let display = unsafe {
        egl.get_platform_display(
            EGL_PLATFORM_SURFACELESS_MESA,
            egl::DEFAULT_DISPLAY,
            &[egl::ATTRIB_NONE],
        )
    }
    .map_err(|e| {
        Error::BackendUnavailable(format!("eglGetPlatformDisplay(surfaceless) failed: {e}"))
    })?;
    egl.initialize(display).map_err(|e| {
        Error::BackendUnavailable(format!("eglInitialize failed ({e}): {}", install_hint()))
    })?;
    let ext = egl
        .query_string(Some(display), egl::EXTENSIONS)
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    if !ext.contains("EGL_KHR_surfaceless_context") {
        return Err(Error::BackendUnavailable(
            "this EGL driver lacks EGL_KHR_surfaceless_context; use GLSTEREO_BACKEND=osmesa".into(),
        ));
    }
    egl.bind_api(egl::OPENGL_API).map_err(|e| {
        Error::BackendUnavailable(format!(
            "this EGL cannot create desktop OpenGL contexts ({e})"
        ))
    })?;
    let config = egl
        // SURFACE_TYPE 0: any; the default (WINDOW_BIT) matches no surfaceless config.
        .choose_first_config(
            display,
            &[
                egl::RENDERABLE_TYPE,
                egl::OPENGL_BIT,
                egl::SURFACE_TYPE,
                0,
                egl::NONE,
            ],
        )
        .map_err(|e| Error::BackendUnavailable(format!("eglChooseConfig failed: {e}")))?
        .ok_or_else(|| {
            Error::BackendUnavailable("EGL offers no desktop OpenGL configuration".into())
        })?;
    Ok(EglShared {
        egl,
        display,
        config,
    })
}

/// The EGL backend.
pub struct EglPlatform {
    shared: Arc<EglShared>,
}

impl EglPlatform {
    /// Loads libEGL and initialises the surfaceless display (once per process).
    pub fn open() -> Result<EglPlatform> {
        Ok(EglPlatform { shared: shared()? })
    }
}

impl EglShared {
    /// A desktop GL context, compatibility profile 4.5 when available;
    /// if the driver refuses that version, whatever it offers by default.
    fn create_context(&self, share: Option<egl::Context>) -> Result<egl::Context> {
        self.egl
            .bind_api(egl::OPENGL_API)
            .map_err(|e| Error::BackendUnavailable(format!("eglBindAPI(OpenGL) failed: {e}")))?;
        let compat_45 = [
            egl::CONTEXT_MAJOR_VERSION,
            4,
            egl::CONTEXT_MINOR_VERSION,
            5,
            egl::CONTEXT_OPENGL_PROFILE_MASK,
            egl::CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
            egl::NONE,
        ];
        self.egl
            .create_context(self.display, self.config, share, &compat_45)
            .or_else(|_| {
                self.egl
                    .create_context(self.display, self.config, share, &[egl::NONE])
            })
            .map_err(|e| match e {
                egl::Error::BadAlloc => {
                    Error::OutOfMemory("eglCreateContext: out of memory".into())
                }
                e => Error::BackendUnavailable(format!("eglCreateContext failed: {e}")),
            })
    }
}

impl Platform for EglPlatform {
    fn kind(&self) -> BackendKind {
        BackendKind::Egl
    }

    fn create_surface(
        &self,
        _config: &Config,
        _w: u32,
        _h: u32,
    ) -> Result<Box<dyn PlatformSurface>> {
        let app = self.shared.create_context(None)?;
        let compositor = match self.shared.create_context(Some(app)) {
            Ok(c) => c,
            Err(e) => {
                let _ = self.shared.egl.destroy_context(self.shared.display, app);
                return Err(e);
            }
        };
        Ok(Box::new(EglSurface {
            shared: self.shared.clone(),
            app,
            compositor,
        }))
    }

    fn get_proc_address(&self, name: &CStr) -> *const c_void {
        match name.to_str() {
            Ok(n) => self
                .shared
                .egl
                .get_proc_address(n)
                .map_or(std::ptr::null(), |f| f as *const c_void),
            Err(_) => std::ptr::null(),
        }
    }
}

/// Two EGL contexts sharing objects; no EGL surface (surfaceless).
struct EglSurface {
    shared: Arc<EglShared>,
    app: egl::Context,
    compositor: egl::Context,
}

// SAFETY: EGL context handles are opaque identifiers usable from any thread
// (EGL itself enforces that a context is current on at most one thread).
unsafe impl Send for EglSurface {}
// SAFETY: as above.
unsafe impl Sync for EglSurface {}

impl PlatformSurface for EglSurface {
    fn make_current(&self, role: ContextRole) -> Result<()> {
        let ctx = match role {
            ContextRole::App => self.app,
            ContextRole::Compositor => self.compositor,
        };
        let egl = &self.shared.egl;
        // The rendering API is per thread: bind it on whichever thread this is.
        egl.bind_api(egl::OPENGL_API)
            .map_err(|e| Error::BackendUnavailable(format!("eglBindAPI(OpenGL) failed: {e}")))?;
        egl.make_current(self.shared.display, None, None, Some(ctx))
            .map_err(|e| match e {
                egl::Error::BadAccess => Error::invalid_operation(
                    "the surface's context is current on another thread: release it there first",
                ),
                e => Error::Gl(format!("eglMakeCurrent failed: {e}")),
            })
    }

    fn native_handles(&self) -> super::NativeHandles {
        super::NativeHandles::Egl {
            display: self.shared.display.as_ptr(),
            context: self.app.as_ptr(),
        }
    }

    fn release_current(&self) -> Result<()> {
        self.shared
            .egl
            .make_current(self.shared.display, None, None, None)
            .map_err(|e| Error::Gl(format!("eglMakeCurrent(release) failed: {e}")))
    }
}

impl Drop for EglSurface {
    fn drop(&mut self) {
        // A context still current somewhere is destroyed when released (EGL rule).
        let _ = self
            .shared
            .egl
            .destroy_context(self.shared.display, self.compositor);
        let _ = self
            .shared
            .egl
            .destroy_context(self.shared.display, self.app);
    }
}

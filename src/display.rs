//! A display: one backend connection, the configurations it offers, and the
//! surfaces made on it.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, OnceLock};

use crate::backend::{self, BackendChoice, BackendKind, Platform};
use crate::config::{Config, ConfigRequest, EmulationPolicy};
use crate::error::{Error, Result};
use crate::gl::Gl;
use crate::stereo::eye_memory::MemoryObjectApi;
use crate::surface::Surface;

/// A backend connection. Shared (`Arc`) by the surfaces made on it, which
/// keep it alive after the program closes it.
pub struct Display {
    platform: Box<dyn Platform>,
    gl: OnceLock<Arc<Gl>>,
    /// GL_EXT_memory_object(_fd), loaded with the GL table (None where the
    /// driver lacks it): surfaces' eyes read in place
    /// ([`crate::stereo::eye_memory`]).
    memory_objects: OnceLock<Option<MemoryObjectApi>>,
    id: u64,
}

/// A new display id: unique for the life of the process (never reused, unlike
/// addresses), so a configuration can name the display that chose it.
fn next_id() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(1);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

impl std::fmt::Debug for Display {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Display({})", self.platform.kind().name())
    }
}

impl Display {
    /// Opens a backend. `BackendChoice::Auto` defers to GLSTEREO_BACKEND and
    /// then to the automatic order (see [`backend::open`]).
    pub fn open(choice: BackendChoice) -> Result<Arc<Display>> {
        let choice = match choice {
            BackendChoice::Auto => {
                BackendChoice::from_env_value(std::env::var("GLSTEREO_BACKEND").ok().as_deref())?
            }
            c => c,
        };
        Ok(Arc::new(Display {
            platform: backend::open(choice)?,
            gl: OnceLock::new(),
            memory_objects: OnceLock::new(),
            id: next_id(),
        }))
    }

    /// Opens the GLX backend on the X display `name` (None: $DISPLAY).
    pub fn open_x11(name: Option<&str>) -> Result<Arc<Display>> {
        Ok(Arc::new(Display {
            platform: Box::new(backend::glx::GlxPlatform::open(name)?),
            gl: OnceLock::new(),
            memory_objects: OnceLock::new(),
            id: next_id(),
        }))
    }

    /// This display's id, unique in the process.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Which backend this display uses.
    pub fn kind(&self) -> BackendKind {
        self.platform.kind()
    }

    pub(crate) fn platform(&self) -> &dyn Platform {
        &*self.platform
    }

    /// The GL table of this backend, loaded on first use (a context of the
    /// backend must be current then).
    pub(crate) fn gl(&self) -> Result<Arc<Gl>> {
        if let Some(gl) = self.gl.get() {
            return Ok(gl.clone());
        }
        // SAFETY: the backend's GetProcAddress returns its GL functions; the
        // caller made a context of this backend current.
        let gl =
            Arc::new(unsafe { Gl::load_current(|name| self.platform.get_proc_address(name))? });
        Ok(self.gl.get_or_init(|| gl).clone())
    }

    /// GL_EXT_memory_object(_fd)'s entry points of this backend, loaded on
    /// first use (None where any is missing; whether the driver takes
    /// memory is checked when a framebuffer is made, see
    /// [`crate::stereo::eye_memory`]).
    pub(crate) fn memory_objects(&self) -> Option<MemoryObjectApi> {
        *self.memory_objects.get_or_init(|| {
            // SAFETY: the backend's GetProcAddress returns its GL functions
            // (or NULL).
            unsafe { MemoryObjectApi::load(|name| self.platform.get_proc_address(name)) }
        })
    }

    /// Chooses a configuration for a glXChooseVisual attribute list (without
    /// the terminating None), honouring GLSTEREO_EMULATION.
    pub fn choose_config(&self, attribs: &[i32]) -> Result<Config> {
        let request = ConfigRequest::parse_visual_attribs(attribs)?;
        let policy =
            EmulationPolicy::from_env_value(std::env::var("GLSTEREO_EMULATION").ok().as_deref())?;
        let mut config = self.platform.choose_config(request, policy)?;
        config.display_id = self.id;
        Ok(config)
    }

    /// Creates a surface of `width` × `height` pixels per eye.
    pub fn create_surface(
        self: &Arc<Self>,
        config: &Config,
        width: u32,
        height: u32,
    ) -> Result<Arc<Surface>> {
        if config.display_id != self.id {
            // A GLX configuration holds a visual of its own X connection,
            // which may be closed by now; every backend refuses alike.
            return Err(Error::invalid_operation(
                "this configuration was chosen on another display: choose one on the display \
                 the surface is made on (gls_config_choose)",
            ));
        }
        Surface::create(self.clone(), config.clone(), width, height)
    }
}

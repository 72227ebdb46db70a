//! OSMesa: Mesa's off-screen software renderer, loaded with dlopen.
//!
//! libOSMesa exports its own `gl*` functions, distinct from libGL's: the
//! library loads every GL function through OSMesaGetProcAddress, and programs
//! that call GL themselves must link -lOSMesa instead of -lGL (see
//! [`super::program_gl_is_osmesa`]).

use std::ffi::{CStr, c_char, c_int, c_uint, c_void};
use std::sync::{Arc, OnceLock};

use super::{BackendKind, ContextRole, Platform, PlatformSurface};
use crate::config::Config;
use crate::error::{Error, Result};

type OSMesaContext = *mut c_void;
const OSMESA_FORMAT: c_int = 0x22;
const OSMESA_RGBA: c_int = 0x1908;
const OSMESA_DEPTH_BITS: c_int = 0x30;
const OSMESA_STENCIL_BITS: c_int = 0x31;
const OSMESA_PROFILE: c_int = 0x33;
const OSMESA_COMPAT_PROFILE: c_int = 0x35;
const OSMESA_CONTEXT_MAJOR_VERSION: c_int = 0x36;
const OSMESA_CONTEXT_MINOR_VERSION: c_int = 0x37;
const GL_UNSIGNED_BYTE: c_uint = 0x1401;

type CreateFn = unsafe extern "C" fn(*const c_int, OSMesaContext) -> OSMesaContext;
type MakeCurrentFn = unsafe extern "C" fn(OSMesaContext, *mut c_void, c_uint, c_int, c_int) -> u8;
type DestroyFn = unsafe extern "C" fn(OSMesaContext);
type GetProcFn = unsafe extern "C" fn(*const c_char) -> *const c_void;

struct OsMesaLib {
    _lib: libloading::Library,
    create_context_attribs: CreateFn,
    make_current: MakeCurrentFn,
    destroy_context: DestroyFn,
    get_proc_address: GetProcFn,
}

fn install_hint() -> &'static str {
    "install libosmesa6 (Debian), or set GLSTEREO_BACKEND=egl"
}

fn lib() -> Result<Arc<OsMesaLib>> {
    static LIB: OnceLock<std::result::Result<Arc<OsMesaLib>, String>> = OnceLock::new();
    LIB.get_or_init(|| load().map(Arc::new).map_err(|e| e.to_string()))
        .clone()
        .map_err(Error::BackendUnavailable)
}

fn load() -> Result<OsMesaLib> {
    // SAFETY: loading Mesa's OSMesa runs only its (well-behaved) initialisers.
    let lib = unsafe { libloading::Library::new("libOSMesa.so.8") }
        .or_else(|_| unsafe { libloading::Library::new("libOSMesa.so") })
        .map_err(|e| {
            Error::BackendUnavailable(format!(
                "libOSMesa.so.8 could not be loaded ({e}): {}",
                install_hint()
            ))
        })?;
    fn sym<T: Copy>(lib: &libloading::Library, name: &str) -> Result<T> {
        // SAFETY: each caller names an OSMesa function whose C signature is T
        // (GL/osmesa.h); the library outlives the copied pointer (kept in OsMesaLib).
        unsafe { lib.get::<T>(name.as_bytes()).map(|s| *s) }.map_err(|e| {
            Error::BackendUnavailable(format!("libOSMesa lacks {name} ({e}): {}", install_hint()))
        })
    }
    Ok(OsMesaLib {
        create_context_attribs: sym::<CreateFn>(&lib, "OSMesaCreateContextAttribs")?,
        make_current: sym::<MakeCurrentFn>(&lib, "OSMesaMakeCurrent")?,
        destroy_context: sym::<DestroyFn>(&lib, "OSMesaDestroyContext")?,
        get_proc_address: sym::<GetProcFn>(&lib, "OSMesaGetProcAddress")?,
        _lib: lib,
    })
}

impl OsMesaLib {
    /// A compatibility-profile context (4.5 when available) with no depth or
    /// stencil of its own: rendering goes to glstereo's framebuffer objects.
    fn create_context(&self, share: OSMesaContext) -> Result<OSMesaContext> {
        let compat_45 = [
            OSMESA_FORMAT,
            OSMESA_RGBA,
            OSMESA_DEPTH_BITS,
            0,
            OSMESA_STENCIL_BITS,
            0,
            OSMESA_PROFILE,
            OSMESA_COMPAT_PROFILE,
            OSMESA_CONTEXT_MAJOR_VERSION,
            4,
            OSMESA_CONTEXT_MINOR_VERSION,
            5,
            0,
        ];
        let plain = [
            OSMESA_FORMAT,
            OSMESA_RGBA,
            OSMESA_DEPTH_BITS,
            0,
            OSMESA_STENCIL_BITS,
            0,
            0,
        ];
        // SAFETY: zero-terminated attribute lists; `share` is NULL or a live context.
        let ctx = unsafe {
            let c = (self.create_context_attribs)(compat_45.as_ptr(), share);
            if c.is_null() {
                (self.create_context_attribs)(plain.as_ptr(), share)
            } else {
                c
            }
        };
        if ctx.is_null() {
            Err(Error::BackendUnavailable(
                "OSMesaCreateContextAttribs failed to create a compatibility context".into(),
            ))
        } else {
            Ok(ctx)
        }
    }
}

/// The OSMesa backend.
pub struct OsMesaPlatform {
    lib: Arc<OsMesaLib>,
}

impl OsMesaPlatform {
    /// Loads libOSMesa.
    pub fn open() -> Result<OsMesaPlatform> {
        Ok(OsMesaPlatform { lib: lib()? })
    }
}

impl Platform for OsMesaPlatform {
    fn kind(&self) -> BackendKind {
        BackendKind::OsMesa
    }

    fn create_surface(
        &self,
        _config: &Config,
        _w: u32,
        _h: u32,
    ) -> Result<Box<dyn PlatformSurface>> {
        let app = self.lib.create_context(std::ptr::null_mut())?;
        let compositor = match self.lib.create_context(app) {
            Ok(c) => c,
            Err(e) => {
                // SAFETY: `app` was just created and is current nowhere.
                unsafe { (self.lib.destroy_context)(app) };
                return Err(e);
            }
        };
        Ok(Box::new(OsMesaSurface {
            lib: self.lib.clone(),
            app,
            compositor,
            buffer: Box::new([0u8; 4]),
        }))
    }

    fn get_proc_address(&self, name: &CStr) -> *const c_void {
        // SAFETY: NUL-terminated name.
        unsafe { (self.lib.get_proc_address)(name.as_ptr()) }
    }
}

/// Two OSMesa contexts sharing objects, bound to a 1x1 buffer: OSMesa needs
/// a buffer to make a context current, but all rendering goes to glstereo's
/// framebuffer objects.
struct OsMesaSurface {
    lib: Arc<OsMesaLib>,
    app: OSMesaContext,
    compositor: OSMesaContext,
    buffer: Box<[u8; 4]>,
}

// SAFETY: OSMesa contexts may be made current on any thread (one at a time,
// as GL requires); the buffer is only written by GL while bound.
unsafe impl Send for OsMesaSurface {}
// SAFETY: as above.
unsafe impl Sync for OsMesaSurface {}

impl PlatformSurface for OsMesaSurface {
    fn make_current(&self, role: ContextRole) -> Result<()> {
        let ctx = match role {
            ContextRole::App => self.app,
            ContextRole::Compositor => self.compositor,
        };
        // SAFETY: live context, and a 1x1 RGBA buffer that outlives it.
        let ok = unsafe {
            (self.lib.make_current)(
                ctx,
                self.buffer.as_ptr() as *mut c_void,
                GL_UNSIGNED_BYTE,
                1,
                1,
            )
        };
        if ok == 0 {
            Err(Error::Gl("OSMesaMakeCurrent failed".into()))
        } else {
            Ok(())
        }
    }

    fn native_handles(&self) -> super::NativeHandles {
        super::NativeHandles::OsMesa {
            context: self.app,
            buffer: self.buffer.as_ptr() as *mut c_void,
        }
    }

    fn release_current(&self) -> Result<()> {
        // SAFETY: NULL context and buffer release the calling thread's context.
        unsafe { (self.lib.make_current)(std::ptr::null_mut(), std::ptr::null_mut(), 0, 0, 0) };
        Ok(())
    }
}

impl Drop for OsMesaSurface {
    fn drop(&mut self) {
        // SAFETY: both contexts are live; Surface released them before dropping.
        unsafe {
            (self.lib.destroy_context)(self.compositor);
            (self.lib.destroy_context)(self.app);
        }
    }
}

//! The real GLX and GL entry points, whatever the program calls: libGL is
//! opened by name (`dlopen("libGL.so.1")`) and its symbols looked up in it,
//! never by global name, so the interposer's own exports (preloaded, hence
//! first in the global scope) are never found by mistake. GL functions come
//! from the real `glXGetProcAddressARB` (libglvnd's dispatch stubs, which
//! call the context current on the calling thread).

use std::ffi::{CStr, c_char, c_int, c_ulong, c_void};
use std::sync::OnceLock;

use x11_dl::glx::{GLXContext, GLXFBConfig, Glx};
use x11_dl::xlib::{self, Xlib};

use crate::gl::Gl;

/// `glXCreateContextAttribsARB`.
pub type CreateContextAttribs = unsafe extern "C" fn(
    *mut xlib::Display,
    GLXFBConfig,
    GLXContext,
    c_int,
    *const c_int,
) -> GLXContext;

/// A function looked up by name, as `glXGetProcAddress` returns it.
pub type AnyFn = unsafe extern "C" fn();

/// Entry points that are not part of x11-dl's GLX table or of [`Gl`].
pub struct Extra {
    /// `glXCreateContextAttribsARB` (None without GLX_ARB_create_context).
    pub create_context_attribs: Option<CreateContextAttribs>,
    /// `glBindFramebufferEXT`.
    pub bind_framebuffer_ext: Option<unsafe extern "system" fn(u32, u32)>,
    /// `glDeleteFramebuffersEXT`.
    pub delete_framebuffers_ext: Option<unsafe extern "system" fn(i32, *const u32)>,
    /// `glDrawBuffersARB`.
    pub draw_buffers_arb: Option<unsafe extern "system" fn(i32, *const u32)>,
    /// `glGetFramebufferAttachmentParameterivEXT`.
    pub get_attachment_ext: Option<unsafe extern "system" fn(u32, u32, u32, *mut i32)>,
    /// `glPushAttrib` (compatibility profile).
    pub push_attrib: Option<unsafe extern "system" fn(u32)>,
    /// `glPopAttrib` (compatibility profile).
    pub pop_attrib: Option<unsafe extern "system" fn()>,
    /// The SGIX FBConfig functions (GLX_SGIX_fbconfig), which take configs too.
    pub sgix: Sgix,
}

/// GLX_SGIX_fbconfig and GLX_SGIX_pbuffer entry points.
#[allow(clippy::type_complexity)]
pub struct Sgix {
    /// `glXChooseFBConfigSGIX`.
    pub choose: Option<
        unsafe extern "C" fn(
            *mut xlib::Display,
            c_int,
            *const c_int,
            *mut c_int,
        ) -> *mut GLXFBConfig,
    >,
    /// `glXGetFBConfigAttribSGIX`.
    pub get_attrib:
        Option<unsafe extern "C" fn(*mut xlib::Display, GLXFBConfig, c_int, *mut c_int) -> c_int>,
    /// `glXGetVisualFromFBConfigSGIX`.
    pub get_visual:
        Option<unsafe extern "C" fn(*mut xlib::Display, GLXFBConfig) -> *mut xlib::XVisualInfo>,
    /// `glXCreateContextWithConfigSGIX`.
    pub create_context: Option<
        unsafe extern "C" fn(
            *mut xlib::Display,
            GLXFBConfig,
            c_int,
            GLXContext,
            c_int,
        ) -> GLXContext,
    >,
    /// `glXCreateGLXPixmapWithConfigSGIX`.
    pub create_pixmap:
        Option<unsafe extern "C" fn(*mut xlib::Display, GLXFBConfig, c_ulong) -> c_ulong>,
    /// `glXCreateGLXPbufferSGIX`.
    pub create_pbuffer: Option<
        unsafe extern "C" fn(*mut xlib::Display, GLXFBConfig, u32, u32, *const c_int) -> c_ulong,
    >,
}

/// libX11, libGL's GLX functions, and the GL table, as loaded once.
pub struct Real {
    /// libX11 (XGetGeometry, XFree, error handling).
    pub xlib: Xlib,
    /// libGL's GLX functions.
    pub glx: Glx,
    /// GL functions (dispatch stubs). Textures and renderbuffers made
    /// through it take reserved names ([`Gl::reserve_names`]).
    pub gl: Gl,
    /// The rest.
    pub extra: Extra,
}

// SAFETY: function tables only; the functions are thread-safe as GLX and
// GL define them (each call applies to the calling thread's context).
unsafe impl Send for Real {}
// SAFETY: as above.
unsafe impl Sync for Real {}

static REAL: OnceLock<Result<Real, String>> = OnceLock::new();

/// The real entry points, loaded on first use; Err says why they cannot be
/// (libGL or libX11 missing: a program calling GLX has both).
pub fn real() -> Result<&'static Real, &'static str> {
    REAL.get_or_init(load).as_ref().map_err(|e| e.as_str())
}

/// [`real`] as the crate's [`crate::Error`]: GLS_ERROR_BACKEND_UNAVAILABLE
/// with the reason.
pub fn loaded() -> crate::Result<&'static Real> {
    real().map_err(|e| crate::Error::BackendUnavailable(e.into()))
}

fn load() -> Result<Real, String> {
    let xlib = Xlib::open()
        .map_err(|e| format!("libX11 could not be loaded ({e}): install libx11-6 (Debian)"))?;
    let glx = Glx::open().map_err(|e| {
        format!(
            "the real libGL.so.1 could not be loaded ({e}): install libgl1 and \
             libglx-mesa0 (Debian) or your GL driver's libGL"
        )
    })?;
    let get = |name: &CStr| -> *const c_void {
        // SAFETY: NUL-terminated name; libGL's own glXGetProcAddressARB.
        unsafe { (glx.glXGetProcAddressARB)(name.as_ptr() as *const u8) }
            .map_or(std::ptr::null(), |f| f as *const c_void)
    };
    // SAFETY: glXGetProcAddressARB returns each named GL function (libglvnd
    // returns a dispatch stub for every gl* name) or NULL.
    let mut gl = unsafe { Gl::load(get) }.map_err(|e| e.to_string())?;
    gl.reserve_names();
    macro_rules! lookup {
        ($name:literal) => {{
            let p = get($name);
            // SAFETY: the named function's address, transmuted to its
            // Khronos signature (the field's type).
            (!p.is_null()).then(|| unsafe { std::mem::transmute::<*const c_void, _>(p) })
        }};
    }
    let extra = Extra {
        create_context_attribs: lookup!(c"glXCreateContextAttribsARB"),
        bind_framebuffer_ext: lookup!(c"glBindFramebufferEXT"),
        delete_framebuffers_ext: lookup!(c"glDeleteFramebuffersEXT"),
        draw_buffers_arb: lookup!(c"glDrawBuffersARB"),
        get_attachment_ext: lookup!(c"glGetFramebufferAttachmentParameterivEXT"),
        push_attrib: lookup!(c"glPushAttrib"),
        pop_attrib: lookup!(c"glPopAttrib"),
        sgix: Sgix {
            choose: lookup!(c"glXChooseFBConfigSGIX"),
            get_attrib: lookup!(c"glXGetFBConfigAttribSGIX"),
            get_visual: lookup!(c"glXGetVisualFromFBConfigSGIX"),
            create_context: lookup!(c"glXCreateContextWithConfigSGIX"),
            create_pixmap: lookup!(c"glXCreateGLXPixmapWithConfigSGIX"),
            create_pbuffer: lookup!(c"glXCreateGLXPbufferSGIX"),
        },
    };
    Ok(Real {
        xlib,
        glx,
        gl,
        extra,
    })
}

/// The real `glXGetProcAddressARB(name)`.
///
/// # Safety
/// `name` must be a NUL-terminated string.
pub unsafe fn get_proc_address(name: *const c_char) -> Option<AnyFn> {
    let r = real().ok()?;
    // SAFETY: forwarded contract.
    unsafe { (r.glx.glXGetProcAddressARB)(name as *const u8) }
}

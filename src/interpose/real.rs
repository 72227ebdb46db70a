//! The real GLX and GL entry points, whatever the program calls: each is
//! the next definition of its name after the layer in the chain of
//! preloaded libraries, else libGL's ([`super::next`] says how, and why
//! never the layer's own). GL functions come from the next
//! `glXGetProcAddressARB` (libglvnd's dispatch stubs, which call the
//! context current on the calling thread, or a layer's below) — from the
//! next `eglGetProcAddress` in a process that draws through EGL.

use std::ffi::{CStr, c_char, c_int, c_uchar, c_uint, c_ulong, c_void};
use std::sync::OnceLock;

use x11_dl::glx::{GLXContext, GLXFBConfig};
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

/// `glColorMaski` and its extension names.
pub type ColorMaski = unsafe extern "system" fn(u32, u8, u8, u8, u8);

/// An indexed glGet (`glGetBooleani_v`, `glGetIntegeri_v`, …) whose values
/// are `T`s.
pub type GetIndexed<T> = unsafe extern "system" fn(u32, u32, *mut T);

/// `glClearColorx` / `glClearColorxOES` (16.16 fixed point).
pub type ClearColorx = unsafe extern "system" fn(i32, i32, i32, i32);

/// Entry points that are not part of x11-dl's GLX table or of [`Gl`].
pub struct Extra {
    /// `glXCreateContextAttribsARB` (None without GLX_ARB_create_context).
    pub create_context_attribs: Option<CreateContextAttribs>,
    /// `glBindFramebufferEXT`.
    pub bind_framebuffer_ext: Option<unsafe extern "system" fn(u32, u32)>,
    /// `glDeleteFramebuffersEXT`.
    pub delete_framebuffers_ext: Option<unsafe extern "system" fn(i32, *const u32)>,
    /// `glDeleteTexturesEXT` (GL_EXT_texture_object).
    pub delete_textures_ext: Option<unsafe extern "system" fn(i32, *const u32)>,
    /// `glDeleteRenderbuffersEXT` (GL_EXT_framebuffer_object).
    pub delete_renderbuffers_ext: Option<unsafe extern "system" fn(i32, *const u32)>,
    /// `glDrawBuffersARB`.
    pub draw_buffers_arb: Option<unsafe extern "system" fn(i32, *const u32)>,
    /// `glGetFramebufferAttachmentParameterivEXT`.
    pub get_attachment_ext: Option<unsafe extern "system" fn(u32, u32, u32, *mut i32)>,
    /// `glPushAttrib` (compatibility profile).
    pub push_attrib: Option<unsafe extern "system" fn(u32)>,
    /// `glPopAttrib` (compatibility profile).
    pub pop_attrib: Option<unsafe extern "system" fn()>,
    /// `glColorMaski` (GL 3.0).
    pub color_maski: Option<ColorMaski>,
    /// `glColorMaskIndexedEXT` (GL_EXT_draw_buffers2).
    pub color_mask_indexed_ext: Option<ColorMaski>,
    /// `glColorMaskiEXT` (GL_EXT_draw_buffers_indexed; Mesa serves it in
    /// desktop contexts too).
    pub color_maski_ext: Option<ColorMaski>,
    /// `glColorMaskiOES` (GL_OES_draw_buffers_indexed; as above).
    pub color_maski_oes: Option<ColorMaski>,
    /// `glGetBooleani_v` (GL 3.0).
    pub get_booleani_v: Option<GetIndexed<u8>>,
    /// `glGetBooleanIndexedvEXT` (GL_EXT_draw_buffers2).
    pub get_boolean_indexedv_ext: Option<GetIndexed<u8>>,
    /// `glGetIntegeri_v` (GL 3.0).
    pub get_integeri_v: Option<GetIndexed<i32>>,
    /// `glGetIntegerIndexedvEXT` (GL_EXT_draw_buffers2).
    pub get_integer_indexedv_ext: Option<GetIndexed<i32>>,
    /// `glGetInteger64i_v` (GL 3.2).
    pub get_integer64i_v: Option<GetIndexed<i64>>,
    /// `glGetFloati_v` (GL 4.1).
    pub get_floati_v: Option<GetIndexed<f32>>,
    /// `glGetFloati_vEXT` (GL_EXT_direct_state_access).
    pub get_floati_v_ext: Option<GetIndexed<f32>>,
    /// `glGetFloati_vOES` (GL_OES_viewport_array; Mesa serves it in desktop
    /// contexts too).
    pub get_floati_v_oes: Option<GetIndexed<f32>>,
    /// `glGetFloatIndexedvEXT` (GL_EXT_direct_state_access).
    pub get_float_indexedv_ext: Option<GetIndexed<f32>>,
    /// `glGetDoublei_v` (GL 4.1).
    pub get_doublei_v: Option<GetIndexed<f64>>,
    /// `glGetDoublei_vEXT` (GL_EXT_direct_state_access).
    pub get_doublei_v_ext: Option<GetIndexed<f64>>,
    /// `glGetDoubleIndexedvEXT` (GL_EXT_direct_state_access).
    pub get_double_indexedv_ext: Option<GetIndexed<f64>>,
    /// `glGetInteger64v` (GL 3.2).
    pub get_integer64v: Option<unsafe extern "system" fn(u32, *mut i64)>,
    /// `glClearColorIiEXT` (GL_EXT_texture_integer).
    pub clear_color_ii_ext: Option<unsafe extern "system" fn(i32, i32, i32, i32)>,
    /// `glClearColorIuiEXT` (GL_EXT_texture_integer).
    pub clear_color_iui_ext: Option<unsafe extern "system" fn(u32, u32, u32, u32)>,
    /// `glClearColorx` (GL_OES_fixed_point's name in OpenGL ES 1; Mesa
    /// serves it in compatibility contexts).
    pub clear_colorx: Option<ClearColorx>,
    /// `glClearColorxOES` (GL_OES_fixed_point).
    pub clear_colorx_oes: Option<ClearColorx>,
    /// GL_EXT_memory_object(_fd): eye textures read in place
    /// ([`crate::stereo::eye_memory`]).
    pub memory_objects: Option<crate::stereo::eye_memory::MemoryObjectApi>,
    /// GL 3.2–4.3's layered attachments and image copies: automatic
    /// stereo's eyes ([`crate::auto::eyes`]).
    pub layered: Option<crate::auto::eyes::LayeredApi>,
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
    /// `glXDestroyGLXPbufferSGIX`.
    pub destroy_pbuffer: Option<unsafe extern "C" fn(*mut xlib::Display, c_ulong)>,
}

macro_rules! glx_table {
    ($( $name:ident ( $($arg:ty),* ) $(-> $ret:ty)? ; )*) => {
        /// The GLX functions the layer forwards to, as [`super::next`] finds them.
        #[allow(non_snake_case, missing_docs)]
        pub struct Glx {
            $( pub $name: unsafe extern "C" fn($($arg),*) $(-> $ret)?, )*
        }

        impl Glx {
            /// Looks every function up; Err names the first one missing.
            fn load() -> Result<Glx, String> {
                Ok(Glx {
                    $( $name: {
                        let name = concat!(stringify!($name), "\0");
                        let p = super::next::next_symbol(
                            CStr::from_bytes_with_nul(name.as_bytes()).expect("NUL-terminated"),
                        );
                        if p.is_null() {
                            let why = if super::next::libgl_loadable() {
                                format!("has no {}", stringify!($name))
                            } else {
                                "could not be loaded".to_owned()
                            };
                            return Err(format!(
                                "the real libGL.so.1 {why}: install libgl1 and libglx-mesa0 \
                                 (Debian) or your GL driver's libGL"
                            ));
                        }
                        // SAFETY: the named GLX function's address, transmuted
                        // to its GLX 1.4 signature (the field's type).
                        unsafe {
                            std::mem::transmute::<*mut c_void, unsafe extern "C" fn($($arg),*) $(-> $ret)?>(p)
                        }
                    }, )*
                })
            }
        }
    };
}

glx_table! {
    glXChooseFBConfig(*mut xlib::Display, c_int, *const c_int, *mut c_int) -> *mut GLXFBConfig;
    glXChooseVisual(*mut xlib::Display, c_int, *mut c_int) -> *mut xlib::XVisualInfo;
    glXCreateContext(*mut xlib::Display, *mut xlib::XVisualInfo, GLXContext, c_int) -> GLXContext;
    glXCreateNewContext(*mut xlib::Display, GLXFBConfig, c_int, GLXContext, c_int) -> GLXContext;
    glXCreatePbuffer(*mut xlib::Display, GLXFBConfig, *const c_int) -> c_ulong;
    glXCreatePixmap(*mut xlib::Display, GLXFBConfig, c_ulong, *const c_int) -> c_ulong;
    glXCreateWindow(*mut xlib::Display, GLXFBConfig, c_ulong, *const c_int) -> c_ulong;
    glXDestroyContext(*mut xlib::Display, GLXContext);
    glXDestroyWindow(*mut xlib::Display, c_ulong);
    glXDestroyPbuffer(*mut xlib::Display, c_ulong);
    glXDestroyPixmap(*mut xlib::Display, c_ulong);
    glXDestroyGLXPixmap(*mut xlib::Display, c_ulong);
    glXGetConfig(*mut xlib::Display, *mut xlib::XVisualInfo, c_int, *mut c_int) -> c_int;
    glXGetCurrentContext() -> GLXContext;
    glXGetCurrentDisplay() -> *mut xlib::Display;
    glXGetCurrentDrawable() -> c_ulong;
    glXGetCurrentReadDrawable() -> c_ulong;
    glXGetFBConfigAttrib(*mut xlib::Display, GLXFBConfig, c_int, *mut c_int) -> c_int;
    glXGetFBConfigs(*mut xlib::Display, c_int, *mut c_int) -> *mut GLXFBConfig;
    glXGetProcAddressARB(*const c_uchar) -> Option<unsafe extern "C" fn()>;
    glXGetVisualFromFBConfig(*mut xlib::Display, GLXFBConfig) -> *mut xlib::XVisualInfo;
    glXIsDirect(*mut xlib::Display, GLXContext) -> c_int;
    glXMakeContextCurrent(*mut xlib::Display, c_ulong, c_ulong, GLXContext) -> c_int;
    glXMakeCurrent(*mut xlib::Display, c_ulong, GLXContext) -> c_int;
    glXQueryDrawable(*mut xlib::Display, c_ulong, c_int, *mut c_uint);
    glXSwapBuffers(*mut xlib::Display, c_ulong);
}

/// libX11, libGL's GLX functions, and the GL table, as loaded once.
pub struct Real {
    /// libX11 (XGetGeometry, XFree, error handling).
    pub xlib: Xlib,
    /// The GLX functions below the layer.
    pub glx: Glx,
    /// GL functions (dispatch stubs). The objects made through it in a
    /// program's share group are named as [`crate::gl::names`] says
    /// ([`Gl::own_names`]).
    pub gl: Gl,
    /// The rest.
    pub extra: Extra,
    /// The next glXSwapBuffers is not libGL's own but a GL layer's below
    /// this one (MangoHud draws its HUD there, VirtualGL sends the frame,
    /// apitrace records it): every frame must go through it.
    pub swap_layered: bool,
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

/// The GL below the layer by name, for automatic stereo
/// ([`crate::auto::host::set_gl_lookup`]).
fn gl_below(name: &CStr) -> *const c_void {
    real().map_or(std::ptr::null(), |r| gl_symbol(&r.glx, name))
}

fn load() -> Result<Real, String> {
    crate::auto::host::set_gl_lookup(gl_below);
    let xlib = Xlib::open()
        .map_err(|e| format!("libX11 could not be loaded ({e}): install libx11-6 (Debian)"))?;
    let glx = Glx::load()?;
    let get = |name: &CStr| -> *const c_void { gl_symbol(&glx, name) };
    // SAFETY: the next glXGetProcAddressARB returns each named GL function
    // (libglvnd returns a dispatch stub for every gl* name) or NULL.
    let mut gl = unsafe { Gl::load(get) }.map_err(|e| e.to_string())?;
    // Names by the share group of the context current on the thread, as
    // the layer saw it made current (asking GLX or EGL is not harmless).
    gl.own_names(super::wsi::made_current_context);
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
        delete_textures_ext: lookup!(c"glDeleteTexturesEXT"),
        delete_renderbuffers_ext: lookup!(c"glDeleteRenderbuffersEXT"),
        draw_buffers_arb: lookup!(c"glDrawBuffersARB"),
        get_attachment_ext: lookup!(c"glGetFramebufferAttachmentParameterivEXT"),
        push_attrib: lookup!(c"glPushAttrib"),
        pop_attrib: lookup!(c"glPopAttrib"),
        color_maski: lookup!(c"glColorMaski"),
        color_mask_indexed_ext: lookup!(c"glColorMaskIndexedEXT"),
        color_maski_ext: lookup!(c"glColorMaskiEXT"),
        color_maski_oes: lookup!(c"glColorMaskiOES"),
        get_booleani_v: lookup!(c"glGetBooleani_v"),
        get_boolean_indexedv_ext: lookup!(c"glGetBooleanIndexedvEXT"),
        get_integeri_v: lookup!(c"glGetIntegeri_v"),
        get_integer_indexedv_ext: lookup!(c"glGetIntegerIndexedvEXT"),
        get_integer64i_v: lookup!(c"glGetInteger64i_v"),
        get_floati_v: lookup!(c"glGetFloati_v"),
        get_floati_v_ext: lookup!(c"glGetFloati_vEXT"),
        get_floati_v_oes: lookup!(c"glGetFloati_vOES"),
        get_float_indexedv_ext: lookup!(c"glGetFloatIndexedvEXT"),
        get_doublei_v: lookup!(c"glGetDoublei_v"),
        get_doublei_v_ext: lookup!(c"glGetDoublei_vEXT"),
        get_double_indexedv_ext: lookup!(c"glGetDoubleIndexedvEXT"),
        get_integer64v: lookup!(c"glGetInteger64v"),
        clear_color_ii_ext: lookup!(c"glClearColorIiEXT"),
        clear_color_iui_ext: lookup!(c"glClearColorIuiEXT"),
        clear_colorx: lookup!(c"glClearColorx"),
        clear_colorx_oes: lookup!(c"glClearColorxOES"),
        // SAFETY: `get` returns the named GL function or NULL.
        memory_objects: unsafe { crate::stereo::eye_memory::MemoryObjectApi::load(get) },
        // SAFETY: as above.
        layered: unsafe { crate::auto::eyes::LayeredApi::load(get) },
        sgix: Sgix {
            choose: lookup!(c"glXChooseFBConfigSGIX"),
            get_attrib: lookup!(c"glXGetFBConfigAttribSGIX"),
            get_visual: lookup!(c"glXGetVisualFromFBConfigSGIX"),
            create_context: lookup!(c"glXCreateContextWithConfigSGIX"),
            create_pixmap: lookup!(c"glXCreateGLXPixmapWithConfigSGIX"),
            create_pbuffer: lookup!(c"glXCreateGLXPbufferSGIX"),
            destroy_pbuffer: lookup!(c"glXDestroyGLXPbufferSGIX"),
        },
    };
    let swap_layered = glx.glXSwapBuffers as *const c_void
        != super::next::bottom_symbol(c"glXSwapBuffers").cast_const();
    Ok(Real {
        xlib,
        glx,
        gl,
        extra,
        swap_layered,
    })
}

/// A GL or GLX function below the layer: the next glXGetProcAddressARB's
/// answer; where that is the layer's own (a layer below that looks names
/// up globally hands the layer's exports back), the next definition of
/// the name ([`super::next::next_symbol`], which is never the layer's).
fn gl_symbol(glx: &Glx, name: &CStr) -> *const c_void {
    // A process that draws through EGL gets its GL functions from the next
    // eglGetProcAddress: a layer below that wraps EGL (apitrace's
    // egltrace, MangoHud) sees the layer's calls and the program's it
    // forwards, as it would the program's own. (libglvnd hands out the
    // same dispatch stubs either way.)
    if let Some(e) = super::egl::egl_if_loaded() {
        if !name.to_bytes().starts_with(b"glX") {
            // SAFETY: NUL-terminated name; the next eglGetProcAddress.
            let p = unsafe { (e.eglGetProcAddress)(name.as_ptr()) }.cast_const();
            if !p.is_null() && !super::next::is_own(p) {
                return p;
            }
        }
    }
    // SAFETY: NUL-terminated name; the next glXGetProcAddressARB.
    let p = unsafe { (glx.glXGetProcAddressARB)(name.as_ptr() as *const u8) }
        .map_or(std::ptr::null(), |f| f as *const c_void);
    if super::next::is_own(p) {
        super::next::next_symbol(name)
    } else {
        p
    }
}

/// The real `glXGetProcAddressARB(name)`: the function below the layer.
///
/// # Safety
/// `name` must be a NUL-terminated string.
pub unsafe fn get_proc_address(name: *const c_char) -> Option<AnyFn> {
    let r = real().ok()?;
    // SAFETY: the caller's NUL-terminated name.
    let p = gl_symbol(&r.glx, unsafe { CStr::from_ptr(name) });
    // SAFETY: NULL or a function's address, as glXGetProcAddress returns.
    unsafe { std::mem::transmute::<*const c_void, Option<AnyFn>>(p) }
}

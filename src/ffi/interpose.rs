//! Legacy GLX and GL entry points with emulated stereo, for programs that
//! create their own GLX contexts and windows (the logic is in
//! [`crate::interpose`]).
//!
//! Unmodified binaries get these under their real names from
//! `libglstereo_preload.so` (run them with `glstereo-run`). Programs rebuilt
//! from source include `<glstereo/compat.h>` after the GL headers, which
//! maps the legacy names onto these `gls_glx_*` / `gls_gl_*` functions, and
//! link with `-lglstereo` (and `-lGL -lX11` as before).
//!
//! Each behaves as the GLX or GL function it replaces (same arguments, same
//! results, same GL errors), with these differences: GLX_STEREO requests
//! succeed on servers without stereo visuals, contexts made from them have
//! an emulated quad-buffered default framebuffer, and each swap shows both
//! eyes in the window in GLSTEREO_MODE (default anaglyph-red-cyan). A
//! program that does not ask for stereo is served by the real libGL
//! unchanged. Types: `Display*`, `XVisualInfo*`, `GLXContext` and
//! `GLXFBConfig` are passed as `void *`, X drawables as `unsigned long`,
//! GL enums as `uint32_t`. Thread rules are GLX's and GL's: GL calls apply
//! to the context current on the calling thread. They report as the
//! functions they replace do (return values, GL errors); problems the layer
//! cannot report that way (no GL 3.0, a context it cannot create) are
//! written to stderr once, prefixed `glstereo:`, and the context then runs
//! in mono. Misuse: a call libGL survives goes to libGL; a call libGL would
//! crash on is refused — see "Misuse" in [`crate::interpose`] and the doc
//! of [`gls_glx_choose_visual`] (the family's, in the header).

use std::ffi::{c_int, c_uchar, c_ulong, c_void};

use x11_dl::glx::{GLXContext, GLXFBConfig};
use x11_dl::xlib::XVisualInfo;

use super::boundary::ffi_boundary;
use crate::interpose::binaries as ibin;
use crate::interpose::dsa as idsa;
use crate::interpose::gl as igl;
use crate::interpose::glx::{self as iglx, Destroy, Flavour, NewContext, Offscreen};

/// The gls_glx_* and gls_gl_* functions stand in for the legacy GLX and GL
/// functions a stereo program calls: `<glstereo/compat.h>` maps their
/// names onto these for programs rebuilt from source (link -lglstereo
/// -lGL -lX11), and libglstereo_preload.so exports them under the real
/// names for unmodified binaries (glstereo-run). Each takes the arguments
/// of the function it replaces (`Display*`, `XVisualInfo*`, `GLXContext`,
/// `GLXFBConfig` as `void *`; drawables as `unsigned long`; GL enums as
/// `uint32_t`), returns what it returns and raises the GL errors it
/// raises; thread rules are GLX's and GL's (GL calls apply to the context
/// current on the calling thread). What the layer cannot report that way
/// (no GL 3.0, a context it cannot create) goes to stderr once, prefixed
/// `glstereo:`, and that context runs in mono. Output settings come from
/// GLSTEREO_MODE, GLSTEREO_SWAP_EYES, GLSTEREO_CROSSTALK,
/// GLSTEREO_SATURATION and GLSTEREO_CAPTURE_DIR, read once.
///
/// Misuse. A call libGL survives goes to libGL, and the program gets what
/// libGL gives: its return value, its X error (through the program's X
/// error handler), its GL error (through glGetError) — for a bad screen,
/// attribute, render type, drawable or enum, a configuration or context
/// libGL does not know (a destroyed one: GLXBadContext). A call libGL
/// would crash on is refused before it gets there: nothing changes, it
/// returns what the function returns on failure (NULL, None, False;
/// GLX_BAD_VALUE from glXGetConfig and glXGetFBConfigAttrib, libglvnd's
/// answer to a NULL there) and leaves a message, for
/// gls_last_error_message() ("gls_glx_choose_visual: dpy (the Display*)
/// must not be NULL") and on stderr once per distinct message
/// ("glstereo: glXChooseVisual refused: …", the channel unmodified binaries
/// have). Refused: a NULL Display* (every function; a release,
/// glXMakeCurrent(dpy, None, NULL), is allowed with NULL, as libglvnd
/// allows it); NULL for glXChooseVisual's attribute list, glXCreateContext's
/// visual, nelements, the value of glXGetConfig / glXGetFBConfigAttrib and
/// glXGetProcAddress's name; a share context the program destroyed (the
/// last 256 are remembered); a stereo context destroyed while current
/// (which GLX keeps until it is released, and the layer destroys then),
/// made current or destroyed again before its release. In GL, a NULL
/// pointer GL would read or write through (glGet*v and glGet*i_v data,
/// glDrawBuffers and glDeleteFramebuffers with n > 0,
/// glGetFramebufferAttachmentParameteriv
/// params; glClearBuffer* and glClearNamedFramebuffer* values,
/// glNamedFramebufferDrawBuffers and glInvalidate(Sub)Framebuffer lists
/// with n > 0, glGet(Named)FramebufferParameteriv and
/// glGetNamedFramebufferAttachmentParameteriv params, glCreateShaderProgramv
/// strings with count > 0, glGetProgramiv params, glGetProgramBinary's
/// format and, with bufSize > 0, binary, glProgramBinary's binary with
/// length > 0): nothing happens but GL_INVALID_VALUE for glGetError in the
/// current context (none with no context current). A pointer that is not
/// NULL but wrong (freed, too short, not terminated) cannot be detected.
/// An internal failure (a bug) is caught and reported as a refusal.
///
/// `glXChooseVisual`: a GLX_STEREO request gets the server's matching
/// mono visual, which the layer then treats as stereo (glXGetConfig
/// reports GLX_STEREO true; contexts created with it are stereo). The
/// result is freed with XFree as usual; NULL when nothing matches.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_choose_visual(
    dpy: *mut c_void,
    screen: c_int,
    attribs: *mut c_int,
) -> *mut c_void {
    ffi_boundary!("gls_glx_choose_visual" for "glXChooseVisual", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::choose_visual(dpy.cast(), screen, attribs) }.map(|p| p.cast())
    })
}

/// `glXGetConfig`: GLX_STEREO is 1 for a visual handed out for a stereo
/// request; everything else is the real visual's. Returns 0 (Success) or
/// a GLX error code (GLX_BAD_VALUE for a NULL display, visual or value).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_get_config(
    dpy: *mut c_void,
    vis: *mut c_void,
    attrib: c_int,
    value: *mut c_int,
) -> c_int {
    ffi_boundary!("gls_glx_get_config" for "glXGetConfig", iglx::GLX_BAD_VALUE => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::get_config(dpy.cast(), vis as *mut XVisualInfo, attrib, value) }
    })
}

/// `glXChooseFBConfig`: with GLX_STEREO True, the configurations matching
/// the rest of the list, as stereo configurations of the layer's (handles
/// every GLX function here accepts; GLX_STEREO reads 1). Freed with XFree.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_choose_fbconfig(
    dpy: *mut c_void,
    screen: c_int,
    attribs: *const c_int,
    nelements: *mut c_int,
) -> *mut *mut c_void {
    ffi_boundary!("gls_glx_choose_fbconfig" for "glXChooseFBConfig", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::choose_fbconfig(dpy.cast(), screen, attribs, nelements, Flavour::Glx13) }.map(|p| p.cast())
    })
}

/// `glXChooseFBConfigSGIX`: as gls_glx_choose_fbconfig().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_choose_fbconfig_sgix(
    dpy: *mut c_void,
    screen: c_int,
    attribs: *const c_int,
    nelements: *mut c_int,
) -> *mut *mut c_void {
    ffi_boundary!("gls_glx_choose_fbconfig_sgix" for "glXChooseFBConfigSGIX", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::choose_fbconfig(dpy.cast(), screen, attribs, nelements, Flavour::Sgix) }.map(|p| p.cast())
    })
}

/// `glXGetFBConfigs`: the server's configurations in their order, followed
/// by a stereo twin of each RGBA window configuration. Freed with XFree.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_get_fbconfigs(
    dpy: *mut c_void,
    screen: c_int,
    nelements: *mut c_int,
) -> *mut *mut c_void {
    ffi_boundary!("gls_glx_get_fbconfigs" for "glXGetFBConfigs", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::get_fbconfigs(dpy.cast(), screen, nelements) }.map(|p| p.cast())
    })
}

/// `glXGetFBConfigAttrib`: GLX_STEREO is 1 for a stereo configuration;
/// everything else is the real configuration's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_get_fbconfig_attrib(
    dpy: *mut c_void,
    config: *mut c_void,
    attribute: c_int,
    value: *mut c_int,
) -> c_int {
    ffi_boundary!("gls_glx_get_fbconfig_attrib" for "glXGetFBConfigAttrib", iglx::GLX_BAD_VALUE => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::get_fbconfig_attrib(dpy.cast(), config as GLXFBConfig, attribute, value, Flavour::Glx13) }
    })
}

/// `glXGetFBConfigAttribSGIX`: as gls_glx_get_fbconfig_attrib().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_get_fbconfig_attrib_sgix(
    dpy: *mut c_void,
    config: *mut c_void,
    attribute: c_int,
    value: *mut c_int,
) -> c_int {
    ffi_boundary!("gls_glx_get_fbconfig_attrib_sgix" for "glXGetFBConfigAttribSGIX", iglx::GLX_BAD_VALUE => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::get_fbconfig_attrib(dpy.cast(), config as GLXFBConfig, attribute, value, Flavour::Sgix) }
    })
}

/// `glXGetVisualFromFBConfig`: the visual of a configuration; for a stereo
/// configuration the visual is treated as stereo (see
/// gls_glx_choose_visual()). Freed with XFree.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_get_visual_from_fbconfig(
    dpy: *mut c_void,
    config: *mut c_void,
) -> *mut c_void {
    ffi_boundary!("gls_glx_get_visual_from_fbconfig" for "glXGetVisualFromFBConfig", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::get_visual_from_fbconfig(dpy.cast(), config as GLXFBConfig, Flavour::Glx13) }.map(|p| p.cast())
    })
}

/// `glXGetVisualFromFBConfigSGIX`: as gls_glx_get_visual_from_fbconfig().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_get_visual_from_fbconfig_sgix(
    dpy: *mut c_void,
    config: *mut c_void,
) -> *mut c_void {
    ffi_boundary!("gls_glx_get_visual_from_fbconfig_sgix" for "glXGetVisualFromFBConfigSGIX", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::get_visual_from_fbconfig(dpy.cast(), config as GLXFBConfig, Flavour::Sgix) }.map(|p| p.cast())
    })
}

/// `glXCreateContext`: with a stereo visual, a stereo context (the layer
/// also creates a context of its own sharing its objects, to present).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_context(
    dpy: *mut c_void,
    vis: *mut c_void,
    share_list: *mut c_void,
    direct: c_int,
) -> *mut c_void {
    ffi_boundary!("gls_glx_create_context" for "glXCreateContext", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::create_context(dpy.cast(), vis.cast(), share_list as GLXContext, direct) }.map(|p| p.cast())
    })
}

/// `glXCreateNewContext`: with a stereo configuration, a stereo context.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_new_context(
    dpy: *mut c_void,
    config: *mut c_void,
    render_type: c_int,
    share_list: *mut c_void,
    direct: c_int,
) -> *mut c_void {
    ffi_boundary!("gls_glx_create_new_context" for "glXCreateNewContext", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe {
            iglx::create_config_context(
                dpy.cast(),
                config as GLXFBConfig,
                NewContext::RenderType(render_type, Flavour::Glx13),
                share_list as GLXContext,
                direct,
            )
        }
        .map(|p| p.cast())
    })
}

/// `glXCreateContextWithConfigSGIX`: as gls_glx_create_new_context().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_context_with_config_sgix(
    dpy: *mut c_void,
    config: *mut c_void,
    render_type: c_int,
    share_list: *mut c_void,
    direct: c_int,
) -> *mut c_void {
    ffi_boundary!("gls_glx_create_context_with_config_sgix" for "glXCreateContextWithConfigSGIX", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe {
            iglx::create_config_context(
                dpy.cast(),
                config as GLXFBConfig,
                NewContext::RenderType(render_type, Flavour::Sgix),
                share_list as GLXContext,
                direct,
            )
        }
        .map(|p| p.cast())
    })
}

/// `glXCreateContextAttribsARB` (GLX_ARB_create_context): with a stereo
/// configuration, a stereo context of any version and profile (3.0 or
/// newer hosts the emulation; older ones run in mono, said on stderr).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_context_attribs_arb(
    dpy: *mut c_void,
    config: *mut c_void,
    share_context: *mut c_void,
    direct: c_int,
    attrib_list: *const c_int,
) -> *mut c_void {
    ffi_boundary!("gls_glx_create_context_attribs_arb" for "glXCreateContextAttribsARB", std::ptr::null_mut() => {
        // SAFETY: GLX's contract, forwarded.
        unsafe {
            iglx::create_config_context(
                dpy.cast(),
                config as GLXFBConfig,
                NewContext::Attribs(attrib_list),
                share_context as GLXContext,
                direct,
            )
        }
        .map(|p| p.cast())
    })
}

/// `glXDestroyContext`, with the layer's context of a stereo one. A stereo
/// context current on a thread stays usable there and is destroyed when it
/// is released, as GLX says.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_destroy_context(dpy: *mut c_void, ctx: *mut c_void) {
    ffi_boundary!("gls_glx_destroy_context" for "glXDestroyContext", () => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::destroy_context(dpy.cast(), ctx as GLXContext) }
    })
}

/// `glXMakeCurrent`: for a stereo context, binds the drawable's emulated
/// framebuffer (made, or resized to the drawable, first) where the program
/// has framebuffer 0. Returns True or False as the real call does.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_make_current(
    dpy: *mut c_void,
    drawable: c_ulong,
    ctx: *mut c_void,
) -> c_int {
    ffi_boundary!("gls_glx_make_current" for "glXMakeCurrent", 0 => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::make_current(dpy.cast(), drawable, None, ctx as GLXContext) }
    })
}

/// `glXMakeContextCurrent`: as gls_glx_make_current(), with separate
/// draw and read drawables.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_make_context_current(
    dpy: *mut c_void,
    draw: c_ulong,
    read: c_ulong,
    ctx: *mut c_void,
) -> c_int {
    ffi_boundary!("gls_glx_make_context_current" for "glXMakeContextCurrent", 0 => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::make_current(dpy.cast(), draw, Some(read), ctx as GLXContext) }
    })
}

/// `glXSwapBuffers`: for a stereo drawable, each eye's back buffer becomes
/// its front buffer, and the front buffers are shown composed in
/// GLSTEREO_MODE (and captured with GLSTEREO_CAPTURE_DIR).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_swap_buffers(dpy: *mut c_void, drawable: c_ulong) {
    ffi_boundary!("gls_glx_swap_buffers" for "glXSwapBuffers", () => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::swap_buffers(dpy.cast(), drawable) }
    })
}

/// `glXCreateWindow` (a stereo configuration makes a window of its real one).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_window(
    dpy: *mut c_void,
    config: *mut c_void,
    win: c_ulong,
    attrib_list: *const c_int,
) -> c_ulong {
    ffi_boundary!("gls_glx_create_window" for "glXCreateWindow", 0 => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::create_window(dpy.cast(), config as GLXFBConfig, win, attrib_list) }
    })
}

/// `glXDestroyWindow`: the stereo buffers of the window go with it, in
/// every stereo context it was bound to (where it is current, when it is
/// released, as GLX keeps a current drawable until then).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_destroy_window(dpy: *mut c_void, window: c_ulong) {
    ffi_boundary!("gls_glx_destroy_window" for "glXDestroyWindow", () => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::destroy_drawable(dpy.cast(), window, Destroy::Window) }
    })
}

/// `glXDestroyPbuffer`: as gls_glx_destroy_window().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_destroy_pbuffer(dpy: *mut c_void, pbuf: c_ulong) {
    ffi_boundary!("gls_glx_destroy_pbuffer" for "glXDestroyPbuffer", () => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::destroy_drawable(dpy.cast(), pbuf, Destroy::Pbuffer) }
    })
}

/// `glXDestroyGLXPbufferSGIX`: as gls_glx_destroy_window().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_destroy_glx_pbuffer_sgix(dpy: *mut c_void, pbuf: c_ulong) {
    ffi_boundary!("gls_glx_destroy_glx_pbuffer_sgix" for "glXDestroyGLXPbufferSGIX", () => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::destroy_drawable(dpy.cast(), pbuf, Destroy::PbufferSgix) }
    })
}

/// `glXDestroyPixmap`: as gls_glx_destroy_window().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_destroy_pixmap(dpy: *mut c_void, pixmap: c_ulong) {
    ffi_boundary!("gls_glx_destroy_pixmap" for "glXDestroyPixmap", () => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::destroy_drawable(dpy.cast(), pixmap, Destroy::Pixmap) }
    })
}

/// `glXDestroyGLXPixmap`: as gls_glx_destroy_window().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_destroy_glx_pixmap(dpy: *mut c_void, pixmap: c_ulong) {
    ffi_boundary!("gls_glx_destroy_glx_pixmap" for "glXDestroyGLXPixmap", () => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::destroy_drawable(dpy.cast(), pixmap, Destroy::GlxPixmap) }
    })
}

/// `glXCreatePixmap` (mono: the real configuration of a stereo one).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_pixmap(
    dpy: *mut c_void,
    config: *mut c_void,
    pixmap: c_ulong,
    attrib_list: *const c_int,
) -> c_ulong {
    ffi_boundary!("gls_glx_create_pixmap" for "glXCreatePixmap", 0 => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::create_offscreen(dpy.cast(), config as GLXFBConfig, Offscreen::Pixmap(pixmap, attrib_list)) }
    })
}

/// `glXCreatePbuffer` (mono: the real configuration of a stereo one).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_pbuffer(
    dpy: *mut c_void,
    config: *mut c_void,
    attrib_list: *const c_int,
) -> c_ulong {
    ffi_boundary!("gls_glx_create_pbuffer" for "glXCreatePbuffer", 0 => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::create_offscreen(dpy.cast(), config as GLXFBConfig, Offscreen::Pbuffer(attrib_list)) }
    })
}

/// `glXCreateGLXPixmapWithConfigSGIX`: as gls_glx_create_pixmap().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_glx_pixmap_with_config_sgix(
    dpy: *mut c_void,
    config: *mut c_void,
    pixmap: c_ulong,
) -> c_ulong {
    ffi_boundary!("gls_glx_create_glx_pixmap_with_config_sgix" for "glXCreateGLXPixmapWithConfigSGIX", 0 => {
        // SAFETY: GLX's contract, forwarded.
        unsafe { iglx::create_offscreen(dpy.cast(), config as GLXFBConfig, Offscreen::PixmapSgix(pixmap)) }
    })
}

/// `glXCreateGLXPbufferSGIX`: as gls_glx_create_pbuffer().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_create_glx_pbuffer_sgix(
    dpy: *mut c_void,
    config: *mut c_void,
    width: u32,
    height: u32,
    attrib_list: *const c_int,
) -> c_ulong {
    ffi_boundary!("gls_glx_create_glx_pbuffer_sgix" for "glXCreateGLXPbufferSGIX", 0 => {
        // SAFETY: GLX's contract, forwarded.
        unsafe {
            iglx::create_offscreen(dpy.cast(), config as GLXFBConfig, Offscreen::PbufferSgix(width, height, attrib_list))
        }
    })
}

/// `glDrawBuffer`: on the emulated default framebuffer, any of GL_NONE,
/// GL_FRONT_LEFT, GL_FRONT_RIGHT, GL_BACK_LEFT, GL_BACK_RIGHT, GL_FRONT,
/// GL_BACK, GL_LEFT, GL_RIGHT, GL_FRONT_AND_BACK; GL_INVALID_ENUM for a
/// value that names no buffer, GL_INVALID_OPERATION for a buffer the
/// visual lacks (an aux buffer, an attachment); nothing changes on error.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_draw_buffer(buf: u32) {
    ffi_boundary!("gls_gl_draw_buffer" for "glDrawBuffer", () => {
        igl::draw_buffer(buf)
    })
}

/// `glDrawBuffers`: on the emulated default framebuffer each entry is
/// GL_NONE or one of the four buffers (GL_BACK alone); GL errors as GL's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_draw_buffers(n: i32, bufs: *const u32) {
    ffi_boundary!("gls_gl_draw_buffers" for "glDrawBuffers", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::draw_buffers(n, bufs, false) }
    })
}

/// `glDrawBuffersARB`: as gls_gl_draw_buffers().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_draw_buffers_arb(n: i32, bufs: *const u32) {
    ffi_boundary!("gls_gl_draw_buffers_arb" for "glDrawBuffersARB", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::draw_buffers(n, bufs, true) }
    })
}

/// `glReadBuffer`: on the emulated default framebuffer, the names
/// glDrawBuffer accepts (GL_FRONT, GL_LEFT and GL_FRONT_AND_BACK read
/// front-left; GL_BACK back-left; GL_RIGHT front-right); errors as
/// gls_gl_draw_buffer().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_read_buffer(src: u32) {
    ffi_boundary!("gls_gl_read_buffer" for "glReadBuffer", () => {
        igl::read_buffer(src)
    })
}

/// `glGetError`: the emulation's errors first (each code once), then the driver's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_get_error() -> u32 {
    ffi_boundary!("gls_gl_get_error" for "glGetError", 0 => { igl::get_error() })
}

/// `glGetIntegerv`: GL_STEREO, GL_DOUBLEBUFFER, GL_DRAW_BUFFER(i),
/// GL_READ_BUFFER and the framebuffer bindings as a stereo visual would
/// answer; colour, depth and stencil bits as the window's visual.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_integerv(pname: u32, data: *mut i32) {
    ffi_boundary!("gls_gl_get_integerv" for "glGetIntegerv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_integerv(pname, data) }
    })
}

/// `glGetBooleanv`: as gls_gl_get_integerv().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_booleanv(pname: u32, data: *mut u8) {
    ffi_boundary!("gls_gl_get_booleanv" for "glGetBooleanv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_booleanv(pname, data) }
    })
}

/// `glGetFloatv`: as gls_gl_get_integerv().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_floatv(pname: u32, data: *mut f32) {
    ffi_boundary!("gls_gl_get_floatv" for "glGetFloatv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_floatv(pname, data) }
    })
}

/// `glGetDoublev`: as gls_gl_get_integerv().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_doublev(pname: u32, data: *mut f64) {
    ffi_boundary!("gls_gl_get_doublev" for "glGetDoublev", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_doublev(pname, data) }
    })
}

/// `glBindFramebuffer`: framebuffer 0 is the emulated default framebuffer.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_bind_framebuffer(target: u32, framebuffer: u32) {
    ffi_boundary!("gls_gl_bind_framebuffer" for "glBindFramebuffer", () => {
        igl::bind_framebuffer(target, framebuffer, false)
    })
}

/// `glBindFramebufferEXT`: as gls_gl_bind_framebuffer().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_bind_framebuffer_ext(target: u32, framebuffer: u32) {
    ffi_boundary!("gls_gl_bind_framebuffer_ext" for "glBindFramebufferEXT", () => {
        igl::bind_framebuffer(target, framebuffer, true)
    })
}

/// `glDeleteFramebuffers`: never deletes the emulated framebuffer; a
/// deleted bound framebuffer reverts to the emulated one.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_delete_framebuffers(n: i32, framebuffers: *const u32) {
    ffi_boundary!("gls_gl_delete_framebuffers" for "glDeleteFramebuffers", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::delete_framebuffers(n, framebuffers, false) }
    })
}

/// `glDeleteFramebuffersEXT`: as gls_gl_delete_framebuffers().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_delete_framebuffers_ext(n: i32, framebuffers: *const u32) {
    ffi_boundary!("gls_gl_delete_framebuffers_ext" for "glDeleteFramebuffersEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::delete_framebuffers(n, framebuffers, true) }
    })
}

/// `glDeleteTextures`: the layer's own textures (in the program's share
/// group, under names from the top of the non-negative range) are left
/// alone, as names the program never made are; every other name is
/// deleted.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_delete_textures(n: i32, textures: *const u32) {
    ffi_boundary!("gls_gl_delete_textures" for "glDeleteTextures", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::delete_objects(n, textures, igl::Deleted::Textures(false)) }
    })
}

/// `glDeleteTexturesEXT`: as gls_gl_delete_textures().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_delete_textures_ext(n: i32, textures: *const u32) {
    ffi_boundary!("gls_gl_delete_textures_ext" for "glDeleteTexturesEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::delete_objects(n, textures, igl::Deleted::Textures(true)) }
    })
}

/// `glDeleteRenderbuffers`: as gls_gl_delete_textures(), for the layer's
/// depth/stencil renderbuffers.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_delete_renderbuffers(n: i32, renderbuffers: *const u32) {
    ffi_boundary!("gls_gl_delete_renderbuffers" for "glDeleteRenderbuffers", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::delete_objects(n, renderbuffers, igl::Deleted::Renderbuffers(false)) }
    })
}

/// `glDeleteRenderbuffersEXT`: as gls_gl_delete_renderbuffers().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_delete_renderbuffers_ext(n: i32, renderbuffers: *const u32) {
    ffi_boundary!("gls_gl_delete_renderbuffers_ext" for "glDeleteRenderbuffersEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::delete_objects(n, renderbuffers, igl::Deleted::Renderbuffers(true)) }
    })
}

/// `glGetFramebufferAttachmentParameteriv`: on the emulated default
/// framebuffer, GL_FRONT_LEFT … GL_BACK_RIGHT, GL_DEPTH and GL_STENCIL
/// answer as the window's buffers do (a buffer the visual lacks has type
/// GL_NONE); other attachments are GL_INVALID_ENUM.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_framebuffer_attachment_parameteriv(
    target: u32,
    attachment: u32,
    pname: u32,
    params: *mut i32,
) {
    ffi_boundary!("gls_gl_get_framebuffer_attachment_parameteriv" for "glGetFramebufferAttachmentParameteriv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_framebuffer_attachment_parameteriv(target, attachment, pname, params, false) }
    })
}

/// `glGetFramebufferAttachmentParameterivEXT`: as
/// gls_gl_get_framebuffer_attachment_parameteriv().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_framebuffer_attachment_parameteriv_ext(
    target: u32,
    attachment: u32,
    pname: u32,
    params: *mut i32,
) {
    ffi_boundary!("gls_gl_get_framebuffer_attachment_parameteriv_ext" for "glGetFramebufferAttachmentParameterivEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_framebuffer_attachment_parameteriv(target, attachment, pname, params, true) }
    })
}

/// `glPushAttrib`: GL_COLOR_BUFFER_BIT also saves the emulated draw buffer,
/// GL_PIXEL_MODE_BIT the emulated read buffer.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_push_attrib(mask: u32) {
    ffi_boundary!("gls_gl_push_attrib" for "glPushAttrib", () => {
        igl::push_attrib(mask)
    })
}

/// `glPopAttrib`: restores what gls_gl_push_attrib() saved.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_pop_attrib() {
    ffi_boundary!("gls_gl_pop_attrib" for "glPopAttrib", () => {
        igl::pop_attrib()
    })
}

/// `glClearColor`: also kept by the layer (see gls_gl_clear()).
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_clear_color(red: f32, green: f32, blue: f32, alpha: f32) {
    ffi_boundary!("gls_gl_clear_color" for "glClearColor", () => {
        igl::clear_color(igl::ClearColor::Float([red, green, blue, alpha]), false)
    })
}

/// `glClearColorIiEXT` (GL_EXT_texture_integer): as gls_gl_clear_color().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_clear_color_ii_ext(red: i32, green: i32, blue: i32, alpha: i32) {
    ffi_boundary!("gls_gl_clear_color_ii_ext" for "glClearColorIiEXT", () => {
        igl::clear_color(igl::ClearColor::Int([red, green, blue, alpha]), false)
    })
}

/// `glClearColorIuiEXT` (GL_EXT_texture_integer): as gls_gl_clear_color().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_clear_color_iui_ext(red: u32, green: u32, blue: u32, alpha: u32) {
    ffi_boundary!("gls_gl_clear_color_iui_ext" for "glClearColorIuiEXT", () => {
        igl::clear_color(igl::ClearColor::Uint([red, green, blue, alpha]), false)
    })
}

/// `glClearColorx` (16.16 fixed point, GL_OES_fixed_point; Mesa serves it
/// in compatibility contexts): as gls_gl_clear_color().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_clear_colorx(red: i32, green: i32, blue: i32, alpha: i32) {
    ffi_boundary!("gls_gl_clear_colorx" for "glClearColorx", () => {
        igl::clear_color(igl::ClearColor::Fixed([red, green, blue, alpha]), false)
    })
}

/// `glClearColorxOES`: as gls_gl_clear_colorx().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_clear_colorx_oes(red: i32, green: i32, blue: i32, alpha: i32) {
    ffi_boundary!("gls_gl_clear_colorx_oes" for "glClearColorxOES", () => {
        igl::clear_color(igl::ClearColor::Fixed([red, green, blue, alpha]), true)
    })
}

/// `glClear`: on the emulated framebuffer of a visual without alpha, the
/// colour is cleared with alpha 1.0 (which that buffer always holds), so
/// that the driver's fast full clear serves it.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_clear(mask: u32) {
    ffi_boundary!("gls_gl_clear" for "glClear", () => {
        igl::clear(mask)
    })
}

/// `glColorMask`: the program's masks, as GL_COLOR_WRITEMASK answers them;
/// while the emulated framebuffer of a visual without alpha is bound, the
/// driver's masks never write alpha (its alpha stays 1.0).
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_color_mask(red: u8, green: u8, blue: u8, alpha: u8) {
    ffi_boundary!("gls_gl_color_mask" for "glColorMask", () => {
        igl::color_mask(red, green, blue, alpha)
    })
}

/// `glColorMaski`: as gls_gl_color_mask() for one draw buffer.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_color_maski(index: u32, red: u8, green: u8, blue: u8, alpha: u8) {
    ffi_boundary!("gls_gl_color_maski" for "glColorMaski", () => {
        igl::color_maski(igl::MaskiName::Core, index, red, green, blue, alpha)
    })
}

/// `glColorMaskIndexedEXT` (GL_EXT_draw_buffers2; Mesa serves it in desktop
/// contexts too): as gls_gl_color_maski().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_color_mask_indexed_ext(
    index: u32,
    red: u8,
    green: u8,
    blue: u8,
    alpha: u8,
) {
    ffi_boundary!("gls_gl_color_mask_indexed_ext" for "glColorMaskIndexedEXT", () => {
        igl::color_maski(igl::MaskiName::IndexedExt, index, red, green, blue, alpha)
    })
}

/// `glColorMaskiEXT` (GL_EXT_draw_buffers_indexed; Mesa serves it in desktop
/// contexts too): as gls_gl_color_maski().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_color_maski_ext(index: u32, red: u8, green: u8, blue: u8, alpha: u8) {
    ffi_boundary!("gls_gl_color_maski_ext" for "glColorMaskiEXT", () => {
        igl::color_maski(igl::MaskiName::Ext, index, red, green, blue, alpha)
    })
}

/// `glColorMaskiOES` (GL_OES_draw_buffers_indexed; Mesa serves it in desktop
/// contexts too): as gls_gl_color_maski().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_color_maski_oes(index: u32, red: u8, green: u8, blue: u8, alpha: u8) {
    ffi_boundary!("gls_gl_color_maski_oes" for "glColorMaskiOES", () => {
        igl::color_maski(igl::MaskiName::Oes, index, red, green, blue, alpha)
    })
}

/// `glGetBooleani_v`: GL_COLOR_WRITEMASK answers the program's masks
/// (what it set with gls_gl_color_mask() and gls_gl_color_maski()), where
/// the driver's masks may differ (they never write alpha to the emulated
/// framebuffer of a visual without alpha); every other state is the
/// driver's. Refused: `data` NULL.
///
/// # Safety
/// `data` must be valid for the values `pname` returns (GL's contract).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_booleani_v(target: u32, index: u32, data: *mut u8) {
    ffi_boundary!("gls_gl_get_booleani_v" for "glGetBooleani_v", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_BOOLEANI_V, target, index, data) }
    })
}

/// `glGetBooleanIndexedvEXT` (GL_EXT_draw_buffers2): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_boolean_indexedv_ext(target: u32, index: u32, data: *mut u8) {
    ffi_boundary!("gls_gl_get_boolean_indexedv_ext" for "glGetBooleanIndexedvEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_BOOLEAN_INDEXEDV_EXT, target, index, data) }
    })
}

/// `glGetIntegeri_v` (GL 3.0): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_integeri_v(target: u32, index: u32, data: *mut i32) {
    ffi_boundary!("gls_gl_get_integeri_v" for "glGetIntegeri_v", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_INTEGERI_V, target, index, data) }
    })
}

/// `glGetIntegerIndexedvEXT` (GL_EXT_draw_buffers2): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_integer_indexedv_ext(target: u32, index: u32, data: *mut i32) {
    ffi_boundary!("gls_gl_get_integer_indexedv_ext" for "glGetIntegerIndexedvEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_INTEGER_INDEXEDV_EXT, target, index, data) }
    })
}

/// `glGetInteger64i_v` (GL 3.2): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_integer64i_v(target: u32, index: u32, data: *mut i64) {
    ffi_boundary!("gls_gl_get_integer64i_v" for "glGetInteger64i_v", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_INTEGER64I_V, target, index, data) }
    })
}

/// `glGetFloati_v` (GL 4.1): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_floati_v(target: u32, index: u32, data: *mut f32) {
    ffi_boundary!("gls_gl_get_floati_v" for "glGetFloati_v", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_FLOATI_V, target, index, data) }
    })
}

/// `glGetFloati_vEXT` (GL_EXT_direct_state_access): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_floati_v_ext(target: u32, index: u32, data: *mut f32) {
    ffi_boundary!("gls_gl_get_floati_v_ext" for "glGetFloati_vEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_FLOATI_V_EXT, target, index, data) }
    })
}

/// `glGetFloati_vOES` (GL_OES_viewport_array): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_floati_v_oes(target: u32, index: u32, data: *mut f32) {
    ffi_boundary!("gls_gl_get_floati_v_oes" for "glGetFloati_vOES", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_FLOATI_V_OES, target, index, data) }
    })
}

/// `glGetFloatIndexedvEXT` (GL_EXT_direct_state_access): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_float_indexedv_ext(target: u32, index: u32, data: *mut f32) {
    ffi_boundary!("gls_gl_get_float_indexedv_ext" for "glGetFloatIndexedvEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_FLOAT_INDEXEDV_EXT, target, index, data) }
    })
}

/// `glGetDoublei_v` (GL 4.1): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_doublei_v(target: u32, index: u32, data: *mut f64) {
    ffi_boundary!("gls_gl_get_doublei_v" for "glGetDoublei_v", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_DOUBLEI_V, target, index, data) }
    })
}

/// `glGetDoublei_vEXT` (GL_EXT_direct_state_access): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_doublei_v_ext(target: u32, index: u32, data: *mut f64) {
    ffi_boundary!("gls_gl_get_doublei_v_ext" for "glGetDoublei_vEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_DOUBLEI_V_EXT, target, index, data) }
    })
}

/// `glGetDoubleIndexedvEXT` (GL_EXT_direct_state_access): as gls_gl_get_booleani_v().
///
/// # Safety
/// As gls_gl_get_booleani_v().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_double_indexedv_ext(target: u32, index: u32, data: *mut f64) {
    ffi_boundary!("gls_gl_get_double_indexedv_ext" for "glGetDoubleIndexedvEXT", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_indexed(&igl::GET_DOUBLE_INDEXEDV_EXT, target, index, data) }
    })
}

/// `glGetInteger64v` (GL 3.2): as gls_gl_get_integerv().
///
/// # Safety
/// `data` must be valid for the values `pname` returns (GL's contract).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_integer64v(pname: u32, data: *mut i64) {
    ffi_boundary!("gls_gl_get_integer64v" for "glGetInteger64v", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { igl::get_integer64v(pname, data) }
    })
}

/// `glBlitFramebuffer`: a blit into the emulated framebuffer of a visual
/// without alpha leaves its alpha 1.0, as on that visual.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn gls_gl_blit_framebuffer(
    src_x0: i32,
    src_y0: i32,
    src_x1: i32,
    src_y1: i32,
    dst_x0: i32,
    dst_y0: i32,
    dst_x1: i32,
    dst_y1: i32,
    mask: u32,
    filter: u32,
) {
    ffi_boundary!("gls_gl_blit_framebuffer" for "glBlitFramebuffer", () => {
        igl::blit_framebuffer(
            [src_x0, src_y0, src_x1, src_y1],
            [dst_x0, dst_y0, dst_x1, dst_y1],
            mask,
            filter,
        )
    })
}

/// `glViewport`: also notices a resized window (the emulated buffers follow
/// it before the program draws).
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_viewport(x: i32, y: i32, width: i32, height: i32) {
    ffi_boundary!("gls_gl_viewport" for "glViewport", () => {
        igl::viewport(x, y, width, height)
    })
}

/// `glFlush`: also shows the front buffers when the program draws to them.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_flush() {
    ffi_boundary!("gls_gl_flush" for "glFlush", () => {
        igl::flush(false)
    })
}

/// `glFinish`: as gls_gl_flush().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_finish() {
    ffi_boundary!("gls_gl_finish" for "glFinish", () => {
        igl::flush(true)
    })
}

/// `glXGetProcAddress` / `glXGetProcAddressARB`: these functions for the
/// names they replace (so programs that look GL and GLX functions up get
/// the stereo versions), the real libGL's for every other name.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_glx_get_proc_address(name: *const c_uchar) -> *mut c_void {
    ffi_boundary!("gls_glx_get_proc_address" for "glXGetProcAddress", std::ptr::null_mut() => {
        if name.is_null() {
            return Err(crate::Error::NullPointer("procName"));
        }
        // SAFETY: GLX's contract: a NUL-terminated name.
        let cname = unsafe { std::ffi::CStr::from_ptr(name.cast()) };
        if let Some(f) = replacement(cname.to_bytes()) {
            return Ok(f);
        }
        // Any other name is libGL's: without libGL, refused (with the reason).
        crate::interpose::real::loaded()?;
        // SAFETY: a NUL-terminated name.
        Ok(unsafe { crate::interpose::real::get_proc_address(name.cast()) }
            .map_or(std::ptr::null_mut(), |f| f as *mut c_void))
    })
}

/// The replacement of a GL or GLX function, by name.
pub fn replacement(name: &[u8]) -> Option<*mut c_void> {
    let f: *mut c_void = match name {
        b"glXChooseVisual" => gls_glx_choose_visual as *mut c_void,
        b"glXGetConfig" => gls_glx_get_config as *mut c_void,
        b"glXChooseFBConfig" => gls_glx_choose_fbconfig as *mut c_void,
        b"glXChooseFBConfigSGIX" => gls_glx_choose_fbconfig_sgix as *mut c_void,
        b"glXGetFBConfigs" => gls_glx_get_fbconfigs as *mut c_void,
        b"glXGetFBConfigAttrib" => gls_glx_get_fbconfig_attrib as *mut c_void,
        b"glXGetFBConfigAttribSGIX" => gls_glx_get_fbconfig_attrib_sgix as *mut c_void,
        b"glXGetVisualFromFBConfig" => gls_glx_get_visual_from_fbconfig as *mut c_void,
        b"glXGetVisualFromFBConfigSGIX" => gls_glx_get_visual_from_fbconfig_sgix as *mut c_void,
        b"glXCreateContext" => gls_glx_create_context as *mut c_void,
        b"glXCreateNewContext" => gls_glx_create_new_context as *mut c_void,
        b"glXCreateContextWithConfigSGIX" => gls_glx_create_context_with_config_sgix as *mut c_void,
        b"glXCreateContextAttribsARB" => gls_glx_create_context_attribs_arb as *mut c_void,
        b"glXDestroyContext" => gls_glx_destroy_context as *mut c_void,
        b"glXMakeCurrent" => gls_glx_make_current as *mut c_void,
        b"glXMakeContextCurrent" | b"glXMakeCurrentReadSGI" => {
            gls_glx_make_context_current as *mut c_void
        }
        b"glXSwapBuffers" => gls_glx_swap_buffers as *mut c_void,
        b"glXCreateWindow" => gls_glx_create_window as *mut c_void,
        b"glXDestroyWindow" => gls_glx_destroy_window as *mut c_void,
        b"glXDestroyPbuffer" => gls_glx_destroy_pbuffer as *mut c_void,
        b"glXDestroyGLXPbufferSGIX" => gls_glx_destroy_glx_pbuffer_sgix as *mut c_void,
        b"glXDestroyPixmap" => gls_glx_destroy_pixmap as *mut c_void,
        b"glXDestroyGLXPixmap" => gls_glx_destroy_glx_pixmap as *mut c_void,
        b"glXCreatePixmap" => gls_glx_create_pixmap as *mut c_void,
        b"glXCreatePbuffer" => gls_glx_create_pbuffer as *mut c_void,
        b"glXCreateGLXPixmapWithConfigSGIX" => {
            gls_glx_create_glx_pixmap_with_config_sgix as *mut c_void
        }
        b"glXCreateGLXPbufferSGIX" => gls_glx_create_glx_pbuffer_sgix as *mut c_void,
        b"glXGetProcAddress" | b"glXGetProcAddressARB" => gls_glx_get_proc_address as *mut c_void,
        b"glDrawBuffer" => gls_gl_draw_buffer as *mut c_void,
        b"glDrawBuffers" => gls_gl_draw_buffers as *mut c_void,
        b"glDrawBuffersARB" | b"glDrawBuffersATI" => gls_gl_draw_buffers_arb as *mut c_void,
        b"glReadBuffer" => gls_gl_read_buffer as *mut c_void,
        b"glGetError" => gls_gl_get_error as *mut c_void,
        b"glGetIntegerv" => gls_gl_get_integerv as *mut c_void,
        b"glGetBooleanv" => gls_gl_get_booleanv as *mut c_void,
        b"glGetFloatv" => gls_gl_get_floatv as *mut c_void,
        b"glGetDoublev" => gls_gl_get_doublev as *mut c_void,
        b"glBindFramebuffer" => gls_gl_bind_framebuffer as *mut c_void,
        b"glBindFramebufferEXT" => gls_gl_bind_framebuffer_ext as *mut c_void,
        b"glDeleteFramebuffers" => gls_gl_delete_framebuffers as *mut c_void,
        b"glDeleteFramebuffersEXT" => gls_gl_delete_framebuffers_ext as *mut c_void,
        b"glDeleteTextures" => gls_gl_delete_textures as *mut c_void,
        b"glDeleteTexturesEXT" => gls_gl_delete_textures_ext as *mut c_void,
        b"glDeleteRenderbuffers" => gls_gl_delete_renderbuffers as *mut c_void,
        b"glDeleteRenderbuffersEXT" => gls_gl_delete_renderbuffers_ext as *mut c_void,
        b"glGetFramebufferAttachmentParameteriv" => {
            gls_gl_get_framebuffer_attachment_parameteriv as *mut c_void
        }
        b"glGetFramebufferAttachmentParameterivEXT" => {
            gls_gl_get_framebuffer_attachment_parameteriv_ext as *mut c_void
        }
        b"glPushAttrib" => gls_gl_push_attrib as *mut c_void,
        b"glPopAttrib" => gls_gl_pop_attrib as *mut c_void,
        b"glViewport" => gls_gl_viewport as *mut c_void,
        b"glColorMask" => gls_gl_color_mask as *mut c_void,
        b"glClear" => gls_gl_clear as *mut c_void,
        b"glClearColor" => gls_gl_clear_color as *mut c_void,
        b"glColorMaski" => gls_gl_color_maski as *mut c_void,
        b"glGetBooleani_v" => gls_gl_get_booleani_v as *mut c_void,
        b"glGetBooleanIndexedvEXT" => gls_gl_get_boolean_indexedv_ext as *mut c_void,
        b"glGetIntegeri_v" => gls_gl_get_integeri_v as *mut c_void,
        b"glGetIntegerIndexedvEXT" => gls_gl_get_integer_indexedv_ext as *mut c_void,
        b"glGetInteger64i_v" => gls_gl_get_integer64i_v as *mut c_void,
        b"glGetFloati_v" => gls_gl_get_floati_v as *mut c_void,
        b"glGetFloati_vEXT" => gls_gl_get_floati_v_ext as *mut c_void,
        b"glGetFloati_vOES" => gls_gl_get_floati_v_oes as *mut c_void,
        b"glGetFloatIndexedvEXT" => gls_gl_get_float_indexedv_ext as *mut c_void,
        b"glGetDoublei_v" => gls_gl_get_doublei_v as *mut c_void,
        b"glGetDoublei_vEXT" => gls_gl_get_doublei_v_ext as *mut c_void,
        b"glGetDoubleIndexedvEXT" => gls_gl_get_double_indexedv_ext as *mut c_void,
        b"glGetInteger64v" => gls_gl_get_integer64v as *mut c_void,
        b"glColorMaskIndexedEXT" => gls_gl_color_mask_indexed_ext as *mut c_void,
        b"glColorMaskiEXT" => gls_gl_color_maski_ext as *mut c_void,
        b"glColorMaskiOES" => gls_gl_color_maski_oes as *mut c_void,
        b"glClearColorIiEXT" => gls_gl_clear_color_ii_ext as *mut c_void,
        b"glClearColorIuiEXT" => gls_gl_clear_color_iui_ext as *mut c_void,
        b"glClearColorx" => gls_gl_clear_colorx as *mut c_void,
        b"glClearColorxOES" => gls_gl_clear_colorx_oes as *mut c_void,
        b"glBlitFramebuffer" => gls_gl_blit_framebuffer as *mut c_void,
        b"glFlush" => gls_gl_flush as *mut c_void,
        b"glFinish" => gls_gl_finish as *mut c_void,
        b"glClearBufferfv" => gls_gl_clear_bufferfv as *mut c_void,
        b"glClearBufferiv" => gls_gl_clear_bufferiv as *mut c_void,
        b"glClearBufferuiv" => gls_gl_clear_bufferuiv as *mut c_void,
        b"glClearNamedFramebufferfv" => gls_gl_clear_named_framebufferfv as *mut c_void,
        b"glClearNamedFramebufferiv" => gls_gl_clear_named_framebufferiv as *mut c_void,
        b"glClearNamedFramebufferuiv" => gls_gl_clear_named_framebufferuiv as *mut c_void,
        b"glClearNamedFramebufferfi" => gls_gl_clear_named_framebufferfi as *mut c_void,
        b"glNamedFramebufferDrawBuffer" => gls_gl_named_framebuffer_draw_buffer as *mut c_void,
        b"glNamedFramebufferDrawBuffers" => gls_gl_named_framebuffer_draw_buffers as *mut c_void,
        b"glNamedFramebufferReadBuffer" => gls_gl_named_framebuffer_read_buffer as *mut c_void,
        b"glBlitNamedFramebuffer" => gls_gl_blit_named_framebuffer as *mut c_void,
        b"glInvalidateFramebuffer" => gls_gl_invalidate_framebuffer as *mut c_void,
        b"glInvalidateSubFramebuffer" => gls_gl_invalidate_sub_framebuffer as *mut c_void,
        b"glInvalidateNamedFramebufferData" => {
            gls_gl_invalidate_named_framebuffer_data as *mut c_void
        }
        b"glInvalidateNamedFramebufferSubData" => {
            gls_gl_invalidate_named_framebuffer_sub_data as *mut c_void
        }
        b"glCheckNamedFramebufferStatus" => gls_gl_check_named_framebuffer_status as *mut c_void,
        b"glCheckNamedFramebufferStatusEXT" => {
            gls_gl_check_named_framebuffer_status_ext as *mut c_void
        }
        b"glGetNamedFramebufferAttachmentParameteriv" => {
            gls_gl_get_named_framebuffer_attachment_parameteriv as *mut c_void
        }
        b"glGetNamedFramebufferParameteriv" => {
            gls_gl_get_named_framebuffer_parameteriv as *mut c_void
        }
        b"glGetFramebufferParameteriv" => gls_gl_get_framebuffer_parameteriv as *mut c_void,
        b"glLinkProgram" | b"glLinkProgramARB" => gls_gl_link_program as *mut c_void,
        b"glCreateShaderProgramv" => gls_gl_create_shader_programv as *mut c_void,
        b"glGetProgramiv" => gls_gl_get_programiv as *mut c_void,
        b"glGetProgramBinary" => gls_gl_get_program_binary as *mut c_void,
        b"glGetProgramBinaryOES" => gls_gl_get_program_binary_oes as *mut c_void,
        b"glProgramBinary" => gls_gl_program_binary as *mut c_void,
        b"glProgramBinaryOES" => gls_gl_program_binary_oes as *mut c_void,
        _ => return None,
    };
    Some(f)
}

/// `glClearBufferfv`: with the emulated default framebuffer bound and a
/// draw buffer name selecting several buffers (GL_BACK, GL_FRONT, GL_LEFT,
/// GL_RIGHT, GL_FRONT_AND_BACK), GL_COLOR draw buffer 0 clears each of
/// them, as GL 4.5 §17.4.3 says (draw buffers 1… are GL_NONE then).
/// Refused: `value` NULL (GL_INVALID_VALUE, nothing cleared).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_clear_bufferfv(buffer: u32, drawbuffer: i32, value: *const f32) {
    ffi_boundary!("gls_gl_clear_bufferfv" for "glClearBufferfv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::clear_buffer(buffer, drawbuffer, value) }
    })
}

/// `glClearBufferiv`: as gls_gl_clear_bufferfv().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_clear_bufferiv(buffer: u32, drawbuffer: i32, value: *const i32) {
    ffi_boundary!("gls_gl_clear_bufferiv" for "glClearBufferiv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::clear_buffer(buffer, drawbuffer, value) }
    })
}

/// `glClearBufferuiv`: as gls_gl_clear_bufferfv().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_clear_bufferuiv(buffer: u32, drawbuffer: i32, value: *const u32) {
    ffi_boundary!("gls_gl_clear_bufferuiv" for "glClearBufferuiv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::clear_buffer(buffer, drawbuffer, value) }
    })
}

/// `glClearNamedFramebufferfv`: framebuffer 0 is the emulated default
/// framebuffer, cleared as gls_gl_clear_bufferfv() clears it. Refused:
/// `value` NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_clear_named_framebufferfv(
    framebuffer: u32,
    buffer: u32,
    drawbuffer: i32,
    value: *const f32,
) {
    ffi_boundary!("gls_gl_clear_named_framebufferfv" for "glClearNamedFramebufferfv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::clear_named_framebuffer(framebuffer, buffer, drawbuffer, value) }
    })
}

/// `glClearNamedFramebufferiv`: as gls_gl_clear_named_framebufferfv().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_clear_named_framebufferiv(
    framebuffer: u32,
    buffer: u32,
    drawbuffer: i32,
    value: *const i32,
) {
    ffi_boundary!("gls_gl_clear_named_framebufferiv" for "glClearNamedFramebufferiv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::clear_named_framebuffer(framebuffer, buffer, drawbuffer, value) }
    })
}

/// `glClearNamedFramebufferuiv`: as gls_gl_clear_named_framebufferfv().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_clear_named_framebufferuiv(
    framebuffer: u32,
    buffer: u32,
    drawbuffer: i32,
    value: *const u32,
) {
    ffi_boundary!("gls_gl_clear_named_framebufferuiv" for "glClearNamedFramebufferuiv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::clear_named_framebuffer(framebuffer, buffer, drawbuffer, value) }
    })
}

/// `glClearNamedFramebufferfi`: framebuffer 0's depth/stencil buffer is
/// the emulated one, which both eyes share.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_clear_named_framebufferfi(
    framebuffer: u32,
    buffer: u32,
    drawbuffer: i32,
    depth: f32,
    stencil: i32,
) {
    ffi_boundary!("gls_gl_clear_named_framebufferfi" for "glClearNamedFramebufferfi", () => {
        idsa::clear_named_framebufferfi(framebuffer, buffer, drawbuffer, depth, stencil)
    })
}

/// `glNamedFramebufferDrawBuffer`: on framebuffer 0, as
/// gls_gl_draw_buffer() with framebuffer 0 bound (same selections, same GL
/// errors), whatever framebuffer is bound.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_named_framebuffer_draw_buffer(framebuffer: u32, buf: u32) {
    ffi_boundary!("gls_gl_named_framebuffer_draw_buffer" for "glNamedFramebufferDrawBuffer", () => {
        idsa::named_framebuffer_draw_buffer(framebuffer, buf)
    })
}

/// `glNamedFramebufferDrawBuffers`: on framebuffer 0, as
/// gls_gl_draw_buffers() with framebuffer 0 bound. Refused: `bufs` NULL
/// with n > 0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_named_framebuffer_draw_buffers(
    framebuffer: u32,
    n: i32,
    bufs: *const u32,
) {
    ffi_boundary!("gls_gl_named_framebuffer_draw_buffers" for "glNamedFramebufferDrawBuffers", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::named_framebuffer_draw_buffers(framebuffer, n, bufs) }
    })
}

/// `glNamedFramebufferReadBuffer`: on framebuffer 0, as
/// gls_gl_read_buffer() with framebuffer 0 bound.
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_named_framebuffer_read_buffer(framebuffer: u32, src: u32) {
    ffi_boundary!("gls_gl_named_framebuffer_read_buffer" for "glNamedFramebufferReadBuffer", () => {
        idsa::named_framebuffer_read_buffer(framebuffer, src)
    })
}

/// `glBlitNamedFramebuffer`: 0 on either side is the emulated default
/// framebuffer (its read buffer; its draw buffers, every buffer a name
/// such as GL_BACK selects).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn gls_gl_blit_named_framebuffer(
    read_framebuffer: u32,
    draw_framebuffer: u32,
    src_x0: i32,
    src_y0: i32,
    src_x1: i32,
    src_y1: i32,
    dst_x0: i32,
    dst_y0: i32,
    dst_x1: i32,
    dst_y1: i32,
    mask: u32,
    filter: u32,
) {
    ffi_boundary!("gls_gl_blit_named_framebuffer" for "glBlitNamedFramebuffer", () => {
        idsa::blit_named_framebuffer(
            read_framebuffer,
            draw_framebuffer,
            [src_x0, src_y0, src_x1, src_y1],
            [dst_x0, dst_y0, dst_x1, dst_y1],
            mask,
            filter,
        )
    })
}

/// `glInvalidateFramebuffer`: with framebuffer 0 bound, the attachments a
/// default framebuffer takes (GL_COLOR, GL_FRONT_LEFT … GL_BACK_RIGHT,
/// GL_DEPTH, GL_STENCIL) with the driver's errors; the emulated buffers
/// keep their contents (invalidation is a hint). Refused: `attachments`
/// NULL with n > 0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_invalidate_framebuffer(
    target: u32,
    num_attachments: i32,
    attachments: *const u32,
) {
    ffi_boundary!("gls_gl_invalidate_framebuffer" for "glInvalidateFramebuffer", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::invalidate_framebuffer(target, num_attachments, attachments) }
    })
}

/// `glInvalidateSubFramebuffer`: as gls_gl_invalidate_framebuffer().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_invalidate_sub_framebuffer(
    target: u32,
    num_attachments: i32,
    attachments: *const u32,
    x: i32,
    y: i32,
    width: i32,
    height: i32,
) {
    ffi_boundary!("gls_gl_invalidate_sub_framebuffer" for "glInvalidateSubFramebuffer", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::invalidate_sub_framebuffer(target, num_attachments, attachments, [x, y, width, height]) }
    })
}

/// `glInvalidateNamedFramebufferData`: on framebuffer 0, as
/// gls_gl_invalidate_framebuffer() with framebuffer 0 bound. Refused:
/// `attachments` NULL with n > 0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_invalidate_named_framebuffer_data(
    framebuffer: u32,
    num_attachments: i32,
    attachments: *const u32,
) {
    ffi_boundary!("gls_gl_invalidate_named_framebuffer_data" for "glInvalidateNamedFramebufferData", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::invalidate_named_framebuffer_data(framebuffer, num_attachments, attachments) }
    })
}

/// `glInvalidateNamedFramebufferSubData`: as
/// gls_gl_invalidate_named_framebuffer_data().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_invalidate_named_framebuffer_sub_data(
    framebuffer: u32,
    num_attachments: i32,
    attachments: *const u32,
    x: i32,
    y: i32,
    width: i32,
    height: i32,
) {
    ffi_boundary!("gls_gl_invalidate_named_framebuffer_sub_data" for "glInvalidateNamedFramebufferSubData", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe {
            idsa::invalidate_named_framebuffer_sub_data(
                framebuffer,
                num_attachments,
                attachments,
                [x, y, width, height],
            )
        }
    })
}

/// `glCheckNamedFramebufferStatus`: framebuffer 0 is the emulated default
/// framebuffer, complete as a window is (whatever a layer below has as its
/// framebuffer 0); `target` is checked as GL checks it (GL_INVALID_ENUM
/// and 0).
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_check_named_framebuffer_status(framebuffer: u32, target: u32) -> u32 {
    ffi_boundary!("gls_gl_check_named_framebuffer_status" for "glCheckNamedFramebufferStatus", 0 => {
        idsa::check_named_framebuffer_status(framebuffer, target, false)
    })
}

/// `glCheckNamedFramebufferStatusEXT` (GL_EXT_direct_state_access): as
/// gls_gl_check_named_framebuffer_status().
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_check_named_framebuffer_status_ext(framebuffer: u32, target: u32) -> u32 {
    ffi_boundary!("gls_gl_check_named_framebuffer_status_ext" for "glCheckNamedFramebufferStatusEXT", 0 => {
        idsa::check_named_framebuffer_status(framebuffer, target, true)
    })
}

/// `glGetNamedFramebufferAttachmentParameteriv`: on framebuffer 0, as
/// gls_gl_get_framebuffer_attachment_parameteriv() with framebuffer 0
/// bound (GL_FRAMEBUFFER_DEFAULT, the window's component sizes; the right
/// buffers as their left twins). Refused: `params` NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_named_framebuffer_attachment_parameteriv(
    framebuffer: u32,
    attachment: u32,
    pname: u32,
    params: *mut i32,
) {
    ffi_boundary!("gls_gl_get_named_framebuffer_attachment_parameteriv" for "glGetNamedFramebufferAttachmentParameteriv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::get_named_framebuffer_attachment_parameteriv(framebuffer, attachment, pname, params) }
    })
}

/// `glGetNamedFramebufferParameteriv`: on framebuffer 0, GL_STEREO and
/// GL_DOUBLEBUFFER of the emulated framebuffer; GL_SAMPLES,
/// GL_SAMPLE_BUFFERS, the implementation read format and type (and the
/// errors) of the window's. Refused: `params` NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_named_framebuffer_parameteriv(
    framebuffer: u32,
    pname: u32,
    params: *mut i32,
) {
    ffi_boundary!("gls_gl_get_named_framebuffer_parameteriv" for "glGetNamedFramebufferParameteriv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::get_named_framebuffer_parameteriv(framebuffer, pname, params) }
    })
}

/// `glGetFramebufferParameteriv`: with framebuffer 0 bound, as
/// gls_gl_get_named_framebuffer_parameteriv() on 0. Refused: `params` NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_framebuffer_parameteriv(
    target: u32,
    pname: u32,
    params: *mut i32,
) {
    ffi_boundary!("gls_gl_get_framebuffer_parameteriv" for "glGetFramebufferParameteriv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::get_framebuffer_parameteriv(target, pname, params) }
    })
}

/// `glLinkProgram`: in a stereo context, a program whose fragment shader
/// writes a user-defined output at location 0 (or `gl_FragData[0]`) is
/// linked a second time with that output also written to locations 5, 6 and
/// 7 (outputs `gls_stereo_copy5`…`7`, or `gl_FragData[5…7]`), which the
/// emulated framebuffer maps to the other buffers a name such as GL_BACK
/// selects: output 0 then reaches every selected buffer, as on a real
/// stereo framebuffer, with the shader run once per fragment. Where that
/// cannot be done (no GLSL source, several fragment shaders, locations 5…7
/// or dual-source outputs in use, `gl_FragData` elements other than 0
/// written) the program is linked as asked and stderr says why, once. It
/// also stands for `glLinkProgramARB` (whose handles are program names in
/// Mesa and the libglvnd drivers).
#[unsafe(no_mangle)]
pub extern "C" fn gls_gl_link_program(program: u32) {
    ffi_boundary!("gls_gl_link_program" for "glLinkProgram", () => {
        idsa::link_program(program)
    })
}

/// `glCreateShaderProgramv`: a fragment program is linked as
/// gls_gl_link_program() links one. Refused: `strings` NULL with count > 0
/// (returns 0).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_create_shader_programv(
    kind: u32,
    count: i32,
    strings: *const *const std::ffi::c_char,
) -> u32 {
    ffi_boundary!("gls_gl_create_shader_programv" for "glCreateShaderProgramv", 0 => {
        // SAFETY: GL's contract, forwarded.
        unsafe { idsa::create_shader_programv(kind, count, strings) }
    })
}

/// `glGetProgramiv`: in a stereo context GL_PROGRAM_BINARY_LENGTH counts
/// the 12-byte tag gls_gl_get_program_binary() puts before the driver's
/// binary; everything else is the driver's answer. Refused: `params` NULL
/// (GL_INVALID_VALUE, nothing written).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_programiv(program: u32, pname: u32, params: *mut i32) {
    ffi_boundary!("gls_gl_get_programiv" for "glGetProgramiv", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { ibin::get_programiv(program, pname, params) }
    })
}

/// `glGetProgramBinary`: in a stereo context, the driver's binary of the
/// program as linked there (with the copies of output 0 that
/// gls_gl_link_program() adds) behind a 12-byte tag of glstereo's, in the
/// driver's binary format; a program whose copies glstereo cannot vouch
/// for gets the driver's binary as it is. Refused: `binary_format` NULL,
/// or `binary` NULL with `buf_size` > 0 (GL_INVALID_VALUE).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_program_binary(
    program: u32,
    buf_size: i32,
    length: *mut i32,
    binary_format: *mut u32,
    binary: *mut c_void,
) {
    ffi_boundary!("gls_gl_get_program_binary" for "glGetProgramBinary", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { ibin::get_program_binary(program, buf_size, length, binary_format, binary, false) }
    })
}

/// `glGetProgramBinaryOES`: as gls_gl_get_program_binary().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_get_program_binary_oes(
    program: u32,
    buf_size: i32,
    length: *mut i32,
    binary_format: *mut u32,
    binary: *mut c_void,
) {
    ffi_boundary!("gls_gl_get_program_binary_oes" for "glGetProgramBinaryOES", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { ibin::get_program_binary(program, buf_size, length, binary_format, binary, true) }
    })
}

/// `glProgramBinary`: a binary gls_gl_get_program_binary() tagged loads
/// the driver's binary behind the tag. In a stereo context a binary
/// without the tag (made without glstereo, or by a mono context) is kept
/// only when its fragment output 0 needs no copies; otherwise its load
/// fails as GL lets a load fail (GL_LINK_STATUS false, no GL error; a
/// shader cache then compiles the source, which glLinkProgram links with
/// the copies) and stderr says so once. Refused: `binary` NULL with
/// `length` > 0 (GL_INVALID_VALUE).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_program_binary(
    program: u32,
    binary_format: u32,
    binary: *const c_void,
    length: i32,
) {
    ffi_boundary!("gls_gl_program_binary" for "glProgramBinary", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { ibin::program_binary(program, binary_format, binary, length, false) }
    })
}

/// `glProgramBinaryOES`: as gls_gl_program_binary().
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_gl_program_binary_oes(
    program: u32,
    binary_format: u32,
    binary: *const c_void,
    length: i32,
) {
    ffi_boundary!("gls_gl_program_binary_oes" for "glProgramBinaryOES", () => {
        // SAFETY: GL's contract, forwarded.
        unsafe { ibin::program_binary(program, binary_format, binary, length, true) }
    })
}

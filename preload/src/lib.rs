//! `libglstereo_preload.so`: glstereo's LD_PRELOAD interposer. Preloaded
//! into an unmodified GLX program (`glstereo-run program args…`), it
//! exports the GLX and GL entry points a stereo program touches under
//! their real names; each calls glstereo's `gls_glx_*` / `gls_gl_*`
//! implementation (`glstereo::ffi::interpose`, the one implementation that
//! also serves programs rebuilt with `<glstereo/compat.h>`), which forwards
//! everything that is not about stereo to the real libGL.
//!
//! Only these names are exported (the glstereo code linked in keeps its
//! `gls_` symbols local, see build.rs), so a program that also links
//! libglstereo.so still gets the library's own.
#![warn(missing_docs)]
#![allow(clippy::missing_safety_doc, non_snake_case)]

use std::ffi::{c_int, c_uchar, c_ulong, c_void};

use glstereo::ffi::interpose as gls;

use glstereo::interpose::next;

/// Each export enters the layer ([`next::enter`]) and calls glstereo's
/// implementation; entered again from inside the layer (a layer below
/// calling the name back globally while the layer forwards to it), it goes
/// straight to libGL's own function instead ([`next::bottom_symbol`]), so a
/// look-up loop never recurses. `own_export` maps each name to its export
/// for glXGetProcAddress.
macro_rules! export {
    ($( $name:ident => $target:ident ( $($arg:ident : $ty:ty),* ) $(-> $ret:ty)? ; )*) => {
        $(
            #[doc = concat!("`", stringify!($name), "`: see `", stringify!($target), "` in glstereo.h.")]
            #[unsafe(no_mangle)]
            #[allow(unused_unsafe)]
            pub unsafe extern "C" fn $name($($arg: $ty),*) $(-> $ret)? {
                let Some(_inside) = next::enter() else {
                    next::loop_detected(stringify!($name));
                    let name = concat!(stringify!($name), "\0");
                    let f = bottom(name);
                    // SAFETY: libGL's function of this name, with its
                    // signature, and the caller's arguments.
                    return unsafe {
                        std::mem::transmute::<*mut c_void, unsafe extern "C" fn($($ty),*) $(-> $ret)?>(f)($($arg),*)
                    };
                };
                // SAFETY: the caller's arguments, under the contract of the
                // GLX/GL function this replaces, which the target shares.
                unsafe { gls::$target($($arg),*) }
            }
        )*

        /// The export standing for `name`, for glXGetProcAddress.
        fn own_export(name: &[u8]) -> Option<*mut c_void> {
            match name {
                $( n if n == stringify!($name).as_bytes() => Some($name as *mut c_void), )*
                _ => None,
            }
        }
    };
}

/// libGL's own function `name` (NUL-terminated) for a re-entered export;
/// a process without it cannot have called the export through libGL, so
/// its absence ends the process with a message rather than a jump to NULL.
fn bottom(name: &'static str) -> *mut c_void {
    let cname = std::ffi::CStr::from_bytes_with_nul(name.as_bytes()).expect("NUL-terminated");
    let f = next::bottom_symbol(cname);
    if f.is_null() {
        eprintln!(
            "glstereo: {} re-entered and libGL.so.1 has no such function; aborting",
            cname.to_string_lossy()
        );
        std::process::abort();
    }
    f
}

export! {
    glXChooseVisual => gls_glx_choose_visual(dpy: *mut c_void, screen: c_int, attribs: *mut c_int) -> *mut c_void;
    glXGetConfig => gls_glx_get_config(dpy: *mut c_void, vis: *mut c_void, attrib: c_int, value: *mut c_int) -> c_int;
    glXChooseFBConfig => gls_glx_choose_fbconfig(dpy: *mut c_void, screen: c_int, attribs: *const c_int, n: *mut c_int) -> *mut *mut c_void;
    glXChooseFBConfigSGIX => gls_glx_choose_fbconfig_sgix(dpy: *mut c_void, screen: c_int, attribs: *const c_int, n: *mut c_int) -> *mut *mut c_void;
    glXGetFBConfigs => gls_glx_get_fbconfigs(dpy: *mut c_void, screen: c_int, n: *mut c_int) -> *mut *mut c_void;
    glXGetFBConfigAttrib => gls_glx_get_fbconfig_attrib(dpy: *mut c_void, config: *mut c_void, attribute: c_int, value: *mut c_int) -> c_int;
    glXGetFBConfigAttribSGIX => gls_glx_get_fbconfig_attrib_sgix(dpy: *mut c_void, config: *mut c_void, attribute: c_int, value: *mut c_int) -> c_int;
    glXGetVisualFromFBConfig => gls_glx_get_visual_from_fbconfig(dpy: *mut c_void, config: *mut c_void) -> *mut c_void;
    glXGetVisualFromFBConfigSGIX => gls_glx_get_visual_from_fbconfig_sgix(dpy: *mut c_void, config: *mut c_void) -> *mut c_void;
    glXCreateContext => gls_glx_create_context(dpy: *mut c_void, vis: *mut c_void, share: *mut c_void, direct: c_int) -> *mut c_void;
    glXCreateNewContext => gls_glx_create_new_context(dpy: *mut c_void, config: *mut c_void, render_type: c_int, share: *mut c_void, direct: c_int) -> *mut c_void;
    glXCreateContextWithConfigSGIX => gls_glx_create_context_with_config_sgix(dpy: *mut c_void, config: *mut c_void, render_type: c_int, share: *mut c_void, direct: c_int) -> *mut c_void;
    glXCreateContextAttribsARB => gls_glx_create_context_attribs_arb(dpy: *mut c_void, config: *mut c_void, share: *mut c_void, direct: c_int, attribs: *const c_int) -> *mut c_void;
    glXDestroyContext => gls_glx_destroy_context(dpy: *mut c_void, ctx: *mut c_void);
    glXMakeCurrent => gls_glx_make_current(dpy: *mut c_void, drawable: c_ulong, ctx: *mut c_void) -> c_int;
    glXMakeContextCurrent => gls_glx_make_context_current(dpy: *mut c_void, draw: c_ulong, read: c_ulong, ctx: *mut c_void) -> c_int;
    glXSwapBuffers => gls_glx_swap_buffers(dpy: *mut c_void, drawable: c_ulong);
    glXCreateWindow => gls_glx_create_window(dpy: *mut c_void, config: *mut c_void, win: c_ulong, attribs: *const c_int) -> c_ulong;
    glXDestroyWindow => gls_glx_destroy_window(dpy: *mut c_void, win: c_ulong);
    glXCreatePixmap => gls_glx_create_pixmap(dpy: *mut c_void, config: *mut c_void, pixmap: c_ulong, attribs: *const c_int) -> c_ulong;
    glXCreatePbuffer => gls_glx_create_pbuffer(dpy: *mut c_void, config: *mut c_void, attribs: *const c_int) -> c_ulong;
    glXCreateGLXPixmapWithConfigSGIX => gls_glx_create_glx_pixmap_with_config_sgix(dpy: *mut c_void, config: *mut c_void, pixmap: c_ulong) -> c_ulong;
    glXCreateGLXPbufferSGIX => gls_glx_create_glx_pbuffer_sgix(dpy: *mut c_void, config: *mut c_void, width: u32, height: u32, attribs: *const c_int) -> c_ulong;
    glDrawBuffer => gls_gl_draw_buffer(buf: u32);
    glDrawBuffers => gls_gl_draw_buffers(n: i32, bufs: *const u32);
    glDrawBuffersARB => gls_gl_draw_buffers_arb(n: i32, bufs: *const u32);
    glReadBuffer => gls_gl_read_buffer(src: u32);
    glGetError => gls_gl_get_error() -> u32;
    glGetIntegerv => gls_gl_get_integerv(pname: u32, data: *mut i32);
    glGetBooleanv => gls_gl_get_booleanv(pname: u32, data: *mut u8);
    glGetFloatv => gls_gl_get_floatv(pname: u32, data: *mut f32);
    glGetDoublev => gls_gl_get_doublev(pname: u32, data: *mut f64);
    glBindFramebuffer => gls_gl_bind_framebuffer(target: u32, framebuffer: u32);
    glBindFramebufferEXT => gls_gl_bind_framebuffer_ext(target: u32, framebuffer: u32);
    glDeleteFramebuffers => gls_gl_delete_framebuffers(n: i32, framebuffers: *const u32);
    glDeleteFramebuffersEXT => gls_gl_delete_framebuffers_ext(n: i32, framebuffers: *const u32);
    glGetFramebufferAttachmentParameteriv => gls_gl_get_framebuffer_attachment_parameteriv(target: u32, attachment: u32, pname: u32, params: *mut i32);
    glGetFramebufferAttachmentParameterivEXT => gls_gl_get_framebuffer_attachment_parameteriv_ext(target: u32, attachment: u32, pname: u32, params: *mut i32);
    glPushAttrib => gls_gl_push_attrib(mask: u32);
    glPopAttrib => gls_gl_pop_attrib();
    glViewport => gls_gl_viewport(x: i32, y: i32, width: i32, height: i32);
    glFlush => gls_gl_flush();
    glFinish => gls_gl_finish();
}

/// A function as `glXGetProcAddress` returns it.
pub type ProcAddress = Option<unsafe extern "C" fn()>;

fn as_proc(p: *mut c_void) -> ProcAddress {
    // SAFETY: NULL or the address of a function; the caller casts it to
    // the named function's type, as with any glXGetProcAddress result.
    unsafe { std::mem::transmute::<*mut c_void, ProcAddress>(p) }
}

/// Both glXGetProcAddress names: this library's exports for their names
/// (so a function found this way is guarded as the direct link is), the
/// layer's other replacements (aliases such as glXMakeCurrentReadSGI), the
/// function below the layer for every other name.
unsafe fn get_proc_address(name: *const c_uchar, which: &'static str) -> ProcAddress {
    let Some(_inside) = next::enter() else {
        next::loop_detected(which);
        let gpa = bottom("glXGetProcAddressARB\0");
        // SAFETY: libGL's glXGetProcAddressARB, with the caller's name.
        return unsafe {
            std::mem::transmute::<*mut c_void, unsafe extern "C" fn(*const c_uchar) -> ProcAddress>(
                gpa,
            )(name)
        };
    };
    if !name.is_null() {
        // SAFETY: non-NULL, NUL-terminated (GLX's contract).
        let n = unsafe { std::ffi::CStr::from_ptr(name.cast()) };
        if let Some(f) = own_export(n.to_bytes()) {
            return as_proc(f);
        }
    }
    // SAFETY: a NUL-terminated name (GLX's contract; NULL is refused there).
    as_proc(unsafe { gls::gls_glx_get_proc_address(name) })
}

/// `glXGetProcAddressARB`: this library's exports for their names (so a
/// function found this way is guarded as a direct link is), the layer's
/// other replacements, the function below the layer for every other name.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetProcAddressARB(name: *const c_uchar) -> ProcAddress {
    // SAFETY: GLX's contract.
    unsafe { get_proc_address(name, "glXGetProcAddressARB") }
}

/// `glXGetProcAddress`: as [`glXGetProcAddressARB`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetProcAddress(name: *const c_uchar) -> ProcAddress {
    // SAFETY: GLX's contract.
    unsafe { get_proc_address(name, "glXGetProcAddress") }
}

/// `dlopen`: libGL.so(.1), libGLX.so(.0) and libOpenGL.so(.0) opened by a
/// program come back as a stub whose look-ups find this library's exports
/// first; everything else is the next dlopen's
/// ([`glstereo::interpose::next`] says how and why).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn dlopen(filename: *const std::ffi::c_char, flags: c_int) -> *mut c_void {
    // SAFETY: dlopen's contract, forwarded.
    unsafe { next::dlopen_for_program(filename, flags) }
}

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

macro_rules! export {
    ($( $name:ident => $target:ident ( $($arg:ident : $ty:ty),* ) $(-> $ret:ty)? ; )*) => {
        $(
            #[doc = concat!("`", stringify!($name), "`: see `", stringify!($target), "` in glstereo.h.")]
            #[unsafe(no_mangle)]
            #[allow(unused_unsafe)]
            pub unsafe extern "C" fn $name($($arg: $ty),*) $(-> $ret)? {
                // SAFETY: the caller's arguments, under the contract of the
                // GLX/GL function this replaces, which the target shares.
                unsafe { gls::$target($($arg),*) }
            }
        )*
    };
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
    glClearBufferfv => gls_gl_clear_bufferfv(buffer: u32, drawbuffer: i32, value: *const f32);
    glClearBufferiv => gls_gl_clear_bufferiv(buffer: u32, drawbuffer: i32, value: *const i32);
    glClearBufferuiv => gls_gl_clear_bufferuiv(buffer: u32, drawbuffer: i32, value: *const u32);
    glClearNamedFramebufferfv => gls_gl_clear_named_framebufferfv(framebuffer: u32, buffer: u32, drawbuffer: i32, value: *const f32);
    glClearNamedFramebufferiv => gls_gl_clear_named_framebufferiv(framebuffer: u32, buffer: u32, drawbuffer: i32, value: *const i32);
    glClearNamedFramebufferuiv => gls_gl_clear_named_framebufferuiv(framebuffer: u32, buffer: u32, drawbuffer: i32, value: *const u32);
    glClearNamedFramebufferfi => gls_gl_clear_named_framebufferfi(framebuffer: u32, buffer: u32, drawbuffer: i32, depth: f32, stencil: i32);
    glNamedFramebufferDrawBuffer => gls_gl_named_framebuffer_draw_buffer(framebuffer: u32, buf: u32);
    glNamedFramebufferDrawBuffers => gls_gl_named_framebuffer_draw_buffers(framebuffer: u32, n: i32, bufs: *const u32);
    glNamedFramebufferReadBuffer => gls_gl_named_framebuffer_read_buffer(framebuffer: u32, src: u32);
    glBlitNamedFramebuffer => gls_gl_blit_named_framebuffer(read: u32, draw: u32, sx0: i32, sy0: i32, sx1: i32, sy1: i32, dx0: i32, dy0: i32, dx1: i32, dy1: i32, mask: u32, filter: u32);
    glInvalidateFramebuffer => gls_gl_invalidate_framebuffer(target: u32, n: i32, attachments: *const u32);
    glInvalidateSubFramebuffer => gls_gl_invalidate_sub_framebuffer(target: u32, n: i32, attachments: *const u32, x: i32, y: i32, width: i32, height: i32);
    glGetNamedFramebufferAttachmentParameteriv => gls_gl_get_named_framebuffer_attachment_parameteriv(framebuffer: u32, attachment: u32, pname: u32, params: *mut i32);
    glGetNamedFramebufferParameteriv => gls_gl_get_named_framebuffer_parameteriv(framebuffer: u32, pname: u32, params: *mut i32);
    glGetFramebufferParameteriv => gls_gl_get_framebuffer_parameteriv(target: u32, pname: u32, params: *mut i32);
    glLinkProgram => gls_gl_link_program(program: u32);
    glLinkProgramARB => gls_gl_link_program(program: u32);
    glCreateShaderProgramv => gls_gl_create_shader_programv(kind: u32, count: i32, strings: *const *const std::ffi::c_char) -> u32;
}

/// A function as `glXGetProcAddress` returns it.
pub type ProcAddress = Option<unsafe extern "C" fn()>;

fn as_proc(p: *mut c_void) -> ProcAddress {
    // SAFETY: NULL or the address of a function; the caller casts it to
    // the named function's type, as with any glXGetProcAddress result.
    unsafe { std::mem::transmute::<*mut c_void, ProcAddress>(p) }
}

/// `glXGetProcAddressARB`: the interposed functions for their names, the
/// real libGL's for every other.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetProcAddressARB(name: *const c_uchar) -> ProcAddress {
    // SAFETY: a NUL-terminated name (GLX's contract).
    as_proc(unsafe { gls::gls_glx_get_proc_address(name) })
}

/// `glXGetProcAddress`: as [`glXGetProcAddressARB`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetProcAddress(name: *const c_uchar) -> ProcAddress {
    // SAFETY: a NUL-terminated name (GLX's contract).
    as_proc(unsafe { gls::gls_glx_get_proc_address(name) })
}

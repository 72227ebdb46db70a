//! `libglstereo_preload.so`: glstereo's LD_PRELOAD interposer. Preloaded
//! into an unmodified GLX program (`glstereo-run program args…`), it
//! exports the GLX and GL entry points a stereo program touches under
//! their real names; each calls glstereo's `gls_glx_*` / `gls_gl_*`
//! implementation (`glstereo::ffi::interpose`, the one implementation that
//! also serves programs rebuilt with `<glstereo/compat.h>`), which forwards
//! everything that is not about stereo to the real libGL.
//!
//! Two kinds of exports:
//! - by hand (`export!`, `forward!` below): the GLX functions and the GL
//!   functions about the default framebuffer, each with its own
//!   implementation;
//! - generated from the Khronos registry (gl.xml) by build.rs: every
//!   desktop GL command of the families that draw (draws, glBegin/glEnd,
//!   display lists, clears, pixel rectangles, blits:
//!   `glstereo::auto::entry_points`) that is not exported by hand, each
//!   calling the next definition through one hook (`hooked`,
//!   `glstereo::interpose::draws`), which costs a thread-local test when
//!   nothing watches the thread's draws.
//!
//! Every address glXGetProcAddress hands out is that of a function of this
//! library's own, never an exported name's (which a layer preloaded above
//! would resolve to its own function). Only these names are exported (the
//! glstereo code linked in keeps its `gls_` symbols local, see build.rs),
//! so a program that also links libglstereo.so still gets the library's
//! own.
#![warn(missing_docs)]
#![allow(clippy::missing_safety_doc, non_snake_case)]

use std::ffi::{c_char, c_int, c_uchar, c_ulong, c_void};
use std::sync::atomic::{AtomicPtr, Ordering};

use glstereo::auto::entry_points::Family;
use glstereo::ffi::egl as gls_egl;
use glstereo::ffi::interpose as gls;
use glstereo::interpose::controls;
use glstereo::interpose::draws::Call;
use glstereo::interpose::next;

/// Each export enters the layer ([`next::enter`]) and calls
/// glstereo's implementation. Entered again while the thread is inside the
/// layer — libGL's own code, or a layer below, calling the name back while
/// the layer calls down — it is not the program calling: it forwards to the
/// next definition of the name ([`pass_down`]).
///
/// The body lives in a function of this library's own (`local::NAME`,
/// not exported); the exported `NAME` only calls it, and `own_export` hands
/// out the local function's address for glXGetProcAddress. The exported
/// name's address would not do: taken in code, it is read through the
/// global symbol table, which yields the *first* definition in the process
/// — a layer preloaded above this one (VirtualGL's faker, apitrace's
/// glxtrace) would be handed its own function back as "the real one".
macro_rules! export {
    ($( $name:ident => $target:ident ( $($arg:ident : $ty:ty),* ) $(-> $ret:ty)? ; )*) => {
        /// The bodies of the exports, at addresses of this library's own.
        mod local {
            use super::*;
            $(
                #[allow(unused_unsafe)]
                pub(super) unsafe extern "C" fn $name($($arg: $ty),*) $(-> $ret)? {
                    static NEXT: AtomicPtr<c_void> = AtomicPtr::new(std::ptr::null_mut());
                    let (_inside, depth) = next::enter();
                    if depth > 0 {
                        let f = pass_down(&NEXT, concat!(stringify!($name), "\0"), depth);
                        // SAFETY: the next definition of this function, with its
                        // signature, and the caller's arguments.
                        return unsafe {
                            std::mem::transmute::<*mut c_void, unsafe extern "C" fn($($ty),*) $(-> $ret)?>(f)($($arg),*)
                        };
                    }
                    // SAFETY: the caller's arguments, under the contract of the
                    // GLX/GL function this replaces, which the target shares.
                    unsafe { gls::$target($($arg),*) }
                }
            )*
        }

        $(
            #[doc = concat!("`", stringify!($name), "`: see `", stringify!($target), "` in glstereo.h.")]
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn $name($($arg: $ty),*) $(-> $ret)? {
                // SAFETY: the caller's arguments, forwarded.
                unsafe { local::$name($($arg),*) }
            }
        )*

        /// This library's own function standing for `name`, for
        /// glXGetProcAddress (see the macro's doc: never the exported
        /// name's address).
        fn own_export(name: &[u8]) -> Option<*mut c_void> {
            match name {
                $( n if n == stringify!($name).as_bytes() => Some(local::$name as *mut c_void), )*
                b"glXGetProcAddress" => Some(local_get_proc_address as *mut c_void),
                b"glXGetProcAddressARB" => Some(local_get_proc_address_arb as *mut c_void),
                _ => None,
            }
        }
    };
}

/// Where an export called from inside the layer goes: the next definition
/// of `name` (NUL-terminated; cached in `slot`), or, nested
/// [`next::NESTING_LIMIT`] deep — a layer below that calls the name back by
/// a global look-up, a loop — libGL's own function, said once on stderr and
/// used for every later call back into this function.
fn pass_down(slot: &AtomicPtr<c_void>, name: &'static str, depth: u32) -> *mut c_void {
    if depth >= next::NESTING_LIMIT {
        next::loop_detected(name.trim_end_matches('\0'));
        // Remembered: from now on a call back into this function goes
        // straight to libGL instead of round the loop again.
        let f = bottom(name);
        slot.store(f, Ordering::Release);
        return f;
    }
    let mut f = slot.load(Ordering::Acquire);
    if f.is_null() {
        let cname = std::ffi::CStr::from_bytes_with_nul(name.as_bytes()).expect("NUL-terminated");
        f = next::next_symbol(cname);
        if f.is_null() {
            f = bottom(name);
        }
        slot.store(f, Ordering::Release);
    }
    f
}

/// libGL's own function `name` (NUL-terminated); a process without it
/// cannot have reached the export through libGL, so its absence ends the
/// process with a message rather than a jump to NULL.
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
    glXDestroyPbuffer => gls_glx_destroy_pbuffer(dpy: *mut c_void, pbuf: c_ulong);
    glXDestroyGLXPbufferSGIX => gls_glx_destroy_glx_pbuffer_sgix(dpy: *mut c_void, pbuf: c_ulong);
    glXDestroyPixmap => gls_glx_destroy_pixmap(dpy: *mut c_void, pixmap: c_ulong);
    glXDestroyGLXPixmap => gls_glx_destroy_glx_pixmap(dpy: *mut c_void, pixmap: c_ulong);
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
    glDeleteTextures => gls_gl_delete_textures(n: i32, textures: *const u32);
    glDeleteTexturesEXT => gls_gl_delete_textures_ext(n: i32, textures: *const u32);
    glDeleteRenderbuffers => gls_gl_delete_renderbuffers(n: i32, renderbuffers: *const u32);
    glDeleteRenderbuffersEXT => gls_gl_delete_renderbuffers_ext(n: i32, renderbuffers: *const u32);
    glGetFramebufferAttachmentParameteriv => gls_gl_get_framebuffer_attachment_parameteriv(target: u32, attachment: u32, pname: u32, params: *mut i32);
    glGetFramebufferAttachmentParameterivEXT => gls_gl_get_framebuffer_attachment_parameteriv_ext(target: u32, attachment: u32, pname: u32, params: *mut i32);
    glPushAttrib => gls_gl_push_attrib(mask: u32);
    glPopAttrib => gls_gl_pop_attrib();
    glViewport => gls_gl_viewport(x: i32, y: i32, width: i32, height: i32);
    glColorMask => gls_gl_color_mask(red: u8, green: u8, blue: u8, alpha: u8);
    glClear => gls_gl_clear(mask: u32);
    glClearColor => gls_gl_clear_color(red: f32, green: f32, blue: f32, alpha: f32);
    glColorMaski => gls_gl_color_maski(index: u32, red: u8, green: u8, blue: u8, alpha: u8);
    glGetBooleani_v => gls_gl_get_booleani_v(target: u32, index: u32, data: *mut u8);
    glGetBooleanIndexedvEXT => gls_gl_get_boolean_indexedv_ext(target: u32, index: u32, data: *mut u8);
    glGetIntegeri_v => gls_gl_get_integeri_v(target: u32, index: u32, data: *mut i32);
    glGetIntegerIndexedvEXT => gls_gl_get_integer_indexedv_ext(target: u32, index: u32, data: *mut i32);
    glGetInteger64i_v => gls_gl_get_integer64i_v(target: u32, index: u32, data: *mut i64);
    glGetFloati_v => gls_gl_get_floati_v(target: u32, index: u32, data: *mut f32);
    glGetFloati_vEXT => gls_gl_get_floati_v_ext(target: u32, index: u32, data: *mut f32);
    glGetFloati_vOES => gls_gl_get_floati_v_oes(target: u32, index: u32, data: *mut f32);
    glGetFloatIndexedvEXT => gls_gl_get_float_indexedv_ext(target: u32, index: u32, data: *mut f32);
    glGetDoublei_v => gls_gl_get_doublei_v(target: u32, index: u32, data: *mut f64);
    glGetDoublei_vEXT => gls_gl_get_doublei_v_ext(target: u32, index: u32, data: *mut f64);
    glGetDoubleIndexedvEXT => gls_gl_get_double_indexedv_ext(target: u32, index: u32, data: *mut f64);
    glGetInteger64v => gls_gl_get_integer64v(pname: u32, data: *mut i64);
    glStereoParameterfNV => gls_gl_stereo_parameterf_nv(pname: u32, param: f32);
    glStereoParameteriNV => gls_gl_stereo_parameteri_nv(pname: u32, param: i32);
    glColorMaskIndexedEXT => gls_gl_color_mask_indexed_ext(index: u32, red: u8, green: u8, blue: u8, alpha: u8);
    glColorMaskiEXT => gls_gl_color_maski_ext(index: u32, red: u8, green: u8, blue: u8, alpha: u8);
    glColorMaskiOES => gls_gl_color_maski_oes(index: u32, red: u8, green: u8, blue: u8, alpha: u8);
    glClearColorIiEXT => gls_gl_clear_color_ii_ext(red: i32, green: i32, blue: i32, alpha: i32);
    glClearColorIuiEXT => gls_gl_clear_color_iui_ext(red: u32, green: u32, blue: u32, alpha: u32);
    glClearColorx => gls_gl_clear_colorx(red: i32, green: i32, blue: i32, alpha: i32);
    glClearColorxOES => gls_gl_clear_colorx_oes(red: i32, green: i32, blue: i32, alpha: i32);
    glBlitFramebuffer => gls_gl_blit_framebuffer(sx0: i32, sy0: i32, sx1: i32, sy1: i32, dx0: i32, dy0: i32, dx1: i32, dy1: i32, mask: u32, filter: u32);
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
    glInvalidateNamedFramebufferData => gls_gl_invalidate_named_framebuffer_data(framebuffer: u32, n: i32, attachments: *const u32);
    glInvalidateNamedFramebufferSubData => gls_gl_invalidate_named_framebuffer_sub_data(framebuffer: u32, n: i32, attachments: *const u32, x: i32, y: i32, width: i32, height: i32);
    glCheckNamedFramebufferStatus => gls_gl_check_named_framebuffer_status(framebuffer: u32, target: u32) -> u32;
    glCheckNamedFramebufferStatusEXT => gls_gl_check_named_framebuffer_status_ext(framebuffer: u32, target: u32) -> u32;
    glGetNamedFramebufferAttachmentParameteriv => gls_gl_get_named_framebuffer_attachment_parameteriv(framebuffer: u32, attachment: u32, pname: u32, params: *mut i32);
    glGetNamedFramebufferParameteriv => gls_gl_get_named_framebuffer_parameteriv(framebuffer: u32, pname: u32, params: *mut i32);
    glGetFramebufferParameteriv => gls_gl_get_framebuffer_parameteriv(target: u32, pname: u32, params: *mut i32);
    glLinkProgram => gls_gl_link_program(program: u32);
    glLinkProgramARB => gls_gl_link_program(program: u32);
    glCreateShaderProgramv => gls_gl_create_shader_programv(kind: u32, count: i32, strings: *const *const std::ffi::c_char) -> u32;
    glGetProgramiv => gls_gl_get_programiv(program: u32, pname: u32, params: *mut i32);
    glGetProgramBinary => gls_gl_get_program_binary(program: u32, buf_size: i32, length: *mut i32, binary_format: *mut u32, binary: *mut c_void);
    glGetProgramBinaryOES => gls_gl_get_program_binary_oes(program: u32, buf_size: i32, length: *mut i32, binary_format: *mut u32, binary: *mut c_void);
    glProgramBinary => gls_gl_program_binary(program: u32, binary_format: u32, binary: *const c_void, length: i32);
    glProgramBinaryOES => gls_gl_program_binary_oes(program: u32, binary_format: u32, binary: *const c_void, length: i32);
}

/// The EGL functions, exported as [`export!`] exports GLX's: each enters
/// the layer and calls glstereo's `gls_egl_*` implementation; entered
/// again from inside the layer it forwards to the next definition of its
/// name (a layer below, then libEGL: [`egl_pass_down`]).
macro_rules! egl_export {
    ($( $name:ident => $target:ident ( $($arg:ident : $ty:ty),* ) -> $ret:ty ; )*) => {
        /// The bodies of the EGL exports, at addresses of this library's own.
        mod egl_local {
            use super::*;
            $(
                pub(super) unsafe extern "C" fn $name($($arg: $ty),*) -> $ret {
                    static NEXT: AtomicPtr<c_void> = AtomicPtr::new(std::ptr::null_mut());
                    let (_inside, depth) = next::enter();
                    if depth > 0 {
                        let f = egl_pass_down(&NEXT, concat!(stringify!($name), "\0"), depth);
                        // SAFETY: the next definition of this function, with its
                        // signature, and the caller's arguments.
                        return unsafe {
                            std::mem::transmute::<*mut c_void, unsafe extern "C" fn($($ty),*) -> $ret>(f)($($arg),*)
                        };
                    }
                    // SAFETY: the caller's arguments, under the contract of the
                    // EGL function this replaces, which the target shares.
                    unsafe { gls_egl::$target($($arg),*) }
                }
            )*
        }

        $(
            #[doc = concat!("`", stringify!($name), "`: see `", stringify!($target), "` in glstereo.h.")]
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn $name($($arg: $ty),*) -> $ret {
                // SAFETY: the caller's arguments, forwarded.
                unsafe { egl_local::$name($($arg),*) }
            }
        )*

        /// This library's own function standing for EGL function `name`,
        /// for eglGetProcAddress.
        fn own_egl_export(name: &[u8]) -> Option<*mut c_void> {
            match name {
                $( n if n == stringify!($name).as_bytes() => Some(egl_local::$name as *mut c_void), )*
                b"eglGetProcAddress" => Some(local_egl_get_proc_address as *mut c_void),
                _ => None,
            }
        }
    };
}

/// [`pass_down`] for an EGL export: the next definition of `name`
/// (cached in `slot`), or libEGL's own, nested [`next::NESTING_LIMIT`]
/// deep. A process whose libEGL lacks the function cannot have reached the
/// export through libEGL: the process ends with a message.
fn egl_pass_down(slot: &AtomicPtr<c_void>, name: &'static str, depth: u32) -> *mut c_void {
    let cname = std::ffi::CStr::from_bytes_with_nul(name.as_bytes()).expect("NUL-terminated");
    if depth >= next::NESTING_LIMIT {
        next::loop_detected(name.trim_end_matches('\0'));
        let f = next::bottom_egl_symbol(cname);
        if f.is_null() {
            no_egl(cname);
        }
        slot.store(f, Ordering::Release);
        return f;
    }
    let mut f = slot.load(Ordering::Acquire);
    if f.is_null() {
        f = next::next_egl_symbol(cname);
        if f.is_null() {
            no_egl(cname);
        }
        slot.store(f, Ordering::Release);
    }
    f
}

fn no_egl(name: &std::ffi::CStr) -> ! {
    eprintln!(
        "glstereo: {} re-entered and libEGL.so.1 has no such function; aborting",
        name.to_string_lossy()
    );
    std::process::abort();
}

egl_export! {
    eglGetDisplay => gls_egl_get_display(native_display: *mut c_void) -> *mut c_void;
    eglGetPlatformDisplay => gls_egl_get_platform_display(platform: u32, native_display: *mut c_void, attrib_list: *const isize) -> *mut c_void;
    eglGetPlatformDisplayEXT => gls_egl_get_platform_display_ext(platform: u32, native_display: *mut c_void, attrib_list: *const i32) -> *mut c_void;
    eglCreateContext => gls_egl_create_context(dpy: *mut c_void, config: *mut c_void, share_context: *mut c_void, attrib_list: *const i32) -> *mut c_void;
    eglDestroyContext => gls_egl_destroy_context(dpy: *mut c_void, ctx: *mut c_void) -> u32;
    eglMakeCurrent => gls_egl_make_current(dpy: *mut c_void, draw: *mut c_void, read: *mut c_void, ctx: *mut c_void) -> u32;
    eglReleaseThread => gls_egl_release_thread() -> u32;
    eglSwapBuffers => gls_egl_swap_buffers(dpy: *mut c_void, surface: *mut c_void) -> u32;
    eglSwapBuffersWithDamageKHR => gls_egl_swap_buffers_with_damage_khr(dpy: *mut c_void, surface: *mut c_void, rects: *const i32, n_rects: i32) -> u32;
    eglSwapBuffersWithDamageEXT => gls_egl_swap_buffers_with_damage_ext(dpy: *mut c_void, surface: *mut c_void, rects: *const i32, n_rects: i32) -> u32;
    eglCreateWindowSurface => gls_egl_create_window_surface(dpy: *mut c_void, config: *mut c_void, win: usize, attrib_list: *const i32) -> *mut c_void;
    eglCreatePlatformWindowSurface => gls_egl_create_platform_window_surface(dpy: *mut c_void, config: *mut c_void, native_window: *mut c_void, attrib_list: *const isize) -> *mut c_void;
    eglCreatePlatformWindowSurfaceEXT => gls_egl_create_platform_window_surface_ext(dpy: *mut c_void, config: *mut c_void, native_window: *mut c_void, attrib_list: *const i32) -> *mut c_void;
    eglDestroySurface => gls_egl_destroy_surface(dpy: *mut c_void, surface: *mut c_void) -> u32;
    eglTerminate => gls_egl_terminate(dpy: *mut c_void) -> u32;
}

/// eglGetProcAddress's body, at an address of this library's own: this
/// library's functions for the EGL and GL names it replaces (so a
/// function found this way is guarded as the direct link is), the function
/// below the layer for every other name.
unsafe extern "C" fn local_egl_get_proc_address(name: *const c_char) -> *mut c_void {
    static NEXT: AtomicPtr<c_void> = AtomicPtr::new(std::ptr::null_mut());
    let (_inside, depth) = next::enter();
    if depth > 0 {
        let gpa = egl_pass_down(&NEXT, "eglGetProcAddress\0", depth);
        // SAFETY: the next eglGetProcAddress, with the caller's name.
        return unsafe {
            std::mem::transmute::<*mut c_void, unsafe extern "C" fn(*const c_char) -> *mut c_void>(
                gpa,
            )(name)
        };
    }
    if !name.is_null() {
        // SAFETY: non-NULL, NUL-terminated (EGL's contract).
        let n = unsafe { std::ffi::CStr::from_ptr(name) }.to_bytes();
        let gl = n.starts_with(b"gl") && !n.starts_with(b"glX");
        let generated =
            || generated::lookup(n).filter(|_| glstereo::interpose::real::loaded().is_ok());
        let own = own_egl_export(n).or_else(|| {
            if gl {
                own_export(n).or_else(generated)
            } else {
                None
            }
        });
        if let Some(f) = own {
            return f;
        }
    }
    // SAFETY: a NUL-terminated name or NULL (answered NULL there).
    unsafe { gls_egl::gls_egl_get_proc_address(name) }
}

/// `eglGetProcAddress`: this library's functions for the EGL and GL names
/// it replaces, the function below the layer for every other name.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn eglGetProcAddress(name: *const c_char) -> *mut c_void {
    // SAFETY: EGL's contract.
    unsafe { local_egl_get_proc_address(name) }
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
    static NEXT: AtomicPtr<c_void> = AtomicPtr::new(std::ptr::null_mut());
    let (_inside, depth) = next::enter();
    if depth > 0 {
        let gpa = pass_down(&NEXT, which, depth);
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
        // A generated wrapper stands for a function of the GL below: with
        // no libGL to call, the name is refused as every other libGL name.
        let generated = || {
            generated::lookup(n.to_bytes()).filter(|_| glstereo::interpose::real::loaded().is_ok())
        };
        if let Some(f) = own_export(n.to_bytes()).or_else(generated) {
            return as_proc(f);
        }
    }
    // SAFETY: a NUL-terminated name (GLX's contract; NULL is refused there).
    as_proc(unsafe { gls::gls_glx_get_proc_address(name) })
}

/// glXGetProcAddressARB's body, at an address of this library's own.
unsafe extern "C" fn local_get_proc_address_arb(name: *const c_uchar) -> ProcAddress {
    // SAFETY: GLX's contract.
    unsafe { get_proc_address(name, "glXGetProcAddressARB\0") }
}

/// glXGetProcAddress's body, at an address of this library's own.
unsafe extern "C" fn local_get_proc_address(name: *const c_uchar) -> ProcAddress {
    // SAFETY: GLX's contract.
    unsafe { get_proc_address(name, "glXGetProcAddress\0") }
}

/// `glXGetProcAddressARB`: this library's own functions for the names it
/// replaces (so a function found this way is guarded as the direct link
/// is), the layer's other replacements, the function below the layer for
/// every other name.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetProcAddressARB(name: *const c_uchar) -> ProcAddress {
    // SAFETY: GLX's contract.
    unsafe { local_get_proc_address_arb(name) }
}

/// `glXGetProcAddress`: as [`glXGetProcAddressARB`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn glXGetProcAddress(name: *const c_uchar) -> ProcAddress {
    // SAFETY: GLX's contract.
    unsafe { local_get_proc_address(name) }
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

/// GLX 1.4 functions the layer does not change, exported only to forward:
/// a program that dlopens libGL gets the stub's handle, and dlsym of these
/// names on it must reach the next layer (a VirtualGL faker below, which
/// replaces many of them), then libGL, as the program's own link would.
/// Each is resolved once, by [`next::next_symbol`]; nested
/// [`next::NESTING_LIMIT`] deep, it takes the call for a loop and goes
/// straight to libGL ([`pass_down`]).
macro_rules! forward {
    ($( $name:ident ( $($arg:ident : $ty:ty),* ) $(-> $ret:ty)? ; )*) => {
        $(
            #[doc = concat!("`", stringify!($name), "`: forwarded to the next definition (a layer below, then libGL).")]
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn $name($($arg: $ty),*) $(-> $ret)? {
                static NEXT: AtomicPtr<c_void> = AtomicPtr::new(std::ptr::null_mut());
                let (_inside, depth) = next::enter();
                let f = pass_down(&NEXT, concat!(stringify!($name), "\0"), depth);
                // SAFETY: the next definition of this GLX function, with its
                // GLX 1.4 signature, and the caller's arguments.
                unsafe {
                    std::mem::transmute::<*mut c_void, unsafe extern "C" fn($($ty),*) $(-> $ret)?>(f)($($arg),*)
                }
            }
        )*
    };
}

forward! {
    glXQueryExtension(dpy: *mut c_void, error_base: *mut c_int, event_base: *mut c_int) -> c_int;
    glXQueryVersion(dpy: *mut c_void, major: *mut c_int, minor: *mut c_int) -> c_int;
    glXQueryExtensionsString(dpy: *mut c_void, screen: c_int) -> *const std::ffi::c_char;
    glXQueryServerString(dpy: *mut c_void, screen: c_int, name: c_int) -> *const std::ffi::c_char;
    glXGetClientString(dpy: *mut c_void, name: c_int) -> *const std::ffi::c_char;
    glXIsDirect(dpy: *mut c_void, ctx: *mut c_void) -> c_int;
    glXCopyContext(dpy: *mut c_void, src: *mut c_void, dst: *mut c_void, mask: c_ulong);
    glXCreateGLXPixmap(dpy: *mut c_void, vis: *mut c_void, pixmap: c_ulong) -> c_ulong;
    glXWaitGL();
    glXWaitX();
    glXUseXFont(font: c_ulong, first: c_int, count: c_int, list_base: c_int);
    glXGetCurrentContext() -> *mut c_void;
    glXGetCurrentDrawable() -> c_ulong;
    glXGetCurrentReadDrawable() -> c_ulong;
    glXGetCurrentDisplay() -> *mut c_void;
    glXQueryContext(dpy: *mut c_void, ctx: *mut c_void, attribute: c_int, value: *mut c_int) -> c_int;
    glXQueryDrawable(dpy: *mut c_void, draw: c_ulong, attribute: c_int, value: *mut u32);
    glXSelectEvent(dpy: *mut c_void, draw: c_ulong, mask: c_ulong);
    glXGetSelectedEvent(dpy: *mut c_void, draw: c_ulong, mask: *mut c_ulong);
}

/// libxcb's event functions, through which every X event reaches a
/// program (an XCB program's own calls, and libX11's to fill its queue):
/// in a process with a stereo context each passes its events through
/// [`glstereo::interpose::controls::filtered`], which takes out the live
/// controls' keys; in any other process it is the next definition's call
/// after one load and a branch. Each forwards to the next definition of
/// its name (a layer below such as VirtualGL's faker, then libxcb; libxcb
/// as loaded when no global scope has it), found once; nested
/// [`next::NESTING_LIMIT`] deep it takes the call for a loop and goes
/// straight to libxcb's own function. The exported name only calls a
/// function of this library's own, as [`export!`]'s do.
macro_rules! xcb_events {
    ($( $name:ident ; )*) => {
        /// The bodies of the event exports, at addresses of this library's own.
        mod xcb_local {
            use super::*;
            $(
                pub(super) unsafe extern "C" fn $name(c: *mut c_void) -> *mut c_void {
                    static NEXT: AtomicPtr<c_void> = AtomicPtr::new(std::ptr::null_mut());
                    let name = concat!(stringify!($name), "\0");
                    let f = xcb_next(&NEXT, name);
                    if !controls::armed() {
                        // SAFETY: the next definition of this libxcb
                        // function, with its signature, and the caller's
                        // connection.
                        return unsafe { f(c) };
                    }
                    let (_inside, depth) = next::enter();
                    let f = if depth >= next::NESTING_LIMIT {
                        xcb_bottom(&NEXT, name)
                    } else {
                        f
                    };
                    // SAFETY: as above; the events are the caller's to free.
                    unsafe { controls::filtered(c, f) }
                }
            )*
        }

        $(
            #[doc = concat!("`", stringify!($name), "`: libxcb's, without the live controls' keys (see `xcb_events!`).")]
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn $name(c: *mut c_void) -> *mut c_void {
                // SAFETY: the caller's connection, forwarded.
                unsafe { xcb_local::$name(c) }
            }
        )*
    };
}

xcb_events! {
    xcb_wait_for_event;
    xcb_poll_for_event;
    xcb_poll_for_queued_event;
}

/// The next definition of libxcb function `name` (NUL-terminated; cached
/// in `slot`). A process without libxcb cannot have called it through
/// the dynamic linker: its absence ends the process with a message.
fn xcb_next(slot: &AtomicPtr<c_void>, name: &'static str) -> controls::NextEvent {
    let mut f = slot.load(Ordering::Acquire);
    if f.is_null() {
        let cname = std::ffi::CStr::from_bytes_with_nul(name.as_bytes()).expect("NUL-terminated");
        f = next::next_symbol_in(cname, LIBXCB);
        if f.is_null() {
            no_libxcb(cname);
        }
        slot.store(f, Ordering::Release);
    }
    // SAFETY: libxcb's event function (or a layer's standing for it).
    unsafe { std::mem::transmute::<*mut c_void, controls::NextEvent>(f) }
}

/// libxcb's own `name` for a call found looping through a layer below
/// ([`pass_down`]'s rule): said once, and used from now on.
fn xcb_bottom(slot: &AtomicPtr<c_void>, name: &'static str) -> controls::NextEvent {
    next::loop_detected(name.trim_end_matches('\0'));
    let cname = std::ffi::CStr::from_bytes_with_nul(name.as_bytes()).expect("NUL-terminated");
    let f = next::own_symbol_in(cname, LIBXCB);
    if f.is_null() {
        no_libxcb(cname);
    }
    slot.store(f, Ordering::Release);
    // SAFETY: libxcb's own event function.
    unsafe { std::mem::transmute::<*mut c_void, controls::NextEvent>(f) }
}

/// libxcb's soname.
const LIBXCB: &std::ffi::CStr = c"libxcb.so.1";

fn no_libxcb(name: &std::ffi::CStr) -> ! {
    eprintln!(
        "glstereo: {} was called and libxcb.so.1 is not loaded; aborting",
        name.to_string_lossy()
    );
    std::process::abort();
}

// The GL commands of the drawing families, generated from gl.xml by
// build.rs: each is exported under its name and calls [`hooked`].
include!(concat!(env!("OUT_DIR"), "/generated.rs"));

/// The next definition of GL command `name` (cached in `slot`): the next
/// glXGetProcAddress's function (a layer below, then libGL's dispatch),
/// never this library's. A command no GL below has cannot have been
/// reached but through a pointer to it: the process ends with a message.
fn gl_next(slot: &AtomicPtr<c_void>, name: &std::ffi::CStr) -> *mut c_void {
    let mut f = slot.load(Ordering::Acquire);
    if f.is_null() {
        // SAFETY: a NUL-terminated name.
        f = unsafe { glstereo::interpose::real::get_proc_address(name.as_ptr()) }
            .map_or(std::ptr::null_mut(), |f| f as *mut c_void);
        if f.is_null() {
            f = next::bottom_symbol(name);
        }
        if f.is_null() {
            eprintln!(
                "glstereo: {} was called and no GL library below has it; aborting",
                name.to_string_lossy()
            );
            std::process::abort();
        }
        slot.store(f, Ordering::Release);
    }
    f
}

/// A generated export's call: straight through when the thread is inside
/// the layer already (the layer's own draws), else through glstereo's
/// hook for the family.
fn hooked<R: glstereo::interpose::draws::Returned>(call: Call, f: impl Fn() -> R) -> R {
    let (_inside, depth) = next::enter();
    if depth > 0 {
        return f();
    }
    glstereo::interpose::draws::around(call, f)
}

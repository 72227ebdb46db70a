//! EGL entry points with automatic stereo (`glstereo-run --auto`), for
//! programs that draw through EGL: the logic is in
//! [`crate::interpose::egl`]. Unmodified binaries get these under their
//! real names from `libglstereo_preload.so`.
//!
//! Each behaves as the EGL function it replaces: same arguments, same
//! results, same EGL errors (every call goes to the real libEGL, which
//! validates its handles); under `--auto` a context the program creates
//! draws both eyes and each swap shows them in GLSTEREO_MODE. Types:
//! `EGLDisplay`, `EGLConfig`, `EGLContext`, `EGLSurface` and native
//! displays and windows are `void *` (eglCreateWindowSurface's native
//! window, an X window ID or a `wl_egl_window *`, is `uintptr_t`),
//! `EGLint` `int32_t`, `EGLBoolean` and `EGLenum` `uint32_t`, `EGLAttrib`
//! `intptr_t`. What the layer cannot report through EGL (no libGL beside
//! libEGL, a layer context it cannot create) goes to stderr once, prefixed
//! `glstereo:`, and that context runs in mono. A missing libEGL is
//! reported the same way, and the call returns EGL's failure value.

use std::ffi::{c_char, c_void};

use super::boundary::ffi_boundary;
use crate::interpose::egl::{self as iegl, Damage, EGL_FALSE, GetDisplay, NewWindow};

/// `eglGetDisplay`: the real call; the display's platform is remembered.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_get_display(native_display: *mut c_void) -> *mut c_void {
    ffi_boundary!("gls_egl_get_display" for "eglGetDisplay", std::ptr::null_mut() => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::get_display(native_display, GetDisplay::Native) }
    })
}

/// `eglGetPlatformDisplay` (EGL 1.5).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_get_platform_display(
    platform: u32,
    native_display: *mut c_void,
    attrib_list: *const isize,
) -> *mut c_void {
    ffi_boundary!("gls_egl_get_platform_display" for "eglGetPlatformDisplay", std::ptr::null_mut() => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::get_display(native_display, GetDisplay::Platform(platform, attrib_list)) }
    })
}

/// `eglGetPlatformDisplayEXT` (EGL_EXT_platform_base).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_get_platform_display_ext(
    platform: u32,
    native_display: *mut c_void,
    attrib_list: *const i32,
) -> *mut c_void {
    ffi_boundary!("gls_egl_get_platform_display_ext" for "eglGetPlatformDisplayEXT", std::ptr::null_mut() => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::get_display(native_display, GetDisplay::PlatformExt(platform, attrib_list)) }
    })
}

/// `eglCreateContext`: under `--auto`, an automatic-stereo context.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_create_context(
    dpy: *mut c_void,
    config: *mut c_void,
    share_context: *mut c_void,
    attrib_list: *const i32,
) -> *mut c_void {
    ffi_boundary!("gls_egl_create_context" for "eglCreateContext", std::ptr::null_mut() => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::create_context(dpy, config, share_context, attrib_list) }
    })
}

/// `eglDestroyContext`: an automatic-stereo context current on a thread is
/// destroyed, with the layer's, when it is released.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_destroy_context(dpy: *mut c_void, ctx: *mut c_void) -> u32 {
    ffi_boundary!("gls_egl_destroy_context" for "eglDestroyContext", EGL_FALSE => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::destroy_context(dpy, ctx) }
    })
}

/// `eglMakeCurrent`: an automatic-stereo context on a surface draws into
/// that surface's emulated framebuffer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_make_current(
    dpy: *mut c_void,
    draw: *mut c_void,
    read: *mut c_void,
    ctx: *mut c_void,
) -> u32 {
    ffi_boundary!("gls_egl_make_current" for "eglMakeCurrent", EGL_FALSE => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::make_current(dpy, draw, read, ctx) }
    })
}

/// `eglReleaseThread`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_release_thread() -> u32 {
    ffi_boundary!("gls_egl_release_thread" for "eglReleaseThread", EGL_FALSE => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::release_thread() }
    })
}

/// `eglSwapBuffers`: an automatic-stereo surface shows both eyes composed
/// in GLSTEREO_MODE.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_swap_buffers(dpy: *mut c_void, surface: *mut c_void) -> u32 {
    ffi_boundary!("gls_egl_swap_buffers" for "eglSwapBuffers", EGL_FALSE => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::swap_buffers(dpy, surface, None) }
    })
}

/// `eglSwapBuffersWithDamageKHR`: as [`gls_egl_swap_buffers`] (the
/// composite is new everywhere: the whole surface is presented).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_swap_buffers_with_damage_khr(
    dpy: *mut c_void,
    surface: *mut c_void,
    rects: *const i32,
    n_rects: i32,
) -> u32 {
    ffi_boundary!("gls_egl_swap_buffers_with_damage_khr" for "eglSwapBuffersWithDamageKHR", EGL_FALSE => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::swap_buffers(dpy, surface, Some((Damage::Khr, rects, n_rects))) }
    })
}

/// `eglSwapBuffersWithDamageEXT`: as [`gls_egl_swap_buffers_with_damage_khr`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_swap_buffers_with_damage_ext(
    dpy: *mut c_void,
    surface: *mut c_void,
    rects: *const i32,
    n_rects: i32,
) -> u32 {
    ffi_boundary!("gls_egl_swap_buffers_with_damage_ext" for "eglSwapBuffersWithDamageEXT", EGL_FALSE => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::swap_buffers(dpy, surface, Some((Damage::Ext, rects, n_rects))) }
    })
}

/// `eglCreateWindowSurface`: the real call (the X window behind it is
/// remembered for the live keys).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_create_window_surface(
    dpy: *mut c_void,
    config: *mut c_void,
    win: usize,
    attrib_list: *const i32,
) -> *mut c_void {
    ffi_boundary!("gls_egl_create_window_surface" for "eglCreateWindowSurface", std::ptr::null_mut() => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::create_window_surface(dpy, config, NewWindow::Native(win, attrib_list)) }
    })
}

/// `eglCreatePlatformWindowSurface` (EGL 1.5).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_create_platform_window_surface(
    dpy: *mut c_void,
    config: *mut c_void,
    native_window: *mut c_void,
    attrib_list: *const isize,
) -> *mut c_void {
    ffi_boundary!("gls_egl_create_platform_window_surface" for "eglCreatePlatformWindowSurface", std::ptr::null_mut() => {
        // SAFETY: EGL's contract, forwarded.
        unsafe {
            iegl::create_window_surface(dpy, config, NewWindow::Platform(native_window, attrib_list))
        }
    })
}

/// `eglCreatePlatformWindowSurfaceEXT` (EGL_EXT_platform_base).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_create_platform_window_surface_ext(
    dpy: *mut c_void,
    config: *mut c_void,
    native_window: *mut c_void,
    attrib_list: *const i32,
) -> *mut c_void {
    ffi_boundary!("gls_egl_create_platform_window_surface_ext" for "eglCreatePlatformWindowSurfaceEXT", std::ptr::null_mut() => {
        // SAFETY: EGL's contract, forwarded.
        unsafe {
            iegl::create_window_surface(dpy, config, NewWindow::PlatformExt(native_window, attrib_list))
        }
    })
}

/// `eglDestroySurface`: the surface's stereo buffers go with it, in every
/// context that has them.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_destroy_surface(dpy: *mut c_void, surface: *mut c_void) -> u32 {
    ffi_boundary!("gls_egl_destroy_surface" for "eglDestroySurface", EGL_FALSE => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::destroy_surface(dpy, surface) }
    })
}

/// `eglTerminate`: the layer's contexts on the display go first.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_terminate(dpy: *mut c_void) -> u32 {
    ffi_boundary!("gls_egl_terminate" for "eglTerminate", EGL_FALSE => {
        // SAFETY: EGL's contract, forwarded.
        unsafe { iegl::terminate(dpy) }
    })
}

/// `eglGetProcAddress` below the layer: the real libEGL's function for
/// `procname` (the preload hands out its own functions for the names it
/// replaces before asking this). NULL `procname`: NULL, as libEGL answers.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_egl_get_proc_address(procname: *const c_char) -> *mut c_void {
    ffi_boundary!("gls_egl_get_proc_address" for "eglGetProcAddress", std::ptr::null_mut() => {
        if procname.is_null() {
            return Ok(std::ptr::null_mut());
        }
        // SAFETY: a NUL-terminated name (EGL's contract).
        unsafe { iegl::get_proc_address(procname) }
    })
}

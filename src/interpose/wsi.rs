//! The window system a stereo context's drawables belong to — GLX or EGL —
//! and the few things [`super::context`] asks of it: what is current on
//! the thread (to put it back), making a context current, a drawable's
//! size, destroying a context, swapping, and the X window behind a
//! drawable (for the live keys and MIT-SHM). Everything else a stereo
//! context does is GL, the same whichever system made the context.

use x11_dl::glx::GLXContext;
use x11_dl::xlib;

use super::egl::{self, Handle};
use super::real::Real;
use super::registry;
use crate::backend::glx::{trap_replied_x_errors, trap_x_errors};
use crate::error::{Error, Result};

/// GLX_WIDTH / GLX_HEIGHT for glXQueryDrawable.
const GLX_WIDTH: i32 = 0x801D;
const GLX_HEIGHT: i32 = 0x801E;

/// Which window system made a stereo context.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wsi {
    /// GLX: displays are `Display*`, drawables X IDs.
    Glx,
    /// EGL: displays are `EGLDisplay`s, drawables `EGLSurface`s.
    Egl,
}

thread_local! {
    /// The context made current on this thread last, by the program or
    /// the layer, through the layer (0: none).
    static MADE_CURRENT: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Records that `ctx` (0: none) was made current on this thread: each
/// make-current that goes through the layer, the program's and its own.
pub(super) fn made_current(ctx: usize) {
    MADE_CURRENT.with(|c| c.set(ctx));
}

/// The context current on this thread as the layer saw it made current,
/// without asking GLX or EGL. Asking the window system the program does
/// not use is not harmless: in a child made with fork(), libglvnd's first
/// call into a library resets its dispatch, and a glXGetCurrentContext
/// there took the EGL program's current context away (its eyes could not
/// be made: tests/egl.rs, the hostile program's fork).
pub(super) fn made_current_context() -> usize {
    MADE_CURRENT.with(std::cell::Cell::get)
}

/// What was current on this thread, as the window system says, to put back.
pub(super) struct Saved {
    wsi: Wsi,
    display: usize,
    draw: u64,
    read: u64,
    ctx: usize,
}

impl Saved {
    /// Makes what was saved current again (nothing current: a release on
    /// `fallback_display`, for GLX, which wants a display for it).
    pub(super) fn restore(&self, r: &Real, fallback_display: usize) {
        made_current(self.ctx);
        match self.wsi {
            Wsi::Glx => {
                // SAFETY: the state that was current a moment ago (or none).
                unsafe {
                    if self.ctx == 0 {
                        (r.glx.glXMakeContextCurrent)(
                            fallback_display as *mut xlib::Display,
                            0,
                            0,
                            std::ptr::null_mut(),
                        );
                    } else {
                        (r.glx.glXMakeContextCurrent)(
                            self.display as *mut xlib::Display,
                            self.draw,
                            self.read,
                            self.ctx as GLXContext,
                        );
                    }
                }
            }
            Wsi::Egl => {
                let Some(e) = egl::egl_if_loaded() else {
                    return;
                };
                let display = if self.ctx == 0 {
                    fallback_display
                } else {
                    self.display
                };
                // SAFETY: the state that was current a moment ago (or none).
                unsafe {
                    (e.eglMakeCurrent)(
                        display as Handle,
                        self.draw as Handle,
                        self.read as Handle,
                        self.ctx as Handle,
                    )
                };
            }
        }
    }
}

impl Wsi {
    /// What is current on this thread now.
    pub(super) fn saved(self, r: &Real) -> Saved {
        let (display, draw, read, ctx) = match self {
            // SAFETY: plain getters of the calling thread's GLX state.
            Wsi::Glx => unsafe {
                (
                    (r.glx.glXGetCurrentDisplay)() as usize,
                    (r.glx.glXGetCurrentDrawable)(),
                    (r.glx.glXGetCurrentReadDrawable)(),
                    (r.glx.glXGetCurrentContext)() as usize,
                )
            },
            Wsi::Egl => egl::egl_if_loaded().map_or((0, 0, 0, 0), egl::current_binding),
        };
        Saved {
            wsi: self,
            display,
            draw,
            read,
            ctx,
        }
    }

    /// Makes `ctx` current on `draw` / `read` (0: no drawable) of
    /// `display`; X errors trapped. False when the system refuses.
    pub(super) fn make_current(
        self,
        r: &Real,
        display: usize,
        draw: u64,
        read: u64,
        ctx: usize,
    ) -> bool {
        let ok = match self {
            Wsi::Glx => {
                let dpy = display as *mut xlib::Display;
                let (ok, err) = trap_x_errors(&r.xlib, dpy, || {
                    // SAFETY: an open display, a context and drawables of
                    // the caller's (errors trapped).
                    unsafe { (r.glx.glXMakeContextCurrent)(dpy, draw, read, ctx as GLXContext) }
                });
                ok != 0 && err == 0
            }
            Wsi::Egl => egl::egl_if_loaded().is_some_and(|e| {
                // SAFETY: EGL validates every handle (EGL_BAD_* errors).
                unsafe {
                    (e.eglMakeCurrent)(
                        display as Handle,
                        draw as Handle,
                        read as Handle,
                        ctx as Handle,
                    ) != egl::EGL_FALSE
                }
            }),
        };
        if ok {
            made_current(ctx);
        }
        ok
    }

    /// Destroys context `ctx` of `display` (current nowhere).
    pub(super) fn destroy_context(self, r: &Real, display: usize, ctx: usize) {
        match self {
            // SAFETY: a context current nowhere.
            Wsi::Glx => unsafe {
                (r.glx.glXDestroyContext)(display as *mut xlib::Display, ctx as GLXContext)
            },
            Wsi::Egl => {
                if let Some(e) = egl::egl_if_loaded() {
                    // SAFETY: as above.
                    unsafe { (e.eglDestroyContext)(display as Handle, ctx as Handle) };
                }
            }
        }
    }

    /// Swaps `drawable`'s buffers in the context current on this thread.
    pub(super) fn swap(self, r: &Real, display: usize, drawable: u64) {
        match self {
            // SAFETY: valid display and drawable, current here.
            Wsi::Glx => unsafe { (r.glx.glXSwapBuffers)(display as *mut xlib::Display, drawable) },
            Wsi::Egl => {
                if let Some(e) = egl::egl_if_loaded() {
                    // SAFETY: as above.
                    unsafe { (e.eglSwapBuffers)(display as Handle, drawable as Handle) };
                }
            }
        }
    }

    /// The X display and X drawable behind `drawable` (the window behind
    /// a GLX window; an EGL surface's window where the program opened the
    /// X display), for the live keys and MIT-SHM.
    pub(super) fn x_drawable(self, display: usize, drawable: u64) -> Option<(usize, u64)> {
        match self {
            Wsi::Glx => Some((
                display,
                registry::with(|reg| reg.x_drawable(display, drawable)),
            )),
            Wsi::Egl => egl::x_window(display, drawable),
        }
    }

    /// Waits until the X server has processed every request of the
    /// display (nothing for an EGL display that is not the program's X
    /// connection).
    pub(super) fn sync(self, r: &Real, display: usize) {
        let x = match self {
            Wsi::Glx => Some(display),
            Wsi::Egl => egl::x_display(display),
        };
        if let Some(x) = x {
            // SAFETY: an open display.
            unsafe { (r.xlib.XSync)(x as *mut xlib::Display, xlib::False) };
        }
    }

    /// The size of a drawable. GLX: XGetGeometry of its X drawable (the
    /// window behind a GLX window), else glXQueryDrawable (pbuffers), X
    /// errors trapped, never reaching the program; takes the registry's
    /// lock: never call it with a context's state locked. EGL:
    /// eglQuerySurface.
    pub(super) fn drawable_size(
        self,
        r: &Real,
        display: usize,
        drawable: u64,
    ) -> Result<(u32, u32)> {
        match self {
            Wsi::Glx => glx_drawable_size(r, display, drawable),
            Wsi::Egl => {
                let e = egl::egl()?;
                egl::surface_size(e, display, drawable)
            }
        }
    }
}

/// XGetGeometry of X drawable `x`: its size, None when the request
/// fails or the size is empty. One round trip, whose reply also tells that
/// the server has processed every earlier request. Its X error is not
/// trapped here: callers trap it.
pub(super) fn geometry(r: &Real, dpy: *mut xlib::Display, x: u64) -> Option<(u32, u32)> {
    let (mut root, mut px, mut py) = (0, 0, 0);
    let (mut w, mut h, mut border, mut depth) = (0u32, 0u32, 0u32, 0u32);
    // SAFETY: valid display and out-pointers; a bad drawable is an X
    // error, which the caller traps.
    let ok = unsafe {
        (r.xlib.XGetGeometry)(
            dpy,
            x,
            &mut root,
            &mut px,
            &mut py,
            &mut w,
            &mut h,
            &mut border,
            &mut depth,
        )
    };
    (ok != 0 && w > 0 && h > 0).then_some((w, h))
}

fn glx_drawable_size(r: &Real, display: usize, drawable: u64) -> Result<(u32, u32)> {
    let dpy = display as *mut xlib::Display;
    let x = registry::with(|reg| reg.x_drawable(display, drawable));
    // One round trip: XGetGeometry's reply brings its error, if any.
    if let (Some(size), 0) = trap_replied_x_errors(&r.xlib, dpy, || geometry(r, dpy, x)) {
        return Ok(size);
    }
    let ((w, h), err) = trap_x_errors(&r.xlib, dpy, || {
        let (mut w, mut h) = (0u32, 0u32);
        // SAFETY: valid display and out-pointers; errors trapped.
        unsafe {
            (r.glx.glXQueryDrawable)(dpy, drawable, GLX_WIDTH, &mut w);
            (r.glx.glXQueryDrawable)(dpy, drawable, GLX_HEIGHT, &mut h);
        }
        (w, h)
    });
    if err == 0 && w > 0 && h > 0 {
        Ok((w, h))
    } else {
        Err(Error::invalid_operation(format!(
            "drawable {drawable:#x} has no size (X error {err}): it was destroyed?"
        )))
    }
}

//! SGI IRIS GL's stereo subset (seed 002) through the C ABI.
//!
//! C programs normally use these through `include/glstereo/irisgl.h`, which
//! defines IRIS GL's names (`getgdesc`, `setmonitor`, `winopen`,
//! `stereobuffer`, `leftbuffer`, `viewport`, `window`, `translate`, …) on
//! top of them. Numeric constants are SGI's own (IRIX `<gl/gl.h>`,
//! `<gl/get.h>`).
//!
//! Thread rules: monitor mode, prefposition and the window table are
//! process-wide; the calls that act on "the current window" use the
//! winopen() window current on the calling thread (winopen() makes the new
//! window current; gls_make_current() switches).

use std::ffi::c_char;
use std::sync::Arc;

use super::boundary::{arg_out, arg_str, ffi_boundary, write_out};
use super::handles::{self, Kind};
use super::surface::gls_surface;
use super::types::gls_result;
use crate::shims::irisgl;
use crate::surface::Surface;

/// getgdesc inquiry GD_XPMAX: the emulated screen's width in pixels.
pub const GLS_IRISGL_GD_XPMAX: i32 = 0;
/// getgdesc inquiry GD_YPMAX: the emulated screen's height in pixels.
pub const GLS_IRISGL_GD_YPMAX: i32 = 1;
/// getgdesc inquiry GD_STEREO: 1, stereo display modes are available.
pub const GLS_IRISGL_GD_STEREO: i32 = 50;
/// getgdesc inquiry GD_STEREO_IN_WINDOW: 1 when windows get stereo buffers.
pub const GLS_IRISGL_GD_STEREO_IN_WINDOW: i32 = 89;

/// Monitor type HZ60: 60 Hz mono (the initial mode).
pub const GLS_IRISGL_HZ60: i32 = 1;
/// Monitor type STR_RECT: full-screen above/below stereo (left eye GL rows
/// 532–1023, right eye rows 0–491 of 1024; 40 rows lost).
pub const GLS_IRISGL_STR_RECT: i32 = 15;
/// Monitor type HZ72: 72 Hz mono.
pub const GLS_IRISGL_HZ72: i32 = 23;
/// Monitor type STR_BOT: windowed stereo in the bottom 492 rows.
pub const GLS_IRISGL_STR_BOT: i32 = 27;
/// Monitor type STR_TOP: windowed stereo in the top 492 rows.
pub const GLS_IRISGL_STR_TOP: i32 = 28;

/// getgdesc(inquiry): GD_XPMAX and GD_YPMAX give the emulated screen's
/// width and height in pixels (1280 and 1024 by default; SGI's programs
/// use getgdesc(GD_XPMAX) - 1 as the last column); GD_STEREO gives 1 (the
/// STR_* modes work on every window); GD_STEREO_IN_WINDOW gives 1 when
/// windows get stereo buffers: for the current window, whether it has
/// them; otherwise whether GLSTEREO_EMULATION allows them.
///
/// @param inquiry one of the four GLS_IRISGL_GD_* values.
/// @param value_out must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_ENUM (another
/// inquiry; irisgl.h's getgdesc() then returns -1, as IRIS GL does);
/// GLS_ERROR_INVALID_VALUE (a bad GLSTEREO_EMULATION). Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_irisgl_getgdesc(inquiry: i32, value_out: *mut i64) -> gls_result {
    ffi_boundary!("gls_irisgl_getgdesc", {
        let out = arg_out(value_out, "value_out")?;
        let v = irisgl::getgdesc(inquiry)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, v) };
        Ok(())
    })
}

/// getmonitor(): the current monitor mode.
///
/// Default: GLS_IRISGL_HZ60.
///
/// @param mode_out must not be NULL.
/// @return GLS_OK or GLS_ERROR_NULL_POINTER. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_irisgl_getmonitor(mode_out: *mut i32) -> gls_result {
    ffi_boundary!("gls_irisgl_getmonitor", {
        let out = arg_out(mode_out, "mode_out")?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, irisgl::getmonitor()) };
        Ok(())
    })
}

/// setmonitor(mode): switches the (process-wide) monitor mode, which sets
/// how every winopen() window's eyes are read: HZ60 / HZ72 the quad buffer
/// (a mono window shows one image to both eyes; a stereobuffer() window its
/// left and right buffers — square-pixel stereo); STR_RECT the above/below
/// rows (GLS_INPUT_STR_RECT); STR_TOP / STR_BOT one 492-row band, from each
/// eye's buffer (GLS_INPUT_STR_TOP / GLS_INPUT_STR_BOT). Restore the mode
/// getmonitor() gave before switching.
///
/// @param mode GLS_IRISGL_HZ60, _HZ72, _STR_RECT, _STR_TOP or _STR_BOT.
/// @return GLS_OK; GLS_ERROR_INVALID_ENUM (another mode);
/// GLS_ERROR_INVALID_VALUE (a window too small for the bands). Nothing
/// changes on error. Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_setmonitor(mode: i32) -> gls_result {
    ffi_boundary!("gls_irisgl_setmonitor", { irisgl::setmonitor(mode) })
}

/// prefposition(x1, x2, y1, y2): the next winopen() window covers these
/// inclusive screen pixels, clamped to the emulated screen (so the seed's
/// prefposition(0, getgdesc(GD_XPMAX), 0, getgdesc(GD_YPMAX)) is the full
/// screen). Only the size matters: the emulated window stands for the
/// screen area it covers.
///
/// @return GLS_OK or GLS_ERROR_INVALID_VALUE (x2 < x1 or y2 < y1). Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_prefposition(x1: i32, x2: i32, y1: i32, y2: i32) -> gls_result {
    ffi_boundary!("gls_irisgl_prefposition", {
        irisgl::prefposition(x1, x2, y1, y2)
    })
}

/// winopen(title): opens a window (GLSTEREO_BACKEND chooses the backend):
/// the size prefposition() gave, else the whole emulated screen; RGBA8
/// with depth, double-buffered underneath, with stereo buffers unless
/// GLSTEREO_EMULATION=off; read in the current monitor mode; made current
/// on the calling thread. As in IRIS GL it starts mono and single-buffered
/// (drawing reaches the front buffers) until gconfig().
///
/// @param title ignored by the headless backends; may be NULL.
/// @param window_out receives the window identifier (>= 1); must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_VALUE (a bad
/// title string or prefposition); GLS_ERROR_BACKEND_UNAVAILABLE;
/// GLS_ERROR_OUT_OF_MEMORY. Thread: the window is current on the calling thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_irisgl_winopen(
    title: *const c_char,
    window_out: *mut i32,
) -> gls_result {
    ffi_boundary!("gls_irisgl_winopen", {
        let out = arg_out(window_out, "window_out")?;
        if !title.is_null() {
            // SAFETY: non-NULL and NUL-terminated (contract).
            unsafe { arg_str(title, "title")? };
        }
        let (id, s) = irisgl::winopen()?;
        let _handle: *mut gls_surface = handles::publish(s, Kind::Surface);
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, id) };
        Ok(())
    })
}

/// winclose(window): releases the window if current on the calling thread
/// and destroys it.
///
/// @return GLS_OK or GLS_ERROR_INVALID_HANDLE (not a live window). Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_winclose(window: i32) -> gls_result {
    ffi_boundary!("gls_irisgl_winclose", {
        let s = irisgl::winclose(window)?;
        drop(handles::release::<Surface, gls_surface>(
            Arc::as_ptr(&s) as *const gls_surface,
            Kind::Surface,
        ));
        Ok(())
    })
}

/// The surface of a winopen() window, to capture it
/// (gls_surface_save_png()) or choose its output format. Owned by the
/// window: winclose() destroys it; do not destroy it yourself.
///
/// @param surface_out must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_irisgl_surface(
    window: i32,
    surface_out: *mut *mut gls_surface,
) -> gls_result {
    ffi_boundary!("gls_irisgl_surface", {
        let out = arg_out(surface_out, "surface_out")?;
        let s = irisgl::window_surface(window)?;
        let handle = Arc::as_ptr(&s) as *mut gls_surface;
        handles::get::<Surface, _>(
            handle,
            Kind::Surface,
            "the window's surface (destroyed by gls_surface_destroy)",
        )?;
        // SAFETY: checked non-NULL; `handle` is live.
        unsafe { write_out(out, handle) };
        Ok(())
    })
}

/// stereobuffer(): the current window gets stereo buffering at the next
/// gconfig(). @return GLS_OK or GLS_ERROR_INVALID_OPERATION (no current
/// winopen() window). Thread: the window's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_stereobuffer() -> gls_result {
    ffi_boundary!("gls_irisgl_stereobuffer", {
        irisgl::set_pending_stereo(true)
    })
}

/// monobuffer(): the current window goes back to mono at the next
/// gconfig(): drawing reaches both eyes' buffers alike.
/// @return as gls_irisgl_stereobuffer(). Thread: the window's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_monobuffer() -> gls_result {
    ffi_boundary!("gls_irisgl_monobuffer", {
        irisgl::set_pending_stereo(false)
    })
}

/// doublebuffer(): the current window draws into back buffers from the
/// next gconfig(), shown by swapbuffers().
/// @return as gls_irisgl_stereobuffer(). Thread: the window's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_doublebuffer() -> gls_result {
    ffi_boundary!("gls_irisgl_doublebuffer", {
        irisgl::set_pending_double(true)
    })
}

/// singlebuffer(): the current window draws into its front (visible)
/// buffers from the next gconfig(). Default for a new window.
/// @return as gls_irisgl_stereobuffer(). Thread: the window's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_singlebuffer() -> gls_result {
    ffi_boundary!("gls_irisgl_singlebuffer", {
        irisgl::set_pending_double(false)
    })
}

/// gconfig(): applies stereobuffer()/monobuffer() and
/// doublebuffer()/singlebuffer() to the current window and points drawing
/// at the buffers they and leftbuffer()/rightbuffer() select.
///
/// @return GLS_OK; GLS_ERROR_INVALID_OPERATION (no current window, or
/// stereobuffer() on a window without stereo buffers — nothing changes).
/// Thread: the window's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_gconfig() -> gls_result {
    ffi_boundary!("gls_irisgl_gconfig", { irisgl::gconfig() })
}

/// leftbuffer(enable): whether drawing reaches the left eye's buffer of a
/// stereo-buffered window (with rightbuffer(): both → GL_BACK, left only →
/// GL_BACK_LEFT, right only → GL_BACK_RIGHT, neither → GL_NONE; the FRONT
/// ones when single-buffered). A mono window remembers it for later.
///
/// Default: true.
///
/// @return as gls_irisgl_stereobuffer(). Thread: the window's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_leftbuffer(enable: bool) -> gls_result {
    ffi_boundary!("gls_irisgl_leftbuffer", { irisgl::leftbuffer(enable) })
}

/// rightbuffer(enable): whether drawing reaches the right eye's buffer; see
/// gls_irisgl_leftbuffer().
///
/// Default: false.
///
/// @return as gls_irisgl_stereobuffer(). Thread: the window's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_rightbuffer(enable: bool) -> gls_result {
    ffi_boundary!("gls_irisgl_rightbuffer", { irisgl::rightbuffer(enable) })
}

/// swapbuffers(): presents a double-buffered current window (both eyes at
/// once); ignored for a single-buffered one, as in IRIS GL.
///
/// @return GLS_OK; GLS_ERROR_INVALID_OPERATION (no current window); the
/// codes of gls_swap_buffers(). Thread: the window's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_swapbuffers() -> gls_result {
    ffi_boundary!("gls_irisgl_swapbuffers", { irisgl::swapbuffers() })
}

/// viewport(left, right, bottom, top) with IRIS GL's inclusive pixel
/// bounds: glViewport(left, bottom, right − left + 1, top − bottom + 1).
/// As IRIS GL's viewport also sets the screenmask, it sets the same
/// glScissor box and enables GL_SCISSOR_TEST, so a clear touches only this
/// viewport (e.g. one eye's band in STR_RECT).
///
/// @return GLS_OK; GLS_ERROR_INVALID_VALUE (right < left or top < bottom);
/// GLS_ERROR_NO_CURRENT_SURFACE. Thread: the surface's. Works on any current surface.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_viewport(left: i32, right: i32, bottom: i32, top: i32) -> gls_result {
    ffi_boundary!("gls_irisgl_viewport", {
        irisgl::viewport(left, right, bottom, top)
    })
}

/// window(left, right, bottom, top, near, far): glFrustum's matrix
/// replaces GL_PROJECTION (the matrix mode is left unchanged). Seed 002's
/// stereo eyes: window(−top·aspect ± half_sep·near/distance, top·aspect ±
/// half_sep·near/distance, −top, top, near, far), then translate(±half_sep, 0, 0).
///
/// @return GLS_OK; GLS_ERROR_INVALID_VALUE (glFrustum's rules: near > 0,
/// far > near, left ≠ right, bottom ≠ top, all finite);
/// GLS_ERROR_NO_CURRENT_SURFACE. Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_window(
    left: f64,
    right: f64,
    bottom: f64,
    top: f64,
    near_clip: f64,
    far_clip: f64,
) -> gls_result {
    ffi_boundary!("gls_irisgl_window", {
        irisgl::window(left, right, bottom, top, near_clip, far_clip)
    })
}

/// translate(x, y, z): multiplies the current GL matrix by a translation,
/// as glTranslated.
///
/// @return GLS_OK; GLS_ERROR_INVALID_VALUE (not finite);
/// GLS_ERROR_NO_CURRENT_SURFACE. Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_irisgl_translate(x: f64, y: f64, z: f64) -> gls_result {
    ffi_boundary!("gls_irisgl_translate", { irisgl::translate(x, y, z) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_c_constants_are_the_shims() {
        assert_eq!(
            [
                GLS_IRISGL_GD_XPMAX,
                GLS_IRISGL_GD_YPMAX,
                GLS_IRISGL_GD_STEREO,
                GLS_IRISGL_GD_STEREO_IN_WINDOW
            ],
            [
                irisgl::GD_XPMAX,
                irisgl::GD_YPMAX,
                irisgl::GD_STEREO,
                irisgl::GD_STEREO_IN_WINDOW
            ]
        );
        assert_eq!(
            [
                GLS_IRISGL_HZ60,
                GLS_IRISGL_STR_RECT,
                GLS_IRISGL_HZ72,
                GLS_IRISGL_STR_BOT,
                GLS_IRISGL_STR_TOP
            ],
            [
                irisgl::HZ60,
                irisgl::STR_RECT,
                irisgl::HZ72,
                irisgl::STR_BOT,
                irisgl::STR_TOP
            ]
        );
    }
}

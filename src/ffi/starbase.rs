//! HP Starbase full-screen stereo (seed 000 §9) through the C ABI.
//!
//! C programs normally use these through `include/glstereo/starbase.h`,
//! which defines Starbase's names (`gescape_arg`, `STEREO`, `gopen`,
//! `gclose`, `gescape`) on top of them and turns result codes into
//! Starbase's `-1` with `errno`.

use std::ffi::c_char;
use std::sync::Arc;

use super::boundary::{arg_out, ffi_boundary, write_out};
use super::handles::{self, Kind};
use super::surface::gls_surface;
use super::types::gls_result;
use crate::error::Error;
use crate::shims::starbase;
use crate::surface::Surface;

/// The argument block of a gescape, as HP's `gescape_arg`: 64 ints, 64
/// floats or 255 chars in 256 bytes. For STEREO, `i[0]` is TRUE (non-zero,
/// sync-doubling on) or FALSE (0, off).
#[repr(C)]
#[derive(Clone, Copy)]
pub union gls_gescape_arg {
    /// The block as ints (`arg.i[0]` for STEREO).
    pub i: [i32; 64],
    /// The block as floats.
    pub f: [f32; 64],
    /// The block as chars.
    pub c: [c_char; 255],
}

/// The STEREO gescape opcode. HP's numeric value is not public; glstereo
/// uses 9000, outside every opcode range of HP's starbase.c.h (0–1308).
pub const GLS_STARBASE_STEREO: i32 = 9000;

/// The `gopen()` kind for an output device (HP's OUTDEV).
pub const GLS_STARBASE_OUTDEV: i32 = 0;
/// The `gopen()` kind for an output and input device (HP's OUTINDEV).
pub const GLS_STARBASE_OUTINDEV: i32 = 2;

fn bad_fildes() -> Error {
    Error::InvalidHandle("fildes (a Starbase descriptor from gopen() or gls_starbase_fildes())")
}

/// The surface a descriptor names, if its gls_surface handle is still live
/// (a destroyed surface's descriptor is dead too).
fn live_surface(fildes: i32) -> Result<Arc<Surface>, Error> {
    let s = starbase::surface(fildes)?;
    let handle = Arc::as_ptr(&s) as *const gls_surface;
    handles::get::<Surface, _>(handle, Kind::Surface, "surface").map_err(|_| bad_fildes())
}

/// A Starbase descriptor (`fildes`) for an existing surface, to pass to
/// gescape(). The same surface always gets the same descriptor. The
/// program keeps owning the surface: gls_surface_destroy() ends the
/// descriptor too (gescape() on it then fails with EBADF).
///
/// @param surface a live surface (mono, any size; sync-doubling reads its
/// front-left buffer). @param fildes_out receives the descriptor (>= 3);
/// must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_starbase_fildes(
    surface: *mut gls_surface,
    fildes_out: *mut i32,
) -> gls_result {
    ffi_boundary!("gls_starbase_fildes", {
        let s: Arc<Surface> = handles::get(surface, Kind::Surface, "surface")?;
        let out = arg_out(fildes_out, "fildes_out")?;
        let id = starbase::fildes_for(&s)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, id) };
        Ok(())
    })
}

/// The emulation's gopen(): opens the emulated screen (GLSTEREO_BACKEND
/// chooses the backend) as a mono, double-buffered RGBA8 surface with a
/// depth buffer, the size of gls_screen_get_size() (1280x1024 unless
/// gls_screen_set_size() said otherwise), and makes it current on the
/// calling thread so the program can draw with GL. Get the surface with
/// gls_starbase_surface(); gls_starbase_close() destroys it.
///
/// @param kind GLS_STARBASE_OUTDEV or GLS_STARBASE_OUTINDEV (the emulation
/// has no input devices). @param fildes_out receives the descriptor (>= 3);
/// must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_ENUM (kind);
/// GLS_ERROR_BACKEND_UNAVAILABLE; GLS_ERROR_OUT_OF_MEMORY; the codes of
/// gls_make_current(). Thread: the surface is current on the calling thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_starbase_open(kind: i32, fildes_out: *mut i32) -> gls_result {
    ffi_boundary!("gls_starbase_open", {
        let out = arg_out(fildes_out, "fildes_out")?;
        if kind != GLS_STARBASE_OUTDEV && kind != GLS_STARBASE_OUTINDEV {
            return Err(Error::invalid_enum(
                "kind",
                kind as u32,
                "use OUTDEV (0) or OUTINDEV (2): the emulated screen is an output device",
            ));
        }
        let (id, s) = starbase::open()?;
        let _handle: *mut gls_surface = handles::publish(s, Kind::Surface);
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, id) };
        Ok(())
    })
}

/// The surface a descriptor names, to capture it (gls_surface_save_png()),
/// choose its output format or present it (gls_swap_buffers()). The handle
/// stays owned by the descriptor's creator: do not destroy a gopen()
/// surface yourself, gls_starbase_close() does.
///
/// @param fildes a descriptor. @param surface_out must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE (not a
/// live descriptor). Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_starbase_surface(
    fildes: i32,
    surface_out: *mut *mut gls_surface,
) -> gls_result {
    ffi_boundary!("gls_starbase_surface", {
        let out = arg_out(surface_out, "surface_out")?;
        let s = live_surface(fildes)?;
        // SAFETY: checked non-NULL; the pointer is the live handle of `s`.
        unsafe { write_out(out, Arc::as_ptr(&s) as *mut gls_surface) };
        Ok(())
    })
}

/// The emulation's gclose(): ends a descriptor. A surface opened by
/// gls_starbase_open() is released (if current on the calling thread) and
/// destroyed; one named with gls_starbase_fildes() is left to its owner.
///
/// @return GLS_OK or GLS_ERROR_INVALID_HANDLE (not a live descriptor;
/// nothing changes). Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_starbase_close(fildes: i32) -> gls_result {
    ffi_boundary!("gls_starbase_close", {
        if let Some(s) = starbase::close(fildes)? {
            // The handle gls_starbase_open() published (already gone if
            // the program destroyed it itself).
            drop(handles::release::<Surface, gls_surface>(
                Arc::as_ptr(&s) as *const gls_surface,
                Kind::Surface,
            ));
        }
        Ok(())
    })
}

/// Starbase's gescape(fildes, op, arg1, arg2). The emulation has one
/// escape, GLS_STARBASE_STEREO: `arg1->i[0]` non-zero (TRUE) turns
/// sync-doubling on for the surface fildes names — its mono frame is then
/// read as left eye = upper half, right eye = lower half, each stretched ×2
/// vertically (GLS_INPUT_SYNC_DOUBLED), and those eyes go to every output
/// format and capture; 0 (FALSE) turns it off (GLS_INPUT_QUAD_BUFFER: the
/// plain mono frame to both eyes). arg2 is not used.
///
/// Default: off.
///
/// @param fildes a live descriptor. @param op GLS_STARBASE_STEREO.
/// @param arg1 must not be NULL. @param arg2 unused; may be NULL.
/// @return GLS_OK; GLS_ERROR_INVALID_HANDLE (fildes, checked first);
/// GLS_ERROR_INVALID_ENUM (op); GLS_ERROR_NULL_POINTER (arg1);
/// GLS_ERROR_INVALID_VALUE (a surface under 2 rows). Nothing changes on
/// error. starbase.h's gescape() turns these into -1 with errno EBADF,
/// EINVAL, EFAULT and EINVAL. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_starbase_gescape(
    fildes: i32,
    op: i32,
    arg1: *const gls_gescape_arg,
    arg2: *mut gls_gescape_arg,
) -> gls_result {
    ffi_boundary!("gls_starbase_gescape", {
        let _ = arg2;
        live_surface(fildes)?;
        // SAFETY: NULL or a valid gescape_arg (contract); every bit pattern
        // is a valid i32, so reading the int view is sound.
        let i0 = unsafe { arg1.as_ref() }.map(|a| unsafe { a.i[0] });
        starbase::gescape(fildes, op, i0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_c_constants_are_the_shims() {
        assert_eq!(GLS_STARBASE_STEREO, starbase::STEREO);
        assert_eq!(
            std::mem::size_of::<gls_gescape_arg>(),
            256,
            "HP's gescape_arg is 256 bytes"
        );
    }
}

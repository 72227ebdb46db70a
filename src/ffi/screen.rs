//! The emulated screen that Starbase's gopen() and IRIS GL's winopen()
//! open, through the C ABI.

use super::boundary::{arg_out, ffi_boundary, write_out};
use super::types::gls_result;
use crate::shims::screen;

/// Sets the size of the emulated screen that gls_starbase_open() (gopen())
/// and gls_irisgl_winopen() (winopen()) open from now on, as a period
/// program's display mode was set outside it (HP's and SGI's setmon).
/// Surfaces already open keep their size.
///
/// Default: 1280x1024, the mode of both seeds. Process-wide.
///
/// @param width, height 1…16384.
/// @return GLS_OK or GLS_ERROR_INVALID_VALUE (nothing changes). Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_screen_set_size(width: u32, height: u32) -> gls_result {
    ffi_boundary!("gls_screen_set_size", {
        screen::set_screen_size(width, height)
    })
}

/// The size of the emulated screen.
///
/// @param width_out, height_out must not be NULL.
/// @return GLS_OK or GLS_ERROR_NULL_POINTER. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_screen_get_size(
    width_out: *mut u32,
    height_out: *mut u32,
) -> gls_result {
    ffi_boundary!("gls_screen_get_size", {
        let w_out = arg_out(width_out, "width_out")?;
        let h_out = arg_out(height_out, "height_out")?;
        let (w, h) = screen::screen_size();
        // SAFETY: both checked non-NULL.
        unsafe {
            write_out(w_out, w);
            write_out(h_out, h);
        }
        Ok(())
    })
}

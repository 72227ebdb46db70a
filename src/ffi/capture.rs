//! Captures that do not stall a frame loop: PNG files written by the
//! surface's own threads (see `Surface::queue_png`).

use std::ffi::c_char;

use super::boundary::{arg_str, ffi_boundary};
use super::handles::{self, Kind};
use super::surface::{gls_surface, image_arg};
use super::types::*;
use crate::surface::Surface;

/// Captures a surface may queue before gls_surface_queue_png waits for the
/// oldest to be written.
pub const GLS_CAPTURE_QUEUE_LENGTH: u32 = 4;

/// Like gls_surface_save_png, but returns as soon as the pixels are read
/// back: the PNG is encoded and written (atomically, temporary file then
/// rename) by the surface's capture threads, in the order queued, so a
/// frame loop can capture every frame. At most GLS_CAPTURE_QUEUE_LENGTH
/// captures wait; beyond that this call waits for the oldest to be
/// written. Call gls_surface_wait_captures() to know that the files exist
/// (destroying the surface also writes what is queued).
///
/// @param surface a live surface. @param image GLS_IMAGE_LEFT, GLS_IMAGE_RIGHT or GLS_IMAGE_COMPOSITE.
/// @param path a file path (UTF-8); must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_ENUM (image); GLS_ERROR_IO when an earlier queued
/// capture failed to be written (reported once, by the next call; the
/// message names its path and the reason; this capture is queued anyway).
/// Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_queue_png(
    surface: *mut gls_surface,
    image: u32,
    path: *const c_char,
) -> gls_result {
    ffi_boundary!("gls_surface_queue_png", {
        let s = handles::get::<Surface, _>(surface, Kind::Surface, "surface")?;
        let which = image_arg(image)?;
        // SAFETY: NUL-terminated (contract).
        let path = unsafe { arg_str(path, "path")? };
        s.queue_png(which, std::path::Path::new(path))
    })
}

/// Waits until every capture queued with gls_surface_queue_png() is
/// written.
///
/// @param surface a live surface.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_IO when a queued capture failed to be written and was not yet
/// reported (the message names its path and the reason). Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_wait_captures(surface: *mut gls_surface) -> gls_result {
    ffi_boundary!("gls_surface_wait_captures", {
        let s = handles::get::<Surface, _>(surface, Kind::Surface, "surface")?;
        s.finish_captures()
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_queue_length_in_the_header_is_the_queues() {
        assert_eq!(
            super::GLS_CAPTURE_QUEUE_LENGTH as usize,
            crate::capture::queue::DEFAULT_CAPACITY
        );
    }
}

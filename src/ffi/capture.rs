//! Captures that do not stall a frame loop: PNG files written by the
//! surface's own threads (see `Surface::queue_png`); and stereo photos,
//! MPO and JPS, written at once or queued (see `Surface::save_stereo_photo`).

use std::ffi::c_char;

use super::boundary::{arg_str, ffi_boundary};
use super::handles::{self, Kind};
use super::surface::{gls_surface, image_arg};
use super::types::*;
use crate::capture::stereo_photo::StereoPhotoFormat;
use crate::error::Error;
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

/// Waits until every capture queued with gls_surface_queue_png() or
/// gls_surface_queue_stereo_photo() is written.
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

/// Stereo photo format: MPO (CIPA DC-007 Multi-Picture Object), two
/// baseline JPEGs in one file, the left eye first, with the MP Index that
/// 3D televisions, phones, the Nintendo 3DS and stereo viewers read.
/// Usual extension: .mpo.
pub const GLS_PHOTO_MPO: u32 = 0;
/// Stereo photo format: JPS (JPEG stereo), one JPEG twice as wide as an
/// eye, the RIGHT eye on the left half (the cross-eyed convention JPS
/// viewers expect), with the JPS APP3 descriptor. Usual extension: .jps.
pub const GLS_PHOTO_JPS: u32 = 1;

/// The stereo photo format a GLS_PHOTO_* value names.
fn photo_arg(format: u32) -> Result<StereoPhotoFormat, Error> {
    match format {
        GLS_PHOTO_MPO => Ok(StereoPhotoFormat::Mpo),
        GLS_PHOTO_JPS => Ok(StereoPhotoFormat::Jps),
        v => Err(Error::invalid_enum(
            "format",
            v,
            "use GLS_PHOTO_MPO or GLS_PHOTO_JPS",
        )),
    }
}

/// Sets the JPEG quality of the surface's stereo photos
/// (gls_surface_save_stereo_photo, gls_surface_queue_stereo_photo).
///
/// Default: 90 (chroma at full resolution; below 90 it is halved both
/// ways, which smears thin coloured lines).
///
/// @param surface a live surface.
/// @param quality 1 (smallest file) … 100 (best image).
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_VALUE (outside 1…100; nothing changes). Any thread.
#[unsafe(no_mangle)]
pub extern "C" fn gls_surface_set_jpeg_quality(
    surface: *mut gls_surface,
    quality: u32,
) -> gls_result {
    ffi_boundary!("gls_surface_set_jpeg_quality", {
        let s = handles::get::<Surface, _>(surface, Kind::Surface, "surface")?;
        s.set_jpeg_quality(quality)
    })
}

/// Writes the two eyes a viewer sees now (the front buffers taken apart
/// by the input framing, exchanged when the surface swaps eyes) as one
/// stereo photo: GLS_PHOTO_MPO or GLS_PHOTO_JPS, at the surface's JPEG
/// quality. The file appears complete or not at all (written to a
/// temporary name, then renamed). Alpha is dropped.
///
/// A mono surface is refused: its two eyes are one image, and a mono MPO
/// or JPS is not a stereo photo (use gls_surface_save_png).
///
/// @param surface a live surface. @param format GLS_PHOTO_MPO or GLS_PHOTO_JPS.
/// @param path a file path (UTF-8); must not be NULL. The extension is not
/// checked (.mpo and .jps are usual).
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_ENUM (format); GLS_ERROR_INVALID_OPERATION (a mono
/// surface: the message says how to get two eyes); GLS_ERROR_INVALID_VALUE
/// (a path that is not UTF-8 or names no file, e.g. ""); GLS_ERROR_OUT_OF_MEMORY;
/// GLS_ERROR_IO (the message names the path and the reason; no file and
/// no temporary file is left). Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_save_stereo_photo(
    surface: *mut gls_surface,
    format: u32,
    path: *const c_char,
) -> gls_result {
    ffi_boundary!("gls_surface_save_stereo_photo", {
        let s = handles::get::<Surface, _>(surface, Kind::Surface, "surface")?;
        let format = photo_arg(format)?;
        // SAFETY: NUL-terminated (contract).
        let path = unsafe { arg_str(path, "path")? };
        s.save_stereo_photo(format, std::path::Path::new(path))
    })
}

/// Like gls_surface_save_stereo_photo, but returns as soon as the eyes are
/// read back: the photo is encoded and written by the surface's capture
/// threads, in order with gls_surface_queue_png captures (see there for
/// the queue length and gls_surface_wait_captures()).
///
/// @param surface a live surface. @param format GLS_PHOTO_MPO or GLS_PHOTO_JPS.
/// @param path a file path (UTF-8); must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_ENUM (format); GLS_ERROR_INVALID_OPERATION (a mono
/// surface; nothing is queued); GLS_ERROR_IO when an earlier queued capture
/// failed to be written (reported once, by the next call; the message names
/// its path and the reason; this capture is queued anyway). Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_queue_stereo_photo(
    surface: *mut gls_surface,
    format: u32,
    path: *const c_char,
) -> gls_result {
    ffi_boundary!("gls_surface_queue_stereo_photo", {
        let s = handles::get::<Surface, _>(surface, Kind::Surface, "surface")?;
        let format = photo_arg(format)?;
        // SAFETY: NUL-terminated (contract).
        let path = unsafe { arg_str(path, "path")? };
        s.queue_stereo_photo(format, std::path::Path::new(path))
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

//! Displays and configurations through the C ABI.

use std::sync::Arc;

use super::boundary::{arg_out, ffi_boundary, write_out};
use super::handles::{self, Kind};
use super::types::*;
use crate::backend::{BackendChoice, BackendKind};
use crate::config::{Config, MAX_ATTRIBUTES, StereoKind};
use crate::display::Display;
use crate::error::Error;

/// An open backend connection (opaque).
pub struct gls_display {
    _private: [u8; 0],
}

/// A chosen framebuffer configuration (opaque).
pub struct gls_config {
    _private: [u8; 0],
}

/// The automatic choice: the GLSTEREO_BACKEND environment variable if set,
/// else GLX when $DISPLAY works, else EGL surfaceless, else OSMesa; a
/// program whose own gl* calls go to libOSMesa always gets OSMesa.
pub const GLS_BACKEND_AUTO: u32 = 0;
/// GLX on the X server named by $DISPLAY: real windows.
pub const GLS_BACKEND_GLX: u32 = 1;
/// EGL on Mesa's surfaceless platform: headless.
pub const GLS_BACKEND_EGL: u32 = 2;
/// OSMesa: headless software rendering (link the program with -lOSMesa).
pub const GLS_BACKEND_OSMESA: u32 = 3;

/// The configuration is mono.
pub const GLS_STEREO_NONE: u32 = 0;
/// The configuration uses the driver's own quad buffer.
pub const GLS_STEREO_NATIVE: u32 = 1;
/// The configuration uses glstereo's emulated quad buffer.
pub const GLS_STEREO_EMULATED: u32 = 2;

fn backend_choice(v: u32) -> Result<BackendChoice, Error> {
    Ok(match v {
        GLS_BACKEND_AUTO => BackendChoice::Auto,
        GLS_BACKEND_GLX => BackendChoice::Only(BackendKind::Glx),
        GLS_BACKEND_EGL => BackendChoice::Only(BackendKind::Egl),
        GLS_BACKEND_OSMESA => BackendChoice::Only(BackendKind::OsMesa),
        _ => {
            return Err(Error::invalid_enum(
                "backend",
                v,
                "use GLS_BACKEND_AUTO, GLS_BACKEND_GLX, GLS_BACKEND_EGL or GLS_BACKEND_OSMESA",
            ));
        }
    })
}

fn backend_code(k: BackendKind) -> u32 {
    match k {
        BackendKind::Glx => GLS_BACKEND_GLX,
        BackendKind::Egl => GLS_BACKEND_EGL,
        BackendKind::OsMesa => GLS_BACKEND_OSMESA,
    }
}

/// Opens a GL backend.
///
/// With GLS_BACKEND_AUTO the environment decides (GLSTEREO_BACKEND=auto|glx|
/// egl|osmesa), so one program runs in a window or headless unchanged.
///
/// @param backend GLS_BACKEND_AUTO, GLS_BACKEND_GLX, GLS_BACKEND_EGL or GLS_BACKEND_OSMESA.
/// @param display_out receives the display; must not be NULL. Close it with gls_display_close().
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_ENUM (backend);
/// GLS_ERROR_INVALID_VALUE (a bad GLSTEREO_BACKEND); GLS_ERROR_BACKEND_UNAVAILABLE
/// when the library cannot be loaded (the message names the package to install).
/// Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_display_open(
    backend: u32,
    display_out: *mut *mut gls_display,
) -> gls_result {
    ffi_boundary!("gls_display_open", {
        let out = arg_out(display_out, "display_out")?;
        let display = Display::open(backend_choice(backend)?)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, handles::publish(display, Kind::Display)) };
        Ok(())
    })
}

/// Closes a display. Surfaces made on it stay usable until destroyed (they
/// keep the backend alive). NULL is a no-op; a handle that is not live is
/// ignored (and reported by gls_last_error_message()). Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_display_close(display: *mut gls_display) {
    ffi_boundary!("gls_display_close", () => {
        if !display.is_null() && handles::release::<Display, _>(display, Kind::Display).is_none() {
            return Err(Error::InvalidHandle("display"));
        }
        Ok(())
    })
}

/// Which backend a display uses.
///
/// @param display a live display. @param backend_out receives
/// GLS_BACKEND_GLX, GLS_BACKEND_EGL or GLS_BACKEND_OSMESA; must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_HANDLE. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_display_get_backend(
    display: *const gls_display,
    backend_out: *mut u32,
) -> gls_result {
    ffi_boundary!("gls_display_get_backend", {
        let d: Arc<Display> = handles::get(display, Kind::Display, "display")?;
        let out = arg_out(backend_out, "backend_out")?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, backend_code(d.kind())) };
        Ok(())
    })
}

/// Chooses a configuration as glXChooseVisual does, from the same attribute
/// list: GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_RED_SIZE … GLX_STENCIL_SIZE
/// (each size followed by its value), terminated by None (0).
///
/// With GLX_STEREO: native stereo when the backend has it, else emulated
/// (gls_config_stereo() says which); with GLSTEREO_EMULATION=off and no
/// native stereo it fails as glXChooseVisual returns NULL, so a program's
/// own fallback (retry without GLX_STEREO) runs.
///
/// @param display a live display.
/// @param glx_attribs the attribute list; must not be NULL; at most 512 entries.
/// @param config_out receives the configuration; must not be NULL. Free it with gls_config_free().
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_ENUM for an unknown attribute (named in the message);
/// GLS_ERROR_INVALID_VALUE for a missing terminator or a bad value or a bad
/// GLSTEREO_EMULATION; GLS_ERROR_NO_MATCHING_CONFIG (the message says which
/// request cannot be met). Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_config_choose(
    display: *mut gls_display,
    glx_attribs: *const i32,
    config_out: *mut *mut gls_config,
) -> gls_result {
    ffi_boundary!("gls_config_choose", {
        let d: Arc<Display> = handles::get(display, Kind::Display, "display")?;
        if glx_attribs.is_null() {
            return Err(Error::NullPointer("glx_attribs"));
        }
        let out = arg_out(config_out, "config_out")?;
        let mut list = Vec::new();
        loop {
            if list.len() >= MAX_ATTRIBUTES {
                return Err(Error::invalid_value(format!(
                    "glx_attribs has no None (0) terminator within {MAX_ATTRIBUTES} entries"
                )));
            }
            // SAFETY: the caller passes a None-terminated list; reading stops at
            // the terminator or the cap above.
            let v = unsafe { *glx_attribs.add(list.len()) };
            if v == 0 {
                break;
            }
            list.push(v);
        }
        let config = d.choose_config(&list)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, handles::publish(Arc::new(config), Kind::Config)) };
        Ok(())
    })
}

/// How a configuration provides stereo.
///
/// @return GLS_STEREO_NONE, GLS_STEREO_NATIVE or GLS_STEREO_EMULATED;
/// GLS_STEREO_NONE for NULL or a handle that is not live (with a message
/// for gls_last_error_message()). Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_config_stereo(config: *const gls_config) -> u32 {
    ffi_boundary!("gls_config_stereo", GLS_STEREO_NONE => {
        let c: Arc<Config> = handles::get(config, Kind::Config, "config")?;
        Ok(match c.stereo {
            StereoKind::None => GLS_STEREO_NONE,
            StereoKind::Native => GLS_STEREO_NATIVE,
            StereoKind::Emulated => GLS_STEREO_EMULATED,
        })
    })
}

/// A configuration attribute as glXGetConfig reports it (GLX_STEREO is 1 for
/// native and emulated stereo; GLX_DOUBLEBUFFER; GLX_DEPTH_SIZE; …).
///
/// @param config a live configuration. @param attrib a GLX attribute.
/// @param value_out must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER, GLS_ERROR_INVALID_HANDLE or
/// GLS_ERROR_INVALID_ENUM (not a visual attribute). Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_config_get_attrib(
    config: *const gls_config,
    attrib: i32,
    value_out: *mut i32,
) -> gls_result {
    ffi_boundary!("gls_config_get_attrib", {
        let c: Arc<Config> = handles::get(config, Kind::Config, "config")?;
        let out = arg_out(value_out, "value_out")?;
        let v = c.get_attrib(attrib)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, v) };
        Ok(())
    })
}

/// Frees a configuration. Surfaces made from it are unaffected. NULL is a
/// no-op. Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_config_free(config: *mut gls_config) {
    ffi_boundary!("gls_config_free", () => {
        if !config.is_null() && handles::release::<Config, _>(config, Kind::Config).is_none() {
            return Err(Error::InvalidHandle("config"));
        }
        Ok(())
    })
}

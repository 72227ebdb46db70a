//! NV_3dvision_settings and automatic stereo through the C ABI: auto-stereo
//! capable surfaces (the analogue of EGL_NV_3dvision_surface), the
//! extension's parameters, Enable/Disable/IsEnabled and the Get commands
//! that answer its state, and the frame call that renders a mono frame once
//! per eye. The GL tokens (GL_3DVISION_STEREO_NV 0x90F4 …
//! GL_STEREO_PROJECTION_ORTHO_NV 0x90FA) and the legacy names
//! (glStereoParameterfNV, …) are in `include/glstereo/nv3dvision.h`.

use std::ffi::c_void;
use std::sync::Arc;

use super::boundary::{arg_out, ffi_boundary, write_out};
use super::display::{gls_config, gls_display};
use super::handles::{self, Kind};
use super::surface::gls_surface;
use super::types::*;
use crate::config::{Config, MAX_ATTRIBUTES};
use crate::display::Display;
use crate::error::Error;
use crate::framing::auto;
use crate::shims::nv3dvision::{GL_3DVISION_STEREO_NV, StateValue, SurfaceAttribs};
use crate::surface::{self, Surface};

/// Ends a surface attribute list.
pub const GLS_SURFACE_ATTRIB_NONE: i32 = 0;
/// Surface attribute: 1 makes the surface auto-stereo capable (NVIDIA 3D
/// Vision automatic stereo; the value of EGL_AUTO_STEREO_NV), 0 does not.
/// Default: 0.
pub const GLS_SURFACE_AUTO_STEREO: i32 = 0x3136;

/// A mono program's frame: draws the whole frame (clear included) with the
/// projection and draw buffers it finds current. `user_data` is the pointer
/// given to gls_auto_stereo_frame().
pub type gls_draw_fn = Option<unsafe extern "C" fn(user_data: *mut c_void)>;

/// Creates a surface as gls_surface_create() does, with creation attributes.
///
/// With GLS_SURFACE_AUTO_STEREO = 1 the surface is auto-stereo capable:
/// frames given to gls_auto_stereo_frame() are rendered once per eye while
/// GL_3DVISION_STEREO_NV is enabled, which it is initially. Such a surface
/// always has left and right buffers: from a mono configuration it gets
/// glstereo's emulated quad buffer (GL_STEREO then reads GL_TRUE, and
/// quad-buffer drawing works as well).
///
/// @param display a live display. @param config a live configuration from it
/// (not a native-stereo one when auto stereo is asked for).
/// @param width, height as gls_surface_create().
/// @param attribs (name, value) pairs ended by GLS_SURFACE_ATTRIB_NONE (0);
/// NULL means no attributes. At most 256 pairs.
/// @param surface_out receives the surface; must not be NULL.
/// @return as gls_surface_create(), plus GLS_ERROR_INVALID_ENUM (an unknown
/// attribute, named in the message), GLS_ERROR_INVALID_VALUE (a value other
/// than 0 or 1, or no terminator), GLS_ERROR_INVALID_OPERATION (auto stereo
/// on a native-stereo configuration). Any thread; the calling thread's
/// current surface is unchanged.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_create_with_attribs(
    display: *mut gls_display,
    config: *const gls_config,
    width: u32,
    height: u32,
    attribs: *const i32,
    surface_out: *mut *mut gls_surface,
) -> gls_result {
    ffi_boundary!("gls_surface_create_with_attribs", {
        let d: Arc<Display> = handles::get(display, Kind::Display, "display")?;
        let c: Arc<Config> = handles::get(config, Kind::Config, "config")?;
        let out = arg_out(surface_out, "surface_out")?;
        let mut pairs = Vec::new();
        if !attribs.is_null() {
            loop {
                let i = 2 * pairs.len();
                if i >= MAX_ATTRIBUTES {
                    return Err(Error::invalid_value(format!(
                        "attribs has no GLS_SURFACE_ATTRIB_NONE (0) terminator within {} pairs",
                        MAX_ATTRIBUTES / 2
                    )));
                }
                // SAFETY: the caller passes a terminated list of pairs; reading
                // stops at the terminator or the cap above.
                let name = unsafe { *attribs.add(i) };
                if name == GLS_SURFACE_ATTRIB_NONE {
                    break;
                }
                // SAFETY: a name other than the terminator is followed by its value.
                let value = unsafe { *attribs.add(i + 1) };
                pairs.push((name, value));
            }
        }
        let a = SurfaceAttribs::parse(&pairs)?;
        let s = auto::create_surface(&d, &c, width, height, a)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, handles::publish(s, Kind::Surface)) };
        Ok(())
    })
}

/// A surface creation attribute, as the surface has it (eglQuerySurface).
///
/// @param surface a live surface. @param attrib GLS_SURFACE_AUTO_STEREO.
/// @param value_out receives the value (1 if auto-stereo capable, else 0); must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_ENUM (attrib). Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_get_attrib(
    surface: *const gls_surface,
    attrib: i32,
    value_out: *mut i32,
) -> gls_result {
    ffi_boundary!("gls_surface_get_attrib", {
        let s: Arc<Surface> = handles::get(surface, Kind::Surface, "surface")?;
        let out = arg_out(value_out, "value_out")?;
        let v = match attrib {
            GLS_SURFACE_AUTO_STEREO => s.nv3dvision().capable() as i32,
            a => {
                return Err(Error::invalid_enum(
                    "attrib",
                    a as u32,
                    "use GLS_SURFACE_AUTO_STEREO (0x3136)",
                ));
            }
        };
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, v) };
        Ok(())
    })
}

/// glStereoParameterfNV: sets one 3D Vision parameter of the current surface.
///
/// - GL_STEREO_SEPARATION_NV: percent, 0…100, of the maximum separation:
///   at 100 far-away geometry is 7 % of the viewport width apart in the two
///   eyes (HP's default camera offset; see src/shims/nv3dvision.rs).
///   Default: 15.
/// - GL_STEREO_CONVERGENCE_NV: the depth shown at the screen surface (zero
///   parallax): clip-space w, the distance from the camera, for
///   perspective; the window depth 0…1 for GL_STEREO_PROJECTION_ORTHO_NV.
///   Default: 0.
/// - GL_STEREO_CUTOFF_NV: geometry at this depth or beyond never pops out
///   of the screen by more than far-away geometry recedes into it (the
///   separation is reduced when it would); 0 or less limits nothing.
///   Default: 0.
/// - GL_STEREO_PROJECTION_NV: GL_STEREO_PROJECTION_PERSPECTIVE_NV (depth
///   from clip w) or GL_STEREO_PROJECTION_ORTHO_NV (depth from the window
///   depth, for glOrtho programs), the value rounded to an integer.
///   Default: PERSPECTIVE.
///
/// Parameters are kept on every surface; on one that is not auto-stereo
/// capable they have no effect on rendering (the spec's rule).
///
/// @return GLS_OK; GLS_ERROR_NO_CURRENT_SURFACE; GLS_ERROR_INVALID_ENUM (an
/// unknown pname, or a projection that is neither method);
/// GLS_ERROR_INVALID_VALUE (separation outside 0…100; a NaN or infinite
/// value). On error nothing changes and gls_get_error() reports
/// GL_INVALID_ENUM or GL_INVALID_VALUE, as the extension specifies.
/// Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_stereo_parameterf_nv(pname: u32, param: f32) -> gls_result {
    ffi_boundary!("gls_stereo_parameterf_nv", {
        surface::require_current()?.with_nv3dvision(|nv| nv.parameter_f(pname, param))
    })
}

/// glStereoParameteriNV: as gls_stereo_parameterf_nv(), the integer taken
/// as a float for separation, convergence and cutoff.
///
/// @return as gls_stereo_parameterf_nv(). Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_stereo_parameteri_nv(pname: u32, param: i32) -> gls_result {
    ffi_boundary!("gls_stereo_parameteri_nv", {
        surface::require_current()?.with_nv3dvision(|nv| nv.parameter_i(pname, param))
    })
}

/// glEnable for the current surface: GL_3DVISION_STEREO_NV enables 3D
/// Vision rendering (no effect on a surface that is not auto-stereo
/// capable, as the extension says); every other cap goes to glEnable.
///
/// @return GLS_OK or GLS_ERROR_NO_CURRENT_SURFACE (a cap GL does not know
/// raises GL_INVALID_ENUM in GL, reported by gls_get_error()). Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_enable(cap: u32) -> gls_result {
    ffi_boundary!("gls_enable", { set_cap(cap, true) })
}

/// glDisable for the current surface: GL_3DVISION_STEREO_NV disables 3D
/// Vision rendering (frames are then drawn once, mono); every other cap goes
/// to glDisable.
///
/// @return as gls_enable(). Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_disable(cap: u32) -> gls_result {
    ffi_boundary!("gls_disable", { set_cap(cap, false) })
}

fn set_cap(cap: u32, on: bool) -> crate::error::Result<()> {
    let s = surface::require_current()?;
    if cap == GL_3DVISION_STEREO_NV {
        return s.with_nv3dvision(|nv| {
            nv.set_enabled(on);
            Ok(())
        });
    }
    // SAFETY: the surface's application context is current on this thread.
    unsafe {
        if on {
            s.gl().Enable(cap)
        } else {
            s.gl().Disable(cap)
        }
    }
    Ok(())
}

/// glIsEnabled for the current surface: GL_3DVISION_STEREO_NV is answered
/// from the 3D Vision state (initially 1 on an auto-stereo capable surface,
/// 0 on any other, where it stays 0); every other cap goes to glIsEnabled.
///
/// @return 1 or 0; 0 when there is no current surface (with a message for
/// gls_last_error_message()). Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_is_enabled(cap: u32) -> u8 {
    ffi_boundary!("gls_is_enabled", 0 => {
        let s = surface::require_current()?;
        if cap == GL_3DVISION_STEREO_NV {
            return Ok(s.nv3dvision().enabled() as u8);
        }
        // SAFETY: the surface's application context is current on this thread.
        Ok(unsafe { s.gl().IsEnabled(cap) })
    })
}

/// The value of a pname the library answers itself: the 3D Vision state,
/// then the emulated default framebuffer's (GL_STEREO, GL_DRAW_BUFFER, …).
fn emulated_value(s: &Arc<Surface>, pname: u32) -> crate::error::Result<Option<StateValue>> {
    if let Some(v) = s.with_nv3dvision(|nv| Ok(nv.query(pname)))? {
        return Ok(Some(v));
    }
    Ok(s.emulated_integer(pname)?
        .map(|v| StateValue::Enum(v as u32)))
}

/// glGetFloatv for the current surface: the 3D Vision state
/// (GL_STEREO_SEPARATION_NV, GL_STEREO_CONVERGENCE_NV, GL_STEREO_CUTOFF_NV
/// as set; GL_STEREO_PROJECTION_NV and GL_3DVISION_STEREO_NV converted as GL
/// converts them) and the emulated default framebuffer's values (as
/// gls_get_integerv()); every other pname goes to glGetFloatv.
///
/// @param pname a GL state name. @param data receives the value(s); must not
/// be NULL and must hold as many values as glGetFloatv writes for pname.
/// @return GLS_OK, GLS_ERROR_NO_CURRENT_SURFACE or GLS_ERROR_NULL_POINTER.
/// Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_get_floatv(pname: u32, data: *mut f32) -> gls_result {
    ffi_boundary!("gls_get_floatv", {
        let s = surface::require_current()?;
        let out = arg_out(data, "data")?;
        match emulated_value(&s, pname)? {
            // SAFETY: checked non-NULL.
            Some(v) => unsafe { write_out(out, v.as_float()) },
            // SAFETY: the surface's context is current; `data` is as large as GL needs (contract).
            None => unsafe { s.gl().GetFloatv(pname, out) },
        }
        Ok(())
    })
}

/// glGetBooleanv for the current surface: as gls_get_floatv(), each value
/// converted to 0 (zero) or 1 (anything else), as GL converts them.
///
/// @return as gls_get_floatv(). Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_get_booleanv(pname: u32, data: *mut u8) -> gls_result {
    ffi_boundary!("gls_get_booleanv", {
        let s = surface::require_current()?;
        let out = arg_out(data, "data")?;
        match emulated_value(&s, pname)? {
            // SAFETY: checked non-NULL.
            Some(v) => unsafe { write_out(out, v.as_boolean() as u8) },
            // SAFETY: the surface's context is current; `data` is as large as GL needs (contract).
            None => unsafe { s.gl().GetBooleanv(pname, out) },
        }
        Ok(())
    })
}

/// Renders one mono frame with automatic stereo.
///
/// On an auto-stereo capable current surface with GL_3DVISION_STEREO_NV
/// enabled, `draw` is called twice: for the left eye, then the right. Before
/// each call the library restores the matrix mode and modelview matrix found
/// at this call, loads the eye's projection (the projection current at this
/// call with x_clip' = x_clip + eye·s·(w_clip − C), eye = −1 left, +1 right;
/// for GL_STEREO_PROJECTION_ORTHO_NV the window depth replaces w_clip) and
/// selects that eye's buffers of the kinds selected now (GL_BACK →
/// GL_BACK_LEFT, then GL_BACK_RIGHT). Afterwards it restores this
/// projection and these draw buffers exactly.
///
/// `draw` must draw the whole mono frame, clear included (the depth buffer
/// is shared by both eyes), and must not change the projection matrix, the
/// draw buffers or the current surface; doing so is reported as
/// GLS_ERROR_INVALID_OPERATION (the right eye is then not drawn). It may
/// change the modelview and any other state; the second call starts from the
/// same modelview as the first.
///
/// On a surface that is not auto-stereo capable, or with 3D Vision disabled,
/// `draw` is called once and nothing else happens, so rendering is exactly
/// mono. Reading back: glReadPixels of GL_BACK/GL_FRONT, and
/// gls_surface_read_pixels() of GL_BACK, GL_FRONT or GL_LEFT, read the left
/// eye (the extension's rule for calls that expect one surface).
///
/// @param draw the frame; must not be NULL. @param user_data passed to draw.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_NO_CURRENT_SURFACE;
/// GLS_ERROR_INVALID_OPERATION (a framebuffer object of the program bound
/// for drawing, a callback that broke the contract above, or a call from
/// inside draw); GLS_ERROR_INVALID_VALUE (a projection matrix that is not
/// finite). Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_auto_stereo_frame(
    draw: gls_draw_fn,
    user_data: *mut c_void,
) -> gls_result {
    ffi_boundary!("gls_auto_stereo_frame", {
        let draw = draw.ok_or(Error::NullPointer("draw"))?;
        let s = surface::require_current()?;
        // SAFETY: the caller's function with the caller's pointer (contract).
        auto::render_frame(&s, &mut || unsafe { draw(user_data) })
    })
}

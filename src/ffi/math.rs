//! Projection and parallax math through the C ABI. None of these calls need
//! a GL context; all are thread-safe.

use glam::{DMat4, DVec3};

use super::boundary::{arg_out, arg_ref, ffi_boundary, write_out};
use super::types::*;
use crate::math::Eye;
use crate::math::parallax::{hp_fit_budget, hp_parallax_percent, parallax};
use crate::math::points::{PointEquation, project_point};
use crate::math::{EyeProjection, Frustum, StereoAdjust, adjust, camera, hp_eye, seeds};

/// Seed 000 Eq 1, mono: x' = x·d/(d−z).
pub const GLS_EQUATION_MONO: u32 = 1;
/// Seed 000 Eq 2, left camera: x' = (x + c/2)·d/(d−z).
pub const GLS_EQUATION_LEFT_CAMERA: u32 = 2;
/// Seed 000 Eq 3, right camera: x' = (x − c/2)·d/(d−z).
pub const GLS_EQUATION_RIGHT_CAMERA: u32 = 3;
/// Seed 000 Eq 4, left camera shifted to zero parallax at z = 0: x' = (x + c/2)·d/(d−z) − c/2.
pub const GLS_EQUATION_LEFT_ZERO_PARALLAX: u32 = 4;
/// Seed 000 Eq 5, right camera shifted to zero parallax at z = 0: x' = (x − c/2)·d/(d−z) + c/2.
pub const GLS_EQUATION_RIGHT_ZERO_PARALLAX: u32 = 5;

/// The comfort budget of seed 000 §7, in percent of viewport width, each side.
pub const GLS_PARALLAX_BUDGET_DEFAULT: f64 = 3.0;
/// Default of both user adjustments (strength and balance).
pub const GLS_ADJUSTMENT_DEFAULT: f64 = 1.0;
/// Upper limit of the user adjustments kept by gls_adjust_step().
pub const GLS_ADJUSTMENT_MAX: f64 = 2.0;

impl From<&gls_frustum> for Frustum {
    fn from(f: &gls_frustum) -> Frustum {
        Frustum {
            left: f.left,
            right: f.right,
            bottom: f.bottom,
            top: f.top,
            near: f.near_clip,
            far: f.far_clip,
        }
    }
}

impl From<&Frustum> for gls_frustum {
    fn from(f: &Frustum) -> gls_frustum {
        gls_frustum {
            left: f.left,
            right: f.right,
            bottom: f.bottom,
            top: f.top,
            near_clip: f.near,
            far_clip: f.far,
        }
    }
}

impl From<&gls_stereo_adjust> for StereoAdjust {
    fn from(a: &gls_stereo_adjust) -> StereoAdjust {
        StereoAdjust {
            zero_parallax_distance: a.zero_parallax_distance,
            offset_adjustment: a.offset_adjustment,
            balance_adjustment: a.balance_adjustment,
        }
    }
}

/// Writes an eye projection to the two C outputs (checked non-NULL before).
///
/// # Safety
/// Both pointers valid for writes.
unsafe fn write_eye(p: &EyeProjection, frustum_out: *mut gls_frustum, offset_out: *mut f64) {
    // SAFETY: checked non-NULL by arg_out; validity is the caller's contract.
    unsafe {
        write_out(frustum_out, gls_frustum::from(&p.frustum));
        write_out(offset_out, p.camera_offset);
    }
}

fn write_matrix(out: *mut f64, m: &DMat4) {
    // SAFETY: `out` was checked non-NULL and the contract says 16 doubles.
    unsafe { std::ptr::copy_nonoverlapping(m.to_cols_array().as_ptr(), out, 16) };
}

/// One eye's frustum and camera offset by HP's method (seed 000 §6–7).
///
/// Xrange = (right − left) × zero_parallax_distance / near_clip;
/// camera offset = Xrange × 0.035 × offset_adjustment, negative for the left
/// eye; asymmetry = −offset × balance_adjustment × near_clip /
/// zero_parallax_distance, added to the frustum's left and right. Draw the eye
/// with `glFrustum(eye frustum)` then `glTranslated(-camera_offset, 0, 0)`.
///
/// @param mono the program's symmetric (or any) frustum; must not be NULL.
/// @param adj the stereo settings; must not be NULL.
/// @param eye GLS_EYE_LEFT or GLS_EYE_RIGHT.
/// @param eye_frustum_out receives the eye's frustum; must not be NULL.
/// @param camera_offset_out receives the camera offset; must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_ENUM for a bad
/// eye; GLS_ERROR_INVALID_VALUE (message names the parameter) for near_clip
/// <= 0, far_clip <= near_clip, left == right, bottom == top,
/// zero_parallax_distance <= 0, a negative adjustment, NaN/infinity, or
/// values so extreme that the eye's frustum, offset or matrix would not be
/// finite (every eye returned works with gls_frustum_matrix()).
/// Outputs are written only on GLS_OK. Thread-safe; no GL context needed.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_stereo_eye(
    mono: *const gls_frustum,
    adj: *const gls_stereo_adjust,
    eye: u32,
    eye_frustum_out: *mut gls_frustum,
    camera_offset_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_stereo_eye", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let (mono, adj) = unsafe { (arg_ref(mono, "mono")?, arg_ref(adj, "adj")?) };
        let frustum_out = arg_out(eye_frustum_out, "eye_frustum_out")?;
        let offset_out = arg_out(camera_offset_out, "camera_offset_out")?;
        let p = hp_eye(&mono.into(), &adj.into(), Eye::try_from(eye)?)?;
        // SAFETY: both outputs checked non-NULL above.
        unsafe { write_eye(&p, frustum_out, offset_out) };
        Ok(())
    })
}

/// One eye's projection matrix by HP's method: glFrustum(eye frustum) ×
/// glTranslated(−camera_offset, 0, 0), column-major, ready for glLoadMatrixd.
///
/// @param mono must not be NULL. @param adj must not be NULL.
/// @param eye GLS_EYE_LEFT or GLS_EYE_RIGHT.
/// @param column_major_out receives 16 doubles; must not be NULL.
/// @return as gls_stereo_eye(). Thread-safe; no GL context needed.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_stereo_eye_matrix(
    mono: *const gls_frustum,
    adj: *const gls_stereo_adjust,
    eye: u32,
    column_major_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_stereo_eye_matrix", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let (mono, adj) = unsafe { (arg_ref(mono, "mono")?, arg_ref(adj, "adj")?) };
        let out = arg_out(column_major_out, "column_major_out")?;
        let p = hp_eye(&mono.into(), &adj.into(), Eye::try_from(eye)?)?;
        write_matrix(out, &p.matrix());
        Ok(())
    })
}

/// The matrix of any eye frustum and camera offset: glFrustum(frustum) ×
/// glTranslated(−camera_offset, 0, 0), column-major. Use it with the outputs
/// of gls_stereo_eye(), gls_sgi_eye(), gls_bourke_eye() or gls_stereo_camera_eye().
///
/// @param frustum must not be NULL and must be valid as for glFrustum.
/// @param camera_offset finite; with the frustum, its matrix must be finite.
/// @param column_major_out receives 16 doubles; must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_VALUE. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_frustum_matrix(
    frustum: *const gls_frustum,
    camera_offset: f64,
    column_major_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_frustum_matrix", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let f = unsafe { arg_ref(frustum, "frustum")? };
        let out = arg_out(column_major_out, "column_major_out")?;
        let p = EyeProjection {
            frustum: Frustum::from(f),
            camera_offset,
        }
        .validated()?;
        write_matrix(out, &p.matrix());
        Ok(())
    })
}

/// Parallax on the convergence plane (seed 003): p = D × (1 − C / w).
/// 0 at w = C, approaching D as w grows, −D at w = C/2.
///
/// @param eye_separation D, finite. @param convergence C, finite.
/// @param depth w, finite and > 0.
/// @return the parallax in scene units; NaN for invalid input (with a message
/// for gls_last_error_message()). Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_parallax(eye_separation: f64, convergence: f64, depth: f64) -> f64 {
    ffi_boundary!("gls_parallax", f64::NAN => { parallax(eye_separation, convergence, depth) })
}

/// Projects a point by one of Equations 1–5 of seed 000 §5: camera on the +z
/// axis at (0, 0, camera_distance), projection plane z = 0, camera separation
/// `separation`. Camera distance 9, point (8, −5, −3), separation 1 gives
/// (6, −3.75), (6.375, −3.75), (5.625, −3.75), (5.875, −3.75), (6.125, −3.75).
///
/// @param camera_distance d > 0. @param separation c >= 0.
/// @param point 3 doubles (x, y, z) with z < d; must not be NULL.
/// @param equation GLS_EQUATION_MONO … GLS_EQUATION_RIGHT_ZERO_PARALLAX.
/// @param xy_out receives 2 doubles; must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER, GLS_ERROR_INVALID_ENUM (equation)
/// or GLS_ERROR_INVALID_VALUE. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_project_point(
    camera_distance: f64,
    separation: f64,
    point: *const f64,
    equation: u32,
    xy_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_project_point", {
        let point = point as *const [f64; 3];
        // SAFETY: NULL-checked; the contract says 3 doubles.
        let p = unsafe { arg_ref(point, "point")? };
        let out = arg_out(xy_out, "xy_out")?;
        let eq = PointEquation::try_from(equation)?;
        let xy = project_point(camera_distance, separation, DVec3::from_array(*p), eq)?;
        // SAFETY: checked non-NULL; the contract says 2 doubles.
        unsafe { std::ptr::copy_nonoverlapping([xy.x, xy.y].as_ptr(), out, 2) };
        Ok(())
    })
}

/// The on-screen parallax, in percent of viewport width, of a point at
/// distance `depth` from the camera under HP's method: positive behind the
/// zero-parallax plane, negative in front. With default adjustments it
/// approaches 7% far away; seed 000 §7 advises staying within ±3%.
///
/// @param mono must not be NULL. @param adj must not be NULL. @param depth > 0.
/// @param percent_out must not be NULL.
/// @return as gls_stereo_eye(). Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_stereo_parallax_percent(
    mono: *const gls_frustum,
    adj: *const gls_stereo_adjust,
    depth: f64,
    percent_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_stereo_parallax_percent", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let (mono, adj) = unsafe { (arg_ref(mono, "mono")?, arg_ref(adj, "adj")?) };
        let out = arg_out(percent_out, "percent_out")?;
        let p = hp_parallax_percent(&mono.into(), &adj.into(), depth)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, p) };
        Ok(())
    })
}

/// The largest stereo that keeps every depth in nearest…farthest within
/// ±budget_percent of viewport width, under HP's method with `adj`'s
/// zero-parallax distance and balance (its offset_adjustment is what is
/// solved for and is ignored).
///
/// @param mono must not be NULL. @param adj must not be NULL.
/// @param nearest, farthest depths, 0 < nearest <= farthest.
/// @param budget_percent > 0; GLS_PARALLAX_BUDGET_DEFAULT is seed 000's 3%.
/// @param separation_out receives the full camera separation; must not be NULL.
/// @param offset_adjustment_out receives the equivalent offset_adjustment; must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_VALUE (also
/// when the whole range is at zero parallax, where any separation fits).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_stereo_fit_budget(
    mono: *const gls_frustum,
    adj: *const gls_stereo_adjust,
    nearest: f64,
    farthest: f64,
    budget_percent: f64,
    separation_out: *mut f64,
    offset_adjustment_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_stereo_fit_budget", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let (mono, adj) = unsafe { (arg_ref(mono, "mono")?, arg_ref(adj, "adj")?) };
        let sep_out = arg_out(separation_out, "separation_out")?;
        let adj_out = arg_out(offset_adjustment_out, "offset_adjustment_out")?;
        let fit = hp_fit_budget(&mono.into(), &adj.into(), nearest, farthest, budget_percent)?;
        // SAFETY: checked non-NULL.
        unsafe {
            write_out(sep_out, fit.separation);
            write_out(adj_out, fit.offset_adjustment);
        }
        Ok(())
    })
}

/// One step of a user adjustment (strength or balance), as seed 000 §7
/// advises: value × 1.1^steps, clamped to 0…2. steps = +1 strengthens, −1
/// weakens. A value of exactly 0 stays 0.
///
/// @return the new value; NaN if `value` is not finite. Thread-safe.
#[unsafe(no_mangle)]
pub extern "C" fn gls_adjust_step(value: f64, steps: i32) -> f64 {
    ffi_boundary!("gls_adjust_step", f64::NAN => { adjust::adjust_step(value, steps) })
}

/// The view matrix of one eye for a camera of any orientation (roll
/// included): gluLookAt with the camera and its target moved by
/// camera_offset along the camera's right vector, which is perpendicular to
/// the view direction and the up vector. Equal to
/// glTranslated(−camera_offset, 0, 0) × gluLookAt(eye, center, up); use it
/// with the eye's frustum (not gls_stereo_eye_matrix, which already translates).
///
/// @param eye, center, up 3 doubles each; must not be NULL; up not parallel to center − eye.
/// @param camera_offset from gls_stereo_eye() (negative for the left eye).
/// @param column_major_out receives 16 doubles; must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_VALUE. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_stereo_look_at(
    eye: *const f64,
    center: *const f64,
    up: *const f64,
    camera_offset: f64,
    column_major_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_stereo_look_at", {
        // SAFETY: NULL-checked; the contract says 3 doubles each.
        let (e, c, u) = unsafe {
            (
                arg_ref(eye as *const [f64; 3], "eye")?,
                arg_ref(center as *const [f64; 3], "center")?,
                arg_ref(up as *const [f64; 3], "up")?,
            )
        };
        let out = arg_out(column_major_out, "column_major_out")?;
        let m = camera::eye_view(
            DVec3::from_array(*e),
            DVec3::from_array(*c),
            DVec3::from_array(*u),
            camera_offset,
        )?;
        write_matrix(out, &m);
        Ok(())
    })
}

/// One eye by SGI IRIS GL's method (seed 002 §7): window(−top·aspect ±
/// half_sep·near/distance, top·aspect ± half_sep·near/distance, −top, top,
/// near, far) then translate(±half_sep, 0, 0), upper signs for the left eye.
/// For STR_RECT, pass the display's aspect (screen width / height) and draw
/// into the 492-row viewport: the viewport squashes the eye by ≈ 0.48
/// (492/1024), which the display stretches back (seed 002 §7's "squashed
/// aspect"); passing 0.48 × the aspect as well would squash it twice.
///
/// @param top, aspect, distance > 0; half_sep >= 0; near/far as glFrustum.
/// @param eye GLS_EYE_LEFT or GLS_EYE_RIGHT.
/// @param eye_frustum_out, camera_offset_out must not be NULL.
/// @return as gls_stereo_eye(). Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_sgi_eye(
    top: f64,
    aspect: f64,
    half_sep: f64,
    near_clip: f64,
    far_clip: f64,
    distance: f64,
    eye: u32,
    eye_frustum_out: *mut gls_frustum,
    camera_offset_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_sgi_eye", {
        let f_out = arg_out(eye_frustum_out, "eye_frustum_out")?;
        let o_out = arg_out(camera_offset_out, "camera_offset_out")?;
        let p = seeds::sgi_window_eye(
            top,
            aspect,
            half_sep,
            near_clip,
            far_clip,
            distance,
            Eye::try_from(eye)?,
        )?;
        // SAFETY: both outputs checked non-NULL.
        unsafe { write_eye(&p, f_out, o_out) };
        Ok(())
    })
}

/// One eye by the Xinerama / Bourke method (seed 001): wd2 = near·tan(fov/2),
/// ndfl = near/focal_length, frustum (∓ratio·wd2 ± ½·eye_separation·ndfl …),
/// camera moved by ∓eye_separation/2. fov is vertical, in degrees, above 0
/// and below 180. Seed 001's
/// defaults: eye_separation 0.04, focal_length 1.
///
/// @return as gls_stereo_eye(). Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_bourke_eye(
    fov_degrees: f64,
    aspect: f64,
    near_clip: f64,
    far_clip: f64,
    eye_separation: f64,
    focal_length: f64,
    eye: u32,
    eye_frustum_out: *mut gls_frustum,
    camera_offset_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_bourke_eye", {
        let f_out = arg_out(eye_frustum_out, "eye_frustum_out")?;
        let o_out = arg_out(camera_offset_out, "camera_offset_out")?;
        let p = seeds::bourke_eye(
            fov_degrees,
            aspect,
            near_clip,
            far_clip,
            eye_separation,
            focal_length,
            Eye::try_from(eye)?,
        )?;
        // SAFETY: both outputs checked non-NULL.
        unsafe { write_eye(&p, f_out, o_out) };
        Ok(())
    })
}

/// One eye by the anaglyph tutorial's StereoCamera (seed 003):
/// a = aspect·tan(fov/2)·C, b = a − D/2, c = a + D/2; left eye frustum
/// (−b·near/C, c·near/C, …) with translate(+D/2); the right eye swaps b and c.
/// fov is vertical, in degrees, above 0 and below 180; D is typically C/30.
///
/// @return as gls_stereo_eye(). Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_stereo_camera_eye(
    convergence: f64,
    eye_separation: f64,
    aspect: f64,
    fov_degrees: f64,
    near_clip: f64,
    far_clip: f64,
    eye: u32,
    eye_frustum_out: *mut gls_frustum,
    camera_offset_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_stereo_camera_eye", {
        let f_out = arg_out(eye_frustum_out, "eye_frustum_out")?;
        let o_out = arg_out(camera_offset_out, "camera_offset_out")?;
        let p = seeds::stereo_camera_eye(
            convergence,
            eye_separation,
            aspect,
            fov_degrees,
            near_clip,
            far_clip,
            Eye::try_from(eye)?,
        )?;
        // SAFETY: both outputs checked non-NULL.
        unsafe { write_eye(&p, f_out, o_out) };
        Ok(())
    })
}

/// NVIDIA's clip-space stereo (seed 004): the projection that maps every
/// vertex to x_clip' = x_clip + eye·s·(w_clip − C), eye = −1 left, +1 right.
/// For a perspective projection P this is the parallel-axis camera with half
/// offset h = s·C / `P[0][0]` and zero parallax at depth C.
///
/// @param projection 16 doubles, column-major; must not be NULL.
/// @param separation s, finite. @param convergence C, finite.
/// @param eye GLS_EYE_LEFT or GLS_EYE_RIGHT.
/// @param column_major_out receives 16 doubles; must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER, GLS_ERROR_INVALID_ENUM or
/// GLS_ERROR_INVALID_VALUE. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_nv_stereo_matrix(
    projection: *const f64,
    separation: f64,
    convergence: f64,
    eye: u32,
    column_major_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_nv_stereo_matrix", {
        // SAFETY: NULL-checked; the contract says 16 doubles.
        let p = unsafe { arg_ref(projection as *const [f64; 16], "projection")? };
        let out = arg_out(column_major_out, "column_major_out")?;
        let m = seeds::nv_clip_shift(
            &DMat4::from_cols_array(p),
            separation,
            convergence,
            Eye::try_from(eye)?,
        )?;
        write_matrix(out, &m);
        Ok(())
    })
}

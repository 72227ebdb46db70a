//! Measured parallax and auto-convergence through the C ABI: what a
//! rendered frame's depth buffer says about its stereo.

use std::ffi::c_char;

use super::boundary::{arg_out, arg_ref, ffi_boundary, write_out};
use super::types::*;
use crate::analysis::{self, ParallaxReport, centre_of_interest, hp_measure_parallax};
use crate::math::{Frustum, StereoAdjust, positive};

/// The measured parallax is within the comfort budget on both sides.
pub const GLS_PARALLAX_WITHIN_BUDGET: u32 = 0;
/// The most negative parallax (in front of the screen) exceeds the budget.
pub const GLS_PARALLAX_WARN_NEGATIVE: u32 = 1;
/// The most positive parallax (behind the screen) exceeds the budget.
pub const GLS_PARALLAX_WARN_POSITIVE: u32 = 2;

/// The parallax a rendered frame spans, measured from its depth buffer by
/// gls_stereo_measure_parallax(). Parallax is right-eye x minus left-eye x
/// on the screen: negative in front of the screen, positive behind it;
/// seed 000 §7 advises keeping both within about 3% of the viewport width.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gls_parallax_report {
    /// The smallest parallax (the most negative when any is negative), in
    /// percent of the viewport width; it belongs to the nearest pixel.
    pub min_percent: f64,
    /// The largest parallax, in percent of the viewport width; it belongs
    /// to the farthest pixel.
    pub max_percent: f64,
    /// min_percent in pixels (percent / 100 × viewport width).
    pub min_pixels: f64,
    /// max_percent in pixels.
    pub max_pixels: f64,
    /// Eye-space distance (along the view axis) of the nearest pixel holding geometry.
    pub nearest_distance: f64,
    /// Eye-space distance of the farthest pixel holding geometry.
    pub farthest_distance: f64,
    /// The budget the warnings compare with, in percent each side.
    pub budget_percent: f64,
    /// How many pixels of the viewport hold geometry.
    pub covered_pixels: u64,
    /// GLS_PARALLAX_WITHIN_BUDGET, or GLS_PARALLAX_WARN_NEGATIVE and/or
    /// GLS_PARALLAX_WARN_POSITIVE (bits).
    pub warnings: u32,
}

impl From<&ParallaxReport> for gls_parallax_report {
    fn from(r: &ParallaxReport) -> gls_parallax_report {
        gls_parallax_report {
            min_percent: r.min_percent,
            max_percent: r.max_percent,
            min_pixels: r.min_pixels,
            max_pixels: r.max_pixels,
            nearest_distance: r.nearest,
            farthest_distance: r.farthest,
            budget_percent: r.budget_percent,
            covered_pixels: r.covered_pixels,
            warnings: if r.negative_exceeds() {
                GLS_PARALLAX_WARN_NEGATIVE
            } else {
                0
            } | if r.positive_exceeds() {
                GLS_PARALLAX_WARN_POSITIVE
            } else {
                0
            },
        }
    }
}

impl From<&gls_parallax_report> for ParallaxReport {
    fn from(r: &gls_parallax_report) -> ParallaxReport {
        ParallaxReport {
            min_percent: r.min_percent,
            max_percent: r.max_percent,
            min_pixels: r.min_pixels,
            max_pixels: r.max_pixels,
            nearest: r.nearest_distance,
            farthest: r.farthest_distance,
            budget_percent: r.budget_percent,
            covered_pixels: r.covered_pixels,
        }
    }
}

/// Measures the on-screen parallax of the frame being drawn on the current
/// surface: the most negative and most positive parallax of its geometry,
/// in percent of the viewport width and in pixels, with warnings when
/// either exceeds ±budget_percent.
///
/// Call it right after drawing an eye with gls_apply_stereo_eye(mono, adj,
/// eye) (or gls_stereo_eye_matrix()), before the next depth clear and
/// before the swap. It reads the depth buffer, which both eyes share:
/// pixels not at the glClearDepth value hold geometry; their window depths
/// are mapped back to eye-space distances through the frustum's near and
/// far clip distances and the current glDepthRange, and the parallax of
/// the nearest and farthest of them is what HP's projection with `adj`
/// gives at those distances. One eye is enough: with parallel-axis stereo
/// a point's parallax depends only on its distance. To include what only
/// the other eye sees, measure after each eye and take the extremes.
/// Only the current viewport is examined.
///
/// @param mono the mono frustum the eyes were derived from; must not be NULL.
/// @param adj the stereo settings the eyes were drawn with; must not be NULL.
/// @param budget_percent > 0; GLS_PARALLAX_BUDGET_DEFAULT is seed 000's 3%.
/// @param report_out receives the report; must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_VALUE (as
/// gls_stereo_eye(), or budget_percent <= 0); GLS_ERROR_NO_CURRENT_SURFACE;
/// GLS_ERROR_INVALID_OPERATION when the surface has no depth buffer, no
/// pixel of the viewport holds geometry, or glDepthRange has equal near
/// and far. The report is written only on GLS_OK. Reads back the depth
/// buffer (and waits for the frame's rendering): cost grows with the
/// surface size. Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_stereo_measure_parallax(
    mono: *const gls_frustum,
    adj: *const gls_stereo_adjust,
    budget_percent: f64,
    report_out: *mut gls_parallax_report,
) -> gls_result {
    ffi_boundary!("gls_stereo_measure_parallax", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let (mono, adj) = unsafe { (arg_ref(mono, "mono")?, arg_ref(adj, "adj")?) };
        let out = arg_out(report_out, "report_out")?;
        let (mono, adj) = (
            Frustum::from(mono).validated()?,
            StereoAdjust::from(adj).validated()?,
        );
        positive("budget_percent", budget_percent)?;
        let capture = analysis::capture_current()?;
        let report = hp_measure_parallax(&capture, &mono, &adj, budget_percent)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, gls_parallax_report::from(&report)) };
        Ok(())
    })
}

/// Auto-convergence: the distance of the centre of interest of the frame
/// being drawn on the current surface, to use as
/// gls_stereo_adjust.zero_parallax_distance so that the subject sits at
/// the screen surface (seed 000 §10: put the plane of zero parallax near
/// the centre of interest).
///
/// The centre of interest is the median eye-space distance of the pixels
/// holding geometry in the middle half of the viewport's width and height
/// (a quarter of its area, where a program frames its subject), or of the
/// whole viewport when that window holds no geometry. The median is a
/// distance the scene really has there and ignores a minority of other
/// pixels (a far background, a near object crossing the view). Call it
/// when gls_stereo_measure_parallax() may be called; apply the result to
/// the next frame (HP's offset scales with the distance, so the strength
/// follows).
///
/// @param mono the mono frustum the frame was drawn with (its near and far
/// clip distances map depth back to distance); must not be NULL.
/// @param distance_out receives the distance; must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_VALUE (a bad
/// frustum); GLS_ERROR_NO_CURRENT_SURFACE; GLS_ERROR_INVALID_OPERATION as
/// gls_stereo_measure_parallax(). Written only on GLS_OK. Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_stereo_auto_converge(
    mono: *const gls_frustum,
    distance_out: *mut f64,
) -> gls_result {
    ffi_boundary!("gls_stereo_auto_converge", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let mono = Frustum::from(unsafe { arg_ref(mono, "mono")? }).validated()?;
        let out = arg_out(distance_out, "distance_out")?;
        let capture = analysis::capture_current()?;
        let c = centre_of_interest(&capture, &mono)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, c.distance) };
        Ok(())
    })
}

/// Describes a parallax report in one line of UTF-8 for people, e.g.
/// "parallax -2.12% to +1.17% of viewport width (-13.6 to +7.5 px),
/// distance 8.032 to 12.443: within the 3% budget", or with "; WARNING:
/// … exceeds the 3% budget (…what to change…)" for each side beyond it.
///
/// Works like snprintf: writes at most len − 1 bytes and a NUL (cut at a
/// character boundary), and reports the full length.
///
/// @param report must not be NULL.
/// @param buf receives the text; may be NULL only when len is 0.
/// @param len size of buf in bytes.
/// @param length_out receives the length of the whole text without the
/// NUL (to size buf); may be NULL.
/// @return GLS_OK or GLS_ERROR_NULL_POINTER. Thread-safe; no GL context needed.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_parallax_report_describe(
    report: *const gls_parallax_report,
    buf: *mut c_char,
    len: usize,
    length_out: *mut usize,
) -> gls_result {
    ffi_boundary!("gls_parallax_report_describe", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let r = unsafe { arg_ref(report, "report")? };
        if len > 0 {
            arg_out(buf, "buf")?;
        }
        let text = ParallaxReport::from(r).describe();
        if len > 0 {
            let mut n = text.len().min(len - 1);
            while !text.is_char_boundary(n) {
                n -= 1;
            }
            // SAFETY: buf is non-NULL and holds len > n bytes (contract).
            unsafe {
                std::ptr::copy_nonoverlapping(text.as_ptr(), buf.cast::<u8>(), n);
                buf.add(n).write(0);
            }
        }
        if !length_out.is_null() {
            // SAFETY: non-NULL; valid for a write (contract).
            unsafe { write_out(length_out, text.len()) };
        }
        Ok(())
    })
}

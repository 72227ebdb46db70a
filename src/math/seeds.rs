//! The other seed formulations of the same stereo camera. Each is written the
//! way its document writes it; the tests prove they all give HP's matrices
//! for matched parameters.

use glam::{DMat4, DVec4};

use super::frustum::{EyeProjection, Frustum};
use super::{
    Eye, field_of_view, finite, finite_matrix, finite_matrix_param, non_negative, positive,
};
use crate::error::Result;

/// SGI IRIS GL (seed 002 §7): `window(−top·aspect ± half_sep·near/distance,
/// top·aspect ± half_sep·near/distance, −top, top, near, far)` then
/// `translate(±half_sep, 0, 0)`; the upper signs for the left eye.
pub fn sgi_window_eye(
    top: f64,
    aspect: f64,
    half_sep: f64,
    near: f64,
    far: f64,
    distance: f64,
    eye: Eye,
) -> Result<EyeProjection> {
    positive("top", top)?;
    positive("aspect", aspect)?;
    non_negative("half_sep", half_sep)?;
    positive("distance", distance)?;
    // Left eye: + shift of the window, translate(+half_sep) = camera at −half_sep.
    let shift = -eye.sign() * half_sep * near / distance;
    let frustum = Frustum {
        left: -top * aspect + shift,
        right: top * aspect + shift,
        bottom: -top,
        top,
        near,
        far,
    };
    EyeProjection {
        frustum,
        camera_offset: eye.sign() * half_sep,
    }
    .validated()
}

/// Xinerama / Bourke (seed 001): `wd2 = near·tan(fov/2)`, `ndfl = near/focal`;
/// the right eye is `glFrustum(−ratio·wd2 − ½·sep·ndfl, ratio·wd2 − ½·sep·ndfl,
/// −wd2, wd2, near, far)` with the camera moved right by sep/2; the left eye
/// mirrors it. `fov_degrees` is the vertical field of view.
pub fn bourke_eye(
    fov_degrees: f64,
    ratio: f64,
    near: f64,
    far: f64,
    eye_separation: f64,
    focal_length: f64,
    eye: Eye,
) -> Result<EyeProjection> {
    field_of_view("fov_degrees", fov_degrees)?;
    positive("ratio", ratio)?;
    positive("near", near)?;
    non_negative("eye_separation", eye_separation)?;
    positive("focal_length", focal_length)?;
    let wd2 = near * (fov_degrees.to_radians() / 2.0).tan();
    let ndfl = near / focal_length;
    let shift = -eye.sign() * 0.5 * eye_separation * ndfl;
    let frustum = Frustum {
        left: -ratio * wd2 + shift,
        right: ratio * wd2 + shift,
        bottom: -wd2,
        top: wd2,
        near,
        far,
    };
    EyeProjection {
        frustum,
        camera_offset: eye.sign() * eye_separation / 2.0,
    }
    .validated()
}

/// The anaglyph tutorial's StereoCamera (seed 003): `a = aspect·tan(fov/2)·C`,
/// `b = a − D/2`, `c = a + D/2`; left eye frustum left = −b·near/C,
/// right = c·near/C, then translate(+D/2); the right eye swaps b and c and
/// translates by −D/2. `fov_degrees` is the vertical field of view.
pub fn stereo_camera_eye(
    convergence: f64,
    eye_separation: f64,
    aspect: f64,
    fov_degrees: f64,
    near: f64,
    far: f64,
    eye: Eye,
) -> Result<EyeProjection> {
    positive("convergence", convergence)?;
    non_negative("eye_separation", eye_separation)?;
    positive("aspect", aspect)?;
    field_of_view("fov_degrees", fov_degrees)?;
    positive("near", near)?;
    let half = (fov_degrees.to_radians() / 2.0).tan();
    let top = near * half;
    let a = aspect * half * convergence;
    let b = a - eye_separation / 2.0;
    let c = a + eye_separation / 2.0;
    let (left, right) = match eye {
        Eye::Left => (-b * near / convergence, c * near / convergence),
        Eye::Right => (-c * near / convergence, b * near / convergence),
    };
    let frustum = Frustum {
        left,
        right,
        bottom: -top,
        top,
        near,
        far,
    };
    EyeProjection {
        frustum,
        camera_offset: eye.sign() * eye_separation / 2.0,
    }
    .validated()
}

/// NVIDIA's clip-space form (seed 004, REFERENCE.md):
/// `x_clip' = x_clip + eye·s·(w_clip − C)`, with eye = −1 for the left eye.
///
/// Returns the projection matrix that does this to every vertex: row x of
/// `projection` plus `eye·s·(row w − C·e_w)`. For a perspective projection with
/// `P[0][0]` = 2n/(r−l), this is the parallel-axis stereo camera whose half
/// offset is `h = s·C / P[0][0]` and whose zero-parallax plane is at depth C.
pub fn nv_clip_shift(
    projection: &DMat4,
    separation: f64,
    convergence: f64,
    eye: Eye,
) -> Result<DMat4> {
    finite("separation", separation)?;
    finite("convergence", convergence)?;
    finite_matrix_param("projection", projection)?;
    let k = eye.sign() * separation;
    let row_w = projection.row(3) - DVec4::new(0.0, 0.0, 0.0, convergence);
    let row_x = projection.row(0) + k * row_w;
    let mut m = *projection;
    // Write row 0 back column by column (glam stores columns).
    m.x_axis.x = row_x.x;
    m.y_axis.x = row_x.y;
    m.z_axis.x = row_x.z;
    m.w_axis.x = row_x.w;
    finite_matrix("the stereo projection matrix", m)
}

/// The NVIDIA separation `s` that matches a camera half offset `h` for a
/// projection whose `P[0][0]` is `p00` at convergence `C`: `s = P00·h / C`.
pub fn nv_separation_for_offset(p00: f64, half_offset: f64, convergence: f64) -> f64 {
    p00 * half_offset / convergence
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::hp::{HP_OFFSET_FRACTION, StereoAdjust, hp_eye, xrange};
    use crate::math::testutil::assert_mat_close;

    /// One scene described five ways: vertical fov, aspect, near, far and the
    /// distance to the zero-parallax plane; HP's offset defines the separation.
    struct Scene {
        fovy: f64,
        aspect: f64,
        near: f64,
        far: f64,
        d: f64,
    }

    const SCENES: [Scene; 3] = [
        Scene {
            fovy: 45.0,
            aspect: 1.25,
            near: 1.0,
            far: 100.0,
            d: 9.0,
        },
        Scene {
            fovy: 60.0,
            aspect: 16.0 / 9.0,
            near: 0.1,
            far: 1000.0,
            d: 2.5,
        },
        Scene {
            fovy: 30.0,
            aspect: 0.48,
            near: 3.0,
            far: 40.0,
            d: 17.0,
        },
    ];

    #[test]
    fn all_five_formulations_give_the_same_matrices() {
        for s in &SCENES {
            let mono = Frustum::perspective(s.fovy, s.aspect, s.near, s.far).unwrap();
            let adj = StereoAdjust::new(s.d);
            let h = xrange(&mono, s.d) * HP_OFFSET_FRACTION; // half separation
            for eye in Eye::BOTH {
                let hp = hp_eye(&mono, &adj, eye).unwrap().matrix();

                let sgi = sgi_window_eye(mono.top, s.aspect, h, s.near, s.far, s.d, eye).unwrap();
                assert_mat_close(&sgi.matrix(), &hp, 1e-12, "SGI window()/translate()");

                let bourke =
                    bourke_eye(s.fovy, s.aspect, s.near, s.far, 2.0 * h, s.d, eye).unwrap();
                assert_mat_close(&bourke.matrix(), &hp, 1e-12, "Xinerama/Bourke");

                let cam =
                    stereo_camera_eye(s.d, 2.0 * h, s.aspect, s.fovy, s.near, s.far, eye).unwrap();
                assert_mat_close(&cam.matrix(), &hp, 1e-12, "anaglyph StereoCamera");

                let p = mono.matrix();
                let sep = nv_separation_for_offset(p.x_axis.x, h, s.d);
                let nv = nv_clip_shift(&p, sep, s.d, eye).unwrap();
                assert_mat_close(&nv, &hp, 1e-12, "NVIDIA clip-space shift");
            }
        }
    }

    #[test]
    fn nv_shift_with_zero_separation_is_the_mono_projection() {
        let p = Frustum::perspective(50.0, 1.0, 1.0, 10.0).unwrap().matrix();
        assert_eq!(nv_clip_shift(&p, 0.0, 5.0, Eye::Left).unwrap(), p);
    }

    #[test]
    fn formulations_reject_bad_parameters_by_name() {
        let e = sgi_window_eye(1.0, 1.0, 0.1, 1.0, 10.0, 0.0, Eye::Left).unwrap_err();
        assert!(e.to_string().contains("distance"), "{e}");
        let e = bourke_eye(45.0, 1.0, 1.0, 10.0, 0.04, -1.0, Eye::Left).unwrap_err();
        assert!(e.to_string().contains("focal_length"), "{e}");
        let e = stereo_camera_eye(5.0, 0.1, 1.0, 45.0, 1.0, 0.5, Eye::Right).unwrap_err();
        assert!(e.to_string().contains("far_clip"), "{e}");
        let e = nv_clip_shift(&DMat4::IDENTITY, f64::NAN, 1.0, Eye::Left).unwrap_err();
        assert!(e.to_string().contains("separation"), "{e}");
    }
}

//! View matrices for a stereo camera of any orientation: each eye is moved
//! along the camera's own right vector, perpendicular to the view direction
//! and to the up vector (seed 000 §6), so a rolled camera stays free of
//! vertical parallax.

use glam::{DMat4, DVec3};

use super::{finite, finite_matrix};
use crate::error::{Error, Result};

fn finite3(name: &str, v: DVec3) -> Result<DVec3> {
    finite(name, v.x)?;
    finite(name, v.y)?;
    finite(name, v.z)?;
    Ok(v)
}

/// gluLookAt(eye, center, up), checked: the view direction must be non-zero
/// and `up` must not be parallel to it.
pub fn look_at(eye: DVec3, center: DVec3, up: DVec3) -> Result<DMat4> {
    basis(eye, center, up)?;
    finite_matrix("the view matrix", DMat4::look_at_rh(eye, center, up))
}

/// The camera's (right, forward) unit vectors.
fn basis(eye: DVec3, center: DVec3, up: DVec3) -> Result<(DVec3, DVec3)> {
    finite3("eye", eye)?;
    finite3("center", center)?;
    finite3("up", up)?;
    let f = center - eye;
    if f.length_squared() == 0.0 {
        return Err(Error::invalid_value("eye and center must differ"));
    }
    let f = f.normalize();
    let s = f.cross(up);
    if s.length_squared() <= 1e-24 * up.length_squared().max(1e-300) {
        return Err(Error::invalid_value(
            "up must not be zero or parallel to the view direction",
        ));
    }
    Ok((s.normalize(), f))
}

/// The view matrix of one eye: the camera and its target both moved by
/// `camera_offset` along the camera's right vector (parallel axes, no toe-in).
/// Equal to `glTranslated(−camera_offset, 0, 0) × gluLookAt(eye, center, up)`.
pub fn eye_view(eye: DVec3, center: DVec3, up: DVec3, camera_offset: f64) -> Result<DMat4> {
    finite("camera_offset", camera_offset)?;
    let (right, _) = basis(eye, center, up)?;
    let shift = right * camera_offset;
    finite_matrix(
        "the eye's view matrix",
        DMat4::look_at_rh(eye + shift, center + shift, up),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::hp::{StereoAdjust, hp_eye};
    use crate::math::testutil::assert_mat_close;
    use crate::math::{Eye, Frustum};
    use glam::DVec4;

    fn window(m: DMat4, p: DVec3) -> (f64, f64) {
        let c = m * DVec4::new(p.x, p.y, p.z, 1.0);
        (c.x / c.w, c.y / c.w)
    }

    #[test]
    fn eye_view_equals_translate_after_look_at() {
        let (e, c, u) = (
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(-2.0, 0.5, -4.0),
            DVec3::new(0.3, 1.0, 0.2),
        );
        let a = eye_view(e, c, u, -0.37).unwrap();
        let b = DMat4::from_translation(DVec3::new(0.37, 0.0, 0.0)) * DMat4::look_at_rh(e, c, u);
        assert_mat_close(&a, &b, 1e-12, "eye view");
    }

    #[test]
    fn a_rolled_camera_has_no_vertical_parallax() {
        let mono = Frustum::perspective(50.0, 1.0, 0.5, 50.0).unwrap();
        let adj = StereoAdjust::new(8.0);
        let eye = DVec3::new(3.0, -1.0, 7.0);
        let center = DVec3::new(0.0, 0.0, 0.0);
        // Roll the camera 35 degrees about its view direction.
        let f = (center - eye).normalize();
        let up = glam::DQuat::from_axis_angle(f, 35f64.to_radians()) * DVec3::Y;
        let pts = [
            DVec3::new(1.0, 2.0, -3.0),
            DVec3::new(-2.0, 0.5, 1.0),
            DVec3::new(0.3, -1.2, 2.5),
        ];
        let mut saw_horizontal = false;
        for p in pts {
            let [l, r] = Eye::BOTH.map(|e| {
                let proj = hp_eye(&mono, &adj, e).unwrap();
                // The offset is applied in the view, so use the frustum alone.
                proj.frustum.matrix() * eye_view(eye, center, up, proj.camera_offset).unwrap()
            });
            let (pl, pr) = (window(l, p), window(r, p));
            assert!(
                (pl.1 - pr.1).abs() < 1e-12,
                "vertical parallax {} at {p}",
                pl.1 - pr.1
            );
            saw_horizontal |= (pl.0 - pr.0).abs() > 1e-3;
        }
        assert!(saw_horizontal, "the eyes must still differ horizontally");
    }

    #[test]
    fn toe_in_would_show_vertical_parallax() {
        // The contrast case: cameras rotated to converge on the centre.
        let mono = Frustum::perspective(50.0, 1.0, 0.5, 50.0).unwrap();
        let p = DVec3::new(2.0, 2.0, -2.0);
        let center = DVec3::ZERO;
        let [l, r] = [-0.5, 0.5]
            .map(|x| mono.matrix() * DMat4::look_at_rh(DVec3::new(x, 0.0, 8.0), center, DVec3::Y));
        assert!((window(l, p).1 - window(r, p).1).abs() > 1e-4);
    }

    #[test]
    fn degenerate_cameras_are_rejected() {
        assert!(eye_view(DVec3::ZERO, DVec3::ZERO, DVec3::Y, 0.1).is_err());
        assert!(eye_view(DVec3::ZERO, DVec3::Y, DVec3::Y, 0.1).is_err());
        assert!(look_at(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y).is_ok());
    }
}

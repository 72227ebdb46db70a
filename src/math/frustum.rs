//! Frusta as glFrustum takes them, and an eye's projection.

use glam::{DMat4, DVec4};

use super::{field_of_view, finite, finite_matrix, positive};
use crate::error::{Error, Result};

/// The six arguments of glFrustum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    /// Left edge of the view window at the near plane.
    pub left: f64,
    /// Right edge of the view window at the near plane.
    pub right: f64,
    /// Bottom edge of the view window at the near plane.
    pub bottom: f64,
    /// Top edge of the view window at the near plane.
    pub top: f64,
    /// Near clipping distance (> 0).
    pub near: f64,
    /// Far clipping distance (> near).
    pub far: f64,
}

impl Frustum {
    /// A symmetric frustum like gluPerspective(fovy, aspect, near, far).
    pub fn perspective(fovy_degrees: f64, aspect: f64, near: f64, far: f64) -> Result<Frustum> {
        let fovy = field_of_view("fovy", fovy_degrees)?;
        positive("aspect", aspect)?;
        let top = near * (fovy.to_radians() / 2.0).tan();
        let right = top * aspect;
        Frustum {
            left: -right,
            right,
            bottom: -top,
            top,
            near,
            far,
        }
        .validated()
    }

    /// Checks the rules of glFrustum plus finiteness: every value finite,
    /// near > 0, far > near, left != right, bottom != top.
    pub fn validated(self) -> Result<Frustum> {
        finite("frustum left", self.left)?;
        finite("frustum right", self.right)?;
        finite("frustum bottom", self.bottom)?;
        finite("frustum top", self.top)?;
        positive("frustum near_clip", self.near)?;
        finite("frustum far_clip", self.far)?;
        if self.far <= self.near {
            return Err(Error::invalid_value(format!(
                "frustum far_clip must be > near_clip, got far_clip {} and near_clip {}",
                self.far, self.near
            )));
        }
        if self.left == self.right {
            return Err(Error::invalid_value(format!(
                "frustum left and right must differ, both are {}",
                self.left
            )));
        }
        if self.bottom == self.top {
            return Err(Error::invalid_value(format!(
                "frustum bottom and top must differ, both are {}",
                self.top
            )));
        }
        finite_matrix("the frustum's projection matrix", self.matrix())?;
        Ok(self)
    }

    /// Width of the view window at the near plane.
    pub fn width(&self) -> f64 {
        self.right - self.left
    }

    /// The same frustum with left and right moved by `dx` (frustum asymmetry).
    pub fn shifted(&self, dx: f64) -> Frustum {
        Frustum {
            left: self.left + dx,
            right: self.right + dx,
            ..*self
        }
    }

    /// The matrix glFrustum multiplies onto the current matrix (column-major).
    pub fn matrix(&self) -> DMat4 {
        let Frustum {
            left: l,
            right: r,
            bottom: b,
            top: t,
            near: n,
            far: f,
        } = *self;
        DMat4::from_cols(
            DVec4::new(2.0 * n / (r - l), 0.0, 0.0, 0.0),
            DVec4::new(0.0, 2.0 * n / (t - b), 0.0, 0.0),
            DVec4::new(
                (r + l) / (r - l),
                (t + b) / (t - b),
                -(f + n) / (f - n),
                -1.0,
            ),
            DVec4::new(0.0, 0.0, -2.0 * f * n / (f - n), 0.0),
        )
    }
}

/// One eye's projection: its (asymmetric) frustum and its camera offset.
///
/// The camera offset is the eye's lateral position relative to the mono
/// camera, negative for the left eye. The scene is moved the other way:
/// the full projection is `glFrustum(frustum) * glTranslated(-camera_offset, 0, 0)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EyeProjection {
    /// The eye's frustum.
    pub frustum: Frustum,
    /// The eye's camera offset along the camera's x axis (negative = left).
    pub camera_offset: f64,
}

impl EyeProjection {
    /// Checks the frustum ([`Frustum::validated`]), that the camera offset is
    /// finite, and that the eye's whole matrix is: every eye the library
    /// hands out passes this.
    pub fn validated(self) -> Result<EyeProjection> {
        self.frustum.validated()?;
        finite("camera_offset", self.camera_offset)?;
        finite_matrix("the eye's projection matrix", self.matrix())?;
        Ok(self)
    }

    /// glFrustum(frustum) × glTranslated(−camera_offset, 0, 0), column-major.
    pub fn matrix(&self) -> DMat4 {
        self.frustum.matrix()
            * DMat4::from_translation(glam::DVec3::new(-self.camera_offset, 0.0, 0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frustum_matrix_maps_the_near_window_corners_to_ndc_corners() {
        let f = Frustum {
            left: -2.0,
            right: 1.0,
            bottom: -0.5,
            top: 1.5,
            near: 1.0,
            far: 10.0,
        };
        let m = f.matrix();
        let ndc = |x: f64, y: f64, z: f64| {
            let c = m * DVec4::new(x, y, z, 1.0);
            (c.x / c.w, c.y / c.w, c.z / c.w)
        };
        assert_eq!(ndc(-2.0, -0.5, -1.0), (-1.0, -1.0, -1.0));
        let (x, y, z) = ndc(1.0 * 10.0, 1.5 * 10.0, -10.0);
        assert!((x - 1.0).abs() < 1e-12 && (y - 1.0).abs() < 1e-12 && (z - 1.0).abs() < 1e-12);
    }

    #[test]
    fn invalid_frusta_name_the_parameter() {
        let good = Frustum {
            left: -1.0,
            right: 1.0,
            bottom: -1.0,
            top: 1.0,
            near: 1.0,
            far: 2.0,
        };
        let cases = [
            (Frustum { near: 0.0, ..good }, "near_clip"),
            (Frustum { near: -1.0, ..good }, "near_clip"),
            (Frustum { far: 1.0, ..good }, "far_clip"),
            (
                Frustum {
                    left: f64::NAN,
                    ..good
                },
                "left",
            ),
            (
                Frustum {
                    top: f64::INFINITY,
                    ..good
                },
                "top",
            ),
            (
                Frustum {
                    right: -1.0,
                    ..good
                },
                "left and right",
            ),
            (
                Frustum {
                    bottom: 1.0,
                    ..good
                },
                "bottom and top",
            ),
        ];
        for (f, name) in cases {
            match f.validated() {
                Err(Error::InvalidValue(msg)) => {
                    assert!(msg.contains(name), "message {msg:?} should name {name:?}")
                }
                other => panic!("{f:?} gave {other:?}, wanted InvalidValue naming {name}"),
            }
        }
        assert!(good.validated().is_ok());
    }
}

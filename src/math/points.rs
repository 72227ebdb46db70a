//! Equations 1–5 of seed 000 §5: where a point lands on the projection plane
//! z = 0 for a camera on the +z axis at (0, 0, d), with camera separation c.

use glam::{DVec2, DVec3};

use super::{finite, finite_result, non_negative, positive};
use crate::error::{Error, Result};

/// Which of the seed's five equations to apply.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointEquation {
    /// Eq 1, mono: x' = x·d/(d−z).
    Mono = 1,
    /// Eq 2, left camera: x' = (x + c/2)·d/(d−z).
    LeftCamera = 2,
    /// Eq 3, right camera: x' = (x − c/2)·d/(d−z).
    RightCamera = 3,
    /// Eq 4, left camera shifted to zero parallax at z = 0: x' = (x + c/2)·d/(d−z) − c/2.
    LeftZeroParallax = 4,
    /// Eq 5, right camera shifted to zero parallax at z = 0: x' = (x − c/2)·d/(d−z) + c/2.
    RightZeroParallax = 5,
}

impl TryFrom<u32> for PointEquation {
    type Error = Error;
    fn try_from(v: u32) -> Result<Self> {
        Ok(match v {
            1 => Self::Mono,
            2 => Self::LeftCamera,
            3 => Self::RightCamera,
            4 => Self::LeftZeroParallax,
            5 => Self::RightZeroParallax,
            _ => {
                return Err(Error::invalid_enum(
                    "equation",
                    v,
                    "use GLS_EQUATION_MONO (1) … GLS_EQUATION_RIGHT_ZERO_PARALLAX (5)",
                ));
            }
        })
    }
}

/// Projects `p` by one of the seed's equations. y' = y·d/(d−z) in all five.
pub fn project_point(
    camera_distance: f64,
    separation: f64,
    p: DVec3,
    eq: PointEquation,
) -> Result<DVec2> {
    let d = positive("camera_distance", camera_distance)?;
    let c = non_negative("separation", separation)?;
    finite("point x", p.x)?;
    finite("point y", p.y)?;
    finite("point z", p.z)?;
    if p.z >= d {
        return Err(Error::invalid_value(format!(
            "point z ({}) must be in front of the camera (less than camera_distance {d})",
            p.z
        )));
    }
    let k = d / (d - p.z);
    let half = c / 2.0;
    let x = match eq {
        PointEquation::Mono => p.x * k,
        PointEquation::LeftCamera => (p.x + half) * k,
        PointEquation::RightCamera => (p.x - half) * k,
        PointEquation::LeftZeroParallax => (p.x + half) * k - half,
        PointEquation::RightZeroParallax => (p.x - half) * k + half,
    };
    Ok(DVec2::new(
        finite_result("the projected x", x)?,
        finite_result("the projected y", p.y * k)?,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_worked_example_comes_out_exactly() {
        let p = DVec3::new(8.0, -5.0, -3.0);
        let want = [
            (PointEquation::Mono, 6.0),
            (PointEquation::LeftCamera, 6.375),
            (PointEquation::RightCamera, 5.625),
            (PointEquation::LeftZeroParallax, 5.875),
            (PointEquation::RightZeroParallax, 6.125),
        ];
        for (eq, x) in want {
            assert_eq!(
                project_point(9.0, 1.0, p, eq).unwrap(),
                DVec2::new(x, -3.75),
                "{eq:?}"
            );
        }
    }

    #[test]
    fn a_point_behind_the_plane_has_positive_parallax_and_in_front_negative() {
        let par = |z: f64| {
            let p = DVec3::new(1.0, 0.0, z);
            project_point(9.0, 1.0, p, PointEquation::RightZeroParallax)
                .unwrap()
                .x
                - project_point(9.0, 1.0, p, PointEquation::LeftZeroParallax)
                    .unwrap()
                    .x
        };
        assert!(par(-3.0) > 0.0);
        assert_eq!(par(0.0), 0.0);
        assert!(par(3.0) < 0.0);
    }

    #[test]
    fn points_at_or_behind_the_camera_are_rejected() {
        let e =
            project_point(9.0, 1.0, DVec3::new(0.0, 0.0, 9.0), PointEquation::Mono).unwrap_err();
        assert!(matches!(e, Error::InvalidValue(_)));
        assert!(PointEquation::try_from(6).is_err());
    }
}

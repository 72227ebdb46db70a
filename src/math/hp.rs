//! HP's stereo projection (seed 000 §6–7): camera offset from the scene's
//! horizontal range at the zero-parallax plane, and a frustum asymmetry that
//! puts that plane at zero parallax.

use super::frustum::{EyeProjection, Frustum};
use super::{Eye, non_negative, positive};
use crate::error::Result;

/// Fraction of the horizontal range at the zero-parallax plane by which each
/// camera is offset (seed 000 §7: `Xrange * 0.035 * UserOffsetAdjustment`).
pub const HP_OFFSET_FRACTION: f64 = 0.035;

/// The user's stereo settings (seed 000 §7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StereoAdjust {
    /// Distance from the camera to the zero-parallax plane (> 0).
    pub zero_parallax_distance: f64,
    /// Stereo strength (UserOffsetAdjustment). Default 1.0; 0 = no stereo.
    pub offset_adjustment: f64,
    /// Parallax balance (UserBalanceAdjustment). Default 1.0; 0 = all negative parallax.
    pub balance_adjustment: f64,
}

impl StereoAdjust {
    /// Default adjustments (1.0, 1.0) with the given zero-parallax distance.
    pub fn new(zero_parallax_distance: f64) -> StereoAdjust {
        StereoAdjust {
            zero_parallax_distance,
            offset_adjustment: 1.0,
            balance_adjustment: 1.0,
        }
    }

    /// Checks: zero_parallax_distance finite and > 0; adjustments finite and >= 0.
    ///
    /// Values above 2.0 (the seed's usual upper limit) are accepted here; the
    /// step helpers in [`super::adjust`] keep interactive changes within 0…2.
    pub fn validated(self) -> Result<StereoAdjust> {
        positive("zero_parallax_distance", self.zero_parallax_distance)?;
        non_negative("offset_adjustment", self.offset_adjustment)?;
        non_negative("balance_adjustment", self.balance_adjustment)?;
        Ok(self)
    }
}

/// Horizontal range of the scene at the zero-parallax plane:
/// `(right − left) × zero_parallax_distance / near`.
pub fn xrange(mono: &Frustum, zero_parallax_distance: f64) -> f64 {
    mono.width() * zero_parallax_distance / mono.near
}

/// One eye's projection by HP's method.
///
/// - camera offset = Xrange × 0.035 × offset_adjustment, negative for the left eye;
/// - asymmetry = −offset × balance_adjustment × near / zero_parallax_distance,
///   added to the frustum's left and right (positive for the left eye).
pub fn hp_eye(mono: &Frustum, adjust: &StereoAdjust, eye: Eye) -> Result<EyeProjection> {
    let mono = mono.validated()?;
    let adjust = adjust.validated()?;
    let d = adjust.zero_parallax_distance;
    let offset = eye.sign() * xrange(&mono, d) * HP_OFFSET_FRACTION * adjust.offset_adjustment;
    let asymmetry = -offset * adjust.balance_adjustment * mono.near / d;
    EyeProjection {
        frustum: mono.shifted(asymmetry),
        camera_offset: offset,
    }
    .validated()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    fn mono() -> Frustum {
        Frustum::perspective(40.0, 1.25, 1.0, 100.0).unwrap()
    }

    #[test]
    fn left_eye_has_positive_asymmetry_and_negative_offset() {
        let adj = StereoAdjust::new(10.0);
        let l = hp_eye(&mono(), &adj, Eye::Left).unwrap();
        let r = hp_eye(&mono(), &adj, Eye::Right).unwrap();
        let asym_l = l.frustum.left - mono().left;
        let asym_r = r.frustum.left - mono().left;
        assert!(asym_l > 0.0 && l.camera_offset < 0.0, "left: {l:?}");
        assert!(asym_r < 0.0 && r.camera_offset > 0.0, "right: {r:?}");
        assert_eq!(l.camera_offset, -r.camera_offset);
        // Xrange × 0.035 exactly as the seed writes it.
        let xr = mono().width() * 10.0 / 1.0;
        assert_eq!(r.camera_offset, xr * 0.035);
        assert!(
            (asym_l - xr * 0.035 * 1.0 / 10.0).abs() < 1e-15,
            "asymmetry {asym_l}"
        );
    }

    #[test]
    fn offset_adjustment_zero_gives_identical_eyes() {
        let adj = StereoAdjust {
            offset_adjustment: 0.0,
            ..StereoAdjust::new(7.0)
        };
        let l = hp_eye(&mono(), &adj, Eye::Left).unwrap();
        let r = hp_eye(&mono(), &adj, Eye::Right).unwrap();
        assert_eq!(l.matrix(), r.matrix());
        assert_eq!(l.frustum, mono());
    }

    #[test]
    fn invalid_adjustments_are_rejected_by_name() {
        let cases = [
            (StereoAdjust::new(0.0), "zero_parallax_distance"),
            (StereoAdjust::new(-3.0), "zero_parallax_distance"),
            (StereoAdjust::new(f64::NAN), "zero_parallax_distance"),
            (
                StereoAdjust {
                    offset_adjustment: -0.1,
                    ..StereoAdjust::new(1.0)
                },
                "offset_adjustment",
            ),
            (
                StereoAdjust {
                    balance_adjustment: f64::INFINITY,
                    ..StereoAdjust::new(1.0)
                },
                "balance_adjustment",
            ),
        ];
        for (adj, name) in cases {
            match hp_eye(&mono(), &adj, Eye::Left) {
                Err(Error::InvalidValue(m)) => assert!(m.contains(name), "{m:?} lacks {name}"),
                other => panic!("{adj:?}: got {other:?}"),
            }
        }
    }
}

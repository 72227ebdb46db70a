//! On-screen parallax, as seed 000 §7 measures it: a percentage of the
//! viewport width, positive behind the screen and negative in front.

use glam::DVec4;

use super::frustum::{EyeProjection, Frustum};
use super::hp::{HP_OFFSET_FRACTION, StereoAdjust, hp_eye, xrange};
use super::{Eye, finite, finite_result, positive};
use crate::error::{Error, Result};

/// The comfort budget of seed 000 §7: parallax within about 3% of the
/// viewport width, both negative and positive.
pub const DEFAULT_BUDGET_PERCENT: f64 = 3.0;

/// The anaglyph tutorial's parallax (seed 003): `p = D·(1 − C/w)` for eye
/// separation D, convergence distance C and depth w, in scene units on the
/// convergence plane. 0 at w = C, → D as w → ∞, −D at w = C/2.
pub fn parallax(eye_separation: f64, convergence: f64, depth: f64) -> Result<f64> {
    finite("eye_separation", eye_separation)?;
    finite("convergence", convergence)?;
    positive("depth", depth)?;
    finite_result("the parallax", eye_separation * (1.0 - convergence / depth))
}

/// The on-screen parallax of a point at distance `depth` in front of the
/// camera, as a fraction of the viewport width (right-eye x minus left-eye x
/// in window units), for any pair of eye projections.
pub fn screen_parallax_fraction(
    left: &EyeProjection,
    right: &EyeProjection,
    depth: f64,
) -> Result<f64> {
    positive("depth", depth)?;
    let x_ndc = |e: &EyeProjection| {
        let c = e.matrix() * DVec4::new(0.0, 0.0, -depth, 1.0);
        c.x / c.w
    };
    // NDC spans 2 units across the viewport.
    Ok((x_ndc(right) - x_ndc(left)) / 2.0)
}

/// The on-screen parallax (percent of viewport width) of depth `depth` under
/// HP's method with these settings.
pub fn hp_parallax_percent(mono: &Frustum, adjust: &StereoAdjust, depth: f64) -> Result<f64> {
    let l = hp_eye(mono, adjust, Eye::Left)?;
    let r = hp_eye(mono, adjust, Eye::Right)?;
    finite_result(
        "the parallax percentage",
        100.0 * screen_parallax_fraction(&l, &r, depth)?,
    )
}

/// The largest stereo that keeps a depth range within a parallax budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BudgetFit {
    /// Full camera separation (twice the camera offset), in scene units.
    pub separation: f64,
    /// The HP offset_adjustment that gives this separation.
    pub offset_adjustment: f64,
}

/// The separation (and the equivalent HP offset adjustment) that keeps the
/// parallax of every depth in `nearest…farthest` within ±`budget_percent` of
/// the viewport width, for HP's method with `adjust`'s zero-parallax distance
/// and balance (its offset adjustment is ignored: it is what is solved for).
///
/// Parallax is linear in the offset: `fraction(w) = offset · (2·near/width) ·
/// (balance/d − 1/w)`, monotonic in w, so the range's ends bound it.
pub fn hp_fit_budget(
    mono: &Frustum,
    adjust: &StereoAdjust,
    nearest: f64,
    farthest: f64,
    budget_percent: f64,
) -> Result<BudgetFit> {
    let mono = mono.validated()?;
    let adjust = adjust.validated()?;
    positive("nearest", nearest)?;
    positive("farthest", farthest)?;
    positive("budget_percent", budget_percent)?;
    if farthest < nearest {
        return Err(Error::invalid_value(format!(
            "farthest ({farthest}) must be >= nearest ({nearest})"
        )));
    }
    let d = adjust.zero_parallax_distance;
    let k = |w: f64| (2.0 * mono.near / mono.width()) * (adjust.balance_adjustment / d - 1.0 / w);
    let worst = k(nearest).abs().max(k(farthest).abs());
    if worst == 0.0 {
        return Err(Error::invalid_value(
            "the depth range lies entirely on the zero-parallax plane: any separation keeps it within budget",
        ));
    }
    let offset = budget_percent / 100.0 / worst;
    Ok(BudgetFit {
        separation: finite_result("the separation", 2.0 * offset)?,
        offset_adjustment: finite_result(
            "the offset adjustment",
            // A mirrored frustum (left > right) has a negative range; the
            // adjustment is a magnitude either way.
            offset / (xrange(&mono, d) * HP_OFFSET_FRACTION).abs(),
        )?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mono() -> Frustum {
        Frustum::perspective(45.0, 4.0 / 3.0, 1.0, 100.0).unwrap()
    }

    #[test]
    fn tutorial_parallax_matches_its_landmarks() {
        assert_eq!(parallax(0.2, 10.0, 10.0).unwrap(), 0.0);
        assert_eq!(parallax(0.2, 10.0, 5.0).unwrap(), -0.2);
        assert!((parallax(0.2, 10.0, 1e12).unwrap() - 0.2).abs() < 1e-9);
        assert!(parallax(0.2, 10.0, 0.0).is_err());
    }

    #[test]
    fn behind_the_plane_is_positive_in_front_negative_on_it_zero() {
        let adj = StereoAdjust::new(10.0);
        assert!(hp_parallax_percent(&mono(), &adj, 20.0).unwrap() > 0.0);
        assert!(hp_parallax_percent(&mono(), &adj, 5.0).unwrap() < 0.0);
        assert!(hp_parallax_percent(&mono(), &adj, 10.0).unwrap().abs() < 1e-12);
    }

    #[test]
    fn hp_defaults_approach_seven_percent_at_infinity() {
        // Each camera moves 3.5% of Xrange, so far points separate by 7%.
        let p = hp_parallax_percent(&mono(), &StereoAdjust::new(10.0), 1e12).unwrap();
        assert!((p - 7.0).abs() < 1e-6, "{p}");
    }

    #[test]
    fn balance_zero_makes_all_parallax_negative() {
        let adj = StereoAdjust {
            balance_adjustment: 0.0,
            ..StereoAdjust::new(10.0)
        };
        for w in [1.5, 5.0, 10.0, 50.0, 99.0] {
            assert!(
                hp_parallax_percent(&mono(), &adj, w).unwrap() < 0.0,
                "depth {w}"
            );
        }
    }

    #[test]
    fn fitted_separation_puts_the_worst_end_exactly_on_the_budget() {
        let adj = StereoAdjust::new(10.0);
        let fit = hp_fit_budget(&mono(), &adj, 6.0, 30.0, 3.0).unwrap();
        let fitted = StereoAdjust {
            offset_adjustment: fit.offset_adjustment,
            ..adj
        };
        let near = hp_parallax_percent(&mono(), &fitted, 6.0).unwrap();
        let far = hp_parallax_percent(&mono(), &fitted, 30.0).unwrap();
        assert!(near < 0.0 && far > 0.0);
        let worst = near.abs().max(far.abs());
        assert!((worst - 3.0).abs() < 1e-9, "near {near}% far {far}%");
        let l = hp_eye(&mono(), &fitted, Eye::Left).unwrap();
        assert!((fit.separation + 2.0 * l.camera_offset).abs() < 1e-12);
    }
}

//! Measured parallax: the on-screen parallax a rendered scene really spans,
//! from its depth buffer, against seed 000 §7's comfort budget; and the
//! centre of interest that auto-convergence puts at zero parallax.
//!
//! Why one depth buffer is enough: with parallel-axis stereo (HP, SGI,
//! Bourke, the anaglyph tutorial and NVIDIA's clip-space shift all are), the
//! two cameras differ only by a lateral offset and a frustum shift, so a
//! point's on-screen parallax depends only on its distance along the view
//! axis ([`screen_parallax_fraction`]), and it is monotonic in that
//! distance. The parallax range of a frame is therefore the parallax of its
//! nearest and farthest visible pixels, and either eye's depth buffer gives
//! them. The depth buffer is shared by both eyes (as on quad-buffer
//! hardware), so it is read right after an eye is drawn, before the next
//! eye's depth clear. Points that only the other eye sees (a sliver at the
//! frustum's side edges, or behind an occluder) are missed; measure after
//! each eye and merge with [`ParallaxReport::merge`] to include them.

use super::depth::{DepthCapture, DepthMapping};
use crate::error::{Error, Result};
use crate::math::parallax::screen_parallax_fraction;
use crate::math::{Eye, EyeProjection, Frustum, StereoAdjust, hp_eye, positive};

/// The central part of the viewport in which auto-convergence looks for the
/// centre of interest: the middle half of its width and of its height
/// (fractions 0.25…0.75), a quarter of its area.
pub const CONVERGENCE_WINDOW: (f64, f64) = (0.25, 0.75);

/// What a frame's parallax spans, as seed 000 §7 measures it: a percentage
/// of the viewport width, negative in front of the screen, positive behind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParallaxReport {
    /// The smallest parallax (the most negative when any is negative), in
    /// percent of the viewport width.
    pub min_percent: f64,
    /// The largest parallax, in percent of the viewport width.
    pub max_percent: f64,
    /// `min_percent` in pixels of the viewport.
    pub min_pixels: f64,
    /// `max_percent` in pixels of the viewport.
    pub max_pixels: f64,
    /// Eye-space distance of the nearest pixel holding geometry.
    pub nearest: f64,
    /// Eye-space distance of the farthest pixel holding geometry.
    pub farthest: f64,
    /// The comfort budget the warnings compare with, percent each side.
    pub budget_percent: f64,
    /// How many pixels of the viewport hold geometry.
    pub covered_pixels: u64,
}

impl ParallaxReport {
    /// True when the most negative parallax is beyond −budget.
    pub fn negative_exceeds(&self) -> bool {
        self.min_percent < -self.budget_percent
    }

    /// True when the most positive parallax is beyond +budget.
    pub fn positive_exceeds(&self) -> bool {
        self.max_percent > self.budget_percent
    }

    /// The range of two measurements (e.g. one after each eye, or one per
    /// frame): the extremes of both, the pixel counts added, the smaller budget.
    pub fn merge(&self, other: &ParallaxReport) -> ParallaxReport {
        let low = if self.min_percent <= other.min_percent {
            self
        } else {
            other
        };
        let high = if self.max_percent >= other.max_percent {
            self
        } else {
            other
        };
        ParallaxReport {
            min_percent: low.min_percent,
            min_pixels: low.min_pixels,
            max_percent: high.max_percent,
            max_pixels: high.max_pixels,
            nearest: self.nearest.min(other.nearest),
            farthest: self.farthest.max(other.farthest),
            budget_percent: self.budget_percent.min(other.budget_percent),
            covered_pixels: self.covered_pixels + other.covered_pixels,
        }
    }

    /// One line for people: the range in percent and pixels, the depths,
    /// and whether it keeps the budget, with what to change when it does not.
    pub fn describe(&self) -> String {
        let mut s = format!(
            "parallax {:+.2}% to {:+.2}% of viewport width ({:+.1} to {:+.1} px), \
             distance {:.3} to {:.3}",
            self.min_percent,
            self.max_percent,
            self.min_pixels,
            self.max_pixels,
            self.nearest,
            self.farthest
        );
        let b = self.budget_percent;
        match (self.negative_exceeds(), self.positive_exceeds()) {
            (false, false) => s.push_str(&format!(": within the {b}% budget")),
            (neg, pos) => {
                if neg {
                    s.push_str(&format!(
                        "; WARNING: {:+.2}% in front of the screen exceeds the {b}% budget \
                         (weaken the offset adjustment or move the zero-parallax plane nearer)",
                        self.min_percent
                    ));
                }
                if pos {
                    s.push_str(&format!(
                        "; WARNING: {:+.2}% behind the screen exceeds the {b}% budget \
                         (weaken the offset adjustment, lower the balance, or move the \
                         zero-parallax plane farther)",
                        self.max_percent
                    ));
                }
            }
        }
        s
    }
}

/// The parallax range of the geometry in `capture`, for a scene drawn with
/// the eye projections `left` and `right` (which must share near and far
/// clip distances, as every parallel-axis stereo pair does).
///
/// Errors: `InvalidValue` for a budget that is not > 0 or eyes whose near or
/// far differ; `InvalidOperation` when no pixel of the viewport holds
/// geometry, or for a degenerate glDepthRange.
pub fn measure_parallax(
    capture: &DepthCapture,
    left: &EyeProjection,
    right: &EyeProjection,
    budget_percent: f64,
) -> Result<ParallaxReport> {
    positive("budget_percent", budget_percent)?;
    let mapping = mapping_of(capture, left, right)?;
    let (mut lo, mut hi, mut n) = (f32::INFINITY, f32::NEG_INFINITY, 0u64);
    capture.for_each_covered(0.0, 1.0, |z| {
        lo = lo.min(z);
        hi = hi.max(z);
        n += 1;
    });
    if n == 0 {
        return Err(nothing_drawn());
    }
    let (a, b) = (mapping.distance(lo as f64), mapping.distance(hi as f64));
    let (nearest, farthest) = (a.min(b), a.max(b));
    let pn = 100.0 * screen_parallax_fraction(left, right, nearest)?;
    let pf = 100.0 * screen_parallax_fraction(left, right, farthest)?;
    let (min_percent, max_percent) = (pn.min(pf), pn.max(pf));
    let vw = capture.viewport.width as f64;
    Ok(ParallaxReport {
        min_percent,
        max_percent,
        min_pixels: min_percent / 100.0 * vw,
        max_pixels: max_percent / 100.0 * vw,
        nearest,
        farthest,
        budget_percent,
        covered_pixels: n,
    })
}

/// [`measure_parallax`] for a scene drawn with HP's projection of `mono`
/// and `adjust` (what gls_apply_stereo_eye() loads).
pub fn hp_measure_parallax(
    capture: &DepthCapture,
    mono: &Frustum,
    adjust: &StereoAdjust,
    budget_percent: f64,
) -> Result<ParallaxReport> {
    let left = hp_eye(mono, adjust, Eye::Left)?;
    let right = hp_eye(mono, adjust, Eye::Right)?;
    measure_parallax(capture, &left, &right, budget_percent)
}

/// Where auto-convergence looks and what it found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CentreOfInterest {
    /// The eye-space distance to put at zero parallax.
    pub distance: f64,
    /// How many pixels the statistic was taken over.
    pub samples: u64,
    /// True when they came from the central window; false when it held no
    /// geometry and the whole viewport was used.
    pub central: bool,
}

/// The centre of interest of a rendered frame: the median eye-space
/// distance of the pixels holding geometry in the central window of the
/// viewport ([`CONVERGENCE_WINDOW`]: the middle half of its width and
/// height), or of the whole viewport when that window holds none.
///
/// Why this statistic: the viewer looks at the middle of the picture, where
/// a program frames its subject; the median is a distance the scene really
/// has there, and it ignores a minority of pixels of anything else (a far
/// background, a near object crossing the view) that a mean or a midrange
/// would be pulled towards. For an even count it is the upper of the two
/// middle values.
///
/// `frustum` gives the near and far clip distances the scene was drawn with
/// (either eye's frustum, or the mono one: they share them).
/// Errors: `InvalidOperation` when no pixel of the viewport holds geometry.
pub fn centre_of_interest(capture: &DepthCapture, frustum: &Frustum) -> Result<CentreOfInterest> {
    let mapping = DepthMapping::new(frustum, capture.depth_range)?;
    let collect = |lo: f64, hi: f64| {
        let mut v = Vec::new();
        capture.for_each_covered(lo, hi, |z| v.push(mapping.distance(z as f64)));
        v
    };
    let (mut d, central) = match collect(CONVERGENCE_WINDOW.0, CONVERGENCE_WINDOW.1) {
        v if !v.is_empty() => (v, true),
        _ => (collect(0.0, 1.0), false),
    };
    if d.is_empty() {
        return Err(nothing_drawn());
    }
    let mid = d.len() / 2;
    let (_, median, _) = d.select_nth_unstable_by(mid, f64::total_cmp);
    Ok(CentreOfInterest {
        distance: *median,
        samples: d.len() as u64,
        central,
    })
}

fn mapping_of(
    capture: &DepthCapture,
    left: &EyeProjection,
    right: &EyeProjection,
) -> Result<DepthMapping> {
    let (l, r) = (left.frustum.validated()?, right.frustum.validated()?);
    if l.near != r.near || l.far != r.far {
        return Err(Error::invalid_value(format!(
            "the eyes' clip distances differ (left near {} far {}, right near {} far {}): \
             a parallel-axis stereo pair shares them",
            l.near, l.far, r.near, r.far
        )));
    }
    DepthMapping::new(&l, capture.depth_range)
}

fn nothing_drawn() -> Error {
    Error::invalid_operation(
        "the depth buffer holds no geometry in the viewport: measure right after drawing an \
         eye (before the next depth clear), with the depth test and depth writes on",
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::depth::{DepthImage, Viewport};
    use crate::math::parallax::hp_parallax_percent;

    const W: u32 = 200;
    const H: u32 = 100;

    fn mono() -> Frustum {
        Frustum::perspective(30.0, W as f64 / H as f64, 1.0, 60.0).unwrap()
    }

    fn map() -> DepthMapping {
        DepthMapping::new(&mono(), (0.0, 1.0)).unwrap()
    }

    /// A rectangle [x0, x1) × [y0, y1) of pixels (y up) and its distance.
    type Rect = ((u32, u32, u32, u32), f64);

    /// A frame of rectangles at given distances (later ones on top).
    fn scene(rects: &[Rect]) -> DepthCapture {
        let m = map();
        DepthCapture::new(DepthImage::from_fn(W, H, |x, y| {
            let mut z = 1.0f32;
            for &((x0, y0, x1, y1), w) in rects {
                if x >= x0 && x < x1 && y >= y0 && y < y1 {
                    z = m.window_depth(w) as f32;
                }
            }
            z
        }))
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn a_plane_at_one_distance_has_the_parallax_the_math_gives() {
        let adj = StereoAdjust::new(10.0);
        for w in [6.0, 10.0, 25.0] {
            let cap = scene(&[((20, 10, 60, 40), w)]);
            let r = hp_measure_parallax(&cap, &mono(), &adj, 3.0).unwrap();
            let want = hp_parallax_percent(&mono(), &adj, w).unwrap();
            // f32 depths of a D24-like precision: distances to ~1e-4 relative.
            assert!(
                close(r.nearest, w, 1e-4 * w) && close(r.farthest, w, 1e-4 * w),
                "{r:?}"
            );
            assert!(close(r.min_percent, want, 1e-4) && close(r.max_percent, want, 1e-4));
            assert!(close(r.min_pixels, want / 100.0 * W as f64, 1e-3));
            assert_eq!(r.covered_pixels, 40 * 30);
        }
    }

    #[test]
    fn nearest_and_farthest_bound_the_range_and_warnings_follow_the_budget() {
        let adj = StereoAdjust::new(10.0);
        // 7% × (1 − 10/w): w = 6 → −4.67%, w = 12 → +1.17%, w = 40 → +5.25%.
        let cap = scene(&[((0, 0, 100, 100), 12.0), ((10, 10, 20, 20), 6.0)]);
        let r = hp_measure_parallax(&cap, &mono(), &adj, 3.0).unwrap();
        assert!(
            close(r.min_percent, 7.0 * (1.0 - 10.0 / 6.0), 1e-3),
            "{r:?}"
        );
        assert!(
            close(r.max_percent, 7.0 * (1.0 - 10.0 / 12.0), 1e-3),
            "{r:?}"
        );
        assert!(r.negative_exceeds() && !r.positive_exceeds());
        assert!(
            r.describe().contains("WARNING: -4.67% in front"),
            "{}",
            r.describe()
        );
        let cap = scene(&[((0, 0, 100, 100), 40.0)]);
        let r = hp_measure_parallax(&cap, &mono(), &adj, 3.0).unwrap();
        assert!(!r.negative_exceeds() && r.positive_exceeds(), "{r:?}");
        assert!(r.describe().contains("behind the screen"));
        let r = hp_measure_parallax(&cap, &mono(), &adj, 6.0).unwrap();
        assert!(
            r.describe().ends_with("within the 6% budget"),
            "{}",
            r.describe()
        );
    }

    #[test]
    fn balance_zero_makes_the_measured_range_negative() {
        let adj = StereoAdjust {
            balance_adjustment: 0.0,
            ..StereoAdjust::new(10.0)
        };
        let cap = scene(&[((0, 0, 100, 100), 12.0), ((10, 10, 20, 20), 59.0)]);
        let r = hp_measure_parallax(&cap, &mono(), &adj, 3.0).unwrap();
        assert!(
            r.min_percent < r.max_percent && r.max_percent < 0.0,
            "{r:?}"
        );
    }

    #[test]
    fn only_the_viewport_counts_and_pixels_are_of_its_width() {
        let adj = StereoAdjust::new(10.0);
        let mut cap = scene(&[((0, 0, 50, 100), 8.0), ((150, 0, 200, 100), 20.0)]);
        cap.viewport = Viewport {
            x: 0,
            y: 0,
            width: 100,
            height: 100,
        };
        let r = hp_measure_parallax(&cap, &mono(), &adj, 3.0).unwrap();
        assert!(
            close(r.farthest, 8.0, 1e-3),
            "the far plane is outside: {r:?}"
        );
        assert!(
            close(r.min_pixels, r.min_percent, 1e-9),
            "100 px wide viewport"
        );
    }

    #[test]
    fn an_empty_frame_is_an_error_that_says_what_to_do() {
        let cap = scene(&[]);
        match hp_measure_parallax(&cap, &mono(), &StereoAdjust::new(10.0), 3.0) {
            Err(Error::InvalidOperation(m)) => assert!(m.contains("depth test"), "{m}"),
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            centre_of_interest(&cap, &mono()),
            Err(Error::InvalidOperation(_))
        ));
        assert!(matches!(
            hp_measure_parallax(&scene(&[((0, 0, 1, 1), 5.0)]), &mono(), &StereoAdjust::new(10.0), 0.0),
            Err(Error::InvalidValue(m)) if m.contains("budget_percent")
        ));
    }

    #[test]
    fn eyes_with_different_clip_distances_are_refused() {
        let adj = StereoAdjust::new(10.0);
        let l = hp_eye(&mono(), &adj, Eye::Left).unwrap();
        let mut r = hp_eye(&mono(), &adj, Eye::Right).unwrap();
        r.frustum.far = 70.0;
        let cap = scene(&[((0, 0, 10, 10), 5.0)]);
        assert!(matches!(
            measure_parallax(&cap, &l, &r, 3.0),
            Err(Error::InvalidValue(m)) if m.contains("clip distances")
        ));
    }

    #[test]
    fn the_centre_of_interest_is_the_subject_not_the_background() {
        // Background at 30 everywhere; the subject at 8 fills 60% × 60% of
        // the middle, so 100% of the central window; a near object at 3
        // in a corner of the window.
        let cap = scene(&[
            ((0, 0, W, H), 30.0),
            ((40, 20, 160, 80), 8.0),
            ((50, 25, 60, 35), 3.0),
        ]);
        let c = centre_of_interest(&cap, &mono()).unwrap();
        assert!(c.central && close(c.distance, 8.0, 1e-3), "{c:?}");
        assert_eq!(c.samples, 100 * 50, "the central window of 200x100");
        // A mean would have been pulled towards the near object.
        let adj = StereoAdjust::new(c.distance);
        let subject = scene(&[((40, 20, 160, 80), 8.0)]);
        let r = hp_measure_parallax(&subject, &mono(), &adj, 3.0).unwrap();
        assert!(
            r.min_percent.abs() < 1e-3 && r.max_percent.abs() < 1e-3,
            "{r:?}"
        );
    }

    #[test]
    fn without_geometry_in_the_middle_the_whole_viewport_is_used() {
        let cap = scene(&[
            ((0, 0, 20, 20), 5.0),
            ((180, 80, 200, 100), 9.0),
            ((0, 80, 30, 100), 9.0),
        ]);
        let c = centre_of_interest(&cap, &mono()).unwrap();
        assert!(!c.central && close(c.distance, 9.0, 1e-3), "{c:?}");
        assert_eq!(c.samples, 400 + 400 + 600);
    }

    #[test]
    fn merging_keeps_the_extremes() {
        let adj = StereoAdjust::new(10.0);
        let a = hp_measure_parallax(&scene(&[((0, 0, 10, 10), 7.0)]), &mono(), &adj, 3.0).unwrap();
        let b = hp_measure_parallax(&scene(&[((0, 0, 5, 10), 14.0)]), &mono(), &adj, 3.0).unwrap();
        let m = a.merge(&b);
        assert_eq!(
            (m.min_percent, m.max_percent),
            (a.min_percent, b.max_percent)
        );
        assert_eq!((m.nearest, m.farthest), (a.nearest, b.farthest));
        assert_eq!(m.covered_pixels, 150);
        assert_eq!(m, b.merge(&a));
    }
}

//! Where each eye goes: composite sizes and eye placements, shared by the CPU
//! reference and the GL compositor so that both draw the same geometry.
//!
//! Coordinates are in output pixels with (0, 0) the TOP-left pixel, as in
//! [`crate::image::Image`]. A GL viewport for a placement `p` in an output
//! of height `H` is `(p.x, H − p.y − p.height, p.width, p.height)`.

use crate::math::Eye;

use super::mode::OutputMode;

/// One eye image scaled into a rectangle of the output.
///
/// The whole eye (W×H texels) maps onto the rectangle: output pixel
/// (x, y) inside it samples the eye at texel coordinates
/// `u = (x − p.x + 0.5) · W / p.width`, `v = (y − p.y + 0.5) · H / p.height`
/// (texel i has its centre at i + 0.5), with bilinear filtering and
/// clamp-to-edge: exactly what GL does when a full-screen quad with texture
/// coordinates 0…1 is drawn into the rectangle's viewport with GL_LINEAR.
/// When the rectangle is the eye's size, this is an exact copy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placement {
    /// The eye drawn here (after any swap of the inputs).
    pub eye: Eye,
    /// Left column of the rectangle.
    pub x: u32,
    /// Top row of the rectangle (0 = top of the output).
    pub y: u32,
    /// Width in output pixels; 0 when the eye gets no columns (see
    /// [`half_split`]).
    pub width: u32,
    /// Height in output pixels; 0 when the eye gets no rows.
    pub height: u32,
}

/// The blank rows between the eyes in `hdmi-frame-packing`:
/// `round(H / 24)` with halves rounded up, i.e. `(H + 12) / 24` in integers.
/// Exactly H/24 for the HDMI 1.4a sizes (720 → 30, 1080 → 45), which is
/// also 1/49 of the packed frame as HDMI and Bino define it.
pub fn hdmi_gap(eye_height: u32) -> u32 {
    eye_height.saturating_add(12) / 24
}

/// The rows each eye gets in `str-rect`: `round(H · 492 / 1024)` with halves
/// rounded up, i.e. `(492·H + 512) / 1024` in integers. 1024 → 492 (SGI's
/// STR_RECT: GL rows 532–1023 left, 0–491 right, 40 lost between);
/// 768 → 369; 480 → 231. Never more than H/2, so the band between the eyes
/// (H − 2·rows) is never negative; for H = 1 it is 0 rows (all black).
pub fn str_rect_eye_rows(height: u32) -> u32 {
    ((u64::from(height) * 492 + 512) / 1024) as u32
}

/// How `n` pixels split between two eyes placed one after the other in the
/// `-half` modes and `starbase`: the first (left or top) eye gets
/// `ceil(n/2)`, the second `floor(n/2)`. For odd n the first eye's squeeze
/// is slightly weaker than the second's; for n = 1 the second eye gets no
/// pixels at all.
pub fn half_split(n: u32) -> (u32, u32) {
    (n - n / 2, n / 2)
}

/// The size of the output frame of `mode` for eyes of `eye_width` ×
/// `eye_height`:
///
/// - `side-by-side`: 2W×H; `top-bottom`: W×2H;
/// - `hdmi-frame-packing`: W×(2H + [`hdmi_gap`]) (1280x720 → 1280x1470,
///   1920x1080 → 1920x2205);
/// - every other mode (quad included): W×H.
///
/// Arithmetic saturates instead of overflowing; [`super::cpu::compose`]
/// rejects outputs larger than [`crate::image::MAX_DIMENSION`].
pub fn composite_size(mode: OutputMode, eye_width: u32, eye_height: u32) -> (u32, u32) {
    let (w, h) = (eye_width, eye_height);
    match mode {
        OutputMode::SideBySide => (w.saturating_mul(2), h),
        OutputMode::TopBottom => (w, h.saturating_mul(2)),
        OutputMode::HdmiFramePacking => (w, h.saturating_mul(2).saturating_add(hdmi_gap(h))),
        OutputMode::Quad
        | OutputMode::Left
        | OutputMode::Right
        | OutputMode::Anaglyph(..)
        | OutputMode::AnaglyphRedBlue
        | OutputMode::SideBySideHalf
        | OutputMode::TopBottomHalf
        | OutputMode::Rows
        | OutputMode::Columns
        | OutputMode::Checkerboard
        | OutputMode::FrameSequential
        | OutputMode::Starbase
        | OutputMode::StrRect => (w, h),
    }
}

/// The eye size whose composite fills a window of `ww` × `wh` pixels: the
/// inverse of [`composite_size`] (each eye half the width for
/// `side-by-side`, half the height for `top-bottom`, the largest H with
/// 2H + gap(H) ≤ wh for `hdmi-frame-packing`, the window size otherwise),
/// at least 1 × 1. A window resized by its user gets eyes of this size.
pub fn eye_size_for_window(mode: OutputMode, ww: u32, wh: u32) -> (u32, u32) {
    let (w, h) = match mode {
        OutputMode::SideBySide => (ww / 2, wh),
        OutputMode::TopBottom => (ww, wh / 2),
        OutputMode::HdmiFramePacking => {
            // 2H + gap(H) is increasing in H: walk down from the upper bound.
            let mut h = wh / 2;
            while h > 1 && 2 * h + hdmi_gap(h) > wh {
                h -= 1;
            }
            (ww, h)
        }
        _ => (ww, wh),
    };
    (w.max(1), h.max(1))
}

/// The two placements of the modes that put each eye in its own rectangle
/// (left first); None for every other mode. Output pixels outside both
/// rectangles are black (0, 0, 0, 255).
///
/// - `side-by-side`: left (0, 0, W, H), right (W, 0, W, H).
/// - `top-bottom`: left (0, 0, W, H), right (0, H, W, H).
/// - `side-by-side-half`: left (0, 0, ⌈W/2⌉, H), right (⌈W/2⌉, 0, ⌊W/2⌋, H).
/// - `top-bottom-half` and `starbase` (the same picture: HP's left eye in the
///   upper 1280x512 of 1280x1024, right in the lower): left (0, 0, W, ⌈H/2⌉),
///   right (0, ⌈H/2⌉, W, ⌊H/2⌋).
/// - `hdmi-frame-packing`: left (0, 0, W, H), right (0, H + gap, W, H).
/// - `str-rect` with e = [`str_rect_eye_rows`]\(H): left (0, 0, W, e),
///   right (0, H − e, W, e).
pub fn placements(mode: OutputMode, eye_width: u32, eye_height: u32) -> Option<[Placement; 2]> {
    let (w, h) = (eye_width, eye_height);
    let place = |eye, x, y, width, height| Placement {
        eye,
        x,
        y,
        width,
        height,
    };
    let pair = |l: Placement, r: Placement| Some([l, r]);
    match mode {
        OutputMode::SideBySide => pair(place(Eye::Left, 0, 0, w, h), place(Eye::Right, w, 0, w, h)),
        OutputMode::TopBottom => pair(place(Eye::Left, 0, 0, w, h), place(Eye::Right, 0, h, w, h)),
        OutputMode::SideBySideHalf => {
            let (a, b) = half_split(w);
            pair(place(Eye::Left, 0, 0, a, h), place(Eye::Right, a, 0, b, h))
        }
        OutputMode::TopBottomHalf | OutputMode::Starbase => {
            let (a, b) = half_split(h);
            pair(place(Eye::Left, 0, 0, w, a), place(Eye::Right, 0, a, w, b))
        }
        OutputMode::HdmiFramePacking => pair(
            place(Eye::Left, 0, 0, w, h),
            place(Eye::Right, 0, h + hdmi_gap(h), w, h),
        ),
        OutputMode::StrRect => {
            let e = str_rect_eye_rows(h);
            pair(
                place(Eye::Left, 0, 0, w, e),
                place(Eye::Right, 0, h - e, w, e),
            )
        }
        OutputMode::Quad
        | OutputMode::Left
        | OutputMode::Right
        | OutputMode::Anaglyph(..)
        | OutputMode::AnaglyphRedBlue
        | OutputMode::Rows
        | OutputMode::Columns
        | OutputMode::Checkerboard
        | OutputMode::FrameSequential => None,
    }
}

/// Whether the [`placements`] of `mode` leave pixels of the composite
/// uncovered, to be painted black (the gap of `hdmi-frame-packing`, the
/// middle rows of `str-rect`): placements never overlap, so exactly when
/// they cover less than the frame. False for the modes without placements.
pub(crate) fn leaves_gaps(mode: OutputMode, eye_width: u32, eye_height: u32) -> bool {
    let Some(places) = placements(mode, eye_width, eye_height) else {
        return false;
    };
    let covered: u64 = places
        .iter()
        .map(|p| u64::from(p.width) * u64::from(p.height))
        .sum();
    let (cw, ch) = composite_size(mode, eye_width, eye_height);
    covered < u64::from(cw) * u64::from(ch)
}

/// The eye shown at output pixel (x, y) of the pixel-interleaved modes,
/// counted from the top-left pixel: `rows` by y, `columns` by x,
/// `checkerboard` by x + y; even = left. None for other modes.
pub fn interleaved_eye(mode: OutputMode, x: u32, y: u32) -> Option<Eye> {
    let even = match mode {
        OutputMode::Rows => y % 2 == 0,
        OutputMode::Columns => x % 2 == 0,
        OutputMode::Checkerboard => (x + y) % 2 == 0,
        _ => return None,
    };
    Some(if even { Eye::Left } else { Eye::Right })
}

/// Where a composite of `cw` × `ch` pixels is shown in a window of `ww` ×
/// `wh` pixels: a rectangle in window pixels, (0, 0) the TOP-left, whose x
/// and y are negative when the composite is larger than the window and
/// cropped. Window pixels outside it are black.
///
/// - Same size: the whole window, pixel for pixel.
/// - `rows`, `columns`, `checkerboard`: never scaled (scaling would mix the
///   interleaved eyes): pixel for pixel, centred, cropped when larger, with
///   the offsets rounded down to even numbers so the window's top-left pixel
///   keeps the composite's parity (top row and left column = left eye).
/// - Every other mode: scaled by one factor to the largest size that fits
///   (aspect ratio kept, sizes rounded to the nearest pixel, at least 1),
///   centred (offsets rounded down), with bilinear filtering.
///
/// Glstereo never resizes a window: a backend that wants the composite
/// pixel for pixel makes its window [`composite_size`] (e.g. 2W × H for
/// `side-by-side` of W × H eyes) and resizes the eye buffers to match.
pub fn window_fit(mode: OutputMode, cw: u32, ch: u32, ww: u32, wh: u32) -> WindowFit {
    let exact = WindowFit {
        x: 0,
        y: 0,
        width: cw,
        height: ch,
    };
    if (cw, ch) == (ww, wh) {
        return exact;
    }
    let centre = |outer: u32, inner: u32| (i64::from(outer) - i64::from(inner)).div_euclid(2);
    if interleaved_eye(mode, 0, 0).is_some() {
        // Floor to even: -3 → -4, 3 → 2.
        let even = |v: i64| (v.div_euclid(2) * 2) as i32;
        return WindowFit {
            x: even(centre(ww, cw)),
            y: even(centre(wh, ch)),
            ..exact
        };
    }
    let (cw64, ch64, ww64, wh64) = (u64::from(cw), u64::from(ch), u64::from(ww), u64::from(wh));
    // Fit the width when the window is relatively narrower, else the height;
    // round(a·b/c) in integers, halves up.
    let scaled = |a: u64, b: u64, c: u64| ((2 * a * b + c) / (2 * c)).max(1) as u32;
    let (width, height) = if ww64 * ch64 <= wh64 * cw64 {
        (ww, scaled(ch64, ww64, cw64).min(wh))
    } else {
        (scaled(cw64, wh64, ch64).min(ww), wh)
    };
    WindowFit {
        x: centre(ww, width) as i32,
        y: centre(wh, height) as i32,
        width,
        height,
    }
}

/// A composite's rectangle in a window (see [`window_fit`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WindowFit {
    /// Left column in the window (negative: cropped on the left).
    pub x: i32,
    /// Top row in the window (negative: cropped at the top).
    pub y: i32,
    /// Width in window pixels.
    pub width: u32,
    /// Height in window pixels.
    pub height: u32,
}

impl WindowFit {
    /// True when the composite fills a `ww` × `wh` window pixel for pixel.
    pub fn is_exact(&self, ww: u32, wh: u32) -> bool {
        (self.x, self.y, self.width, self.height) == (0, 0, ww, wh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hdmi_frame_packing_matches_the_hdmi_sizes() {
        let m = OutputMode::HdmiFramePacking;
        assert_eq!(composite_size(m, 1280, 720), (1280, 1470));
        assert_eq!(composite_size(m, 1920, 1080), (1920, 2205));
        // Rounding for heights that are not multiples of 24: half up.
        assert_eq!(hdmi_gap(11), 0);
        assert_eq!(hdmi_gap(12), 1);
        assert_eq!(hdmi_gap(35), 1);
        assert_eq!(hdmi_gap(36), 2);
        assert_eq!(hdmi_gap(1), 0);
    }

    #[test]
    fn only_gaps_between_placements_are_left_to_paint_black() {
        let m = OutputMode::HdmiFramePacking;
        assert!(leaves_gaps(m, 1280, 720));
        assert!(!leaves_gaps(m, 64, 11), "no gap under 12 rows");
        assert!(leaves_gaps(OutputMode::StrRect, 1280, 1024));
        for m in [
            OutputMode::SideBySide,
            OutputMode::SideBySideHalf,
            OutputMode::TopBottomHalf,
            OutputMode::Left,
            OutputMode::Rows,
        ] {
            assert!(!leaves_gaps(m, 7, 5), "{m}");
        }
    }

    #[test]
    fn full_size_modes_double_one_dimension_and_others_keep_the_eye_size() {
        for m in OutputMode::all() {
            let got = composite_size(m, 640, 480);
            let want = match m {
                OutputMode::SideBySide => (1280, 480),
                OutputMode::TopBottom => (640, 960),
                OutputMode::HdmiFramePacking => (640, 980),
                _ => (640, 480),
            };
            assert_eq!(got, want, "{m}");
        }
        assert_eq!(
            composite_size(OutputMode::SideBySide, u32::MAX, 1),
            (u32::MAX, 1),
            "saturates instead of overflowing"
        );
    }

    #[test]
    fn str_rect_keeps_sgi_rows_for_1024_and_scales_otherwise() {
        assert_eq!(str_rect_eye_rows(1024), 492);
        let p = placements(OutputMode::StrRect, 1280, 1024).unwrap();
        // Top-first rows 0..492 are GL rows 532..1023; rows 532..1024 are GL 0..491.
        assert_eq!((p[0].eye, p[0].y, p[0].height), (Eye::Left, 0, 492));
        assert_eq!((p[1].eye, p[1].y, p[1].height), (Eye::Right, 532, 492));
        assert_eq!(1024 - (p[0].y + p[0].height), 532, "left's GL bottom row");
        assert_eq!(1024 - (p[1].y + p[1].height), 0, "right's GL bottom row");
        assert_eq!(str_rect_eye_rows(768), 369);
        assert_eq!(str_rect_eye_rows(480), 231);
        for h in 1..=4096 {
            let e = str_rect_eye_rows(h);
            assert!(2 * e <= h, "H={h}: eyes of {e} rows overlap");
            let exact = f64::from(h) * 492.0 / 1024.0;
            assert!((f64::from(e) - exact).abs() <= 0.5, "H={h}: {e} vs {exact}");
        }
    }

    #[test]
    fn half_modes_split_first_eye_ceil_second_floor() {
        assert_eq!(half_split(1024), (512, 512));
        assert_eq!(half_split(5), (3, 2));
        assert_eq!(half_split(1), (1, 0));
        let p = placements(OutputMode::SideBySideHalf, 5, 3).unwrap();
        assert_eq!((p[0].x, p[0].width, p[1].x, p[1].width), (0, 3, 3, 2));
        let p = placements(OutputMode::Starbase, 1280, 1024).unwrap();
        assert_eq!(
            p,
            [
                Placement {
                    eye: Eye::Left,
                    x: 0,
                    y: 0,
                    width: 1280,
                    height: 512
                },
                Placement {
                    eye: Eye::Right,
                    x: 0,
                    y: 512,
                    width: 1280,
                    height: 512
                },
            ],
            "HP Starbase: left = upper 1280x512, right = lower 1280x512"
        );
    }

    #[test]
    fn placements_stay_inside_the_composite_and_do_not_overlap() {
        for m in OutputMode::all() {
            for (w, h) in [(1, 1), (2, 3), (7, 5), (64, 48), (1280, 1024)] {
                let (cw, ch) = composite_size(m, w, h);
                let Some([a, b]) = placements(m, w, h) else {
                    continue;
                };
                assert_eq!((a.eye, b.eye), (Eye::Left, Eye::Right), "{m}");
                for p in [a, b] {
                    assert!(
                        p.x + p.width <= cw && p.y + p.height <= ch,
                        "{m} {w}x{h}: {p:?}"
                    );
                }
                let apart = a.x + a.width <= b.x || a.y + a.height <= b.y;
                assert!(apart, "{m} {w}x{h}: {a:?} overlaps {b:?}");
            }
        }
    }

    #[test]
    fn placements_exist_exactly_for_the_rectangle_modes() {
        use OutputMode::*;
        for m in OutputMode::all() {
            let want = matches!(
                m,
                SideBySide
                    | TopBottom
                    | SideBySideHalf
                    | TopBottomHalf
                    | HdmiFramePacking
                    | Starbase
                    | StrRect
            );
            assert_eq!(placements(m, 8, 6).is_some(), want, "{m}");
        }
    }

    #[test]
    fn interleave_parity_counts_from_the_top_left() {
        use OutputMode::*;
        assert_eq!(interleaved_eye(Rows, 5, 0), Some(Eye::Left));
        assert_eq!(interleaved_eye(Rows, 0, 1), Some(Eye::Right));
        assert_eq!(interleaved_eye(Columns, 0, 7), Some(Eye::Left));
        assert_eq!(interleaved_eye(Columns, 1, 0), Some(Eye::Right));
        assert_eq!(interleaved_eye(Checkerboard, 0, 0), Some(Eye::Left));
        assert_eq!(interleaved_eye(Checkerboard, 1, 0), Some(Eye::Right));
        assert_eq!(interleaved_eye(Checkerboard, 1, 1), Some(Eye::Left));
        assert_eq!(interleaved_eye(SideBySide, 0, 0), None);
    }

    #[test]
    fn window_fit_keeps_same_sizes_and_interleave_parity_and_scales_the_rest() {
        use OutputMode::*;
        let f = window_fit(Rows, 640, 480, 640, 480);
        assert!(f.is_exact(640, 480));
        // Interleaved: never scaled, centred with even offsets, cropped when larger.
        assert_eq!(
            window_fit(Rows, 640, 480, 643, 487),
            WindowFit {
                x: 0,
                y: 2,
                width: 640,
                height: 480
            }
        );
        assert_eq!(
            window_fit(Checkerboard, 640, 480, 634, 474),
            WindowFit {
                x: -4,
                y: -4,
                width: 640,
                height: 480
            }
        );
        // Side-by-side full of 640x480 eyes in a 640x480 window: scaled to 640x240, centred.
        assert_eq!(
            window_fit(SideBySide, 1280, 480, 640, 480),
            WindowFit {
                x: 0,
                y: 120,
                width: 640,
                height: 240
            }
        );
        // HDMI frame packing 1280x1470 in a 1280x720 window: pillarboxed.
        let f = window_fit(HdmiFramePacking, 1280, 1470, 1280, 720);
        assert_eq!((f.width, f.height), (627, 720));
        assert_eq!((f.x, f.y), ((1280 - 627) / 2, 0));
        // Any size: the fitted rectangle lies inside the window and touches two sides.
        for (cw, ch, ww, wh) in [
            (7, 3, 2, 9),
            (1, 1, 1000, 3),
            (5000, 1, 3, 3),
            (33, 17, 34, 17),
        ] {
            let f = window_fit(AnaglyphRedBlue, cw, ch, ww, wh);
            assert!(f.x >= 0 && f.y >= 0, "{f:?}");
            assert!(
                f.x as u32 + f.width <= ww && f.y as u32 + f.height <= wh,
                "{f:?}"
            );
            assert!(f.width == ww || f.height == wh, "{f:?}");
        }
    }

    #[test]
    fn eye_size_for_window_inverts_composite_size() {
        for mode in OutputMode::all() {
            for (w, h) in [(640, 480), (1280, 720), (1920, 1080), (33, 17), (1, 1)] {
                let (cw, ch) = composite_size(mode, w, h);
                assert_eq!(eye_size_for_window(mode, cw, ch), (w, h), "{mode} {w}x{h}");
            }
        }
        assert_eq!(eye_size_for_window(OutputMode::SideBySide, 1, 1), (1, 1));
    }
}

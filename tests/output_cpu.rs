//! The CPU composite of the output formats, checked four ways: cases worked
//! out by hand (the and more), properties that must hold in every
//! mode (swap, crosstalk, alpha, sizes), and agreement with a slow per-pixel
//! model written straight from the documented rules, and byte for byte
//! against the reference (`cpu::reference`, the oracle) it is fast beside.

use glstereo::Error;
use glstereo::image::Image;
use glstereo::math::Eye;
use glstereo::output::anaglyph::{dubois_matrices, linear_to_srgb, luma, srgb_to_linear};
use glstereo::output::pattern::{gradient, noise};
use glstereo::output::{
    AnaglyphColors, AnaglyphMethod, OutputMode, OutputOptions, compose, compose_into,
    composite_size, placements,
};

fn solid(w: u32, h: u32, rgb: [u8; 3]) -> Image {
    Image::from_fn(w, h, |_, _| [rgb[0], rgb[1], rgb[2], 255])
}

fn plain() -> OutputOptions {
    OutputOptions::default()
}

fn with(swap_eyes: bool, crosstalk: f32, saturation: f32) -> OutputOptions {
    OutputOptions {
        swap_eyes,
        crosstalk,
        saturation,
    }
}

fn mode(name: &str) -> OutputMode {
    OutputMode::from_name(name).unwrap()
}

fn run(name: &str, o: OutputOptions, l: &Image, r: &Image) -> Image {
    compose(mode(name), &o, l, r, 0).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Fails with where the two images differ most when that exceeds `tol`.
fn assert_within(got: &Image, want: &Image, tol: u8, what: &str) {
    assert_eq!(
        (got.width(), got.height()),
        (want.width(), want.height()),
        "{what}: size"
    );
    let (d, x, y, c) = got.max_difference(want).unwrap();
    assert!(
        d <= tol,
        "{what}: at ({x}, {y}) channel {c} saw {:?}, wanted {:?} (difference {d} > {tol})",
        got.get(x, y),
        want.get(x, y)
    );
}

/// The composite modes (every mode but quad).
fn composites() -> impl Iterator<Item = OutputMode> {
    OutputMode::all().filter(|&m| m != OutputMode::Quad)
}

// ---------------------------------------------------------------- by hand

#[test]
fn red_cyan_of_white_left_and_black_right_is_pure_red() {
    let out = run(
        "anaglyph-red-cyan",
        plain(),
        &solid(4, 3, [255; 3]),
        &solid(4, 3, [0; 3]),
    );
    for (x, y) in [(0, 0), (3, 2), (1, 1)] {
        assert_eq!(out.get(x, y), [255, 0, 0, 255], "pixel ({x}, {y})");
    }
}

#[test]
fn red_cyan_of_the_redblue_overlap_is_black() {
    // RedBlue: the left eye's rectangle is blue, the right eye's red.
    let out = run(
        "anaglyph-red-cyan",
        plain(),
        &solid(2, 2, [0, 0, 255]),
        &solid(2, 2, [255, 0, 0]),
    );
    assert_eq!(out.get(1, 1), [0, 0, 0, 255]);
}

#[test]
fn plain_masks_take_each_channel_from_the_documented_eye() {
    let (l, r) = (solid(2, 2, [10, 20, 30]), solid(2, 2, [40, 50, 60]));
    for (name, want) in [
        ("anaglyph-red-cyan", [10, 50, 60]),
        ("anaglyph-green-magenta", [40, 20, 60]),
        ("anaglyph-amber-blue", [10, 20, 60]),
    ] {
        assert_eq!(
            run(name, plain(), &l, &r).get(0, 0),
            [want[0], want[1], want[2], 255],
            "{name}"
        );
    }
}

#[test]
fn half_colour_greys_only_the_left_eye() {
    // Y(pure red) = 0.299·255 = 76.2 → 76; the right eye stays in colour.
    let (l, r) = (solid(1, 1, [255, 0, 0]), solid(1, 1, [0, 255, 0]));
    assert_eq!(
        run("anaglyph-red-cyan-half", plain(), &l, &r).get(0, 0),
        [76, 255, 0, 255]
    );
    assert_eq!(
        run("anaglyph-amber-blue-half", plain(), &l, &r).get(0, 0),
        [76, 76, 0, 255]
    );
    assert_eq!(
        run("anaglyph-green-magenta-half", plain(), &l, &r).get(0, 0),
        [0, 76, 0, 255]
    );
}

#[test]
fn mono_and_red_blue_use_each_eyes_luminance() {
    // Y(blue) = 0.114·255 = 29.07 → 29; Y(red) = 76.2 → 76; Y(green) = 149.7 → 150.
    let (blue, red) = (solid(1, 1, [0, 0, 255]), solid(1, 1, [255, 0, 0]));
    assert_eq!(
        run("anaglyph-red-cyan-mono", plain(), &blue, &red).get(0, 0),
        [29, 76, 76, 255]
    );
    assert_eq!(
        run(
            "anaglyph-red-blue",
            plain(),
            &solid(1, 1, [255; 3]),
            &solid(1, 1, [0, 255, 0])
        )
        .get(0, 0),
        [255, 0, 150, 255]
    );
}

#[test]
fn dubois_of_white_and_black_saturates_the_glasses_colours() {
    // Red-cyan, left white: rows of M_L sum to 1.05, −0.148, −0.115 → (255, 0, 0).
    let (white, black) = (solid(1, 1, [255; 3]), solid(1, 1, [0; 3]));
    assert_eq!(
        run("anaglyph-red-cyan-dubois", plain(), &white, &black).get(0, 0),
        [255, 0, 0, 255]
    );
    // Right white: rows of M_R sum to −0.05, 1.147, 1.115 → (0, 255, 255).
    assert_eq!(
        run("anaglyph-red-cyan-dubois", plain(), &black, &white).get(0, 0),
        [0, 255, 255, 255]
    );
}

#[test]
fn dubois_of_grey_stays_grey() {
    for colors in AnaglyphColors::ALL {
        let m = OutputMode::Anaglyph(colors, AnaglyphMethod::Dubois);
        for g in [0u8, 1, 10, 50, 118, 128, 200, 254, 255] {
            let grey = solid(1, 1, [g; 3]);
            let got = compose(m, &plain(), &grey, &grey, 0).unwrap().get(0, 0);
            for (c, v) in got[..3].iter().enumerate() {
                assert!(
                    v.abs_diff(g) <= 1,
                    "{m} of grey {g}: channel {c} saw {v}, wanted {g} ± 1"
                );
            }
        }
    }
}

#[test]
fn saturation_blends_toward_luminance_as_vtk_does() {
    // s = 0.65, left pure red: Y = 76.245; 76.245 + 0.65·(255 − 76.245) = 192.44 → 192.
    let out = run(
        "anaglyph-red-cyan",
        with(false, 0.0, 0.65),
        &solid(1, 1, [255, 0, 0]),
        &solid(1, 1, [0; 3]),
    );
    assert_eq!(out.get(0, 0), [192, 0, 0, 255]);
    // Saturation 0 turns every plain anaglyph into its -mono variant.
    let (l, r) = (noise(16, 8, 1), noise(16, 8, 2));
    for colors in AnaglyphColors::ALL {
        let grey = compose(
            OutputMode::Anaglyph(colors, AnaglyphMethod::FullColor),
            &with(false, 0.0, 0.0),
            &l,
            &r,
            0,
        );
        let mono = compose(
            OutputMode::Anaglyph(colors, AnaglyphMethod::Monochrome),
            &plain(),
            &l,
            &r,
            0,
        );
        assert_within(
            &grey.unwrap(),
            &mono.unwrap(),
            1,
            &format!("{colors:?} at saturation 0 vs -mono"),
        );
    }
}

#[test]
fn saturation_leaves_non_anaglyph_modes_alone() {
    let (l, r) = (noise(8, 6, 3), noise(8, 6, 4));
    for m in composites().filter(|m| !m.is_anaglyph()) {
        let a = compose(m, &with(false, 0.0, 0.2), &l, &r, 0).unwrap();
        let b = compose(m, &plain(), &l, &r, 0).unwrap();
        assert_eq!(a, b, "{m} changed with saturation 0.2");
    }
}

#[test]
fn side_by_side_halves_are_the_eyes_exactly() {
    let (l, r) = (noise(7, 5, 10), noise(7, 5, 11));
    let out = run("side-by-side", plain(), &l, &r);
    assert_eq!((out.width(), out.height()), (14, 5));
    for y in 0..5 {
        for x in 0..7 {
            assert_eq!(out.get(x, y), l.get(x, y), "left half ({x}, {y})");
            assert_eq!(out.get(x + 7, y), r.get(x, y), "right half ({x}, {y})");
        }
    }
}

#[test]
fn top_bottom_puts_the_left_eye_on_top_exactly() {
    let (l, r) = (noise(5, 4, 12), noise(5, 4, 13));
    let out = run("top-bottom", plain(), &l, &r);
    assert_eq!((out.width(), out.height()), (5, 8));
    for y in 0..4 {
        assert_eq!(out.row(y), l.row(y), "top row {y} is the left eye's");
        assert_eq!(
            out.row(y + 4),
            r.row(y),
            "bottom row {y} is the right eye's"
        );
    }
}

fn average(a: [u8; 4], b: [u8; 4]) -> [u8; 4] {
    // round((a + b)/2), halves up, exactly.
    std::array::from_fn(|c| {
        if c == 3 {
            255
        } else {
            (u16::from(a[c]) + u16::from(b[c])).div_ceil(2) as u8
        }
    })
}

#[test]
fn half_modes_average_pairs_instead_of_dropping_them() {
    let (l, r) = (noise(8, 6, 20), noise(8, 6, 21));
    let sbs = run("side-by-side-half", plain(), &l, &r);
    assert_eq!((sbs.width(), sbs.height()), (8, 6));
    for y in 0..6 {
        for i in 0..4 {
            assert_eq!(
                sbs.get(i, y),
                average(l.get(2 * i, y), l.get(2 * i + 1, y)),
                "left ({i}, {y})"
            );
            assert_eq!(
                sbs.get(4 + i, y),
                average(r.get(2 * i, y), r.get(2 * i + 1, y)),
                "right ({i}, {y})"
            );
        }
    }
    for name in ["top-bottom-half", "starbase"] {
        let tb = run(name, plain(), &l, &r);
        assert_eq!((tb.width(), tb.height()), (8, 6), "{name}");
        for x in 0..8 {
            for i in 0..3 {
                assert_eq!(
                    tb.get(x, i),
                    average(l.get(x, 2 * i), l.get(x, 2 * i + 1)),
                    "{name} top ({x}, {i})"
                );
                assert_eq!(
                    tb.get(x, 3 + i),
                    average(r.get(x, 2 * i), r.get(x, 2 * i + 1)),
                    "{name} bottom ({x}, {i})"
                );
            }
        }
    }
}

#[test]
fn odd_half_splits_give_the_first_eye_the_extra_pixel() {
    // 5 columns: left eye squeezed into 3, right into 2; no column left black.
    let (l, r) = (solid(5, 3, [200, 0, 0]), solid(5, 3, [0, 0, 200]));
    let out = run("side-by-side-half", plain(), &l, &r);
    let row: Vec<[u8; 4]> = (0..5).map(|x| out.get(x, 1)).collect();
    assert_eq!(
        row,
        vec![[200, 0, 0, 255]; 3]
            .into_iter()
            .chain(vec![[0, 0, 200, 255]; 2])
            .collect::<Vec<_>>()
    );
    // One row: the left eye gets it, the right eye none.
    let one = run(
        "top-bottom-half",
        plain(),
        &solid(3, 1, [9; 3]),
        &solid(3, 1, [7; 3]),
    );
    assert_eq!(one.get(2, 0), [9, 9, 9, 255]);
}

#[test]
fn interleaves_count_parity_from_the_top_left_pixel() {
    let (l, r) = (noise(6, 5, 30), noise(6, 5, 31));
    let rows = run("rows", plain(), &l, &r);
    assert_eq!(
        rows.row(0),
        l.row(0),
        "the top row is the left eye's top row"
    );
    assert_eq!(rows.row(1), r.row(1), "row 1 is the right eye's row 1");
    assert_eq!(rows.row(4), l.row(4));
    let cols = run("columns", plain(), &l, &r);
    let cb = run("checkerboard", plain(), &l, &r);
    for y in 0..5 {
        for x in 0..6 {
            let want_col = if x % 2 == 0 { l.get(x, y) } else { r.get(x, y) };
            assert_eq!(cols.get(x, y), want_col, "columns ({x}, {y})");
            let want_cb = if (x + y) % 2 == 0 {
                l.get(x, y)
            } else {
                r.get(x, y)
            };
            assert_eq!(cb.get(x, y), want_cb, "checkerboard ({x}, {y})");
        }
    }
}

#[test]
fn frame_sequential_alternates_starting_with_the_left_eye() {
    let (l, r) = (noise(4, 4, 40), noise(4, 4, 41));
    for (frame, want) in [(0, &l), (1, &r), (2, &l), (1001, &r)] {
        let out = compose(OutputMode::FrameSequential, &plain(), &l, &r, frame).unwrap();
        assert_eq!(&out, want, "frame {frame}");
    }
    let swapped = compose(
        OutputMode::FrameSequential,
        &with(true, 0.0, 1.0),
        &l,
        &r,
        0,
    )
    .unwrap();
    assert_eq!(swapped, r, "frame 0 with swapped eyes holds the right eye");
    assert_eq!(with(true, 0.0, 1.0).frame_sequential_eye(0), Eye::Right);
}

#[test]
fn hdmi_frame_packing_stacks_left_gap_right() {
    let (l, r) = (noise(16, 48, 50), noise(16, 48, 51));
    let out = run("hdmi-frame-packing", plain(), &l, &r);
    assert_eq!((out.width(), out.height()), (16, 98), "48 + 2 + 48");
    for y in 0..48 {
        assert_eq!(out.row(y), l.row(y), "row {y} is the left eye's");
        assert_eq!(
            out.row(50 + y),
            r.row(y),
            "row {} is the right eye's row {y}",
            50 + y
        );
    }
    for y in 48..50 {
        assert!(
            out.row(y).chunks_exact(4).all(|p| p == [0, 0, 0, 255]),
            "gap row {y} is black"
        );
    }
    let big = composite_size(OutputMode::HdmiFramePacking, 1920, 1080);
    assert_eq!(big, (1920, 2205));
}

#[test]
fn str_rect_keeps_sgi_rows_at_1024() {
    let (l, r) = (solid(2, 1024, [200, 10, 0]), solid(2, 1024, [0, 10, 200]));
    let out = run("str-rect", plain(), &l, &r);
    assert_eq!((out.width(), out.height()), (2, 1024));
    let at = |y: u32| out.get(1, y);
    // Top-first row t is GL row 1023 − t.
    assert_eq!(at(0), [200, 10, 0, 255], "GL row 1023: left");
    assert_eq!(at(491), [200, 10, 0, 255], "GL row 532: left");
    assert_eq!(at(492), [0, 0, 0, 255], "GL row 531: blank");
    assert_eq!(at(531), [0, 0, 0, 255], "GL row 492: blank");
    assert_eq!(at(532), [0, 10, 200, 255], "GL row 491: right");
    assert_eq!(at(1023), [0, 10, 200, 255], "GL row 0: right");
}

#[test]
fn str_rect_and_starbase_squash_the_whole_eye() {
    // A vertical gradient eye: the squashed copy runs from the eye's top to
    // its bottom, so the first and last rows of the band are near 0 and 255.
    let g = Image::from_fn(1, 1024, |_, y| [(y / 4) as u8, 0, 0, 255]);
    for (name, first, last) in [("str-rect", 0, 491), ("starbase", 0, 511)] {
        let out = run(name, plain(), &g, &g);
        let (top, bottom) = (out.get(0, first)[0], out.get(0, last)[0]);
        assert!(
            top <= 1 && bottom >= 254,
            "{name}: left band runs {top}..{bottom}, wanted 0..255"
        );
        let mut prev = 0;
        for y in first..=last {
            let v = out.get(0, y)[0];
            assert!(
                v >= prev,
                "{name}: row {y} ({v}) darker than the row above ({prev})"
            );
            prev = v;
        }
    }
}

#[test]
fn left_and_right_show_one_eye_unchanged_even_with_crosstalk() {
    let (l, r) = (noise(5, 5, 60), noise(5, 5, 61));
    let o = with(false, 0.8, 0.3);
    assert_eq!(compose(OutputMode::Left, &o, &l, &r, 0).unwrap(), l);
    assert_eq!(compose(OutputMode::Right, &o, &l, &r, 0).unwrap(), r);
    let swapped = with(true, 0.8, 0.3);
    assert_eq!(
        compose(OutputMode::Left, &swapped, &l, &r, 0).unwrap(),
        r,
        "left with swapped eyes"
    );
}

// ------------------------------------------------------- every-mode rules

#[test]
fn every_mode_produces_its_composite_size() {
    for (w, h) in [(1, 1), (5, 3), (64, 48)] {
        let (l, r) = (noise(w, h, 70), noise(w, h, 71));
        for m in composites() {
            let out = compose(m, &plain(), &l, &r, 0).unwrap();
            assert_eq!(
                (out.width(), out.height()),
                composite_size(m, w, h),
                "{m} of {w}x{h}"
            );
        }
    }
}

#[test]
fn swapping_eyes_equals_exchanging_the_inputs_in_every_mode() {
    let (a, b) = (gradient(9, 7, 0), noise(9, 7, 80));
    for o in [plain(), with(false, 0.3, 0.6)] {
        let swapped = OutputOptions {
            swap_eyes: true,
            ..o
        };
        for m in composites() {
            for frame in [0, 1] {
                let one = compose(m, &swapped, &a, &b, frame).unwrap();
                let other = compose(m, &o, &b, &a, frame).unwrap();
                assert_eq!(
                    one, other,
                    "{m}, frame {frame}, {o:?}: swap ≠ exchanged inputs"
                );
                if m != OutputMode::Left && m != OutputMode::Right {
                    let unswapped = compose(m, &o, &a, &b, frame).unwrap();
                    assert_ne!(
                        one, unswapped,
                        "{m}, frame {frame}: swapping changed nothing"
                    );
                }
            }
        }
    }
}

#[test]
fn crosstalk_zero_changes_nothing_and_one_of_identical_eyes_is_black() {
    let e = noise(6, 4, 90);
    for m in composites() {
        let same = compose(m, &plain(), &e, &e, 0).unwrap();
        let zero = compose(m, &with(false, 0.0, 1.0), &e, &e, 0).unwrap();
        assert_eq!(same, zero, "{m}: crosstalk 0 is not the identity");
        let full = compose(m, &with(false, 1.0, 1.0), &e, &e, 0).unwrap();
        if m.shows_both_eyes() {
            for (i, p) in full.pixels().chunks_exact(4).enumerate() {
                assert_eq!(
                    p,
                    [0, 0, 0, 255],
                    "{m}: pixel {i} not black with crosstalk 1 of identical eyes"
                );
            }
        } else {
            assert_eq!(full, e, "{m} shows one eye; crosstalk does not apply");
        }
    }
}

#[test]
fn crosstalk_subtracts_the_fraction_of_the_other_eye_per_channel() {
    // L' = max(L − kR, 0), R' = max(R − kL, 0) with k = 0.5.
    let (l, r) = (solid(1, 1, [200, 100, 0]), solid(1, 1, [100, 60, 255]));
    let out = run("side-by-side", with(false, 0.5, 1.0), &l, &r);
    assert_eq!(
        out.get(0, 0),
        [150, 70, 0, 255],
        "left minus half the right"
    );
    assert_eq!(
        out.get(1, 0),
        [0, 10, 255, 255],
        "right minus half the left"
    );
}

#[test]
fn output_alpha_is_opaque_whatever_the_input_alpha() {
    let clear = |seed| {
        let mut img = noise(5, 4, seed);
        for a in img.pixels_mut().iter_mut().skip(3).step_by(4) {
            *a = 0;
        }
        img
    };
    let (l, r) = (clear(100), clear(101));
    for m in composites() {
        for o in [plain(), with(false, 0.2, 0.5)] {
            let out = compose(m, &o, &l, &r, 0).unwrap();
            assert!(
                out.pixels().iter().skip(3).step_by(4).all(|&a| a == 255),
                "{m} {o:?}: alpha not 255"
            );
        }
    }
}

#[test]
fn composing_into_a_used_buffer_leaves_nothing_of_the_previous_frame() {
    let (l, r) = (noise(6, 48, 110), noise(6, 48, 111));
    let o = with(false, 0.1, 0.9);
    for before in composites() {
        let mut out = compose(before, &o, &r, &l, 1).unwrap();
        for m in composites() {
            compose_into(m, &o, &l, &r, 0, &mut out).unwrap();
            assert_eq!(
                out,
                compose(m, &o, &l, &r, 0).unwrap(),
                "{m} composed over {before}"
            );
        }
    }
}

#[test]
fn a_refused_compose_into_leaves_the_buffer_alone() {
    let e = noise(4, 4, 120);
    let mut out = compose(OutputMode::Rows, &plain(), &e, &e, 0).unwrap();
    let kept = out.clone();
    assert!(compose_into(OutputMode::Quad, &plain(), &e, &e, 0, &mut out).is_err());
    assert!(
        compose_into(
            OutputMode::Rows,
            &with(false, 2.0, 1.0),
            &e,
            &e,
            0,
            &mut out
        )
        .is_err()
    );
    assert!(compose_into(OutputMode::Rows, &plain(), &e, &noise(4, 5, 1), 0, &mut out).is_err());
    assert_eq!(out, kept);
}

// ----------------------------------------------------------------- errors

#[test]
fn quad_is_refused_because_it_is_not_a_composite() {
    let e = solid(2, 2, [1; 3]);
    let err = compose(OutputMode::Quad, &plain(), &e, &e, 0).unwrap_err();
    assert!(
        matches!(err, Error::InvalidOperation(_)),
        "saw {err:?}, wanted InvalidOperation"
    );
    assert!(err.to_string().contains("quad"), "{err}");
}

#[test]
fn eyes_of_different_sizes_are_refused_with_both_sizes() {
    let err = compose(
        OutputMode::Rows,
        &plain(),
        &solid(4, 3, [0; 3]),
        &solid(3, 4, [0; 3]),
        0,
    )
    .unwrap_err();
    assert!(matches!(err, Error::InvalidValue(_)), "{err:?}");
    let msg = err.to_string();
    assert!(msg.contains("4x3") && msg.contains("3x4"), "{msg}");
}

#[test]
fn frames_beyond_the_size_limit_are_refused() {
    let max = glstereo::image::MAX_DIMENSION;
    let e = solid(max, 1, [0; 3]);
    let err = compose(OutputMode::SideBySide, &plain(), &e, &e, 0).unwrap_err();
    assert!(matches!(err, Error::InvalidValue(_)), "{err:?}");
    assert!(err.to_string().contains(&format!("{}x1", 2 * max)), "{err}");
    assert!(compose(OutputMode::SideBySideHalf, &plain(), &e, &e, 0).is_ok());
}

#[test]
fn out_of_range_options_are_refused() {
    let e = solid(2, 2, [0; 3]);
    for o in [
        with(false, 1.5, 1.0),
        with(false, 0.0, -1.0),
        with(false, f32::NAN, 1.0),
    ] {
        let err = compose(OutputMode::Rows, &o, &e, &e, 0).unwrap_err();
        assert!(matches!(err, Error::InvalidValue(_)), "{o:?}: {err:?}");
    }
}

// ------------------------------------- agreement with a per-pixel model

type Rgb = [f32; 3];

fn texel(img: &Image, x: i64, y: i64) -> Rgb {
    let cx = x.clamp(0, i64::from(img.width()) - 1) as u32;
    let cy = y.clamp(0, i64::from(img.height()) - 1) as u32;
    let p = img.get(cx, cy);
    [p[0], p[1], p[2]].map(|v| f32::from(v) / 255.0)
}

/// GL_LINEAR at texel coordinates (u, v), clamp-to-edge.
fn bilinear(img: &Image, u: f64, v: f64) -> Rgb {
    let (x, y) = (u - 0.5, v - 0.5);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let (a, b, c, d) = (
        texel(img, x0, y0),
        texel(img, x0 + 1, y0),
        texel(img, x0, y0 + 1),
        texel(img, x0 + 1, y0 + 1),
    );
    std::array::from_fn(|i| {
        let top = a[i] * (1.0 - fx) + b[i] * fx;
        let bottom = c[i] * (1.0 - fx) + d[i] * fx;
        top * (1.0 - fy) + bottom * fy
    })
}

/// Saturation, then crosstalk, as documented.
fn prepare(l: Rgb, r: Rgb, s: f32, k: f32) -> (Rgb, Rgb) {
    let sat = |p: Rgb| {
        let y = luma(p);
        p.map(|c| y + s * (c - y))
    };
    let (l, r) = (sat(l), sat(r));
    (
        std::array::from_fn(|c| (l[c] - k * r[c]).max(0.0)),
        std::array::from_fn(|c| (r[c] - k * l[c]).max(0.0)),
    )
}

/// Every composite straight from the module documentation, one pixel at a time.
fn model(m: OutputMode, o: &OutputOptions, left: &Image, right: &Image, frame: u64) -> Image {
    let (l, r) = if o.swap_eyes {
        (right, left)
    } else {
        (left, right)
    };
    let s = if m.is_anaglyph() { o.saturation } else { 1.0 };
    let k = if m.shows_both_eyes() {
        o.crosstalk
    } else {
        0.0
    };
    let (w, h) = (left.width(), left.height());
    let (cw, ch) = composite_size(m, w, h);
    let places = placements(m, w, h);
    Image::from_fn(cw, ch, |x, y| {
        let at = |img: &Image| bilinear(img, f64::from(x) + 0.5, f64::from(y) + 0.5);
        let rgb: Rgb = match m {
            OutputMode::Left => at(l),
            OutputMode::Right => at(r),
            OutputMode::FrameSequential => {
                let (a, b) = prepare(at(l), at(r), s, k);
                if frame % 2 == 0 { a } else { b }
            }
            OutputMode::Rows | OutputMode::Columns | OutputMode::Checkerboard => {
                let (a, b) = prepare(at(l), at(r), s, k);
                let parity = match m {
                    OutputMode::Rows => y,
                    OutputMode::Columns => x,
                    _ => x + y,
                };
                if parity % 2 == 0 { a } else { b }
            }
            OutputMode::AnaglyphRedBlue => {
                let (a, b) = prepare(at(l), at(r), s, k);
                [luma(a), 0.0, luma(b)]
            }
            OutputMode::Anaglyph(colors, method) => {
                let (a, b) = prepare(at(l), at(r), s, k);
                let mask = colors.left_channels();
                match method {
                    AnaglyphMethod::FullColor => {
                        std::array::from_fn(|c| if mask[c] { a[c] } else { b[c] })
                    }
                    AnaglyphMethod::HalfColor => {
                        std::array::from_fn(|c| if mask[c] { luma(a) } else { b[c] })
                    }
                    AnaglyphMethod::Monochrome => {
                        std::array::from_fn(|c| if mask[c] { luma(a) } else { luma(b) })
                    }
                    AnaglyphMethod::Dubois => {
                        let dm = dubois_matrices(colors);
                        let (la, lb) = (a.map(srgb_to_linear), b.map(srgb_to_linear));
                        std::array::from_fn(|c| {
                            let v: f32 = (0..3)
                                .map(|i| dm.left[c][i] * la[i] + dm.right[c][i] * lb[i])
                                .sum();
                            linear_to_srgb(v.clamp(0.0, 1.0))
                        })
                    }
                }
            }
            _ => {
                let inside = places
                    .into_iter()
                    .flatten()
                    .find(|p| x >= p.x && x < p.x + p.width && y >= p.y && y < p.y + p.height);
                match inside {
                    None => [0.0; 3],
                    Some(p) => {
                        let u = (f64::from(x - p.x) + 0.5) * f64::from(w) / f64::from(p.width);
                        let v = (f64::from(y - p.y) + 0.5) * f64::from(h) / f64::from(p.height);
                        let (a, b) = prepare(bilinear(l, u, v), bilinear(r, u, v), s, k);
                        if p.eye == Eye::Left { a } else { b }
                    }
                }
            }
        };
        let q = |f: f32| (f * 255.0).round().clamp(0.0, 255.0) as u8;
        [q(rgb[0]), q(rgb[1]), q(rgb[2]), 255]
    })
}

#[test]
fn the_fast_composite_is_the_reference_byte_for_byte() {
    // Widths around the kernels' 16-pixel steps; heights odd and even.
    let sizes = [(37, 23), (16, 12), (1, 1), (3, 40), (64, 33), (50, 2)];
    let options = [
        plain(),
        with(true, 0.0, 1.0),
        with(false, 0.35, 1.0),
        with(false, 0.0, 0.5),
        with(true, 0.2, 0.65),
    ];
    for (w, h) in sizes {
        let eyes = [
            (gradient(w, h, 0), gradient(w, h, 90)),
            (noise(w, h, 7), noise(w, h, 8)),
            (solid(w, h, [255, 255, 255]), solid(w, h, [0, 0, 0])),
        ];
        for (l, r) in &eyes {
            for o in &options {
                for m in composites() {
                    for frame in [0, 1] {
                        let got = compose(m, o, l, r, frame).unwrap();
                        let want = glstereo::output::cpu::reference(m, o, l, r, frame).unwrap();
                        // -dubois is within 1: of changed eyes it interpolates
                        // the sRGB curve, with AVX-512 it is fixed point.
                        let dubois = matches!(m, OutputMode::Anaglyph(_, AnaglyphMethod::Dubois));
                        let tol = u8::from(dubois);
                        assert_within(
                            &got,
                            &want,
                            tol,
                            &format!("{m} {w}x{h} frame {frame} {o:?}"),
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn every_mode_agrees_with_the_per_pixel_model_within_one_unit() {
    let sizes = [(16, 12), (7, 5), (1, 1), (3, 40)];
    let options = [
        plain(),
        with(true, 0.0, 1.0),
        with(false, 0.35, 1.0),
        with(true, 0.2, 0.65),
    ];
    for (w, h) in sizes {
        let eyes = [
            (gradient(w, h, 0), gradient(w, h, 90)),
            (noise(w, h, 7), noise(w, h, 8)),
        ];
        for (l, r) in &eyes {
            for o in &options {
                for m in composites() {
                    for frame in [0, 3] {
                        let got = compose(m, o, l, r, frame).unwrap();
                        let want = model(m, o, l, r, frame);
                        assert_within(&got, &want, 1, &format!("{m} {w}x{h} frame {frame} {o:?}"));
                    }
                }
            }
        }
    }
}

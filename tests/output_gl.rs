//! The GL compositor against the CPU reference on a real Mesa EGL context:
//! test patterns drawn into the eye buffers of a real surface (glDrawPixels,
//! as a program would), every composite mode, both eye orders, with and
//! without crosstalk and saturation, through every input framing, at odd
//! and even sizes — the GL composite must equal `cpu::compose` within 1
//! unit per channel. Plus the simple cases worked out by hand.

#[path = "common/gl_surface.rs"]
mod gl_surface;

use glstereo::backend::BackendKind;
use glstereo::framing::InputFraming;
use glstereo::image::Image;
use glstereo::output::pattern::{gradient, noise};
use glstereo::output::{ComposePath, OutputMode, OutputOptions, compose};
use glstereo::surface;

use gl_surface::*;

const BACKEND: BackendKind = BackendKind::Egl;

#[test]
fn gl_composite_matches_the_cpu_reference_in_every_mode_and_eye_order() {
    for (w, h) in [(33, 17), (64, 48)] {
        let s = stereo_surface(BACKEND, w, h);
        let pairs = [
            ("gradients", gradient(w, h, 0), gradient(w, h, 100)),
            ("noise", noise(w, h, 1), noise(w, h, 2)),
            ("gradient/noise", gradient(w, h, 7), noise(w, h, 3)),
        ];
        for (what, l, r) in &pairs {
            show(&s, l, r);
            for swap_eyes in [false, true] {
                let o = OutputOptions {
                    swap_eyes,
                    ..OutputOptions::default()
                };
                check_all_modes(&s, &o, l, r, &format!("{w}x{h} {what}"));
            }
        }
        surface::make_current(None).unwrap();
    }
}

#[test]
fn gl_composite_matches_the_cpu_reference_with_crosstalk_and_saturation() {
    for (w, h) in [(33, 17), (64, 48)] {
        let s = stereo_surface(BACKEND, w, h);
        let (l, r) = (noise(w, h, 11), gradient(w, h, 60));
        show(&s, &l, &r);
        for (swap_eyes, crosstalk, saturation) in [
            (false, 0.3, 0.65),
            (true, 0.3, 0.65),
            (false, 1.0, 0.0),
            (true, 0.07, 1.0),
        ] {
            let o = OutputOptions {
                swap_eyes,
                crosstalk,
                saturation,
            };
            check_all_modes(&s, &o, &l, &r, &format!("{w}x{h}"));
        }
        surface::make_current(None).unwrap();
    }
}

#[test]
fn every_input_framing_composes_on_gl_as_extract_then_compose() {
    // A mono surface holding one frame; each framing takes its eyes apart.
    // 33x17: odd width (side-by-side's right half is a column narrower and
    // is stretched), odd height; 40x1024 keeps STR_RECT's 492-row eyes.
    for (w, h) in [(33, 17), (40, 1024), (64, 48)] {
        let s = mono_surface(BACKEND, w, h);
        let frame = noise(w, h, 5);
        show_mono(&s, &frame);
        let front = s.read_pixels(glstereo::gl::enums::GL_FRONT_LEFT).unwrap();
        assert_within(&front, &frame, 0, "the frame drawn is the frame read");
        let opts = [
            OutputOptions::default(),
            OutputOptions {
                swap_eyes: true,
                crosstalk: 0.25,
                saturation: 0.5,
            },
        ];
        for framing in InputFraming::ALL {
            s.set_framing(framing).unwrap();
            let [ls, rs] = framing.sources(s.config().shape(), w, h);
            let (l, r) = (framing.extract(&ls, &frame), framing.extract(&rs, &frame));
            for o in &opts {
                check_all_modes(&s, o, &l, &r, &format!("{w}x{h} {framing:?}"));
            }
        }
        surface::make_current(None).unwrap();
    }
}

#[test]
fn red_cyan_of_white_left_and_black_right_is_pure_red_on_gl() {
    let s = stereo_surface(BACKEND, 8, 6);
    show(&s, &solid(8, 6, [255; 3]), &solid(8, 6, [0; 3]));
    s.set_output(OutputMode::from_name("anaglyph-red-cyan").unwrap())
        .unwrap();
    let img = s.composite_image_via(ComposePath::Gl).unwrap();
    for (x, y) in [(0, 0), (7, 5), (3, 2)] {
        assert_eq!(img.get(x, y), [255, 0, 0, 255], "pixel ({x}, {y})");
    }
    surface::make_current(None).unwrap();
}

#[test]
fn red_cyan_of_the_redblue_overlap_is_black_on_gl() {
    // RedBlue's overlap: the left eye blue, the right eye red.
    let s = stereo_surface(BACKEND, 4, 4);
    show(&s, &solid(4, 4, [0, 0, 255]), &solid(4, 4, [255, 0, 0]));
    s.set_output(OutputMode::from_name("rc").unwrap()).unwrap();
    let img = s.composite_image_via(ComposePath::Gl).unwrap();
    assert_eq!(img.get(2, 2), [0, 0, 0, 255]);
    surface::make_current(None).unwrap();
}

#[test]
fn side_by_side_puts_the_left_eye_in_the_left_half_on_gl() {
    let (w, h) = (21, 9);
    let s = stereo_surface(BACKEND, w, h);
    let (l, r) = (noise(w, h, 8), noise(w, h, 9));
    show(&s, &l, &r);
    s.set_output(OutputMode::SideBySide).unwrap();
    let img = s.composite_image_via(ComposePath::Gl).unwrap();
    assert_eq!((img.width(), img.height()), (2 * w, h));
    for y in 0..h {
        for x in 0..w {
            assert_eq!(img.get(x, y), l.get(x, y), "left half at ({x}, {y})");
            assert_eq!(img.get(w + x, y), r.get(x, y), "right half at ({x}, {y})");
        }
    }
    // Swapped, the left half holds the right eye.
    s.set_options(OutputOptions {
        swap_eyes: true,
        ..OutputOptions::default()
    })
    .unwrap();
    let img = s.composite_image_via(ComposePath::Gl).unwrap();
    assert_eq!(img.get(3, 4), r.get(3, 4));
    surface::make_current(None).unwrap();
}

#[test]
fn frame_sequential_alternates_eyes_across_swaps_on_gl() {
    let (w, h) = (10, 6);
    let s = stereo_surface(BACKEND, w, h);
    s.set_output(OutputMode::FrameSequential).unwrap();
    let (l, r) = (solid(w, h, [200, 10, 10]), solid(w, h, [10, 10, 200]));
    for swap_eyes in [false, true] {
        s.set_options(OutputOptions {
            swap_eyes,
            ..OutputOptions::default()
        })
        .unwrap();
        for _ in 0..4 {
            show(&s, &l, &r); // a new frame: both eyes drawn, one swap
            let frame = s.frames() - 1;
            let shows_left = (frame % 2 == 0) != swap_eyes;
            let want = if shows_left { &l } else { &r };
            let img = s.composite_image_via(ComposePath::Gl).unwrap();
            assert_eq!(
                img.get(4, 3),
                want.get(4, 3),
                "frame {frame}, swap {swap_eyes}: want the {} eye",
                if shows_left { "left" } else { "right" }
            );
        }
    }
    surface::make_current(None).unwrap();
}

#[test]
fn quad_on_a_surface_without_native_stereo_composes_red_cyan_on_gl() {
    let s = stereo_surface(BACKEND, 8, 4);
    let (l, r) = (noise(8, 4, 20), noise(8, 4, 21));
    show(&s, &l, &r);
    s.set_output(OutputMode::Quad).unwrap();
    let img = s.composite_image_via(ComposePath::Gl).unwrap();
    let want = compose(
        OutputMode::from_name("anaglyph-red-cyan").unwrap(),
        &OutputOptions::default(),
        &l,
        &r,
        0,
    )
    .unwrap();
    assert_within(&img, &want, 0, "quad falls back to anaglyph-red-cyan");
    surface::make_current(None).unwrap();
}

#[test]
fn a_composite_too_tall_fails_the_same_way_on_both_paths() {
    // 1x8192 eyes: hdmi-frame-packing would be 1x16725, over 16384.
    let s = stereo_surface(BACKEND, 1, 8192);
    s.set_output(OutputMode::HdmiFramePacking).unwrap();
    let gl = s.composite_image_via(ComposePath::Gl).unwrap_err();
    let cpu = s.composite_image_via(ComposePath::Cpu).unwrap_err();
    assert_eq!(gl.to_string(), cpu.to_string());
    assert!(gl.to_string().contains("16725"), "{gl}");
    // The surface still composes in another mode afterwards.
    s.set_output(OutputMode::TopBottom).unwrap();
    let img = s.composite_image_via(ComposePath::Gl).unwrap();
    assert_eq!((img.width(), img.height()), (1, 16384));
    surface::make_current(None).unwrap();
}

#[test]
fn the_preferred_path_gives_the_reference_image() {
    // composite_image() picks CPU or GL per mode and options: either way,
    // the reference image.
    let (w, h) = (20, 10);
    let s = stereo_surface(BACKEND, w, h);
    let (l, r) = (gradient(w, h, 3), noise(w, h, 4));
    show(&s, &l, &r);
    for o in [
        OutputOptions::default(),
        OutputOptions {
            swap_eyes: true,
            crosstalk: 0.2,
            saturation: 0.5,
        },
    ] {
        s.set_options(o).unwrap();
        for mode in composites() {
            s.set_output(mode).unwrap();
            let got = s.composite_image().unwrap();
            let want = compose(mode, &o, &l, &r, s.frames() - 1).unwrap();
            assert_within(
                &got,
                &want,
                1,
                &format!("composite_image() in {mode}, {o:?}"),
            );
        }
    }
    surface::make_current(None).unwrap();
}

fn solid(w: u32, h: u32, rgb: [u8; 3]) -> Image {
    Image::from_fn(w, h, |_, _| [rgb[0], rgb[1], rgb[2], 255])
}

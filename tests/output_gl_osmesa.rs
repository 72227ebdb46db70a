//! The GL compositor against the CPU reference on OSMesa (a subset of
//! `output_gl.rs`, which runs on EGL): every composite mode, both eye
//! orders, with crosstalk and saturation, at odd and even sizes, and the framings
//! that resample. OSMesa has its own process (test binary): it is a second
//! copy of Mesa.

#[path = "common/gl_surface.rs"]
mod gl_surface;

use glstereo::backend::BackendKind;
use glstereo::framing::InputFraming;
use glstereo::output::pattern::{gradient, noise};
use glstereo::output::{ComposePath, OutputMode, OutputOptions};
use glstereo::surface;

use gl_surface::*;

const BACKEND: BackendKind = BackendKind::OsMesa;

#[test]
fn gl_composite_matches_the_cpu_reference_on_osmesa() {
    // Odd and even sizes: interleave parity counted from the wrong edge
    // agrees with the right one at odd sizes only.
    for (w, h) in [(33, 17), (34, 18)] {
        let s = stereo_surface(BACKEND, w, h);
        let (l, r) = (noise(w, h, 31), gradient(w, h, 77));
        show(&s, &l, &r);
        for (swap_eyes, crosstalk, saturation) in
            [(false, 0.0, 1.0), (true, 0.0, 1.0), (true, 0.3, 0.65)]
        {
            let o = OutputOptions {
                swap_eyes,
                crosstalk,
                saturation,
            };
            check_all_modes(&s, &o, &l, &r, &format!("osmesa {w}x{h}"));
        }
        surface::make_current(None).unwrap();
    }
}

#[test]
fn resampling_framings_compose_on_gl_as_extract_then_compose_on_osmesa() {
    let (w, h) = (33, 17);
    let s = mono_surface(BACKEND, w, h);
    let frame = noise(w, h, 41);
    show_mono(&s, &frame);
    for framing in [
        InputFraming::SyncDoubled,
        InputFraming::StrRect,
        InputFraming::SideBySide,
    ] {
        s.set_framing(framing).unwrap();
        let [ls, rs] = framing.sources(s.config().shape(), w, h);
        let (l, r) = (framing.extract(&ls, &frame), framing.extract(&rs, &frame));
        check_all_modes(
            &s,
            &OutputOptions::default(),
            &l,
            &r,
            &format!("{framing:?}"),
        );
    }
    surface::make_current(None).unwrap();
}

#[test]
fn red_cyan_of_white_left_and_black_right_is_pure_red_on_osmesa() {
    let s = stereo_surface(BACKEND, 5, 3);
    let white = glstereo::image::Image::from_fn(5, 3, |_, _| [255; 4]);
    let black = glstereo::image::Image::from_fn(5, 3, |_, _| [0, 0, 0, 255]);
    show(&s, &white, &black);
    s.set_output(OutputMode::from_name("anaglyph-red-cyan").unwrap())
        .unwrap();
    let img = s.composite_image_via(ComposePath::Gl).unwrap();
    assert_eq!(img.get(2, 1), [255, 0, 0, 255]);
    surface::make_current(None).unwrap();
}

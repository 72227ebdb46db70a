//! The window paths of a software renderer (GLX under Xvfb, llvmpipe): the
//! composite reaches the window as pixels (MIT-SHM), composed on the CPU
//! (rows in GL's order or flipped), by blits, or by GL and read back. Every
//! one must show exactly what a capture of the composite holds, at odd and
//! even sizes, frame after frame.

mod common;

use std::sync::Arc;

use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::gl::enums::*;
use glstereo::output::layout::composite_size;
use glstereo::output::{OutputMode, OutputOptions};
use glstereo::surface::{self, Surface};

use common::xvfb::{Xvfb, screenshot};

/// Different content per eye and frame: scissored clears in bands (exact
/// colours), left vertical, right horizontal.
fn draw(s: &Arc<Surface>, frame: u32) {
    let gl = s.gl();
    let (w, h) = s.size();
    for (buf, vertical) in [(GL_BACK_LEFT, true), (GL_BACK_RIGHT, false)] {
        s.draw_buffer(buf).unwrap();
        // SAFETY: the surface is current on this thread.
        unsafe {
            gl.Enable(GL_SCISSOR_TEST);
            for k in 0..7u32 {
                let c = ((k + frame) % 7) as f32 / 6.0;
                if vertical {
                    gl.Scissor((w * k / 7) as i32, 0, (w / 7 + 1) as i32, h as i32);
                    gl.ClearColor(c, 0.25, 1.0 - c, 1.0);
                } else {
                    gl.Scissor(0, (h * k / 7) as i32, w as i32, (h / 7 + 1) as i32);
                    gl.ClearColor(1.0 - c, c, 0.6, 1.0);
                }
                gl.Clear(GL_COLOR_BUFFER_BIT);
            }
            gl.Disable(GL_SCISSOR_TEST);
        }
    }
}

fn sync(s: &Surface) {
    use glstereo::backend::NativeHandles;
    let NativeHandles::Glx { display, .. } = s.native_handles() else {
        panic!("not GLX")
    };
    let xl = x11_dl::xlib::Xlib::open().unwrap();
    // SAFETY: the surface's own live connection.
    unsafe { (xl.XSync)(display.cast(), 0) };
}

fn check_modes(w: u32, h: u32, options: OutputOptions, names: &[&str]) {
    let x = Xvfb::start(2 * w + 16, 2 * h + 16);
    let d = Display::open_x11(Some(&x.display)).unwrap();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO])
        .unwrap();
    let s = d.create_surface(&c, w, h).unwrap();
    s.set_options(options).unwrap();
    surface::make_current(Some(&s)).unwrap();
    for name in names {
        let mode = OutputMode::from_name(name).unwrap();
        s.set_output(mode).unwrap();
        let (ww, wh) = composite_size(mode, w, h);
        // The first frame after a mode change resizes the window (GL
        // path); the later ones take the window path under test.
        for frame in 0..3 {
            draw(&s, frame);
            s.swap_buffers().unwrap();
            sync(&s);
            let want = s.composite_image().unwrap();
            let got = screenshot(&x.display, 0, 0, ww, wh);
            let (diff, px, py, ch) = got.max_difference(&want).unwrap();
            assert!(
                diff <= 1,
                "{name} at {w}x{h}, frame {frame}: window pixel ({px}, {py}) channel {ch} \
                 differs by {diff} from the composite"
            );
        }
    }
    surface::make_current(None).unwrap();
}

const MODES: &[&str] = &[
    "anaglyph-red-cyan",
    "anaglyph-green-magenta-half",
    "anaglyph-red-cyan-dubois",
    "left",
    "right",
    "side-by-side",
    "top-bottom",
    "side-by-side-half",
    "top-bottom-half",
    "rows",
    "columns",
    "checkerboard",
    "frame-sequential",
    "hdmi-frame-packing",
    "starbase",
    "str-rect",
];

#[test]
fn every_mode_shows_its_composite_at_an_odd_size() {
    check_modes(97, 61, OutputOptions::default(), MODES);
}

#[test]
fn every_mode_shows_its_composite_at_an_even_size() {
    check_modes(96, 64, OutputOptions::default(), MODES);
}

#[test]
fn swapped_eyes_with_crosstalk_show_their_composite() {
    let options = OutputOptions {
        swap_eyes: true,
        crosstalk: 0.25,
        saturation: 0.8,
    };
    check_modes(
        96,
        64,
        options,
        &[
            "anaglyph-red-cyan",
            "rows",
            "side-by-side",
            "checkerboard",
            "left",
            "frame-sequential",
        ],
    );
}

#[test]
fn swapped_eyes_alone_show_their_composite() {
    let options = OutputOptions {
        swap_eyes: true,
        ..OutputOptions::default()
    };
    check_modes(
        97,
        61,
        options,
        &[
            "anaglyph-amber-blue",
            "side-by-side",
            "top-bottom",
            "right",
            "frame-sequential",
            "hdmi-frame-packing",
        ],
    );
}

#[test]
fn wide_windows_are_read_back_in_bands_without_seams() {
    // 1280 pixels a row: the one-pass paths read 102 rows at a time, so
    // 250 rows take three bands, the last one short.
    check_modes(
        1280,
        250,
        OutputOptions::default(),
        &[
            "anaglyph-red-cyan",
            "side-by-side",
            "top-bottom",
            "left",
            "hdmi-frame-packing",
        ],
    );
}

//! Surfaces with test patterns in their eye buffers, and the comparison of
//! a surface's GL composite with the CPU reference. Included with
//! `#[path]` by the compositor tests (one backend per test binary).
#![allow(dead_code)]

use std::sync::Arc;

use glstereo::backend::{BackendChoice, BackendKind};
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::gl::enums::*;
use glstereo::image::Image;
use glstereo::output::{ComposePath, OutputMode, OutputOptions, compose};
use glstereo::surface::{self, Surface};

fn surface(backend: BackendKind, stereo: bool, w: u32, h: u32) -> Arc<Surface> {
    let d = Display::open(BackendChoice::Only(backend)).expect("display");
    let mut attrs = vec![GLX_RGBA, GLX_ALPHA_SIZE, 8, GLX_DOUBLEBUFFER];
    if stereo {
        attrs.push(GLX_STEREO);
    }
    let c = d.choose_config(&attrs).expect("config");
    let s = d.create_surface(&c, w, h).expect("surface");
    surface::make_current(Some(&s)).expect("make current");
    s
}

/// A double-buffered stereo surface, current on this thread.
pub fn stereo_surface(backend: BackendKind, w: u32, h: u32) -> Arc<Surface> {
    surface(backend, true, w, h)
}

/// A double-buffered mono surface, current on this thread.
pub fn mono_surface(backend: BackendKind, w: u32, h: u32) -> Arc<Surface> {
    surface(backend, false, w, h)
}

/// Draws `img` into `buffer` of the current surface with glDrawPixels at
/// window position (0, 0), as a program would.
pub fn draw_image(s: &Arc<Surface>, buffer: u32, img: &Image) {
    s.draw_buffer(buffer).unwrap();
    let mut rows = img.clone();
    rows.flip_vertical(); // GL rows are bottom first
    let gl = s.gl();
    // SAFETY: the surface is current on this thread; the pixels are
    // width × height RGBA8 rows, tightly packed.
    unsafe {
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        gl.WindowPos2i(0, 0);
        gl.DrawPixels(
            img.width() as i32,
            img.height() as i32,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            rows.pixels().as_ptr().cast(),
        );
    }
    assert_eq!(
        s.take_gl_error().unwrap(),
        GL_NO_ERROR,
        "drawing the pattern"
    );
}

/// One frame of a stereo surface: each eye drawn into its back buffer, one swap.
pub fn show(s: &Arc<Surface>, left: &Image, right: &Image) {
    draw_image(s, GL_BACK_LEFT, left);
    draw_image(s, GL_BACK_RIGHT, right);
    s.swap_buffers().unwrap();
}

/// One frame of a mono surface.
pub fn show_mono(s: &Arc<Surface>, frame: &Image) {
    draw_image(s, GL_BACK, frame);
    s.swap_buffers().unwrap();
}

/// Fails with where the two images differ most when that exceeds `tol`.
pub fn assert_within(got: &Image, want: &Image, tol: u8, what: &str) {
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

/// Every composite mode (all but quad).
pub fn composites() -> impl Iterator<Item = OutputMode> {
    OutputMode::all().filter(|&m| m != OutputMode::Quad)
}

/// In every composite mode, the surface's GL composite with options `o`
/// equals `cpu::compose` of the eyes `l` and `r` within 1 unit per channel.
pub fn check_all_modes(s: &Arc<Surface>, o: &OutputOptions, l: &Image, r: &Image, what: &str) {
    s.set_options(*o).unwrap();
    for mode in composites() {
        s.set_output(mode).unwrap();
        let got = s
            .composite_image_via(ComposePath::Gl)
            .unwrap_or_else(|e| panic!("{what} {mode}: {e}"));
        let want = compose(mode, o, l, r, s.frames() - 1).unwrap();
        assert_within(&got, &want, 1, &format!("{what}, {mode}, {o:?}"));
    }
}

//! A library Surface's eye buffers read in place (`src/stereo/eye_memory.rs`)
//! on llvmpipe: headless EGL and OSMesa surfaces with PNG captures, and a
//! GLX window grabbed with XGetImage on a private Xvfb, show the same
//! pixels as with GLSTEREO_EYE_MEMORY=0 (read back by glReadPixels),
//! including after the window is resized (which replaces storage from
//! memory), and the eyes are memory files that a resize does not pile up
//! and that a destroyed surface leaves none of.
//!
//! The environment variable is read by the library when a framebuffer is
//! made, so each run is a child process (this test binary again, running
//! [`child`]); the parent compares what the two runs wrote.

mod common;
#[path = "common/gl_surface.rs"]
mod gl_surface;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

use glstereo::backend::{BackendChoice, BackendKind, NativeHandles};
use glstereo::capture::{read_png, write_png};
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::gl::enums::*;
use glstereo::image::Image;
use glstereo::output::pattern::{gradient, noise};
use glstereo::output::{AnaglyphColors, AnaglyphMethod, OutputMode};
use glstereo::surface::{self, CaptureImage, Surface};

use common::xvfb::{Xvfb, screenshot};
use gl_surface::draw_image;

/// The scenario a child runs, and the directory it writes to.
const SCENARIO: &str = "GLS_TEST_EYE_MEMORY_SCENARIO";
const OUT: &str = "GLS_TEST_EYE_MEMORY_OUT";

/// Output modes captured: a CPU channel mask (anaglyph, composed from the
/// eyes on the CPU on llvmpipe), a CPU copy of each eye (side-by-side), and
/// a GL pass (Dubois, composed by GL from the textures).
const MODES: [OutputMode; 3] = [
    OutputMode::Anaglyph(AnaglyphColors::RedCyan, AnaglyphMethod::FullColor),
    OutputMode::SideBySide,
    OutputMode::Anaglyph(AnaglyphColors::RedCyan, AnaglyphMethod::Dubois),
];

/// The eyes' memory files mapped in this process: (distinct files,
/// mappings; each file is mapped by the library and by llvmpipe).
fn eye_memory() -> (usize, usize) {
    let maps = std::fs::read_to_string("/proc/self/maps").expect("maps");
    let lines: Vec<&str> = maps
        .lines()
        .filter(|l| l.contains("/memfd:glstereo eye"))
        .collect();
    let files: std::collections::HashSet<&str> = lines
        .iter()
        .filter_map(|l| l.split_whitespace().nth(4))
        .collect();
    (files.len(), lines.len())
}

/// Left and right eye content for frame `frame` of `w` × `h`.
fn eyes(w: u32, h: u32, frame: u8) -> (Image, Image) {
    (noise(w, h, u64::from(frame) + 7), gradient(w, h, frame))
}

fn show(s: &Arc<Surface>, frame: u8) {
    let (w, h) = s.size();
    let (l, r) = eyes(w, h, frame);
    draw_image(s, GL_BACK_LEFT, &l);
    draw_image(s, GL_BACK_RIGHT, &r);
    s.swap_buffers().unwrap();
}

/// Writes the eyes (synchronous and queued captures, and read_pixels) and
/// the composite in every mode of [`MODES`] as PNGs named `tag-…`.
fn capture_all(s: &Arc<Surface>, out: &Path, tag: &str) {
    for (which, name) in [(CaptureImage::Left, "left"), (CaptureImage::Right, "right")] {
        s.save_png(which, &out.join(format!("{tag}-{name}.png")))
            .unwrap();
        s.queue_png(which, &out.join(format!("{tag}-{name}-queued.png")))
            .unwrap();
    }
    for (buffer, name) in [
        (GL_FRONT_LEFT, "front-left"),
        (GL_FRONT_RIGHT, "front-right"),
    ] {
        write_png(
            &s.read_pixels(buffer).unwrap(),
            &out.join(format!("{tag}-{name}.png")),
        )
        .unwrap();
    }
    for (i, mode) in MODES.into_iter().enumerate() {
        s.set_output(mode).unwrap();
        s.queue_png(
            CaptureImage::Composite,
            &out.join(format!("{tag}-composite-{i}.png")),
        )
        .unwrap();
    }
    s.set_output(MODES[0]).unwrap();
    s.finish_captures().unwrap();
}

/// Writes `name` = `value` into the child's output directory.
fn note(out: &Path, name: &str, value: impl std::fmt::Display) {
    std::fs::write(out.join(name), value.to_string()).unwrap();
}

fn headless(backend: BackendKind, out: &Path) {
    let d = Display::open(BackendChoice::Only(backend)).expect("display");
    let c = d
        .choose_config(&[GLX_RGBA, GLX_ALPHA_SIZE, 8, GLX_DOUBLEBUFFER, GLX_STEREO])
        .unwrap();
    // Odd sizes: rows padded to 4 texels and 64 bytes in llvmpipe's layout.
    let s = d.create_surface(&c, 67, 45).unwrap();
    surface::make_current(Some(&s)).unwrap();
    for frame in 0..3 {
        show(&s, frame);
    }
    capture_all(&s, out, "current");
    // Current on no thread: read back by GL, which synchronises.
    surface::make_current(None).unwrap();
    capture_all(&s, out, "released");
    note(out, "files", eye_memory().0);
    // The display stays open: the surface's memory goes with the surface.
    drop(s);
    note(out, "after-destroy", eye_memory().1);
    // Destroyed right after swaps that only flush (llvmpipe may still be
    // rasterizing into the eyes): the memory outlives the rendering.
    for _ in 0..8 {
        let s = d.create_surface(&c, 512, 512).unwrap();
        surface::make_current(Some(&s)).unwrap();
        for frame in 0..3 {
            clear_frame(&s, frame);
        }
        surface::make_current(None).unwrap();
    }
    note(out, "after-quick-destroys", eye_memory().1);
    drop(d);
}

/// A frame of clears only (each eye its own colour), then a swap.
fn clear_frame(s: &Arc<Surface>, frame: u8) {
    let gl = s.gl();
    for (buffer, shade) in [(GL_BACK_LEFT, 0.2), (GL_BACK_RIGHT, 0.7)] {
        s.draw_buffer(buffer).unwrap();
        // SAFETY: the surface is current on this thread.
        unsafe {
            gl.ClearColor(shade, f32::from(frame) / 7.0, 0.5, 1.0);
            gl.Clear(GL_COLOR_BUFFER_BIT);
        }
    }
    s.swap_buffers().unwrap();
}

fn window(out: &Path) {
    let display = std::env::var("DISPLAY").unwrap();
    let d = Display::open_x11(Some(&display)).unwrap();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO])
        .unwrap();
    let s = d.create_surface(&c, 200, 100).unwrap();
    surface::make_current(Some(&s)).unwrap();
    let NativeHandles::Glx {
        display: dpy,
        window,
        ..
    } = s.native_handles()
    else {
        panic!("not GLX")
    };
    let xl = x11_dl::xlib::Xlib::open().unwrap();
    // SAFETY: the surface's own live connection.
    let sync = || unsafe { (xl.XSync)(dpy.cast(), 0) };
    for frame in 0..2 {
        show(&s, frame);
    }
    sync();
    write_png(
        &screenshot(&display, 0, 0, 200, 100),
        &out.join("window.png"),
    )
    .unwrap();
    capture_all(&s, out, "window");
    // The user resizes the window: this frame keeps its eyes, the next
    // has eyes of the new size (textures from memory are replaced).
    // SAFETY: the surface's live connection and window.
    unsafe { (xl.XResizeWindow)(dpy.cast(), window, 151, 77) };
    sync();
    show(&s, 2);
    assert_eq!(s.size(), (151, 77), "the eyes follow the window");
    // SAFETY: the surface is current here.
    unsafe { s.gl().Viewport(0, 0, 151, 77) };
    for frame in 3..5 {
        show(&s, frame);
    }
    sync();
    write_png(
        &screenshot(&display, 0, 0, 151, 77),
        &out.join("resized-window.png"),
    )
    .unwrap();
    capture_all(&s, out, "resized");
    note(out, "files", eye_memory().0);
    surface::make_current(None).unwrap();
    // The display stays open: the surface's memory goes with the surface.
    drop(s);
    note(out, "after-destroy", eye_memory().1);
    drop(d);
}

/// The child's side: runs the scenario named in the environment (and
/// nothing when run as a plain test).
#[test]
fn child() {
    let (Ok(scenario), Some(out)) = (std::env::var(SCENARIO), std::env::var_os(OUT)) else {
        return;
    };
    let out = PathBuf::from(out);
    match scenario.as_str() {
        "egl" => headless(BackendKind::Egl, &out),
        "osmesa" => headless(BackendKind::OsMesa, &out),
        "glx" => window(&out),
        s => panic!("unknown scenario {s}"),
    }
}

/// Runs `scenario` in a child, in place or not; returns its directory.
fn run(scenario: &str, in_place: bool, display: Option<&str>) -> PathBuf {
    let dir = common::scratch(&format!("eye-memory-{scenario}-{in_place}"));
    let mut cmd = Command::new(std::env::current_exe().unwrap());
    cmd.args(["--exact", "child", "--nocapture", "--test-threads=1"])
        .env(SCENARIO, scenario)
        .env(OUT, &dir)
        .env_remove("GLSTEREO_EYE_MEMORY")
        .env_remove("GLSTEREO_MODE");
    if !in_place {
        cmd.env("GLSTEREO_EYE_MEMORY", "0");
    }
    if let Some(d) = display {
        cmd.env("DISPLAY", d);
    }
    let o = cmd.output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.success(),
        "{scenario} (in place {in_place}) failed:\n{}\n{stderr}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert!(
        !stderr.contains("glstereo:"),
        "{scenario} (in place {in_place}) warned: {stderr}"
    );
    dir
}

fn number(dir: &Path, name: &str) -> usize {
    std::fs::read_to_string(dir.join(name))
        .unwrap()
        .parse()
        .unwrap()
}

/// Both runs wrote the same images (every PNG of the read-back run has its
/// twin, equal byte for byte in pixels), the in-place run's eyes were four
/// memory files (and the read-back run's none), and a destroyed surface
/// left no mapping. Returns the in-place run's directory.
fn same_either_way(scenario: &str, display: Option<&str>) -> PathBuf {
    let placed = run(scenario, true, display);
    let read = run(scenario, false, display);
    assert_eq!(
        number(&placed, "files"),
        4,
        "{scenario}: the four colour buffers of a double-buffered stereo surface are memory \
         files (and a resize left no old ones)"
    );
    assert_eq!(
        number(&read, "files"),
        0,
        "{scenario}: none with GLSTEREO_EYE_MEMORY=0"
    );
    if scenario != "glx" {
        assert_eq!(
            number(&placed, "after-quick-destroys"),
            0,
            "{scenario}: mappings of eye memory left after surfaces destroyed right after swaps"
        );
    }
    assert_eq!(
        number(&placed, "after-destroy"),
        0,
        "{scenario}: mappings of eye memory left after the surface was destroyed"
    );
    let mut compared = 0;
    for entry in std::fs::read_dir(&read).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "png") {
            continue;
        }
        let name = path.file_name().unwrap();
        let want = read_png(&path).unwrap();
        let got = read_png(&placed.join(name)).unwrap();
        assert_eq!(
            (got.width(), got.height()),
            (want.width(), want.height()),
            "{scenario}: size of {name:?}"
        );
        let (d, x, y, _) = got.max_difference(&want).unwrap();
        assert_eq!(
            d, 0,
            "{scenario}: {name:?} in place differs from read back by {d} at ({x}, {y})"
        );
        compared += 1;
    }
    assert!(
        compared >= 14,
        "{scenario}: only {compared} images compared"
    );
    placed
}

/// What was drawn is what the captures hold (so two equally wrong runs
/// cannot pass): the eyes of the last frame, exactly.
fn holds_the_drawn_eyes(dir: &Path, tag: &str, w: u32, h: u32, frame: u8) {
    let (l, r) = eyes(w, h, frame);
    for (name, want) in [
        ("left", &l),
        ("right", &r),
        ("front-left", &l),
        ("front-right", &r),
    ] {
        let got = read_png(&dir.join(format!("{tag}-{name}.png"))).unwrap();
        let (d, x, y, _) = got.max_difference(want).unwrap();
        assert_eq!(
            d, 0,
            "{tag}-{name}: differs from what was drawn by {d} at ({x}, {y})"
        );
    }
}

#[test]
fn an_egl_surface_captures_the_same_pixels_in_place_as_read_back() {
    let dir = same_either_way("egl", None);
    holds_the_drawn_eyes(&dir, "current", 67, 45, 2);
    holds_the_drawn_eyes(&dir, "released", 67, 45, 2);
}

#[test]
fn an_osmesa_surface_captures_the_same_pixels_in_place_as_read_back() {
    let dir = same_either_way("osmesa", None);
    holds_the_drawn_eyes(&dir, "current", 67, 45, 2);
}

#[test]
fn a_glx_window_shows_the_same_pixels_in_place_as_read_back_also_after_a_resize() {
    let x = Xvfb::start(640, 480);
    let dir = same_either_way("glx", Some(&x.display));
    holds_the_drawn_eyes(&dir, "window", 200, 100, 1);
    holds_the_drawn_eyes(&dir, "resized", 151, 77, 4);
    // The window shows the anaglyph of the eyes drawn (checked against the
    // capture of the composite, made the same way in both runs).
    for (window, composite) in [
        ("window.png", "window-composite-0.png"),
        ("resized-window.png", "resized-composite-0.png"),
    ] {
        let got = read_png(&dir.join(window)).unwrap();
        let want = read_png(&dir.join(composite)).unwrap();
        let (d, x, y, _) = got.max_difference(&want).unwrap();
        assert!(
            d <= 1,
            "{window}: differs from the composite by {d} at ({x}, {y})"
        );
    }
}

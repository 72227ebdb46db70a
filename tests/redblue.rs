//! The RedBlue port (seed 000 §4) run as a real C program, headless on EGL
//! and on OSMesa, with every buffer's pixels checked.

mod common;

use std::path::Path;
use std::process::Command;

use glstereo::image::Image;

const GREY: [u8; 4] = [51, 51, 51, 255];
// glColor3b(0, 0, 127): GL maps signed byte c to (2c + 1) / 255, so 0
// becomes 1/255 (Mesa follows the classic rule); 127 becomes 1.0.
const BLUE: [u8; 4] = [1, 1, 255, 255];
const RED: [u8; 4] = [255, 1, 1, 255];

/// Window-space rectangle [x0, x1) × [y0, y1) (rows top first) of an NDC
/// rectangle on a W×H viewport.
fn ndc_rect(w: u32, h: u32, (nx0, ny0, nx1, ny1): (f64, f64, f64, f64)) -> (u32, u32, u32, u32) {
    let x = |n: f64| ((n + 1.0) / 2.0 * w as f64).round() as u32;
    let y = |n: f64| h - ((n + 1.0) / 2.0 * h as f64).round() as u32;
    (x(nx0), y(ny1), x(nx1), y(ny0))
}

/// Checks that `img` holds `color` inside the rectangle and `outside`
/// everywhere else, allowing one pixel of slack at each edge.
fn assert_rect(
    img: &Image,
    what: &str,
    rect: (u32, u32, u32, u32),
    color: [u8; 4],
    outside: [u8; 4],
) {
    let (x0, y0, x1, y1) = rect;
    for y in 0..img.height() {
        for x in 0..img.width() {
            let near_edge = |a: u32, e: u32| a + 1 >= e && a <= e;
            if near_edge(x, x0) || near_edge(x, x1) || near_edge(y, y0) || near_edge(y, y1) {
                continue;
            }
            let inside = x >= x0 && x < x1 && y >= y0 && y < y1;
            let want = if inside { color } else { outside };
            let got = img.get(x, y);
            assert!(
                got.iter().zip(want).all(|(g, w)| g.abs_diff(w) <= 1),
                "{what}: pixel ({x}, {y}) {} the rectangle {rect:?} is {got:?}, want {want:?} (±1)",
                if inside { "inside" } else { "outside" }
            );
        }
    }
}

fn run_redblue(osmesa: bool, backend: &str, out: &Path, extra_env: &[(&str, &str)]) -> String {
    run_redblue_args(osmesa, backend, out, extra_env, &[])
}

fn run_redblue_args(
    osmesa: bool,
    backend: &str,
    out: &Path,
    extra_env: &[(&str, &str)],
    args: &[&str],
) -> String {
    let exe = common::build_example("redblue", osmesa);
    let mut cmd = Command::new(exe);
    cmd.args(["--out", out.to_str().unwrap(), "--size", "320x240"])
        .args(args)
        .env("GLSTEREO_BACKEND", backend)
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_EMULATION");
    for (k, v) in extra_env {
        cmd.env(k, v);
    }
    String::from_utf8_lossy(&common::run_ok(&mut cmd).stdout).into_owned()
}

fn check_stereo_images(out: &Path) {
    let (w, h) = (320, 240);
    let left_rect = ndc_rect(w, h, (-0.8, -0.8, 0.2, 0.2));
    let right_rect = ndc_rect(w, h, (-0.2, -0.2, 0.8, 0.8));
    let left = common::png(&out.join("left.png"));
    let right = common::png(&out.join("right.png"));
    assert_eq!((left.width(), left.height()), (w, h));
    // Each eye has only its own rectangle: the other one is absent.
    assert_rect(&left, "left eye", left_rect, BLUE, GREY);
    assert_rect(&right, "right eye", right_rect, RED, GREY);
    // Red-cyan composite: R from the left eye, G and B from the right.
    let comp = common::png(&out.join("composite.png"));
    let (ox, oy) = (w / 2, h / 2); // inside both rectangles
    let overlap = comp.get(ox, oy);
    assert!(
        overlap[..3].iter().all(|&c| c <= 1),
        "overlap {overlap:?}: left blue has no red, right red has no green/blue, so ~black"
    );
    assert_eq!(comp.get(5, 5), [51, 51, 51, 255], "grey background");
}

#[test]
fn redblue_on_egl_puts_each_rectangle_in_its_own_eye() {
    let out = common::scratch("redblue_egl");
    let stdout = run_redblue(false, "egl", &out, &[]);
    assert!(stdout.contains("emulated stereo"), "{stdout}");
    check_stereo_images(&out);
}

#[test]
fn redblue_on_osmesa_puts_each_rectangle_in_its_own_eye() {
    let out = common::scratch("redblue_osmesa");
    let stdout = run_redblue(true, "osmesa", &out, &[]);
    assert!(stdout.contains("emulated stereo"), "{stdout}");
    check_stereo_images(&out);
}

#[test]
fn redblue_falls_back_to_mono_when_emulation_is_off() {
    let out = common::scratch("redblue_mono");
    let stdout = run_redblue(false, "egl", &out, &[("GLSTEREO_EMULATION", "off")]);
    assert!(stdout.contains("no stereo"), "{stdout}");
    // Mono: both rectangles in the one image (red drawn last, on top), same for both eyes.
    let left = common::png(&out.join("left.png"));
    let right = common::png(&out.join("right.png"));
    assert_eq!(left, right, "a mono surface shows one image to both eyes");
    assert_eq!(left.get(160, 120), RED, "overlap: red drawn over blue");
    assert_eq!(left.get(80, 200), BLUE);
    assert_eq!(left.get(5, 5), GREY);
}

#[test]
fn an_osmesa_build_refuses_the_egl_backend_kind_of_mistake() {
    // A program linked with -lGL cannot draw into an OSMesa context: the
    // library says so instead of rendering nothing.
    let exe = common::build_example("redblue", false);
    let o = Command::new(exe)
        .env("GLSTEREO_BACKEND", "osmesa")
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("-lOSMesa"), "{err}");
}

#[test]
fn the_output_mode_comes_from_the_command_line_or_the_environment() {
    // --mode through gls_surface_set_output: side-by-side is 2W x H, left eye on the left.
    let out = common::scratch("redblue_sbs");
    run_redblue_args(false, "egl", &out, &[], &["--mode", "side-by-side"]);
    let comp = common::png(&out.join("composite.png"));
    let left = common::png(&out.join("left.png"));
    assert_eq!((comp.width(), comp.height()), (640, 240));
    for (x, y) in [(0, 0), (100, 150), (319, 239)] {
        assert_eq!(
            comp.get(x, y),
            left.get(x, y),
            "left half is the left eye at ({x}, {y})"
        );
    }
    // GLSTEREO_MODE, with an alias, case-insensitive: VirtualGL's "tb" = top-bottom-half.
    let out = common::scratch("redblue_env_tb");
    run_redblue(false, "egl", &out, &[("GLSTEREO_MODE", "TB")]);
    let comp = common::png(&out.join("composite.png"));
    assert_eq!((comp.width(), comp.height()), (320, 240));
    // The left eye (blue rectangle at rows 96..216 of 240) squeezed into the top half.
    assert_eq!(comp.get(100, 48 + 30)[2], 255, "blue in the top half");
    assert!(
        comp.get(100, 120 + 30)[2] < 60,
        "no blue at that place in the bottom half"
    );
}

#[test]
fn a_bad_mode_is_a_clear_error_listing_the_names() {
    let exe = common::build_example("redblue", false);
    let o = Command::new(&exe)
        .env("GLSTEREO_BACKEND", "egl")
        .env("GLSTEREO_MODE", "garbage")
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("garbage")
            && err.contains("anaglyph-red-cyan")
            && err.contains("checkerboard"),
        "{err}"
    );
    let o = Command::new(&exe)
        .args(["--mode", "nonsense"])
        .env("GLSTEREO_BACKEND", "egl")
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("side-by-side"),
        "lists the valid names"
    );
}

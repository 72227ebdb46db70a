//! Unmodified GLX programs under glstereo-run on a real X server (Xvfb):
//! a legacy stereo program and a freeglut GLUT_STEREO program show the
//! composite of their two eyes in their windows (read back from the server
//! as a screenshot would), their captures hold the eyes they drew, and a
//! mono program is untouched.

mod common;

use std::path::PathBuf;
use std::process::Command;

use common::preload::{Running, Screen, built, compile_plain};
use common::xvfb::Xvfb;
use glstereo::image::Image;
use glstereo::output::OutputMode;
use glstereo::output::options::OutputOptions;

const W: u32 = 160;
const H: u32 = 120;

/// Builds tests/c/NAME.c (linked with `libs` only) once per test binary.
fn program(name: &str, libs: &[&str]) -> PathBuf {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static BUILT: OnceLock<Mutex<HashMap<String, PathBuf>>> = OnceLock::new();
    let mut map = BUILT
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    map.entry(name.to_owned())
        .or_insert_with(|| {
            let dir = common::lib_dir().join("test-preload");
            std::fs::create_dir_all(&dir).unwrap();
            let exe = dir.join(name);
            let tmp = dir.join(format!(".{name}-{}", std::process::id()));
            compile_plain(
                &common::root().join("tests/c").join(format!("{name}.c")),
                &tmp,
                libs,
            );
            std::fs::rename(&tmp, &exe).unwrap();
            exe
        })
        .clone()
}

/// The RedBlue eyes the programs draw, as seed 000 §4 describes them: a
/// grey 0.2 background (51), the left eye's blue rectangle (-0.8,-0.8)–
/// (0.2,0.2), the right eye's red (-0.2,-0.2)–(0.8,0.8). Pixel centres
/// exactly on an edge are avoided by the sample points, not here.
fn redblue_eye(left: bool, x: u32, y: u32) -> [u8; 4] {
    // Normalised device coordinates of the pixel centre (y up).
    let nx = (x as f64 + 0.5) / W as f64 * 2.0 - 1.0;
    let ny = 1.0 - (y as f64 + 0.5) / H as f64 * 2.0;
    let (lo, hi) = if left { (-0.8, 0.2) } else { (-0.2, 0.8) };
    let inside = nx > lo && nx < hi && ny > lo && ny < hi;
    match (inside, left) {
        (true, true) => [0, 0, 255, 255],
        (true, false) => [255, 0, 0, 255],
        _ => [51, 51, 51, 255],
    }
}

/// Sample points well inside each region of the RedBlue frame: background,
/// left rectangle only, overlap, right rectangle only.
const SAMPLES: [(f64, f64); 4] = [(-0.9, 0.9), (-0.5, -0.5), (0.0, 0.0), (0.5, 0.5)];

fn sample_pixels() -> Vec<(u32, u32)> {
    SAMPLES
        .iter()
        .map(|&(nx, ny)| {
            (
                ((nx + 1.0) / 2.0 * W as f64) as u32,
                ((1.0 - ny) / 2.0 * H as f64) as u32,
            )
        })
        .collect()
}

fn expected_eyes() -> (Image, Image) {
    (
        Image::from_fn(W, H, |x, y| redblue_eye(true, x, y)),
        Image::from_fn(W, H, |x, y| redblue_eye(false, x, y)),
    )
}

/// Runs the legacy program under glstereo-run in `mode` with a capture
/// directory; returns the window as the server shows it, the capture
/// directory, and the program's report line.
fn run_legacy(x: &Xvfb, mode: &str, capture: &str) -> (Image, PathBuf, String) {
    let exe = program("legacy_stereo", &["-lGL", "-lX11"]);
    let dir = common::scratch(capture);
    let mut cmd = Command::new(&built().run);
    cmd.args(["-m", mode, "--capture"])
        .arg(&dir)
        .arg(&exe)
        .args([W.to_string(), H.to_string()])
        .env("DISPLAY", &x.display);
    let mut p = Running::start(cmd);
    let id = p.ready();
    let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).expect("window id");
    let shot = Screen::open(&x.display).grab(window);
    let report = p.stdout.first().cloned().unwrap_or_default();
    let stderr = p.finish();
    assert!(
        !stderr.contains("glstereo:"),
        "the layer complained: {stderr}"
    );
    (shot, dir, report)
}

fn assert_close(got: &Image, want: &Image, what: &str) {
    assert_eq!(
        (got.width(), got.height()),
        (want.width(), want.height()),
        "{what}: size"
    );
    if let Some((d, x, y, c)) = got.max_difference(want) {
        assert!(
            d <= 1,
            "{what}: pixel ({x},{y}) channel {c} is {:?}, want {:?}",
            got.get(x, y),
            want.get(x, y)
        );
    }
}

#[test]
fn legacy_glx_program_shows_the_red_cyan_anaglyph_of_both_eyes() {
    let x = Xvfb::start(640, 480);
    let (shot, dir, report) = run_legacy(&x, "anaglyph-red-cyan", "legacy_anaglyph");
    assert!(
        report.contains("glx_stereo 1 gl_stereo 1 framebuffer 0 draw_buffer 0x405 error 0x0"),
        "what the program saw: {report}"
    );
    // Red from the left eye, green and blue from the right, by hand.
    let want = [
        [51, 51, 51, 255], // background: grey in both eyes
        [0, 51, 51, 255],  // left blue rectangle: R 0 from the left, G B grey from the right
        [0, 0, 0, 255],    // overlap: left blue (R 0), right red (G B 0)
        [51, 0, 0, 255],   // right red rectangle: R grey from the left, G B 0
    ];
    for ((px, py), want) in sample_pixels().into_iter().zip(want) {
        assert_eq!(shot.get(px, py), want, "window pixel ({px},{py})");
    }
    // The capture holds the eyes as drawn, and the composite the window shows.
    let (left, right) = expected_eyes();
    for (px, py) in sample_pixels() {
        assert_eq!(
            common::png(&dir.join("left-000001.png")).get(px, py),
            left.get(px, py)
        );
        assert_eq!(
            common::png(&dir.join("right-000001.png")).get(px, py),
            right.get(px, py)
        );
    }
    assert_close(
        &common::png(&dir.join("composite-000001.png")),
        &shot,
        "capture vs window",
    );
}

#[test]
fn legacy_glx_program_window_matches_the_reference_composite_in_each_mode() {
    let x = Xvfb::start(640, 480);
    for (mode, name) in [
        (OutputMode::SideBySideHalf, "side-by-side-half"),
        (OutputMode::Rows, "rows"),
        (OutputMode::Columns, "columns"),
    ] {
        let (shot, dir, _) = run_legacy(&x, name, &format!("legacy_{name}"));
        // The eyes the program drew (checked against the seed's frame), and
        // the window against the CPU reference composite of them.
        let left = common::png(&dir.join("left-000001.png"));
        let right = common::png(&dir.join("right-000001.png"));
        let (want_l, want_r) = expected_eyes();
        for (px, py) in sample_pixels() {
            assert_eq!(left.get(px, py), want_l.get(px, py), "{name} left eye");
            assert_eq!(right.get(px, py), want_r.get(px, py), "{name} right eye");
        }
        let reference =
            glstereo::output::compose(mode, &OutputOptions::default(), &left, &right, 0).unwrap();
        assert_close(&shot, &reference, name);
        // And by hand: rows alternate eyes from the top row (left) down.
        if mode == OutputMode::Rows {
            let (lx, ly) = sample_pixels()[1]; // left rectangle only
            let even = ly & !1;
            assert_eq!(
                shot.get(lx, even),
                [0, 0, 255, 255],
                "rows: even row is left"
            );
            assert_eq!(
                shot.get(lx, even + 1),
                [51, 51, 51, 255],
                "rows: odd row is right"
            );
        }
    }
}

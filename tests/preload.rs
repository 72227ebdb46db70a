//! Unmodified GLX programs under glstereo-run on a real X server (Xvfb):
//! a legacy stereo program and a freeglut GLUT_STEREO program show the
//! composite of their two eyes in their windows (read back from the server
//! as a screenshot would), their captures hold the eyes they drew, and a
//! mono program is untouched.

mod common;

use std::path::PathBuf;
use std::process::Command;

use common::preload::{Running, Screen, built, compile_plain, grab_ready};
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

/// How a test finds the program's window.
#[derive(Clone, Copy)]
enum Window {
    /// The program prints "ready 0x<id>".
    Printed,
    /// The top-level window with this title.
    Titled(&'static str),
}

/// Runs `exe args` under glstereo-run in `mode` (and with `flags`) with a
/// capture directory; returns the window as the server shows it, the
/// capture directory, and the program's first report line.
fn run_under_layer(
    x: &Xvfb,
    (exe, args): (&std::path::Path, &[String]),
    window: Window,
    (mode, flags): (&str, &[&str]),
    capture: &str,
) -> (Image, PathBuf, String) {
    let dir = common::scratch(capture);
    let mut cmd = Command::new(&built().run);
    cmd.args(["-m", mode])
        .args(flags)
        .arg("--capture")
        .arg(&dir)
        .arg(exe)
        .args(args)
        .env("DISPLAY", &x.display);
    let mut p = Running::start(cmd);
    let id = p.ready();
    let screen = Screen::open(&x.display);
    let window = match window {
        Window::Printed => u64::from_str_radix(id.trim_start_matches("0x"), 16).expect("window id"),
        Window::Titled(t) => screen
            .find_window(t)
            .unwrap_or_else(|| panic!("no window titled {t}")),
    };
    let shot = screen.grab(window);
    let report = p.stdout.first().cloned().unwrap_or_default();
    let stderr = p.finish();
    assert!(
        !stderr.contains("glstereo:"),
        "the layer complained: {stderr}"
    );
    (shot, dir, report)
}

fn run_legacy(x: &Xvfb, mode: &str, capture: &str) -> (Image, PathBuf, String) {
    let exe = program("legacy_stereo", &["-lGL", "-lX11"]);
    let size = [W.to_string(), H.to_string()];
    run_under_layer(x, (&exe, &size), Window::Printed, (mode, &[]), capture)
}

fn run_glut(x: &Xvfb, mode: &str, capture: &str) -> (Image, PathBuf, String) {
    let exe = program("glut_stereo", &["-lglut", "-lGL"]);
    run_under_layer(
        x,
        (&exe, &[]),
        Window::Titled("glut_stereo"),
        (mode, &[]),
        capture,
    )
}

/// The capture's eyes are the RedBlue eyes, and the window is the CPU
/// reference composite of them in `mode`.
fn check_mode(shot: &Image, dir: &std::path::Path, mode: OutputMode, what: &str) {
    let left = common::png(&dir.join("left-000001.png"));
    let right = common::png(&dir.join("right-000001.png"));
    let (want_l, want_r) = expected_eyes();
    for (px, py) in sample_pixels() {
        assert_eq!(left.get(px, py), want_l.get(px, py), "{what}: left eye");
        assert_eq!(right.get(px, py), want_r.get(px, py), "{what}: right eye");
    }
    let reference =
        glstereo::output::compose(mode, &OutputOptions::default(), &left, &right, 0).unwrap();
    assert_close(shot, &reference, what);
    assert_close(
        &common::png(&dir.join("composite-000001.png")),
        shot,
        &format!("{what}: captured composite vs window"),
    );
}

/// The three modes every program is checked in, and a hand-made check of each.
const MODES: [(OutputMode, &str); 3] = [
    (
        OutputMode::Anaglyph(
            glstereo::output::AnaglyphColors::RedCyan,
            glstereo::output::AnaglyphMethod::FullColor,
        ),
        "anaglyph-red-cyan",
    ),
    (OutputMode::SideBySideHalf, "side-by-side-half"),
    (OutputMode::Rows, "rows"),
];

/// What a person checks on the screen, computed by hand from the RedBlue
/// frame (not from the library).
fn check_by_hand(shot: &Image, mode: OutputMode, what: &str) {
    let s = sample_pixels();
    match mode {
        OutputMode::Rows => {
            // Rows alternate eyes from the top row (left) down.
            let (lx, ly) = s[1]; // left rectangle only
            let even = ly & !1;
            assert_eq!(
                shot.get(lx, even),
                [0, 0, 255, 255],
                "{what}: even row is left"
            );
            assert_eq!(
                shot.get(lx, even + 1),
                [51, 51, 51, 255],
                "{what}: odd row is right"
            );
        }
        OutputMode::SideBySideHalf => {
            // Left half: the left eye squeezed; its blue square spans x
            // -0.8..0.2 of the eye, so -0.9..-0.4 of the window.
            let at = |nx: f64, ny: f64| {
                shot.get(
                    ((nx + 1.0) / 2.0 * W as f64) as u32,
                    ((1.0 - ny) / 2.0 * H as f64) as u32,
                )
            };
            assert_eq!(
                at(-0.65, -0.5),
                [0, 0, 255, 255],
                "{what}: left eye in the left half"
            );
            assert_eq!(
                at(0.75, 0.5),
                [255, 0, 0, 255],
                "{what}: right eye in the right half"
            );
            assert_eq!(
                at(0.75, -0.5),
                [51, 51, 51, 255],
                "{what}: right eye background"
            );
        }
        _ => {
            // Red from the left eye, green and blue from the right.
            let want = [
                [51, 51, 51, 255], // background: grey in both eyes
                [0, 51, 51, 255],  // left blue rectangle: R 0 (left), G B grey (right)
                [0, 0, 0, 255],    // overlap: left blue (R 0), right red (G B 0)
                [51, 0, 0, 255],   // right red rectangle: R grey (left), G B 0
            ];
            for ((px, py), want) in s.into_iter().zip(want) {
                assert_eq!(shot.get(px, py), want, "{what}: window pixel ({px},{py})");
            }
        }
    }
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
fn legacy_glx_program_shows_its_two_eyes_in_each_mode() {
    let x = Xvfb::start(640, 480);
    for (mode, name) in MODES {
        let (shot, dir, report) = run_legacy(&x, name, &format!("legacy_{name}"));
        assert!(
            report.contains("glx_stereo 1 gl_stereo 1 framebuffer 0 draw_buffer 0x405 error 0x0"),
            "what the program saw: {report}"
        );
        check_by_hand(&shot, mode, name);
        check_mode(&shot, &dir, mode, name);
    }
}

#[test]
fn freeglut_stereo_program_shows_its_two_eyes_in_each_mode() {
    let x = Xvfb::start(640, 480);
    for (mode, name) in MODES {
        let (shot, dir, report) = run_glut(&x, name, &format!("glut_{name}"));
        assert!(
            report.contains("gl_stereo 1 glut_window_stereo 1 error 0x0"),
            "what the program saw: {report}"
        );
        check_by_hand(&shot, mode, name);
        check_mode(&shot, &dir, mode, name);
    }
}

#[test]
fn draw_buffer_rules_hold_through_the_layer_on_stereo_visuals() {
    let x = Xvfb::start(320, 240);
    let exe = program("glx_draw_buffers", &["-lGL", "-lX11"]);
    // glXChooseVisual visuals (double and single), and a core-profile
    // context of a glXChooseFBConfig configuration.
    for (what, at_least) in [("stereo", 150), ("core", 100)] {
        let out = common::run_ok(
            Command::new(&built().run)
                .arg(&exe)
                .arg(what)
                .env("DISPLAY", &x.display),
        );
        let stdout = String::from_utf8_lossy(&out.stdout);
        let (summary, passed) = common::summary(&stdout);
        assert!(
            summary.ends_with(" passed, 0 failed") && passed > at_least,
            "{what}: {summary}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// Runs `exe` (which prints "ready 0x<window>") with or without the layer;
/// returns its window and its report line.
fn run_mono(x: &Xvfb, layer: Option<&std::path::Path>) -> (Image, String) {
    let exe = program("mono_glx", &["-lGL", "-lX11"]);
    let mut cmd = match layer {
        Some(capture) => {
            let mut c = Command::new(&built().run);
            c.arg("--capture").arg(capture).arg(&exe);
            c
        }
        None => Command::new(&exe),
    };
    cmd.env("DISPLAY", &x.display);
    let (shot, report, stderr) = grab_ready(cmd, &x.display);
    assert!(stderr.is_empty(), "stderr: {stderr}");
    (shot, report)
}

#[test]
fn a_mono_program_runs_as_it_would_without_the_layer() {
    let x = Xvfb::start(320, 240);
    let capture = common::scratch("mono_capture");
    let (without, report_without) = run_mono(&x, None);
    let (with, report_with) = run_mono(&x, Some(&capture));
    assert_eq!(
        report_without, "stereo 0 draw_buffer 0x405 read_buffer 0x405 framebuffer 0 error 0x0",
        "the driver's own answers"
    );
    assert_eq!(
        report_with, report_without,
        "what GL reports under the layer"
    );
    assert_eq!(
        with.max_difference(&without).map(|d| d.0),
        Some(0),
        "the window differs under the layer (difference, x, y, channel): {:?}",
        with.max_difference(&without)
    );
    // The picture is not trivial (the test would catch a blank window).
    assert_ne!(with.get(40, 90), with.get(150, 5));
    // No stereo: nothing presented by the layer, nothing captured.
    assert_eq!(std::fs::read_dir(&capture).unwrap().count(), 0);

    // GL's answers for the draw-buffer probes on mono visuals are the
    // driver's, byte for byte (Mesa's single-buffered windows even accept
    // GL_BACK, which the GL rules forbid: the layer leaves that alone).
    let exe = program("glx_draw_buffers", &["-lGL", "-lX11"]);
    let plain = common::run_ok(Command::new(&exe).arg("mono").env("DISPLAY", &x.display));
    let layered = common::run_ok(
        Command::new(&built().run)
            .arg(&exe)
            .arg("mono")
            .env("DISPLAY", &x.display),
    );
    let (plain, layered) = (
        String::from_utf8_lossy(&plain.stdout),
        String::from_utf8_lossy(&layered.stdout),
    );
    assert!(plain.lines().count() > 50, "{plain}");
    assert_eq!(layered, plain);
}

/// A stereo visual without alpha under the layer answers alpha exactly as
/// Mesa's mono visual without alpha does: reads of 1.0 after clears,
/// draws, blits (under GL_RASTERIZER_DISCARD too) and
/// glClearBuffer/glClearNamedFramebuffer, blending with a destination
/// alpha of 1.0, GL_COLOR_WRITEMASK as the program set it (with
/// glColorMask, glColorMaski or its extension names; read by any glGet),
/// and the clear colour as any setter set it (the layer keeps its eyes in
/// RGBA8 and never lets alpha be written).
#[test]
fn a_visual_without_alpha_reads_alpha_one_as_mesa_does() {
    let x = Xvfb::start(320, 240);
    let exe = program("glx_opaque_alpha", &["-lGL", "-lX11"]);
    let plain = common::run_ok(Command::new(&exe).arg("mono").env("DISPLAY", &x.display));
    let layered = common::run_ok(
        Command::new(&built().run)
            .arg(&exe)
            .arg("stereo")
            .env("DISPLAY", &x.display),
    );
    let (plain, layered) = (
        String::from_utf8_lossy(&plain.stdout),
        String::from_utf8_lossy(&layered.stdout),
    );
    // Mesa's reference is a visual without alpha, whose alpha reads 1.0.
    assert!(plain.starts_with("alpha_bits 0\n"), "{plain}");
    let line = |out: &str, what: &str| -> String {
        out.lines()
            .find(|l| l.starts_with(&format!("{what} ")))
            .unwrap_or_else(|| panic!("no line {what:?} in\n{out}"))
            .to_string()
    };
    for what in [
        "clear 0.25",
        "draw alpha 0.3",
        "blit into fb0",
        "named blit into fb0",
    ] {
        assert!(
            line(&layered, what).contains(" 255 alpha 1.000 error 0x0"),
            "{layered}"
        );
    }
    assert!(
        line(&layered, "fbo clear 0.5").contains(" 128 alpha 0.502"),
        "{layered}"
    );
    assert!(
        line(&layered, "fb0 1110").contains("writemask 1110 int 1110"),
        "{layered}"
    );
    assert!(
        line(&layered, "blend dst_alpha").contains("rgba 255 255 255 255"),
        "{layered}"
    );
    assert!(
        line(&layered, "blend one_minus_dst_alpha").contains("rgba 51 102 153 255"),
        "{layered}"
    );
    // The other names of glColorMaski keep alpha 1.0 and answer as set.
    for what in [
        "glColorMaskIndexedEXT",
        "glColorMaskiEXT",
        "glColorMaskiOES",
    ] {
        let lines: Vec<&str> = layered
            .lines()
            .filter(|l| l.starts_with(&format!("{what} ")))
            .collect();
        assert_eq!(
            lines,
            [
                format!("{what} writemask 1011 int 1011 index1 0111 error 0x0"),
                format!("{what} rgba 255 102 255 255 alpha 1.000 error 0x0"),
            ],
            "{layered}"
        );
    }
    assert!(
        line(&layered, "fb0 queries glGetInteger64i_v 1").ends_with(" 0101"),
        "{layered}"
    );
    assert!(
        line(&layered, "fb0 queries glGetFloatv").contains("glGetInteger64v 1011"),
        "{layered}"
    );
    // Rasterizer discard: the blit lands, alpha stays 1.0.
    assert!(
        line(&layered, "blit under rasterizer discard").contains("rgba 255 0 128 255"),
        "{layered}"
    );
    assert!(
        line(&layered, "fb0 clear after glClearColorIuiEXT").contains("rgba 128 255 64 255"),
        "{layered}"
    );
    assert_eq!(layered, plain);
}

/// A visual's depth bits are the depth buffer's: a stereo program on a
/// GLX_STEREO configuration of 16, 24 or 32 depth bits (or 24 and 8 of
/// stencil), and a mono one under `--auto=depth`, get GL_DEPTH_BITS,
/// depths read back in every type, stencil and the depth test's verdict
/// on surfaces a step of precision apart, bit for bit as Mesa's
/// framebuffer object of the same formats gives them
/// (tests/c/glx_depth_bits.c). Mesa's own window of that configuration
/// answers the same but for interpolated depths of a slanted surface, in
/// the last bit of the visual's precision (of a 32-bit one: of the float
/// depth is interpolated in): it rasterizes windows top down and
/// framebuffer objects bottom up.
#[test]
fn a_visuals_depth_bits_are_stored_tested_and_read_back_as_mesa_stores_them() {
    let x = Xvfb::start(320, 240);
    let exe = program("glx_depth_bits", &["-lGL", "-lX11"]);
    let stdout = |out: std::process::Output| String::from_utf8_lossy(&out.stdout).into_owned();
    for bits in ["16", "24", "32", "24s8"] {
        let mesa = |how: &str| {
            stdout(common::run_ok(
                Command::new(&exe)
                    .args([how, bits])
                    .env("DISPLAY", &x.display),
            ))
        };
        let (fbo, window) = (mesa("fbo"), mesa("mono"));
        let (depth, stencil) = bits.split_once('s').unwrap_or((bits, "0"));
        assert!(
            fbo.starts_with(&format!("depth_bits {depth} stencil_bits {stencil}\n")),
            "{bits}: {fbo}"
        );
        for (how, args) in [
            ("a stereo configuration", vec!["stereo"]),
            ("--auto=depth", vec!["--auto=depth", "mono"]),
        ] {
            let mut c = Command::new(&built().run);
            c.args(&args[..args.len() - 1])
                .arg(&exe)
                .args([args[args.len() - 1], bits]);
            let ours = stdout(common::run_ok(c.env("DISPLAY", &x.display)));
            assert_eq!(
                ours, fbo,
                "{bits}, {how}: the layer, then Mesa's framebuffer object"
            );
        }
        // Mesa's window: the same lines, a slanted depth within one step
        // (of 32 bits: of the float llvmpipe interpolates depth in).
        let step = match depth {
            "16" => 1u64 << 16,
            _ => 1 << 8,
        };
        assert_eq!(fbo.lines().count(), window.lines().count(), "{bits}");
        for (f, w) in fbo.lines().zip(window.lines()) {
            let uint = |l: &str| -> Option<u64> {
                let words: Vec<&str> = l.split(' ').collect();
                (words[0] == "depth").then(|| words[4].parse().unwrap())
            };
            match (uint(f), uint(w)) {
                (Some(a), Some(b)) => assert!(
                    a.abs_diff(b) <= step,
                    "{bits}: {f} (framebuffer object), {w} (window)"
                ),
                _ => assert_eq!(f, w, "{bits}: framebuffer object, window"),
            }
        }
    }
}

/// Runs `legacy_stereo` at 160x120 under the layer (rows, captured), sends
/// it `commands` (each answered by a redrawn frame), and checks that the
/// window then shows frame `frame` (counted from 0) of the capture, whose
/// eyes are the window's new 200x90, composed. Returns those eyes.
fn resized_legacy(name: &str, commands: &[&str], frame: u64, what: &str) -> (Image, Image) {
    let x = Xvfb::start(640, 480);
    let exe = program("legacy_stereo", &["-lGL", "-lX11"]);
    let dir = common::scratch(name);
    let mut cmd = Command::new(&built().run);
    cmd.args(["-m", "rows", "--capture"])
        .arg(&dir)
        .arg(&exe)
        .args(["160", "120"])
        .env("DISPLAY", &x.display);
    let mut p = Running::start(cmd);
    let id = p.ready();
    let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).unwrap();
    for command in commands {
        p.send(command);
        p.ready();
    }
    let shot = Screen::open(&x.display).grab(window);
    let stderr = p.finish();
    glstereo::capture::write_png(&shot, &dir.join("window.png")).unwrap();
    assert!(!stderr.contains("glstereo:"), "{stderr}");
    assert_eq!((shot.width(), shot.height()), (200, 90));
    let left = common::png(&dir.join(format!("left-{:06}.png", frame + 1)));
    let right = common::png(&dir.join(format!("right-{:06}.png", frame + 1)));
    assert_eq!(
        (left.width(), left.height()),
        (200, 90),
        "{what}: the eyes are the window's new size"
    );
    let reference = glstereo::output::compose(
        OutputMode::Rows,
        &OutputOptions::default(),
        &left,
        &right,
        frame,
    )
    .unwrap();
    assert_close(&shot, &reference, what);
    (left, right)
}

#[test]
fn the_stereo_buffers_follow_a_resized_window() {
    // The program resizes its window and redraws (its reshape sets the viewport).
    let (left, right) =
        resized_legacy("legacy_resize", &["resize 200 90"], 1, "the resized window");
    // The second frame fills the new window: the left eye's blue square
    // spans x 10%..60% and y 40%..90% of it.
    assert_eq!(
        left.get(70, 60),
        [0, 0, 255, 255],
        "left eye at the new size"
    );
    assert_eq!(
        right.get(150, 20),
        [255, 0, 0, 255],
        "right eye at the new size"
    );
}

/// A window resized behind the program's back (no reshape handler, no
/// glViewport): the frame presented then may still be of the old size, but
/// the stereo buffers follow by the next one, which the window shows
/// composed at the new size.
#[test]
fn the_stereo_buffers_follow_a_window_resized_behind_the_programs_back() {
    // Same size again the second time: no change, one more frame.
    let (left, right) = resized_legacy(
        "legacy_wm_resize",
        &["wmresize 200 90", "wmresize 200 90"],
        2,
        "the window resized behind the program's back",
    );
    // The viewport stayed 160x120 at the bottom left: the left eye's blue
    // rectangle spans x 16..96 and y 12..72 of it (GL coordinates), so
    // image row 90 - 1 - 40 = 49 at x 50 is blue; the right eye's red one
    // spans x 64..144, y 48..108: row 90 - 1 - 80 = 9 at x 120 is red.
    assert_eq!(left.get(50, 49), [0, 0, 255, 255], "left eye");
    assert_eq!(right.get(120, 9), [255, 0, 0, 255], "right eye");
}

/// A program that resizes its own window and draws without a glViewport
/// (a fixed viewport; its clear ignores the viewport) gets its very next
/// frame at the new size, as Mesa's own software framebuffer gives it (the
/// size is taken at the first draw after a swap): the frame presented
/// right after the resize is the window's size, cleared all over.
#[test]
fn a_window_resized_before_the_next_draw_gets_that_frame_at_its_new_size() {
    let (left, right) = resized_legacy(
        "legacy_wm_resize_once",
        &["wmresize 200 90"],
        1,
        "the frame drawn right after the resize",
    );
    // glClear covered the whole new window (grey 0.2), beyond the old
    // 160x120 viewport at the bottom left: top right corner.
    for (eye, img) in [("left", &left), ("right", &right)] {
        assert_eq!(img.get(195, 3), [51, 51, 51, 255], "{eye} eye's clear");
    }
    assert_eq!(left.get(50, 49), [0, 0, 255, 255], "left eye");
    assert_eq!(right.get(120, 9), [255, 0, 0, 255], "right eye");
}

/// Swapping a window the program destroyed: the layer warns, and no X
/// error of its requests reaches the program's default (fatal) handler.
#[test]
fn swapping_a_destroyed_window_is_a_warning_not_an_x_error() {
    let x = Xvfb::start(320, 240);
    let exe = program("swap_after_destroy", &["-lGL", "-lX11"]);
    let out = common::run_ok(
        Command::new(&built().run)
            .arg(&exe)
            .env("DISPLAY", &x.display),
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stdout.trim(), "survived", "{stderr}");
    assert!(!stderr.contains("X Error"), "{stderr}");
    assert!(
        stderr.contains("glstereo: presenting the stereo frame") && stderr.contains("destroyed"),
        "the layer says why nothing was shown: {stderr}"
    );
}

#[test]
fn a_single_buffered_stereo_program_is_shown_when_it_flushes() {
    let x = Xvfb::start(640, 480);
    let exe = program("legacy_stereo", &["-lGL", "-lX11"]);
    let args = [W.to_string(), H.to_string(), "single".to_owned()];
    let (shot, _, report) = run_under_layer(
        &x,
        (&exe, &args),
        Window::Printed,
        ("anaglyph-red-cyan", &[]),
        "legacy_single",
    );
    assert!(
        report.contains("glx_stereo 1 gl_stereo 1 framebuffer 0 draw_buffer 0x404 error 0x0"),
        "{report}"
    );
    check_by_hand(&shot, MODES[0].0, "single-buffered anaglyph");
}

#[test]
fn capture_format_writes_stereo_photos_of_every_frame_beside_the_pngs() {
    use common::photo::{mean_error, pillow};
    let x = Xvfb::start(640, 480);
    let exe = program("legacy_stereo", &["-lGL", "-lX11"]);
    let size = [W.to_string(), H.to_string()];
    // Without and with --swap-eyes: the PNG eyes are the buffers as drawn,
    // the stereo photos hold the eyes as a viewer sees them.
    for swap in [false, true] {
        let mut flags = vec!["--capture-format", "png,mpo,jps", "-q", "95"];
        if swap {
            flags.push("--swap-eyes");
        }
        let (_, dir, _) = run_under_layer(
            &x,
            (&exe, &size),
            Window::Printed,
            ("rows", &flags),
            &format!("capture_photos_swap_{swap}"),
        );
        let mut frames: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| {
                let name = e.unwrap().file_name().to_string_lossy().into_owned();
                Some(name.strip_prefix("left-")?.strip_suffix(".png")?.to_owned())
            })
            .collect();
        frames.sort();
        assert!(!frames.is_empty(), "no frame captured in {}", dir.display());
        for n in &frames {
            let drawn_left = common::png(&dir.join(format!("left-{n}.png")));
            let drawn_right = common::png(&dir.join(format!("right-{n}.png")));
            let (left, right) = if swap {
                (drawn_right, drawn_left)
            } else {
                (drawn_left, drawn_right)
            };
            let what = format!("stereo-{n}, swap {swap}");
            let (format, count, images) = pillow(&dir.join(format!("stereo-{n}.mpo")));
            assert_eq!((format.as_str(), count), ("MPO", 2), "{what}.mpo");
            let errors = [
                mean_error(&images[0].2, W, 0, &left),
                mean_error(&images[1].2, W, 0, &right),
            ];
            assert!(
                errors.iter().all(|e| *e < 3.0),
                "{what}.mpo vs the eyes: {errors:?}"
            );
            let (_, _, jps) = pillow(&dir.join(format!("stereo-{n}.jps")));
            let (w, h, rgb) = &jps[0];
            assert_eq!((*w, *h), (2 * W, H));
            let errors = [
                mean_error(rgb, 2 * W, 0, &right),
                mean_error(rgb, 2 * W, W, &left),
            ];
            assert!(
                errors.iter().all(|e| *e < 3.0),
                "{what}.jps (right eye on the left) vs the eyes: {errors:?}"
            );
            // The RedBlue eyes differ: swapped halves would not match.
            assert!(mean_error(rgb, 2 * W, 0, &left) > 10.0, "{what}.jps");
            assert!(mean_error(&images[0].2, W, 0, &right) > 10.0, "{what}.mpo");
        }
    }
}

#[test]
fn glstereo_run_checks_its_options_before_the_program_starts_and_sets_the_environment() {
    let dir = common::scratch("glstereo_run_options");
    let marker = dir.join("ran");
    let touch = format!("touch '{}'", marker.display());
    // A mode that does not exist: exit 2, the valid names, the program never runs.
    let out = Command::new(&built().run)
        .args(["-m", "nonsense", "sh", "-c", &touch])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("unknown output mode \"nonsense\"") && stderr.contains("side-by-side-half"),
        "{stderr}"
    );
    assert!(!marker.exists(), "the program must not run");
    // A bad setting in the environment is caught the same way.
    let out = Command::new(&built().run)
        .args(["sh", "-c", &touch])
        .env("GLSTEREO_SWAP_EYES", "maybe")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("GLSTEREO_SWAP_EYES"));
    assert!(!marker.exists());
    // A capture format that does not exist, a quality out of range, and
    // capture settings without a capture directory.
    for (args, want) in [
        (&["-c", "x", "-f", "gif"][..], "png, jps or mpo"),
        (
            &["-c", "x", "--jpeg-quality=0"][..],
            "1 (smallest file) to 100",
        ),
        (&["--capture-format", "mpo"][..], "give --capture DIR too"),
        // Options that take no value refuse one given with `=`, and
        // --auto takes only its two kinds.
        (
            &["--auto=bogus"][..],
            "--auto=bogus is not a kind of automatic stereo",
        ),
        (&["--auto=0"][..], "--auto=geometry or --auto=depth"),
        (&["--swap-eyes=1"][..], "--swap-eyes takes no value"),
        (&["--verbose=yes"][..], "--verbose takes no value"),
        (&["--help=me"][..], "--help takes no value"),
        (&["--version=2"][..], "--version takes no value"),
    ] {
        let out = Command::new(&built().run)
            .args(args)
            .args(["sh", "-c", &touch])
            .current_dir(&dir)
            .env_remove("GLSTEREO_CAPTURE_DIR")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(want), "{args:?}: {stderr}");
        assert!(!marker.exists(), "{args:?}: the program must not run");
    }
    // No program; a program that does not exist.
    let out = Command::new(&built().run)
        .args(["-m", "rows"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = Command::new(&built().run)
        .arg(dir.join("no-such-program"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(127));
    // A program that exists but cannot be executed (no x bit; refused even
    // to root): 126, as the manual's EXIT STATUS says.
    let not_executable = dir.join("not-executable");
    std::fs::write(&not_executable, "#!/bin/sh\n").unwrap();
    let out = Command::new(&built().run)
        .arg(&not_executable)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(126),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    // What the program gets: the preload library first (an existing
    // LD_PRELOAD kept after it), the canonical mode, swap, the capture
    // directory (made, absolute).
    let capture = dir.join("frames");
    let out = common::run_ok(
        Command::new(&built().run)
            .args(["-st", "rc", "--swap-eyes", "--capture"])
            .arg(&capture)
            .args(["-f", "mpo,png", "-q", "80"])
            .args([
                "sh",
                "-c",
                "echo \"$LD_PRELOAD|$GLSTEREO_MODE|$GLSTEREO_SWAP_EYES|$GLSTEREO_CAPTURE_DIR\
                 |$GLSTEREO_CAPTURE_FORMAT|$GLSTEREO_JPEG_QUALITY\"",
            ])
            .env("LD_PRELOAD", "libother.so"),
    );
    let line = String::from_utf8_lossy(&out.stdout).trim().to_owned();
    let want = format!(
        "{}:libother.so|anaglyph-red-cyan|1|{}|mpo,png|80",
        built().preload.canonicalize().unwrap().display(),
        capture.canonicalize().unwrap().display()
    );
    assert_eq!(line, want);
}

/// The distinct memfd files named "glstereo eye" that process `pid` maps:
/// eye textures whose storage the layer reads in place.
fn eye_memory_files(pid: u32) -> usize {
    let maps = std::fs::read_to_string(format!("/proc/{pid}/maps")).expect("maps");
    let inodes: std::collections::HashSet<&str> = maps
        .lines()
        .filter(|l| l.contains("/memfd:glstereo eye"))
        .filter_map(|l| l.split_whitespace().nth(4))
        .collect();
    inodes.len()
}

/// On llvmpipe (every machine this project runs on has no GPU) the four
/// colour buffers of a double-buffered stereo window are memory the layer
/// maps and composes from in place; with GLSTEREO_EYE_MEMORY=0 they are
/// ordinary textures read back. The window shows the same pixels either
/// way, in a channel-mask mode (anaglyph) and a copy mode (left), and a
/// resize (which replaces storage from memory) keeps both eyes right.
#[test]
fn the_eyes_are_composed_where_llvmpipe_drew_them() {
    let x = Xvfb::start(320, 240);
    let exe = program("legacy_stereo", &["-lGL", "-lX11"]);
    for (mode, name) in [
        (MODES[0].0, "anaglyph-red-cyan"),
        (OutputMode::Left, "left"),
    ] {
        let mut shots = Vec::new();
        for in_place in [true, false] {
            let dir = common::scratch(&format!("in-place-{name}-{in_place}"));
            let mut cmd = Command::new(&built().run);
            cmd.args(["-m", name, "--capture"])
                .arg(&dir)
                .arg(&exe)
                .args([W.to_string(), H.to_string()])
                .env("DISPLAY", &x.display);
            if !in_place {
                cmd.env("GLSTEREO_EYE_MEMORY", "0");
            }
            let mut p = Running::start(cmd);
            let id = p.ready();
            let files = eye_memory_files(p.pid());
            let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).unwrap();
            let shot = Screen::open(&x.display).grab(window);
            let stderr = p.finish();
            assert!(!stderr.contains("glstereo:"), "{name}: {stderr}");
            let what = format!("{name}, in place {in_place}");
            assert_eq!(
                files,
                if in_place { 4 } else { 0 },
                "{what}: eye buffers in memory files"
            );
            check_mode(&shot, &dir, mode, &what);
            shots.push(shot);
        }
        assert_close(
            &shots[0],
            &shots[1],
            &format!("{name}: in place vs read back"),
        );
    }
}

/// `--auto`, `--auto=geometry` and `--auto=depth` reach the program as
/// `GLSTEREO_AUTO` (the layer reads its kind from there).
#[test]
fn glstereo_run_passes_the_kind_of_automatic_stereo_on() {
    for (flag, want) in [
        ("--auto", "geometry"),
        ("-a", "geometry"),
        ("--auto=geometry", "geometry"),
        ("--auto=depth", "depth"),
        ("--auto=DEPTH", "depth"),
    ] {
        let out = common::run_ok(Command::new(&built().run).args([
            flag,
            "sh",
            "-c",
            "echo \"$GLSTEREO_AUTO\"",
        ]));
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_eq!(stdout.trim(), want, "{flag}");
    }
}

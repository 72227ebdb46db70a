//! Real clients under glstereo-run, each unmodified, on a private Xvfb:
//! programs written on Debian's own toolkits (GLFW 3.3, SDL2, PyOpenGL +
//! freeglut, libepoxy, Qt 5, Qt 6), OpenSceneGraph's osgshape and Mesa's glxgears, each
//! finding GL the way its toolkit does (a direct link, dlopen + dlsym,
//! ctypes, glXGetProcAddress). Each must get stereo, land each eye's
//! clears and draws in that eye's buffers, and show both eyes in its window
//! in `side-by-side` (read back with XGetImage, checked half by half).
//!
//! Also: the loader's answers to bad input are the same with and without
//! the layer (dl_probe.c). Other GL layers stacked with glstereo are
//! tests/stacking.rs.
//!
//! The programs are in tests/clients/ (their headers say what they print).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::clients::*;
use common::preload::{Screen, built};
use common::xvfb::Xvfb;
use glstereo::image::Image;

#[test]
fn glfw_core_profile_stereo_window_shows_both_eyes() {
    let exe = c_client("glfw_stereo", &["-lglfw"]);
    check_layered(&exe, &[], "glfw_stereo", "GLFW 3.3 core");
}

#[test]
fn a_mono_glfw_program_runs_as_without_the_layer() {
    // GLFW dlopens libGL: under the layer it gets the layer's stubs, and a
    // program that never asks for stereo must see the driver's answers.
    let x = Xvfb::start(320, 240);
    let exe = c_client("glfw_stereo", &["-lglfw"]);
    let mut plain = Command::new(&exe);
    plain.arg("mono").env("DISPLAY", &x.display);
    let without = run_client(&x, plain, "glfw_stereo");
    let with = run_client(&x, under_layer(&x, &exe, &["mono"]), "glfw_stereo");
    assert!(
        without
            .lines
            .iter()
            .any(|l| l == "report gl_stereo 0 toolkit_stereo 0 error 0x0"),
        "{:?}",
        without.lines
    );
    for l in without
        .lines
        .iter()
        .filter(|l| l.starts_with("pixel BACK "))
    {
        let n: Vec<u32> = l
            .split_whitespace()
            .skip(2)
            .map(|v| v.parse().unwrap())
            .collect();
        let want = eye_colour(true, n[0], n[1]);
        assert_eq!([n[2] as u8, n[3] as u8, n[4] as u8], want, "{l}");
    }
    assert_eq!(with.lines, without.lines, "what the program saw");
    assert_eq!(
        with.shot.max_difference(&without.shot).map(|d| d.0),
        Some(0),
        "the window differs under the layer (difference, x, y, channel): {:?}",
        with.shot.max_difference(&without.shot)
    );
    // Not a blank window: the left eye's picture.
    assert_eq!(with.shot.get(40, 30), [0, 255, 0, 255]);
    assert_eq!(with.shot.get(80, 60), [255, 0, 0, 255]);
}

#[test]
fn sdl2_default_context_stereo_window_shows_both_eyes() {
    let exe = c_client("sdl_stereo", &["-lSDL2"]);
    check_layered(&exe, &["default"], "sdl_stereo", "SDL2 default context");
}

#[test]
fn sdl2_core_3_2_context_stereo_window_shows_both_eyes() {
    let exe = c_client("sdl_stereo", &["-lSDL2"]);
    check_layered(&exe, &["core"], "sdl_stereo", "SDL2 3.2 core");
}

#[test]
fn pyopengl_freeglut_stereo_window_shows_both_eyes() {
    let script = clients().join("pyopengl_stereo.py");
    check_layered(
        Path::new(PYTHON),
        &[script.to_str().unwrap()],
        "pyopengl_stereo",
        "PyOpenGL + freeglut",
    );
}

#[test]
fn libepoxy_glx_stereo_window_shows_both_eyes() {
    // GTK's GL loader: every GLX and GL call through epoxy's dispatch.
    let exe = c_client("epoxy_stereo", &["-lepoxy", "-lX11"]);
    check_layered(&exe, &[], "epoxy_stereo", "libepoxy");
}

#[test]
fn qt5_stereo_surface_format_shows_both_eyes() {
    check_layered(&qt_client(), &[], "qt_stereo", "Qt 5 QWindow");
}

/// A private shader cache directory for Qt (and Mesa): XDG_CACHE_HOME.
fn qt6_cache(name: &str) -> PathBuf {
    common::scratch(&format!("qt6-cache-{name}"))
}

/// `qt6_stereo MODE` with the shader cache in `cache`, Qt's cache log on.
fn qt6_command(mut cmd: Command, cache: &Path) -> Command {
    cmd.env("XDG_CACHE_HOME", cache)
        .env("QT_LOGGING_RULES", "qt.opengl.diskcache.debug=true");
    cmd
}

/// `qt6_stereo MODE` without the layer (Mesa's mono fallback), which fills
/// the shader cache `cache` with Mesa's program binaries: its stdout.
fn qt6_without_layer(x: &Xvfb, mode: &str, cache: &Path) -> String {
    let mut cmd = under_layer(x, &qt6_client(), &[mode]);
    // The same environment, without glstereo-run.
    let mut plain = Command::new(qt6_client());
    plain.arg(mode);
    for (k, v) in cmd.get_envs() {
        if let Some(v) = v {
            plain.env(k, v);
        }
    }
    plain.env_remove("LD_PRELOAD");
    let _ = &mut cmd;
    let out = common::run_ok(&mut qt6_command(plain, cache));
    let binaries = std::fs::read_dir(cache)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with("qtshadercache"))
        .flat_map(|d| std::fs::read_dir(d.path()).unwrap())
        .count();
    assert!(
        binaries > 0,
        "Qt cached no program binary without the layer:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The frame of qt6_stereo.cpp `window` at eye pixel (x, y): magenta
/// (drawn under GL_BACK, so in both eyes), a green square in the left eye
/// and a yellow one in the right, where eyes.h puts its squares.
fn qt6_eye_colour(left: bool, x: u32, y: u32) -> [u8; 3] {
    match (left, eye_colour(left, x, y)) {
        (true, [0, 255, 0]) => [0, 255, 0],
        (false, [255, 255, 0]) => [255, 255, 0],
        _ => [255, 0, 255],
    }
}

/// The line the layer says when it refuses a program binary.
const REFUSED: &str = "a program binary made without glstereo's copies";

/// qt6_stereo.cpp `window` under the layer with the shader cache `cache`:
/// stereo granted, both eyes' pixels (a draw under GL_BACK with the cached
/// program in both), the window side by side; its stderr.
fn qt6_window_shows_both_eyes(x: &Xvfb, cache: &Path, what: &str) -> String {
    let cmd = qt6_command(under_layer(x, &qt6_client(), &["window"]), cache);
    let out = run_client_saying(x, cmd, "qt6 stereo window", &[REFUSED]);
    let report = out.lines.iter().find(|l| l.starts_with("report "));
    assert_eq!(
        report.map(String::as_str),
        Some("report gl_stereo 1 toolkit_stereo 1 error 0x0"),
        "{what}: {:?}",
        out.lines
    );
    let pixels: Vec<&String> = out
        .lines
        .iter()
        .filter(|l| l.starts_with("pixel "))
        .collect();
    assert_eq!(pixels.len(), 12, "{what}: {:?}", out.lines);
    for l in pixels {
        let f: Vec<&str> = l.split_whitespace().collect();
        let n: Vec<u32> = f[2..].iter().map(|v| v.parse().unwrap()).collect();
        let want = qt6_eye_colour(f[1].ends_with("_LEFT"), n[0], n[1]);
        assert_eq!(
            [n[2] as u8, n[3] as u8, n[4] as u8],
            want,
            "{what}: {l} (the program's draw under GL_BACK must reach both eyes)\n{}",
            out.stderr
        );
    }
    check_side_by_side_of(&out.shot, what, qt6_eye_colour);
    out.stderr
}

#[test]
fn qt6_stereo_window_with_an_empty_shader_cache_shows_both_eyes() {
    let x = Xvfb::start(320, 240);
    let cache = qt6_cache("empty");
    let first = qt6_window_shows_both_eyes(&x, &cache, "Qt 6 QWindow, empty cache");
    assert!(
        first.contains("Program binary not in cache") && !first.contains(REFUSED),
        "{first}"
    );
    // The binary Qt cached under the layer loads under it.
    let second = qt6_window_shows_both_eyes(&x, &cache, "Qt 6 QWindow, its own cache");
    assert!(
        second.contains("Program binary received from cache") && !second.contains(REFUSED),
        "the layer's own program binary did not load from Qt's cache:\n{second}"
    );
}

#[test]
fn qt6_stereo_window_with_a_shader_cache_filled_without_the_layer_shows_both_eyes() {
    let x = Xvfb::start(320, 240);
    let cache = qt6_cache("filled");
    qt6_without_layer(&x, "window", &cache);
    let stderr = qt6_window_shows_both_eyes(&x, &cache, "Qt 6 QWindow, cache filled without");
    assert!(
        stderr.contains(REFUSED) && stderr.contains("Program binary failed to load"),
        "the binary Mesa cached without the copies was not refused:\n{stderr}"
    );
    // Qt cached the program it compiled instead: it loads now.
    let again = qt6_window_shows_both_eyes(&x, &cache, "Qt 6 QWindow, cache refilled");
    assert!(
        again.contains("Program binary received from cache") && !again.contains(REFUSED),
        "{again}"
    );
}

#[test]
fn qt6_opengl_widget_in_a_stereo_window_reads_its_framebuffer_object_as_mono() {
    let x = Xvfb::start(320, 240);
    let cache = qt6_cache("widget");
    let mesa = qt6_without_layer(&x, "widget", &cache);
    let paint = |lines: &[String]| {
        lines
            .iter()
            .find(|l| l.starts_with("paint "))
            .cloned()
            .unwrap_or_default()
    };
    let mesa_lines: Vec<String> = mesa.lines().map(str::to_owned).collect();
    assert_eq!(
        paint(&mesa_lines),
        "paint gl_stereo 0 gl_doublebuffer 0 fbo_bound 1",
        "Mesa's answer in paintGL"
    );
    let cmd = qt6_command(under_layer(&x, &qt6_client(), &["widget"]), &cache);
    let out = run_client_saying(&x, cmd, "qt6 stereo widget", &[REFUSED]);
    assert_eq!(
        paint(&out.lines),
        paint(&mesa_lines),
        "GL_STEREO / GL_DOUBLEBUFFER in paintGL, with Qt's framebuffer object bound"
    );
    assert!(
        out.lines
            .iter()
            .any(|l| l == "report toolkit_stereo 1 error 0x0"),
        "{:?}",
        out.lines
    );
    // Qt composes the widget into the stereo window: both eyes green.
    check_side_by_side_of(&out.shot, "Qt 6 QOpenGLWidget", |_, _, _| [0, 255, 0]);
}

#[test]
fn openscenegraph_quad_buffer_stereo_shows_two_different_eyes() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(640, 480);
    let mut cmd = under_layer(&x, Path::new("osgshape"), &[]);
    cmd.env("OSG_STEREO", "ON")
        .env("OSG_STEREO_MODE", "QUAD_BUFFER")
        .env("OSG_WINDOW", "0 0 320 240");
    let mut osg = Renderer::start(cmd, "osgshape");
    let screen = Screen::open(&x.display);
    // OSG's clear colour (0.2, 0.2, 0.4) and shapes in front of it.
    let background =
        |p: [u8; 4]| p[0].abs_diff(51) <= 2 && p[1].abs_diff(51) <= 2 && p[2].abs_diff(102) <= 2;
    let scene = |img: &Image| {
        let area = img.width() * img.height();
        let bg = count(img, background);
        bg > area / 4 && bg < area * 98 / 100
    };
    let (window, shot) = osg.picture(
        &screen,
        |s| s.find_class("osgViewer"),
        |shot| {
            let (l, r) = halves(shot);
            scene(&l) && scene(&r)
        },
    );
    let stderr = osg.quit(&screen, window);
    let _ = glstereo::capture::write_png(&shot, &common::scratch("osg").join("window.png"));
    assert_eq!((shot.width(), shot.height()), (320, 240));
    let (left, right) = halves(&shot);
    for (eye, img) in [("left", &left), ("right", &right)] {
        assert!(
            scene(img),
            "the {eye} half does not show OSG's scene on its background \
             ({} of {} pixels background)",
            count(img, background),
            img.width() * img.height()
        );
    }
    assert!(letterboxed(&shot), "the window is not a side-by-side frame");
    same_scene(&left, &right, |p| !background(p), "OSG");
    // OSG's left and right cameras see the shapes from two places.
    let d = differing(&left, &right);
    assert!(
        d > left.width() * left.height() / 100,
        "the halves are the same picture ({d} pixels differ): one eye shown twice"
    );
    assert!(!stderr.contains("glstereo:"), "{stderr}");
    assert!(!stderr.contains("Not able to create"), "{stderr}");
}

#[test]
fn glxgears_stereo_shows_two_different_eyes() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(640, 480);
    let cmd = under_layer(&x, Path::new("glxgears"), &["-stereo"]);
    let (shot, stderr) = gears_shown(&x, cmd, "glxgears -stereo");
    let _ = glstereo::capture::write_png(&shot, &common::scratch("glxgears").join("window.png"));
    let (left, right) = halves(&shot);
    assert!(gears_in(&left), "no gears in the left half");
    assert!(gears_in(&right), "no gears in the right half");
    assert!(letterboxed(&shot), "the window is not a side-by-side frame");
    same_scene(
        &left,
        &right,
        |p| p[0] > 90 && p[1] < 40 && p[2] < 40,
        "red gear",
    );
    same_scene(&left, &right, |p| p[1] > 90 && p[0] < 40, "green gear");
    same_scene(
        &left,
        &right,
        |p| p[2] > 90 && p[0] < 60 && p[1] < 60,
        "blue gear",
    );
    // glxgears draws each eye with its own frustum and camera offset.
    let d = differing(&left, &right);
    assert!(
        d > left.width() * left.height() / 100,
        "the halves are the same picture ({d} pixels differ): one eye shown twice"
    );
    assert!(!stderr.contains("glstereo:"), "{stderr}");
}

/// dl_probe's output, with or without the layer.
fn dl_probe(layered: bool, probe_layer: bool) -> String {
    let exe = c_client("dl_probe", &["-ldl"]);
    let mut cmd = if layered {
        let mut c = Command::new(&built().run);
        c.arg(&exe);
        c
    } else {
        Command::new(&exe)
    };
    if probe_layer {
        cmd.env("GLSTEREO_PROBE_LAYERED", "1");
    }
    let out = common::run_ok(&mut cmd);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

const GL_NAMES: [&str; 5] = [
    "libGL.so.1",
    "libGL.so",
    "libGLX.so.0",
    "libOpenGL.so.0",
    "by-path",
];

#[test]
fn loader_answers_to_bad_input_are_unchanged_by_the_layer() {
    let plain = dl_probe(false, false);
    // What glibc answers: another library opens and works; an unknown name
    // is NULL with dlerror set, on every handle; dlclose returns 0.
    for want in [
        "other-library 1 1 1",
        "other-handle-gl-name 1 1",
        "default-unknown 1 1",
        "next-unknown 1 1",
        "missing-library 1 1",
    ] {
        assert!(plain.lines().any(|l| l == want), "{want} in\n{plain}");
    }
    for name in GL_NAMES {
        for want in [
            format!("open {name} 1"),
            format!("unknown {name} 1 1"),
            format!("close {name} 0"),
        ] {
            assert!(plain.lines().any(|l| l == want), "{want} in\n{plain}");
        }
    }
    assert_eq!(
        dl_probe(true, false),
        plain,
        "the same answers under the layer"
    );
}

#[test]
fn dlopen_of_every_gl_library_name_reaches_the_layer() {
    let out = dl_probe(true, true);
    for name in GL_NAMES {
        let want = format!("layer {name} 1");
        assert!(
            out.lines().any(|l| l == want),
            "dlsym on dlopen(\"{name}\") does not give the layer's function:\n{out}"
        );
    }
}

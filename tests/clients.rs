//! Real clients under glstereo-run, each unmodified, on a private Xvfb:
//! programs written on Debian's own toolkits (GLFW 3.3, SDL2, PyOpenGL +
//! freeglut, libepoxy, Qt 5), OpenSceneGraph's osgshape and Mesa's glxgears, each
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

use std::path::Path;
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

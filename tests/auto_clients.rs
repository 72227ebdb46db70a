//! Programs from Debian, unmodified and mono, under `glstereo-run --auto`
//! (issue 23 item 6): glxgears without -stereo, osgviewer, a GLFW
//! core-profile program, PyOpenGL + freeglut and a Qt 5 QOpenGLWidget.
//! Each window is grabbed (XGetImage) in `side-by-side-half` — each eye
//! squeezed to half the width, at full height, left on the left — and
//! checked half by half: both halves show the scene, each object's
//! pixels in the right half are those of the left half moved along the
//! rows only (same rows, same counts, the same vertical centre), by the
//! parallax 3D Vision's rule gives its depth: s·(1 − C/w)·W eye pixels,
//! half that in the squeezed halves; near objects (w < C) move left, far
//! ones right, and a HUD (w = 1) stays put. Without --auto the same
//! program's window is what it is without the layer (one mono picture).
//!
//! The programs of tests/clients/*_depths.* draw one scene (their headers
//! say it): red at w 2, green at w 4, blue at w 8 and a white HUD bar.

mod common;
#[path = "common/parallax.rs"]
mod parallax;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::clients::*;
use common::preload::Screen;
use common::xvfb::Xvfb;
use glstereo::image::Image;

/// The largest separation: s = 0.07.
const SEPARATION: &str = "100";
const S: f64 = 0.07;

/// `glstereo-run --auto -m side-by-side-half --convergence C PROGRAM ARGS`
/// (`convergence` None: without --auto).
fn command(x: &Xvfb, convergence: Option<f64>, program: &Path, args: &[&str]) -> Command {
    command_in("--auto", x, convergence, program, args)
}

/// [`command`] in automatic mode `auto` (`--auto` or `--auto=depth`).
fn command_in(
    auto: &str,
    x: &Xvfb,
    convergence: Option<f64>,
    program: &Path,
    args: &[&str],
) -> Command {
    let c = convergence.map(|c| c.to_string());
    let mut options = vec!["-m", "side-by-side-half"];
    if let Some(c) = &c {
        options.extend([auto, "--separation", SEPARATION, "--convergence", c]);
    }
    under_layer_with(x, &options, program, args)
}

/// The two eyes of a `side-by-side-half` window: its left and right
/// halves, each W/2 x H.
fn eyes_of(shot: &Image) -> [Image; 2] {
    let (hw, h) = (shot.width() / 2, shot.height());
    [0, hw].map(|x0| Image::from_fn(hw, h, |x, y| shot.get(x0 + x, y)))
}

/// Saved beside the test binary for a person looking into a failure.
fn keep(shot: &Image, name: &str) -> PathBuf {
    let path = common::scratch(&format!("auto-clients-{name}")).join("window.png");
    let _ = glstereo::capture::write_png(shot, &path);
    path
}

/// One object of a scene: its name, which pixels are its, and the shift
/// (right eye minus left, window pixels) it must have, within `tolerance`.
struct Object<'a> {
    name: &'a str,
    is: &'a dyn Fn([u8; 4]) -> bool,
    shift: std::ops::RangeInclusive<f64>,
}

/// How far each object moved from the left eye to the right (window
/// pixels, x), after checking that it moved along its rows only: its
/// vertical centre is the same (±0.5; ±1 for solids), and so is, with
/// `rows` Some(slack), the number of its pixels in every row (±slack:
/// flat objects), with None its top and bottom row (±1: solids, whose
/// sides at other depths move by other amounts and change the counts).
fn horizontal_shifts(
    eyes: &[Image; 2],
    objects: &[Object],
    rows: Option<u32>,
    what: &str,
) -> Vec<f64> {
    let mut shifts = Vec::new();
    for o in objects {
        let (nl, xl, yl) = blob(&eyes[0], o.is);
        let (nr, xr, yr) = blob(&eyes[1], o.is);
        assert!(
            nl > 50 && nr > 50,
            "{what}: the {} object is missing from an eye ({nl} pixels left, {nr} right)",
            o.name
        );
        let counts = |img: &Image| -> Vec<u32> {
            (0..img.height())
                .map(|y| (0..img.width()).filter(|&x| (o.is)(img.get(x, y))).count() as u32)
                .collect()
        };
        let (l, r) = (counts(&eyes[0]), counts(&eyes[1]));
        match rows {
            Some(slack) => {
                for (y, (l, r)) in l.iter().zip(&r).enumerate() {
                    assert!(
                        l.abs_diff(*r) <= slack,
                        "{what}: row {y} holds {l} pixels of the {} object in the left eye and \
                         {r} in the right: the eyes differ by more than a horizontal shift",
                        o.name
                    );
                }
            }
            None => {
                let extent = |c: &[u32]| {
                    let first = c.iter().position(|&n| n > 0).unwrap_or(0) as i64;
                    let last = c.iter().rposition(|&n| n > 0).unwrap_or(0) as i64;
                    (first, last)
                };
                let (el, er) = (extent(&l), extent(&r));
                assert!(
                    (el.0 - er.0).abs() <= 1 && (el.1 - er.1).abs() <= 1,
                    "{what}: the {} object spans rows {el:?} in the left eye and {er:?} in \
                     the right: the eyes differ by more than a horizontal shift",
                    o.name
                );
            }
        }
        // A flat object's pixels only move along their rows, so its
        // centre stays within half a pixel; a solid's sides at other
        // depths move by other amounts, uncover or hide other lit
        // pixels and move its centre too (glxgears' blue gear at C 80:
        // up to 0.63 pixels in 45 captures), within its extents' ±1.
        let vertical = if rows.is_some() { 0.5 } else { 1.0 };
        assert!(
            (yr - yl).abs() < vertical,
            "{what}: the {} object moved vertically by {:.2} pixels",
            o.name,
            yr - yl
        );
        let dx = xr - xl;
        assert!(
            o.shift.contains(&dx),
            "{what}: the {} object moved by {dx:.2} pixels from the left eye to the right, \
             want {:?}",
            o.name,
            o.shift
        );
        shifts.push(dx);
    }
    shifts
}

fn red(p: [u8; 4]) -> bool {
    p[0] > 100 && p[1] < 60 && p[2] < 60
}
fn green(p: [u8; 4]) -> bool {
    p[1] > 100 && p[0] < 60 && p[2] < 60
}
fn blue(p: [u8; 4]) -> bool {
    p[2] > 100 && p[0] < 40 && p[1] < 40
}
fn white(p: [u8; 4]) -> bool {
    p[0] > 200 && p[1] > 200 && p[2] > 200
}

/// The `*_depths` programs' window (eye) size.
const DEPTHS_W: u32 = 240;
const DEPTHS_H: u32 = 160;
/// Their convergence: the green square's w.
const DEPTHS_C: f64 = 4.0;

/// The shift (window pixels) of an object at clip w `w` in a squeezed
/// half: s·(1 − C/w)·W eye pixels, halved (None: the HUD, 0).
fn squeezed_parallax(w: Option<f64>, c: f64, eye_width: u32) -> f64 {
    w.map_or(0.0, |w| S * (1.0 - c / w) * eye_width as f64 / 2.0)
}

/// A `*_depths` program (`title` its window) under `glstereo-run AUTO_MODE`
/// (`--auto` or `--auto=depth`) on `x`: its eyes hold the scene with each
/// object's parallax (±1 pixel: the squeeze rounds), the HUD at the
/// screen. What it said on stderr.
#[allow(clippy::too_many_arguments)]
fn depths_at_their_parallax(
    x: &Xvfb,
    auto_mode: &str,
    program: &Path,
    args: &[&str],
    title: &str,
    allowed: &[&str],
    what: &str,
) -> String {
    let auto = run_client_saying(
        x,
        command_in(auto_mode, x, Some(DEPTHS_C), program, args),
        title,
        allowed,
    );
    let mode = auto_mode.trim_start_matches('-').replace('=', "-");
    keep(&auto.shot, &format!("{title}-{mode}"));
    assert!(
        auto.lines.iter().any(|l| l == "report error 0x0"),
        "{what}: {:?}",
        auto.lines
    );
    assert_eq!(
        (auto.shot.width(), auto.shot.height()),
        (DEPTHS_W, DEPTHS_H),
        "{what}: window size"
    );
    let eyes = eyes_of(&auto.shot);
    let want = |w: Option<f64>| {
        let p = squeezed_parallax(w, DEPTHS_C, DEPTHS_W);
        p - 1.0..=p + 1.0
    };
    let objects = [
        Object {
            name: "red (w 2, near)",
            is: &red,
            shift: want(Some(2.0)),
        },
        Object {
            name: "green (w 4, at the convergence)",
            is: &green,
            shift: want(Some(4.0)),
        },
        Object {
            name: "blue (w 8, far)",
            is: &blue,
            shift: want(Some(8.0)),
        },
        Object {
            name: "white HUD bar (w 1)",
            is: &white,
            shift: want(None),
        },
    ];
    let shifts = horizontal_shifts(&eyes, &objects, Some(1), what);
    assert!(
        shifts[0] < -4.0 && shifts[2] > 2.0,
        "{what}: near and far do not move apart: {shifts:?}"
    );
    eprintln!("{what}: shifts (red, green, blue, HUD) {shifts:?} window pixels");
    auto.stderr
}

/// A `*_depths` program (`title` its window) under --auto: its eyes hold
/// the scene with each object's parallax (±1 pixel: the squeeze rounds);
/// without --auto the window equals the program's own, without the layer.
fn depths_program(program: &Path, args: &[&str], title: &str, allowed: &[&str], what: &str) {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(320, 240);
    depths_at_their_parallax(&x, "--auto", program, args, title, allowed, what);

    // Without --auto: the program's own picture, as without the layer.
    let with = run_client(&x, command(&x, None, program, args), title);
    let mut plain = Command::new(program);
    plain
        .args(args)
        .env("DISPLAY", &x.display)
        .env("QT_QPA_PLATFORM", "xcb");
    for (k, v) in command(&x, None, program, args).get_envs() {
        if let (Some(v), true) = (v, k == "XDG_RUNTIME_DIR") {
            plain.env(k, v);
        }
    }
    let without = run_client(&x, plain, title);
    assert_eq!(
        with.shot.max_difference(&without.shot).map(|d| d.0),
        Some(0),
        "{what}: without --auto the window differs from the program's own \
         (difference, x, y, channel): {:?}",
        with.shot.max_difference(&without.shot)
    );
    // One picture: the squares side by side across the window.
    let (_, x_blue, _) = blob(&with.shot, blue);
    assert!(
        x_blue > DEPTHS_W as f64 / 2.0,
        "{what}: without --auto the blue square is at x {x_blue:.0}, not in the right \
         part of one mono picture"
    );
}

#[test]
fn a_mono_glfw_core_profile_program_under_auto_shows_each_depth_with_its_parallax() {
    let exe = c_client("glfw_depths", &["-lglfw"]);
    depths_program(&exe, &[], "glfw_depths", &[], "GLFW 3.3 core");
}

#[test]
fn a_mono_pyopengl_freeglut_program_under_auto_shows_each_depth_with_its_parallax() {
    let script = clients().join("pyopengl_depths.py");
    depths_program(
        Path::new(PYTHON),
        &[script.to_str().unwrap()],
        "pyopengl_depths",
        &[],
        "PyOpenGL + freeglut",
    );
}

/// QOpenGLWidget draws into a framebuffer object of Qt's, in a context of
/// its own, and the window's context draws its texture into the window:
/// render to texture, stereoized (src/auto/render_targets.rs).
#[test]
fn a_mono_qt5_opengl_widget_under_auto_shows_each_depth_with_its_parallax() {
    let exe = cxx_client("qt5_depths", &["Qt5Widgets"]);
    depths_program(&exe, &[], "qt5 depths", &[], "Qt 5 QOpenGLWidget");
}

/// The GLFW program with its context made through EGL
/// (GLFW_EGL_CONTEXT_API): a desktop GL core context of libEGL's, on the
/// X11 window (src/interpose/egl.rs).
#[test]
fn a_mono_glfw_program_on_egl_under_auto_shows_each_depth_with_its_parallax() {
    let exe = c_client("glfw_depths", &["-lglfw"]);
    depths_program(&exe, &["egl"], "glfw_depths", &[], "GLFW 3.3 core on EGL");
}

/// SDL2 forced to EGL on X11 (SDL_VIDEO_X11_FORCE_EGL) with an OpenGL ES
/// 2.0 context and GLSL ES 1.00 shaders: SDL dlopens libEGL and
/// libGLESv2, and every GL function comes from SDL_GL_GetProcAddress
/// (eglGetProcAddress).
#[test]
fn a_mono_sdl2_gles2_program_on_egl_under_auto_shows_each_depth_with_its_parallax() {
    let exe = c_client("sdl_depths", &["-lSDL2"]);
    depths_program(&exe, &[], "sdl_depths", &[], "SDL2 OpenGL ES 2.0 on EGL");
}

/// Qt 5's EGL integration on X11 (QT_XCB_GL_INTEGRATION=xcb_egl): the
/// QOpenGLWidget's framebuffer object and the window's composition, in
/// desktop GL contexts of libEGL's.
#[test]
fn a_mono_qt5_opengl_widget_on_egl_under_auto_shows_each_depth_with_its_parallax() {
    let exe = cxx_client("qt5_depths", &["Qt5Widgets"]);
    depths_program(
        &exe,
        &["egl"],
        "qt5 depths",
        &[],
        "Qt 5 QOpenGLWidget on EGL",
    );
}

/// The same programs under `--auto=depth`. They draw their squares with
/// the depth test off, so the window's depth holds none of them; the
/// layer has each such draw write its depth beside it (the depth array's
/// other layer), and the eyes made from that frame show each square at
/// its parallax, as `--auto`'s rendered eyes do, the HUD at the screen,
/// and nothing said of a frame without depth. Desktop GL on GLX, and
/// OpenGL ES on EGL.
#[test]
fn mono_programs_that_draw_with_the_depth_test_off_get_each_depth_under_auto_depth() {
    let glfw = c_client("glfw_depths", &["-lglfw"]);
    let sdl = c_client("sdl_depths", &["-lSDL2"]);
    for (exe, title) in [(&glfw, "glfw_depths"), (&sdl, "sdl_depths")] {
        let _one = one_renderer_at_a_time();
        let x = Xvfb::start(320, 240);
        let what = format!("{title} under --auto=depth");
        let stderr = depths_at_their_parallax(&x, "--auto=depth", exe, &[], title, &[], &what);
        assert!(!stderr.contains("wrote no depth"), "{what}: {stderr}");
    }
}

/// glxgears' gears (camera 40 units away: w ≈ 35…45) in one run per
/// convergence: C 20 puts them all behind the screen (they move right by
/// s·(1 − 20/40)·300/2 ≈ 5.25 window pixels), C 80 in front of it (left
/// by ≈ 10.5). Without --auto its window is one mono picture.
#[test]
fn glxgears_without_stereo_under_auto_moves_its_gears_by_their_depth() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(640, 480);
    for (c, around) in [(20.0, 5.25), (80.0, -10.5)] {
        let what = format!("glxgears, convergence {c}");
        let mut gears = Renderer::start(command(&x, Some(c), Path::new("glxgears"), &[]), &what);
        let screen = Screen::open(&x.display);
        let (window, shot) = gears.picture(
            &screen,
            |s| s.find_window("glxgears"),
            |shot| eyes_of(shot).iter().all(gears_in),
        );
        let stderr = gears.quit(&screen, window);
        keep(&shot, &format!("glxgears-auto-c{c}"));
        assert!(!stderr.contains("glstereo:"), "{what}: {stderr}");
        let eyes = eyes_of(&shot);
        assert!(
            eyes.iter().all(gears_in),
            "{what}: gears missing from a half"
        );
        let near = around - 2.5..=around + 2.5;
        let objects = [
            Object {
                name: "red gear",
                is: &|p| p[0] > 90 && p[1] < 40 && p[2] < 40,
                shift: near.clone(),
            },
            Object {
                name: "green gear",
                is: &|p| p[1] > 90 && p[0] < 40,
                shift: near.clone(),
            },
            Object {
                name: "blue gear",
                is: &|p| p[2] > 90 && p[0] < 60 && p[1] < 60,
                shift: near,
            },
        ];
        let shifts = horizontal_shifts(&eyes, &objects, None, &what);
        eprintln!("{what}: shifts (red, green, blue) {shifts:?} window pixels");
    }
    let mut gears = Renderer::start(
        command(&x, None, Path::new("glxgears"), &[]),
        "glxgears without --auto",
    );
    let screen = Screen::open(&x.display);
    let (window, shot) = gears.picture(&screen, |s| s.find_window("glxgears"), gears_in);
    gears.quit(&screen, window);
    keep(&shot, "glxgears-mono");
    let [l, r] = eyes_of(&shot);
    assert!(
        gears_in(&shot) && !(gears_in(&l) && gears_in(&r)),
        "glxgears without --auto: the window is not one mono picture of the gears"
    );
}

/// osgviewer's scene: three cubes one behind the other along the view
/// (OBJ's z towards the viewer, so red nearest), far enough apart that a
/// convergence between them puts red in front of the screen and blue
/// behind it.
fn osg_scene() -> PathBuf {
    let dir = common::scratch("auto-clients-osg");
    let mut obj = String::from("mtllib depths.mtl\n");
    for (n, (material, cx, cz)) in [
        ("red", -3.0, 10.0),
        ("green", 0.0, 0.0),
        ("blue", 3.0, -10.0),
    ]
    .into_iter()
    .enumerate()
    {
        for i in 0..8 {
            let d = |bit: u32| if i & bit != 0 { 1.0 } else { -1.0 };
            obj += &format!("v {} {} {}\n", cx + d(4), d(2), cz + d(1));
        }
        obj += &format!("usemtl {material}\n");
        // The corners of each face, by their bits (x 4, y 2, z 1).
        for face in [
            [0, 1, 3, 2],
            [4, 6, 7, 5],
            [0, 4, 5, 1],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 5, 7, 3],
        ] {
            let v: Vec<String> = face.iter().map(|c| (n * 8 + c + 1).to_string()).collect();
            obj += &format!("f {}\n", v.join(" "));
        }
    }
    std::fs::write(dir.join("depths.obj"), obj).unwrap();
    std::fs::write(
        dir.join("depths.mtl"),
        "newmtl red\nKd 1 0 0\nKa 0 0 0\nnewmtl green\nKd 0 1 0\nKa 0 0 0\n\
         newmtl blue\nKd 0 0 1\nKa 0 0 0\n",
    )
    .unwrap();
    dir.join("depths.obj")
}

/// OSG's clear colour (0.2, 0.2, 0.4).
fn osg_background(p: [u8; 4]) -> bool {
    p[0].abs_diff(51) <= 2 && p[1].abs_diff(51) <= 2 && p[2].abs_diff(102) <= 2
}

/// osgviewer (fixed function, OSG's own near/far per frame) with its
/// statistics HUD ('s': an orthographic camera's text): the cubes move by
/// their depth, near against far, and the HUD's text stays put. The
/// camera is ≈ 47 units from the green cube (measured: with convergence 40
/// the cubes move -1, +2 and +4.5 window pixels, w ≈ 37, 47 and 59):
/// convergence 47 puts red in front of the screen and blue behind.
#[test]
fn osgviewer_in_mono_under_auto_moves_near_and_far_apart_and_keeps_its_hud() {
    osgviewer_under("--auto");
}

/// [`osgviewer_in_mono_under_auto_moves_near_and_far_apart_and_keeps_its_hud`]
/// with eyes made from one render: OSG draws its statistics with a camera
/// of its own after the scene's, so the cubes keep the scene's depth and
/// the HUD stays put.
#[test]
fn osgviewer_in_mono_under_auto_depth_moves_near_and_far_apart_and_keeps_its_hud() {
    osgviewer_under("--auto=depth");
}

fn osgviewer_under(auto: &str) {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(640, 480);
    let scene = osg_scene();
    let mut cmd = command_in(
        auto,
        &x,
        Some(47.0),
        Path::new("osgviewer"),
        &[scene.to_str().unwrap()],
    );
    cmd.env("OSG_WINDOW", "0 0 400 300");
    let mut osg = Renderer::start(cmd, &format!("osgviewer {auto}"));
    let screen = Screen::open(&x.display);
    let cubes = |img: &Image| [red, green, blue].iter().all(|f| blob(img, f).0 > 50);
    let (window, _) = osg.picture(
        &screen,
        |s| s.find_class("osgViewer"),
        |shot| eyes_of(shot).iter().all(cubes),
    );
    screen.press_key(window, x11_dl::keysym::XK_s);
    // The statistics: text at the top left of each eye.
    let hud = |img: &Image| {
        count(
            &Image::from_fn(img.width(), 20, |x, y| img.get(x, y)),
            |p| !osg_background(p),
        )
    };
    let (_, shot) = osg.picture(
        &screen,
        |s| s.find_class("osgViewer"),
        |shot| eyes_of(shot).iter().all(|e| cubes(e) && hud(e) > 20),
    );
    let stderr = osg.quit(&screen, window);
    keep(&shot, &format!("osgviewer{auto}"));
    assert!(!stderr.contains("glstereo:"), "{stderr}");
    assert_eq!((shot.width(), shot.height()), (400, 300));
    let eyes = eyes_of(&shot);
    assert!(
        eyes.iter().all(|e| hud(e) > 20),
        "osgviewer {auto}: no statistics HUD in an eye"
    );
    let objects = [
        Object {
            name: "red cube (near)",
            is: &red,
            shift: -6.0..=-0.5,
        },
        Object {
            name: "green cube",
            is: &green,
            shift: -1.0..=1.0,
        },
        Object {
            name: "blue cube (far)",
            is: &blue,
            shift: 0.5..=6.0,
        },
    ];
    let shifts = horizontal_shifts(&eyes, &objects, None, &format!("osgviewer {auto}"));
    eprintln!("osgviewer {auto}: shifts (red, green, blue) {shifts:?} window pixels");
    // The HUD: its rows are the same picture in both eyes.
    for y in 0..20 {
        for x in 0..eyes[0].width() {
            assert_eq!(
                eyes[0].get(x, y),
                eyes[1].get(x, y),
                "osgviewer {auto}: the statistics HUD differs between the eyes at ({x}, {y})"
            );
        }
    }
}

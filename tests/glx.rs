//! The GLX backend on a real X server (Xvfb, started by the test): stereo
//! visual choice with fallback, the emulated quad buffer in a window, window
//! events, a lost server.

mod common;

use glstereo::config::StereoKind;
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::error::Error;
use glstereo::gl::enums::*;
use glstereo::surface;

use common::xvfb::Xvfb;

#[test]
fn xvfb_has_no_stereo_visual_so_stereo_is_emulated_in_a_window() {
    let x = Xvfb::start(640, 480);
    let d = Display::open_x11(Some(&x.display)).unwrap();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_DEPTH_SIZE, 16])
        .unwrap();
    assert_eq!(
        c.stereo,
        StereoKind::Emulated,
        "Mesa under Xvfb has no stereo visual"
    );
    let s = d.create_surface(&c, 64, 48).unwrap();
    surface::make_current(Some(&s)).unwrap();
    let gl = s.gl();
    for (buf, rgba) in [
        (GL_BACK_LEFT, [1.0, 0.0, 0.0, 1.0]),
        (GL_BACK_RIGHT, [0.0, 0.0, 1.0, 1.0]),
    ] {
        s.draw_buffer(buf).unwrap();
        // SAFETY: the surface is current.
        unsafe {
            gl.ClearColor(rgba[0], rgba[1], rgba[2], rgba[3]);
            gl.Clear(GL_COLOR_BUFFER_BIT);
        }
    }
    s.swap_buffers().unwrap();
    assert_eq!(
        s.read_pixels(GL_FRONT_LEFT).unwrap().get(5, 5),
        [255, 0, 0, 255]
    );
    assert_eq!(
        s.read_pixels(GL_FRONT_RIGHT).unwrap().get(5, 5),
        [0, 0, 255, 255]
    );
    surface::make_current(None).unwrap();
}

#[test]
fn emulation_off_fails_as_glx_choose_visual_returns_null() {
    let x = Xvfb::start(320, 240);
    let d = Display::open_x11(Some(&x.display)).unwrap();
    // No env mutation in a threaded test: exercise the policy directly.
    let req = glstereo::config::ConfigRequest::parse_visual_attribs(&[
        GLX_RGBA,
        GLX_DOUBLEBUFFER,
        GLX_STEREO,
    ])
    .unwrap();
    let p = glstereo::backend::glx::GlxPlatform::open(Some(&x.display)).unwrap();
    use glstereo::backend::Platform;
    let e = p
        .choose_config(req, glstereo::config::EmulationPolicy::Off)
        .unwrap_err();
    assert!(matches!(e, Error::NoMatchingConfig(_)), "{e:?}");
    let mono = d.choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER]).unwrap();
    assert_eq!(mono.stereo, StereoKind::None);
}

#[test]
fn no_display_is_a_clear_error_naming_the_fix() {
    let e = Display::open_x11(Some(":59999")).unwrap_err();
    assert!(matches!(e, Error::BackendUnavailable(_)), "{e:?}");
    let m = e.to_string();
    assert!(
        m.contains(":59999") && m.contains("Xvfb") && m.contains("GLSTEREO_BACKEND=egl"),
        "{m}"
    );
}

#[test]
fn a_killed_server_is_reported_not_an_exit() {
    let mut x = Xvfb::start(320, 240);
    let d = Display::open_x11(Some(&x.display)).unwrap();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO])
        .unwrap();
    let s = d.create_surface(&c, 32, 32).unwrap();
    surface::make_current(Some(&s)).unwrap();
    s.swap_buffers().unwrap();
    x.kill();
    // The next calls that talk to the server fail with DISPLAY_LOST; the test process lives on.
    let mut lost = None;
    for _ in 0..50 {
        match s.swap_buffers() {
            Err(e) => {
                lost = Some(e);
                break;
            }
            Ok(()) => std::thread::sleep(std::time::Duration::from_millis(20)),
        }
    }
    let e = lost.expect("swapping on a dead server must fail");
    assert!(matches!(e, Error::DisplayLost(_)), "{e:?}");
    let _ = surface::make_current(None);
    drop(s);
    drop(d);
}

#[test]
fn a_program_whose_server_dies_gets_display_lost_and_exits_without_cleanup() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};

    let mut x = Xvfb::start(320, 240);
    let dir = common::scratch("x_server_killed");
    let exe = dir.join("x_server_killed");
    common::compile_c(
        &[common::root().join("tests/c/x_server_killed.c")],
        &exe,
        &["-pthread"],
    );
    let mut child = Command::new(&exe)
        .env("DISPLAY", &x.display)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = BufReader::new(child.stdout.take().unwrap());
    let mut line = String::new();
    out.read_line(&mut line).unwrap();
    assert_eq!(line.trim(), "ready", "the program set up its window");
    x.kill();
    let deadline = Instant::now() + Duration::from_secs(30);
    let status = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break st;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let mut e = String::new();
            let _ = std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut e);
            panic!("the program hung after its X server died; stderr: {e}");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut out, &mut rest).unwrap();
    assert!(status.success(), "exit {status}: {rest}");
    assert!(
        rest.contains("GLS_ERROR_DISPLAY_LOST") && rest.contains("lost"),
        "{rest}"
    );
}

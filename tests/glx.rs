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

/// Display on `x`, a stereo (GLX_STEREO, double-buffered RGBA) window of
/// `w`x`h` per eye, made current on this thread. Keep the display while
/// the surface lives.
fn current_stereo_window(
    x: &Xvfb,
    w: u32,
    h: u32,
) -> (
    std::sync::Arc<Display>,
    std::sync::Arc<glstereo::surface::Surface>,
) {
    let d = Display::open_x11(Some(&x.display)).unwrap();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO])
        .unwrap();
    let s = d.create_surface(&c, w, h).unwrap();
    surface::make_current(Some(&s)).unwrap();
    (d, s)
}

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
    let (d, s) = current_stereo_window(&x, 32, 32);
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

/// Fills the back buffers with a different pattern per eye: vertical bands
/// in the left eye, horizontal bands in the right, drawn with scissored
/// clears so every pixel is exact.
fn draw_eye_patterns(s: &std::sync::Arc<glstereo::surface::Surface>) {
    let gl = s.gl();
    let (w, h) = s.size();
    for (buf, vertical) in [(GL_BACK_LEFT, true), (GL_BACK_RIGHT, false)] {
        s.draw_buffer(buf).unwrap();
        // SAFETY: the surface is current on this thread.
        unsafe {
            gl.Enable(GL_SCISSOR_TEST);
            let bands = 8;
            for k in 0..bands {
                let c = k as f32 / (bands - 1) as f32;
                if vertical {
                    gl.Scissor((w * k / bands) as i32, 0, (w / bands + 1) as i32, h as i32);
                    gl.ClearColor(c, 0.3, 1.0 - c, 1.0);
                } else {
                    gl.Scissor(0, (h * k / bands) as i32, w as i32, (h / bands + 1) as i32);
                    gl.ClearColor(1.0 - c, c, 0.6, 1.0);
                }
                gl.Clear(GL_COLOR_BUFFER_BIT);
            }
            gl.Disable(GL_SCISSOR_TEST);
            gl.Scissor(0, 0, w as i32, h as i32);
        }
    }
}

fn sync(s: &glstereo::surface::Surface) {
    use glstereo::backend::NativeHandles;
    let NativeHandles::Glx { display, .. } = s.native_handles() else {
        panic!("not GLX")
    };
    let xl = x11_dl::xlib::Xlib::open().unwrap();
    // SAFETY: the surface's own live connection.
    unsafe { (xl.XSync)(display.cast(), 0) };
}

#[test]
fn the_window_shows_the_composite_of_each_mode_pixel_for_pixel() {
    use glstereo::output::OutputMode;
    let x = Xvfb::start(1280, 1024);
    let (_d, s) = current_stereo_window(&x, 160, 120);
    for name in [
        "anaglyph-red-cyan",
        "side-by-side-half",
        "rows",
        "side-by-side",
        "top-bottom",
        "checkerboard",
    ] {
        let mode = OutputMode::from_name(name).unwrap();
        s.set_output(mode).unwrap();
        draw_eye_patterns(&s);
        s.swap_buffers().unwrap();
        sync(&s);
        let want = s.composite_image().unwrap();
        // side-by-side is the Xinerama passive layout: a double-width window.
        let (ww, wh) = glstereo::output::layout::composite_size(mode, 160, 120);
        assert_eq!((want.width(), want.height()), (ww, wh), "{name}");
        let got = common::xvfb::screenshot(&x.display, 0, 0, ww, wh);
        let (diff, px, py, ch) = got.max_difference(&want).unwrap();
        assert!(
            diff <= 1,
            "{name}: window pixel ({px}, {py}) channel {ch} differs by {diff} from the composite"
        );
    }
    surface::make_current(None).unwrap();
}

#[test]
fn resizing_the_window_resizes_the_eyes_by_the_next_frame() {
    use glstereo::backend::{NativeHandles, WindowEvent};
    let x = Xvfb::start(1280, 1024);
    let (_d, s) = current_stereo_window(&x, 200, 100);
    draw_eye_patterns(&s);
    s.swap_buffers().unwrap();
    // The user (or XResizeWindow) makes the window 300x150.
    let NativeHandles::Glx {
        display, window, ..
    } = s.native_handles()
    else {
        panic!()
    };
    let xl = x11_dl::xlib::Xlib::open().unwrap();
    // SAFETY: the surface's live connection and window.
    unsafe {
        (xl.XResizeWindow)(display.cast(), window, 300, 150);
        (xl.XSync)(display.cast(), 0);
    }
    assert_eq!(s.size(), (200, 100), "this frame keeps its eyes");
    s.swap_buffers().unwrap();
    assert_eq!(
        s.size(),
        (300, 150),
        "the next frame has eyes of the new size"
    );
    let mut saw = None;
    while let Some(e) = s.next_event() {
        if let WindowEvent::Resized(w, h) = e {
            saw = Some((w, h));
        }
    }
    assert_eq!(
        saw,
        Some((300, 150)),
        "a resize event with the new eye size"
    );
    // The program draws the new size; the window shows it pixel for pixel.
    // SAFETY: current surface.
    unsafe { s.gl().Viewport(0, 0, 300, 150) };
    draw_eye_patterns(&s);
    s.swap_buffers().unwrap();
    sync(&s);
    let want = s.composite_image().unwrap();
    let got = common::xvfb::screenshot(&x.display, 0, 0, 300, 150);
    assert!(got.max_difference(&want).unwrap().0 <= 1);
    surface::make_current(None).unwrap();
}

#[test]
fn closing_the_window_is_reported_and_ends_cleanly() {
    use glstereo::backend::{NativeHandles, WindowEvent};
    use x11_dl::xlib;
    let x = Xvfb::start(640, 480);
    let d = Display::open_x11(Some(&x.display)).unwrap();
    let c = d.choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER]).unwrap();
    let s = d.create_surface(&c, 64, 64).unwrap();
    assert!(!s.close_requested());
    let NativeHandles::Glx {
        display, window, ..
    } = s.native_handles()
    else {
        panic!()
    };
    let xl = xlib::Xlib::open().unwrap();
    // A window manager's close button: WM_PROTOCOLS / WM_DELETE_WINDOW.
    // SAFETY: the surface's live connection and window; a zeroed event filled in.
    unsafe {
        let dpy: *mut xlib::Display = display.cast();
        let mut ev: xlib::XEvent = std::mem::zeroed();
        ev.client_message.type_ = xlib::ClientMessage;
        ev.client_message.window = window;
        ev.client_message.message_type = (xl.XInternAtom)(dpy, c"WM_PROTOCOLS".as_ptr(), 0);
        ev.client_message.format = 32;
        ev.client_message.data.set_long(
            0,
            (xl.XInternAtom)(dpy, c"WM_DELETE_WINDOW".as_ptr(), 0) as i64,
        );
        (xl.XSendEvent)(dpy, window, 0, 0, &mut ev);
        (xl.XSync)(dpy, 0);
    }
    assert_eq!(s.next_event(), Some(WindowEvent::CloseRequested));
    assert!(s.close_requested());
    drop(s);
    drop(d);
}

/// The same C example, run headless on EGL and in a window on GLX, writes
/// the same images: only GLSTEREO_BACKEND changes.
#[test]
fn every_example_gives_the_same_images_in_a_window_and_headless() {
    use std::process::Command;
    let x = Xvfb::start(1600, 1200);
    let cases: &[(&str, &[&str])] = &[
        ("redblue", &["--size", "320x240"]),
        ("oglplane", &["--size", "320x240", "--frames", "3"]),
        ("starbase", &["--size", "320x256"]),
        ("irisgl", &["--size", "320x256"]),
        ("irisgl", &["--size", "320x256", "--square-pixel"]),
        ("autostereo", &["--size", "320x240", "--frames", "2"]),
        (
            "xinerama",
            &["--size", "160x120", "--modes", "side-by-side"],
        ),
    ];
    for (k, (name, args)) in cases.iter().enumerate() {
        let exe = common::build_example(name, false);
        let mut outs = Vec::new();
        for backend in ["egl", "glx"] {
            let out = common::scratch(&format!("example_window_{k}_{backend}"));
            let mut cmd = Command::new(&exe);
            cmd.args(*args)
                .arg("--out")
                .arg(&out)
                .env("GLSTEREO_BACKEND", backend)
                .env("DISPLAY", &x.display)
                .env_remove("GLSTEREO_MODE");
            common::run_ok(&mut cmd);
            outs.push(out);
        }
        let files = pngs_under(&outs[0]);
        assert!(!files.is_empty(), "{name} wrote no images");
        for f in &files {
            let rel = f.strip_prefix(&outs[0]).unwrap();
            let a = common::png(f);
            let b = common::png(&outs[1].join(rel));
            assert_eq!(
                a,
                b,
                "{name} {args:?}: {} differs between EGL and GLX",
                rel.display()
            );
        }
    }
}

/// Every PNG under `dir`, recursively, sorted.
fn pngs_under(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(pngs_under(&p));
        } else if p.extension().is_some_and(|x| x == "png") {
            out.push(p);
        }
    }
    out.sort();
    out
}

/// The top-level window of `display` whose title starts with `prefix`, and its title.
fn find_window(
    xl: &x11_dl::xlib::Xlib,
    dpy: *mut x11_dl::xlib::Display,
    prefix: &str,
) -> Option<(u64, String)> {
    // SAFETY: plain Xlib queries on a live connection; returned memory is freed.
    unsafe {
        let root = (xl.XDefaultRootWindow)(dpy);
        let (mut r, mut p, mut children, mut n) = (0, 0, std::ptr::null_mut(), 0u32);
        if (xl.XQueryTree)(dpy, root, &mut r, &mut p, &mut children, &mut n) == 0 {
            return None;
        }
        let mut found = None;
        for i in 0..n as usize {
            let w = *children.add(i);
            let mut name = std::ptr::null_mut();
            if (xl.XFetchName)(dpy, w, &mut name) != 0 && !name.is_null() {
                let s = std::ffi::CStr::from_ptr(name)
                    .to_string_lossy()
                    .into_owned();
                (xl.XFree)(name.cast());
                if s.starts_with(prefix) {
                    found = Some((w, s));
                }
            }
        }
        if !children.is_null() {
            (xl.XFree)(children.cast());
        }
        found
    }
}

#[test]
fn oglplane_in_a_window_takes_keys_shows_its_settings_and_closes() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    use x11_dl::xlib;

    let x = Xvfb::start(800, 600);
    let exe = common::build_example("oglplane", false);
    let mut child = Command::new(&exe)
        .args(["--interactive", "--size", "320x240"])
        .env("GLSTEREO_BACKEND", "glx")
        .env("DISPLAY", &x.display)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let xl = xlib::Xlib::open().unwrap();
    let name = std::ffi::CString::new(x.display.clone()).unwrap();
    // SAFETY: a connection of the test's own.
    let dpy = unsafe { (xl.XOpenDisplay)(name.as_ptr()) };
    assert!(!dpy.is_null());
    let wait_title = |want: &str| -> String {
        let deadline = Instant::now() + Duration::from_secs(30);
        loop {
            if let Some((_, t)) = find_window(&xl, dpy, "OGLPlane") {
                if t.contains(want) {
                    return t;
                }
            }
            assert!(
                Instant::now() < deadline,
                "no OGLPlane window titled with {want:?}"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    };
    let title = wait_title("offset adjustment 1.0000");
    assert!(title.contains("balance adjustment 1.0000"), "{title}");
    let (window, _) = find_window(&xl, dpy, "OGLPlane").unwrap();
    let send = |ev: &mut xlib::XEvent| {
        // SAFETY: the program's window on the test's connection.
        unsafe {
            (xl.XSendEvent)(dpy, window, 0, xlib::KeyPressMask, ev);
            (xl.XSync)(dpy, 0);
        }
    };
    // '=' twice (stronger) and ']' once (more positive balance), unshifted keys.
    for sym in [
        x11_dl::keysym::XK_equal,
        x11_dl::keysym::XK_equal,
        x11_dl::keysym::XK_bracketright,
    ] {
        // SAFETY: a zeroed key event filled in.
        let mut ev: xlib::XEvent = unsafe { std::mem::zeroed() };
        // SAFETY: writing the key member of the union.
        unsafe {
            ev.key.type_ = xlib::KeyPress;
            ev.key.window = window;
            ev.key.root = (xl.XDefaultRootWindow)(dpy);
            ev.key.keycode = (xl.XKeysymToKeycode)(dpy, sym as u64) as u32;
            ev.key.same_screen = 1;
        }
        send(&mut ev);
    }
    let title = wait_title("offset adjustment 1.2100");
    assert!(
        title.contains("balance adjustment 1.1000"),
        "strength x1.1 twice, balance x1.1 once: {title}"
    );
    // The window manager's close button ends the program cleanly.
    // SAFETY: a zeroed client message filled in.
    let mut ev: xlib::XEvent = unsafe { std::mem::zeroed() };
    // SAFETY: writing the client_message member; atoms from the live connection.
    unsafe {
        ev.client_message.type_ = xlib::ClientMessage;
        ev.client_message.window = window;
        ev.client_message.message_type = (xl.XInternAtom)(dpy, c"WM_PROTOCOLS".as_ptr(), 0);
        ev.client_message.format = 32;
        ev.client_message.data.set_long(
            0,
            (xl.XInternAtom)(dpy, c"WM_DELETE_WINDOW".as_ptr(), 0) as i64,
        );
        (xl.XSendEvent)(dpy, window, 0, 0, &mut ev);
        (xl.XSync)(dpy, 0);
        (xl.XCloseDisplay)(dpy);
    }
    let deadline = Instant::now() + Duration::from_secs(30);
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("oglplane did not end after its window was closed");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let out: Vec<String> = BufReader::new(child.stdout.take().unwrap())
        .lines()
        .map(Result::unwrap)
        .collect();
    assert!(status.success(), "{out:?}");
    assert!(
        out.iter()
            .any(|l| l.contains("offset adjustment 1.2100, balance adjustment 1.1000")),
        "stdout shows the values too: {out:?}"
    );
}

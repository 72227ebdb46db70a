//! The live keys (src/interpose/controls.rs) in real programs under
//! glstereo-run on a private Xvfb, typed as a user types them (XTEST: the
//! server makes the key events and their modifier state):
//!
//! - tests/c/keys_stereo.c, a legacy Xlib stereo program that draws only
//!   on Expose and prints every key it gets, reading its events with
//!   XNextEvent (blocking) or XPending + XCheck*Event, its keys as core
//!   or as XInput 2 events;
//! - tests/clients/glfw_keys.c, a GLFW 3.3 core-profile stereo program
//!   drawing continuously (Xlib under GLFW);
//! - tests/clients/qt_keys.cpp, a Qt 5 stereo QWindow (Qt reads libxcb
//!   itself, on a thread of its own);
//! - Mesa's glxgears -stereo.
//!
//! Ctrl+F7 must change the window's layout (grabbed with XGetImage),
//! Ctrl+F8 exchange its eyes, the program must never get those keys but
//! get every other one, and stderr must say each change once. A program
//! without stereo, or with GLSTEREO_KEYS=0, gets the keys untouched; the
//! keys of automatic stereo are taken only under --auto; a key is known
//! by the keyboard map of the moment.

mod common;

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use common::clients::*;
use common::preload::{Running, Screen, built};
use common::xvfb::Xvfb;
use glstereo::image::Image;
use x11_dl::keysym::*;

const CTRL: &[u32] = &[XK_Control_L];
const CTRL_SHIFT: &[u32] = &[XK_Control_L, XK_Shift_L];
const NONE: &[u32] = &[];

/// tests/c/keys_stereo.c (links -lGL -lX11 -lXi).
fn keys_stereo() -> std::path::PathBuf {
    c_program("keys_stereo", &["-lGL", "-lX11", "-lXi"])
}

/// `glstereo-run [args] program pargs` on `x`.
fn run(x: &Xvfb, args: &[&str], program: &Path, pargs: &[&str]) -> Command {
    let mut cmd = Command::new(&built().run);
    cmd.args(args)
        .arg(program)
        .args(pargs)
        .env("DISPLAY", &x.display)
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_SWAP_EYES")
        .env_remove("GLSTEREO_AUTO")
        .env_remove("GLSTEREO_KEYS");
    cmd
}

/// Window points (x, y from the top left) and the colour each must have.
type Expected = Vec<((u32, u32), [u8; 3])>;

fn matches(shot: &Image, want: &Expected) -> bool {
    want.iter().all(|&((x, y), c)| {
        let got = shot.get(x, y);
        (0..3).all(|i| got[i].abs_diff(c[i]) <= 8)
    })
}

/// Grabs `window` until it shows `want` (30 s at most), else fails saying
/// what it showed.
fn wait_for(screen: &Screen, window: u64, want: &Expected, what: &str) -> Image {
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        let shot = screen.grab(window);
        if matches(&shot, want) {
            return shot;
        }
        if Instant::now() > deadline {
            let _ = glstereo::capture::write_png(
                &shot,
                &common::scratch(&format!("keys-{}", what.replace(' ', "-"))).join("window.png"),
            );
            let got: Vec<_> = want
                .iter()
                .map(|&((x, y), _)| ((x, y), shot.get(x, y)))
                .collect();
            panic!("{what}: the window never showed {want:?}; it shows {got:?}");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

const RED: [u8; 3] = [255, 0, 0];
const GREEN: [u8; 3] = [0, 255, 0];
const BLUE: [u8; 3] = [0, 0, 255];
const YELLOW: [u8; 3] = [255, 255, 0];
const BLACK: [u8; 3] = [0, 0, 0];

/// The eyes as shown: exchanged or not.
fn shown<T>(swapped: bool, left: T, right: T) -> (T, T) {
    if swapped {
        (right, left)
    } else {
        (left, right)
    }
}

/// keys_stereo's 160x120 frame in anaglyph-red-cyan (red from the eye
/// shown as left, green and blue from the other): in the bottom-left
/// quarter (left red, right blue) and the top-left one (left green,
/// right blue).
fn keys_anaglyph(swapped: bool) -> Expected {
    let mix = |(l, r): ([u8; 3], [u8; 3])| [l[0], r[1], r[2]];
    vec![
        ((40, 90), mix(shown(swapped, RED, BLUE))),
        ((20, 15), mix(shown(swapped, GREEN, BLUE))),
    ]
}

/// keys_stereo's frame in side-by-side: the 320x120 composite at half
/// size in rows 30..90, the eye shown as left in the left half; black
/// above and below.
fn keys_side_by_side(swapped: bool) -> Expected {
    // The left eye: red, green top-left quarter; the right eye: blue,
    // yellow bottom-right quarter (each eye 80x60 here).
    let left = [((20, 45), GREEN), ((60, 75), RED)];
    let right = [((20, 45), BLUE), ((60, 75), YELLOW)];
    let (a, b) = shown(swapped, left, right);
    let mut want: Expected = a.to_vec();
    want.extend(b.iter().map(|&((x, y), c)| ((x + 80, y), c)));
    want.extend([((80, 10), BLACK), ((80, 110), BLACK)]);
    want
}

/// The program's key lines.
fn keys_of(lines: &[String]) -> Vec<&str> {
    lines
        .iter()
        .filter(|l| l.starts_with("key "))
        .map(String::as_str)
        .collect()
}

/// The layer's lines on stderr.
fn said(stderr: &str) -> Vec<&str> {
    stderr.lines().filter(|l| l.contains("glstereo:")).collect()
}

/// Starts keys_stereo `pargs` under the layer with the environment `env`
/// added, and returns it, its window and a screen connection.
fn start(x: &Xvfb, pargs: &[&str], env: &[(&str, &str)]) -> (Running, u64, Screen) {
    let mut cmd = run(x, &[], &keys_stereo(), pargs);
    cmd.envs(env.iter().copied());
    let mut p = Running::start(cmd);
    let id = p.ready();
    let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).expect("window id");
    (p, window, Screen::open(&x.display))
}

/// keys_stereo with its event loop `loop_kind` (next, check) and its keys
/// as `input` events (core, xi2).
fn keys_in_an_event_driven_xlib_program(loop_kind: &str, input: &str) {
    let x = Xvfb::start(320, 240);
    let (p, w, screen) = start(&x, &["stereo", loop_kind, input], &[]);
    wait_for(&screen, w, &keys_anaglyph(false), "the default anaglyph");
    screen.type_keys(w, &[(CTRL, XK_F7)]);
    wait_for(
        &screen,
        w,
        &keys_side_by_side(false),
        "side-by-side after Ctrl+F7",
    );
    screen.type_keys(w, &[(CTRL, XK_F8)]);
    wait_for(
        &screen,
        w,
        &keys_side_by_side(true),
        "the eyes exchanged after Ctrl+F8",
    );
    screen.type_keys(w, &[(CTRL_SHIFT, XK_F7)]);
    wait_for(
        &screen,
        w,
        &keys_anaglyph(true),
        "anaglyph again after Ctrl+Shift+F7",
    );
    // Other keys reach the program; so do the keys of automatic stereo
    // without --auto.
    screen.type_keys(w, &[(NONE, XK_a), (CTRL, XK_t), (NONE, XK_Escape)]);
    let (lines, stderr) = p.finish_with_stdout();
    let keys = keys_of(&lines);
    assert!(
        keys.iter()
            .all(|k| !k.contains(" F7 ") && !k.contains(" F8 ")),
        "the program got a control key: {keys:?}"
    );
    for want in [
        "key press a state 0x0",
        "key release a state 0x0",
        "key press t state 0x4",
        "key release t state 0x4",
        "key press Escape state 0x0",
    ] {
        assert!(keys.contains(&want), "{want:?} missing from {keys:?}");
    }
    // The Control and Shift keys themselves are the program's.
    assert_eq!(
        keys.iter()
            .filter(|k| k.starts_with("key press Control_L"))
            .count(),
        4,
        "{keys:?}"
    );
    assert_eq!(
        said(&stderr),
        [
            "glstereo: format side-by-side (Ctrl+F7; Ctrl+Shift+F7 back)",
            "glstereo: eyes exchanged (Ctrl+F8)",
            "glstereo: format anaglyph-red-cyan (Ctrl+F7; Ctrl+Shift+F7 back)",
            "glstereo: Ctrl+F2 to Ctrl+F6 and Ctrl+T change automatic stereo, which this \
             program does not have (glstereo-run --auto): those keys go to the program",
        ],
        "{stderr}"
    );
}

#[test]
fn keys_change_the_format_and_eye_order_of_an_xlib_program_blocked_in_xnextevent() {
    keys_in_an_event_driven_xlib_program("next", "core");
}

#[test]
fn keys_change_the_format_and_eye_order_of_an_xlib_program_polling_with_xpending() {
    keys_in_an_event_driven_xlib_program("check", "core");
}

#[test]
fn keys_are_taken_from_xinput2_key_events_too() {
    keys_in_an_event_driven_xlib_program("next", "xi2");
}

#[test]
fn a_program_without_stereo_gets_every_key_untouched() {
    let x = Xvfb::start(320, 240);
    let (p, w, screen) = start(&x, &["mono"], &[]);
    screen.type_keys(
        w,
        &[
            (CTRL, XK_F7),
            (CTRL, XK_F8),
            (CTRL, XK_F4),
            (CTRL, XK_t),
            (NONE, XK_Escape),
        ],
    );
    let (lines, stderr) = p.finish_with_stdout();
    let keys = keys_of(&lines);
    for k in ["F7", "F8", "F4", "t"] {
        for what in ["press", "release"] {
            let want = format!("key {what} {k} state 0x4");
            assert!(
                keys.contains(&want.as_str()),
                "{want:?} missing from {keys:?}"
            );
        }
    }
    assert!(said(&stderr).is_empty(), "{stderr}");
}

#[test]
fn under_auto_the_keys_of_automatic_stereo_are_taken_and_said() {
    // A mono program: under --auto its context is an automatic-stereo
    // context, which arms the keys as a stereo context does.
    let x = Xvfb::start(320, 240);
    let (p, w, screen) = start(&x, &["mono"], &[("GLSTEREO_AUTO", "1")]);
    screen.type_keys(
        w,
        &[
            (CTRL, XK_F4),
            (CTRL, XK_F4),
            (CTRL, XK_F3),
            (CTRL, XK_F6),
            (CTRL, XK_F6),
            (CTRL, XK_F5),
            (CTRL, XK_t),
            (CTRL, XK_t),
            (CTRL, XK_F2),
            (CTRL, XK_F2),
            (NONE, XK_b),
            (NONE, XK_Escape),
        ],
    );
    let (lines, stderr) = p.finish_with_stdout();
    let keys = keys_of(&lines);
    assert_eq!(
        keys.iter()
            .filter(|k| !k.contains("Control_L"))
            .copied()
            .collect::<Vec<_>>(),
        [
            "key press b state 0x0",
            "key release b state 0x0",
            "key press Escape state 0x0"
        ],
        "{keys:?}"
    );
    assert_eq!(
        said(&stderr),
        [
            "glstereo: separation 20% (Ctrl+F3/F4)",
            "glstereo: separation 25% (Ctrl+F3/F4)",
            "glstereo: separation 20% (Ctrl+F3/F4)",
            "glstereo: convergence 1.1, set by hand from 1 (automatic convergence had chosen \
             no value yet) (Ctrl+F5/F6)",
            "glstereo: convergence 1.21 (Ctrl+F5/F6)",
            "glstereo: convergence 1.1 (Ctrl+F5/F6)",
            "glstereo: automatic stereo off (Ctrl+T)",
            "glstereo: automatic stereo on (Ctrl+T)",
            "glstereo: automatic stereo makes both eyes from one render's depth (depth) \
             (Ctrl+F2)",
            "glstereo: automatic stereo renders both eyes (geometry) (Ctrl+F2)",
        ],
        "{stderr}"
    );
}

#[test]
fn glstereo_keys_0_leaves_every_key_to_the_program() {
    let x = Xvfb::start(320, 240);
    let (p, w, screen) = start(&x, &["stereo"], &[("GLSTEREO_KEYS", "0")]);
    screen.type_keys(w, &[(CTRL, XK_F7), (NONE, XK_Escape)]);
    let (lines, stderr) = p.finish_with_stdout();
    assert!(
        keys_of(&lines).contains(&"key press F7 state 0x4"),
        "{lines:?}"
    );
    assert!(said(&stderr).is_empty(), "{stderr}");
}

/// The blue gear's horizontal shift from the left half to the right one
/// (pixels; glxgears -stereo in side-by-side at 300x300: about +3.8 with
/// the eyes in order, -3.8 exchanged — the red and green gears shift
/// about 1.3 and -1.6 — measured steady while the gears turn).
fn blue_gear_shift(shot: &Image) -> f64 {
    let (l, r) = halves(shot);
    let blue = |p: [u8; 4]| p[2] > 90 && p[0] < 60 && p[1] < 60;
    blob(&l, blue).1 - blob(&r, blue).1
}

/// glxgears shown side by side, each half holding its gears.
fn gears_side_by_side(shot: &Image) -> bool {
    let (l, r) = halves(shot);
    letterboxed(shot) && gears_in(&l) && gears_in(&r)
}

#[test]
fn keys_change_the_format_and_eye_order_of_glxgears() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(640, 480);
    let mut gears = Renderer::start(
        run(&x, &[], Path::new("glxgears"), &["-stereo"]),
        "glxgears -stereo",
    );
    let screen = Screen::open(&x.display);
    let find = |s: &Screen| s.find_window("glxgears");
    let (w, shot) = gears.picture(&screen, find, |shot| count(shot, |p| p[0] > 90) > 1000);
    assert!(
        !gears_side_by_side(&shot),
        "glxgears starts in the default format (anaglyph-red-cyan)"
    );
    screen.type_keys(w, &[(CTRL, XK_F7)]);
    let (_, shot) = gears.picture(&screen, find, |shot| {
        gears_side_by_side(shot) && blue_gear_shift(shot) > 2.0
    });
    assert!(
        gears_side_by_side(&shot) && blue_gear_shift(&shot) > 2.0,
        "after Ctrl+F7: not side-by-side with the eyes in order (blue gear shift {:.2})",
        blue_gear_shift(&shot)
    );
    screen.type_keys(w, &[(CTRL, XK_F8)]);
    let (_, shot) = gears.picture(&screen, find, |shot| {
        gears_side_by_side(shot) && blue_gear_shift(shot) < -2.0
    });
    assert!(
        gears_side_by_side(&shot) && blue_gear_shift(&shot) < -2.0,
        "after Ctrl+F8: the eyes are not exchanged (blue gear shift {:.2})",
        blue_gear_shift(&shot)
    );
    // glxgears quits on Escape: it still gets its keys.
    let stderr = gears.quit(&screen, w);
    assert_eq!(
        said(&stderr),
        [
            "glstereo: format side-by-side (Ctrl+F7; Ctrl+Shift+F7 back)",
            "glstereo: eyes exchanged (Ctrl+F8)",
        ],
        "{stderr}"
    );
}

/// tests/clients/glfw_keys.c's window (eyes.h's frame, 160x120) in
/// side-by-side, at eyes.h's sample points.
fn glfw_side_by_side(swapped: bool) -> Expected {
    let mut want = Expected::new();
    for (left_half, x0) in [(true, 0), (false, W / 2)] {
        let left_eye = shown(swapped, true, false).0 == left_half;
        for &(ex, ey) in &EYE_POINTS[..3] {
            let (sx, sy) = (x0 + ex / 2, H / 4 + (H - 1 - ey) / 2);
            want.push(((sx, sy), eye_colour(left_eye, ex, ey)));
        }
    }
    want
}

/// glfw_keys's window in anaglyph-red-cyan.
fn glfw_anaglyph(swapped: bool) -> Expected {
    EYE_POINTS[..3]
        .iter()
        .map(|&(ex, ey)| {
            let (l, r) = shown(swapped, eye_colour(true, ex, ey), eye_colour(false, ex, ey));
            ((ex, H - 1 - ey), [l[0], r[1], r[2]])
        })
        .collect()
}

#[test]
fn keys_change_the_format_and_eye_order_of_a_glfw_program() {
    let x = Xvfb::start(320, 240);
    let exe = c_client("glfw_keys", &["-lglfw"]);
    let mut p = Running::start(run(&x, &["-m", "side-by-side"], &exe, &[]));
    p.ready();
    let screen = Screen::open(&x.display);
    let w = screen
        .find_window("glfw_keys")
        .expect("the glfw_keys window");
    wait_for(&screen, w, &glfw_side_by_side(false), "GLFW side-by-side");
    screen.type_keys(w, &[(CTRL, XK_F7)]);
    wait_for(
        &screen,
        w,
        &glfw_anaglyph(false),
        "GLFW anaglyph after Ctrl+F7",
    );
    screen.type_keys(w, &[(CTRL, XK_F8)]);
    wait_for(
        &screen,
        w,
        &glfw_anaglyph(true),
        "GLFW eyes exchanged after Ctrl+F8",
    );
    screen.type_keys(w, &[(NONE, XK_a), (CTRL, XK_F6), (NONE, XK_Escape)]);
    let (lines, stderr) = p.finish_with_stdout();
    let keys = keys_of(&lines);
    // GLFW's key codes: A 65, Escape 256, F6 295, F7 296, F8 297, left
    // Control 341; GLFW_MOD_CONTROL 0x2.
    assert!(
        keys.iter()
            .all(|k| !k.contains(" 296 ") && !k.contains(" 297 ")),
        "the program got a control key: {keys:?}"
    );
    for want in [
        "key press 65 mods 0x0",
        "key release 65 mods 0x0",
        "key press 295 mods 0x2",
        "key press 256 mods 0x0",
    ] {
        assert!(keys.contains(&want), "{want:?} missing from {keys:?}");
    }
    assert_eq!(
        said(&stderr),
        [
            "glstereo: format anaglyph-red-cyan (Ctrl+F7; Ctrl+Shift+F7 back)",
            "glstereo: eyes exchanged (Ctrl+F8)",
            "glstereo: Ctrl+F2 to Ctrl+F6 and Ctrl+T change automatic stereo, which this \
             program does not have (glstereo-run --auto): those keys go to the program",
        ],
        "{stderr}"
    );
}

#[test]
fn keys_change_the_format_and_eye_order_of_a_qt5_program_reading_xcb_itself() {
    let x = Xvfb::start(320, 240);
    let exe = qt5_client("qt_keys");
    let mut cmd = run(&x, &["-m", "side-by-side"], &exe, &[]);
    cmd.env("QT_QPA_PLATFORM", "xcb")
        .env("XDG_RUNTIME_DIR", common::scratch("qt-keys-runtime"));
    let mut p = Running::start(cmd);
    p.ready();
    let screen = Screen::open(&x.display);
    let w = screen
        .find_class("qt_keys")
        .or_else(|| screen.find_window("qt_keys"))
        .expect("the qt_keys window");
    wait_for(&screen, w, &glfw_side_by_side(false), "Qt side-by-side");
    screen.type_keys(w, &[(CTRL, XK_F8)]);
    wait_for(
        &screen,
        w,
        &glfw_side_by_side(true),
        "Qt eyes exchanged after Ctrl+F8",
    );
    screen.type_keys(w, &[(CTRL, XK_F7)]);
    wait_for(
        &screen,
        w,
        &glfw_anaglyph(true),
        "Qt anaglyph after Ctrl+F7",
    );
    screen.type_keys(w, &[(NONE, XK_a), (NONE, XK_Escape)]);
    let (lines, stderr) = p.finish_with_stdout();
    let keys = keys_of(&lines);
    // Qt's key codes: A 0x41, Escape 0x1000000, F7 0x1000036, F8 0x1000037.
    assert!(
        keys.iter()
            .all(|k| !k.contains(" 0x1000036 ") && !k.contains(" 0x1000037 ")),
        "the program got a control key: {keys:?}"
    );
    for want in [
        "key press 0x41 mods 0x0",
        "key release 0x41 mods 0x0",
        "key press 0x1000000 mods 0x0",
    ] {
        assert!(keys.contains(&want), "{want:?} missing from {keys:?}");
    }
    assert_eq!(
        said(&stderr),
        [
            "glstereo: eyes exchanged (Ctrl+F8)",
            "glstereo: format anaglyph-red-cyan (Ctrl+F7; Ctrl+Shift+F7 back)",
        ],
        "{stderr}"
    );
}

#[test]
fn keys_follow_the_keyboard_map_when_it_changes() {
    let x = Xvfb::start(320, 240);
    let (p, w, screen) = start(&x, &["stereo", "next"], &[]);
    wait_for(&screen, w, &keys_anaglyph(false), "the default anaglyph");
    // The key that was F7 becomes F12, and the B key becomes F7.
    let (old_f7, b) = (screen.keycode(XK_F7), screen.keycode(XK_b));
    screen.set_keysym(old_f7, XK_F12);
    screen.set_keysym(b, XK_F7);
    screen.type_keycodes(w, &[(CTRL, b), (CTRL, old_f7)]);
    wait_for(
        &screen,
        w,
        &keys_side_by_side(false),
        "side-by-side after the new Ctrl+F7",
    );
    screen.type_keys(w, &[(NONE, XK_Escape)]);
    let (lines, stderr) = p.finish_with_stdout();
    let keys = keys_of(&lines);
    assert!(
        keys.iter().all(|k| !k.contains(" F7 ")),
        "the program got the control key: {keys:?}"
    );
    assert!(keys.contains(&"key press F12 state 0x4"), "{keys:?}");
    assert_eq!(
        said(&stderr),
        ["glstereo: format side-by-side (Ctrl+F7; Ctrl+Shift+F7 back)"],
        "{stderr}"
    );
}

//! Automatic stereo for programs that draw through EGL (issue 31): OpenGL
//! ES and desktop GL contexts of libEGL, on X11 windows (Xvfb) and as
//! native Wayland clients (weston's headless backend, started here).
//!
//! - tests/c/egl_auto_oracle.c draws one scene as a mono OpenGL ES program
//!   (GLSL ES 3.00, and GLSL ES 1.00 without a #version line) and, without
//!   the layer, each eye with 3D Vision's rule applied by hand: the eyes
//!   `glstereo-run --auto` captures are those pixel for pixel, on X11 and on
//!   Wayland. Without --auto the layer changes no pixel of it.
//! - glmark2 (Debian's glmark2-es2-x11, glmark2-es2-wayland,
//!   glmark2-wayland) under --auto: both eyes drawn, the same content
//!   shifted along rows only, at depth (near and far apart), in the
//!   captures and in what the window shows (the X window grabbed; weston's
//!   screen read with weston-screenshooter).
//!
//! SDL2, GLFW and Qt 5 on EGL are in tests/auto_clients.rs.

mod common;
#[path = "common/parallax.rs"]
mod parallax;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::clients::{Renderer, build_once, one_renderer_at_a_time};
use common::preload::{Screen, built};
use common::weston::Weston;
use common::xvfb::Xvfb;
use glstereo::image::Image;

const W: u32 = 200;
const H: u32 = 150;
const SEPARATION: &str = "100";
const CONVERGENCE: &str = "4";

fn oracle() -> PathBuf {
    build_once("egl_auto_oracle", |out| {
        common::preload::compile_plain(
            &common::root().join("tests/c/egl_auto_oracle.c"),
            out,
            &[
                "-lEGL",
                "-lGLESv2",
                "-lX11",
                "-lwayland-client",
                "-lwayland-egl",
            ],
        )
    })
}

/// Where a program runs: an X server, or a Wayland compositor.
enum Server {
    X(Xvfb),
    Wayland(Weston),
}

impl Server {
    fn name(&self) -> &'static str {
        match self {
            Server::X(_) => "x11",
            Server::Wayland(_) => "wayland",
        }
    }

    fn on<'a>(&self, cmd: &'a mut Command) -> &'a mut Command {
        match self {
            Server::X(x) => cmd.env("DISPLAY", &x.display).env_remove("WAYLAND_DISPLAY"),
            Server::Wayland(w) => w.client(cmd),
        }
    }
}

/// The eye the oracle draws itself with the rule applied by hand (`run`:
/// directly, or under glstereo-run without --auto).
fn by_hand(server: &Server, api: &str, eye: &str, dir: &Path, layer: bool) -> Image {
    let out = dir.join(format!("hand-{eye}-{}.rgba", u8::from(layer)));
    let mut cmd = if layer {
        let mut c = Command::new(&built().run);
        c.arg(oracle());
        c
    } else {
        Command::new(oracle())
    };
    common::run_ok(
        server
            .on(&mut cmd)
            .args([server.name(), api, eye, SEPARATION, CONVERGENCE])
            .arg(&out),
    );
    Image::from_pixels(W, H, std::fs::read(&out).unwrap()).unwrap()
}

/// The eyes glstereo-run --auto captures of the mono oracle (frame
/// `frames`), and its stdout.
fn under_auto(server: &Server, api: &str, frames: u32, dir: &Path) -> ([Image; 2], String) {
    let o = common::run_ok(
        server
            .on(&mut Command::new(&built().run))
            .args([
                "--auto",
                "--separation",
                SEPARATION,
                "--convergence",
                CONVERGENCE,
            ])
            .arg("--capture")
            .arg(dir)
            .arg(oracle())
            .args([server.name(), api, "mono", "frames", &frames.to_string()]),
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !stderr.contains("glstereo:"),
        "the layer complained: {stderr}"
    );
    let eyes = ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-{frames:06}.png"))));
    (eyes, String::from_utf8_lossy(&o.stdout).into_owned())
}

fn differing(a: &Image, b: &Image) -> Vec<(u32, u32, [u8; 4], [u8; 4])> {
    let mut d = Vec::new();
    for y in 0..a.height() {
        for x in 0..a.width() {
            let (p, q) = (a.get(x, y), b.get(x, y));
            if (0..3).any(|c| p[c].abs_diff(q[c]) > 2) {
                d.push((x, y, p, q));
            }
        }
    }
    d
}

fn compare_with_the_oracle(server: &Server, api: &str) {
    let what = format!("{} {api}", server.name());
    let dir = common::scratch(&format!("egl-{}-{api}", server.name()));
    let hand = ["left", "right"].map(|eye| by_hand(server, api, eye, &dir, false));
    // Three frames: the eyes of the last, after two presents and flips.
    let (eyes, stdout) = under_auto(server, api, 3, &dir);
    for (n, eye) in ["left", "right"].into_iter().enumerate() {
        let d = differing(&eyes[n], &hand[n]);
        assert!(
            d.is_empty(),
            "{what}, {eye} eye: {} pixels differ from the eye drawn by hand, \
             e.g. (x, y, --auto, by hand) {:?}",
            d.len(),
            &d[..d.len().min(8)]
        );
    }
    assert!(
        differing(&eyes[0], &eyes[1]).len() > 500,
        "{what}: the eyes are alike"
    );
    // glReadPixels reads the left eye, as the mono program would read its
    // one buffer; the program saw no GL error.
    let p = eyes[0].get(50, H - 1 - 75);
    assert!(
        stdout.contains(&format!("read {} {} {}\n", p[0], p[1], p[2])),
        "{what}: glReadPixels gave {stdout:?}, the left eye has {p:?}"
    );
    assert!(stdout.contains("error 0x0"), "{what}: {stdout}");
    // Without --auto the layer changes nothing of an EGL program.
    for eye in ["left", "right"] {
        let n = usize::from(eye == "right");
        let under = by_hand(server, api, eye, &dir, true);
        assert!(
            differing(&under, &hand[n]).is_empty(),
            "{what}: under glstereo-run without --auto the {eye} eye the program draws differs"
        );
    }
}

#[test]
fn an_opengl_es_program_on_x11_under_auto_equals_each_eye_drawn_by_hand() {
    let _one = one_renderer_at_a_time();
    let server = Server::X(Xvfb::start(W + 40, H + 40));
    compare_with_the_oracle(&server, "es3");
    compare_with_the_oracle(&server, "es100");
}

#[test]
fn an_opengl_es_wayland_client_under_auto_equals_each_eye_drawn_by_hand() {
    let _one = one_renderer_at_a_time();
    let server = Server::Wayland(Weston::start(640, 480));
    compare_with_the_oracle(&server, "es3");
    compare_with_the_oracle(&server, "es100");
}

/// A window composed on the CPU (an anaglyph on llvmpipe: no copy of the
/// eyes serves it) is uploaded as composed, top row first, and blitted
/// upside down into GL's bottom-first window: the X window shows the very
/// composite the capture writes, upright, pixel for pixel.
#[test]
fn an_egl_window_composed_on_the_cpu_shows_the_composite_upright() {
    let _one = one_renderer_at_a_time();
    let server = Server::X(Xvfb::start(W + 40, H + 40));
    let Server::X(x) = &server else {
        unreachable!()
    };
    let what = "the oracle on X11, an anaglyph composed on the CPU";
    let args = |cmd: &mut Command| {
        cmd.args([
            "--auto",
            "--separation",
            SEPARATION,
            "--convergence",
            CONVERGENCE,
            "-m",
            "anaglyph-red-cyan",
        ]);
    };
    let dir = common::scratch("egl-cpu-window");
    let mut once = Command::new(&built().run);
    args(server.on(&mut once));
    common::run_ok(
        once.arg("--capture")
            .arg(&dir)
            .arg(oracle())
            .args(["x11", "es3", "mono"]),
    );
    let want = common::png(&dir.join("composite-000001.png"));
    assert_eq!((want.width(), want.height()), (W, H), "{what}");
    let mut cmd = Command::new(&built().run);
    args(server.on(&mut cmd));
    cmd.arg(oracle())
        .args(["x11", "es3", "mono", "frames", "1000000"]);
    let mut run = Renderer::start(cmd, what);
    let screen = Screen::open(&x.display);
    let (_, shot) = run.picture(
        &screen,
        |s| s.find_window("egl_auto_oracle"),
        |shot| (shot.width(), shot.height()) == (W, H) && differing(shot, &want).is_empty(),
    );
    drop(run);
    assert_eq!((shot.width(), shot.height()), (W, H), "{what}: the window");
    let off = differing(&shot, &want);
    assert!(
        off.is_empty(),
        "{what}: {} pixels of the window are not the captured composite's, e.g. {:?}",
        off.len(),
        &off[..off.len().min(5)]
    );
}

/// The program resizes its window after its first frame (XResizeWindow,
/// or wl_egl_window_resize): the eyes follow, at the new size.
fn follows_a_resize(server: &Server) {
    let what = format!("the oracle on {} resized to 160x120", server.name());
    let dir = common::scratch(&format!("egl-resize-{}", server.name()));
    let o = common::run_ok(
        server
            .on(&mut Command::new(&built().run))
            .args(["--auto", "--separation", SEPARATION, "--capture"])
            .arg(&dir)
            .arg(oracle())
            .args([server.name(), "es3", "mono", "frames", "3", "resize"]),
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("error 0x0"), "{what}: {stdout}");
    let first = ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-000001.png"))));
    let [l, r] = last_captured(&dir, &what);
    assert_eq!(
        (first[0].width(), first[0].height()),
        (W, H),
        "{what}: first frame"
    );
    for eye in [&l, &r] {
        assert_eq!(
            (eye.width(), eye.height()),
            (160, 120),
            "{what}: the last frame's size"
        );
    }
    assert!(
        differing(&l, &r).len() > 100,
        "{what}: the eyes are alike after the resize"
    );
}

#[test]
fn an_egl_window_the_program_resizes_is_followed_on_x11_and_wayland() {
    let _one = one_renderer_at_a_time();
    follows_a_resize(&Server::X(Xvfb::start(W + 40, H + 40)));
    follows_a_resize(&Server::Wayland(Weston::start(640, 480)));
}

/// The last captured eyes in `dir` (the last frame whose two eyes are
/// both written: the program may have been stopped in the middle of one).
fn last_captured(dir: &Path, what: &str) -> [Image; 2] {
    let last = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .filter_map(|e| {
            let n = e.file_name().to_string_lossy().into_owned();
            n.strip_prefix("left-").map(str::to_owned)
        })
        .filter(|n| dir.join(format!("right-{n}")).exists())
        .max()
        .unwrap_or_else(|| panic!("{what}: nothing captured in {}", dir.display()));
    ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-{last}"))))
}

/// glmark2's window size.
const SIZE: (u32, u32) = (800, 600);

/// `glmark2` binary `exe` under `auto` (`--auto`: two rendered eyes, or
/// `--auto=depth`: eyes made from one render's depth; separation 100 %,
/// automatic convergence), side by side, capturing into `dir`, running
/// scene `bench` for `seconds`.
fn glmark2(
    server: &Server,
    auto: &str,
    (exe, bench): (&str, &str),
    seconds: u32,
    dir: &Path,
) -> Command {
    let mut cmd = Command::new(&built().run);
    server
        .on(&mut cmd)
        .args([
            auto,
            "--separation",
            "100",
            "-m",
            "side-by-side-half",
            "--capture",
        ])
        .arg(dir)
        .args([
            exe,
            "-s",
            &format!("{}x{}", SIZE.0, SIZE.1),
            "-b",
            &format!("{bench}:duration={seconds}"),
        ]);
    cmd
}

/// The glmark2 window on weston's screen `shot`: the bounding box (x, y,
/// w, h) of what differs from `empty`, the screen before it mapped, below
/// the panel (whose clock changes).
fn window_box(shot: &Image, empty: &Image) -> Option<(u32, u32, u32, u32)> {
    const PANEL: u32 = 40;
    let (mut x0, mut y0, mut x1, mut y1) = (u32::MAX, u32::MAX, 0, 0);
    for y in PANEL..shot.height() {
        for x in 0..shot.width() {
            if shot.get(x, y) != empty.get(x, y) {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
        }
    }
    (x1 > x0 && y1 > y0).then(|| (x0, y0, x1 - x0 + 1, y1 - y0 + 1))
}

/// The left and right halves of `img`'s region (x, y, w, h).
fn halves_of(img: &Image, (x0, y0, w, h): (u32, u32, u32, u32)) -> [Image; 2] {
    let hw = w / 2;
    [x0, x0 + hw].map(|x| Image::from_fn(hw, h, |i, j| img.get(x + i, y0 + j)))
}

#[test]
fn glmark2_es2_on_x11_under_auto_shows_its_scene_at_depth_in_both_halves() {
    glmark2_es2_on_x11("--auto");
}

/// One render, both eyes made from its depth: the ES context's eyes are
/// memory the layer makes them in (as a GLX window's), then GL composes
/// them and the real eglSwapBuffers shows them.
#[test]
fn glmark2_es2_on_x11_under_auto_depth_shows_its_scene_at_depth_in_both_halves() {
    glmark2_es2_on_x11("--auto=depth");
}

/// glmark2-es2 (EGL on X11) under `auto`: its window's halves, grabbed,
/// and its captured eyes at depth.
fn glmark2_es2_on_x11(auto: &str) {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(1024, 768);
    let server = Server::X(x);
    let dir = common::scratch(&format!("egl-glmark2-es2-x11{auto}"));
    let what = &format!("glmark2-es2 (X11) build {auto}");
    let mut run = Renderer::start(
        glmark2(&server, auto, ("glmark2-es2", "build"), 60, &dir),
        what,
    );
    let Server::X(x) = &server else {
        unreachable!()
    };
    let screen = Screen::open(&x.display);
    let (window, shot) = run.picture(
        &screen,
        |s| s.find_window("glmark2 2023.01"),
        |shot| {
            let [l, r] = halves_of(shot, (0, 0, shot.width(), shot.height()));
            let lit = |img: &Image| common::clients::count(img, |p| p[0] > 40) > 400;
            lit(&l) && lit(&r)
        },
    );
    // The first frames are drawn at convergence 0 (everything at the far
    // limit) until the first measure: on a loaded machine, a few seconds.
    // Grab again until the halves are not one shift everywhere.
    let mut shot = shot;
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
    while std::time::Instant::now() < deadline {
        let [l, r] = halves_of(&shot, (0, 0, shot.width(), shot.height()));
        let p = parallax::measure(&l, &r, 48, 3);
        if p.quantile(0.1) != p.quantile(0.9) {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(500));
        shot = screen.grab(window);
    }
    let stderr = run.quit(&screen, window);
    let _ = glstereo::capture::write_png(&shot, &dir.join("window.png"));
    assert!(!stderr.contains("glstereo:"), "{what}: {stderr}");
    assert_eq!((shot.width(), shot.height()), SIZE, "{what}: window size");
    let [l, r] = halves_of(&shot, (0, 0, SIZE.0, SIZE.1));
    // Half-width eyes: shifts are halved, and a small smooth object has
    // few textured blocks.
    parallax::check_depth_of(&l, &r, 12, 2, &format!("{what}, the window"));
    let [l, r] = last_captured(&dir, what);
    parallax::check_depth(&l, &r, 4, &format!("{what}, the captured eyes"));
}

/// glmark2 on weston under `auto`: its eyes captured, and weston's
/// screen (its composition of the program's surface) with the two halves
/// at depth.
fn glmark2_on_wayland(auto: &str, exe: &str, bench: &str) {
    let _one = one_renderer_at_a_time();
    let server = Server::Wayland(Weston::start(1024, 768));
    let Server::Wayland(weston) = &server else {
        unreachable!()
    };
    let what = format!("{exe} {bench} {auto}");
    let dir = common::scratch(&format!("egl-{exe}-{bench}{auto}"));
    let shots = common::scratch(&format!("egl-{exe}-{bench}{auto}-screen"));
    // The empty desktop, once the shell has drawn it: the same twice.
    let mut empty: Option<Image> = None;
    for _ in 0..40 {
        std::thread::sleep(std::time::Duration::from_millis(500));
        let shot = weston.screenshot(&shots);
        let below_panel = |a: &Image, b: &Image| {
            (40..a.height()).all(|y| (0..a.width()).all(|x| a.get(x, y) == b.get(x, y)))
        };
        match (&empty, shot) {
            (Some(e), Some(s)) if below_panel(e, &s) => break,
            (_, s) => empty = s,
        }
    }
    let empty = empty.unwrap_or_else(|| panic!("{what}: weston showed no desktop"));
    let run = Renderer::start(glmark2(&server, auto, (exe, bench), 60, &dir), &what);
    // The screen once the program has presented a few frames.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    let mut seen = None;
    let mut last_box = None;
    while std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_secs(2));
        let frames = std::fs::read_dir(&dir).map_or(0, |d| d.count());
        // Automatic convergence has settled after the first frames.
        if frames < 90 {
            continue;
        }
        let Some(shot) = weston.screenshot(&shots) else {
            continue;
        };
        let _ = glstereo::capture::write_png(&shot, &shots.join("last.png"));
        last_box = window_box(&shot, &empty);
        if let Some(b) = last_box.filter(|b| b.2 == SIZE.0 && b.3 == SIZE.1) {
            let [l, r] = halves_of(&shot, b);
            let lit = |img: &Image| common::clients::count(img, |p| p[0] > 40) > 400;
            if lit(&l) && lit(&r) {
                // Two more pictures of the window where it is: the scene
                // turns, and its depth is judged on all three
                // ([`parallax::check_depth_of_any`]).
                let mut pairs = vec![[l, r]];
                for _ in 0..2 {
                    std::thread::sleep(std::time::Duration::from_millis(700));
                    if let Some(s) = weston.screenshot(&shots) {
                        if window_box(&s, &empty) == Some(b) {
                            pairs.push(halves_of(&s, b));
                        }
                    }
                }
                seen = Some((shot, pairs));
                break;
            }
        }
    }
    let stderr = run.stop();
    assert!(!stderr.contains("glstereo:"), "{what}: {stderr}");
    let (shot, pairs) = seen.unwrap_or_else(|| {
        panic!(
            "{what}: weston never showed an 800x600 window with both halves drawn (last seen \
             at {last_box:?}): {stderr}"
        )
    });
    let _ = glstereo::capture::write_png(&shot, &shots.join("screen.png"));
    parallax::check_depth_of_any(&pairs, 12, 2, &format!("{what}, weston's screen"));
    let [l, r] = last_captured(&dir, &what);
    parallax::check_depth(&l, &r, 4, &format!("{what}, the captured eyes"));
}

#[test]
fn glmark2_es2_wayland_under_auto_shows_its_scene_at_depth_on_weston() {
    glmark2_on_wayland("--auto", "glmark2-es2-wayland", "build");
}

#[test]
fn glmark2_wayland_desktop_gl_under_auto_shows_its_scene_at_depth_on_weston() {
    glmark2_on_wayland("--auto", "glmark2-wayland", "shadow");
}

/// One render on Wayland, both eyes made from its depth in the ES
/// context's eye memory.
#[test]
fn glmark2_es2_wayland_under_auto_depth_shows_its_scene_at_depth_on_weston() {
    glmark2_on_wayland("--auto=depth", "glmark2-es2-wayland", "build");
}

fn churn() -> PathBuf {
    build_once("egl_churn", |out| {
        common::preload::compile_plain(
            &common::root().join("tests/c/egl_churn.c"),
            out,
            &["-lEGL", "-lGLESv2", "-lX11"],
        )
    })
}

/// What a program of tests/c/proc_usage.h used: resident memory, heap in
/// use (KB) and descriptors, each in the second quarter of its rounds and
/// the last ("usage rss E L fds E L heap E L").
struct Usage {
    rss: (i64, i64),
    fds: (i64, i64),
    heap: (i64, i64),
}

fn usage(lines: &str) -> Usage {
    let l = lines
        .lines()
        .find_map(|l| l.strip_prefix("usage rss "))
        .unwrap_or_else(|| panic!("no usage line in {lines}"));
    let v: Vec<i64> = l
        .split_whitespace()
        .filter_map(|t| t.parse().ok())
        .collect();
    assert_eq!(v.len(), 6, "{l}");
    Usage {
        rss: (v[0], v[1]),
        fds: (v[2], v[3]),
        heap: (v[4], v[5]),
    }
}

/// How much more than Mesa's own a program's resident memory may grow
/// under the layer from the second quarter of its rounds to the last.
const RSS_SLACK_KB: i64 = 2048;

/// The same for the heap it has in use (malloc's, exact to the byte: a
/// leak of a few KB a round shows here first).
const HEAP_SLACK_KB: i64 = 256;

/// Runs `exe ROUNDS` (a program printing every answer it gets, then its
/// [`usage`]) without the layer and under `glstereo-run AUTO` on `x`
/// (`--auto` or `--auto=depth`):
/// every line but the usage the same, nothing of the layer's on stderr,
/// resident memory and heap in use from the second quarter of the rounds
/// to the last growing no more than Mesa's own (with [`RSS_SLACK_KB`],
/// [`HEAP_SLACK_KB`]) and descriptors flat. Mesa's stdout.
fn answers_as_mesa(x: &Xvfb, exe: &Path, auto: &str, rounds: &str) -> String {
    let name = exe.file_name().unwrap_or_default().to_string_lossy();
    let run = |layer: bool| {
        let mut cmd = if layer {
            let mut c = Command::new(&built().run);
            c.arg(auto).arg(exe);
            c
        } else {
            Command::new(exe)
        };
        let out = cmd
            .arg(rounds)
            .env("DISPLAY", &x.display)
            .output()
            .unwrap_or_else(|e| panic!("{name} runs: {e}"));
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(
            out.status.success(),
            "{name} (layer {layer}) exited {}:\n{stderr}",
            out.status
        );
        (stdout, stderr)
    };
    let (mesa, _) = run(false);
    let (ours, stderr) = run(true);
    assert!(mesa.contains("done\n"), "{mesa}");
    let strip = |s: &str| -> Vec<String> {
        s.lines()
            .filter(|l| !l.starts_with("usage "))
            .map(str::to_owned)
            .collect()
    };
    let (a, b) = (strip(&mesa), strip(&ours));
    for (i, (m, o)) in a.iter().zip(&b).enumerate() {
        assert_eq!(m, o, "{name} line {i}: Mesa said {m:?}, under --auto {o:?}");
    }
    assert_eq!(a.len(), b.len(), "{ours}");
    assert!(!stderr.contains("glstereo"), "{stderr}");
    let (m, u) = (usage(&mesa), usage(&ours));
    let grew = |(a, b): (i64, i64)| b - a;
    assert!(
        grew(u.rss) <= grew(m.rss) + RSS_SLACK_KB && grew(u.heap) <= grew(m.heap) + HEAP_SLACK_KB,
        "{name}: resident memory from the second quarter of the rounds to the last: {:?} KB \
         under --auto, {:?} KB without; heap in use {:?} KB under --auto, {:?} KB without",
        u.rss,
        m.rss,
        u.heap,
        m.heap
    );
    assert_eq!(
        u.fds.0, u.fds.1,
        "{name}: descriptors from the second quarter of the rounds to the last"
    );
    mesa
}

#[test]
fn a_hostile_egl_program_gets_mesas_every_answer_under_auto_and_its_memory_stays_flat() {
    // Contexts and surfaces made and destroyed in every order (destroyed
    // while current, the display terminated while current, the X window
    // destroyed under its surface, a fork), windows resized to 1x1, 3x500
    // and 640x2 between frames, calls EGL refuses: every result, error
    // and read-back pixel as Mesa gives them without the layer; nothing
    // on stderr; memory and descriptors flat from rounds 15-29 to 45-59.
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(800, 600);
    let mesa = answers_as_mesa(&x, &churn(), "--auto", "60");
    assert!(mesa.contains("child exited 0"), "{mesa}");
}

#[test]
fn a_hostile_egl_program_gets_mesas_every_answer_under_auto_depth() {
    // The same under --auto=depth, whose ES eyes are memory the CPU reads
    // and writes in place (their second eye's memory begins right after
    // the first's; the display terminated while current at 64x48 once
    // crashed the driver's free of it at the release: round 4).
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(800, 600);
    let mesa = answers_as_mesa(&x, &churn(), "--auto=depth", "24");
    assert!(mesa.contains("child exited 0"), "{mesa}");
}

/// tests/c/egl_targets.c: an OpenGL ES 3.2 program's framebuffer
/// objects of every kind ES has (2D textures of glTexImage2D and
/// glTexStorage2D with mipmaps, cube map faces, 2D array layers,
/// multisample textures and renderbuffers resolved by blits, a texture
/// deleted while attached and its name made a cube map), 1x1 to 640x2,
/// copies between them and copies ES refuses, a new share group every 8
/// rounds. Its draws are orthographic (both eyes the mono picture), so
/// under --auto — where its non-square targets get eyes, bound and bound
/// back by the layer — every pixel read, binding and GL error must be
/// Mesa's without the layer; memory and descriptors flat.
#[test]
fn an_opengl_es_programs_render_targets_of_every_kind_get_mesas_every_answer_under_auto() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(400, 300);
    let exe = build_once("egl_targets", |out| {
        common::preload::compile_plain(
            &common::root().join("tests/c/egl_targets.c"),
            out,
            &["-lEGL", "-lGLESv2", "-lX11"],
        )
    });
    answers_as_mesa(&x, &exe, "--auto", "96");
}

/// `exe args` run to its end, without the layer (`option` None) or as
/// `glstereo-run OPTION exe args`, with `display` as DISPLAY (None: no
/// X display at all): its stdout and stderr. It must exit 0.
fn run_to_end(
    exe: &Path,
    option: Option<&str>,
    args: &[&str],
    display: Option<&str>,
) -> (String, String) {
    let mut cmd = match option {
        Some(o) => {
            let mut c = Command::new(&built().run);
            c.arg(o).arg(exe);
            c
        }
        None => Command::new(exe),
    };
    cmd.args(args);
    match display {
        Some(d) => cmd.env("DISPLAY", d),
        None => cmd.env_remove("DISPLAY"),
    };
    let out = cmd.output().expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        out.status.success(),
        "{} {option:?} {args:?}: {}\n{stderr}",
        exe.display(),
        out.status
    );
    (String::from_utf8_lossy(&out.stdout).into_owned(), stderr)
}

/// tests/c/egl_share_groups.c: the program's framebuffer objects in a
/// share group beside the one where the layer made its own, and in one
/// made after that group ended, with the same small names as the
/// layer's: the program's glDeleteFramebuffers deletes them as without
/// the layer (the layer's names are its own only in their group; it
/// used to drop the program's delete of a name it held in any group).
#[test]
fn a_programs_framebuffers_in_another_share_group_are_its_own_to_delete_under_auto() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(400, 300);
    let exe = build_once("egl_share_groups", |out| {
        common::preload::compile_plain(
            &common::root().join("tests/c/egl_share_groups.c"),
            out,
            &["-lEGL", "-lGLESv2", "-lX11"],
        )
    });
    let display = Some(x.display.as_str());
    let (mesa, _) = run_to_end(&exe, None, &[], display);
    let (ours, stderr) = run_to_end(&exe, Some("--auto"), &[], display);
    assert!(mesa.contains("done\n") && mesa.contains("is 0"), "{mesa}");
    assert_eq!(ours, mesa, "under --auto (stderr: {stderr})");
}

/// tests/c/egl_close.c: an EGL program closes its X display while its
/// context is current on one of its windows, then clears and swaps on
/// (Mesa keeps the surface; the swap succeeds) and exits without
/// eglTerminate. The layer puts an EGL window's frames to the X server
/// through that display (MIT-SHM): its XCloseDisplay frees the images
/// and ends that, so the program gets Mesa's every answer under both
/// kinds of automatic stereo (before: the swap after the close crashed in
/// the layer's XSync of the freed display).
#[test]
fn an_egl_program_that_closes_its_x_display_while_current_swaps_on_as_under_mesa() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(320, 240);
    let exe = build_once("egl_close", |out| {
        common::preload::compile_plain(
            &common::root().join("tests/c/egl_close.c"),
            out,
            &["-lEGL", "-lGLESv2", "-lX11"],
        )
    });
    let display = Some(x.display.as_str());
    let (mesa, _) = run_to_end(&exe, None, &[], display);
    assert!(
        mesa.ends_with("swap-display-closed 1 0x3000\ndone\n"),
        "{mesa}"
    );
    for auto in ["--auto", "--auto=depth"] {
        let (ours, stderr) = run_to_end(&exe, Some(auto), &[], display);
        assert_eq!(ours, mesa, "under {auto} (stderr: {stderr})");
    }
}

/// A program on an EGL display with no windows (Mesa's surfaceless
/// platform, an EGL device: where `vglrun -d egl` renders a program's GLX
/// frames) has nothing to show eyes in: under either automatic mode it
/// gets Mesa's every answer, and stderr tells the user once where the
/// layer goes instead of leaving them with a silent mono picture.
#[test]
fn a_program_on_a_windowless_egl_display_stays_mono_under_auto_and_is_told_why() {
    let _one = one_renderer_at_a_time();
    let exe = build_once("egl_windowless", |out| {
        common::preload::compile_plain(
            &common::root().join("tests/c/egl_windowless.c"),
            out,
            &["-lEGL", "-lGLESv2"],
        )
    });
    let said = "--auto: a context on an EGL device or surfaceless display has no window \
                to show two eyes in, so it stays mono; under VirtualGL, start the layer \
                inside it: vglrun -d egl glstereo-run --auto PROGRAM";
    for platform in ["surfaceless", "device"] {
        let run = |layer: Option<&str>| run_to_end(&exe, layer, &[platform], None);
        let (mesa, _) = run(None);
        assert!(
            mesa.contains("pixel 32,24: 0 255 0 255\n") && mesa.ends_with("error 0x0\ndone\n"),
            "{mesa}"
        );
        for auto in ["--auto", "--auto=depth"] {
            let (ours, stderr) = run(Some(auto));
            assert_eq!(ours, mesa, "{platform} {auto} (stderr: {stderr})");
            assert_eq!(
                stderr.matches(said).count(),
                1,
                "{platform} {auto}: said once, and nothing else: {stderr}"
            );
            assert_eq!(stderr.lines().count(), 1, "{platform} {auto}: {stderr}");
        }
        let (ours, stderr) = run(Some("--"));
        assert_eq!(ours, mesa, "{platform} without --auto");
        assert!(stderr.is_empty(), "{platform} without --auto: {stderr}");
    }
}

/// Runs tests/c/egl_threads.c (two threads, one EGLDisplay, a window,
/// surface and ES 2 context each) under `glstereo-run OPTIONS` with
/// `args`, `rounds` times on `x`: each time both threads report their
/// `frames` frames as their own picture, and the layer says nothing.
fn egl_threads(x: &Xvfb, options: &[&str], args: &[&str], frames: u32, rounds: u32) {
    let program = build_once("egl_threads", |out| {
        common::preload::compile_plain(
            &common::root().join("tests/c/egl_threads.c"),
            out,
            &["-lEGL", "-lGLESv2", "-lX11", "-lpthread"],
        )
    });
    let want = format!("thread 0 ok {frames}\nthread 1 ok {frames}\n");
    for round in 0..rounds {
        let out = Command::new(&built().run)
            .args(options)
            .arg(&program)
            .arg(frames.to_string())
            .args(args)
            .env("DISPLAY", &x.display)
            .output()
            .expect("egl_threads runs");
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        let what = format!("{options:?} {args:?} round {round}");
        assert!(
            out.status.success() && stdout.contains(&want),
            "{what}: exited {}:\n{stdout}{stderr}",
            out.status
        );
        assert!(!stderr.contains("glstereo"), "{what}: {stderr}");
    }
}

#[test]
fn two_threads_drawing_through_egl_under_auto_each_read_their_own_picture() {
    // 300 frames each with read-backs, five times: a race shows as a
    // wrong read-back, an error or a crash now and then, not every time.
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(400, 300);
    egl_threads(&x, &["--auto", "-m", "side-by-side"], &[], 300, 5);
}

#[test]
fn egl_terminated_while_two_threads_draw_under_auto_lets_them_draw_until_they_release() {
    // tests/c/egl_threads.c "terminate": eglTerminate halfway while both
    // threads' contexts are current; EGL keeps them usable until
    // released, so each goes on reading its own picture, its swaps fail
    // with EGL_NOT_INITIALIZED as without the layer, and its release frees
    // its share group in the driver. At 64x48 the first eye's last row
    // ends where the second eye's memory begins: the layer readies that
    // memory for the driver at the release (once a crash there).
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(400, 300);
    for auto in ["--auto", "--auto=depth"] {
        egl_threads(&x, &[auto], &["terminate"], 40, 3);
    }
}

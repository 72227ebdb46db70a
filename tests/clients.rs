//! Real clients under glstereo-run, each unmodified, on a private Xvfb:
//! programs written on Debian's own toolkits (GLFW 3.3, SDL2, PyOpenGL +
//! freeglut, libepoxy, Qt 5, Qt 6), OpenSceneGraph's osgshape and Mesa's glxgears, each
//! finding GL the way its toolkit does (a direct link, dlopen + dlsym,
//! ctypes, glXGetProcAddress). Each must get stereo, land each eye's
//! clears and draws in that eye's buffers, and show both eyes in its window
//! in `side-by-side` (read back with XGetImage, checked half by half).
//!
//! Also: the loader's answers to bad input are the same with and without
//! the layer (dl_probe.c), glstereo composes with a GL layer of our own
//! preloaded below it (forwarder.c, built as VirtualGL's faker and as a
//! layer that hands out its own wrappers), and apitrace records a
//! glstereo-run session that it replays.
//!
//! The programs are in tests/clients/ (their headers say what they print).

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Mutex, MutexGuard, OnceLock};
use std::time::{Duration, Instant};

use common::preload::{Running, Screen, built, grab_ready};
use common::xvfb::Xvfb;
use glstereo::image::Image;

/// The clients' window (eye) size, as tests/clients/eyes.h draws it.
const W: u32 = 160;
const H: u32 = 120;

/// Debian's python3, which has python3-opengl (not a pyenv one on PATH).
const PYTHON: &str = "/usr/bin/python3";

fn clients() -> PathBuf {
    common::root().join("tests/clients")
}

/// Builds `out_name` once per test binary with `compile(tmp_path)`; the
/// lock serialises the compilers (two cores are shared).
fn build_once(out_name: &str, compile: impl FnOnce(&Path)) -> PathBuf {
    static BUILT: OnceLock<Mutex<HashMap<String, PathBuf>>> = OnceLock::new();
    let mut map = BUILT
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(p) = map.get(out_name) {
        return p.clone();
    }
    let dir = common::lib_dir().join("test-clients");
    std::fs::create_dir_all(&dir).unwrap();
    let exe = dir.join(out_name);
    let tmp = dir.join(format!(".{out_name}-{}", std::process::id()));
    compile(&tmp);
    std::fs::rename(&tmp, &exe).unwrap();
    map.insert(out_name.to_owned(), exe.clone());
    exe
}

fn compile(cmd: &mut Command, what: &str) {
    let o = cmd.output().unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        o.status.success(),
        "compiling {what} failed:\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// tests/clients/NAME.c, strict C99, linked with `libs` only.
fn c_client(name: &str, libs: &[&str]) -> PathBuf {
    build_once(name, |out| {
        compile(
            Command::new("cc")
                .args(common::C_FLAGS)
                .arg(clients().join(format!("{name}.c")))
                .arg("-o")
                .arg(out)
                .args(libs),
            name,
        )
    })
}

/// tests/clients/qt_stereo.cpp against Qt5Gui (pkg-config).
fn qt_client() -> PathBuf {
    build_once("qt_stereo", |out| {
        let pc = common::run_ok(Command::new("pkg-config").args(["--cflags", "--libs", "Qt5Gui"]));
        let flags = String::from_utf8_lossy(&pc.stdout).into_owned();
        compile(
            Command::new("g++")
                .args([
                    "-std=c++17",
                    "-Wall",
                    "-Wextra",
                    "-Wpedantic",
                    "-Werror",
                    "-g",
                    "-fPIC",
                ])
                .arg(clients().join("qt_stereo.cpp"))
                .arg("-o")
                .arg(out)
                .args(flags.split_whitespace()),
            "qt_stereo.cpp",
        )
    })
}

/// tests/clients/qt6_stereo.cpp against Qt 6's widgets (pkg-config).
fn qt6_client() -> PathBuf {
    build_once("qt6_stereo", |out| {
        let pc = common::run_ok(Command::new("pkg-config").args([
            "--cflags",
            "--libs",
            "Qt6OpenGLWidgets",
            "Qt6Widgets",
            "Qt6OpenGL",
            "Qt6Gui",
        ]));
        let flags = String::from_utf8_lossy(&pc.stdout).into_owned();
        compile(
            Command::new("g++")
                .args([
                    "-std=c++17",
                    "-Wall",
                    "-Wextra",
                    "-Wpedantic",
                    "-Werror",
                    "-g",
                    "-fPIC",
                ])
                .arg(clients().join("qt6_stereo.cpp"))
                .arg("-o")
                .arg(out)
                .args(flags.split_whitespace()),
            "qt6_stereo.cpp",
        )
    })
}

/// tests/clients/forwarder.c as a shared library: linked as VirtualGL's
/// faker is (`local` false) or with -Bsymbolic-functions, so that the
/// wrappers its glXGetProcAddress returns are its own (`local` true).
fn forwarder(local: bool) -> PathBuf {
    let name = if local {
        "forwarder-local.so"
    } else {
        "forwarder.so"
    };
    build_once(name, |out| {
        let mut cmd = Command::new("cc");
        cmd.args(common::C_FLAGS)
            .args(["-fPIC", "-shared"])
            .arg(clients().join("forwarder.c"))
            .arg("-o")
            .arg(out);
        if local {
            cmd.arg("-Wl,-Bsymbolic-functions");
        }
        // It resolves everything with dlsym: keep libGL as a dependency, so
        // dlsym on its own handle finds libGL's functions too.
        cmd.args(["-Wl,--no-as-needed", "-lGL"]);
        compile(&mut cmd, name)
    })
}

/// The legacy GLX stereo program of tests/c (links -lGL -lX11).
fn legacy_stereo() -> PathBuf {
    build_once("legacy_stereo", |out| {
        compile(
            Command::new("cc")
                .args(common::C_FLAGS)
                .arg(common::root().join("tests/c/legacy_stereo.c"))
                .arg("-o")
                .arg(out)
                .args(["-lGL", "-lX11"]),
            "legacy_stereo.c",
        )
    })
}

/// Programs that render continuously (OSG, glxgears, apitrace) run one at
/// a time: llvmpipe on two shared cores.
fn one_renderer_at_a_time() -> MutexGuard<'static, ()> {
    static LOCK: Mutex<()> = Mutex::new(());
    LOCK.lock().unwrap_or_else(|e| e.into_inner())
}

/// `glstereo-run -m side-by-side PROGRAM ARGS` on `x`, with the
/// environment a desktop session would give (Qt wants XDG_RUNTIME_DIR).
fn under_layer(x: &Xvfb, program: &Path, args: &[&str]) -> Command {
    // One private runtime directory for every client of this test binary
    // (made once: tests run in parallel).
    static RUNTIME: OnceLock<PathBuf> = OnceLock::new();
    let runtime = RUNTIME.get_or_init(|| {
        let dir = common::scratch("xdg-runtime");
        std::fs::set_permissions(&dir, std::os::unix::fs::PermissionsExt::from_mode(0o700))
            .unwrap();
        dir
    });
    let mut cmd = Command::new(&built().run);
    cmd.args(["-m", "side-by-side"])
        .arg(program)
        .args(args)
        .env("DISPLAY", &x.display)
        .env("XDG_RUNTIME_DIR", runtime)
        .env("QT_QPA_PLATFORM", "xcb");
    cmd
}

/// What one of our clients printed and showed.
struct Outcome {
    /// The window as the X server has it, while the program waits.
    shot: Image,
    /// Its stdout lines up to "ready".
    lines: Vec<String>,
    /// Its stderr.
    stderr: String,
}

/// Runs one of our clients (they print their report, "ready", then wait
/// for a line on stdin) and grabs its window, named `title`.
fn run_client(x: &Xvfb, cmd: Command, title: &str) -> Outcome {
    run_client_saying(x, cmd, title, &[])
}

/// [`run_client`], where the layer may say the lines of `allowed` (each
/// "glstereo:" line of stderr must contain one of them).
fn run_client_saying(x: &Xvfb, cmd: Command, title: &str, allowed: &[&str]) -> Outcome {
    let mut p = Running::start(cmd);
    p.ready();
    let screen = Screen::open(&x.display);
    // The window whose WM_CLASS is the title (Qt also names an unmapped
    // 1x1 leader window after the program), else the one titled so.
    let window = screen
        .find_class(title)
        .or_else(|| screen.find_window(title))
        .unwrap_or_else(|| panic!("no window titled {title}"));
    let shot = screen.grab(window);
    let lines = p.stdout.clone();
    let stderr = p.finish();
    // Kept for a person looking into a failure: test-scratch/shot-N/.
    static SHOTS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = SHOTS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let _ = glstereo::capture::write_png(
        &shot,
        &common::scratch(&format!("shot-{n}")).join(format!("{title}.png")),
    );
    let said = stderr
        .lines()
        .filter(|l| l.contains("glstereo:"))
        .find(|l| !allowed.iter().any(|a| l.contains(a)));
    assert!(said.is_none(), "{title}: the layer complained: {stderr}");
    Outcome {
        shot,
        lines,
        stderr,
    }
}

/// The colour eyes.h puts at eye pixel (x, y) (rows bottom up, as
/// glReadPixels counts them): left eye red with a green square at
/// (-0.75, 0.25)-(-0.25, 0.75), right eye blue with a yellow square at
/// (0.25, -0.75)-(0.75, -0.25).
fn eye_colour(left: bool, x: u32, y: u32) -> [u8; 3] {
    let nx = (x as f64 + 0.5) / W as f64 * 2.0 - 1.0;
    let ny = (y as f64 + 0.5) / H as f64 * 2.0 - 1.0;
    let inside = |x0: f64, y0: f64| nx > x0 && nx < x0 + 0.5 && ny > y0 && ny < y0 + 0.5;
    match left {
        true if inside(-0.75, 0.25) => [0, 255, 0],
        true => [255, 0, 0],
        false if inside(0.25, -0.75) => [255, 255, 0],
        false => [0, 0, 255],
    }
}

/// The program's own report: stereo granted by GL and by the toolkit, no
/// GL error, and each buffer holding its eye before and after the swap.
fn check_report(lines: &[String], what: &str) {
    let report = lines
        .iter()
        .find(|l| l.starts_with("report "))
        .unwrap_or_else(|| panic!("{what}: no report line in {lines:?}"));
    assert_eq!(
        report, "report gl_stereo 1 toolkit_stereo 1 error 0x0",
        "{what}: stereo granted (GL_STEREO, the toolkit's own query), no GL error"
    );
    let mut buffers = Vec::new();
    for l in lines.iter().filter(|l| l.starts_with("pixel ")) {
        let f: Vec<&str> = l.split_whitespace().collect();
        assert_eq!(f.len(), 7, "{what}: {l}");
        let n: Vec<u32> = f[2..].iter().map(|v| v.parse().unwrap()).collect();
        let left = f[1].ends_with("_LEFT");
        let want = eye_colour(left, n[0], n[1]);
        assert_eq!(
            [n[2] as u8, n[3] as u8, n[4] as u8],
            want,
            "{what}: {} at ({}, {})",
            f[1],
            n[0],
            n[1]
        );
        buffers.push(f[1].to_owned());
    }
    buffers.dedup();
    assert_eq!(
        buffers,
        ["BACK_LEFT", "BACK_RIGHT", "FRONT_LEFT", "FRONT_RIGHT"],
        "{what}: every buffer read (3 points each): {lines:?}"
    );
    assert_eq!(lines.iter().filter(|l| l.starts_with("pixel ")).count(), 12);
}

/// Eye pixels (x, y bottom up) checked on the screen: the middle (the
/// background of both eyes), the centres of the two squares, and points
/// just inside and outside a square's corner.
const EYE_POINTS: [(u32, u32); 7] = [
    (80, 60),
    (40, 90),
    (120, 30),
    (24, 78),
    (16, 72),
    (136, 42),
    (144, 48),
];

/// The window in `side-by-side`: the 2W x H composite scaled by 1/2 to fit
/// the W x H window, centred (rows H/4 .. 3H/4), left eye in the left half.
fn check_side_by_side(shot: &Image, what: &str) {
    check_side_by_side_of(shot, what, eye_colour);
}

/// [`check_side_by_side`] of eyes whose pixels `colour` gives.
fn check_side_by_side_of(shot: &Image, what: &str, colour: impl Fn(bool, u32, u32) -> [u8; 3]) {
    assert_eq!((shot.width(), shot.height()), (W, H), "{what}: window size");
    for (left, x0) in [(true, 0), (false, W / 2)] {
        for &(ex, ey) in &EYE_POINTS {
            let want = colour(left, ex, ey);
            let (sx, sy) = (x0 + ex / 2, H / 4 + (H - 1 - ey) / 2);
            let got = shot.get(sx, sy);
            let close = (0..3).all(|c| got[c].abs_diff(want[c]) <= 8);
            assert!(
                close,
                "{what}: window pixel ({sx},{sy}) is {got:?}, want {want:?} \
                 (the {} eye's pixel ({ex},{ey}))",
                if left { "left" } else { "right" }
            );
        }
    }
}

fn check_client(x: &Xvfb, cmd: Command, title: &str, what: &str) {
    let out = run_client(x, cmd, title);
    check_report(&out.lines, what);
    check_side_by_side(&out.shot, what);
}

/// [`check_client`] on `program args` under the layer, in an Xvfb of its own.
fn check_layered(program: &Path, args: &[&str], title: &str, what: &str) {
    let x = Xvfb::start(320, 240);
    check_client(&x, under_layer(&x, program, args), title, what);
}

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

/// A continuously rendering program of someone else's, started here.
struct Renderer {
    child: Child,
    what: String,
}

impl Renderer {
    fn start(mut cmd: Command, what: &str) -> Renderer {
        let child = cmd
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("{what} starts: {e}"));
        Renderer {
            child,
            what: what.to_owned(),
        }
    }

    /// Waits up to 60 s for `ok` of the window `find` finds; returns the
    /// last picture seen (the test asserts on it).
    fn picture(
        &mut self,
        screen: &Screen,
        find: impl Fn(&Screen) -> Option<u64>,
        ok: impl Fn(&Image) -> bool,
    ) -> (u64, Image) {
        let deadline = Instant::now() + Duration::from_secs(60);
        let mut last = None;
        while Instant::now() < deadline {
            if let Some(status) = self.child.try_wait().unwrap() {
                let err = self.stderr();
                panic!("{} exited early ({status}):\n{err}", self.what);
            }
            if let Some(w) = find(screen) {
                let shot = screen.grab(w);
                if ok(&shot) {
                    return (w, shot);
                }
                last = Some((w, shot));
            }
            std::thread::sleep(Duration::from_millis(250));
        }
        last.unwrap_or_else(|| panic!("{}: no window within 60 s", self.what))
    }

    /// Presses Escape in `window` (these programs quit on it) and returns
    /// stderr, failing unless the program exits 0 within 60 s.
    fn quit(mut self, screen: &Screen, window: u64) -> String {
        screen.press_key(window, x11_dl::keysym::XK_Escape);
        let deadline = Instant::now() + Duration::from_secs(60);
        while Instant::now() < deadline {
            if let Some(status) = self.child.try_wait().unwrap() {
                let err = self.stderr();
                assert!(status.success(), "{} exited {status}:\n{err}", self.what);
                return err;
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        let _ = self.child.kill();
        let err = self.stderr();
        panic!("{} did not quit on Escape:\n{err}", self.what);
    }

    fn stderr(&mut self) -> String {
        let _ = self.child.wait();
        let mut s = String::new();
        if let Some(mut e) = self.child.stderr.take() {
            let _ = std::io::Read::read_to_string(&mut e, &mut s);
        }
        s
    }
}

impl Drop for Renderer {
    fn drop(&mut self) {
        // Only the child this test started, by its handle.
        if self.child.try_wait().ok().flatten().is_none() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// The two halves of a side-by-side window of `w` x `h` (eyes 2:1 fitted
/// at half size, rows h/4 .. 3h/4).
fn halves(shot: &Image) -> (Image, Image) {
    let (w, h) = (shot.width(), shot.height());
    let (hw, top) = (w / 2, h / 4);
    (
        Image::from_fn(hw, h / 2, |x, y| shot.get(x, top + y)),
        Image::from_fn(hw, h / 2, |x, y| shot.get(hw + x, top + y)),
    )
}

fn count(img: &Image, pred: impl Fn([u8; 4]) -> bool) -> u32 {
    let mut n = 0;
    for y in 0..img.height() {
        for x in 0..img.width() {
            n += pred(img.get(x, y)) as u32;
        }
    }
    n
}

/// How many pixels of `img` satisfy `pred`, and their centre.
fn blob(img: &Image, pred: impl Fn([u8; 4]) -> bool) -> (u32, f64, f64) {
    let (mut n, mut sx, mut sy) = (0u32, 0.0, 0.0);
    for y in 0..img.height() {
        for x in 0..img.width() {
            if pred(img.get(x, y)) {
                n += 1;
                sx += x as f64;
                sy += y as f64;
            }
        }
    }
    (n, sx / n.max(1) as f64, sy / n.max(1) as f64)
}

/// Both halves show the same scene (`pred`'s pixels) in about the same
/// amount and place, as two eyes of one frame do; two halves of one mono
/// picture do not.
fn same_scene(left: &Image, right: &Image, pred: impl Fn([u8; 4]) -> bool + Copy, what: &str) {
    let (nl, xl, yl) = blob(left, pred);
    let (nr, xr, yr) = blob(right, pred);
    let (w, h) = (left.width() as f64, left.height() as f64);
    assert!(
        nl > 0
            && nr > 0
            && (nl as f64 / nr as f64) > 0.75
            && (nl as f64 / nr as f64) < 1.33
            && (xl - xr).abs() < w * 0.1
            && (yl - yr).abs() < h * 0.1,
        "{what}: the halves do not show one scene twice: left {nl} pixels around \
         ({xl:.0},{yl:.0}), right {nr} around ({xr:.0},{yr:.0})"
    );
}

/// The rows above and below the fitted side-by-side frame are black.
fn letterboxed(shot: &Image) -> bool {
    let h = shot.height();
    (0..shot.width()).all(|x| {
        [0, h / 4 - 2, h * 3 / 4 + 1, h - 1]
            .iter()
            .all(|&y| shot.get(x, y) == [0, 0, 0, 255])
    })
}

/// Pixels that differ between the two halves (same position in each).
fn differing(a: &Image, b: &Image) -> u32 {
    let mut n = 0;
    for y in 0..a.height() {
        for x in 0..a.width() {
            n += (a.get(x, y) != b.get(x, y)) as u32;
        }
    }
    n
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

/// glxgears' gears: red (0.8, 0.1, 0), green (0, 0.8, 0.2), blue (0.2,
/// 0.2, 1) under one light; the background is black.
fn gears_in(img: &Image) -> bool {
    let red = count(img, |p| p[0] > 90 && p[1] < 40 && p[2] < 40);
    let green = count(img, |p| p[1] > 90 && p[0] < 40);
    let blue = count(img, |p| p[2] > 90 && p[0] < 60 && p[1] < 60);
    red > 50 && green > 50 && blue > 50
}

/// Starts `cmd` (`what`: glxgears -stereo, under the layer) on `x` and
/// quits it once both halves of its window show gears: that window and
/// the program's stderr.
fn gears_shown(x: &Xvfb, cmd: Command, what: &str) -> (Image, String) {
    let mut gears = Renderer::start(cmd, what);
    let screen = Screen::open(&x.display);
    let (window, shot) = gears.picture(
        &screen,
        |s| s.find_window("glxgears"),
        |shot| {
            let (l, r) = halves(shot);
            gears_in(&l) && gears_in(&r)
        },
    );
    let stderr = gears.quit(&screen, window);
    (shot, stderr)
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

#[test]
fn apitrace_records_a_glstereo_run_that_replays() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(640, 480);
    let dir = common::scratch("apitrace");
    let trace = dir.join("gears.trace");
    let mut cmd = Command::new("apitrace");
    cmd.arg("trace")
        .arg("-o")
        .arg(&trace)
        .arg(&built().run)
        .args(["-m", "side-by-side", "glxgears", "-stereo"])
        .env("DISPLAY", &x.display);
    let (shot, stderr) = gears_shown(&x, cmd, "apitrace trace glstereo-run glxgears -stereo");
    let (left, right) = halves(&shot);
    assert!(
        gears_in(&left) && gears_in(&right) && differing(&left, &right) > 100,
        "both eyes under apitrace"
    );
    assert!(!stderr.contains("glstereo:"), "{stderr}");
    let replay = Command::new("apitrace")
        .arg("replay")
        .arg(&trace)
        .env("DISPLAY", &x.display)
        .output()
        .expect("apitrace replay runs");
    assert!(
        replay.status.success(),
        "apitrace replay exited {}:\n{}{}",
        replay.status,
        String::from_utf8_lossy(&replay.stdout),
        String::from_utf8_lossy(&replay.stderr)
    );
    // The trace holds the layer's own calls to GL below it: its framebuffer
    // objects and the composite it presents, with the program's swaps.
    let dump = common::run_ok(Command::new("apitrace").arg("dump").arg(&trace));
    let dump = String::from_utf8_lossy(&dump.stdout);
    for call in ["glBindFramebuffer(", "glXSwapBuffers("] {
        assert!(dump.contains(call), "no {call} in the trace");
    }
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

/// How the forwarder below glstereo finds the functions it forwards to.
#[derive(Clone, Copy, Debug)]
enum Below {
    /// dlsym(RTLD_NEXT); dlopen of libGL is not faked.
    Next,
    /// dlsym(RTLD_NEXT); dlopen of libGL gives the forwarder's handle
    /// (VirtualGL's dlfaker).
    FakedDlopen,
    /// In libGL.so.1 opened at load time through the global dlopen, as
    /// VirtualGL's faker loads its "real" libGL: under glstereo that finds
    /// glstereo's exports, a loop.
    DlopenedLibGl,
}

/// Runs the legacy stereo program under glstereo-run with `forwarder`
/// preloaded below it: it must get stereo and show both eyes. Returns the
/// forwarder's call counts and the program's stderr.
fn legacy_over_forwarder(forwarder: &Path, below: Below) -> (HashMap<String, u64>, String) {
    let x = Xvfb::start(320, 240);
    let counts = common::scratch(&format!(
        "forwarder-{}-{below:?}",
        forwarder.file_name().unwrap().to_string_lossy()
    ))
    .join("counts");
    let mut cmd = under_layer(&x, &legacy_stereo(), &[&W.to_string(), &H.to_string()]);
    cmd.env("LD_PRELOAD", forwarder)
        .env("FORWARDER_COUNTS", &counts)
        .env(
            "FORWARDER_DLOPEN",
            if matches!(below, Below::FakedDlopen) {
                "1"
            } else {
                "0"
            },
        );
    if matches!(below, Below::DlopenedLibGl) {
        cmd.env("FORWARDER_NEXT", "dlopen");
    }
    let (shot, report, stderr) = grab_ready(cmd, &x.display);
    assert!(
        report.contains("glx_stereo 1 gl_stereo 1"),
        "stereo granted over the forwarder: {report}"
    );
    // RedBlue in side-by-side: the left eye's blue square in the left
    // half, the right eye's red one in the right half, grey around.
    let at = |half: u32, nx: f64, ny: f64| {
        shot.get(
            half * W / 2 + ((nx + 1.0) / 4.0 * W as f64) as u32,
            H / 4 + ((1.0 - ny) / 4.0 * H as f64) as u32,
        )
    };
    assert_eq!(at(0, -0.5, -0.5), [0, 0, 255, 255], "left eye, left half");
    assert_eq!(at(0, 0.5, 0.5), [51, 51, 51, 255], "left eye background");
    assert_eq!(at(1, 0.5, 0.5), [255, 0, 0, 255], "right eye, right half");
    assert_eq!(at(1, -0.5, -0.5), [51, 51, 51, 255], "right eye background");
    (read_counts(&counts), stderr)
}

/// As [`legacy_over_forwarder`], for a layer that composes cleanly: the
/// layer says nothing.
fn counts_over_forwarder(forwarder: &Path, below: Below) -> HashMap<String, u64> {
    let (counts, stderr) = legacy_over_forwarder(forwarder, below);
    assert!(
        !stderr.contains("glstereo:"),
        "the layer complained: {stderr}"
    );
    counts
}

fn read_counts(path: &Path) -> HashMap<String, u64> {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("the forwarder wrote no counts ({}): {e}", path.display()));
    text.lines()
        .filter_map(|l| {
            let (n, c) = l.split_once(' ')?;
            Some((n.to_owned(), c.parse().ok()?))
        })
        .collect()
}

/// The calls only glstereo makes (the program calls glXSwapBuffers, which
/// glstereo takes; it never binds a framebuffer) reached the forwarder.
fn assert_layer_calls_went_through(counts: &HashMap<String, u64>, what: &str) {
    for name in ["glXSwapBuffers", "glXChooseVisual", "glBindFramebuffer"] {
        assert!(
            counts.get(name).copied().unwrap_or(0) > 0,
            "{what}: glstereo's {name} did not go through the layer below it: {counts:?}"
        );
    }
}

#[test]
fn the_forwarder_counts_a_plain_programs_calls() {
    // The control: the forwarder alone sees a mono program's calls.
    let x = Xvfb::start(320, 240);
    let counts = common::scratch("forwarder-alone").join("counts");
    let mono = build_once("mono_glx", |out| {
        compile(
            Command::new("cc")
                .args(common::C_FLAGS)
                .arg(common::root().join("tests/c/mono_glx.c"))
                .arg("-o")
                .arg(out)
                .args(["-lGL", "-lX11"]),
            "mono_glx.c",
        )
    });
    let mut cmd = Command::new(mono);
    cmd.env("DISPLAY", &x.display)
        .env("LD_PRELOAD", forwarder(true))
        .env("FORWARDER_COUNTS", &counts);
    let mut p = Running::start(cmd);
    p.ready();
    p.finish();
    let counts = read_counts(&counts);
    for name in ["glXChooseVisual", "glXMakeCurrent", "glXSwapBuffers"] {
        assert!(
            counts.get(name).copied().unwrap_or(0) > 0,
            "{name}: {counts:?}"
        );
    }
}

#[test]
fn stereo_composes_with_a_plain_forwarding_layer_below() {
    // A layer that neither fakes dlopen nor hands out interposed wrappers.
    let counts = counts_over_forwarder(&forwarder(true), Below::Next);
    assert_layer_calls_went_through(&counts, "plain forwarder");
}

#[test]
fn stereo_composes_with_a_layer_that_fakes_dlopen_like_virtualgl() {
    // dlopen("libGL.so.1") gives the forwarder's handle; its
    // glXGetProcAddress hands out its own wrappers.
    let counts = counts_over_forwarder(&forwarder(true), Below::FakedDlopen);
    assert_layer_calls_went_through(&counts, "dlopen-faking forwarder");
}

#[test]
fn stereo_composes_with_a_layer_linked_like_virtualgls_faker() {
    // As above, linked as VirtualGL's faker is: the wrapper addresses it
    // hands out resolve through the global scope, to glstereo's exports
    // (`vglrun glstereo-run` recursed on that until the stack overflowed).
    let counts = counts_over_forwarder(&forwarder(false), Below::FakedDlopen);
    assert_layer_calls_went_through(&counts, "VirtualGL-like forwarder");
}

#[test]
fn a_glfw_program_composes_with_a_layer_below() {
    // GLFW dlopens libGL itself: the layer must be reached that way too,
    // and its real calls still go through the forwarder.
    let x = Xvfb::start(320, 240);
    let counts = common::scratch("forwarder-glfw").join("counts");
    let exe = c_client("glfw_stereo", &["-lglfw"]);
    let mut cmd = under_layer(&x, &exe, &[]);
    cmd.env("LD_PRELOAD", forwarder(true))
        .env("FORWARDER_COUNTS", &counts)
        .env("FORWARDER_DLOPEN", "1");
    check_client(&x, cmd, "glfw_stereo", "GLFW over a forwarder");
    let counts = read_counts(&counts);
    for name in ["glXSwapBuffers", "glBindFramebuffer"] {
        assert!(
            counts.get(name).copied().unwrap_or(0) > 0,
            "glstereo's {name} did not go through the layer below it: {counts:?}"
        );
    }
}

#[test]
fn a_layer_below_whose_real_functions_are_glstereos_is_a_loop_broken_with_a_message() {
    // The forwarder's "real" functions come from dlopen("libGL.so.1") made
    // through glstereo's dlopen at load time: glstereo's own exports. Each
    // call glstereo forwards comes straight back; glstereo must say so and
    // answer with libGL's function, never recurse.
    for local in [true, false] {
        let (counts, stderr) = legacy_over_forwarder(&forwarder(local), Below::DlopenedLibGl);
        assert!(
            stderr.contains("glstereo: glXSwapBuffers") && stderr.contains("loop"),
            "no message about the loop: {stderr}"
        );
        for line in stderr.lines() {
            assert_eq!(
                stderr.lines().filter(|l| *l == line).count(),
                1,
                "said more than once: {line}"
            );
        }
        assert!(
            counts.get("glXSwapBuffers").copied().unwrap_or(0) > 0,
            "{counts:?}"
        );
    }
}

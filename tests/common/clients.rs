//! Running real clients under glstereo-run on a private Xvfb: building
//! the programs of tests/clients/, starting them, grabbing their windows
//! and checking what each eye shows (tests/clients.rs, tests/stacking.rs).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Mutex, MutexGuard, OnceLock};
use std::time::{Duration, Instant};

use super::preload::{Running, Screen, built};
use super::xvfb::Xvfb;
use glstereo::image::Image;

/// The clients' window (eye) size, as tests/clients/eyes.h draws it.
pub const W: u32 = 160;
pub const H: u32 = 120;

/// Debian's python3, which has python3-opengl (not a pyenv one on PATH).
pub const PYTHON: &str = "/usr/bin/python3";

pub fn clients() -> PathBuf {
    super::root().join("tests/clients")
}

/// Builds `out_name` once per test binary with `compile(tmp_path)`; the
/// lock serialises the compilers (two cores are shared).
pub fn build_once(out_name: &str, compile: impl FnOnce(&Path)) -> PathBuf {
    static BUILT: OnceLock<Mutex<HashMap<String, PathBuf>>> = OnceLock::new();
    let mut map = BUILT
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(p) = map.get(out_name) {
        return p.clone();
    }
    let dir = super::lib_dir().join("test-clients");
    std::fs::create_dir_all(&dir).unwrap();
    let exe = dir.join(out_name);
    let tmp = dir.join(format!(".{out_name}-{}", std::process::id()));
    compile(&tmp);
    std::fs::rename(&tmp, &exe).unwrap();
    map.insert(out_name.to_owned(), exe.clone());
    exe
}

pub fn compile(cmd: &mut Command, what: &str) {
    let o = cmd.output().unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        o.status.success(),
        "compiling {what} failed:\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// tests/clients/NAME.c, strict C99, linked with `libs` only.
pub fn c_client(name: &str, libs: &[&str]) -> PathBuf {
    build_once(name, |out| {
        compile(
            Command::new("cc")
                .args(super::C_FLAGS)
                .arg(clients().join(format!("{name}.c")))
                .arg("-o")
                .arg(out)
                .args(libs),
            name,
        )
    })
}

/// tests/clients/NAME.cpp, strict C++17, against the pkg-config `modules`.
pub fn cxx_client(name: &str, modules: &[&str]) -> PathBuf {
    build_once(name, |out| {
        let pc = super::run_ok(
            Command::new("pkg-config")
                .args(["--cflags", "--libs"])
                .args(modules),
        );
        let flags = String::from_utf8_lossy(&pc.stdout).into_owned();
        let source = format!("{name}.cpp");
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
                .arg(clients().join(&source))
                .arg("-o")
                .arg(out)
                .args(flags.split_whitespace()),
            &source,
        )
    })
}

/// tests/clients/qt_stereo.cpp against Qt5Gui.
pub fn qt_client() -> PathBuf {
    qt5_client("qt_stereo")
}

/// tests/clients/NAME.cpp against Qt5Gui.
pub fn qt5_client(name: &str) -> PathBuf {
    cxx_client(name, &["Qt5Gui"])
}

/// tests/clients/qt6_stereo.cpp against Qt 6's widgets.
pub fn qt6_client() -> PathBuf {
    cxx_client(
        "qt6_stereo",
        &["Qt6OpenGLWidgets", "Qt6Widgets", "Qt6OpenGL", "Qt6Gui"],
    )
}

/// tests/clients/forwarder.c as a shared library: linked as VirtualGL's
/// faker is (`local` false) or with -Bsymbolic-functions, so that the
/// wrappers its glXGetProcAddress returns are its own (`local` true).
pub fn forwarder(local: bool) -> PathBuf {
    let name = if local {
        "forwarder-local.so"
    } else {
        "forwarder.so"
    };
    build_once(name, |out| {
        let mut cmd = Command::new("cc");
        cmd.args(super::C_FLAGS)
            .args(["-fPIC", "-shared"])
            .arg(clients().join("forwarder.c"))
            .arg("-o")
            .arg(out);
        if local {
            cmd.arg("-Wl,-Bsymbolic-functions");
        }
        // It resolves everything with dlsym: keep libGL as a dependency, so
        // dlsym on its own handle finds libGL's functions too.
        cmd.args(["-Wl,--no-as-needed", "-lGL", "-lX11"]);
        compile(&mut cmd, name)
    })
}

/// The legacy GLX stereo program of tests/c (links -lGL -lX11).
pub fn legacy_stereo() -> PathBuf {
    c_program("legacy_stereo", &["-lGL", "-lX11"])
}

/// tests/c/NAME.c, a plain program (no glstereo), strict C99, linked
/// with `libs` only.
pub fn c_program(name: &str, libs: &[&str]) -> PathBuf {
    build_once(name, |out| {
        compile(
            Command::new("cc")
                .args(super::C_FLAGS)
                .arg(super::root().join(format!("tests/c/{name}.c")))
                .arg("-o")
                .arg(out)
                .args(libs),
            name,
        )
    })
}

/// Programs that render continuously (OSG, glxgears, apitrace) run one at
/// a time: llvmpipe on two shared cores.
pub fn one_renderer_at_a_time() -> MutexGuard<'static, ()> {
    static LOCK: Mutex<()> = Mutex::new(());
    LOCK.lock().unwrap_or_else(|e| e.into_inner())
}

/// `glstereo-run -m side-by-side PROGRAM ARGS` on `x`, with the
/// environment a desktop session would give (Qt wants XDG_RUNTIME_DIR).
pub fn under_layer(x: &Xvfb, program: &Path, args: &[&str]) -> Command {
    under_layer_with(x, &["-m", "side-by-side"], program, args)
}

/// `glstereo-run OPTIONS PROGRAM ARGS` on `x`, in the environment of
/// [`under_layer`].
pub fn under_layer_with(x: &Xvfb, options: &[&str], program: &Path, args: &[&str]) -> Command {
    // One private runtime directory for every client of this test binary
    // (made once: tests run in parallel).
    static RUNTIME: OnceLock<PathBuf> = OnceLock::new();
    let runtime = RUNTIME.get_or_init(|| {
        let dir = super::scratch("xdg-runtime");
        std::fs::set_permissions(&dir, std::os::unix::fs::PermissionsExt::from_mode(0o700))
            .unwrap();
        dir
    });
    let mut cmd = Command::new(&built().run);
    cmd.args(options)
        .arg(program)
        .args(args)
        .env("DISPLAY", &x.display)
        .env("XDG_RUNTIME_DIR", runtime)
        .env("QT_QPA_PLATFORM", "xcb");
    cmd
}

/// What one of our clients printed and showed.
pub struct Outcome {
    /// The window as the X server has it, while the program waits.
    pub shot: Image,
    /// Its stdout lines up to "ready".
    pub lines: Vec<String>,
    /// Its stderr.
    pub stderr: String,
}

/// Runs one of our clients (they print their report, "ready", then wait
/// for a line on stdin) and grabs its window, named `title`.
pub fn run_client(x: &Xvfb, cmd: Command, title: &str) -> Outcome {
    run_client_saying(x, cmd, title, &[])
}

/// [`run_client`], where the layer may say the lines of `allowed` (each
/// "glstereo:" line of stderr must contain one of them).
pub fn run_client_saying(x: &Xvfb, cmd: Command, title: &str, allowed: &[&str]) -> Outcome {
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
        &super::scratch(&format!("shot-{n}")).join(format!("{title}.png")),
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
pub fn eye_colour(left: bool, x: u32, y: u32) -> [u8; 3] {
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
pub fn check_report(lines: &[String], what: &str) {
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
pub const EYE_POINTS: [(u32, u32); 7] = [
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
pub fn check_side_by_side(shot: &Image, what: &str) {
    check_side_by_side_of(shot, what, eye_colour);
}

/// [`check_side_by_side`] of eyes whose pixels `colour` gives.
pub fn check_side_by_side_of(shot: &Image, what: &str, colour: impl Fn(bool, u32, u32) -> [u8; 3]) {
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

pub fn check_client(x: &Xvfb, cmd: Command, title: &str, what: &str) {
    let out = run_client(x, cmd, title);
    check_report(&out.lines, what);
    check_side_by_side(&out.shot, what);
}

/// [`check_client`] on `program args` under the layer, in an Xvfb of its own.
pub fn check_layered(program: &Path, args: &[&str], title: &str, what: &str) {
    let x = Xvfb::start(320, 240);
    check_client(&x, under_layer(&x, program, args), title, what);
}

/// A continuously rendering program of someone else's, started here.
pub struct Renderer {
    child: Child,
    what: String,
}

impl Renderer {
    pub fn start(mut cmd: Command, what: &str) -> Renderer {
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
    pub fn picture(
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
    pub fn quit(mut self, screen: &Screen, window: u64) -> String {
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

    /// Kills the program (one that never quits by itself, as glmark2 on
    /// Wayland) and returns its stderr.
    pub fn stop(mut self) -> String {
        let _ = self.child.kill();
        self.stderr()
    }

    pub fn stderr(&mut self) -> String {
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
pub fn halves(shot: &Image) -> (Image, Image) {
    let (w, h) = (shot.width(), shot.height());
    let (hw, top) = (w / 2, h / 4);
    (
        Image::from_fn(hw, h / 2, |x, y| shot.get(x, top + y)),
        Image::from_fn(hw, h / 2, |x, y| shot.get(hw + x, top + y)),
    )
}

pub fn count(img: &Image, pred: impl Fn([u8; 4]) -> bool) -> u32 {
    let mut n = 0;
    for y in 0..img.height() {
        for x in 0..img.width() {
            n += pred(img.get(x, y)) as u32;
        }
    }
    n
}

/// How many pixels of `img` satisfy `pred`, and their centre.
pub fn blob(img: &Image, pred: impl Fn([u8; 4]) -> bool) -> (u32, f64, f64) {
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
pub fn same_scene(left: &Image, right: &Image, pred: impl Fn([u8; 4]) -> bool + Copy, what: &str) {
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
pub fn letterboxed(shot: &Image) -> bool {
    let h = shot.height();
    (0..shot.width()).all(|x| {
        [0, h / 4 - 2, h * 3 / 4 + 1, h - 1]
            .iter()
            .all(|&y| shot.get(x, y) == [0, 0, 0, 255])
    })
}

/// Pixels that differ between the two halves (same position in each).
pub fn differing(a: &Image, b: &Image) -> u32 {
    let mut n = 0;
    for y in 0..a.height() {
        for x in 0..a.width() {
            n += (a.get(x, y) != b.get(x, y)) as u32;
        }
    }
    n
}

/// glxgears' gears: red (0.8, 0.1, 0), green (0, 0.8, 0.2), blue (0.2,
/// 0.2, 1) under one light; the background is black.
pub fn gears_in(img: &Image) -> bool {
    let red = count(img, |p| p[0] > 90 && p[1] < 40 && p[2] < 40);
    let green = count(img, |p| p[1] > 90 && p[0] < 40);
    let blue = count(img, |p| p[2] > 90 && p[0] < 60 && p[1] < 60);
    red > 50 && green > 50 && blue > 50
}

/// Starts `cmd` (`what`: glxgears -stereo, under the layer) on `x` and
/// quits it once both halves of its window show gears: that window and
/// the program's stderr.
pub fn gears_shown(x: &Xvfb, cmd: Command, what: &str) -> (Image, String) {
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

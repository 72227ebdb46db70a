//! Running unmodified programs under glstereo-run: the preload crate built
//! for this test run, plain C programs (no glstereo), and their windows
//! read back from the X server (XGetImage), as a screenshot sees them.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::OnceLock;
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

use glstereo::image::Image;
use x11_dl::xlib;

/// glstereo-run and libglstereo_preload.so, built for this test run.
pub struct Built {
    /// target/<profile>/glstereo-run.
    pub run: PathBuf,
    /// target/<profile>/libglstereo_preload.so.
    pub preload: PathBuf,
}

/// Builds the preload crate (library and glstereo-run) with the profile and
/// target directory of this test binary, once per test binary. `cargo
/// test` builds only what the root package's tests link; the preload
/// library is a cdylib of another package, so it is built here, fresh.
///
/// `GLSTEREO_TEST_BUILD=DIR` uses the glstereo-run and preload library
/// already built in DIR (e.g. an older build's target/debug) instead: how
/// to see a test fail on the code before a fix.
pub fn built() -> &'static Built {
    static BUILT: OnceLock<Built> = OnceLock::new();
    BUILT.get_or_init(|| {
        if let Some(dir) = std::env::var_os("GLSTEREO_TEST_BUILD") {
            let dir = PathBuf::from(dir);
            return Built {
                run: dir.join("glstereo-run"),
                preload: dir.join("libglstereo_preload.so"),
            };
        }
        let deps = super::lib_dir();
        let profile_dir = deps.parent().expect("target/<profile>");
        let target = profile_dir.parent().expect("target");
        let profile = match profile_dir.file_name().and_then(|n| n.to_str()) {
            Some("debug") | None => "dev".to_owned(),
            Some(p) => p.to_owned(),
        };
        let out = Command::new(env!("CARGO"))
            .args(["build", "-p", "glstereo-preload", "--profile", &profile])
            .arg("--target-dir")
            .arg(target)
            .current_dir(super::root())
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "building glstereo-preload failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        Built {
            run: profile_dir.join("glstereo-run"),
            preload: profile_dir.join("libglstereo_preload.so"),
        }
    })
}

/// Compiles a plain C program (strict flags, no glstereo) with `libs`.
pub fn compile_plain(source: &Path, out: &Path, libs: &[&str]) {
    let o = Command::new("cc")
        .args(super::C_FLAGS)
        .arg(source)
        .arg("-o")
        .arg(out)
        .args(libs)
        .output()
        .expect("cc runs");
    assert!(
        o.status.success(),
        "compiling {} failed:\n{}",
        source.display(),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A running program that prints `ready …` once its frame is on screen and
/// exits after a line on stdin.
pub struct Running {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: Receiver<String>,
    /// Every stdout line so far.
    pub stdout: Vec<String>,
}

impl Running {
    /// Starts `cmd` with piped stdin/stdout.
    pub fn start(mut cmd: Command) -> Running {
        let mut child = cmd
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("{cmd:?} starts: {e}"));
        let stdout = child.stdout.take().unwrap();
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        Running {
            stdin: child.stdin.take(),
            child,
            lines: rx,
            stdout: Vec::new(),
        }
    }

    /// Waits (up to 60 s) for the `ready` line and returns what follows
    /// "ready " on it.
    pub fn ready(&mut self) -> String {
        loop {
            match self.lines.recv_timeout(Duration::from_secs(60)) {
                Ok(line) => {
                    self.stdout.push(line.clone());
                    if let Some(rest) = line.strip_prefix("ready") {
                        return rest.trim().to_owned();
                    }
                }
                Err(_) => {
                    // Its stdout closed: it is exiting (a crash shows as its
                    // signal); or 60 s passed: it is killed.
                    let mut status = None;
                    for _ in 0..20 {
                        status = self.child.try_wait().ok().flatten();
                        if status.is_some() {
                            break;
                        }
                        std::thread::sleep(Duration::from_millis(100));
                    }
                    let _ = self.child.kill();
                    let out = self.child.wait_with_output_now();
                    let status = status.map_or("still running, killed".into(), |s| s.to_string());
                    panic!(
                        "the program never said ready ({status}); stdout {:?}\nstderr:\n{out}",
                        self.stdout
                    );
                }
            }
        }
    }

    /// The program's process id.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Sends a line to the program's stdin.
    pub fn send(&mut self, line: &str) {
        let stdin = self.stdin.as_mut().expect("stdin open");
        writeln!(stdin, "{line}").expect("the program reads stdin");
        stdin.flush().expect("flush");
    }

    /// Lets the program exit (a line on stdin) and returns its stderr,
    /// failing unless it exits with status 0 within 60 s.
    pub fn finish(self) -> String {
        self.finish_with_stdout().1
    }

    /// [`Running::finish`], with every stdout line the program wrote.
    pub fn finish_with_stdout(mut self) -> (Vec<String>, String) {
        if let Some(mut stdin) = self.stdin.take() {
            let _ = writeln!(stdin);
        }
        for _ in 0..600 {
            if let Some(status) = self.child.try_wait().expect("wait") {
                let err = self.child.wait_with_output_now();
                // Up to the end of its stdout (the reader thread may still
                // be passing the last lines on when the program has exited).
                while let Ok(l) = self.lines.recv_timeout(Duration::from_secs(5)) {
                    self.stdout.push(l);
                }
                assert!(
                    status.success(),
                    "the program exited with {status}; stdout {:?}\nstderr:\n{err}",
                    self.stdout
                );
                return (std::mem::take(&mut self.stdout), err);
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        let _ = self.child.kill();
        panic!("the program did not exit within 60 s");
    }
}

trait StderrNow {
    fn wait_with_output_now(&mut self) -> String;
}

impl StderrNow for Child {
    fn wait_with_output_now(&mut self) -> String {
        let _ = self.wait();
        let mut s = String::new();
        if let Some(mut e) = self.stderr.take() {
            let _ = std::io::Read::read_to_string(&mut e, &mut s);
        }
        s
    }
}

/// Runs `cmd`, a program that prints "ready 0x<its window>", grabs that
/// window on `display` once it is ready and lets the program exit: its
/// window, its first stdout line (its report) and its stderr.
pub fn grab_ready(cmd: Command, display: &str) -> (Image, String, String) {
    let mut p = Running::start(cmd);
    let id = p.ready();
    let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).expect("window id");
    let shot = Screen::open(display).grab(window);
    let report = p.stdout.first().cloned().unwrap_or_default();
    let stderr = p.finish();
    (shot, report, stderr)
}

/// An X connection of the test's own, for screenshots.
pub struct Screen {
    xlib: xlib::Xlib,
    display: *mut xlib::Display,
}

impl Screen {
    /// Connects to `display` (e.g. ":103").
    pub fn open(display: &str) -> Screen {
        let xlib = xlib::Xlib::open().expect("libX11");
        let name = std::ffi::CString::new(display).unwrap();
        // SAFETY: NUL-terminated name.
        let d = unsafe { (xlib.XOpenDisplay)(name.as_ptr()) };
        assert!(!d.is_null(), "cannot open {display}");
        Screen { xlib, display: d }
    }

    /// The window's contents as the server has them (RGBA, alpha 255).
    /// Waits (up to 30 s) for the window to be viewable: XGetImage of a
    /// window not mapped yet is a BadMatch X error, which Xlib's default
    /// handler turns into the exit of the whole test binary (a loaded
    /// machine maps a program's window later than it says it is ready).
    pub fn grab(&self, window: u64) -> Image {
        let x = &self.xlib;
        // SAFETY: valid display; the window exists while the program waits.
        unsafe {
            let mut attrs: xlib::XWindowAttributes = std::mem::zeroed();
            let deadline = std::time::Instant::now() + Duration::from_secs(30);
            loop {
                assert_ne!(
                    (x.XGetWindowAttributes)(self.display, window, &mut attrs),
                    0,
                    "window {window:#x} exists"
                );
                if attrs.map_state == xlib::IsViewable {
                    break;
                }
                assert!(
                    std::time::Instant::now() < deadline,
                    "window {window:#x} is not viewable within 30 s"
                );
                std::thread::sleep(Duration::from_millis(50));
            }
            let (w, h) = (attrs.width as u32, attrs.height as u32);
            let img = (x.XGetImage)(self.display, window, 0, 0, w, h, !0, xlib::ZPixmap);
            assert!(!img.is_null(), "XGetImage of {window:#x}");
            let out = Image::from_fn(w, h, |px, py| {
                let p = (x.XGetPixel)(img, px as i32, py as i32);
                [(p >> 16) as u8, (p >> 8) as u8, p as u8, 255]
            });
            (x.XDestroyImage)(img);
            out
        }
    }

    /// The top-level windows (the root window's children, bottom to top).
    fn top_level(&self) -> Vec<u64> {
        let x = &self.xlib;
        // SAFETY: valid display; the list is freed with XFree.
        unsafe {
            let root = (x.XDefaultRootWindow)(self.display);
            let (mut r, mut parent) = (0, 0);
            let mut children: *mut xlib::Window = std::ptr::null_mut();
            let mut n = 0u32;
            (x.XQueryTree)(
                self.display,
                root,
                &mut r,
                &mut parent,
                &mut children,
                &mut n,
            );
            let windows = (0..n as usize).map(|i| *children.add(i)).collect();
            if !children.is_null() {
                (x.XFree)(children.cast());
            }
            windows
        }
    }

    /// The top-level window whose WM_NAME is `name`.
    pub fn find_window(&self, name: &str) -> Option<u64> {
        let x = &self.xlib;
        self.top_level().into_iter().rfind(|&w| {
            // SAFETY: valid display and window; the name is freed with XFree.
            unsafe {
                let mut title: *mut std::ffi::c_char = std::ptr::null_mut();
                let mut named = false;
                if (x.XFetchName)(self.display, w, &mut title) != 0 && !title.is_null() {
                    named = std::ffi::CStr::from_ptr(title).to_string_lossy() == name;
                    (x.XFree)(title.cast());
                }
                named
            }
        })
    }

    /// The top-level windows whose WM_CLASS class is `class` (e.g.
    /// OpenSceneGraph's unnamed "osgViewer" windows).
    pub fn find_class(&self, class: &str) -> Option<u64> {
        let x = &self.xlib;
        self.top_level().into_iter().rfind(|&w| {
            // SAFETY: valid display and window; the strings are freed with XFree.
            unsafe {
                let mut hint: xlib::XClassHint = std::mem::zeroed();
                let mut classed = false;
                if (x.XGetClassHint)(self.display, w, &mut hint) != 0 {
                    for s in [hint.res_name, hint.res_class] {
                        if !s.is_null() {
                            classed |= std::ffi::CStr::from_ptr(s).to_string_lossy() == class;
                            (x.XFree)(s.cast());
                        }
                    }
                }
                classed
            }
        })
    }

    /// Sends `window` a key press and release of `keysym` (e.g.
    /// `x11_dl::keysym::XK_Escape`), as a user's key would arrive.
    pub fn press_key(&self, window: u64, keysym: u32) {
        let x = &self.xlib;
        // SAFETY: valid display and window; the events are plain structs.
        unsafe {
            let code = (x.XKeysymToKeycode)(self.display, keysym as xlib::KeySym);
            for (kind, mask) in [
                (xlib::KeyPress, xlib::KeyPressMask),
                (xlib::KeyRelease, xlib::KeyReleaseMask),
            ] {
                let mut ev: xlib::XEvent = std::mem::zeroed();
                ev.key = xlib::XKeyEvent {
                    type_: kind,
                    serial: 0,
                    send_event: 1,
                    display: self.display,
                    window,
                    root: (x.XDefaultRootWindow)(self.display),
                    subwindow: 0,
                    time: 0,
                    x: 1,
                    y: 1,
                    x_root: 1,
                    y_root: 1,
                    state: 0,
                    keycode: code as u32,
                    same_screen: 1,
                };
                (x.XSendEvent)(self.display, window, 0, mask, &mut ev);
            }
            (x.XFlush)(self.display);
        }
    }

    /// Types `chords` into `window` as a user at the keyboard would: the
    /// window gets the input focus, then for each chord `(modifiers, key)`
    /// (keysyms, e.g. `&[XK_Control_L]`, `XK_F7`) the modifiers go down,
    /// the key is pressed and released, and the modifiers go up — real key
    /// events made by the server (the XTEST extension, libXtst), whose
    /// state field the server fills from the modifiers held.
    pub fn type_keys(&self, window: u64, chords: &[(&[u32], u32)]) {
        let coded: Vec<(&[u32], u8)> = chords
            .iter()
            .map(|&(mods, key)| (mods, self.keycode(key)))
            .collect();
        self.type_keycodes(window, &coded);
    }

    /// The key (keycode) that has `keysym`, as this connection knows the
    /// keyboard map.
    pub fn keycode(&self, keysym: u32) -> u8 {
        // SAFETY: valid display.
        let c = unsafe { (self.xlib.XKeysymToKeycode)(self.display, keysym as xlib::KeySym) };
        assert_ne!(c, 0, "no key has keysym {keysym:#x}");
        c
    }

    /// [`Screen::type_keys`] with each chord's key given by its keycode.
    pub fn type_keycodes(&self, window: u64, chords: &[(&[u32], u8)]) {
        let x = &self.xlib;
        let xtst = x11_dl::xtest::Xf86vmode::open().expect("libXtst.so.6 (package libxtst6)");
        // SAFETY: valid display and window; XTEST requests only.
        unsafe {
            let (mut ev, mut er, mut major, mut minor) = (0, 0, 0, 0);
            assert_ne!(
                (xtst.XTestQueryExtension)(self.display, &mut ev, &mut er, &mut major, &mut minor),
                0,
                "the X server has no XTEST extension"
            );
            (x.XSetInputFocus)(
                self.display,
                window,
                xlib::RevertToParent,
                xlib::CurrentTime,
            );
            let key = |code: u8, down: bool| {
                (xtst.XTestFakeKeyEvent)(self.display, u32::from(code), down as i32, 0);
            };
            for &(mods, code) in chords {
                for &m in mods {
                    key(self.keycode(m), true);
                }
                key(code, true);
                key(code, false);
                for &m in mods.iter().rev() {
                    key(self.keycode(m), false);
                }
            }
            (x.XSync)(self.display, 0);
        }
    }

    /// Gives key `keycode` the single keysym `keysym` in the server's
    /// keyboard map (as xmodmap does; the server tells the clients).
    pub fn set_keysym(&self, keycode: u8, keysym: u32) {
        let mut sym = keysym as xlib::KeySym;
        // SAFETY: valid display; one keysym for one keycode.
        unsafe {
            (self.xlib.XChangeKeyboardMapping)(self.display, i32::from(keycode), 1, &mut sym, 1);
            (self.xlib.XSync)(self.display, 0);
        }
    }
}

impl Drop for Screen {
    fn drop(&mut self) {
        // SAFETY: our own connection, closed once.
        unsafe { (self.xlib.XCloseDisplay)(self.display) };
    }
}

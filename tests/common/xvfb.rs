//! A private X server for one test: Xvfb on a display number it picks itself
//! (-displayfd), stopped when dropped.
//!
//! Self-contained (no `super::`), so benches/frame_loop includes it too with
//! `#[path = "../../tests/common/xvfb.rs"]`.

use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A running Xvfb.
pub struct Xvfb {
    child: Child,
    /// The display name, e.g. ":103".
    pub display: String,
}

impl Xvfb {
    /// Starts Xvfb with one 24-bit screen of the given size.
    pub fn start(width: u32, height: u32) -> Xvfb {
        Self::start_with(width, height, "")
    }

    /// As [`Xvfb::start`], with more Xvfb arguments (e.g. "-extension GLX").
    pub fn start_with(width: u32, height: u32, extra: &str) -> Xvfb {
        // Beside the test (or bench) binary: target/<profile>/deps/xvfb.
        let exe = std::env::current_exe().expect("test binary path");
        let dir = exe.parent().expect("target/<profile>/deps").join("xvfb");
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir
            .join(format!(
                "display-{}-{:?}",
                std::process::id(),
                std::thread::current().id()
            ))
            .to_string_lossy()
            .replace(['(', ')'], "");
        let _ = std::fs::remove_file(&file);
        // -displayfd writes the chosen display number to fd 3, redirected to a file.
        let child = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "exec Xvfb -displayfd 3 -screen 0 {width}x{height}x24 -nolisten tcp -noreset {extra} 3>'{file}'"
            ))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb starts (package xvfb)");
        // Owned by the guard from here on: a panic below still stops it.
        let mut server = Xvfb {
            child,
            display: String::new(),
        };
        let deadline = Instant::now() + Duration::from_secs(20);
        loop {
            if let Ok(s) = std::fs::read_to_string(&file) {
                if s.ends_with('\n') {
                    let _ = std::fs::remove_file(&file);
                    server.display = format!(":{}", s.trim());
                    return server;
                }
            }
            assert!(
                Instant::now() < deadline,
                "Xvfb did not report a display within 20 s"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Kills the server now (to test a lost connection).
    pub fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        self.kill();
    }
}

/// What is on the screen of `display` in the rectangle (x, y, w, h) of the
/// root window, as RGBA (alpha 255). Windows without a window manager sit at
/// (0, 0), so a window's pixels are the rectangle at the origin.
pub fn screenshot(display: &str, x: i32, y: i32, w: u32, h: u32) -> glstereo::image::Image {
    use x11_dl::xlib::{self, Xlib};
    let xl = Xlib::open().expect("libX11");
    let name = std::ffi::CString::new(display).unwrap();
    // SAFETY: plain Xlib calls on a connection opened and closed here; the
    // image is read within its bounds and destroyed.
    unsafe {
        let dpy = (xl.XOpenDisplay)(name.as_ptr());
        assert!(!dpy.is_null(), "cannot open {display} for a screenshot");
        let root = (xl.XDefaultRootWindow)(dpy);
        let img = (xl.XGetImage)(dpy, root, x, y, w, h, !0, xlib::ZPixmap);
        assert!(!img.is_null(), "XGetImage failed");
        let mut out = glstereo::image::Image::new(w, h);
        for py in 0..h {
            for px in 0..w {
                let p = ((*img).funcs.get_pixel.unwrap())(img, px as i32, py as i32);
                let (r, g, b) = ((p >> 16) & 0xff, (p >> 8) & 0xff, p & 0xff);
                out.set(px, py, [r as u8, g as u8, b as u8, 255]);
            }
        }
        ((*img).funcs.destroy_image.unwrap())(img);
        (xl.XCloseDisplay)(dpy);
        out
    }
}

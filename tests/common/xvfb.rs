//! A private X server for one test: Xvfb on a display number it picks itself
//! (-displayfd), stopped when dropped.

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
        let dir = super::lib_dir().join("xvfb");
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

//! A private Wayland server for one test: weston's headless backend with
//! the pixman renderer (so weston composites, and its screenshooter
//! reads what it shows), in a runtime directory of its own, stopped when
//! dropped.

use std::path::{Path, PathBuf};

use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use glstereo::image::Image;

/// A running weston.
pub struct Weston {
    child: Child,
    /// Its XDG_RUNTIME_DIR.
    pub runtime_dir: PathBuf,
    /// Its socket's name (WAYLAND_DISPLAY).
    pub socket: String,
}

impl Weston {
    /// Starts weston with one `width` × `height` output; `--debug` lets
    /// weston-screenshooter read it.
    pub fn start(width: u32, height: u32) -> Weston {
        let name = format!(
            "weston-{}-{:?}",
            std::process::id(),
            std::thread::current().id()
        )
        .replace(['(', ')'], "");
        let runtime_dir = super::scratch(&name);
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&runtime_dir, std::fs::Permissions::from_mode(0o700)).unwrap();
        let socket = "wayland-test".to_owned();
        let log = std::fs::File::create(runtime_dir.join("weston.log")).unwrap();
        let child = Command::new("weston")
            .args([
                "--backend=headless-backend.so",
                "--use-pixman",
                "--debug",
                "--idle-time=0",
                &format!("--width={width}"),
                &format!("--height={height}"),
                &format!("--socket={socket}"),
            ])
            .env("XDG_RUNTIME_DIR", &runtime_dir)
            .env_remove("WAYLAND_DISPLAY")
            .env_remove("DISPLAY")
            .stdout(Stdio::null())
            .stderr(log)
            .spawn()
            .expect("weston starts (package weston)");
        let server = Weston {
            child,
            runtime_dir,
            socket,
        };
        let deadline = Instant::now() + Duration::from_secs(20);
        while !server.runtime_dir.join(&server.socket).exists() {
            assert!(
                Instant::now() < deadline,
                "weston did not open its socket within 20 s: {}",
                std::fs::read_to_string(server.runtime_dir.join("weston.log")).unwrap_or_default()
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        // The shell's panel and background are up before a client maps.
        std::thread::sleep(Duration::from_millis(500));
        server
    }

    /// `cmd` as a client of this server (and of no X server).
    pub fn client<'a>(&self, cmd: &'a mut Command) -> &'a mut Command {
        cmd.env("XDG_RUNTIME_DIR", &self.runtime_dir)
            .env("WAYLAND_DISPLAY", &self.socket)
            .env_remove("DISPLAY")
    }

    /// What weston shows now, as weston-screenshooter writes it (None when
    /// it wrote nothing within 10 s).
    pub fn screenshot(&self, dir: &Path) -> Option<Image> {
        for e in std::fs::read_dir(dir).ok()?.flatten() {
            if e.file_name()
                .to_string_lossy()
                .starts_with("wayland-screenshot")
            {
                let _ = std::fs::remove_file(e.path());
            }
        }
        let status = self
            .client(&mut Command::new("timeout"))
            .args(["10", "weston-screenshooter"])
            .current_dir(dir)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .ok()?;
        if !status.success() {
            return None;
        }
        let shot = std::fs::read_dir(dir).ok()?.flatten().find(|e| {
            e.file_name()
                .to_string_lossy()
                .starts_with("wayland-screenshot")
        })?;
        Some(super::png(&shot.path()))
    }
}

impl Drop for Weston {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

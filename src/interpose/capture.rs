//! Capture of every presented stereo frame (GLSTEREO_CAPTURE_DIR, what
//! `glstereo-run --capture DIR` sets), numbered from 000001 in
//! presentation order over the whole process, in the formats
//! GLSTEREO_CAPTURE_FORMAT lists (`glstereo-run --capture-format`; default
//! `png`):
//! - `png`: `left-NNNNNN.png`, `right-NNNNNN.png` and
//!   `composite-NNNNNN.png`;
//! - `mpo`, `jps`: the stereo photo `stereo-NNNNNN.mpo` / `.jps`
//!   ([`crate::capture::stereo_photo`]) of the two eyes (exchanged with
//!   GLSTEREO_SWAP_EYES, as a viewer sees them) at GLSTEREO_JPEG_QUALITY
//!   (1…100, default 90).
//!
//! The frame loop only reads the two front buffers back (two glReadPixels
//! in the layer's context); composing (on the CPU, [`crate::output::cpu`],
//! the reference the window's GL composite matches within 1 unit) and PNG
//! encoding run on worker threads. The queue is bounded: when the workers
//! fall behind, presenting waits for room rather than dropping a frame or
//! growing without limit. Frames still queued when the program exits are
//! written before it ends (an `atexit` handler).
//!
//! A child the program makes with fork() inherits the queue but none of
//! its threads (fork copies only the calling thread): the frames in it
//! are the parent's to write, and the workers cannot be joined there (a
//! join of a thread of another process panics, inside the extern "C"
//! exit handler: an abort). So the queue remembers the process that made
//! it: in any other process presenting captures nothing (said once on
//! stderr) and exiting leaves the queue alone, whichever way the child
//! ends (exit, a return from main, _exit, exec).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::sync::{Arc, Mutex, OnceLock};
use std::thread::JoinHandle;

use crate::capture::stereo_photo::{self, DEFAULT_JPEG_QUALITY, StereoPhotoFormat};
use crate::error::{Error, Result};
use crate::image::Image;
use crate::output::OutputMode;
use crate::output::cpu;
use crate::output::options::OutputOptions;

/// The capture directory variable.
pub const ENV_CAPTURE_DIR: &str = "GLSTEREO_CAPTURE_DIR";
/// The capture formats variable: `png`, `jps`, `mpo`, or a comma-separated
/// list of them.
pub const ENV_CAPTURE_FORMAT: &str = "GLSTEREO_CAPTURE_FORMAT";
/// The JPEG quality of captured stereo photos (1…100).
pub const ENV_JPEG_QUALITY: &str = "GLSTEREO_JPEG_QUALITY";

/// What each captured frame is written as.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CaptureSettings {
    /// The left, right and composite PNGs.
    pub png: bool,
    /// Stereo photos, in the order named.
    pub photos: Vec<StereoPhotoFormat>,
    /// Their JPEG quality.
    pub jpeg_quality: u8,
}

impl Default for CaptureSettings {
    fn default() -> Self {
        CaptureSettings {
            png: true,
            photos: Vec::new(),
            jpeg_quality: DEFAULT_JPEG_QUALITY,
        }
    }
}

impl CaptureSettings {
    /// The settings `get` (an environment lookup) gives: the formats of
    /// GLSTEREO_CAPTURE_FORMAT and the quality of GLSTEREO_JPEG_QUALITY,
    /// each defaulted when unset or empty.
    ///
    /// # Errors
    /// [`Error::InvalidValue`] naming the variable, the value and what is
    /// accepted.
    pub fn from_env_with(get: impl Fn(&str) -> Option<String>) -> Result<CaptureSettings> {
        let mut s = CaptureSettings::default();
        if let Some(list) = get(ENV_CAPTURE_FORMAT).filter(|v| !v.trim().is_empty()) {
            s.png = false;
            for name in list.split(',').map(str::trim) {
                let bad = || {
                    Error::invalid_value(format!(
                        "{ENV_CAPTURE_FORMAT}={list}: {name:?} is not a capture format; use \
                         png, jps or mpo, or a comma-separated list of them (png,mpo)"
                    ))
                };
                match name.to_ascii_lowercase().as_str() {
                    "png" => s.png = true,
                    n => {
                        let f = StereoPhotoFormat::ALL
                            .into_iter()
                            .find(|f| f.extension() == n)
                            .ok_or_else(bad)?;
                        if !s.photos.contains(&f) {
                            s.photos.push(f);
                        }
                    }
                }
            }
        }
        if let Some(q) = get(ENV_JPEG_QUALITY).filter(|v| !v.trim().is_empty()) {
            let n = q.trim().parse::<u32>().unwrap_or(0);
            s.jpeg_quality = stereo_photo::check_quality(n)
                .map_err(|e| Error::invalid_value(format!("{ENV_JPEG_QUALITY}={q}: {e}")))?;
        }
        Ok(s)
    }

    /// [`CaptureSettings::from_env_with`] of the process environment.
    pub fn from_env() -> Result<CaptureSettings> {
        Self::from_env_with(|k| std::env::var(k).ok())
    }
}

/// Frames queued per worker before presenting waits.
const QUEUE_PER_WORKER: usize = 2;

/// One presented frame: the two eyes (front buffers, rows top first) and
/// how to compose them.
pub struct Frame {
    /// The left eye.
    pub left: Image,
    /// The right eye.
    pub right: Image,
    /// The output mode the window shows.
    pub mode: OutputMode,
    /// Its options.
    pub options: OutputOptions,
    /// The presented frame's index (frame-sequential parity).
    pub frame_index: u64,
}

/// Where frames go.
pub struct Sink {
    /// The process that started the workers (a forked child has another id).
    pid: u32,
    dir: PathBuf,
    settings: CaptureSettings,
    next: AtomicU64,
    tx: Mutex<Option<SyncSender<(u64, Frame)>>>,
    workers: Mutex<Vec<JoinHandle<()>>>,
}

/// The capture sink, when GLSTEREO_CAPTURE_DIR names a directory (made if
/// missing; if it cannot be, stderr says so once and nothing is captured).
/// An invalid GLSTEREO_CAPTURE_FORMAT or GLSTEREO_JPEG_QUALITY is reported
/// on stderr and the defaults (PNGs) are used.
pub fn sink() -> Option<&'static Sink> {
    static SINK: OnceLock<Option<Sink>> = OnceLock::new();
    SINK.get_or_init(|| {
        let dir = std::env::var_os(ENV_CAPTURE_DIR).filter(|d| !d.is_empty())?;
        let dir = PathBuf::from(dir);
        // A bad value gets the defaults, as the layer's other settings do.
        let settings = CaptureSettings::from_env().unwrap_or_else(|e| {
            super::warn(&format!("{e}; capturing PNGs (the default)"));
            CaptureSettings::default()
        });
        if let Err(e) = std::fs::create_dir_all(&dir) {
            super::warn(&format!(
                "{ENV_CAPTURE_DIR}={}: cannot create the directory ({e}); frames are not captured",
                dir.display()
            ));
            return None;
        }
        Some(Sink::start(dir, settings))
    })
    .as_ref()
}

extern "C" fn flush_at_exit() {
    // A forked child inherits the handler; its parent writes the frames.
    if let Some(s) = sink().filter(|s| s.owned_here()) {
        s.flush();
    }
}

impl Sink {
    fn start(dir: PathBuf, settings: CaptureSettings) -> Sink {
        let workers = std::thread::available_parallelism()
            .map_or(1, |n| n.get())
            .clamp(1, 4);
        let (tx, rx) = sync_channel::<(u64, Frame)>(workers * QUEUE_PER_WORKER);
        let rx = Arc::new(Mutex::new(rx));
        let handles = (0..workers)
            .map(|i| {
                let rx = rx.clone();
                let dir = dir.clone();
                let settings = settings.clone();
                std::thread::Builder::new()
                    .name(format!("glstereo-capture-{i}"))
                    .spawn(move || work(&dir, &settings, &rx))
                    .expect("a capture thread starts")
            })
            .collect();
        // SAFETY: registers a plain extern "C" function once per process.
        unsafe { libc::atexit(flush_at_exit) };
        Sink {
            pid: std::process::id(),
            dir,
            settings,
            next: AtomicU64::new(1),
            tx: Mutex::new(Some(tx)),
            workers: Mutex::new(handles),
        }
    }

    /// The directory frames are written to.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// What each frame is written as.
    pub fn settings(&self) -> &CaptureSettings {
        &self.settings
    }

    /// Whether this process started the workers (false in a forked child).
    fn owned_here(&self) -> bool {
        self.pid == std::process::id()
    }

    /// Queues a frame (waits while the queue is full). In a forked child,
    /// whose queue has no workers, the frame is not captured.
    pub fn submit(&self, frame: Frame) {
        if !self.owned_here() {
            super::warn(&format!(
                "{ENV_CAPTURE_DIR}: frames presented in a child made with fork() are not \
                 captured (the capture threads are its parent's)"
            ));
            return;
        }
        let tx = self.tx.lock().unwrap_or_else(|e| e.into_inner()).clone();
        if let Some(tx) = tx {
            let n = self.next.fetch_add(1, Ordering::Relaxed);
            let _ = tx.send((n, frame));
        }
    }

    /// Writes every queued frame and stops the workers (in the process
    /// that started them: a forked child leaves them alone).
    pub fn flush(&self) {
        if !self.owned_here() {
            return;
        }
        drop(self.tx.lock().unwrap_or_else(|e| e.into_inner()).take());
        let handles = std::mem::take(&mut *self.workers.lock().unwrap_or_else(|e| e.into_inner()));
        for h in handles {
            let _ = h.join();
        }
    }
}

fn work(dir: &Path, settings: &CaptureSettings, rx: &Mutex<Receiver<(u64, Frame)>>) {
    loop {
        let next = rx.lock().unwrap_or_else(|e| e.into_inner()).recv();
        let Ok((n, frame)) = next else {
            return;
        };
        if let Err(e) = write_frame(dir, settings, n, frame) {
            super::warn(&format!("capture: {e}"));
        }
    }
}

fn opaque(mut img: Image) -> Image {
    img.make_opaque();
    img
}

fn write_frame(dir: &Path, settings: &CaptureSettings, n: u64, frame: Frame) -> Result<()> {
    let left = opaque(frame.left);
    let right = opaque(frame.right);
    if settings.png {
        let composite = opaque(cpu::compose(
            frame.mode,
            &frame.options,
            &left,
            &right,
            frame.frame_index,
        )?);
        for (name, img) in [
            ("left", &left),
            ("right", &right),
            ("composite", &composite),
        ] {
            crate::capture::write_png(img, &dir.join(format!("{name}-{n:06}.png")))?;
        }
    }
    let (l, r) = if frame.options.swap_eyes {
        (&right, &left)
    } else {
        (&left, &right)
    };
    for &format in &settings.photos {
        let path = dir.join(format!("stereo-{n:06}.{}", format.extension()));
        stereo_photo::write(format, l, r, settings.jpeg_quality, &path)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(format: Option<&str>, quality: Option<&str>) -> Result<CaptureSettings> {
        CaptureSettings::from_env_with(|k| match k {
            ENV_CAPTURE_FORMAT => format.map(str::to_owned),
            ENV_JPEG_QUALITY => quality.map(str::to_owned),
            _ => None,
        })
    }

    #[test]
    fn capture_formats_are_a_list_of_png_jps_mpo() {
        assert_eq!(settings(None, None).unwrap(), CaptureSettings::default());
        let s = settings(Some("MPO, png,mpo"), Some("75")).unwrap();
        assert!(s.png);
        assert_eq!(s.photos, vec![StereoPhotoFormat::Mpo]);
        assert_eq!(s.jpeg_quality, 75);
        let s = settings(Some("jps"), None).unwrap();
        assert!(!s.png, "only what is named");
        assert_eq!(s.photos, vec![StereoPhotoFormat::Jps]);
        for bad in ["gif", "png,", "png;mpo"] {
            let e = settings(Some(bad), None).unwrap_err().to_string();
            assert!(
                e.contains(ENV_CAPTURE_FORMAT) && e.contains("png, jps or mpo"),
                "{e}"
            );
        }
        for bad in ["0", "101", "high"] {
            let e = settings(None, Some(bad)).unwrap_err().to_string();
            assert!(
                e.contains(ENV_JPEG_QUALITY) && e.contains("1 (smallest"),
                "{e}"
            );
        }
    }
}

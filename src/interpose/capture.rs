//! Capture of every presented stereo frame (GLSTEREO_CAPTURE_DIR, what
//! `glstereo-run --capture DIR` sets): `left-NNNNNN.png`,
//! `right-NNNNNN.png` and `composite-NNNNNN.png`, numbered from 000001 in
//! presentation order over the whole process.
//!
//! The frame loop only reads the two front buffers back (two glReadPixels
//! in the layer's context); composing (on the CPU, [`crate::output::cpu`],
//! the reference the window's GL composite matches within 1 unit) and PNG
//! encoding run on worker threads. The queue is bounded: when the workers
//! fall behind, presenting waits for room rather than dropping a frame or
//! growing without limit. Frames still queued when the program exits are
//! written before it ends (an `atexit` handler).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::sync::{Arc, Mutex, OnceLock};
use std::thread::JoinHandle;

use crate::image::Image;
use crate::output::OutputMode;
use crate::output::cpu;
use crate::output::options::OutputOptions;

/// The capture directory variable.
pub const ENV_CAPTURE_DIR: &str = "GLSTEREO_CAPTURE_DIR";

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
    dir: PathBuf,
    next: AtomicU64,
    tx: Mutex<Option<SyncSender<(u64, Frame)>>>,
    workers: Mutex<Vec<JoinHandle<()>>>,
}

/// The capture sink, when GLSTEREO_CAPTURE_DIR names a directory (made if
/// missing; if it cannot be, stderr says so once and nothing is captured).
pub fn sink() -> Option<&'static Sink> {
    static SINK: OnceLock<Option<Sink>> = OnceLock::new();
    SINK.get_or_init(|| {
        let dir = std::env::var_os(ENV_CAPTURE_DIR).filter(|d| !d.is_empty())?;
        let dir = PathBuf::from(dir);
        if let Err(e) = std::fs::create_dir_all(&dir) {
            super::warn(&format!(
                "{ENV_CAPTURE_DIR}={}: cannot create the directory ({e}); frames are not captured",
                dir.display()
            ));
            return None;
        }
        Some(Sink::start(dir))
    })
    .as_ref()
}

extern "C" fn flush_at_exit() {
    if let Some(s) = sink() {
        s.flush();
    }
}

impl Sink {
    fn start(dir: PathBuf) -> Sink {
        let workers = std::thread::available_parallelism()
            .map_or(1, |n| n.get())
            .clamp(1, 4);
        let (tx, rx) = sync_channel::<(u64, Frame)>(workers * QUEUE_PER_WORKER);
        let rx = Arc::new(Mutex::new(rx));
        let handles = (0..workers)
            .map(|i| {
                let rx = rx.clone();
                let dir = dir.clone();
                std::thread::Builder::new()
                    .name(format!("glstereo-capture-{i}"))
                    .spawn(move || work(&dir, &rx))
                    .expect("a capture thread starts")
            })
            .collect();
        // SAFETY: registers a plain extern "C" function once per process.
        unsafe { libc::atexit(flush_at_exit) };
        Sink {
            dir,
            next: AtomicU64::new(1),
            tx: Mutex::new(Some(tx)),
            workers: Mutex::new(handles),
        }
    }

    /// The directory frames are written to.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Queues a frame (waits while the queue is full).
    pub fn submit(&self, frame: Frame) {
        let tx = self.tx.lock().unwrap_or_else(|e| e.into_inner()).clone();
        if let Some(tx) = tx {
            let n = self.next.fetch_add(1, Ordering::Relaxed);
            let _ = tx.send((n, frame));
        }
    }

    /// Writes every queued frame and stops the workers.
    pub fn flush(&self) {
        drop(self.tx.lock().unwrap_or_else(|e| e.into_inner()).take());
        let handles = std::mem::take(&mut *self.workers.lock().unwrap_or_else(|e| e.into_inner()));
        for h in handles {
            let _ = h.join();
        }
    }
}

fn work(dir: &Path, rx: &Mutex<Receiver<(u64, Frame)>>) {
    loop {
        let next = rx.lock().unwrap_or_else(|e| e.into_inner()).recv();
        let Ok((n, frame)) = next else {
            return;
        };
        if let Err(e) = write_frame(dir, n, frame) {
            super::warn(&format!("capture: {e}"));
        }
    }
}

fn opaque(mut img: Image) -> Image {
    img.make_opaque();
    img
}

fn write_frame(dir: &Path, n: u64, frame: Frame) -> crate::Result<()> {
    let left = opaque(frame.left);
    let right = opaque(frame.right);
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
    Ok(())
}

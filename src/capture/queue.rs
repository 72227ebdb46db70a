//! Captures off the rendering thread (PNG images, MPO/JPS stereo photos):
//! writer threads with a bounded queue, and recycled image buffers.
//!
//! Encoding a 1280x1024 frame takes about 3.6 ms (fast compression) and
//! writing it atomically with fsync 1–5 ms more; both eyes every frame on
//! the rendering thread hold a frame loop under 30 frames/s (measured:
//! 29 frames/s with a light scene). Through this queue the rendering
//! thread only reads the pixels back into a recycled buffer and hands it
//! over. Two threads follow: one encodes ([`super::encode_png`], or
//! [`super::stereo_photo::encode`] for a stereo pair), one
//! writes ([`super::write_atomically`]: temporary file, fsync, rename), so
//! encoding goes on while a file is flushed to disk. The queue holds at
//! most `capacity` images: a program that captures faster than the disk
//! takes them waits in [`CaptureQueue::submit`] (memory stays bounded). Files
//! are written in submission order, so a path captured twice ends with the
//! later image.
//!
//! A failed write is kept and returned by the next [`CaptureQueue::submit`] or
//! [`CaptureQueue::flush`] (the first one since the last report); later
//! captures still go ahead.
//!
//! A child made with fork() inherits the queue but not its threads: there
//! it takes no capture ([`CaptureQueue::submit`] fails), waits for none
//! (the parent writes what was queued) and, dropped, joins no thread.

use crate::sync::LockRecover;
use std::path::PathBuf;
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;

use super::stereo_photo::{self, StereoPhotoFormat};
use crate::error::{Error, Result};
use crate::image::Image;

/// Captures waiting or being written, at most, by default.
pub const DEFAULT_CAPACITY: usize = 4;

/// Pixel buffers kept for reuse, at most.
const FREE_BUFFERS: usize = 8;

/// What a queued capture writes.
#[derive(Debug)]
pub enum Capture {
    /// One image as a PNG.
    Png(Image),
    /// Two eyes as a stereo photo.
    StereoPhoto {
        /// MPO or JPS.
        format: StereoPhotoFormat,
        /// JPEG quality, 1 … 100.
        quality: u8,
        /// The left eye.
        left: Image,
        /// The right eye (the same size).
        right: Image,
    },
}

impl Capture {
    fn encode(&self, path: &std::path::Path, out: &mut Vec<u8>) -> Result<()> {
        match self {
            Capture::Png(image) => super::encode_png(image, path, out),
            Capture::StereoPhoto {
                format,
                quality,
                left,
                right,
            } => stereo_photo::encode(*format, left, right, *quality, path, out),
        }
    }

    fn into_buffers(self) -> Vec<Vec<u8>> {
        match self {
            Capture::Png(image) => vec![image.into_pixels()],
            Capture::StereoPhoto { left, right, .. } => {
                vec![left.into_pixels(), right.into_pixels()]
            }
        }
    }
}

/// What the writer thread shares with the queue's owner.
#[derive(Default)]
struct Shared {
    state: Mutex<State>,
    /// Signalled when an image is done.
    done: Condvar,
}

#[derive(Default)]
struct State {
    /// Submitted and not yet written.
    pending: usize,
    /// The first failure since the last report.
    error: Option<Error>,
    /// Pixel buffers of written captures, for reuse.
    free: Vec<Vec<u8>>,
}

/// Capture writer threads with a bounded queue (see the module documentation).
pub struct CaptureQueue {
    /// The process whose threads these are (a forked child has another id).
    pid: u32,
    sender: Option<SyncSender<(Capture, PathBuf)>>,
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
    capacity: usize,
}

impl std::fmt::Debug for CaptureQueue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "CaptureQueue(capacity {})", self.capacity)
    }
}

impl CaptureQueue {
    /// Starts the writer thread; at most `capacity` (≥ 1) images wait.
    ///
    /// # Errors
    /// [`Error::InvalidValue`] for a capacity of 0; [`Error::Io`] when the
    /// thread cannot be started.
    pub fn new(capacity: usize) -> Result<CaptureQueue> {
        if capacity == 0 {
            return Err(Error::invalid_value(
                "a capture queue needs room for at least one image",
            ));
        }
        // The channel holds capacity − 1: the encoder holds one more.
        let (sender, captures) = sync_channel(capacity - 1);
        // Encoded files waiting for the disk (their pixels are free again).
        let (encoded, files) = sync_channel(2);
        let shared = Arc::new(Shared::default());
        let spawn = |name: &str, f: Box<dyn FnOnce() + Send>| {
            std::thread::Builder::new()
                .name(name.into())
                .spawn(f)
                .map_err(|e| Error::Io(format!("cannot start the capture thread: {e}")))
        };
        let encoder = {
            let shared = shared.clone();
            spawn(
                "glstereo-capture-encode",
                Box::new(move || encode_all(&captures, &encoded, &shared)),
            )?
        };
        let writer = {
            let shared = shared.clone();
            spawn(
                "glstereo-capture-write",
                Box::new(move || write_all(&files, &shared)),
            )?
        };
        Ok(CaptureQueue {
            pid: std::process::id(),
            sender: Some(sender),
            shared,
            workers: vec![encoder, writer],
            capacity,
        })
    }

    /// An image of `width` × `height` to capture into: a written image's
    /// buffer when one is free (no allocation in a steady frame loop), else
    /// a new one. Its contents are unspecified.
    pub fn image(&self, width: u32, height: u32) -> Result<Image> {
        let len = width as usize * height as usize * 4;
        let recycled = {
            let mut st = self.shared.state.recover();
            st.free
                .iter()
                .position(|b| b.capacity() >= len)
                .map(|i| st.free.swap_remove(i))
        };
        match recycled {
            Some(mut buf) => {
                buf.resize(len, 0);
                Image::from_pixels(width, height, buf)
            }
            None => Image::try_new(width, height),
        }
    }

    /// Queues `capture` to be written to `path`; returns at once, unless
    /// the queue is full (then when a capture is done).
    ///
    /// # Errors
    /// The first write of an earlier capture that failed since the last
    /// report (this capture is queued all the same; its own failure is
    /// reported by the next call); [`Error::Io`] if the writer thread is
    /// gone, or in a child made with fork() (nothing queued).
    pub fn submit(&self, capture: Capture, path: PathBuf) -> Result<()> {
        if !self.owned_here() {
            return Err(Error::Io(format!(
                "cannot queue {}: the capture threads belong to the process this one was \
                 forked from; capture from the parent, or write the file directly",
                path.display()
            )));
        }
        // What failed before this capture, taken before it is sent: this
        // capture's own failure is always the next call's to report, never
        // this one's, however fast the writer fails it.
        let earlier = {
            let mut st = self.shared.state.recover();
            st.pending += 1;
            st.error.take()
        };
        let sent = self
            .sender
            .as_ref()
            .expect("the sender lives until drop")
            .send((capture, path));
        if sent.is_err() {
            self.shared.state.recover().pending -= 1;
            return Err(Error::Io("the capture thread has stopped".into()));
        }
        match earlier {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Waits until every queued image is written (in a forked child: at
    /// once; what was queued before the fork is the parent's to write).
    ///
    /// # Errors
    /// The first write that failed since the last report.
    pub fn flush(&self) -> Result<()> {
        if !self.owned_here() {
            return Ok(());
        }
        let mut st = self.shared.state.recover();
        while st.pending > 0 {
            st = self.shared.done.wait(st).unwrap();
        }
        match st.error.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

impl CaptureQueue {
    /// Whether this process started the threads (false in a forked child).
    fn owned_here(&self) -> bool {
        self.pid == std::process::id()
    }
}

impl Drop for CaptureQueue {
    /// Writes what is queued, then stops the thread; in a forked child,
    /// where the threads do not exist, only forgets them.
    fn drop(&mut self) {
        if !self.owned_here() {
            // Neither joined nor detached: they are another process's.
            // The channel and state stay too (a worker of the parent may
            // have held their locks at the fork).
            std::mem::forget(self.sender.take());
            std::mem::forget(std::mem::take(&mut self.workers));
            return;
        }
        self.sender = None;
        for w in self.workers.drain(..) {
            let _ = w.join();
        }
    }
}

/// One image is done (written, or failed with `result`).
fn finish(shared: &Shared, result: Result<()>) {
    let mut st = shared.state.recover();
    if let Err(e) = result {
        st.error.get_or_insert(e);
    }
    st.pending -= 1;
    drop(st);
    shared.done.notify_all();
}

/// The encoding thread: encodes each capture, recycles its buffers (a
/// few: enough for the captures in flight) and passes the file on.
fn encode_all(
    captures: &Receiver<(Capture, PathBuf)>,
    encoded: &SyncSender<(Vec<u8>, PathBuf)>,
    shared: &Shared,
) {
    while let Ok((capture, path)) = captures.recv() {
        let mut bytes = Vec::new();
        let result = capture.encode(&path, &mut bytes);
        {
            let mut st = shared.state.recover();
            for buf in capture.into_buffers() {
                if st.free.len() < FREE_BUFFERS {
                    st.free.push(buf);
                }
            }
        }
        match result {
            Ok(()) => {
                if encoded.send((bytes, path)).is_err() {
                    finish(
                        shared,
                        Err(Error::Io("the capture writer has stopped".into())),
                    );
                }
            }
            Err(e) => finish(shared, Err(e)),
        }
    }
}

/// The writing thread: each encoded file, atomically, in order.
fn write_all(files: &Receiver<(Vec<u8>, PathBuf)>, shared: &Shared) {
    while let Ok((bytes, path)) = files.recv() {
        let result = super::write_atomically(&path, |w| {
            w.write_all(&bytes)
                .map_err(|e| Error::Io(format!("cannot write {}: {e}", path.display())))
        });
        finish(shared, result);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::capture::read_png;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("glstereo-queue-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn queued_images_are_written_in_order_and_buffers_come_back() {
        let d = dir("order");
        let q = CaptureQueue::new(2).unwrap();
        for i in 0..6u8 {
            let mut img = q.image(5, 3).unwrap();
            img.pixels_mut().fill(i * 40);
            // The same path every time: the last image must win.
            q.submit(Capture::Png(img), d.join("same.png")).unwrap();
            let mut other = q.image(5, 3).unwrap();
            other.pixels_mut().fill(i);
            q.submit(Capture::Png(other), d.join(format!("f{i}.png")))
                .unwrap();
        }
        q.flush().unwrap();
        assert_eq!(read_png(&d.join("same.png")).unwrap().get(4, 2), [200; 4]);
        for i in 0..6u8 {
            assert_eq!(
                read_png(&d.join(format!("f{i}.png"))).unwrap().get(0, 0),
                [i; 4]
            );
        }
        let st = q.shared.state.recover();
        assert!(!st.free.is_empty(), "written buffers are kept for reuse");
        drop(st);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_failed_write_is_reported_once_and_later_images_still_go() {
        let d = dir("errors");
        let q = CaptureQueue::new(1).unwrap();
        // Reported by whichever call comes after the failure.
        let e = q
            .submit(
                Capture::Png(Image::new(2, 2)),
                PathBuf::from("/nonexistent-dir/a.png"),
            )
            .err()
            .or_else(|| q.flush().err())
            .expect("the failed write is reported");
        assert!(e.to_string().contains("/nonexistent-dir/a.png"), "{e}");
        q.submit(Capture::Png(Image::new(2, 2)), d.join("b.png"))
            .unwrap();
        q.flush().unwrap();
        assert!(d.join("b.png").exists());
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_forked_child_neither_queues_nor_waits_nor_joins() {
        let d = dir("fork");
        let q = CaptureQueue::new(2).unwrap();
        // Captures in flight at the fork: the parent's to write.
        for i in 0..3 {
            q.submit(
                Capture::Png(Image::new(256, 256)),
                d.join(format!("p{i}.png")),
            )
            .unwrap();
        }
        // SAFETY: the child runs only the queue's code, then _exit; a
        // panic there is caught, never unwinds into the test harness.
        let child = unsafe { libc::fork() };
        assert!(child >= 0, "fork failed");
        if child == 0 {
            let code = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                let child_png = d.join("child.png");
                if q.submit(Capture::Png(Image::new(2, 2)), child_png).is_ok() {
                    return 3; // queued where no thread will write it
                }
                if q.flush().is_err() {
                    return 4;
                }
                drop(q); // no join of the parent's threads
                0
            }))
            .unwrap_or(5);
            // SAFETY: ends the child without the harness's exit handlers.
            unsafe { libc::_exit(code) };
        }
        let mut status = 0;
        let mut waited = 0;
        // SAFETY: our own child; a plain status out-pointer.
        while unsafe { libc::waitpid(child, &mut status, libc::WNOHANG) } == 0 {
            if waited == 200 {
                // SAFETY: our own child.
                unsafe { libc::kill(child, libc::SIGKILL) };
                panic!("the forked child hung (in flush or in joining the parent's threads)");
            }
            std::thread::sleep(std::time::Duration::from_millis(100));
            waited += 1;
        }
        assert!(
            libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0,
            "the child ended with status {status:#x} (3: a capture queued, 4: flush failed, \
             5: a panic, signal: an abort)"
        );
        q.flush().unwrap();
        for i in 0..3 {
            assert!(
                d.join(format!("p{i}.png")).exists(),
                "p{i}.png written by the parent"
            );
        }
        assert!(!d.join("child.png").exists());
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_queue_needs_room() {
        assert!(matches!(CaptureQueue::new(0), Err(Error::InvalidValue(_))));
    }
}

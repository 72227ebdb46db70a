//! Stage timings of a presented stereo frame, for finding where a frame's
//! time goes (`BENCHMARKS.md`, "Breakdown of a stereo frame").
//!
//! Behind the cargo feature `profile-stages`, off by default: without it
//! [`span`] is a plain call of its closure and the frame marks are empty
//! functions, so the instrumented code compiles to what it was. With it,
//! every thread that presents frames sums the wall time of each [`Stage`]
//! and prints, every `GLSTEREO_PROFILE` frames (default 100), one line to
//! stderr with the mean milliseconds per frame of each stage:
//!
//! ```text
//! glstereo profile 1280x1024 over 100 frames (ms/frame): between 1.20 flip 0.01 finish 1.71 ...
//! ```
//!
//! `between` is the time from the end of one present to the start of the
//! next: the program's own work (issuing both eyes' GL calls; llvmpipe
//! rasterizes them later, inside `finish`).
//!
//! ```sh
//! cargo build --release -p glstereo-preload --features profile-stages
//! GLSTEREO_PROFILE=200 target/release/glstereo-run ./program
//! ```

/// A stage of presenting a stereo frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(not(feature = "profile-stages"), allow(dead_code))]
pub(crate) enum Stage {
    /// The program's work between two presents.
    Between,
    /// Flipping the emulated back and front buffers.
    Flip,
    /// glFinish (or glFlush) of the program's rendering.
    Finish,
    /// Making the layer's (compositor's) context current.
    SwitchIn,
    /// Making the program's context current again.
    SwitchOut,
    /// X requests that wait for a reply (drawable geometry, X errors
    /// trapped), other than [`Stage::XSync`].
    RoundTrip,
    /// The XSync that waits for the server to have shown the frame.
    XSync,
    /// glReadPixels of the eyes (or of a GL composite).
    ReadBack,
    /// The CPU composite into the window's image.
    Compose,
    /// A GL composite (shader passes, blits) and glXSwapBuffers.
    GlCompose,
    /// XShmPutImage and its flush.
    Put,
    /// Both eyes made from the frame's colour and depth (`--auto=depth`):
    /// the depth read and the kernel, where they are made apart from the
    /// composite (a composite that reads them row by row makes them
    /// inside [`Stage::Compose`]).
    FromDepth,
}

#[cfg(feature = "profile-stages")]
mod on {
    use super::Stage;
    use std::cell::RefCell;
    use std::time::{Duration, Instant};

    const STAGES: [(Stage, &str); 12] = [
        (Stage::Between, "between"),
        (Stage::Flip, "flip"),
        (Stage::Finish, "finish"),
        (Stage::SwitchIn, "switch-in"),
        (Stage::SwitchOut, "switch-out"),
        (Stage::RoundTrip, "round-trips"),
        (Stage::XSync, "x-sync"),
        (Stage::ReadBack, "read-back"),
        (Stage::Compose, "compose"),
        (Stage::GlCompose, "gl-compose+swap"),
        (Stage::Put, "shm-put"),
        (Stage::FromDepth, "from-depth"),
    ];

    #[derive(Default)]
    struct Sums {
        total: [Duration; STAGES.len()],
        counts: [u32; STAGES.len()],
        frames: u32,
        present: Duration,
        frame_start: Option<Instant>,
        last_end: Option<Instant>,
        size: (u32, u32),
    }

    thread_local! {
        static SUMS: RefCell<Sums> = RefCell::new(Sums::default());
    }

    fn every() -> u32 {
        static EVERY: std::sync::OnceLock<u32> = std::sync::OnceLock::new();
        *EVERY.get_or_init(|| {
            std::env::var("GLSTEREO_PROFILE")
                .ok()
                .and_then(|v| v.parse().ok())
                .filter(|&n| n > 0)
                .unwrap_or(100)
        })
    }

    fn index(stage: Stage) -> usize {
        STAGES
            .iter()
            .position(|(s, _)| *s == stage)
            .expect("every stage is listed")
    }

    pub(crate) fn add(stage: Stage, d: Duration) {
        SUMS.with(|s| {
            let mut s = s.borrow_mut();
            let i = index(stage);
            s.total[i] += d;
            s.counts[i] += 1;
        });
    }

    pub(crate) fn frame_start(size: (u32, u32)) {
        let now = Instant::now();
        SUMS.with(|s| {
            let mut s = s.borrow_mut();
            if let Some(end) = s.last_end {
                let i = index(Stage::Between);
                s.total[i] += now - end;
                s.counts[i] += 1;
            }
            s.frame_start = Some(now);
            s.size = size;
        });
    }

    pub(crate) fn frame_end() {
        let now = Instant::now();
        SUMS.with(|s| {
            let mut s = s.borrow_mut();
            let Some(start) = s.frame_start.take() else {
                return;
            };
            s.present += now - start;
            s.frames += 1;
            if s.frames >= every() {
                let n = f64::from(s.frames);
                let ms = |d: Duration| d.as_secs_f64() * 1e3 / n;
                let mut line = format!(
                    "glstereo profile {}x{} over {} frames (ms/frame): present {:.3}",
                    s.size.0,
                    s.size.1,
                    s.frames,
                    ms(s.present)
                );
                for (i, (_, name)) in STAGES.iter().enumerate() {
                    if s.counts[i] > 0 {
                        line += &format!(" {name} {:.3}", ms(s.total[i]));
                    }
                }
                eprintln!("{line}");
                *s = Sums::default();
            }
            s.last_end = Some(Instant::now());
        });
    }
}

/// Runs `f`, counting its wall time to `stage` (with `profile-stages`).
#[cfg(feature = "profile-stages")]
pub(crate) fn span<T>(stage: Stage, f: impl FnOnce() -> T) -> T {
    let t = std::time::Instant::now();
    let v = f();
    on::add(stage, t.elapsed());
    v
}

/// Runs `f` (timed to `stage` with the feature `profile-stages`).
#[cfg(not(feature = "profile-stages"))]
#[inline(always)]
pub(crate) fn span<T>(_stage: Stage, f: impl FnOnce() -> T) -> T {
    f()
}

/// A present of a frame of `size()` starts (with `profile-stages`).
#[cfg(feature = "profile-stages")]
pub(crate) fn frame_start(size: impl FnOnce() -> (u32, u32)) {
    on::frame_start(size());
}

/// A present starts (a no-op without `profile-stages`; `size` is not
/// called).
#[cfg(not(feature = "profile-stages"))]
#[inline(always)]
pub(crate) fn frame_start(_size: impl FnOnce() -> (u32, u32)) {}

/// A present ended (with `profile-stages`: prints the means every
/// `GLSTEREO_PROFILE` frames).
#[cfg(feature = "profile-stages")]
pub(crate) fn frame_end() {
    on::frame_end();
}

/// A present ended (a no-op without `profile-stages`).
#[cfg(not(feature = "profile-stages"))]
#[inline(always)]
pub(crate) fn frame_end() {}

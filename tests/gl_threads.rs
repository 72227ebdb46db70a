//! Surfaces on several threads composing on GL at once (EGL, llvmpipe):
//! what a program with one surface per thread does, and what the
//! compositor tests do when the test harness runs them in parallel. Each
//! thread makes its own surfaces, draws its eyes, composes them on GL in
//! the modes whose kernels are the heaviest (Dubois, squeezed, interleaved)
//! and checks every pixel against the CPU reference, then destroys them.
//!
//! And one surface composed from two threads at once (EGL and OSMesa), as
//! the API allows ("Any thread" for captures and read-backs).
//!
//! `stress_surfaces_on_threads_compose_at_once` (ignored) is the same at
//! length, for `tests/stress_gl_threads.sh`: `GLSTEREO_STRESS_THREADS`
//! threads (default 4) of `GLSTEREO_STRESS_ROUNDS` surfaces (default 20).

#[path = "common/gl_surface.rs"]
mod gl_surface;

use glstereo::backend::BackendKind;
use glstereo::output::pattern::{gradient, noise};
use glstereo::output::{ComposePath, OutputMode, OutputOptions, compose};
use glstereo::surface;

use gl_surface::*;

/// The modes each round composes.
const MODES: [&str; 5] = [
    "anaglyph-red-cyan-dubois",
    "anaglyph-amber-blue-dubois",
    "side-by-side-half",
    "rows",
    "anaglyph-red-cyan",
];

/// `threads` threads, each making `rounds` surfaces one after the other.
fn surfaces_on_threads(threads: usize, rounds: usize) {
    let handles: Vec<_> = (0..threads)
        .map(|t| {
            std::thread::Builder::new()
                .name(format!("surface-thread-{t}"))
                .spawn(move || {
                    for round in 0..rounds {
                        // Sizes differ per thread and round (odd and even).
                        let w = 31 + ((t * 7 + round * 5) % 40) as u32;
                        let h = 17 + ((t * 3 + round * 11) % 30) as u32;
                        let s = stereo_surface(BackendKind::Egl, w, h);
                        let (l, r) = (gradient(w, h, round as u8), noise(w, h, t as u64));
                        show(&s, &l, &r);
                        let o = OutputOptions {
                            crosstalk: if round % 2 == 1 { 0.2 } else { 0.0 },
                            ..OutputOptions::default()
                        };
                        s.set_options(o).unwrap();
                        for name in MODES {
                            let mode = OutputMode::from_name(name).unwrap();
                            s.set_output(mode).unwrap();
                            let got = s.composite_image_via(ComposePath::Gl).unwrap();
                            let want = compose(mode, &o, &l, &r, s.frames() - 1).unwrap();
                            let what = format!("thread {t}, round {round}, {w}x{h}, {name}");
                            assert_within(&got, &want, 1, &what);
                        }
                        surface::make_current(None).unwrap();
                    }
                })
                .unwrap()
        })
        .collect();
    for h in handles {
        h.join().expect("a surface thread failed");
    }
}

fn env_or(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(default)
}

#[test]
fn surfaces_on_four_threads_compose_on_gl_at_once() {
    surfaces_on_threads(4, 3);
}

#[test]
#[ignore = "a stress run: tests/stress_gl_threads.sh runs it in a loop under load"]
fn stress_surfaces_on_threads_compose_at_once() {
    surfaces_on_threads(
        env_or("GLSTEREO_STRESS_THREADS", 4),
        env_or("GLSTEREO_STRESS_ROUNDS", 20),
    );
}

/// One surface composed from two threads at once (a program capturing it
/// on a thread of its own while another presents, or two capture threads):
/// each call gets the composite. Before, both threads made the surface's
/// compositor context current at once: EGL refused the second (the call
/// failed), OSMesa let the context be current on both.
fn one_surface_composed_on_two_threads(backend: BackendKind) {
    let (w, h) = (40, 24);
    let s = stereo_surface(backend, w, h);
    let (l, r) = (gradient(w, h, 3), noise(w, h, 9));
    show(&s, &l, &r);
    let mode = OutputMode::from_name("anaglyph-red-cyan-dubois").unwrap();
    s.set_output(mode).unwrap();
    let want = compose(mode, &OutputOptions::default(), &l, &r, s.frames() - 1).unwrap();
    // Current on no thread: every call makes the compositor context current itself.
    surface::make_current(None).unwrap();
    let threads: Vec<_> = (0..2)
        .map(|t| {
            let (s, want) = (s.clone(), want.clone());
            std::thread::spawn(move || {
                for round in 0..200 {
                    let got = s
                        .composite_image_via(ComposePath::Gl)
                        .unwrap_or_else(|e| panic!("thread {t}, round {round}: {e}"));
                    assert_within(&got, &want, 1, &format!("thread {t}, round {round}"));
                }
            })
        })
        .collect();
    for t in threads {
        t.join().expect("a composing thread failed");
    }
}

#[test]
fn one_surface_composes_on_two_threads_at_once_egl() {
    one_surface_composed_on_two_threads(BackendKind::Egl);
}

#[test]
fn one_surface_composes_on_two_threads_at_once_osmesa() {
    one_surface_composed_on_two_threads(BackendKind::OsMesa);
}

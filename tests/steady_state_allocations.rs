//! Steady-state frames allocate nothing on the heap: a counting global
//! allocator (this test binary's own) counts the allocations the calling
//! thread makes during frames after the first few. Counted, not timed.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::Arc;

use glstereo::backend::{BackendChoice, BackendKind};
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::gl::enums::*;
use glstereo::image::Image;
use glstereo::output::pattern::noise;
use glstereo::output::{OutputMode, OutputOptions, compose_into};
use glstereo::surface::{self, Surface};

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn count() {
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: forwards to the system allocator; counting touches only a
// thread-local Cell (no allocation, no lock).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: forwarded contract.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: forwarded contract.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: forwarded contract.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded contract.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Heap allocations this thread makes while running `f`.
fn allocations_in(f: impl FnOnce()) -> u64 {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn the_counter_sees_allocations() {
    assert!(allocations_in(|| drop(std::hint::black_box(vec![1u8; 100]))) >= 1);
}

#[test]
fn cpu_composition_into_a_reused_image_allocates_nothing_after_the_first() {
    let (l, r) = (noise(64, 48, 1), noise(64, 48, 2));
    let staged = OutputOptions {
        swap_eyes: true,
        crosstalk: 0.2,
        saturation: 0.5,
    };
    for options in [OutputOptions::default(), staged] {
        for mode in OutputMode::all().filter(|&m| m != OutputMode::Quad) {
            let mut out = Image::new(1, 1);
            compose_into(mode, &options, &l, &r, 3, &mut out).unwrap();
            let n = allocations_in(|| {
                for frame in 0..3 {
                    compose_into(mode, &options, &l, &r, frame, &mut out).unwrap();
                }
            });
            assert_eq!(n, 0, "{mode} with {options:?}: {n} allocations in 3 frames");
        }
    }
}

/// One frame of a quad-buffer program: each eye cleared, then a swap.
fn frame(s: &Arc<Surface>, i: u32) {
    let gl = s.gl();
    for (buffer, shade) in [(GL_BACK_LEFT, 0.2), (GL_BACK_RIGHT, 0.7)] {
        s.draw_buffer(buffer).unwrap();
        // SAFETY: the surface is current on this thread.
        unsafe {
            gl.ClearColor(shade, (i % 7) as f32 / 7.0, 0.5, 1.0);
            gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        }
    }
    s.swap_buffers().unwrap();
}

fn frames_allocate_nothing(s: &Arc<Surface>, what: &str) {
    for i in 0..3 {
        frame(s, i);
    }
    let n = allocations_in(|| {
        for i in 3..13 {
            frame(s, i);
        }
    });
    assert_eq!(n, 0, "{what}: {n} allocations in 10 frames");
}

#[test]
fn headless_frames_allocate_nothing() {
    for kind in [BackendKind::Egl, BackendKind::OsMesa] {
        let d = Display::open(BackendChoice::Only(kind)).unwrap();
        let c = d
            .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_DEPTH_SIZE, 24])
            .unwrap();
        let s = d.create_surface(&c, 96, 64).unwrap();
        surface::make_current(Some(&s)).unwrap();
        frames_allocate_nothing(&s, kind.name());
        surface::make_current(None).unwrap();
    }
}

#[test]
fn window_frames_allocate_nothing_in_every_kind_of_window_path() {
    let x = common::xvfb::Xvfb::start(400, 300);
    let d = Display::open_x11(Some(&x.display)).unwrap();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_DEPTH_SIZE, 24])
        .unwrap();
    // 96x64, and 320x240: a composite of 65536 pixels or more is written
    // in two bands at once, the lower by the layer's helper thread (made
    // at the first such frame, then kept).
    for (w, h) in [(96, 64), (320, 240)] {
        let s = d.create_surface(&c, w, h).unwrap();
        surface::make_current(Some(&s)).unwrap();
        // CPU pixels, blit-mode pixels, a flipped CPU mode, GL composite read back.
        for name in [
            "anaglyph-red-cyan",
            "side-by-side",
            "top-bottom-half",
            "anaglyph-red-cyan-dubois",
        ] {
            s.set_output(OutputMode::from_name(name).unwrap()).unwrap();
            frames_allocate_nothing(&s, &format!("{name} at {w}x{h}"));
        }
        surface::make_current(None).unwrap();
    }
}

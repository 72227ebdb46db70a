//! Both eyes made from one colour + depth frame (`--auto=depth`,
//! `glstereo::reproject`), on one thread, at 800x600 and 1280x1024, of
//! two scenes: *ground*, a sloping ground with near boxes, overlays and
//! nothing drawn along the top (long runs of one shift); *cube*, a box
//! turned 45 degrees in the middle of a cleared window, its two faces
//! receding (a shift that changes every dozen pixels, a hole at each
//! change: glmark2's texture and build scenes); against a memcpy of the
//! two eyes' bytes measured in the same run (what writing the eyes costs
//! at the least).
//!
//! ```sh
//! cargo bench --bench reproject
//! ```

use criterion::Criterion;
use glstereo::reproject::{self, RowScratch, Rule};

const SIZES: [(usize, usize); 2] = [(800, 600), (1280, 1024)];

/// A frame of colour noise and depths by `depth_at(x, y)`.
fn frame_of(w: usize, h: usize, depth_at: impl Fn(usize, usize) -> f32) -> (Vec<u32>, Vec<f32>) {
    let mut seed = 0x1234_5678_u64;
    let mut colour = Vec::with_capacity(w * h);
    let mut depth = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            colour.push(seed as u32 | 0xFF00_0000);
            depth.push(depth_at(x, y));
        }
    }
    (colour, depth)
}

/// *ground*: depth a ground sloping away up the rows, boxes nearer in a
/// grid, the top fifth nothing drawn (1.0), a few overlay pixels (NaN).
fn ground(w: usize, h: usize) -> (Vec<u32>, Vec<f32>) {
    frame_of(w, h, |x, y| {
        let ground = 0.90 + 0.09 * y as f32 / h as f32;
        let boxed = (x / 64) % 3 == 1 && (y / 48) % 3 == 1;
        if y > h * 4 / 5 {
            1.0
        } else if x % 97 == 0 && y % 89 == 0 {
            f32::NAN
        } else if boxed {
            0.80 + 0.01 * (x % 64) as f32 / 64.0
        } else {
            ground
        }
    })
}

/// *cube*: the middle half of the window a box edge-on, its faces from
/// depth 0.85 at the sides to 0.97 at the middle; the rest nothing drawn.
fn cube(w: usize, h: usize) -> (Vec<u32>, Vec<f32>) {
    frame_of(w, h, |x, y| {
        if x > w / 4 && x < w * 3 / 4 && y > h / 5 && y < h * 4 / 5 {
            let u = (x - w / 4) as f32 / (w / 2) as f32;
            0.85 + 0.12 * (1.0 - (2.0 * u - 1.0).abs())
        } else {
            1.0
        }
    })
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    // A camera's rule: D from about −20 px (near) to +k = 14 px.
    let rule = Rule {
        offset: -120.0,
        slope: 134.0,
        clear: 1.0,
        clear_step: 1.0 / 16_777_215.0,
    };
    for (w, h) in SIZES {
        let mut left = vec![0u32; w * h];
        let mut right = vec![0u32; w * h];
        let mut scratch = RowScratch::default();
        let mut g = c.benchmark_group(format!("reproject/{w}x{h}"));
        for (name, (colour, depth)) in [("ground", ground(w, h)), ("cube", cube(w, h))] {
            g.bench_function(format!("both-eyes-{name}"), |b| {
                b.iter(|| {
                    reproject::frame(
                        &rule,
                        ((0, w), 0..h),
                        w,
                        &colour,
                        &depth,
                        [&mut left, &mut right],
                        &mut scratch,
                    )
                })
            });
        }
        // Pages written, not a fresh zeroed allocation (whose pages would
        // all be the one zero page, always in cache).
        let colour = ground(w, h).0;
        g.bench_function("memcpy-both-eyes", |b| {
            b.iter(|| {
                left.copy_from_slice(&colour);
                right.copy_from_slice(&colour);
            })
        });
        g.finish();
    }
    c.final_summary();
}

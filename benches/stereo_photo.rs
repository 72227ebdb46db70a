//! Encoding one stereo frame (two 1280x1024 eyes) as a stereo photo (MPO,
//! JPS at quality 90) against encoding the same two eyes as PNGs (what
//! `--capture` wrote before), in memory, measured in one run.
//!
//! ```sh
//! cargo bench --bench stereo_photo
//! ```
//!
//! The eyes are smooth gradients with a few hard-edged rectangles, a
//! stand-in for a rendered frame (the encoders' time depends on content:
//! noise is far slower to compress, a flat frame far faster). After
//! criterion's report, a table gives each format's median time divided by
//! the median time of the two PNGs.

use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

use criterion::Criterion;
use glstereo::capture::encode_png;
use glstereo::capture::stereo_photo::{self, StereoPhotoFormat};
use glstereo::image::Image;

const W: u32 = 1280;
const H: u32 = 1024;

/// Median nanoseconds per iteration of every benchmark, by id.
static RESULTS: Mutex<Vec<(String, Vec<f64>)>> = Mutex::new(Vec::new());

fn eye(shift: u32) -> Image {
    Image::from_fn(W, H, |x, y| {
        let boxed = (200 + shift..520 + shift).contains(&x) && (300..700).contains(&y)
            || (800 + shift..900 + shift).contains(&x) && (100..900).contains(&y);
        if boxed {
            [30, 60 + (y % 7) as u8, 200, 255]
        } else {
            [(x * 255 / W) as u8, (y * 255 / H) as u8, 120, 255]
        }
    })
}

fn main() {
    let mut c = Criterion::default().configure_from_args().sample_size(20);
    let (left, right) = (eye(0), eye(24));
    let path = Path::new("bench");
    let mut group = c.benchmark_group(format!("stereo_photo/{W}x{H}"));
    let mut bench = |id: &str, f: &mut dyn FnMut() -> usize| {
        let mut times = Vec::new();
        group.bench_function(id, |b| {
            b.iter_custom(|iters| {
                let start = Instant::now();
                for _ in 0..iters {
                    std::hint::black_box(f());
                }
                let d = start.elapsed();
                times.push(d.as_nanos() as f64 / iters as f64);
                d
            })
        });
        RESULTS.lock().unwrap().push((id.to_owned(), times));
    };
    bench("png-both-eyes", &mut || {
        let mut out = Vec::new();
        encode_png(&left, path, &mut out).unwrap();
        encode_png(&right, path, &mut out).unwrap();
        out.len()
    });
    for format in StereoPhotoFormat::ALL {
        bench(format.extension(), &mut || {
            let mut out = Vec::new();
            stereo_photo::encode(format, &left, &right, 90, path, &mut out).unwrap();
            out.len()
        });
    }
    group.finish();
    c.final_summary();

    let median = |v: &[f64]| {
        let mut v = v.to_vec();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let results = RESULTS.lock().unwrap();
    let png = median(&results[0].1);
    println!(
        "\n{:<16} {:>10} {:>14}",
        "format", "median ms", "÷ two PNGs"
    );
    for (id, times) in results.iter() {
        let m = median(times);
        println!("{id:<16} {:>10.2} {:>14.2}", m / 1e6, m / png);
    }
    let size = |f: &mut dyn FnMut(&mut Vec<u8>)| {
        let mut out = Vec::new();
        f(&mut out);
        out.len()
    };
    let png_bytes = size(&mut |o| {
        encode_png(&left, path, o).unwrap();
        encode_png(&right, path, o).unwrap();
    });
    println!("\nbytes: two PNGs {png_bytes}");
    for format in StereoPhotoFormat::ALL {
        let n = size(&mut |o| stereo_photo::encode(format, &left, &right, 90, path, o).unwrap());
        println!("bytes: {} {n}", format.extension());
    }
}

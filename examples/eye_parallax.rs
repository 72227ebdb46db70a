//! Measures the parallax between two eye images (PNG files, e.g. the
//! `left-NNNNNN.png` and `right-NNNNNN.png` of `glstereo-run --capture`)
//! by block matching, as tests/common/parallax.rs describes.
//!
//!   cargo run --release --example eye_parallax LEFT.png RIGHT.png [RANGE]
//!
//! Prints how many textured 16x16 blocks matched, how many matched off
//! their rows, the quantiles of the horizontal shift (right-eye position
//! minus left-eye position, in pixels: positive behind the screen), and a
//! histogram of the shifts.

#[path = "../tests/common/parallax.rs"]
mod parallax;

fn read(path: &str) -> glstereo::image::Image {
    glstereo::capture::read_png(std::path::Path::new(path))
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 3 {
        eprintln!("usage: eye_parallax LEFT.png RIGHT.png [RANGE]");
        std::process::exit(2);
    }
    let (l, r) = (read(&args[1]), read(&args[2]));
    let range = args
        .get(3)
        .and_then(|s| s.parse().ok())
        .unwrap_or((l.width() / 16).max(4) as i32);
    let p = parallax::measure(&l, &r, range, 2);
    println!("{}", p.summary());
    let mut counts = std::collections::BTreeMap::new();
    for s in p.shifts() {
        *counts.entry(s).or_insert(0) += 1;
    }
    for (s, n) in counts {
        println!("{s:>5} {n:>5} {}", "#".repeat(n.min(60)));
    }
}

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

use std::io::Write;

fn read(path: &str) -> glstereo::image::Image {
    glstereo::capture::read_png(std::path::Path::new(path)).unwrap_or_else(|e| {
        eprintln!("eye_parallax: {path}: {e}");
        std::process::exit(1)
    })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 3 {
        eprintln!("usage: eye_parallax LEFT.png RIGHT.png [RANGE]");
        std::process::exit(2);
    }
    let (l, r) = (read(&args[1]), read(&args[2]));
    let range = match args.get(3) {
        None => (l.width() / 16).max(4) as i32,
        Some(s) => s.parse().unwrap_or_else(|_| {
            eprintln!("eye_parallax: RANGE {s:?} is not a whole number of pixels");
            std::process::exit(2)
        }),
    };
    let p = parallax::measure(&l, &r, range, 2);
    let mut counts = std::collections::BTreeMap::new();
    for s in p.shifts() {
        *counts.entry(s).or_insert(0) += 1;
    }
    // A reader that stops early (`| head`) ends the output, not in a panic.
    let mut out = std::io::stdout().lock();
    let print = || -> std::io::Result<()> {
        writeln!(out, "{}", p.summary())?;
        for (s, n) in counts {
            writeln!(out, "{s:>5} {n:>5} {}", "#".repeat(n.min(60)))?;
        }
        out.flush()
    };
    if let Err(e) = print()
        && e.kind() != std::io::ErrorKind::BrokenPipe
    {
        eprintln!("eye_parallax: {e}");
        std::process::exit(1);
    }
}

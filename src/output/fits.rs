//! Property tests of every frame a window can get: for every output
//! format, every vector level the processor has and every window size a
//! user can make — each from 1x1 to 64x64, thin ones (1 or 2 pixels wide
//! or high, up to 4096 long) and random ones up to 4096x4096 — the rows
//! [`Frame::write_with`] writes equal the reference composite fitted to
//! the window ([`fitted`] of [`reference`]). Each level keeps one
//! [`Scratch`] from case to case, as a window keeps its buffers while the
//! program is resized, and the eyes are sometimes of another size than
//! the window (a resize the program has not followed with glViewport).
//!
//! The sizes are many, so these run in an optimised build: `make test`
//! runs them with `cargo test --release --lib output::fits`; a debug
//! `cargo test` lists them as ignored.

use super::cpu::{fitted, reference};
use super::kernels::Simd;
use super::mode::{AnaglyphMethod, OutputMode};
use super::options::OutputOptions;
use super::pattern::{gradient, noise};
use super::rows::{EyeRows, Frame, Scratch, Target};
use crate::image::{Image, as_words_mut};
use crate::stereo::eye_memory::Rows;

/// SplitMix64: the same sequence everywhere.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// 1 … `n`.
    pub(super) fn upto(&mut self, n: u32) -> u32 {
        1 + (self.next() % u64::from(n)) as u32
    }
}

/// Writes the frame of `mode` from eyes `l`, `r` into a target of `size`,
/// the eyes stored bottom row first as GL keeps them and handed over in
/// bands of `band` rows where the frame allows it (as the window reads
/// them back), with `scratch` left from earlier frames.
#[allow(clippy::too_many_arguments)]
pub(super) fn written(
    simd: Simd,
    mode: OutputMode,
    o: &OutputOptions,
    l: &Image,
    r: &Image,
    size: (u32, u32),
    band: u32,
    scratch: &mut Scratch,
) -> Image {
    let (w, h) = (l.width(), l.height());
    let frame = Frame::new(mode, o, 1, (w, h), size);
    let flipped = |img: &Image| {
        let mut f = img.clone();
        f.flip_vertical();
        f
    };
    let (fl, fr) = (flipped(l), flipped(r));
    let mut out = Image::new(size.0, size.1);
    let mut target = Target {
        words: as_words_mut(out.pixels_mut()).expect("aligned words"),
        stride: size.0 as usize,
        size,
        first: 0,
    };
    let band = if frame.row_local() { band.max(1) } else { h };
    let mut y0 = 0;
    while y0 < h {
        let n = band.min(h - y0);
        let whole = n == h;
        // Only this band's rows, as a band read back holds them.
        let rows = |img: &Image| {
            let len = w as usize * 4;
            let mut b = Image::new(w, n);
            let at = y0 as usize * len;
            b.pixels_mut()
                .copy_from_slice(&img.pixels()[at..at + n as usize * len]);
            b
        };
        let (bl, br) = if whole {
            (fl.clone(), fr.clone())
        } else {
            (rows(&fl), rows(&fr))
        };
        let eyes = [&bl, &br].map(|b| EyeRows::gl(Rows::of_image(b), y0, h));
        let out_rows = if whole {
            0..size.1
        } else {
            frame.rows_of_band(y0..y0 + n)
        };
        frame.write_with(simd, eyes, out_rows, &mut target, scratch, |v| v);
        y0 += n;
    }
    out
}

/// The levels this processor has, lowest first.
fn levels() -> impl Iterator<Item = Simd> {
    Simd::ALL.into_iter().filter(|&s| s <= Simd::detected())
}

/// Options of a case: the defaults, or swapped eyes with crosstalk and
/// saturation (every stage of the pipeline).
fn options(changed: bool) -> OutputOptions {
    if changed {
        OutputOptions {
            swap_eyes: true,
            crosstalk: 0.3,
            saturation: 0.6,
        }
    } else {
        OutputOptions::default()
    }
}

/// The modes that are composites (every one but `quad`).
fn composites() -> impl Iterator<Item = OutputMode> {
    OutputMode::all().filter(|&m| m != OutputMode::Quad)
}

/// One buffer set per level, kept across the cases of a test.
struct Windows {
    scratch: [Scratch; 3],
    cases: usize,
}

impl Windows {
    fn new() -> Windows {
        Windows {
            scratch: Default::default(),
            cases: 0,
        }
    }

    /// Eyes of `eye` size into a window of `size`, at every level, against
    /// the reference. Dubois may differ by 1 where the eyes are changed
    /// (saturation, crosstalk) or in AVX-512's fixed point; everything
    /// else is exact.
    fn check(&mut self, mode: OutputMode, eye: (u32, u32), size: (u32, u32), seed: u64) {
        let (w, h) = eye;
        let (l, r) = (noise(w, h, seed), gradient(w, h, seed as u8));
        let o = options(seed % 3 == 0);
        let want = fitted(&reference(mode, &o, &l, &r, 1).unwrap(), mode, size);
        let dubois = matches!(mode, OutputMode::Anaglyph(_, AnaglyphMethod::Dubois));
        for simd in levels() {
            let band = 1 + (seed as u32 % h.max(1));
            let scratch = &mut self.scratch[simd as usize];
            let got = written(simd, mode, &o, &l, &r, size, band, scratch);
            let (d, x, y, c) = got.max_difference(&want).expect("same size");
            let tol = dubois && (o != OutputOptions::default() || simd == Simd::Avx512);
            assert!(
                d <= u8::from(tol),
                "{mode}: eyes {w}x{h} into a {}x{} window ({simd:?}, bands of {band}, \
                 {o:?}, after {} other cases): ({x}, {y}) channel {c} is {:?}, want {:?}",
                size.0,
                size.1,
                self.cases,
                got.get(x, y),
                want.get(x, y)
            );
        }
        self.cases += 1;
    }
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "many sizes: make test runs it with --release"
)]
fn every_window_from_1x1_to_64x64_is_the_reference_fitted() {
    let mut rng = Rng(64);
    for mode in composites() {
        let mut windows = Windows::new();
        for ww in 1..=64 {
            for wh in 1..=64 {
                // The eyes of the window's size (a program that follows
                // its window), then of another (one that has not yet).
                windows.check(mode, (ww, wh), (ww, wh), rng.next());
                let eye = (rng.upto(64), rng.upto(64));
                windows.check(mode, eye, (ww, wh), rng.next());
            }
        }
    }
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "many sizes: make test runs it with --release"
)]
fn thin_windows_up_to_4096_are_the_reference_fitted() {
    let mut rng = Rng(4096);
    for mode in composites() {
        let mut windows = Windows::new();
        let lengths: Vec<u32> = (1..=64)
            .chain((0..24).map(|_| rng.upto(4096)))
            .chain([4095, 4096])
            .collect();
        for thin in [1, 2] {
            for &long in &lengths {
                for size in [(thin, long), (long, thin)] {
                    windows.check(mode, size, size, rng.next());
                    // Eyes as thin the other way, or small and square.
                    let eye = if rng.next() % 2 == 0 {
                        (size.1, size.0)
                    } else {
                        (rng.upto(48), rng.upto(48))
                    };
                    windows.check(mode, eye, size, rng.next());
                }
            }
        }
    }
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "many sizes: make test runs it with --release"
)]
fn random_windows_up_to_4096x4096_are_the_reference_fitted() {
    let mut rng = Rng(4242);
    for mode in composites() {
        let mut windows = Windows::new();
        for _ in 0..2 {
            let size = (rng.upto(4096), rng.upto(4096));
            windows.check(mode, size, size, rng.next());
            // Eyes of a smaller random size (a frame from before a resize).
            let eye = (rng.upto(1024), rng.upto(1024));
            windows.check(mode, eye, size, rng.next());
        }
    }
}

/// [`Frame::write_split`] — a window's frame composed in two bands at
/// once, the lower on a helper thread — writes exactly the bytes
/// [`Frame::write`] writes whole (itself checked against the reference
/// above), for every format, with the eyes in place (GL's row order, as
/// eye memory has them): windows at and above the split's threshold
/// (square, odd, a column one pixel wide and 16384 high, rows two high)
/// and random ones up to 2048x2048, eyes of the window's size or of
/// another, buffers kept from case to case.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "many large frames: make test runs it with --release"
)]
fn a_window_composed_in_two_bands_at_once_equals_it_composed_whole() {
    use super::rows::SPLIT_PIXELS;
    // The helper is the process's: this test counts on having it.
    let _turn = super::helper::turn();
    let mut rng = Rng(0x0005_9117);
    let mut sizes = vec![
        (256, 256),
        (257, 255),
        (1, 16384),
        (4, 16384),
        (16384, 2),
        (16384, 1),
        (800, 600),
        (4096, 17),
        (5, 13109),
        (255, 257),
    ];
    sizes.extend((0..16).map(|_| (rng.upto(2048), rng.upto(2048))));
    let modes: Vec<OutputMode> = composites().collect();
    let mut split_scratch: [[Scratch; 2]; 3] = Default::default();
    let mut whole_scratch: [Scratch; 3] = Default::default();
    let mut case = 0usize;
    for &size in &sizes {
        for k in 0..6 {
            let mode = modes[case % modes.len()];
            case += 1;
            let eye = if k % 2 == 0 {
                size
            } else {
                (rng.upto(700), rng.upto(700))
            };
            let (w, h) = eye;
            let seed = rng.next();
            let mut l = noise(w, h, seed);
            let mut r = gradient(w, h, seed as u8);
            l.flip_vertical();
            r.flip_vertical();
            let o = options(seed % 3 == 0);
            let frame = Frame::new(mode, &o, case as u64, eye, size);
            let eyes = [&l, &r].map(|b| EyeRows::gl(Rows::of_image(b), 0, h));
            let big = u64::from(size.0) * u64::from(size.1) >= SPLIT_PIXELS && size.1 >= 2;
            for simd in levels() {
                let mut whole = Image::new(size.0, size.1);
                let mut split = Image::new(size.0, size.1);
                let mut two = false;
                for (out, split_it) in [(&mut whole, false), (&mut split, true)] {
                    let mut target = Target {
                        words: as_words_mut(out.pixels_mut()).expect("aligned words"),
                        stride: size.0 as usize,
                        size,
                        first: 0,
                    };
                    let s = &mut split_scratch[simd as usize];
                    if split_it {
                        two = frame.write_split_with(simd, eyes, 0..size.1, &mut target, s, |v| v);
                    } else {
                        let s = &mut whole_scratch[simd as usize];
                        frame.write_with(simd, eyes, 0..size.1, &mut target, s, |v| v);
                    }
                }
                assert_eq!(
                    two, big,
                    "{mode}: a {}x{} window split in two",
                    size.0, size.1
                );
                assert!(
                    split.pixels() == whole.pixels(),
                    "{mode}: eyes {w}x{h} into a {}x{} window ({simd:?}, split: {big}, {o:?}): {:?}",
                    size.0,
                    size.1,
                    split.max_difference(&whole)
                );
            }
        }
    }
}

/// Eyes made from a colour and depth frame as the composite reads them
/// (as `--auto=depth` makes them), with the reprojection kernel and a
/// buffer per band.
struct Made {
    width: usize,
    height: usize,
    /// Rows bottom first.
    colour: Vec<u32>,
    depth: Vec<f32>,
    rule: crate::reproject::Rule,
    bands: [std::sync::Mutex<crate::reproject::RowScratch>; 2],
}

impl super::rows::MakeEyes for Made {
    fn size(&self) -> (u32, u32) {
        (self.width as u32, self.height as u32)
    }

    fn row(&self, band: usize, y: u32, out: [&mut [u32]; 2]) {
        let (w, y) = (self.width, y as usize);
        let mut scratch = self.bands[band].lock().expect("one thread a band");
        crate::reproject::row(
            Simd::detected(),
            &self.rule,
            (w / 5, w - w / 7),
            &self.colour[y * w..(y + 1) * w],
            &self.depth[y * w..(y + 1) * w],
            out,
            &mut scratch,
        );
    }

    fn in_place(&self) {
        panic!("a row-local composite never asks for the eyes in place");
    }
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "many sizes: make test runs it with --release"
)]
fn a_window_composed_from_eyes_made_as_it_reads_them_equals_it_from_eyes_made_whole() {
    // The helper is the process's: this test counts on having it.
    let _turn = super::helper::turn();
    let mut rng = Rng(0x00ED_E915);
    let mut sizes = vec![
        (1, 1),
        (1, 2),
        (2, 1),
        (3, 3),
        (256, 256),
        (257, 255),
        (1, 16384),
        (16384, 1),
        (16384, 2),
        (800, 600),
        (4096, 17),
        (5, 1311),
    ];
    sizes.extend((0..12).map(|_| (rng.upto(1500), rng.upto(1500))));
    let modes: Vec<OutputMode> = composites().collect();
    let mut made_scratch: [[Scratch; 2]; 3] = Default::default();
    let mut whole_scratch: [Scratch; 3] = Default::default();
    let mut case = 0usize;
    for &size in &sizes {
        for k in 0..4 {
            let mode = modes[case % modes.len()];
            case += 1;
            // Eyes of the window's size (or another: not row-local).
            let eye = if k < 3 {
                size
            } else {
                (rng.upto(300), rng.upto(300))
            };
            let (w, h) = (eye.0 as usize, eye.1 as usize);
            let seed = rng.next();
            let colour = noise(eye.0, eye.1, seed);
            let colour: Vec<u32> = colour
                .pixels()
                .chunks_exact(4)
                .map(|p| u32::from_le_bytes([p[0], p[1], p[2], p[3]]))
                .collect();
            // Ground sloping up the rows, boxes nearer, nothing drawn
            // along some rows, a few overlay pixels.
            let depth: Vec<f32> = (0..w * h)
                .map(|i| {
                    let (x, y) = (i % w, i / w);
                    match (x * 7 + y * 3) % 41 {
                        0 => f32::NAN,
                        _ if y % 9 == 4 => 1.0,
                        _ if (x / 11 + y / 5) % 3 == 0 => 0.3,
                        _ => 0.5 + 0.4 * (y as f32 / h as f32),
                    }
                })
                .collect();
            let made = Made {
                width: w,
                height: h,
                colour,
                depth,
                rule: crate::reproject::Rule {
                    offset: -9.0,
                    slope: 20.0,
                    clear: 1.0,
                    clear_step: 1e-7,
                },
                bands: Default::default(),
            };
            // The eyes made whole first, rows bottom first.
            let mut eyes = [vec![0u32; w * h], vec![0u32; w * h]];
            {
                let [l, r] = &mut eyes;
                for (y, (l, r)) in l.chunks_exact_mut(w).zip(r.chunks_exact_mut(w)).enumerate() {
                    super::rows::MakeEyes::row(&made, 0, y as u32, [l, r]);
                }
            }
            let views =
                [&eyes[0], &eyes[1]].map(|b| EyeRows::gl(Rows::of_words(b, w, eye.1), 0, eye.1));
            let o = options(seed % 3 == 0);
            let frame = Frame::new(mode, &o, case as u64, eye, size);
            for simd in levels() {
                let mut whole = Image::new(size.0, size.1);
                let mut fused = Image::new(size.0, size.1);
                fn target(out: &mut Image) -> Target<'_> {
                    let size = (out.width(), out.height());
                    Target {
                        words: as_words_mut(out.pixels_mut()).expect("aligned words"),
                        stride: size.0 as usize,
                        size,
                        first: 0,
                    }
                }
                let s = &mut whole_scratch[simd as usize];
                frame.write_with(simd, views, 0..size.1, &mut target(&mut whole), s, |v| v);
                let s = &mut made_scratch[simd as usize];
                let wrote = frame.write_split_made(simd, &made, &mut target(&mut fused), s, |v| v);
                assert_eq!(
                    wrote,
                    frame.row_local(),
                    "{mode}: eyes {w}x{h} into a {}x{} window made as read",
                    size.0,
                    size.1
                );
                if wrote {
                    assert!(
                        fused.pixels() == whole.pixels(),
                        "{mode}: eyes {w}x{h} into a {}x{} window ({simd:?}, {o:?}): {:?}",
                        size.0,
                        size.1,
                        fused.max_difference(&whole)
                    );
                }
            }
        }
    }
}

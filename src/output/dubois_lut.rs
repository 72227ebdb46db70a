//! The `-dubois` anaglyphs by tables: for 8-bit eyes, byte for byte what
//! [`super::cpu::reference`] computes; for eyes changed by saturation or
//! crosstalk, within 1 unit of it.
//!
//! The reference computes, per output channel c,
//! `v = ML[c][0]·lin(l0) + ML[c][1]·lin(l1) + ML[c][2]·lin(l2) + MR[c][0]·lin(r0) + …`
//! in f32 from left to right, then `unorm(linear_to_srgb(clamp(v, 0, 1))·255)`.
//! Here:
//!
//! - **Decoding** `lin(x)` of a whole number x is a table of the
//!   reference's 256 values; the products and the sum are the reference's
//!   f32 operations in its order, so `v` is the reference's `v`, bit for
//!   bit. A channel that is not a whole number (after saturation or
//!   crosstalk) interpolates the table linearly between its neighbours:
//!   the curve bends so little over one unit that this is within 6·10⁻⁶
//!   of `powf`'s value, which moves the output by at most 0.05 units.
//! - **Encoding** `v` to a byte is exact. At or below the curve's linear
//!   toe (v ≤ 0.0031308) it is the reference's own arithmetic. Above, a
//!   table of [`BUCKETS`] equal intervals of (0, 1] stores for each
//!   interval the byte at its start and the smallest f32 in it at which
//!   the byte goes up by one (the curve's slope keeps every step at least
//!   1.2 intervals apart, so there is at most one), found by bisecting the
//!   f32 values with the reference function. Both are packed in one word:
//!   the byte above bit 23, and the threshold as the f32 fraction of the
//!   interval (`v·BUCKETS` minus the interval's index, a whole number of
//!   2⁻²³ there, exactly). So one table read and one compare per channel.
//!
//! The tables are built once per process (a few milliseconds). With AVX2
//! the reads are gathers, 8 pixels at a time. Runs of equal pixels (flat
//! backgrounds) are composed once ([`Memo`]).
//!
//! Unit tests check the bytes against the reference on every grey pair,
//! 100 000 random pixel pairs per pair of glasses, and the encoding on
//! every 64th f32 of (0, 1] and around every threshold.

use std::sync::OnceLock;

use super::anaglyph::{dubois_matrices, linear_to_srgb, srgb_to_linear};
use super::kernels::{ALPHA, N, Planes, Stage, chunks};
use super::mode::AnaglyphColors;

/// Intervals of the encoding table over (0, 1].
const BUCKETS: usize = 4096;
/// Where the linear toe of the sRGB curve ends (as in `linear_to_srgb`).
const KNEE: f32 = 0.003_130_8;
/// The threshold bits of an encoding entry (all ones: no step).
const FRACTION: u32 = (1 << 23) - 1;

/// The reference encoding of a linear value: the output byte.
fn encode_reference(v: f32) -> u32 {
    let o = linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0;
    // As cpu::unorm: clamp, round half up.
    (o.clamp(0.0, 255.0) + 0.5) as u32
}

/// `lin` of 0…255, and entry 256 = entry 255 (for interpolation at 255).
fn decode_table() -> &'static [f32; 257] {
    static TABLE: OnceLock<[f32; 257]> = OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|v| srgb_to_linear(v.min(255) as f32 / 255.0)))
}

/// The encoding table (see the module documentation): entry i for the
/// interval [i, i + 1)/BUCKETS (entry BUCKETS: v = 1).
fn encode_table() -> &'static [u32; BUCKETS + 1] {
    static TABLE: OnceLock<Box<[u32; BUCKETS + 1]>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let entry = |i: usize| {
            let lo = i as f32 / BUCKETS as f32;
            let byte = encode_reference(lo);
            let hi = (i + 1) as f32 / BUCKETS as f32;
            // Below the knee's interval the table is not read.
            if i >= BUCKETS || (hi <= KNEE) || encode_reference(hi) == byte {
                return byte << 23 | FRACTION;
            }
            assert_eq!(encode_reference(hi), byte + 1, "one step per interval");
            // The smallest f32 in [lo, hi] whose byte is higher.
            let (mut a, mut z) = (lo.to_bits(), hi.to_bits());
            while z - a > 1 {
                let m = a + (z - a) / 2;
                if encode_reference(f32::from_bits(m)) > byte {
                    z = m;
                } else {
                    a = m;
                }
            }
            let t = f32::from_bits(z);
            if t == hi {
                return byte << 23 | FRACTION;
            }
            let fraction = (t * BUCKETS as f32 - i as f32) * (1 << 23) as f32;
            debug_assert_eq!(fraction.fract(), 0.0, "interval {i}");
            byte << 23 | fraction as u32
        };
        let v: Vec<u32> = (0..=BUCKETS).map(entry).collect();
        v.into_boxed_slice()
            .try_into()
            .expect("BUCKETS + 1 entries")
    })
}

/// [`encode_reference`] of `v` by the table.
#[inline(always)]
fn encode(table: &[u32; BUCKETS + 1], v: f32) -> u32 {
    let v = v.clamp(0.0, 1.0);
    if v <= KNEE {
        return ((12.92 * v) * 255.0 + 0.5) as u32;
    }
    let x = v * BUCKETS as f32;
    let i = (x as usize).min(BUCKETS);
    let fraction = ((x - i as f32) * (1 << 23) as f32) as u32;
    let e = table[i];
    (e >> 23) + u32::from(fraction >= e & FRACTION)
}

/// `lin` of a channel value in 0…255 (not a whole number: interpolated).
#[inline(always)]
fn decode(table: &[f32; 257], x: f32) -> f32 {
    let i = (x as usize).min(255);
    let (a, b) = (table[i], table[i + 1]);
    a + (x - i as f32) * (b - a)
}

/// The two eyes' [`N`] pixels as a kernel takes them: 8-bit words, or
/// planes after saturation or crosstalk.
#[derive(Clone, Copy)]
enum Pixels<'a> {
    Words(&'a [u32; N], &'a [u32; N]),
    Planes(&'a Planes, &'a Planes),
}

/// The last [`N`] pixel pairs composed and their anaglyph: runs of equal
/// pixels (flat backgrounds, within a row and from row to row) are
/// composed once.
#[derive(Debug, Default)]
pub(crate) struct Memo(Option<([u32; N], [u32; N], [u32; N])>);

/// The Dubois anaglyph of one pair of glasses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Dubois {
    /// Row c: the left eye's R, G, B and the right eye's R, G, B weights
    /// of output channel c.
    m: [[f32; 6]; 3],
}

impl Dubois {
    pub(crate) fn new(colors: AnaglyphColors) -> Dubois {
        let d = dubois_matrices(colors);
        // Build the tables now, not inside a frame.
        let _ = (decode_table(), encode_table());
        Dubois {
            m: std::array::from_fn(|c| {
                std::array::from_fn(|k| {
                    if k < 3 {
                        d.left[c][k]
                    } else {
                        d.right[c][k - 3]
                    }
                })
            }),
        }
    }

    /// One row: `out[x]` the anaglyph of `a[x]` (left) and `b[x]` (right)
    /// after `stage`, through `px`; `memo` holds the last [`N`] pixels
    /// composed (clear it when the anaglyph or the stage changes).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn row(
        &self,
        avx2: bool,
        stage: Stage,
        memo: &mut Memo,
        a: &[u32],
        b: &[u32],
        out: &mut [u32],
        px: impl Fn(u32) -> u32,
    ) {
        let last = &mut memo.0;
        chunks(
            a,
            b,
            out,
            px,
            #[inline(always)]
            |l, r| {
                if let Some((pl, pr, po)) = &last {
                    if pl == l && pr == r {
                        return *po;
                    }
                }
                let o = if stage.is_identity() {
                    self.chunk(avx2, Pixels::Words(l, r))
                } else {
                    let (mut lp, mut rp) = (Planes::of(l), Planes::of(r));
                    stage.apply(&mut lp, &mut rp);
                    self.chunk(avx2, Pixels::Planes(&lp, &rp))
                };
                *last = Some((*l, *r, o));
                o
            },
        );
    }

    /// [`N`] pixels, with AVX2 when `avx2` says the processor has it.
    #[inline(always)]
    fn chunk(&self, avx2: bool, p: Pixels<'_>) -> [u32; N] {
        #[cfg(target_arch = "x86_64")]
        if avx2 {
            // SAFETY: `avx2` says the processor has AVX2 (see with_simd).
            return unsafe { self.chunk_avx2(p) };
        }
        let _ = avx2;
        self.chunk_scalar(p)
    }

    /// [`N`] pixels, one at a time.
    #[inline(always)]
    fn chunk_scalar(&self, p: Pixels<'_>) -> [u32; N] {
        let (dec, enc) = (decode_table(), encode_table());
        let mut out = [0; N];
        for (i, out) in out.iter_mut().enumerate() {
            let mut lin = [0.0; 6];
            for (k, v) in lin.iter_mut().enumerate() {
                *v = match p {
                    Pixels::Words(l, r) => {
                        let w = if k < 3 { l[i] } else { r[i] };
                        dec[(w >> (8 * (k % 3)) & 0xFF) as usize]
                    }
                    Pixels::Planes(l, r) => {
                        let p = if k < 3 { &l.0[k] } else { &r.0[k - 3] };
                        decode(dec, p[i])
                    }
                };
            }
            let mut word = ALPHA;
            for (c, m) in self.m.iter().enumerate() {
                let v = m[0] * lin[0]
                    + m[1] * lin[1]
                    + m[2] * lin[2]
                    + m[3] * lin[3]
                    + m[4] * lin[4]
                    + m[5] * lin[5];
                word |= encode(enc, v) << (8 * c);
            }
            *out = word;
        }
        out
    }

    /// [`Dubois::chunk_scalar`] with AVX2 gathers, 8 pixels at a time; the
    /// same operations in the same order, so the same bytes.
    ///
    /// # Safety
    /// The processor has AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[inline]
    unsafe fn chunk_avx2(&self, p: Pixels<'_>) -> [u32; N] {
        use std::arch::x86_64::*;
        let (dec, enc) = (decode_table(), encode_table());
        let mut out = [0u32; N];
        for half in 0..N / 8 {
            let mut lin = [_mm256_setzero_ps(); 6];
            for (k, lin) in lin.iter_mut().enumerate() {
                *lin = match p {
                    Pixels::Words(l, r) => {
                        let w = if k < 3 { l } else { r };
                        // SAFETY: 8 words at 8·half of an array of N = 16.
                        let w = unsafe { _mm256_loadu_si256(w[8 * half..].as_ptr().cast()) };
                        let shift = _mm256_set1_epi32(8 * (k % 3) as i32);
                        let i =
                            _mm256_and_si256(_mm256_srlv_epi32(w, shift), _mm256_set1_epi32(0xFF));
                        // SAFETY: indices 0…255 of a 257-entry table.
                        unsafe { _mm256_i32gather_ps::<4>(dec.as_ptr(), i) }
                    }
                    Pixels::Planes(l, r) => {
                        let p = if k < 3 { &l.0[k] } else { &r.0[k - 3] };
                        // SAFETY: 8 f32 at 8·half of an array of N = 16.
                        let x = unsafe { _mm256_loadu_ps(p[8 * half..].as_ptr()) };
                        // Channel values lie in 0…255: the indices stay in the table.
                        let i = _mm256_min_epi32(_mm256_cvttps_epi32(x), _mm256_set1_epi32(255));
                        // SAFETY: indices 0…255 and 1…256 of a 257-entry table.
                        let (a, b) = unsafe {
                            (
                                _mm256_i32gather_ps::<4>(dec.as_ptr(), i),
                                _mm256_i32gather_ps::<4>(dec.as_ptr().add(1), i),
                            )
                        };
                        let f = _mm256_sub_ps(x, _mm256_cvtepi32_ps(i));
                        _mm256_add_ps(a, _mm256_mul_ps(f, _mm256_sub_ps(b, a)))
                    }
                };
            }
            let mut word = _mm256_set1_epi32(ALPHA as i32);
            for (c, m) in self.m.iter().enumerate() {
                let term = |k: usize| _mm256_mul_ps(_mm256_set1_ps(m[k]), lin[k]);
                let mut v = term(0);
                for k in 1..6 {
                    v = _mm256_add_ps(v, term(k));
                }
                let v = _mm256_min_ps(_mm256_max_ps(v, _mm256_setzero_ps()), _mm256_set1_ps(1.0));
                // The toe: the reference's arithmetic.
                let toe = _mm256_mul_ps(
                    _mm256_mul_ps(v, _mm256_set1_ps(12.92)),
                    _mm256_set1_ps(255.0),
                );
                let toe = _mm256_cvttps_epi32(_mm256_add_ps(toe, _mm256_set1_ps(0.5)));
                // Above: the table's byte, plus one from its threshold on.
                let x = _mm256_mul_ps(v, _mm256_set1_ps(BUCKETS as f32));
                let i = _mm256_cvttps_epi32(x);
                let fraction = _mm256_sub_ps(x, _mm256_cvtepi32_ps(i));
                let fraction =
                    _mm256_cvttps_epi32(_mm256_mul_ps(fraction, _mm256_set1_ps((1 << 23) as f32)));
                // SAFETY: v ≤ 1, so the index is at most BUCKETS.
                let e = unsafe { _mm256_i32gather_epi32::<4>(enc.as_ptr().cast(), i) };
                let below = _mm256_cmpgt_epi32(
                    _mm256_and_si256(e, _mm256_set1_epi32(FRACTION as i32)),
                    fraction,
                );
                // below is all ones (−1) where the threshold is not reached.
                let byte = _mm256_add_epi32(
                    _mm256_srli_epi32::<23>(e),
                    _mm256_add_epi32(below, _mm256_set1_epi32(1)),
                );
                let at_toe =
                    _mm256_castps_si256(_mm256_cmp_ps::<_CMP_LE_OQ>(v, _mm256_set1_ps(KNEE)));
                let byte = _mm256_blendv_epi8(byte, toe, at_toe);
                word = _mm256_or_si256(
                    word,
                    _mm256_sllv_epi32(byte, _mm256_set1_epi32(8 * c as i32)),
                );
            }
            // SAFETY: 8 words at 8·half of an array of N = 16.
            unsafe { _mm256_storeu_si256(out[8 * half..].as_mut_ptr().cast(), word) };
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::anaglyph::dubois_pixel;
    use crate::output::kernels::with_simd;

    /// The reference: cpu.rs's arithmetic.
    fn reference(colors: AnaglyphColors, l: [f32; 3], r: [f32; 3]) -> [u8; 3] {
        let m = dubois_matrices(colors);
        let lin = |x: [f32; 3]| x.map(|v| srgb_to_linear(v / 255.0));
        let o = dubois_pixel(&m, lin(l), lin(r));
        o.map(|v| ((v * 255.0).clamp(0.0, 255.0) + 0.5) as u8)
    }

    /// Composes N pixel pairs with both kernels (AVX2 where available) and
    /// compares each pixel with the reference within `tol`.
    fn check(colors: AnaglyphColors, pairs: &[([f32; 3], [f32; 3])], staged: bool, tol: i32) {
        let d = Dubois::new(colors);
        for group in pairs.chunks(N) {
            let planes = |eye: usize| {
                Planes(std::array::from_fn(|c| {
                    std::array::from_fn(|i| group.get(i).map_or(0.0, |p| [p.0, p.1][eye][c]))
                }))
            };
            let (l, r) = (planes(0), planes(1));
            let words = |p: &Planes| {
                let mut w = [0; N];
                for (i, w) in w.iter_mut().enumerate() {
                    *w = u32::from_le_bytes(
                        [0, 1, 2, 3].map(|c| p.0.get(c).map_or(9, |c| c[i] as u8)),
                    );
                }
                w
            };
            let (lw, rw) = (words(&l), words(&r));
            let pixels = if staged {
                Pixels::Planes(&l, &r)
            } else {
                Pixels::Words(&lw, &rw)
            };
            let mut got = vec![d.chunk(false, pixels)];
            if with_simd(|avx2| avx2) {
                got.push(d.chunk(true, pixels));
            }
            for words in got {
                for (i, &(pl, pr)) in group.iter().enumerate() {
                    let want = reference(colors, pl, pr);
                    let w = words[i].to_le_bytes();
                    for c in 0..3 {
                        let diff = (i32::from(w[c]) - i32::from(want[c])).abs();
                        assert!(
                            diff <= tol,
                            "{colors:?} left {pl:?} right {pr:?}: {:?}, want {want:?}",
                            &w[..3]
                        );
                    }
                    assert_eq!(w[3], 255);
                }
            }
        }
    }

    fn random_pairs(n: usize, whole: bool) -> Vec<([f32; 3], [f32; 3])> {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        (0..n)
            .map(|_| {
                let v = next().to_le_bytes();
                let f = |b: u8, k: usize| {
                    let frac = if whole {
                        0.0
                    } else {
                        (v[k] as f32 / 256.0) * 0.999
                    };
                    (f32::from(b) + frac).min(255.0)
                };
                (
                    [f(v[0], 6), f(v[1], 7), f(v[2], 6)],
                    [f(v[3], 7), f(v[4], 6), f(v[5], 7)],
                )
            })
            .collect()
    }

    #[test]
    fn eight_bit_eyes_give_the_reference_bytes_on_grey_pairs_and_random_pixels() {
        let greys: Vec<_> = (0..=255u8)
            .flat_map(|a| (0..=255u8).map(move |b| ([f32::from(a); 3], [f32::from(b); 3])))
            .collect();
        let random = random_pairs(100_000, true);
        for colors in AnaglyphColors::ALL {
            check(colors, &greys, false, 0);
            check(colors, &random, false, 0);
        }
    }

    #[test]
    fn changed_eyes_stay_within_one_unit_of_the_reference() {
        let random = random_pairs(50_000, false);
        for colors in AnaglyphColors::ALL {
            check(colors, &random, true, 1);
        }
    }

    #[test]
    fn the_encoding_table_gives_the_reference_byte_for_every_value() {
        let table = encode_table();
        let check = |v: f32| {
            assert_eq!(
                encode(table, v),
                encode_reference(v),
                "v = {v:e} ({:#x})",
                v.to_bits()
            );
        };
        // Every 64th f32 of [0, 1].
        for bits in (0..=1.0f32.to_bits()).step_by(64) {
            check(f32::from_bits(bits));
        }
        // Around every step the table knows, and around the knee.
        for (i, e) in table.iter().enumerate() {
            if e & FRACTION == FRACTION {
                continue;
            }
            let t = (i as f32 + (e & FRACTION) as f32 / (1 << 23) as f32) / BUCKETS as f32;
            for d in -64i32..=64 {
                check(f32::from_bits(t.to_bits().wrapping_add_signed(d)));
            }
        }
        for d in -4096i32..=4096 {
            check(f32::from_bits(KNEE.to_bits().wrapping_add_signed(d)));
        }
    }
}

//! The `-dubois` anaglyphs by tables: with AVX-512, in fixed point,
//! within 1 unit of what [`super::cpu::reference`] computes; otherwise,
//! for 8-bit eyes byte for byte the reference, and for eyes changed by
//! saturation or crosstalk within 1 unit of it.
//!
//! The reference computes, per output channel c,
//! `v = ML[c][0]·lin(l0) + ML[c][1]·lin(l1) + ML[c][2]·lin(l2) + MR[c][0]·lin(r0) + …`
//! in f32 from left to right, then `unorm(linear_to_srgb(clamp(v, 0, 1))·255)`.
//!
//! **AVX-512** (8-bit eyes; [`Dubois::row_avx512`], 16 pixels a vector,
//! no memory read but the eyes): within 1 unit, and equal to the
//! reference for more than 99 % of channels.
//!
//! - **Decoding**: `lin(x)·2¹⁵` rounded to 16 bits, its low and high bytes
//!   looked up by byte permutes (VBMI) of 4 registers each, every byte of
//!   the pixels at once; errors ≤ 2⁻¹⁶.
//! - **The sum** in 32-bit integers, pairs of 16-bit products at a time
//!   (VNNI), with the weights rounded to 16 bits (`round(w·2^S)`, S = 15,
//!   or 14 for weights of 1 or more); errors ≤ 6·2⁻¹⁶ + 2⁻¹⁶·Σ|w|.
//! - **Encoding** in f32: on the toe (v ≤ 0.0031308) its linear formula;
//!   above, per octave [2^e, 2^(e+1)) of v, `255·1.055·2^(e/2.4)` (a
//!   16-entry permute by the exponent) times a cubic of the mantissa
//!   ([`CUBIC`], within 0.03 units); rounded half up, and bytes saturated.
//!
//! At the curve's steepest (the toe: 3294 units per unit of v) the errors
//! add up to less than 0.45 of a unit, so the byte is the reference's or
//! its neighbour.
//!
//! **Otherwise** (AVX2 gathers, or one pixel at a time: exact for 8-bit
//! eyes):
//!
//! - **Decoding** `lin(x)` of a whole number x is a table of the
//!   reference's 256 values; the products and the sum are the reference's
//!   f32 operations in its order, so `v` is the reference's `v`, bit for
//!   bit. A channel that is not a whole number (after saturation or
//!   crosstalk) interpolates the table linearly between its neighbours:
//!   the curve bends so little over one unit that this is within 6·10⁻⁶
//!   of `powf`'s value, which moves the output by at most 0.05 units.
//!   (Changed eyes take this way with AVX-512 too.)
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
//! Unit tests check every level of vector code the processor has against
//! the reference: on every grey pair, 100 000 random pixel pairs per pair
//! of glasses and the edges (0, 1, 10, 11, 12, 127, 128, 254, 255 per
//! channel against black, white, primaries and the toe's first level),
//! exactly or (AVX-512) within 1 and off by one for under 2 % of channels
//! (0.8 % measured);
//! the encoding table on every 64th f32 of (0, 1] and around every
//! threshold.

use std::sync::OnceLock;

use super::anaglyph::{dubois_matrices, linear_to_srgb, srgb_to_linear};
use super::kernels::{ALPHA, N, Planes, Simd, Stage, ahead, chunks};
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
    /// The same in fixed point, for the AVX-512 kernel.
    #[cfg_attr(not(glstereo_avx512), allow(dead_code))]
    fixed: Fixed,
}

/// The sRGB decoding in fixed point: `lin(x)·2¹⁵` rounded (white, 2¹⁵,
/// as 2¹⁵ − 1), split into its low and high bytes for byte permutes.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
fn decode_q15() -> &'static [[u8; 256]; 2] {
    static TABLE: OnceLock<[[u8; 256]; 2]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let q = |x: usize| {
            let v = (srgb_to_linear(x as f32 / 255.0) as f64 * 32768.0).round();
            v.min(32767.0) as u16
        };
        [
            std::array::from_fn(|x| q(x) as u8),
            std::array::from_fn(|x| (q(x) >> 8) as u8),
        ]
    })
}

/// Byte permutes of a chunk's decoded low and high bytes (bit 6 of an
/// index: the high) into word pairs per pixel: byte j of dword i from
/// byte 4i + f[j] of the pixel words.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
const fn pair_index(f: [u8; 4]) -> [u8; 64] {
    let mut b = [0; 64];
    let mut j = 0;
    while j < 64 {
        let (i, k) = (j / 4, j % 4);
        b[j] = if k % 2 == 1 { 64 } else { 0 } + 4 * i as u8 + f[k];
        j += 1;
    }
    b
}

/// (R, G) of a pixel, and (B, B) (the left eye's in the low word, the
/// right eye's in the high).
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
const PAIR_RG: [u8; 64] = pair_index([0, 0, 1, 1]);
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
const PAIR_BB: [u8; 64] = pair_index([2, 2, 2, 2]);

/// m^(1/2.4) on [1, 2] by a cubic (Chebyshev interpolation; within
/// 1.1·10⁻⁴, 0.03 of an output unit at the top octave), lowest power first.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
const CUBIC: [f32; 4] = [0.461_083_8, 0.688_601, -0.173_310_86, 0.023_732_816];

/// [`Dubois`] in fixed point for [`Dubois::chunk_avx512`]: per output
/// channel, the six weights as 16-bit integers `round(w·2^S)` (S = 15, or
/// 14 where a weight is 1 or more), so that the sum of weight × decoded
/// channel (2¹⁵ for 1) is `v·2^(15+S)`, exactly, in 32 bits; and the
/// constants of the encoding of such a sum.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Fixed {
    /// Word pairs (left R, left G), (left B, right B), (right R, right G).
    pairs: [[u32; 3]; 3],
    /// The sum at the knee: at or below, the linear toe.
    knee: [f32; 3],
    /// Output units (+0.5, for rounding) per unit of the sum, on the toe.
    toe: [f32; 3],
    /// S − 14: which of [`octaves`] the channel's sums take.
    octave: [u8; 3],
}

/// By a sum's biased f32 exponent mod 16, where the sum is `v·2^(15+S)`
/// (entry S − 14): 255·1.055·2^(e/2.4) for v in [2^e, 2^(e+1)), e = −9…0
/// (the toe's octaves: 0).
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
fn octaves() -> &'static [[f32; 16]; 2] {
    static TABLE: OnceLock<[[f32; 16]; 2]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = [[0.0; 16]; 2];
        for (i, t) in t.iter_mut().enumerate() {
            for e in -9..=0 {
                let slot = (127 + e + 15 + 14 + i as i32) as usize % 16;
                t[slot] = 255.0 * 1.055 * 2f32.powf(e as f32 / 2.4);
            }
        }
        t
    })
}

impl Fixed {
    fn new(m: &[[f32; 6]; 3]) -> Fixed {
        let mut f = Fixed {
            pairs: [[0; 3]; 3],
            knee: [0.0; 3],
            toe: [0.0; 3],
            octave: [0; 3],
        };
        for (c, m) in m.iter().enumerate() {
            let max = m.iter().fold(0.0f32, |a, w| a.max(w.abs()));
            let s: i32 = if max * 32768.0 < 32767.0 { 15 } else { 14 };
            let q = m.map(|w| (f64::from(w) * f64::from(1 << s)).round() as i32);
            let total: i64 = q.iter().map(|q| i64::from(q.abs()) * 32767).sum();
            assert!(total < 1 << 31, "the sums fit in 32 bits");
            let pair = |a: i32, b: i32| (a as u16 as u32) | (b as u16 as u32) << 16;
            f.pairs[c] = [pair(q[0], q[1]), pair(q[2], q[5]), pair(q[3], q[4])];
            let unit = 2f32.powi(15 + s);
            f.knee[c] = KNEE * unit;
            f.toe[c] = 12.92 * 255.0 / unit;
            f.octave[c] = (s - 14) as u8;
        }
        f
    }
}

/// The constants of [`Dubois::row_avx512`] in registers, and its kernel.
#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
#[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
struct Avx512<'a> {
    /// The low and the high bytes of [`decode_q15`], 64 entries a register.
    lo: [std::arch::x86_64::__m512i; 4],
    hi: [std::arch::x86_64::__m512i; 4],
    /// [`PAIR_RG`], [`PAIR_BB`].
    rg: std::arch::x86_64::__m512i,
    bb: std::arch::x86_64::__m512i,
    /// [`Fixed::octave`].
    octave: [std::arch::x86_64::__m512; 3],
    fixed: &'a Fixed,
}

#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
#[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
impl Avx512<'_> {
    #[target_feature(enable = "avx512f,avx512bw,avx512vbmi,avx512vnni,fma")]
    #[inline]
    fn new(d: &Dubois) -> Avx512<'_> {
        use std::arch::x86_64::*;
        let q = decode_q15();
        // SAFETY: 64 bytes of a 256-byte table at a multiple of 64, or of
        // a 64-byte constant; 16 f32.
        let load = |p: &[u8]| unsafe { _mm512_loadu_si512(p.as_ptr().cast()) };
        let planes = |t: &[u8; 256]| [0, 1, 2, 3].map(|i| load(&t[64 * i..]));
        Avx512 {
            lo: planes(&q[0]),
            hi: planes(&q[1]),
            rg: load(&PAIR_RG),
            bb: load(&PAIR_BB),
            octave: d
                .fixed
                .octave
                .map(|i| unsafe { _mm512_loadu_ps(octaves()[usize::from(i)].as_ptr()) }),
            fixed: &d.fixed,
        }
    }

    /// Each byte of the pixels `w` (alpha too, unused) decoded: its low or
    /// high byte (`t`), by the byte's low 7 bits in two 128-entry halves.
    #[target_feature(enable = "avx512f,avx512bw,avx512vbmi")]
    #[inline]
    fn decode(
        w: std::arch::x86_64::__m512i,
        t: &[std::arch::x86_64::__m512i; 4],
    ) -> std::arch::x86_64::__m512i {
        use std::arch::x86_64::*;
        let k = _mm512_movepi8_mask(w);
        let a = _mm512_permutex2var_epi8(t[0], w, t[1]);
        let b = _mm512_permutex2var_epi8(t[2], w, t[3]);
        _mm512_mask_blend_epi8(k, a, b)
    }

    /// `acc` + the pairwise products of the words of `a` and of the
    /// word pair `*w` (read from memory, broadcast by the instruction: the
    /// nine pairs would not stay in registers beside the tables). (As
    /// asm: LLVM's generic tuning splits the intrinsic into a multiply and
    /// an add, two instructions for one.)
    #[target_feature(enable = "avx512f,avx512vnni")]
    #[inline]
    fn dot(
        mut acc: std::arch::x86_64::__m512i,
        a: std::arch::x86_64::__m512i,
        w: &u32,
    ) -> std::arch::x86_64::__m512i {
        // SAFETY: an AVX-512 VNNI instruction reading the 4 bytes of `w`.
        unsafe {
            std::arch::asm!(
                "vpdpwssd {acc}, {a}, dword ptr [{w}]{{1to16}}",
                acc = inout(zmm_reg) acc,
                a = in(zmm_reg) a,
                w = in(reg) w,
                options(pure, readonly, nostack, preserves_flags),
            );
        }
        acc
    }

    /// The sum of output channel `c` of the word pairs `p`, as f32
    /// (`v·2^(15+S)`).
    #[target_feature(enable = "avx512f,avx512bw,avx512vnni")]
    #[inline]
    fn sum(&self, c: usize, p: &[std::arch::x86_64::__m512i; 3]) -> std::arch::x86_64::__m512 {
        use std::arch::x86_64::*;
        let w = &self.fixed.pairs[c];
        let first = _mm512_madd_epi16(p[0], _mm512_set1_epi32(w[0] as i32));
        let sum = Self::dot(Self::dot(first, p[1], &w[1]), p[2], &w[2]);
        _mm512_cvtepi32_ps(sum)
    }

    /// Output channel `c` of its sum `f` above the toe: the octave's scale
    /// × the cubic of the mantissa, + 0.5 for rounding.
    #[target_feature(enable = "avx512f,fma")]
    #[inline]
    fn curve(&self, c: usize, f: std::arch::x86_64::__m512) -> std::arch::x86_64::__m512 {
        use std::arch::x86_64::*;
        let m = _mm512_getmant_ps::<_MM_MANT_NORM_1_2, _MM_MANT_SIGN_SRC>(f);
        let e = _mm512_srli_epi32::<23>(_mm512_castps_si512(f));
        let scale = _mm512_permutexvar_ps(e, self.octave[c]);
        let y = _mm512_fmadd_ps(_mm512_set1_ps(CUBIC[3]), m, _mm512_set1_ps(CUBIC[2]));
        let y = _mm512_fmadd_ps(y, m, _mm512_set1_ps(CUBIC[1]));
        let y = _mm512_fmadd_ps(y, m, _mm512_set1_ps(CUBIC[0]));
        _mm512_fmadd_ps(scale, y, _mm512_set1_ps(0.5 - 0.055 * 255.0))
    }

    /// Output channels of the word pairs `p`, as 32-bit integers (outside
    /// 0…255 where the byte saturates): on the toe (sums at or below the
    /// knee) its linear formula; a step where no channel is on it (most
    /// of a picture: the toe is its darkest 4 %) skips that.
    #[target_feature(enable = "avx512f,avx512bw,avx512vnni,fma")]
    #[inline]
    fn channels(&self, p: &[std::arch::x86_64::__m512i; 3]) -> [std::arch::x86_64::__m512i; 3] {
        use std::arch::x86_64::*;
        let fx = self.fixed;
        let f = [self.sum(0, p), self.sum(1, p), self.sum(2, p)];
        let mut v = [
            self.curve(0, f[0]),
            self.curve(1, f[1]),
            self.curve(2, f[2]),
        ];
        // (No closures here: they would not be compiled with these
        // features, and every intrinsic in them would be a call.)
        let mut at_toe = [0; 3];
        for c in 0..3 {
            at_toe[c] = _mm512_cmp_ps_mask::<_CMP_LE_OQ>(f[c], _mm512_set1_ps(fx.knee[c]));
        }
        if at_toe[0] | at_toe[1] | at_toe[2] != 0 {
            for c in 0..3 {
                let t = _mm512_fmadd_ps(f[c], _mm512_set1_ps(fx.toe[c]), _mm512_set1_ps(0.5));
                v[c] = _mm512_mask_blend_ps(at_toe[c], v[c], t);
            }
        }
        [
            _mm512_cvttps_epi32(v[0]),
            _mm512_cvttps_epi32(v[1]),
            _mm512_cvttps_epi32(v[2]),
        ]
    }

    /// The anaglyph of 16 pixel pairs.
    #[target_feature(enable = "avx512f,avx512bw,avx512vbmi,avx512vnni,fma")]
    #[inline]
    fn compose(
        &self,
        l: std::arch::x86_64::__m512i,
        r: std::arch::x86_64::__m512i,
    ) -> std::arch::x86_64::__m512i {
        use std::arch::x86_64::*;
        let (l_lo, l_hi) = (Self::decode(l, &self.lo), Self::decode(l, &self.hi));
        let (r_lo, r_hi) = (Self::decode(r, &self.lo), Self::decode(r, &self.hi));
        // Word pairs per pixel: (left R, G), (left B, right B), (right R, G).
        let p = [
            _mm512_permutex2var_epi8(l_lo, self.rg, l_hi),
            _mm512_mask_blend_epi16(
                0xAAAA_AAAA,
                _mm512_permutex2var_epi8(l_lo, self.bb, l_hi),
                _mm512_permutex2var_epi8(r_lo, self.bb, r_hi),
            ),
            _mm512_permutex2var_epi8(r_lo, self.rg, r_hi),
        ];
        // Saturated into bytes (below 0 and above 255 clamp), per 128-bit
        // lane R0-3 G0-3 B0-3 A0-3, then reordered into pixels.
        let [r, g, b] = self.channels(&p);
        let rg = _mm512_packus_epi32(r, g);
        let ba = _mm512_packus_epi32(b, _mm512_set1_epi32(255));
        let order = _mm512_broadcast_i32x4(_mm_setr_epi8(
            0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15,
        ));
        _mm512_shuffle_epi8(_mm512_packus_epi16(rg, ba), order)
    }
}

impl Dubois {
    pub(crate) fn new(colors: AnaglyphColors) -> Dubois {
        let d = dubois_matrices(colors);
        // Build the tables now, not inside a frame.
        let _ = (decode_table(), encode_table(), decode_q15(), octaves());
        let m = std::array::from_fn(|c| {
            std::array::from_fn(|k| {
                if k < 3 {
                    d.left[c][k]
                } else {
                    d.right[c][k - 3]
                }
            })
        });
        Dubois {
            m,
            fixed: Fixed::new(&m),
        }
    }

    /// One row: `out[x]` the anaglyph of `a[x]` (left) and `b[x]` (right)
    /// after `stage`, through `px`; `memo` holds the last [`N`] pixels
    /// composed (clear it when the anaglyph or the stage changes).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn row(
        &self,
        simd: Simd,
        stage: Stage,
        memo: &mut Memo,
        a: &[u32],
        b: &[u32],
        out: &mut [u32],
        px: impl Fn(u32) -> u32,
    ) {
        #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
        if simd.avx512() && stage.is_identity() {
            // SAFETY: `simd` says the processor has these features (see
            // with_simd).
            return unsafe { self.row_avx512(memo, a, b, out, px) };
        }
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
                    self.chunk(simd, Pixels::Words(l, r))
                } else {
                    let (mut lp, mut rp) = (Planes::of(l), Planes::of(r));
                    stage.apply(&mut lp, &mut rp);
                    self.chunk(simd, Pixels::Planes(&lp, &rp))
                };
                *last = Some((*l, *r, o));
                o
            },
        );
    }

    /// [`N`] pixels, with the vector code `simd` says the processor has.
    #[inline(always)]
    fn chunk(&self, simd: Simd, p: Pixels<'_>) -> [u32; N] {
        #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
        if let (true, Pixels::Words(l, r)) = (simd.avx512(), p) {
            // SAFETY: `simd` says the processor has these features (see
            // with_simd).
            return unsafe { self.chunk_avx512(l, r) };
        }
        #[cfg(target_arch = "x86_64")]
        if simd.avx2() {
            // SAFETY: `simd` says the processor has AVX2 (see with_simd).
            return unsafe { self.chunk_avx2(p) };
        }
        let _ = simd;
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

    /// [`N`] 8-bit pixel pairs with AVX-512 ([`Dubois::row_avx512`]).
    ///
    /// # Safety
    /// As [`Dubois::row_avx512`].
    #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
    #[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
    #[target_feature(enable = "avx512f,avx512bw,avx512vbmi,avx512vnni,fma")]
    unsafe fn chunk_avx512(&self, l: &[u32; N], r: &[u32; N]) -> [u32; N] {
        let mut out = [0; N];
        // SAFETY: the caller's promise.
        unsafe { self.row_avx512(&mut Memo::default(), l, r, &mut out, |v| v) };
        out
    }

    /// [`Dubois::row`] of 8-bit eyes (no saturation, no crosstalk) with
    /// AVX-512, [`N`] pixels a vector ([`Avx512`]).
    ///
    /// # Safety
    /// The processor has AVX-512 F, BW, VBMI and VNNI, and FMA.
    #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
    #[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
    #[target_feature(enable = "avx512f,avx512bw,avx512vbmi,avx512vnni,fma")]
    #[inline]
    unsafe fn row_avx512(
        &self,
        memo: &mut Memo,
        a: &[u32],
        b: &[u32],
        out: &mut [u32],
        px: impl Fn(u32) -> u32,
    ) {
        use std::arch::x86_64::*;
        let k = Avx512::new(self);
        // SAFETY (every load and store below): N words of an array or a
        // slice at least that long from that offset.
        let load = |w: &[u32]| unsafe { _mm512_loadu_si512(w.as_ptr().cast()) };
        let store = |v: __m512i| {
            let mut w = [0u32; N];
            unsafe { _mm512_storeu_si512(w.as_mut_ptr().cast(), v) };
            w
        };
        // The last chunk composed, for runs of equal pixels.
        let (mut last, mut valid) = match &memo.0 {
            Some((l, r, o)) => ([load(l), load(r), load(o)], true),
            None => ([_mm512_setzero_si512(); 3], false),
        };
        let n = out.len().min(a.len()).min(b.len());
        let whole = n - n % N;
        let mut x = 0;
        while x < n {
            ahead([a, b], out, x);
            let (l, r) = if x < whole {
                (load(&a[x..]), load(&b[x..]))
            } else {
                let (mut l, mut r) = ([0u32; N], [0u32; N]);
                l[..n - whole].copy_from_slice(&a[whole..n]);
                r[..n - whole].copy_from_slice(&b[whole..n]);
                (load(&l), load(&r))
            };
            let differ =
                _mm512_cmpneq_epi32_mask(l, last[0]) | _mm512_cmpneq_epi32_mask(r, last[1]);
            if !valid || differ != 0 {
                last = [l, r, k.compose(l, r)];
                valid = true;
            }
            let o = store(last[2]);
            let m = N.min(n - x);
            if m == N {
                // A whole step: a fixed-size loop, one vector store (a
                // loop of variable length is a call to memcpy, after
                // which every constant is loaded again).
                let out: &mut [u32; N] = (&mut out[x..x + N]).try_into().expect("N words");
                for i in 0..N {
                    out[i] = px(o[i]);
                }
            } else {
                for (o, &v) in out[x..x + m].iter_mut().zip(&o) {
                    *o = px(v);
                }
            }
            x += N;
        }
        if valid {
            memo.0 = Some((store(last[0]), store(last[1]), store(last[2])));
        }
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

    /// The reference: cpu.rs's arithmetic.
    fn reference(colors: AnaglyphColors, l: [f32; 3], r: [f32; 3]) -> [u8; 3] {
        let m = dubois_matrices(colors);
        let lin = |x: [f32; 3]| x.map(|v| srgb_to_linear(v / 255.0));
        let o = dubois_pixel(&m, lin(l), lin(r));
        o.map(|v| ((v * 255.0).clamp(0.0, 255.0) + 0.5) as u8)
    }

    /// The levels of vector code this processor can run.
    fn levels() -> impl Iterator<Item = Simd> {
        Simd::ALL.into_iter().filter(|&s| s <= Simd::detected())
    }

    /// Composes the pixel pairs N at a time at vector level `simd` and
    /// compares each pixel with the reference within `tol`; returns how
    /// many channels differ from it.
    fn check(
        simd: Simd,
        colors: AnaglyphColors,
        pairs: &[([f32; 3], [f32; 3])],
        staged: bool,
        tol: i32,
    ) -> usize {
        let d = Dubois::new(colors);
        let mut differ = 0;
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
            let words = d.chunk(simd, pixels);
            for (i, &(pl, pr)) in group.iter().enumerate() {
                let want = reference(colors, pl, pr);
                let w = words[i].to_le_bytes();
                for c in 0..3 {
                    let diff = (i32::from(w[c]) - i32::from(want[c])).abs();
                    differ += usize::from(diff != 0);
                    assert!(
                        diff <= tol,
                        "{simd:?} {colors:?} left {pl:?} right {pr:?}: {:?}, want {want:?}",
                        &w[..3]
                    );
                }
                assert_eq!(w[3], 255);
            }
        }
        differ
    }

    /// The tolerance of 8-bit eyes: exact but for AVX-512's fixed point.
    fn tolerance(simd: Simd) -> i32 {
        i32::from(simd == Simd::Avx512)
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

    /// Grey pairs, random pixels and the edges (black, white, the toe's
    /// last and first levels, the primaries).
    fn eight_bit_pairs() -> Vec<([f32; 3], [f32; 3])> {
        let greys = (0..=255u8)
            .flat_map(|a| (0..=255u8).map(move |b| ([f32::from(a); 3], [f32::from(b); 3])));
        let levels = [0.0, 1.0, 10.0, 11.0, 12.0, 127.0, 128.0, 254.0, 255.0];
        let edges: Vec<[f32; 3]> = levels
            .iter()
            .flat_map(|&r| levels.iter().flat_map(move |&g| levels.map(|b| [r, g, b])))
            .collect();
        let edge_pairs = edges
            .iter()
            .flat_map(|&l| {
                [
                    [0.0; 3],
                    [255.0; 3],
                    [255.0, 0.0, 0.0],
                    [0.0, 255.0, 255.0],
                    [11.0; 3],
                ]
                .map(|r| (l, r))
            })
            .chain(edges.iter().map(|&r| ([255.0, 10.0, 0.0], r)));
        greys
            .chain(edge_pairs)
            .chain(random_pairs(100_000, true))
            .collect()
    }

    #[test]
    fn eight_bit_eyes_give_the_reference_bytes_at_every_level() {
        // AVX-512 within 1, the others exactly: on grey pairs, 100 000
        // random pixel pairs per pair of glasses, and the edges.
        let pairs = eight_bit_pairs();
        for simd in levels() {
            for colors in AnaglyphColors::ALL {
                let differ = check(simd, colors, &pairs, false, tolerance(simd));
                // Off by one only where the reference is close to a half.
                assert!(
                    differ * 50 < pairs.len() * 3,
                    "{simd:?} {colors:?}: {differ} channels of {} differ",
                    3 * pairs.len()
                );
                eprintln!(
                    "{simd:?} {colors:?}: {differ} of {} channels off by one",
                    3 * pairs.len()
                );
            }
        }
    }

    #[test]
    fn changed_eyes_stay_within_one_unit_of_the_reference() {
        let random = random_pairs(50_000, false);
        for simd in levels() {
            for colors in AnaglyphColors::ALL {
                check(simd, colors, &random, true, 1);
            }
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

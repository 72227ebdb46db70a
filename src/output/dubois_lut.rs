//! The `-dubois` anaglyphs by tables: with AVX-512, in fixed point,
//! within 1 unit of what [`super::cpu::reference`] computes; otherwise,
//! for 8-bit eyes byte for byte the reference, and for eyes changed by
//! saturation or crosstalk within 1 unit of it.
//!
//! The reference computes, per output channel c,
//! `v = ML[c][0]·lin(l0) + ML[c][1]·lin(l1) + ML[c][2]·lin(l2) + MR[c][0]·lin(r0) + …`
//! in f32 from left to right, then `unorm(linear_to_srgb(clamp(v, 0, 1))·255)`.
//!
//! **AVX-512** (8-bit eyes; [`Dubois::row_avx512`], 32 pixels a step,
//! software-pipelined): within 1 unit, and equal to the reference for more
//! than 99 % of channels.
//!
//! - **Decoding**: the six channels of 32 pixels packed by byte permutes
//!   into three registers of channel pairs per pixel (left R, G; left B
//!   and the right eye's B, moved into the left eye's alpha byte; right R,
//!   G), then `lin(x)·2¹⁵` rounded to 16 bits, its low and high bytes
//!   looked up by byte permutes (VBMI) of 128-entry halves of the table,
//!   and unpacked into 16-bit pairs; errors ≤ 2⁻¹⁶.
//! - **The sum** in 32-bit integers, pairs of 16-bit products at a time
//!   (VNNI), with the weights rounded to 16 bits (`round(w·2^S)`, S = 15,
//!   or 14 for weights of 1 or more); errors ≤ 6·2⁻¹⁶ + 2⁻¹⁶·Σ|w|.
//! - **Encoding** in f32: the smaller of the curve — per octave
//!   [2^e, 2^(e+1)) of v, `255·1.055·2^(e/2.4)` (a 32-entry permute by the
//!   exponent and the mantissa's top bit) times a cubic of the mantissa
//!   ([`CUBIC`], within 0.03 units), minus 0.055·255 — and the toe's line
//!   `12.92·255·v`: sRGB's two pieces cross at the knee, so the smaller is
//!   the right one but within 0.002 units in the half octave the knee
//!   splits, and half octaves wholly below the knee give the curve a huge
//!   scale ([`Fixed::scale`]). Rounded to nearest, bytes saturated by
//!   packing.
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
#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
use super::kernels::VectorPx;
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
    /// The same in fixed point, for the AVX-512 kernel (one per pair of
    /// glasses, built once: its tables are 400 bytes).
    #[cfg_attr(not(glstereo_avx512), allow(dead_code))]
    fixed: &'static Fixed,
}

/// 64-byte alignment for the AVX-512 kernel's tables (whole cache lines,
/// loads that never split one).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
struct Lines<T>(T);

/// The sRGB decoding in fixed point: `lin(x)·2¹⁵` rounded (white, 2¹⁵,
/// as 2¹⁵ − 1), split into its low and high bytes for byte permutes.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
fn decode_q15() -> &'static Lines<[[u8; 256]; 2]> {
    static TABLE: OnceLock<Lines<[[u8; 256]; 2]>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let q = |x: usize| {
            let v = (srgb_to_linear(x as f32 / 255.0) as f64 * 32768.0).round();
            v.min(32767.0) as u16
        };
        Lines([
            std::array::from_fn(|x| q(x) as u8),
            std::array::from_fn(|x| (q(x) >> 8) as u8),
        ])
    })
}

/// The pixel of byte i of a packed pair register (32 pixels, two channels
/// each, [`Dubois::row_avx512`]): in 128-bit lane l, bytes 0–7 hold the
/// pairs of pixels 4l…4l+3 and bytes 8–15 those of pixels 16+4l…16+4l+3,
/// so that unpacking a lane's low and high halves into words gives
/// pixels 0–15 and 16–31 in order.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
const fn packed_pixel(i: usize) -> usize {
    let (lane, pair) = (i / 16, i % 16 / 2);
    if pair < 4 {
        4 * lane + pair
    } else {
        16 + 4 * lane + pair - 4
    }
}

/// Byte permutes of two eye registers (32 pixels: byte 4p + c is channel
/// c of pixel p) into a packed pair register of channels `first` and
/// `first` + 1.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
const fn pack_index(first: usize) -> Lines<[u8; 64]> {
    let mut b = [0; 64];
    let mut i = 0;
    while i < 64 {
        b[i] = (4 * packed_pixel(i) + first + i % 2) as u8;
        i += 1;
    }
    Lines(b)
}

/// (R, G) of each pixel; and (B, alpha), where the kernel has put the
/// right eye's blue in the left eye's alpha byte.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
static PACK_RG: Lines<[u8; 64]> = pack_index(0);
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
static PACK_BA: Lines<[u8; 64]> = pack_index(2);

/// m^(1/2.4) on [1, 2] by a cubic (Chebyshev interpolation; within
/// 1.1·10⁻⁴, 0.03 of an output unit at the top octave), lowest power first.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
const CUBIC: [f32; 4] = [0.461_083_8, 0.688_601, -0.173_310_86, 0.023_732_816];

/// A scale the curve takes where a half octave lies below the knee, so
/// that the toe's line is the smaller (see [`Fixed::scale`]).
const ABOVE: f32 = 1e30;

/// [`Dubois`] in fixed point for [`Dubois::row_avx512`]: per output
/// channel, the six weights as 16-bit integers `round(w·2^S)` (S = 15, or
/// 14 where a weight is 1 or more), so that the sum of weight × decoded
/// channel (2¹⁵ for 1) is `v·2^(15+S)`, exactly, in 32 bits; and the
/// constants of the encoding of such a sum.
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernel's.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Fixed {
    /// Word pairs (left R, left G), (left B, right B), (right R, right G).
    pairs: [[u32; 3]; 3],
    /// Output units per unit of the sum on the toe (12.92·255/2^(15+S)).
    toe: [f32; 3],
    /// By the f32 bits of a sum shifted right by 22, mod 32 (the octave
    /// [2^e, 2^(e+1)) of v and which half of it): 255·1.055·2^(e/2.4), the
    /// curve's scale there (e = −9…0; above 1, e = 0's, which saturates);
    /// [`ABOVE`] for every other half octave. On the toe (v ≤ 0.0031308)
    /// the output is the smaller of the toe's line and the curve: every
    /// half octave wholly below the knee makes the curve huge, and in the
    /// one the knee splits, [1.5, 2)·2⁻⁹, the curve lies under the line by
    /// at most 0.0008·255 above the knee and within 0.002 units of it
    /// below; higher the curve is the smaller (sRGB's two pieces cross
    /// at the knee and the line is steeper).
    scale: Lines<[[f32; 32]; 3]>,
}

impl Fixed {
    fn new(m: &[[f32; 6]; 3]) -> Fixed {
        let mut f = Fixed {
            pairs: [[0; 3]; 3],
            toe: [0.0; 3],
            scale: Lines([[ABOVE; 32]; 3]),
        };
        for (c, m) in m.iter().enumerate() {
            let max = m.iter().fold(0.0f32, |a, w| a.max(w.abs()));
            let s: i32 = if max * 32768.0 < 32767.0 { 15 } else { 14 };
            let q = m.map(|w| (f64::from(w) * f64::from(1 << s)).round() as i32);
            let total: i64 = q.iter().map(|q| i64::from(q.abs()) * 32767).sum();
            assert!(total < 1 << 31, "the sums fit in 32 bits");
            // Positive sums stay below 2^(16+S) (v < 2): one half-octave
            // slot per half octave from 2⁻¹⁵ up.
            let positive: i64 = q.iter().map(|&q| i64::from(q.max(0)) * 32767).sum();
            assert!(positive < 1 << (16 + s), "v < 2");
            let pair = |a: i32, b: i32| (a as u16 as u32) | (b as u16 as u32) << 16;
            f.pairs[c] = [pair(q[0], q[1]), pair(q[2], q[5]), pair(q[3], q[4])];
            f.toe[c] = (12.92 * 255.0 / 2f64.powi(15 + s)) as f32;
            for e in -9..=1 {
                for half in 0..2 {
                    let top = 2f64.powi(e) * (1.0 + f64::from(half + 1) / 2.0);
                    let slot = (2 * (127 + 15 + s + e) + half) as usize % 32;
                    if top > f64::from(KNEE) {
                        f.scale.0[c][slot] = 255.0 * 1.055 * 2f32.powf(e.min(0) as f32 / 2.4);
                    }
                }
            }
        }
        f
    }
}

/// The AVX-512 kernel of [`Dubois::row_avx512`] (its tables stay in
/// memory: a byte permute overwrites one of its two tables, and the
/// instructions read the other from memory at no cost).
#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
#[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
struct Avx512<'a> {
    fixed: &'a Fixed,
    /// [`decode_q15`].
    q15: &'static Lines<[[u8; 256]; 2]>,
}

/// The sums of one step's 32 pixels: [pixels 0–15, 16–31][channel].
#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
type Sums = [[std::arch::x86_64::__m512i; 3]; 2];

#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
#[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
impl Avx512<'_> {
    /// The first 64 bytes of `p`.
    #[target_feature(enable = "avx512f")]
    #[inline]
    fn line(p: &[u8]) -> std::arch::x86_64::__m512i {
        assert!(p.len() >= 64, "a line of 64 bytes");
        // SAFETY: 64 bytes of the slice (checked above).
        unsafe { std::arch::x86_64::_mm512_loadu_si512(p.as_ptr().cast()) }
    }

    /// Each byte of `x` decoded: its low and high bytes, by the byte's low
    /// 7 bits in two 128-entry halves of the table.
    #[target_feature(enable = "avx512f,avx512bw,avx512vbmi")]
    #[inline]
    fn decode(&self, x: std::arch::x86_64::__m512i) -> [std::arch::x86_64::__m512i; 2] {
        use std::arch::x86_64::*;
        let k = _mm512_movepi8_mask(x);
        let [lo, hi] = &self.q15.0;
        [
            _mm512_mask_blend_epi8(
                k,
                _mm512_permutex2var_epi8(Self::line(&lo[..]), x, Self::line(&lo[64..])),
                _mm512_permutex2var_epi8(Self::line(&lo[128..]), x, Self::line(&lo[192..])),
            ),
            _mm512_mask_blend_epi8(
                k,
                _mm512_permutex2var_epi8(Self::line(&hi[..]), x, Self::line(&hi[64..])),
                _mm512_permutex2var_epi8(Self::line(&hi[128..]), x, Self::line(&hi[192..])),
            ),
        ]
    }

    /// `acc` + the pairwise products of the words of `a` and of the
    /// word pair `*w` (read from memory, broadcast by the instruction).
    /// (As asm: LLVM's generic tuning splits the intrinsic into a multiply
    /// and an add, two instructions for one.)
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

    /// The sums of 32 pixel pairs: the left eye `l` and the right `r`,
    /// 16 pixels a register.
    #[target_feature(enable = "avx512f,avx512bw,avx512vbmi,avx512vnni")]
    #[inline]
    fn sums(&self, l: [std::arch::x86_64::__m512i; 2], r: [std::arch::x86_64::__m512i; 2]) -> Sums {
        use std::arch::x86_64::*;
        let (rg, ba) = (Self::line(&PACK_RG.0), Self::line(&PACK_BA.0));
        // The right eye's blue in the left eye's alpha byte (bit select).
        let alpha = _mm512_set1_epi32(0xFF00_0000u32 as i32);
        let lb = [
            _mm512_ternarylogic_epi32::<0xCA>(alpha, _mm512_slli_epi32::<8>(r[0]), l[0]),
            _mm512_ternarylogic_epi32::<0xCA>(alpha, _mm512_slli_epi32::<8>(r[1]), l[1]),
        ];
        // Pairs (left R, G), (left B, right B), (right R, G), decoded and
        // unpacked into words: dword i of [0] is pixel i, of [1] 16 + i.
        let packed = [
            _mm512_permutex2var_epi8(lb[0], rg, lb[1]),
            _mm512_permutex2var_epi8(lb[0], ba, lb[1]),
            _mm512_permutex2var_epi8(r[0], rg, r[1]),
        ];
        let (a, b, c) = (
            self.decode(packed[0]),
            self.decode(packed[1]),
            self.decode(packed[2]),
        );
        let words = [
            [
                _mm512_unpacklo_epi8(a[0], a[1]),
                _mm512_unpacklo_epi8(b[0], b[1]),
                _mm512_unpacklo_epi8(c[0], c[1]),
            ],
            [
                _mm512_unpackhi_epi8(a[0], a[1]),
                _mm512_unpackhi_epi8(b[0], b[1]),
                _mm512_unpackhi_epi8(c[0], c[1]),
            ],
        ];
        let mut sums = [[_mm512_setzero_si512(); 3]; 2];
        for (sums, p) in sums.iter_mut().zip(&words) {
            for (sum, w) in sums.iter_mut().zip(&self.fixed.pairs) {
                let first = _mm512_madd_epi16(p[0], _mm512_set1_epi32(w[0] as i32));
                *sum = Self::dot(Self::dot(first, p[1], &w[1]), p[2], &w[2]);
            }
        }
        sums
    }

    /// Output channel `c` of its sums, as 32-bit integers (outside 0…255
    /// where the byte saturates): the smaller of the curve (the octave's
    /// scale × the cubic of the mantissa) and the toe's line (see
    /// [`Fixed::scale`]), rounded to nearest.
    #[target_feature(enable = "avx512f,fma")]
    #[inline]
    fn channel(&self, c: usize, s: std::arch::x86_64::__m512i) -> std::arch::x86_64::__m512i {
        use std::arch::x86_64::*;
        // Rounded down, so that no sum rounds up into the next octave.
        let f = _mm512_cvt_roundepi32_ps::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(s);
        let m = _mm512_getmant_ps::<_MM_MANT_NORM_1_2, _MM_MANT_SIGN_ZERO>(f);
        let half = _mm512_srli_epi32::<22>(_mm512_castps_si512(f));
        let table = &self.fixed.scale.0[c];
        // SAFETY: 16 f32 of a 32-entry table, twice.
        let scale = unsafe {
            _mm512_permutex2var_ps(
                _mm512_loadu_ps(table.as_ptr()),
                half,
                _mm512_loadu_ps(table[16..].as_ptr()),
            )
        };
        let y = _mm512_fmadd_ps(_mm512_set1_ps(CUBIC[3]), m, _mm512_set1_ps(CUBIC[2]));
        let y = _mm512_fmadd_ps(y, m, _mm512_set1_ps(CUBIC[1]));
        let y = _mm512_fmadd_ps(y, m, _mm512_set1_ps(CUBIC[0]));
        let curve = _mm512_fmadd_ps(scale, y, _mm512_set1_ps(-0.055 * 255.0));
        let toe = _mm512_mul_ps(f, _mm512_set1_ps(self.fixed.toe[c]));
        _mm512_cvtps_epi32(_mm512_min_ps(curve, toe))
    }

    /// The anaglyph of 16 pixels of [`Sums`].
    #[target_feature(enable = "avx512f,avx512bw,fma")]
    #[inline]
    fn encode(&self, s: &[std::arch::x86_64::__m512i; 3]) -> std::arch::x86_64::__m512i {
        use std::arch::x86_64::*;
        let (r, g, b) = (
            self.channel(0, s[0]),
            self.channel(1, s[1]),
            self.channel(2, s[2]),
        );
        // Saturated into bytes (below 0 and above 255 clamp), per 128-bit
        // lane R0-3 G0-3 B0-3 A0-3, then reordered into pixels.
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
        let _ = (decode_table(), encode_table(), decode_q15());
        let m = std::array::from_fn(|c| {
            std::array::from_fn(|k| {
                if k < 3 {
                    d.left[c][k]
                } else {
                    d.right[c][k - 3]
                }
            })
        });
        static FIXED: [OnceLock<Fixed>; 3] = [const { OnceLock::new() }; 3];
        let fixed = FIXED[colors as usize].get_or_init(|| Fixed::new(&m));
        Dubois { m, fixed }
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
    /// AVX-512 ([`Avx512`]), 32 pixels a step, software-pipelined: a step
    /// sums the next 32 pixels before it encodes its own (summed by the
    /// step before), so that the two long dependency chains overlap. A
    /// step whose 32 pixel pairs equal the last step's (flat backgrounds)
    /// copies its anaglyph; `memo` carries that across rows.
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
        /// Pixels a step.
        const STEP: usize = 2 * N;
        type Eyes = [__m512i; 4];
        let k = Avx512 {
            fixed: self.fixed,
            q15: decode_q15(),
        };
        let n = out.len().min(a.len()).min(b.len());
        // (All three as long, so that one test bounds an index into each.)
        let (a, b, out) = (&a[..n], &b[..n], &mut out[..n]);
        // SAFETY (every load and store below): N words of an array or a
        // slice at least that long from that offset.
        let load = |w: &[u32]| unsafe { _mm512_loadu_si512(w.as_ptr().cast()) };
        // A first step up to the output's (or the eyes') next cache line,
        // so that the steps after it store (and load) whole lines: a step
        // across two lines cost 4 % of the row (glibc's large blocks start
        // 16 bytes into a line). (In rows of fewer than 16 steps the extra
        // step costs more.)
        let first = {
            let line = |w: &[u32]| (64 - w.as_ptr() as usize % 64) % 64 / 4;
            let (la, lb, lo) = (line(a), line(b), line(out));
            let head = if la == lb && la != lo { la } else { lo };
            if head > 0 && n >= 16 * STEP {
                head
            } else {
                STEP
            }
            .min(n)
        };
        // The pixels of the step at x.
        let span = |x: usize| if x == 0 { first } else { STEP.min(n - x) };
        // The masks of a step's m pixels (its two registers).
        let masks = |m: usize| -> [__mmask16; 2] {
            let bits = |m: usize| if m >= N { !0 } else { (1u16 << m) - 1 };
            [bits(m), bits(m.saturating_sub(N))]
        };
        // The step at x: the left eye's two registers, then the right's
        // (zeros past its pixels). (A macro: as a closure it was called,
        // and every register saved around the call.)
        macro_rules! step {
            ($x:expr) => {{
                let x: usize = $x;
                let m = span(x);
                if m == STEP {
                    [
                        load(&a[x..x + STEP]),
                        load(&a[x + N..x + STEP]),
                        load(&b[x..x + STEP]),
                        load(&b[x + N..x + STEP]),
                    ]
                } else {
                    let k = masks(m);
                    let (a, b) = (&a[x..x + m], &b[x..x + m]);
                    // SAFETY: the masks cover the m words of a and b from
                    // 0 and N (masked-off words are not read).
                    unsafe {
                        [
                            _mm512_maskz_loadu_epi32(k[0], a.as_ptr().cast()),
                            _mm512_maskz_loadu_epi32(k[1], a.as_ptr().wrapping_add(N).cast()),
                            _mm512_maskz_loadu_epi32(k[0], b.as_ptr().cast()),
                            _mm512_maskz_loadu_epi32(k[1], b.as_ptr().wrapping_add(N).cast()),
                        ]
                    }
                }
            }};
        }
        // Whether two steps' pixels are equal: the first 16 left pixels
        // decide for most steps that differ, then (x ^ y) | z, four times.
        let equal = |p: &Eyes, q: &Eyes| {
            if _mm512_cmpeq_epi64_mask(p[0], q[0]) != 0xFF {
                return false;
            }
            let d = _mm512_xor_si512(p[0], q[0]);
            let d = _mm512_ternarylogic_epi32::<0xBE>(p[1], q[1], d);
            let d = _mm512_ternarylogic_epi32::<0xBE>(p[2], q[2], d);
            let d = _mm512_ternarylogic_epi32::<0xBE>(p[3], q[3], d);
            _mm512_test_epi64_mask(d, d) == 0
        };
        // The last step composed (its pixels and anaglyph), from the memo
        // of the row before: its N pixels twice.
        let (mut last, mut last_out, mut valid) = match &memo.0 {
            Some((l, r, o)) => {
                let (l, r, o) = (load(l), load(r), load(o));
                ([l, l, r, r], [o, o], true)
            }
            None => (
                [_mm512_setzero_si512(); 4],
                [_mm512_setzero_si512(); 2],
                false,
            ),
        };
        // `px` on whole registers where it is a byte map (a window's byte
        // order): a store of the registers read back word by word through
        // `px` stalls on forwarding and cost 7 % of the step.
        let map = VectorPx::of(&px);
        // Writes a step's anaglyph at x through px.
        macro_rules! emit {
            ($x:expr, $v:expr) => {{
                let (x, mut v): (usize, [__m512i; 2]) = ($x, $v);
                let m = span(x);
                if let Some(map) = &map {
                    v = [map.apply(v[0]), map.apply(v[1])];
                }
                if m == STEP && map.is_some() {
                    // SAFETY: N words at x and x + N of a slice of x + 2N.
                    unsafe {
                        _mm512_storeu_si512(out[x..x + STEP].as_mut_ptr().cast(), v[0]);
                        _mm512_storeu_si512(out[x + N..x + STEP].as_mut_ptr().cast(), v[1]);
                    }
                } else if map.is_some() {
                    let k = masks(m);
                    let out = &mut out[x..x + m];
                    // SAFETY: the masks cover the m words of out from 0
                    // and N (masked-off words are not written).
                    unsafe {
                        _mm512_mask_storeu_epi32(out.as_mut_ptr().cast(), k[0], v[0]);
                        _mm512_mask_storeu_epi32(
                            out.as_mut_ptr().wrapping_add(N).cast(),
                            k[1],
                            v[1],
                        );
                    }
                } else {
                    let mut o = [0u32; STEP];
                    // SAFETY: N words at 0 and N of 2N.
                    unsafe {
                        _mm512_storeu_si512(o.as_mut_ptr().cast(), v[0]);
                        _mm512_storeu_si512(o[N..].as_mut_ptr().cast(), v[1]);
                    }
                    for (o, &v) in out[x..x + m].iter_mut().zip(&o) {
                        *o = px(v);
                    }
                }
            }};
        }
        let mut x = 0;
        'steps: while x < n {
            let eyes: Eyes = step!(x);
            if valid && equal(&eyes, &last) {
                // A run of equal steps.
                emit!(x, last_out);
                x += span(x);
                continue;
            }
            // Steps that differ from the one before, pipelined: the next
            // step's sums before this one's encoding. (The step before is
            // compared from memory, read a moment ago, where its first
            // left pixel is the same: kept in registers, it cost 4 % of a
            // row.)
            let mut sums = k.sums([eyes[0], eyes[1]], [eyes[2], eyes[3]]);
            loop {
                ahead([a, b], out, x + STEP);
                ahead([a, b], out, x + STEP + N);
                let next = x + span(x);
                let next_eyes: Option<Eyes> = (next < n).then(|| step!(next));
                let run = match &next_eyes {
                    Some(e) => a[next] == a[x] && equal(e, &step!(x)),
                    None => true,
                };
                match next_eyes {
                    Some(next_eyes) if !run => {
                        let next_sums =
                            k.sums([next_eyes[0], next_eyes[1]], [next_eyes[2], next_eyes[3]]);
                        emit!(x, [k.encode(&sums[0]), k.encode(&sums[1])]);
                        (sums, x) = (next_sums, next);
                    }
                    _ => {
                        last_out = [k.encode(&sums[0]), k.encode(&sums[1])];
                        (last, valid) = (step!(x), true);
                        emit!(x, last_out);
                        x = next;
                        continue 'steps;
                    }
                }
            }
        }
        if !valid {
            return;
        }
        // The last step's first N pixel pairs (past the row's end: zero
        // pairs and their anaglyph, as true as any).
        let store = |v: __m512i| {
            let mut w = [0u32; N];
            // SAFETY: N words into an array of N.
            unsafe { _mm512_storeu_si512(w.as_mut_ptr().cast(), v) };
            w
        };
        memo.0 = Some((store(last[0]), store(last[2]), store(last_out[0])));
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
    use crate::output::kernels::Stage;

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

    /// A pixel pair (left, right), channels 0…255.
    type Pair = ([f32; 3], [f32; 3]);

    /// The AVX-512 row tests' setup: the identity stage and noise pairs;
    /// None (and a word why) on a processor without AVX-512.
    fn avx512_rows() -> Option<(Stage, Vec<Pair>)> {
        if Simd::detected() < Simd::Avx512 {
            eprintln!("no AVX-512 here");
            return None;
        }
        let stage = Stage {
            saturation: 1.0,
            crosstalk: 0.0,
        };
        Some((stage, random_pairs(4096, true)))
    }

    /// An 8-bit pixel word of a noise pair's eye (alpha 0x55: the kernel
    /// must write 255 whatever it reads).
    fn word(p: [f32; 3]) -> u32 {
        u32::from_le_bytes([p[0] as u8, p[1] as u8, p[2] as u8, 0x55])
    }

    /// Rows through every path of the AVX-512 kernel: lengths around its
    /// 32-pixel step, runs of equal steps (from the row before too, by the
    /// memo), and a window's byte order, against the one-pixel-at-a-time
    /// kernel within 1.
    #[test]
    fn avx512_rows_match_the_scalar_kernel_through_runs_tails_and_byte_orders() {
        let Some((stage, noise)) = avx512_rows() else {
            return;
        };
        use crate::backend::PixelLayout;
        for colors in AnaglyphColors::ALL {
            let d = Dubois::new(colors);
            for len in [1, 15, 16, 17, 31, 32, 33, 63, 64, 65, 100, 1280] {
                // Noise, then a flat run, then noise, then flat again.
                let row = |eye: usize, y: usize| -> Vec<u32> {
                    (0..len)
                        .map(|x| {
                            let flat = (x / 40) % 2 == 1 || y == 1;
                            let i = if flat {
                                7
                            } else {
                                (x * 31 + y * 17) % noise.len()
                            };
                            word([noise[i].0, noise[i].1][eye])
                        })
                        .collect()
                };
                let (mut memo_a, mut memo_s) = (Memo::default(), Memo::default());
                // Then rows of 32 made of the halves of the last step of the
                // row before: the memo must pair a step's pixels with their
                // own anaglyph.
                let halves = |y: usize| {
                    let (a, b) = (row(0, 0), row(1, 0));
                    let last = |r: &[u32], h: usize| -> Vec<u32> {
                        let start = (len - 1) / (2 * N) * (2 * N) + h * N;
                        (0..N)
                            .map(|i| r.get(start + i).copied().unwrap_or(0))
                            .collect()
                    };
                    let (l, r) = (last(&a, y % 2), last(&b, 0));
                    ([l.clone(), l].concat(), [r.clone(), r].concat())
                };
                for y in 0..6 {
                    let (a, b) = if y < 3 {
                        (row(0, y), row(1, y))
                    } else {
                        halves(y)
                    };
                    if y == 3 {
                        (memo_a, memo_s) = (Memo::default(), Memo::default());
                        let (a, b) = (row(0, 0), row(1, 0));
                        let mut o = vec![0; len];
                        d.row(Simd::Avx512, stage, &mut memo_a, &a, &b, &mut o, |v| v);
                        d.row(Simd::Scalar, stage, &mut memo_s, &a, &b, &mut o, |v| v);
                    }
                    let len = a.len();
                    let px = |v| PixelLayout::Bgrx.convert(v);
                    let (mut fast, mut slow) = (vec![0; len], vec![0; len]);
                    d.row(Simd::Avx512, stage, &mut memo_a, &a, &b, &mut fast, px);
                    d.row(Simd::Scalar, stage, &mut memo_s, &a, &b, &mut slow, px);
                    for x in 0..len {
                        let (f, s) = (fast[x].to_le_bytes(), slow[x].to_le_bytes());
                        for c in 0..4 {
                            assert!(
                                (i32::from(f[c]) - i32::from(s[c])).abs() <= 1,
                                "{colors:?} length {len} row {y} pixel {x}: {:08x}, want {:08x}",
                                fast[x],
                                slow[x]
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn avx512_rows_at_every_alignment_match_the_scalar_kernel_and_write_only_their_pixels() {
        // The kernel's first step runs up to a cache line (of the output,
        // or of the eyes where they share an offset): rows starting at
        // every offset into a line, eyes and output apart or together.
        let Some((stage, noise)) = avx512_rows() else {
            return;
        };
        use crate::backend::PixelLayout;
        const WORDS: usize = 1400;
        const GUARD: u32 = 0xDEAD_BEEF;
        let d = Dubois::new(AnaglyphColors::RedCyan);
        let offsets = [
            (0, 0, 0),
            (4, 4, 4),
            (4, 4, 0),
            (0, 0, 4),
            (3, 5, 7),
            (15, 15, 1),
            (1, 0, 15),
        ];
        type Px = fn(u32) -> u32;
        let orders: [Px; 3] = [
            |v| v,
            |v| PixelLayout::Bgrx.convert(v),
            // Not a byte map (the probes keep their bytes, opaque words
            // turn): the word-by-word path.
            |v| if v >> 24 == 0xFF { v.rotate_left(8) } else { v },
        ];
        for len in [17, 511, 512, 700, 1280] {
            for &(oa, ob, oo) in &offsets {
                for (k, px) in orders.iter().enumerate() {
                    let (mut a, mut b) = (Lines([0u32; WORDS]), Lines([0u32; WORDS]));
                    for x in 0..len {
                        // Noise with a flat stretch (a run of equal steps),
                        // then one flat in the left eye only (not a run).
                        let i = if (200..300).contains(&x) {
                            5
                        } else {
                            (x * 31) % noise.len()
                        };
                        let j = if (300..400).contains(&x) { 5 } else { i };
                        a.0[oa + x] = word(noise[j].0);
                        b.0[ob + x] = word(noise[i].1);
                    }
                    let (a, b) = (&a.0[oa..oa + len], &b.0[ob..ob + len]);
                    let mut fast = Lines([GUARD; WORDS]);
                    let mut slow = vec![0; len];
                    let (mut memo_f, mut memo_s) = (Memo::default(), Memo::default());
                    // Twice: the second row starts from the first's memo.
                    for y in 0..2 {
                        let out = &mut fast.0[oo..oo + len];
                        d.row(Simd::Avx512, stage, &mut memo_f, a, b, out, px);
                        d.row(Simd::Scalar, stage, &mut memo_s, a, b, &mut slow, px);
                        for (x, (&f, &s)) in fast.0[oo..oo + len].iter().zip(&slow).enumerate() {
                            let (fb, sb) = (f.to_le_bytes(), s.to_le_bytes());
                            for c in 0..4 {
                                assert!(
                                    (i32::from(fb[c]) - i32::from(sb[c])).abs() <= 1,
                                    "length {len}, offsets {oa} {ob} {oo}, order {k}, row {y}, \
                                     pixel {x}: {f:08x}, want {s:08x}"
                                );
                            }
                        }
                        let outside = fast.0[..oo].iter().chain(&fast.0[oo + len..]);
                        assert!(
                            outside.into_iter().all(|&w| w == GUARD),
                            "length {len}, offsets {oa} {ob} {oo}, order {k}: written outside the row"
                        );
                    }
                }
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

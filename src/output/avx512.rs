//! Hand-written AVX-512 forms of two float kernels the compiler's generic
//! vector code leaves slow: the luminance anaglyphs (`-mono`, `-half`'s
//! grey eye, `anaglyph-red-blue`) and the blend between two rows of an
//! eye (`str-rect`, and every placement scaled vertically only).
//!
//! Both are the reference's f32 operations in its order, one instruction
//! per operation (no fused multiply-add), so they give its bytes exactly.
//! What they save is the generic code's bookkeeping: channels are picked
//! out of the pixel words with one byte shuffle each, and the clamp of
//! [`super::kernels::unorm`] is left out where the values cannot leave
//! 0…255: a luminance of bytes is at most 255·(0.299 + 0.587 + 0.114),
//! which f32 rounds to at most 255.00002 (rounded half up: 255), and a
//! blend `a + f·(b − a)` of bytes with f in [0, 1] stays between `a` and
//! `b` (f32 rounding is monotone and both are exact).
//!
//! 16 pixels a step, the cache lines 2 KiB ahead asked for
//! ([`super::kernels::ahead`]); a row's last partial step loads under a
//! mask. Every word written goes through the caller's `px`. Measured in
//! benches/compose.rs at 1280x1024 (CPU time / memcpy of the composite,
//! one run): -mono 2.16 -> 1.53, red-blue 2.16 -> 1.54, -half 1.80 ->
//! 1.51, str-rect 2.46 -> 1.85.

#![allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).

use std::arch::x86_64::*;

use super::anaglyph::LUMA;
use super::kernels::{ALPHA, N, VectorPx, ahead};

/// Byte shuffles (per 128-bit lane) that put byte `c` of each pixel word
/// into the low byte of its lane and zero the rest.
const fn channel_index(c: u8) -> [u8; 16] {
    let mut b = [0x80; 16];
    let mut i = 0;
    while i < 4 {
        b[4 * i] = 4 * i as u8 + c;
        i += 1;
    }
    b
}

/// R, G, B of 16 pixel words as f32.
#[target_feature(enable = "avx512f,avx512bw")]
#[inline]
fn channels(w: __m512i) -> [__m512; 3] {
    const G: [u8; 16] = channel_index(1);
    const B: [u8; 16] = channel_index(2);
    // SAFETY: 16 bytes of 16-byte arrays.
    let (g, b) = unsafe {
        (
            _mm512_broadcast_i32x4(_mm_loadu_si128(G.as_ptr().cast())),
            _mm512_broadcast_i32x4(_mm_loadu_si128(B.as_ptr().cast())),
        )
    };
    [
        _mm512_cvtepi32_ps(_mm512_and_si512(w, _mm512_set1_epi32(0xFF))),
        _mm512_cvtepi32_ps(_mm512_shuffle_epi8(w, g)),
        _mm512_cvtepi32_ps(_mm512_shuffle_epi8(w, b)),
    ]
}

/// `unorm` of values known to be in 0…255.5 (see the module
/// documentation): + 0.5, truncated.
#[target_feature(enable = "avx512f")]
#[inline]
fn round(v: __m512) -> __m512i {
    _mm512_cvttps_epi32(_mm512_add_ps(v, _mm512_set1_ps(0.5)))
}

/// `p + f·(q − p)`.
#[target_feature(enable = "avx512f")]
#[inline]
fn lerp(p: __m512, q: __m512, f: __m512) -> __m512 {
    _mm512_add_ps(p, _mm512_mul_ps(f, _mm512_sub_ps(q, p)))
}

/// Three channel values (0…255 in 32-bit lanes) as pixel words, alpha 255.
#[target_feature(enable = "avx512f")]
#[inline]
fn pack(c: [__m512i; 3]) -> __m512i {
    let rgb = _mm512_ternarylogic_epi32::<0xFE>(
        c[0],
        _mm512_slli_epi32::<8>(c[1]),
        _mm512_slli_epi32::<16>(c[2]),
    );
    _mm512_or_si512(rgb, _mm512_set1_epi32(ALPHA as i32))
}

/// The rounded luminance of 16 pixel words in R, G and B (alpha 0):
/// `kernels::grey_words`' operations.
#[target_feature(enable = "avx512f,avx512bw")]
#[inline]
fn luma(w: __m512i) -> __m512i {
    let [r, g, b] = channels(w);
    let y = _mm512_add_ps(
        _mm512_add_ps(
            _mm512_mul_ps(_mm512_set1_ps(LUMA[0]), r),
            _mm512_mul_ps(_mm512_set1_ps(LUMA[1]), g),
        ),
        _mm512_mul_ps(_mm512_set1_ps(LUMA[2]), b),
    );
    // The byte into R, G and B.
    const SPREAD: [u8; 16] = [
        0, 0, 0, 0x80, 4, 4, 4, 0x80, 8, 8, 8, 0x80, 12, 12, 12, 0x80,
    ];
    // SAFETY: 16 bytes of a 16-byte array.
    let spread = unsafe { _mm_loadu_si128(SPREAD.as_ptr().cast()) };
    _mm512_shuffle_epi8(round(y), _mm512_broadcast_i32x4(spread))
}

/// Runs `$f` (an expression of the 16 pixel words `$l` and `$r`) over
/// 16-pixel steps of the rows `$a` and `$b` into `$out` (as long as the
/// shortest), the last step under a mask. (A macro, not a function taking
/// a closure: a closure is not compiled with its function's target
/// features, and its intrinsics would become calls.)
macro_rules! steps {
    ($a:expr, $b:expr, $out:expr, $px:expr, |$l:ident, $r:ident| $f:expr) => {{
        let (a, b, out): (&[u32], &[u32], &mut [u32]) = ($a, $b, $out);
        let n = out.len().min(a.len()).min(b.len());
        // `px` on the registers where it is a byte map (a window's byte
        // order), so that they are stored whole.
        let map = VectorPx::of(&$px);
        let mut x = 0;
        while x < n {
            ahead([a, b], out, x);
            let m = N.min(n - x);
            let mask: __mmask16 = if m == N { !0 } else { (1 << m) - 1 };
            // SAFETY: the mask covers m ≤ n − x words, all inside a and b
            // (masked-off words are not read).
            let ($l, $r) = unsafe {
                (
                    _mm512_maskz_loadu_epi32(mask, a[x..].as_ptr().cast()),
                    _mm512_maskz_loadu_epi32(mask, b[x..].as_ptr().cast()),
                )
            };
            let v = $f;
            if let Some(map) = &map {
                // SAFETY: the mask covers m ≤ n − x words, all inside out.
                unsafe {
                    _mm512_mask_storeu_epi32(out[x..].as_mut_ptr().cast(), mask, map.apply(v))
                };
                x += N;
                continue;
            }
            let mut words = [0u32; N];
            // SAFETY: 16 words into an array of 16.
            unsafe { _mm512_storeu_si512(words.as_mut_ptr().cast(), v) };
            if m == N {
                // A whole step: a fixed-size loop, one vector store (a
                // loop of variable length would be a call to memcpy).
                let o: &mut [u32; N] = (&mut out[x..x + N]).try_into().expect("N words");
                for i in 0..N {
                    o[i] = $px(words[i]);
                }
            } else {
                for (o, &v) in out[x..x + m].iter_mut().zip(&words) {
                    *o = $px(v);
                }
            }
            x += N;
        }
    }};
}

/// `PairOp::Mix` with a grey eye on untouched eyes: each eye's word or its
/// luminance (`grey`), bytes from the first where `lm` has them and from
/// the second elsewhere, kept where `km` has them, alpha 255.
///
/// # Safety
/// The processor has AVX-512 F and BW.
#[target_feature(enable = "avx512f,avx512bw")]
#[inline]
pub(crate) unsafe fn mix_grey(
    (lm, km): (u32, u32),
    grey: [bool; 2],
    a: &[u32],
    b: &[u32],
    out: &mut [u32],
    px: impl Fn(u32) -> u32,
) {
    let (lm, km) = (_mm512_set1_epi32(lm as i32), _mm512_set1_epi32(km as i32));
    let alpha = _mm512_set1_epi32(ALPHA as i32);
    steps!(a, b, out, px, |l, r| {
        let l = if grey[0] { luma(l) } else { l };
        let r = if grey[1] { luma(r) } else { r };
        // lm ? l : r, bit by bit; then & km, | alpha.
        let rgb = _mm512_ternarylogic_epi32::<0xCA>(lm, l, r);
        _mm512_ternarylogic_epi32::<0xEA>(rgb, km, alpha)
    });
}

/// `a + f·(b − a)` of each channel of the rows `a` and `b`, rounded, alpha
/// 255: the reference's blend between two rows of an eye.
///
/// # Safety
/// The processor has AVX-512 F and BW; `f` is in [0, 1].
#[target_feature(enable = "avx512f,avx512bw")]
#[inline]
pub(crate) unsafe fn blend_rows(
    f: f32,
    a: &[u32],
    b: &[u32],
    out: &mut [u32],
    px: impl Fn(u32) -> u32,
) {
    debug_assert!((0.0..=1.0).contains(&f));
    let f = _mm512_set1_ps(f);
    steps!(a, b, out, px, |p, q| {
        let (p, q) = (channels(p), channels(q));
        pack([
            round(lerp(p[0], q[0], f)),
            round(lerp(p[1], q[1], f)),
            round(lerp(p[2], q[2], f)),
        ])
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::anaglyph::luma;
    use crate::output::cpu::tap;
    use crate::output::kernels::Simd;
    use crate::output::layout::str_rect_eye_rows;

    /// The reference's rounding.
    fn unorm(v: f32) -> u32 {
        u32::from(crate::output::cpu::unorm(v))
    }

    fn have_avx512() -> bool {
        let have = Simd::detected() >= Simd::Avx512;
        if !have {
            eprintln!("no AVX-512 here: nothing to check");
        }
        have
    }

    #[test]
    fn the_luminance_of_every_colour_is_the_references() {
        if !have_avx512() {
            return;
        }
        let y = |w: u32| unorm(luma([0, 8, 16].map(|s| (w >> s & 0xFF) as f32)));
        // Rows of 4099 colours (a partial last step), all 2²⁴ of them;
        // the left eye's luminance in R, the right eye's (the colour's
        // bytes reversed) in G and B.
        let colours: Vec<u32> = (0..1 << 24).map(|c| c | 0x5A00_0000).collect();
        let reversed: Vec<u32> = colours.iter().map(|c| c.swap_bytes() >> 8).collect();
        let mut out = vec![0; 4099];
        for (a, b) in colours.chunks(4099).zip(reversed.chunks(4099)) {
            let out = &mut out[..a.len()];
            // SAFETY: the processor has AVX-512 (checked above).
            unsafe { mix_grey((0xFF, 0x00FF_FFFF), [true, true], a, b, out, |v| v) };
            for ((&o, &p), &q) in out.iter().zip(a).zip(b) {
                let want = y(p) | (y(q) * 0x0001_0100) | ALPHA;
                assert_eq!(o, want, "colours {p:08x} and {q:08x}");
            }
        }
    }

    #[test]
    fn the_blend_of_every_pair_of_bytes_is_the_references() {
        if !have_avx512() {
            return;
        }
        // Every str-rect row's weight at three heights, and the ends.
        let mut weights = vec![0.0, 1.0, 0.5, f32::from_bits(1), 1.0 - f32::EPSILON / 2.0];
        for h in [1024, 768, 480] {
            let e = str_rect_eye_rows(h);
            weights.extend((0..e).map(|y| tap(y, h, e).f));
        }
        weights.sort_by(f32::total_cmp);
        weights.dedup();
        // Byte pairs (a, b) in R, (b, a) in G, (a, 255 − b) in B.
        let pairs = |i: u32| {
            let (a, b) = (i & 0xFF, i >> 8);
            (a | b << 8 | a << 16, b | a << 8 | (255 - b) << 16)
        };
        let (p, q): (Vec<u32>, Vec<u32>) = (0..1 << 16).map(pairs).unzip();
        let mut out = vec![0; p.len() - 5];
        for f in weights {
            let n = out.len();
            // SAFETY: the processor has AVX-512 (checked above); f in [0, 1].
            unsafe { blend_rows(f, &p[..n], &q[..n], &mut out, |v| v) };
            for ((&o, &p), &q) in out.iter().zip(&p).zip(&q) {
                let c = |w: u32, s: u32| (w >> s & 0xFF) as f32;
                let want = [0, 8, 16]
                    .map(|s| unorm(c(p, s) + f * (c(q, s) - c(p, s))) << s)
                    .iter()
                    .fold(ALPHA, |w, c| w | c);
                assert_eq!(o, want, "{p:08x} to {q:08x} at {f}");
            }
        }
    }

    #[test]
    fn a_window_byte_order_is_applied_to_every_length_of_row() {
        if !have_avx512() {
            return;
        }
        use crate::backend::PixelLayout;
        // Through a BGRX window's order, rows of 1…40 pixels (whole and
        // partial steps), the same words as through no order then the
        // window's conversion; and the words past the row untouched.
        let bgrx = |v| PixelLayout::Bgrx.convert(v);
        let a: Vec<u32> = (0..40u32).map(|i| i.wrapping_mul(0x9E37_79B9)).collect();
        let b: Vec<u32> = (0..40u32).map(|i| i.wrapping_mul(0x85EB_CA6B)).collect();
        for n in 1..=40 {
            let (mut plain, mut mixed, mut blended) = (vec![7; 41], vec![7; 41], vec![7; 41]);
            // SAFETY: the processor has AVX-512 (checked above).
            unsafe {
                mix_grey(
                    (0xFF, 0x00FF_FFFF),
                    [true, false],
                    &a[..n],
                    &b[..n],
                    &mut plain[..n],
                    |v| v,
                );
                mix_grey(
                    (0xFF, 0x00FF_FFFF),
                    [true, false],
                    &a[..n],
                    &b[..n],
                    &mut mixed[..n],
                    bgrx,
                );
            }
            for x in 0..41 {
                let want = if x < n { bgrx(plain[x]) } else { 7 };
                assert_eq!(mixed[x], want, "mix, {n} pixels, pixel {x}");
            }
            // SAFETY: as above; f in [0, 1].
            unsafe {
                blend_rows(0.25, &a[..n], &b[..n], &mut plain[..n], |v| v);
                blend_rows(0.25, &a[..n], &b[..n], &mut blended[..n], bgrx);
            }
            for x in 0..41 {
                let want = if x < n { bgrx(plain[x]) } else { 7 };
                assert_eq!(blended[x], want, "blend, {n} pixels, pixel {x}");
            }
        }
    }
}

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
use super::kernels::{ALPHA, N, VectorPx, ahead, ask_next_rows};

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

/// The mask of a step's first `m` (0…16) lanes.
#[inline(always)]
fn lanes(m: usize) -> __mmask16 {
    if m >= N { !0 } else { (1 << m) - 1 }
}

/// Stores the first `out.len()` (1…16) words of `v`: whole through `map`
/// where `px` is a byte map, else word by word through `px`.
#[target_feature(enable = "avx512f,avx512bw")]
#[inline]
fn put(v: __m512i, map: Option<&VectorPx>, out: &mut [u32], px: &impl Fn(u32) -> u32) {
    let m = out.len();
    debug_assert!((1..=N).contains(&m));
    let mask = lanes(m);
    if let Some(map) = map {
        // SAFETY: the mask covers the m words of out.
        unsafe { _mm512_mask_storeu_epi32(out.as_mut_ptr().cast(), mask, map.apply(v)) };
        return;
    }
    let mut words = [0u32; N];
    // SAFETY: 16 words into an array of 16.
    unsafe { _mm512_storeu_si512(words.as_mut_ptr().cast(), v) };
    if let Ok(o) = <&mut [u32; N]>::try_from(&mut *out) {
        // A whole step: a fixed-size loop, one vector store (a loop of
        // variable length would be a call to memcpy).
        for i in 0..N {
            o[i] = px(words[i]);
        }
    } else {
        for (o, &v) in out.iter_mut().zip(&words) {
            *o = px(v);
        }
    }
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
            let mask = lanes(m);
            // SAFETY: the mask covers m ≤ n − x words, all inside a and b
            // (masked-off words are not read).
            let ($l, $r) = unsafe {
                (
                    _mm512_maskz_loadu_epi32(mask, a[x..].as_ptr().cast()),
                    _mm512_maskz_loadu_epi32(mask, b[x..].as_ptr().cast()),
                )
            };
            put($f, map.as_ref(), &mut out[x..x + m], &$px);
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

/// Words 16·j … 16·j + 15 from `p`, of which the first `k` may be read
/// (the rest are zero).
///
/// # Safety
/// The `k` words from `p` are readable.
#[target_feature(enable = "avx512f")]
#[inline]
unsafe fn words(p: *const u32, k: usize, j: usize) -> __m512i {
    let mask = lanes(k.saturating_sub(N * j));
    // SAFETY: the mask covers the words of the k readable ones.
    unsafe { _mm512_maskz_loadu_epi32(mask, p.wrapping_add(N * j).cast()) }
}

/// The reference's bilinear sample of two rows of an eye (`r0`, `r1`:
/// rows i0 and i1 of the vertical tap, weight `fy` of `r1`) at the
/// horizontal taps `(i0, i1, fx)` of `out`'s pixels, 16 a step: each
/// pixel's two texels blended between the rows, then with each other,
/// clamped to 0…255 and rounded, alpha 255 — `rows::gather_store`'s
/// operations in its order, so its bytes. The texels of a step come by
/// two permutes a row from the 32 words at the step's first tap when all
/// its taps lie among them (any scale down to about 1:2, and every scale
/// up), or four permutes a row from the 64 words there (down to about
/// 1:4: HDMI frame packing fitted into its eye's window is 1:2.04), else
/// by gathers. Each step asks for a line of the `next` rows (the next
/// call's; [`ask_next_rows`]). Measured (perf samples, HDMI frame packing of 1280x1024 eyes fitted
/// into their window): the row loop with AVX2 gathers 2.24 ms a frame,
/// with this kernel 2.24 (1.5 → 1.17 ns a pixel on rows in cache: the
/// lines were the cost), with the next rows asked for 1.40.
///
/// # Safety
/// The processor has AVX-512 F and BW; every tap of the first
/// `out.len()` pixels indexes a texel of both rows.
#[target_feature(enable = "avx512f,avx512bw")]
#[inline]
pub(crate) unsafe fn sample_taps(
    (r0, r1, fy): (&[u32], &[u32], f32),
    (i0, i1, fx): (&[i32], &[i32], &[f32]),
    out: &mut [u32],
    next: [&[u32]; 2],
    px: impl Fn(u32) -> u32,
) {
    let n = out.len().min(i0.len()).min(i1.len()).min(fx.len());
    let len = r0.len().min(r1.len());
    debug_assert!(
        i0[..n]
            .iter()
            .chain(&i1[..n])
            .all(|&i| (0..len as i64).contains(&i64::from(i)))
    );
    let map = VectorPx::of(&px);
    let fy = _mm512_set1_ps(fy);
    let (zero, top) = (_mm512_setzero_ps(), _mm512_set1_ps(255.0));
    let mut x = 0;
    while x < n {
        let m = N.min(n - x);
        let mask = lanes(m);
        // SAFETY: the mask covers m ≤ n − x entries of each tap array.
        let (a, b, f) = unsafe {
            (
                _mm512_maskz_loadu_epi32(mask, i0[x..].as_ptr().cast()),
                _mm512_maskz_loadu_epi32(mask, i1[x..].as_ptr().cast()),
                _mm512_maskz_loadu_ps(mask, fx[x..].as_ptr()),
            )
        };
        // The taps as offsets from the step's first tap (unsigned: a tap
        // before it is out of range too).
        let base = i0[x] as usize;
        ahead([&r0[base..], &r1[base..]], &out[x..], 0);
        ask_next_rows(next, x / N);
        let from = _mm512_set1_epi32(base as i32);
        let (oa, ob) = (_mm512_sub_epi32(a, from), _mm512_sub_epi32(b, from));
        let (near, nearer) = (_mm512_set1_epi32(64), _mm512_set1_epi32(32));
        let within = |a: __mmask16, b: __mmask16| a == mask && b == mask;
        // [row 0 at i0, row 1 at i0, row 0 at i1, row 1 at i1].
        let w: [__m512i; 4] = if within(
            _mm512_mask_cmplt_epu32_mask(mask, oa, near),
            _mm512_mask_cmplt_epu32_mask(mask, ob, near),
        ) {
            // The words from base, 16 a register (none past the rows' end
            // read: no tap reaches them); base < len (a tap).
            let k = len - base;
            let (p0, p1) = (r0[base..].as_ptr(), r1[base..].as_ptr());
            // SAFETY: as above.
            let (a0, a1, b0, b1) = unsafe {
                (
                    words(p0, k, 0),
                    words(p0, k, 1),
                    words(p1, k, 0),
                    words(p1, k, 1),
                )
            };
            let mut w = [
                _mm512_permutex2var_epi32(a0, oa, a1),
                _mm512_permutex2var_epi32(b0, oa, b1),
                _mm512_permutex2var_epi32(a0, ob, a1),
                _mm512_permutex2var_epi32(b0, ob, b1),
            ];
            let (ha, hb) = (
                _mm512_cmpge_epu32_mask(oa, nearer),
                _mm512_cmpge_epu32_mask(ob, nearer),
            );
            if (ha | hb) & mask != 0 {
                // Offsets 32…63: from the next 32 words.
                // SAFETY: as above.
                let (a2, a3, b2, b3) = unsafe {
                    (
                        words(p0, k, 2),
                        words(p0, k, 3),
                        words(p1, k, 2),
                        words(p1, k, 3),
                    )
                };
                w = [
                    _mm512_mask_blend_epi32(ha, w[0], _mm512_permutex2var_epi32(a2, oa, a3)),
                    _mm512_mask_blend_epi32(ha, w[1], _mm512_permutex2var_epi32(b2, oa, b3)),
                    _mm512_mask_blend_epi32(hb, w[2], _mm512_permutex2var_epi32(a2, ob, a3)),
                    _mm512_mask_blend_epi32(hb, w[3], _mm512_permutex2var_epi32(b2, ob, b3)),
                ];
            }
            w
        } else {
            let none = _mm512_setzero_si512();
            let (p0, p1): (*const i32, *const i32) = (r0.as_ptr().cast(), r1.as_ptr().cast());
            // SAFETY: the lanes under the mask index texels of both rows
            // (contract); the others are not read.
            unsafe {
                [
                    _mm512_mask_i32gather_epi32::<4>(none, mask, a, p0),
                    _mm512_mask_i32gather_epi32::<4>(none, mask, a, p1),
                    _mm512_mask_i32gather_epi32::<4>(none, mask, b, p0),
                    _mm512_mask_i32gather_epi32::<4>(none, mask, b, p1),
                ]
            }
        };
        let c = [
            channels(w[0]),
            channels(w[1]),
            channels(w[2]),
            channels(w[3]),
        ];
        let mut v = [_mm512_setzero_si512(); 3];
        for (k, v) in v.iter_mut().enumerate() {
            let s = lerp(lerp(c[0][k], c[1][k], fy), lerp(c[2][k], c[3][k], fy), f);
            *v = round(_mm512_min_ps(_mm512_max_ps(s, zero), top));
        }
        put(pack(v), map.as_ref(), &mut out[x..x + m], &px);
        x += N;
    }
}

/// Each pair of words of `row` averaged into one of `out` (a composite
/// half as wide as its eye: `side-by-side-half`, `over-under-half`'s
/// columns): byte by byte, halves rounded up, alpha 255 — the
/// reference's `average2`, which is what `vpavgb` computes. 16 words of
/// `out` a step from 32 of `row`: the even and the odd words picked by
/// two permutes, averaged by one instruction. `out` is at most half as
/// long as `row`. (Bit operations on words: the hardware's prefetching
/// keeps up, [`super::kernels::AHEAD`].)
///
/// # Safety
/// The processor has AVX-512 F and BW.
#[target_feature(enable = "avx512f,avx512bw")]
#[inline]
pub(crate) unsafe fn halve_row(row: &[u32], out: &mut [u32], px: impl Fn(u32) -> u32) {
    let n = out.len().min(row.len() / 2);
    let map = VectorPx::of(&px);
    let even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    let odd = _mm512_add_epi32(even, _mm512_set1_epi32(1));
    let alpha = _mm512_set1_epi32(ALPHA as i32);
    let mut x = 0;
    while x < n {
        let m = N.min(n - x);
        // SAFETY: the masks cover the 2·m ≤ row.len() − 2·x words of
        // this step (masked-off words are not read; the second load's
        // address may lie past the row when its mask is empty).
        let (a, b) = unsafe {
            let at = row[2 * x..].as_ptr();
            (
                _mm512_maskz_loadu_epi32(lanes(2 * m), at.cast()),
                _mm512_maskz_loadu_epi32(
                    lanes((2 * m).saturating_sub(N)),
                    at.wrapping_add(N).cast(),
                ),
            )
        };
        let avg = _mm512_avg_epu8(
            _mm512_permutex2var_epi32(a, even, b),
            _mm512_permutex2var_epi32(a, odd, b),
        );
        put(
            _mm512_or_si512(avg, alpha),
            map.as_ref(),
            &mut out[x..x + m],
            &px,
        );
        x += N;
    }
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

    #[test]
    fn bilinear_taps_at_every_scale_are_the_references_and_write_only_their_pixels() {
        if !have_avx512() {
            return;
        }
        use crate::backend::PixelLayout;
        // Rows of 1…300 texels onto 1…200 pixels: scales up, down to
        // about 1:2 (the permutes) and further (the gathers), HDMI frame
        // packing's 1024/2091, whole and partial steps; weights between
        // the rows at the ends and inside; through no byte order, a
        // window's BGRX, and one that is not a byte map; words past the
        // row untouched.
        let bgrx = |v| PixelLayout::Bgrx.convert(v);
        let odd = |v: u32| v.rotate_left(4);
        let word = |i: u32, k: u32| i.wrapping_mul(0x9E37_79B9).wrapping_add(k) | ALPHA;
        let mut cases = vec![(2091, 1024), (1280, 627), (300, 200), (17, 33), (1, 5)];
        for src in [1, 2, 15, 16, 17, 31, 32, 33, 70, 300] {
            for dst in [1, 3, 8, 16, 17, 40, 45, 64, 99, 150, 200] {
                cases.push((src, dst));
            }
        }
        for (src, dst) in cases {
            let (r0, r1): (Vec<u32>, Vec<u32>) = (0..src).map(|i| (word(i, 1), word(i, 7))).unzip();
            let taps: Vec<_> = (0..dst).map(|i| tap(i, src, dst)).collect();
            let i0: Vec<i32> = taps.iter().map(|t| t.i0 as i32).collect();
            let i1: Vec<i32> = taps.iter().map(|t| t.i1 as i32).collect();
            let fx: Vec<f32> = taps.iter().map(|t| t.f).collect();
            for fy in [0.0, 0.3, 0.5, 1.0] {
                // The reference's operations, pixel by pixel.
                let c = |w: u32, k: u32| (w >> (8 * k) & 0xFF) as f32;
                let l = |p: f32, q: f32, f: f32| p + f * (q - p);
                let want: Vec<u32> = taps
                    .iter()
                    .map(|t| {
                        (0..3).fold(ALPHA, |w, k| {
                            let a = l(c(r0[t.i0], k), c(r1[t.i0], k), fy);
                            let b = l(c(r0[t.i1], k), c(r1[t.i1], k), fy);
                            w | unorm(l(a, b, t.f)) << (8 * k)
                        })
                    })
                    .collect();
                let n = dst as usize;
                let (mut plain, mut ordered, mut other) =
                    (vec![7; n + 1], vec![7; n + 1], vec![7; n + 1]);
                // SAFETY: the processor has AVX-512 (checked above); the
                // taps index texels of both rows.
                unsafe {
                    sample_taps(
                        (&r0, &r1, fy),
                        (&i0, &i1, &fx),
                        &mut plain[..n],
                        [&[], &[]],
                        |v| v,
                    );
                    sample_taps(
                        (&r0, &r1, fy),
                        (&i0, &i1, &fx),
                        &mut ordered[..n],
                        [&r1, &r0],
                        bgrx,
                    );
                    sample_taps(
                        (&r0, &r1, fy),
                        (&i0, &i1, &fx),
                        &mut other[..n],
                        [&[], &r0],
                        odd,
                    );
                }
                for x in 0..=n {
                    let what = |w: &dyn Fn(u32) -> u32| if x < n { w(want[x]) } else { 7 };
                    let at = format!("{src} texels onto {dst}, fy {fy}, pixel {x}");
                    assert_eq!(plain[x], what(&|v| v), "{at}");
                    assert_eq!(ordered[x], what(&bgrx), "{at}, BGRX");
                    assert_eq!(other[x], what(&odd), "{at}, rotated");
                }
            }
        }
    }
}

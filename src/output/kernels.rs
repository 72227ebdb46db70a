//! The pixel kernels of the composite: what one row of output pixels is
//! made of, given rows of the two eyes, as RGBA8 words (R in the low byte,
//! as [`crate::image::as_words`] reads an image on a little-endian machine).
//!
//! Every kernel computes exactly what [`super::cpu::reference`] computes,
//! byte for byte, with two exceptions, both within 1 unit of the
//! reference (see [`super::dubois_lut`]): `-dubois` of eyes changed by
//! saturation or crosstalk (whose channels are no longer whole numbers)
//! decodes sRGB by interpolating a table instead of calling `powf`; and
//! `-dubois` with AVX-512 computes in fixed point.
//!
//! Two kinds of kernels:
//!
//! - **Word kernels** for untouched eyes (no saturation, no crosstalk):
//!   copies, channel masks, interleaves and 2:1 averages are bit
//!   operations on whole pixels ([`average2`], [`average4`]): memory speed.
//! - **Float kernels** for everything else: [`N`] pixels at a time are
//!   unpacked into f32 planes ([`Planes`]), put through saturation and
//!   crosstalk ([`Stage`]) and the mode ([`PairOp`]) with the reference's
//!   operations in the reference's order, and packed with its rounding.
//!   Loops over fixed-size arrays, which the compiler turns into vector
//!   code; [`with_simd`] compiles them once more for AVX2 and once for
//!   AVX-512 and picks the copy at run time that the processor can run
//!   ([`Simd`]). The luminance anaglyphs and the blend between two rows
//!   have hand-written AVX-512 forms (`super::avx512`), the same
//!   operations.
//!
//! Output alpha is always 255 and input alpha is ignored; every word
//! written goes through the caller's `px` (a window's byte order).

use super::anaglyph::LUMA;
use super::dubois_lut::{Dubois, Memo};
use super::mode::{AnaglyphColors, AnaglyphMethod};

/// Alpha 255 and black, as an RGBA8 word.
pub(crate) const ALPHA: u32 = 0xFF00_0000;

/// Pixels per float kernel step.
pub(crate) const N: usize = 16;

/// The per-byte average of two RGBA8 words, halves rounded up:
/// ⌈(a + b)/2⌉ = (a | b) − ((a ^ b) >> 1), masked so no bit crosses bytes.
#[inline(always)]
pub(crate) fn average2(a: u32, b: u32) -> u32 {
    (a | b) - (((a ^ b) >> 1) & 0x7F7F_7F7F)
}

/// The per-byte average of four RGBA8 words, halves rounded up:
/// ⌊(a + b + c + d + 2)/4⌋, two bytes at a time in 16-bit lanes.
#[inline(always)]
pub(crate) fn average4(a: u32, b: u32, c: u32, d: u32) -> u32 {
    const LO: u32 = 0x00FF_00FF;
    let sum = |s: u32| (a >> s & LO) + (b >> s & LO) + (c >> s & LO) + (d >> s & LO) + 0x0002_0002;
    (sum(0) >> 2 & LO) | (sum(8) << 6 & !LO)
}

/// The reference's rounding of a value in 0…255 units: clamped, halves up
/// (NaN gives 0).
#[inline(always)]
pub(crate) fn unorm(v: f32) -> u32 {
    let v = if v > 0.0 { v } else { 0.0 };
    let v = if v < 255.0 { v } else { 255.0 };
    // SAFETY: 0.5 ≤ v + 0.5 ≤ 255.5, finite and in range. (A plain `as`
    // would saturate, which the compiler does one lane at a time.)
    unsafe { (v + 0.5).to_int_unchecked::<i32>() as u32 }
}

/// [`N`] pixels as f32 R, G, B planes in 0…255 units.
#[derive(Clone, Copy)]
pub(crate) struct Planes(pub(crate) [[f32; N]; 3]);

impl Planes {
    // (Plain loops: `array::from_fn` is not always inlined, and then costs
    // a call per element.)
    #[inline(always)]
    pub(crate) fn of(words: &[u32; N]) -> Planes {
        let mut p = Planes([[0.0; N]; 3]);
        for (c, plane) in p.0.iter_mut().enumerate() {
            for (v, w) in plane.iter_mut().zip(words) {
                *v = (w >> (8 * c) & 0xFF) as f32;
            }
        }
        p
    }

    /// [`super::anaglyph::luma`] of each pixel, in the same order.
    #[inline(always)]
    pub(crate) fn luma(&self) -> [f32; N] {
        let [r, g, b] = &self.0;
        let mut y = [0.0; N];
        for i in 0..N {
            y[i] = LUMA[0] * r[i] + LUMA[1] * g[i] + LUMA[2] * b[i];
        }
        y
    }

    /// The planes rounded into words, alpha 255.
    #[inline(always)]
    pub(crate) fn pack(&self) -> [u32; N] {
        let [r, g, b] = &self.0;
        let mut out = [0; N];
        for i in 0..N {
            out[i] = unorm(r[i]) | unorm(g[i]) << 8 | unorm(b[i]) << 16 | ALPHA;
        }
        out
    }
}

/// The per-eye colour steps before the mode, with their effective values
/// (1 and 0 where the mode ignores them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Stage {
    pub(crate) saturation: f32,
    pub(crate) crosstalk: f32,
}

impl Stage {
    pub(crate) fn is_identity(self) -> bool {
        self.saturation == 1.0 && self.crosstalk == 0.0
    }

    /// Saturation, then crosstalk, on two eyes' pixels at the same places.
    #[inline(always)]
    pub(crate) fn apply(self, l: &mut Planes, r: &mut Planes) {
        let s = self.saturation;
        if s != 1.0 {
            for p in [&mut *l, &mut *r] {
                let y = p.luma();
                for c in &mut p.0 {
                    for (v, y) in c.iter_mut().zip(y) {
                        *v = y + s * (*v - y);
                    }
                }
            }
        }
        let k = self.crosstalk;
        if k != 0.0 {
            for (a, b) in l.0.iter_mut().zip(&mut r.0) {
                for (x, y) in a.iter_mut().zip(b.iter_mut()) {
                    let (p, q) = (*x - k * *y, *y - k * *x);
                    *x = if p > 0.0 { p } else { 0.0 };
                    *y = if q > 0.0 { q } else { 0.0 };
                }
            }
        }
    }

    /// Crosstalk alone, for a row sampled as f32 RGBA pixels: `e − k·o`,
    /// clamped at 0 (the other eye's row unchanged).
    pub(crate) fn subtract(self, e: &mut [[f32; 4]], o: &[[f32; 4]]) {
        let k = self.crosstalk;
        for (e, o) in e.iter_mut().zip(o) {
            for c in 0..3 {
                let v = e[c] - k * o[c];
                e[c] = if v > 0.0 { v } else { 0.0 };
            }
        }
    }
}

/// What a pixel of the first and the second eye at the same place become.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PairOp {
    /// One of the two, by parity: the first eye where `x·columns + row`
    /// is even (`row`: 0 or 1, set per row), else the second. Left, right
    /// and frame-sequential pick always (columns false, row 0).
    Pick { columns: bool, row: u32 },
    /// Channel by channel from the first eye (`left`) or the second, each
    /// eye in colour or as its luminance (`grey`); channels not `kept` are
    /// 0 (red-blue has no green).
    Mix {
        left: [bool; 3],
        grey: [bool; 2],
        keep: [bool; 3],
    },
    /// Dubois' matrices in linear light.
    Dubois(Dubois),
}

impl PairOp {
    /// The op of an anaglyph mode.
    pub(crate) fn anaglyph(colors: AnaglyphColors, method: AnaglyphMethod) -> PairOp {
        match method {
            AnaglyphMethod::Dubois => PairOp::Dubois(Dubois::new(colors)),
            m => PairOp::Mix {
                left: colors.left_channels(),
                grey: [
                    m != AnaglyphMethod::FullColor,
                    m == AnaglyphMethod::Monochrome,
                ],
                keep: [true; 3],
            },
        }
    }

    /// `anaglyph-red-blue`: (Y(left), 0, Y(right)).
    pub(crate) const RED_BLUE: PairOp = PairOp::Mix {
        left: [true, false, false],
        grey: [true, true],
        keep: [true, false, true],
    };

    /// `out[x] = op(a[x], b[x])` along a row (the same length, x counted
    /// from column 0), each word through `px`; `simd` as [`with_simd`]
    /// passes it; `memo` as [`Dubois::row`] takes it.
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
        px: impl Fn(u32) -> u32 + Copy,
    ) {
        let plain = stage.is_identity();
        match *self {
            PairOp::Pick {
                columns: false,
                row,
            } if plain => {
                // The whole row from one eye: a copy, which reads one row
                // where the select below reads both.
                let src = if row == 0 { a } else { b };
                for (o, &p) in out.iter_mut().zip(src) {
                    *o = px(p | ALPHA);
                }
            }
            PairOp::Pick { columns, row } if plain => {
                // All ones where the second eye shows: a select the compiler vectorises.
                let odd = |x: usize| ((x as u32 & u32::from(columns)) ^ row).wrapping_neg();
                for (x, ((o, &p), &q)) in out.iter_mut().zip(a).zip(b).enumerate() {
                    *o = px((p & !odd(x)) | (q & odd(x)) | ALPHA);
                }
            }
            PairOp::Mix { left, grey, keep } if plain => {
                // Channel masks on words: each eye's word, or its luminance
                // in every byte.
                let m = |set: [bool; 3]| {
                    let b = set.map(|on| if on { 0xFF } else { 0 });
                    u32::from_le_bytes([b[0], b[1], b[2], 0])
                };
                let (lm, rm, km) = (m(left), m(left.map(|l| !l)), m(keep));
                if grey == [false, false] {
                    for ((o, &p), &q) in out.iter_mut().zip(a).zip(b) {
                        *o = px((p & lm) | (q & rm) | ALPHA);
                    }
                    return;
                }
                #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
                if simd.avx512() {
                    // SAFETY: `simd` says the processor has AVX-512 (see
                    // with_simd).
                    unsafe { super::avx512::mix_grey((lm, km), grey, a, b, out, px) };
                    return;
                }
                chunks(
                    a,
                    b,
                    out,
                    px,
                    #[inline(always)]
                    |l, r| {
                        let l = if grey[0] { grey_words(l) } else { *l };
                        let r = if grey[1] { grey_words(r) } else { *r };
                        let mut o = [0; N];
                        for i in 0..N {
                            o[i] = ((l[i] & lm) | (r[i] & rm)) & km | ALPHA;
                        }
                        o
                    },
                );
            }
            PairOp::Dubois(d) => d.row(simd, stage, memo, a, b, out, px),
            op => chunks(
                a,
                b,
                out,
                px,
                #[inline(always)]
                |l, r| {
                    let (mut l, mut r) = (Planes::of(l), Planes::of(r));
                    stage.apply(&mut l, &mut r);
                    op.planes(&l, &r)
                },
            ),
        }
    }

    /// The float form of Pick and Mix, on planes after the stage (lanes
    /// from an even column).
    #[inline(always)]
    fn planes(&self, l: &Planes, r: &Planes) -> [u32; N] {
        match *self {
            PairOp::Pick { columns, row } => {
                let (mut a, b) = (l.pack(), r.pack());
                for (i, (a, b)) in a.iter_mut().zip(b).enumerate() {
                    if (i as u32 & u32::from(columns)) ^ row != 0 {
                        *a = b;
                    }
                }
                a
            }
            PairOp::Mix { left, grey, keep } => {
                let (yl, yr) = (l.luma(), r.luma());
                let mut out = Planes([[0.0; N]; 3]);
                for (c, o) in out.0.iter_mut().enumerate() {
                    let (eye, y, g) = if left[c] {
                        (&l.0[c], &yl, grey[0])
                    } else {
                        (&r.0[c], &yr, grey[1])
                    };
                    if keep[c] {
                        *o = if g { *y } else { *eye };
                    }
                }
                out.pack()
            }
            PairOp::Dubois(_) => unreachable!("Dubois composes its own chunks"),
        }
    }
}

/// Each pixel's luminance, rounded, in R, G and B (alpha 0).
#[inline(always)]
fn grey_words(w: &[u32; N]) -> [u32; N] {
    let mut g = [0; N];
    for (g, &w) in g.iter_mut().zip(w) {
        let c = |s: u32| (w >> s & 0xFF) as f32;
        // Planes::luma's arithmetic.
        *g = unorm(LUMA[0] * c(0) + LUMA[1] * c(8) + LUMA[2] * c(16)) * 0x01_0101;
    }
    g
}

/// Runs `f` over [`N`]-pixel chunks of two rows into `out` (the last
/// chunk padded with black).
#[inline(always)]
pub(crate) fn chunks(
    a: &[u32],
    b: &[u32],
    out: &mut [u32],
    px: impl Fn(u32) -> u32,
    mut f: impl FnMut(&[u32; N], &[u32; N]) -> [u32; N],
) {
    let n = out.len();
    let whole = n - n % N;
    for (x, ((o, l), r)) in out[..whole]
        .chunks_exact_mut(N)
        .zip(a.chunks_exact(N))
        .zip(b.chunks_exact(N))
        .enumerate()
    {
        ahead([&a[N * x..], &b[N * x..]], o, 0);
        let l = l.try_into().expect("N words");
        let r = r.try_into().expect("N words");
        let o: &mut [u32; N] = o.try_into().expect("N words");
        for (o, v) in o.iter_mut().zip(f(l, r)) {
            *o = px(v);
        }
    }
    if whole < n {
        let (mut l, mut r) = ([0; N], [0; N]);
        l[..n - whole].copy_from_slice(&a[whole..n]);
        r[..n - whole].copy_from_slice(&b[whole..n]);
        for (o, v) in out[whole..].iter_mut().zip(f(&l, &r)) {
            *o = px(v);
        }
    }
}

/// How far ahead of a row's loop its cache lines are asked for, in
/// words (2 KiB). The eyes' rows and the composite are streams of
/// megabytes: asked for this early, a kernel with arithmetic to do no
/// longer waits for its reads and for its writes' cache lines (at
/// 1280x1024, -mono 2.06 -> 1.44–1.58 of a memcpy of its bytes, str-rect
/// 2.41 -> 1.8–1.9; benches/compose.rs, alternated runs). Loops of bit
/// operations on words go as fast as the hardware's own prefetching
/// takes them: asking there made them no faster, and top-bottom-half's
/// slower (1.7 -> 2.1–2.4), so they do not.
pub(crate) const AHEAD: usize = 512;

/// Asks for the cache lines [`AHEAD`] words past `x` of the rows `reads`
/// (to read) and `out` (to write). A hint: past a row's end it touches
/// whatever follows (the next row, usually), and never faults.
#[inline(always)]
pub(crate) fn ahead(reads: [&[u32]; 2], out: &[u32], x: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_ET0, _MM_HINT_T0, _mm_prefetch};
        let at = |row: &[u32]| row.as_ptr().wrapping_add(x + AHEAD).cast::<i8>();
        // SAFETY: a prefetch reads nothing and faults on no address.
        unsafe {
            _mm_prefetch::<_MM_HINT_T0>(at(reads[0]));
            if !std::ptr::eq(reads[0], reads[1]) {
                _mm_prefetch::<_MM_HINT_T0>(at(reads[1]));
            }
            _mm_prefetch::<_MM_HINT_ET0>(at(out));
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (reads, out, x);
}

/// Asks for line `line` (0, 1, …: 64 bytes each) of each of `next`'s rows
/// while it is within their first [`AHEAD`] words: a resampling loop
/// calls it once a step with the rows the next call will read, whose
/// first lines its own asking ([`ahead`]) never reaches — GL's eyes lie
/// bottom first, so past a row's end lies the row above, already read.
#[inline(always)]
pub(crate) fn ask_next_rows(next: [&[u32]; 2], line: usize) {
    let x = line * 16;
    if x >= AHEAD {
        return;
    }
    #[cfg(target_arch = "x86_64")]
    for row in next {
        if let Some(w) = row.get(x) {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            // SAFETY: a prefetch reads nothing and faults on no address.
            unsafe { _mm_prefetch::<_MM_HINT_T0>((w as *const u32).cast()) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = next;
}

/// A word map that is a byte map: output byte j is input byte `from[j]`,
/// or (None) a constant, OR-ed in from `or`. [`ByteMap::of`] finds it
/// from probes and checks it on more, so that a kernel can apply a
/// caller's `px` (a window's byte order) to whole registers.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernels'.
pub(crate) struct ByteMap {
    from: [Option<u8>; 4],
    or: u32,
}

#[cfg_attr(not(glstereo_avx512), allow(dead_code))] // The AVX-512 kernels'.
impl ByteMap {
    /// `px` as a byte map, if it is one on every probe.
    pub(crate) fn of(px: &impl Fn(u32) -> u32) -> Option<ByteMap> {
        let (a, b) = (px(0x0302_0100).to_le_bytes(), px(0x0706_0504).to_le_bytes());
        let mut map = ByteMap {
            from: [None; 4],
            or: 0,
        };
        for j in 0..4 {
            if a[j] < 4 && b[j] == a[j] + 4 {
                map.from[j] = Some(a[j]);
            } else if a[j] == b[j] {
                map.or |= u32::from(a[j]) << (8 * j);
            } else {
                return None;
            }
        }
        // Checked on four more words (every byte distinct, both ends of
        // the range): a kernel asks once per row, so this stays short.
        for w in [0xFFFE_FDFC, 0x8040_2010, 0x7F3F_1F0F, 0] {
            if px(w) != map.apply(w) {
                return None;
            }
        }
        Some(map)
    }

    fn apply(&self, w: u32) -> u32 {
        let b = w.to_le_bytes();
        let mut out = self.or;
        for (j, from) in self.from.iter().enumerate() {
            if let Some(f) = from {
                out |= u32::from(b[usize::from(*f)]) << (8 * j);
            }
        }
        out
    }

    /// Whether it leaves words of alpha 255 (every kernel's) as they are.
    fn is_identity(&self) -> bool {
        self.from[..3] == [Some(0), Some(1), Some(2)]
            && self.or & 0x00FF_FFFF == 0
            && matches!(self.from[3], Some(3) | None)
            && (self.from[3].is_some() || self.or >> 24 == 0xFF)
    }
}

/// A [`ByteMap`] on registers: a byte shuffle and an OR, or nothing.
#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
#[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
pub(crate) struct VectorPx {
    shuffle: std::arch::x86_64::__m512i,
    or: std::arch::x86_64::__m512i,
    identity: bool,
}

#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
#[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
impl VectorPx {
    /// `px` on registers, where it is a byte map (a kernel then writes its
    /// registers whole, not word by word through `px`: a store read back
    /// in words stalls on forwarding).
    #[target_feature(enable = "avx512f,avx512bw")]
    #[inline]
    pub(crate) fn of(px: &impl Fn(u32) -> u32) -> Option<VectorPx> {
        use std::arch::x86_64::*;
        let map = ByteMap::of(px)?;
        let mut ctrl = [0x80u8; 64];
        for (i, c) in ctrl.iter_mut().enumerate() {
            if let Some(b) = map.from[i % 4] {
                *c = (i & !3) as u8 + b;
            }
        }
        Some(VectorPx {
            // SAFETY: 64 bytes.
            shuffle: unsafe { _mm512_loadu_si512(ctrl.as_ptr().cast()) },
            or: _mm512_set1_epi32(map.or as i32),
            identity: map.is_identity(),
        })
    }

    /// The words of `v` (alpha 255) through the map.
    #[target_feature(enable = "avx512f,avx512bw")]
    #[inline]
    pub(crate) fn apply(&self, v: std::arch::x86_64::__m512i) -> std::arch::x86_64::__m512i {
        use std::arch::x86_64::*;
        if self.identity {
            return v;
        }
        _mm512_or_si512(_mm512_shuffle_epi8(v, self.shuffle), self.or)
    }
}

/// The vector instructions a kernel may use, from none to AVX-512 (the
/// subset glstereo uses: F, BW, VL, DQ, VBMI, VNNI, with AVX2 and FMA;
/// only where the compiler has them, Rust 1.89 on: `cfg(glstereo_avx512)`).
/// Ordered: a level has everything the levels below it have.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Simd {
    Scalar,
    Avx2,
    Avx512,
}

impl Simd {
    /// Every level, lowest first.
    #[cfg(test)]
    pub(crate) const ALL: [Simd; 3] = [Simd::Scalar, Simd::Avx2, Simd::Avx512];

    /// The highest level this processor has (std caches the checks).
    pub(crate) fn detected() -> Simd {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            #[cfg(glstereo_avx512)]
            #[allow(clippy::incompatible_msrv)]
            // Only compiled with Rust ≥ 1.89 (build.rs).
            if has!("avx2")
                && has!("fma")
                && has!("avx512f")
                && has!("avx512bw")
                && has!("avx512vl")
                && has!("avx512dq")
                && has!("avx512vbmi")
                && has!("avx512vnni")
            {
                return Simd::Avx512;
            }
            if has!("avx2") {
                return Simd::Avx2;
            }
        }
        Simd::Scalar
    }

    /// Whether AVX2 may be used.
    #[inline(always)]
    pub(crate) fn avx2(self) -> bool {
        self >= Simd::Avx2
    }

    /// Whether AVX-512 (the subset above) may be used.
    #[inline(always)]
    pub(crate) fn avx512(self) -> bool {
        self >= Simd::Avx512
    }
}

/// Runs `f` with vector code for this processor: `f` compiled for
/// AVX-512 or AVX2 where the processor has them (checked once, cached by
/// std), else for the baseline, and told which ([`Simd`]); `max` caps the
/// level (tests force each level with it). `f` must be `#[inline(always)]`
/// all the way down for the copies to be vector code.
#[inline(always)]
pub(crate) fn with_simd<T>(max: Simd, f: impl FnOnce(Simd) -> T) -> T {
    #[cfg(target_arch = "x86_64")]
    match max.min(Simd::detected()) {
        #[cfg(glstereo_avx512)]
        Simd::Avx512 => {
            #[target_feature(
                enable = "avx2,fma,avx512f,avx512bw,avx512vl,avx512dq,avx512vbmi,avx512vnni"
            )]
            fn avx512<T>(f: impl FnOnce(Simd) -> T) -> T {
                f(Simd::Avx512)
            }
            // SAFETY: the processor has these features (Simd::detected).
            return unsafe { avx512(f) };
        }
        Simd::Avx2 => {
            #[target_feature(enable = "avx2")]
            fn avx2<T>(f: impl FnOnce(Simd) -> T) -> T {
                f(Simd::Avx2)
            }
            // SAFETY: the processor has AVX2 (Simd::detected).
            return unsafe { avx2(f) };
        }
        _ => {}
    }
    let _ = max;
    f(Simd::Scalar)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_byte_orders_are_byte_maps_and_other_maps_are_not() {
        use crate::backend::PixelLayout;
        let id = ByteMap::of(&|v| v).expect("identity");
        assert!(id.is_identity());
        let rgbx = ByteMap::of(&|v| PixelLayout::Rgbx.convert(v)).expect("Rgbx");
        assert!(rgbx.is_identity(), "{rgbx:?}");
        let bgrx = ByteMap::of(&|v| PixelLayout::Bgrx.convert(v)).expect("Bgrx");
        assert!(!bgrx.is_identity());
        for w in [0u32, 0x0102_0304, 0xFFEE_DDCC, 0x8040_2010] {
            assert_eq!(bgrx.apply(w), PixelLayout::Bgrx.convert(w));
            assert_eq!(rgbx.apply(w), PixelLayout::Rgbx.convert(w));
        }
        // Not byte maps: arithmetic, bit rotations, a map right on the
        // two first probes only.
        assert_eq!(ByteMap::of(&|v: u32| v.wrapping_add(1)), None);
        assert_eq!(ByteMap::of(&|v: u32| v.rotate_left(4)), None);
        assert_eq!(
            ByteMap::of(&|v: u32| if v == 0x0302_0100 || v == 0x0706_0504 {
                v
            } else {
                !v
            }),
            None
        );
    }

    #[test]
    fn averages_round_each_byte_half_up() {
        for a in (0..=255u32).step_by(3) {
            for b in 0..=255u32 {
                let want = (a + b).div_ceil(2);
                let (x, y) = (a * 0x0101_0101, b * 0x0101_0101);
                assert_eq!(average2(x, y), want * 0x0101_0101, "bytes {a} and {b}");
                let (x, y) = (a << 8 | 0xFF, b << 8);
                assert_eq!(average2(x, y), want << 8 | 0x80, "lane 1 with {a}, {b}");
                for (c, d) in [(0, 0), (255, 255), (a, 255 - b), (7, 200)] {
                    let want = (a + b + c + d + 2) / 4;
                    let w = |v: u32| v * 0x0101_0101;
                    assert_eq!(
                        average4(w(a), w(b), w(c), w(d)),
                        w(want),
                        "bytes {a} {b} {c} {d}"
                    );
                }
            }
        }
    }

    #[test]
    fn unorm_is_the_references_rounding() {
        // The reference's own rules are tested in cpu.rs; here the fast
        // form must give its bytes for every value a kernel can meet.
        let mut v = -8.0f32;
        while v <= 300.0 {
            assert_eq!(unorm(v), u32::from(crate::output::cpu::unorm(v)), "{v}");
            v += 1.0 / 64.0;
        }
        for v in [
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            254.5,
            254.499_98,
        ] {
            assert_eq!(unorm(v), u32::from(crate::output::cpu::unorm(v)), "{v}");
        }
    }
}

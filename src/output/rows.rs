//! The composite of every mode, row by row, straight from the eyes into
//! wherever it goes: an [`Image`] ([`super::cpu::compose_into`]), or a
//! window's buffer at the window's size ([`super::window`]), letterboxed,
//! scaled or cropped by [`super::layout::window_fit`] in the same pass.
//!
//! The eyes are rows wherever they are ([`EyeRows`]): an image (top row
//! first), an eye texture mapped in place or a band of rows read back
//! (GL's order, bottom row first). A window row is made from the rows of
//! the composite it shows, and each composite row from the rows of the
//! eyes it shows:
//!
//! - **pair modes** (left, right, frame-sequential, the anaglyphs, the
//!   interleaves): composite row y from row y of both eyes, pixel by pixel
//!   ([`PairOp`]);
//! - **placement modes** (side-by-side, top-bottom, their halves, HDMI
//!   frame packing, starbase, str-rect): each eye sampled into its
//!   rectangle ([`super::layout::placements`]): copied, averaged 2:1 (whole
//!   pixels, exact), or filtered bilinearly in f32 as the reference does;
//!   black where no eye goes.
//!
//! A window of the composite's size gets the composite rows written
//! straight into it. Otherwise the rows a window row needs are composed
//! into reused row buffers and resampled as the reference's
//! [`super::cpu::resample`] does (2:1 in both directions: [`average4`],
//! exact). Every word goes through the caller's `px` (a window's byte
//! order). The result is byte for byte [`super::cpu::reference`] (and its
//! resampling), but for `-dubois` of eyes changed by saturation or
//! crosstalk, or with AVX-512 (within 1, see [`super::dubois_lut`]).

use std::ops::Range;

use crate::image::{Image, as_words};
use crate::math::Eye;
use crate::stereo::eye_memory::Rows;

use super::cpu::{Tap, tap};
use super::dubois_lut::Memo;
use super::kernels::{
    ALPHA, PairOp, Planes, Simd, Stage, ask_next_rows, average2, average4, chunks, with_simd,
};
use super::layout::{Placement, WindowFit, composite_size, placements, window_fit};
use super::mode::OutputMode;
use super::options::OutputOptions;

/// One eye's rows, as RGBA8 words.
#[derive(Clone, Copy)]
pub(crate) struct EyeRows<'a> {
    rows: Rows<'a>,
    /// GL's order: stored row k is eye row `height − 1 − first − k`.
    bottom_first: bool,
    /// The first stored row's index in its order.
    first: u32,
    /// The eye's height.
    height: u32,
}

impl<'a> EyeRows<'a> {
    /// An image's rows (top first); None where they are not aligned words.
    pub(crate) fn image(img: &'a Image) -> Option<EyeRows<'a>> {
        EyeRows::new(Rows::of_image(img), false, 0, img.height())
    }

    /// Rows in GL's order of an eye `height` rows high, the first of them
    /// GL row `first` (a band, or 0 for the whole eye); None where they are
    /// not aligned words.
    pub(crate) fn gl(rows: Rows<'a>, first: u32, height: u32) -> Option<EyeRows<'a>> {
        EyeRows::new(rows, true, first, height)
    }

    fn new(rows: Rows<'a>, bottom_first: bool, first: u32, height: u32) -> Option<EyeRows<'a>> {
        // Rows are evenly spaced: two aligned rows make them all aligned.
        let aligned = (0..rows.height().min(2)).all(|k| as_words(rows.row(k)).is_some());
        (aligned && rows.height() > 0).then_some(EyeRows {
            rows,
            bottom_first,
            first,
            height,
        })
    }

    /// Eye row `y` (0 = top), which must be stored here.
    #[inline(always)]
    fn row(&self, y: u32) -> &'a [u32] {
        let k = if self.bottom_first {
            self.height - 1 - y - self.first
        } else {
            y - self.first
        };
        as_words(self.rows.row(k)).expect("aligned rows (checked when made)")
    }

    /// Eye rows `y`…`y + n − 1` as one run of words, where they are
    /// stored top first with no gap between them.
    fn span(&self, y: u32, n: u32) -> Option<&'a [u32]> {
        if self.bottom_first {
            return None;
        }
        as_words(self.rows.span(y.checked_sub(self.first)?, n)?)
    }

    /// The rows a vertical tap reads: the second only when it weighs (a
    /// band may not hold it), else the first twice.
    #[inline(always)]
    fn tap_rows(&self, vt: &Tap) -> (&'a [u32], &'a [u32]) {
        let r0 = self.row(vt.i0 as u32);
        let one = vt.f == 0.0 || vt.i0 == vt.i1;
        (r0, if one { r0 } else { self.row(vt.i1 as u32) })
    }
}

/// Eyes that are made as the composite reads them, row by row, instead
/// of being read from where they are (`--auto=depth`: both eyes made from
/// one frame and its depth, [`crate::auto::from_depth`]): a composite
/// that needs only eye row y for its row y (a row-local composite) gets
/// them a few rows at a time into buffers that stay in cache, so the
/// eyes are never written out to memory and read in again.
pub trait MakeEyes: Sync {
    /// The eyes' size.
    fn size(&self) -> (u32, u32);

    /// Makes row `y` (GL's order: 0 is the bottom row) of the left and
    /// right eye into `out` (each the eyes' width), with the buffers of
    /// `band` (0 or 1: each used by one thread at a time).
    fn row(&self, band: usize, y: u32, out: [&mut [u32]; 2]);

    /// Makes every row of both eyes where the eyes are, for a composite
    /// (or a capture) that reads them there. Once: later calls do
    /// nothing.
    fn in_place(&self);
}

/// Bytes of each eye made at a time by [`Frame::write_made`]: both eyes'
/// rows stay in the first-level cache until they are composed.
const MADE_BYTES: usize = 16 * 1024;

/// The target pixels from which [`Frame::write_split`] composes in two
/// threads.
pub(crate) const SPLIT_PIXELS: u64 = 1 << 16;

/// Rows of RGBA8 words to write into (an image or a window's buffer).
pub(crate) struct Target<'a> {
    pub(crate) words: &'a mut [u32],
    /// Words from one row to the next.
    pub(crate) stride: usize,
    pub(crate) size: (u32, u32),
    /// The row `words` starts at: 0, but for the lower band of a split
    /// write ([`Frame::write_split`]).
    pub(crate) first: u32,
}

impl Target<'_> {
    /// The rows above `mid` and those from it on, as two targets (of a
    /// target whose first row is 0).
    fn split(&mut self, mid: u32) -> (Target<'_>, Target<'_>) {
        debug_assert_eq!(self.first, 0);
        let (stride, size) = (self.stride, self.size);
        let (upper, lower) = self.words.split_at_mut(mid as usize * stride);
        let part = |words, first| Target {
            words,
            stride,
            size,
            first,
        };
        (part(upper, 0), part(lower, mid))
    }

    fn row(&mut self, y: u32) -> &mut [u32] {
        let at = (y - self.first) as usize * self.stride;
        &mut self.words[at..at + self.size.0 as usize]
    }
}

/// Buffers reused from frame to frame (nothing is allocated once they
/// have grown to a frame's size).
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    a: Vec<[f32; 4]>,
    b: Vec<[f32; 4]>,
    tmp: Vec<[f32; 4]>,
    /// Horizontal taps of spans and of the window's scaling, by key.
    span_taps: TapCache,
    window_taps: TapCache,
    /// Composite rows a scaled or cropped window samples (row index, words),
    /// kept within one [`Frame::write`] call.
    rows: [(Option<u32>, Vec<u32>); 2],
    /// A black composite row.
    black: Vec<u32>,
    /// The last pixels `-dubois` composed (cleared by every [`Frame::write`]).
    memo: Memo,
    /// Eye rows made by [`Frame::write_made`], top first.
    made: [Vec<u32>; 2],
}

/// A composite row that need not be composed (see [`Frame::verbatim`]).
#[derive(Clone, Copy)]
enum Verbatim<'e> {
    Row(&'e [u32]),
    Black,
}

/// A composite row: `v` when it need not be composed, else the cache's
/// slot `s`.
#[inline(always)]
fn row_of<'a>(
    v: Option<Verbatim<'a>>,
    s: Option<usize>,
    black: &'a [u32],
    cache: &'a [(Option<u32>, Vec<u32>); 2],
) -> &'a [u32] {
    match v {
        Some(Verbatim::Row(r)) => r,
        Some(Verbatim::Black) => black,
        None => &cache[s.expect("composed")].1,
    }
}

/// The taps of `dst` pixels over `src` texels, kept while they stay the
/// same; also as arrays of texel indices and weights, for gathers.
#[derive(Debug, Default)]
struct TapCache {
    key: (u32, u32),
    taps: Vec<Tap>,
    i0: Vec<i32>,
    i1: Vec<i32>,
    f: Vec<f32>,
}

impl TapCache {
    fn get(&mut self, src: u32, dst: u32) -> &TapCache {
        if self.key != (src, dst) || self.taps.len() != dst as usize {
            self.taps.clear();
            self.taps.extend((0..dst).map(|i| tap(i, src, dst)));
            self.i0.clear();
            self.i0.extend(self.taps.iter().map(|t| t.i0 as i32));
            self.i1.clear();
            self.i1.extend(self.taps.iter().map(|t| t.i1 as i32));
            self.f.clear();
            self.f.extend(self.taps.iter().map(|t| t.f));
            self.key = (src, dst);
        }
        self
    }
}

/// Where composite rows come from.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// Row y of eyes `eyes[0]` and `eyes[1]` (indices into the delivered
    /// pair) through `op`; with `row_parity`, Pick's row parity is y's.
    Pair {
        op: PairOp,
        eyes: [usize; 2],
        row_parity: bool,
    },
    /// Each placement from eye `index` (crosstalk against the other).
    Places([(Placement, usize); 2]),
}

/// One frame of a mode, as it goes into a target of some size.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    source: Source,
    stage: Stage,
    eye: (u32, u32),
    composite: (u32, u32),
    target: (u32, u32),
    fit: WindowFit,
}

impl Frame {
    /// The frame of `mode` (not `quad`) with validated `options` for eyes
    /// of `eye` size, into a target of `target` size; `frame_index` as in
    /// [`super::cpu::compose`].
    pub(crate) fn new(
        mode: OutputMode,
        options: &OutputOptions,
        frame_index: u64,
        eye: (u32, u32),
        target: (u32, u32),
    ) -> Frame {
        let (w, h) = eye;
        let composite = composite_size(mode, w, h);
        // Eye indices after the swap: the left eye shown is delivered eye `l`.
        let (l, r) = if options.swap_eyes { (1, 0) } else { (0, 1) };
        let stage = Stage {
            saturation: if mode.is_anaglyph() {
                options.saturation
            } else {
                1.0
            },
            crosstalk: if mode.shows_both_eyes() {
                options.crosstalk
            } else {
                0.0
            },
        };
        let pick = |columns| PairOp::Pick { columns, row: 0 };
        let pair = |op, eyes, row_parity| Source::Pair {
            op,
            eyes,
            row_parity,
        };
        let source = match mode {
            OutputMode::Quad | OutputMode::Left => pair(pick(false), [l, l], false),
            OutputMode::Right => pair(pick(false), [r, r], false),
            OutputMode::FrameSequential => {
                // The eye accounts for the swap: index the delivered eyes.
                let shown = usize::from(options.frame_sequential_eye(frame_index) == Eye::Right);
                let other = if stage.crosstalk == 0.0 {
                    shown
                } else {
                    1 - shown
                };
                pair(pick(false), [shown, other], false)
            }
            OutputMode::Anaglyph(colors, method) => {
                pair(PairOp::anaglyph(colors, method), [l, r], false)
            }
            OutputMode::AnaglyphRedBlue => pair(PairOp::RED_BLUE, [l, r], false),
            OutputMode::Rows => pair(pick(false), [l, r], true),
            OutputMode::Columns => pair(pick(true), [l, r], false),
            OutputMode::Checkerboard => pair(pick(true), [l, r], true),
            _ => {
                let places = placements(mode, w, h).expect("a placement mode");
                Source::Places(places.map(|p| (p, if p.eye == Eye::Left { l } else { r })))
            }
        };
        Frame {
            source,
            stage,
            eye,
            composite,
            target,
            fit: window_fit(mode, composite.0, composite.1, target.0, target.1),
        }
    }

    /// Which of the delivered eyes (left, right) the frame reads.
    pub(crate) fn reads(&self) -> [bool; 2] {
        let mut reads = [false; 2];
        match self.source {
            Source::Pair { eyes, .. } => eyes.iter().for_each(|&i| reads[i] = true),
            Source::Places(places) => {
                for (p, i) in places {
                    if p.width > 0 && p.height > 0 {
                        reads[i] = true;
                        reads[1 - i] |= self.stage.crosstalk != 0.0;
                    }
                }
            }
        }
        reads
    }

    /// Whether target row y needs only eye row y: the target is the
    /// composite's size and no eye is scaled vertically. Such frames can be
    /// made from bands of eye rows.
    pub(crate) fn row_local(&self) -> bool {
        let vertical = match self.source {
            Source::Pair { .. } => true,
            Source::Places(places) => places
                .iter()
                .all(|(p, _)| p.height == self.eye.1 && p.y == 0),
        };
        vertical && self.composite == self.target
    }

    /// The target rows that eye rows `gl` (GL's order, bottom first) make
    /// in a [`Frame::row_local`] frame.
    pub(crate) fn rows_of_band(&self, gl: Range<u32>) -> Range<u32> {
        let h = self.eye.1;
        h - gl.end.min(h)..h - gl.start.min(h)
    }

    /// Writes target rows `rows` from `eyes` (the delivered left and right
    /// eye; those [`Frame::reads`] must be Some and hold the rows needed),
    /// each word through `px`.
    pub(crate) fn write(
        &self,
        eyes: [Option<EyeRows<'_>>; 2],
        rows: Range<u32>,
        target: &mut Target<'_>,
        scratch: &mut Scratch,
        px: impl Fn(u32) -> u32 + Copy,
    ) {
        self.write_with(Simd::Avx512, eyes, rows, target, scratch, px)
    }

    /// [`Frame::write`] of the rows `rows` of a whole target (`first` 0)
    /// in two bands at once: the lower on the layer's helper thread
    /// ([`super::helper`]), the upper on this one, each with its own
    /// scratch. A window's frame is composed after the renderer finished
    /// it, when its threads are idle: two cores compose it in about half
    /// the time. The bytes are [`Frame::write`]'s (each row is made from
    /// the eyes alone). Targets below [`SPLIT_PIXELS`] are written here
    /// alone (handing work over costs microseconds), and so is the lower
    /// band where the helper is busy with another thread's frame, cannot
    /// be made, or did not finish. True where two threads wrote it.
    pub(crate) fn write_split(
        &self,
        eyes: [Option<EyeRows<'_>>; 2],
        rows: Range<u32>,
        target: &mut Target<'_>,
        scratch: &mut [Scratch; 2],
        px: impl Fn(u32) -> u32 + Copy + Send + Sync,
    ) -> bool {
        self.write_split_with(Simd::Avx512, eyes, rows, target, scratch, px)
    }

    /// [`Frame::write_split`] with vector code of level `max` at most.
    pub(crate) fn write_split_with(
        &self,
        max: Simd,
        eyes: [Option<EyeRows<'_>>; 2],
        rows: Range<u32>,
        target: &mut Target<'_>,
        scratch: &mut [Scratch; 2],
        px: impl Fn(u32) -> u32 + Copy + Send + Sync,
    ) -> bool {
        let n = rows.end.saturating_sub(rows.start);
        let size = target.size;
        if n < 2
            || u64::from(n) * u64::from(size.0) < SPLIT_PIXELS
            || target.first != 0
            || rows.end > size.1
        {
            self.write_with(max, eyes, rows, target, &mut scratch[0], px);
            return false;
        }
        let mid = rows.start + n / 2;
        let [upper_scratch, lower_scratch] = scratch;
        let (mut upper, mut lower) = target.split(mid);
        let end = rows.end;
        let done = super::helper::both(
            || self.write_with(max, eyes, rows.start..mid, &mut upper, upper_scratch, px),
            &mut || self.write_with(max, eyes, mid..end, &mut lower, lower_scratch, px),
        );
        if !done {
            self.write_with(max, eyes, mid..end, &mut lower, lower_scratch, px);
        }
        done
    }

    /// [`Frame::write_split`] of the whole target of a
    /// [`Frame::row_local`] frame from eyes made as they are read
    /// ([`MakeEyes`]): each band's eye rows made a few at a time into
    /// buffers of its scratch, then composed. The bytes are those of
    /// [`Frame::write`] from eyes made whole first. False (nothing
    /// written) where the frame is not row-local or `made` is not of the
    /// frame's eye size.
    pub(crate) fn write_split_made(
        &self,
        max: Simd,
        made: &dyn MakeEyes,
        target: &mut Target<'_>,
        scratch: &mut [Scratch; 2],
        px: impl Fn(u32) -> u32 + Copy + Send + Sync,
    ) -> bool {
        let size = target.size;
        if !self.row_local() || made.size() != self.eye || target.first != 0 || size != self.target
        {
            return false;
        }
        let n = size.1;
        let [upper_scratch, lower_scratch] = scratch;
        if n < 2 || u64::from(n) * u64::from(size.0) < SPLIT_PIXELS {
            self.write_made(max, made, 0, 0..n, target, upper_scratch, px);
            return true;
        }
        let mid = n / 2;
        let (mut upper, mut lower) = target.split(mid);
        let done = super::helper::both(
            || self.write_made(max, made, 0, 0..mid, &mut upper, upper_scratch, px),
            &mut || self.write_made(max, made, 1, mid..n, &mut lower, lower_scratch, px),
        );
        if !done {
            self.write_made(max, made, 0, mid..n, &mut lower, lower_scratch, px);
        }
        true
    }

    /// Target rows `rows` of a row-local frame from eyes made by `made`
    /// with its buffers of `band`, [`MADE_BYTES`] of each eye at a time.
    #[allow(clippy::too_many_arguments)]
    fn write_made(
        &self,
        max: Simd,
        made: &dyn MakeEyes,
        band: usize,
        rows: Range<u32>,
        target: &mut Target<'_>,
        scratch: &mut Scratch,
        px: impl Fn(u32) -> u32 + Copy,
    ) {
        let (w, h) = self.eye;
        let wide = w as usize;
        let chunk = (MADE_BYTES / (wide * 4)).clamp(1, h as usize) as u32;
        let mut bufs = std::mem::take(&mut scratch.made);
        for b in &mut bufs {
            b.resize(chunk as usize * wide, 0);
        }
        let mut t0 = rows.start;
        while t0 < rows.end {
            let n = chunk.min(rows.end - t0);
            let [l, r] = &mut bufs;
            for (k, (l, r)) in l
                .chunks_exact_mut(wide)
                .zip(r.chunks_exact_mut(wide))
                .take(n as usize)
                .enumerate()
            {
                // Target row t0 + k is eye row t0 + k (row-local), GL row
                // h − 1 − (t0 + k); stored top first.
                made.row(band, h - 1 - (t0 + k as u32), [l, r]);
            }
            let eyes = [&bufs[0], &bufs[1]].map(|b| {
                EyeRows::new(
                    Rows::of_words(&b[..n as usize * wide], wide, n),
                    false,
                    t0,
                    h,
                )
            });
            self.write_with(max, eyes, t0..t0 + n, target, scratch, px);
            t0 += n;
        }
        scratch.made = bufs;
    }

    /// [`Frame::write`] with vector code of level `max` at most (tests
    /// check every level with it).
    pub(crate) fn write_with(
        &self,
        max: Simd,
        eyes: [Option<EyeRows<'_>>; 2],
        rows: Range<u32>,
        target: &mut Target<'_>,
        scratch: &mut Scratch,
        px: impl Fn(u32) -> u32 + Copy,
    ) {
        // Rows composed for an earlier call are of another frame (other
        // eyes, perhaps another size): never reused.
        scratch.memo = Memo::default();
        for (row, _) in &mut scratch.rows {
            *row = None;
        }
        with_simd(
            max,
            #[inline(always)]
            |simd| self.write_rows(simd, eyes, rows, target, scratch, px),
        )
    }

    #[inline(always)]
    fn write_rows(
        &self,
        simd: Simd,
        eyes: [Option<EyeRows<'_>>; 2],
        rows: Range<u32>,
        target: &mut Target<'_>,
        scratch: &mut Scratch,
        px: impl Fn(u32) -> u32 + Copy,
    ) {
        let (cw, ch) = self.composite;
        let (tw, _) = self.target;
        let fit = self.fit;
        let black_px = px(ALPHA);
        let scaled = (fit.width, fit.height) != (cw, ch);
        let ty = |t: u32| i64::from(t) - i64::from(fit.y);
        let end = rows.end;
        let mut ts = rows;
        while let Some(t) = ts.next() {
            let y = ty(t);
            if y < 0 || y >= i64::from(fit.height) {
                target.row(t).fill(black_px);
                continue;
            }
            let y = y as u32;
            if !scaled && fit.x == 0 && cw == tw {
                if let Some(n) = self.fused_rows(simd, eyes, y, t, end, target, scratch, px) {
                    ts = t + n..end;
                    continue;
                }
                self.composite_row(simd, eyes, y, target.row(t), scratch, px);
                continue;
            }
            if !scaled {
                // Cropped or centred, pixel for pixel.
                let slot = self.cached_row(simd, eyes, y, scratch);
                let line = &scratch.rows[slot].1;
                let out = target.row(t);
                out.fill(black_px);
                let x0 = fit.x.max(0) as usize;
                let skip = (-fit.x).max(0) as usize;
                let n = (cw as usize - skip).min(tw as usize - x0);
                for (o, &v) in out[x0..x0 + n].iter_mut().zip(&line[skip..skip + n]) {
                    *o = px(v);
                }
                continue;
            }
            // Scaled: the composite rows of this row's tap, resampled.
            let vt = tap(y, ch, fit.height);
            let (i0, i1) = (vt.i0 as u32, vt.i1 as u32);
            let (v0, v1) = (self.verbatim(eyes, i0), self.verbatim(eyes, i1));
            // (No closures around the composing: they would not be
            // inlined into the vector code.)
            let s0 = if v0.is_none() {
                Some(self.cached_row(simd, eyes, i0, scratch))
            } else {
                None
            };
            let s1 = if v1.is_none() {
                Some(self.cached_row_besides(simd, eyes, i1, s0.unwrap_or(0), scratch))
            } else {
                None
            };
            if scratch.black.len() != cw as usize {
                scratch.black.clear();
                scratch.black.resize(cw as usize, ALPHA);
            }
            let Scratch {
                rows: cache,
                black,
                a,
                tmp,
                window_taps,
                ..
            } = scratch;
            let (r0, r1) = (row_of(v0, s0, black, cache), row_of(v1, s1, black, cache));
            let (x0, n) = (fit.x as usize, fit.width as usize);
            let out = target.row(t);
            out[..x0].fill(black_px);
            out[x0 + n..].fill(black_px);
            let out = &mut out[x0..x0 + n];
            if 2 * fit.width == cw && 2 * fit.height == ch {
                for ((o, a), b) in out
                    .iter_mut()
                    .zip(r0.chunks_exact(2))
                    .zip(r1.chunks_exact(2))
                {
                    *o = px(average4(a[0], a[1], b[0], b[1]) | ALPHA);
                }
            } else if fit.width == cw {
                sample(r0, r1, vt.f, None, tmp, a);
                store(a, out, px);
            } else {
                // The next window row's eye rows, asked for while this one
                // is made (see kernels::ask_next_rows).
                let mut next: [&[u32]; 2] = [&[], &[]];
                if y + 1 < fit.height {
                    let t = tap(y + 1, ch, fit.height);
                    for (n, i) in next.iter_mut().zip([t.i0, t.i1]) {
                        if let Some(Verbatim::Row(row)) = self.verbatim(eyes, i as u32) {
                            *n = row;
                        }
                    }
                }
                sample_store(
                    simd,
                    (r0, r1, vt.f),
                    window_taps.get(cw, fit.width),
                    out,
                    next,
                    px,
                );
            }
        }
    }

    /// Composite row `y` when it is an eye's row as it is (but for alpha)
    /// or black: rows of the full-width unscaled placements without
    /// crosstalk (top-bottom, HDMI frame packing), and the rows between
    /// placements. None when it must be composed.
    #[inline(always)]
    fn verbatim<'e>(&self, eyes: [Option<EyeRows<'e>>; 2], y: u32) -> Option<Verbatim<'e>> {
        let Source::Places(places) = self.source else {
            return None;
        };
        let (w, h) = self.eye;
        let mut inside = places
            .iter()
            .filter(|(p, _)| p.width > 0 && y >= p.y && y < p.y + p.height);
        match inside.next() {
            None => Some(Verbatim::Black),
            Some((p, i))
                if (p.width, p.height) == (w, h)
                    && w == self.composite.0
                    && self.stage.crosstalk == 0.0 =>
            {
                Some(Verbatim::Row(eyes[*i]?.row(y - p.y)))
            }
            Some(_) => None,
        }
    }

    /// Composite row `y` in a row buffer of `scratch` (composed unless it
    /// is there already, in the other slot than `keep`); returns the slot.
    #[inline(always)]
    fn cached_row_besides(
        &self,
        simd: Simd,
        eyes: [Option<EyeRows<'_>>; 2],
        y: u32,
        keep: usize,
        scratch: &mut Scratch,
    ) -> usize {
        if let Some(slot) = scratch.rows.iter().position(|(i, _)| *i == Some(y)) {
            return slot;
        }
        let slot = 1 - keep;
        let mut line = std::mem::take(&mut scratch.rows[slot].1);
        line.resize(self.composite.0 as usize, 0);
        scratch.rows[slot].0 = None;
        self.composite_row(simd, eyes, y, &mut line, scratch, |v| v);
        scratch.rows[slot] = (Some(y), line);
        slot
    }

    /// [`Frame::cached_row_besides`] with either slot free for it.
    #[inline(always)]
    fn cached_row(
        &self,
        simd: Simd,
        eyes: [Option<EyeRows<'_>>; 2],
        y: u32,
        scratch: &mut Scratch,
    ) -> usize {
        // Prefer to overwrite the slot holding the lower row (rows go down).
        let keep = match scratch.rows.each_ref().map(|r| r.0) {
            [Some(a), Some(b)] if a < b => 1,
            [Some(_), Some(_)] | [Some(_), None] => 0,
            _ => 1,
        };
        self.cached_row_besides(simd, eyes, y, keep, scratch)
    }

    /// Dubois's rows `y`… composed as one row into target rows `t`…
    /// (before `end`), where the eyes' rows and the target's follow each
    /// other in memory with no gap: its pipelined kernel then starts once
    /// a band, not once a row (a row's first and last steps cost about 6 %
    /// of a 1280-pixel row). How many rows, or None (one row at a time).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn fused_rows(
        &self,
        simd: Simd,
        eyes: [Option<EyeRows<'_>>; 2],
        y: u32,
        t: u32,
        end: u32,
        target: &mut Target<'_>,
        scratch: &mut Scratch,
        px: impl Fn(u32) -> u32 + Copy,
    ) -> Option<u32> {
        let Source::Pair {
            op: op @ PairOp::Dubois(_),
            eyes: [a, b],
            ..
        } = self.source
        else {
            return None;
        };
        let w = self.composite.0 as usize;
        let n = (end - t).min(self.fit.height - y);
        if n < 2 || target.stride != w || target.size.0 as usize != w {
            return None;
        }
        let (a, b) = (eyes[a]?.span(y, n)?, eyes[b]?.span(y, n)?);
        // (Eyes as wide as the composite: the rows line up.)
        if a.len() != n as usize * w || b.len() != a.len() {
            return None;
        }
        let at = t.checked_sub(target.first)? as usize * w;
        let out = target.words.get_mut(at..at + n as usize * w)?;
        op.row(simd, self.stage, &mut scratch.memo, a, b, out, px);
        Some(n)
    }

    /// Composite row `y` into `out` (the composite's width).
    #[inline(always)]
    fn composite_row(
        &self,
        simd: Simd,
        eyes: [Option<EyeRows<'_>>; 2],
        y: u32,
        out: &mut [u32],
        scratch: &mut Scratch,
        px: impl Fn(u32) -> u32 + Copy,
    ) {
        let eye = |i: usize| eyes[i].expect("an eye the frame reads");
        match self.source {
            Source::Pair {
                op,
                eyes: [a, b],
                row_parity,
            } => {
                let op = match op {
                    PairOp::Pick { columns, .. } if row_parity => PairOp::Pick {
                        columns,
                        row: y & 1,
                    },
                    op => op,
                };
                let (a, b) = (eye(a).row(y), eye(b).row(y));
                op.row(simd, self.stage, &mut scratch.memo, a, b, out, px);
            }
            Source::Places(places) => {
                let inside = |p: &Placement| p.width > 0 && y >= p.y && y < p.y + p.height;
                let covered: u32 = places
                    .iter()
                    .filter(|(p, _)| inside(p))
                    .map(|(p, _)| p.width)
                    .sum();
                if covered < self.composite.0 {
                    out.fill(px(ALPHA));
                }
                for (p, i) in places.iter().filter(|(p, _)| inside(p)) {
                    let other = eyes[1 - i];
                    let span = &mut out[p.x as usize..(p.x + p.width) as usize];
                    self.span(simd, p, eye(*i), other, y - p.y, span, scratch, px);
                }
            }
        }
    }

    /// Row `y` of placement `p`: `e` sampled into it, crosstalk against `o`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn span(
        &self,
        simd: Simd,
        p: &Placement,
        e: EyeRows<'_>,
        o: Option<EyeRows<'_>>,
        y: u32,
        out: &mut [u32],
        scratch: &mut Scratch,
        px: impl Fn(u32) -> u32 + Copy,
    ) {
        let (w, h) = self.eye;
        let vt = tap(y, h, p.height);
        let one_row = vt.f == 0.0 || vt.i0 == vt.i1;
        let (r0, r1) = e.tap_rows(&vt);
        let k = self.stage.crosstalk;
        // Whole-pixel ways, exactly the reference's bytes: a copy, and 2:1
        // averages (a tap halfway between two texels).
        if k == 0.0 && p.width == w && one_row {
            for (o, &v) in out.iter_mut().zip(r0) {
                *o = px(v | ALPHA);
            }
            return;
        }
        if k == 0.0 && p.width == w && vt.f == 0.5 && vt.i1 == vt.i0 + 1 {
            for ((o, &a), &b) in out.iter_mut().zip(r0).zip(r1) {
                *o = px(average2(a, b) | ALPHA);
            }
            return;
        }
        if k == 0.0 && 2 * p.width == w && one_row {
            #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
            if simd.avx512() {
                // SAFETY: `simd` says the processor has AVX-512 (with_simd).
                unsafe { super::avx512::halve_row(r0, out, px) };
                return;
            }
            for (o, pair) in out.iter_mut().zip(r0.chunks_exact(2)) {
                *o = px(average2(pair[0], pair[1]) | ALPHA);
            }
            return;
        }
        if k == 0.0 && p.width == w {
            // Between two rows: the reference's f32 steps, 16 pixels at a time.
            let f = vt.f;
            #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
            if simd.avx512() && (0.0..=1.0).contains(&f) {
                // SAFETY: `simd` says the processor has AVX-512 (see
                // with_simd); f is in [0, 1].
                unsafe { super::avx512::blend_rows(f, r0, r1, out, px) };
                return;
            }
            chunks(
                r0,
                r1,
                out,
                px,
                #[inline(always)]
                |a, b| {
                    let (mut a, b) = (Planes::of(a), Planes::of(b));
                    for (a, b) in a.0.iter_mut().zip(&b.0) {
                        for (a, b) in a.iter_mut().zip(b) {
                            *a += f * (b - *a);
                        }
                    }
                    a.pack()
                },
            );
            return;
        }
        let Scratch {
            a,
            b,
            tmp,
            span_taps,
            ..
        } = scratch;
        let ht = (p.width != w).then(|| span_taps.get(w, p.width));
        if let (Some(ht), 0.0) = (ht, k) {
            sample_store(simd, (r0, r1, vt.f), ht, out, [&[], &[]], px);
            return;
        }
        let ht = ht.map(|t| &t.taps[..]);
        sample(r0, r1, vt.f, ht, tmp, a);
        if k != 0.0 {
            let (o0, o1) = o.expect("the other eye, for crosstalk").tap_rows(&vt);
            sample(o0, o1, vt.f, ht, tmp, b);
            self.stage.subtract(a, b);
        }
        store(a, out, px);
    }
}

/// Samples between rows `r0` and `r1` (weight `f` of `r1`; the same slice
/// twice for one row), then along the row by taps `ht` (None: every
/// pixel), as the reference does: f32, the rows first. (`p + f·(q − p)`
/// is `p` for f = 0 or q = p, so the reference's skipping of those is the
/// same numbers.)
#[inline(always)]
fn sample(
    r0: &[u32],
    r1: &[u32],
    f: f32,
    ht: Option<&[Tap]>,
    tmp: &mut Vec<[f32; 4]>,
    dst: &mut Vec<[f32; 4]>,
) {
    lerp_rows(r0, r1, f, if ht.is_some() { &mut *tmp } else { &mut *dst });
    if let Some(ht) = ht {
        dst.resize(ht.len(), [0.0; 4]);
        for (d, t) in dst.iter_mut().zip(ht) {
            *d = lerp(tmp[t.i0], tmp[t.i1], t.f);
        }
    }
}

/// [`sample`] then [`store`], pixel by pixel from the two rows (16 at a
/// time with AVX-512, 8 by AVX2 gathers): each output pixel's two columns
/// are sampled between the rows, then between each other, as the
/// reference does. Asks for the first lines of the `next` rows on the way
/// ([`ask_next_rows`]).
#[inline(always)]
fn sample_store(
    simd: Simd,
    (r0, r1, f): (&[u32], &[u32], f32),
    ht: &TapCache,
    out: &mut [u32],
    next: [&[u32]; 2],
    px: impl Fn(u32) -> u32 + Copy,
) {
    let mut done = 0;
    #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
    if simd.avx512() {
        // SAFETY: `simd` says the processor has AVX-512 (see with_simd);
        // the taps index texels of the rows (clamped to their edge), as
        // long as both rows.
        unsafe { super::avx512::sample_taps((r0, r1, f), (&ht.i0, &ht.i1, &ht.f), out, next, px) };
        return;
    }
    #[cfg(target_arch = "x86_64")]
    if simd.avx2() {
        // SAFETY: `simd` says the processor has AVX2 (see with_simd).
        done = unsafe { gather_store((r0, r1, f), ht, out, next, px) };
    }

    let _ = simd;
    let column = |i: usize| lerp(unpack(r0[i]), unpack(r1[i]), f);
    for (x, (o, t)) in out.iter_mut().zip(&ht.taps).enumerate().skip(done) {
        if x % 8 == 0 {
            ask_next_rows(next, x / 8);
        }
        *o = px(pack(lerp(column(t.i0), column(t.i1), t.f)));
    }
}

/// [`sample_store`] 8 pixels at a time: the same operations, so the same
/// bytes. Returns how many pixels it wrote (a multiple of 8; the caller
/// does the rest).
///
/// # Safety
/// The processor has AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn gather_store(
    (r0, r1, fy): (&[u32], &[u32], f32),
    ht: &TapCache,
    out: &mut [u32],
    next: [&[u32]; 2],
    px: impl Fn(u32) -> u32,
) -> usize {
    use std::arch::x86_64::*;
    let whole = out.len().min(ht.taps.len()) / 8 * 8;
    let (p0, p1): (*const i32, *const i32) = (r0.as_ptr().cast(), r1.as_ptr().cast());
    let fy = _mm256_set1_ps(fy);
    let lerp =
        |a: __m256, b: __m256, f: __m256| _mm256_add_ps(a, _mm256_mul_ps(f, _mm256_sub_ps(b, a)));
    for x in (0..whole).step_by(8) {
        ask_next_rows(next, x / 8);
        debug_assert!(
            ht.i0[x..x + 8]
                .iter()
                .chain(&ht.i1[x..x + 8])
                .all(|&i| (i as usize) < r0.len())
        );
        // SAFETY: 8 entries at x < whole of arrays at least that long; the
        // taps index texels of the rows (clamped to their edge), as long as
        // both rows.
        let (fx, w) = unsafe {
            let i0 = _mm256_loadu_si256(ht.i0[x..].as_ptr().cast());
            let i1 = _mm256_loadu_si256(ht.i1[x..].as_ptr().cast());
            (
                _mm256_loadu_ps(ht.f[x..].as_ptr()),
                [
                    _mm256_i32gather_epi32::<4>(p0, i0),
                    _mm256_i32gather_epi32::<4>(p1, i0),
                    _mm256_i32gather_epi32::<4>(p0, i1),
                    _mm256_i32gather_epi32::<4>(p1, i1),
                ],
            )
        };
        let mut word = _mm256_set1_epi32(ALPHA as i32);
        for c in 0..3 {
            let shift = _mm256_set1_epi32(8 * c);
            let ch = |w: __m256i| {
                _mm256_cvtepi32_ps(_mm256_and_si256(
                    _mm256_srlv_epi32(w, shift),
                    _mm256_set1_epi32(0xFF),
                ))
            };
            let a = lerp(ch(w[0]), ch(w[1]), fy);
            let b = lerp(ch(w[2]), ch(w[3]), fy);
            let v = lerp(a, b, fx);
            // kernels::unorm: clamp to 0…255, + 0.5, truncate.
            let v = _mm256_min_ps(_mm256_max_ps(v, _mm256_setzero_ps()), _mm256_set1_ps(255.0));
            let v = _mm256_cvttps_epi32(_mm256_add_ps(v, _mm256_set1_ps(0.5)));
            word = _mm256_or_si256(word, _mm256_sllv_epi32(v, shift));
        }
        let mut words = [0u32; 8];
        // SAFETY: 8 words into an array of 8.
        unsafe { _mm256_storeu_si256(words.as_mut_ptr().cast(), word) };
        for (o, w) in out[x..x + 8].iter_mut().zip(words) {
            *o = px(w);
        }
    }
    whole
}

/// `rows[x]` between `r0[x]` and `r1[x]` (weight `f` of `r1`). (Plain
/// loops: `Vec::extend` is not always inlined into the vector code.)
#[inline(always)]
fn lerp_rows(r0: &[u32], r1: &[u32], f: f32, rows: &mut Vec<[f32; 4]>) {
    rows.resize(r0.len(), [0.0; 4]);
    for ((t, &p), &q) in rows.iter_mut().zip(r0).zip(r1) {
        *t = lerp(unpack(p), unpack(q), f);
    }
}

#[inline(always)]
fn unpack(v: u32) -> [f32; 4] {
    let b = v.to_le_bytes();
    [b[0], b[1], b[2], b[3]].map(f32::from)
}

/// `a + f·(b − a)` per channel.
#[inline(always)]
fn lerp(mut a: [f32; 4], b: [f32; 4], f: f32) -> [f32; 4] {
    for c in 0..4 {
        a[c] += f * (b[c] - a[c]);
    }
    a
}

#[inline(always)]
fn pack(s: [f32; 4]) -> u32 {
    use super::kernels::unorm;
    unorm(s[0]) | unorm(s[1]) << 8 | unorm(s[2]) << 16 | ALPHA
}

/// Rounds f32 pixels into words, alpha 255, through `px`.
#[inline(always)]
fn store(src: &[[f32; 4]], out: &mut [u32], px: impl Fn(u32) -> u32) {
    for (o, &s) in out.iter_mut().zip(src) {
        *o = px(pack(s));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::cpu::{fitted, reference};
    use crate::output::fits::written;
    use crate::output::mode::AnaglyphMethod;
    use crate::output::pattern::{gradient, noise};

    #[test]
    fn every_mode_fits_any_target_as_the_reference_resampled() {
        let options = [
            OutputOptions::default(),
            OutputOptions {
                swap_eyes: true,
                crosstalk: 0.3,
                saturation: 0.6,
            },
        ];
        for (w, h) in [(16, 12), (17, 13), (70, 41)] {
            let (l, r) = (noise(w, h, 5), gradient(w, h, 40));
            for o in &options {
                for mode in OutputMode::all().filter(|&m| m != OutputMode::Quad) {
                    let (cw, ch) = composite_size(mode, w, h);
                    let reference = reference(mode, o, &l, &r, 1).unwrap();
                    // The composite's size, the eye's (glstereo-run's window),
                    // larger, smaller, 2:1 in both directions, and as wide
                    // but taller (rows letterboxed, pixel for pixel).
                    let sizes = [
                        (cw, ch),
                        (w, h),
                        (40, 31),
                        (9, 7),
                        (cw / 2, ch / 2),
                        (cw, ch + 7),
                    ];
                    for size in sizes {
                        let size = (size.0.max(1), size.1.max(1));
                        let want = fitted(&reference, mode, size);
                        for (band, simd) in [h, 5]
                            .into_iter()
                            .flat_map(|b| Simd::ALL.map(|s| (b, s)))
                            .filter(|&(_, s)| s <= Simd::detected())
                        {
                            let got =
                                written(simd, mode, o, &l, &r, size, band, &mut Scratch::default());
                            let (d, x, y, c) = got.max_difference(&want).unwrap();
                            let changed = *o != OutputOptions::default();
                            let dubois =
                                matches!(mode, OutputMode::Anaglyph(_, AnaglyphMethod::Dubois));
                            // Dubois within 1 when the eyes are changed or
                            // in AVX-512's fixed point; everything else exact.
                            let tol = dubois && (changed || simd == Simd::Avx512);
                            assert!(
                                d <= u8::from(tol),
                                "{mode} {w}x{h} into {size:?} (bands of {band}, {simd:?}), {o:?}: \
                                 ({x}, {y}) channel {c} is {:?}, want {:?}",
                                got.get(x, y),
                                want.get(x, y)
                            );
                        }
                    }
                }
            }
        }
    }
}

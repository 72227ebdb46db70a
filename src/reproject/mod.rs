//! Both eyes from one rendered frame: `glstereo-run --auto=depth`
//! (`GLSTEREO_AUTO=depth`). One colour + depth frame in, two eyes out;
//! no GL here. The program renders once, mono; at its present the layer
//! hands this module the frame's colour, the depth of its scene and the
//! rule that turns a depth into a shift, and gets the two eyes
//! automatic stereo's two rendered passes would have drawn
//! ([`crate::auto`], "The rule"), as far as one picture holds them.
//!
//! # The shift of a pixel
//!
//! `--auto` moves each vertex of eye e (−1 left, +1 right) in clip space
//! by x' = x + e·s·(w − C): in normalised device coordinates by
//! e·s·(1 − C/w), in window pixels by e·k·(1 − C/w) with k = s·(viewport
//! width)/2. For a perspective camera the clip w of a point is
//! b / (z_ndc + a) ([`crate::auto::converge::Perspective`]), and z_ndc is
//! an affine function of the window depth d (glDepthRange, glClipControl),
//! so the disparity magnitude
//!
//! ```text
//! D(d) = k·(1 − C/w) = k·(1 − C·(z_ndc(d) + a)/b) = offset + slope·d
//! ```
//!
//! is affine in the window depth: one multiply and one add per pixel
//! ([`Rule`]); the left eye's pixel moves by −D, the right eye's by +D.
//! Where the projection is not known and the convergence was chosen as a
//! depth, `--auto`'s depth form e·s·(z_c − z)/(z_c − α) is affine in
//! z_ndc as well. D grows with the distance (nearer is smaller) in both
//! forms, whatever the depth convention (reversed depth included): it is
//! the order in which pixels hide each other.
//!
//! # Making an eye: forward, with a depth test on D, holes from the far side
//!
//! Each pixel of the scene's columns is put where its eye sees it
//! (rounded to the nearest column); where two land on one column the one
//! with the smaller D (the nearer) stays. Columns nothing lands on are
//! holes: what the centre view hid behind a nearer object and the eye
//! sees beside it. A hole is filled with the colour of whichever of its
//! two neighbours is farther (larger D), so the background is stretched
//! across it and a near object is never smeared over its edge.
//!
//! Three kinds of pixel:
//! - **geometry**: moved by its D;
//! - **nothing drawn** (the depth within one D24 step of the clear depth):
//!   not moved, and behind everything: a clear colour, or a background
//!   drawn flat (w = 1, no depth), is the same in both eyes of `--auto`;
//! - **at the screen** (a depth of NaN: the layer marks the pixels a flat
//!   draw wrote after the scene, a HUD or text): not moved, and in front
//!   of everything, as the overlay was drawn over the scene.
//!
//! The choices this replaced, measured against `--auto`'s two rendered
//! eyes, are in the README ("Automatic stereo from one render").
//!
//! # Kernels
//!
//! [`row_reference`] is the definition, pixel by pixel, with a depth test
//! at every landing. `row` gets the same words with spans: the shifts
//! of a row are computed 16 pixels at a time in loops over fixed-size
//! arrays (compiled for AVX2 and AVX-512 by `with_simd`), and the row is
//! cut into runs of one kind and one shift as they are (a surface rounds
//! to the same shift over many pixels: a chunk of 16 that continues the
//! run costs one vector compare); each run lands as one copy, the
//! columns it covers kept as bits. The holes are the clear bits; the
//! depth-test keys of their two neighbours, all the fill needs, are found
//! among the runs within the row's largest shift of them, never computed
//! for the other pixels. A row of more than 64 runs (noise, a surface
//! edge-on to the eye) keeps the run that landed last on each column
//! instead, whose cost does not grow with the runs.
//!
//! No depth test is needed between runs: nothing drawn lands first, then the geometry in the order in which a later run is
//! the nearer wherever two land on one column (left to right for the
//! right eye, right to left for the left: where two pixels land together
//! the one whose shift is smaller toward the eye is nearer, McMillan's
//! occlusion-compatible order), then the overlays. `fits` proves the two
//! equal, word for word, at every vector level and every size.

use crate::output::kernels::{Simd, with_simd};

#[cfg(test)]
mod fits;

/// Pixels per vector step of [`row`].
const N: usize = 16;

/// The largest shift, in pixels, either way: any larger D (a point at the
/// eye, a depth the projection does not map) is clamped to it, far
/// outside every window a server can make, so every column index stays
/// in range of i32 arithmetic.
pub const LIMIT: f32 = 1.0e6;

/// Depth-test key of a hole (nothing has landed).
const HOLE: f32 = f32::INFINITY;
/// Key of a pixel where nothing was drawn: behind every geometry.
const BACKGROUND: f32 = f32::MAX;
/// Key of a pixel at the screen (an overlay): in front of everything.
const OVERLAY: f32 = f32::NEG_INFINITY;

/// A pixel's kind for [`row`]'s runs: geometry's shift (within
/// ±[`LIMIT`]), or one of these.
const CODE_BACKGROUND: i32 = i32::MIN;
const CODE_OVERLAY: i32 = i32::MIN + 1;
/// A column no run has landed on.
const NO_RUN: u32 = u32::MAX;

/// How a frame's depths become shifts: D(d) = `offset` + `slope`·d
/// pixels (module docs), the left eye's pixel moved by −D and the right
/// eye's by +D; depths within `clear_step` of `clear` hold nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rule {
    /// D at window depth 0, in pixels.
    pub offset: f32,
    /// D's change per unit of window depth, in pixels.
    pub slope: f32,
    /// The frame's clear depth (glClearDepth).
    pub clear: f32,
    /// Depths this close to `clear` hold nothing (one D24 step).
    pub clear_step: f32,
}

impl Rule {
    /// The rule of a perspective camera whose clip w is b / (z_ndc + a):
    /// disparity magnitude k·(1 − C/w) for `k` pixels per unit of e·s·NDC
    /// (s·viewport width/2) and convergence `c` (a distance), window depth
    /// d = n + (f − n)·(z_ndc + 1)/2 for glDepthRange(n, f) (or
    /// n + (f − n)·z_ndc with clip control's zero-to-one depth).
    /// None where it maps nothing (a degenerate depth range or camera).
    pub fn perspective(
        (a, b): (f64, f64),
        k: f64,
        c: f64,
        (near, far): (f64, f64),
        zero_to_one: bool,
        clear: f64,
    ) -> Option<Rule> {
        // z_ndc = p + q·d.
        let (p, q) = ndc_of_window(near, far, zero_to_one)?;
        // D = k − k·C·(z_ndc + a)/b.
        let m = k * c / b;
        Rule::affine(k - m * (p + a), -m * q, clear)
    }

    /// The rule of `--auto`'s depth form (a projection automatic stereo
    /// cannot see, converged at NDC depth `zc` of a projection of depth
    /// offset `alpha`): D = k·(z_c − z_ndc)/(z_c − α).
    pub fn depth_form(
        k: f64,
        (zc, alpha): (f64, f64),
        (near, far): (f64, f64),
        zero_to_one: bool,
        clear: f64,
    ) -> Option<Rule> {
        let (p, q) = ndc_of_window(near, far, zero_to_one)?;
        let m = k / (zc - alpha);
        Rule::affine(m * (zc - p), -m * q, clear)
    }

    /// Every pixel holding geometry moved by the same `k` (convergence 0:
    /// the whole picture behind the screen).
    pub fn constant(k: f64, clear: f64) -> Rule {
        Rule::affine(k, 0.0, clear).unwrap_or_else(Rule::flat)
    }

    /// No depth: every pixel where it is (both eyes the frame).
    pub fn flat() -> Rule {
        Rule {
            offset: 0.0,
            slope: 0.0,
            clear: f32::NAN,
            clear_step: 0.0,
        }
    }

    fn affine(offset: f64, slope: f64, clear: f64) -> Option<Rule> {
        (offset.is_finite() && slope.is_finite()).then_some(Rule {
            offset: offset as f32,
            slope: slope as f32,
            clear: clear as f32,
            clear_step: crate::analysis::depth::DEPTH_STEP_24 as f32,
        })
    }

    /// [`Rule::pixel`] as [`row`]'s run code (the shift, or the kind of a
    /// pixel that does not move) and key, in selects the compiler keeps in
    /// vector registers.
    #[inline(always)]
    fn code(&self, d: f32) -> (i32, f32) {
        let v = self.offset + self.slope * d;
        let v = if v > LIMIT { LIMIT } else { v };
        let v = if v < -LIMIT { -LIMIT } else { v };
        let nothing = (d - self.clear).abs() <= self.clear_step;
        let overlay = d.is_nan();
        let geometry = !(nothing || overlay || v.is_nan());
        let moved = if geometry { v } else { 0.0 };
        // SAFETY: |moved| ≤ LIMIT + ½, finite: in range of i32.
        let shift = unsafe { (moved + 0.5).floor().to_int_unchecked::<i32>() };
        let code = if overlay {
            CODE_OVERLAY
        } else if geometry {
            shift
        } else {
            CODE_BACKGROUND
        };
        let key = if overlay {
            OVERLAY
        } else if geometry {
            v
        } else {
            BACKGROUND
        };
        (code, key)
    }

    /// The shift and the depth-test key of one pixel of window depth `d`:
    /// (round(D) for geometry, else 0; D, [`BACKGROUND`] or [`OVERLAY`]).
    #[inline(always)]
    fn pixel(&self, d: f32) -> (i32, f32) {
        let v = self.offset + self.slope * d;
        let v = if v > LIMIT { LIMIT } else { v };
        let v = if v < -LIMIT { -LIMIT } else { v };
        let nothing = (d - self.clear).abs() <= self.clear_step;
        let overlay = d.is_nan();
        // NaN in v (a NaN depth, or a rule of NaN) is an overlay or 0.
        let shift = (v + 0.5).floor() as i32;
        if overlay {
            (0, OVERLAY)
        } else if nothing || v.is_nan() {
            (0, BACKGROUND)
        } else {
            (shift, v)
        }
    }
}

/// (p, q) with z_ndc = p + q·d for window depth d and glDepthRange(n, f).
fn ndc_of_window(n: f64, f: f64, zero_to_one: bool) -> Option<(f64, f64)> {
    let range = f - n;
    if !range.is_finite() || range == 0.0 {
        return None;
    }
    Some(if zero_to_one {
        (-n / range, 1.0 / range)
    } else {
        (-2.0 * n / range - 1.0, 2.0 / range)
    })
}

/// The buffers of the kernels ([`frame`]), kept from row to row and frame to frame (a
/// frame allocates nothing once they have grown).
#[derive(Debug, Default)]
pub struct RowScratch {
    /// The runs of the row's columns: start, end, code.
    runs: Vec<(u32, u32, i32)>,
    /// The columns something has landed on, a bit each ([`land_runs`]).
    cover: Vec<u64>,
    /// The run whose pixel landed last on each column ([`NO_RUN`]: none),
    /// for rows of many runs ([`land_owned`]).
    owner: Vec<u32>,
    source: Vec<u32>,
}

/// Rows of at most this many runs find a hole's neighbours among the
/// runs near it ([`land_runs`]); rows of more keep an owner per column
/// ([`land_owned`]), whose cost does not grow with the runs.
const RUNS_SEARCHED: usize = 64;

/// [`row_reference`]'s eyes, with `depth` and `colour` rows of one
/// length and `columns` in them: `rule`'s run codes for the columns, and
/// what lands where, by the runs.
pub(crate) fn row(
    simd: Simd,
    rule: &Rule,
    columns: (usize, usize),
    colour: &[u32],
    depth: &[f32],
    out: [&mut [u32]; 2],
    scratch: &mut RowScratch,
) {
    check(columns, colour, depth, &out);
    with_simd(
        simd,
        #[inline(always)]
        |simd| {
            let reach = runs_of(simd, rule, columns, depth, &mut scratch.runs);
            // Nothing moves (a row of nothing drawn, overlays and geometry
            // at the screen): every pixel lands where it is, on its own.
            if reach == 0 {
                for out in out {
                    out.copy_from_slice(colour);
                }
                return;
            }
            let RowScratch {
                runs, cover, owner, ..
            } = scratch;
            let row = Row {
                rule,
                columns,
                colour,
                depth,
                runs,
                reach,
            };
            if runs.len() > RUNS_SEARCHED {
                owner.resize(colour.len(), NO_RUN);
            }
            let (x0, x1) = columns;
            for (sign, out) in [-1, 1].into_iter().zip(out) {
                out[..x0].copy_from_slice(&colour[..x0]);
                out[x1..].copy_from_slice(&colour[x1..]);
                if runs.len() <= RUNS_SEARCHED {
                    land_runs(&row, sign, cover, out);
                } else {
                    land_owned(&row, sign, owner, out);
                }
            }
        },
    );
}

/// The two eyes' rows (`out[0]` left, `out[1]` right) of one row of the
/// frame: `colour` (RGBA8 words) and `depth` (window depths), the columns
/// `columns` (the scene's viewport on this row) made by `rule`, the
/// others copied. The definition: one pixel at a time.
///
/// Panics unless the five rows are of one length and `columns` is in it.
pub fn row_reference(
    rule: &Rule,
    columns: (usize, usize),
    colour: &[u32],
    depth: &[f32],
    out: [&mut [u32]; 2],
) {
    let n = check(columns, colour, depth, &out);
    let mut shift = vec![0i32; n];
    let mut key = vec![0f32; n];
    for x in 0..n {
        (shift[x], key[x]) = rule.pixel(depth[x]);
    }
    let mut landed = vec![0f32; n];
    for (eye, out) in out.into_iter().enumerate() {
        land(eye, columns, colour, &shift, &key, &mut landed, out);
    }
}

/// Both eyes of a whole frame on this thread, at the best vector level
/// the processor has: `colour` and `depth` are `width`-wide rows (bottom
/// first or top first, as long as both agree), the rows `rows` and
/// columns `columns` of it (the scene's viewport) made by `rule` and the
/// others copied, into `out` (left, right), each as long as `colour`.
///
/// Panics unless the buffers are whole rows of one length and the
/// viewport is inside them.
pub fn frame(
    rule: &Rule,
    (columns, rows): ((usize, usize), std::ops::Range<usize>),
    width: usize,
    colour: &[u32],
    depth: &[f32],
    out: [&mut [u32]; 2],
    scratch: &mut RowScratch,
) {
    assert!(width > 0 && colour.len() % width == 0, "whole rows");
    let simd = Simd::detected();
    let [left, right] = out;
    let rows_of = |b: &[u32]| b.len() / width;
    assert!(
        depth.len() == colour.len()
            && rows_of(left) == rows_of(colour)
            && left.len() == right.len(),
        "buffers of one size"
    );
    for (y, (((c, d), l), r)) in colour
        .chunks_exact(width)
        .zip(depth.chunks_exact(width))
        .zip(left.chunks_exact_mut(width))
        .zip(right.chunks_exact_mut(width))
        .enumerate()
    {
        if rows.contains(&y) {
            row(simd, rule, columns, c, d, [l, r], scratch);
        } else {
            l.copy_from_slice(c);
            r.copy_from_slice(c);
        }
    }
}

/// [`row`] of a frame whose left eye is written where its colour is read
/// (a layer read and written in place): `io` holds the colour and gets
/// the left eye.
pub(crate) fn row_in_place(
    simd: Simd,
    rule: &Rule,
    columns: (usize, usize),
    io: &mut [u32],
    depth: &[f32],
    right: &mut [u32],
    scratch: &mut RowScratch,
) {
    let mut source = std::mem::take(&mut scratch.source);
    source.clear();
    source.extend_from_slice(io);
    row(simd, rule, columns, &source, depth, [io, right], scratch);
    scratch.source = source;
}

/// Marks the pixels of a row where `colour` differs from `scene` (the
/// row as the scene left it, before flat draws over it) as overlays: a
/// depth of NaN, at the screen in both eyes.
#[inline(always)]
pub fn mark_overlays(colour: &[u32], scene: &[u32], depth: &mut [f32]) {
    for ((c, s), d) in colour.iter().zip(scene).zip(depth) {
        if c != s {
            *d = f32::NAN;
        }
    }
}

fn check(columns: (usize, usize), colour: &[u32], depth: &[f32], out: &[&mut [u32]; 2]) -> usize {
    let n = colour.len();
    assert!(
        depth.len() == n && out.iter().all(|o| o.len() == n),
        "rows of one length"
    );
    assert!(
        columns.0 <= columns.1 && columns.1 <= n,
        "columns {columns:?} of {n}"
    );
    n
}

/// The index of the first element of `s` for which `hit` holds, looked
/// for [`N`] at a time (a comparison the compiler makes in vector
/// registers), then one at a time in the chunk that has it.
#[inline(always)]
fn first<T: Copy>(s: &[T], hit: impl Fn(T) -> bool) -> Option<usize> {
    let mut chunks = s.chunks_exact(N);
    let mut base = 0;
    for c in &mut chunks {
        let c: &[T; N] = c.try_into().expect("N");
        let mut any = false;
        for &v in c {
            any |= hit(v);
        }
        if any {
            return c.iter().position(|&v| hit(v)).map(|p| base + p);
        }
        base += N;
    }
    chunks
        .remainder()
        .iter()
        .position(|&v| hit(v))
        .map(|p| base + p)
}

/// The runs of equal code ([`Rule::code`]) among the columns [`x0`,
/// `x1`) into `runs`; gives back the reach: the largest shift of a run of
/// geometry, either way (0: nothing moves). The codes are made [`N`] at
/// a time in vector registers, with a bit for each pixel whose code is
/// not its left neighbour's ([`changes`]): a chunk that continues the
/// current run is passed over whole, and in one that does not only the
/// starts of runs are visited.
#[inline(always)]
fn runs_of(
    simd: Simd,
    rule: &Rule,
    (x0, x1): (usize, usize),
    depth: &[f32],
    runs: &mut Vec<(u32, u32, i32)>,
) -> i64 {
    runs.clear();
    let d = &depth[x0..x1];
    let Some(&d0) = d.first() else {
        return 0;
    };
    let mut start = 0;
    let mut current = rule.code(d0).0;
    let mut reach = 0i64;
    let mut end = |start: usize, stop: usize, code: i32, runs: &mut Vec<(u32, u32, i32)>| {
        if code > CODE_OVERLAY {
            reach = reach.max(i64::from(code).abs());
        }
        runs.push(((x0 + start) as u32, (x0 + stop) as u32, code));
    };
    let mut chunks = d.chunks_exact(N);
    let mut base = 0;
    for c in &mut chunks {
        let c: &[f32; N] = c.try_into().expect("N");
        let mut code = [0i32; N];
        for i in 0..N {
            code[i] = rule.code(c[i]).0;
        }
        let mut starts = changes(simd, &code, current);
        while starts != 0 {
            let i = starts.trailing_zeros() as usize;
            end(start, base + i, current, runs);
            (start, current) = (base + i, code[i]);
            starts &= starts - 1;
        }
        base += N;
    }
    for (i, &v) in chunks.remainder().iter().enumerate() {
        let k = rule.code(v).0;
        if k != current {
            end(start, base + i, current, runs);
            (start, current) = (base + i, k);
        }
    }
    end(start, d.len(), current, runs);
    reach
}

/// Bit i set where `code[i]` differs from the code before it (`before`
/// for `code[0]`): where runs start in a chunk. The definition is the
/// loop at [`Simd::Scalar`]; the vector levels compare the chunk with
/// itself moved one lane in registers (a compare at an offset in memory
/// would reload the chunk just stored, which the processor cannot
/// forward from the store).
#[inline(always)]
fn changes(simd: Simd, code: &[i32; N], before: i32) -> u32 {
    #[cfg(all(target_arch = "x86_64", glstereo_avx512))]
    if simd == Simd::Avx512 {
        // SAFETY: `simd` says the processor has AVX-512 (with_simd).
        return unsafe { changes_avx512(code, before) };
    }
    #[cfg(target_arch = "x86_64")]
    if simd >= Simd::Avx2 {
        // SAFETY: `simd` says the processor has AVX2 (with_simd).
        return unsafe { changes_avx2(code, before) };
    }
    let _ = simd;
    let mut bits = 0u32;
    let mut last = before;
    for (i, &k) in code.iter().enumerate() {
        bits |= u32::from(k != last) << i;
        last = k;
    }
    bits
}

#[cfg(all(target_arch = "x86_64", glstereo_avx512))]
#[allow(clippy::incompatible_msrv)] // Only compiled with Rust ≥ 1.89 (build.rs).
#[target_feature(enable = "avx512f")]
#[inline]
fn changes_avx512(code: &[i32; N], before: i32) -> u32 {
    use std::arch::x86_64::*;
    // SAFETY: 16 words of a 16-word array.
    let v = unsafe { _mm512_loadu_si512(code.as_ptr().cast()) };
    // [before, code[0], …, code[14]].
    let moved = _mm512_alignr_epi32(v, _mm512_set1_epi32(before), 15);
    u32::from(_mm512_cmpneq_epi32_mask(v, moved))
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn changes_avx2(code: &[i32; N], before: i32) -> u32 {
    use std::arch::x86_64::*;
    // SAFETY: two halves of 8 words of a 16-word array.
    let (lo, hi) = unsafe {
        (
            _mm256_loadu_si256(code.as_ptr().cast()),
            _mm256_loadu_si256(code.as_ptr().add(8).cast()),
        )
    };
    // Each half moved up one lane, its first lane the word before it.
    let up = _mm256_setr_epi32(7, 0, 1, 2, 3, 4, 5, 6);
    let moved = |v: __m256i, first: __m256i| {
        _mm256_blend_epi32::<1>(_mm256_permutevar8x32_epi32(v, up), first)
    };
    let lo_moved = moved(lo, _mm256_set1_epi32(before));
    let hi_moved = moved(hi, _mm256_permutevar8x32_epi32(lo, up));
    let same = |a: __m256i, b: __m256i| {
        _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(a, b))) as u32
    };
    !(same(lo, lo_moved) | same(hi, hi_moved) << 8) & 0xFFFF
}

/// A row to land ([`row`]): the rule, the scene's columns, the frame's
/// colour and depths, the runs of the columns and their reach.
struct Row<'a> {
    rule: &'a Rule,
    columns: (usize, usize),
    colour: &'a [u32],
    depth: &'a [f32],
    runs: &'a [(u32, u32, i32)],
    reach: i64,
}

impl Row<'_> {
    /// How far a run of `code` moves in eye `sign` (−1 left, +1 right).
    #[inline(always)]
    fn shift(sign: i64, code: i32) -> i64 {
        match code {
            CODE_BACKGROUND | CODE_OVERLAY => 0,
            s => sign * i64::from(s),
        }
    }

    /// Lands run `i` in eye `sign` (a copy of its colour), clipped to the
    /// columns: the columns [lo, hi) it covered, if any.
    #[inline(always)]
    fn put(&self, sign: i64, i: usize, out: &mut [u32]) -> Option<(usize, usize)> {
        let (x0, x1) = self.columns;
        let (a, b, code) = self.runs[i];
        let d = Row::shift(sign, code);
        let lo = (i64::from(a) + d).max(x0 as i64);
        let hi = (i64::from(b) + d).min(x1 as i64);
        (lo < hi).then(|| {
            let (lo, hi) = (lo as usize, hi as usize);
            let from = (lo as i64 - d) as usize;
            out[lo..hi].copy_from_slice(&self.colour[from..from + (hi - lo)]);
            (lo, hi)
        })
    }

    /// The runs in the order they land in eye `sign` (module docs): what
    /// was not drawn, the geometry (left to right in the right eye, right
    /// to left in the left), the overlays; `put` gets each.
    #[inline(always)]
    fn in_order(&self, sign: i64, mut put: impl FnMut(usize)) {
        let runs = self.runs;
        let geometry = |c: i32| c != CODE_BACKGROUND && c != CODE_OVERLAY;
        for (i, r) in runs.iter().enumerate() {
            if r.2 == CODE_BACKGROUND {
                put(i);
            }
        }
        if sign > 0 {
            for (i, r) in runs.iter().enumerate() {
                if geometry(r.2) {
                    put(i);
                }
            }
        } else {
            for (i, r) in runs.iter().enumerate().rev() {
                if geometry(r.2) {
                    put(i);
                }
            }
        }
        for (i, r) in runs.iter().enumerate() {
            if r.2 == CODE_OVERLAY {
                put(i);
            }
        }
    }

    /// The depth-test key of the pixel of run `i` that landed on column
    /// `t` in eye `sign`.
    #[inline(always)]
    fn key(&self, sign: i64, i: usize, t: usize) -> f32 {
        let from = t as i64 - Row::shift(sign, self.runs[i].2);
        self.rule.code(self.depth[from as usize]).1
    }

    /// The key of what landed last on column `t` (something did) in eye
    /// `sign`, found among the runs that can reach it: an overlay at `t`,
    /// else the geometry run landing there last, else what was not drawn
    /// at `t`. `near` holds the runs near the column asked before, which
    /// is never to the right of `t` (a row's holes are filled left to
    /// right): it moves along the runs, never back.
    #[inline(always)]
    fn landed(&self, sign: i64, t: usize, near: &mut Near) -> f32 {
        let runs = self.runs;
        let t64 = t as i64;
        // The run at t, and the runs whose source is within reach of t.
        while runs[near.at].1 as usize <= t {
            near.at += 1;
        }
        while i64::from(runs[near.lo].1) <= t64 - self.reach {
            near.lo += 1;
        }
        while near.hi < runs.len() && i64::from(runs[near.hi].0) <= t64 + self.reach {
            near.hi += 1;
        }
        let here = runs[near.at].2;
        if here == CODE_OVERLAY {
            return OVERLAY;
        }
        let covers = |i: usize| {
            let (a, b, code) = runs[i];
            let d = Row::shift(sign, code);
            code > CODE_OVERLAY && i64::from(a) + d <= t64 && t64 < i64::from(b) + d
        };
        let last = if sign > 0 {
            (near.lo..near.hi).rev().find(|&i| covers(i))
        } else {
            (near.lo..near.hi).find(|&i| covers(i))
        };
        match last {
            Some(i) => self.key(sign, i, t),
            None if here == CODE_BACKGROUND => BACKGROUND,
            None => HOLE,
        }
    }

    /// Fills the holes [start, end) of eye `sign` (`out`) as [`land`]
    /// does: from the farther of the two neighbours whose keys `landed`
    /// gives.
    #[inline(always)]
    fn fill(
        &self,
        (start, end): (usize, usize),
        out: &mut [u32],
        mut landed: impl FnMut(usize) -> f32,
    ) {
        let (x0, x1) = self.columns;
        let left = (start > x0).then(|| start - 1);
        let right = (end < x1).then_some(end);
        let from = match (left, right) {
            (Some(l), Some(r)) => Some(if landed(l) >= landed(r) { l } else { r }),
            (l, r) => l.or(r),
        };
        match from {
            Some(f) => {
                let c = out[f];
                out[start..end].fill(c);
            }
            None => out[start..end].copy_from_slice(&self.colour[start..end]),
        }
    }
}

/// Where [`Row::landed`] is along the runs: the run at the column asked,
/// the first whose source ends within reach of it, the first whose source
/// starts beyond reach of it.
#[derive(Default)]
struct Near {
    at: usize,
    lo: usize,
    hi: usize,
}

/// The columns of one eye's row (`sign` −1 left: moved by −shift; +1
/// right: +shift) from the runs (module docs), each run one copy, the
/// columns covered kept as bits; then the holes, as [`land`] fills them,
/// the keys of their neighbours found among the runs near them
/// ([`Row::landed`]).
#[inline(always)]
fn land_runs(row: &Row, sign: i64, cover: &mut Vec<u64>, out: &mut [u32]) {
    let (x0, x1) = row.columns;
    let n = x1 - x0;
    cover.clear();
    cover.resize(n.div_ceil(64), 0);
    row.in_order(sign, |i| {
        if let Some((lo, hi)) = row.put(sign, i, out) {
            set_bits(cover, lo - x0, hi - x0);
        }
    });
    let mut near = Near::default();
    let mut t = 0;
    while t < n {
        let start = next_bit(cover, t, n, false);
        if start == n {
            break;
        }
        let end = next_bit(cover, start, n, true);
        row.fill((x0 + start, x0 + end), out, |c| {
            row.landed(sign, c, &mut near)
        });
        t = end;
    }
}

/// Sets bits [lo, hi) of `bits` (lo < hi).
#[inline(always)]
fn set_bits(bits: &mut [u64], lo: usize, hi: usize) {
    let (a, b) = (lo / 64, (hi - 1) / 64);
    let first = !0u64 << (lo % 64);
    let last = !0u64 >> (63 - (hi - 1) % 64);
    if a == b {
        bits[a] |= first & last;
    } else {
        bits[a] |= first;
        bits[a + 1..b].fill(!0);
        bits[b] |= last;
    }
}

/// The first bit at or after `from` (below `n`) that is `set`, or `n`.
#[inline(always)]
fn next_bit(bits: &[u64], from: usize, n: usize, set: bool) -> usize {
    let flip = if set { 0 } else { !0u64 };
    let mut i = from / 64;
    let mut w = (bits[i] ^ flip) & (!0u64 << (from % 64));
    loop {
        if w != 0 {
            return (i * 64 + w.trailing_zeros() as usize).min(n);
        }
        i += 1;
        if i * 64 >= n {
            return n;
        }
        w = bits[i] ^ flip;
    }
}

/// [`land_runs`] for rows of many runs: the run that landed last is kept
/// for each column (`owner`), and the holes are the columns without one.
#[inline(always)]
fn land_owned(row: &Row, sign: i64, owner: &mut [u32], out: &mut [u32]) {
    let (x0, x1) = row.columns;
    owner[x0..x1].fill(NO_RUN);
    row.in_order(sign, |i| {
        if let Some((lo, hi)) = row.put(sign, i, out) {
            owner[lo..hi].fill(i as u32);
        }
    });
    let mut t = x0;
    while t < x1 {
        let Some(p) = first(&owner[t..x1], |o| o == NO_RUN) else {
            break;
        };
        let start = t + p;
        let end = first(&owner[start..x1], |o| o != NO_RUN).map_or(x1, |q| start + q);
        row.fill((start, end), out, |c| row.key(sign, owner[c] as usize, c));
        t = end;
    }
}

/// One eye's row (`eye` 0 left: moved by −shift; 1 right: +shift): the
/// scatter with its depth test, then the holes.
#[inline(always)]
fn land(
    eye: usize,
    (x0, x1): (usize, usize),
    colour: &[u32],
    shift: &[i32],
    key: &[f32],
    landed: &mut [f32],
    out: &mut [u32],
) {
    out[..x0].copy_from_slice(&colour[..x0]);
    out[x1..].copy_from_slice(&colour[x1..]);
    if x0 == x1 {
        return;
    }
    let landed = &mut landed[x0..x1];
    landed.fill(HOLE);
    let sign: i64 = if eye == 0 { -1 } else { 1 };
    let span = (x1 - x0) as u64;
    for x in x0..x1 {
        let t = x as i64 + sign * i64::from(shift[x]) - x0 as i64;
        // Only landings inside the columns (a negative t wraps past span).
        if (t as u64) < span {
            let t = t as usize;
            if key[x] < landed[t] {
                landed[t] = key[x];
                out[x0 + t] = colour[x];
            }
        }
    }
    fill_holes(landed, &mut out[x0..x1], &colour[x0..x1]);
}

/// Each run of holes in `landed` takes the colour of its farther
/// neighbour (the larger key; the left one when equal; the one there is
/// at an end; `colour` where the whole row is holes).
#[inline(always)]
fn fill_holes(landed: &[f32], out: &mut [u32], colour: &[u32]) {
    let n = landed.len();
    let mut x = 0;
    while x < n {
        if landed[x] != HOLE {
            x += 1;
            continue;
        }
        let start = x;
        while x < n && landed[x] == HOLE {
            x += 1;
        }
        let from = match (start.checked_sub(1), (x < n).then_some(x)) {
            (Some(l), Some(r)) => Some(if landed[l] >= landed[r] { l } else { r }),
            (l, r) => l.or(r),
        };
        match from {
            Some(f) => {
                let c = out[f];
                out[start..x].fill(c);
            }
            None => out[start..x].copy_from_slice(&colour[start..x]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rule(offset: f32, slope: f32) -> Rule {
        Rule {
            offset,
            slope,
            clear: 1.0,
            clear_step: 1e-7,
        }
    }

    fn eyes(rule: &Rule, colour: &[u32], depth: &[f32]) -> [Vec<u32>; 2] {
        let n = colour.len();
        let (mut l, mut r) = (vec![0; n], vec![0; n]);
        row_reference(rule, (0, n), colour, depth, [&mut l, &mut r]);
        [l, r]
    }

    #[test]
    fn a_pixel_moves_by_its_disparity_in_each_eye_and_its_hole_takes_the_far_side() {
        // Far background (depth 0.9, D = 2) with a near object (0.1,
        // D = -2) over columns 8..12: D = -2.5 + 5·d... take offset -2.5,
        // slope 5: d 0.9 → 2.0, d 0.1 → -2.0.
        let r = rule(-2.5, 5.0);
        let colour: Vec<u32> = (0..20)
            .map(|x| if (8..12).contains(&x) { 1000 + x } else { x })
            .collect();
        let depth: Vec<f32> = (0..20)
            .map(|x| if (8..12).contains(&x) { 0.1 } else { 0.9 })
            .collect();
        let [left, right] = eyes(&r, &colour, &depth);
        // Right eye: the object 2 columns left (6..10), the background 2
        // right; the object's old columns 10..14 hold background from x=8..
        // hidden in the centre: filled from the far side.
        assert_eq!(&right[6..10], &colour[8..12], "{right:?}");
        assert_eq!(right[14], 12, "background moved right by 2: {right:?}");
        for x in 10..14 {
            assert!(
                right[x] < 1000,
                "no near pixel smeared over its edge at {x}: {right:?}"
            );
        }
        // Left eye: the mirror.
        assert_eq!(&left[10..14], &colour[8..12], "{left:?}");
        assert_eq!(left[4], 6);
        for x in 6..10 {
            assert!(left[x] < 1000, "{left:?}");
        }
    }

    #[test]
    fn nothing_drawn_stays_and_lies_behind_and_an_overlay_stays_in_front() {
        // Geometry far (D = 3) left of nothing drawn (depth 1.0): it moves
        // over the clear colour, which does not move.
        let r = rule(3.0, 0.0);
        let colour: Vec<u32> = (0..12).collect();
        let mut depth = vec![0.5f32; 12];
        for d in &mut depth[6..] {
            *d = 1.0;
        }
        depth[2] = f32::NAN; // an overlay pixel among the geometry
        let [left, right] = eyes(&r, &colour, &depth);
        // Geometry x moved to x + 3 over the clear colour.
        assert_eq!(&right[6..9], &[3, 4, 5], "{right:?}");
        assert_eq!(&right[9..], &[9, 10, 11], "nothing drawn stays: {right:?}");
        // Where the overlay's own scene pixel would have landed: a hole
        // between two geometry pixels of one depth (the left one).
        assert_eq!(right[5], 1, "{right:?}");
        assert_eq!(right[2], 2, "the overlay stays at the screen: {right:?}");
        assert_eq!(
            left[2], 2,
            "in front of the geometry landing there: {left:?}"
        );
        assert_eq!(&left[0..2], &[3, 4]);
        // Holes between the overlay and what was not drawn: the far side.
        assert_eq!(&left[3..6], &[6, 6, 6], "{left:?}");
        assert_eq!(left[8], 8);
    }

    #[test]
    fn the_rule_of_a_camera_is_autos_disparity_at_every_depth() {
        use glam::DMat4;
        let proj = DMat4::perspective_rh_gl(1.0, 4.0 / 3.0, 0.5, 50.0).to_cols_array();
        let p = crate::auto::converge::Perspective::from_matrix(&proj).expect("perspective");
        let (a, b) = p.terms();
        let (k, c) = (7.0, 4.0);
        for (range, zto) in [((0.0, 1.0), false), ((0.2, 0.9), false), ((0.0, 1.0), true)] {
            let r = Rule::perspective((a, b), k, c, range, zto, 1.0).expect("rule");
            for w in [0.6, 1.0, 4.0, 9.0, 40.0] {
                // The point's NDC z from the matrix, then its window depth.
                let clip = DMat4::from_cols_array(&proj) * glam::DVec4::new(0.0, 0.0, -w, 1.0);
                let z = clip.z / clip.w;
                let t = if zto { z } else { (z + 1.0) / 2.0 };
                let d = range.0 + (range.1 - range.0) * t;
                let want = k * (1.0 - c / w);
                let got = f64::from(r.offset) + f64::from(r.slope) * d;
                assert!(
                    (got - want).abs() < 1e-3 * (1.0 + want.abs()),
                    "w {w}: {got} against {want}"
                );
            }
        }
        assert_eq!(
            Rule::perspective((a, b), k, c, (0.5, 0.5), false, 1.0),
            None
        );
    }

    #[test]
    fn the_depth_form_is_autos_at_every_depth() {
        let (k, zc, alpha) = (5.0, 0.6, 1.0);
        let r = Rule::depth_form(k, (zc, alpha), (0.0, 1.0), false, 1.0).expect("rule");
        for z in [-0.5, 0.0, 0.6, 0.95] {
            let d = (z + 1.0) / 2.0;
            let want = k * (zc - z) / (zc - alpha);
            let got = f64::from(r.offset) + f64::from(r.slope) * d;
            assert!((got - want).abs() < 1e-4, "z {z}: {got} against {want}");
        }
    }

    #[test]
    fn huge_and_absurd_depths_and_rules_give_columns_in_range() {
        for r in [
            rule(1e30, 1e30),
            rule(-1e30, 0.0),
            rule(f32::NAN, 1.0),
            rule(0.0, f32::INFINITY),
        ] {
            let colour: Vec<u32> = (0..9).collect();
            let depth = [
                0.0,
                0.5,
                f32::NAN,
                f32::INFINITY,
                -1.0,
                1.0,
                1e38,
                -0.0,
                0.25,
            ];
            let [left, right] = eyes(&r, &colour, &depth);
            for v in left.iter().chain(&right) {
                assert!(*v < 9, "{r:?}: {left:?} {right:?}");
            }
        }
    }

    #[test]
    fn a_flat_rule_gives_the_frame_in_both_eyes() {
        let colour: Vec<u32> = (0..33).map(|x| x * 7).collect();
        let depth: Vec<f32> = (0..33).map(|x| x as f32 / 40.0).collect();
        let [l, r] = eyes(&Rule::flat(), &colour, &depth);
        assert_eq!(l, colour);
        assert_eq!(r, colour);
    }
}

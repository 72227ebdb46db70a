//! Every composite output mode on the CPU: [`compose`] / [`compose_into`]
//! (fast: the row kernels of `output/rows.rs`) and [`reference()`], the
//! "oracle": pure Rust, no GL, one pixel at a time, the rules below taken
//! literally. The fast path gives the reference's bytes (but for `-dubois`
//! of eyes changed by saturation or crosstalk, and for `-dubois` on a
//! processor with AVX-512, within 1 unit); the GL
//! compositor reproduces it within 1 unit per channel.
//!
//! # Numbers
//!
//! Everything is defined as GL computes it. A unorm8 channel v reads as
//! v/255; all arithmetic is in f32 with no intermediate rounding (one pass
//! from the eye images to the output); a result f is written as
//! `round(f·255)`, clamped to 0…255, halves rounded up. Output alpha is
//! always 255; input alpha is ignored. (The code works in 0…255 units,
//! which is the same arithmetic scaled.)
//!
//! # Sampling
//!
//! Where an eye is scaled ([`super::layout::Placement`]), output pixel
//! (x, y) samples the eye at texel coordinates
//! `u = (x − p.x + 0.5)·W/p.width`, `v = (y − p.y + 0.5)·H/p.height` with
//! bilinear filtering (texel i centred at i + 0.5) and clamp-to-edge, as
//! GL_LINEAR + GL_CLAMP_TO_EDGE does. Halving an even size therefore gives
//! the exact average of two source pixels (rows for `top-bottom-half`,
//! columns for `side-by-side-half`); nothing is dropped. Unscaled
//! placements are exact copies. The eye images are top row first; GL's
//! bottom-first textures give the same samples (v ↦ H − v maps texel
//! centres onto texel centres).
//!
//! # Pipeline, in this order
//!
//! 1. **Swap**: with `swap_eyes`, the inputs are exchanged before anything
//!    else, so `compose(m, swap, L, R) == compose(m, no swap, R, L)` in
//!    every mode.
//! 2. **Saturation** (`anaglyph-*` only), per eye and pixel:
//!    `c' = Y + s·(c − Y)` with Y = [`super::anaglyph::luma`] of that pixel.
//!    s = 1 changes nothing, so the plain masks are exact by default.
//! 3. **Crosstalk reduction** (every mode that shows both eyes, i.e. all but
//!    `left`/`right`), per channel, from the values of step 2:
//!    `L' = max(L − k·R, 0)`, `R' = max(R − k·L, 0)`, where L and R are the
//!    two eyes sampled at the SAME eye-texel coordinate (for scaled
//!    placements: both eyes are filtered first, then subtracted).
//! 4. **The mode**:
//!    - `left` / `right`: that eye, exactly.
//!    - anaglyph plain: channel mask in full colour — red-cyan R from the
//!      left eye, G and B from the right; green-magenta G from the left, R
//!      and B from the right; amber-blue R and G from the left, B from the
//!      right.
//!    - `-half`: the left eye's channels carry its luminance Y(L'); the
//!      right eye's channels stay in colour.
//!    - `-mono`: every channel carries its eye's luminance.
//!    - `-dubois`: both eyes sRGB-decoded with the exact piecewise curve,
//!      `clamp(M_L·l + M_R·r, 0, 1)` with the matrices of
//!      [`super::anaglyph::dubois_matrices`], sRGB-encoded.
//!    - `anaglyph-red-blue`: (Y(L'), 0, Y(R')).
//!    - `rows` / `columns` / `checkerboard`: pixel (x, y) from the left
//!      eye's pixel (x, y) when y / x / x + y is even (row 0 = top), else
//!      the right eye's pixel (x, y).
//!    - `frame-sequential`: the left eye when `frame_index` is even, the
//!      right when odd (after the swap; see
//!      [`super::options::OutputOptions::frame_sequential_eye`]).
//!    - `side-by-side`, `top-bottom` (full and `-half`), `hdmi-frame-packing`,
//!      `starbase`, `str-rect`: each eye scaled into its
//!      [`super::layout::placements`] rectangle; everything else black.
//!
//! `quad` is not a composite: [`compose`] refuses it with
//! [`Error::InvalidOperation`]; the surface layer shows quad natively or
//! falls back on configs without native stereo.

use crate::error::{Error, Result};
use crate::image::{Image, MAX_DIMENSION, as_words_mut, check_size};
use crate::math::Eye;

use super::anaglyph::{DuboisMatrices, dubois_matrices, dubois_pixel, luma, srgb_to_linear};
use super::layout::{Placement, composite_size, leaves_gaps, placements};
use super::mode::{AnaglyphColors, AnaglyphMethod, OutputMode};
use super::options::OutputOptions;
use super::rows::{EyeRows, Frame, Scratch, Target};

/// One pixel's R, G, B in 0…255 units (f32, unrounded), and its alpha,
/// carried along only so rows convert four bytes at a time (it is ignored).
type Rgb = [f32; 4];

/// The colour part of a pixel, for [`luma`].
#[inline]
fn rgb(p: &Rgb) -> [f32; 3] {
    [p[0], p[1], p[2]]
}

/// Composes the two eye images into the output frame of `mode` by the rules
/// of this module's documentation.
///
/// `frame_index` matters only to `frame-sequential` (even = left eye).
///
/// # Errors
/// - [`Error::InvalidOperation`] for `quad`, which is not a composite.
/// - [`Error::InvalidValue`] when the eyes differ in size, when `options` is
///   out of range, or when the output would exceed
///   [`MAX_DIMENSION`] in either direction.
pub fn compose(
    mode: OutputMode,
    options: &OutputOptions,
    left: &Image,
    right: &Image,
    frame_index: u64,
) -> Result<Image> {
    let mut out = Image::new(1, 1);
    compose_into(mode, options, left, right, frame_index, &mut out)?;
    Ok(out)
}

/// [`compose`] into an existing image, reusing its allocation (a frame loop
/// avoids a fresh multi-megabyte buffer, and its page faults, per frame).
/// `out` is resized to the composite size. On error `out` is unchanged.
pub fn compose_into(
    mode: OutputMode,
    options: &OutputOptions,
    left: &Image,
    right: &Image,
    frame_index: u64,
    out: &mut Image,
) -> Result<()> {
    let (w, h) = (left.width(), left.height());
    let size = composite_size(mode, w, h);
    compose_fitted(mode, options, left, right, frame_index, size, out)
}

/// The composite as a window of `size` shows it: placed by
/// [`super::layout::window_fit`] (scaled bilinearly as [`resample`] does,
/// or for the interleaved modes cropped, centred on black), in one pass
/// from the eyes. At the composite's size this is [`compose_into`]. `out`
/// is resized to `size`; on error it is unchanged.
///
/// # Errors
/// As [`compose`]; also [`Error::InvalidValue`] for a `size` outside
/// 1…[`MAX_DIMENSION`].
pub fn compose_fitted(
    mode: OutputMode,
    options: &OutputOptions,
    left: &Image,
    right: &Image,
    frame_index: u64,
    size: (u32, u32),
    out: &mut Image,
) -> Result<()> {
    let (options, _) = check_eyes(mode, options, left, right)?;
    check_size(size.0, size.1)?;
    // Nothing can fail past this point, so `out` is untouched on error.
    out.resize(size.0, size.1, "composite")?;
    let eyes = [EyeRows::image(left), EyeRows::image(right)];
    let frame = Frame::new(
        mode,
        &options,
        frame_index,
        (left.width(), left.height()),
        size,
    );
    match (eyes, as_words_mut(out.pixels_mut())) {
        ([Some(l), Some(r)], Some(words)) => {
            let mut target = Target {
                words,
                stride: size.0 as usize,
                size,
                first: 0,
            };
            with_scratch(|scratch| {
                frame.write([Some(l), Some(r)], 0..size.1, &mut target, scratch, |v| v);
            });
        }
        // Buffers that are not aligned words (never from the system
        // allocator) or a big-endian machine: the reference, placed.
        _ => {
            *out = fitted(
                &reference(mode, &options, left, right, frame_index)?,
                mode,
                size,
            )
        }
    }
    Ok(())
}

/// `composite` placed in a window of `size` by [`super::layout::window_fit`]
/// (the reference's way: [`resample`] when scaled).
pub fn fitted(composite: &Image, mode: OutputMode, size: (u32, u32)) -> Image {
    let (cw, ch) = (composite.width(), composite.height());
    let fit = super::layout::window_fit(mode, cw, ch, size.0, size.1);
    let shown = if (fit.width, fit.height) == (cw, ch) {
        composite.clone()
    } else {
        resample(composite, 0, 0, cw, ch, fit.width, fit.height)
    };
    Image::from_fn(size.0, size.1, |x, y| {
        let (sx, sy) = (x as i32 - fit.x, y as i32 - fit.y);
        if sx >= 0 && sy >= 0 && (sx as u32) < shown.width() && (sy as u32) < shown.height() {
            shown.get(sx as u32, sy as u32)
        } else {
            [0, 0, 0, 255]
        }
    })
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

/// Runs `f` with this thread's row buffers (fresh ones if they are in use
/// further up the stack), so that a frame loop allocates nothing.
fn with_scratch<T>(f: impl FnOnce(&mut Scratch) -> T) -> T {
    SCRATCH.with(|s| match s.try_borrow_mut() {
        Ok(mut s) => f(&mut s),
        Err(_) => f(&mut Scratch::default()),
    })
}

/// The checks of [`compose_into`]: eyes of one size, and
/// [`check_composite`]'s.
fn check_eyes(
    mode: OutputMode,
    options: &OutputOptions,
    left: &Image,
    right: &Image,
) -> Result<(OutputOptions, (u32, u32))> {
    let (w, h) = (left.width(), left.height());
    if (right.width(), right.height()) != (w, h) {
        return Err(Error::invalid_value(format!(
            "the left eye is {w}x{h} but the right eye is {}x{}: both eyes must be the same size",
            right.width(),
            right.height()
        )));
    }
    check_composite(mode, options, w, h)
}

/// The checks every composite passes, on the CPU and on GL alike: valid
/// options, an output no larger than [`MAX_DIMENSION`] a side, and a
/// composite mode (not `quad`). Returns the validated options and the
/// composite size.
pub(crate) fn check_composite(
    mode: OutputMode,
    options: &OutputOptions,
    w: u32,
    h: u32,
) -> Result<(OutputOptions, (u32, u32))> {
    let options = options.validated()?;
    let (cw, ch) = composite_size(mode, w, h);
    if check_size(cw, ch).is_err() {
        return Err(Error::invalid_value(format!(
            "{mode} of {w}x{h} eyes makes a {cw}x{ch} frame; each side must be at most \
             {MAX_DIMENSION}: use smaller eyes or a same-size mode such as {}",
            OutputMode::SideBySideHalf
        )));
    }
    if mode == OutputMode::Quad {
        return Err(Error::invalid_operation(
            "quad is native quad-buffer output, not a composite image: choose left, right \
             or a composite mode (a surface without native stereo falls back by itself)",
        ));
    }
    Ok((options, (cw, ch)))
}

/// The oracle: [`compose`] by this module's rules taken literally, one
/// pixel at a time in f32 (slow; for tests and as the fallback of
/// [`compose_into`]). Same errors as [`compose`].
pub fn reference(
    mode: OutputMode,
    options: &OutputOptions,
    left: &Image,
    right: &Image,
    frame_index: u64,
) -> Result<Image> {
    let (options, (cw, ch)) = check_eyes(mode, options, left, right)?;
    let (w, h) = (left.width(), left.height());
    let (l, r) = if options.swap_eyes {
        (right, left)
    } else {
        (left, right)
    };
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
    let mut out = Image::new(cw, ch);
    match mode {
        OutputMode::Quad => {} // refused above
        OutputMode::Left | OutputMode::Right | OutputMode::FrameSequential => {
            // `frame_sequential_eye` accounts for the swap: pick from the
            // unswapped inputs.
            let (eye, shown, other) = match mode {
                OutputMode::Left => (Eye::Left, l, r),
                OutputMode::Right => (Eye::Right, r, l),
                _ => match options.frame_sequential_eye(frame_index) {
                    Eye::Left => (Eye::Left, left, right),
                    Eye::Right => (Eye::Right, right, left),
                },
            };
            let full = Placement {
                eye,
                x: 0,
                y: 0,
                width: w,
                height: h,
            };
            draw_placement(&full, shown, other, stage, &mut out);
        }
        OutputMode::Anaglyph(colors, method) => {
            anaglyph(Anaglyph::Masked(colors, method), l, r, stage, &mut out);
        }
        OutputMode::AnaglyphRedBlue => anaglyph(Anaglyph::RedBlue, l, r, stage, &mut out),
        OutputMode::Rows | OutputMode::Columns | OutputMode::Checkerboard => {
            interleave(mode, l, r, stage, &mut out);
        }
        OutputMode::SideBySide
        | OutputMode::TopBottom
        | OutputMode::SideBySideHalf
        | OutputMode::TopBottomHalf
        | OutputMode::HdmiFramePacking
        | OutputMode::Starbase
        | OutputMode::StrRect => {
            // Always Some for these modes (a layout test checks it).
            let places = placements(mode, w, h);
            if leaves_gaps(mode, w, h) {
                out = Image::from_fn(cw, ch, |_, _| [0, 0, 0, 255]);
            }
            for p in places.iter().flatten() {
                let (eye, other) = match p.eye {
                    Eye::Left => (l, r),
                    Eye::Right => (r, l),
                };
                draw_placement(p, eye, other, stage, &mut out);
            }
        }
    }
    Ok(out)
}

/// The per-eye colour steps before the mode, with their effective values
/// (1 and 0 where the mode ignores them).
#[derive(Clone, Copy)]
struct Stage {
    saturation: f32,
    crosstalk: f32,
}

impl Stage {
    /// Saturation then crosstalk on two rows sampled at the same coordinates.
    fn apply(self, l: &mut [Rgb], r: &mut [Rgb]) {
        if self.saturation != 1.0 {
            desaturate(l, self.saturation);
            desaturate(r, self.saturation);
        }
        let k = self.crosstalk;
        if k != 0.0 {
            for (a, b) in l.iter_mut().zip(r.iter_mut()) {
                for c in 0..3 {
                    let (x, y) = (a[c], b[c]);
                    a[c] = (x - k * y).max(0.0);
                    b[c] = (y - k * x).max(0.0);
                }
            }
        }
    }
}

fn desaturate(row: &mut [Rgb], s: f32) {
    for p in row {
        let y = luma(rgb(p));
        for c in &mut p[..3] {
            *c = y + s * (*c - y);
        }
    }
}

#[inline]
pub(crate) fn unorm(v: f32) -> u8 {
    // Clamp, then round half up; `as` truncates the non-negative sum.
    (v.clamp(0.0, 255.0) + 0.5) as u8
}

fn load(src: &[u8], dst: &mut Vec<Rgb>) {
    dst.clear();
    dst.extend(
        src.chunks_exact(4)
            .map(|p| [p[0], p[1], p[2], p[3]].map(f32::from)),
    );
}

fn store(src: &[Rgb], dst: &mut [u8]) {
    for (d, s) in dst.chunks_exact_mut(4).zip(src) {
        d[0] = unorm(s[0]);
        d[1] = unorm(s[1]);
        d[2] = unorm(s[2]);
        d[3] = 255;
    }
}

fn row_mut(img: &mut Image, y: u32) -> &mut [u8] {
    let stride = img.width() as usize * 4;
    let start = y as usize * stride;
    &mut img.pixels_mut()[start..start + stride]
}

/// One bilinear tap along an axis: texels i0 and i1 weighted (1 − f) and f.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tap {
    pub(crate) i0: usize,
    pub(crate) i1: usize,
    pub(crate) f: f32,
}

/// The tap of output pixel `i` when `src_len` texels are scaled onto
/// `dst_len` pixels: centre `(i + 0.5)·src_len/dst_len`, clamp-to-edge.
pub(crate) fn tap(i: u32, src_len: u32, dst_len: u32) -> Tap {
    let c = (f64::from(i) + 0.5) * f64::from(src_len) / f64::from(dst_len) - 0.5;
    let base = c.floor();
    let last = i64::from(src_len) - 1;
    let i0 = (base as i64).clamp(0, last) as usize;
    let i1 = (base as i64 + 1).clamp(0, last) as usize;
    Tap {
        i0,
        i1,
        f: (c - base) as f32,
    }
}
/// Samples one row of an eye for a placement: vertical tap `vt`, horizontal
/// taps `ht` (None = the placement has the eye's width: copy columns).
fn sample_row(img: &Image, vt: Tap, ht: Option<&[Tap]>, tmp: &mut Vec<Rgb>, dst: &mut Vec<Rgb>) {
    let target: &mut Vec<Rgb> = if ht.is_some() { tmp } else { dst };
    load(img.row(vt.i0 as u32), target);
    if vt.f != 0.0 && vt.i1 != vt.i0 {
        let f = vt.f;
        for (p, q) in target.iter_mut().zip(img.row(vt.i1 as u32).chunks_exact(4)) {
            for c in 0..4 {
                p[c] += f * (f32::from(q[c]) - p[c]);
            }
        }
    }
    if let Some(ht) = ht {
        dst.clear();
        dst.extend(ht.iter().map(|t| {
            let (a, b) = (tmp[t.i0], tmp[t.i1]);
            std::array::from_fn(|c| a[c] + t.f * (b[c] - a[c]))
        }));
    }
}

/// Resamples the rectangle (`x`, `y`, `w`, `h`) of `src` (rows top first)
/// to `out_w` × `out_h` pixels with the module's bilinear rule (sample at
/// the output pixel centre mapped into the rectangle, clamp-to-edge within
/// it). Same size is an exact copy. Output alpha is 255.
///
/// Panics if the rectangle is empty or not inside `src` (callers build it
/// from the image's own size).
pub fn resample(src: &Image, x: u32, y: u32, w: u32, h: u32, out_w: u32, out_h: u32) -> Image {
    assert!(
        w > 0 && h > 0 && x + w <= src.width() && y + h <= src.height(),
        "resample rectangle"
    );
    let mut sub = Image::new(w, h);
    for row in 0..h {
        let s = &src.row(y + row)[x as usize * 4..(x + w) as usize * 4];
        row_mut(&mut sub, row).copy_from_slice(s);
    }
    let mut out = Image::new(out_w, out_h);
    let ht: Vec<Tap> = (0..out_w).map(|i| tap(i, w, out_w)).collect();
    let ht = (w != out_w).then_some(&ht[..]);
    let (mut tmp, mut line) = (Vec::new(), Vec::new());
    for row in 0..out_h {
        sample_row(&sub, tap(row, h, out_h), ht, &mut tmp, &mut line);
        store(&line, row_mut(&mut out, row));
    }
    out
}

/// Draws `eye` scaled into placement `p`, with crosstalk against `other`
/// sampled at the same coordinates.
fn draw_placement(p: &Placement, eye: &Image, other: &Image, stage: Stage, out: &mut Image) {
    if p.width == 0 || p.height == 0 {
        return;
    }
    let (w, h) = (eye.width(), eye.height());
    let x0 = p.x as usize * 4;
    let span = p.width as usize * 4;
    let k = stage.crosstalk;

    let taps: Vec<Tap> = (0..p.width).map(|i| tap(i, w, p.width)).collect();
    let ht = (p.width != w).then_some(&taps[..]);
    let (mut a, mut b, mut tmp) = (Vec::new(), Vec::new(), Vec::new());
    for y in 0..p.height {
        let vt = tap(y, h, p.height);
        sample_row(eye, vt, ht, &mut tmp, &mut a);
        if k != 0.0 {
            sample_row(other, vt, ht, &mut tmp, &mut b);
            for (e, o) in a.iter_mut().zip(b.iter()) {
                for c in 0..3 {
                    e[c] = (e[c] - k * o[c]).max(0.0);
                }
            }
        }
        store(&a, &mut row_mut(out, p.y + y)[x0..x0 + span]);
    }
}

/// Rows, columns or checkerboard.
fn interleave(mode: OutputMode, l: &Image, r: &Image, stage: Stage, out: &mut Image) {
    let (w, h) = (l.width(), l.height());
    // Which eye pixel x of row y shows: left when (x·cx + y·cy) is even.
    let (cx, cy) = match mode {
        OutputMode::Rows => (0, 1),
        OutputMode::Columns => (1, 0),
        _ => (1, 1),
    };
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for y in 0..h {
        load(l.row(y), &mut a);
        load(r.row(y), &mut b);
        stage.apply(&mut a, &mut b);
        let dst = row_mut(out, y);
        for x in 0..w as usize {
            let src = if (x * cx + y as usize * cy) % 2 == 0 {
                &a
            } else {
                &b
            };
            store(&src[x..x + 1], &mut dst[x * 4..x * 4 + 4]);
        }
    }
}

/// The anaglyph variants.
#[derive(Clone, Copy)]
enum Anaglyph {
    Masked(AnaglyphColors, AnaglyphMethod),
    RedBlue,
}

/// sRGB decoding of the 256 unorm8 values, in 0…1.
fn decode_table() -> [f32; 256] {
    std::array::from_fn(|v| srgb_to_linear(v as f32 / 255.0))
}

fn anaglyph(kind: Anaglyph, l: &Image, r: &Image, stage: Stage, out: &mut Image) {
    let h = l.height();
    // Integral inputs (no saturation, no crosstalk) decode by table.
    let table = (stage.saturation == 1.0 && stage.crosstalk == 0.0).then(decode_table);
    let decode = |v: f32| match &table {
        Some(t) => t[v as usize],
        None => srgb_to_linear(v / 255.0),
    };
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for y in 0..h {
        load(l.row(y), &mut a);
        load(r.row(y), &mut b);
        stage.apply(&mut a, &mut b);
        let dst = row_mut(out, y);
        match kind {
            Anaglyph::RedBlue => {
                for ((d, p), q) in dst.chunks_exact_mut(4).zip(a.iter()).zip(b.iter()) {
                    d.copy_from_slice(&[unorm(luma(rgb(p))), 0, unorm(luma(rgb(q))), 255]);
                }
            }
            Anaglyph::Masked(colors, AnaglyphMethod::Dubois) => {
                let m: DuboisMatrices = dubois_matrices(colors);
                for ((d, p), q) in dst.chunks_exact_mut(4).zip(a.iter()).zip(b.iter()) {
                    let lin = |x: &Rgb| [decode(x[0]), decode(x[1]), decode(x[2])];
                    let o = dubois_pixel(&m, lin(p), lin(q));
                    d.copy_from_slice(&[
                        unorm(o[0] * 255.0),
                        unorm(o[1] * 255.0),
                        unorm(o[2] * 255.0),
                        255,
                    ]);
                }
            }
            Anaglyph::Masked(colors, method) => {
                let mask = colors.left_channels();
                let left_grey = method != AnaglyphMethod::FullColor;
                let right_grey = method == AnaglyphMethod::Monochrome;
                for ((d, p), q) in dst.chunks_exact_mut(4).zip(a.iter()).zip(b.iter()) {
                    let (yl, yr) = (luma(rgb(p)), luma(rgb(q)));
                    for c in 0..3 {
                        d[c] = unorm(match (mask[c], left_grey, right_grey) {
                            (true, false, _) => p[c],
                            (true, true, _) => yl,
                            (false, _, false) => q[c],
                            (false, _, true) => yr,
                        });
                    }
                    d[3] = 255;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halving_an_even_axis_taps_exactly_between_two_texels() {
        for i in 0..8 {
            let t = tap(i, 16, 8);
            assert_eq!(
                (t.i0, t.i1, t.f),
                (2 * i as usize, 2 * i as usize + 1, 0.5),
                "pixel {i}"
            );
        }
    }

    #[test]
    fn same_size_taps_are_exact_texels() {
        for i in 0..7 {
            let t = tap(i, 7, 7);
            assert_eq!((t.i0, t.f), (i as usize, 0.0), "pixel {i}");
        }
    }

    #[test]
    fn taps_clamp_to_the_edge() {
        // Squeezing 5 texels onto 3 pixels: centres 0.833, 2.5, 4.167.
        let t: Vec<Tap> = (0..3).map(|i| tap(i, 5, 3)).collect();
        assert_eq!((t[0].i0, t[0].i1), (0, 1));
        assert!((t[0].f - 0.333_333).abs() < 1e-5, "{:?}", t[0]);
        assert_eq!((t[1].i0, t[1].i1, t[1].f), (2, 3, 0.0));
        assert_eq!((t[2].i0, t[2].i1), (3, 4));
        assert!((t[2].f - 0.666_667).abs() < 1e-5, "{:?}", t[2]);
        // Magnifying 1 texel onto 2 pixels: both sides clamp to texel 0.
        for i in 0..2 {
            assert_eq!((tap(i, 1, 2).i0, tap(i, 1, 2).i1), (0, 0), "pixel {i}");
        }
    }

    #[test]
    fn unorm_rounds_half_up_and_clamps() {
        assert_eq!(unorm(-3.0), 0);
        assert_eq!(unorm(0.49), 0);
        assert_eq!(unorm(0.5), 1);
        assert_eq!(unorm(127.5), 128);
        assert_eq!(unorm(254.6), 255);
        assert_eq!(unorm(300.0), 255);
        for v in 0..=255u8 {
            assert_eq!(unorm(f32::from(v)), v, "integral {v}");
        }
    }

    #[test]
    fn luminance_anaglyphs_of_8_bit_eyes_follow_the_float_rules_exactly() {
        let (w, h) = (37, 5);
        let (l, r) = (
            crate::output::pattern::noise(w, h, 11),
            crate::output::pattern::noise(w, h, 12),
        );
        let y = |p: [u8; 4]| unorm(luma([p[0], p[1], p[2]].map(f32::from)));
        let mut modes = vec![(OutputMode::AnaglyphRedBlue, AnaglyphColors::RedCyan)];
        for c in AnaglyphColors::ALL {
            for m in [AnaglyphMethod::HalfColor, AnaglyphMethod::Monochrome] {
                modes.push((OutputMode::Anaglyph(c, m), c));
            }
        }
        for (mode, colors) in modes {
            let out = compose(mode, &OutputOptions::default(), &l, &r, 0).unwrap();
            for (px, py) in (0..h).flat_map(|py| (0..w).map(move |px| (px, py))) {
                let (p, q) = (l.get(px, py), r.get(px, py));
                let want = match mode {
                    OutputMode::AnaglyphRedBlue => [y(p), 0, y(q), 255],
                    OutputMode::Anaglyph(_, method) => {
                        let mask = colors.left_channels();
                        let mut v = [0, 0, 0, 255];
                        for c in 0..3 {
                            v[c] = match (mask[c], method == AnaglyphMethod::Monochrome) {
                                (true, _) => y(p),
                                (false, false) => q[c],
                                (false, true) => y(q),
                            };
                        }
                        v
                    }
                    _ => unreachable!(),
                };
                assert_eq!(out.get(px, py), want, "{mode} at ({px}, {py})");
            }
        }
    }

    #[test]
    fn decode_table_matches_the_curve() {
        let t = decode_table();
        assert_eq!(t[0], 0.0);
        assert_eq!(t[255], 1.0);
        assert_eq!(t[128], srgb_to_linear(128.0 / 255.0));
    }
}

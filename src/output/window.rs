//! The cheap ways to put a composite into a window, used by
//! [`super::gl::GlCompositor::compose_window`] before its shader passes.
//!
//! On a software renderer a full-screen shader pass is the expensive part
//! of a frame: llvmpipe takes 2.6–3.9 ms for the simplest one at
//! 1280x1024 and 5–10 ms for the compositor's kernels, while a same-size
//! glBlitFramebuffer, a glReadPixels and a glTexSubImage2D each take about
//! 0.2 ms and a CPU channel mask 0.3 ms (`examples/compose_paths.rs`,
//! `benches/compose.rs`). So, when the composite fills the window exactly
//! and every eye is a rectangle of the eye's size:
//!
//! - **Blit** (every renderer): `left`, `right`, `frame-sequential`,
//!   `side-by-side`, `top-bottom` and `hdmi-frame-packing` without
//!   crosstalk are copies of whole eyes, so each eye is one same-size
//!   glBlitFramebuffer (plus a clear of the gap for HDMI frame packing).
//!   A blit copies alpha, so this path is taken only when the window has
//!   no alpha bits (what a window shows has no alpha anyway).
//! - **CPU** (software renderers, where [`preferred_path`] picks the CPU):
//!   read the eyes back, compose them with [`cpu::compose_into`] into a
//!   reused image, upload it with one glTexSubImage2D and blit it. Modes
//!   whose pixels depend only on their own row (the anaglyphs, `columns`,
//!   the side-by-side ones) and the row-interleaved ones are composed in
//!   GL's bottom-first row order directly, so nothing is flipped; the
//!   others are flipped to the reference's top-first order and back.
//!
//! Both give exactly [`cpu::compose`]'s pixels: a blit of an unscaled eye
//! is a copy, and the CPU path is the reference itself. Everything else
//! (Dubois, crosstalk and saturation on same-size modes, a window of
//! another size, hardware renderers' composites) is left to the shaders.

use crate::backend::{PixelTarget, convert_row};
use crate::error::Result;
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::image::{Image, as_words, as_words_mut, flip_rows};
use crate::math::Eye;
use crate::profile::{self, Stage};
use crate::stereo::eye_memory::Rows;

use super::cpu;
use super::gl::{Canvas, ComposePath, Job, TexRect, preferred_path};
use super::layout::{Placement, composite_size, leaves_gaps, placements};
use super::mode::{AnaglyphMethod, OutputMode};
use super::options::OutputOptions;

/// Bytes of each eye read back at a time by the window paths that write
/// straight into the window's buffer: a band of both eyes stays in cache
/// between the read-back and the write (measured at 1280x1024 on llvmpipe:
/// 1.5 ms for read-back and mask in 128-row bands, 2.25 ms for whole eyes).
const BAND_BYTES: usize = 512 * 1024;

/// GL_ALPHA_BITS (compatibility profile): alpha bits of the draw framebuffer.
const GL_ALPHA_BITS: u32 = 0x0D55;

/// How a composite reaches the window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum WindowPath {
    /// One same-size blit per eye.
    Blit,
    /// Read back, compose on the CPU, upload, blit.
    Cpu,
}

/// The window path for `mode` with validated `options`, when the
/// composite fills the window exactly and no eye needs resampling; None
/// means the shader passes.
pub(crate) fn window_path(
    mode: OutputMode,
    options: &OutputOptions,
    software: bool,
    window_has_alpha: bool,
) -> Option<WindowPath> {
    let copies = matches!(
        mode,
        OutputMode::Left
            | OutputMode::Right
            | OutputMode::FrameSequential
            | OutputMode::SideBySide
            | OutputMode::TopBottom
            | OutputMode::HdmiFramePacking
    ) && (options.crosstalk == 0.0 || !mode.shows_both_eyes());
    if copies && !window_has_alpha {
        return Some(WindowPath::Blit);
    }
    if software
        && mode != OutputMode::Quad
        && preferred_path(true, mode, options) == ComposePath::Cpu
    {
        return Some(WindowPath::Cpu);
    }
    None
}

/// How a composite reaches a window that shows pixels from memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Plan {
    /// A plain channel mask of untouched eyes, written straight into the
    /// window's buffer from the eyes read back (one pass).
    Mask,
    /// Whole eyes copied into their places in the window's buffer.
    Copies,
    /// Composed on the CPU from the eyes read back, then written.
    Cpu,
    /// Composed by GL, read back, then written.
    Gl,
}

/// The plan for `mode` with validated `options` on a software renderer;
/// `unscaled`: every eye is a rectangle of the eye's size.
pub(crate) fn pixel_plan(mode: OutputMode, options: &OutputOptions, unscaled: bool) -> Plan {
    if !unscaled {
        return Plan::Gl;
    }
    let untouched = options.crosstalk == 0.0 && options.saturation == 1.0;
    match mode {
        OutputMode::Anaglyph(_, AnaglyphMethod::FullColor) if untouched => Plan::Mask,
        _ if window_path(mode, options, false, false) == Some(WindowPath::Blit) => Plan::Copies,
        _ if preferred_path(true, mode, options) == ComposePath::Cpu => Plan::Cpu,
        _ => Plan::Gl,
    }
}

/// How the CPU path orders rows: Some(swap) when composing GL's bottom-first
/// rows gives the bottom-first composite (swapping the eyes when `swap`,
/// which keeps the top-row parity of the interleaved modes on an even
/// height); None when the rows must be flipped to top-first and back.
fn bottom_first(mode: OutputMode, eye_height: u32) -> Option<bool> {
    match mode {
        OutputMode::Anaglyph(..)
        | OutputMode::AnaglyphRedBlue
        | OutputMode::Columns
        | OutputMode::Left
        | OutputMode::Right
        | OutputMode::FrameSequential
        | OutputMode::SideBySide
        | OutputMode::SideBySideHalf => Some(false),
        // Row 0 is the top row: counted from the bottom, its parity is that
        // of height − 1. compose(swap, L, R) == compose(R, L) in every mode,
        // crosstalk included.
        OutputMode::Rows | OutputMode::Checkerboard => Some(eye_height % 2 == 0),
        _ => None,
    }
}

/// Where the eyes of a copy mode (see [`window_path`]'s Blit) go: each
/// eye's placement in the composite and its rectangle, indexed by the eye
/// placed (at most one place each).
fn copies(job: &Job, options: &OutputOptions) -> [Option<(Placement, TexRect)>; 2] {
    let (w, h) = job.eye_size;
    let [left, right] = job.eyes;
    let (l, r) = if options.swap_eyes {
        (right, left)
    } else {
        (left, right)
    };
    let full = |eye| Placement {
        eye,
        x: 0,
        y: 0,
        width: w,
        height: h,
    };
    let mut draws = [None, None];
    let mut put =
        |p: Placement, rect: TexRect| draws[usize::from(p.eye == Eye::Right)] = Some((p, rect));
    match job.mode {
        OutputMode::Left => put(full(Eye::Left), l),
        OutputMode::Right => put(full(Eye::Right), r),
        OutputMode::FrameSequential => {
            // The eye accounts for the swap: pick from the unswapped inputs.
            let eye = options.frame_sequential_eye(job.frame_index);
            put(full(eye), if eye == Eye::Left { left } else { right });
        }
        mode => {
            for p in placements(mode, w, h).expect("a rectangle mode") {
                put(p, if p.eye == Eye::Left { l } else { r });
            }
        }
    }
    draws
}

/// Reused GL objects and buffers of the window paths (made on first use,
/// in the compositor context).
#[derive(Debug)]
pub(crate) struct WindowPaths {
    read_fbo: u32,
    upload: Canvas,
    eyes: [Image; 2],
    out: Image,
}

impl Default for WindowPaths {
    fn default() -> Self {
        WindowPaths {
            read_fbo: 0,
            upload: Canvas::default(),
            eyes: [Image::new(1, 1), Image::new(1, 1)],
            out: Image::new(1, 1),
        }
    }
}

/// Binds `texture` as the colour buffer of `fbo`, bound for reading.
///
/// # Safety
/// The compositor context must be current; `fbo` is one of its framebuffers.
unsafe fn read_from(gl: &Gl, fbo: u32, texture: u32) {
    // SAFETY: contract.
    unsafe {
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        gl.FramebufferTexture2D(
            GL_READ_FRAMEBUFFER,
            GL_COLOR_ATTACHMENT0,
            GL_TEXTURE_2D,
            texture,
            0,
        );
        gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    }
}

impl WindowPaths {
    /// Whether the draw framebuffer `framebuffer` (its `buffer`) has alpha
    /// bits (true when the driver does not say).
    ///
    /// # Safety
    /// The compositor context must be current.
    pub(crate) unsafe fn has_alpha(gl: &Gl, framebuffer: u32, buffer: u32) -> bool {
        // SAFETY: contract.
        unsafe {
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
            gl.DrawBuffer(buffer);
            gl.take_error();
            let bits = gl.integer(GL_ALPHA_BITS);
            gl.take_error() != GL_NO_ERROR || bits > 0
        }
    }

    /// Composes `job` (a composite that fills the `framebuffer`'s `buffer`
    /// exactly, eyes of the eye size) the way `path` says.
    ///
    /// # Safety
    /// The compositor context of the surface owning the job's textures must
    /// be current; `options` are the job's, validated.
    pub(crate) unsafe fn compose(
        &mut self,
        gl: &Gl,
        path: WindowPath,
        job: &Job,
        options: &OutputOptions,
        framebuffer: u32,
        buffer: u32,
    ) -> Result<()> {
        // SAFETY: contract.
        unsafe {
            gl.Disable(GL_SCISSOR_TEST);
            gl.Disable(GL_FRAMEBUFFER_SRGB);
            gl.ColorMask(1, 1, 1, 1);
            match path {
                WindowPath::Blit => self.blit_eyes(gl, job, options, framebuffer, buffer),
                WindowPath::Cpu => self.cpu(gl, job, options, framebuffer, buffer),
            }
        }
    }

    /// The framebuffer the eyes are read through, made on first use.
    ///
    /// # Safety
    /// The compositor context must be current.
    unsafe fn read_fbo(&mut self, gl: &Gl) -> u32 {
        if self.read_fbo == 0 {
            // SAFETY: contract.
            self.read_fbo = unsafe { gl.gen_framebuffer() };
        }
        self.read_fbo
    }

    unsafe fn blit_eyes(
        &mut self,
        gl: &Gl,
        job: &Job,
        options: &OutputOptions,
        framebuffer: u32,
        buffer: u32,
    ) -> Result<()> {
        let (w, h) = job.eye_size;
        let draws = copies(job, options);
        let (_, ch) = composite_size(job.mode, w, h);
        // SAFETY: the compositor context is current (contract of the callers).
        unsafe {
            let fbo = self.read_fbo(gl);
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
            gl.DrawBuffer(buffer);
            if leaves_gaps(job.mode, w, h) {
                gl.ClearColor(0.0, 0.0, 0.0, 1.0);
                gl.Clear(GL_COLOR_BUFFER_BIT);
            }
            for (p, src) in draws.into_iter().flatten() {
                debug_assert_eq!((p.width, p.height), (src.width, src.height));
                read_from(gl, fbo, src.texture);
                let y = (ch - p.y - p.height) as i32;
                gl.BlitFramebuffer(
                    src.x as i32,
                    src.y as i32,
                    (src.x + src.width) as i32,
                    (src.y + src.height) as i32,
                    p.x as i32,
                    y,
                    (p.x + p.width) as i32,
                    y + p.height as i32,
                    GL_COLOR_BUFFER_BIT,
                    GL_NEAREST,
                );
            }
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        }
        Ok(())
    }

    /// Reads the eyes back and composes them on the CPU into the reused
    /// image; returns it and whether its rows are bottom first.
    ///
    /// # Safety
    /// As [`WindowPaths::compose`]; the job's eyes are of the eye size.
    pub(crate) unsafe fn cpu_image(
        &mut self,
        gl: &Gl,
        job: &Job,
        options: &OutputOptions,
    ) -> Result<(&Image, bool)> {
        let (w, h) = job.eye_size;
        let order = bottom_first(job.mode, h);
        let same = job.eyes[1] == job.eyes[0];
        // SAFETY: contract.
        let fbo = unsafe { self.read_fbo(gl) };
        for (i, rect) in job.eyes.iter().enumerate().take(if same { 1 } else { 2 }) {
            let img = &mut self.eyes[i];
            img.resize(w, h, "read-back eye")?;
            // SAFETY: the present (or capture) finished the rendering into
            // the eyes, and the rows are used here, before any resize
            // (contract).
            if let Some(rows) = unsafe { job.rows_in_place(rect, w, h) } {
                // One copy from where the driver drew, flipped on the way
                // when the composite wants rows top first.
                profile::span(Stage::ReadBack, || {
                    rows.copy_to(img.pixels_mut(), order.is_none())
                });
                continue;
            }
            // SAFETY: the compositor context is current (contract); the
            // image holds w×h×4 bytes.
            profile::span(Stage::ReadBack, || unsafe {
                read_from(gl, fbo, rect.texture);
                gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
                gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
                gl.ReadPixels(
                    rect.x as i32,
                    rect.y as i32,
                    w as i32,
                    h as i32,
                    GL_RGBA,
                    GL_UNSIGNED_BYTE,
                    img.pixels_mut().as_mut_ptr().cast(),
                );
            });
            if order.is_none() {
                flip_rows(img.pixels_mut(), w as usize * 4);
            }
        }
        let mut opts = *options;
        if order == Some(true) {
            opts.swap_eyes = !opts.swap_eyes;
        }
        let [l, r] = &self.eyes;
        let r = if same { l } else { r };
        profile::span(Stage::Compose, || {
            cpu::compose_into(job.mode, &opts, l, r, job.frame_index, &mut self.out)
        })?;
        Ok((&self.out, order.is_some()))
    }

    /// Reads the compositor's capture framebuffer (`canvas`) into the
    /// reused image, rows bottom first as GL stores them.
    ///
    /// # Safety
    /// The compositor context must be current and `canvas` complete.
    pub(crate) unsafe fn read_canvas(&mut self, gl: &Gl, canvas: &Canvas) -> Result<&Image> {
        self.out
            .resize(canvas.width, canvas.height, "read-back composite")?;
        // SAFETY: contract; the image holds width×height×4 bytes.
        unsafe {
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, canvas.fbo);
            gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
            gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
            gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
            gl.ReadPixels(
                0,
                0,
                canvas.width as i32,
                canvas.height as i32,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                self.out.pixels_mut().as_mut_ptr().cast(),
            );
        }
        Ok(&self.out)
    }

    /// Reads the eye rectangles `rects` (each of `w` × `h`; None: not
    /// needed) back in bands of rows, bottom first, and calls `each` with
    /// the first GL row of the band and the bands (the same buffer for two
    /// equal rectangles). A band may hold more rows than remain. When
    /// every rectangle needed is one of the job's eyes in place
    /// ([`Job::in_place`]), nothing is read back: `each` is called once
    /// with the whole rectangles.
    ///
    /// # Safety
    /// As [`WindowPaths::compose`].
    unsafe fn bands(
        &mut self,
        gl: &Gl,
        job: &Job,
        rects: [Option<TexRect>; 2],
        w: u32,
        h: u32,
        mut each: impl FnMut(u32, [Option<Rows<'_>>; 2]),
    ) -> Result<()> {
        // SAFETY: the present finished the rendering into the eyes, and the
        // rows are used here, before any resize (contract).
        let placed = rects.map(|r| r.and_then(|r| unsafe { job.rows_in_place(&r, w, h) }));
        if rects
            .iter()
            .zip(&placed)
            .all(|(r, p)| r.is_none() || p.is_some())
        {
            profile::span(Stage::Compose, || each(0, placed));
            return Ok(());
        }
        let rows = ((BAND_BYTES / (w as usize * 4)).max(1) as u32).min(h);
        let same = rects[0].is_some() && rects[0] == rects[1];
        // SAFETY: contract.
        let fbo = unsafe {
            gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
            gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
            self.read_fbo(gl)
        };
        for img in &mut self.eyes {
            img.resize(w, rows, "band of an eye")?;
        }
        let mut y0 = 0;
        while y0 < h {
            let n = rows.min(h - y0);
            for (i, rect) in rects.iter().enumerate() {
                let Some(rect) = rect else { continue };
                if i == 1 && same {
                    continue;
                }
                // SAFETY: contract; the band holds w × rows × 4 bytes ≥ n rows.
                profile::span(Stage::ReadBack, || unsafe {
                    read_from(gl, fbo, rect.texture);
                    gl.ReadPixels(
                        rect.x as i32,
                        (rect.y + y0) as i32,
                        w as i32,
                        n as i32,
                        GL_RGBA,
                        GL_UNSIGNED_BYTE,
                        self.eyes[i].pixels_mut().as_mut_ptr().cast(),
                    );
                });
            }
            let band =
                |i: usize| rects[i].map(|_| Rows::of_image(&self.eyes[if same { 0 } else { i }]));
            profile::span(Stage::Compose, || each(y0, [band(0), band(1)]));
            y0 += n;
        }
        Ok(())
    }

    /// Writes the composite into a window's buffer by `plan` (not
    /// [`Plan::Gl`], which the compositor does itself).
    ///
    /// # Safety
    /// As [`WindowPaths::compose`]; the job's eyes are of the eye size and
    /// the target of the composite's size.
    pub(crate) unsafe fn fill(
        &mut self,
        gl: &Gl,
        plan: Plan,
        job: &Job,
        options: &OutputOptions,
        target: &mut PixelTarget<'_>,
    ) -> Result<()> {
        let (w, h) = job.eye_size;
        match plan {
            Plan::Mask => {
                let OutputMode::Anaglyph(colors, _) = job.mode else {
                    unreachable!("a mask plan is made for anaglyphs only")
                };
                let m = colors.left_channels().map(|b| if b { 0xFF } else { 0 });
                let left_mask = u32::from_le_bytes([m[0], m[1], m[2], 0]);
                let [mut l, mut r] = job.eyes;
                if options.swap_eyes {
                    std::mem::swap(&mut l, &mut r);
                }
                let layout = target.layout;
                // SAFETY: contract.
                unsafe {
                    self.bands(gl, job, [Some(l), Some(r)], w, h, |y0, [lb, rb]| {
                        let (lb, rb) = (lb.expect("left band"), rb.expect("right band"));
                        for k in 0..lb.height().min(h - y0) {
                            // GL rows count from the bottom, the window's from the top.
                            let dst = target.row_mut(h - 1 - (y0 + k));
                            mask_row(lb.row(k), rb.row(k), dst, left_mask, |v| layout.convert(v));
                        }
                    })?
                };
            }
            Plan::Copies => {
                let draws = copies(job, options);
                let places = draws.map(|d| d.map(|(p, _)| p));
                let sources = draws.map(|d| d.map(|(_, rect)| rect));
                if leaves_gaps(job.mode, w, h) {
                    let black = target.layout.convert(0);
                    for y in 0..target.size.1 {
                        fill_words(target.row_mut(y), black);
                    }
                }
                let layout = target.layout;
                // SAFETY: contract.
                unsafe {
                    self.bands(gl, job, sources, w, h, |y0, bands| {
                        for (p, band) in places.iter().zip(bands) {
                            let (Some(p), Some(band)) = (p, band) else {
                                continue;
                            };
                            let x0 = p.x as usize * 4;
                            for k in 0..band.height().min(h - y0) {
                                let row = p.y + (h - 1 - (y0 + k));
                                let dst = &mut target.row_mut(row)[x0..x0 + w as usize * 4];
                                convert_row(band.row(k), dst, layout);
                            }
                        }
                    })?
                };
            }
            Plan::Cpu => {
                // SAFETY: contract.
                let (img, bottom_first) = unsafe { self.cpu_image(gl, job, options)? };
                profile::span(Stage::Compose, || target.write_image(img, bottom_first));
            }
            Plan::Gl => unreachable!("the compositor composes GL plans"),
        }
        Ok(())
    }

    unsafe fn cpu(
        &mut self,
        gl: &Gl,
        job: &Job,
        options: &OutputOptions,
        framebuffer: u32,
        buffer: u32,
    ) -> Result<()> {
        // SAFETY: contract.
        let bottom = unsafe { self.cpu_image(gl, job, options)?.1 };
        let (cw, ch) = (self.out.width(), self.out.height());
        if !bottom {
            flip_rows(self.out.pixels_mut(), cw as usize * 4);
        }
        // SAFETY: as above; the image holds cw×ch×4 bytes.
        unsafe {
            self.upload.ensure(gl, cw, ch)?;
            gl.BindTexture(GL_TEXTURE_2D, self.upload.texture);
            gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
            gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
            gl.TexSubImage2D(
                GL_TEXTURE_2D,
                0,
                0,
                0,
                cw as i32,
                ch as i32,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                self.out.pixels().as_ptr().cast(),
            );
            gl.BindTexture(GL_TEXTURE_2D, 0);
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, self.upload.fbo);
            gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
            gl.DrawBuffer(buffer);
            gl.BlitFramebuffer(
                0,
                0,
                cw as i32,
                ch as i32,
                0,
                0,
                cw as i32,
                ch as i32,
                GL_COLOR_BUFFER_BIT,
                GL_NEAREST,
            );
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        }
        Ok(())
    }
}

/// One row of a plain channel-mask anaglyph: R, G, B from the left eye
/// where `left_mask` has ones, else from the right; each result word
/// (alpha 255) passed through `out` (a window's pixel layout).
fn mask_row(l: &[u8], r: &[u8], dst: &mut [u8], left_mask: u32, out: impl Fn(u32) -> u32) {
    let right_mask = !left_mask & 0x00FF_FFFF;
    let pixel = |p: u32, q: u32| out((p & left_mask) | (q & right_mask) | 0xFF00_0000);
    if let (Some(a), Some(b)) = (as_words(l), as_words(r)) {
        if let Some(d) = as_words_mut(dst) {
            for ((d, &p), &q) in d.iter_mut().zip(a).zip(b) {
                *d = pixel(p, q);
            }
            return;
        }
    }
    for ((d, p), q) in dst
        .chunks_exact_mut(4)
        .zip(l.chunks_exact(4))
        .zip(r.chunks_exact(4))
    {
        let w = |s: &[u8]| u32::from_le_bytes([s[0], s[1], s[2], s[3]]);
        d.copy_from_slice(&pixel(w(p), w(q)).to_le_bytes());
    }
}

/// Every pixel of a row set to one word.
fn fill_words(dst: &mut [u8], word: u32) {
    match as_words_mut(dst) {
        Some(d) => d.fill(word),
        None => dst
            .chunks_exact_mut(4)
            .for_each(|d| d.copy_from_slice(&word.to_le_bytes())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::pattern::noise;

    /// Composing bottom-first rows (eyes swapped where `bottom_first` says)
    /// gives the bottom-first composite, for every mode it allows, at odd
    /// and even heights.
    #[test]
    fn bottom_first_composition_is_the_flipped_composite() {
        for (w, h) in [(6, 4), (5, 7)] {
            let (l, r) = (noise(w, h, 3), noise(w, h, 4));
            let flipped = |img: &Image| {
                let mut f = img.clone();
                f.flip_vertical();
                f
            };
            for mode in OutputMode::all().filter(|&m| m != OutputMode::Quad) {
                let Some(swap) = bottom_first(mode, h) else {
                    continue;
                };
                for crosstalk in [0.0, 0.25] {
                    let options = OutputOptions {
                        crosstalk,
                        ..OutputOptions::default()
                    };
                    let want = flipped(&cpu::compose(mode, &options, &l, &r, 1).unwrap());
                    let opts = OutputOptions {
                        swap_eyes: swap,
                        ..options
                    };
                    let got = cpu::compose(mode, &opts, &flipped(&l), &flipped(&r), 1).unwrap();
                    assert_eq!(got, want, "{mode} at {w}x{h}, crosstalk {crosstalk}");
                }
            }
        }
    }

    #[test]
    fn copies_blit_only_without_alpha_and_crosstalk() {
        let plain = OutputOptions::default();
        let staged = OutputOptions {
            crosstalk: 0.2,
            ..plain
        };
        for m in [
            OutputMode::SideBySide,
            OutputMode::Left,
            OutputMode::HdmiFramePacking,
        ] {
            assert_eq!(
                window_path(m, &plain, false, false),
                Some(WindowPath::Blit),
                "{m}"
            );
            assert_eq!(window_path(m, &plain, false, true), None, "{m} with alpha");
            assert_eq!(
                window_path(m, &plain, true, true),
                Some(WindowPath::Cpu),
                "{m}"
            );
        }
        // Left shows one eye: crosstalk does not apply, it stays a copy.
        assert_eq!(
            window_path(OutputMode::Left, &staged, false, false),
            Some(WindowPath::Blit)
        );
        assert_eq!(
            window_path(OutputMode::SideBySide, &staged, false, false),
            None
        );
        let dubois = OutputMode::from_name("anaglyph-red-cyan-dubois").unwrap();
        assert_eq!(window_path(dubois, &plain, true, false), None);
        let red_cyan = OutputMode::from_name("anaglyph-red-cyan").unwrap();
        assert_eq!(
            window_path(red_cyan, &plain, true, false),
            Some(WindowPath::Cpu)
        );
        assert_eq!(window_path(red_cyan, &plain, false, false), None);
    }
}

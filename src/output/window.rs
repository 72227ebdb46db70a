//! The cheap ways to put a composite into a window: as pixels from memory
//! ([`WindowPaths::fill`], a software renderer's MIT-SHM image), or by
//! blits and one upload into the window's GL back buffer
//! ([`WindowPaths::compose`], used by
//! [`super::gl::GlCompositor::compose_window`] before its shader passes).
//!
//! On a software renderer a full-screen shader pass is the expensive part
//! of a frame: llvmpipe takes 2.6–3.9 ms for the simplest one at
//! 1280x1024 and 5–29 ms for the compositor's kernels, while a same-size
//! glBlitFramebuffer, a glReadPixels and a glTexSubImage2D each take about
//! 0.2 ms and the CPU composes any mode in 0.3–3 ms
//! (`examples/compose_paths.rs`, `benches/compose.rs`). So:
//!
//! - **Pixels** (software renderers whose window shows pixels from
//!   memory): every mode, with any options, composed on the CPU row by row
//!   straight into the window's buffer at the window's size
//!   ([`super::rows`]: letterboxed, scaled or cropped as
//!   [`super::layout::window_fit`] says, in the window's byte order), from
//!   the eyes where llvmpipe drew them ([`crate::stereo::eye_memory`]) or
//!   read back: in bands that stay in cache when every window row needs
//!   only its own eye rows, else whole.
//! - **Blit** (every renderer, GL windows): `left`, `right`,
//!   `frame-sequential`, `side-by-side`, `top-bottom` and
//!   `hdmi-frame-packing` without crosstalk are copies of whole eyes, so
//!   each eye is one same-size glBlitFramebuffer (plus a clear of the gap
//!   for HDMI frame packing). A blit copies alpha, so this path is taken
//!   only when the window has no alpha bits.
//! - **CPU** (software renderers, GL windows the composite's size): the
//!   composite made as for Pixels into a reused image, uploaded with one
//!   glTexSubImage2D and blitted.
//!
//! All give [`cpu::compose`]'s pixels (a blit of an unscaled eye is a
//! copy; the others are its kernels). Eyes in framing rectangles of
//! another size, windows of another size on a GL window, and hardware
//! renderers are left to the shaders.

use crate::backend::{PixelLayout, PixelTarget};
use crate::error::Result;
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::image::{Image, as_words_mut, flip_rows};
use crate::math::Eye;
use crate::profile::{self, Stage};
use crate::stereo::eye_memory::Rows;

use super::cpu;
use super::gl::{Canvas, ComposePath, Job, TexRect, preferred_path};
use super::kernels::Simd;
use super::layout::{Placement, composite_size, leaves_gaps, placements};
use super::mode::OutputMode;
use super::options::OutputOptions;
use super::rows::{EyeRows, Frame, MakeEyes, Scratch, Target};

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
    /// Composed on the CPU straight into the window's buffer.
    Rows,
    /// Composed by GL, read back, then written (eyes in framing rectangles
    /// of another size than the eye, which GL resamples first).
    Gl,
}

/// The plan on a software renderer; `unscaled`: every eye is a rectangle
/// of the eye's size.
pub(crate) fn pixel_plan(unscaled: bool) -> Plan {
    if unscaled { Plan::Rows } else { Plan::Gl }
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
    out: Image,
    rows: RowPaths,
}

impl Default for WindowPaths {
    fn default() -> Self {
        WindowPaths {
            read_fbo: 0,
            upload: Canvas::default(),
            out: Image::new(1, 1),
            rows: RowPaths {
                eyes: [Image::new(1, 1), Image::new(1, 1)],
                scratch: [Scratch::default(), Scratch::default()],
            },
        }
    }
}

/// What composing on the CPU reuses: the eyes read back (GL's row order,
/// whole or a band at a time) and the row kernels' buffers (the second
/// for the helper thread of a split write, [`Frame::write_split`]).
#[derive(Debug)]
struct RowPaths {
    eyes: [Image; 2],
    scratch: [Scratch; 2],
}

/// The composite of `job` fitted to a target of `size`, and the eyes it
/// reads (None for an eye it does not).
fn frame_of(job: &Job, options: &OutputOptions, size: (u32, u32)) -> (Frame, [Option<TexRect>; 2]) {
    let frame = Frame::new(job.mode, options, job.frame_index, job.eye_size, size);
    let reads = frame.reads();
    let rects = [0, 1].map(|i| reads[i].then_some(job.eyes[i]));
    (frame, rects)
}

/// A window's image as rows of 32-bit words.
fn words_of<'t>(target: &'t mut PixelTarget<'_>) -> Result<Target<'t>> {
    let size = target.size;
    let stride = target.stride / 4;
    match as_words_mut(target.data) {
        Some(words) if target.stride % 4 == 0 => Ok(Target {
            words,
            stride,
            size,
            first: 0,
        }),
        _ => Err(crate::error::Error::Gl(
            "the window's image is not made of aligned 32-bit pixels".into(),
        )),
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

    /// Composes `job` on the CPU into `out` (rows top first, resized to
    /// the composite), from the eyes in place or read back.
    ///
    /// # Safety
    /// As [`WindowPaths::compose`]; the job's eyes are of the eye size.
    pub(crate) unsafe fn cpu_image(
        &mut self,
        gl: &Gl,
        job: &Job,
        options: &OutputOptions,
        out: &mut Image,
    ) -> Result<()> {
        // SAFETY: contract.
        unsafe {
            let fbo = self.read_fbo(gl);
            self.rows.image(gl, fbo, job, options, out)
        }
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

    /// Writes the composite of `job` into a window's buffer, fitted to the
    /// window's size, by `plan` (not [`Plan::Gl`], which the compositor
    /// does itself). `made`: the job's eyes are made as they are read
    /// ([`MakeEyes`]).
    ///
    /// # Safety
    /// As [`WindowPaths::compose`]; the job's eyes are of the eye size.
    pub(crate) unsafe fn fill(
        &mut self,
        gl: &Gl,
        plan: Plan,
        job: &Job,
        options: &OutputOptions,
        target: &mut PixelTarget<'_>,
        made: Option<&dyn MakeEyes>,
    ) -> Result<()> {
        debug_assert_eq!(plan, Plan::Rows, "the compositor composes GL plans");
        let layout = target.layout;
        let mut target = words_of(target)?;
        // SAFETY: contract.
        unsafe {
            let fbo = self.read_fbo(gl);
            // One copy of the kernels per layout, each converting with
            // constants (a layout read per pixel keeps them scalar).
            match layout {
                PixelLayout::Bgrx => {
                    self.rows
                        .write(gl, fbo, job, options, &mut target, made, |v| {
                            PixelLayout::Bgrx.convert(v)
                        })
                }
                PixelLayout::Rgbx => {
                    self.rows
                        .write(gl, fbo, job, options, &mut target, made, |v| {
                            PixelLayout::Rgbx.convert(v)
                        })
                }
            }
        }
    }

    /// [`WindowPaths::fill`] of [`Plan::Rows`] when every eye the frame
    /// reads is in place: no GL call, so the program's context may be
    /// current instead of the compositor's. Ok(false), nothing written,
    /// when an eye would have to be read back.
    ///
    /// # Safety
    /// The rendering into the job's eyes has finished; they are of the eye
    /// size and stay allocated until this returns.
    pub(crate) unsafe fn fill_in_place(
        &mut self,
        job: &Job,
        options: &OutputOptions,
        target: &mut PixelTarget<'_>,
        made: Option<&dyn MakeEyes>,
    ) -> Result<bool> {
        let layout = target.layout;
        let mut target = words_of(target)?;
        let rows = &mut self.rows;
        // SAFETY: contract.
        Ok(unsafe {
            match layout {
                PixelLayout::Bgrx => rows.write_in_place(job, options, &mut target, made, |v| {
                    PixelLayout::Bgrx.convert(v)
                }),
                PixelLayout::Rgbx => rows.write_in_place(job, options, &mut target, made, |v| {
                    PixelLayout::Rgbx.convert(v)
                }),
            }
        })
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
        unsafe {
            let fbo = self.read_fbo(gl);
            self.rows.image(gl, fbo, job, options, &mut self.out)?;
        }
        // Rows top first, uploaded as they are and blitted upside down
        // (GL's rows are bottom first): no pass over the composite to turn
        // it over.
        let (cw, ch) = (self.out.width(), self.out.height());
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
                ch as i32,
                cw as i32,
                0,
                GL_COLOR_BUFFER_BIT,
                GL_NEAREST,
            );
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        }
        Ok(())
    }
}

impl RowPaths {
    /// Composes `job` into `target` (of any size: the composite is fitted
    /// to it) row by row, each word through `px`. The eyes the frame reads
    /// are taken in place when they are; else read back in bands of
    /// [`BAND_BYTES`] when every target row needs only its own eye rows
    /// (a band of both eyes stays in cache until it is composed), whole
    /// otherwise.
    ///
    /// # Safety
    /// As [`WindowPaths::compose`]; the job's eyes are of the eye size;
    /// `fbo` is a framebuffer of the compositor context.
    #[allow(clippy::too_many_arguments)]
    unsafe fn write(
        &mut self,
        gl: &Gl,
        fbo: u32,
        job: &Job,
        options: &OutputOptions,
        target: &mut Target<'_>,
        made: Option<&dyn MakeEyes>,
        px: impl Fn(u32) -> u32 + Copy + Send + Sync,
    ) -> Result<()> {
        // SAFETY: contract.
        if unsafe { self.write_in_place(job, options, target, made, px) } {
            return Ok(());
        }
        // Read back from where they are: made there first.
        if let Some(m) = made {
            m.in_place();
        }
        let (w, h) = job.eye_size;
        let (frame, rects) = frame_of(job, options, target.size);
        let all = 0..target.size.1;
        let band = if frame.row_local() {
            ((BAND_BYTES / (w as usize * 4)).max(1) as u32).min(h)
        } else {
            h
        };
        let same = rects[0].is_some() && rects[0] == rects[1];
        for img in &mut self.eyes {
            img.resize(w, band, "eye rows read back")?;
        }
        let mut y0 = 0;
        while y0 < h {
            let n = band.min(h - y0);
            for (i, rect) in rects.iter().enumerate() {
                if let (Some(rect), false) = (rect, i == 1 && same) {
                    // SAFETY: contract; the image holds w × band ≥ n rows.
                    unsafe { read_back(gl, fbo, rect, y0, n, &mut self.eyes[i]) };
                }
            }
            let view = |i: usize| {
                let img = &self.eyes[if same { 0 } else { i }];
                rects[i].and_then(|_| EyeRows::gl(Rows::of_image(img), y0, h))
            };
            let rows = if band == h {
                all.clone()
            } else {
                frame.rows_of_band(y0..y0 + n)
            };
            let eyes = [view(0), view(1)];
            profile::span(Stage::Compose, || {
                frame.write(eyes, rows, target, &mut self.scratch[0], px)
            });
            y0 += n;
        }
        Ok(())
    }

    /// [`RowPaths::write`] when every eye the frame reads is in place
    /// ([`Job::in_place`]): no GL call, so any context (or none) may be
    /// current. False, with nothing written, when an eye would have to be
    /// read back. Eyes `made` as they are read go straight into a
    /// row-local composite ([`Frame::write_split_made`]); for any other
    /// they are made in place first.
    ///
    /// # Safety
    /// The rendering into the eyes has finished, and the job's eyes are of
    /// the eye size and stay allocated until this returns.
    unsafe fn write_in_place(
        &mut self,
        job: &Job,
        options: &OutputOptions,
        target: &mut Target<'_>,
        made: Option<&dyn MakeEyes>,
        px: impl Fn(u32) -> u32 + Copy + Send + Sync,
    ) -> bool {
        let (w, h) = job.eye_size;
        let (frame, rects) = frame_of(job, options, target.size);
        // SAFETY: contract.
        let placed = rects.map(|r| r.and_then(|r| unsafe { job.rows_in_place(&r, w, h) }));
        let eyes = placed.map(|p| p.and_then(|rows| EyeRows::gl(rows, 0, h)));
        if !rects
            .iter()
            .zip(&eyes)
            .all(|(r, e)| r.is_none() || e.is_some())
        {
            return false;
        }
        if let Some(m) = made {
            let scratch = &mut self.scratch;
            if profile::span(Stage::Compose, || {
                frame.write_split_made(Simd::Avx512, m, target, scratch, px)
            }) {
                return true;
            }
            profile::span(Stage::FromDepth, || m.in_place());
        }
        let all = 0..target.size.1;
        profile::span(Stage::Compose, || {
            frame.write_split(eyes, all, target, &mut self.scratch, px)
        });
        true
    }

    /// [`WindowPaths::cpu_image`] (`fbo` as for [`RowPaths::write`]).
    ///
    /// # Safety
    /// As [`RowPaths::write`].
    unsafe fn image(
        &mut self,
        gl: &Gl,
        fbo: u32,
        job: &Job,
        options: &OutputOptions,
        out: &mut Image,
    ) -> Result<()> {
        let (w, h) = job.eye_size;
        let size = composite_size(job.mode, w, h);
        out.resize(size.0, size.1, "composite")?;
        let stride = size.0 as usize;
        match as_words_mut(out.pixels_mut()) {
            Some(words) => {
                let mut target = Target {
                    words,
                    stride,
                    size,
                    first: 0,
                };
                // SAFETY: contract.
                unsafe { self.write(gl, fbo, job, options, &mut target, None, |v| v) }
            }
            None => {
                // Not aligned words (a big-endian machine): the eyes read
                // back top first and composed by cpu::compose.
                let [l, r] = job.eyes.map(|rect| {
                    let mut img = Image::new(w, h);
                    // SAFETY: contract; the image holds w × h pixels.
                    unsafe { read_back(gl, fbo, &rect, 0, h, &mut img) };
                    flip_rows(img.pixels_mut(), w as usize * 4);
                    img
                });
                *out = cpu::compose(job.mode, options, &l, &r, job.frame_index)?;
                Ok(())
            }
        }
    }
}

/// Reads `n` rows of `rect` (of the image's width) from GL row `y0` into
/// `img` (at least that large), in GL's order.
///
/// # Safety
/// The compositor context is current; `fbo` is one of its framebuffers.
unsafe fn read_back(gl: &Gl, fbo: u32, rect: &TexRect, y0: u32, n: u32, img: &mut Image) {
    // SAFETY: contract; the image holds at least width × n × 4 bytes.
    profile::span(Stage::ReadBack, || unsafe {
        read_from(gl, fbo, rect.texture);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
        gl.ReadPixels(
            rect.x as i32,
            (rect.y + y0) as i32,
            img.width() as i32,
            n as i32,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            img.pixels_mut().as_mut_ptr().cast(),
        );
    });
}

#[cfg(test)]
mod tests {
    use super::*;

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
        // A software renderer composes every other mode on the CPU.
        let dubois = OutputMode::from_name("anaglyph-red-cyan-dubois").unwrap();
        assert_eq!(
            window_path(dubois, &staged, true, false),
            Some(WindowPath::Cpu)
        );
        let red_cyan = OutputMode::from_name("anaglyph-red-cyan").unwrap();
        assert_eq!(
            window_path(red_cyan, &plain, true, false),
            Some(WindowPath::Cpu)
        );
        assert_eq!(window_path(red_cyan, &plain, false, false), None);
    }
}

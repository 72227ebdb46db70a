//! `--auto=depth` at a present: the program rendered its frame once, mono,
//! into the left eye of its emulated framebuffer; here both eyes are made
//! from that colour and the depth of the frame's scene
//! ([`crate::reproject`]), in place, before the frame is composed and
//! shown as any other.
//!
//! Where the depth comes from, and how it maps to a shift, is what
//! automatic convergence already finds ([`crate::auto::converge`]): the
//! window's depth when a draw with a known perspective reached it (or a
//! copy of it taken before a later pass overwrote it), else the depth of
//! the render target that scene went into (a program that draws off
//! screen and composes the window with a full-screen pass), with the
//! projection of the frame's last perspective draw and the frame's depth
//! range, clip control and clear depth. Only the scene's viewport moves.
//! The convergence is the one `--auto` would draw with: the user's, or
//! automatic convergence's.

use crate::auto::converge::{Frame, Scene};
use crate::auto::eyes::DepthRows;
use crate::auto::live;
use crate::gl::Gl;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::output::MakeEyes;
use crate::output::helper::Alone;
use crate::output::kernels::Simd;
use crate::reproject::{self, RowScratch, Rule};
use crate::stereo::buffers::ColorBuffer;
use crate::stereo::emulated::EmulatedFramebuffer;
use crate::stereo::eye_memory::EyePixels;

/// The buffers of a context's frames made from depth, kept from frame to
/// frame (a frame allocates nothing once they have grown).
#[derive(Debug, Default)]
pub struct Scratch {
    depth: Vec<f32>,
    /// Each band's ([`Pending`]): the kernel's, and a row of depths.
    rows: [(RowScratch, Vec<f32>); 2],
    /// The eyes read back and made, where they are not in memory: left
    /// (and the overlays' scene), right.
    eyes: [Vec<u32>; 2],
}

/// How a frame's eyes were made ([`make`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Made {
    /// From the depth of the scene.
    FromDepth,
    /// Both eyes the frame (automatic stereo off, no scene this frame, a
    /// projection whose depth cannot be mapped).
    Flat,
}

/// Makes both eyes of `fb`'s front buffers from its front-left colour
/// (the program's mono frame) and the depth `frame` says holds the scene
/// (None: none drawn this frame). Where the eyes are memory the CPU reads
/// and writes (llvmpipe) they are not made here: the [`Pending`] given
/// back makes them as the composite reads them ([`MakeEyes`]), or in
/// place (an EGL context's too, whose window eglSwapBuffers shows); else
/// (a hardware renderer, a GL layer below, `GLSTEREO_EYE_MEMORY=0`) they
/// are read back, made and written again with GL here.
///
/// `switch_in` makes the layer's context (sharing the program's objects)
/// current: called before the first GL call, where one is needed (the
/// eyes or the depth not in memory). Errors from it come back.
///
/// # Safety
/// The program's rendering into `fb` has finished (glFinish), and its
/// context or the layer's is current. A [`Pending`] reads and writes the
/// eyes' memory: it is used before `fb` draws, resizes or goes, and
/// nothing else reads or writes the eyes meanwhile.
pub unsafe fn make(
    gl: &Gl,
    fb: &EmulatedFramebuffer,
    frame: Option<&Frame>,
    scratch: &mut Scratch,
    switch_in: &mut dyn FnMut() -> crate::Result<()>,
) -> crate::Result<(Made, Option<Pending>)> {
    let (Some(left), Some(right)) = (
        fb.pixels(ColorBuffer::FrontLeft),
        fb.pixels(ColorBuffer::FrontRight),
    ) else {
        switch_in()?;
        // SAFETY: contract.
        return unsafe { make_through_gl(gl, fb, frame, scratch) }.map(|m| (m, None));
    };
    let (w, h) = left.size();
    if right.size() != (w, h) {
        return Err(crate::Error::Gl("eyes of two sizes".into()));
    }
    let plan = match frame.filter(|_| live::auto_on()) {
        // SAFETY: contract.
        Some(f) => unsafe {
            let buffers = (&mut scratch.depth, &mut scratch.eyes);
            rule_of(gl, fb, f, (w, h), buffers, switch_in)?
        },
        None => None,
    };
    // SAFETY: contract: GL has finished with the eyes, and these are the
    // only views of their rows meanwhile.
    let eyes = unsafe { [EyeRows::of_memory(&left), EyeRows::of_memory(&right)] };
    let [Some(l), Some(r)] = eyes else {
        return Err(crate::Error::Gl("eye rows not aligned to words".into()));
    };
    let overlays = frame.is_some_and(|f| f.overlays);
    let pending = Pending::new(plan, overlays, [l, r], scratch);
    Ok((pending.made(), Some(pending)))
}

/// A band's kernel buffers and row of depths ([`Pending`]).
type Band = Mutex<(RowScratch, Vec<f32>)>;

/// A frame's eyes to make from its colour and depth ([`make`]): row by
/// row as a composite reads them (its [`MakeEyes`]), or all at once where
/// they are ([`MakeEyes::in_place`]). Give its buffers back with
/// [`Pending::finish`].
pub struct Pending {
    /// None: both eyes the frame.
    job: Option<Job>,
    eyes: [EyeRows; 2],
    /// The depths read back, rows bottom first (with [`Depths::Read`]).
    depth: Vec<f32>,
    /// Each band's kernel buffers and row of depths: one thread each.
    /// (Each alone on its cache lines: the kernel writes its vectors'
    /// lengths at every row.)
    bands: [Alone<Band>; 2],
    /// Made in place already.
    done: AtomicBool,
}

impl Pending {
    /// The eyes `eyes` (the left holding the frame's colour, the right,
    /// where the frame has `overlays`, the scene's before them) to make by
    /// `plan` (the rule, viewport and whether the scene is the window's:
    /// [`rule_of`]; None: both eyes the frame), with `scratch`'s buffers.
    fn new(
        plan: Option<Plan>,
        overlays: bool,
        eyes: [EyeRows; 2],
        scratch: &mut Scratch,
    ) -> Pending {
        let (w, h) = (eyes[0].width, eyes[0].height);
        let job = plan.and_then(
            |Plan {
                 rule,
                 viewport: (vx, vy, vw, vh),
                 window,
                 depth,
             }| {
                let columns = (
                    vx.clamp(0, w as i32) as usize,
                    (vx + vw).clamp(0, w as i32) as usize,
                );
                let rows = vy.clamp(0, h as i32) as usize..(vy + vh).clamp(0, h as i32) as usize;
                (columns.0 < columns.1 && !rows.is_empty()).then(|| Job {
                    rule,
                    columns,
                    rows,
                    // Overlays drawn over the window's scene: the pixels
                    // that differ from the scene's colour kept in the
                    // right eye's layer.
                    overlays: window && overlays,
                    simd: Simd::detected(),
                    memory: match depth {
                        Depths::Memory(rows, beside) => (Some(rows), beside),
                        Depths::Read(beside) => (None, beside),
                    },
                })
            },
        );
        let [a, b] = std::mem::take(&mut scratch.rows);
        Pending {
            job,
            eyes,
            depth: std::mem::take(&mut scratch.depth),
            bands: [Alone(Mutex::new(a)), Alone(Mutex::new(b))],
            done: AtomicBool::new(false),
        }
    }

    /// How the eyes are made.
    pub fn made(&self) -> Made {
        match self.job {
            Some(_) => Made::FromDepth,
            None => Made::Flat,
        }
    }

    /// Gives the buffers back to `scratch` (for the next frame).
    pub fn finish(self, scratch: &mut Scratch) {
        scratch.depth = self.depth;
        scratch.rows = self
            .bands
            .map(|b| b.0.into_inner().unwrap_or_else(|e| e.into_inner()));
    }

    /// The depths of row `y` (GL's order) of a frame made by `job`, in
    /// `row` or in the read-back, marked where overlays are.
    ///
    /// # Safety
    /// GL finished the frame (make's contract); y < the eyes' height.
    unsafe fn depths<'a>(
        &'a self,
        job: &Job,
        y: usize,
        row: &'a mut Vec<f32>,
        (colour, scene): (&[u32], &[u32]),
    ) -> &'a [f32] {
        let w = self.eyes[0].width;
        let read = || &self.depth[y * w..(y + 1) * w];
        match (&job.memory, job.overlays) {
            ((None, None), false) => read(),
            ((memory, beside), overlays) => {
                row.resize(w, 0.0);
                // At the frame's vector level: the conversions of the
                // depth words, the merge and the marks compiled for it.
                crate::output::kernels::with_simd(
                    job.simd,
                    #[inline(always)]
                    |_| {
                        match memory {
                            // SAFETY: contract; y < the depth's height (rule_of).
                            Some(rows) => unsafe { rows.read_row(y, row) },
                            None => row.copy_from_slice(read()),
                        }
                        if let Some(b) = beside {
                            // SAFETY: as above (rule_of: the window's size).
                            unsafe { b.nearer_row(y, row) };
                        }
                        if overlays {
                            reproject::mark_overlays(colour, scene, row);
                        }
                    },
                );
                row
            }
        }
    }

    /// Makes rows `ys` of the eyes where they are, with band `band`'s
    /// buffers.
    fn band_in_place(&self, band: usize, ys: std::ops::Range<usize>) {
        let mut guard = self.bands[band].lock().unwrap_or_else(|e| e.into_inner());
        let (scratch, row) = &mut *guard;
        for y in ys {
            // SAFETY: each band's rows are its own (in_place splits them);
            // no other view of the eyes is alive while they are made
            // (make's contract).
            let (l, r) = unsafe { (self.eyes[0].row(y), self.eyes[1].row(y)) };
            match &self.job {
                Some(job) if job.rows.contains(&y) => {
                    // SAFETY: make's contract; y < height.
                    let depth = unsafe { self.depths(job, y, row, (l, r)) };
                    let rule = &job.rule;
                    reproject::row_in_place(job.simd, rule, job.columns, l, depth, r, scratch);
                }
                _ => r.copy_from_slice(l),
            }
        }
    }
}

impl MakeEyes for Pending {
    fn size(&self) -> (u32, u32) {
        (self.eyes[0].width as u32, self.eyes[0].height as u32)
    }

    fn row(&self, band: usize, y: u32, [left, right]: [&mut [u32]; 2]) {
        let y = y as usize;
        // SAFETY: make's contract: the eyes are only read while rows are
        // made from them (in_place writes them, never at the same time).
        let (colour, scene) = unsafe { (&*self.eyes[0].row(y), &*self.eyes[1].row(y)) };
        match &self.job {
            Some(job) if job.rows.contains(&y) => {
                let mut guard = self.bands[band & 1]
                    .lock()
                    .unwrap_or_else(|e| e.into_inner());
                let (scratch, row) = &mut *guard;
                // SAFETY: make's contract; y < height (the compositor's
                // rows are the eyes').
                let depth = unsafe { self.depths(job, y, row, (colour, scene)) };
                reproject::row(
                    job.simd,
                    &job.rule,
                    job.columns,
                    colour,
                    depth,
                    [left, right],
                    scratch,
                );
            }
            _ => {
                left.copy_from_slice(colour);
                right.copy_from_slice(colour);
            }
        }
    }

    fn in_place(&self) {
        if self.done.swap(true, Ordering::AcqRel) {
            return;
        }
        let h = self.eyes[0].height;
        let mid = h / 2;
        let mut upper = || self.band_in_place(1, mid..h);
        if !crate::output::helper::both(|| self.band_in_place(0, 0..mid), &mut upper) {
            self.band_in_place(0, mid..h);
        }
    }
}

/// Rows of an eye, bottom first, as words: the eye's memory in place, or
/// a buffer read back.
#[derive(Clone, Copy)]
struct EyeRows {
    first: *mut u32,
    /// Words from one row to the next.
    stride: usize,
    width: usize,
    height: usize,
}

// SAFETY: a view of memory that [`EyeRows::row`]'s contract keeps to one
// thread per row.
unsafe impl Send for EyeRows {}
// SAFETY: as above.
unsafe impl Sync for EyeRows {}

impl EyeRows {
    /// The rows of an eye in memory; None where they are not aligned to
    /// words.
    ///
    /// # Safety
    /// As [`EyePixels::row_words_mut`], for as long as the rows are used.
    unsafe fn of_memory(eye: &EyePixels) -> Option<EyeRows> {
        let (w, h) = eye.size();
        // SAFETY: contract.
        let first = unsafe { eye.row_words_mut(0)? }.as_mut_ptr();
        let stride = if h > 1 {
            // SAFETY: as above.
            let second = unsafe { eye.row_words_mut(1)? }.as_mut_ptr();
            (second as usize - first as usize) / 4
        } else {
            w as usize
        };
        Some(EyeRows {
            first,
            stride,
            width: w as usize,
            height: h as usize,
        })
    }

    /// The rows of a buffer of `width` × `height` words.
    fn of_buffer(buffer: &mut [u32], width: usize, height: usize) -> EyeRows {
        assert!(buffer.len() >= width * height, "rows of the buffer");
        EyeRows {
            first: buffer.as_mut_ptr(),
            stride: width,
            width,
            height,
        }
    }

    /// Row `y`.
    ///
    /// # Safety
    /// `y` < height; no other view of the row is alive while it is used.
    #[allow(clippy::mut_from_ref)] // rows handed to one thread each
    unsafe fn row(&self, y: usize) -> &mut [u32] {
        assert!(y < self.height, "row {y} of {}", self.height);
        // SAFETY: contract; inside the rows (y < height).
        unsafe { std::slice::from_raw_parts_mut(self.first.add(y * self.stride), self.width) }
    }
}

/// How one frame's eyes are made ([`Pending`]).
struct Job {
    rule: Rule,
    columns: (usize, usize),
    rows: std::ops::Range<usize>,
    overlays: bool,
    simd: Simd,
    /// The depths in place (else in the read-back).
    /// The window's depth in place (None: read back), and where
    /// perspective draws with the depth test off wrote theirs
    /// ([`Depths`]).
    memory: (Option<DepthRows>, Option<DepthRows>),
}

/// [`make`] where the eyes are GL's own: the front-left (and, with
/// overlays, front-right) colour read back, both eyes made on the CPU
/// and written into the front textures.
///
/// # Safety
/// As [`make`].
unsafe fn make_through_gl(
    gl: &Gl,
    fb: &EmulatedFramebuffer,
    frame: Option<&Frame>,
    scratch: &mut Scratch,
) -> crate::Result<Made> {
    let (w, h) = fb.size();
    let n = w as usize * h as usize;
    let buffers = [ColorBuffer::FrontLeft, ColorBuffer::FrontRight];
    let textures = buffers.map(|b| fb.texture(b));
    if n == 0 || textures.contains(&0) {
        return Err(crate::Error::invalid_operation(
            "no front buffers to make eyes in",
        ));
    }
    let plan = match frame.filter(|_| live::auto_on()) {
        // SAFETY: contract.
        Some(f) => unsafe {
            let buffers = (&mut scratch.depth, &mut scratch.eyes);
            rule_of(gl, fb, f, (w, h), buffers, &mut || Ok(()))?
        },
        None => None,
    };
    let overlays = plan.as_ref().is_some_and(|m| m.window) && frame.is_some_and(|f| f.overlays);
    let [left, right] = &mut scratch.eyes;
    // SAFETY: contract.
    unsafe {
        read_eye(gl, fb, buffers[0], left)?;
        if overlays {
            read_eye(gl, fb, buffers[1], right)?;
        } else {
            right.clear();
            right.resize(n, 0);
        }
    }
    let (uw, uh) = (w as usize, h as usize);
    let eyes = [
        EyeRows::of_buffer(left, uw, uh),
        EyeRows::of_buffer(right, uw, uh),
    ];
    let pending = Pending::new(plan, overlays, eyes, scratch);
    pending.in_place();
    let done = pending.made();
    pending.finish(scratch);
    // SAFETY: contract; each buffer holds w × h words.
    unsafe {
        for (texture, eye) in textures.into_iter().zip(&scratch.eyes) {
            write_texture(gl, texture, (w, h), eye);
        }
    }
    Ok(done)
}

/// Reads the front buffer `buffer` of `fb` into `out` as words, rows
/// bottom first.
///
/// # Safety
/// As [`make`], the layer's context current.
unsafe fn read_eye(
    gl: &Gl,
    fb: &EmulatedFramebuffer,
    buffer: ColorBuffer,
    out: &mut Vec<u32>,
) -> crate::Result<()> {
    let (w, h) = fb.size();
    out.clear();
    out.resize(w as usize * h as usize, 0);
    // SAFETY: contract; the words are w × h × 4 bytes.
    unsafe { fb.read_pixels_as_gl(gl, buffer, crate::image::as_bytes_mut(out)) }
}

/// Writes `pixels` (rows bottom first) into the RGBA8 texture `texture`.
///
/// # Safety
/// As [`make`]; `pixels` holds `w` × `h` words.
unsafe fn write_texture(gl: &Gl, texture: u32, (w, h): (u32, u32), pixels: &[u32]) {
    use crate::gl::enums::*;
    // SAFETY: contract.
    unsafe {
        gl.BindTexture(GL_TEXTURE_2D, texture);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl.TexSubImage2D(
            GL_TEXTURE_2D,
            0,
            0,
            0,
            w as i32,
            h as i32,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            pixels.as_ptr().cast(),
        );
        gl.BindTexture(GL_TEXTURE_2D, 0);
    }
}

/// The rule of `frame`'s scene, its viewport and whether it is the
/// window's, with the scene's depth read into `depth` (`w` × `h` window
/// depths, rows bottom first), marked where overlays were drawn into its
/// render target (`colour`: buffers to read the target's colour into);
/// None where the frame's depth cannot be mapped to a shift.
///
/// # Safety
/// As [`make`].
unsafe fn rule_of(
    gl: &Gl,
    fb: &EmulatedFramebuffer,
    frame: &Frame,
    (w, h): (u32, u32),
    (depth, colour): (&mut Vec<f32>, &mut [Vec<u32>; 2]),
    switch_in: &mut dyn FnMut() -> crate::Result<()>,
) -> crate::Result<Option<Plan>> {
    let Some(eyes) = fb.layered() else {
        return Ok(None);
    };
    let window = frame.window.map(|(scene, copy)| {
        let source = match copy {
            Some(c) => eyes.attachments().with_depth_copy(c),
            None => eyes.attachments(),
        };
        // The window's own depth, not overwritten since the scene: in
        // place where it is memory.
        let memory = copy.is_none().then(|| eyes.left_depth()).flatten();
        // The depth of the perspective draws made with the depth test off
        // (no other draw writes there): nearer wins, with the far plane
        // as the clear depth, where "nothing" is farthest.
        let beside = eyes
            .right_depth()
            .filter(|_| frame.depth_beside && frame.clear_depth == 1.0);
        (source, (w, h), scene, Some((memory, beside)))
    });
    // A scene of known projection first, the window's before a target's
    // (as automatic convergence chooses: [`crate::auto::converge`]).
    let target = frame.target.map(|(t, size, scene)| (t, size, scene, None));
    let mut places: Vec<_> = window.into_iter().chain(target).collect();
    places.sort_by_key(|(_, _, scene, _)| scene.perspective.is_none());
    let Some((source, size, scene, in_window)) = places.into_iter().next() else {
        return Ok(None);
    };
    if size != (w, h) {
        crate::report::tell(&format!(
            "--auto=depth: the scene's depth is {}x{}, the window {w}x{h}: this frame is flat",
            size.0, size.1
        ));
        return Ok(None);
    }
    let (memory, beside) = in_window.unwrap_or((None, None));
    if beside.is_some_and(|b| b.size() != (w as usize, h as usize)) {
        return Ok(None);
    }
    if !frame.depth_written && beside.is_none() {
        // Said always where the scene is known to be in perspective (a 3D
        // scene lost); with -v only where its projection cannot be seen
        // (it may be a picture of w = 1 drawn by a shader of its own).
        let say = if scene.perspective.is_some() {
            crate::report::warn
        } else {
            crate::report::tell
        };
        say(
            "--auto=depth: this frame's scene wrote no depth (its draws have the depth test or \
             depth writes off), so no eye can be made from it: it is flat; --auto renders \
             each eye",
        );
        return Ok(None);
    }
    let Some(rule) = rule_for(frame, &scene) else {
        return Ok(None);
    };
    let plan = |depth| Plan {
        rule,
        viewport: scene.viewport,
        window: in_window.is_some(),
        depth,
    };
    if !frame.depth_written {
        // No draw wrote the window's depth: it holds nothing of this frame
        // (a program that never clears it). The depth beside alone.
        return Ok(beside.map(|b| plan(Depths::Memory(b, None))));
    }
    if let Some(rows) = memory.filter(|m| m.size() == (w as usize, h as usize)) {
        crate::report::tell(
            "--auto=depth: the window's depth is read in place (memory shared with the \
             renderer)",
        );
        return Ok(Some(plan(Depths::Memory(rows, beside))));
    }
    switch_in()?;
    // SAFETY: contract; the rectangle is the whole of the eyes.
    let read =
        unsafe { source.read_left_depth(gl, fb.read_fbo(), (0, 0, w as i32, h as i32), depth) };
    let read = read && depth.len() >= w as usize * h as usize;
    if let Some(array) = frame
        .target_overlays
        .filter(|_| read && in_window.is_none())
    {
        // Overlays drawn into the scene's target: the pixels they changed
        // stay at the screen, as the window's (the target is the window's
        // size, its pixels where the window shows them).
        let [now, before] = colour;
        let size = (w as i32, h as i32);
        // SAFETY: contract; the array is the target's, of the window's size.
        unsafe {
            source.read_colour_layer(gl, fb.read_fbo(), (array, 0), size, now);
            source.read_colour_layer(gl, fb.read_fbo(), (array, 1), size, before);
        }
        // A pass over most of the target (a fog, an occlusion term
        // blended over the scene) is the scene's, not an overlay: it
        // moves with the scene as before.
        let changed = now
            .iter()
            .zip(before.iter())
            .filter(|(a, b)| a != b)
            .count();
        if changed <= now.len() / 2 {
            reproject::mark_overlays(now, before, depth);
            crate::report::tell(
                "--auto=depth: overlays drawn into the scene's render target stay at the screen",
            );
        } else {
            crate::report::tell(
                "--auto=depth: draws after the scene changed most of its render target (a pass \
                 over the scene, not overlays): they move with the scene",
            );
        }
    }
    Ok(read.then(|| plan(Depths::Read(beside))))
}

/// How a frame's eyes are made ([`rule_of`]).
struct Plan {
    rule: Rule,
    /// The scene's viewport: what moves.
    viewport: (i32, i32, i32, i32),
    /// The scene is the window's (overlays over it are told apart).
    window: bool,
    depth: Depths,
}

/// Where a frame's depths are.
#[derive(Clone, Copy)]
enum Depths {
    /// Read back into the scratch buffer, rows bottom first; with the
    /// depth array's second layer where perspective draws with the depth
    /// test off wrote theirs.
    Read(Option<DepthRows>),
    /// The window's depth in place, and the depth array's second layer
    /// where perspective draws with the depth test off wrote theirs.
    Memory(DepthRows, Option<DepthRows>),
}

/// The rule `--auto` draws `scene` of `frame` with, as a shift of window
/// depth: its separation, its convergence (the user's, or automatic
/// convergence's as a distance or as a depth).
pub fn rule_for(frame: &Frame, scene: &Scene) -> Option<Rule> {
    let k = frame.left_shift.abs() * f64::from(scene.viewport.2) / 2.0;
    let chosen = live::convergence().map(f64::from);
    let automatic = live::automatic_convergence().map(f64::from);
    let depth = live::automatic_depth().map(|(z, a)| (f64::from(z), f64::from(a)));
    let (range, zto, clear) = (frame.depth_range, frame.zero_to_one, frame.clear_depth);
    match scene.perspective {
        Some(p) => {
            let c = chosen
                .or(automatic)
                .or_else(|| depth.and_then(|(z, _)| p.distance_at(z)))
                .unwrap_or(0.0);
            Rule::perspective(p.terms(), k, c, range, zto, clear)
        }
        None => match (chosen, automatic, depth) {
            (None, _, Some(zc)) => Rule::depth_form(k, zc, range, zto, clear),
            // Convergence 0, NV_3dvision_settings' initial one: every
            // point e·s·w over in clip space, e·s in NDC, behind the screen.
            (None, None, None) => Some(Rule::constant(k, clear)),
            _ => {
                crate::report::warn(
                    "--auto=depth: this program's projection cannot be seen (matrices in \
                     buffers or built in its shaders), so a convergence given as a distance \
                     cannot be placed in its depth: its frames are flat; use --convergence \
                     auto (the default), or --auto",
                );
                None
            }
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::fits::Rng;

    /// A frame of `w` × `h`: colour noise; the scene's colour, equal but
    /// where overlays were drawn over it; depths of a ground, near boxes
    /// and nothing drawn.
    fn frame(w: usize, h: usize, rng: &mut Rng) -> (Vec<u32>, Vec<u32>, Vec<f32>) {
        let colour: Vec<u32> = (0..w * h).map(|_| rng.next() as u32).collect();
        let scene = colour
            .iter()
            .map(|&c| if rng.next() % 13 == 0 { c ^ 0xFF } else { c })
            .collect();
        let depth = (0..w * h)
            .map(|i| match rng.next() % 10 {
                0 => 1.0,
                1..=3 => 0.2,
                _ => 0.5 + 0.4 * ((i / w) as f32 / h as f32),
            })
            .collect();
        (colour, scene, depth)
    }

    #[test]
    fn eyes_made_as_the_composite_reads_them_are_the_eyes_made_in_place() {
        let _turn = crate::output::helper::turn();
        let mut rng = Rng(0xF0_5ED);
        let mut scratch = Scratch::default();
        for (w, h) in [
            (1, 1),
            (1, 7),
            (9, 1),
            (3, 2),
            (64, 48),
            (257, 33),
            (800, 61),
        ] {
            for (overlays, viewport) in [
                (true, (0, 0, w as i32, h as i32)),
                (false, (2, 1, w as i32 - 3, h as i32 - 1)),
                (true, (-5, -5, 4 * w as i32, 3)),
            ] {
                let (colour, scene, depth) = frame(w, h, &mut rng);
                let rule = Rule {
                    offset: -6.0,
                    slope: 14.0,
                    clear: 1.0,
                    clear_step: 1e-7,
                };
                let plan = || Plan {
                    rule,
                    viewport,
                    window: true,
                    depth: Depths::Read(None),
                };
                // Made as read: row by row, the eyes left as they were.
                let (mut l, mut r) = (colour.clone(), scene.clone());
                scratch.depth.clone_from(&depth);
                let eyes = [
                    EyeRows::of_buffer(&mut l, w, h),
                    EyeRows::of_buffer(&mut r, w, h),
                ];
                let pending = Pending::new(Some(plan()), overlays, eyes, &mut scratch);
                // (A viewport of no pixels here: flat.)
                let inside = |a: i32, n: i32, size| a.clamp(0, size) < (a + n).clamp(0, size);
                let some = inside(viewport.0, viewport.2, w as i32)
                    && inside(viewport.1, viewport.3, h as i32);
                let want = if some { Made::FromDepth } else { Made::Flat };
                assert_eq!(pending.made(), want, "{w}x{h} {viewport:?}");
                let (mut rows_l, mut rows_r) = (vec![0; w * h], vec![0; w * h]);
                for y in 0..h {
                    let band = y % 2;
                    let out = [
                        &mut rows_l[y * w..(y + 1) * w],
                        &mut rows_r[y * w..(y + 1) * w],
                    ];
                    pending.row(band, y as u32, out);
                }
                pending.finish(&mut scratch);
                assert!(
                    l == colour && r == scene,
                    "rows made leave the eyes as they are"
                );
                // Made in place.
                scratch.depth.clone_from(&depth);
                let eyes = [
                    EyeRows::of_buffer(&mut l, w, h),
                    EyeRows::of_buffer(&mut r, w, h),
                ];
                let pending = Pending::new(Some(plan()), overlays, eyes, &mut scratch);
                pending.in_place();
                pending.in_place();
                pending.finish(&mut scratch);
                assert!(
                    l == rows_l && r == rows_r,
                    "{w}x{h}, overlays {overlays}, viewport {viewport:?}"
                );
                // Some pixel moved: the eyes differ from the frame.
                if w >= 64 && some {
                    assert!(l != colour && r != colour, "{w}x{h}: at depth");
                }
            }
        }
    }

    #[test]
    fn a_flat_frame_gives_the_frame_in_both_eyes_made_either_way() {
        let mut rng = Rng(7);
        let (w, h) = (33, 5);
        let (colour, scene, _) = frame(w, h, &mut rng);
        let mut scratch = Scratch::default();
        let (mut l, mut r) = (colour.clone(), scene);
        let eyes = [
            EyeRows::of_buffer(&mut l, w, h),
            EyeRows::of_buffer(&mut r, w, h),
        ];
        let pending = Pending::new(None, true, eyes, &mut scratch);
        assert_eq!(pending.made(), Made::Flat);
        let (mut a, mut b) = (vec![0; w], vec![0; w]);
        pending.row(1, 3, [&mut a, &mut b]);
        assert!(a == colour[3 * w..4 * w] && b == a);
        pending.in_place();
        pending.finish(&mut scratch);
        assert!(l == colour && r == colour);
    }
}

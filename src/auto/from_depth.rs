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
use crate::auto::eyes::Attachments;
use crate::auto::live;
use crate::gl::Gl;
use crate::output::kernels::Simd;
use crate::reproject::{self, Rule, RowScratch};
use crate::stereo::buffers::ColorBuffer;
use crate::stereo::emulated::EmulatedFramebuffer;
use crate::stereo::eye_memory::EyePixels;

/// The buffers of a context's frames made from depth, kept from frame to
/// frame (a frame allocates nothing once they have grown).
#[derive(Debug, Default)]
pub struct Scratch {
    depth: Vec<f32>,
    row: RowScratch,
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
/// (None: none drawn this frame): in place where the eyes are memory the
/// CPU reads and writes (llvmpipe), else read back and written again
/// with GL (a hardware renderer, an OpenGL ES context,
/// `GLSTEREO_EYE_MEMORY=0`).
///
/// # Safety
/// The layer's context, sharing the program's objects, is current; the
/// program's rendering into `fb` has finished (glFinish).
pub unsafe fn make(
    gl: &Gl,
    fb: &EmulatedFramebuffer,
    frame: Option<&Frame>,
    scratch: &mut Scratch,
) -> crate::Result<Made> {
    let (Some(left), Some(right)) = (
        fb.pixels(ColorBuffer::FrontLeft),
        fb.pixels(ColorBuffer::FrontRight),
    ) else {
        // SAFETY: contract.
        return unsafe { make_through_gl(gl, fb, frame, scratch) };
    };
    let (w, h) = left.size();
    if right.size() != (w, h) {
        return Err(crate::Error::Gl("eyes of two sizes".into()));
    }
    let made = match frame.filter(|_| live::auto_on()) {
        // SAFETY: contract.
        Some(f) => unsafe { rule_of(gl, fb, f, (w, h), &mut scratch.depth) },
        None => None,
    };
    // Overlays drawn over the window's scene: the pixels that differ from
    // the scene's colour kept in the right eye's layer.
    let overlays = frame.is_some_and(|f| f.overlays)
        && made.as_ref().is_some_and(|(_, _, window)| *window);
    // SAFETY: contract: GL has finished with the eyes, and these rows are
    // the only views of them meanwhile.
    unsafe {
        match made {
            Some((rule, (vx, vy, vw, vh), _)) => {
                let columns = (
                    vx.clamp(0, w as i32) as usize,
                    (vx + vw).clamp(0, w as i32) as usize,
                );
                let rows = vy.clamp(0, h as i32) as u32..(vy + vh).clamp(0, h as i32) as u32;
                let simd = Simd::detected();
                for y in 0..h {
                    let (Some(l), Some(r)) = (left.row_words_mut(y), right.row_words_mut(y))
                    else {
                        return Err(crate::Error::Gl("eye rows not aligned to words".into()));
                    };
                    if rows.contains(&y) && columns.0 < columns.1 {
                        let at = y as usize * w as usize;
                        let depth = &mut scratch.depth[at..at + w as usize];
                        if overlays {
                            reproject::mark_overlays(l, r, depth);
                        }
                        reproject::row_in_place(
                            simd,
                            &rule,
                            columns,
                            l,
                            depth,
                            r,
                            &mut scratch.row,
                        );
                    } else {
                        r.copy_from_slice(l);
                    }
                }
                Ok(Made::FromDepth)
            }
            None => {
                copy_left_to_right(&left, &right, h)?;
                Ok(Made::Flat)
            }
        }
    }
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
    let textures = [ColorBuffer::FrontLeft, ColorBuffer::FrontRight].map(|b| fb.texture(b));
    if n == 0 || textures.contains(&0) {
        return Err(crate::Error::invalid_operation("no front buffers to make eyes in"));
    }
    let made = match frame.filter(|_| live::auto_on()) {
        // SAFETY: contract.
        Some(f) => unsafe { rule_of(gl, fb, f, (w, h), &mut scratch.depth) },
        None => None,
    };
    let Some((rule, (vx, vy, vw, vh), window)) = made else {
        // Both eyes the frame: one copy on the GPU's side.
        // SAFETY: contract.
        unsafe { read_texture(gl, fb, textures[0], (w, h), &mut scratch.eyes[0])? };
        // SAFETY: as above; the buffer holds w × h words.
        unsafe { write_texture(gl, textures[1], (w, h), &scratch.eyes[0]) };
        return Ok(Made::Flat);
    };
    let overlays = window && frame.is_some_and(|f| f.overlays);
    let [left, right] = &mut scratch.eyes;
    // SAFETY: contract.
    unsafe {
        read_texture(gl, fb, textures[0], (w, h), left)?;
        if overlays {
            read_texture(gl, fb, textures[1], (w, h), right)?;
        } else {
            right.clear();
            right.resize(n, 0);
        }
    }
    let columns = (
        vx.clamp(0, w as i32) as usize,
        (vx + vw).clamp(0, w as i32) as usize,
    );
    let rows = vy.clamp(0, h as i32) as usize..(vy + vh).clamp(0, h as i32) as usize;
    let simd = Simd::detected();
    let w = w as usize;
    for (y, ((l, r), depth)) in left
        .chunks_exact_mut(w)
        .zip(right.chunks_exact_mut(w))
        .zip(scratch.depth.chunks_exact_mut(w))
        .enumerate()
    {
        if rows.contains(&y) && columns.0 < columns.1 {
            if overlays {
                reproject::mark_overlays(l, r, depth);
            }
            reproject::row_in_place(simd, &rule, columns, l, depth, r, &mut scratch.row);
        } else {
            r.copy_from_slice(l);
        }
    }
    // SAFETY: contract; each buffer holds w × h words.
    unsafe {
        write_texture(gl, textures[0], fb.size(), left);
        write_texture(gl, textures[1], fb.size(), right);
    }
    Ok(Made::FromDepth)
}

/// Reads the RGBA8 texture `texture` (`size`) into `out`, rows bottom
/// first, through `fb`'s read framebuffer.
///
/// # Safety
/// As [`make`].
unsafe fn read_texture(
    gl: &Gl,
    fb: &EmulatedFramebuffer,
    texture: u32,
    (w, h): (u32, u32),
    out: &mut Vec<u32>,
) -> crate::Result<()> {
    use crate::gl::enums::*;
    out.clear();
    out.resize(w as usize * h as usize, 0);
    // SAFETY: contract; `out` holds w × h words.
    unsafe {
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fb.read_fbo());
        gl.FramebufferTexture2D(
            GL_READ_FRAMEBUFFER,
            GL_COLOR_ATTACHMENT0,
            GL_TEXTURE_2D,
            texture,
            0,
        );
        gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
        gl.ReadPixels(
            0,
            0,
            w as i32,
            h as i32,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            out.as_mut_ptr().cast(),
        );
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        gl.check("reading the frame for --auto=depth")
    }
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

/// Both eyes the left one.
///
/// # Safety
/// As [`make`].
unsafe fn copy_left_to_right(left: &EyePixels, right: &EyePixels, h: u32) -> crate::Result<()> {
    for y in 0..h {
        // SAFETY: contract of the caller.
        let (Some(l), Some(r)) = (unsafe { left.row_words_mut(y) }, unsafe {
            right.row_words_mut(y)
        }) else {
            return Err(crate::Error::Gl("eye rows not aligned to words".into()));
        };
        r.copy_from_slice(l);
    }
    Ok(())
}

/// The rule of `frame`'s scene, its viewport and whether it is the
/// window's, with the scene's depth read into `depth` (`w` × `h` window
/// depths, rows bottom first); None where the frame's depth cannot be
/// mapped to a shift.
///
/// # Safety
/// As [`make`].
unsafe fn rule_of(
    gl: &Gl,
    fb: &EmulatedFramebuffer,
    frame: &Frame,
    (w, h): (u32, u32),
    depth: &mut Vec<f32>,
) -> Option<(Rule, (i32, i32, i32, i32), bool)> {
    let eyes = fb.layered()?;
    let window = frame.window.map(|(scene, copy)| {
        let source = match copy {
            Some(c) => eyes.attachments().with_depth_copy(c),
            None => eyes.attachments(),
        };
        (source, (w, h), scene, true)
    });
    // A scene of known projection first, the window's before a target's
    // (as automatic convergence chooses: [`crate::auto::converge`]).
    let target = frame.target.map(|(t, size, scene)| (t, size, scene, false));
    let mut places: Vec<(Attachments, (u32, u32), Scene, bool)> =
        window.into_iter().chain(target).collect();
    places.sort_by_key(|(_, _, scene, _)| scene.perspective.is_none());
    let (source, size, scene, in_window) = places.into_iter().next()?;
    if size != (w, h) {
        crate::report::tell(&format!(
            "--auto=depth: the scene's depth is {}x{}, the window {w}x{h}: this frame is flat",
            size.0, size.1
        ));
        return None;
    }
    let rule = rule_for(frame, &scene)?;
    // SAFETY: contract; the rectangle is the whole of the eyes.
    let read = unsafe { source.read_left_depth(gl, fb.read_fbo(), (0, 0, w as i32, h as i32), depth) };
    (read && depth.len() >= w as usize * h as usize).then_some((rule, scene.viewport, in_window))
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
                crate::report::tell(
                    "--auto=depth: a frame whose projection glstereo cannot see, at a \
                     convergence set as a distance: flat until automatic convergence finds \
                     its depth",
                );
                None
            }
        },
    }
}

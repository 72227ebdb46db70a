//! Automatic stereo of a mono renderer (NVIDIA 3D Vision, seed 004): a
//! fixed-function program's frame, given as a draw callback, is rendered
//! once per eye with the eye's projection, into the eye's buffers.
//!
//! # The frame contract ([`render_frame`], `gls_auto_stereo_frame`)
//!
//! On an auto-stereo capable surface ([`create_surface`]) with
//! 3DVISION_STEREO_NV enabled, with the surface current on the calling
//! thread and its default framebuffer bound for drawing:
//!
//! 1. The projection matrix current at the call is the mono projection `P`.
//!    The draw buffers selected at the call are the program's (GL_BACK for a
//!    double-buffered mono program).
//! 2. For the left eye, then the right eye, the library
//!    - puts the matrix mode and the modelview matrix back to what they were
//!      at the call (so both eyes start from the same state),
//!    - loads the eye's projection ([`StereoSettings::eye_projection`] of `P`),
//!    - selects that eye's buffers of the kinds the program selected (GL_BACK
//!      → GL_BACK_LEFT, then GL_BACK_RIGHT; GL_FRONT → GL_FRONT_LEFT/RIGHT;
//!      GL_FRONT_AND_BACK → GL_LEFT/GL_RIGHT),
//!    - calls the callback, which draws the whole mono frame: it clears
//!      (colour and depth: the depth buffer is shared by both eyes) and draws
//!      the scene. It may change the modelview and any other state except
//!      the projection matrix, the draw buffers and the current surface.
//! 3. Afterwards the mono projection and the program's draw buffers are
//!    restored exactly; the modelview and other state are as the right eye's
//!    call left them (as after one mono call).
//!
//! A callback that changes the projection matrix or the draw buffers, or
//! makes another surface current, breaks the eyes: that is detected after
//! each call and reported as GLS_ERROR_INVALID_OPERATION (the right eye is
//! then not drawn; the projection and draw buffers are restored).
//!
//! When the surface is not auto-stereo capable, or 3D Vision is disabled, the
//! callback is called once and nothing is touched: what it renders is what a
//! mono program renders (on a capable surface, GL_BACK then reaches both eyes
//! alike).
//!
//! # Reading pixels
//!
//! As the spec resolves (issue 4), calls that expect one surface read the
//! left eye: the program's glReadPixels with GL_BACK or GL_FRONT selected
//! reads GL_BACK_LEFT / GL_FRONT_LEFT, and so does gls_surface_read_pixels
//! with GL_BACK, GL_FRONT or GL_LEFT. A buffer named by its eye
//! (GL_BACK_RIGHT, GL_RIGHT, …) is read as named: the surface has two eyes.

use std::cell::Cell;
use std::sync::Arc;

use glam::DMat4;

use crate::config::{Config, StereoKind};
use crate::display::Display;
use crate::error::{Error, Result};
use crate::gl::enums::*;
use crate::math::Eye;
use crate::shims::nv3dvision::{StereoSettings, SurfaceAttribs};
use crate::stereo::emulated::MAX_DRAW_BUFFERS;
use crate::surface::{self, Surface};

const GL_MODELVIEW_MATRIX: u32 = 0x0BA6;

thread_local! {
    /// Whether a frame is being rendered on this thread (no nesting).
    static IN_FRAME: Cell<bool> = const { Cell::new(false) };
}

/// Creates a surface with the creation attributes `attribs`. An auto-stereo
/// capable surface always has left and right buffers (that is where the
/// eyes go): a mono configuration gets glstereo's emulated quad buffer, so
/// GL_STEREO reads GL_TRUE on it and quad-buffer drawing works too. Its 3D
/// Vision rendering starts enabled.
pub fn create_surface(
    display: &Arc<Display>,
    config: &Config,
    width: u32,
    height: u32,
    attribs: SurfaceAttribs,
) -> Result<Arc<Surface>> {
    if !attribs.auto_stereo {
        return display.create_surface(config, width, height);
    }
    let mut config = config.clone();
    match config.stereo {
        StereoKind::None => config.stereo = StereoKind::Emulated,
        StereoKind::Emulated => {}
        StereoKind::Native => {
            return Err(Error::invalid_operation(
                "automatic stereo renders into glstereo's emulated eyes, and this configuration \
                 uses the driver's native stereo: choose it with GLSTEREO_EMULATION=force, or \
                 without GLX_STEREO",
            ));
        }
    }
    let s = display.create_surface(&config, width, height)?;
    s.make_auto_stereo_capable();
    Ok(s)
}

/// The buffer of `eye` of the same kind(s) as `name`: front → that eye's
/// front, back → its back, both (GL_LEFT, GL_RIGHT, GL_FRONT_AND_BACK) →
/// GL_LEFT or GL_RIGHT. GL_NONE stays GL_NONE.
pub fn eye_buffer(name: u32, eye: Eye) -> u32 {
    let (front, back, both) = match eye {
        Eye::Left => (GL_FRONT_LEFT, GL_BACK_LEFT, GL_LEFT),
        Eye::Right => (GL_FRONT_RIGHT, GL_BACK_RIGHT, GL_RIGHT),
    };
    match name {
        GL_FRONT_LEFT | GL_FRONT_RIGHT | GL_FRONT => front,
        GL_BACK_LEFT | GL_BACK_RIGHT | GL_BACK => back,
        GL_LEFT | GL_RIGHT | GL_FRONT_AND_BACK => both,
        other => other,
    }
}

/// The program's draw-buffer selection, as the queries report it.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Selection {
    /// glDrawBuffer(name) (or glDrawBuffers with one output: same effect).
    Single(u32),
    /// glDrawBuffers(n, names) with n > 1 (trailing GL_NONEs dropped).
    Multi(Vec<u32>),
}

impl Selection {
    fn read(s: &Arc<Surface>) -> Result<Option<Selection>> {
        // GL_DRAW_BUFFER, then GL_DRAW_BUFFER0.., in one query.
        let mut pnames = [GL_DRAW_BUFFER; MAX_DRAW_BUFFERS + 1];
        for (i, p) in pnames[1..].iter_mut().enumerate() {
            *p = GL_DRAW_BUFFER0 + i as u32;
        }
        let values = s.emulated_integers(pnames)?;
        let Some(first) = values[0] else {
            return Ok(None);
        };
        let mut names: Vec<u32> = values[1..].iter().map(|v| v.unwrap_or(0) as u32).collect();
        while names.len() > 1 && names.last() == Some(&GL_NONE) {
            names.pop();
        }
        Ok(Some(if names.len() <= 1 {
            Single(first as u32)
        } else {
            Multi(names)
        }))
    }

    /// The same selection for one eye. An output whose eye buffer an
    /// earlier output already took draws nowhere (glDrawBuffers forbids
    /// naming a buffer twice).
    fn for_eye(&self, eye: Eye) -> Selection {
        match self {
            Single(n) => Single(eye_buffer(*n, eye)),
            Multi(ns) => {
                let mut out: Vec<u32> = Vec::with_capacity(ns.len());
                for &n in ns {
                    let b = eye_buffer(n, eye);
                    out.push(if b != GL_NONE && out.contains(&b) {
                        GL_NONE
                    } else {
                        b
                    });
                }
                Multi(out)
            }
        }
    }

    fn apply(&self, s: &Arc<Surface>) -> Result<()> {
        match self {
            Single(n) => s.draw_buffer(*n),
            Multi(ns) => s.draw_buffers(ns),
        }
    }
}
use Selection::{Multi, Single};

/// # Safety
/// The surface's application context must be current on this thread.
unsafe fn matrix(s: &Surface, pname: u32) -> DMat4 {
    let mut m = [0.0f64; 16];
    // SAFETY: contract; a matrix query writes 16 values.
    unsafe { s.gl().GetDoublev(pname, m.as_mut_ptr()) };
    DMat4::from_cols_array(&m)
}

/// # Safety
/// The surface's application context must be current on this thread.
unsafe fn load(s: &Surface, mode: u32, m: &DMat4) {
    let gl = s.gl();
    // SAFETY: contract.
    unsafe {
        let prev = gl.integer(GL_MATRIX_MODE) as u32;
        gl.MatrixMode(mode);
        gl.LoadMatrixd(m.to_cols_array().as_ptr());
        gl.MatrixMode(prev);
    }
}

/// Renders one mono frame by the contract in the module docs: `draw` once
/// per eye when the current surface renders automatic stereo, else once.
pub fn render_frame(surface: &Arc<Surface>, draw: &mut dyn FnMut()) -> Result<()> {
    if IN_FRAME.with(Cell::get) {
        return Err(Error::invalid_operation(
            "a frame is already being rendered on this thread: the draw callback must not \
             call gls_auto_stereo_frame() itself",
        ));
    }
    let settings: StereoSettings = surface.with_nv3dvision(|nv| Ok(*nv))?;
    if !settings.renders_stereo() {
        draw();
        return Ok(());
    }
    let Some(program) = Selection::read(surface)? else {
        return Err(Error::invalid_operation(
            "a framebuffer object of the program is bound for drawing: automatic stereo renders \
             into the surface's eyes; bind framebuffer 0 (gls_bind_framebuffer) first",
        ));
    };
    // SAFETY: the surface is current on this thread (checked by with_nv3dvision).
    let (mode, mono, modelview) = unsafe {
        (
            surface.gl().integer(GL_MATRIX_MODE) as u32,
            matrix(surface, GL_PROJECTION_MATRIX),
            matrix(surface, GL_MODELVIEW_MATRIX),
        )
    };
    // Everything that can fail on bad input is computed before GL changes.
    let eyes = [
        (Eye::Left, settings.eye_projection(&mono, Eye::Left)?),
        (Eye::Right, settings.eye_projection(&mono, Eye::Right)?),
    ];
    /// Clears IN_FRAME however the frame ends (a Rust callback may panic).
    struct InFrame;
    impl Drop for InFrame {
        fn drop(&mut self) {
            IN_FRAME.with(|f| f.set(false));
        }
    }
    IN_FRAME.with(|f| f.set(true));
    let in_frame = InFrame;
    let result = draw_eyes(surface, &program, mode, &modelview, &eyes, draw);
    drop(in_frame);
    if surface::current().is_some_and(|c| Arc::ptr_eq(&c, surface)) {
        // SAFETY: still current on this thread (checked).
        unsafe { load(surface, GL_PROJECTION, &mono) };
        let restored = program.apply(surface);
        result?;
        restored
    } else {
        result
    }
}

fn draw_eyes(
    surface: &Arc<Surface>,
    program: &Selection,
    mode: u32,
    modelview: &DMat4,
    eyes: &[(Eye, DMat4); 2],
    draw: &mut dyn FnMut(),
) -> Result<()> {
    for (i, (eye, projection)) in eyes.iter().enumerate() {
        let gl = surface.gl();
        // SAFETY: the surface is current on this thread (checked by the
        // caller before the first eye, and below after every callback).
        let loaded = unsafe {
            if i > 0 {
                load(surface, GL_MODELVIEW, modelview);
                gl.MatrixMode(mode);
            }
            load(surface, GL_PROJECTION, projection);
            // GL keeps its own (single-precision) copy: compare with that.
            matrix(surface, GL_PROJECTION_MATRIX)
        };
        let selection = program.for_eye(*eye);
        selection.apply(surface)?;
        draw();
        let eye_name = match eye {
            Eye::Left => "left",
            Eye::Right => "right",
        };
        if !surface::current().is_some_and(|c| Arc::ptr_eq(&c, surface)) {
            return Err(Error::invalid_operation(format!(
                "the draw callback made another surface current (or none) while drawing the \
                 {eye_name} eye: it must draw into the surface that was current when \
                 gls_auto_stereo_frame() was called"
            )));
        }
        // SAFETY: current (checked just above).
        let after = unsafe { matrix(surface, GL_PROJECTION_MATRIX) };
        if after != loaded {
            return Err(Error::invalid_operation(format!(
                "the draw callback changed the projection matrix while drawing the {eye_name} \
                 eye: automatic stereo loads each eye's projection before calling it, so set \
                 the mono projection before gls_auto_stereo_frame() and change only the \
                 modelview in the callback (the mono projection and the draw buffers were \
                 restored{})",
                if i == 0 {
                    "; the right eye was not drawn"
                } else {
                    ""
                }
            )));
        }
        if Selection::read(surface)?.as_ref() != Some(&selection) {
            return Err(Error::invalid_operation(format!(
                "the draw callback changed the draw buffers (or bound a framebuffer object) \
                 while drawing the {eye_name} eye: automatic stereo selects each eye's buffers \
                 before calling it; select the buffers before gls_auto_stereo_frame() and \
                 restore any framebuffer binding in the callback (the mono projection and the \
                 draw buffers were restored{})",
                if i == 0 {
                    "; the right eye was not drawn"
                } else {
                    ""
                }
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_eye_gets_the_buffers_of_the_kinds_the_program_selected() {
        let cases = [
            (GL_BACK, GL_BACK_LEFT, GL_BACK_RIGHT),
            (GL_BACK_LEFT, GL_BACK_LEFT, GL_BACK_RIGHT),
            (GL_BACK_RIGHT, GL_BACK_LEFT, GL_BACK_RIGHT),
            (GL_FRONT, GL_FRONT_LEFT, GL_FRONT_RIGHT),
            (GL_FRONT_LEFT, GL_FRONT_LEFT, GL_FRONT_RIGHT),
            (GL_FRONT_AND_BACK, GL_LEFT, GL_RIGHT),
            (GL_LEFT, GL_LEFT, GL_RIGHT),
            (GL_RIGHT, GL_LEFT, GL_RIGHT),
            (GL_NONE, GL_NONE, GL_NONE),
        ];
        for (name, l, r) in cases {
            assert_eq!(eye_buffer(name, Eye::Left), l, "{name:#x} left");
            assert_eq!(eye_buffer(name, Eye::Right), r, "{name:#x} right");
        }
    }

    #[test]
    fn multiple_outputs_never_name_a_buffer_twice() {
        let m = Multi(vec![GL_BACK_LEFT, GL_BACK_RIGHT, GL_NONE]);
        assert_eq!(
            m.for_eye(Eye::Right),
            Multi(vec![GL_BACK_RIGHT, GL_NONE, GL_NONE])
        );
        assert_eq!(Single(GL_BACK).for_eye(Eye::Left), Single(GL_BACK_LEFT));
    }
}

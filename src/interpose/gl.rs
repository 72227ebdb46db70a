//! The GL entry points a stereo program touches, as the layer answers them
//! while one of its stereo contexts is current on the calling thread.
//! With no stereo context current (a mono program, or a mono context of a
//! stereo one) each goes straight to the driver after one thread-local test.
//!
//! The rules (GL 4.5 compatibility, default framebuffer; the emulation
//! follows [`crate::stereo::buffers`]):
//! - glDrawBuffer / glDrawBuffers / glReadBuffer select emulated buffers
//!   while framebuffer 0 is bound; a bad value raises the GL error GL
//!   would (kept for glGetError) and changes nothing. With the program's
//!   own framebuffer object bound they go to the driver unchanged.
//! - glGetError reports the first error since the last glGetError, the
//!   emulation's or the driver's, and drops the rest, as Mesa does.
//!   A query the driver refuses (GL_DRAW_BUFFER8 with 8 draw buffers)
//!   keeps its error and gets no emulated answer written.
//! - glGetIntegerv / Booleanv / Floatv / Doublev answer GL_STEREO (true)
//!   and GL_DOUBLEBUFFER while the emulated framebuffer is the draw
//!   framebuffer (GL answers them from the draw framebuffer: with the
//!   program's own object bound, the driver's false), GL_DRAW_BUFFER(i), GL_READ_BUFFER and the draw/read
//!   framebuffer bindings (0 for the emulated framebuffer) as a stereo
//!   visual would; GL_RED/GREEN/BLUE/ALPHA/DEPTH/STENCIL_BITS, GL_SAMPLES
//!   and GL_SAMPLE_BUFFERS come from the window's real framebuffer (the
//!   visual the program chose), as does glGetFramebufferAttachmentParameteriv
//!   on framebuffer 0 (right buffers answer as their left twins; a buffer
//!   the shape lacks has type GL_NONE).
//! - glBindFramebuffer(target, 0) binds the emulated framebuffer;
//!   glDeleteFramebuffers never deletes it, and when it deletes the
//!   program's bound framebuffer the binding reverts to the emulated one,
//!   as it would revert to framebuffer 0.
//! - glPushAttrib / glPopAttrib save and restore the emulated draw buffer
//!   (GL_COLOR_BUFFER_BIT) and read buffer (GL_PIXEL_MODE_BIT), as they do
//!   a real default framebuffer's;
//! - A visual without alpha gets GL_RGBA8 eyes (llvmpipe reads them back
//!   about six times faster than GL_RGB8) whose alpha stays 1.0, as a
//!   default framebuffer without alpha bits reads and blends: glColorMask /
//!   glColorMaski (and its names glColorMaskIndexedEXT, glColorMaskiEXT,
//!   glColorMaskiOES) are kept as the program set them (GL_COLOR_WRITEMASK
//!   through every glGet*v and glGet*i_v and their extension names, and
//!   glPopAttrib, answer and restore those), and the driver's masks never
//!   write alpha while that framebuffer is bound for drawing;
//!   glBlitFramebuffer, glBlitNamedFramebuffer and glClearNamedFramebuffer
//!   into it, which the bound masks do not stop, are followed by a clear of
//!   its alpha to 1.0 (with GL_RASTERIZER_DISCARD off for it: discard stops
//!   clears, not blits). glClear of its colour clears alpha to 1.0 with
//!   alpha written (the clear colour is kept as the program set it, by any
//!   of its setters: [`ClearColor`]), so that llvmpipe's fast full clear
//!   serves it rather than a masked quad. Not seen: these calls compiled
//!   into a display list, which run when the list is called.
//! - glViewport notices a resized window before the program draws into it;
//!   glFlush / glFinish show the front buffers when the program draws to
//!   them (single-buffered visuals, or glDrawBuffer(GL_FRONT…)).

use super::context::{CtxState, Current, MASKED_BUFFERS, current, stereo_current};
use super::dsa::GL_COLOR;
use super::real::{Real, loaded};
use crate::error::{Error, Result};
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::gl::names::Kind;
use crate::shims::nv3dvision::{
    GL_3DVISION_STEREO_NV, GL_STEREO_PROJECTION_NV, StateValue, StereoSettings,
};
use crate::stereo::buffers::{ColorBuffer, gl_error_code};
use crate::stereo::emulated::{
    BufferFormats, DrawSelection, EmulatedFramebuffer, MAX_DRAW_BUFFERS, ReadSelection,
    default_framebuffer_query,
};

/// GL_DEPTH and GL_STENCIL, the default framebuffer's attachment names.
const GL_DEPTH: u32 = 0x1801;
const GL_STENCIL: u32 = 0x1802;
const GL_SAMPLE_BUFFERS: u32 = 0x80A8;
const GL_SAMPLES: u32 = 0x80A9;
const GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE: u32 = 0x8CD0;
const GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME: u32 = 0x8CD1;
/// glPushAttrib bits that cover the draw buffer and the read buffer.
const GL_COLOR_BUFFER_BIT_ATTRIB: u32 = 0x4000;
const GL_PIXEL_MODE_BIT: u32 = 0x0020;
const GL_ATTRIB_STACK_DEPTH: u32 = 0x0BB0;
const GL_COLOR_WRITEMASK: u32 = 0x0C23;

/// Refuses a NULL pointer that GL would read or write through (libGL
/// dereferences it and crashes): nothing is forwarded, and GL_INVALID_VALUE
/// is raised in the current context — in a stereo context's error flag
/// ([`CtxState::push_error`]), in any other context by the driver itself through
/// glViewport(0, 0, -1, -1), which GL rejects with exactly that error and
/// no other effect. With no context current nothing is raised (GL calls do
/// nothing then).
pub(super) fn refuse_null(r: &Real, what: &'static str) -> Error {
    match current() {
        Some(cur) => cur.sc.lock().push_error(&r.gl, GL_INVALID_VALUE),
        // SAFETY: an erroneous call GL ignores, in whatever context is current.
        None => unsafe { r.gl.Viewport(0, 0, -1, -1) },
    }
    Error::NullPointer(what)
}

/// `p` is NULL while GL needs `n` values there.
pub(super) fn missing<T>(n: i32, p: *const T) -> bool {
    n > 0 && p.is_null()
}

/// The emulated framebuffer of `drawable`, when it is what `binding` has bound.
pub(super) fn bound<'a>(
    gl: &Gl,
    fbs: &'a mut std::collections::HashMap<u64, super::context::Drawn>,
    drawable: u64,
    binding: u32,
) -> Option<&'a mut EmulatedFramebuffer> {
    // SAFETY: the program's context is current (callers).
    let name = unsafe { gl.integer(binding) } as u32;
    fbs.get_mut(&drawable)
        .map(|d| &mut d.fb)
        .filter(|fb| name != 0 && fb.app_fbo() == name)
}

pub(super) fn read_drawable(cur: &Current) -> u64 {
    if cur.read == 0 { cur.draw } else { cur.read }
}

/// Runs `f` on the emulated framebuffer the program has bound at
/// `binding` (of `drawable`), raising its GL error; false when the
/// program has its own framebuffer bound (the driver handles the call).
fn on_emulated(
    cur: &Current,
    gl: &Gl,
    binding: u32,
    drawable: u64,
    f: impl FnOnce(&mut EmulatedFramebuffer, &Gl) -> crate::Result<()>,
) -> bool {
    let mut st = cur.sc.lock();
    let Some(fb) = bound(gl, &mut st.fbs, drawable, binding) else {
        return false;
    };
    if let Err(e) = f(fb, gl) {
        st.push_error(gl, gl_error_code(&e));
    }
    true
}

/// glDrawBuffer.
pub fn draw_buffer(buf: u32) -> Result<()> {
    let r = loaded()?;
    if let Some(cur) = current() {
        let draw = cur.draw;
        if on_emulated(&cur, &r.gl, GL_DRAW_FRAMEBUFFER_BINDING, draw, |fb, gl| {
            // SAFETY: the program's context is current.
            unsafe { fb.set_draw_buffer(gl, buf) }
        }) {
            return Ok(());
        }
    }
    // SAFETY: forwarded call.
    unsafe { r.gl.DrawBuffer(buf) };
    Ok(())
}

/// glDrawBuffers (and glDrawBuffersARB when `arb`). Refused: `bufs` NULL
/// with `n` > 0 (`refuse_null`).
///
/// # Safety
/// `bufs` must hold `n` values (GL's contract).
pub unsafe fn draw_buffers(n: i32, bufs: *const u32, arb: bool) -> Result<()> {
    let r = loaded()?;
    if missing(n, bufs) {
        return Err(refuse_null(r, "bufs"));
    }
    if let Some(cur) = current() {
        let draw = cur.draw;
        let handled = on_emulated(&cur, &r.gl, GL_DRAW_FRAMEBUFFER_BINDING, draw, |fb, gl| {
            if n < 0 {
                return Err(crate::Error::invalid_value(
                    "glDrawBuffers: n is negative (GL_INVALID_VALUE)",
                ));
            }
            let names = if n == 0 {
                &[][..]
            } else {
                // SAFETY: GL's contract: `bufs` holds n values.
                unsafe { std::slice::from_raw_parts(bufs, n as usize) }
            };
            // SAFETY: the program's context is current.
            unsafe { fb.set_draw_buffers(gl, names) }
        });
        if handled {
            return Ok(());
        }
    }
    match (arb, r.extra.draw_buffers_arb) {
        // SAFETY: forwarded call.
        (true, Some(f)) => unsafe { f(n, bufs) },
        // SAFETY: forwarded call.
        _ => unsafe { r.gl.DrawBuffers(n, bufs) },
    }
    Ok(())
}

/// glReadBuffer.
pub fn read_buffer(src: u32) -> Result<()> {
    let r = loaded()?;
    if let Some(cur) = current() {
        let read = read_drawable(&cur);
        if on_emulated(&cur, &r.gl, GL_READ_FRAMEBUFFER_BINDING, read, |fb, gl| {
            // SAFETY: the program's context is current.
            unsafe { fb.set_read_buffer(gl, src) }
        }) {
            return Ok(());
        }
    }
    // SAFETY: forwarded call.
    unsafe { r.gl.ReadBuffer(src) };
    Ok(())
}

/// glGetError.
pub fn get_error() -> Result<u32> {
    let r = loaded()?;
    if let Some(cur) = current() {
        if let Some(e) = cur.sc.lock().take_error(&r.gl) {
            return Ok(e);
        }
    }
    // SAFETY: forwarded call.
    Ok(unsafe { r.gl.GetError() })
}

/// Whether the layer may answer `pname` for the default framebuffer: the
/// pnames of [`default_framebuffer_query`], and those [`from_window`].
fn answered(pname: u32) -> bool {
    matches!(
        pname,
        GL_STEREO
            | GL_DOUBLEBUFFER
            | GL_DRAW_BUFFER
            | GL_READ_BUFFER
            | GL_DRAW_FRAMEBUFFER_BINDING
            | GL_READ_FRAMEBUFFER_BINDING
    ) || (GL_DRAW_BUFFER0..=GL_DRAW_BUFFER15).contains(&pname)
        || from_window(pname)
}

/// Whether `pname` describes the draw framebuffer's buffers, which the
/// window's real framebuffer answers.
fn from_window(pname: u32) -> bool {
    matches!(
        pname,
        GL_RED_BITS
            | GL_GREEN_BITS
            | GL_BLUE_BITS
            | GL_ALPHA_BITS
            | GL_DEPTH_BITS
            | GL_STENCIL_BITS
            | GL_SAMPLES
            | GL_SAMPLE_BUFFERS
    )
}

/// Runs `f` with the window's real framebuffer bound for drawing and
/// reading, then puts the program's bindings back.
pub(super) fn with_window_framebuffer<T>(gl: &Gl, f: impl FnOnce() -> T) -> T {
    // SAFETY: the program's context is current (callers).
    unsafe {
        let draw = gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32;
        let read = gl.integer(GL_READ_FRAMEBUFFER_BINDING) as u32;
        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        let v = f();
        gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, draw);
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, read);
        v
    }
}

/// The layer's answer for `pname`, or None where the driver's stands.
fn emulated_value(gl: &Gl, pname: u32) -> Option<i32> {
    if !answered(pname) {
        return None;
    }
    let cur = current()?;
    let read_d = read_drawable(&cur);
    let st = cur.sc.lock();
    // SAFETY: the program's context is current.
    let (draw_name, read_name) = unsafe {
        (
            gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32,
            gl.integer(GL_READ_FRAMEBUFFER_BINDING) as u32,
        )
    };
    let fb_of = |d: u64, name: u32| {
        st.fbs
            .get(&d)
            .map(|x| &x.fb)
            .filter(|fb| name != 0 && fb.app_fbo() == name)
    };
    let draw = fb_of(cur.draw, draw_name);
    let read = fb_of(read_d, read_name);
    if from_window(pname) {
        draw?;
        // SAFETY: the program's context is current; one value written.
        let v = with_window_framebuffer(gl, || unsafe { gl.integer(pname) });
        return Some(v);
    }
    default_framebuffer_query(pname, cur.sc.program_shape(), draw, read)
}

/// glGetIntegerv / Booleanv / Floatv / Doublev: the driver's answer
/// (`forward`), then the layer's for the pnames it answers, converted as
/// GL converts an integer state to `T`. Refused: `data` NULL (`refuse_null`).
///
/// # Safety
/// `data` must be valid for the values `pname` returns (GL's contract).
unsafe fn get_v<T>(
    r: &Real,
    pname: u32,
    data: *mut T,
    forward: impl FnOnce(u32, *mut T),
    convert: fn(i32) -> T,
) -> Result<()> {
    if data.is_null() {
        return Err(refuse_null(r, "data"));
    }
    let cur = match current() {
        Some(cur) if answered(pname) || pname == GL_COLOR_WRITEMASK => cur,
        _ => {
            forward(pname, data);
            return Ok(());
        }
    };
    if !driver_accepts(&r.gl, &cur, || forward(pname, data)) {
        return Ok(());
    }
    if pname == GL_COLOR_WRITEMASK {
        // SAFETY: GL_COLOR_WRITEMASK returns four values (GL's contract).
        unsafe { write_mask(0, data, convert) };
        return Ok(());
    }
    if let Some(v) = emulated_value(&r.gl, pname) {
        // SAFETY: non-NULL; every answered pname returns one value.
        unsafe { *data = convert(v) };
    }
    Ok(())
}

/// Runs `query`, the driver's answer to a query the layer may answer
/// over, in the stereo context `cur` (current), and says whether the
/// driver took it: where it raised an error (a pname or index it does not
/// have, such as GL_DRAW_BUFFER8 with 8 draw buffers), GL writes nothing,
/// so the layer must not either; the error stays the program's (kept as
/// Mesa keeps it, [`CtxState::push_error`]). The program's earlier error
/// is saved first, so that the query's own is told apart.
pub(super) fn driver_accepts(gl: &Gl, cur: &Current, query: impl FnOnce()) -> bool {
    cur.sc.lock().save_driver_errors(gl);
    query();
    // SAFETY: the program's context is current (callers).
    let e = unsafe { gl.GetError() };
    if e != GL_NO_ERROR {
        cur.sc.lock().push_error(gl, e);
    }
    e == GL_NO_ERROR
}

/// glGetIntegerv. Refused: `data` NULL (`refuse_null`).
///
/// # Safety
/// `data` must be valid for the values `pname` returns (GL's contract).
pub unsafe fn get_integerv(pname: u32, data: *mut i32) -> Result<()> {
    let r = loaded()?;
    // SAFETY: `data` holds the one value the pname returns (GL's contract).
    if unsafe { nv_answer(r, pname, data, StateValue::as_integer)? } {
        return Ok(());
    }
    // SAFETY: forwarded contract; the forwarded call gets it.
    unsafe { get_v(r, pname, data, |p, d| r.gl.GetIntegerv(p, d), |v| v) }
}

/// glGetBooleanv.
///
/// # Safety
/// As [`get_integerv`].
pub unsafe fn get_booleanv(pname: u32, data: *mut u8) -> Result<()> {
    let r = loaded()?;
    // SAFETY: `data` holds the one value the pname returns (GL's contract).
    if unsafe { nv_answer(r, pname, data, |v| v.as_boolean() as u8)? } {
        return Ok(());
    }
    // SAFETY: forwarded contract; the forwarded call gets it.
    unsafe {
        get_v(
            r,
            pname,
            data,
            |p, d| r.gl.GetBooleanv(p, d),
            |v| (v != 0) as u8,
        )
    }
}

/// glGetFloatv.
///
/// # Safety
/// As [`get_integerv`].
pub unsafe fn get_floatv(pname: u32, data: *mut f32) -> Result<()> {
    let r = loaded()?;
    // SAFETY: `data` holds the one value the pname returns (GL's contract).
    if unsafe { nv_answer(r, pname, data, StateValue::as_float)? } {
        return Ok(());
    }
    // SAFETY: forwarded contract; the forwarded call gets it.
    unsafe { get_v(r, pname, data, |p, d| r.gl.GetFloatv(p, d), |v| v as f32) }
}

/// glGetDoublev.
///
/// # Safety
/// As [`get_integerv`].
pub unsafe fn get_doublev(pname: u32, data: *mut f64) -> Result<()> {
    let r = loaded()?;
    // SAFETY: `data` holds the one value the pname returns (GL's contract).
    if unsafe { nv_answer(r, pname, data, |v| f64::from(v.as_float()))? } {
        return Ok(());
    }
    // SAFETY: forwarded contract; the forwarded call gets it.
    unsafe { get_v(r, pname, data, |p, d| r.gl.GetDoublev(p, d), f64::from) }
}

/// glGetInteger64v (GL 3.2), as [`get_integerv`].
///
/// # Safety
/// As [`get_integerv`].
pub unsafe fn get_integer64v(pname: u32, data: *mut i64) -> Result<()> {
    let r = loaded()?;
    // SAFETY: `data` holds the one value the pname returns (GL's contract).
    if unsafe { nv_answer(r, pname, data, |v| i64::from(v.as_integer()))? } {
        return Ok(());
    }
    let f = r
        .extra
        .get_integer64v
        .ok_or_else(|| lacks("glGetInteger64v", "GL 3.2"))?;
    // SAFETY: forwarded contract; the forwarded call gets it.
    unsafe { get_v(r, pname, data, |p, d| f(p, d), i64::from) }
}

/// The NV_3dvision_settings values (GL_3DVISION_STEREO_NV and the
/// STEREO_*_NV pnames, seed 004) in a context given automatic stereo,
/// written to `data` as `convert` makes them the query's type; true when
/// answered. Elsewhere the driver answers (GL_INVALID_ENUM on Mesa: the
/// extension is automatic stereo's). Refused: `data` NULL.
///
/// # Safety
/// `data` is NULL or valid for one value.
unsafe fn nv_answer<T>(
    r: &Real,
    pname: u32,
    data: *mut T,
    convert: fn(StateValue) -> T,
) -> Result<bool> {
    if !(GL_3DVISION_STEREO_NV..=GL_STEREO_PROJECTION_NV).contains(&pname) {
        return Ok(false);
    }
    let Some(cur) = current().filter(|c| c.sc.auto()) else {
        return Ok(false);
    };
    if data.is_null() {
        return Err(refuse_null(r, "data"));
    }
    let Some(v) = cur
        .sc
        .with_auto(cur.draw, |st, _| crate::auto::runtime::query(st, pname))
    else {
        return Ok(false);
    };
    // SAFETY: non-NULL, one value (contract).
    unsafe { *data = convert(v) };
    Ok(true)
}

/// glStereoParameterfNV (`Ok(value)`) and glStereoParameteriNV
/// (`Err(value)`), NV_3dvision_settings (seed 004). In a context given
/// automatic stereo (glstereo-run --auto) they set separation,
/// convergence, cutoff and projection method
/// ([`crate::auto::runtime::set_parameter`]); a bad pname or value raises
/// the extension's GL error and changes nothing. Elsewhere, as the
/// extension says of a context without 3D Vision, they have no effect on
/// rendering (the same errors, and stderr says once that automatic
/// stereo is off); with no context current, nothing, as GL.
pub fn stereo_parameter(pname: u32, value: std::result::Result<f32, i32>) -> Result<()> {
    let r = loaded()?;
    let Some(cur) = current() else {
        if !super::live::auto_requested() {
            note_no_auto();
        }
        return Ok(());
    };
    let outcome = if cur.sc.auto() {
        cur.sc.with_auto(cur.draw, |st, _| {
            crate::auto::runtime::set_parameter(st, pname, value)
        })
    } else {
        note_no_auto();
        let mut s = StereoSettings::new(false);
        match value {
            Ok(f) => s.parameter_f(pname, f),
            Err(i) => s.parameter_i(pname, i),
        }
    };
    if let Err(e) = outcome {
        cur.sc.lock().push_error(&r.gl, gl_error_code(&e));
    }
    Ok(())
}

/// Says once that glStereoParameter*NV has no effect without --auto.
fn note_no_auto() {
    static SAID: std::sync::Once = std::sync::Once::new();
    SAID.call_once(|| {
        super::warn(
            "glStereoParameterNV has no effect: automatic stereo is off for this \
             context (run the program with glstereo-run --auto, or GLSTEREO_AUTO=1)",
        )
    });
}

/// Writes the program's colour mask of draw buffer `index` (what
/// GL_COLOR_WRITEMASK answers) over the driver's answer in `data`, as
/// `convert` turns GL's booleans into the query's type, when a stereo
/// context is current.
///
/// # Safety
/// `data` is valid for four values.
unsafe fn write_mask<T>(index: usize, data: *mut T, convert: fn(i32) -> T) {
    if let Some(cur) = current() {
        let mask = cur.sc.lock().color_mask[index];
        for (i, &m) in mask.iter().enumerate() {
            // SAFETY: four values (contract).
            unsafe { *data.add(i) = convert(m as i32) };
        }
    }
}

/// The error for a GL function the program called that the driver lacks
/// (`offered_by`: the GL version or extension that brings it).
pub(super) fn lacks(name: &str, offered_by: &str) -> Error {
    Error::BackendUnavailable(format!(
        "the GL library lacks {name}: it needs a driver with {offered_by}"
    ))
}

/// Binds the emulated framebuffer(s) at `target` in place of framebuffer
/// 0; false for a target GL does not know (the driver raises its error).
fn bind_emulated(cur: &Current, gl: &Gl, target: u32) -> bool {
    let st = cur.sc.lock();
    let Some(draw) = st.fbs.get(&cur.draw).map(|d| d.fb.app_fbo()) else {
        return false;
    };
    let read = st
        .fbs
        .get(&read_drawable(cur))
        .map_or(draw, |d| d.fb.app_fbo());
    // SAFETY: the program's context is current.
    unsafe {
        match target {
            GL_FRAMEBUFFER if draw == read => gl.BindFramebuffer(GL_FRAMEBUFFER, draw),
            GL_FRAMEBUFFER => {
                gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, draw);
                gl.BindFramebuffer(GL_READ_FRAMEBUFFER, read);
            }
            GL_DRAW_FRAMEBUFFER => gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, draw),
            GL_READ_FRAMEBUFFER => gl.BindFramebuffer(GL_READ_FRAMEBUFFER, read),
            _ => return false,
        }
    }
    true
}

/// glBindFramebuffer (glBindFramebufferEXT when `ext`).
pub fn bind_framebuffer(target: u32, framebuffer: u32, ext: bool) -> Result<()> {
    let r = loaded()?;
    let cur = current();
    let emulated = framebuffer == 0
        && cur
            .as_ref()
            .is_some_and(|cur| bind_emulated(cur, &r.gl, target));
    if !emulated {
        match (ext, r.extra.bind_framebuffer_ext) {
            // SAFETY: forwarded call.
            (true, Some(f)) => unsafe { f(target, framebuffer) },
            // SAFETY: forwarded call.
            _ => unsafe { r.gl.BindFramebuffer(target, framebuffer) },
        }
    }
    if let Some(cur) = cur {
        if target != GL_READ_FRAMEBUFFER && cur.sc.formats().opaque {
            apply_color_mask(&r.gl, cur.sc.formats(), &cur.sc.lock());
        }
    }
    Ok(())
}

/// glDeleteFramebuffers (glDeleteFramebuffersEXT when `ext`). Refused:
/// `names` NULL with `n` > 0 (`refuse_null`).
///
/// # Safety
/// `names` must hold `n` values (GL's contract).
pub unsafe fn delete_framebuffers(n: i32, names: *const u32, ext: bool) -> Result<()> {
    let r = loaded()?;
    if missing(n, names) {
        return Err(refuse_null(r, "framebuffers"));
    }
    let forward = |n: i32, p: *const u32| match (ext, r.extra.delete_framebuffers_ext) {
        // SAFETY: forwarded call.
        (true, Some(f)) => unsafe { f(n, p) },
        // SAFETY: forwarded call.
        _ => unsafe { r.gl.DeleteFramebuffers(n, p) },
    };
    let cur = match current() {
        Some(c) if n > 0 => c,
        _ => {
            forward(n, names);
            return Ok(());
        }
    };
    // SAFETY: GL's contract: `names` holds n values.
    let list = unsafe { std::slice::from_raw_parts(names, n as usize) };
    let kept: Vec<u32> = {
        let st = cur.sc.lock();
        // The emulated framebuffer, and the layer's own framebuffers (Mesa
        // shares framebuffers across the share group).
        list.iter()
            .copied()
            .filter(|&f| !st.is_ours(f) && !r.gl.owns(Kind::Framebuffer, f))
            .collect()
    };
    forward(kept.len() as i32, kept.as_ptr());
    if cur.sc.auto() {
        crate::auto::runtime::framebuffers_deleted(&cur, &kept);
    }
    // Deleting the bound framebuffer reverts the binding to framebuffer 0,
    // which is the emulated one.
    let gl = &r.gl;
    // SAFETY: the program's context is current.
    let (draw, read) = unsafe {
        (
            gl.integer(GL_DRAW_FRAMEBUFFER_BINDING),
            gl.integer(GL_READ_FRAMEBUFFER_BINDING),
        )
    };
    if draw == 0 {
        bind_emulated(&cur, gl, GL_DRAW_FRAMEBUFFER);
    }
    if read == 0 {
        bind_emulated(&cur, gl, GL_READ_FRAMEBUFFER);
    }
    if cur.sc.formats().opaque {
        apply_color_mask(gl, cur.sc.formats(), &cur.sc.lock());
    }
    Ok(())
}

/// Which objects a glDelete* call names (see [`delete_objects`]).
#[derive(Clone, Copy)]
pub enum Deleted {
    /// glDeleteTextures (glDeleteTexturesEXT when true).
    Textures(bool),
    /// glDeleteRenderbuffers (glDeleteRenderbuffersEXT when true).
    Renderbuffers(bool),
}

/// glDeleteTextures, glDeleteRenderbuffers and their EXT names: the
/// layer's own objects, which live in the program's share group
/// ([`crate::gl::names`]), are left alone, as names the program never made
/// are; every other name is forwarded, in order. Refused: `names` NULL
/// with `n` > 0 (`refuse_null`).
///
/// # Safety
/// `names` must hold `n` values (GL's contract).
pub unsafe fn delete_objects(n: i32, names: *const u32, what: Deleted) -> Result<()> {
    let r = loaded()?;
    let kind = match what {
        Deleted::Textures(_) => Kind::Texture,
        Deleted::Renderbuffers(_) => Kind::Renderbuffer,
    };
    if missing(n, names) {
        return Err(refuse_null(
            r,
            match kind {
                Kind::Texture => "textures",
                _ => "renderbuffers",
            },
        ));
    }
    let forward = |n: i32, p: *const u32| match what {
        // SAFETY: forwarded calls.
        Deleted::Textures(true) if r.extra.delete_textures_ext.is_some() => unsafe {
            (r.extra.delete_textures_ext.expect("checked"))(n, p)
        },
        Deleted::Textures(_) => unsafe { r.gl.DeleteTextures(n, p) },
        Deleted::Renderbuffers(true) if r.extra.delete_renderbuffers_ext.is_some() => unsafe {
            (r.extra.delete_renderbuffers_ext.expect("checked"))(n, p)
        },
        Deleted::Renderbuffers(_) => unsafe { r.gl.DeleteRenderbuffers(n, p) },
    };
    if n <= 0 {
        forward(n, names);
        return Ok(());
    }
    // SAFETY: GL's contract: `names` holds n values.
    let list = unsafe { std::slice::from_raw_parts(names, n as usize) };
    if !r.gl.owns_any(kind) || !list.iter().any(|&name| r.gl.owns(kind, name)) || !in_stereo_group()
    {
        forward(n, names);
        auto_deleted(list, what);
        return Ok(());
    }
    let kept: Vec<u32> = list
        .iter()
        .copied()
        .filter(|&name| !r.gl.owns(kind, name))
        .collect();
    forward(kept.len() as i32, kept.as_ptr());
    auto_deleted(&kept, what);
    Ok(())
}

/// Automatic stereo forgets the eyes of the program's deleted textures
/// or renderbuffers `names` (a context given automatic stereo is current).
fn auto_deleted(names: &[u32], what: Deleted) {
    let Some(cur) = current().filter(|c| c.sc.auto()) else {
        return;
    };
    use crate::auto::render_targets::Object;
    let objects: Vec<Object> = names
        .iter()
        .map(|&n| match what {
            Deleted::Textures(_) => Object::Texture(n),
            Deleted::Renderbuffers(_) => Object::Renderbuffer(n),
        })
        .collect();
    // SAFETY: the program's context is current on this thread.
    unsafe { crate::auto::runtime::objects_deleted(&cur, &objects) };
}

/// Whether the context current on this thread shares objects with a
/// stereo context (where the layer's objects live): a stereo context, or
/// one the program made sharing with one.
fn in_stereo_group() -> bool {
    stereo_current() || {
        let ctx = super::wsi::made_current_context();
        ctx != 0 && super::registry::with(|reg| reg.in_stereo_group(ctx))
    }
}

/// glGetFramebufferAttachmentParameteriv (…EXT when `ext`). Refused:
/// `params` NULL (`refuse_null`).
///
/// # Safety
/// `params` must be valid for one value (GL's contract).
pub unsafe fn get_framebuffer_attachment_parameteriv(
    target: u32,
    attachment: u32,
    pname: u32,
    params: *mut i32,
    ext: bool,
) -> Result<()> {
    let r = loaded()?;
    if params.is_null() {
        return Err(refuse_null(r, "params"));
    }
    // SAFETY: forwarded contract; `params` is not NULL.
    unsafe { attachment_parameter(r, target, attachment, pname, params, ext) };
    Ok(())
}

/// [`get_framebuffer_attachment_parameteriv`] with `params` not NULL.
unsafe fn attachment_parameter(
    r: &Real,
    target: u32,
    attachment: u32,
    pname: u32,
    params: *mut i32,
    ext: bool,
) {
    let gl = &r.gl;
    let forward = |attachment: u32| match (ext, r.extra.get_attachment_ext) {
        // SAFETY: forwarded call.
        (true, Some(f)) => unsafe { f(target, attachment, pname, params) },
        // SAFETY: forwarded call.
        _ => unsafe { gl.GetFramebufferAttachmentParameteriv(target, attachment, pname, params) },
    };
    let Some(cur) = current() else {
        return forward(attachment);
    };
    let (binding, drawable) = match target {
        GL_FRAMEBUFFER | GL_DRAW_FRAMEBUFFER => (GL_DRAW_FRAMEBUFFER_BINDING, cur.draw),
        GL_READ_FRAMEBUFFER => (GL_READ_FRAMEBUFFER_BINDING, read_drawable(&cur)),
        _ => return forward(attachment),
    };
    {
        let mut st = cur.sc.lock();
        if bound(gl, &mut st.fbs, drawable, binding).is_none() {
            drop(st);
            return forward(attachment);
        }
    }
    // SAFETY: forwarded contract.
    unsafe {
        emulated_attachment(gl, &cur, attachment, pname, params, |twin| {
            with_window_framebuffer(gl, || forward(twin))
        })
    }
}

/// The answer of glGetFramebufferAttachmentParameteriv (or its named form)
/// for `attachment` of an emulated default framebuffer: GL_FRONT_LEFT …
/// GL_BACK_RIGHT (GL_FRONT, GL_BACK as their left buffers), GL_DEPTH and
/// GL_STENCIL; any other attachment is GL_INVALID_ENUM. A colour buffer the
/// shape lacks has type GL_NONE; the others are answered by the window's
/// own buffer (`window(attachment)`): right buffers as their left twins
/// (same format), depth and stencil as they are.
///
/// # Safety
/// The program's context is current; `params` is not NULL.
pub(super) unsafe fn emulated_attachment(
    gl: &Gl,
    cur: &Current,
    attachment: u32,
    pname: u32,
    params: *mut i32,
    window: impl FnOnce(u32),
) {
    let color = match attachment {
        GL_FRONT_LEFT | GL_FRONT => Some(ColorBuffer::FrontLeft),
        GL_BACK_LEFT | GL_BACK => Some(ColorBuffer::BackLeft),
        GL_FRONT_RIGHT => Some(ColorBuffer::FrontRight),
        GL_BACK_RIGHT => Some(ColorBuffer::BackRight),
        GL_DEPTH | GL_STENCIL => None,
        _ => return cur.sc.lock().push_error(gl, GL_INVALID_ENUM),
    };
    match color {
        Some(b) if !cur.sc.program_shape().allocated().contains(b) => match pname {
            // SAFETY: not NULL (contract), one value (GL's contract).
            GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE => unsafe { *params = GL_NONE as i32 },
            GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME => cur.sc.lock().push_error(gl, GL_INVALID_ENUM),
            _ => cur.sc.lock().push_error(gl, GL_INVALID_OPERATION),
        },
        // GL 4.5 §9.2.3: a default framebuffer's buffers answer only these
        // (an object name, texture level or layer is an FBO's); Mesa says
        // so for its windows too. Not asked of the window below, which a
        // layer such as VirtualGL stands in for with an object of its own.
        _ if !DEFAULT_ATTACHMENT_PNAMES.contains(&pname) => {
            cur.sc.lock().push_error(gl, GL_INVALID_ENUM)
        }
        _ => window(match color {
            Some(ColorBuffer::FrontRight) => GL_FRONT_LEFT,
            Some(ColorBuffer::BackRight) => GL_BACK_LEFT,
            _ => attachment,
        }),
    }
}

/// The glGetFramebufferAttachmentParameteriv names a default
/// framebuffer's buffers answer: the object type, the component sizes,
/// the component type and the colour encoding.
const DEFAULT_ATTACHMENT_PNAMES: [u32; 9] = [
    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
    0x8212, // GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE
    0x8213, // GREEN_SIZE
    0x8214, // BLUE_SIZE
    0x8215, // ALPHA_SIZE
    0x8216, // DEPTH_SIZE
    0x8217, // STENCIL_SIZE
    0x8211, // COMPONENT_TYPE
    0x8210, // COLOR_ENCODING
];

/// glViewport: before forwarding it, a size other than the buffers' makes
/// the layer check (once a frame) whether the window was resized.
pub fn viewport(x: i32, y: i32, width: i32, height: i32) -> Result<()> {
    let r = loaded()?;
    if let Some(cur) = current() {
        if let Err(e) = cur.sc.viewport_hint(&cur, width, height) {
            super::warn(&format!("following a resized window: {e}"));
        }
    }
    // SAFETY: forwarded call.
    unsafe { r.gl.Viewport(x, y, width, height) };
    Ok(())
}

/// glFlush (`finish` false) or glFinish: forwarded; then, when the program
/// draws to a front buffer of the emulated framebuffer, the fronts are shown.
pub fn flush(finish: bool) -> Result<()> {
    let r = loaded()?;
    // SAFETY: forwarded calls.
    unsafe { if finish { r.gl.Finish() } else { r.gl.Flush() } }
    let Some(cur) = current() else {
        return Ok(());
    };
    let fronts = {
        let mut st = cur.sc.lock();
        bound(&r.gl, &mut st.fbs, cur.draw, GL_DRAW_FRAMEBUFFER_BINDING).is_some_and(|fb| {
            let set = fb.draw_set();
            !fb.shape().double_buffered
                || set.contains(ColorBuffer::FrontLeft)
                || set.contains(ColorBuffer::FrontRight)
        })
    };
    if fronts {
        if let Err(e) = cur.sc.present(cur.draw, false, true) {
            super::warn(&format!("showing the front buffers: {e}"));
        }
    }
    Ok(())
}

/// The attribute stack's depth, read in the program's context without
/// touching its GL errors: the driver's pending error (the program's) is
/// moved to the stereo context's flag first, and the error of the query
/// itself (GL_INVALID_ENUM in a core-profile context, which has no
/// attribute stack) is dropped; None then.
fn stack_depth(gl: &Gl, cur: &Current) -> Option<i32> {
    let mut st = cur.sc.lock();
    st.save_driver_errors(gl);
    // SAFETY: the program's context is current (callers).
    unsafe {
        let depth = gl.integer(GL_ATTRIB_STACK_DEPTH);
        (gl.GetError() == GL_NO_ERROR).then_some(depth)
    }
}

/// glPushAttrib.
pub fn push_attrib(mask: u32) -> Result<()> {
    let r = loaded()?;
    if let Some(push) = r.extra.push_attrib {
        push_selections(&r.gl, push, mask);
    }
    Ok(())
}

fn push_selections(gl: &Gl, push: unsafe extern "system" fn(u32), mask: u32) {
    let Some(cur) = current() else {
        // SAFETY: forwarded call.
        return unsafe { push(mask) };
    };
    let before = stack_depth(gl, &cur);
    // SAFETY: forwarded call; its GL error stays the driver's.
    unsafe { push(mask) };
    let after = stack_depth(gl, &cur);
    if before.is_none() || after != before.map(|d| d + 1) {
        // Stack overflow, or a core context: GL pushed nothing.
        return;
    }
    let read_d = read_drawable(&cur);
    let mut st = cur.sc.lock();
    let draw_on_emulated = bound(gl, &mut st.fbs, cur.draw, GL_DRAW_FRAMEBUFFER_BINDING).is_some();
    let read_on_emulated = bound(gl, &mut st.fbs, read_d, GL_READ_FRAMEBUFFER_BINDING).is_some();
    let saved = super::context::SavedSelections {
        draw_on_emulated,
        read_on_emulated,
        draw: (mask & GL_COLOR_BUFFER_BIT_ATTRIB != 0)
            .then(|| {
                st.fbs
                    .get(&cur.draw)
                    .map(|d| (cur.draw, d.fb.draw_selection()))
            })
            .flatten(),
        read: (mask & GL_PIXEL_MODE_BIT != 0)
            .then(|| st.fbs.get(&read_d).map(|d| (read_d, d.fb.read_selection())))
            .flatten(),
        color_mask: (mask & GL_COLOR_BUFFER_BIT_ATTRIB != 0)
            .then_some((st.color_mask, st.clear_color)),
    };
    st.attribs.push(saved);
}

/// glPopAttrib: GL restores its own state; the emulated selections the
/// matching push saved are put back when the emulated framebuffer is the
/// one bound.
pub fn pop_attrib() -> Result<()> {
    let r = loaded()?;
    if let Some(pop) = r.extra.pop_attrib {
        pop_selections(&r.gl, pop);
    }
    Ok(())
}

fn pop_selections(gl: &Gl, pop: unsafe extern "system" fn()) {
    let Some(cur) = current() else {
        // SAFETY: forwarded call.
        return unsafe { pop() };
    };
    let before = stack_depth(gl, &cur);
    // What the pop may wrongly change (see CrossPop): the buffers of the
    // framebuffers bound now, as they are before it.
    let kept = {
        let mut st = cur.sc.lock();
        CrossPop::before(gl, &cur, &mut st)
    };
    // SAFETY: forwarded call; its GL error stays the driver's.
    unsafe { pop() };
    // Enables may be back on: automatic stereo's fixed-function stand-in
    // reads them again.
    cur.sc.with_auto(cur.draw, |st, _| st.forget_enables());
    let after = stack_depth(gl, &cur);
    if before.is_none() || after.map(|d| d + 1) != before {
        // Stack underflow, or a core context: GL popped nothing.
        return;
    }
    let mut st = cur.sc.lock();
    let Some(saved) = st.attribs.pop() else {
        return;
    };
    kept.after(gl, &mut st, &saved);
    if let Some((mask, clear_color)) = saved.color_mask {
        // GL restored the driver's masks as they were at the push (alpha
        // off if the emulated framebuffer was bound then): put the
        // program's back and apply them to what is bound now.
        st.color_mask = mask;
        st.clear_color = clear_color;
        apply_color_mask(gl, cur.sc.formats(), &st);
    }
}

/// The buffer selections of the framebuffers bound just before a
/// glPopAttrib, for a pop across framebuffers. GL restores the draw and
/// read buffers a push saved onto whatever framebuffer is bound at the
/// pop; Mesa (22.3, a mono visual) leaves a framebuffer's buffers as they
/// are when the saved names do not fit it — default-framebuffer names
/// (GL_BACK…) popped while a framebuffer object is bound, attachments
/// popped while the default framebuffer is bound — with no error, and
/// applies GL_NONE anywhere. Under the layer the driver saw the
/// emulation's own attachments where the program had framebuffer 0,
/// which fit any framebuffer object: so the layer puts back what the
/// driver should have left (`tests/c/glx_opaque_alpha.c` compares each
/// case with Mesa's mono visual).
struct CrossPop {
    draw: Kept<([u32; MAX_DRAW_BUFFERS], usize), DrawSelection>,
    read: Kept<u32, ReadSelection>,
}

/// What a pop across framebuffers must not change, for draw or read.
enum Kept<Own, Emulated> {
    /// The pop lands where its push was made (or restores nothing here).
    Nothing,
    /// Pushed on the emulated framebuffer, popping onto the program's own
    /// object: its buffers as they are now (GL_DRAW_BUFFERi / GL_READ_BUFFER).
    Own(Own),
    /// Pushed on the program's object, popping onto the emulated
    /// framebuffer of this drawable: its selection as it is now.
    Emulated(u64, Emulated),
}

impl CrossPop {
    /// Before the driver pops `top` (the matching push's entry): only the
    /// cases that cross framebuffers are queried.
    fn before(gl: &Gl, cur: &Current, st: &mut CtxState) -> CrossPop {
        let Some(top) = st.attribs.last() else {
            return CrossPop {
                draw: Kept::Nothing,
                read: Kept::Nothing,
            };
        };
        let (draw_saved, draw_on) = (top.draw.is_some(), top.draw_on_emulated);
        let (read_saved, read_on) = (top.read.is_some(), top.read_on_emulated);
        let read_d = read_drawable(cur);
        // SAFETY: the program's context is current (callers); queries that
        // raise no error.
        let own = |st: &CtxState, binding| unsafe {
            let name = gl.integer(binding) as u32;
            name != 0 && !st.is_ours(name)
        };
        let draw = if !draw_saved {
            Kept::Nothing
        } else if draw_on {
            if own(st, GL_DRAW_FRAMEBUFFER_BINDING) {
                // SAFETY: as above.
                let n =
                    unsafe { gl.integer(GL_MAX_DRAW_BUFFERS) }.clamp(1, MAX_DRAW_BUFFERS as i32);
                let mut bufs = [GL_NONE; MAX_DRAW_BUFFERS];
                for (i, b) in bufs.iter_mut().enumerate().take(n as usize) {
                    // SAFETY: as above.
                    *b = unsafe { gl.integer(GL_DRAW_BUFFER0 + i as u32) } as u32;
                }
                Kept::Own((bufs, n as usize))
            } else {
                Kept::Nothing
            }
        } else {
            bound(gl, &mut st.fbs, cur.draw, GL_DRAW_FRAMEBUFFER_BINDING)
                .map_or(Kept::Nothing, |fb| {
                    Kept::Emulated(cur.draw, fb.draw_selection())
                })
        };
        let read = if !read_saved {
            Kept::Nothing
        } else if read_on {
            if own(st, GL_READ_FRAMEBUFFER_BINDING) {
                // SAFETY: as above.
                Kept::Own(unsafe { gl.integer(GL_READ_BUFFER) } as u32)
            } else {
                Kept::Nothing
            }
        } else {
            bound(gl, &mut st.fbs, read_d, GL_READ_FRAMEBUFFER_BINDING)
                .map_or(Kept::Nothing, |fb| {
                    Kept::Emulated(read_d, fb.read_selection())
                })
        };
        CrossPop { draw, read }
    }

    /// After the driver's pop of `saved`'s entry: the emulated selections
    /// it saved go back where the emulated framebuffer is bound, and a pop
    /// across framebuffers leaves the bound one's buffers, except GL_NONE.
    fn after(self, gl: &Gl, st: &mut CtxState, saved: &super::context::SavedSelections) {
        // SAFETY (every block): the program's context is current (callers).
        if let Some((d, sel)) = saved.draw {
            let fb = bound(gl, &mut st.fbs, d, GL_DRAW_FRAMEBUFFER_BINDING);
            match (self.draw, fb) {
                (_, Some(fb)) if saved.draw_on_emulated => unsafe {
                    fb.restore_draw_selection(gl, sel)
                },
                (Kept::Own((bufs, n)), _) if !sel.is_none() => unsafe {
                    gl.DrawBuffers(n as i32, bufs.as_ptr())
                },
                (Kept::Emulated(d0, before), _) => {
                    if let Some(fb) = bound(gl, &mut st.fbs, d0, GL_DRAW_FRAMEBUFFER_BINDING) {
                        // The driver popped the program's object's buffers
                        // onto the emulated framebuffer: only GL_NONE fits.
                        let none = (0..MAX_DRAW_BUFFERS as u32)
                            .all(|i| unsafe { gl.integer(GL_DRAW_BUFFER0 + i) } as u32 == GL_NONE);
                        unsafe {
                            if none {
                                let _ = fb.set_draw_buffer(gl, GL_NONE);
                            } else {
                                fb.restore_draw_selection(gl, before);
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        if let Some((d, sel)) = saved.read {
            let fb = bound(gl, &mut st.fbs, d, GL_READ_FRAMEBUFFER_BINDING);
            match (self.read, fb) {
                (_, Some(fb)) if saved.read_on_emulated => unsafe {
                    fb.restore_read_selection(gl, sel)
                },
                (Kept::Own(buf), _) if !sel.is_none() => unsafe { gl.ReadBuffer(buf) },
                (Kept::Emulated(d0, before), _) => {
                    if let Some(fb) = bound(gl, &mut st.fbs, d0, GL_READ_FRAMEBUFFER_BINDING) {
                        let none = unsafe { gl.integer(GL_READ_BUFFER) } as u32 == GL_NONE;
                        unsafe {
                            if none {
                                let _ = fb.set_read_buffer(gl, GL_NONE);
                            } else {
                                fb.restore_read_selection(gl, before);
                            }
                        }
                    }
                }
                _ => {}
            }
        }
    }
}

/// Sets the driver's colour masks to the program's (`st.color_mask`),
/// with alpha never written while an opaque emulated framebuffer is bound
/// for drawing, so that its alpha stays 1.0.
pub(super) fn apply_color_mask(gl: &Gl, formats: BufferFormats, st: &CtxState) {
    // SAFETY: the program's context is current (callers).
    let draw = unsafe { gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) } as u32;
    let keep_alpha = formats.opaque && st.is_ours(draw);
    set_driver_masks(gl, &st.color_mask, keep_alpha);
}

fn set_driver_masks(gl: &Gl, masks: &[[bool; 4]; MASKED_BUFFERS], keep_alpha: bool) {
    let b = |m: [bool; 4]| {
        let [r, g, b, a] = m.map(u8::from);
        (r, g, b, if keep_alpha { 0 } else { a })
    };
    let maski = loaded().ok().and_then(|r| r.extra.color_maski);
    match maski {
        Some(f) if masks.iter().any(|m| *m != masks[0]) => {
            for (i, &m) in masks.iter().enumerate() {
                let (r, g, bl, a) = b(m);
                // SAFETY: the program's context is current; i < 8.
                unsafe { f(i as u32, r, g, bl, a) };
            }
        }
        _ => {
            let (r, g, bl, a) = b(masks[0]);
            // SAFETY: the program's context is current.
            unsafe { gl.ColorMask(r, g, bl, a) };
        }
    }
}

/// The clear colour as the program last set it: GL keeps one clear
/// colour, which glClearColor sets as floats, glClearColorIiEXT /
/// glClearColorIuiEXT (GL_EXT_texture_integer) as integers and
/// glClearColorx / glClearColorxOES (GL_OES_fixed_point) as 16.16 fixed
/// point. The layer sets it back with the same setter, so that the
/// driver's state (GL_COLOR_CLEAR_VALUE) is what the program left.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClearColor {
    /// glClearColor.
    Float([f32; 4]),
    /// glClearColorIiEXT.
    Int([i32; 4]),
    /// glClearColorIuiEXT.
    Uint([u32; 4]),
    /// glClearColorx / glClearColorxOES.
    Fixed([i32; 4]),
}

/// The bits of 1.0f, the alpha an integer clear colour has for a clear of
/// a normalized buffer: Mesa keeps the clear colour as one union of
/// floats and integers (what glGetFloatv(GL_COLOR_CLEAR_VALUE) answers
/// after glClearColorIuiEXT is those bits as floats), so these bits clear
/// alpha to 1.0 there; a driver that converts the integer instead clamps
/// it to 1.0 as well.
const ONE_BITS: u32 = 0x3F80_0000;

impl ClearColor {
    /// The same colour with alpha 1.0, in the same setter's terms.
    fn opaque(self) -> ClearColor {
        match self {
            ClearColor::Float([r, g, b, _]) => ClearColor::Float([r, g, b, 1.0]),
            ClearColor::Int([r, g, b, _]) => ClearColor::Int([r, g, b, ONE_BITS as i32]),
            ClearColor::Uint([r, g, b, _]) => ClearColor::Uint([r, g, b, ONE_BITS]),
            ClearColor::Fixed([r, g, b, _]) => ClearColor::Fixed([r, g, b, 0x1_0000]),
        }
    }

    /// Sets it as the driver's clear colour, with its own setter.
    ///
    /// # Safety
    /// The program's context is current.
    unsafe fn set(self, r: &Real) -> Result<()> {
        let x = &r.extra;
        // SAFETY: the program's context is current (contract).
        unsafe {
            match self {
                ClearColor::Float([cr, cg, cb, ca]) => r.gl.ClearColor(cr, cg, cb, ca),
                ClearColor::Int([cr, cg, cb, ca]) => x
                    .clear_color_ii_ext
                    .ok_or_else(|| lacks("glClearColorIiEXT", "GL_EXT_texture_integer"))?(
                    cr, cg, cb, ca,
                ),
                ClearColor::Uint([cr, cg, cb, ca]) => x
                    .clear_color_iui_ext
                    .ok_or_else(|| lacks("glClearColorIuiEXT", "GL_EXT_texture_integer"))?(
                    cr, cg, cb, ca,
                ),
                ClearColor::Fixed([cr, cg, cb, ca]) => x
                    .clear_colorx
                    .or(x.clear_colorx_oes)
                    .ok_or_else(|| lacks("glClearColorx", "GL_OES_fixed_point"))?(
                    cr, cg, cb, ca
                ),
            }
        }
        Ok(())
    }
}

/// glClearColor, glClearColorIiEXT, glClearColorIuiEXT, glClearColorx and
/// glClearColorxOES (`color` says which): forwarded, and kept as the
/// program's clear colour (see [`clear`]). `fixed_oes` picks
/// glClearColorxOES for a fixed-point colour.
pub fn clear_color(color: ClearColor, fixed_oes: bool) -> Result<()> {
    let r = loaded()?;
    match (color, fixed_oes) {
        (ClearColor::Fixed([cr, cg, cb, ca]), true) => {
            let f = r
                .extra
                .clear_colorx_oes
                .ok_or_else(|| lacks("glClearColorxOES", "GL_OES_fixed_point"))?;
            // SAFETY: forwarded call.
            unsafe { f(cr, cg, cb, ca) }
        }
        // SAFETY: forwarded call.
        _ => unsafe { color.set(r)? },
    }
    if let Some(cur) = current() {
        cur.sc.lock().clear_color = color;
    }
    Ok(())
}

/// glClear. On an opaque emulated framebuffer the colour is cleared with
/// alpha 1.0 and alpha written (what the buffer holds anyway), so that a
/// clear the program masks nothing of stays the driver's fast full clear
/// rather than a masked one (llvmpipe draws a quad for that).
pub fn clear(mask: u32) -> Result<()> {
    super::draws::notice_clear(super::draws::Call {
        family: crate::auto::entry_points::Family::Clear,
        name: "glClear",
        args: &[u64::from(mask)],
    });
    let r = loaded()?;
    let gl = &r.gl;
    let cur = match current() {
        Some(cur) if mask & GL_COLOR_BUFFER_BIT != 0 && cur.sc.formats().opaque => cur,
        _ => {
            // SAFETY: forwarded call.
            unsafe { gl.Clear(mask) };
            return Ok(());
        }
    };
    let st = cur.sc.lock();
    // The binding is asked, not tracked: the query costs ≈ 20 ns on
    // llvmpipe (a 1280x1024 clear ≈ 0.45 ms), while a tracked copy would
    // have to follow every binding change the layer does not see (a layer
    // below it, a binding made through a function pointer it never
    // handed out), and a stale one would let alpha be written.
    // SAFETY: the program's context is current.
    let draw = unsafe { gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) } as u32;
    if !st.is_ours(draw) {
        drop(st);
        // SAFETY: forwarded call.
        unsafe { gl.Clear(mask) };
        return Ok(());
    }
    let color = st.clear_color;
    let mut masks = st.color_mask;
    for m in &mut masks {
        m[3] = true;
    }
    set_driver_masks(gl, &masks, false);
    // SAFETY: the program's context is current. The colour's setter
    // exists: the program set the colour with it.
    let set = unsafe { color.opaque().set(r) };
    if set.is_ok() {
        // SAFETY: as above.
        unsafe { gl.Clear(mask) };
    }
    // SAFETY: as above.
    let back = unsafe { color.set(r) };
    set_driver_masks(gl, &st.color_mask, true);
    set.and(back)
}

/// glColorMask: kept as the program's masks (what GL_COLOR_WRITEMASK
/// answers); the driver's never write alpha while an opaque emulated
/// framebuffer is bound.
pub fn color_mask(red: u8, green: u8, blue: u8, alpha: u8) -> Result<()> {
    let r = loaded()?;
    if let Some(cur) = current() {
        let mut st = cur.sc.lock();
        st.color_mask = [[red != 0, green != 0, blue != 0, alpha != 0]; MASKED_BUFFERS];
        apply_color_mask(&r.gl, cur.sc.formats(), &st);
        return Ok(());
    }
    // SAFETY: forwarded call.
    unsafe { r.gl.ColorMask(red, green, blue, alpha) };
    Ok(())
}

/// The names of glColorMaski: GL 3.0's and the extensions' (each goes to
/// its own function below the layer).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaskiName {
    /// glColorMaski (GL 3.0).
    Core,
    /// glColorMaskIndexedEXT (GL_EXT_draw_buffers2).
    IndexedExt,
    /// glColorMaskiEXT (GL_EXT_draw_buffers_indexed).
    Ext,
    /// glColorMaskiOES (GL_OES_draw_buffers_indexed).
    Oes,
}

/// glColorMaski (or one of its other names, `name`): as [`color_mask`]
/// for draw buffer `index`. An index GL refuses goes to the driver, which
/// raises GL_INVALID_VALUE.
pub fn color_maski(
    name: MaskiName,
    index: u32,
    red: u8,
    green: u8,
    blue: u8,
    alpha: u8,
) -> Result<()> {
    let r = loaded()?;
    let x = &r.extra;
    let (f, gl_name, offered_by) = match name {
        MaskiName::Core => (x.color_maski, "glColorMaski", "GL 3.0"),
        MaskiName::IndexedExt => (
            x.color_mask_indexed_ext,
            "glColorMaskIndexedEXT",
            "GL_EXT_draw_buffers2",
        ),
        MaskiName::Ext => (
            x.color_maski_ext,
            "glColorMaskiEXT",
            "GL_EXT_draw_buffers_indexed",
        ),
        MaskiName::Oes => (
            x.color_maski_oes,
            "glColorMaskiOES",
            "GL_OES_draw_buffers_indexed",
        ),
    };
    let f = f.ok_or_else(|| lacks(gl_name, offered_by))?;
    if let Some(cur) = current() {
        if (index as usize) < MASKED_BUFFERS {
            let mut st = cur.sc.lock();
            st.color_mask[index as usize] = [red != 0, green != 0, blue != 0, alpha != 0];
            apply_color_mask(&r.gl, cur.sc.formats(), &st);
            return Ok(());
        }
    }
    // SAFETY: forwarded call.
    unsafe { f(index, red, green, blue, alpha) };
    Ok(())
}

/// One of the indexed glGet functions: its GL name, what brings it (a GL
/// version or an extension), and where the layer finds it below itself.
pub struct IndexedGet<T: 'static> {
    /// The GL name, e.g. "glGetIntegeri_v".
    pub name: &'static str,
    /// The GL version or extension that brings it.
    pub offered_by: &'static str,
    /// The function below the layer.
    pub pick: fn(&super::real::Extra) -> Option<super::real::GetIndexed<T>>,
    /// How GL turns a boolean state into the query's type.
    pub convert: fn(i32) -> T,
}

/// `glGetBooleani_v`.
pub const GET_BOOLEANI_V: IndexedGet<u8> = IndexedGet {
    name: "glGetBooleani_v",
    offered_by: "GL 3.0",
    pick: |x| x.get_booleani_v,
    convert: |v| (v != 0) as u8,
};

/// `glGetBooleanIndexedvEXT`.
pub const GET_BOOLEAN_INDEXEDV_EXT: IndexedGet<u8> = IndexedGet {
    name: "glGetBooleanIndexedvEXT",
    offered_by: "GL_EXT_draw_buffers2",
    pick: |x| x.get_boolean_indexedv_ext,
    convert: |v| (v != 0) as u8,
};

/// `glGetIntegeri_v`.
pub const GET_INTEGERI_V: IndexedGet<i32> = IndexedGet {
    name: "glGetIntegeri_v",
    offered_by: "GL 3.0",
    pick: |x| x.get_integeri_v,
    convert: |v| v,
};

/// `glGetIntegerIndexedvEXT`.
pub const GET_INTEGER_INDEXEDV_EXT: IndexedGet<i32> = IndexedGet {
    name: "glGetIntegerIndexedvEXT",
    offered_by: "GL_EXT_draw_buffers2",
    pick: |x| x.get_integer_indexedv_ext,
    convert: |v| v,
};

/// `glGetInteger64i_v`.
pub const GET_INTEGER64I_V: IndexedGet<i64> = IndexedGet {
    name: "glGetInteger64i_v",
    offered_by: "GL 3.2",
    pick: |x| x.get_integer64i_v,
    convert: |v| v as i64,
};

/// `glGetFloati_v`.
pub const GET_FLOATI_V: IndexedGet<f32> = IndexedGet {
    name: "glGetFloati_v",
    offered_by: "GL 4.1",
    pick: |x| x.get_floati_v,
    convert: |v| v as f32,
};

/// `glGetFloati_vEXT`.
pub const GET_FLOATI_V_EXT: IndexedGet<f32> = IndexedGet {
    name: "glGetFloati_vEXT",
    offered_by: "GL_EXT_direct_state_access",
    pick: |x| x.get_floati_v_ext,
    convert: |v| v as f32,
};

/// `glGetFloati_vOES`.
pub const GET_FLOATI_V_OES: IndexedGet<f32> = IndexedGet {
    name: "glGetFloati_vOES",
    offered_by: "GL_OES_viewport_array",
    pick: |x| x.get_floati_v_oes,
    convert: |v| v as f32,
};

/// `glGetFloatIndexedvEXT`.
pub const GET_FLOAT_INDEXEDV_EXT: IndexedGet<f32> = IndexedGet {
    name: "glGetFloatIndexedvEXT",
    offered_by: "GL_EXT_direct_state_access",
    pick: |x| x.get_float_indexedv_ext,
    convert: |v| v as f32,
};

/// `glGetDoublei_v`.
pub const GET_DOUBLEI_V: IndexedGet<f64> = IndexedGet {
    name: "glGetDoublei_v",
    offered_by: "GL 4.1",
    pick: |x| x.get_doublei_v,
    convert: f64::from,
};

/// `glGetDoublei_vEXT`.
pub const GET_DOUBLEI_V_EXT: IndexedGet<f64> = IndexedGet {
    name: "glGetDoublei_vEXT",
    offered_by: "GL_EXT_direct_state_access",
    pick: |x| x.get_doublei_v_ext,
    convert: f64::from,
};

/// `glGetDoubleIndexedvEXT`.
pub const GET_DOUBLE_INDEXEDV_EXT: IndexedGet<f64> = IndexedGet {
    name: "glGetDoubleIndexedvEXT",
    offered_by: "GL_EXT_direct_state_access",
    pick: |x| x.get_double_indexedv_ext,
    convert: f64::from,
};

/// glGetBooleani_v, glGetIntegeri_v, glGetInteger64i_v, glGetFloati_v,
/// glGetDoublei_v and their extension names (`get` says which):
/// GL_COLOR_WRITEMASK answers the program's masks; every other state is
/// the driver's answer. Refused: `data` NULL (`refuse_null`).
///
/// # Safety
/// `data` must be valid for the values `pname` returns (GL's contract).
pub unsafe fn get_indexed<T>(
    get: &IndexedGet<T>,
    pname: u32,
    index: u32,
    data: *mut T,
) -> Result<()> {
    let r = loaded()?;
    let f = (get.pick)(&r.extra).ok_or_else(|| lacks(get.name, get.offered_by))?;
    if data.is_null() {
        return Err(refuse_null(r, "data"));
    }
    // SAFETY (both): forwarded call.
    let forward = || unsafe { f(pname, index, data) };
    let cur = match current() {
        Some(cur) if pname == GL_COLOR_WRITEMASK && (index as usize) < MASKED_BUFFERS => cur,
        _ => {
            forward();
            return Ok(());
        }
    };
    if driver_accepts(&r.gl, &cur, forward) {
        // SAFETY: GL_COLOR_WRITEMASK returns four values (GL's contract).
        unsafe { write_mask(index as usize, data, get.convert) };
    }
    Ok(())
}

/// glBlitFramebuffer: a blit ignores the colour masks, so one into an
/// opaque emulated framebuffer has its alpha put back to 1.0.
#[allow(clippy::too_many_arguments)]
pub fn blit_framebuffer(src: [i32; 4], dst: [i32; 4], mask: u32, filter: u32) -> Result<()> {
    let r = loaded()?;
    let args = [
        src[0] as u64,
        src[1] as u64,
        src[2] as u64,
        src[3] as u64,
        dst[0] as u64,
        dst[1] as u64,
        dst[2] as u64,
        dst[3] as u64,
        u64::from(mask),
        u64::from(filter),
    ];
    let call = super::draws::Call {
        family: crate::auto::entry_points::Family::Blit,
        name: "glBlitFramebuffer",
        args: &args,
    };
    // Through the draws' hook: the size check after a present, and under
    // --auto a blit into the window reaches each eye.
    super::draws::around(call, || {
        // SAFETY: forwarded call.
        unsafe {
            r.gl.BlitFramebuffer(
                src[0], src[1], src[2], src[3], dst[0], dst[1], dst[2], dst[3], mask, filter,
            )
        }
    });
    if mask & GL_COLOR_BUFFER_BIT != 0 {
        if let Some(cur) = current() {
            // SAFETY: the program's context is current.
            let draw = unsafe { r.gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) } as u32;
            restore_alpha(&r.gl, &cur, draw);
        }
    }
    Ok(())
}

/// Puts alpha back to 1.0 in the draw buffers of `fbo` when it is an
/// opaque emulated framebuffer of the current context (after a blit or a
/// clear that the colour masks did not stop), restoring the program's
/// bindings and masks.
pub(super) fn restore_alpha(gl: &Gl, cur: &Current, fbo: u32) {
    if !cur.sc.formats().opaque {
        return;
    }
    let st = cur.sc.lock();
    if !st.is_ours(fbo) {
        return;
    }
    // SAFETY: the program's context is current.
    unsafe {
        let draw = gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32;
        // Rasterizer discard stops clears but not blits (GL 4.5 §14.1):
        // off for the clear of alpha, as the blit wrote anyway.
        let discard = gl.IsEnabled(GL_RASTERIZER_DISCARD) != 0;
        if discard {
            gl.Disable(GL_RASTERIZER_DISCARD);
        }
        gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        gl.ColorMask(0, 0, 0, 1);
        let one = [0.0f32, 0.0, 0.0, 1.0];
        for i in 0..MASKED_BUFFERS as u32 {
            if gl.integer(GL_DRAW_BUFFER0 + i) as u32 != GL_NONE {
                gl.ClearBufferfv(GL_COLOR, i as i32, one.as_ptr());
            }
        }
        gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, draw);
        if discard {
            gl.Enable(GL_RASTERIZER_DISCARD);
        }
    }
    apply_color_mask(gl, cur.sc.formats(), &st);
}

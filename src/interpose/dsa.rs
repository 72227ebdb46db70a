//! glClearBuffer and GL 4.5 direct state access on framebuffer 0, and the
//! link of programs whose fragment output 0 must reach every selected
//! buffer, while a stereo context is current. With none current, each goes
//! straight to the driver after one thread-local test.
//!
//! - glClearBuffer{fv,iv,uiv}(GL_COLOR, 0, …) and glClearNamedFramebuffer*
//!   (0, GL_COLOR, 0, …) under a glDrawBuffer name selecting several
//!   buffers clear each of them (GL 4.5 §17.4.3); draw buffers 1… are
//!   GL_NONE then and clear nothing. glClearBufferfi and depth/stencil
//!   clears need nothing: both eyes share one depth/stencil buffer.
//! - glNamedFramebufferDrawBuffer(s) / ReadBuffer(0, …) set the emulated
//!   selections with the errors of [`crate::stereo::buffers`], wherever
//!   the program has bound its own framebuffer;
//! - glBlitNamedFramebuffer with 0 on either side blits from or into the
//!   emulated buffers (the read buffer, the draw buffers);
//! - glGetNamedFramebufferAttachmentParameteriv(0, …) answers as
//!   glGetFramebufferAttachmentParameteriv on framebuffer 0 does
//!   (GL_FRAMEBUFFER_DEFAULT, the window's sizes, right buffers as their
//!   left twins); glGetNamedFramebufferParameteriv
//!   (0, …) and glGetFramebufferParameteriv with framebuffer 0 bound
//!   answer from the window's framebuffer (GL_SAMPLES, GL_SAMPLE_BUFFERS,
//!   the implementation read format and type, and the errors), with
//!   GL_STEREO and GL_DOUBLEBUFFER those of the emulated one;
//! - glInvalidate(Sub)Framebuffer with framebuffer 0 bound, and
//!   glInvalidateNamedFramebuffer(Sub)Data on 0, are validated as Mesa
//!   validates a window (GL_COLOR, GL_DEPTH, GL_STENCIL, GL_FRONT_LEFT …
//!   GL_BACK_RIGHT: [`crate::stereo::buffers::default_invalidate_error`]):
//!   invalidation is a hint, and the emulated buffers keep their contents;
//! - glCheckNamedFramebufferStatus(0, …) is the emulated framebuffer
//!   object's status; glReadnPixels goes to the driver unchanged (the read
//!   framebuffer bound is the emulated one).
//!
//! What describes the window's own buffers (component sizes and encoding,
//! samples, the read format) is asked of framebuffer 0 as the layer below
//! presents it, through the non-named queries (which VirtualGL translates
//! for the framebuffer object it stands in with); nothing is asked of a
//! framebuffer 0 by name, which a layer below may have left undefined.
//! - glLinkProgram / glCreateShaderProgramv: a program with a user-defined
//!   fragment output at location 0 is relinked with copies of it
//!   ([`crate::stereo::outputs`]), so output 0 reaches every buffer a
//!   glDrawBuffer name selects.

use std::ffi::{CStr, c_char, c_void};
use std::sync::OnceLock;

use super::context::{Current, current};
use super::gl::{
    bound, emulated_attachment, missing, read_drawable, refuse_null, with_window_framebuffer,
};
use super::real::{Real, loaded};
use crate::error::{Error, Result};
use crate::gl::enums::*;
use crate::stereo::buffers::{default_invalidate_error, gl_error_code};
use crate::stereo::emulated::{DrawSlots, EmulatedFramebuffer};
use crate::stereo::outputs::{LinkFns, Outcome};

pub(super) const GL_COLOR: u32 = 0x1800;
const GL_FRAGMENT_SHADER: u32 = 0x8B30;

type ClearFn<T> = unsafe extern "system" fn(u32, i32, *const T);
type ClearNamedFn<T> = unsafe extern "system" fn(u32, u32, i32, *const T);
type InvalidateFn = unsafe extern "system" fn(u32, i32, *const u32);
type InvalidateSubFn = unsafe extern "system" fn(u32, i32, *const u32, i32, i32, i32, i32);
type InvalidateNamedFn = unsafe extern "system" fn(u32, i32, *const u32);
type InvalidateNamedSubFn = unsafe extern "system" fn(u32, i32, *const u32, i32, i32, i32, i32);
type CheckNamedFn = unsafe extern "system" fn(u32, u32) -> u32;
type ParamFn = unsafe extern "system" fn(u32, u32, *mut i32);
type AttachmentFn = unsafe extern "system" fn(u32, u32, u32, *mut i32);
type BlitFn = unsafe extern "system" fn(u32, u32, i32, i32, i32, i32, i32, i32, i32, i32, u32, u32);

macro_rules! fns {
    ($( $field:ident: $ty:ty = $sym:literal; )*) => {
        /// The real functions of this module (None where the driver lacks
        /// one: the program cannot have called it then, as
        /// glXGetProcAddress gave it nothing to call).
        pub struct Fns {
            $( $field: Option<$ty>, )*
            /// What relinking needs (None before GL 4.3).
            link: Option<LinkFns>,
        }

        fn load() -> Fns {
            let get = |name: &CStr| -> *const c_void {
                // SAFETY: a NUL-terminated name.
                unsafe { super::real::get_proc_address(name.as_ptr()) }
                    .map_or(std::ptr::null(), |f| f as *const c_void)
            };
            Fns {
                $( $field: {
                    let p = get($sym);
                    // SAFETY: the named function, with its Khronos signature (the field's type).
                    (!p.is_null()).then(|| unsafe { std::mem::transmute::<*const c_void, $ty>(p) })
                }, )*
                // SAFETY: `get` returns the named function or NULL.
                link: unsafe { LinkFns::load(get) },
            }
        }
    };
}

fns! {
    clear_fv: ClearFn<f32> = c"glClearBufferfv";
    clear_iv: ClearFn<i32> = c"glClearBufferiv";
    clear_uiv: ClearFn<u32> = c"glClearBufferuiv";
    clear_named_fv: ClearNamedFn<f32> = c"glClearNamedFramebufferfv";
    clear_named_iv: ClearNamedFn<i32> = c"glClearNamedFramebufferiv";
    clear_named_uiv: ClearNamedFn<u32> = c"glClearNamedFramebufferuiv";
    clear_named_fi: unsafe extern "system" fn(u32, u32, i32, f32, i32) = c"glClearNamedFramebufferfi";
    named_draw_buffer: unsafe extern "system" fn(u32, u32) = c"glNamedFramebufferDrawBuffer";
    named_draw_buffers: unsafe extern "system" fn(u32, i32, *const u32) = c"glNamedFramebufferDrawBuffers";
    named_read_buffer: unsafe extern "system" fn(u32, u32) = c"glNamedFramebufferReadBuffer";
    blit_named: BlitFn = c"glBlitNamedFramebuffer";
    invalidate: InvalidateFn = c"glInvalidateFramebuffer";
    invalidate_sub: InvalidateSubFn = c"glInvalidateSubFramebuffer";
    invalidate_named: InvalidateNamedFn = c"glInvalidateNamedFramebufferData";
    invalidate_named_sub: InvalidateNamedSubFn = c"glInvalidateNamedFramebufferSubData";
    check_named: CheckNamedFn = c"glCheckNamedFramebufferStatus";
    check_named_ext: CheckNamedFn = c"glCheckNamedFramebufferStatusEXT";
    named_attachment: AttachmentFn = c"glGetNamedFramebufferAttachmentParameteriv";
    named_parameter: ParamFn = c"glGetNamedFramebufferParameteriv";
    parameter: ParamFn = c"glGetFramebufferParameteriv";
    create_shader_programv: unsafe extern "system" fn(u32, i32, *const *const c_char) -> u32 = c"glCreateShaderProgramv";
}

fn fns() -> &'static Fns {
    static FNS: OnceLock<Fns> = OnceLock::new();
    FNS.get_or_init(load)
}

/// What relinking needs (None before GL 4.3).
pub(super) fn link_fns() -> Option<&'static LinkFns> {
    fns().link.as_ref()
}

/// The real function, or the refusal a missing one gets (the program
/// called a function the driver does not have).
fn need<T>(f: Option<T>, name: &str) -> Result<T> {
    f.ok_or_else(|| {
        Error::BackendUnavailable(format!(
            "the GL library lacks {name}: it needs a newer GL driver"
        ))
    })
}

/// The emulated framebuffer of the context's draw drawable (`read` false)
/// or read drawable, when the current context is a stereo one that has it:
/// what framebuffer 0 names in direct state access.
fn with_fb0<T>(
    cur: &Current,
    read: bool,
    f: impl FnOnce(&mut EmulatedFramebuffer, &mut Vec<u32>) -> T,
) -> Option<T> {
    let drawable = if read { read_drawable(cur) } else { cur.draw };
    let mut st = cur.sc.lock();
    let st = &mut *st;
    let fb = &mut st.fbs.get_mut(&drawable)?.fb;
    let mut errors = Vec::new();
    let v = f(fb, &mut errors);
    if let (Some(&e), Ok(r)) = (errors.first(), super::real::real()) {
        // The first error only: GL keeps one (later ones are dropped).
        st.push_error(&r.gl, e);
    }
    Some(v)
}

/// glNamedFramebuffer{DrawBuffer,DrawBuffers,ReadBuffer} on `framebuffer`:
/// on 0, when it is emulated, `select` changes the emulated selection (the
/// read drawable's when `read`), its GL error queued; otherwise `forward`
/// calls the driver.
fn select_named(
    framebuffer: u32,
    read: bool,
    select: impl FnOnce(&mut EmulatedFramebuffer) -> crate::Result<()>,
    forward: impl FnOnce(),
) {
    let emulated = framebuffer == 0
        && current().is_some_and(|cur| {
            with_fb0(&cur, read, |fb, errors| {
                if let Err(e) = select(fb) {
                    errors.push(gl_error_code(&e));
                }
            })
            .is_some()
        });
    if !emulated {
        forward();
    }
}

/// The value types of glClearBuffer{fv,iv,uiv} and
/// glClearNamedFramebuffer{fv,iv,uiv} (f32, i32, u32): each names its
/// real functions.
pub trait ClearValue: Sized {
    /// glClearBuffer's name for this type ("glClearBufferfv" …).
    const CLEAR: &'static str;
    /// glClearNamedFramebuffer's name for this type.
    const CLEAR_NAMED: &'static str;
    /// The real glClearBuffer for this type.
    fn clear(f: &Fns) -> Option<ClearFn<Self>>;
    /// The real glClearNamedFramebuffer for this type.
    fn clear_named(f: &Fns) -> Option<ClearNamedFn<Self>>;
}

macro_rules! clear_value {
    ($( $t:ty: $clear:ident, $named:ident, $suffix:literal; )*) => {$(
        impl ClearValue for $t {
            const CLEAR: &'static str = concat!("glClearBuffer", $suffix);
            const CLEAR_NAMED: &'static str = concat!("glClearNamedFramebuffer", $suffix);
            fn clear(f: &Fns) -> Option<ClearFn<Self>> {
                f.$clear
            }
            fn clear_named(f: &Fns) -> Option<ClearNamedFn<Self>> {
                f.$named
            }
        }
    )*};
}

clear_value! {
    f32: clear_fv, clear_named_fv, "fv";
    i32: clear_iv, clear_named_iv, "iv";
    u32: clear_uiv, clear_named_uiv, "uiv";
}

/// glClearBuffer{fv,iv,uiv}. Refused: `value` NULL (`refuse_null`).
///
/// # Safety
/// `value` must hold the values GL reads for `buffer` (GL's contract).
pub unsafe fn clear_buffer<T: ClearValue>(
    buffer: u32,
    drawbuffer: i32,
    value: *const T,
) -> Result<()> {
    super::draws::notice_clear(super::draws::Call {
        family: crate::auto::entry_points::Family::Clear,
        name: T::CLEAR,
        args: &[u64::from(buffer), drawbuffer as u64],
    });
    let r = loaded()?;
    let real = need(T::clear(fns()), T::CLEAR)?;
    if value.is_null() {
        return Err(refuse_null(r, "value"));
    }
    if buffer == GL_COLOR {
        if let Some(cur) = current() {
            let slots: Option<DrawSlots> = {
                let mut st = cur.sc.lock();
                bound(&r.gl, &mut st.fbs, cur.draw, GL_DRAW_FRAMEBUFFER_BINDING)
                    .map(|fb| fb.draw_buffer_slots(drawbuffer))
            };
            if let Some(slots) = slots {
                for &slot in slots.as_slice() {
                    // SAFETY: forwarded call, one slot at a time.
                    unsafe { real(buffer, slot, value) };
                }
                return Ok(());
            }
        }
    }
    // SAFETY: forwarded call.
    unsafe { real(buffer, drawbuffer, value) };
    Ok(())
}

/// Framebuffer 0's object and the slots of `drawbuffer` (for GL_COLOR),
/// when framebuffer 0 is emulated.
fn fb0_slots(buffer: u32, drawbuffer: i32) -> Option<(u32, DrawSlots)> {
    let cur = current()?;
    with_fb0(&cur, false, |fb, _| {
        let slots = if buffer == GL_COLOR {
            fb.draw_buffer_slots(drawbuffer)
        } else {
            DrawSlots::one(drawbuffer)
        };
        (fb.app_fbo(), slots)
    })
}

/// glClearNamedFramebuffer{fv,iv,uiv}. Refused: `value` NULL.
///
/// # Safety
/// `value` must hold the values GL reads for `buffer` (GL's contract).
pub unsafe fn clear_named_framebuffer<T: ClearValue>(
    framebuffer: u32,
    buffer: u32,
    drawbuffer: i32,
    value: *const T,
) -> Result<()> {
    super::draws::notice_clear(super::draws::Call {
        family: crate::auto::entry_points::Family::Clear,
        name: T::CLEAR_NAMED,
        args: &[u64::from(framebuffer), u64::from(buffer), drawbuffer as u64],
    });
    let r = loaded()?;
    let real = need(T::clear_named(fns()), T::CLEAR_NAMED)?;
    if value.is_null() {
        return Err(refuse_null(r, "value"));
    }
    if framebuffer == 0 {
        if let Some((fbo, slots)) = fb0_slots(buffer, drawbuffer) {
            for &slot in slots.as_slice() {
                // SAFETY: forwarded call on the emulated framebuffer object.
                unsafe { real(fbo, buffer, slot, value) };
            }
            if buffer == GL_COLOR {
                // The masks in force are those of the framebuffer bound,
                // which may write alpha.
                if let Some(cur) = current() {
                    super::gl::restore_alpha(&r.gl, &cur, fbo);
                }
            }
            return Ok(());
        }
    }
    // SAFETY: forwarded call.
    unsafe { real(framebuffer, buffer, drawbuffer, value) };
    Ok(())
}

/// glClearNamedFramebufferfi: framebuffer 0's depth/stencil buffer is the
/// emulated one (both eyes share it).
pub fn clear_named_framebufferfi(
    framebuffer: u32,
    buffer: u32,
    drawbuffer: i32,
    depth: f32,
    stencil: i32,
) -> Result<()> {
    super::draws::notice_clear(super::draws::Call {
        family: crate::auto::entry_points::Family::Clear,
        name: "glClearNamedFramebufferfi",
        args: &[u64::from(framebuffer), u64::from(buffer), drawbuffer as u64],
    });
    loaded()?;
    let real = need(fns().clear_named_fi, "glClearNamedFramebufferfi")?;
    let fbo = if framebuffer == 0 {
        current()
            .and_then(|cur| with_fb0(&cur, false, |fb, _| fb.app_fbo()))
            .unwrap_or(0)
    } else {
        framebuffer
    };
    // SAFETY: forwarded call.
    unsafe { real(fbo, buffer, drawbuffer, depth, stencil) };
    Ok(())
}

/// glNamedFramebufferDrawBuffer.
pub fn named_framebuffer_draw_buffer(framebuffer: u32, buf: u32) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().named_draw_buffer, "glNamedFramebufferDrawBuffer")?;
    select_named(
        framebuffer,
        false,
        // SAFETY: the program's context is current.
        |fb| unsafe { fb.set_draw_buffer(&r.gl, buf) },
        // SAFETY: forwarded call.
        || unsafe { real(framebuffer, buf) },
    );
    Ok(())
}

/// glNamedFramebufferDrawBuffers. Refused: `bufs` NULL with `n` > 0.
///
/// # Safety
/// `bufs` must hold `n` values (GL's contract).
pub unsafe fn named_framebuffer_draw_buffers(
    framebuffer: u32,
    n: i32,
    bufs: *const u32,
) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().named_draw_buffers, "glNamedFramebufferDrawBuffers")?;
    if missing(n, bufs) {
        return Err(refuse_null(r, "bufs"));
    }
    select_named(
        framebuffer,
        false,
        |fb| {
            if n < 0 {
                return Err(Error::invalid_value(
                    "glNamedFramebufferDrawBuffers: n is negative (GL_INVALID_VALUE)",
                ));
            }
            let names = if n == 0 {
                &[][..]
            } else {
                // SAFETY: GL's contract: `bufs` holds n values.
                unsafe { std::slice::from_raw_parts(bufs, n as usize) }
            };
            // SAFETY: the program's context is current.
            unsafe { fb.set_draw_buffers(&r.gl, names) }
        },
        // SAFETY: forwarded call.
        || unsafe { real(framebuffer, n, bufs) },
    );
    Ok(())
}

/// glNamedFramebufferReadBuffer.
pub fn named_framebuffer_read_buffer(framebuffer: u32, src: u32) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().named_read_buffer, "glNamedFramebufferReadBuffer")?;
    select_named(
        framebuffer,
        true,
        // SAFETY: the program's context is current.
        |fb| unsafe { fb.set_read_buffer(&r.gl, src) },
        // SAFETY: forwarded call.
        || unsafe { real(framebuffer, src) },
    );
    Ok(())
}

/// glBlitNamedFramebuffer: 0 on either side is the emulated framebuffer
/// (its read buffer, its draw buffers).
#[allow(clippy::too_many_arguments)]
pub fn blit_named_framebuffer(
    read: u32,
    draw: u32,
    src: [i32; 4],
    dst: [i32; 4],
    mask: u32,
    filter: u32,
) -> Result<()> {
    super::draws::notice(crate::auto::entry_points::Family::Blit);
    let r = loaded()?;
    let real = need(fns().blit_named, "glBlitNamedFramebuffer")?;
    let (mut read, mut draw) = (read, draw);
    if let Some(cur) = current() {
        if read == 0 {
            read = with_fb0(&cur, true, |fb, _| fb.app_fbo()).unwrap_or(0);
        }
        if draw == 0 {
            draw = with_fb0(&cur, false, |fb, _| fb.app_fbo()).unwrap_or(0);
        }
    }
    // SAFETY: forwarded call.
    unsafe {
        real(
            read, draw, src[0], src[1], src[2], src[3], dst[0], dst[1], dst[2], dst[3], mask,
            filter,
        )
    };
    if mask & GL_COLOR_BUFFER_BIT != 0 {
        // A blit ignores the colour masks: an opaque emulated framebuffer
        // gets its alpha of 1.0 back.
        if let Some(cur) = current() {
            super::gl::restore_alpha(&r.gl, &cur, draw);
        }
    }
    Ok(())
}

/// Whether the emulated framebuffer is what `target` has bound (GL_FRAMEBUFFER
/// and GL_DRAW_FRAMEBUFFER: the draw binding).
fn emulated_at(r: &Real, cur: &Current, target: u32) -> bool {
    let (binding, drawable) = match target {
        GL_FRAMEBUFFER | GL_DRAW_FRAMEBUFFER => (GL_DRAW_FRAMEBUFFER_BINDING, cur.draw),
        GL_READ_FRAMEBUFFER => (GL_READ_FRAMEBUFFER_BINDING, read_drawable(cur)),
        _ => return false,
    };
    let mut st = cur.sc.lock();
    bound(&r.gl, &mut st.fbs, drawable, binding).is_some()
}

/// Invalidation of the emulated default framebuffer (`size`: the Sub
/// forms' width and height): validated as a driver validates a window
/// ([`default_invalidate_error`], the error queued), whatever the layer
/// below has as framebuffer 0; the eyes keep their contents (a hint GL
/// lets an implementation ignore).
///
/// # Safety
/// `attachments` holds `n` values when `n` > 0 (GL's contract).
unsafe fn invalidate_emulated(
    r: &Real,
    cur: &Current,
    n: i32,
    attachments: *const u32,
    size: Option<(i32, i32)>,
) {
    let list = if n > 0 {
        // SAFETY: contract; not NULL (callers refuse that).
        unsafe { std::slice::from_raw_parts(attachments, n as usize) }
    } else {
        &[]
    };
    if let Some(e) = default_invalidate_error(n, list, size) {
        cur.sc.lock().push_error(&r.gl, e);
    }
}

/// glInvalidateFramebuffer: with framebuffer 0 bound at `target`,
/// validated as a driver validates a window's, the eyes kept (a hint).
/// Refused: `attachments` NULL with n > 0.
///
/// # Safety
/// `attachments` must hold `n` values (GL's contract).
pub unsafe fn invalidate_framebuffer(target: u32, n: i32, attachments: *const u32) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().invalidate, "glInvalidateFramebuffer")?;
    if missing(n, attachments) {
        return Err(refuse_null(r, "attachments"));
    }
    match current() {
        // SAFETY: contract.
        Some(cur) if emulated_at(r, &cur, target) => unsafe {
            invalidate_emulated(r, &cur, n, attachments, None)
        },
        // SAFETY: forwarded call.
        _ => unsafe { real(target, n, attachments) },
    }
    Ok(())
}

/// glInvalidateSubFramebuffer: as [`invalidate_framebuffer`].
///
/// # Safety
/// As [`invalidate_framebuffer`].
pub unsafe fn invalidate_sub_framebuffer(
    target: u32,
    n: i32,
    attachments: *const u32,
    rect: [i32; 4],
) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().invalidate_sub, "glInvalidateSubFramebuffer")?;
    if missing(n, attachments) {
        return Err(refuse_null(r, "attachments"));
    }
    let [x, y, w, h] = rect;
    match current() {
        // SAFETY: contract.
        Some(cur) if emulated_at(r, &cur, target) => unsafe {
            invalidate_emulated(r, &cur, n, attachments, Some((w, h)))
        },
        // SAFETY: forwarded call.
        _ => unsafe { real(target, n, attachments, x, y, w, h) },
    }
    Ok(())
}

/// The current stereo context, when framebuffer 0 is emulated in it (what
/// direct state access on 0 names).
fn emulated_fb0() -> Option<Current> {
    current().filter(|c| with_fb0(c, false, |_, _| ()).is_some())
}

/// glInvalidateNamedFramebufferData: on framebuffer 0, when it is
/// emulated, as [`invalidate_framebuffer`]. Refused: `attachments` NULL
/// with n > 0.
///
/// # Safety
/// `attachments` must hold `n` values (GL's contract).
pub unsafe fn invalidate_named_framebuffer_data(
    framebuffer: u32,
    n: i32,
    attachments: *const u32,
) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().invalidate_named, "glInvalidateNamedFramebufferData")?;
    if missing(n, attachments) {
        return Err(refuse_null(r, "attachments"));
    }
    match emulated_fb0().filter(|_| framebuffer == 0) {
        // SAFETY: contract.
        Some(cur) => unsafe { invalidate_emulated(r, &cur, n, attachments, None) },
        // SAFETY: forwarded call.
        None => unsafe { real(framebuffer, n, attachments) },
    }
    Ok(())
}

/// glInvalidateNamedFramebufferSubData: as
/// [`invalidate_named_framebuffer_data`].
///
/// # Safety
/// As [`invalidate_named_framebuffer_data`].
pub unsafe fn invalidate_named_framebuffer_sub_data(
    framebuffer: u32,
    n: i32,
    attachments: *const u32,
    rect: [i32; 4],
) -> Result<()> {
    let r = loaded()?;
    let real = need(
        fns().invalidate_named_sub,
        "glInvalidateNamedFramebufferSubData",
    )?;
    if missing(n, attachments) {
        return Err(refuse_null(r, "attachments"));
    }
    let [x, y, w, h] = rect;
    match emulated_fb0().filter(|_| framebuffer == 0) {
        // SAFETY: contract.
        Some(cur) => unsafe { invalidate_emulated(r, &cur, n, attachments, Some((w, h))) },
        // SAFETY: forwarded call.
        None => unsafe { real(framebuffer, n, attachments, x, y, w, h) },
    }
    Ok(())
}

/// glCheckNamedFramebufferStatus (…EXT when `ext`): framebuffer 0, when it
/// is emulated, is answered by the emulated framebuffer's own object (the
/// read drawable's for GL_READ_FRAMEBUFFER; the driver checks `target`),
/// whatever the layer below has as framebuffer 0 (VirtualGL makes contexts
/// current without a surface: there it is GL_FRAMEBUFFER_UNDEFINED).
pub fn check_named_framebuffer_status(framebuffer: u32, target: u32, ext: bool) -> Result<u32> {
    loaded()?;
    let real = if ext {
        need(fns().check_named_ext, "glCheckNamedFramebufferStatusEXT")?
    } else {
        need(fns().check_named, "glCheckNamedFramebufferStatus")?
    };
    let own = (framebuffer == 0)
        .then(current)
        .flatten()
        .and_then(|cur| with_fb0(&cur, target == GL_READ_FRAMEBUFFER, |fb, _| fb.app_fbo()))
        .filter(|&fbo| fbo != 0);
    // SAFETY: forwarded call, on the emulated framebuffer's object for 0.
    Ok(unsafe { real(own.unwrap_or(framebuffer), target) })
}

/// glGetNamedFramebufferAttachmentParameteriv: on framebuffer 0, as
/// glGetFramebufferAttachmentParameteriv on the emulated default
/// framebuffer. Refused: `params` NULL.
///
/// # Safety
/// `params` must be valid for one value (GL's contract).
pub unsafe fn get_named_framebuffer_attachment_parameteriv(
    framebuffer: u32,
    attachment: u32,
    pname: u32,
    params: *mut i32,
) -> Result<()> {
    let r = loaded()?;
    let real = need(
        fns().named_attachment,
        "glGetNamedFramebufferAttachmentParameteriv",
    )?;
    if params.is_null() {
        return Err(refuse_null(r, "params"));
    }
    if framebuffer == 0 {
        if let Some(cur) = emulated_fb0() {
            // The window's buffer answers as glGetFramebufferAttachmentParameteriv
            // finds it, through the layer below (VirtualGL stands in for
            // framebuffer 0 there; the named form on 0 would ask a context
            // current without a surface).
            // SAFETY: the program's context is current; `params` not NULL.
            unsafe {
                emulated_attachment(&r.gl, &cur, attachment, pname, params, |twin| {
                    with_window_framebuffer(&r.gl, || {
                        r.gl.GetFramebufferAttachmentParameteriv(
                            GL_DRAW_FRAMEBUFFER,
                            twin,
                            pname,
                            params,
                        )
                    })
                })
            };
            return Ok(());
        }
    }
    // SAFETY: forwarded call.
    unsafe { real(framebuffer, attachment, pname, params) };
    Ok(())
}

/// GL_STEREO and GL_DOUBLEBUFFER of the emulated framebuffer, written over
/// the window's answer.
fn stereo_parameter(cur: &Current, pname: u32, params: *mut i32) {
    let shape = cur.sc.program_shape();
    let v = match pname {
        GL_STEREO => shape.stereo,
        GL_DOUBLEBUFFER => shape.double_buffered,
        _ => return,
    };
    // SAFETY: not NULL (callers), one value.
    unsafe { *params = v as i32 };
}

/// glGetNamedFramebufferParameteriv: on framebuffer 0, the window's
/// framebuffer answers (values and errors), with the emulated GL_STEREO
/// and GL_DOUBLEBUFFER. Refused: `params` NULL.
///
/// # Safety
/// `params` must be valid for one value (GL's contract).
pub unsafe fn get_named_framebuffer_parameteriv(
    framebuffer: u32,
    pname: u32,
    params: *mut i32,
) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().named_parameter, "glGetNamedFramebufferParameteriv")?;
    if params.is_null() {
        return Err(refuse_null(r, "params"));
    }
    if framebuffer == 0 {
        if let Some(cur) = emulated_fb0() {
            default_parameter(r, &cur, pname, params);
            return Ok(());
        }
    }
    // SAFETY: forwarded call.
    unsafe { real(framebuffer, pname, params) };
    Ok(())
}

/// glGetFramebufferParameteriv: with framebuffer 0 bound at `target`, as
/// [`get_named_framebuffer_parameteriv`] on 0. Refused: `params` NULL.
///
/// # Safety
/// `params` must be valid for one value (GL's contract).
pub unsafe fn get_framebuffer_parameteriv(target: u32, pname: u32, params: *mut i32) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().parameter, "glGetFramebufferParameteriv")?;
    if params.is_null() {
        return Err(refuse_null(r, "params"));
    }
    match current() {
        Some(cur) if emulated_at(r, &cur, target) => default_parameter(r, &cur, pname, params),
        // SAFETY: forwarded call.
        _ => unsafe { real(target, pname, params) },
    }
    Ok(())
}

/// glGetFramebufferParameters' answer for the emulated default
/// framebuffer (`params` not NULL): GL_STEREO and GL_DOUBLEBUFFER its own;
/// the parameters GL 4.5 gives only to framebuffer objects
/// (GL_FRAMEBUFFER_DEFAULT_*) GL_INVALID_OPERATION; every other the
/// window's, through the layer below with its framebuffer 0 bound (the
/// driver brings the read format up to date only for a bound framebuffer)
/// — values and GL_INVALID_ENUM for unknown names.
fn default_parameter(r: &Real, cur: &Current, pname: u32, params: *mut i32) {
    const GL_FRAMEBUFFER_DEFAULT_WIDTH: u32 = 0x9310;
    const GL_FRAMEBUFFER_DEFAULT_FIXED_SAMPLE_LOCATIONS: u32 = 0x9314;
    const GL_IMPLEMENTATION_COLOR_READ_TYPE: u32 = 0x8B9A;
    const GL_IMPLEMENTATION_COLOR_READ_FORMAT: u32 = 0x8B9B;
    if (GL_FRAMEBUFFER_DEFAULT_WIDTH..=GL_FRAMEBUFFER_DEFAULT_FIXED_SAMPLE_LOCATIONS)
        .contains(&pname)
    {
        cur.sc.lock().push_error(&r.gl, GL_INVALID_OPERATION);
        return;
    }
    let Some(real) = fns().parameter else {
        return;
    };
    let target = match pname {
        GL_IMPLEMENTATION_COLOR_READ_FORMAT | GL_IMPLEMENTATION_COLOR_READ_TYPE => {
            GL_READ_FRAMEBUFFER
        }
        _ => GL_DRAW_FRAMEBUFFER,
    };
    // SAFETY: forwarded call, on the window's framebuffer; `params` not NULL.
    with_window_framebuffer(&r.gl, || unsafe { real(target, pname, params) });
    stereo_parameter(cur, pname, params);
}

/// Relinks `program` with output 0 copied ([`LinkFns::duplicate_output_zero`])
/// in the program's context, keeping its GL errors apart: the driver's
/// pending errors are queued first and the relink's own dropped.
fn duplicate(r: &Real, cur: &Current, program: u32, source: Option<&str>) {
    let Some(link) = fns().link.as_ref() else {
        return;
    };
    cur.sc.lock().save_driver_errors(&r.gl);
    // SAFETY: the program's context is current.
    let outcome = unsafe { link.duplicate_output_zero(program, source) };
    // SAFETY: as above; drops the relink's own errors.
    while unsafe { r.gl.GetError() } != GL_NO_ERROR {}
    super::binaries::record_link(
        &mut cur.sc.lock(),
        program,
        !matches!(outcome, Outcome::Kept(_)),
    );
    if let Outcome::Kept(why) = outcome {
        // Once per reason, not per program: engines link many variants of
        // one shader (and the ones drawing only into their own framebuffer
        // objects lose nothing).
        super::warn(&format!(
            "a linked program keeps its fragment output 0 in the first buffer a glDrawBuffer \
             name such as GL_BACK selects: {why}"
        ));
    }
}

/// glLinkProgram: in a stereo context, a program with a user-defined
/// fragment output at location 0 is linked again with copies of it.
pub fn link_program(program: u32) -> Result<()> {
    let r = loaded()?;
    // SAFETY: forwarded call.
    unsafe { r.gl.LinkProgram(program) };
    match current() {
        Some(cur) if cur.sc.auto() => shift(r, &cur, program),
        Some(cur) => duplicate(r, &cur, program, None),
        None => {}
    }
    Ok(())
}

/// In a context given automatic stereo: `program`'s last vertex stage
/// relinked with the eye's shift ([`crate::auto::runtime::linked`]; its
/// one relink: the eyes are layers of one colour buffer, so output 0
/// needs no copies), its GL errors kept apart as [`duplicate`] keeps them.
fn shift(r: &Real, cur: &Current, program: u32) {
    cur.sc.lock().save_driver_errors(&r.gl);
    // SAFETY: the program's context is current.
    unsafe {
        crate::auto::runtime::linked(cur.sc.group(), program);
        while r.gl.GetError() != GL_NO_ERROR {}
    }
}

/// glCreateShaderProgramv: as [`link_program`] for a fragment program.
/// Refused: `strings` NULL with `count` > 0.
///
/// # Safety
/// `strings` must hold `count` NUL-terminated strings (GL's contract).
pub unsafe fn create_shader_programv(
    kind: u32,
    count: i32,
    strings: *const *const c_char,
) -> Result<u32> {
    let r = loaded()?;
    let real = need(fns().create_shader_programv, "glCreateShaderProgramv")?;
    if missing(count, strings) {
        return Err(refuse_null(r, "strings"));
    }
    if let Some(cur) = current().filter(|c| c.sc.auto()) {
        // SAFETY: GL's contract: `count` NUL-terminated strings.
        let parts: Vec<String> = (0..count.max(0) as usize)
            .map(|i| unsafe { *strings.add(i) })
            .filter(|s| !s.is_null())
            .map(|s| unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned())
            .collect();
        let refs: Vec<&str> = parts.iter().map(String::as_str).collect();
        let mut program = 0;
        if let Some(text) = crate::auto::runtime::separable_source(kind, &refs) {
            let c = std::ffi::CString::new(text).unwrap_or_default();
            cur.sc.lock().save_driver_errors(&r.gl);
            // SAFETY: one NUL-terminated string.
            program = unsafe { real(kind, 1, &c.as_ptr()) };
            let mut linked = 0;
            // SAFETY: as above; drops the rewrite's own errors.
            unsafe {
                r.gl.GetProgramiv(program, GL_LINK_STATUS, &mut linked);
                if program != 0 && linked == 0 {
                    r.gl.DeleteProgram(program);
                    program = 0;
                }
                while r.gl.GetError() != GL_NO_ERROR {}
            }
        }
        if program == 0 {
            // SAFETY: forwarded call.
            program = unsafe { real(kind, count, strings) };
        }
        // SAFETY: the program's context is current.
        unsafe { crate::auto::runtime::created(cur.sc.group(), program) };
        return Ok(program);
    }
    // SAFETY: forwarded call.
    let program = unsafe { real(kind, count, strings) };
    if program == 0 || kind != GL_FRAGMENT_SHADER {
        return Ok(program);
    }
    if let Some(cur) = current() {
        let mut source = String::new();
        // SAFETY: GL's contract: `count` NUL-terminated strings.
        for i in 0..count.max(0) as usize {
            let s = unsafe { *strings.add(i) };
            if !s.is_null() {
                // SAFETY: as above.
                source.push_str(&unsafe { CStr::from_ptr(s) }.to_string_lossy());
            }
        }
        duplicate(r, &cur, program, Some(&source));
    }
    Ok(program)
}

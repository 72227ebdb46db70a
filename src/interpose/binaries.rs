//! Program binaries keep the stereo guarantee: in a stereo context a
//! program's fragment output 0 reaches every buffer a glDrawBuffer name
//! such as GL_BACK selects because glLinkProgram adds copies of it
//! ([`crate::stereo::outputs`]); a program loaded with glProgramBinary is
//! not linked, so a binary made without the copies (by a run without the
//! layer, or by a mono context) would draw only into the first selected
//! buffer — the left eye under GL_BACK — silently.
//!
//! - glGetProgramBinary (and glGetProgramBinaryOES) in a stereo context
//!   hands out the driver's binary of the program as linked here (with
//!   its copies) behind a 12-byte tag of the layer's ([`TAG_LEN`]: a
//!   magic, a version and whether output 0 reaches every selected buffer),
//!   in the driver's own format, so GL_PROGRAM_BINARY_FORMATS and
//!   GL_NUM_PROGRAM_BINARY_FORMATS stay the driver's;
//!   glGetProgramiv(GL_PROGRAM_BINARY_LENGTH) counts the tag. A program
//!   the layer cannot vouch for (linked in another context whose output 0
//!   has no copies) gets the driver's binary untagged.
//! - glProgramBinary (and glProgramBinaryOES) of a tagged binary loads the
//!   driver's binary behind the tag, in any context (in a mono context the
//!   copies write draw buffers that are GL_NONE: nothing). In a stereo
//!   context a binary without the tag is loaded, and kept only when its
//!   output 0 needs no copies; otherwise the load fails as GL lets a load
//!   fail (GL_LINK_STATUS false, no GL error: the ARB_get_program_binary
//!   contract every shader cache handles by compiling the source, which
//!   the layer then links with the copies), and stderr says so once.
//!   Without the layer a tagged binary is one the driver does not know:
//!   its load fails the same way.
//! - Errors are the driver's: a bad program name, a negative length or a
//!   buffer too small raise what the driver raises for the call.

use std::ffi::{CStr, c_void};
use std::sync::OnceLock;

use super::context::{CtxState, Current, current};
use super::gl::{driver_accepts, refuse_null};
use super::real::{Real, loaded};
use crate::error::Result;
use crate::gl::enums::*;
use crate::stereo::outputs::Reach;

/// GL_PROGRAM_BINARY_LENGTH (glGetProgramiv).
pub const GL_PROGRAM_BINARY_LENGTH: u32 = 0x8741;

/// The tag's magic: "glsSTBIN".
const MAGIC: [u8; 8] = *b"glsSTBIN";
/// The tag's version.
const VERSION: u8 = 1;
/// The tag's length: the magic, the version, whether output 0 reaches
/// every selected buffer (1) or only the first (0, a program the layer
/// linked without copies, which it said on stderr then), two bytes 0.
pub const TAG_LEN: usize = 12;

/// How many programs a stereo context remembers the link of (forgetting
/// one only makes its binary untagged, and its interface is asked).
const REMEMBERED: usize = 4096;

type GetBinaryFn = unsafe extern "system" fn(u32, i32, *mut i32, *mut u32, *mut c_void);
type BinaryFn = unsafe extern "system" fn(u32, u32, *const c_void, i32);
type GetProgramivFn = unsafe extern "system" fn(u32, u32, *mut i32);

/// The real functions of this module (None where the driver lacks one:
/// the program cannot have called it then).
struct Fns {
    get_binary: Option<GetBinaryFn>,
    get_binary_oes: Option<GetBinaryFn>,
    binary: Option<BinaryFn>,
    binary_oes: Option<BinaryFn>,
    get_programiv: Option<GetProgramivFn>,
}

fn fns() -> &'static Fns {
    static FNS: OnceLock<Fns> = OnceLock::new();
    FNS.get_or_init(|| {
        let get = |name: &CStr| {
            // SAFETY: a NUL-terminated name.
            unsafe { super::real::get_proc_address(name.as_ptr()) }
                .map_or(std::ptr::null(), |f| f as *const c_void)
        };
        macro_rules! pick {
            ($name:literal, $ty:ty) => {{
                let p = get($name);
                // SAFETY: the named function, with its Khronos signature.
                (!p.is_null()).then(|| unsafe { std::mem::transmute::<*const c_void, $ty>(p) })
            }};
        }
        Fns {
            get_binary: pick!(c"glGetProgramBinary", GetBinaryFn),
            get_binary_oes: pick!(c"glGetProgramBinaryOES", GetBinaryFn),
            binary: pick!(c"glProgramBinary", BinaryFn),
            binary_oes: pick!(c"glProgramBinaryOES", BinaryFn),
            get_programiv: pick!(c"glGetProgramiv", GetProgramivFn),
        }
    })
}

fn need<T>(f: Option<T>, name: &str, offered_by: &str) -> Result<T> {
    f.ok_or_else(|| super::gl::lacks(name, offered_by))
}

/// What a stereo context knows of the programs linked in it: whether
/// output 0 reaches every selected buffer (false: linked as the user
/// linked it, [`crate::stereo::outputs::Outcome::Kept`]).
#[derive(Default)]
pub struct Linked(std::collections::HashMap<u32, bool>);

impl Linked {
    /// Records how `program` was linked or loaded here.
    pub fn record(&mut self, program: u32, every: bool) {
        if self.0.len() >= REMEMBERED && !self.0.contains_key(&program) {
            self.0.clear();
        }
        self.0.insert(program, every);
    }

    fn get(&self, program: u32) -> Option<bool> {
        self.0.get(&program).copied()
    }
}

/// The tag of a binary of a program whose output 0 reaches every
/// selected buffer (`every`) or only the first.
fn tag(every: bool) -> [u8; TAG_LEN] {
    let mut t = [0u8; TAG_LEN];
    t[..8].copy_from_slice(&MAGIC);
    t[8] = VERSION;
    t[9] = every as u8;
    t
}

/// The tag's "every" when `bytes` start with a tag of the layer's.
fn read_tag(bytes: &[u8]) -> Option<bool> {
    (bytes.len() >= TAG_LEN && bytes[..8] == MAGIC && bytes[8] == VERSION).then(|| bytes[9] != 0)
}

/// Whether the binary of `program` gets the tag, and with what: what its
/// link here recorded, else what its interface shows (Some(true) for
/// [`Reach::Every`]); None: the layer cannot vouch for it.
fn vouch(r: &Real, cur: &Current, program: u32) -> Option<bool> {
    if let Some(every) = cur.sc.lock().programs.get(program) {
        return Some(every);
    }
    (reach(r, cur, program)? == Reach::Every).then_some(true)
}

/// [`crate::stereo::outputs::LinkFns::reach`] of `program` in the
/// program's context, its GL errors kept apart (None before GL 4.3).
fn reach(r: &Real, cur: &Current, program: u32) -> Option<Reach> {
    let link = super::dsa::link_fns()?;
    cur.sc.lock().save_driver_errors(&r.gl);
    // SAFETY: the program's context is current; a name GL checked.
    let reach = unsafe { link.reach(program) };
    // SAFETY: as above; drops the queries' own errors.
    while unsafe { r.gl.GetError() } != GL_NO_ERROR {}
    Some(reach)
}

/// glGetProgramiv: GL_PROGRAM_BINARY_LENGTH counts the tag of the
/// binary glGetProgramBinary hands out in a stereo context; everything
/// else is the driver's. Refused: `params` NULL.
///
/// # Safety
/// `params` must be valid for the values `pname` returns (GL's contract).
pub unsafe fn get_programiv(program: u32, pname: u32, params: *mut i32) -> Result<()> {
    let r = loaded()?;
    let real = need(fns().get_programiv, "glGetProgramiv", "GL 2.0")?;
    if params.is_null() {
        return Err(refuse_null(r, "params"));
    }
    // SAFETY (both): forwarded call.
    let forward = || unsafe { real(program, pname, params) };
    let cur = match current() {
        Some(cur) if pname == GL_PROGRAM_BINARY_LENGTH => cur,
        _ => {
            forward();
            return Ok(());
        }
    };
    // SAFETY: one value written when the driver accepted the query.
    if driver_accepts(&r.gl, &cur, forward)
        && unsafe { *params } > 0
        && vouch(r, &cur, program).is_some()
    {
        // SAFETY: as above.
        unsafe { *params += TAG_LEN as i32 };
    }
    Ok(())
}

/// glGetProgramBinary (glGetProgramBinaryOES when `oes`): in a stereo
/// context the driver's binary behind the layer's tag. Refused:
/// `binary_format` NULL, `binary` NULL with `buf_size` > 0.
///
/// # Safety
/// GL's contract: `binary` holds `buf_size` bytes; `length` is NULL or
/// valid for one value.
pub unsafe fn get_program_binary(
    program: u32,
    buf_size: i32,
    length: *mut i32,
    binary_format: *mut u32,
    binary: *mut c_void,
    oes: bool,
) -> Result<()> {
    let r = loaded()?;
    let real = match oes {
        true => need(
            fns().get_binary_oes,
            "glGetProgramBinaryOES",
            "GL_OES_get_program_binary",
        )?,
        false => need(fns().get_binary, "glGetProgramBinary", "GL 4.1")?,
    };
    if binary_format.is_null() {
        return Err(refuse_null(r, "binaryFormat"));
    }
    if buf_size > 0 && binary.is_null() {
        return Err(refuse_null(r, "binary"));
    }
    let cur = match current() {
        Some(cur) if buf_size >= 0 => cur,
        _ => {
            // SAFETY: forwarded call.
            unsafe { real(program, buf_size, length, binary_format, binary) };
            return Ok(());
        }
    };
    let every = vouch(r, &cur, program);
    let Some(every) = every else {
        // SAFETY: forwarded call.
        unsafe { real(program, buf_size, length, binary_format, binary) };
        return Ok(());
    };
    // The driver's binary after the tag; a buffer too small for both
    // is one too small for the driver's (its GL_INVALID_OPERATION).
    let room = (buf_size as usize).saturating_sub(TAG_LEN);
    let at = if room == 0 {
        binary
    } else {
        // SAFETY: `binary` holds buf_size > TAG_LEN bytes (GL's contract).
        unsafe { binary.cast::<u8>().add(TAG_LEN).cast::<c_void>() }
    };
    // The driver writes its length here (Mesa: 0 first, also when it
    // then raises an error); the program's variable gets what it wrote.
    // SAFETY: NULL or valid for one value (GL's contract).
    let mut written = if length.is_null() {
        0
    } else {
        unsafe { *length }
    };
    let accepted = driver_accepts(&r.gl, &cur, || {
        // SAFETY: `at` holds `room` bytes.
        unsafe { real(program, room as i32, &mut written, binary_format, at) }
    });
    if !accepted || written <= 0 {
        if !length.is_null() {
            // SAFETY: valid for one value (GL's contract).
            unsafe { *length = written };
        }
        return Ok(());
    }
    // SAFETY: the driver wrote `written` bytes after TAG_LEN of
    // `binary`'s buf_size; the tag goes before them.
    unsafe {
        std::ptr::copy_nonoverlapping(tag(every).as_ptr(), binary.cast::<u8>(), TAG_LEN);
        if !length.is_null() {
            *length = written + TAG_LEN as i32;
        }
    }
    Ok(())
}

/// glProgramBinary (glProgramBinaryOES when `oes`): a binary with the
/// layer's tag loads the driver's binary behind it; in a stereo context a
/// binary without it is kept only when its output 0 needs no copies,
/// else its load fails (GL_LINK_STATUS false, no GL error) and stderr
/// says so once. Refused: `binary` NULL with `length` > 0.
///
/// # Safety
/// GL's contract: `binary` holds `length` bytes.
pub unsafe fn program_binary(
    program: u32,
    binary_format: u32,
    binary: *const c_void,
    length: i32,
    oes: bool,
) -> Result<()> {
    let r = loaded()?;
    let real = match oes {
        true => need(
            fns().binary_oes,
            "glProgramBinaryOES",
            "GL_OES_get_program_binary",
        )?,
        false => need(fns().binary, "glProgramBinary", "GL 4.1")?,
    };
    if length > 0 && binary.is_null() {
        return Err(refuse_null(r, "binary"));
    }
    let bytes: &[u8] = if length > 0 {
        // SAFETY: GL's contract: `binary` holds `length` bytes.
        unsafe { std::slice::from_raw_parts(binary.cast::<u8>(), length as usize) }
    } else {
        &[]
    };
    if let Some(every) = read_tag(bytes) {
        let inner = &bytes[TAG_LEN..];
        // SAFETY: forwarded call with the driver's binary.
        unsafe {
            real(
                program,
                binary_format,
                inner.as_ptr().cast(),
                inner.len() as i32,
            )
        };
        if let Some(cur) = current() {
            loaded_here(r, &cur, program, every);
        }
        return Ok(());
    }
    // SAFETY: forwarded call.
    unsafe { real(program, binary_format, binary, length) };
    let Some(cur) = current() else {
        return Ok(());
    };
    if !linked(r, &cur, program) {
        return Ok(());
    }
    if reach(r, &cur, program) == Some(Reach::Every) {
        cur.sc.lock().programs.record(program, true);
        return Ok(());
    }
    // Refused as GL lets a load fail: a load of no bytes (GL_LINK_STATUS
    // false, the executable gone, no GL error), its GL errors apart.
    cur.sc.lock().save_driver_errors(&r.gl);
    // SAFETY: forwarded call, with no bytes.
    unsafe { real(program, binary_format, binary, 0) };
    // SAFETY: the program's context is current.
    while unsafe { r.gl.GetError() } != GL_NO_ERROR {}
    super::warn(
        "a program binary made without glstereo's copies of fragment output 0 was refused \
         (glProgramBinary fails, GL_LINK_STATUS false): loaded, its output 0 would reach only \
         the first buffer a glDrawBuffer name such as GL_BACK selects; the program's shader \
         cache compiles the source instead",
    );
    Ok(())
}

/// A tagged binary of `program` loaded in the stereo context `cur`:
/// recorded, and a program linked without copies is said on stderr, as
/// its link was.
fn loaded_here(r: &Real, cur: &Current, program: u32, every: bool) {
    if !linked(r, cur, program) {
        return;
    }
    cur.sc.lock().programs.record(program, every);
    if !every {
        super::warn(
            "a linked program keeps its fragment output 0 in the first buffer a glDrawBuffer \
             name such as GL_BACK selects: it was loaded from a program binary of a program \
             linked so",
        );
    }
}

/// GL_LINK_STATUS of `program`, its GL errors kept apart (false for a
/// name GL refuses).
fn linked(r: &Real, cur: &Current, program: u32) -> bool {
    let Some(real) = fns().get_programiv else {
        return false;
    };
    let mut status = 0;
    cur.sc.lock().save_driver_errors(&r.gl);
    // SAFETY: the program's context is current; one value.
    unsafe { real(program, GL_LINK_STATUS, &mut status) };
    // SAFETY: as above; drops the query's own error.
    while unsafe { r.gl.GetError() } != GL_NO_ERROR {}
    status != 0
}

/// Records the outcome of a link in the stereo context's state.
pub(super) fn record_link(st: &mut CtxState, program: u32, every: bool) {
    st.programs.record(program, every);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_read_back_and_foreign_bytes_are_not_tags() {
        for every in [true, false] {
            let mut b = tag(every).to_vec();
            b.extend_from_slice(b"driver bytes");
            assert_eq!(read_tag(&b), Some(every));
        }
        assert_eq!(read_tag(b"glsSTBIN"), None, "too short");
        assert_eq!(read_tag(&[0u8; 64]), None);
        let mut other = tag(true);
        other[8] = VERSION + 1;
        assert_eq!(read_tag(&other), None, "another version");
    }

    #[test]
    fn the_remembered_links_stay_bounded() {
        let mut l = Linked::default();
        for p in 0..(REMEMBERED as u32 * 3) {
            l.record(p, p % 2 == 0);
            assert!(l.0.len() <= REMEMBERED);
            assert_eq!(l.get(p), Some(p % 2 == 0));
        }
    }
}

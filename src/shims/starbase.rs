//! HP Starbase full-screen stereo (seed 000 §9), emulated.
//!
//! On HP hardware, `gescape(fildes, STEREO, &arg1, &arg2)` with
//! `arg1.i[0] = TRUE` doubles the vertical sync: the upper half of the
//! 1280x1024 mono framebuffer fills the screen for the left eye, the lower
//! half for the right, each stretched ×2 vertically (so programs draw each
//! eye squashed 1:2). `FALSE` restores the plain mono display.
//!
//! Here the same escape sets the surface's input framing:
//! [`InputFraming::SyncDoubled`] when on, [`InputFraming::QuadBuffer`]
//! (which shows a mono surface's one frame to both eyes) when off. The
//! eyes then flow to every output format and capture.
//!
//! A program names its surface with a descriptor (`fildes`), got in one of
//! two ways:
//! - [`fildes_for`] an existing surface (the program keeps owning it);
//! - [`open`], the emulation's `gopen()`: a mono double-buffered surface
//!   the size of the emulated screen ([`super::screen`], 1280x1024 by
//!   default), current on the calling thread, owned by the descriptor and
//!   destroyed by [`close`].

use std::sync::{Arc, Mutex, MutexGuard, Weak};

use super::descriptors::Descriptors;
use super::screen;
use crate::error::{Error, Result};
use crate::framing::InputFraming;
use crate::surface::{self, Surface};

/// The `STEREO` gescape opcode. HP's numeric value is not in any public
/// source we could find (HP's 1989 `starbase.c.h` predates it, and uses
/// 0–1308 for its escapes), so glstereo uses 9000, outside every range of
/// that header. Programs use the name, so they compile unchanged.
pub const STEREO: i32 = 9000;

/// The first descriptor handed out: 3, after the standard streams, so a
/// Starbase descriptor never looks like stdin, stdout or stderr.
pub const FIRST_FILDES: i32 = 3;

/// A decoded gescape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Escape {
    /// `STEREO`: sync-doubling on (true) or off (false).
    Stereo(bool),
}

impl Escape {
    /// Decodes an opcode and the first int of `arg1` (None when `arg1` is
    /// NULL). Any non-zero `arg1.i[0]` means on, as C's TRUE.
    pub fn decode(op: i32, arg1_i0: Option<i32>) -> Result<Escape> {
        match op {
            STEREO => {
                let on = arg1_i0.ok_or(Error::NullPointer("arg1"))?;
                Ok(Escape::Stereo(on != 0))
            }
            _ => Err(Error::invalid_enum(
                "op",
                op as u32,
                format!(
                    "glstereo emulates one gescape, STEREO ({STEREO}); other Starbase escapes are not available"
                ),
            )),
        }
    }
}

/// The input framing a surface gets with sync-doubling on or off.
pub fn framing(sync_doubling: bool) -> InputFraming {
    if sync_doubling {
        InputFraming::SyncDoubled
    } else {
        InputFraming::QuadBuffer
    }
}

/// One descriptor: the surface it names, and whether it owns it.
struct Entry {
    surface: Weak<Surface>,
    owned: Option<Arc<Surface>>,
}

static FILDES: Mutex<Descriptors<Entry>> = Mutex::new(Descriptors::new(FIRST_FILDES));

fn table() -> MutexGuard<'static, Descriptors<Entry>> {
    FILDES.lock().unwrap_or_else(|e| e.into_inner())
}

fn bad_fildes() -> Error {
    Error::InvalidHandle("fildes (a Starbase descriptor from gopen() or gls_starbase_fildes())")
}

/// The descriptor naming `surface`: the one it already has, or a new one.
/// The program keeps owning the surface; the descriptor dies with it.
pub fn fildes_for(surface: &Arc<Surface>) -> Result<i32> {
    let mut t = table();
    // Forget descriptors whose surfaces are gone, so the search stays short.
    t.retain(|e| e.surface.strong_count() > 0);
    let target = Arc::downgrade(surface);
    if let Some(id) = t.find(|e| Weak::ptr_eq(&e.surface, &target)) {
        return Ok(id);
    }
    t.insert(Entry {
        surface: target,
        owned: None,
    })
}

/// The emulation's `gopen()`: a mono, double-buffered surface the size of
/// the emulated screen, made current on the calling thread, named by a new
/// descriptor that owns it.
pub fn open() -> Result<(i32, Arc<Surface>)> {
    let (w, h) = screen::screen_size();
    let s = screen::open_surface(w, h, false)?;
    surface::make_current(Some(&s))?;
    let id = table().insert(Entry {
        surface: Arc::downgrade(&s),
        owned: Some(s.clone()),
    });
    match id {
        Ok(id) => Ok((id, s)),
        Err(e) => {
            s.release_if_current();
            Err(e)
        }
    }
}

/// The surface a descriptor names.
pub fn surface(fildes: i32) -> Result<Arc<Surface>> {
    table()
        .get(fildes)
        .and_then(|e| e.surface.upgrade())
        .ok_or_else(bad_fildes)
}

/// The emulation's `gclose()`: forgets the descriptor. A surface opened by
/// [`open`] is released if current here and returned, for the caller to
/// drop (it is destroyed with the last reference); a surface named with
/// [`fildes_for`] is left alone (None).
pub fn close(fildes: i32) -> Result<Option<Arc<Surface>>> {
    let entry = table().remove(fildes).ok_or_else(bad_fildes)?;
    if let Some(s) = &entry.owned {
        s.release_if_current();
    }
    Ok(entry.owned)
}

/// `gescape(fildes, op, arg1, arg2)`. The descriptor is checked first, then
/// the opcode; on error nothing changes.
pub fn gescape(fildes: i32, op: i32, arg1_i0: Option<i32>) -> Result<()> {
    let s = surface(fildes)?;
    match Escape::decode(op, arg1_i0)? {
        Escape::Stereo(on) => s.set_framing(framing(on)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stereo_true_and_false_turn_sync_doubling_on_and_off() {
        assert_eq!(Escape::decode(STEREO, Some(1)), Ok(Escape::Stereo(true)));
        assert_eq!(Escape::decode(STEREO, Some(0)), Ok(Escape::Stereo(false)));
        assert_eq!(
            Escape::decode(STEREO, Some(-1)),
            Ok(Escape::Stereo(true)),
            "any non-zero int is C's TRUE"
        );
        assert_eq!(framing(true), InputFraming::SyncDoubled);
        assert_eq!(framing(false), InputFraming::QuadBuffer);
    }

    #[test]
    fn unknown_opcodes_and_a_missing_arg1_are_errors_that_say_so() {
        let e = Escape::decode(1, Some(1)).unwrap_err();
        assert!(
            matches!(
                e,
                Error::InvalidEnum {
                    what: "op",
                    value: 1,
                    ..
                }
            ),
            "{e:?}"
        );
        assert!(e.to_string().contains("STEREO (9000)"), "{e}");
        assert_eq!(
            Escape::decode(STEREO, None),
            Err(Error::NullPointer("arg1"))
        );
    }

    #[test]
    fn an_unknown_descriptor_is_an_invalid_handle() {
        for fildes in [-1, 0, 1, 2, i32::MAX] {
            assert!(matches!(surface(fildes), Err(Error::InvalidHandle(_))));
            assert!(matches!(
                gescape(fildes, STEREO, Some(1)),
                Err(Error::InvalidHandle(_))
            ));
            assert!(matches!(close(fildes), Err(Error::InvalidHandle(_))));
        }
    }
}

//! The program's draws, as the preload library's wrappers generated from
//! gl.xml report them (`preload/build.rs`: the commands of the families of
//! [`crate::auto::entry_points`] that draw into the default framebuffer,
//! and the state automatic stereo watches), and the hand-written
//! replacements that also draw (glClear, glClearBuffer, blits). A call
//! passes through [`around`], which costs a thread-local test when nothing
//! watches the thread's draws.
//!
//! What watches them:
//! - after a stereo context presents, its drawable's size is checked
//!   again at the first draw (as Mesa's own software framebuffer takes a
//!   resized window's size at the first draw after a swap), so a program
//!   that resizes its window and draws with its old viewport draws the
//!   frame at the new size (0 frames lost);
//! - while a context given automatic stereo is current on the thread,
//!   every call goes to [`crate::auto::runtime`], which sends draws to
//!   both eyes.

use std::cell::Cell;

use crate::auto::entry_points::Family;

use super::context::current;

pub use crate::auto::call::{Call, Returned};

/// [`WATCH`]: check the drawable's size at the next draw.
const SIZE: u8 = 1;
/// [`WATCH`]: a context given automatic stereo is current.
const AUTO: u8 = 2;

thread_local! {
    /// What watches this thread's draws (bits): 0, the fast path.
    static WATCH: Cell<u8> = const { Cell::new(0) };
}

/// Runs `draw` (the call to the next definition), with what the thread's
/// state asks for around it.
pub fn around<R: Returned>(call: Call, draw: impl Fn() -> R) -> R {
    let watch = WATCH.with(Cell::get);
    if watch == 0 {
        return draw();
    }
    if watch & SIZE != 0 {
        check_size(call.family);
    }
    if watch & AUTO != 0 {
        if let Some(cur) = current() {
            return crate::auto::runtime::around(&cur, call, draw);
        }
    }
    draw()
}

/// Before a clear by a hand-written replacement (glClear,
/// glClearBuffer*, glClearNamedFramebuffer*): [`notice`], and what
/// automatic stereo does before a clear ([`crate::auto::runtime::before_clear`]:
/// the window's depth put back where a draw with the depth test off left
/// another layer attached, the scene's depth kept before it is cleared).
pub fn notice_clear(call: Call) {
    notice(call.family);
    if WATCH.with(Cell::get) & AUTO != 0 {
        if let Some(cur) = current() {
            crate::auto::runtime::before_clear(&cur, &call);
        }
    }
}

/// Before a draw of `family` by a hand-written replacement (glClear,
/// glClearBuffer*, the blits): a size check asked for by
/// [`check_size_at_next_draw`].
pub fn notice(family: Family) {
    let watch = WATCH.with(Cell::get);
    if watch & SIZE != 0 {
        check_size(family);
    }
    if watch & AUTO != 0 {
        // A clear compiled into a display list keeps it off the fast path.
        if let Some(cur) = current() {
            crate::auto::runtime::not_geometry_only(&cur, family);
        }
    }
}

fn check_size(family: Family) {
    if !matches!(
        family,
        Family::Draw
            | Family::BeginEnd
            | Family::DisplayList
            | Family::Clear
            | Family::RasterPixels
            | Family::Blit
    ) {
        return;
    }
    WATCH.with(|c| c.set(c.get() & !SIZE));
    if let Some(cur) = current() {
        if let Err(e) = cur.sc.follow_drawable_size(&cur) {
            super::warn(&format!("following a resized window: {e}"));
        }
    }
}

/// Asks the next draw on this thread to check the drawable's size.
pub fn check_size_at_next_draw() {
    WATCH.with(|c| c.set(c.get() | SIZE));
}

/// Says whether a context given automatic stereo is now current on this
/// thread ([`super::context::set_current`]).
pub fn watch_auto(on: bool) {
    WATCH.with(|c| c.set(if on { c.get() | AUTO } else { c.get() & !AUTO }));
}

//! The program's draws, as the preload library's wrappers generated from
//! gl.xml report them (`preload/build.rs`: the commands of the families of
//! [`crate::auto::entry_points`] that draw into the default framebuffer),
//! and the hand-written replacements that also draw (glClear, glClearBuffer,
//! blits). A draw passes through [`around`], which costs a thread-local
//! test when nothing watches the thread's draws.
//!
//! What watches them: after a stereo context presents, its drawable's size
//! is checked again at the first draw (as Mesa's own software framebuffer
//! takes a resized window's size at the first draw after a swap), so a
//! program that resizes its window and draws with its old viewport draws
//! the frame at the new size (0 frames lost).

use std::cell::Cell;

use crate::auto::entry_points::Family;

use super::context::current;

/// What a generated wrapper reports of its command.
#[derive(Clone, Copy, Debug)]
pub struct Call {
    /// The command's family.
    pub family: Family,
    /// Its name.
    pub name: &'static str,
}

thread_local! {
    /// The next draw on this thread checks the drawable's size first.
    static SIZE_CHECK: Cell<bool> = const { Cell::new(false) };
}

/// Runs `draw` (the call to the next definition), with what the thread's
/// state asks for before it.
pub fn around<R>(call: Call, draw: impl Fn() -> R) -> R {
    notice(call.family);
    draw()
}

/// Before a draw of `family` (the generated wrappers, and the hand-written
/// replacements of glClear, glClearBuffer* and the blits): a size check
/// asked for by [`check_size_at_next_draw`].
pub fn notice(_family: Family) {
    if !SIZE_CHECK.with(Cell::get) {
        return;
    }
    SIZE_CHECK.with(|c| c.set(false));
    if let Some(cur) = current() {
        if let Err(e) = cur.sc.follow_drawable_size(&cur) {
            super::warn(&format!("following a resized window: {e}"));
        }
    }
}

/// Asks the next draw on this thread to check the drawable's size.
pub fn check_size_at_next_draw() {
    SIZE_CHECK.with(|c| c.set(true));
}

//! The one narrow interface between automatic stereo and the layer that
//! feeds it (ARCHITECTURE.md, "The layer and automatic stereo"): the
//! layer (`crate::interpose`, GLX today, EGL beside it) owns entry points,
//! contexts, drawables and presenting; it hands automatic stereo each
//! call of the families it watches ([`crate::auto::call::Call`]) with the
//! calling context as a [`Host`], and, once, how to find the GL below it
//! ([`set_gl_lookup`]). Automatic stereo decides what each call does and
//! never reaches into the layer.

use std::ffi::{CStr, c_void};
use std::sync::OnceLock;

use crate::auto::eyes::Attachments;
use crate::auto::runtime::AutoState;

/// The context a call of the program's is made in, as automatic stereo
/// sees it.
pub trait Host {
    /// The share group (programs and textures are the group's).
    fn group(&self) -> u64;
    /// The context itself: framebuffer objects are per context.
    fn context(&self) -> usize;
    /// Runs `f` with the context's automatic-stereo state and the layered
    /// eyes of its draw drawable's emulated framebuffer, with the name of
    /// the framebuffer object the program draws into for it (None: it
    /// has none).
    fn with_auto<T>(&self, f: impl FnOnce(&mut AutoState, Option<(u32, Attachments)>) -> T) -> T;
}

/// Looks a GL command up by name in the GL below the layer (NULL when it
/// has none).
pub type GlLookup = fn(&CStr) -> *const c_void;

static LOOKUP: OnceLock<GlLookup> = OnceLock::new();

/// Says where automatic stereo finds its GL functions (the layer calls it
/// before it hands over any call; later calls change nothing).
pub fn set_gl_lookup(lookup: GlLookup) {
    let _ = LOOKUP.set(lookup);
}

/// `name` in the GL below the layer (NULL before [`set_gl_lookup`], or
/// when that GL has no such command).
pub fn gl_proc(name: &CStr) -> *const c_void {
    LOOKUP.get().map_or(std::ptr::null(), |f| f(name))
}

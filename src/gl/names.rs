//! Names of the objects the library makes in a program's share group (the
//! LD_PRELOAD interposer's eye textures, depth/stencil renderbuffers and
//! framebuffer objects), when [`super::Gl::own_names`] is on.
//!
//! # What the names must do
//!
//! - Stay out of the way of the names a legacy program uses without
//!   generating them: `glBindTexture(GL_TEXTURE_2D, 1)` creates texture 1
//!   in the compatibility profile, and programs of the GL 1.x era number
//!   their textures themselves from 1.
//! - Leave the program's own glGen* names as they are without the library:
//!   small (legacy programs index small tables with them).
//! - Read as non-negative through a `GLint`: bindings are read back with
//!   glGetIntegerv, and programs and layers keep them so (VirtualGL puts
//!   back only bindings >= 0).
//! - Not trouble a GL layer below that tracks objects: RenderDoc 1.24
//!   crashed on glBindFramebuffer of a framebuffer name glGenFramebuffers
//!   never handed out, in the library's context (it took texture and
//!   renderbuffer names made by binding).
//! - Be out of reach of the program's glDelete*: [`LayerNames::owns`] says
//!   which names are the library's (the interposer leaves them alone, as
//!   names the program never made).
//!
//! So textures and renderbuffers take names counting down from
//! [`RESERVED_TOP`], created by binding them (the library's context is a
//! compatibility one), where no program's name is. Mesa hands out "highest
//! name ever used + 1" while that fits below 0xFFFFFFFE, else the lowest
//! free names; a name at 0x7FFFFFFF would make the program's next glGen*
//! name 0x80000000. So each such object is followed by one at
//! [`ALLOCATOR_CEILING`], made and deleted at once: Mesa's highest name
//! stays there, and the program's glGen* names stay the lowest free ones.
//! No object with a name of 2³¹ or more is left, and none is ever bound
//! in a program's context. Framebuffer objects, which a program almost
//! never numbers itself, take glGen* names as any program's do (on Mesa,
//! which shares them across the share group, the program's next ones
//! start a few names later).

use std::collections::HashSet;
use std::sync::Mutex;

/// The first name textures and renderbuffers of the library take; later
/// ones count down: the highest name that reads as non-negative through a
/// `GLint`.
pub const RESERVED_TOP: u32 = 0x7FFF_FFFF;

/// The name of the short-lived object that keeps Mesa's name allocator
/// handing out the lowest free names (see the module doc).
pub const ALLOCATOR_CEILING: u32 = 0xFFFF_FFFE;

/// The kinds of objects the library names in a program's share group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Textures (glGenTextures).
    Texture,
    /// Renderbuffers (glGenRenderbuffers).
    Renderbuffer,
    /// Framebuffer objects (glGenFramebuffers; Mesa shares them across a
    /// share group).
    Framebuffer,
}

impl Kind {
    fn index(self) -> usize {
        match self {
            Kind::Texture => 0,
            Kind::Renderbuffer => 1,
            Kind::Framebuffer => 2,
        }
    }
}

/// The names the library holds, by kind.
#[derive(Debug, Default)]
pub struct LayerNames {
    owned: Mutex<[HashSet<u32>; 3]>,
}

impl LayerNames {
    /// Whether `name` is one the library holds (in some share group).
    pub fn owns(&self, kind: Kind, name: u32) -> bool {
        name != 0 && self.lock()[kind.index()].contains(&name)
    }

    /// Whether the library holds any name of `kind`.
    pub fn any(&self, kind: Kind) -> bool {
        !self.lock()[kind.index()].is_empty()
    }

    /// Records `name` as the library's.
    pub fn keep(&self, kind: Kind, name: u32) {
        self.lock()[kind.index()].insert(name);
    }

    /// Forgets `names` (the library deletes them).
    pub fn release(&self, kind: Kind, names: &[u32]) {
        let mut owned = self.lock();
        for n in names {
            owned[kind.index()].remove(n);
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, [HashSet<u32>; 3]> {
        self.owned.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The next name of the reserved range (textures and renderbuffers).
pub(super) fn next_reserved() -> u32 {
    use std::sync::atomic::{AtomicU32, Ordering};
    static NEXT: AtomicU32 = AtomicU32::new(RESERVED_TOP);
    NEXT.fetch_sub(1, Ordering::Relaxed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reserved_names_read_as_non_negative_gl_ints() {
        let a = next_reserved();
        let b = next_reserved();
        assert!(b < a && a <= RESERVED_TOP);
        assert!((a as i32) > 0 && (b as i32) > 0);
    }

    #[test]
    fn ownership_is_by_kind_and_forgotten_on_release() {
        let names = LayerNames::default();
        names.keep(Kind::Texture, 5000);
        assert!(names.owns(Kind::Texture, 5000));
        assert!(!names.owns(Kind::Renderbuffer, 5000));
        assert!(names.any(Kind::Texture) && !names.any(Kind::Framebuffer));
        names.release(Kind::Texture, &[5000, 7]);
        assert!(!names.owns(Kind::Texture, 5000));
    }
}

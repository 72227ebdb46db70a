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

use std::collections::{HashMap, HashSet};
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

/// The names the library holds, by share group and kind.
///
/// Names are per share group in GL: framebuffer 3 of one group is not
/// framebuffer 3 of another. So a name is the library's only in the group
/// it was made in — the group of the context current when it is made,
/// asked of it, or released — and a group's names are forgotten when the
/// group ends (its objects went with its last context). Contexts the
/// library was not told of ([`LayerNames::join`]) are in no group: nothing
/// made there is remembered, no name there is the library's.
#[derive(Debug)]
pub struct LayerNames {
    /// The context current on the calling thread (0: none).
    current: fn() -> usize,
    state: Mutex<State>,
}

#[derive(Debug, Default)]
struct State {
    /// Each known context's share group.
    contexts: HashMap<usize, u64>,
    /// Each group's names, by kind.
    owned: HashMap<u64, [HashSet<u32>; 3]>,
}

impl LayerNames {
    /// Names kept by the share group of the context `current` says is
    /// current on the calling thread.
    pub fn new(current: fn() -> usize) -> Self {
        LayerNames {
            current,
            state: Mutex::default(),
        }
    }

    /// Context `ctx` (the program's or the library's own) is in share
    /// group `group`.
    pub fn join(&self, ctx: usize, group: u64) {
        if ctx != 0 && group != 0 {
            self.lock().contexts.insert(ctx, group);
        }
    }

    /// Context `ctx` is destroyed (its group may live on in others).
    pub fn leave(&self, ctx: usize) {
        self.lock().contexts.remove(&ctx);
    }

    /// Share group `group` ended: its objects are gone, and with them its
    /// names.
    pub fn group_ended(&self, group: u64) {
        let mut st = self.lock();
        st.owned.remove(&group);
        st.contexts.retain(|_, g| *g != group);
    }

    /// Whether `name` is one the library holds in the current context's
    /// share group.
    pub fn owns(&self, kind: Kind, name: u32) -> bool {
        name != 0 && self.with_current(|set| set.is_some_and(|s| s[kind.index()].contains(&name)))
    }

    /// Whether the library holds any name of `kind` in the current
    /// context's share group.
    pub fn any(&self, kind: Kind) -> bool {
        self.with_current(|set| set.is_some_and(|s| !s[kind.index()].is_empty()))
    }

    /// Records `name` as the library's in the current context's share
    /// group.
    pub fn keep(&self, kind: Kind, name: u32) {
        let ctx = (self.current)();
        let mut st = self.lock();
        if let Some(&g) = st.contexts.get(&ctx) {
            st.owned.entry(g).or_default()[kind.index()].insert(name);
        }
    }

    /// Forgets `names` (the library deletes them in the current context's
    /// share group).
    pub fn release(&self, kind: Kind, names: &[u32]) {
        let ctx = (self.current)();
        let mut st = self.lock();
        let Some(&g) = st.contexts.get(&ctx) else {
            return;
        };
        if let Some(set) = st.owned.get_mut(&g) {
            for n in names {
                set[kind.index()].remove(n);
            }
            if set.iter().all(HashSet::is_empty) {
                st.owned.remove(&g);
            }
        }
    }

    /// How many contexts, groups and names are recorded (tests: nothing
    /// grows).
    pub fn len(&self) -> usize {
        let st = self.lock();
        st.contexts.len()
            + st.owned.len()
            + st.owned.values().flatten().map(HashSet::len).sum::<usize>()
    }

    /// Whether nothing is recorded.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn with_current<T>(&self, f: impl FnOnce(Option<&[HashSet<u32>; 3]>) -> T) -> T {
        let ctx = (self.current)();
        let st = self.lock();
        let set = st.contexts.get(&ctx).and_then(|g| st.owned.get(g));
        f(set)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
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

    use std::cell::Cell;

    thread_local! {
        static CURRENT: Cell<usize> = const { Cell::new(0) };
    }

    fn current() -> usize {
        CURRENT.with(Cell::get)
    }

    fn make_current(ctx: usize) {
        CURRENT.with(|c| c.set(ctx));
    }

    #[test]
    fn ownership_is_by_kind_and_forgotten_on_release() {
        let names = LayerNames::new(current);
        names.join(0x10, 1);
        make_current(0x10);
        names.keep(Kind::Texture, 5000);
        assert!(names.owns(Kind::Texture, 5000));
        assert!(!names.owns(Kind::Renderbuffer, 5000));
        assert!(names.any(Kind::Texture) && !names.any(Kind::Framebuffer));
        names.release(Kind::Texture, &[5000, 7]);
        assert!(!names.owns(Kind::Texture, 5000));
        names.leave(0x10);
        assert!(names.is_empty());
    }

    #[test]
    fn a_name_is_the_librarys_only_in_its_own_share_group() {
        // Framebuffer 1 of the library's in group 1 is not the program's
        // framebuffer 1 of group 2: a glDeleteFramebuffers there is the
        // program's to make.
        let names = LayerNames::new(current);
        names.join(0x10, 1);
        names.join(0x18, 1);
        names.join(0x20, 2);
        make_current(0x10);
        names.keep(Kind::Framebuffer, 1);
        make_current(0x18);
        assert!(
            names.owns(Kind::Framebuffer, 1),
            "a context of the same group"
        );
        make_current(0x20);
        assert!(!names.owns(Kind::Framebuffer, 1));
        assert!(!names.any(Kind::Framebuffer));
        make_current(0x30);
        names.keep(Kind::Framebuffer, 2);
        assert!(
            !names.owns(Kind::Framebuffer, 2),
            "an unknown context keeps nothing"
        );
        make_current(0);
        assert!(!names.owns(Kind::Framebuffer, 1));
    }

    #[test]
    fn a_share_groups_names_go_when_it_ends() {
        let names = LayerNames::new(current);
        for group in 1..=100u64 {
            let ctx = group as usize * 0x10;
            names.join(ctx, group);
            names.join(ctx + 8, group);
            make_current(ctx);
            for n in 1..=5 {
                names.keep(Kind::Framebuffer, n);
                names.keep(Kind::Texture, RESERVED_TOP - n);
            }
            names.leave(ctx);
            names.group_ended(group);
        }
        assert!(names.is_empty(), "{names:?}");
    }
}

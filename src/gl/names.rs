//! Names of the objects the library makes in a program's share group (the
//! LD_PRELOAD interposer's eye textures, depth/stencil renderbuffers and
//! framebuffer objects), when [`super::Gl::own_names`] is on.
//!
//! # What the names must do
//!
//! - Come from the driver's glGen*, as any program's do. A GL layer below
//!   the library may track every object it sees named: RenderDoc 1.24
//!   crashes on glBindFramebuffer of a name glGenFramebuffers never handed
//!   out (measured), and apitrace and VirtualGL record or translate what
//!   they see. So no name is made up, not even for a moment.
//! - Read as non-negative through a `GLint`: bindings are read back with
//!   glGetIntegerv, and programs and layers keep them so (VirtualGL puts
//!   back only bindings >= 0). glGen* names are small.
//! - Stay out of the way of names a legacy program uses without generating
//!   them: `glBindTexture(GL_TEXTURE_2D, 1)` creates texture 1 in the
//!   compatibility profile, and programs of the GL 1.x era number their
//!   textures (and display lists) themselves from 1. So the library never
//!   keeps a name below [`NAME_FLOOR`]: when glGen* hands it a lower one,
//!   it generates a block of [`NAME_FLOOR`] names at once, keeps the
//!   highest and deletes the others (generated names are the driver's own
//!   business, which every layer sees as a program's). Mesa hands out
//!   "highest name ever used + 1" while that fits, so a program's own
//!   glGen* names then continue above the block; drivers that hand out the
//!   lowest free name give them back from 1.
//! - Be out of reach of the program's glDelete*: [`LayerNames::owns`] says
//!   which names are the library's (the interposer leaves them alone, as
//!   names the program never made).

use std::collections::HashSet;
use std::sync::Mutex;

/// Names below this are never kept by the library (see the module doc).
pub const NAME_FLOOR: u32 = 4096;

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
        name >= NAME_FLOOR && self.lock()[kind.index()].contains(&name)
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

/// One name of `kind` at or above [`NAME_FLOOR`], from `make` (glGen*: fills
/// the slice) and `delete` (glDelete*): the first generated name when it
/// is high enough, else the highest of a block of [`NAME_FLOOR`] generated
/// at once, the rest deleted again. 0 when the driver hands out nothing
/// (no context, out of memory).
pub fn generate_above_floor(make: impl Fn(&mut [u32]), delete: impl Fn(&[u32])) -> u32 {
    let mut one = [0u32];
    make(&mut one);
    if one[0] >= NAME_FLOOR || one[0] == 0 {
        return one[0];
    }
    delete(&one);
    let mut block = vec![0u32; NAME_FLOOR as usize];
    make(&mut block);
    let Some((&kept, rest)) = block.split_last() else {
        return 0;
    };
    delete(rest);
    kept
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    /// An allocator as Mesa's: highest name ever used + 1.
    struct Mesa {
        max: RefCell<u32>,
        live: RefCell<HashSet<u32>>,
    }

    impl Mesa {
        fn new(used: u32) -> Mesa {
            Mesa {
                max: RefCell::new(used),
                live: RefCell::new((1..=used).collect()),
            }
        }
        fn make(&self, out: &mut [u32]) {
            for n in out {
                *self.max.borrow_mut() += 1;
                *n = *self.max.borrow();
                self.live.borrow_mut().insert(*n);
            }
        }
        fn delete(&self, names: &[u32]) {
            for n in names {
                self.live.borrow_mut().remove(n);
            }
        }
    }

    #[test]
    fn a_name_below_the_floor_is_never_kept_and_the_block_is_given_back() {
        let m = Mesa::new(3);
        let name = generate_above_floor(|o| m.make(o), |d| m.delete(d));
        assert!(name >= NAME_FLOOR, "{name}");
        // Only the kept name and the program's three stay alive.
        let live = m.live.borrow();
        assert_eq!(live.len(), 4, "{live:?}");
        assert!(live.contains(&name) && (1..=3).all(|n| live.contains(&n)));
        drop(live);
        // The program's next generated name is above the block.
        let mut next = [0];
        m.make(&mut next);
        assert!(next[0] > name);
        // Later names of the library are taken as they come.
        assert_eq!(
            generate_above_floor(|o| m.make(o), |d| m.delete(d)),
            next[0] + 1
        );
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

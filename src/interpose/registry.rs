//! What the interposer knows about the program's GLX objects: which
//! visuals were handed out as stereo, the stereo FBConfigs it made, the
//! stereo contexts, and the X window behind each GLX window.
//!
//! Stereo FBConfigs are handles of the interposer's own (a small heap
//! block each, alive for the process): the real configurations are shared
//! by every request (a program may choose the same configuration with and
//! without stereo), so stereo has to live in a handle of its own. Every
//! GLX function that takes a configuration is interposed and translates it
//! back ([`Registry::real_config`]). Visuals are plain `XVisualInfo`
//! copies the program frees itself: the pointer handed out for a stereo
//! request is remembered with its visual ID (a later allocation at the same
//! address for another visual is not mistaken for it).

use std::collections::{HashMap, VecDeque};
use std::sync::{Arc, Mutex, MutexGuard};

use super::context::StereoContext;

/// A stereo FBConfig handle: what its pointer points to.
#[derive(Debug)]
#[repr(C)]
pub struct FakeConfig {
    /// [`FAKE_MAGIC`].
    magic: u64,
    /// The real configuration.
    pub real: usize,
    /// The display it belongs to.
    pub display: usize,
}

/// "glsSTERE", recognisable in a debugger.
const FAKE_MAGIC: u64 = 0x676c_7353_5445_5245;

/// The bookkeeping, behind one lock (GLX calls are rare; GL calls never
/// take this lock). It is never taken while a context's state is locked.
#[derive(Default)]
pub struct Registry {
    /// `XVisualInfo*` handed out for a stereo request → its visual ID.
    stereo_visuals: HashMap<usize, u64>,
    /// Stereo FBConfig handle → what it stands for.
    fakes: HashMap<usize, &'static FakeConfig>,
    /// (display, real config) → its stereo handle.
    fake_of: HashMap<(usize, usize), usize>,
    /// Program context → its stereo state.
    contexts: HashMap<usize, Arc<StereoContext>>,
    /// (display, GLX window) → X window.
    glx_windows: HashMap<(usize, u64), u64>,
    /// Stereo contexts glXDestroyContext destroyed while current on a
    /// thread: really destroyed when released ([`StereoContext::defer_destroy`]).
    doomed: HashMap<usize, Arc<StereoContext>>,
    /// Contexts glXDestroyContext destroyed, oldest first (at most
    /// [`DEAD_CONTEXTS`]); an address leaves the list when a new context
    /// is created at it.
    dead: VecDeque<usize>,
}

/// How many destroyed contexts are remembered (the share-list check).
pub const DEAD_CONTEXTS: usize = 256;

static REGISTRY: Mutex<Option<Registry>> = Mutex::new(None);

/// Runs `f` on the registry.
pub fn with<T>(f: impl FnOnce(&mut Registry) -> T) -> T {
    let mut guard: MutexGuard<'_, Option<Registry>> =
        REGISTRY.lock().unwrap_or_else(|e| e.into_inner());
    f(guard.get_or_insert_with(Registry::default))
}

impl Registry {
    /// Remembers that `visual` (an `XVisualInfo*`) was handed out for a
    /// stereo request, or (stereo = false) that it was not.
    pub fn mark_visual(&mut self, visual: usize, visual_id: u64, stereo: bool) {
        if stereo {
            self.stereo_visuals.insert(visual, visual_id);
        } else {
            self.stereo_visuals.remove(&visual);
        }
    }

    /// Whether `visual` (with this visual ID) was handed out as stereo.
    pub fn is_stereo_visual(&self, visual: usize, visual_id: u64) -> bool {
        self.stereo_visuals.get(&visual) == Some(&visual_id)
    }

    /// The stereo handle of a real configuration (made on first use).
    pub fn fake_config(&mut self, display: usize, real: usize) -> usize {
        if let Some(&f) = self.fake_of.get(&(display, real)) {
            return f;
        }
        let fake: &'static FakeConfig = Box::leak(Box::new(FakeConfig {
            magic: FAKE_MAGIC,
            real,
            display,
        }));
        let p = fake as *const FakeConfig as usize;
        self.fakes.insert(p, fake);
        self.fake_of.insert((display, real), p);
        p
    }

    /// The real configuration behind `config`, and whether `config` is a
    /// stereo handle.
    pub fn real_config(&self, config: usize) -> (usize, bool) {
        match self.fakes.get(&config) {
            Some(f) => (f.real, true),
            None => (config, false),
        }
    }

    /// The display a stereo FBConfig handle was made for (None: not one).
    pub fn fake_display(&self, config: usize) -> Option<usize> {
        self.fakes.get(&config).map(|f| f.display)
    }

    /// Remembers that the program destroyed context `ctx`.
    pub fn mark_dead(&mut self, ctx: usize) {
        self.dead.retain(|&c| c != ctx);
        if self.dead.len() == DEAD_CONTEXTS {
            self.dead.pop_front();
        }
        self.dead.push_back(ctx);
    }

    /// Whether `ctx` is a context the program destroyed (and no context was
    /// created at its address since).
    pub fn is_dead(&self, ctx: usize) -> bool {
        self.dead.contains(&ctx)
    }

    /// A context was created at `ctx`: whatever was known about an earlier
    /// context at that address is forgotten.
    pub fn born(&mut self, ctx: usize) {
        self.dead.retain(|&c| c != ctx);
        self.contexts.remove(&ctx);
        self.doomed.remove(&ctx);
    }

    /// Records a stereo context destroyed while current (its destruction
    /// waits for its release).
    pub fn add_doomed(&mut self, ctx: usize, sc: Arc<StereoContext>) {
        self.doomed.insert(ctx, sc);
    }

    /// Whether `ctx` is a stereo context destroyed while current and not
    /// yet released.
    pub fn is_doomed(&self, ctx: usize) -> bool {
        self.doomed.contains_key(&ctx)
    }

    /// A doomed context was released and destroyed.
    pub fn remove_doomed(&mut self, ctx: usize) {
        self.doomed.remove(&ctx);
    }

    /// Records a stereo context.
    pub fn add_context(&mut self, ctx: usize, sc: Arc<StereoContext>) {
        self.contexts.insert(ctx, sc);
    }

    /// The stereo state of a program context (None: a mono context).
    pub fn context(&self, ctx: usize) -> Option<Arc<StereoContext>> {
        self.contexts.get(&ctx).cloned()
    }

    /// Forgets a stereo context.
    pub fn remove_context(&mut self, ctx: usize) -> Option<Arc<StereoContext>> {
        self.contexts.remove(&ctx)
    }

    /// The stereo contexts of `display`.
    pub fn contexts_of(&self, display: usize) -> Vec<Arc<StereoContext>> {
        self.contexts
            .values()
            .filter(|sc| sc.display() == display)
            .cloned()
            .collect()
    }

    /// Records the X window behind a GLX window.
    pub fn add_glx_window(&mut self, display: usize, glx_window: u64, window: u64) {
        self.glx_windows.insert((display, glx_window), window);
    }

    /// Forgets a GLX window.
    pub fn remove_glx_window(&mut self, display: usize, glx_window: u64) {
        self.glx_windows.remove(&(display, glx_window));
    }

    /// The X drawable to ask the size of: the X window behind a GLX window,
    /// else the drawable itself.
    pub fn x_drawable(&self, display: usize, drawable: u64) -> u64 {
        self.glx_windows
            .get(&(display, drawable))
            .copied()
            .unwrap_or(drawable)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fake_configs_are_stable_distinct_and_translate_back() {
        let mut r = Registry::default();
        let a = r.fake_config(1, 0x1000);
        let b = r.fake_config(1, 0x2000);
        assert_ne!(a, b);
        assert_eq!(r.fake_config(1, 0x1000), a, "one handle per real config");
        assert_ne!(r.fake_config(2, 0x1000), a, "per display");
        assert_eq!(r.real_config(a), (0x1000, true));
        assert_eq!(r.real_config(0x1000), (0x1000, false));
    }

    #[test]
    fn destroyed_contexts_are_remembered_until_their_address_is_reused() {
        let mut r = Registry::default();
        r.mark_dead(0x10);
        r.mark_dead(0x20);
        assert!(r.is_dead(0x10) && r.is_dead(0x20) && !r.is_dead(0x30));
        r.born(0x10);
        assert!(!r.is_dead(0x10) && r.is_dead(0x20));
        for i in 0..DEAD_CONTEXTS {
            r.mark_dead(0x1000 + i);
        }
        assert!(!r.is_dead(0x20), "the oldest is dropped past the limit");
        assert!(r.is_dead(0x1000) && r.is_dead(0x1000 + DEAD_CONTEXTS - 1));
    }

    #[test]
    fn a_reused_visual_address_for_another_visual_is_not_stereo() {
        let mut r = Registry::default();
        r.mark_visual(0x55, 33, true);
        assert!(r.is_stereo_visual(0x55, 33));
        assert!(!r.is_stereo_visual(0x55, 34));
        r.mark_visual(0x55, 33, false);
        assert!(!r.is_stereo_visual(0x55, 33));
    }
}

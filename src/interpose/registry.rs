//! What the interposer knows about the program's GLX objects: which
//! visuals were handed out as stereo, the stereo FBConfigs it made, the
//! stereo contexts, and the X window behind each GLX window.
//!
//! Stereo FBConfigs are handles of the interposer's own (a small heap
//! block each, alive as long as their display): the real configurations are shared
//! by every request (a program may choose the same configuration with and
//! without stereo), so stereo has to live in a handle of its own. Every
//! GLX function that takes a configuration is interposed and translates it
//! back ([`Registry::real_config`]). Visuals are plain `XVisualInfo`
//! copies the program frees itself: the pointer handed out for a stereo
//! request is remembered with its visual ID (a later allocation at the same
//! address for another visual is not mistaken for it).
//!
//! Everything recorded for a display is forgotten when the program closes
//! it ([`Registry::forget_display`], from XCloseDisplay's hook, installed
//! by `glx::watch`): a program that opens and closes displays must not grow,
//! and a new display at a closed one's address must not inherit its state.

use std::collections::{HashMap, HashSet, VecDeque};
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
    /// `XVisualInfo*` handed out for a stereo request → its visual ID and
    /// display.
    stereo_visuals: HashMap<usize, (u64, usize)>,
    /// Stereo FBConfig handle (the address of the box) → what it stands for.
    fakes: HashMap<usize, Box<FakeConfig>>,
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
    /// Displays whose XCloseDisplay calls [`Registry::forget_display`].
    watched: HashSet<usize>,
    /// Every live context the program made → its share group (contexts
    /// made with a share context join its group; the layer's own contexts
    /// join the program's).
    groups: HashMap<usize, u64>,
    /// Share groups holding a stereo context, whose objects include the
    /// layer's.
    stereo_groups: HashSet<u64>,
    /// The last share group number handed out.
    last_group: u64,
    /// Display → whether GLX renders directly there (asked once: stereo
    /// is emulated only where it does).
    direct: HashMap<usize, bool>,
}

/// What [`Registry::forget_display`] removed, to be dropped after the
/// registry's lock is released.
#[must_use]
pub struct Forgotten {
    /// The display's stereo contexts (and those destroyed while current).
    pub contexts: Vec<Arc<StereoContext>>,
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
    /// Remembers that `visual` (an `XVisualInfo*` of `display`) was handed
    /// out for a stereo request, or (stereo = false) that it was not.
    pub fn mark_visual(&mut self, display: usize, visual: usize, visual_id: u64, stereo: bool) {
        if stereo {
            self.stereo_visuals.insert(visual, (visual_id, display));
        } else {
            self.stereo_visuals.remove(&visual);
        }
    }

    /// Whether `visual` (with this visual ID) was handed out as stereo.
    pub fn is_stereo_visual(&self, visual: usize, visual_id: u64) -> bool {
        self.stereo_visuals
            .get(&visual)
            .is_some_and(|&(id, _)| id == visual_id)
    }

    /// The stereo handle of a real configuration (made on first use).
    pub fn fake_config(&mut self, display: usize, real: usize) -> usize {
        if let Some(&f) = self.fake_of.get(&(display, real)) {
            return f;
        }
        let fake = Box::new(FakeConfig {
            magic: FAKE_MAGIC,
            real,
            display,
        });
        let p = &*fake as *const FakeConfig as usize;
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
        self.groups.remove(&ctx);
    }

    /// Records new context `ctx`, made sharing objects with `share` (0:
    /// none), in `share`'s share group or a group of its own.
    pub fn join_group(&mut self, ctx: usize, share: usize) {
        let group = match self.groups.get(&share) {
            Some(&g) if share != 0 => g,
            _ => {
                self.last_group += 1;
                self.last_group
            }
        };
        self.groups.insert(ctx, group);
    }

    /// Context `ctx` is gone (destroyed for real, or its display closed):
    /// it leaves its share group, and the group is returned when `ctx`
    /// was its last context (the group's objects went with it).
    pub fn left_group(&mut self, ctx: usize) -> Option<u64> {
        let group = self.groups.remove(&ctx)?;
        if self.groups.values().any(|&g| g == group) {
            return None;
        }
        self.stereo_groups.remove(&group);
        Some(group)
    }

    /// The share group of context `ctx` (0: unknown).
    pub fn group(&self, ctx: usize) -> u64 {
        self.groups.get(&ctx).copied().unwrap_or(0)
    }

    /// Whether context `ctx` shares objects with a stereo context (and so
    /// with the layer's objects).
    pub fn in_stereo_group(&self, ctx: usize) -> bool {
        self.groups
            .get(&ctx)
            .is_some_and(|g| self.stereo_groups.contains(g))
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
        if let Some(&g) = self.groups.get(&ctx) {
            self.stereo_groups.insert(g);
        }
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

    /// Whether GLX renders directly on `display`, if known.
    pub fn renders_directly(&self, display: usize) -> Option<bool> {
        self.direct.get(&display).copied()
    }

    /// Records whether GLX renders directly on `display`.
    pub fn set_renders_directly(&mut self, display: usize, direct: bool) {
        self.direct.insert(display, direct);
    }

    /// Marks `display` as watched; true the first time (install the hook).
    pub fn watch(&mut self, display: usize) -> bool {
        self.watched.insert(display)
    }

    /// Forgets everything recorded for `display` (closing): its stereo
    /// visuals, configurations (the handles are freed: libGL frees the
    /// real ones too), contexts and GLX windows.
    pub fn forget_display(&mut self, display: usize) -> Forgotten {
        self.watched.remove(&display);
        self.direct.remove(&display);
        self.stereo_visuals.retain(|_, &mut (_, d)| d != display);
        self.fakes.retain(|_, f| f.display != display);
        self.fake_of.retain(|&(d, _), _| d != display);
        self.glx_windows.retain(|&(d, _), _| d != display);
        let mut contexts = Vec::new();
        for map in [&mut self.contexts, &mut self.doomed] {
            let gone: Vec<usize> = map
                .iter()
                .filter(|(_, sc)| sc.display() == display)
                .map(|(&k, _)| k)
                .collect();
            contexts.extend(gone.into_iter().filter_map(|k| map.remove(&k)));
        }
        Forgotten { contexts }
    }

    /// How many entries the registry holds (tests: nothing grows).
    pub fn len(&self) -> usize {
        self.stereo_visuals.len()
            + self.fakes.len()
            + self.fake_of.len()
            + self.contexts.len()
            + self.doomed.len()
            + self.glx_windows.len()
            + self.watched.len()
            + self.direct.len()
            + self.groups.len()
            + self.stereo_groups.len()
    }

    /// Whether the registry holds nothing.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
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
        r.mark_visual(1, 0x55, 33, true);
        assert!(r.is_stereo_visual(0x55, 33));
        assert!(!r.is_stereo_visual(0x55, 34));
        r.mark_visual(1, 0x55, 33, false);
        assert!(!r.is_stereo_visual(0x55, 33));
    }

    #[test]
    fn closing_a_display_forgets_only_its_state() {
        let mut r = Registry::default();
        for d in [1, 2] {
            assert!(r.watch(d));
            assert!(!r.watch(d), "watched once");
            r.mark_visual(d, 0x100 * d, 33, true);
            r.fake_config(d, 0x1000);
            r.add_glx_window(d, 0x400001, 0x200001);
            r.set_renders_directly(d, d == 2);
        }
        let a2 = r.fake_config(2, 0x1000);
        let before = r.len();
        let gone = r.forget_display(1);
        assert!(gone.contexts.is_empty());
        assert_eq!(r.len(), before / 2, "display 2's half remains");
        assert!(!r.is_stereo_visual(0x100, 33) && r.is_stereo_visual(0x200, 33));
        assert_eq!(r.real_config(a2), (0x1000, true));
        assert_eq!(r.x_drawable(1, 0x400001), 0x400001);
        assert_eq!(r.x_drawable(2, 0x400001), 0x200001);
        assert_eq!(r.renders_directly(1), None);
        assert_eq!(r.renders_directly(2), Some(true));
        assert!(
            r.watch(1),
            "a new display at the same address is watched again"
        );
        let _ = r.forget_display(1);
        let _ = r.forget_display(2);
        assert!(r.is_empty());
    }

    #[test]
    fn a_share_group_is_forgotten_with_its_last_context() {
        // A program that makes a new share group every few frames (and
        // destroys the old one) leaves nothing behind.
        let mut r = Registry::default();
        for round in 0..100usize {
            let (a, b) = (0x1000 + round * 0x20, 0x1010 + round * 0x20);
            r.born(a);
            r.join_group(a, 0);
            r.born(b);
            r.join_group(b, a);
            let group = r.group(a);
            assert_eq!(r.group(b), group, "b shares a's objects");
            let sc = crate::interpose::context::StereoContext::new_on(
                crate::interpose::wsi::Wsi::Egl,
                1,
                a,
                0,
                crate::stereo::buffers::FramebufferShape {
                    stereo: true,
                    double_buffered: true,
                },
                crate::stereo::emulated::BufferFormats::surface(0, 0),
                group,
            );
            r.add_context(a, sc);
            assert!(r.in_stereo_group(b));
            r.remove_context(a);
            assert_eq!(r.left_group(a), None, "b is still in the group");
            assert_eq!(r.left_group(b), Some(group));
            assert_eq!(r.left_group(b), None, "left once");
        }
        assert!(r.is_empty());
    }
}

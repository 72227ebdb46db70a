//! A stereo context of the program: its emulated default framebuffer on
//! each drawable it is bound to, the GL errors the emulation raised, and
//! the layer's own context that presents the eyes.
//!
//! Objects and where they live:
//! - the colour textures and the depth/stencil renderbuffer of each
//!   drawable's [`EmulatedFramebuffer`] are made in the layer's context,
//!   which shares objects with the program's (names as
//!   [`crate::gl::names`] says);
//! - the framebuffer object the program renders into is made in the
//!   program's context (framebuffer objects are not shared) and bound
//!   wherever the program would have framebuffer 0;
//! - the compositor's programs, vertex array and canvases live in the
//!   layer's context, which is made current on the program's drawable to
//!   compose into its real back buffer and swap, then the program's
//!   context is made current again. On a software renderer (llvmpipe) a
//!   double-buffered window gets the composite from memory instead, through
//!   a MIT-SHM image per drawable (`backend/xshm.rs`): the eyes are read
//!   back in bands and composed on the CPU straight into the shared
//!   segment, with no full-window GL pass and no swap — unless the next
//!   glXSwapBuffers belongs to another GL layer below this one (MangoHud,
//!   VirtualGL, apitrace: [`super::real::Real::swap_layered`]), which must
//!   see every frame: then the composite goes through GL and that swap.

use std::cell::Cell;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::ThreadId;

use x11_dl::xlib;

use super::capture;
use super::real::{Real, loaded, real};
use super::registry;
use super::settings;
use super::wsi::Wsi;
use crate::backend::glx::{trap_replied_x_errors, trap_x_errors};
use crate::backend::xshm::{Connection, ShmImage, ShmSlot};
use crate::error::{Error, Result};
use crate::framing::InputFraming;
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::image::Image;
use crate::output::MakeEyes;
use crate::output::gl::{GlCompositor, Job};
use crate::profile::{self, Stage};
use crate::stereo::buffers::{ColorBuffer, FramebufferShape};
use crate::stereo::emulated::{BufferFormats, DrawSelection, EmulatedFramebuffer, ReadSelection};

/// Orders binds, to find the context a drawable was bound to last.
static BIND_TICK: AtomicU64 = AtomicU64::new(1);

/// One drawable's emulated framebuffer in one context.
pub(super) struct Drawn {
    pub(super) fb: EmulatedFramebuffer,
    /// Its window's MIT-SHM image, when frames are shown from memory
    /// (unsupported: through the layer's GL context and glXSwapBuffers —
    /// a pixmap or pbuffer, no MIT-SHM, an unsupported visual).
    image: ShmSlot,
    /// Frames presented.
    frames: u64,
    /// [`BIND_TICK`] when last bound.
    last_bound: u64,
    /// A glViewport of another size already checked the drawable's size
    /// this frame.
    viewport_checked: bool,
    /// The window's size as the server told it right after the last frame
    /// was put through MIT-SHM (the request that tells it also waits for
    /// the frame to be shown), None when unknown: the next present of a
    /// frame of that size needs no request of its own to learn it.
    size_seen: Option<(u32, u32)>,
    /// Its drawable was destroyed where the buffers could not be freed at
    /// once (while current: GLX keeps a current drawable until it is
    /// released; or while the context was current on another thread):
    /// freed when the context is next bound or released.
    gone: bool,
}

/// The mutable part of a stereo context. Lock order: the registry's lock
/// may be held when a state is locked, never the other way round.
pub(super) struct CtxState {
    pub(super) fbs: HashMap<u64, Drawn>,
    /// The context's GL error flag as Mesa keeps it: the first error
    /// raised since the last glGetError, by the emulation or by the driver
    /// (saved before the layer called GL in the program's context), or
    /// GL_NO_ERROR. glGetError reports it before asking the driver; every
    /// later error until then is dropped, as Mesa drops it.
    pub(super) pending: u32,
    compositor: GlCompositor,
    /// Whether the program's context can host the emulation (GL ≥ 3.0);
    /// None until first bound.
    usable: Option<bool>,
    /// The thread it is current on.
    owner: Option<ThreadId>,
    /// glXDestroyContext was called while it was current on a thread: it
    /// is destroyed (the program's context and the layer's) when released.
    destroyed: bool,
    /// One entry per level of the context's attribute stack (glPushAttrib):
    /// the emulated draw/read selections the pushed bits cover.
    pub(super) attribs: Vec<SavedSelections>,
    /// The colour write masks the program set (glColorMask, glColorMaski),
    /// by draw buffer index: what GL_COLOR_WRITEMASK answers. While an
    /// opaque emulated framebuffer ([`BufferFormats::opaque`]) is bound
    /// for drawing, the driver's masks never write alpha.
    pub(super) color_mask: [[bool; 4]; MASKED_BUFFERS],
    /// The program's clear colour (glClearColor), which the layer's fast
    /// clear of an opaque emulated framebuffer changes for a moment.
    pub(super) clear_color: super::gl::ClearColor,
    /// How the programs linked here reach the selected buffers (what
    /// their binaries are tagged with, [`super::binaries`]).
    pub(super) programs: super::binaries::Linked,
    /// Automatic stereo's state ([`crate::auto::runtime`]).
    pub(super) auto: crate::auto::runtime::AutoState,
}

/// The draw buffer indices whose colour masks the layer shadows
/// (GL_MAX_DRAW_BUFFERS of llvmpipe and of most drivers).
pub(super) const MASKED_BUFFERS: usize = 8;

/// The emulated buffer selections saved by one glPushAttrib: the draw
/// selection with GL_COLOR_BUFFER_BIT, the read one with GL_PIXEL_MODE_BIT.
pub(super) struct SavedSelections {
    pub(super) draw: Option<(u64, DrawSelection)>,
    pub(super) read: Option<(u64, ReadSelection)>,
    /// The emulated framebuffer was the one bound for drawing / reading
    /// at the push (else the program's own object was, or none was saved).
    pub(super) draw_on_emulated: bool,
    pub(super) read_on_emulated: bool,
    /// The program's colour masks, with GL_COLOR_BUFFER_BIT.
    pub(super) color_mask: Option<([[bool; 4]; MASKED_BUFFERS], super::gl::ClearColor)>,
}

impl CtxState {
    /// Whether `fbo` is one of this context's emulated framebuffers.
    pub(super) fn is_ours(&self, fbo: u32) -> bool {
        fbo != 0 && self.fbs.values().any(|d| d.fb.app_fbo() == fbo)
    }

    /// Raises GL error `code` in the program's context (current: callers),
    /// as Mesa records one: only when no error was raised since the last
    /// glGetError, the driver's included (an error the driver holds came
    /// first, and is the one kept).
    pub(super) fn push_error(&mut self, gl: &Gl, code: u32) {
        if code == GL_NO_ERROR || self.pending != GL_NO_ERROR {
            return;
        }
        self.save_driver_errors(gl);
        if self.pending == GL_NO_ERROR {
            self.pending = code;
        }
    }

    /// Moves the driver's error flag into [`CtxState::pending`] (where one
    /// is held already, the driver's later error is dropped, as Mesa drops
    /// it), so the layer's own GL calls in the program's context neither
    /// lose nor fake any.
    pub(super) fn save_driver_errors(&mut self, gl: &Gl) {
        // SAFETY: the program's context is current (callers).
        let e = unsafe { gl.GetError() };
        if self.pending == GL_NO_ERROR {
            self.pending = e;
        }
    }

    /// glGetError: the flag [`CtxState::pending`] holds, clearing the
    /// driver's too (an error it raised since came later and is dropped);
    /// None when it holds none (the driver's flag is the answer).
    pub(super) fn take_error(&mut self, gl: &Gl) -> Option<u32> {
        if self.pending == GL_NO_ERROR {
            return None;
        }
        // SAFETY: the program's context is current (callers).
        unsafe { gl.GetError() };
        Some(std::mem::replace(&mut self.pending, GL_NO_ERROR))
    }
}

/// A stereo context of the program.
pub struct StereoContext {
    /// The window system that made it.
    wsi: Wsi,
    display: usize,
    ctx: usize,
    ours: usize,
    shape: FramebufferShape,
    formats: BufferFormats,
    /// A mono context given automatic stereo (glstereo-run --auto): its
    /// buffers are stereo, its program sees a mono visual.
    auto: bool,
    /// Its share group ([`registry::Registry::group`]).
    group: u64,
    state: Mutex<CtxState>,
    /// Its display was closed: nothing may be done with it any more (it
    /// may still sit in another thread's current slot).
    closed: AtomicBool,
    /// Its display was terminated (eglTerminate) while it was current on
    /// another thread, which may render into its eyes until it releases
    /// it: the layered eyes' memory is readied for the driver, and the
    /// layer's view of it unmapped, at that release
    /// ([`StereoContext::before_release`]), not at the terminate.
    ended_elsewhere: AtomicBool,
    /// Held while the layer makes the program's context current itself,
    /// and around glXMakeCurrent of it: the layer's own make-current of a
    /// context that is current nowhere (to free a destroyed drawable's
    /// buffers, or to present) never races the program's.
    binding: Mutex<()>,
}

/// The stereo context current on this thread and its drawables.
#[derive(Clone)]
pub struct Current {
    /// The context.
    pub sc: Arc<StereoContext>,
    /// Its `Display*`.
    pub display: usize,
    /// The draw drawable.
    pub draw: u64,
    /// The read drawable.
    pub read: u64,
}

impl crate::auto::host::Host for Current {
    fn group(&self) -> u64 {
        self.sc.group()
    }

    fn context(&self) -> usize {
        Arc::as_ptr(&self.sc) as usize
    }

    fn with_auto<T>(
        &self,
        f: impl FnOnce(
            &mut crate::auto::runtime::AutoState,
            Option<(u32, crate::auto::eyes::Attachments)>,
        ) -> T,
    ) -> T {
        self.sc.with_auto(self.draw, f)
    }
}

thread_local! {
    /// The stereo context current on this thread: a leaked `Box<Current>`,
    /// NULL for a mono context or none. A plain pointer has no destructor,
    /// so the slot stays usable while the process exits: programs call GLX
    /// from `atexit` handlers (freeglut destroys its windows there), which
    /// run after thread-local destructors.
    static CURRENT: Cell<*mut Current> = const { Cell::new(std::ptr::null_mut()) };
}

/// Whether a stereo context is current on this thread (the fast test every
/// interposed GL call makes first).
pub fn stereo_current() -> bool {
    CURRENT.with(|c| !c.get().is_null())
}

/// The stereo context current on this thread.
pub fn current() -> Option<Current> {
    CURRENT.with(|c| {
        let p = c.get();
        // SAFETY: NULL or a Box this thread leaked in set_current and still owns.
        (!p.is_null()).then(|| unsafe { (*p).clone() })
    })
}

/// Forgets the stereo context current on this thread without releasing
/// it (its display is closing: nothing may be done with it any more).
pub fn forget_current() {
    let old = CURRENT.with(|c| c.replace(std::ptr::null_mut()));
    super::draws::watch_auto(false);
    if !old.is_null() {
        // SAFETY: the Box set_current leaked; reclaimed once.
        drop(unsafe { Box::from_raw(old) });
    }
}

/// After the window system's real make-current succeeded (glXMakeCurrent,
/// glXMakeContextCurrent, eglMakeCurrent): `sc`, the stereo record of the
/// context made current (None: a mono context, or a release), gets its
/// emulated framebuffer bound on `draw`/`read` and becomes this thread's
/// current record; `binding` (the context's binding lock, held across the
/// real call) goes; then the context current here `before`, if now current
/// nowhere, is told (the buffers of drawables destroyed while it was
/// current on them go). A context whose framebuffer cannot be bound runs
/// in mono, said once.
pub fn made_current<B>(
    before: Option<Current>,
    sc: Option<Arc<StereoContext>>,
    display: usize,
    (draw, read): (u64, u64),
    binding: B,
) {
    let next = match sc {
        Some(sc) if draw != 0 && !sc.unusable() => match sc.bind(draw, read) {
            Ok(()) => Some(Current {
                sc,
                display,
                draw,
                read,
            }),
            Err(e) => {
                super::warn(&format!("{e}; this context runs in mono"));
                None
            }
        },
        _ => None,
    };
    set_current(next);
    drop(binding);
    if let Some(old) = before {
        if current().is_none_or(|now| !Arc::ptr_eq(&now.sc, &old.sc)) {
            old.sc.released();
        }
    }
}

/// The program made context `ctx` (GLX's or EGL's), sharing objects
/// with `share` (0: none): whatever was known of an earlier context at
/// its address is forgotten, and it joins `share`'s share group or a new
/// one.
pub fn context_created(ctx: usize, share: usize) {
    let group = registry::with(|reg| {
        reg.born(ctx);
        reg.join_group(ctx, share);
        reg.group(ctx)
    });
    if let Ok(r) = real() {
        r.gl.context_joined(ctx, group);
    }
}

/// The program's context `ctx` is destroyed for real (not current
/// anywhere): it leaves its share group, and when it was the group's
/// last context, what the layer knew of the group's objects goes (they
/// went with the group).
pub fn context_destroyed(ctx: usize) {
    let ended = registry::with(|reg| reg.left_group(ctx));
    if let Ok(r) = real() {
        r.gl.context_left(ctx);
        if let Some(group) = ended {
            r.gl.group_ended(group);
        }
    }
    if let Some(group) = ended {
        crate::auto::render_targets::forget_group(group);
    }
}

/// Records what is current on this thread now.
pub fn set_current(new: Option<Current>) {
    let me = std::thread::current().id();
    let fresh = new
        .clone()
        .map_or(std::ptr::null_mut(), |n| Box::into_raw(Box::new(n)));
    let old = CURRENT.with(|c| c.replace(fresh));
    // SAFETY: NULL or the Box set_current leaked before; reclaimed once.
    let old = (!old.is_null()).then(|| *unsafe { Box::from_raw(old) });
    if let Some(old) = old {
        let still = new.as_ref().is_some_and(|n| Arc::ptr_eq(&n.sc, &old.sc));
        if !still {
            let destroyed = {
                let mut st = old.sc.lock();
                if st.owner == Some(me) {
                    st.owner = None;
                }
                st.destroyed
            };
            if destroyed {
                // Deferred from glXDestroyContext: no longer current anywhere.
                old.sc.destroy();
                registry::with(|reg| reg.remove_doomed(old.sc.context()));
                context_destroyed(old.sc.context());
            }
        }
    }
    super::draws::watch_auto(new.as_ref().is_some_and(|n| n.sc.auto()));
    if let Some(n) = new {
        n.sc.lock().owner = Some(me);
    }
}

/// Deletes the program-side objects of destroyed drawables' buffers (their
/// framebuffer objects, which hold the textures) and finishes the
/// program's rendering, so that nothing renders into their memory when the
/// layer's context frees it ([`StereoContext::free_shared_side`]).
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn free_program_side(gl: &Gl, gone: &mut [(u64, Drawn)]) {
    if gone.is_empty() {
        return;
    }
    // SAFETY: contract. Deleting a bound framebuffer object reverts the
    // binding to 0, where the caller binds what belongs there.
    unsafe {
        for (_, d) in gone.iter_mut() {
            d.fb.delete_app_fbo(gl);
        }
        gl.Finish();
    }
}

impl StereoContext {
    /// The stereo state of program context `ctx`, presented with the
    /// layer's context `ours` (which shares its objects); its emulated
    /// buffers have `shape` and `formats` (those of the program's visual).
    pub fn new(
        display: usize,
        ctx: usize,
        ours: usize,
        shape: FramebufferShape,
        formats: BufferFormats,
        group: u64,
    ) -> Arc<StereoContext> {
        Self::new_on(Wsi::Glx, display, ctx, ours, shape, formats, group)
    }

    /// [`Self::new`] for a context of window system `wsi` (`display` and
    /// the contexts are that system's handles).
    pub fn new_on(
        wsi: Wsi,
        display: usize,
        ctx: usize,
        ours: usize,
        shape: FramebufferShape,
        formats: BufferFormats,
        group: u64,
    ) -> Arc<StereoContext> {
        Arc::new(StereoContext {
            wsi,
            display,
            ctx,
            ours,
            shape,
            formats,
            auto: formats.layered.is_some(),
            group,
            closed: AtomicBool::new(false),
            ended_elsewhere: AtomicBool::new(false),
            binding: Mutex::new(()),
            state: Mutex::new(CtxState {
                fbs: HashMap::new(),
                pending: GL_NO_ERROR,
                compositor: GlCompositor::new(),
                usable: None,
                owner: None,
                destroyed: false,
                attribs: Vec::new(),
                color_mask: [[true; 4]; MASKED_BUFFERS],
                clear_color: super::gl::ClearColor::Float([0.0; 4]),
                programs: Default::default(),
                auto: Default::default(),
            }),
        })
    }

    /// The window system that made it.
    pub fn wsi(&self) -> Wsi {
        self.wsi
    }

    /// The `Display*` (`EGLDisplay`) it was made on.
    pub fn display(&self) -> usize {
        self.display
    }

    /// The program's `GLXContext` (`EGLContext`).
    pub fn context(&self) -> usize {
        self.ctx
    }

    /// The layer's own context, in the program's share group.
    pub fn ours(&self) -> usize {
        self.ours
    }

    /// The storage formats of its emulated framebuffers.
    pub fn formats(&self) -> BufferFormats {
        self.formats
    }

    /// The framebuffer shape of its buffers.
    pub fn shape(&self) -> FramebufferShape {
        self.shape
    }

    /// The framebuffer shape the program's visual has: mono for a context
    /// given automatic stereo ([`Self::auto`]), else [`Self::shape`].
    pub fn program_shape(&self) -> FramebufferShape {
        FramebufferShape {
            stereo: self.shape.stereo && !self.auto,
            ..self.shape
        }
    }

    /// Whether this is a mono context given automatic stereo
    /// (glstereo-run --auto; [`crate::auto`]).
    pub fn auto(&self) -> bool {
        self.auto
    }

    /// Its share group: programs linked in one context of it are used in
    /// every other.
    pub fn group(&self) -> u64 {
        self.group
    }

    /// Runs `f` with the context's automatic-stereo state and the layered
    /// eyes of `drawable`'s emulated framebuffer (None: it has none) with
    /// the name of the framebuffer object the program draws into for it.
    pub fn with_auto<T>(
        &self,
        drawable: u64,
        f: impl FnOnce(
            &mut crate::auto::runtime::AutoState,
            Option<(u32, crate::auto::eyes::Attachments)>,
        ) -> T,
    ) -> T {
        let mut st = self.lock();
        let eyes = st
            .fbs
            .get(&drawable)
            .and_then(|d| d.fb.layered_attachments().map(|a| (d.fb.app_fbo(), a)));
        f(&mut st.auto, eyes)
    }

    /// Held around the program's glXMakeCurrent of this context and
    /// wherever the layer makes it current itself: the layer's own
    /// make-current of a context that is current nowhere never races the
    /// program's.
    pub fn hold_binding(&self) -> MutexGuard<'_, ()> {
        self.binding.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub(super) fn lock(&self) -> MutexGuard<'_, CtxState> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// When `drawable` was last bound to this context (None: never).
    pub fn last_bound(&self, drawable: u64) -> Option<u64> {
        self.lock().fbs.get(&drawable).map(|d| d.last_bound)
    }

    /// Whether the emulation is off for this context (GL < 3.0).
    pub fn unusable(&self) -> bool {
        self.lock().usable == Some(false)
    }

    /// glXDestroyContext of this context: when it is current on a thread,
    /// marks it to be destroyed when released and returns true (GLX keeps a
    /// current context alive until then, and the layer makes it current
    /// again after presenting, which a destroyed context cannot be);
    /// false when it is current nowhere (destroy it now).
    pub fn defer_destroy(&self) -> bool {
        let mut st = self.lock();
        st.destroyed = st.owner.is_some();
        st.destroyed
    }

    /// Whether it is current on a thread other than the calling one.
    pub fn current_elsewhere(&self) -> bool {
        let me = std::thread::current().id();
        self.lock().owner.is_some_and(|t| t != me)
    }

    /// Marks it as belonging to a display the program closed (XCloseDisplay
    /// frees the connection: the layer must never use it again).
    pub fn mark_closed(&self) {
        self.end_of_share_group();
        // XCloseDisplay's hooks run before it disconnects.
        self.release_images(Connection::Closing);
        self.closed.store(true, Ordering::SeqCst);
    }

    /// Before the share group may go (its objects freed by the driver, not
    /// by the layer): readies the layered eyes' shared memory for that
    /// ([`EmulatedFramebuffer::prepare_unmap`]).
    fn end_of_share_group(&self) {
        for drawn in self.lock().fbs.values() {
            drawn.fb.prepare_unmap();
        }
    }

    /// Frees the MIT-SHM images of its drawables.
    fn release_images(&self, connection: Connection) {
        if self.is_closed() {
            return;
        }
        self.release_images_on(self.x_display(), connection);
    }

    /// Frees the MIT-SHM images of its drawables, made on the X display
    /// `x` (None: it is gone; only this process's side is freed).
    pub(crate) fn release_images_on(&self, x: Option<usize>, connection: Connection) {
        let Ok(r) = real() else {
            return;
        };
        let (dpy, connection) = match x {
            Some(x) => (x as *mut xlib::Display, connection),
            None => (std::ptr::null_mut(), Connection::Lost),
        };
        let mut st = self.lock();
        for drawn in st.fbs.values_mut() {
            // SAFETY: made on this display, in the state the caller says.
            unsafe { drawn.image.release(&r.xlib, dpy, connection) };
        }
    }

    /// The X display its frames are put to with MIT-SHM: a GLX context's
    /// own, an EGL display's X display where the program opened it.
    fn x_display(&self) -> Option<usize> {
        match self.wsi {
            Wsi::Glx => Some(self.display),
            Wsi::Egl => super::egl::x_display(self.display),
        }
    }

    fn is_closed(&self) -> bool {
        self.closed.load(Ordering::SeqCst)
    }

    fn check_open(&self) -> Result<()> {
        if self.is_closed() {
            Err(Error::DisplayLost(
                "the stereo context's display was closed (XCloseDisplay) while it was current"
                    .into(),
            ))
        } else {
            Ok(())
        }
    }

    /// Destroys the program's context (a destroy the layer deferred, see
    /// [`Self::defer_destroy`]) and the layer's.
    fn destroy(&self) {
        if self.is_closed() {
            return;
        }
        if let Ok(r) = real() {
            // The program's context, which it destroyed, current nowhere now.
            self.wsi.destroy_context(r, self.display, self.ctx);
        }
        self.destroy_ours();
    }

    /// Destroys the layer's context. The textures it made belong to the
    /// program's share group and go with it.
    pub fn destroy_ours(&self) {
        if self.is_closed() {
            return;
        }
        self.end_of_share_group();
        self.release_images(Connection::Open);
        if let Ok(r) = real() {
            // Our own context, current nowhere (it is only made current
            // inside the layer's calls).
            self.wsi.destroy_context(r, self.display, self.ours);
            r.gl.context_left(self.ours);
        }
        if self.ended_elsewhere.load(Ordering::SeqCst) {
            // The program's thread may still render into the eyes: their
            // memory is readied and unmapped at its release.
            return;
        }
        // Neither context reads the layered eyes' memory any more.
        for drawn in self.lock().fbs.values_mut() {
            drawn.fb.unmap_layers();
        }
    }

    /// eglTerminate of its display, with the program's context current on
    /// the calling thread (EGL keeps it usable until it is released): from
    /// now on it renders into the real default framebuffer, in mono, where
    /// it had the emulated one bound, and what it rendered into the eyes is
    /// finished. The driver frees the eyes' memory with the share group at
    /// the release, reading the word the layer writes at the end of the share group
    /// inside the first eye's rows: nothing may render over it after that.
    pub fn leave_eyes_here(&self) {
        let Ok(r) = real() else {
            return;
        };
        let gl = &r.gl;
        let st = self.lock();
        // SAFETY: the program's context is current on this thread (the
        // caller's contract); binding 0 raises no error.
        unsafe {
            for (target, binding) in [
                (GL_DRAW_FRAMEBUFFER, GL_DRAW_FRAMEBUFFER_BINDING),
                (GL_READ_FRAMEBUFFER, GL_READ_FRAMEBUFFER_BINDING),
            ] {
                if st.is_ours(gl.integer(binding) as u32) {
                    gl.BindFramebuffer(target, 0);
                }
            }
            gl.Finish();
        }
    }

    /// eglTerminate of its display while it is current on another thread,
    /// which may render into its eyes until it releases it: their memory
    /// is readied for the driver, and the layer's view of it unmapped, at
    /// that release ([`StereoContext::before_release`]), not now.
    pub fn mark_ended_elsewhere(&self) {
        self.ended_elsewhere.store(true, Ordering::SeqCst);
    }

    /// Before the real call that releases it on this thread (eglMakeCurrent,
    /// eglReleaseThread), where the driver may free its share group: for a
    /// context whose display was terminated while it was current here
    /// ([`StereoContext::mark_ended_elsewhere`]), its rendering is finished and
    /// the eyes' memory readied for the driver's free. Returns whether
    /// [`StereoContext::after_release`] must follow a successful release.
    pub fn before_release(&self) -> bool {
        if !self.ended_elsewhere.load(Ordering::SeqCst) {
            return false;
        }
        if let Ok(r) = real() {
            // SAFETY: the program's context is current on this thread.
            unsafe { r.gl.Finish() };
        }
        self.end_of_share_group();
        true
    }

    /// After a successful release that [`StereoContext::before_release`]
    /// readied: the layer's view of the eyes' memory goes.
    pub fn after_release(&self) {
        if self.ended_elsewhere.swap(false, Ordering::SeqCst) {
            for drawn in self.lock().fbs.values_mut() {
                drawn.fb.unmap_layers();
            }
        }
    }

    /// Makes the layer's context current on `drawable`.
    fn make_ours_current(&self, r: &Real, drawable: u64) -> Result<()> {
        if !self
            .wsi
            .make_current(r, self.display, drawable, drawable, self.ours)
        {
            return Err(Error::Gl(format!(
                "the layer's context could not be made current on drawable {drawable:#x}"
            )));
        }
        Ok(())
    }

    /// After the real `glXMake[Context]Current` made this context current on
    /// `draw` / `read`: makes sure each drawable has its emulated
    /// framebuffer at the drawable's size, and binds it where the program
    /// has framebuffer 0 (or had this context's framebuffer of another
    /// drawable). The program's state is otherwise untouched; its pending
    /// GL errors are kept for its glGetError.
    pub fn bind(self: &Arc<Self>, draw: u64, read: u64) -> Result<()> {
        let r = loaded()?;
        self.check_open()?;
        let gl = &r.gl;
        // Sizes first: the registry lock is never taken under a state lock.
        let mut wanted = vec![(draw, self.wsi.drawable_size(r, self.display, draw)?)];
        if read != draw && read != 0 {
            wanted.push((read, self.wsi.drawable_size(r, self.display, read)?));
        }
        let gone_ids = self.gone_drawables(r, draw, read);
        let mut st = self.lock();
        if st.usable.is_none() {
            // SAFETY: the program's context is current.
            let v = unsafe { crate::gl::current_version(gl) };
            st.usable = Some(v.is_some_and(|v| v >= (3, 0)));
        }
        if st.usable == Some(false) {
            return Err(Error::BackendUnavailable(
                "the program's GL context is older than GL 3.0 (no framebuffer objects), \
                 so its stereo buffers cannot be emulated"
                    .into(),
            ));
        }
        let mut gone: Vec<(u64, Drawn)> = gone_ids
            .iter()
            .filter_map(|&d| st.fbs.remove_entry(&d))
            .collect();
        let stale: Vec<(u64, (u32, u32))> = wanted
            .iter()
            .copied()
            .filter(|(d, size)| st.fbs.get(d).is_none_or(|x| x.fb.size() != *size))
            .collect();
        // SAFETY: the program's context is current.
        unsafe { free_program_side(gl, &mut gone) };
        if !stale.is_empty() || !gone.is_empty() {
            let saved = self.wsi.saved(r);
            let made = self.make_ours_current(r, draw).and_then(|()| {
                // SAFETY: the layer's context is current.
                unsafe { self.free_shared_side(r, gone) };
                self.allocate(gl, &mut st, &stale)
            });
            saved.restore(r, self.display);
            made?;
        }
        // In the program's context: its framebuffer objects and bindings.
        st.save_driver_errors(gl);
        let tick = BIND_TICK.fetch_add(1, Ordering::Relaxed);
        for (d, _) in &wanted {
            let drawn = st.fbs.get_mut(d).expect("allocated above");
            drawn.last_bound = tick;
            if drawn.fb.app_fbo() == 0 {
                // SAFETY: the program's context is current; it shares the
                // textures made in ours.
                unsafe { drawn.fb.create_app_fbo(gl)? };
            } else if drawn.fb.attachments_stale() {
                // SAFETY: as above; its framebuffer object is the drawn one's.
                unsafe { drawn.fb.reattach_app(gl)? };
            }
        }
        let draw_fbo = st.fbs[&draw].fb.app_fbo();
        let read_fbo = st.fbs.get(&read).map_or(draw_fbo, |d| d.fb.app_fbo());
        // SAFETY: the program's context is current.
        unsafe {
            let bound_draw = gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32;
            if bound_draw == 0 || st.is_ours(bound_draw) {
                gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, draw_fbo);
            }
            let bound_read = gl.integer(GL_READ_FRAMEBUFFER_BINDING) as u32;
            if bound_read == 0 || st.is_ours(bound_read) {
                gl.BindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo);
            }
            super::gl::apply_color_mask(gl, self.formats, &st);
            gl.check("binding the emulated stereo framebuffer")
        }
    }

    /// The drawables whose buffers [`Self::bind`] of `draw` and `read`
    /// frees: those marked gone ([`Drawn::gone`]), and, when one of `draw`
    /// and `read` is new to the context, every other one that no longer
    /// exists (an X window destroyed with XDestroyWindow, with its parent,
    /// through xcb or by another client, which the layer does not see):
    /// one trapped XGetGeometry each (glXQueryDrawable for pbuffers and
    /// pixmaps), only then, never per frame. Takes the registry's lock:
    /// call it with no state locked.
    fn gone_drawables(&self, r: &Real, draw: u64, read: u64) -> Vec<u64> {
        let (mut gone, others) = {
            let st = self.lock();
            let new = !st.fbs.contains_key(&draw) || (read != 0 && !st.fbs.contains_key(&read));
            let mut gone = Vec::new();
            let mut others = Vec::new();
            for (&d, drawn) in &st.fbs {
                if drawn.gone {
                    // Also when it is `draw` or `read`: a new drawable
                    // with the destroyed one's id gets buffers of its own.
                    gone.push(d);
                } else if new && d != draw && d != read {
                    others.push(d);
                }
            }
            (gone, others)
        };
        gone.extend(
            others
                .into_iter()
                .filter(|&d| self.wsi.drawable_size(r, self.display, d).is_err()),
        );
        gone
    }

    /// Drawable `drawable` of this context's display is being destroyed
    /// (glXDestroyWindow, glXDestroyPbuffer, glXDestroyPixmap…; called
    /// before the real destroy, while it still exists): frees its buffers
    /// now where GLX allows, else marks them to be freed when the context
    /// is next bound or released. Current here on
    /// another drawable: freed in the program's context, then the layer's.
    /// Current nowhere: the program's context and the layer's are made
    /// current for the moment (with no drawable, or on `drawable`), then
    /// what was current is put back. Current on `drawable` (GLX keeps it
    /// until released) or on another thread: marked.
    pub fn drawable_destroyed(self: &Arc<Self>, drawable: u64) {
        if self.is_closed() {
            return;
        }
        let Ok(r) = real() else {
            return;
        };
        let _binding = self.hold_binding();
        let here_on = current()
            .filter(|c| Arc::ptr_eq(&c.sc, self))
            .map(|c| (c.draw, c.read));
        let mut st = self.lock();
        let elsewhere = st.owner.is_some() && here_on.is_none();
        let Some(drawn) = st.fbs.get_mut(&drawable) else {
            return;
        };
        match here_on {
            Some((draw, read)) if draw == drawable || read == drawable => {
                drawn.gone = true;
                return;
            }
            _ if elsewhere => {
                drawn.gone = true;
                return;
            }
            _ => {}
        }
        let drawn = st.fbs.remove_entry(&drawable).expect("found above");
        let host = here_on.map_or(drawable, |(draw, _)| draw);
        if let Some(kept) = self.free_now(r, vec![drawn], here_on.is_some(), host) {
            st.fbs.extend(kept);
        }
    }

    /// After this context stopped being current on this thread: frees the
    /// buffers of drawables destroyed while it was current on them, now
    /// that it is current nowhere (as [`Self::drawable_destroyed`]).
    pub fn released(self: &Arc<Self>) {
        if self.is_closed() {
            return;
        }
        let Ok(r) = real() else {
            return;
        };
        let _binding = self.hold_binding();
        let mut st = self.lock();
        if st.owner.is_some() || st.destroyed || !st.fbs.values().any(|d| d.gone) {
            return;
        }
        let ids: Vec<u64> = st
            .fbs
            .iter()
            .filter(|(_, d)| d.gone)
            .map(|(&k, _)| k)
            .collect();
        let gone: Vec<(u64, Drawn)> = ids.iter().filter_map(|d| st.fbs.remove_entry(d)).collect();
        // No drawable to fall back on: these are destroyed.
        if let Some(kept) = self.free_now(r, gone, false, 0) {
            st.fbs.extend(kept);
        }
    }

    /// Frees `gone` (removed from the state, whose lock the caller holds
    /// with [`StereoContext::binding`]): in the program's context — current
    /// here when `program_current`, else made current with no drawable or
    /// on `host` — its framebuffer objects go and its rendering is
    /// finished; then in the layer's, the textures, their memory and the
    /// images. What was current is put back. Returns the entries it could
    /// not free (no context could be made current), marked gone, keyed by
    /// drawable, for the caller to put back.
    fn free_now(
        &self,
        r: &Real,
        mut gone: Vec<(u64, Drawn)>,
        program_current: bool,
        host: u64,
    ) -> Option<Vec<(u64, Drawn)>> {
        let saved = self.wsi.saved(r);
        let give_back = |mut gone: Vec<(u64, Drawn)>| {
            for (_, d) in &mut gone {
                d.gone = true;
            }
            Some(gone)
        };
        if !program_current && !self.make_current_anywhere(r, self.ctx, host) {
            saved.restore(r, self.display);
            return give_back(gone);
        }
        // SAFETY: the program's context is current.
        unsafe { free_program_side(&r.gl, &mut gone) };
        let ours = self.make_current_anywhere(r, self.ours, host);
        let kept = if ours {
            // SAFETY: the layer's context is current.
            unsafe { self.free_shared_side(r, gone) };
            None
        } else {
            give_back(gone)
        };
        saved.restore(r, self.display);
        kept
    }

    /// Makes `ctx` (the program's context or the layer's) current with no
    /// drawable (GLX 1.3 with GL ≥ 3.0 contexts; Mesa allows it), else on
    /// `host` (0: none), X errors trapped; false when neither works.
    fn make_current_anywhere(&self, r: &Real, ctx: usize, host: u64) -> bool {
        // A context of the program's or the layer's, current nowhere else
        // (binding held, or current on this thread), and a drawable or none.
        let attempt = |d: u64| self.wsi.make_current(r, self.display, d, d, ctx);
        attempt(0) || (host != 0 && attempt(host))
    }

    /// Frees the shared objects of destroyed drawables' buffers (their
    /// framebuffer objects in the program's context went first,
    /// [`free_program_side`]): textures, renderbuffer, memory, images.
    ///
    /// # Safety
    /// The layer's context is current on this thread.
    unsafe fn free_shared_side(&self, r: &Real, gone: Vec<(u64, Drawn)>) {
        let (dpy, connection) = match self.x_display() {
            Some(x) => (x as *mut xlib::Display, Connection::Open),
            None => (std::ptr::null_mut(), Connection::Lost),
        };
        for (_, mut d) in gone {
            // SAFETY: the layer's context (which made them) is current;
            // the program's finished its rendering into them.
            unsafe {
                d.fb.release(&r.gl);
                d.image.release(&r.xlib, dpy, connection);
            }
        }
    }

    /// Allocates or resizes the framebuffers of `stale` drawables; the
    /// layer's context is current.
    fn allocate(&self, gl: &Gl, st: &mut CtxState, stale: &[(u64, (u32, u32))]) -> Result<()> {
        for &(d, (w, h)) in stale {
            match st.fbs.get_mut(&d) {
                // SAFETY: the layer's context (sharing the textures) is current.
                Some(drawn) => unsafe { drawn.fb.resize(gl, w, h)? },
                None => {
                    // SAFETY: the layer's context is current.
                    let fb = unsafe {
                        EmulatedFramebuffer::allocate_with(gl, self.shape, w, h, self.formats)?
                    };
                    st.fbs.insert(
                        d,
                        Drawn {
                            fb,
                            image: ShmSlot::Untried,
                            frames: 0,
                            last_bound: 0,
                            viewport_checked: false,
                            size_seen: None,
                            gone: false,
                        },
                    );
                }
            }
        }
        // The program's context uses the new storage next: make it complete.
        // SAFETY: the layer's context is current.
        unsafe { gl.Finish() };
        Ok(())
    }

    /// The size of `drawable` when the window system can tell it; an EGL
    /// surface destroyed while current has none and keeps its buffers
    /// (EGL keeps the surface until it is released), so None, quietly.
    fn live_size(&self, r: &Real, drawable: u64) -> Result<Option<(u32, u32)>> {
        match self.wsi.drawable_size(r, self.display, drawable) {
            Ok(size) => Ok(Some(size)),
            Err(_) if self.wsi == Wsi::Egl => Ok(None),
            Err(e) => Err(e),
        }
    }

    /// glViewport in this context (current here on `cur`): the first call
    /// of a frame with a size other than the buffers' checks whether the
    /// window was resized, and if so resizes the buffers before the program
    /// draws (as a real default framebuffer follows its window).
    pub fn viewport_hint(self: &Arc<Self>, cur: &Current, width: i32, height: i32) -> Result<()> {
        let r = loaded()?;
        let current_size = {
            let mut st = self.lock();
            let Some(drawn) = st.fbs.get_mut(&cur.draw) else {
                return Ok(());
            };
            let asked = (width.max(0) as u32, height.max(0) as u32);
            if drawn.viewport_checked || drawn.fb.size() == asked {
                return Ok(());
            }
            drawn.viewport_checked = true;
            drawn.fb.size()
        };
        if self
            .live_size(r, cur.draw)?
            .is_none_or(|s| s == current_size)
        {
            return Ok(());
        }
        self.bind(cur.draw, cur.read)
    }

    /// The first draw after a present ([`super::draws`]): the drawable's
    /// size, asked of the X server (one round trip, as Mesa's software
    /// framebuffer asks at the first draw after each swap), and the buffers
    /// resized before the program draws when the window changed size since
    /// — the program resized it itself, or a window manager did.
    pub fn follow_drawable_size(self: &Arc<Self>, cur: &Current) -> Result<()> {
        let r = loaded()?;
        let size = match self.lock().fbs.get(&cur.draw) {
            Some(d) => d.fb.size(),
            None => return Ok(()),
        };
        if self.live_size(r, cur.draw)?.is_none_or(|s| s == size) {
            return Ok(());
        }
        self.bind(cur.draw, cur.read)
    }

    /// Presents `drawable`'s front buffers: with `flip`, first its back
    /// buffers become the front ones (glXSwapBuffers); without, the fronts
    /// as they are (glFlush/glFinish after drawing to a front buffer).
    /// The eyes are composed in the output mode into the drawable's real
    /// back buffer in the layer's context, which swaps it; then what was
    /// current before is made current again. `here`: this is the stereo
    /// context current on this thread, on `drawable`.
    pub fn present(self: &Arc<Self>, drawable: u64, flip: bool, here: bool) -> Result<()> {
        let r = loaded()?;
        self.check_open()?;
        let saved = self.wsi.saved(r);
        let _binding = (!here).then(|| self.hold_binding());
        if !here {
            // Not current on this thread (and not on another: checked by the
            // caller): bind it here for the flip.
            if !self
                .wsi
                .make_current(r, self.display, drawable, drawable, self.ctx)
            {
                return Err(Error::Gl(
                    "the drawable's stereo context could not be made current".into(),
                ));
            }
        }
        // A fault (a panic) while presenting costs this frame only: what
        // was current goes back, and the next frame starts as any other.
        let result =
            crate::fault::contain(|| self.flip_and_show(r, drawable, flip)).and_then(|r| r);
        profile::span(Stage::SwitchOut, || saved.restore(r, self.display));
        if here {
            // A resize after the frame replaced textures the program draws
            // the next one into: attach the new ones now (otherwise when
            // the context is next made current).
            let mut st = self.lock();
            if let Some(drawn) = st.fbs.get_mut(&drawable) {
                // A live switch of automatic stereo's kind attaches the
                // eyes' layers anew (Ctrl+F2).
                drawn.fb.follow_auto_mode();
                // SAFETY: the program's context is current again, on `drawable`.
                let reattached = unsafe { drawn.fb.reattach_app(&r.gl) };
                if result.is_ok() {
                    reattached?;
                }
            }
            // The window may change size before the program draws again.
            super::draws::check_size_at_next_draw();
        }
        profile::frame_end();
        result
    }

    /// [`Self::present`] with the program's context current on `drawable`:
    /// flips, then shows the fronts from the layer's context. Whatever it
    /// leaves current, the caller puts back what was current before.
    fn flip_and_show(&self, r: &Real, drawable: u64, flip: bool) -> Result<()> {
        let gl = &r.gl;
        // The size seen after the last frame's put, while frames of that
        // size go out through MIT-SHM; else (a first frame, a resize the
        // program made known through glViewport, the GL path, a window
        // that was gone) the server is asked. A window resized behind the
        // program's back shows one frame at the old size, and the buffers
        // follow for the next one; the put to a window destroyed since is
        // an X error trapped in put_pixels, and the next present reports it.
        let seen = {
            let st = self.lock();
            st.fbs
                .get(&drawable)
                .and_then(|d| d.size_seen.filter(|&s| s == d.fb.size()))
        };
        let window = match seen {
            Some(size) => size,
            None => profile::span(Stage::RoundTrip, || {
                self.wsi.drawable_size(r, self.display, drawable)
            })?,
        };
        profile::frame_start(|| window);
        let x_window = self.wsi.x_drawable(self.display, drawable);
        let mut guard = self.lock();
        let st = &mut *guard;
        // The layer's own calls below keep the program's errors apart.
        st.save_driver_errors(gl);
        let drawn = st
            .fbs
            .get_mut(&drawable)
            .ok_or_else(|| Error::invalid_operation("no stereo buffers for this drawable"))?;
        // Automatic convergence measures some frames: what the program's
        // context says of this one.
        let measured = if self.auto {
            // SAFETY: the program's context is current on this thread.
            unsafe { crate::auto::runtime::frame_geometry(&mut st.auto, self.group, drawn.frames) }
        } else {
            None
        };
        // SAFETY: the program's context is current on this thread.
        unsafe {
            // Automatic stereo draws both eyes into layers: the buffers
            // shown get them.
            drawn.fb.resolve_layers(!flip);
            if flip {
                profile::span(Stage::Flip, || drawn.fb.swap(gl));
            }
            gl.take_error();
            // The layer's context reads what the program drew: finish it.
            profile::span(Stage::Finish, || gl.Finish());
            // Nothing renders into replaced textures now: free their memory.
            drawn.fb.release_retired(gl);
        }
        drawn.frames += 1;
        drawn.viewport_checked = false;
        let frame_index = drawn.frames - 1;
        // The layer's context is made current only when this frame needs
        // GL of its own (a measure, a capture, a GL composite, a resize):
        // a frame composed on the CPU from eyes in memory and put with
        // MIT-SHM needs none, and each make-current costs a round trip on
        // Mesa's software GLX.
        let mut ours = false;
        if let Some(frame) = measured.as_ref().filter(|f| f.converges) {
            self.switch_in(r, drawable, &mut ours)?;
            let fb = &drawn.fb;
            if let Some(eyes) = fb.layered() {
                let scratch = &mut st.auto.measure;
                // SAFETY: the layer's context, sharing the program's
                // objects, is current; `read_fbo` is of that context.
                unsafe { crate::auto::converge::measure(gl, eyes, fb.read_fbo(), frame, scratch) };
            }
        }
        // Eyes made from the frame's depth (--auto=depth): the program
        // drew its frame once, into the left eye. Where the eyes are in
        // memory they are made as the composite reads them (`pending`).
        let mut pending = None;
        if self.auto && crate::auto::live::from_depth() {
            let scratch = &mut st.auto.from_depth;
            // The layer's context only where the depth or the eyes are
            // read through GL.
            let mut switch_in = || self.switch_in(r, drawable, &mut ours);
            // SAFETY: the program's frame is finished (above); the layer's
            // context is made current before any GL call of make's; the
            // pending eyes are made (below) before the program draws again
            // or the framebuffer is resized.
            let made = profile::span(Stage::FromDepth, || unsafe {
                crate::auto::from_depth::make(
                    gl,
                    &drawn.fb,
                    measured.as_ref(),
                    scratch,
                    &mut switch_in,
                )
            });
            match made {
                Ok((m, p)) => {
                    settings::tell(&format!(
                        "automatic stereo from depth: each frame rendered once, both eyes made \
                         from its colour and depth ({})",
                        match m {
                            crate::auto::from_depth::Made::FromDepth => "this frame at depth",
                            crate::auto::from_depth::Made::Flat => "this frame flat",
                        }
                    ));
                    pending = p;
                }
                Err(e) => crate::report::warn(&format!("{e}")),
            }
        }
        let made = pending.as_ref().map(|p| p as &dyn MakeEyes);
        let shown = self.compose_and_swap(
            r,
            st,
            (drawable, x_window),
            window,
            frame_index,
            &mut ours,
            made,
        );
        if let Some(p) = pending {
            p.finish(&mut st.auto.from_depth);
        }
        shown
    }

    /// Whether a frame of this context's windows may go to the X server
    /// from memory (MIT-SHM) instead of through the real swap: a GLX
    /// window, or an EGL surface's X window where the program opened the
    /// display ([`Wsi::x_drawable`]); not where the swap is another
    /// layer's, which must see every frame.
    fn puts_pixels(&self, r: &Real) -> bool {
        match self.wsi {
            Wsi::Glx => !r.swap_layered,
            Wsi::Egl => !super::egl::swap_layered(),
        }
    }

    /// Makes the layer's context current on `drawable` unless `ours` says
    /// it is already.
    fn switch_in(&self, r: &Real, drawable: u64, ours: &mut bool) -> Result<()> {
        if !*ours {
            profile::span(Stage::SwitchIn, || self.make_ours_current(r, drawable))?;
            *ours = true;
        }
        Ok(())
    }

    /// Composes, captures, shows the frame (from memory or with a swap) of
    /// `drawable` (of the given size; `x_window` is the X display and X
    /// drawable behind it, where there is one), and follows a resized
    /// window. With the program's context current on the drawable, or the
    /// layer's when `ours` says so; the layer's is made current where its
    /// GL is needed.
    #[allow(clippy::too_many_arguments)]
    fn compose_and_swap(
        &self,
        r: &Real,
        st: &mut CtxState,
        (drawable, x_window): (u64, Option<(usize, u64)>),
        (width, height): (u32, u32),
        frame_index: u64,
        ours: &mut bool,
        made: Option<&dyn MakeEyes>,
    ) -> Result<()> {
        let gl = &r.gl;
        let mode = super::live::mode();
        let options = super::live::options();
        if let Some((x_display, x_window)) = x_window {
            super::controls::presented(x_display, x_window, width, height);
        }
        let CtxState {
            fbs, compositor, ..
        } = st;
        let drawn = fbs.get_mut(&drawable).expect("checked by present");
        let job = Job::front_buffers(
            &drawn.fb,
            InputFraming::QuadBuffer,
            mode,
            options,
            frame_index,
        );
        // A software renderer's frame goes to the window from memory when
        // it can (one CPU pass instead of a full-window GL pass and the
        // swap's own copy; see backend/xshm.rs), else through GL. Not for
        // single-buffered windows: Mesa's software driver copies the
        // program's real front buffer into the window when the program
        // flushes, over the frame put there.
        // Not when the next glXSwapBuffers is another layer's: that layer
        // must see every frame (MangoHud's HUD, VirtualGL's transport).
        // Some(size after the put) when the frame went out through MIT-SHM.
        let mut seen = None;
        if self.wsi == Wsi::Glx && r.swap_layered {
            settings::tell(
                "frames are presented through the glXSwapBuffers of a GL layer below glstereo \
                 (composed by GL, not put with MIT-SHM)",
            );
        } else if self.wsi == Wsi::Egl && super::egl::swap_layered() {
            settings::tell(
                "frames are presented through the eglSwapBuffers of a layer below glstereo",
            );
        }
        // An EGL surface on X whose display the program opened goes the
        // same way (its real eglSwapBuffers is then not called: Mesa's
        // software EGL would send the frame again, without MIT-SHM);
        // other EGL surfaces (Wayland, EGL's own X connection) through
        // the real eglSwapBuffers.
        let capturing = capture::sink();
        // A capture reads the eyes where they are: made there first.
        if let (Some(m), Some(_)) = (made, &capturing) {
            m.in_place();
        }
        let shown = match x_window {
            Some(x) if self.shape.double_buffered && self.puts_pixels(r) => {
                // SAFETY: the program finished the eyes (flip_and_show).
                let in_place = match capturing {
                    None if !*ours => unsafe { compositor.in_place_plan(&job) },
                    _ => None,
                };
                if in_place.is_none() {
                    self.switch_in(r, drawable, ours)?;
                }
                // SAFETY: the layer's context is current on the drawable
                // (or the plan needs no GL), whose X drawable is `x`; the
                // job's textures are shared with it.
                unsafe {
                    put_pixels(
                        r,
                        compositor,
                        drawn,
                        x,
                        (width, height),
                        &job,
                        in_place,
                        &mut seen,
                        made,
                    )
                }
            }
            _ => Ok(false),
        };
        if !matches!(shown, Ok(true)) {
            self.switch_in(r, drawable, ours)?;
        }
        // `in_gl`: the frame is shown through the window's GL buffers (the
        // swap, or the glFinish of a single-buffered window, below), even
        // when composing into them failed.
        let (composed, in_gl) = match shown {
            Ok(true) => (Ok(()), false),
            // SAFETY: as above.
            Ok(false) => (
                profile::span(Stage::GlCompose, || unsafe {
                    if let Some(m) = made {
                        m.in_place();
                    }
                    compositor.compose_window(gl, &job, 0, width, height)
                }),
                true,
            ),
            Err(e) => (Err(e), false),
        };
        // Read the eyes back before the swap: with Mesa's software GLX,
        // binding framebuffer 0 after a swap (as reading back ends by doing)
        // fixes the window's size until the next swap, so a resize that
        // follows would be missed for a frame.
        if let Some(sink) = capturing {
            let (w, h) = drawn.fb.size();
            let mut left = Image::new(w, h);
            let mut right = Image::new(w, h);
            // SAFETY: the layer's context is current; the images hold w×h×4 bytes.
            unsafe {
                drawn
                    .fb
                    .read_pixels(gl, ColorBuffer::FrontLeft, left.pixels_mut())?;
                drawn
                    .fb
                    .read_pixels(gl, ColorBuffer::FrontRight, right.pixels_mut())?;
            }
            sink.submit(capture::Frame {
                left,
                right,
                mode,
                options,
                frame_index,
            });
        }
        if in_gl && self.shape.double_buffered {
            // The drawable is current in our context.
            profile::span(Stage::GlCompose, || {
                self.wsi.swap(r, self.display, drawable)
            });
        } else if in_gl {
            // A single-buffered window was drawn in its front buffer.
            // SAFETY: our context is current.
            unsafe { gl.Finish() };
        }
        // The frame is on the server when presenting returns: Mesa's
        // software swap sends the image in several requests without
        // waiting, and another client (a screenshot, a compositor) could
        // otherwise see it half drawn or not yet. One round trip: after a
        // MIT-SHM put, put_pixels's size query was it.
        drawn.size_seen = seen.flatten();
        if seen.is_none() {
            profile::span(Stage::XSync, || self.wsi.sync(r, self.display));
        }
        let (width, height) = drawn.size_seen.unwrap_or((width, height));
        if drawn.fb.size() != (width, height) {
            self.switch_in(r, drawable, ours)?;
            // SAFETY: the layer's context is current.
            unsafe {
                drawn.fb.resize(gl, width, height)?;
                gl.Finish();
            }
        }
        composed
    }
}

/// Shows `job`'s composite in the window `x_window` from memory through
/// MIT-SHM, when the renderer is software and the window can take it.
/// Ok(false): nothing shown, take the GL path (a hardware renderer, a
/// composite of another size than the window, `quad`, no MIT-SHM, a pixmap
/// or pbuffer drawable, an unsupported visual). The put and a size query
/// behind it run with X errors trapped (a window destroyed since the last
/// frame must not end the program); when the put was sent, `seen` becomes
/// Some(the window's size, None if it is gone), and the query's reply
/// means the server has shown the frame. `in_place`: a plan of
/// [`GlCompositor::in_place_plan`], composed without GL.
///
/// # Safety
/// The layer's context is current on the drawable, or `in_place` is Some
/// and the eyes are finished; `display` is open and `x_window` is the
/// drawable's X drawable; the job's textures are shared with the layer's
/// context.
#[allow(clippy::too_many_arguments)]
unsafe fn put_pixels(
    r: &Real,
    compositor: &mut GlCompositor,
    drawn: &mut Drawn,
    (display, x_window): (usize, u64),
    size: (u32, u32),
    job: &Job,
    in_place: Option<crate::output::gl::PixelPlan>,
    seen: &mut Option<Option<(u32, u32)>>,
    made: Option<&dyn MakeEyes>,
) -> Result<bool> {
    if drawn.image.unsupported() {
        return Ok(false);
    }
    let gl = &r.gl;
    let plan = match in_place {
        Some(plan) => plan,
        // SAFETY: the layer's context is current (contract).
        None => match unsafe { compositor.pixel_plan(gl, job, size.0, size.1)? } {
            Some(plan) => plan,
            None => return Ok(false),
        },
    };
    let dpy = display as *mut xlib::Display;
    // SAFETY: open display, the drawable's X drawable (contract); the
    // layer's context is current and the plan is for this job and size.
    unsafe {
        drawn.image.put(
            &r.xlib,
            (dpy, x_window),
            size,
            || shm_image(r, dpy, x_window, size),
            &mut |t| match in_place {
                Some(_) => compositor.fill_in_place(job, plan, t, made),
                None => compositor.fill_pixels(gl, job, plan, t, made),
            },
            &mut |put| {
                let (size, err) = trap_replied_x_errors(&r.xlib, dpy, || {
                    put();
                    profile::span(Stage::XSync, || super::wsi::geometry(r, dpy, x_window))
                });
                *seen = Some(size.filter(|_| err == 0));
            },
        )
    }
}

/// A MIT-SHM image of `size` for `window` (its visual and depth); None when
/// `window` is not an InputOutput window or MIT-SHM cannot serve it. X
/// errors are trapped, never reach the program.
///
/// # Safety
/// `dpy` is an open display.
unsafe fn shm_image(
    r: &Real,
    dpy: *mut xlib::Display,
    window: u64,
    size: (u32, u32),
) -> Option<ShmImage> {
    // SAFETY: plain C struct, filled by Xlib.
    let mut attrs: xlib::XWindowAttributes = unsafe { std::mem::zeroed() };
    let (ok, err) = trap_x_errors(&r.xlib, dpy, || {
        // SAFETY: open display; a bad window is an X error, trapped.
        unsafe { (r.xlib.XGetWindowAttributes)(dpy, window, &mut attrs) }
    });
    if ok == 0 || err != 0 || attrs.class != xlib::InputOutput {
        return None;
    }
    let trap = |f: &mut dyn FnMut()| trap_x_errors(&r.xlib, dpy, f).1;
    // SAFETY: open display; the window's own visual and depth.
    unsafe { ShmImage::create(&r.xlib, dpy, window, attrs.visual, attrs.depth, size, &trap) }
}

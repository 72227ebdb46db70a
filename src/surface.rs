//! Surfaces: an emulated stereo default framebuffer with its two contexts,
//! and the per-thread notion of the current surface.
//!
//! GL's rule holds: a surface's application context is current on at most
//! one thread at a time, and each thread has at most one current surface.

use crate::sync::LockRecover;
use std::cell::RefCell;
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::ThreadId;

use crate::backend::{ContextRole, PlatformSurface, WindowEvent};
use crate::config::{Config, StereoKind};
use crate::display::Display;
use crate::error::{Error, Result};
use crate::framing::{EyeSource, InputFraming};
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::image::{Image, check_size};
use crate::output::gl::{ComposePath, GlCompositor, Job, preferred_path};
use crate::output::layout::{composite_size, eye_size_for_window};
use crate::output::options::{OutputOptions, OutputSettings};
use crate::output::{AnaglyphColors, AnaglyphMethod, OutputMode, cpu};
use crate::profile::{self, Stage};
use crate::shims::nv3dvision::StereoSettings;
use crate::stereo::buffers::{ColorBuffer, gl_error_code, resolve_read_buffer};
use crate::stereo::emulated::{BufferFormats, EmulatedFramebuffer, default_framebuffer_query};

// Captures without a stall: PNGs and stereo photos written by threads, and
// the stereo photos themselves (src/surface/captures.rs).
mod captures;

thread_local! {
    /// The surface current on this thread and which of its contexts.
    static CURRENT: Current = const { Current(RefCell::new(None)) };
}

/// This thread's current surface. A thread that ends with a surface current
/// releases it (as if it called gls_make_current(NULL)): otherwise the
/// surface would stay owned by a thread that no longer exists — no other
/// thread could make it current — and a surface destroyed meanwhile would
/// never free its contexts.
struct Current(RefCell<Option<(Arc<Surface>, ContextRole)>>);

impl std::ops::Deref for Current {
    type Target = RefCell<Option<(Arc<Surface>, ContextRole)>>;
    fn deref(&self) -> &Self::Target {
        &self.0
    }
}

impl Drop for Current {
    fn drop(&mut self) {
        if let Some((s, _)) = self.0.get_mut().take() {
            let _ = s.platform.release_current();
            *s.owner.lock().unwrap_or_else(|e| e.into_inner()) = None;
        }
    }
}

/// The surface whose application context is current on this thread.
pub fn current() -> Option<Arc<Surface>> {
    CURRENT.with(|c| match &*c.borrow() {
        Some((s, ContextRole::App)) => Some(s.clone()),
        _ => None,
    })
}

/// The current surface, or `NoCurrentSurface`.
pub fn require_current() -> Result<Arc<Surface>> {
    current().ok_or(Error::NoCurrentSurface)
}

/// Makes `surface`'s application context current on this thread (None
/// releases the current one).
pub fn make_current(surface: Option<&Arc<Surface>>) -> Result<()> {
    let me = std::thread::current().id();
    let prev = CURRENT.with(|c| c.borrow().clone());
    let Some(s) = surface else {
        if let Some((p, _)) = prev {
            p.platform.release_current()?;
            *p.owner.recover() = None;
            CURRENT.with(|c| *c.borrow_mut() = None);
        }
        return Ok(());
    };
    if let Some((p, ContextRole::App)) = &prev {
        if Arc::ptr_eq(p, s) {
            return Ok(());
        }
    }
    {
        // Checked and taken under one lock: another thread checking meanwhile
        // waits, then finds the surface taken.
        let mut owner = s.owner.recover();
        if owner.is_some_and(|t| t != me) {
            return Err(Error::invalid_operation(
                "this surface is current on another thread: release it there first (gls_make_current(NULL))",
            ));
        }
        if let Some((p, _)) = &prev {
            if !Arc::ptr_eq(&p.display, &s.display) {
                // A different backend (or display): leave nothing of it current here.
                let _ = p.platform.release_current();
            }
        }
        if let Err(e) = s.platform.make_current(ContextRole::App) {
            if let Some((p, role)) = &prev {
                let _ = p.platform.make_current(*role);
            }
            return Err(e);
        }
        *owner = Some(me);
    }
    if let Some((p, _)) = &prev {
        if !Arc::ptr_eq(p, s) {
            *p.owner.recover() = None;
        }
    }
    CURRENT.with(|c| *c.borrow_mut() = Some((s.clone(), ContextRole::App)));
    let mut st = s.state.recover();
    // SAFETY (both): the application context was just made current.
    let attached = if st.fb.app_fbo() == 0 {
        unsafe { st.fb.attach_app(&s.gl) }
    } else {
        // Eye textures replaced by a resize whose re-attachment failed at
        // the swap (see Surface::reattach_replaced_eyes) get another try.
        unsafe { st.fb.reattach_app(&s.gl) }
    };
    if let Err(e) = attached {
        drop(st);
        let _ = make_current(None);
        return Err(e);
    }
    Ok(())
}

/// The output mode a surface uses when neither the program nor
/// GLSTEREO_MODE chose one, and the fallback for `quad` on a surface without
/// native stereo.
pub const DEFAULT_OUTPUT: OutputMode =
    OutputMode::Anaglyph(AnaglyphColors::RedCyan, AnaglyphMethod::FullColor);

/// The mutable state of a surface.
struct SurfaceState {
    /// The eye buffers. Their GL objects go with the surface's contexts;
    /// eye memory ([`crate::stereo::eye_memory`]) is freed before (see
    /// `Drop for Surface`).
    fb: EmulatedFramebuffer,
    /// How the program delivers its eyes.
    framing: InputFraming,
    /// The window size seen at the last swap (None before the first, and
    /// always for headless surfaces).
    window: Option<(u32, u32)>,
    /// The output mode as set (may be `quad`).
    output: OutputMode,
    /// Swap, crosstalk, saturation.
    options: OutputOptions,
    /// Swaps so far.
    frames: u64,
    /// A GL error the emulation raised, reported by the next get_error().
    pending_gl_error: u32,
    /// The GL compositor (objects in the compositor context, made on first use).
    compositor: GlCompositor,
    /// NV_3dvision_settings state (src/shims/nv3dvision.rs).
    nv3dvision: StereoSettings,
    /// JPEG quality of stereo photos (MPO, JPS), 1 … 100.
    jpeg_quality: u8,
    /// The application context's rendering is finished (glFinish) for the
    /// compositor call running now: the CPU may read eyes in place
    /// ([`crate::stereo::eye_memory`]). Set by
    /// [`Surface::with_compositor`] around its closure only.
    eyes_finished: bool,
}

/// A stereo (or mono) surface: emulated default framebuffer, two contexts.
pub struct Surface {
    display: Arc<Display>,
    config: Config,
    platform: Box<dyn PlatformSurface>,
    gl: Arc<Gl>,
    /// The thread the application context is current on. Held while that
    /// context is made current, so that two threads cannot both find the
    /// surface free and both make it current (OSMesa lets a context be
    /// current on two threads at once; Mesa's GL state is not made for it).
    owner: Mutex<Option<ThreadId>>,
    /// Held by the thread whose call has the compositor context current
    /// ([`Surface::with_compositor`]): from the make-current to the
    /// release, one thread at a time. Without it a second thread composing
    /// or reading the surface meanwhile made the same context current too:
    /// EGL refused it (the call failed), OSMesa allowed it.
    compositing: Mutex<()>,
    state: Mutex<SurfaceState>,
    /// The capture encoder and writer threads, started by the first queued capture.
    captures: Mutex<Option<crate::capture::queue::CaptureQueue>>,
}

impl Drop for Surface {
    /// Frees eye memory ([`crate::stereo::eye_memory`]) before the contexts
    /// go: the application context's rendering is finished first. Left to
    /// context destruction, Mesa unmaps the memory with the share group
    /// while llvmpipe may still be rasterizing a swapped frame into it (a
    /// headless swap only flushes): a crash in its rasterizer threads.
    /// Nothing else needs a context: the GL objects go with the contexts.
    /// No context of the surface is current anywhere now (a thread's
    /// current surface holds a reference to it).
    fn drop(&mut self) {
        let st = self.state.get_mut().unwrap_or_else(|e| e.into_inner());
        if !st.fb.holds_memory() {
            return;
        }
        let (platform, gl) = (&*self.platform, &self.gl);
        let mut release = || {
            platform.make_current(ContextRole::App)?;
            // SAFETY: the application context is current.
            unsafe { gl.Finish() };
            platform.make_current(ContextRole::Compositor)?;
            // SAFETY: the compositor context is current; `fb.release`
            // finishes its work before it frees the memory.
            unsafe { st.fb.release(gl) };
            Ok(())
        };
        // A thread whose current surface is being dropped with its
        // thread-local state has nothing current to put back.
        if CURRENT.try_with(|_| ()).is_ok() {
            let _ = with_compositor_of(&self.display, platform, release);
        } else {
            let _ = release();
            let _ = platform.release_current();
        }
    }
}

impl std::fmt::Debug for Surface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (w, h) = self.size();
        write!(f, "Surface({w}x{h}, {:?})", self.config.stereo)
    }
}

/// Runs `f` with `platform`'s compositor context current, then puts back
/// whatever was current on this thread before.
///
/// When the thread's current surface belongs to another display, its
/// context is released first and this one's released before it is made
/// current again: backends share Mesa's per-thread GL dispatch (libOSMesa
/// and the EGL/GLX driver both use libglapi), and a make-current that the
/// other backend's bookkeeping thinks changes nothing would leave GL calls
/// going to the wrong context.
fn with_compositor_of<T>(
    display: &Arc<Display>,
    platform: &dyn PlatformSurface,
    f: impl FnOnce() -> Result<T>,
) -> Result<T> {
    let saved = CURRENT.with(|c| c.borrow().clone());
    let foreign = saved
        .as_ref()
        .is_some_and(|(p, _)| !Arc::ptr_eq(&p.display, display));
    if let (true, Some((p, _))) = (foreign, &saved) {
        p.platform.release_current()?;
    }
    if let Err(e) = profile::span(Stage::SwitchIn, || {
        platform.make_current(ContextRole::Compositor)
    }) {
        if let Some((p, role)) = &saved {
            let _ = p.platform.make_current(*role);
        }
        return Err(e);
    }
    let result = f();
    let restored = profile::span(Stage::SwitchOut, || match &saved {
        Some((p, role)) => {
            if foreign {
                let _ = platform.release_current();
            }
            p.platform.make_current(*role)
        }
        None => platform.release_current(),
    });
    let value = result?;
    restored?;
    Ok(value)
}

impl Surface {
    pub(crate) fn create(
        display: Arc<Display>,
        config: Config,
        width: u32,
        height: u32,
    ) -> Result<Arc<Surface>> {
        check_size(width, height)?;
        // The environment's output settings apply to every new surface; a
        // bad value fails here, before anything is created.
        let settings = OutputSettings::from_env()?;
        let mode = effective_mode(settings.mode.unwrap_or(DEFAULT_OUTPUT), &config);
        // A window shows the composite pixel for pixel: side-by-side of W×H
        // eyes is a 2W×H window (Xinerama's passive layout), and so on.
        let (win_w, win_h) = composite_size(mode, width, height);
        check_size(win_w, win_h)?;
        let platform = display.platform().create_surface(&config, win_w, win_h)?;
        let shape = config.shape();
        let (fb, gl) = with_compositor_of(&display, &*platform, || {
            let gl = display.gl()?;
            // Eyes the CPU reads where llvmpipe draws them, where it can
            // (checked when made; ordinary textures otherwise).
            let formats = BufferFormats {
                in_place: display.memory_objects(),
                ..BufferFormats::surface(config.depth_bits, config.stencil_bits)
            };
            // SAFETY: the compositor context is current.
            let fb =
                unsafe { EmulatedFramebuffer::allocate_with(&gl, shape, width, height, formats)? };
            if fb.holds_memory() {
                // The clears of the new eyes land before the CPU reads them.
                // SAFETY: as above.
                unsafe { gl.Finish() };
            }
            Ok((fb, gl))
        })?;
        Ok(Arc::new(Surface {
            display,
            config,
            platform,
            gl,
            owner: Mutex::new(None),
            compositing: Mutex::new(()),
            state: Mutex::new(SurfaceState {
                fb,
                framing: InputFraming::QuadBuffer,
                window: None,
                output: settings.mode.unwrap_or(DEFAULT_OUTPUT),
                options: settings.options,
                frames: 0,
                pending_gl_error: GL_NO_ERROR,
                compositor: GlCompositor::new(),
                nv3dvision: StereoSettings::new(false),
                jpeg_quality: crate::capture::stereo_photo::DEFAULT_JPEG_QUALITY,
                eyes_finished: false,
            }),
            captures: Mutex::new(None),
        }))
    }

    /// The display this surface was made on.
    pub fn display(&self) -> &Arc<Display> {
        &self.display
    }

    /// The surface's configuration.
    pub fn config(&self) -> &Config {
        &self.config
    }

    /// The GL table (valid while one of this surface's contexts is current).
    pub fn gl(&self) -> &Gl {
        &self.gl
    }

    /// The address of a GL function of this surface's backend.
    pub fn get_proc_address(&self, name: &std::ffi::CStr) -> *const std::ffi::c_void {
        self.display.platform().get_proc_address(name)
    }

    /// Width and height of each eye's buffers.
    pub fn size(&self) -> (u32, u32) {
        self.state.recover().fb.size()
    }

    /// Swaps so far.
    pub fn frames(&self) -> u64 {
        self.state.recover().frames
    }

    fn is_current_here(self: &Arc<Self>) -> bool {
        current().is_some_and(|c| Arc::ptr_eq(&c, self))
    }

    /// The state, for a call that needs this surface current on this thread.
    fn current_state(self: &Arc<Self>) -> Result<MutexGuard<'_, SurfaceState>> {
        if !self.is_current_here() {
            return Err(Error::NoCurrentSurface);
        }
        Ok(self.state.recover())
    }

    /// Runs `f` in the application context: directly when this surface is
    /// current here, else by making it current for the call and restoring
    /// the thread's previous surface. Fails if it is current on another thread.
    fn with_app<T>(self: &Arc<Self>, f: impl FnOnce(&mut SurfaceState) -> Result<T>) -> Result<T> {
        if self.is_current_here() {
            return f(&mut self.state.recover());
        }
        let prev = current();
        make_current(Some(self))?;
        let r = f(&mut self.state.recover());
        let restored = make_current(prev.as_ref());
        let v = r?;
        restored?;
        Ok(v)
    }

    /// Runs `f` in this surface's compositor context, after making sure the
    /// application's rendering is complete when it is current on this thread.
    fn with_compositor<T>(
        self: &Arc<Self>,
        f: impl FnOnce(&Gl, &mut SurfaceState) -> Result<T>,
    ) -> Result<T> {
        self.with_compositor_as(false, f)
    }

    /// [`Surface::with_compositor`]; `finished`: the caller finished the
    /// application context's rendering itself. When it is finished either
    /// way, `f` sees [`SurfaceState::eyes_finished`] and may read eyes in
    /// place; otherwise (the surface is current on another thread, or on
    /// none) they are read back by GL, which synchronises.
    fn with_compositor_as<T>(
        self: &Arc<Self>,
        finished: bool,
        f: impl FnOnce(&Gl, &mut SurfaceState) -> Result<T>,
    ) -> Result<T> {
        let here = self.is_current_here();
        if here {
            // SAFETY: the application context is current; objects it renders
            // to are only guaranteed visible to another context after Finish.
            profile::span(Stage::Finish, || unsafe { self.gl.Finish() });
        }
        // One thread at a time has the compositor context current.
        let _compositing = self.compositing.recover();
        with_compositor_of(&self.display, &*self.platform, || {
            let mut st = self.state.recover();
            st.eyes_finished = here || finished;
            let r = f(&self.gl, &mut st);
            st.eyes_finished = false;
            r
        })
    }

    /// glDrawBuffer on the emulated default framebuffer (this surface must
    /// be current). On error the state is unchanged and the GL error is
    /// also queued for [`Surface::take_gl_error`].
    pub fn draw_buffer(self: &Arc<Self>, name: u32) -> Result<()> {
        let mut st = self.current_state()?;
        // SAFETY: the application context is current (checked).
        let r = unsafe { st.fb.set_draw_buffer(&self.gl, name) };
        record_gl_error(&mut st, &r);
        r
    }

    /// glDrawBuffers on the emulated default framebuffer.
    pub fn draw_buffers(self: &Arc<Self>, names: &[u32]) -> Result<()> {
        let mut st = self.current_state()?;
        // SAFETY: the application context is current (checked).
        let r = unsafe { st.fb.set_draw_buffers(&self.gl, names) };
        record_gl_error(&mut st, &r);
        r
    }

    /// glReadBuffer on the emulated default framebuffer.
    pub fn read_buffer(self: &Arc<Self>, name: u32) -> Result<()> {
        let mut st = self.current_state()?;
        // SAFETY: the application context is current (checked).
        let r = unsafe { st.fb.set_read_buffer(&self.gl, name) };
        record_gl_error(&mut st, &r);
        r
    }

    /// glLinkProgram with output 0 copied to the other selected buffers
    /// ([`crate::stereo::outputs`]; `gls_link_program`).
    pub fn link_program(self: &Arc<Self>, program: u32) -> Result<()> {
        let mut st = self.current_state()?;
        let gl = &self.gl;
        // SAFETY: the application context is current (checked).
        unsafe {
            // The program's pending error is kept for gls_get_error().
            let pending = gl.GetError();
            if st.pending_gl_error == GL_NO_ERROR {
                st.pending_gl_error = pending;
            }
            gl.LinkProgram(program);
            match gl.GetError() {
                GL_NO_ERROR => {}
                e => {
                    if st.pending_gl_error == GL_NO_ERROR {
                        st.pending_gl_error = e;
                    }
                    let what = format!("glLinkProgram({program}) raised GL error {e:#06x}");
                    return Err(if e == GL_INVALID_VALUE {
                        Error::invalid_value(format!("{what}: not a program name"))
                    } else {
                        Error::invalid_operation(format!("{what}: not a program object"))
                    });
                }
            }
            let Some(fns) = crate::stereo::outputs::LinkFns::load(|n| self.get_proc_address(n))
            else {
                return Err(Error::invalid_operation(
                    "the driver lacks GL 4.3 program interface queries: the program is linked \
                     once, and its output 0 reaches only the first selected buffer",
                ));
            };
            let outcome = fns.duplicate_output_zero(program, None);
            while gl.GetError() != GL_NO_ERROR {}
            match outcome {
                crate::stereo::outputs::Outcome::Kept(why) => {
                    Err(Error::invalid_operation(format!(
                        "{why}: program {program} is linked as glLinkProgram links it, and its \
                         output 0 reaches only the first selected buffer"
                    )))
                }
                _ => Ok(()),
            }
        }
    }

    /// The GL error glGetError would report: one the emulation raised
    /// first, else the driver's.
    pub fn take_gl_error(self: &Arc<Self>) -> Result<u32> {
        let mut st = self.current_state()?;
        let e = std::mem::replace(&mut st.pending_gl_error, GL_NO_ERROR);
        if e != GL_NO_ERROR {
            return Ok(e);
        }
        // SAFETY: the application context is current (checked).
        Ok(unsafe { self.gl.GetError() })
    }

    /// Emulated glGetIntegerv values of the default framebuffer, None for
    /// any other `pname` (or when the program has its own FBO bound).
    pub fn emulated_integer(self: &Arc<Self>, pname: u32) -> Result<Option<i32>> {
        Ok(self.emulated_integers([pname])?[0])
    }

    /// [`Surface::emulated_integer`] of several `pnames` at once (one lock,
    /// one look at the framebuffer bindings).
    pub fn emulated_integers<const N: usize>(
        self: &Arc<Self>,
        pnames: [u32; N],
    ) -> Result<[Option<i32>; N]> {
        let st = self.current_state()?;
        // SAFETY: the application context is current (checked).
        let (draw_fbo, read_fbo) = unsafe {
            (
                self.gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32,
                self.gl.integer(GL_READ_FRAMEBUFFER_BINDING) as u32,
            )
        };
        let ours = st.fb.app_fbo();
        let draw = Some(&st.fb).filter(|_| draw_fbo == ours);
        let read = Some(&st.fb).filter(|_| read_fbo == ours);
        Ok(pnames.map(|p| default_framebuffer_query(p, self.config.shape(), draw, read)))
    }

    /// glBindFramebuffer with 0 meaning the emulated default framebuffer.
    pub fn bind_framebuffer(self: &Arc<Self>, target: u32, framebuffer: u32) -> Result<()> {
        let st = self.current_state()?;
        let name = if framebuffer == 0 {
            st.fb.app_fbo()
        } else {
            framebuffer
        };
        // SAFETY: the application context is current (checked).
        unsafe { self.gl.BindFramebuffer(target, name) };
        Ok(())
    }

    /// Loads one eye's HP projection into GL_PROJECTION (the matrix mode is
    /// left as it was).
    pub fn load_projection(self: &Arc<Self>, column_major: &[f64; 16]) -> Result<()> {
        let _st = self.current_state()?;
        // SAFETY: the application context is current (checked).
        unsafe {
            let mode = self.gl.integer(GL_MATRIX_MODE) as u32;
            self.gl.MatrixMode(GL_PROJECTION);
            self.gl.LoadMatrixd(column_major.as_ptr());
            self.gl.MatrixMode(mode);
        }
        Ok(())
    }

    /// Presents the frame: each eye's back buffer becomes its front buffer
    /// (double-buffered configs; single-buffered ones just flush). On a
    /// surface with a window ([`PlatformSurface::drawable_size`] is Some),
    /// the new front buffers are then composed in the output mode into the
    /// window's framebuffer 0 in the compositor context (placed by
    /// [`crate::output::layout::window_fit`]), and `present()` is called
    /// with the compositor context still current — or, on a software
    /// renderer whose backend shows pixels from memory, the composite is
    /// written into the window directly
    /// ([`PlatformSurface::present_pixels`]; no GL pass, no `present()`).
    pub fn swap_buffers(self: &Arc<Self>) -> Result<()> {
        profile::frame_start(|| self.size());
        let shown = self.swap_and_show();
        profile::frame_end();
        shown
    }

    /// [`Surface::swap_buffers`], between the profile's frame marks.
    fn swap_and_show(self: &Arc<Self>) -> Result<()> {
        // Made current here just for the swap, the application context is
        // finished before it is released when the window reads its eyes in
        // place (when current here, with_compositor finishes it).
        let here = self.is_current_here();
        profile::span(Stage::Flip, || {
            self.with_app(|st| {
                // SAFETY: with_app made the application context current.
                unsafe {
                    st.fb.swap(&self.gl);
                    if here || !st.fb.holds_memory() {
                        self.gl.Flush();
                    } else {
                        self.gl.Finish();
                    }
                }
                st.frames += 1;
                Ok(())
            })
        })?;
        if let Some((width, height)) = self.platform.drawable_size() {
            let mode = self.effective_output();
            if here && self.present_in_place(mode, (width, height))? {
                return Ok(());
            }
            let shown = self.with_compositor_as(!here, |gl, st| {
                let resized = st.window != Some((width, height));
                let job = gl_job(st, mode);
                // A software renderer's frame goes to the window as pixels
                // when the backend shows them (GLX: MIT-SHM), skipping a
                // full-window GL pass (see GlCompositor::pixel_plan).
                if !resized && self.platform.accepts_pixels() {
                    // SAFETY: the compositor context is current.
                    let plan = unsafe { st.compositor.pixel_plan(gl, &job, width, height)? };
                    if let Some(plan) = plan {
                        let compositor = &mut st.compositor;
                        let shown = self.platform.present_pixels((width, height), &mut |t| {
                            // SAFETY: the compositor context is current; the
                            // job's textures are this surface's; the plan is
                            // for this job and the window's size.
                            unsafe { compositor.fill_pixels(gl, &job, plan, t, None) }
                        })?;
                        if shown {
                            return Ok(());
                        }
                    }
                }
                // SAFETY: with_compositor made the compositor context current;
                // the job's textures are this surface's.
                profile::span(Stage::GlCompose, || unsafe {
                    st.compositor.compose_window(gl, &job, 0, width, height)?;
                    self.platform.present()
                })?;
                if resized {
                    // Mesa's software GLX learns a drawable's new size only
                    // when the drawable is bound again after a swap: the
                    // frame just shown was cut to the old size, so rebind
                    // and show it again.
                    self.platform.release_current()?;
                    self.platform.make_current(ContextRole::Compositor)?;
                    // SAFETY: as above.
                    unsafe { st.compositor.compose_window(gl, &job, 0, width, height)? };
                    self.platform.present()?;
                    // A window resized (by its user or XResizeWindow) gets eye
                    // buffers to match by the next frame.
                    st.window = Some((width, height));
                    let (ew, eh) = eye_size_for_window(mode, width, height);
                    let (fw, fh) = st.framing.frame_size(ew, eh);
                    if (fw, fh) != st.fb.size() {
                        // SAFETY: the compositor context is current.
                        unsafe { st.fb.resize(gl, fw, fh)? };
                        if st.fb.holds_memory() {
                            // The clears of the new eyes land before the
                            // CPU reads them.
                            // SAFETY: as above.
                            unsafe { gl.Finish() };
                        }
                    }
                }
                Ok(())
            });
            // A resize replaced eye textures made from memory: the program
            // draws its next frame into the new ones.
            let reattached = self.reattach_replaced_eyes();
            return shown.and(reattached);
        }
        self.platform.present()
    }

    /// Shows the frame in the window as pixels composed on the CPU from
    /// eyes in memory, with the application context (current on this
    /// thread) left current: no GL call, so the compositor context is not
    /// made current (a make-current and back each frame). False, nothing
    /// shown, when the frame needs the compositor's GL: the window changed
    /// size, an eye is not in memory, the backend does not take pixels, or
    /// the renderer is not yet known to be software (the first frame).
    fn present_in_place(self: &Arc<Self>, mode: OutputMode, size: (u32, u32)) -> Result<bool> {
        if !self.platform.accepts_pixels() {
            return Ok(false);
        }
        // SAFETY: the application context is current on this thread (the
        // caller checked); the CPU reads its eyes once it has finished.
        profile::span(Stage::Finish, || unsafe { self.gl.Finish() });
        let _compositing = self.compositing.recover();
        let mut st = self.state.recover();
        if st.window != Some(size) {
            return Ok(false);
        }
        st.eyes_finished = true;
        let job = gl_job(&st, mode);
        st.eyes_finished = false;
        // SAFETY: finished above.
        let Some(plan) = (unsafe { st.compositor.in_place_plan(&job) }) else {
            return Ok(false);
        };
        let compositor = &mut st.compositor;
        self.platform.present_pixels(size, &mut |t| {
            // SAFETY: finished above; the eyes stay allocated while the
            // state is locked.
            unsafe { compositor.fill_in_place(&job, plan, t, None) }
        })
    }

    /// After a resize replaced eye textures made from memory
    /// ([`crate::stereo::eye_memory`]; their storage is immutable), attaches
    /// the new ones to the application context's framebuffer object, and
    /// frees the old memory once that context has finished with it.
    fn reattach_replaced_eyes(self: &Arc<Self>) -> Result<()> {
        if !self.state.recover().fb.attachments_stale() {
            return Ok(());
        }
        self.with_app(|st| {
            // SAFETY: with_app made the application context current; the
            // compositor context finished its work when it resized (and the
            // memory check before).
            unsafe {
                let reattached = st.fb.reattach_app(&self.gl);
                self.gl.Finish();
                st.fb.release_retired(&self.gl);
                reattached
            }
        })
    }

    /// Reads one colour buffer (glReadBuffer naming rules: GL_FRONT is
    /// front-left, GL_RIGHT front-right, …), rows top first.
    pub fn read_pixels(self: &Arc<Self>, name: u32) -> Result<Image> {
        let buffer = resolve_read_buffer(self.config.shape(), name)?
            .ok_or_else(|| Error::invalid_operation("GL_NONE names no buffer to read"))?;
        self.read_color_buffer(buffer)
    }

    fn read_color_buffer(self: &Arc<Self>, buffer: ColorBuffer) -> Result<Image> {
        let mut img = self.with_compositor(|gl, st| {
            let (w, h) = st.fb.size();
            let mut img = Image::try_new(w, h)?;
            // SAFETY: the compositor context is current; the image has w×h×4 bytes.
            unsafe { read_eye(gl, st, buffer, img.pixels_mut())? };
            Ok(img)
        })?;
        if self.config.request.color[3] == 0 {
            // GL reads alpha as 1.0 from a framebuffer without alpha bits.
            img.make_opaque();
        }
        Ok(img)
    }

    /// Reads the depth buffer both eyes share (it holds what was drawn
    /// last) as window depths, rows bottom first. The program's rendering
    /// is finished first when the surface is current on this thread.
    pub fn read_depth(self: &Arc<Self>) -> Result<crate::analysis::DepthImage> {
        if self.config.depth_bits == 0 {
            return Err(Error::invalid_operation(
                "this surface has no depth buffer: choose a configuration with GLX_DEPTH_SIZE",
            ));
        }
        self.with_compositor(|gl, st| {
            let (w, h) = st.fb.size();
            let mut values = crate::image::try_vec(w as usize * h as usize, 0f32, "a depth image")?;
            // SAFETY: the compositor context is current; `values` has w×h entries.
            unsafe { st.fb.read_depth(gl, &mut values)? };
            crate::analysis::DepthImage::new(w, h, values)
        })
    }

    /// The two eyes as they are displayed now, taken apart from the front
    /// buffers by the surface's input framing (a mono surface in the
    /// quad-buffer framing shows its one image to both eyes).
    pub fn eye_images(self: &Arc<Self>) -> Result<(Image, Image)> {
        let (framing, shape, (w, h)) = {
            let st = self.state.recover();
            (st.framing, st.fb.shape(), st.fb.size())
        };
        let [ls, rs] = framing.sources(shape, w, h);
        let left_buf = self.read_color_buffer(ls.buffer)?;
        let right_buf = if rs.buffer == ls.buffer {
            None
        } else {
            Some(self.read_color_buffer(rs.buffer)?)
        };
        // An eye that is a whole buffer is that buffer as displayed (opaque,
        // as `extract` makes it); only rectangles are taken apart.
        let whole = |s: &EyeSource| (s.x, s.y, s.width, s.height) == (0, 0, w, h);
        let opaque = |mut img: Image| {
            img.make_opaque();
            img
        };
        let right = match right_buf {
            Some(buf) if whole(&rs) => opaque(buf),
            Some(buf) => framing.extract(&rs, &buf),
            None if whole(&rs) => opaque(left_buf.try_clone()?),
            None => framing.extract(&rs, &left_buf),
        };
        let left = if whole(&ls) {
            opaque(left_buf)
        } else {
            framing.extract(&ls, &left_buf)
        };
        Ok((left, right))
    }

    /// The output mode as set (`quad` included).
    pub fn output(&self) -> OutputMode {
        self.state.recover().output
    }

    /// The mode the composite is made in: the output mode, except that
    /// `quad` on a surface without native stereo falls back to
    /// [`DEFAULT_OUTPUT`] (anaglyph-red-cyan).
    pub fn effective_output(&self) -> OutputMode {
        effective_mode(self.output(), &self.config)
    }

    /// Sets the output mode.
    ///
    /// A window is resized to the new mode's composite of the current eyes
    /// (e.g. twice as wide for `side-by-side`), so it stays pixel for pixel.
    pub fn set_output(&self, mode: OutputMode) -> Result<()> {
        self.state.recover().output = mode;
        self.fit_window()
    }

    /// The window size that shows the composite of the current eyes pixel
    /// for pixel.
    fn window_size_for(&self, st: &SurfaceState) -> (u32, u32) {
        let (fw, fh) = st.fb.size();
        let (ew, eh) = st.framing.eye_size(fw, fh);
        composite_size(effective_mode(st.output, &self.config), ew, eh)
    }

    /// Resizes a window to show the composite pixel for pixel (after the
    /// output mode or the input framing changed); nothing headless.
    fn fit_window(&self) -> Result<()> {
        if self.platform.drawable_size().is_none() {
            return Ok(());
        }
        let (w, h) = self.window_size_for(&self.state.recover());
        check_size(w, h)?;
        // The next swap sees the new size, rebinds the drawable and keeps
        // the eyes (they already match the new composite).
        self.platform.resize_window(w, h)
    }

    /// The next event of the surface's window (keys, close requests, resizes
    /// with the new eye size); None when there is none or no window.
    pub fn next_event(&self) -> Option<WindowEvent> {
        match self.platform.next_event()? {
            WindowEvent::Resized(w, h) => {
                let (ew, eh) = eye_size_for_window(self.effective_output(), w, h);
                Some(WindowEvent::Resized(ew, eh))
            }
            e => Some(e),
        }
    }

    /// Whether the user asked to close the surface's window.
    pub fn close_requested(&self) -> bool {
        self.platform.close_requested()
    }

    /// Sets the window title (no effect headless).
    pub fn set_title(&self, title: &str) -> Result<()> {
        self.platform.set_title(title)
    }

    /// The backend's own handles of this surface.
    pub fn native_handles(&self) -> crate::backend::NativeHandles {
        self.platform.native_handles()
    }

    /// The output options.
    pub fn options(&self) -> OutputOptions {
        self.state.recover().options
    }

    /// Sets the output options (validated first; on error nothing changes).
    pub fn set_options(&self, options: OutputOptions) -> Result<()> {
        let options = options.validated()?;
        self.state.recover().options = options;
        Ok(())
    }

    /// The input framing.
    pub fn framing(&self) -> InputFraming {
        self.state.recover().framing
    }

    /// Sets how the program delivers its eyes (checked against the size).
    pub fn set_framing(&self, framing: InputFraming) -> Result<()> {
        let mut st = self.state.recover();
        let (w, h) = st.fb.size();
        framing.check(st.fb.shape(), w, h)?;
        st.framing = framing;
        drop(st);
        self.fit_window()
    }

    /// The composite in the surface's output mode, as a viewer sees it now.
    /// For `frame-sequential`, the frame presented last (the first swap is
    /// frame 0, the left eye). Made the faster way for this renderer, mode
    /// and options ([`crate::output::gl::preferred_path`]).
    pub fn composite_image(self: &Arc<Self>) -> Result<Image> {
        self.composite(None)
    }

    /// [`Surface::composite_image`] made a given way: both ways give the
    /// same image within 1 unit per channel (the GL way falls back to the
    /// CPU for a composite larger than the driver renders).
    pub fn composite_image_via(self: &Arc<Self>, path: ComposePath) -> Result<Image> {
        self.composite(Some(path))
    }

    fn composite(self: &Arc<Self>, path: Option<ComposePath>) -> Result<Image> {
        let mode = self.effective_output();
        if path != Some(ComposePath::Cpu) {
            let on_gl = self.with_compositor(|gl, st| {
                let job = gl_job(st, mode);
                let c = &mut st.compositor;
                // SAFETY: with_compositor made the compositor context
                // current; the job's textures are this surface's.
                unsafe {
                    let (w, h) = job.eye_size;
                    let (cw, ch) = crate::output::composite_size(mode, w, h);
                    let fits = cw <= c.max_side(gl) && ch <= c.max_side(gl);
                    let chosen = path
                        .unwrap_or_else(|| preferred_path(c.cpu_device(gl), mode, &job.options));
                    if !fits || chosen == ComposePath::Cpu {
                        return Ok(None);
                    }
                    let (cw, ch) = c.compose_capture(gl, &job)?;
                    let mut img = Image::try_new(cw, ch)?;
                    c.read_capture(gl, &mut img)?;
                    Ok(Some(img))
                }
            })?;
            if let Some(img) = on_gl {
                return Ok(img);
            }
        }
        self.composite_image_cpu()
    }

    fn composite_image_cpu(self: &Arc<Self>) -> Result<Image> {
        let (left, right) = self.eye_images()?;
        let (options, frames) = {
            let st = self.state.recover();
            (st.options, st.frames)
        };
        cpu::compose(
            self.effective_output(),
            &options,
            &left,
            &right,
            frames.saturating_sub(1),
        )
    }

    /// Writes one of the images a viewer sees now to a PNG file
    /// (atomically). A display shows no alpha, so neither does the file.
    pub fn save_png(self: &Arc<Self>, which: CaptureImage, path: &std::path::Path) -> Result<()> {
        // One read-back for an eye (not both), no extra copies (captures.rs).
        let mut img = Image::new(1, 1);
        self.capture_into(which, &mut img)?;
        crate::capture::write_png(&img, path)
    }

    // --- NV_3dvision_settings hooks (logic in shims::nv3dvision, framing::auto) ---

    /// Makes this surface auto-stereo capable (EGL_NV_3dvision_surface):
    /// called once, at creation, by [`crate::framing::auto::create_surface`].
    pub(crate) fn make_auto_stereo_capable(&self) {
        self.state.recover().nv3dvision = StereoSettings::new(true);
    }

    /// A copy of this surface's NV_3dvision_settings state (any thread).
    pub fn nv3dvision(&self) -> StereoSettings {
        self.state.recover().nv3dvision
    }

    /// Runs `f` on this surface's NV_3dvision_settings state (this surface
    /// must be current here). A failure of `f` is also queued as the
    /// matching GL error for [`Surface::take_gl_error`].
    pub fn with_nv3dvision<T>(
        self: &Arc<Self>,
        f: impl FnOnce(&mut StereoSettings) -> Result<T>,
    ) -> Result<T> {
        let mut st = self.current_state()?;
        let r = f(&mut st.nv3dvision);
        if let Err(e) = &r {
            record_gl_error(&mut st, &Err(e.clone()));
        }
        r
    }

    /// Releases this surface if it is current on the calling thread.
    pub(crate) fn release_if_current(self: &Arc<Self>) {
        if self.is_current_here() {
            let _ = make_current(None);
        }
    }
}

/// Which image a capture writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CaptureImage {
    /// The left eye's front buffer.
    Left,
    /// The right eye's front buffer (the left one on a mono surface).
    Right,
    /// Both eyes composed in the surface's output mode.
    Composite,
}

/// The GL compositor's job for the front buffers as they are now. Eyes
/// are read in place only when the application's rendering is finished
/// ([`SurfaceState::eyes_finished`]).
fn gl_job(st: &SurfaceState, mode: OutputMode) -> Job {
    let mut job = Job::front_buffers(
        &st.fb,
        st.framing,
        mode,
        st.options,
        st.frames.saturating_sub(1),
    );
    if !st.eyes_finished {
        job.in_place = [None; 2];
    }
    job
}

/// The mode a composite is made in: `quad` falls back to [`DEFAULT_OUTPUT`]
/// on a configuration without native stereo.
fn effective_mode(mode: OutputMode, config: &Config) -> OutputMode {
    match mode {
        OutputMode::Quad if config.stereo != StereoKind::Native => DEFAULT_OUTPUT,
        m => m,
    }
}

/// Reads colour buffer `buffer` into `out` (RGBA8, rows top first): from
/// where the driver drew it when it is in place and the application's
/// rendering is finished ([`SurfaceState::eyes_finished`]; one copy that
/// also flips the rows), else by glReadPixels.
///
/// # Safety
/// The compositor context is current; `out` holds width × height × 4 bytes.
unsafe fn read_eye(gl: &Gl, st: &SurfaceState, buffer: ColorBuffer, out: &mut [u8]) -> Result<()> {
    let (w, h) = st.fb.size();
    let placed = st.fb.pixels(buffer).filter(|_| st.eyes_finished);
    // SAFETY: finished (checked), and used before any resize or release
    // (the state is locked).
    if let Some(rows) = placed.as_ref().and_then(|p| unsafe { p.rect(0, 0, w, h) }) {
        profile::span(Stage::ReadBack, || rows.copy_to(out, true));
        return Ok(());
    }
    // SAFETY: contract.
    profile::span(Stage::ReadBack, || unsafe {
        st.fb.read_pixels(gl, buffer, out)
    })
}

fn record_gl_error(st: &mut SurfaceState, r: &Result<()>) {
    if let Err(e) = r {
        if st.pending_gl_error == GL_NO_ERROR {
            st.pending_gl_error = gl_error_code(e);
        }
    }
}

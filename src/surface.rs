//! Surfaces: an emulated stereo default framebuffer with its two contexts,
//! and the per-thread notion of the current surface.
//!
//! GL's rule holds: a surface's application context is current on at most
//! one thread at a time, and each thread has at most one current surface.

use std::cell::RefCell;
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::ThreadId;

use crate::backend::{ContextRole, PlatformSurface};
use crate::config::{Config, StereoKind};
use crate::display::Display;
use crate::error::{Error, Result};
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::image::{Image, check_size};
use crate::shims::nv3dvision::StereoSettings;
use crate::stereo::buffers::{ColorBuffer, resolve_read_buffer};
use crate::stereo::emulated::EmulatedFramebuffer;

thread_local! {
    /// The surface current on this thread and which of its contexts.
    static CURRENT: RefCell<Option<(Arc<Surface>, ContextRole)>> = const { RefCell::new(None) };
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
            *p.owner.lock().unwrap() = None;
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
        let owner = s.owner.lock().unwrap();
        if owner.is_some_and(|t| t != me) {
            return Err(Error::invalid_operation(
                "this surface is current on another thread: release it there first (gls_make_current(NULL))",
            ));
        }
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
    if let Some((p, _)) = &prev {
        if !Arc::ptr_eq(p, s) {
            *p.owner.lock().unwrap() = None;
        }
    }
    *s.owner.lock().unwrap() = Some(me);
    CURRENT.with(|c| *c.borrow_mut() = Some((s.clone(), ContextRole::App)));
    let mut st = s.state.lock().unwrap();
    if st.fb.app_fbo() == 0 {
        // SAFETY: the application context was just made current.
        if let Err(e) = unsafe { st.fb.attach_app(&s.gl) } {
            drop(st);
            let _ = make_current(None);
            return Err(e);
        }
    }
    Ok(())
}

/// The mutable state of a surface.
struct SurfaceState {
    fb: EmulatedFramebuffer,
    /// Swaps so far.
    frames: u64,
    /// A GL error the emulation raised, reported by the next get_error().
    pending_gl_error: u32,
    /// NV_3dvision_settings state (src/shims/nv3dvision.rs).
    nv3dvision: StereoSettings,
}

/// A stereo (or mono) surface: emulated default framebuffer, two contexts.
pub struct Surface {
    display: Arc<Display>,
    config: Config,
    platform: Box<dyn PlatformSurface>,
    gl: Arc<Gl>,
    owner: Mutex<Option<ThreadId>>,
    state: Mutex<SurfaceState>,
}

impl std::fmt::Debug for Surface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (w, h) = self.size();
        write!(f, "Surface({w}x{h}, {:?})", self.config.stereo)
    }
}

/// Runs `f` with `platform`'s compositor context current, then puts back
/// whatever was current on this thread before.
fn with_compositor_of<T>(
    platform: &dyn PlatformSurface,
    f: impl FnOnce() -> Result<T>,
) -> Result<T> {
    let saved = CURRENT.with(|c| c.borrow().clone());
    platform.make_current(ContextRole::Compositor)?;
    let result = f();
    let restored = match &saved {
        Some((p, role)) => p.platform.make_current(*role),
        None => platform.release_current(),
    };
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
        if config.stereo == StereoKind::Native {
            return Err(Error::invalid_operation(
                "native stereo configurations need a window: use the GLX backend",
            ));
        }
        let platform = display.platform().create_surface(&config, width, height)?;
        let shape = config.shape();
        let (fb, gl) = with_compositor_of(&*platform, || {
            let gl = display.gl()?;
            // SAFETY: the compositor context is current.
            let fb = unsafe {
                EmulatedFramebuffer::allocate(
                    &gl,
                    shape,
                    width,
                    height,
                    config.depth_bits,
                    config.stencil_bits,
                )?
            };
            Ok((fb, gl))
        })?;
        Ok(Arc::new(Surface {
            display,
            config,
            platform,
            gl,
            owner: Mutex::new(None),
            state: Mutex::new(SurfaceState {
                fb,
                frames: 0,
                pending_gl_error: GL_NO_ERROR,
                nv3dvision: StereoSettings::new(false),
            }),
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
        self.state.lock().unwrap().fb.size()
    }

    /// Swaps so far.
    pub fn frames(&self) -> u64 {
        self.state.lock().unwrap().frames
    }

    fn is_current_here(self: &Arc<Self>) -> bool {
        current().is_some_and(|c| Arc::ptr_eq(&c, self))
    }

    /// The state, for a call that needs this surface current on this thread.
    fn current_state(self: &Arc<Self>) -> Result<MutexGuard<'_, SurfaceState>> {
        if !self.is_current_here() {
            return Err(Error::NoCurrentSurface);
        }
        Ok(self.state.lock().unwrap())
    }

    /// Runs `f` in the application context: directly when this surface is
    /// current here, else by making it current for the call and restoring
    /// the thread's previous surface. Fails if it is current on another thread.
    fn with_app<T>(self: &Arc<Self>, f: impl FnOnce(&mut SurfaceState) -> Result<T>) -> Result<T> {
        if self.is_current_here() {
            return f(&mut self.state.lock().unwrap());
        }
        let prev = current();
        make_current(Some(self))?;
        let r = f(&mut self.state.lock().unwrap());
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
        if self.is_current_here() {
            // SAFETY: the application context is current; objects it renders
            // to are only guaranteed visible to another context after Finish.
            unsafe { self.gl.Finish() };
        }
        with_compositor_of(&*self.platform, || {
            f(&self.gl, &mut self.state.lock().unwrap())
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
        let st = self.current_state()?;
        // SAFETY: the application context is current (checked).
        let (draw_fbo, read_fbo) = unsafe {
            (
                self.gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32,
                self.gl.integer(GL_READ_FRAMEBUFFER_BINDING) as u32,
            )
        };
        let ours = st.fb.app_fbo();
        Ok(match pname {
            GL_STEREO => Some((self.config.stereo != StereoKind::None) as i32),
            GL_DOUBLEBUFFER => Some(self.config.request.double_buffer as i32),
            GL_DRAW_FRAMEBUFFER_BINDING if draw_fbo == ours => Some(0),
            GL_READ_FRAMEBUFFER_BINDING if read_fbo == ours => Some(0),
            GL_DRAW_BUFFER if draw_fbo == ours => Some(st.fb.draw_buffer_query(0) as i32),
            p if (GL_DRAW_BUFFER0..=GL_DRAW_BUFFER15).contains(&p) && draw_fbo == ours => {
                Some(st.fb.draw_buffer_query((p - GL_DRAW_BUFFER0) as usize) as i32)
            }
            GL_READ_BUFFER if read_fbo == ours => Some(st.fb.read_buffer_query() as i32),
            _ => None,
        })
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
    /// (double-buffered configs; single-buffered ones just flush).
    pub fn swap_buffers(self: &Arc<Self>) -> Result<()> {
        self.with_app(|st| {
            // SAFETY: with_app made the application context current.
            unsafe {
                st.fb.swap(&self.gl);
                self.gl.Flush();
            }
            st.frames += 1;
            Ok(())
        })?;
        self.platform.present()
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
            let mut img = Image::new(w, h);
            // SAFETY: the compositor context is current; the image has w×h×4 bytes.
            unsafe { st.fb.read_pixels(gl, buffer, img.pixels_mut())? };
            Ok(img)
        })?;
        if self.config.request.color[3] == 0 {
            // GL reads alpha as 1.0 from a framebuffer without alpha bits.
            set_opaque(&mut img);
        }
        Ok(img)
    }

    /// The two eyes as they are displayed now (the front buffers); a mono
    /// surface shows its one image to both eyes.
    pub fn eye_images(self: &Arc<Self>) -> Result<(Image, Image)> {
        let left = self.read_color_buffer(ColorBuffer::FrontLeft)?;
        let right = if self.config.shape().stereo {
            self.read_color_buffer(ColorBuffer::FrontRight)?
        } else {
            left.clone()
        };
        Ok((left, right))
    }

    /// The composite in the surface's output mode, as a viewer sees it now.
    pub fn composite_image(self: &Arc<Self>) -> Result<Image> {
        let (left, right) = self.eye_images()?;
        Ok(red_cyan(&left, &right))
    }

    /// Writes one of the images a viewer sees now to a PNG file
    /// (atomically). A display shows no alpha, so neither does the file.
    pub fn save_png(self: &Arc<Self>, which: CaptureImage, path: &std::path::Path) -> Result<()> {
        let mut img = match which {
            CaptureImage::Left => self.eye_images()?.0,
            CaptureImage::Right => self.eye_images()?.1,
            CaptureImage::Composite => self.composite_image()?,
        };
        set_opaque(&mut img);
        crate::capture::write_png(&img, path)
    }

    // --- NV_3dvision_settings hooks (logic in shims::nv3dvision, framing::auto) ---

    /// Makes this surface auto-stereo capable (EGL_NV_3dvision_surface):
    /// called once, at creation, by [`crate::framing::auto::create_surface`].
    pub(crate) fn make_auto_stereo_capable(&self) {
        self.state.lock().unwrap().nv3dvision = StereoSettings::new(true);
    }

    /// A copy of this surface's NV_3dvision_settings state (any thread).
    pub fn nv3dvision(&self) -> StereoSettings {
        self.state.lock().unwrap().nv3dvision
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

fn set_opaque(img: &mut Image) {
    for px in img.pixels_mut().chunks_exact_mut(4) {
        px[3] = 255;
    }
}

/// Interim composite until the output formats land: a full-colour red-cyan
/// anaglyph (R from the left eye, G and B from the right).
fn red_cyan(left: &Image, right: &Image) -> Image {
    let mut out = right.clone();
    for (o, l) in out
        .pixels_mut()
        .chunks_exact_mut(4)
        .zip(left.pixels().chunks_exact(4))
    {
        o[0] = l[0];
        o[3] = 255;
    }
    out
}

fn record_gl_error(st: &mut SurfaceState, r: &Result<()>) {
    if let Err(e) = r {
        let code = match e {
            Error::InvalidEnum { .. } => GL_INVALID_ENUM,
            Error::InvalidValue(_) => GL_INVALID_VALUE,
            _ => GL_INVALID_OPERATION,
        };
        if st.pending_gl_error == GL_NO_ERROR {
            st.pending_gl_error = code;
        }
    }
}

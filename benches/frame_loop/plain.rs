//! The mono program: a plain GL program with no glstereo in its frame.
//!
//! Contexts and windows are made directly with EGL, OSMesa and GLX (the
//! same calls any program makes). Headless (EGL surfaceless, OSMesa), the
//! "default framebuffer" is a framebuffer object of the surface's size with
//! one RGBA8 colour texture and a D24S8 renderbuffer, as glstereo's own
//! eye buffers are; on GLX it is the window's double-buffered framebuffer 0,
//! shown by glXSwapBuffers.

use std::ffi::{CStr, CString, c_int, c_uint, c_void};

use glstereo::gl::Gl;
use glstereo::gl::enums::*;
use khronos_egl as egl;
use x11_dl::glx::{self, Glx};
use x11_dl::xlib::{self, Xlib};

const EGL_PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;

/// A plain context (and, for GLX, its window).
#[allow(clippy::large_enum_variant)] // one per process
pub enum Plain {
    Egl {
        egl: egl::DynamicInstance<egl::EGL1_5>,
        display: egl::Display,
        context: egl::Context,
    },
    OsMesa {
        _lib: libloading::Library,
        make_current: unsafe extern "C" fn(*mut c_void, *mut c_void, c_uint, c_int, c_int) -> u8,
        get_proc: unsafe extern "C" fn(*const std::ffi::c_char) -> *const c_void,
        context: *mut c_void,
        buffer: Box<[u8; 4]>,
    },
    Glx {
        xlib: Xlib,
        glx: Glx,
        display: *mut xlib::Display,
        window: xlib::Window,
        context: glx::GLXContext,
    },
}

impl Plain {
    pub fn egl() -> Plain {
        // SAFETY: loads libEGL; plain EGL calls with valid arguments.
        unsafe {
            let egl = egl::DynamicInstance::<egl::EGL1_5>::load_required().expect("libEGL");
            let display = egl
                .get_platform_display(
                    EGL_PLATFORM_SURFACELESS_MESA,
                    egl::DEFAULT_DISPLAY,
                    &[egl::ATTRIB_NONE],
                )
                .expect("surfaceless display");
            egl.initialize(display).expect("eglInitialize");
            egl.bind_api(egl::OPENGL_API).expect("eglBindAPI");
            let config = egl
                .choose_first_config(
                    display,
                    &[
                        egl::RENDERABLE_TYPE,
                        egl::OPENGL_BIT,
                        egl::SURFACE_TYPE,
                        0,
                        egl::NONE,
                    ],
                )
                .expect("eglChooseConfig")
                .expect("an OpenGL config");
            let context = egl
                .create_context(
                    display,
                    config,
                    None,
                    &[
                        egl::CONTEXT_MAJOR_VERSION,
                        4,
                        egl::CONTEXT_MINOR_VERSION,
                        5,
                        egl::CONTEXT_OPENGL_PROFILE_MASK,
                        egl::CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
                        egl::NONE,
                    ],
                )
                .expect("eglCreateContext");
            Plain::Egl {
                egl,
                display,
                context,
            }
        }
    }

    pub fn osmesa() -> Plain {
        // SAFETY: loads libOSMesa; the symbols have these C signatures.
        unsafe {
            let lib = libloading::Library::new("libOSMesa.so.8").expect("libOSMesa.so.8");
            let create: unsafe extern "C" fn(*const c_int, *mut c_void) -> *mut c_void =
                *lib.get(b"OSMesaCreateContextAttribs").unwrap();
            let make_current = *lib.get(b"OSMesaMakeCurrent").unwrap();
            let get_proc = *lib.get(b"OSMesaGetProcAddress").unwrap();
            // OSMESA_FORMAT RGBA, no depth (rendering goes to the FBO),
            // compatibility profile 4.5.
            let attribs = [
                0x22, 0x1908, 0x30, 0, 0x31, 0, 0x33, 0x35, 0x36, 4, 0x37, 5, 0,
            ];
            let context = create(attribs.as_ptr(), std::ptr::null_mut());
            assert!(!context.is_null(), "OSMesaCreateContextAttribs");
            Plain::OsMesa {
                _lib: lib,
                make_current,
                get_proc,
                context,
                buffer: Box::new([0; 4]),
            }
        }
    }

    /// A double-buffered RGB window with a 24-bit depth buffer at (x, 0).
    pub fn glx(display_name: &str, x: i32, width: u32, height: u32) -> Plain {
        let xl = Xlib::open().expect("libX11");
        let gx = Glx::open().expect("libGL");
        let name = CString::new(display_name).unwrap();
        // SAFETY: plain Xlib/GLX calls on a connection opened here.
        unsafe {
            let display = (xl.XOpenDisplay)(name.as_ptr());
            assert!(!display.is_null(), "cannot open {display_name}");
            let screen = (xl.XDefaultScreen)(display);
            let mut attribs = [
                glx::GLX_RGBA,
                glx::GLX_DOUBLEBUFFER,
                glx::GLX_RED_SIZE,
                8,
                glx::GLX_GREEN_SIZE,
                8,
                glx::GLX_BLUE_SIZE,
                8,
                glx::GLX_DEPTH_SIZE,
                24,
                0,
            ];
            let vi = (gx.glXChooseVisual)(display, screen, attribs.as_mut_ptr());
            assert!(!vi.is_null(), "glXChooseVisual");
            let root = (xl.XRootWindow)(display, screen);
            let mut wa: xlib::XSetWindowAttributes = std::mem::zeroed();
            wa.colormap = (xl.XCreateColormap)(display, root, (*vi).visual, xlib::AllocNone);
            let window = (xl.XCreateWindow)(
                display,
                root,
                x,
                0,
                width,
                height,
                0,
                (*vi).depth,
                xlib::InputOutput as u32,
                (*vi).visual,
                xlib::CWColormap | xlib::CWBorderPixel,
                &mut wa,
            );
            (xl.XMapWindow)(display, window);
            (xl.XSync)(display, xlib::False);
            let context = (gx.glXCreateContext)(display, vi, std::ptr::null_mut(), xlib::True);
            assert!(!context.is_null(), "glXCreateContext");
            (xl.XFree)(vi.cast());
            Plain::Glx {
                xlib: xl,
                glx: gx,
                display,
                window,
                context,
            }
        }
    }

    pub fn make_current(&self) {
        // SAFETY: live handles made above.
        unsafe {
            match self {
                Plain::Egl {
                    egl,
                    display,
                    context,
                } => {
                    egl.bind_api(egl::OPENGL_API).unwrap();
                    egl.make_current(*display, None, None, Some(*context))
                        .expect("eglMakeCurrent");
                }
                Plain::OsMesa {
                    make_current,
                    context,
                    buffer,
                    ..
                } => {
                    let ok = make_current(*context, buffer.as_ptr() as *mut c_void, 0x1401, 1, 1);
                    assert!(ok != 0, "OSMesaMakeCurrent");
                }
                Plain::Glx {
                    glx,
                    display,
                    window,
                    context,
                    ..
                } => {
                    assert!(
                        (glx.glXMakeCurrent)(*display, *window, *context) != 0,
                        "glXMakeCurrent"
                    );
                }
            }
        }
    }

    pub fn get_proc_address(&self, name: &CStr) -> *const c_void {
        // SAFETY: NUL-terminated names.
        unsafe {
            match self {
                Plain::Egl { egl, .. } => egl
                    .get_proc_address(name.to_str().unwrap())
                    .map_or(std::ptr::null(), |f| f as *const c_void),
                Plain::OsMesa { get_proc, .. } => get_proc(name.as_ptr()),
                Plain::Glx { glx, .. } => (glx.glXGetProcAddressARB)(name.as_ptr().cast())
                    .map_or(std::ptr::null(), |f| f as *const c_void),
            }
        }
    }

    /// Whether frames are shown in a window (else rendered to an FBO).
    pub fn has_window(&self) -> bool {
        matches!(self, Plain::Glx { .. })
    }

    /// Ends a frame the way a plain program does: glXSwapBuffers in a
    /// window; nothing headless (the benchmark's glFinish follows).
    pub fn swap(&self) {
        if let Plain::Glx {
            glx,
            display,
            window,
            ..
        } = self
        {
            // SAFETY: live display and window; this context is current.
            unsafe { (glx.glXSwapBuffers)(*display, *window) };
        }
    }

    /// Makes the stand-in default framebuffer of a headless program: an FBO
    /// with an RGBA8 texture and a D24S8 renderbuffer (bound for drawing).
    ///
    /// # Safety
    /// This context must be current and `gl` belong to it.
    pub unsafe fn default_framebuffer(&self, gl: &Gl, width: u32, height: u32) -> u32 {
        if self.has_window() {
            return 0;
        }
        let (mut fbo, mut tex, mut rb) = (0, 0, 0);
        // SAFETY: contract.
        unsafe {
            gl.GenFramebuffers(1, &mut fbo);
            gl.GenTextures(1, &mut tex);
            gl.GenRenderbuffers(1, &mut rb);
            gl.BindTexture(GL_TEXTURE_2D, tex);
            gl.TexImage2D(
                GL_TEXTURE_2D,
                0,
                GL_RGBA8 as i32,
                width as i32,
                height as i32,
                0,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                std::ptr::null(),
            );
            gl.BindRenderbuffer(GL_RENDERBUFFER, rb);
            gl.RenderbufferStorage(
                GL_RENDERBUFFER,
                GL_DEPTH24_STENCIL8,
                width as i32,
                height as i32,
            );
            gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
            gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
            gl.FramebufferRenderbuffer(
                GL_FRAMEBUFFER,
                GL_DEPTH_STENCIL_ATTACHMENT,
                GL_RENDERBUFFER,
                rb,
            );
            let mut tex2 = 0;
            gl.GenTextures(1, &mut tex2);
            gl.BindTexture(GL_TEXTURE_2D, tex2);
            gl.TexImage2D(
                GL_TEXTURE_2D,
                0,
                GL_RGBA8 as i32,
                width as i32,
                height as i32,
                0,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                std::ptr::null(),
            );
            gl.FramebufferTexture2D(
                GL_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0 + 1,
                GL_TEXTURE_2D,
                tex2,
                0,
            );
            assert_eq!(
                gl.CheckFramebufferStatus(GL_FRAMEBUFFER),
                GL_FRAMEBUFFER_COMPLETE
            );
        }
        fbo
    }
}

impl Drop for Plain {
    fn drop(&mut self) {
        // SAFETY: handles made above; released before destroyed.
        unsafe {
            match self {
                Plain::Egl {
                    egl,
                    display,
                    context,
                } => {
                    let _ = egl.make_current(*display, None, None, None);
                    let _ = egl.destroy_context(*display, *context);
                }
                Plain::OsMesa { .. } => {}
                Plain::Glx {
                    xlib,
                    glx,
                    display,
                    window,
                    context,
                } => {
                    (glx.glXMakeCurrent)(*display, 0, std::ptr::null_mut());
                    (glx.glXDestroyContext)(*display, *context);
                    (xlib.XDestroyWindow)(*display, *window);
                    (xlib.XCloseDisplay)(*display);
                }
            }
        }
    }
}

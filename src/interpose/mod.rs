//! Stereo for unmodified GLX programs: the logic behind the LD_PRELOAD
//! library (`libglstereo_preload.so`, run by `glstereo-run`) and behind the
//! `gls_glx_*` / `gls_gl_*` functions that `<glstereo/compat.h>` maps the
//! legacy names to in programs rebuilt from source. One implementation
//! serves both; the C entry points are in [`crate::ffi::interpose`].
//!
//! # What a legacy program does, and what it gets
//!
//! The program asks for a stereo visual (glXChooseVisual with GLX_STEREO,
//! glXChooseFBConfig with GLX_STEREO True, GLUT_STEREO), creates a context
//! and a window with it, draws each eye with glDrawBuffer(GL_BACK_LEFT /
//! GL_BACK_RIGHT) and swaps once (seed 000 §3–4). Mesa has no stereo
//! visual, so:
//!
//! - the stereo request is answered with the matching mono visual or
//!   configuration, remembered as stereo ([`registry`]); glXGetConfig and
//!   glXGetFBConfigAttrib report GLX_STEREO true for it;
//! - a context created from it is a *stereo context* ([`context`]): the
//!   first time it is made current on a drawable, the layer makes that
//!   drawable's emulated default framebuffer — the four colour buffers and
//!   the shared depth/stencil buffer of [`crate::stereo::emulated`], sized
//!   to the drawable and resized with it — and binds it in the program's
//!   context wherever the program has framebuffer 0. Those buffers live
//!   as long as the drawable: the GLX destroy functions free them in every
//!   context (a drawable current somewhere when its context is released),
//!   and a window destroyed behind GLX's back (XDestroyWindow, its parent,
//!   xcb, another client) is found gone the next time the context is made
//!   current on a new drawable ([`context::StereoContext::drawable_destroyed`]);
//! - GL calls about the default framebuffer are answered as a stereo
//!   visual would ([`gl`]), with the exact GL errors of
//!   [`crate::stereo::buffers`]; so are glClearBuffer and GL 4.5 direct
//!   state access on framebuffer 0, and programs are linked so that a
//!   shader's output 0 reaches every buffer a name such as GL_BACK selects
//!   ([`dsa`], [`crate::stereo::outputs`]), program binaries included
//!   ([`binaries`]);
//! - glXSwapBuffers flips back and front buffers and shows the front
//!   buffers composed in GLSTEREO_MODE (default anaglyph-red-cyan) in the
//!   window ([`context::StereoContext::present`]), and, with
//!   GLSTEREO_CAPTURE_DIR, writes each frame's eyes and composite
//!   ([`capture`]).
//!
//! A program that never asks for stereo runs as it would without the
//! layer: its calls go to the real libGL after one registry look-up per
//! GLX call and one thread-local test per interposed GL call; no object is
//! made and no GL call added.
//!
//! # Where the composite is drawn, and why a context of the layer's own
//!
//! Presenting draws the eyes into the window's real back buffer with
//! shaders, a vertex array, textures and framebuffer objects. Doing that in
//! the program's context would mean saving and restoring every piece of
//! state a draw depends on (program, vertex array, texture units and
//! samplers, viewport, scissor, blending, depth/stencil, colour masks,
//! sRGB, rasterizer discard, alpha test and clip planes of the
//! compatibility profile, transform feedback, conditional rendering, pixel
//! store…), and a core-profile program has no glPushAttrib to help: one
//! missed item corrupts the program silently. Instead each stereo context
//! gets a companion compatibility context of the layer, created with the
//! same visual or configuration and sharing the program's objects (so it
//! samples the eye textures). glXSwapBuffers finishes the program's
//! rendering, makes the layer's context current on the same drawable,
//! composes and swaps there, and makes the program's context current again
//! exactly as it was (display, draw and read drawables). The program's GL
//! state is never touched; GL guarantees each context's state is its own.
//!
//! Cost: two context switches per frame, which measure ≈ 1.3 µs for the
//! pair with Mesa's llvmpipe under Xvfb, against ≈ 1.2 ms for the cheapest
//! mono 1280x1024 frame (a clear and a swap); plus one glFinish (the
//! swap waits for the rendering anyway) and one XGetGeometry round trip
//! (≈ 17 µs) to follow the window's size. The composite itself is the GL
//! compositor's pass ([`crate::output::gl`]).
//!
//! # Misuse: what libGL survives goes to libGL, what would crash it is refused
//!
//! The layer answers a wrong call as libGL does whenever libGL answers it:
//! the program sees libGL's return value, X error and GL error (a bad
//! screen, attribute, render type, drawable or GL enum; a configuration or
//! context libGL does not know — libglvnd reports a destroyed context as
//! GLXBadContext). What libglvnd 1.6 with Mesa 22 crashes on (measured:
//! tests/c/misuse_glx.c runs each case, and fails with SIGSEGV without the
//! checks) is refused before libGL sees it, with the failure value of the
//! function and a message (for
//! gls_last_error_message() and, once per distinct message, on stderr as
//! `glstereo: glXName refused: …`):
//!
//! - a NULL `Display*`: libGL crashes in every function but glXGetConfig,
//!   glXMakeCurrent, glXSwapBuffers and glXDestroyWindow; the layer refuses
//!   it everywhere (one rule; a silent no-op of glXSwapBuffers would hide
//!   the bug), except for a release, glXMakeCurrent(NULL, None, NULL),
//!   which libglvnd accepts;
//! - NULL where GLX needs a pointer: glXChooseVisual's list, glXCreateContext's
//!   visual, `nelements`, the value of glXGetConfig / glXGetFBConfigAttrib
//!   (GLX_BAD_VALUE, as libglvnd answers for glXGetConfig), the name of
//!   glXGetProcAddress. A NULL configuration or glXChooseFBConfig list is
//!   libGL's to answer (GLXBadFBConfig; the defaults);
//! - a share context the program destroyed (libGL reads the freed context):
//!   [`registry::Registry::is_dead`] remembers the last
//!   [`registry::DEAD_CONTEXTS`] destroyed;
//! - a stereo context destroyed while current: GLX keeps it until it is
//!   released, and presenting makes the program's context current again
//!   after the layer's, which libGL refuses for a destroyed context (the
//!   program would then draw into the layer's context). So its real
//!   destruction waits for the release ([`context::StereoContext::defer_destroy`]),
//!   and making it current or destroying it again meanwhile is refused;
//! - GL: a NULL pointer GL reads or writes through (glGet*v and glGet*i_v,
//!   glDrawBuffers and glDeleteFramebuffers with n > 0,
//!   glGetFramebufferAttachmentParameteriv,
//!   and the functions of [`dsa`]: glClearBuffer* and glClearNamedFramebuffer*
//!   values, glNamedFramebufferDrawBuffers and glInvalidate(Sub)Framebuffer
//!   lists with n > 0, the glGet*FramebufferParameteriv and
//!   glGetNamedFramebufferAttachmentParameteriv params,
//!   glCreateShaderProgramv strings; and of [`binaries`]: glGetProgramiv
//!   params, glGetProgramBinary's format and binary, glProgramBinary's
//!   binary):
//!   nothing happens but GL_INVALID_VALUE, in the stereo context's error
//!   flag or, in any other context, raised by the driver itself
//!   with glViewport(0, 0, -1, -1) (GL rejects it with exactly that error
//!   and no other effect). With no context current nothing is raised, as
//!   GL raises nothing then.
//!
//! Pointers that are not NULL but wrong (freed, too short, unterminated
//! lists) cannot be detected, by libGL or the layer. The layer's own GL
//! queries in the program's context never add or hide a GL error (the
//! program's pending error is moved to the context's flag first; see
//! [`gl::push_attrib`] in a core-profile context), and a query the driver
//! refuses gets no emulated answer written.
//!
//! GL errors are kept as Mesa keeps them: one flag per context, the first
//! error raised since the last glGetError, whether the emulation or the
//! driver raised it; later ones are dropped. (GL 4.5 describes one flag
//! per error code; where Mesa can answer, the layer's answer is Mesa's.)
//!
//! # Threads
//!
//! GLX's rules: each thread has its own current context. The stereo context
//! current on a thread is a thread-local slot ([`context::current`]); each
//! stereo context's state has its own lock, the registry one lock taken
//! briefly (never under a state lock). Two threads render and swap their
//! own stereo contexts at once, on their own X connections or on one
//! (XInitThreads), and a context moves between threads by release and
//! make-current (tests/threads.rs, tests/c/glx_threads.c). A stereo
//! drawable swapped on a thread other than the one its context is current
//! on is not updated (said on stderr): GLX would swap a context's drawable
//! only where it is current too.
//!
//! Names: the layer's textures, renderbuffers and framebuffer objects live
//! in the program's share group. Textures and renderbuffers take names
//! from just below 2^31, framebuffer objects glGen* names
//! ([`crate::gl::names`] says why: legacy programs bind small texture
//! names they never generated and index small tables with their generated
//! ones, bindings read through a GLint must stay non-negative, layers
//! below track framebuffer objects by name). The program's glDelete* leave
//! them alone; the layer's framebuffer object in the program's context is
//! never reported (bindings of it read 0).
//!
//! # Other GL layers in the process
//!
//! The layer is one of several: VirtualGL, apitrace, RenderDoc and
//! MangoHud stack above or below it (tests/stacking.rs runs each, in both
//! launch orders). Above it, a layer asks it for "the real" functions
//! (dlsym(RTLD_NEXT), glXGetProcAddress, dlopen of libGL) and gets the
//! layer's own — never the first definition of a name in the process,
//! which would be that layer's own function (preload/src/lib.rs). Below
//! it ([`next`]):
//! - every frame goes through the next glXSwapBuffers when that is another
//!   layer's ([`real::Real::swap_layered`]): MangoHud draws its HUD there,
//!   VirtualGL sends the frame, apitrace and RenderDoc end a frame there;
//!   the composite is drawn by GL then, not put with MIT-SHM, and the eyes
//!   are plain textures (no imported memory, which no layer can replay);
//! - the layer's own context is made with glXCreateContextAttribsARB
//!   where the program's configuration allows (RenderDoc captures only
//!   such contexts' frames);
//! - framebuffer 0 answers from the emulated framebuffer, whatever the
//!   layer below has as its framebuffer 0 (VirtualGL makes contexts current
//!   without a surface: there it is undefined) — see [`dsa`];
//! - stereo a driver or a layer below offers (VirtualGL's own 144 stereo
//!   configurations) is used as it is when the user chose no format, and
//!   emulated like a mono configuration when the user chose one
//!   ([`settings::native_allowed`]); GLSTEREO_VERBOSE says which.
//!
//! A layer above that takes libGL's functions straight from libGL,
//! bypassing every layer after it (MangoHud, when it is preloaded before
//! glstereo by hand: it finds libc's dlopen by walking the ELF tables), is
//! out of reach: the program's contexts and swaps never pass through
//! glstereo then.

pub mod attribs;
pub mod binaries;
pub mod capture;
pub mod context;
pub mod controls;
pub mod draws;
pub mod dsa;
pub mod egl;
pub mod gl;
pub mod glx;
pub mod live;
pub mod next;
pub mod real;
pub mod registry;
pub mod settings;
pub mod wsi;

/// Writes `glstereo: <message>` to stderr, once per distinct message
/// ([`crate::report::warn`]): the layer has no return code to report
/// through.
pub use crate::report::warn;

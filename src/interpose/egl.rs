//! Automatic stereo for programs that draw through EGL: OpenGL ES and
//! desktop GL contexts, on X11 windows and as native Wayland clients
//! (issue 31). EGL has no stereo configuration, so the only stereo an EGL
//! program can get is `--auto`'s; a program run without it is served by
//! the real libEGL, after one registry look-up per interposed EGL call.
//!
//! What an EGL program does, and what it gets under `--auto`:
//!
//! - eglCreateContext (ES 1.x is left alone; ES 2, ES 3.x, desktop GL
//!   through eglBindAPI) gets an automatic-stereo context, as a GLX
//!   context does ([`super::glx`]): a [`StereoContext`] with the layer's
//!   own context beside it, made with the same configuration and sharing
//!   the program's objects. The layer's own context is always a desktop
//!   compatibility context, whatever the program's API: Mesa shares
//!   objects between ES and desktop contexts (measured on Mesa 22.3:
//!   textures made in an ES 3.2 context are textures in a 4.5
//!   compatibility context sharing with it), so the compositor is the one
//!   [`crate::output::gl`] has. A configuration that cannot make desktop
//!   contexts takes EGL_KHR_no_config_context.
//! - eglMakeCurrent on a window or pbuffer surface binds the surface's
//!   emulated framebuffer where the program has framebuffer 0
//!   ([`StereoContext::bind`]); a context made current with no surface
//!   (EGL_KHR_surfaceless_context) draws into its own framebuffer objects.
//! - eglSwapBuffers and eglSwapBuffersWithDamage(KHR/EXT) present the
//!   eyes composed in the output format: on a software renderer, into an
//!   X11 window of a display the program opened, from memory with
//!   MIT-SHM as a GLX window's (the real swap is not called); else into
//!   the program's own surface, from the layer's context, with the real
//!   eglSwapBuffers (the damage rectangles are the program's frame's; the
//!   composite is new everywhere). eglSwapInterval is the program's: EGL keeps it on the
//!   surface, which the layer's swap uses.
//! - eglDestroySurface frees the surface's buffers in every context that
//!   has them; eglDestroyContext of a current context waits for its
//!   release, as EGL keeps it until then; eglTerminate destroys the layer's
//!   contexts on the display first (EGL would destroy them with it, and
//!   the program's contexts current on a thread stay usable until they
//!   are released, mono).
//! - Sizes are EGL's (eglQuerySurface): Mesa reports an X11 window's size
//!   as the server has it, and a Wayland window's as wl_egl_window_resize
//!   set it.
//!
//! Where the surfaces live: an X11 window (eglGetDisplay of a `Display*`,
//! EGL_PLATFORM_X11_KHR) also gets the live keys, as a GLX window does; a
//! Wayland surface gets none (the keyboard is the program's wl_keyboard,
//! which the layer does not see).

use std::collections::HashMap;
use std::ffi::{CStr, c_char, c_void};
use std::sync::{Mutex, OnceLock};

use super::context::{StereoContext, current, set_current};
use super::real::loaded;
use super::registry;
use super::settings;
use super::wsi::Wsi;
use crate::error::{Error, Result};
use crate::stereo::buffers::FramebufferShape;
use crate::stereo::emulated::BufferFormats;

/// `EGLBoolean`.
pub type EglBoolean = u32;
/// `EGLint`.
pub type EglInt = i32;
/// `EGLenum`.
pub type EglEnum = u32;
/// `EGLAttrib` (EGL 1.5).
pub type EglAttrib = isize;
/// `EGLDisplay`, `EGLConfig`, `EGLContext`, `EGLSurface`.
pub type Handle = *mut c_void;

/// EGL_FALSE / EGL_TRUE.
pub const EGL_FALSE: EglBoolean = 0;
/// EGL_TRUE.
pub const EGL_TRUE: EglBoolean = 1;
const EGL_NONE: EglInt = 0x3038;
const EGL_ALPHA_SIZE: EglInt = 0x3021;
const EGL_DEPTH_SIZE: EglInt = 0x3025;
const EGL_STENCIL_SIZE: EglInt = 0x3026;
const EGL_RENDERABLE_TYPE: EglInt = 0x3040;
const EGL_OPENGL_BIT: EglInt = 0x0008;
const EGL_HEIGHT: EglInt = 0x3056;
const EGL_WIDTH: EglInt = 0x3057;
const EGL_DRAW: EglInt = 0x3059;
const EGL_READ: EglInt = 0x305A;
const EGL_CONTEXT_CLIENT_VERSION: EglInt = 0x3098;
const EGL_OPENGL_ES_API: EglEnum = 0x30A0;
const EGL_OPENGL_API: EglEnum = 0x30A2;
/// EGL_PLATFORM_X11_KHR (= EGL_PLATFORM_X11_EXT).
pub const EGL_PLATFORM_X11_KHR: EglEnum = 0x31D5;
/// EGL_PLATFORM_WAYLAND_KHR (= EGL_PLATFORM_WAYLAND_EXT).
pub const EGL_PLATFORM_WAYLAND_KHR: EglEnum = 0x31D8;
/// EGL_PLATFORM_XCB_EXT.
pub const EGL_PLATFORM_XCB_EXT: EglEnum = 0x31DC;
/// EGL_EXT_platform_device.
pub const EGL_PLATFORM_DEVICE_EXT: EglEnum = 0x313F;
/// EGL_MESA_platform_surfaceless.
pub const EGL_PLATFORM_SURFACELESS_MESA: EglEnum = 0x31DD;

macro_rules! egl_table {
    (
        required { $( $name:ident ( $($arg:ty),* ) -> $ret:ty ; )* }
        optional { $( $oname:ident ( $($oarg:ty),* ) -> $oret:ty ; )* }
    ) => {
        /// The EGL functions the layer calls, as [`super::next`] finds them
        /// (a layer below, then libEGL).
        #[allow(non_snake_case, missing_docs)]
        pub struct Egl {
            $( pub $name: unsafe extern "C" fn($($arg),*) -> $ret, )*
            $( pub $oname: Option<unsafe extern "C" fn($($oarg),*) -> $oret>, )*
        }

        impl Egl {
            /// Looks every function up; Err names the first one missing.
            fn load() -> std::result::Result<Egl, String> {
                Ok(Egl {
                    $( $name: {
                        let name = concat!(stringify!($name), "\0");
                        let p = super::next::next_egl_symbol(
                            CStr::from_bytes_with_nul(name.as_bytes()).expect("NUL-terminated"),
                        );
                        if p.is_null() {
                            let why = if super::next::libegl_loadable() {
                                format!("has no {}", stringify!($name))
                            } else {
                                "could not be loaded".to_owned()
                            };
                            return Err(format!(
                                "the real libEGL.so.1 {why}: install libegl1 and \
                                 libegl-mesa0 (Debian) or your GL driver's libEGL"
                            ));
                        }
                        // SAFETY: the named EGL function's address, transmuted
                        // to its EGL 1.4 signature (the field's type).
                        unsafe {
                            std::mem::transmute::<*mut c_void, unsafe extern "C" fn($($arg),*) -> $ret>(p)
                        }
                    }, )*
                    $( $oname: {
                        let name = concat!(stringify!($oname), "\0");
                        let p = super::next::next_egl_symbol(
                            CStr::from_bytes_with_nul(name.as_bytes()).expect("NUL-terminated"),
                        );
                        // SAFETY: NULL or the named function's address, with
                        // its Khronos signature.
                        (!p.is_null()).then(|| unsafe {
                            std::mem::transmute::<*mut c_void, unsafe extern "C" fn($($oarg),*) -> $oret>(p)
                        })
                    }, )*
                })
            }
        }
    };
}

egl_table! {
    required {
        eglGetProcAddress(*const c_char) -> *mut c_void;
        eglQueryAPI() -> EglEnum;
        eglBindAPI(EglEnum) -> EglBoolean;
        eglGetConfigAttrib(Handle, Handle, EglInt, *mut EglInt) -> EglBoolean;
        eglCreateContext(Handle, Handle, Handle, *const EglInt) -> Handle;
        eglDestroyContext(Handle, Handle) -> EglBoolean;
        eglMakeCurrent(Handle, Handle, Handle, Handle) -> EglBoolean;
        eglGetCurrentContext() -> Handle;
        eglGetCurrentDisplay() -> Handle;
        eglGetCurrentSurface(EglInt) -> Handle;
        eglQueryContext(Handle, Handle, EglInt, *mut EglInt) -> EglBoolean;
        eglQuerySurface(Handle, Handle, EglInt, *mut EglInt) -> EglBoolean;
        eglSwapBuffers(Handle, Handle) -> EglBoolean;
        eglGetError() -> EglInt;
    }
    optional {
        eglGetDisplay(*mut c_void) -> Handle;
        eglGetPlatformDisplay(EglEnum, *mut c_void, *const EglAttrib) -> Handle;
        eglGetPlatformDisplayEXT(EglEnum, *mut c_void, *const EglInt) -> Handle;
        eglCreateWindowSurface(Handle, Handle, usize, *const EglInt) -> Handle;
        eglCreatePlatformWindowSurface(Handle, Handle, *mut c_void, *const EglAttrib) -> Handle;
        eglCreatePlatformWindowSurfaceEXT(Handle, Handle, *mut c_void, *const EglInt) -> Handle;
        eglDestroySurface(Handle, Handle) -> EglBoolean;
        eglTerminate(Handle) -> EglBoolean;
        eglReleaseThread() -> EglBoolean;
        eglSwapBuffersWithDamageKHR(Handle, Handle, *const EglInt, EglInt) -> EglBoolean;
        eglSwapBuffersWithDamageEXT(Handle, Handle, *const EglInt, EglInt) -> EglBoolean;
    }
}

// SAFETY: function pointers only; EGL's functions are thread-safe as EGL
// defines them.
unsafe impl Send for Egl {}
// SAFETY: as above.
unsafe impl Sync for Egl {}

static EGL: OnceLock<std::result::Result<Egl, String>> = OnceLock::new();

/// The real EGL entry points, loaded on first use.
pub fn egl() -> Result<&'static Egl> {
    EGL.get_or_init(Egl::load)
        .as_ref()
        .map_err(|e| Error::BackendUnavailable(e.clone()))
}

/// The real EGL if the process loaded it already (a process that never
/// called EGL does not get libEGL loaded by the layer's look-ups).
pub fn egl_if_loaded() -> Option<&'static Egl> {
    EGL.get().and_then(|e| e.as_ref().ok())
}

/// Whether the next eglSwapBuffers is another layer's (MangoHud's, apitrace's
/// egltrace), not libEGL's own: that layer sees every presented frame.
pub fn swap_layered() -> bool {
    static LAYERED: OnceLock<bool> = OnceLock::new();
    *LAYERED.get_or_init(|| {
        egl_if_loaded().is_some_and(|e| {
            e.eglSwapBuffers as *const c_void
                != super::next::bottom_egl_symbol(c"eglSwapBuffers").cast_const()
        })
    })
}

/// Which window system an EGL display draws on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Platform {
    /// X11 through Xlib: the native display is a `Display*` (0: EGL's own
    /// connection to $DISPLAY).
    X11,
    /// X11 through XCB (EGL_PLATFORM_XCB_EXT).
    Xcb,
    /// Wayland: the native display is a `wl_display*`.
    Wayland,
    /// A device or Mesa's surfaceless platform: no window surfaces at
    /// all, only pbuffers and framebuffer objects (VirtualGL's `-d egl`
    /// renders there).
    Windowless,
    /// Anything else (GBM…).
    Other,
}

/// What the layer knows of an EGL display.
#[derive(Clone, Copy, Debug)]
struct DisplayInfo {
    platform: Platform,
    /// The native display (`Display*`, `wl_display*`…), 0 for the default.
    native: usize,
    /// The program closed the native X display (XCloseDisplay): the
    /// layer no longer uses it.
    x_closed: bool,
}

/// What the layer knows of a window surface.
#[derive(Clone, Copy, Debug)]
struct SurfaceInfo {
    /// The X window behind it (X11 platforms), else 0.
    x_window: u64,
}

#[derive(Default)]
struct State {
    displays: HashMap<usize, DisplayInfo>,
    surfaces: HashMap<(usize, usize), SurfaceInfo>,
}

static STATE: Mutex<Option<State>> = Mutex::new(None);

fn with_state<T>(f: impl FnOnce(&mut State) -> T) -> T {
    let mut g = STATE.lock().unwrap_or_else(|e| e.into_inner());
    f(g.get_or_insert_with(State::default))
}

/// The X display and window behind surface `surface` of EGL display
/// `display`, for the live keys and MIT-SHM: None on other platforms,
/// where the program let EGL open its own X connection, or after it
/// closed its own.
pub fn x_window(display: usize, surface: u64) -> Option<(usize, u64)> {
    with_state(|s| {
        let d = s.displays.get(&display)?;
        let w = s.surfaces.get(&(display, surface as usize))?;
        (d.platform == Platform::X11 && d.native != 0 && !d.x_closed && w.x_window != 0)
            .then_some((d.native, w.x_window))
    })
}

/// The `Display*` behind an X11 EGL display the program opened itself
/// (and has not closed).
pub fn x_display(display: usize) -> Option<usize> {
    with_state(|s| {
        s.displays
            .get(&display)
            .filter(|d| d.platform == Platform::X11 && d.native != 0 && !d.x_closed)
            .map(|d| d.native)
    })
}

/// XCloseDisplay of `x`, a display the program opened: the EGL displays
/// on it, which from now on the layer never uses it for (their frames go
/// through the real eglSwapBuffers).
pub fn x_display_closed(x: usize) -> Vec<usize> {
    with_state(|s| {
        let mut on = Vec::new();
        for (&display, d) in &mut s.displays {
            if d.platform == Platform::X11 && d.native == x && !d.x_closed {
                d.x_closed = true;
                on.push(display);
            }
        }
        on
    })
}

/// The platform eglGetDisplay gives `native`, as Mesa decides it:
/// EGL_PLATFORM when set; a `wl_display*` (its first word is the address
/// of libwayland's `wl_display_interface`); otherwise X11.
fn platform_of_native(native: *mut c_void) -> Platform {
    if let Ok(p) = std::env::var("EGL_PLATFORM") {
        return match p.as_str() {
            "x11" => Platform::X11,
            "wayland" => Platform::Wayland,
            "surfaceless" | "device" => Platform::Windowless,
            _ => Platform::Other,
        };
    }
    if native.is_null() {
        // Debian's Mesa lists x11 first: EGL_DEFAULT_DISPLAY is X11 there.
        return Platform::X11;
    }
    // SAFETY: a NUL-terminated name; RTLD_DEFAULT finds libwayland-client
    // where the program loaded it globally.
    let mut iface = unsafe { libc::dlsym(libc::RTLD_DEFAULT, c"wl_display_interface".as_ptr()) };
    if iface.is_null() {
        iface = super::next::own_symbol_in(c"wl_display_interface", c"libwayland-client.so.0");
    }
    // SAFETY: a native display is a pointer to an object whose first word
    // EGL reads the same way (Mesa's own detection).
    if !iface.is_null() && unsafe { *(native as *const *mut c_void) } == iface {
        Platform::Wayland
    } else {
        Platform::X11
    }
}

fn platform_of(platform: EglEnum) -> Platform {
    match platform {
        EGL_PLATFORM_X11_KHR => Platform::X11,
        EGL_PLATFORM_XCB_EXT => Platform::Xcb,
        EGL_PLATFORM_WAYLAND_KHR => Platform::Wayland,
        EGL_PLATFORM_DEVICE_EXT | EGL_PLATFORM_SURFACELESS_MESA => Platform::Windowless,
        _ => Platform::Other,
    }
}

fn remember_display(display: Handle, platform: Platform, native: *mut c_void) {
    if !display.is_null() {
        with_state(|s| {
            s.displays.insert(
                display as usize,
                DisplayInfo {
                    platform,
                    native: native as usize,
                    x_closed: false,
                },
            )
        });
    }
}

/// Which eglGetDisplay the program called.
pub enum GetDisplay {
    /// eglGetDisplay(native).
    Native,
    /// eglGetPlatformDisplay(platform, native, attribs).
    Platform(EglEnum, *const EglAttrib),
    /// eglGetPlatformDisplayEXT(platform, native, attribs).
    PlatformExt(EglEnum, *const EglInt),
}

/// eglGetDisplay, eglGetPlatformDisplay and eglGetPlatformDisplayEXT:
/// the real call, and the display's platform remembered.
///
/// # Safety
/// As those functions.
pub unsafe fn get_display(native: *mut c_void, how: GetDisplay) -> Result<Handle> {
    let e = egl()?;
    // SAFETY: forwarded calls.
    let (d, platform) = unsafe {
        match how {
            GetDisplay::Native => (
                e.eglGetDisplay.map_or(std::ptr::null_mut(), |f| f(native)),
                platform_of_native(native),
            ),
            GetDisplay::Platform(p, a) => (
                e.eglGetPlatformDisplay
                    .map_or(std::ptr::null_mut(), |f| f(p, native, a)),
                platform_of(p),
            ),
            GetDisplay::PlatformExt(p, a) => (
                e.eglGetPlatformDisplayEXT
                    .map_or(std::ptr::null_mut(), |f| f(p, native, a)),
                platform_of(p),
            ),
        }
    };
    remember_display(d, platform, native);
    Ok(d)
}

/// Which eglCreate*WindowSurface the program called.
pub enum NewWindow {
    /// eglCreateWindowSurface(native window).
    Native(usize, *const EglInt),
    /// eglCreatePlatformWindowSurface(pointer to the native window).
    Platform(*mut c_void, *const EglAttrib),
    /// eglCreatePlatformWindowSurfaceEXT(pointer to the native window).
    PlatformExt(*mut c_void, *const EglInt),
}

/// eglCreateWindowSurface and eglCreatePlatformWindowSurface(EXT): the
/// real call; the X window behind an X11 surface is remembered (for the
/// live keys).
///
/// # Safety
/// As those functions.
pub unsafe fn create_window_surface(dpy: Handle, config: Handle, how: NewWindow) -> Result<Handle> {
    let e = egl()?;
    let platform = with_state(|s| s.displays.get(&(dpy as usize)).map(|d| d.platform));
    // SAFETY: forwarded calls.
    let (surface, x_window) = unsafe {
        match how {
            NewWindow::Native(w, a) => (
                e.eglCreateWindowSurface
                    .map_or(std::ptr::null_mut(), |f| f(dpy, config, w, a)),
                w as u64,
            ),
            NewWindow::Platform(w, a) => (
                e.eglCreatePlatformWindowSurface
                    .map_or(std::ptr::null_mut(), |f| f(dpy, config, w, a)),
                x_window_behind(platform, w),
            ),
            NewWindow::PlatformExt(w, a) => (
                e.eglCreatePlatformWindowSurfaceEXT
                    .map_or(std::ptr::null_mut(), |f| f(dpy, config, w, a)),
                x_window_behind(platform, w),
            ),
        }
    };
    if !surface.is_null() {
        let x_window = if platform == Some(Platform::X11) {
            x_window
        } else {
            0
        };
        with_state(|s| {
            s.surfaces
                .insert((dpy as usize, surface as usize), SurfaceInfo { x_window })
        });
    }
    Ok(surface)
}

/// The X window a platform window surface's `native` points to
/// (EGL_KHR_platform_x11: a `Window*`), 0 elsewhere.
///
/// # Safety
/// `native` is what the program passed to the successful call.
unsafe fn x_window_behind(platform: Option<Platform>, native: *mut c_void) -> u64 {
    if platform == Some(Platform::X11) && !native.is_null() {
        // SAFETY: EGL_KHR_platform_x11's native window is a Window*.
        unsafe { *(native as *const u64) }
    } else {
        0
    }
}

/// eglDestroySurface: the surface's buffers go in every context that has
/// them (where it is current, when it is released), then the real call.
///
/// # Safety
/// As eglDestroySurface.
pub unsafe fn destroy_surface(dpy: Handle, surface: Handle) -> Result<EglBoolean> {
    let e = egl()?;
    if !surface.is_null() {
        for sc in registry::with(|reg| reg.contexts_of(dpy as usize)) {
            sc.drawable_destroyed(surface as u64);
        }
    }
    // SAFETY: forwarded call.
    let ok = unsafe { e.eglDestroySurface.map_or(EGL_FALSE, |f| f(dpy, surface)) };
    if ok != EGL_FALSE {
        with_state(|s| s.surfaces.remove(&(dpy as usize, surface as usize)));
    }
    Ok(ok)
}

/// The major version an attribute list asks of an ES context (1 when it
/// says nothing, EGL's default).
///
/// # Safety
/// `attribs` is NULL or an EGL_NONE-terminated list.
unsafe fn es_major(attribs: *const EglInt) -> EglInt {
    let mut major = 1;
    if attribs.is_null() {
        return major;
    }
    let mut i = 0;
    loop {
        // SAFETY: an EGL_NONE-terminated list of pairs (EGL's contract).
        let key = unsafe { *attribs.add(i) };
        if key == EGL_NONE {
            return major;
        }
        // SAFETY: as above: each key has its value.
        let value = unsafe { *attribs.add(i + 1) };
        if key == EGL_CONTEXT_CLIENT_VERSION {
            major = value;
        }
        i += 2;
    }
}

/// eglCreateContext: the real call; under `--auto`, an automatic-stereo
/// context (see the module doc). OpenGL ES 1.x contexts stay mono (no
/// framebuffer objects to emulate the window with; said once).
///
/// # Safety
/// As eglCreateContext.
pub unsafe fn create_context(
    dpy: Handle,
    config: Handle,
    share: Handle,
    attribs: *const EglInt,
) -> Result<Handle> {
    let e = egl()?;
    if !share.is_null() && registry::with(|reg| reg.is_dead(share as usize)) {
        // libEGL answers a destroyed share context with EGL_BAD_CONTEXT;
        // it is the layer's objects that must not be looked up in it.
        // SAFETY: forwarded call; EGL reports the error.
        return Ok(unsafe { (e.eglCreateContext)(dpy, config, share, attribs) });
    }
    // SAFETY: forwarded call.
    let ctx = unsafe { (e.eglCreateContext)(dpy, config, share, attribs) };
    if ctx.is_null() {
        return Ok(ctx);
    }
    super::context::context_created(ctx as usize, share as usize);
    if !super::live::auto_requested() {
        return Ok(ctx);
    }
    let windowless = with_state(|s| {
        s.displays
            .get(&(dpy as usize))
            .is_some_and(|d| d.platform == Platform::Windowless)
    });
    if windowless {
        // No window surface can be made there, so no frame of it is ever
        // shown: eyes made in it would never be seen. It is where
        // VirtualGL renders a program's GLX frames (`vglrun -d egl`), whose
        // windows the layer only sees from above VirtualGL.
        super::warn(
            "--auto: a context on an EGL device or surfaceless display has no \
             window to show two eyes in, so it stays mono; under VirtualGL, start \
             the layer inside it: vglrun -d egl glstereo-run --auto PROGRAM",
        );
        return Ok(ctx);
    }
    // SAFETY: plain EGL query of the calling thread's bound API.
    let api = unsafe { (e.eglQueryAPI)() };
    // SAFETY: the program's attribute list, which EGL just accepted.
    if api == EGL_OPENGL_ES_API && unsafe { es_major(attribs) } < 2 {
        super::warn(
            "an OpenGL ES 1.x context has no framebuffer objects: it runs in mono \
             under --auto",
        );
        return Ok(ctx);
    }
    // SAFETY: a context EGL just made on `dpy` with `config`.
    unsafe { adopt(e, dpy, config, ctx, api) };
    Ok(ctx)
}

/// Makes program context `ctx` an automatic-stereo context: creates the
/// layer's desktop compatibility context sharing its objects, with the
/// program's configuration, else with no configuration
/// (EGL_KHR_no_config_context). On failure stderr says why and the
/// context stays mono.
///
/// # Safety
/// `ctx` is a live context of `dpy` made with `config`.
unsafe fn adopt(e: &Egl, dpy: Handle, config: Handle, ctx: Handle, api: EglEnum) {
    let Ok(r) = loaded() else {
        super::warn(
            "automatic stereo needs the real libGL.so.1 beside libEGL (for the GL \
             functions): this context stays mono",
        );
        return;
    };
    if r.extra.layered.is_none() {
        super::warn(
            "automatic stereo needs GL 4.3 / OpenGL ES 3.2 (layered framebuffers, \
             glCopyImageSubData): this context stays mono",
        );
        return;
    }
    let attrib = |a: EglInt| -> EglInt {
        let mut v = 0;
        // SAFETY: a valid display and configuration (the context was made).
        let ok = unsafe { (e.eglGetConfigAttrib)(dpy, config, a, &mut v) };
        if ok == EGL_FALSE { 0 } else { v }
    };
    let none = [EGL_NONE];
    let make = |c: Handle| -> Handle {
        // SAFETY: the calling thread's bound API is put back after; the
        // list is EGL_NONE-terminated.
        unsafe {
            let api = (e.eglQueryAPI)();
            (e.eglBindAPI)(EGL_OPENGL_API);
            let ours = (e.eglCreateContext)(dpy, c, ctx, none.as_ptr());
            (e.eglBindAPI)(api);
            ours
        }
    };
    let mut ours = std::ptr::null_mut();
    if attrib(EGL_RENDERABLE_TYPE) & EGL_OPENGL_BIT != 0 {
        ours = make(config);
    }
    if ours.is_null() {
        // EGL_NO_CONFIG_KHR: a context that fits any surface.
        ours = make(std::ptr::null_mut());
    }
    if ours.is_null() {
        // SAFETY: plain EGL error query of this thread.
        let err = unsafe { (e.eglGetError)() };
        super::warn(&format!(
            "the layer's own GL context could not be created (EGL error {err:#x}): \
             this context runs in mono"
        ));
        return;
    }
    let bits = |a| attrib(a).max(0) as u32;
    let shape = FramebufferShape {
        stereo: true,
        double_buffered: true,
    };
    let formats = BufferFormats {
        // Frames go through GL and the real eglSwapBuffers, but eyes made
        // from depth (--auto=depth) are made by the CPU: where they are
        // memory it reads and writes in place, nothing is read back or
        // uploaded. Not under a GL layer (RenderDoc, apitrace), which
        // must see plain GL it can record and replay.
        in_place: r.extra.memory_objects.filter(|_| !swap_layered()),
        layered: r.extra.layered,
        // An OpenGL ES context's glDrawBuffers names attachment i at i only.
        positional: api == EGL_OPENGL_ES_API,
        ..BufferFormats::matching(
            bits(EGL_ALPHA_SIZE),
            bits(EGL_DEPTH_SIZE),
            bits(EGL_STENCIL_SIZE),
        )
    };
    let group = registry::with(|reg| reg.group(ctx as usize));
    // The layer's own context shares the program's objects: what it
    // names is the group's.
    r.gl.context_joined(ours as usize, group);
    let sc = StereoContext::new_on(
        Wsi::Egl,
        dpy as usize,
        ctx as usize,
        ours as usize,
        shape,
        formats,
        group,
    );
    settings::tell(&format!(
        "automatic stereo for an EGL context: both eyes shown as {} in the program's surface",
        super::live::mode().canonical_name()
    ));
    registry::with(|reg| reg.add_context(ctx as usize, sc));
    if let Some(x) = x_display(dpy as usize) {
        super::controls::arm(&r.xlib, x as *mut x11_dl::xlib::Display);
        // Frames go to its windows with MIT-SHM: its XCloseDisplay must
        // free their images first, and end that.
        super::glx::watch(r, x as *mut x11_dl::xlib::Display);
    }
}

/// eglDestroyContext: as glXDestroyContext ([`super::glx::destroy_context`]):
/// an automatic-stereo context current on a thread is destroyed, with the
/// layer's, when it is released.
///
/// # Safety
/// As eglDestroyContext.
pub unsafe fn destroy_context(dpy: Handle, ctx: Handle) -> Result<EglBoolean> {
    let e = egl()?;
    if ctx.is_null() {
        // SAFETY: forwarded call (EGL_BAD_CONTEXT).
        return Ok(unsafe { (e.eglDestroyContext)(dpy, ctx) });
    }
    let key = ctx as usize;
    let sc = registry::with(|reg| reg.context(key));
    let Some(sc) = sc.filter(|sc| sc.display() == dpy as usize) else {
        // SAFETY: forwarded call.
        let ok = unsafe { (e.eglDestroyContext)(dpy, ctx) };
        if ok != EGL_FALSE {
            registry::with(|reg| reg.mark_dead(key));
            super::context::context_destroyed(key);
        }
        return Ok(ok);
    };
    if registry::with(|reg| reg.is_doomed(key)) {
        // Destroyed already, current until released: EGL's answer to a
        // second destroy of a context marked for deletion.
        return Ok(EGL_TRUE);
    }
    let deferred = registry::with(|reg| {
        reg.mark_dead(key);
        reg.remove_context(key);
        let deferred = sc.defer_destroy();
        if deferred {
            reg.add_doomed(key, sc.clone());
        }
        deferred
    });
    if deferred {
        return Ok(EGL_TRUE);
    }
    // SAFETY: forwarded call.
    let ok = unsafe { (e.eglDestroyContext)(dpy, ctx) };
    sc.destroy_ours();
    super::context::context_destroyed(key);
    Ok(ok)
}

/// eglMakeCurrent: the real call, then, for an automatic-stereo context
/// on a surface, its emulated framebuffer bound ([`StereoContext::bind`]).
///
/// # Safety
/// As eglMakeCurrent.
pub unsafe fn make_current(
    dpy: Handle,
    draw: Handle,
    read: Handle,
    ctx: Handle,
) -> Result<EglBoolean> {
    let e = egl()?;
    if !ctx.is_null() && registry::with(|reg| reg.is_doomed(ctx as usize)) {
        // EGL would make a context marked for deletion current again (it
        // lives until released); the layer destroys it at the release.
        super::warn(
            "eglMakeCurrent of a context the program destroyed while current: it runs in \
             mono until released",
        );
    }
    let sc = if ctx.is_null() {
        None
    } else {
        registry::with(|reg| reg.context(ctx as usize))
    };
    let before = current();
    let readied = before
        .as_ref()
        .is_some_and(|b| b.sc.context() != ctx as usize && b.sc.before_release());
    let held = sc.clone();
    let binding = held.as_ref().map(|sc| sc.hold_binding());
    // SAFETY: forwarded call.
    let ok = unsafe { (e.eglMakeCurrent)(dpy, draw, read, ctx) };
    if ok == EGL_FALSE {
        return Ok(ok);
    }
    if readied && let Some(b) = &before {
        b.sc.after_release();
    }
    super::wsi::made_current(ctx as usize);
    let (draw, read) = (draw as u64, read as u64);
    let read = if read == 0 { draw } else { read };
    super::context::made_current(before, sc, dpy as usize, (draw, read), binding);
    Ok(ok)
}

/// eglReleaseThread: the thread's current context is released, as
/// eglMakeCurrent with none.
///
/// # Safety
/// As eglReleaseThread.
pub unsafe fn release_thread() -> Result<EglBoolean> {
    let e = egl()?;
    let before = current();
    let readied = before.as_ref().is_some_and(|b| b.sc.before_release());
    // SAFETY: forwarded call.
    let ok = unsafe { e.eglReleaseThread.map_or(EGL_TRUE, |f| f()) };
    if readied
        && ok != EGL_FALSE
        && let Some(b) = &before
    {
        b.sc.after_release();
    }
    super::wsi::made_current(0);
    if before.is_some() {
        set_current(None);
        if let Some(old) = before {
            old.sc.released();
        }
    }
    Ok(ok)
}

/// eglSwapBuffers and eglSwapBuffersWithDamage(KHR/EXT) (`damage`, as
/// the program passed it, for a surface the layer does not present):
/// for an automatic-stereo context current here on `surface`, the eyes
/// are presented ([`StereoContext::present`]); any other surface gets the
/// real call.
///
/// # Safety
/// As those functions.
pub unsafe fn swap_buffers(
    dpy: Handle,
    surface: Handle,
    damage: Option<(Damage, *const EglInt, EglInt)>,
) -> Result<EglBoolean> {
    let e = egl()?;
    let here = current().filter(|c| c.display == dpy as usize && c.draw == surface as u64);
    // A surface destroyed while current (EGL keeps it until released)
    // can no longer be swapped: the real call says so (EGL_BAD_SURFACE),
    // as it would without the layer.
    let mut w: EglInt = 0;
    // SAFETY: a query of the program's handles; EGL checks them.
    let here = here
        .filter(|_| unsafe { (e.eglQuerySurface)(dpy, surface, EGL_WIDTH, &mut w) } != EGL_FALSE);
    if let Some(c) = here {
        if let Err(err) = c.sc.present(surface as u64, true, true) {
            super::warn(&format!("presenting the stereo frame: {err}"));
        }
        return Ok(EGL_TRUE);
    }
    // SAFETY: forwarded calls.
    Ok(unsafe {
        match damage {
            None => (e.eglSwapBuffers)(dpy, surface),
            Some((Damage::Khr, rects, n)) => e
                .eglSwapBuffersWithDamageKHR
                .map_or(EGL_FALSE, |f| f(dpy, surface, rects, n)),
            Some((Damage::Ext, rects, n)) => e
                .eglSwapBuffersWithDamageEXT
                .map_or(EGL_FALSE, |f| f(dpy, surface, rects, n)),
        }
    })
}

/// Which eglSwapBuffersWithDamage.
#[derive(Clone, Copy, Debug)]
pub enum Damage {
    /// EGL_KHR_swap_buffers_with_damage.
    Khr,
    /// EGL_EXT_swap_buffers_with_damage.
    Ext,
}

/// eglTerminate: the layer's contexts on the display are destroyed first
/// (EGL destroys everything of the display; the program's contexts
/// current on a thread stay usable, mono, until released), then the real
/// call.
///
/// # Safety
/// As eglTerminate.
pub unsafe fn terminate(dpy: Handle) -> Result<EglBoolean> {
    let e = egl()?;
    let here = current().filter(|c| c.display == dpy as usize);
    if let Some(c) = &here {
        c.sc.leave_eyes_here();
        super::context::forget_current();
    }
    let gone = registry::with(|reg| {
        let contexts = reg.contexts_of(dpy as usize);
        for sc in &contexts {
            reg.remove_context(sc.context());
        }
        contexts
    });
    for sc in gone {
        if sc.current_elsewhere() {
            sc.mark_ended_elsewhere();
        }
        sc.destroy_ours();
        sc.mark_closed();
    }
    // SAFETY: forwarded call.
    let ok = unsafe { e.eglTerminate.map_or(EGL_FALSE, |f| f(dpy)) };
    if ok != EGL_FALSE {
        with_state(|s| s.surfaces.retain(|&(d, _), _| d != dpy as usize));
    }
    Ok(ok)
}

/// The real eglGetProcAddress's answer for `name` (the function below
/// the layer).
///
/// # Safety
/// `name` is NUL-terminated.
pub unsafe fn get_proc_address(name: *const c_char) -> Result<*mut c_void> {
    let e = egl()?;
    // SAFETY: the caller's NUL-terminated name.
    let p = unsafe { (e.eglGetProcAddress)(name) };
    Ok(if super::next::is_own(p) {
        // A layer below handed the layer's own function back.
        // SAFETY: as above.
        super::next::bottom_egl_symbol(unsafe { CStr::from_ptr(name) })
    } else {
        p
    })
}

/// EGL's side of [`super::wsi::Wsi::Egl`]: what is current on this thread.
pub(super) fn current_binding(e: &Egl) -> (usize, u64, u64, usize) {
    // SAFETY: plain getters of the calling thread's EGL state.
    unsafe {
        (
            (e.eglGetCurrentDisplay)() as usize,
            (e.eglGetCurrentSurface)(EGL_DRAW) as u64,
            (e.eglGetCurrentSurface)(EGL_READ) as u64,
            (e.eglGetCurrentContext)() as usize,
        )
    }
}

/// A surface's size as EGL reports it.
pub(super) fn surface_size(e: &Egl, display: usize, surface: u64) -> Result<(u32, u32)> {
    let (mut w, mut h) = (0, 0);
    // SAFETY: out-pointers; a bad surface is EGL_BAD_SURFACE, no crash.
    let ok = unsafe {
        (e.eglQuerySurface)(display as Handle, surface as Handle, EGL_WIDTH, &mut w) != EGL_FALSE
            && (e.eglQuerySurface)(display as Handle, surface as Handle, EGL_HEIGHT, &mut h)
                != EGL_FALSE
    };
    if ok && w > 0 && h > 0 {
        Ok((w as u32, h as u32))
    } else {
        // SAFETY: plain EGL error query of this thread (clears it: the
        // program did not make this call).
        let err = unsafe { (e.eglGetError)() };
        Err(Error::invalid_operation(format!(
            "EGL surface {surface:#x} has no size (EGL error {err:#x}): it was destroyed?"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_attribute_list_says_which_es_version() {
        // SAFETY: EGL_NONE-terminated lists.
        unsafe {
            assert_eq!(es_major(std::ptr::null()), 1);
            assert_eq!(es_major([EGL_NONE].as_ptr()), 1);
            assert_eq!(
                es_major([EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE].as_ptr()),
                2
            );
            assert_eq!(
                es_major([0x30FB, 1, EGL_CONTEXT_CLIENT_VERSION, 3, EGL_NONE].as_ptr()),
                3
            );
        }
    }

    #[test]
    fn platforms_are_read_from_their_enums() {
        assert_eq!(platform_of(EGL_PLATFORM_X11_KHR), Platform::X11);
        assert_eq!(platform_of(EGL_PLATFORM_WAYLAND_KHR), Platform::Wayland);
        assert_eq!(platform_of(EGL_PLATFORM_XCB_EXT), Platform::Xcb);
        assert_eq!(platform_of(0x31DD), Platform::Windowless);
        assert_eq!(platform_of(0x313F), Platform::Windowless);
        assert_eq!(platform_of(0x31D7), Platform::Other);
    }
}

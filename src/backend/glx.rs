//! GLX on an X server: real windows. libX11 and libGL are loaded at run
//! time (x11-dl), so the library loads on machines without X.
//!
//! A stereo configuration takes a real stereo visual when the server has one
//! (native: the window has left and right buffers); otherwise a double-
//! buffered RGB visual for the window, and the eyes live in glstereo's
//! emulated framebuffer either way. Presenting composes the eyes into the
//! window's back buffer (or, for `quad` on a native visual, copies each eye
//! into its own back buffer) and swaps.
//!
//! X errors never end the process: protocol errors of the library's own
//! requests are trapped, and a lost connection (server killed) is recorded
//! by an I/O-error exit handler (libX11 ≥ 1.7) instead of Xlib's exit().

use crate::sync::LockRecover;
use std::collections::VecDeque;
use std::ffi::{CStr, CString, c_int, c_void};
use std::sync::atomic::{AtomicBool, AtomicI32, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use x11_dl::glx::{self, Glx};
use x11_dl::xlib::{self, Xlib};

use super::xshm::{Connection, ShmImage, ShmSlot};
use super::{BackendKind, ContextRole, Platform, PlatformSurface, WindowEvent};
use crate::config::{Config, ConfigRequest, EmulationPolicy, glx as attr};
use crate::error::{Error, Result};

fn no_display_hint() -> &'static str {
    "start an X server (e.g. `Xvfb :1 & export DISPLAY=:1`), or run headless with GLSTEREO_BACKEND=egl"
}

/// `XSetIOErrorExitHandler` (libX11 ≥ 1.7): lets the process survive a lost
/// connection. Not in x11-dl, so looked up at run time.
type SetIoExitHandler = unsafe extern "C" fn(
    *mut xlib::Display,
    Option<unsafe extern "C" fn(*mut xlib::Display, *mut c_void)>,
    *mut c_void,
);

type IoErrorHandler = unsafe extern "C" fn(*mut xlib::Display) -> c_int;

/// A connection opened by this library, as the process-wide hooks see it.
struct Registered {
    display: usize,
    /// Points to the connection's boxed [`ConnectionState`] (lives until unregistered).
    state: usize,
}

/// Whether a connection was lost and whether it was already closed.
struct ConnectionState {
    lost: AtomicBool,
    closed: AtomicBool,
}

/// Connections opened by this library.
static OUR_DISPLAYS: Mutex<Vec<Registered>> = Mutex::new(Vec::new());
/// XCloseDisplay, for the exit hook.
static CLOSE_DISPLAY: OnceLock<unsafe extern "C" fn(*mut xlib::Display) -> c_int> = OnceLock::new();
/// XUnlockDisplay, for the I/O-error exit handler.
static UNLOCK_DISPLAY: OnceLock<unsafe extern "C" fn(*mut xlib::Display)> = OnceLock::new();

/// At process exit, closes the connections that were lost and not yet
/// closed: otherwise the GL libraries' own exit-time cleanup would try to
/// lock a dead connection and hang the exiting process.
extern "C" fn close_lost_connections_at_exit() {
    let Ok(list) = OUR_DISPLAYS.lock() else {
        return;
    };
    let Some(close) = CLOSE_DISPLAY.get() else {
        return;
    };
    for r in list.iter() {
        // SAFETY: registered states outlive their registration.
        let st = unsafe { &*(r.state as *const ConnectionState) };
        if st.lost.load(Ordering::SeqCst) && !st.closed.swap(true, Ordering::SeqCst) {
            // SAFETY: a connection of ours, never closed (checked above).
            unsafe { close(r.display as *mut xlib::Display) };
        }
    }
}
/// The process's I/O error handler before ours was installed.
static PREVIOUS_IO_HANDLER: OnceLock<Option<IoErrorHandler>> = OnceLock::new();

/// Xlib's I/O error handler is process-wide and its default calls exit().
/// For the library's own connections this handler returns, so Xlib goes on
/// to the connection's exit handler ([`on_io_error_exit`]), which records the
/// loss; the program's connections go to whatever handler it had.
unsafe extern "C" fn on_io_error(display: *mut xlib::Display) -> c_int {
    let ours = OUR_DISPLAYS
        .lock()
        .map(|v| v.iter().any(|r| r.display == display as usize))
        .unwrap_or(false);
    if ours {
        return 0;
    }
    match PREVIOUS_IO_HANDLER.get().copied().flatten() {
        // SAFETY: the handler the process installed before us, with Xlib's signature.
        Some(previous) => unsafe { previous(display) },
        // No previous handler: behave as Xlib's default does for others' connections.
        None => std::process::exit(1),
    }
}

/// Runs on the thread that met the I/O error, after Xlib marked the
/// connection dead. Xlib's `_XIOError` also takes the display's user lock
/// (XLockDisplay) and never releases it, expecting the process to exit; if
/// this thread later ends, every other thread would block on the connection
/// forever (exit-time cleanup included). Releasing it here is safe: calls on
/// a dead connection return at once.
unsafe extern "C" fn on_io_error_exit(display: *mut xlib::Display, state: *mut c_void) {
    // SAFETY: `state` is the ConnectionState boxed in GlxShared, which outlives the connection.
    unsafe {
        (*(state as *const ConnectionState))
            .lost
            .store(true, Ordering::SeqCst)
    };
    if let Some(unlock) = UNLOCK_DISPLAY.get() {
        // SAFETY: this thread holds the user lock _XIOError took.
        unsafe { unlock(display) };
    }
}

/// The first X protocol error code seen while a trap is set (0 = none).
static TRAPPED: AtomicI32 = AtomicI32::new(0);
/// Serialises traps: the error handler is process-wide.
static TRAP_LOCK: Mutex<()> = Mutex::new(());
/// The connection a trap covers, and the serial of its first request.
static TRAP_DISPLAY: AtomicUsize = AtomicUsize::new(0);
static TRAP_SERIAL: AtomicU64 = AtomicU64::new(0);
/// The error handler the trap replaced (Xlib's default when none was set).
static TRAP_PREVIOUS: Mutex<Option<XErrorHandler>> = Mutex::new(None);

type XErrorHandler = unsafe extern "C" fn(*mut xlib::Display, *mut xlib::XErrorEvent) -> c_int;

unsafe extern "C" fn on_x_error(
    display: *mut xlib::Display,
    event: *mut xlib::XErrorEvent,
) -> c_int {
    // SAFETY: Xlib passes a valid event.
    let (code, serial) = unsafe { ((*event).error_code as i32, (*event).serial) };
    if display as usize == TRAP_DISPLAY.load(Ordering::SeqCst)
        && serial >= TRAP_SERIAL.load(Ordering::SeqCst)
    {
        let _ = TRAPPED.compare_exchange(0, code, Ordering::SeqCst, Ordering::SeqCst);
        return 0;
    }
    // An error of a request the trap does not cover (another connection,
    // or a request sent before it): handled as it would be without the trap.
    let previous = *TRAP_PREVIOUS.lock().unwrap_or_else(|e| e.into_inner());
    match previous {
        // SAFETY: the process's handler, with Xlib's signature.
        Some(h) => unsafe { h(display, event) },
        None => 0,
    }
}

/// Runs `f`, whose X requests go to `display`, with the protocol errors of
/// those requests trapped, and returns the first error code (0 = none).
/// Errors of earlier requests on the connection, and of other connections,
/// still reach the process's own error handler: a program's connection can
/// be used (the LD_PRELOAD interposer does) without hiding the program's
/// errors from it. Ends with an XSync, so every error of `f` has arrived.
pub(crate) fn trap_x_errors<T>(
    xlib: &Xlib,
    display: *mut xlib::Display,
    f: impl FnOnce() -> T,
) -> (T, i32) {
    trap_errors(xlib, display, true, f)
}

/// [`trap_x_errors`] for an `f` whose last request waits for its reply
/// (XGetGeometry, XGetWindowAttributes): Xlib has handled the errors of
/// every earlier request, and of that one, when the reply (or its error)
/// arrives, so no XSync follows — one round trip instead of two.
pub(crate) fn trap_replied_x_errors<T>(
    xlib: &Xlib,
    display: *mut xlib::Display,
    f: impl FnOnce() -> T,
) -> (T, i32) {
    trap_errors(xlib, display, false, f)
}

fn trap_errors<T>(
    xlib: &Xlib,
    display: *mut xlib::Display,
    sync: bool,
    f: impl FnOnce() -> T,
) -> (T, i32) {
    let _guard = TRAP_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    TRAPPED.store(0, Ordering::SeqCst);
    TRAP_DISPLAY.store(display as usize, Ordering::SeqCst);
    // SAFETY: a valid display; XNextRequest only reads its request counter.
    TRAP_SERIAL.store(unsafe { (xlib.XNextRequest)(display) }, Ordering::SeqCst);
    // SAFETY: installs a handler that records or forwards; restored below.
    let old = unsafe { (xlib.XSetErrorHandler)(Some(on_x_error)) };
    *TRAP_PREVIOUS.lock().unwrap_or_else(|e| e.into_inner()) = old;
    // The program's handler goes back even if `f` panics (a fault the
    // caller contains must not leave the program's X errors trapped).
    let restore = Restore {
        xlib,
        display,
        old,
        sync,
    };
    let v = f();
    drop(restore);
    (v, TRAPPED.swap(0, Ordering::SeqCst))
}

/// Ends a trap: delivers its pending errors (`sync`), then puts the
/// program's handler back.
struct Restore<'a> {
    xlib: &'a Xlib,
    display: *mut xlib::Display,
    old: Option<XErrorHandler>,
    sync: bool,
}

impl Drop for Restore<'_> {
    fn drop(&mut self) {
        // SAFETY: valid display; XSync delivers pending errors to the handler.
        unsafe {
            if self.sync {
                (self.xlib.XSync)(self.display, xlib::False);
            }
            (self.xlib.XSetErrorHandler)(self.old);
        }
        TRAP_DISPLAY.store(0, Ordering::SeqCst);
    }
}

/// One X connection with GLX, shared by the display and its surfaces.
struct GlxShared {
    xlib: Xlib,
    glx: Glx,
    display: *mut xlib::Display,
    screen: c_int,
    wm_delete: xlib::Atom,
    state: Box<ConnectionState>,
    name: String,
}

// SAFETY: XInitThreads is called before the connection is opened, which
// makes Xlib calls on one Display safe from any thread; GLX calls follow GL's
// one-current-context-per-thread rule, which the surface layer enforces.
unsafe impl Send for GlxShared {}
// SAFETY: as above.
unsafe impl Sync for GlxShared {}

impl GlxShared {
    fn check_alive(&self) -> Result<()> {
        if self.state.lost.load(Ordering::SeqCst) {
            Err(Error::DisplayLost(format!(
                "the connection to X display {} was lost (the server exited?): \
                 destroy the surfaces and open a new display",
                self.name
            )))
        } else {
            Ok(())
        }
    }

    /// Runs `f` with X protocol errors trapped; returns the first error code.
    fn trap<T>(&self, f: impl FnOnce() -> T) -> (T, i32) {
        trap_x_errors(&self.xlib, self.display, f)
    }

    /// glXChooseVisual for a request; None when the server has no match.
    fn choose_visual(&self, request: &ConfigRequest, stereo: bool) -> Option<xlib::XVisualInfo> {
        let mut list = vec![
            attr::GLX_RGBA,
            attr::GLX_DOUBLEBUFFER,
            attr::GLX_RED_SIZE,
            request.color[0].max(1) as i32,
            attr::GLX_GREEN_SIZE,
            request.color[1].max(1) as i32,
            attr::GLX_BLUE_SIZE,
            request.color[2].max(1) as i32,
        ];
        if stereo {
            list.push(attr::GLX_STEREO);
        }
        list.push(0);
        // SAFETY: valid display and a None-terminated list; the result is
        // copied and freed with XFree.
        unsafe {
            let vi = (self.glx.glXChooseVisual)(self.display, self.screen, list.as_mut_ptr());
            if vi.is_null() {
                return None;
            }
            let info = *vi;
            (self.xlib.XFree)(vi.cast());
            Some(info)
        }
    }
}

impl Drop for GlxShared {
    fn drop(&mut self) {
        let mut list = OUR_DISPLAYS.lock().unwrap_or_else(|e| e.into_inner());
        // Closed even when the connection is lost: XCloseDisplay runs the
        // close hooks of the GL libraries (glvnd forgets the display), then
        // frees it; its requests fail through the handlers that return.
        if !self.state.closed.swap(true, Ordering::SeqCst) {
            // SAFETY: the last reference: no surface uses the connection any more.
            unsafe { (self.xlib.XCloseDisplay)(self.display) };
        }
        list.retain(|r| r.display != self.display as usize);
    }
}

/// The window visual chosen for a configuration.
struct GlxVisual {
    info: xlib::XVisualInfo,
}

// SAFETY: the Visual pointer belongs to the connection's immutable screen
// data, valid for the connection's lifetime.
unsafe impl Send for GlxVisual {}
// SAFETY: as above.
unsafe impl Sync for GlxVisual {}

/// The GLX backend.
pub struct GlxPlatform {
    shared: Arc<GlxShared>,
}

impl GlxPlatform {
    /// Opens the X display `name` (None: $DISPLAY) and checks for GLX.
    pub fn open(name: Option<&str>) -> Result<GlxPlatform> {
        let xlib = Xlib::open().map_err(|e| {
            Error::BackendUnavailable(format!(
                "libX11 could not be loaded ({e}): install libx11-6, or {}",
                no_display_hint()
            ))
        })?;
        let glx = Glx::open().map_err(|e| {
            Error::BackendUnavailable(format!(
                "libGL could not be loaded ({e}): install libgl1 and libglx-mesa0 (Debian), or use GLSTEREO_BACKEND=egl"
            ))
        })?;
        static THREADS: OnceLock<()> = OnceLock::new();
        // SAFETY: XInitThreads before this library's first connection.
        THREADS.get_or_init(|| unsafe {
            (xlib.XInitThreads)();
        });
        let shown = name
            .map(str::to_owned)
            .or_else(|| std::env::var("DISPLAY").ok())
            .filter(|s| !s.is_empty());
        let Some(shown) = shown else {
            return Err(Error::BackendUnavailable(format!(
                "no X display: $DISPLAY is not set; {}",
                no_display_hint()
            )));
        };
        let cname = CString::new(shown.clone())
            .map_err(|_| Error::invalid_value("display name contains NUL"))?;
        // SAFETY: NUL-terminated name.
        let display = unsafe { (xlib.XOpenDisplay)(cname.as_ptr()) };
        if display.is_null() {
            return Err(Error::BackendUnavailable(format!(
                "cannot open X display {shown:?}: {}",
                no_display_hint()
            )));
        }
        let state = Box::new(ConnectionState {
            lost: AtomicBool::new(false),
            closed: AtomicBool::new(false),
        });
        // SAFETY: valid display; libX11's own symbol, looked up by name.
        unsafe {
            if let Ok(lib) = libloading::Library::new("libX11.so.6") {
                if let Ok(set) = lib.get::<SetIoExitHandler>(b"XSetIOErrorExitHandler") {
                    set(
                        display,
                        Some(on_io_error_exit),
                        &*state as *const ConnectionState as *mut c_void,
                    );
                }
                // libX11 stays loaded (x11-dl holds it); dropping this handle is fine.
            }
            PREVIOUS_IO_HANDLER.get_or_init(|| (xlib.XSetIOErrorHandler)(Some(on_io_error)));
        }
        UNLOCK_DISPLAY.get_or_init(|| xlib.XUnlockDisplay);
        CLOSE_DISPLAY.get_or_init(|| {
            // SAFETY: registers a plain extern "C" function once per process.
            unsafe { libc::atexit(close_lost_connections_at_exit) };
            xlib.XCloseDisplay
        });
        OUR_DISPLAYS.recover().push(Registered {
            display: display as usize,
            state: &*state as *const ConnectionState as usize,
        });
        // SAFETY: valid display.
        let screen = unsafe { (xlib.XDefaultScreen)(display) };
        let (mut err_base, mut ev_base) = (0, 0);
        // SAFETY: valid display and out-pointers.
        if unsafe { (glx.glXQueryExtension)(display, &mut err_base, &mut ev_base) } == 0 {
            // Unregistered first: `state` is freed on return, and the exit
            // hook would otherwise read it (and close this display again).
            OUR_DISPLAYS
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .retain(|r| r.display != display as usize);
            // SAFETY: valid display, closed once.
            unsafe { (xlib.XCloseDisplay)(display) };
            return Err(Error::BackendUnavailable(format!(
                "X display {shown:?} has no GLX extension: start Xvfb with GLX (the default) or use GLSTEREO_BACKEND=egl"
            )));
        }
        // SAFETY: valid display and a static name.
        let wm_delete =
            unsafe { (xlib.XInternAtom)(display, c"WM_DELETE_WINDOW".as_ptr(), xlib::False) };
        Ok(GlxPlatform {
            shared: Arc::new(GlxShared {
                xlib,
                glx,
                display,
                screen,
                wm_delete,
                state,
                name: shown,
            }),
        })
    }

    /// The Xlib `Display*` of this connection.
    pub fn x_display(&self) -> *mut c_void {
        self.shared.display.cast()
    }
}

impl Platform for GlxPlatform {
    fn kind(&self) -> BackendKind {
        BackendKind::Glx
    }

    fn choose_config(&self, request: ConfigRequest, policy: EmulationPolicy) -> Result<Config> {
        self.shared.check_alive()?;
        if let Some(why) = request.unsupported_reason() {
            return Err(Error::NoMatchingConfig(why));
        }
        let native = if request.stereo && policy != EmulationPolicy::Force {
            self.shared.choose_visual(&request, true)
        } else {
            None
        };
        let mut config = Config::choose(request, native.is_some(), policy)?;
        let info = match native {
            Some(info) => info,
            None => self.shared.choose_visual(&request, false).ok_or_else(|| {
                Error::NoMatchingConfig(format!(
                    "X display {} offers no double-buffered RGB GLX visual",
                    self.shared.name
                ))
            })?,
        };
        config.native = Some(Arc::new(GlxVisual { info }));
        Ok(config)
    }

    fn create_surface(
        &self,
        config: &Config,
        width: u32,
        height: u32,
    ) -> Result<Box<dyn PlatformSurface>> {
        let sh = &self.shared;
        sh.check_alive()?;
        let vis = config
            .native
            .as_ref()
            .and_then(|n| n.downcast_ref::<GlxVisual>())
            .ok_or_else(|| {
                Error::invalid_operation("this configuration was not chosen on a GLX display")
            })?;
        let mut info = vis.info;
        let x = &sh.xlib;
        let ((window, colormap), err) = sh.trap(|| {
            // SAFETY: valid display and visual; attributes fully initialised.
            unsafe {
                let root = (x.XRootWindow)(sh.display, info.screen);
                let colormap = (x.XCreateColormap)(sh.display, root, info.visual, xlib::AllocNone);
                let mut wa: xlib::XSetWindowAttributes = std::mem::zeroed();
                wa.colormap = colormap;
                wa.border_pixel = 0;
                wa.event_mask = xlib::StructureNotifyMask | xlib::KeyPressMask | xlib::ExposureMask;
                let window = (x.XCreateWindow)(
                    sh.display,
                    root,
                    0,
                    0,
                    width,
                    height,
                    0,
                    info.depth,
                    xlib::InputOutput as u32,
                    info.visual,
                    xlib::CWColormap | xlib::CWBorderPixel | xlib::CWEventMask,
                    &mut wa,
                );
                let mut protocols = [sh.wm_delete];
                (x.XSetWMProtocols)(sh.display, window, protocols.as_mut_ptr(), 1);
                (x.XStoreName)(sh.display, window, c"glstereo".as_ptr());
                (x.XMapWindow)(sh.display, window);
                (window, colormap)
            }
        });
        if err != 0 || window == 0 {
            return Err(Error::BackendUnavailable(format!(
                "creating a {width}x{height} window on X display {} failed (X error {err})",
                sh.name
            )));
        }
        let mut surface = GlxSurface {
            shared: sh.clone(),
            window,
            colormap,
            visual: info.visual,
            depth: info.depth,
            shm: Mutex::new(ShmSlot::Untried),
            app: std::ptr::null_mut(),
            compositor: std::ptr::null_mut(),
            state: Mutex::new(WindowState {
                size: (width, height),
                close_requested: false,
                events: VecDeque::new(),
            }),
        };
        // SAFETY: valid display and visual info; a NULL context is reported.
        unsafe {
            for direct in [xlib::True, xlib::False] {
                surface.app =
                    (sh.glx.glXCreateContext)(sh.display, &mut info, std::ptr::null_mut(), direct);
                if !surface.app.is_null() {
                    surface.compositor =
                        (sh.glx.glXCreateContext)(sh.display, &mut info, surface.app, direct);
                    break;
                }
            }
        }
        if surface.app.is_null() || surface.compositor.is_null() {
            return Err(Error::BackendUnavailable(format!(
                "glXCreateContext failed on X display {}",
                sh.name
            )));
        }
        Ok(Box::new(surface))
    }

    fn get_proc_address(&self, name: &CStr) -> *const c_void {
        // SAFETY: NUL-terminated name.
        unsafe { (self.shared.glx.glXGetProcAddressARB)(name.as_ptr().cast()) }
            .map_or(std::ptr::null(), |f| f as *const c_void)
    }
}

/// What the window's events told us.
struct WindowState {
    size: (u32, u32),
    close_requested: bool,
    events: VecDeque<WindowEvent>,
}

/// A window with two GLX contexts sharing objects.
struct GlxSurface {
    shared: Arc<GlxShared>,
    window: xlib::Window,
    colormap: xlib::Colormap,
    /// The window's visual and depth (for MIT-SHM images).
    visual: *mut xlib::Visual,
    depth: c_int,
    /// Its MIT-SHM image, when it shows CPU pixels ([`super::xshm`]).
    shm: Mutex<ShmSlot>,
    app: glx::GLXContext,
    compositor: glx::GLXContext,
    state: Mutex<WindowState>,
}

// SAFETY: see GlxShared; GLX contexts are made current on one thread at a
// time (enforced by the surface layer).
unsafe impl Send for GlxSurface {}
// SAFETY: as above.
unsafe impl Sync for GlxSurface {}

/// Queued window events kept at most (older ones are dropped).
const MAX_QUEUED_EVENTS: usize = 256;

/// The event types [`GlxSurface::pump`] takes from the queue.
const WINDOW_EVENT_TYPES: [c_int; 4] = [
    xlib::ConfigureNotify,
    xlib::ClientMessage,
    xlib::KeyPress,
    xlib::DestroyNotify,
];

/// XCheckIfEvent predicate: an event of [`WINDOW_EVENT_TYPES`] for the
/// window `arg` points to. Runs with the display locked: calls no Xlib.
unsafe extern "C" fn is_window_event(
    _display: *mut xlib::Display,
    ev: *mut xlib::XEvent,
    arg: xlib::XPointer,
) -> xlib::Bool {
    // SAFETY: Xlib passes a queued event; `arg` is the &Window pump passed.
    let (ty, window, ours) = unsafe {
        (
            (*ev).get_type(),
            (*ev).any.window,
            *arg.cast::<xlib::Window>(),
        )
    };
    (window == ours && WINDOW_EVENT_TYPES.contains(&ty)) as xlib::Bool
}

impl GlxSurface {
    /// Reads every pending event of this window, in the order they came
    /// (no round trip). Runs on every frame ([`PlatformSurface::drawable_size`]),
    /// so the queue is scanned and the connection polled once per call,
    /// not once per event type.
    fn pump(&self) {
        let sh = &self.shared;
        if sh.state.lost.load(Ordering::SeqCst) {
            return;
        }
        let mut st = self.state.recover();
        let mut window = self.window;
        // SAFETY: valid display; `ev` is a plain C union filled by Xlib; the
        // predicate reads only the event and `window`, which outlives the call.
        unsafe {
            let mut ev: xlib::XEvent = std::mem::zeroed();
            while (sh.xlib.XCheckIfEvent)(
                sh.display,
                &mut ev,
                Some(is_window_event),
                (&mut window as *mut xlib::Window).cast(),
            ) != 0
            {
                match ev.get_type() {
                    xlib::ConfigureNotify => {
                        let c = ev.configure;
                        let size = (c.width as u32, c.height as u32);
                        if c.width > 0 && c.height > 0 && size != st.size {
                            st.size = size;
                            st.events.push_back(WindowEvent::Resized(size.0, size.1));
                        }
                    }
                    xlib::ClientMessage => {
                        if ev.client_message.data.get_long(0) as xlib::Atom == sh.wm_delete {
                            st.close_requested = true;
                            st.events.push_back(WindowEvent::CloseRequested);
                        }
                    }
                    xlib::DestroyNotify => st.close_requested = true,
                    _ => {
                        let mut key = ev.key;
                        let sym = (sh.xlib.XLookupKeysym)(&mut key, 0);
                        st.events.push_back(WindowEvent::Key(sym as u32));
                    }
                }
                while st.events.len() > MAX_QUEUED_EVENTS {
                    st.events.pop_front();
                }
            }
        }
    }
}

impl PlatformSurface for GlxSurface {
    fn make_current(&self, role: ContextRole) -> Result<()> {
        self.shared.check_alive()?;
        let ctx = match role {
            ContextRole::App => self.app,
            ContextRole::Compositor => self.compositor,
        };
        // SAFETY: valid display, window and context.
        let ok = unsafe { (self.shared.glx.glXMakeCurrent)(self.shared.display, self.window, ctx) };
        self.shared.check_alive()?;
        if ok == 0 {
            return Err(Error::Gl("glXMakeCurrent failed".into()));
        }
        Ok(())
    }

    fn release_current(&self) -> Result<()> {
        if self.shared.state.lost.load(Ordering::SeqCst) {
            return Ok(());
        }
        // SAFETY: valid display; None/NULL releases the thread's context.
        unsafe { (self.shared.glx.glXMakeCurrent)(self.shared.display, 0, std::ptr::null_mut()) };
        Ok(())
    }

    fn present(&self) -> Result<()> {
        self.shared.check_alive()?;
        // SAFETY: valid display and window; the compositor context is current.
        unsafe { (self.shared.glx.glXSwapBuffers)(self.shared.display, self.window) };
        self.shared.check_alive()
    }

    fn accepts_pixels(&self) -> bool {
        !self.shm.recover().unsupported()
    }

    fn present_pixels(
        &self,
        size: (u32, u32),
        fill: &mut dyn FnMut(super::PixelTarget<'_>) -> Result<()>,
    ) -> Result<bool> {
        let sh = &self.shared;
        sh.check_alive()?;
        if size != self.state.recover().size {
            return Ok(false);
        }
        let trap = |f: &mut dyn FnMut()| sh.trap(f).1;
        // SAFETY: live connection (checked above); the window's own visual
        // and depth.
        let shown = unsafe {
            self.shm.recover().put(
                &sh.xlib,
                (sh.display, self.window),
                size,
                || {
                    ShmImage::create(
                        &sh.xlib,
                        sh.display,
                        self.window,
                        self.visual,
                        self.depth,
                        size,
                        &trap,
                    )
                },
                fill,
                &mut |put| put(),
            )?
        };
        sh.check_alive()?;
        Ok(shown)
    }

    fn drawable_size(&self) -> Option<(u32, u32)> {
        self.pump();
        Some(self.state.recover().size)
    }

    fn resize_window(&self, width: u32, height: u32) -> Result<()> {
        self.shared.check_alive()?;
        // SAFETY: valid display and window.
        unsafe {
            (self.shared.xlib.XResizeWindow)(self.shared.display, self.window, width, height);
            (self.shared.xlib.XSync)(self.shared.display, xlib::False);
        }
        self.pump();
        Ok(())
    }

    fn next_event(&self) -> Option<WindowEvent> {
        self.pump();
        self.state.recover().events.pop_front()
    }

    fn close_requested(&self) -> bool {
        self.pump();
        self.state.recover().close_requested
    }

    fn set_title(&self, title: &str) -> Result<()> {
        self.shared.check_alive()?;
        let t = CString::new(title.replace('\0', " ")).unwrap_or_default();
        // SAFETY: valid display and window; NUL-terminated title.
        unsafe {
            (self.shared.xlib.XStoreName)(self.shared.display, self.window, t.as_ptr());
            (self.shared.xlib.XFlush)(self.shared.display);
        }
        Ok(())
    }

    fn native_handles(&self) -> super::NativeHandles {
        super::NativeHandles::Glx {
            display: self.shared.display.cast(),
            window: self.window,
            context: self.app.cast(),
        }
    }
}

impl Drop for GlxSurface {
    fn drop(&mut self) {
        let sh = &self.shared;
        let alive = !sh.state.lost.load(Ordering::SeqCst);
        let connection = if alive {
            Connection::Open
        } else {
            Connection::Lost
        };
        // SAFETY: made on this connection; X calls only while it is alive.
        unsafe { self.shm.recover().release(&sh.xlib, sh.display, connection) };
        if !alive {
            return;
        }
        // SAFETY: the surface layer released these contexts from every thread
        // before dropping; valid display, window and colormap.
        unsafe {
            if !self.compositor.is_null() {
                (sh.glx.glXDestroyContext)(sh.display, self.compositor);
            }
            if !self.app.is_null() {
                (sh.glx.glXDestroyContext)(sh.display, self.app);
            }
            (sh.xlib.XDestroyWindow)(sh.display, self.window);
            (sh.xlib.XFreeColormap)(sh.display, self.colormap);
            (sh.xlib.XFlush)(sh.display);
        }
    }
}

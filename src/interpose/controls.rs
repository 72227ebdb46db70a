//! Live controls: keys in the program's window that change how its stereo
//! is shown while it runs, as NVIDIA 3D Vision's driver had them and
//! VirtualGL's configuration dialog has them for its stereo modes.
//!
//! | keys                     | change                                        | applies to |
//! |--------------------------|-----------------------------------------------|------------|
//! | Ctrl+F3 / Ctrl+F4        | separation down / up, 5 points (0 … 100 %)    | `--auto`   |
//! | Ctrl+F5 / Ctrl+F6        | convergence ÷ 1.1 / × 1.1                      | `--auto`   |
//! | Ctrl+T                   | automatic stereo off / on                     | `--auto`   |
//! | Ctrl+F2                  | eyes rendered (geometry) / made from depth    | `--auto`   |
//! | Ctrl+F7 / Ctrl+Shift+F7  | next / previous output format ([`FORMAT_CYCLE`]) | every stereo window |
//! | Ctrl+F8                  | exchange the eyes / put them back             | every stereo window |
//!
//! The first five are 3D Vision's (its "depth amount" and convergence
//! keys and its on/off key); F7 and F8 are the next free keys of that row,
//! and F2 the one before it (3D Vision had none there).
//! A change takes effect at the next frame (each setting lives in
//! [`super::live`], read at every present and draw) and is said once on
//! stderr, e.g. `glstereo: separation 20% (Ctrl+F3/F4)`.
//!
//! - Separation steps by 5 points from the current value's multiple of
//!   5 (15 → 20 → 25 …; 12 → 15 up, → 10 down), within 0 … 100.
//! - Convergence steps multiplicatively, as the user adjustments of HP's
//!   guide do ([`crate::math::adjust`]): a distance in the program's own
//!   units has no natural step. From `auto`, the first step takes over
//!   the value automatic convergence chose last
//!   ([`live::automatic_convergence`]), or 1 when it has chosen none
//!   yet, and says so; convergence stays the user's from then on.
//! - Without `--auto` the separation, convergence and Ctrl+T keys would
//!   change nothing: they are left to the program (Ctrl+T is many a
//!   program's own key), and stderr says once why.
//! - The format cycle starts from the format the program was started in
//!   (`-m`, `GLSTEREO_MODE`), then [`FORMAT_CYCLE`]; Ctrl+Shift+F7 goes
//!   the other way.
//!
//! "Ctrl" is either Control key; Shift is part of a key only where the
//! table says so; with Alt (Mod1), Super (Mod4) or AltGr (Mod5) held it
//! is not a control. Caps Lock and Num Lock make no difference. A key is
//! recognised by the symbol its key has unshifted in the keyboard map
//! (column 0 of the core map, as VirtualGL recognises its pop-up key).
//!
//! # Where the keys are taken: libxcb's event functions
//!
//! Every event reaches a program through one of three functions of
//! libxcb: `xcb_wait_for_event`, `xcb_poll_for_event` and
//! `xcb_poll_for_queued_event`. XCB programs (Qt) call them themselves;
//! libX11 — every Xlib since 1.2 is built on XCB — calls them to fill
//! its own event queue, through the dynamic linker, so the preload
//! library's definitions are the ones it gets (VirtualGL's faker
//! intercepts the same three, and Xlib's XNextEvent family above them,
//! only to watch). The preload library's exports pass each event through
//! [`filtered`], which drops the controls' key presses and releases
//! (after applying the change) and returns the next event instead:
//!
//! - `xcb_wait_for_event` waits for the next event, as it was asked to;
//!   the polls poll again, and return NULL when nothing else is there. No
//!   call blocks where it did not block before.
//! - An Xlib program never has the keys in its queue, so every Xlib
//!   function sees a consistent queue: XNextEvent, XPeekEvent,
//!   XWindowEvent, XMaskEvent, XIfEvent and XPeekIfEvent wait for the
//!   next other event, the XCheck* functions and XPending /
//!   XEventsQueued count and return only other events. Exact, not
//!   approximate, because the keys are removed before Xlib queues them.
//! - Core KeyPress / KeyRelease events (Qt 5/6, SDL2, GLFW, freeglut and
//!   plain Xlib programs take their keys so) and XInput 2 XI_KeyPress /
//!   XI_KeyRelease GenericEvents (GTK 3's) are both recognised; raw
//!   XInput 2 key events (XI_RawKeyPress, sent to the root window beside
//!   the ordinary ones) are left alone.
//! - What is approximate: a program that waits on the connection's file
//!   descriptor itself (select/poll) and then calls a blocking function
//!   without asking XPending first wakes for a control key and then
//!   blocks until the next other event. Programs that read their own
//!   events with XCB from a libxcb they opened with dlopen and looked up
//!   with dlsym on that handle do not see the keys taken: the keys reach
//!   them and change nothing.
//!
//! The keys are taken from every window of the process, not just the
//! stereo ones: toolkits put the focus on a top-level window that need
//! not be the GL window, and the settings are the process's anyway.
//!
//! # When the keys are controls
//!
//! Only in a process that has made a stereo context the layer presents
//! (the GLX layer arms the keys when it makes the first one, for the
//! rest of the process) or, under `--auto`, any GL context (all of them
//! become automatic-stereo contexts). Until then — and in every program without stereo — each
//! event function costs one atomic load and a branch more than libxcb's
//! own, and every key reaches the program. `GLSTEREO_KEYS=0` turns the
//! controls off altogether. Stereo the layer does not present (a
//! driver's or VirtualGL's own quad buffer, used as it is when no format
//! was chosen) does not arm them.
//!
//! # The layer's own X connection
//!
//! Nothing may be asked of the program's connection from inside its
//! event read: libX11 reads events with its Display locked, and a
//! request there (XGetKeyboardMapping, XSendEvent) would wait for that
//! lock forever. So arming opens a connection of the layer's own to the
//! same server (with libxcb, which every X program has loaded), and
//! everything the controls ask of the server goes through it:
//!
//! - XInput's major opcode (to know its GenericEvents), asked once;
//! - the keyboard map, read when the controls are armed and again when
//!   a control's key is pressed after the server said the map changed
//!   (xmodmap, setxkbmap): a MappingNotify on this connection, which never
//!   asks for XKB and so is sent the core event for every change (the
//!   program's own connection need not get one: libX11 initialises XKB
//!   in XOpenDisplay, and an XKB client is told only through the XKB
//!   events it selected);
//! - the repaint request: a program that redraws only for Expose events
//!   (most event-driven viewers) would show a change only at its next
//!   redraw, so after each change the windows the layer presented lately
//!   (up to [`REMEMBERED_WINDOWS`], as [`presented`] records them) are
//!   sent an Expose event of their whole area. The server delivers it
//!   only to a program that selected Expose events on the window; a
//!   program that draws continuously draws one frame more.

use std::ffi::c_void;
use std::io::Write;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU8, AtomicU64, Ordering};

use x11_dl::keysym;
use x11_dl::xlib::{Display, Xlib};

use super::{live, settings};
use crate::output::{AnaglyphColors, AnaglyphMethod, OutputMode};

/// `GLSTEREO_KEYS=0` (or `false`, `no`): no live controls, every key
/// reaches the program. Default: on.
pub const ENV_KEYS: &str = "GLSTEREO_KEYS";

/// A change the user asks for with a key.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// Ctrl+F3.
    SeparationDown,
    /// Ctrl+F4.
    SeparationUp,
    /// Ctrl+F5.
    ConvergenceDown,
    /// Ctrl+F6.
    ConvergenceUp,
    /// Ctrl+T.
    AutoToggle,
    /// Ctrl+F2: `--auto`'s two kinds ([`live::AutoMode`]).
    AutoModeToggle,
    /// Ctrl+F7.
    NextFormat,
    /// Ctrl+Shift+F7.
    PreviousFormat,
    /// Ctrl+F8.
    SwapEyes,
}

impl Control {
    /// Whether it changes automatic stereo, and so is a control only
    /// under `--auto`.
    pub fn automatic_only(self) -> bool {
        matches!(
            self,
            Control::SeparationDown
                | Control::SeparationUp
                | Control::ConvergenceDown
                | Control::ConvergenceUp
                | Control::AutoToggle
                | Control::AutoModeToggle
        )
    }
}

/// A key the controls use, by the symbol its key has unshifted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Key {
    F3 = 1,
    F4,
    F5,
    F6,
    F7,
    F8,
    T,
    F2,
}

impl Key {
    const ALL: [Key; 8] = [
        Key::F3,
        Key::F4,
        Key::F5,
        Key::F6,
        Key::F7,
        Key::F8,
        Key::T,
        Key::F2,
    ];

    fn keysym(self) -> u32 {
        match self {
            Key::F3 => keysym::XK_F3,
            Key::F4 => keysym::XK_F4,
            Key::F5 => keysym::XK_F5,
            Key::F6 => keysym::XK_F6,
            Key::F7 => keysym::XK_F7,
            Key::F8 => keysym::XK_F8,
            Key::F2 => keysym::XK_F2,
            Key::T => keysym::XK_t,
        }
    }

    fn of_keysym(sym: u64) -> Option<Key> {
        Key::ALL.into_iter().find(|k| u64::from(k.keysym()) == sym)
    }

    fn from_code(v: u8) -> Option<Key> {
        Key::ALL.into_iter().find(|&k| k as u8 == v)
    }
}

/// X's modifier bits in a key event's state field.
const SHIFT: u32 = 1 << 0;
const CONTROL: u32 = 1 << 2;
const MOD1: u32 = 1 << 3;
const MOD4: u32 = 1 << 6;
const MOD5: u32 = 1 << 7;

/// The control a press of `key` is with the modifiers of `state`.
fn control_of(key: Key, state: u32) -> Option<Control> {
    let shift = match state & (SHIFT | CONTROL | MOD1 | MOD4 | MOD5) {
        CONTROL => false,
        s if s == CONTROL | SHIFT => true,
        _ => return None,
    };
    Some(match (key, shift) {
        (Key::F3, false) => Control::SeparationDown,
        (Key::F4, false) => Control::SeparationUp,
        (Key::F5, false) => Control::ConvergenceDown,
        (Key::F6, false) => Control::ConvergenceUp,
        (Key::T, false) => Control::AutoToggle,
        (Key::F2, false) => Control::AutoModeToggle,
        (Key::F7, false) => Control::NextFormat,
        (Key::F7, true) => Control::PreviousFormat,
        (Key::F8, false) => Control::SwapEyes,
        _ => return None,
    })
}

/// A key event, from a core KeyPress / KeyRelease.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct KeyEvent {
    press: bool,
    keycode: u8,
    state: u32,
}

/// What one event is to the controls.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Seen {
    Key(KeyEvent),
    Other,
}

/// Core event codes (the response type without the send-event bit).
const KEY_PRESS: u8 = 2;
const KEY_RELEASE: u8 = 3;
const GENERIC_EVENT: u8 = 35;
/// XInput 2's event types (a GenericEvent's `evtype`).
const XI_KEY_PRESS: u16 = 2;
const XI_KEY_RELEASE: u16 = 3;
/// Bytes of an XInput 2 key event as libxcb returns it up to its
/// effective modifiers (wire bytes 72..76, moved 4 on by libxcb's full
/// sequence number after byte 32).
const XI_KEY_EVENT_BYTES: usize = 80;

/// Reads an event as libxcb returns it: 32 bytes of the X protocol's
/// event, then the full sequence number, then (a GenericEvent) the rest
/// of the protocol's event. A core key event's detail is its keycode, its
/// state a 16-bit field at byte 28; an XInput 2 key event (a
/// GenericEvent of extension `xi_opcode`, 0 when the server has none)
/// has its type at byte 8, its keycode at 16 and its effective modifiers
/// (the core state's bits) at 76.
fn parse(ev: &[u8], xi_opcode: u8) -> Seen {
    let u16_at = |i: usize| u16::from_ne_bytes([ev[i], ev[i + 1]]);
    let u32_at = |i: usize| u32::from_ne_bytes([ev[i], ev[i + 1], ev[i + 2], ev[i + 3]]);
    if ev.len() < 32 {
        return Seen::Other;
    }
    match ev[0] & 0x7f {
        t @ (KEY_PRESS | KEY_RELEASE) => Seen::Key(KeyEvent {
            press: t == KEY_PRESS,
            keycode: ev[1],
            state: u32::from(u16_at(28)),
        }),
        GENERIC_EVENT if xi_opcode != 0 && ev[1] == xi_opcode && ev.len() >= XI_KEY_EVENT_BYTES => {
            let t = u16_at(8);
            match u8::try_from(u32_at(16)) {
                Ok(keycode) if t == XI_KEY_PRESS || t == XI_KEY_RELEASE => Seen::Key(KeyEvent {
                    press: t == XI_KEY_PRESS,
                    keycode,
                    state: u32_at(76),
                }),
                _ => Seen::Other,
            }
        }
        _ => Seen::Other,
    }
}

/// The bytes of an event libxcb returned: 32, or for a GenericEvent
/// 36 + 4 × its length field (libxcb adds the full sequence number after
/// byte 32). A GenericEvent claiming more than 1 MiB is read as its first
/// 32 bytes.
///
/// # Safety
/// `ev` must be an event as libxcb returns it.
unsafe fn event_bytes<'a>(ev: *const u8) -> &'a [u8] {
    // SAFETY: every libxcb event has at least 32 bytes.
    let head = unsafe { std::slice::from_raw_parts(ev, 32) };
    if head[0] & 0x7f != GENERIC_EVENT {
        return head;
    }
    let words = u32::from_ne_bytes([head[4], head[5], head[6], head[7]]) as usize;
    if words > (1 << 18) {
        return head;
    }
    // SAFETY: libxcb allocated 32 + 4 + 4 × length bytes for it.
    unsafe { std::slice::from_raw_parts(ev, 36 + 4 * words) }
}

/// What becomes of a key event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Decision {
    /// The program gets it.
    Pass,
    /// The program gets it: a key of automatic stereo without `--auto`.
    PassNotAutomatic,
    /// Taken: the release of a key whose press was taken.
    TakeRelease,
    /// Taken, and the change made.
    Apply(Control),
}

/// The rule: `key` is what the event's keycode is in the keyboard map,
/// `press_taken` whether the last press of that keycode was taken.
fn decide(ev: KeyEvent, key: Option<Key>, press_taken: bool, automatic: bool) -> Decision {
    if !ev.press {
        return if press_taken {
            Decision::TakeRelease
        } else {
            Decision::Pass
        };
    }
    match key.and_then(|k| control_of(k, ev.state)) {
        Some(c) if c.automatic_only() && !automatic => Decision::PassNotAutomatic,
        Some(c) => Decision::Apply(c),
        None => Decision::Pass,
    }
}

/// Separation after one step: the next multiple of 5 up or down, within
/// 0 … 100.
fn step_separation(s: f32, up: bool) -> f32 {
    let s = if s.is_finite() {
        s
    } else {
        live::DEFAULT_SEPARATION
    };
    let n = if up {
        (s / 5.0).floor() + 1.0
    } else {
        (s / 5.0).ceil() - 1.0
    };
    (n * 5.0).clamp(0.0, 100.0)
}

/// The factor of one convergence step.
const CONVERGENCE_STEP: f32 = 1.1;

/// Where a convergence step started.
#[derive(Clone, Copy, Debug, PartialEq)]
enum StepFrom {
    /// The user's value.
    Set,
    /// Automatic convergence's last value.
    Automatic(f32),
    /// Automatic, with no value chosen yet: 1.
    Unknown,
}

/// Convergence after one step from `set` (None: automatic, whose last
/// value is `automatic`): × or ÷ 1.1. A result that is not a finite
/// distance > 0 keeps the value.
fn step_convergence(set: Option<f32>, automatic: Option<f32>, up: bool) -> (f32, StepFrom) {
    let (from, how) = match (set, automatic) {
        // A program may have set 0 or less (glStereoParameterfNV), which
        // no factor moves: the keys step from automatic's value or 1.
        (Some(c), _) if c > 0.0 => (c, StepFrom::Set),
        (_, Some(a)) => (a, StepFrom::Automatic(a)),
        (_, None) => (1.0, StepFrom::Unknown),
    };
    let to = if up {
        from * CONVERGENCE_STEP
    } else {
        from / CONVERGENCE_STEP
    };
    if to.is_finite() && to > 0.0 {
        (to, how)
    } else {
        (from, how)
    }
}

/// The formats Ctrl+F7 goes through after the one the program started
/// in: the two-eyes-in-one-frame layouts first (they show at a glance
/// that the key worked), then the other glasses and single eyes. The
/// formats for special hardware (frame-sequential, HDMI frame packing,
/// Starbase, STR_RECT, the half-colour and monochrome anaglyphs) are
/// chosen with `-m`.
pub const FORMAT_CYCLE: [OutputMode; 13] = [
    OutputMode::Anaglyph(AnaglyphColors::RedCyan, AnaglyphMethod::FullColor),
    OutputMode::SideBySide,
    OutputMode::TopBottom,
    OutputMode::SideBySideHalf,
    OutputMode::TopBottomHalf,
    OutputMode::Rows,
    OutputMode::Columns,
    OutputMode::Checkerboard,
    OutputMode::Anaglyph(AnaglyphColors::RedCyan, AnaglyphMethod::Dubois),
    OutputMode::Anaglyph(AnaglyphColors::GreenMagenta, AnaglyphMethod::FullColor),
    OutputMode::Anaglyph(AnaglyphColors::AmberBlue, AnaglyphMethod::FullColor),
    OutputMode::Left,
    OutputMode::Right,
];

/// The format after `now` (forward) or before it, in the cycle that
/// starts with `start` and goes on with [`FORMAT_CYCLE`].
fn next_format(start: OutputMode, now: OutputMode, forward: bool) -> OutputMode {
    let cycle: Vec<OutputMode> = std::iter::once(start)
        .chain(FORMAT_CYCLE.into_iter().filter(|&m| m != start))
        .collect();
    let n = cycle.len();
    match cycle.iter().position(|&m| m == now) {
        Some(i) if forward => cycle[(i + 1) % n],
        Some(i) => cycle[(i + n - 1) % n],
        None => cycle[0],
    }
}

/// A number as the messages say it: at most 4 significant digits, no
/// trailing zeros.
fn short(v: f32) -> String {
    let digits = if v > 0.0 && v.is_finite() {
        (3 - v.log10().floor() as i32).clamp(0, 8) as usize
    } else {
        0
    };
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// Makes the change and says what it is now (the stderr line without
/// the `glstereo: ` prefix).
fn apply(c: Control) -> String {
    match c {
        Control::SeparationDown | Control::SeparationUp => {
            let s = step_separation(live::separation(), c == Control::SeparationUp);
            live::set_separation(s);
            let limit = match s {
                0.0 => ", the least",
                100.0 => ", the most",
                _ => "",
            };
            format!("separation {}%{limit} (Ctrl+F3/F4)", short(s))
        }
        Control::ConvergenceDown | Control::ConvergenceUp => {
            let (v, from) = step_convergence(
                live::convergence(),
                live::automatic_convergence(),
                c == Control::ConvergenceUp,
            );
            live::set_convergence(Some(v));
            let how = match from {
                StepFrom::Set => String::new(),
                StepFrom::Automatic(a) => {
                    format!(", set by hand from automatic convergence's {}", short(a))
                }
                StepFrom::Unknown => {
                    ", set by hand from 1 (automatic convergence had chosen no value yet)"
                        .to_owned()
                }
            };
            format!("convergence {}{how} (Ctrl+F5/F6)", short(v))
        }
        Control::AutoToggle => {
            let on = !live::auto_on();
            live::set_auto_on(on);
            format!(
                "automatic stereo {} (Ctrl+T)",
                if on { "on" } else { "off" }
            )
        }
        Control::AutoModeToggle => {
            let mode = match live::auto_mode() {
                live::AutoMode::Geometry => live::AutoMode::Depth,
                live::AutoMode::Depth => live::AutoMode::Geometry,
            };
            live::set_auto_mode(mode);
            format!(
                "automatic stereo {} (Ctrl+F2)",
                match mode {
                    live::AutoMode::Geometry => "renders both eyes (geometry)",
                    live::AutoMode::Depth => "makes both eyes from one render's depth (depth)",
                }
            )
        }
        Control::NextFormat | Control::PreviousFormat => {
            let m = next_format(
                settings::window_mode(),
                live::mode(),
                c == Control::NextFormat,
            );
            live::set_mode(m);
            format!("format {m} (Ctrl+F7; Ctrl+Shift+F7 back)")
        }
        Control::SwapEyes => {
            let swap = !live::swap_eyes();
            live::set_swap_eyes(swap);
            format!(
                "eyes {} (Ctrl+F8)",
                if swap { "exchanged" } else { "in order" }
            )
        }
    }
}

/// Whether `GLSTEREO_KEYS` leaves the controls on.
fn enabled() -> bool {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ON.get_or_init(
        || match std::env::var(ENV_KEYS).ok().as_deref().map(str::trim) {
            None | Some("") => true,
            Some(v) => match v.to_ascii_lowercase().as_str() {
                "1" | "true" | "yes" => true,
                "0" | "false" | "no" => false,
                _ => {
                    super::warn(&format!(
                        "{ENV_KEYS}={v:?} is not 0 or 1; the live keys are on"
                    ));
                    true
                }
            },
        },
    )
}

/// The keys' state, read by every event of an armed process.
struct Keys {
    /// The process has a stereo (or automatic) context: events are looked at.
    armed: AtomicBool,
    /// By keycode: the [`Key`] its unshifted symbol is (0: none).
    map: [AtomicU8; 256],
    /// Keycodes whose last press was taken: their release is taken too.
    taken: [AtomicU64; 4],
}

static KEYS: Keys = Keys {
    armed: AtomicBool::new(false),
    map: [const { AtomicU8::new(0) }; 256],
    taken: [const { AtomicU64::new(0) }; 4],
};

impl Keys {
    fn key(&self, keycode: u8) -> Option<Key> {
        Key::from_code(self.map[usize::from(keycode)].load(Ordering::Relaxed))
    }

    fn taken(&self, keycode: u8) -> bool {
        let (word, bit) = (usize::from(keycode) / 64, keycode % 64);
        self.taken[word].load(Ordering::Relaxed) & (1 << bit) != 0
    }

    fn set_taken(&self, keycode: u8, taken: bool) {
        let (word, bit) = (usize::from(keycode) / 64, keycode % 64);
        if taken {
            self.taken[word].fetch_or(1 << bit, Ordering::Relaxed);
        } else {
            self.taken[word].fetch_and(!(1 << bit), Ordering::Relaxed);
        }
    }
}

/// Whether the process's events are looked at (the preload's exports test
/// this first: an unarmed process pays one load and a branch).
#[inline]
pub fn armed() -> bool {
    KEYS.armed.load(Ordering::Acquire)
}

/// The layer's own X connection, opened when the controls are armed.
static OWN: Mutex<Option<own::Own>> = Mutex::new(None);

/// XInput's major opcode on the server (0: none), the `extension` of its
/// GenericEvents.
static XI_OPCODE: AtomicU8 = AtomicU8::new(0);

/// Arms the controls for a process that has a stereo context on `dpy`
/// (or an automatic one): opens the layer's own connection to the same
/// X server and reads the keyboard map. Called by the GLX layer in the
/// program's GLX call; a no-op once armed, and with `GLSTEREO_KEYS=0`.
pub(crate) fn arm(xlib: &Xlib, dpy: *mut Display) {
    if armed() || dpy.is_null() || !enabled() {
        return;
    }
    let mut slot = OWN.lock().unwrap_or_else(|e| e.into_inner());
    if armed() {
        return;
    }
    // SAFETY: a valid display (the caller's GLX call succeeded on it);
    // XDisplayString returns the display's own NUL-terminated name.
    let name = unsafe { (xlib.XDisplayString)(dpy) };
    if name.is_null() {
        return;
    }
    // SAFETY: as above.
    let name = unsafe { std::ffi::CStr::from_ptr(name) };
    let Some(own) = own::Own::open(dpy as usize, name) else {
        super::warn(&format!(
            "no X connection of the layer's own could be opened to {}: the live keys are off",
            name.to_string_lossy()
        ));
        return;
    };
    own.read_keyboard();
    XI_OPCODE.store(own.extension_opcode(c"XInputExtension"), Ordering::Relaxed);
    *slot = Some(own);
    KEYS.armed.store(true, Ordering::Release);
}

/// Reads the keyboard map again when the server said it changed (a
/// MappingNotify on the layer's connection, which, never having asked
/// for XKB, gets the core event for every change: xmodmap, setxkbmap,
/// XChangeKeyboardMapping).
fn follow_keyboard() {
    if let Some(own) = OWN.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
        if own.keyboard_changed() {
            own.read_keyboard();
        }
    }
}

/// Looks at one event of an armed process: true when it is taken (a
/// control's key press, whose change is made here, or its release).
fn take(ev: &[u8]) -> bool {
    let Seen::Key(k) = parse(ev, XI_OPCODE.load(Ordering::Relaxed)) else {
        return false;
    };
    // Only a press with Control held can be a control: only then is the
    // keyboard map looked at (and first brought up to date).
    if k.press && k.state & CONTROL != 0 {
        follow_keyboard();
    }
    let decision = decide(
        k,
        KEYS.key(k.keycode),
        KEYS.taken(k.keycode),
        live::auto_requested(),
    );
    // A press starts over: a release lost (focus moved away meanwhile)
    // does not take the key's next release.
    if k.press {
        KEYS.set_taken(k.keycode, matches!(decision, Decision::Apply(_)));
    }
    match decision {
        Decision::Pass => false,
        Decision::PassNotAutomatic => {
            super::warn(
                "Ctrl+F2 to Ctrl+F6 and Ctrl+T change automatic stereo, which this program \
                 does not have (glstereo-run --auto): those keys go to the program",
            );
            false
        }
        Decision::TakeRelease => {
            KEYS.set_taken(k.keycode, false);
            true
        }
        Decision::Apply(c) => {
            let said = apply(c);
            // Not eprintln: a failing stderr must not panic here.
            let _ = writeln!(std::io::stderr(), "glstereo: {said}");
            repaint();
            true
        }
    }
}

/// An event-reading function of libxcb: `xcb_wait_for_event`,
/// `xcb_poll_for_event` or `xcb_poll_for_queued_event`.
pub type NextEvent = unsafe extern "C" fn(*mut c_void) -> *mut c_void;

/// What the preload library's event functions return in an armed process:
/// `next`'s events on connection `c`, without the controls' keys (each
/// taken event is freed and the next one read the same way: waited for,
/// or polled). NULL as `next` returns it; a NULL connection gets NULL
/// (libxcb would crash on it).
///
/// # Safety
/// `next` must be one of libxcb's event functions (or a layer's standing
/// for it) and `c` a connection it accepts, or NULL.
pub unsafe fn filtered(c: *mut c_void, next: NextEvent) -> *mut c_void {
    if c.is_null() {
        return std::ptr::null_mut();
    }
    loop {
        // SAFETY: the caller's function and connection.
        let ev = unsafe { next(c) };
        if ev.is_null() {
            return ev;
        }
        // SAFETY: an event as libxcb returns it.
        let bytes = unsafe { event_bytes(ev.cast()) };
        let taken = std::panic::catch_unwind(|| take(bytes)).unwrap_or(false);
        if !taken {
            return ev;
        }
        // SAFETY: libxcb's events are malloc'ed and the caller's to free;
        // this one is not handed out.
        unsafe { libc::free(ev) };
    }
}

/// How many windows [`presented`] remembers for the repaint request.
pub const REMEMBERED_WINDOWS: usize = 16;

/// A window the layer presented: `(Display*, X window, width, height)`.
type Shown = (usize, u64, u16, u16);

static SHOWN: Mutex<Vec<Shown>> = Mutex::new(Vec::new());

/// The layer presented a frame in X window `window` of `display`, of
/// `width` x `height` pixels: remembered for the repaint request after a
/// change (the most recent [`REMEMBERED_WINDOWS`]).
pub fn presented(display: usize, window: u64, width: u32, height: u32) {
    if !armed() {
        return;
    }
    let entry = (
        display,
        window,
        width.min(u16::MAX as u32) as u16,
        height.min(u16::MAX as u32) as u16,
    );
    let mut shown = SHOWN.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(i) = shown.iter().position(|s| s.0 == display && s.1 == window) {
        shown[i] = entry;
        return;
    }
    if shown.len() == REMEMBERED_WINDOWS {
        shown.remove(0);
    }
    shown.push(entry);
}

/// After a change: an Expose event for each window shown lately, so that
/// a program that draws only when exposed shows the change now.
fn repaint() {
    let windows: Vec<Shown> = SHOWN.lock().unwrap_or_else(|e| e.into_inner()).clone();
    if let Some(own) = OWN.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
        own.expose(&windows);
    }
}

/// The layer's own X connection: libxcb's functions (libxcb's own, under
/// every layer: this connection is the layer's business alone) and the
/// connection.
mod own {
    use std::ffi::{CStr, c_char, c_int, c_uint, c_void};
    use std::sync::atomic::Ordering;

    use super::{KEYS, Key, NextEvent, Shown};

    type Connect = unsafe extern "C" fn(*const c_char, *mut c_int) -> *mut c_void;
    type HasError = unsafe extern "C" fn(*mut c_void) -> c_int;
    type GetSetup = unsafe extern "C" fn(*mut c_void) -> *const u8;
    type SendEvent = unsafe extern "C" fn(*mut c_void, u8, u32, u32, *const c_char) -> c_uint;
    type Flush = unsafe extern "C" fn(*mut c_void) -> c_int;
    type GetKeyboardMapping = unsafe extern "C" fn(*mut c_void, u8, u8) -> c_uint;
    type GetKeyboardMappingReply =
        unsafe extern "C" fn(*mut c_void, c_uint, *mut *mut c_void) -> *mut u8;
    type QueryExtension = unsafe extern "C" fn(*mut c_void, u16, *const c_char) -> c_uint;
    type QueryExtensionReply =
        unsafe extern "C" fn(*mut c_void, c_uint, *mut *mut c_void) -> *mut u8;
    type Keysyms = unsafe extern "C" fn(*const u8) -> *const u32;
    type KeysymsLength = unsafe extern "C" fn(*const u8) -> c_int;

    /// ExposureMask: only clients that selected Expose events get one.
    const EXPOSURE_MASK: u32 = 1 << 15;
    /// The core Expose and MappingNotify event codes.
    const EXPOSE: u8 = 12;
    const MAPPING_NOTIFY: u8 = 34;
    /// MappingNotify's `request` for the keyboard map.
    const MAPPING_KEYBOARD: u8 = 1;

    pub(super) struct Own {
        /// The program's `Display*` the connection was opened beside: its
        /// windows are on this connection's server.
        display: usize,
        conn: *mut c_void,
        get_setup: GetSetup,
        send_event: SendEvent,
        flush: Flush,
        poll: NextEvent,
        get_keyboard_mapping: GetKeyboardMapping,
        get_keyboard_mapping_reply: GetKeyboardMappingReply,
        keysyms: Keysyms,
        keysyms_length: KeysymsLength,
        query_extension: QueryExtension,
        query_extension_reply: QueryExtensionReply,
    }

    // SAFETY: an xcb connection may be used from any thread (libxcb locks
    // it); the rest are function addresses. Used under `super::OWN`'s lock.
    unsafe impl Send for Own {}

    fn libxcb(name: &CStr) -> *mut c_void {
        super::super::next::own_symbol_in(name, c"libxcb.so.1")
    }

    impl Own {
        /// Connects to display `name`, the name of the program's
        /// `display`; None when libxcb lacks a function (it cannot: they
        /// are libxcb's core) or the server refuses.
        pub(super) fn open(display: usize, name: &CStr) -> Option<Own> {
            let names = [
                c"xcb_connect",
                c"xcb_connection_has_error",
                c"xcb_get_setup",
                c"xcb_send_event",
                c"xcb_flush",
                c"xcb_poll_for_event",
                c"xcb_get_keyboard_mapping",
                c"xcb_get_keyboard_mapping_reply",
                c"xcb_get_keyboard_mapping_keysyms",
                c"xcb_get_keyboard_mapping_keysyms_length",
                c"xcb_query_extension",
                c"xcb_query_extension_reply",
            ];
            let f: Vec<*mut c_void> = names.iter().map(|n| libxcb(n)).collect();
            if f.iter().any(|p| p.is_null()) {
                return None;
            }
            // SAFETY: libxcb's functions, each transmuted to its xcb.h /
            // xproto.h signature.
            unsafe {
                use std::mem::transmute as t;
                let connect = t::<*mut c_void, Connect>(f[0]);
                let has_error = t::<*mut c_void, HasError>(f[1]);
                let conn = connect(name.as_ptr(), std::ptr::null_mut());
                // xcb_connect never returns NULL: a failed connection is an
                // object in an error state (kept: libxcb frees it on
                // disconnect only, and it is tiny).
                if conn.is_null() || has_error(conn) != 0 {
                    return None;
                }
                Some(Own {
                    display,
                    conn,
                    get_setup: t::<*mut c_void, GetSetup>(f[2]),
                    send_event: t::<*mut c_void, SendEvent>(f[3]),
                    flush: t::<*mut c_void, Flush>(f[4]),
                    poll: t::<*mut c_void, NextEvent>(f[5]),
                    get_keyboard_mapping: t::<*mut c_void, GetKeyboardMapping>(f[6]),
                    get_keyboard_mapping_reply: t::<*mut c_void, GetKeyboardMappingReply>(f[7]),
                    keysyms: t::<*mut c_void, Keysyms>(f[8]),
                    keysyms_length: t::<*mut c_void, KeysymsLength>(f[9]),
                    query_extension: t::<*mut c_void, QueryExtension>(f[10]),
                    query_extension_reply: t::<*mut c_void, QueryExtensionReply>(f[11]),
                })
            }
        }

        /// Reads every event the server sent this connection (errors of
        /// Expose events sent to windows destroyed since, MappingNotify);
        /// true when one said the keyboard map changed. Never waits.
        pub(super) fn keyboard_changed(&self) -> bool {
            let mut changed = false;
            loop {
                // SAFETY: the layer's live connection.
                let e = unsafe { (self.poll)(self.conn) }.cast::<u8>();
                if e.is_null() {
                    return changed;
                }
                // SAFETY: an event of at least 32 bytes, malloc'ed by libxcb.
                unsafe {
                    changed |= *e & 0x7f == MAPPING_NOTIFY && *e.add(4) == MAPPING_KEYBOARD;
                    libc::free(e.cast());
                }
            }
        }

        /// Fills the keyboard table from the server's core keyboard map
        /// (one round trip; an unanswered request leaves the table as it was).
        pub(super) fn read_keyboard(&self) {
            // SAFETY: the layer's live connection; the setup outlives it
            // and holds min_keycode and max_keycode at bytes 34 and 35.
            let (min, max) = unsafe {
                let setup = (self.get_setup)(self.conn);
                if setup.is_null() {
                    return;
                }
                (*setup.add(34), *setup.add(35))
            };
            if min < 8 || max < min {
                return;
            }
            let count = max - min + 1;
            // SAFETY: a request and its reply on the layer's connection;
            // the keysyms are read within the length the reply gives, and
            // the reply is freed.
            unsafe {
                let cookie = (self.get_keyboard_mapping)(self.conn, min, count);
                let reply =
                    (self.get_keyboard_mapping_reply)(self.conn, cookie, std::ptr::null_mut());
                if reply.is_null() {
                    return;
                }
                let per = usize::from(*reply.add(1));
                let syms = (self.keysyms)(reply);
                let len = usize::try_from((self.keysyms_length)(reply)).unwrap_or(0);
                for code in 0..256 {
                    KEYS.map[code].store(0, Ordering::Relaxed);
                }
                if per > 0 && !syms.is_null() {
                    for i in 0..usize::from(count).min(len / per) {
                        let sym = *syms.add(i * per);
                        if let Some(k) = Key::of_keysym(u64::from(sym)) {
                            KEYS.map[usize::from(min) + i].store(k as u8, Ordering::Relaxed);
                        }
                    }
                }
                libc::free(reply.cast());
            }
        }

        /// The major opcode of extension `name` on the server, 0 when it
        /// has none (one round trip).
        pub(super) fn extension_opcode(&self, name: &CStr) -> u8 {
            let bytes = name.to_bytes();
            // SAFETY: a request and its reply on the layer's connection; the
            // reply's `present` and `major_opcode` are bytes 8 and 9; freed.
            unsafe {
                let cookie = (self.query_extension)(self.conn, bytes.len() as u16, name.as_ptr());
                let reply = (self.query_extension_reply)(self.conn, cookie, std::ptr::null_mut());
                if reply.is_null() {
                    return 0;
                }
                let opcode = if *reply.add(8) != 0 { *reply.add(9) } else { 0 };
                libc::free(reply.cast());
                opcode
            }
        }

        /// Sends each window of the display the connection was opened
        /// beside an Expose event of its whole area (windows of another
        /// display may be on another server).
        pub(super) fn expose(&self, windows: &[Shown]) {
            for &(display, window, width, height) in windows {
                if display != self.display {
                    continue;
                }
                let mut ev = [0u8; 32];
                ev[0] = EXPOSE;
                ev[4..8].copy_from_slice(&(window as u32).to_ne_bytes());
                ev[12..14].copy_from_slice(&width.to_ne_bytes());
                ev[14..16].copy_from_slice(&height.to_ne_bytes());
                // SAFETY: the layer's live connection and a 32-byte event.
                unsafe {
                    (self.send_event)(
                        self.conn,
                        0,
                        window as u32,
                        EXPOSURE_MASK,
                        ev.as_ptr().cast(),
                    )
                };
            }
            // SAFETY: the layer's connection.
            unsafe { (self.flush)(self.conn) };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn press(state: u32) -> KeyEvent {
        KeyEvent {
            press: true,
            keycode: 73,
            state,
        }
    }

    #[test]
    fn each_key_with_ctrl_is_its_control_and_other_modifiers_make_it_none() {
        let table = [
            (Key::F3, Control::SeparationDown),
            (Key::F4, Control::SeparationUp),
            (Key::F5, Control::ConvergenceDown),
            (Key::F6, Control::ConvergenceUp),
            (Key::T, Control::AutoToggle),
            (Key::F2, Control::AutoModeToggle),
            (Key::F7, Control::NextFormat),
            (Key::F8, Control::SwapEyes),
        ];
        const LOCK: u32 = 1 << 1;
        const MOD2: u32 = 1 << 4;
        for (key, control) in table {
            assert_eq!(control_of(key, CONTROL), Some(control), "{key:?}");
            assert_eq!(
                control_of(key, CONTROL | LOCK | MOD2),
                Some(control),
                "Caps Lock and Num Lock make no difference: {key:?}"
            );
            for other in [
                0,
                SHIFT,
                MOD1,
                CONTROL | MOD1,
                CONTROL | MOD4,
                CONTROL | MOD5,
            ] {
                assert_eq!(control_of(key, other), None, "{key:?} with {other:#x}");
            }
        }
        assert_eq!(
            control_of(Key::F7, CONTROL | SHIFT),
            Some(Control::PreviousFormat)
        );
        for key in [Key::F2, Key::F3, Key::F4, Key::F5, Key::F6, Key::F8, Key::T] {
            assert_eq!(control_of(key, CONTROL | SHIFT), None, "{key:?}");
        }
    }

    #[test]
    fn the_release_of_a_taken_press_is_taken_and_other_keys_pass() {
        let release = KeyEvent {
            press: false,
            ..press(CONTROL)
        };
        assert_eq!(
            decide(press(CONTROL), Some(Key::F7), false, false),
            Decision::Apply(Control::NextFormat)
        );
        assert_eq!(
            decide(release, Some(Key::F7), true, false),
            Decision::TakeRelease
        );
        assert_eq!(decide(release, Some(Key::F7), false, false), Decision::Pass);
        assert_eq!(decide(press(CONTROL), None, false, true), Decision::Pass);
        assert_eq!(decide(press(0), Some(Key::F7), false, true), Decision::Pass);
        // The keys of automatic stereo are controls only under --auto.
        assert_eq!(
            decide(press(CONTROL), Some(Key::T), false, false),
            Decision::PassNotAutomatic
        );
        assert_eq!(
            decide(press(CONTROL), Some(Key::T), false, true),
            Decision::Apply(Control::AutoToggle)
        );
        assert_eq!(
            decide(press(CONTROL), Some(Key::F8), false, false),
            Decision::Apply(Control::SwapEyes)
        );
    }

    #[test]
    fn events_are_read_as_libxcb_returns_them() {
        let mut ev = [0u8; 32];
        ev[0] = KEY_PRESS | 0x80; // sent with XSendEvent
        ev[1] = 75;
        ev[28..30].copy_from_slice(&(CONTROL as u16 | 0x2000).to_ne_bytes());
        assert_eq!(
            parse(&ev, 0),
            Seen::Key(KeyEvent {
                press: true,
                keycode: 75,
                state: CONTROL | 0x2000
            })
        );
        ev[0] = KEY_RELEASE;
        assert!(matches!(
            parse(&ev, 0),
            Seen::Key(KeyEvent { press: false, .. })
        ));
        for t in [0u8, 1, 4, 12, 34, 35, 127, 255] {
            ev[0] = t;
            assert_eq!(parse(&ev, 0), Seen::Other, "type {t}");
        }
        assert_eq!(parse(&ev[..31], 0), Seen::Other, "too short");
    }

    #[test]
    fn xinput2_key_events_are_read_as_libxcb_returns_them() {
        // An XI_KeyPress of 80 wire bytes (no buttons or valuators):
        // libxcb's copy has the full sequence number at 32..36.
        const XI: u8 = 131;
        let mut ev = vec![0u8; 36 + 48];
        ev[0] = GENERIC_EVENT;
        ev[1] = XI;
        ev[4..8].copy_from_slice(&12u32.to_ne_bytes());
        ev[8..10].copy_from_slice(&XI_KEY_PRESS.to_ne_bytes());
        ev[16..20].copy_from_slice(&73u32.to_ne_bytes());
        ev[76..80].copy_from_slice(&(CONTROL | 0x10).to_ne_bytes());
        let key = Seen::Key(KeyEvent {
            press: true,
            keycode: 73,
            state: CONTROL | 0x10,
        });
        assert_eq!(parse(&ev, XI), key);
        assert_eq!(parse(&ev, 0), Seen::Other, "the server has no XInput");
        assert_eq!(parse(&ev, XI + 1), Seen::Other, "another extension's");
        assert_eq!(parse(&ev[..79], XI), Seen::Other, "too short");
        ev[8..10].copy_from_slice(&XI_KEY_RELEASE.to_ne_bytes());
        assert!(matches!(
            parse(&ev, XI),
            Seen::Key(KeyEvent { press: false, .. })
        ));
        ev[8..10].copy_from_slice(&13u16.to_ne_bytes()); // XI_RawKeyPress
        assert_eq!(parse(&ev, XI), Seen::Other);
        ev[8..10].copy_from_slice(&XI_KEY_PRESS.to_ne_bytes());
        ev[16..20].copy_from_slice(&300u32.to_ne_bytes());
        assert_eq!(parse(&ev, XI), Seen::Other, "no such keycode");
        // As the filter sees it in libxcb's memory.
        // SAFETY: a buffer of 36 + 4 × 12 bytes, as the length says.
        assert_eq!(unsafe { event_bytes(ev.as_ptr()) }.len(), ev.len());
        ev[4..8].copy_from_slice(&u32::MAX.to_ne_bytes());
        // SAFETY: the length is refused before it is used.
        assert_eq!(unsafe { event_bytes(ev.as_ptr()) }.len(), 32);
    }

    #[test]
    fn separation_steps_by_five_within_zero_and_a_hundred() {
        assert_eq!(step_separation(15.0, true), 20.0);
        assert_eq!(step_separation(15.0, false), 10.0);
        assert_eq!(step_separation(12.0, true), 15.0);
        assert_eq!(step_separation(12.0, false), 10.0);
        assert_eq!(step_separation(0.0, false), 0.0);
        assert_eq!(step_separation(100.0, true), 100.0);
        assert_eq!(step_separation(98.0, true), 100.0);
        assert_eq!(step_separation(f32::NAN, true), 20.0);
    }

    #[test]
    fn convergence_steps_by_ten_percent_from_the_set_or_automatic_value() {
        let (v, how) = step_convergence(Some(2.0), Some(9.0), true);
        assert!((v - 2.2).abs() < 1e-6 && how == StepFrom::Set);
        let (v, how) = step_convergence(None, Some(5.0), false);
        assert!((v - 5.0 / 1.1).abs() < 1e-6 && how == StepFrom::Automatic(5.0));
        let (v, how) = step_convergence(None, None, true);
        assert!((v - 1.1).abs() < 1e-6 && how == StepFrom::Unknown);
        // Never to infinity or zero: the value stays.
        assert_eq!(step_convergence(Some(f32::MAX), None, true).0, f32::MAX);
        let tiny = f32::from_bits(1);
        assert_eq!(step_convergence(Some(tiny), None, false).0, tiny);
    }

    #[test]
    fn the_format_cycle_starts_at_the_programs_format_and_wraps_both_ways() {
        let red_cyan = FORMAT_CYCLE[0];
        assert_eq!(
            next_format(red_cyan, red_cyan, true),
            OutputMode::SideBySide
        );
        assert_eq!(next_format(red_cyan, red_cyan, false), OutputMode::Right);
        assert_eq!(next_format(red_cyan, OutputMode::Right, true), red_cyan);
        // A format outside the cycle is its first member.
        let rows = OutputMode::Rows;
        assert_eq!(
            next_format(OutputMode::Starbase, OutputMode::Starbase, true),
            red_cyan
        );
        assert_eq!(
            next_format(OutputMode::Starbase, red_cyan, false),
            OutputMode::Starbase
        );
        // A format of the cycle is not visited twice.
        let mut seen = vec![rows];
        let mut m = next_format(rows, rows, true);
        while m != rows {
            assert!(!seen.contains(&m), "{m} twice");
            seen.push(m);
            m = next_format(rows, m, true);
        }
        assert_eq!(seen.len(), FORMAT_CYCLE.len());
        assert!(!FORMAT_CYCLE.contains(&OutputMode::Quad));
    }

    #[test]
    fn numbers_are_said_short() {
        assert_eq!(short(20.0), "20");
        assert_eq!(short(1.1), "1.1");
        assert_eq!(short(1.0 / 1.1), "0.9091");
        assert_eq!(short(1.61051), "1.611");
        assert_eq!(short(2500.0), "2500");
        assert_eq!(short(0.0), "0");
    }
}

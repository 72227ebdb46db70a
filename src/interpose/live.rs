//! What the user can change while a program runs under `glstereo-run`: the
//! output format and the eye order of every stereo window (and, in
//! [`crate::auto::live`], automatic stereo's on/off, separation and
//! convergence, re-exported here). Each starts as the environment says
//! (glstereo-run's options set it) and is read at each present, so a
//! change (the keys in the program's window) takes effect at the next
//! frame. One atomic per setting: a reader never waits.
//!
//! | variable                | accepted                      | default |
//! |-------------------------|-------------------------------|---------|
//! | `GLSTEREO_MODE`         | a format (glstereo-run -m)    | `anaglyph-red-cyan` |
//! | `GLSTEREO_SWAP_EYES`    | as in [`crate::output::options`] | `0` |
//!
//! A bad value is said once on stderr and the default is used
//! (glstereo-run refuses bad values before the program starts).

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::output::OutputMode;
use crate::output::options::OutputOptions;

use super::settings;

pub use crate::auto::live::{
    AutoMode, DEFAULT_SEPARATION, ENV_AUTO, ENV_CONVERGENCE, ENV_SEPARATION, auto_mode, auto_on,
    auto_requested, automatic_convergence, convergence, from_depth, parse_auto, parse_convergence,
    parse_separation, separation, set_auto_mode, set_auto_on, set_automatic_convergence,
    set_convergence, set_separation,
};

/// The live settings.
struct Live {
    /// The window format, by its index in [`OutputMode::ALL`].
    mode: AtomicUsize,
    swap_eyes: AtomicBool,
}

fn live() -> &'static Live {
    static LIVE: OnceLock<Live> = OnceLock::new();
    LIVE.get_or_init(|| Live {
        mode: AtomicUsize::new(settings::window_mode().index()),
        swap_eyes: AtomicBool::new(settings::get().options.swap_eyes),
    })
}

/// The format stereo windows are shown in now.
pub fn mode() -> OutputMode {
    OutputMode::ALL[live().mode.load(Ordering::Relaxed)]
}

/// Shows stereo windows in `mode` from the next frame on.
pub fn set_mode(mode: OutputMode) {
    live().mode.store(mode.index(), Ordering::Relaxed);
}

/// Whether the eyes are exchanged now.
pub fn swap_eyes() -> bool {
    live().swap_eyes.load(Ordering::Relaxed)
}

/// Exchanges the eyes (or not) from the next frame on.
pub fn set_swap_eyes(swap: bool) {
    live().swap_eyes.store(swap, Ordering::Relaxed);
}

/// The output options now: the environment's, with the live eye order.
pub fn options() -> OutputOptions {
    OutputOptions {
        swap_eyes: swap_eyes(),
        ..settings::get().options
    }
}

//! The interposer's settings, read once from the environment (what
//! glstereo-run sets): GLSTEREO_MODE, GLSTEREO_SWAP_EYES,
//! GLSTEREO_CROSSTALK, GLSTEREO_SATURATION (see [`crate::output::options`])
//! and GLSTEREO_CAPTURE_DIR (see [`super::capture`]).

use std::sync::OnceLock;

use crate::output::OutputMode;
use crate::output::options::OutputSettings;
use crate::surface::DEFAULT_OUTPUT;

/// The settings, read on first use. A bad value is reported on stderr once
/// and the defaults are used (glstereo-run refuses bad values before the
/// program starts).
pub fn get() -> &'static OutputSettings {
    static SETTINGS: OnceLock<OutputSettings> = OnceLock::new();
    SETTINGS.get_or_init(|| {
        OutputSettings::from_env().unwrap_or_else(|e| {
            super::warn(&format!("{e}; using the defaults"));
            OutputSettings::default()
        })
    })
}

/// The mode windows are composed in: GLSTEREO_MODE, or [`DEFAULT_OUTPUT`]
/// (anaglyph-red-cyan) when it is unset or `quad` (a window of an emulated
/// stereo visual has no right buffers).
pub fn window_mode() -> OutputMode {
    match get().mode {
        None | Some(OutputMode::Quad) => DEFAULT_OUTPUT,
        Some(m) => m,
    }
}

/// Whether a stereo request may be answered with native stereo — the
/// driver's quad buffer, or the stereo visuals and configurations a layer
/// below offers (VirtualGL's): when the user chose no format, or chose
/// `quad`. An explicit format (GLSTEREO_MODE, `glstereo-run -m`) means the
/// user wants that format, so every stereo request is emulated and shown
/// in it.
pub fn native_allowed() -> bool {
    matches!(get().mode, None | Some(OutputMode::Quad))
}

pub use crate::report::{ENV_VERBOSE, tell, verbose};

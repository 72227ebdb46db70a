//! The emulated screen both period APIs open: its size, and how a
//! full-screen surface is made on it.
//!
//! A Starbase `gopen()` or an IRIS GL `winopen()` on a real workstation
//! opens (part of) a physical screen whose mode was set outside the
//! program (HP's and SGI's `setmon`). Here the screen is a size, per
//! process: 1280x1024 by default, the mode both seeds use; a program (or a
//! test) may set another with [`set_screen_size`] before opening.

use std::sync::{Arc, Mutex};

use crate::backend::BackendChoice;
use crate::config::glx::*;
use crate::display::Display;
use crate::error::{Error, Result};
use crate::image::check_size;
use crate::surface::Surface;

/// The screen size both seeds use: 1280x1024.
pub const DEFAULT_SCREEN_SIZE: (u32, u32) = (1280, 1024);

static SCREEN: Mutex<(u32, u32)> = Mutex::new(DEFAULT_SCREEN_SIZE);

/// The emulated screen's width and height in pixels.
pub fn screen_size() -> (u32, u32) {
    *SCREEN.lock().unwrap_or_else(|e| e.into_inner())
}

/// Sets the emulated screen's size for surfaces opened from now on
/// (1…16384 each; on error nothing changes).
pub fn set_screen_size(width: u32, height: u32) -> Result<()> {
    check_size(width, height)?;
    *SCREEN.lock().unwrap_or_else(|e| e.into_inner()) = (width, height);
    Ok(())
}

/// The attribute list of a period window: RGBA8, double-buffered, 24-bit
/// depth, and stereo when asked.
fn attribs(stereo: bool) -> Vec<i32> {
    let mut a = vec![
        GLX_RGBA,
        GLX_DOUBLEBUFFER,
        GLX_RED_SIZE,
        8,
        GLX_GREEN_SIZE,
        8,
        GLX_BLUE_SIZE,
        8,
        GLX_DEPTH_SIZE,
        24,
    ];
    if stereo {
        a.push(GLX_STEREO);
    }
    a
}

/// Opens a display (the automatic backend choice, so GLSTEREO_BACKEND
/// decides) and makes a `width` × `height` double-buffered surface on it:
/// stereo (emulated) when `stereo` is asked and available, else mono.
pub fn open_surface(width: u32, height: u32, stereo: bool) -> Result<Arc<Surface>> {
    check_size(width, height)?;
    let display = Display::open(BackendChoice::Auto)?;
    let config = match display.choose_config(&attribs(stereo)) {
        Err(Error::NoMatchingConfig(_)) if stereo => display.choose_config(&attribs(false))?,
        r => r?,
    };
    display.create_surface(&config, width, height)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_screen_is_the_seeds_1280x1024_until_set_and_a_bad_size_changes_nothing() {
        // The only test in the crate that touches the process-wide size.
        assert_eq!(screen_size(), (1280, 1024));
        assert!(set_screen_size(0, 10).is_err());
        assert_eq!(screen_size(), (1280, 1024));
        set_screen_size(640, 480).unwrap();
        assert_eq!(screen_size(), (640, 480));
        set_screen_size(1280, 1024).unwrap();
    }

    #[test]
    fn period_windows_ask_for_rgba8_double_buffering_and_depth() {
        let a = attribs(true);
        assert_eq!(a[..2], [GLX_RGBA, GLX_DOUBLEBUFFER]);
        assert_eq!(a.last(), Some(&GLX_STEREO));
        assert!(!attribs(false).contains(&GLX_STEREO));
    }
}

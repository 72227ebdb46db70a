//! SGI IRIS GL's stereo subset (seed 002), emulated.
//!
//! - Monitor modes (`getmonitor` / `setmonitor`) are process-wide, as the
//!   display's mode is: HZ60 (initial) and HZ72 are mono; STR_RECT reads
//!   each `winopen` window as SGI's above/below format
//!   ([`InputFraming::StrRect`]: left eye GL rows 532–1023, right eye rows
//!   0–491 of 1024, the 40 rows between lost); STR_TOP / STR_BOT show the
//!   top / bottom 492-row band of the window to both eyes, from the left
//!   and right buffers when the window has stereo buffers
//!   ([`InputFraming::StrTop`], [`InputFraming::StrBot`]).
//! - Square-pixel stereo (`stereobuffer()` + `gconfig()`,
//!   `leftbuffer` / `rightbuffer`) is the emulated quad buffer. Every
//!   `winopen` window is made with stereo buffers (when stereo emulation is
//!   allowed), so `gconfig()` only changes which buffers drawing reaches:
//!   in mono mode both eyes' buffers get the same pixels.
//! - `getgdesc` answers GD_XPMAX / GD_YPMAX with the emulated screen's
//!   width and height in pixels (1280 and 1024 by default: SGI's own
//!   programs write `prefposition(0, getgdesc(GD_XPMAX) - 1, …)`),
//!   GD_STEREO with 1 (every window can use the STR_* framings) and
//!   GD_STEREO_IN_WINDOW with 1 when windows get stereo buffers.
//! - `viewport` takes IRIS GL's inclusive pixel bounds and, as IRIS GL
//!   does, also sets the screenmask (the scissor box); `window` is
//!   glFrustum into GL_PROJECTION; `translate` multiplies the current matrix.
//!
//! Numeric values are SGI's, from IRIX's `<gl/gl.h>` (GD_*) and
//! `<gl/get.h>` (monitor types).

use std::sync::{Arc, Mutex, MutexGuard};

use glam::{DMat4, DVec3};

use super::descriptors::Descriptors;
use super::screen;
use crate::config::{EmulationPolicy, StereoKind};
use crate::error::{Error, Result};
use crate::framing::InputFraming;
use crate::gl::enums::*;
use crate::math::Frustum;
use crate::surface::{self, Surface};

/// getgdesc: the screen's width in pixels (SGI's value 0).
pub const GD_XPMAX: i32 = 0;
/// getgdesc: the screen's height in pixels (SGI's value 1).
pub const GD_YPMAX: i32 = 1;
/// getgdesc: whether the system can show stereo at all (SGI's value 50).
pub const GD_STEREO: i32 = 50;
/// getgdesc: whether windows can have stereo buffers (SGI's value 89).
pub const GD_STEREO_IN_WINDOW: i32 = 89;

/// Monitor type: standard 60 Hz (SGI's value 1).
pub const HZ60: i32 = 1;
/// Monitor type: StereoGraphics stereo, 1280x492x2 (SGI's value 15).
pub const STR_RECT: i32 = 15;
/// Monitor type: multi-scan 72 Hz (SGI's value 23).
pub const HZ72: i32 = 23;
/// Monitor type: stereo, bottom buffer primary (SGI's value 27).
pub const STR_BOT: i32 = 27;
/// Monitor type: stereo, top buffer primary (SGI's value 28).
pub const STR_TOP: i32 = 28;

/// The monitor modes the emulation offers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Monitor {
    /// 60 Hz mono (the initial mode).
    Hz60,
    /// 72 Hz mono.
    Hz72,
    /// Full-screen above/below stereo.
    StrRect,
    /// Windowed stereo in the top 492 rows.
    StrTop,
    /// Windowed stereo in the bottom 492 rows.
    StrBot,
}

impl Monitor {
    /// SGI's numeric value.
    pub fn code(self) -> i32 {
        match self {
            Monitor::Hz60 => HZ60,
            Monitor::Hz72 => HZ72,
            Monitor::StrRect => STR_RECT,
            Monitor::StrTop => STR_TOP,
            Monitor::StrBot => STR_BOT,
        }
    }

    /// How a `winopen` window's eyes are read in this mode.
    pub fn framing(self) -> InputFraming {
        match self {
            Monitor::Hz60 | Monitor::Hz72 => InputFraming::QuadBuffer,
            Monitor::StrRect => InputFraming::StrRect,
            Monitor::StrTop => InputFraming::StrTop,
            Monitor::StrBot => InputFraming::StrBot,
        }
    }
}

impl TryFrom<i32> for Monitor {
    type Error = Error;
    fn try_from(v: i32) -> Result<Monitor> {
        Ok(match v {
            HZ60 => Monitor::Hz60,
            HZ72 => Monitor::Hz72,
            STR_RECT => Monitor::StrRect,
            STR_TOP => Monitor::StrTop,
            STR_BOT => Monitor::StrBot,
            _ => {
                return Err(Error::invalid_enum(
                    "monitor type",
                    v as u32,
                    format!(
                        "use HZ60 ({HZ60}), HZ72 ({HZ72}), STR_RECT ({STR_RECT}), \
                         STR_TOP ({STR_TOP}) or STR_BOT ({STR_BOT})"
                    ),
                ));
            }
        })
    }
}

/// The getgdesc inquiries the emulation answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Inquiry {
    /// GD_XPMAX.
    XPMax,
    /// GD_YPMAX.
    YPMax,
    /// GD_STEREO.
    Stereo,
    /// GD_STEREO_IN_WINDOW.
    StereoInWindow,
}

impl TryFrom<i32> for Inquiry {
    type Error = Error;
    fn try_from(v: i32) -> Result<Inquiry> {
        Ok(match v {
            GD_XPMAX => Inquiry::XPMax,
            GD_YPMAX => Inquiry::YPMax,
            GD_STEREO => Inquiry::Stereo,
            GD_STEREO_IN_WINDOW => Inquiry::StereoInWindow,
            _ => {
                return Err(Error::invalid_enum(
                    "getgdesc inquiry",
                    v as u32,
                    format!(
                        "the emulation answers GD_XPMAX ({GD_XPMAX}), GD_YPMAX ({GD_YPMAX}), \
                         GD_STEREO ({GD_STEREO}) and GD_STEREO_IN_WINDOW ({GD_STEREO_IN_WINDOW})"
                    ),
                ));
            }
        })
    }
}

/// A window's buffer configuration: what gconfig() made current, what the
/// next gconfig() will, and the leftbuffer / rightbuffer flags.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Buffering {
    /// Stereo buffering is configured (stereobuffer() + gconfig()).
    pub stereo: bool,
    /// Double buffering is configured (doublebuffer() + gconfig()).
    pub double: bool,
    /// stereobuffer() (true) or monobuffer() (false) since the last gconfig().
    pub pending_stereo: bool,
    /// doublebuffer() (true) or singlebuffer() (false) since the last gconfig().
    pub pending_double: bool,
    /// leftbuffer(): draw into the left eye's buffer.
    pub left: bool,
    /// rightbuffer(): draw into the right eye's buffer.
    pub right: bool,
}

impl Default for Buffering {
    /// IRIS GL's initial window: mono, single-buffered, leftbuffer(TRUE),
    /// rightbuffer(FALSE).
    fn default() -> Self {
        Buffering {
            stereo: false,
            double: false,
            pending_stereo: false,
            pending_double: false,
            left: true,
            right: false,
        }
    }
}

impl Buffering {
    /// Applies the pending configuration (gconfig()).
    pub fn gconfig(&mut self) {
        self.stereo = self.pending_stereo;
        self.double = self.pending_double;
    }

    /// The GL draw buffer that drawing goes to: the back buffers when
    /// double-buffered, else the front ones; in stereo mode the eyes
    /// leftbuffer / rightbuffer select (both: GL_BACK / GL_FRONT, which
    /// reach both eyes; neither: GL_NONE); in mono mode both eyes, so a
    /// mono window looks the same to each.
    pub fn draw_buffer(&self) -> u32 {
        let (both, left, right) = if self.double {
            (GL_BACK, GL_BACK_LEFT, GL_BACK_RIGHT)
        } else {
            (GL_FRONT, GL_FRONT_LEFT, GL_FRONT_RIGHT)
        };
        if !self.stereo {
            return both;
        }
        match (self.left, self.right) {
            (true, true) => both,
            (true, false) => left,
            (false, true) => right,
            (false, false) => GL_NONE,
        }
    }
}

/// glViewport's (x, y, width, height) for IRIS GL's viewport(left, right,
/// bottom, top), whose bounds are inclusive pixel coordinates.
pub fn viewport_rect(left: i32, right: i32, bottom: i32, top: i32) -> Result<(i32, i32, i32, i32)> {
    if right < left || top < bottom {
        return Err(Error::invalid_value(format!(
            "viewport({left}, {right}, {bottom}, {top}): right must be >= left and top >= bottom \
             (the bounds are inclusive pixels: viewport(0, 1279, 0, 1023) is 1280x1024)"
        )));
    }
    Ok((
        left,
        bottom,
        (i64::from(right) - i64::from(left) + 1).min(i64::from(i32::MAX)) as i32,
        (i64::from(top) - i64::from(bottom) + 1).min(i64::from(i32::MAX)) as i32,
    ))
}

/// The matrix of IRIS GL's window(): glFrustum's.
pub fn window_matrix(
    left: f64,
    right: f64,
    bottom: f64,
    top: f64,
    near: f64,
    far: f64,
) -> Result<DMat4> {
    Ok(Frustum {
        left,
        right,
        bottom,
        top,
        near,
        far,
    }
    .validated()?
    .matrix())
}

/// The matrix of IRIS GL's translate(): glTranslate's.
pub fn translate_matrix(x: f64, y: f64, z: f64) -> Result<DMat4> {
    if !(x.is_finite() && y.is_finite() && z.is_finite()) {
        return Err(Error::invalid_value(format!(
            "translate({x}, {y}, {z}): every component must be finite"
        )));
    }
    Ok(DMat4::from_translation(DVec3::new(x, y, z)))
}

/// The size of the next window: prefposition(x1, x2, y1, y2) (inclusive
/// screen pixels, clamped to the screen, so the seed's
/// `prefposition(0, getgdesc(GD_XPMAX), 0, getgdesc(GD_YPMAX))` is the full
/// screen) or, without one, the whole screen.
pub fn window_size(pref: Option<[i32; 4]>, screen: (u32, u32)) -> Result<(u32, u32)> {
    let Some([x1, x2, y1, y2]) = pref else {
        return Ok(screen);
    };
    // The part of [lo, hi] on a screen of `n` pixels.
    let visible =
        |lo: i32, hi: i32, n: u32| i64::from(hi).min(i64::from(n) - 1) - i64::from(lo).max(0) + 1;
    let (w, h) = (visible(x1, x2, screen.0), visible(y1, y2, screen.1));
    if w < 1 || h < 1 {
        return Err(Error::invalid_value(format!(
            "prefposition({x1}, {x2}, {y1}, {y2}) leaves no pixels of the {}x{} screen",
            screen.0, screen.1
        )));
    }
    Ok((w as u32, h as u32))
}

/// One winopen() window.
struct Window {
    surface: Arc<Surface>,
    buffering: Buffering,
}

struct State {
    monitor: Monitor,
    pref: Option<[i32; 4]>,
    windows: Descriptors<Window>,
}

static STATE: Mutex<State> = Mutex::new(State {
    monitor: Monitor::Hz60,
    pref: None,
    windows: Descriptors::new(1),
});

fn state() -> MutexGuard<'static, State> {
    STATE.lock().unwrap_or_else(|e| e.into_inner())
}

fn bad_window() -> Error {
    Error::InvalidHandle("window (an IRIS GL window identifier from winopen())")
}

/// getgdesc(inquiry).
pub fn getgdesc(inquiry: i32) -> Result<i64> {
    let (w, h) = screen::screen_size();
    Ok(match Inquiry::try_from(inquiry)? {
        Inquiry::XPMax => i64::from(w),
        Inquiry::YPMax => i64::from(h),
        Inquiry::Stereo => 1,
        Inquiry::StereoInWindow => match surface::current() {
            Some(s) => i64::from(s.config().stereo != StereoKind::None),
            None => {
                let policy = EmulationPolicy::from_env_value(
                    std::env::var("GLSTEREO_EMULATION").ok().as_deref(),
                )?;
                i64::from(policy != EmulationPolicy::Off)
            }
        },
    })
}

/// getmonitor(): the current monitor mode's SGI value (initially HZ60).
pub fn getmonitor() -> i32 {
    state().monitor.code()
}

/// setmonitor(type): switches the monitor mode, which re-frames every
/// winopen() window. On error (an unknown type, or a window too small for
/// the STR_* bands) nothing changes.
pub fn setmonitor(code: i32) -> Result<()> {
    let monitor = Monitor::try_from(code)?;
    let mut st = state();
    let framing = monitor.framing();
    for (_, w) in st.windows.iter() {
        let (width, height) = w.surface.size();
        framing.check(w.surface.config().shape(), width, height)?;
    }
    for (_, w) in st.windows.iter() {
        w.surface.set_framing(framing)?;
    }
    st.monitor = monitor;
    Ok(())
}

/// prefposition(x1, x2, y1, y2): the size of the next winopen() window.
pub fn prefposition(x1: i32, x2: i32, y1: i32, y2: i32) -> Result<()> {
    if x2 < x1 || y2 < y1 {
        return Err(Error::invalid_value(format!(
            "prefposition({x1}, {x2}, {y1}, {y2}): x2 must be >= x1 and y2 >= y1"
        )));
    }
    state().pref = Some([x1, x2, y1, y2]);
    Ok(())
}

/// winopen(): a window the size prefposition() asked for (the whole
/// emulated screen without it), with stereo buffers when stereo emulation
/// is allowed, read in the current monitor mode, made current on the
/// calling thread. Mono, single-buffered until gconfig() says otherwise.
pub fn winopen() -> Result<(i32, Arc<Surface>)> {
    let mut st = state();
    let (w, h) = window_size(st.pref, screen::screen_size())?;
    let s = screen::open_surface(w, h, true)?;
    s.set_framing(st.monitor.framing())?;
    surface::make_current(Some(&s))?;
    let buffering = Buffering::default();
    let registered = s.draw_buffer(buffering.draw_buffer()).and_then(|()| {
        st.windows.insert(Window {
            surface: s.clone(),
            buffering,
        })
    });
    match registered {
        Ok(id) => {
            st.pref = None;
            Ok((id, s))
        }
        Err(e) => {
            s.release_if_current();
            Err(e)
        }
    }
}

/// winclose(window): forgets the window, releases it if current here, and
/// returns its surface for the caller to drop.
pub fn winclose(window: i32) -> Result<Arc<Surface>> {
    let w = state().windows.remove(window).ok_or_else(bad_window)?;
    w.surface.release_if_current();
    Ok(w.surface)
}

/// The surface of a winopen() window.
pub fn window_surface(window: i32) -> Result<Arc<Surface>> {
    state()
        .windows
        .get(window)
        .map(|w| w.surface.clone())
        .ok_or_else(bad_window)
}

/// The buffer configuration of a winopen() window.
pub fn buffering(window: i32) -> Result<Buffering> {
    state()
        .windows
        .get(window)
        .map(|w| w.buffering)
        .ok_or_else(bad_window)
}

/// Runs `f` on the winopen() window current on this thread.
fn with_current_window<T>(f: impl FnOnce(&mut Window) -> Result<T>) -> Result<T> {
    let no_window = || {
        Error::invalid_operation(
            "no IRIS GL window is current on this thread: call winopen() first",
        )
    };
    let current = surface::current().ok_or_else(no_window)?;
    let mut st = state();
    let id = st
        .windows
        .find(|w| Arc::ptr_eq(&w.surface, &current))
        .ok_or_else(no_window)?;
    f(st.windows.get_mut(id).expect("found above"))
}

/// Changes the current window's buffering with `change`, then points GL's
/// draw buffer where the new buffering says. On error nothing changes.
fn rebuffer(change: impl FnOnce(&mut Buffering) -> Result<()>) -> Result<()> {
    with_current_window(|w| {
        let mut b = w.buffering;
        change(&mut b)?;
        if b.stereo && w.surface.config().stereo == StereoKind::None {
            return Err(Error::invalid_operation(
                "this window has no stereo buffers (stereo emulation is off: \
                 GLSTEREO_EMULATION=off), so stereobuffer() cannot take effect; \
                 check getgdesc(GD_STEREO_IN_WINDOW) first",
            ));
        }
        w.surface.draw_buffer(b.draw_buffer())?;
        w.buffering = b;
        Ok(())
    })
}

/// stereobuffer() (true) or monobuffer() (false): takes effect at gconfig().
pub fn set_pending_stereo(stereo: bool) -> Result<()> {
    with_current_window(|w| {
        w.buffering.pending_stereo = stereo;
        Ok(())
    })
}

/// doublebuffer() (true) or singlebuffer() (false): takes effect at gconfig().
pub fn set_pending_double(double: bool) -> Result<()> {
    with_current_window(|w| {
        w.buffering.pending_double = double;
        Ok(())
    })
}

/// gconfig(): applies stereobuffer/monobuffer and doublebuffer/singlebuffer.
pub fn gconfig() -> Result<()> {
    rebuffer(|b| {
        b.gconfig();
        Ok(())
    })
}

/// leftbuffer(enable).
pub fn leftbuffer(enable: bool) -> Result<()> {
    rebuffer(|b| {
        b.left = enable;
        Ok(())
    })
}

/// rightbuffer(enable).
pub fn rightbuffer(enable: bool) -> Result<()> {
    rebuffer(|b| {
        b.right = enable;
        Ok(())
    })
}

/// swapbuffers(): presents a double-buffered window; IRIS GL ignores it in
/// single-buffer mode, and so does the emulation.
pub fn swapbuffers() -> Result<()> {
    let (s, double) = with_current_window(|w| Ok((w.surface.clone(), w.buffering.double)))?;
    if double { s.swap_buffers() } else { Ok(()) }
}

/// viewport(left, right, bottom, top) on the current surface: glViewport
/// and, as IRIS GL's viewport sets the screenmask, glScissor with
/// GL_SCISSOR_TEST enabled.
pub fn viewport(left: i32, right: i32, bottom: i32, top: i32) -> Result<()> {
    let (x, y, w, h) = viewport_rect(left, right, bottom, top)?;
    let s = surface::require_current()?;
    let gl = s.gl();
    // SAFETY: the surface's application context is current on this thread.
    unsafe {
        gl.Viewport(x, y, w, h);
        gl.Scissor(x, y, w, h);
        gl.Enable(GL_SCISSOR_TEST);
    }
    Ok(())
}

/// window(left, right, bottom, top, near, far): the frustum replaces
/// GL_PROJECTION (the matrix mode is left as it was).
pub fn window(left: f64, right: f64, bottom: f64, top: f64, near: f64, far: f64) -> Result<()> {
    let m = window_matrix(left, right, bottom, top, near, far)?;
    surface::require_current()?.load_projection(&m.to_cols_array())
}

/// translate(x, y, z): multiplies the current matrix, as glTranslate.
pub fn translate(x: f64, y: f64, z: f64) -> Result<()> {
    let m = translate_matrix(x, y, z)?.to_cols_array();
    let s = surface::require_current()?;
    // SAFETY: the surface's application context is current on this thread;
    // `m` holds 16 doubles.
    unsafe { s.gl().MultMatrixd(m.as_ptr()) };
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sgi_constants_have_irix_values() {
        assert_eq!(
            (GD_XPMAX, GD_YPMAX, GD_STEREO, GD_STEREO_IN_WINDOW),
            (0, 1, 50, 89)
        );
        assert_eq!(
            (HZ60, STR_RECT, HZ72, STR_BOT, STR_TOP),
            (1, 15, 23, 27, 28)
        );
    }

    #[test]
    fn monitor_codes_round_trip_and_choose_the_framing() {
        for m in [
            Monitor::Hz60,
            Monitor::Hz72,
            Monitor::StrRect,
            Monitor::StrTop,
            Monitor::StrBot,
        ] {
            assert_eq!(Monitor::try_from(m.code()), Ok(m));
        }
        assert_eq!(Monitor::StrRect.framing(), InputFraming::StrRect);
        assert_eq!(Monitor::Hz72.framing(), InputFraming::QuadBuffer);
        let e = Monitor::try_from(24).unwrap_err(); // HZ50: real, but not emulated
        assert!(e.to_string().contains("STR_RECT (15)"), "{e}");
        assert!(Inquiry::try_from(2).is_err(), "GD_XMMAX is not answered");
        assert_eq!(Inquiry::try_from(89), Ok(Inquiry::StereoInWindow));
    }

    #[test]
    fn left_and_right_flags_select_the_buffers_the_seed_describes() {
        let mut b = Buffering::default();
        assert_eq!(
            b.draw_buffer(),
            GL_FRONT,
            "single-buffered mono: both front buffers"
        );
        b.pending_double = true;
        b.gconfig();
        assert_eq!(b.draw_buffer(), GL_BACK, "mono: both eyes alike");
        b.pending_stereo = true;
        assert_eq!(
            b.draw_buffer(),
            GL_BACK,
            "stereobuffer() waits for gconfig()"
        );
        b.gconfig();
        assert_eq!(b.draw_buffer(), GL_BACK_LEFT, "left is the initial default");
        for (l, r, want) in [
            (true, false, GL_BACK_LEFT),
            (false, true, GL_BACK_RIGHT),
            (true, true, GL_BACK),
            (false, false, GL_NONE),
        ] {
            b.left = l;
            b.right = r;
            assert_eq!(b.draw_buffer(), want, "leftbuffer({l}) rightbuffer({r})");
        }
        b.pending_double = false;
        b.gconfig();
        b.left = false;
        b.right = true;
        assert_eq!(b.draw_buffer(), GL_FRONT_RIGHT);
    }

    #[test]
    fn viewport_bounds_are_inclusive_pixels() {
        assert_eq!(viewport_rect(0, 1279, 532, 1023), Ok((0, 532, 1280, 492)));
        assert_eq!(viewport_rect(0, 1279, 0, 491), Ok((0, 0, 1280, 492)));
        assert_eq!(viewport_rect(5, 5, 7, 7), Ok((5, 7, 1, 1)));
        assert!(viewport_rect(10, 9, 0, 0).is_err());
        assert!(viewport_rect(0, 0, 1, 0).is_err());
        assert_eq!(
            viewport_rect(i32::MIN, i32::MAX, 0, 0).unwrap().2,
            i32::MAX,
            "no overflow"
        );
    }

    #[test]
    fn window_and_translate_are_glfrustum_and_gltranslate() {
        let m = window_matrix(-1.0, 1.0, -1.0, 1.0, 1.0, 3.0).unwrap();
        // glFrustum(-1, 1, -1, 1, 1, 3): diagonal 1, 1, -(3+1)/(3-1); [3][2] = -2·3·1/(3-1).
        assert_eq!(m.x_axis.x, 1.0);
        assert_eq!(m.z_axis.z, -2.0);
        assert_eq!(m.w_axis.z, -3.0);
        assert_eq!(m.z_axis.w, -1.0);
        assert!(window_matrix(-1.0, 1.0, -1.0, 1.0, 0.0, 3.0).is_err());
        let t = translate_matrix(0.5, 0.0, -2.0).unwrap();
        assert_eq!(t.w_axis.truncate(), DVec3::new(0.5, 0.0, -2.0));
        assert!(translate_matrix(f64::NAN, 0.0, 0.0).is_err());
    }

    #[test]
    fn prefposition_is_clamped_to_the_screen() {
        let screen = (1280, 1024);
        assert_eq!(window_size(None, screen), Ok((1280, 1024)));
        assert_eq!(
            window_size(Some([0, 1280, 0, 1024]), screen),
            Ok((1280, 1024)),
            "the seed's prefposition(0, GD_XPMAX, 0, GD_YPMAX)"
        );
        assert_eq!(
            window_size(Some([0, 1279, 532, 1023]), screen),
            Ok((1280, 492))
        );
        assert!(window_size(Some([2000, 3000, 0, 10]), screen).is_err());
    }
}

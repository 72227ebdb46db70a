//! Automatic stereo's live settings: on or off, separation, convergence
//! (`glstereo-run --auto`). Each starts as the environment says
//! (glstereo-run's options set it) and is read at each draw of an
//! automatic-stereo context, so a change — the live keys in the
//! program's window ([`crate::interpose::controls`]), or a program of 3D
//! Vision's kind calling glStereoParameterfNV — takes effect at the next
//! frame. One atomic per setting: a reader never waits.
//!
//! | variable                | accepted                      | default |
//! |-------------------------|-------------------------------|---------|
//! | `GLSTEREO_AUTO`         | `0` `1` `true` `false` `yes` `no`, `geometry` `depth` | `0` |
//! | `GLSTEREO_SEPARATION`   | percent, 0 … 100              | `15` |
//! | `GLSTEREO_CONVERGENCE`  | `auto`, or a distance > 0     | `auto` |
//!
//! `1` (and `true`, `yes`) is `geometry`: each frame rendered once per
//! eye ([`crate::auto`]); `depth` renders it once and makes both eyes from
//! its colour and depth ([`crate::reproject`]).
//!
//! A bad value is said once on stderr and the default is used
//! (glstereo-run refuses bad values before the program starts).

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicU8, AtomicU32, AtomicU64, Ordering};

use crate::report::warn;

/// Automatic stereo for programs that never ask for stereo.
pub const ENV_AUTO: &str = "GLSTEREO_AUTO";
/// Automatic stereo's separation, in percent of its maximum.
pub const ENV_SEPARATION: &str = "GLSTEREO_SEPARATION";
/// Automatic stereo's convergence: the w (distance) at the screen.
pub const ENV_CONVERGENCE: &str = "GLSTEREO_CONVERGENCE";

/// The default separation, percent: NVIDIA 3D Vision's default depth
/// amount, already the library's initial value for NV_3dvision_settings.
pub const DEFAULT_SEPARATION: f32 = 15.0;

/// How automatic stereo makes the eyes of a mono program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AutoMode {
    /// Every draw made once per eye, its vertices moved by the rule
    /// (`--auto`, `--auto=geometry`): exact, about twice the rendering.
    Geometry,
    /// The frame rendered once, mono; both eyes made from its colour and
    /// depth at the present (`--auto=depth`, [`crate::reproject`]).
    Depth,
}

impl AutoMode {
    /// The name glstereo-run and `GLSTEREO_AUTO` take.
    pub fn name(self) -> &'static str {
        match self {
            AutoMode::Geometry => "geometry",
            AutoMode::Depth => "depth",
        }
    }
}

/// The live settings.
struct Live {
    /// Mono programs get automatic stereo (glstereo-run --auto).
    auto: bool,
    /// [`AutoMode`] as 0 (geometry) or 1 (depth).
    mode: AtomicU8,
    /// Automatic stereo is on (3D Vision's Ctrl+T,
    /// glEnable(GL_3DVISION_STEREO_NV)); only with `auto`.
    auto_on: AtomicBool,
    /// f32 bits, percent.
    separation: AtomicU32,
    /// f32 bits; NaN: automatic.
    convergence: AtomicU32,
    /// f32 bits: the value automatic convergence chose last; NaN: none yet.
    automatic: AtomicU32,
    /// Two f32s (low: the screen's NDC depth, high: the projection's depth
    /// offset α): the convergence automatic convergence chose last as a
    /// depth, where the scene's projection was not known; NaN: none.
    automatic_depth: AtomicU64,
}

const NO_DEPTH: u64 = 0x7FC0_0000;

fn live() -> &'static Live {
    static LIVE: OnceLock<Live> = OnceLock::new();
    LIVE.get_or_init(|| {
        let auto = match std::env::var(ENV_AUTO).ok().as_deref().map(str::trim) {
            None | Some("") => None,
            Some(v) => parse_auto(v).unwrap_or_else(|e| {
                warn(&format!("{e}; automatic stereo is off"));
                None
            }),
        };
        let (auto, mode) = (auto.is_some(), auto.unwrap_or(AutoMode::Geometry));
        let separation = std::env::var(ENV_SEPARATION)
            .ok()
            .filter(|v| !v.trim().is_empty())
            .map_or(Ok(DEFAULT_SEPARATION), |v| parse_separation(&v))
            .unwrap_or_else(|e| {
                warn(&format!("{e}; using {DEFAULT_SEPARATION}"));
                DEFAULT_SEPARATION
            });
        let convergence = std::env::var(ENV_CONVERGENCE)
            .ok()
            .filter(|v| !v.trim().is_empty())
            .map_or(Ok(None), |v| parse_convergence(&v))
            .unwrap_or_else(|e| {
                warn(&format!("{e}; using auto"));
                None
            });
        Live {
            auto,
            mode: AtomicU8::new(mode as u8),
            auto_on: AtomicBool::new(auto),
            separation: AtomicU32::new(separation.to_bits()),
            convergence: AtomicU32::new(convergence.unwrap_or(f32::NAN).to_bits()),
            automatic: AtomicU32::new(f32::NAN.to_bits()),
            automatic_depth: AtomicU64::new(NO_DEPTH),
        }
    })
}

/// `0`/`1`/`true`/`false`/`yes`/`no`, any case.
fn parse_flag(v: &str) -> Option<bool> {
    match v.trim().to_ascii_lowercase().as_str() {
        "1" | "true" | "yes" => Some(true),
        "0" | "false" | "no" => Some(false),
        _ => None,
    }
}

/// GLSTEREO_AUTO: Some(mode) for automatic stereo (`1`, `true`, `yes`,
/// `geometry`: [`AutoMode::Geometry`]; `depth`), None for off (`0`,
/// `false`, `no`), any case.
pub fn parse_auto(v: &str) -> crate::Result<Option<AutoMode>> {
    match v.trim().to_ascii_lowercase().as_str() {
        "geometry" => Ok(Some(AutoMode::Geometry)),
        "depth" => Ok(Some(AutoMode::Depth)),
        f => match parse_flag(f) {
            Some(on) => Ok(on.then_some(AutoMode::Geometry)),
            None => Err(crate::Error::invalid_value(format!(
                "{ENV_AUTO}={v:?} is not 0, 1, geometry or depth"
            ))),
        },
    }
}

/// GLSTEREO_SEPARATION: a percentage, 0 … 100.
pub fn parse_separation(v: &str) -> crate::Result<f32> {
    match v.trim().parse::<f32>() {
        Ok(s) if (0.0..=100.0).contains(&s) => Ok(s),
        _ => Err(crate::Error::invalid_value(format!(
            "{ENV_SEPARATION}={v:?} is not a percentage from 0 to 100"
        ))),
    }
}

/// GLSTEREO_CONVERGENCE: `auto` (None), or a distance > 0.
pub fn parse_convergence(v: &str) -> crate::Result<Option<f32>> {
    let t = v.trim();
    if t.eq_ignore_ascii_case("auto") {
        return Ok(None);
    }
    match t.parse::<f32>() {
        Ok(c) if c.is_finite() && c > 0.0 => Ok(Some(c)),
        _ => Err(crate::Error::invalid_value(format!(
            "{ENV_CONVERGENCE}={v:?} is not auto or a distance greater than 0"
        ))),
    }
}

/// Whether mono programs get automatic stereo (glstereo-run --auto).
pub fn auto_requested() -> bool {
    live().auto
}

/// Whether automatic stereo is on now (requested, and not turned off).
pub fn auto_on() -> bool {
    let l = live();
    l.auto && l.auto_on.load(Ordering::Relaxed)
}

/// Turns automatic stereo on or off (only where it was requested).
pub fn set_auto_on(on: bool) {
    live().auto_on.store(on, Ordering::Relaxed);
}

/// How automatic stereo makes the eyes now ([`AutoMode`]).
pub fn auto_mode() -> AutoMode {
    match live().mode.load(Ordering::Relaxed) {
        0 => AutoMode::Geometry,
        _ => AutoMode::Depth,
    }
}

/// Makes the eyes so from the next frame on (only where automatic stereo
/// was requested).
pub fn set_auto_mode(mode: AutoMode) {
    live().mode.store(mode as u8, Ordering::Relaxed);
}

/// Whether this frame's eyes are made from its depth: automatic stereo
/// requested, in [`AutoMode::Depth`] (on or off: off, both eyes are the
/// frame).
pub fn from_depth() -> bool {
    live().auto && auto_mode() == AutoMode::Depth
}

/// Automatic stereo's separation now, percent (0 … 100).
pub fn separation() -> f32 {
    f32::from_bits(live().separation.load(Ordering::Relaxed))
}

/// Sets the separation (clamped to 0 … 100).
pub fn set_separation(percent: f32) {
    let s = if percent.is_finite() {
        percent.clamp(0.0, 100.0)
    } else {
        DEFAULT_SEPARATION
    };
    live().separation.store(s.to_bits(), Ordering::Relaxed);
}

/// Automatic stereo's convergence now: Some(distance), or None for
/// automatic.
pub fn convergence() -> Option<f32> {
    let c = f32::from_bits(live().convergence.load(Ordering::Relaxed));
    (!c.is_nan()).then_some(c)
}

/// Sets the convergence (None: automatic; a value that is not finite is
/// ignored). The user's values are > 0 ([`parse_convergence`]); a
/// program's own glStereoParameterfNV may set any finite one, 0 (the
/// extension's initial value) included.
pub fn set_convergence(c: Option<f32>) {
    match c {
        Some(v) if !v.is_finite() => {}
        v => live()
            .convergence
            .store(v.unwrap_or(f32::NAN).to_bits(), Ordering::Relaxed),
    }
}

/// The convergence automatic convergence chose last (what the scene is
/// converged at while [`convergence`] is None), None before it chose one.
/// The live keys step from it when the user first takes convergence over
/// ([`crate::interpose::controls`]).
pub fn automatic_convergence() -> Option<f32> {
    let c = f32::from_bits(live().automatic.load(Ordering::Relaxed));
    (!c.is_nan()).then_some(c)
}

/// Automatic stereo says which convergence it chose (a value ≤ 0 or not
/// finite is ignored); it replaces a convergence chosen as a depth.
pub fn set_automatic_convergence(c: f32) {
    if c.is_finite() && c > 0.0 {
        live().automatic.store(c.to_bits(), Ordering::Relaxed);
        live().automatic_depth.store(NO_DEPTH, Ordering::Relaxed);
    }
}

/// The convergence automatic convergence chose last as a depth, where
/// the scene's projection was not known (a program whose matrices are in
/// uniform buffers or built in its shader): the screen's NDC depth z_c
/// and the depth offset α of the projection kind (clip z = α·w + β),
/// ([`crate::auto::converge`]). None when it chose a distance, or
/// nothing yet.
pub fn automatic_depth() -> Option<(f32, f32)> {
    let v = live().automatic_depth.load(Ordering::Relaxed);
    let z = f32::from_bits(v as u32);
    (!z.is_nan()).then(|| (z, f32::from_bits((v >> 32) as u32)))
}

/// Automatic stereo says it chose the depth `z` (NDC) of a projection of
/// depth offset `alpha`; it replaces a convergence chosen as a distance.
pub fn set_automatic_depth(z: f32, alpha: f32) {
    if z.is_finite() && alpha.is_finite() && z != alpha {
        let v = u64::from(z.to_bits()) | u64::from(alpha.to_bits()) << 32;
        live().automatic_depth.store(v, Ordering::Relaxed);
        live()
            .automatic
            .store(f32::NAN.to_bits(), Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn separation_and_convergence_parse_as_documented() {
        assert_eq!(parse_separation(" 15 ").unwrap(), 15.0);
        assert_eq!(parse_separation("0").unwrap(), 0.0);
        assert_eq!(parse_separation("100").unwrap(), 100.0);
        for bad in ["-1", "100.5", "x", "", "NaN"] {
            assert!(parse_separation(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_convergence("AUTO").unwrap(), None);
        assert_eq!(parse_convergence("2.5").unwrap(), Some(2.5));
        for bad in ["0", "-3", "inf", "near"] {
            assert!(parse_convergence(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_flag("Yes"), Some(true));
        assert_eq!(parse_auto(" Depth ").unwrap(), Some(AutoMode::Depth));
        assert_eq!(parse_auto("geometry").unwrap(), Some(AutoMode::Geometry));
        assert_eq!(parse_auto("1").unwrap(), Some(AutoMode::Geometry));
        assert_eq!(parse_auto("no").unwrap(), None);
        for bad in ["bogus", "deep", "2", ""] {
            assert!(parse_auto(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_flag("nope"), None);
    }
}

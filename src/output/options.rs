//! The options every output mode takes, and reading them (with the mode)
//! from the environment.
//!
//! | variable             | accepted                                   | default |
//! |----------------------|--------------------------------------------|---------|
//! | `GLSTEREO_MODE`      | a canonical mode name or alias             | unset: the surface's own default |
//! | `GLSTEREO_SWAP_EYES` | `0` `1` `true` `false` `yes` `no`          | `0`     |
//! | `GLSTEREO_CROSSTALK` | a number 0 … 1                             | `0`     |
//! | `GLSTEREO_SATURATION`| a number 0 … 1                             | `1`     |
//!
//! Values are trimmed and matched case-insensitively; an empty value counts
//! as unset. Every variable is parsed before anything is returned: a bad
//! value anywhere is one error naming each bad variable, its value and what
//! is accepted, and no setting is taken from the environment at all.

use crate::error::{Error, Result};
use crate::math::Eye;

use super::mode::{OutputMode, valid_names_sentence};

/// The output mode variable.
pub const ENV_MODE: &str = "GLSTEREO_MODE";
/// The swap-eyes variable.
pub const ENV_SWAP_EYES: &str = "GLSTEREO_SWAP_EYES";
/// The crosstalk-reduction variable.
pub const ENV_CROSSTALK: &str = "GLSTEREO_CROSSTALK";
/// The anaglyph colour-saturation variable.
pub const ENV_SATURATION: &str = "GLSTEREO_SATURATION";

/// Options that apply on top of any output mode. The pipeline order is
/// fixed: swap, then saturation, then crosstalk, then the mode (see
/// [`super::cpu`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputOptions {
    /// Exchange the two eyes before anything else, in every mode (with
    /// `left` this shows the right eye). Default: false.
    pub swap_eyes: bool,
    /// Crosstalk reduction ("ghostbusting"), 0 … 1: each eye has this
    /// fraction of the other subtracted, per channel, clamped at 0.
    /// Applies to every mode that shows both eyes (not `left`/`right`).
    /// Default: 0 (off).
    pub crosstalk: f32,
    /// Anaglyph colour saturation as VTK has it, 0 … 1: each eye is blended
    /// toward its luminance, `c' = Y + saturation·(c − Y)`; 1 leaves colours
    /// unchanged, 0 makes both eyes grey. Applies to the `anaglyph-*` modes
    /// only. Default: 1 (VTK's default is 0.65).
    pub saturation: f32,
}

impl Default for OutputOptions {
    fn default() -> Self {
        OutputOptions {
            swap_eyes: false,
            crosstalk: 0.0,
            saturation: 1.0,
        }
    }
}

fn unit_interval(what: &str, v: f32) -> Result<f32> {
    if v.is_finite() && (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(Error::invalid_value(format!(
            "{what} must be a number from 0 to 1, got {v}"
        )))
    }
}

impl OutputOptions {
    /// Checks crosstalk and saturation are finite and within 0 … 1.
    pub fn validated(self) -> Result<Self> {
        unit_interval("crosstalk", self.crosstalk)?;
        unit_interval("saturation", self.saturation)?;
        Ok(self)
    }

    /// Which eye's image a `frame-sequential` frame with this index holds:
    /// the left eye on even indices, the right on odd, exchanged when
    /// `swap_eyes` is set.
    pub fn frame_sequential_eye(&self, frame_index: u64) -> Eye {
        let eye = if frame_index % 2 == 0 {
            Eye::Left
        } else {
            Eye::Right
        };
        if self.swap_eyes { eye.other() } else { eye }
    }
}

/// The mode and options together, as read from the environment.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct OutputSettings {
    /// The mode of `GLSTEREO_MODE`; None when it is unset or empty.
    pub mode: Option<OutputMode>,
    /// The options; each unset variable keeps its default.
    pub options: OutputOptions,
}

fn parse_bool(v: &str) -> Option<bool> {
    match v.to_ascii_lowercase().as_str() {
        "1" | "true" | "yes" => Some(true),
        "0" | "false" | "no" => Some(false),
        _ => None,
    }
}

fn parse_unit(v: &str) -> Option<f32> {
    v.parse::<f32>()
        .ok()
        .filter(|x| x.is_finite() && (0.0..=1.0).contains(x))
}

impl OutputSettings {
    /// Reads the settings through `get`, which returns a variable's value or
    /// None when it is unset (tests pass a map; [`OutputSettings::from_env`]
    /// passes the process environment). On error nothing is returned: the
    /// message names every bad variable.
    pub fn from_env_with(get: impl Fn(&str) -> Option<String>) -> Result<OutputSettings> {
        let value = |name: &str| {
            get(name)
                .map(|v| v.trim().to_owned())
                .filter(|v| !v.is_empty())
        };
        let mut problems = Vec::new();
        let mut settings = OutputSettings::default();

        if let Some(v) = value(ENV_MODE) {
            match OutputMode::from_name(&v) {
                Ok(m) => settings.mode = Some(m),
                Err(_) => problems.push(format!(
                    "{ENV_MODE}={v:?} is not an output mode; {}",
                    valid_names_sentence()
                )),
            }
        }
        if let Some(v) = value(ENV_SWAP_EYES) {
            match parse_bool(&v) {
                Some(b) => settings.options.swap_eyes = b,
                None => problems.push(format!(
                    "{ENV_SWAP_EYES}={v:?} is not a yes/no value; use 0, 1, true, false, yes or no"
                )),
            }
        }
        for (name, slot) in [
            (ENV_CROSSTALK, &mut settings.options.crosstalk),
            (ENV_SATURATION, &mut settings.options.saturation),
        ] {
            if let Some(v) = value(name) {
                match parse_unit(&v) {
                    Some(x) => *slot = x,
                    None => problems.push(format!(
                        "{name}={v:?} is not a number from 0 to 1 (e.g. 0, 0.25, 1)"
                    )),
                }
            }
        }

        if problems.is_empty() {
            Ok(settings)
        } else {
            Err(Error::invalid_value(problems.join("; ")))
        }
    }

    /// Reads the settings from the process environment. A value that is not
    /// valid Unicode is reported as a bad value, not ignored.
    pub fn from_env() -> Result<OutputSettings> {
        Self::from_env_with(|name| match std::env::var(name) {
            Ok(v) => Some(v),
            Err(std::env::VarError::NotPresent) => None,
            Err(std::env::VarError::NotUnicode(raw)) => Some(raw.to_string_lossy().into_owned()),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn env(pairs: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let map: HashMap<String, String> = pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |k| map.get(k).cloned()
    }

    #[test]
    fn empty_environment_gives_defaults_and_no_mode() {
        let s = OutputSettings::from_env_with(env(&[])).unwrap();
        assert_eq!(s.mode, None);
        assert_eq!(s.options, OutputOptions::default());
        assert_eq!(
            OutputOptions::default(),
            OutputOptions {
                swap_eyes: false,
                crosstalk: 0.0,
                saturation: 1.0
            }
        );
        let blank = OutputSettings::from_env_with(env(&[(ENV_MODE, "  "), (ENV_CROSSTALK, "")]));
        assert_eq!(
            blank,
            Ok(OutputSettings::default()),
            "empty counts as unset"
        );
    }

    #[test]
    fn every_variable_is_read() {
        let s = OutputSettings::from_env_with(env(&[
            (ENV_MODE, "VERTICAL_SPLIT"),
            (ENV_SWAP_EYES, "Yes"),
            (ENV_CROSSTALK, " 0.25 "),
            (ENV_SATURATION, "0.65"),
        ]))
        .unwrap();
        assert_eq!(s.mode, Some(OutputMode::TopBottomHalf));
        assert!(s.options.swap_eyes);
        assert_eq!(s.options.crosstalk, 0.25);
        assert_eq!(s.options.saturation, 0.65);
    }

    #[test]
    fn swap_eyes_accepts_exactly_the_documented_words() {
        for (v, want) in [
            ("0", false),
            ("1", true),
            ("true", true),
            ("FALSE", false),
            ("yes", true),
            ("No", false),
        ] {
            let s = OutputSettings::from_env_with(env(&[(ENV_SWAP_EYES, v)])).unwrap();
            assert_eq!(s.options.swap_eyes, want, "GLSTEREO_SWAP_EYES={v}");
        }
        for bad in ["2", "y", "on", "-1"] {
            assert!(
                OutputSettings::from_env_with(env(&[(ENV_SWAP_EYES, bad)])).is_err(),
                "GLSTEREO_SWAP_EYES={bad} was accepted"
            );
        }
    }

    #[test]
    fn bad_values_name_variable_value_and_what_is_accepted() {
        let cases = [
            (ENV_MODE, "purple", "valid names are quad"),
            (ENV_SWAP_EYES, "maybe", "0, 1, true, false, yes or no"),
            (ENV_CROSSTALK, "1.5", "from 0 to 1"),
            (ENV_CROSSTALK, "nan", "from 0 to 1"),
            (ENV_SATURATION, "-0.1", "from 0 to 1"),
            (ENV_SATURATION, "lots", "from 0 to 1"),
        ];
        for (var, value, accepted) in cases {
            let err = OutputSettings::from_env_with(env(&[(var, value)])).unwrap_err();
            assert_eq!(err.code(), crate::ffi::types::GLS_ERROR_INVALID_VALUE);
            let msg = err.to_string();
            assert!(
                msg.contains(var) && msg.contains(value) && msg.contains(accepted),
                "{var}={value}: message {msg:?} should name the variable, the value and {accepted:?}"
            );
        }
    }

    #[test]
    fn one_bad_value_rejects_the_whole_environment_and_reports_all() {
        let r = OutputSettings::from_env_with(env(&[
            (ENV_MODE, "rc"),
            (ENV_SWAP_EYES, "1"),
            (ENV_CROSSTALK, "2"),
            (ENV_SATURATION, "x"),
        ]));
        let msg = r.expect_err("bad crosstalk must fail").to_string();
        assert!(
            msg.contains(ENV_CROSSTALK) && msg.contains(ENV_SATURATION),
            "both bad variables reported: {msg}"
        );
        assert!(!msg.contains(ENV_MODE), "good variables not blamed: {msg}");
    }

    #[test]
    fn options_validation_rejects_out_of_range() {
        assert!(OutputOptions::default().validated().is_ok());
        for (k, s) in [
            (-0.01, 1.0),
            (1.01, 1.0),
            (f32::NAN, 1.0),
            (0.0, 2.0),
            (0.0, f32::INFINITY),
        ] {
            let o = OutputOptions {
                swap_eyes: false,
                crosstalk: k,
                saturation: s,
            };
            assert!(
                o.validated().is_err(),
                "crosstalk {k}, saturation {s} accepted"
            );
        }
    }

    #[test]
    fn frame_sequential_eye_alternates_from_left_and_swaps() {
        let o = OutputOptions::default();
        assert_eq!(o.frame_sequential_eye(0), Eye::Left);
        assert_eq!(o.frame_sequential_eye(1), Eye::Right);
        assert_eq!(o.frame_sequential_eye(u64::MAX), Eye::Right);
        let swapped = OutputOptions {
            swap_eyes: true,
            ..o
        };
        assert_eq!(swapped.frame_sequential_eye(0), Eye::Right);
        assert_eq!(swapped.frame_sequential_eye(7), Eye::Left);
    }
}

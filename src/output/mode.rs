//! The output modes: one enum, their canonical names, and the aliases users
//! bring from VirtualGL and OpenSceneGraph.
//!
//! Names are matched case-insensitively after trimming surrounding
//! whitespace. Every canonical name parses to its mode; so does every alias
//! in [`ALIASES`]. Anything else is [`Error::InvalidValue`] with a message
//! that lists every valid name.

use std::ffi::CStr;
use std::fmt;
use std::str::FromStr;

use crate::error::{Error, Result};

/// Which pair of coloured filters the viewer's anaglyph glasses have. The
/// first colour is the filter over the LEFT eye.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AnaglyphColors {
    /// Red over the left eye, cyan over the right.
    RedCyan,
    /// Green over the left eye, magenta over the right.
    GreenMagenta,
    /// Amber (yellow) over the left eye, blue over the right (ColorCode 3-D).
    AmberBlue,
}

impl AnaglyphColors {
    /// All three, in the order of the canonical mode list.
    pub const ALL: [AnaglyphColors; 3] = [
        AnaglyphColors::RedCyan,
        AnaglyphColors::GreenMagenta,
        AnaglyphColors::AmberBlue,
    ];

    /// Which output channels (R, G, B) the LEFT eye supplies; the right eye
    /// supplies the others. Red-cyan: R; green-magenta: G; amber-blue: R and G.
    pub fn left_channels(self) -> [bool; 3] {
        match self {
            AnaglyphColors::RedCyan => [true, false, false],
            AnaglyphColors::GreenMagenta => [false, true, false],
            AnaglyphColors::AmberBlue => [true, true, false],
        }
    }
}

/// How each eye's colour is treated inside an anaglyph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AnaglyphMethod {
    /// Plain channel mask in full colour (no suffix).
    FullColor,
    /// `-half`: the left eye's channels carry its luminance, the right eye's
    /// channels stay in colour.
    HalfColor,
    /// `-mono`: both eyes' channels carry their luminance.
    Monochrome,
    /// `-dubois`: Eric Dubois' least-squares matrices, applied in linear light.
    Dubois,
}

impl AnaglyphMethod {
    /// All four, in the order of the canonical mode list.
    pub const ALL: [AnaglyphMethod; 4] = [
        AnaglyphMethod::FullColor,
        AnaglyphMethod::HalfColor,
        AnaglyphMethod::Monochrome,
        AnaglyphMethod::Dubois,
    ];
}

/// Every way glstereo can show the two eyes. See each variant for where the
/// eyes go; rows and columns count from the TOP-LEFT pixel of the output
/// (row 0 is the top row, as in [`crate::image::Image`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OutputMode {
    /// `quad`: native quad-buffer passthrough. Not a composite: the CPU
    /// reference refuses it; a surface on a non-native config falls back.
    Quad,
    /// `left`: the left eye only, unchanged.
    Left,
    /// `right`: the right eye only, unchanged.
    Right,
    /// `anaglyph-<colors>[-half|-mono|-dubois]`: one frame of the eye size,
    /// each eye seen through one coloured filter.
    Anaglyph(AnaglyphColors, AnaglyphMethod),
    /// `anaglyph-red-blue`: red = left luminance, green 0, blue = right
    /// luminance, for the CrystalEyes-era demos and red/blue glasses.
    AnaglyphRedBlue,
    /// `side-by-side`: both eyes at full size in a 2W×H frame, left on the left.
    SideBySide,
    /// `top-bottom`: both eyes at full size in a W×2H frame, left on top.
    TopBottom,
    /// `side-by-side-half`: each eye squeezed (filtered) to half width in a
    /// W×H frame, left on the left.
    SideBySideHalf,
    /// `top-bottom-half`: each eye squeezed (filtered) to half height in a
    /// W×H frame, left on top.
    TopBottomHalf,
    /// `rows`: row-interleaved; even rows (the top row is row 0) from the left eye.
    Rows,
    /// `columns`: column-interleaved; even columns (the leftmost is 0) from the left eye.
    Columns,
    /// `checkerboard`: pixel (x, y) from the left eye when x + y is even.
    Checkerboard,
    /// `frame-sequential`: each presented frame holds one eye at full size,
    /// the left eye on even frame indices.
    FrameSequential,
    /// `hdmi-frame-packing`: left on top, a black gap, right below
    /// (1280x720 → 1280x1470).
    HdmiFramePacking,
    /// `starbase`: HP Starbase sync-doubled stereo; the left eye squashed
    /// into the upper half, the right into the lower half, same frame size.
    Starbase,
    /// `str-rect`: SGI STR_RECT; each eye squashed to 492/1024 of the
    /// height, left on top, a black band between.
    StrRect,
}

use AnaglyphColors::*;
use AnaglyphMethod::*;

impl OutputMode {
    /// Every mode, in the canonical order (also the order of the
    /// `GLS_OUTPUT_*` constants, which number them from 0).
    pub const ALL: [OutputMode; 27] = [
        OutputMode::Quad,
        OutputMode::Left,
        OutputMode::Right,
        OutputMode::Anaglyph(RedCyan, FullColor),
        OutputMode::Anaglyph(RedCyan, HalfColor),
        OutputMode::Anaglyph(RedCyan, Monochrome),
        OutputMode::Anaglyph(RedCyan, Dubois),
        OutputMode::Anaglyph(GreenMagenta, FullColor),
        OutputMode::Anaglyph(GreenMagenta, HalfColor),
        OutputMode::Anaglyph(GreenMagenta, Monochrome),
        OutputMode::Anaglyph(GreenMagenta, Dubois),
        OutputMode::Anaglyph(AmberBlue, FullColor),
        OutputMode::Anaglyph(AmberBlue, HalfColor),
        OutputMode::Anaglyph(AmberBlue, Monochrome),
        OutputMode::Anaglyph(AmberBlue, Dubois),
        OutputMode::AnaglyphRedBlue,
        OutputMode::SideBySide,
        OutputMode::TopBottom,
        OutputMode::SideBySideHalf,
        OutputMode::TopBottomHalf,
        OutputMode::Rows,
        OutputMode::Columns,
        OutputMode::Checkerboard,
        OutputMode::FrameSequential,
        OutputMode::HdmiFramePacking,
        OutputMode::Starbase,
        OutputMode::StrRect,
    ];

    /// Iterates over every mode in canonical order.
    pub fn all() -> impl Iterator<Item = OutputMode> {
        Self::ALL.into_iter()
    }

    /// The position of this mode in [`OutputMode::ALL`].
    pub fn index(self) -> usize {
        Self::ALL
            .iter()
            .position(|&m| m == self)
            .expect("OutputMode::ALL lists every mode")
    }

    /// The canonical name as a NUL-terminated static string (what
    /// `gls_output_name()` returns).
    pub fn canonical_c_name(self) -> &'static CStr {
        match self {
            OutputMode::Quad => c"quad",
            OutputMode::Left => c"left",
            OutputMode::Right => c"right",
            OutputMode::Anaglyph(RedCyan, FullColor) => c"anaglyph-red-cyan",
            OutputMode::Anaglyph(RedCyan, HalfColor) => c"anaglyph-red-cyan-half",
            OutputMode::Anaglyph(RedCyan, Monochrome) => c"anaglyph-red-cyan-mono",
            OutputMode::Anaglyph(RedCyan, Dubois) => c"anaglyph-red-cyan-dubois",
            OutputMode::Anaglyph(GreenMagenta, FullColor) => c"anaglyph-green-magenta",
            OutputMode::Anaglyph(GreenMagenta, HalfColor) => c"anaglyph-green-magenta-half",
            OutputMode::Anaglyph(GreenMagenta, Monochrome) => c"anaglyph-green-magenta-mono",
            OutputMode::Anaglyph(GreenMagenta, Dubois) => c"anaglyph-green-magenta-dubois",
            OutputMode::Anaglyph(AmberBlue, FullColor) => c"anaglyph-amber-blue",
            OutputMode::Anaglyph(AmberBlue, HalfColor) => c"anaglyph-amber-blue-half",
            OutputMode::Anaglyph(AmberBlue, Monochrome) => c"anaglyph-amber-blue-mono",
            OutputMode::Anaglyph(AmberBlue, Dubois) => c"anaglyph-amber-blue-dubois",
            OutputMode::AnaglyphRedBlue => c"anaglyph-red-blue",
            OutputMode::SideBySide => c"side-by-side",
            OutputMode::TopBottom => c"top-bottom",
            OutputMode::SideBySideHalf => c"side-by-side-half",
            OutputMode::TopBottomHalf => c"top-bottom-half",
            OutputMode::Rows => c"rows",
            OutputMode::Columns => c"columns",
            OutputMode::Checkerboard => c"checkerboard",
            OutputMode::FrameSequential => c"frame-sequential",
            OutputMode::HdmiFramePacking => c"hdmi-frame-packing",
            OutputMode::Starbase => c"starbase",
            OutputMode::StrRect => c"str-rect",
        }
    }

    /// The canonical name, e.g. `"anaglyph-red-cyan-dubois"`.
    pub fn canonical_name(self) -> &'static str {
        // The names above are ASCII literals, so this cannot fail.
        self.canonical_c_name().to_str().unwrap_or("")
    }

    /// The mode of a canonical name or alias, case-insensitive, surrounding
    /// whitespace ignored. Unknown names are [`Error::InvalidValue`] listing
    /// every valid name.
    pub fn from_name(name: &str) -> Result<OutputMode> {
        let wanted = name.trim();
        if let Some(m) = Self::all().find(|m| m.canonical_name().eq_ignore_ascii_case(wanted)) {
            return Ok(m);
        }
        if let Some(a) = ALIASES.iter().find(|a| a.name.eq_ignore_ascii_case(wanted)) {
            return Ok(a.mode);
        }
        Err(Error::invalid_value(format!(
            "unknown output mode {name:?}; {}",
            valid_names_sentence()
        )))
    }

    /// True for modes whose output holds both eyes in one frame or sequence
    /// (everything but `quad`, `left` and `right`): the modes where crosstalk
    /// reduction applies.
    pub fn shows_both_eyes(self) -> bool {
        !matches!(
            self,
            OutputMode::Quad | OutputMode::Left | OutputMode::Right
        )
    }

    /// True for the anaglyph family (`anaglyph-*`): the modes where colour
    /// saturation applies.
    pub fn is_anaglyph(self) -> bool {
        matches!(self, OutputMode::Anaglyph(..) | OutputMode::AnaglyphRedBlue)
    }
}

impl fmt::Display for OutputMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.canonical_name())
    }
}

impl FromStr for OutputMode {
    type Err = Error;
    fn from_str(s: &str) -> Result<OutputMode> {
        OutputMode::from_name(s)
    }
}

/// Which program's vocabulary an alias comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AliasSource {
    /// VirtualGL's `vglrun -st` / `VGL_STEREO` letters.
    VirtualGl,
    /// OpenSceneGraph's `OSG_STEREO_MODE` names.
    OpenSceneGraph,
}

/// A name another program uses for one of our modes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Alias {
    /// The alias as that program spells it (matched case-insensitively).
    pub name: &'static str,
    /// The mode it selects here.
    pub mode: OutputMode,
    /// The program it comes from.
    pub source: AliasSource,
    /// How that program's output differs from ours, or "" when it matches.
    pub differs: &'static str,
}

const fn vgl(name: &'static str, mode: OutputMode, differs: &'static str) -> Alias {
    Alias {
        name,
        mode,
        source: AliasSource::VirtualGl,
        differs,
    }
}

const fn osg(name: &'static str, mode: OutputMode, differs: &'static str) -> Alias {
    Alias {
        name,
        mode,
        source: AliasSource::OpenSceneGraph,
        differs,
    }
}

/// Every alias, with what it maps to and where the peer's picture differs
/// from ours. Decided from what each program actually draws:
///
/// - VirtualGL (`server/VirtualWin.cpp`, `common/Frame.cpp`): its frames are
///   bottom-up. `rc`/`gm` are the same channel masks as ours. `by` takes R and
///   G from the RIGHT eye and B from the LEFT, the opposite of our
///   `anaglyph-amber-blue`. `i` copies row j (counted from the BOTTOM) from
///   the left eye when j is even. `tb` keeps every other row (dropped, not
///   filtered) and puts the left eye in the BOTTOM half. `ss` keeps every
///   other column, left eye on the left. `quad`, `left`, `right` are already
///   canonical names here.
/// - OpenSceneGraph (`osgViewer/View.cpp`, 3.x): `ANAGLYPHIC` draws the left
///   eye through a red colour mask and the right through cyan, in full
///   colour. `HORIZONTAL_SPLIT` / `VERTICAL_SPLIT` divide the window into two
///   viewports (left eye left / top by default), so each eye gets half the
///   frame: our `-half` modes. The interlace and checkerboard modes draw the
///   left eye where a polygon-stipple stencil, anchored at the window's
///   BOTTOM-left pixel, is 0: bottom row 0 is right, row 1 left; column 0 is
///   left; the bottom-left pixel is left in the checkerboard.
pub const ALIASES: &[Alias] = &[
    vgl("rc", OutputMode::Anaglyph(RedCyan, FullColor), ""),
    vgl("gm", OutputMode::Anaglyph(GreenMagenta, FullColor), ""),
    vgl(
        "by",
        OutputMode::Anaglyph(AmberBlue, FullColor),
        "VirtualGL shows the LEFT eye in blue and the right in amber (R,G); \
         we show the left eye in amber, as ColorCode 3-D glasses expect: set \
         GLSTEREO_SWAP_EYES=1 for VirtualGL's assignment",
    ),
    vgl(
        "i",
        OutputMode::Rows,
        "VirtualGL counts rows from the BOTTOM (its bottom row is left); we \
         count from the top (our top row is left): the two agree only when \
         the height is odd",
    ),
    vgl(
        "tb",
        OutputMode::TopBottomHalf,
        "VirtualGL puts the left eye at the BOTTOM and drops every other row; \
         we put the left eye on top and filter",
    ),
    vgl(
        "ss",
        OutputMode::SideBySideHalf,
        "VirtualGL drops every other column; we filter (left on the left in both)",
    ),
    osg("QUAD_BUFFER", OutputMode::Quad, ""),
    osg("ANAGLYPHIC", OutputMode::Anaglyph(RedCyan, FullColor), ""),
    osg(
        "HORIZONTAL_SPLIT",
        OutputMode::SideBySideHalf,
        "OpenSceneGraph renders each eye straight into its half-window \
         viewport; we squeeze the full-size eye into it",
    ),
    osg(
        "VERTICAL_SPLIT",
        OutputMode::TopBottomHalf,
        "OpenSceneGraph renders each eye straight into its half-window \
         viewport; we squeeze the full-size eye into it",
    ),
    osg(
        "HORIZONTAL_INTERLACE",
        OutputMode::Rows,
        "OpenSceneGraph's bottom row is the right eye; our top row is the \
         left eye: the two agree only when the height is even",
    ),
    osg("VERTICAL_INTERLACE", OutputMode::Columns, ""),
    osg(
        "CHECKERBOARD",
        OutputMode::Checkerboard,
        "OpenSceneGraph's bottom-left pixel is the left eye; our top-left \
         pixel is: the two agree only when the height is odd",
    ),
    osg("LEFT_EYE", OutputMode::Left, ""),
    osg("RIGHT_EYE", OutputMode::Right, ""),
];

/// "valid names are quad, left, …; aliases: rc, gm, …" — the tail of every
/// unknown-mode message.
pub fn valid_names_sentence() -> String {
    let names: Vec<&str> = OutputMode::all().map(OutputMode::canonical_name).collect();
    let aliases: Vec<&str> = ALIASES
        .iter()
        .map(|a| a.name)
        .filter(|a| !names.iter().any(|n| n.eq_ignore_ascii_case(a)))
        .collect();
    format!(
        "valid names are {}; aliases (VirtualGL, OpenSceneGraph): {}",
        names.join(", "),
        aliases.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_lists_each_mode_once_with_a_distinct_name() {
        let mut names: Vec<&str> = OutputMode::all().map(OutputMode::canonical_name).collect();
        assert_eq!(names.len(), 27);
        names.sort();
        names.dedup();
        assert_eq!(names.len(), 27, "canonical names must be distinct");
        for (i, m) in OutputMode::all().enumerate() {
            assert_eq!(m.index(), i, "{m} is at position {i} of ALL");
        }
    }

    #[test]
    fn every_anaglyph_combination_is_listed() {
        for c in AnaglyphColors::ALL {
            for m in AnaglyphMethod::ALL {
                let mode = OutputMode::Anaglyph(c, m);
                assert!(OutputMode::ALL.contains(&mode), "{mode:?} missing from ALL");
            }
        }
    }

    #[test]
    fn canonical_names_parse_back_in_any_case() {
        for m in OutputMode::all() {
            let name = m.canonical_name();
            assert_eq!(OutputMode::from_name(name), Ok(m), "{name}");
            assert_eq!(
                name.to_uppercase().parse::<OutputMode>(),
                Ok(m),
                "upper-case {name}"
            );
            assert_eq!(OutputMode::from_name(&format!("  {name}\n")), Ok(m));
            assert_eq!(m.to_string(), name);
        }
    }

    #[test]
    fn suffixes_name_the_anaglyph_method() {
        for m in OutputMode::all() {
            if let OutputMode::Anaglyph(_, method) = m {
                let name = m.canonical_name();
                let want = match method {
                    FullColor => {
                        !name.ends_with("-half")
                            && !name.ends_with("-mono")
                            && !name.ends_with("-dubois")
                    }
                    HalfColor => name.ends_with("-half"),
                    Monochrome => name.ends_with("-mono"),
                    Dubois => name.ends_with("-dubois"),
                };
                assert!(want, "{name} does not match {method:?}");
            }
        }
    }

    #[test]
    fn every_alias_maps_as_documented_in_any_case() {
        let want = [
            ("rc", "anaglyph-red-cyan"),
            ("gm", "anaglyph-green-magenta"),
            ("by", "anaglyph-amber-blue"),
            ("i", "rows"),
            ("tb", "top-bottom-half"),
            ("ss", "side-by-side-half"),
            ("quad", "quad"),
            ("left", "left"),
            ("right", "right"),
            ("QUAD_BUFFER", "quad"),
            ("ANAGLYPHIC", "anaglyph-red-cyan"),
            ("HORIZONTAL_SPLIT", "side-by-side-half"),
            ("VERTICAL_SPLIT", "top-bottom-half"),
            ("HORIZONTAL_INTERLACE", "rows"),
            ("VERTICAL_INTERLACE", "columns"),
            ("CHECKERBOARD", "checkerboard"),
            ("LEFT_EYE", "left"),
            ("RIGHT_EYE", "right"),
        ];
        for (alias, canonical) in want {
            for spelling in [alias.to_owned(), alias.to_lowercase(), alias.to_uppercase()] {
                let got = OutputMode::from_name(&spelling).map(OutputMode::canonical_name);
                assert_eq!(got, Ok(canonical), "alias {spelling:?}");
            }
        }
        // Every entry of ALIASES is covered by the table above.
        for a in ALIASES {
            assert!(
                want.iter().any(|(n, _)| *n == a.name),
                "alias {} untested",
                a.name
            );
        }
    }

    #[test]
    fn an_alias_spelled_like_a_canonical_name_means_that_mode() {
        // OSG's CHECKERBOARD is our checkerboard; an alias that meant another
        // mode than its canonical namesake could never be reached.
        for a in ALIASES {
            if let Some(m) =
                OutputMode::all().find(|m| m.canonical_name().eq_ignore_ascii_case(a.name))
            {
                assert_eq!(m, a.mode, "alias {} collides with canonical {m}", a.name);
            }
        }
    }

    #[test]
    fn unknown_name_is_invalid_value_listing_every_name() {
        let err = OutputMode::from_name("anaglyph-purple").unwrap_err();
        assert_eq!(err.code(), crate::ffi::types::GLS_ERROR_INVALID_VALUE);
        let msg = err.to_string();
        assert!(msg.contains("\"anaglyph-purple\""), "message: {msg}");
        for m in OutputMode::all() {
            assert!(
                msg.contains(m.canonical_name()),
                "message lacks {}: {msg}",
                m.canonical_name()
            );
        }
        let lower = msg.to_lowercase();
        for a in ALIASES {
            assert!(
                lower.contains(&a.name.to_lowercase()),
                "message lacks alias {}: {msg}",
                a.name
            );
        }
        assert!(OutputMode::from_name("").is_err());
        assert!(OutputMode::from_name("side by side").is_err());
    }

    #[test]
    fn left_channels_are_the_documented_masks() {
        assert_eq!(RedCyan.left_channels(), [true, false, false]);
        assert_eq!(GreenMagenta.left_channels(), [false, true, false]);
        assert_eq!(AmberBlue.left_channels(), [true, true, false]);
    }
}

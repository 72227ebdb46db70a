//! Output modes through the C ABI: the GLS_OUTPUT_* values and the
//! translation between them and mode names. None of these calls need a GL
//! context; all are thread-safe.

use std::ffi::c_char;

use super::boundary::{arg_out, arg_str, ffi_boundary, write_out};
use crate::error::{Error, Result};
use crate::output::{AnaglyphColors as C, AnaglyphMethod as M, OutputMode};

/// Native quad-buffer stereo ("quad"): both eyes go to the driver's left and
/// right buffers. Only on configs with native stereo; elsewhere a surface
/// falls back to a composite.
pub const GLS_OUTPUT_QUAD: u32 = 0;
/// The left eye only ("left").
pub const GLS_OUTPUT_LEFT: u32 = 1;
/// The right eye only ("right").
pub const GLS_OUTPUT_RIGHT: u32 = 2;
/// Red-cyan anaglyph in full colour ("anaglyph-red-cyan"): R from the left eye, G and B from the right.
pub const GLS_OUTPUT_ANAGLYPH_RED_CYAN: u32 = 3;
/// Red-cyan anaglyph, left eye as luminance ("anaglyph-red-cyan-half").
pub const GLS_OUTPUT_ANAGLYPH_RED_CYAN_HALF: u32 = 4;
/// Red-cyan anaglyph, both eyes as luminance ("anaglyph-red-cyan-mono").
pub const GLS_OUTPUT_ANAGLYPH_RED_CYAN_MONO: u32 = 5;
/// Red-cyan anaglyph with Dubois' least-squares matrices ("anaglyph-red-cyan-dubois").
pub const GLS_OUTPUT_ANAGLYPH_RED_CYAN_DUBOIS: u32 = 6;
/// Green-magenta anaglyph in full colour ("anaglyph-green-magenta"): G from the left eye, R and B from the right.
pub const GLS_OUTPUT_ANAGLYPH_GREEN_MAGENTA: u32 = 7;
/// Green-magenta anaglyph, left eye as luminance ("anaglyph-green-magenta-half").
pub const GLS_OUTPUT_ANAGLYPH_GREEN_MAGENTA_HALF: u32 = 8;
/// Green-magenta anaglyph, both eyes as luminance ("anaglyph-green-magenta-mono").
pub const GLS_OUTPUT_ANAGLYPH_GREEN_MAGENTA_MONO: u32 = 9;
/// Green-magenta anaglyph with Dubois' matrices ("anaglyph-green-magenta-dubois").
pub const GLS_OUTPUT_ANAGLYPH_GREEN_MAGENTA_DUBOIS: u32 = 10;
/// Amber-blue anaglyph in full colour ("anaglyph-amber-blue"): R and G from the left eye, B from the right.
pub const GLS_OUTPUT_ANAGLYPH_AMBER_BLUE: u32 = 11;
/// Amber-blue anaglyph, left eye as luminance ("anaglyph-amber-blue-half").
pub const GLS_OUTPUT_ANAGLYPH_AMBER_BLUE_HALF: u32 = 12;
/// Amber-blue anaglyph, both eyes as luminance ("anaglyph-amber-blue-mono").
pub const GLS_OUTPUT_ANAGLYPH_AMBER_BLUE_MONO: u32 = 13;
/// Amber-blue anaglyph with Dubois' matrices ("anaglyph-amber-blue-dubois").
pub const GLS_OUTPUT_ANAGLYPH_AMBER_BLUE_DUBOIS: u32 = 14;
/// Red-blue anaglyph ("anaglyph-red-blue"): red = left luminance, green 0, blue = right luminance.
pub const GLS_OUTPUT_ANAGLYPH_RED_BLUE: u32 = 15;
/// Both eyes at full size side by side, left on the left ("side-by-side"): a 2W×H frame.
pub const GLS_OUTPUT_SIDE_BY_SIDE: u32 = 16;
/// Both eyes at full size, left on top ("top-bottom"): a W×2H frame.
pub const GLS_OUTPUT_TOP_BOTTOM: u32 = 17;
/// Each eye squeezed (filtered) to half width, left on the left ("side-by-side-half"): W×H.
pub const GLS_OUTPUT_SIDE_BY_SIDE_HALF: u32 = 18;
/// Each eye squeezed (filtered) to half height, left on top ("top-bottom-half"): W×H.
pub const GLS_OUTPUT_TOP_BOTTOM_HALF: u32 = 19;
/// Row interleave ("rows"): the top row and every second row below it from the left eye.
pub const GLS_OUTPUT_ROWS: u32 = 20;
/// Column interleave ("columns"): the leftmost column and every second one from the left eye.
pub const GLS_OUTPUT_COLUMNS: u32 = 21;
/// Checkerboard ("checkerboard"): pixel (x, y), counted from the top-left, from the left eye when x + y is even.
pub const GLS_OUTPUT_CHECKERBOARD: u32 = 22;
/// Frame-sequential ("frame-sequential"): each presented frame holds one eye, the left eye first.
pub const GLS_OUTPUT_FRAME_SEQUENTIAL: u32 = 23;
/// HDMI 1.4a frame packing ("hdmi-frame-packing"): left on top, a black gap of H/24 rows, right below (1280x720 → 1280x1470).
pub const GLS_OUTPUT_HDMI_FRAME_PACKING: u32 = 24;
/// HP Starbase sync-doubled stereo ("starbase"): left eye squashed into the upper half, right into the lower, same frame size.
pub const GLS_OUTPUT_STARBASE: u32 = 25;
/// SGI STR_RECT ("str-rect"): each eye squashed to 492 of 1024 rows (scaled for other heights), left on top, black rows between.
pub const GLS_OUTPUT_STR_RECT: u32 = 26;
/// The number of output modes: the valid GLS_OUTPUT_* values are 0 … GLS_OUTPUT_COUNT − 1.
pub const GLS_OUTPUT_COUNT: u32 = 27;

/// The GLS_OUTPUT_* value of a mode.
pub fn output_code(mode: OutputMode) -> u32 {
    match mode {
        OutputMode::Quad => GLS_OUTPUT_QUAD,
        OutputMode::Left => GLS_OUTPUT_LEFT,
        OutputMode::Right => GLS_OUTPUT_RIGHT,
        OutputMode::Anaglyph(C::RedCyan, M::FullColor) => GLS_OUTPUT_ANAGLYPH_RED_CYAN,
        OutputMode::Anaglyph(C::RedCyan, M::HalfColor) => GLS_OUTPUT_ANAGLYPH_RED_CYAN_HALF,
        OutputMode::Anaglyph(C::RedCyan, M::Monochrome) => GLS_OUTPUT_ANAGLYPH_RED_CYAN_MONO,
        OutputMode::Anaglyph(C::RedCyan, M::Dubois) => GLS_OUTPUT_ANAGLYPH_RED_CYAN_DUBOIS,
        OutputMode::Anaglyph(C::GreenMagenta, M::FullColor) => GLS_OUTPUT_ANAGLYPH_GREEN_MAGENTA,
        OutputMode::Anaglyph(C::GreenMagenta, M::HalfColor) => {
            GLS_OUTPUT_ANAGLYPH_GREEN_MAGENTA_HALF
        }
        OutputMode::Anaglyph(C::GreenMagenta, M::Monochrome) => {
            GLS_OUTPUT_ANAGLYPH_GREEN_MAGENTA_MONO
        }
        OutputMode::Anaglyph(C::GreenMagenta, M::Dubois) => {
            GLS_OUTPUT_ANAGLYPH_GREEN_MAGENTA_DUBOIS
        }
        OutputMode::Anaglyph(C::AmberBlue, M::FullColor) => GLS_OUTPUT_ANAGLYPH_AMBER_BLUE,
        OutputMode::Anaglyph(C::AmberBlue, M::HalfColor) => GLS_OUTPUT_ANAGLYPH_AMBER_BLUE_HALF,
        OutputMode::Anaglyph(C::AmberBlue, M::Monochrome) => GLS_OUTPUT_ANAGLYPH_AMBER_BLUE_MONO,
        OutputMode::Anaglyph(C::AmberBlue, M::Dubois) => GLS_OUTPUT_ANAGLYPH_AMBER_BLUE_DUBOIS,
        OutputMode::AnaglyphRedBlue => GLS_OUTPUT_ANAGLYPH_RED_BLUE,
        OutputMode::SideBySide => GLS_OUTPUT_SIDE_BY_SIDE,
        OutputMode::TopBottom => GLS_OUTPUT_TOP_BOTTOM,
        OutputMode::SideBySideHalf => GLS_OUTPUT_SIDE_BY_SIDE_HALF,
        OutputMode::TopBottomHalf => GLS_OUTPUT_TOP_BOTTOM_HALF,
        OutputMode::Rows => GLS_OUTPUT_ROWS,
        OutputMode::Columns => GLS_OUTPUT_COLUMNS,
        OutputMode::Checkerboard => GLS_OUTPUT_CHECKERBOARD,
        OutputMode::FrameSequential => GLS_OUTPUT_FRAME_SEQUENTIAL,
        OutputMode::HdmiFramePacking => GLS_OUTPUT_HDMI_FRAME_PACKING,
        OutputMode::Starbase => GLS_OUTPUT_STARBASE,
        OutputMode::StrRect => GLS_OUTPUT_STR_RECT,
    }
}

impl From<OutputMode> for u32 {
    fn from(mode: OutputMode) -> u32 {
        output_code(mode)
    }
}

impl TryFrom<u32> for OutputMode {
    type Error = Error;
    fn try_from(v: u32) -> Result<OutputMode> {
        OutputMode::all()
            .find(|&m| output_code(m) == v)
            .ok_or_else(|| {
                Error::invalid_enum(
                    "output",
                    v,
                    format!(
                        "use one of GLS_OUTPUT_QUAD (0) … GLS_OUTPUT_STR_RECT ({})",
                        GLS_OUTPUT_COUNT - 1
                    ),
                )
            })
    }
}

/// The GLS_OUTPUT_* value of an output mode name: a canonical name
/// ("anaglyph-red-cyan", "side-by-side-half", "hdmi-frame-packing", …) or an
/// alias from VirtualGL (rc, gm, by, i, tb, ss) or OpenSceneGraph
/// (QUAD_BUFFER, ANAGLYPHIC, HORIZONTAL_SPLIT, VERTICAL_SPLIT,
/// HORIZONTAL_INTERLACE, VERTICAL_INTERLACE, CHECKERBOARD, LEFT_EYE,
/// RIGHT_EYE). Case-insensitive; surrounding whitespace is ignored.
/// GLSTEREO_MODE accepts exactly the same names. Aliases select our
/// nearest mode: VirtualGL's tb and OpenSceneGraph's VERTICAL_SPLIT give
/// GLS_OUTPUT_TOP_BOTTOM_HALF with the left eye on top, whatever the peer does.
///
/// Default: none; this call only translates. A surface's mode is set with
/// gls_surface_set_output() or GLSTEREO_MODE.
///
/// @param name a NUL-terminated UTF-8 string; must not be NULL.
/// @param output_out receives the GLS_OUTPUT_* value; must not be NULL;
/// written only on success.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER when name or output_out is NULL;
/// GLS_ERROR_INVALID_VALUE when name is not a known mode (the message lists
/// every valid name) or is not UTF-8.
/// Thread-safe from any thread; needs no GL context.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_output_from_name(
    name: *const c_char,
    output_out: *mut u32,
) -> super::types::gls_result {
    ffi_boundary!("gls_output_from_name", {
        // SAFETY: NULL-checked; NUL-termination is the caller's contract.
        let name = unsafe { arg_str(name, "name")? };
        let out = arg_out(output_out, "output_out")?;
        let mode = OutputMode::from_name(name)?;
        // SAFETY: checked non-NULL; validity is the caller's contract.
        unsafe { write_out(out, output_code(mode)) };
        Ok(())
    })
}

/// The canonical name of a GLS_OUTPUT_* value, e.g.
/// "anaglyph-red-cyan-dubois" for GLS_OUTPUT_ANAGLYPH_RED_CYAN_DUBOIS;
/// gls_output_from_name() of the name gives the value back.
///
/// @param output GLS_OUTPUT_QUAD (0) … GLS_OUTPUT_STR_RECT (26).
/// @return a static string, valid for the life of the process; do not free
/// it. NULL for any other value, with a GLS_ERROR_INVALID_ENUM message for
/// gls_last_error_message().
/// Thread-safe from any thread; needs no GL context.
#[unsafe(no_mangle)]
pub extern "C" fn gls_output_name(output: u32) -> *const c_char {
    ffi_boundary!("gls_output_name", std::ptr::null() => {
        Ok(OutputMode::try_from(output)?.canonical_c_name().as_ptr())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_number_the_canonical_list_from_zero() {
        for (i, m) in OutputMode::all().enumerate() {
            assert_eq!(output_code(m), i as u32, "{m}");
            assert_eq!(OutputMode::try_from(i as u32), Ok(m));
            assert_eq!(u32::from(m), i as u32);
        }
        assert_eq!(OutputMode::ALL.len() as u32, GLS_OUTPUT_COUNT);
        assert_eq!(GLS_OUTPUT_STR_RECT, GLS_OUTPUT_COUNT - 1);
    }

    #[test]
    fn values_past_the_range_are_invalid_enum_naming_it() {
        for v in [GLS_OUTPUT_COUNT, 1000, u32::MAX] {
            let err = OutputMode::try_from(v).unwrap_err();
            assert_eq!(err.code(), crate::ffi::types::GLS_ERROR_INVALID_ENUM);
            let msg = err.to_string();
            assert!(
                msg.contains("GLS_OUTPUT_QUAD (0)") && msg.contains("GLS_OUTPUT_STR_RECT (26)"),
                "{v}: {msg}"
            );
        }
    }
}

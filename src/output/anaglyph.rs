//! The colour math of the anaglyph modes, in one place so the GL shaders can
//! take their constants from here.
//!
//! All values are normalised: a unorm8 channel v is v/255 (as GL samples
//! it), results go back with `round(f·255)` clamped to 0…255.

use super::mode::AnaglyphColors;

/// Luminance weights (R, G, B): ITU-R BT.601 luma, applied to the
/// sRGB-encoded values as stored (no linearisation).
///
/// Why these: the `-half` and `-mono` anaglyphs come from Bino, which
/// computes luminance exactly this way, and BT.601 luma is the standard
/// weighting for gamma-encoded R'G'B' (which is what the eye buffers hold).
/// They sum to 1, so a grey stays the same grey and saturation never changes
/// an eye's luminance. The same weights serve saturation, `-half`, `-mono`
/// and `anaglyph-red-blue`. (VTK's Anaglyph uses 0.3086/0.6094/0.0820 and
/// its RedBlue the plain mean (R+G+B)/3; results differ from ours by a few
/// units on saturated colours.)
pub const LUMA: [f32; 3] = [0.299, 0.587, 0.114];

/// The luminance of an RGB triple with [`LUMA`]: `0.299·R + 0.587·G + 0.114·B`.
#[inline]
pub fn luma(rgb: [f32; 3]) -> f32 {
    LUMA[0] * rgb[0] + LUMA[1] * rgb[1] + LUMA[2] * rgb[2]
}

/// Eric Dubois' least-squares anaglyph matrices for one pair of glasses:
/// rows are the output R, G, B; columns the input r, g, b; applied to
/// LINEAR RGB: `out = clamp(left · l + right · r, 0, 1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DuboisMatrices {
    /// Applied to the left eye's linear RGB.
    pub left: [[f32; 3]; 3],
    /// Applied to the right eye's linear RGB.
    pub right: [[f32; 3]; 3],
}

/// The Dubois matrices of each pair of glasses (REFERENCE.md).
pub fn dubois_matrices(colors: AnaglyphColors) -> DuboisMatrices {
    match colors {
        AnaglyphColors::RedCyan => DuboisMatrices {
            left: [
                [0.437, 0.449, 0.164],
                [-0.062, -0.062, -0.024],
                [-0.048, -0.050, -0.017],
            ],
            right: [
                [-0.011, -0.032, -0.007],
                [0.377, 0.761, 0.009],
                [-0.026, -0.093, 1.234],
            ],
        },
        AnaglyphColors::GreenMagenta => DuboisMatrices {
            left: [
                [-0.062, -0.158, -0.039],
                [0.284, 0.668, 0.143],
                [-0.015, -0.027, 0.021],
            ],
            right: [
                [0.529, 0.705, 0.024],
                [-0.016, -0.015, -0.065],
                [0.009, 0.075, 0.937],
            ],
        },
        AnaglyphColors::AmberBlue => DuboisMatrices {
            left: [
                [1.062, -0.205, 0.299],
                [-0.026, 0.908, 0.068],
                [-0.038, -0.173, 0.022],
            ],
            right: [
                [-0.016, -0.123, -0.017],
                [0.006, 0.062, -0.017],
                [0.094, 0.185, 0.911],
            ],
        },
    }
}

/// The exact piecewise sRGB decoding (IEC 61966-2-1): c ≤ 0.04045 → c/12.92,
/// else ((c + 0.055)/1.055)^2.4. Input and output 0…1.
#[inline]
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The exact piecewise sRGB encoding: l ≤ 0.0031308 → 12.92·l, else
/// 1.055·l^(1/2.4) − 0.055. Input and output 0…1.
#[inline]
pub fn linear_to_srgb(l: f32) -> f32 {
    if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// One Dubois anaglyph pixel from the two eyes' LINEAR RGB: the matrices
/// applied, clamped to 0…1, sRGB-encoded (result 0…1, encoded).
#[inline]
pub fn dubois_pixel(m: &DuboisMatrices, left_linear: [f32; 3], right_linear: [f32; 3]) -> [f32; 3] {
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let (ml, mr) = (m.left[c], m.right[c]);
        let v = ml[0] * left_linear[0]
            + ml[1] * left_linear[1]
            + ml[2] * left_linear[2]
            + mr[0] * right_linear[0]
            + mr[1] * right_linear[1]
            + mr[2] * right_linear[2];
        *o = linear_to_srgb(v.clamp(0.0, 1.0));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luma_weights_sum_to_one() {
        assert!((LUMA.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        assert!((luma([0.5, 0.5, 0.5]) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn srgb_curve_round_trips_every_unorm8_value() {
        for v in 0..=255u8 {
            let c = f32::from(v) / 255.0;
            let back = (linear_to_srgb(srgb_to_linear(c)) * 255.0).round();
            assert_eq!(back, f32::from(v), "unorm8 {v}");
        }
        // Known points of the curve.
        assert!((srgb_to_linear(0.5) - 0.214_041).abs() < 1e-5);
        assert!((linear_to_srgb(0.18) - 0.461_356).abs() < 1e-5);
        // The two pieces of each curve meet at the joins.
        let (c, l) = (0.04045f32, 0.003_130_8f32);
        assert!((c / 12.92 - ((c + 0.055) / 1.055).powf(2.4)).abs() < 1e-6);
        assert!((12.92 * l - (1.055 * l.powf(1.0 / 2.4) - 0.055)).abs() < 1e-6);
    }

    #[test]
    fn dubois_rows_sum_to_about_one_so_grey_stays_grey() {
        for colors in AnaglyphColors::ALL {
            let m = dubois_matrices(colors);
            for c in 0..3 {
                let sum: f32 = m.left[c].iter().chain(&m.right[c]).sum();
                assert!(
                    (sum - 1.0).abs() <= 0.0015,
                    "{colors:?} row {c} sums to {sum}"
                );
            }
        }
    }
}

//! The user's strength (offset) and balance adjustments: default 1.0, changed
//! multiplicatively by 1.1 per step, kept within 0…2 (seed 000 §7).

use super::finite;
use crate::error::Result;

/// Default value of both adjustments.
pub const ADJUSTMENT_DEFAULT: f64 = 1.0;
/// Lower limit: 0 means no stereo (offset) or no asymmetry (balance).
pub const ADJUSTMENT_MIN: f64 = 0.0;
/// Upper limit the seed recommends.
pub const ADJUSTMENT_MAX: f64 = 2.0;
/// Factor of one step.
pub const ADJUSTMENT_STEP: f64 = 1.1;

/// `value × 1.1^steps`, clamped to 0…2. Positive steps strengthen, negative
/// weaken. A value of exactly 0 stays 0 (multiplication cannot leave it);
/// set it explicitly to come back.
pub fn adjust_step(value: f64, steps: i32) -> Result<f64> {
    finite("value", value)?;
    if value == 0.0 {
        // 0 stays 0, even for steps so large that 1.1^steps is infinite
        // (0 × ∞ would be NaN).
        return Ok(0.0);
    }
    Ok((value * ADJUSTMENT_STEP.powi(steps)).clamp(ADJUSTMENT_MIN, ADJUSTMENT_MAX))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_multiply_and_clamp() {
        assert!((adjust_step(1.0, 1).unwrap() - 1.1).abs() < 1e-15);
        assert!((adjust_step(1.0, -1).unwrap() - 1.0 / 1.1).abs() < 1e-15);
        assert!((adjust_step(adjust_step(1.0, 3).unwrap(), -3).unwrap() - 1.0).abs() < 1e-12);
        assert_eq!(adjust_step(1.9, 1).unwrap(), 2.0);
        assert_eq!(adjust_step(5.0, 0).unwrap(), 2.0);
        assert_eq!(adjust_step(-1.0, 0).unwrap(), 0.0);
        assert!(adjust_step(f64::NAN, 1).is_err());
        assert_eq!(adjust_step(0.0, i32::MAX).unwrap(), 0.0);
        assert_eq!(adjust_step(1.0, i32::MAX).unwrap(), 2.0);
        assert_eq!(adjust_step(1.0, i32::MIN).unwrap(), 0.0);
    }
}

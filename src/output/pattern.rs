//! Deterministic test images for comparing the GL compositor with the CPU
//! reference: smooth gradients (which expose filtering and rounding) and
//! noise (which exposes any misplaced pixel).

use crate::image::Image;

/// A gradient: red rises left to right, green top to bottom, blue along the
/// diagonal, with `phase` (any value) shifting the blue so the two eyes can
/// differ. Alpha 255.
pub fn gradient(width: u32, height: u32, phase: u8) -> Image {
    let (wd, hd) = (width.max(2) - 1, height.max(2) - 1);
    Image::from_fn(width, height, |x, y| {
        let r = x * 255 / wd;
        let g = y * 255 / hd;
        let b = ((x + y) * 255 / (wd + hd) + u32::from(phase)) % 256;
        [r as u8, g as u8, b as u8, 255]
    })
}

/// Uniform noise from a 64-bit xorshift generator seeded by `seed`: the same
/// seed always gives the same image. Alpha 255.
pub fn noise(width: u32, height: u32, seed: u64) -> Image {
    // splitmix64 of the seed, so nearby seeds give unrelated images.
    let mut state = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    state = (state ^ (state >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    state = (state ^ (state >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    state ^= state >> 31;
    state |= 1;
    Image::from_fn(width, height, |_, _| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let [r, g, b, ..] = state.to_le_bytes();
        [r, g, b, 255]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradient_spans_the_full_range() {
        let g = gradient(256, 256, 0);
        assert_eq!(g.get(0, 0), [0, 0, 0, 255]);
        assert_eq!(g.get(255, 255), [255, 255, 255, 255]);
        assert_ne!(gradient(8, 8, 0), gradient(8, 8, 40), "phase shifts blue");
        let tiny = gradient(1, 1, 0);
        assert_eq!(tiny.get(0, 0)[3], 255);
    }

    #[test]
    fn noise_is_deterministic_per_seed_and_varied() {
        assert_eq!(noise(16, 9, 3), noise(16, 9, 3));
        assert_ne!(noise(16, 9, 3), noise(16, 9, 4));
        let n = noise(64, 64, 1);
        let mut seen = [false; 256];
        for p in n.pixels().chunks_exact(4) {
            seen[p[0] as usize] = true;
        }
        let distinct = seen.iter().filter(|&&s| s).count();
        assert!(
            distinct > 200,
            "only {distinct} distinct red values in 4096 pixels"
        );
    }
}

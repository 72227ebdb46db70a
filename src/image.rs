//! RGBA8 images in memory, rows top first: what captures, the CPU reference
//! of the output formats and the tests exchange.

use crate::error::{Error, Result};

/// Largest width or height the library accepts for any image or surface.
/// 16384 is the largest texture llvmpipe and most drivers support.
pub const MAX_DIMENSION: u32 = 16384;

/// An RGBA8 image, 4 bytes a pixel, rows top first, no padding.
#[derive(Clone, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Vec<u8>,
}

impl std::fmt::Debug for Image {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Image({}x{})", self.width, self.height)
    }
}

/// Checks a width and height: each 1…MAX_DIMENSION.
pub fn check_size(width: u32, height: u32) -> Result<()> {
    if width == 0 || height == 0 || width > MAX_DIMENSION || height > MAX_DIMENSION {
        return Err(Error::invalid_value(format!(
            "size {width}x{height} is out of range: width and height must each be 1…{MAX_DIMENSION}"
        )));
    }
    Ok(())
}

/// `len` copies of `value`, or `OutOfMemory` naming `what` when the memory
/// cannot be had (instead of aborting the process, as `vec!` does).
pub fn try_vec<T: Clone>(len: usize, value: T, what: &str) -> Result<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| {
        Error::OutOfMemory(format!(
            "{} MiB for {what} could not be allocated: free memory or use a smaller surface",
            (len * std::mem::size_of::<T>()) >> 20
        ))
    })?;
    v.resize(len, value);
    Ok(v)
}

/// Reverses the order of `stride`-byte rows in place (GL reads rows bottom first).
pub fn flip_rows(pixels: &mut [u8], stride: usize) {
    let h = pixels.len() / stride;
    for y in 0..h / 2 {
        let (top, bottom) = pixels.split_at_mut((h - 1 - y) * stride);
        top[y * stride..(y + 1) * stride].swap_with_slice(&mut bottom[..stride]);
    }
}

/// `bytes` as RGBA8 pixel words (R in the low byte), when they are
/// 4-byte aligned, a whole number of pixels, on a little-endian machine
/// (an [`Image`]'s buffer from the system allocator always is aligned);
/// None otherwise, for a byte-wise fallback. Word loops compile to vector
/// code that byte-chunk loops do not (2–4× faster here).
pub fn as_words(bytes: &[u8]) -> Option<&[u32]> {
    if cfg!(target_endian = "big") {
        return None;
    }
    // SAFETY: every bit pattern is a valid u32; align_to hands out only
    // the aligned middle, and the checks below refuse anything else.
    let (head, words, tail) = unsafe { bytes.align_to::<u32>() };
    (head.is_empty() && tail.is_empty()).then_some(words)
}

/// [`as_words`], mutable.
pub fn as_words_mut(bytes: &mut [u8]) -> Option<&mut [u32]> {
    if cfg!(target_endian = "big") {
        return None;
    }
    // SAFETY: as in `as_words`; writes of any u32 are valid bytes.
    let (head, words, tail) = unsafe { bytes.align_to_mut::<u32>() };
    (head.is_empty() && tail.is_empty()).then_some(words)
}

/// Pixel words as their bytes (RGBA8 on a little-endian machine).
pub fn as_bytes(words: &[u32]) -> &[u8] {
    // SAFETY: u8 has no alignment and every u32 is valid bytes; the
    // length is the words' size in bytes.
    unsafe { std::slice::from_raw_parts(words.as_ptr().cast::<u8>(), words.len() * 4) }
}

/// Pixel words as their bytes (RGBA8 on a little-endian machine): the
/// buffer a read-back of pixels fills.
pub fn as_bytes_mut(words: &mut [u32]) -> &mut [u8] {
    // SAFETY: u8 has no alignment and any byte values are a valid u32;
    // the length is the words' size in bytes.
    unsafe { std::slice::from_raw_parts_mut(words.as_mut_ptr().cast::<u8>(), words.len() * 4) }
}

impl Image {
    /// A black, fully transparent image. Panics on a size outside
    /// 1…MAX_DIMENSION (check with [`check_size`] first for user input), and
    /// when the memory cannot be had — a panic the C boundary reports as
    /// GLS_ERROR_PANIC, where a failed `vec!` would abort the whole process.
    /// Images as large as a surface use [`Image::try_new`].
    pub fn new(width: u32, height: u32) -> Image {
        Self::try_new(width, height).unwrap_or_else(|e| panic!("{e}"))
    }

    /// A black, fully transparent image; `InvalidValue` for a size outside
    /// 1…MAX_DIMENSION, `OutOfMemory` when its pixels cannot be allocated.
    pub fn try_new(width: u32, height: u32) -> Result<Image> {
        check_size(width, height)?;
        Ok(Image {
            width,
            height,
            pixels: try_vec(width as usize * height as usize * 4, 0u8, "an image")?,
        })
    }

    /// A copy, or `OutOfMemory` when the memory cannot be had.
    pub fn try_clone(&self) -> Result<Image> {
        let mut pixels = try_vec(0, 0u8, "an image")?;
        pixels.try_reserve_exact(self.pixels.len()).map_err(|_| {
            Error::OutOfMemory(format!(
                "{} MiB for a copy of a {}x{} image could not be allocated: free memory or use a smaller surface",
                self.pixels.len() >> 20,
                self.width,
                self.height
            ))
        })?;
        pixels.extend_from_slice(&self.pixels);
        Ok(Image {
            width: self.width,
            height: self.height,
            pixels,
        })
    }

    /// Gives the image the size `width`×`height`, keeping its allocation
    /// (a frame loop avoids a fresh multi-megabyte buffer, and its page
    /// faults, per frame); the contents are unspecified after a change.
    /// `InvalidValue` for a size outside 1…MAX_DIMENSION, `OutOfMemory`
    /// naming `what` when the memory cannot be had; the image is unchanged
    /// on error.
    pub(crate) fn resize(&mut self, width: u32, height: u32, what: &str) -> Result<()> {
        if (self.width, self.height) == (width, height) {
            return Ok(());
        }
        check_size(width, height)?;
        let len = width as usize * height as usize * 4;
        let extra = len.saturating_sub(self.pixels.len());
        if self.pixels.try_reserve_exact(extra).is_err() {
            return Err(Error::OutOfMemory(format!(
                "{} MiB for a {width}x{height} {what} could not be allocated: free memory or use a smaller surface",
                len >> 20
            )));
        }
        self.pixels.resize(len, 0);
        (self.width, self.height) = (width, height);
        Ok(())
    }

    /// An image of the given pixels (rows top first, 4 bytes a pixel).
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<u8>) -> Result<Image> {
        check_size(width, height)?;
        if pixels.len() != width as usize * height as usize * 4 {
            return Err(Error::invalid_value(format!(
                "{} bytes cannot be a {width}x{height} RGBA8 image ({} bytes)",
                pixels.len(),
                width as usize * height as usize * 4
            )));
        }
        Ok(Image {
            width,
            height,
            pixels,
        })
    }

    /// An image whose pixel (x, y) (y = 0 at the top) is `f(x, y)`.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> [u8; 4]) -> Image {
        let mut img = Image::new(width, height);
        for y in 0..height {
            for x in 0..width {
                img.set(x, y, f(x, y));
            }
        }
        img
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixel bytes, rows top first.
    pub fn pixels(&self) -> &[u8] {
        &self.pixels
    }

    /// The pixel bytes, mutable.
    pub fn pixels_mut(&mut self) -> &mut [u8] {
        &mut self.pixels
    }

    /// Takes the pixel bytes.
    pub fn into_pixels(self) -> Vec<u8> {
        self.pixels
    }

    /// One row (y = 0 at the top).
    pub fn row(&self, y: u32) -> &[u8] {
        let stride = self.width as usize * 4;
        &self.pixels[y as usize * stride..(y as usize + 1) * stride]
    }

    fn index(&self, x: u32, y: u32) -> usize {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside {self:?}"
        );
        (y as usize * self.width as usize + x as usize) * 4
    }

    /// The pixel at (x, y), y = 0 at the top.
    pub fn get(&self, x: u32, y: u32) -> [u8; 4] {
        let i = self.index(x, y);
        self.pixels[i..i + 4].try_into().unwrap()
    }

    /// Sets the pixel at (x, y), y = 0 at the top.
    pub fn set(&mut self, x: u32, y: u32, rgba: [u8; 4]) {
        let i = self.index(x, y);
        self.pixels[i..i + 4].copy_from_slice(&rgba);
    }

    /// Sets every pixel's alpha to 255 (a display shows no alpha).
    pub(crate) fn make_opaque(&mut self) {
        match as_words_mut(&mut self.pixels) {
            Some(words) => words.iter_mut().for_each(|w| *w |= 0xFF00_0000),
            None => self.pixels.chunks_exact_mut(4).for_each(|p| p[3] = 255),
        }
    }

    /// Reverses the row order in place (GL reads rows bottom first).
    pub fn flip_vertical(&mut self) {
        flip_rows(&mut self.pixels, self.width as usize * 4);
    }

    /// The largest per-channel difference to another image of the same size,
    /// and where it is (x, y, channel); None when sizes differ.
    pub fn max_difference(&self, other: &Image) -> Option<(u8, u32, u32, usize)> {
        if self.width != other.width || self.height != other.height {
            return None;
        }
        let mut worst = (0u8, 0, 0, 0);
        for (i, (a, b)) in self.pixels.iter().zip(&other.pixels).enumerate() {
            let d = a.abs_diff(*b);
            if d > worst.0 {
                let p = i / 4;
                worst = (
                    d,
                    (p % self.width as usize) as u32,
                    (p / self.width as usize) as u32,
                    i % 4,
                );
            }
        }
        Some(worst)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flip_vertical_reverses_rows() {
        let mut img = Image::from_fn(3, 5, |x, y| [x as u8, y as u8, 0, 255]);
        img.flip_vertical();
        assert_eq!(img.get(2, 0), [2, 4, 0, 255]);
        assert_eq!(img.get(1, 2), [1, 2, 0, 255]);
        assert_eq!(img.get(0, 4), [0, 0, 0, 255]);
    }

    #[test]
    fn resize_keeps_the_allocation_and_refuses_bad_sizes() {
        let mut img = Image::new(8, 8);
        let ptr = img.pixels().as_ptr();
        img.resize(4, 2, "image").unwrap();
        assert_eq!((img.width(), img.height(), img.pixels().len()), (4, 2, 32));
        assert_eq!(img.pixels().as_ptr(), ptr);
        assert!(img.resize(0, 2, "image").is_err());
        assert_eq!((img.width(), img.height()), (4, 2));
    }

    #[test]
    fn sizes_are_checked() {
        assert!(check_size(0, 10).is_err());
        assert!(check_size(100_000, 100_000).is_err());
        assert!(Image::from_pixels(2, 2, vec![0; 15]).is_err());
        let a = Image::from_fn(4, 4, |x, _| [x as u8; 4]);
        let mut b = a.clone();
        b.set(3, 1, [9, 9, 0, 9]);
        assert_eq!(a.max_difference(&b), Some((6, 3, 1, 0)));
    }
}

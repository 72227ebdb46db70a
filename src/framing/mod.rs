//! Input framings: how a program delivers its two eyes. The first stage of
//! the data flow (input framing → two eye images → output format).
//!
//! - This module: framings of frames the program draws itself (quad buffer,
//!   HP sync-doubled, SGI STR_RECT/STR_TOP/STR_BOT, Xinerama side-by-side).
//! - [`auto`]: automatic stereo of a mono renderer (NVIDIA 3D Vision): one
//!   mono frame, drawn once per eye with a per-eye projection.
//!
//! Each framing names, for each eye, a rectangle of one colour buffer of
//! the surface and the size the eye has once taken apart (an [`EyeSource`]).
//! Eyes stretched by the display (sync-doubling) are resampled with the
//! output formats' bilinear rule ([`crate::output::cpu::resample`]); the GL
//! compositor samples the same rectangles.

pub mod auto;

use crate::error::{Error, Result};
use crate::image::Image;
use crate::output::layout::{half_split, str_rect_eye_rows};
use crate::stereo::buffers::{ColorBuffer, FramebufferShape};

/// How a program delivers its two eyes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum InputFraming {
    /// Quad buffer: the left and right front buffers (GLX_STEREO, HP
    /// windowed OpenGL, SGI square-pixel stereo). A mono surface shows its
    /// one buffer to both eyes.
    #[default]
    QuadBuffer,
    /// HP Starbase sync-doubling (seed 000 §9): one mono frame, left eye in
    /// the upper half, right eye in the lower half, each drawn squashed 1:2
    /// and stretched ×2 vertically by the doubled vertical sync.
    SyncDoubled,
    /// SGI STR_RECT (seed 002 §3, §6): for a 1024-row frame, left eye in the
    /// top 492 rows (GL rows 532–1023), right eye in the bottom 492 (GL rows
    /// 0–491), the 40 rows between lost in blanking; each eye stretched to
    /// the full frame height. Other heights scale proportionally
    /// ([`str_rect_eye_rows`]).
    StrRect,
    /// Xinerama "passive" stereo (seed 001): a double-width mono frame, left
    /// eye in the left half, right eye in the right half, not stretched.
    SideBySide,
    /// SGI STR_TOP (seed 002 §3, §5): the display shows only the top 492 of
    /// 1024 rows (GL rows 532–1023), stretched to the full height, to both
    /// eyes; a window with left and right buffers shows each to its eye.
    /// So: both eyes from that band, the left eye from the left buffer and
    /// the right eye from the right buffer (the left one on a mono surface).
    /// Other heights scale as [`InputFraming::StrRect`].
    StrTop,
    /// SGI STR_BOT: as [`InputFraming::StrTop`] with the bottom 492 rows
    /// (GL rows 0–491).
    StrBot,
}

/// Where one eye comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EyeSource {
    /// The colour buffer holding it.
    pub buffer: ColorBuffer,
    /// Left edge of its rectangle in the buffer.
    pub x: u32,
    /// Top edge (rows counted from the top) of its rectangle.
    pub y: u32,
    /// Width of its rectangle.
    pub width: u32,
    /// Height of its rectangle.
    pub height: u32,
}

impl InputFraming {
    /// Every framing.
    pub const ALL: [InputFraming; 6] = [
        InputFraming::QuadBuffer,
        InputFraming::SyncDoubled,
        InputFraming::StrRect,
        InputFraming::SideBySide,
        InputFraming::StrTop,
        InputFraming::StrBot,
    ];

    /// The size of each eye once taken apart from a `width` × `height` frame.
    pub fn eye_size(self, width: u32, height: u32) -> (u32, u32) {
        match self {
            InputFraming::SideBySide => (half_split(width).0, height),
            _ => (width, height),
        }
    }

    /// The frame size that holds two eyes of `eye_width` × `eye_height` this
    /// way (the inverse of [`InputFraming::eye_size`]): twice as wide for
    /// side-by-side, the eye size for the others.
    pub fn frame_size(self, eye_width: u32, eye_height: u32) -> (u32, u32) {
        match self {
            InputFraming::SideBySide => (eye_width.saturating_mul(2), eye_height),
            _ => (eye_width, eye_height),
        }
    }

    /// Checks that a `width` × `height` frame can be taken apart this way.
    pub fn check(self, shape: FramebufferShape, width: u32, height: u32) -> Result<()> {
        let too_small = match self {
            InputFraming::QuadBuffer => false,
            InputFraming::SyncDoubled => height < 2,
            InputFraming::StrRect | InputFraming::StrTop | InputFraming::StrBot => {
                str_rect_eye_rows(height) == 0
            }
            InputFraming::SideBySide => width < 2,
        };
        if too_small {
            return Err(Error::invalid_value(format!(
                "a {width}x{height} frame is too small to hold two eyes as {self:?}"
            )));
        }
        // On a stereo surface the one-frame framings read the left buffers
        // only, as a sync-doubled display shows one mono frame; StrTop and
        // StrBot read both, as SGI's windowed stereo does.
        let _ = shape;
        Ok(())
    }

    /// Where the left and right eyes come from in a `width` × `height`
    /// surface of `shape`: from the front buffers, which are what the
    /// display shows.
    pub fn sources(self, shape: FramebufferShape, width: u32, height: u32) -> [EyeSource; 2] {
        let fl = ColorBuffer::FrontLeft;
        let fr = if shape.stereo {
            ColorBuffer::FrontRight
        } else {
            fl
        };
        let whole = |buffer| EyeSource {
            buffer,
            x: 0,
            y: 0,
            width,
            height,
        };
        match self {
            InputFraming::QuadBuffer => [whole(fl), whole(fr)],
            InputFraming::SyncDoubled => {
                let (top, bottom) = half_split(height);
                [
                    EyeSource {
                        buffer: fl,
                        x: 0,
                        y: 0,
                        width,
                        height: top,
                    },
                    EyeSource {
                        buffer: fl,
                        x: 0,
                        y: top,
                        width,
                        height: bottom,
                    },
                ]
            }
            InputFraming::StrRect => {
                let rows = str_rect_eye_rows(height);
                [
                    EyeSource {
                        buffer: fl,
                        x: 0,
                        y: 0,
                        width,
                        height: rows,
                    },
                    EyeSource {
                        buffer: fl,
                        x: 0,
                        y: height - rows,
                        width,
                        height: rows,
                    },
                ]
            }
            InputFraming::StrTop | InputFraming::StrBot => {
                let rows = str_rect_eye_rows(height);
                let y = if self == InputFraming::StrTop {
                    0
                } else {
                    height - rows
                };
                let band = |buffer| EyeSource {
                    buffer,
                    x: 0,
                    y,
                    width,
                    height: rows,
                };
                [band(fl), band(fr)]
            }
            InputFraming::SideBySide => {
                let (l, r) = half_split(width);
                [
                    EyeSource {
                        buffer: fl,
                        x: 0,
                        y: 0,
                        width: l,
                        height,
                    },
                    EyeSource {
                        buffer: fl,
                        x: l,
                        y: 0,
                        width: r,
                        height,
                    },
                ]
            }
        }
    }

    /// Takes one eye out of a buffer image (CPU): its rectangle resampled
    /// to the eye size.
    pub fn extract(self, source: &EyeSource, buffer: &Image) -> Image {
        let (w, h) = self.eye_size(buffer.width(), buffer.height());
        crate::output::cpu::resample(
            buffer,
            source.x,
            source.y,
            source.width,
            source.height,
            w,
            h,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MONO: FramebufferShape = FramebufferShape {
        stereo: false,
        double_buffered: true,
    };

    #[test]
    fn str_rect_takes_the_rows_the_seed_gives() {
        let [l, r] = InputFraming::StrRect.sources(MONO, 1280, 1024);
        // Top-first rows 0..492 are GL rows 532..1023; rows 532..1024 are GL rows 0..491.
        assert_eq!((l.y, l.height), (0, 492));
        assert_eq!((r.y, r.height), (532, 492));
        assert_eq!(1024 - (l.y + l.height), 532, "left eye's lowest GL row");
        assert_eq!(1024 - r.y - 1, 491, "right eye's highest GL row");
    }

    #[test]
    fn sync_doubling_splits_halves_and_stretches_them_back() {
        let [l, r] = InputFraming::SyncDoubled.sources(MONO, 1280, 1024);
        assert_eq!((l.y, l.height, r.y, r.height), (0, 512, 512, 512));
        // A frame whose upper half is white and lower half black.
        let frame = Image::from_fn(8, 8, |_, y| if y < 4 { [255; 4] } else { [0, 0, 0, 255] });
        let [ls, rs] = InputFraming::SyncDoubled.sources(MONO, 8, 8);
        let left = InputFraming::SyncDoubled.extract(&ls, &frame);
        let right = InputFraming::SyncDoubled.extract(&rs, &frame);
        assert_eq!((left.width(), left.height()), (8, 8));
        assert!(
            left.pixels().chunks(4).all(|p| p == [255; 4]),
            "left eye is the white half, stretched"
        );
        assert!(
            right.pixels().chunks(4).all(|p| p == [0, 0, 0, 255]),
            "right eye is the black half"
        );
    }

    #[test]
    fn str_top_and_str_bot_take_one_band_from_each_eyes_buffer() {
        let stereo = FramebufferShape {
            stereo: true,
            double_buffered: true,
        };
        let [l, r] = InputFraming::StrTop.sources(stereo, 1280, 1024);
        assert_eq!(
            (l.buffer, r.buffer),
            (ColorBuffer::FrontLeft, ColorBuffer::FrontRight)
        );
        assert_eq!((l.y, l.height, r.y, r.height), (0, 492, 0, 492));
        let [l, r] = InputFraming::StrBot.sources(MONO, 1280, 1024);
        assert_eq!(
            (l.buffer, r.buffer),
            (ColorBuffer::FrontLeft, ColorBuffer::FrontLeft)
        );
        // Top-first rows 532..1024 are GL rows 0..491.
        assert_eq!((l.y, l.height), (532, 492));
        assert_eq!(r, l);
        assert!(InputFraming::StrTop.check(MONO, 4, 1).is_err());
        assert_eq!(InputFraming::StrBot.eye_size(1280, 1024), (1280, 1024));
    }

    #[test]
    fn side_by_side_halves_a_double_width_frame_without_stretching() {
        let frame = Image::from_fn(10, 3, |x, y| [x as u8, y as u8, 0, 255]);
        let f = InputFraming::SideBySide;
        assert_eq!(f.eye_size(10, 3), (5, 3));
        let [ls, rs] = f.sources(MONO, 10, 3);
        let (l, r) = (f.extract(&ls, &frame), f.extract(&rs, &frame));
        assert_eq!(l.get(4, 2), [4, 2, 0, 255]);
        assert_eq!(r.get(0, 1), [5, 1, 0, 255]);
        assert!(f.check(MONO, 1, 3).is_err());
    }

    #[test]
    fn quad_buffer_uses_both_front_buffers_and_mono_shows_one() {
        let stereo = FramebufferShape {
            stereo: true,
            double_buffered: true,
        };
        let [l, r] = InputFraming::QuadBuffer.sources(stereo, 4, 4);
        assert_eq!(
            (l.buffer, r.buffer),
            (ColorBuffer::FrontLeft, ColorBuffer::FrontRight)
        );
        let [l, r] = InputFraming::QuadBuffer.sources(MONO, 4, 4);
        assert_eq!(
            (l.buffer, r.buffer),
            (ColorBuffer::FrontLeft, ColorBuffer::FrontLeft)
        );
    }
}

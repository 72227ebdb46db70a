//! The colour buffers of a default framebuffer and the GL 4.5 compatibility
//! rules for selecting them with glDrawBuffer, glDrawBuffers and
//! glReadBuffer. Pure: no GL calls. The same rules serve the emulated quad
//! buffer of every backend and the LD_PRELOAD interposer.
//!
//! Checked against Mesa 22.3 on a real GLX default framebuffer: a buffer the
//! visual lacks is GL_INVALID_OPERATION; a value that is not a buffer name is
//! GL_INVALID_ENUM; glReadBuffer accepts the same names as glDrawBuffer
//! (FRONT_AND_BACK reads front-left); GL_DRAW_BUFFER / GL_READ_BUFFER report
//! the enum as the program passed it.

use crate::error::{Error, Result};
use crate::gl::enums::*;

/// One physical colour buffer of a (possibly stereo, possibly double-buffered)
/// default framebuffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ColorBuffer {
    /// GL_FRONT_LEFT: the visible left (or only) buffer.
    FrontLeft = 0,
    /// GL_BACK_LEFT.
    BackLeft = 1,
    /// GL_FRONT_RIGHT: the visible right buffer (stereo only).
    FrontRight = 2,
    /// GL_BACK_RIGHT (stereo and double-buffered only).
    BackRight = 3,
}

impl ColorBuffer {
    /// All four, in index order.
    pub const ALL: [ColorBuffer; 4] = [
        ColorBuffer::FrontLeft,
        ColorBuffer::BackLeft,
        ColorBuffer::FrontRight,
        ColorBuffer::BackRight,
    ];

    /// The GL name of this buffer.
    pub fn gl_enum(self) -> u32 {
        match self {
            ColorBuffer::FrontLeft => GL_FRONT_LEFT,
            ColorBuffer::BackLeft => GL_BACK_LEFT,
            ColorBuffer::FrontRight => GL_FRONT_RIGHT,
            ColorBuffer::BackRight => GL_BACK_RIGHT,
        }
    }

    /// Index 0…3 (FrontLeft, BackLeft, FrontRight, BackRight).
    pub fn index(self) -> usize {
        self as usize
    }

    /// The buffer this one becomes (front ↔ back of the same eye) at a swap.
    pub fn swapped(self) -> ColorBuffer {
        match self {
            ColorBuffer::FrontLeft => ColorBuffer::BackLeft,
            ColorBuffer::BackLeft => ColorBuffer::FrontLeft,
            ColorBuffer::FrontRight => ColorBuffer::BackRight,
            ColorBuffer::BackRight => ColorBuffer::FrontRight,
        }
    }

    fn bit(self) -> u8 {
        1 << self.index()
    }
}

/// A set of colour buffers (what a draw-buffer value selects).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BufferSet(u8);

impl BufferSet {
    /// No buffer (GL_NONE).
    pub const EMPTY: BufferSet = BufferSet(0);

    /// A set of the given buffers.
    pub fn of(buffers: &[ColorBuffer]) -> BufferSet {
        buffers.iter().copied().collect()
    }

    /// Whether `b` is in the set.
    pub fn contains(self, b: ColorBuffer) -> bool {
        self.0 & b.bit() != 0
    }

    /// The buffers in the set, in index order (left eye before right).
    pub fn iter(self) -> impl Iterator<Item = ColorBuffer> {
        ColorBuffer::ALL
            .into_iter()
            .filter(move |b| self.contains(*b))
    }

    /// Whether the set is empty.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Intersection.
    pub fn intersect(self, other: BufferSet) -> BufferSet {
        BufferSet(self.0 & other.0)
    }

    /// Number of buffers.
    pub fn len(self) -> usize {
        self.0.count_ones() as usize
    }
}

impl FromIterator<ColorBuffer> for BufferSet {
    fn from_iter<I: IntoIterator<Item = ColorBuffer>>(buffers: I) -> BufferSet {
        BufferSet(buffers.into_iter().fold(0, |m, b| m | b.bit()))
    }
}

/// The shape of a default framebuffer: which colour buffers exist.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FramebufferShape {
    /// Left and right buffers (GLX_STEREO).
    pub stereo: bool,
    /// Front and back buffers (GLX_DOUBLEBUFFER).
    pub double_buffered: bool,
}

impl FramebufferShape {
    /// The buffers this framebuffer has.
    pub fn allocated(self) -> BufferSet {
        // Bits, not a Vec: called on every glDrawBuffer of a frame.
        let mut bits = ColorBuffer::FrontLeft.bit();
        if self.double_buffered {
            bits |= ColorBuffer::BackLeft.bit();
        }
        if self.stereo {
            bits |= ColorBuffer::FrontRight.bit();
            if self.double_buffered {
                bits |= ColorBuffer::BackRight.bit();
            }
        }
        BufferSet(bits)
    }

    /// The initial draw and read buffer: GL_BACK when double-buffered, else GL_FRONT.
    pub fn initial_buffer(self) -> u32 {
        if self.double_buffered {
            GL_BACK
        } else {
            GL_FRONT
        }
    }
}

/// Every name glDrawBuffer accepts for a default framebuffer, with the
/// buffers each would select if all four existed (GL 4.5 compat, table 17.4).
fn named_buffers(buf: u32) -> Option<BufferSet> {
    use ColorBuffer::*;
    Some(match buf {
        GL_NONE => BufferSet::EMPTY,
        GL_FRONT_LEFT => BufferSet::of(&[FrontLeft]),
        GL_FRONT_RIGHT => BufferSet::of(&[FrontRight]),
        GL_BACK_LEFT => BufferSet::of(&[BackLeft]),
        GL_BACK_RIGHT => BufferSet::of(&[BackRight]),
        GL_FRONT => BufferSet::of(&[FrontLeft, FrontRight]),
        GL_BACK => BufferSet::of(&[BackLeft, BackRight]),
        GL_LEFT => BufferSet::of(&[FrontLeft, BackLeft]),
        GL_RIGHT => BufferSet::of(&[FrontRight, BackRight]),
        GL_FRONT_AND_BACK => BufferSet::of(&ColorBuffer::ALL),
        _ => return None,
    })
}

/// Names that are GL draw-buffer enums but never name a buffer of an
/// emulated default framebuffer (aux buffers, FBO attachments).
fn is_other_buffer_name(buf: u32) -> bool {
    (GL_AUX0..=GL_AUX3).contains(&buf)
        || (GL_COLOR_ATTACHMENT0..=GL_COLOR_ATTACHMENT31).contains(&buf)
}

const DRAW_BUFFER_NAMES: &str = "use GL_NONE, GL_FRONT_LEFT, GL_FRONT_RIGHT, GL_BACK_LEFT, GL_BACK_RIGHT, \
     GL_FRONT, GL_BACK, GL_LEFT, GL_RIGHT or GL_FRONT_AND_BACK";

/// The GL error a failed emulated call raises: GL_INVALID_ENUM,
/// GL_INVALID_VALUE, or GL_INVALID_OPERATION for every other failure.
pub fn gl_error_code(e: &Error) -> u32 {
    match e {
        Error::InvalidEnum { .. } => GL_INVALID_ENUM,
        Error::InvalidValue(_) => GL_INVALID_VALUE,
        _ => GL_INVALID_OPERATION,
    }
}

/// The GL error glInvalidateFramebuffer, glInvalidateSubFramebuffer and
/// glInvalidateNamedFramebuffer(Sub)Data raise for a default framebuffer
/// (desktop GL, in Mesa's order): a negative `n`, or a negative width or
/// height (`size`, for the Sub forms) is GL_INVALID_VALUE; an attachment
/// other than GL_COLOR, GL_DEPTH, GL_STENCIL, GL_FRONT_LEFT, GL_FRONT_RIGHT,
/// GL_BACK_LEFT and GL_BACK_RIGHT is GL_INVALID_ENUM. None: accepted.
/// Invalidation is a hint: what it accepts, an emulated framebuffer may
/// keep.
pub fn default_invalidate_error(
    n: i32,
    attachments: &[u32],
    size: Option<(i32, i32)>,
) -> Option<u32> {
    if n < 0 || size.is_some_and(|(w, h)| w < 0 || h < 0) {
        return Some(GL_INVALID_VALUE);
    }
    attachments
        .iter()
        .any(|&a| {
            !matches!(
                a,
                GL_COLOR_NAME
                    | GL_DEPTH_NAME
                    | GL_STENCIL_NAME
                    | GL_FRONT_LEFT
                    | GL_FRONT_RIGHT
                    | GL_BACK_LEFT
                    | GL_BACK_RIGHT
            )
        })
        .then_some(GL_INVALID_ENUM)
}

/// GL_COLOR, GL_DEPTH and GL_STENCIL, the names a default framebuffer's
/// buffers take in glInvalidate* and glClearBuffer.
const GL_COLOR_NAME: u32 = 0x1800;
const GL_DEPTH_NAME: u32 = 0x1801;
const GL_STENCIL_NAME: u32 = 0x1802;

/// Human-readable name of a buffer enum, for messages.
pub fn buffer_name(buf: u32) -> String {
    match buf {
        GL_NONE => "GL_NONE".into(),
        GL_FRONT_LEFT => "GL_FRONT_LEFT".into(),
        GL_FRONT_RIGHT => "GL_FRONT_RIGHT".into(),
        GL_BACK_LEFT => "GL_BACK_LEFT".into(),
        GL_BACK_RIGHT => "GL_BACK_RIGHT".into(),
        GL_FRONT => "GL_FRONT".into(),
        GL_BACK => "GL_BACK".into(),
        GL_LEFT => "GL_LEFT".into(),
        GL_RIGHT => "GL_RIGHT".into(),
        GL_FRONT_AND_BACK => "GL_FRONT_AND_BACK".into(),
        b if (GL_AUX0..=GL_AUX3).contains(&b) => format!("GL_AUX{}", b - GL_AUX0),
        b if (GL_COLOR_ATTACHMENT0..=GL_COLOR_ATTACHMENT31).contains(&b) => {
            format!("GL_COLOR_ATTACHMENT{}", b - GL_COLOR_ATTACHMENT0)
        }
        b => format!("{b:#06x}"),
    }
}

fn describe(shape: FramebufferShape) -> &'static str {
    match (shape.stereo, shape.double_buffered) {
        (true, true) => "a double-buffered stereo",
        (true, false) => "a single-buffered stereo",
        (false, true) => "a double-buffered mono",
        (false, false) => "a single-buffered mono",
    }
}

/// What glDrawBuffer(buf) selects on a default framebuffer of this shape.
///
/// Errors as GL: a value that is no buffer name is `InvalidEnum`; a name that
/// selects none of the allocated buffers (other than GL_NONE), an aux buffer
/// or an FBO attachment is `InvalidOperation`.
pub fn resolve_draw_buffer(shape: FramebufferShape, buf: u32) -> Result<BufferSet> {
    match named_buffers(buf) {
        Some(set) if buf == GL_NONE => Ok(set),
        Some(set) => {
            let present = set.intersect(shape.allocated());
            if present.is_empty() {
                Err(Error::invalid_operation(format!(
                    "{} names no buffer of {} framebuffer (GL_INVALID_OPERATION)",
                    buffer_name(buf),
                    describe(shape)
                )))
            } else {
                Ok(present)
            }
        }
        None if is_other_buffer_name(buf) => Err(Error::invalid_operation(format!(
            "{} is not a buffer of the default framebuffer (GL_INVALID_OPERATION)",
            buffer_name(buf)
        ))),
        None => Err(Error::invalid_enum("draw buffer", buf, DRAW_BUFFER_NAMES)),
    }
}

/// What glReadBuffer(src) reads from: one buffer, or none for GL_NONE.
///
/// GL_FRONT, GL_LEFT and GL_FRONT_AND_BACK read front-left; GL_BACK reads
/// back-left; GL_RIGHT reads front-right. Errors as [`resolve_draw_buffer`].
pub fn resolve_read_buffer(shape: FramebufferShape, src: u32) -> Result<Option<ColorBuffer>> {
    use ColorBuffer::*;
    let wanted = match src {
        GL_NONE => return Ok(None),
        GL_FRONT_LEFT | GL_FRONT | GL_LEFT | GL_FRONT_AND_BACK => FrontLeft,
        GL_BACK_LEFT | GL_BACK => BackLeft,
        GL_FRONT_RIGHT | GL_RIGHT => FrontRight,
        GL_BACK_RIGHT => BackRight,
        b if is_other_buffer_name(b) => {
            return Err(Error::invalid_operation(format!(
                "{} is not a buffer of the default framebuffer (GL_INVALID_OPERATION)",
                buffer_name(b)
            )));
        }
        b => return Err(Error::invalid_enum("read buffer", b, DRAW_BUFFER_NAMES)),
    };
    if shape.allocated().contains(wanted) {
        Ok(Some(wanted))
    } else {
        Err(Error::invalid_operation(format!(
            "{} names no buffer of {} framebuffer (GL_INVALID_OPERATION)",
            buffer_name(src),
            describe(shape)
        )))
    }
}

/// What glDrawBuffers(n, bufs) selects on a default framebuffer: one buffer
/// (or none) per fragment output.
///
/// GL rules: n must be 0…max_draw_buffers (`InvalidValue`); each entry must
/// be GL_NONE or a single buffer name (GL_BACK is accepted alone, as Mesa
/// does); GL_FRONT, GL_LEFT, GL_RIGHT, GL_FRONT_AND_BACK are `InvalidEnum`;
/// a buffer named twice, or one the framebuffer lacks, is `InvalidOperation`.
pub fn resolve_draw_buffers(
    shape: FramebufferShape,
    bufs: &[u32],
    max_draw_buffers: usize,
) -> Result<Vec<Option<ColorBuffer>>> {
    if bufs.len() > max_draw_buffers {
        return Err(Error::invalid_value(format!(
            "glDrawBuffers: n = {} exceeds GL_MAX_DRAW_BUFFERS ({max_draw_buffers}) (GL_INVALID_VALUE)",
            bufs.len()
        )));
    }
    let mut out = Vec::with_capacity(bufs.len());
    let mut seen = BufferSet::EMPTY;
    for &b in bufs {
        let one = match b {
            GL_NONE => None,
            GL_FRONT_LEFT => Some(ColorBuffer::FrontLeft),
            GL_FRONT_RIGHT => Some(ColorBuffer::FrontRight),
            GL_BACK_LEFT => Some(ColorBuffer::BackLeft),
            GL_BACK_RIGHT => Some(ColorBuffer::BackRight),
            GL_BACK if bufs.len() == 1 => Some(ColorBuffer::BackLeft),
            GL_BACK => {
                return Err(Error::invalid_operation(
                    "glDrawBuffers: GL_BACK is only allowed alone (n = 1) (GL_INVALID_OPERATION)",
                ));
            }
            b if is_other_buffer_name(b) => {
                return Err(Error::invalid_operation(format!(
                    "glDrawBuffers: {} is not a buffer of the default framebuffer (GL_INVALID_OPERATION)",
                    buffer_name(b)
                )));
            }
            b => {
                return Err(Error::invalid_enum(
                    "glDrawBuffers entry",
                    b,
                    "each entry must be GL_NONE, GL_FRONT_LEFT, GL_FRONT_RIGHT, GL_BACK_LEFT or GL_BACK_RIGHT",
                ));
            }
        };
        if let Some(cb) = one {
            if !shape.allocated().contains(cb) {
                return Err(Error::invalid_operation(format!(
                    "glDrawBuffers: {} names no buffer of {} framebuffer (GL_INVALID_OPERATION)",
                    buffer_name(b),
                    describe(shape)
                )));
            }
            if seen.contains(cb) {
                return Err(Error::invalid_operation(format!(
                    "glDrawBuffers: {} appears twice (GL_INVALID_OPERATION)",
                    buffer_name(b)
                )));
            }
            seen = BufferSet(seen.0 | cb.bit());
        }
        out.push(one);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::ColorBuffer::*;
    use super::*;

    const STEREO_DB: FramebufferShape = FramebufferShape {
        stereo: true,
        double_buffered: true,
    };
    const STEREO_SB: FramebufferShape = FramebufferShape {
        stereo: true,
        double_buffered: false,
    };
    const MONO_DB: FramebufferShape = FramebufferShape {
        stereo: false,
        double_buffered: true,
    };
    const MONO_SB: FramebufferShape = FramebufferShape {
        stereo: false,
        double_buffered: false,
    };

    fn set(b: &[ColorBuffer]) -> BufferSet {
        BufferSet::of(b)
    }

    #[test]
    fn draw_buffer_table_on_a_double_buffered_stereo_framebuffer() {
        let want = [
            (GL_NONE, set(&[])),
            (GL_FRONT_LEFT, set(&[FrontLeft])),
            (GL_FRONT_RIGHT, set(&[FrontRight])),
            (GL_BACK_LEFT, set(&[BackLeft])),
            (GL_BACK_RIGHT, set(&[BackRight])),
            (GL_FRONT, set(&[FrontLeft, FrontRight])),
            (GL_BACK, set(&[BackLeft, BackRight])),
            (GL_LEFT, set(&[FrontLeft, BackLeft])),
            (GL_RIGHT, set(&[FrontRight, BackRight])),
            (GL_FRONT_AND_BACK, set(&ColorBuffer::ALL)),
        ];
        for (e, s) in want {
            assert_eq!(
                resolve_draw_buffer(STEREO_DB, e).unwrap(),
                s,
                "{}",
                buffer_name(e)
            );
        }
    }

    #[test]
    fn buffers_a_config_lacks_are_invalid_operation() {
        for (shape, bad) in [
            (MONO_DB, &[GL_FRONT_RIGHT, GL_BACK_RIGHT, GL_RIGHT][..]),
            (
                MONO_SB,
                &[
                    GL_FRONT_RIGHT,
                    GL_BACK_RIGHT,
                    GL_RIGHT,
                    GL_BACK_LEFT,
                    GL_BACK,
                ][..],
            ),
            (STEREO_SB, &[GL_BACK_LEFT, GL_BACK_RIGHT, GL_BACK][..]),
        ] {
            for &e in bad {
                let r = resolve_draw_buffer(shape, e);
                assert!(
                    matches!(r, Err(Error::InvalidOperation(_))),
                    "{shape:?} {}: {r:?}",
                    buffer_name(e)
                );
                let r = resolve_read_buffer(shape, e);
                assert!(
                    matches!(r, Err(Error::InvalidOperation(_))),
                    "read {shape:?} {}: {r:?}",
                    buffer_name(e)
                );
            }
        }
        // Names that select some allocated buffer select only those.
        assert_eq!(
            resolve_draw_buffer(MONO_DB, GL_FRONT_AND_BACK).unwrap(),
            set(&[FrontLeft, BackLeft])
        );
        assert_eq!(
            resolve_draw_buffer(MONO_SB, GL_LEFT).unwrap(),
            set(&[FrontLeft])
        );
        assert_eq!(
            resolve_draw_buffer(STEREO_SB, GL_FRONT).unwrap(),
            set(&[FrontLeft, FrontRight])
        );
        assert_eq!(
            resolve_draw_buffer(MONO_DB, GL_BACK).unwrap(),
            set(&[BackLeft])
        );
    }

    #[test]
    fn non_buffer_values_are_invalid_enum_and_aux_or_attachments_invalid_operation() {
        for shape in [STEREO_DB, MONO_SB] {
            for e in [0x1234, GL_TEXTURE_2D, 0xFFFF_FFFF, 1] {
                assert!(matches!(
                    resolve_draw_buffer(shape, e),
                    Err(Error::InvalidEnum { .. })
                ));
                assert!(matches!(
                    resolve_read_buffer(shape, e),
                    Err(Error::InvalidEnum { .. })
                ));
            }
            for e in [GL_AUX0, GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT0 + 3] {
                assert!(matches!(
                    resolve_draw_buffer(shape, e),
                    Err(Error::InvalidOperation(_))
                ));
                assert!(matches!(
                    resolve_read_buffer(shape, e),
                    Err(Error::InvalidOperation(_))
                ));
            }
        }
    }

    #[test]
    fn read_buffer_picks_one_buffer_as_mesa_does() {
        let want = [
            (GL_NONE, None),
            (GL_FRONT, Some(FrontLeft)),
            (GL_LEFT, Some(FrontLeft)),
            (GL_FRONT_AND_BACK, Some(FrontLeft)),
            (GL_BACK, Some(BackLeft)),
            (GL_RIGHT, Some(FrontRight)),
            (GL_BACK_RIGHT, Some(BackRight)),
            (GL_FRONT_RIGHT, Some(FrontRight)),
        ];
        for (e, b) in want {
            assert_eq!(
                resolve_read_buffer(STEREO_DB, e).unwrap(),
                b,
                "{}",
                buffer_name(e)
            );
        }
    }

    #[test]
    fn draw_buffers_follow_the_gl_rules() {
        assert_eq!(
            resolve_draw_buffers(STEREO_DB, &[GL_BACK_LEFT, GL_BACK_RIGHT], 8).unwrap(),
            vec![Some(BackLeft), Some(BackRight)]
        );
        assert_eq!(
            resolve_draw_buffers(STEREO_DB, &[GL_BACK], 8).unwrap(),
            vec![Some(BackLeft)]
        );
        assert_eq!(
            resolve_draw_buffers(STEREO_DB, &[GL_NONE, GL_FRONT_RIGHT], 8).unwrap(),
            vec![None, Some(FrontRight)]
        );
        for bad in [GL_FRONT, GL_LEFT, GL_RIGHT, GL_FRONT_AND_BACK, 0x1234] {
            assert!(matches!(
                resolve_draw_buffers(STEREO_DB, &[bad], 8),
                Err(Error::InvalidEnum { .. })
            ));
        }
        assert!(matches!(
            resolve_draw_buffers(STEREO_DB, &[GL_BACK_LEFT, GL_BACK_LEFT], 8),
            Err(Error::InvalidOperation(_))
        ));
        assert!(matches!(
            resolve_draw_buffers(MONO_DB, &[GL_BACK_RIGHT], 8),
            Err(Error::InvalidOperation(_))
        ));
        assert!(matches!(
            resolve_draw_buffers(STEREO_DB, &[GL_NONE; 9], 8),
            Err(Error::InvalidValue(_))
        ));
        assert!(matches!(
            resolve_draw_buffers(STEREO_DB, &[GL_BACK, GL_NONE], 8),
            Err(Error::InvalidOperation(_))
        ));
    }

    #[test]
    fn initial_buffer_and_swap_pairs() {
        assert_eq!(STEREO_DB.initial_buffer(), GL_BACK);
        assert_eq!(MONO_SB.initial_buffer(), GL_FRONT);
        for b in ColorBuffer::ALL {
            assert_eq!(b.swapped().swapped(), b);
        }
        assert_eq!(STEREO_DB.allocated().len(), 4);
        assert_eq!(MONO_SB.allocated(), set(&[FrontLeft]));
    }

    #[test]
    fn invalidating_a_default_framebuffer_is_validated_as_mesa_validates_a_window() {
        // Accepted: the names Mesa 22.3 takes for a window (the probes of
        // tests/c/glx_core_stereo.c on a mono window).
        for a in [
            0x1800,
            0x1801,
            0x1802,
            GL_FRONT_LEFT,
            GL_BACK_LEFT,
            GL_FRONT_RIGHT,
            GL_BACK_RIGHT,
        ] {
            assert_eq!(default_invalidate_error(1, &[a], None), None, "{a:#x}");
        }
        for a in [GL_COLOR_ATTACHMENT0, 0x8D00, GL_FRONT, GL_BACK, 0x1234] {
            assert_eq!(
                default_invalidate_error(2, &[0x1800, a], None),
                Some(GL_INVALID_ENUM),
                "{a:#x}"
            );
        }
        assert_eq!(
            default_invalidate_error(-1, &[], None),
            Some(GL_INVALID_VALUE)
        );
        // The value check comes first, as in Mesa.
        assert_eq!(
            default_invalidate_error(1, &[GL_COLOR_ATTACHMENT0], Some((4, -1))),
            Some(GL_INVALID_VALUE)
        );
        assert_eq!(default_invalidate_error(0, &[], Some((0, 0))), None);
    }
}

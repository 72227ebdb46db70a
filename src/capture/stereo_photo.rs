//! Stereo photos: the two eyes in one file that stereo viewers, 3D
//! televisions, phones and the Nintendo 3DS open as a stereo pair.
//!
//! JPEG encoding is the `jpeg-encoder` crate's (baseline, 4:4:4 chroma at
//! quality 90 and above, 4:2:0 below). What is ours is the container: the
//! MP Index of an MPO and the descriptor of a JPS, laid out below.
//!
//! # MPO (CIPA DC-007 Multi-Picture Format, "Multi-frame Disparity")
//!
//! Two complete baseline JPEG files, one after the other: the left eye
//! first, then the right eye. Each carries an APP2 segment with the MP
//! Extension, inserted after the encoder's JFIF APP0 segment (DC-007 puts
//! it after APP0/APP1). All numbers are big-endian; every offset inside an
//! MP Extension counts from its MP Header (the `MM` byte order mark, M0).
//!
//! ```text
//! left eye (Size1 bytes)
//!   FFD8                          SOI
//!   FFE0 …                        APP0 "JFIF" (from the encoder)
//!   FFE2 LLLL "MPF\0"             APP2; LLLL = 2 + 4 + 152
//!   M0+0   4D4D 002A 00000008     MP Header: big-endian, first IFD at 8
//!   M0+8   MP Index IFD, 3 entries:
//!            B000 UNDEFINED 4   "0100"          MPFVersion
//!            B001 LONG      1   2               NumberOfImages
//!            B002 UNDEFINED 32  offset 50       MPEntry
//!          next IFD: 82
//!   M0+50  MP Entry 1: 20020002 Size1 00000000 0000 0000
//!          MP Entry 2: 00020002 Size2 Offset2  0000 0000
//!            (attribute: bit 29 representative image, bits 26–24 JPEG,
//!             bits 23–0 type 020002 Multi-frame Disparity; size in bytes
//!             from SOI to EOI; offset of the image's SOI from M0, 0 for
//!             the first image; two dependent-image entry numbers, none)
//!   M0+82  MP Attribute IFD, 4 entries:
//!            B101 LONG      1   1               MPIndividualNum
//!            B204 LONG      1   1               BaseViewpointNum (the left eye)
//!            B205 SRATIONAL 1   offset 136      ConvergenceAngle: unknown
//!            B206 RATIONAL  1   offset 144      BaselineLength: unknown
//!          next IFD: 0
//!   M0+136 FFFFFFFF FFFFFFFF  FFFFFFFF FFFFFFFF (DC-007's "unknown")
//!   …                             DQT, SOF0, DHT, SOS, scan (the encoder's)
//!   FFD9                          EOI
//! right eye (Size2 bytes), at file offset Offset2 + (M0's file offset)
//!   FFD8, FFE0 …, FFE2 LLLL "MPF\0" (LLLL = 2 + 4 + 90)
//!   M0'+0  4D4D 002A 00000008
//!   M0'+8  MP Attribute IFD, 5 entries: B000 "0100", B101 = 2, B204 = 1,
//!          B205 and B206 (values at 74 and 82) unknown as above; next 0
//!   …, FFD9
//! ```
//!
//! A glstereo rendering has no physical camera, so the convergence angle and
//! baseline length are written as unknown.
//!
//! # JPS (VRex stereo JPEG)
//!
//! One baseline JPEG of 2W×H holding both eyes side by side, the right eye
//! on the left half and the left eye on the right half (the convention for
//! cross-eyed free viewing that JPS viewers expect), with an APP3 segment
//! after APP0:
//!
//! ```text
//!   FFE3 0010 "_JPSJPS_" 0004 00 00 02 01
//!             identifier descriptor length; the 32-bit descriptor:
//!             separation 0, flags 0 (full size; "left field first" not
//!             set: right eye first), layout 2 side-by-side, media type 1 stereo
//! ```
//!
//! Both formats need two different eyes: a mono surface is refused by the
//! callers ([`crate::surface::Surface::save_stereo_photo`]).

use std::io::Write;
use std::path::Path;

use jpeg_encoder::{ColorType, Encoder};

use crate::error::{Error, Result};
use crate::image::Image;

/// The JPEG quality used when none is set (1 … 100).
pub const DEFAULT_JPEG_QUALITY: u8 = 90;

/// A stereo photo format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StereoPhotoFormat {
    /// CIPA DC-007 Multi-Picture Object: two JPEGs, left eye first.
    Mpo,
    /// JPEG Stereo: one 2W×H JPEG, right eye on the left half.
    Jps,
}

impl StereoPhotoFormat {
    /// Both formats.
    pub const ALL: [StereoPhotoFormat; 2] = [StereoPhotoFormat::Mpo, StereoPhotoFormat::Jps];

    /// The format's name and file extension: `mpo`, `jps`.
    pub fn extension(self) -> &'static str {
        match self {
            StereoPhotoFormat::Mpo => "mpo",
            StereoPhotoFormat::Jps => "jps",
        }
    }
}

/// Checks a JPEG quality: 1 (smallest file) … 100 (best image).
///
/// # Errors
/// [`Error::InvalidValue`] outside that range, saying so.
pub fn check_quality(quality: u32) -> Result<u8> {
    match u8::try_from(quality) {
        Ok(q @ 1..=100) => Ok(q),
        _ => Err(Error::invalid_value(format!(
            "JPEG quality {quality} is out of range: give 1 (smallest file) to 100 (best \
             image); the default is {DEFAULT_JPEG_QUALITY}"
        ))),
    }
}

/// Encodes `left` and `right` (the same size) as a stereo photo into `out`;
/// `path` only names the file in messages.
///
/// # Errors
/// [`Error::InvalidValue`] for eyes of different sizes or a quality out of
/// range; [`Error::Io`] when writing fails.
pub fn encode(
    format: StereoPhotoFormat,
    left: &Image,
    right: &Image,
    quality: u8,
    path: &Path,
    out: &mut dyn Write,
) -> Result<()> {
    check_quality(quality.into())?;
    if (left.width(), left.height()) != (right.width(), right.height()) {
        return Err(Error::invalid_value(format!(
            "the eyes of a stereo photo must be the same size (left {}x{}, right {}x{})",
            left.width(),
            left.height(),
            right.width(),
            right.height()
        )));
    }
    let bytes = match format {
        StereoPhotoFormat::Mpo => mpo(left, right, quality)?,
        StereoPhotoFormat::Jps => jps(left, right, quality)?,
    };
    out.write_all(&bytes)
        .map_err(|e| Error::Io(format!("cannot write {}: {e}", path.display())))
}

/// Writes a stereo photo to `path` atomically (see
/// [`super::write_atomically`]): complete, or no file at all.
pub fn write(
    format: StereoPhotoFormat,
    left: &Image,
    right: &Image,
    quality: u8,
    path: &Path,
) -> Result<()> {
    super::write_atomically(path, |w| encode(format, left, right, quality, path, w))
}

fn jpeg_error(e: jpeg_encoder::EncodingError) -> Error {
    Error::invalid_value(format!("JPEG encoding failed: {e}"))
}

fn side(v: u32, what: &str) -> Result<u16> {
    u16::try_from(v).map_err(|_| {
        Error::invalid_value(format!(
            "a JPEG {what} is at most 65535 pixels; this one would be {v}"
        ))
    })
}

/// RGBA pixels (`width` × `height`, rows top first) as a baseline JPEG
/// with `app` segments after APP0.
fn jpeg(
    pixels: &[u8],
    (width, height): (u32, u32),
    quality: u8,
    app: &[(u8, &[u8])],
) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut enc = Encoder::new(&mut bytes, quality);
    for (n, data) in app {
        enc.add_app_segment(*n, data).map_err(jpeg_error)?;
    }
    enc.encode(
        pixels,
        side(width, "width")?,
        side(height, "height")?,
        ColorType::Rgba,
    )
    .map_err(jpeg_error)?;
    Ok(bytes)
}

/// One eye as a baseline JPEG.
fn eye_jpeg(image: &Image, quality: u8) -> Result<Vec<u8>> {
    jpeg(
        image.pixels(),
        (image.width(), image.height()),
        quality,
        &[],
    )
}

/// TIFF field types used by the MP Extension.
const LONG: u16 = 4;
const RATIONAL: u16 = 5;
const UNDEFINED: u16 = 7;
const SRATIONAL: u16 = 10;

/// "Unknown" for a (S)RATIONAL attribute (DC-007): every bit set.
const UNKNOWN_RATIONAL: [u8; 8] = [0xFF; 8];

/// One IFD field: tag, type, count and its value's bytes (big-endian).
struct Field {
    tag: u16,
    kind: u16,
    count: u32,
    value: Vec<u8>,
}

fn long(tag: u16, v: u32) -> Field {
    Field {
        tag,
        kind: LONG,
        count: 1,
        value: v.to_be_bytes().to_vec(),
    }
}

/// An IFD starting at `start` (from M0) with the values longer than 4 bytes
/// right after it; the next-IFD pointer names the byte after those values
/// when `chained`, else 0.
fn ifd(start: u32, fields: &[Field], chained: bool) -> Vec<u8> {
    let n = fields.len() as u32;
    let mut values_at = start + 2 + 12 * n + 4;
    let mut dir = (n as u16).to_be_bytes().to_vec();
    let mut values: Vec<u8> = Vec::new();
    for f in fields {
        dir.extend(f.tag.to_be_bytes());
        dir.extend(f.kind.to_be_bytes());
        dir.extend(f.count.to_be_bytes());
        if f.value.len() <= 4 {
            let mut inline = f.value.clone();
            inline.resize(4, 0);
            dir.extend(inline);
        } else {
            dir.extend(values_at.to_be_bytes());
            values_at += f.value.len() as u32;
            values.extend(&f.value);
        }
    }
    let next = if chained { values_at } else { 0 };
    dir.extend(next.to_be_bytes());
    dir.extend(values);
    dir
}

/// The MP Header: big-endian, first IFD at offset 8.
const MP_HEADER: [u8; 8] = [b'M', b'M', 0x00, 0x2A, 0, 0, 0, 8];
/// MP type "Multi-frame Disparity" (DC-007 Table 4), JPEG data format.
const DISPARITY: u32 = 0x02_0002;
/// The representative-image flag of an MP Entry's attribute.
const REPRESENTATIVE: u32 = 1 << 29;

/// The MP Attribute IFD of image `number` (1-based) at `start`.
fn attributes(start: u32, number: u32, with_version: bool) -> Vec<u8> {
    let mut fields = Vec::new();
    if with_version {
        fields.push(Field {
            tag: 0xB000,
            kind: UNDEFINED,
            count: 4,
            value: b"0100".to_vec(),
        });
    }
    fields.push(long(0xB101, number));
    fields.push(long(0xB204, 1));
    for (tag, kind) in [(0xB205, SRATIONAL), (0xB206, RATIONAL)] {
        fields.push(Field {
            tag,
            kind,
            count: 1,
            value: UNKNOWN_RATIONAL.to_vec(),
        });
    }
    ifd(start, &fields, false)
}

/// The MP Extension (after "MPF\0") of the first image: MP Index IFD for
/// two images of `sizes` bytes, the second at `second_offset` from M0, then
/// the first image's MP Attribute IFD.
fn first_extension(sizes: [u32; 2], second_offset: u32) -> Vec<u8> {
    let mut entries = Vec::with_capacity(32);
    for (attr, size, offset) in [
        (REPRESENTATIVE | DISPARITY, sizes[0], 0),
        (DISPARITY, sizes[1], second_offset),
    ] {
        entries.extend(attr.to_be_bytes());
        entries.extend(size.to_be_bytes());
        entries.extend(offset.to_be_bytes());
        entries.extend([0u8; 4]);
    }
    let index = ifd(
        8,
        &[
            Field {
                tag: 0xB000,
                kind: UNDEFINED,
                count: 4,
                value: b"0100".to_vec(),
            },
            long(0xB001, 2),
            Field {
                tag: 0xB002,
                kind: UNDEFINED,
                count: 32,
                value: entries,
            },
        ],
        true,
    );
    let mut ext = MP_HEADER.to_vec();
    ext.extend(&index);
    let attr_start = ext.len() as u32;
    ext.extend(attributes(attr_start, 1, false));
    ext
}

/// The MP Extension of the second image: its MP Attribute IFD only.
fn second_extension() -> Vec<u8> {
    let mut ext = MP_HEADER.to_vec();
    ext.extend(attributes(8, 2, true));
    ext
}

/// An APP2 "MPF" segment holding `ext`.
fn mpf_segment(ext: &[u8]) -> Vec<u8> {
    let len = (2 + 4 + ext.len()) as u16;
    let mut seg = vec![0xFF, 0xE2];
    seg.extend(len.to_be_bytes());
    seg.extend(b"MPF\0");
    seg.extend(ext);
    seg
}

/// Where an APP2 segment goes in an encoded JPEG: after SOI and any APP0
/// or APP1 segments.
fn app2_position(jpeg: &[u8]) -> usize {
    let mut at = 2;
    while jpeg.len() >= at + 4 && jpeg[at] == 0xFF && matches!(jpeg[at + 1], 0xE0 | 0xE1) {
        at += 2 + u16::from_be_bytes([jpeg[at + 2], jpeg[at + 3]]) as usize;
    }
    at
}

fn mpo(left: &Image, right: &Image, quality: u8) -> Result<Vec<u8>> {
    let first = eye_jpeg(left, quality)?;
    let second = eye_jpeg(right, quality)?;
    // The segments' lengths do not depend on the sizes and offsets they
    // hold, so one trial build gives them.
    let first_seg_len = mpf_segment(&first_extension([0, 0], 0)).len();
    let second_seg = mpf_segment(&second_extension());
    let at1 = app2_position(&first);
    let at2 = app2_position(&second);
    let too_big = || Error::invalid_value("an MPO is at most 4 GiB: use a smaller surface");
    let size1 = u32::try_from(first.len() + first_seg_len).map_err(|_| too_big())?;
    let size2 = u32::try_from(second.len() + second_seg.len()).map_err(|_| too_big())?;
    // M0: after the segment's marker, length and "MPF\0".
    let m0 = (at1 + 8) as u32;
    let first_seg = mpf_segment(&first_extension([size1, size2], size1 - m0));
    debug_assert_eq!(first_seg.len(), first_seg_len);
    let mut out = Vec::with_capacity(size1 as usize + size2 as usize);
    out.extend(&first[..at1]);
    out.extend(&first_seg);
    out.extend(&first[at1..]);
    out.extend(&second[..at2]);
    out.extend(&second_seg);
    out.extend(&second[at2..]);
    Ok(out)
}

/// The JPS APP3 payload: identifier, descriptor length, descriptor
/// (separation 0, flags 0, layout side-by-side, media type stereo).
const JPS_DESCRIPTOR: [u8; 14] = [
    b'_', b'J', b'P', b'S', b'J', b'P', b'S', b'_', 0x00, 0x04, 0x00, 0x00, 0x02, 0x01,
];

fn jps(left: &Image, right: &Image, quality: u8) -> Result<Vec<u8>> {
    let (w, h) = (left.width(), left.height());
    // Cross-eyed order: the right eye on the left half, copied row by row
    // into one 2W×H buffer for the encoder's RGBA path.
    let row = w as usize * 4;
    let mut pair = crate::image::try_vec(row * 2 * h as usize, 0u8, "a JPS frame")?;
    for (y, out) in pair.chunks_exact_mut(row * 2).enumerate() {
        out[..row].copy_from_slice(right.row(y as u32));
        out[row..].copy_from_slice(left.row(y as u32));
    }
    jpeg(&pair, (w * 2, h), quality, &[(3, &JPS_DESCRIPTOR)])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eyes() -> (Image, Image) {
        let l = Image::from_fn(24, 16, |x, _| [200, 40, (x * 8) as u8, 255]);
        let r = Image::from_fn(24, 16, |_, y| [20, 180, (y * 12) as u8, 255]);
        (l, r)
    }

    fn be32(b: &[u8], at: usize) -> u32 {
        u32::from_be_bytes(b[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn the_mp_index_names_both_images_by_size_and_offset() {
        let (l, r) = eyes();
        let file = mpo(&l, &r, 90).unwrap();
        let seg = file.windows(4).position(|w| w == b"MPF\0").unwrap();
        let m0 = seg + 4;
        assert_eq!(&file[seg - 4..seg - 2], &[0xFF, 0xE2]);
        assert_eq!(&file[m0..m0 + 8], &MP_HEADER);
        // NumberOfImages, then the MP Entries at the offset B002 names.
        assert_eq!(u16::from_be_bytes([file[m0 + 8], file[m0 + 9]]), 3);
        assert_eq!(be32(&file, m0 + 10 + 12 + 8), 2);
        let entries = m0 + be32(&file, m0 + 10 + 24 + 8) as usize;
        let size1 = be32(&file, entries + 4) as usize;
        let size2 = be32(&file, entries + 16 + 4) as usize;
        let off2 = be32(&file, entries + 16 + 8) as usize;
        assert_eq!(be32(&file, entries), 0x2002_0002);
        assert_eq!(be32(&file, entries + 16), 0x0002_0002);
        assert_eq!(be32(&file, entries + 8), 0, "the first image's offset is 0");
        assert_eq!(size1 + size2, file.len());
        assert_eq!(
            m0 + off2,
            size1,
            "the second image starts where the first ends"
        );
        assert_eq!(&file[size1..size1 + 2], &[0xFF, 0xD8]);
        assert_eq!(&file[size1 - 2..size1], &[0xFF, 0xD9]);
        assert_eq!(&file[file.len() - 2..], &[0xFF, 0xD9]);
        // The second image has its own MPF segment (attributes only).
        let second = &file[size1..];
        let s2 = second.windows(4).position(|w| w == b"MPF\0").unwrap();
        let ifd2 = s2 + 4 + 8;
        assert_eq!(u16::from_be_bytes([second[ifd2], second[ifd2 + 1]]), 5);
        // MPIndividualNum (the second field) is 2.
        assert_eq!(
            u16::from_be_bytes([second[ifd2 + 14], second[ifd2 + 15]]),
            0xB101
        );
        assert_eq!(be32(second, ifd2 + 14 + 8), 2);
    }

    #[test]
    fn a_jps_is_one_double_width_jpeg_with_the_stereo_descriptor() {
        let (l, r) = eyes();
        let file = jps(&l, &r, 90).unwrap();
        let at = file.windows(8).position(|w| w == b"_JPSJPS_").unwrap();
        assert_eq!(&file[at - 4..at - 2], &[0xFF, 0xE3]);
        assert_eq!(&file[at..at + 14], &JPS_DESCRIPTOR);
        // SOF0 (baseline): height then width.
        let sof = file.windows(2).position(|w| w == [0xFF, 0xC0]).unwrap();
        let h = u16::from_be_bytes([file[sof + 5], file[sof + 6]]);
        let w = u16::from_be_bytes([file[sof + 7], file[sof + 8]]);
        assert_eq!((w, h), (48, 16));
    }

    #[test]
    fn quality_outside_1_to_100_is_refused_with_the_range() {
        for q in [0, 101, 256, u32::MAX] {
            let e = check_quality(q).unwrap_err();
            assert!(matches!(e, Error::InvalidValue(_)), "{e}");
            assert!(e.to_string().contains("1 (smallest file) to 100"), "{e}");
        }
        assert_eq!(check_quality(1).unwrap(), 1);
        assert_eq!(check_quality(100).unwrap(), 100);
    }

    #[test]
    fn eyes_of_different_sizes_are_refused() {
        let (l, _) = eyes();
        let r = Image::new(3, 3);
        let e = encode(
            StereoPhotoFormat::Mpo,
            &l,
            &r,
            90,
            Path::new("x.mpo"),
            &mut Vec::new(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("same size"), "{e}");
    }

    #[test]
    fn a_failed_write_leaves_no_file() {
        let (l, r) = eyes();
        let e = write(
            StereoPhotoFormat::Mpo,
            &l,
            &r,
            90,
            Path::new("/nonexistent-dir/x.mpo"),
        )
        .unwrap_err();
        assert!(matches!(e, Error::Io(_)), "{e}");
        assert!(e.to_string().contains("/nonexistent-dir/x.mpo"), "{e}");
    }
}

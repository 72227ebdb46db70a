//! Writing images to PNG files, and stereo pairs to MPO or JPS files
//! ([`stereo_photo`]): atomically (a temporary file in the same directory,
//! renamed into place), so a failed or interrupted capture never leaves a
//! half-written file under the requested name.

pub mod queue;
pub mod stereo_photo;

use std::io::{BufWriter, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{Error, Result};
use crate::image::Image;

/// Encodes `image` as an 8-bit RGBA PNG (fast compression) into `path`.
pub fn write_png(image: &Image, path: &Path) -> Result<()> {
    write_atomically(path, |w| encode_png(image, path, w))
}

/// Encodes `image` as an 8-bit RGBA PNG with fast compression (the Sub
/// filter and fdeflate: about 3.6 ms for a rendered 1280x1024 frame) into
/// `out`; `path` only names the file in messages.
pub fn encode_png(image: &Image, path: &Path, out: &mut dyn Write) -> Result<()> {
    let mut enc = png::Encoder::new(out, image.width(), image.height());
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Fast);
    let mut writer = enc
        .write_header()
        .map_err(|e| Error::Io(format!("cannot write {}: {e}", path.display())))?;
    // Streamed: write_image_data would first compress the whole image into
    // memory (as large as the image for noisy content).
    let mut stream = writer
        .stream_writer()
        .map_err(|e| Error::Io(format!("cannot write {}: {e}", path.display())))?;
    stream
        .write_all(image.pixels())
        .map_err(|e| Error::Io(format!("cannot write {}: {e}", path.display())))?;
    stream
        .finish()
        .map_err(|e| Error::Io(format!("cannot write {}: {e}", path.display())))
}

/// Writes a file atomically: `write` fills a temporary file in the same
/// directory, which is flushed to disk and renamed to `path`; on any
/// failure the temporary file is removed and `path` is untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<()>,
) -> Result<()> {
    static SEQ: AtomicU64 = AtomicU64::new(0);
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| Error::invalid_value(format!("{} names no file", path.display())))?;
    let tmp = dir.join(format!(
        ".{}.tmp-{}-{}",
        name.to_string_lossy(),
        std::process::id(),
        SEQ.fetch_add(1, Ordering::Relaxed)
    ));
    let io = |what: &str, e: std::io::Error| Error::Io(format!("{what} {}: {e}", path.display()));
    let result = (|| {
        let file = std::fs::File::create(&tmp).map_err(|e| io("cannot create", e))?;
        let mut w = BufWriter::new(file);
        write(&mut w)?;
        let file = w
            .into_inner()
            .map_err(|e| io("cannot write", e.into_error()))?;
        // A failed sync means the data may never reach the disk: report it
        // rather than rename a file that may be incomplete into place.
        file.sync_all().map_err(|e| io("cannot write", e))?;
        drop(file);
        std::fs::rename(&tmp, path).map_err(|e| io("cannot rename the capture into", e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Reads an 8-bit RGB or RGBA PNG into an [`Image`] (for tests and tools).
pub fn read_png(path: &Path) -> Result<Image> {
    let file = std::fs::File::open(path)
        .map_err(|e| Error::Io(format!("cannot open {}: {e}", path.display())))?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder
        .read_info()
        .map_err(|e| Error::Io(format!("{} is not a readable PNG: {e}", path.display())))?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| Error::Io(format!("{} is not a readable PNG: {e}", path.display())))?;
    buf.truncate(info.buffer_size());
    let pixels = match (info.color_type, info.bit_depth) {
        (png::ColorType::Rgba, png::BitDepth::Eight) => buf,
        (png::ColorType::Rgb, png::BitDepth::Eight) => buf
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect(),
        (c, d) => {
            return Err(Error::Io(format!(
                "{}: {c:?} at {d:?} is not an 8-bit RGB(A) PNG",
                path.display()
            )));
        }
    };
    Image::from_pixels(info.width, info.height, pixels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trips_and_leaves_no_temporary_file() {
        let dir = std::env::temp_dir().join(format!("glstereo-capture-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let img = Image::from_fn(7, 5, |x, y| [x as u8 * 30, y as u8 * 40, 200, 255]);
        let path = dir.join("a.png");
        write_png(&img, &path).unwrap();
        assert_eq!(read_png(&path).unwrap(), img);
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("a.png")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_unwritable_path_is_an_io_error_naming_it() {
        let img = Image::new(2, 2);
        let e = write_png(&img, Path::new("/nonexistent-dir/x.png")).unwrap_err();
        assert!(matches!(e, Error::Io(_)));
        assert!(e.to_string().contains("/nonexistent-dir/x.png"), "{e}");
    }
}

//! Writing images to PNG files, and stereo pairs to MPO or JPS files
//! ([`stereo_photo`]): atomically (a temporary file in the same directory,
//! renamed into place), so a failed or interrupted capture never leaves a
//! half-written file under the requested name.
//!
//! The directory may be shared with other users (`glstereo-run --capture
//! /tmp/frames`): whoever can write it can plant a file or a symbolic link
//! under any name there. So the temporary file is made under a name
//! nobody can predict (64 random bits), created exclusively and never
//! through a symbolic link (`O_CREAT | O_EXCL | O_NOFOLLOW`: a name
//! already taken, by anything, is skipped for another), and renamed over
//! the requested name, which replaces whatever is there (a link itself,
//! not its target). Nothing the library or the layer creates elsewhere is
//! named in a shared place: eye memory is an anonymous memfd, MIT-SHM
//! segments are `IPC_PRIVATE` with mode 0600.

pub mod queue;
pub mod stereo_photo;

use std::io::{BufWriter, Write};
use std::path::Path;

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
/// directory (made exclusively, under a random name: see the module
/// documentation), which is flushed to disk and renamed to `path`; on any
/// failure the temporary file is removed and `path` is untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<()>,
) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| Error::invalid_value(format!("{} names no file", path.display())))?;
    let io = |what: &str, e: std::io::Error| Error::Io(format!("{what} {}: {e}", path.display()));
    let (tmp, file) =
        create_temporary(dir, name, random_u64).map_err(|e| io("cannot create", e))?;
    let result = (|| {
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

/// Names tried before [`create_temporary`] gives up (each taken name is
/// 1 in 2^64 by chance: only a directory filling up, or someone planting
/// names it cannot guess, makes it try twice).
const TEMPORARY_TRIES: usize = 64;

/// Creates a new, empty temporary file for `name` in `dir`, named
/// `.NAME.tmp-RANDOM` with `random` giving the 64 bits: exclusively, never
/// through a symbolic link (`O_CREAT | O_EXCL | O_NOFOLLOW`), and a name
/// that exists in any form is left as it is and another drawn. The file's
/// mode is 0666 less the umask, as `File::create` gives.
///
/// # Errors
/// The error of the last attempt (`AlreadyExists` after
/// [`TEMPORARY_TRIES`] taken names).
fn create_temporary(
    dir: &Path,
    name: &std::ffi::OsStr,
    mut random: impl FnMut() -> u64,
) -> std::io::Result<(std::path::PathBuf, std::fs::File)> {
    use std::os::unix::fs::OpenOptionsExt;
    // At most 255 bytes in a name (NAME_MAX): a long name is cut, at a
    // character boundary, to leave room for the suffix.
    let shown = name.to_string_lossy();
    let mut end = shown.len().min(200);
    while !shown.is_char_boundary(end) {
        end -= 1;
    }
    let mut last = std::io::Error::from(std::io::ErrorKind::AlreadyExists);
    for _ in 0..TEMPORARY_TRIES {
        let tmp = dir.join(format!(".{}.tmp-{:016x}", &shown[..end], random()));
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .mode(0o666)
            .custom_flags(libc::O_NOFOLLOW)
            .open(&tmp)
        {
            Ok(file) => return Ok((tmp, file)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = e,
            Err(e) => return Err(e),
        }
    }
    Err(last)
}

/// 64 bits nobody else can predict: from the kernel (getrandom), or if
/// that fails, from the standard library's randomly keyed hasher.
fn random_u64() -> u64 {
    let mut bytes = [0u8; 8];
    // SAFETY: writes at most 8 bytes into the array.
    let n = unsafe { libc::getrandom(bytes.as_mut_ptr().cast(), bytes.len(), 0) };
    if n == bytes.len() as isize {
        return u64::from_ne_bytes(bytes);
    }
    use std::hash::{BuildHasher, Hasher};
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos()),
    );
    h.finish()
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

    /// A fresh directory of this test's own under the system's temporary one.
    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("glstereo-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn symlinks_planted_in_a_shared_directory_are_never_followed() {
        // Another user who can write the capture directory plants links
        // to a file of ours: at the temporary names the writer used to use
        // (.NAME.tmp-PID-SEQ, predictable) and at the capture's own name.
        let dir = scratch("planted");
        let theirs = scratch("planted-victims");
        let victim = theirs.join("precious");
        std::fs::write(&victim, b"precious").unwrap();
        let name = "left-000001.png";
        for seq in 0..512 {
            let planted = dir.join(format!(".{name}.tmp-{}-{seq}", std::process::id()));
            std::os::unix::fs::symlink(&victim, planted).unwrap();
        }
        let final_victim = theirs.join("precious-too");
        std::fs::write(&final_victim, b"precious too").unwrap();
        std::os::unix::fs::symlink(&final_victim, dir.join(name)).unwrap();

        let img = Image::from_fn(6, 4, |x, y| [x as u8 * 40, y as u8 * 60, 7, 255]);
        write_png(&img, &dir.join(name)).unwrap();

        assert_eq!(
            std::fs::read(&victim).unwrap(),
            b"precious",
            "a link's target was written"
        );
        assert_eq!(std::fs::read(&final_victim).unwrap(), b"precious too");
        let meta = std::fs::symlink_metadata(dir.join(name)).unwrap();
        assert!(
            meta.is_file(),
            "the capture replaced the planted link: {meta:?}"
        );
        assert_eq!(read_png(&dir.join(name)).unwrap(), img);
        // The planted links are left alone, and no temporary file is left.
        let mut links = 0;
        for e in std::fs::read_dir(&dir).unwrap() {
            let e = e.unwrap();
            if e.file_name() != name {
                assert!(
                    e.file_type().unwrap().is_symlink(),
                    "{:?} left",
                    e.file_name()
                );
                links += 1;
            }
        }
        assert_eq!(links, 512);
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_dir_all(&theirs).unwrap();
    }

    #[test]
    fn a_taken_temporary_name_is_left_alone_and_another_drawn() {
        let dir = scratch("taken");
        let victim = dir.join("victim");
        std::fs::write(&victim, b"keep").unwrap();
        let taken = |n: u64| dir.join(format!(".b.png.tmp-{n:016x}"));
        std::os::unix::fs::symlink(&victim, taken(7)).unwrap();
        std::fs::write(taken(8), b"someone's").unwrap();
        let mut draws = [7u64, 8, 9].into_iter();
        let (tmp, _file) =
            create_temporary(&dir, "b.png".as_ref(), || draws.next().unwrap()).unwrap();
        assert_eq!(tmp, taken(9));
        assert_eq!(std::fs::read(&victim).unwrap(), b"keep");
        assert!(std::fs::symlink_metadata(taken(7)).unwrap().is_symlink());
        assert_eq!(std::fs::read(taken(8)).unwrap(), b"someone's");
        // Every name taken: an error, not a file written through a link.
        let e = create_temporary(&dir, "b.png".as_ref(), || 7).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::AlreadyExists);
        assert_eq!(std::fs::read(&victim).unwrap(), b"keep");
        // A name too long for a temporary one is cut, not refused.
        let long = "x".repeat(250);
        let (tmp, _file) = create_temporary(&dir, long.as_ref(), random_u64).unwrap();
        assert!(tmp.file_name().unwrap().len() <= 255, "{tmp:?}");
        assert_ne!(random_u64(), random_u64());
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

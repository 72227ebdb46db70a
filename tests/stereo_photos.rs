//! Stereo photos (MPO, JPS) of a real EGL surface, read back with readers
//! that are not ours: Pillow's MPO and JPEG plugins decode the pixels,
//! exiftool reads the MP Index and the JPS descriptor. And the misuse the
//! C API refuses: a mono surface, a quality out of range, a path that
//! cannot be written (no file left behind), bad enums and NULLs.

mod common;
#[path = "common/gl_surface.rs"]
mod gl_surface;

use std::ffi::CString;
use std::path::Path;

use glstereo::backend::BackendKind;
use glstereo::capture::read_png;
use glstereo::capture::stereo_photo::StereoPhotoFormat;
use glstereo::error::Error;
use glstereo::ffi::capture::{
    GLS_PHOTO_JPS, GLS_PHOTO_MPO, gls_surface_queue_stereo_photo, gls_surface_save_stereo_photo,
    gls_surface_set_jpeg_quality, gls_surface_wait_captures,
};
use glstereo::ffi::display::{
    GLS_BACKEND_EGL, gls_config_choose, gls_config_free, gls_display_close, gls_display_open,
};
use glstereo::ffi::surface::{gls_surface_create, gls_surface_destroy};
use glstereo::ffi::types::*;
use glstereo::image::Image;
use glstereo::surface::{self, CaptureImage};

use common::last_error;
use common::photo::{exiftool, mean_error, pillow, tag};
use gl_surface::{mono_surface, show, show_mono, stereo_surface};

const W: u32 = 96;
const H: u32 = 64;

/// Two eyes that differ everywhere (warm and cool gradients, a dark square
/// shifted between them), smooth enough for JPEG to keep them close.
fn eyes() -> (Image, Image) {
    let square = |x: u32, y: u32, x0: u32| (x0..x0 + 24).contains(&x) && (20..44).contains(&y);
    let left = Image::from_fn(W, H, |x, y| {
        if square(x, y, 30) {
            [20, 20, 20, 255]
        } else {
            [200 + (x * 50 / W) as u8, 90 + (y * 60 / H) as u8, 40, 255]
        }
    });
    let right = Image::from_fn(W, H, |x, y| {
        if square(x, y, 42) {
            [20, 20, 20, 255]
        } else {
            [30, 120 + (y * 80 / H) as u8, 160 + (x * 90 / W) as u8, 255]
        }
    });
    (left, right)
}

#[test]
fn mpo_and_jps_hold_the_eyes_as_independent_readers_see_them() {
    let dir = common::scratch("stereo-photos");
    let s = stereo_surface(BackendKind::Egl, W, H);
    let (left, right) = eyes();
    show(&s, &left, &right);
    // The eyes as the PNG capture writes them: the reference.
    s.save_png(CaptureImage::Left, &dir.join("left.png"))
        .unwrap();
    s.save_png(CaptureImage::Right, &dir.join("right.png"))
        .unwrap();
    let l_png = read_png(&dir.join("left.png")).unwrap();
    let r_png = read_png(&dir.join("right.png")).unwrap();
    assert_eq!(s.jpeg_quality(), 90, "the documented default");
    for fmt in StereoPhotoFormat::ALL {
        let ext = fmt.extension();
        s.save_stereo_photo(fmt, &dir.join(format!("saved.{ext}")))
            .unwrap();
        s.queue_stereo_photo(fmt, &dir.join(format!("queued.{ext}")))
            .unwrap();
    }
    s.finish_captures().unwrap();

    for name in ["saved", "queued"] {
        // MPO: Pillow's MPO plugin, two frames of the eye's size.
        let mpo = dir.join(format!("{name}.mpo"));
        let (format, n, frames) = pillow(&mpo);
        assert_eq!((format.as_str(), n), ("MPO", 2), "{name}.mpo");
        for (i, (w, h, _)) in frames.iter().enumerate() {
            assert_eq!((*w, *h), (W, H), "{name}.mpo frame {i}");
        }
        let (l_err, r_err) = (
            mean_error(&frames[0].2, W, 0, &l_png),
            mean_error(&frames[1].2, W, 0, &r_png),
        );
        assert!(
            l_err < 2.5 && r_err < 2.5,
            "{name}.mpo: mean error left {l_err:.2}, right {r_err:.2} (want < 2.5)"
        );
        // The eyes differ: the first frame is not the right eye.
        let swapped = mean_error(&frames[0].2, W, 0, &r_png);
        assert!(
            swapped > 40.0,
            "{name}.mpo frame 0 vs right eye: {swapped:.1}"
        );

        // exiftool: the MP Index, both images, where they are.
        let tags = exiftool(&mpo);
        let len = std::fs::metadata(&mpo).unwrap().len();
        assert_eq!(tag(&tags, "MPF0", "MPFVersion"), "0100");
        assert_eq!(tag(&tags, "MPF0", "NumberOfImages"), "2");
        let num = |g: &str, t: &str| tag(&tags, g, t).parse::<u64>().unwrap();
        assert_eq!(num("MPImage1", "MPImageType"), 0x020002, "disparity");
        assert_eq!(num("MPImage2", "MPImageType"), 0x020002, "disparity");
        assert_eq!(num("MPImage1", "MPImageStart"), 0);
        let (len1, start2, len2) = (
            num("MPImage1", "MPImageLength"),
            num("MPImage2", "MPImageStart"),
            num("MPImage2", "MPImageLength"),
        );
        assert_eq!(start2, len1, "the second image follows the first");
        assert_eq!(len1 + len2, len, "the two images are the whole file");
        let bytes = std::fs::read(&mpo).unwrap();
        assert_eq!(
            &bytes[start2 as usize..][..2],
            &[0xFF, 0xD8],
            "SOI at start"
        );

        // JPS: one 2W x H image, the right eye on the left half.
        let jps = dir.join(format!("{name}.jps"));
        let (format, n, frames) = pillow(&jps);
        assert_eq!((format.as_str(), n), ("JPEG", 1), "{name}.jps");
        let (w, h, rgb) = &frames[0];
        assert_eq!((*w, *h), (2 * W, H), "{name}.jps size");
        let on_left = mean_error(rgb, 2 * W, 0, &r_png);
        let on_right = mean_error(rgb, 2 * W, W, &l_png);
        assert!(
            on_left < 2.5 && on_right < 2.5,
            "{name}.jps: right eye on the left half within {on_left:.2}, left eye on \
             the right half within {on_right:.2} (want < 2.5)"
        );
        let swapped = mean_error(rgb, 2 * W, 0, &l_png);
        assert!(
            swapped > 40.0,
            "{name}.jps left half vs left eye: {swapped:.1}"
        );
        let tags = exiftool(&jps);
        assert_eq!(tag(&tags, "JPS", "JPSLayout"), "2", "side by side");
        assert_eq!(tag(&tags, "JPS", "JPSType"), "1", "stereo");
        assert_eq!(tag(&tags, "JPS", "JPSFlags"), "0", "right eye first");
    }
    surface::make_current(None).unwrap();
}

#[test]
fn swapped_eyes_and_quality_reach_the_photo() {
    let dir = common::scratch("stereo-photos-settings");
    let s = stereo_surface(BackendKind::Egl, W, H);
    let (left, right) = eyes();
    show(&s, &left, &right);
    s.set_jpeg_quality(30).unwrap();
    s.save_stereo_photo(StereoPhotoFormat::Mpo, &dir.join("q30.mpo"))
        .unwrap();
    s.set_jpeg_quality(100).unwrap();
    s.save_stereo_photo(StereoPhotoFormat::Mpo, &dir.join("q100.mpo"))
        .unwrap();
    let size = |f: &str| std::fs::metadata(dir.join(f)).unwrap().len();
    assert!(
        size("q30.mpo") * 2 < size("q100.mpo"),
        "quality 30: {} bytes, quality 100: {} bytes",
        size("q30.mpo"),
        size("q100.mpo")
    );
    // Swapped eyes: the first image is the right eye.
    let mut o = s.options();
    o.swap_eyes = true;
    s.set_options(o).unwrap();
    s.save_stereo_photo(StereoPhotoFormat::Mpo, &dir.join("swapped.mpo"))
        .unwrap();
    let (_, _, frames) = pillow(&dir.join("swapped.mpo"));
    let first = mean_error(&frames[0].2, W, 0, &right);
    assert!(first < 2.5, "swapped: first image vs right eye {first:.2}");
    surface::make_current(None).unwrap();
}

#[test]
fn a_mono_surface_whose_framing_holds_two_eyes_makes_a_stereo_photo() {
    // Xinerama passive stereo: one double-width mono frame, an eye per half.
    let dir = common::scratch("stereo-photos-framing");
    let s = mono_surface(BackendKind::Egl, 2 * W, H);
    s.set_framing(glstereo::framing::InputFraming::SideBySide)
        .unwrap();
    let (left, right) = eyes();
    let frame = Image::from_fn(2 * W, H, |x, y| {
        if x < W {
            left.get(x, y)
        } else {
            right.get(x - W, y)
        }
    });
    show_mono(&s, &frame);
    s.save_stereo_photo(StereoPhotoFormat::Mpo, &dir.join("xinerama.mpo"))
        .unwrap();
    let (format, n, frames) = pillow(&dir.join("xinerama.mpo"));
    assert_eq!((format.as_str(), n), ("MPO", 2));
    assert_eq!((frames[0].0, frames[0].1), (W, H), "each image is one eye");
    let errors = [
        mean_error(&frames[0].2, W, 0, &left),
        mean_error(&frames[1].2, W, 0, &right),
    ];
    assert!(errors.iter().all(|e| *e < 2.5), "{errors:?}");
    surface::make_current(None).unwrap();
}

#[test]
fn bad_input_gets_its_documented_error_and_leaves_no_file() {
    let dir = common::scratch("stereo-photos-errors");
    // A mono surface: one image is not a stereo photo.
    let m = mono_surface(BackendKind::Egl, W, H);
    show_mono(&m, &eyes().0);
    for fmt in StereoPhotoFormat::ALL {
        let path = dir.join(format!("mono.{}", fmt.extension()));
        let e = m.save_stereo_photo(fmt, &path).unwrap_err();
        assert!(matches!(e, Error::InvalidOperation(_)), "{e}");
        let msg = e.to_string();
        assert!(
            msg.contains("mono") && msg.contains("not a stereo photo"),
            "{msg}"
        );
        let e = m.queue_stereo_photo(fmt, &path).unwrap_err();
        assert!(matches!(e, Error::InvalidOperation(_)), "{e}");
        m.finish_captures().unwrap();
        assert!(!path.exists(), "nothing written for a mono surface");
    }
    surface::make_current(None).unwrap();

    let s = stereo_surface(BackendKind::Egl, W, H);
    let (left, right) = eyes();
    show(&s, &left, &right);
    // Quality out of range: refused, nothing changes.
    for q in [0, 101, 1000] {
        let e = s.set_jpeg_quality(q).unwrap_err();
        assert!(matches!(e, Error::InvalidValue(_)), "{e}");
        assert!(e.to_string().contains("1 (smallest file) to 100"), "{e}");
    }
    assert_eq!(s.jpeg_quality(), 90);
    // A directory that does not exist.
    let e = s
        .save_stereo_photo(StereoPhotoFormat::Mpo, Path::new("/nonexistent-dir/a.mpo"))
        .unwrap_err();
    assert!(matches!(e, Error::Io(_)), "{e}");
    assert!(e.to_string().contains("/nonexistent-dir/a.mpo"), "{e}");
    // The rename fails (the name is a non-empty directory): the encoded
    // file was written under a temporary name, which must be gone.
    let blocked = dir.join("blocked.jps");
    std::fs::create_dir_all(blocked.join("inside")).unwrap();
    let e = s
        .save_stereo_photo(StereoPhotoFormat::Jps, &blocked)
        .unwrap_err();
    assert!(matches!(e, Error::Io(_)), "{e}");
    let left_over: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        left_over,
        vec!["blocked.jps".to_owned()],
        "no temporary file"
    );
    surface::make_current(None).unwrap();
}

#[test]
fn the_c_calls_return_their_documented_codes() {
    let dir = common::scratch("stereo-photos-c");
    // SAFETY: valid out-pointers and attribute lists; handles from these calls.
    unsafe {
        let mut d = std::ptr::null_mut();
        assert_eq!(gls_display_open(GLS_BACKEND_EGL, &mut d), GLS_OK);
        let open = |stereo: bool| {
            // GLX_RGBA, GLX_DOUBLEBUFFER, (GLX_STEREO,) None
            let attribs: &[i32] = if stereo { &[4, 5, 6, 0] } else { &[4, 5, 0] };
            let mut c = std::ptr::null_mut();
            assert_eq!(gls_config_choose(d, attribs.as_ptr(), &mut c), GLS_OK);
            let mut s = std::ptr::null_mut();
            assert_eq!(gls_surface_create(d, c, 8, 6, &mut s), GLS_OK);
            gls_config_free(c);
            s
        };
        let s = open(true);
        let mono = open(false);
        let path = |n: &str| CString::new(dir.join(n).to_str().unwrap()).unwrap();

        assert_eq!(gls_surface_set_jpeg_quality(s, 75), GLS_OK);
        for q in [0, 101] {
            assert_eq!(gls_surface_set_jpeg_quality(s, q), GLS_ERROR_INVALID_VALUE);
            assert!(
                last_error().contains("1 (smallest file) to 100"),
                "{}",
                last_error()
            );
        }
        assert_eq!(
            gls_surface_set_jpeg_quality(std::ptr::null_mut(), 90),
            GLS_ERROR_NULL_POINTER
        );
        let a = path("a.mpo");
        assert_eq!(
            gls_surface_save_stereo_photo(s, GLS_PHOTO_MPO, a.as_ptr()),
            GLS_OK
        );
        assert!(dir.join("a.mpo").is_file());
        let b = path("b.jps");
        assert_eq!(
            gls_surface_queue_stereo_photo(s, GLS_PHOTO_JPS, b.as_ptr()),
            GLS_OK
        );
        assert_eq!(gls_surface_wait_captures(s), GLS_OK);
        assert!(dir.join("b.jps").is_file());
        for f in [
            gls_surface_save_stereo_photo,
            gls_surface_queue_stereo_photo,
        ] {
            assert_eq!(f(s, 7, a.as_ptr()), GLS_ERROR_INVALID_ENUM);
            assert!(last_error().contains("GLS_PHOTO_MPO"), "{}", last_error());
            assert_eq!(
                f(s, GLS_PHOTO_MPO, std::ptr::null()),
                GLS_ERROR_NULL_POINTER
            );
            assert_eq!(
                f(std::ptr::null_mut(), GLS_PHOTO_MPO, a.as_ptr()),
                GLS_ERROR_NULL_POINTER
            );
            let m = path("mono.mpo");
            assert_eq!(
                f(mono, GLS_PHOTO_MPO, m.as_ptr()),
                GLS_ERROR_INVALID_OPERATION
            );
            assert!(last_error().contains("mono"), "{}", last_error());
        }
        let bad = CString::new("/nonexistent-dir/c.mpo").unwrap();
        assert_eq!(
            gls_surface_save_stereo_photo(s, GLS_PHOTO_MPO, bad.as_ptr()),
            GLS_ERROR_IO
        );
        assert!(
            last_error().contains("/nonexistent-dir/c.mpo"),
            "{}",
            last_error()
        );
        assert!(!dir.join("mono.mpo").exists());

        gls_surface_destroy(mono);
        gls_surface_destroy(s);
        assert_eq!(
            gls_surface_save_stereo_photo(s, GLS_PHOTO_MPO, a.as_ptr()),
            GLS_ERROR_INVALID_HANDLE
        );
        gls_display_close(d);
    }
}

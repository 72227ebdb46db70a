//! Queued PNG captures (`Surface::queue_png`, `gls_surface_queue_png`):
//! the files hold what a synchronous capture writes, in the order queued,
//! and failures are reported with the documented codes.

mod common;
#[path = "common/gl_surface.rs"]
mod gl_surface;

use std::ffi::CString;

use glstereo::backend::BackendKind;
use glstereo::capture::read_png;
use glstereo::ffi::capture::{gls_surface_queue_png, gls_surface_wait_captures};
use glstereo::ffi::display::{
    GLS_BACKEND_EGL, gls_config_choose, gls_config_free, gls_display_close, gls_display_open,
};
use glstereo::ffi::surface::{
    GLS_IMAGE_COMPOSITE, GLS_IMAGE_LEFT, GLS_IMAGE_RIGHT, gls_surface_create, gls_surface_destroy,
};
use glstereo::ffi::types::*;
use glstereo::output::pattern::{gradient, noise};
use glstereo::surface::{self, CaptureImage};

use common::last_error;
use gl_surface::{show, stereo_surface};

#[test]
fn queued_and_saved_captures_hold_the_eyes_and_composite_in_order() {
    let dir = common::scratch("queued-captures");
    let s = stereo_surface(BackendKind::Egl, 37, 21);
    surface::make_current(Some(&s)).unwrap();
    let mut shown = Vec::new();
    for frame in 0..3u8 {
        show(
            &s,
            &noise(37, 21, u64::from(frame)),
            &gradient(37, 21, frame),
        );
        // What a viewer sees, by the independent read-back paths.
        let (left, right) = s.eye_images().unwrap();
        shown.push([left, right, s.composite_image().unwrap()]);
        for (which, name) in [
            (CaptureImage::Left, "left"),
            (CaptureImage::Right, "right"),
            (CaptureImage::Composite, "composite"),
        ] {
            s.queue_png(which, &dir.join(format!("{name}-{frame}.png")))
                .unwrap();
            // The same name every frame: the last frame's image must win.
            s.queue_png(which, &dir.join(format!("{name}-last.png")))
                .unwrap();
            s.save_png(which, &dir.join(format!("{name}-sync-{frame}.png")))
                .unwrap();
        }
    }
    s.finish_captures().unwrap();
    for (i, name) in ["left", "right", "composite"].into_iter().enumerate() {
        for (frame, images) in shown.iter().enumerate() {
            for file in [
                format!("{name}-{frame}.png"),
                format!("{name}-sync-{frame}.png"),
            ] {
                assert_eq!(read_png(&dir.join(&file)).unwrap(), images[i], "{file}");
            }
        }
        assert_eq!(
            read_png(&dir.join(format!("{name}-last.png"))).unwrap(),
            shown[2][i],
            "{name}: the last queued capture of a path wins"
        );
    }
    surface::make_current(None).unwrap();
}

#[test]
fn the_c_calls_queue_wait_and_report_errors_with_their_codes() {
    let dir = common::scratch("queued-captures-c");
    // SAFETY: valid out-pointers and attribute lists; handles from these calls.
    unsafe {
        let mut d = std::ptr::null_mut();
        assert_eq!(gls_display_open(GLS_BACKEND_EGL, &mut d), GLS_OK);
        let attribs = [4, 5, 6, 0]; // GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, None
        let mut c = std::ptr::null_mut();
        assert_eq!(gls_config_choose(d, attribs.as_ptr(), &mut c), GLS_OK);
        let mut s = std::ptr::null_mut();
        assert_eq!(gls_surface_create(d, c, 8, 6, &mut s), GLS_OK);

        let good = CString::new(dir.join("a.png").to_str().unwrap()).unwrap();
        assert_eq!(
            gls_surface_queue_png(s, GLS_IMAGE_LEFT, good.as_ptr()),
            GLS_OK
        );
        assert_eq!(
            gls_surface_queue_png(s, GLS_IMAGE_RIGHT, std::ptr::null()),
            GLS_ERROR_NULL_POINTER
        );
        assert_eq!(
            gls_surface_queue_png(s, 7, good.as_ptr()),
            GLS_ERROR_INVALID_ENUM
        );
        assert!(last_error().contains("GLS_IMAGE_LEFT"), "{}", last_error());
        assert_eq!(
            gls_surface_queue_png(std::ptr::null_mut(), GLS_IMAGE_LEFT, good.as_ptr()),
            GLS_ERROR_NULL_POINTER
        );
        assert_eq!(gls_surface_wait_captures(s), GLS_OK);
        assert_eq!(read_png(&dir.join("a.png")).unwrap().width(), 8);

        let bad = CString::new("/nonexistent-dir/b.png").unwrap();
        let queued = gls_surface_queue_png(s, GLS_IMAGE_COMPOSITE, bad.as_ptr());
        // The failure surfaces in whichever call follows the write.
        let rc = if queued == GLS_OK {
            gls_surface_wait_captures(s)
        } else {
            queued
        };
        assert_eq!(rc, GLS_ERROR_IO);
        assert!(
            last_error().contains("/nonexistent-dir/b.png"),
            "{}",
            last_error()
        );
        assert_eq!(gls_surface_wait_captures(s), GLS_OK, "reported once");

        gls_surface_destroy(s);
        assert_eq!(gls_surface_wait_captures(s), GLS_ERROR_INVALID_HANDLE);
        gls_config_free(c);
        gls_display_close(d);
    }
}

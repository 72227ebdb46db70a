//! Automatic convergence: where automatic stereo puts the screen when the
//! user has not (`GLSTEREO_CONVERGENCE=auto`, the default). Every
//! [`PERIOD`] frames the layer reads the left eye's depth in the central
//! window of the program's viewport (the window's eyes when the frame drew
//! into them, else the stereoized render target it drew into last: a
//! program that draws its scene off screen and blits it or shows it as a
//! texture) ([`CONVERGENCE_WINDOW`]: the middle
//! half of its width and height), maps it back to distance with the
//! perspective projection the frame was drawn with, and converges at the
//! median: the centre of interest, as `gls_stereo_auto_converge` computes
//! it for programs that ask ([`crate::analysis::centre_of_interest`]).
//! What the viewer looks at then sits at the screen, nearer things come
//! out of it and farther ones go behind it.
//!
//! The projection: the fixed-function GL_PROJECTION_MATRIX in effect at
//! the present when it is a perspective one, else the last perspective
//! matrix the program uploaded with glUniformMatrix4fv or
//! glProgramUniformMatrix4fv ([`Perspective::from_upload`]). Before either
//! is known, or when no pixel of the window holds geometry, the
//! convergence stays where it was (0 at first: NV_3dvision_settings'
//! initial value, the whole picture behind the screen).

use crate::analysis::depth::{DepthCapture, DepthImage, DepthMapping};
use crate::analysis::parallax::CONVERGENCE_WINDOW;
use crate::auto::eyes::{Attachments, LayeredEyes};
use crate::gl::Gl;
use crate::interpose::live;
use crate::math::frustum::Frustum;

/// Frames between two measurements (the first at the first present).
pub const PERIOD: u64 = 30;

/// What the program's context says of a frame at its present
/// ([`crate::auto::runtime::frame_geometry`]).
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// The projection the frame was drawn with.
    pub perspective: Perspective,
    /// The program's viewport.
    pub viewport: (i32, i32, i32, i32),
    /// glDepthRange.
    pub depth_range: (f64, f64),
    /// glClearDepth.
    pub clear_depth: f64,
    /// Something was drawn into the window's eyes.
    pub window: bool,
    /// The stereoized render target drawn into last (its arrays and
    /// size): measured when the window's eyes were not drawn or hold no
    /// geometry where the viewer looks (a program that draws off screen
    /// and blits, or shows its scene as a textured quad without depth).
    pub target: Option<(Attachments, (u32, u32))>,
}

/// Measures `frame` in `eyes` (the layered eyes of an automatic-stereo
/// framebuffer) through `fbo`, a framebuffer object of the current
/// context (the layer's own, sharing the program's objects), and publishes
/// the convergence it finds ([`crate::interpose::live`]); stderr says
/// it under `--verbose`.
///
/// # Safety
/// A context sharing the eyes' objects is current on this thread.
pub unsafe fn measure(gl: &Gl, eyes: &LayeredEyes, fbo: u32, frame: &Frame, scratch: &mut Scratch) {
    let window = frame.window.then(|| (None, (eyes.width(), eyes.height())));
    let target = frame.target.map(|(t, size)| (Some(t), size));
    // SAFETY: contract.
    let Some(c) = window
        .into_iter()
        .chain(target)
        .find_map(|(source, size)| unsafe {
            centre_of(gl, eyes, fbo, frame, source, size, scratch)
        })
    else {
        return;
    };
    let before = live::automatic_convergence();
    live::set_automatic_convergence(c as f32);
    if before.is_none_or(|b| (b - c as f32).abs() > 0.01 * b.abs()) {
        crate::interpose::settings::tell(&format!(
            "automatic convergence at {c:.3} (the centre of interest; Ctrl+F5/F6 set it by hand)"
        ));
    }
}

/// The convergence [`centre`] finds in the left eye's depth of the
/// window's eyes (`source` None) or of a render target, `size` pixels.
///
/// # Safety
/// As [`measure`].
unsafe fn centre_of(
    gl: &Gl,
    eyes: &LayeredEyes,
    fbo: u32,
    frame: &Frame,
    source: Option<Attachments>,
    (width, height): (u32, u32),
    scratch: &mut Scratch,
) -> Option<f64> {
    let (x, y, w, h) = window(frame.viewport);
    let (x0, y0) = (x.max(0), y.max(0));
    let (x1, y1) = ((x + w).min(width as i32), (y + h).min(height as i32));
    if x1 <= x0 || y1 <= y0 {
        return None;
    }
    let rect = (x0, y0, x1 - x0, y1 - y0);
    // SAFETY: contract; the rectangle is inside what is read.
    let read = unsafe {
        match source {
            Some(target) => target.read_left_depth(gl, fbo, rect, &mut scratch.depth),
            None => eyes.read_left_depth(gl, fbo, rect, &mut scratch.depth),
        }
    };
    if !read {
        return None;
    }
    centre(
        scratch,
        (rect.2 as u32, rect.3 as u32),
        &frame.perspective,
        frame.depth_range,
        frame.clear_depth,
    )
}

/// The depth terms of a perspective projection: clip z = `a`·z_eye + `b`,
/// clip w = −z_eye (row 3 of the matrix is (0, 0, −1, 0)), so a window
/// depth maps back to the eye distance w.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perspective {
    a: f64,
    b: f64,
}

impl Perspective {
    /// From a column-major 4x4 matrix (as glGetDoublev and a
    /// non-transposed glUniformMatrix4fv give it); None when it is not a
    /// perspective projection with a near and a far plane in front of the
    /// eye.
    pub fn from_matrix(m: &[f64; 16]) -> Option<Perspective> {
        let row3 = [m[3], m[7], m[11], m[15]];
        Perspective::checked(row3, m[10], m[14])
    }

    /// From `count` matrices of 16 floats at `value`, uploaded with
    /// `transpose` (row-major when true): the last perspective one.
    pub fn from_upload(value: &[f32], transpose: bool) -> Option<Perspective> {
        value.chunks_exact(16).rev().find_map(|m| {
            let m: Vec<f64> = m.iter().map(|&v| f64::from(v)).collect();
            if transpose {
                Perspective::checked([m[12], m[13], m[14], m[15]], m[10], m[11])
            } else {
                Perspective::checked([m[3], m[7], m[11], m[15]], m[10], m[14])
            }
        })
    }

    fn checked(row3: [f64; 4], a: f64, b: f64) -> Option<Perspective> {
        let p = Perspective { a, b };
        (row3 == [0.0, 0.0, -1.0, 0.0] && p.frustum().is_some()).then_some(p)
    }

    /// The near and far distances (a frustum whose sides do not matter
    /// here): near = b / (a − 1), far = b / (a + 1).
    fn frustum(&self) -> Option<Frustum> {
        let (near, far) = (self.b / (self.a - 1.0), self.b / (self.a + 1.0));
        (near.is_finite() && far.is_finite() && near > 0.0 && far > near).then_some(Frustum {
            left: -near,
            right: near,
            bottom: -near,
            top: near,
            near,
            far,
        })
    }
}

/// The part of a viewport `(x, y, width, height)` whose depth is read:
/// the central window, at least one pixel each way.
pub fn window((x, y, w, h): (i32, i32, i32, i32)) -> (i32, i32, i32, i32) {
    let (lo, hi) = CONVERGENCE_WINDOW;
    let span = |origin: i32, size: i32| {
        let a = (size as f64 * lo).floor() as i32;
        let b = ((size as f64 * hi).ceil() as i32).max(a + 1);
        (origin + a, b - a)
    };
    let (wx, ww) = span(x, w);
    let (wy, wh) = span(y, h);
    (wx, wy, ww, wh)
}

/// The buffers of a measurement, kept by the context from one to the next
/// (a measured frame allocates nothing once they have grown).
#[derive(Debug, Default)]
pub struct Scratch {
    /// Window depths read back.
    pub depth: Vec<f32>,
    /// Their distances.
    distances: Vec<f64>,
}

/// The convergence for a frame: the median eye distance of the pixels of
/// `scratch.depth` (`width` × `height` window depths, the central window)
/// that hold geometry (not at `clear_depth`), drawn with `perspective` and
/// glDepthRange `depth_range`. None when none does.
pub fn centre(
    scratch: &mut Scratch,
    (width, height): (u32, u32),
    perspective: &Perspective,
    depth_range: (f64, f64),
    clear_depth: f64,
) -> Option<f64> {
    let frustum = perspective.frustum()?;
    let mapping = DepthMapping::new(&frustum, depth_range).ok()?;
    let depth = std::mem::take(&mut scratch.depth);
    let mut capture = DepthCapture::new(DepthImage::new(width, height, depth).ok()?);
    capture.depth_range = depth_range;
    capture.clear_depth = clear_depth;
    let d = &mut scratch.distances;
    d.clear();
    capture.for_each_covered(0.0, 1.0, |z| d.push(mapping.distance(f64::from(z))));
    scratch.depth = capture.depth.into_values();
    if d.is_empty() {
        return None;
    }
    let mid = d.len() / 2;
    let (_, median, _) = d.select_nth_unstable_by(mid, f64::total_cmp);
    Some(*median)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DMat4;

    fn glu_perspective(near: f64, far: f64) -> [f64; 16] {
        DMat4::perspective_rh_gl(1.0, 4.0 / 3.0, near, far).to_cols_array()
    }

    #[test]
    fn the_near_and_far_planes_come_back_from_the_matrix() {
        let p = Perspective::from_matrix(&glu_perspective(0.5, 40.0)).unwrap();
        let f = p.frustum().unwrap();
        assert!(
            (f.near - 0.5).abs() < 1e-9 && (f.far - 40.0).abs() < 1e-9,
            "{f:?}"
        );
        let ortho = DMat4::orthographic_rh_gl(-1.0, 1.0, -1.0, 1.0, 0.1, 10.0).to_cols_array();
        assert_eq!(Perspective::from_matrix(&ortho), None);
        assert_eq!(
            Perspective::from_matrix(&DMat4::IDENTITY.to_cols_array()),
            None
        );
    }

    #[test]
    fn an_upload_gives_its_last_perspective_matrix_either_way_round() {
        let m = glu_perspective(1.0, 100.0);
        let f: Vec<f32> = m.iter().map(|&v| v as f32).collect();
        let t: Vec<f32> = DMat4::from_cols_array(&m)
            .transpose()
            .to_cols_array()
            .iter()
            .map(|&v| v as f32)
            .collect();
        let want = Perspective::from_matrix(&m).unwrap();
        for (value, transpose) in [(&f, false), (&t, true)] {
            let got = Perspective::from_upload(value, transpose).unwrap();
            assert!((got.a - want.a).abs() < 1e-5 && (got.b - want.b).abs() < 1e-5);
        }
        // A model-view matrix after the projection: the projection still.
        let mut two = f.clone();
        two.extend(DMat4::IDENTITY.to_cols_array().iter().map(|&v| v as f32));
        assert!(Perspective::from_upload(&two, false).is_some());
        assert_eq!(Perspective::from_upload(&f[..12], false), None);
    }

    #[test]
    fn the_centre_is_the_median_distance_of_what_was_drawn() {
        let m = glu_perspective(1.0, 100.0);
        let p = Perspective::from_matrix(&m).unwrap();
        // Window depth of a point at distance w: ndc = -a + b / w.
        let depth = |w: f64| ((-p.a + p.b / w) * 0.5 + 0.5) as f32;
        // 10 pixels at 5, 6 at 20, 4 cleared (1.0).
        let mut v = vec![depth(5.0); 10];
        v.extend([depth(20.0); 6]);
        v.extend([1.0; 4]);
        let mut scratch = Scratch {
            depth: v,
            ..Default::default()
        };
        let c = centre(&mut scratch, (5, 4), &p, (0.0, 1.0), 1.0).unwrap();
        assert!((c - 5.0).abs() < 1e-3, "{c}");
        // The buffers are kept for the next measurement.
        assert_eq!(scratch.depth.len(), 20);
        assert!(scratch.distances.capacity() >= 16);
        scratch.depth = vec![1.0; 20];
        assert_eq!(centre(&mut scratch, (5, 4), &p, (0.0, 1.0), 1.0), None);
    }

    #[test]
    fn the_window_is_the_middle_half_of_the_viewport() {
        assert_eq!(window((0, 0, 400, 300)), (100, 75, 200, 150));
        assert_eq!(window((10, 20, 1, 1)), (10, 20, 1, 1));
    }
}

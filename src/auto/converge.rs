//! Automatic convergence: where automatic stereo puts the screen when the
//! user has not (`GLSTEREO_CONVERGENCE=auto`, the default). Every
//! [`PERIOD`] frames and at least every [`INTERVAL`] (every one of the
//! first [`EAGER`] until one finds the scene: [`measures`], [`due`])
//! the layer reads the left eye's depth in the central
//! window of the program's viewport (the window's eyes when the frame drew
//! into them, else the stereoized render target it drew into last: a
//! program that draws its scene off screen and blits it or shows it as a
//! texture) ([`CONVERGENCE_WINDOW`]: the middle
//! half of its width and height), maps it back to distance with the
//! perspective projection the frame was drawn with, and converges at the
//! median: the centre of interest, as `gls_stereo_auto_converge` computes
//! it for programs that ask ([`crate::analysis::centre_of_interest`]).
//! The left eye is the program's view moved by the rule, each depth by
//! its own amount: what it shows in the central window depends on the
//! convergence it was drawn with, so a measurement that took the eye's
//! pixels as they lie would find another centre at every convergence
//! (objects near the window's edges come in or go out) and the next
//! measurement would move it again. Each pixel is put back where the
//! program's own view has it (moved by the rule's −e·s·(1 − C/w) for its
//! distance w) and counted when that is inside the window: the centre is
//! the program's, whatever the convergence.
//! What the viewer looks at then sits at the screen, nearer things come
//! out of it and farther ones go behind it.
//!
//! The projection: the fixed-function GL_PROJECTION_MATRIX in effect at
//! the present when it is a perspective one, else the last perspective
//! matrix the program uploaded with glUniformMatrix4fv or
//! glProgramUniformMatrix4fv before a draw into what is measured — a
//! projection alone or the combined model-view-projection matrix of an
//! object ([`Perspective::from_upload`]: only the depth terms matter, and
//! every product of a camera's projection has the same). Before either
//! is known, or when no pixel of the window holds geometry, the
//! convergence stays where it was (0 at first: NV_3dvision_settings'
//! initial value, the whole picture behind the screen).

use crate::analysis::depth::{DEPTH_STEP_24, DepthMapping};
use crate::analysis::parallax::CONVERGENCE_WINDOW;
use crate::auto::eyes::{Attachments, LayeredEyes};
use crate::auto::live;
use crate::gl::Gl;
use crate::math::frustum::Frustum;

/// Frames between two measurements (the first at the first present).
pub const PERIOD: u64 = 30;

/// Frames at the start that are all measured until one finds the scene.
pub const EAGER: u64 = 2 * PERIOD;

/// The longest a program presenting slowly goes between two
/// measurements ([`due`]).
pub const INTERVAL: std::time::Duration = std::time::Duration::from_secs(1);

/// Whether frame `frame` (counted from 0) is measured: every
/// [`PERIOD`]th, and each of the first [`EAGER`] until a measurement
/// found the scene (a program that presents a few frames and then only
/// on events — Blender, a viewer waiting for input — may draw its scene
/// after the first; one whose depth never holds its scene, a 2D game, is
/// not read every frame for ever). Other frames are measured when they
/// are [`due`].
pub fn measures(frame: u64) -> bool {
    frame % PERIOD == 0
        || (frame < EAGER
            && live::automatic_convergence().is_none()
            && live::automatic_depth().is_none())
}

/// Whether a frame whose first draw comes `since` after the last measured
/// frame's present is measured whatever its number: a program that
/// presents on events (Blender, a viewer waiting for input) draws 30
/// frames over a minute and changes its view between two far apart; the
/// first frame of a new view is measured then, as it is drawn. (What it
/// finds shows from the next frame: a program that then stops drawing
/// keeps the convergence before until it draws again, and one that
/// accumulates samples of a still view over its next frames — Blender's
/// viewport anti-aliasing — blends its first sample, at the convergence
/// before, into the picture.)
pub fn due(since: std::time::Duration) -> bool {
    since >= INTERVAL
}

/// What the program's context says of a frame at its present
/// ([`crate::auto::runtime::frame_geometry`]).
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// glClipControl's depth mode is GL_ZERO_TO_ONE (NDC depth 0…1).
    pub zero_to_one: bool,
    /// glDepthRange.
    pub depth_range: (f64, f64),
    /// glClearDepth.
    pub clear_depth: f64,
    /// The scene was drawn into the window's eyes; with the 2D texture
    /// its left eye's depth was copied into when a later draw of the
    /// frame may have overwritten it.
    pub window: Option<(Scene, Option<u32>)>,
    /// The render target with eyes and depth a perspective draw reached
    /// last (its arrays and size, the draw's projection and viewport):
    /// measured when the window's eyes hold no geometry where the viewer
    /// looks (a program that draws its scene off screen and blits it or
    /// shows it as a textured quad).
    pub target: Option<(Attachments, (u32, u32), Scene)>,
    /// The median distance of the origins of the objects the frame's
    /// perspective draws placed (their combined model-view-projection
    /// matrices' clip w of (0, 0, 0)): the centre of interest where the
    /// depth holds no scene (translucent geometry drawn without depth
    /// writes: glmark2's jellyfish, its buffer grid).
    pub origin: Option<f64>,
    /// The left eye's e·s (signed: the rule moves its NDC x by
    /// `left_shift`·(1 − C/w)).
    pub left_shift: f64,
    /// Automatic convergence measures this frame ([`measure`]); a frame
    /// whose eyes are made from its depth is recorded without it.
    pub converges: bool,
    /// `--auto=depth`: flat draws came into the window after its scene,
    /// whose colour then is in the right eye's layer
    /// ([`crate::auto::from_depth`]).
    pub overlays: bool,
    /// `--auto=depth`: draws that are not the scene's came into the
    /// scene's render target after it; layer 1 of this colour array
    /// holds the target's colour from before them
    /// ([`crate::auto::render_targets::SceneTarget::colour_kept`]).
    pub target_overlays: Option<u32>,
    /// `--auto=depth`: a perspective draw of the frame wrote depth (the
    /// depth test on, depth writes on). Where none did, the depth holds no
    /// scene (what it holds is a clear, or undefined), and no eye can be
    /// made from it.
    pub depth_written: bool,
    /// `--auto=depth`: perspective draws with the depth test off wrote
    /// their depth into the window's depth array's second layer
    /// ([`crate::auto::from_depth`] takes the nearer of the two).
    pub depth_beside: bool,
}

/// How a frame's scene was drawn where automatic convergence measures it.
#[derive(Clone, Copy, Debug)]
pub struct Scene {
    /// Its projection (None: one automatic stereo cannot see).
    pub perspective: Option<Perspective>,
    /// The viewport it was drawn in.
    pub viewport: Viewport,
}

/// A viewport: x, y, width, height.
pub type Viewport = (i32, i32, i32, i32);

/// Measures `frame` in `eyes` (the layered eyes of an automatic-stereo
/// framebuffer) through `fbo`, a framebuffer object of the current
/// context (the layer's own, sharing the program's objects), and publishes
/// the convergence it finds ([`crate::interpose::live`]); stderr says
/// it under `--verbose`.
///
/// # Safety
/// A context sharing the eyes' objects is current on this thread.
pub unsafe fn measure(gl: &Gl, eyes: &LayeredEyes, fbo: u32, frame: &Frame, scratch: &mut Scratch) {
    let window = frame.window.map(|(scene, copy)| {
        let source = copy.map(|c| eyes.attachments().with_depth_copy(c));
        (source, (eyes.width(), eyes.height()), scene)
    });
    let target = frame.target.map(|(t, size, scene)| (Some(t), size, scene));
    // A scene whose projection is known comes first: the window's eyes
    // may hold only a pass whose projection cannot be seen (a full-screen
    // quad of a program that uploads no matrix, composing a render target
    // the scene went into: glmark2's terrain), whose flat depth is not the
    // scene's; the window before the target otherwise.
    let mut places: Vec<_> = window.into_iter().chain(target).collect();
    places.sort_by_key(|(_, _, scene)| scene.perspective.is_none());
    // SAFETY: contract.
    let Some(found) = places
        .into_iter()
        .find_map(|(source, size, scene)| unsafe {
            centre_of(gl, eyes, fbo, frame, (source, &scene), size, scratch)
        })
        .or(frame.origin.map(Centre::Distance))
    else {
        return;
    };
    match found {
        Centre::Distance(c) => {
            let before = live::automatic_convergence();
            live::set_automatic_convergence(c as f32);
            if before.is_none_or(|b| (b - c as f32).abs() > 0.01 * b.abs()) {
                crate::report::tell(&format!(
                    "automatic convergence at {c:.3} (the centre of interest; Ctrl+F5/F6 set \
                     it by hand)"
                ));
            }
        }
        Centre::Depth(z) => {
            // The depth offset α of clip z = α·w + β, for far ≫ near: 1
            // for GL's perspective ((f + n) / (f − n)) and for one into
            // GL_ZERO_TO_ONE (f / (f − n)); reversed depth (cleared to 0):
            // 0 into GL_ZERO_TO_ONE, −1 into GL's −1…1.
            let alpha = match (frame.zero_to_one, frame.clear_depth < 0.5) {
                (_, false) => 1.0,
                (true, true) => 0.0,
                (false, true) => -1.0,
            };
            let before = live::automatic_depth();
            live::set_automatic_depth(z as f32, alpha);
            if before.is_none_or(|(b, _)| (b - z as f32).abs() > 1e-4) {
                crate::report::tell(&format!(
                    "automatic convergence at depth {z:.5} (NDC; the centre of interest of a \
                     projection glstereo cannot see; Ctrl+F5/F6 set it by hand)"
                ));
            }
        }
    }
}

/// What a measurement found: the centre of interest's distance (the clip
/// w at the screen), or, where the projection is not known, its NDC
/// depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Centre {
    /// The distance C.
    Distance(f64),
    /// The NDC depth z_c.
    Depth(f64),
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
    (source, scene): (Option<Attachments>, &Scene),
    (width, height): (u32, u32),
    scratch: &mut Scratch,
) -> Option<Centre> {
    let (x, y, w, h) = window(scene.viewport);
    let (vx, _, vw, _) = scene.viewport;
    // How the frame's left eye was moved from the program's view: its
    // pixels are put back ([`Seen`]) where the rule it was drawn with can
    // be undone from what the depth says (a projection not known, drawn
    // at a convergence chosen as a distance: as they lie, in the window).
    let rule = match (
        &scene.perspective,
        live::automatic_convergence(),
        live::automatic_depth(),
    ) {
        (Some(p), c, z) => Some(Rule::Distance(
            c.map(f64::from)
                .or_else(|| z.and_then(|(z, _)| p.distance_at(z.into())))
                .unwrap_or(0.0),
        )),
        (None, Some(_), _) => None,
        (None, None, Some((z, alpha))) => Some(Rule::Depth {
            zc: z.into(),
            alpha: alpha.into(),
        }),
        (None, None, None) => Some(Rule::Distance(0.0)),
    };
    // The whole width of the window's rows where pixels are put back.
    let (x, w) = if rule.is_some() { (vx, vw) } else { (x, w) };
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
    let size = (rect.2 as u32, rect.3 as u32);
    let (wx, _, ww, _) = window(scene.viewport);
    let seen = Seen {
        left_shift: frame.left_shift,
        rule,
        pixels_per_ndc: f64::from(vw) / 2.0,
        window: (f64::from(wx - x0), f64::from(wx + ww - x0)),
    };
    match &scene.perspective {
        Some(p) => centre(
            scratch,
            size,
            p,
            frame.depth_range,
            frame.clear_depth,
            &seen,
        )
        .map(Centre::Distance),
        None => centre_depth(scratch, size, frame, &seen).map(Centre::Depth),
    }
}

/// Calls `f(column, window depth)` for every pixel of `depth` (`width` ×
/// `height` window depths, rows bottom first) that holds geometry (not
/// within one D24 step of `clear_depth`); None when `depth` is smaller
/// than that.
fn covered(
    depth: &[f32],
    (width, height): (u32, u32),
    clear_depth: f64,
    mut f: impl FnMut(usize, f64),
) -> Option<()> {
    let width = width as usize;
    if width == 0 || depth.len() < width * height as usize {
        return None;
    }
    for row in depth.chunks_exact(width).take(height as usize) {
        for (x, &z) in row.iter().enumerate() {
            let z = f64::from(z);
            if (z - clear_depth).abs() > DEPTH_STEP_24 {
                f(x, z);
            }
        }
    }
    Some(())
}

/// The NDC depth of the median of the pixels of `scratch.depth` that
/// hold geometry (not at the frame's clear depth) and lie in the central
/// window in the program's view (`seen`), for a projection that is not
/// known: the same pixel [`centre`] finds, as a depth.
fn centre_depth(
    scratch: &mut Scratch,
    (width, height): (u32, u32),
    frame: &Frame,
    seen: &Seen,
) -> Option<f64> {
    let (n, f) = frame.depth_range;
    let ndc = |d: f64| {
        let t = (d - n) / (f - n);
        if frame.zero_to_one { t } else { 2.0 * t - 1.0 }
    };
    let d = &mut scratch.distances;
    d.clear();
    covered(
        &scratch.depth,
        (width, height),
        frame.clear_depth,
        |x, z| {
            if seen.inside(x, None, ndc(z)) {
                d.push(z);
            }
        },
    )?;
    if d.is_empty() {
        return None;
    }
    let mid = d.len() / 2;
    let (_, median, _) = d.select_nth_unstable_by(mid, f64::total_cmp);
    Some(ndc(*median))
}

/// The depth terms of a perspective camera: clip z = −`a`·w + `b`, where
/// w is the clip w, so a window depth maps back to the distance w. A
/// projection alone has them (row 3 = (0, 0, −1, 0), w = −z_eye), and so
/// does any product of one with the matrices before it — the combined
/// model-view-projection matrix a shader program uploads per object: with
/// P·V·M, row 3 is −(row 2 of V·M) and row 2 is `a`·(row 2 of V·M) plus
/// `b` in w's column, so row 2 = −`a`·row 3 + (0, 0, 0, `b`) whatever
/// the model and view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perspective {
    a: f64,
    b: f64,
}

impl Perspective {
    /// From a column-major 4x4 matrix (as glGetDoublev and a
    /// non-transposed glUniformMatrix4fv give it); None when it is not a
    /// perspective camera with a near and a far plane in front of the eye.
    pub fn from_matrix(m: &[f64; 16]) -> Option<Perspective> {
        Perspective::of_rows([m[2], m[6], m[10], m[14]], [m[3], m[7], m[11], m[15]])
    }

    /// From `count` matrices of 16 floats at `value`, uploaded with
    /// `transpose` (row-major when true): the last perspective one
    /// (a projection, or a projection times the matrices before it).
    pub fn from_upload(value: &[f32], transpose: bool) -> Option<Perspective> {
        Perspective::from_upload_with_origin(value, transpose).map(|(p, _)| p)
    }

    /// [`Perspective::from_upload`], with the clip w of the point (0, 0, 0)
    /// the matrix takes: for a projection times the matrices before it,
    /// the distance of the model's origin (0 for a projection alone).
    pub fn from_upload_with_origin(value: &[f32], transpose: bool) -> Option<(Perspective, f64)> {
        value.chunks_exact(16).rev().find_map(|m| {
            let m: Vec<f64> = m.iter().map(|&v| f64::from(v)).collect();
            // Element (3, 3) is the 16th value either way round.
            let p = if transpose {
                Perspective::of_rows([m[8], m[9], m[10], m[11]], [m[12], m[13], m[14], m[15]])
            } else {
                Perspective::of_rows([m[2], m[6], m[10], m[14]], [m[3], m[7], m[11], m[15]])
            };
            p.map(|p| (p, m[15]))
        })
    }

    /// From rows 2 (z) and 3 (w) of a matrix: row 2's first three terms
    /// must be row 3's times one number (−`a`; within float rounding of
    /// an uploaded f32 product), and row 3's must not all be 0 (an
    /// orthographic or affine matrix: w is the same everywhere).
    fn of_rows(z: [f64; 4], w: [f64; 4]) -> Option<Perspective> {
        let dot = |p: &[f64; 4], q: &[f64; 4]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        let ww = dot(&w, &w);
        if ww.is_nan() || ww <= 0.0 || !ww.is_finite() {
            return None;
        }
        let alpha = dot(&z, &w) / ww;
        let off = (0..3).map(|i| (z[i] - alpha * w[i]).powi(2)).sum::<f64>();
        if off > 1e-9 * dot(&z, &z).max(ww) {
            return None;
        }
        let p = Perspective {
            a: -alpha,
            b: z[3] - alpha * w[3],
        };
        p.frustum().map(|_| p)
    }

    /// The depth terms (a, b): a point at NDC depth z is at clip w
    /// b / (z + a).
    pub fn terms(&self) -> (f64, f64) {
        (self.a, self.b)
    }

    /// The distance (clip w) of a point at NDC depth `z`: b / (z + a);
    /// None where that is not a distance in front of the eye.
    pub fn distance_at(&self, z: f64) -> Option<f64> {
        let w = self.b / (z + self.a);
        (w.is_finite() && w > 0.0).then_some(w)
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

/// The rule a frame's eye was drawn with, as far as a measurement
/// undoes it ([`Seen`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rule {
    /// At convergence C (a distance): NDC x moved by e·s·(1 − C/w).
    Distance(f64),
    /// At the NDC depth `zc` of a projection of depth offset `alpha`
    /// (where the projection is not known): NDC x moved by
    /// e·s·(zc − z)/(zc − alpha), z the pixel's NDC depth.
    Depth {
        /// The convergence's NDC depth.
        zc: f64,
        /// The projection's depth offset α.
        alpha: f64,
    },
}

/// How the left eye's pixels read for a measurement lie against the
/// program's own view ([`centre`], and `centre_depth` where the
/// projection is not known).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seen {
    /// [`Frame::left_shift`].
    pub left_shift: f64,
    /// The rule the eye was drawn with (None: one that cannot be undone;
    /// the pixels are taken as they lie).
    pub rule: Option<Rule>,
    /// Half the viewport's width: window pixels per NDC unit.
    pub pixels_per_ndc: f64,
    /// The central window's columns [from, to) in the pixels read.
    pub window: (f64, f64),
}

impl Seen {
    /// Whether a pixel of column `x` (its centre at x + ½) at distance
    /// `w` (where known) and NDC depth `z` lies in the window in the
    /// program's view.
    fn inside(&self, x: usize, w: Option<f64>, z: f64) -> bool {
        let ndc = match self.rule {
            None => 0.0,
            Some(Rule::Distance(0.0)) => 1.0,
            Some(Rule::Distance(c)) => w.map_or(0.0, |w| 1.0 - c / w),
            Some(Rule::Depth { zc, alpha }) => (zc - z) / (zc - alpha),
        };
        let at = x as f64 + 0.5 - self.left_shift * ndc * self.pixels_per_ndc;
        at >= self.window.0 && at < self.window.1
    }
}

/// The convergence for a frame: the median eye distance of the pixels of
/// `scratch.depth` (`width` × `height` window depths of the left eye: the
/// central window's rows) that hold geometry (not at `clear_depth`) and
/// lie in the central window in the program's own view (`seen`), drawn
/// with `perspective` and glDepthRange `depth_range`. None when none
/// does.
pub fn centre(
    scratch: &mut Scratch,
    (width, height): (u32, u32),
    perspective: &Perspective,
    (near, far): (f64, f64),
    clear_depth: f64,
    seen: &Seen,
) -> Option<f64> {
    let frustum = perspective.frustum()?;
    let mapping = DepthMapping::new(&frustum, (near, far)).ok()?;
    let d = &mut scratch.distances;
    d.clear();
    covered(&scratch.depth, (width, height), clear_depth, |x, z| {
        let w = mapping.distance(z);
        if w.is_finite() && w > 0.0 && seen.inside(x, Some(w), 0.0) {
            d.push(w);
        }
    })?;
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

    /// `m` as a program uploads it: f32, column-major and transposed.
    fn as_uploaded(m: DMat4) -> [Vec<f32>; 2] {
        [m, m.transpose()].map(|m| m.to_cols_array().iter().map(|&v| v as f32).collect())
    }

    #[test]
    fn an_upload_gives_the_distance_of_its_models_origin() {
        let proj = DMat4::perspective_rh_gl(0.9, 4.0 / 3.0, 0.5, 100.0);
        let eye = glam::DVec3::new(3.0, 2.0, 9.0);
        let view = DMat4::look_at_rh(eye, glam::DVec3::ZERO, glam::DVec3::Y);
        let at = glam::DVec3::new(1.0, -2.0, 0.5);
        let model = DMat4::from_translation(at) * DMat4::from_rotation_y(0.7);
        // The distance of the model's origin along the view direction.
        let want = -(view.transform_point3(at)).z;
        let [f, t] = as_uploaded(proj * view * model);
        for (value, transpose) in [(&f, false), (&t, true)] {
            let (_, w) = Perspective::from_upload_with_origin(value, transpose).unwrap();
            assert!((w - want).abs() < 1e-4 * want, "{w} against {want}");
        }
        // A projection alone places nothing.
        let p: Vec<f32> = proj.to_cols_array().iter().map(|&v| v as f32).collect();
        assert_eq!(
            Perspective::from_upload_with_origin(&p, false).unwrap().1,
            0.0
        );
    }

    #[test]
    fn a_model_view_projection_gives_its_cameras_depth_terms() {
        let proj = DMat4::perspective_rh_gl(0.9, 16.0 / 9.0, 0.25, 60.0);
        let want = Perspective::from_matrix(&proj.to_cols_array()).unwrap();
        let view = DMat4::look_at_rh(
            glam::DVec3::new(3.0, 2.0, 9.0),
            glam::DVec3::ZERO,
            glam::DVec3::Y,
        );
        let models = [
            DMat4::IDENTITY,
            DMat4::from_rotation_y(1.1) * DMat4::from_translation(glam::DVec3::new(1.0, -2.0, 0.5)),
            DMat4::from_scale(glam::DVec3::new(2.0, 0.5, 3.0)) * DMat4::from_rotation_x(-0.4),
        ];
        for model in models {
            let mvp = proj * view * model;
            let m = mvp.to_cols_array();
            let got = Perspective::from_matrix(&m).unwrap();
            assert!((got.a - want.a).abs() < 1e-9 && (got.b - want.b).abs() < 1e-9);
            let [f, t] = as_uploaded(mvp);
            for (value, transpose) in [(&f, false), (&t, true)] {
                let got = Perspective::from_upload(value, transpose).unwrap();
                assert!(
                    (got.a - want.a).abs() < 1e-4 * want.a.abs(),
                    "{got:?} {want:?}"
                );
                assert!(
                    (got.b - want.b).abs() < 1e-4 * want.b.abs(),
                    "{got:?} {want:?}"
                );
            }
            // The distance a depth maps back to is the clip w of the point.
            let point = glam::DVec4::new(0.3, -0.7, 0.2, 1.0);
            let clip = mvp * point;
            let ndc_z = clip.z / clip.w;
            assert!((got.b / (ndc_z + got.a) - clip.w).abs() < 1e-9 * clip.w);
        }
        // Orthographic cameras, model-view matrices and other matrices:
        // not a perspective.
        let ortho = DMat4::orthographic_rh_gl(-4.0, 4.0, -3.0, 3.0, 0.1, 50.0) * view;
        let mut skew = (proj * view).to_cols_array();
        skew[2] += 0.3; // row 2 no longer a multiple of row 3
        for m in [ortho.to_cols_array(), view.to_cols_array(), skew] {
            assert_eq!(Perspective::from_matrix(&m), None, "{m:?}");
        }
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
        let all = Seen {
            left_shift: -0.1,
            rule: None,
            pixels_per_ndc: 0.0,
            window: (0.0, 5.0),
        };
        let c = centre(&mut scratch, (5, 4), &p, (0.0, 1.0), 1.0, &all).unwrap();
        assert!((c - 5.0).abs() < 1e-3, "{c}");
        // The buffers are kept for the next measurement.
        assert_eq!(scratch.depth.len(), 20);
        assert!(scratch.distances.capacity() >= 16);
        scratch.depth = vec![1.0; 20];
        assert_eq!(
            centre(&mut scratch, (5, 4), &p, (0.0, 1.0), 1.0, &all),
            None
        );
    }

    /// One row of 80 pixels: `near` over columns 4..20 (left of the
    /// window [20, 60)), `far` over 20..40 (inside it), `none` elsewhere.
    fn row(near: f64, far: f64, none: f64) -> Vec<f64> {
        (0..80)
            .map(|x| match x {
                4..=19 => near,
                20..=39 => far,
                _ => none,
            })
            .collect()
    }

    /// The left eye of a view at convergence `c`: each pixel of `view`
    /// (distances, 0: nothing) moved by the rule, nearer over farther.
    fn left_eye(view: &[f64], seen: &Seen, c: f64) -> Vec<f64> {
        let mut eye = vec![0.0f64; view.len()];
        for (x, &w) in view.iter().enumerate() {
            if w == 0.0 {
                continue;
            }
            let moved = seen.left_shift * (1.0 - c / w) * seen.pixels_per_ndc;
            let to = (x as f64 + moved).round();
            if to >= 0.0 && (to as usize) < eye.len() {
                let e = &mut eye[to as usize];
                if *e == 0.0 || w < *e {
                    *e = w;
                }
            }
        }
        eye
    }

    #[test]
    fn the_centre_is_the_programs_whatever_convergence_the_eye_was_drawn_with() {
        let p = Perspective::from_matrix(&glu_perspective(1.0, 100.0)).unwrap();
        let depth = |w: f64| {
            if w == 0.0 {
                1.0
            } else {
                ((-p.a + p.b / w) * 0.5 + 0.5) as f32
            }
        };
        // One row of 80 pixels, the window [20, 60): a near object (w 2)
        // over columns 4..20, left of the window, and a far one (w 8) over
        // 20..40, inside it: in the program's view the centre is far.
        let view = row(2.0, 8.0, 0.0);
        let base = Seen {
            left_shift: -0.2,
            rule: Some(Rule::Distance(0.0)),
            pixels_per_ndc: 40.0,
            window: (20.0, 60.0),
        };
        for c in [0.0, 2.0, 5.0, 8.0, 20.0] {
            let seen = Seen {
                rule: Some(Rule::Distance(c)),
                ..base
            };
            let eye = left_eye(&view, &seen, c);
            let mut scratch = Scratch {
                depth: eye.iter().map(|&w| depth(w)).collect(),
                ..Default::default()
            };
            let got = centre(&mut scratch, (80, 1), &p, (0.0, 1.0), 1.0, &seen).unwrap();
            assert!((got - 8.0).abs() < 1e-3, "convergence {c}: centre {got}");
        }
        // Taken as they lie, the eye's pixels give another centre at
        // convergence 8 (the near object moved 24 pixels into the window,
        // over the far one).
        let c = 8.0;
        let eye = left_eye(
            &view,
            &Seen {
                rule: Some(Rule::Distance(c)),
                ..base
            },
            c,
        );
        let near_inside = eye[20..60].iter().filter(|&&w| w == 2.0).count();
        let far_inside = eye[20..60].iter().filter(|&&w| w == 8.0).count();
        assert!(
            near_inside > far_inside,
            "{near_inside} near, {far_inside} far"
        );
    }

    #[test]
    fn the_centre_as_a_depth_is_the_programs_whatever_depth_the_eye_was_drawn_at() {
        // NDC depths: a near object (0.2) left of the window [20, 60) and a
        // far one (0.9) inside it, in the program's view; window depth
        // (z + 1) / 2, cleared to 1.
        let view = row(0.2, 0.9, 1.0);
        let frame = Frame {
            zero_to_one: false,
            depth_range: (0.0, 1.0),
            clear_depth: 1.0,
            window: None,
            target: None,
            origin: None,
            left_shift: -0.2,
            converges: true,
            overlays: false,
            target_overlays: None,
            depth_written: true,
            depth_beside: false,
        };
        for zc in [0.2, 0.5, 0.8] {
            let seen = Seen {
                left_shift: -0.2,
                rule: Some(Rule::Depth { zc, alpha: 1.0 }),
                pixels_per_ndc: 40.0,
                window: (20.0, 60.0),
            };
            // The eye: each pixel moved by the rule, nearer over farther.
            let mut eye = vec![1.0f64; 80];
            for (x, &z) in view.iter().enumerate().filter(|(_, z)| **z < 1.0) {
                let moved = -0.2 * (zc - z) / (zc - 1.0) * 40.0;
                let to = (x as f64 + moved).round();
                if (0.0..80.0).contains(&to) && z < eye[to as usize] {
                    eye[to as usize] = z;
                }
            }
            let mut scratch = Scratch {
                depth: eye.iter().map(|&z| ((z + 1.0) / 2.0) as f32).collect(),
                ..Default::default()
            };
            let got = centre_depth(&mut scratch, (80, 1), &frame, &seen).unwrap();
            assert!((got - 0.9).abs() < 1e-6, "drawn at {zc}: centre {got}");
        }
    }

    #[test]
    fn a_program_presenting_slowly_is_measured_every_interval() {
        assert!(measures(EAGER + PERIOD), "every PERIODth frame");
        assert!(!measures(EAGER + 1));
        assert!(due(INTERVAL), "a frame an INTERVAL after the last");
        assert!(!due(INTERVAL - std::time::Duration::from_millis(1)));
    }

    #[test]
    fn the_window_is_the_middle_half_of_the_viewport() {
        assert_eq!(window((0, 0, 400, 300)), (100, 75, 200, 150));
        assert_eq!(window((10, 20, 1, 1)), (10, 20, 1, 1));
    }
}

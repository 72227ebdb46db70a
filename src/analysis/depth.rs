//! Depth-buffer samples and the way back from a window depth to an
//! eye-space distance. Pure: no GL.

use crate::error::{Error, Result};
use crate::math::Frustum;

/// One D24 depth step: window depths within this of the clear value count
/// as background (a 24-bit depth buffer cannot tell them apart).
pub const DEPTH_STEP_24: f64 = 1.0 / 16_777_215.0;

/// A depth buffer read back as window depths, rows bottom first (the order
/// of glReadPixels and of window coordinates: (0, 0) is the lower-left pixel).
#[derive(Clone, PartialEq)]
pub struct DepthImage {
    width: u32,
    height: u32,
    values: Vec<f32>,
}

impl std::fmt::Debug for DepthImage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "DepthImage({}x{})", self.width, self.height)
    }
}

impl DepthImage {
    /// A depth image of `values` (width × height, rows bottom first).
    pub fn new(width: u32, height: u32, values: Vec<f32>) -> Result<DepthImage> {
        crate::image::check_size(width, height)?;
        if values.len() != width as usize * height as usize {
            return Err(Error::invalid_value(format!(
                "{} depth values cannot be a {width}x{height} depth image",
                values.len()
            )));
        }
        Ok(DepthImage {
            width,
            height,
            values,
        })
    }

    /// Its values, rows bottom first (the image's buffer, given back).
    pub fn into_values(self) -> Vec<f32> {
        self.values
    }

    /// A depth image whose pixel (x, y) (y = 0 at the bottom) is `f(x, y)`.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> f32) -> DepthImage {
        crate::image::check_size(width, height).expect("depth image size");
        let mut values = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                values.push(f(x, y));
            }
        }
        DepthImage {
            width,
            height,
            values,
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The window depth of pixel (x, y), y = 0 at the bottom.
    pub fn get(&self, x: u32, y: u32) -> f32 {
        self.values[y as usize * self.width as usize + x as usize]
    }

    /// Every value, rows bottom first.
    pub fn values(&self) -> &[f32] {
        &self.values
    }
}

/// A glViewport rectangle in window coordinates (y up from the bottom row).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Viewport {
    /// Left edge.
    pub x: i32,
    /// Bottom edge.
    pub y: i32,
    /// Width (> 0).
    pub width: i32,
    /// Height (> 0).
    pub height: i32,
}

impl Viewport {
    /// The viewport covering a whole `width` × `height` surface.
    pub fn full(width: u32, height: u32) -> Viewport {
        Viewport {
            x: 0,
            y: 0,
            width: width as i32,
            height: height as i32,
        }
    }
}

/// The map from window depth back to eye-space distance for a perspective
/// (glFrustum) projection with near and far clip distances n and f and
/// glDepthRange(range_near, range_far):
///
/// z_ndc = 2 (z_w − range_near) / (range_far − range_near) − 1, and
/// distance = 2 f n / ((f + n) − z_ndc (f − n)).
///
/// The camera offset and frustum asymmetry of a parallel-axis stereo eye
/// change neither n nor f nor the distance of a point, so either eye's
/// depth buffer maps the same way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthMapping {
    near: f64,
    far: f64,
    range_near: f64,
    range_far: f64,
}

impl DepthMapping {
    /// The mapping of `frustum`'s near and far planes under glDepthRange(range.0, range.1).
    pub fn new(frustum: &Frustum, depth_range: (f64, f64)) -> Result<DepthMapping> {
        let f = frustum.validated()?;
        let (rn, rf) = depth_range;
        if !(rn.is_finite() && rf.is_finite()) || rn == rf {
            return Err(Error::invalid_operation(format!(
                "glDepthRange({rn}, {rf}) maps every distance to one depth: distances cannot be \
                 recovered; use distinct near and far values (the default is 0, 1)"
            )));
        }
        Ok(DepthMapping {
            near: f.near,
            far: f.far,
            range_near: rn,
            range_far: rf,
        })
    }

    /// The eye-space distance (along the view axis) of a window depth.
    pub fn distance(&self, window_depth: f64) -> f64 {
        let (n, f) = (self.near, self.far);
        let z_ndc =
            2.0 * (window_depth - self.range_near) / (self.range_far - self.range_near) - 1.0;
        2.0 * f * n / ((f + n) - z_ndc * (f - n))
    }

    /// The window depth of an eye-space distance (the inverse of [`Self::distance`]).
    pub fn window_depth(&self, distance: f64) -> f64 {
        let (n, f) = (self.near, self.far);
        let z_ndc = ((f + n) - 2.0 * f * n / distance) / (f - n);
        self.range_near + (z_ndc + 1.0) / 2.0 * (self.range_far - self.range_near)
    }
}

/// What a measurement reads from a rendered frame: the depth buffer and
/// the GL state needed to interpret it.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthCapture {
    /// The depth buffer (shared by both eyes: it holds what was drawn last).
    pub depth: DepthImage,
    /// The viewport the scene was drawn in.
    pub viewport: Viewport,
    /// glDepthRange when the scene was drawn.
    pub depth_range: (f64, f64),
    /// glClearDepth: pixels still at this value hold no geometry.
    pub clear_depth: f64,
}

impl DepthCapture {
    /// A capture of `depth` drawn with the whole surface as viewport, the
    /// default depth range (0, 1) and clear depth 1.
    pub fn new(depth: DepthImage) -> DepthCapture {
        let viewport = Viewport::full(depth.width(), depth.height());
        DepthCapture {
            depth,
            viewport,
            depth_range: (0.0, 1.0),
            clear_depth: 1.0,
        }
    }

    /// Calls `f(window_depth)` for every pixel that holds geometry (depth
    /// not within one D24 step of the clear value) inside the part of the
    /// viewport from fraction `lo` to `hi` of its width and height (0…1 is
    /// the whole viewport), clipped to the depth image. A pixel is inside
    /// when its centre is (GL's rule for polygons).
    pub(crate) fn for_each_covered(&self, lo: f64, hi: f64, mut f: impl FnMut(f32)) {
        let vp = self.viewport;
        let span = |origin: i32, size: i32, limit: u32| {
            // Pixel i (centre i + 0.5) is inside [a, b) when ceil(a − ½) <= i < ceil(b − ½).
            let edge = |t: f64| {
                let e = (origin as f64 + t * size as f64 - 0.5).ceil();
                e.clamp(0.0, limit as f64) as u32
            };
            (edge(lo), edge(hi))
        };
        let (x0, x1) = span(vp.x, vp.width, self.depth.width());
        let (y0, y1) = span(vp.y, vp.height, self.depth.height());
        let w = self.depth.width() as usize;
        for y in y0..y1 {
            let row = &self.depth.values()[y as usize * w..(y as usize + 1) * w];
            for &z in &row[x0 as usize..x1 as usize] {
                if (z as f64 - self.clear_depth).abs() > DEPTH_STEP_24 {
                    f(z);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frustum() -> Frustum {
        Frustum::perspective(40.0, 4.0 / 3.0, 1.0, 50.0).unwrap()
    }

    #[test]
    fn distance_inverts_the_frustum_matrix_depth() {
        // The window depth GL computes from the projection matrix, done independently.
        let m = frustum().matrix();
        for w in [1.0, 2.5, 10.0, 37.0, 50.0] {
            let c = m * glam::DVec4::new(0.3, -0.2, -w, 1.0);
            let z_w = (c.z / c.w + 1.0) / 2.0;
            let map = DepthMapping::new(&frustum(), (0.0, 1.0)).unwrap();
            assert!((map.distance(z_w) - w).abs() < 1e-9 * w, "w {w}");
            assert!((map.window_depth(w) - z_w).abs() < 1e-12, "w {w}");
        }
    }

    #[test]
    fn a_depth_range_is_undone() {
        let map = DepthMapping::new(&frustum(), (0.25, 0.75)).unwrap();
        let plain = DepthMapping::new(&frustum(), (0.0, 1.0)).unwrap();
        let z = plain.window_depth(12.0);
        assert!((map.distance(0.25 + 0.5 * z) - 12.0).abs() < 1e-9);
        let reversed = DepthMapping::new(&frustum(), (1.0, 0.0)).unwrap();
        assert!((reversed.distance(1.0 - z) - 12.0).abs() < 1e-9);
        assert!(matches!(
            DepthMapping::new(&frustum(), (0.5, 0.5)),
            Err(Error::InvalidOperation(m)) if m.contains("glDepthRange")
        ));
    }

    #[test]
    fn covered_pixels_skip_the_clear_value_and_stay_in_the_viewport() {
        // 4x2: geometry at x = 1 and x = 3 of the bottom row only.
        let img = DepthImage::from_fn(4, 2, |x, y| if y == 0 && x % 2 == 1 { 0.5 } else { 1.0 });
        let mut cap = DepthCapture::new(img);
        let mut n = 0;
        cap.for_each_covered(0.0, 1.0, |_| n += 1);
        assert_eq!(n, 2);
        cap.viewport = Viewport {
            x: -2,
            y: 0,
            width: 4,
            height: 2,
        };
        let mut n = 0;
        cap.for_each_covered(0.0, 1.0, |_| n += 1);
        assert_eq!(n, 1, "only x = 0, 1 are inside a viewport from -2 to 2");
        cap.viewport = Viewport::full(4, 2);
        cap.clear_depth = 0.5;
        let mut n = 0;
        cap.for_each_covered(0.0, 1.0, |_| n += 1);
        assert_eq!(n, 6, "with clear depth 0.5 the 1.0 pixels are geometry");
    }

    #[test]
    fn depth_images_check_their_size() {
        assert!(DepthImage::new(2, 2, vec![0.0; 3]).is_err());
        assert!(DepthImage::new(0, 2, vec![]).is_err());
        let d = DepthImage::new(2, 1, vec![0.25, 0.75]).unwrap();
        assert_eq!((d.get(0, 0), d.get(1, 0)), (0.25, 0.75));
    }
}

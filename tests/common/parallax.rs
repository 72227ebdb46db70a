//! Parallax between two eye images, measured as a viewer's eyes see it: by
//! block matching. Each textured 16x16 block of the left eye is looked
//! for in the right eye along its rows (and a few rows up and down, to see
//! that the best match is on the same rows); a block whose best match is
//! clear (well below the mean difference, and unlike matches two pixels
//! or more away) gives its horizontal shift: right-eye position minus
//! left-eye position, positive behind the screen.
//!
//! Self-contained (no `super::`): `examples/eye_parallax.rs` includes it
//! too, to measure captured PNGs by hand.

#![allow(dead_code)]

use glstereo::image::Image;

/// One matched block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Match {
    /// The block's top-left pixel in the left eye.
    pub x: u32,
    pub y: u32,
    /// Where it is in the right eye, relative: columns (positive: right)
    /// and rows (positive: down).
    pub dx: i32,
    pub dy: i32,
    /// Mean absolute luma difference per pixel at the match (0…255).
    pub cost: f32,
}

/// What [`measure`] found.
#[derive(Clone, Debug, Default)]
pub struct Parallax {
    /// Blocks with texture enough to match.
    pub textured: usize,
    pub matches: Vec<Match>,
}

pub const BLOCK: u32 = 16;

fn luma(img: &Image) -> Vec<f32> {
    img.pixels()
        .chunks_exact(4)
        .map(|p| 0.299 * f32::from(p[0]) + 0.587 * f32::from(p[1]) + 0.114 * f32::from(p[2]))
        .collect()
}

/// Block matching of `left` against `right` (the same size): shifts up to
/// `range` columns either way, `rows` rows either way.
pub fn measure(left: &Image, right: &Image, range: i32, rows: i32) -> Parallax {
    assert_eq!(
        (left.width(), left.height()),
        (right.width(), right.height()),
        "eyes of one size"
    );
    let (w, h) = (left.width() as i32, left.height() as i32);
    let (l, r) = (luma(left), luma(right));
    let b = BLOCK as i32;
    let mut out = Parallax::default();
    let mut y = rows;
    while y + b + rows <= h {
        let mut x = range;
        while x + b + range <= w {
            let at = |img: &[f32], px: i32, py: i32| img[(py * w + px) as usize];
            // Texture: the block's luma spread.
            let (mut sum, mut sq) = (0.0f32, 0.0f32);
            for j in 0..b {
                for i in 0..b {
                    let v = at(&l, x + i, y + j);
                    sum += v;
                    sq += v * v;
                }
            }
            let n = (b * b) as f32;
            let var = sq / n - (sum / n) * (sum / n);
            if var < 40.0 {
                x += b;
                continue;
            }
            out.textured += 1;
            let cost = |dx: i32, dy: i32| {
                let mut s = 0.0f32;
                for j in 0..b {
                    for i in 0..b {
                        s += (at(&l, x + i, y + j) - at(&r, x + i + dx, y + j + dy)).abs();
                    }
                }
                s / n
            };
            let mut all = Vec::with_capacity(((2 * range + 1) * (2 * rows + 1)) as usize);
            for dy in -rows..=rows {
                for dx in -range..=range {
                    all.push((cost(dx, dy), dx, dy));
                }
            }
            let best = *all
                .iter()
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .expect("candidates");
            let mean = all.iter().map(|c| c.0).sum::<f32>() / all.len() as f32;
            let rival = all
                .iter()
                .filter(|c| (c.1 - best.1).abs() >= 2 || c.2 != best.2)
                .map(|c| c.0)
                .fold(f32::INFINITY, f32::min);
            if best.0 < 0.35 * mean && best.0 < 0.7 * rival && best.0 < 12.0 {
                out.matches.push(Match {
                    x: x as u32,
                    y: y as u32,
                    dx: best.1,
                    dy: best.2,
                    cost: best.0,
                });
            }
            x += b;
        }
        y += b;
    }
    out
}

impl Parallax {
    /// The horizontal shifts, sorted.
    pub fn shifts(&self) -> Vec<i32> {
        let mut s: Vec<i32> = self.matches.iter().map(|m| m.dx).collect();
        s.sort_unstable();
        s
    }

    /// The shift at quantile `q` (0…1) of the matches; None without any.
    pub fn quantile(&self, q: f64) -> Option<i32> {
        let s = self.shifts();
        (!s.is_empty()).then(|| s[((s.len() - 1) as f64 * q).round() as usize])
    }

    /// How many matches are off their rows.
    pub fn off_rows(&self) -> usize {
        self.off_rows_by_more_than(0)
    }

    /// How many matches are more than `rows` rows off theirs.
    pub fn off_rows_by_more_than(&self, rows: i32) -> usize {
        self.matches.iter().filter(|m| m.dy.abs() > rows).count()
    }

    /// One line: matched of textured, rows, quantiles 10/50/90 %.
    pub fn summary(&self) -> String {
        let q = |q| self.quantile(q).map_or("-".into(), |v: i32| v.to_string());
        format!(
            "{} of {} blocks matched, {} off their rows; shift p10 {} median {} p90 {}",
            self.matches.len(),
            self.textured,
            self.off_rows(),
            q(0.1),
            q(0.5),
            q(0.9)
        )
    }
}

/// How many pixels of `a` and `b` (same size) differ by more than 2 in a
/// colour channel.
pub fn differing_pixels(a: &Image, b: &Image) -> usize {
    let mut n = 0;
    for y in 0..a.height() {
        for x in 0..a.width() {
            let (p, q) = (a.get(x, y), b.get(x, y));
            n += usize::from((0..3).any(|c| p[c].abs_diff(q[c]) > 2));
        }
    }
    n
}

/// Checks two eye images as a viewer sees them (the halves of a
/// side-by-side-half picture, or full captures): they differ, enough
/// textured blocks match, nearly all on their rows (smooth shading
/// matches a row or two off now and then; a picture moved or distorted
/// vertically would match off its rows mostly), and near and far are
/// apart: shifts from p10 to p90 span at least `min_spread` pixels.
/// Returns the measure for further checks.
pub fn check_depth(left: &Image, right: &Image, min_spread: i32, what: &str) -> Parallax {
    checked(left, right, (20, 0), min_spread, what)
}

/// [`check_depth`] for a small object, smoothly shaded, in a half-width
/// eye: at least `min_matched` blocks matched (it has few textured ones),
/// and a block one row off counts as on its rows (a smooth shade matches
/// one row up or down as well; a picture moved vertically is more off).
pub fn check_depth_of(
    left: &Image,
    right: &Image,
    min_matched: usize,
    min_spread: i32,
    what: &str,
) -> Parallax {
    checked(left, right, (min_matched, 1), min_spread, what)
}

fn checked(
    left: &Image,
    right: &Image,
    limits: (usize, i32),
    min_spread: i32,
    what: &str,
) -> Parallax {
    let p = judged(left, right, limits, min_spread, what).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{what}: {}", p.summary());
    p
}

/// [`checked`]'s judgement: the measure, or what is wrong.
fn judged(
    left: &Image,
    right: &Image,
    (min_matched, row_slack): (usize, i32),
    min_spread: i32,
    what: &str,
) -> Result<Parallax, String> {
    if differing_pixels(left, right) <= 200 {
        return Err(format!("{what}: the eyes are alike (no stereo)"));
    }
    let p = measure(left, right, 48, 3);
    let matched = p.matches.len();
    if matched < min_matched {
        return Err(format!(
            "{what}: only {matched} blocks matched between the eyes ({})",
            p.summary()
        ));
    }
    if p.off_rows_by_more_than(row_slack) * 3 > matched {
        return Err(format!(
            "{what}: {} of {matched} blocks matched more than {row_slack} rows off theirs: the \
             eyes are not the same content shifted along rows ({})",
            p.off_rows_by_more_than(row_slack),
            p.summary()
        ));
    }
    let (lo, hi) = (p.quantile(0.1).unwrap(), p.quantile(0.9).unwrap());
    if hi - lo < min_spread {
        return Err(format!(
            "{what}: shifts p10 {lo} to p90 {hi}: the scene is flat ({})",
            p.summary()
        ));
    }
    Ok(p)
}

/// [`check_depth_of`] of several pictures of one moving scene (left and
/// right eye each): a turning object seen edge-on has little depth in one
/// frame and its full depth a moment later, so the scene passes when one
/// of its pictures does (the first that does is returned), and fails
/// with what was wrong with each.
#[allow(dead_code)] // not every test binary checks moving scenes
pub fn check_depth_of_any(
    pairs: &[[Image; 2]],
    min_matched: usize,
    min_spread: i32,
    what: &str,
) -> Parallax {
    let mut wrong = Vec::new();
    for (i, [l, r]) in pairs.iter().enumerate() {
        let what = format!("{what} (picture {} of {})", i + 1, pairs.len());
        match judged(l, r, (min_matched, 1), min_spread, &what) {
            Ok(p) => {
                eprintln!("{what}: {}", p.summary());
                return p;
            }
            Err(e) => wrong.push(e),
        }
    }
    panic!("{}", wrong.join("\n"));
}

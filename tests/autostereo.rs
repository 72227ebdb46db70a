//! The autostereo example (a mono fixed-function program under automatic
//! stereo) run as a real C program, headless on EGL and OSMesa, with every
//! frame's eye images measured: the card at the convergence depth has zero
//! parallax, the others the parallax the settings predict, and the frame
//! with separation 0 has identical eyes.

mod common;

use std::path::Path;
use std::process::Command;

use glstereo::image::Image;
use glstereo::shims::nv3dvision::{
    GL_STEREO_CONVERGENCE_NV, GL_STEREO_SEPARATION_NV, StereoSettings,
};

const W: u32 = 320;
const H: u32 = 240;
const GREY: [u8; 4] = [128, 128, 128, 255];

/// The example's cards, written out here: colour, depth, NDC y range.
const CARDS: [([u8; 3], f64, f64, f64); 3] = [
    ([230, 20, 20], 4.0, 0.4, 0.8),
    ([20, 200, 20], 8.0, -0.2, 0.2),
    ([20, 20, 230], 16.0, -0.8, -0.4),
];

fn left_edge(img: &Image, color: [u8; 3], y0: f64, y1: f64) -> f64 {
    let row = ((1.0 - (y0 + y1) / 2.0) / 2.0 * H as f64) as u32;
    let want = [color[0], color[1], color[2], 255];
    (0..W)
        .find(|&x| img.get(x, row) == want)
        .unwrap_or_else(|| panic!("no {color:?} pixel on row {row}")) as f64
}

/// Parses "frame N: separation S%, convergence C" lines.
fn frames(stdout: &str) -> Vec<(u32, f32, f32)> {
    stdout
        .lines()
        .filter_map(|l| {
            let rest = l.strip_prefix("frame ")?;
            let (n, rest) = rest.split_once(": separation ")?;
            let (s, rest) = rest.split_once("%, convergence ")?;
            Some((n.parse().ok()?, s.parse().ok()?, rest.trim().parse().ok()?))
        })
        .collect()
}

fn run_and_check(osmesa: bool, backend: &str, out: &Path) {
    let exe = common::build_example("autostereo", osmesa);
    let o = common::run_ok(
        Command::new(exe)
            .args(["--out", out.to_str().unwrap(), "--size", "320x240"])
            .args(["--frames", "5"])
            .env("GLSTEREO_BACKEND", backend)
            .env_remove("GLSTEREO_MODE")
            .env_remove("GLSTEREO_EMULATION"),
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("3D Vision enabled, initial separation 15.0%, convergence 0.0"),
        "{stdout}"
    );
    let frames = frames(&stdout);
    assert_eq!(frames.len(), 5, "{stdout}");
    let mut separations = Vec::new();
    let mut convergences = Vec::new();
    for (n, separation, convergence) in frames {
        let dir = out.join(format!("frame{n:02}"));
        let l = common::png(&dir.join("left.png"));
        let r = common::png(&dir.join("right.png"));
        assert!(dir.join("composite.png").exists());
        assert_eq!((l.width(), l.height()), (W, H));
        assert_eq!(l.get(2, 2), GREY, "frame {n}: grey background");
        let mut settings = StereoSettings::new(true);
        settings
            .parameter_f(GL_STEREO_SEPARATION_NV, separation)
            .unwrap();
        settings
            .parameter_f(GL_STEREO_CONVERGENCE_NV, convergence)
            .unwrap();
        if separation == 0.0 {
            assert_eq!(l, r, "frame {n}: separation 0 gives identical eyes");
        }
        for (color, depth, y0, y1) in CARDS {
            let measured = left_edge(&r, color, y0, y1) - left_edge(&l, color, y0, y1);
            let predicted = settings.parallax_fraction(depth) * W as f64;
            assert!(
                (measured - predicted).abs() <= 1.0,
                "frame {n} (separation {separation}%, convergence {convergence}): card at \
                 depth {depth} moved {measured} px, predicted {predicted:.2}"
            );
            if depth == convergence as f64 {
                assert_eq!(
                    measured, 0.0,
                    "frame {n}: the card at the convergence depth"
                );
            }
        }
        separations.push(separation);
        convergences.push(convergence);
    }
    // The example changes both settings over its frames.
    assert!(
        separations.windows(2).all(|w| w[1] > w[0]),
        "{separations:?}"
    );
    assert!(
        convergences.windows(2).all(|w| w[1] != w[0]),
        "{convergences:?}"
    );
}

#[test]
fn autostereo_on_egl_puts_the_converged_card_at_the_screen_in_every_frame() {
    let out = common::scratch("autostereo_egl");
    run_and_check(false, "egl", &out);
}

#[test]
fn autostereo_on_osmesa_puts_the_converged_card_at_the_screen_in_every_frame() {
    let out = common::scratch("autostereo_osmesa");
    run_and_check(true, "osmesa", &out);
}

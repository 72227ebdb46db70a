//! The OGLPlane port (seed 000 §11) run as a real C program, headless on
//! EGL and on OSMesa: its images are checked against the stereo math.
//!
//! Parallax is measured from the images through the airplane's navigation
//! lights (3×3-pixel points of unique colours at the nose and the wing
//! tips): a point's pixels are centred on the pixel centre nearest its
//! window position, so each light's centroid is within half a pixel of
//! where the math puts it, and its parallax within one pixel. The
//! expected positions come from the airplane's pose (a function of the
//! frame number, replicated here) and the library's HP projection.

mod common;

use std::path::Path;
use std::process::{Command, Output};

use glam::{DMat4, DVec3, DVec4};
use glstereo::image::Image;
use glstereo::math::{Eye, Frustum, StereoAdjust, hp_eye};

const W: u32 = 640;
const H: u32 = 480;

// The scene, as c-examples/oglplane.c defines it.
const HFOV_DEGREES: f64 = 50.0;
const NEAR: f64 = 1.0;
const FAR: f64 = 50.0;
const CAMERA_DISTANCE: f64 = 10.0;
const TILT_DEGREES: f64 = 20.0;
const ANGLE_STEP: f64 = 6.0;
const NOSE: [f64; 3] = [2.2, 0.0, 0.0];
const LEFT_TIP: [f64; 3] = [-2.2, 0.25, -1.4];
const RIGHT_TIP: [f64; 3] = [-2.2, 0.25, 1.4];
/// Bounding-box centre: x −2.2…2.2, y −0.6 (keel)…0.25 (tips), z −1.4…1.4.
const CENTRE: [f64; 3] = [0.0, -0.175, 0.0];
const AMBER: [u8; 3] = [255, 200, 0];
const RED: [u8; 3] = [230, 0, 0];
const GREEN: [u8; 3] = [0, 200, 0];
const GREY: [u8; 4] = [115, 115, 115, 255];

#[derive(Clone, Copy, Debug, PartialEq)]
enum Backend {
    Egl,
    OsMesa,
}

struct Run {
    stdout: String,
    left: Image,
    right: Image,
    dir: std::path::PathBuf,
}

fn command(backend: Backend, args: &[&str]) -> Command {
    let exe = common::build_example("oglplane", backend == Backend::OsMesa);
    let mut cmd = Command::new(exe);
    cmd.args(args)
        .env(
            "GLSTEREO_BACKEND",
            match backend {
                Backend::Egl => "egl",
                Backend::OsMesa => "osmesa",
            },
        )
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_EMULATION");
    cmd
}

fn oglplane(backend: Backend, name: &str, args: &[&str]) -> Run {
    let out = common::scratch(&format!("oglplane_{name}_{backend:?}"));
    let mut all = vec!["--out", out.to_str().unwrap()];
    all.extend_from_slice(args);
    let o = common::run_ok(&mut command(backend, &all));
    Run {
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        left: common::png(&out.join("left.png")),
        right: common::png(&out.join("right.png")),
        dir: out,
    }
}

fn mono() -> Frustum {
    let hw = NEAR * (HFOV_DEGREES / 2.0).to_radians().tan();
    let hh = hw * H as f64 / W as f64;
    Frustum {
        left: -hw,
        right: hw,
        bottom: -hh,
        top: hh,
        near: NEAR,
        far: FAR,
    }
}

/// A model point in eye space for the airplane turned `angle` degrees.
fn eye_space(p: [f64; 3], angle: f64) -> DVec3 {
    let m = DMat4::from_translation(DVec3::new(0.0, 0.0, -CAMERA_DISTANCE))
        * DMat4::from_rotation_x(TILT_DEGREES.to_radians())
        * DMat4::from_rotation_y(angle.to_radians())
        * DMat4::from_translation(-DVec3::from_array(CENTRE));
    m.transform_point3(DVec3::from_array(p))
}

/// Where `eye` puts an eye-space point: x from the left edge, y from the
/// top edge, in pixels.
fn window(eye: Eye, adj: &StereoAdjust, p: DVec3) -> (f64, f64) {
    let c = hp_eye(&mono(), adj, eye).unwrap().matrix() * DVec4::new(p.x, p.y, p.z, 1.0);
    let (x, y) = (c.x / c.w, c.y / c.w);
    (
        (x + 1.0) / 2.0 * W as f64,
        H as f64 - (y + 1.0) / 2.0 * H as f64,
    )
}

/// Centroid (pixel centres, rows top first) and pixel count of one colour.
fn light(img: &Image, rgb: [u8; 3]) -> (f64, f64, usize) {
    let (mut sx, mut sy, mut n) = (0.0, 0.0, 0);
    for y in 0..img.height() {
        for x in 0..img.width() {
            if img.get(x, y)[..3] == rgb {
                sx += x as f64 + 0.5;
                sy += y as f64 + 0.5;
                n += 1;
            }
        }
    }
    assert!(n > 0, "no pixel of colour {rgb:?}");
    (sx / n as f64, sy / n as f64, n)
}

/// A light's parallax (right-eye x − left-eye x) in the images and by the
/// math, after checking each eye's position and that there is no vertical
/// parallax.
fn light_parallax(
    run: &Run,
    rgb: [u8; 3],
    p: [f64; 3],
    angle: f64,
    adj: &StereoAdjust,
) -> (f64, f64) {
    let q = eye_space(p, angle);
    let mut got = [0.0; 2];
    let mut want = [0.0; 2];
    let mut rows = [0.0; 2];
    for (i, (eye, img)) in [(Eye::Left, &run.left), (Eye::Right, &run.right)]
        .into_iter()
        .enumerate()
    {
        let (cx, cy, n) = light(img, rgb);
        let (wx, wy) = window(eye, adj, q);
        assert_eq!(n, 9, "{eye:?} eye: light {rgb:?} should be 3x3 pixels");
        assert!(
            (cx - wx).abs() <= 0.5 + 1e-6 && (cy - wy).abs() <= 0.5 + 1e-6,
            "{eye:?} eye: light {rgb:?} is centred at ({cx}, {cy}); the math puts it at ({wx:.3}, {wy:.3})"
        );
        got[i] = cx;
        want[i] = wx;
        rows[i] = cy;
    }
    assert_eq!(
        rows[0], rows[1],
        "light {rgb:?}: no vertical parallax (no toe-in)"
    );
    eprintln!(
        "light {rgb:?}: parallax {:+.3} px in the images, {:+.3} px by the math",
        got[1] - got[0],
        want[1] - want[0]
    );
    (got[1] - got[0], want[1] - want[0])
}

/// The numbers of a "measured …: parallax A% to B% …, distance N to F" line.
#[derive(Debug)]
struct Measured {
    min_percent: f64,
    max_percent: f64,
    nearest: f64,
    farthest: f64,
    line: String,
}

fn measured(stdout: &str, prefix: &str) -> Measured {
    let line = stdout
        .lines()
        .find(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("no line starting {prefix:?} in:\n{stdout}"));
    let tokens: Vec<&str> = line.split_whitespace().collect();
    let num = |after: &str| -> (f64, f64) {
        let i = tokens.iter().position(|t| *t == after).expect(after);
        let clean = |t: &str| {
            t.trim_end_matches([':', ';', '%', ','])
                .parse::<f64>()
                .unwrap()
        };
        (clean(tokens[i + 1]), clean(tokens[i + 3]))
    };
    let (min_percent, max_percent) = num("parallax");
    let (nearest, farthest) = num("distance");
    Measured {
        min_percent,
        max_percent,
        nearest,
        farthest,
        line: line.to_owned(),
    }
}

fn adjust_values(stdout: &str) -> (f64, f64) {
    let line = stdout
        .lines()
        .find(|l| l.contains("offset adjustment"))
        .unwrap_or_else(|| panic!("no settings line in:\n{stdout}"));
    let value = |key: &str| -> f64 {
        let rest = &line[line.find(key).unwrap() + key.len()..];
        rest.split([',', ' '])
            .find(|t| !t.is_empty())
            .unwrap()
            .parse()
            .unwrap()
    };
    (value("offset adjustment "), value("balance adjustment "))
}

fn check_nose_in_front_far_tip_behind(backend: Backend) {
    let angle = -60.0;
    let run = oglplane(backend, "pose", &["--angle", "-60"]);
    assert!(run.stdout.contains("emulated stereo"), "{}", run.stdout);
    assert!(
        run.stdout.contains("last at angle -60.0 deg"),
        "{}",
        run.stdout
    );
    let adj = StereoAdjust::new(CAMERA_DISTANCE);
    let nose = eye_space(NOSE, angle);
    let (left_tip, right_tip) = (eye_space(LEFT_TIP, angle), eye_space(RIGHT_TIP, angle));
    // The pose: nose nearest, left tip farthest (the keel and folds lie between).
    assert!(nose.z > right_tip.z && right_tip.z > left_tip.z);

    let (got, want) = light_parallax(&run, AMBER, NOSE, angle, &adj);
    assert!(want < -3.0, "the nose is in front of the screen: {want} px");
    assert!(
        (got - want).abs() <= 1.0,
        "nose parallax {got} px in the images, {want:.3} px by the math"
    );
    let (got, want) = light_parallax(&run, RED, LEFT_TIP, angle, &adj);
    assert!(
        want > 3.0,
        "the far wing tip is behind the screen: {want} px"
    );
    assert!(
        (got - want).abs() <= 1.0,
        "left tip parallax {got} px in the images, {want:.3} px by the math"
    );
    let (got, want) = light_parallax(&run, GREEN, RIGHT_TIP, angle, &adj);
    assert!(
        (got - want).abs() <= 1.0,
        "right tip parallax {got} px in the images, {want:.3} px by the math"
    );

    // The library's measurement from the depth buffer finds the same extremes.
    let m = measured(&run.stdout, "measured in the last frame:");
    let (dn, df) = (-nose.z, -left_tip.z);
    assert!(
        (m.nearest - dn).abs() < 0.05 && (m.farthest - df).abs() < 0.05,
        "{m:?}: nose at {dn}, tip at {df}"
    );
    let pct = |w: f64| glstereo::math::parallax::hp_parallax_percent(&mono(), &adj, w).unwrap();
    assert!(
        (m.min_percent - pct(dn)).abs() < 0.02 && (m.max_percent - pct(df)).abs() < 0.02,
        "{m:?}"
    );
    assert!(m.min_percent < 0.0 && m.max_percent > 0.0, "{m:?}");
    // And the background is the seed's grey, not black.
    assert_eq!(run.left.get(2, 2), GREY);

    // The stereo photos of the frame, as Pillow decodes them: the MPO's two
    // images are the eyes, the JPS has the right eye on its left half.
    use common::photo::{mean_error, pillow};
    let (format, n, frames) = pillow(&run.dir.join("oglplane.mpo"));
    assert_eq!((format.as_str(), n), ("MPO", 2));
    let errors = [
        mean_error(&frames[0].2, W, 0, &run.left),
        mean_error(&frames[1].2, W, 0, &run.right),
    ];
    assert!(errors.iter().all(|e| *e < 2.0), "oglplane.mpo: {errors:?}");
    let (_, _, frames) = pillow(&run.dir.join("oglplane.jps"));
    let (w, h, rgb) = &frames[0];
    assert_eq!((*w, *h), (2 * W, H));
    let errors = [
        mean_error(rgb, 2 * W, 0, &run.right),
        mean_error(rgb, 2 * W, W, &run.left),
    ];
    assert!(errors.iter().all(|e| *e < 2.0), "oglplane.jps: {errors:?}");
}

#[test]
fn oglplane_nose_is_in_front_and_far_wing_tip_behind_as_the_math_says_on_egl() {
    check_nose_in_front_far_tip_behind(Backend::Egl);
}

#[test]
fn oglplane_nose_is_in_front_and_far_wing_tip_behind_as_the_math_says_on_osmesa() {
    check_nose_in_front_far_tip_behind(Backend::OsMesa);
}

fn check_offset_zero(backend: Backend) {
    let run = oglplane(backend, "offset0", &["--offset", "0"]);
    assert_eq!((adjust_values(&run.stdout)).0, 0.0);
    light(&run.left, AMBER); // the airplane is there
    assert!(
        run.left == run.right,
        "offset adjustment 0 must give pixel-identical eyes"
    );
    let m = measured(&run.stdout, "measured in the last frame:");
    assert!(
        m.min_percent.abs() < 0.005 && m.max_percent.abs() < 0.005,
        "{m:?}"
    );
}

#[test]
fn oglplane_offset_zero_gives_pixel_identical_eyes_on_egl() {
    check_offset_zero(Backend::Egl);
}

#[test]
fn oglplane_offset_zero_gives_pixel_identical_eyes_on_osmesa() {
    check_offset_zero(Backend::OsMesa);
}

fn check_budget(backend: Backend) {
    // One full turn: 60 frames of 6 degrees, measured each frame.
    let run = oglplane(backend, "turn", &["--frames", "60"]);
    let last = -60.0 + 59.0 * ANGLE_STEP;
    assert!(
        run.stdout
            .contains(&format!("60 frames, last at angle {last:.1} deg")),
        "{}",
        run.stdout
    );
    let m = measured(&run.stdout, "measured over 60 frames:");
    assert!(
        m.min_percent >= -3.0 && m.max_percent <= 3.0,
        "default settings must stay within the 3% budget: {}",
        m.line
    );
    assert!(
        m.min_percent < -1.0 && m.max_percent > 1.0,
        "both signs, balanced: {}",
        m.line
    );
    assert!(m.line.ends_with("within the 3% budget"), "{}", m.line);
    // The last frame's lights agree, measured from the images.
    let adj = StereoAdjust::new(CAMERA_DISTANCE);
    for (rgb, p) in [(AMBER, NOSE), (RED, LEFT_TIP), (GREEN, RIGHT_TIP)] {
        let (got, _) = light_parallax(&run, rgb, p, last, &adj);
        assert!(
            got.abs() <= 0.03 * W as f64 + 1.0,
            "light {rgb:?}: {got} px"
        );
    }
}

#[test]
fn oglplane_default_settings_stay_within_the_comfort_budget_all_the_way_round_on_egl() {
    check_budget(Backend::Egl);
}

#[test]
fn oglplane_default_settings_stay_within_the_comfort_budget_all_the_way_round_on_osmesa() {
    check_budget(Backend::OsMesa);
}

fn check_balance_zero(backend: Backend) {
    let angle = -60.0;
    let run = oglplane(backend, "balance0", &["--balance", "0"]);
    let adj = StereoAdjust {
        balance_adjustment: 0.0,
        ..StereoAdjust::new(CAMERA_DISTANCE)
    };
    for (rgb, p) in [(AMBER, NOSE), (RED, LEFT_TIP), (GREEN, RIGHT_TIP)] {
        let (got, want) = light_parallax(&run, rgb, p, angle, &adj);
        assert!(
            got < 0.0,
            "balance 0: light {rgb:?} has parallax {got} px, want negative"
        );
        assert!(
            (got - want).abs() <= 1.0,
            "light {rgb:?}: {got} px, math {want:.3} px"
        );
    }
    let m = measured(&run.stdout, "measured in the last frame:");
    assert!(
        m.max_percent < 0.0,
        "balance 0 makes all parallax negative: {}",
        m.line
    );
}

#[test]
fn oglplane_balance_zero_makes_all_parallax_negative_on_egl() {
    check_balance_zero(Backend::Egl);
}

#[test]
fn oglplane_balance_zero_makes_all_parallax_negative_on_osmesa() {
    check_balance_zero(Backend::OsMesa);
}

#[test]
fn oglplane_keys_step_strength_and_balance_by_1_1_independently() {
    let base = oglplane(Backend::Egl, "keys0", &[]);
    let m0 = measured(&base.stdout, "measured in the last frame:");
    assert_eq!(adjust_values(&base.stdout), (1.0, 1.0));

    let run = oglplane(Backend::Egl, "keys1", &["--keys", "+"]);
    assert_eq!(adjust_values(&run.stdout), (1.1, 1.0));
    // One step stronger: every parallax ×1.1 (HP's offset and asymmetry both scale).
    let m1 = measured(&run.stdout, "measured in the last frame:");
    assert!(
        (m1.min_percent / m0.min_percent - 1.1).abs() < 0.01
            && (m1.max_percent / m0.max_percent - 1.1).abs() < 0.01,
        "{m0:?} then {m1:?}"
    );

    let run = oglplane(Backend::Egl, "keys2", &["--keys", "+++[["]);
    let (o, b) = adjust_values(&run.stdout);
    assert!(
        (o - 1.331).abs() < 1e-4 && (b - 1.0 / 1.21).abs() < 1e-4,
        "{o} {b}"
    );

    let run = oglplane(
        Backend::Egl,
        "keys3",
        &["--offset", "0.5", "--balance", "1.9", "--keys", "]]-"],
    );
    let (o, b) = adjust_values(&run.stdout);
    assert!(
        (o - 0.5 / 1.1).abs() < 1e-4 && b == 2.0,
        "clamped at 2: {o} {b}"
    );

    let many = "-".repeat(60);
    let run = oglplane(Backend::Egl, "keys4", &["--keys", &many]);
    let (o, b) = adjust_values(&run.stdout);
    assert!(o > 0.0 && o < 0.004 && b == 1.0, "{o} {b}");
}

#[test]
fn oglplane_rejects_bad_values_with_a_message_and_writes_nothing() {
    let out = common::scratch("oglplane_bad");
    let cases: &[(&[&str], &str)] = &[
        (&["--offset", "2.5"], "--offset wants a number from 0 to 2"),
        (
            &["--balance", "-0.1"],
            "--balance wants a number from 0 to 2",
        ),
        (&["--offset", "strong"], "--offset wants a number"),
        (&["--frames", "0"], "--frames"),
        (&["--frames", "2.5"], "whole number"),
        (&["--keys", "+q"], "'q' is not a key"),
        (&["--zero-parallax", "0"], "--zero-parallax"),
        (&["--wobble", "3"], "unknown option --wobble"),
        (&["--angle"], "--angle"),
    ];
    for (args, want) in cases {
        let mut all = vec!["--out", out.to_str().unwrap()];
        all.extend_from_slice(args);
        let o: Output = command(Backend::Egl, &all).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(want),
            "{args:?}: stderr {err:?} should say {want:?}"
        );
        assert!(
            !Path::new(&out.join("left.png")).exists(),
            "{args:?} wrote images"
        );
    }
}

#[test]
fn oglplane_runs_in_mono_when_stereo_is_unavailable() {
    let out = common::scratch("oglplane_mono");
    let o = common::run_ok(
        command(Backend::Egl, &["--out", out.to_str().unwrap()]).env("GLSTEREO_EMULATION", "off"),
    );
    let (stdout, stderr) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert!(
        stderr.contains("stereo is not available") && stderr.contains("running in mono"),
        "{stderr}"
    );
    assert!(
        stdout.contains("no stereo") && stdout.contains("none, the picture is mono"),
        "{stdout}"
    );
    let (left, right) = (
        common::png(&out.join("left.png")),
        common::png(&out.join("right.png")),
    );
    assert!(left == right, "a mono surface shows one image to both eyes");
    // Drawn with the mono frustum: the nose light is where Eq 1's camera puts it.
    let (cx, cy, _) = light(&left, AMBER);
    let p = eye_space(NOSE, -60.0);
    let c = mono().matrix() * DVec4::new(p.x, p.y, p.z, 1.0);
    let (wx, wy) = (
        (c.x / c.w + 1.0) / 2.0 * W as f64,
        H as f64 - (c.y / c.w + 1.0) / 2.0 * H as f64,
    );
    assert!(
        (cx - wx).abs() <= 0.5 + 1e-6 && (cy - wy).abs() <= 0.5 + 1e-6,
        "({cx}, {cy}) vs ({wx}, {wy})"
    );
}

#[test]
fn oglplane_auto_convergence_moves_zero_parallax_onto_the_airplane() {
    // Zero parallax far behind the airplane: all of it in front, beyond budget.
    let run = oglplane(Backend::Egl, "far", &["--zero-parallax", "30"]);
    let m = measured(&run.stdout, "measured in the last frame:");
    assert!(m.max_percent < -3.0, "{}", m.line);
    // Auto-convergence measures frame 1 and converges frame 2 on the airplane.
    let run = oglplane(
        Backend::Egl,
        "auto",
        &["--zero-parallax", "30", "--auto-converge", "--frames", "2"],
    );
    let m = measured(&run.stdout, "measured in the last frame:");
    assert!(
        m.min_percent < 0.0 && m.max_percent > 0.0 && m.min_percent > -3.0 && m.max_percent < 3.0,
        "the converged airplane straddles the screen within budget: {}",
        m.line
    );
    // The plane it chose lies inside the airplane's depth range.
    let line = run
        .stdout
        .lines()
        .find(|l| l.starts_with("centre of interest"))
        .unwrap();
    let d: f64 = line.split_whitespace().nth(5).unwrap().parse().unwrap();
    assert!(
        d > m.nearest && d < m.farthest && (d - CAMERA_DISTANCE).abs() < 1.0,
        "{line}; {m:?}"
    );
}

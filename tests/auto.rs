//! Automatic stereo (glstereo-run --auto, issue 23) of unmodified mono
//! programs, against an oracle: tests/c/auto_oracle.c draws one scene as a
//! mono program (under the layer, whose captures are the eyes), and draws
//! each eye itself with 3D Vision's rule applied by hand to its projection
//! (without the layer, read back by the program). The eyes must be those
//! pixel for pixel, in a compatibility context (fixed function: immediate
//! mode, client arrays, a display list, glRectf, lighting, bitmaps,
//! glDrawPixels, an orthographic HUD) and in a core one (one shader
//! program; glDrawArrays, glDrawElements, instanced and multi draws).
//! Without --auto the same program is left alone.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::clients::build_once;
use common::preload::{built, compile_plain, grab_ready};
use common::xvfb::Xvfb;
use glstereo::image::Image;

const W: u32 = 200;
const H: u32 = 150;
/// The settings of the runs: the largest separation (s = 0.07) and the
/// convergence at w = 4, so near and far objects move visibly.
const SEPARATION: &str = "100";
const CONVERGENCE: &str = "4";

fn oracle() -> PathBuf {
    build_once("auto_oracle", |out| {
        compile_plain(
            &common::root().join("tests/c/auto_oracle.c"),
            out,
            &["-lGL", "-lX11", "-lm"],
        )
    })
}

/// The eyes glstereo-run --auto makes of the mono program (its captures),
/// and its stdout. `in_place`: the eyes' layers share their memory with
/// the textures presentation reads (llvmpipe), else they are copied.
fn under_auto(x: &Xvfb, profile: &str, dir: &Path, in_place: bool) -> ([Image; 2], String) {
    run_auto(
        x,
        &["--separation", SEPARATION, "--convergence", CONVERGENCE],
        &[profile, "mono"],
        dir,
        in_place,
    )
}

/// The eyes and stdout of the oracle run with `args` under
/// `glstereo-run --auto FLAGS --capture DIR`.
fn run_auto(
    x: &Xvfb,
    flags: &[&str],
    args: &[&str],
    dir: &Path,
    in_place: bool,
) -> ([Image; 2], String) {
    let o = common::run_ok(
        Command::new(&built().run)
            .env("GLSTEREO_EYE_MEMORY", if in_place { "1" } else { "0" })
            .arg("--auto")
            .args(flags)
            .arg("--capture")
            .arg(dir)
            .arg(oracle())
            .args(args)
            .env("DISPLAY", &x.display),
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !stderr.contains("glstereo:"),
        "the layer complained: {stderr}"
    );
    let eyes = ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-000001.png"))));
    (eyes, String::from_utf8_lossy(&o.stdout).into_owned())
}

/// One of our C clients (tests/c/NAME.c, linked with libGL and Xlib),
/// built once.
fn client(name: &str) -> PathBuf {
    build_once(name, |out| {
        compile_plain(
            &common::root().join(format!("tests/c/{name}.c")),
            out,
            &["-lGL", "-lX11"],
        )
    })
}

/// `exe args` under `glstereo-run --auto` with the tests' separation and
/// convergence, its frame captured into `dir`: the eyes of frame 1 and
/// its stdout.
fn auto_capture(x: &Xvfb, exe: &Path, args: &[&str], dir: &Path) -> ([Image; 2], String) {
    auto_capture_in(x, ("--auto", CONVERGENCE), exe, args, dir)
}

/// [`auto_capture`] under `auto` (`--auto`, or `--auto=depth`) at
/// `convergence` (a distance, or `auto`).
fn auto_capture_in(
    x: &Xvfb,
    (auto, convergence): (&str, &str),
    exe: &Path,
    args: &[&str],
    dir: &Path,
) -> ([Image; 2], String) {
    let o = common::run_ok(
        Command::new(&built().run)
            .args([
                auto,
                "--separation",
                SEPARATION,
                "--convergence",
                convergence,
            ])
            .arg("--capture")
            .arg(dir)
            .arg(exe)
            .args(args)
            .env("DISPLAY", &x.display),
    );
    let eyes = ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-000001.png"))));
    (eyes, String::from_utf8_lossy(&o.stdout).into_owned())
}

/// The eye the program draws itself with the rule applied by hand, with
/// no layer.
fn by_hand(x: &Xvfb, profile: &str, eye: &str, dir: &Path) -> Image {
    let out = dir.join(format!("hand-{eye}.rgba"));
    common::run_ok(
        Command::new(oracle())
            .args([profile, eye, SEPARATION, CONVERGENCE])
            .arg(&out)
            .env("DISPLAY", &x.display),
    );
    Image::from_pixels(W, H, std::fs::read(&out).unwrap()).unwrap()
}

fn differing(a: &Image, b: &Image) -> Vec<(u32, u32, [u8; 4], [u8; 4])> {
    let mut d = Vec::new();
    for y in 0..H {
        for x in 0..W {
            let (p, q) = (a.get(x, y), b.get(x, y));
            if (0..3).any(|c| p[c].abs_diff(q[c]) > 2) {
                d.push((x, y, p, q));
            }
        }
    }
    d
}

/// The centre of the pixels of `colour` (None: none of it).
fn centre(img: &Image, colour: [u8; 3]) -> Option<(f64, f64)> {
    let (mut sx, mut sy, mut n) = (0.0, 0.0, 0.0);
    for y in 0..img.height() {
        for x in 0..img.width() {
            let p = img.get(x, y);
            if p[..3] == colour {
                sx += x as f64;
                sy += y as f64;
                n += 1.0;
            }
        }
    }
    (n > 0.0).then(|| (sx / n, sy / n))
}

/// The scene's objects: colour, clip w (None: the HUD, w = 1).
const OBJECTS_LEGACY: [([u8; 3], Option<f64>); 5] = [
    ([255, 0, 0], Some(2.0)),
    ([255, 255, 0], Some(4.0)),
    ([0, 255, 0], Some(8.0)),
    ([0, 0, 255], Some(6.0)),
    ([255, 255, 255], None),
];

/// The eyes differ by horizontal shifts only, each object's by the
/// parallax the rule gives its depth: s·(1 − C/w)·W pixels (right eye
/// minus left), negative for near objects (w < C), zero at the
/// convergence and for the HUD, positive for far ones.
fn check_parallax(eyes: &[Image; 2], objects: &[([u8; 3], Option<f64>)], what: &str) {
    check_parallax_at(eyes, objects, CONVERGENCE.parse().unwrap(), 0.5, what);
}

/// [`check_parallax`] with convergence `c`, the centres' rows within
/// `dy` (an object the HUD covers in part moves its centre when it
/// moves).
fn check_parallax_at(
    eyes: &[Image; 2],
    objects: &[([u8; 3], Option<f64>)],
    c: f64,
    dy: f64,
    what: &str,
) {
    let s = 0.07 * SEPARATION.parse::<f64>().unwrap() / 100.0;
    for &(colour, w) in objects {
        let l = centre(&eyes[0], colour).unwrap_or_else(|| panic!("{what}: no {colour:?} left"));
        let r = centre(&eyes[1], colour).unwrap_or_else(|| panic!("{what}: no {colour:?} right"));
        let want = w.map_or(0.0, |w| s * (1.0 - c / w) * W as f64);
        assert!(
            (r.0 - l.0 - want).abs() < 1.0 && (r.1 - l.1).abs() < dy,
            "{what}: the {colour:?} object (w {w:?}) moved by ({:.2}, {:.2}) from the left eye \
             to the right, want ({want:.2}, 0)",
            r.0 - l.0,
            r.1 - l.1
        );
    }
}

fn compare_with_the_oracle(profile: &str, objects: &[([u8; 3], Option<f64>)]) {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    let dir = common::scratch(&format!("auto-{profile}"));
    let hand = ["left", "right"].map(|eye| by_hand(&x, profile, eye, &dir));
    let copied = common::scratch(&format!("auto-{profile}-copied"));
    let (eyes, stdout) = under_auto(&x, profile, &dir, true);
    let (eyes_copied, _) = under_auto(&x, profile, &copied, false);
    for (n, eye) in ["left", "right"].into_iter().enumerate() {
        for (how, got) in [("in place", &eyes[n]), ("copied", &eyes_copied[n])] {
            let d = differing(got, &hand[n]);
            assert!(
                d.is_empty(),
                "{profile}, {eye} eye ({how}): {} pixels differ from the eye drawn by hand, \
                 e.g. (x, y, --auto, by hand) {:?}",
                d.len(),
                &d[..d.len().min(8)]
            );
        }
    }
    assert!(
        differing(&eyes[0], &eyes[1]).len() > 500,
        "{profile}: the eyes are alike"
    );
    check_parallax(&eyes, objects, profile);
    // glReadPixels reads the left eye (seed 004), as the mono program
    // would read its one buffer; the program saw no GL error.
    let p = eyes[0].get(50, H - 1 - 75);
    assert!(
        stdout.contains(&format!("read {} {} {}\n", p[0], p[1], p[2])),
        "{profile}: glReadPixels gave {stdout:?}, the left eye has {p:?}"
    );
    assert!(stdout.contains("error 0x0"), "{profile}: {stdout}");
}

#[test]
fn a_mono_fixed_function_program_under_auto_equals_each_eye_drawn_by_hand() {
    compare_with_the_oracle("legacy", &OBJECTS_LEGACY);
}

/// The core scene's objects, as [`OBJECTS_LEGACY`].
const OBJECTS_CORE: [([u8; 3], Option<f64>); 5] = [
    ([255, 0, 0], Some(2.0)),
    ([255, 255, 0], Some(4.0)),
    ([0, 255, 0], Some(8.0)),
    ([0, 0, 255], Some(6.0)),
    ([255, 255, 255], None),
];

#[test]
fn a_mono_core_profile_program_under_auto_equals_each_eye_drawn_by_hand() {
    compare_with_the_oracle("core", &OBJECTS_CORE);
}

/// With no convergence given, automatic stereo converges where the
/// viewer looks: at the first present it measures the left eye's depth in
/// the middle of the view and puts the screen at the median distance
/// there. The first frame is drawn at convergence 0 (every object shifted
/// alike, as NV_3dvision_settings starts); the next ones have the object
/// in the middle at the screen, nearer ones in front of it and farther
/// ones behind, each by the parallax the rule gives its depth.
#[test]
fn automatic_convergence_puts_the_middle_of_the_view_at_the_screen() {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    for profile in ["legacy", "core"] {
        converges_at_the_middle(&x, profile, &[], "converge");
    }
}

/// Runs the oracle's `profile` scene for 32 frames (drawn as `how`
/// says: [] into the window, ["blit"] off screen and blitted) under
/// `--auto -v` and checks that the convergence said is one of the
/// scene's distances, said once (measured again, it stays), and frames 2,
/// 3 and 32 have each object's parallax.
fn converges_at_the_middle(x: &Xvfb, profile: &str, how: &[&str], name: &str) {
    let dir = common::scratch(&format!("auto-{name}-{profile}"));
    let o = common::run_ok(
        Command::new(&built().run)
            .args(["--auto", "-v", "--separation", SEPARATION, "--capture"])
            .arg(&dir)
            .arg(oracle())
            .args([profile, "mono"])
            .args(how)
            // Frame 31 (index 30) is measured again.
            .args(["frames", "32"])
            .env("DISPLAY", &x.display),
    );
    let what = format!("{profile} {how:?}");
    let stderr = String::from_utf8_lossy(&o.stderr);
    let c: f64 = stderr
        .lines()
        .find_map(|l| l.strip_prefix("glstereo: automatic convergence at "))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("{what}: no automatic convergence said: {stderr}"));
    let objects: &[([u8; 3], Option<f64>)] = if profile == "legacy" {
        &OBJECTS_LEGACY
    } else {
        &OBJECTS_CORE
    };
    // The median distance in the middle of the program's own view is a
    // distance the scene has there: one of its flat objects', or (legacy)
    // its lit quads' at 3 and its textured ones' at 5.
    let others: &[f64] = if profile == "legacy" {
        &[3.0, 5.0]
    } else {
        &[]
    };
    assert!(
        objects
            .iter()
            .filter_map(|&(_, w)| w)
            .chain(others.iter().copied())
            .any(|w| (w - c).abs() < 1e-2),
        "{what}: converged at {c}, no object is at that distance"
    );
    // Measured again at that convergence, the centre stays (the eye's
    // pixels are put back where the program's view has them): said once.
    let said = stderr
        .lines()
        .filter(|l| l.starts_with("glstereo: automatic convergence at "))
        .count();
    assert_eq!(said, 1, "{what}: the convergence moved: {stderr}");
    let eyes =
        |n: u32| ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-{n:06}.png"))));
    // Frame 1, at convergence 0, is the whole picture shifted (its
    // objects partly out of the window): not the frames after.
    let first = eyes(1);
    assert!(
        differing(&first[1], &eyes(2)[1]).len() > 100,
        "{what}: the first frame's right eye is the converged one's"
    );
    for n in [2, 3, 32] {
        check_parallax_at(&eyes(n), objects, c, 1.0, &format!("{what}, frame {n}"));
    }
}

/// A frame drawn into a framebuffer object of the window's size and
/// blitted into the window (as VTK shows its scene) is in stereo: each
/// eye of the window equals the eye drawn by hand, pixel for pixel; and
/// automatic convergence measures it in the framebuffer object.
#[test]
fn a_scene_drawn_off_screen_and_blitted_into_the_window_is_in_stereo() {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    for profile in ["legacy", "core"] {
        let dir = common::scratch(&format!("auto-blit-{profile}"));
        let hand = ["left", "right"].map(|eye| by_hand(&x, profile, eye, &dir));
        let blitted = common::scratch(&format!("auto-blit-{profile}-run"));
        let (eyes, stdout) = run_auto(
            &x,
            &["--separation", SEPARATION, "--convergence", CONVERGENCE],
            &[profile, "mono", "blit"],
            &blitted,
            true,
        );
        for (n, eye) in ["left", "right"].into_iter().enumerate() {
            let d = differing(&eyes[n], &hand[n]);
            assert!(
                d.is_empty(),
                "{profile}, {eye} eye: {} pixels differ from the eye drawn by hand, e.g. {:?}",
                d.len(),
                &d[..d.len().min(8)]
            );
        }
        assert!(stdout.contains("error 0x0"), "{profile}: {stdout}");
        // Its window's depth is never written (the scene's depth is the
        // framebuffer object's): automatic convergence measures the
        // stereoized framebuffer object's left depth instead, and
        // converges as for a scene drawn into the window.
        converges_at_the_middle(&x, profile, &["blit"], "converge-blit");
    }
}

/// Each automatic-stereo context's eyes go with it: forty contexts made,
/// drawn and destroyed keep memfd mappings, file descriptors and resident
/// memory flat (before: 2 memfd mappings and ~1.2 MB a 320x240 context),
/// under both kinds of automatic stereo; under --auto=depth each frame's
/// backdrop, drawn with the depth test off, writes its depth beside the
/// eyes (the depth array's second layer), which goes with them too.
#[test]
fn automatic_stereo_contexts_made_and_destroyed_leave_nothing_behind() {
    let _one = common::clients::one_renderer_at_a_time();
    let exe = client("auto_churn");
    let x = Xvfb::start(W + 40, H + 40);
    for auto in ["--auto", "--auto=depth"] {
        let o = common::run_ok(
            Command::new(&built().run)
                .arg(auto)
                .arg(&exe)
                .env("DISPLAY", &x.display),
        );
        let stdout = String::from_utf8_lossy(&o.stdout);
        let sample = |n: u32| -> [i64; 3] {
            let l = stdout
                .lines()
                .find_map(|l| l.strip_prefix(&format!("sample {n} ")))
                .unwrap_or_else(|| panic!("{auto}: no sample {n}: {stdout}"));
            let v: Vec<i64> = l.split_whitespace().map(|v| v.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        };
        let (warm, end) = (sample(10), sample(40));
        assert_eq!(warm[1], end[1], "{auto}: memfd mappings grew: {stdout}");
        assert_eq!(warm[2], end[2], "{auto}: file descriptors grew: {stdout}");
        assert!(
            end[0] - warm[0] < 10_000,
            "{auto}: resident memory grew by {} kB over 30 contexts: {stdout}",
            end[0] - warm[0]
        );
    }
}

/// Transform feedback captures what the mono program captures: each
/// vertex once and unshifted (the draw once with rasterizer discard, then
/// both eyes with the capture paused), a draw under rasterizer discard
/// once; the primitives-written query counts the mono draws; the window
/// still shows the triangle in stereo.
#[test]
fn transform_feedback_captures_the_mono_draws_once() {
    let _one = common::clients::one_renderer_at_a_time();
    let exe = client("auto_feedback");
    let x = Xvfb::start(W + 40, H + 40);
    let plain = common::run_ok(Command::new(&exe).env("DISPLAY", &x.display));
    let plain = String::from_utf8_lossy(&plain.stdout).into_owned();
    assert!(plain.contains("written 2\n"), "without the layer: {plain}");
    // Both kinds: two rendered eyes, and eyes made from one render.
    let dir = common::scratch("auto-feedback");
    let (eyes, auto) = auto_capture(&x, &exe, &[], &dir);
    assert_eq!(
        auto, plain,
        "the capture under --auto is not the mono program's"
    );
    assert!(
        differing(&eyes[0], &eyes[1]).len() > 100,
        "the triangle is not in stereo while captured"
    );
    // The program writes clip coordinates itself: eyes made from depth
    // cannot turn its depth into a distance, so they take automatic
    // convergence's, which puts its one triangle at the screen. The
    // capture is the mono program's, and both eyes show the triangle.
    let dir = common::scratch("auto-feedback-depth");
    let (eyes, depth) = auto_capture_in(&x, ("--auto=depth", "auto"), &exe, &[], &dir);
    assert_eq!(
        depth, plain,
        "the capture under --auto=depth is not the mono program's"
    );
    for (eye, img) in ["left", "right"].iter().zip(&eyes) {
        let yellow = common::clients::count(img, |p| p[0] > 200 && p[1] > 200 && p[2] < 60);
        assert!(yellow > 100, "--auto=depth: no triangle in the {eye} eye");
    }
}

/// A program that knows 3D Vision tunes itself (NV_3dvision_settings,
/// seed 004): its glStereoParameterfNV separation and convergence give
/// the eyes the rule gives by hand, glGetFloatv and glIsEnabled answer
/// what it set, bad values raise the extension's errors, and
/// glDisable(GL_3DVISION_STEREO_NV) makes both eyes the mono picture.
#[test]
fn a_program_sets_separation_and_convergence_itself_and_turns_stereo_off() {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    for profile in ["legacy", "core"] {
        let dir = common::scratch(&format!("auto-nv-{profile}"));
        let hand = ["left", "right"].map(|eye| by_hand(&x, profile, eye, &dir));
        let tuned = common::scratch(&format!("auto-nv-{profile}-tuned"));
        // The user's defaults (separation 15) are what the program changes.
        let (eyes, stdout) = run_auto(
            &x,
            &[],
            &[profile, "tuned", SEPARATION, CONVERGENCE],
            &tuned,
            true,
        );
        assert!(
            stdout.contains(&format!("nv {SEPARATION} {CONVERGENCE} 1 0x501 0x500\n")),
            "{profile}: the settings read back as {stdout:?}"
        );
        for (n, eye) in ["left", "right"].into_iter().enumerate() {
            let d = differing(&eyes[n], &hand[n]);
            assert!(
                d.is_empty(),
                "{profile}, {eye} eye: {} pixels differ from the eye drawn by hand with the \
                 program's settings, e.g. {:?}",
                d.len(),
                &d[..d.len().min(8)]
            );
        }
        let off = common::scratch(&format!("auto-nv-{profile}-off"));
        let (eyes, stdout) = run_auto(&x, &[], &[profile, "off"], &off, true);
        assert!(stdout.contains("nv-off 0\n"), "{profile}: {stdout:?}");
        assert!(
            differing(&eyes[0], &eyes[1]).is_empty(),
            "{profile}: with GL_3DVISION_STEREO_NV disabled the eyes differ"
        );
        assert!(
            differing(&eyes[0], &hand[0]).len() > 100,
            "{profile}: the disabled eyes are the shifted ones"
        );
    }
}

/// Without --auto the mono program's window holds exactly what it holds
/// without the layer, and nothing is captured (no stereo context).
#[test]
fn without_auto_a_mono_program_is_left_alone() {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    for profile in ["legacy", "core"] {
        let dir = common::scratch(&format!("auto-off-{profile}"));
        let mut layered = Command::new(&built().run);
        layered
            .arg("--capture")
            .arg(&dir)
            .arg(oracle())
            .args([profile, "mono", "wait"])
            .env("DISPLAY", &x.display);
        let (with, _, stderr) = grab_ready(layered, &x.display);
        assert!(!stderr.contains("glstereo:"), "{stderr}");
        let mut plain = Command::new(oracle());
        plain
            .args([profile, "mono", "wait"])
            .env("DISPLAY", &x.display);
        let (without, _, _) = grab_ready(plain, &x.display);
        assert_eq!(
            differing(&with, &without).len(),
            0,
            "{profile}: the window differs under glstereo-run without --auto"
        );
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            0,
            "{profile}: frames were captured without --auto"
        );
    }
}

/// Under --auto the window shows both eyes in the format asked for:
/// side-by-side (the 2W x H composite scaled by 1/2, centred) holds the
/// captured eyes half by half.
#[test]
fn the_window_shows_both_eyes_in_the_format_asked_for() {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    let dir = common::scratch("auto-window");
    let mut cmd = Command::new(&built().run);
    cmd.args(["--auto", "-m", "side-by-side"])
        .args(["--separation", SEPARATION, "--convergence", CONVERGENCE])
        .arg("--capture")
        .arg(&dir)
        .arg(oracle())
        .args(["legacy", "mono", "wait"])
        .env("DISPLAY", &x.display);
    let (shot, _, stderr) = grab_ready(cmd, &x.display);
    assert!(!stderr.contains("glstereo:"), "{stderr}");
    let composite = common::png(&dir.join("composite-000001.png"));
    assert_eq!((composite.width(), composite.height()), (2 * W, H));
    let eyes = ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-000001.png"))));
    for (half, eye) in eyes.iter().enumerate() {
        for y in 0..H {
            for x in 0..W {
                assert_eq!(
                    composite.get(half as u32 * W + x, y),
                    eye.get(x, y),
                    "composite ({x}, {y}) of eye {half}"
                );
            }
        }
    }
    // The window: the composite scaled to W x H/2, rows H/4..3H/4. Flat
    // areas (the HUD bar, the background) match the eyes there.
    let bar = shot.get(25 / 2, H / 4 + (H - 10) / 2);
    assert_eq!(bar[..3], [255, 255, 255], "the HUD bar in the left half");
    let bar = shot.get(W / 2 + 25 / 2, H / 4 + (H - 10) / 2);
    assert_eq!(bar[..3], [255, 255, 255], "the HUD bar in the right half");
}

/// Queries count what the mono program's draws produce, not the second
/// eye's (issue 23 item 4): samples passed (one draw and three in one
/// query), primitives generated, any samples passed of a hidden and a seen
/// quad, their availability, and conditional rendering on them — the same
/// lines as without the layer (the counted quads sit at the convergence,
/// where both eyes have them as mono does).
#[test]
fn queries_count_the_mono_draws_once() {
    let _one = common::clients::one_renderer_at_a_time();
    let exe = client("auto_queries");
    let x = Xvfb::start(W + 40, H + 40);
    let plain = common::run_ok(Command::new(&exe).env("DISPLAY", &x.display));
    let plain = String::from_utf8_lossy(&plain.stdout).into_owned();
    assert!(
        plain.contains("primitives 5\n") && plain.contains("any-hidden 0\n"),
        "without the layer: {plain}"
    );
    for kind in ["--auto", "--auto=depth"] {
        let dir = common::scratch(&format!("auto-queries{kind}"));
        let (eyes, auto) = auto_capture_in(&x, (kind, CONVERGENCE), &exe, &[], &dir);
        assert_eq!(
            auto, plain,
            "the counts under {kind} are not the mono program's"
        );
        // Both eyes were drawn: the background (w = 8) is shifted between them.
        assert!(
            differing(&eyes[0], &eyes[1]).len() > 100,
            "{kind}: the eyes are alike"
        );
    }
}

/// The first and last column of row `y` of `img` holding `colour`.
fn run_of(img: &Image, y: u32, colour: [u8; 3]) -> Option<(u32, u32)> {
    let xs: Vec<u32> = (0..img.width())
        .filter(|&x| img.get(x, y)[..3] == colour)
        .collect();
    Some((*xs.first()?, *xs.last()?))
}

/// Draws with the depth test off under `--auto=depth` (tests/c/
/// auto_depth_off.c): the layer draws them with a depth layer of its own
/// attached, so each is at its depth in the eyes made from the frame —
/// the red quad (w 2, drawn with the test off, half over the background
/// and half over nothing) moves by its own parallax, not the
/// background's nor the screen's — while the program sees the GL it
/// would see without the layer: its depth state after the draw, its
/// samples passed, the depth and colours it reads back (the blue quad
/// drawn after with the test on is tested against the program's depth,
/// not the red quad's), no error. The same whether the quads are drawn
/// by a GLSL program, with glBegin/glEnd or from display lists.
#[test]
fn draws_with_the_depth_test_off_are_at_their_depth_under_auto_depth_unseen_by_the_program() {
    let _one = common::clients::one_renderer_at_a_time();
    let exe = client("auto_depth_off");
    let x = Xvfb::start(W + 40, H + 40);
    for mode in ["shader", "immediate", "list"] {
        depth_off_in(&x, &exe, mode);
    }
}

/// [`draws_with_the_depth_test_off_are_at_their_depth_under_auto_depth_unseen_by_the_program`]
/// with the quads drawn in `mode` (a GLSL program; glBegin/glEnd; display lists).
fn depth_off_in(x: &Xvfb, exe: &Path, mode: &str) {
    let plain = common::run_ok(Command::new(exe).arg(mode).env("DISPLAY", &x.display));
    let plain = String::from_utf8_lossy(&plain.stdout).into_owned();
    assert!(
        plain.contains("depth 140 90 4294967295\n")
            && plain.contains("pixel 90 95 0 0 255\n")
            && plain.matches("error 0x0\n").count() == 2,
        "{mode}, without the layer: {plain}"
    );
    let dir = common::scratch(&format!("auto-depth-off-{mode}"));
    let (eyes, ours) = auto_capture_in(x, ("--auto=depth", CONVERGENCE), exe, &[mode], &dir);
    // Every line Mesa's, the depths read back to their last bit (the
    // visual's 32: the layer's depth buffer has the visual's bits).
    assert_eq!(ours, plain, "{mode} under --auto=depth, then without");
    // Parallax, right eye minus left: s·(1 − C/w)·W pixels.
    let s = 0.07 * SEPARATION.parse::<f64>().unwrap() / 100.0;
    let c: f64 = CONVERGENCE.parse().unwrap();
    let want = |w: f64| s * (1.0 - c / w) * W as f64;
    // Rows (from the top) where each quad is alone: the red quad's top
    // rows (above the blue one), the background below both (its right
    // edge: its left is the window's). Not the blue quad: drawn over the
    // nearer red one (which wrote no depth of the program's), it takes
    // the nearer depth there, as the README says.
    for (name, colour, y, w, edges) in [
        ("red (w 2, test off)", [255, 0, 0], 40, 2.0, [true, true]),
        ("green (w 8)", [0, 255, 0], 130, 8.0, [false, true]),
    ] {
        let (l, r) = (run_of(&eyes[0], y, colour), run_of(&eyes[1], y, colour));
        let (Some(l), Some(r)) = (l, r) else {
            panic!("{mode} {name}: not in both eyes at row {y}");
        };
        let shifts = [r.0 as f64 - l.0 as f64, r.1 as f64 - l.1 as f64];
        for (shift, measured) in shifts.iter().zip(edges) {
            assert!(
                !measured || (shift - want(w)).abs() <= 1.5,
                "{mode} {name}: moved {shifts:?} from the left eye to the right, want {:.1}",
                want(w)
            );
        }
    }
}

/// A program that clears its depth in the middle of a frame
/// (tests/c/auto_depth_cleared.c), by glClear, glClearBufferfv and
/// glClearNamedFramebufferfv. After a draw with the depth test off (which
/// `--auto=depth` makes with a depth layer of its own attached), the
/// clear clears the program's depth: its later draws and reads are
/// Mesa's under both kinds of automatic stereo (before: the clear went to
/// the other layer and the program saw its older depth hide the green
/// quad). After the scene, then a gizmo in perspective in a corner
/// viewport (VTK's orientation axes): under `--auto=depth` the scene
/// keeps its depth (copied before the clear) and its parallax, as
/// `--auto` draws it, in the window and in a render target blitted into
/// it (as VTK 9 draws), and the gizmo stays at the screen in both (before:
/// the gizmo was taken for the scene and the frame was flat; drawn into
/// a render target, it moved with the scene behind it). A flat pass over
/// the whole render target after the scene is no overlay: the frame keeps
/// its parallax.
#[test]
fn a_depth_clear_in_the_frame_clears_the_programs_depth_and_keeps_the_scenes_eyes() {
    let _one = common::clients::one_renderer_at_a_time();
    let exe = client("auto_depth_cleared");
    let x = Xvfb::start(W + 40, H + 40);
    for how in ["clear", "clearbuffer", "named"] {
        let plain = common::run_ok(
            Command::new(&exe)
                .args([how, "beside"])
                .env("DISPLAY", &x.display),
        );
        let plain = String::from_utf8_lossy(&plain.stdout).into_owned();
        assert!(
            plain.starts_with("centre 0 255 0\n") && plain.ends_with("error 0x0\n"),
            "{how}, without the layer: {plain}"
        );
        for auto in ["--auto", "--auto=depth"] {
            let dir = common::scratch(&format!("auto-depth-cleared-{how}{auto}"));
            let (_, ours) = auto_capture_in(&x, (auto, CONVERGENCE), &exe, &[how, "beside"], &dir);
            assert_eq!(ours, plain, "{how} under {auto}, then without the layer");
        }
        for what in ["gizmo", "scissored", "target", "pass"] {
            let eyes = ["--auto", "--auto=depth"].map(|auto| {
                let dir = common::scratch(&format!("auto-depth-cleared-{how}-{what}{auto}"));
                auto_capture_in(&x, (auto, CONVERGENCE), &exe, &[how, what], &dir).0
            });
            // The red quad (w 2) in the middle row: its edges move by
            // s·(1 − C/w)·W = −14 pixels under --auto. (The pass adds 32
            // of blue to every pixel: it is no overlay, and the frame
            // keeps its depth.)
            let red = if what == "pass" {
                [255, 0, 32]
            } else {
                [255, 0, 0]
            };
            let shift = |[l, r]: &[Image; 2]| {
                let (a, b) = (run_of(l, H / 2, red), run_of(r, H / 2, red));
                let (Some(a), Some(b)) = (a, b) else {
                    panic!("{how} {what}: the red quad is not in both eyes");
                };
                [b.0 as i64 - a.0 as i64, b.1 as i64 - a.1 as i64]
            };
            let (truth, made) = (shift(&eyes[0]), shift(&eyes[1]));
            assert!(
                truth.iter().all(|&s| (s + 14).abs() <= 1)
                    && truth.iter().zip(made).all(|(t, m)| (t - m).abs() <= 1),
                "{how} {what}: the red quad moved {made:?} under --auto=depth, {truth:?} under --auto"
            );
            if what == "pass" {
                continue;
            }
            // The gizmo (white, bottom right) at the screen in both eyes,
            // drawn into the window or into a render target blitted into it
            // (before: there, it moved with the scene behind it).
            let y = H - 25;
            let [l, r] = &eyes[1];
            let (a, b) = (run_of(l, y, [255, 255, 255]), run_of(r, y, [255, 255, 255]));
            assert!(
                a.is_some() && a == b,
                "{how} {what}: the gizmo at {a:?} in the left eye, {b:?} in the right"
            );
            // Its label (cyan, flat) too.
            let y = H - 6;
            let (a, b) = (run_of(l, y, [0, 255, 255]), run_of(r, y, [0, 255, 255]));
            assert!(
                a.is_some() && a == b,
                "{how} {what}: the label at {a:?} in the left eye, {b:?} in the right"
            );
        }
    }
}

/// A square render target of another size than the window is seen from
/// a light (a shadow or reflection map): drawn in perspective, it stays
/// one picture both eyes show; a target of the window's size drawn in
/// perspective gets eyes. The same program shows its target's picture
/// (a red quad at w = 2) on a quad of the window at the convergence
/// (w = 4): a 64x64 target gives both eyes the same pixels there, a
/// window-sized one shifts the red quad between the eyes.
#[test]
fn square_targets_seen_from_a_light_stay_mono_and_window_sized_ones_get_eyes() {
    let _one = common::clients::one_renderer_at_a_time();
    let exe = client("auto_targets");
    let x = Xvfb::start(W + 40, H + 40);
    for (size, stereo) in [("small", false), ("window", true)] {
        let dir = common::scratch(&format!("auto-targets-{size}"));
        let (eyes, stdout) = auto_capture(&x, &exe, &[size], &dir);
        assert!(stdout.contains("error 0x0"), "{size}: {stdout}");
        let red = centre(&eyes[0], [255, 0, 0]).unwrap_or_else(|| panic!("{size}: no red left"));
        let right = centre(&eyes[1], [255, 0, 0]).unwrap_or_else(|| panic!("{size}: no red right"));
        let d = differing(&eyes[0], &eyes[1]).len();
        if stereo {
            // Near (w = 2 < C = 4): the right eye's red is to the left, by
            // its parallax in the target, which the window's quad shows at
            // 0.6 of its width (x = ±2.4 at w = 4 of a ±1 frustum).
            let s = 0.07 * SEPARATION.parse::<f64>().unwrap() / 100.0;
            let want = s * (1.0 - 4.0 / 2.0) * W as f64 * 0.6;
            assert!(
                (right.0 - red.0 - want).abs() < 1.0,
                "{size}: red moved by {:.2}, want {want:.2}",
                right.0 - red.0
            );
        } else {
            assert_eq!(d, 0, "{size}: the eyes differ in {d} pixels");
            assert_eq!(red, right, "{size}: the red quad moved");
        }
    }
}

/// Render targets by data flow (tests/c/auto_passes.c): a mono program's
/// scene reaches the window through framebuffer objects of its own — a
/// half-size copy, a G-buffer with a depth texture sampled later, a
/// multisample target and its resolve blit, ping-pong blurs, mipmaps, a
/// glCopyTexSubImage2D and a blit between targets, glCopyImageSubData of a
/// depth texture and of a colour rectangle, a regions texture not
/// redrawn in the second frame — and each eye equals the program's own
/// frame drawn with the rule applied by hand to its camera (never to the
/// light of its shadow map, never to its full-screen passes).
#[test]
fn render_targets_get_eyes_where_stereo_flows_each_eye_as_drawn_by_hand() {
    passes_as_drawn_by_hand(&client("auto_passes"), "glx");
}

/// The same program in OpenGL ES 3.2 through EGL (tests/c/auto_passes.c
/// built with -DGLES): ES has no direct state access, so the layer gives
/// its targets eyes by binding and binding back, naming each texture by
/// the target the program defined it with — and each eye is again the
/// eye drawn by hand, pixel for pixel, in every case.
#[test]
fn opengl_es_render_targets_get_eyes_where_stereo_flows_each_eye_as_drawn_by_hand() {
    let exe = build_once("auto_passes_es", |out| {
        compile_plain(
            &common::root().join("tests/c/auto_passes.c"),
            out,
            &["-DGLES", "-lEGL", "-lGLESv2", "-lX11"],
        )
    });
    passes_as_drawn_by_hand(&exe, "es");
}

/// Every case of tests/c/auto_passes.c built as `exe`, under --auto and
/// by hand (`what` names the build in the scratch directories).
fn passes_as_drawn_by_hand(exe: &Path, what: &str) {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    let mut failures = Vec::new();
    for case in [
        "half",
        "mrt",
        "msaa",
        "pingpong",
        "mipmap",
        "copy",
        "copyimage",
        "shadow",
        "regions",
    ] {
        let dir = common::scratch(&format!("auto-passes-{what}-{case}"));
        let mut refused_by_hand = String::new();
        let hand = ["left", "right"].map(|eye| {
            let out = dir.join(format!("hand-{eye}.rgba"));
            let o = common::run_ok(
                Command::new(exe)
                    .args([case, eye, SEPARATION, CONVERGENCE])
                    .arg(&out)
                    .env("DISPLAY", &x.display),
            );
            refused_by_hand = refused(&String::from_utf8_lossy(&o.stdout));
            Image::from_pixels(W, H, std::fs::read(&out).unwrap()).unwrap()
        });
        let o = common::run_ok(
            Command::new(&built().run)
                .args([
                    "--auto",
                    "--separation",
                    SEPARATION,
                    "--convergence",
                    CONVERGENCE,
                ])
                .arg("--capture")
                .arg(&dir)
                .arg(exe)
                .args([case, "mono"])
                .env("DISPLAY", &x.display),
        );
        let (stdout, stderr) = (
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr),
        );
        if stderr.contains("glstereo:") || !stdout.contains("error 0x0") {
            failures.push(format!("{case}: {stdout} {stderr}"));
            continue;
        }
        // Copies GL refuses get GL's errors under the layer too, and
        // change nothing (the eyes are compared below).
        if refused(&stdout) != refused_by_hand
            || refused_by_hand.lines().any(|l| l.ends_with(": 0x0"))
        {
            failures.push(format!(
                "{case}: refused copies answered\n{}\nwithout the layer\n{refused_by_hand}",
                refused(&stdout)
            ));
        }
        // The second frame (the regions case draws its region only in the first).
        let eyes = ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-000002.png"))));
        for (n, eye) in ["left", "right"].into_iter().enumerate() {
            let d = differing(&eyes[n], &hand[n]);
            if !d.is_empty() {
                failures.push(format!(
                    "{case}, {eye} eye: {} pixels differ from the eye drawn by hand, \
                     e.g. (x, y, --auto, by hand) {:?}",
                    d.len(),
                    &d[..d.len().min(4)]
                ));
            }
        }
        if differing(&eyes[0], &eyes[1]).len() < 200 {
            failures.push(format!("{case}: the eyes are alike"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A program that draws on events (tests/c/auto_ubo.c gap: 1.2 s
/// without a frame, then the view twice as far away, as Blender's
/// camera view entered seconds in): the first frame after the gap is
/// measured although it is not a 30th, and the next frame converges on
/// the new centre: the middle quad, now at w = 12, at the screen.
#[test]
fn a_frame_after_a_pause_is_measured_and_the_next_converges_on_the_new_view() {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    let dir = common::scratch("auto-ubo-gap");
    let stderr = run_ubo(&x, &dir, &["4", "gap"]);
    let said = stderr
        .lines()
        .filter(|l| l.starts_with("glstereo: automatic convergence at depth"))
        .count();
    assert_eq!(said, 2, "one convergence for each view: {stderr}");
    let eyes = ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-000004.png"))));
    check_parallax_at(
        &eyes,
        &[
            ([0, 255, 0], Some(12.0)),
            ([255, 0, 0], Some(6.0)),
            ([0, 0, 255], Some(24.0)),
        ],
        12.0,
        0.5,
        "the view after the pause",
    );
}

/// The lines of a client's stdout that say what GL answered a refused
/// call.
fn refused(stdout: &str) -> String {
    stdout
        .lines()
        .filter(|l| l.contains(" refused "))
        .collect::<Vec<_>>()
        .join("\n")
}

/// tests/c/auto_ubo.c `args` under `glstereo-run --auto -v` with the
/// tests' separation, captured into `dir`: its stderr (it printed "error
/// 0x0").
fn run_ubo(x: &Xvfb, dir: &Path, args: &[&str]) -> String {
    let o = common::run_ok(
        Command::new(&built().run)
            .args(["--auto", "-v", "--separation", SEPARATION])
            .arg("--capture")
            .arg(dir)
            .arg(client("auto_ubo"))
            .args(args)
            .env("DISPLAY", &x.display),
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("error 0x0"), "{stdout}");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Automatic convergence where the camera's matrix is in a uniform buffer
/// (tests/c/auto_ubo.c), so no upload shows the projection: the centre
/// of interest is found as a depth and the rule computed from each
/// vertex's clip depth. The quad filling the middle of the view (w = 6)
/// sits at the screen, the near one (w = 3) in front, the far one
/// (w = 12) behind, each by the parallax the rule gives with C = 6
/// (the build before left C at 0: every object 14 pixels apart).
#[test]
fn automatic_convergence_finds_the_centre_where_the_matrices_are_in_a_uniform_buffer() {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    let dir = common::scratch("auto-ubo");
    run_ubo(&x, &dir, &["3"]);
    // Frame 0 is measured; the third frame is drawn with it.
    let eyes = ["left", "right"].map(|e| common::png(&dir.join(format!("{e}-000003.png"))));
    check_parallax_at(
        &eyes,
        &[
            ([0, 255, 0], Some(6.0)),
            ([255, 0, 0], Some(3.0)),
            ([0, 0, 255], Some(12.0)),
        ],
        6.0,
        0.5,
        "matrices in a uniform buffer",
    );
}

/// The share of `truth`'s pixels that `made` has within one pixel along
/// its row: the same colour (within 6 of 255 a channel) at x − 1, x or
/// x + 1, or a colour between those (an edge or a gradient sampled half a
/// pixel over).
fn found_within_a_pixel(made: &Image, truth: &Image) -> f64 {
    let (w, h) = (truth.width(), truth.height());
    let mut found = 0u32;
    for y in 0..h {
        for x in 0..w {
            let t = truth.get(x, y);
            let near: Vec<[u8; 4]> = [x.wrapping_sub(1), x, x + 1]
                .into_iter()
                .filter(|&x| x < w)
                .map(|x| made.get(x, y))
                .collect();
            let same = near
                .iter()
                .any(|p| (0..3).all(|c| p[c].abs_diff(t[c]) <= 6));
            let between = (0..3).all(|c| {
                let lo = near.iter().map(|p| p[c]).min().unwrap_or(0);
                let hi = near.iter().map(|p| p[c]).max().unwrap_or(0);
                t[c].saturating_add(6) >= lo && t[c] <= hi.saturating_add(6)
            });
            found += u32::from(same || between);
        }
    }
    f64::from(found) / f64::from(w * h)
}

/// `--auto=depth`: the program draws its frame once, and both eyes are
/// made from its colour and depth. Each eye has the pixels of the eye
/// drawn by hand (`--auto`'s truth) within one pixel along the row — at
/// least `least` of them: what the mono frame cannot show is where a
/// near object uncovers what it hid (the left eye of the fixed-function
/// scene: its red square, twice as near as the screen at the largest
/// separation, uncovers a shaded cylinder the mono frame never had) —,
/// every object moved by its parallax, the HUD (drawn with w = 1 over the
/// scene) where it is in both eyes, and glReadPixels gives what the
/// program gives without the layer: its mono frame.
fn from_depth_against_the_oracle(
    profile: &str,
    objects: &[([u8; 3], Option<f64>)],
    least: [f64; 2],
) {
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    let dir = common::scratch(&format!("auto-depth-{profile}"));
    let hand = ["left", "right"].map(|eye| by_hand(&x, profile, eye, &dir));
    let (eyes, stdout) = run_auto(
        &x,
        &[
            "--auto=depth",
            "--separation",
            SEPARATION,
            "--convergence",
            CONVERGENCE,
        ],
        &[profile, "mono"],
        &dir,
        true,
    );
    for (n, eye) in ["left", "right"].into_iter().enumerate() {
        let share = found_within_a_pixel(&eyes[n], &hand[n]);
        assert!(
            share >= least[n],
            "{profile}, {eye} eye from depth: {:.2} % of the pixels drawn by hand are within a \
             pixel, want {:.2} %",
            100.0 * share,
            100.0 * least[n]
        );
        let hud = |img: &Image| {
            (0..H)
                .flat_map(|y| (0..W).map(move |x| (x, y)))
                .filter(|&(x, y)| img.get(x, y)[..3] == [255, 255, 255])
                .collect::<Vec<_>>()
        };
        assert_eq!(
            hud(&eyes[n]),
            hud(&hand[n]),
            "{profile}, {eye} eye from depth: the HUD is not where the eye drawn by hand has it"
        );
    }
    check_parallax(&eyes, objects, &format!("{profile} from depth"));
    let plain = common::run_ok(
        Command::new(oracle())
            .args([profile, "mono"])
            .env("DISPLAY", &x.display),
    );
    let read = |out: &str| {
        out.lines()
            .find(|l| l.starts_with("read "))
            .map(str::to_owned)
    };
    let want = read(&String::from_utf8_lossy(&plain.stdout));
    assert!(want.is_some(), "{profile}: the program read nothing");
    assert_eq!(
        read(&stdout),
        want,
        "{profile}: glReadPixels under --auto=depth is not the mono frame's"
    );
    assert!(stdout.contains("error 0x0"), "{profile}: {stdout}");
}

/// `--auto=depth` makes the eyes as the window's composite reads them
/// where each composite row needs only its own eye rows (they are never
/// written to memory and read again), and in place first where it does
/// not (top-bottom, scaled into the window): either way the window shows
/// exactly the composite of the eyes captured from the same frame.
#[test]
fn under_auto_depth_the_window_shows_the_composite_of_the_eyes_made_from_depth() {
    use glstereo::output::{OutputMode, OutputOptions, compose_fitted};
    let _one = common::clients::one_renderer_at_a_time();
    let x = Xvfb::start(W + 40, H + 40);
    let dir = common::scratch("auto-depth-window");
    let flags = [
        "--auto=depth",
        "--separation",
        SEPARATION,
        "--convergence",
        CONVERGENCE,
    ];
    let (eyes, _) = run_auto(&x, &flags, &["legacy", "mono"], &dir, true);
    assert!(
        differing(&eyes[0], &eyes[1]).len() > 1000,
        "the captured eyes are at depth"
    );
    for mode in [
        "anaglyph-red-cyan-dubois",
        "side-by-side-half",
        "rows",
        "checkerboard",
        "right",
        "top-bottom",
    ] {
        let mut cmd = Command::new(&built().run);
        cmd.args(flags)
            .args(["-m", mode])
            .arg(oracle())
            .args(["legacy", "mono", "wait"])
            .env("DISPLAY", &x.display);
        let (shot, _, stderr) = grab_ready(cmd, &x.display);
        assert!(!stderr.contains("glstereo:"), "{mode}: {stderr}");
        let m = OutputMode::from_name(mode).expect("a mode");
        let mut want = Image::new(1, 1);
        compose_fitted(
            m,
            &OutputOptions::default(),
            &eyes[0],
            &eyes[1],
            0,
            (W, H),
            &mut want,
        )
        .expect("composed");
        let off: Vec<_> = (0..H)
            .flat_map(|y| (0..W).map(move |x| (x, y)))
            .filter(|&(x, y)| shot.get(x, y)[..3] != want.get(x, y)[..3])
            .collect();
        assert!(
            off.is_empty(),
            "{mode}: {} window pixels are not the captured eyes' composite, the first at {:?}",
            off.len(),
            off.first()
        );
    }
}

#[test]
fn a_fixed_function_program_under_auto_depth_has_each_eye_within_a_pixel_of_the_truth() {
    // Measured 98.93 % (left: the uncovered cylinder) and 99.97 %.
    from_depth_against_the_oracle("legacy", &OBJECTS_LEGACY, [0.985, 0.995]);
}

#[test]
fn a_core_profile_program_under_auto_depth_has_each_eye_within_a_pixel_of_the_truth() {
    // Measured 100 % in both eyes.
    from_depth_against_the_oracle("core", &OBJECTS_CORE, [0.995, 0.995]);
}

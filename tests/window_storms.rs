//! A stereo window resized at random under glstereo-run, frame after
//! frame, in every format that fits its composite to the window: no panic,
//! no wrong frame (tests/c/glx_resize_storm.c checks the fronts and the
//! window of each). And a fault inside the layer (a panic injected into a
//! composition with GLSTEREO_TEST_FAULT) costs that frame only: one line on
//! stderr that names it, no backtrace unless asked for, every other frame
//! right.

mod common;

use std::process::{Command, Output};

use common::clients::c_program;
use common::preload::built;
use common::xvfb::Xvfb;

/// The formats whose composite is fitted to the window (scaled, or
/// letterboxed), and the Dubois anaglyph (the window-sized kernel).
const FITTED: [&str; 5] = [
    "side-by-side",
    "top-bottom",
    "hdmi-frame-packing",
    "side-by-side-half",
    "anaglyph-red-cyan-dubois",
];

/// Frames per run (`make test`; the reproduction used 200).
const FRAMES: &str = "100";

/// Frames per run of a mono program under `--auto=depth` (10 runs).
const AUTO_FRAMES: &str = "40";

fn storm(
    x: &Xvfb,
    mode: &str,
    frames: &str,
    seed: &str,
    viewport: bool,
    env: &[(&str, &str)],
) -> Output {
    let exe = c_program("glx_resize_storm", &["-lGL", "-lX11"]);
    let viewport = if viewport { "viewport" } else { "noviewport" };
    Command::new(&built().run)
        .args(["-m", mode])
        .arg(&exe)
        .args([frames, seed, viewport, mode])
        .env("DISPLAY", &x.display)
        .env_remove("RUST_BACKTRACE")
        .env_remove("GLSTEREO_VERBOSE")
        .envs(env.iter().copied())
        .output()
        .expect("glstereo-run starts")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn a_window_resized_at_random_shows_every_frame_in_every_fitted_format() {
    let x = Xvfb::start(1700, 1300);
    for (k, mode) in FITTED.iter().enumerate() {
        for viewport in [false, true] {
            let seed = if viewport { 4242 + k } else { 777 + k };
            let out = storm(&x, mode, FRAMES, &seed.to_string(), viewport, &[]);
            let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
            let what = format!("{mode}, seed {seed}, glViewport after each resize: {viewport}");
            assert!(
                !stderr.contains("panicked") && !stderr.contains("glstereo:"),
                "{what}: the layer said\n{stderr}"
            );
            assert!(
                out.status.success() && stdout.contains(&format!("frames {FRAMES} wrong 0")),
                "{what}: {}\n{stdout}\n{stderr}",
                out.status
            );
        }
    }
}

#[test]
fn a_fault_in_a_composition_costs_its_own_frame_and_says_so_in_one_line() {
    let x = Xvfb::start(1700, 1300);
    // Composition 1 is the program's first frame, at 64x64; 3 is the
    // second frame of the storm.
    let fault = [("GLSTEREO_TEST_FAULT", "compose:3")];
    let out = storm(&x, "side-by-side", "12", "5", true, &fault);
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    let ours: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("glstereo:"))
        .collect();
    assert_eq!(ours.len(), 1, "one line from the layer:\n{stderr}");
    for words in [
        "internal error, a bug in glstereo",
        "GLSTEREO_TEST_FAULT asked composition 3 to fail",
        "src/output/gl.rs:",
        "GLSTEREO_VERBOSE=1",
    ] {
        assert!(
            ours[0].contains(words),
            "the line names the fault ({words}): {}",
            ours[0]
        );
    }
    assert!(
        !stderr.contains("stack backtrace") && !stderr.contains("RUST_BACKTRACE"),
        "no backtrace unless asked:\n{stderr}"
    );
    // The faulted frame may not reach the window (what it shows then is
    // the frame before, which may still pass the window's check); its
    // fronts do (they are flipped before the composition), and every
    // other frame is right.
    let wrong: Vec<&str> = stderr.lines().filter(|l| l.starts_with("frame ")).collect();
    assert!(
        wrong
            .iter()
            .all(|l| l.starts_with("frame 1 at ") && !l.contains("fronts")),
        "only the faulted frame (storm frame 1) may be wrong, in its window only:\n{stderr}"
    );
    assert!(
        stdout.contains(&format!("frames 12 wrong {}", wrong.len())),
        "{stdout}"
    );

    // Asked for, the panic comes with its backtrace, for a bug report.
    let out = storm(
        &x,
        "side-by-side",
        "3",
        "5",
        true,
        &[fault[0], ("GLSTEREO_VERBOSE", "1")],
    );
    let stderr = text(&out.stderr);
    assert!(
        stderr.contains("fault::inject")
            && stderr.contains("GLSTEREO_TEST_FAULT asked composition 3"),
        "GLSTEREO_VERBOSE prints the panic and its backtrace:\n{stderr}"
    );
}

/// `--auto=depth`: a mono program resized at random (1x1 to 1600x1200,
/// thin ones too) drawing a scene with depth and a HUD: both eyes made
/// from its depth at every size in every fitted format, with no panic and
/// nothing said, and its own read of its last frame is what it reads
/// without the layer (its mono frame). Its visual's 32-bit depth, and
/// once a 16-bit one: both read in place (the HUD writes no depth).
#[test]
fn a_mono_window_resized_at_random_under_auto_depth_gets_its_eyes_at_every_size() {
    let x = Xvfb::start(1700, 1300);
    let exe = c_program("auto_resize_storm", &["-lGL", "-lX11"]);
    let runs = FITTED
        .iter()
        .enumerate()
        .flat_map(|(k, mode)| ["viewport", "noviewport"].map(|v| (k, *mode, v, None)))
        .chain([(FITTED.len(), "side-by-side-half", "viewport", Some("16"))]);
    for (k, mode, viewport, bits) in runs {
        let seed = (31 + k).to_string();
        let mut args = vec![AUTO_FRAMES, seed.as_str(), viewport];
        args.extend(bits);
        let out = Command::new(&built().run)
            .args(["--auto=depth", "-m", mode])
            .arg(&exe)
            .args(&args)
            .env("DISPLAY", &x.display)
            .env_remove("GLSTEREO_VERBOSE")
            .output()
            .expect("glstereo-run starts");
        let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
        let what = format!("--auto=depth {mode}, seed {seed}, {viewport}, depth {bits:?}");
        assert!(
            !stderr.contains("panicked") && !stderr.contains("glstereo:"),
            "{what}: the layer said\n{stderr}"
        );
        assert!(
            out.status.success() && stdout.contains(&format!("frames {AUTO_FRAMES}")),
            "{what}: {}\n{stdout}\n{stderr}",
            out.status
        );
        let plain = Command::new(&exe)
            .args(&args)
            .env("DISPLAY", &x.display)
            .output()
            .expect("the program starts");
        let centre = |s: &str| {
            s.lines()
                .find(|l| l.starts_with("centre "))
                .map(str::to_owned)
        };
        assert_eq!(
            centre(&stdout),
            centre(&text(&plain.stdout)),
            "{what}: the program's read of its frame is not its mono frame's"
        );
        assert!(stdout.contains("error 0x0"), "{what}: {stdout}");
    }
}

//! zink (Mesa's GL over Vulkan, here over lavapipe: Debian's
//! mesa-vulkan-drivers), the closest thing on a machine without a GPU to
//! a hardware driver's GL. Under `LIBGL_ALWAYS_SOFTWARE=1
//! MESA_LOADER_DRIVER_OVERRIDE=zink`:
//! - the draw-buffer and core-profile conformance programs
//!   (tests/c/glx_draw_buffers.c, tests/c/glx_core_stereo.c) pass under
//!   glstereo-run, every pixel of each eye checked, and the answers that do
//!   not depend on stereo are zink's own on a mono window (Mesa 22.3's zink
//!   crashed at the first clear under GL_BACK on the emulation's sparse
//!   draw-buffer table; the gaps are filled there);
//! - zink is not taken for a software renderer (its GL_RENDERER names
//!   llvmpipe in brackets): a stereo window is composed by GL and swapped,
//!   the path of a hardware driver, and shows the CPU reference composite
//!   of the eyes it captured;
//! - the library's own surfaces (EGL) compose on GL there and give what
//!   llvmpipe gives.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use glstereo::image::Image;
use glstereo::output::{OutputMode, OutputOptions};

use common::preload::{Running, Screen, built, compile_plain};
use common::xvfb::Xvfb;

/// Sets the variables that make libGL (and libEGL) load zink over a CPU
/// Vulkan device, with a private runtime directory (lavapipe's window
/// system code complains without one).
fn zink(cmd: &mut Command) -> &mut Command {
    let runtime = common::lib_dir().join("test-zink-runtime");
    std::fs::create_dir_all(&runtime).unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&runtime, std::fs::Permissions::from_mode(0o700)).unwrap();
    cmd.env("LIBGL_ALWAYS_SOFTWARE", "1")
        .env("MESA_LOADER_DRIVER_OVERRIDE", "zink")
        .env("XDG_RUNTIME_DIR", runtime)
        .env_remove("LD_PRELOAD")
        .env_remove("GLSTEREO_CAPTURE_DIR")
        .env_remove("GLSTEREO_MODE")
}

/// Fails with what to install unless GLX on `display` is zink.
fn require_zink(display: &str) {
    let out = zink(Command::new("glxinfo").arg("-B").env("DISPLAY", display))
        .output()
        .expect("glxinfo runs (package mesa-utils)");
    let info = String::from_utf8_lossy(&out.stdout);
    assert!(
        info.contains("OpenGL renderer string: zink"),
        "zink is not available: install mesa-vulkan-drivers (Debian); glxinfo said:\n{info}{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// tests/c/NAME.c linked with -lGL -lX11 only.
fn program(name: &str) -> PathBuf {
    let dir = common::scratch(&format!("zink_{name}"));
    let exe = dir.join(name);
    compile_plain(
        &common::root().join("tests/c").join(format!("{name}.c")),
        &exe,
        &["-lGL", "-lX11"],
    );
    exe
}

/// Runs `exe arg` on zink (under glstereo-run when `layer`); its stdout,
/// failing unless it exits 0 with an "N passed, 0 failed" summary of at
/// least `at_least` checks (0: no summary asked) and the layer said
/// nothing.
fn run(x: &Xvfb, layer: bool, exe: &Path, arg: &str, at_least: u32) -> String {
    let mut cmd = if layer {
        let mut c = Command::new(&built().run);
        c.arg(exe);
        c
    } else {
        Command::new(exe)
    };
    zink(cmd.arg(arg).env("DISPLAY", &x.display));
    let out = cmd.output().expect("the program starts");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let what = format!("{} {arg} on zink", exe.display());
    assert!(
        out.status.success(),
        "{what}: {} (a crash in the Vulkan driver shows as SIGSEGV)\n{stdout}\n{stderr}",
        out.status
    );
    if at_least > 0 {
        let (summary, passed) = common::summary(&stdout);
        assert!(
            summary.ends_with(" passed, 0 failed") && passed >= at_least,
            "{what}: {summary}\n{stderr}"
        );
    }
    assert!(
        !stderr.contains("glstereo:"),
        "{what}: the layer complained: {stderr}"
    );
    stdout
}

fn probes(stdout: &str) -> Vec<&str> {
    stdout.lines().filter(|l| l.starts_with("probe ")).collect()
}

#[test]
fn the_draw_buffer_and_core_profile_conformance_programs_pass_on_zink() {
    let x = Xvfb::start(320, 240);
    require_zink(&x.display);
    let draw_buffers = program("glx_draw_buffers");
    run(&x, true, &draw_buffers, "stereo", 150);
    run(&x, true, &draw_buffers, "core", 100);
    let core = program("glx_core_stereo");
    run(&x, true, &core, "core33", 100);
    run(&x, true, &core, "compat", 10);
    let stereo = run(&x, true, &core, "core45", 190);
    // What does not depend on stereo is zink's own answer on a mono window.
    let mono = run(&x, false, &core, "mono45", 0);
    assert!(probes(&mono).len() > 150, "{mono}");
    assert_eq!(
        probes(&stereo),
        probes(&mono),
        "the answers on the emulated framebuffer differ from zink's on a mono window"
    );
}

/// tests/c/legacy_stereo.c's window size.
const W: u32 = 160;
const H: u32 = 120;

#[test]
fn a_stereo_window_on_zink_is_composed_by_gl_and_shows_the_reference_composite() {
    let x = Xvfb::start(2 * W + 32, 2 * H + 32);
    require_zink(&x.display);
    let exe = program("legacy_stereo");
    let crosstalk = OutputOptions {
        crosstalk: 0.25,
        ..OutputOptions::default()
    };
    for (name, options) in [
        ("anaglyph-red-cyan", OutputOptions::default()),
        ("anaglyph-red-cyan-dubois", OutputOptions::default()),
        ("side-by-side-half", OutputOptions::default()),
        ("rows", OutputOptions::default()),
        ("anaglyph-red-cyan-half", crosstalk),
    ] {
        let what = format!("{name}, crosstalk {}", options.crosstalk);
        let dir = common::scratch(&format!("zink_window_{name}"));
        let mut cmd = Command::new(&built().run);
        cmd.args(["-m", name, "--capture"])
            .arg(&dir)
            .arg(&exe)
            .args([W.to_string(), H.to_string()]);
        zink(&mut cmd)
            .env("DISPLAY", &x.display)
            .env("GLSTEREO_CROSSTALK", options.crosstalk.to_string());
        let mut p = Running::start(cmd);
        let id = p.ready();
        let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).expect("window id");
        // The capture threads write the frame soon after (each file
        // appears complete or not at all).
        for _ in 0..200 {
            if dir.join("right-000001.png").exists() && dir.join("left-000001.png").exists() {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        let left = common::png(&dir.join("left-000001.png"));
        let right = common::png(&dir.join("right-000001.png"));
        // The eyes are RedBlue's: grey, a blue square left, a red one right.
        assert_eq!(left.get(40, 80), [0, 0, 255, 255], "{what}: left eye");
        assert_eq!(right.get(120, 40), [255, 0, 0, 255], "{what}: right eye");
        assert_eq!(left.get(4, 4), [51, 51, 51, 255], "{what}: background");
        let mode = OutputMode::from_name(name).unwrap();
        let want = glstereo::output::compose(mode, &options, &left, &right, 0).unwrap();
        // zink presents through Vulkan's window system code, which puts
        // the image on the server after glXSwapBuffers returns (as a GPU
        // driver's swap does): the window is looked at until it shows the
        // frame, for at most 10 s.
        let screen = Screen::open(&x.display);
        let mut shot = screen.grab(window);
        for _ in 0..200 {
            if within_one(&shot, &want) {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
            shot = screen.grab(window);
        }
        let report = p.stdout.first().cloned().unwrap_or_default();
        let stderr = p.finish();
        assert!(!stderr.contains("glstereo:"), "{what}: {stderr}");
        assert!(report.contains("gl_stereo 1"), "{what}: {report}");
        assert_within_one(&shot, &want, &what);
    }
}

fn within_one(got: &Image, want: &Image) -> bool {
    (got.width(), got.height()) == (want.width(), want.height())
        && got.max_difference(want).is_none_or(|(d, ..)| d <= 1)
}

fn assert_within_one(got: &Image, want: &Image, what: &str) {
    assert_eq!(
        (got.width(), got.height()),
        (want.width(), want.height()),
        "{what}: size"
    );
    if let Some((d, px, py, c)) = got.max_difference(want) {
        assert!(
            d <= 1,
            "{what}: window pixel ({px},{py}) channel {c} is {:?}, the reference {:?}",
            got.get(px, py),
            want.get(px, py)
        );
    }
}

#[test]
fn the_librarys_own_surfaces_compose_on_zink_as_on_llvmpipe() {
    // RedBlue headless (EGL) in a Dubois mode and a byte-shuffling one,
    // once on llvmpipe and once on zink: the same eyes, and composites
    // within one unit (both compose captures on the CPU: zink's device
    // is lavapipe).
    let exe = common::build_example("redblue", false);
    for mode in ["anaglyph-red-cyan-dubois", "side-by-side-half"] {
        let mut images = Vec::new();
        for on_zink in [false, true] {
            let out = common::scratch(&format!("zink_redblue_{mode}_{on_zink}"));
            let mut cmd = Command::new(&exe);
            if on_zink {
                zink(&mut cmd);
            }
            cmd.args(["--out"])
                .arg(&out)
                .args(["--mode", mode])
                .env("GLSTEREO_BACKEND", "egl")
                .env_remove("GLSTEREO_MODE");
            common::run_ok(&mut cmd);
            images.push(
                ["left", "right", "composite"].map(|k| common::png(&out.join(format!("{k}.png")))),
            );
        }
        for (k, what) in ["left", "right", "composite"].iter().enumerate() {
            assert_within_one(&images[1][k], &images[0][k], &format!("{mode}: {what}"));
        }
    }
}

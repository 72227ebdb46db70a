//! Programs rebuilt from source with `<glstereo/compat.h>`: the legacy
//! stereo program and the draw-buffer rules program, unchanged, their GLX
//! and GL names mapped onto the library's gls_ functions at compile time
//! and linked with -lglstereo (no preloading), on a real X server.

mod common;

use std::process::Command;

use common::preload::{Running, Screen};
use common::xvfb::Xvfb;

fn build(name: &str) -> std::path::PathBuf {
    let dir = common::scratch(&format!("compat_{name}"));
    let exe = dir.join(name);
    common::compile_c(
        &[common::root().join("tests/c").join(format!("{name}.c"))],
        &exe,
        &["-lGL", "-lX11"],
    );
    exe
}

#[test]
fn rebuilt_legacy_program_shows_both_eyes_without_preloading() {
    let x = Xvfb::start(320, 240);
    let exe = build("compat_legacy");
    let mut cmd = Command::new(&exe);
    cmd.args(["160", "120"])
        .env("DISPLAY", &x.display)
        .env("GLSTEREO_MODE", "side-by-side-half")
        .env_remove("LD_PRELOAD");
    let mut p = Running::start(cmd);
    let id = p.ready();
    let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).unwrap();
    let shot = Screen::open(&x.display).grab(window);
    let report = p.stdout.first().cloned().unwrap_or_default();
    let stderr = p.finish();
    assert!(stderr.is_empty(), "stderr: {stderr}");
    assert!(
        report.contains("glx_stereo 1 gl_stereo 1 framebuffer 0 draw_buffer 0x405 error 0x0"),
        "{report}"
    );
    // side-by-side-half: the left eye's blue square squeezed into the left
    // half, the right eye's red square into the right half (seed 000 §4).
    let at = |nx: f64, ny: f64| {
        shot.get(
            ((nx + 1.0) / 2.0 * 160.0) as u32,
            ((1.0 - ny) / 2.0 * 120.0) as u32,
        )
    };
    assert_eq!(at(-0.65, -0.5), [0, 0, 255, 255], "left eye, left half");
    assert_eq!(at(0.75, 0.5), [255, 0, 0, 255], "right eye, right half");
    assert_eq!(at(-0.95, 0.9), [51, 51, 51, 255], "background");
}

#[test]
fn rebuilt_program_keeps_every_draw_buffer_rule() {
    let x = Xvfb::start(320, 240);
    let exe = build("compat_draw_buffers");
    let out = common::run_ok(
        Command::new(&exe)
            .arg("stereo")
            .env("DISPLAY", &x.display)
            .env_remove("LD_PRELOAD"),
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let summary = stdout.lines().last().unwrap_or("");
    assert!(
        summary.ends_with(" passed, 0 failed") && !summary.starts_with("0 "),
        "{summary}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

//! Core-profile programs see a real stereo framebuffer: a shader's
//! user-defined output 0, glClearBuffer and GL 4.5 direct state access on
//! framebuffer 0 reach every buffer the draw buffer selects, checked pixel
//! by pixel in each eye by tests/c/glx_core_stereo.c — an unmodified GLX
//! program under glstereo-run, and the same program rebuilt with
//! <glstereo/compat.h> — on a real Xvfb with Mesa. What GL answers about a
//! default framebuffer independently of stereo (the errors of the DSA calls,
//! the window's formats) is compared with Mesa's own answers on a mono
//! configuration.

mod common;

use std::path::PathBuf;
use std::process::Command;

use common::preload::{built, compile_plain};
use common::xvfb::Xvfb;

/// tests/c/glx_core_stereo.c linked with -lGL -lX11 only.
fn plain() -> PathBuf {
    let dir = common::scratch("core_stereo_plain");
    let exe = dir.join("glx_core_stereo");
    compile_plain(
        &common::root().join("tests/c/glx_core_stereo.c"),
        &exe,
        &["-lGL", "-lX11"],
    );
    exe
}

/// tests/c/compat_core_stereo.c: the same program with <glstereo/compat.h>.
fn rebuilt() -> PathBuf {
    let dir = common::scratch("core_stereo_compat");
    let exe = dir.join("compat_core_stereo");
    common::compile_c(
        &[common::root().join("tests/c/compat_core_stereo.c")],
        &exe,
        &["-lGL", "-lX11"],
    );
    exe
}

/// Runs `cmd` and checks its "N passed, 0 failed" summary (at least
/// `at_least` checks); returns its stdout.
fn passes(what: &str, cmd: &mut Command, at_least: u32) -> String {
    let out = common::run_ok(cmd);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let (summary, passed) = common::summary(&stdout);
    assert!(
        summary.ends_with(" passed, 0 failed") && passed >= at_least,
        "{what}: {summary}\n{stderr}"
    );
    assert!(
        !stderr.contains("glstereo:"),
        "{what}: the layer complained: {stderr}"
    );
    stdout
}

/// glx_core_stereo.c `binary`: a binary made by a mono context (as by a
/// run without the layer) is refused in the stereo context when its
/// output 0 needs the copies, and stderr says so; binaries made there
/// round-trip with them (core and OES names), and load in the mono one.
fn program_binaries_keep_output_zero_in_every_buffer(mut cmd: Command) {
    let out = common::run_ok(&mut cmd);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let (summary, passed) = common::summary(&stdout);
    assert!(
        summary.ends_with(" passed, 0 failed") && passed >= 60,
        "binary: {summary}\n{stderr}"
    );
    assert!(
        stderr.contains("glstereo: a program binary made without glstereo's copies"),
        "the refused binary is not said on stderr: {stderr}"
    );
}

fn probes(stdout: &str) -> Vec<&str> {
    stdout.lines().filter(|l| l.starts_with("probe ")).collect()
}

#[test]
fn shaders_clears_and_dsa_reach_both_eyes_under_glstereo_run() {
    let x = Xvfb::start(320, 240);
    let exe = plain();
    let run = |mode: &str| {
        let mut c = Command::new(&built().run);
        c.arg(&exe).arg(mode).env("DISPLAY", &x.display);
        c
    };
    passes("core33", &mut run("core33"), 100);
    passes("compat", &mut run("compat"), 10);
    let stereo = passes("core45", &mut run("core45"), 190);

    // A program the copies cannot be added to: linked as asked, and stderr
    // says why.
    let out = common::run_ok(&mut run("kept"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // GL_STEREO, output 0 in back-left, location 6 kept: a run that
    // checked nothing does not count as passing.
    let (summary, passed) = common::summary(&stdout);
    assert!(
        summary.ends_with(" passed, 0 failed") && passed >= 3,
        "{stdout}\n{stderr}"
    );
    assert!(
        stderr.contains("glstereo: a linked program keeps its fragment output 0")
            && stderr.contains("output b uses location 6"),
        "{stderr}"
    );

    program_binaries_keep_output_zero_in_every_buffer(run("binary"));

    // The probes' answers are Mesa's own for a default framebuffer.
    let mono = common::run_ok(
        Command::new(&exe)
            .arg("mono45")
            .env("DISPLAY", &x.display)
            .env_remove("LD_PRELOAD"),
    );
    let mono = String::from_utf8_lossy(&mono.stdout);
    assert!(probes(&mono).len() > 150, "{mono}");
    assert_eq!(
        probes(&stereo),
        probes(&mono),
        "the DSA answers on the emulated framebuffer differ from Mesa's on a mono window"
    );
    // And a mono program under the layer gets exactly Mesa's answers.
    let layered = common::run_ok(&mut run("mono45"));
    assert_eq!(String::from_utf8_lossy(&layered.stdout), mono);
}

#[test]
fn shaders_clears_and_dsa_reach_both_eyes_rebuilt_with_compat_h() {
    let x = Xvfb::start(320, 240);
    let exe = rebuilt();
    let run = |mode: &str| {
        let mut c = Command::new(&exe);
        c.arg(mode)
            .env("DISPLAY", &x.display)
            .env_remove("LD_PRELOAD");
        c
    };
    passes("core33", &mut run("core33"), 100);
    passes("compat", &mut run("compat"), 10);
    let stereo = passes("core45", &mut run("core45"), 190);
    program_binaries_keep_output_zero_in_every_buffer(run("binary"));
    let mono = common::run_ok(&mut run("mono45"));
    let mono = String::from_utf8_lossy(&mono.stdout);
    assert_eq!(probes(&stereo), probes(&mono));
}

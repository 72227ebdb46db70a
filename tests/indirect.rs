//! Indirect GLX (`LIBGL_ALWAYS_INDIRECT=1`, as over some `ssh -X`
//! set-ups): a program told it has stereo must get it, so where GL renders
//! indirectly (GL 1.4: no framebuffer objects to emulate stereo with)
//! stereo requests get the driver's own answer and the program's mono
//! fallback runs, as without the layer; a stereo context the program asks
//! to be indirect on a display that renders directly is made direct and
//! gets both eyes. tests/c/stereo_or_fallback.c on a private Xvfb that
//! allows indirect contexts (+iglx).

mod common;

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use common::preload::{built, compile_plain};
use common::xvfb::Xvfb;

/// tests/c/stereo_or_fallback.c, built once for both tests.
fn program() -> &'static PathBuf {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        let dir = common::scratch("stereo_or_fallback");
        let exe = dir.join("stereo_or_fallback");
        compile_plain(
            &common::root().join("tests/c/stereo_or_fallback.c"),
            &exe,
            &["-lGL", "-lX11"],
        );
        exe
    })
}

const INDIRECT_LINE: &str = "glstereo: GL rendering on this X display is indirect";
const STEREO: &str = "stereo: gl_stereo 1 left ff0000 right 0000ff is_direct 1";

/// Runs the program (under the layer unless `layer` is false) with `env`
/// set; its stdout and stderr, failing unless it exits 0.
fn run(x: &Xvfb, layer: bool, args: [&str; 2], env: &[(&str, &str)]) -> (String, String) {
    let exe = program();
    let mut cmd = if layer {
        let mut c = Command::new(&built().run);
        c.arg(exe);
        c
    } else {
        Command::new(exe)
    };
    cmd.args(args)
        .env("DISPLAY", &x.display)
        .env_remove("LIBGL_ALWAYS_INDIRECT")
        .env_remove("LD_PRELOAD");
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = common::run_ok(&mut cmd);
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn stereo_is_refused_where_gl_renders_indirectly_and_the_fallback_runs() {
    let x = Xvfb::start_with(320, 240, "+iglx");
    let indirect = [("LIBGL_ALWAYS_INDIRECT", "1")];
    for how in ["visual", "fbconfig"] {
        for direct in ["direct", "indirect"] {
            let what = format!("LIBGL_ALWAYS_INDIRECT=1, {how}, {direct} context asked");
            let (stdout, stderr) = run(&x, true, [how, direct], &indirect);
            assert_eq!(
                stdout, "fallback: no stereo (0 stereo configs listed)\n",
                "{what}: stderr:\n{stderr}"
            );
            assert_eq!(stderr.matches(INDIRECT_LINE).count(), 1, "{what}: {stderr}");
            // Without the layer: the same answer (Mesa has no stereo).
            let (plain, _) = run(&x, false, [how, direct], &indirect);
            assert_eq!(stdout, plain, "{what}: the layer's answer is Mesa's");
        }
    }
    // A client whose libGL finds no driver renders indirectly too, with
    // no variable saying so: the layer asks (a context of its own, once).
    let no_driver = [("LIBGL_DRIVERS_PATH", "/nonexistent")];
    for how in ["visual", "fbconfig"] {
        let (stdout, stderr) = run(&x, true, [how, "direct"], &no_driver);
        assert!(
            stdout.starts_with("fallback: no stereo"),
            "no driver, {how}: {stdout}\n{stderr}"
        );
        assert_eq!(stderr.matches(INDIRECT_LINE).count(), 1, "{how}: {stderr}");
    }
}

#[test]
fn a_stereo_context_asked_to_be_indirect_is_made_direct_and_gets_both_eyes() {
    let x = Xvfb::start_with(320, 240, "+iglx");
    for how in ["visual", "fbconfig"] {
        for direct in ["direct", "indirect"] {
            let (stdout, stderr) = run(&x, true, [how, direct], &[]);
            assert_eq!(stdout.trim(), STEREO, "{how}, {direct}: stderr:\n{stderr}");
            assert!(!stderr.contains("glstereo:"), "{how}, {direct}: {stderr}");
        }
    }
}

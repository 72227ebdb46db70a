//! `make check-sanitize`: the C examples, the misuse suites and the threads
//! program built with -fsanitize=address,undefined (gcc's runtimes) run
//! clean — no AddressSanitizer, LeakSanitizer or UBSan report — on EGL and
//! on OSMesa; and unmodified GLX programs (the legacy stereo program, the
//! freeglut one, the misuse suite of the stereo layer) built the same way
//! run clean under glstereo-run, the preload library inside them, on a
//! private Xvfb. LeakSanitizer suppressions: tests/sanitize/lsan.supp
//! (Mesa's own leaks only, each explained there).
//!
//! Every test here is named `sanitized_*`: `make test` runs them through
//! `make check-sanitize` and skips them in its own `cargo test`.

mod common;
#[path = "common/sanitize.rs"]
mod sanitize;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Builds one C example with the sanitizers: linked with -lGL, or with
/// -lOSMesa for the OSMesa backend (as c-examples/Makefile does).
fn example(name: &str, osmesa: bool) -> PathBuf {
    let dir = common::lib_dir().join("test-sanitize");
    std::fs::create_dir_all(&dir).unwrap();
    let exe = dir.join(if osmesa {
        format!("{name}-osmesa")
    } else {
        name.to_owned()
    });
    let gl: &[&str] = match (name, osmesa) {
        ("projection", _) => &[],
        (_, true) => &["-lOSMesa"],
        (_, false) => &["-lGL"],
    };
    sanitize::compile(
        &[common::root().join("c-examples").join(format!("{name}.c"))],
        &exe,
        gl,
    );
    exe
}

/// Runs every example as c-examples/demo.sh does, writing images.
fn examples(backend: &str) {
    let osmesa = backend == "osmesa";
    let out = common::scratch(&format!("sanitize-examples-{backend}"));
    let runs: &[(&str, &[&str])] = &[
        (
            "redblue",
            &["--modes", "anaglyph-red-cyan-dubois,side-by-side,rows"],
        ),
        ("starbase", &[]),
        ("irisgl", &[]),
        ("irisgl", &["--square-pixel"]),
        ("oglplane", &["--frames", "10"]),
        ("autostereo", &["--frames", "3"]),
    ];
    for (i, (name, args)) in runs.iter().enumerate() {
        let exe = example(name, osmesa);
        let dir = out.join(format!("{i}-{name}"));
        sanitize::run_clean(
            &format!("{name} {args:?} on {backend}"),
            Command::new(&exe)
                .args(*args)
                .arg("--out")
                .arg(&dir)
                .env("GLSTEREO_BACKEND", backend)
                .env_remove("DISPLAY"),
        );
        assert!(
            dir.join("composite.png").exists() || dir.join("frame02/composite.png").exists(),
            "{name} wrote no composite in {}",
            dir.display()
        );
    }
}

#[test]
fn sanitized_examples_run_clean_on_egl() {
    examples("egl");
    let exe = example("projection", false);
    sanitize::run_clean("projection", &mut Command::new(exe));
}

#[test]
fn sanitized_examples_run_clean_on_osmesa() {
    examples("osmesa");
}

fn c_test(name: &str) -> PathBuf {
    let exe = common::scratch(&format!("sanitize-{name}")).join(name);
    sanitize::compile(
        &[common::root().join(format!("tests/c/{name}.c"))],
        &exe,
        &[
            "-I",
            common::root().join("tests/c").to_str().unwrap(),
            "-pthread",
        ],
    );
    exe
}

#[test]
fn sanitized_misuse_suite_runs_clean() {
    let exe = c_test("misuse");
    let o = sanitize::run_clean("misuse", Command::new(&exe).env_remove("DISPLAY"));
    assert!(String::from_utf8_lossy(&o.stdout).contains(" passed, 0 failed"));
    let x = common::xvfb::Xvfb::start(320, 240);
    let o = sanitize::run_clean(
        "misuse glx",
        Command::new(&exe).arg("glx").env("DISPLAY", &x.display),
    );
    assert!(String::from_utf8_lossy(&o.stdout).contains(" passed, 0 failed"));
}

/// tests/c/NAME.c as a plain GLX program (no glstereo) with the sanitizers.
fn plain(name: &str, extra: &[&str]) -> PathBuf {
    let exe = common::scratch(&format!("sanitize-plain-{name}")).join(name);
    sanitize::compile_plain(
        &common::root().join(format!("tests/c/{name}.c")),
        &exe,
        extra,
    );
    exe
}

/// Runs `program args` under glstereo-run on `display` (stdin empty: the
/// test programs then exit after their first frame) and requires it clean.
fn under_layer(what: &str, display: &str, program: &Path, args: &[&str]) -> String {
    let o = sanitize::run_clean_preloaded(
        what,
        Command::new(&common::preload::built().run)
            .arg(program)
            .args(args)
            .env("DISPLAY", display)
            .env_remove("GLSTEREO_MODE")
            .env_remove("GLSTEREO_CAPTURE_DIR")
            .stdin(Stdio::null()),
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !stderr.contains("glstereo:"),
        "{what}: the layer complained: {stderr}"
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn sanitized_legacy_and_freeglut_stereo_programs_run_clean_under_glstereo_run() {
    let x = common::xvfb::Xvfb::start(320, 240);
    let legacy = plain("legacy_stereo", &["-lGL", "-lX11"]);
    let out = under_layer("legacy_stereo", &x.display, &legacy, &["64", "48"]);
    assert!(
        out.contains("glx_stereo 1 gl_stereo 1 framebuffer 0 draw_buffer 0x405 error 0x0"),
        "{out}"
    );
    let out = under_layer(
        "legacy_stereo single",
        &x.display,
        &legacy,
        &["64", "48", "single"],
    );
    assert!(out.contains("gl_stereo 1"), "{out}");
    let glut = plain("glut_stereo", &["-lglut", "-lGL"]);
    let out = under_layer("glut_stereo", &x.display, &glut, &[]);
    assert!(
        out.contains("gl_stereo 1 glut_window_stereo 1 error 0x0"),
        "{out}"
    );
}

#[test]
fn sanitized_layer_misuse_suite_runs_clean_through_libglstereo_and_the_preload() {
    let x = common::xvfb::Xvfb::start(320, 240);
    let include = format!("-I{}", common::root().join("tests/c").display());
    let exe = common::scratch("sanitize-misuse-glx").join("misuse_glx");
    sanitize::compile(
        &[common::root().join("tests/c/misuse_glx.c")],
        &exe,
        &[&include, "-lGL", "-lX11"],
    );
    let o = sanitize::run_clean_preloaded(
        "misuse_glx",
        Command::new(&exe)
            .env("DISPLAY", &x.display)
            .env_remove("GLSTEREO_MODE"),
    );
    assert!(String::from_utf8_lossy(&o.stdout).contains(" passed, 0 failed"));
    let exe = plain(
        "misuse_glx",
        &[&include, "-DMISUSE_PRELOAD", "-lGL", "-lX11"],
    );
    let o = sanitize::run_clean_preloaded(
        "misuse_glx under glstereo-run",
        Command::new(&common::preload::built().run)
            .arg(&exe)
            .env("DISPLAY", &x.display)
            .env_remove("GLSTEREO_MODE"),
    );
    assert!(String::from_utf8_lossy(&o.stdout).contains(" passed, 0 failed"));
}

#[test]
fn sanitized_glx_threads_run_clean_under_glstereo_run() {
    let x = common::xvfb::Xvfb::start(320, 240);
    let include = format!("-I{}", common::root().join("tests/c").display());
    let exe = plain("glx_threads", &[&include, "-pthread", "-lGL", "-lX11"]);
    for connections in ["own", "shared"] {
        let out = under_layer(
            &format!("glx_threads {connections}"),
            &x.display,
            &exe,
            &[connections, "1000"],
        );
        assert!(out.contains(" passed, 0 failed"), "{out}");
    }
}

#[test]
fn sanitized_threads_run_clean() {
    let exe = c_test("threads");
    for backend in ["egl", "osmesa"] {
        let o = sanitize::run_clean(
            &format!("threads on {backend}"),
            Command::new(&exe).args([backend, "1000"]),
        );
        assert!(String::from_utf8_lossy(&o.stdout).contains(" passed, 0 failed"));
    }
}

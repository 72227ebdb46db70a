//! `make check-sanitize`: the C examples, the misuse suite and the threads
//! program built with -fsanitize=address,undefined (gcc's runtimes) run
//! clean — no AddressSanitizer, LeakSanitizer or UBSan report — on EGL and
//! on OSMesa. LeakSanitizer suppressions: tests/sanitize/lsan.supp (Mesa's
//! own leaks only, each explained there).
//!
//! Every test here is named `sanitized_*`: `make test` runs them through
//! `make check-sanitize` and skips them in its own `cargo test`.

mod common;
#[path = "common/sanitize.rs"]
mod sanitize;

use std::path::PathBuf;
use std::process::Command;

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

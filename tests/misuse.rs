//! The C misuse suite (tests/c/misuse.c): every function of glstereo.h
//! called wrongly — NULL pointers, bad enums, out-of-range values, no
//! current surface, dead handles, surfaces of several displays — returns
//! its documented code with a message of its own, and the process goes on.
//!
//! The list of functions is taken from the header, so a new export without
//! a misuse case fails `every_export_of_the_header_has_a_misuse_case`.
//! The suite also runs under valgrind (here) and with ASan/UBSan
//! (tests/sanitize.rs).

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The functions glstereo.h declares (the names before "(" on declaration
/// lines; comments, macros and typedefs skipped).
fn header_functions() -> BTreeSet<String> {
    let text = std::fs::read_to_string(common::root().join("include/glstereo.h")).unwrap();
    let mut names = BTreeSet::new();
    for line in text.lines() {
        let skip = ["/", "*", " ", "#", "typedef", "}", "extern"];
        if line.is_empty() || skip.iter().any(|p| line.starts_with(p)) {
            continue;
        }
        // The identifier right before the first "(" is the function.
        let Some(paren) = line.find('(') else {
            continue;
        };
        let head = &line[..paren];
        let start = head
            .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .map_or(0, |i| i + 1);
        if head[start..].starts_with("gls_") {
            names.insert(head[start..].to_owned());
        }
    }
    names
}

/// The functions a shared library exports whose names start with `prefix`
/// (its dynamic symbol table). The preload library's glX*/gl* exports can be
/// listed the same way, to require a misuse case for each.
fn library_exports(lib: &Path, prefix: &str) -> BTreeSet<String> {
    let o = Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(lib)
        .output()
        .expect("nm runs (package binutils, installed with gcc)");
    assert!(o.status.success(), "nm {}", lib.display());
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| {
            let mut f = l.split_whitespace();
            let (_addr, kind, name) = (f.next()?, f.next()?, f.next()?);
            (kind == "T" && name.starts_with(prefix)).then(|| name.to_owned())
        })
        .collect()
}

/// Builds the suite into its own scratch directory.
fn build(scratch: &str) -> PathBuf {
    let exe = common::scratch(scratch).join("misuse");
    common::compile_c(
        &[common::root().join("tests/c/misuse.c")],
        &exe,
        &[
            "-I",
            common::root().join("tests/c").to_str().unwrap(),
            "-pthread",
        ],
    );
    exe
}

/// Runs the suite; it must pass every check and exit 0.
fn run(exe: &Path, args: &[&str], display: Option<&str>) -> Output {
    let mut cmd = Command::new(exe);
    cmd.args(args)
        .env("RUST_BACKTRACE", "0")
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_EMULATION");
    match display {
        Some(d) => cmd.env("DISPLAY", d),
        None => cmd.env_remove("DISPLAY"),
    };
    let o = common::run_ok(&mut cmd);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
    o
}

fn covered(o: &Output) -> BTreeSet<String> {
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| l.strip_prefix("covers "))
        .map(str::to_owned)
        .collect()
}

#[test]
fn every_export_of_the_header_has_a_misuse_case() {
    let exe = build("misuse");
    let o = run(&exe, &[], None);
    let declared = header_functions();
    let exercised = covered(&o);
    assert!(
        declared.len() > 80,
        "the header parser found only {declared:?}"
    );
    let missing: Vec<_> = declared.difference(&exercised).collect();
    let unknown: Vec<_> = exercised.difference(&declared).collect();
    assert!(
        missing.is_empty(),
        "exports of include/glstereo.h without a case in tests/c/misuse.c: {missing:?}"
    );
    assert!(
        unknown.is_empty(),
        "tests/c/misuse.c exercises names the header does not declare: {unknown:?}"
    );
    let passed: usize = String::from_utf8_lossy(&o.stdout)
        .lines()
        .find_map(|l| l.strip_suffix(" passed, 0 failed")?.parse().ok())
        .unwrap();
    assert!(
        passed > 1000,
        "only {passed} checks ran: was a section skipped?"
    );
}

#[test]
fn the_header_declares_exactly_what_the_library_exports() {
    // A function exported without a declaration could not be called (or
    // misused) from C; a declaration without an export would not link.
    let declared = header_functions();
    let exported = library_exports(&common::lib_dir().join("libglstereo.so"), "gls_");
    assert_eq!(
        declared, exported,
        "include/glstereo.h and libglstereo.so disagree"
    );
}

#[test]
fn glx_configurations_and_current_surfaces_across_connections() {
    let exe = build("misuse-glx");
    let x = common::xvfb::Xvfb::start(320, 240);
    let o = run(&exe, &["glx"], Some(&x.display));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("covers gls_display_open"), "{stdout}");
}

#[test]
fn the_misuse_suite_is_clean_under_valgrind() {
    // ASan (tests/sanitize.rs) instruments the C side only; valgrind sees
    // every read and write of the library's own (Rust) code too, e.g. that
    // a dead handle is never dereferenced. Mesa's shader disk cache is off:
    // its zstd compression trips valgrind's uninitialised-value check.
    let exe = build("misuse-valgrind");
    let o = Command::new("valgrind")
        .args([
            "--error-exitcode=99",
            "--leak-check=full",
            "--show-leak-kinds=definite",
            "--errors-for-leak-kinds=definite",
        ])
        .arg(format!(
            "--suppressions={}",
            common::root()
                .join("tests/sanitize/valgrind.supp")
                .display()
        ))
        .arg(exe)
        .env("MESA_SHADER_CACHE_DISABLE", "true")
        .env("LP_NUM_THREADS", "0")
        .env("RUST_BACKTRACE", "0")
        .env_remove("DISPLAY")
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_EMULATION")
        .output()
        .expect("valgrind runs (package valgrind; `make deps` installs it)");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && stdout.contains(" passed, 0 failed"),
        "valgrind: {}\n{stdout}\n{}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
}

//! Building C programs with AddressSanitizer + UndefinedBehaviorSanitizer
//! (gcc's runtimes: libasan, libubsan, which come with gcc) and running them
//! so that any report fails the test. Included with `#[path]` by the tests
//! that use it (tests/sanitize.rs, tests/leaks.rs).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::common::{compile_c, root};

/// Compiler flags of a sanitized build: ASan (with LeakSanitizer) and UBSan,
/// every UBSan finding fatal, frame pointers kept for the stacks.
pub const FLAGS: &[&str] = &[
    "-fsanitize=address,undefined",
    "-fno-sanitize-recover=all",
    "-fno-omit-frame-pointer",
    "-O1",
];

/// The LeakSanitizer suppressions (Mesa's own leaks only; see the file).
pub fn lsan_suppressions() -> PathBuf {
    root().join("tests/sanitize/lsan.supp")
}

/// Compiles C sources with the sanitizers (and `extra`, e.g. -lGL).
pub fn compile(sources: &[PathBuf], out: &Path, extra: &[&str]) {
    let mut args: Vec<&str> = FLAGS.to_vec();
    args.extend_from_slice(extra);
    compile_c(sources, out, &args);
}

/// Sets the sanitizer options on a command: leaks checked at exit with the
/// suppressions, any report fatal, UBSan with stacks.
pub fn configure(cmd: &mut Command) -> &mut Command {
    cmd.env(
        "ASAN_OPTIONS",
        "detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1:check_initialization_order=1",
    )
    .env(
        "LSAN_OPTIONS",
        format!("suppressions={}:print_suppressions=0", lsan_suppressions().display()),
    )
    .env("UBSAN_OPTIONS", "halt_on_error=1:print_stacktrace=1")
    .env("RUST_BACKTRACE", "0")
}

/// Fails with both streams when the program did not exit 0 or a sanitizer
/// reported anything.
pub fn assert_clean(what: &str, o: &Output) {
    let stderr = String::from_utf8_lossy(&o.stderr);
    let reported = [
        "ERROR: AddressSanitizer",
        "ERROR: LeakSanitizer",
        "runtime error:",
    ]
    .iter()
    .any(|m| stderr.contains(m));
    assert!(
        o.status.success() && !reported,
        "{what}: exit {}\n--- stdout\n{}\n--- stderr\n{}",
        o.status,
        String::from_utf8_lossy(&o.stdout),
        stderr
    );
}

/// Runs a sanitized program and requires it to be clean.
pub fn run_clean(what: &str, cmd: &mut Command) -> Output {
    let o = configure(cmd).output().expect("program starts");
    assert_clean(what, &o);
    o
}

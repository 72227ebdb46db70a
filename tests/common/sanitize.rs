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

/// Compiles a plain C program (no glstereo: one to run under glstereo-run)
/// with the sanitizers and `extra` (-I, -D, -lGL …).
pub fn compile_plain(source: &Path, out: &Path, extra: &[&str]) {
    let o = Command::new("cc")
        .args(crate::common::C_FLAGS)
        .args(FLAGS)
        .arg(source)
        .arg("-o")
        .arg(out)
        .args(extra)
        .output()
        .expect("cc runs");
    assert!(
        o.status.success(),
        "compiling {} failed:\n{}",
        source.display(),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// ASan's options: leaks checked at exit, any report fatal.
///
/// `intercept_tls_get_addr=0`: GCC 12's sanitizer runtime (Debian 12; fixed
/// from GCC 14 and LLVM 17) takes a dynamic TLS block that happens to
/// start 16 bytes past a page boundary for one with a glibc 2.19 header
/// and reads the two words before it as its bounds; LeakSanitizer's
/// stop-the-world tracer then faults at exit ("Tracer caught signal 11",
/// no leak reported, exit 1). Mesa's driver modules have dynamic TLS, so
/// the threads test on EGL failed that way once in a `make test` run.
const ASAN_OPTIONS: &str = "detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1:check_initialization_order=1:intercept_tls_get_addr=0";

/// Sets the sanitizer options on a command: leaks checked at exit with the
/// suppressions, any report fatal, UBSan with stacks.
pub fn configure(cmd: &mut Command) -> &mut Command {
    cmd.env("ASAN_OPTIONS", ASAN_OPTIONS)
        .env(
            "LSAN_OPTIONS",
            format!(
                "suppressions={}:print_suppressions=0",
                lsan_suppressions().display()
            ),
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

/// tests/c/keep_modules.c built as a shared library (once): a dlclose()
/// that keeps libraries loaded, so LeakSanitizer still scans the globals of
/// Mesa's DRI driver, which XCloseDisplay unloads (see the file).
pub fn keep_modules() -> PathBuf {
    static SHIM: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    SHIM.get_or_init(|| {
        let dir = crate::common::lib_dir().join("test-sanitize");
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("keep_modules.so");
        let tmp = dir.join(format!(".keep_modules-{}.so", std::process::id()));
        let o = Command::new("cc")
            .args(crate::common::C_FLAGS)
            .args(["-shared", "-fPIC"])
            .arg(root().join("tests/c/keep_modules.c"))
            .arg("-o")
            .arg(&tmp)
            .output()
            .expect("cc runs");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::rename(&tmp, &out).unwrap();
        out
    })
    .clone()
}

/// As [`run_clean`] for a GLX program, with Mesa's driver kept loaded
/// ([`keep_modules`]) and, for glstereo-run, which preloads its library
/// ahead of the program's ASan runtime, ASan's check that its runtime
/// comes first off. ASan still intercepts every allocation (the preloaded
/// libraries define no malloc), so nothing goes unchecked.
pub fn run_clean_preloaded(what: &str, cmd: &mut Command) -> Output {
    configure(cmd)
        .env(
            "ASAN_OPTIONS",
            format!("{ASAN_OPTIONS}:verify_asan_link_order=0"),
        )
        .env("LD_PRELOAD", keep_modules());
    let o = cmd.output().expect("program starts");
    assert_clean(what, &o);
    o
}

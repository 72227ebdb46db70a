//! Helpers shared by the integration tests: where the built library is, and
//! how to compile and run the C programs against it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The crate root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The directory holding libglstereo.so for this build profile
/// (target/<profile>, the parent of the test binary's deps/).
pub fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>")
        .to_path_buf()
}

/// A scratch directory for one test, emptied first.
pub fn scratch(name: &str) -> PathBuf {
    let dir = lib_dir().join("test-scratch").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// The strict C flags every C program in this project builds with.
pub const C_FLAGS: &[&str] = &[
    "-std=c99",
    "-Wall",
    "-Wextra",
    "-Wpedantic",
    "-Werror",
    "-g",
];

/// Compiles C sources into `out` against include/ and libglstereo (rpath set).
pub fn compile_c(sources: &[PathBuf], out: &Path, extra: &[&str]) {
    let lib = lib_dir();
    assert!(
        lib.join("libglstereo.so").exists(),
        "libglstereo.so not found in {}",
        lib.display()
    );
    ensure_soname_link(&lib);
    let mut cmd = Command::new("cc");
    cmd.args(C_FLAGS)
        .arg("-I")
        .arg(root().join("include"))
        .args(sources)
        .arg("-o")
        .arg(out)
        .arg("-L")
        .arg(&lib)
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .arg("-lglstereo")
        .args(extra)
        .arg("-lm");
    let o = cmd.output().expect("cc runs");
    assert!(
        o.status.success(),
        "compiling {sources:?} failed:\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The library's soname is libglstereo.so.0 (as installed); in the build
/// tree that name must point at the freshly built libglstereo.so.
pub fn ensure_soname_link(lib: &Path) {
    let link = lib.join("libglstereo.so.0");
    if std::fs::read_link(&link).ok().as_deref() != Some(Path::new("libglstereo.so")) {
        let _ = std::fs::remove_file(&link);
        // Another test may create it at the same moment; either result is fine.
        let _ = std::os::unix::fs::symlink("libglstereo.so", &link);
    }
}

/// Runs a program and returns its output, failing with both streams shown
/// if it did not exit with status 0.
pub fn run_ok(cmd: &mut Command) -> Output {
    let o = cmd.output().expect("program starts");
    assert!(
        o.status.success(),
        "{cmd:?} exited with {}\n--- stdout\n{}\n--- stderr\n{}",
        o.status,
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

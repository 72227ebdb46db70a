//! Helpers shared by the integration tests: where the built library is, and
//! how to compile and run the C programs against it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub mod clients;
pub mod photo;
pub mod preload;
pub mod weston;
pub mod xvfb;

/// The crate root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The directory holding the libglstereo.so built with this test binary:
/// target/<profile>/deps. (`cargo test` refreshes the library there but not
/// the copy in target/<profile>, which only `cargo build` updates.)
pub fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent().expect("target/<profile>/deps").to_path_buf()
}

/// A scratch directory for one test, emptied first.
pub fn scratch(name: &str) -> PathBuf {
    let dir = lib_dir().join("test-scratch").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// The message of this thread's last failed gls_* call
/// (gls_last_error_message()).
pub fn last_error() -> String {
    // SAFETY: never NULL.
    unsafe { std::ffi::CStr::from_ptr(glstereo::ffi::core::gls_last_error_message()) }
        .to_string_lossy()
        .into_owned()
}

/// The last line of a C test program's stdout, its "N passed, M failed"
/// summary, and N (0 when the line does not start with a number).
pub fn summary(stdout: &str) -> (&str, u32) {
    let summary = stdout.lines().last().unwrap_or("");
    let passed = summary
        .split_whitespace()
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    (summary, passed)
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
        // DT_RPATH (not RUNPATH): searched before LD_LIBRARY_PATH, which
        // cargo sets to target/<profile> first, where an older library may
        // sit; the program must load the one this test run built.
        .arg(format!("-Wl,--disable-new-dtags,-rpath,{}", lib.display()))
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
        // Made under a name of this process, then renamed over the link:
        // a program another test starts meanwhile finds the old link or the
        // new one, never none.
        let fresh = lib.join(format!("libglstereo.so.0.{}", std::process::id()));
        let _ = std::fs::remove_file(&fresh);
        if std::os::unix::fs::symlink("libglstereo.so", &fresh).is_ok() {
            let _ = std::fs::rename(&fresh, &link);
        }
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

/// Builds one C example (c-examples/NAME.c with example.h) into the scratch
/// area: linked with -lGL, or with -lOSMesa when `osmesa`.
pub fn build_example(name: &str, osmesa: bool) -> PathBuf {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    // Tests of one binary share each build; the lock serialises compilers.
    static BUILT: OnceLock<Mutex<HashMap<(String, bool), PathBuf>>> = OnceLock::new();
    let mut built = BUILT
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(p) = built.get(&(name.to_owned(), osmesa)) {
        return p.clone();
    }
    let dir = lib_dir().join("test-examples");
    std::fs::create_dir_all(&dir).unwrap();
    let exe = dir.join(if osmesa {
        format!("{name}-osmesa")
    } else {
        name.to_owned()
    });
    let src = root().join("c-examples").join(format!("{name}.c"));
    // Each test binary may build the same example; build to a unique name
    // and rename, so concurrent builds never see a half-written file.
    let tmp = dir.join(format!(
        ".{}-{}",
        exe.file_name().unwrap().to_string_lossy(),
        std::process::id()
    ));
    compile_c(&[src], &tmp, &[if osmesa { "-lOSMesa" } else { "-lGL" }]);
    std::fs::rename(&tmp, &exe).unwrap();
    built.insert((name.to_owned(), osmesa), exe.clone());
    exe
}

/// Reads a PNG written by the library.
pub fn png(path: &Path) -> glstereo::image::Image {
    glstereo::capture::read_png(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

//! What a new user does: clone the repository, run a plain `cargo build`
//! (no `make`), build a C program as the README shows (`cc prog.c
//! -Iinclude -Ltarget/debug -lglstereo -Wl,-rpath,…`) and run it. The
//! library's soname is `libglstereo.so.0`, so the program starts only if
//! the build left that name beside `libglstereo.so` (build.rs does).
//!
//! The clone is of the committed tree (HEAD of this checkout): changes not
//! yet committed are not in it. It builds from scratch (about a minute on
//! two cores), offline, from the crates cargo already downloaded.

mod common;

use std::path::Path;
use std::process::Command;

/// The C program: prints the library's version.
const PROGRAM: &str = r#"#include <stdio.h>
#include "glstereo.h"

int main(void) {
    printf("%s\n", gls_version());
    return 0;
}
"#;

#[test]
fn a_c_program_linked_after_a_plain_cargo_build_starts() {
    let dir = common::scratch("fresh-clone");
    let clone = dir.join("glstereo");
    common::run_ok(
        Command::new("git")
            .args(["clone", "--quiet"])
            .arg(common::root())
            .arg(&clone),
    );
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    common::run_ok(
        Command::new(cargo)
            .args(["build", "--offline", "--quiet"])
            .current_dir(&clone)
            // The default layout, target/debug, as the README assumes.
            .env_remove("CARGO_TARGET_DIR")
            .env_remove("CARGO_BUILD_TARGET_DIR"),
    );
    let lib = clone.join("target/debug");
    let src = dir.join("prog.c");
    std::fs::write(&src, PROGRAM).unwrap();
    let exe = dir.join("prog");
    common::run_ok(
        Command::new("cc")
            .args(common::C_FLAGS)
            .arg(&src)
            .arg("-o")
            .arg(&exe)
            .arg(format!("-I{}", clone.join("include").display()))
            .arg(format!("-L{}", lib.display()))
            .arg("-lglstereo")
            .arg(format!("-Wl,-rpath,{}", lib.display()))
            .current_dir(&clone),
    );
    // The program asks for the soname, as one linked against an installed
    // library does.
    let dynamic = common::run_ok(Command::new("readelf").arg("-d").arg(&exe));
    let dynamic = String::from_utf8_lossy(&dynamic.stdout);
    assert!(
        dynamic.contains("Shared library: [libglstereo.so.0]"),
        "the program should need libglstereo.so.0:\n{dynamic}"
    );
    // It starts (no LD_LIBRARY_PATH: the rpath alone finds the library).
    let out = Command::new(&exe)
        .env_remove("LD_LIBRARY_PATH")
        .output()
        .expect("the program runs");
    assert!(
        out.status.success(),
        "the program did not start: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        env!("CARGO_PKG_VERSION")
    );
    assert_eq!(
        std::fs::read_link(lib.join("libglstereo.so.0")).unwrap(),
        Path::new("libglstereo.so")
    );
    // Half a gigabyte of build products: not kept.
    let _ = std::fs::remove_dir_all(&dir);
}

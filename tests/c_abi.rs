//! C programs compiled with the strict flags against the generated header
//! and the cdylib, run, and their checks required to pass.

mod common;

use std::process::Command;

#[test]
fn c_math_program_reproduces_the_seed_and_gets_documented_codes() {
    let dir = common::scratch("math_abi");
    let exe = dir.join("math_abi");
    common::compile_c(&[common::root().join("tests/c/math_abi.c")], &exe, &[]);
    let out = common::run_ok(&mut Command::new(&exe));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
}

#[test]
fn c_surface_misuse_gets_documented_codes_and_the_process_goes_on() {
    let dir = common::scratch("surface_abi");
    let exe = dir.join("surface_abi");
    common::compile_c(&[common::root().join("tests/c/surface_abi.c")], &exe, &[]);
    let out = common::run_ok(&mut Command::new(&exe));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
}

#[test]
fn c_nv3dvision_program_uses_the_legacy_names_and_gets_the_spec_errors() {
    let dir = common::scratch("nv3dvision_abi");
    let exe = dir.join("nv3dvision_abi");
    common::compile_c(
        &[common::root().join("tests/c/nv3dvision_abi.c")],
        &exe,
        &["-lGL"],
    );
    let out = common::run_ok(Command::new(&exe).env("GLSTEREO_BACKEND", "egl"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
}

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

#[test]
fn the_readme_example_builds_runs_and_draws_redblue() {
    let readme = std::fs::read_to_string(common::root().join("README.md")).unwrap();
    let section = readme
        .split("## A C example")
        .nth(1)
        .expect("README has the example section");
    let code = section
        .split("```c\n")
        .nth(1)
        .and_then(|s| s.split("```").next())
        .expect("a ```c block");
    let dir = common::scratch("readme_example");
    let src = dir.join("readme.c");
    std::fs::write(&src, code).unwrap();
    let exe = dir.join("readme");
    common::compile_c(&[src], &exe, &["-lGL"]);
    common::run_ok(
        Command::new(&exe)
            .current_dir(&dir)
            .env("GLSTEREO_BACKEND", "egl")
            .env_remove("GLSTEREO_MODE"),
    );
    let img = common::png(&dir.join("redblue.png"));
    assert_eq!((img.width(), img.height()), (640, 480));
    // Red-cyan: R from the left eye, G and B from the right. Where only the
    // left eye has its blue rectangle (R = 1 from glColor3b's (2c+1)/255),
    // G and B are the right eye's grey; where only the right eye has red,
    // R is the left eye's grey and G, B the red's 1.
    assert_eq!(img.get(100, 400), [1, 51, 51, 255], "left-only area");
    assert_eq!(img.get(540, 80), [51, 1, 1, 255], "right-only area");
    assert_eq!(img.get(5, 5), [51, 51, 51, 255], "grey background");
}

#[test]
fn c_program_linked_with_gls_link_program_draws_output_0_into_both_eyes() {
    let dir = common::scratch("shader_outputs_abi");
    let exe = dir.join("shader_outputs_abi");
    common::compile_c(
        &[common::root().join("tests/c/shader_outputs_abi.c")],
        &exe,
        &[],
    );
    let out = common::run_ok(&mut Command::new(&exe));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(" passed, 0 failed") && !stdout.starts_with("0 "),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

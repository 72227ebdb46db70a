//! Threads (tests/c/threads.c): two threads render and swap 1000 frames at
//! once, each on its own surface and context, with every frame's eyes
//! checked pixel by pixel and each thread's last-error message checked to
//! be its own; one surface handed from thread to thread, also by a thread
//! that ends without releasing it.

mod common;

use std::process::Command;

/// Frames each thread renders.
const FRAMES: &str = "1000";

fn run(backend: &str) {
    let exe = common::scratch(&format!("threads-{backend}")).join("threads");
    common::compile_c(
        &[common::root().join("tests/c/threads.c")],
        &exe,
        &[
            "-I",
            common::root().join("tests/c").to_str().unwrap(),
            "-pthread",
        ],
    );
    let o = common::run_ok(Command::new(&exe).args([backend, FRAMES]));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("2 threads x 1000 frames, every frame checked"),
        "{stdout}"
    );
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
}

#[test]
fn two_threads_render_1000_frames_each_on_egl_with_correct_images_and_their_own_errors() {
    run("egl");
}

#[test]
fn two_threads_render_1000_frames_each_on_osmesa_with_correct_images_and_their_own_errors() {
    run("osmesa");
}

//! Threads (tests/c/threads.c): two threads render and swap 1000 frames at
//! once, each on its own surface and context, with every frame's eyes
//! checked pixel by pixel and each thread's last-error message checked to
//! be its own; one surface handed from thread to thread, also by a thread
//! that ends without releasing it.
//!
//! And the stereo layer (tests/c/glx_threads.c, an unmodified GLX program
//! under glstereo-run on a private Xvfb): two threads with their own stereo
//! contexts and windows render and swap 1000 frames at once — each on its
//! own X connection, and both on one (XInitThreads) — with every frame's
//! eyes and every tenth window checked, GL errors staying in the context
//! that made them; a context destroyed by another thread while current
//! keeps working until released; a released context taken over by a new
//! thread.

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

fn glx_threads(connections: &str) {
    let exe = common::scratch(&format!("threads-glx-{connections}")).join("glx_threads");
    common::preload::compile_plain(
        &common::root().join("tests/c/glx_threads.c"),
        &exe,
        &[
            &format!("-I{}", common::root().join("tests/c").display()),
            "-pthread",
            "-lGL",
            "-lX11",
        ],
    );
    let x = common::xvfb::Xvfb::start(320, 240);
    let o = common::run_ok(
        Command::new(&common::preload::built().run)
            .arg(&exe)
            .args([connections, FRAMES])
            .env("DISPLAY", &x.display)
            .env_remove("GLSTEREO_MODE")
            .env_remove("GLSTEREO_CAPTURE_DIR"),
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stdout.contains("2 threads x 1000 frames, every frame checked")
            && stdout.contains(" passed, 0 failed"),
        "{stdout}\n{stderr}"
    );
    assert!(
        !stderr.contains("glstereo:"),
        "the layer complained: {stderr}"
    );
}

#[test]
fn two_threads_with_their_own_stereo_glx_contexts_and_connections_under_the_preload() {
    glx_threads("own");
}

#[test]
fn two_threads_with_their_own_stereo_glx_contexts_on_one_connection_under_the_preload() {
    glx_threads("shared");
}

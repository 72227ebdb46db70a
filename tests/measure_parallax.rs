//! Measured parallax and auto-convergence on real Mesa rendering, from C:
//! tests/c/measure_parallax.c draws quads at known distances through the
//! library's eye projections and checks the measurement against the math
//! and against the eye images, on EGL and on OSMesa.

mod common;

use std::process::Command;

fn run(osmesa: bool) {
    let name = if osmesa {
        "measure_osmesa"
    } else {
        "measure_egl"
    };
    let dir = common::scratch(name);
    let exe = dir.join(name);
    common::compile_c(
        &[common::root().join("tests/c/measure_parallax.c")],
        &exe,
        &[if osmesa { "-lOSMesa" } else { "-lGL" }],
    );
    let out = common::run_ok(
        Command::new(&exe).env("GLSTEREO_BACKEND", if osmesa { "osmesa" } else { "egl" }),
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
}

#[test]
fn measured_parallax_matches_the_math_and_the_images_on_egl() {
    run(false);
}

#[test]
fn measured_parallax_matches_the_math_and_the_images_on_osmesa() {
    run(true);
}

/// The depth read-back is the shared depth/stencil buffer, rows bottom
/// first, exact to D24 precision: set with scissored depth clears on a real
/// EGL context, it reads back where and what was set, from either eye.
#[test]
fn depth_reads_back_bottom_row_first_with_d24_precision() {
    use glstereo::backend::{BackendChoice, BackendKind};
    use glstereo::config::glx::*;
    use glstereo::display::Display;
    use glstereo::gl::enums::*;
    use glstereo::surface;

    let (w, h) = (16u32, 8u32);
    let d = Display::open(BackendChoice::Only(BackendKind::Egl)).expect("EGL display");
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_DEPTH_SIZE, 24])
        .unwrap();
    let s = d.create_surface(&c, w, h).unwrap();
    surface::make_current(Some(&s)).unwrap();
    let gl = s.gl();
    // SAFETY: the surface is current on this thread.
    unsafe {
        gl.ClearDepth(1.0);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        gl.Enable(GL_SCISSOR_TEST);
        gl.Scissor(0, 0, 3, 2); // bottom-left 3x2
        gl.ClearDepth(0.25);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        s.draw_buffer(GL_BACK_RIGHT).unwrap(); // the depth buffer is the same for either eye
        gl.Scissor(10, 6, 6, 2); // top-right 6x2
        gl.ClearDepth(0.7);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        gl.Disable(GL_SCISSOR_TEST);
    }
    let depth = s.read_depth().unwrap();
    assert_eq!((depth.width(), depth.height()), (w, h));
    let d24 = |v: f64| ((v * 16_777_215.0).round() / 16_777_215.0) as f32;
    for y in 0..h {
        for x in 0..w {
            let want = if x < 3 && y < 2 {
                d24(0.25)
            } else if x >= 10 && y >= 6 {
                d24(0.7)
            } else {
                1.0
            };
            let got = depth.get(x, y);
            assert!(
                (got - want).abs() <= 1e-7,
                "depth at ({x}, {y}) from the bottom is {got}, want {want}"
            );
        }
    }
    surface::make_current(None).unwrap();
}

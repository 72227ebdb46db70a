//! Measures the two ways a capture of the composite can be made, in every
//! output mode, on one backend:
//!
//! - cpu: read both eyes back (glReadPixels each) and `cpu::compose`;
//! - gl:  compose on GL in the compositor context, then one glReadPixels.
//!
//! ```sh
//! cargo run --release --example compose_paths -- egl [WxH] [iterations] [crosstalk] [saturation]
//! cargo run --release --example compose_paths -- osmesa
//! ```
//!
//! Prints the minimum and median milliseconds of each path per mode. The numbers behind
//! `output::gl::preferred_path` come from this program.

use std::sync::Arc;
use std::time::Instant;

use glstereo::backend::{BackendChoice, BackendKind};
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::gl::enums::*;
use glstereo::image::Image;
use glstereo::output::pattern::noise;
use glstereo::output::{ComposePath, OutputMode, OutputOptions};
use glstereo::surface::{self, Surface};

fn draw(s: &Arc<Surface>, buffer: u32, img: &Image) {
    s.draw_buffer(buffer).unwrap();
    let mut rows = img.clone();
    rows.flip_vertical();
    // SAFETY: the surface is current; the pixels are tightly packed RGBA8.
    unsafe {
        let gl = s.gl();
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl.WindowPos2i(0, 0);
        gl.DrawPixels(
            img.width() as i32,
            img.height() as i32,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            rows.pixels().as_ptr().cast(),
        );
    }
}

/// (minimum, median) milliseconds of `n` captures. The minimum is the cost
/// without interference from other processes on the machine.
fn time_ms(s: &Arc<Surface>, path: ComposePath, n: usize) -> (f64, f64) {
    let _ = s.composite_image_via(path).unwrap(); // warm up (compiles shaders)
    let mut t: Vec<f64> = (0..n)
        .map(|_| {
            let start = Instant::now();
            let img = s.composite_image_via(path).unwrap();
            std::hint::black_box(img);
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    (t[0], t[n / 2])
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let kind = match args.get(1).map(String::as_str) {
        Some("osmesa") => BackendKind::OsMesa,
        _ => BackendKind::Egl,
    };
    let (w, h) = args
        .get(2)
        .and_then(|s| s.split_once('x'))
        .map(|(a, b)| (a.parse().unwrap(), b.parse().unwrap()))
        .unwrap_or((1280, 1024));
    let n: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(15);
    let options = OutputOptions {
        swap_eyes: false,
        crosstalk: args.get(4).and_then(|s| s.parse().ok()).unwrap_or(0.0),
        saturation: args.get(5).and_then(|s| s.parse().ok()).unwrap_or(1.0),
    };

    let d = Display::open(BackendChoice::Only(kind)).unwrap();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO])
        .unwrap();
    let s = d.create_surface(&c, w, h).unwrap();
    surface::make_current(Some(&s)).unwrap();
    draw(&s, GL_BACK_LEFT, &noise(w, h, 1));
    draw(&s, GL_BACK_RIGHT, &noise(w, h, 2));
    s.swap_buffers().unwrap();
    surface::make_current(None).unwrap();
    s.set_options(options).unwrap();

    println!(
        "{} {w}x{h}, crosstalk {}, saturation {}, {n} captures each, milliseconds",
        kind.name(),
        options.crosstalk,
        options.saturation
    );
    println!(
        "{:<30} {:>8} {:>8} {:>8} {:>8}",
        "mode", "cpu min", "gl min", "cpu med", "gl med"
    );
    for mode in OutputMode::all().filter(|&m| m != OutputMode::Quad) {
        s.set_output(mode).expect("set_output");
        let cpu = time_ms(&s, ComposePath::Cpu, n);
        let gl = time_ms(&s, ComposePath::Gl, n);
        println!(
            "{:<30} {:>8.2} {:>8.2} {:>8.2} {:>8.2}",
            mode.canonical_name(),
            cpu.0,
            gl.0,
            cpu.1,
            gl.1
        );
    }
}

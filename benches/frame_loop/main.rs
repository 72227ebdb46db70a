//! Frame-loop benchmark: the same scene rendered by a plain mono program and
//! by a stereo program through glstereo, on EGL (surfaceless), OSMesa and
//! GLX (a private Xvfb), at 1280x1024, for a light and a heavy scene.
//!
//! ```sh
//! cargo bench --bench frame_loop                   # every backend, both scenes
//! cargo bench --bench frame_loop -- --backend egl --scene heavy --rounds 12
//! make bench                                       # this and the composition benches
//! ```
//!
//! Method (see BENCHMARKS.md): both programs live in one process, each with
//! its own context; batches of mono and stereo frames alternate (mono,
//! stereo, mono, …) so that drift in the machine's load hits both alike.
//! A frame is everything the program does per frame:
//!
//! - mono: clear, draw, then `glXSwapBuffers` (GLX) or nothing (headless);
//! - stereo: `glDrawBuffer(GL_BACK_LEFT)`, clear, draw the left eye,
//!   `glDrawBuffer(GL_BACK_RIGHT)`, clear, draw the right eye,
//!   `gls_swap_buffers` (GLX: composes the output mode into the window and
//!   swaps);
//!
//! and headless frames end with glFinish in both programs (a headless frame
//! is done when its pixels are). Each frame is timed; the ratio printed is
//! median(stereo) / median(mono) over the run.
//!
//! Headless, a third program runs in the same alternation: the plain
//! program drawing both eyes into two colour textures of one FBO (shared
//! depth), no layer: the two-renders floor, so `stereo / control` is what
//! the layer itself costs (`--no-control` skips it).
//!
//! `--capture` adds, to the stereo program, a PNG capture of both eyes every
//! frame (`Surface::queue_png`: read back here, written by the surface's
//! PNG threads, at most 4 waiting), and its frames per second are the
//! stereo column. `--capture-sync` captures with `Surface::save_png` instead
//! (encoded and written on the rendering thread), for comparison.
//!
//! `--stereo-only` runs the stereo program alone, frame after frame: built
//! with `--features profile-stages`, it prints where its frames' time goes
//! (`GLSTEREO_PROFILE=N`: every N frames; BENCHMARKS.md, breakdown).
//!
//! The parent process runs one child per backend (`--backend NAME`), and
//! starts Xvfb for GLX itself.

mod plain;
mod scene;
// The tests' private Xvfb (-displayfd), stopped when dropped.
#[allow(dead_code)]
#[path = "../../tests/common/xvfb.rs"]
mod xvfb;

use std::process::{Command, Stdio};
use std::sync::Arc;
use std::time::{Duration, Instant};

use glstereo::backend::{BackendChoice, BackendKind};
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::gl::Gl;
use glstereo::gl::enums::*;
use glstereo::math::Eye;
use glstereo::output::{OutputMode, composite_size};
use glstereo::surface::DEFAULT_OUTPUT;
use glstereo::surface::{self, Surface};

use plain::Plain;
use scene::{Scene, SceneGl, Weight};
use xvfb::Xvfb;

struct Args {
    backend: Option<String>,
    display: Option<String>,
    scenes: Vec<Weight>,
    rounds: usize,
    width: u32,
    height: u32,
    mode: Option<OutputMode>,
    capture: bool,
    capture_sync: bool,
    control: bool,
    stereo_only: bool,
}

fn parse_args() -> Args {
    let mut a = Args {
        backend: None,
        display: None,
        scenes: vec![Weight::Light, Weight::Heavy],
        rounds: 10,
        width: 1280,
        height: 1024,
        mode: None,
        capture: false,
        capture_sync: false,
        control: true,
        stereo_only: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--backend" => a.backend = it.next(),
            "--display" => a.display = it.next(),
            "--scene" => {
                a.scenes = match it.next().as_deref() {
                    Some("light") => vec![Weight::Light],
                    Some("heavy") => vec![Weight::Heavy],
                    _ => vec![Weight::Light, Weight::Heavy],
                }
            }
            "--rounds" => a.rounds = it.next().and_then(|s| s.parse().ok()).unwrap_or(10),
            "--size" => {
                let s = it.next().unwrap_or_default();
                let (w, h) = s.split_once('x').expect("--size WxH");
                (a.width, a.height) = (w.parse().unwrap(), h.parse().unwrap());
            }
            "--mode" => a.mode = Some(it.next().expect("--mode NAME").parse().expect("a mode")),
            "--capture" => a.capture = true,
            "--capture-sync" => (a.capture, a.capture_sync) = (true, true),
            "--no-control" => a.control = false,
            // Only stereo frames, back to back: what a profile-stages build
            // (BENCHMARKS.md, breakdown) times without mono frames between.
            "--stereo-only" => (a.stereo_only, a.control) = (true, false),
            // cargo bench passes --bench; criterion-style filters are ignored.
            _ => {}
        }
    }
    a
}

fn main() {
    let args = parse_args();
    match args.backend.as_deref() {
        Some(b) if b != "all" => run_backend(&args, b),
        _ => orchestrate(&args),
    }
}

/// Runs one child process per backend (Xvfb started here for GLX).
fn orchestrate(args: &Args) {
    let exe = std::env::current_exe().unwrap();
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_owned())
        })
        .unwrap_or_default();
    println!(
        "frame loop {}x{}, {} rounds; {} cores ({cpu}); LP_NUM_THREADS={}",
        args.width,
        args.height,
        args.rounds,
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        std::env::var("LP_NUM_THREADS").unwrap_or_else(|_| "unset".into())
    );
    for backend in ["egl", "osmesa", "glx"] {
        let mut xvfb = None;
        let mut cmd = Command::new(&exe);
        cmd.args(std::env::args().skip(1).filter(|a| a != "--bench"));
        cmd.args(["--backend", backend]);
        if backend == "glx" {
            // Room for the stereo window at (0, 0), as large as twice the
            // eyes' size in either direction, and the mono one beside it.
            let x = Xvfb::start(3 * args.width + 32, 2 * args.height + 32);
            cmd.args(["--display", &x.display]);
            xvfb = Some(x);
        }
        let status = cmd.stdout(Stdio::inherit()).status().expect("child runs");
        drop(xvfb);
        if !status.success() {
            eprintln!("frame_loop: {backend} failed ({status})");
        }
    }
}

/// Per-frame milliseconds of each program, alternated by batch.
struct Timings {
    control: Vec<f64>,
    mono: Vec<f64>,
    stereo: Vec<f64>,
}

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    if s.is_empty() {
        return f64::NAN;
    }
    s[s.len() / 2]
}

fn run_backend(args: &Args, backend: &str) {
    let kind = match backend {
        "egl" => BackendKind::Egl,
        "osmesa" => BackendKind::OsMesa,
        "glx" => BackendKind::Glx,
        other => panic!("unknown backend {other}"),
    };
    for &weight in &args.scenes {
        let t = measure(args, kind, weight);
        let (m, s) = (median(&t.mono), median(&t.stereo));
        println!(
            "{:<7} {:<5} ({:>6} triangles){}: mono {:>7.2} ms ({:>6.1} fps), stereo {:>7.2} ms ({:>6.1} fps), ratio {:.3} [{} + {} frames]",
            kind.name(),
            weight.name(),
            weight.triangles(),
            args.mode.map(|m| format!(" {m}")).unwrap_or_default(),
            m,
            1e3 / m,
            s,
            1e3 / s,
            s / m,
            t.mono.len(),
            t.stereo.len()
        );
        if !t.control.is_empty() {
            let c = median(&t.control);
            println!(
                "        control (plain program, both eyes into two FBOs, no layer): {c:.2} ms, \
                 ratio {:.3}; stereo / control {:.3}",
                c / m,
                s / c
            );
        }
    }
}

/// The stereo program's surface and scene.
struct Stereo {
    surface: Arc<Surface>,
    scene: Scene,
}

fn measure(args: &Args, kind: BackendKind, weight: Weight) -> Timings {
    let (w, h) = (args.width, args.height);
    // The mono program.
    let plain = match kind {
        BackendKind::Egl => Plain::egl(),
        BackendKind::OsMesa => Plain::osmesa(),
        // Beside the stereo window (at the origin), fully on the screen:
        // a window partly off the screen would be cheaper to show.
        BackendKind::Glx => Plain::glx(
            args.display.as_deref().expect("--display"),
            composite_size(args.mode.unwrap_or(DEFAULT_OUTPUT), w, h).0 as i32 + 16,
            w,
            h,
        ),
    };
    plain.make_current();
    // SAFETY: the plain context is current; its GetProcAddress returns its functions.
    let mono_gl = unsafe { Gl::load_current(|n| plain.get_proc_address(n)) }.unwrap();
    // SAFETY: as above.
    let mono_fbo = unsafe { plain.default_framebuffer(&mono_gl, w, h) };
    // SAFETY: as above.
    let mono_scene = unsafe {
        let ext = SceneGl::load(|n| plain.get_proc_address(n));
        Scene::new(&mono_gl, ext, weight, w, h)
    };

    // The stereo program, through glstereo.
    let display = match kind {
        BackendKind::Glx => Display::open_x11(args.display.as_deref()).unwrap(),
        k => Display::open(BackendChoice::Only(k)).unwrap(),
    };
    let config = display
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_DEPTH_SIZE, 24])
        .unwrap();
    let surface = display.create_surface(&config, w, h).unwrap();
    if let Some(mode) = args.mode {
        surface.set_output(mode).unwrap();
    }
    surface::make_current(Some(&surface)).unwrap();
    // SAFETY: the surface is current; its GetProcAddress returns its backend's functions.
    let stereo_scene = unsafe {
        let ext = SceneGl::load(|n| surface.get_proc_address(n));
        Scene::new(surface.gl(), ext, weight, w, h)
    };
    let stereo = Stereo {
        surface,
        scene: stereo_scene,
    };
    surface::make_current(None).unwrap();

    // Batches of about 0.3 s each, at least 3 frames.
    let batch = match weight {
        Weight::Light => 20,
        Weight::Heavy => 4,
    };
    let mut t = Timings {
        control: Vec::new(),
        mono: Vec::new(),
        stereo: Vec::new(),
    };
    let mut frame = 0u64;
    let mut capture = args.capture.then(|| capture_dir(kind, weight));
    for round in 0..=args.rounds {
        // Round 0 warms up (shader compilation, first allocations).
        let keep = round > 0;
        plain.make_current();
        for _ in 0..if args.stereo_only { 0 } else { batch } {
            let start = Instant::now();
            // SAFETY: the plain context is current.
            unsafe {
                mono_gl.BindFramebuffer(GL_FRAMEBUFFER, mono_fbo);
                mono_scene.draw(&mono_gl, frame, None);
            }
            plain.swap();
            if !plain.has_window() {
                // SAFETY: as above.
                unsafe { mono_gl.Finish() };
            }
            if keep {
                t.mono.push(ms(start.elapsed()));
            }
            frame += 1;
        }
        if args.control && !plain.has_window() {
            for _ in 0..batch {
                let start = Instant::now();
                // SAFETY: the plain context is current.
                unsafe {
                    mono_gl.BindFramebuffer(GL_FRAMEBUFFER, mono_fbo);
                    mono_gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
                    mono_scene.draw(&mono_gl, frame, Some(Eye::Left));
                    mono_gl.DrawBuffer(GL_COLOR_ATTACHMENT0 + 1);
                    mono_scene.draw(&mono_gl, frame, Some(Eye::Right));
                    mono_gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
                    mono_gl.Finish();
                }
                if keep {
                    t.control.push(ms(start.elapsed()));
                }
                frame += 1;
            }
        }
        surface::make_current(Some(&stereo.surface)).unwrap();
        for _ in 0..batch {
            let start = Instant::now();
            stereo_frame(&stereo, frame, kind != BackendKind::Glx);

            if let Some(dir) = &mut capture {
                save_eyes(&stereo.surface, dir, frame, args.capture_sync);
            }
            if keep {
                t.stereo.push(ms(start.elapsed()));
            }
            frame += 1;
        }
        surface::make_current(None).unwrap();
    }
    if let Some(dir) = capture {
        surface::make_current(Some(&stereo.surface)).unwrap();
        stereo.surface.finish_captures().unwrap();
        let last = glstereo::capture::read_png(&dir.join("left-0.png")).unwrap();
        assert_eq!((last.width(), last.height()), (w, h), "a captured eye");
        surface::make_current(None).unwrap();
        let _ = std::fs::remove_dir_all(dir);
    }
    t
}

fn stereo_frame(st: &Stereo, frame: u64, finish: bool) {
    let s = &st.surface;
    for (buffer, eye) in [(GL_BACK_LEFT, Eye::Left), (GL_BACK_RIGHT, Eye::Right)] {
        s.draw_buffer(buffer).unwrap();
        // SAFETY: the surface is current.
        unsafe { st.scene.draw(s.gl(), frame, Some(eye)) };
    }
    s.swap_buffers().unwrap();
    if finish {
        // SAFETY: the surface is current.
        unsafe { s.gl().Finish() };
    }
}

fn capture_dir(kind: BackendKind, weight: Weight) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "glstereo-frame-loop-{}-{}-{}",
        std::process::id(),
        kind.name(),
        weight.name()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn save_eyes(s: &Arc<Surface>, dir: &std::path::Path, frame: u64, sync: bool) {
    use glstereo::surface::CaptureImage;
    // A ring of file names: the files are rewritten, the disk does not fill.
    let n = frame % 8;
    for (which, name) in [(CaptureImage::Left, "left"), (CaptureImage::Right, "right")] {
        let path = dir.join(format!("{name}-{n}.png"));
        if sync {
            s.save_png(which, &path).unwrap();
        } else {
            s.queue_png(which, &path).unwrap();
        }
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

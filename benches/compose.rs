//! Composition of every output mode, on the CPU and on GL (EGL surfaceless,
//! llvmpipe here), at 1280x1024 and 1920x1080 eyes, against a memcpy of the
//! composite's bytes measured in the same run.
//!
//! ```sh
//! cargo bench --bench compose                 # everything (about 6 minutes)
//! cargo bench --bench compose -- cpu/1280     # one group (criterion filter)
//! cargo bench --bench compose -- ratios-only  # the ratio table alone (a filter matching nothing)
//! COMPOSE_MODES=anaglyph-red-cyan-dubois,str-rect cargo bench --bench compose -- ratios-only
//! ```
//!
//! (`COMPOSE_MODES`: only these modes, by canonical name.)
//!
//! - `cpu/WxH/MODE`: [`compose_into`] of two in-memory eyes into a reused
//!   output image (what a frame loop or a capture does per frame);
//! - `gl/WxH/MODE`: the GL compositor composing the two eye textures into
//!   its capture framebuffer, then glFinish (no read-back);
//! - `cpu/WxH/memcpy-COMPOSITE`: `copy_from_slice` of as many bytes as the
//!   composite of the mode has (W×H×4 for same-size modes, twice that for
//!   side-by-side and top-bottom), between two preallocated buffers.
//!
//! After criterion's report, a table gives each mode's median time divided
//! by the median memcpy of its composite's bytes (same run), in wall-clock
//! time and in the thread's CPU time (on a machine shared with other jobs
//! a composition that outlasts a scheduler slice waits for a core more
//! often than a short copy does, which inflates the wall-clock ratio; the
//! CPU-time ratio is what the machine's load leaves alone).

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use criterion::{BenchmarkGroup, Criterion, measurement::WallTime};
use glstereo::backend::{BackendChoice, BackendKind};
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::gl::Gl;
use glstereo::gl::enums::*;
use glstereo::image::Image;
use glstereo::output::gl::{Job, TexRect};
use glstereo::output::pattern::noise;
use glstereo::output::{GlCompositor, OutputMode, OutputOptions, compose_into, composite_size};
use glstereo::surface::{self, Surface};

const SIZES: [(u32, u32); 2] = [(1280, 1024), (1920, 1080)];

/// Median nanoseconds per iteration of every benchmark, by id.
static RESULTS: Mutex<BTreeMap<String, Vec<f64>>> = Mutex::new(BTreeMap::new());

/// Runs `f` through criterion's `iter_custom`, keeping each sample's time
/// per iteration for the ratio table.
fn bench(group: &mut BenchmarkGroup<'_, WallTime>, id: &str, mut f: impl FnMut()) {
    let key = format!("{}/{id}", group_name(group));
    group.bench_function(id, |b| {
        b.iter_custom(|iters| {
            let start = Instant::now();
            for _ in 0..iters {
                f();
            }
            let d = start.elapsed();
            RESULTS
                .lock()
                .unwrap()
                .entry(key.clone())
                .or_default()
                .push(d.as_nanos() as f64 / iters as f64);
            d
        })
    });
}

thread_local! {
    static GROUP: std::cell::RefCell<String> = const { std::cell::RefCell::new(String::new()) };
}

fn group_name(_: &BenchmarkGroup<'_, WallTime>) -> String {
    GROUP.with(|g| g.borrow().clone())
}

fn group<'a>(c: &'a mut Criterion, name: String) -> BenchmarkGroup<'a, WallTime> {
    GROUP.with(|g| *g.borrow_mut() = name.clone());
    let mut g = c.benchmark_group(name);
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    g
}

/// Every mode but quad, or those named in `COMPOSE_MODES` (comma
/// separated canonical names).
fn modes() -> impl Iterator<Item = OutputMode> {
    let only = std::env::var("COMPOSE_MODES").ok();
    OutputMode::all().filter(move |&m| {
        m != OutputMode::Quad
            && only
                .as_deref()
                .is_none_or(|o| o.split(',').any(|n| n == m.canonical_name()))
    })
}

fn memcpy_id(bytes: usize) -> String {
    format!("memcpy-{bytes}")
}

fn cpu_benches(c: &mut Criterion) {
    let options = OutputOptions::default();
    for (w, h) in SIZES {
        let mut g = group(c, format!("cpu/{w}x{h}"));
        let (left, right) = (noise(w, h, 1), noise(w, h, 2));
        let mut sizes: Vec<usize> = modes()
            .map(|m| {
                let (cw, ch) = composite_size(m, w, h);
                cw as usize * ch as usize * 4
            })
            .collect();
        sizes.sort_unstable();
        sizes.dedup();
        for bytes in sizes {
            let src = vec![7u8; bytes];
            let mut dst = vec![0u8; bytes];
            bench(&mut g, &memcpy_id(bytes), || {
                dst.copy_from_slice(std::hint::black_box(&src));
                std::hint::black_box(&mut dst);
            });
        }
        for mode in modes() {
            let mut out = Image::new(1, 1);
            compose_into(mode, &options, &left, &right, 0, &mut out).unwrap();
            bench(&mut g, mode.canonical_name(), || {
                compose_into(mode, &options, &left, &right, 0, &mut out).unwrap();
                std::hint::black_box(&mut out);
            });
        }
        g.finish();
    }
}

/// Uploads an image as an RGBA8 texture (rows bottom first, as GL stores them).
///
/// # Safety
/// A context of `gl` must be current.
unsafe fn texture(gl: &Gl, img: &Image) -> u32 {
    let mut rows = img.clone();
    rows.flip_vertical();
    let mut t = 0;
    // SAFETY: contract; the pixels are w×h×4 bytes.
    unsafe {
        gl.GenTextures(1, &mut t);
        gl.BindTexture(GL_TEXTURE_2D, t);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        gl.TexImage2D(
            GL_TEXTURE_2D,
            0,
            GL_RGBA8 as i32,
            img.width() as i32,
            img.height() as i32,
            0,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            rows.pixels().as_ptr().cast(),
        );
    }
    t
}

fn gl_benches(c: &mut Criterion) {
    let display = match Display::open(BackendChoice::Only(BackendKind::Egl)) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("GL benches skipped: {e}");
            return;
        }
    };
    let config = display
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER])
        .unwrap();
    // A small surface only to hold a context: the benchmark brings its own textures.
    let s: Arc<Surface> = display.create_surface(&config, 16, 16).unwrap();
    surface::make_current(Some(&s)).unwrap();
    let gl = s.gl();
    let options = OutputOptions::default();
    for (w, h) in SIZES {
        let mut g = group(c, format!("gl/{w}x{h}"));
        // SAFETY: the surface's context is current.
        let (lt, rt) = unsafe { (texture(gl, &noise(w, h, 1)), texture(gl, &noise(w, h, 2))) };
        let rect = |texture| TexRect {
            texture,
            x: 0,
            y: 0,
            width: w,
            height: h,
        };
        let mut compositor = GlCompositor::new();
        for mode in modes() {
            let job = Job {
                mode,
                options,
                frame_index: 0,
                eyes: [rect(lt), rect(rt)],
                eye_size: (w, h),
                in_place: [None; 2],
            };
            // SAFETY: the context is current and owns the textures.
            unsafe {
                compositor.compose_capture(gl, &job).unwrap();
                gl.Finish();
            }
            bench(&mut g, mode.canonical_name(), || {
                // SAFETY: as above.
                unsafe {
                    compositor.compose_capture(gl, &job).unwrap();
                    gl.Finish();
                }
            });
        }
        g.finish();
    }
    surface::make_current(None).unwrap();
}

fn math_benches(c: &mut Criterion) {
    use glstereo::math::frustum::Frustum;
    use glstereo::math::hp::{StereoAdjust, hp_eye};
    use glstereo::math::parallax::parallax;
    use glstereo::math::{Eye, seeds};
    let mut g = group(c, "math".into());
    let mono = Frustum::perspective(40.0, 1.25, 1.0, 100.0).unwrap();
    let adj = StereoAdjust::new(10.0);
    bench(&mut g, "hp_eye", || {
        std::hint::black_box(hp_eye(std::hint::black_box(&mono), &adj, Eye::Left).unwrap());
    });
    bench(&mut g, "hp_eye_matrix", || {
        let p = hp_eye(std::hint::black_box(&mono), &adj, Eye::Right).unwrap();
        std::hint::black_box(p.matrix());
    });
    bench(&mut g, "parallax", || {
        std::hint::black_box(parallax(std::hint::black_box(0.065), 2.0, 5.0).unwrap());
    });
    bench(&mut g, "bourke_eye", || {
        std::hint::black_box(
            seeds::bourke_eye(
                std::hint::black_box(45.0),
                1.25,
                0.1,
                100.0,
                0.065,
                2.0,
                Eye::Left,
            )
            .unwrap(),
        );
    });
    g.finish();
}

/// Median of a benchmark's samples, in nanoseconds per iteration.
fn median_ns(id: &str) -> Option<f64> {
    let r = RESULTS.lock().unwrap();
    let mut v = r.get(id)?.clone();
    v.sort_by(f64::total_cmp);
    Some(v[v.len() / 2])
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// This thread's CPU time: on a machine shared with other jobs, the time
/// the thread actually ran (not the time it waited for a core).
fn thread_time() -> Duration {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid clock id and a timespec to write.
    let r = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    assert_eq!(r, 0, "CLOCK_THREAD_CPUTIME_ID");
    Duration::new(t.tv_sec as u64, t.tv_nsec as u32)
}

/// Medians of `compose` and of `copy`, timed in alternating blocks (4
/// copies, 4 compositions, …; the first of each block only warms the
/// caches) so that the machine's drift hits both alike and each runs as
/// warm as its own working set allows: (compose, copy) in wall-clock
/// milliseconds, then in milliseconds of this thread's CPU time.
fn alternated(
    rounds: usize,
    mut compose: impl FnMut(),
    mut copy: impl FnMut(),
) -> ((f64, f64), (f64, f64)) {
    let block = |f: &mut dyn FnMut(), into: &mut (Vec<f64>, Vec<f64>)| {
        f();
        for _ in 0..3 {
            let (t, c) = (Instant::now(), thread_time());
            f();
            let c = thread_time() - c;
            into.0.push(t.elapsed().as_secs_f64() * 1e3);
            into.1.push(c.as_secs_f64() * 1e3);
        }
    };
    let (mut a, mut b) = ((Vec::new(), Vec::new()), (Vec::new(), Vec::new()));
    for _ in 0..rounds {
        block(&mut copy, &mut b);
        block(&mut compose, &mut a);
    }
    ((median(a.0), median(b.0)), (median(a.1), median(b.1)))
}

/// The targets' table: every mode's CPU composition against a memcpy of
/// its composite's bytes, alternated (same run), and criterion's GL medians
/// against the same copy.
fn ratio_table(rounds: usize) {
    println!(
        "\nratio to a memcpy of the composite's bytes: CPU alternated with the copy \
         in blocks, {rounds} rounds, medians (wall clock; \"on-CPU\": this thread's CPU \
         time, what a loaded machine does not inflate); GL from criterion's samples above"
    );
    println!(
        "{:<36} {:>10} {:>10} {:>8} {:>10} {:>10} {:>8} {:>10} {:>8}",
        "mode @ eyes",
        "memcpy ms",
        "cpu ms",
        "cpu ×",
        "on-CPU cp",
        "on-CPU ms",
        "on-CPU ×",
        "gl ms",
        "gl ×"
    );
    let options = OutputOptions::default();
    for (w, h) in SIZES {
        let (left, right) = (noise(w, h, 1), noise(w, h, 2));
        for mode in modes() {
            let (cw, ch) = composite_size(mode, w, h);
            let bytes = cw as usize * ch as usize * 4;
            let src = vec![7u8; bytes];
            let mut dst = vec![0u8; bytes];
            let mut out = Image::new(1, 1);
            let ((cpu, copy), (cpu_t, copy_t)) = alternated(
                rounds,
                || {
                    compose_into(mode, &options, &left, &right, 0, &mut out).unwrap();
                    std::hint::black_box(&mut out);
                },
                || {
                    dst.copy_from_slice(std::hint::black_box(&src));
                    std::hint::black_box(&mut dst);
                },
            );
            let gl = median_ns(&format!("gl/{w}x{h}/{}", mode.canonical_name())).map(|v| v / 1e6);
            println!(
                "{:<36} {:>10.3} {:>10.3} {:>8.2} {:>10.3} {:>10.3} {:>8.2} {:>10} {:>8}",
                format!("{} @ {w}x{h}", mode.canonical_name()),
                copy,
                cpu,
                cpu / copy,
                copy_t,
                cpu_t,
                cpu_t / copy_t,
                gl.map_or("-".into(), |v| format!("{v:.3}")),
                gl.map_or("-".into(), |v| format!("{:.2}", v / copy)),
            );
        }
    }
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    cpu_benches(&mut c);
    gl_benches(&mut c);
    math_benches(&mut c);
    c.final_summary();
    // A filter that matches nothing (`ratios-only`) skips criterion's
    // runs: the table alone takes about 20 s on a quiet machine.
    ratio_table(15);
}

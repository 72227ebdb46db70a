//! glstereo in a stack of GL layers, in either order: VirtualGL, apitrace,
//! MangoHud and RenderDoc, and a forwarding layer of our own
//! (tests/clients/forwarder.c) that does, one at a time or all at once,
//! what VirtualGL's faker does to the layers around it
//! (`FORWARDER_LIKE_VGL`, its header says how): it takes the functions
//! below it through dlsym(RTLD_NEXT, "glXGetProcAddress") and exits when it
//! gets its own back; it shares every context with one of its own; it
//! saves framebuffer bindings as GLint and puts back only non-negative
//! ones; it offers stereo configurations of its own; it makes contexts
//! current without a surface and stands in for each window with a
//! framebuffer object of its own. VirtualGL itself is not in Debian and is
//! not built here: README.md's table of layers says what it does, run by
//! hand.
//!
//! "Below" means after glstereo in LD_PRELOAD (`glstereo-run LAYER prog`
//! for layers that append themselves, as MangoHud and renderdoccmd do, and
//! `LAYER glstereo-run prog` for those that prepend, as vglrun and apitrace
//! do, give the same order); "above" before it.

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::clients::*;
use common::preload::{Running, Screen, built, grab_ready};
use common::xvfb::Xvfb;
use glstereo::image::Image;

/// `program args` with `layer` preloaded ABOVE glstereo (first in
/// LD_PRELOAD), shown in side-by-side, on `x`.
fn above(x: &Xvfb, layer: &Path, program: &Path, args: &[&str]) -> Command {
    let mut preload = layer.as_os_str().to_owned();
    preload.push(":");
    preload.push(built().preload.as_os_str());
    let mut cmd = Command::new(program);
    cmd.args(args)
        .env("LD_PRELOAD", preload)
        .env("GLSTEREO_MODE", "side-by-side")
        .env("DISPLAY", &x.display);
    cmd
}

/// `program args` under glstereo-run (side-by-side) with `layer`
/// preloaded BELOW glstereo.
fn below(x: &Xvfb, layer: &Path, program: &Path, args: &[&str]) -> Command {
    let mut cmd = under_layer(x, program, args);
    cmd.env("LD_PRELOAD", layer);
    cmd
}

/// The forwarder's call counts, from the file FORWARDER_COUNTS named.
fn read_counts(path: &Path) -> HashMap<String, u64> {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("the forwarder wrote no counts ({}): {e}", path.display()));
    text.lines()
        .filter_map(|l| {
            let (n, c) = l.split_once(' ')?;
            Some((n.to_owned(), c.parse().ok()?))
        })
        .collect()
}

/// How often the forwarder counted `name`.
fn count_of(counts: &HashMap<String, u64>, name: &str) -> u64 {
    counts.get(name).copied().unwrap_or(0)
}

/// A scratch file for the forwarder's counts of one test.
fn counts_file(test: &str) -> PathBuf {
    common::scratch(test).join("counts")
}

#[test]
fn apitrace_records_a_glstereo_run_that_replays() {
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(640, 480);
    let dir = common::scratch("apitrace");
    let trace = dir.join("gears.trace");
    let mut cmd = Command::new("apitrace");
    cmd.arg("trace")
        .arg("-o")
        .arg(&trace)
        .arg(&built().run)
        .args(["-m", "side-by-side", "glxgears", "-stereo"])
        .env("DISPLAY", &x.display);
    let (shot, stderr) = gears_shown(&x, cmd, "apitrace trace glstereo-run glxgears -stereo");
    let (left, right) = halves(&shot);
    assert!(
        gears_in(&left) && gears_in(&right) && differing(&left, &right) > 100,
        "both eyes under apitrace"
    );
    assert!(!stderr.contains("glstereo:"), "{stderr}");
    let replay = Command::new("apitrace")
        .arg("replay")
        .arg(&trace)
        .env("DISPLAY", &x.display)
        .output()
        .expect("apitrace replay runs");
    assert!(
        replay.status.success(),
        "apitrace replay exited {}:\n{}{}",
        replay.status,
        String::from_utf8_lossy(&replay.stdout),
        String::from_utf8_lossy(&replay.stderr)
    );
    // The trace holds the layer's own calls to GL below it: its framebuffer
    // objects and the composite it presents, with the program's swaps.
    let dump = common::run_ok(Command::new("apitrace").arg("dump").arg(&trace));
    let dump = String::from_utf8_lossy(&dump.stdout);
    for call in ["glBindFramebuffer(", "glXSwapBuffers("] {
        assert!(dump.contains(call), "no {call} in the trace");
    }
}

/// How the forwarder below glstereo finds the functions it forwards to.
#[derive(Clone, Copy, Debug)]
enum Below {
    /// dlsym(RTLD_NEXT); dlopen of libGL is not faked.
    Next,
    /// dlsym(RTLD_NEXT); dlopen of libGL gives the forwarder's handle
    /// (VirtualGL's dlfaker).
    FakedDlopen,
    /// In libGL.so.1 opened at load time through the global dlopen, as
    /// VirtualGL's faker loads its "real" libGL: under glstereo that finds
    /// glstereo's exports, a loop.
    DlopenedLibGl,
}

/// Runs the legacy stereo program under glstereo-run with `forwarder`
/// preloaded below it: it must get stereo and show both eyes. Returns the
/// forwarder's call counts and the program's stderr.
fn legacy_over_forwarder(forwarder: &Path, below: Below) -> (HashMap<String, u64>, String) {
    let x = Xvfb::start(320, 240);
    let counts = common::scratch(&format!(
        "forwarder-{}-{below:?}",
        forwarder.file_name().unwrap().to_string_lossy()
    ))
    .join("counts");
    let mut cmd = under_layer(&x, &legacy_stereo(), &[&W.to_string(), &H.to_string()]);
    cmd.env("LD_PRELOAD", forwarder)
        .env("FORWARDER_COUNTS", &counts)
        .env(
            "FORWARDER_DLOPEN",
            if matches!(below, Below::FakedDlopen) {
                "1"
            } else {
                "0"
            },
        );
    if matches!(below, Below::DlopenedLibGl) {
        cmd.env("FORWARDER_NEXT", "dlopen");
    }
    let (shot, report, stderr) = grab_ready(cmd, &x.display);
    assert!(
        report.contains("glx_stereo 1 gl_stereo 1"),
        "stereo granted over the forwarder: {report}"
    );
    // RedBlue in side-by-side: the left eye's blue square in the left
    // half, the right eye's red one in the right half, grey around.
    let at = |half: u32, nx: f64, ny: f64| {
        shot.get(
            half * W / 2 + ((nx + 1.0) / 4.0 * W as f64) as u32,
            H / 4 + ((1.0 - ny) / 4.0 * H as f64) as u32,
        )
    };
    assert_eq!(at(0, -0.5, -0.5), [0, 0, 255, 255], "left eye, left half");
    assert_eq!(at(0, 0.5, 0.5), [51, 51, 51, 255], "left eye background");
    assert_eq!(at(1, 0.5, 0.5), [255, 0, 0, 255], "right eye, right half");
    assert_eq!(at(1, -0.5, -0.5), [51, 51, 51, 255], "right eye background");
    (read_counts(&counts), stderr)
}

/// As [`legacy_over_forwarder`], for a layer that composes cleanly: the
/// layer says nothing.
fn counts_over_forwarder(forwarder: &Path, below: Below) -> HashMap<String, u64> {
    let (counts, stderr) = legacy_over_forwarder(forwarder, below);
    assert!(
        !stderr.contains("glstereo:"),
        "the layer complained: {stderr}"
    );
    counts
}

/// The calls only glstereo makes (the program calls glXSwapBuffers, which
/// glstereo takes; it never binds a framebuffer) reached the forwarder.
fn assert_layer_calls_went_through(counts: &HashMap<String, u64>, what: &str) {
    for name in ["glXSwapBuffers", "glXChooseVisual", "glBindFramebuffer"] {
        assert!(
            counts.get(name).copied().unwrap_or(0) > 0,
            "{what}: glstereo's {name} did not go through the layer below it: {counts:?}"
        );
    }
}

#[test]
fn the_forwarder_counts_a_plain_programs_calls() {
    // The control: the forwarder alone sees a mono program's calls.
    let x = Xvfb::start(320, 240);
    let counts = common::scratch("forwarder-alone").join("counts");
    let mono = build_once("mono_glx", |out| {
        compile(
            Command::new("cc")
                .args(common::C_FLAGS)
                .arg(common::root().join("tests/c/mono_glx.c"))
                .arg("-o")
                .arg(out)
                .args(["-lGL", "-lX11"]),
            "mono_glx.c",
        )
    });
    let mut cmd = Command::new(mono);
    cmd.env("DISPLAY", &x.display)
        .env("LD_PRELOAD", forwarder(true))
        .env("FORWARDER_COUNTS", &counts);
    let mut p = Running::start(cmd);
    p.ready();
    p.finish();
    let counts = read_counts(&counts);
    for name in ["glXChooseVisual", "glXMakeCurrent", "glXSwapBuffers"] {
        assert!(
            counts.get(name).copied().unwrap_or(0) > 0,
            "{name}: {counts:?}"
        );
    }
}

#[test]
fn stereo_composes_with_a_plain_forwarding_layer_below() {
    // A layer that neither fakes dlopen nor hands out interposed wrappers.
    let counts = counts_over_forwarder(&forwarder(true), Below::Next);
    assert_layer_calls_went_through(&counts, "plain forwarder");
}

#[test]
fn stereo_composes_with_a_layer_that_fakes_dlopen_like_virtualgl() {
    // dlopen("libGL.so.1") gives the forwarder's handle; its
    // glXGetProcAddress hands out its own wrappers.
    let counts = counts_over_forwarder(&forwarder(true), Below::FakedDlopen);
    assert_layer_calls_went_through(&counts, "dlopen-faking forwarder");
}

#[test]
fn stereo_composes_with_a_layer_linked_like_virtualgls_faker() {
    // As above, linked as VirtualGL's faker is: the wrapper addresses it
    // hands out resolve through the global scope, to glstereo's exports
    // (`vglrun glstereo-run` recursed on that until the stack overflowed).
    let counts = counts_over_forwarder(&forwarder(false), Below::FakedDlopen);
    assert_layer_calls_went_through(&counts, "VirtualGL-like forwarder");
}

#[test]
fn a_glfw_program_composes_with_a_layer_below() {
    // GLFW dlopens libGL itself: the layer must be reached that way too,
    // and its real calls still go through the forwarder.
    let x = Xvfb::start(320, 240);
    let counts = common::scratch("forwarder-glfw").join("counts");
    let exe = c_client("glfw_stereo", &["-lglfw"]);
    let mut cmd = under_layer(&x, &exe, &[]);
    cmd.env("LD_PRELOAD", forwarder(true))
        .env("FORWARDER_COUNTS", &counts)
        .env("FORWARDER_DLOPEN", "1");
    check_client(&x, cmd, "glfw_stereo", "GLFW over a forwarder");
    let counts = read_counts(&counts);
    for name in ["glXSwapBuffers", "glBindFramebuffer"] {
        assert!(
            counts.get(name).copied().unwrap_or(0) > 0,
            "glstereo's {name} did not go through the layer below it: {counts:?}"
        );
    }
}

#[test]
fn a_layer_below_whose_real_functions_are_glstereos_is_a_loop_broken_with_a_message() {
    // The forwarder's "real" functions come from dlopen("libGL.so.1") made
    // through glstereo's dlopen at load time: glstereo's own exports. Each
    // call glstereo forwards comes straight back; glstereo must say so and
    // answer with libGL's function, never recurse.
    for local in [true, false] {
        let (counts, stderr) = legacy_over_forwarder(&forwarder(local), Below::DlopenedLibGl);
        assert!(
            stderr.contains("glstereo: glXSwapBuffers") && stderr.contains("loop"),
            "no message about the loop: {stderr}"
        );
        for line in stderr.lines() {
            assert_eq!(
                stderr.lines().filter(|l| *l == line).count(),
                1,
                "said more than once: {line}"
            );
        }
        assert!(
            counts.get("glXSwapBuffers").copied().unwrap_or(0) > 0,
            "{counts:?}"
        );
    }
}

// ---- A layer above glstereo asks it for functions -------------------------

#[test]
fn a_layer_above_that_checks_its_real_functions_gets_glstereos_own() {
    // The forwarder linked as VirtualGL's faker is, preloaded first, takes
    // every function below it from glstereo's glXGetProcAddress and exits
    // ("got the fake one instead") when one of them is its own: glstereo
    // handed out the first definition of each name in the process.
    let x = Xvfb::start(320, 240);
    for (program, args, title, libs) in [
        ("glfw_stereo", &[][..], "glfw_stereo", &["-lglfw"][..]),
        ("sdl_stereo", &["core"][..], "sdl_stereo", &["-lSDL2"][..]),
    ] {
        let exe = c_client(program, libs);
        let mut cmd = above(&x, &forwarder(false), &exe, args);
        cmd.env("FORWARDER_LIKE_VGL", "gpa");
        check_client(
            &x,
            cmd,
            title,
            &format!("{program} under a layer above glstereo"),
        );
    }
}

#[test]
fn apitrace_above_glstereo_records_a_program_that_keeps_its_stereo() {
    // `glstereo-run apitrace trace PROG`: apitrace prepends its glxtrace.so,
    // which asserts that the glXCreateContextAttribsARB it gets is not its
    // own.
    let x = Xvfb::start(320, 240);
    let trace = common::scratch("apitrace-above").join("glfw.trace");
    let mut cmd = Command::new(&built().run);
    cmd.args(["-m", "side-by-side", "apitrace", "trace", "-o"])
        .arg(&trace)
        .arg(c_client("glfw_stereo", &["-lglfw"]))
        .env("DISPLAY", &x.display);
    check_client(
        &x,
        cmd,
        "glfw_stereo",
        "GLFW traced by apitrace above glstereo",
    );
    let dump = common::run_ok(Command::new("apitrace").arg("dump").arg(&trace));
    let dump = String::from_utf8_lossy(&dump.stdout);
    // The program's own calls, as it made them.
    for call in [
        "glXCreateContextAttribsARB(",
        "glDrawBuffer(mode = GL_BACK_RIGHT)",
        "glXSwapBuffers(",
    ] {
        assert!(dump.contains(call), "no {call} in the trace");
    }
}

// ---- VirtualGL's ways below glstereo --------------------------------------

/// One of our clients under glstereo-run -m side-by-side with the forwarder
/// below it doing `ways` of VirtualGL's: it must get stereo and show both
/// eyes; returns the forwarder's counts and the program's report lines.
fn under_virtualgl_like(
    program: &str,
    args: &[&str],
    libs: &[&str],
    ways: &str,
) -> HashMap<String, u64> {
    let x = Xvfb::start(320, 240);
    let counts = counts_file(&format!("vgl-like-{program}-{}", args.join("-")));
    let mut cmd = below(&x, &forwarder(false), &c_client(program, libs), args);
    cmd.env("FORWARDER_LIKE_VGL", ways)
        .env("FORWARDER_COUNTS", &counts);
    check_client(
        &x,
        cmd,
        program,
        &format!("{program} {args:?} over a VirtualGL-like layer ({ways})"),
    );
    read_counts(&counts)
}

#[test]
fn the_layers_names_are_put_back_by_a_layer_that_saves_bindings_as_glint() {
    // VirtualGL re-creates its own framebuffer at make-current and swap and
    // puts back only bindings that read >= 0 through a GLint: a name of the
    // layer's at 0xFFFFFFFA (-6) stayed unbound (SDL2: black eyes).
    for (program, args, libs) in [
        ("sdl_stereo", &["default"][..], &["-lSDL2"][..]),
        ("sdl_stereo", &["core"][..], &["-lSDL2"][..]),
        ("glfw_stereo", &[][..], &["-lglfw"][..]),
    ] {
        let counts = under_virtualgl_like(program, args, libs, "gpa,share,bindings,surfaceless");
        assert_eq!(
            count_of(&counts, "negative-bindings"),
            0,
            "{program} {args:?}: the layer below saved a binding it cannot put back: {counts:?}"
        );
        assert!(
            count_of(&counts, "frames-shown") >= 1,
            "{program} {args:?}: no frame went through the layer below: {counts:?}"
        );
    }
}

#[test]
fn names_the_program_deletes_or_binds_without_making_them_leave_the_layers_objects_alone() {
    // legacy_stereo "names": glDelete* of every texture, renderbuffer and
    // framebuffer name in 1..65536 and just below 2^31 and 2^32, then
    // texture names 1..64 bound and filled without glGenTextures; the
    // program's own generated texture must go, the stereo buffers stay.
    let x = Xvfb::start(320, 240);
    let mut cmd = under_layer(&x, &legacy_stereo(), &[&W.to_string(), &H.to_string()]);
    cmd.env("LD_PRELOAD", forwarder(false))
        .env("FORWARDER_LIKE_VGL", "share,bindings");
    let mut p = Running::start(cmd);
    p.ready();
    p.send("names");
    let window = p.ready();
    let window = u64::from_str_radix(window.trim_start_matches("0x"), 16).expect("window id");
    let shot = Screen::open(&x.display).grab(window);
    let lines = p.stdout.clone();
    let stderr = p.finish();
    assert!(
        lines.iter().any(|l| l == "names own_texture_deleted 1"),
        "the program's own texture was not deleted: {lines:?}"
    );
    let report = lines
        .iter()
        .rev()
        .find(|l| l.starts_with("glx_stereo"))
        .unwrap();
    assert!(
        report.ends_with("error 0x0"),
        "GL error after the deletes (the stereo buffers were deleted?): {report}"
    );
    check_redblue_side_by_side(&shot, "after the program's deletes and guessed binds");
    assert!(!stderr.contains("glstereo:"), "{stderr}");
}

/// The RedBlue frame of legacy_stereo in side-by-side: the left eye's blue
/// square in the left half, the right eye's red one in the right half.
fn check_redblue_side_by_side(shot: &Image, what: &str) {
    let at = |half: u32, nx: f64, ny: f64| {
        shot.get(
            half * W / 2 + ((nx + 1.0) / 4.0 * W as f64) as u32,
            H / 4 + ((1.0 - ny) / 4.0 * H as f64) as u32,
        )
    };
    assert_eq!(
        at(0, -0.5, -0.5),
        [0, 0, 255, 255],
        "{what}: left eye, left half"
    );
    assert_eq!(
        at(0, 0.5, 0.5),
        [51, 51, 51, 255],
        "{what}: left eye background"
    );
    assert_eq!(
        at(1, 0.5, 0.5),
        [255, 0, 0, 255],
        "{what}: right eye, right half"
    );
    assert_eq!(
        at(1, -0.5, -0.5),
        [51, 51, 51, 255],
        "{what}: right eye background"
    );
}

#[test]
fn an_explicit_format_emulates_the_stereo_a_layer_below_offers() {
    // The forwarder offers stereo configurations of its own (without right
    // buffers): GLFW picks from glXGetFBConfigs. With -m side-by-side the
    // user wants that format: emulated, both eyes in their halves.
    let x = Xvfb::start(320, 240);
    let mut cmd = below(
        &x,
        &forwarder(false),
        &c_client("glfw_stereo", &["-lglfw"]),
        &[],
    );
    cmd.env("FORWARDER_LIKE_VGL", "all")
        .env("GLSTEREO_VERBOSE", "1");
    let mut p = Running::start(cmd);
    p.ready();
    let screen = Screen::open(&x.display);
    let window = screen.find_window("glfw_stereo").expect("the window");
    let shot = screen.grab(window);
    let lines = p.stdout.clone();
    let stderr = p.finish();
    check_report(&lines, "GLFW over stereo offered below, -m side-by-side");
    check_side_by_side(&shot, "GLFW over stereo offered below, -m side-by-side");
    assert!(
        stderr.contains("glstereo: stereo is emulated: both eyes shown as side-by-side")
            && !stderr.contains("stereo is native"),
        "-v says which stereo the program got: {stderr}"
    );
}

#[test]
fn without_a_format_the_stereo_a_layer_below_offers_stays_native() {
    let x = Xvfb::start(320, 240);
    let exe = c_client("glfw_stereo", &["-lglfw"]);
    let mut cmd = Command::new(&built().run);
    cmd.arg("-v")
        .arg(&exe)
        .env("DISPLAY", &x.display)
        .env("LD_PRELOAD", forwarder(false))
        .env("FORWARDER_LIKE_VGL", "stereo");
    let mut p = Running::start(cmd);
    p.ready();
    let stderr = p.finish();
    assert!(
        stderr.contains("glstereo: stereo is native") && !stderr.contains("stereo is emulated"),
        "with no format chosen, the layer below's stereo is the program's: {stderr}"
    );
}

#[test]
fn framebuffer_zero_answers_the_same_over_a_layer_that_makes_contexts_current_without_a_surface() {
    // glx_core_stereo core45 (233 checks, then its probes of framebuffer
    // 0) alone and over the forwarder doing all of VirtualGL's ways.
    let x = Xvfb::start(320, 240);
    let exe = common::scratch("stacking-core45").join("glx_core_stereo");
    common::preload::compile_plain(
        &common::root().join("tests/c/glx_core_stereo.c"),
        &exe,
        &["-lGL", "-lX11"],
    );
    let run = |layer: bool| {
        let mut c = Command::new(&built().run);
        c.args(["-m", "side-by-side"])
            .arg(&exe)
            .arg("core45")
            .env("DISPLAY", &x.display);
        if layer {
            c.env("LD_PRELOAD", forwarder(false))
                .env("FORWARDER_LIKE_VGL", "all");
        }
        let out = common::run_ok(&mut c);
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        let (summary, passed) = common::summary(&stdout);
        assert!(
            summary.ends_with(" passed, 0 failed") && passed >= 230,
            "core45 (layer below: {layer}): {summary}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        stdout
    };
    let alone = run(false);
    let layered = run(true);
    let probes = |s: &str| -> Vec<String> {
        s.lines()
            .filter(|l| l.starts_with("probe "))
            // The component type of GL_DEPTH and GL_STENCIL is the layer
            // below's answer for its own stand-in: VirtualGL asks its
            // combined depth/stencil attachment, which GL refuses
            // (GL_INVALID_OPERATION), for every program, glstereo or not.
            .filter(|l| !l.contains("(0, 0x1801, 0x8211)") && !l.contains("(0, 0x1802, 0x8211)"))
            .map(str::to_owned)
            .collect()
    };
    let (a, b) = (probes(&alone), probes(&layered));
    assert!(a.len() > 100, "{} probes", a.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x, y, "framebuffer 0 answers differently over the layer");
    }
    assert_eq!(a.len(), b.len());
}

#[test]
fn every_frame_goes_through_the_swap_of_a_layer_below() {
    // legacy_stereo presents a frame, then one per "resize": each must
    // reach the next glXSwapBuffers. In side-by-side-half (a composite of
    // the window's size) a window of llvmpipe alone gets its frames through
    // MIT-SHM, past any layer below.
    let x = Xvfb::start(320, 240);
    let counts = counts_file("every-frame-below");
    let mut cmd = Command::new(&built().run);
    cmd.args(["-m", "side-by-side-half"])
        .arg(legacy_stereo())
        .args([W.to_string(), H.to_string()])
        .env("DISPLAY", &x.display)
        .env("LD_PRELOAD", forwarder(true))
        .env("FORWARDER_COUNTS", &counts);
    let mut p = Running::start(cmd);
    p.ready();
    for _ in 0..2 {
        p.send(&format!("resize {W} {H}"));
        p.ready();
    }
    let lines = p.stdout.clone();
    let stderr = p.finish();
    assert!(!stderr.contains("glstereo:"), "{stderr}");
    assert!(
        lines
            .iter()
            .filter(|l| l.starts_with("glx_stereo 1 gl_stereo 1"))
            .count()
            == 3,
        "{lines:?}"
    );
    let counts = read_counts(&counts);
    assert!(
        count_of(&counts, "glXSwapBuffers") >= 3,
        "of 3 frames, these reached the layer below: {counts:?}"
    );
}

/// tests/clients/capture_stereo.c (GLFW, RenderDoc's in-app API header).
fn capture_client() -> PathBuf {
    c_client("capture_stereo", &["-lglfw", "-ldl"])
}

// ---- MangoHud --------------------------------------------------------------

/// MangoHud's HUD in `img`: its text is white, and glxgears draws nothing
/// white (red, green and blue gears, lit, on black).
fn hud_pixels(img: &Image) -> u32 {
    count(img, |p| p[0] > 200 && p[1] > 200 && p[2] > 200)
}

/// The two halves of a side-by-side-half window (each eye squeezed to
/// half the width, full height).
fn squeezed_halves(shot: &Image) -> (Image, Image) {
    let (w, h) = (shot.width(), shot.height());
    let hw = w / 2;
    (
        Image::from_fn(hw, h, |x, y| shot.get(x, y)),
        Image::from_fn(hw, h, |x, y| shot.get(hw + x, y)),
    )
}

#[test]
fn mangohuds_hud_shows_over_both_eyes_in_either_launch_order() {
    let _one = one_renderer_at_a_time();
    for (what, mangohud_first) in [
        ("glstereo-run mangohud glxgears -stereo", false),
        ("mangohud glstereo-run glxgears -stereo", true),
    ] {
        let x = Xvfb::start(640, 480);
        let mut cmd = if mangohud_first {
            let mut c = Command::new("mangohud");
            c.arg(&built().run);
            c
        } else {
            Command::new(&built().run)
        };
        // side-by-side-half: a composite of the window's size, which a
        // window of llvmpipe alone gets through MIT-SHM.
        cmd.args(["-m", "side-by-side-half"]);
        if !mangohud_first {
            cmd.arg("mangohud");
        }
        cmd.args(["glxgears", "-stereo"])
            .env("DISPLAY", &x.display)
            .env("MANGOHUD_CONFIG", "position=top-left,font_size=24");
        let mut gears = Renderer::start(cmd, what);
        let screen = Screen::open(&x.display);
        let (window, shot) = gears.picture(
            &screen,
            |s| s.find_window("glxgears"),
            |shot| {
                let (l, r) = squeezed_halves(shot);
                gears_in(&l) && gears_in(&r) && hud_pixels(shot) > 50
            },
        );
        let _ = gears.quit(&screen, window);
        let _ = glstereo::capture::write_png(
            &shot,
            &common::scratch(&format!("mangohud-{mangohud_first}")).join("window.png"),
        );
        let (left, right) = squeezed_halves(&shot);
        assert!(gears_in(&left) && gears_in(&right), "{what}: both eyes");
        assert!(
            differing(&left, &right) > left.width() * left.height() / 100,
            "{what}: the halves are one eye twice"
        );
        assert!(
            hud_pixels(&shot) > 50,
            "{what}: no HUD ({} white pixels)",
            hud_pixels(&shot)
        );
    }
}

// ---- RenderDoc -------------------------------------------------------------

#[test]
fn renderdoc_captures_a_stereo_core_program_in_either_order() {
    // capture_stereo asks RenderDoc's in-app API for a capture of frame 5;
    // renderdoccmd preloads librenderdoc.so after glstereo in both orders
    // (it appends; with --opt-hook-children it follows glstereo-run's exec).
    let _one = one_renderer_at_a_time();
    let dir = common::scratch("renderdoc");
    for (what, renderdoc_first) in [
        ("glstereo-run renderdoccmd capture PROG", false),
        ("renderdoccmd capture glstereo-run PROG", true),
    ] {
        let x = Xvfb::start(320, 240);
        let template = dir.join(if renderdoc_first { "first" } else { "second" });
        let client = capture_client();
        let mut cmd;
        if renderdoc_first {
            cmd = Command::new("renderdoccmd");
            cmd.args(["capture", "-w", "--opt-hook-children", "-c"])
                .arg(&template)
                .arg(&built().run)
                .args(["-m", "side-by-side"]);
        } else {
            cmd = Command::new(&built().run);
            cmd.args(["-m", "side-by-side", "renderdoccmd", "capture", "-w", "-c"])
                .arg(&template);
        }
        cmd.arg(&client)
            .args(["10", "5"])
            .env("DISPLAY", &x.display);
        let out = run_client(&x, cmd, "capture_stereo");
        check_report(&out.lines, what);
        check_side_by_side(&out.shot, what);
        assert!(
            out.lines.iter().any(|l| l == "renderdoc 1"),
            "{what}: RenderDoc was not loaded in the program: {:?}",
            out.lines
        );
        let name = format!("{}_frame", template.file_name().unwrap().to_string_lossy());
        let capture = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .find(|e| e.file_name().to_string_lossy().starts_with(&name))
            .unwrap_or_else(|| panic!("{what}: RenderDoc wrote no capture in {}", dir.display()));
        let bytes = std::fs::read(capture.path()).unwrap();
        assert!(
            bytes.starts_with(b"RDOC") && bytes.len() > 4096,
            "{what}: {} is not a RenderDoc capture",
            capture.path().display()
        );
    }
}

// ---- EGL programs ----------------------------------------------------------

/// MangoHud's text in `img`, drawn magenta (MANGOHUD_CONFIG text_color):
/// glmark2's build scene has nothing magenta.
fn magenta_pixels(img: &Image) -> u32 {
    count(img, |p| p[0] > 180 && p[1] < 90 && p[2] > 180)
}

/// A half of glmark2's window with its scene drawn: more than its clear
/// colour.
fn glmark2_drawn(img: &Image) -> bool {
    let first = img.get(0, img.height() - 1);
    count(img, |p| (0..3).any(|c| p[c].abs_diff(first[c]) > 8)) > 2000
}

#[test]
fn mangohuds_hud_shows_over_both_eyes_of_an_egl_program_under_auto_in_either_order() {
    // glmark2-es2 (EGL, OpenGL ES) dlopens libEGL.so.1; MangoHud hooks
    // eglSwapBuffers. Without glstereo MangoHud shows no HUD here (its hook
    // is not reached through glmark2's handle); the layer's libEGL stub
    // passes the swap down to it.
    // Both kinds of automatic stereo: two rendered eyes, and eyes made
    // from one render's depth.
    let _one = one_renderer_at_a_time();
    for (auto, mangohud_first) in [
        ("--auto", false),
        ("--auto", true),
        ("--auto=depth", false),
        ("--auto=depth", true),
    ] {
        let what = if mangohud_first {
            format!("mangohud glstereo-run {auto} glmark2-es2")
        } else {
            format!("glstereo-run {auto} mangohud glmark2-es2")
        };
        let what = what.as_str();
        let x = Xvfb::start(800, 600);
        let mut cmd = if mangohud_first {
            let mut c = Command::new("mangohud");
            c.arg(&built().run);
            c
        } else {
            Command::new(&built().run)
        };
        cmd.args([auto, "-m", "side-by-side-half"]);
        if !mangohud_first {
            cmd.arg("mangohud");
        }
        cmd.args(["glmark2-es2", "-s", "640x480", "-b", "build:duration=60"])
            .env("DISPLAY", &x.display)
            .env(
                "MANGOHUD_CONFIG",
                "position=top-left,font_size=24,text_color=FF00FF",
            );
        let mut run = Renderer::start(cmd, what);
        let screen = Screen::open(&x.display);
        let (window, shot) = run.picture(
            &screen,
            |s| s.find_window("glmark2 2023.01"),
            |shot| {
                let (l, r) = squeezed_halves(shot);
                glmark2_drawn(&l) && glmark2_drawn(&r) && magenta_pixels(shot) > 50
            },
        );
        let stderr = run.quit(&screen, window);
        let _ = glstereo::capture::write_png(
            &shot,
            &common::scratch(&format!("mangohud-egl-{auto}-{mangohud_first}")).join("window.png"),
        );
        let (left, right) = squeezed_halves(&shot);
        assert!(
            glmark2_drawn(&left) && glmark2_drawn(&right),
            "{what}: both eyes"
        );
        assert!(
            differing(&left, &right) > left.width() * left.height() / 200,
            "{what}: the halves are one eye twice"
        );
        assert!(
            magenta_pixels(&shot) > 50,
            "{what}: no HUD ({} magenta pixels)\n{stderr}",
            magenta_pixels(&shot)
        );
    }
}

#[test]
fn apitraces_egltrace_records_an_egl_program_under_auto_that_replays_cleanly() {
    // `apitrace trace --api egl glstereo-run --auto PROG`: egltrace.so below
    // glstereo records the program's calls the layer forwards and the
    // layer's own (its context, the eyes' draws, the composite), and
    // eglretrace replays them without a failed compile or link.
    let _one = one_renderer_at_a_time();
    let x = Xvfb::start(640, 480);
    let trace = common::scratch("apitrace-egl").join("glmark2-es2.trace");
    let _ = std::fs::remove_file(&trace);
    let mut cmd = Command::new("apitrace");
    cmd.args(["trace", "--api", "egl", "-o"])
        .arg(&trace)
        .arg(&built().run)
        .args(["--auto", "-m", "side-by-side-half"])
        .args(["glmark2-es2", "-s", "320x240", "-b", "build:duration=2"])
        .env("DISPLAY", &x.display);
    let out = common::run_ok(&mut cmd);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("FPS:"),
        "glmark2-es2 under egltrace and glstereo ran no scene:\n{stdout}"
    );
    let replay = Command::new("eglretrace")
        .arg(&trace)
        .env("DISPLAY", &x.display)
        .output()
        .expect("eglretrace runs");
    let said = format!(
        "{}{}",
        String::from_utf8_lossy(&replay.stdout),
        String::from_utf8_lossy(&replay.stderr)
    );
    assert!(
        replay.status.success(),
        "eglretrace exited {}:\n{said}",
        replay.status
    );
    for bad in ["compilation failed", "link failed", "error"] {
        assert!(!said.contains(bad), "eglretrace says {bad:?}:\n{said}");
    }
    let dump = common::run_ok(Command::new("apitrace").arg("dump").arg(&trace));
    let dump = String::from_utf8_lossy(&dump.stdout);
    // The program's context and the layer's desktop GL context sharing it,
    // the rewritten vertex stage linked, the eyes presented.
    for call in [
        "eglBindAPI(api = EGL_OPENGL_API)",
        "glLinkProgram(",
        "glBindFramebuffer(",
        "eglSwapBuffers(",
    ] {
        assert!(dump.contains(call), "no {call} in the trace");
    }
}

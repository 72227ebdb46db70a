//! The period APIs run as real C programs, headless on EGL and OSMesa: HP
//! Starbase's gescape(STEREO) (seed 000 §9) and SGI IRIS GL's stereo modes
//! (seed 002), with their eye images checked pixel by pixel against the
//! same scene drawn through the quad buffer at full resolution, and the
//! compat headers' misuse answers checked in C.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use glstereo::framing::InputFraming;
use glstereo::image::Image;
use glstereo::stereo::buffers::FramebufferShape;

const MONO: FramebufferShape = FramebufferShape {
    stereo: false,
    double_buffered: true,
};

/// Runs a C example with the backend and arguments given, writing its
/// images into a fresh scratch directory.
fn run_example(name: &str, osmesa: bool, scratch: &str, args: &[&str]) -> (PathBuf, String) {
    let exe = common::build_example(name, osmesa);
    let out = common::scratch(scratch);
    let mut cmd = Command::new(exe);
    cmd.args(["--out", out.to_str().unwrap()])
        .args(args)
        .env("GLSTEREO_BACKEND", if osmesa { "osmesa" } else { "egl" })
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_EMULATION");
    let o = common::run_ok(&mut cmd);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !stderr.contains("IRIS GL emulation:"),
        "no legacy call may fail: {stderr}"
    );
    (out, String::from_utf8_lossy(&o.stdout).into_owned())
}

fn images(dir: &Path) -> (Image, Image) {
    (
        common::png(&dir.join("left.png")),
        common::png(&dir.join("right.png")),
    )
}

/// How far `got` strays outside the range [lo, hi] (per channel, max).
fn outside(got: [u8; 4], lo: [u8; 4], hi: [u8; 4]) -> u8 {
    (0..3)
        .map(|c| {
            lo[c]
                .saturating_sub(got[c])
                .max(got[c].saturating_sub(hi[c]))
        })
        .max()
        .unwrap()
}

/// Compares `got`'s rows `y0 .. y0 + n` (one eye drawn at half vertical
/// resolution) with `full` (the same eye at full resolution, 2n rows)
/// halved vertically: row k of the half against rows 2k and 2k+1. Where
/// the two full rows agree, `got` must be within 2 of them per channel;
/// where they differ — an edge that falls between the two rows the halving
/// merges, the vertical resolution the half-height eye lacks — `got` must
/// lie within 2 of the range they span. Returns how many pixels were edges.
fn assert_matches_halved(got: &Image, y0: u32, full: &Image, what: &str) -> usize {
    let (w, n) = (full.width(), full.height() / 2);
    assert_eq!(got.width(), w, "{what}: width");
    let mut edges = 0;
    for k in 0..n {
        for x in 0..w {
            let (a, b) = (full.get(x, 2 * k), full.get(x, 2 * k + 1));
            let lo = std::array::from_fn(|c| a[c].min(b[c]));
            let hi = std::array::from_fn(|c| a[c].max(b[c]));
            if (0..3).any(|c| hi[c] - lo[c] > 2) {
                edges += 1;
            }
            let g = got.get(x, y0 + k);
            assert!(
                outside(g, lo, hi) <= 2,
                "{what}: pixel ({x}, {k}) of the half-height eye is {g:?}; the full-resolution \
                 eye has {a:?} and {b:?} in rows {} and {} (want within 2 of them)",
                2 * k,
                2 * k + 1
            );
        }
    }
    edges
}

/// Counts the pixels of `img` within 2 of `color`.
fn count(img: &Image, color: [u8; 3]) -> usize {
    img.pixels()
        .chunks(4)
        .filter(|p| (0..3).all(|c| p[c].abs_diff(color[c]) <= 2))
        .count()
}

const BLUE: [u8; 3] = [1, 1, 255];
const RED: [u8; 3] = [255, 1, 1];
const WHITE: [u8; 3] = [255, 255, 255];

/// Runs the Starbase program three ways (sync-doubled; sync-doubled then
/// turned off before saving; the windowed-OpenGL reference) and checks the
/// eyes against the reference.
fn starbase_matches_the_quad_buffer(osmesa: bool) {
    let tag = if osmesa { "osmesa" } else { "egl" };
    let (stereo, stdout) = run_example("starbase", osmesa, &format!("starbase_{tag}"), &[]);
    assert!(stdout.contains("sync-doubling on, 1280x1024"), "{stdout}");
    let (mono, _) = run_example(
        "starbase",
        osmesa,
        &format!("starbase_mono_{tag}"),
        &["--save-mono"],
    );
    let (reference, _) = run_example(
        "starbase",
        osmesa,
        &format!("starbase_quad_{tag}"),
        &["--quad-buffer"],
    );
    let (left, right) = images(&stereo);
    let (frame, frame_again) = images(&mono);
    let (ref_left, ref_right) = images(&reference);
    assert_eq!(
        (left.width(), left.height()),
        (1280, 1024),
        "each eye fills the screen"
    );
    assert_eq!(
        frame, frame_again,
        "with sync-doubling off both eyes see the one frame"
    );

    // The eyes are the frame's halves, stretched x2 as the doubled sync shows them.
    let [ls, rs] = InputFraming::SyncDoubled.sources(MONO, 1280, 1024);
    assert_eq!((ls.y, ls.height, rs.y, rs.height), (0, 512, 512, 512));
    assert!(
        left == InputFraming::SyncDoubled.extract(&ls, &frame),
        "the left eye is the upper half of the frame, stretched"
    );
    assert!(
        right == InputFraming::SyncDoubled.extract(&rs, &frame),
        "the right eye is the lower half of the frame, stretched"
    );

    // Each half is its eye of the full-resolution scene, at half the rows.
    let e1 = assert_matches_halved(&frame, 0, &ref_left, "left eye (upper half)");
    let e2 = assert_matches_halved(&frame, 512, &ref_right, "right eye (lower half)");
    // The comparison is not vacuous: it saw the rectangles and the airplane,
    // and only a small share of pixels sit on an edge.
    assert!(count(&ref_left, BLUE) > 100_000 && count(&ref_left, RED) == 0);
    assert!(count(&ref_right, RED) > 100_000 && count(&ref_right, BLUE) == 0);
    assert!(
        count(&ref_left, WHITE) > 1000 && count(&ref_right, WHITE) > 1000,
        "the airplane"
    );
    let total = 1280 * 512;
    assert!(
        e1 < total / 50 && e2 < total / 50,
        "edges {e1} and {e2} of {total} pixels per eye"
    );
}

#[test]
fn starbase_eyes_match_the_full_resolution_quad_buffer_scene_at_half_the_rows_on_egl() {
    starbase_matches_the_quad_buffer(false);
}

#[test]
fn starbase_eyes_match_the_full_resolution_quad_buffer_scene_at_half_the_rows_on_osmesa() {
    starbase_matches_the_quad_buffer(true);
}

#[test]
fn turning_sync_doubling_off_restores_the_plain_mono_frame() {
    let (mono, _) = run_example("starbase", false, "starbase_off", &["--save-mono"]);
    let (left, right) = images(&mono);
    assert!(left == right, "both eyes see the one frame");
    // The plain frame shows both squashed eyes: blue only in the upper
    // half, red only in the lower half, as the program drew them.
    let (top, bottom) = (
        Image::from_fn(1280, 512, |x, y| left.get(x, y)),
        Image::from_fn(1280, 512, |x, y| left.get(x, y + 512)),
    );
    assert!(count(&top, BLUE) > 50_000 && count(&top, RED) == 0);
    assert!(count(&bottom, RED) > 50_000 && count(&bottom, BLUE) == 0);
}

/// Compiles a C test program against the compat headers (linked with -lGL).
fn build_c_test(name: &str) -> PathBuf {
    let dir = common::scratch(&format!("{name}_build"));
    let exe = dir.join(name);
    common::compile_c(
        &[common::root().join(format!("tests/c/{name}.c"))],
        &exe,
        &["-lGL"],
    );
    exe
}

/// Runs a C test program on EGL and requires all its checks to pass.
fn run_c_test(exe: &Path, args: &[&str], env: &[(&str, &str)]) -> String {
    let mut cmd = Command::new(exe);
    cmd.args(args)
        .env("GLSTEREO_BACKEND", "egl")
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_EMULATION");
    for (k, v) in env {
        cmd.env(k, v);
    }
    let o = common::run_ok(&mut cmd);
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
    stdout
}

fn uniform(img: &Image, color: [u8; 4], what: &str) {
    for y in 0..img.height() {
        for x in 0..img.width() {
            assert_eq!(img.get(x, y), color, "{what}: pixel ({x}, {y})");
        }
    }
}

const OPAQUE_WHITE: [u8; 4] = [255, 255, 255, 255];
const OPAQUE_BLACK: [u8; 4] = [0, 0, 0, 255];

#[test]
fn bad_gescape_opcodes_and_descriptors_give_minus_one_with_errno_and_change_nothing() {
    let exe = build_c_test("starbase_abi");
    let out = common::scratch("starbase_abi");
    run_c_test(&exe, &[out.to_str().unwrap()], &[]);
    // Sync-doubled (the bad calls after turning it on changed nothing):
    // left = the white upper half, right = the black lower half, stretched.
    let on_left = common::png(&out.join("on-left.png"));
    assert_eq!((on_left.width(), on_left.height()), (64, 32));
    uniform(&on_left, OPAQUE_WHITE, "sync-doubled left eye");
    uniform(
        &common::png(&out.join("on-right.png")),
        OPAQUE_BLACK,
        "sync-doubled right eye",
    );
    // Off (a bad call did not turn it back on): both eyes the plain frame.
    let off_left = common::png(&out.join("off-left.png"));
    assert_eq!(off_left, common::png(&out.join("off-right.png")));
    for y in 0..32 {
        let want = if y < 16 { OPAQUE_WHITE } else { OPAQUE_BLACK };
        assert_eq!(off_left.get(5, y), want, "mono frame row {y}");
    }
}

fn irisgl_abi() -> PathBuf {
    use std::sync::OnceLock;
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| build_c_test("irisgl_abi")).clone()
}

#[test]
fn getgdesc_answers_the_screen_size_and_the_stereo_capabilities() {
    run_c_test(&irisgl_abi(), &["gdesc"], &[]);
}

#[test]
fn without_stereo_emulation_windows_have_no_stereo_buffers_and_say_so() {
    run_c_test(
        &irisgl_abi(),
        &["gdesc-off"],
        &[("GLSTEREO_EMULATION", "off")],
    );
}

#[test]
fn setmonitor_round_trips_through_getmonitor_and_bad_modes_change_nothing() {
    run_c_test(&irisgl_abi(), &["monitor"], &[]);
}

#[test]
fn leftbuffer_and_rightbuffer_select_the_buffers_seed_002_describes() {
    run_c_test(&irisgl_abi(), &["buffers"], &[]);
}

#[test]
fn viewport_window_and_translate_are_the_gl_calls_with_iris_gl_conventions() {
    run_c_test(&irisgl_abi(), &["transforms"], &[]);
}

#[test]
fn str_rect_str_top_and_str_bot_take_the_eyes_from_the_rows_seed_002_gives() {
    let out = common::scratch("irisgl_eyes");
    run_c_test(&irisgl_abi(), &["eyes", out.to_str().unwrap()], &[]);
    let eye = |name: &str| common::png(&out.join(format!("{name}.png")));
    const GREEN: [u8; 4] = [0, 255, 0, 255];
    const BLUE: [u8; 4] = [0, 0, 255, 255];
    const YELLOW: [u8; 4] = [255, 255, 0, 255];
    const CYAN: [u8; 4] = [0, 255, 255, 255];
    const MAGENTA: [u8; 4] = [255, 0, 255, 255];
    // STR_RECT: one frame; left eye = rows 532-1023, right eye = rows 0-491
    // (of the left buffer), stretched; none of the 40 magenta rows between.
    uniform(&eye("str_rect-left"), GREEN, "STR_RECT left eye");
    uniform(&eye("str_rect-right"), BLUE, "STR_RECT right eye");
    // STR_TOP / STR_BOT: one band, each eye from its own buffer.
    uniform(&eye("str_top-left"), GREEN, "STR_TOP left eye");
    uniform(&eye("str_top-right"), YELLOW, "STR_TOP right eye");
    uniform(&eye("str_bot-left"), BLUE, "STR_BOT left eye");
    uniform(&eye("str_bot-right"), CYAN, "STR_BOT right eye");
    // HZ60: square-pixel stereo shows each buffer whole (top-first rows).
    let (left, right) = (eye("hz60-left"), eye("hz60-right"));
    assert_eq!((left.width(), left.height()), (1280, 1024));
    for (y, l, r) in [
        (0, GREEN, YELLOW),
        (491, GREEN, YELLOW),
        (492, MAGENTA, MAGENTA),
        (531, MAGENTA, MAGENTA),
        (532, BLUE, CYAN),
        (1023, BLUE, CYAN),
    ] {
        assert_eq!(
            (left.get(640, y), right.get(640, y)),
            (l, r),
            "HZ60 row {y}"
        );
    }
}

/// Compares an eye drawn into `band_rows` rows and stretched to the full
/// height (`got`) with the same eye drawn at full resolution (`full`):
/// every pixel must lie within 2 (per channel) of the range of `full`'s
/// pixels in the same column within `radius` rows — the detail a band of
/// fewer rows cannot hold. Returns how many pixels sat near an edge (where
/// that range is wider than 2).
fn assert_matches_within_rows(got: &Image, full: &Image, radius: u32, what: &str) -> usize {
    assert_eq!(
        (got.width(), got.height()),
        (full.width(), full.height()),
        "{what}: size"
    );
    let (w, h) = (full.width(), full.height());
    let mut edges = 0;
    for y in 0..h {
        let rows = y.saturating_sub(radius)..(y + radius + 1).min(h);
        for x in 0..w {
            let (mut lo, mut hi) = ([255u8, 255, 255, 255], [0u8, 0, 0, 255]);
            for yy in rows.clone() {
                let p = full.get(x, yy);
                for c in 0..3 {
                    lo[c] = lo[c].min(p[c]);
                    hi[c] = hi[c].max(p[c]);
                }
            }
            if (0..3).any(|c| hi[c] - lo[c] > 2) {
                edges += 1;
            }
            let g = got.get(x, y);
            assert!(
                outside(g, lo, hi) <= 2,
                "{what}: pixel ({x}, {y}) is {g:?}; the full-resolution eye spans {lo:?}..{hi:?} \
                 in rows {rows:?} of that column"
            );
        }
    }
    edges
}

#[test]
fn irisgl_str_rect_eyes_match_its_square_pixel_stereo_within_the_492_rows() {
    let (str_rect, stdout) = run_example("irisgl", false, "irisgl_str_rect", &[]);
    assert!(
        stdout.contains("STR_RECT, 1280x1024 screen, each eye 1280x492"),
        "{stdout}"
    );
    let (square, stdout) = run_example("irisgl", false, "irisgl_square", &["--square-pixel"]);
    assert!(stdout.contains("square-pixel stereo"), "{stdout}");
    let (left, right) = images(&str_rect);
    let (ref_left, ref_right) = images(&square);
    assert!(count(&ref_left, BLUE) > 100_000 && count(&ref_left, RED) == 0);
    assert!(count(&ref_right, RED) > 100_000 && count(&ref_right, BLUE) == 0);
    assert!(count(&ref_left, WHITE) > 1000, "the airplane");
    // 492 rows stretched to 1024: each eye row blends two band rows whose
    // centres lie within 1024/492 ≈ 2.1 rows of it, and a band pixel's
    // coverage is decided up to half a row from a full-resolution centre:
    // 3 rows either side. (2 is too few: thin airplane lines fail it.)
    let e1 = assert_matches_within_rows(&left, &ref_left, 3, "STR_RECT left eye");
    let e2 = assert_matches_within_rows(&right, &ref_right, 3, "STR_RECT right eye");
    let total = 1280 * 1024;
    assert!(
        e1 < total / 20 && e2 < total / 20,
        "edges {e1} and {e2} of {total}"
    );
}

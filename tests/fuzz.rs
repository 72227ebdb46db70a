//! Bounded fuzzing on stable Rust (cargo-fuzz's sanitizers need nightly): a
//! deterministic structured random generator per target, seeded by the
//! committed corpus in tests/fuzz_corpus/, checking invariants through the
//! C ABI the way a C program meets the code:
//!
//! - `glx_attribs`: glXChooseVisual attribute lists (`config.rs`) through
//!   gls_config_choose — the code agrees with the parser, configs report what
//!   was asked, parse → print → parse round-trips, missing terminators caught.
//! - `output_modes`: mode names (`src/output/mode.rs`) through
//!   gls_output_from_name, any bytes (invalid UTF-8, embedded NUL) — names
//!   and aliases accepted exactly, case and spaces ignored, name → mode →
//!   name round-trips.
//! - `env`: GLSTEREO_MODE / _SWAP_EYES / _CROSSTALK / _SATURATION
//!   (`options.rs`), GLSTEREO_BACKEND, GLSTEREO_EMULATION,
//!   GLSTEREO_CAPTURE_FORMAT and GLSTEREO_JPEG_QUALITY — accepted
//!   exactly when each value is valid, every bad variable named, settings
//!   round-trip.
//! - `math`: every projection entry point (`src/math` through `src/ffi/math.rs`)
//!   with NaN, infinities, subnormals, huge and tiny values — NaN/inf always
//!   rejected, results finite, every eye frustum usable by gls_frustum_matrix,
//!   outputs untouched on error, codes as documented; and
//!   gls_parallax_report_describe with any report and buffer length.
//!
//! - `window_fits`: every output format fitted to a window
//!   (`glstereo::output::compose_fitted`, what a window under glstereo-run
//!   gets) for eyes and windows of random sizes — 1 to 3 pixels thin, small,
//!   up to 4096 long — one call after another on one thread, so that each
//!   reuses the row buffers the last one left, as a window being resized
//!   does: each frame equals the reference composite fitted to the window
//!   (`cpu::fitted`), Dubois within 1 where the eyes are changed.
//!
//! No panic anywhere (a panic would come back as GLS_ERROR_PANIC and fail).
//! Every error must carry a message of its own.
//!
//! Time: GLSTEREO_FUZZ_SECONDS (default 2) in total, shared equally by the
//! five targets; `make test` sets 60. Seed: GLSTEREO_FUZZ_SEED (default
//! fixed, so a run is reproducible). A failure prints the input as a corpus
//! line: add it to tests/fuzz_corpus/<target>.txt once fixed.

mod common;

use std::collections::BTreeMap;
use std::ffi::{CStr, CString, c_char};
use std::time::{Duration, Instant};

use glstereo::backend::{BackendChoice, BackendKind};
use glstereo::capture::stereo_photo::StereoPhotoFormat;
use glstereo::config::{ConfigRequest, EmulationPolicy, glx::*};
use glstereo::ffi::analysis::{gls_parallax_report, gls_parallax_report_describe};
use glstereo::ffi::display::*;
use glstereo::ffi::math::*;
use glstereo::ffi::output::{GLS_OUTPUT_COUNT, gls_output_from_name, gls_output_name};
use glstereo::ffi::types::*;
use glstereo::interpose::capture::{CaptureSettings, ENV_CAPTURE_FORMAT, ENV_JPEG_QUALITY};
use glstereo::output::mode::{ALIASES, OutputMode};
use glstereo::output::options::{
    ENV_CROSSTALK, ENV_MODE, ENV_SATURATION, ENV_SWAP_EYES, OutputSettings,
};

use common::last_error;

const TARGETS: u32 = 5;

// ---- the engine --------------------------------------------------------

/// SplitMix64: small, fast, and the same sequence everywhere.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn chance(&mut self, one_in: usize) -> bool {
        self.below(one_in) == 0
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

fn budget() -> Duration {
    let total: f64 = std::env::var("GLSTEREO_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2.0);
    Duration::from_secs_f64(total.max(0.0) / f64::from(TARGETS))
}

fn seed(target: &str) -> u64 {
    let base = std::env::var("GLSTEREO_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x676c_7374_6572_656f); // "glstereo"
    target
        .bytes()
        .fold(base, |h, b| h.rotate_left(5) ^ u64::from(b))
}

/// The committed corpus of a target: one input per line, '#' comments.
fn corpus(target: &str) -> Vec<String> {
    let path = common::root().join(format!("tests/fuzz_corpus/{target}.txt"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(str::to_owned)
        .collect()
}

/// Runs a target: every corpus line, then generated inputs (fresh or
/// mutated corpus lines) until the time is up. `check` gets an input in its
/// corpus form and says what is wrong with the library's answer.
fn fuzz(
    target: &str,
    generate: impl Fn(&mut Rng, &[String]) -> String,
    check: impl Fn(&str) -> Result<(), String>,
) {
    let lines = corpus(target);
    assert!(!lines.is_empty(), "empty corpus for {target}");
    for line in &lines {
        if let Err(e) = check(line) {
            panic!("{target}: corpus line {line:?}: {e}");
        }
    }
    let seed = seed(target);
    let mut rng = Rng(seed);
    let deadline = Instant::now() + budget();
    let mut n = 0u64;
    while Instant::now() < deadline {
        let input = generate(&mut rng, &lines);
        if let Err(e) = check(&input) {
            panic!(
                "{target}: input {n} of seed {seed} failed: {e}\n\
                 as a corpus line for tests/fuzz_corpus/{target}.txt:\n{input}"
            );
        }
        n += 1;
    }
    println!(
        "{target}: {} corpus lines, {n} generated inputs",
        lines.len()
    );
}

/// Checks a result code is allowed and, when it is an error, that the
/// message is the function's own.
fn expect_code(function: &str, code: gls_result, allowed: &[gls_result]) -> Result<(), String> {
    if code == GLS_ERROR_PANIC {
        return Err(format!("{function} panicked: {}", last_error()));
    }
    if !allowed.contains(&code) {
        return Err(format!(
            "{function} returned {code}, allowed {allowed:?}: {}",
            last_error()
        ));
    }
    if code != GLS_OK {
        let m = last_error();
        if !m.starts_with(&format!("{function}: ")) || m.len() < function.len() + 10 {
            return Err(format!("{function} failed with code {code} but left {m:?}"));
        }
    }
    Ok(())
}

// ---- strings with escapes (corpus form) ------------------------------------

/// Decodes a corpus string: `\xNN` is a byte, `\\` a backslash.
fn unescape(s: &str) -> Vec<u8> {
    let b = s.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'\\' && i + 1 < b.len() && b[i + 1] == b'\\' {
            out.push(b'\\');
            i += 2;
        } else if b[i] == b'\\' && i + 3 < b.len() && b[i + 1] == b'x' {
            let hex = std::str::from_utf8(&b[i + 2..i + 4]).unwrap_or("zz");
            match u8::from_str_radix(hex, 16) {
                Ok(v) => {
                    out.push(v);
                    i += 4;
                }
                Err(_) => {
                    out.push(b[i]);
                    i += 1;
                }
            }
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    out
}

/// Encodes bytes as a corpus string (printable ASCII kept, the rest `\xNN`).
fn escape(bytes: &[u8]) -> String {
    let mut s = String::new();
    for &c in bytes {
        match c {
            b'\\' => s.push_str("\\\\"),
            b'|' | b'=' => s.push_str(&format!("\\x{c:02x}")),
            0x20..=0x7e => s.push(c as char),
            _ => s.push_str(&format!("\\x{c:02x}")),
        }
    }
    s
}

/// Interesting text pieces for names and values.
fn random_text(rng: &mut Rng, words: &[&str]) -> Vec<u8> {
    let pieces: &[&[u8]] = &[
        b" ",
        b"\t",
        b"\n",
        b"-",
        b"_",
        b"0",
        b"1",
        b".",
        b"e",
        b"\xff",
        b"\xc3\xa9",
        b"\xe2\x80\x8b",
        b"\xf0\x9f\x98\x80",
        b"\0",
        b"nan",
        b"inf",
        b"-0",
        b"1e-45",
        b"0.5",
        b"+1",
        b"0x1",
    ];
    let mut v = Vec::new();
    for _ in 0..rng.below(4) + 1 {
        match rng.below(4) {
            0 => {
                let piece: &&[u8] = rng.pick(pieces);
                v.extend_from_slice(piece)
            }
            1 => {
                let w = rng.pick(words).as_bytes().to_vec();
                // Random case, truncation or a doubled character.
                let mut w: Vec<u8> = w
                    .into_iter()
                    .map(|c| {
                        if rng.chance(3) {
                            c.to_ascii_uppercase()
                        } else {
                            c
                        }
                    })
                    .collect();
                if rng.chance(5) && !w.is_empty() {
                    let k = rng.below(w.len());
                    w.truncate(k);
                }
                if rng.chance(8) && !w.is_empty() {
                    let k = rng.below(w.len());
                    w.insert(k, w[k]);
                }
                v.extend(w);
            }
            2 => v.extend_from_slice(rng.pick(words).as_bytes()),
            _ => {
                for _ in 0..rng.below(6) {
                    v.push(rng.next() as u8);
                }
            }
        }
    }
    v
}

// ---- glx_attribs -------------------------------------------------------------

const GLX_TOKENS: &[i32] = &[
    GLX_USE_GL,
    GLX_BUFFER_SIZE,
    GLX_LEVEL,
    GLX_RGBA,
    GLX_DOUBLEBUFFER,
    GLX_STEREO,
    GLX_AUX_BUFFERS,
    GLX_RED_SIZE,
    GLX_GREEN_SIZE,
    GLX_BLUE_SIZE,
    GLX_ALPHA_SIZE,
    GLX_DEPTH_SIZE,
    GLX_STENCIL_SIZE,
    GLX_ACCUM_RED_SIZE,
    GLX_ACCUM_GREEN_SIZE,
    GLX_ACCUM_BLUE_SIZE,
    GLX_ACCUM_ALPHA_SIZE,
    GLX_SAMPLE_BUFFERS,
    GLX_SAMPLES,
    GLX_FRAMEBUFFER_SRGB_CAPABLE_ARB,
];

fn gen_attribs(rng: &mut Rng, corpus: &[String]) -> String {
    let mut v: Vec<i32> = if rng.chance(2) {
        rng.pick(corpus)
            .split_whitespace()
            .filter_map(|t| t.parse().ok())
            .collect()
    } else {
        Vec::new()
    };
    let edits = rng.below(6) + 1;
    for _ in 0..edits {
        let value = match rng.below(6) {
            0 | 1 => *rng.pick(GLX_TOKENS),
            2 => rng.below(40) as i32 - 2,
            3 => *rng.pick(&[i32::MIN, i32::MAX, -1, 8, 24, 32, 0x8000]),
            4 => rng.next() as i32,
            _ => 0,
        };
        match rng.below(3) {
            0 if !v.is_empty() => {
                let k = rng.below(v.len());
                v[k] = value;
            }
            1 if !v.is_empty() => {
                v.remove(rng.below(v.len()));
            }
            _ => {
                let k = rng.below(v.len() + 1);
                v.insert(k, value);
            }
        }
    }
    if rng.chance(50) {
        // Long enough to lack a terminator within the 512 read.
        let fill = *rng.pick(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_USE_GL]);
        v.extend(std::iter::repeat_n(fill, 520));
    }
    v.iter().map(i32::to_string).collect::<Vec<_>>().join(" ")
}

/// A request printed back as an attribute list (booleans, then sizes).
fn print_request(r: &ConfigRequest) -> Vec<i32> {
    let mut v = Vec::new();
    for (on, t) in [
        (r.rgba, GLX_RGBA),
        (r.double_buffer, GLX_DOUBLEBUFFER),
        (r.stereo, GLX_STEREO),
    ] {
        if on {
            v.push(t);
        }
    }
    let sizes = [
        (GLX_RED_SIZE, r.color[0] as i32),
        (GLX_GREEN_SIZE, r.color[1] as i32),
        (GLX_BLUE_SIZE, r.color[2] as i32),
        (GLX_ALPHA_SIZE, r.color[3] as i32),
        (GLX_DEPTH_SIZE, r.depth as i32),
        (GLX_STENCIL_SIZE, r.stencil as i32),
        (GLX_ACCUM_RED_SIZE, r.accum[0] as i32),
        (GLX_ACCUM_GREEN_SIZE, r.accum[1] as i32),
        (GLX_ACCUM_BLUE_SIZE, r.accum[2] as i32),
        (GLX_ACCUM_ALPHA_SIZE, r.accum[3] as i32),
        (GLX_AUX_BUFFERS, r.aux_buffers as i32),
        (GLX_LEVEL, r.level),
        (GLX_BUFFER_SIZE, r.buffer_size as i32),
        (GLX_SAMPLES, r.samples as i32),
        (GLX_FRAMEBUFFER_SRGB_CAPABLE_ARB, r.srgb as i32),
    ];
    for (t, value) in sizes {
        v.push(t);
        v.push(value);
    }
    v
}

/// One EGL display for the whole target (choosing a config needs no GL).
fn egl_display() -> usize {
    static D: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *D.get_or_init(|| {
        let mut d = std::ptr::null_mut();
        // SAFETY: a valid out-pointer.
        let r = unsafe { gls_display_open(GLS_BACKEND_EGL, &mut d) };
        assert_eq!(r, GLS_OK, "EGL: {}", last_error());
        d as usize
    })
}

fn check_attribs(line: &str) -> Result<(), String> {
    let values: Vec<i32> = line
        .split_whitespace()
        .map(|t| t.parse().map_err(|_| format!("bad corpus token {t:?}")))
        .collect::<Result<_, _>>()?;
    // What C passes: the list up to the first 0 (the terminator).
    let list: Vec<i32> = values.iter().copied().take_while(|&v| v != 0).collect();
    let mut terminated = values.clone();
    terminated.push(0);
    let display = egl_display() as *mut gls_display;
    let mut config = std::ptr::null_mut();
    // SAFETY: a live display, a terminated list, a valid out-pointer.
    let code = unsafe { gls_config_choose(display, terminated.as_ptr(), &mut config) };
    let parsed = ConfigRequest::parse_visual_attribs(&list);
    let name = "gls_config_choose";
    if list.len() >= 512 {
        expect_code(name, code, &[GLS_ERROR_INVALID_VALUE])?;
        return if last_error().contains("terminator") {
            Ok(())
        } else {
            Err(format!("a list without terminator: {}", last_error()))
        };
    }
    match &parsed {
        Err(e) => {
            expect_code(name, code, &[e.code()])?;
            if let glstereo::Error::InvalidEnum { value, .. } = e {
                if !last_error().contains(&format!("{value:#x}")) {
                    return Err(format!(
                        "the unknown attribute is not named: {}",
                        last_error()
                    ));
                }
            }
            if !config.is_null() {
                return Err("config_out written on error".into());
            }
        }
        Ok(r) => {
            let cannot = r.unsupported_reason().is_some();
            expect_code(
                name,
                code,
                &[if cannot {
                    GLS_ERROR_NO_MATCHING_CONFIG
                } else {
                    GLS_OK
                }],
            )?;
            if code == GLS_OK {
                let get = |attrib| {
                    let mut v = -7;
                    // SAFETY: a live config and a valid out-pointer.
                    let c = unsafe { gls_config_get_attrib(config, attrib, &mut v) };
                    (c == GLS_OK).then_some(v)
                };
                let depth = if r.depth > 0 || r.stencil > 0 { 24 } else { 0 };
                let want = [
                    (GLX_STEREO, r.stereo as i32),
                    (GLX_DOUBLEBUFFER, r.double_buffer as i32),
                    (GLX_DEPTH_SIZE, depth),
                    (GLX_RGBA, 1),
                ];
                for (attrib, v) in want {
                    if get(attrib) != Some(v) {
                        return Err(format!(
                            "attribute {attrib} is {:?}, asked {v}",
                            get(attrib)
                        ));
                    }
                }
                // SAFETY: a live config.
                let stereo = gls_config_stereo(config);
                if (stereo == GLS_STEREO_EMULATED) != r.stereo {
                    return Err(format!(
                        "gls_config_stereo {stereo} for stereo {}",
                        r.stereo
                    ));
                }
                gls_config_free(config);
            }
            // parse → print → parse
            let again = ConfigRequest::parse_visual_attribs(&print_request(r))
                .map_err(|e| format!("the printed request does not parse: {e}"))?;
            if &again != r {
                return Err(format!("round trip changed {r:?} into {again:?}"));
            }
        }
    }
    Ok(())
}

#[test]
fn fuzz_glx_attribute_lists() {
    fuzz("glx_attribs", gen_attribs, check_attribs);
}

// ---- output_modes --------------------------------------------------------------

fn mode_words() -> Vec<&'static str> {
    let mut w: Vec<&'static str> = OutputMode::all().map(|m| m.canonical_name()).collect();
    w.extend(ALIASES.iter().map(|a| a.name));
    w
}

fn gen_mode(rng: &mut Rng, corpus: &[String]) -> String {
    let words = mode_words();
    let mut v = if rng.chance(3) {
        unescape(rng.pick(corpus).as_str())
    } else {
        Vec::new()
    };
    let fresh = random_text(rng, &words);
    if v.is_empty() || rng.chance(2) {
        v = fresh;
    } else {
        let k = rng.below(v.len() + 1);
        v.splice(k..k, fresh);
    }
    escape(&v)
}

fn check_mode(line: &str) -> Result<(), String> {
    let bytes = unescape(line);
    // C sees the string up to its first NUL.
    let c_bytes: Vec<u8> = bytes.iter().copied().take_while(|&b| b != 0).collect();
    let c = CString::new(c_bytes.clone()).unwrap();
    let mut out = 0xDEAD_u32;
    // SAFETY: NUL-terminated name, valid out-pointer.
    let code = unsafe { gls_output_from_name(c.as_ptr(), &mut out) };
    let name = "gls_output_from_name";
    let Ok(text) = std::str::from_utf8(&c_bytes) else {
        expect_code(name, code, &[GLS_ERROR_INVALID_VALUE])?;
        return if out == 0xDEAD {
            Ok(())
        } else {
            Err("output written on error".into())
        };
    };
    let trimmed = text.trim();
    let known = mode_words().iter().any(|w| w.eq_ignore_ascii_case(trimmed));
    if !known {
        expect_code(name, code, &[GLS_ERROR_INVALID_VALUE])?;
        if !last_error().contains("anaglyph-red-cyan") || out != 0xDEAD {
            return Err(format!("bad error for {text:?}: {} / {out}", last_error()));
        }
        return Ok(());
    }
    expect_code(name, code, &[GLS_OK])?;
    // name → mode → name
    let canonical = gls_output_name(out);
    if canonical.is_null() {
        return Err(format!("gls_output_name({out}) is NULL"));
    }
    // SAFETY: a static NUL-terminated string.
    let canonical = unsafe { CStr::from_ptr(canonical) }.to_str().unwrap();
    let m = OutputMode::from_name(canonical).map_err(|e| e.to_string())?;
    if u32::from(m) != out || OutputMode::from_name(&trimmed.to_ascii_uppercase()).ok() != Some(m) {
        return Err(format!(
            "{text:?} → {out} → {canonical:?} does not round-trip"
        ));
    }
    Ok(())
}

#[test]
fn fuzz_output_mode_names() {
    fuzz("output_modes", gen_mode, check_mode);
    // Every code that names no mode is refused with a message.
    for code in [GLS_OUTPUT_COUNT, 1000, u32::MAX] {
        if !gls_output_name(code).is_null() || !last_error().starts_with("gls_output_name: ") {
            panic!("gls_output_name({code})");
        }
    }
}

// ---- env -------------------------------------------------------------------------

const ENV_KEYS: &[&str] = &[
    "MODE",
    "SWAP",
    "CROSSTALK",
    "SATURATION",
    "BACKEND",
    "EMULATION",
    "FORMAT",
    "QUALITY",
];

fn gen_env(rng: &mut Rng, corpus: &[String]) -> String {
    let mut fields: BTreeMap<String, Vec<u8>> = if rng.chance(2) {
        parse_env_line(rng.pick(corpus).as_str())
    } else {
        BTreeMap::new()
    };
    let mut words = mode_words();
    words.extend([
        "0",
        "1",
        "true",
        "false",
        "yes",
        "no",
        "on",
        "off",
        "force",
        "auto",
        "glx",
        "egl",
        "osmesa",
        "0.25",
        "1.0",
        "0.0001",
        "1e-3",
        "-0",
        "1.5",
        "NaN",
        "inf",
        "",
        "png",
        "jps",
        "mpo",
        "png,mpo",
        " MPO , jps",
        "jpg",
        "png,",
        "90",
        "100",
        "101",
        "+7",
    ]);
    for _ in 0..rng.below(4) + 1 {
        let key = rng.pick(ENV_KEYS).to_string();
        if rng.chance(6) {
            fields.remove(&key);
        } else {
            let value = if rng.chance(2) {
                rng.pick(&words).as_bytes().to_vec()
            } else {
                random_text(rng, &words)
            };
            fields.insert(key, value);
        }
    }
    fields
        .iter()
        .map(|(k, v)| format!("{k}={}", escape(v)))
        .collect::<Vec<_>>()
        .join("|")
}

fn parse_env_line(line: &str) -> BTreeMap<String, Vec<u8>> {
    line.split('|')
        .filter_map(|f| {
            let (k, v) = f.split_once('=')?;
            Some((k.to_owned(), unescape(v)))
        })
        .collect()
}

fn check_env(line: &str) -> Result<(), String> {
    let fields: BTreeMap<String, String> = parse_env_line(line)
        .into_iter()
        .map(|(k, v)| (k, String::from_utf8_lossy(&v).into_owned()))
        .collect();
    let var = |k: &str| fields.get(k).cloned();
    let env = |name: &str| match name {
        n if n == ENV_MODE => var("MODE"),
        n if n == ENV_SWAP_EYES => var("SWAP"),
        n if n == ENV_CROSSTALK => var("CROSSTALK"),
        n if n == ENV_SATURATION => var("SATURATION"),
        _ => None,
    };
    // The documented rules, independently: trimmed; empty = unset.
    let set = |k: &str| {
        var(k)
            .map(|v| v.trim().to_owned())
            .filter(|v| !v.is_empty())
    };
    let mode_ok =
        set("MODE").is_none_or(|v| mode_words().iter().any(|w| w.eq_ignore_ascii_case(&v)));
    let swap_ok = set("SWAP").is_none_or(|v| {
        ["0", "1", "true", "false", "yes", "no"].contains(&v.to_ascii_lowercase().as_str())
    });
    let unit_ok = |k: &str| {
        set(k).is_none_or(|v| {
            v.parse::<f32>()
                .is_ok_and(|x| x.is_finite() && (0.0..=1.0).contains(&x))
        })
    };
    let bad: Vec<&str> = [
        (ENV_MODE, mode_ok),
        (ENV_SWAP_EYES, swap_ok),
        (ENV_CROSSTALK, unit_ok("CROSSTALK")),
        (ENV_SATURATION, unit_ok("SATURATION")),
    ]
    .iter()
    .filter(|(_, ok)| !ok)
    .map(|(n, _)| *n)
    .collect();
    match OutputSettings::from_env_with(env) {
        Ok(s) => {
            if !bad.is_empty() {
                return Err(format!("accepted although {bad:?} are bad"));
            }
            let o = s.options;
            if !(o.crosstalk.is_finite() && o.saturation.is_finite()) {
                return Err(format!("non-finite settings {o:?}"));
            }
            // settings → variables → settings
            let printed = |name: &str| match name {
                n if n == ENV_MODE => s.mode.map(|m| m.canonical_name().to_owned()),
                n if n == ENV_SWAP_EYES => Some(if o.swap_eyes { "1" } else { "0" }.into()),
                n if n == ENV_CROSSTALK => Some(format!("{}", o.crosstalk)),
                n if n == ENV_SATURATION => Some(format!("{}", o.saturation)),
                _ => None,
            };
            let again = OutputSettings::from_env_with(printed).map_err(|e| e.to_string())?;
            if again.mode != s.mode || again.options != o {
                return Err(format!("round trip changed {s:?} into {again:?}"));
            }
        }
        Err(e) => {
            if e.code() != GLS_ERROR_INVALID_VALUE {
                return Err(format!("code {} for a bad variable", e.code()));
            }
            let msg = e.to_string();
            if bad.is_empty() || bad.iter().any(|n| !msg.contains(n)) {
                return Err(format!("bad {bad:?}, message {msg:?}"));
            }
        }
    }
    if let Some(v) = var("BACKEND") {
        let want = match v.trim().to_ascii_lowercase().as_str() {
            "" | "auto" => Some(BackendChoice::Auto),
            "glx" => Some(BackendChoice::Only(BackendKind::Glx)),
            "egl" => Some(BackendChoice::Only(BackendKind::Egl)),
            "osmesa" => Some(BackendChoice::Only(BackendKind::OsMesa)),
            _ => None,
        };
        match (BackendChoice::from_env_value(Some(&v)), want) {
            (Ok(got), Some(w)) if got == w => {}
            (Err(e), None) if e.to_string().contains("GLSTEREO_BACKEND") => {}
            (got, w) => return Err(format!("GLSTEREO_BACKEND={v:?}: {got:?}, wanted {w:?}")),
        }
    }
    if let Some(v) = var("EMULATION") {
        let want = match v.trim().to_ascii_lowercase().as_str() {
            "" | "on" | "1" | "yes" | "true" | "auto" => Some(EmulationPolicy::Auto),
            "off" | "0" | "no" | "false" => Some(EmulationPolicy::Off),
            "force" => Some(EmulationPolicy::Force),
            _ => None,
        };
        match (EmulationPolicy::from_env_value(Some(&v)), want) {
            (Ok(got), Some(w)) if got == w => {}
            (Err(e), None) if e.to_string().contains("GLSTEREO_EMULATION") => {}
            (got, w) => return Err(format!("GLSTEREO_EMULATION={v:?}: {got:?}, wanted {w:?}")),
        }
    }
    // GLSTEREO_CAPTURE_FORMAT / GLSTEREO_JPEG_QUALITY (glstereo-run's
    // --capture-format, --jpeg-quality): a list of png/jps/mpo; 1…100.
    let capture_env = |name: &str| match name {
        n if n == ENV_CAPTURE_FORMAT => var("FORMAT"),
        n if n == ENV_JPEG_QUALITY => var("QUALITY"),
        _ => None,
    };
    let format_ok = set("FORMAT").is_none_or(|v| {
        v.split(',')
            .all(|f| ["png", "jps", "mpo"].contains(&f.trim().to_ascii_lowercase().as_str()))
    });
    let quality_ok =
        set("QUALITY").is_none_or(|v| v.parse::<u32>().is_ok_and(|q| (1..=100).contains(&q)));
    match CaptureSettings::from_env_with(capture_env) {
        Ok(c) => {
            if !(format_ok && quality_ok) {
                return Err(format!("capture settings {c:?} accepted from bad values"));
            }
            let named = |f: &str| {
                set("FORMAT")
                    .is_some_and(|v| v.split(',').any(|x| x.trim().eq_ignore_ascii_case(f)))
            };
            let png = set("FORMAT").is_none() || named("png");
            let mpo = c.photos.contains(&StereoPhotoFormat::Mpo);
            let jps = c.photos.contains(&StereoPhotoFormat::Jps);
            if (c.png, mpo, jps) != (png, named("mpo"), named("jps")) {
                return Err(format!("capture settings {c:?} for {line}"));
            }
            if !(1..=100).contains(&c.jpeg_quality) {
                return Err(format!("JPEG quality {}", c.jpeg_quality));
            }
        }
        Err(e) => {
            let msg = e.to_string();
            let names_it = (!format_ok && msg.contains(ENV_CAPTURE_FORMAT))
                || (!quality_ok && msg.contains(ENV_JPEG_QUALITY));
            if e.code() != GLS_ERROR_INVALID_VALUE || !names_it {
                return Err(format!("capture settings refused with {msg:?}"));
            }
        }
    }
    Ok(())
}

#[test]
fn fuzz_environment_variables() {
    fuzz("env", gen_env, check_env);
}

// ---- math -----------------------------------------------------------------------

/// Each entry point: its name and how many float arguments it takes (an
/// eye or equation enum, when it has one, comes last).
const MATH_FUNCTIONS: &[(&str, usize, bool)] = &[
    ("gls_stereo_eye", 9, true),
    ("gls_stereo_eye_matrix", 9, true),
    ("gls_frustum_matrix", 7, false),
    ("gls_parallax", 3, false),
    ("gls_project_point", 5, true),
    ("gls_stereo_parallax_percent", 10, false),
    ("gls_stereo_fit_budget", 12, false),
    ("gls_adjust_step", 1, true),
    ("gls_stereo_look_at", 10, false),
    ("gls_sgi_eye", 6, true),
    ("gls_bourke_eye", 6, true),
    ("gls_stereo_camera_eye", 6, true),
    ("gls_nv_stereo_matrix", 18, true),
    ("gls_parallax_report_describe", 7, true),
];

fn interesting_float(rng: &mut Rng) -> f64 {
    const POOL: &[f64] = &[
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        2.0,
        10.0,
        100.0,
        0.75,
        -0.75,
        1e-300,
        1e300,
        -1e300,
        5e-324,
        f64::MIN_POSITIVE,
        f64::MAX,
        f64::MIN,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        179.999_999,
        180.0,
        90.0,
        1e-9,
        1e9,
        3.0,
        9.0,
        -3.0,
    ];
    match rng.below(4) {
        0 => f64::from_bits(rng.next()),
        1 => (rng.next() as f64 / u64::MAX as f64) * 200.0 - 100.0,
        _ => *rng.pick(POOL),
    }
}

fn gen_math(rng: &mut Rng, corpus: &[String]) -> String {
    if rng.chance(2) {
        // Mutate a corpus line: replace some numbers.
        let line = rng.pick(corpus).clone();
        let mut parts: Vec<String> = line.split_whitespace().map(str::to_owned).collect();
        let floats = MATH_FUNCTIONS
            .iter()
            .find(|f| f.0 == parts[0])
            .map_or(0, |f| f.1);
        for _ in 0..rng.below(3) + 1 {
            if floats > 0 {
                let k = 1 + rng.below(floats);
                parts[k] = format!("{:?}", interesting_float(rng));
            }
        }
        return parts.join(" ");
    }
    let (name, floats, has_enum) = *rng.pick(MATH_FUNCTIONS);
    let mut parts = vec![name.to_owned()];
    for _ in 0..floats {
        parts.push(format!("{:?}", interesting_float(rng)));
    }
    if has_enum {
        let e = match rng.below(5) {
            0 => rng.next() as u32,
            1 => 2,
            _ => rng.below(6) as u32,
        };
        let e = if name == "gls_adjust_step" {
            *rng.pick(&[0, 1, -1, 3, -40, 100, i32::MAX, i32::MIN]) as u32
        } else if name == "gls_parallax_report_describe" {
            rng.below(300) as u32
        } else {
            e
        };
        parts.push(e.to_string());
    }
    parts.join(" ")
}

const SENTINEL: f64 = 12345.678;

fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

fn frustum_of(a: &[f64]) -> gls_frustum {
    gls_frustum {
        left: a[0],
        right: a[1],
        bottom: a[2],
        top: a[3],
        near_clip: a[4],
        far_clip: a[5],
    }
}

fn frustum_values(f: &gls_frustum) -> [f64; 6] {
    [f.left, f.right, f.bottom, f.top, f.near_clip, f.far_clip]
}

/// Checks an eye a function returned: finite, a valid frustum, and usable
/// by gls_frustum_matrix (whose matrix must be finite).
fn check_eye(f: &gls_frustum, offset: f64) -> Result<(), String> {
    let v = frustum_values(f);
    if !all_finite(&v) || !offset.is_finite() {
        return Err(format!("non-finite eye {v:?} offset {offset}"));
    }
    let mut m = [SENTINEL; 16];
    // SAFETY: valid pointers; 16 doubles.
    let code = unsafe { gls_frustum_matrix(f, offset, m.as_mut_ptr()) };
    if code != GLS_OK {
        return Err(format!(
            "the eye {v:?} (offset {offset}) is refused by gls_frustum_matrix: {}",
            last_error()
        ));
    }
    if !all_finite(&m) {
        return Err(format!("matrix of the eye {v:?} is not finite: {m:?}"));
    }
    Ok(())
}

fn check_math(line: &str) -> Result<(), String> {
    let mut parts = line.split_whitespace();
    let name = parts.next().ok_or("empty line")?;
    let &(_, floats, has_enum) = MATH_FUNCTIONS
        .iter()
        .find(|f| f.0 == name)
        .ok_or_else(|| format!("unknown function {name}"))?;
    let a: Vec<f64> = parts
        .by_ref()
        .take(floats)
        .map(|t| t.parse().map_err(|_| format!("bad number {t:?}")))
        .collect::<Result<_, _>>()?;
    if a.len() != floats {
        return Err(format!("{name} takes {floats} numbers"));
    }
    let e: u32 = if has_enum {
        let t = parts.next().ok_or("missing enum")?;
        t.parse::<u32>()
            .or_else(|_| t.parse::<i32>().map(|v| v as u32))
            .map_err(|_| format!("bad enum {t:?}"))?
    } else {
        0
    };
    let finite_in = all_finite(&a);
    let eye_ok = e <= 1;
    // The codes each may return with valid pointers, and whether the
    // result must be an error (a NaN or infinity in, or a bad enum).
    let must_fail = !finite_in || (has_enum && !eye_ok);
    let allowed_enum = if has_enum {
        &[GLS_OK, GLS_ERROR_INVALID_ENUM, GLS_ERROR_INVALID_VALUE][..]
    } else {
        &[GLS_OK, GLS_ERROR_INVALID_VALUE][..]
    };
    let mut f_out = frustum_of(&[SENTINEL; 6]);
    let mut off = SENTINEL;
    let mut m = [SENTINEL; 16];
    let unchanged = |f: &gls_frustum, off: f64, m: &[f64; 16]| {
        frustum_values(f) == [SENTINEL; 6] && off == SENTINEL && m.iter().all(|&x| x == SENTINEL)
    };
    // SAFETY (every call below): valid pointers to initialised values of
    // the sizes each function documents.
    let code = unsafe {
        match name {
            "gls_stereo_eye"
            | "gls_stereo_eye_matrix"
            | "gls_stereo_parallax_percent"
            | "gls_stereo_fit_budget" => {
                let mono = frustum_of(&a[..6]);
                let adj = gls_stereo_adjust {
                    zero_parallax_distance: a[6],
                    offset_adjustment: a[7],
                    balance_adjustment: a[8],
                };
                match name {
                    "gls_stereo_eye" => gls_stereo_eye(&mono, &adj, e, &mut f_out, &mut off),
                    "gls_stereo_eye_matrix" => {
                        gls_stereo_eye_matrix(&mono, &adj, e, m.as_mut_ptr())
                    }
                    "gls_stereo_parallax_percent" => {
                        gls_stereo_parallax_percent(&mono, &adj, a[9], &mut off)
                    }
                    _ => {
                        gls_stereo_fit_budget(&mono, &adj, a[9], a[10], a[11], &mut off, &mut m[0])
                    }
                }
            }
            "gls_frustum_matrix" => gls_frustum_matrix(&frustum_of(&a[..6]), a[6], m.as_mut_ptr()),
            "gls_parallax" => {
                off = gls_parallax(a[0], a[1], a[2]);
                if off.is_nan() {
                    off = SENTINEL;
                    GLS_ERROR_INVALID_VALUE
                } else {
                    GLS_OK
                }
            }
            "gls_project_point" => {
                let p = [a[2], a[3], a[4]];
                gls_project_point(a[0], a[1], p.as_ptr(), e, m.as_mut_ptr())
            }
            "gls_adjust_step" => {
                off = gls_adjust_step(a[0], e as i32);
                if off.is_nan() {
                    off = SENTINEL;
                    GLS_ERROR_INVALID_VALUE
                } else {
                    GLS_OK
                }
            }
            "gls_stereo_look_at" => gls_stereo_look_at(
                a[0..3].as_ptr(),
                a[3..6].as_ptr(),
                a[6..9].as_ptr(),
                a[9],
                m.as_mut_ptr(),
            ),
            "gls_sgi_eye" => {
                gls_sgi_eye(a[0], a[1], a[2], a[3], a[4], a[5], e, &mut f_out, &mut off)
            }
            "gls_bourke_eye" => {
                gls_bourke_eye(a[0], a[1], a[2], a[3], a[4], a[5], e, &mut f_out, &mut off)
            }
            "gls_stereo_camera_eye" => {
                gls_stereo_camera_eye(a[0], a[1], a[2], a[3], a[4], a[5], e, &mut f_out, &mut off)
            }
            "gls_nv_stereo_matrix" => {
                gls_nv_stereo_matrix(a[..16].as_ptr(), a[16], a[17], e, m.as_mut_ptr())
            }
            _ => return check_describe(&a, e as usize),
        }
    };
    let allowed: &[gls_result] = if name == "gls_adjust_step" || name == "gls_parallax" {
        &[GLS_OK, GLS_ERROR_INVALID_VALUE]
    } else if name == "gls_project_point" {
        &[GLS_OK, GLS_ERROR_INVALID_ENUM, GLS_ERROR_INVALID_VALUE]
    } else {
        allowed_enum
    };
    let eq_ok = name != "gls_project_point" || (1..=5).contains(&e);
    let must_fail = if name == "gls_project_point" {
        !finite_in || !eq_ok
    } else if name == "gls_adjust_step" {
        !a[0].is_finite()
    } else {
        must_fail
    };
    expect_code(name, code, allowed)?;
    if code != GLS_OK {
        return if unchanged(&f_out, off, &m) {
            Ok(())
        } else {
            Err(format!("{name} wrote its outputs on error {code}"))
        };
    }
    if must_fail {
        return Err(format!("{name} accepted {a:?} / {e}"));
    }
    match name {
        "gls_stereo_eye" | "gls_sgi_eye" | "gls_bourke_eye" | "gls_stereo_camera_eye" => {
            check_eye(&f_out, off)
        }
        "gls_stereo_parallax_percent" | "gls_parallax" | "gls_adjust_step" => {
            if !off.is_finite() {
                Err(format!("{name} gave {off}"))
            } else if name == "gls_adjust_step" && !(0.0..=2.0).contains(&off) {
                Err(format!("gls_adjust_step gave {off}, outside 0…2"))
            } else {
                Ok(())
            }
        }
        "gls_stereo_fit_budget" => {
            if !(off.is_finite() && m[0].is_finite() && off >= 0.0 && m[0] >= 0.0) {
                return Err(format!("fit gave separation {off}, adjustment {}", m[0]));
            }
            // The answer, used as the adjustment, keeps both depths in budget.
            let mono = frustum_of(&a[..6]);
            let adj = gls_stereo_adjust {
                zero_parallax_distance: a[6],
                offset_adjustment: m[0],
                balance_adjustment: a[8],
            };
            for depth in [a[9], a[10]] {
                let mut p = SENTINEL;
                // SAFETY: valid pointers.
                let c = unsafe { gls_stereo_parallax_percent(&mono, &adj, depth, &mut p) };
                if c == GLS_OK && p.abs() > a[11] * (1.0 + 1e-6) + 1e-9 {
                    return Err(format!(
                        "the fitted adjustment {} gives {p}% at depth {depth}, budget {}%",
                        m[0], a[11]
                    ));
                }
            }
            Ok(())
        }
        "gls_project_point" => {
            if all_finite(&m[..2]) {
                Ok(())
            } else {
                Err(format!("projected point {:?}", &m[..2]))
            }
        }
        _ => {
            if all_finite(&m) {
                Ok(())
            } else {
                Err(format!("{name} gave a non-finite matrix {m:?}"))
            }
        }
    }
}

/// gls_parallax_report_describe with any report (NaN, huge, any warning
/// bits) and any buffer length: never fails, NUL-terminated within len,
/// cut at a character boundary, full length reported.
fn check_describe(a: &[f64], len: usize) -> Result<(), String> {
    let report = gls_parallax_report {
        min_percent: a[0],
        max_percent: a[1],
        min_pixels: a[2],
        max_pixels: a[3],
        nearest_distance: a[4],
        farthest_distance: a[5],
        budget_percent: a[6],
        covered_pixels: a[0].to_bits(),
        warnings: a[1].to_bits() as u32,
    };
    let mut buf = vec![0x55 as c_char; len + 8];
    let mut full = usize::MAX;
    // SAFETY: buf holds len (+8) bytes; valid pointers.
    let code = unsafe { gls_parallax_report_describe(&report, buf.as_mut_ptr(), len, &mut full) };
    expect_code("gls_parallax_report_describe", code, &[GLS_OK])?;
    let bytes: Vec<u8> = buf.iter().map(|&c| c as u8).collect();
    if bytes[len..].iter().any(|&b| b != 0x55) {
        return Err(format!("wrote past len {len}"));
    }
    if len == 0 {
        return Ok(());
    }
    let Some(nul) = bytes[..len].iter().position(|&b| b == 0) else {
        return Err(format!("no NUL within len {len}"));
    };
    let text = std::str::from_utf8(&bytes[..nul]).map_err(|e| format!("not UTF-8: {e}"))?;
    // The whole text, to compare with what fitted.
    let mut whole = vec![0 as c_char; full + 1];
    let mut again = 0;
    // SAFETY: whole holds full + 1 bytes.
    let code =
        unsafe { gls_parallax_report_describe(&report, whole.as_mut_ptr(), full + 1, &mut again) };
    expect_code("gls_parallax_report_describe", code, &[GLS_OK])?;
    // SAFETY: NUL-terminated by the call above.
    let whole = unsafe { CStr::from_ptr(whole.as_ptr()) }
        .to_str()
        .map_err(|e| e.to_string())?;
    let fits = full.min(len - 1);
    if again != full
        || whole.len() != full
        || !whole.starts_with(text)
        || nul > fits
        || nul + 4 <= fits
    {
        return Err(format!(
            "wrote {nul} bytes of {full} into {len}: {text:?} of {whole:?}"
        ));
    }
    Ok(())
}

#[test]
fn fuzz_projection_parameters() {
    fuzz("math", gen_math, check_math);
}

// ---- window_fits ---------------------------------------------------------

/// A side of an eye or a window: thin, small, medium or long (up to 4096).
fn gen_side(rng: &mut Rng) -> u32 {
    match rng.below(8) {
        0 | 1 => 1 + rng.below(3) as u32,
        2..=4 => 1 + rng.below(64) as u32,
        5 | 6 => 1 + rng.below(400) as u32,
        _ => 1 + rng.below(4096) as u32,
    }
}

/// `MODE EYE_W EYE_H WIN_W WIN_H SWAP CROSSTALK SATURATION SEED`, the area
/// of the eyes and of the window kept under 2^20 pixels (a long side comes
/// with a short one).
fn gen_window_fit(rng: &mut Rng, corpus: &[String]) -> String {
    let mode = OutputMode::ALL[rng.below(OutputMode::ALL.len())];
    let mut size = || loop {
        let (w, h) = (gen_side(rng), gen_side(rng));
        if w * h <= 1 << 20 {
            return (w, h);
        }
    };
    let (eye, win) = (size(), size());
    // Often the window of the eyes' size, as a program that follows it.
    let win = if rng.chance(3) { eye } else { win };
    let changed = rng.chance(3);
    if rng.chance(8) && !corpus.is_empty() {
        // A corpus case again, after other sizes filled the buffers.
        return rng.pick(corpus).clone();
    }
    format!(
        "{} {} {} {} {} {} {} {} {}",
        mode.canonical_name(),
        eye.0,
        eye.1,
        win.0,
        win.1,
        u8::from(changed),
        if changed { 0.25 } else { 0.0 },
        if changed { 0.5 } else { 1.0 },
        rng.next() % 1000
    )
}

fn check_window_fit(line: &str) -> Result<(), String> {
    use glstereo::output::cpu::{fitted, reference};
    use glstereo::output::pattern::{gradient, noise};
    use glstereo::output::{AnaglyphMethod, OutputOptions, compose_fitted};
    let f: Vec<&str> = line.split_whitespace().collect();
    let [mode, ew, eh, ww, wh, swap, crosstalk, saturation, seed] = f[..] else {
        return Err(format!("a case has 9 fields: {line:?}"));
    };
    let num = |s: &str| s.parse::<u32>().map_err(|e| format!("{s:?}: {e}"));
    let real = |s: &str| s.parse::<f32>().map_err(|e| format!("{s:?}: {e}"));
    let mode = OutputMode::from_name(mode).map_err(|e| e.to_string())?;
    let (eye, win) = ((num(ew)?, num(eh)?), (num(ww)?, num(wh)?));
    let o = OutputOptions {
        swap_eyes: swap == "1",
        crosstalk: real(crosstalk)?,
        saturation: real(saturation)?,
    };
    let seed = u64::from(num(seed)?);
    let (l, r) = (
        noise(eye.0, eye.1, seed),
        gradient(eye.0, eye.1, seed as u8),
    );
    let mut got = glstereo::image::Image::new(1, 1);
    let done = compose_fitted(mode, &o, &l, &r, 1, win, &mut got);
    if mode == OutputMode::Quad {
        // Not a composite: refused, the image untouched.
        return match done {
            Err(_) if got.width() == 1 => Ok(()),
            _ => Err("quad was composed".into()),
        };
    }
    done.map_err(|e| format!("refused: {e}"))?;
    let want = fitted(
        &reference(mode, &o, &l, &r, 1).map_err(|e| e.to_string())?,
        mode,
        win,
    );
    let (d, x, y, c) = got
        .max_difference(&want)
        .ok_or_else(|| format!("a {}x{} image, want {win:?}", got.width(), got.height()))?;
    let dubois = matches!(mode, OutputMode::Anaglyph(_, AnaglyphMethod::Dubois));
    if d > u8::from(dubois) {
        return Err(format!(
            "({x}, {y}) channel {c} is {:?}, the reference fitted {:?}",
            got.get(x, y),
            want.get(x, y)
        ));
    }
    Ok(())
}

#[test]
fn fuzz_window_fits() {
    fuzz("window_fits", gen_window_fit, check_window_fit);
}

//! The C misuse suites: every function of glstereo.h called wrongly — NULL
//! pointers, bad enums, out-of-range values, no current surface, dead
//! handles, surfaces of several displays — returns its documented code
//! with a message of its own, and the process goes on.
//!
//! - tests/c/misuse.c: the library's own API (headless; with "glx", GLX
//!   displays on a private Xvfb);
//! - tests/c/misuse_glx.c: the stereo layer's gls_glx_* / gls_gl_*
//!   functions on a private Xvfb (NULL displays and pointers, bad values,
//!   destroyed contexts, double destroy, contexts and configurations of
//!   another display, GL calls with no, a mono, a stereo and a core-profile
//!   context), once through libglstereo and once, rebuilt with the real
//!   GLX/GL names, under glstereo-run (libglstereo_preload.so).
//!
//! The list of functions is taken from the header, so a new export without
//! a misuse case fails `every_export_of_the_header_has_a_misuse_case`.
//! The suites also run under valgrind (here) and with ASan/UBSan
//! (tests/sanitize.rs).

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The functions glstereo.h declares (the names before "(" on declaration
/// lines; comments, macros and typedefs skipped).
fn header_functions() -> BTreeSet<String> {
    let text = std::fs::read_to_string(common::root().join("include/glstereo.h")).unwrap();
    let mut names = BTreeSet::new();
    for line in text.lines() {
        let skip = ["/", "*", " ", "#", "typedef", "}", "extern"];
        if line.is_empty() || skip.iter().any(|p| line.starts_with(p)) {
            continue;
        }
        // The identifier right before the first "(" is the function.
        let Some(paren) = line.find('(') else {
            continue;
        };
        let head = &line[..paren];
        let start = head
            .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .map_or(0, |i| i + 1);
        if head[start..].starts_with("gls_") {
            names.insert(head[start..].to_owned());
        }
    }
    names
}

/// The functions a shared library exports whose names start with `prefix`
/// (its dynamic symbol table). The preload library's glX*/gl* exports can be
/// listed the same way, to require a misuse case for each.
fn library_exports(lib: &Path, prefix: &str) -> BTreeSet<String> {
    let o = Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(lib)
        .output()
        .expect("nm runs (package binutils, installed with gcc)");
    assert!(o.status.success(), "nm {}", lib.display());
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| {
            let mut f = l.split_whitespace();
            let (_addr, kind, name) = (f.next()?, f.next()?, f.next()?);
            (kind == "T" && name.starts_with(prefix)).then(|| name.to_owned())
        })
        .collect()
}

/// Builds the suite into its own scratch directory.
fn build(scratch: &str) -> PathBuf {
    let exe = common::scratch(scratch).join("misuse");
    common::compile_c(
        &[common::root().join("tests/c/misuse.c")],
        &exe,
        &[
            "-I",
            common::root().join("tests/c").to_str().unwrap(),
            "-pthread",
        ],
    );
    exe
}

/// Runs the suite; it must pass every check and exit 0.
fn run(exe: &Path, args: &[&str], display: Option<&str>) -> Output {
    let mut cmd = Command::new(exe);
    cmd.args(args)
        .env("RUST_BACKTRACE", "0")
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_EMULATION");
    match display {
        Some(d) => cmd.env("DISPLAY", d),
        None => cmd.env_remove("DISPLAY"),
    };
    let o = common::run_ok(&mut cmd);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
    o
}

/// Builds tests/c/misuse_egl.c against glstereo.h (the gls_egl_ names)
/// and libEGL (the real ones, its oracle).
fn build_egl() -> PathBuf {
    let exe = common::scratch("misuse-egl").join("misuse_egl");
    let src = common::root().join("tests/c/misuse_egl.c");
    common::compile_c(&[src], &exe, &["-lEGL", "-lGLESv2", "-lX11"]);
    exe
}

/// Builds tests/c/misuse_glx.c: against glstereo.h (the gls_ names), or
/// with `preload` as a plain GLX program (the real names, no glstereo) to
/// run under glstereo-run.
fn build_glx(scratch: &str, preload: bool) -> PathBuf {
    let exe = common::scratch(scratch).join("misuse_glx");
    let src = common::root().join("tests/c/misuse_glx.c");
    let include = format!("-I{}", common::root().join("tests/c").display());
    if preload {
        common::preload::compile_plain(
            &src,
            &exe,
            &[&include, "-DMISUSE_PRELOAD", "-lGL", "-lX11"],
        );
    } else {
        common::compile_c(&[src], &exe, &[&include, "-lGL", "-lX11"]);
    }
    exe
}

/// The lines of stdout that start with `prefix` (the rest of each).
fn listed(o: &Output, prefix: &str) -> BTreeSet<String> {
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| l.strip_prefix(prefix))
        .map(str::to_owned)
        .collect()
}

fn covered(o: &Output) -> BTreeSet<String> {
    listed(o, "covers ")
}

/// The number of checks a run passed.
fn passed(o: &Output) -> usize {
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .find_map(|l| l.strip_suffix(" passed, 0 failed")?.parse().ok())
        .unwrap_or(0)
}

#[test]
fn every_export_of_the_header_has_a_misuse_case() {
    let exe = build("misuse");
    let o = run(&exe, &[], None);
    let x = common::xvfb::Xvfb::start(320, 240);
    let glx = run(&build_glx("misuse-layer", false), &[], Some(&x.display));
    let egl = run(&build_egl(), &[], Some(&x.display));
    let declared = header_functions();
    let mut exercised = covered(&o);
    exercised.extend(covered(&glx));
    exercised.extend(covered(&egl));
    assert!(
        declared.len() > 80,
        "the header parser found only {declared:?}"
    );
    let missing: Vec<_> = declared.difference(&exercised).collect();
    let unknown: Vec<_> = exercised.difference(&declared).collect();
    assert!(
        missing.is_empty(),
        "exports of include/glstereo.h without a case in tests/c/misuse.c, \
         tests/c/misuse_glx.c or tests/c/misuse_egl.c: {missing:?}"
    );
    assert!(
        unknown.is_empty(),
        "the misuse suites exercise names the header does not declare: {unknown:?}"
    );
    let (library, layer, egl) = (passed(&o), passed(&glx), passed(&egl));
    assert!(
        library > 1000 && layer > 400 && egl > 50,
        "only {library} + {layer} + {egl} checks ran: was a section skipped?"
    );
}

/// The GLX or GL name a gls_glx_* / gls_gl_* function stands in for (the
/// name the preload library exports it under, and its stderr messages use).
fn legacy_name(gls: &str) -> &'static str {
    const NAMES: &[(&str, &str)] = &[
        ("gls_glx_choose_visual", "glXChooseVisual"),
        ("gls_glx_get_config", "glXGetConfig"),
        ("gls_glx_choose_fbconfig", "glXChooseFBConfig"),
        ("gls_glx_choose_fbconfig_sgix", "glXChooseFBConfigSGIX"),
        ("gls_glx_get_fbconfigs", "glXGetFBConfigs"),
        ("gls_glx_get_fbconfig_attrib", "glXGetFBConfigAttrib"),
        (
            "gls_glx_get_fbconfig_attrib_sgix",
            "glXGetFBConfigAttribSGIX",
        ),
        (
            "gls_glx_get_visual_from_fbconfig",
            "glXGetVisualFromFBConfig",
        ),
        (
            "gls_glx_get_visual_from_fbconfig_sgix",
            "glXGetVisualFromFBConfigSGIX",
        ),
        ("gls_glx_create_context", "glXCreateContext"),
        ("gls_glx_create_new_context", "glXCreateNewContext"),
        (
            "gls_glx_create_context_with_config_sgix",
            "glXCreateContextWithConfigSGIX",
        ),
        (
            "gls_glx_create_context_attribs_arb",
            "glXCreateContextAttribsARB",
        ),
        ("gls_glx_destroy_context", "glXDestroyContext"),
        ("gls_glx_make_current", "glXMakeCurrent"),
        ("gls_glx_make_context_current", "glXMakeContextCurrent"),
        ("gls_glx_swap_buffers", "glXSwapBuffers"),
        ("gls_glx_create_window", "glXCreateWindow"),
        ("gls_glx_destroy_window", "glXDestroyWindow"),
        ("gls_glx_create_pixmap", "glXCreatePixmap"),
        ("gls_glx_create_pbuffer", "glXCreatePbuffer"),
        (
            "gls_glx_create_glx_pixmap_with_config_sgix",
            "glXCreateGLXPixmapWithConfigSGIX",
        ),
        ("gls_glx_create_glx_pbuffer_sgix", "glXCreateGLXPbufferSGIX"),
        ("gls_gl_get_programiv", "glGetProgramiv"),
        ("gls_gl_get_program_binary", "glGetProgramBinary"),
        ("gls_gl_get_program_binary_oes", "glGetProgramBinaryOES"),
        ("gls_gl_program_binary", "glProgramBinary"),
        ("gls_gl_program_binary_oes", "glProgramBinaryOES"),
        ("gls_glx_destroy_pbuffer", "glXDestroyPbuffer"),
        (
            "gls_glx_destroy_glx_pbuffer_sgix",
            "glXDestroyGLXPbufferSGIX",
        ),
        ("gls_glx_destroy_pixmap", "glXDestroyPixmap"),
        ("gls_glx_destroy_glx_pixmap", "glXDestroyGLXPixmap"),
        ("gls_glx_get_proc_address", "glXGetProcAddress"),
        ("gls_gl_draw_buffers", "glDrawBuffers"),
        ("gls_gl_draw_buffers_arb", "glDrawBuffersARB"),
        ("gls_gl_get_integerv", "glGetIntegerv"),
        ("gls_gl_get_booleanv", "glGetBooleanv"),
        ("gls_gl_get_floatv", "glGetFloatv"),
        ("gls_gl_get_doublev", "glGetDoublev"),
        ("gls_gl_delete_framebuffers", "glDeleteFramebuffers"),
        ("gls_gl_delete_framebuffers_ext", "glDeleteFramebuffersEXT"),
        ("gls_gl_delete_textures", "glDeleteTextures"),
        ("gls_gl_delete_textures_ext", "glDeleteTexturesEXT"),
        ("gls_gl_delete_renderbuffers", "glDeleteRenderbuffers"),
        (
            "gls_gl_delete_renderbuffers_ext",
            "glDeleteRenderbuffersEXT",
        ),
        (
            "gls_gl_get_framebuffer_attachment_parameteriv",
            "glGetFramebufferAttachmentParameteriv",
        ),
        (
            "gls_gl_get_framebuffer_attachment_parameteriv_ext",
            "glGetFramebufferAttachmentParameterivEXT",
        ),
        ("gls_gl_clear_bufferfv", "glClearBufferfv"),
        ("gls_gl_clear_bufferiv", "glClearBufferiv"),
        ("gls_gl_clear_bufferuiv", "glClearBufferuiv"),
        (
            "gls_gl_clear_named_framebufferfv",
            "glClearNamedFramebufferfv",
        ),
        (
            "gls_gl_clear_named_framebufferiv",
            "glClearNamedFramebufferiv",
        ),
        (
            "gls_gl_clear_named_framebufferuiv",
            "glClearNamedFramebufferuiv",
        ),
        (
            "gls_gl_named_framebuffer_draw_buffers",
            "glNamedFramebufferDrawBuffers",
        ),
        ("gls_gl_invalidate_framebuffer", "glInvalidateFramebuffer"),
        (
            "gls_gl_invalidate_named_framebuffer_data",
            "glInvalidateNamedFramebufferData",
        ),
        (
            "gls_gl_invalidate_named_framebuffer_sub_data",
            "glInvalidateNamedFramebufferSubData",
        ),
        (
            "gls_gl_check_named_framebuffer_status",
            "glCheckNamedFramebufferStatus",
        ),
        (
            "gls_gl_check_named_framebuffer_status_ext",
            "glCheckNamedFramebufferStatusEXT",
        ),
        (
            "gls_gl_invalidate_sub_framebuffer",
            "glInvalidateSubFramebuffer",
        ),
        (
            "gls_gl_get_named_framebuffer_attachment_parameteriv",
            "glGetNamedFramebufferAttachmentParameteriv",
        ),
        (
            "gls_gl_get_named_framebuffer_parameteriv",
            "glGetNamedFramebufferParameteriv",
        ),
        (
            "gls_gl_get_framebuffer_parameteriv",
            "glGetFramebufferParameteriv",
        ),
        ("gls_gl_create_shader_programv", "glCreateShaderProgramv"),
        ("gls_gl_get_booleani_v", "glGetBooleani_v"),
        ("gls_gl_get_boolean_indexedv_ext", "glGetBooleanIndexedvEXT"),
        ("gls_gl_get_integeri_v", "glGetIntegeri_v"),
        ("gls_gl_get_integer_indexedv_ext", "glGetIntegerIndexedvEXT"),
        ("gls_gl_get_integer64i_v", "glGetInteger64i_v"),
        ("gls_gl_get_integer64v", "glGetInteger64v"),
        ("gls_gl_get_floati_v", "glGetFloati_v"),
        ("gls_gl_get_floati_v_ext", "glGetFloati_vEXT"),
        ("gls_gl_get_floati_v_oes", "glGetFloati_vOES"),
        ("gls_gl_get_float_indexedv_ext", "glGetFloatIndexedvEXT"),
        ("gls_gl_get_doublei_v", "glGetDoublei_v"),
        ("gls_gl_get_doublei_v_ext", "glGetDoublei_vEXT"),
        ("gls_gl_get_double_indexedv_ext", "glGetDoubleIndexedvEXT"),
    ];
    NAMES
        .iter()
        .find(|(g, _)| *g == gls)
        .unwrap_or_else(|| panic!("{gls} is refused by the suite but has no legacy name here"))
        .1
}

/// Checks the stderr of a misuse_glx run: each refused function said so,
/// as `glstereo: <GLX/GL name> refused: …`, each distinct message once, and
/// the layer said nothing else.
fn check_refusals_on_stderr(o: &Output) {
    let stderr = String::from_utf8_lossy(&o.stderr);
    let refused = listed(o, "refuses ");
    assert!(refused.len() > 20, "refusals listed: {refused:?}");
    for gls in &refused {
        let line = format!("glstereo: {} refused: ", legacy_name(gls));
        assert!(
            stderr.contains(&line),
            "{gls}: no \"{line}…\" line\n{stderr}"
        );
    }
    // Each distinct message once, however often the call was refused.
    let mut lines: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains(" refused: "))
        .collect();
    let all = lines.len();
    lines.sort_unstable();
    lines.dedup();
    assert_eq!(lines.len(), all, "a message repeated:\n{stderr}");
    let other: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("glstereo:") && !l.contains(" refused: "))
        .collect();
    // The suite sets NV_3dvision_settings parameters without --auto: said
    // once, as the extension's calls do nothing then.
    let nv = "glstereo: glStereoParameterNV has no effect: automatic stereo is off";
    let said = other.iter().filter(|l| l.starts_with(nv)).count();
    assert_eq!(
        said, 1,
        "glStereoParameter*NV without --auto said once:\n{stderr}"
    );
    let other: Vec<&&str> = other.iter().filter(|l| !l.starts_with(nv)).collect();
    assert!(other.is_empty(), "the layer also said: {other:?}");
}

#[test]
fn the_stereo_layer_refuses_what_libgl_would_crash_on_and_passes_the_rest() {
    let x = common::xvfb::Xvfb::start(320, 240);
    let o = run(
        &build_glx("misuse-layer-compat", false),
        &[],
        Some(&x.display),
    );
    check_refusals_on_stderr(&o);
}

#[test]
fn the_same_misuse_through_libglstereo_preload_under_glstereo_run() {
    let x = common::xvfb::Xvfb::start(320, 240);
    let exe = build_glx("misuse-layer-preload", true);
    let mut cmd = Command::new(&common::preload::built().run);
    cmd.arg(exe)
        .env("DISPLAY", &x.display)
        .env("RUST_BACKTRACE", "0")
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_SWAP_EYES")
        .env_remove("GLSTEREO_CAPTURE_DIR");
    let o = common::run_ok(&mut cmd);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
    assert!(passed(&o) > 400, "{stdout}");
    check_refusals_on_stderr(&o);
}

#[test]
fn the_header_declares_exactly_what_the_library_exports() {
    // A function exported without a declaration could not be called (or
    // misused) from C; a declaration without an export would not link.
    let declared = header_functions();
    let exported = library_exports(&common::lib_dir().join("libglstereo.so"), "gls_");
    assert_eq!(
        declared, exported,
        "include/glstereo.h and libglstereo.so disagree"
    );
}

#[test]
fn glx_configurations_and_current_surfaces_across_connections() {
    let exe = build("misuse-glx");
    let x = common::xvfb::Xvfb::start(320, 240);
    let o = run(&exe, &["glx"], Some(&x.display));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("covers gls_display_open"), "{stdout}");
}

#[test]
fn the_misuse_suite_is_clean_under_valgrind() {
    // ASan (tests/sanitize.rs) instruments the C side only; valgrind sees
    // every read and write of the library's own (Rust) code too, e.g. that
    // a dead handle is never dereferenced. Mesa's shader disk cache is off:
    // its zstd compression trips valgrind's uninitialised-value check.
    let exe = build("misuse-valgrind");
    let o = Command::new("valgrind")
        .args([
            "--error-exitcode=99",
            "--leak-check=full",
            "--show-leak-kinds=definite",
            "--errors-for-leak-kinds=definite",
        ])
        .arg(format!(
            "--suppressions={}",
            common::root()
                .join("tests/sanitize/valgrind.supp")
                .display()
        ))
        .arg(exe)
        .env("MESA_SHADER_CACHE_DISABLE", "true")
        .env("LP_NUM_THREADS", "0")
        .env("RUST_BACKTRACE", "0")
        .env_remove("DISPLAY")
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_EMULATION")
        .output()
        .expect("valgrind runs (package valgrind; `make deps` installs it)");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && stdout.contains(" passed, 0 failed"),
        "valgrind: {}\n{stdout}\n{}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
}

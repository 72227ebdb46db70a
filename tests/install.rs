//! `make install PREFIX=…` into a temporary prefix, then what a user does
//! with it: pkg-config finds glstereo, `cc prog.c $(pkg-config --cflags
//! --libs glstereo)` builds and runs, a program rebuilt with
//! <glstereo/compat.h> runs, and the installed glstereo-run finds its
//! preload library and runs an unmodified stereo program.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::preload::{Running, Screen};
use common::xvfb::Xvfb;

/// The profile this test binary was built with, as the Makefile names it.
fn profile() -> String {
    common::lib_dir()
        .parent()
        .and_then(|p| p.file_name())
        .and_then(|n| n.to_str())
        .unwrap_or("debug")
        .to_owned()
}

fn sh(script: &str, env: &[(&str, &Path)]) -> std::process::Output {
    let mut cmd = Command::new("sh");
    cmd.arg("-c").arg(script);
    for (k, v) in env {
        cmd.env(k, v);
    }
    common::run_ok(&mut cmd)
}

fn install(prefix: &Path) {
    let out = Command::new("make")
        .arg("-C")
        .arg(common::root())
        .arg("install")
        .arg(format!("PREFIX={}", prefix.display()))
        .arg(format!("INSTALL_PROFILE={}", profile()))
        .arg(format!("CARGO={}", env!("CARGO")))
        .output()
        .expect("make runs");
    assert!(
        out.status.success(),
        "make install failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn make_install_gives_a_c_library_pkg_config_and_glstereo_run() {
    let dir = common::scratch("install");
    let prefix = dir.join("prefix");
    install(&prefix);
    let lib = prefix.join("lib");
    let version = env!("CARGO_PKG_VERSION");

    // Files, soname and links, as a C library installs.
    for f in [
        format!("lib/libglstereo.so.{version}"),
        "lib/libglstereo.a".into(),
        "lib/libglstereo_preload.so".into(),
        // The stubs a program that dlopens GL gets (src/interpose/next.rs).
        "lib/libglstereo_stub_GL.so".into(),
        "lib/libglstereo_stub_GLX.so".into(),
        "lib/libglstereo_stub_OpenGL.so".into(),
        "lib/libglstereo_stub_EGL.so".into(),
        "lib/libglstereo_stub_GLESv2.so".into(),
        "lib/pkgconfig/glstereo.pc".into(),
        "include/glstereo.h".into(),
        "include/glstereo/compat.h".into(),
        "include/glstereo/starbase.h".into(),
        "bin/glstereo-run".into(),
        "share/man/man1/glstereo-run.1".into(),
    ] {
        assert!(prefix.join(&f).is_file(), "{f} installed");
    }
    assert_eq!(
        std::fs::read_link(lib.join("libglstereo.so")).unwrap(),
        PathBuf::from("libglstereo.so.0")
    );
    assert_eq!(
        std::fs::read_link(lib.join("libglstereo.so.0")).unwrap(),
        PathBuf::from(format!("libglstereo.so.{version}"))
    );
    let dynamic = sh(
        "readelf -d \"$LIB\"",
        &[("LIB", &lib.join("libglstereo.so"))],
    );
    assert!(
        String::from_utf8_lossy(&dynamic.stdout).contains("Library soname: [libglstereo.so.0]"),
        "soname"
    );

    // pkg-config.
    let pc = [("PKG_CONFIG_PATH", lib.join("pkgconfig"))];
    let pc: Vec<(&str, &Path)> = pc.iter().map(|(k, v)| (*k, v.as_path())).collect();
    let flags = sh("pkg-config --cflags --libs glstereo", &pc);
    let flags = String::from_utf8_lossy(&flags.stdout).into_owned();
    assert!(
        flags.contains(&format!("-I{}", prefix.join("include").display())),
        "{flags}"
    );
    assert!(flags.contains(&format!("-L{}", lib.display())), "{flags}");
    assert!(flags.contains("-lglstereo"), "{flags}");
    let v = sh("pkg-config --modversion glstereo", &pc);
    assert_eq!(String::from_utf8_lossy(&v.stdout).trim(), version);

    // A program built with exactly `cc prog.c $(pkg-config --cflags --libs glstereo)`.
    let src = common::root().join("tests/c/installed.c");
    let exe = dir.join("installed");
    let mut env = pc.clone();
    env.push(("SRC", &src));
    env.push(("EXE", &exe));
    sh(
        "cc \"$SRC\" $(pkg-config --cflags --libs glstereo) -o \"$EXE\"",
        &env,
    );
    let out = common::run_ok(
        Command::new(&exe)
            .env("LD_LIBRARY_PATH", &lib)
            .env("GLSTEREO_BACKEND", "egl"),
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
    // It runs against the installed library.
    let ldd = sh("ldd \"$EXE\"", &[("EXE", &exe), ("LD_LIBRARY_PATH", &lib)]);
    assert!(
        String::from_utf8_lossy(&ldd.stdout)
            .contains(&format!("{}/libglstereo.so.0", lib.display())),
        "{}",
        String::from_utf8_lossy(&ldd.stdout)
    );

    let x = Xvfb::start(320, 240);

    // A legacy program rebuilt with <glstereo/compat.h> against the install.
    let compat_src = common::root().join("tests/c/compat_legacy.c");
    let compat = dir.join("compat_legacy");
    let mut env = pc.clone();
    env.push(("SRC", &compat_src));
    env.push(("EXE", &compat));
    sh(
        "cc -std=c99 \"$SRC\" $(pkg-config --cflags --libs glstereo) -lGL -lX11 -o \"$EXE\"",
        &env,
    );
    let mut cmd = Command::new(&compat);
    cmd.env("LD_LIBRARY_PATH", &lib).env("DISPLAY", &x.display);
    let mut p = Running::start(cmd);
    let id = p.ready();
    let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).unwrap();
    // The default mode: red from the left eye, green and blue from the right
    // (a pixel inside the left eye's blue rectangle only).
    let shot = Screen::open(&x.display).grab(window);
    assert_eq!(shot.get(40, 90), [0, 51, 51, 255], "anaglyph pixel");
    assert!(p.stdout[0].contains("gl_stereo 1"), "{:?}", p.stdout);
    p.finish();

    // The installed glstereo-run finds the installed preload library and
    // runs the unmodified program.
    let legacy = dir.join("legacy_stereo");
    common::preload::compile_plain(
        &common::root().join("tests/c/legacy_stereo.c"),
        &legacy,
        &["-lGL", "-lX11"],
    );
    let mut cmd = Command::new(prefix.join("bin/glstereo-run"));
    cmd.args(["-m", "left"])
        .arg(&legacy)
        .env("DISPLAY", &x.display)
        .env_remove("GLSTEREO_PRELOAD_LIB");
    let mut p = Running::start(cmd);
    let id = p.ready();
    let window = u64::from_str_radix(id.trim_start_matches("0x"), 16).unwrap();
    let shot = Screen::open(&x.display).grab(window);
    assert_eq!(
        shot.get(40, 90),
        [0, 0, 255, 255],
        "left mode shows the left eye"
    );
    assert!(p.stdout[0].contains("gl_stereo 1"), "{:?}", p.stdout);
    p.finish();

    let help = common::run_ok(Command::new(prefix.join("bin/glstereo-run")).arg("--help"));
    let help = String::from_utf8_lossy(&help.stdout);
    for m in glstereo::output::OutputMode::all() {
        assert!(help.contains(m.canonical_name()), "--help lists {m}");
    }
    for a in glstereo::output::ALIASES {
        assert!(help.contains(a.name), "--help lists alias {}", a.name);
    }
}

//! Faults from outside a program (tests/c/faults.c): each is a clear error
//! with a message that says what to do, the process goes on (no abort, no
//! exit), and nothing is left half-written.
//!
//! - A backend library missing: the program runs in a private mount
//!   namespace (`unshare -Urm`) where the system library directory is a
//!   tmpfs of symlinks to the real files, without libEGL, libEGL_mesa,
//!   libOSMesa or libGL — what a machine without those packages looks like.
//!   Where namespaces are not allowed (a chroot, a container), stand-ins
//!   of those files on `LD_LIBRARY_PATH` fail to load as missing ones do
//!   (each needs a library that does not exist), for every dlopen by name
//!   in the process (libc's own included) and for the loader, and an
//!   LD_PRELOAD shim (tests/c/hide_libs.c) fails a dlopen of them by path;
//!   glstereo-run without libGL is checked both ways wherever namespaces
//!   are allowed.
//! - $DISPLAY pointing nowhere, and an X server without GLX (a killed X
//!   server is tests/glx.rs's `a_killed_server_is_reported_not_an_exit`).
//! - Surfaces of 100000x100000, 0x0, and 16384x16384 with 1 GiB of address
//!   space left (the driver runs out of memory); read-backs and captures
//!   without memory left; a draw-buffer count of 2^31 − 1 under a limit.
//! - GLSTEREO_MODE=garbage, in the library and in a C example; for
//!   glstereo-run (exit 2 before the program runs) and for the preload
//!   library used without it (the default mode, said once).
//! - glstereo-run where the real libGL is missing: a program linked with
//!   -lGL stops in the loader; one that finds glX*/gl* at run time gets the
//!   layer's, which refuse every call naming the package (tests/c/no_libgl.c).
//! - Unwritable capture paths, and a disk that fills up in the middle of a
//!   capture (RLIMIT_FSIZE, and a 128 KiB tmpfs in a private namespace): an
//!   I/O error naming the path, the previous file intact, no temporary left.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn faults() -> PathBuf {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        let exe = common::scratch("faults-build").join("faults");
        common::compile_c(&[common::root().join("tests/c/faults.c")], &exe, &[]);
        exe
    })
    .clone()
}

/// A command running tests/c/faults.c with a clean environment for the
/// variables under test.
fn cmd(args: &[&str]) -> Command {
    let mut c = Command::new(faults());
    c.args(args)
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_BACKEND")
        .env_remove("GLSTEREO_EMULATION")
        .env_remove("DISPLAY")
        .env("RUST_BACKTRACE", "0");
    c
}

/// What the program printed: ("open", "result") → "GLS_OK", …
struct Said {
    stdout: String,
}

impl Said {
    fn of(o: &Output) -> Said {
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(
            o.status.success(),
            "the program did not exit normally ({}): a crash or an exit inside the library?\n\
             --- stdout\n{stdout}\n--- stderr\n{}",
            o.status,
            String::from_utf8_lossy(&o.stderr)
        );
        Said { stdout }
    }

    fn get(&self, step: &str, what: &str) -> Option<&str> {
        let prefix = format!("{step} {what} ");
        self.stdout.lines().find_map(|l| l.strip_prefix(&prefix))
    }

    /// Requires `step` to have ended with `code` (and, for an error, a
    /// message containing every one of `words`).
    fn expect(&self, step: &str, code: &str, words: &[&str]) -> &Self {
        assert_eq!(
            self.get(step, "result"),
            Some(code),
            "{step}: wanted {code}\n{}",
            self.stdout
        );
        if code != "GLS_OK" {
            let m = self.get(step, "message").unwrap_or("");
            assert!(
                m.starts_with("gls_") && words.iter().all(|w| m.contains(w)),
                "{step}: the message {m:?} should mention {words:?}"
            );
        }
        self
    }

    fn backend(&self) -> Option<u32> {
        self.stdout
            .lines()
            .find_map(|l| l.strip_prefix("backend ")?.parse().ok())
    }
}

fn run(c: &mut Command) -> Said {
    Said::of(&c.output().expect("faults runs"))
}

// ---- missing libraries ------------------------------------------------------

/// Whether this process may make user and mount namespaces
/// (GLSTEREO_TEST_NO_NAMESPACES=1 tries the fallbacks instead).
fn namespaces() -> bool {
    static OK: OnceLock<bool> = OnceLock::new();
    *OK.get_or_init(|| {
        std::env::var_os("GLSTEREO_TEST_NO_NAMESPACES").is_none()
            && Command::new("unshare")
                .args(["-Urm", "true"])
                .output()
                .is_ok_and(|o| o.status.success())
    })
}

/// The multiarch library directory (/usr/lib/x86_64-linux-gnu).
fn system_lib_dir() -> String {
    let o = Command::new("cc").arg("-print-multiarch").output().unwrap();
    let arch = String::from_utf8_lossy(&o.stdout).trim().to_owned();
    format!("/usr/lib/{arch}")
}

/// How a test makes libraries missing.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Hiding {
    /// A private mount namespace whose system library directory lacks
    /// the files (where user and mount namespaces are allowed).
    Namespace,
    /// Stand-ins on `LD_LIBRARY_PATH`, searched before the system's: a
    /// library of each hidden file's name that needs a library that does
    /// not exist, so the loader fails to open it, for every dlopen by name
    /// in the process and for a program linked with it; and
    /// tests/c/hide_libs.c preloaded for a dlopen by path (chroots and
    /// containers).
    Stubs,
}

/// The methods this machine allows, the real one first.
fn hidings() -> Vec<Hiding> {
    if namespaces() {
        vec![Hiding::Namespace, Hiding::Stubs]
    } else {
        eprintln!("no user/mount namespaces here: hiding libraries with stand-ins only");
        vec![Hiding::Stubs]
    }
}

/// Runs `c` where the library files matching the shell patterns `hide`
/// (e.g. "libEGL.so*") do not exist.
fn without_libraries(c: &mut Command, hide: &[&str]) -> Said {
    Said::of(&output_without_libraries(c, hide))
}

/// [`without_libraries`], returning the output whatever the exit status.
fn output_without_libraries(c: &mut Command, hide: &[&str]) -> Output {
    hidden(hidings()[0], c, hide)
}

/// [`output_without_libraries`] by the method `how`.
fn hidden(how: Hiding, c: &mut Command, hide: &[&str]) -> Output {
    match how {
        Hiding::Namespace => in_namespace(c, hide),
        Hiding::Stubs => {
            let prefixes: Vec<&str> = hide.iter().map(|p| p.trim_end_matches('*')).collect();
            // glstereo-run keeps an LD_PRELOAD it finds, after its own library.
            c.env("LD_LIBRARY_PATH", stubs(hide))
                .env("LD_PRELOAD", hide_shim())
                .env("GLSTEREO_TEST_HIDE", prefixes.join(":"))
                .output()
                .expect("the program starts")
        }
    }
}

/// tests/c/hide_libs.c built once: dlopen of a hidden file by its path
/// fails too.
fn hide_shim() -> &'static Path {
    static SHIM: OnceLock<PathBuf> = OnceLock::new();
    SHIM.get_or_init(|| {
        let shim = common::scratch("faults-shim").join("hide_libs.so");
        let o = Command::new("cc")
            .args(common::C_FLAGS)
            .args(["-shared", "-fPIC"])
            .arg(common::root().join("tests/c/hide_libs.c"))
            .arg("-o")
            .arg(&shim)
            .arg("-ldl")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        shim
    })
}

fn in_namespace(c: &mut Command, hide: &[&str]) -> Output {
    // In a private mount namespace the system directory becomes a tmpfs
    // of symlinks to the real files, less the hidden ones. cp runs
    // through the real loader: the tmpfs hides the loader's own link.
    let script = r#"set -e
d="$GLS_LIBDIR"; o=$(mktemp -d)
mount --bind "$d" "$o"
mount -t tmpfs tmpfs "$d"
ld=$(echo "$o"/ld-linux*.so.*)
"$ld" --library-path "$o" /usr/bin/cp -as "$o"/. "$d"/
for p in $GLS_HIDE; do rm -f "$d"/$p; done
exec "$@""#;
    let program = c.get_program().to_owned();
    let args: Vec<_> = c.get_args().map(|a| a.to_owned()).collect();
    let mut n = Command::new("unshare");
    n.args(["-Urm", "sh", "-c", script, "sh"])
        .arg(program)
        .args(args)
        .env("GLS_LIBDIR", system_lib_dir())
        .env("GLS_HIDE", hide.join(" "));
    for (k, v) in c.get_envs() {
        match v {
            Some(v) => n.env(k, v),
            None => n.env_remove(k),
        };
    }
    n.output().expect("unshare runs")
}

/// A directory of stand-ins for the system library files matching the
/// patterns `hide` (made once per set): each has the file's name and
/// needs `<name>.hidden-by-the-test`, which does not exist, so opening it
/// fails as "… cannot open shared object file: No such file or
/// directory", as for a missing library.
fn stubs(hide: &[&str]) -> PathBuf {
    use std::collections::HashMap;
    use std::sync::Mutex;
    static MADE: Mutex<Option<HashMap<String, PathBuf>>> = Mutex::new(None);
    let key = hide.join(" ");
    let mut made = MADE.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(dir) = made.get_or_insert_with(HashMap::new).get(&key) {
        return dir.clone();
    }
    let n = made.as_ref().map_or(0, HashMap::len);
    let dir = common::scratch(&format!("faults-hidden-{n}"));
    let source = dir.join("stub.c");
    std::fs::write(&source, "int glstereo_test_stand_in;\n").unwrap();
    let cc = |args: &[&std::ffi::OsStr]| {
        let o = Command::new("cc").args(args).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    let matches = |name: &str| {
        hide.iter().any(|p| match p.strip_suffix('*') {
            Some(prefix) => name.starts_with(prefix),
            None => name == *p,
        })
    };
    let mut names: Vec<String> = std::fs::read_dir(system_lib_dir())
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|name| matches(name))
        .collect();
    names.sort();
    assert!(!names.is_empty(), "no system library matches {hide:?}");
    for name in names {
        // Linked against a library of the missing name, which then goes.
        let missing = format!("{name}.hidden-by-the-test");
        let needed = dir.join(&missing);
        let soname = format!("-Wl,-soname,{missing}");
        cc(&[
            "-shared".as_ref(),
            "-fPIC".as_ref(),
            source.as_os_str(),
            "-o".as_ref(),
            needed.as_os_str(),
            soname.as_ref(),
        ]);
        let stub = dir.join(&name);
        cc(&[
            "-shared".as_ref(),
            "-fPIC".as_ref(),
            source.as_os_str(),
            "-o".as_ref(),
            stub.as_os_str(),
            "-Wl,--no-as-needed".as_ref(),
            needed.as_os_str(),
        ]);
        std::fs::remove_file(&needed).unwrap();
    }
    made.get_or_insert_with(HashMap::new)
        .insert(key, dir.clone());
    dir
}

#[test]
fn without_libegl_egl_is_unavailable_naming_the_package_and_auto_falls_back() {
    let hide = ["libEGL.so*"];
    without_libraries(&mut cmd(&["open", "egl"]), &hide)
        .expect(
            "open",
            "GLS_ERROR_BACKEND_UNAVAILABLE",
            &["libEGL", "libegl1", "GLSTEREO_BACKEND=osmesa"],
        )
        .expect("after", "GLS_OK", &[]);
    let auto = without_libraries(&mut cmd(&["open", "auto"]), &hide);
    auto.expect("open", "GLS_OK", &[]);
    assert_eq!(auto.backend(), Some(3), "auto without EGL: OSMesa");
}

#[test]
fn without_mesas_egl_vendor_egl_is_unavailable_naming_the_package() {
    without_libraries(&mut cmd(&["open", "egl"]), &["libEGL_mesa.so*"])
        .expect("open", "GLS_ERROR_BACKEND_UNAVAILABLE", &["libegl-mesa0"])
        .expect("after", "GLS_OK", &[]);
}

#[test]
fn without_libosmesa_osmesa_is_unavailable_naming_the_package() {
    without_libraries(&mut cmd(&["open", "osmesa"]), &["libOSMesa.so*"])
        .expect(
            "open",
            "GLS_ERROR_BACKEND_UNAVAILABLE",
            &["libOSMesa", "libosmesa6"],
        )
        .expect("after", "GLS_OK", &[]);
}

#[test]
fn without_any_backend_auto_lists_what_to_install() {
    without_libraries(
        &mut cmd(&["open", "auto"]),
        &["libEGL.so*", "libOSMesa.so*", "libGL.so*"],
    )
    .expect(
        "open",
        "GLS_ERROR_BACKEND_UNAVAILABLE",
        &["no GL backend", "libegl1", "libosmesa6"],
    )
    .expect("after", "GLS_OK", &[]);
}

#[test]
fn without_libgl_glx_is_unavailable_naming_the_package() {
    without_libraries(cmd(&["open", "glx"]).env("DISPLAY", ":0"), &["libGL.so*"])
        .expect(
            "open",
            "GLS_ERROR_BACKEND_UNAVAILABLE",
            &["libGL", "libgl1"],
        )
        .expect("after", "GLS_OK", &[]);
}

// ---- X displays ---------------------------------------------------------------

#[test]
fn a_display_pointing_nowhere_is_unavailable_and_auto_uses_egl() {
    for nowhere in [":9999", "nohost.invalid:0", "garbage:::"] {
        run(cmd(&["open", "glx"]).env("DISPLAY", nowhere)).expect(
            "open",
            "GLS_ERROR_BACKEND_UNAVAILABLE",
            &["cannot open X display", nowhere, "GLSTEREO_BACKEND=egl"],
        );
        let auto = run(cmd(&["open", "auto"]).env("DISPLAY", nowhere));
        auto.expect("open", "GLS_OK", &[]);
        assert_eq!(auto.backend(), Some(2), "auto with DISPLAY={nowhere}: EGL");
    }
    run(cmd(&["open", "glx"]).env("DISPLAY", "")).expect(
        "open",
        "GLS_ERROR_BACKEND_UNAVAILABLE",
        &["DISPLAY", "not set"],
    );
}

#[test]
fn an_x_server_without_glx_is_unavailable_and_the_exit_is_clean() {
    let x = common::xvfb::Xvfb::start_with(320, 240, "-extension GLX");
    run(cmd(&["open", "glx"]).env("DISPLAY", &x.display)).expect(
        "open",
        "GLS_ERROR_BACKEND_UNAVAILABLE",
        &["no GLX extension", "GLSTEREO_BACKEND=egl"],
    );
    // The library's exit hook must not touch the refused connection
    // (it read freed memory once): valgrind sees every read.
    let o = Command::new("valgrind")
        .args(["--error-exitcode=99", "-q"])
        .arg(format!(
            "--suppressions={}",
            common::root()
                .join("tests/sanitize/valgrind.supp")
                .display()
        ))
        .arg(faults())
        .args(["open", "glx"])
        .env("DISPLAY", &x.display)
        .output()
        .expect("valgrind runs");
    assert!(
        o.status.success(),
        "valgrind: {}\n{}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
}

// ---- the preload library (glstereo-run) --------------------------------------

/// tests/c/NAME.c as a plain program (no glstereo) with `libs`.
fn plain(name: &str, libs: &[&str]) -> PathBuf {
    let exe = common::scratch(&format!("faults-{name}")).join(name);
    common::preload::compile_plain(
        &common::root().join(format!("tests/c/{name}.c")),
        &exe,
        libs,
    );
    exe
}

/// `glstereo-run program args` on `display`, settings from a clean slate.
fn glstereo_run(display: &str, program: &Path, args: &[&str]) -> Command {
    let mut c = Command::new(&common::preload::built().run);
    c.arg(program)
        .args(args)
        .env("DISPLAY", display)
        .env_remove("GLSTEREO_MODE")
        .env_remove("GLSTEREO_SWAP_EYES")
        .env_remove("GLSTEREO_CAPTURE_DIR")
        .env("RUST_BACKTRACE", "0")
        .stdin(std::process::Stdio::null());
    c
}

#[test]
fn glstereo_run_without_libgl_refuses_every_call_naming_the_package_and_nothing_crashes() {
    let x = common::xvfb::Xvfb::start(320, 240);
    for how in hidings() {
        // A program that finds glX*/gl* at run time: it gets the layer's,
        // which cannot load the real libGL.
        let exe = plain("no_libgl", &["-lX11", "-ldl"]);
        let o = hidden(
            how,
            &mut glstereo_run(&x.display, &exe, &[]),
            &["libGL.so*"],
        );
        let stdout = String::from_utf8_lossy(&o.stdout);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(
            o.status.success(),
            "{how:?}: exit {}\n{stdout}\n{stderr}",
            o.status
        );
        for line in [
            "libGL: missing",
            "glXChooseVisual -> NULL",
            "glXChooseFBConfig -> NULL, n -1",
            "glXCreateContext -> NULL",
            "glXMakeCurrent -> 0",
            "glXSwapBuffers -> returned",
            "glXGetProcAddressARB -> NULL",
            "glDrawBuffer, glGetIntegerv -> -7",
            "glGetError -> 0x0",
            "done",
        ] {
            assert!(
                stdout.contains(line),
                "{how:?}: wanted {line:?}:\n{stdout}\n{stderr}"
            );
        }
        for name in [
            "glXChooseVisual",
            "glXChooseFBConfig",
            "glXCreateContext",
            "glXMakeCurrent",
            "glXSwapBuffers",
            "glXGetProcAddress",
            "glDrawBuffer",
            "glGetIntegerv",
            "glGetError",
        ] {
            let said = format!("glstereo: {name} refused: the real libGL.so.1 could not be loaded");
            assert!(
                stderr.contains(&said),
                "{how:?}: wanted {said:?}:\n{stderr}"
            );
        }
        assert!(stderr.contains("install libgl1"), "{how:?}: {stderr}");

        // A program linked with -lGL does not start: the loader says why
        // (glstereo-run and its library need no libGL themselves).
        let legacy = plain("legacy_stereo", &["-lGL", "-lX11"]);
        let o = hidden(
            how,
            &mut glstereo_run(&x.display, &legacy, &["32", "32"]),
            &["libGL.so*"],
        );
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(127), "{how:?}: {stderr}");
        assert!(
            stderr.contains("libGL.so.1") && !stderr.contains("glstereo:"),
            "{how:?}: {stderr}"
        );
    }
}

#[test]
fn an_unknown_glstereo_mode_stops_glstereo_run_and_the_preload_alone_uses_the_default() {
    let x = common::xvfb::Xvfb::start(320, 240);
    let legacy = plain("legacy_stereo", &["-lGL", "-lX11"]);
    // glstereo-run checks the variable before the program starts: exit 2.
    let o = glstereo_run(&x.display, &legacy, &["32", "32"])
        .env("GLSTEREO_MODE", "garbage")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("GLSTEREO_MODE")
            && stderr.contains("garbage")
            && stderr.contains("anaglyph-red-cyan"),
        "{stderr}"
    );
    assert!(o.stdout.is_empty(), "the program ran");

    // The library preloaded without glstereo-run (or the variable changed
    // after): it says so once and shows the default, anaglyph-red-cyan.
    let dir = common::scratch("faults-mode-garbage-preload");
    let o = Command::new(&legacy)
        .args(["40", "30"])
        .env("LD_PRELOAD", &common::preload::built().preload)
        .env("GLSTEREO_MODE", "garbage")
        .env("GLSTEREO_CAPTURE_DIR", &dir)
        .env("DISPLAY", &x.display)
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("glx_stereo 1 gl_stereo 1"), "{stdout}");
    assert_eq!(
        stderr.matches("glstereo:").count(),
        1,
        "one message:\n{stderr}"
    );
    assert!(
        stderr.contains("GLSTEREO_MODE")
            && stderr.contains("garbage")
            && stderr.contains("using the defaults"),
        "{stderr}"
    );
    // The RedBlue frame (tests/c/legacy_stereo.c) in red-cyan: at (-0.5,
    // -0.5) only the left eye's blue square (red channel from the left eye:
    // 0; green and blue from the right eye's grey background: 51).
    let composite = common::png(&dir.join("composite-000001.png"));
    assert_eq!(composite.get(10, 22), [0, 51, 51, 255]);
}

// ---- surfaces -----------------------------------------------------------------

#[test]
fn impossible_surface_sizes_are_invalid_values_and_the_process_goes_on() {
    for backend in ["egl", "osmesa"] {
        for (w, h) in [
            ("100000", "100000"),
            ("0", "0"),
            ("0", "64"),
            ("16385", "1"),
        ] {
            run(cmd(&["surface", w, h]).env("GLSTEREO_BACKEND", backend))
                .expect(
                    "surface",
                    "GLS_ERROR_INVALID_VALUE",
                    &[&format!("{w}x{h}"), "16384"],
                )
                .expect("small", "GLS_OK", &[]);
        }
    }
}

#[test]
fn a_surface_the_driver_cannot_allocate_is_out_of_memory_not_an_abort() {
    // 16384x16384 is a valid size, but its four colour buffers need 4 GiB:
    // with 1 GiB of address space left the driver's allocation fails.
    for backend in ["egl", "osmesa"] {
        run(cmd(&["memory", "16384", "16384", "1024"]).env("GLSTEREO_BACKEND", backend))
            .expect("big", "GLS_ERROR_OUT_OF_MEMORY", &["smaller surface"])
            .expect("swap", "GLS_OK", &[]);
    }
}

#[test]
fn reading_back_without_memory_is_out_of_memory_not_an_abort() {
    // A 8192x4096 mono surface (one 128 MiB colour buffer) read back with
    // 64 MiB of address space left: every read-back path fails cleanly
    // (it aborted the process, as a failed Rust allocation does).
    for backend in ["egl", "osmesa"] {
        run(cmd(&["readback", "8192", "4096", "64"]).env("GLSTEREO_BACKEND", backend))
            .expect(
                "left",
                "GLS_ERROR_OUT_OF_MEMORY",
                &["MiB", "could not be allocated"],
            )
            .expect("composite", "GLS_ERROR_OUT_OF_MEMORY", &["MiB"])
            .expect("read", "GLS_ERROR_OUT_OF_MEMORY", &["MiB"])
            .expect("small", "GLS_OK", &[]);
    }
}

#[test]
fn a_huge_draw_buffer_count_is_an_invalid_value_not_an_abort() {
    // gls_draw_buffers(INT_MAX, bufs) allocated INT_MAX entries first,
    // which aborted the process under a memory limit.
    run(cmd(&["drawbuffers", "512"]).env("GLSTEREO_BACKEND", "egl")).expect(
        "drawbuffers",
        "GLS_ERROR_INVALID_VALUE",
        &["2147483647", "GL_MAX_DRAW_BUFFERS"],
    );
}

#[test]
fn glstereo_mode_garbage_is_an_invalid_value_naming_the_variable() {
    for backend in ["egl", "osmesa"] {
        run(cmd(&["surface", "32", "32"])
            .env("GLSTEREO_BACKEND", backend)
            .env("GLSTEREO_MODE", "garbage"))
        .expect(
            "surface",
            "GLS_ERROR_INVALID_VALUE",
            &["GLSTEREO_MODE", "garbage", "anaglyph-red-cyan"],
        )
        .expect("small", "GLS_OK", &[]);
    }
    // A real program: it reports the library's message and exits 1.
    let exe = common::build_example("redblue", false);
    let dir = common::scratch("faults-mode-garbage");
    let o = Command::new(exe)
        .arg("--out")
        .arg(&dir)
        .env("GLSTEREO_BACKEND", "egl")
        .env("GLSTEREO_MODE", "garbage")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "redblue: {}\n{stderr}", o.status);
    assert!(stderr.contains("GLSTEREO_MODE"), "{stderr}");
    assert!(!dir.join("composite.png").exists());
}

// ---- captures -------------------------------------------------------------------

/// The names in a directory.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn unwritable_capture_paths_are_io_errors_naming_the_path() {
    let dir = common::scratch("faults-unwritable");
    let file = dir.join("a-file");
    std::fs::write(&file, b"not a directory").unwrap();
    let cases = [
        "/nonexistent-glstereo-dir/capture.png".to_owned(),
        format!("{}/capture.png", file.display()),
        dir.display().to_string(), // a directory
        "/proc/glstereo-capture.png".to_owned(),
    ];
    for path in &cases {
        run(cmd(&["capture", path]).env("GLSTEREO_BACKEND", "egl"))
            .expect("capture", "GLS_ERROR_IO", &[path])
            .expect("left", "GLS_ERROR_IO", &[path]);
    }
    assert_eq!(
        names(&dir),
        ["a-file"],
        "a failed capture left files behind"
    );
    assert_eq!(std::fs::read(&file).unwrap(), b"not a directory");
}

#[test]
fn a_file_size_limit_hit_midway_leaves_the_previous_capture_whole() {
    let dir = common::scratch("faults-fsize");
    let path = dir.join("capture.png");
    let p = path.to_str().unwrap();
    // A complete capture first (the noise makes it ~260 KiB).
    run(cmd(&["capture", p]).env("GLSTEREO_BACKEND", "egl"))
        .expect("capture", "GLS_OK", &[])
        .expect("left", "GLS_OK", &[]);
    let before = std::fs::read(&path).unwrap();
    assert!(before.len() > 200_000, "capture of {} bytes", before.len());
    // Then the same capture with files limited to 64 KiB: the write fails
    // with EFBIG in the middle of the PNG.
    run(cmd(&["capture", p, "65536"]).env("GLSTEREO_BACKEND", "egl"))
        .expect("capture", "GLS_ERROR_IO", &[p, "too large"])
        .expect("left", "GLS_ERROR_IO", &[p]);
    assert_eq!(names(&dir), ["capture.png"], "a temporary file was left");
    assert_eq!(
        std::fs::read(&path).unwrap(),
        before,
        "the previous capture changed"
    );
    common::png(&path);
}

/// Runs the capture program on a fresh tmpfs (with `options`) mounted in a
/// private namespace; returns what it said and what the directory held.
fn capture_on_tmpfs(options: &str) -> Option<(Said, String)> {
    if !namespaces() {
        eprintln!(
            "no user/mount namespaces here: the tmpfs cases are covered by RLIMIT_FSIZE only"
        );
        return None;
    }
    let dir = common::scratch(&format!("faults-tmpfs-{}", options.replace(',', "-")));
    let script = r#"mount -t tmpfs -o "$GLS_OPTIONS" tmpfs "$GLS_DIR" || exit 3
"$@"
echo "files: $(ls -A "$GLS_DIR" | tr '\n' ' ')""#;
    let mut c = Command::new("unshare");
    c.args(["-Urm", "sh", "-c", script, "sh"])
        .arg(faults())
        .args(["capture", &format!("{}/capture.png", dir.display())])
        .env("GLS_DIR", &dir)
        .env("GLS_OPTIONS", options)
        .env("GLSTEREO_BACKEND", "egl")
        .env_remove("DISPLAY")
        .env("RUST_BACKTRACE", "0");
    let said = run(&mut c);
    let files = said
        .stdout
        .lines()
        .find_map(|l| l.strip_prefix("files:"))
        .unwrap_or("?")
        .trim()
        .to_owned();
    Some((said, files))
}

#[test]
fn a_disk_that_fills_up_midway_leaves_no_file_and_no_temporary() {
    // 128 KiB: the ~260 KiB PNG cannot fit; ENOSPC in the middle.
    if let Some((said, files)) = capture_on_tmpfs("size=128k") {
        said.expect("capture", "GLS_ERROR_IO", &["capture.png", "No space left"])
            .expect("left", "GLS_ERROR_IO", &["capture.png"]);
        assert_eq!(files, "", "the full disk holds {files:?}");
    }
}

#[test]
fn a_read_only_file_system_is_an_io_error() {
    if let Some((said, files)) = capture_on_tmpfs("ro") {
        said.expect("capture", "GLS_ERROR_IO", &["capture.png", "Read-only"]);
        assert_eq!(files, "");
    }
}

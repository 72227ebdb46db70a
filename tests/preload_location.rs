//! glstereo-run finds the stereo layer by where it is installed — the build
//! tree, a `make install DESTDIR=… PREFIX=…` tree, the Debian packages'
//! private directory — with no path set by hand, and a program of the
//! other word size (32-bit on a 64-bit system) gets one line saying what
//! to install instead of the loader's "wrong ELF class".
//!
//! Each tree is laid out as its installer lays it (glstereo-run and the
//! preload library of this test run, hard-linked or copied), and the
//! program run is `env`, which prints the LD_PRELOAD it was given.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::preload::built;

/// Debian's multiarch directory for this machine's own word size.
fn triplet() -> String {
    match std::env::consts::ARCH {
        "x86" => "i386-linux-gnu".into(),
        "arm" => "arm-linux-gnueabihf".into(),
        a => format!("{a}-linux-gnu"),
    }
}

/// The other word size on this machine: (Debian name, multiarch
/// directory, ELF machine), for the architectures glstereo-run knows.
fn other() -> Option<(&'static str, &'static str, u16)> {
    match std::env::consts::ARCH {
        "x86_64" => Some(("i386", "i386-linux-gnu", 3)),
        "aarch64" => Some(("armhf", "arm-linux-gnueabihf", 40)),
        _ => None,
    }
}

/// `from` at `to` (parents made): a hard link where it can be, so the
/// installed copy is the file just built, else a copy.
fn place(from: &Path, to: &Path) {
    std::fs::create_dir_all(to.parent().unwrap()).unwrap();
    if std::fs::hard_link(from, to).is_err() {
        std::fs::copy(from, to).unwrap_or_else(|e| panic!("copying {}: {e}", from.display()));
    }
}

/// A tree with glstereo-run at `bin` and, when given, the preload
/// library at `lib` (both relative to `root`).
fn tree(root: &Path, bin: &str, lib: Option<&str>) -> (PathBuf, Option<PathBuf>) {
    let run = root.join(bin).join("glstereo-run");
    place(&built().run, &run);
    let lib = lib.map(|l| {
        let p = root.join(l).join("libglstereo_preload.so");
        place(&built().preload, &p);
        p
    });
    (run, lib)
}

/// `glstereo-run -- PROGRAM`, with no preload path set by hand.
fn run_under(glstereo_run: &Path, program: &Path) -> Output {
    Command::new(glstereo_run)
        .arg("--")
        .arg(program)
        .env_remove("GLSTEREO_PRELOAD_LIB")
        .env_remove("LD_PRELOAD")
        .output()
        .expect("glstereo-run starts")
}

/// The LD_PRELOAD `env` printed under glstereo-run.
fn preloaded(glstereo_run: &Path) -> String {
    let out = run_under(glstereo_run, Path::new("/usr/bin/env"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "glstereo-run env failed ({}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
        .lines()
        .find_map(|l| l.strip_prefix("LD_PRELOAD="))
        .unwrap_or_else(|| panic!("env printed no LD_PRELOAD:\n{stdout}"))
        .to_owned()
}

fn canonical(p: &Path) -> String {
    p.canonicalize().unwrap().display().to_string()
}

#[test]
fn glstereo_run_finds_the_layer_in_the_build_tree() {
    let b = built();
    assert_eq!(preloaded(&b.run), canonical(&b.preload));
}

#[test]
fn glstereo_run_finds_the_layer_in_a_make_install_tree() {
    let dir = common::scratch("preload_location_install");
    // make install DESTDIR=dir PREFIX=/opt/glstereo: PREFIX/bin, PREFIX/lib.
    let (run, lib) = tree(&dir, "opt/glstereo/bin", Some("opt/glstereo/lib"));
    assert_eq!(preloaded(&run), canonical(&lib.unwrap()));
}

#[test]
fn glstereo_run_finds_the_layer_where_the_debian_package_puts_it() {
    let dir = common::scratch("preload_location_deb");
    let private = format!("usr/lib/{}/glstereo", triplet());
    let (run, lib) = tree(&dir, "usr/bin", Some(&private));
    assert_eq!(preloaded(&run), canonical(&lib.unwrap()));
}

#[test]
fn glstereo_run_without_a_layer_says_where_it_looked() {
    let dir = common::scratch("preload_location_none");
    let (run, _) = tree(&dir, "usr/bin", None);
    let out = run_under(&run, Path::new("/usr/bin/env"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("cannot find libglstereo_preload.so")
            && stderr.contains(&format!("lib/{}/glstereo", triplet())),
        "wanted where it looked, saw: {stderr}"
    );
}

/// The 52-byte header of a little-endian ELF32 executable for `machine`:
/// all the kernel and glstereo-run read of a program's word size.
fn elf32_header(machine: u16) -> Vec<u8> {
    let mut h = vec![0u8; 52];
    h[..4].copy_from_slice(b"\x7fELF");
    h[4] = 1; // ELFCLASS32
    h[5] = 1; // ELFDATA2LSB
    h[6] = 1; // EV_CURRENT
    h[16..18].copy_from_slice(&2u16.to_le_bytes()); // ET_EXEC
    h[18..20].copy_from_slice(&machine.to_le_bytes());
    h[20..24].copy_from_slice(&1u32.to_le_bytes());
    h[40..42].copy_from_slice(&52u16.to_le_bytes()); // e_ehsize
    h
}

fn executable(path: &Path, bytes: &[u8]) {
    use std::os::unix::fs::PermissionsExt;
    std::fs::write(path, bytes).unwrap();
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).unwrap();
}

#[test]
fn a_program_of_the_other_word_size_is_told_what_to_install() {
    let Some((debian, _, machine)) = other() else {
        eprintln!(
            "skipped: no other word size known on {}",
            std::env::consts::ARCH
        );
        return;
    };
    let dir = common::scratch("preload_location_32");
    let private = format!("usr/lib/{}/glstereo", triplet());
    let (run, _) = tree(&dir, "usr/bin", Some(&private));
    let prog = dir.join("prog32");
    executable(&prog, &elf32_header(machine));
    let out = run_under(&run, &prog);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "one line, saw: {stderr}");
    for want in [
        "is a 32-bit program".to_owned(),
        format!("apt-get install libglstereo-preload:{debian}"),
        format!("dpkg --add-architecture {debian}"),
    ] {
        assert!(stderr.contains(&want), "wanted {want:?}, saw: {stderr}");
    }
    assert!(
        !stderr.contains("wrong ELF class") && !stderr.contains("ld.so"),
        "a loader error: {stderr}"
    );
}

/// With the other word size's layer installed (the packages' directory of
/// that architecture), a real program of that word size gets it, built
/// with `cc -m32` (gcc-multilib, in the Makefile's packages); the layer
/// there is a stand-in file, which the loader reports and ignores: the
/// program prints the LD_PRELOAD it was given.
#[test]
fn a_program_of_the_other_word_size_gets_that_word_sizes_layer() {
    let Some((_, other_triplet, _)) = other() else {
        eprintln!(
            "skipped: no other word size known on {}",
            std::env::consts::ARCH
        );
        return;
    };
    let dir = common::scratch("preload_location_32_found");
    let src = dir.join("print_preload.c");
    std::fs::write(
        &src,
        "#include <stdio.h>\n#include <stdlib.h>\nint main(void) {\n\
         \x20   const char *p = getenv(\"LD_PRELOAD\");\n\
         \x20   printf(\"LD_PRELOAD=%s\\n\", p ? p : \"\");\n    return 0;\n}\n",
    )
    .unwrap();
    let prog = dir.join("print_preload32");
    let built32 = Command::new("cc")
        .args(["-m32", "-o"])
        .arg(&prog)
        .arg(&src)
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        built32,
        "`cc -m32` cannot build a 32-bit program here: install gcc-multilib (make deps does)"
    );
    let private = format!("usr/lib/{}/glstereo", triplet());
    let (run, _) = tree(&dir, "usr/bin", Some(&private));
    let layer32 = dir
        .join("usr/lib")
        .join(other_triplet)
        .join("glstereo/libglstereo_preload.so");
    std::fs::create_dir_all(layer32.parent().unwrap()).unwrap();
    std::fs::write(&layer32, b"stand-in").unwrap();
    let out = run_under(&run, &prog);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(&format!("LD_PRELOAD={}", canonical(&layer32))),
        "wanted the {other_triplet} layer, saw: {stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

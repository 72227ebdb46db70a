//! Generates the C header with cbindgen.
//!
//! The header is always generated into `$OUT_DIR/glstereo.h`. It is copied to
//! `include/glstereo.h` only when `GLSTEREO_WRITE_HEADER=1` (what `make header`
//! sets), so a build never silently rewrites the committed header; the test
//! `header_has_no_drift` compares the two byte for byte.
//!
//! It also names the library's soname in the build tree: libglstereo.so is
//! linked with the soname `libglstereo.so.0` (as `make install` installs
//! it), so a C program linked against `target/<profile>/libglstereo.so`
//! asks the loader for `libglstereo.so.0`. The link
//! `target/<profile>/libglstereo.so.0 -> libglstereo.so` is made here, so a
//! plain `cargo build` gives a library such a program can start with.

use std::path::PathBuf;

fn main() {
    let crate_dir = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let out_dir = PathBuf::from(std::env::var("OUT_DIR").unwrap());

    println!("cargo:rerun-if-changed=cbindgen.toml");
    println!("cargo:rerun-if-changed=src/ffi");
    println!("cargo:rerun-if-env-changed=GLSTEREO_WRITE_HEADER");
    // A soname, so the library installs and links like any C library. Not
    // `rustc-cdylib-link-arg`: cargo passes that one on to every cdylib that
    // depends on this crate (cargo issue #9562), which would give
    // libglstereo_preload.so this soname too.
    println!("cargo:rustc-link-arg=-Wl,-soname,libglstereo.so.0");
    link_soname(&out_dir);
    avx512_cfg();

    let mut config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml"))
        .expect("cbindgen.toml is readable and valid");
    // Version macros come from Cargo.toml, so the header cannot disagree with gls_version().
    let v = |k: &str| std::env::var(k).unwrap();
    config.after_includes = Some(format!(
        "\n/** Version of this header; compare with gls_version() at run time. */\n\
         #define GLSTEREO_VERSION_MAJOR {}\n#define GLSTEREO_VERSION_MINOR {}\n\
         #define GLSTEREO_VERSION_PATCH {}\n#define GLSTEREO_VERSION_STRING \"{}\"\n",
        v("CARGO_PKG_VERSION_MAJOR"),
        v("CARGO_PKG_VERSION_MINOR"),
        v("CARGO_PKG_VERSION_PATCH"),
        v("CARGO_PKG_VERSION"),
    ));
    let generated = out_dir.join("glstereo.h");
    match cbindgen::Builder::new()
        .with_src(crate_dir.join("src/ffi/mod.rs"))
        .with_config(config)
        .generate()
    {
        Ok(bindings) => {
            bindings.write_to_file(&generated);
        }
        Err(e) => {
            // A parse error must not hide behind a stale header.
            panic!("cbindgen could not generate the header: {e}");
        }
    }
    if std::env::var("GLSTEREO_WRITE_HEADER").as_deref() == Ok("1") {
        let target = crate_dir.join("include").join("glstereo.h");
        let new = std::fs::read(&generated).unwrap();
        if std::fs::read(&target).ok().as_deref() != Some(&new[..]) {
            std::fs::write(&target, &new).expect("include/glstereo.h is writable");
        }
    }
}

/// Makes `libglstereo.so.0 -> libglstereo.so` in the directory cargo puts
/// the library in (`target/<profile>`, or `target/<triple>/<profile>`).
///
/// That directory is not given to build scripts; it is the one holding
/// `build/<package>-<hash>/out` (`OUT_DIR`). When `OUT_DIR` is laid out
/// otherwise (a `build.build-dir` of its own), a warning says what to do
/// instead. The link is relative and may dangle until the library is
/// linked, which cargo does after this script.
fn link_soname(out_dir: &std::path::Path) {
    let mut up = out_dir.ancestors();
    let (out, pkg, build, profile) = (up.next(), up.next(), up.next(), up.next());
    let name = |p: Option<&std::path::Path>| {
        p.and_then(|p| p.file_name())
            .and_then(|n| n.to_str())
            .map(str::to_owned)
    };
    let classic = name(out).as_deref() == Some("out")
        && name(pkg).is_some_and(|n| n.starts_with("glstereo-"))
        && name(build).as_deref() == Some("build");
    let Some(profile) = profile.filter(|_| classic) else {
        println!(
            "cargo:warning=cannot tell where libglstereo.so goes (OUT_DIR {}): \
             link libglstereo.so.0 to it by hand, or run `make build`",
            out_dir.display()
        );
        return;
    };
    let link = profile.join("libglstereo.so.0");
    let target = std::path::Path::new("libglstereo.so");
    if std::fs::read_link(&link).ok().as_deref() == Some(target) {
        return;
    }
    // Made under another name and renamed over the link, so a program
    // starting meanwhile finds the old link or the new one, never none.
    let fresh = profile.join(format!("libglstereo.so.0.{}", std::process::id()));
    let _ = std::fs::remove_file(&fresh);
    if let Err(e) =
        std::os::unix::fs::symlink(target, &fresh).and_then(|()| std::fs::rename(&fresh, &link))
    {
        println!(
            "cargo:warning=cannot make {} (a C program linked here would not start): {e}",
            link.display()
        );
    }
}

/// `cfg(glstereo_avx512)` where the compiler has the AVX-512 intrinsics
/// and target features (stable since Rust 1.89; the crate's MSRV is
/// older): the AVX-512 kernels of `src/output` are compiled only then.
fn avx512_cfg() {
    println!("cargo:rustc-check-cfg=cfg(glstereo_avx512)");
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = std::process::Command::new(rustc)
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok());
    // "rustc 1.95.0 (…)"
    let minor = version.as_deref().and_then(|v| {
        let mut parts = v.split_whitespace().nth(1)?.split('.');
        let major: u32 = parts.next()?.parse().ok()?;
        let minor: u32 = parts.next()?.parse().ok()?;
        Some(if major > 1 { u32::MAX } else { minor })
    });
    if minor.is_some_and(|m| m >= 89) {
        println!("cargo:rustc-cfg=glstereo_avx512");
    }
}

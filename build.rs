//! Generates the C header with cbindgen.
//!
//! The header is always generated into `$OUT_DIR/glstereo.h`. It is copied to
//! `include/glstereo.h` only when `GLSTEREO_WRITE_HEADER=1` (what `make header`
//! sets), so a build never silently rewrites the committed header; the test
//! `header_has_no_drift` compares the two byte for byte.

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

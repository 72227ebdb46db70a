//! Link settings of libglstereo_preload.so, and the stub libraries that
//! stand for libGL.so.1, libGLX.so.0 and libOpenGL.so.0 when a program
//! dlopens them (glstereo::interpose::next says why).
use std::path::{Path, PathBuf};
use std::process::Command;

/// Each stub's file name (also its soname) and the library it stands for.
const STUBS: [(&str, &str); 3] = [
    ("libglstereo_stub_GL.so", "libGL.so.1"),
    ("libglstereo_stub_GLX.so", "libGLX.so.0"),
    ("libglstereo_stub_OpenGL.so", "libOpenGL.so.0"),
];

fn main() {
    // Only the interposed GL/GLX names are exported: the glstereo code linked
    // in keeps its gls_ symbols local, so a program that also links
    // libglstereo.so binds those to the library, not to this copy.
    println!("cargo:rustc-cdylib-link-arg=-Wl,--exclude-libs,ALL");
    // Its own soname (the glstereo dependency's build script names libglstereo.so.0).
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libglstereo_preload.so");
    println!("cargo:rerun-if-changed=build.rs");
    stubs();
}

/// Links the stubs into the profile directory, beside the preload library.
/// A stub has no code: only its dependencies, in order, the preload library
/// and the GL library, so dlsym on its handle finds the preload's exports
/// first and the GL library's other functions after. Both dependencies are
/// named by soname; empty libraries with those sonames stand in for them at
/// link time, so building needs neither libGL nor the preload yet.
fn stubs() {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    // OUT_DIR is <target>/<profile>/build/<package>-<hash>/out.
    let profile_dir = out
        .ancestors()
        .nth(3)
        .expect("target/<profile>")
        .to_path_buf();
    let cc = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    let empty = |path: &Path, soname: &str| {
        link(&cc, path, soname, &[]);
    };
    let preload = out.join("libglstereo_preload.so");
    empty(&preload, "libglstereo_preload.so");
    for (stub, gl) in STUBS {
        let stand_in = out.join(gl);
        empty(&stand_in, gl);
        link(&cc, &profile_dir.join(stub), stub, &[&preload, &stand_in]);
    }
}

/// `cc -shared -nostdlib` of an empty source with `soname` and, in order,
/// `needed` as dependencies.
fn link(cc: &std::ffi::OsStr, out: &Path, soname: &str, needed: &[&Path]) {
    let status = Command::new(cc)
        .args(["-shared", "-nostdlib", "-Wl,--no-as-needed"])
        .arg(format!("-Wl,-soname,{soname}"))
        .arg("-o")
        .arg(out)
        .args(["-x", "c", "/dev/null", "-x", "none"])
        .args(needed)
        .status()
        .unwrap_or_else(|e| panic!("running the C compiler ({cc:?}) for {soname} failed: {e}"));
    assert!(status.success(), "linking {} failed", out.display());
}

//! Link settings of libglstereo_preload.so, and the stub libraries that
//! stand for libGL.so.1, libGLX.so.0, libOpenGL.so.0, libEGL.so.1 and
//! libGLESv2.so.2 when a program
//! dlopens them (glstereo::interpose::next says why).
use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "gen_gl.rs"]
mod gen_gl;

/// The rule that says which family a GL command belongs to (the crate's
/// own, shared with its tests and docs).
#[path = "../src/auto/entry_points.rs"]
#[allow(dead_code)]
mod entry_points;

use entry_points::Family;

/// The families whose commands get generated wrappers calling glstereo's
/// hook (`glstereo::interpose::draws`): everything that draws into the
/// default framebuffer, the capabilities automatic stereo answers
/// (glEnable/glDisable/glIsEnabled of GL_3DVISION_STEREO_NV), the
/// matrix uploads automatic convergence learns projections from, the
/// queries and transform feedback whose capture stays single, the
/// lighting state the fixed-function stand-in is keyed on, the texture
/// bindings that tell which textures a draw samples, the commands that
/// read or write a texture's contents outside draws, and the copies from
/// framebuffers into textures, and the program bindings (a display list
/// that binds a program is not geometry only).
const GENERATED: &[Family] = &[
    Family::Draw,
    Family::BeginEnd,
    Family::DisplayList,
    Family::Clear,
    Family::RasterPixels,
    Family::Blit,
    Family::Settings,
    Family::Projection,
    Family::SideEffect,
    Family::Lighting,
    Family::Texture,
    Family::TextureData,
    Family::TextureWrite,
    Family::Read,
    Family::Program,
];

/// Each stub's file name (also its soname) and the library it stands for.
const STUBS: [(&str, &str); 5] = [
    ("libglstereo_stub_GL.so", "libGL.so.1"),
    ("libglstereo_stub_GLX.so", "libGLX.so.0"),
    ("libglstereo_stub_OpenGL.so", "libOpenGL.so.0"),
    ("libglstereo_stub_EGL.so", "libEGL.so.1"),
    ("libglstereo_stub_GLESv2.so", "libGLESv2.so.2"),
];

fn main() {
    // Only the interposed GL/GLX names are exported: the glstereo code linked
    // in keeps its gls_ symbols local, so a program that also links
    // libglstereo.so binds those to the library, not to this copy.
    println!("cargo:rustc-cdylib-link-arg=-Wl,--exclude-libs,ALL");
    // Its own soname (the glstereo dependency's build script names libglstereo.so.0).
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libglstereo_preload.so");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=gen_gl.rs");
    println!("cargo:rerun-if-changed=src/lib.rs");
    println!("cargo:rerun-if-changed=../src/auto/entry_points.rs");
    stubs();
    wrappers();
}

/// The names src/lib.rs exports by hand (`export!` and `forward!`): no
/// generated wrapper for those.
fn hand_exported() -> std::collections::BTreeSet<String> {
    let lib = std::fs::read_to_string("src/lib.rs").expect("preload/src/lib.rs");
    lib.lines()
        .filter_map(|l| {
            let t = l.trim_start();
            let name: String = t
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            let rest = &t[name.len()..];
            (name.starts_with("gl") && (rest.starts_with(" =>") || rest.starts_with('(')))
                .then_some(name)
        })
        .collect()
}

/// $OUT_DIR/generated.rs: an export per GL command of the [`GENERATED`]
/// families (as gl.xml declares it) that src/lib.rs does not export by
/// hand, each calling the next definition through glstereo's hook, and
/// `generated::lookup` for glXGetProcAddress.
fn wrappers() {
    let xml = std::str::from_utf8(khronos_api::GL_XML).expect("gl.xml is UTF-8");
    let hand = hand_exported();
    let mut exports = String::new();
    let mut bodies = String::new();
    let mut lookup = String::new();
    let mut count = 0;
    for cmd in gen_gl::desktop_commands(xml) {
        let Some(family) = entry_points::family(&cmd.name) else {
            continue;
        };
        if !GENERATED.contains(&family) || hand.contains(&cmd.name) {
            continue;
        }
        count += 1;
        let name = &cmd.name;
        let params: Vec<String> = cmd
            .params
            .iter()
            .map(|(n, t)| format!("{n}: {t}"))
            .collect();
        let params = params.join(", ");
        let types: Vec<&str> = cmd.params.iter().map(|(_, t)| t.as_str()).collect();
        let types = types.join(", ");
        let args: Vec<&str> = cmd.params.iter().map(|(n, _)| n.as_str()).collect();
        let args = args.join(", ");
        // Each argument as 64 bits, for the hook (draws::Call::args).
        let bits: Vec<String> = cmd
            .params
            .iter()
            .map(|(n, t)| match t.as_str() {
                "f32" => format!("{n}.to_bits() as u64"),
                "f64" => format!("{n}.to_bits()"),
                t if t.starts_with('*') => format!("{n} as usize as u64"),
                _ => format!("{n} as u64"),
            })
            .collect();
        let bits = bits.join(", ");
        let ret = cmd
            .ret
            .as_ref()
            .map(|r| format!(" -> {r}"))
            .unwrap_or_default();
        exports.push_str(&format!(
            "/// `{name}` (gl.xml): glstereo's draw hook, then the next definition.\n\
             #[unsafe(no_mangle)]\n\
             pub unsafe extern \"C\" fn {name}({params}){ret} {{\n\
             \x20   // SAFETY: the caller's arguments, forwarded.\n\
             \x20   unsafe {{ generated::{name}({args}) }}\n\
             }}\n\n"
        ));
        bodies.push_str(&format!(
            "    pub(crate) unsafe extern \"C\" fn {name}({params}){ret} {{\n\
             \x20       static NEXT: AtomicPtr<c_void> = AtomicPtr::new(std::ptr::null_mut());\n\
             \x20       let f = gl_next(&NEXT, c\"{name}\");\n\
             \x20       // SAFETY: the next {name}, with its gl.xml signature, and the caller's arguments.\n\
             \x20       let call = || unsafe {{ std::mem::transmute::<*mut c_void, unsafe extern \"system\" fn({types}){ret}>(f)({args}) }};\n\
             \x20       hooked(Call {{ family: Family::{family:?}, name: \"{name}\", args: &[{bits}] }}, call)\n\
             \x20   }}\n\n"
        ));
        lookup.push_str(&format!(
            "            b\"{name}\" => Some({name} as *mut c_void),\n"
        ));
    }
    assert!(
        count > 50,
        "only {count} generated wrappers: gl.xml not read?"
    );
    let code = format!(
        "// Generated by preload/build.rs from gl.xml ({count} commands of the families\n\
         // {GENERATED:?}): do not edit.\n\n\
         {exports}\
         /// The bodies of the generated exports, at addresses of this library's own.\n\
         #[allow(non_snake_case, clippy::too_many_arguments)]\n\
         pub(crate) mod generated {{\n\
         \x20   use super::*;\n\n\
         {bodies}\
         \x20   /// This library's own function for `name`, among the generated ones.\n\
         \x20   pub(crate) fn lookup(name: &[u8]) -> Option<*mut c_void> {{\n\
         \x20       match name {{\n\
         {lookup}\
         \x20           _ => None,\n\
         \x20       }}\n\
         \x20   }}\n\
         }}\n"
    );
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(out.join("generated.rs"), code).expect("writing generated.rs");
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
        // libc last: no code of its own needs it, but a shared library
        // that names no libc is taken for a mis-built one (lintian).
        .arg("-lc")
        .status()
        .unwrap_or_else(|e| panic!("running the C compiler ({cc:?}) for {soname} failed: {e}"));
    assert!(status.success(), "linking {} failed", out.display());
}

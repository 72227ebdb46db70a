//! The committed header is exactly what cbindgen generates, and its version
//! agrees with Cargo.toml and gls_version().

mod common;

#[test]
fn header_has_no_drift() {
    let generated = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/glstereo.h")).unwrap();
    let committed = std::fs::read_to_string(common::root().join("include/glstereo.h"))
        .expect("include/glstereo.h exists");
    if generated != committed {
        let line = generated
            .lines()
            .zip(committed.lines())
            .position(|(a, b)| a != b)
            .map_or_else(
                || "(lengths differ)".to_owned(),
                |i| format!("first difference at line {}", i + 1),
            );
        panic!("include/glstereo.h is out of date ({line}): run `make header` and commit it");
    }
    assert!(committed.contains("DO NOT EDIT"));
}

#[test]
fn version_agrees_everywhere() {
    let v = env!("CARGO_PKG_VERSION");
    let ptr = glstereo::ffi::core::gls_version();
    // SAFETY: gls_version returns a static NUL-terminated string.
    let runtime = unsafe { std::ffi::CStr::from_ptr(ptr) }.to_str().unwrap();
    assert_eq!(runtime, v);
    let header = std::fs::read_to_string(common::root().join("include/glstereo.h")).unwrap();
    assert!(
        header.contains(&format!("#define GLSTEREO_VERSION_STRING \"{v}\"")),
        "header's version macro differs from Cargo.toml's {v}"
    );
    let mut parts = v.split('.');
    for name in ["MAJOR", "MINOR", "PATCH"] {
        let want = format!("#define GLSTEREO_VERSION_{name} {}", parts.next().unwrap());
        assert!(header.contains(&want), "header lacks {want:?}");
    }
}

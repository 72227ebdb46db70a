//! The output-mode exports and constants as C sees them: the header's
//! GLS_OUTPUT_* values, name ↔ value translation, and the documented codes
//! for NULL, unknown and out-of-range arguments.

mod common;

use std::ffi::{CStr, CString, c_char};

use glstereo::ffi::output::{GLS_OUTPUT_COUNT, gls_output_from_name, gls_output_name};
use glstereo::ffi::types::*;
use glstereo::output::{ALIASES, OutputMode};

use common::last_error;

fn from_name(name: &str) -> (gls_result, u32) {
    let c = CString::new(name).unwrap();
    let mut out = u32::MAX;
    // SAFETY: a valid C string and a valid output slot.
    let rc = unsafe { gls_output_from_name(c.as_ptr(), &mut out) };
    (rc, out)
}

fn name_of(output: u32) -> Option<String> {
    let p = gls_output_name(output);
    // SAFETY: non-NULL results are static NUL-terminated strings.
    (!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_owned())
}

#[test]
fn header_defines_one_constant_per_mode_named_after_it() {
    let header = std::fs::read_to_string(common::root().join("include/glstereo.h")).unwrap();
    let mut seen = 0;
    for line in header.lines() {
        let Some(rest) = line.strip_prefix("#define GLS_OUTPUT_") else {
            continue;
        };
        let (suffix, value) = rest.split_once(' ').expect("#define NAME VALUE");
        let value: u32 = value.trim().parse().expect("a number");
        if suffix == "COUNT" {
            assert_eq!(value, OutputMode::ALL.len() as u32);
            continue;
        }
        let name =
            name_of(value).unwrap_or_else(|| panic!("GLS_OUTPUT_{suffix} = {value} has no name"));
        assert_eq!(
            suffix,
            name.to_uppercase().replace('-', "_"),
            "GLS_OUTPUT_{suffix} is {value}, whose name is {name}"
        );
        seen += 1;
    }
    assert_eq!(seen, OutputMode::ALL.len(), "constants in the header");
}

#[test]
fn every_value_names_itself_and_parses_back() {
    for v in 0..GLS_OUTPUT_COUNT {
        let name = name_of(v).unwrap_or_else(|| panic!("value {v} has no name: {}", last_error()));
        assert_eq!(from_name(&name), (GLS_OK, v), "{name}");
        assert_eq!(
            from_name(&name.to_uppercase()),
            (GLS_OK, v),
            "{name} upper-case"
        );
    }
}

#[test]
fn aliases_translate_to_their_modes() {
    for a in ALIASES {
        for spelling in [a.name.to_lowercase(), a.name.to_uppercase()] {
            let (rc, v) = from_name(&spelling);
            assert_eq!(rc, GLS_OK, "{spelling}: {}", last_error());
            assert_eq!(
                name_of(v).as_deref(),
                Some(a.mode.canonical_name()),
                "{spelling}"
            );
        }
    }
    assert_eq!(
        from_name("tb").1,
        glstereo::ffi::output::GLS_OUTPUT_TOP_BOTTOM_HALF
    );
    assert_eq!(
        from_name("ANAGLYPHIC").1,
        glstereo::ffi::output::GLS_OUTPUT_ANAGLYPH_RED_CYAN
    );
}

#[test]
fn unknown_name_is_invalid_value_listing_names_and_leaves_the_output_alone() {
    let (rc, out) = from_name("anaglyph-ultraviolet");
    assert_eq!(rc, GLS_ERROR_INVALID_VALUE);
    assert_eq!(out, u32::MAX, "output_out written on failure");
    let msg = last_error();
    assert!(msg.starts_with("gls_output_from_name: "), "{msg}");
    assert!(
        msg.contains("anaglyph-ultraviolet")
            && msg.contains("side-by-side-half")
            && msg.contains("VERTICAL_SPLIT"),
        "{msg}"
    );
}

#[test]
fn null_and_non_utf8_arguments_get_the_documented_codes() {
    let mut out = 7u32;
    // SAFETY: NULL is the case under test; the output pointer is valid.
    let rc = unsafe { gls_output_from_name(std::ptr::null(), &mut out) };
    assert_eq!(rc, GLS_ERROR_NULL_POINTER);
    assert!(
        last_error().contains("name must not be NULL"),
        "{}",
        last_error()
    );
    let name = CString::new("rows").unwrap();
    // SAFETY: a valid name; NULL output is the case under test.
    let rc = unsafe { gls_output_from_name(name.as_ptr(), std::ptr::null_mut()) };
    assert_eq!(rc, GLS_ERROR_NULL_POINTER);
    assert!(last_error().contains("output_out"), "{}", last_error());
    let bad = [0xFFu8, 0xFE, 0];
    // SAFETY: NUL-terminated bytes.
    let rc = unsafe { gls_output_from_name(bad.as_ptr() as *const c_char, &mut out) };
    assert_eq!(rc, GLS_ERROR_INVALID_VALUE);
    assert_eq!(out, 7, "output_out written on failure");
}

#[test]
fn out_of_range_value_has_no_name_and_says_the_range() {
    for v in [GLS_OUTPUT_COUNT, u32::MAX] {
        assert_eq!(name_of(v), None, "value {v}");
        let msg = last_error();
        assert!(
            msg.starts_with("gls_output_name: ") && msg.contains("GLS_OUTPUT_STR_RECT (26)"),
            "value {v}: {msg}"
        );
    }
}

//! GLX attribute lists as a program passes them: reading them safely from C
//! and taking the stereo request out before the real GLX sees it (Mesa has
//! no stereo visual, so a list that keeps GLX_STEREO matches nothing).
//! Pure: no X, no GL.

use crate::config::MAX_ATTRIBUTES;
use crate::config::glx::*;

/// GLX_DONT_CARE, as a glXChooseFBConfig value.
pub const GLX_DONT_CARE: i32 = -1;
/// GLX_FBCONFIG_ID: when present, glXChooseFBConfig ignores every other attribute.
pub const GLX_FBCONFIG_ID: i32 = 0x8013;

/// Booleans of a glXChooseVisual list, which stand alone (every other
/// attribute is followed by a value, as Mesa's parser reads them).
fn is_visual_boolean(a: i32) -> bool {
    matches!(a, GLX_USE_GL | GLX_RGBA | GLX_DOUBLEBUFFER | GLX_STEREO)
}

/// A glXChooseVisual list read up to its `None` terminator (excluded).
///
/// # Safety
/// `list` must be NULL or point to a `None`-terminated attribute list.
pub unsafe fn read_visual_list(list: *const i32) -> Vec<i32> {
    // SAFETY: forwarded contract; values are read only at positions the
    // list's own structure says exist.
    unsafe { read_list(list, |a| if is_visual_boolean(a) { 1 } else { 2 }) }
}

/// A glXChooseFBConfig (or context attribute) list read up to its `None`
/// terminator (excluded): attribute/value pairs.
///
/// # Safety
/// `list` must be NULL or point to a `None`-terminated list of pairs.
pub unsafe fn read_pair_list(list: *const i32) -> Vec<i32> {
    // SAFETY: forwarded contract.
    unsafe { read_list(list, |_| 2) }
}

unsafe fn read_list(list: *const i32, width: impl Fn(i32) -> usize) -> Vec<i32> {
    let mut out = Vec::new();
    if list.is_null() {
        return out;
    }
    let mut i = 0;
    while i < MAX_ATTRIBUTES {
        // SAFETY: position i is an attribute position of a None-terminated
        // list (the caller's contract): it exists.
        let a = unsafe { *list.add(i) };
        if a == 0 {
            break;
        }
        out.push(a);
        if width(a) == 2 {
            // SAFETY: a non-terminator attribute that takes a value has one.
            out.push(unsafe { *list.add(i + 1) });
        }
        i += width(a);
    }
    out
}

/// A glXChooseVisual list without its GLX_STEREO booleans, terminated by
/// `None`, and whether GLX_STEREO was asked for.
pub fn strip_visual_stereo(list: &[i32]) -> (Vec<i32>, bool) {
    let mut out = Vec::with_capacity(list.len() + 1);
    let mut stereo = false;
    let mut i = 0;
    while i < list.len() {
        let a = list[i];
        if a == GLX_STEREO {
            stereo = true;
            i += 1;
            continue;
        }
        let n = if is_visual_boolean(a) { 1 } else { 2 };
        out.extend_from_slice(&list[i..(i + n).min(list.len())]);
        i += n;
    }
    out.push(0);
    (out, stereo)
}

/// A glXChooseFBConfig list without its GLX_STEREO pair, terminated by
/// `None`, and whether GLX_STEREO was required (a value other than False
/// or GLX_DONT_CARE). A list with GLX_FBCONFIG_ID asks for one
/// configuration by its ID and nothing else, so it never asks for stereo.
pub fn strip_fbconfig_stereo(list: &[i32]) -> (Vec<i32>, bool) {
    let mut out = Vec::with_capacity(list.len() + 1);
    let mut stereo = false;
    let by_id = list.chunks(2).any(|p| p[0] == GLX_FBCONFIG_ID);
    for pair in list.chunks(2) {
        if pair[0] == GLX_STEREO {
            let v = pair.get(1).copied().unwrap_or(0);
            stereo |= v != 0 && v != GLX_DONT_CARE && !by_id;
            continue;
        }
        out.extend_from_slice(pair);
    }
    out.push(0);
    (out, stereo)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visual_lists_lose_only_the_stereo_boolean() {
        // Seed 000 §3's list.
        let seed = [
            GLX_RGBA,
            GLX_DOUBLEBUFFER,
            GLX_RED_SIZE,
            1,
            GLX_GREEN_SIZE,
            1,
            GLX_BLUE_SIZE,
            1,
            GLX_DEPTH_SIZE,
            1,
            GLX_STEREO,
        ];
        let (out, stereo) = strip_visual_stereo(&seed);
        assert!(stereo);
        assert_eq!(out, [&seed[..10], &[0]].concat());
        // A value that equals GLX_STEREO's token is a value, not the boolean.
        let (out, stereo) = strip_visual_stereo(&[GLX_RGBA, GLX_DEPTH_SIZE, GLX_STEREO]);
        assert!(!stereo);
        assert_eq!(out, [GLX_RGBA, GLX_DEPTH_SIZE, GLX_STEREO, 0]);
        let (out, stereo) = strip_visual_stereo(&[]);
        assert!(!stereo);
        assert_eq!(out, [0]);
    }

    #[test]
    fn fbconfig_lists_lose_the_stereo_pair_and_say_whether_it_was_required() {
        let list = [GLX_RED_SIZE, 1, GLX_DOUBLEBUFFER, 1, GLX_STEREO, 1];
        assert_eq!(
            strip_fbconfig_stereo(&list),
            (vec![GLX_RED_SIZE, 1, GLX_DOUBLEBUFFER, 1, 0], true)
        );
        for v in [0, GLX_DONT_CARE] {
            let (out, stereo) = strip_fbconfig_stereo(&[GLX_STEREO, v, GLX_DEPTH_SIZE, 24]);
            assert!(!stereo, "GLX_STEREO {v}");
            assert_eq!(out, [GLX_DEPTH_SIZE, 24, 0]);
        }
        let (_, stereo) = strip_fbconfig_stereo(&[GLX_FBCONFIG_ID, 0x21, GLX_STEREO, 1]);
        assert!(!stereo, "GLX_FBCONFIG_ID overrides everything else");
    }

    #[test]
    fn lists_are_read_by_their_structure_up_to_none() {
        let visual = [GLX_RGBA, GLX_DEPTH_SIZE, 0, GLX_STEREO, 0, 99];
        // SAFETY: a None-terminated list (the 0 after GLX_DEPTH_SIZE is its value).
        let got = unsafe { read_visual_list(visual.as_ptr()) };
        assert_eq!(got, [GLX_RGBA, GLX_DEPTH_SIZE, 0, GLX_STEREO]);
        let pairs = [GLX_STEREO, 1, GLX_DEPTH_SIZE, 0, 0, 7];
        // SAFETY: a None-terminated pair list.
        let got = unsafe { read_pair_list(pairs.as_ptr()) };
        assert_eq!(got, [GLX_STEREO, 1, GLX_DEPTH_SIZE, 0]);
        // SAFETY: NULL is an empty list.
        assert!(unsafe { read_pair_list(std::ptr::null()) }.is_empty());
    }
}

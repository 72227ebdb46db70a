//! Where the layer's calls go next, and how programs that load GL
//! themselves reach the layer.
//!
//! # The next implementation, not libGL by name
//!
//! The layer is one link of a chain of preloaded libraries: a program run as
//! `vglrun glstereo-run prog` or `apitrace trace glstereo-run prog` has
//! `LD_PRELOAD=libglstereo_preload.so:<the other layer>` (glstereo-run puts
//! itself first), and each GLX or GL call the layer forwards must reach the
//! layer below it, then libGL. So each real function is the *next* definition
//! of its name after the layer's own library, as `dlsym(RTLD_NEXT, name)`
//! finds it ([`next_symbol`]): another layer preloaded after this one, else
//! the libGL the program linked. Where the program did not link libGL (it
//! loads it itself with `dlopen(…, RTLD_LOCAL)`, as GLFW, SDL2, PyOpenGL and
//! libepoxy do), nothing global defines the name and the layer opens
//! `libGL.so.1` itself, through the next `dlopen` (so a layer below that
//! replaces dlopen, as VirtualGL's dlfaker does, still gets its say).
//!
//! An answer inside the layer's own library is never taken: a layer below
//! that looks names up globally (dlsym(RTLD_DEFAULT), its own
//! glXGetProcAddress) may hand the layer's exports back, and calling those
//! as "the real function" recursed until the stack overflowed. Such an
//! answer is replaced by libGL's own function ([`bottom_symbol`]: libGL
//! opened with libc's own dlopen, under every layer).
//!
//! # Loops found at run time
//!
//! Code below the layer may call a GL or GLX name globally *while the layer
//! is calling down*, which lands in the layer's export again: libGL's own
//! code now and then, or a layer below whose "real" function is a global
//! look-up. The preload's exports count how deep the calling thread is
//! inside the layer ([`enter`]). Entered from inside, an export is not
//! serving the program: it forwards to the next definition of its name,
//! without stereo. A layer below that keeps calling back is a loop: at
//! [`NESTING_LIMIT`] deep the export says so on stderr, once per function,
//! and calls libGL's own function directly. It never recurses unbounded.
//!
//! # Programs that load GL themselves
//!
//! LD_PRELOAD puts the layer's exports first in the global scope, so a
//! direct link, `dlsym(RTLD_DEFAULT, …)` and `dlsym(RTLD_NEXT, …)` from the
//! executable find them, and the layer's `glXGetProcAddress(ARB)` hands
//! them out. But `dlsym(handle, …)` on a handle from
//! `dlopen("libGL.so.1")` searches that library and its dependencies only.
//! So the preload replaces `dlopen` ([`dlopen_for_program`]): for
//! libGL.so(.1), libGLX.so(.0), libOpenGL.so(.0), libEGL.so(.1) and
//! libGLESv2.so(.2), by any path, it opens
//! the library as asked (same flags, same failure), then returns the handle
//! of a small stub library installed beside the preload whose dependencies
//! are, in order, the preload and that GL library
//! (`libglstereo_stub_GL.so`, `…_GLX.so`, `…_OpenGL.so`, `…_EGL.so`,
//! `…_GLESv2.so`, made by the
//! preload's build script). dlsym on it finds the layer's replacement first
//! and every other name in the real library; unknown names get dlsym's own
//! NULL and dlerror; dlclose closes the stub (the real library stays while
//! anything else holds it). Every other dlopen, and any dlopen made while
//! the calling thread is inside the layer (the layer's own look-ups, a layer
//! below loading libGL), goes to the next dlopen untouched.

use std::cell::Cell;
use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::sync::OnceLock;

/// `dlopen`'s type.
type DlopenFn = unsafe extern "C" fn(*const c_char, c_int) -> *mut c_void;

thread_local! {
    /// How many of the layer's exports are running on this thread.
    static DEPTH: Cell<u32> = const { Cell::new(0) };
}

/// Proof that the calling thread is inside one of the layer's exports; the
/// depth drops again when it is dropped (also on unwinding).
pub struct Entered(());

impl Drop for Entered {
    fn drop(&mut self) {
        DEPTH.with(|d| d.set(d.get().saturating_sub(1)));
    }
}

/// How deep exports may nest on one thread before a re-entry is taken
/// for a loop ([`enter`]).
pub const NESTING_LIMIT: u32 = 8;

/// Enters the layer and says how deep the thread was inside it already:
/// 0 for a call from the program; more for a call back by name while the
/// layer is calling down (libGL's own code may do that: no loop, the call
/// goes to the next definition); [`NESTING_LIMIT`] or more, a loop.
pub fn enter() -> (Entered, u32) {
    DEPTH.with(|d| {
        let depth = d.get();
        d.set(depth + 1);
        (Entered(()), depth)
    })
}

/// Whether the calling thread is inside one of the layer's exports.
pub fn inside() -> bool {
    DEPTH.with(|d| d.get() > 0)
}

/// Says once per function that `name` was re-entered from below.
pub fn loop_detected(name: &str) {
    super::warn(&format!(
        "{name} was called back into glstereo by a GL layer below it while glstereo was \
         forwarding a call to that layer (a look-up loop); such calls go straight to libGL, \
         without stereo"
    ));
}

/// The base address of the object (executable or shared library) holding
/// `p`, or None when `p` is in none.
fn object_of(p: *const c_void) -> Option<usize> {
    if p.is_null() {
        return None;
    }
    let mut info = std::mem::MaybeUninit::<libc::Dl_info>::zeroed();
    // SAFETY: dladdr only reads its address argument and fills `info`.
    let found = unsafe { libc::dladdr(p, info.as_mut_ptr()) } != 0;
    // SAFETY: zero-initialised and filled by dladdr where found.
    let info = unsafe { info.assume_init() };
    (found && !info.dli_fbase.is_null()).then_some(info.dli_fbase as usize)
}

/// The layer's own library (libglstereo_preload.so, or libglstereo.so for
/// programs rebuilt with compat.h): its base address and path.
fn own_object() -> &'static (usize, Option<CString>) {
    static OWN: OnceLock<(usize, Option<CString>)> = OnceLock::new();
    OWN.get_or_init(|| {
        let here = own_object as *const c_void;
        let mut info = std::mem::MaybeUninit::<libc::Dl_info>::zeroed();
        // SAFETY: as in object_of.
        let found = unsafe { libc::dladdr(here, info.as_mut_ptr()) } != 0;
        // SAFETY: zero-initialised and filled by dladdr where found.
        let info = unsafe { info.assume_init() };
        if !found {
            return (0, None);
        }
        let path = (!info.dli_fname.is_null())
            // SAFETY: dladdr's file name is a NUL-terminated string of the loader.
            .then(|| unsafe { CStr::from_ptr(info.dli_fname) }.to_owned());
        (info.dli_fbase as usize, path)
    })
}

/// Whether `p` lies in the layer's own library.
pub fn is_own(p: *const c_void) -> bool {
    let own = own_object().0;
    own != 0 && object_of(p) == Some(own)
}

/// The next `dlopen` after the layer's library (libc's, or a layer's below).
fn next_dlopen() -> Option<DlopenFn> {
    static NEXT: OnceLock<usize> = OnceLock::new();
    let p = *NEXT.get_or_init(|| {
        // SAFETY: dlsym with a NUL-terminated name; RTLD_NEXT is relative to
        // this library, the caller of dlsym.
        let p = unsafe { libc::dlsym(libc::RTLD_NEXT, c"dlopen".as_ptr()) };
        if is_own(p) { 0 } else { p as usize }
    });
    // SAFETY: the address of a function with dlopen's signature.
    (p != 0).then(|| unsafe { std::mem::transmute::<usize, DlopenFn>(p) })
}

/// libc's own `dlopen`, under every layer: looked up in libc's handle.
fn libc_dlopen() -> Option<DlopenFn> {
    static LIBC: OnceLock<usize> = OnceLock::new();
    let p = *LIBC.get_or_init(|| {
        // SAFETY: libc is loaded in every process; RTLD_NOLOAD only looks
        // it up. This goes through the global dlopen (the preload's, which
        // passes a name that is not GL's to the next dlopen).
        let h = unsafe { libc::dlopen(c"libc.so.6".as_ptr(), libc::RTLD_NOW | libc::RTLD_NOLOAD) };
        if h.is_null() {
            return 0;
        }
        // SAFETY: a live handle and a NUL-terminated name.
        unsafe { libc::dlsym(h, c"dlopen".as_ptr()) as usize }
    });
    // SAFETY: the address of libc's dlopen.
    (p != 0).then(|| unsafe { std::mem::transmute::<usize, DlopenFn>(p) })
}

/// Calls the next dlopen (see the module doc).
///
/// # Safety
/// As dlopen: `filename` NULL or NUL-terminated.
pub unsafe fn real_dlopen(filename: *const c_char, flags: c_int) -> *mut c_void {
    match next_dlopen() {
        // SAFETY: forwarded contract.
        Some(f) => unsafe { f(filename, flags) },
        None => std::ptr::null_mut(),
    }
}

/// libGL.so.1 as the next dlopen opens it (kept open for the process).
fn next_libgl() -> *mut c_void {
    static H: OnceLock<usize> = OnceLock::new();
    // SAFETY: a NUL-terminated name.
    *H.get_or_init(|| unsafe {
        real_dlopen(c"libGL.so.1".as_ptr(), libc::RTLD_NOW | libc::RTLD_LOCAL) as usize
    }) as *mut c_void
}

/// libGL.so.1 as libc's own dlopen opens it, under every layer.
fn bottom_libgl() -> *mut c_void {
    static H: OnceLock<usize> = OnceLock::new();
    *H.get_or_init(|| match libc_dlopen() {
        // SAFETY: libc's dlopen with a NUL-terminated name.
        Some(f) => unsafe { f(c"libGL.so.1".as_ptr(), libc::RTLD_NOW | libc::RTLD_LOCAL) as usize },
        None => 0,
    }) as *mut c_void
}

/// Whether libGL.so.1 can be opened at all (under every layer).
pub fn libgl_loadable() -> bool {
    !bottom_libgl().is_null()
}

/// dlsym of `name` in `handle`, refusing an answer inside the layer.
fn lookup_in(handle: *mut c_void, name: &CStr) -> *mut c_void {
    if handle.is_null() {
        return std::ptr::null_mut();
    }
    // SAFETY: a live handle (or RTLD_NEXT) and a NUL-terminated name.
    let p = unsafe { libc::dlsym(handle, name.as_ptr()) };
    if is_own(p) { std::ptr::null_mut() } else { p }
}

/// The next definition of `name` after the layer (see the module doc);
/// NULL where neither the chain nor libGL has one.
pub fn next_symbol(name: &CStr) -> *mut c_void {
    let p = lookup_in(libc::RTLD_NEXT, name);
    if !p.is_null() {
        return p;
    }
    let p = lookup_in(next_libgl(), name);
    if !p.is_null() {
        return p;
    }
    bottom_symbol(name)
}

/// The next definition of `name`, a function of library `soname` that is
/// not GL's (libxcb's event functions): the next definition after the
/// layer, else the one in `soname` as loaded already (a library opened
/// with RTLD_LOCAL, as SDL2 opens libX11 and so libxcb, is in no global
/// scope). Never the layer's own; NULL where `soname` is not loaded —
/// nothing is loaded for the look-up (a program that never loaded GL
/// does not get libGL loaded behind its back, unlike [`next_symbol`]).
pub fn next_symbol_in(name: &CStr, soname: &CStr) -> *mut c_void {
    let p = lookup_in(libc::RTLD_NEXT, name);
    if !p.is_null() {
        return p;
    }
    own_symbol_in(name, soname)
}

/// `soname`'s own `name`, under every layer (a handle's look-up searches
/// that library and its dependencies only); NULL where `soname` is not
/// loaded.
pub fn own_symbol_in(name: &CStr, soname: &CStr) -> *mut c_void {
    let Some(open) = libc_dlopen() else {
        return std::ptr::null_mut();
    };
    // SAFETY: libc's dlopen with a NUL-terminated name; RTLD_NOLOAD only
    // finds a library that is loaded already. The reference it takes is
    // kept: the address found is cached by the caller, and must stay
    // valid if the program unloads its own user of the library.
    let h = unsafe { open(soname.as_ptr(), libc::RTLD_LAZY | libc::RTLD_NOLOAD) };
    lookup_in(h, name)
}

/// libGL's own `name`, under every layer: from libGL.so.1 opened with
/// libc's dlopen, else from its glXGetProcAddressARB. NULL without libGL.
pub fn bottom_symbol(name: &CStr) -> *mut c_void {
    let h = bottom_libgl();
    let p = lookup_in(h, name);
    if !p.is_null() {
        return p;
    }
    type Gpa = unsafe extern "C" fn(*const u8) -> *mut c_void;
    let gpa = lookup_in(h, c"glXGetProcAddressARB");
    if gpa.is_null() {
        return std::ptr::null_mut();
    }
    // SAFETY: libGL's glXGetProcAddressARB, with a NUL-terminated name.
    let p = unsafe { std::mem::transmute::<*mut c_void, Gpa>(gpa)(name.as_ptr().cast()) };
    if is_own(p) { std::ptr::null_mut() } else { p }
}

/// libEGL.so.1 as the next dlopen opens it (kept open for the process).
fn next_libegl() -> *mut c_void {
    static H: OnceLock<usize> = OnceLock::new();
    // SAFETY: a NUL-terminated name.
    *H.get_or_init(|| unsafe {
        real_dlopen(c"libEGL.so.1".as_ptr(), libc::RTLD_NOW | libc::RTLD_LOCAL) as usize
    }) as *mut c_void
}

/// libEGL.so.1 as libc's own dlopen opens it, under every layer.
fn bottom_libegl() -> *mut c_void {
    static H: OnceLock<usize> = OnceLock::new();
    *H.get_or_init(|| match libc_dlopen() {
        // SAFETY: libc's dlopen with a NUL-terminated name.
        Some(f) => unsafe {
            f(c"libEGL.so.1".as_ptr(), libc::RTLD_NOW | libc::RTLD_LOCAL) as usize
        },
        None => 0,
    }) as *mut c_void
}

/// Whether libEGL.so.1 can be opened at all (under every layer).
pub fn libegl_loadable() -> bool {
    !bottom_libegl().is_null()
}

/// The next definition of EGL function `name` after the layer, as
/// [`next_symbol`] finds GL's: the chain of preloaded libraries, then
/// libEGL.so.1 (opened through the next dlopen), then libEGL's own
/// ([`bottom_egl_symbol`]). NULL where no EGL has it.
pub fn next_egl_symbol(name: &CStr) -> *mut c_void {
    let p = lookup_in(libc::RTLD_NEXT, name);
    if !p.is_null() {
        return p;
    }
    let p = lookup_in(next_libegl(), name);
    if !p.is_null() {
        return p;
    }
    bottom_egl_symbol(name)
}

/// libEGL's own `name`, under every layer: from libEGL.so.1 opened with
/// libc's dlopen, else (extension functions, which libEGL does not
/// export) from its eglGetProcAddress. NULL without libEGL.
pub fn bottom_egl_symbol(name: &CStr) -> *mut c_void {
    let h = bottom_libegl();
    let p = lookup_in(h, name);
    if !p.is_null() {
        return p;
    }
    type Gpa = unsafe extern "C" fn(*const c_char) -> *mut c_void;
    let gpa = lookup_in(h, c"eglGetProcAddress");
    if gpa.is_null() {
        return std::ptr::null_mut();
    }
    // SAFETY: libEGL's eglGetProcAddress, with a NUL-terminated name.
    let p = unsafe { std::mem::transmute::<*mut c_void, Gpa>(gpa)(name.as_ptr()) };
    if is_own(p) { std::ptr::null_mut() } else { p }
}

/// Which GL library a dlopen names, by its file name in any directory:
/// the stub that stands for it.
fn stub_for(filename: &CStr) -> Option<&'static str> {
    let bytes = filename.to_bytes();
    let base = bytes.rsplit(|&b| b == b'/').next().unwrap_or(bytes);
    let is = |stem: &[u8]| {
        base.strip_prefix(stem)
            .is_some_and(|rest| rest.is_empty() || rest.starts_with(b"."))
    };
    if is(b"libGL.so") {
        Some(STUB_GL)
    } else if is(b"libGLX.so") {
        Some(STUB_GLX)
    } else if is(b"libOpenGL.so") {
        Some(STUB_OPENGL)
    } else if is(b"libEGL.so") {
        Some(STUB_EGL)
    } else if is(b"libGLESv2.so") {
        Some(STUB_GLESV2)
    } else {
        None
    }
}

/// The stub standing for libGL.so.1 (its dependencies: the preload, libGL.so.1).
pub const STUB_GL: &str = "libglstereo_stub_GL.so";
/// The stub standing for libGLX.so.0.
pub const STUB_GLX: &str = "libglstereo_stub_GLX.so";
/// The stub standing for libOpenGL.so.0.
pub const STUB_OPENGL: &str = "libglstereo_stub_OpenGL.so";
/// The stub standing for libEGL.so.1 (SDL2, GLFW, Qt and libepoxy open it).
pub const STUB_EGL: &str = "libglstereo_stub_EGL.so";
/// The stub standing for libGLESv2.so.2.
pub const STUB_GLESV2: &str = "libglstereo_stub_GLESv2.so";

/// The preload's `dlopen` (see the module doc).
///
/// # Safety
/// As dlopen: `filename` NULL or NUL-terminated.
pub unsafe fn dlopen_for_program(filename: *const c_char, flags: c_int) -> *mut c_void {
    // SAFETY: forwarded contract.
    let real = || unsafe { real_dlopen(filename, flags) };
    if filename.is_null() || inside() {
        return real();
    }
    // SAFETY: dlopen's contract: a NUL-terminated name.
    let Some(stub) = stub_for(unsafe { CStr::from_ptr(filename) }) else {
        return real();
    };
    // Open the GL library itself as asked: its failure is the program's
    // answer, and the stub's dependency then binds to this very object
    // (a dependency is matched by soname among the loaded objects first).
    let h = real();
    if h.is_null() {
        return h;
    }
    let Some(dir) = own_object()
        .1
        .as_ref()
        .and_then(|p| std::path::Path::new(std::ffi::OsStr::from_bytes(p.to_bytes())).parent())
    else {
        return h;
    };
    let Ok(path) = CString::new(dir.join(stub).into_os_string().into_vec()) else {
        return h;
    };
    // SAFETY: a NUL-terminated path; the program's flags without
    // RTLD_NOLOAD (the GL library is loaded, the stub may not be yet).
    let s = unsafe { real_dlopen(path.as_ptr(), flags & !libc::RTLD_NOLOAD) };
    if s.is_null() {
        super::warn(&format!(
            "{} is missing or cannot be loaded beside the preload library: programs that \
             dlopen GL get no stereo; reinstall glstereo",
            path.to_string_lossy()
        ));
        return h;
    }
    // The stub holds the GL library now; drop the program's extra reference
    // so dlclose of the stub releases everything it opened.
    // SAFETY: the handle the real dlopen just returned.
    unsafe { libc::dlclose(h) };
    s
}

use std::os::unix::ffi::{OsStrExt, OsStringExt};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gl_libraries_are_recognised_by_file_name_in_any_directory() {
        let cases: [(&CStr, Option<&str>); 17] = [
            (c"libGL.so.1", Some(STUB_GL)),
            (c"libGL.so", Some(STUB_GL)),
            (c"/usr/lib/x86_64-linux-gnu/libGL.so.1.7.0", Some(STUB_GL)),
            (c"libGLX.so.0", Some(STUB_GLX)),
            (c"./lib/libGLX.so", Some(STUB_GLX)),
            (c"libOpenGL.so.0", Some(STUB_OPENGL)),
            (c"/opt/x/libOpenGL.so.0.0.0", Some(STUB_OPENGL)),
            (c"libGLU.so.1", None),
            (c"libGLX_mesa.so.0", None),
            (c"libGLESv2.so.2", Some(STUB_GLESV2)),
            (c"libEGL.so.1", Some(STUB_EGL)),
            (c"/usr/lib/x86_64-linux-gnu/libEGL.so", Some(STUB_EGL)),
            (c"libEGL_mesa.so.0", None),
            (c"libGLESv1_CM.so.1", None),
            (c"libGL.so1", None),
            (c"/usr/lib/libGL.so.1/libm.so.6", None),
            (c"", None),
        ];
        for (name, stub) in cases {
            assert_eq!(stub_for(name), stub, "{name:?}");
        }
    }

    #[test]
    fn the_layer_depth_counts_nested_entries_and_unwinds() {
        let (a, d0) = enter();
        assert_eq!(d0, 0);
        {
            let (_b, d1) = enter();
            assert_eq!(d1, 1);
            assert!(inside());
        }
        drop(a);
        assert!(!inside());
        let caught = std::panic::catch_unwind(|| {
            let _e = enter();
            panic!("unwinds");
        });
        assert!(caught.is_err());
        assert!(!inside(), "a panic leaves the depth where it was");
    }

    #[test]
    fn the_next_definition_is_never_the_layers_own() {
        // In a test binary the crate is linked into the executable: the
        // next definition of a libc name is libc's, outside this object.
        let p = next_symbol(c"strlen");
        assert!(!p.is_null());
        assert!(!is_own(p));
        assert!(is_own(own_object as *const c_void));
    }
}

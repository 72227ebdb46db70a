//! GL backends: where contexts come from. Chosen at run time and loaded with
//! dlopen, so the library links no GL library and loads on machines that
//! have none (the error then names the package to install).
//!
//! Every surface owns two contexts that share objects: the *application*
//! context the program renders with, and a *compositor* context the library
//! uses to read back and compose the eyes, so nothing the library does ever
//! touches the program's GL state.

pub mod egl;
pub mod glx;
pub mod osmesa;
pub(crate) mod xshm;

use std::ffi::{CStr, c_void};

use crate::config::{Config, ConfigRequest, EmulationPolicy};
use crate::error::{Error, Result};

/// Which GL backend a display uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendKind {
    /// GLX on an X server ($DISPLAY): real windows.
    Glx,
    /// EGL on Mesa's surfaceless platform: headless.
    Egl,
    /// OSMesa: headless, software only.
    OsMesa,
}

impl BackendKind {
    /// The name used by GLSTEREO_BACKEND and in messages.
    pub fn name(self) -> &'static str {
        match self {
            BackendKind::Glx => "glx",
            BackendKind::Egl => "egl",
            BackendKind::OsMesa => "osmesa",
        }
    }
}

/// What the program or the user asked for: a specific backend or the
/// automatic choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendChoice {
    /// GLX when $DISPLAY is usable, else EGL surfaceless, else OSMesa (and
    /// OSMesa first when the program's `gl*` calls resolve to libOSMesa).
    Auto,
    /// Exactly this backend.
    Only(BackendKind),
}

impl BackendChoice {
    /// Parses GLSTEREO_BACKEND: auto, glx, egl or osmesa (any case); unset or
    /// empty is auto.
    pub fn from_env_value(v: Option<&str>) -> Result<BackendChoice> {
        match v.map(|s| s.trim().to_ascii_lowercase()).as_deref() {
            None | Some("") | Some("auto") => Ok(BackendChoice::Auto),
            Some("glx") => Ok(BackendChoice::Only(BackendKind::Glx)),
            Some("egl") => Ok(BackendChoice::Only(BackendKind::Egl)),
            Some("osmesa") => Ok(BackendChoice::Only(BackendKind::OsMesa)),
            Some(other) => Err(Error::invalid_value(format!(
                "GLSTEREO_BACKEND={other:?} is not valid: use auto, glx, egl or osmesa"
            ))),
        }
    }
}

/// Which of a surface's two contexts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContextRole {
    /// The context the program renders with.
    App,
    /// The library's own context (read-back, composition, presentation).
    Compositor,
}

/// One backend connection (an EGL display, the OSMesa library, an X display).
pub trait Platform: Send + Sync {
    /// Which backend this is.
    fn kind(&self) -> BackendKind;

    /// Chooses a configuration for a parsed request. Backends without native
    /// stereo use [`Config::choose`] with `native_stereo_available = false`.
    fn choose_config(&self, request: ConfigRequest, policy: EmulationPolicy) -> Result<Config> {
        Config::choose(request, false, policy)
    }

    /// Creates the drawable (if any) and the two contexts of a surface.
    fn create_surface(
        &self,
        config: &Config,
        width: u32,
        height: u32,
    ) -> Result<Box<dyn PlatformSurface>>;

    /// The address of a GL function of this backend (NULL if unknown; EGL
    /// may return a stub for unknown names).
    fn get_proc_address(&self, name: &CStr) -> *const c_void;
}

/// Something that happened to a window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WindowEvent {
    /// A key was pressed: its X keysym (XK_*; Latin-1 keys are their character codes).
    Key(u32),
    /// The user asked to close the window (the window manager's close button).
    CloseRequested,
    /// The window was resized: from the platform, the window size; from a
    /// surface, the new size of each eye (in effect from the next frame).
    Resized(u32, u32),
}

/// The backend's own handles of a surface, for programs that mix glstereo
/// with their own use of the backend.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NativeHandles {
    /// Xlib `Display*`, the X `Window`, and the application's `GLXContext`.
    Glx {
        /// `Display*`.
        display: *mut c_void,
        /// `Window` (XID).
        window: u64,
        /// `GLXContext` of the application.
        context: *mut c_void,
    },
    /// `EGLDisplay` and the application's `EGLContext` (surfaceless: no `EGLSurface`).
    Egl {
        /// `EGLDisplay`.
        display: *mut c_void,
        /// `EGLContext` of the application.
        context: *mut c_void,
    },
    /// The application's `OSMesaContext` and the buffer it is bound to.
    OsMesa {
        /// `OSMesaContext` of the application.
        context: *mut c_void,
        /// The 1x1 RGBA buffer bound with OSMesaMakeCurrent (rendering goes to glstereo's framebuffer).
        buffer: *mut c_void,
    },
}

/// How a window buffer stores a pixel: a 32-bit little-endian word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelLayout {
    /// Bytes B, G, R, X (red mask 0xff0000): Xvfb's and most X servers' 24-bit visuals.
    Bgrx,
    /// Bytes R, G, B, X (red mask 0x0000ff).
    Rgbx,
}

impl PixelLayout {
    /// An RGBA8 word (R in the low byte) as this layout's word, X byte 0xff.
    #[inline(always)]
    pub fn convert(self, rgba: u32) -> u32 {
        let w = match self {
            PixelLayout::Bgrx => ((rgba & 0xff) << 16) | (rgba & 0xff00) | ((rgba >> 16) & 0xff),
            PixelLayout::Rgbx => rgba,
        };
        w | 0xff00_0000
    }
}

/// A window buffer to write one frame into ([`PlatformSurface::present_pixels`]).
#[derive(Debug)]
pub struct PixelTarget<'a> {
    /// The rows, top first, `stride` bytes apart (4-byte aligned).
    pub data: &'a mut [u8],
    /// Bytes from one row to the next (at least width × 4).
    pub stride: usize,
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// How pixels are stored.
    pub layout: PixelLayout,
}

impl PixelTarget<'_> {
    /// Row `y` (0 = top), `width × 4` bytes.
    pub fn row_mut(&mut self, y: u32) -> &mut [u8] {
        let start = y as usize * self.stride;
        &mut self.data[start..start + self.size.0 as usize * 4]
    }

    /// Writes an RGBA8 image of the target's size (rows top first unless
    /// `bottom_first`) in the target's layout.
    pub fn write_image(&mut self, img: &crate::image::Image, bottom_first: bool) {
        let h = self.size.1;
        for y in 0..h {
            let src = img.row(if bottom_first { h - 1 - y } else { y });
            let layout = self.layout;
            convert_row(src, self.row_mut(y), layout);
        }
    }
}

/// Converts a row of RGBA8 pixels into `layout`'s words (on word slices
/// when aligned: about memcpy speed; byte by byte otherwise).
pub fn convert_row(src: &[u8], dst: &mut [u8], layout: PixelLayout) {
    use crate::image::{as_words, as_words_mut};
    if let (Some(s), Some(d)) = (as_words(src), as_words_mut(dst)) {
        for (d, &v) in d.iter_mut().zip(s) {
            *d = layout.convert(v);
        }
        return;
    }
    for (d, s) in dst.chunks_exact_mut(4).zip(src.chunks_exact(4)) {
        let v = u32::from_le_bytes([s[0], s[1], s[2], s[3]]);
        d.copy_from_slice(&layout.convert(v).to_le_bytes());
    }
}

/// The backend half of a surface: its drawable and two contexts.
pub trait PlatformSurface: Send + Sync {
    /// Makes one of the surface's contexts current on the calling thread.
    fn make_current(&self, role: ContextRole) -> Result<()>;

    /// Releases whatever context of this backend is current on the calling thread.
    fn release_current(&self) -> Result<()>;

    /// Shows the drawable's back buffer (a real swap); headless backends do nothing.
    /// For a surface with a window ([`PlatformSurface::drawable_size`] is
    /// Some), it is called with the compositor context current, right after
    /// the composite was drawn into that context's framebuffer 0 (its back
    /// buffer when double-buffered).
    fn present(&self) -> Result<()> {
        Ok(())
    }

    /// Whether [`PlatformSurface::present_pixels`] may show a frame (false
    /// once it found it cannot): lets the caller skip preparing one.
    fn accepts_pixels(&self) -> bool {
        false
    }

    /// Shows a frame of `size` in the window from memory, instead of a GL
    /// composite and [`PlatformSurface::present`]: the cheaper way on a
    /// software renderer (GLX: MIT-SHM, see `backend/xshm.rs`). `fill`
    /// writes the frame into the backend's buffer; it is called at most
    /// once, and its error is returned. Ok(false) when the backend cannot
    /// (no window, no MIT-SHM, an unsupported visual, `size` is not the
    /// window's): nothing was shown and the caller takes the GL path.
    fn present_pixels(
        &self,
        _size: (u32, u32),
        _fill: &mut dyn FnMut(PixelTarget<'_>) -> Result<()>,
    ) -> Result<bool> {
        Ok(false)
    }

    /// The drawable's current size, for backends with windows that can be
    /// resized; None for headless surfaces, whose size is fixed. Some makes
    /// every swap compose the front buffers into the compositor context's
    /// framebuffer 0 at this size (fitted by
    /// [`crate::output::layout::window_fit`]) before [`PlatformSurface::present`].
    fn drawable_size(&self) -> Option<(u32, u32)> {
        None
    }

    /// Resizes the window (headless surfaces: `InvalidOperation`).
    fn resize_window(&self, _width: u32, _height: u32) -> Result<()> {
        Err(Error::invalid_operation(
            "a headless surface has no window to resize",
        ))
    }

    /// The next window event, if any (headless surfaces have none).
    fn next_event(&self) -> Option<WindowEvent> {
        None
    }

    /// Whether the user asked to close the window.
    fn close_requested(&self) -> bool {
        false
    }

    /// Sets the window title (headless surfaces: nothing to do).
    fn set_title(&self, _title: &str) -> Result<()> {
        Ok(())
    }

    /// The backend's own handles.
    fn native_handles(&self) -> NativeHandles;
}

/// Opens the backend `choice` selects. For Auto, tries GLX (when compiled
/// in and $DISPLAY is set), then EGL, then OSMesa, except that a program
/// whose `gl*` symbols come from libOSMesa gets OSMesa (its calls could not
/// reach any other backend's context).
pub fn open(choice: BackendChoice) -> Result<Box<dyn Platform>> {
    match choice {
        BackendChoice::Only(kind) => open_kind(kind),
        BackendChoice::Auto => {
            if program_gl_is_osmesa() == Some(true) {
                return open_kind(BackendKind::OsMesa);
            }
            let mut failures = Vec::new();
            for kind in auto_order() {
                match open_kind(kind) {
                    Ok(p) => return Ok(p),
                    Err(e) => failures.push(format!("{}: {e}", kind.name())),
                }
            }
            Err(Error::BackendUnavailable(format!(
                "no GL backend could be opened ({})",
                failures.join("; ")
            )))
        }
    }
}

fn auto_order() -> Vec<BackendKind> {
    let mut v = Vec::new();
    if glx_available() && std::env::var_os("DISPLAY").is_some_and(|d| !d.is_empty()) {
        v.push(BackendKind::Glx);
    }
    v.push(BackendKind::Egl);
    v.push(BackendKind::OsMesa);
    v
}

/// Whether GLX is worth trying: libGL can be loaded.
fn glx_available() -> bool {
    // SAFETY: loading the system's libGL runs only its initialisers; the GLX
    // backend loads it anyway when used.
    unsafe { libloading::Library::new("libGL.so.1") }.is_ok()
}

fn open_kind(kind: BackendKind) -> Result<Box<dyn Platform>> {
    match kind {
        BackendKind::Egl => Ok(Box::new(egl::EglPlatform::open()?)),
        BackendKind::OsMesa => {
            if program_gl_is_osmesa() == Some(false) {
                return Err(Error::BackendUnavailable(
                    "this program calls GL through libGL, whose calls cannot reach an OSMesa \
                     context: link it with -lOSMesa instead of -lGL, or use GLSTEREO_BACKEND=egl"
                        .into(),
                ));
            }
            Ok(Box::new(osmesa::OsMesaPlatform::open()?))
        }
        BackendKind::Glx => Ok(Box::new(glx::GlxPlatform::open(None)?)),
    }
}

/// Where the process's global `glClear` comes from: Some(true) for
/// libOSMesa, Some(false) for another GL library, None when the program
/// does not call GL itself.
pub fn program_gl_is_osmesa() -> Option<bool> {
    // SAFETY: dlsym/dladdr with a static NUL-terminated name and a valid
    // Dl_info out-pointer; the returned strings are owned by the loader.
    unsafe {
        let sym = libc::dlsym(libc::RTLD_DEFAULT, c"glClear".as_ptr());
        if sym.is_null() {
            return None;
        }
        let mut info: libc::Dl_info = std::mem::zeroed();
        if libc::dladdr(sym, &mut info) == 0 || info.dli_fname.is_null() {
            return None;
        }
        let lib = CStr::from_ptr(info.dli_fname).to_string_lossy();
        Some(lib.contains("OSMesa"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backend_names_parse() {
        assert_eq!(
            BackendChoice::from_env_value(None).unwrap(),
            BackendChoice::Auto
        );
        assert_eq!(
            BackendChoice::from_env_value(Some("EGL")).unwrap(),
            BackendChoice::Only(BackendKind::Egl)
        );
        assert_eq!(
            BackendChoice::from_env_value(Some(" osmesa ")).unwrap(),
            BackendChoice::Only(BackendKind::OsMesa)
        );
        let e = BackendChoice::from_env_value(Some("vulkan")).unwrap_err();
        assert!(e.to_string().contains("auto, glx, egl or osmesa"), "{e}");
    }
}

//! Surfaces, the current surface, and the emulated default framebuffer's GL
//! state through the C ABI.

use std::ffi::{c_char, c_void};
use std::sync::Arc;

use super::boundary::{arg_out, arg_ref, arg_str, ffi_boundary, write_out};
use super::display::{gls_config, gls_display};
use super::handles::{self, Kind};
use super::types::*;
use crate::backend::{NativeHandles, WindowEvent};
use crate::config::Config;
use crate::display::Display;
use crate::error::Error;
use crate::framing::InputFraming;
use crate::math::{Eye, hp_eye};
use crate::surface::{self, CaptureImage, Surface};

/// A stereo (or mono) drawing surface with its own GL context (opaque).
pub struct gls_surface {
    _private: [u8; 0],
}

/// The left eye's front buffer, as displayed.
pub const GLS_IMAGE_LEFT: u32 = 0;
/// The right eye's front buffer, as displayed (the left one on a mono surface).
pub const GLS_IMAGE_RIGHT: u32 = 1;
/// Both eyes composed in the surface's output mode, as a viewer sees them.
pub const GLS_IMAGE_COMPOSITE: u32 = 2;

/// The capture a GLS_IMAGE_* value names.
pub(super) fn image_arg(image: u32) -> Result<CaptureImage, Error> {
    match image {
        GLS_IMAGE_LEFT => Ok(CaptureImage::Left),
        GLS_IMAGE_RIGHT => Ok(CaptureImage::Right),
        GLS_IMAGE_COMPOSITE => Ok(CaptureImage::Composite),
        v => Err(Error::invalid_enum(
            "image",
            v,
            "use GLS_IMAGE_LEFT, GLS_IMAGE_RIGHT or GLS_IMAGE_COMPOSITE",
        )),
    }
}

fn surface_arg(s: *const gls_surface) -> Result<Arc<Surface>, Error> {
    handles::get(s, Kind::Surface, "surface")
}

/// Creates a surface: an emulated default framebuffer of `width` × `height`
/// pixels per eye (left/right, front/back as the configuration says, one
/// depth/stencil buffer shared by both eyes) and its own GL context
/// (compatibility profile, 4.5 on Mesa).
///
/// @param display a live display. @param config a live configuration from it.
/// @param width, height 1…16384 (and within the driver's limits).
/// @param surface_out receives the surface; must not be NULL. Destroy it with gls_surface_destroy().
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_VALUE (size, or a bad GLSTEREO_MODE and the other
/// output variables); GLS_ERROR_INVALID_OPERATION (a configuration chosen on
/// another display); GLS_ERROR_OUT_OF_MEMORY;
/// GLS_ERROR_BACKEND_UNAVAILABLE (no context could be created). Any thread;
/// the calling thread's current surface is unchanged.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_create(
    display: *mut gls_display,
    config: *const gls_config,
    width: u32,
    height: u32,
    surface_out: *mut *mut gls_surface,
) -> gls_result {
    ffi_boundary!("gls_surface_create", {
        let d: Arc<Display> = handles::get(display, Kind::Display, "display")?;
        let c: Arc<Config> = handles::get(config, Kind::Config, "config")?;
        let out = arg_out(surface_out, "surface_out")?;
        let s = d.create_surface(&c, width, height)?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, handles::publish(s, Kind::Surface)) };
        Ok(())
    })
}

/// Destroys a surface and its context. If it is current on the calling
/// thread it is released first; if it is current on another thread it lives
/// on until released there. NULL is a no-op; a handle that is not live is
/// ignored (and reported by gls_last_error_message()).
#[unsafe(no_mangle)]
pub extern "C" fn gls_surface_destroy(surface: *mut gls_surface) {
    ffi_boundary!("gls_surface_destroy", () => {
        if surface.is_null() {
            return Ok(());
        }
        let s: Arc<Surface> =
            handles::release(surface, Kind::Surface).ok_or(Error::InvalidHandle("surface"))?;
        s.release_if_current();
        Ok(())
    })
}

/// The size of each eye's buffers.
///
/// @param surface a live surface. @param width_out, height_out must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_HANDLE. Thread-safe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_get_size(
    surface: *const gls_surface,
    width_out: *mut u32,
    height_out: *mut u32,
) -> gls_result {
    ffi_boundary!("gls_surface_get_size", {
        let s = surface_arg(surface)?;
        let w_out = arg_out(width_out, "width_out")?;
        let h_out = arg_out(height_out, "height_out")?;
        let (w, h) = s.size();
        // SAFETY: checked non-NULL.
        unsafe {
            write_out(w_out, w);
            write_out(h_out, h);
        }
        Ok(())
    })
}

/// Makes a surface's context current on the calling thread, with its
/// emulated default framebuffer bound (as glXMakeCurrent binds a window).
/// The first time, the viewport and scissor box are set to the surface
/// size. NULL releases the current surface.
///
/// @return GLS_OK; GLS_ERROR_INVALID_HANDLE; GLS_ERROR_INVALID_OPERATION if
/// the surface is current on another thread. Per thread, as in GL.
#[unsafe(no_mangle)]
pub extern "C" fn gls_make_current(surface: *mut gls_surface) -> gls_result {
    ffi_boundary!("gls_make_current", {
        if surface.is_null() {
            return surface::make_current(None);
        }
        let s = surface_arg(surface)?;
        surface::make_current(Some(&s))
    })
}

/// glDrawBuffer for the emulated default framebuffer of the current surface.
///
/// GL_BACK (both back buffers on stereo), GL_FRONT, GL_LEFT, GL_RIGHT,
/// GL_FRONT_LEFT, GL_FRONT_RIGHT, GL_BACK_LEFT, GL_BACK_RIGHT,
/// GL_FRONT_AND_BACK and GL_NONE select what GL 4.5 says. Fixed-function
/// colour, gl_FragColor, glClear and glBlitFramebuffer reach every selected
/// buffer. A shader's user-defined output 0 (`layout(location = 0) out
/// vec4`) reaches every selected buffer when its program was linked with
/// gls_link_program() in place of glLinkProgram (which writes copies of it
/// to locations 5…7, where the emulated framebuffer keeps the other
/// selected buffers); linked with glLinkProgram it reaches only the first
/// selected buffer (the left eye's when both are selected), and the others
/// get undefined values. glClearBuffer(GL_COLOR, 0, …) clears only the
/// first selected buffer: clear with glClear, or select each buffer in
/// turn. (Programs under glstereo-run or rebuilt with
/// <glstereo/compat.h> get all of this from their usual GL calls.)
///
/// @param gl_buffer a GL buffer name.
/// @return GLS_OK; GLS_ERROR_NO_CURRENT_SURFACE; GLS_ERROR_INVALID_ENUM (not
/// a buffer name); GLS_ERROR_INVALID_OPERATION (a buffer the configuration
/// lacks: right buffers on mono, back buffers on single-buffered; or an
/// FBO attachment). After an error nothing changed; gls_get_error() reports
/// the matching GL error. Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_draw_buffer(gl_buffer: u32) -> gls_result {
    ffi_boundary!("gls_draw_buffer", {
        surface::require_current()?.draw_buffer(gl_buffer)
    })
}

/// glDrawBuffers for the emulated default framebuffer: output i goes to
/// `bufs[i]` (GL_NONE, GL_FRONT_LEFT, GL_FRONT_RIGHT, GL_BACK_LEFT,
/// GL_BACK_RIGHT; GL_BACK alone).
///
/// @param n 0…GL_MAX_DRAW_BUFFERS (at most 8). @param bufs n values; must not be NULL when n > 0.
/// @return GLS_OK; GLS_ERROR_NO_CURRENT_SURFACE; GLS_ERROR_NULL_POINTER;
/// GLS_ERROR_INVALID_VALUE (n); GLS_ERROR_INVALID_ENUM (GL_FRONT, GL_LEFT,
/// GL_RIGHT, GL_FRONT_AND_BACK, or not a buffer); GLS_ERROR_INVALID_OPERATION
/// (a buffer named twice or one the configuration lacks). Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_draw_buffers(n: i32, bufs: *const u32) -> gls_result {
    ffi_boundary!("gls_draw_buffers", {
        let s = surface::require_current()?;
        if n < 0 {
            return Err(Error::invalid_value(format!("n must be >= 0, got {n}")));
        }
        if n > 0 && bufs.is_null() {
            return Err(Error::NullPointer("bufs"));
        }
        const MAX: usize = crate::stereo::emulated::MAX_DRAW_BUFFERS;
        if n as usize > MAX {
            // More than any driver takes. Not a list of n entries (n may be
            // 2^31 − 1: allocating it aborted the process under a memory
            // limit): any longer list records the same GL_INVALID_VALUE.
            let _ = s.draw_buffers(&[crate::gl::enums::GL_NONE; MAX + 1]);
            return Err(Error::invalid_value(format!(
                "glDrawBuffers: n = {n} exceeds GL_MAX_DRAW_BUFFERS (at most {MAX}) (GL_INVALID_VALUE)"
            )));
        }
        let list = if n == 0 {
            &[][..]
        } else {
            // SAFETY: non-NULL and holds n values (contract).
            unsafe { std::slice::from_raw_parts(bufs, n as usize) }
        };
        s.draw_buffers(list)
    })
}

/// glReadBuffer for the emulated default framebuffer: GL_FRONT, GL_LEFT and
/// GL_FRONT_AND_BACK read front-left, GL_BACK back-left, GL_RIGHT front-right.
///
/// @return as gls_draw_buffer(). Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_read_buffer(gl_buffer: u32) -> gls_result {
    ffi_boundary!("gls_read_buffer", {
        surface::require_current()?.read_buffer(gl_buffer)
    })
}

/// glLinkProgram for a program that draws into the current surface's
/// emulated default framebuffer: links `program`, then, when its fragment
/// shader writes a user-defined output at location 0, links it again with
/// that output also written to outputs `gls_stereo_copy5`…`7` (locations
/// 5…7; for a shader writing `gl_FragData[0]`, to `gl_FragData[5…7]`), so
/// that output 0 reaches every buffer gls_draw_buffer() selects (GL_BACK:
/// both eyes) in one pass: the shader runs once per fragment, so atomic
/// counters, image stores and queries count as on a real stereo
/// framebuffer. The program keeps its shaders attached; its introspection
/// shows the three extra outputs. Use it in place of glLinkProgram; check
/// GL_LINK_STATUS as usual.
///
/// @param program a program object of the current surface's context.
/// @return GLS_OK (also when the link failed or the program needs no
/// copies: no fragment shader, gl_FragColor); GLS_ERROR_NO_CURRENT_SURFACE;
/// GLS_ERROR_INVALID_VALUE / GLS_ERROR_INVALID_OPERATION when glLinkProgram
/// itself raises that GL error (not a program name; gls_get_error() reports
/// it); GLS_ERROR_INVALID_OPERATION, with the reason in
/// gls_last_error_message(), when the copies cannot be added (no GLSL
/// source, as with SPIR-V; several fragment shaders; outputs at locations
/// 5…7 or dual-source outputs; `gl_FragData` elements other than 0 written;
/// a driver before GL 4.3): the program is then linked as glLinkProgram
/// links it, and output 0 reaches only the first selected buffer. Thread:
/// the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_link_program(program: u32) -> gls_result {
    ffi_boundary!("gls_link_program", {
        surface::require_current()?.link_program(program)
    })
}

/// glGetError for the current surface: an error the emulation raised
/// (e.g. GL_INVALID_ENUM from gls_draw_buffer) first, then the driver's.
///
/// @return a GL error code; GL_NO_ERROR (0) when there is no current
/// surface (with a message for gls_last_error_message()). Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_get_error() -> u32 {
    ffi_boundary!("gls_get_error", 0 => { surface::require_current()?.take_gl_error() })
}

/// glGetIntegerv with the emulated default framebuffer's values: GL_STEREO
/// and GL_DOUBLEBUFFER of the configuration, GL_DRAW_BUFFER,
/// GL_DRAW_BUFFERi and GL_READ_BUFFER as set, and 0 for
/// GL_DRAW/READ_FRAMEBUFFER_BINDING while the emulated framebuffer is bound;
/// the NV_3dvision_settings state (GL_STEREO_PROJECTION_NV, the separation,
/// convergence and cutoff rounded to the nearest integer, GL_3DVISION_STEREO_NV).
/// Every other pname goes to glGetIntegerv.
///
/// @param pname a GL state name. @param data receives the value(s); must not
/// be NULL and must hold as many values as glGetIntegerv writes for pname.
/// @return GLS_OK, GLS_ERROR_NO_CURRENT_SURFACE or GLS_ERROR_NULL_POINTER.
/// Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_get_integerv(pname: u32, data: *mut i32) -> gls_result {
    ffi_boundary!("gls_get_integerv", {
        let s = surface::require_current()?;
        let out = arg_out(data, "data")?;
        if let Some(v) = s.with_nv3dvision(|nv| Ok(nv.query(pname)))? {
            // SAFETY: checked non-NULL.
            unsafe { write_out(out, v.as_integer()) };
            return Ok(());
        }
        match s.emulated_integer(pname)? {
            // SAFETY: checked non-NULL.
            Some(v) => unsafe { write_out(out, v) },
            // SAFETY: the surface's context is current; `data` is as large as GL needs (contract).
            None => unsafe { s.gl().GetIntegerv(pname, out) },
        }
        Ok(())
    })
}

/// glBindFramebuffer where framebuffer 0 means the emulated default
/// framebuffer (a program's own framebuffer objects bind as usual).
///
/// @return GLS_OK or GLS_ERROR_NO_CURRENT_SURFACE. Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_bind_framebuffer(target: u32, framebuffer: u32) -> gls_result {
    ffi_boundary!("gls_bind_framebuffer", {
        surface::require_current()?.bind_framebuffer(target, framebuffer)
    })
}

/// The address of a GL function of the current surface's backend, for
/// programs that load GL themselves (as with glXGetProcAddress).
///
/// @param name a GL function name; must not be NULL.
/// @return the address, or NULL with a message when there is no current
/// surface. Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_get_proc_address(name: *const c_char) -> *mut c_void {
    ffi_boundary!("gls_get_proc_address", std::ptr::null_mut() => {
        // SAFETY: NUL-terminated (contract).
        let name = unsafe { arg_str(name, "name")? };
        let s = surface::require_current()?;
        let c = std::ffi::CString::new(name).map_err(|_| Error::invalid_value("name contains NUL"))?;
        Ok(s.display().platform().get_proc_address(&c) as *mut c_void)
    })
}

/// Loads one eye's HP projection (as gls_stereo_eye_matrix()) into
/// GL_PROJECTION of the current context; the matrix mode is left unchanged.
///
/// @return as gls_stereo_eye_matrix(), plus GLS_ERROR_NO_CURRENT_SURFACE.
/// Thread: the surface's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_apply_stereo_eye(
    mono: *const gls_frustum,
    adj: *const gls_stereo_adjust,
    eye: u32,
) -> gls_result {
    ffi_boundary!("gls_apply_stereo_eye", {
        // SAFETY: NULL-checked; validity is the caller's contract.
        let (mono, adj) = unsafe { (arg_ref(mono, "mono")?, arg_ref(adj, "adj")?) };
        let p = hp_eye(&mono.into(), &adj.into(), Eye::try_from(eye)?)?;
        let s = surface::require_current()?;
        s.load_projection(&p.matrix().to_cols_array())
    })
}

/// Presents a frame: for double-buffered configurations each eye's back
/// buffer becomes its front buffer (one swap for both eyes); the contents
/// of the new back buffers are undefined, as after a real swap.
///
/// @param surface a live surface, current on the calling thread or on none.
/// @return GLS_OK; GLS_ERROR_INVALID_HANDLE; GLS_ERROR_INVALID_OPERATION if
/// it is current on another thread. Thread: the surface's.
#[unsafe(no_mangle)]
pub extern "C" fn gls_swap_buffers(surface: *mut gls_surface) -> gls_result {
    ffi_boundary!("gls_swap_buffers", { surface_arg(surface)?.swap_buffers() })
}

/// Reads one colour buffer as RGBA8, rows top first (the reverse of
/// glReadPixels), width × height × 4 bytes. Buffer names follow
/// glReadBuffer: GL_FRONT_LEFT, GL_BACK_RIGHT, GL_FRONT (= front-left),
/// GL_RIGHT (= front-right), …
///
/// The program's rendering is finished first when the surface is current on
/// the calling thread; from another thread, synchronise with it yourself.
///
/// @param surface a live surface. @param gl_buffer a buffer name.
/// @param rgba receives the pixels; must not be NULL.
/// @param len size of rgba in bytes; at least width × height × 4.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_ENUM; GLS_ERROR_INVALID_OPERATION (a buffer the
/// configuration lacks, or GL_NONE); GLS_ERROR_INVALID_VALUE (len too small);
/// GLS_ERROR_OUT_OF_MEMORY (no memory for the read-back).
/// Nothing is written on error. Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_read_pixels(
    surface: *mut gls_surface,
    gl_buffer: u32,
    rgba: *mut u8,
    len: usize,
) -> gls_result {
    ffi_boundary!("gls_surface_read_pixels", {
        let s = surface_arg(surface)?;
        let out = arg_out(rgba, "rgba")?;
        let (w, h) = s.size();
        let need = w as usize * h as usize * 4;
        if len < need {
            return Err(Error::invalid_value(format!(
                "len is {len} bytes; a {w}x{h} RGBA8 image needs {need}"
            )));
        }
        let img = s.read_pixels(gl_buffer)?;
        // SAFETY: `out` holds at least `need` bytes (checked above).
        unsafe { std::ptr::copy_nonoverlapping(img.pixels().as_ptr(), out, need) };
        Ok(())
    })
}

/// Writes what a viewer sees now to a PNG file: GLS_IMAGE_LEFT or
/// GLS_IMAGE_RIGHT (an eye's front buffer), or GLS_IMAGE_COMPOSITE (both
/// eyes in the surface's output mode). Rows top first, 8-bit RGBA. The file
/// appears complete or not at all (written to a temporary name, then renamed).
///
/// @param surface a live surface. @param image GLS_IMAGE_LEFT, GLS_IMAGE_RIGHT or GLS_IMAGE_COMPOSITE.
/// @param path a file path (UTF-8); must not be NULL.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_ENUM (image); GLS_ERROR_INVALID_VALUE (a path that is
/// not UTF-8 or names no file, e.g. ""); GLS_ERROR_OUT_OF_MEMORY (no memory
/// for the image); GLS_ERROR_IO (the message names the path and the reason;
/// no file and no temporary file is left). Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_save_png(
    surface: *mut gls_surface,
    image: u32,
    path: *const c_char,
) -> gls_result {
    ffi_boundary!("gls_surface_save_png", {
        let s = surface_arg(surface)?;
        let which = image_arg(image)?;
        // SAFETY: NUL-terminated (contract).
        let path = unsafe { arg_str(path, "path")? };
        s.save_png(which, std::path::Path::new(path))
    })
}

/// Input framing: the left and right front buffers (GLX_STEREO, HP windowed
/// OpenGL, SGI square-pixel stereo). Default.
pub const GLS_INPUT_QUAD_BUFFER: u32 = 0;
/// Input framing: HP Starbase sync-doubling (seed 000 §9). One mono frame:
/// left eye in the upper half, right eye in the lower half, each drawn
/// squashed 1:2 and stretched ×2 vertically as the display shows it.
pub const GLS_INPUT_SYNC_DOUBLED: u32 = 1;
/// Input framing: SGI STR_RECT (seed 002). For 1024 rows: left eye in GL
/// rows 532–1023, right eye in rows 0–491, 40 rows lost; each stretched to
/// the full height. Other heights scale proportionally.
pub const GLS_INPUT_STR_RECT: u32 = 2;
/// Input framing: Xinerama "passive" stereo (seed 001). A double-width mono
/// frame: left eye in the left half, right eye in the right half.
pub const GLS_INPUT_SIDE_BY_SIDE: u32 = 3;
/// Input framing: SGI STR_TOP (seed 002). For 1024 rows: both eyes from GL
/// rows 532–1023, stretched to the full height; the left eye from the left
/// buffer, the right eye from the right buffer (the left one on mono).
pub const GLS_INPUT_STR_TOP: u32 = 4;
/// Input framing: SGI STR_BOT, as GLS_INPUT_STR_TOP with GL rows 0–491.
pub const GLS_INPUT_STR_BOT: u32 = 5;

/// Sets the output format a surface's composite (its window, and
/// GLS_IMAGE_COMPOSITE captures) is made in. A window is resized to show the
/// new composite pixel for pixel (e.g. twice as wide for side-by-side).
///
/// GLS_OUTPUT_QUAD shows the eyes in the driver's own quad buffer on a
/// natively stereo configuration; on any other it falls back to
/// GLS_OUTPUT_ANAGLYPH_RED_CYAN (gls_surface_get_output() still reports QUAD).
///
/// Default: GLSTEREO_MODE when set at surface creation, else
/// GLS_OUTPUT_ANAGLYPH_RED_CYAN.
///
/// @param surface a live surface. @param output a GLS_OUTPUT_* value.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER, GLS_ERROR_INVALID_HANDLE or
/// GLS_ERROR_INVALID_ENUM (nothing changes). Any thread.
#[unsafe(no_mangle)]
pub extern "C" fn gls_surface_set_output(surface: *mut gls_surface, output: u32) -> gls_result {
    ffi_boundary!("gls_surface_set_output", {
        let s = surface_arg(surface)?;
        s.set_output(crate::output::OutputMode::try_from(output)?)
    })
}

/// The output format as set (GLS_OUTPUT_QUAD included, even where it falls back).
///
/// @param surface a live surface. @param output_out must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_HANDLE. Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_get_output(
    surface: *const gls_surface,
    output_out: *mut u32,
) -> gls_result {
    ffi_boundary!("gls_surface_get_output", {
        let s = surface_arg(surface)?;
        let out = arg_out(output_out, "output_out")?;
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, u32::from(s.output())) };
        Ok(())
    })
}

/// Exchanges the eyes in every output format (for glasses worn the other
/// way round, or a peer's opposite convention).
///
/// Default: GLSTEREO_SWAP_EYES at surface creation, else false.
///
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_HANDLE. Any thread.
#[unsafe(no_mangle)]
pub extern "C" fn gls_surface_set_swap_eyes(
    surface: *mut gls_surface,
    swap_eyes: bool,
) -> gls_result {
    ffi_boundary!("gls_surface_set_swap_eyes", {
        let s = surface_arg(surface)?;
        s.set_options(crate::output::OutputOptions {
            swap_eyes,
            ..s.options()
        })
    })
}

/// Crosstalk ("ghosting") reduction: subtracts this fraction of the other
/// eye from each eye before composing, in every format that shows both eyes.
///
/// Default: GLSTEREO_CROSSTALK at surface creation, else 0.
///
/// @param crosstalk 0…1.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER, GLS_ERROR_INVALID_HANDLE or
/// GLS_ERROR_INVALID_VALUE (outside 0…1 or NaN; nothing changes). Any thread.
#[unsafe(no_mangle)]
pub extern "C" fn gls_surface_set_crosstalk(
    surface: *mut gls_surface,
    crosstalk: f32,
) -> gls_result {
    ffi_boundary!("gls_surface_set_crosstalk", {
        let s = surface_arg(surface)?;
        s.set_options(crate::output::OutputOptions {
            crosstalk,
            ..s.options()
        })
    })
}

/// Anaglyph colour saturation, as VTK has it: each eye is blended toward
/// its luminance before the anaglyph filter (1 = full colour, 0 = grey).
/// Lower values reduce retinal rivalry on saturated scenes.
///
/// Default: GLSTEREO_SATURATION at surface creation, else 1.
///
/// @param saturation 0…1.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER, GLS_ERROR_INVALID_HANDLE or
/// GLS_ERROR_INVALID_VALUE (outside 0…1 or NaN; nothing changes). Any thread.
#[unsafe(no_mangle)]
pub extern "C" fn gls_surface_set_saturation(
    surface: *mut gls_surface,
    saturation: f32,
) -> gls_result {
    ffi_boundary!("gls_surface_set_saturation", {
        let s = surface_arg(surface)?;
        s.set_options(crate::output::OutputOptions {
            saturation,
            ..s.options()
        })
    })
}

/// Sets how the program delivers its eyes (the input framing): the quad
/// buffer (default), one sync-doubled frame (HP Starbase), SGI STR_RECT,
/// a double-width side-by-side frame (Xinerama), or SGI STR_TOP / STR_BOT.
/// The eyes taken apart flow to every output format and capture.
///
/// @param surface a live surface. @param input a GLS_INPUT_* value.
/// @return GLS_OK; GLS_ERROR_NULL_POINTER; GLS_ERROR_INVALID_HANDLE;
/// GLS_ERROR_INVALID_ENUM; GLS_ERROR_INVALID_VALUE when the surface is too small to hold two eyes
/// that way (nothing changes). Any thread.
#[unsafe(no_mangle)]
pub extern "C" fn gls_surface_set_input(surface: *mut gls_surface, input: u32) -> gls_result {
    ffi_boundary!("gls_surface_set_input", {
        let s = surface_arg(surface)?;
        let framing = match input {
            GLS_INPUT_QUAD_BUFFER => InputFraming::QuadBuffer,
            GLS_INPUT_SYNC_DOUBLED => InputFraming::SyncDoubled,
            GLS_INPUT_STR_RECT => InputFraming::StrRect,
            GLS_INPUT_SIDE_BY_SIDE => InputFraming::SideBySide,
            GLS_INPUT_STR_TOP => InputFraming::StrTop,
            GLS_INPUT_STR_BOT => InputFraming::StrBot,
            v => {
                return Err(Error::invalid_enum(
                    "input",
                    v,
                    "use GLS_INPUT_QUAD_BUFFER, GLS_INPUT_SYNC_DOUBLED, GLS_INPUT_STR_RECT, GLS_INPUT_SIDE_BY_SIDE, GLS_INPUT_STR_TOP or GLS_INPUT_STR_BOT",
                ));
            }
        };
        s.set_framing(framing)
    })
}

/// No event.
pub const GLS_EVENT_NONE: u32 = 0;
/// A key was pressed: `key` holds its X keysym (for Latin-1 keys, the
/// character code, e.g. '+' = 0x2b).
pub const GLS_EVENT_KEY: u32 = 1;
/// The user asked to close the window.
pub const GLS_EVENT_CLOSE: u32 = 2;
/// The window was resized: `width` × `height` is the new size of each eye,
/// in effect from the next frame (after the next gls_swap_buffers()).
pub const GLS_EVENT_RESIZE: u32 = 3;

/// A window event, filled by gls_surface_poll_event().
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct gls_event {
    /// GLS_EVENT_NONE, GLS_EVENT_KEY, GLS_EVENT_CLOSE or GLS_EVENT_RESIZE.
    pub kind: u32,
    /// The keysym of a GLS_EVENT_KEY; 0 otherwise.
    pub key: u32,
    /// The new eye width of a GLS_EVENT_RESIZE; 0 otherwise.
    pub width: u32,
    /// The new eye height of a GLS_EVENT_RESIZE; 0 otherwise.
    pub height: u32,
}

/// Takes the next event of a surface's window without waiting. Headless
/// surfaces have none.
///
/// @param surface a live surface. @param event_out receives the event
/// (type GLS_EVENT_NONE when there is none); must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_HANDLE. Any
/// thread (events are read from the window's connection without blocking).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_poll_event(
    surface: *mut gls_surface,
    event_out: *mut gls_event,
) -> gls_result {
    ffi_boundary!("gls_surface_poll_event", {
        let s = surface_arg(surface)?;
        let out = arg_out(event_out, "event_out")?;
        let ev = match s.next_event() {
            None => gls_event::default(),
            Some(WindowEvent::Key(k)) => gls_event {
                kind: GLS_EVENT_KEY,
                key: k,
                ..Default::default()
            },
            Some(WindowEvent::CloseRequested) => gls_event {
                kind: GLS_EVENT_CLOSE,
                ..Default::default()
            },
            Some(WindowEvent::Resized(w, h)) => gls_event {
                kind: GLS_EVENT_RESIZE,
                width: w,
                height: h,
                ..Default::default()
            },
        };
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, ev) };
        Ok(())
    })
}

/// Whether the user asked to close the surface's window (the window
/// manager's close button); the window stays until the surface is destroyed.
///
/// @return true or false; false for a headless surface, NULL or a handle
/// that is not live (with a message). Any thread.
#[unsafe(no_mangle)]
pub extern "C" fn gls_surface_should_close(surface: *mut gls_surface) -> bool {
    ffi_boundary!("gls_surface_should_close", false => { Ok(surface_arg(surface)?.close_requested()) })
}

/// Sets the title of the surface's window (programs show their stereo
/// settings there, as OGLPlane does). No effect headless.
///
/// @param surface a live surface. @param title UTF-8; must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER, GLS_ERROR_INVALID_HANDLE or
/// GLS_ERROR_DISPLAY_LOST. Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_set_title(
    surface: *mut gls_surface,
    title: *const c_char,
) -> gls_result {
    ffi_boundary!("gls_surface_set_title", {
        let s = surface_arg(surface)?;
        // SAFETY: NUL-terminated (contract).
        let title = unsafe { arg_str(title, "title")? };
        s.set_title(title)
    })
}

/// Native handles (advanced): the backend objects behind a surface, for
/// programs that mix glstereo with their own use of GLX, EGL or OSMesa.
/// Fields a backend does not have are NULL / 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct gls_native_handles {
    /// GLS_BACKEND_GLX, GLS_BACKEND_EGL or GLS_BACKEND_OSMESA.
    pub backend: u32,
    /// GLX: the Xlib `Display*`; EGL: the `EGLDisplay`.
    pub display: *mut c_void,
    /// GLX: the X `Window` (XID) the surface presents into.
    pub window: u64,
    /// The program's context: `GLXContext`, `EGLContext` or `OSMesaContext`.
    pub context: *mut c_void,
    /// OSMesa: the buffer bound with OSMesaMakeCurrent (rendering goes to
    /// glstereo's framebuffer, not there).
    pub osmesa_buffer: *mut c_void,
}

/// Native handles (advanced, see gls_native_handles). The objects stay
/// owned by glstereo: do not destroy them; they live as long as the surface.
/// Making the context current yourself bypasses glstereo's bookkeeping:
/// use gls_make_current().
///
/// @param surface a live surface. @param handles_out must not be NULL.
/// @return GLS_OK, GLS_ERROR_NULL_POINTER or GLS_ERROR_INVALID_HANDLE. Any thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gls_surface_get_native_handles(
    surface: *mut gls_surface,
    handles_out: *mut gls_native_handles,
) -> gls_result {
    ffi_boundary!("gls_surface_get_native_handles", {
        let s = surface_arg(surface)?;
        let out = arg_out(handles_out, "handles_out")?;
        let null = std::ptr::null_mut();
        let h = match s.native_handles() {
            NativeHandles::Glx {
                display,
                window,
                context,
            } => gls_native_handles {
                backend: super::display::GLS_BACKEND_GLX,
                display,
                window,
                context,
                osmesa_buffer: null,
            },
            NativeHandles::Egl { display, context } => gls_native_handles {
                backend: super::display::GLS_BACKEND_EGL,
                display,
                window: 0,
                context,
                osmesa_buffer: null,
            },
            NativeHandles::OsMesa { context, buffer } => gls_native_handles {
                backend: super::display::GLS_BACKEND_OSMESA,
                display: null,
                window: 0,
                context,
                osmesa_buffer: buffer,
            },
        };
        // SAFETY: checked non-NULL.
        unsafe { write_out(out, h) };
        Ok(())
    })
}

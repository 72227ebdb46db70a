//! The GLX entry points, as the layer answers them: stereo requests get a
//! (mono) visual or configuration of the server marked as stereo, contexts
//! made from those are stereo contexts ([`StereoContext`]), making one
//! current binds its emulated framebuffer, and glXSwapBuffers presents it.
//! Everything else goes to the real GLX unchanged.
//!
//! With GLSTEREO_MODE=quad on a server that has real stereo visuals, stereo
//! requests get those and the layer does nothing (the driver's own quad
//! buffer).
//!
//! Stereo is granted only where the layer can deliver it: its emulated
//! framebuffer is a framebuffer object (GL 3.0) in the program's context,
//! and indirect GLX (`LIBGL_ALWAYS_INDIRECT=1`, as some `ssh -X` set-ups
//! use) offers GL 1.4. So on a display where GLX does not render directly
//! (it asks once per display) stereo requests get the driver's own answer
//! (no stereo visual on Mesa: the program's mono fallback runs), and a
//! stereo context the program asks to be indirect is made direct.

use std::ffi::{c_int, c_ulong};

use x11_dl::glx::{GLXContext, GLXFBConfig};
use x11_dl::xlib::{Display, XExtCodes, XVisualInfo};

use super::attribs::{
    read_pair_list, read_visual_list, strip_fbconfig_stereo, strip_visual_stereo,
};
use super::context::{StereoContext, current, made_current};
use super::real::{Real, loaded};
use super::registry;
use super::settings;
use crate::backend::glx::trap_x_errors;
use crate::backend::xshm::Connection;
use crate::config::glx::{
    GLX_ALPHA_SIZE, GLX_DEPTH_SIZE, GLX_DOUBLEBUFFER, GLX_STENCIL_SIZE, GLX_STEREO,
};
use crate::error::{Error, Result};
use crate::stereo::buffers::FramebufferShape;
use crate::stereo::emulated::BufferFormats;

const GLX_DRAWABLE_TYPE: c_int = 0x8010;
const GLX_RENDER_TYPE: c_int = 0x8011;
const GLX_WINDOW_BIT: c_int = 0x1;
const GLX_RGBA_BIT: c_int = 0x1;
const GLX_RGBA_TYPE: c_int = 0x8014;
/// glXCreateContextAttribsARB's list for the layer's own contexts: the
/// compatibility profile, the driver's highest version.
const COMPATIBILITY: [c_int; 3] = [
    0x9126, // GLX_CONTEXT_PROFILE_MASK_ARB
    0x2,    // GLX_CONTEXT_COMPATIBILITY_PROFILE_BIT_ARB
    0,
];
/// glXGetConfig / glXGetFBConfigAttrib success.
const SUCCESS: c_int = 0;
/// glXGetConfig / glXGetFBConfigAttrib: a bad argument (libglvnd's answer
/// for a NULL display, visual or value pointer), GLX_BAD_ATTRIBUTE, and
/// GLX_BAD_VISUAL.
pub const GLX_BAD_VALUE: c_int = 6;

/// The Display* every GLX function needs: NULL is refused (libGL
/// dereferences it in every function but glXGetConfig, glXMakeCurrent,
/// glXSwapBuffers and glXDestroyWindow).
fn display(dpy: *mut Display) -> Result<*mut Display> {
    if dpy.is_null() {
        Err(Error::NullPointer("dpy (the Display*)"))
    } else {
        Ok(dpy)
    }
}

/// A pointer argument GLX requires: NULL is refused.
fn required<T>(p: *const T, what: &'static str) -> Result<()> {
    if p.is_null() {
        Err(Error::NullPointer(what))
    } else {
        Ok(())
    }
}

/// Makes XCloseDisplay of `dpy` forget what the layer recorded for it
/// ([`registry::Registry::forget_display`]): called before the first thing
/// is recorded for a display. The hook is an Xlib extension's close_display
/// procedure (as libGL's own GLX uses), run by XCloseDisplay while the
/// connection is still open.
pub(super) fn watch(r: &Real, dpy: *mut Display) {
    if !registry::with(|reg| reg.watch(dpy as usize)) {
        return;
    }
    // SAFETY: a valid display (checked non-NULL by callers, and libGL just
    // answered for it); XAddExtension returns codes owned by the display.
    unsafe {
        let codes = (r.xlib.XAddExtension)(dpy);
        if codes.is_null() {
            super::warn(
                "XAddExtension failed: what the layer records for a display is kept after XCloseDisplay",
            );
            return;
        }
        (r.xlib.XESetCloseDisplay)(dpy, (*codes).extension, Some(display_closed));
    }
}

/// XCloseDisplay's hook ([`watch`]). A callback from Xlib: no panic may
/// leave it.
unsafe extern "C" fn display_closed(dpy: *mut Display, _codes: *mut XExtCodes) -> c_int {
    let _ = std::panic::catch_unwind(|| {
        let gone = registry::with(|reg| reg.forget_display(dpy as usize));
        for sc in &gone.contexts {
            sc.mark_closed();
            // Destroyed with the connection, and the layer's with it.
            if let Ok(r) = super::real::real() {
                r.gl.context_left(sc.ours());
            }
            super::context::context_destroyed(sc.context());
        }
        // A context of the display current on this thread (the program
        // closes the display without releasing it) is forgotten too: the
        // layer must not touch the closed connection afterwards.
        if current().is_some_and(|c| c.sc.display() == dpy as usize) {
            super::context::forget_current();
        }
        drop(gone);
        // EGL displays on this connection: their contexts' MIT-SHM images
        // are freed while it is open, and none is made on it again.
        for egl in super::egl::x_display_closed(dpy as usize) {
            for sc in registry::with(|reg| reg.contexts_of(egl)) {
                sc.release_images_on(Some(dpy as usize), Connection::Closing);
            }
        }
    });
    0
}

/// A share list the program already destroyed is refused (libGL reads the
/// freed context and crashes; GLX says GLXBadContext).
fn live_share(share: GLXContext, what: &'static str) -> Result<()> {
    if !share.is_null() && registry::with(|reg| reg.is_dead(share as usize)) {
        Err(Error::InvalidHandle(what))
    } else {
        Ok(())
    }
}

/// Whether stereo can be emulated for contexts on `dpy`: whether GLX
/// renders directly there (the emulation needs GL 3.0 framebuffer objects;
/// an indirect context has GL 1.4). Not where `LIBGL_ALWAYS_INDIRECT` makes
/// every context indirect; else asked once per display, when `probe` is
/// given: it makes a context (direct requested) that glXIsDirect answers
/// for, destroyed at once, X errors trapped. Without a probe (a listing
/// of every configuration, which mono programs make too) or when the probe
/// makes no context (the program's own would fail the same way), nothing
/// is decided. When stereo cannot be emulated, stderr says so once.
fn emulation_possible(r: &Real, dpy: *mut Display, probe: Option<&dyn Fn() -> GLXContext>) -> bool {
    let known = if indirect_forced() {
        Some(false)
    } else {
        registry::with(|reg| reg.renders_directly(dpy as usize))
    };
    let direct = match (known, probe) {
        (Some(known), _) => known,
        (None, None) => return true,
        (None, Some(probe)) => {
            let (direct, err) = trap_x_errors(&r.xlib, dpy, || {
                let ctx = probe();
                // SAFETY: a context just made on this display, destroyed once.
                (!ctx.is_null()).then(|| unsafe {
                    let direct = (r.glx.glXIsDirect)(dpy, ctx) != 0;
                    (r.glx.glXDestroyContext)(dpy, ctx);
                    direct
                })
            });
            let Some(direct) = direct.filter(|_| err == 0) else {
                return true;
            };
            watch(r, dpy);
            registry::with(|reg| reg.set_renders_directly(dpy as usize, direct));
            direct
        }
    };
    if !direct {
        warn_indirect();
    }
    direct
}

fn warn_indirect() {
    super::warn(
        "GL rendering on this X display is indirect (LIBGL_ALWAYS_INDIRECT, or a server this \
         client cannot render to directly), which has no framebuffer objects: stereo cannot be \
         emulated, so stereo requests get the driver's own answer (no stereo visual) and the \
         program's mono fallback runs; unset LIBGL_ALWAYS_INDIRECT for stereo",
    );
}

/// Whether the program's new context `ctx` of a stereo visual or
/// configuration (created direct) renders directly. One that does not
/// (the display could not be asked before stereo was promised: a
/// configuration picked from glXGetFBConfigs' whole list) runs in mono,
/// stderr says why, and the display is known from then on.
fn direct_context(r: &Real, dpy: *mut Display, ctx: GLXContext) -> bool {
    // SAFETY: a context the real GLX just made on this display.
    if unsafe { (r.glx.glXIsDirect)(dpy, ctx) } != 0 {
        return true;
    }
    watch(r, dpy);
    registry::with(|reg| reg.set_renders_directly(dpy as usize, false));
    warn_indirect();
    false
}

/// Whether `LIBGL_ALWAYS_INDIRECT` makes every GLX context indirect, as
/// libGL reads it (1, true, y or yes, in any case).
fn indirect_forced() -> bool {
    std::env::var("LIBGL_ALWAYS_INDIRECT").is_ok_and(|v| {
        let v = v.trim();
        ["1", "true", "y", "yes"]
            .iter()
            .any(|t| v.eq_ignore_ascii_case(t))
    })
}

/// glXChooseVisual. Refused: a NULL display or attribute list.
///
/// # Safety
/// As glXChooseVisual: a valid display and a `None`-terminated list.
pub unsafe fn choose_visual(
    dpy: *mut Display,
    screen: c_int,
    attribs: *mut c_int,
) -> Result<*mut XVisualInfo> {
    let r = loaded()?;
    display(dpy)?;
    required(attribs, "attribList")?;
    // SAFETY: the caller's list, read by its structure.
    let list = unsafe { read_visual_list(attribs) };
    let (mut stripped, stereo) = strip_visual_stereo(&list);
    if stereo && settings::native_allowed() {
        // SAFETY: forwarded call.
        let v = unsafe { (r.glx.glXChooseVisual)(dpy, screen, attribs) };
        if !v.is_null() {
            tell_native();
            return Ok(v);
        }
    }
    let mut v = if stereo {
        // SAFETY: a None-terminated list.
        unsafe { (r.glx.glXChooseVisual)(dpy, screen, stripped.as_mut_ptr()) }
    } else {
        // SAFETY: forwarded call.
        unsafe { (r.glx.glXChooseVisual)(dpy, screen, attribs) }
    };
    // SAFETY: a visual the real GLX returned, for a probe context.
    let probe = || unsafe { (r.glx.glXCreateContext)(dpy, v, std::ptr::null_mut(), 1) };
    let stereo = if stereo && !v.is_null() && !emulation_possible(r, dpy, Some(&probe)) {
        // The driver's own answer to the stereo request.
        // SAFETY: the visual list is ours to free; then a forwarded call.
        unsafe {
            (r.xlib.XFree)(v.cast());
            v = (r.glx.glXChooseVisual)(dpy, screen, attribs);
        }
        false
    } else {
        stereo
    };
    if !v.is_null() {
        // SAFETY: a visual the real GLX returned.
        let id = unsafe { (*v).visualid };
        if stereo {
            watch(r, dpy);
        }
        registry::with(|reg| reg.mark_visual(dpy as usize, v as usize, id, stereo));
    }
    Ok(v)
}

/// glXGetConfig. Refused (GLX_BAD_VALUE, as libglvnd answers): a NULL
/// display, visual or value pointer.
///
/// # Safety
/// As glXGetConfig.
pub unsafe fn get_config(
    dpy: *mut Display,
    vis: *mut XVisualInfo,
    attrib: c_int,
    value: *mut c_int,
) -> Result<c_int> {
    let r = loaded()?;
    display(dpy)?;
    required(vis, "vis (the XVisualInfo*)")?;
    required(value, "value")?;
    if attrib == GLX_STEREO {
        // SAFETY: a visual pointer of the program's.
        let id = unsafe { (*vis).visualid };
        if registry::with(|reg| reg.is_stereo_visual(vis as usize, id)) {
            // SAFETY: non-NULL out-pointer.
            unsafe { *value = 1 };
            return Ok(SUCCESS);
        }
    }
    // SAFETY: forwarded call.
    Ok(unsafe { (r.glx.glXGetConfig)(dpy, vis, attrib, value) })
}

/// Which entry point a configuration call came through.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Flavour {
    /// GLX 1.3.
    Glx13,
    /// GLX_SGIX_fbconfig.
    Sgix,
}

/// glXChooseFBConfig / glXChooseFBConfigSGIX. Refused: a NULL display
/// or `nelements` (a NULL attribute list is GLX's "defaults").
///
/// # Safety
/// As glXChooseFBConfig.
pub unsafe fn choose_fbconfig(
    dpy: *mut Display,
    screen: c_int,
    attribs: *const c_int,
    nelements: *mut c_int,
    flavour: Flavour,
) -> Result<*mut GLXFBConfig> {
    let r = loaded()?;
    display(dpy)?;
    required(nelements, "nelements")?;
    let choose = |list: *const c_int| match flavour {
        // SAFETY: forwarded call.
        Flavour::Glx13 => unsafe { (r.glx.glXChooseFBConfig)(dpy, screen, list, nelements) },
        Flavour::Sgix => match r.extra.sgix.choose {
            // SAFETY: forwarded call.
            Some(f) => unsafe { f(dpy, screen, list, nelements) },
            None => std::ptr::null_mut(),
        },
    };
    // SAFETY: the caller's list of pairs.
    let list = unsafe { read_pair_list(attribs) };
    let (stripped, stereo) = strip_fbconfig_stereo(&list);
    if !stereo {
        return Ok(choose(attribs));
    }
    if settings::native_allowed() {
        let native = choose(attribs);
        // SAFETY: nelements was written by the real call when it returned a list.
        if !native.is_null() && unsafe { *nelements } > 0 {
            tell_native();
            return Ok(native);
        }
    }
    let configs = choose(stripped.as_ptr());
    if configs.is_null() {
        return Ok(configs);
    }
    // SAFETY: the real call wrote the count of the list it returned.
    let n = unsafe { *nelements }.max(0) as usize;
    if n > 0 {
        // SAFETY: the list holds n > 0 configurations; a probe context.
        let probe = || unsafe {
            (r.glx.glXCreateNewContext)(dpy, *configs, GLX_RGBA_TYPE, std::ptr::null_mut(), 1)
        };
        if !emulation_possible(r, dpy, Some(&probe)) {
            // The driver's own answer to the stereo request.
            // SAFETY: the list is ours to free; then a forwarded call.
            unsafe { (r.xlib.XFree)(configs.cast()) };
            return Ok(choose(attribs));
        }
    }
    watch(r, dpy);
    registry::with(|reg| {
        for i in 0..n {
            // SAFETY: i < n entries of the list, which the program frees with XFree.
            unsafe {
                let slot = configs.add(i);
                *slot = reg.fake_config(dpy as usize, *slot as usize) as GLXFBConfig;
            }
        }
    });
    Ok(configs)
}

/// glXGetFBConfigs: the server's configurations, followed by a stereo twin
/// of each mono RGBA window configuration (so programs that pick from the
/// whole list, as GLFW does, find stereo ones). The first entries are the
/// real list, in its order — but for the stereo configurations the driver
/// or a layer below offers (VirtualGL has 144), which are left out when
/// the user chose a format ([`settings::native_allowed`]): the program
/// then picks one of the layer's, emulated and shown in that format. No
/// twins where stereo is known not to be possible (`LIBGL_ALWAYS_INDIRECT`,
/// or a display found to render indirectly; no probe context here: mono
/// programs list too).
///
/// Refused: a NULL display or `nelements`.
///
/// # Safety
/// As glXGetFBConfigs.
pub unsafe fn get_fbconfigs(
    dpy: *mut Display,
    screen: c_int,
    nelements: *mut c_int,
) -> Result<*mut GLXFBConfig> {
    let r = loaded()?;
    display(dpy)?;
    required(nelements, "nelements")?;
    // SAFETY: forwarded call.
    let configs = unsafe { (r.glx.glXGetFBConfigs)(dpy, screen, nelements) };
    if configs.is_null() {
        return Ok(configs);
    }
    // SAFETY: the count of the list the real call returned.
    let n = unsafe { *nelements }.max(0) as usize;
    let attr = |c: GLXFBConfig, a: c_int| {
        let mut v = 0;
        // SAFETY: a real configuration of this display.
        unsafe { (r.glx.glXGetFBConfigAttrib)(dpy, c, a, &mut v) };
        v
    };
    // Mono programs list every configuration too: no probe context here.
    if !emulation_possible(r, dpy, None) {
        return Ok(configs);
    }
    // SAFETY: n entries.
    let reals: Vec<GLXFBConfig> = unsafe { std::slice::from_raw_parts(configs, n) }
        .iter()
        .copied()
        .filter(|&c| settings::native_allowed() || attr(c, GLX_STEREO) == 0)
        .collect();
    let n = reals.len();
    let twinned: Vec<GLXFBConfig> = reals
        .iter()
        .copied()
        .filter(|&c| {
            attr(c, GLX_RENDER_TYPE) & GLX_RGBA_BIT != 0
                && attr(c, GLX_DRAWABLE_TYPE) & GLX_WINDOW_BIT != 0
                && attr(c, GLX_STEREO) == 0
        })
        .collect();
    watch(r, dpy);
    let twins: Vec<GLXFBConfig> = registry::with(|reg| {
        twinned
            .iter()
            .map(|&c| reg.fake_config(dpy as usize, c as usize) as GLXFBConfig)
            .collect()
    });
    let total = n + twins.len();
    // SAFETY: a list the program frees with XFree (libX11's XFree is free()).
    let list =
        unsafe { libc::malloc(total * std::mem::size_of::<GLXFBConfig>()) } as *mut GLXFBConfig;
    if list.is_null() {
        // No memory for the twins: the real list, without stereo ones.
        return Ok(configs);
    }
    // SAFETY: `list` holds `total` entries; `configs` came from Xlib.
    unsafe {
        std::ptr::copy_nonoverlapping(reals.as_ptr(), list, n);
        std::ptr::copy_nonoverlapping(twins.as_ptr(), list.add(n), twins.len());
        (r.xlib.XFree)(configs.cast());
        *nelements = total as c_int;
    }
    Ok(list)
}

/// glXGetFBConfigAttrib / glXGetFBConfigAttribSGIX. Refused
/// (GLX_BAD_VALUE): a NULL display or value pointer. A stereo
/// configuration asked about on another display is answered by the real
/// call with its real configuration, as GLX answers a configuration of
/// another display (GLXBadFBConfig).
///
/// # Safety
/// As glXGetFBConfigAttrib.
pub unsafe fn get_fbconfig_attrib(
    dpy: *mut Display,
    config: GLXFBConfig,
    attrib: c_int,
    value: *mut c_int,
    flavour: Flavour,
) -> Result<c_int> {
    let r = loaded()?;
    display(dpy)?;
    required(value, "value")?;
    let (real_config, ours) = registry::with(|reg| {
        let (c, _) = reg.real_config(config as usize);
        (c, reg.fake_display(config as usize) == Some(dpy as usize))
    });
    if ours && attrib == GLX_STEREO {
        // SAFETY: non-NULL out-pointer.
        unsafe { *value = 1 };
        return Ok(SUCCESS);
    }
    let c = real_config as GLXFBConfig;
    Ok(match (flavour, r.extra.sgix.get_attrib) {
        // SAFETY: forwarded call.
        (Flavour::Sgix, Some(f)) => unsafe { f(dpy, c, attrib, value) },
        // SAFETY: forwarded call.
        _ => unsafe { (r.glx.glXGetFBConfigAttrib)(dpy, c, attrib, value) },
    })
}

/// glXGetVisualFromFBConfig / glXGetVisualFromFBConfigSGIX. Refused: a
/// NULL display.
///
/// # Safety
/// As glXGetVisualFromFBConfig.
pub unsafe fn get_visual_from_fbconfig(
    dpy: *mut Display,
    config: GLXFBConfig,
    flavour: Flavour,
) -> Result<*mut XVisualInfo> {
    let r = loaded()?;
    display(dpy)?;
    let (real_config, stereo) = registry::with(|reg| reg.real_config(config as usize));
    let c = real_config as GLXFBConfig;
    let v = match (flavour, r.extra.sgix.get_visual) {
        // SAFETY: forwarded call.
        (Flavour::Sgix, Some(f)) => unsafe { f(dpy, c) },
        // SAFETY: forwarded call.
        _ => unsafe { (r.glx.glXGetVisualFromFBConfig)(dpy, c) },
    };
    if !v.is_null() {
        // SAFETY: a visual the real GLX returned.
        let id = unsafe { (*v).visualid };
        if stereo {
            watch(r, dpy);
        }
        registry::with(|reg| reg.mark_visual(dpy as usize, v as usize, id, stereo));
    }
    Ok(v)
}

/// Says (with GLSTEREO_VERBOSE) that a stereo request got native stereo.
fn tell_native() {
    settings::tell(
        "stereo is native: the driver's or a GL layer below's own stereo configuration, \
         shown as that layer shows it; choose a format (glstereo-run -m MODE) to have \
         glstereo emulate and show it instead",
    );
}

/// Makes program context `ctx` a stereo context: creates the layer's
/// context (`make_ours(ctx)`, sharing its objects; X errors trapped) and
/// records the shape the configuration gives (`attrib` reads it). On
/// failure stderr says why and the context stays mono.
fn adopt(
    r: &Real,
    dpy: *mut Display,
    ctx: GLXContext,
    make_ours: &[&dyn Fn(GLXContext) -> GLXContext],
    attrib: impl Fn(c_int) -> c_int,
    auto: bool,
) {
    if auto && r.extra.layered.is_none() {
        super::warn(
            "automatic stereo needs GL 4.3 (layered framebuffers, glCopyImageSubData): \
             this context stays mono",
        );
        return;
    }
    // The first way that works (each tried with its own X errors trapped).
    let mut ours = std::ptr::null_mut();
    let mut err = 0;
    for make in make_ours {
        let (c, e) = trap_x_errors(&r.xlib, dpy, || make(ctx));
        (ours, err) = (c, e);
        if !c.is_null() && e == 0 {
            break;
        }
    }
    if ours.is_null() || err != 0 {
        super::warn(&format!(
            "the layer's own GL context could not be created (X error {err}): \
             this stereo context runs in mono"
        ));
        return;
    }
    let shape = FramebufferShape {
        stereo: true,
        double_buffered: attrib(GLX_DOUBLEBUFFER) != 0,
    };
    let bits = |a| attrib(a).max(0) as u32;
    let formats = BufferFormats {
        // Eyes in memory the CPU reads serve the MIT-SHM path; a GL layer
        // below (RenderDoc, apitrace) must see plain GL it can record and
        // replay, and frames go through GL there anyway.
        in_place: r.extra.memory_objects.filter(|_| !r.swap_layered),
        layered: r.extra.layered.filter(|_| auto),
        ..BufferFormats::matching(
            bits(GLX_ALPHA_SIZE),
            bits(GLX_DEPTH_SIZE),
            bits(GLX_STENCIL_SIZE),
        )
    };
    let group = registry::with(|reg| reg.group(ctx as usize));
    // The layer's own context shares the program's objects: what it
    // names is the group's.
    r.gl.context_joined(ours as usize, group);
    let sc = StereoContext::new(
        dpy as usize,
        ctx as usize,
        ours as usize,
        shape,
        formats,
        group,
    );
    settings::tell(&format!(
        "{}: both eyes shown as {} in the program's window",
        if auto {
            "automatic stereo for a mono context"
        } else {
            "stereo is emulated"
        },
        super::live::mode().canonical_name()
    ));
    watch(r, dpy);
    registry::with(|reg| reg.add_context(ctx as usize, sc));
    super::controls::arm(&r.xlib, dpy);
}

/// Under `--auto` every context the program makes is an automatic-stereo
/// context: the live keys work from the first one on.
fn arm_automatic(r: &Real, dpy: *mut Display, ctx: GLXContext) {
    if !ctx.is_null() && super::live::auto_requested() {
        super::controls::arm(&r.xlib, dpy);
    }
}

/// Forgets whatever was known about a context at this address (a new
/// context may reuse a destroyed one's address), and records the share
/// group it joins.
fn forget(ctx: GLXContext, share: GLXContext) {
    if !ctx.is_null() {
        super::context::context_created(ctx as usize, share as usize);
    }
}

/// glXCreateContext. Refused: a NULL display or visual, a share list the
/// program destroyed. A context of a stereo visual is created direct
/// whatever `direct` says (stereo is emulated only in direct contexts).
///
/// # Safety
/// As glXCreateContext.
pub unsafe fn create_context(
    dpy: *mut Display,
    vis: *mut XVisualInfo,
    share: GLXContext,
    direct: c_int,
) -> Result<GLXContext> {
    let r = loaded()?;
    display(dpy)?;
    required(vis, "vis (the XVisualInfo*)")?;
    live_share(share, "shareList (destroyed by glXDestroyContext)")?;
    // SAFETY: the program's visual.
    let id = unsafe { (*vis).visualid };
    let stereo = registry::with(|reg| reg.is_stereo_visual(vis as usize, id));
    // A stereo context is direct: an indirect one could not be emulated.
    let direct = if stereo { 1 } else { direct };
    // SAFETY: forwarded call.
    let ctx = unsafe { (r.glx.glXCreateContext)(dpy, vis, share, direct) };
    forget(ctx, share);
    if ctx.is_null() {
        return Ok(ctx);
    }
    let mut native = 0;
    if !stereo && (settings::verbose() || super::live::auto_requested()) {
        // SAFETY: a valid visual.
        unsafe { (r.glx.glXGetConfig)(dpy, vis, GLX_STEREO, &mut native) };
        if native != 0 {
            tell_native();
        }
    }
    // Under --auto a mono visual's context gets automatic stereo.
    let auto = !stereo && native == 0 && super::live::auto_requested();
    if (stereo || auto) && direct_context(r, dpy, ctx) {
        adopt(
            r,
            dpy,
            ctx,
            // SAFETY: the same visual, sharing the program's context.
            &[&|prog| unsafe { (r.glx.glXCreateContext)(dpy, vis, prog, direct) }],
            |a| {
                let mut v = 0;
                // SAFETY: a valid visual.
                unsafe { (r.glx.glXGetConfig)(dpy, vis, a, &mut v) };
                v
            },
            auto,
        );
    } else {
        arm_automatic(r, dpy, ctx);
    }
    Ok(ctx)
}

/// How a configuration-based context is created.
pub enum NewContext {
    /// glXCreateNewContext / glXCreateContextWithConfigSGIX(render_type).
    RenderType(c_int, Flavour),
    /// glXCreateContextAttribsARB(attribs).
    Attribs(*const c_int),
}

/// glXCreateNewContext, glXCreateContextWithConfigSGIX and
/// glXCreateContextAttribsARB. Refused: a NULL display, a share context
/// the program destroyed. A context of a stereo configuration is created
/// direct whatever `direct` says.
///
/// # Safety
/// As those functions.
pub unsafe fn create_config_context(
    dpy: *mut Display,
    config: GLXFBConfig,
    how: NewContext,
    share: GLXContext,
    direct: c_int,
) -> Result<GLXContext> {
    let r = loaded()?;
    display(dpy)?;
    live_share(share, "the share context (destroyed by glXDestroyContext)")?;
    let (real_config, stereo) = registry::with(|reg| reg.real_config(config as usize));
    let c = real_config as GLXFBConfig;
    // A stereo context is direct: an indirect one could not be emulated.
    let direct = if stereo { 1 } else { direct };
    let ctx = match how {
        // SAFETY: forwarded calls.
        NewContext::RenderType(t, Flavour::Glx13) => unsafe {
            (r.glx.glXCreateNewContext)(dpy, c, t, share, direct)
        },
        NewContext::RenderType(t, Flavour::Sgix) => match r.extra.sgix.create_context {
            // SAFETY: forwarded call.
            Some(f) => unsafe { f(dpy, c, t, share, direct) },
            None => std::ptr::null_mut(),
        },
        NewContext::Attribs(list) => match r.extra.create_context_attribs {
            // SAFETY: forwarded call.
            Some(f) => unsafe { f(dpy, c, share, direct, list) },
            None => std::ptr::null_mut(),
        },
    };
    forget(ctx, share);
    let mut native = 0;
    if !stereo && !ctx.is_null() && (settings::verbose() || super::live::auto_requested()) {
        // SAFETY: a real configuration.
        unsafe { (r.glx.glXGetFBConfigAttrib)(dpy, c, GLX_STEREO, &mut native) };
        if native != 0 {
            tell_native();
        }
    }
    // Under --auto a mono configuration's context gets automatic stereo.
    let auto = !stereo && native == 0 && super::live::auto_requested();
    if (stereo || auto) && !ctx.is_null() && direct_context(r, dpy, ctx) {
        adopt(
            r,
            dpy,
            ctx,
            &[
                // A compatibility context of the same configuration, sharing
                // the program's objects, made as GL 3.2+ programs make
                // theirs: RenderDoc below captures only frames whose
                // context was made with glXCreateContextAttribsARB, and the
                // frame's swap is this context's.
                &|prog| match r.extra.create_context_attribs {
                    // SAFETY: a valid configuration and a None-terminated list.
                    Some(f) => unsafe { f(dpy, c, prog, direct, COMPATIBILITY.as_ptr()) },
                    None => std::ptr::null_mut(),
                },
                // SAFETY: as above, the GLX 1.3 way.
                &|prog| unsafe { (r.glx.glXCreateNewContext)(dpy, c, GLX_RGBA_TYPE, prog, direct) },
            ],
            |a| {
                let mut v = 0;
                // SAFETY: a real configuration.
                unsafe { (r.glx.glXGetFBConfigAttrib)(dpy, c, a, &mut v) };
                v
            },
            auto,
        );
    } else {
        arm_automatic(r, dpy, ctx);
    }
    Ok(ctx)
}

/// glXDestroyContext. Refused: a NULL display; a stereo context destroyed
/// already that is still current (its destruction waits for its release).
/// A stereo context current on a thread is destroyed, with the layer's
/// context, when it is released: GLX keeps it alive until then, and
/// presenting makes it current again, which a destroyed context cannot be.
/// Any other context goes to the real call (a context destroyed before
/// gets GLX's GLXBadContext error), and is remembered as destroyed (a share
/// list of it is refused).
///
/// # Safety
/// As glXDestroyContext.
pub unsafe fn destroy_context(dpy: *mut Display, ctx: GLXContext) -> Result<()> {
    let r = loaded()?;
    display(dpy)?;
    if ctx.is_null() {
        // SAFETY: forwarded call (nothing, in libGL).
        unsafe { (r.glx.glXDestroyContext)(dpy, ctx) };
        return Ok(());
    }
    let key = ctx as usize;
    let (sc, deferred) = registry::with(|reg| {
        if reg.is_doomed(key) {
            return Err(doomed());
        }
        reg.mark_dead(key);
        let sc = reg.remove_context(key);
        // Registry before state: decided under both locks, so a release on
        // another thread either sees the mark or came first.
        let deferred = sc.as_ref().is_some_and(|sc| sc.defer_destroy());
        if deferred {
            reg.add_doomed(key, sc.clone().expect("deferred"));
        }
        Ok((sc, deferred))
    })?;
    if deferred {
        return Ok(());
    }
    // SAFETY: forwarded call.
    unsafe { (r.glx.glXDestroyContext)(dpy, ctx) };
    if let Some(sc) = sc {
        sc.destroy_ours();
    }
    super::context::context_destroyed(key);
    Ok(())
}

fn doomed() -> Error {
    Error::invalid_operation(
        "ctx was destroyed by glXDestroyContext: it stays current where it is until \
         released, and cannot be made current again",
    )
}

/// glXMakeCurrent (`read` None) and glXMakeContextCurrent. Refused
/// (False): a NULL display, except for a release (no context, no
/// drawables), which libglvnd allows.
///
/// # Safety
/// As those functions.
pub unsafe fn make_current(
    dpy: *mut Display,
    draw: c_ulong,
    read: Option<c_ulong>,
    ctx: GLXContext,
) -> Result<c_int> {
    let r = loaded()?;
    let release = ctx.is_null() && draw == 0 && read.unwrap_or(0) == 0;
    if !release {
        display(dpy)?;
    }
    if !ctx.is_null() && registry::with(|reg| reg.is_doomed(ctx as usize)) {
        return Err(doomed());
    }
    let sc = if ctx.is_null() {
        None
    } else {
        registry::with(|reg| reg.context(ctx as usize))
    };
    let before = current();
    // The layer's own make-current of this context (freeing a destroyed
    // drawable's buffers while it is current nowhere) waits for this one.
    let held = sc.clone();
    let binding = held.as_ref().map(|sc| sc.hold_binding());
    let ok = match read {
        // SAFETY: forwarded calls.
        None => unsafe { (r.glx.glXMakeCurrent)(dpy, draw, ctx) },
        Some(read) => unsafe { (r.glx.glXMakeContextCurrent)(dpy, draw, read, ctx) },
    };
    if ok == 0 {
        return Ok(ok);
    }
    super::wsi::made_current(ctx as usize);
    let read = read.unwrap_or(draw);
    made_current(before, sc, dpy as usize, (draw, read), binding);
    Ok(ok)
}

/// glXSwapBuffers. Refused: a NULL display.
///
/// # Safety
/// As glXSwapBuffers.
pub unsafe fn swap_buffers(dpy: *mut Display, drawable: c_ulong) -> Result<()> {
    let r = loaded()?;
    display(dpy)?;
    let here = current().filter(|c| c.display == dpy as usize && c.draw == drawable);
    let target = match here {
        Some(c) => Some((c.sc, true)),
        // The stereo context this drawable was bound to last (the
        // contexts' states are read after the registry's lock is released).
        None => registry::with(|reg| reg.contexts_of(dpy as usize))
            .into_iter()
            .filter_map(|sc| sc.last_bound(drawable).map(|t| (t, sc)))
            .max_by_key(|(t, _)| *t)
            .map(|(_, sc)| (sc, false)),
    };
    if let Some((sc, here)) = target {
        if !here && sc.current_elsewhere() {
            super::warn(
                "glXSwapBuffers on a stereo drawable whose context is current on another \
                 thread: swap it on that thread; the window is not updated",
            );
        } else {
            if let Err(e) = sc.present(drawable, true, here) {
                super::warn(&format!("presenting the stereo frame: {e}"));
            }
            return Ok(());
        }
    }
    // SAFETY: forwarded call.
    unsafe { (r.glx.glXSwapBuffers)(dpy, drawable) };
    Ok(())
}

/// glXCreateWindow (records the X window behind the GLX window). Refused:
/// a NULL display.
///
/// # Safety
/// As glXCreateWindow.
pub unsafe fn create_window(
    dpy: *mut Display,
    config: GLXFBConfig,
    window: c_ulong,
    attribs: *const c_int,
) -> Result<c_ulong> {
    let r = loaded()?;
    display(dpy)?;
    let (c, _) = registry::with(|reg| reg.real_config(config as usize));
    // SAFETY: forwarded call with the real configuration.
    let w = unsafe { (r.glx.glXCreateWindow)(dpy, c as GLXFBConfig, window, attribs) };
    if w != 0 {
        watch(r, dpy);
        registry::with(|reg| reg.add_glx_window(dpy as usize, w, window));
    }
    Ok(w)
}

/// A GLX drawable's destroyer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Destroy {
    /// glXDestroyWindow.
    Window,
    /// glXDestroyPbuffer.
    Pbuffer,
    /// glXDestroyGLXPbufferSGIX.
    PbufferSgix,
    /// glXDestroyPixmap.
    Pixmap,
    /// glXDestroyGLXPixmap.
    GlxPixmap,
}

/// glXDestroyWindow, glXDestroyPbuffer, glXDestroyGLXPbufferSGIX,
/// glXDestroyPixmap and glXDestroyGLXPixmap (`what` says which): the
/// stereo buffers every stereo context of the display has for the
/// drawable are freed ([`StereoContext::drawable_destroyed`]: at once,
/// or when the context is released where GLX keeps the drawable), then
/// the real function destroys it. Refused: a NULL display.
///
/// # Safety
/// As the GLX function.
pub unsafe fn destroy_drawable(dpy: *mut Display, drawable: c_ulong, what: Destroy) -> Result<()> {
    let r = loaded()?;
    display(dpy)?;
    if drawable != 0 {
        for sc in registry::with(|reg| reg.contexts_of(dpy as usize)) {
            sc.drawable_destroyed(drawable);
        }
    }
    if what == Destroy::Window {
        registry::with(|reg| reg.remove_glx_window(dpy as usize, drawable));
    }
    // SAFETY: forwarded calls.
    unsafe {
        match what {
            Destroy::Window => (r.glx.glXDestroyWindow)(dpy, drawable),
            Destroy::Pbuffer => (r.glx.glXDestroyPbuffer)(dpy, drawable),
            Destroy::PbufferSgix => {
                if let Some(f) = r.extra.sgix.destroy_pbuffer {
                    f(dpy, drawable)
                }
            }
            Destroy::Pixmap => (r.glx.glXDestroyPixmap)(dpy, drawable),
            Destroy::GlxPixmap => (r.glx.glXDestroyGLXPixmap)(dpy, drawable),
        }
    }
    Ok(())
}

/// glXCreatePixmap, glXCreatePbuffer and their SGIX forms: the real
/// configuration behind a stereo one (these drawables are mono).
pub enum Offscreen {
    /// glXCreatePixmap(pixmap, attribs).
    Pixmap(c_ulong, *const c_int),
    /// glXCreatePbuffer(attribs).
    Pbuffer(*const c_int),
    /// glXCreateGLXPixmapWithConfigSGIX(pixmap).
    PixmapSgix(c_ulong),
    /// glXCreateGLXPbufferSGIX(width, height, attribs).
    PbufferSgix(u32, u32, *const c_int),
}

/// Creates an offscreen drawable of a configuration. Refused: a NULL
/// display.
///
/// # Safety
/// As the corresponding GLX function.
pub unsafe fn create_offscreen(
    dpy: *mut Display,
    config: GLXFBConfig,
    what: Offscreen,
) -> Result<c_ulong> {
    let r = loaded()?;
    display(dpy)?;
    let (c, _) = registry::with(|reg| reg.real_config(config as usize));
    let c = c as GLXFBConfig;
    // SAFETY: forwarded calls with the real configuration.
    Ok(unsafe {
        match what {
            Offscreen::Pixmap(p, a) => (r.glx.glXCreatePixmap)(dpy, c, p, a),
            Offscreen::Pbuffer(a) => (r.glx.glXCreatePbuffer)(dpy, c, a),
            Offscreen::PixmapSgix(p) => r.extra.sgix.create_pixmap.map_or(0, |f| f(dpy, c, p)),
            Offscreen::PbufferSgix(w, h, a) => r
                .extra
                .sgix
                .create_pbuffer
                .map_or(0, |f| f(dpy, c, w, h, a)),
        }
    })
}

//! Render to texture under automatic stereo ([`crate::auto`], "Render to
//! texture"): a framebuffer object of the program's whose colour is one
//! 2D texture at least the size of the window (Qt's QOpenGLWidget, VTK,
//! engines that draw the scene off screen and then show it as a textured
//! quad) is stereoized, as 3D Vision stereoized screen-sized render
//! targets. Smaller ones (shadow maps, reflections, picking) stay mono.
//!
//! - The first draw into such a framebuffer attaches, in place of the
//!   program's texture and depth/stencil, a 2-layer colour array of the
//!   texture's format and a 2-layer depth array: the draws then reach both
//!   eyes as draws into the window's eyes do, by the uniform and gl_Layer
//!   ([`crate::auto::runtime`]), with no switch. A clear clears both.
//! - Layer 1 is also seen as a 2D texture (a texture view): the right
//!   eye's copy of the program's texture. Before a draw that may sample the
//!   program's texture (any draw outside that framebuffer), layer 0 is
//!   copied into it once per change (glCopyImageSubData): what the program
//!   reads back or samples in mono is the left eye, as seed 004 resolves
//!   for ReadPixels. In the right eye's draws, texture units holding the
//!   program's texture hold the view instead (a binding does not end
//!   llvmpipe's scene).
//! - glReadPixels from the framebuffer reads layer 0: the left eye; a blit
//!   from it into the window copies each eye's layer into that eye
//!   ([`known`]).
//! - Both layers start as copies of the program's buffers, which hold
//!   what was made before the first draw (the first frame's glClear).
//!
//! Not covered: framebuffers with more than one colour attachment, a
//! colour renderbuffer, multisampled attachments, a separate stencil
//! buffer, a texture level other than 0 or a layer of an array; textures
//! sampled through image units or bindless handles; what the program sizes
//! smaller than the window and scales up. Those framebuffers stay mono. A
//! program that attaches something else to a stereoized framebuffer makes
//! it mono again (its attachments are the program's from then on).

use std::collections::HashMap;

use std::sync::{Mutex, OnceLock};

use crate::auto::eyes::Attachments;
use crate::auto::gl_fns;
use crate::math::Eye;

const GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE: u32 = 0x8CD0;
const GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME: u32 = 0x8CD1;
const GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL: u32 = 0x8CD2;
const GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER: u32 = 0x8CD4;
const GL_FRAMEBUFFER_ATTACHMENT_LAYERED: u32 = 0x8DA7;
const GL_COLOR_ATTACHMENT0: u32 = 0x8CE0;
const GL_DEPTH_ATTACHMENT: u32 = 0x8D00;
const GL_STENCIL_ATTACHMENT: u32 = 0x8D20;
const GL_DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;
const GL_DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const GL_FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;
const GL_NONE: i32 = 0;
const GL_TEXTURE: i32 = 0x1702;
const GL_RENDERBUFFER: i32 = 0x8D41;
const GL_TEXTURE_2D: u32 = 0x0DE1;
const GL_TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const GL_TEXTURE_DEPTH: u32 = 0x8071;
const GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE: u32 = 0x8CD3;
const GL_TEXTURE_WIDTH: u32 = 0x1000;
const GL_TEXTURE_HEIGHT: u32 = 0x1001;
const GL_TEXTURE_INTERNAL_FORMAT: u32 = 0x1003;
const GL_TEXTURE_SAMPLES: u32 = 0x9106;
const GL_RENDERBUFFER_WIDTH: u32 = 0x8D42;
const GL_RENDERBUFFER_HEIGHT: u32 = 0x8D43;
const GL_RENDERBUFFER_INTERNAL_FORMAT: u32 = 0x8D44;
const GL_RENDERBUFFER_SAMPLES: u32 = 0x8CAB;
const GL_TEXTURE_MIN_FILTER: u32 = 0x2801;
const GL_TEXTURE_MAG_FILTER: u32 = 0x2800;
const GL_TEXTURE_WRAP_S: u32 = 0x2802;
const GL_TEXTURE_WRAP_T: u32 = 0x2803;
const GL_ACTIVE_TEXTURE: u32 = 0x84E0;
const GL_TEXTURE0: u32 = 0x84C0;
const GL_TEXTURE_BINDING_2D: u32 = 0x8069;
const GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS: u32 = 0x8B4D;
const GL_RGBA: i32 = 0x1908;
const GL_RGB: i32 = 0x1907;
const GL_RGBA8: u32 = 0x8058;
const GL_RGB8: u32 = 0x8051;
const GL_DEPTH_COMPONENT: i32 = 0x1902;
const GL_DEPTH_STENCIL: i32 = 0x84F9;
const GL_DEPTH_COMPONENT24: u32 = 0x81A6;
const GL_DEPTH24_STENCIL8: u32 = 0x88F0;

/// The texture units scanned for the program's texture in the right
/// eye's draws (at most; fewer where the driver has fewer).
const UNITS: i32 = 16;

gl_fns! {
    /// GL 4.5's direct state access, texture views and image copies:
    /// stereoizing a framebuffer changes no binding of the program's.
    pub struct TargetFns {
        get_integerv = c"glGetIntegerv": fn(u32, *mut i32);
        get_framebuffer_attachment_parameteriv = c"glGetNamedFramebufferAttachmentParameteriv": fn(u32, u32, u32, *mut i32);
        get_texture_level_parameteriv = c"glGetTextureLevelParameteriv": fn(u32, i32, u32, *mut i32);
        get_texture_parameteriv = c"glGetTextureParameteriv": fn(u32, u32, *mut i32);
        texture_parameteri = c"glTextureParameteri": fn(u32, u32, i32);
        get_renderbuffer_parameteriv = c"glGetNamedRenderbufferParameteriv": fn(u32, u32, *mut i32);
        create_textures = c"glCreateTextures": fn(u32, i32, *mut u32);
        gen_textures = c"glGenTextures": fn(i32, *mut u32);
        delete_textures = c"glDeleteTextures": fn(i32, *const u32);
        texture_storage_3d = c"glTextureStorage3D": fn(u32, i32, u32, i32, i32, i32);
        texture_view = c"glTextureView": fn(u32, u32, u32, u32, u32, u32, u32, u32);
        framebuffer_texture = c"glNamedFramebufferTexture": fn(u32, u32, u32, i32);
        framebuffer_renderbuffer = c"glNamedFramebufferRenderbuffer": fn(u32, u32, u32, u32);
        check_framebuffer_status = c"glCheckNamedFramebufferStatus": fn(u32, u32) -> u32;
        copy_image_sub_data = c"glCopyImageSubData": fn(u32, u32, i32, i32, i32, i32, u32, u32, i32, i32, i32, i32, i32, i32, i32);
        is_texture = c"glIsTexture": fn(u32) -> u8;
        active_texture = c"glActiveTexture": fn(u32);
        bind_texture = c"glBindTexture": fn(u32, u32);
    }
}

/// The table, loaded once (None: no GL 4.5 here; render targets stay mono).
fn fns() -> Option<&'static TargetFns> {
    static FNS: OnceLock<Option<TargetFns>> = OnceLock::new();
    FNS.get_or_init(|| {
        let get = crate::auto::host::gl_proc;
        // SAFETY: `get` returns the named GL function or NULL.
        let t = unsafe { TargetFns::load(get) };
        if t.is_none() {
            crate::report::warn(
                "automatic stereo of render targets needs GL 4.5's direct state access: \
                 what programs draw into their own framebuffer objects stays mono",
            );
        }
        t
    })
    .as_ref()
}

/// One stereoized framebuffer object of the program's.
#[derive(Debug)]
struct Target {
    /// The context whose framebuffer object it is (framebuffer objects
    /// are not shared; textures are).
    context: usize,
    fbo: u32,
    /// The program's colour texture (2D, level 0).
    texture: u32,
    /// The program's depth/stencil attachment, put back if the
    /// framebuffer cannot be completed with the arrays: (attachment point,
    /// object type, name).
    depth_of_program: Option<(u32, i32, u32)>,
    /// The 2-layer colour array in its place.
    colour: u32,
    /// The 2-layer depth array (0: none) and where it is attached.
    depth: u32,
    depth_attachment: u32,
    /// Layer 1 of `colour` as a 2D texture: the right eye's texture.
    right: u32,
    width: i32,
    height: i32,
    /// Drawn into since layer 0 was last copied into `texture`.
    dirty: bool,
}

/// A share group's stereoized render targets: one context draws into a
/// target, another may show its texture (Qt's QOpenGLWidget renders in a
/// context of its own and the window's context composes it).
#[derive(Debug, Default)]
pub struct Targets {
    targets: Vec<Target>,
    /// Framebuffers looked at and left mono: (context, framebuffer, its
    /// colour object), looked at again only when that changes.
    mono: Vec<(usize, u32, u32)>,
}

/// Runs `f` with the render targets of the share group `group`.
pub fn with_group<T>(group: u64, f: impl FnOnce(&mut Targets) -> T) -> T {
    static GROUPS: Mutex<Option<HashMap<u64, Targets>>> = Mutex::new(None);
    let mut g = GROUPS.lock().unwrap_or_else(|e| e.into_inner());
    f(g.get_or_insert_with(HashMap::new).entry(group).or_default())
}

/// The eye arrays of the draw framebuffer `fbo` of `context` when it is
/// one of `targets` (or becomes one now), else None (the draw is mono).
/// `eyes`: the window's eyes (their API and size).
///
/// # Safety
/// The program's context `context` is current on this thread.
pub unsafe fn eyes_of(
    targets: &mut Targets,
    context: usize,
    fbo: u32,
    eyes: &Attachments,
) -> Option<Attachments> {
    let f = fns()?;
    // SAFETY: contract; one value per query.
    unsafe {
        let colour = attachment(
            f,
            fbo,
            GL_COLOR_ATTACHMENT0,
            GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME,
        );
        let ours = |t: &Target| t.context == context && t.fbo == fbo;
        if let Some(t) = targets.targets.iter_mut().find(|t| ours(t)) {
            if colour as u32 == t.colour {
                t.dirty = true;
                return Some(eyes.of_target(t.colour, t.depth, t.depth_attachment));
            }
            // The program attached something else: its framebuffer now.
            let gone = targets.targets.iter().position(ours).expect("found");
            release(f, targets.targets.swap_remove(gone));
        }
        if targets.mono.contains(&(context, fbo, colour as u32)) {
            return None;
        }
        match stereoize(f, context, fbo, eyes) {
            Some(mut t) => {
                t.dirty = true;
                let a = eyes.of_target(t.colour, t.depth, t.depth_attachment);
                targets.targets.push(t);
                Some(a)
            }
            None => {
                targets.mono.retain(|&(c, b, _)| (c, b) != (context, fbo));
                targets.mono.push((context, fbo, colour as u32));
                None
            }
        }
    }
}

/// The eye arrays of `fbo` of `context` when it is a stereoized target
/// already (to read from it eye by eye: a blit out of it), else None.
/// `eyes`: the window's eyes (their API).
pub fn known(
    targets: &Targets,
    context: usize,
    fbo: u32,
    eyes: &Attachments,
) -> Option<Attachments> {
    targets
        .targets
        .iter()
        .find(|t| t.context == context && t.fbo == fbo)
        .map(|t| eyes.of_target(t.colour, t.depth, t.depth_attachment))
}

/// The size of `context`'s stereoized target `fbo` (None: not one).
pub fn size(targets: &Targets, context: usize, fbo: u32) -> Option<(u32, u32)> {
    targets
        .targets
        .iter()
        .find(|t| t.context == context && t.fbo == fbo)
        .map(|t| (t.width.max(0) as u32, t.height.max(0) as u32))
}

/// Before a draw of `context` into `drawing` (its draw framebuffer): the
/// program's textures of the other targets drawn into since, given their
/// left eye.
///
/// # Safety
/// The program's context `context` is current on this thread.
pub unsafe fn resolve(targets: &mut Targets, context: usize, drawing: u32) {
    let Some(f) = fns() else {
        return;
    };
    let others = |t: &&mut Target| t.dirty && (t.context, t.fbo) != (context, drawing);
    for t in targets.targets.iter_mut().filter(others) {
        // SAFETY: contract; both are width × height of one format; the
        // program's texture still exists (checked).
        unsafe {
            if (f.is_texture)(t.texture) == 0 {
                continue;
            }
            (f.copy_image_sub_data)(
                t.colour,
                GL_TEXTURE_2D_ARRAY,
                0,
                0,
                0,
                0,
                t.texture,
                GL_TEXTURE_2D,
                0,
                0,
                0,
                0,
                t.width,
                t.height,
                1,
            );
            // The right eye's view samples as the program's texture does.
            for p in [
                GL_TEXTURE_MIN_FILTER,
                GL_TEXTURE_MAG_FILTER,
                GL_TEXTURE_WRAP_S,
                GL_TEXTURE_WRAP_T,
            ] {
                let mut v = 0;
                (f.get_texture_parameteriv)(t.texture, p, &mut v);
                (f.texture_parameteri)(t.right, p, v);
            }
        }
        t.dirty = false;
    }
}

/// Texture units whose 2D binding was exchanged for an eye: put back by
/// [`Bound::restore`].
#[derive(Debug, Default)]
pub struct Bound {
    units: Vec<(u32, u32)>,
    active: u32,
}

/// For `eye`'s draw: the units holding a target's texture hold that eye's
/// copy (the right eye's view; the left eye's is the program's texture).
///
/// # Safety
/// The program's context is current on this thread.
pub unsafe fn bind_eye(targets: &Targets, eye: Eye) -> Bound {
    let mut bound = Bound::default();
    let Some(f) = fns() else {
        return bound;
    };
    if eye == Eye::Left || targets.targets.is_empty() {
        return bound;
    }
    // SAFETY: contract; one value per query; units below the maximum.
    unsafe {
        let (mut active, mut max) = (0, 0);
        (f.get_integerv)(GL_ACTIVE_TEXTURE, &mut active);
        (f.get_integerv)(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &mut max);
        bound.active = active as u32;
        for unit in 0..max.clamp(0, UNITS) as u32 {
            (f.active_texture)(GL_TEXTURE0 + unit);
            let mut name = 0;
            (f.get_integerv)(GL_TEXTURE_BINDING_2D, &mut name);
            if let Some(t) = targets.targets.iter().find(|t| t.texture == name as u32) {
                (f.bind_texture)(GL_TEXTURE_2D, t.right);
                bound.units.push((unit, name as u32));
            }
        }
        (f.active_texture)(bound.active);
    }
    bound
}

impl Bound {
    /// Puts the program's bindings back.
    ///
    /// # Safety
    /// The context of [`bind_eye`] is current on this thread.
    pub unsafe fn restore(self) {
        let Some(f) = fns() else {
            return;
        };
        if self.units.is_empty() {
            return;
        }
        // SAFETY: contract.
        unsafe {
            for (unit, name) in self.units {
                (f.active_texture)(GL_TEXTURE0 + unit);
                (f.bind_texture)(GL_TEXTURE_2D, name);
            }
            (f.active_texture)(self.active);
        }
    }
}

unsafe fn attachment(f: &TargetFns, fbo: u32, point: u32, pname: u32) -> i32 {
    let mut v = 0;
    // SAFETY: contract of the callers; one value.
    unsafe { (f.get_framebuffer_attachment_parameteriv)(fbo, point, pname, &mut v) };
    v
}

unsafe fn level(f: &TargetFns, texture: u32, pname: u32) -> i32 {
    let mut v = 0;
    // SAFETY: as above.
    unsafe { (f.get_texture_level_parameteriv)(texture, 0, pname, &mut v) };
    v
}

unsafe fn renderbuffer(f: &TargetFns, rb: u32, pname: u32) -> i32 {
    let mut v = 0;
    // SAFETY: as above.
    unsafe { (f.get_renderbuffer_parameteriv)(rb, pname, &mut v) };
    v
}

/// A sized format for an array of the texture's `format`.
fn sized(format: i32) -> u32 {
    match format {
        GL_RGBA => GL_RGBA8,
        GL_RGB => GL_RGB8,
        GL_DEPTH_COMPONENT => GL_DEPTH_COMPONENT24,
        GL_DEPTH_STENCIL => GL_DEPTH24_STENCIL8,
        f => f as u32,
    }
}

/// Stereoizes `fbo` when it is a render target of the window's size
/// (module docs); None when it stays mono. Every query is of an object
/// the framebuffer names, so no call raises a GL error the program would
/// see.
unsafe fn stereoize(f: &TargetFns, context: usize, fbo: u32, eyes: &Attachments) -> Option<Target> {
    // SAFETY: contract of the callers; one value per query; objects made
    // here are named by GL.
    unsafe {
        let at = |point, pname| attachment(f, fbo, point, pname);
        if fbo == 0 || at(GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) != GL_TEXTURE
        {
            return None;
        }
        let texture = at(GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME) as u32;
        if at(
            GL_COLOR_ATTACHMENT0,
            GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL,
        ) != 0
            || at(GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_LAYERED) != 0
            || at(
                GL_COLOR_ATTACHMENT0,
                GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER,
            ) != 0
        {
            return None;
        }
        for i in 1..4 {
            if at(
                GL_COLOR_ATTACHMENT0 + i,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
            ) != GL_NONE
            {
                return None;
            }
        }
        // A 2D texture: not a cube map's face, not an array's layer (above),
        // one deep. (GL_TEXTURE_TARGET is not asked: Mesa answers it only
        // in 4.5 core contexts, else with GL_INVALID_ENUM.)
        if at(
            GL_COLOR_ATTACHMENT0,
            GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE,
        ) != 0
            || level(f, texture, GL_TEXTURE_DEPTH) != 1
            || level(f, texture, GL_TEXTURE_SAMPLES) > 1
        {
            return None;
        }
        let (width, height) = (
            level(f, texture, GL_TEXTURE_WIDTH),
            level(f, texture, GL_TEXTURE_HEIGHT),
        );
        let window = (
            level(f, eyes.colour(), GL_TEXTURE_WIDTH),
            level(f, eyes.colour(), GL_TEXTURE_HEIGHT),
        );
        if width < window.0 || height < window.1 || width <= 0 || height <= 0 {
            return None;
        }
        let format = sized(level(f, texture, GL_TEXTURE_INTERNAL_FORMAT));
        // Depth and stencil: none, depth alone, or one packed buffer.
        let kind = |point| at(point, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE);
        let name = |point| at(point, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME) as u32;
        let (depth_kind, stencil_kind) = (kind(GL_DEPTH_ATTACHMENT), kind(GL_STENCIL_ATTACHMENT));
        let depth_of_program = match (depth_kind, stencil_kind) {
            (GL_NONE, GL_NONE) => None,
            (d, GL_NONE) => Some((GL_DEPTH_ATTACHMENT, d, name(GL_DEPTH_ATTACHMENT))),
            (d, s) if d == s && name(GL_DEPTH_ATTACHMENT) == name(GL_STENCIL_ATTACHMENT) => {
                Some((GL_DEPTH_STENCIL_ATTACHMENT, d, name(GL_DEPTH_ATTACHMENT)))
            }
            _ => return None,
        };
        let depth_format = match depth_of_program {
            None => None,
            Some((_, GL_RENDERBUFFER, rb)) => {
                if renderbuffer(f, rb, GL_RENDERBUFFER_SAMPLES) > 0
                    || renderbuffer(f, rb, GL_RENDERBUFFER_WIDTH) < width
                    || renderbuffer(f, rb, GL_RENDERBUFFER_HEIGHT) < height
                {
                    return None;
                }
                Some(sized(renderbuffer(f, rb, GL_RENDERBUFFER_INTERNAL_FORMAT)))
            }
            Some((_, GL_TEXTURE, tex)) => {
                if level(f, tex, GL_TEXTURE_SAMPLES) > 1 {
                    return None;
                }
                Some(sized(level(f, tex, GL_TEXTURE_INTERNAL_FORMAT)))
            }
            Some(_) => return None,
        };
        let mut t = Target {
            context,
            fbo,
            texture,
            depth_of_program,
            colour: 0,
            depth: 0,
            depth_attachment: depth_of_program.map_or(GL_DEPTH_ATTACHMENT, |d| d.0),
            right: 0,
            width,
            height,
            dirty: false,
        };
        (f.create_textures)(GL_TEXTURE_2D_ARRAY, 1, &mut t.colour);
        (f.texture_storage_3d)(t.colour, 1, format, width, height, 2);
        (f.gen_textures)(1, &mut t.right);
        (f.texture_view)(t.right, GL_TEXTURE_2D, t.colour, format, 0, 1, 1, 1);
        if let Some(df) = depth_format {
            (f.create_textures)(GL_TEXTURE_2D_ARRAY, 1, &mut t.depth);
            (f.texture_storage_3d)(t.depth, 1, df, width, height, 2);
        }
        (f.framebuffer_texture)(fbo, GL_COLOR_ATTACHMENT0, t.colour, 0);
        if t.depth != 0 {
            (f.framebuffer_texture)(fbo, t.depth_attachment, t.depth, 0);
        }
        if (f.check_framebuffer_status)(fbo, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE {
            put_back(f, &t);
            release(f, t);
            return None;
        }
        // Both eyes start from what the program's buffers hold: a clear
        // (glClear is no draw, so it went to them) or anything else made
        // before this first draw.
        let copies = [(texture, GL_TEXTURE_2D, t.colour)].into_iter().chain(
            depth_of_program
                .filter(|_| t.depth != 0)
                .map(|(_, kind, name)| {
                    let target = if kind == GL_RENDERBUFFER {
                        GL_RENDERBUFFER as u32
                    } else {
                        GL_TEXTURE_2D
                    };
                    (name, target, t.depth)
                }),
        );
        for (source, target, array) in copies {
            for layer in 0..2 {
                (f.copy_image_sub_data)(
                    source,
                    target,
                    0,
                    0,
                    0,
                    0,
                    array,
                    GL_TEXTURE_2D_ARRAY,
                    0,
                    0,
                    0,
                    layer,
                    width,
                    height,
                    1,
                );
            }
        }
        Some(t)
    }
}

/// Attaches the program's own texture and depth/stencil again.
unsafe fn put_back(f: &TargetFns, t: &Target) {
    // SAFETY: contract of the callers.
    unsafe {
        (f.framebuffer_texture)(t.fbo, GL_COLOR_ATTACHMENT0, t.texture, 0);
        match t.depth_of_program {
            Some((point, GL_RENDERBUFFER, rb)) => {
                (f.framebuffer_renderbuffer)(t.fbo, point, GL_RENDERBUFFER as u32, rb)
            }
            Some((point, _, tex)) => (f.framebuffer_texture)(t.fbo, point, tex, 0),
            None => {}
        }
    }
}

/// Deletes the layer's objects of `t`.
unsafe fn release(f: &TargetFns, t: Target) {
    let names: Vec<u32> = [t.colour, t.depth, t.right]
        .into_iter()
        .filter(|&n| n != 0)
        .collect();
    // SAFETY: contract of the callers; names made here.
    unsafe { (f.delete_textures)(names.len() as i32, names.as_ptr()) };
}

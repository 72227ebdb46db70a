//! Render targets under automatic stereo: which of a program's framebuffer
//! objects are drawn in stereo, and how ([`crate::auto`], "Render to
//! texture").
//!
//! # The policy: stereo flows with the data
//!
//! A program's framebuffer object (a *target*) gets eyes when what is
//! drawn into it differs between the eyes:
//!
//! 1. a draw into it samples a texture that has eyes (on any texture
//!    unit): a post-processing pass, a blur of a blur, a composite of
//!    regions (Blender's, Qt Quick's), a resolve drawn as a quad;
//! 2. a blit into it comes from a target that has eyes (a multisample
//!    resolve, a copy between targets);
//! 3. a draw into it has its vertices moved per eye — the program's
//!    rewritten vertex stage or the fixed-function stand-in: the scene's
//!    camera — unless the target is *seen from a light*: it has no colour
//!    attachment (a depth-only shadow map), or its colour is square and
//!    not the window's size (a shadow map with colour, a cube or
//!    environment face). Those stay mono and both eyes sample the one
//!    picture, as a light has one viewpoint.
//!
//! Anything else is drawn once, unshifted: a target no stereo reaches (a
//! user interface drawn into a texture, a look-up table, a texture a
//! program fills by drawing) stays one picture. Once a target has eyes
//! it keeps them until the program attaches something else to it, and a
//! texture keeps its eyes (what a region not redrawn this frame shows)
//! until the program redefines or deletes it. Size, aspect, attachment
//! count and kind play no part beyond rule 3: scaled-down targets (bloom,
//! blur chains, half-resolution ambient occlusion) get eyes because a
//! stereo texture flows into them, G-buffers with several colour
//! attachments get eyes on every attachment, colour and depth
//! renderbuffers and multisample targets too.
//!
//! 3D Vision Automatic decided by shape alone (BPG-05394-001: non-square
//! targets at least the back buffer's size stereo, square ones mono, a
//! draw without depth a full-screen pass), so a half-resolution blur of a
//! stereo scene came out mono and flat, and a 4:3 shadow map stereo.
//!
//! What it gets wrong, and what happens then:
//! - a camera that is not the viewer's drawn into a non-square colour
//!   target (a planar reflection, a security-camera screen, a portal)
//!   gets eyes shifted as the viewer's camera is: the picture on the
//!   mirror or screen has depth of its own instead of lying flat on it;
//! - a shadow map with a non-square colour attachment (variance or
//!   exponential shadow maps of 2:1) gets eyes: each eye's shadows are
//!   looked up in a map shifted for that eye, so shadow edges sit a few
//!   pixels off between the eyes;
//! - a square target drawn from the viewer's camera (a square window's
//!   size excepted) stays mono: its picture is flat;
//! - targets the layer cannot give eyes — cube map faces, array layers,
//!   3D slices, mipmap levels other than 0, rectangle textures, textures
//!   the program sampled through image units or bindless handles — stay
//!   mono (flat), and a draw sampling a stereo texture into one of them
//!   sees the left eye.
//!
//! # How
//!
//! A program's texture or renderbuffer with eyes has a *twin*: a 2-layer
//! array texture of its format and size (2D, or 2D multisample; with its
//! mipmap chain), layer 0 the left eye and layer 1 the right, and a
//! texture view of layer 1 (the right eye's texture). A target with eyes
//! has its attachments replaced by its objects' twins, attached layered:
//! its draws reach both eyes by gl_Layer as the window's do
//! ([`crate::auto::runtime`]), with no framebuffer switch. The program's
//! own object holds the left eye: layer 0 is copied into it
//! (glCopyImageSubData, ≈ 0.1 ms at 1280x1024) before anything else may
//! read it — a draw into another target, a glGenerateMipmap (whose
//! result is then made for the right eye too), a read of its pixels — so
//! what a program reads back of its own texture is the left eye, as seed
//! 004 resolves reads. In the right eye's draws every texture unit whose
//! 2D or 2D multisample binding is a texture with eyes holds that
//! texture's right view instead (a binding does not end llvmpipe's
//! scene). Blits from a target with eyes are made eye to eye; into one
//! from a mono source, the same picture into both eyes. Copies of
//! images (glCopyTexSubImage2D from a target with eyes, glCopyImageSubData
//! from an object with eyes) give the destination eyes, copied eye to
//! eye. A new twin starts
//! with both layers holding what the program's object held.

use crate::auto::eyes::Attachments;
use crate::math::Eye;

const GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE: u32 = 0x8CD0;
const GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME: u32 = 0x8CD1;
const GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL: u32 = 0x8CD2;
const GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE: u32 = 0x8CD3;
const GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER: u32 = 0x8CD4;
const GL_FRAMEBUFFER_ATTACHMENT_LAYERED: u32 = 0x8DA7;
const GL_COLOR_ATTACHMENT0: u32 = 0x8CE0;
const GL_DEPTH_ATTACHMENT: u32 = 0x8D00;
const GL_STENCIL_ATTACHMENT: u32 = 0x8D20;
const GL_DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;
const GL_READ_FRAMEBUFFER: u32 = 0x8CA8;
const GL_TEXTURE: i32 = 0x1702;
const GL_RENDERBUFFER: i32 = 0x8D41;
const GL_TEXTURE_2D: u32 = 0x0DE1;
const GL_TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const GL_TEXTURE_2D_MULTISAMPLE: u32 = 0x9100;
const GL_TEXTURE_2D_MULTISAMPLE_ARRAY: u32 = 0x9102;
const GL_TEXTURE_DEPTH: u32 = 0x8071;
const GL_TEXTURE_WIDTH: u32 = 0x1000;
const GL_TEXTURE_HEIGHT: u32 = 0x1001;
const GL_TEXTURE_INTERNAL_FORMAT: u32 = 0x1003;
const GL_TEXTURE_SAMPLES: u32 = 0x9106;
const GL_TEXTURE_FIXED_SAMPLE_LOCATIONS: u32 = 0x9107;
const GL_TEXTURE_IMMUTABLE_FORMAT: u32 = 0x912F;
const GL_TEXTURE_IMMUTABLE_LEVELS: u32 = 0x82DF;
const GL_TEXTURE_DEPTH_SIZE: u32 = 0x884A;
const GL_TEXTURE_STENCIL_SIZE: u32 = 0x88F1;
const GL_RENDERBUFFER_WIDTH: u32 = 0x8D42;
const GL_RENDERBUFFER_HEIGHT: u32 = 0x8D43;
const GL_RENDERBUFFER_INTERNAL_FORMAT: u32 = 0x8D44;
const GL_RENDERBUFFER_SAMPLES: u32 = 0x8CAB;
const GL_ACTIVE_TEXTURE: u32 = 0x84E0;
const GL_TEXTURE0: u32 = 0x84C0;
const GL_TEXTURE_BINDING_2D: u32 = 0x8069;
const GL_TEXTURE_BINDING_2D_MULTISAMPLE: u32 = 0x9104;
const GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS: u32 = 0x8B4D;
const GL_TEXTURE_BINDING_2D_ARRAY: u32 = 0x8C1D;
const GL_PIXEL_UNPACK_BUFFER: u32 = 0x88EC;
const GL_PIXEL_UNPACK_BUFFER_BINDING: u32 = 0x88EF;
const GL_TEXTURE_MAX_LEVEL: u32 = 0x813D;
const GL_RGBA: i32 = 0x1908;
const GL_RGB: i32 = 0x1907;
const GL_RG: i32 = 0x8227;
const GL_RED: i32 = 0x1903;
const GL_LUMINANCE: i32 = 0x1909;
const GL_LUMINANCE_ALPHA: i32 = 0x190A;
const GL_ALPHA: i32 = 0x1906;
const GL_DEPTH_COMPONENT: i32 = 0x1902;
const GL_DEPTH_STENCIL: i32 = 0x84F9;
/// The sampling state a right view copies from the program's texture.
const SAMPLING: [u32; 9] = [
    0x2801, // GL_TEXTURE_MIN_FILTER
    0x2800, // GL_TEXTURE_MAG_FILTER
    0x2802, // GL_TEXTURE_WRAP_S
    0x2803, // GL_TEXTURE_WRAP_T
    0x8072, // GL_TEXTURE_WRAP_R
    0x884C, // GL_TEXTURE_COMPARE_MODE
    0x884D, // GL_TEXTURE_COMPARE_FUNC
    0x813C, // GL_TEXTURE_BASE_LEVEL
    0x813D, // GL_TEXTURE_MAX_LEVEL
];

/// The colour attachment points looked at (GL_MAX_COLOR_ATTACHMENTS is 8
/// on Mesa).
const COLOURS: u32 = 8;
/// The texture units scanned for textures with eyes (at most; fewer
/// where the driver has fewer).
const UNITS: i32 = 32;

mod api;

pub use api::ContextApi;
use api::Gl;

/// A program object that can have eyes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Object {
    /// A texture, by name.
    Texture(u32),
    /// A renderbuffer, by name.
    Renderbuffer(u32),
}

/// The storage of a program object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Shape {
    /// Its internal format as GL reports it (unsized where the program
    /// gave an unsized one: GL_RGBA of glTexImage2D).
    format: u32,
    width: i32,
    height: i32,
    /// 0: not multisampled.
    samples: i32,
    fixed_locations: bool,
    levels: i32,
}

/// A program object with eyes (module docs, "How").
#[derive(Debug)]
struct Twin {
    object: Object,
    shape: Shape,
    /// The 2-layer array: layer 0 the left eye, layer 1 the right.
    array: u32,
    /// The right eye's texture: layer 1 seen as a texture of the
    /// object's kind (a view), or, for an unsized format (which no
    /// immutable storage, so no view, has), a texture of its own that
    /// layer 1 is copied into with layer 0.
    right: u32,
    /// `right` is a view of layer 1.
    view: bool,
    /// Layer 0 was drawn into since it was copied into the object.
    dirty: bool,
}

/// A target with eyes: the program's objects at its attachment points
/// (each replaced by its twin's array).
#[derive(Debug)]
struct Stereo {
    context: usize,
    fbo: u32,
    points: Vec<(u32, Object)>,
    /// An object of it lost its eyes while another context was current:
    /// the program's objects go back at this context's next draw into it.
    stale: bool,
}

/// What a target's attachments allow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Structure {
    /// Something the layer cannot give eyes (module docs).
    Unsupported,
    /// Seen from a light (rule 3): mono unless stereo flows into it.
    Light,
    /// Anything else.
    Plain,
}

/// A target looked at and left mono, with what it had attached then.
#[derive(Debug)]
struct Looked {
    context: usize,
    fbo: u32,
    attached: Vec<(u32, Object)>,
    structure: Structure,
}

/// A share group's render targets and textures with eyes: one context
/// draws into a target, another may show its texture (Qt's
/// QOpenGLWidget renders in a context of its own and the window's
/// context composes it).
#[derive(Debug, Default)]
pub struct Targets {
    /// Where the group's scene was drawn last, for automatic convergence
    /// (a program may draw its scene in one context and present it from
    /// another: Blender's draw manager and its window).
    pub scene: SceneTarget,
    twins: Vec<Twin>,
    stereo: Vec<Stereo>,
    looked: Vec<Looked>,
    /// Changes whenever a twin is made or goes ([`Targets::generation`]).
    generation: u64,
    /// What the group's contexts are (asked at the first call that needs
    /// it; EGL shares objects only between contexts of one API).
    api: Option<ContextApi>,
    /// OpenGL ES: the target each 2D or 2D multisample texture of the
    /// program's was defined with (ES cannot be asked a texture's
    /// target, and binding one to another target is an error the
    /// program would see). A texture without one stays mono.
    es_targets: std::collections::HashMap<u32, u32>,
}

/// The render targets of every share group, by group.
type Groups = std::collections::HashMap<u64, Targets>;

fn groups() -> std::sync::MutexGuard<'static, Option<Groups>> {
    static GROUPS: std::sync::Mutex<Option<Groups>> = std::sync::Mutex::new(None);
    GROUPS.lock().unwrap_or_else(|e| e.into_inner())
}

/// Runs `f` with the render targets of the share group `group`.
pub fn with_group<T>(group: u64, f: impl FnOnce(&mut Targets) -> T) -> T {
    f(groups()
        .get_or_insert_with(Groups::new)
        .entry(group)
        .or_default())
}

/// Share group `group` ended (its last context was destroyed): its
/// targets, twins and the textures' targets went with it, and what the
/// layer knew of them goes too.
pub fn forget_group(group: u64) {
    if let Some(g) = groups().as_mut() {
        g.remove(&group);
    }
}

/// What decides a draw's target ([`eyes_of`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct Draw {
    /// The draw's vertices are moved per eye (rule 3).
    pub shifted: bool,
    /// It samples a texture with eyes (rule 1; [`Sampled::any`]).
    pub samples_stereo: bool,
    /// It is a blit from a target with eyes (rule 2).
    pub from_stereo: bool,
}

/// The texture units of a draw holding textures with eyes:
/// (unit, binding target, the program's texture, its right view).
#[derive(Clone, Debug, Default)]
pub struct Sampled {
    units: Vec<(u32, u32, u32, u32)>,
}

impl Sampled {
    /// Whether a unit holds a texture with eyes.
    pub fn any(&self) -> bool {
        !self.units.is_empty()
    }
}

/// The units holding textures with eyes now (none scanned when no
/// texture has eyes).
///
/// # Safety
/// The program's context is current on this thread.
pub unsafe fn sampled(targets: &Targets) -> Sampled {
    let mut s = Sampled::default();
    let Some(f) = api::common() else {
        return s;
    };
    if !targets
        .twins
        .iter()
        .any(|t| matches!(t.object, Object::Texture(_)))
    {
        return s;
    }
    // SAFETY: contract; one value per query; units below the maximum.
    unsafe {
        let (active, max) = (
            integer(f, GL_ACTIVE_TEXTURE),
            integer(f, GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS),
        );
        for unit in 0..max.clamp(0, UNITS) as u32 {
            (f.active_texture)(GL_TEXTURE0 + unit);
            for (binding, target) in [
                (GL_TEXTURE_BINDING_2D, GL_TEXTURE_2D),
                (GL_TEXTURE_BINDING_2D_MULTISAMPLE, GL_TEXTURE_2D_MULTISAMPLE),
            ] {
                let name = integer(f, binding) as u32;
                if name == 0 {
                    continue;
                }
                if let Some(t) = targets.twin(Object::Texture(name)) {
                    s.units.push((unit, target, name, t.right));
                }
            }
        }
        (f.active_texture)(active as u32);
    }
    s
}

/// For `eye`'s draw: the units of `sampled` hold that eye's texture (the
/// right view; the left eye's is the program's texture).
///
/// # Safety
/// The program's context is current on this thread.
pub unsafe fn bind_eye(sampled: &Sampled, eye: Eye) -> Bound<'_> {
    let bound = Bound {
        sampled,
        active: 0,
        on: eye == Eye::Right && sampled.any(),
    };
    if !bound.on {
        return bound;
    }
    let Some(f) = api::common() else {
        return Bound { on: false, ..bound };
    };
    // SAFETY: contract.
    unsafe {
        let active = integer(f, GL_ACTIVE_TEXTURE) as u32;
        for &(unit, target, _, right) in &sampled.units {
            (f.active_texture)(GL_TEXTURE0 + unit);
            (f.bind_texture)(target, right);
        }
        (f.active_texture)(active);
        Bound { active, ..bound }
    }
}

/// Units whose binding was exchanged for an eye: put back by
/// [`Bound::restore`].
#[derive(Debug)]
pub struct Bound<'a> {
    sampled: &'a Sampled,
    active: u32,
    on: bool,
}

impl Bound<'_> {
    /// Puts the program's bindings back.
    ///
    /// # Safety
    /// The context of [`bind_eye`] is current on this thread.
    pub unsafe fn restore(self) {
        if !self.on {
            return;
        }
        let Some(f) = api::common() else {
            return;
        };
        // SAFETY: contract.
        unsafe {
            for &(unit, target, name, _) in &self.sampled.units {
                (f.active_texture)(GL_TEXTURE0 + unit);
                (f.bind_texture)(target, name);
            }
            (f.active_texture)(self.active);
        }
    }
}

impl Targets {
    /// A number that changes whenever a texture gets or loses eyes: a
    /// scan of the units ([`sampled`]) holds while it is the same.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The calls for the group's contexts (None: its render targets
    /// stay mono).
    ///
    /// # Safety
    /// A context of the group is current on this thread.
    unsafe fn gl(&mut self) -> Option<Gl> {
        // SAFETY: contract.
        api::gl(unsafe { context_api(self) })
    }

    /// The target the layer names program object `o` by: a
    /// renderbuffer's; in OpenGL ES a texture's as it was defined (None
    /// where that was not seen); in desktop GL any (direct state access
    /// needs none).
    fn target_of(&self, o: Object) -> Option<u32> {
        match o {
            Object::Renderbuffer(_) => Some(GL_RENDERBUFFER as u32),
            Object::Texture(t) if self.api == Some(ContextApi::Es) => {
                self.es_targets.get(&t).copied()
            }
            Object::Texture(_) => Some(GL_TEXTURE_2D),
        }
    }

    fn twin(&self, o: Object) -> Option<&Twin> {
        self.twins.iter().find(|t| t.object == o)
    }

    fn stereo_at(&self, context: usize, fbo: u32) -> Option<usize> {
        self.stereo
            .iter()
            .position(|s| s.context == context && s.fbo == fbo)
    }

    /// The arrays of a target with eyes, as attachments (with the API of
    /// `eyes`, the window's).
    fn attachments(&self, s: &Stereo, eyes: &Attachments) -> Attachments {
        let mut colour = [0u32; COLOURS as usize];
        let (mut depth, mut depth_point, mut stencil) = (0, GL_DEPTH_ATTACHMENT, 0);
        for &(point, o) in &s.points {
            let array = self.twin(o).map_or(0, |t| t.array);
            match point {
                GL_DEPTH_ATTACHMENT | GL_DEPTH_STENCIL_ATTACHMENT => {
                    depth = array;
                    depth_point = point;
                }
                GL_STENCIL_ATTACHMENT => stencil = array,
                p => colour[(p - GL_COLOR_ATTACHMENT0) as usize] = array,
            }
        }
        eyes.of_target(colour, (depth, depth_point), stencil)
    }
}

/// The objects attached to `fbo` now, each at its point (a depth and
/// stencil of one object as GL_DEPTH_STENCIL_ATTACHMENT), and whether the
/// layer can give them eyes (Unsupported) — reading only what the
/// framebuffer names, so no query raises a GL error.
unsafe fn attached(f: &Gl, targets: &Targets, fbo: u32) -> (Vec<(u32, Object)>, bool) {
    let mut out = Vec::new();
    let mut supported = true;
    // SAFETY: contract of the callers; one value per query.
    unsafe {
        f.attachments(fbo, |at| {
            let points = (0..COLOURS)
                .map(|i| GL_COLOR_ATTACHMENT0 + i)
                .chain([GL_DEPTH_ATTACHMENT, GL_STENCIL_ATTACHMENT]);
            for point in points {
                let name = at(point, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME) as u32;
                if name == 0 {
                    continue;
                }
                let object = match at(point, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) {
                    GL_TEXTURE => {
                        if at(point, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL) != 0
                            || at(point, GL_FRAMEBUFFER_ATTACHMENT_LAYERED) != 0
                            || at(point, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER) != 0
                            || at(point, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE) != 0
                        {
                            supported = false;
                        }
                        Object::Texture(name)
                    }
                    GL_RENDERBUFFER => Object::Renderbuffer(name),
                    _ => {
                        supported = false;
                        continue;
                    }
                };
                supported &= targets.target_of(object).is_some();
                out.push((point, object));
            }
        });
    }
    // One object at depth and stencil: a packed depth/stencil attachment.
    let depth = out.iter().position(|&(p, _)| p == GL_DEPTH_ATTACHMENT);
    let stencil = out.iter().position(|&(p, _)| p == GL_STENCIL_ATTACHMENT);
    if let (Some(d), Some(s)) = (depth, stencil) {
        if out[d].1 == out[s].1 {
            out[d].0 = GL_DEPTH_STENCIL_ATTACHMENT;
            out.remove(s);
        }
    }
    (out, supported)
}

unsafe fn integer(f: &api::Common, pname: u32) -> i32 {
    let mut v = 0;
    // SAFETY: contract of the callers; one value.
    unsafe { (f.get_integerv)(pname, &mut v) };
    v
}

/// For an unsized internal format (what glTexImage2D keeps of GL_RGBA):
/// a format and type glTexImage3D takes it with; None for a sized one.
/// glCopyImageSubData copies only between equal unsized formats, so the
/// arrays of such a texture have its very format (mutable storage).
fn unsized_layout(format: u32) -> Option<(u32, u32)> {
    const UNSIGNED_BYTE: u32 = 0x1401;
    const UNSIGNED_INT: u32 = 0x1405;
    const UNSIGNED_INT_24_8: u32 = 0x84FA;
    Some(match format as i32 {
        GL_RGBA | 4 => (GL_RGBA as u32, UNSIGNED_BYTE),
        GL_RGB | 3 => (GL_RGB as u32, UNSIGNED_BYTE),
        GL_RG => (GL_RG as u32, UNSIGNED_BYTE),
        GL_RED => (GL_RED as u32, UNSIGNED_BYTE),
        GL_LUMINANCE | 1 => (GL_LUMINANCE as u32, UNSIGNED_BYTE),
        GL_LUMINANCE_ALPHA | 2 => (GL_LUMINANCE_ALPHA as u32, UNSIGNED_BYTE),
        GL_ALPHA => (GL_ALPHA as u32, UNSIGNED_BYTE),
        GL_DEPTH_COMPONENT => (GL_DEPTH_COMPONENT as u32, UNSIGNED_INT),
        GL_DEPTH_STENCIL => (GL_DEPTH_STENCIL as u32, UNSIGNED_INT_24_8),
        _ => return None,
    })
}

/// The shape of `o` now, named by `target` ([`Targets::target_of`]);
/// None where it has no storage or no known target. A texture's levels:
/// its immutable count, else the whole chain for colour (a program may
/// make mipmaps later), one for depth and stencil.
unsafe fn shape(f: &Gl, o: Object, target: Option<u32>) -> Option<Shape> {
    // SAFETY: contract of the callers.
    unsafe {
        let s = match o {
            Object::Texture(t) => {
                let t = (t, target?);
                let (width, height) = (f.level(t, GL_TEXTURE_WIDTH), f.level(t, GL_TEXTURE_HEIGHT));
                if f.level(t, GL_TEXTURE_DEPTH) != 1 {
                    return None;
                }
                let samples = f.level(t, GL_TEXTURE_SAMPLES);
                let depth_or_stencil = f.level(t, GL_TEXTURE_DEPTH_SIZE) > 0
                    || f.level(t, GL_TEXTURE_STENCIL_SIZE) > 0;
                let levels = if f.texture_int(t, GL_TEXTURE_IMMUTABLE_FORMAT) != 0 {
                    f.texture_int(t, GL_TEXTURE_IMMUTABLE_LEVELS)
                } else if depth_or_stencil || samples > 0 {
                    1
                } else {
                    32 - (width.max(height).max(1) as u32).leading_zeros() as i32
                };
                Shape {
                    format: f.level(t, GL_TEXTURE_INTERNAL_FORMAT) as u32,
                    width,
                    height,
                    samples,
                    fixed_locations: samples == 0
                        || f.level(t, GL_TEXTURE_FIXED_SAMPLE_LOCATIONS) != 0,
                    levels: levels.max(1),
                }
            }
            Object::Renderbuffer(rb) => Shape {
                format: f.renderbuffer(rb, GL_RENDERBUFFER_INTERNAL_FORMAT) as u32,
                width: f.renderbuffer(rb, GL_RENDERBUFFER_WIDTH),
                height: f.renderbuffer(rb, GL_RENDERBUFFER_HEIGHT),
                samples: f.renderbuffer(rb, GL_RENDERBUFFER_SAMPLES),
                fixed_locations: true,
                levels: 1,
            },
        };
        (s.width > 0 && s.height > 0).then_some(s)
    }
}

/// What `attached` allows (rule 3's light test against the window's
/// size `window`).
unsafe fn structure(
    f: &Gl,
    targets: &Targets,
    attached: &[(u32, Object)],
    supported: bool,
    window: (i32, i32),
) -> Structure {
    if !supported || attached.is_empty() {
        return Structure::Unsupported;
    }
    // SAFETY: contract of the callers.
    unsafe {
        let mut colours = attached
            .iter()
            .filter(|&&(p, _)| (GL_COLOR_ATTACHMENT0..GL_COLOR_ATTACHMENT0 + COLOURS).contains(&p))
            .map(|&(_, o)| shape(f, o, targets.target_of(o)))
            .peekable();
        if colours.peek().is_none() {
            return Structure::Light;
        }
        let mut light = true;
        for s in colours {
            let Some(s) = s else {
                return Structure::Unsupported;
            };
            light &= s.width == s.height && (s.width, s.height) != window;
        }
        if attached
            .iter()
            .any(|&(_, o)| shape(f, o, targets.target_of(o)).is_none())
        {
            return Structure::Unsupported;
        }
        if light {
            Structure::Light
        } else {
            Structure::Plain
        }
    }
}

/// The eyes of the draw framebuffer `fbo` of `context` for a draw of
/// kind `draw`: its arrays when it has eyes or gets them now by the
/// policy (module docs), else None (the draw is mono). `eyes`: the
/// window's eyes (their API and size).
///
/// # Safety
/// The program's context `context` is current on this thread.
pub unsafe fn eyes_of(
    targets: &mut Targets,
    context: usize,
    fbo: u32,
    eyes: &Attachments,
    draw: Draw,
) -> Option<Attachments> {
    if fbo == 0 {
        return None;
    }
    // SAFETY: contract.
    let gl = unsafe { targets.gl() }?;
    let f = &gl;
    // SAFETY: contract.
    unsafe {
        if let Some(i) = targets
            .stereo_at(context, fbo)
            .filter(|&i| targets.stereo[i].stale)
        {
            let s = targets.stereo.swap_remove(i);
            restore_program_objects(f, &s);
        }
        let (now, supported) = attached(f, targets, fbo);
        if let Some(i) = targets.stereo_at(context, fbo) {
            let ours = |&(p, o): &(u32, Object)| {
                targets
                    .twin(o)
                    .is_some_and(|t| now.contains(&(p, Object::Texture(t.array))))
            };
            if targets.stereo[i].points.iter().all(ours)
                && now.len() == targets.stereo[i].points.len()
            {
                let s = &targets.stereo[i];
                let a = targets.attachments(s, eyes);
                let objects: Vec<Object> = s.points.iter().map(|&(_, o)| o).collect();
                for t in targets
                    .twins
                    .iter_mut()
                    .filter(|t| objects.contains(&t.object))
                {
                    t.dirty = true;
                }
                return Some(a);
            }
            // The program attached something else: its framebuffer now.
            // Points still holding a twin's array get the program's object
            // back.
            let s = targets.stereo.swap_remove(i);
            put_back(f, targets, &s, &now);
            return eyes_of(targets, context, fbo, eyes, draw);
        }
        let known = targets
            .looked
            .iter()
            .find(|l| l.context == context && l.fbo == fbo && l.attached == now)
            .map(|l| l.structure);
        let structure = match known {
            Some(s) => s,
            None => {
                let window = (eyes.colour(), GL_TEXTURE_2D_ARRAY);
                let window = (
                    f.level(window, GL_TEXTURE_WIDTH),
                    f.level(window, GL_TEXTURE_HEIGHT),
                );
                let s = structure(f, targets, &now, supported, window);
                targets
                    .looked
                    .retain(|l| (l.context, l.fbo) != (context, fbo));
                targets.looked.push(Looked {
                    context,
                    fbo,
                    attached: now.clone(),
                    structure: s,
                });
                s
            }
        };
        let wanted = match structure {
            Structure::Unsupported => false,
            Structure::Light => draw.samples_stereo || draw.from_stereo,
            Structure::Plain => draw.samples_stereo || draw.from_stereo || draw.shifted,
        };
        if !wanted {
            return None;
        }
        match stereoize(f, targets, context, fbo, &now) {
            Some(s) => {
                targets
                    .looked
                    .retain(|l| (l.context, l.fbo) != (context, fbo));
                let a = targets.attachments(&s, eyes);
                targets.stereo.push(s);
                Some(a)
            }
            None => {
                if let Some(l) = targets
                    .looked
                    .iter_mut()
                    .find(|l| l.context == context && l.fbo == fbo)
                {
                    l.structure = Structure::Unsupported;
                }
                None
            }
        }
    }
}

/// What the group's contexts are (asked once).
///
/// # Safety
/// A context of the group is current on this thread.
pub unsafe fn context_api(targets: &mut Targets) -> ContextApi {
    // SAFETY: contract.
    *targets
        .api
        .get_or_insert_with(|| unsafe { api::context_api() })
}

/// The program defined storage of `texture` through `target` (a
/// glTexImage2D, glTexStorage2D(Multisample), glCopyTexImage2D naming
/// the texture bound there): OpenGL ES keeps the target, the only way
/// the layer may learn it (asked by binding, a wrong target raises an
/// error the program would see).
///
/// # Safety
/// A context of the group is current on this thread.
pub unsafe fn texture_defined(targets: &mut Targets, texture: u32, target: u32) {
    // SAFETY: contract.
    let api = unsafe { context_api(targets) };
    if api == ContextApi::Es
        && texture != 0
        && matches!(target, GL_TEXTURE_2D | GL_TEXTURE_2D_MULTISAMPLE)
    {
        targets.es_targets.insert(texture, target);
    }
}

/// The program deleted `objects`: their eyes go ([`forget`]), and what
/// the layer knew of them.
///
/// # Safety
/// The program's context `context` is current on this thread.
pub unsafe fn deleted(targets: &mut Targets, context: usize, objects: &[Object]) {
    for o in objects {
        if let Object::Texture(t) = o {
            targets.es_targets.remove(t);
        }
    }
    // SAFETY: contract.
    unsafe { forget(targets, context, objects) }
}

/// The eyes of `fbo` of `context` when it has eyes already (to read from
/// it eye by eye: a blit out of it), else None. `eyes`: the window's.
pub fn known(
    targets: &Targets,
    context: usize,
    fbo: u32,
    eyes: &Attachments,
) -> Option<Attachments> {
    let i = targets.stereo_at(context, fbo)?;
    Some(targets.attachments(&targets.stereo[i], eyes))
}

/// The size of `context`'s target `fbo` with eyes (None: not one).
pub fn size(targets: &Targets, context: usize, fbo: u32) -> Option<(u32, u32)> {
    let s = &targets.stereo[targets.stereo_at(context, fbo)?];
    s.points.iter().find_map(|&(_, o)| {
        let t = targets.twin(o)?;
        Some((t.shape.width.max(0) as u32, t.shape.height.max(0) as u32))
    })
}

/// Gives `fbo` eyes: every attached object a twin (made, or the one it
/// has when its shape is still the object's), the arrays attached
/// layered. None, with the program's objects attached again, where the
/// framebuffer is then incomplete.
unsafe fn stereoize(
    f: &Gl,
    targets: &mut Targets,
    context: usize,
    fbo: u32,
    now: &[(u32, Object)],
) -> Option<Stereo> {
    // SAFETY: contract of the callers; objects made here are named by GL.
    unsafe {
        for &(_, o) in now {
            let shape = shape(f, o, targets.target_of(o))?;
            match targets.twins.iter().position(|t| t.object == o) {
                Some(i) if targets.twins[i].shape == shape => {}
                found => {
                    if let Some(i) = found {
                        release(f, targets.twins.swap_remove(i));
                    }
                    targets.generation += 1;
                    targets.twins.push(make_twin(f, o, shape)?);
                }
            }
        }
        let s = Stereo {
            context,
            fbo,
            points: now.to_vec(),
            stale: false,
        };
        for &(point, o) in now {
            let array = targets.twin(o).expect("made above").array;
            f.framebuffer_texture(fbo, point, array, 0);
        }
        if !f.complete(fbo) {
            put_back(f, targets, &s, &[]);
            return None;
        }
        for t in targets
            .twins
            .iter_mut()
            .filter(|t| now.iter().any(|&(_, o)| o == t.object))
        {
            t.dirty = true;
        }
        Some(s)
    }
}

/// A twin of `o` (module docs), both layers holding `o`'s level 0. None
/// where the driver refuses (checked without raising a GL error: made
/// storage is immutable, or has the size asked) or the format is one of
/// no known layout.
unsafe fn make_twin(f: &Gl, o: Object, shape: Shape) -> Option<Twin> {
    let unsized_format = unsized_layout(shape.format);
    // SAFETY: contract of the callers; names made here.
    unsafe {
        let mut t = Twin {
            object: o,
            shape,
            array: 0,
            right: 0,
            view: unsized_format.is_none(),
            dirty: false,
        };
        let (array_target, view_target) = if shape.samples > 0 {
            (GL_TEXTURE_2D_MULTISAMPLE_ARRAY, GL_TEXTURE_2D_MULTISAMPLE)
        } else {
            (GL_TEXTURE_2D_ARRAY, GL_TEXTURE_2D)
        };
        match unsized_format {
            None => {
                t.array = f.new_texture(array_target);
                f.storage(
                    (t.array, array_target),
                    shape.levels,
                    (shape.samples, shape.fixed_locations),
                    shape.format,
                    (shape.width, shape.height, 2),
                );
                (f.c.gen_textures)(1, &mut t.right);
                (f.c.texture_view)(
                    t.right,
                    view_target,
                    t.array,
                    shape.format,
                    0,
                    shape.levels as u32,
                    1,
                    1,
                );
                // A view made (no error raised) has immutable storage.
                if f.texture_int((t.array, array_target), GL_TEXTURE_IMMUTABLE_FORMAT) == 0
                    || f.texture_int((t.right, view_target), GL_TEXTURE_IMMUTABLE_FORMAT) == 0
                {
                    release(f, t);
                    return None;
                }
            }
            Some((format, kind)) if shape.samples == 0 => {
                t.array = f.new_texture(GL_TEXTURE_2D_ARRAY);
                t.right = f.new_texture(GL_TEXTURE_2D);
                // Mutable storage is given through a binding: the active
                // unit's and the unpack buffer's are put back.
                let pbo = f.integer(GL_PIXEL_UNPACK_BUFFER_BINDING) as u32;
                let was = [
                    f.integer(GL_TEXTURE_BINDING_2D_ARRAY) as u32,
                    f.integer(GL_TEXTURE_BINDING_2D) as u32,
                ];
                (f.c.bind_buffer)(GL_PIXEL_UNPACK_BUFFER, 0);
                (f.c.bind_texture)(GL_TEXTURE_2D_ARRAY, t.array);
                (f.c.bind_texture)(GL_TEXTURE_2D, t.right);
                for l in 0..shape.levels {
                    let (w, h) = ((shape.width >> l).max(1), (shape.height >> l).max(1));
                    let none = std::ptr::null();
                    let internal = shape.format as i32;
                    (f.c.tex_image_3d)(
                        GL_TEXTURE_2D_ARRAY,
                        l,
                        internal,
                        w,
                        h,
                        2,
                        0,
                        format,
                        kind,
                        none,
                    );
                    (f.c.tex_image_2d)(GL_TEXTURE_2D, l, internal, w, h, 0, format, kind, none);
                }
                (f.c.bind_texture)(GL_TEXTURE_2D_ARRAY, was[0]);
                (f.c.bind_texture)(GL_TEXTURE_2D, was[1]);
                (f.c.bind_buffer)(GL_PIXEL_UNPACK_BUFFER, pbo);
                let array = (t.array, GL_TEXTURE_2D_ARRAY);
                let right = (t.right, GL_TEXTURE_2D);
                for tex in [array, right] {
                    f.set_texture_int(tex, GL_TEXTURE_MAX_LEVEL, shape.levels - 1);
                }
                if f.level(array, GL_TEXTURE_WIDTH) != shape.width
                    || f.level(right, GL_TEXTURE_WIDTH) != shape.width
                {
                    release(f, t);
                    return None;
                }
            }
            Some(_) => return None,
        }
        let (name, target) = source(o, &shape);
        complete_for(f, o, &shape, || {
            for layer in 0..2 {
                copy_layer(
                    f,
                    (name, target, 0, 0),
                    (t.array, array_target, 0, layer),
                    (0, 0, shape.width, shape.height),
                );
            }
            if !t.view {
                copy_layer(
                    f,
                    (name, target, 0, 0),
                    (t.right, GL_TEXTURE_2D, 0, 0),
                    (0, 0, shape.width, shape.height),
                );
            }
        });
        copy_sampling(f, o, &shape, t.right);
        Some(t)
    }
}

/// One layer of one level of an image: name, glCopyImageSubData
/// target, level, layer.
type Layer = (u32, u32, i32, i32);

/// glCopyImageSubData of rectangle (x, y, width, height) from `from` to
/// the same place of `to`.
///
/// # Safety
/// A context of the objects' share group is current; the rectangle is
/// inside both, of one format class.
unsafe fn copy_layer(f: &Gl, from: Layer, to: Layer, (x, y, w, h): (i32, i32, i32, i32)) {
    // SAFETY: contract.
    unsafe { copy_rect(f, (from, (x, y)), (to, (x, y)), (w, h)) }
}

/// The name and glCopyImageSubData target of a program object of `shape`.
fn source(o: Object, shape: &Shape) -> (u32, u32) {
    match o {
        Object::Texture(t) if shape.samples > 0 => (t, GL_TEXTURE_2D_MULTISAMPLE),
        Object::Texture(t) => (t, GL_TEXTURE_2D),
        Object::Renderbuffer(rb) => (rb, GL_RENDERBUFFER as u32),
    }
}

/// Runs `f` (a glCopyImageSubData to or from the program's texture)
/// with the texture complete: Mesa copies only between complete textures,
/// and a program's render texture with a mipmap filter has no mipmaps
/// until it makes them (glGenerateMipmap after drawing). Its minification
/// filter is made GL_LINEAR meanwhile (which needs the base level only)
/// and put back after. A multisample texture has no filters.
unsafe fn complete_for(f: &Gl, o: Object, shape: &Shape, f_copy: impl FnOnce()) {
    const GL_TEXTURE_MIN_FILTER: u32 = 0x2801;
    const GL_LINEAR: i32 = 0x2601;
    const GL_NEAREST: i32 = 0x2600;
    if !matches!(o, Object::Texture(_)) || shape.samples > 0 {
        return f_copy();
    }
    let t = source(o, shape);
    // SAFETY: contract of the callers.
    unsafe {
        let min = f.texture_int(t, GL_TEXTURE_MIN_FILTER);
        let mipmapped = min != GL_LINEAR && min != GL_NEAREST && min != 0;
        if mipmapped {
            f.set_texture_int(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        }
        f_copy();
        if mipmapped {
            f.set_texture_int(t, GL_TEXTURE_MIN_FILTER, min);
        }
    }
}

/// The sampling state of the program's texture `o` (of `shape`) on its
/// right view `right` (a multisample texture has none).
unsafe fn copy_sampling(f: &Gl, o: Object, shape: &Shape, right: u32) {
    if matches!(o, Object::Texture(_)) && shape.samples == 0 {
        // SAFETY: contract of the callers; valid pnames of both.
        unsafe { f.copy_parameters(source(o, shape), (right, GL_TEXTURE_2D), &SAMPLING) }
    }
}

/// Attaches the program's objects of `s` again at the points that still
/// hold their twins' arrays (`now`: what is attached; empty: every
/// point).
unsafe fn put_back(f: &Gl, targets: &Targets, s: &Stereo, now: &[(u32, Object)]) {
    for &(point, o) in &s.points {
        let array = targets.twin(o).map_or(0, |t| t.array);
        if !now.is_empty() && !now.contains(&(point, Object::Texture(array))) {
            continue;
        }
        // SAFETY: contract of the callers.
        unsafe {
            match o {
                Object::Texture(t) => f.framebuffer_texture(s.fbo, point, t, 0),
                Object::Renderbuffer(rb) => f.framebuffer_renderbuffer(s.fbo, point, rb),
            }
        }
    }
}

/// Deletes the layer's objects of `t`.
unsafe fn release(f: &Gl, t: Twin) {
    let names: Vec<u32> = [t.array, t.right].into_iter().filter(|&n| n != 0).collect();
    // SAFETY: contract of the callers; names made here.
    unsafe { (f.c.delete_textures)(names.len() as i32, names.as_ptr()) };
}

/// Before a draw of `context` into `drawing` (its draw framebuffer), and
/// before anything else reads a texture (`drawing` 0): the program's
/// objects whose twins were drawn into since get their left eye, but
/// those of `drawing` itself.
///
/// # Safety
/// The program's context `context` is current on this thread.
pub unsafe fn resolve(targets: &mut Targets, context: usize, drawing: u32) {
    // SAFETY: contract.
    let Some(gl) = (unsafe { targets.gl() }) else {
        return;
    };
    let f = &gl;
    let busy: Vec<Object> = targets
        .stereo_at(context, drawing)
        .map(|i| targets.stereo[i].points.iter().map(|&(_, o)| o).collect())
        .unwrap_or_default();
    for t in targets
        .twins
        .iter_mut()
        .filter(|t| t.dirty && !busy.contains(&t.object))
    {
        // SAFETY: contract; both are of one shape (checked against the
        // object: a program that redefined it loses the twin at its next
        // target decision, and is not written into meanwhile).
        unsafe {
            let (name, target) = source(t.object, &t.shape);
            if shape(f, t.object, Some(target)) != Some(t.shape) {
                continue;
            }
            let array_target = if t.shape.samples > 0 {
                GL_TEXTURE_2D_MULTISAMPLE_ARRAY
            } else {
                GL_TEXTURE_2D_ARRAY
            };
            complete_for(f, t.object, &t.shape, || {
                copy_layer(
                    f,
                    (t.array, array_target, 0, 0),
                    (name, target, 0, 0),
                    (0, 0, t.shape.width, t.shape.height),
                )
            });
            if !t.view {
                copy_layer(
                    f,
                    (t.array, array_target, 0, 1),
                    (t.right, GL_TEXTURE_2D, 0, 0),
                    (0, 0, t.shape.width, t.shape.height),
                );
            }
            copy_sampling(f, t.object, &t.shape, t.right);
        }
        t.dirty = false;
    }
}

/// After the program's glGenerateMipmap of `texture`: its right view
/// gets its mipmaps too (made from layer 1). The caller resolved it
/// first, so the program's own mipmaps are the left eye's.
///
/// # Safety
/// The program's context is current on this thread.
pub unsafe fn mipmaps_made(targets: &mut Targets, texture: u32) {
    // SAFETY: contract.
    let Some(gl) = (unsafe { targets.gl() }) else {
        return;
    };
    let f = &gl;
    if let Some(t) = targets.twin(Object::Texture(texture)) {
        if t.shape.levels > 1 && t.shape.samples == 0 {
            // SAFETY: contract; the array (its view) or the right texture
            // is complete at level 0.
            unsafe {
                f.generate_mipmap(if t.view {
                    (t.array, GL_TEXTURE_2D_ARRAY)
                } else {
                    (t.right, GL_TEXTURE_2D)
                })
            };
        }
    }
}

/// `objects` lose their eyes (the program deleted them, or gave one new
/// contents outside draws): their twins go, and the targets that had
/// them are the program's again — at once in `context` (current on this
/// thread), at their context's next draw into them elsewhere.
///
/// # Safety
/// The program's context `context` is current on this thread.
pub unsafe fn forget(targets: &mut Targets, context: usize, objects: &[Object]) {
    if !targets.twins.iter().any(|t| objects.contains(&t.object)) {
        return;
    }
    // SAFETY: contract.
    let Some(gl) = (unsafe { targets.gl() }) else {
        return;
    };
    let f = &gl;
    let mut kept = Vec::new();
    for s in std::mem::take(&mut targets.stereo) {
        if !s.points.iter().any(|(_, o)| objects.contains(o)) {
            kept.push(s);
        } else if s.context == context {
            // SAFETY: contract.
            unsafe { restore_program_objects(f, &s) };
        } else {
            kept.push(Stereo { stale: true, ..s });
        }
    }
    targets.stereo = kept;
    targets
        .looked
        .retain(|l| !l.attached.iter().any(|(_, o)| objects.contains(o)));
    let (gone, kept): (Vec<Twin>, Vec<Twin>) = std::mem::take(&mut targets.twins)
        .into_iter()
        .partition(|t| objects.contains(&t.object));
    targets.twins = kept;
    targets.generation += 1;
    for t in gone {
        // SAFETY: contract.
        unsafe { release(f, t) };
    }
}

/// Attaches the program's own objects of `s` again (detaching those it
/// deleted since, as GL detached them where it could).
unsafe fn restore_program_objects(f: &Gl, s: &Stereo) {
    for &(point, o) in &s.points {
        // SAFETY: contract of the callers.
        unsafe {
            match o {
                Object::Texture(t) => {
                    let t = if (f.c.is_texture)(t) != 0 { t } else { 0 };
                    f.framebuffer_texture(s.fbo, point, t, 0)
                }
                Object::Renderbuffer(rb) => {
                    let rb = if (f.c.is_renderbuffer)(rb) != 0 {
                        rb
                    } else {
                        0
                    };
                    f.framebuffer_renderbuffer(s.fbo, point, rb)
                }
            }
        }
    }
}

/// After the program's glCopyTex(Sub)Image2D into level 0 of `texture`
/// (rectangle `w` × `h` at (`xoff`, `yoff`)) from (`x`, `y`) of a read
/// framebuffer with eyes, `source` (the copy read its left eye): the
/// texture gets eyes, its right eye copied from the source's right eye.
///
/// # Safety
/// The program's context `context` is current on this thread, with the
/// framebuffer of `source` bound for reading.
pub unsafe fn copied_from_eyes(
    targets: &mut Targets,
    context: usize,
    texture: u32,
    source: &Attachments,
    (xoff, yoff, x, y, w, h): (i32, i32, i32, i32, i32, i32),
) {
    // SAFETY: contract.
    let Some(gl) = (unsafe { targets.gl() }) else {
        return;
    };
    let f = &gl;
    let o = Object::Texture(texture);
    // SAFETY: contract; names made here.
    unsafe {
        let Some(shape) = shape(f, o, targets.target_of(o)).filter(|s| s.samples == 0) else {
            return forget(targets, context, &[o]);
        };
        let Some(t) = twin_after_copy(f, targets, context, o, shape, (xoff, yoff, w, h)) else {
            return;
        };
        source.attach(GL_READ_FRAMEBUFFER, Some(Eye::Right));
        f.copy_sub_image_2d((t.right, GL_TEXTURE_2D), 0, (xoff, yoff), (x, y, w, h));
        source.attach(GL_READ_FRAMEBUFFER, None);
        if !t.view {
            copy_layer(
                f,
                (t.right, GL_TEXTURE_2D, 0, 0),
                (t.array, GL_TEXTURE_2D_ARRAY, 0, 1),
                (xoff, yoff, w, h),
            );
        }
    }
}

/// After the program's copy into rectangle (x, y, w, h) of level 0 of
/// `o` (now of `shape`): its twin, layer 0 given what the copy wrote, or
/// a new one (both layers holding the object) where it had none of that
/// shape. None where the driver makes none.
///
/// # Safety
/// The program's context `context` is current on this thread.
unsafe fn twin_after_copy<'t>(
    f: &Gl,
    targets: &'t mut Targets,
    context: usize,
    o: Object,
    shape: Shape,
    rect: (i32, i32, i32, i32),
) -> Option<&'t Twin> {
    // SAFETY: contract; names made here.
    unsafe {
        match targets.twins.iter().position(|t| t.object == o) {
            Some(i) if targets.twins[i].shape == shape => {
                let t = &targets.twins[i];
                let (name, target) = source(o, &shape);
                let array_target = if shape.samples > 0 {
                    GL_TEXTURE_2D_MULTISAMPLE_ARRAY
                } else {
                    GL_TEXTURE_2D_ARRAY
                };
                complete_for(f, o, &shape, || {
                    copy_layer(f, (name, target, 0, 0), (t.array, array_target, 0, 0), rect)
                });
            }
            found => {
                if found.is_some() {
                    forget(targets, context, &[o]);
                }
                let t = make_twin(f, o, shape)?;
                targets.twins.push(t);
                targets.generation += 1;
            }
        }
    }
    targets.twin(o)
}

/// One image of a glCopyImageSubData: name, target, level, x, y, z.
pub type Image = (u32, u32, i32, i32, i32, i32);

/// The object of an image of glCopyImageSubData that can have eyes (a
/// 2D or 2D multisample texture or a renderbuffer; its level 0 and layer
/// 0 where it is read).
fn image_object((name, target, level, _, _, z): Image) -> Option<Object> {
    match target {
        _ if level != 0 || z != 0 => None,
        GL_TEXTURE_2D | GL_TEXTURE_2D_MULTISAMPLE => Some(Object::Texture(name)),
        t if t == GL_RENDERBUFFER as u32 => Some(Object::Renderbuffer(name)),
        _ => None,
    }
}

/// The shape of the object of `image` ([`image_object`]); None where it
/// has none, or (OpenGL ES) where the target the program named is not
/// the one the layer saw it defined with (asking by binding would raise
/// an error the program could see).
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn image_shape(f: &Gl, targets: &Targets, image: Image) -> Option<Shape> {
    let o = image_object(image)?;
    let target = targets.target_of(o).filter(|&t| !f.es() || t == image.1)?;
    // SAFETY: contract.
    unsafe { shape(f, o, Some(target)) }
}

/// After the program's glCopyImageSubData of `w` × `h` × `depth` from
/// `from` to `to` (the copy read the left eye of a source with eyes,
/// which [`resolve`] put into the program's object): a destination copied
/// from a source with eyes gets eyes of its own, its right eye copied from
/// the source's (Blender copies its viewport's depth so its overlays can
/// test against it: the right eye's overlays must test against the right
/// eye's depth); a destination copied from a mono source is one picture
/// again.
///
/// # Safety
/// The program's context `context` is current on this thread.
pub unsafe fn copied_image(
    targets: &mut Targets,
    context: usize,
    from: Image,
    to: Image,
    (w, h, depth): (i32, i32, i32),
) {
    // SAFETY: contract.
    let Some(gl) = (unsafe { targets.gl() }) else {
        return;
    };
    let f = &gl;
    let dst = match to.1 {
        t if t == GL_RENDERBUFFER as u32 => Object::Renderbuffer(to.0),
        _ => Object::Texture(to.0),
    };
    let from_eyes = image_object(from)
        .filter(|_| (to.2, to.5) == (0, 0))
        .and_then(|o| targets.twin(o))
        .map(|t| (t.array, t.shape));
    // SAFETY: contract; names made here.
    unsafe {
        let to_shape = image_shape(f, targets, to);
        // A copy GL refuses (outside either image, more than one layer of
        // a 2D image, depth or stencil between other formats) changed
        // nothing: neither does the layer.
        let refused = |s: &Shape, (x, y): (i32, i32)| depth != 1 || !inside(s, (x, y, w, h));
        let from_shape = image_shape(f, targets, from);
        if to_shape.is_some_and(|s| refused(&s, (to.3, to.4)))
            || from_shape.is_some_and(|s| refused(&s, (from.3, from.4)))
            || matches!((from_shape, to_shape), (Some(a), Some(b))
                if a.format != b.format && (depth_or_stencil(a.format) || depth_or_stencil(b.format)))
        {
            return;
        }
        let Some((array, eyes_shape)) = from_eyes else {
            return forget(targets, context, &[dst]);
        };
        let Some(shape) = to_shape.filter(|s| s.samples == eyes_shape.samples) else {
            return forget(targets, context, &[dst]);
        };
        let array_target = if shape.samples > 0 {
            GL_TEXTURE_2D_MULTISAMPLE_ARRAY
        } else {
            GL_TEXTURE_2D_ARRAY
        };
        let Some(t) = twin_after_copy(f, targets, context, dst, shape, (to.3, to.4, w, h)) else {
            return;
        };
        copy_rect(
            f,
            ((array, array_target, 0, 1), (from.3, from.4)),
            ((t.array, array_target, 0, 1), (to.3, to.4)),
            (w, h),
        );
        if !t.view {
            copy_rect(
                f,
                ((array, array_target, 0, 1), (from.3, from.4)),
                ((t.right, GL_TEXTURE_2D, 0, 0), (to.3, to.4)),
                (w, h),
            );
        }
    }
}

/// Whether rectangle (x, y, w, h) is a non-empty part of level 0 of
/// `shape`.
fn inside(shape: &Shape, (x, y, w, h): (i32, i32, i32, i32)) -> bool {
    let end = |at: i32, size: i32| i64::from(at) + i64::from(size);
    w > 0
        && h > 0
        && x >= 0
        && y >= 0
        && end(x, w) <= i64::from(shape.width)
        && end(y, h) <= i64::from(shape.height)
}

/// Whether `format` is a depth or stencil format (glCopyImageSubData
/// copies those only to the very same format).
fn depth_or_stencil(format: u32) -> bool {
    matches!(
        format,
        0x1902 // GL_DEPTH_COMPONENT
            | 0x84F9 // GL_DEPTH_STENCIL
            | 0x81A5 // GL_DEPTH_COMPONENT16
            | 0x81A6 // GL_DEPTH_COMPONENT24
            | 0x81A7 // GL_DEPTH_COMPONENT32
            | 0x8CAC // GL_DEPTH_COMPONENT32F
            | 0x88F0 // GL_DEPTH24_STENCIL8
            | 0x8CAD // GL_DEPTH32F_STENCIL8
            | 0x8D48 // GL_STENCIL_INDEX8
    )
}

/// glCopyImageSubData of a `w` × `h` rectangle from (fx, fy) of one
/// layer to (tx, ty) of another.
///
/// # Safety
/// As [`copy_layer`].
unsafe fn copy_rect(
    f: &Gl,
    (from, (fx, fy)): (Layer, (i32, i32)),
    (to, (tx, ty)): (Layer, (i32, i32)),
    (w, h): (i32, i32),
) {
    // SAFETY: contract.
    unsafe {
        (f.c.copy_image_sub_data)(
            from.0, from.1, from.2, fx, fy, from.3, to.0, to.1, to.2, tx, ty, to.3, w, h, 1,
        )
    }
}

/// The program deleted framebuffers `fbos` of `context`.
pub fn framebuffers_deleted(targets: &mut Targets, context: usize, fbos: &[u32]) {
    targets
        .stereo
        .retain(|s| s.context != context || !fbos.contains(&s.fbo));
    targets
        .looked
        .retain(|l| l.context != context || !fbos.contains(&l.fbo));
}

/// The render target with eyes and depth a perspective draw (or one whose
/// projection is not known, where no known one came) reached last on a
/// measured frame: its arrays and size, and how the scene was drawn; with
/// its depth's left eye copied where a later draw may overwrite it.
#[derive(Debug, Default)]
pub struct SceneTarget {
    /// The target and its scene.
    pub drawn: Option<(Attachments, (u32, u32), crate::auto::converge::Scene)>,
    /// The copy of its left eye's depth.
    pub copy: DepthCopy,
    /// `copy` holds the scene's depth (a later draw came after it).
    pub copied: bool,
    /// The program cleared the target's depth after the scene (drawn in
    /// this viewport), copied first: a perspective draw into it in
    /// another viewport is an overlay, not the scene.
    pub cleared: Option<(i32, i32, i32, i32)>,
    /// `--auto=depth`: a draw that is not the scene's (a flat one, or a
    /// perspective one in another viewport after a depth clear: an
    /// orientation gizmo, its labels) came into the target after the
    /// scene; this colour array's right-eye layer holds the scene's
    /// colour from before it ([`copy_left_colour`]), so that the present
    /// can tell the pixels such draws changed.
    pub colour_kept: Option<u32>,
}

/// A copy of an eye's depth, kept by automatic convergence: a later
/// draw of the frame (a full-screen pass with depth writes over the
/// scene) may overwrite the depth it measures, so the left eye's depth is
/// copied when such a draw comes ([`copy_left_depth`]).
#[derive(Debug, Default)]
pub struct DepthCopy {
    /// A 2D texture (0: none yet).
    pub texture: u32,
    format: u32,
    size: (i32, i32),
}

/// Copies layer 0 (the left eye) of the colour array `array` into its
/// layer 1 (`--auto=depth`, where the right eye's layer is the layer's
/// own: [`crate::auto::from_depth`]); false where it cannot be.
///
/// # Safety
/// The program's context is current on this thread; `array` is a 2D
/// array texture of its share group (the window's eyes').
pub unsafe fn copy_left_colour(api: ContextApi, array: u32) -> bool {
    let Some(gl) = api::gl(api) else {
        return false;
    };
    let f = &gl;
    // SAFETY: contract.
    unsafe {
        let tex = (array, GL_TEXTURE_2D_ARRAY);
        let size = (
            f.level(tex, GL_TEXTURE_WIDTH),
            f.level(tex, GL_TEXTURE_HEIGHT),
        );
        if array == 0 || size.0 <= 0 || size.1 <= 0 || f.level(tex, GL_TEXTURE_DEPTH) < 2 {
            return false;
        }
        copy_layer(
            f,
            (array, GL_TEXTURE_2D_ARRAY, 0, 0),
            (array, GL_TEXTURE_2D_ARRAY, 0, 1),
            (0, 0, size.0, size.1),
        );
    }
    true
}

/// Copies layer 0 (the left eye) of the depth array `array` into `copy`
/// (made, or made again for another size or format); false where it
/// cannot be.
///
/// # Safety
/// The program's context is current on this thread; `array` is a 2D
/// array texture of its share group (the window's eyes' or a twin's).
pub unsafe fn copy_left_depth(api: ContextApi, array: u32, copy: &mut DepthCopy) -> bool {
    let Some(gl) = api::gl(api) else {
        return false;
    };
    let f = &gl;
    // SAFETY: contract; names made here.
    unsafe {
        let tex = (array, GL_TEXTURE_2D_ARRAY);
        let format = f.level(tex, GL_TEXTURE_INTERNAL_FORMAT) as u32;
        let size = (
            f.level(tex, GL_TEXTURE_WIDTH),
            f.level(tex, GL_TEXTURE_HEIGHT),
        );
        if size.0 <= 0 || size.1 <= 0 {
            return false;
        }
        if copy.texture == 0 || (copy.format, copy.size) != (format, size) {
            if copy.texture != 0 {
                (f.c.delete_textures)(1, &copy.texture);
            }
            *copy = DepthCopy {
                texture: 0,
                format,
                size,
            };
            copy.texture = f.new_texture(GL_TEXTURE_2D);
            let copied = (copy.texture, GL_TEXTURE_2D);
            match unsized_layout(format) {
                None => f.storage(copied, 1, (0, true), format, (size.0, size.1, 0)),
                Some((layout, kind)) => {
                    let pbo = f.integer(GL_PIXEL_UNPACK_BUFFER_BINDING) as u32;
                    let was = f.integer(GL_TEXTURE_BINDING_2D) as u32;
                    (f.c.bind_buffer)(GL_PIXEL_UNPACK_BUFFER, 0);
                    (f.c.bind_texture)(GL_TEXTURE_2D, copy.texture);
                    let none = std::ptr::null();
                    (f.c.tex_image_2d)(
                        GL_TEXTURE_2D,
                        0,
                        format as i32,
                        size.0,
                        size.1,
                        0,
                        layout,
                        kind,
                        none,
                    );
                    (f.c.bind_texture)(GL_TEXTURE_2D, was);
                    (f.c.bind_buffer)(GL_PIXEL_UNPACK_BUFFER, pbo);
                }
            }
            if f.level(copied, GL_TEXTURE_WIDTH) != size.0 {
                (f.c.delete_textures)(1, &copy.texture);
                copy.texture = 0;
                return false;
            }
        }
        copy_layer(
            f,
            (array, GL_TEXTURE_2D_ARRAY, 0, 0),
            (copy.texture, GL_TEXTURE_2D, 0, 0),
            (0, 0, size.0, size.1),
        );
        true
    }
}

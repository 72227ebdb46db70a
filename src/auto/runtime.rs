//! Automatic stereo at run time: what a context given automatic stereo
//! (glstereo-run --auto) does with each call of the families the preload
//! library reports ([`crate::interpose::draws`]), following the design of
//! [`crate::auto`]. The program draws into the layered eyes of its
//! emulated framebuffer ([`crate::auto::eyes`]); each draw reaches both.
//!
//! - **Draws** (glDraw*, glMultiDraw*, glRect*, glEvalMesh*): made once per
//!   eye, the eye chosen by the uniform `gls_auto_eye` at the reserved
//!   location of the current program (rewritten at link time,
//!   [`crate::auto::link`]), of the pipeline's last-stage program, or of
//!   the layer's stand-in for fixed-function vertex processing
//!   ([`crate::auto::standin`]) bound for the draw. Where the vertices
//!   cannot choose a layer (two-sided fixed-function lighting,
//!   texture-coordinate generation, ARB vertex programs, a program that
//!   was not rewritten)
//!   each eye's layers are attached in turn, with the eye's projection for
//!   fixed function ([`crate::auto::fixed`]) or the shift in a rewritten
//!   program's uniform: the slow path. After the eyes the uniform holds
//!   the neutral value (no shift, no layer), so draws the layer does not
//!   see (glRasterPos through a vertex shader, a display list's own
//!   program) are mono.
//! - **Immediate mode**: glBegin opens a display list of the layer's (the
//!   vertices are compiled, not drawn), glEnd closes it and calls it once
//!   per eye as a draw. Inside a display list the program compiles,
//!   nothing is done (the list is drawn when called).
//! - **Display lists**: glCallList / glCallLists run the list once per eye
//!   by the slow path (a list may change programs, lighting or matrices
//!   inside), the matrices put back between the eyes; a list compiled
//!   with GL_COMPILE_AND_EXECUTE is compiled, then called so.
//! - **glDrawPixels, glBitmap, glCopyPixels**: once per eye into that
//!   eye's layers, at the eye's raster position ([`crate::auto::fixed`]).
//! - **Blits** into the default framebuffer (glBlitFramebuffer too,
//!   which the layer exports by hand): once per eye into that eye's
//!   layers, from the same eye of the default framebuffer or of a
//!   stereoized render target, else from the one picture.
//! - **glClear**, **glClearBuffer***: once (a clear clears every layer).
//! - **Transform feedback**: once the program has begun it, a draw while
//!   it captures is made once with the neutral eye under rasterizer
//!   discard (the mono capture), then for both eyes with the capture
//!   paused; a draw under rasterizer discard is made once.
//! - **NV_3dvision_settings**: glEnable / glDisable / glIsEnabled of
//!   GL_3DVISION_STEREO_NV turn automatic stereo on and off (both eyes
//!   then drawn alike).
//!
//! Under `--auto=depth` ([`crate::auto::live::AutoMode::Depth`]) every
//! draw, blit and pixel rectangle is made once, into the left eye's layer
//! (a rewritten program's uniform unshifted), and each frame records
//! where its scene is: the eyes are made from its depth at the present
//! ([`crate::auto::from_depth`]).
//!
//! Draws into the program's own framebuffer objects are made once, mono,
//! with the neutral uniform, except into render targets of the window's
//! size, which are drawn in stereo as the window is
//! ([`crate::auto::render_targets`]).

use std::collections::HashMap;

use std::sync::{Mutex, OnceLock};

use glam::DMat4;

use crate::auto::call::{Call, Returned};
use crate::auto::converge::{self, Perspective, Scene};
use crate::auto::entry_points::Family;
use crate::auto::eyes::{Attachments, layer};
use crate::auto::fixed;
use crate::auto::gl_fns;
use crate::auto::host::{self, Host};
use crate::auto::link::{self, LinkOutcome};
use crate::auto::live;
use crate::auto::render_targets::{self, Draw, Sampled, Targets};
use crate::auto::standin::{self, FixedVertexState, Lighting};
use crate::auto::vertex::LayerWrite;
use crate::math::Eye;
use crate::shims::nv3dvision::{
    GL_3DVISION_STEREO_NV, GL_STEREO_CONVERGENCE_NV, GL_STEREO_SEPARATION_NV, StereoSettings,
};
use crate::stereo::outputs::LinkFns;

const GL_CURRENT_PROGRAM: u32 = 0x8B8D;
const GL_VERSION: u32 = 0x1F02;
const GL_PROGRAM_PIPELINE_BINDING: u32 = 0x825A;
const GL_DRAW_FRAMEBUFFER_BINDING: u32 = 0x8CA6;
const GL_READ_FRAMEBUFFER_BINDING: u32 = 0x8CAA;
const GL_DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const GL_READ_FRAMEBUFFER: u32 = 0x8CA8;
const GL_MAX_UNIFORM_LOCATIONS: u32 = 0x826E;
const GL_VERTEX_SHADER: u32 = 0x8B31;
const GL_GEOMETRY_SHADER: u32 = 0x8DD9;
const GL_TESS_EVALUATION_SHADER: u32 = 0x8E87;
const GL_LIGHTING: u32 = 0x0B50;
const GL_TEXTURE_GEN_S: u32 = 0x0C60;
const GL_VERTEX_PROGRAM_ARB: u32 = 0x8620;
const GL_FOG: u32 = 0x0B60;
const GL_ACTIVE_TEXTURE: u32 = 0x84E0;
const GL_TEXTURE0: u32 = 0x84C0;
const GL_MAX_TEXTURE_UNITS: u32 = 0x84E2;
const GL_MAX_TEXTURE_COORDS: u32 = 0x8871;
const GL_MAX_CLIP_PLANES: u32 = 0x0D32;
const GL_CLIP_PLANE0: u32 = 0x3000;
const GL_COLOR_SUM: u32 = 0x8458;
const GL_LIGHT0: u32 = 0x4000;
const GL_NORMALIZE: u32 = 0x0BA1;
const GL_RESCALE_NORMAL: u32 = 0x803A;
const GL_COLOR_MATERIAL: u32 = 0x0B57;
const GL_COLOR_MATERIAL_FACE: u32 = 0x0B55;
const GL_COLOR_MATERIAL_PARAMETER: u32 = 0x0B56;
const GL_LIGHT_MODEL_LOCAL_VIEWER: u32 = 0x0B51;
const GL_LIGHT_MODEL_TWO_SIDE: u32 = 0x0B52;
const GL_LIGHT_MODEL_COLOR_CONTROL: u32 = 0x81F8;
const GL_SEPARATE_SPECULAR_COLOR: u32 = 0x81FA;
const GL_MAX_LIGHTS: u32 = 0x0D31;
const GL_POSITION: u32 = 0x1203;
const GL_SPOT_CUTOFF: u32 = 0x1206;
const GL_CONSTANT_ATTENUATION: u32 = 0x1207;
const GL_LINEAR_ATTENUATION: u32 = 0x1208;
const GL_QUADRATIC_ATTENUATION: u32 = 0x1209;
const GL_PROGRAM_POINT_SIZE: u32 = 0x8642;
/// The fixed-function texture targets a unit may enable.
const TEXTURE_TARGETS: [u32; 5] = [0x0DE0, 0x0DE1, 0x806F, 0x8513, 0x84F5];
const GL_FOG_COORD_SRC: u32 = 0x8450;
const GL_FOG_COORD: u32 = 0x8451;
const GL_MATRIX_MODE: u32 = 0x0BA0;
const GL_MODELVIEW: u32 = 0x1700;
const GL_PROJECTION: u32 = 0x1701;
const GL_MODELVIEW_MATRIX: u32 = 0x0BA6;
const GL_PROJECTION_MATRIX: u32 = 0x0BA7;
const GL_COMPILE: u32 = 0x1300;
const GL_COMPILE_AND_EXECUTE: u32 = 0x1301;
const GL_CURRENT_RASTER_POSITION: u32 = 0x0B07;
const GL_CURRENT_RASTER_POSITION_VALID: u32 = 0x0B08;
const GL_VIEWPORT: u32 = 0x0BA2;
const GL_DEPTH_RANGE: u32 = 0x0B70;
const GL_RASTERIZER_DISCARD: u32 = 0x8C89;
const GL_TRANSFORM_FEEDBACK_PAUSED: u32 = 0x8E23;
const GL_TRANSFORM_FEEDBACK_ACTIVE: u32 = 0x8E24;
const GL_DEPTH_CLEAR_VALUE: u32 = 0x0B73;
const GL_LINK_STATUS: u32 = 0x8B82;
const GL_CLIP_DEPTH_MODE: u32 = 0x935D;
const GL_NEGATIVE_ONE_TO_ONE: u32 = 0x935E;
const GL_ZERO_TO_ONE: u32 = 0x935F;
const GL_TEXTURE_2D_TARGET: u32 = 0x0DE1;
const GL_TEXTURE_BINDING_2D_PNAME: u32 = 0x8069;

gl_fns! {
    /// The GL functions of automatic stereo at run time, below the layer.
    pub struct AutoFns {
        get_integerv = c"glGetIntegerv": fn(u32, *mut i32);
        get_string = c"glGetString": fn(u32) -> *const u8;
        get_floatv = c"glGetFloatv": fn(u32, *mut f32);
        get_doublev = c"glGetDoublev": fn(u32, *mut f64);
        is_enabled = c"glIsEnabled": fn(u32) -> u8;
        get_lightfv = c"glGetLightfv": fn(u32, u32, *mut f32);
        use_program = c"glUseProgram": fn(u32);
        uniform4f = c"glUniform4f": fn(i32, f32, f32, f32, f32);
        program_uniform4f = c"glProgramUniform4f": fn(u32, i32, f32, f32, f32, f32);
        get_program_pipelineiv = c"glGetProgramPipelineiv": fn(u32, u32, *mut i32);
        get_uniform_location = c"glGetUniformLocation": fn(u32, *const std::ffi::c_char) -> i32;
        gen_lists = c"glGenLists": fn(i32) -> u32;
        new_list = c"glNewList": fn(u32, u32);
        end_list = c"glEndList": fn();
        call_list = c"glCallList": fn(u32);
        matrix_mode = c"glMatrixMode": fn(u32);
        load_matrixd = c"glLoadMatrixd": fn(*const f64);
        bitmap = c"glBitmap": fn(i32, i32, f32, f32, f32, f32, *const u8);
        enable = c"glEnable": fn(u32);
        active_texture = c"glActiveTexture": fn(u32);
        disable = c"glDisable": fn(u32);
        gen_queries = c"glGenQueries": fn(i32, *mut u32);
        delete_queries = c"glDeleteQueries": fn(i32, *const u32);
        begin_query_indexed = c"glBeginQueryIndexed": fn(u32, u32, u32);
        end_query_indexed = c"glEndQueryIndexed": fn(u32, u32);
        get_query_objectui64v = c"glGetQueryObjectui64v": fn(u32, u32, *mut u64);
        begin_conditional_render = c"glBeginConditionalRender": fn(u32, u32);
        get_query_indexediv = c"glGetQueryIndexediv": fn(u32, u32, u32, *mut i32);
        depth_func = c"glDepthFunc": fn(u32);
        depth_mask = c"glDepthMask": fn(u8);
        clear_bufferfv = c"glClearBufferfv": fn(u32, i32, *const f32);
        bind_framebuffer = c"glBindFramebuffer": fn(u32, u32);
        is_framebuffer = c"glIsFramebuffer": fn(u32) -> u8;
        get_framebuffer_attachment_parameteriv = c"glGetFramebufferAttachmentParameteriv": fn(u32, u32, u32, *mut i32);
        pause_transform_feedback = c"glPauseTransformFeedback": fn();
        resume_transform_feedback = c"glResumeTransformFeedback": fn();
    }
}

/// The tables, loaded once from the GL below the layer.
struct Tables {
    gl: AutoFns,
    link: LinkFns,
}

fn tables() -> Option<&'static Tables> {
    static TABLES: OnceLock<Option<Tables>> = OnceLock::new();
    TABLES
        .get_or_init(|| {
            let get = host::gl_proc;
            // SAFETY: `get` returns the named GL function or NULL.
            let t = unsafe {
                Some(Tables {
                    gl: AutoFns::load(get)?,
                    link: LinkFns::load(get)?,
                })
            };
            if t.is_none() {
                crate::report::warn(
                    "automatic stereo needs GL 4.1's functions, which the GL library lacks: \
                     programs stay mono",
                );
            }
            t
        })
        .as_ref()
}

/// Where a rewritten program's eye uniform is, and whether its last
/// vertex stage writes the eye's layer (not in GLSL ES, whose vertex
/// stages cannot: its draws attach each eye's layers in turn).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Rewritten {
    location: i32,
    layer: bool,
    /// The locations of the uniforms its last vertex stage computes
    /// gl_Position from (the camera's matrices; −1: none more); all −1
    /// where none was found (the position comes from a function, a
    /// uniform block): every upload is looked at then.
    projecting: [i32; 4],
}

/// What the layer knows of a program after its link: where its eye
/// uniform is when its last vertex stage was rewritten.
static PROGRAMS: Mutex<Option<HashMap<(u64, u32), Rewritten>>> = Mutex::new(None);

fn record(group: u64, program: u32, rewritten: Option<Rewritten>) {
    let mut p = PROGRAMS.lock().unwrap_or_else(|e| e.into_inner());
    let map = p.get_or_insert_with(HashMap::new);
    match rewritten {
        Some(r) => map.insert((group, program), r),
        None => map.remove(&(group, program)),
    };
}

fn rewritten(group: u64, program: u32) -> Option<Rewritten> {
    let p = PROGRAMS.lock().unwrap_or_else(|e| e.into_inner());
    p.as_ref()?.get(&(group, program)).copied()
}

/// The reserved uniform location: the last the driver offers.
fn reserved_location(f: &AutoFns) -> Option<u32> {
    static LOCATION: OnceLock<Option<u32>> = OnceLock::new();
    *LOCATION.get_or_init(|| {
        let mut max = 0;
        // SAFETY: a context is current (callers); one value.
        unsafe { (f.get_integerv)(GL_MAX_UNIFORM_LOCATIONS, &mut max) };
        (max > 1).then(|| max as u32 - 1)
    })
}

/// A context's automatic-stereo state.
#[derive(Default)]
pub struct AutoState {
    /// The program's NV_3dvision_settings state beyond the live settings
    /// (cutoff, projection method).
    settings: Option<StereoSettings>,
    /// The stand-in programs made so far, by the state they reproduce.
    standin: Vec<(FixedVertexState, u32)>,
    /// The state the stand-in depends on, as last read ([`fixed_state`]);
    /// None: to be read again (glEnable, glDisable, glPopAttrib, a display
    /// list, glLight*, glLightModel* or glColorMaterial ran since).
    fixed_enables: Option<FixedVertexState>,
    /// A stand-in could not be made: fixed function takes the slow path.
    standin_failed: bool,
    /// The layer's display list for immediate mode (0: none yet).
    list: u32,
    /// Between glBegin and glEnd into the layer's list.
    in_begin: bool,
    /// Between a glBegin GL executed (into a mono target) and its glEnd.
    in_mono_begin: bool,
    /// The program compiles a display list: (list, convert to execute at
    /// glEndList).
    compiling: Option<(u32, bool)>,
    /// The list compiling holds geometry only: draws, vertices, matrices,
    /// uniforms, lists of geometry only — nothing that changes which
    /// program draws, the stand-in's key, texture bindings, or clears.
    compiling_plain: bool,
    /// The display lists compiled so far, by name: geometry only (true),
    /// or not. A list of geometry only is drawn by the eye's uniform as
    /// any draw (the fast path); the others attach each eye's layers in
    /// turn, since they may change anything between their draws.
    lists: HashMap<u32, bool>,
    /// What the program uploaded to each of its programs as 4x4 uniform
    /// matrices ([`crate::auto::converge`]): the last perspective one
    /// (what a draw with that program projects with), or None where it
    /// uploaded matrices and none perspective (an orthographic overlay). A
    /// program without an entry projects as automatic stereo cannot see
    /// (matrices in uniform buffers, built in the shader, or none: a
    /// full-screen pass).
    uploads: Vec<(u32, Option<Perspective>)>,
    /// The clip w of the model's origin under each program's last
    /// perspective upload (a combined model-view-projection matrix: the
    /// distance of the object; 0 for a projection alone).
    origins: Vec<(u32, f64)>,
    /// The origins' distances of this measured frame's perspective draws
    /// ([`converge::Frame::origin`]).
    frame_origins: Vec<f64>,
    /// This frame is not measured: draws leave their projection unread.
    unmeasured: bool,
    /// When the last measured frame was presented ([`converge::due`]).
    measured_at: Option<std::time::Instant>,
    /// This frame's first draw looked at the clock ([`converge::due`]).
    clock_read: bool,
    /// The program has begun transform feedback: draws check whether it
    /// is capturing.
    feedback: bool,
    /// A perspective draw reached the window's eyes this measured frame:
    /// their depth holds its scene, drawn with this projection (None: a
    /// draw whose projection automatic stereo cannot see, taken where no
    /// known perspective draw came; a program that draws off screen and
    /// then only passes a picture through the window leaves none, and is
    /// measured in its target).
    window_drawn: Option<Scene>,

    /// Automatic convergence's buffers.
    pub measure: converge::Scratch,
    /// The buffers of eyes made from depth ([`crate::auto::from_depth`]).
    pub from_depth: crate::auto::from_depth::Scratch,
    /// The left eye's depth of the window's eyes, copied when a draw that
    /// is not the scene's (a full-screen pass with depth writes, an
    /// overlay) came into them after the scene on a measured frame;
    /// `depth_copied`: it holds the frame's scene
    /// ([`render_targets::copy_left_depth`]; a render target's is the
    /// share group's, [`render_targets::SceneTarget`]).
    depth_copy: render_targets::DepthCopy,
    depth_copied: bool,
    /// `--auto=depth`: the program cleared the window's depth after this
    /// frame's scene (drawn in this viewport), whose depth was copied
    /// first ([`before_clear`]): a perspective draw in another viewport
    /// after it (an orientation gizmo in a corner) is an overlay, not the
    /// scene.
    depth_cleared: Option<(i32, i32, i32, i32)>,
    /// `--auto=depth`: a flat draw (an overlay: a HUD, text) came into the
    /// window's eyes after this frame's scene, and the scene's colour was
    /// copied into the right eye's layer before it ([`keep_scene_colour`]).
    colour_kept: bool,
    /// `--auto=depth`: a perspective draw of this frame wrote depth
    /// ([`converge::Frame::depth_written`]); looked at by each draw until
    /// one did.
    depth_written: bool,
    /// `--auto=depth`: a perspective draw of this frame with the depth
    /// test off came into the window's eyes, and wrote its depth into the
    /// depth array's second layer ([`depth_beside`]).
    depth_beside: bool,
    /// The window's eyes' framebuffer object and its attachments while
    /// the depth array's second layer is at its depth attachment point
    /// (between draws with the depth test off, [`depth_beside`]); put
    /// back by [`restore_depth`] before anything else may use its depth.
    beside_attached: Option<(u32, Attachments)>,
    /// The texture units holding textures with eyes, as last scanned, and
    /// the twins' generation then; None: to be scanned again (a binding
    /// changed: the texture commands, glPopAttrib, a display list).
    sampled: Option<(u64, Sampled)>,
    /// The program's counting queries active now ([`Counting`]).
    queries: Vec<Counting>,
    /// Ended counting queries that have segments: (the program's name,
    /// its target, the segments), read by glGetQueryObject* and
    /// glBeginConditionalRender as one.
    segmented: Vec<(u32, u32, Vec<u32>)>,
}

/// A query of the program's that counts what draws produce
/// (GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED(_CONSERVATIVE),
/// GL_PRIMITIVES_GENERATED): it must not count the right eye's draws, so
/// it is ended before them and a segment of the layer's own begun after;
/// its result is the sum of its segments (any, for the boolean ones).
#[derive(Debug)]
pub struct Counting {
    target: u32,
    index: u32,
    /// The program's name for it.
    id: u32,
    /// The layer's queries begun after the program's, in order.
    segments: Vec<u32>,
    /// Ended for draws it must not count.
    paused: bool,
}

const GL_SAMPLES_PASSED: u32 = 0x8914;
const GL_ANY_SAMPLES_PASSED: u32 = 0x8C2F;
const GL_ANY_SAMPLES_PASSED_CONSERVATIVE: u32 = 0x8D6A;
const GL_PRIMITIVES_GENERATED: u32 = 0x8C87;
const GL_QUERY_RESULT: u32 = 0x8866;
const GL_QUERY_RESULT_AVAILABLE: u32 = 0x8867;
const GL_QUERY_RESULT_NO_WAIT: u32 = 0x9194;
const GL_QUERY_BUFFER_BINDING: u32 = 0x9193;
const GL_CURRENT_QUERY: u32 = 0x8865;

/// Whether a query of `target` counts what draws produce.
fn counts(target: u32) -> bool {
    matches!(
        target,
        GL_SAMPLES_PASSED
            | GL_ANY_SAMPLES_PASSED
            | GL_ANY_SAMPLES_PASSED_CONSERVATIVE
            | GL_PRIMITIVES_GENERATED
    )
}

/// Ends the active counting queries `which` selects, before draws they
/// must not count.
unsafe fn pause_counting(f: &AutoFns, queries: &mut [Counting], which: impl Fn(u32) -> bool) {
    for q in queries.iter_mut().filter(|q| !q.paused && which(q.target)) {
        // SAFETY: the program's context is current (callers); the query
        // is active on (target, index).
        unsafe { (f.end_query_indexed)(q.target, q.index) };
        q.paused = true;
    }
}

/// Begins a new segment of every paused counting query.
unsafe fn resume_counting(f: &AutoFns, queries: &mut [Counting]) {
    for q in queries.iter_mut().filter(|q| q.paused) {
        let mut seg = 0;
        // SAFETY: the program's context is current (callers).
        unsafe {
            (f.gen_queries)(1, &mut seg);
            (f.begin_query_indexed)(q.target, q.index, seg);
        }
        q.segments.push(seg);
        q.paused = false;
    }
}

impl AutoState {
    /// The settings a draw uses now: the live separation, convergence and
    /// on/off with this context's cutoff and method.
    fn settings(&mut self) -> StereoSettings {
        let mut s = *self
            .settings
            .get_or_insert_with(|| StereoSettings::new(true));
        let separation = if live::auto_on() {
            live::separation()
        } else {
            0.0
        };
        let _ = s.parameter_f(GL_STEREO_SEPARATION_NV, separation);
        let convergence = live::convergence()
            .or_else(live::automatic_convergence)
            .unwrap_or(0.0);
        let _ = s.parameter_f(GL_STEREO_CONVERGENCE_NV, convergence);
        s
    }

    /// The settings of the draw about to be made ([`DrawSettings`]).
    ///
    /// # Safety
    /// The program's context is current on this thread.
    unsafe fn draw_settings(&mut self, f: &AutoFns) -> DrawSettings {
        let mut nv = self.settings();
        // SAFETY: contract.
        let (c, depth) = unsafe { draw_convergence(f, self) };
        if let Some(c) = c {
            let _ = nv.parameter_f(GL_STEREO_CONVERGENCE_NV, c);
        }
        DrawSettings { nv, depth }
    }

    /// The state the fixed-function stand-in depends on may have changed
    /// (glEnable, glDisable, glPopAttrib, a display list, glLight*,
    /// glLightModel*, glColorMaterial): read it again at the next
    /// fixed-function draw.
    pub fn forget_enables(&mut self) {
        self.fixed_enables = None;
        self.sampled = None;
    }

    /// The texture bindings may have changed: scan them again at the
    /// next draw.
    pub fn forget_bindings(&mut self) {
        self.sampled = None;
    }

    /// The units holding textures with eyes now ([`render_targets::sampled`],
    /// scanned again only after a binding or the set of twins changed).
    ///
    /// # Safety
    /// The program's context is current on this thread.
    unsafe fn sampled(&mut self, targets: &Targets) -> Sampled {
        let generation = targets.generation();
        match &self.sampled {
            Some((g, s)) if *g == generation => s.clone(),
            _ => {
                // SAFETY: contract.
                let s = unsafe { render_targets::sampled(targets) };
                self.sampled = Some((generation, s.clone()));
                s
            }
        }
    }

    /// The program's NV_3dvision_settings state (cutoff, method).
    pub fn nv_settings(&mut self) -> &mut StereoSettings {
        self.settings
            .get_or_insert_with(|| StereoSettings::new(true))
    }
}

/// Where an eye's uniform goes.
#[derive(Clone, Copy, Debug)]
struct Target {
    program: u32,
    location: i32,
    /// Set with glProgramUniform4f (a pipeline's stage), not glUniform4f.
    separate: bool,
}

/// How one draw reaches the eyes.
#[derive(Clone, Copy, Debug)]
enum Path {
    /// Once, as the program made it: not into the eyes.
    Mono(Option<Target>),
    /// The eye by the uniform of `target` (the stand-in's when `standin`
    /// is its program, bound for the draw).
    Uniform { target: Target, standin: bool },
    /// Each eye's layers attached in turn, with the eye's projection
    /// (`fixed`) and the shift in `target`'s uniform.
    Layers { fixed: bool, target: Option<Target> },
}

/// The settings of one draw: the context's, its convergence the draw's
/// own where automatic convergence chose a depth ([`draw_convergence`]),
/// and then, for a draw whose projection is not known, the depth form's
/// (z_c, k).
struct DrawSettings {
    nv: StereoSettings,
    depth: Option<(f32, f32)>,
}

/// The uniform's value for `eye` (None: neutral) with `settings`; `layer`
/// whether the stage writes the eye's layer: (e·s, C, layer, 0), or in
/// the depth form (e·s, z_c, layer, k) ([`crate::auto::vertex`]).
fn eye_value(settings: &DrawSettings, eye: Option<Eye>, with_layer: bool) -> [f32; 4] {
    let (c, k) = match settings.depth {
        Some((z, k)) => (z, k),
        None => (settings.nv.convergence(), 0.0),
    };
    match eye {
        None => [0.0, c, -1.0, 0.0],
        Some(e) => [
            (e.sign() * settings.nv.effective_separation()) as f32,
            c,
            if with_layer { layer(e) as f32 } else { -1.0 },
            k,
        ],
    }
}

unsafe fn set_uniform(f: &AutoFns, t: Target, v: [f32; 4]) {
    // SAFETY: contract of the callers: the program's context is current
    // and `t` a linked program with the uniform at its location.
    unsafe {
        if t.separate {
            (f.program_uniform4f)(t.program, t.location, v[0], v[1], v[2], v[3]);
        } else {
            (f.uniform4f)(t.location, v[0], v[1], v[2], v[3]);
        }
    }
}

unsafe fn integer(f: &AutoFns, pname: u32) -> i32 {
    let mut v = 0;
    // SAFETY: a context is current (callers); one value.
    unsafe { (f.get_integerv)(pname, &mut v) };
    v
}

/// The program supplying the vertices' last stage now: Some((program,
/// separate)), or None for fixed-function vertex processing.
unsafe fn vertex_program(f: &AutoFns) -> Option<(u32, bool)> {
    // SAFETY: contract of the callers.
    unsafe {
        let p = integer(f, GL_CURRENT_PROGRAM) as u32;
        if p != 0 {
            return Some((p, false));
        }
        let pipe = integer(f, GL_PROGRAM_PIPELINE_BINDING) as u32;
        if pipe == 0 {
            return None;
        }
        for stage in [
            GL_GEOMETRY_SHADER,
            GL_TESS_EVALUATION_SHADER,
            GL_VERTEX_SHADER,
        ] {
            let mut prog = 0;
            (f.get_program_pipelineiv)(pipe, stage, &mut prog);
            if prog != 0 {
                return Some((prog as u32, true));
            }
        }
        None
    }
}

/// The fixed-function state the stand-in must reproduce now, or None
/// when it cannot (texture-coordinate generation on a unit with a
/// texture, an ARB vertex program; two-sided lighting the stand-in itself
/// refuses). The per-unit enables are read only
/// after something may have changed them (`AutoState::fixed_enables`): a
/// unit's enables are read by making it active, a dozen calls per unit.
unsafe fn fixed_state(f: &AutoFns, st: &mut AutoState) -> Option<FixedVertexState> {
    // SAFETY: contract of the callers.
    unsafe {
        if (f.is_enabled)(GL_VERTEX_PROGRAM_ARB) != 0 {
            return None;
        }
        let enables = match st.fixed_enables {
            Some(e) => e,
            None => {
                let e = read_enables(f);
                st.fixed_enables = Some(e);
                e
            }
        };
        if enables.texgen {
            return None;
        }
        // glFog's source is not an enable: read at every draw under fog.
        let fog_coord = enables.fog && integer(f, GL_FOG_COORD_SRC) as u32 == GL_FOG_COORD;
        Some(FixedVertexState {
            fog_coord,
            ..enables
        })
    }
}

/// The lighting state of the stand-in's key, GL_LIGHTING being on: the
/// enabled lights and the kind of each (positional, spot, attenuated),
/// as Mesa keys its own fixed-function program, so that the stand-in
/// computes only what each light needs; the colour material, the light
/// model, the normals' treatment.
unsafe fn read_lighting(f: &AutoFns) -> Lighting {
    // SAFETY (every call): a compatibility context is current (callers);
    // glGetLightfv writes at most 4 values.
    let on = |cap| unsafe { (f.is_enabled)(cap) != 0 };
    let int = |pname| unsafe { integer(f, pname) };
    let light = |i: u32, pname: u32| {
        let mut v = [0.0f32; 4];
        unsafe { (f.get_lightfv)(GL_LIGHT0 + i, pname, v.as_mut_ptr()) };
        v
    };
    let mut l = Lighting {
        color_material: if on(GL_COLOR_MATERIAL)
            && int(GL_COLOR_MATERIAL_FACE) as u32 != crate::gl::enums::GL_BACK
        {
            int(GL_COLOR_MATERIAL_PARAMETER) as u32
        } else {
            0
        },
        local_viewer: int(GL_LIGHT_MODEL_LOCAL_VIEWER) != 0,
        two_side: int(GL_LIGHT_MODEL_TWO_SIDE) != 0,
        separate_specular: int(GL_LIGHT_MODEL_COLOR_CONTROL) as u32 == GL_SEPARATE_SPECULAR_COLOR,
        normalize: on(GL_NORMALIZE),
        rescale_normal: on(GL_RESCALE_NORMAL),
        ..Lighting::default()
    };
    for i in (0..int(GL_MAX_LIGHTS).clamp(0, 8) as u32).filter(|&i| on(GL_LIGHT0 + i)) {
        let bit = 1u8 << i;
        l.lights |= bit;
        if light(i, GL_POSITION)[3] != 0.0 {
            l.positional |= bit;
            let k = [
                GL_CONSTANT_ATTENUATION,
                GL_LINEAR_ATTENUATION,
                GL_QUADRATIC_ATTENUATION,
            ]
            .map(|p| light(i, p)[0]);
            if k != [1.0, 0.0, 0.0] {
                l.attenuated |= bit;
            }
        }
        if light(i, GL_SPOT_CUTOFF)[0] != 180.0 {
            l.spot |= bit;
        }
    }
    l
}

/// The state [`fixed_state`] keeps between changes: the enables, and
/// under GL_LIGHTING the lighting ([`read_lighting`]).
unsafe fn read_enables(f: &AutoFns) -> FixedVertexState {
    // SAFETY: contract of the callers.
    unsafe {
        let on = |cap| (f.is_enabled)(cap) != 0;
        let active = integer(f, GL_ACTIVE_TEXTURE) as u32;
        let units = integer(f, GL_MAX_TEXTURE_UNITS)
            .min(integer(f, GL_MAX_TEXTURE_COORDS))
            .clamp(0, 32) as u32;
        let (mut texture_units, mut texgen) = (0u32, false);
        for unit in 0..units {
            (f.active_texture)(GL_TEXTURE0 + unit);
            if TEXTURE_TARGETS.into_iter().any(on) {
                texture_units |= 1 << unit;
                texgen |= (GL_TEXTURE_GEN_S..=GL_TEXTURE_GEN_S + 3).any(on);
            }
        }
        (f.active_texture)(active);
        let planes = integer(f, GL_MAX_CLIP_PLANES).clamp(0, 64) as u32;
        FixedVertexState {
            lighting: on(GL_LIGHTING).then(|| read_lighting(f)),
            texgen,
            texture_units,
            fog: on(GL_FOG),
            fog_coord: false,
            color_sum: on(GL_COLOR_SUM),
            clip_planes: (0..planes).any(|i| on(GL_CLIP_PLANE0 + i)),
            program_point_size: on(GL_PROGRAM_POINT_SIZE),
        }
    }
}

/// The stand-in program for `state` in this context, made the first time.
unsafe fn standin_program(t: &Tables, st: &mut AutoState, state: FixedVertexState) -> Option<u32> {
    if st.standin_failed {
        return None;
    }
    if let Some(&(_, p)) = st.standin.iter().find(|(s, _)| *s == state) {
        return Some(p);
    }
    let location = reserved_location(&t.gl)?;
    let made = standin::source(state, location).ok().and_then(|src| {
        // SAFETY: the program's context is current (callers).
        unsafe {
            let vs = t.link.compile_as(GL_VERTEX_SHADER, &src)?;
            let p = (t.link.create_program)();
            (t.link.attach_shader)(p, vs);
            (t.link.link_program)(p);
            (t.link.detach_shader)(p, vs);
            (t.link.delete_shader)(vs);
            if t.link.program_int(p, GL_LINK_STATUS) == 0 {
                (t.link.delete_program)(p);
                return None;
            }
            Some(p)
        }
    });
    match made {
        Some(p) => {
            st.standin.push((state, p));
            Some(p)
        }
        None => {
            st.standin_failed = true;
            crate::report::warn(
                "the fixed-function stand-in vertex shader does not build here: \
                 fixed-function draws take the slow path (a framebuffer change per eye)",
            );
            None
        }
    }
}

/// Whether a draw (`name`) now has its vertices moved per eye: fixed
/// function (the stand-in, or the slow path), a program whose last
/// vertex stage was rewritten, a display list (whatever it holds).
///
/// # Safety
/// The program's context is current (callers).
unsafe fn shifted(f: &AutoFns, group: u64, name: &str) -> bool {
    if name.starts_with("glCallList") {
        return true;
    }
    // SAFETY: contract.
    match unsafe { vertex_program(f) } {
        None => true,
        Some((p, _)) => rewritten(group, p).is_some(),
    }
}

/// How a draw of `kind` reaches the eyes now. `lists`: a display list is
/// called (whatever it holds: the slow path).
unsafe fn choose(
    t: &Tables,
    cur: &impl Host,
    st: &mut AutoState,
    app_fbo: u32,
    lists: bool,
) -> Path {
    let f = &t.gl;
    // SAFETY: the program's context is current (callers).
    unsafe {
        let program = vertex_program(f);
        let program_rewritten = program.and_then(|(p, _)| rewritten(cur.group(), p));
        let target = program
            .zip(program_rewritten)
            .map(|((p, separate), r)| Target {
                program: p,
                location: r.location,
                separate,
            });
        if integer(f, GL_DRAW_FRAMEBUFFER_BINDING) as u32 != app_fbo {
            return Path::Mono(target);
        }
        if lists {
            return Path::Layers {
                fixed: program.is_none(),
                target,
            };
        }
        match (program, target) {
            (Some(_), Some(target)) if program_rewritten.is_some_and(|r| r.layer) => {
                Path::Uniform {
                    target,
                    standin: false,
                }
            }
            // A stage that cannot write the layer (GLSL ES): the shift by
            // the uniform, the eye's layers attached in turn.
            (Some(_), Some(target)) => Path::Layers {
                fixed: false,
                target: Some(target),
            },
            (Some(_), None) => Path::Layers {
                fixed: false,
                target: None,
            },
            (None, _) => {
                let standin = fixed_state(f, st).and_then(|state| standin_program(t, st, state));
                match (standin, reserved_location(f)) {
                    (Some(p), Some(l)) => Path::Uniform {
                        target: Target {
                            program: p,
                            location: l as i32,
                            separate: false,
                        },
                        standin: true,
                    },
                    _ => Path::Layers {
                        fixed: true,
                        target: None,
                    },
                }
            }
        }
    }
}

const EYES: [Eye; 2] = [Eye::Left, Eye::Right];

/// The program's matrices a display list may change, to put back between
/// the eyes.
struct Matrices {
    mode: u32,
    modelview: [f64; 16],
    projection: [f64; 16],
}

unsafe fn matrices(f: &AutoFns) -> Matrices {
    let mut m = Matrices {
        mode: 0,
        modelview: [0.0; 16],
        projection: [0.0; 16],
    };
    // SAFETY: a compatibility context is current (callers); 16 values each.
    unsafe {
        m.mode = integer(f, GL_MATRIX_MODE) as u32;
        (f.get_doublev)(GL_MODELVIEW_MATRIX, m.modelview.as_mut_ptr());
        (f.get_doublev)(GL_PROJECTION_MATRIX, m.projection.as_mut_ptr());
    }
    m
}

/// Loads `projection` (column-major) and puts back the program's matrix
/// mode `mode`.
unsafe fn load_projection(f: &AutoFns, projection: &[f64; 16], mode: u32) {
    // SAFETY: as above.
    unsafe {
        (f.matrix_mode)(GL_PROJECTION);
        (f.load_matrixd)(projection.as_ptr());
        (f.matrix_mode)(mode);
    }
}

/// Draws `draw` into both eyes by `path` with `settings`; `restore`: put
/// the matrices back between the eyes (a display list may change them);
/// `queries`: the counting queries, kept off the right eye's draws.
#[allow(clippy::too_many_arguments)] // the state of one draw, taken apart by its callers
unsafe fn eyes(
    t: &Tables,
    path: Path,
    settings: &DrawSettings,
    layered: &Attachments,
    sampled: &Sampled,
    restore: bool,
    queries: &mut [Counting],
    draw: &mut dyn FnMut(),
) {
    let f = &t.gl;
    // SAFETY: the program's context is current with the layered eyes'
    // framebuffer object bound for drawing (checked by `choose`).
    unsafe {
        // Eyes made from the frame's depth: a draw into the eyes is made
        // once, mono, as the program made it, into the left eye's layer
        // (a rewritten program's uniform unshifted, layer 0; fixed
        // function as it is, without the stand-in).
        if live::from_depth() {
            match path {
                Path::Mono(_) => {}
                Path::Uniform {
                    target,
                    standin: false,
                }
                | Path::Layers {
                    target: Some(target),
                    ..
                } => {
                    let mut left = eye_value(settings, None, false);
                    left[2] = layer(Eye::Left) as f32;
                    set_uniform(f, target, left);
                    draw();
                    set_uniform(f, target, eye_value(settings, None, false));
                    return;
                }
                Path::Uniform { .. } | Path::Layers { .. } => return draw(),
            }
        }
        match path {
            Path::Mono(target) => {
                if let Some(target) = target {
                    set_uniform(f, target, eye_value(settings, None, false));
                }
                draw();
            }
            Path::Uniform { target, standin } => {
                if standin {
                    (f.use_program)(target.program);
                }
                let saved = restore.then(|| matrices(f));
                for eye in EYES {
                    if eye == Eye::Right {
                        pause_counting(f, queries, |_| true);
                        if let Some(m) = &saved {
                            (f.matrix_mode)(GL_MODELVIEW);
                            (f.load_matrixd)(m.modelview.as_ptr());
                            load_projection(f, &m.projection, m.mode);
                        }
                    }
                    set_uniform(f, target, eye_value(settings, Some(eye), true));
                    let bound = render_targets::bind_eye(sampled, eye);
                    draw();
                    bound.restore();
                }
                resume_counting(f, queries);
                set_uniform(f, target, eye_value(settings, None, false));
                if standin {
                    (f.use_program)(0);
                }
            }
            Path::Layers { fixed, target } => {
                let saved = (fixed || restore).then(|| matrices(f));
                for (i, eye) in EYES.into_iter().enumerate() {
                    if i == 1 {
                        pause_counting(f, queries, |_| true);
                    }
                    if i == 1 && restore {
                        let m = saved.as_ref().expect("saved");
                        (f.matrix_mode)(GL_MODELVIEW);
                        (f.load_matrixd)(m.modelview.as_ptr());
                        load_projection(f, &m.projection, m.mode);
                    }
                    layered.attach(GL_DRAW_FRAMEBUFFER, Some(eye));
                    if let Some(m) = saved.as_ref().filter(|_| fixed) {
                        let mono = DMat4::from_cols_array(&m.projection);
                        if let Some(p) = fixed::eye_projection(&settings.nv, &mono, eye) {
                            load_projection(f, &p.to_cols_array(), m.mode);
                        }
                    }
                    if let Some(target) = target {
                        set_uniform(f, target, eye_value(settings, Some(eye), false));
                    }
                    let bound = render_targets::bind_eye(sampled, eye);
                    draw();
                    bound.restore();
                }
                layered.attach(GL_DRAW_FRAMEBUFFER, None);
                resume_counting(f, queries);
                if let Some(target) = target {
                    set_uniform(f, target, eye_value(settings, None, false));
                }
                if let Some(m) = saved.as_ref().filter(|_| fixed) {
                    // Put the program's projection back, unless the list
                    // loaded one of its own.
                    let mut now = [0.0f64; 16];
                    (f.get_doublev)(GL_PROJECTION_MATRIX, now.as_mut_ptr());
                    let mono = DMat4::from_cols_array(&m.projection);
                    let right = fixed::eye_projection(&settings.nv, &mono, Eye::Right)
                        .map_or(m.projection, |p| p.to_cols_array());
                    if now == right.map(|v| v as f32 as f64) || now == right {
                        load_projection(f, &m.projection, integer(f, GL_MATRIX_MODE) as u32);
                    }
                }
            }
        }
    }
}

/// The hook of a context given automatic stereo (module docs).
pub fn around<R: Returned>(cur: &impl Host, call: Call, draw: impl Fn() -> R) -> R {
    let Some(t) = tables() else {
        return draw();
    };
    if matches!(call.family, Family::Read | Family::Framebuffer) {
        // They may use the window's depth, or change what is attached
        // (clears: before_clear).
        // SAFETY: the program's context is current on this thread.
        cur.with_auto(|st, _| unsafe { restore_depth(&t.gl, st) });
    }
    match call.family {
        Family::Settings => {
            if matches!(
                call.name,
                "glEnable" | "glDisable" | "glEnablei" | "glDisablei"
            ) {
                not_geometry_only(cur, call.family);
                cur.with_auto(|st, _| st.forget_enables());
            }
            settings_call(call, draw)
        }
        Family::Projection => {
            learn_projection(cur, &call);
            draw()
        }
        Family::Lighting => {
            not_geometry_only(cur, call.family);
            cur.with_auto(|st, _| st.forget_enables());
            draw()
        }
        Family::Texture => {
            not_geometry_only(cur, call.family);
            cur.with_auto(|st, _| st.forget_bindings());
            draw()
        }
        // SAFETY: the program's context is current on this thread.
        Family::TextureData => unsafe { texture_data(t, cur, call, draw) },
        // SAFETY: as above.
        Family::TextureWrite => unsafe { texture_write(t, cur, call, draw) },
        // SAFETY: as above.
        Family::Read => unsafe { read_call(t, cur, call, draw) },
        Family::Clear => {
            not_geometry_only(cur, call.family);
            before_clear(cur, &call);
            draw()
        }
        Family::SideEffect => {
            if call.name.starts_with("glBeginTransformFeedback") {
                cur.with_auto(|st, _| st.feedback = true);
                return draw();
            }
            // SAFETY: the program's context is current on this thread.
            unsafe { queries(&t.gl, cur, call, draw) }
        }
        Family::Draw
        | Family::BeginEnd
        | Family::DisplayList
        | Family::RasterPixels
        | Family::Blit => {
            let mut out = None;
            drawing(t, cur, call, &mut || out = Some(draw()));
            out.unwrap_or_else(|| R::from_bits(0))
        }
        _ => {
            not_geometry_only(cur, call.family);
            draw()
        }
    }
}

thread_local! {
    /// This thread's context compiles a display list of the program's.
    static COMPILING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// A call of `family` while the program compiles a display list: the
/// list is not geometry only unless the family is one that keeps it so
/// (draws, glBegin/glEnd, other lists — judged by `drawing` —, uniform
/// matrices).
pub fn not_geometry_only(cur: &impl Host, family: Family) {
    if !COMPILING.with(std::cell::Cell::get)
        || matches!(
            family,
            Family::Draw | Family::BeginEnd | Family::DisplayList | Family::Projection
        )
    {
        return;
    }
    cur.with_auto(|st, _| st.compiling_plain = false);
}

/// A command that reads a texture's contents outside draws, or makes new
/// contents from them ([`Family::TextureData`]): textures with eyes get
/// their left eye first; after glGenerateMipmap of one, its right view
/// gets mipmaps too.
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn texture_data<R: Returned>(
    t: &Tables,
    cur: &impl Host,
    call: Call,
    draw: impl Fn() -> R,
) -> R {
    let context = cur.context();
    render_targets::with_group(cur.group(), |targets| {
        // SAFETY: contract.
        unsafe {
            render_targets::resolve(targets, context, 0);
            let r = draw();
            let texture = match call.name {
                "glGenerateMipmap" | "glGenerateMipmapEXT" => match call.u32(0) {
                    GL_TEXTURE_2D_TARGET => {
                        Some(integer(&t.gl, GL_TEXTURE_BINDING_2D_PNAME) as u32)
                    }
                    _ => None,
                },
                "glGenerateTextureMipmap" | "glGenerateTextureMipmapEXT" => Some(call.u32(0)),
                _ => None,
            };
            if let Some(texture) = texture {
                render_targets::mipmaps_made(targets, texture);
            }
            // glCopyImageSubData wrote its destination: eye to eye from a
            // source with eyes.
            if call.name.starts_with("glCopyImageSubData") && call.args.len() == 15 {
                let image = |i: usize| {
                    let v = |k: usize| call.u32(i + k) as i32;
                    (call.u32(i), call.u32(i + 1), v(2), v(3), v(4), v(5))
                };
                let size = (
                    call.u32(12) as i32,
                    call.u32(13) as i32,
                    call.u32(14) as i32,
                );
                render_targets::copied_image(targets, context, image(0), image(6), size);
            }
            r
        }
    })
}

/// The texture a command of the texture families writes or reads: its
/// first argument for the direct-state-access forms (glTexture*,
/// glCompressedTexture*, glClearTex*), else the 2D (or 2D multisample)
/// texture bound to its target on the active unit; None for other
/// targets.
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn texture_of(f: &AutoFns, call: &Call) -> Option<u32> {
    const GL_TEXTURE_2D_MULTISAMPLE: u32 = 0x9100;
    const GL_TEXTURE_BINDING_2D_MULTISAMPLE: u32 = 0x9104;
    if names_texture(call) {
        return Some(call.u32(0));
    }
    // SAFETY: contract; one value.
    unsafe {
        match call.u32(0) {
            GL_TEXTURE_2D_TARGET => Some(integer(f, GL_TEXTURE_BINDING_2D_PNAME) as u32),
            GL_TEXTURE_2D_MULTISAMPLE => Some(integer(f, GL_TEXTURE_BINDING_2D_MULTISAMPLE) as u32),
            _ => None,
        }
    }
}

/// Whether a texture command names its texture (direct state access,
/// glClearTex*) rather than a target of the active unit.
fn names_texture(call: &Call) -> bool {
    let n = call.name;
    n.starts_with("glTexture")
        || n.starts_with("glCompressedTexture")
        || n.starts_with("glClearTex")
        || n.starts_with("glCopyTexture")
}

/// Whether a texture command defines the texture's images (glTexImage*,
/// glTexStorage*, glCopyTexImage*, through the active unit's target)
/// rather than changing part of them (the *SubImage* commands).
fn defines_texture(call: &Call) -> bool {
    !names_texture(call) && !call.name.contains("SubImage")
}

/// A command that gives a texture new contents outside draws
/// ([`Family::TextureWrite`]): a texture with eyes is one picture again.
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn texture_write<R: Returned>(
    t: &Tables,
    cur: &impl Host,
    call: Call,
    draw: impl Fn() -> R,
) -> R {
    let r = draw();
    // SAFETY: contract.
    if let Some(texture) = unsafe { texture_of(&t.gl, &call) }.filter(|&n| n != 0) {
        let context = cur.context();
        render_targets::with_group(cur.group(), |targets| unsafe {
            if defines_texture(&call) {
                render_targets::texture_defined(targets, texture, call.u32(0));
            }
            render_targets::forget(
                targets,
                context,
                &[render_targets::Object::Texture(texture)],
            )
        });
    }
    r
}

/// glCopyTex(Sub)Image2D and glCopyTextureSubImage2D ([`Family::Read`]):
/// the program's copy reads the left eye of a read framebuffer with
/// eyes (as a mono program's reads do); the texture then gets eyes, its
/// right eye copied from the source's right eye. A copy from a mono
/// source into a texture with eyes makes it one picture again. Other
/// reads (glReadPixels: the left eye) as they are.
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn read_call<R: Returned>(
    t: &Tables,
    cur: &impl Host,
    call: Call,
    draw: impl Fn() -> R,
) -> R {
    let name = call.name.trim_end_matches("EXT");
    // (x offset, y offset, x, y, width, height) argument positions.
    let region = match name {
        "glCopyTexSubImage2D" | "glCopyTextureSubImage2D" => {
            [Some(2), Some(3), Some(4), Some(5), Some(6), Some(7)]
        }
        "glCopyTexImage2D" => [None, None, Some(3), Some(4), Some(5), Some(6)],
        _ => return draw(),
    };
    if call.u32(1) != 0 {
        // Not level 0: the texture is one picture.
        // SAFETY: contract.
        return unsafe { texture_write(t, cur, call, draw) };
    }
    let f = &t.gl;
    let (context, group) = (cur.context(), cur.group());
    cur.with_auto(|_, eyes| {
        let Some((window_fbo, window_eyes)) = eyes else {
            return draw();
        };
        render_targets::with_group(group, |targets| {
            // SAFETY: contract.
            unsafe {
                render_targets::resolve(targets, context, 0);
                let r = draw();
                let Some(texture) = texture_of(f, &call).filter(|&n| n != 0) else {
                    return r;
                };
                if defines_texture(&call) {
                    render_targets::texture_defined(targets, texture, call.u32(0));
                }
                let read = integer(f, GL_READ_FRAMEBUFFER_BINDING) as u32;
                let source = if read == window_fbo {
                    Some(window_eyes)
                } else {
                    render_targets::known(targets, context, read, &window_eyes)
                };
                let arg = |i: Option<usize>| i.map_or(0, |i| call.u32(i) as i32);
                let rect = (
                    arg(region[0]),
                    arg(region[1]),
                    arg(region[2]),
                    arg(region[3]),
                    arg(region[4]),
                    arg(region[5]),
                );
                match source {
                    Some(s) => {
                        render_targets::copied_from_eyes(targets, context, texture, &s, rect)
                    }
                    None => render_targets::forget(
                        targets,
                        context,
                        &[render_targets::Object::Texture(texture)],
                    ),
                }
                r
            }
        })
    })
}

/// The program deleted textures or renderbuffers `objects` in a context
/// given automatic stereo: their eyes go.
///
/// # Safety
/// The program's context is current on this thread.
pub unsafe fn objects_deleted(host: &impl Host, objects: &[render_targets::Object]) {
    let context = host.context();
    // SAFETY: contract.
    render_targets::with_group(host.group(), |targets| unsafe {
        render_targets::deleted(targets, context, objects)
    });
}

/// The program deleted framebuffers `fbos` of `host`'s context.
pub fn framebuffers_deleted(host: &impl Host, fbos: &[u32]) {
    let context = host.context();
    render_targets::with_group(host.group(), |targets| {
        render_targets::framebuffers_deleted(targets, context, fbos)
    });
}

/// The program's queries under automatic stereo ([`Counting`]):
/// glBeginQuery*, glEndQuery*, glGetQueryObject*, glDeleteQueries*,
/// glBeginConditionalRender*; the other commands of the family as they are.
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn queries<R: Returned>(
    f: &AutoFns,
    cur: &impl Host,
    call: Call,
    draw: impl Fn() -> R,
) -> R {
    let name = call.name;
    let indexed = name.contains("QueryIndexed");
    // SAFETY: contract (every GL call below is in the program's context).
    unsafe {
        if name.starts_with("glBeginQuery") {
            let (target, index, id) = if indexed {
                (call.u32(0), call.u32(1), call.u32(2))
            } else {
                (call.u32(0), 0, call.u32(1))
            };
            let r = draw();
            if counts(target) {
                // Only a query GL began (an error leaves none).
                let mut current = 0;
                (f.get_query_indexediv)(target, index, GL_CURRENT_QUERY, &mut current);
                if current as u32 == id && id != 0 {
                    cur.with_auto(|st, _| {
                        forget_segments(f, st, id);
                        st.queries
                            .retain(|q| (q.target, q.index) != (target, index));
                        st.queries.push(Counting {
                            target,
                            index,
                            id,
                            segments: Vec::new(),
                            paused: false,
                        });
                    });
                }
            }
            return r;
        }
        if name.starts_with("glEndQuery") {
            let (target, index) = (call.u32(0), if indexed { call.u32(1) } else { 0 });
            let r = draw();
            cur.with_auto(|st, _| {
                if let Some(i) = st
                    .queries
                    .iter()
                    .position(|q| (q.target, q.index) == (target, index))
                {
                    let q = st.queries.remove(i);
                    if !q.segments.is_empty() {
                        st.segmented.push((q.id, q.target, q.segments));
                    }
                }
            });
            return r;
        }
        if name.starts_with("glDeleteQueries") {
            let (n, ids) = (call.u32(0) as i32, call.ptr::<u32>(1));
            if n > 0 && !ids.is_null() {
                // SAFETY: GL's contract: n names at ids.
                let ids = std::slice::from_raw_parts(ids, n as usize);
                cur.with_auto(|st, _| {
                    for &id in ids {
                        forget_segments(f, st, id);
                        if let Some(i) = st.queries.iter().position(|q| q.id == id) {
                            // Deleting the program's active query ends it: the
                            // segment active in its place ends with it.
                            let q = st.queries.remove(i);
                            if !q.paused && !q.segments.is_empty() {
                                (f.end_query_indexed)(q.target, q.index);
                            }
                            (f.delete_queries)(q.segments.len() as i32, q.segments.as_ptr());
                        }
                    }
                });
            }
            return draw();
        }
        if name.starts_with("glGetQueryObject") {
            return query_object(f, cur, call, draw);
        }
        if name.starts_with("glBeginConditionalRender") {
            let (id, mode) = (call.u32(0), call.u32(1));
            // The condition is the sum of the segments: render under an
            // object whose own result says the same (waiting for them).
            let chosen = cur.with_auto(|st, _| {
                let (_, _, segments) = st.segmented.iter().find(|(i, ..)| *i == id)?;
                let result = |q: u32| {
                    let mut v = 0u64;
                    (f.get_query_objectui64v)(q, GL_QUERY_RESULT, &mut v);
                    v
                };
                if result(id) != 0 {
                    return Some(id);
                }
                Some(
                    segments
                        .iter()
                        .copied()
                        .find(|&q| result(q) != 0)
                        .unwrap_or(id),
                )
            });
            if let Some(q) = chosen {
                (f.begin_conditional_render)(q, mode);
                return R::from_bits(0);
            }
        }
        draw()
    }
}

/// Deletes the segments of the program's ended query `id`.
unsafe fn forget_segments(f: &AutoFns, st: &mut AutoState, id: u32) {
    if let Some(i) = st.segmented.iter().position(|(q, ..)| *q == id) {
        let (_, _, segments) = st.segmented.swap_remove(i);
        // SAFETY: the program's context is current (callers).
        unsafe { (f.delete_queries)(segments.len() as i32, segments.as_ptr()) };
    }
}

/// glGetQueryObject{iv,uiv,i64v,ui64v}(ARB, EXT) of a query with
/// segments: its result is their sum (any, for the boolean targets), and
/// it is available when all are.
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn query_object<R: Returned>(
    f: &AutoFns,
    cur: &impl Host,
    call: Call,
    draw: impl Fn() -> R,
) -> R {
    let (id, pname, params) = (call.u32(0), call.u32(1), call.ptr::<u8>(2));
    let name = call.name.trim_end_matches("ARB").trim_end_matches("EXT");
    let width = if name.ends_with("64v") { 8 } else { 4 };
    let signed = !name.ends_with("uiv") && !name.ends_with("ui64v");
    // SAFETY: contract; GL's: params holds one value of the command's type.
    unsafe {
        let wanted = matches!(
            pname,
            GL_QUERY_RESULT | GL_QUERY_RESULT_NO_WAIT | GL_QUERY_RESULT_AVAILABLE
        );
        let mut before = [0u8; 8];
        if wanted && !params.is_null() {
            std::ptr::copy_nonoverlapping(params, before.as_mut_ptr(), width);
        }
        let r = draw();
        if !wanted || params.is_null() {
            return r;
        }
        cur.with_auto(|st, _| {
            let Some((_, target, segments)) = st.segmented.iter().find(|(i, ..)| *i == id) else {
                return;
            };
            // Into a query buffer params is an offset: not summed here.
            if integer(f, GL_QUERY_BUFFER_BINDING) != 0 {
                return;
            }
            let value = |q: u32, p: u32| {
                let mut v = 0u64;
                (f.get_query_objectui64v)(q, p, &mut v);
                v
            };
            let available = segments
                .iter()
                .all(|&q| value(q, GL_QUERY_RESULT_AVAILABLE) != 0);
            let mut own = [0u8; 8];
            std::ptr::copy_nonoverlapping(params, own.as_mut_ptr(), width);
            let own = if width == 8 {
                u64::from_ne_bytes(own)
            } else {
                u64::from(u32::from_ne_bytes([own[0], own[1], own[2], own[3]]))
            };
            let out = match pname {
                GL_QUERY_RESULT_AVAILABLE => u64::from(own != 0 && available),
                GL_QUERY_RESULT_NO_WAIT if !available => {
                    // Not available: params as the program left it.
                    std::ptr::copy_nonoverlapping(before.as_ptr(), params, width);
                    return;
                }
                _ => {
                    let sum = segments
                        .iter()
                        .fold(own, |a, &q| a.saturating_add(value(q, GL_QUERY_RESULT)));
                    if *target == GL_PRIMITIVES_GENERATED || *target == GL_SAMPLES_PASSED {
                        sum
                    } else {
                        u64::from(sum != 0)
                    }
                }
            };
            if width == 8 {
                std::ptr::copy_nonoverlapping(out.to_ne_bytes().as_ptr(), params, 8);
            } else {
                let max = if signed {
                    i32::MAX as u64
                } else {
                    u32::MAX as u64
                };
                let v = out.min(max) as u32;
                std::ptr::copy_nonoverlapping(v.to_ne_bytes().as_ptr(), params, 4);
            }
        });
        r
    }
}

/// glUniformMatrix4fv / glProgramUniformMatrix4fv (and their ARB/EXT
/// names): a perspective projection among the matrices is remembered for
/// automatic convergence, while the convergence is automatic.
fn learn_projection(cur: &impl Host, call: &Call) {
    if live::convergence().is_some() && !live::from_depth() {
        return;
    }
    // glProgramUniform* take the program first.
    let at = usize::from(call.name.starts_with("glProgramUniform"));
    let count = call.u32(at + 1) as i32;
    let transpose = call.u32(at + 2) as u8 != 0;
    let value: *const f32 = call.ptr(at + 3);
    // A projection comes alone or with a few others; more is an array of
    // bones or instances, not looked through.
    if value.is_null() || !(1..=8).contains(&count) {
        return;
    }
    // SAFETY: GL's contract: `count` matrices of 16 floats at `value`.
    let value = unsafe { std::slice::from_raw_parts(value, 16 * count as usize) };
    let with_origin = Perspective::from_upload_with_origin(value, transpose);
    let p = with_origin.map(|(p, _)| p);
    let program = if at == 1 {
        call.u32(0)
    } else {
        // SAFETY: the program's context is current (callers); one value.
        tables().map_or(0, |t| unsafe { integer(&t.gl, GL_CURRENT_PROGRAM) } as u32)
    };
    if program == 0 {
        return;
    }
    // Where the program's position is known to come from named uniforms,
    // only uploads to those are its camera: a light's matrix (a shadow
    // map's lookup, glmark2's refract) is perspective too.
    let location = call.u32(at) as i32;
    // Where the position is that one matrix times the vertex, what is
    // uploaded to it is the draw's whole projection: an affine one (a
    // HUD's identity or orthographic matrix) makes its draws flat.
    let whole = count == 1
        && rewritten(cur.group(), program).is_some_and(|r| {
            r.projecting[0] == location && r.projecting[1..].iter().all(|&l| l < 0)
        });
    if let Some(r) = rewritten(cur.group(), program) {
        let known = r.projecting.iter().filter(|&&l| l >= 0);
        if r.projecting[0] >= 0
            && !known
                .clone()
                .any(|&l| l >= location && l < location + count)
        {
            return;
        }
    }
    // A perspective matrix is what the program projects with; another one
    // (a model-view beside it, an orthographic overlay) counts only where
    // no perspective one came.
    cur.with_auto(|st, _| {
        match st.uploads.iter_mut().find(|(q, _)| *q == program) {
            Some(u) if p.is_some() || whole => u.1 = p,
            Some(_) => {}
            None => st.uploads.push((program, p)),
        }
        if let Some((_, origin)) = with_origin {
            match st.origins.iter_mut().find(|(q, _)| *q == program) {
                Some(o) => o.1 = origin,
                None => st.origins.push((program, origin)),
            }
        }
    });
}

/// How a draw projects, as automatic convergence can tell.
#[derive(Clone, Copy, Debug)]
enum Projection {
    /// A perspective camera of these depth terms.
    Perspective(Perspective),
    /// No perspective: orthographic, w = 1 (nothing to converge).
    Flat,
    /// A program whose matrices automatic stereo cannot see.
    Unknown,
}

/// How the draw about to be made projects: fixed function's projection
/// matrix, or what the draw's program uploaded.
///
/// # Safety
/// The program's context is current (callers).
unsafe fn projection(f: &AutoFns, st: &AutoState) -> Projection {
    // SAFETY: contract.
    unsafe {
        match vertex_program(f) {
            Some((p, _)) => match st.uploads.iter().find(|(q, _)| *q == p) {
                Some((_, Some(persp))) => Projection::Perspective(*persp),
                Some((_, None)) => Projection::Flat,
                None => Projection::Unknown,
            },
            None => {
                let mut m = [0.0f64; 16];
                (f.get_doublev)(GL_PROJECTION_MATRIX, m.as_mut_ptr());
                Perspective::from_matrix(&m).map_or(Projection::Flat, Projection::Perspective)
            }
        }
    }
}

/// The convergence of the draw about to be made, where automatic
/// convergence chose a depth (the scene's projection was not known):
/// (the distance, for a draw whose perspective is known; the depth form's
/// (z_c, k), for one whose projection is not). (None, None): the
/// settings' convergence as it is.
///
/// # Safety
/// The program's context is current (callers).
unsafe fn draw_convergence(f: &AutoFns, st: &AutoState) -> (Option<f32>, Option<(f32, f32)>) {
    if live::convergence().is_some() {
        return (None, None);
    }
    let Some((z, alpha)) = live::automatic_depth() else {
        return (None, None);
    };
    // SAFETY: contract.
    match unsafe { projection(f, st) } {
        Projection::Perspective(p) => (p.distance_at(f64::from(z)).map(|c| c as f32), None),
        Projection::Flat => (None, None),
        Projection::Unknown => (None, Some((z, 1.0 / (z - alpha)))),
    }
}

/// The projection of a draw of a measured frame: Some(known perspective)
/// or Some(None) for one automatic stereo cannot see; None on other
/// frames, and for flat draws (nothing there to converge on).
///
/// # Safety
/// The program's context is current (callers).
unsafe fn draw_perspective(f: &AutoFns, st: &AutoState) -> Option<Option<Perspective>> {
    if !records(st) {
        return None;
    }
    // SAFETY: contract.
    match unsafe { projection(f, st) } {
        Projection::Perspective(p) => Some(Some(p)),
        Projection::Unknown => Some(None),
        Projection::Flat => None,
    }
}

/// Whether this frame's draws record where its scene is and how it
/// projects: a frame automatic convergence measures, and every frame
/// whose eyes are made from its depth.
fn records(st: &AutoState) -> bool {
    live::from_depth() || (!st.unmeasured && live::convergence().is_none())
}

/// Whether a draw now writes depth: the depth test on and depth writes
/// on (a framebuffer without depth writes none, and its depth stays
/// what the frame's clear made it).
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn writes_depth(f: &AutoFns) -> bool {
    const GL_DEPTH_WRITEMASK: u32 = 0x0B72;
    // SAFETY: contract; queries of state every context has.
    unsafe {
        (f.is_enabled)(crate::gl::enums::GL_DEPTH_TEST) != 0 && integer(f, GL_DEPTH_WRITEMASK) != 0
    }
}

/// `--auto=depth`: a draw of known perspective into the window's eyes
/// with the depth test off (glmark2 ideas' table, a floor or sky drawn
/// first as a backdrop) writes no depth, so nothing could be made of its
/// pixels: it would stay at the screen however far it is. It is drawn
/// as the program drew it, with the depth array's second layer (no eye's
/// under this mode) at the depth attachment and the depth test on with
/// GL_ALWAYS: every fragment passes, as with the test off, so the colour
/// is the program's to the bit, and the second layer gets the depth of
/// what it shows (the last such draw's, the painter's order). That layer
/// is cleared to the far plane at the first such draw of a frame; the
/// present takes the nearer of the two layers ([`crate::auto::from_depth`]).
/// The program's depth state is as it was after the draw; the second
/// layer stays attached until something else may use the depth
/// ([`restore_depth`]: a renderer such as llvmpipe finishes its binned
/// work at each change of attachments, so one a draw would cost more than
/// the draws). Not with the stencil test on (the second layer's stencil
/// is not the program's) or rasterizer discard (nothing drawn). Whether
/// the draw wrote its depth there.
///
/// # Safety
/// The program's context is current on this thread, the window's eyes'
/// framebuffer object `fbo` bound for drawing with `layered` attached
/// (or, after an earlier such draw, its second depth layer).
unsafe fn depth_beside(
    f: &AutoFns,
    st: &mut AutoState,
    (fbo, layered): (u32, &Attachments),
    draw: &mut dyn FnMut(),
) -> bool {
    const GL_STENCIL_TEST: u32 = 0x0B90;
    const GL_SCISSOR_TEST: u32 = 0x0C11;
    const GL_DEPTH_FUNC: u32 = 0x0B74;
    const GL_DEPTH_WRITEMASK: u32 = 0x0B72;
    const GL_DEPTH: u32 = 0x1801;
    const GL_ALWAYS: u32 = 0x0207;
    use crate::gl::enums::GL_DEPTH_TEST;
    // SAFETY: contract.
    unsafe {
        if (f.is_enabled)(GL_DEPTH_TEST) != 0
            || (f.is_enabled)(GL_STENCIL_TEST) != 0
            || (f.is_enabled)(GL_RASTERIZER_DISCARD) != 0
        {
            restore_depth(f, st);
            draw();
            return false;
        }
        if st.beside_attached.is_none() {
            if !layered.attach_depth(GL_DRAW_FRAMEBUFFER, 1) {
                draw();
                return false;
            }
            st.beside_attached = Some((fbo, *layered));
        }
        let func = integer(f, GL_DEPTH_FUNC) as u32;
        let mask = integer(f, GL_DEPTH_WRITEMASK) != 0;
        (f.depth_mask)(1);
        if !st.depth_beside {
            let scissor = (f.is_enabled)(GL_SCISSOR_TEST) != 0;
            if scissor {
                (f.disable)(GL_SCISSOR_TEST);
            }
            let far = 1.0f32;
            (f.clear_bufferfv)(GL_DEPTH, 0, &far);
            if scissor {
                (f.enable)(GL_SCISSOR_TEST);
            }
        }
        (f.enable)(GL_DEPTH_TEST);
        (f.depth_func)(GL_ALWAYS);
        draw();
        (f.disable)(GL_DEPTH_TEST);
        (f.depth_func)(func);
        (f.depth_mask)(mask as u8);
        true
    }
}

/// Puts the window's depth (the depth array's first layer) back at its
/// eyes' depth attachment where [`depth_beside`] left the second there.
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn restore_depth(f: &AutoFns, st: &mut AutoState) {
    let Some((fbo, layered)) = st.beside_attached.take() else {
        return;
    };
    const GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME: u32 = 0x8CD1;
    const GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER: u32 = 0x8CD4;
    // SAFETY: contract; the framebuffer object is this context's.
    unsafe {
        let bound = integer(f, GL_DRAW_FRAMEBUFFER_BINDING) as u32;
        if bound != fbo {
            if (f.is_framebuffer)(fbo) == 0 {
                // Gone with its drawable.
                return;
            }
            (f.bind_framebuffer)(GL_DRAW_FRAMEBUFFER, fbo);
        }
        // Only where the second layer is still there: the layer may have
        // attached new eyes since (a resize), or let the object go.
        let query = |pname| {
            let mut v = -1;
            (f.get_framebuffer_attachment_parameteriv)(
                GL_DRAW_FRAMEBUFFER,
                layered.depth_point(),
                pname,
                &mut v,
            );
            v
        };
        if integer(f, GL_DRAW_FRAMEBUFFER_BINDING) as u32 == fbo
            && query(GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME) as u32 == layered.depth()
            && query(GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER) == 1
        {
            layered.attach_depth(GL_DRAW_FRAMEBUFFER, 0);
        }
        if bound != fbo {
            (f.bind_framebuffer)(GL_DRAW_FRAMEBUFFER, bound);
        }
    }
}

/// [`eyes`] for a draw [`depth_beside`] may make: the window's eyes'
/// framebuffer object and attachments `window`; what the draw did is
/// recorded in `st` for the present.
///
/// # Safety
/// As [`depth_beside`].
unsafe fn eyes_beside(
    t: &Tables,
    st: &mut AutoState,
    path: Path,
    settings: &DrawSettings,
    window: (u32, &Attachments),
    sampled: &Sampled,
    draw: &mut dyn FnMut(),
) {
    let mut queries = std::mem::take(&mut st.queries);
    let mut wrote = false;
    // SAFETY: contract.
    unsafe {
        eyes(
            t,
            path,
            settings,
            window.1,
            sampled,
            false,
            &mut queries,
            &mut || {
                wrote = depth_beside(&t.gl, st, window, draw);
            },
        );
    }
    st.queries = queries;
    st.depth_beside |= wrote;
}

/// `--auto=depth`: a flat draw (w = 1: a HUD, text, a 2D pass) comes
/// into the window's eyes after the frame's scene: the colour its draw
/// buffer holds now (the scene) is copied into that array's right-eye
/// layer, which nothing else draws in this mode, so that the present
/// tells the pixels flat draws changed and keeps them at the screen
/// ([`crate::auto::from_depth`]). Once per scene.
///
/// # Safety
/// The program's context is current on this thread, the window's eyes'
/// framebuffer object bound for drawing.
unsafe fn keep_scene_colour(
    f: &AutoFns,
    api: render_targets::ContextApi,
    layered: &Attachments,
) -> Option<u32> {
    const GL_DRAW_BUFFER0: u32 = 0x8825;
    const GL_COLOR_ATTACHMENT0: u32 = 0x8CE0;
    if !live::from_depth() {
        return None;
    }
    // SAFETY: contract.
    unsafe {
        let buffer = integer(f, GL_DRAW_BUFFER0) as u32;
        let i = buffer
            .checked_sub(GL_COLOR_ATTACHMENT0)
            .filter(|&i| i < 8)?;
        let array = layered.colour_at(i as usize);
        render_targets::copy_left_colour(api, array).then_some(array)
    }
}

/// Whether `call` (of [`Family::Clear`]) clears depth, and of which
/// framebuffer: Some(None) the draw framebuffer, Some(Some(n)) framebuffer
/// object n (glClearNamedFramebuffer*; 0 the default).
fn clears_depth(call: &Call) -> Option<Option<u32>> {
    const GL_DEPTH_BUFFER_BIT: u32 = 0x100;
    const GL_DEPTH: u32 = 0x1801;
    const GL_DEPTH_STENCIL: u32 = 0x84F9;
    let depth = |buffer: u32| buffer == GL_DEPTH || buffer == GL_DEPTH_STENCIL;
    match call.name {
        "glClear" => (call.u32(0) & GL_DEPTH_BUFFER_BIT != 0).then_some(None),
        n if n.starts_with("glClearNamedFramebuffer") => {
            depth(call.u32(1)).then_some(Some(call.u32(0)))
        }
        n if n.starts_with("glClearBuffer") => depth(call.u32(0)).then_some(None),
        _ => None,
    }
}

/// Before a clear (glClear, glClearBuffer*, glClearNamedFramebuffer*; by
/// the hand-written replacements of the preload layer or through
/// [`around`]): the window's depth is put back where a draw with the
/// depth test off left the depth array's second layer attached
/// (`restore_depth`: the clear is the program's depth's); and under
/// `--auto=depth`, a clear of the depth of the window's eyes or of the
/// scene's render target after the frame's scene, with depth writes on
/// (a clear honours the mask), first copies the scene's depth aside, as a
/// draw that would overwrite it does (`keep_scene_depth`), so that the
/// eyes are made from the scene and not from what is drawn after the
/// clear (VTK's and ParaView's orientation axes in a corner renderer, a
/// gizmo drawn over fresh depth). Not while a display list is compiled
/// (its clears run when it is called).
pub fn before_clear(cur: &impl Host, call: &Call) {
    let Some(t) = tables() else {
        return;
    };
    // SAFETY: the program's context is current on this thread.
    cur.with_auto(|st, _| unsafe { restore_depth(&t.gl, st) });
    let Some(named) = clears_depth(call) else {
        return;
    };
    if COMPILING.with(std::cell::Cell::get) || !live::from_depth() {
        return;
    }
    let f = &t.gl;
    let group = cur.group();
    cur.with_auto(|st, eyes_of| {
        let Some((window_fbo, layered)) = eyes_of else {
            return;
        };
        const GL_DEPTH_WRITEMASK: u32 = 0x0B72;
        // SAFETY: the program's context is current on this thread.
        let (mask, bound) = unsafe {
            (
                integer(f, GL_DEPTH_WRITEMASK) != 0,
                integer(f, GL_DRAW_FRAMEBUFFER_BINDING) as u32,
            )
        };
        let fbo = match named {
            // The default framebuffer is the window's eyes.
            Some(0) => window_fbo,
            Some(n) => n,
            None => bound,
        };
        if !mask || !records(st) {
            return;
        }
        render_targets::with_group(group, |targets| {
            // SAFETY: as above.
            unsafe {
                let api = render_targets::context_api(targets);
                if fbo == window_fbo {
                    let Some(scene) = st.window_drawn else {
                        return;
                    };
                    if !st.depth_copied {
                        st.depth_copied = render_targets::copy_left_depth(
                            api,
                            layered.depth(),
                            &mut st.depth_copy,
                        );
                    }
                    if st.depth_copied {
                        st.depth_cleared = Some(scene.viewport);
                    }
                    return;
                }
                // The scene's render target, where the cleared framebuffer
                // (the one bound) has its depth array attached.
                let scene = &mut targets.scene;
                let Some((a, _, drawn)) = scene.drawn else {
                    return;
                };
                const GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME: u32 = 0x8CD1;
                let mut attached = -1;
                (f.get_framebuffer_attachment_parameteriv)(
                    GL_DRAW_FRAMEBUFFER,
                    a.depth_point(),
                    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME,
                    &mut attached,
                );
                if fbo != bound || attached as u32 != a.depth() || a.depth() == 0 {
                    return;
                }
                if !scene.copied {
                    scene.copied = render_targets::copy_left_depth(api, a.depth(), &mut scene.copy);
                }
                if scene.copied {
                    scene.cleared = Some(drawn.viewport);
                }
            }
        });
    });
}

/// A draw that is not the scene's comes into depth `array` holding this
/// measured frame's scene (drawn with a known perspective: `known`), not
/// yet kept (`copied`): its left eye is copied into `copy` before the
/// draw may overwrite it, once per scene drawn. A draw that writes no
/// depth (a HUD drawn with the depth test or depth writes off) leaves
/// the scene's depth where it is, to be read there (in place, where it is
/// memory): nothing is copied for it.
///
/// # Safety
/// The program's context is current on this thread.
unsafe fn keep_scene_depth(
    f: &AutoFns,
    api: render_targets::ContextApi,
    measured: bool,
    known: bool,
    array: u32,
    (copy, copied): (&mut render_targets::DepthCopy, &mut bool),
) {
    // SAFETY: contract.
    if !measured || !known || *copied || array == 0 || !unsafe { writes_depth(f) } {
        return;
    }
    // SAFETY: contract.
    *copied = unsafe { render_targets::copy_left_depth(api, array, copy) };
}

/// What automatic convergence reads of a frame at its present, and what
/// eyes made from depth need of every frame ([`converge::Frame::converges`]
/// says whether it is measured), in the program's context; None when
/// neither applies: this frame is not measured (the user set
/// the convergence, automatic stereo is off, it is not a
/// [`converge::PERIOD`]th frame, nothing was drawn into the window's eyes
/// or a stereoized render target this frame — the window's depth is not
/// the scene's then — or no perspective projection is known). A frame
/// that drew only into render targets is measured in the last of them.
///
/// # Safety
/// The program's context is current on this thread.
pub unsafe fn frame_geometry(
    st: &mut AutoState,
    group: u64,
    frame: u64,
) -> Option<converge::Frame> {
    // This frame's draws read their projections if the last present
    // said so (or its first draw found it due); the next frame's do if
    // it is measured.
    if let Some(t) = tables() {
        // SAFETY: contract.
        unsafe { restore_depth(&t.gl, st) };
    }
    let measured = !st.unmeasured;
    if measured {
        st.measured_at = Some(std::time::Instant::now());
    }
    st.unmeasured = !converge::measures(frame + 1);
    st.clock_read = false;
    let copied = std::mem::take(&mut st.depth_copied);
    st.depth_cleared = None;
    let overlays = std::mem::take(&mut st.colour_kept);
    let depth_written = std::mem::take(&mut st.depth_written);
    let depth_beside = std::mem::take(&mut st.depth_beside);
    let origin = {
        let o = &mut st.frame_origins;
        let median = (!o.is_empty()).then(|| {
            let mid = o.len() / 2;
            *o.select_nth_unstable_by(mid, f64::total_cmp).1
        });
        o.clear();
        median
    };
    let window = st
        .window_drawn
        .take()
        .map(|scene| (scene, copied.then_some(st.depth_copy.texture)));
    let mut target_overlays = None;
    let target = render_targets::with_group(group, |targets| {
        let s = &mut targets.scene;
        let copied = std::mem::take(&mut s.copied);
        s.cleared = None;
        target_overlays = s.colour_kept.take();
        s.drawn.take().map(|(a, size, scene)| {
            let a = if copied {
                a.with_depth_copy(s.copy.texture)
            } else {
                a
            };
            (a, size, scene)
        })
    });
    let converges = measured && live::convergence().is_none() && live::auto_on();
    if !(converges || live::from_depth()) || (window.is_none() && target.is_none()) {
        return None;
    }
    let t = tables()?;
    let f = &t.gl;
    // SAFETY: contract.
    unsafe {
        // Single precision: OpenGL ES has no glGetDoublev.
        let mut range = [0.0f32; 2];
        (f.get_floatv)(GL_DEPTH_RANGE, range.as_mut_ptr());
        let mut clear = 1.0f32;
        (f.get_floatv)(GL_DEPTH_CLEAR_VALUE, &mut clear);
        // GL 4.5's clip control (a core context of an older GL raises an
        // error, which the caller keeps apart, and leaves the default).
        let mut mode = GL_NEGATIVE_ONE_TO_ONE as i32;
        (f.get_integerv)(GL_CLIP_DEPTH_MODE, &mut mode);
        Some(converge::Frame {
            zero_to_one: mode as u32 == GL_ZERO_TO_ONE,
            depth_range: (f64::from(range[0]), f64::from(range[1])),
            clear_depth: f64::from(clear),
            window,
            target,
            origin,
            left_shift: crate::math::Eye::Left.sign() * st.settings().effective_separation(),
            converges,
            overlays,
            target_overlays,
            depth_written,
            depth_beside,
        })
    }
}

/// glEnable / glDisable / glIsEnabled of GL_3DVISION_STEREO_NV.
fn settings_call<R: Returned>(call: Call, draw: impl Fn() -> R) -> R {
    if call.args.len() != 1 || call.u32(0) != GL_3DVISION_STEREO_NV {
        return draw();
    }
    match call.name {
        "glEnable" => live::set_auto_on(true),
        "glDisable" => live::set_auto_on(false),
        "glIsEnabled" => return R::from_bits(live::auto_on() as u64),
        _ => return draw(),
    }
    R::from_bits(0)
}

/// A call of the drawing families (module docs).
fn drawing(t: &Tables, cur: &impl Host, call: Call, draw: &mut dyn FnMut()) {
    let f = &t.gl;
    let group = cur.group();
    cur.with_auto(|st, eyes_of| {
        if st.in_mono_begin {
            // Between a glBegin GL executed and its glEnd only vertex
            // commands (and glCallList) are allowed: nothing of the
            // layer's own.
            if call.name == "glEnd" {
                st.in_mono_begin = false;
            }
            return draw();
        }
        // Only the draws [`depth_beside`] may make keep the depth layer it
        // attached (each decides below); anything else may use the depth.
        let may_keep =
            call.family == Family::Draw || matches!(call.name, "glBegin" | "glEnd" | "glCallList");
        if !may_keep {
            // SAFETY: the program's context is current on this thread.
            unsafe { restore_depth(f, st) };
        }
        let Some((mut app_fbo, mut layered)) = eyes_of else {
            return draw();
        };
        if st.unmeasured && !st.clock_read {
            st.clock_read = true;
            st.unmeasured = !st.measured_at.is_some_and(|t| converge::due(t.elapsed()));
        }
        let (window_fbo, window_eyes) = (app_fbo, layered);
        render_targets::with_group(group, |targets| {
            // SAFETY: the program's context is current on this thread.
            unsafe {
                // A render target of the program's drawn in stereo takes the
                // place of the window's eyes; the others' textures are given
                // their left eye before anything may sample them.
                let context = cur.context();
                let blit = call.family == Family::Blit;
                let mut sampled = Sampled::default();
                let mut known_window_draw = false;
                if st.compiling.is_none() {
                    let api = render_targets::context_api(targets);
                    let fbo = integer(f, GL_DRAW_FRAMEBUFFER_BINDING) as u32;
                    let perspective = if blit {
                        None
                    } else {
                        draw_perspective(f, st).map(|perspective| {
                            let mut vp = [0i32; 4];
                            (f.get_integerv)(GL_VIEWPORT, vp.as_mut_ptr());
                            Scene {
                                perspective,
                                viewport: (vp[0], vp[1], vp[2], vp[3]),
                            }
                        })
                    };
                    // Where the object it draws is (a fallback for a
                    // scene that writes no depth).
                    if perspective.is_some_and(|s| s.perspective.is_some())
                        && st.frame_origins.len() < 4096
                    {
                        if let Some((p, _)) = vertex_program(f) {
                            if let Some(&(_, w)) = st.origins.iter().find(|(q, _)| *q == p) {
                                if w > 0.0 && w.is_finite() {
                                    st.frame_origins.push(w);
                                }
                            }
                        }
                    }
                    // A known perspective draw is the scene; one whose
                    // projection is unknown only where none known came.
                    let known = |s: &Option<Scene>| s.is_some_and(|s| s.perspective.is_some());
                    if !st.depth_written && perspective.is_some() && live::from_depth() {
                        st.depth_written = writes_depth(f);
                    }
                    // After the scene's depth was cleared, a perspective
                    // draw in another viewport is an overlay (before_clear).
                    let overlay = st
                        .depth_cleared
                        .is_some_and(|vp| perspective.is_some_and(|p| p.viewport != vp));
                    known_window_draw = fbo == window_fbo && known(&perspective) && !overlay;
                    if fbo == window_fbo && known(&perspective) && !overlay {
                        st.depth_cleared = None;
                        st.window_drawn = perspective;
                        st.depth_copied = false;
                        st.colour_kept = false;
                    } else if fbo == window_fbo && !blit {
                        if (perspective.is_none() || overlay)
                            && known(&st.window_drawn)
                            && !st.colour_kept
                        {
                            st.colour_kept = keep_scene_colour(f, api, &layered).is_some();
                        }
                        keep_scene_depth(
                            f,
                            api,
                            records(st),
                            known(&st.window_drawn),
                            layered.depth(),
                            (&mut st.depth_copy, &mut st.depth_copied),
                        );
                        if perspective.is_some() && !known(&st.window_drawn) && !overlay {
                            if st.depth_cleared.take().is_some() {
                                // The scene again after its depth was
                                // cleared: its own depth now.
                                st.depth_copied = false;
                            }
                            st.window_drawn = perspective;
                        }
                    }
                    if !blit {
                        // Between glBegin and glEnd (the layer's list is
                        // compiling: glActiveTexture would go into it)
                        // the units are as glBegin found them.
                        sampled = if st.in_begin {
                            st.sampled.as_ref().map(|s| s.1.clone()).unwrap_or_default()
                        } else {
                            st.sampled(targets)
                        };
                    }
                    if fbo != app_fbo {
                        // The policy's facts about this draw
                        // (render_targets, "The policy").
                        let read = integer(f, GL_READ_FRAMEBUFFER_BINDING) as u32;
                        let kind = Draw {
                            shifted: !blit && shifted(f, group, call.name),
                            samples_stereo: sampled.any(),
                            from_stereo: blit
                                && (read == window_fbo
                                    || render_targets::known(targets, context, read, &layered)
                                        .is_some()),
                        };
                        if let Some(a) =
                            render_targets::eyes_of(targets, context, fbo, &layered, kind)
                        {
                            (app_fbo, layered) = (fbo, a);
                            // Measured: the last one with depth (a scene;
                            // the post-processing passes after it have none).
                            let size = render_targets::size(targets, context, fbo);
                            // After the scene's depth was cleared, a
                            // perspective draw in another viewport into it
                            // is an overlay (before_clear).
                            let overlay = targets.scene.cleared.is_some_and(|vp| {
                                targets
                                    .scene
                                    .drawn
                                    .is_some_and(|d| d.0.depth() == a.depth())
                                    && perspective.is_some_and(|p| p.viewport != vp)
                            });
                            match (perspective, size, a.has_depth()) {
                                (Some(scene), Some(s), true)
                                    if scene.perspective.is_some() && !overlay =>
                                {
                                    targets.scene.drawn = Some((a, s, scene));
                                    targets.scene.copied = false;
                                    targets.scene.cleared = None;
                                    targets.scene.colour_kept = None;
                                }
                                _ if blit => {}
                                (p, size, depth) => {
                                    let scene = &mut targets.scene;
                                    if let Some((t, _, s)) = scene.drawn {
                                        if t.depth() == a.depth() {
                                            keep_scene_depth(
                                                f,
                                                api,
                                                records(st),
                                                s.perspective.is_some(),
                                                a.depth(),
                                                (&mut scene.copy, &mut scene.copied),
                                            );
                                            // A flat draw, or a gizmo after
                                            // a depth clear: its pixels are
                                            // told at the present by the
                                            // scene's colour kept before it,
                                            // as in the window.
                                            if (p.is_none() || overlay)
                                                && s.perspective.is_some()
                                                && scene.colour_kept.is_none()
                                            {
                                                scene.colour_kept = keep_scene_colour(f, api, &a);
                                            }
                                        }
                                    }
                                    // Unknown projections where no known one came.
                                    let unknown_first = targets
                                        .scene
                                        .drawn
                                        .is_none_or(|t| t.2.perspective.is_none());
                                    if let (Some(scene), Some(s), true, true, false) =
                                        (p, size, depth, unknown_first, overlay)
                                    {
                                        if targets.scene.cleared.is_some() {
                                            // The scene again after its depth
                                            // was cleared: its own depth now.
                                            targets.scene.copied = false;
                                            targets.scene.cleared = None;
                                        }
                                        targets.scene.colour_kept = None;
                                        targets.scene.drawn = Some((a, s, scene));
                                    }
                                }
                            }
                        }
                    }
                    render_targets::resolve(targets, context, fbo);
                }
                // A draw into the window's eyes of known perspective under
                // --auto=depth: one [`depth_beside`] may give its depth.
                let beside = live::from_depth() && app_fbo == window_fbo && known_window_draw;
                let keeps_depth = |st: &AutoState| beside && !st.feedback;
                match (call.family, call.name) {
                    (Family::DisplayList, "glNewList") => {
                        let (list, mode) = (call.u32(0), call.u32(1));
                        if mode == GL_COMPILE_AND_EXECUTE && st.compiling.is_none() {
                            (f.new_list)(list, GL_COMPILE);
                            st.compiling = Some((list, true));
                        } else {
                            draw();
                            st.compiling = Some((list, false));
                        }
                        st.compiling_plain = true;
                        COMPILING.with(|c| c.set(true));
                        return;
                    }
                    (Family::DisplayList, "glEndList") => {
                        draw();
                        COMPILING.with(|c| c.set(false));
                        let Some((list, execute)) = st.compiling.take() else {
                            return;
                        };
                        let plain = st.compiling_plain;
                        st.lists.insert(list, plain);
                        if execute {
                            let settings = st.draw_settings(f);
                            let path = choose(t, cur, st, app_fbo, !plain);
                            eyes(
                                t,
                                path,
                                &settings,
                                &layered,
                                &sampled,
                                true,
                                &mut st.queries,
                                &mut || (f.call_list)(list),
                            );
                            if !plain {
                                st.forget_enables();
                            }
                        }
                        return;
                    }
                    _ if st.compiling.is_some() => {
                        // A list called inside keeps this one geometry only
                        // if it is; glBitmap and glDrawPixels need each eye's
                        // raster position.
                        let nested_plain =
                            call.name == "glCallList" && st.lists.get(&call.u32(0)) == Some(&true);
                        if (call.family == Family::DisplayList && !nested_plain)
                            || call.family == Family::RasterPixels
                        {
                            st.compiling_plain = false;
                        }
                        return draw();
                    }
                    (Family::BeginEnd, "glBegin") => {
                        // Drawn at glEnd (from the layer's list), where it
                        // may keep the depth layer beside; drawn now where
                        // it is made mono.
                        if integer(f, GL_DRAW_FRAMEBUFFER_BINDING) as u32 != app_fbo {
                            restore_depth(f, st);
                            st.in_mono_begin = true;
                            return draw();
                        }
                        if st.list == 0 {
                            st.list = (f.gen_lists)(1);
                        }
                        if st.list == 0 {
                            restore_depth(f, st);
                            st.in_mono_begin = true;
                            return draw();
                        }
                        (f.new_list)(st.list, GL_COMPILE);
                        st.in_begin = true;
                        return draw();
                    }
                    (Family::BeginEnd, "glEnd") => {
                        if !st.in_begin {
                            restore_depth(f, st);
                            return draw();
                        }
                        draw();
                        (f.end_list)();
                        st.in_begin = false;
                        let settings = st.draw_settings(f);
                        let path = choose(t, cur, st, app_fbo, false);
                        let list = st.list;
                        let mut draw_list = || (f.call_list)(list);
                        if keeps_depth(st) {
                            let window = (window_fbo, &layered);
                            let d = &mut draw_list;
                            return eyes_beside(t, st, path, &settings, window, &sampled, d);
                        }
                        restore_depth(f, st);
                        let q = &mut st.queries;
                        return eyes(
                            t,
                            path,
                            &settings,
                            &layered,
                            &sampled,
                            false,
                            q,
                            &mut draw_list,
                        );
                    }
                    _ if st.in_begin => return draw(),
                    (Family::RasterPixels, _) if live::from_depth() => return draw(),
                    (Family::RasterPixels, name) => {
                        let settings = st.draw_settings(f);
                        let q = &mut st.queries;
                        return pixels(t, &settings.nv, app_fbo, &layered, name, call, q, draw);
                    }
                    (Family::Blit, _) => {
                        if integer(f, GL_DRAW_FRAMEBUFFER_BINDING) as u32 != app_fbo
                            || live::from_depth()
                        {
                            return draw();
                        }
                        // Each eye from the same eye of the source where it
                        // has eyes: the window's, or a stereoized target's
                        // (a scene drawn off screen and blitted into the
                        // window, as VTK does); else the one picture.
                        let read = integer(f, GL_READ_FRAMEBUFFER_BINDING) as u32;
                        let source = if read == window_fbo {
                            Some(window_eyes)
                        } else {
                            render_targets::known(targets, context, read, &window_eyes)
                        };
                        for eye in EYES {
                            layered.attach(GL_DRAW_FRAMEBUFFER, Some(eye));
                            if let Some(s) = &source {
                                s.attach(GL_READ_FRAMEBUFFER, Some(eye));
                            }
                            draw();
                        }
                        layered.attach(GL_DRAW_FRAMEBUFFER, None);
                        if let Some(s) = &source {
                            s.attach(GL_READ_FRAMEBUFFER, None);
                        }
                        return;
                    }
                    _ => {}
                }
                let lists = call.family == Family::DisplayList;
                // A list of geometry only takes the fast path, with the
                // matrices put back between the eyes (it may move them).
                let plain =
                    lists && call.name == "glCallList" && st.lists.get(&call.u32(0)) == Some(&true);
                let settings = st.draw_settings(f);
                let path = choose(t, cur, st, app_fbo, lists && !plain);
                if (call.family == Family::Draw || plain) && keeps_depth(st) {
                    let window = (window_fbo, &layered);
                    return eyes_beside(t, st, path, &settings, window, &sampled, draw);
                }
                restore_depth(f, st);
                if st.feedback && call.family == Family::Draw {
                    // Transform feedback captures what the mono program
                    // would: the draw once, unshifted and not rasterized,
                    // then both eyes with the capture paused. With
                    // rasterizer discard on nothing reaches the eyes: the
                    // draw once.
                    let mono = Path::Mono(match path {
                        Path::Uniform {
                            target,
                            standin: false,
                        } => Some(target),
                        _ => None,
                    });
                    if (f.is_enabled)(GL_RASTERIZER_DISCARD) != 0 {
                        let q = &mut st.queries;
                        return eyes(t, mono, &settings, &layered, &sampled, false, q, draw);
                    }
                    if integer(f, GL_TRANSFORM_FEEDBACK_ACTIVE) != 0
                        && integer(f, GL_TRANSFORM_FEEDBACK_PAUSED) == 0
                    {
                        let q = &mut st.queries;
                        (f.enable)(GL_RASTERIZER_DISCARD);
                        eyes(t, mono, &settings, &layered, &sampled, false, q, draw);
                        (f.disable)(GL_RASTERIZER_DISCARD);
                        (f.pause_transform_feedback)();
                        // The mono draw generated the primitives: the eyes'
                        // are not counted again.
                        pause_counting(f, q, |t| t == GL_PRIMITIVES_GENERATED);
                        eyes(t, path, &settings, &layered, &sampled, false, q, draw);
                        resume_counting(f, q);
                        (f.resume_transform_feedback)();
                        return;
                    }
                }
                eyes(
                    t,
                    path,
                    &settings,
                    &layered,
                    &sampled,
                    lists,
                    &mut st.queries,
                    draw,
                );
                if lists && !plain {
                    // It may have changed any enable.
                    st.forget_enables();
                }
            }
        })
    })
}

/// glDrawPixels, glBitmap, glCopyPixels (`name`) into each eye at the
/// eye's raster position ([`crate::auto::fixed`]).
#[allow(clippy::too_many_arguments)] // as eyes()
unsafe fn pixels(
    t: &Tables,
    settings: &StereoSettings,
    app_fbo: u32,
    layered: &Attachments,
    name: &str,
    call: Call,
    queries: &mut [Counting],
    draw: &mut dyn FnMut(),
) {
    let f = &t.gl;
    // SAFETY: the program's context is current (callers).
    unsafe {
        if integer(f, GL_DRAW_FRAMEBUFFER_BINDING) as u32 != app_fbo {
            return draw();
        }
        let valid = integer(f, GL_CURRENT_RASTER_POSITION_VALID) != 0;
        let mut raster = [0.0f32; 4];
        (f.get_floatv)(GL_CURRENT_RASTER_POSITION, raster.as_mut_ptr());
        let mut viewport = [0i32; 4];
        (f.get_integerv)(GL_VIEWPORT, viewport.as_mut_ptr());
        let shifts = EYES.map(|e| {
            if valid {
                fixed::raster_shift(settings, raster, viewport[2] as f64, e)
            } else {
                0.0
            }
        });
        let nudge = |dx: f64, dy: f64| {
            if dx != 0.0 || dy != 0.0 {
                (f.bitmap)(0, 0, 0.0, 0.0, dx as f32, dy as f32, std::ptr::null());
            }
        };
        // The read framebuffer follows the eye (glCopyPixels) when it is
        // the eyes' too.
        let read_too = integer(f, GL_READ_FRAMEBUFFER_BINDING) as u32 == app_fbo;
        let (xmove, ymove) = if name.starts_with("glBitmap") && valid {
            (call.f32(4) as f64, call.f32(5) as f64)
        } else {
            (0.0, 0.0)
        };
        for (i, eye) in EYES.into_iter().enumerate() {
            if i == 1 {
                pause_counting(f, queries, |_| true);
            }
            layered.attach(GL_DRAW_FRAMEBUFFER, Some(eye));
            if read_too {
                layered.attach(GL_READ_FRAMEBUFFER, Some(eye));
            }
            nudge(shifts[i], 0.0);
            draw();
            // glBitmap moved the raster position by (xmove, ymove): once,
            // as in mono.
            if i == 0 {
                nudge(-shifts[i] - xmove, -ymove);
            } else {
                nudge(-shifts[i], 0.0);
            }
        }
        layered.attach(GL_DRAW_FRAMEBUFFER, None);
        resume_counting(f, queries);
        if read_too {
            layered.attach(GL_READ_FRAMEBUFFER, None);
        }
    }
}

/// After glLinkProgram of `program` in a context given automatic stereo:
/// its last vertex stage relinked with the eye's shift
/// ([`crate::auto::link`]), and what came of it recorded for its draws.
/// Said once per reason on stderr when a program keeps its stage.
///
/// # Safety
/// The program's context is current on this thread; GL errors the relink
/// raises are the caller's to drop.
pub unsafe fn linked(group: u64, program: u32) {
    let Some(t) = tables() else {
        return;
    };
    let Some(location) = reserved_location(&t.gl) else {
        return;
    };
    // SAFETY: contract.
    let outcome = unsafe {
        link::shift_last_stage(
            &t.link,
            program,
            LayerWrite::FromUniform,
            Some(location),
            context_is_es(&t.gl),
        )
    };
    // SAFETY: contract.
    let at = unsafe { located(t, program, &outcome) };
    record(group, program, at);
}

/// Whether the context current on this thread is an OpenGL ES one (its
/// GL_VERSION begins "OpenGL ES", as every ES version's must).
///
/// # Safety
/// A context is current on this thread.
unsafe fn context_is_es(f: &AutoFns) -> bool {
    // SAFETY: contract; NULL or a NUL-terminated string of the driver.
    unsafe {
        let v = (f.get_string)(GL_VERSION);
        !v.is_null()
            && std::ffi::CStr::from_ptr(v.cast())
                .to_bytes()
                .starts_with(b"OpenGL ES")
    }
}

/// Where the eye's uniform of `program` is after `outcome`.
unsafe fn located(t: &Tables, program: u32, outcome: &LinkOutcome) -> Option<Rewritten> {
    match outcome {
        LinkOutcome::Shifted(s) => {
            // SAFETY: contract of the callers.
            let projecting = unsafe { projecting(t, program, &s.position) };
            match s.location {
                Some(l) => Some(Rewritten {
                    location: l as i32,
                    layer: s.layer,
                    projecting,
                }),
                // SAFETY: contract of the callers.
                None => unsafe { uniform_location(t, program) }.map(|location| Rewritten {
                    location,
                    layer: s.layer,
                    projecting,
                }),
            }
        }
        LinkOutcome::Kept(why) => {
            crate::report::warn(&format!(
                "a program is drawn unshifted in both eyes (automatic stereo): {why}"
            ));
            None
        }
        LinkOutcome::NotNeeded(_) => None,
    }
}

/// The locations of the uniforms among `names` (what gl_Position is
/// computed from) in the linked `program`: up to four, the rest −1.
/// More than four is not a camera: none then.
///
/// # Safety
/// `program`'s context is current.
unsafe fn projecting(t: &Tables, program: u32, names: &[String]) -> [i32; 4] {
    let mut out = [-1; 4];
    let mut n = 0;
    for name in names.iter().take(32) {
        let Ok(c) = std::ffi::CString::new(name.as_str()) else {
            continue;
        };
        // SAFETY: contract; a NUL-terminated name.
        let l = unsafe { (t.gl.get_uniform_location)(program, c.as_ptr()) };
        if l >= 0 {
            if n == out.len() {
                return [-1; 4];
            }
            out[n] = l;
            n += 1;
        }
    }
    out
}

unsafe fn uniform_location(t: &Tables, program: u32) -> Option<i32> {
    let name = std::ffi::CString::new(crate::auto::vertex::EYE_UNIFORM).expect("no NUL");
    // SAFETY: contract of the callers.
    let l = unsafe { (t.gl.get_uniform_location)(program, name.as_ptr()) };
    (l >= 0).then_some(l)
}

/// glCreateShaderProgramv in a context given automatic stereo: the source
/// a vertex-processing stage's separable program is made from (None: the
/// program's own), and, after the call, [`created`].
pub fn separable_source(kind: u32, strings: &[&str]) -> Option<String> {
    let t = tables()?;
    let location = reserved_location(&t.gl)?;
    // SAFETY: the program's context is current (the caller's call).
    let es = unsafe { context_is_es(&t.gl) };
    match link::shift_separable(kind, strings, LayerWrite::FromUniform, Some(location), es) {
        Ok(s) => s,
        Err(why) => {
            crate::report::warn(&format!(
                "a program is drawn unshifted in both eyes (automatic stereo): {}",
                why.0
            ));
            None
        }
    }
}

/// Records a program made by glCreateShaderProgramv (or loaded from a
/// binary): where its eye uniform is, if it has one.
///
/// # Safety
/// The program's context is current on this thread.
pub unsafe fn created(group: u64, program: u32) {
    let Some(t) = tables() else {
        return;
    };
    // SAFETY: contract.
    let at = unsafe { uniform_location(t, program) };
    // Its stage writes the layer where GLSL can: not in OpenGL ES.
    // SAFETY: contract.
    let layer = !unsafe { context_is_es(&t.gl) };
    record(
        group,
        program,
        at.map(|location| Rewritten {
            location,
            layer,
            projecting: [-1; 4],
        }),
    );
}

/// glStereoParameterfNV / glStereoParameteriNV (`Ok(f)` / `Err(i)` as
/// the program passed it) in a context given automatic stereo. Separation
/// and convergence are the live settings (the keys step from the
/// program's values, and stderr says the keys' changes); the cutoff and
/// projection method are the context's. On an error nothing changes: seed
/// 004's INVALID_ENUM for an unknown pname or projection method,
/// INVALID_VALUE for a separation outside 0…100 (and a value that is not
/// finite).
pub fn set_parameter(st: &mut AutoState, pname: u32, value: Result<f32, i32>) -> crate::Result<()> {
    let mut s = st.settings();
    match value {
        Ok(f) => s.parameter_f(pname, f)?,
        Err(i) => s.parameter_i(pname, i)?,
    }
    match pname {
        GL_STEREO_SEPARATION_NV => live::set_separation(s.separation()),
        GL_STEREO_CONVERGENCE_NV => live::set_convergence(Some(s.convergence())),
        _ => *st.nv_settings() = s,
    }
    Ok(())
}

/// GL_3DVISION_STEREO_NV and the STEREO_*_NV values of a context given
/// automatic stereo, for glGet* (None: not one of them).
pub fn query(st: &mut AutoState, pname: u32) -> Option<crate::shims::nv3dvision::StateValue> {
    let mut s = st.settings();
    if !live::auto_on() {
        s.set_enabled(false);
    }
    let _ = s.parameter_f(GL_STEREO_SEPARATION_NV, live::separation());
    s.query(pname)
}

//! Automatic stereo of unmodified mono programs: `glstereo-run --auto`
//! (issue 23), NVIDIA 3D Vision Automatic for Linux. The design, and the
//! parts of it that do not depend on how the preload library exports its
//! functions: the vertex-stage rewrite ([`vertex`], [`link`], [`glsl`]),
//! the fixed-function paths ([`fixed`], [`standin`]), the eyes as layers
//! ([`target`]) and
//! the list of entry points to intercept ([`entry_points`]). Each is tested
//! on llvmpipe against a program that draws each eye itself with the rule
//! applied by hand, pixel by pixel. [`runtime`] wires them to the preload
//! library's generated wrappers and says which parts of this design run
//! today; the rest below is design (shader stores of the second eye's
//! draws are not kept single, README, "Automatic stereo"; render targets
//! are [`render_targets`]).
//!
//! # The rule
//!
//! Every vertex that reaches the rasterizer is moved, for eye e (−1 left,
//! +1 right), as 3D Vision's driver moves it (REFERENCE.md, seed 004):
//!
//! ```text
//! x_clip' = x_clip + e·s·(w_clip − C)          unless w_clip == 1
//! ```
//!
//! s = 0.07 · S / 100 (S the separation in percent, the library's
//! [`MAX_SEPARATION`](crate::shims::nv3dvision::MAX_SEPARATION)), C the
//! convergence (the w at the screen). w_clip == 1 — orthographic HUDs,
//! text, full-screen passes — is left exactly where it was: the comparison
//! is exact in the shader ([`vertex`]) and, for fixed-function vertices,
//! a projection whose row 3 is (0, 0, 0, 1) is used as it is ([`fixed`]).
//! The state is [`StereoSettings`](crate::shims::nv3dvision::StereoSettings)
//! (separation, convergence, cutoff, projection method, enable): the
//! program's own glEnable(GL_3DVISION_STEREO_NV), glStereoParameter{f,i}NV
//! and glGet* of the STEREO_*_NV names reach it, with seed 004's errors.
//!
//! ## Defaults, and why
//!
//! - **Separation 15 %** (`GLSTEREO_SEPARATION`, `--separation`): NVIDIA's
//!   default depth amount, already the library's initial value. Far
//!   geometry is then 1.05 % of the viewport width apart, a third of HP's
//!   3 % comfort budget (seed 000; [`crate::analysis::parallax`]), which
//!   leaves the rest of the budget to what comes out of the screen.
//! - **Convergence `auto`** (`GLSTEREO_CONVERGENCE=auto|<w>`,
//!   `--convergence`): C is a distance in the program's own units, which
//!   differ by orders of magnitude between programs, so no number is a
//!   good default. Every 30 frames (the first at the first present) the
//!   layer puts C at the centre of interest of the left eye's depth layer
//!   (of the window's eyes, else of the stereoized render target the frame
//!   drew into last)
//!   ([`converge`]: the median distance in the middle half of the view's
//!   width and height, what `gls_stereo_auto_converge` computes for
//!   programs that ask, [`crate::analysis::centre_of_interest`]). Depth
//!   maps back to distance with the projection's near and far planes: the
//!   fixed-function projection of the measured frame's last perspective
//!   draw, or, for shader programs, the last perspective matrix (row 3 =
//!   (0, 0, −1, 0)) the program uploaded with glUniformMatrix4fv or
//!   glProgramUniformMatrix4fv. Until one is known, or when the program
//!   sets it (glStereoParameterfNV), C stays what it is; the first value
//!   is 0, NV_3dvision_settings' initial convergence: the whole picture
//!   behind the screen. Pop-out is not limited beyond the rule (the
//!   extension's cutoff stays the program's, 0 unless it sets one).
//! - The change is applied between frames, said once on stderr.
//!
//! # How a draw reaches both eyes: chosen by a uniform, no switch
//!
//! Measured (BENCHMARKS.md, "Automatic stereo: per-eye mechanisms";
//! `benches/auto_mechanisms.sh`): llvmpipe ends its scene (binning stops,
//! the rasterizer threads are woken and waited for) at every change of
//! framebuffer state — a glBindFramebuffer, a draw-buffer switch, a
//! re-attachment — for ≈ 12 µs, and a viewport + scissor change for
//! ≈ 22 µs. Switching the eye's target per draw therefore costs
//! 1.2–1.3x the program's own two passes at 10 draws a frame, 2–2.4x at
//! 100 and 6x at 1000. Not switching anything costs nothing: one target
//! holds both eyes, each draw is issued twice with a uniform
//! `gls_auto_eye` = (e·s, C, eye index, 0) changed between, and the
//! program's last vertex stage, rewritten at link time, writes the eye
//! index to where the target keeps that eye. Measured 0.96–1.09x of the
//! program's two passes from 1 to 1000 draws a frame (light scenes,
//! 400x300, quiet machine).
//!
//! The target as designed and tested here is **one layered framebuffer
//! object** — colour buffers and the depth/stencil buffer as 2-layer array
//! textures, layer 0 the left eye, layer 1 the right ([`target`]) — and
//! the index goes to gl_Layer (GL_ARB_shader_viewport_layer_array in
//! vertex and tessellation evaluation shaders, built in for geometry
//! shaders; llvmpipe 22.3 has it). Each eye has its own depth and stencil
//! (the depth array's layers), so draws interleaved eye by eye keep their
//! depth tests (one shared depth buffer, as quad-buffer stereo has, would
//! break them: variant c). One glClear clears both layers. glReadPixels,
//! glCopyTex*Image* and blits from a layered framebuffer read layer 0: the
//! left eye, as seed 004 resolves for ReadPixels, with no work. Nothing
//! of the program's viewport, scissor or gl_FragCoord changes.
//!
//! The alternative the rewrite also produces
//! ([`vertex::LayerWrite::ViewportIndex`]) is **one double-width target**
//! with a viewport per eye, the index written to gl_ViewportIndex
//! (variant e2; proved here too: a program's eyes in the two halves equal
//! each eye drawn by hand). It measured as d on light scenes, and better
//! where d is weak: a vertex shader that writes
//! gl_Layer makes one huge draw per eye 1.35–1.75x slower on llvmpipe
//! (heavy scene, one draw per eye, every run), where e2 stayed at
//! 0.92–0.99x. Its price is in the layer: every glViewport*, glScissor*,
//! glDepthRange* and the scissor enable of the program translated into
//! two indexed viewports and scissors (the scissor always on, so wide
//! points and lines stay in their eye), gl_FragCoord.x corrected in the
//! right eye (a fragment-shader macro, beside [`crate::stereo::outputs`]),
//! glClear under a scissor made per eye, and raster positions and blits
//! offset by the width. Which of the two: a run on a quiet machine
//! (`VARIANTS="a d dt e2 f2 a"`) decides; both keep the one uniform and
//! every other part of this design.
//!
//! Long scenes: llvmpipe bins a whole scene before rasterizing it, so a
//! heavy frame in one scene loses the overlap of binning with the
//! rasterizer threads that the program's own two passes get from their
//! eye switch. The layer flushes after a draw once 64K vertices are in the
//! scene (variant dt; never for light frames): at 100–1000 heavy draws a
//! frame that ran at 0.57–1.04x of the program's two passes.
//!
//! Rejected, with their measurements: a framebuffer object per eye (b),
//! draw-buffer or layer switching (c, c2), a viewport per eye set by
//! glViewport (e: the most expensive); one draw for both eyes by
//! instancing (f1: as cheap, but the program's own instancing,
//! gl_InstanceID and attribute divisors would need rewriting) or a
//! duplicating geometry shader (f2: as cheap, cheapest for one huge draw,
//! but Mesa refuses a geometry shader with GL_QUADS, GL_QUAD_STRIP and
//! GL_POLYGON — the primitives of legacy immediate mode — and with
//! fixed-function vertex processing: "Program lacks a vertex shader").
//!
//! # Each family of draws
//!
//! - **Shaders** (compatibility and core): the last vertex-processing
//!   stage — geometry, else tessellation evaluation, else vertex — is
//!   rewritten at glLinkProgram / glCreateShaderProgramv ([`link`],
//!   [`vertex`]): the rule after the user's `main` (early returns
//!   included) or before each EmitVertex / EmitStreamVertex(0), and
//!   gl_Layer from the uniform. The uniform has a reserved location, the
//!   last the driver offers (GL_MAX_UNIFORM_LOCATIONS − 1; every desktop
//!   GLSL version takes it, with GL_ARB_explicit_uniform_location and,
//!   before 3.30, GL_ARB_explicit_attrib_location enabled; ES 3.10 too),
//!   so one glUniform4f reaches whichever program is current, display
//!   lists included; ES 1.00 and 3.00 shaders get a plain uniform the
//!   layer looks up after the link. A uniform block was the alternative:
//!   it would take a binding point from the program. Per draw the layer calls
//!   glUniform4f twice on the current program (glProgramUniform4f on the
//!   pipeline's last-stage program for separate shader objects, whose
//!   other vertex-stage programs get the neutral value (0, C, −1, 0) so no
//!   position is shifted twice).
//! - **Fixed function**: a vertex shader of the layer stands in for
//!   fixed-function vertex processing ([`standin`]: `ftransform()` keeps
//!   positions invariant with fixed function; colours, texture coordinates
//!   through the texture matrices, fog coordinate, gl_ClipVertex, point
//!   size, one-sided lighting — each enabled light, positional or not,
//!   spot, attenuation, colour material, local viewer, separate specular,
//!   normalised or rescaled normals — generated from the fixed-function
//!   state the layer reads, as Mesa's own `ffvertex_prog` does), with the
//!   same rule and uniform, bound in place of program 0, the fragment
//!   stage left fixed-function; measured as d (variant dff: 1.00–1.06x at
//!   400x300 under load 8), and proved here pixel for pixel against fixed
//!   function drawn by hand for the state it models. glRasterPos* is made with program 0 meanwhile:
//!   with a vertex shader bound, Mesa 22.3 reports the raster position's
//!   clip w as 1/w (measured: 0.333 for w = 3), and the eyes' raster
//!   positions are computed from it. State the stand-in does not model
//!   (today two-sided lighting and texgen; vertex blending, NV programs…)
//!   takes the
//!   slow path of [`fixed`], proved here pixel for pixel too: the eye's
//!   projection loaded by the matrix form (row 0 + e·s·row 3 −
//!   e·s·C·(0, 0, 0, 1); orthographic projections as they are) and the
//!   eye's layers attached for the draw — two scene flushes per draw
//!   (variant c2ff: 1.3x at 10 draws, 2.4x at 100).
//! - **Immediate mode**: the draw happens at glEnd, and the vertices
//!   must reach the second eye too (a geometry shader cannot duplicate
//!   GL_QUADS on Mesa, see above). At glBegin the layer starts a display
//!   list of its own (glNewList(GL_COMPILE)), so the per-vertex calls go
//!   straight to GL and are compiled; at glEnd it ends the list and calls
//!   it once per eye with the eye's uniform (proved here pixel for pixel
//!   with the fixed-function stand-in). Only glBegin and glEnd need
//!   wrapping for that. While the program compiles a list of its own
//!   (lists do not nest), the per-vertex commands
//!   ([`entry_points::Family::Vertex`]) are recorded as they pass through
//!   and emitted again for the second eye after glEnd.
//! - **Display lists**: when the program compiles a list, each draw and
//!   glEnd is compiled twice, each preceded by glUniform4f at the reserved
//!   location (glUniform is compiled into lists; framebuffer calls are
//!   not, which is why the eye is a uniform). glCallList then needs
//!   nothing. ES 1.00 and 3.00 shaders, which cannot take the reserved
//!   location, get in lists the location of the program current when the
//!   list was compiled.
//! - **Client arrays, buffer objects, instanced, indirect, multi draws**:
//!   one family ([`entry_points::Family::Draw`]): each call is made twice.
//!   Indirect draws read their parameters twice, which is what they are
//!   for.
//! - **glClear**: once (both layers). glClearBuffer* likewise.
//! - **glDrawPixels, glBitmap, glCopyPixels**: per eye, at the eye's raster
//!   position ([`fixed`]: GL keeps the raster position's clip w, so the
//!   shift is computed at the draw and the position moved with a 0x0
//!   glBitmap, which keeps its colour and texture coordinates), into that
//!   eye's layers; glCopyPixels reads the same eye.
//! - **Blits into the default framebuffer**: a blit writes layer 0 only,
//!   so the layer blits once per eye (eye layers attached in turn): from a
//!   stereo render target eye to eye, from a mono one the same picture
//!   into both (flat, as on 3D Vision).
//!
//! # Render to texture
//!
//! What a program draws into its own framebuffer objects and then shows
//! (a textured quad, a blit, a chain of post-processing passes: Qt, VTK,
//! glmark2, most engines) must be in stereo too. 3D Vision decided by a
//! target's shape; here stereo flows with the data ([`render_targets`],
//! which states the policy and its mistakes): a target gets eyes when a
//! draw into it samples a texture with eyes, a blit into it comes from a
//! target with eyes, or a draw into it is moved per eye and it is not
//! seen from a light (depth only, or square and not the window's size).
//! The same policy holds in OpenGL ES 3.2 contexts, which have no direct
//! state access: there each step binds what it needs and binds back, and
//! a texture is named by the target the program defined it with (a
//! texture whose definition the layer did not see — an EGLImage — stays
//! mono). Its objects then have 2-layer twins drawn exactly as the window's eyes
//! are (uniform and gl_Layer, no switch); the program's own objects hold
//! the left eye, copied in before anything else reads them, and the
//! right eye's draws sample the right layer (a texture binding does not
//! end llvmpipe's scene).
//!
//! # Side effects stay single where GL allows
//!
//! - **Transform feedback**: when it is active (and not paused) at a draw,
//!   the layer draws once with the neutral eye and rasterizer discard (the
//!   capture is the mono one), pauses it, draws both eyes, and resumes it.
//!   With GL_RASTERIZER_DISCARD on, nothing reaches the eyes: one draw.
//! - **Queries** (built: `runtime::Counting`): GL_TIME_ELAPSED and
//!   GL_TIMESTAMP measure what really runs (both eyes).
//!   GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED(_CONSERVATIVE) and
//!   GL_PRIMITIVES_GENERATED must not count the right eye: the layer ends
//!   the query's current segment before a right-eye draw and begins a
//!   segment of its own after it (with transform feedback, the eyes'
//!   primitives are kept out of GL_PRIMITIVES_GENERATED too: the mono
//!   draw made them), answers glGetQueryObject* with the sum of the
//!   segments (any, for the boolean targets; available when all are), and
//!   begins conditional rendering on a segment whose own result says what
//!   the sum says (waiting for them). GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN
//!   counts only the mono draw already (the capture is paused for the
//!   eyes). Not covered: results written into a query buffer object.
//! - **Atomic counters, image and buffer stores**: a shader with them runs
//!   once per eye and stores twice. In the rewritten vertex stage,
//!   `atomicCounter*` and `image*` calls can be guarded by the eye (a
//!   macro per built-in, w of the uniform = 1 in the right eye); SSBO
//!   assignments and every fragment-stage store cannot be told apart, and
//!   happen per eye: not kept (3D Vision had the same limit).
//! - **Reads**: glReadPixels and glCopyTex*Image* read the left eye (layer
//!   0); glReadPixels of GL_DEPTH_COMPONENT reads the left eye's depth.
//! - glAccum: the accumulation buffer is one; accumulation is not
//!   stereoized (a program using it gets the left eye's accumulation in
//!   both eyes).
//!
//! # What cannot be covered, and how the layer says so
//!
//! Once per program, on stderr (`glstereo: …`): a program whose last
//! vertex stage has no GLSL source (SPIR-V through glShaderBinary /
//! glSpecializeShader; glProgramBinary of a binary the layer did not
//! produce — the uniform is missing after the load), ARB/NV assembly
//! vertex programs (glProgramStringARB), a shader that uses the layer's
//! names (`gls_auto_*`), or a rewrite that does not compile or link
//! ([`link::LinkOutcome::Kept`]). Those programs draw into both eyes
//! unshifted: their geometry sits at the screen, flat, and everything else
//! stays in stereo. Binaries the program gets from a rewritten program
//! (glGetProgramBinary) carry the rewrite and load with it. ES shaders
//! (`#version 100`, `300 es`) cannot write gl_Layer: they are shifted, and
//! their draws go to each eye by attaching its layers (the slow path). A
//! separable program whose earlier stage is used in a pipeline without its
//! later one is not shifted. Mesh shaders are not in GL 4.5.
//!
//! # Live controls
//!
//! As 3D Vision's: Ctrl+F3 / Ctrl+F4 separation down / up (×1/1.1, ×1.1
//! within 0…100 %), Ctrl+F5 / Ctrl+F6 convergence down / up (×1/1.1,
//! ×1.1; leaves `auto`), Ctrl+T stereo on/off (GL_3DVISION_STEREO_NV),
//! and Ctrl+F7 the next output format, Ctrl+F8 swap the eyes (these two
//! for quad-buffer programs too). The keys are taken out of the program's
//! event stream where the layer reads it (XNextEvent, XPeekEvent,
//! XWindowEvent, XMaskEvent, XCheck*Event, XIfEvent, and for xcb programs
//! such as Qt xcb_poll_for_event / xcb_wait_for_event): a room of its own
//! beside the GLX interposer. Each change is said once on stderr.
//!
//! # Entry points
//!
//! [`entry_points::family`] classifies every command of gl.xml; a wrapper
//! generator applies it. Counts over the 2978 desktop commands of the
//! registry the `khronos_api` crate ships (its test keeps them):
//!
//! | family | commands | what the wrapper does |
//! |---|---|---|
//! | Draw | 68 | the call once per eye (uniform, or projection + layers) |
//! | BeginEnd | 2 | glBegin starts the layer's list, glEnd calls it per eye |
//! | Vertex | 638 | recorded between glBegin and glEnd while the program compiles a list |
//! | DisplayList | 4 | compile draws per eye; glCallList as is |
//! | Clear | 9 | once (layered), per eye on the slow path |
//! | RasterPos | 30 | with program 0 while the fixed-function stand-in is bound |
//! | RasterPixels | 4 | per eye at the eye's raster position |
//! | Blit | 3 | per eye into the default framebuffer |
//! | Read | 29 | left eye (layer 0); a texture copied from eyes gets them (glCopyTex(Sub)Image2D) |
//! | Program | 20 | link-time rewrite; which program has the last stage |
//! | Introspection | 16 | the layer's uniform hidden from the program |
//! | Framebuffer | 34 | the eyes, a stereoized target, or mono |
//! | Texture | 10 | a texture with eyes sampled in the right eye is its right view |
//! | TextureData | 22 | a texture with eyes given its left eye first; mipmaps for both eyes |
//! | TextureWrite | 42 | a texture with eyes written outside draws is one picture again |
//! | SideEffect | 35 | queries segmented and summed, transform feedback paused |
//! | Settings | 18 | GL_3DVISION_STEREO_NV and the STEREO_*_NV pnames |
//! | Projection | 4 | glUniformMatrix4fv & co.: automatic convergence's projection |
//! | Lighting | 14 | glLight*, glLightModel*, glColorMaterial: the stand-in's lighting read again |
//!
//! 1002 in all (most are the per-vertex commands of immediate mode and
//! their extension forms); glStereoParameterfNV / glStereoParameteriNV are
//! an OpenGL ES extension, not in gl.xml's desktop set: two hand-typed
//! exports. Without `--auto` each wrapper is one thread-local test and the
//! call passed on, as the layer's interposed calls are today.

pub mod call;
pub mod converge;
pub mod entry_points;
pub mod eyes;
pub mod fixed;
pub mod from_depth;
pub mod glsl;
pub mod host;
pub mod link;
pub mod live;
pub mod render_targets;
pub mod runtime;
pub mod standin;
pub mod target;
pub mod vertex;

#[cfg(test)]
mod testgl;

/// Declares a table of GL entry points loaded by name through a
/// GetProcAddress, as [`crate::stereo::outputs::LinkFns`] is: a struct of
/// `pub(crate)` function pointers and an `unsafe fn load` that fails
/// (None) when one is missing.
macro_rules! gl_fns {
    ($(#[$meta:meta])* $vis:vis struct $name:ident {
        $( $field:ident = $sym:literal: fn($($ty:ty),*) $(-> $ret:ty)?; )*
    }) => {
        $(#[$meta])*
        #[allow(non_snake_case)]
        $vis struct $name {
            $( pub(crate) $field: unsafe extern "system" fn($($ty),*) $(-> $ret)?, )*
        }

        impl $name {
            /// Looks every function up through `get`; None when one is missing.
            ///
            /// # Safety
            /// `get` must return the named GL function (its Khronos
            /// signature) or NULL.
            #[allow(dead_code)]
            pub unsafe fn load(get: impl Fn(&std::ffi::CStr) -> *const std::ffi::c_void) -> Option<$name> {
                Some($name {
                    $( $field: {
                        let p = get($sym);
                        if p.is_null() {
                            return None;
                        }
                        // SAFETY: the named function, with its Khronos signature.
                        unsafe { std::mem::transmute::<*const std::ffi::c_void, unsafe extern "system" fn($($ty),*) $(-> $ret)?>(p) }
                    }, )*
                })
            }
        }
    };
}
pub(crate) use gl_fns;

//! The GL compositor: every composite output mode drawn by GL in a
//! surface's compositor context, reproducing [`super::cpu`] (the oracle)
//! within 1 unit per channel.
//!
//! # How it follows the CPU rules
//!
//! - **Sources.** The eyes are read straight from the emulated
//!   framebuffer's colour textures, each through its input framing's
//!   rectangle ([`TexRect`], GL rows: bottom first). An eye whose rectangle
//!   is not the eye's size (sync-doubled, STR_RECT, the narrower right half
//!   of an odd-width side-by-side frame) is first resampled into an RGBA8
//!   texture of the eye's size, exactly as [`crate::framing::InputFraming::extract`]
//!   rounds it to an 8-bit image on the CPU; every other eye is sampled in
//!   place, offset into its texture.
//! - **Sampling.** Output pixels sample at the documented coordinates
//!   `c = (i + 0.5)·src/dst − 0.5` (texel units, rows counted from the top),
//!   bilinear, clamped to the edge of the eye's rectangle. The shader
//!   evaluates GL_LINEAR's formula itself from four `texelFetch`es, taking
//!   each tap as the reference does (the weight is the fraction of an
//!   integer ratio, so it is the same f32), vertical then horizontal,
//!   instead of using the texture unit's filter: that one clamps at the
//!   texture's edge, not the rectangle's, and drivers interpolate unorm8
//!   texels with reduced-precision weights. Unscaled draws fetch one texel.
//! - **Numbers.** One f32 pass in 0…255 units, as the reference computes:
//!   each fetched texel is turned back into its exact integer, and the
//!   result is rounded half up in the shader and written as an exact unorm
//!   value, so ties round as on the CPU (that matters where an eye is
//!   resampled before `-dubois` amplifies a unit); the sRGB curves of
//!   `-dubois` are the exact piecewise ones; alpha is 1.
//! - **Pipeline.** Swap (exchanging the sources), saturation (`anaglyph-*`),
//!   crosstalk (both eyes sampled at the same coordinate, after filtering),
//!   then the mode; `frame-sequential` picks its eye with
//!   [`OutputOptions::frame_sequential_eye`].
//!
//! # Programs and state
//!
//! GLSL 1.30, so any GL 3.0 context works. Seven small programs (copy and
//! scale, each with or without crosstalk; interleave; channel-mask
//! anaglyphs; Dubois), each compiled on first use in the compositor
//! context, with uniform locations cached; a frame allocates nothing (the
//! capture framebuffer and the resampling targets are reallocated only when
//! a size changes). The compositor context belongs to the library: every
//! draw sets the state it depends on and restores nothing.
//!
//! GL objects are released with the compositor context (as the emulated
//! framebuffer's are).

use crate::error::{Error, Result};
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::image::{Image, flip_rows};
use crate::math::Eye;
use crate::profile::{self, Stage};
use crate::stereo::eye_memory::{EyePixels, Rows};

use super::anaglyph::{DuboisMatrices, LUMA, dubois_matrices};
use super::cpu::check_composite;
use super::layout::{leaves_gaps, placements, window_fit};
use super::mode::{AnaglyphMethod, OutputMode};
use super::options::OutputOptions;
use super::rows::MakeEyes;
use super::window::{Plan, WindowPaths, pixel_plan, window_path};

/// A rectangle of a texture holding one eye, in GL texel coordinates (rows
/// counted from the BOTTOM, as GL stores them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexRect {
    /// The texture (GL_TEXTURE_2D, RGBA8, level 0 only).
    pub texture: u32,
    /// Left column.
    pub x: u32,
    /// Bottom row.
    pub y: u32,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
}

impl TexRect {
    /// The rectangle of an input framing's [`crate::framing::EyeSource`]
    /// (rows counted from the top) in a texture of `buffer_height` rows.
    pub fn from_source(
        texture: u32,
        source: &crate::framing::EyeSource,
        buffer_height: u32,
    ) -> TexRect {
        TexRect {
            texture,
            x: source.x,
            y: buffer_height - source.y - source.height,
            width: source.width,
            height: source.height,
        }
    }
}

/// One composition: the mode, its options, and where the two eyes are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Job {
    /// The output mode (`quad` only for a natively stereo window).
    pub mode: OutputMode,
    /// Swap, crosstalk, saturation.
    pub options: OutputOptions,
    /// Which presented frame this is (`frame-sequential`: even = left eye).
    pub frame_index: u64,
    /// The left and right eyes as delivered (before any swap).
    pub eyes: [TexRect; 2],
    /// The size of each eye once taken apart (the composite is made from
    /// eyes of this size; rectangles of another size are resampled to it).
    pub eye_size: (u32, u32),
    /// Where the CPU reads eye textures in place (by texture; None where
    /// they are read back): see [`crate::stereo::eye_memory`].
    pub in_place: [Option<EyePixels>; 2],
}

impl Job {
    /// The rows of `rect` (of `w` × `h` texels) read in place, when its
    /// texture is one of [`Job::in_place`].
    ///
    /// # Safety
    /// The rendering into the texture has finished, and the rows are used
    /// before its framebuffer is resized or released.
    pub unsafe fn rows_in_place(&self, rect: &TexRect, w: u32, h: u32) -> Option<Rows<'_>> {
        let m = self
            .in_place
            .iter()
            .flatten()
            .find(|m| m.texture == rect.texture)?;
        // SAFETY: contract.
        unsafe { m.rect(rect.x, rect.y, w, h) }
    }

    /// The job for an emulated framebuffer's front buffers as they are
    /// now, taken apart by `framing` (the eyes as displayed).
    pub fn front_buffers(
        fb: &crate::stereo::emulated::EmulatedFramebuffer,
        framing: crate::framing::InputFraming,
        mode: OutputMode,
        options: OutputOptions,
        frame_index: u64,
    ) -> Job {
        let (w, h) = fb.size();
        let [ls, rs] = framing.sources(fb.shape(), w, h);
        Job {
            mode,
            options,
            frame_index,
            eyes: [ls, rs].map(|s| TexRect::from_source(fb.texture(s.buffer), &s, h)),
            eye_size: framing.eye_size(w, h),
            in_place: [ls, rs].map(|s| fb.pixels(s.buffer)),
        }
    }
}

/// How a composite reaches a window that shows pixels from memory (from
/// [`GlCompositor::pixel_plan`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelPlan(Plan);

/// [`GlCompositor::pixel_plan`] for a window of `size`, `software` saying
/// whether the renderer is (asked only for a good job).
fn cpu_plan(
    job: &Job,
    size: (u32, u32),
    software: impl FnOnce() -> bool,
) -> Result<Option<PixelPlan>> {
    let (w, h) = job.eye_size;
    if job.mode == OutputMode::Quad {
        return Ok(None);
    }
    let (_, composite) = check_composite(job.mode, &job.options, w, h)?;
    if cfg!(target_endian = "big") || !software() {
        return Ok(None);
    }
    let unscaled = job.eyes.iter().all(|e| (e.width, e.height) == (w, h));
    let plan = pixel_plan(unscaled);
    Ok((plan == Plan::Rows || composite == size).then_some(PixelPlan(plan)))
}

/// Which way a capture of the composite is made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ComposePath {
    /// Read the eyes back (one glReadPixels each) and compose with
    /// [`super::cpu::compose`].
    Cpu,
    /// Compose on GL into a framebuffer of the composite's size and read
    /// that back (one glReadPixels).
    Gl,
}

/// The faster way to capture the composite of `mode` with `options`, on a
/// renderer whose device is the CPU (`cpu_device`, [`composes_on_cpu`]:
/// llvmpipe, softpipe, swrast, zink over lavapipe — what EGL surfaceless,
/// OSMesa and Xvfb give on a machine without a GPU) or a hardware one.
///
/// On a software renderer, the CPU for every mode and option: its row
/// kernels compose any mode in 0.3–3 ms at 1280x1024 (`benches/compose.rs`),
/// from the eyes where llvmpipe drew them or read back (0.3–1 ms for both),
/// while the renderer's own shader pass takes 8–29 ms on llvmpipe
/// (`examples/compose_paths.rs`, Mesa 22.3.6, 2 shared cores; softpipe and
/// zink over lavapipe are slower still: BENCHMARKS.md). On a hardware
/// renderer, always GL (not measured here: a GPU composes in well under a
/// millisecond, and one image is read back instead of two). `mode` and
/// `options` no longer change the choice; they stay for callers that ask
/// per mode.
///
/// Both paths give the same image within 1 unit per channel.
pub fn preferred_path(cpu_device: bool, mode: OutputMode, options: &OutputOptions) -> ComposePath {
    let _ = (mode, options);
    if cpu_device {
        ComposePath::Cpu
    } else {
        ComposePath::Gl
    }
}

/// Whether a GL_RENDERER string names one of Mesa's software rasterizers
/// as the GL driver: llvmpipe, softpipe, swrast (their name comes first)
/// or the classic "Software Rasterizer". A GL driver over another API
/// names its device after its own name — zink over lavapipe is
/// "zink (llvmpipe (LLVM …))", virgl "virgl (…)" — and is not one: its
/// frames reach the window through its own swap (zink: Vulkan's), so it
/// gets the GL paths a hardware driver gets, wherever its device renders.
pub fn is_software_renderer(renderer: &str) -> bool {
    let r = renderer.trim_start().to_ascii_lowercase();
    ["llvmpipe", "softpipe", "swrast"]
        .iter()
        .any(|s| r.starts_with(s))
        || r.contains("software rasterizer")
}

/// Whether the device behind a GL_RENDERER string is the CPU: one of
/// Mesa's software rasterizers ([`is_software_renderer`]), or zink over
/// lavapipe ("zink (llvmpipe …)", "zink (Lavapipe …)"), whose Vulkan device
/// renders on this process's cores. There the CPU row kernels compose a
/// window's frame from the eyes read back (then one upload and a blit)
/// faster than the renderer runs the shader passes (BENCHMARKS.md, "Where
/// each format is composed"). virgl's device is the host's, not ours.
pub fn composes_on_cpu(renderer: &str) -> bool {
    let r = renderer.trim_start().to_ascii_lowercase();
    is_software_renderer(renderer)
        || (r.starts_with("zink") && (r.contains("(llvmpipe") || r.contains("(lavapipe")))
}

/// The shader programs; one per family of modes and variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kernel {
    /// One eye copied into a rectangle of its own size.
    Copy,
    /// As Copy, minus crosstalk·(the other eye).
    CopyCrosstalk,
    /// One eye scaled into a rectangle (bilinear).
    Scale,
    /// As Scale, minus crosstalk·(the other eye, scaled the same way).
    ScaleCrosstalk,
    /// `rows`, `columns`, `checkerboard`.
    Interleave,
    /// The channel-mask anaglyphs (full, half, mono) and `anaglyph-red-blue`.
    Mask,
    /// The `-dubois` anaglyphs.
    Dubois,
}

const KERNELS: usize = 7;

impl Kernel {
    fn index(self) -> usize {
        self as usize
    }

    fn place(scaled: bool, crosstalk: bool) -> Kernel {
        match (scaled, crosstalk) {
            (false, false) => Kernel::Copy,
            (false, true) => Kernel::CopyCrosstalk,
            (true, false) => Kernel::Scale,
            (true, true) => Kernel::ScaleCrosstalk,
        }
    }

    /// The preprocessor lines selecting this kernel in [`FRAGMENT`].
    fn defines(self) -> &'static str {
        match self {
            Kernel::Copy => "#define KERNEL 0\n#define SCALED 0\n#define CROSSTALK 0\n",
            Kernel::CopyCrosstalk => "#define KERNEL 0\n#define SCALED 0\n#define CROSSTALK 1\n",
            Kernel::Scale => "#define KERNEL 0\n#define SCALED 1\n#define CROSSTALK 0\n",
            Kernel::ScaleCrosstalk => "#define KERNEL 0\n#define SCALED 1\n#define CROSSTALK 1\n",
            Kernel::Interleave => "#define KERNEL 1\n#define SCALED 0\n#define CROSSTALK 1\n",
            Kernel::Mask => "#define KERNEL 2\n#define SCALED 0\n#define CROSSTALK 1\n",
            Kernel::Dubois => "#define KERNEL 3\n#define SCALED 0\n#define CROSSTALK 1\n",
        }
    }
}

/// A triangle that covers the viewport; no vertex attributes.
const VERTEX: &str = "#version 130
void main() {
    gl_Position = vec4(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0, 0.0, 1.0);
}
";

/// Every kernel's fragment shader, selected by KERNEL, SCALED, CROSSTALK
/// (see [`Kernel::defines`]); LUMA is prepended from [`LUMA`].
const FRAGMENT: &str = r#"
uniform sampler2D u_tex0;   // the eye drawn (place), or the left eye (others)
uniform sampler2D u_tex1;   // the other eye, or the right eye
uniform ivec4 u_rect0;      // each eye's rectangle in its texture: x, y (bottom), w, h
uniform ivec4 u_rect1;
uniform ivec4 u_dst;        // the viewport: x, y (bottom), w, h
uniform float u_crosstalk;
uniform float u_saturation;
uniform ivec2 u_parity;     // interleave: left where (x·px + row·py) is even
uniform vec3 u_left_mask;   // anaglyph: channels from the left eye (1) or the right (0)
uniform vec2 u_grey;        // anaglyph: left, right eye as luminance (1) or colour (0)
uniform vec3 u_keep;        // anaglyph: channels kept (red-blue has no green)
uniform mat3 u_dubois_l;
uniform mat3 u_dubois_r;

// Values are in 0…255 units, as in the CPU reference: a texel is its exact
// integer (the fetched k/255 rounded back), so the arithmetic, and the
// rounding of ties, follow the reference.
vec3 texel(sampler2D s, ivec2 p) { return floor(texelFetch(s, p, 0).rgb * 255.0 + 0.5); }

// round(v) with halves up, clamped to 0…255, as a unorm value GL stores exactly.
vec4 unorm(vec3 v) { return vec4(floor(clamp(v, 0.0, 255.0) + 0.5) / 255.0, 1.0); }

// One bilinear tap along an axis, exactly as the CPU reference takes it:
// output pixel i of m, over n texels, is centred at (i + 0.5)·n/m − 0.5 =
// num/den; texels i0, i1 clamped to the edge; weight f = the fraction,
// computed from integers so it is the same f32 the reference computes.
void tap(int i, int n, int m, out int i0, out int i1, out float f) {
    int num = (2 * i + 1) * n - m;
    int den = 2 * m;
    int base = num >= 0 ? num / den : -((den - 1 - num) / den);
    f = float(num - base * den) / float(den);
    i0 = clamp(base, 0, n - 1);
    i1 = clamp(base + 1, 0, n - 1);
}

// Where output pixel p (of the viewport) samples an eye of n texels: rows
// counted from the TOP as in the reference.
struct Taps { ivec2 i0; ivec2 i1; vec2 f; };

Taps taps(ivec2 p, ivec2 n) {
    Taps t;
    tap(p.x, n.x, u_dst.z, t.i0.x, t.i1.x, t.f.x);
    tap(u_dst.w - 1 - p.y, n.y, u_dst.w, t.i0.y, t.i1.y, t.f.y);
    return t;
}

// GL_LINEAR with clamp-to-edge inside the rectangle r: vertical, then
// horizontal, in the reference's order.
vec3 bilinear(sampler2D s, ivec4 r, Taps t) {
    int y0 = r.y + r.w - 1 - t.i0.y;
    int y1 = r.y + r.w - 1 - t.i1.y;
    vec3 t00 = texel(s, ivec2(r.x + t.i0.x, y0));
    vec3 t01 = texel(s, ivec2(r.x + t.i0.x, y1));
    vec3 t10 = texel(s, ivec2(r.x + t.i1.x, y0));
    vec3 t11 = texel(s, ivec2(r.x + t.i1.x, y1));
    vec3 a = t00 + t.f.y * (t01 - t00);
    vec3 b = t10 + t.f.y * (t11 - t10);
    return a + t.f.x * (b - a);
}

float luma(vec3 c) { return LUMA.r * c.r + LUMA.g * c.g + LUMA.b * c.b; }

// Saturation, then crosstalk, on both eyes at one coordinate.
void stage(inout vec3 l, inout vec3 r) {
    float yl = luma(l);
    float yr = luma(r);
    l = yl + u_saturation * (l - yl);
    r = yr + u_saturation * (r - yr);
    vec3 l2 = max(l - u_crosstalk * r, 0.0);
    r = max(r - u_crosstalk * l, 0.0);
    l = l2;
}

// The exact piecewise sRGB curves, on 0…1 values.
vec3 srgb_to_linear(vec3 c) {
    return mix(pow((c + 0.055) / 1.055, vec3(2.4)), c / 12.92, lessThanEqual(c, vec3(0.04045)));
}

vec3 linear_to_srgb(vec3 l) {
    return mix(1.055 * pow(l, vec3(1.0 / 2.4)) - 0.055, 12.92 * l,
               lessThanEqual(l, vec3(0.0031308)));
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) - u_dst.xy;
#if KERNEL == 0
#if SCALED
    Taps t = taps(p, u_rect0.zw);
    vec3 e = bilinear(u_tex0, u_rect0, t);
#if CROSSTALK
    e = max(e - u_crosstalk * bilinear(u_tex1, u_rect1, t), 0.0);
#endif
#else
    vec3 e = texel(u_tex0, u_rect0.xy + p);
#if CROSSTALK
    e = max(e - u_crosstalk * texel(u_tex1, u_rect1.xy + p), 0.0);
#endif
#endif
    gl_FragColor = unorm(e);
#else
    vec3 l = texel(u_tex0, u_rect0.xy + p);
    vec3 r = texel(u_tex1, u_rect1.xy + p);
#if KERNEL == 1
    vec3 l2 = max(l - u_crosstalk * r, 0.0);
    vec3 r2 = max(r - u_crosstalk * l, 0.0);
    int row = u_dst.w - 1 - p.y;
    bool left = ((p.x * u_parity.x + row * u_parity.y) & 1) == 0;
    gl_FragColor = unorm(left ? l2 : r2);
#elif KERNEL == 2
    stage(l, r);
    vec3 lv = u_grey.x > 0.5 ? vec3(luma(l)) : l;
    vec3 rv = u_grey.y > 0.5 ? vec3(luma(r)) : r;
    gl_FragColor = unorm(u_keep * mix(rv, lv, greaterThan(u_left_mask, vec3(0.5))));
#else
    stage(l, r);
    vec3 o = u_dubois_l * srgb_to_linear(l / 255.0) + u_dubois_r * srgb_to_linear(r / 255.0);
    gl_FragColor = unorm(linear_to_srgb(clamp(o, 0.0, 1.0)) * 255.0);
#endif
#endif
}
"#;

/// A linked program and its uniform locations (-1 where a kernel lacks one).
#[derive(Clone, Copy, Debug, Default)]
struct Program {
    id: u32,
    rect0: i32,
    rect1: i32,
    dst: i32,
    crosstalk: i32,
    saturation: i32,
    parity: i32,
    left_mask: i32,
    grey: i32,
    keep: i32,
    dubois_l: i32,
    dubois_r: i32,
}

/// A framebuffer with one RGBA8 texture, reallocated when its size changes.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Canvas {
    pub(crate) fbo: u32,
    pub(crate) texture: u32,
    pub(crate) width: u32,
    pub(crate) height: u32,
}

impl Canvas {
    /// Makes the canvas `width` × `height` (contents undefined after a change).
    pub(crate) unsafe fn ensure(&mut self, gl: &Gl, width: u32, height: u32) -> Result<()> {
        if self.fbo != 0 && (self.width, self.height) == (width, height) {
            return Ok(());
        }
        // SAFETY: the compositor context is current (contract of the callers).
        unsafe {
            if self.fbo == 0 {
                self.fbo = gl.gen_framebuffer();
                self.texture = gl.gen_texture();
            }
            gl.BindTexture(GL_TEXTURE_2D, self.texture);
            for (pname, v) in [
                (GL_TEXTURE_MIN_FILTER, GL_NEAREST),
                (GL_TEXTURE_MAG_FILTER, GL_NEAREST),
                (GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE),
                (GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE),
            ] {
                gl.TexParameteri(GL_TEXTURE_2D, pname, v as i32);
            }
            gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
            gl.TexImage2D(
                GL_TEXTURE_2D,
                0,
                GL_RGBA8 as i32,
                width as i32,
                height as i32,
                0,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                std::ptr::null(),
            );
            gl.BindTexture(GL_TEXTURE_2D, 0);
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, self.fbo);
            gl.FramebufferTexture2D(
                GL_DRAW_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0,
                GL_TEXTURE_2D,
                self.texture,
                0,
            );
            gl.check("allocating a composition buffer")?;
            let status = gl.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
            if status != GL_FRAMEBUFFER_COMPLETE {
                return Err(Error::Gl(format!(
                    "the {width}x{height} composition framebuffer is incomplete (status {status:#06x})"
                )));
            }
        }
        (self.width, self.height) = (width, height);
        Ok(())
    }
}

/// The per-draw values of the mode (uniforms a kernel may use).
#[derive(Clone, Copy, Debug)]
struct Style {
    crosstalk: f32,
    saturation: f32,
    parity: [i32; 2],
    left_mask: [f32; 3],
    grey: [f32; 2],
    keep: [f32; 3],
    dubois: Option<DuboisMatrices>,
}

/// Where a draw goes: a viewport of the bound draw framebuffer (GL
/// coordinates, bottom row first).
#[derive(Clone, Copy, Debug)]
struct Viewport {
    x: i32,
    y: i32,
    width: u32,
    height: u32,
}

/// The GL compositor of one surface. Create it with [`GlCompositor::new`]
/// (no GL calls); its GL objects are made in the compositor context on
/// first use.
#[derive(Debug, Default)]
pub struct GlCompositor {
    programs: [Program; KERNELS],
    vao: u32,
    /// The composite of captures (and of windows whose size differs).
    capture: Canvas,
    /// Eyes resampled from framing rectangles of another size.
    resampled: [Canvas; 2],
    /// The largest side a composite may have here (0: not queried yet).
    limit: u32,
    /// Whether the renderer is a software rasterizer (None: not queried yet).
    software: Option<bool>,
    /// Whether its device is the CPU ([`composes_on_cpu`]; None: not
    /// queried yet).
    cpu_device: Option<bool>,
    /// The blit and CPU ways into a window ([`super::window`]).
    window: WindowPaths,
}

impl GlCompositor {
    /// A compositor with no GL objects yet.
    pub fn new() -> GlCompositor {
        GlCompositor::default()
    }

    /// The largest width or height this context can compose into (the
    /// smaller of GL_MAX_TEXTURE_SIZE and GL_MAX_VIEWPORT_DIMS).
    ///
    /// # Safety
    /// The compositor context must be current.
    pub unsafe fn max_side(&mut self, gl: &Gl) -> u32 {
        if self.limit == 0 {
            let mut dims = [0i32; 2];
            // SAFETY: contract; GL_MAX_VIEWPORT_DIMS writes two values.
            let tex = unsafe {
                gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, dims.as_mut_ptr());
                gl.integer(GL_MAX_TEXTURE_SIZE)
            };
            self.limit = tex.min(dims[0]).min(dims[1]).max(0) as u32;
        }
        self.limit
    }

    /// Whether this context renders in software ([`is_software_renderer`]).
    ///
    /// # Safety
    /// The compositor context must be current.
    pub unsafe fn software(&mut self, gl: &Gl) -> bool {
        // SAFETY: contract.
        *self
            .software
            .get_or_insert_with(|| is_software_renderer(&unsafe { gl.string(GL_RENDERER) }))
    }

    /// Whether this context's device is the CPU ([`composes_on_cpu`]).
    ///
    /// # Safety
    /// The compositor context must be current.
    pub unsafe fn cpu_device(&mut self, gl: &Gl) -> bool {
        // SAFETY: contract.
        *self
            .cpu_device
            .get_or_insert_with(|| composes_on_cpu(&unsafe { gl.string(GL_RENDERER) }))
    }

    /// Composes `job` into the compositor's capture framebuffer and returns
    /// the composite's size; read it with [`GlCompositor::read_capture`].
    ///
    /// # Errors
    /// As [`super::cpu::compose`] (`quad` is not a composite; options out of
    /// range; a composite over [`crate::image::MAX_DIMENSION`]); also
    /// [`Error::InvalidValue`] for a composite larger than this context can
    /// render ([`GlCompositor::max_side`]), and [`Error::Gl`] /
    /// [`Error::OutOfMemory`] from the driver.
    ///
    /// # Safety
    /// The compositor context of the surface owning the job's textures must
    /// be current, and the textures must be RGBA8 with the rectangles inside.
    pub unsafe fn compose_capture(&mut self, gl: &Gl, job: &Job) -> Result<(u32, u32)> {
        let (w, h) = job.eye_size;
        let (options, (cw, ch)) = check_composite(job.mode, &job.options, w, h)?;
        // SAFETY: contract.
        unsafe {
            self.check_fits(gl, job.mode, cw, ch)?;
            gl.take_error();
            let eyes = self.prepare(gl, job)?;
            self.capture.ensure(gl, cw, ch)?;
            self.draw_mode(
                gl,
                self.capture.fbo,
                GL_COLOR_ATTACHMENT0,
                job,
                &options,
                eyes,
            )?;
            gl.check("composing the eyes")?;
        }
        Ok((cw, ch))
    }

    /// Reads the last capture into `out` (rows top first), which must have
    /// the size [`GlCompositor::compose_capture`] returned.
    ///
    /// # Safety
    /// The compositor context must be current.
    pub unsafe fn read_capture(&self, gl: &Gl, out: &mut Image) -> Result<()> {
        let (w, h) = (self.capture.width, self.capture.height);
        if self.capture.fbo == 0 || (out.width(), out.height()) != (w, h) {
            return Err(Error::invalid_operation(format!(
                "read_capture into a {}x{} image: the last capture is {w}x{h}",
                out.width(),
                out.height()
            )));
        }
        // SAFETY: contract; `out` holds w×h×4 bytes (checked).
        unsafe {
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, self.capture.fbo);
            gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
            gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
            gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
            gl.ReadPixels(
                0,
                0,
                w as i32,
                h as i32,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                out.pixels_mut().as_mut_ptr().cast(),
            );
            gl.check("reading the composite")?;
        }
        flip_rows(out.pixels_mut(), w as usize * 4);
        Ok(())
    }

    /// Composes `job` into a window: `framebuffer` (0 for the drawable of
    /// the current context; another name for a framebuffer object standing
    /// in for one) of `width` × `height` pixels. The composite is placed by
    /// [`super::layout::window_fit`]: pixel for pixel when the sizes match,
    /// else letterboxed on black (interleaved modes cropped, never scaled).
    ///
    /// Framebuffer 0 is drawn in its back buffer when it is double-buffered,
    /// else its front; `quad` (natively stereo drawables only) draws the
    /// left eye into the left back buffer and the right eye into the right
    /// one. A framebuffer object gets colour attachment 0 (and 1 for the
    /// right eye of `quad`).
    ///
    /// # Safety
    /// As [`GlCompositor::compose_capture`]; `framebuffer` must be complete
    /// and at least `width` × `height`.
    pub unsafe fn compose_window(
        &mut self,
        gl: &Gl,
        job: &Job,
        framebuffer: u32,
        width: u32,
        height: u32,
    ) -> Result<()> {
        crate::fault::inject(crate::fault::Site::Compose);
        let (w, h) = job.eye_size;
        // SAFETY: contract.
        let double = framebuffer == 0
            && unsafe {
                gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
                gl.integer(GL_DOUBLEBUFFER) != 0
            };
        let (buf, left_buf, right_buf) = match (framebuffer, double) {
            (0, true) => (GL_BACK, GL_BACK_LEFT, GL_BACK_RIGHT),
            (0, false) => (GL_FRONT, GL_FRONT_LEFT, GL_FRONT_RIGHT),
            _ => (
                GL_COLOR_ATTACHMENT0,
                GL_COLOR_ATTACHMENT0,
                GL_COLOR_ATTACHMENT0 + 1,
            ),
        };
        // The blit and CPU paths, when the composite fills the window.
        if job.mode != OutputMode::Quad && job.eyes.iter().all(|e| (e.width, e.height) == (w, h)) {
            let (options, (cw, ch)) = check_composite(job.mode, &job.options, w, h)?;
            if (cw, ch) == (width, height) {
                // SAFETY: contract.
                let path = unsafe {
                    let cpu = self.cpu_device(gl);
                    let alpha = WindowPaths::has_alpha(gl, framebuffer, buf);
                    window_path(job.mode, &options, cpu, alpha)
                };
                if let Some(path) = path {
                    // SAFETY: contract.
                    return unsafe {
                        gl.take_error();
                        self.window
                            .compose(gl, path, job, &options, framebuffer, buf)?;
                        gl.check("composing the eyes into the window")
                    };
                }
            }
        }
        let single = [(job.mode, buf)];
        let quad = [(OutputMode::Left, left_buf), (OutputMode::Right, right_buf)];
        let passes: &[(OutputMode, u32)] = if job.mode == OutputMode::Quad {
            &quad
        } else {
            &single
        };
        // SAFETY: contract.
        unsafe {
            gl.take_error();
            let mut eyes = None;
            for &(mode, buffer) in passes {
                let pass = Job { mode, ..*job };
                let (options, (cw, ch)) = check_composite(mode, &job.options, w, h)?;
                self.check_fits(gl, mode, cw, ch)?;
                let prepared = match eyes {
                    Some(e) => e,
                    None => *eyes.insert(self.prepare(gl, job)?),
                };
                let fit = window_fit(mode, cw, ch, width, height);
                if fit.is_exact(width, height) {
                    self.draw_mode(gl, framebuffer, buffer, &pass, &options, prepared)?;
                    continue;
                }
                self.capture.ensure(gl, cw, ch)?;
                let capture = self.capture.fbo;
                self.draw_mode(gl, capture, GL_COLOR_ATTACHMENT0, &pass, &options, prepared)?;
                gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
                gl.DrawBuffer(buffer);
                gl.ClearColor(0.0, 0.0, 0.0, 1.0);
                gl.Clear(GL_COLOR_BUFFER_BIT);
                gl.BindFramebuffer(GL_READ_FRAMEBUFFER, capture);
                gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
                let y = height as i32 - fit.y - fit.height as i32;
                let filter = if (fit.width, fit.height) == (cw, ch) {
                    GL_NEAREST
                } else {
                    GL_LINEAR
                };
                gl.BlitFramebuffer(
                    0,
                    0,
                    cw as i32,
                    ch as i32,
                    fit.x,
                    y,
                    fit.x + fit.width as i32,
                    y + fit.height as i32,
                    GL_COLOR_BUFFER_BIT,
                    filter,
                );
            }
            gl.check("composing the eyes into the window")
        }
    }

    /// The composite of `job` into `out` (rows top first, resized when
    /// needed, its buffer reused otherwise), made the faster way here
    /// ([`preferred_path`]): on the CPU from the eyes read back into reused
    /// buffers, or by GL and one read-back. Ok(false), with `out`
    /// untouched, when GL would be needed but the composite exceeds what
    /// this driver renders (the caller composes on the CPU then).
    ///
    /// # Errors
    /// As [`GlCompositor::compose_capture`].
    ///
    /// # Safety
    /// As [`GlCompositor::compose_capture`].
    pub unsafe fn capture_into(&mut self, gl: &Gl, job: &Job, out: &mut Image) -> Result<bool> {
        let (w, h) = job.eye_size;
        let (options, (cw, ch)) = check_composite(job.mode, &job.options, w, h)?;
        let unscaled = job.eyes.iter().all(|e| (e.width, e.height) == (w, h));
        // SAFETY: contract.
        unsafe {
            let cpu = self.cpu_device(gl);
            gl.take_error();
            if unscaled && preferred_path(cpu, job.mode, &options) == ComposePath::Cpu {
                self.window.cpu_image(gl, job, &options, out)?;
                gl.check("reading the eyes back")?;
                return Ok(true);
            }
            if cw > self.max_side(gl) || ch > self.max_side(gl) {
                return Ok(false);
            }
            self.compose_capture(gl, job)?;
            out.resize(cw, ch, "composite")?;
            self.read_capture(gl, out)?;
        }
        Ok(true)
    }

    /// How `job` can reach a window of `width` × `height` that shows pixels
    /// from memory ([`crate::backend::PlatformSurface::present_pixels`]) on
    /// a software renderer: composed on the CPU at the window's size (any
    /// mode, any options, fitted as [`super::layout::window_fit`] says), or,
    /// for eyes in framing rectangles of another size, by GL when the
    /// composite is the window's size. None on a hardware renderer (its GL
    /// composite into the window is cheaper), for `quad`, and otherwise.
    /// See `output/window.rs`.
    ///
    /// # Errors
    /// As [`GlCompositor::compose_capture`] for a bad job.
    ///
    /// # Safety
    /// The compositor context must be current.
    pub unsafe fn pixel_plan(
        &mut self,
        gl: &Gl,
        job: &Job,
        width: u32,
        height: u32,
    ) -> Result<Option<PixelPlan>> {
        // SAFETY: contract.
        cpu_plan(job, (width, height), || unsafe { self.software(gl) })
    }

    /// [`GlCompositor::pixel_plan`] for a frame composed on the CPU from
    /// eyes that are all in place ([`Job::in_place`]) at any window size,
    /// decided without a GL call (the renderer is known to be software from
    /// an earlier frame): then [`GlCompositor::fill_in_place`] writes it
    /// with any context current. None otherwise, or for a bad job (the GL
    /// path reports it).
    ///
    /// # Safety
    /// The rendering into the job's eyes has finished.
    pub unsafe fn in_place_plan(&self, job: &Job) -> Option<PixelPlan> {
        let (w, h) = job.eye_size;
        // Rows fit any window size: the size given is not looked at.
        let plan = cpu_plan(job, (0, 0), || self.software == Some(true)).ok()??;
        // SAFETY: contract.
        let placed = job
            .eyes
            .iter()
            .all(|e| unsafe { job.rows_in_place(e, w, h) }.is_some());
        (plan.0 == Plan::Rows && placed).then_some(plan)
    }

    /// Writes the composite of `job` into `target` as [`GlCompositor::fill_pixels`]
    /// does, for a plan of [`GlCompositor::in_place_plan`], without a GL call.
    /// `made`: the job's eyes are made as they are read (the composite
    /// makes them, [`MakeEyes`]).
    ///
    /// # Errors
    /// A bad job; an eye no longer in place (nothing is written then).
    ///
    /// # Safety
    /// As [`GlCompositor::in_place_plan`]; the eyes stay allocated until
    /// this returns.
    pub unsafe fn fill_in_place(
        &mut self,
        job: &Job,
        plan: PixelPlan,
        mut target: crate::backend::PixelTarget<'_>,
        made: Option<&dyn MakeEyes>,
    ) -> Result<()> {
        crate::fault::inject(crate::fault::Site::Compose);
        debug_assert_eq!(plan.0, Plan::Rows);
        let options = job.options.validated()?;
        // SAFETY: contract.
        if unsafe {
            self.window
                .fill_in_place(job, &options, &mut target, made)?
        } {
            Ok(())
        } else {
            Err(Error::Gl(
                "an eye is no longer in memory the CPU can read".into(),
            ))
        }
    }

    /// Writes the composite of `job` into `target` (fitted to its size) as
    /// `plan` says, with buffers reused from frame to frame; `made` as for
    /// [`GlCompositor::fill_in_place`].
    ///
    /// # Errors
    /// As [`GlCompositor::compose_capture`].
    ///
    /// # Safety
    /// As [`GlCompositor::compose_capture`]; `plan` came from
    /// [`GlCompositor::pixel_plan`] for this job and the target's size.
    pub unsafe fn fill_pixels(
        &mut self,
        gl: &Gl,
        job: &Job,
        plan: PixelPlan,
        mut target: crate::backend::PixelTarget<'_>,
        made: Option<&dyn MakeEyes>,
    ) -> Result<()> {
        crate::fault::inject(crate::fault::Site::Compose);
        let options = job.options.validated()?;
        // SAFETY: contract.
        unsafe {
            gl.take_error();
            match plan.0 {
                Plan::Gl => {
                    if let Some(m) = made {
                        m.in_place();
                    }
                    profile::span(Stage::GlCompose, || self.compose_capture(gl, job))?;
                    let canvas = self.capture;
                    let img =
                        profile::span(Stage::ReadBack, || self.window.read_canvas(gl, &canvas))?;
                    profile::span(Stage::Compose, || target.write_image(img, true));
                }
                Plan::Rows => self
                    .window
                    .fill(gl, plan.0, job, &options, &mut target, made)?,
            }
            gl.check("composing the eyes for the window")
        }
    }

    unsafe fn check_fits(&mut self, gl: &Gl, mode: OutputMode, cw: u32, ch: u32) -> Result<()> {
        // SAFETY: contract of the callers.
        let limit = unsafe { self.max_side(gl) };
        if cw > limit || ch > limit {
            return Err(Error::invalid_value(format!(
                "{mode} makes a {cw}x{ch} frame, larger than this GL driver renders \
                 ({limit} pixels a side): use smaller eyes or a same-size mode"
            )));
        }
        Ok(())
    }

    /// The eyes as rectangles of the eye's size: sampled in place, or
    /// resampled into the compositor's own textures first.
    unsafe fn prepare(&mut self, gl: &Gl, job: &Job) -> Result<[TexRect; 2]> {
        let (w, h) = job.eye_size;
        let mut out = job.eyes;
        for i in 0..2 {
            let src = job.eyes[i];
            if (src.width, src.height) == (w, h) {
                continue;
            }
            if i == 1 && src == job.eyes[0] {
                out[1] = out[0];
                continue;
            }
            // SAFETY: contract of the callers.
            unsafe {
                self.resampled[i].ensure(gl, w, h)?;
                let canvas = self.resampled[i];
                gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, canvas.fbo);
                gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
                let vp = Viewport {
                    x: 0,
                    y: 0,
                    width: w,
                    height: h,
                };
                self.draw(gl, Kernel::Scale, src, src, vp, &plain_style(0.0, 1.0))?;
                out[i] = TexRect {
                    texture: canvas.texture,
                    x: 0,
                    y: 0,
                    width: w,
                    height: h,
                };
            }
        }
        Ok(out)
    }

    /// Draws the composite of `job.mode` with its bottom-left corner at
    /// (0, 0) of `framebuffer`'s `buffer`. `options` are validated; `eyes`
    /// are prepared (each of the eye's size).
    unsafe fn draw_mode(
        &mut self,
        gl: &Gl,
        framebuffer: u32,
        buffer: u32,
        job: &Job,
        options: &OutputOptions,
        eyes: [TexRect; 2],
    ) -> Result<()> {
        let mode = job.mode;
        let (w, h) = job.eye_size;
        let (_, ch) = super::layout::composite_size(mode, w, h);
        let [left, right] = eyes;
        let (l, r) = if options.swap_eyes {
            (right, left)
        } else {
            (left, right)
        };
        let k = if mode.shows_both_eyes() {
            options.crosstalk
        } else {
            0.0
        };
        let s = if mode.is_anaglyph() {
            options.saturation
        } else {
            1.0
        };
        let mut style = plain_style(k, s);
        let full = Viewport {
            x: 0,
            y: 0,
            width: w,
            height: h,
        };
        // SAFETY: contract of the callers.
        unsafe {
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
            gl.DrawBuffer(buffer);
            match mode {
                OutputMode::Quad => Err(Error::invalid_operation(
                    "quad is drawn per buffer, not as one composite",
                )),
                OutputMode::Left => self.draw(gl, Kernel::Copy, l, r, full, &style),
                OutputMode::Right => self.draw(gl, Kernel::Copy, r, l, full, &style),
                OutputMode::FrameSequential => {
                    // The eye accounts for the swap: pick from the unswapped inputs.
                    let (shown, other) = match options.frame_sequential_eye(job.frame_index) {
                        Eye::Left => (left, right),
                        Eye::Right => (right, left),
                    };
                    let kernel = Kernel::place(false, k != 0.0);
                    self.draw(gl, kernel, shown, other, full, &style)
                }
                OutputMode::Anaglyph(colors, AnaglyphMethod::Dubois) => {
                    style.dubois = Some(dubois_matrices(colors));
                    self.draw(gl, Kernel::Dubois, l, r, full, &style)
                }
                OutputMode::Anaglyph(colors, method) => {
                    style.left_mask = colors.left_channels().map(|b| f32::from(u8::from(b)));
                    style.grey = [
                        f32::from(u8::from(method != AnaglyphMethod::FullColor)),
                        f32::from(u8::from(method == AnaglyphMethod::Monochrome)),
                    ];
                    self.draw(gl, Kernel::Mask, l, r, full, &style)
                }
                OutputMode::AnaglyphRedBlue => {
                    style.left_mask = [1.0, 0.0, 0.0];
                    style.grey = [1.0, 1.0];
                    style.keep = [1.0, 0.0, 1.0];
                    self.draw(gl, Kernel::Mask, l, r, full, &style)
                }
                OutputMode::Rows | OutputMode::Columns | OutputMode::Checkerboard => {
                    style.parity = match mode {
                        OutputMode::Rows => [0, 1],
                        OutputMode::Columns => [1, 0],
                        _ => [1, 1],
                    };
                    self.draw(gl, Kernel::Interleave, l, r, full, &style)
                }
                OutputMode::SideBySide
                | OutputMode::TopBottom
                | OutputMode::SideBySideHalf
                | OutputMode::TopBottomHalf
                | OutputMode::HdmiFramePacking
                | OutputMode::Starbase
                | OutputMode::StrRect => {
                    let places = placements(mode, w, h).expect("a rectangle mode");
                    if leaves_gaps(mode, w, h) {
                        gl.ClearColor(0.0, 0.0, 0.0, 1.0);
                        gl.Clear(GL_COLOR_BUFFER_BIT);
                    }
                    for p in places {
                        if p.width == 0 || p.height == 0 {
                            continue;
                        }
                        let (eye, other) = match p.eye {
                            Eye::Left => (l, r),
                            Eye::Right => (r, l),
                        };
                        let scaled = (p.width, p.height) != (w, h);
                        let vp = Viewport {
                            x: p.x as i32,
                            y: (ch - p.y - p.height) as i32,
                            width: p.width,
                            height: p.height,
                        };
                        self.draw(gl, Kernel::place(scaled, k != 0.0), eye, other, vp, &style)?;
                    }
                    Ok(())
                }
            }
        }
    }

    /// One full-viewport draw of `kernel` into the bound draw framebuffer.
    unsafe fn draw(
        &mut self,
        gl: &Gl,
        kernel: Kernel,
        eye: TexRect,
        other: TexRect,
        vp: Viewport,
        style: &Style,
    ) -> Result<()> {
        // SAFETY: contract of the callers (compositor context current).
        unsafe {
            let p = self.program(gl, kernel)?;
            for cap in [
                GL_BLEND,
                GL_DEPTH_TEST,
                GL_STENCIL_TEST,
                GL_SCISSOR_TEST,
                GL_CULL_FACE,
                GL_DITHER,
                GL_FRAMEBUFFER_SRGB,
                GL_COLOR_LOGIC_OP,
                GL_RASTERIZER_DISCARD,
            ] {
                gl.Disable(cap);
            }
            gl.ColorMask(1, 1, 1, 1);
            gl.UseProgram(p.id);
            gl.BindVertexArray(self.vao);
            gl.ActiveTexture(GL_TEXTURE0 + 1);
            gl.BindTexture(GL_TEXTURE_2D, other.texture);
            gl.ActiveTexture(GL_TEXTURE0);
            gl.BindTexture(GL_TEXTURE_2D, eye.texture);
            gl.Viewport(vp.x, vp.y, vp.width as i32, vp.height as i32);
            let rect = |r: TexRect| (r.x as i32, r.y as i32, r.width as i32, r.height as i32);
            let (a, b, c, d) = rect(eye);
            gl.Uniform4i(p.rect0, a, b, c, d);
            let (a, b, c, d) = rect(other);
            gl.Uniform4i(p.rect1, a, b, c, d);
            gl.Uniform4i(p.dst, vp.x, vp.y, vp.width as i32, vp.height as i32);
            gl.Uniform1f(p.crosstalk, style.crosstalk);
            gl.Uniform1f(p.saturation, style.saturation);
            gl.Uniform2i(p.parity, style.parity[0], style.parity[1]);
            let [r, g, b] = style.left_mask;
            gl.Uniform3f(p.left_mask, r, g, b);
            gl.Uniform2f(p.grey, style.grey[0], style.grey[1]);
            let [r, g, b] = style.keep;
            gl.Uniform3f(p.keep, r, g, b);
            if let Some(m) = &style.dubois {
                // Rows are the output channels: upload row-major (transpose).
                gl.UniformMatrix3fv(p.dubois_l, 1, GL_TRUE, m.left.as_ptr().cast());
                gl.UniformMatrix3fv(p.dubois_r, 1, GL_TRUE, m.right.as_ptr().cast());
            }
            gl.DrawArrays(GL_TRIANGLES, 0, 3);
        }
        Ok(())
    }

    /// The program of `kernel`, compiled and linked on first use.
    unsafe fn program(&mut self, gl: &Gl, kernel: Kernel) -> Result<Program> {
        let slot = &mut self.programs[kernel.index()];
        if slot.id != 0 {
            return Ok(*slot);
        }
        // SAFETY: contract of the callers (compositor context current).
        unsafe {
            if self.vao == 0 {
                gl.GenVertexArrays(1, &mut self.vao);
            }
            let header = format!(
                "#version 130\n{}const vec3 LUMA = vec3({:?}, {:?}, {:?});\n",
                kernel.defines(),
                LUMA[0],
                LUMA[1],
                LUMA[2]
            );
            let id = link(gl, &[VERTEX], &[&header, FRAGMENT])
                .map_err(|e| Error::Gl(format!("the {kernel:?} composition shader: {e}")))?;
            let loc = |name: &std::ffi::CStr| gl.GetUniformLocation(id, name.as_ptr());
            let p = Program {
                id,
                rect0: loc(c"u_rect0"),
                rect1: loc(c"u_rect1"),
                dst: loc(c"u_dst"),
                crosstalk: loc(c"u_crosstalk"),
                saturation: loc(c"u_saturation"),
                parity: loc(c"u_parity"),
                left_mask: loc(c"u_left_mask"),
                grey: loc(c"u_grey"),
                keep: loc(c"u_keep"),
                dubois_l: loc(c"u_dubois_l"),
                dubois_r: loc(c"u_dubois_r"),
            };
            gl.UseProgram(id);
            gl.Uniform1i(loc(c"u_tex0"), 0);
            gl.Uniform1i(loc(c"u_tex1"), 1);
            *slot = p;
            Ok(p)
        }
    }
}

fn plain_style(crosstalk: f32, saturation: f32) -> Style {
    Style {
        crosstalk,
        saturation,
        parity: [0, 0],
        left_mask: [0.0; 3],
        grey: [0.0; 2],
        keep: [1.0; 3],
        dubois: None,
    }
}

/// Compiles one shader from `sources` (concatenated).
unsafe fn compile(gl: &Gl, kind: u32, sources: &[&str]) -> std::result::Result<u32, String> {
    let ptrs: Vec<*const std::ffi::c_char> = sources.iter().map(|s| s.as_ptr().cast()).collect();
    let lens: Vec<i32> = sources.iter().map(|s| s.len() as i32).collect();
    // SAFETY: a context is current (contract); the pointers and lengths
    // describe live strings for the duration of the call.
    unsafe {
        let sh = gl.CreateShader(kind);
        gl.ShaderSource(sh, sources.len() as i32, ptrs.as_ptr(), lens.as_ptr());
        gl.CompileShader(sh);
        let mut ok = 0;
        gl.GetShaderiv(sh, GL_COMPILE_STATUS, &mut ok);
        if ok == 0 {
            // `info_log` passes a buffer of `n` bytes.
            let log = info_log(|n, len, buf| gl.GetShaderInfoLog(sh, n, len, buf));
            gl.DeleteShader(sh);
            return Err(format!("compiling failed: {log}"));
        }
        Ok(sh)
    }
}

/// Compiles and links a program; the shaders are deleted afterwards.
unsafe fn link(gl: &Gl, vertex: &[&str], fragment: &[&str]) -> std::result::Result<u32, String> {
    // SAFETY: a context is current (contract).
    unsafe {
        let vs = compile(gl, GL_VERTEX_SHADER, vertex)?;
        let fs = match compile(gl, GL_FRAGMENT_SHADER, fragment) {
            Ok(fs) => fs,
            Err(e) => {
                gl.DeleteShader(vs);
                return Err(e);
            }
        };
        let prog = gl.CreateProgram();
        gl.AttachShader(prog, vs);
        gl.AttachShader(prog, fs);
        gl.LinkProgram(prog);
        gl.DeleteShader(vs);
        gl.DeleteShader(fs);
        let mut ok = 0;
        gl.GetProgramiv(prog, GL_LINK_STATUS, &mut ok);
        if ok == 0 {
            // `info_log` passes a buffer of `n` bytes.
            let log = info_log(|n, len, buf| gl.GetProgramInfoLog(prog, n, len, buf));
            gl.DeleteProgram(prog);
            return Err(format!("linking failed: {log}"));
        }
        Ok(prog)
    }
}

fn info_log(get: impl Fn(i32, *mut i32, *mut std::ffi::c_char)) -> String {
    let mut buf = vec![0u8; 4096];
    let mut len = 0;
    get(buf.len() as i32, &mut len, buf.as_mut_ptr().cast());
    buf.truncate(len.clamp(0, 4096) as usize);
    String::from_utf8_lossy(&buf).trim().to_owned()
}

#[cfg(test)]
mod tests {
    //! The compositor driven directly in a real EGL context, with textures
    //! of its own and a framebuffer object standing in for a window.

    use super::*;
    use crate::output::cpu::{compose, resample};
    use crate::output::layout::composite_size;
    use crate::output::pattern::{gradient, noise};

    use crate::testing::egl_context as context;

    /// A texture holding `img` (stored bottom row first, as GL does).
    unsafe fn texture(gl: &Gl, img: &Image) -> TexRect {
        let mut c = Canvas::default();
        let mut rows = img.clone();
        rows.flip_vertical();
        // SAFETY: a context is current; the pixels are tightly packed RGBA8.
        unsafe {
            c.ensure(gl, img.width(), img.height()).unwrap();
            gl.BindTexture(GL_TEXTURE_2D, c.texture);
            gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
            gl.TexSubImage2D(
                GL_TEXTURE_2D,
                0,
                0,
                0,
                img.width() as i32,
                img.height() as i32,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                rows.pixels().as_ptr().cast(),
            );
        }
        TexRect {
            texture: c.texture,
            x: 0,
            y: 0,
            width: img.width(),
            height: img.height(),
        }
    }

    /// A framebuffer object with `n` RGBA8 colour attachments of w × h,
    /// cleared to grey (so untouched pixels show).
    unsafe fn window(gl: &Gl, n: u32, w: u32, h: u32) -> u32 {
        let mut fbo = 0;
        // SAFETY: a context is current.
        unsafe {
            gl.GenFramebuffers(1, &mut fbo);
            for i in 0..n {
                let mut c = Canvas::default();
                c.ensure(gl, w, h).unwrap();
                gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
                gl.FramebufferTexture2D(
                    GL_DRAW_FRAMEBUFFER,
                    GL_COLOR_ATTACHMENT0 + i,
                    GL_TEXTURE_2D,
                    c.texture,
                    0,
                );
                gl.DrawBuffer(GL_COLOR_ATTACHMENT0 + i);
                gl.ClearColor(0.5, 0.5, 0.5, 1.0);
                gl.Clear(GL_COLOR_BUFFER_BIT);
            }
        }
        fbo
    }

    unsafe fn read(gl: &Gl, fbo: u32, attachment: u32, w: u32, h: u32) -> Image {
        let mut img = Image::new(w, h);
        // SAFETY: a context is current; the image holds w×h×4 bytes.
        unsafe {
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
            gl.ReadBuffer(GL_COLOR_ATTACHMENT0 + attachment);
            gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
            gl.ReadPixels(
                0,
                0,
                w as i32,
                h as i32,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                img.pixels_mut().as_mut_ptr().cast(),
            );
            assert_eq!(gl.take_error(), GL_NO_ERROR);
        }
        img.flip_vertical();
        img
    }

    fn max_diff(a: &Image, b: &Image) -> u8 {
        a.max_difference(b).expect("same size").0
    }

    /// `composite` placed in a black `ww` × `wh` window at (x, y), cropped.
    fn placed(composite: &Image, ww: u32, wh: u32, x: i32, y: i32) -> Image {
        Image::from_fn(ww, wh, |wx, wy| {
            let (cx, cy) = (wx as i32 - x, wy as i32 - y);
            if cx >= 0 && cy >= 0 && cx < composite.width() as i32 && cy < composite.height() as i32
            {
                composite.get(cx as u32, cy as u32)
            } else {
                [0, 0, 0, 255]
            }
        })
    }

    fn job(mode: OutputMode, l: TexRect, r: TexRect) -> Job {
        Job {
            mode,
            options: OutputOptions::default(),
            frame_index: 0,
            eyes: [l, r],
            eye_size: (l.width, l.height),
            in_place: [None; 2],
        }
    }

    #[test]
    fn mesa_software_renderers_are_recognised() {
        assert!(is_software_renderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
        assert!(is_software_renderer("softpipe"));
        assert!(is_software_renderer("Mesa X11 Software Rasterizer"));
        assert!(!is_software_renderer(
            "Mesa Intel(R) UHD Graphics 620 (KBL GT2)"
        ));
        assert!(!is_software_renderer(
            "AMD Radeon RX 6600 (navi23, LLVM 15.0.6, DRM 3.49)"
        ));
        // GL over Vulkan (or a remote GPU) names its device in brackets.
        assert!(!is_software_renderer(
            "zink (llvmpipe (LLVM 15.0.6, 256 bits))"
        ));
        assert!(!is_software_renderer(
            "zink (Lavapipe (LLVM 19.1.7, 256 bits))"
        ));
        assert!(!is_software_renderer(
            "virgl (LLVMPIPE (LLVM 15.0.6, 256 bits))"
        ));
    }

    #[test]
    fn zink_over_lavapipe_composes_on_the_cpu_and_gpus_do_not() {
        for cpu in [
            "llvmpipe (LLVM 15.0.6, 256 bits)",
            "softpipe",
            "zink (llvmpipe (LLVM 15.0.6, 256 bits))",
            "zink (Lavapipe (LLVM 19.1.7, 256 bits))",
        ] {
            assert!(composes_on_cpu(cpu), "{cpu}");
        }
        for gpu in [
            "Mesa Intel(R) UHD Graphics 620 (KBL GT2)",
            "zink (AMD Radeon RX 6600 (RADV NAVI23))",
            "virgl (LLVMPIPE (LLVM 15.0.6, 256 bits))",
        ] {
            assert!(!composes_on_cpu(gpu), "{gpu}");
        }
    }

    #[test]
    fn a_window_of_the_composite_size_shows_it_pixel_for_pixel() {
        let cx = context();
        let (w, h) = (23, 11);
        let (li, ri) = (noise(w, h, 1), gradient(w, h, 9));
        let mut c = GlCompositor::new();
        // SAFETY: the context is current on this thread.
        unsafe {
            let (l, r) = (texture(&cx.gl, &li), texture(&cx.gl, &ri));
            for mode in [
                OutputMode::from_name("anaglyph-red-cyan-dubois").unwrap(),
                OutputMode::SideBySide,
                OutputMode::Checkerboard,
            ] {
                let (cw, ch) = composite_size(mode, w, h);
                let win = window(&cx.gl, 1, cw, ch);
                c.compose_window(&cx.gl, &job(mode, l, r), win, cw, ch)
                    .unwrap();
                let want = compose(mode, &OutputOptions::default(), &li, &ri, 0).unwrap();
                let got = read(&cx.gl, win, 0, cw, ch);
                assert!(max_diff(&got, &want) <= 1, "{mode}");
            }
        }
    }

    #[test]
    fn interleaved_modes_are_centred_unscaled_keeping_parity_and_cropped() {
        let cx = context();
        let (w, h) = (16, 10);
        let (li, ri) = (noise(w, h, 3), noise(w, h, 4));
        let mut c = GlCompositor::new();
        // SAFETY: the context is current on this thread.
        unsafe {
            let (l, r) = (texture(&cx.gl, &li), texture(&cx.gl, &ri));
            for mode in [
                OutputMode::Rows,
                OutputMode::Columns,
                OutputMode::Checkerboard,
            ] {
                let want = compose(mode, &OutputOptions::default(), &li, &ri, 0).unwrap();
                // Larger: centred with even offsets (3 → 2, 2 → 2). Smaller: cropped (−3 → −4).
                for (ww, wh, x, y) in [(21, 15, 2, 2), (10, 7, -4, -2)] {
                    let win = window(&cx.gl, 1, ww, wh);
                    c.compose_window(&cx.gl, &job(mode, l, r), win, ww, wh)
                        .unwrap();
                    let got = read(&cx.gl, win, 0, ww, wh);
                    let exp = placed(&want, ww, wh, x, y);
                    assert_eq!(max_diff(&got, &exp), 0, "{mode} in {ww}x{wh}");
                }
            }
        }
    }

    #[test]
    fn other_composites_are_scaled_to_fit_on_black() {
        let cx = context();
        let (w, h) = (16, 8);
        let (li, ri) = (gradient(w, h, 0), gradient(w, h, 128));
        let mut c = GlCompositor::new();
        // SAFETY: the context is current on this thread.
        unsafe {
            let (l, r) = (texture(&cx.gl, &li), texture(&cx.gl, &ri));
            // Side-by-side 32x8 in a 16x8 window: 16x4 at row 2, black above and below.
            let win = window(&cx.gl, 1, w, h);
            c.compose_window(&cx.gl, &job(OutputMode::SideBySide, l, r), win, w, h)
                .unwrap();
            let got = read(&cx.gl, win, 0, w, h);
            let full = compose(
                OutputMode::SideBySide,
                &OutputOptions::default(),
                &li,
                &ri,
                0,
            )
            .unwrap();
            let scaled = resample(&full, 0, 0, 32, 8, 16, 4);
            let want = placed(&scaled, w, h, 0, 2);
            // The blit's filter is the driver's (reduced-precision weights).
            let d = max_diff(&got, &want);
            assert!(d <= 2, "scaled side-by-side differs by {d}");
            for x in 0..w {
                for y in [0, 1, 6, 7] {
                    assert_eq!(got.get(x, y), [0, 0, 0, 255], "letterbox at ({x}, {y})");
                }
            }
        }
    }

    #[test]
    fn quad_draws_each_eye_into_its_own_buffer() {
        let cx = context();
        let (w, h) = (9, 5);
        let (li, ri) = (noise(w, h, 5), noise(w, h, 6));
        let mut c = GlCompositor::new();
        // SAFETY: the context is current on this thread.
        unsafe {
            let (l, r) = (texture(&cx.gl, &li), texture(&cx.gl, &ri));
            let win = window(&cx.gl, 2, w, h);
            c.compose_window(&cx.gl, &job(OutputMode::Quad, l, r), win, w, h)
                .unwrap();
            assert_eq!(max_diff(&read(&cx.gl, win, 0, w, h), &li), 0, "left");
            assert_eq!(max_diff(&read(&cx.gl, win, 1, w, h), &ri), 0, "right");
            // Quad is no composite image: a capture refuses it as the CPU does.
            let e = c
                .compose_capture(&cx.gl, &job(OutputMode::Quad, l, r))
                .unwrap_err();
            assert!(matches!(e, Error::InvalidOperation(_)), "{e}");
        }
    }

    #[test]
    fn eyes_in_sub_rectangles_clamp_at_the_rectangle_not_the_texture() {
        // Two eyes in one texture, each stretched to twice its size (as a
        // sync-doubled frame is): the taps at an eye's inner edge must
        // clamp there, not blend in the other eye's first texels.
        let cx = context();
        let (w, h) = (7, 6);
        let frame = noise(w, h, 7);
        let mut c = GlCompositor::new();
        // SAFETY: the context is current on this thread.
        unsafe {
            let t = texture(&cx.gl, &frame);
            // Stacked: left = top 3 rows (GL rows 3..6), right = bottom 3.
            let top = TexRect {
                y: 3,
                height: 3,
                ..t
            };
            let bottom = TexRect { height: 3, ..t };
            // Side by side: left = columns 0..3, right = columns 3..7 (one wider).
            let west = TexRect { width: 3, ..t };
            let east = TexRect {
                x: 3,
                width: 4,
                ..t
            };
            let cases = [
                ((top, bottom), (w, h), [(0, 0, w, 3), (0, 3, w, 3)]),
                ((west, east), (w, h), [(0, 0, 3, h), (3, 0, 4, h)]),
            ];
            for ((l, r), (ew, eh), [a, b]) in cases {
                let li = resample(&frame, a.0, a.1, a.2, a.3, ew, eh);
                let ri = resample(&frame, b.0, b.1, b.2, b.3, ew, eh);
                for mode in [OutputMode::SideBySide, OutputMode::TopBottomHalf] {
                    let j = Job {
                        eye_size: (ew, eh),
                        ..job(mode, l, r)
                    };
                    let (cw, ch) = c.compose_capture(&cx.gl, &j).unwrap();
                    let mut got = Image::new(cw, ch);
                    c.read_capture(&cx.gl, &mut got).unwrap();
                    let want = compose(mode, &OutputOptions::default(), &li, &ri, 0).unwrap();
                    assert_eq!(max_diff(&got, &want), 0, "{mode} of {l:?}, {r:?}");
                }
            }
        }
    }
}

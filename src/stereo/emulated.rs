//! An emulated default framebuffer: up to four RGBA8 colour textures
//! (front-left, back-left, front-right, back-right) and one depth/stencil
//! renderbuffer shared by both eyes, as on real quad-buffer hardware.
//!
//! The textures are created in the surface's compositor context and shared
//! with the application context, which renders into them through one
//! framebuffer object. Each colour buffer lives in a fixed attachment
//! *slot*; a swap exchanges which slot is "front" and which is "back" for
//! each eye and re-issues glDrawBuffers/glReadBuffer, so presenting a frame
//! copies nothing.
//!
//! The draw-buffer table of that framebuffer object is sparse where GL
//! says outputs go nowhere: under glDrawBuffer(GL_BACK) on stereo it is
//! {back-left, NONE ×4, back-right} (the copies of output 0 are at
//! [`COPY_LOCATIONS`]). Mesa 22.3's zink crashes on a table with two or
//! more GL_NONE entries below its last buffer (inside its Vulkan driver,
//! at the first clear or draw; its own GL programs can trigger it too), so
//! on zink ([`fills_draw_buffer_gaps`]) the gaps are filled with
//! one-channel textures nothing reads, attached at
//! `GL_COLOR_ATTACHMENT4…7`: outputs 1…4 still reach no colour buffer the
//! program can see, and every query answers as before.
//!
//! Where the driver allows (llvmpipe) and the formats ask for it
//! ([`BufferFormats::in_place`]), the colour textures' storage is memory
//! the CPU maps too ([`crate::stereo::eye_memory`]), so a composite reads
//! the eyes where they were drawn ([`EmulatedFramebuffer::pixels`]).
//! Such storage is immutable: a resize replaces the textures, the
//! program's framebuffer object takes the new ones
//! ([`EmulatedFramebuffer::reattach_app`]) and the old memory is freed
//! once nothing renders into it ([`EmulatedFramebuffer::release_retired`]).

use crate::auto::eyes::{LayeredApi, LayeredEyes};
use crate::error::{Error, Result};
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::image::flip_rows;
use crate::stereo::buffers::{
    BufferSet, ColorBuffer, FramebufferShape, resolve_draw_buffer, resolve_draw_buffers,
    resolve_read_buffer,
};
use crate::stereo::eye_memory::{self, EyePixels, MemoryObjectApi, TextureMemory};

/// The layers of the layered eyes the program draws into: every one
/// (None), or the left eye's only where automatic stereo makes the eyes
/// from the frame's depth ([`crate::auto::from_depth`]): nothing is drawn
/// into the right eye's layer then, and a glClear clears one layer, not
/// two.
fn drawn_layers() -> Option<crate::math::Eye> {
    crate::auto::live::from_depth().then_some(crate::math::Eye::Left)
}

/// Largest number of fragment outputs the draw state tracks (GL 3.0's
/// minimum GL_MAX_DRAW_BUFFERS, which every host of the emulation has).
pub const MAX_DRAW_BUFFERS: usize = 8;

/// The fragment-output locations (and draw-buffer slots of the emulated
/// framebuffer object) that carry copies of output 0 to the second, third
/// and fourth buffer a glDrawBuffer name selects: the top three of
/// [`MAX_DRAW_BUFFERS`], which programs drawing into a default framebuffer
/// leave unused (only output 0 reaches a default framebuffer under
/// glDrawBuffer). In that order: the second buffer at 5 leaves four gaps
/// below it (slots 1…4), as many as there are filler attachments where a
/// driver needs the gaps filled ([`fills_draw_buffer_gaps`]).
pub const COPY_LOCATIONS: [u32; 3] = [5, 6, 7];

/// Filler attachments at most (`GL_COLOR_ATTACHMENT4…7`; GL 3.0 has 8).
const FILLERS: usize = MAX_DRAW_BUFFERS - 4;

/// Whether the renderer named `renderer` (GL_RENDERER) gets the gaps of
/// its draw-buffer tables filled (see the module documentation): zink,
/// whose Mesa 22.3 crashes on two GL_NONE entries below the last buffer
/// (checked with and without glstereo; zink on Mesa 25 does not, and
/// llvmpipe never did). The cost is four one-channel textures the size of
/// the eyes and their writes; other drivers take the sparse table.
pub fn fills_draw_buffer_gaps(renderer: &str) -> bool {
    renderer.starts_with("zink")
}

/// Up to four draw-buffer indices ([`EmulatedFramebuffer::draw_buffer_slots`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawSlots {
    slots: [i32; 4],
    n: usize,
}

impl DrawSlots {
    /// Just `i`.
    pub fn one(i: i32) -> DrawSlots {
        let mut v = DrawSlots::default();
        v.push(i);
        v
    }

    fn push(&mut self, i: i32) {
        self.slots[self.n] = i;
        self.n += 1;
    }

    /// The indices.
    pub fn as_slice(&self) -> &[i32] {
        &self.slots[..self.n]
    }
}

/// Puts the filler attachments (`GL_COLOR_ATTACHMENT4…7`, in order) in
/// the GL_NONE entries of a draw-buffer table below its last buffer, as
/// many as there are fillers; entries after the last buffer stay GL_NONE.
fn fill_gaps(table: &mut [u32]) {
    let last = table.iter().rposition(|&a| a != GL_NONE).unwrap_or(0);
    let gaps = table[..last].iter_mut().filter(|a| **a == GL_NONE);
    for (a, k) in gaps.zip(0..FILLERS) {
        *a = GL_COLOR_ATTACHMENT0 + (4 + k) as u32;
    }
}

/// What glGetIntegerv(`pname`) reports about an emulated default
/// framebuffer of `shape`, or None where the driver's own answer stands.
/// `draw` and `read` are the emulated framebuffer when its object is the
/// one bound to that target, None when the program has bound its own.
///
/// Answered: GL_STEREO and GL_DOUBLEBUFFER (from the shape, when the
/// emulated framebuffer is the draw framebuffer: GL answers them from the
/// draw framebuffer, and a framebuffer object is neither);
/// GL_DRAW_BUFFER, GL_DRAW_BUFFERi and GL_READ_BUFFER (as the program set
/// them); GL_DRAW_FRAMEBUFFER_BINDING and GL_READ_FRAMEBUFFER_BINDING (0:
/// the emulation's framebuffer object is the default framebuffer).
pub fn default_framebuffer_query(
    pname: u32,
    shape: FramebufferShape,
    draw: Option<&EmulatedFramebuffer>,
    read: Option<&EmulatedFramebuffer>,
) -> Option<i32> {
    match (pname, draw, read) {
        (GL_STEREO, Some(_), _) => Some(shape.stereo as i32),
        (GL_DOUBLEBUFFER, Some(_), _) => Some(shape.double_buffered as i32),
        (GL_DRAW_FRAMEBUFFER_BINDING, Some(_), _) => Some(0),
        (GL_READ_FRAMEBUFFER_BINDING, _, Some(_)) => Some(0),
        (GL_DRAW_BUFFER, Some(fb), _) => Some(fb.draw_buffer_query(0) as i32),
        (p, Some(fb), _) if (GL_DRAW_BUFFER0..=GL_DRAW_BUFFER15).contains(&p) => {
            Some(fb.draw_buffer_query((p - GL_DRAW_BUFFER0) as usize) as i32)
        }
        (GL_READ_BUFFER, _, Some(fb)) => Some(fb.read_buffer_query() as i32),
        _ => None,
    }
}

/// A saved draw-buffer selection of an [`EmulatedFramebuffer`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DrawSelection(DrawState);

/// A saved read-buffer selection of an [`EmulatedFramebuffer`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReadSelection {
    name: u32,
    buffer: Option<ColorBuffer>,
}

impl DrawSelection {
    /// Whether every name the program gave is GL_NONE (the only names a
    /// default framebuffer and a framebuffer object both accept).
    pub fn is_none(&self) -> bool {
        match self.0 {
            DrawState::Single { name, .. } => name == GL_NONE,
            DrawState::Multi { n, names, .. } => names[..n].iter().all(|&b| b == GL_NONE),
        }
    }
}

impl ReadSelection {
    /// Whether the program's name is GL_NONE.
    pub fn is_none(&self) -> bool {
        self.name == GL_NONE
    }
}

/// The draw-buffer state as the program set it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum DrawState {
    /// glDrawBuffer(name): every output 0 fragment goes to every buffer in `set`.
    Single { name: u32, set: BufferSet },
    /// glDrawBuffers(n, names): output i goes to `bufs[i]`.
    Multi {
        n: usize,
        names: [u32; MAX_DRAW_BUFFERS],
        bufs: [Option<ColorBuffer>; MAX_DRAW_BUFFERS],
    },
}

/// The storage formats of an emulated framebuffer's buffers.
#[derive(Clone, Copy, Debug)]
pub struct BufferFormats {
    /// Internal format of each colour texture: GL_RGBA8 (GL_RGB8 where a
    /// caller asks for it; llvmpipe reads GL_RGB8 back about six times
    /// more slowly).
    pub color: u32,
    /// The buffers stand for a visual without alpha in GL_RGBA8 storage:
    /// their alpha is cleared to 1.0 and the user of the buffers (the
    /// preload layer) keeps it 1.0, so that they read alpha as 1.0 and
    /// blend with a destination alpha of 1.0 as a default framebuffer
    /// without alpha bits does.
    pub opaque: bool,
    /// Internal format of the one depth/stencil renderbuffer:
    /// GL_DEPTH24_STENCIL8, GL_DEPTH_COMPONENT16, 24 or 32, or 0 for none.
    pub depth: u32,
    /// Make RGBA8 colour textures from memory the CPU reads in place,
    /// where the driver allows ([`crate::stereo::eye_memory`]; llvmpipe),
    /// through this API. Their storage is then immutable: a resize
    /// replaces the textures, and the program's framebuffer object needs
    /// [`EmulatedFramebuffer::reattach_app`].
    pub in_place: Option<MemoryObjectApi>,
    /// Automatic stereo ([`crate::auto::eyes`]): the colour buffers are
    /// the layers of two arrays (a front and a back pair), depth and
    /// stencil one array, all made through this API and attached layered,
    /// so one draw reaches both eyes by its layer.
    pub layered: Option<LayeredApi>,
    /// The program's context is OpenGL ES, whose glDrawBuffers on a
    /// framebuffer object takes GL_COLOR_ATTACHMENTi only at position i
    /// (ES 3.2 §15.2.1; desktop GL takes any order): with layered eyes the
    /// pair drawn into (the back pair) is kept at GL_COLOR_ATTACHMENT0 and
    /// the front pair at 1, the pairs re-attached at each swap
    /// ([`EmulatedFramebuffer::swap`]) where desktop GL only exchanges the
    /// draw buffers.
    pub positional: bool,
}

impl BufferFormats {
    /// What [`EmulatedFramebuffer::allocate`] uses: RGBA8 colour, and the
    /// depth and stencil of [`BufferFormats::matching`].
    pub fn surface(depth_bits: u32, stencil_bits: u32) -> BufferFormats {
        BufferFormats {
            color: GL_RGBA8,
            opaque: false,
            depth: depth_format(depth_bits, stencil_bits),
            in_place: None,
            layered: None,
            positional: false,
        }
    }

    /// Formats that behave as a visual with these bits: RGBA8 colour,
    /// [`BufferFormats::opaque`] when it has no alpha, a depth-only buffer
    /// of the visual's depth bits when it has depth but no stencil (the
    /// stencil test then passes, as GL says without a stencil buffer), so
    /// that depths are stored, tested and read back as the driver's own
    /// buffer of those bits does: a 16-bit buffer for 16 bits, a 32-bit
    /// one for 32 (what glXChooseVisual gives a program that asks for any
    /// depth on Mesa; 24 bits there differ from its depths in the low
    /// bits). Depth with stencil is D24S8, the one such format drivers
    /// render to as unsigned normalised depth.
    pub fn matching(alpha_bits: u32, depth_bits: u32, stencil_bits: u32) -> BufferFormats {
        BufferFormats {
            color: GL_RGBA8,
            opaque: alpha_bits == 0,
            depth: depth_format(depth_bits, stencil_bits),
            in_place: None,
            layered: None,
            positional: false,
        }
    }

    fn depth_attachment(self) -> u32 {
        depth_attachment_of(self.depth)
    }
}

/// The depth buffer's format for a visual of these bits
/// ([`BufferFormats::matching`]).
fn depth_format(depth_bits: u32, stencil_bits: u32) -> u32 {
    match (depth_bits, stencil_bits > 0) {
        (0, false) => 0,
        (1..=16, false) => GL_DEPTH_COMPONENT16,
        (17..=24, false) => GL_DEPTH_COMPONENT24,
        (_, false) => GL_DEPTH_COMPONENT32,
        _ => GL_DEPTH24_STENCIL8,
    }
}

/// Where a depth buffer of `format` attaches: depth and stencil together
/// for GL_DEPTH24_STENCIL8, depth alone for the depth-only formats.
pub(crate) fn depth_attachment_of(format: u32) -> u32 {
    if format == GL_DEPTH24_STENCIL8 {
        GL_DEPTH_STENCIL_ATTACHMENT
    } else {
        GL_DEPTH_ATTACHMENT
    }
}

/// The GL objects and state of one emulated default framebuffer.
#[derive(Debug)]
pub struct EmulatedFramebuffer {
    shape: FramebufferShape,
    width: u32,
    height: u32,
    /// Colour textures by slot (0 where the buffer does not exist).
    textures: [u32; 4],
    /// Depth/stencil renderbuffer (0 when the config has neither).
    depth_stencil: u32,
    /// One-channel textures that fill the gaps of the draw-buffer table
    /// at `GL_COLOR_ATTACHMENT4…7` (all 0 where the driver takes gaps:
    /// [`fills_draw_buffer_gaps`]).
    fillers: [u32; FILLERS],
    /// Storage formats.
    formats: BufferFormats,
    /// Slot of each colour buffer, by [`ColorBuffer::index`].
    slot_of: [usize; 4],
    /// The framebuffer object in the application context (0 until attached).
    app_fbo: u32,
    /// A framebuffer object in the compositor context, for reading textures.
    read_fbo: u32,
    /// Storage of each slot's texture when it is memory the CPU reads in
    /// place ([`crate::stereo::eye_memory`]).
    memory: [Option<TextureMemory>; 4],
    /// Memory of replaced textures, freed by
    /// [`EmulatedFramebuffer::release_retired`].
    retired: Vec<TextureMemory>,
    /// The program's framebuffer object holds replaced textures.
    attachments_stale: bool,
    /// The layers of the layered eyes attached for the program
    /// ([`drawn_layers`] when they were attached).
    attached_layers: Option<crate::math::Eye>,
    draw: DrawState,
    read_name: u32,
    read: Option<ColorBuffer>,
    /// Automatic stereo's layered eyes ([`BufferFormats::layered`]).
    layered: Option<LayeredEyes>,
    /// Layered eyes replaced by a resize, released by
    /// [`EmulatedFramebuffer::release_retired`].
    retired_layers: Vec<LayeredEyes>,
}

impl EmulatedFramebuffer {
    /// Creates the colour textures and the depth/stencil renderbuffer and
    /// clears them (colour to transparent black). The compositor context of
    /// the surface must be current.
    ///
    /// # Safety
    /// A context of `gl`'s backend must be current on this thread.
    pub unsafe fn allocate(
        gl: &Gl,
        shape: FramebufferShape,
        width: u32,
        height: u32,
        depth_bits: u32,
        stencil_bits: u32,
    ) -> Result<EmulatedFramebuffer> {
        let formats = BufferFormats::surface(depth_bits, stencil_bits);
        // SAFETY: forwarded contract.
        unsafe { Self::allocate_with(gl, shape, width, height, formats) }
    }

    /// [`EmulatedFramebuffer::allocate`] with chosen storage formats. A
    /// driver that cannot render to GL_RGB8 textures gets GL_RGBA8.
    ///
    /// # Safety
    /// A context of `gl`'s backend must be current on this thread.
    pub unsafe fn allocate_with(
        gl: &Gl,
        shape: FramebufferShape,
        width: u32,
        height: u32,
        formats: BufferFormats,
    ) -> Result<EmulatedFramebuffer> {
        let initial = shape.initial_buffer();
        let mut fb = EmulatedFramebuffer {
            shape,
            width,
            height,
            textures: [0; 4],
            depth_stencil: 0,
            fillers: [0; FILLERS],
            formats,
            slot_of: [0, 1, 2, 3],
            app_fbo: 0,
            read_fbo: 0,
            memory: Default::default(),
            retired: Vec::new(),
            attachments_stale: false,
            attached_layers: None,
            draw: DrawState::Single {
                name: initial,
                set: resolve_draw_buffer(shape, initial).expect("the initial buffer exists"),
            },
            read_name: initial,
            read: resolve_read_buffer(shape, initial).expect("the initial buffer exists"),
            layered: None,
            retired_layers: Vec::new(),
        };
        // SAFETY: a context is current (contract).
        unsafe {
            let max_tex = gl.integer(GL_MAX_TEXTURE_SIZE).max(0) as u32;
            let max_rb = gl.integer(GL_MAX_RENDERBUFFER_SIZE).max(0) as u32;
            let limit = max_tex.min(max_rb);
            if width > limit || height > limit {
                return Err(Error::invalid_value(format!(
                    "surface size {width}x{height} exceeds this driver's limit of {limit} pixels per side"
                )));
            }
            gl.take_error();
            fb.read_fbo = gl.gen_framebuffer();
            // Layered eyes make their own textures.
            for b in shape
                .allocated()
                .iter()
                .filter(|_| formats.layered.is_none())
            {
                fb.textures[fb.slot_of[b.index()]] = gl.gen_texture();
            }
            // Layered eyes keep depth and stencil in their own array.
            if formats.depth != 0 && formats.layered.is_none() {
                fb.depth_stencil = gl.gen_renderbuffer();
            }
            if fills_draw_buffer_gaps(&gl.string(GL_RENDERER)) {
                for f in &mut fb.fillers {
                    *f = gl.gen_texture();
                }
            }
            let mut stored = fb.allocate_storage(gl);
            if stored.is_ok() && formats.color != GL_RGBA8 && !fb.color_renderable(gl) {
                fb.formats.color = GL_RGBA8;
                stored = fb.allocate_storage(gl);
            }
            if let Err(e) = stored {
                fb.delete(gl);
                return Err(e);
            }
        }
        Ok(fb)
    }

    /// Whether the colour textures' format can be rendered to here.
    unsafe fn color_renderable(&self, gl: &Gl) -> bool {
        // SAFETY: a context is current (contract of the callers).
        unsafe {
            gl.BindFramebuffer(GL_FRAMEBUFFER, self.read_fbo);
            gl.FramebufferTexture2D(
                GL_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0,
                GL_TEXTURE_2D,
                self.textures[0],
                0,
            );
            let status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
            gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            status == GL_FRAMEBUFFER_COMPLETE
        }
    }

    /// The storage formats in use.
    pub fn formats(&self) -> BufferFormats {
        self.formats
    }

    /// (Re)allocates texture and renderbuffer storage at the current size and clears it.
    unsafe fn allocate_storage(&mut self, gl: &Gl) -> Result<()> {
        if let Some(api) = self.formats.layered {
            // SAFETY: contract.
            return unsafe { self.allocate_layered(gl, api) };
        }
        let (w, h) = (self.width as i32, self.height as i32);
        // SAFETY: a context is current (contract of the callers).
        unsafe {
            // Storage from memory is immutable: such textures are replaced
            // (the old ones go once nothing renders into them).
            self.retire_memory(gl);
            if !self.allocate_in_place(gl) {
                for &tex in self.textures.iter().filter(|&&t| t != 0) {
                    gl.BindTexture(GL_TEXTURE_2D, tex);
                    gl.TexImage2D(
                        GL_TEXTURE_2D,
                        0,
                        self.formats.color as i32,
                        w,
                        h,
                        0,
                        GL_RGBA,
                        GL_UNSIGNED_BYTE,
                        std::ptr::null(),
                    );
                }
            }
            for &tex in self.textures.iter().filter(|&&t| t != 0) {
                gl.BindTexture(GL_TEXTURE_2D, tex);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST as i32);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST as i32);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE as i32);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE as i32);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
            }
            // The fillers' contents are never read: no clear.
            for &tex in self.fillers.iter().filter(|&&t| t != 0) {
                gl.BindTexture(GL_TEXTURE_2D, tex);
                gl.TexImage2D(
                    GL_TEXTURE_2D,
                    0,
                    GL_R8 as i32,
                    w,
                    h,
                    0,
                    GL_RED,
                    GL_UNSIGNED_BYTE,
                    std::ptr::null(),
                );
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
            }
            gl.BindTexture(GL_TEXTURE_2D, 0);
            if self.depth_stencil != 0 {
                gl.BindRenderbuffer(GL_RENDERBUFFER, self.depth_stencil);
                gl.RenderbufferStorage(GL_RENDERBUFFER, self.formats.depth, w, h);
                gl.BindRenderbuffer(GL_RENDERBUFFER, 0);
            }
            gl.check("allocating the stereo buffers")?;
            // Clear every colour buffer: new storage is undefined otherwise.
            gl.BindFramebuffer(GL_FRAMEBUFFER, self.read_fbo);
            gl.Disable(GL_SCISSOR_TEST);
            gl.ColorMask(1, 1, 1, 1);
            let alpha = if self.formats.opaque { 1.0 } else { 0.0 };
            gl.ClearColor(0.0, 0.0, 0.0, alpha);
            for &tex in self.textures.iter().filter(|&&t| t != 0) {
                gl.FramebufferTexture2D(
                    GL_FRAMEBUFFER,
                    GL_COLOR_ATTACHMENT0,
                    GL_TEXTURE_2D,
                    tex,
                    0,
                );
                gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
                gl.Clear(GL_COLOR_BUFFER_BIT);
            }
            gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            gl.check("clearing the stereo buffers")
        }
    }

    /// [`Self::allocate_storage`] of layered eyes: new ones (the old go
    /// once nothing renders into them), their textures in the slots.
    unsafe fn allocate_layered(&mut self, gl: &Gl, api: LayeredApi) -> Result<()> {
        if let Some(old) = self.layered.take() {
            self.retired_layers.push(old);
        }
        let pairs = [true, self.shape.double_buffered];
        // SAFETY: contract.
        let eyes = unsafe {
            LayeredEyes::allocate(
                gl,
                api,
                self.formats.in_place,
                (self.width, self.height),
                (self.formats.depth, self.formats.opaque),
                pairs,
                self.read_fbo,
            )?
        };
        for slot in 0..4 {
            self.textures[slot] = eyes.texture(slot);
        }
        self.layered = Some(eyes);
        self.attachments_stale = self.app_fbo != 0;
        Ok(())
    }

    /// Copies the layered eyes (automatic stereo) into the colour buffers
    /// a present shows: the back buffers before a swap (`front` false),
    /// the front buffers of a single-buffered framebuffer. Nothing without
    /// layered eyes.
    ///
    /// # Safety
    /// A context sharing the framebuffer's objects must be current.
    pub unsafe fn resolve_layers(&self, front: bool) {
        let Some(eyes) = &self.layered else {
            return;
        };
        let left = if front || !self.shape.double_buffered {
            ColorBuffer::FrontLeft
        } else {
            ColorBuffer::BackLeft
        };
        // SAFETY: contract.
        unsafe { eyes.resolve(crate::auto::eyes::pair(self.slot_of[left.index()])) };
    }

    /// Readies layered eyes' shared memory to be freed by the driver
    /// rather than by [`Self::release`] (their share group ends): nothing
    /// may render into them afterwards.
    pub fn prepare_unmap(&self) {
        for eyes in self.layered.iter().chain(&self.retired_layers) {
            eyes.prepare_unmap();
        }
    }

    /// Once the share group's contexts that used them are destroyed:
    /// unmaps the layer's own view of the layered eyes' shared memory
    /// ([`LayeredEyes::unmap`]).
    pub fn unmap_layers(&mut self) {
        for eyes in self
            .layered
            .iter_mut()
            .chain(self.retired_layers.iter_mut())
        {
            eyes.unmap();
        }
    }

    /// The layered eyes of automatic stereo, if this framebuffer has them.
    pub fn layered(&self) -> Option<&LayeredEyes> {
        self.layered.as_ref()
    }

    /// Gives every colour texture storage the CPU reads in place
    /// ([`crate::stereo::eye_memory`]) when the formats ask for it and the
    /// driver allows; true when all have it, false (and no texture has it)
    /// otherwise. The textures must have no storage yet.
    unsafe fn allocate_in_place(&mut self, gl: &Gl) -> bool {
        let Some(api) = self.formats.in_place else {
            return false;
        };
        if self.formats.color != GL_RGBA8 || !eye_memory::wanted() {
            return false;
        }
        // SAFETY: a context is current (contract of the callers).
        let Some(uuid) = (unsafe { eye_memory::llvmpipe_identity(gl) }) else {
            return false;
        };
        let mut all = true;
        for slot in 0..4 {
            let tex = self.textures[slot];
            if tex == 0 {
                continue;
            }
            // SAFETY: as above; `tex` has no storage.
            let made =
                unsafe { TextureMemory::create(gl, &api, &uuid, tex, self.width, self.height) };
            let Some(m) = made else {
                all = false;
                break;
            };
            // SAFETY: as above.
            let fits = unsafe { m.verify(gl, tex, self.read_fbo) };
            self.memory[slot] = Some(m);
            if !fits {
                all = false;
                break;
            }
        }
        if all {
            return true;
        }
        eye_memory::give_up("the driver did not take memory for them, or laid it out otherwise");
        // SAFETY: as above. The textures and memory made here were only
        // used here (memory retired by earlier sizes waits for the program
        // as before): every texture that may have been given storage gets
        // a new name, and its memory goes after it.
        unsafe {
            gl.Finish();
            for slot in 0..4 {
                if self.textures[slot] != 0 {
                    gl.delete_textures(&[self.textures[slot]]);
                    self.textures[slot] = gl.gen_texture();
                }
                if let Some(m) = self.memory[slot].take() {
                    m.release(&api);
                }
            }
        }
        self.attachments_stale = self.app_fbo != 0;
        false
    }

    /// Replaces the colour textures whose storage is memory by new names
    /// without storage; their memory waits in `retired` until
    /// [`EmulatedFramebuffer::release_retired`] (the program's
    /// framebuffer object may still hold the old textures).
    unsafe fn retire_memory(&mut self, gl: &Gl) {
        for slot in 0..4 {
            if let Some(m) = self.memory[slot].take() {
                // SAFETY: a context is current (contract of the callers).
                unsafe {
                    gl.delete_textures(&[self.textures[slot]]);
                    self.textures[slot] = gl.gen_texture();
                }
                self.retired.push(m);
                self.attachments_stale = self.app_fbo != 0;
            }
        }
    }

    /// Frees the memory of textures replaced since the last call. Call
    /// when no context renders into them any more: after the program's
    /// context finished its work with the new attachments in place.
    ///
    /// # Safety
    /// A context sharing the framebuffer's objects must be current.
    pub unsafe fn release_retired(&mut self, gl: &Gl) {
        for mut eyes in self.retired_layers.drain(..) {
            // SAFETY: contract.
            unsafe { eyes.release(gl) };
        }
        if self.retired.is_empty() {
            return;
        }
        let api = self.formats.in_place.expect("memory came from this API");
        for m in self.retired.drain(..) {
            // SAFETY: contract; the textures were deleted when retired.
            unsafe { m.release(&api) };
        }
    }

    /// Whether the program's framebuffer object still holds textures that
    /// were replaced ([`EmulatedFramebuffer::reattach_app`] puts the new ones
    /// in).
    pub fn attachments_stale(&self) -> bool {
        self.attachments_stale
    }

    /// Attaches the current textures to the program's framebuffer object
    /// after they were replaced (a resize of storage from memory), keeping
    /// its draw and read buffers and the context's bindings.
    ///
    /// # Safety
    /// The context owning the program's framebuffer object must be current.
    pub unsafe fn reattach_app(&mut self, gl: &Gl) -> Result<()> {
        if !self.attachments_stale || self.app_fbo == 0 {
            self.attachments_stale = false;
            return Ok(());
        }
        // SAFETY: contract.
        unsafe {
            let prev_draw = gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32;
            let prev_read = gl.integer(GL_READ_FRAMEBUFFER_BINDING) as u32;
            gl.BindFramebuffer(GL_FRAMEBUFFER, self.app_fbo);
            let attached = self.attach_storage(gl);
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, prev_draw);
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, prev_read);
            self.attachments_stale = false;
            attached
        }
    }

    /// Marks the attachments stale ([`Self::reattach_app`]) where the
    /// layered eyes were attached for another kind of automatic stereo
    /// than the one on now (a live switch: Ctrl+F2).
    pub fn follow_auto_mode(&mut self) {
        if self.layered.is_some() && self.app_fbo != 0 && self.attached_layers != drawn_layers() {
            self.attachments_stale = true;
        }
    }

    /// Whether any colour texture's storage (or a replaced one's, not yet
    /// freed) is memory from [`crate::stereo::eye_memory`].
    pub fn holds_memory(&self) -> bool {
        self.memory.iter().any(Option::is_some)
            || !self.retired.is_empty()
            || self.layered.as_ref().is_some_and(|e| e.pixels(0).is_some())
            || !self.retired_layers.is_empty()
    }

    /// Where the CPU reads `buffer` in place, when its storage is memory
    /// ([`crate::stereo::eye_memory`]).
    pub fn pixels(&self, buffer: ColorBuffer) -> Option<EyePixels> {
        if !self.shape.allocated().contains(buffer) {
            return None;
        }
        let slot = self.slot_of[buffer.index()];
        if let Some(eyes) = &self.layered {
            return eyes.pixels(slot);
        }
        self.memory[slot]
            .as_ref()
            .map(|m| m.pixels(self.textures[slot]))
    }

    /// Deletes the textures, the renderbuffer and the read framebuffer
    /// (the application's framebuffer object goes with its context). The
    /// context the framebuffer was allocated in must be current.
    ///
    /// # Safety
    /// That context (or one sharing its objects, for everything but the
    /// read framebuffer) must be current on this thread.
    pub unsafe fn release(&mut self, gl: &Gl) {
        // SAFETY: contract.
        unsafe { self.delete(gl) }
    }

    /// Deletes the shared objects (compositor context current).
    unsafe fn delete(&mut self, gl: &Gl) {
        // SAFETY: a context is current (contract of the callers).
        unsafe {
            gl.delete_textures(&self.textures);
            gl.delete_textures(&self.fillers);
            if self.memory.iter().any(Option::is_some) || !self.retired.is_empty() {
                // Memory goes with its memory object: nothing may render
                // into it any more.
                gl.Finish();
                for m in self.memory.iter_mut().filter_map(Option::take) {
                    self.retired.push(m);
                }
                self.release_retired(gl);
            }
            if self.depth_stencil != 0 {
                gl.delete_renderbuffers(&[self.depth_stencil]);
            }
            for mut eyes in self
                .layered
                .take()
                .into_iter()
                .chain(self.retired_layers.drain(..))
            {
                eyes.release(gl);
            }
            gl.delete_framebuffers(&[self.read_fbo]);
        }
        self.textures = [0; 4];
        self.fillers = [0; FILLERS];
        self.depth_stencil = 0;
        self.read_fbo = 0;
    }

    /// The buffers this framebuffer has.
    pub fn shape(&self) -> FramebufferShape {
        self.shape
    }

    /// Width and height of each colour buffer.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The framebuffer object of the layer's context for reading the
    /// textures.
    pub fn read_fbo(&self) -> u32 {
        self.read_fbo
    }

    /// The framebuffer object the application renders into (0 before attach).
    pub fn app_fbo(&self) -> u32 {
        self.app_fbo
    }

    /// The texture holding `buffer` now (0 if the framebuffer lacks it).
    pub fn texture(&self, buffer: ColorBuffer) -> u32 {
        if self.shape.allocated().contains(buffer) {
            self.textures[self.slot_of[buffer.index()]]
        } else {
            0
        }
    }

    /// Creates the application's framebuffer object, binds it as the draw
    /// and read framebuffer, applies the draw/read state, and sets the
    /// viewport and scissor box to the full size, as a GL context does the
    /// first time it is bound to a window. The application context must be
    /// current.
    ///
    /// # Safety
    /// The surface's application context must be current on this thread.
    pub unsafe fn attach_app(&mut self, gl: &Gl) -> Result<()> {
        // SAFETY: the application context is current (contract).
        unsafe {
            gl.take_error();
            self.create_app_fbo(gl)?;
            gl.BindFramebuffer(GL_FRAMEBUFFER, self.app_fbo);
            gl.Viewport(0, 0, self.width as i32, self.height as i32);
            gl.Scissor(0, 0, self.width as i32, self.height as i32);
            gl.check("binding the stereo framebuffer")
        }
    }

    /// Creates the application's framebuffer object in the context current
    /// on this thread, attaches the buffers and applies the draw/read
    /// state, and leaves that context's framebuffer bindings as they were:
    /// the caller decides what to bind (the LD_PRELOAD interposer binds it
    /// in place of the program's framebuffer 0). Touches no other state.
    ///
    /// # Safety
    /// A context sharing objects with the one the framebuffer was allocated
    /// in must be current on this thread.
    pub unsafe fn create_app_fbo(&mut self, gl: &Gl) -> Result<()> {
        // SAFETY: contract.
        unsafe {
            let prev_draw = gl.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32;
            let prev_read = gl.integer(GL_READ_FRAMEBUFFER_BINDING) as u32;
            self.app_fbo = gl.gen_framebuffer();
            gl.BindFramebuffer(GL_FRAMEBUFFER, self.app_fbo);
            let attached = self.attach_storage(gl);
            if attached.is_ok() {
                self.apply_draw(gl);
                self.apply_read(gl);
            }
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, prev_draw);
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, prev_read);
            if attached.is_err() {
                gl.delete_framebuffers(&[self.app_fbo]);
                self.app_fbo = 0;
            }
            attached
        }
    }

    /// Deletes the application's framebuffer object, when the drawable it
    /// stands for goes: the textures it holds (and their memory) are freed
    /// only once no framebuffer object holds them.
    ///
    /// # Safety
    /// The context the object was made in (the application's) must be
    /// current on this thread.
    pub unsafe fn delete_app_fbo(&mut self, gl: &Gl) {
        if self.app_fbo != 0 {
            // SAFETY: contract.
            unsafe { gl.DeleteFramebuffers(1, &self.app_fbo) };
            self.app_fbo = 0;
            self.attachments_stale = false;
        }
    }

    unsafe fn attach_storage(&mut self, gl: &Gl) -> Result<()> {
        // SAFETY: the application context is current with app_fbo bound.
        unsafe {
            if let Some(attachments) = self.layered_attachments() {
                self.attached_layers = drawn_layers();
                attachments.attach(GL_FRAMEBUFFER, self.attached_layers);
                let status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
                if status != GL_FRAMEBUFFER_COMPLETE {
                    return Err(Error::Gl(format!(
                        "the layered eyes are incomplete (status {status:#06x})"
                    )));
                }
                return Ok(());
            }
            for slot in 0..4 {
                gl.FramebufferTexture2D(
                    GL_FRAMEBUFFER,
                    GL_COLOR_ATTACHMENT0 + slot as u32,
                    GL_TEXTURE_2D,
                    self.textures[slot],
                    0,
                );
            }
            for (k, &tex) in self.fillers.iter().enumerate() {
                if tex != 0 {
                    gl.FramebufferTexture2D(
                        GL_FRAMEBUFFER,
                        GL_COLOR_ATTACHMENT0 + (4 + k) as u32,
                        GL_TEXTURE_2D,
                        tex,
                        0,
                    );
                }
            }
            if self.depth_stencil != 0 {
                gl.FramebufferRenderbuffer(
                    GL_FRAMEBUFFER,
                    self.formats.depth_attachment(),
                    GL_RENDERBUFFER,
                    self.depth_stencil,
                );
            }
            let status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
            if status != GL_FRAMEBUFFER_COMPLETE {
                return Err(Error::Gl(format!(
                    "the stereo framebuffer is incomplete (status {status:#06x}): the driver cannot \
                     render to RGBA8 textures with a D24S8 renderbuffer"
                )));
            }
        }
        Ok(())
    }

    fn attachment(&self, b: Option<ColorBuffer>) -> u32 {
        b.map_or(GL_NONE, |b| {
            let slot = self.slot_of[b.index()];
            // Layered eyes: a pair's two buffers are one attachment, at
            // the pair's index, or (positional) the back pair at 0.
            let slot = if self.layered.is_some() {
                self.pair_position(crate::auto::eyes::pair(slot))
            } else {
                slot
            };
            GL_COLOR_ATTACHMENT0 + slot as u32
        })
    }

    /// The attachment index of layered pair `pair`: the pair's own, or
    /// with [`BufferFormats::positional`] 0 for the back pair and 1 for
    /// the front one.
    fn pair_position(&self, pair: usize) -> usize {
        if !self.formats.positional {
            return pair;
        }
        let back = crate::auto::eyes::pair(self.slot_of[ColorBuffer::BackLeft.index()]);
        usize::from(pair != back)
    }

    /// The layered eyes' attachments as the program's framebuffer object
    /// has them (the back pair at attachment 0 with
    /// [`BufferFormats::positional`], else each pair at its index), if this framebuffer
    /// has layered eyes.
    pub fn layered_attachments(&self) -> Option<crate::auto::eyes::Attachments> {
        let eyes = self.layered.as_ref()?;
        let order = [0, 1].map(|position| {
            (0..2)
                .find(|&p| self.pair_position(p) == position)
                .unwrap_or(position)
        });
        Some(eyes.attachments_in(order))
    }

    /// The attachments glDrawBuffers must get for the current draw state.
    /// A glDrawBuffer name selecting several buffers (GL_BACK on stereo is
    /// back-left and back-right) puts the first in slot 0 and the others in
    /// the slots of [`COPY_LOCATIONS`]: fixed-function colour and
    /// gl_FragColor reach every enabled slot, and a shader's user-defined
    /// output 0 reaches them through the copies
    /// [`crate::stereo::outputs`] adds at link time. Slots 1…4 stay
    /// GL_NONE, so outputs 1…4 go nowhere, as GL says for glDrawBuffer;
    /// where the driver needs them filled, the fillers take the GL_NONE
    /// entries below the last buffer (as many as there are fillers).
    fn draw_attachments(&self) -> ([u32; MAX_DRAW_BUFFERS], usize) {
        let mut out = [GL_NONE; MAX_DRAW_BUFFERS];
        let n = match self.draw {
            DrawState::Single { set, .. } if set.is_empty() => 1,
            DrawState::Single { set, .. } => {
                let mut buffers = set.iter();
                if let Some(first) = buffers.next() {
                    out[0] = self.attachment(Some(first));
                }
                let mut n = 1;
                let mut copies = COPY_LOCATIONS.iter();
                for b in buffers {
                    let att = self.attachment(Some(b));
                    // Layered eyes: both buffers of a pair are one attachment.
                    if out.contains(&att) {
                        continue;
                    }
                    let Some(&slot) = copies.next() else { break };
                    out[slot as usize] = att;
                    n = slot as usize + 1;
                }
                n
            }
            DrawState::Multi { n, bufs, .. } => {
                for i in 0..n {
                    out[i] = self.attachment(bufs[i]);
                }
                n.max(1)
            }
        };
        if self.fillers[0] != 0 {
            fill_gaps(&mut out[..n]);
        }
        (out, n)
    }

    /// The draw-buffer indices of the framebuffer object that stand for
    /// the program's draw buffer `i`: under a glDrawBuffer name selecting
    /// several buffers, draw buffer 0 is slot 0 and the copy slots in use,
    /// and draw buffers 1… are none (GL_NONE); otherwise `i` itself. For
    /// glClearBuffer, which clears one draw buffer by index.
    pub fn draw_buffer_slots(&self, i: i32) -> DrawSlots {
        match self.draw {
            DrawState::Single { set, .. } if set.len() > 1 && self.layered.is_some() => {
                let (atts, _) = self.draw_attachments();
                let mut v = DrawSlots::default();
                if i == 0 {
                    for (k, &a) in atts.iter().enumerate() {
                        if a != GL_NONE {
                            v.push(k as i32);
                        }
                    }
                } else if !(1..MAX_DRAW_BUFFERS as i32).contains(&i) {
                    v.push(i);
                }
                v
            }
            DrawState::Single { set, .. } if set.len() > 1 => {
                if i == 0 {
                    let mut v = DrawSlots::default();
                    v.push(0);
                    for &slot in &COPY_LOCATIONS[..set.len() - 1] {
                        v.push(slot as i32);
                    }
                    v
                } else if (1..MAX_DRAW_BUFFERS as i32).contains(&i) {
                    DrawSlots::default()
                } else {
                    // Out of range: the driver raises GL_INVALID_VALUE.
                    DrawSlots::one(i)
                }
            }
            _ => DrawSlots::one(i),
        }
    }

    /// Runs `f` with the application FBO bound to `target`, restoring the
    /// program's own binding afterwards if it had another one bound.
    unsafe fn with_bound(&self, gl: &Gl, target: u32, binding: u32, f: impl FnOnce()) {
        // SAFETY: the application context is current (contract of the callers).
        unsafe {
            let prev = gl.integer(binding) as u32;
            if prev != self.app_fbo {
                gl.BindFramebuffer(target, self.app_fbo);
            }
            f();
            if prev != self.app_fbo {
                gl.BindFramebuffer(target, prev);
            }
        }
    }

    unsafe fn apply_draw(&self, gl: &Gl) {
        let (atts, n) = self.draw_attachments();
        // SAFETY: the application context is current (contract of the callers).
        unsafe {
            self.with_bound(gl, GL_DRAW_FRAMEBUFFER, GL_DRAW_FRAMEBUFFER_BINDING, || {
                gl.DrawBuffers(n as i32, atts.as_ptr())
            })
        }
    }

    unsafe fn apply_read(&self, gl: &Gl) {
        let att = self.attachment(self.read);
        // SAFETY: the application context is current (contract of the callers).
        unsafe {
            self.with_bound(gl, GL_READ_FRAMEBUFFER, GL_READ_FRAMEBUFFER_BINDING, || {
                gl.ReadBuffer(att)
            })
        }
    }

    /// glDrawBuffer on the emulated framebuffer. On error nothing changes.
    ///
    /// # Safety
    /// The surface's application context must be current on this thread.
    pub unsafe fn set_draw_buffer(&mut self, gl: &Gl, name: u32) -> Result<()> {
        let set = resolve_draw_buffer(self.shape, name)?;
        self.draw = DrawState::Single { name, set };
        // SAFETY: contract.
        unsafe { self.apply_draw(gl) };
        Ok(())
    }

    /// glDrawBuffers on the emulated framebuffer. On error nothing changes.
    ///
    /// # Safety
    /// The surface's application context must be current on this thread.
    pub unsafe fn set_draw_buffers(&mut self, gl: &Gl, names: &[u32]) -> Result<()> {
        // SAFETY: a context is current (contract).
        let max =
            (unsafe { gl.integer(GL_MAX_DRAW_BUFFERS) }.max(1) as usize).min(MAX_DRAW_BUFFERS);
        let resolved = resolve_draw_buffers(self.shape, names, max)?;
        let mut st = DrawState::Multi {
            n: names.len(),
            names: [GL_NONE; MAX_DRAW_BUFFERS],
            bufs: [None; MAX_DRAW_BUFFERS],
        };
        if let DrawState::Multi {
            names: ns, bufs, ..
        } = &mut st
        {
            ns[..names.len()].copy_from_slice(names);
            bufs[..names.len()].copy_from_slice(&resolved);
        }
        self.draw = st;
        // SAFETY: contract.
        unsafe { self.apply_draw(gl) };
        Ok(())
    }

    /// glReadBuffer on the emulated framebuffer. On error nothing changes.
    ///
    /// # Safety
    /// The surface's application context must be current on this thread.
    pub unsafe fn set_read_buffer(&mut self, gl: &Gl, name: u32) -> Result<()> {
        self.read = resolve_read_buffer(self.shape, name)?;
        self.read_name = name;
        // SAFETY: contract.
        unsafe { self.apply_read(gl) };
        Ok(())
    }

    /// The draw-buffer selection as the program set it, to put back later
    /// ([`EmulatedFramebuffer::restore_draw_selection`]; glPushAttrib).
    pub fn draw_selection(&self) -> DrawSelection {
        DrawSelection(self.draw)
    }

    /// The read-buffer selection as the program set it.
    pub fn read_selection(&self) -> ReadSelection {
        ReadSelection {
            name: self.read_name,
            buffer: self.read,
        }
    }

    /// Puts back a draw-buffer selection taken earlier (glPopAttrib), and
    /// applies it.
    ///
    /// # Safety
    /// The surface's application context must be current on this thread.
    pub unsafe fn restore_draw_selection(&mut self, gl: &Gl, sel: DrawSelection) {
        self.draw = sel.0;
        // SAFETY: contract.
        unsafe { self.apply_draw(gl) };
    }

    /// Puts back a read-buffer selection taken earlier, and applies it.
    ///
    /// # Safety
    /// The surface's application context must be current on this thread.
    pub unsafe fn restore_read_selection(&mut self, gl: &Gl, sel: ReadSelection) {
        self.read_name = sel.name;
        self.read = sel.buffer;
        // SAFETY: contract.
        unsafe { self.apply_read(gl) };
    }

    /// GL_DRAW_BUFFER (i = None) or GL_DRAW_BUFFERi as the program set it.
    pub fn draw_buffer_query(&self, i: usize) -> u32 {
        match self.draw {
            DrawState::Single { name, .. } => {
                if i == 0 {
                    name
                } else {
                    GL_NONE
                }
            }
            DrawState::Multi { n, names, .. } => {
                if i < n {
                    names[i]
                } else {
                    GL_NONE
                }
            }
        }
    }

    /// GL_READ_BUFFER as the program set it.
    pub fn read_buffer_query(&self) -> u32 {
        self.read_name
    }

    /// The buffers the current draw state writes (no allocation: asked on
    /// every glFlush under the interposer).
    pub fn draw_set(&self) -> BufferSet {
        match self.draw {
            DrawState::Single { set, .. } => set,
            DrawState::Multi { n, bufs, .. } => bufs[..n].iter().flatten().copied().collect(),
        }
    }

    /// Presents a double-buffered framebuffer: each eye's back buffer becomes
    /// its front buffer (and the old front the new back, whose contents are
    /// undefined as after a real swap). Single-buffered: nothing to do.
    ///
    /// # Safety
    /// The surface's application context must be current on this thread.
    pub unsafe fn swap(&mut self, gl: &Gl) {
        if !self.shape.double_buffered {
            return;
        }
        self.slot_of.swap(
            ColorBuffer::FrontLeft.index(),
            ColorBuffer::BackLeft.index(),
        );
        self.slot_of.swap(
            ColorBuffer::FrontRight.index(),
            ColorBuffer::BackRight.index(),
        );
        // SAFETY: contract.
        unsafe {
            if self.formats.positional && self.layered.is_some() && self.app_fbo != 0 {
                // The new back pair moves to attachment 0 (the draw
                // buffers below then name it where ES allows).
                self.with_bound(gl, GL_DRAW_FRAMEBUFFER, GL_DRAW_FRAMEBUFFER_BINDING, || {
                    if let Some(a) = self.layered_attachments() {
                        a.attach(GL_DRAW_FRAMEBUFFER, self.attached_layers);
                    }
                });
            }
            self.apply_draw(gl);
            self.apply_read(gl);
        }
    }

    /// Changes the size of every buffer; contents become undefined (cleared
    /// to transparent black), as when a window is resized. The compositor
    /// context must be current.
    ///
    /// # Safety
    /// A context of the surface must be current on this thread.
    pub unsafe fn resize(&mut self, gl: &Gl, width: u32, height: u32) -> Result<()> {
        crate::image::check_size(width, height)?;
        let old = (self.width, self.height);
        (self.width, self.height) = (width, height);
        // SAFETY: contract.
        let r = unsafe { self.allocate_storage(gl) };
        if r.is_err() {
            (self.width, self.height) = old;
            // SAFETY: contract; best effort to restore the old storage.
            let _ = unsafe { self.allocate_storage(gl) };
        }
        r
    }

    /// Reads one colour buffer into `out` (RGBA8, rows top first). The
    /// compositor context must be current.
    ///
    /// # Safety
    /// The surface's compositor context must be current on this thread and
    /// `out` must hold width × height × 4 bytes.
    pub unsafe fn read_pixels(&self, gl: &Gl, buffer: ColorBuffer, out: &mut [u8]) -> Result<()> {
        // SAFETY: contract.
        unsafe { self.read_pixels_as_gl(gl, buffer, out)? };
        flip_rows(out, self.width as usize * 4);
        Ok(())
    }

    /// [`Self::read_pixels`] with the rows in GL's order, bottom first.
    ///
    /// # Safety
    /// As [`Self::read_pixels`].
    pub unsafe fn read_pixels_as_gl(
        &self,
        gl: &Gl,
        buffer: ColorBuffer,
        out: &mut [u8],
    ) -> Result<()> {
        let tex = self.texture(buffer);
        if tex == 0 {
            return Err(Error::invalid_operation(format!(
                "this framebuffer has no {buffer:?} buffer"
            )));
        }
        let stride = self.width as usize * 4;
        assert_eq!(
            out.len(),
            stride * self.height as usize,
            "read_pixels buffer size"
        );
        // SAFETY: compositor context current; `out` is large enough (asserted).
        unsafe {
            gl.take_error();
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, self.read_fbo);
            gl.FramebufferTexture2D(
                GL_READ_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0,
                GL_TEXTURE_2D,
                tex,
                0,
            );
            gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
            gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
            gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
            gl.ReadPixels(
                0,
                0,
                self.width as i32,
                self.height as i32,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                out.as_mut_ptr().cast(),
            );
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
            gl.check("reading the stereo buffers")
        }
    }

    /// Reads the depth/stencil renderbuffer's depth as window depths in
    /// 0…1 into `out`, rows bottom first (glReadPixels order). Both eyes
    /// share it, so it holds what the program drew last. The compositor
    /// context must be current.
    ///
    /// # Safety
    /// The surface's compositor context must be current on this thread and
    /// `out` must hold width × height values.
    pub unsafe fn read_depth(&self, gl: &Gl, out: &mut [f32]) -> Result<()> {
        if let Some(eyes) = self.layered.as_ref() {
            assert_eq!(out.len(), (self.width * self.height) as usize);
            // SAFETY: as below; the left eye's depth.
            return unsafe {
                gl.take_error();
                gl.BindFramebuffer(GL_READ_FRAMEBUFFER, self.read_fbo);
                if !eyes.attach_left_depth(GL_READ_FRAMEBUFFER, true) {
                    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
                    return Err(Error::invalid_operation(
                        "this framebuffer has no depth buffer: choose a configuration with GLX_DEPTH_SIZE",
                    ));
                }
                gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
                gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
                gl.ReadPixels(
                    0,
                    0,
                    self.width as i32,
                    self.height as i32,
                    GL_DEPTH_COMPONENT,
                    GL_FLOAT,
                    out.as_mut_ptr().cast(),
                );
                eyes.attach_left_depth(GL_READ_FRAMEBUFFER, false);
                gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
                gl.check("reading the depth buffer")
            };
        }
        if self.depth_stencil == 0 {
            return Err(Error::invalid_operation(
                "this framebuffer has no depth buffer: choose a configuration with GLX_DEPTH_SIZE",
            ));
        }
        assert_eq!(
            out.len(),
            self.width as usize * self.height as usize,
            "read_depth buffer size"
        );
        // SAFETY: compositor context current; `out` is large enough (asserted).
        unsafe {
            gl.take_error();
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, self.read_fbo);
            gl.FramebufferRenderbuffer(
                GL_READ_FRAMEBUFFER,
                self.formats.depth_attachment(),
                GL_RENDERBUFFER,
                self.depth_stencil,
            );
            gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
            gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
            gl.ReadPixels(
                0,
                0,
                self.width as i32,
                self.height as i32,
                GL_DEPTH_COMPONENT,
                GL_FLOAT,
                out.as_mut_ptr().cast(),
            );
            gl.FramebufferRenderbuffer(
                GL_READ_FRAMEBUFFER,
                self.formats.depth_attachment(),
                GL_RENDERBUFFER,
                0,
            );
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
            gl.check("reading the depth buffer")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: u32 = GL_COLOR_ATTACHMENT0 + 1;
    const B: u32 = GL_COLOR_ATTACHMENT0 + 3;
    const F: [u32; 4] = [
        GL_COLOR_ATTACHMENT0 + 4,
        GL_COLOR_ATTACHMENT0 + 5,
        GL_COLOR_ATTACHMENT0 + 6,
        GL_COLOR_ATTACHMENT0 + 7,
    ];

    #[test]
    fn the_second_selected_buffer_leaves_no_more_gaps_than_there_are_fillers() {
        // GL_BACK on stereo: back-left in slot 0, back-right at the first
        // copy location, the gaps below it filled.
        assert_eq!(COPY_LOCATIONS[0] as usize - 1, FILLERS);
        let mut t = [A, GL_NONE, GL_NONE, GL_NONE, GL_NONE, B];
        fill_gaps(&mut t);
        assert_eq!(t, [A, F[0], F[1], F[2], F[3], B]);
    }

    #[test]
    fn gaps_are_filled_below_the_last_buffer_only_and_at_most_four() {
        let mut t = [GL_NONE, A, GL_NONE, B, GL_NONE];
        fill_gaps(&mut t);
        assert_eq!(t, [F[0], A, F[1], B, GL_NONE], "trailing NONE stays");
        let mut t = [A, GL_NONE, GL_NONE, GL_NONE, GL_NONE, GL_NONE, GL_NONE, B];
        fill_gaps(&mut t);
        assert_eq!(t, [A, F[0], F[1], F[2], F[3], GL_NONE, GL_NONE, B]);
        for mut t in [[GL_NONE; 1], [A; 1]] {
            let before = t;
            fill_gaps(&mut t);
            assert_eq!(t, before, "nothing to fill");
        }
    }

    #[test]
    fn only_zink_gets_its_gaps_filled() {
        assert!(fills_draw_buffer_gaps(
            "zink (llvmpipe (LLVM 15.0.6, 256 bits))"
        ));
        assert!(!fills_draw_buffer_gaps("llvmpipe (LLVM 15.0.6, 256 bits)"));
        assert!(!fills_draw_buffer_gaps(
            "AMD Radeon RX 6600 (navi23, LLVM 15.0.6, DRM 3.49)"
        ));
    }
}

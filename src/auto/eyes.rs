//! The eyes of an automatic-stereo context: the emulated default
//! framebuffer's colour buffers and depth/stencil as 2-layer array
//! textures, layer 0 the left eye and layer 1 the right ([`crate::auto`],
//! "How a draw reaches both eyes"), attached layered to the framebuffer
//! object the program draws into in place of framebuffer 0.
//!
//! The emulated framebuffer ([`crate::stereo::emulated`]) has its colour
//! buffers in four slots, a front and a back pair (slots 0 and 2, 1 and
//! 3; a swap exchanges the pairs' roles). Here each pair is one array:
//! slot `s` is layer `s / 2` of pair `s % 2`'s array, attached at
//! GL_COLOR_ATTACHMENT0 + `s % 2`, so a program's GL_BACK (both back
//! buffers) is one attachment and a draw reaches both eyes by its layer.
//! One depth/stencil array serves both pairs (a default framebuffer has
//! one depth buffer; here one per eye).
//!
//! What presentation composes and captures is a 2D texture per slot:
//! - where the driver takes memory from a file (llvmpipe,
//!   [`crate::stereo::eye_memory`]), each pair's array and its two 2D
//!   textures are the same memory: a memory object for the array and the
//!   left eye's texture, and a second import of the same file whose data
//!   starts at the second layer for the right eye's. Nothing is copied;
//!   a composite reads the layers in place. Checked when made (markers
//!   cleared into each layer are found in the 2D textures and at the
//!   addresses predicted), else given up for the process;
//! - elsewhere the 2D textures are ordinary ones, and each present copies
//!   the pair's layers into them ([`LayeredEyes::resolve`],
//!   glCopyImageSubData).

use crate::auto::gl_fns;
use crate::error::{Error, Result};
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::math::Eye;
use crate::stereo::eye_memory::{self, EyePixels, MemoryObjectApi};

const GL_TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const GL_DEPTH_STENCIL: u32 = 0x84F9;
const GL_UNSIGNED_INT_24_8: u32 = 0x84FA;
const GL_DEPTH_COMPONENT: u32 = 0x1902;
const GL_UNSIGNED_INT: u32 = 0x1405;
const GL_DEPTH_COMPONENT16: u32 = 0x81A5;
const GL_DEPTH24_STENCIL8: u32 = 0x88F0;
const GL_STENCIL_ATTACHMENT: u32 = 0x8D20;

gl_fns! {
    /// The GL 3.2–4.3 functions layered eyes need, beyond [`Gl`]'s.
    #[derive(Clone, Copy, Debug)]
    pub struct LayeredApi {
        tex_image_3d = c"glTexImage3D": fn(u32, i32, i32, i32, i32, i32, i32, u32, u32, *const std::ffi::c_void);
        framebuffer_texture = c"glFramebufferTexture": fn(u32, u32, u32, i32);
        framebuffer_texture_layer = c"glFramebufferTextureLayer": fn(u32, u32, u32, i32, i32);
        copy_image_sub_data = c"glCopyImageSubData": fn(u32, u32, i32, i32, i32, i32, u32, u32, i32, i32, i32, i32, i32, i32, i32);
    }
}

/// The largest 24-bit depth.
const DEPTH_MAX: u32 = 0xFF_FFFF;

/// How a depth word of memory holds its depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthBits {
    /// A 32-bit word, 24-bit depth in its low bits (Z24_UNORM_S8_UINT,
    /// Z24X8).
    Low,
    /// A 32-bit word, depth in its high 24 bits (S8_UINT_Z24_UNORM, X8Z24;
    /// Z32_UNORM, whose low 8 bits are below what a shift can show).
    High,
    /// A 16-bit word of depth (Z16_UNORM).
    Short,
}

/// Rows of depth words in memory ([`LayeredEyes::left_depth`]).
#[derive(Clone, Copy, Debug)]
pub struct DepthRows {
    first: *const u8,
    /// Bytes from one row to the next (a multiple of 4).
    stride: usize,
    width: usize,
    height: usize,
    bits: DepthBits,
}

// SAFETY: a read-only view of shared memory, read after GL finished.
unsafe impl Send for DepthRows {}
// SAFETY: as above.
unsafe impl Sync for DepthRows {}

impl DepthRows {
    /// Width and height in pixels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Row `y`'s window depths (0 … 1) into `out` (`width` long).
    ///
    /// # Safety
    /// The memory lives and GL has finished writing it (the contract of
    /// [`LayeredEyes::left_depth`]); `y` < height.
    #[inline(always)]
    pub unsafe fn read_row(&self, y: usize, out: &mut [f32]) {
        // SAFETY: contract.
        unsafe { self.each(y, out, |_, d| d) }
    }

    /// Calls `f` with each of `out` and the depth of its pixel in row
    /// `y`, storing what it returns.
    ///
    /// # Safety
    /// As [`DepthRows::read_row`].
    #[inline(always)]
    unsafe fn each(&self, y: usize, out: &mut [f32], f: impl Fn(f32, f32) -> f32) {
        debug_assert!(y < self.height);
        // SAFETY: contract; a row is inside the mapping, its start aligned
        // to 4 bytes (the mapping is page-aligned, the stride a multiple
        // of 4).
        let start = unsafe { self.first.add(y * self.stride) };
        // Through i32 (exact below 2^24): a conversion every vector level
        // has.
        match self.bits {
            DepthBits::Low | DepthBits::High => {
                // SAFETY: as above; `width` words of 4 bytes.
                let row = unsafe { std::slice::from_raw_parts(start.cast::<u32>(), self.width) };
                let shift = if self.bits == DepthBits::Low { 0 } else { 8 };
                let scale = 1.0 / DEPTH_MAX as f32;
                for (o, &w) in out.iter_mut().zip(row) {
                    *o = f(*o, ((w >> shift) & DEPTH_MAX) as i32 as f32 * scale);
                }
            }
            DepthBits::Short => {
                // SAFETY: as above; `width` words of 2 bytes.
                let row = unsafe { std::slice::from_raw_parts(start.cast::<u16>(), self.width) };
                let scale = 1.0 / f32::from(u16::MAX);
                for (o, &w) in out.iter_mut().zip(row) {
                    *o = f(*o, f32::from(w) * scale);
                }
            }
        }
    }

    /// Row `y`'s window depths where they are nearer than `out`'s: each
    /// of `out` the smaller of the two.
    ///
    /// # Safety
    /// As [`DepthRows::read_row`].
    #[inline(always)]
    pub unsafe fn nearer_row(&self, y: usize, out: &mut [f32]) {
        // SAFETY: contract.
        unsafe { self.each(y, out, f32::min) }
    }
}

/// The layer of `eye`.
pub fn layer(eye: Eye) -> i32 {
    match eye {
        Eye::Left => 0,
        Eye::Right => 1,
    }
}

/// The pair (array) of slot `slot`.
pub fn pair(slot: usize) -> usize {
    slot % 2
}

/// One pair's memory: a file mapped here, imported twice (data at the
/// first layer, and at the second).
#[derive(Debug)]
struct PairMemory {
    objects: [u32; 2],
    map: *mut u8,
    map_len: usize,
    data_offset: usize,
    layer_stride: usize,
    stride: usize,
}

// SAFETY: plain shared memory; reads are ordered by GL synchronisation
// (the present's glFinish), as for eye_memory's textures.
unsafe impl Send for PairMemory {}

impl PairMemory {
    /// A new file for two layers of `width` × `height` pixels of `texel`
    /// bytes (2 or 4), mapped here and imported `imports` times (1 or 2):
    /// import i's data starts at layer i (module docs). None where the
    /// file, the mapping or an import cannot be had.
    ///
    /// # Safety
    /// A context with the memory-object API `api` is current.
    unsafe fn imported(
        api: &MemoryObjectApi,
        uuid: &[u8; 16],
        name: &std::ffi::CStr,
        (width, height): (u32, u32),
        imports: usize,
        texel: usize,
    ) -> Option<PairMemory> {
        // llvmpipe's rows: 4-texel blocks, cache lines, as for RGBA8.
        let stride = eye_memory::cache_lines(eye_memory::predicted_stride(width) / 4 * texel);
        let rows = (height as usize).div_ceil(4) * 4;
        let layer_stride = stride.checked_mul(rows)?;
        let page = 4096;
        let data_offset = page;
        let map_len = data_offset + 2 * layer_stride + page;
        // SAFETY: plain libc calls on a file this function owns; GL calls
        // in the current context (contract).
        unsafe {
            let fd = libc::memfd_create(name.as_ptr(), libc::MFD_CLOEXEC);
            if fd < 0 {
                return None;
            }
            let ok = libc::ftruncate(fd, map_len as libc::off_t) == 0;
            let map = if ok {
                libc::mmap(
                    std::ptr::null_mut(),
                    map_len,
                    libc::PROT_READ | libc::PROT_WRITE,
                    libc::MAP_SHARED,
                    fd,
                    0,
                )
            } else {
                libc::MAP_FAILED
            };
            if map == libc::MAP_FAILED {
                libc::close(fd);
                return None;
            }
            let mut memory = PairMemory {
                objects: [0; 2],
                map: map.cast(),
                map_len,
                data_offset,
                layer_stride,
                stride,
            };
            // Each import reads the header as the file has it then: where
            // its data starts.
            for i in 0..imports.min(2) {
                let start = data_offset + i * layer_stride;
                let head = eye_memory::header(map_len, start, uuid);
                if libc::pwrite(fd, head.as_ptr().cast(), head.len(), 0) != head.len() as isize {
                    break;
                }
                // The driver closes the descriptor it is given.
                let given = libc::dup(fd);
                if given < 0 {
                    break;
                }
                (api.create)(1, &mut memory.objects[i]);
                (api.import_fd)(
                    memory.objects[i],
                    map_len as u64,
                    eye_memory::GL_HANDLE_TYPE_OPAQUE_FD_EXT,
                    given,
                );
            }
            libc::close(fd);
            // The header the first import's data needs before it again.
            let head = eye_memory::header(map_len, data_offset, uuid);
            std::ptr::copy_nonoverlapping(head.as_ptr(), memory.map, head.len());
            if memory.objects[..imports.min(2)].contains(&0) {
                memory.release(api);
                return None;
            }
            Some(memory)
        }
    }

    /// Gives `array` (2 layers) and the 2D textures `eyes` (left, right)
    /// `width` × `height` RGBA8 storage in one new file. None when the
    /// driver lacks glTexStorageMem3DEXT or refuses (the textures may then
    /// have storage of no use: the caller replaces them).
    unsafe fn create(
        gl: &Gl,
        api: &MemoryObjectApi,
        uuid: &[u8; 16],
        array: u32,
        eyes: [u32; 2],
        (width, height): (u32, u32),
    ) -> Option<PairMemory> {
        let storage_3d = api.tex_storage_mem_3d?;
        // SAFETY: contract.
        unsafe {
            let memory = PairMemory::imported(api, uuid, c"glstereo eyes", (width, height), 2, 4)?;
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, array);
            storage_3d(
                GL_TEXTURE_2D_ARRAY,
                1,
                GL_RGBA8,
                width as i32,
                height as i32,
                2,
                memory.objects[0],
                0,
            );
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
            for (i, &tex) in eyes.iter().enumerate() {
                gl.BindTexture(GL_TEXTURE_2D, tex);
                (api.tex_storage_mem_2d)(
                    GL_TEXTURE_2D,
                    1,
                    GL_RGBA8,
                    width as i32,
                    height as i32,
                    memory.objects[i],
                    0,
                );
            }
            gl.BindTexture(GL_TEXTURE_2D, 0);
            if gl.take_error() != GL_NO_ERROR {
                memory.release(api);
                return None;
            }
            Some(memory)
        }
    }

    /// Gives the depth array `array` (2 layers) `width` × `height`
    /// storage of `format` (GL_DEPTH24_STENCIL8, GL_DEPTH_COMPONENT24 or
    /// 32: one 32-bit word a pixel; GL_DEPTH_COMPONENT16: a 16-bit one) in
    /// one new file, imported once: the CPU reads the left eye's depth in
    /// place (`--auto=depth`). None where the driver refuses.
    unsafe fn create_depth(
        gl: &Gl,
        api: &MemoryObjectApi,
        uuid: &[u8; 16],
        array: u32,
        format: u32,
        (width, height): (u32, u32),
    ) -> Option<PairMemory> {
        let storage_3d = api.tex_storage_mem_3d?;
        // SAFETY: as in `create`.
        unsafe {
            let texel = if format == GL_DEPTH_COMPONENT16 { 2 } else { 4 };
            let memory =
                PairMemory::imported(api, uuid, c"glstereo depth", (width, height), 1, texel)?;
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, array);
            storage_3d(
                GL_TEXTURE_2D_ARRAY,
                1,
                format,
                width as i32,
                height as i32,
                2,
                memory.objects[0],
                0,
            );
            gl.TexParameteri(
                GL_TEXTURE_2D_ARRAY,
                GL_TEXTURE_MIN_FILTER,
                GL_NEAREST as i32,
            );
            gl.TexParameteri(
                GL_TEXTURE_2D_ARRAY,
                GL_TEXTURE_MAG_FILTER,
                GL_NEAREST as i32,
            );
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
            if gl.take_error() != GL_NO_ERROR {
                memory.release(api);
                return None;
            }
            Some(memory)
        }
    }

    /// Where the CPU reads layer `l` of this memory: `texture`'s pixels.
    fn pixels(&self, l: usize, texture: u32, (width, height): (u32, u32)) -> EyePixels {
        // SAFETY: the layer starts inside the mapping, which lives as long
        // as the textures (EyePixels' contract).
        unsafe {
            EyePixels::new(
                texture,
                self.map.add(self.data_offset + l * self.layer_stride),
                self.stride,
                width,
                height,
            )
        }
    }

    /// Writes where the driver finds the start of its view of the second
    /// import when it frees it: the word before that import's data, inside
    /// the first layer (whose contents are no longer needed: nothing may
    /// render into it afterwards).
    fn prepare_unmap(&self) {
        let start = self.data_offset + self.layer_stride;
        let word = std::mem::size_of::<usize>();
        // SAFETY: inside the mapping (the first layer's last bytes).
        unsafe {
            std::ptr::copy_nonoverlapping(
                start.to_ne_bytes().as_ptr(),
                self.map.add(start - word),
                word,
            )
        };
    }

    /// Unmaps the layer's own view of the memory, leaving the memory
    /// objects to the driver (their share group ends, or ended).
    fn unmap(self) {
        // SAFETY: the layer's own mapping, read by nothing after this.
        unsafe { libc::munmap(self.map.cast(), self.map_len) };
    }

    /// Deletes both memory objects and unmaps. The textures made from
    /// them must be deleted and nothing render into them any more.
    unsafe fn release(self, api: &MemoryObjectApi) {
        self.prepare_unmap();
        // SAFETY: contract.
        unsafe {
            for o in self.objects.iter().rev().filter(|&&o| o != 0) {
                (api.delete)(1, o);
            }
            libc::munmap(self.map.cast(), self.map_len);
        }
    }
}

/// The layered colour and depth/stencil of one emulated framebuffer, and
/// the 2D textures presentation reads (module docs).
#[derive(Debug)]
pub struct LayeredEyes {
    api: LayeredApi,
    /// The colour arrays by pair (0: the pair does not exist).
    colour: [u32; 2],
    /// The 2D texture of each slot (0: none).
    textures: [u32; 4],
    /// The depth (and stencil) array, 0 for a visual with neither.
    depth: u32,
    /// GL_DEPTH_STENCIL_ATTACHMENT or GL_DEPTH_ATTACHMENT.
    depth_attachment: u32,
    width: u32,
    height: u32,
    /// Each pair's memory, where its textures share it (else they are
    /// copied into at each present).
    memory: [Option<PairMemory>; 2],
    /// The depth array's memory, where the CPU reads it in place, and
    /// where its depth is in each word (its low 24 bits, else its high).
    depth_memory: Option<(PairMemory, DepthBits)>,
    memory_api: Option<MemoryObjectApi>,
}

/// The GL objects of [`LayeredEyes`] a draw attaches: copied out of the
/// context's state for the length of one call.
#[derive(Clone, Copy, Debug)]
pub struct Attachments {
    api: LayeredApi,
    /// The array at GL_COLOR_ATTACHMENT0 + i (0: none).
    colour: [u32; 8],
    depth: u32,
    /// GL_DEPTH_ATTACHMENT or GL_DEPTH_STENCIL_ATTACHMENT.
    depth_attachment: u32,
    /// A stencil array of its own, at GL_STENCIL_ATTACHMENT (0: none).
    stencil: u32,
    /// `depth` is a 2D texture (a copy of an eye's depth), not an array.
    depth_2d: bool,
    /// The depth array's layers are memory the CPU reads (the window's
    /// eyes on llvmpipe): what [`Attachments::attach_depth`] is for.
    depth_in_memory: bool,
}

impl LayeredEyes {
    /// Makes the arrays and textures of `pairs` (pair 1 only for a
    /// double-buffered framebuffer), `width` × `height` × 2, colour RGBA8
    /// (cleared to transparent black, or opaque black when `opaque`),
    /// depth in `depth_format` (GL_DEPTH24_STENCIL8, GL_DEPTH_COMPONENT24
    /// or 0 for none), in the context current (sharing the program's
    /// objects); `memory`: the memory-object API, to share the textures'
    /// storage (module docs); `fbo` a framebuffer object of the context
    /// for the clears.
    ///
    /// # Safety
    /// A context of `gl`'s backend must be current on this thread.
    pub unsafe fn allocate(
        gl: &Gl,
        api: LayeredApi,
        memory: Option<MemoryObjectApi>,
        (width, height): (u32, u32),
        (depth_format, opaque): (u32, bool),
        pairs: [bool; 2],
        fbo: u32,
    ) -> Result<LayeredEyes> {
        // SAFETY: contract; no data uploaded.
        unsafe {
            let mut eyes = LayeredEyes {
                api,
                colour: [0; 2],
                textures: [0; 4],
                depth: 0,
                depth_attachment: crate::stereo::emulated::depth_attachment_of(depth_format),
                width,
                height,
                memory: [None, None],
                depth_memory: None,
                memory_api: None,
            };
            // A side of one pixel (Qt's 1x1 surface for making contexts):
            // llvmpipe lays the array out otherwise than predicted
            // (measured: 1x1, 64x1, 1x64; 2x2 and larger as predicted), and
            // giving up would give up for every later window of the
            // process. Such eyes are read back; they are never shown.
            let uuid = memory
                .filter(|_| eye_memory::wanted() && width > 1 && height > 1)
                .and_then(|m| eye_memory::llvmpipe_identity(gl).map(|u| (m, u)));
            for p in (0..2).filter(|&p| pairs[p]) {
                eyes.colour[p] = gl.gen_texture_of(GL_TEXTURE_2D_ARRAY);
                eyes.textures[p] = gl.gen_texture();
                eyes.textures[p + 2] = gl.gen_texture();
                let shared = uuid.as_ref().and_then(|(m, u)| {
                    PairMemory::create(
                        gl,
                        m,
                        u,
                        eyes.colour[p],
                        [eyes.textures[p], eyes.textures[p + 2]],
                        (width, height),
                    )
                });
                match shared {
                    Some(s) => {
                        eyes.memory[p] = Some(s);
                        eyes.memory_api = memory;
                    }
                    None => {
                        if uuid.is_some() {
                            // Storage of no use may have been given: new names.
                            gl.take_error();
                            gl.delete_textures(&[
                                eyes.colour[p],
                                eyes.textures[p],
                                eyes.textures[p + 2],
                            ]);
                            eyes.colour[p] = gl.gen_texture_of(GL_TEXTURE_2D_ARRAY);
                            eyes.textures[p] = gl.gen_texture();
                            eyes.textures[p + 2] = gl.gen_texture();
                        }
                        eyes.plain_colour(gl, p);
                    }
                }
            }
            // Sampled and copied as single-level textures.
            for &tex in eyes.textures.iter().filter(|&&t| t != 0) {
                gl.BindTexture(GL_TEXTURE_2D, tex);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST as i32);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST as i32);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE as i32);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE as i32);
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
            }
            gl.BindTexture(GL_TEXTURE_2D, 0);
            if depth_format != 0 {
                eyes.depth = gl.gen_texture_of(GL_TEXTURE_2D_ARRAY);
                let shared = uuid.as_ref().filter(|_| eyes.memory[0].is_some());
                let memory = shared.and_then(|(m, u)| {
                    PairMemory::create_depth(gl, m, u, eyes.depth, depth_format, (width, height))
                });
                let found =
                    memory.and_then(|m| match eyes.verify_depth(gl, &m, fbo, depth_format) {
                        Some(bits) => Some((m, bits)),
                        None => {
                            m.release(uuid.as_ref().map(|(a, _)| a).expect("made with it"));
                            None
                        }
                    });
                match found {
                    Some(d) => eyes.depth_memory = Some(d),
                    None => {
                        if shared.is_some() {
                            gl.take_error();
                            gl.delete_textures(&[eyes.depth]);
                            eyes.depth = gl.gen_texture_of(GL_TEXTURE_2D_ARRAY);
                        }
                        let (format, ty) = if depth_format == GL_DEPTH24_STENCIL8 {
                            (GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8)
                        } else {
                            (GL_DEPTH_COMPONENT, GL_UNSIGNED_INT)
                        };
                        eyes.array_storage(gl, eyes.depth, depth_format, format, ty);
                    }
                }
            }
            if let Err(e) = gl.check("allocating the layered eyes") {
                eyes.release(gl);
                return Err(e);
            }
            // New storage is undefined: clear both layers of each pair.
            gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
            gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
            gl.Disable(GL_SCISSOR_TEST);
            gl.ColorMask(1, 1, 1, 1);
            gl.ClearColor(0.0, 0.0, 0.0, if opaque { 1.0 } else { 0.0 });
            let mut complete = true;
            for &array in eyes.colour.iter().filter(|&&a| a != 0) {
                (api.framebuffer_texture)(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, array, 0);
                complete &= gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
                if complete {
                    gl.Clear(GL_COLOR_BUFFER_BIT);
                }
            }
            (api.framebuffer_texture)(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0);
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            if !complete {
                eyes.release(gl);
                return Err(Error::Gl(
                    "the driver cannot render to a layered RGBA8 array texture".into(),
                ));
            }
            if eyes.memory.iter().any(Option::is_some) && !eyes.verify(gl, fbo) {
                eye_memory::give_up(
                    "the driver laid out the layered eyes otherwise than predicted",
                );
                eyes.release(gl);
                return Self::allocate(
                    gl,
                    api,
                    None,
                    (width, height),
                    (depth_format, opaque),
                    pairs,
                    fbo,
                );
            }
            Ok(eyes)
        }
    }

    /// Where depth memory of `format` holds its values: markers of depth
    /// cleared into a corner of each layer are found at the addresses
    /// predicted, in the low 24 bits of their words or in the high ones
    /// (a 16-bit format: in its words). None where they are not (the
    /// memory is then of no use).
    unsafe fn verify_depth(
        &self,
        gl: &Gl,
        m: &PairMemory,
        fbo: u32,
        format: u32,
    ) -> Option<DepthBits> {
        const GL_NONE: u32 = 0;
        let (w, h) = (self.width, self.height);
        let corners = [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)];
        let value = |i: usize| 0x10_2030 + 0x01_1111 * i as u32;
        let short = format == GL_DEPTH_COMPONENT16;
        let texel = if short { 2 } else { 4 };
        // A marker is found where it is within one step of the word's
        // precision: a 32-bit depth holds a 24-bit marker as its high 24
        // bits up to the rounding of the conversion.
        let near = |found: u32, want: u32| found.abs_diff(want) <= 1;
        let mut low = !short;
        let mut high = !short;
        let mut sixteen = short;
        // SAFETY: contract of the callers (the layer's own context);
        // reads stay inside the mapping.
        unsafe {
            gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
            gl.DrawBuffer(GL_NONE);
            gl.ReadBuffer(GL_NONE);
            gl.Enable(GL_SCISSOR_TEST);
            gl.DepthMask(1);
            for l in 0..2 {
                (self.api.framebuffer_texture_layer)(
                    GL_FRAMEBUFFER,
                    self.depth_attachment,
                    self.depth,
                    0,
                    l as i32,
                );
                if gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE {
                    low = false;
                    high = false;
                    sixteen = false;
                    break;
                }
                for (i, &(x, y)) in corners.iter().enumerate() {
                    let v = value(i + 4 * l);
                    gl.Scissor(x as i32, y as i32, 1, 1);
                    gl.ClearDepth(f64::from(v) / f64::from(DEPTH_MAX));
                    gl.Clear(GL_DEPTH_BUFFER_BIT);
                }
                gl.Finish();
                for (i, &(x, y)) in corners.iter().enumerate() {
                    let v = value(i + 4 * l);
                    let at = m.data_offset
                        + l * m.layer_stride
                        + y as usize * m.stride
                        + x as usize * texel;
                    let mut word = [0u8; 4];
                    std::ptr::copy_nonoverlapping(m.map.add(at), word.as_mut_ptr(), texel);
                    if short {
                        let word = u32::from(u16::from_ne_bytes([word[0], word[1]]));
                        sixteen &= near(word, (v + 0x80) >> 8);
                    } else {
                        let word = u32::from_ne_bytes(word);
                        low &= word & DEPTH_MAX == v;
                        high &= near(word >> 8, v);
                    }
                }
            }
            (self.api.framebuffer_texture_layer)(GL_FRAMEBUFFER, self.depth_attachment, 0, 0, 0);
            gl.Disable(GL_SCISSOR_TEST);
            gl.ClearDepth(1.0);
            gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
            gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            if gl.take_error() != GL_NO_ERROR {
                return None;
            }
        }
        match (low, high, sixteen) {
            (true, _, _) => Some(DepthBits::Low),
            (false, true, _) => Some(DepthBits::High),
            (_, _, true) => Some(DepthBits::Short),
            _ => None,
        }
    }

    /// The left eye's depth (layer 0 of the depth array) where the CPU
    /// reads it in place: rows bottom first, one word a pixel. Valid as
    /// [`EyePixels`] are, and read as they are: after the present's
    /// glFinish.
    pub fn left_depth(&self) -> Option<DepthRows> {
        self.depth_rows(0)
    }

    /// Layer 1 of the depth array, as [`LayeredEyes::left_depth`]. Under
    /// `--auto=depth` no eye is drawn there: it holds the depth of the
    /// frame's perspective draws made with the depth test off
    /// ([`Attachments::attach_depth`]).
    pub fn right_depth(&self) -> Option<DepthRows> {
        self.depth_rows(1)
    }

    fn depth_rows(&self, layer: usize) -> Option<DepthRows> {
        let (m, bits) = self.depth_memory.as_ref()?;
        Some(DepthRows {
            // SAFETY: both layers are inside the mapping (verify_depth
            // found each where predicted).
            first: unsafe { m.map.add(m.data_offset + layer * m.layer_stride) }.cast_const(),
            stride: m.stride,
            width: self.width as usize,
            height: self.height as usize,
            bits: *bits,
        })
    }

    /// Ordinary storage for pair `p`: its array and its 2D textures.
    unsafe fn plain_colour(&self, gl: &Gl, p: usize) {
        // SAFETY: contract of the callers.
        unsafe {
            self.array_storage(gl, self.colour[p], GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
            for tex in [self.textures[p], self.textures[p + 2]] {
                gl.BindTexture(GL_TEXTURE_2D, tex);
                gl.TexImage2D(
                    GL_TEXTURE_2D,
                    0,
                    GL_RGBA8 as i32,
                    self.width as i32,
                    self.height as i32,
                    0,
                    GL_RGBA,
                    GL_UNSIGNED_BYTE,
                    std::ptr::null(),
                );
            }
            gl.BindTexture(GL_TEXTURE_2D, 0);
        }
    }

    unsafe fn array_storage(&self, gl: &Gl, tex: u32, internal: u32, format: u32, ty: u32) {
        // SAFETY: contract of the callers; no data uploaded.
        unsafe {
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, tex);
            (self.api.tex_image_3d)(
                GL_TEXTURE_2D_ARRAY,
                0,
                internal as i32,
                self.width as i32,
                self.height as i32,
                2,
                0,
                format,
                ty,
                std::ptr::null(),
            );
            gl.TexParameteri(
                GL_TEXTURE_2D_ARRAY,
                GL_TEXTURE_MIN_FILTER,
                GL_NEAREST as i32,
            );
            gl.TexParameteri(
                GL_TEXTURE_2D_ARRAY,
                GL_TEXTURE_MAG_FILTER,
                GL_NEAREST as i32,
            );
            gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
        }
    }

    /// The eyes' width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// The eyes' height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The left eye's depth (layer 0 of the depth array) in `(x, y, w, h)`
    /// as window depths, rows bottom first, read through `fbo`
    /// ([`Attachments::read_left_depth`]). Into `out`; false without depth.
    ///
    /// # Safety
    /// As [`Attachments::read_left_depth`].
    pub unsafe fn read_left_depth(
        &self,
        gl: &Gl,
        fbo: u32,
        rect: (i32, i32, i32, i32),
        out: &mut Vec<f32>,
    ) -> bool {
        // SAFETY: contract.
        unsafe { self.attachments().read_left_depth(gl, fbo, rect, out) }
    }

    /// Whether the shared storage is where it is predicted: a marker
    /// cleared into each corner of each layer of each array is read back
    /// through the layer's 2D texture and found at its address.
    unsafe fn verify(&self, gl: &Gl, fbo: u32) -> bool {
        let (w, h) = (self.width, self.height);
        let corners = [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)];
        let mut ok = true;
        // SAFETY: contract of the callers; reads stay inside the mapping.
        unsafe {
            gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
            gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
            gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
            gl.Enable(GL_SCISSOR_TEST);
            gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
            gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
            for p in 0..2 {
                let Some(m) = &self.memory[p] else { continue };
                for l in 0..2 {
                    (self.api.framebuffer_texture_layer)(
                        GL_FRAMEBUFFER,
                        GL_COLOR_ATTACHMENT0,
                        self.colour[p],
                        0,
                        l as i32,
                    );
                    for (i, &(x, y)) in corners.iter().enumerate() {
                        let v = eye_memory::marker(i + 4 * l);
                        gl.Scissor(x as i32, y as i32, 1, 1);
                        gl.ClearColor(
                            f32::from(v[0]) / 255.0,
                            f32::from(v[1]) / 255.0,
                            f32::from(v[2]) / 255.0,
                            f32::from(v[3]) / 255.0,
                        );
                        gl.Clear(GL_COLOR_BUFFER_BIT);
                    }
                    gl.Finish();
                    gl.FramebufferTexture2D(
                        GL_FRAMEBUFFER,
                        GL_COLOR_ATTACHMENT0,
                        GL_TEXTURE_2D,
                        self.textures[p + 2 * l],
                        0,
                    );
                    for (i, &(x, y)) in corners.iter().enumerate() {
                        let v = eye_memory::marker(i + 4 * l);
                        let mut got = [0u8; 4];
                        gl.ReadPixels(
                            x as i32,
                            y as i32,
                            1,
                            1,
                            GL_RGBA,
                            GL_UNSIGNED_BYTE,
                            got.as_mut_ptr().cast(),
                        );
                        let at = m.data_offset
                            + l * m.layer_stride
                            + y as usize * m.stride
                            + x as usize * 4;
                        ok &= got == v && std::slice::from_raw_parts(m.map.add(at), 4) == v;
                    }
                    gl.FramebufferTexture2D(
                        GL_FRAMEBUFFER,
                        GL_COLOR_ATTACHMENT0,
                        GL_TEXTURE_2D,
                        0,
                        0,
                    );
                }
            }
            gl.Disable(GL_SCISSOR_TEST);
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            ok &= gl.take_error() == GL_NO_ERROR;
        }
        ok
    }

    /// Width and height of each eye.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The 2D texture presentation reads for slot `slot` (0: none).
    pub fn texture(&self, slot: usize) -> u32 {
        self.textures[slot]
    }

    /// Where the CPU reads slot `slot` in place (its pair's storage is
    /// shared), else None.
    pub fn pixels(&self, slot: usize) -> Option<EyePixels> {
        let m = self.memory[pair(slot)].as_ref()?;
        Some(m.pixels(slot / 2, self.textures[slot], (self.width, self.height)))
    }

    /// What a draw attaches.
    pub fn attachments(&self) -> Attachments {
        self.attachments_in([0, 1])
    }

    /// [`Self::attachments`] with pair `order[i]` at GL_COLOR_ATTACHMENT0 + i.
    pub fn attachments_in(&self, order: [usize; 2]) -> Attachments {
        let mut colour = [0; 8];
        colour[0] = self.colour[order[0]];
        colour[1] = self.colour[order[1]];
        Attachments {
            api: self.api,
            colour,
            depth: self.depth,
            depth_attachment: self.depth_attachment,
            stencil: 0,
            depth_2d: false,
            depth_in_memory: self.depth_memory.is_some(),
        }
    }

    /// Copies pair `p`'s layers into its 2D textures, where they do not
    /// share storage: what the present shows.
    ///
    /// # Safety
    /// A context sharing the textures must be current.
    pub unsafe fn resolve(&self, p: usize) {
        if self.memory[p].is_some() || self.colour[p] == 0 {
            return;
        }
        for l in 0..2 {
            // SAFETY: contract; both are width × height.
            unsafe {
                (self.api.copy_image_sub_data)(
                    self.colour[p],
                    GL_TEXTURE_2D_ARRAY,
                    0,
                    0,
                    0,
                    l as i32,
                    self.textures[p + 2 * l],
                    GL_TEXTURE_2D,
                    0,
                    0,
                    0,
                    0,
                    self.width as i32,
                    self.height as i32,
                    1,
                )
            }
        }
    }

    /// Attaches the left eye's depth to the framebuffer bound at `target`
    /// (`on` false: detaches it), for reading it back; false when there is
    /// no depth.
    ///
    /// # Safety
    /// A context sharing the arrays must be current.
    pub unsafe fn attach_left_depth(&self, target: u32, on: bool) -> bool {
        if self.depth == 0 {
            return false;
        }
        // SAFETY: contract.
        unsafe {
            (self.api.framebuffer_texture_layer)(
                target,
                self.depth_attachment,
                if on { self.depth } else { 0 },
                0,
                0,
            )
        };
        true
    }

    /// Readies the shared memory to be freed by the driver with the share
    /// group (the module docs): nothing may render into
    /// these eyes afterwards.
    pub fn prepare_unmap(&self) {
        for m in self.memory.iter().flatten() {
            m.prepare_unmap();
        }
    }

    /// After the contexts that drew into and composed these eyes are gone
    /// (the driver frees the memory objects with the share group,
    /// [`Self::prepare_unmap`]): unmaps the layer's own view of the memory,
    /// which nothing reads any more. Without this each destroyed context
    /// kept its eyes' memory mapped (2 memfd mappings, ~5 MB at 640x480).
    pub fn unmap(&mut self) {
        for m in self.memory.iter_mut().filter_map(Option::take) {
            m.unmap();
        }
        if let Some((m, _)) = self.depth_memory.take() {
            m.unmap();
        }
    }

    /// Deletes the arrays and textures, and frees shared memory (nothing
    /// may render into it any more: the caller finished the contexts that
    /// did).
    ///
    /// # Safety
    /// A context sharing them must be current.
    pub unsafe fn release(&mut self, gl: &Gl) {
        // SAFETY: contract; names made here.
        unsafe {
            let names: Vec<u32> = self
                .colour
                .iter()
                .chain(&self.textures)
                .chain(std::iter::once(&self.depth))
                .copied()
                .filter(|&n| n != 0)
                .collect();
            gl.delete_textures(&names);
            if self.memory.iter().any(Option::is_some) {
                gl.Finish();
            }
            for m in self.memory.iter_mut().filter_map(Option::take) {
                m.release(&self.memory_api.expect("memory came from this API"));
            }
            if let Some((m, _)) = self.depth_memory.take() {
                m.release(&self.memory_api.expect("memory came from this API"));
            }
        }
        self.colour = [0; 2];
        self.textures = [0; 4];
        self.depth = 0;
    }
}

impl Attachments {
    /// The attachments of a program's framebuffer object given eyes by
    /// the layer ([`crate::auto::render_targets`]): colour arrays by
    /// attachment index (0: none), the depth array (0: none) and its
    /// attachment point, a stencil array of its own (0: none), with the
    /// API of the context's own eyes.
    pub fn of_target(
        &self,
        colour: [u32; 8],
        (depth, depth_attachment): (u32, u32),
        stencil: u32,
    ) -> Attachments {
        Attachments {
            api: self.api,
            colour,
            depth,
            depth_attachment,
            stencil,
            depth_2d: false,
            depth_in_memory: false,
        }
    }

    /// These attachments with their depth array's left eye replaced by
    /// `copy`, a 2D texture holding it (what automatic convergence
    /// measures when a later draw overwrote the depth: [`Self::depth`]).
    pub fn with_depth_copy(&self, copy: u32) -> Attachments {
        Attachments {
            colour: [0; 8],
            stencil: 0,
            depth: copy,
            depth_2d: true,
            ..*self
        }
    }

    /// The depth array (0: none).
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// The left eye's depth (layer 0 of the depth array: the window's eyes or a
    /// stereoized render target) in `(x, y, w, h)`
    /// as window depths, rows bottom first, read through `fbo`, a
    /// framebuffer object of the current context (its depth attachment
    /// is left empty and GL_READ_FRAMEBUFFER at 0). Into `out`; false without depth.
    ///
    /// # Safety
    /// A context sharing the arrays is current; the rectangle is inside
    /// the eyes; the context's pixel-pack state is the layer's own.
    pub unsafe fn read_left_depth(
        &self,
        gl: &Gl,
        fbo: u32,
        (x, y, w, h): (i32, i32, i32, i32),
        out: &mut Vec<f32>,
    ) -> bool {
        if self.depth == 0 || w <= 0 || h <= 0 {
            return false;
        }
        // The buffer keeps its capacity from one measurement to the next.
        out.clear();
        out.resize(w as usize * h as usize, 0.0);
        let attach = || {
            // SAFETY: contract (the framebuffer bound for reading).
            unsafe {
                if self.depth_2d {
                    (self.api.framebuffer_texture)(
                        GL_READ_FRAMEBUFFER,
                        self.depth_attachment,
                        self.depth,
                        0,
                    );
                } else {
                    (self.api.framebuffer_texture_layer)(
                        GL_READ_FRAMEBUFFER,
                        self.depth_attachment,
                        self.depth,
                        0,
                        0,
                    );
                }
            }
        };
        let read = (GL_DEPTH_COMPONENT, GL_FLOAT, out.as_mut_ptr().cast());
        // SAFETY: contract; `out` holds w × h floats at alignment 4.
        unsafe { self.read_attached(gl, (fbo, self.depth_attachment), attach, (x, y, w, h), read) };
        true
    }

    /// Reads `(x, y, w, h)` of what `attach` attaches at `attachment` of
    /// `fbo` (bound for reading when it is called) as `format` and `kind`
    /// into `out`, then leaves the attachment empty and
    /// GL_READ_FRAMEBUFFER at 0.
    ///
    /// # Safety
    /// As [`Self::read_left_depth`]; `out` holds the rectangle's pixels.
    unsafe fn read_attached(
        &self,
        gl: &Gl,
        (fbo, attachment): (u32, u32),
        attach: impl FnOnce(),
        (x, y, w, h): (i32, i32, i32, i32),
        (format, kind, out): (u32, u32, *mut std::ffi::c_void),
    ) {
        // SAFETY: contract.
        unsafe {
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
            attach();
            gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
            gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
            gl.ReadPixels(x, y, w, h, format, kind, out);
            (self.api.framebuffer_texture_layer)(GL_READ_FRAMEBUFFER, attachment, 0, 0, 0);
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        }
    }

    /// Layer `layer` of the colour array `array` (a render target's, of
    /// this share group) as RGBA8 words, `w` × `h` from its corner, rows
    /// bottom first, read through `fbo` as [`Self::read_left_depth`]
    /// reads (its colour attachment 0 is left empty). Into `out`.
    ///
    /// # Safety
    /// As [`Self::read_left_depth`]; the array is at least `w` × `h` and
    /// has the layer.
    pub unsafe fn read_colour_layer(
        &self,
        gl: &Gl,
        fbo: u32,
        (array, layer): (u32, i32),
        (w, h): (i32, i32),
        out: &mut Vec<u32>,
    ) {
        out.clear();
        out.resize(w.max(0) as usize * h.max(0) as usize, 0);
        if array == 0 || w <= 0 || h <= 0 {
            return;
        }
        let attach = || {
            // SAFETY: contract (the framebuffer bound for reading).
            unsafe {
                (self.api.framebuffer_texture_layer)(
                    GL_READ_FRAMEBUFFER,
                    GL_COLOR_ATTACHMENT0,
                    array,
                    0,
                    layer,
                );
                gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
            }
        };
        let read = (GL_RGBA, GL_UNSIGNED_BYTE, out.as_mut_ptr().cast());
        // SAFETY: contract; `out` holds w × h words.
        unsafe { self.read_attached(gl, (fbo, GL_COLOR_ATTACHMENT0), attach, (0, 0, w, h), read) };
    }

    /// Whether there is a depth array (what automatic convergence reads).
    pub fn has_depth(&self) -> bool {
        self.depth != 0
    }

    /// Where the depth array is attached: GL_DEPTH_ATTACHMENT or
    /// GL_DEPTH_STENCIL_ATTACHMENT.
    pub fn depth_point(&self) -> u32 {
        self.depth_attachment
    }

    /// Attaches layer `layer` of the depth array alone to `target`'s
    /// framebuffer at its depth attachment point (colour and stencil
    /// stay as they are); false where there is no depth array, or where
    /// its second layer would be of no use (`layer` 1 of an array the CPU
    /// does not read in place: its frames are made from the depth read
    /// back, which has only the first).
    ///
    /// # Safety
    /// A context sharing the arrays is current; `target`'s framebuffer
    /// is the one these attachments were made for.
    pub unsafe fn attach_depth(&self, target: u32, layer: i32) -> bool {
        if self.depth == 0 || self.depth_2d || (layer == 1 && !self.depth_in_memory) {
            return false;
        }
        // SAFETY: contract.
        unsafe {
            (self.api.framebuffer_texture_layer)(
                target,
                self.depth_attachment,
                self.depth,
                0,
                layer,
            )
        };
        true
    }

    /// The first pair's colour array (the eyes' size is its size).
    pub fn colour(&self) -> u32 {
        self.colour[0]
    }

    /// The colour array at GL_COLOR_ATTACHMENT0 + `i` (0: none).
    pub fn colour_at(&self, i: usize) -> u32 {
        self.colour.get(i).copied().unwrap_or(0)
    }

    /// Attaches every array, every layer (the window's pair `p` at
    /// GL_COLOR_ATTACHMENT0 + p, a render target's at its points), and
    /// the depth and stencil arrays, to the framebuffer object bound at
    /// `target`; with `eye`, that eye's layers only (the slow path: draws
    /// whose vertices cannot choose a layer; blits eye by eye).
    ///
    /// # Safety
    /// A context sharing the arrays must be current with the object bound.
    pub unsafe fn attach(&self, target: u32, eye: Option<Eye>) {
        let one = |attachment: u32, tex: u32| {
            // SAFETY: contract.
            unsafe {
                match eye {
                    None => (self.api.framebuffer_texture)(target, attachment, tex, 0),
                    Some(e) => {
                        (self.api.framebuffer_texture_layer)(target, attachment, tex, 0, layer(e))
                    }
                }
            }
        };
        for (p, &tex) in self.colour.iter().enumerate() {
            if tex != 0 {
                one(GL_COLOR_ATTACHMENT0 + p as u32, tex);
            }
        }
        if self.depth != 0 {
            one(self.depth_attachment, self.depth);
        }
        if self.stencil != 0 {
            one(GL_STENCIL_ATTACHMENT, self.stencil);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(words: &[u32], width: usize, bits: DepthBits) -> DepthRows {
        DepthRows {
            first: words.as_ptr().cast(),
            stride: (width + 1) * 4,
            width,
            height: words.len() / (width + 1),
            bits,
        }
    }

    /// Both layouts of a depth word read as their 24-bit depth, and the
    /// second layer merged in keeps the nearer of the two at each pixel,
    /// the padding past a row's width never read.
    #[test]
    fn a_row_of_depth_words_reads_as_depths_and_merges_the_nearer() {
        let d = |v: u32| v as f32 / DEPTH_MAX as f32;
        let (near, mid, far) = (0x10_0000, 0x80_0000, DEPTH_MAX);
        for bits in [DepthBits::Low, DepthBits::High] {
            let word = |depth: u32, other: u32| match bits {
                DepthBits::Low => depth | other << 24,
                _ => depth << 8 | other,
            };
            // Two rows of three, and one word of padding each.
            let first = [
                word(mid, 0xAB),
                word(far, 1),
                word(near, 0xFF),
                0xDEAD,
                word(0, 7),
                word(mid, 0),
                word(far, 0x55),
                0xBEEF,
            ];
            let second = [
                word(near, 3),
                word(mid, 0),
                word(far, 0x80),
                0,
                word(far, 0),
                word(far, 0),
                word(mid, 9),
                0,
            ];
            let (a, b) = (rows(&first, 3, bits), rows(&second, 3, bits));
            let mut out = [0.0f32; 3];
            for (y, want, merged) in [
                (0, [d(mid), d(far), d(near)], [d(near), d(mid), d(near)]),
                (1, [0.0, d(mid), d(far)], [0.0, d(mid), d(mid)]),
            ] {
                // SAFETY: the words outlive the reads; y < height.
                unsafe { a.read_row(y, &mut out) };
                assert_eq!(out, want, "{bits:?} row {y}");
                // SAFETY: as above.
                unsafe { b.nearer_row(y, &mut out) };
                assert_eq!(out, merged, "{bits:?} row {y} merged");
            }
        }
    }
    /// 16-bit depth words (a 16-bit visual's buffer) read as their
    /// depth, rows a stride of bytes apart, and merge as 32-bit ones do.
    #[test]
    fn a_row_of_sixteen_bit_depths_reads_and_merges_the_nearer() {
        let d = |v: u16| f32::from(v) / 65535.0;
        // Two rows of three, one padding word each, in words of 4 bytes
        // so that the rows start aligned as the mapping's do.
        let words = |h: [u16; 8]| {
            let mut w = [0u32; 4];
            // SAFETY: 16 bytes either way, u16's alignment below u32's.
            unsafe { std::slice::from_raw_parts_mut(w.as_mut_ptr().cast::<u16>(), 8) }
                .copy_from_slice(&h);
            w
        };
        let first = words([0x8000, 0xFFFF, 0x1000, 0xDEAD, 0, 0x8000, 0xFFFF, 0xBEEF]);
        let second = words([0x1000, 0x8000, 0xFFFF, 0, 0xFFFF, 0xFFFF, 0x7FFF, 0]);
        let rows = |words: &[u32]| DepthRows {
            first: words.as_ptr().cast(),
            stride: 8,
            width: 3,
            height: 2,
            bits: DepthBits::Short,
        };
        let (a, b) = (rows(&first), rows(&second));
        let mut out = [0.0f32; 3];
        for (y, want, merged) in [
            (
                0,
                [d(0x8000), 1.0, d(0x1000)],
                [d(0x1000), d(0x8000), d(0x1000)],
            ),
            (1, [0.0, d(0x8000), 1.0], [0.0, d(0x8000), d(0x7FFF)]),
        ] {
            // SAFETY: the words outlive the reads; y < height.
            unsafe { a.read_row(y, &mut out) };
            assert_eq!(out, want, "row {y}");
            // SAFETY: as above.
            unsafe { b.nearer_row(y, &mut out) };
            assert_eq!(out, merged, "row {y} merged");
        }
    }
    /// The depth rows at every vector level the processor has (as the
    /// present runs them, inside `with_simd`) give the scalar reference's
    /// floats bit for bit: rows 1 to 300 words wide and some up to 8192,
    /// rows padded apart by any number of words, words of every value,
    /// every kind of word, merged into rows holding anything (NaN too).
    #[test]
    fn depth_rows_at_every_vector_level_are_the_scalar_references() {
        use crate::output::kernels::{Simd, with_simd};
        let mut rng = crate::output::fits::Rng(0x5EED_DE97);
        // One word at a time, by the formula of each kind.
        let reference = |bits: DepthBits, word: u32| -> f32 {
            let scale = 1.0 / DEPTH_MAX as f32;
            match bits {
                DepthBits::Low => (word & DEPTH_MAX) as i32 as f32 * scale,
                DepthBits::High => (word >> 8) as i32 as f32 * scale,
                DepthBits::Short => f32::from(word as u16) * (1.0 / f32::from(u16::MAX)),
            }
        };
        let widths = (1..=300).chain([511, 1024, 1920, 4099, 8192]);
        for width in widths {
            for bits in [DepthBits::Low, DepthBits::High, DepthBits::Short] {
                let bytes: usize = if bits == DepthBits::Short { 2 } else { 4 };
                let pad = (rng.next() % 3) as usize;
                let stride_words = (width * bytes).div_ceil(4) + pad;
                let height = 2;
                let words: Vec<u32> = (0..stride_words * height)
                    .map(|_| match rng.next() % 5 {
                        0 => 0,
                        1 => u32::MAX,
                        _ => rng.next() as u32,
                    })
                    .collect();
                let rows = DepthRows {
                    first: words.as_ptr().cast(),
                    stride: stride_words * 4,
                    width,
                    height,
                    bits,
                };
                let start: Vec<f32> = (0..width)
                    .map(|_| match rng.next() % 6 {
                        0 => f32::NAN,
                        1 => f32::INFINITY,
                        2 => -0.0,
                        _ => (rng.next() >> 40) as f32 / (1u64 << 24) as f32,
                    })
                    .collect();
                for y in 0..height {
                    let word = |x: usize| -> u32 {
                        // SAFETY: inside `words` (x < width, row y).
                        unsafe {
                            let at = rows.first.add(y * rows.stride + x * bytes);
                            if bytes == 2 {
                                u32::from(at.cast::<u16>().read())
                            } else {
                                at.cast::<u32>().read()
                            }
                        }
                    };
                    let read: Vec<u32> = (0..width)
                        .map(|x| reference(bits, word(x)).to_bits())
                        .collect();
                    let merged: Vec<u32> = (0..width)
                        .map(|x| start[x].min(reference(bits, word(x))).to_bits())
                        .collect();
                    for level in Simd::ALL.into_iter().filter(|&s| s <= Simd::detected()) {
                        let mut out = vec![7.0f32; width];
                        // SAFETY: the words outlive the reads; y < height.
                        with_simd(
                            level,
                            #[inline(always)]
                            |_| unsafe { rows.read_row(y, &mut out) },
                        );
                        let got: Vec<u32> = out.iter().map(|v| v.to_bits()).collect();
                        assert_eq!(got, read, "{bits:?} width {width} row {y} at {level:?}");
                        let mut out = start.clone();
                        // SAFETY: as above.
                        with_simd(
                            level,
                            #[inline(always)]
                            |_| unsafe { rows.nearer_row(y, &mut out) },
                        );
                        let got: Vec<u32> = out.iter().map(|v| v.to_bits()).collect();
                        assert_eq!(
                            got, merged,
                            "{bits:?} width {width} row {y} merged at {level:?}"
                        );
                    }
                }
            }
        }
    }
}

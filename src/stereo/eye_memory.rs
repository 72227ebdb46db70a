//! Eye buffers the CPU reads where the renderer wrote them.
//!
//! On a software renderer a presented stereo frame used to read both eyes
//! back with glReadPixels before composing them into the window's image:
//! at 1280x1024 on llvmpipe that is 0.6–0.75 ms of memory copies per
//! frame, and 10 MB more through the caches (BENCHMARKS.md, "Breakdown of
//! a stereo frame"). llvmpipe stores a colour texture as plain rows in
//! memory, and with GL_EXT_memory_object_fd it takes that memory from a
//! file descriptor. So the eye textures can be made from a memfd that the
//! layer maps as well: once the program's rendering is finished (the
//! glFinish every present already makes), the composite reads the eyes
//! where llvmpipe wrote them, and nothing is read back.
//!
//! llvmpipe imports only memory it recognises: the file starts with a
//! header (the sizes, then the first 16 bytes of the SHA-1 of its driver
//! identity, `"llvmpipe"` followed by the build's git revision, which
//! Mesa also appends to GL_VERSION). The header is written here the way
//! Mesa's `os_import_memory_fd` reads it. Everything is checked before it
//! is used: the renderer is llvmpipe and lists the extension, the import
//! gives a complete framebuffer, and markers cleared into the corners of
//! each texture by GL are found at the addresses the layout predicts.
//! Anything else (another driver, another Mesa layout, a refused import)
//! and the texture is an ordinary one read back as before; after one
//! failed check no more are tried in the process.
//! `GLSTEREO_EYE_MEMORY=0` turns the in-place reads off (for comparing).
//!
//! The library's own surfaces (`src/surface.rs`) make their eyes this way
//! too: a window composes from them, and captures and read-backs copy them
//! once (rows flipped on the way) instead of glReadPixels — when the
//! program's context is current on the calling thread (so it is finished
//! there first); otherwise they are read back by GL, which synchronises.

use std::ffi::{CStr, c_void};
use std::sync::atomic::{AtomicBool, Ordering};

use crate::gl::Gl;
use crate::gl::enums::*;

/// GL_HANDLE_TYPE_OPAQUE_FD_EXT (GL_EXT_memory_object_fd).
pub(crate) const GL_HANDLE_TYPE_OPAQUE_FD_EXT: u32 = 0x9586;

/// GL_EXT_memory_object's entry points, loaded where the driver has them.
#[derive(Clone, Copy, Debug)]
pub struct MemoryObjectApi {
    pub(crate) create: unsafe extern "system" fn(i32, *mut u32),
    pub(crate) delete: unsafe extern "system" fn(i32, *const u32),
    pub(crate) import_fd: unsafe extern "system" fn(u32, u64, u32, i32),
    pub(crate) tex_storage_mem_2d: unsafe extern "system" fn(u32, i32, u32, i32, i32, u32, u64),
    /// glTexStorageMem3DEXT (automatic stereo's layered eyes,
    /// [`crate::auto::eyes`]), where the driver has it.
    pub(crate) tex_storage_mem_3d:
        Option<unsafe extern "system" fn(u32, i32, u32, i32, i32, i32, u32, u64)>,
}

impl MemoryObjectApi {
    /// Loads the four functions through `get`; None if any is missing.
    ///
    /// # Safety
    /// `get` must return the named GL function's address (with the
    /// Khronos signature) or NULL.
    pub unsafe fn load(mut get: impl FnMut(&CStr) -> *const c_void) -> Option<MemoryObjectApi> {
        let mut f = |name: &CStr| {
            let p = get(name);
            (!p.is_null()).then_some(p)
        };
        let create = f(c"glCreateMemoryObjectsEXT")?;
        let delete = f(c"glDeleteMemoryObjectsEXT")?;
        let import_fd = f(c"glImportMemoryFdEXT")?;
        let storage = f(c"glTexStorageMem2DEXT")?;
        let storage_3d = f(c"glTexStorageMem3DEXT");
        // SAFETY: each address is the named function's, whose Khronos
        // signature the field's type spells.
        unsafe {
            Some(MemoryObjectApi {
                create: std::mem::transmute::<
                    *const c_void,
                    unsafe extern "system" fn(i32, *mut u32),
                >(create),
                delete: std::mem::transmute::<
                    *const c_void,
                    unsafe extern "system" fn(i32, *const u32),
                >(delete),
                import_fd: std::mem::transmute::<
                    *const c_void,
                    unsafe extern "system" fn(u32, u64, u32, i32),
                >(import_fd),
                tex_storage_mem_2d: std::mem::transmute::<
                    *const c_void,
                    unsafe extern "system" fn(u32, i32, u32, i32, i32, u32, u64),
                >(storage),
                tex_storage_mem_3d: storage_3d.map(|p| {
                    std::mem::transmute::<
                        *const c_void,
                        unsafe extern "system" fn(u32, i32, u32, i32, i32, i32, u32, u64),
                    >(p)
                }),
            })
        }
    }
}

/// Set after a failed check: no more tries in this process.
static GIVEN_UP: AtomicBool = AtomicBool::new(false);

/// Whether in-place eye memory may be tried: not given up after a failed
/// check, and not turned off with `GLSTEREO_EYE_MEMORY=0`.
pub fn wanted() -> bool {
    !GIVEN_UP.load(Ordering::Relaxed)
        && std::env::var_os("GLSTEREO_EYE_MEMORY").is_none_or(|v| v != "0")
}

/// Stops trying for the rest of the process, saying why once.
pub fn give_up(why: &str) {
    if !GIVEN_UP.swap(true, Ordering::Relaxed) {
        crate::interpose::warn(&format!(
            "eye textures are read back instead of in place ({why})"
        ));
    }
}

/// The first `offset` bytes of a file llvmpipe imports, as Mesa's own
/// allocator (`os_malloc_aligned_fd`) lays them out: at the start its
/// `struct memory_header` (native `size_t`s: the file's size, where the
/// data starts, the identity's hash), which the import reads; and the
/// offset again in the `size_t` just before the data, where the driver
/// finds the header to unmap its view when the memory object goes
/// (without it, it would unmap a length read from the pixels).
pub(crate) fn header(total: usize, offset: usize, uuid: &[u8; 16]) -> Vec<u8> {
    let word = size_of::<usize>();
    assert!(offset >= 2 * word + 16 + word, "room for the header");
    let mut h = vec![0; offset];
    h[..word].copy_from_slice(&total.to_ne_bytes());
    h[word..2 * word].copy_from_slice(&offset.to_ne_bytes());
    h[2 * word..2 * word + 16].copy_from_slice(uuid);
    h[offset - word..].copy_from_slice(&offset.to_ne_bytes());
    h
}

/// llvmpipe's driver identity for the context current on this thread, as
/// the hash its memory import compares: Some when the renderer is
/// llvmpipe with GL_EXT_memory_object_fd (compatibility-profile
/// extension string) and GL_VERSION is Mesa's.
///
/// # Safety
/// A context of `gl`'s backend must be current.
pub unsafe fn llvmpipe_identity(gl: &Gl) -> Option<[u8; 16]> {
    // SAFETY: contract.
    let (renderer, version, extensions) = unsafe {
        (
            gl.string(GL_RENDERER),
            gl.string(GL_VERSION),
            gl.string(GL_EXTENSIONS),
        )
    };
    // SAFETY: contract (GL_EXTENSIONS is an error in a core profile).
    unsafe { gl.take_error() };
    if !renderer.starts_with("llvmpipe")
        || !extensions
            .split_ascii_whitespace()
            .any(|e| e == "GL_EXT_memory_object_fd")
    {
        return None;
    }
    let id = driver_id(&version)?;
    let digest = sha1(id.as_bytes());
    let mut uuid = [0; 16];
    uuid.copy_from_slice(&digest[..16]);
    Some(uuid)
}

/// `"llvmpipe"` and what Mesa appends to its version in GL_VERSION (its
/// git revision, `" (git-1a2b3c4d)"`, or nothing in a release build):
/// "4.5 (Compatibility Profile) Mesa 22.3.6" gives "llvmpipe".
fn driver_id(gl_version: &str) -> Option<String> {
    let after = &gl_version[gl_version.find("Mesa ")? + 5..];
    let suffix = after.find(' ').map_or("", |i| &after[i..]);
    Some(format!("llvmpipe{suffix}"))
}

/// SHA-1 (FIPS 180-4) of `data`.
fn sha1(data: &[u8]) -> [u8; 20] {
    let mut h: [u32; 5] = [
        0x6745_2301,
        0xEFCD_AB89,
        0x98BA_DCFE,
        0x1032_5476,
        0xC3D2_E1F0,
    ];
    let mut msg = data.to_vec();
    msg.push(0x80);
    while msg.len() % 64 != 56 {
        msg.push(0);
    }
    msg.extend_from_slice(&((data.len() as u64) * 8).to_be_bytes());
    for block in msg.chunks_exact(64) {
        let mut w = [0u32; 80];
        for (i, word) in block.chunks_exact(4).enumerate() {
            w[i] = u32::from_be_bytes([word[0], word[1], word[2], word[3]]);
        }
        for i in 16..80 {
            w[i] = (w[i - 3] ^ w[i - 8] ^ w[i - 14] ^ w[i - 16]).rotate_left(1);
        }
        let [mut a, mut b, mut c, mut d, mut e] = h;
        for (i, &wi) in w.iter().enumerate() {
            let (f, k) = match i {
                0..=19 => ((b & c) | (!b & d), 0x5A82_7999),
                20..=39 => (b ^ c ^ d, 0x6ED9_EBA1),
                40..=59 => ((b & c) | (b & d) | (c & d), 0x8F1B_BCDC),
                _ => (b ^ c ^ d, 0xCA62_C1D6),
            };
            let t = a
                .rotate_left(5)
                .wrapping_add(f)
                .wrapping_add(e)
                .wrapping_add(k)
                .wrapping_add(wi);
            (e, d, c, b, a) = (d, c, b.rotate_left(30), a, t);
        }
        for (x, y) in h.iter_mut().zip([a, b, c, d, e]) {
            *x = x.wrapping_add(y);
        }
    }
    let mut out = [0; 20];
    for (i, x) in h.iter().enumerate() {
        out[i * 4..i * 4 + 4].copy_from_slice(&x.to_be_bytes());
    }
    out
}

/// llvmpipe's row stride for an RGBA8 texture `width` texels wide: the
/// width rounded up to 4 texels, in bytes rounded up to a 64-byte cache
/// line. Checked against the texture's real layout before use.
pub(crate) fn predicted_stride(width: u32) -> usize {
    (width as usize).div_ceil(4) * 4 * 4
}

/// Rounds `n` up to a multiple of 64.
pub(crate) fn cache_lines(n: usize) -> usize {
    n.div_ceil(64) * 64
}

/// A colour texture whose storage is a memfd that this process maps too.
/// Its rows are bottom first (GL's order), `stride` bytes apart, RGBA8.
#[derive(Debug)]
pub struct TextureMemory {
    memory_object: u32,
    map: *mut u8,
    map_len: usize,
    data_offset: usize,
    stride: usize,
    width: u32,
    height: u32,
}

// SAFETY: the mapping is plain shared memory; which thread reads it is
// governed by the GL synchronisation of its users (see EyePixels).
unsafe impl Send for TextureMemory {}

impl TextureMemory {
    /// Gives `texture` (a name with no storage yet) `width` × `height`
    /// RGBA8 storage in a new memfd mapped here. None when the file, the
    /// mapping or the import fails (the texture may then have been given
    /// storage of no use: the caller replaces it).
    ///
    /// # Safety
    /// A context of `gl`'s backend, whose driver `uuid` identifies, must be
    /// current; `api` is its memory-object API.
    pub unsafe fn create(
        gl: &Gl,
        api: &MemoryObjectApi,
        uuid: &[u8; 16],
        texture: u32,
        width: u32,
        height: u32,
    ) -> Option<TextureMemory> {
        let stride = cache_lines(predicted_stride(width));
        let rows = (height as usize).div_ceil(4) * 4;
        // A page for the header, the rows, and a page of slack.
        let page = 4096;
        let data_offset = page;
        let map_len = data_offset + stride.checked_mul(rows)? + page;
        // SAFETY: plain libc calls on a file this function owns.
        unsafe {
            let fd = libc::memfd_create(c"glstereo eye".as_ptr(), libc::MFD_CLOEXEC);
            if fd < 0 {
                return None;
            }
            let head = header(map_len, data_offset, uuid);
            let ok = libc::ftruncate(fd, map_len as libc::off_t) == 0
                && libc::pwrite(fd, head.as_ptr().cast(), head.len(), 0) == head.len() as isize;
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
            // The driver closes the descriptor it is given.
            let given = if map == libc::MAP_FAILED {
                -1
            } else {
                libc::dup(fd)
            };
            libc::close(fd);
            if given < 0 {
                if map != libc::MAP_FAILED {
                    libc::munmap(map, map_len);
                }
                return None;
            }
            let mut memory_object = 0;
            (api.create)(1, &mut memory_object);
            (api.import_fd)(
                memory_object,
                map_len as u64,
                GL_HANDLE_TYPE_OPAQUE_FD_EXT,
                given,
            );
            gl.BindTexture(GL_TEXTURE_2D, texture);
            (api.tex_storage_mem_2d)(
                GL_TEXTURE_2D,
                1,
                GL_RGBA8,
                width as i32,
                height as i32,
                memory_object,
                0,
            );
            gl.BindTexture(GL_TEXTURE_2D, 0);
            let memory = TextureMemory {
                memory_object,
                map: map.cast(),
                map_len,
                data_offset,
                stride,
                width,
                height,
            };
            if gl.take_error() != GL_NO_ERROR {
                memory.release_now(api);
                return None;
            }
            Some(memory)
        }
    }

    /// Whether GL writes `texture` (this memory's) where the layout says:
    /// the texture is a complete colour attachment, and markers cleared
    /// into its four corners are found at the predicted addresses. Leaves
    /// the texture's contents undefined, the framebuffer `fbo` without
    /// attachment, GL_FRAMEBUFFER at 0, the scissor test off and the
    /// colour mask all on.
    ///
    /// # Safety
    /// The context the texture was made in must be current; `fbo` is a
    /// framebuffer object of it.
    pub unsafe fn verify(&self, gl: &Gl, texture: u32, fbo: u32) -> bool {
        let (w, h) = (self.width, self.height);
        let mut corners = vec![(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)];
        // One marker per pixel (a window one texel wide or high).
        corners.sort_unstable();
        corners.dedup();
        // SAFETY: contract; reads stay inside the mapping (rows × stride).
        unsafe {
            gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
            gl.FramebufferTexture2D(
                GL_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0,
                GL_TEXTURE_2D,
                texture,
                0,
            );
            let complete = gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
            if complete {
                gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
                gl.ColorMask(1, 1, 1, 1);
                gl.Disable(GL_SCISSOR_TEST);
                gl.ClearColor(0.0, 0.0, 0.0, 0.0);
                gl.Clear(GL_COLOR_BUFFER_BIT);
                gl.Enable(GL_SCISSOR_TEST);
                for (i, &(x, y)) in corners.iter().enumerate() {
                    let v = marker(i);
                    gl.Scissor(x as i32, y as i32, 1, 1);
                    gl.ClearColor(
                        f32::from(v[0]) / 255.0,
                        f32::from(v[1]) / 255.0,
                        f32::from(v[2]) / 255.0,
                        f32::from(v[3]) / 255.0,
                    );
                    gl.Clear(GL_COLOR_BUFFER_BIT);
                }
                gl.Disable(GL_SCISSOR_TEST);
                gl.Finish();
            }
            gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            let _ = gl.take_error();
            complete
                && corners.iter().enumerate().all(|(i, &(x, y))| {
                    let at = self.data_offset + y as usize * self.stride + x as usize * 4;
                    std::slice::from_raw_parts(self.map.add(at), 4) == marker(i)
                })
        }
    }

    /// What a composite reads: `texture`'s pixels (this memory's).
    pub fn pixels(&self, texture: u32) -> EyePixels {
        EyePixels {
            texture,
            // SAFETY: the data starts inside the mapping.
            rows: unsafe { self.map.add(self.data_offset) },
            stride: self.stride,
            width: self.width,
            height: self.height,
        }
    }

    /// Deletes the memory object and unmaps. The texture made from it must
    /// be deleted, and no rendering into it pending in any context (llvmpipe
    /// unmaps its own view of the file with the memory object).
    ///
    /// # Safety
    /// A context of the share group the memory object was made in must be
    /// current; the conditions above hold.
    pub unsafe fn release(self, api: &MemoryObjectApi) {
        // SAFETY: contract.
        unsafe { self.release_now(api) }
    }

    unsafe fn release_now(self, api: &MemoryObjectApi) {
        // SAFETY: contract of the callers; Drop unmaps.
        unsafe { (api.delete)(1, &self.memory_object) };
    }
}

impl Drop for TextureMemory {
    fn drop(&mut self) {
        // SAFETY: the mapping made in create, unmapped once.
        unsafe { libc::munmap(self.map.cast(), self.map_len) };
    }
}

/// A distinct RGBA8 colour for corner `i`.
pub(crate) fn marker(i: usize) -> [u8; 4] {
    let i = i as u8;
    [0x11 + i, 0xA0 - i, 0x5C + 3 * i, 0xF0 - 7 * i]
}

/// Where a composite reads an eye texture's pixels in place: rows bottom
/// first, `stride` bytes apart, RGBA8. Valid while the texture's
/// framebuffer is neither resized nor released, and to be read only when
/// the rendering into it has finished (after the present's glFinish).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EyePixels {
    /// The texture the pixels are of.
    pub texture: u32,
    rows: *const u8,
    stride: usize,
    width: u32,
    height: u32,
}

// SAFETY: a view of shared memory; see the type's contract.
unsafe impl Send for EyePixels {}
// SAFETY: as above (read only).
unsafe impl Sync for EyePixels {}

impl EyePixels {
    /// The pixels of `texture`, `width` × `height` RGBA8 rows bottom first
    /// from `rows`, `stride` bytes apart (a layer of automatic stereo's
    /// eyes, [`crate::auto::eyes`]).
    ///
    /// # Safety
    /// The rows are inside a mapping that lives as the type's contract
    /// says.
    pub(crate) unsafe fn new(
        texture: u32,
        rows: *const u8,
        stride: usize,
        width: u32,
        height: u32,
    ) -> EyePixels {
        EyePixels {
            texture,
            rows,
            stride,
            width,
            height,
        }
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Row `y` (0: the bottom one) as RGBA8 words to read and write in
    /// place; None past the last row, or where the rows are not aligned
    /// to words.
    ///
    /// # Safety
    /// The contract of [`EyePixels`] holds while the row is used, and
    /// nothing else reads or writes the row meanwhile (GL has finished
    /// with it, and no other row view of the same row is alive).
    #[allow(clippy::mut_from_ref)] // a view of shared memory, as the contract says
    pub unsafe fn row_words_mut(&self, y: u32) -> Option<&mut [u32]> {
        if y >= self.height || self.stride % 4 != 0 || self.rows as usize % 4 != 0 {
            return None;
        }
        // SAFETY: inside the mapping (row checked above), aligned to
        // words, the mapping writable (PROT_WRITE); exclusive by contract.
        Some(unsafe {
            std::slice::from_raw_parts_mut(
                self.rows
                    .add(y as usize * self.stride)
                    .cast::<u32>()
                    .cast_mut(),
                self.width as usize,
            )
        })
    }

    /// The rows of the rectangle at (`x`, `y`) (bottom row), `width` ×
    /// `height` texels; None if it is not inside the texture.
    ///
    /// # Safety
    /// The contract of [`EyePixels`] holds for as long as the rows are used.
    pub unsafe fn rect(&self, x: u32, y: u32, width: u32, height: u32) -> Option<Rows<'_>> {
        if width == 0
            || height == 0
            || x.checked_add(width)? > self.width
            || y.checked_add(height)? > self.height
        {
            return None;
        }
        let row_bytes = width as usize * 4;
        let len = (height as usize - 1) * self.stride + row_bytes;
        // SAFETY: inside the mapping (checked above); contract for the rest.
        let data = unsafe {
            std::slice::from_raw_parts(
                self.rows.add(y as usize * self.stride + x as usize * 4),
                len,
            )
        };
        Some(Rows {
            data,
            stride: self.stride,
            row_bytes,
            height,
        })
    }
}

/// Rows of RGBA8 pixels, `stride` bytes apart: a read-back band or an eye
/// in place.
#[derive(Clone, Copy, Debug)]
pub struct Rows<'a> {
    data: &'a [u8],
    stride: usize,
    row_bytes: usize,
    height: u32,
}

impl<'a> Rows<'a> {
    /// The rows of a whole image.
    pub fn of_image(img: &'a crate::image::Image) -> Rows<'a> {
        Rows {
            data: img.pixels(),
            stride: img.width() as usize * 4,
            row_bytes: img.width() as usize * 4,
            height: img.height(),
        }
    }

    /// `height` rows of `width` pixel words packed in `words` (panics
    /// unless it holds them).
    pub fn of_words(words: &'a [u32], width: usize, height: u32) -> Rows<'a> {
        assert!(words.len() >= width * height as usize, "rows of the words");
        Rows {
            data: crate::image::as_bytes(&words[..width * height as usize]),
            stride: width * 4,
            row_bytes: width * 4,
            height,
        }
    }

    /// Row `k` (panics past the last).
    pub fn row(&self, k: u32) -> &'a [u8] {
        assert!(k < self.height, "row {k} of {}", self.height);
        let at = k as usize * self.stride;
        &self.data[at..at + self.row_bytes]
    }

    /// Rows `k`…`k + n − 1` as one slice, where they follow each other
    /// with no gap (None where the stride leaves one, or past the last).
    pub fn span(&self, k: u32, n: u32) -> Option<&'a [u8]> {
        if self.stride != self.row_bytes || k.checked_add(n)? > self.height {
            return None;
        }
        let at = k as usize * self.stride;
        self.data.get(at..at + n as usize * self.row_bytes)
    }

    /// How many rows.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Copies the rows, packed, into `out` (height × row bytes long): in
    /// their order, or reversed when `flip` (GL's bottom-first rows become
    /// an image's top-first ones in the same pass).
    pub fn copy_to(&self, out: &mut [u8], flip: bool) {
        let n = self.row_bytes;
        assert_eq!(out.len(), n * self.height as usize, "rows copied");
        for (k, dst) in out.chunks_exact_mut(n).enumerate() {
            let k = k as u32;
            dst.copy_from_slice(self.row(if flip { self.height - 1 - k } else { k }));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stereo::buffers::{ColorBuffer, FramebufferShape};
    use crate::stereo::emulated::{BufferFormats, EmulatedFramebuffer};

    /// An EGL context of its own ([`crate::testing::egl_context`]) and
    /// its memory-object API.
    struct Context {
        api: MemoryObjectApi,
        cx: crate::testing::EglContext,
    }

    impl std::ops::Deref for Context {
        type Target = crate::testing::EglContext;
        fn deref(&self) -> &Self::Target {
            &self.cx
        }
    }

    fn context() -> Context {
        let cx = crate::testing::egl_context();
        // SAFETY: the platform's GetProcAddress.
        let api = unsafe { MemoryObjectApi::load(|n| cx.display.platform().get_proc_address(n)) }
            .expect("GL_EXT_memory_object's functions");
        Context { api, cx }
    }

    /// `tex`'s pixels as glReadPixels gives them (rows bottom first).
    unsafe fn read_back(gl: &Gl, fbo: u32, tex: u32, w: u32, h: u32) -> Vec<u8> {
        let mut out = vec![0; (w * h * 4) as usize];
        // SAFETY: contract; `out` holds w × h × 4 bytes.
        unsafe {
            gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
            gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
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
                out.as_mut_ptr().cast(),
            );
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        out
    }

    #[test]
    fn llvmpipe_draws_into_memory_the_cpu_reads_as_gl_reads_it_back() {
        let cx = context();
        let gl = &*cx.gl;
        // SAFETY: the context is current.
        unsafe {
            let uuid = llvmpipe_identity(gl).expect("llvmpipe with GL_EXT_memory_object_fd");
            let fbo = gl.gen_framebuffer();
            // Odd sizes: rows padded to 4 texels and to cache lines.
            for (w, h) in [(37, 5), (1, 1), (130, 3)] {
                let tex = gl.gen_texture();
                let m = TextureMemory::create(gl, &cx.api, &uuid, tex, w, h).expect("made");
                assert!(
                    m.verify(gl, tex, fbo),
                    "{w}x{h}: the layout is the predicted one"
                );
                // Something of every row and column: a clear and a scissored box.
                gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
                gl.FramebufferTexture2D(
                    GL_FRAMEBUFFER,
                    GL_COLOR_ATTACHMENT0,
                    GL_TEXTURE_2D,
                    tex,
                    0,
                );
                gl.ClearColor(0.2, 0.4, 0.6, 0.8);
                gl.Clear(GL_COLOR_BUFFER_BIT);
                gl.Enable(GL_SCISSOR_TEST);
                gl.Scissor(w as i32 / 3, h as i32 / 2, w.div_ceil(2) as i32, 1);
                gl.ClearColor(1.0, 0.0, 0.5, 1.0);
                gl.Clear(GL_COLOR_BUFFER_BIT);
                gl.Disable(GL_SCISSOR_TEST);
                gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
                gl.Finish();
                let want = read_back(gl, fbo, tex, w, h);
                let px = m.pixels(tex);
                let rows = px.rect(0, 0, w, h).expect("inside");
                let got: Vec<u8> = (0..h).flat_map(|k| rows.row(k).to_vec()).collect();
                assert_eq!(got, want, "{w}x{h}: in place vs read back");
                assert!(px.rect(1, 0, w, h).is_none(), "a rectangle past the edge");
                gl.DeleteTextures(1, &tex);
                m.release(&cx.api);
            }
            gl.DeleteFramebuffers(1, &fbo);
        }
    }

    #[test]
    fn memory_the_driver_does_not_recognise_fails_the_check() {
        let cx = context();
        let gl = &*cx.gl;
        // SAFETY: the context is current.
        unsafe {
            let fbo = gl.gen_framebuffer();
            let tex = gl.gen_texture();
            // Another driver's identity: llvmpipe refuses the import.
            let wrong = [0x5A; 16];
            if let Some(m) = TextureMemory::create(gl, &cx.api, &wrong, tex, 16, 16) {
                assert!(!m.verify(gl, tex, fbo), "a refused import is not used");
                gl.DeleteTextures(1, &tex);
                m.release(&cx.api);
            }
            gl.take_error();
            gl.DeleteFramebuffers(1, &fbo);
        }
    }

    #[test]
    fn an_emulated_framebuffer_in_memory_is_replaced_on_resize() {
        let cx = context();
        let gl = &*cx.gl;
        let shape = FramebufferShape {
            stereo: true,
            double_buffered: true,
        };
        let formats = BufferFormats {
            in_place: Some(cx.api),
            ..BufferFormats::matching(0, 24, 0)
        };
        // SAFETY: the context is current.
        unsafe {
            let mut fb = EmulatedFramebuffer::allocate_with(gl, shape, 20, 10, formats).unwrap();
            let before = fb.texture(ColorBuffer::BackLeft);
            let px = fb.pixels(ColorBuffer::BackLeft).expect("in place");
            assert_eq!(px.texture, before);
            // Cleared to opaque black at allocation (a visual without alpha).
            gl.Finish();
            let rows = px.rect(0, 0, 20, 10).unwrap();
            assert!((0..10).all(|k| rows.row(k).chunks(4).all(|p| p == [0, 0, 0, 255])));
            fb.resize(gl, 30, 12).unwrap();
            let after = fb.texture(ColorBuffer::BackLeft);
            assert_ne!(after, before, "immutable storage: a new texture");
            let px = fb
                .pixels(ColorBuffer::BackRight)
                .expect("in place after the resize");
            assert!(px.rect(0, 0, 30, 12).is_some() && px.rect(0, 0, 31, 12).is_none());
            gl.Finish();
            fb.release_retired(gl);
            fb.release(gl);
        }
    }

    fn hex(b: &[u8]) -> String {
        b.iter().map(|x| format!("{x:02x}")).collect()
    }

    #[test]
    fn sha1_matches_the_fips_examples() {
        assert_eq!(
            hex(&sha1(b"abc")),
            "a9993e364706816aba3e25717850c26c9cd0d89d"
        );
        assert_eq!(hex(&sha1(b"")), "da39a3ee5e6b4b0d3255bfef95601890afd80709");
        assert_eq!(
            hex(&sha1(
                b"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"
            )),
            "84983e441c3bd26ebaae4aa1f95129e5e54670f1"
        );
        let million = vec![b'a'; 1_000_000];
        assert_eq!(
            hex(&sha1(&million)),
            "34aa973cd4c4daa4f61eeb2bdbad27316534016f"
        );
    }

    #[test]
    fn the_driver_identity_is_llvmpipe_and_mesas_git_suffix() {
        assert_eq!(
            driver_id("4.5 (Compatibility Profile) Mesa 22.3.6").as_deref(),
            Some("llvmpipe")
        );
        assert_eq!(
            driver_id("4.5 (Core Profile) Mesa 23.1.0-devel (git-1a2b3c4d5e)").as_deref(),
            Some("llvmpipe (git-1a2b3c4d5e)")
        );
        assert_eq!(driver_id("4.6.0 NVIDIA 535.54.03"), None);
    }

    #[test]
    fn the_header_is_laid_out_as_mesas_allocator_lays_it_out() {
        let uuid: [u8; 16] = std::array::from_fn(|i| i as u8 + 1);
        let h = header(3 * 4096, 4096, &uuid);
        assert_eq!(h.len(), 4096);
        let word = |at: usize| usize::from_ne_bytes(h[at..at + 8].try_into().unwrap());
        assert_eq!((word(0), word(8)), (3 * 4096, 4096));
        assert_eq!(&h[16..32], &uuid);
        assert_eq!(word(4096 - 8), 4096, "the offset just before the data");
        assert!(h[32..4096 - 8].iter().all(|&b| b == 0));
    }

    #[test]
    fn the_predicted_layout_pads_to_four_texels_and_cache_lines() {
        assert_eq!(cache_lines(predicted_stride(1280)), 5120);
        assert_eq!(cache_lines(predicted_stride(400)), 1600);
        assert_eq!(cache_lines(predicted_stride(1)), 64);
        assert_eq!(cache_lines(predicted_stride(17)), 128);
    }

    #[test]
    fn rows_are_copied_packed_in_order_or_flipped() {
        // Two rows of one texel each, 8 bytes apart (4 bytes of padding).
        let data = [1, 2, 3, 4, 0, 0, 0, 0, 5, 6, 7, 8];
        let rows = Rows {
            data: &data,
            stride: 8,
            row_bytes: 4,
            height: 2,
        };
        let mut out = [0; 8];
        rows.copy_to(&mut out, false);
        assert_eq!(out, [1, 2, 3, 4, 5, 6, 7, 8]);
        rows.copy_to(&mut out, true);
        assert_eq!(out, [5, 6, 7, 8, 1, 2, 3, 4]);
    }

    #[test]
    fn rows_of_an_image_are_its_rows() {
        let mut img = crate::image::Image::new(2, 3);
        img.pixels_mut()[8..16].copy_from_slice(&[1, 2, 3, 4, 5, 6, 7, 8]);
        let rows = Rows::of_image(&img);
        assert_eq!(rows.height(), 3);
        assert_eq!(rows.row(1), &[1, 2, 3, 4, 5, 6, 7, 8]);
    }
}

//! A small GL function table, loaded from the backend's GetProcAddress.
//!
//! The library links no GL library: every GL entry point it calls comes
//! through this table, loaded from eglGetProcAddress, OSMesaGetProcAddress or
//! glXGetProcAddress. That is what lets one process use OSMesa (whose `gl*`
//! symbols differ from libGL's) and what lets the library load on machines
//! without GL at all.
//!
//! Entry points are loaded by name; `eglGetProcAddress` returns stubs for
//! unknown names, so whether a function really exists is decided from the
//! context's version ([`Gl::version`]), not from the pointer.

pub mod enums;

use std::ffi::{CStr, c_char, c_void};
use std::sync::atomic::{AtomicU32, Ordering};

use crate::error::{Error, Result};

#[allow(non_camel_case_types, missing_docs)]
pub mod types {
    pub type GLenum = u32;
    pub type GLuint = u32;
    pub type GLint = i32;
    pub type GLsizei = i32;
    pub type GLboolean = u8;
    pub type GLbitfield = u32;
    pub type GLfloat = f32;
    pub type GLdouble = f64;
    pub type GLchar = std::ffi::c_char;
    pub type GLsizeiptr = isize;
    pub type GLintptr = isize;
    pub type GLsync = *const std::ffi::c_void;
    pub type GLuint64 = u64;
}
use types::*;

macro_rules! gl_table {
    ($( $method:ident = $sym:literal ($($arg:ident : $ty:ty),*) $(-> $ret:ty)?; )*) => {
        /// GL entry points of one backend. Calling them requires a context of
        /// that backend to be current on the calling thread.
        #[allow(non_snake_case)]
        pub struct Gl {
            $( $method: unsafe extern "system" fn($($ty),*) $(-> $ret)?, )*
            version: (u32, u32),
            /// The next reserved name, when shared objects are named from the top ([`Gl::reserve_names`]).
            reserved: Option<AtomicU32>,
        }

        impl Gl {
            /// Loads every entry point through `get`. Fails (naming the
            /// function) if any is NULL.
            ///
            /// # Safety
            /// `get` must return the address of the named GL function of the
            /// backend (with its real signature) or NULL.
            pub unsafe fn load(mut get: impl FnMut(&CStr) -> *const c_void) -> Result<Gl> {
                Ok(Gl {
                    $( $method: {
                        let p = get(unsafe { CStr::from_bytes_with_nul_unchecked(concat!($sym, "\0").as_bytes()) });
                        if p.is_null() {
                            return Err(Error::BackendUnavailable(format!(
                                "the GL library lacks {}: a GL 3.0 or newer driver is required", $sym
                            )));
                        }
                        // SAFETY: the backend's GetProcAddress returned this
                        // function's address; the signature is the Khronos one.
                        unsafe { std::mem::transmute::<*const c_void, unsafe extern "system" fn($($ty),*) $(-> $ret)?>(p) }
                    }, )*
                    version: (0, 0),
                    reserved: None,
                })
            }

            $(
                #[doc = concat!("`", $sym, "`.\n\n# Safety\nA context of this backend must be current on the calling thread, and pointer arguments valid as GL requires.")]
                #[allow(clippy::too_many_arguments, non_snake_case)]
                #[inline]
                pub unsafe fn $method(&self, $($arg: $ty),*) $(-> $ret)? {
                    // SAFETY: forwarded under the caller's contract.
                    unsafe { (self.$method)($($arg),*) }
                }
            )*
        }
    };
}

gl_table! {
    GetError = "glGetError"() -> GLenum;
    GetString = "glGetString"(name: GLenum) -> *const u8;
    GetIntegerv = "glGetIntegerv"(pname: GLenum, data: *mut GLint);
    GetBooleanv = "glGetBooleanv"(pname: GLenum, data: *mut GLboolean);
    GetFloatv = "glGetFloatv"(pname: GLenum, data: *mut GLfloat);
    GetDoublev = "glGetDoublev"(pname: GLenum, data: *mut GLdouble);
    Flush = "glFlush"();
    Finish = "glFinish"();
    Enable = "glEnable"(cap: GLenum);
    Disable = "glDisable"(cap: GLenum);
    IsEnabled = "glIsEnabled"(cap: GLenum) -> GLboolean;
    Viewport = "glViewport"(x: GLint, y: GLint, w: GLsizei, h: GLsizei);
    Scissor = "glScissor"(x: GLint, y: GLint, w: GLsizei, h: GLsizei);
    ClearColor = "glClearColor"(r: GLfloat, g: GLfloat, b: GLfloat, a: GLfloat);
    Clear = "glClear"(mask: GLbitfield);
    ClearBufferfv = "glClearBufferfv"(buffer: GLenum, drawbuffer: GLint, value: *const GLfloat);
    ClearDepth = "glClearDepth"(depth: GLdouble);
    ColorMask = "glColorMask"(r: GLboolean, g: GLboolean, b: GLboolean, a: GLboolean);
    PixelStorei = "glPixelStorei"(pname: GLenum, param: GLint);
    ReadPixels = "glReadPixels"(x: GLint, y: GLint, w: GLsizei, h: GLsizei, format: GLenum, ty: GLenum, data: *mut c_void);
    DrawBuffer = "glDrawBuffer"(buf: GLenum);
    DrawBuffers = "glDrawBuffers"(n: GLsizei, bufs: *const GLenum);
    ReadBuffer = "glReadBuffer"(src: GLenum);
    DrawPixels = "glDrawPixels"(w: GLsizei, h: GLsizei, format: GLenum, ty: GLenum, data: *const c_void);
    WindowPos2i = "glWindowPos2i"(x: GLint, y: GLint);
    MatrixMode = "glMatrixMode"(mode: GLenum);
    LoadMatrixd = "glLoadMatrixd"(m: *const GLdouble);
    MultMatrixd = "glMultMatrixd"(m: *const GLdouble);

    GenTextures = "glGenTextures"(n: GLsizei, out: *mut GLuint);
    DeleteTextures = "glDeleteTextures"(n: GLsizei, names: *const GLuint);
    BindTexture = "glBindTexture"(target: GLenum, tex: GLuint);
    ActiveTexture = "glActiveTexture"(unit: GLenum);
    TexImage2D = "glTexImage2D"(target: GLenum, level: GLint, internal: GLint, w: GLsizei, h: GLsizei, border: GLint, format: GLenum, ty: GLenum, data: *const c_void);
    TexSubImage2D = "glTexSubImage2D"(target: GLenum, level: GLint, x: GLint, y: GLint, w: GLsizei, h: GLsizei, format: GLenum, ty: GLenum, data: *const c_void);
    TexParameteri = "glTexParameteri"(target: GLenum, pname: GLenum, param: GLint);

    GenFramebuffers = "glGenFramebuffers"(n: GLsizei, out: *mut GLuint);
    DeleteFramebuffers = "glDeleteFramebuffers"(n: GLsizei, names: *const GLuint);
    BindFramebuffer = "glBindFramebuffer"(target: GLenum, fb: GLuint);
    FramebufferTexture2D = "glFramebufferTexture2D"(target: GLenum, attachment: GLenum, textarget: GLenum, tex: GLuint, level: GLint);
    FramebufferRenderbuffer = "glFramebufferRenderbuffer"(target: GLenum, attachment: GLenum, rbtarget: GLenum, rb: GLuint);
    GetFramebufferAttachmentParameteriv = "glGetFramebufferAttachmentParameteriv"(target: GLenum, attachment: GLenum, pname: GLenum, out: *mut GLint);
    CheckFramebufferStatus = "glCheckFramebufferStatus"(target: GLenum) -> GLenum;
    BlitFramebuffer = "glBlitFramebuffer"(sx0: GLint, sy0: GLint, sx1: GLint, sy1: GLint, dx0: GLint, dy0: GLint, dx1: GLint, dy1: GLint, mask: GLbitfield, filter: GLenum);
    GenRenderbuffers = "glGenRenderbuffers"(n: GLsizei, out: *mut GLuint);
    DeleteRenderbuffers = "glDeleteRenderbuffers"(n: GLsizei, names: *const GLuint);
    BindRenderbuffer = "glBindRenderbuffer"(target: GLenum, rb: GLuint);
    RenderbufferStorage = "glRenderbufferStorage"(target: GLenum, internal: GLenum, w: GLsizei, h: GLsizei);

    CreateShader = "glCreateShader"(ty: GLenum) -> GLuint;
    ShaderSource = "glShaderSource"(shader: GLuint, count: GLsizei, strings: *const *const GLchar, lengths: *const GLint);
    CompileShader = "glCompileShader"(shader: GLuint);
    GetShaderiv = "glGetShaderiv"(shader: GLuint, pname: GLenum, out: *mut GLint);
    GetShaderInfoLog = "glGetShaderInfoLog"(shader: GLuint, max: GLsizei, len: *mut GLsizei, log: *mut GLchar);
    DeleteShader = "glDeleteShader"(shader: GLuint);
    CreateProgram = "glCreateProgram"() -> GLuint;
    AttachShader = "glAttachShader"(program: GLuint, shader: GLuint);
    LinkProgram = "glLinkProgram"(program: GLuint);
    GetProgramiv = "glGetProgramiv"(program: GLuint, pname: GLenum, out: *mut GLint);
    GetProgramInfoLog = "glGetProgramInfoLog"(program: GLuint, max: GLsizei, len: *mut GLsizei, log: *mut GLchar);
    DeleteProgram = "glDeleteProgram"(program: GLuint);
    UseProgram = "glUseProgram"(program: GLuint);
    GetUniformLocation = "glGetUniformLocation"(program: GLuint, name: *const GLchar) -> GLint;
    Uniform1i = "glUniform1i"(loc: GLint, v: GLint);
    Uniform1f = "glUniform1f"(loc: GLint, v: GLfloat);
    Uniform2f = "glUniform2f"(loc: GLint, a: GLfloat, b: GLfloat);
    Uniform3f = "glUniform3f"(loc: GLint, a: GLfloat, b: GLfloat, c: GLfloat);
    Uniform4f = "glUniform4f"(loc: GLint, a: GLfloat, b: GLfloat, c: GLfloat, d: GLfloat);
    Uniform2i = "glUniform2i"(loc: GLint, a: GLint, b: GLint);
    Uniform4i = "glUniform4i"(loc: GLint, a: GLint, b: GLint, c: GLint, d: GLint);
    UniformMatrix3fv = "glUniformMatrix3fv"(loc: GLint, count: GLsizei, transpose: GLboolean, v: *const GLfloat);
    GenVertexArrays = "glGenVertexArrays"(n: GLsizei, out: *mut GLuint);
    DeleteVertexArrays = "glDeleteVertexArrays"(n: GLsizei, names: *const GLuint);
    BindVertexArray = "glBindVertexArray"(vao: GLuint);
    DrawArrays = "glDrawArrays"(mode: GLenum, first: GLint, count: GLsizei);

    GenBuffers = "glGenBuffers"(n: GLsizei, out: *mut GLuint);
    DeleteBuffers = "glDeleteBuffers"(n: GLsizei, names: *const GLuint);
    BindBuffer = "glBindBuffer"(target: GLenum, buf: GLuint);
    BufferData = "glBufferData"(target: GLenum, size: GLsizeiptr, data: *const c_void, usage: GLenum);
    MapBufferRange = "glMapBufferRange"(target: GLenum, offset: GLintptr, len: GLsizeiptr, access: GLbitfield) -> *mut c_void;
    UnmapBuffer = "glUnmapBuffer"(target: GLenum) -> GLboolean;
    FenceSync = "glFenceSync"(condition: GLenum, flags: GLbitfield) -> GLsync;
    ClientWaitSync = "glClientWaitSync"(sync: GLsync, flags: GLbitfield, timeout: GLuint64) -> GLenum;
    DeleteSync = "glDeleteSync"(sync: GLsync);
}

impl Gl {
    /// Loads the table and reads the version of the context current on this
    /// thread (which must belong to the same backend).
    ///
    /// # Safety
    /// As [`Gl::load`], and a context of the backend must be current.
    pub unsafe fn load_current(get: impl FnMut(&CStr) -> *const c_void) -> Result<Gl> {
        // SAFETY: forwarded contract.
        let mut gl = unsafe { Gl::load(get)? };
        // SAFETY: a context is current (contract).
        let v = unsafe { gl.string(enums::GL_VERSION) };
        gl.version = parse_version(&v).ok_or_else(|| {
            Error::BackendUnavailable(format!(
                "the GL context reports an unreadable version {v:?}"
            ))
        })?;
        if gl.version < (3, 0) {
            return Err(Error::BackendUnavailable(format!(
                "the GL context is version {}.{}; glstereo needs GL 3.0 or newer (framebuffer objects)",
                gl.version.0, gl.version.1
            )));
        }
        Ok(gl)
    }

    /// The context's GL version (major, minor).
    pub fn version(&self) -> (u32, u32) {
        self.version
    }

    /// From now on, [`Gl::gen_texture`], [`Gl::gen_renderbuffer`] and
    /// [`Gl::gen_framebuffer`] name objects downward from
    /// [`RESERVED_NAME_TOP`] instead of asking the driver. For objects made
    /// in a share group that an unmodified program also uses (the
    /// LD_PRELOAD interposer): legacy programs often bind texture names
    /// they never generated (`glBindTexture(GL_TEXTURE_2D, 1)` is legal in
    /// the compatibility profile), so the library's objects must not take
    /// the small names glGen* hands out first. Needs a compatibility-profile
    /// context (binding an unused name creates it).
    ///
    /// The names stay below 2³¹: bindings are read back as `GLint`
    /// (glGetIntegerv), and programs and other layers store them so —
    /// VirtualGL puts back only bindings that read as non-negative. Mesa
    /// hands out `highest name ever used + 1` while that fits below
    /// 0xFFFFFFFE, else the lowest free names; a name at 0x7FFFFFFF would
    /// make the program's next glGen* name 0x80000000 (negative as a
    /// `GLint`). So each reserved object is followed by one at
    /// [`ALLOCATOR_CEILING`], made and deleted at once ([`Gl::push_ceiling`]):
    /// Mesa's highest name ever used stays there, and the program's glGen*
    /// names stay the lowest free ones, as small as without the library.
    /// No object with a name above 2³¹ is left behind, and none is ever
    /// bound in a program's context.
    pub fn reserve_names(&mut self) {
        self.reserved = Some(AtomicU32::new(RESERVED_NAME_TOP));
    }

    fn next_reserved(&self) -> Option<u32> {
        self.reserved
            .as_ref()
            .map(|next| next.fetch_sub(1, Ordering::Relaxed))
    }

    /// Whether [`Gl::reserve_names`] is on and has handed out a name: the
    /// library has objects in some program's share group.
    pub fn reserved_names_used(&self) -> bool {
        self.reserved
            .as_ref()
            .is_some_and(|next| next.load(Ordering::Relaxed) != RESERVED_NAME_TOP)
    }

    /// Makes and deletes an object named [`ALLOCATOR_CEILING`] with `bind`
    /// (a glBind* of a target taking that kind of object) and `delete`
    /// (its glDelete*): see [`Gl::reserve_names`]. The binding is left at 0
    /// (callers restore theirs).
    ///
    /// # Safety
    /// A compatibility-profile context of this backend must be current.
    unsafe fn push_ceiling(&self, bind: impl Fn(u32), delete: unsafe fn(&Gl, i32, *const u32)) {
        bind(ALLOCATOR_CEILING);
        bind(0);
        // SAFETY: contract; one name read.
        unsafe { delete(self, 1, &ALLOCATOR_CEILING) };
    }

    /// One new texture name, bound to GL_TEXTURE_2D (the binding is left
    /// at 0). See [`Gl::reserve_names`].
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn gen_texture(&self) -> u32 {
        let mut name = 0;
        // SAFETY: contract; one name written.
        unsafe {
            let bind = |n| self.BindTexture(enums::GL_TEXTURE_2D, n);
            match self.next_reserved() {
                Some(n) => {
                    name = n;
                    self.push_ceiling(bind, Gl::DeleteTextures);
                }
                None => self.GenTextures(1, &mut name),
            }
            // Binding creates the object (and marks a reserved name used).
            bind(name);
            bind(0);
        }
        name
    }

    /// One new renderbuffer name (created; the binding is left at 0). See
    /// [`Gl::reserve_names`].
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn gen_renderbuffer(&self) -> u32 {
        let mut name = 0;
        // SAFETY: contract; one name written.
        unsafe {
            let bind = |n| self.BindRenderbuffer(enums::GL_RENDERBUFFER, n);
            match self.next_reserved() {
                Some(n) => {
                    name = n;
                    self.push_ceiling(bind, Gl::DeleteRenderbuffers);
                }
                None => self.GenRenderbuffers(1, &mut name),
            }
            bind(name);
            bind(0);
        }
        name
    }

    /// One new framebuffer-object name, for the library's own contexts
    /// (compositor and layer contexts, compatibility profile). Mesa shares
    /// framebuffer objects across a share group, so with
    /// [`Gl::reserve_names`] they too come from the reserved range, where a
    /// program that deletes or binds names it guessed cannot reach them.
    /// The framebuffer bindings are left as they were.
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn gen_framebuffer(&self) -> u32 {
        let mut name = 0;
        // SAFETY: contract; one name written, bindings restored.
        unsafe {
            match self.next_reserved() {
                Some(n) => {
                    name = n;
                    let draw = self.integer(enums::GL_DRAW_FRAMEBUFFER_BINDING) as u32;
                    let read = self.integer(enums::GL_READ_FRAMEBUFFER_BINDING) as u32;
                    let bind = |n| self.BindFramebuffer(enums::GL_FRAMEBUFFER, n);
                    self.push_ceiling(bind, Gl::DeleteFramebuffers);
                    // Binding creates the object.
                    bind(name);
                    self.BindFramebuffer(enums::GL_DRAW_FRAMEBUFFER, draw);
                    self.BindFramebuffer(enums::GL_READ_FRAMEBUFFER, read);
                }
                None => self.GenFramebuffers(1, &mut name),
            }
        }
        name
    }

    /// One new framebuffer-object name for the *current* context, which may
    /// be a program's (the emulated default framebuffer's object), left
    /// bound to GL_FRAMEBUFFER. With [`Gl::reserve_names`], a reserved name
    /// where the context creates objects by binding (compatibility
    /// profile); else, and in a core-profile context (which refuses names
    /// glGenFramebuffers did not hand out, and where a program cannot bind
    /// a name it guessed either), the driver's. The caller keeps the
    /// program's pending GL errors: this reads the error queue.
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn gen_framebuffer_here(&self) -> u32 {
        // SAFETY: contract.
        unsafe {
            if let Some(n) = self.next_reserved() {
                self.BindFramebuffer(enums::GL_FRAMEBUFFER, n);
                if self.GetError() == enums::GL_NO_ERROR {
                    return n;
                }
            }
            let mut name = 0;
            self.GenFramebuffers(1, &mut name);
            self.BindFramebuffer(enums::GL_FRAMEBUFFER, name);
            name
        }
    }

    /// glGetString as a Rust string ("" when NULL).
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn string(&self, name: u32) -> String {
        // SAFETY: a context is current (contract); the result is NULL or a
        // NUL-terminated static string.
        let p = unsafe { self.GetString(name) };
        if p.is_null() {
            String::new()
        } else {
            // SAFETY: non-NULL, NUL-terminated (GL guarantees).
            unsafe { CStr::from_ptr(p as *const c_char) }
                .to_string_lossy()
                .into_owned()
        }
    }

    /// One glGetIntegerv value.
    ///
    /// # Safety
    /// A context of this backend must be current; `pname` must return one value.
    pub unsafe fn integer(&self, pname: u32) -> i32 {
        let mut v = 0;
        // SAFETY: contract; one value written.
        unsafe { self.GetIntegerv(pname, &mut v) };
        v
    }

    /// Drains the GL error queue, returning the first error (GL_NO_ERROR if none).
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn take_error(&self) -> u32 {
        // SAFETY: contract.
        let first = unsafe { self.GetError() };
        if first != enums::GL_NO_ERROR {
            // A context has a bounded number of error flags; drain them.
            for _ in 0..16 {
                // SAFETY: contract.
                if unsafe { self.GetError() } == enums::GL_NO_ERROR {
                    break;
                }
            }
        }
        first
    }

    /// Turns a pending GL error into an [`Error`] describing `what` failed.
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn check(&self, what: &str) -> Result<()> {
        // SAFETY: contract.
        match unsafe { self.take_error() } {
            enums::GL_NO_ERROR => Ok(()),
            enums::GL_OUT_OF_MEMORY => Err(Error::OutOfMemory(format!(
                "{what}: the GL driver ran out of memory; use a smaller surface"
            ))),
            e => Err(Error::Gl(format!("{what}: GL error {e:#06x}"))),
        }
    }
}

/// The first name [`Gl::reserve_names`] hands out; later ones count down:
/// the highest name that reads as non-negative through a `GLint`.
pub const RESERVED_NAME_TOP: u32 = 0x7FFF_FFFF;

/// How many names below [`RESERVED_NAME_TOP`] count as reserved: far more
/// than the library ever makes, far above anything glGen* hands out.
pub const RESERVED_NAME_SPAN: u32 = 1 << 24;

/// The name of the short-lived object that keeps Mesa's name allocator
/// handing out the lowest free names ([`Gl::reserve_names`]): the highest
/// name Mesa's quick path (`highest + 1`) no longer takes.
pub const ALLOCATOR_CEILING: u32 = 0xFFFF_FFFE;

/// Whether `name` lies in the library's reserved range (see
/// [`Gl::reserve_names`]): a program can only have it by guessing.
pub fn is_reserved_name(name: u32) -> bool {
    name > RESERVED_NAME_TOP - RESERVED_NAME_SPAN && name <= RESERVED_NAME_TOP
}

/// Parses the GL_VERSION string of the current context into (major, minor).
///
/// # Safety
/// A context of this backend must be current.
pub unsafe fn current_version(gl: &Gl) -> Option<(u32, u32)> {
    // SAFETY: contract.
    parse_version(&unsafe { gl.string(enums::GL_VERSION) })
}

/// Parses "4.5 (Compatibility Profile) Mesa 22.3.6" or "OpenGL ES 3.2 …" into (4, 5).
fn parse_version(s: &str) -> Option<(u32, u32)> {
    let s = s.strip_prefix("OpenGL ES ").unwrap_or(s);
    let num = s.split_whitespace().next()?;
    let mut it = num.split('.');
    let major = it.next()?.parse().ok()?;
    let minor = it.next()?.parse().ok()?;
    Some((major, minor))
}

#[cfg(test)]
mod tests {
    #[test]
    fn versions_parse() {
        assert_eq!(
            super::parse_version("4.5 (Compatibility Profile) Mesa 22.3.6"),
            Some((4, 5))
        );
        assert_eq!(super::parse_version("3.1.0 NVIDIA 535"), Some((3, 1)));
        assert_eq!(super::parse_version("garbage"), None);
    }
}

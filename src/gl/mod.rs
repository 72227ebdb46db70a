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
pub mod names;

use std::ffi::{CStr, c_char, c_void};

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
            /// The names of the library's objects in a program's share group ([`Gl::own_names`]).
            names: Option<names::LayerNames>,
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
                    names: None,
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
    DepthMask = "glDepthMask"(flag: GLboolean);
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
    /// [`Gl::gen_framebuffer`] name objects as [`names`] says (for objects
    /// made in a share group that an unmodified program also uses: the
    /// LD_PRELOAD interposer) and remember them until
    /// [`Gl::delete_textures`] (and the like) deletes them. Needs a
    /// compatibility-profile context (binding an unused name creates it).
    /// Names are kept by share group ([`names::LayerNames`]): `current`
    /// says which context is current on the calling thread, and
    /// [`Gl::context_joined`] which group a context is in.
    pub fn own_names(&mut self, current: fn() -> usize) {
        self.names = Some(names::LayerNames::new(current));
    }

    /// Context `ctx` (the program's or the library's) is in share group
    /// `group` (with [`Gl::own_names`] on).
    pub fn context_joined(&self, ctx: usize, group: u64) {
        if let Some(n) = &self.names {
            n.join(ctx, group);
        }
    }

    /// Context `ctx` is destroyed (with [`Gl::own_names`] on).
    pub fn context_left(&self, ctx: usize) {
        if let Some(n) = &self.names {
            n.leave(ctx);
        }
    }

    /// Share group `group` ended, and the library's objects in it with it:
    /// their names are forgotten (with [`Gl::own_names`] on).
    pub fn group_ended(&self, group: u64) {
        if let Some(n) = &self.names {
            n.group_ended(group);
        }
    }

    /// Whether `name` names an object of `kind` the library made (with
    /// [`Gl::own_names`] on).
    pub fn owns(&self, kind: names::Kind, name: u32) -> bool {
        self.names.as_ref().is_some_and(|n| n.owns(kind, name))
    }

    /// Whether the library holds any object of `kind` (with
    /// [`Gl::own_names`] on): a glDelete* of the program needs no look-up
    /// otherwise.
    pub fn owns_any(&self, kind: names::Kind) -> bool {
        self.names.as_ref().is_some_and(|n| n.any(kind))
    }

    /// A texture or renderbuffer name: with [`Gl::own_names`], from the
    /// reserved range, followed by the allocator ceiling (`bind` binds a
    /// name of the kind, `delete` deletes one) and remembered; else
    /// glGen*'s (`make`).
    ///
    /// # Safety
    /// A context of this backend must be current.
    unsafe fn reserved_or_generated(
        &self,
        kind: names::Kind,
        make: impl Fn() -> u32,
        bind: impl Fn(u32),
        delete: impl Fn(u32),
    ) -> u32 {
        let Some(owned) = &self.names else {
            return make();
        };
        let name = names::next_reserved();
        bind(names::ALLOCATOR_CEILING);
        bind(0);
        delete(names::ALLOCATOR_CEILING);
        owned.keep(kind, name);
        name
    }

    /// One new texture name, bound to GL_TEXTURE_2D (the binding is left
    /// at 0). See [`Gl::own_names`].
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn gen_texture(&self) -> u32 {
        // SAFETY: contract.
        unsafe { self.gen_texture_of(enums::GL_TEXTURE_2D) }
    }

    /// One new texture name of `target` (GL_TEXTURE_2D_ARRAY…), created
    /// by binding it there (the binding is left at 0). See
    /// [`Gl::own_names`].
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn gen_texture_of(&self, target: u32) -> u32 {
        // SAFETY: contract; one name written or read at a time.
        unsafe {
            let bind = |n| self.BindTexture(target, n);
            let name = self.reserved_or_generated(
                names::Kind::Texture,
                || {
                    let mut n = 0;
                    self.GenTextures(1, &mut n);
                    n
                },
                bind,
                |n| self.DeleteTextures(1, &n),
            );
            // Binding creates the object.
            bind(name);
            bind(0);
            name
        }
    }

    /// One new renderbuffer name (created; the binding is left at 0). See
    /// [`Gl::own_names`].
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn gen_renderbuffer(&self) -> u32 {
        // SAFETY: contract; one name written or read at a time.
        unsafe {
            let bind = |n| self.BindRenderbuffer(enums::GL_RENDERBUFFER, n);
            let name = self.reserved_or_generated(
                names::Kind::Renderbuffer,
                || {
                    let mut n = 0;
                    self.GenRenderbuffers(1, &mut n);
                    n
                },
                bind,
                |n| self.DeleteRenderbuffers(1, &n),
            );
            bind(name);
            bind(0);
            name
        }
    }

    /// One new framebuffer-object name from glGenFramebuffers (not bound:
    /// the caller binds it to attach), remembered as the library's with
    /// [`Gl::own_names`].
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn gen_framebuffer(&self) -> u32 {
        let mut name = 0;
        // SAFETY: contract; one name written.
        unsafe { self.GenFramebuffers(1, &mut name) };
        if let Some(owned) = &self.names {
            owned.keep(names::Kind::Framebuffer, name);
        }
        name
    }

    /// glDeleteTextures of the library's own `names` (forgotten as its).
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn delete_textures(&self, names: &[u32]) {
        if let Some(owned) = &self.names {
            owned.release(names::Kind::Texture, names);
        }
        // SAFETY: contract.
        unsafe { self.DeleteTextures(names.len() as i32, names.as_ptr()) }
    }

    /// glDeleteRenderbuffers of the library's own `names`.
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn delete_renderbuffers(&self, names: &[u32]) {
        if let Some(owned) = &self.names {
            owned.release(names::Kind::Renderbuffer, names);
        }
        // SAFETY: contract.
        unsafe { self.DeleteRenderbuffers(names.len() as i32, names.as_ptr()) }
    }

    /// glDeleteFramebuffers of the library's own `names`.
    ///
    /// # Safety
    /// A context of this backend must be current.
    pub unsafe fn delete_framebuffers(&self, names: &[u32]) {
        if let Some(owned) = &self.names {
            owned.release(names::Kind::Framebuffer, names);
        }
        // SAFETY: contract.
        unsafe { self.DeleteFramebuffers(names.len() as i32, names.as_ptr()) }
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

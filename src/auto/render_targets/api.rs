//! The GL calls giving render targets eyes, in both kinds of context.
//!
//! Desktop GL 4.5 names every object it changes or asks about (direct
//! state access): no binding of the program's changes. OpenGL ES has no
//! direct state access, so there each operation binds the object it
//! needs (a texture on the active unit to its target, a renderbuffer,
//! a framebuffer for drawing), does its work and binds back what the
//! program had, before the call returns. ES also cannot say a texture's
//! target from its name: the caller gives it ([`Tex`]), from what the
//! program defined the texture with (the share group's record,
//! [`super::Targets`]).
//!
//! ES needs 3.2 (glCopyImageSubData, glFramebufferTexture, multisample
//! array textures) and texture views (GL_OES_texture_view or
//! GL_EXT_texture_view); where it has less, its render targets stay mono
//! (said once).

use crate::auto::gl_fns;

/// A texture and the target it was made for (2D, 2D array, 2D
/// multisample, 2D multisample array). Desktop GL ignores the target.
pub type Tex = (u32, u32);

const GL_TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const GL_TEXTURE_2D_MULTISAMPLE: u32 = 0x9100;
const GL_TEXTURE_2D_MULTISAMPLE_ARRAY: u32 = 0x9102;
const GL_RENDERBUFFER: u32 = 0x8D41;
const GL_RENDERBUFFER_BINDING: u32 = 0x8CA7;
const GL_DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const GL_DRAW_FRAMEBUFFER_BINDING: u32 = 0x8CA6;
const GL_FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;
const GL_MAJOR_VERSION: u32 = 0x821B;
const GL_MINOR_VERSION: u32 = 0x821C;
const GL_NUM_EXTENSIONS: u32 = 0x821D;
const GL_EXTENSIONS: u32 = 0x1F03;
const GL_VERSION: u32 = 0x1F02;

gl_fns! {
    /// What both kinds of context share.
    pub struct Common {
        get_integerv = c"glGetIntegerv": fn(u32, *mut i32);
        get_string = c"glGetString": fn(u32) -> *const u8;
        get_stringi = c"glGetStringi": fn(u32, u32) -> *const u8;
        gen_textures = c"glGenTextures": fn(i32, *mut u32);
        delete_textures = c"glDeleteTextures": fn(i32, *const u32);
        tex_image_3d = c"glTexImage3D": fn(u32, i32, i32, i32, i32, i32, i32, u32, u32, *const std::ffi::c_void);
        tex_image_2d = c"glTexImage2D": fn(u32, i32, i32, i32, i32, i32, u32, u32, *const std::ffi::c_void);
        bind_buffer = c"glBindBuffer": fn(u32, u32);
        bind_texture = c"glBindTexture": fn(u32, u32);
        active_texture = c"glActiveTexture": fn(u32);
        is_texture = c"glIsTexture": fn(u32) -> u8;
        is_renderbuffer = c"glIsRenderbuffer": fn(u32) -> u8;
        texture_view = c"glTextureView": fn(u32, u32, u32, u32, u32, u32, u32, u32);
        copy_image_sub_data = c"glCopyImageSubData": fn(u32, u32, i32, i32, i32, i32, u32, u32, i32, i32, i32, i32, i32, i32, i32);
    }
}

gl_fns! {
    /// GL 4.5's direct state access.
    struct Dsa {
        get_framebuffer_attachment_parameteriv = c"glGetNamedFramebufferAttachmentParameteriv": fn(u32, u32, u32, *mut i32);
        get_texture_level_parameteriv = c"glGetTextureLevelParameteriv": fn(u32, i32, u32, *mut i32);
        get_texture_parameteriv = c"glGetTextureParameteriv": fn(u32, u32, *mut i32);
        get_texture_parameterfv = c"glGetTextureParameterfv": fn(u32, u32, *mut f32);
        texture_parameteri = c"glTextureParameteri": fn(u32, u32, i32);
        texture_parameterf = c"glTextureParameterf": fn(u32, u32, f32);
        get_renderbuffer_parameteriv = c"glGetNamedRenderbufferParameteriv": fn(u32, u32, *mut i32);
        create_textures = c"glCreateTextures": fn(u32, i32, *mut u32);
        texture_storage_3d = c"glTextureStorage3D": fn(u32, i32, u32, i32, i32, i32);
        texture_storage_2d = c"glTextureStorage2D": fn(u32, i32, u32, i32, i32);
        texture_storage_3d_multisample = c"glTextureStorage3DMultisample": fn(u32, i32, u32, i32, i32, i32, u8);
        framebuffer_texture = c"glNamedFramebufferTexture": fn(u32, u32, u32, i32);
        framebuffer_renderbuffer = c"glNamedFramebufferRenderbuffer": fn(u32, u32, u32, u32);
        check_framebuffer_status = c"glCheckNamedFramebufferStatus": fn(u32, u32) -> u32;
        generate_texture_mipmap = c"glGenerateTextureMipmap": fn(u32);
        copy_texture_sub_image_2d = c"glCopyTextureSubImage2D": fn(u32, i32, i32, i32, i32, i32, i32, i32);
    }
}

gl_fns! {
    /// OpenGL ES 3.2's calls on bound objects.
    struct Binding {
        get_framebuffer_attachment_parameteriv = c"glGetFramebufferAttachmentParameteriv": fn(u32, u32, u32, *mut i32);
        get_tex_level_parameteriv = c"glGetTexLevelParameteriv": fn(u32, i32, u32, *mut i32);
        get_tex_parameteriv = c"glGetTexParameteriv": fn(u32, u32, *mut i32);
        get_tex_parameterfv = c"glGetTexParameterfv": fn(u32, u32, *mut f32);
        tex_parameteri = c"glTexParameteri": fn(u32, u32, i32);
        tex_parameterf = c"glTexParameterf": fn(u32, u32, f32);
        get_renderbuffer_parameteriv = c"glGetRenderbufferParameteriv": fn(u32, u32, *mut i32);
        bind_renderbuffer = c"glBindRenderbuffer": fn(u32, u32);
        bind_framebuffer = c"glBindFramebuffer": fn(u32, u32);
        tex_storage_3d = c"glTexStorage3D": fn(u32, i32, u32, i32, i32, i32);
        tex_storage_2d = c"glTexStorage2D": fn(u32, i32, u32, i32, i32);
        tex_storage_3d_multisample = c"glTexStorage3DMultisample": fn(u32, i32, u32, i32, i32, i32, u8);
        framebuffer_texture = c"glFramebufferTexture": fn(u32, u32, u32, i32);
        framebuffer_renderbuffer = c"glFramebufferRenderbuffer": fn(u32, u32, u32, u32);
        check_framebuffer_status = c"glCheckFramebufferStatus": fn(u32) -> u32;
        generate_mipmap = c"glGenerateMipmap": fn(u32);
        copy_tex_sub_image_2d = c"glCopyTexSubImage2D": fn(u32, i32, i32, i32, i32, i32, i32, i32);
    }
}

/// What a share group's contexts are ([`crate::auto::render_targets::context_api`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContextApi {
    /// Desktop OpenGL.
    Desktop,
    /// OpenGL ES 3.2 with texture views.
    Es,
    /// OpenGL ES with less: its render targets stay mono.
    EsWithout,
}

/// The API of the current context.
///
/// # Safety
/// A context is current on this thread.
pub unsafe fn context_api() -> ContextApi {
    let Some(c) = common() else {
        return ContextApi::Desktop;
    };
    // SAFETY: contract; NULL or NUL-terminated strings of the driver;
    // extension indices below their count.
    unsafe {
        let v = (c.get_string)(GL_VERSION);
        let es = !v.is_null()
            && std::ffi::CStr::from_ptr(v.cast())
                .to_bytes()
                .starts_with(b"OpenGL ES");
        if !es {
            return ContextApi::Desktop;
        }
        let int = |p| {
            let mut v = 0;
            (c.get_integerv)(p, &mut v);
            v
        };
        let version = (int(GL_MAJOR_VERSION), int(GL_MINOR_VERSION));
        let views = (0..int(GL_NUM_EXTENSIONS).max(0) as u32).any(|i| {
            let e = (c.get_stringi)(GL_EXTENSIONS, i);
            !e.is_null()
                && matches!(
                    std::ffi::CStr::from_ptr(e.cast()).to_bytes(),
                    b"GL_OES_texture_view" | b"GL_EXT_texture_view"
                )
        });
        if version >= (3, 2) && views && binding().is_some() {
            ContextApi::Es
        } else {
            crate::report::warn(&format!(
                "automatic stereo of render targets in OpenGL ES needs ES 3.2 with \
                 texture views (this context: ES {}.{}{}): what the program draws into \
                 its own framebuffer objects stays mono",
                version.0,
                version.1,
                if views {
                    ""
                } else {
                    ", no GL_OES_texture_view"
                },
            ));
            ContextApi::EsWithout
        }
    }
}

/// The shared table, loaded once.
pub fn common() -> Option<&'static Common> {
    static T: std::sync::OnceLock<Option<Common>> = std::sync::OnceLock::new();
    // SAFETY: gl_proc returns the named GL function or NULL.
    T.get_or_init(|| unsafe { Common::load(crate::auto::host::gl_proc) })
        .as_ref()
}

fn dsa() -> Option<&'static Dsa> {
    static T: std::sync::OnceLock<Option<Dsa>> = std::sync::OnceLock::new();
    T.get_or_init(|| {
        // SAFETY: gl_proc returns the named GL function or NULL.
        let t = unsafe { Dsa::load(crate::auto::host::gl_proc) };
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

fn binding() -> Option<&'static Binding> {
    static T: std::sync::OnceLock<Option<Binding>> = std::sync::OnceLock::new();
    // SAFETY: gl_proc returns the named GL function or NULL.
    T.get_or_init(|| unsafe { Binding::load(crate::auto::host::gl_proc) })
        .as_ref()
}

#[derive(Clone, Copy)]
enum Calls {
    Dsa(&'static Dsa),
    Binding(&'static Binding),
}

/// The calls for one kind of context (module docs).
#[derive(Clone, Copy)]
pub struct Gl {
    /// The calls both kinds share.
    pub c: &'static Common,
    calls: Calls,
}

/// The calls for contexts of `api`; None where render targets stay mono.
pub fn gl(api: ContextApi) -> Option<Gl> {
    let c = common()?;
    let calls = match api {
        ContextApi::Desktop => Calls::Dsa(dsa()?),
        ContextApi::Es => Calls::Binding(binding()?),
        ContextApi::EsWithout => return None,
    };
    Some(Gl { c, calls })
}

/// The binding query of a texture target.
fn binding_of(target: u32) -> u32 {
    match target {
        GL_TEXTURE_2D_ARRAY => 0x8C1D,
        GL_TEXTURE_2D_MULTISAMPLE => 0x9104,
        GL_TEXTURE_2D_MULTISAMPLE_ARRAY => 0x9105,
        _ => 0x8069, // GL_TEXTURE_BINDING_2D
    }
}

impl Gl {
    /// Whether this is the ES (binding) form.
    pub fn es(&self) -> bool {
        matches!(self.calls, Calls::Binding(_))
    }

    /// # Safety
    /// A context is current on this thread.
    pub unsafe fn integer(&self, pname: u32) -> i32 {
        let mut v = 0;
        // SAFETY: contract; one value.
        unsafe { (self.c.get_integerv)(pname, &mut v) };
        v
    }

    /// Runs `f` with `tex` bound to its target on the active unit (ES
    /// only; the program's binding put back after).
    unsafe fn on_texture<R>(&self, (name, target): Tex, f: impl FnOnce(u32) -> R) -> R {
        // SAFETY: contract of the callers.
        unsafe {
            let was = self.integer(binding_of(target)) as u32;
            (self.c.bind_texture)(target, name);
            let r = f(target);
            (self.c.bind_texture)(target, was);
            r
        }
    }

    /// Runs `f` with `fbo` bound for drawing (ES only; the program's
    /// draw framebuffer put back after).
    unsafe fn on_framebuffer<R>(&self, b: &Binding, fbo: u32, f: impl FnOnce() -> R) -> R {
        // SAFETY: contract of the callers.
        unsafe {
            let was = self.integer(GL_DRAW_FRAMEBUFFER_BINDING) as u32;
            if was != fbo {
                (b.bind_framebuffer)(GL_DRAW_FRAMEBUFFER, fbo);
            }
            let r = f();
            if was != fbo {
                (b.bind_framebuffer)(GL_DRAW_FRAMEBUFFER, was);
            }
            r
        }
    }

    /// Runs `f` with a query of `fbo`'s attachments: (point, pname) →
    /// value.
    ///
    /// # Safety
    /// A context is current on this thread; `fbo` is a framebuffer of it.
    pub unsafe fn attachments<R>(
        &self,
        fbo: u32,
        f: impl FnOnce(&dyn Fn(u32, u32) -> i32) -> R,
    ) -> R {
        // SAFETY: contract; one value per query.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => f(&|point, pname| {
                    let mut v = 0;
                    (d.get_framebuffer_attachment_parameteriv)(fbo, point, pname, &mut v);
                    v
                }),
                Calls::Binding(b) => self.on_framebuffer(b, fbo, || {
                    f(&|point, pname| {
                        let mut v = 0;
                        (b.get_framebuffer_attachment_parameteriv)(
                            GL_DRAW_FRAMEBUFFER,
                            point,
                            pname,
                            &mut v,
                        );
                        v
                    })
                }),
            }
        }
    }

    /// Level 0's `pname` of `tex`.
    ///
    /// # Safety
    /// A context is current on this thread; `tex` a texture of its target.
    pub unsafe fn level(&self, tex: Tex, pname: u32) -> i32 {
        let mut v = 0;
        // SAFETY: contract; one value.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.get_texture_level_parameteriv)(tex.0, 0, pname, &mut v),
                Calls::Binding(b) => self.on_texture(tex, |target| {
                    (b.get_tex_level_parameteriv)(target, 0, pname, &mut v)
                }),
            }
        }
        v
    }

    /// The integer parameter `pname` of `tex`.
    ///
    /// # Safety
    /// As [`Self::level`].
    pub unsafe fn texture_int(&self, tex: Tex, pname: u32) -> i32 {
        let mut v = 0;
        // SAFETY: contract; one value.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.get_texture_parameteriv)(tex.0, pname, &mut v),
                Calls::Binding(b) => {
                    self.on_texture(tex, |target| (b.get_tex_parameteriv)(target, pname, &mut v))
                }
            }
        }
        v
    }

    /// Copies the parameters `pnames` of `from` to `to` (as floats).
    ///
    /// # Safety
    /// As [`Self::level`], for both.
    pub unsafe fn copy_parameters(&self, from: Tex, to: Tex, pnames: &[u32]) {
        // SAFETY: contract; one value per query.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => {
                    for &p in pnames {
                        let mut v = 0.0f32;
                        (d.get_texture_parameterfv)(from.0, p, &mut v);
                        (d.texture_parameterf)(to.0, p, v);
                    }
                }
                Calls::Binding(b) => {
                    let mut values = vec![0.0f32; pnames.len()];
                    self.on_texture(from, |target| {
                        for (&p, v) in pnames.iter().zip(&mut values) {
                            (b.get_tex_parameterfv)(target, p, v);
                        }
                    });
                    self.on_texture(to, |target| {
                        for (&p, &v) in pnames.iter().zip(&values) {
                            (b.tex_parameterf)(target, p, v);
                        }
                    });
                }
            }
        }
    }

    /// Sets the integer parameter `pname` of `tex`.
    ///
    /// # Safety
    /// As [`Self::level`].
    pub unsafe fn set_texture_int(&self, tex: Tex, pname: u32, value: i32) {
        // SAFETY: contract.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.texture_parameteri)(tex.0, pname, value),
                Calls::Binding(b) => {
                    self.on_texture(tex, |target| (b.tex_parameteri)(target, pname, value))
                }
            }
        }
    }

    /// The parameter `pname` of renderbuffer `rb`.
    ///
    /// # Safety
    /// A context is current on this thread; `rb` a renderbuffer of it.
    pub unsafe fn renderbuffer(&self, rb: u32, pname: u32) -> i32 {
        let mut v = 0;
        // SAFETY: contract; one value.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.get_renderbuffer_parameteriv)(rb, pname, &mut v),
                Calls::Binding(b) => {
                    let was = self.integer(GL_RENDERBUFFER_BINDING) as u32;
                    (b.bind_renderbuffer)(GL_RENDERBUFFER, rb);
                    (b.get_renderbuffer_parameteriv)(GL_RENDERBUFFER, pname, &mut v);
                    (b.bind_renderbuffer)(GL_RENDERBUFFER, was);
                }
            }
        }
        v
    }

    /// A new texture of `target`.
    ///
    /// # Safety
    /// A context is current on this thread.
    pub unsafe fn new_texture(&self, target: u32) -> u32 {
        let mut name = 0;
        // SAFETY: contract; one name.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.create_textures)(target, 1, &mut name),
                Calls::Binding(_) => {
                    (self.c.gen_textures)(1, &mut name);
                    // The first binding makes the texture of its target.
                    self.on_texture((name, target), |_| ());
                }
            }
        }
        name
    }

    /// Immutable storage for `tex`: `levels` levels (or `samples`
    /// samples: `levels` is then 1) of `format`, `width` × `height` ×
    /// `depth` (depth 0: a 2D texture).
    ///
    /// # Safety
    /// A context is current on this thread; `tex` a new texture of its
    /// target.
    pub unsafe fn storage(
        &self,
        tex: Tex,
        levels: i32,
        (samples, fixed): (i32, bool),
        format: u32,
        (width, height, depth): (i32, i32, i32),
    ) {
        // SAFETY: contract.
        unsafe {
            match self.calls {
                Calls::Dsa(d) if samples > 0 => (d.texture_storage_3d_multisample)(
                    tex.0,
                    samples,
                    format,
                    width,
                    height,
                    depth,
                    u8::from(fixed),
                ),
                Calls::Dsa(d) if depth > 0 => {
                    (d.texture_storage_3d)(tex.0, levels, format, width, height, depth)
                }
                Calls::Dsa(d) => (d.texture_storage_2d)(tex.0, levels, format, width, height),
                Calls::Binding(b) => self.on_texture(tex, |target| {
                    if samples > 0 {
                        (b.tex_storage_3d_multisample)(
                            target,
                            samples,
                            format,
                            width,
                            height,
                            depth,
                            u8::from(fixed),
                        )
                    } else if depth > 0 {
                        (b.tex_storage_3d)(target, levels, format, width, height, depth)
                    } else {
                        (b.tex_storage_2d)(target, levels, format, width, height)
                    }
                }),
            }
        }
    }

    /// Attaches level `level` of texture `tex` (layered where it is an
    /// array) at `point` of `fbo`.
    ///
    /// # Safety
    /// A context is current on this thread; `fbo` a framebuffer of it.
    pub unsafe fn framebuffer_texture(&self, fbo: u32, point: u32, tex: u32, level: i32) {
        // SAFETY: contract.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.framebuffer_texture)(fbo, point, tex, level),
                Calls::Binding(b) => self.on_framebuffer(b, fbo, || {
                    (b.framebuffer_texture)(GL_DRAW_FRAMEBUFFER, point, tex, level)
                }),
            }
        }
    }

    /// Attaches renderbuffer `rb` at `point` of `fbo`.
    ///
    /// # Safety
    /// As [`Self::framebuffer_texture`].
    pub unsafe fn framebuffer_renderbuffer(&self, fbo: u32, point: u32, rb: u32) {
        // SAFETY: contract.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.framebuffer_renderbuffer)(fbo, point, GL_RENDERBUFFER, rb),
                Calls::Binding(b) => self.on_framebuffer(b, fbo, || {
                    (b.framebuffer_renderbuffer)(GL_DRAW_FRAMEBUFFER, point, GL_RENDERBUFFER, rb)
                }),
            }
        }
    }

    /// Whether `fbo` is complete for drawing.
    ///
    /// # Safety
    /// As [`Self::framebuffer_texture`].
    pub unsafe fn complete(&self, fbo: u32) -> bool {
        // SAFETY: contract.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.check_framebuffer_status)(fbo, GL_DRAW_FRAMEBUFFER),
                Calls::Binding(b) => self
                    .on_framebuffer(b, fbo, || (b.check_framebuffer_status)(GL_DRAW_FRAMEBUFFER)),
            }
        }
        .eq(&GL_FRAMEBUFFER_COMPLETE)
    }

    /// Makes the mipmaps of `tex` from its base level.
    ///
    /// # Safety
    /// As [`Self::level`]; `tex` complete at its base level.
    pub unsafe fn generate_mipmap(&self, tex: Tex) {
        // SAFETY: contract.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => (d.generate_texture_mipmap)(tex.0),
                Calls::Binding(b) => self.on_texture(tex, |target| (b.generate_mipmap)(target)),
            }
        }
    }

    /// Copies rectangle (x, y, w, h) of the read framebuffer into level
    /// `level` of the 2D texture `tex` at (xoff, yoff).
    ///
    /// # Safety
    /// As [`Self::level`]; the rectangle inside both.
    pub unsafe fn copy_sub_image_2d(
        &self,
        tex: Tex,
        level: i32,
        (xoff, yoff): (i32, i32),
        (x, y, w, h): (i32, i32, i32, i32),
    ) {
        // SAFETY: contract.
        unsafe {
            match self.calls {
                Calls::Dsa(d) => {
                    (d.copy_texture_sub_image_2d)(tex.0, level, xoff, yoff, x, y, w, h)
                }
                Calls::Binding(b) => self.on_texture(tex, |target| {
                    (b.copy_tex_sub_image_2d)(target, level, xoff, yoff, x, y, w, h)
                }),
            }
        }
    }
}

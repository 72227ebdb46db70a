//! The eyes of an automatic-stereo context: the emulated default
//! framebuffer's colour and depth/stencil as 2-layer array textures,
//! layer 0 the left eye and layer 1 the right ([`crate::auto`], "How a
//! draw reaches both eyes"), attached layered to the framebuffer object
//! the program draws into in place of framebuffer 0.
//!
//! The emulated framebuffer ([`crate::stereo::emulated`]) keeps its
//! per-eye 2D textures, which presentation composes and captures read: at
//! each present the layers are copied into the buffers being presented
//! ([`LayeredEyes::copy_eye`], glCopyImageSubData), so every output format
//! and capture works as for a quad-buffer program. A mono program has one
//! colour buffer to draw into: every draw and read buffer it selects
//! (GL_BACK, GL_FRONT…) is the layered one, which stands for its back
//! buffer (front for a single-buffered visual).

use crate::auto::gl_fns;
use crate::error::{Error, Result};
use crate::gl::Gl;
use crate::gl::enums::*;
use crate::math::Eye;

const GL_TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const GL_DEPTH_STENCIL: u32 = 0x84F9;
const GL_UNSIGNED_INT_24_8: u32 = 0x84FA;
const GL_DEPTH_COMPONENT: u32 = 0x1902;
const GL_UNSIGNED_INT: u32 = 0x1405;
const GL_DEPTH_COMPONENT24: u32 = 0x81A6;
const GL_DEPTH_ATTACHMENT: u32 = 0x8D00;
const GL_DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;

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

/// The layer of `eye`.
pub fn layer(eye: Eye) -> i32 {
    match eye {
        Eye::Left => 0,
        Eye::Right => 1,
    }
}

/// The layered colour and depth/stencil of one emulated framebuffer.
#[derive(Clone, Copy, Debug)]
pub struct LayeredEyes {
    api: LayeredApi,
    /// The colour array (RGBA8, 2 layers).
    pub colour: u32,
    /// The depth (and stencil) array, 0 for a visual with neither.
    pub depth: u32,
    /// GL_DEPTH_STENCIL_ATTACHMENT or GL_DEPTH_ATTACHMENT.
    depth_attachment: u32,
    width: u32,
    height: u32,
}

impl LayeredEyes {
    /// Makes the arrays, `width` × `height` × 2, colour in `colour_format`
    /// (cleared to transparent black, or opaque black when `opaque`),
    /// depth in `depth_format` (GL_DEPTH24_STENCIL8, GL_DEPTH_COMPONENT24
    /// or 0 for none), in the context current (sharing the program's
    /// objects); `fbo` is a framebuffer object of that context for the
    /// clear.
    ///
    /// # Safety
    /// A context of `gl`'s backend must be current on this thread.
    pub unsafe fn allocate(
        gl: &Gl,
        api: LayeredApi,
        (width, height): (u32, u32),
        (colour_format, depth_format): (u32, u32),
        opaque: bool,
        fbo: u32,
    ) -> Result<LayeredEyes> {
        // SAFETY: contract; no data uploaded.
        unsafe {
            let colour = gl.gen_texture_of(GL_TEXTURE_2D_ARRAY);
            let depth = if depth_format != 0 {
                gl.gen_texture_of(GL_TEXTURE_2D_ARRAY)
            } else {
                0
            };
            let eyes = LayeredEyes {
                api,
                colour,
                depth,
                depth_attachment: if depth_format == GL_DEPTH_COMPONENT24 {
                    GL_DEPTH_ATTACHMENT
                } else {
                    GL_DEPTH_STENCIL_ATTACHMENT
                },
                width,
                height,
            };
            let storage = [
                (colour, colour_format, GL_RGBA, GL_UNSIGNED_BYTE),
                (
                    depth,
                    depth_format,
                    if depth_format == GL_DEPTH_COMPONENT24 {
                        GL_DEPTH_COMPONENT
                    } else {
                        GL_DEPTH_STENCIL
                    },
                    if depth_format == GL_DEPTH_COMPONENT24 {
                        GL_UNSIGNED_INT
                    } else {
                        GL_UNSIGNED_INT_24_8
                    },
                ),
            ];
            for (tex, internal, format, ty) in storage {
                if tex == 0 {
                    continue;
                }
                gl.BindTexture(GL_TEXTURE_2D_ARRAY, tex);
                (api.tex_image_3d)(
                    GL_TEXTURE_2D_ARRAY,
                    0,
                    internal as i32,
                    width as i32,
                    height as i32,
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
            }
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
            if let Err(e) = gl.check("allocating the layered eyes") {
                eyes.release(gl);
                return Err(e);
            }
            // New storage is undefined: clear both layers.
            gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
            (api.framebuffer_texture)(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, colour, 0);
            gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
            gl.Disable(GL_SCISSOR_TEST);
            gl.ColorMask(1, 1, 1, 1);
            gl.ClearColor(0.0, 0.0, 0.0, if opaque { 1.0 } else { 0.0 });
            let complete = gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
            if complete {
                gl.Clear(GL_COLOR_BUFFER_BIT);
            }
            (api.framebuffer_texture)(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0);
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            if !complete {
                eyes.release(gl);
                return Err(Error::Gl(
                    "the driver cannot render to a layered RGBA8 array texture".into(),
                ));
            }
            Ok(eyes)
        }
    }

    /// Width and height of each eye.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Attaches the arrays, every layer, to the framebuffer object bound
    /// at `target`: colour at GL_COLOR_ATTACHMENT0.
    ///
    /// # Safety
    /// A context sharing the arrays must be current with the object bound.
    pub unsafe fn attach(&self, target: u32) {
        // SAFETY: contract.
        unsafe {
            (self.api.framebuffer_texture)(target, GL_COLOR_ATTACHMENT0, self.colour, 0);
            if self.depth != 0 {
                (self.api.framebuffer_texture)(target, self.depth_attachment, self.depth, 0);
            }
        }
    }

    /// Attaches `eye`'s layers only (the slow path: draws whose vertices
    /// cannot choose a layer), or every layer again (None).
    ///
    /// # Safety
    /// As [`LayeredEyes::attach`].
    pub unsafe fn attach_eye(&self, target: u32, eye: Option<Eye>) {
        let Some(eye) = eye else {
            // SAFETY: contract.
            return unsafe { self.attach(target) };
        };
        // SAFETY: contract.
        unsafe {
            (self.api.framebuffer_texture_layer)(
                target,
                GL_COLOR_ATTACHMENT0,
                self.colour,
                0,
                layer(eye),
            );
            if self.depth != 0 {
                (self.api.framebuffer_texture_layer)(
                    target,
                    self.depth_attachment,
                    self.depth,
                    0,
                    layer(eye),
                );
            }
        }
    }

    /// Copies `eye`'s colour into the 2D texture `texture` (of the same
    /// size): what presentation reads.
    ///
    /// # Safety
    /// A context sharing both textures must be current.
    pub unsafe fn copy_eye(&self, eye: Eye, texture: u32) {
        // SAFETY: contract; both are width × height.
        unsafe {
            (self.api.copy_image_sub_data)(
                self.colour,
                GL_TEXTURE_2D_ARRAY,
                0,
                0,
                0,
                layer(eye),
                texture,
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

    /// Attaches the left eye's depth to the framebuffer bound at `target`
    /// (None: detaches it), for reading it back.
    ///
    /// # Safety
    /// As [`LayeredEyes::attach`].
    pub unsafe fn attach_left_depth(&self, target: u32, on: bool) {
        // SAFETY: contract.
        unsafe {
            (self.api.framebuffer_texture_layer)(
                target,
                self.depth_attachment,
                if on { self.depth } else { 0 },
                0,
                0,
            )
        }
    }

    /// Deletes the arrays.
    ///
    /// # Safety
    /// A context sharing them must be current.
    pub unsafe fn release(&self, gl: &Gl) {
        // SAFETY: contract; names made here.
        unsafe {
            gl.delete_textures(&[self.colour]);
            if self.depth != 0 {
                gl.delete_textures(&[self.depth]);
            }
        }
    }
}

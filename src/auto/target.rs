//! The eyes as layers: a framebuffer object whose colour and depth/stencil
//! attachments are 2-layer array textures, layer 0 the left eye and layer
//! 1 the right. What the emulated default framebuffer
//! ([`crate::stereo::emulated`]) becomes under `--auto`, here in its
//! smallest form (one colour buffer) for the mechanisms and their tests.
//!
//! Why layers (BENCHMARKS.md, "Automatic stereo: per-eye mechanisms"):
//! llvmpipe ends its scene — binning stops, the rasterizer threads are
//! woken, ≈ 12 µs — at every framebuffer change: a draw-buffer switch or
//! a re-attachment costs as much (a viewport change twice); with the eyes
//! as layers and the eye chosen by a uniform that the last vertex stage
//! writes to gl_Layer, a draw reaches both eyes with no framebuffer state
//! changing at all, for 0.96–1.09x of what the program pays drawing both
//! eyes itself (light scenes, 400x300; [`crate::auto`] has the rest,
//! and the double-width alternative). Each eye has its own depth and stencil (the layers of the
//! depth array), so draws interleaved eye by eye keep their depth tests,
//! and glClear clears every layer at once.
//!
//! Draws whose vertices cannot choose a layer (fixed-function vertex
//! processing without the layer's stand-in shader, ES shaders) go to one
//! eye at a time by attaching that eye's layers ([`EyeTarget::bind_eye`])
//! and attaching both again afterwards ([`EyeTarget::bind_layered`]): the
//! slow path, a scene flush per eye.

use crate::auto::gl_fns;
use crate::math::Eye;

const GL_TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const GL_RGBA8: u32 = 0x8058;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;
const GL_DEPTH24_STENCIL8: u32 = 0x88F0;
const GL_DEPTH_STENCIL: u32 = 0x84F9;
const GL_UNSIGNED_INT_24_8: u32 = 0x84FA;
const GL_TEXTURE_MIN_FILTER: u32 = 0x2801;
const GL_NEAREST: i32 = 0x2600;
const GL_FRAMEBUFFER: u32 = 0x8D40;
const GL_DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const GL_READ_FRAMEBUFFER: u32 = 0x8CA8;
const GL_COLOR_ATTACHMENT0: u32 = 0x8CE0;
const GL_DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;
const GL_FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;
const GL_READ_FRAMEBUFFER_BINDING: u32 = 0x8CAA;

gl_fns! {
    /// The GL functions of the eye target and the per-eye mechanisms.
    pub struct TargetFns {
        gen_textures = c"glGenTextures": fn(i32, *mut u32);
        delete_textures = c"glDeleteTextures": fn(i32, *const u32);
        bind_texture = c"glBindTexture": fn(u32, u32);
        tex_image_3d = c"glTexImage3D": fn(u32, i32, i32, i32, i32, i32, i32, u32, u32, *const std::ffi::c_void);
        tex_parameteri = c"glTexParameteri": fn(u32, u32, i32);
        gen_framebuffers = c"glGenFramebuffers": fn(i32, *mut u32);
        delete_framebuffers = c"glDeleteFramebuffers": fn(i32, *const u32);
        bind_framebuffer = c"glBindFramebuffer": fn(u32, u32);
        framebuffer_texture = c"glFramebufferTexture": fn(u32, u32, u32, i32);
        framebuffer_texture_layer = c"glFramebufferTextureLayer": fn(u32, u32, u32, i32, i32);
        check_framebuffer_status = c"glCheckFramebufferStatus": fn(u32) -> u32;
        get_integerv = c"glGetIntegerv": fn(u32, *mut i32);
        read_pixels = c"glReadPixels": fn(i32, i32, i32, i32, u32, u32, *mut std::ffi::c_void);
    }
}

/// A layered framebuffer object: 2-layer RGBA8 colour and depth/stencil
/// arrays (module docs).
pub struct EyeTarget {
    /// The framebuffer object.
    pub framebuffer: u32,
    /// The colour array texture (layer 0 left, 1 right).
    pub colour: u32,
    /// The depth/stencil array texture.
    pub depth: u32,
    /// Width of each eye.
    pub width: i32,
    /// Height of each eye.
    pub height: i32,
}

fn layer(eye: Eye) -> i32 {
    match eye {
        Eye::Left => 0,
        Eye::Right => 1,
    }
}

impl EyeTarget {
    /// Makes the target, bound to GL_FRAMEBUFFER with both layers attached.
    /// None when the driver does not complete it.
    ///
    /// # Safety
    /// A GL context must be current on this thread.
    pub unsafe fn create(fns: &TargetFns, width: i32, height: i32) -> Option<EyeTarget> {
        let mut tex = [0u32; 2];
        let mut framebuffer = 0;
        // SAFETY: contract; arrays sized as GL is told, no data uploaded.
        unsafe {
            (fns.gen_textures)(2, tex.as_mut_ptr());
            for (t, (internal, format, ty)) in tex.iter().zip([
                (GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE),
                (GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8),
            ]) {
                (fns.bind_texture)(GL_TEXTURE_2D_ARRAY, *t);
                (fns.tex_image_3d)(
                    GL_TEXTURE_2D_ARRAY,
                    0,
                    internal as i32,
                    width,
                    height,
                    2,
                    0,
                    format,
                    ty,
                    std::ptr::null(),
                );
                (fns.tex_parameteri)(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            }
            (fns.bind_texture)(GL_TEXTURE_2D_ARRAY, 0);
            (fns.gen_framebuffers)(1, &mut framebuffer);
            (fns.bind_framebuffer)(GL_FRAMEBUFFER, framebuffer);
            let target = EyeTarget {
                framebuffer,
                colour: tex[0],
                depth: tex[1],
                width,
                height,
            };
            target.bind_layered(fns);
            if (fns.check_framebuffer_status)(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE {
                target.destroy(fns);
                return None;
            }
            Some(target)
        }
    }

    /// Attaches both layers (every eye) to the bound draw framebuffer,
    /// which must be this target's.
    ///
    /// # Safety
    /// A GL context must be current on this thread, this target's object
    /// bound for drawing.
    pub unsafe fn bind_layered(&self, fns: &TargetFns) {
        // SAFETY: contract.
        unsafe {
            (fns.framebuffer_texture)(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, self.colour, 0);
            (fns.framebuffer_texture)(
                GL_DRAW_FRAMEBUFFER,
                GL_DEPTH_STENCIL_ATTACHMENT,
                self.depth,
                0,
            );
        }
    }

    /// Attaches `eye`'s layers only (for draws that cannot choose a layer).
    ///
    /// # Safety
    /// As [`EyeTarget::bind_layered`].
    pub unsafe fn bind_eye(&self, fns: &TargetFns, eye: Eye) {
        // SAFETY: contract.
        unsafe {
            (fns.framebuffer_texture_layer)(
                GL_DRAW_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0,
                self.colour,
                0,
                layer(eye),
            );
            (fns.framebuffer_texture_layer)(
                GL_DRAW_FRAMEBUFFER,
                GL_DEPTH_STENCIL_ATTACHMENT,
                self.depth,
                0,
                layer(eye),
            );
        }
    }

    /// `eye`'s colour, RGBA8 rows bottom first, read through a scratch
    /// framebuffer (the bindings are restored).
    ///
    /// # Safety
    /// A GL context must be current on this thread, rendering finished or
    /// not (glReadPixels waits).
    pub unsafe fn read(&self, fns: &TargetFns, eye: Eye) -> Vec<u8> {
        let mut out = vec![0u8; (self.width * self.height * 4) as usize];
        // SAFETY: contract; the buffer holds width x height RGBA8 pixels.
        unsafe {
            let mut read = 0;
            (fns.get_integerv)(GL_READ_FRAMEBUFFER_BINDING, &mut read);
            let mut fb = 0;
            (fns.gen_framebuffers)(1, &mut fb);
            (fns.bind_framebuffer)(GL_READ_FRAMEBUFFER, fb);
            (fns.framebuffer_texture_layer)(
                GL_READ_FRAMEBUFFER,
                GL_COLOR_ATTACHMENT0,
                self.colour,
                0,
                layer(eye),
            );
            (fns.read_pixels)(
                0,
                0,
                self.width,
                self.height,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                out.as_mut_ptr().cast(),
            );
            (fns.bind_framebuffer)(GL_READ_FRAMEBUFFER, read as u32);
            (fns.delete_framebuffers)(1, &fb);
        }
        out
    }

    /// Deletes the target's objects (a binding of its framebuffer object
    /// reverts to 0, as GL does for a deleted bound object).
    ///
    /// # Safety
    /// A GL context must be current on this thread.
    pub unsafe fn destroy(&self, fns: &TargetFns) {
        // SAFETY: contract; names this target made.
        unsafe {
            (fns.delete_framebuffers)(1, &self.framebuffer);
            (fns.delete_textures)(2, [self.colour, self.depth].as_ptr());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::auto::testgl::{GL_COLOR_BUFFER_BIT, GL_DEPTH_BUFFER_BIT, ProgramFns};
    use crate::testing::egl_context;

    gl_fns! {
        struct More {
            clear_color = c"glClearColor": fn(f32, f32, f32, f32);
            clear = c"glClear": fn(u32);
            blit_framebuffer = c"glBlitFramebuffer": fn(i32, i32, i32, i32, i32, i32, i32, i32, u32, u32);
            new_list = c"glNewList": fn(u32, u32);
            end_list = c"glEndList": fn();
            call_list = c"glCallList": fn(u32);
            get_uniformfv = c"glGetUniformfv": fn(u32, i32, *mut f32);
        }
    }

    const W: i32 = 8;
    const H: i32 = 4;

    unsafe fn pixel(fns: &TargetFns) -> [u8; 4] {
        let mut p = [0u8; 4];
        // SAFETY: a context is current; one pixel.
        unsafe { (fns.read_pixels)(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, p.as_mut_ptr().cast()) };
        p
    }

    /// What the design relies on: reads of a layered framebuffer see layer
    /// 0 (the left eye), a blit into it writes layer 0 only, one glClear
    /// clears both layers, and glUniform is compiled into display lists.
    #[test]
    fn layered_targets_read_and_blit_layer_0_and_clear_every_layer() {
        let cx = egl_context();
        let get = |n: &std::ffi::CStr| cx.display.platform().get_proc_address(n);
        // SAFETY: the EGL context is current on this thread.
        unsafe {
            let fns = TargetFns::load(get).unwrap();
            let more = More::load(get).unwrap();
            let p = ProgramFns::load(get).unwrap();
            let t = EyeTarget::create(&fns, W, H).unwrap();
            (more.clear_color)(0.0, 0.0, 1.0, 1.0);
            (more.clear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            assert_eq!(t.read(&fns, Eye::Left)[..4], [0, 0, 255, 255]);
            assert_eq!(
                t.read(&fns, Eye::Right)[..4],
                [0, 0, 255, 255],
                "one clear, both layers"
            );
            t.bind_eye(&fns, Eye::Right);
            (more.clear_color)(1.0, 0.0, 0.0, 1.0);
            (more.clear)(GL_COLOR_BUFFER_BIT);
            t.bind_layered(&fns);
            (fns.bind_framebuffer)(GL_READ_FRAMEBUFFER, t.framebuffer);
            assert_eq!(
                pixel(&fns),
                [0, 0, 255, 255],
                "glReadPixels of a layered framebuffer: layer 0"
            );
            // A blit from a green framebuffer into the layered one.
            let src = EyeTarget::create(&fns, W, H).unwrap();
            (more.clear_color)(0.0, 1.0, 0.0, 1.0);
            (more.clear)(GL_COLOR_BUFFER_BIT);
            (fns.bind_framebuffer)(GL_READ_FRAMEBUFFER, src.framebuffer);
            (fns.bind_framebuffer)(GL_DRAW_FRAMEBUFFER, t.framebuffer);
            (more.blit_framebuffer)(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, 0x2600);
            assert_eq!(t.read(&fns, Eye::Left)[..4], [0, 255, 0, 255]);
            assert_eq!(
                t.read(&fns, Eye::Right)[..4],
                [255, 0, 0, 255],
                "a blit writes layer 0 only"
            );
            // glUniform in a display list acts when the list is called.
            let program = p.program(&[(
                0x8B31,
                "#version 330\nuniform vec4 u;\nvoid main() { gl_Position = u; }\n",
            )]);
            (p.use_program)(program);
            let u = (p.get_uniform_location)(program, c"u".as_ptr());
            (more.new_list)(1, 0x1300); // GL_COMPILE
            (p.uniform4f)(u, 1.0, 2.0, 3.0, 4.0);
            (more.end_list)();
            let mut v = [0.0f32; 4];
            (more.get_uniformfv)(program, u, v.as_mut_ptr());
            assert_eq!(v, [0.0; 4], "compiled, not executed");
            (more.call_list)(1);
            (more.get_uniformfv)(program, u, v.as_mut_ptr());
            assert_eq!(v, [1.0, 2.0, 3.0, 4.0], "executed by glCallList");
            assert_eq!((p.get_error)(), 0);
            src.destroy(&fns);
            t.destroy(&fns);
        }
    }
}

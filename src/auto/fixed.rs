//! Fixed-function draws in both eyes: the eye's projection in effect at
//! each draw (the matrix form of the rule), raster positions for
//! glDrawPixels, glBitmap and glCopyPixels, and the draw issued once per
//! eye into that eye's layers of the [`EyeTarget`].
//!
//! # The matrix form
//!
//! For fixed-function vertex processing the clip-space rule
//! `x' = x + e·s·(w − C)` is row 0 of the projection `P` replaced by
//! `row0 + e·s·row3 − e·s·C·(0, 0, 0, 1)` (REFERENCE.md), exact for
//! vertices whose modelview output has w = 1 (glVertex2/3, and glVertex4
//! with w = 1). A projection whose row 3 is (0, 0, 0, 1) — glOrtho,
//! gluOrtho2D, the identity of 2D overlays — gives every such vertex
//! w_clip = 1: the rule leaves those alone, so that projection is used
//! as it is ([`eye_projection`]). Under STEREO_PROJECTION_ORTHO_NV the
//! program asked for orthographic stereo: every projection gets the
//! window-depth form of [`crate::shims::nv3dvision::ortho_clip_shift`].
//!
//! The projection is read at the draw (glGetDoublev(GL_PROJECTION_MATRIX):
//! the one in effect, whatever matrix calls, display lists or
//! glPopAttrib put it there), each eye's loaded with glLoadMatrixd, and
//! the program's own restored exactly after the second eye (GL keeps
//! floats: the doubles read back load the same floats), with the program's
//! matrix mode.
//!
//! # Raster positions
//!
//! glRasterPos transforms its point when it is called, so the raster
//! position a glDrawPixels, glBitmap or glCopyPixels uses is the mono one.
//! GL keeps it in window coordinates with its clip w
//! (GL_CURRENT_RASTER_POSITION = (x_w, y_w, z_w, w_c)), which is all the
//! rule needs: the eye's position is `x_w + e·s·(w_c − C)/w_c · width/2`
//! for a viewport `width` wide ([`raster_shift`]; w_c = 1, as after
//! glWindowPos, moves nothing). The layer moves the raster position there
//! with `glBitmap(0, 0, 0, 0, dx, 0, NULL)` — the one GL call that moves it
//! without touching its colour, texture coordinates or validity — draws,
//! and moves it back; glBitmap's own advance (xmove, ymove) is kept once,
//! as in mono ([`FixedDraw::bitmap`]).
//!
//! # Cost
//!
//! Fixed-function vertices cannot choose a layer, so this path attaches
//! each eye's layers in turn ([`EyeTarget::bind_eye`]): two framebuffer
//! changes per draw, each a llvmpipe scene flush (BENCHMARKS.md, variant
//! c2ff). The fast path for fixed-function programs is a vertex shader of
//! the layer standing in for fixed-function vertex processing (variant
//! dff; [`crate::auto`], "Fixed function").

use glam::{DMat4, DVec4};

use crate::auto::gl_fns;
use crate::auto::target::{EyeTarget, TargetFns};
use crate::math::Eye;
use crate::math::seeds::nv_clip_shift;
use crate::shims::nv3dvision::{ProjectionMethod, StereoSettings, ortho_clip_shift};

const GL_MATRIX_MODE: u32 = 0x0BA0;
const GL_PROJECTION: u32 = 0x1701;
const GL_PROJECTION_MATRIX: u32 = 0x0BA7;
const GL_CURRENT_RASTER_POSITION: u32 = 0x0B07;
const GL_CURRENT_RASTER_POSITION_VALID: u32 = 0x0B08;
const GL_VIEWPORT: u32 = 0x0BA2;

/// The projection `eye`'s fixed-function draws use for the mono
/// projection `mono` (module docs), or None where `mono` is used as it is:
/// no separation, or an orthographic projection under the PERSPECTIVE
/// method.
pub fn eye_projection(settings: &StereoSettings, mono: &DMat4, eye: Eye) -> Option<DMat4> {
    let s = settings.effective_separation();
    if s == 0.0 {
        return None;
    }
    let c = settings.convergence() as f64;
    match settings.projection() {
        ProjectionMethod::Perspective if mono.row(3) == DVec4::W => None,
        ProjectionMethod::Perspective => nv_clip_shift(mono, s, c, eye).ok(),
        ProjectionMethod::Ortho => ortho_clip_shift(mono, s, c, eye).ok(),
    }
}

/// How far (window pixels, +x) `eye`'s raster position lies from the mono
/// one `raster` = GL_CURRENT_RASTER_POSITION (x_w, y_w, z_w, w_c), in a
/// viewport `width` pixels wide: `e·s·(w_c − C)/w_c · width/2`; 0 for
/// w_c = 1 (and w_c ≤ 0, which a valid raster position does not have).
/// Under the ORTHO method the window depth z_w stands for the depth:
/// `e·s·(z_w − C) · width/2`.
pub fn raster_shift(settings: &StereoSettings, raster: [f32; 4], width: f64, eye: Eye) -> f64 {
    let k = eye.sign() * settings.effective_separation();
    let c = settings.convergence() as f64;
    let w = raster[3] as f64;
    let ndc = match settings.projection() {
        ProjectionMethod::Perspective if w == 1.0 || w <= 0.0 => 0.0,
        ProjectionMethod::Perspective => k * (w - c) / w,
        ProjectionMethod::Ortho => k * (raster[2] as f64 - c),
    };
    ndc * width / 2.0
}

gl_fns! {
    /// The GL functions fixed-function draws need.
    pub struct FixedFns {
        get_integerv = c"glGetIntegerv": fn(u32, *mut i32);
        get_doublev = c"glGetDoublev": fn(u32, *mut f64);
        get_floatv = c"glGetFloatv": fn(u32, *mut f32);
        matrix_mode = c"glMatrixMode": fn(u32);
        load_matrixd = c"glLoadMatrixd": fn(*const f64);
        bitmap = c"glBitmap": fn(i32, i32, f32, f32, f32, f32, *const u8);
    }
}

/// One fixed-function program's draws, sent to both eyes of `target`
/// with `settings` (module docs). The program's draw framebuffer must be
/// `target`'s object, with both layers attached.
pub struct FixedDraw<'a> {
    /// GL functions.
    pub fns: &'a FixedFns,
    /// The target's GL functions.
    pub target_fns: &'a TargetFns,
    /// The eyes.
    pub target: &'a EyeTarget,
    /// Separation, convergence, method.
    pub settings: StereoSettings,
}

const EYES: [Eye; 2] = [Eye::Left, Eye::Right];

impl FixedDraw<'_> {
    /// One draw call (`draw` makes it: glDrawArrays, glEnd's replay,
    /// glCallList…) with each eye's projection, into each eye.
    ///
    /// # Safety
    /// A GL context must be current on this thread, the target bound for
    /// drawing, no program or pipeline in use (fixed-function vertices).
    pub unsafe fn draw(&self, mut draw: impl FnMut()) {
        // SAFETY: contract; matrix queries write 16 values.
        unsafe {
            let mut mono = [0.0f64; 16];
            (self.fns.get_doublev)(GL_PROJECTION_MATRIX, mono.as_mut_ptr());
            let mono_m = DMat4::from_cols_array(&mono);
            let eyes = EYES.map(|e| eye_projection(&self.settings, &mono_m, e));
            let mut mode = 0;
            if eyes.iter().any(Option::is_some) {
                (self.fns.get_integerv)(GL_MATRIX_MODE, &mut mode);
                (self.fns.matrix_mode)(GL_PROJECTION);
            }
            for (eye, projection) in EYES.iter().zip(&eyes) {
                self.target.bind_eye(self.target_fns, *eye);
                if let Some(p) = projection {
                    (self.fns.load_matrixd)(p.to_cols_array().as_ptr());
                }
                draw();
            }
            if eyes.iter().any(Option::is_some) {
                (self.fns.load_matrixd)(mono.as_ptr());
                (self.fns.matrix_mode)(mode as u32);
            }
            self.target.bind_layered(self.target_fns);
        }
    }

    /// The raster position's shift per eye, or None when the raster
    /// position is invalid (GL then draws nothing).
    unsafe fn raster_shifts(&self) -> Option<[f64; 2]> {
        // SAFETY: contract of the callers; the queries write 1, 4 and 4 values.
        unsafe {
            let mut valid = 0;
            (self.fns.get_integerv)(GL_CURRENT_RASTER_POSITION_VALID, &mut valid);
            if valid == 0 {
                return None;
            }
            let mut raster = [0.0f32; 4];
            (self.fns.get_floatv)(GL_CURRENT_RASTER_POSITION, raster.as_mut_ptr());
            let mut viewport = [0i32; 4];
            (self.fns.get_integerv)(GL_VIEWPORT, viewport.as_mut_ptr());
            Some(EYES.map(|e| raster_shift(&self.settings, raster, viewport[2] as f64, e)))
        }
    }

    /// Moves the raster position by (dx, dy) and nothing else.
    unsafe fn move_raster(&self, dx: f64, dy: f64) {
        if dx != 0.0 || dy != 0.0 {
            // SAFETY: contract of the callers; a 0x0 bitmap reads nothing.
            unsafe { (self.fns.bitmap)(0, 0, 0.0, 0.0, dx as f32, dy as f32, std::ptr::null()) };
        }
    }

    /// glDrawPixels or glCopyPixels (`draw` makes the call) at each eye's
    /// raster position, into each eye. glCopyPixels reads the read
    /// framebuffer as bound: the caller points it at the same eye.
    ///
    /// # Safety
    /// As [`FixedDraw::draw`].
    pub unsafe fn pixels(&self, mut draw: impl FnMut(Eye)) {
        // SAFETY: contract.
        unsafe {
            let shifts = self.raster_shifts().unwrap_or([0.0; 2]);
            for (eye, dx) in EYES.iter().zip(shifts) {
                self.target.bind_eye(self.target_fns, *eye);
                self.move_raster(dx, 0.0);
                draw(*eye);
                self.move_raster(-dx, 0.0);
            }
            self.target.bind_layered(self.target_fns);
        }
    }

    /// glBitmap(…, xmove, ymove, …) (`draw` makes the call) at each eye's
    /// raster position, into each eye; afterwards the raster position has
    /// moved by (xmove, ymove) once, as in mono.
    ///
    /// # Safety
    /// As [`FixedDraw::draw`].
    pub unsafe fn bitmap(&self, xmove: f32, ymove: f32, mut draw: impl FnMut()) {
        // SAFETY: contract.
        unsafe {
            let Some([left, right]) = self.raster_shifts() else {
                // Invalid: GL draws nothing and does not move it; once is mono.
                draw();
                return;
            };
            self.target.bind_eye(self.target_fns, Eye::Left);
            self.move_raster(left, 0.0);
            draw();
            self.move_raster(-left - xmove as f64, -ymove as f64);
            self.target.bind_eye(self.target_fns, Eye::Right);
            self.move_raster(right, 0.0);
            draw();
            self.move_raster(-right, 0.0);
            self.target.bind_layered(self.target_fns);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::auto::testgl::*;
    use crate::shims::nv3dvision::{GL_STEREO_CONVERGENCE_NV, GL_STEREO_SEPARATION_NV};
    use crate::testing::egl_context;

    const W: i32 = 160;
    const H: i32 = 120;
    const SEPARATION: f32 = 100.0;
    const CONVERGENCE: f32 = 4.0;

    fn settings() -> StereoSettings {
        let mut s = StereoSettings::new(true);
        s.parameter_f(GL_STEREO_SEPARATION_NV, SEPARATION).unwrap();
        s.parameter_f(GL_STEREO_CONVERGENCE_NV, CONVERGENCE)
            .unwrap();
        s
    }

    /// glFrustum's matrix.
    fn frustum(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> DMat4 {
        DMat4::from_cols(
            DVec4::new(2.0 * n / (r - l), 0.0, 0.0, 0.0),
            DVec4::new(0.0, 2.0 * n / (t - b), 0.0, 0.0),
            DVec4::new(
                (r + l) / (r - l),
                (t + b) / (t - b),
                -(f + n) / (f - n),
                -1.0,
            ),
            DVec4::new(0.0, 0.0, -2.0 * f * n / (f - n), 0.0),
        )
    }

    /// glOrtho's matrix.
    fn ortho(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> DMat4 {
        DMat4::from_cols(
            DVec4::new(2.0 / (r - l), 0.0, 0.0, 0.0),
            DVec4::new(0.0, 2.0 / (t - b), 0.0, 0.0),
            DVec4::new(0.0, 0.0, -2.0 / (f - n), 0.0),
            DVec4::new(
                -(r + l) / (r - l),
                -(t + b) / (t - b),
                -(f + n) / (f - n),
                1.0,
            ),
        )
    }

    /// How a frame's projections and drawing calls are made: by the mono
    /// program under the layer, or by a program drawing one eye itself.
    trait Frame {
        fn projection(&mut self, p: &ProgramFns, mono: DMat4);
        fn draw(&mut self, f: &mut dyn FnMut());
        fn pixels(&mut self, f: &mut dyn FnMut());
        fn bitmap(&mut self, xmove: f32, ymove: f32, f: &mut dyn FnMut());
        /// glRasterPos* (`f` makes the call).
        fn raster_pos(&mut self, f: &mut dyn FnMut()) {
            f()
        }
    }

    unsafe fn load_projection(p: &ProgramFns, m: &DMat4) {
        // SAFETY: a context is current (the tests).
        unsafe {
            (p.matrix_mode)(super::GL_PROJECTION);
            (p.load_matrixd)(m.to_cols_array().as_ptr());
            (p.matrix_mode)(GL_MODELVIEW);
        }
    }

    /// The mono program under the layer: each call goes through
    /// [`FixedDraw`], as the layer's wrappers will send it.
    struct UnderLayer<'a>(FixedDraw<'a>);

    impl Frame for UnderLayer<'_> {
        fn projection(&mut self, p: &ProgramFns, mono: DMat4) {
            // SAFETY: a context is current.
            unsafe { load_projection(p, &mono) };
        }
        fn draw(&mut self, f: &mut dyn FnMut()) {
            // SAFETY: a context is current, the target bound, no program.
            unsafe { self.0.draw(f) };
        }
        fn pixels(&mut self, f: &mut dyn FnMut()) {
            // SAFETY: as above.
            unsafe { self.0.pixels(|_| f()) };
        }
        fn bitmap(&mut self, xmove: f32, ymove: f32, f: &mut dyn FnMut()) {
            // SAFETY: as above.
            unsafe { self.0.bitmap(xmove, ymove, f) };
        }
    }

    /// The oracle: a program drawing one eye itself, with the rule of
    /// REFERENCE.md applied by hand to each projection it loads (row 0
    /// becomes row0 + e·s·row3 − e·s·C·(0,0,0,1); orthographic ones, whose
    /// w is 1, are left alone), and its raster positions transformed by GL
    /// under that projection.
    struct ByHand(Eye);

    impl Frame for ByHand {
        fn projection(&mut self, p: &ProgramFns, mono: DMat4) {
            let k = self.0.sign() * 0.07 * SEPARATION as f64 / 100.0;
            let mut m = mono.to_cols_array_2d();
            if mono.row(3) != DVec4::new(0.0, 0.0, 0.0, 1.0) {
                for col in &mut m {
                    col[0] += k * col[3];
                }
                m[3][0] -= k * CONVERGENCE as f64;
            }
            // SAFETY: a context is current.
            unsafe { load_projection(p, &DMat4::from_cols_array_2d(&m)) };
        }
        fn draw(&mut self, f: &mut dyn FnMut()) {
            f()
        }
        fn pixels(&mut self, f: &mut dyn FnMut()) {
            f()
        }
        fn bitmap(&mut self, _: f32, _: f32, f: &mut dyn FnMut()) {
            f()
        }
    }

    /// The mono program with the layer's stand-in vertex shader
    /// ([`crate::auto::standin`]) bound in place of fixed-function vertex
    /// processing: each draw made once per eye with the eye's uniform, the
    /// neutral value between draws; pixel rectangles as [`UnderLayer`].
    struct StandIn<'a> {
        p: &'a ProgramFns,
        program: u32,
        location: i32,
        pixels: FixedDraw<'a>,
    }

    impl Frame for StandIn<'_> {
        fn projection(&mut self, p: &ProgramFns, mono: DMat4) {
            // SAFETY: a context is current.
            unsafe { load_projection(p, &mono) };
        }
        fn draw(&mut self, f: &mut dyn FnMut()) {
            let s = self.pixels.settings.effective_separation() as f32;
            let c = self.pixels.settings.convergence();
            // SAFETY: a context is current, the stand-in in use.
            unsafe {
                (self.p.uniform4f)(self.location, -s, c, 0.0, 0.0);
                f();
                (self.p.uniform4f)(self.location, s, c, 1.0, 0.0);
                f();
                (self.p.uniform4f)(self.location, 0.0, c, -1.0, 0.0);
            }
        }
        fn pixels(&mut self, f: &mut dyn FnMut()) {
            // SAFETY: as above.
            unsafe { self.pixels.pixels(|_| f()) };
        }
        fn bitmap(&mut self, xmove: f32, ymove: f32, f: &mut dyn FnMut()) {
            // SAFETY: as above.
            unsafe { self.pixels.bitmap(xmove, ymove, f) };
        }
        fn raster_pos(&mut self, f: &mut dyn FnMut()) {
            // Fixed function computes the raster position (module docs of
            // crate::auto::standin).
            // SAFETY: as above.
            unsafe {
                (self.p.use_program)(0);
                f();
                (self.p.use_program)(self.program);
            }
        }
    }

    /// As [`StandIn`], but each draw (here glBegin … glEnd) is compiled
    /// into a display list of the layer's as it is made, then the list is
    /// called once per eye: immediate mode in both eyes without recording
    /// its per-vertex calls.
    struct StandInList<'a> {
        inner: StandIn<'a>,
        list: u32,
    }

    impl Frame for StandInList<'_> {
        fn projection(&mut self, p: &ProgramFns, mono: DMat4) {
            self.inner.projection(p, mono)
        }
        fn draw(&mut self, f: &mut dyn FnMut()) {
            let p = self.inner.p;
            let list = self.list;
            // SAFETY: a context is current, no list being compiled.
            unsafe {
                (p.new_list)(list, 0x1300); // GL_COMPILE
                f();
                (p.end_list)();
            }
            // SAFETY: as above.
            self.inner.draw(&mut || unsafe { (p.call_list)(list) });
        }
        fn pixels(&mut self, f: &mut dyn FnMut()) {
            self.inner.pixels(f)
        }
        fn bitmap(&mut self, xmove: f32, ymove: f32, f: &mut dyn FnMut()) {
            self.inner.bitmap(xmove, ymove, f)
        }
        fn raster_pos(&mut self, f: &mut dyn FnMut()) {
            self.inner.raster_pos(f)
        }
    }

    unsafe fn quad(p: &ProgramFns, x0: f32, y0: f32, x1: f32, y1: f32, z0: f32, z1: f32) {
        // SAFETY: a context is current.
        unsafe {
            (p.begin)(GL_QUADS);
            (p.vertex3f)(x0, y0, z0);
            (p.vertex3f)(x1, y0, z1);
            (p.vertex3f)(x1, y1, z1);
            (p.vertex3f)(x0, y1, z0);
            (p.end)();
        }
    }

    /// A legacy frame: clear, a perspective scene of quads at depths in
    /// front of, at and behind the convergence (one slanted across them),
    /// depth-tested; a glDrawPixels block and two glBitmap glyphs at raster
    /// positions under the perspective; then a HUD under glOrtho.
    unsafe fn scene(p: &ProgramFns, frame: &mut dyn Frame) {
        let glyph = [
            0b1111_0000u8,
            0b1001_0000,
            0b1001_0000,
            0b1111_1111,
            0,
            0xFF,
            0x81,
            0xFF,
        ];
        let block: Vec<u8> = (0..8 * 8).flat_map(|_| [255u8, 255, 0, 255]).collect();
        // SAFETY: a context is current.
        unsafe {
            (p.clear_color)(0.2, 0.2, 0.2, 1.0);
            (p.enable)(GL_DEPTH_TEST);
            (p.clear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            frame.projection(p, frustum(-0.5, 0.5, -0.375, 0.375, 1.0, 20.0));
            (p.load_identity)();
            (p.color3f)(0.0, 0.0, 1.0);
            frame.draw(&mut || quad(p, -6.0, -4.0, 6.0, 4.0, -10.0, -10.0));
            (p.color3f)(0.0, 1.0, 0.0);
            frame.draw(&mut || quad(p, -1.5, -1.0, 0.5, 0.5, -4.0, -4.0));
            (p.color3f)(1.0, 0.0, 0.0);
            frame.draw(&mut || quad(p, -0.3, -0.2, 0.1, 0.3, -2.0, -2.0));
            (p.color3f)(1.0, 0.4, 0.0);
            frame.draw(&mut || quad(p, 0.2, -1.5, 3.0, -0.5, -2.5, -9.0));
            frame.raster_pos(&mut || (p.raster_pos3f)(0.3, -0.2, -3.0));
            frame.pixels(&mut || {
                (p.draw_pixels)(8, 8, GL_RGBA, GL_UNSIGNED_BYTE, block.as_ptr().cast())
            });
            (p.color3f)(1.0, 1.0, 1.0);
            frame.raster_pos(&mut || (p.raster_pos3f)(-2.0, 1.0, -12.0));
            frame.bitmap(10.0, 0.0, &mut || {
                (p.bitmap)(8, 8, 0.0, 0.0, 10.0, 0.0, glyph.as_ptr())
            });
            frame.bitmap(10.0, 0.0, &mut || {
                (p.bitmap)(8, 8, 0.0, 0.0, 10.0, 0.0, glyph.as_ptr())
            });
            frame.projection(p, ortho(0.0, W as f64, 0.0, H as f64, -1.0, 1.0));
            (p.disable)(GL_DEPTH_TEST);
            (p.color3f)(1.0, 1.0, 1.0);
            frame.draw(&mut || quad(p, 10.0, 100.0, 40.0, 110.0, 0.0, 0.0));
        }
    }

    /// Runs a frame through the [`Frame`] it makes: the mono program
    /// under one of the layer's paths, drawing into the layered target.
    type UnderTest<'a> =
        &'a dyn Fn(&ProgramFns, &FixedFns, &TargetFns, &EyeTarget, &mut dyn FnMut(&mut dyn Frame));

    /// Draws [`scene`] mono through the frame `make` makes, and by hand
    /// per eye; compares the eyes pixel by pixel.
    fn compare_with_hand_drawn_eyes(make: UnderTest) {
        let cx = egl_context();
        let get = |n: &std::ffi::CStr| cx.display.platform().get_proc_address(n);
        // SAFETY: the EGL context is current on this thread for the test.
        unsafe {
            let p = ProgramFns::load(get).unwrap();
            let tf = TargetFns::load(get).unwrap();
            let ff = FixedFns::load(get).unwrap();
            (p.viewport)(0, 0, W, H);
            let layered = EyeTarget::create(&tf, W, H).expect("a layered target");
            make(&p, &ff, &tf, &layered, &mut |frame| scene(&p, frame));
            (p.use_program)(0);
            let got = [layered.read(&tf, Eye::Left), layered.read(&tf, Eye::Right)];
            let oracle = EyeTarget::create(&tf, W, H).unwrap();
            for (i, eye) in EYES.into_iter().enumerate() {
                oracle.bind_eye(&tf, eye);
                scene(&p, &mut ByHand(eye));
                oracle.bind_layered(&tf);
                let want = oracle.read(&tf, eye);
                let differ = differing_pixels(&got[i], &want);
                if differ > 0 {
                    let mut at = Vec::new();
                    for (n, (a, b)) in got[i].chunks(4).zip(want.chunks(4)).enumerate() {
                        if a != b && at.len() < 12 {
                            at.push(format!(
                                "({},{}) {:?} want {:?}",
                                n as i32 % W,
                                n as i32 / W,
                                a,
                                b
                            ));
                        }
                    }
                    eprintln!("{}", at.join("\n"));
                }
                assert_eq!(
                    differ, 0,
                    "{eye:?} eye: {differ} pixels differ from the eye drawn by hand"
                );
            }
            assert_eq!((p.get_error)(), 0);
            // The glDrawPixels block (yellow) is whole in each eye, at a
            // different place: it lies in front of the convergence.
            let yellow = |img: &[u8]| -> Vec<usize> {
                img.chunks(4)
                    .enumerate()
                    .filter(|(_, p)| p == &[255, 255, 0, 255])
                    .map(|(i, _)| i)
                    .collect()
            };
            let (l, r) = (yellow(&got[0]), yellow(&got[1]));
            assert_eq!((l.len(), r.len()), (64, 64), "the 8x8 block in each eye");
            assert!(
                r[0] % W as usize + 2 < l[0] % W as usize,
                "near: the right eye's block is left of the left eye's"
            );
            let between = differing_pixels(&got[0], &got[1]);
            assert!(
                between > 500,
                "the eyes differ in only {between} pixels: no stereo"
            );
            // The HUD (glOrtho, w = 1) is where it was in both eyes.
            let hud = |img: &[u8]| -> Vec<u8> {
                (100..110)
                    .flat_map(|y| {
                        img[((y * W + 8) * 4) as usize..((y * W + 42) * 4) as usize].to_vec()
                    })
                    .collect()
            };
            assert_eq!(hud(&got[0]), hud(&got[1]), "the HUD moved between the eyes");
            assert!(
                hud(&got[0])
                    .chunks(4)
                    .filter(|p| p[0] == 255 && p[2] == 255)
                    .count()
                    >= 30 * 10
            );
            layered.destroy(&tf);
            oracle.destroy(&tf);
        }
    }

    #[test]
    fn a_mono_fixed_function_frame_in_both_eyes_equals_each_eye_drawn_by_hand() {
        compare_with_hand_drawn_eyes(&|_, ff, tf, target, run| {
            run(&mut UnderLayer(FixedDraw {
                fns: ff,
                target_fns: tf,
                target,
                settings: settings(),
            }))
        });
    }

    #[test]
    fn the_stand_in_vertex_shader_draws_what_fixed_function_draws_by_hand() {
        compare_with_hand_drawn_eyes(&|p, ff, tf, target, run| {
            // SAFETY: the test's context is current.
            unsafe {
                let mut max = 0;
                (p.get_integerv)(0x826E, &mut max); // GL_MAX_UNIFORM_LOCATIONS
                let location = max - 1;
                let src =
                    crate::auto::standin::source(Default::default(), location as u32).unwrap();
                let program = p.program(&[(0x8B31, &src)]);
                (p.use_program)(program);
                (p.uniform4f)(location, 0.0, CONVERGENCE, -1.0, 0.0);
                run(&mut StandIn {
                    p,
                    program,
                    location,
                    pixels: FixedDraw {
                        fns: ff,
                        target_fns: tf,
                        target,
                        settings: settings(),
                    },
                });
            }
        });
    }

    #[test]
    fn immediate_mode_compiled_into_a_list_and_called_per_eye_equals_each_eye_drawn_by_hand() {
        compare_with_hand_drawn_eyes(&|p, ff, tf, target, run| {
            // SAFETY: the test's context is current.
            unsafe {
                let mut max = 0;
                (p.get_integerv)(0x826E, &mut max); // GL_MAX_UNIFORM_LOCATIONS
                let location = max - 1;
                let src =
                    crate::auto::standin::source(Default::default(), location as u32).unwrap();
                let program = p.program(&[(0x8B31, &src)]);
                (p.use_program)(program);
                (p.uniform4f)(location, 0.0, CONVERGENCE, -1.0, 0.0);
                run(&mut StandInList {
                    inner: StandIn {
                        p,
                        program,
                        location,
                        pixels: FixedDraw {
                            fns: ff,
                            target_fns: tf,
                            target,
                            settings: settings(),
                        },
                    },
                    list: (p.gen_lists)(1),
                });
            }
        });
    }

    #[test]
    fn orthographic_projections_and_w_1_raster_positions_are_left_alone() {
        let s = settings();
        let o = ortho(0.0, 100.0, 0.0, 100.0, -1.0, 1.0);
        assert_eq!(eye_projection(&s, &o, Eye::Left), None);
        let f = frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0);
        let l = eye_projection(&s, &f, Eye::Left).unwrap();
        // Row 0 only, by k = -0.07: row0 + k·row3 - k·C·(0,0,0,1).
        assert_eq!(l.row(1), f.row(1));
        assert_eq!(l.row(0), f.row(0) - 0.07 * f.row(3) + 0.07 * 4.0 * DVec4::W);
        assert_eq!(
            raster_shift(&s, [10.0, 10.0, 0.5, 1.0], 160.0, Eye::Left),
            0.0
        );
        // At w = 2C the point is s/2 of the half-width behind: 0.07 · 0.5 · 80 px.
        let dx = raster_shift(&s, [10.0, 10.0, 0.5, 8.0], 160.0, Eye::Right);
        assert!((dx - 0.07 * 0.5 * 80.0).abs() < 1e-12, "{dx}");
        // Nearer than C: the other way.
        assert!(raster_shift(&s, [10.0, 10.0, 0.5, 2.0], 160.0, Eye::Right) < 0.0);
        let mut none = s;
        none.parameter_f(GL_STEREO_SEPARATION_NV, 0.0).unwrap();
        assert_eq!(eye_projection(&none, &f, Eye::Right), None);
    }
}

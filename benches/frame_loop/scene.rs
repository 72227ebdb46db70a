//! The benchmark scene: a lit torus in a vertex buffer, drawn with the
//! fixed-function pipeline, identical for the mono and the stereo program.

use std::ffi::{CStr, c_void};

use glstereo::gl::Gl;
use glstereo::gl::enums::*;
use glstereo::math::Eye;
use glstereo::math::frustum::Frustum;
use glstereo::math::hp::{StereoAdjust, hp_eye};

const GL_VERTEX_ARRAY: u32 = 0x8074;
const GL_NORMAL_ARRAY: u32 = 0x8075;
const GL_FLOAT: u32 = 0x1406;
const GL_UNSIGNED_INT: u32 = 0x1405;
const GL_TRIANGLES: u32 = 0x0004;
const GL_ARRAY_BUFFER: u32 = 0x8892;
const GL_ELEMENT_ARRAY_BUFFER: u32 = 0x8893;
const GL_STATIC_DRAW: u32 = 0x88E4;
const GL_LIGHTING: u32 = 0x0B50;
const GL_LIGHT0: u32 = 0x4000;
const GL_POSITION: u32 = 0x1203;
const GL_NORMALIZE: u32 = 0x0BA1;

/// The few fixed-function entry points the library's table does not carry.
#[allow(non_snake_case)]
pub struct SceneGl {
    EnableClientState: unsafe extern "system" fn(u32),
    VertexPointer: unsafe extern "system" fn(i32, u32, i32, *const c_void),
    NormalPointer: unsafe extern "system" fn(u32, i32, *const c_void),
    DrawElements: unsafe extern "system" fn(u32, i32, u32, *const c_void),
    Lightfv: unsafe extern "system" fn(u32, u32, *const f32),
}

impl SceneGl {
    /// Loads the entry points through a backend's GetProcAddress.
    ///
    /// # Safety
    /// `get` must return the named GL functions of the current context's backend.
    pub unsafe fn load(get: impl Fn(&CStr) -> *const c_void) -> SceneGl {
        macro_rules! f {
            ($name:literal, $ty:ty) => {{
                let p = get($name);
                assert!(!p.is_null(), "{:?} missing", $name);
                // SAFETY: the backend returned this Khronos function (contract).
                unsafe { std::mem::transmute::<*const c_void, $ty>(p) }
            }};
        }
        SceneGl {
            EnableClientState: f!(c"glEnableClientState", unsafe extern "system" fn(u32)),
            VertexPointer: f!(
                c"glVertexPointer",
                unsafe extern "system" fn(i32, u32, i32, *const c_void)
            ),
            NormalPointer: f!(
                c"glNormalPointer",
                unsafe extern "system" fn(u32, i32, *const c_void)
            ),
            DrawElements: f!(
                c"glDrawElements",
                unsafe extern "system" fn(u32, i32, u32, *const c_void)
            ),
            Lightfv: f!(
                c"glLightfv",
                unsafe extern "system" fn(u32, u32, *const f32)
            ),
        }
    }
}

/// Which scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Weight {
    /// 384 triangles.
    Light,
    /// 262 144 triangles.
    Heavy,
}

impl Weight {
    pub fn name(self) -> &'static str {
        match self {
            Weight::Light => "light",
            Weight::Heavy => "heavy",
        }
    }

    /// Segments around the ring and around the tube.
    fn segments(self) -> (u32, u32) {
        match self {
            Weight::Light => (16, 12),
            Weight::Heavy => (512, 256),
        }
    }

    pub fn triangles(self) -> u32 {
        let (m, n) = self.segments();
        2 * m * n
    }
}

/// A torus uploaded to buffer objects of the current context.
pub struct Scene {
    ext: SceneGl,
    vbo: u32,
    ibo: u32,
    indices: i32,
    width: u32,
    height: u32,
}

impl Scene {
    /// Builds the torus and uploads it (a context must be current).
    ///
    /// # Safety
    /// `gl` and `ext` belong to the context current on this thread.
    pub unsafe fn new(gl: &Gl, ext: SceneGl, weight: Weight, width: u32, height: u32) -> Scene {
        let (m, n) = weight.segments();
        let (big, small) = (1.0f32, 0.4f32);
        let mut verts: Vec<f32> = Vec::with_capacity((m * n * 6) as usize);
        for i in 0..m {
            let u = i as f32 / m as f32 * std::f32::consts::TAU;
            for j in 0..n {
                let v = j as f32 / n as f32 * std::f32::consts::TAU;
                let (nx, ny, nz) = (u.cos() * v.cos(), u.sin() * v.cos(), v.sin());
                let r = big + small * v.cos();
                verts.extend([r * u.cos(), r * u.sin(), small * v.sin(), nx, ny, nz]);
            }
        }
        let mut idx: Vec<u32> = Vec::with_capacity((m * n * 6) as usize);
        let at = |i: u32, j: u32| (i % m) * n + (j % n);
        for i in 0..m {
            for j in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                idx.extend([a, b, c, a, c, d]);
            }
        }
        let mut bufs = [0u32; 2];
        // SAFETY: contract; the slices outlive the uploads.
        unsafe {
            gl.GenBuffers(2, bufs.as_mut_ptr());
            gl.BindBuffer(GL_ARRAY_BUFFER, bufs[0]);
            gl.BufferData(
                GL_ARRAY_BUFFER,
                (verts.len() * 4) as isize,
                verts.as_ptr().cast(),
                GL_STATIC_DRAW,
            );
            gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, bufs[1]);
            gl.BufferData(
                GL_ELEMENT_ARRAY_BUFFER,
                (idx.len() * 4) as isize,
                idx.as_ptr().cast(),
                GL_STATIC_DRAW,
            );
        }
        Scene {
            ext,
            vbo: bufs[0],
            ibo: bufs[1],
            indices: idx.len() as i32,
            width,
            height,
        }
    }

    /// Clears and draws the torus at frame `frame` for `eye` (None: mono)
    /// into the bound draw framebuffer.
    ///
    /// # Safety
    /// The context the scene was made in must be current.
    pub unsafe fn draw(&self, gl: &Gl, frame: u64, eye: Option<Eye>) {
        let aspect = f64::from(self.width) / f64::from(self.height);
        let mono = Frustum::perspective(40.0, aspect, 1.0, 20.0).unwrap();
        let projection = match eye {
            None => mono.matrix(),
            Some(e) => hp_eye(&mono, &StereoAdjust::new(4.0), e).unwrap().matrix(),
        };
        let angle = frame as f64 * 0.02;
        let model = glam::DMat4::from_translation(glam::DVec3::new(0.0, 0.0, -4.0))
            * glam::DMat4::from_rotation_x(angle * 0.7)
            * glam::DMat4::from_rotation_y(angle);
        let light = [1.0f32, 1.0, 1.0, 0.0];
        // SAFETY: contract; matrices are 16 doubles; buffer offsets index the bound VBO.
        unsafe {
            gl.Viewport(0, 0, self.width as i32, self.height as i32);
            gl.ClearColor(0.1, 0.1, 0.15, 1.0);
            gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            gl.Enable(GL_DEPTH_TEST);
            gl.Enable(GL_LIGHTING);
            gl.Enable(GL_LIGHT0);
            gl.Enable(GL_NORMALIZE);
            gl.MatrixMode(GL_PROJECTION);
            gl.LoadMatrixd(projection.to_cols_array().as_ptr());
            gl.MatrixMode(GL_MODELVIEW);
            gl.LoadMatrixd(glam::DMat4::IDENTITY.to_cols_array().as_ptr());
            (self.ext.Lightfv)(GL_LIGHT0, GL_POSITION, light.as_ptr());
            gl.LoadMatrixd(model.to_cols_array().as_ptr());
            gl.BindBuffer(GL_ARRAY_BUFFER, self.vbo);
            gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, self.ibo);
            (self.ext.EnableClientState)(GL_VERTEX_ARRAY);
            (self.ext.EnableClientState)(GL_NORMAL_ARRAY);
            (self.ext.VertexPointer)(3, GL_FLOAT, 24, std::ptr::null());
            (self.ext.NormalPointer)(GL_FLOAT, 24, 12usize as *const c_void);
            (self.ext.DrawElements)(
                GL_TRIANGLES,
                self.indices,
                GL_UNSIGNED_INT,
                std::ptr::null(),
            );
        }
    }
}

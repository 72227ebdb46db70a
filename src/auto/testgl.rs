//! What the tests' "programs" call: the GL a mono program uses, loaded
//! from the test's EGL context (llvmpipe), and a few helpers.

use std::ffi::{CStr, CString, c_char, c_void};

use crate::auto::gl_fns;

pub const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
pub const GL_DEPTH_BUFFER_BIT: u32 = 0x0100;
pub const GL_DEPTH_TEST: u32 = 0x0B71;
pub const GL_SCISSOR_TEST: u32 = 0x0C11;
pub const GL_MODELVIEW: u32 = 0x1700;
pub const GL_QUADS: u32 = 0x0007;
pub const GL_TRIANGLES: u32 = 0x0004;
pub const GL_RGBA: u32 = 0x1908;
pub const GL_UNSIGNED_BYTE: u32 = 0x1401;
pub const GL_FRAGMENT_SHADER: u32 = 0x8B30;
pub const GL_COMPILE_STATUS: u32 = 0x8B81;
pub const GL_LINK_STATUS: u32 = 0x8B82;

gl_fns! {
    /// A mono program's GL.
    pub struct ProgramFns {
        begin = c"glBegin": fn(u32);
        end = c"glEnd": fn();
        vertex3f = c"glVertex3f": fn(f32, f32, f32);
        color3f = c"glColor3f": fn(f32, f32, f32);
        matrix_mode = c"glMatrixMode": fn(u32);
        load_identity = c"glLoadIdentity": fn();
        load_matrixd = c"glLoadMatrixd": fn(*const f64);
        raster_pos3f = c"glRasterPos3f": fn(f32, f32, f32);
        bitmap = c"glBitmap": fn(i32, i32, f32, f32, f32, f32, *const u8);
        draw_pixels = c"glDrawPixels": fn(i32, i32, u32, u32, *const c_void);
        clear_color = c"glClearColor": fn(f32, f32, f32, f32);
        clear = c"glClear": fn(u32);
        enable = c"glEnable": fn(u32);
        disable = c"glDisable": fn(u32);
        viewport = c"glViewport": fn(i32, i32, i32, i32);
        create_shader = c"glCreateShader": fn(u32) -> u32;
        shader_source = c"glShaderSource": fn(u32, i32, *const *const c_char, *const i32);
        compile_shader = c"glCompileShader": fn(u32);
        get_shaderiv = c"glGetShaderiv": fn(u32, u32, *mut i32);
        get_shader_info_log = c"glGetShaderInfoLog": fn(u32, i32, *mut i32, *mut c_char);
        create_program = c"glCreateProgram": fn() -> u32;
        attach_shader = c"glAttachShader": fn(u32, u32);
        link_program = c"glLinkProgram": fn(u32);
        get_programiv = c"glGetProgramiv": fn(u32, u32, *mut i32);
        get_program_info_log = c"glGetProgramInfoLog": fn(u32, i32, *mut i32, *mut c_char);
        use_program = c"glUseProgram": fn(u32);
        delete_program = c"glDeleteProgram": fn(u32);
        get_uniform_location = c"glGetUniformLocation": fn(u32, *const c_char) -> i32;
        uniform4f = c"glUniform4f": fn(i32, f32, f32, f32, f32);
        uniform_matrix4fv = c"glUniformMatrix4fv": fn(i32, i32, u8, *const f32);
        program_uniform4f = c"glProgramUniform4f": fn(u32, i32, f32, f32, f32, f32);
        create_shader_programv = c"glCreateShaderProgramv": fn(u32, i32, *const *const c_char) -> u32;
        get_error = c"glGetError": fn() -> u32;
        get_integerv = c"glGetIntegerv": fn(u32, *mut i32);
        gen_vertex_arrays = c"glGenVertexArrays": fn(i32, *mut u32);
        bind_vertex_array = c"glBindVertexArray": fn(u32);
        gen_buffers = c"glGenBuffers": fn(i32, *mut u32);
        bind_buffer = c"glBindBuffer": fn(u32, u32);
        buffer_data = c"glBufferData": fn(u32, isize, *const c_void, u32);
        vertex_attrib_pointer = c"glVertexAttribPointer": fn(u32, i32, u32, u8, i32, *const c_void);
        enable_vertex_attrib_array = c"glEnableVertexAttribArray": fn(u32);
        draw_arrays = c"glDrawArrays": fn(u32, i32, i32);
        patch_parameteri = c"glPatchParameteri": fn(u32, i32);
        gen_program_pipelines = c"glGenProgramPipelines": fn(i32, *mut u32);
        use_program_stages = c"glUseProgramStages": fn(u32, u32, u32);
        bind_program_pipeline = c"glBindProgramPipeline": fn(u32);
        program_uniform_matrix4fv = c"glProgramUniformMatrix4fv": fn(u32, i32, i32, u8, *const f32);
        program_uniform4fv = c"glProgramUniform4fv": fn(u32, i32, i32, *const f32);
        viewport_indexedf = c"glViewportIndexedf": fn(u32, f32, f32, f32, f32);
        gen_lists = c"glGenLists": fn(i32) -> u32;
        new_list = c"glNewList": fn(u32, u32);
        end_list = c"glEndList": fn();
        call_list = c"glCallList": fn(u32);
        scissor_indexed = c"glScissorIndexed": fn(u32, i32, i32, i32, i32);
    }
}

impl ProgramFns {
    /// Compiles a shader; Err(info log) when it does not compile.
    pub unsafe fn shader(&self, ty: u32, source: &str) -> Result<u32, String> {
        // SAFETY: contract of the callers (a context is current).
        unsafe {
            let s = (self.create_shader)(ty);
            let src = CString::new(source).unwrap();
            (self.shader_source)(s, 1, &src.as_ptr(), std::ptr::null());
            (self.compile_shader)(s);
            let mut ok = 0;
            (self.get_shaderiv)(s, GL_COMPILE_STATUS, &mut ok);
            if ok == 0 {
                let mut log = vec![0 as c_char; 4096];
                (self.get_shader_info_log)(
                    s,
                    log.len() as i32,
                    std::ptr::null_mut(),
                    log.as_mut_ptr(),
                );
                return Err(CStr::from_ptr(log.as_ptr()).to_string_lossy().into_owned());
            }
            Ok(s)
        }
    }

    /// Compiles and links a program of (type, source) pairs; panics with
    /// the logs when that fails.
    pub unsafe fn program(&self, stages: &[(u32, &str)]) -> u32 {
        // SAFETY: contract of the callers.
        unsafe {
            let p = (self.create_program)();
            for &(ty, src) in stages {
                let s = self
                    .shader(ty, src)
                    .unwrap_or_else(|log| panic!("{src}\n{log}"));
                (self.attach_shader)(p, s);
            }
            (self.link_program)(p);
            assert!(self.linked(p), "{}", self.program_log(p));
            p
        }
    }

    /// Whether `p` is linked.
    pub unsafe fn linked(&self, p: u32) -> bool {
        let mut ok = 0;
        // SAFETY: contract of the callers.
        unsafe { (self.get_programiv)(p, GL_LINK_STATUS, &mut ok) };
        ok != 0
    }

    /// A program's info log.
    pub unsafe fn program_log(&self, p: u32) -> String {
        let mut log = vec![0 as c_char; 4096];
        // SAFETY: contract of the callers; the buffer's size is passed.
        unsafe {
            (self.get_program_info_log)(
                p,
                log.len() as i32,
                std::ptr::null_mut(),
                log.as_mut_ptr(),
            );
            CStr::from_ptr(log.as_ptr()).to_string_lossy().into_owned()
        }
    }
}

/// How many pixels (of RGBA8 rows) differ between two images.
pub fn differing_pixels(a: &[u8], b: &[u8]) -> usize {
    a.chunks(4).zip(b.chunks(4)).filter(|(x, y)| x != y).count()
}

//! The emulated default framebuffer follows the GL 4.5 compatibility rules
//! for glDrawBuffer / glReadBuffer on every configuration shape, on a real
//! Mesa EGL context: each name reaches exactly the buffers GL says, errors
//! are the GL ones and change nothing, and one swap presents both eyes.

use std::sync::Arc;

use glstereo::backend::{BackendChoice, BackendKind};
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::error::Error;
use glstereo::gl::enums::*;
use glstereo::surface::{self, Surface};

const W: u32 = 16;
const H: u32 = 8;

#[derive(Clone, Copy, Debug)]
struct Shape {
    stereo: bool,
    double: bool,
}

const SHAPES: [Shape; 4] = [
    Shape {
        stereo: true,
        double: true,
    },
    Shape {
        stereo: true,
        double: false,
    },
    Shape {
        stereo: false,
        double: true,
    },
    Shape {
        stereo: false,
        double: false,
    },
];

/// The four buffers, written out independently of the library.
const FL: u32 = GL_FRONT_LEFT;
const BL: u32 = GL_BACK_LEFT;
const FR: u32 = GL_FRONT_RIGHT;
const BR: u32 = GL_BACK_RIGHT;

fn allocated(s: Shape) -> Vec<u32> {
    let mut v = vec![FL];
    if s.double {
        v.push(BL);
    }
    if s.stereo {
        v.push(FR);
        if s.double {
            v.push(BR);
        }
    }
    v
}

/// What each draw-buffer name selects if all four buffers exist (GL 4.5 table 17.4).
fn names() -> Vec<(u32, &'static str, Vec<u32>)> {
    vec![
        (GL_FRONT_LEFT, "GL_FRONT_LEFT", vec![FL]),
        (GL_FRONT_RIGHT, "GL_FRONT_RIGHT", vec![FR]),
        (GL_BACK_LEFT, "GL_BACK_LEFT", vec![BL]),
        (GL_BACK_RIGHT, "GL_BACK_RIGHT", vec![BR]),
        (GL_FRONT, "GL_FRONT", vec![FL, FR]),
        (GL_BACK, "GL_BACK", vec![BL, BR]),
        (GL_LEFT, "GL_LEFT", vec![FL, BL]),
        (GL_RIGHT, "GL_RIGHT", vec![FR, BR]),
        (GL_FRONT_AND_BACK, "GL_FRONT_AND_BACK", vec![FL, BL, FR, BR]),
    ]
}

fn make(shape: Shape) -> Arc<Surface> {
    let d = Display::open(BackendChoice::Only(BackendKind::Egl)).expect("EGL display");
    let mut attrs = vec![GLX_RGBA, GLX_ALPHA_SIZE, 8];
    if shape.double {
        attrs.push(GLX_DOUBLEBUFFER);
    }
    if shape.stereo {
        attrs.push(GLX_STEREO);
    }
    let c = d.choose_config(&attrs).unwrap();
    let s = d.create_surface(&c, W, H).unwrap();
    surface::make_current(Some(&s)).unwrap();
    s
}

fn clear(s: &Surface, rgba: [f32; 4]) {
    // SAFETY: the surface is current on this thread.
    unsafe {
        s.gl().ClearColor(rgba[0], rgba[1], rgba[2], rgba[3]);
        s.gl().Clear(GL_COLOR_BUFFER_BIT);
    }
}

/// The colour of every allocated buffer, by name.
fn contents(s: &Arc<Surface>, shape: Shape) -> Vec<(u32, [u8; 4])> {
    allocated(shape)
        .into_iter()
        .map(|b| (b, s.read_pixels(b).unwrap().get(W / 2, H / 2)))
        .collect()
}

fn reset(s: &Arc<Surface>, initial: u32) {
    s.draw_buffer(GL_FRONT_AND_BACK).unwrap();
    clear(s, [0.0; 4]);
    s.draw_buffer(initial).unwrap();
    assert_eq!(s.take_gl_error().unwrap(), GL_NO_ERROR);
}

#[test]
fn every_draw_buffer_name_reaches_exactly_the_buffers_gl_says() {
    for shape in SHAPES {
        let s = make(shape);
        let initial = if shape.double { GL_BACK } else { GL_FRONT };
        assert_eq!(
            s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
            Some(initial as i32),
            "{shape:?} initial"
        );
        assert_eq!(
            s.emulated_integer(GL_READ_BUFFER).unwrap(),
            Some(initial as i32)
        );
        for (name, label, all) in names() {
            reset(&s, initial);
            let want: Vec<u32> = all
                .iter()
                .copied()
                .filter(|b| allocated(shape).contains(b))
                .collect();
            let r = s.draw_buffer(name);
            if want.is_empty() {
                assert!(
                    matches!(r, Err(Error::InvalidOperation(_))),
                    "{shape:?} {label}: {r:?}"
                );
                assert_eq!(
                    s.take_gl_error().unwrap(),
                    GL_INVALID_OPERATION,
                    "{shape:?} {label}"
                );
                assert_eq!(
                    s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
                    Some(initial as i32),
                    "{shape:?} {label}: state changed"
                );
                // Drawing still goes where it went before the failed call.
                clear(&s, [1.0, 1.0, 1.0, 1.0]);
                let initial_set: Vec<u32> = names()
                    .into_iter()
                    .find(|n| n.0 == initial)
                    .unwrap()
                    .2
                    .into_iter()
                    .filter(|b| allocated(shape).contains(b))
                    .collect();
                for (b, px) in contents(&s, shape) {
                    let lit = px == [255; 4];
                    assert_eq!(
                        lit,
                        initial_set.contains(&b),
                        "{shape:?} after failed {label}: buffer {b:#x} is {px:?}"
                    );
                }
                continue;
            }
            r.unwrap_or_else(|e| panic!("{shape:?} {label}: {e}"));
            assert_eq!(
                s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
                Some(name as i32),
                "{shape:?} {label}"
            );
            clear(&s, [1.0, 0.5, 0.25, 1.0]);
            for (b, px) in contents(&s, shape) {
                let lit = px == [255, 128, 64, 255];
                assert_eq!(
                    lit,
                    want.contains(&b),
                    "{shape:?} {label}: buffer {b:#x} is {px:?}"
                );
            }
        }
        // GL_NONE draws nowhere.
        reset(&s, initial);
        s.draw_buffer(GL_NONE).unwrap();
        clear(&s, [1.0; 4]);
        assert!(
            contents(&s, shape).iter().all(|(_, px)| *px == [0; 4]),
            "{shape:?} GL_NONE drew"
        );
        // Not buffer names: INVALID_ENUM; aux and FBO attachments: INVALID_OPERATION.
        for (bad, code) in [
            (0x1234, GL_INVALID_ENUM),
            (GL_TEXTURE_2D, GL_INVALID_ENUM),
            (GL_AUX0, GL_INVALID_OPERATION),
            (GL_COLOR_ATTACHMENT0, GL_INVALID_OPERATION),
        ] {
            reset(&s, initial);
            assert!(s.draw_buffer(bad).is_err());
            assert_eq!(s.take_gl_error().unwrap(), code, "{shape:?} draw {bad:#x}");
            assert!(s.read_buffer(bad).is_err());
            assert_eq!(s.take_gl_error().unwrap(), code, "{shape:?} read {bad:#x}");
            assert_eq!(
                s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
                Some(initial as i32)
            );
            assert_eq!(
                s.emulated_integer(GL_READ_BUFFER).unwrap(),
                Some(initial as i32)
            );
        }
        surface::make_current(None).unwrap();
    }
}

#[test]
fn read_buffer_names_read_the_buffers_gl_says() {
    let shape = Shape {
        stereo: true,
        double: true,
    };
    let s = make(shape);
    // A distinct colour in each buffer.
    let colors = [
        (FL, [1.0, 0.0, 0.0, 1.0]),
        (BL, [0.0, 1.0, 0.0, 1.0]),
        (FR, [0.0, 0.0, 1.0, 1.0]),
        (BR, [1.0, 1.0, 0.0, 1.0]),
    ];
    for (b, c) in colors {
        s.draw_buffer(b).unwrap();
        clear(&s, c);
    }
    let want = [
        (GL_FRONT_LEFT, [255, 0, 0, 255]),
        (GL_FRONT, [255, 0, 0, 255]),
        (GL_LEFT, [255, 0, 0, 255]),
        (GL_FRONT_AND_BACK, [255, 0, 0, 255]),
        (GL_BACK_LEFT, [0, 255, 0, 255]),
        (GL_BACK, [0, 255, 0, 255]),
        (GL_FRONT_RIGHT, [0, 0, 255, 255]),
        (GL_RIGHT, [0, 0, 255, 255]),
        (GL_BACK_RIGHT, [255, 255, 0, 255]),
    ];
    for (name, px) in want {
        s.read_buffer(name).unwrap();
        assert_eq!(
            s.emulated_integer(GL_READ_BUFFER).unwrap(),
            Some(name as i32)
        );
        // The program's own glReadPixels reads the selected buffer.
        let mut got = [0u8; 4];
        // SAFETY: current surface; 1 pixel into a 4-byte buffer.
        unsafe {
            s.gl().ReadPixels(
                1,
                1,
                1,
                1,
                GL_RGBA,
                GL_UNSIGNED_BYTE,
                got.as_mut_ptr().cast(),
            )
        };
        assert_eq!(got, px, "glReadBuffer({name:#x})");
    }
    // The library's read-back follows the same names.
    assert_eq!(s.read_pixels(GL_RIGHT).unwrap().get(0, 0), [0, 0, 255, 255]);
    surface::make_current(None).unwrap();
}

#[test]
fn one_swap_makes_both_back_buffers_the_front_buffers() {
    let s = make(Shape {
        stereo: true,
        double: true,
    });
    s.draw_buffer(GL_BACK_LEFT).unwrap();
    clear(&s, [1.0, 0.0, 0.0, 1.0]);
    s.draw_buffer(GL_BACK_RIGHT).unwrap();
    clear(&s, [0.0, 0.0, 1.0, 1.0]);
    let fronts_before = (s.read_pixels(FL).unwrap(), s.read_pixels(FR).unwrap());
    s.swap_buffers().unwrap();
    assert_eq!(
        s.read_pixels(FL).unwrap().get(3, 3),
        [255, 0, 0, 255],
        "front-left after swap"
    );
    assert_eq!(
        s.read_pixels(FR).unwrap().get(3, 3),
        [0, 0, 255, 255],
        "front-right after swap"
    );
    // The draw state still says GL_BACK_RIGHT, now meaning the other texture.
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
        Some(GL_BACK_RIGHT as i32)
    );
    clear(&s, [0.0, 1.0, 0.0, 1.0]);
    assert_eq!(
        s.read_pixels(FR).unwrap().get(3, 3),
        [0, 0, 255, 255],
        "drawing the back must not touch the front"
    );
    assert_eq!(s.read_pixels(BR).unwrap().get(3, 3), [0, 255, 0, 255]);
    s.swap_buffers().unwrap();
    assert_eq!(
        s.read_pixels(FR).unwrap().get(3, 3),
        [0, 255, 0, 255],
        "second swap"
    );
    assert_eq!(
        s.read_pixels(FL).unwrap(),
        fronts_before.0,
        "left back still holds the first front (black)"
    );
    assert_eq!(s.frames(), 2);
    surface::make_current(None).unwrap();
}

#[test]
fn emulated_state_queries_answer_as_a_stereo_visual_would() {
    let s = make(Shape {
        stereo: true,
        double: true,
    });
    assert_eq!(s.emulated_integer(GL_STEREO).unwrap(), Some(1));
    assert_eq!(s.emulated_integer(GL_DOUBLEBUFFER).unwrap(), Some(1));
    assert_eq!(
        s.emulated_integer(GL_DRAW_FRAMEBUFFER_BINDING).unwrap(),
        Some(0),
        "the layer's FBO is invisible"
    );
    s.draw_buffers(&[GL_BACK_LEFT, GL_BACK_RIGHT]).unwrap();
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
        Some(GL_BACK_LEFT as i32)
    );
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER0 + 1).unwrap(),
        Some(GL_BACK_RIGHT as i32)
    );
    assert!(matches!(
        s.draw_buffers(&[GL_FRONT]),
        Err(Error::InvalidEnum { .. })
    ));
    assert!(matches!(
        s.draw_buffers(&[GL_BACK_LEFT, GL_BACK_LEFT]),
        Err(Error::InvalidOperation(_))
    ));
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER0 + 1).unwrap(),
        Some(GL_BACK_RIGHT as i32),
        "unchanged after errors"
    );
    surface::make_current(None).unwrap();
    let mono = make(Shape {
        stereo: false,
        double: false,
    });
    assert_eq!(mono.emulated_integer(GL_STEREO).unwrap(), Some(0));
    assert_eq!(mono.emulated_integer(GL_DOUBLEBUFFER).unwrap(), Some(0));
    surface::make_current(None).unwrap();
}

type RectF = unsafe extern "system" fn(f32, f32, f32, f32);
type Color4F = unsafe extern "system" fn(f32, f32, f32, f32);

#[test]
fn fixed_function_colour_and_shaders_reach_the_documented_buffers() {
    let s = make(Shape {
        stereo: true,
        double: true,
    });
    let gl = s.gl();
    // SAFETY: the names are GL 1.0 functions with these signatures.
    let (rect, color): (RectF, Color4F) = unsafe {
        (
            std::mem::transmute::<*const std::ffi::c_void, RectF>(s.get_proc_address(c"glRectf")),
            std::mem::transmute::<*const std::ffi::c_void, Color4F>(
                s.get_proc_address(c"glColor4f"),
            ),
        )
    };
    s.draw_buffer(GL_BACK).unwrap();
    clear(&s, [0.0, 0.0, 0.0, 1.0]);
    // SAFETY: current surface.
    unsafe {
        color(0.0, 1.0, 0.0, 1.0);
        rect(-1.0, -1.0, 1.0, 1.0);
        gl.Finish();
    }
    assert_eq!(
        s.read_pixels(BL).unwrap().get(4, 4),
        [0, 255, 0, 255],
        "fixed function reaches back-left"
    );
    assert_eq!(
        s.read_pixels(BR).unwrap().get(4, 4),
        [0, 255, 0, 255],
        "fixed function reaches back-right"
    );

    // gl_FragColor is broadcast to every selected buffer; a user-defined
    // `out vec4` goes to location 0 only: the first selected buffer, the left
    // eye (the other's contents are undefined, GL's rule for unwritten outputs).
    let vs = "#version 130\nvoid main(){ vec2 p = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0; gl_Position = vec4(p, 0.0, 1.0); }\n";
    let frag_color = "#version 130\nvoid main(){ gl_FragColor = vec4(0.0, 0.0, 1.0, 1.0); }\n";
    let out_vec4 =
        "#version 130\nout vec4 color;\nvoid main(){ color = vec4(1.0, 0.0, 1.0, 1.0); }\n";
    let draw = |fs: &str| {
        // SAFETY: current surface; valid shader sources.
        unsafe {
            let prog = gl.CreateProgram();
            for (ty, src) in [(GL_VERTEX_SHADER, vs), (GL_FRAGMENT_SHADER, fs)] {
                let sh = gl.CreateShader(ty);
                let c = std::ffi::CString::new(src).unwrap();
                gl.ShaderSource(sh, 1, &c.as_ptr(), std::ptr::null());
                gl.CompileShader(sh);
                let mut ok = 0;
                gl.GetShaderiv(sh, GL_COMPILE_STATUS, &mut ok);
                assert_eq!(ok, 1, "shader compiles");
                gl.AttachShader(prog, sh);
                gl.DeleteShader(sh);
            }
            gl.LinkProgram(prog);
            gl.UseProgram(prog);
            let mut vao = 0;
            gl.GenVertexArrays(1, &mut vao);
            gl.BindVertexArray(vao);
            clear(&s, [0.0, 0.0, 0.0, 1.0]);
            gl.DrawArrays(GL_TRIANGLES, 0, 3);
            gl.Finish();
            gl.UseProgram(0);
            gl.DeleteProgram(prog);
            gl.BindVertexArray(0);
            gl.DeleteVertexArrays(1, &vao);
        }
    };
    draw(frag_color);
    assert_eq!(
        s.read_pixels(BL).unwrap().get(4, 4),
        [0, 0, 255, 255],
        "gl_FragColor reaches the left eye"
    );
    assert_eq!(
        s.read_pixels(BR).unwrap().get(4, 4),
        [0, 0, 255, 255],
        "gl_FragColor reaches the right eye"
    );
    draw(out_vec4);
    assert_eq!(
        s.read_pixels(BL).unwrap().get(4, 4),
        [255, 0, 255, 255],
        "out vec4 reaches the first buffer, the left eye"
    );
    surface::make_current(None).unwrap();
}

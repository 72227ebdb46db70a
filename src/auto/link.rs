//! The clip-space shift at link time: a program's last vertex-processing
//! stage relinked with the source of [`crate::auto::vertex`], as
//! [`crate::stereo::outputs`] relinks fragment shaders (and with its GL
//! table, [`LinkFns`]).
//!
//! After a successful glLinkProgram: the attached shaders' types give the
//! last stage (geometry, else tessellation evaluation, else vertex; none:
//! the program's vertices are fixed-function, [`crate::auto::fixed`]). Its
//! shader object that defines `main` is compiled again from the rewritten
//! source and linked in place of the user's, which is attached again
//! afterwards, so glGetAttachedShaders and glGetShaderSource show the
//! user's objects. A separable program (glCreateShaderProgramv, or
//! GL_PROGRAM_SEPARABLE) is one stage or several: its own last stage is
//! rewritten the same way, and at a draw the layer gives the eye's values
//! only to the program that supplies the pipeline's last stage and the
//! neutral value (no shift, layer −1) to the others, so no position is
//! shifted twice ([`crate::auto`], "Each family of draws"; tested with a
//! vertex and a geometry program in one pipeline).
//!
//! The reserved uniform location is tried first (every desktop GLSL
//! version takes it on Mesa 22.3); a compiler that refuses it (ES 1.00
//! and 3.00 shaders) gets the plain declaration, and the layer looks the
//! location up after the link ([`Shifted::location`]). Anything else that fails — no source (SPIR-V,
//! glProgramBinary), several objects of the stage defining `main`, a
//! rewrite that does not compile or link — links the program again as the
//! user linked it, and says why ([`LinkOutcome::Kept`]): that program
//! draws both eyes unshifted.

use crate::auto::glsl::{self, Profile, Scan};
use crate::auto::vertex::{self, LayerWrite, NotCovered, Options, Rewrite, Stage, shift_position};
use crate::stereo::outputs::LinkFns;

const GL_SHADER_TYPE: u32 = 0x8B4F;
const GL_LINK_STATUS: u32 = 0x8B82;

/// What a successful rewrite did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Shifted {
    /// The stage that was rewritten.
    pub stage: Stage,
    /// The reserved location the uniform got, or None: look it up by name
    /// ([`vertex::EYE_UNIFORM`]).
    pub location: Option<u32>,
    /// Whether the stage writes gl_Layer (false for ES shaders: their
    /// eye's target must be chosen outside the shader).
    pub layer: bool,
    /// The names the stage computes gl_Position from
    /// ([`glsl::position_names`]): the program's camera matrices among
    /// them.
    pub position: Vec<String>,
}

/// What [`shift_last_stage`] did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LinkOutcome {
    /// Relinked with the shift.
    Shifted(Shifted),
    /// Nothing to do: the link failed, or the program has no
    /// vertex-processing stage (fixed-function vertices), or its last stage
    /// writes no position.
    NotNeeded(String),
    /// Linked as the user linked it, for this reason.
    Kept(String),
}

/// The options a stage gets: the eye's index written to `index` where
/// the language lets the stage write it, and the reserved location.
fn options(stage: Stage, scan: &Scan, index: LayerWrite, location: Option<u32>) -> Options {
    Options {
        layer: if vertex::can_write_layer(stage, scan.version) {
            index
        } else {
            LayerWrite::None
        },
        // GLSL ES has explicit uniform locations from 3.10 on and no
        // extension for them before: the uniform is looked up by name.
        location: if scan.version.profile == Profile::Es && scan.version.number < 310 {
            None
        } else {
            location
        },
    }
}

/// Rewrites the last vertex-processing stage of the linked `program`
/// (module docs). `index` is where the eye's index goes (gl_Layer or
/// gl_ViewportIndex: the target's form), `location` the reserved uniform
/// location to try; `es`: the context is OpenGL ES, where a source
/// without `#version` is GLSL ES 1.00 ([`vertex::as_es_compiles`]).
///
/// # Safety
/// A GL context must be current on this thread and `program` one of its
/// program objects. GL errors may be raised (by the user's misuse the link
/// itself reports); callers keep the program's error state apart.
pub unsafe fn shift_last_stage(
    fns: &LinkFns,
    program: u32,
    index: LayerWrite,
    location: Option<u32>,
    es: bool,
) -> LinkOutcome {
    // SAFETY: contract.
    unsafe {
        if fns.program_int(program, GL_LINK_STATUS) == 0 {
            return LinkOutcome::NotNeeded("the program did not link".into());
        }
        let shaders: Vec<(u32, u32)> = fns
            .attached_shaders(program)
            .into_iter()
            .map(|s| (s, fns.shader_int(s, GL_SHADER_TYPE) as u32))
            .collect();
        let Some(stage) = vertex::last_stage(shaders.iter().map(|&(_, t)| t)) else {
            return LinkOutcome::NotNeeded(
                "the program has no vertex-processing shader: its vertices are fixed-function"
                    .into(),
            );
        };
        let mut chosen = None;
        for &(shader, ty) in &shaders {
            if ty != stage.gl() {
                continue;
            }
            let Some(source) = fns.shader_source(shader) else {
                return LinkOutcome::Kept(format!(
                    "the {} shader has no GLSL source (SPIR-V)",
                    stage.name()
                ));
            };
            let source = if es {
                vertex::as_es_compiles(source)
            } else {
                source
            };
            let scan = vertex::scan(&source);
            match shift_position(&source, stage, options(stage, &scan, index, location)) {
                Ok(Rewrite::NotNeeded(_)) => {}
                Ok(Rewrite::Shifted(_)) if chosen.is_some() => {
                    return LinkOutcome::Kept(format!(
                        "several {} shader objects define main",
                        stage.name()
                    ));
                }
                Ok(Rewrite::Shifted(text)) => chosen = Some((shader, source, scan, text)),
                Err(NotCovered(why)) => return LinkOutcome::Kept(why),
            }
        }
        let Some((user, source, scan, text)) = chosen else {
            return LinkOutcome::NotNeeded(format!(
                "the {} stage writes no position the rasterizer gets",
                stage.name()
            ));
        };
        let mut used = options(stage, &scan, index, location);
        let mut copy = fns.compile_as(stage.gl(), &text);
        if copy.is_none() && location.is_some() {
            used = options(stage, &scan, index, None);
            copy = match shift_position(&source, stage, used) {
                Ok(Rewrite::Shifted(text)) => fns.compile_as(stage.gl(), &text),
                _ => None,
            };
        }
        let Some(copy) = copy else {
            return LinkOutcome::Kept(format!(
                "the rewritten {} shader does not compile",
                stage.name()
            ));
        };
        // While the user's shader is detached, a scratch program holds it:
        // a shader the user already deleted would otherwise go away.
        let holder = (fns.create_program)();
        (fns.attach_shader)(holder, user);
        (fns.detach_shader)(program, user);
        (fns.attach_shader)(program, copy);
        (fns.link_program)(program);
        let ok = fns.program_int(program, GL_LINK_STATUS) != 0;
        (fns.detach_shader)(program, copy);
        (fns.delete_shader)(copy);
        (fns.attach_shader)(program, user);
        (fns.delete_program)(holder);
        if ok {
            return LinkOutcome::Shifted(Shifted {
                stage,
                location: used.location,
                layer: used.layer == LayerWrite::FromUniform,
                position: glsl::position_names(&glsl::blank_comments(&source)),
            });
        }
        (fns.link_program)(program);
        LinkOutcome::Kept(format!(
            "the program with the rewritten {} shader does not link",
            stage.name()
        ))
    }
}

/// The source glCreateShaderProgramv should compile for a shader of
/// `shader_type` made of `strings` (joined, as GL joins them): the shift
/// for a vertex-processing stage (the program is separable and has just
/// this stage, so it is its own last), the strings unchanged (None) for
/// any other stage or when the source is not covered (the reason in `Err`).
pub fn shift_separable(
    shader_type: u32,
    strings: &[&str],
    index: LayerWrite,
    location: Option<u32>,
    es: bool,
) -> Result<Option<String>, NotCovered> {
    let Some(stage) = Stage::from_gl(shader_type) else {
        return Ok(None);
    };
    let source = strings.concat();
    let source = if es {
        vertex::as_es_compiles(source)
    } else {
        source
    };
    let scan = vertex::scan(&source);
    match shift_position(&source, stage, options(stage, &scan, index, location))? {
        Rewrite::Shifted(text) => Ok(Some(text)),
        Rewrite::NotNeeded(_) => Ok(None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::auto::target::{EyeTarget, TargetFns};
    use crate::auto::testgl::*;
    use crate::auto::vertex::{GL_GEOMETRY_SHADER, GL_TESS_EVALUATION_SHADER, GL_VERTEX_SHADER};
    use crate::math::Eye;
    use crate::testing::egl_context;
    use std::ffi::{CStr, CString};

    const GL_MAX_UNIFORM_LOCATIONS: u32 = 0x826E;
    const GL_TESS_CONTROL_SHADER: u32 = 0x8E88;
    const GL_PATCHES: u32 = 0x000E;
    const GL_PATCH_VERTICES: u32 = 0x8E72;
    const GL_ARRAY_BUFFER: u32 = 0x8892;
    const GL_STATIC_DRAW: u32 = 0x88E4;
    const GL_FLOAT: u32 = 0x1406;

    struct Fixture {
        _cx: crate::testing::EglContext,
        p: ProgramFns,
        link: LinkFns,
        tf: TargetFns,
        /// The reserved location: the last one the driver offers.
        location: u32,
    }

    fn fixture() -> Fixture {
        let cx = egl_context();
        let get = |n: &CStr| cx.display.platform().get_proc_address(n);
        // SAFETY: the EGL context is current on this thread.
        unsafe {
            let p = ProgramFns::load(get).unwrap();
            let link = LinkFns::load(get).unwrap();
            let tf = TargetFns::load(get).unwrap();
            let mut max = 0;
            (p.get_integerv)(GL_MAX_UNIFORM_LOCATIONS, &mut max);
            assert!(max > 1024, "GL_MAX_UNIFORM_LOCATIONS {max}");
            Fixture {
                _cx: cx,
                p,
                link,
                tf,
                location: max as u32 - 1,
            }
        }
    }

    unsafe fn uniform_location(p: &ProgramFns, program: u32) -> i32 {
        let name = CString::new(vertex::EYE_UNIFORM).unwrap();
        // SAFETY: contract of the callers.
        unsafe { (p.get_uniform_location)(program, name.as_ptr()) }
    }

    const FS_110: &str = "void main() { gl_FragColor = gl_Color; }\n";

    /// Programs of every GLSL version a vertex stage can be written in,
    /// each with the version's own fragment shader.
    /// A program to link: its name, its stages and whether its last stage
    /// can write gl_Layer.
    type Case = (&'static str, Vec<(u32, &'static str)>, bool);

    fn programs() -> Vec<Case> {
        let fs330 = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
        vec![
            (
                "no #version",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "void main() { gl_Position = ftransform(); gl_FrontColor = gl_Color; }\n",
                    ),
                    (GL_FRAGMENT_SHADER, FS_110),
                ],
                true,
            ),
            (
                "110",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 110\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (GL_FRAGMENT_SHADER, FS_110),
                ],
                true,
            ),
            (
                "120 invariant",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 120\ninvariant gl_Position;\nvoid main() { gl_Position = ftransform(); }\n",
                    ),
                    (GL_FRAGMENT_SHADER, FS_110),
                ],
                true,
            ),
            (
                "130",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 130\nin vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_FRAGMENT_SHADER,
                        "#version 130\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n",
                    ),
                ],
                true,
            ),
            (
                "140",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 140\nin vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_FRAGMENT_SHADER,
                        "#version 140\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n",
                    ),
                ],
                true,
            ),
            (
                "150 compatibility",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 150 compatibility\nvoid main() { gl_Position = ftransform(); }\n",
                    ),
                    (
                        GL_FRAGMENT_SHADER,
                        "#version 150 compatibility\nvoid main() { gl_FragColor = vec4(1.0); }\n",
                    ),
                ],
                true,
            ),
            (
                "330 early return",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 330 core\nlayout(location = 0) in vec4 p;\nvoid main() {\n    gl_Position = p;\n    if (p.x > 0.0)\n        return;\n    gl_Position.y += 1.0;\n}\n",
                    ),
                    (GL_FRAGMENT_SHADER, fs330),
                ],
                true,
            ),
            (
                "410 gl_PerVertex",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 410 core\nout gl_PerVertex { vec4 gl_Position; float gl_PointSize; };\nlayout(location = 0) in vec4 p;\nvoid main() { gl_Position = p; gl_PointSize = 1.0; }\n",
                    ),
                    (GL_FRAGMENT_SHADER, fs330),
                ],
                true,
            ),
            (
                "430 own explicit locations",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 430 core\nlayout(location = 3) uniform mat4 m;\nlayout(location = 0) in vec4 p;\nvoid main() { gl_Position = m * p; }\n",
                    ),
                    (GL_FRAGMENT_SHADER, fs330),
                ],
                true,
            ),
            (
                "450 geometry streams",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 450 core\nlayout(location = 0) in vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_GEOMETRY_SHADER,
                        "#version 450 core\nlayout(points) in;\nlayout(points, max_vertices = 2) out;\nlayout(stream = 1) out float other;\nvoid main() {\n    gl_Position = gl_in[0].gl_Position;\n    EmitStreamVertex(0);\n    other = 1.0;\n    EmitStreamVertex(1);\n}\n",
                    ),
                    (GL_FRAGMENT_SHADER, fs330),
                ],
                true,
            ),
            (
                "330 geometry, first declarations in preprocessor conditionals",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 330 core\nlayout(location = 0) in vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_GEOMETRY_SHADER,
                        "#version 330 core\n#define SHADOWS 0\n#if SHADOWS\nuniform mat4 light;\n#endif\n#ifdef GL_ES\nprecision highp float;\n#else\n#endif\nlayout(triangles) in;\nlayout(triangle_strip, max_vertices = 3) out;\nvoid emit(int i) { gl_Position = gl_in[i].gl_Position; EmitVertex (); }\nvoid main() {\n    for (int i = 0; i < 3; i++) emit(i);\n    EndPrimitive();\n}\n",
                    ),
                    (GL_FRAGMENT_SHADER, fs330),
                ],
                true,
            ),
            (
                "150 geometry, every declaration in one conditional",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 150\nin vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_GEOMETRY_SHADER,
                        "#version 150\n#ifndef NO_GS\nlayout(points) in;\nlayout(points, max_vertices = 1) out;\nvoid main() { gl_Position = gl_in[0].gl_Position; EmitVertex(); }\n#endif\n",
                    ),
                    (
                        GL_FRAGMENT_SHADER,
                        "#version 150\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n",
                    ),
                ],
                true,
            ),
            (
                "450 tessellation",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 450 core\nlayout(location = 0) in vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_TESS_CONTROL_SHADER,
                        "#version 450 core\nlayout(vertices = 3) out;\nvoid main() {\n    gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;\n    gl_TessLevelOuter[0] = 1.0; gl_TessLevelOuter[1] = 1.0; gl_TessLevelOuter[2] = 1.0;\n    gl_TessLevelInner[0] = 1.0;\n}\n",
                    ),
                    (
                        GL_TESS_EVALUATION_SHADER,
                        "#version 450 core\nlayout(triangles) in;\nvoid main() {\n    gl_Position = gl_TessCoord.x * gl_in[0].gl_Position + gl_TessCoord.y * gl_in[1].gl_Position + gl_TessCoord.z * gl_in[2].gl_Position;\n}\n",
                    ),
                    (GL_FRAGMENT_SHADER, fs330),
                ],
                true,
            ),
            (
                "100 es",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_FRAGMENT_SHADER,
                        "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = vec4(1.0); }\n",
                    ),
                ],
                false,
            ),
            (
                "300 es",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 300 es\nin vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_FRAGMENT_SHADER,
                        "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n",
                    ),
                ],
                false,
            ),
            (
                "310 es",
                vec![
                    (
                        GL_VERTEX_SHADER,
                        "#version 310 es\nin vec4 p;\nvoid main() { gl_Position = p; }\n",
                    ),
                    (
                        GL_FRAGMENT_SHADER,
                        "#version 310 es\nprecision mediump float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n",
                    ),
                ],
                false,
            ),
        ]
    }

    #[test]
    fn the_last_stage_of_every_glsl_version_relinks_with_the_shift() {
        let f = fixture();
        // SAFETY: the fixture's context is current.
        unsafe {
            for (name, stages, layer) in programs() {
                let program = f.p.program(&stages);
                let before = f.link.attached_shaders(program);
                let outcome = shift_last_stage(
                    &f.link,
                    program,
                    LayerWrite::FromUniform,
                    Some(f.location),
                    false,
                );
                let LinkOutcome::Shifted(s) = outcome else {
                    panic!("{name}: {outcome:?}");
                };
                assert_eq!(
                    s.stage,
                    vertex::last_stage(stages.iter().map(|&(t, _)| t)).unwrap(),
                    "{name}"
                );
                assert_eq!(s.layer, layer, "{name}: gl_Layer written");
                assert!(f.p.linked(program), "{name}");
                let at = uniform_location(&f.p, program);
                // Every desktop version takes the reserved location (ES
                // before 3.10 has no explicit uniform locations).
                assert_eq!(
                    s.location.is_some(),
                    !name.ends_with(" es") || name == "310 es",
                    "{name}"
                );
                match s.location {
                    Some(l) => assert_eq!(at, l as i32, "{name}: the reserved location"),
                    None => assert!(at >= 0, "{name}: the uniform is there"),
                }
                let mut after = f.link.attached_shaders(program);
                after.sort_unstable();
                let mut before = before;
                before.sort_unstable();
                assert_eq!(after, before, "{name}: the user's shaders attached again");
                eprintln!("{name}: {:?} stage, location {:?}", s.stage, s.location);
                (f.p.delete_program)(program);
            }
            assert_eq!((f.p.get_error)(), 0);
        }
    }

    #[test]
    fn the_viewport_index_form_compiles_in_every_stage() {
        let f = fixture();
        let options = Options {
            layer: LayerWrite::ViewportIndex,
            location: Some(f.location),
        };
        for (name, stages, layer) in programs() {
            if !layer {
                continue;
            }
            for &(ty, src) in &stages {
                let Some(stage) = Stage::from_gl(ty) else {
                    continue;
                };
                if Some(stage) != vertex::last_stage(stages.iter().map(|&(t, _)| t)) {
                    continue;
                }
                // gl_ViewportIndex is a geometry shader's from GLSL 4.10
                // (GL_ARB_viewport_array) on.
                if stage == Stage::Geometry && vertex::scan(src).version.number < 410 {
                    continue;
                }
                let Ok(Rewrite::Shifted(out)) = vertex::shift_position(src, stage, options) else {
                    panic!("{name}: not rewritten");
                };
                // SAFETY: the fixture's context is current.
                let compiled = unsafe { f.p.shader(ty, &out) };
                assert!(compiled.is_ok(), "{name}: {compiled:?}\n{out}");
            }
        }
    }

    #[test]
    fn what_is_not_rewritten_is_linked_as_the_user_linked_it() {
        let f = fixture();
        // SAFETY: the fixture's context is current.
        unsafe {
            // Fragment shader only: fixed-function vertices.
            let program = f.p.program(&[(GL_FRAGMENT_SHADER, FS_110)]);
            assert!(matches!(
                shift_last_stage(
                    &f.link,
                    program,
                    LayerWrite::FromUniform,
                    Some(f.location),
                    false
                ),
                LinkOutcome::NotNeeded(_)
            ));
            // The program's own identifier in our namespace.
            let program = f.p.program(&[
                (GL_VERTEX_SHADER, "#version 330\nuniform vec4 gls_auto_eye;\nvoid main() { gl_Position = gls_auto_eye; }\n"),
                (GL_FRAGMENT_SHADER, FS_110),
            ]);
            let outcome = shift_last_stage(
                &f.link,
                program,
                LayerWrite::FromUniform,
                Some(f.location),
                false,
            );
            assert!(
                matches!(&outcome, LinkOutcome::Kept(why) if why.contains("gls_auto_eye")),
                "{outcome:?}"
            );
            assert!(f.p.linked(program));
        }
    }

    #[test]
    fn compile_errors_name_the_users_lines() {
        let f = fixture();
        for (version, next) in [
            ("#version 120\n", "attribute vec4 p;\n"),
            ("#version 330 core\n", "in vec4 p;\n"),
        ] {
            let src =
                format!("{version}{next}void main() {{\n    gl_Position = p;\n    nonsense;\n}}\n");
            let out = match vertex::shift_position(
                &src,
                Stage::Vertex,
                Options {
                    layer: LayerWrite::FromUniform,
                    location: Some(f.location),
                },
            ) {
                Ok(Rewrite::Shifted(s)) => s,
                other => panic!("{other:?}"),
            };
            // SAFETY: the fixture's context is current.
            let own = unsafe { f.p.shader(GL_VERTEX_SHADER, &src) }.unwrap_err();
            let ours = unsafe { f.p.shader(GL_VERTEX_SHADER, &out) }.unwrap_err();
            assert!(own.contains("0:5("), "{own}");
            assert!(
                ours.contains("0:5("),
                "{version}: the user's error at line 5, got {ours}"
            );
        }
    }

    #[test]
    fn separable_programs_get_the_shift_before_they_are_made() {
        let f = fixture();
        let src = "#version 410 core\nout gl_PerVertex { vec4 gl_Position; };\nlayout(location = 0) in vec4 p;\nvoid main() { gl_Position = p; }\n";
        let out = shift_separable(
            GL_VERTEX_SHADER,
            &[&src[..20], &src[20..]],
            LayerWrite::FromUniform,
            Some(f.location),
            false,
        )
        .unwrap()
        .expect("a vertex stage is shifted");
        assert_eq!(
            shift_separable(
                GL_FRAGMENT_SHADER,
                &[FS_110],
                LayerWrite::FromUniform,
                None,
                false
            ),
            Ok(None)
        );
        let c = CString::new(out).unwrap();
        // SAFETY: the fixture's context is current; one string.
        unsafe {
            let program = (f.p.create_shader_programv)(GL_VERTEX_SHADER, 1, &c.as_ptr());
            assert!(f.p.linked(program), "{}", f.p.program_log(program));
            assert_eq!(uniform_location(&f.p, program), f.location as i32);
            // Each separable program's eye is its own: set without using it.
            (f.p.program_uniform4f)(program, f.location as i32, 0.07, 4.0, 1.0, 0.0);
            assert_eq!((f.p.get_error)(), 0);
        }
    }

    /// Eye values as the layer sets them: (e·s, C, layer, 0).
    fn eye_values(eye: Eye, s: f32, c: f32) -> [f32; 4] {
        match eye {
            Eye::Left => [-s, c, 0.0, 0.0],
            Eye::Right => [s, c, 1.0, 0.0],
        }
    }

    /// Quads at w = 2, 4 (the convergence) and 10 under a perspective
    /// `m`, one slanted across depths, and one HUD quad under an
    /// orthographic matrix (w = 1): 5 quads of 6 vertices (x, y, z).
    fn quads() -> Vec<f32> {
        let mut v = Vec::new();
        let mut quad = |x0: f32, y0: f32, x1: f32, y1: f32, z0: f32, z1: f32| {
            for (x, y, z) in [
                (x0, y0, z0),
                (x1, y0, z1),
                (x1, y1, z1),
                (x0, y0, z0),
                (x1, y1, z1),
                (x0, y1, z0),
            ] {
                v.extend([x, y, z]);
            }
        };
        quad(-6.0, -4.0, 6.0, 4.0, -10.0, -10.0);
        quad(-1.5, -1.0, 0.5, 0.5, -4.0, -4.0);
        quad(-0.3, -0.2, 0.1, 0.3, -2.0, -2.0);
        quad(0.2, -1.5, 3.0, -0.5, -2.5, -9.0);
        quad(10.0, 100.0, 40.0, 110.0, 0.0, 0.0);
        v
    }

    /// The row-major 4x4 frustum (-0.5, 0.5, -0.375, 0.375, 1, 20) and the
    /// orthographic (0, 160, 0, 120, -1, 1), as GL wants them (column-major).
    fn matrices() -> ([f32; 16], [f32; 16]) {
        let (n, f) = (1.0f32, 20.0f32);
        let frustum = [
            2.0 * n,
            0.0,
            0.0,
            0.0,
            0.0,
            2.0 * n / 0.75,
            0.0,
            0.0,
            0.0,
            0.0,
            -(f + n) / (f - n),
            -1.0,
            0.0,
            0.0,
            -2.0 * f * n / (f - n),
            0.0,
        ];
        let ortho = [
            2.0 / 160.0,
            0.0,
            0.0,
            0.0,
            0.0,
            2.0 / 120.0,
            0.0,
            0.0,
            0.0,
            0.0,
            -1.0,
            0.0,
            -1.0,
            -1.0,
            0.0,
            1.0,
        ];
        (frustum, ortho)
    }

    /// The matrix form of the rule, by hand: row 0 += k·row 3 − k·C·(0,0,0,1);
    /// an orthographic matrix (row 3 = (0,0,0,1)) as it is.
    fn by_hand(m: [f32; 16], k: f32, c: f32) -> [f32; 16] {
        let mut out = m;
        if [m[3], m[7], m[11], m[15]] != [0.0, 0.0, 0.0, 1.0] {
            for col in 0..4 {
                out[4 * col] += k * m[4 * col + 3];
            }
            out[12] -= k * c;
        }
        out
    }

    /// A core program (vertex + optional geometry + fragment) drawn mono
    /// through the layer's mechanism — its last stage rewritten, every
    /// draw issued once per eye with the eye's values — and by a program
    /// that draws each eye itself with the rule applied to its matrices by
    /// hand; the eyes compared pixel by pixel.
    fn compare_with_hand_drawn_eyes(stages: &[(u32, &str)], mode: u32) {
        compare_eyes(stages, mode, LayerWrite::FromUniform);
    }

    /// As [`compare_with_hand_drawn_eyes`], the eye's index written to
    /// `index`: gl_Layer into a layered target, or gl_ViewportIndex into a
    /// double-width one (viewport 0 the left half, 1 the right, each
    /// scissored), whose halves are compared.
    fn compare_eyes(stages: &[(u32, &str)], mode: u32, index: LayerWrite) {
        const W: i32 = 160;
        const H: i32 = 120;
        let (s, c) = (0.07f32, 4.0f32);
        let f = fixture();
        let colours = [
            [0.0f32, 0.0, 1.0, 1.0],
            [0.0, 1.0, 0.0, 1.0],
            [1.0, 0.0, 0.0, 1.0],
            [1.0, 0.4, 0.0, 1.0],
            [1.0, 1.0, 1.0, 1.0],
        ];
        // SAFETY: the fixture's context is current.
        unsafe {
            let p = &f.p;
            let mut vao = 0;
            (p.gen_vertex_arrays)(1, &mut vao);
            (p.bind_vertex_array)(vao);
            let v = quads();
            let mut vbo = 0;
            (p.gen_buffers)(1, &mut vbo);
            (p.bind_buffer)(GL_ARRAY_BUFFER, vbo);
            (p.buffer_data)(
                GL_ARRAY_BUFFER,
                (v.len() * 4) as isize,
                v.as_ptr().cast(),
                GL_STATIC_DRAW,
            );
            (p.vertex_attrib_pointer)(0, 3, GL_FLOAT, 0, 0, std::ptr::null());
            (p.enable_vertex_attrib_array)(0);
            (p.viewport)(0, 0, W, H);
            (p.clear_color)(0.2, 0.2, 0.2, 1.0);
            (p.enable)(GL_DEPTH_TEST);
            (p.patch_parameteri)(GL_PATCH_VERTICES, 3);
            let (frustum, ortho) = matrices();
            let draw_all = |program: u32, before_each: &mut dyn FnMut(usize, &mut dyn FnMut())| {
                let lc = (p.get_uniform_location)(program, c"colour".as_ptr());
                for (i, colour) in colours.iter().enumerate() {
                    (p.uniform4f)(lc, colour[0], colour[1], colour[2], colour[3]);
                    before_each(i, &mut || {
                        (p.draw_arrays)(mode, (i * 6) as i32, 6);
                    });
                }
            };
            // Under the layer.
            let mono = p.program(stages);
            let outcome = shift_last_stage(&f.link, mono, index, Some(f.location), false);
            assert!(matches!(outcome, LinkOutcome::Shifted(_)), "{outcome:?}");
            (p.use_program)(mono);
            let lm = (p.get_uniform_location)(mono, c"m".as_ptr());
            let wide = index == LayerWrite::ViewportIndex;
            // The double-width target: the left layer of a 2W-wide one.
            let layered = EyeTarget::create(&f.tf, if wide { 2 * W } else { W }, H).unwrap();
            if wide {
                layered.bind_eye(&f.tf, Eye::Left);
                for e in 0..2 {
                    (p.viewport_indexedf)(e as u32, (e * W) as f32, 0.0, W as f32, H as f32);
                    (p.scissor_indexed)(e as u32, e * W, 0, W, H);
                }
                (p.viewport)(0, 0, 2 * W, H);
            }
            (p.clear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            if wide {
                for e in 0..2 {
                    (p.viewport_indexedf)(e as u32, (e * W) as f32, 0.0, W as f32, H as f32);
                }
                (p.enable)(GL_SCISSOR_TEST);
            }
            draw_all(mono, &mut |i, draw| {
                (p.uniform_matrix4fv)(
                    lm,
                    1,
                    0,
                    if i == 4 {
                        ortho.as_ptr()
                    } else {
                        frustum.as_ptr()
                    },
                );
                for eye in [Eye::Left, Eye::Right] {
                    let [a, b, l, z] = eye_values(eye, s, c);
                    (p.uniform4f)(f.location as i32, a, b, l, z);
                    draw();
                }
            });
            let got = if wide {
                (p.disable)(GL_SCISSOR_TEST);
                (p.viewport)(0, 0, W, H);
                let both = layered.read(&f.tf, Eye::Left);
                let half = |e: usize| -> Vec<u8> {
                    both.chunks((8 * W) as usize)
                        .flat_map(|row| {
                            row[e * (4 * W) as usize..(e + 1) * (4 * W) as usize].to_vec()
                        })
                        .collect()
                };
                [half(0), half(1)]
            } else {
                [
                    layered.read(&f.tf, Eye::Left),
                    layered.read(&f.tf, Eye::Right),
                ]
            };
            // By hand, one eye at a time.
            let own = p.program(stages);
            (p.use_program)(own);
            let lm = (p.get_uniform_location)(own, c"m".as_ptr());
            let oracle = EyeTarget::create(&f.tf, W, H).unwrap();
            for (n, eye) in [Eye::Left, Eye::Right].into_iter().enumerate() {
                oracle.bind_eye(&f.tf, eye);
                (p.clear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                let k = eye.sign() as f32 * s;
                draw_all(own, &mut |i, draw| {
                    let m = by_hand(if i == 4 { ortho } else { frustum }, k, c);
                    (p.uniform_matrix4fv)(lm, 1, 0, m.as_ptr());
                    draw();
                });
                let want = oracle.read(&f.tf, eye);
                let differ = differing_pixels(&got[n], &want);
                // The shader adds e·s·(w − C) to x after the matrix, the
                // oracle folds it into the matrix: the same value up to
                // float rounding, which may move an edge pixel.
                assert!(
                    differ <= 8,
                    "{eye:?}: {differ} of {} pixels differ from the eye drawn by hand",
                    W * H
                );
                eprintln!("{eye:?}: {differ} pixels differ");
            }
            assert!(differing_pixels(&got[0], &got[1]) > 500, "no stereo");
            assert_eq!((p.get_error)(), 0);
            layered.destroy(&f.tf);
            oracle.destroy(&f.tf);
        }
    }

    const VS: &str = "#version 330 core\nlayout(location = 0) in vec3 p;\nuniform mat4 m;\nvoid main() {\n    gl_Position = m * vec4(p, 1.0);\n}\n";
    const FS: &str =
        "#version 330 core\nuniform vec4 colour;\nout vec4 c;\nvoid main() { c = colour; }\n";

    #[test]
    fn a_vertex_shader_program_in_both_eyes_equals_each_eye_drawn_by_hand() {
        compare_with_hand_drawn_eyes(
            &[(GL_VERTEX_SHADER, VS), (GL_FRAGMENT_SHADER, FS)],
            GL_TRIANGLES,
        );
    }

    #[test]
    fn the_viewport_index_form_in_a_double_width_target_equals_each_eye_drawn_by_hand() {
        compare_eyes(
            &[(GL_VERTEX_SHADER, VS), (GL_FRAGMENT_SHADER, FS)],
            GL_TRIANGLES,
            LayerWrite::ViewportIndex,
        );
    }

    #[test]
    fn a_geometry_shader_program_in_both_eyes_equals_each_eye_drawn_by_hand() {
        let gs = "#version 330 core\nlayout(triangles) in;\nlayout(triangle_strip, max_vertices = 3) out;\nvoid main() {\n    for (int i = 0; i < 3; i++) {\n        gl_Position = gl_in[i].gl_Position;\n        if (i == 1)\n            EmitVertex();\n        else\n            EmitVertex();\n    }\n    EndPrimitive();\n}\n";
        compare_with_hand_drawn_eyes(
            &[
                (GL_VERTEX_SHADER, VS),
                (GL_GEOMETRY_SHADER, gs),
                (GL_FRAGMENT_SHADER, FS),
            ],
            GL_TRIANGLES,
        );
    }

    #[test]
    fn a_tessellation_program_in_both_eyes_equals_each_eye_drawn_by_hand() {
        let tcs = "#version 400 core\nlayout(vertices = 3) out;\nvoid main() {\n    gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;\n    gl_TessLevelOuter[0] = 2.0; gl_TessLevelOuter[1] = 2.0; gl_TessLevelOuter[2] = 2.0;\n    gl_TessLevelInner[0] = 2.0;\n}\n";
        let tes = "#version 400 core\nlayout(triangles) in;\nvoid main() {\n    gl_Position = gl_TessCoord.x * gl_in[0].gl_Position + gl_TessCoord.y * gl_in[1].gl_Position + gl_TessCoord.z * gl_in[2].gl_Position;\n}\n";
        compare_with_hand_drawn_eyes(
            &[
                (GL_VERTEX_SHADER, VS),
                (GL_TESS_CONTROL_SHADER, tcs),
                (GL_TESS_EVALUATION_SHADER, tes),
                (GL_FRAGMENT_SHADER, FS),
            ],
            GL_PATCHES,
        );
    }

    /// Separate shader objects: a pipeline of a vertex program and a
    /// geometry program, each rewritten as its own last stage. The layer
    /// gives the eye to the pipeline's last stage and the neutral value to
    /// the other, so the position is shifted once: the eyes equal a plain
    /// pipeline drawing each eye with the rule applied by hand.
    #[test]
    fn a_program_pipeline_shifts_once_in_its_last_stage() {
        const W: i32 = 160;
        const H: i32 = 120;
        let (s, c) = (0.07f32, 4.0f32);
        let vs = "#version 410 core\nout gl_PerVertex { vec4 gl_Position; };\nlayout(location = 0) in vec3 p;\nuniform mat4 m;\nvoid main() { gl_Position = m * vec4(p, 1.0); }\n";
        let gs = "#version 410 core\nlayout(triangles) in;\nlayout(triangle_strip, max_vertices = 3) out;\nin gl_PerVertex { vec4 gl_Position; } gl_in[];\nout gl_PerVertex { vec4 gl_Position; };\nvoid main() {\n    for (int i = 0; i < 3; i++) {\n        gl_Position = gl_in[i].gl_Position;\n        EmitVertex();\n    }\n}\n";
        let fs =
            "#version 410 core\nuniform vec4 colour;\nout vec4 c;\nvoid main() { c = colour; }\n";
        let f = fixture();
        let p = &f.p;
        let colours = [
            [0.0f32, 0.0, 1.0, 1.0],
            [0.0, 1.0, 0.0, 1.0],
            [1.0, 0.0, 0.0, 1.0],
            [1.0, 0.4, 0.0, 1.0],
            [1.0, 1.0, 1.0, 1.0],
        ];
        // SAFETY: the fixture's context is current; strings NUL-terminated.
        unsafe {
            let separable = |ty: u32, src: &str, rewrite: bool| -> u32 {
                let src = match rewrite {
                    true => shift_separable(
                        ty,
                        &[src],
                        LayerWrite::FromUniform,
                        Some(f.location),
                        false,
                    )
                    .unwrap()
                    .unwrap_or(src.to_owned()),
                    false => src.to_owned(),
                };
                let cs = CString::new(src).unwrap();
                let prog = (p.create_shader_programv)(ty, 1, &cs.as_ptr());
                assert!(p.linked(prog), "{}", p.program_log(prog));
                prog
            };
            let pipeline = |rewrite: bool| -> (u32, u32, u32, u32) {
                let (v, g, fr) = (
                    separable(GL_VERTEX_SHADER, vs, rewrite),
                    separable(GL_GEOMETRY_SHADER, gs, rewrite),
                    separable(GL_FRAGMENT_SHADER, fs, false),
                );
                let mut pipe = 0;
                (p.gen_program_pipelines)(1, &mut pipe);
                (p.use_program_stages)(pipe, 0x1, v); // GL_VERTEX_SHADER_BIT
                (p.use_program_stages)(pipe, 0x4, g); // GL_GEOMETRY_SHADER_BIT
                (p.use_program_stages)(pipe, 0x2, fr); // GL_FRAGMENT_SHADER_BIT
                (pipe, v, g, fr)
            };
            let mut vao = 0;
            (p.gen_vertex_arrays)(1, &mut vao);
            (p.bind_vertex_array)(vao);
            let v = quads();
            let mut vbo = 0;
            (p.gen_buffers)(1, &mut vbo);
            (p.bind_buffer)(GL_ARRAY_BUFFER, vbo);
            (p.buffer_data)(
                GL_ARRAY_BUFFER,
                (v.len() * 4) as isize,
                v.as_ptr().cast(),
                GL_STATIC_DRAW,
            );
            (p.vertex_attrib_pointer)(0, 3, GL_FLOAT, 0, 0, std::ptr::null());
            (p.enable_vertex_attrib_array)(0);
            (p.viewport)(0, 0, W, H);
            (p.clear_color)(0.2, 0.2, 0.2, 1.0);
            (p.enable)(GL_DEPTH_TEST);
            let (frustum, ortho) = matrices();
            // The layer's way: one draw per eye, the eye in the last stage.
            let (pipe, vp, gp, fp) = pipeline(true);
            (p.bind_program_pipeline)(pipe);
            let (lm, lc) = (
                (p.get_uniform_location)(vp, c"m".as_ptr()),
                (p.get_uniform_location)(fp, c"colour".as_ptr()),
            );
            assert_eq!(
                uniform_location(p, vp),
                f.location as i32,
                "the vertex program is rewritten too"
            );
            (p.program_uniform4f)(vp, f.location as i32, 0.0, c, -1.0, 0.0);
            let layered = EyeTarget::create(&f.tf, W, H).unwrap();
            (p.clear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            for (i, colour) in colours.iter().enumerate() {
                (p.program_uniform4fv)(fp, lc, 1, colour.as_ptr());
                (p.program_uniform_matrix4fv)(
                    vp,
                    lm,
                    1,
                    0,
                    if i == 4 {
                        ortho.as_ptr()
                    } else {
                        frustum.as_ptr()
                    },
                );
                for eye in [Eye::Left, Eye::Right] {
                    (p.program_uniform4fv)(
                        gp,
                        f.location as i32,
                        1,
                        eye_values(eye, s, c).as_ptr(),
                    );
                    (p.draw_arrays)(GL_TRIANGLES, (i * 6) as i32, 6);
                }
            }
            let got = [
                layered.read(&f.tf, Eye::Left),
                layered.read(&f.tf, Eye::Right),
            ];
            // By hand: a plain pipeline, each eye's matrices.
            let (pipe, vp, _, fp) = pipeline(false);
            (p.bind_program_pipeline)(pipe);
            let (lm, lc) = (
                (p.get_uniform_location)(vp, c"m".as_ptr()),
                (p.get_uniform_location)(fp, c"colour".as_ptr()),
            );
            let oracle = EyeTarget::create(&f.tf, W, H).unwrap();
            for (n, eye) in [Eye::Left, Eye::Right].into_iter().enumerate() {
                oracle.bind_eye(&f.tf, eye);
                (p.clear)(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                for (i, colour) in colours.iter().enumerate() {
                    (p.program_uniform4fv)(fp, lc, 1, colour.as_ptr());
                    let m = by_hand(
                        if i == 4 { ortho } else { frustum },
                        eye.sign() as f32 * s,
                        c,
                    );
                    (p.program_uniform_matrix4fv)(vp, lm, 1, 0, m.as_ptr());
                    (p.draw_arrays)(GL_TRIANGLES, (i * 6) as i32, 6);
                }
                let differ = differing_pixels(&got[n], &oracle.read(&f.tf, eye));
                assert!(
                    differ <= 8,
                    "{eye:?}: {differ} pixels differ from the eye drawn by hand"
                );
            }
            assert!(differing_pixels(&got[0], &got[1]) > 500, "no stereo");
            assert_eq!((p.get_error)(), 0);
        }
    }
}

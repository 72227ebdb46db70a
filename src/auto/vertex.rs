//! The clip-space shift in a program's last vertex-processing stage: the
//! source edit. Pure string work; [`crate::auto::link`] compiles and links
//! the result.
//!
//! Every position that reaches the rasterizer gets, for the eye being
//! drawn, 3D Vision's rule (REFERENCE.md):
//!
//! ```text
//! if (gl_Position.w != 1.0)
//!     gl_Position.x += gls_auto_eye.x * (gl_Position.w - gls_auto_eye.y);
//! if (gls_auto_eye.z >= 0.0)
//!     gl_Layer = int(gls_auto_eye.z);
//! ```
//!
//! with the uniform `vec4 gls_auto_eye` = (e·s, C, layer, 0): e = −1 for
//! the left eye and +1 for the right, s the effective separation, C the
//! convergence, and the eye's layer of the emulated framebuffer (or −1
//! where the draw goes elsewhere: gl_Layer is then the shader's own).
//! Where automatic convergence knows the screen only as a depth z_c of a
//! projection it does not know (matrices in uniform buffers, built in the
//! shader), the uniform is (e·s, z_c, layer, k) and w − C is computed as
//! (z_c·w − z)·k ([`shift_statement`]): equal for clip z = α·w + β with
//! k = 1/(z_c − α), whatever β.
//! Positions with w == 1 (orthographic HUDs, text, full-screen passes) are
//! left exactly as they were; so is everything when e·s is 0.
//!
//! Where the rule goes, by stage:
//! - **vertex** and **tessellation evaluation** shaders: after the user's
//!   `main` returns (early `return`s included). The user's `main` becomes
//!   `gls_auto_user_main` by a `#define` placed right after `#version`
//!   (the preprocessor never sees comments, so `main` in a comment is
//!   untouched), and a new `main` that calls it and then applies the rule
//!   is appended, with the uniform's declaration;
//! - **geometry** shaders: at every `EmitVertex()` and
//!   `EmitStreamVertex(0)`, where the vertex is emitted. Function-like
//!   macros turn each call into `(gls_auto_emit(n), EmitVertex())`, an
//!   expression, so `if (c) EmitVertex(); else …` keeps its meaning;
//!   `gls_auto_emit` is declared before the shader's first declaration (so
//!   after every `#extension` of the shader) and defined at the end. Only
//!   stream 0 is rasterized, so other streams' vertices are not shifted.
//!
//! Directives added after `#version`: `#extension
//! GL_ARB_shader_viewport_layer_array : enable` where a vertex or
//! tessellation evaluation shader writes gl_Layer (geometry shaders have
//! it built in), and `#extension GL_ARB_explicit_uniform_location :
//! enable` where the uniform gets a reserved location before GLSL 4.30
//! (before 3.30 with `GL_ARB_explicit_attrib_location`, which Mesa wants
//! for explicit uniform locations too).
//! Each insertion is followed by a `#line` directive that gives the next
//! user line the number it had, by the rule of the shader's version (GLSL
//! 3.30 and ES 3.00 changed what `#line N` means), so compile errors name
//! the user's lines.
//!
//! What the rule needs from the source, checked here ([`NotCovered`]): a
//! definition of `main` (another shader object of the same stage without
//! one is left alone: see [`defines_main`](crate::auto::glsl::defines_main)),
//! no identifier of our own (`gls_auto_…`) already in use, and, when the
//! stage redeclares `out gl_PerVertex`, gl_Position among its members
//! (else the stage writes no position: nothing to shift, [`Rewrite::NotNeeded`]).
//! `invariant gl_Position`, `precise`, precision statements, `ftransform()`
//! and `gl_Position` in an output block need nothing: the rule reads and
//! writes gl_Position after the user's code, by the same expression in
//! every rewritten program, so invariance between them holds.

use crate::auto::glsl::{self, Profile, Scan, Version};

/// The uniform that carries (e·s, C, layer, 0) for the eye being drawn.
pub const EYE_UNIFORM: &str = "gls_auto_eye";
/// What the user's `main` is renamed to.
const USER_MAIN: &str = "gls_auto_user_main";
/// The geometry shader's per-emit function.
const EMIT: &str = "gls_auto_emit";
/// The prefix of every identifier the rewrite adds.
const PREFIX: &str = "gls_auto_";

/// GL_VERTEX_SHADER.
pub const GL_VERTEX_SHADER: u32 = 0x8B31;
/// GL_TESS_EVALUATION_SHADER.
pub const GL_TESS_EVALUATION_SHADER: u32 = 0x8E87;
/// GL_GEOMETRY_SHADER.
pub const GL_GEOMETRY_SHADER: u32 = 0x8DD9;

/// A vertex-processing stage that can be the last before the rasterizer
/// (GL 4.5 has no mesh shaders). Ordered: a later stage overrides.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Stage {
    /// GL_VERTEX_SHADER.
    Vertex,
    /// GL_TESS_EVALUATION_SHADER.
    TessEvaluation,
    /// GL_GEOMETRY_SHADER.
    Geometry,
}

impl Stage {
    /// The stage of a shader type, or None for a type that is not a
    /// vertex-processing stage that can reach the rasterizer (fragment,
    /// compute, tessellation control).
    pub fn from_gl(shader_type: u32) -> Option<Stage> {
        match shader_type {
            GL_VERTEX_SHADER => Some(Stage::Vertex),
            GL_TESS_EVALUATION_SHADER => Some(Stage::TessEvaluation),
            GL_GEOMETRY_SHADER => Some(Stage::Geometry),
            _ => None,
        }
    }

    /// The GL shader type.
    pub fn gl(self) -> u32 {
        match self {
            Stage::Vertex => GL_VERTEX_SHADER,
            Stage::TessEvaluation => GL_TESS_EVALUATION_SHADER,
            Stage::Geometry => GL_GEOMETRY_SHADER,
        }
    }

    /// The stage's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Vertex => "vertex",
            Stage::TessEvaluation => "tessellation evaluation",
            Stage::Geometry => "geometry",
        }
    }
}

/// The last vertex-processing stage among shader types (geometry, else
/// tessellation evaluation, else vertex): the one whose gl_Position the
/// rasterizer gets.
pub fn last_stage(shader_types: impl IntoIterator<Item = u32>) -> Option<Stage> {
    shader_types.into_iter().filter_map(Stage::from_gl).max()
}

/// How the rewritten stage chooses the eye's layer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayerWrite {
    /// gl_Layer from the uniform (layered eye targets).
    FromUniform,
    /// gl_ViewportIndex from the uniform (one double-width target, a
    /// viewport per eye; [`crate::auto`], "How a draw reaches both eyes").
    ViewportIndex,
    /// No index written: the eye's target is chosen outside the shader
    /// (ES shaders, which have neither output in these stages).
    None,
}

impl LayerWrite {
    /// The built-in the index goes to, if any.
    fn builtin(self) -> Option<&'static str> {
        match self {
            LayerWrite::FromUniform => Some("gl_Layer"),
            LayerWrite::ViewportIndex => Some("gl_ViewportIndex"),
            LayerWrite::None => None,
        }
    }
}

/// Choices of a rewrite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Whether gl_Layer is written.
    pub layer: LayerWrite,
    /// A reserved uniform location for [`EYE_UNIFORM`], the same in every
    /// rewritten program (then `glUniform4f(location, …)` reaches whichever
    /// program is current, display lists included); None: the location
    /// is looked up after the link.
    pub location: Option<u32>,
}

/// What [`shift_position`] made of a source.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Rewrite {
    /// The edited source.
    Shifted(String),
    /// Nothing to do: this shader object defines no `main` (another object
    /// of the stage does), or the stage writes no gl_Position.
    NotNeeded(&'static str),
}

/// Why a stage cannot be rewritten; the program then draws each eye with
/// its position unshifted (both eyes alike, flat at the screen).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NotCovered(pub String);

/// Whether the stage at `version` can write gl_Layer in this context:
/// geometry shaders from GLSL 1.50 (ES: never, without
/// EXT_geometry_shader), the other stages through
/// GL_ARB_shader_viewport_layer_array, which ES shaders cannot enable.
pub fn can_write_layer(stage: Stage, version: Version) -> bool {
    match (version.profile, stage) {
        (Profile::Es, _) => false,
        (_, Stage::Geometry) => version.number >= 150,
        _ => true,
    }
}

/// A `#line` directive that gives the next line number `n`, by the rule
/// of `version`.
fn line_directive(version: Version, n: u32) -> String {
    if version.line_directive_names_next_line() {
        format!("#line {n}\n")
    } else {
        format!("#line {}\n", n.saturating_sub(1))
    }
}

/// The uniform's declaration.
fn uniform_declaration(version: Version, location: Option<u32>) -> String {
    let precision = if version.profile == Profile::Es {
        "highp "
    } else {
        ""
    };
    match location {
        Some(l) => format!("layout(location = {l}) uniform {precision}vec4 {EYE_UNIFORM};\n"),
        None => format!("uniform {precision}vec4 {EYE_UNIFORM};\n"),
    }
}

/// The rule's statements, indented for a function body.
fn rule(layer: LayerWrite) -> String {
    let mut s = shift_statement();
    if let Some(builtin) = layer.builtin() {
        s.push_str(&format!(
            "    if ({EYE_UNIFORM}.z >= 0.0)\n        {builtin} = int({EYE_UNIFORM}.z);\n"
        ));
    }
    s
}

/// The shift of gl_Position.x for the eye (module docs): w − C is
/// `gls_auto_eye.w` = 0's form; with `gls_auto_eye.w` = k ≠ 0 the same
/// w − C computed from the clip depth, (z_c·w − z)·k, where the
/// convergence is a depth z_c of a projection automatic stereo does not
/// know ([`crate::auto::converge`]).
pub fn shift_statement() -> String {
    format!(
        "    if (gl_Position.w != 1.0)\n        gl_Position.x += {EYE_UNIFORM}.x * ({EYE_UNIFORM}.w == 0.0 ? gl_Position.w - {EYE_UNIFORM}.y : ({EYE_UNIFORM}.y * gl_Position.w - gl_Position.z) * {EYE_UNIFORM}.w);\n"
    )
}

/// `source` with the eye's shift applied to every position its `stage`
/// hands the rasterizer (module docs).
pub fn shift_position(source: &str, stage: Stage, options: Options) -> Result<Rewrite, NotCovered> {
    let text = glsl::blank_comments(source);
    if !glsl::defines_main(&text) {
        return Ok(Rewrite::NotNeeded("this shader object defines no main"));
    }
    if let Some((_, id)) = glsl::identifiers(&text)
        .into_iter()
        .find(|(_, id)| id.starts_with(PREFIX))
    {
        return Err(NotCovered(format!(
            "the {} shader already uses the name {id}, which the rewrite needs",
            stage.name()
        )));
    }
    if glsl::out_per_vertex_members(&text).is_some_and(|m| !glsl::uses(&m, "gl_Position")) {
        return Ok(Rewrite::NotNeeded(
            "the stage redeclares gl_PerVertex without gl_Position",
        ));
    }
    let scan = glsl::scan(source);
    let version = scan.version;
    if stage == Stage::Geometry && version.number < 150 && version.profile != Profile::Es {
        return Err(NotCovered(format!(
            "a geometry shader of GLSL {} (EXT/ARB_geometry_shader4) is not rewritten",
            version.number
        )));
    }
    let layer = match options.layer {
        LayerWrite::FromUniform | LayerWrite::ViewportIndex if !can_write_layer(stage, version) => {
            return Err(NotCovered(format!(
                "a {} shader of GLSL {} cannot write gl_Layer",
                stage.name(),
                version.number
            )));
        }
        l => l,
    };
    let location = options.location;
    // GL_ARB_shader_viewport_layer_array makes gl_Layer a member of the
    // vertex and tessellation evaluation stages' gl_PerVertex: a shader
    // that redeclares the block must list it to keep it.
    let with_layer;
    let mut source = source;
    if let (Some(builtin), false) = (layer.builtin(), stage == Stage::Geometry) {
        if let Some((brace, members)) = glsl::out_per_vertex(&text) {
            if !glsl::uses(&members, builtin) {
                with_layer = format!("{} int {builtin};{}", &source[..brace], &source[brace..]);
                source = &with_layer;
            }
        }
    }

    let mut head = String::new();
    if layer != LayerWrite::None && stage != Stage::Geometry {
        head.push_str("#extension GL_ARB_shader_viewport_layer_array : enable\n");
    }
    let needs_location_ext = location.is_some()
        && match version.profile {
            Profile::Es => version.number < 310,
            _ => version.number < 430,
        };
    if needs_location_ext {
        // Mesa: "uniform explicit location requires
        // GL_ARB_explicit_uniform_location and either
        // GL_ARB_explicit_attrib_location or GLSL 3.30".
        if version.profile != Profile::Es && version.number < 330 {
            head.push_str("#extension GL_ARB_explicit_attrib_location : enable\n");
        }
        head.push_str("#extension GL_ARB_explicit_uniform_location : enable\n");
    }
    head.push_str(&format!("#define main {USER_MAIN}\n"));
    if stage == Stage::Geometry {
        head.push_str(&format!("#define EmitVertex() ({EMIT}(0), EmitVertex())\n"));
        head.push_str(&format!(
            "#define EmitStreamVertex(s) ({EMIT}(s), EmitStreamVertex(s))\n"
        ));
    }

    let mut out = String::with_capacity(source.len() + 800);
    let (before, rest) = source.split_at(scan.after_version);
    out.push_str(before);
    if scan.version_unterminated {
        out.push('\n');
    }
    out.push_str(&head);
    if scan.after_version > 0 {
        out.push_str(&line_directive(version, scan.after_version_line_number));
    }
    if stage == Stage::Geometry {
        // Declarations the macros need before the shader's first use of
        // EmitVertex: at the line of its first declaration, after its own
        // #extension directives.
        let split = scan.first_token_line - scan.after_version;
        let (pre, post) = rest.split_at(split);
        out.push_str(pre);
        if !pre.is_empty() && !pre.ends_with('\n') {
            out.push('\n');
        }
        out.push_str(&uniform_declaration(version, location));
        out.push_str(&format!("void {EMIT}(int stream);\n"));
        out.push_str(&line_directive(version, scan.first_token_line_number));
        out.push_str(post);
    } else {
        out.push_str(rest);
    }
    if !out.ends_with('\n') {
        out.push('\n');
    }
    out.push_str("#undef main\n");
    match stage {
        Stage::Geometry => {
            out.push_str("#undef EmitVertex\n#undef EmitStreamVertex\n");
            out.push_str(&format!(
                "void {EMIT}(int stream)\n{{\n    if (stream != 0)\n        return;\n{}}}\n",
                rule(layer)
            ));
            out.push_str(&format!("void main()\n{{\n    {USER_MAIN}();\n}}\n"));
        }
        Stage::Vertex | Stage::TessEvaluation => {
            out.push_str(&uniform_declaration(version, location));
            out.push_str(&format!(
                "void main()\n{{\n    {USER_MAIN}();\n{}}}\n",
                rule(layer)
            ));
        }
    }
    Ok(Rewrite::Shifted(out))
}

/// The scan of `source`, for callers that choose options by version.
pub fn scan(source: &str) -> Scan {
    glsl::scan(source)
}

/// `source` as an OpenGL ES context compiles it: without a `#version`
/// directive it is GLSL ES 1.00 there (GLSL 1.10 in desktop GL, which
/// [`scan`] assumes), so it gets the directive, and `#line 0` after it,
/// which keeps every line's number (in ES 1.00 the line after `#line N`
/// is N + 1). A source with a `#version` is returned as it is.
pub fn as_es_compiles(source: String) -> String {
    if glsl::scan(&source).after_version == 0 {
        format!("#version 100\n#line 0\n{source}")
    } else {
        source
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAYERED: Options = Options {
        layer: LayerWrite::FromUniform,
        location: Some(1000),
    };

    fn shifted(source: &str, stage: Stage, options: Options) -> String {
        match shift_position(source, stage, options) {
            Ok(Rewrite::Shifted(s)) => s,
            other => panic!("wanted a rewrite, got {other:?}"),
        }
    }

    #[test]
    fn the_last_stage_is_geometry_then_tessellation_evaluation_then_vertex() {
        let fs = 0x8B30;
        let tcs = 0x8E88;
        assert_eq!(last_stage([fs, GL_VERTEX_SHADER]), Some(Stage::Vertex));
        assert_eq!(
            last_stage([GL_VERTEX_SHADER, tcs, GL_TESS_EVALUATION_SHADER, fs]),
            Some(Stage::TessEvaluation)
        );
        assert_eq!(
            last_stage([
                GL_GEOMETRY_SHADER,
                GL_VERTEX_SHADER,
                GL_TESS_EVALUATION_SHADER
            ]),
            Some(Stage::Geometry)
        );
        assert_eq!(last_stage([fs, tcs]), None);
    }

    #[test]
    fn a_vertex_shader_gets_a_new_main_after_its_own() {
        let src = "#version 330 core\nin vec4 p;\n// void main() in a comment\nvoid main() {\n    if (p.x > 0.0) { gl_Position = p; return; }\n    gl_Position = -p;\n}\n";
        let out = shifted(src, Stage::Vertex, LAYERED);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "#version 330 core");
        assert_eq!(
            lines[1],
            "#extension GL_ARB_shader_viewport_layer_array : enable"
        );
        assert_eq!(
            lines[2],
            "#extension GL_ARB_explicit_uniform_location : enable"
        );
        assert_eq!(lines[3], "#define main gls_auto_user_main");
        // GLSL 3.30: `#line 2` names the next line.
        assert_eq!(lines[4], "#line 2");
        assert_eq!(lines[5], "in vec4 p;");
        assert!(out.contains("// void main() in a comment\n"));
        assert!(out.contains("#undef main\nlayout(location = 1000) uniform vec4 gls_auto_eye;\nvoid main()\n{\n    gls_auto_user_main();\n    if (gl_Position.w != 1.0)\n"));
        assert!(out.contains("gl_Layer = int(gls_auto_eye.z);"));
    }

    #[test]
    fn old_versions_number_lines_their_way_and_need_the_location_extension() {
        let out = shifted(
            "#version 120\nattribute vec4 p;\nvoid main(){gl_Position=ftransform();}",
            Stage::Vertex,
            LAYERED,
        );
        // GLSL 1.20: `#line 1` makes the next line 2.
        assert!(
            out.contains("#define main gls_auto_user_main\n#line 1\nattribute"),
            "{out}"
        );
        assert!(out.contains("#extension GL_ARB_explicit_attrib_location : enable\n#extension GL_ARB_explicit_uniform_location : enable\n"));
        let out = shifted("#version 450\nvoid main(){}", Stage::Vertex, LAYERED);
        assert!(!out.contains("GL_ARB_explicit_uniform_location"));
        // No #version: no #line needed, the define goes first.
        let out = shifted(
            "void main(){}",
            Stage::Vertex,
            Options {
                layer: LayerWrite::FromUniform,
                location: None,
            },
        );
        assert!(
            out.starts_with("#extension GL_ARB_shader_viewport_layer_array : enable\n#define main")
        );
        assert!(out.contains("\nuniform vec4 gls_auto_eye;\n"));
    }

    #[test]
    fn es_shaders_get_highp_and_no_layer() {
        let src =
            "#version 300 es\nprecision mediump float;\nin vec4 p;\nvoid main(){gl_Position=p;}\n";
        let err = shift_position(src, Stage::Vertex, LAYERED).unwrap_err();
        assert!(err.0.contains("cannot write gl_Layer"), "{err:?}");
        let out = shifted(
            src,
            Stage::Vertex,
            Options {
                layer: LayerWrite::None,
                location: None,
            },
        );
        assert!(out.contains("uniform highp vec4 gls_auto_eye;"));
        assert!(!out.contains("gl_Layer"));
        assert!(!out.contains("#extension"));
        assert!(out.contains("#line 2\n"));
    }

    #[test]
    fn geometry_shaders_shift_at_each_emit_of_stream_0() {
        let src = "#version 150\n#extension GL_ARB_gpu_shader5 : enable\nlayout(triangles) in;\nlayout(triangle_strip, max_vertices = 3) out;\nvoid main() {\n    for (int i = 0; i < 3; i++) {\n        gl_Position = gl_in[i].gl_Position;\n        if (i == 0) EmitVertex(); else EmitVertex();\n    }\n}\n";
        let out = shifted(src, Stage::Geometry, LAYERED);
        // The user's #extension stays before every declaration.
        let ext = out.find("GL_ARB_gpu_shader5").unwrap();
        let decl = out.find("vec4 gls_auto_eye;").unwrap();
        assert!(ext < decl, "{out}");
        assert!(out.contains("#define EmitVertex() (gls_auto_emit(0), EmitVertex())\n"));
        assert!(
            out.contains("#define EmitStreamVertex(s) (gls_auto_emit(s), EmitStreamVertex(s))\n")
        );
        // GLSL 1.50: `#line 2` makes the next line 3.
        assert!(
            out.contains("void gls_auto_emit(int stream);\n#line 2\nlayout(triangles) in;"),
            "{out}"
        );
        assert!(out.contains("    if (stream != 0)\n        return;\n"));
        assert!(
            !out.contains("GL_ARB_shader_viewport_layer_array"),
            "built in for geometry shaders"
        );
    }

    #[test]
    fn what_is_not_rewritten_says_why() {
        let no_main = "#version 330\nvec4 helper(vec4 p) { return p; }\n";
        assert_eq!(
            shift_position(no_main, Stage::Vertex, LAYERED),
            Ok(Rewrite::NotNeeded("this shader object defines no main"))
        );
        let no_position = "#version 410\nout gl_PerVertex { float gl_PointSize; };\nvoid main(){ gl_PointSize = 1.0; }\n";
        assert!(matches!(
            shift_position(no_position, Stage::Vertex, LAYERED),
            Ok(Rewrite::NotNeeded(_))
        ));
        let ours = "#version 330\nuniform vec4 gls_auto_eye;\nvoid main(){}\n";
        let err = shift_position(ours, Stage::Vertex, LAYERED).unwrap_err();
        assert!(err.0.contains("gls_auto_eye"), "{err:?}");
        let old_gs = "#version 120\n#extension GL_EXT_geometry_shader4 : enable\nvoid main(){}\n";
        assert!(shift_position(old_gs, Stage::Geometry, LAYERED).is_err());
    }

    #[test]
    fn the_eye_can_choose_a_viewport_instead_of_a_layer() {
        let src = "#version 410\nout gl_PerVertex { vec4 gl_Position; };\nvoid main(){ gl_Position = vec4(0.0); }\n";
        let options = Options {
            layer: LayerWrite::ViewportIndex,
            location: Some(9),
        };
        let out = shifted(src, Stage::Vertex, options);
        assert!(
            out.contains("out gl_PerVertex { int gl_ViewportIndex; vec4 gl_Position; };"),
            "{out}"
        );
        assert!(out.contains("gl_ViewportIndex = int(gls_auto_eye.z);"));
        assert!(!out.contains("gl_Layer"));
        assert!(out.contains("GL_ARB_shader_viewport_layer_array"));
    }

    #[test]
    fn a_block_with_gl_position_is_rewritten() {
        let src = "#version 410\nout gl_PerVertex { vec4 gl_Position; };\ninvariant gl_Position;\nvoid main(){ gl_Position = vec4(0.0); }\n";
        let out = shifted(src, Stage::TessEvaluation, LAYERED);
        assert!(out.contains("gl_Position.x += gls_auto_eye.x"));
        // gl_Layer joins the redeclared block, on its line.
        assert!(
            out.contains("\n#line 2\nout gl_PerVertex { int gl_Layer; vec4 gl_Position; };\n"),
            "{out}"
        );
        let out = shifted(
            src,
            Stage::TessEvaluation,
            Options {
                layer: LayerWrite::None,
                location: None,
            },
        );
        assert!(!out.contains("gl_Layer"));
    }
}

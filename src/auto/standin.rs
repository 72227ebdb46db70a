//! The layer's vertex shader standing in for fixed-function vertex
//! processing: the fast path of fixed-function draws ([`crate::auto`],
//! "Each family of draws"). Fixed function cannot write gl_Layer; this
//! shader does what fixed-function vertex processing does for the state
//! it models, plus the eye's shift and layer, so a fixed-function draw
//! reaches an eye by a uniform change as a shader draw does (measured as
//! variant dff: 1.00–1.06x of the program's own two passes at 400x300).
//!
//! The program object has only this vertex shader: fragments stay
//! fixed-function (texturing, fog, alpha test… as the program set them).
//! `ftransform()` gives exactly the position fixed function computes
//! (GLSL's invariance rule for it), which keeps depth equal between the
//! program's fixed-function and shader passes.
//!
//! Modelled here: the vertex colour (primary, and secondary under
//! GL_COLOR_SUM), texture coordinates through the texture matrix of each
//! unit with a texture enabled, the fog coordinate under GL_FOG
//! (glFogCoord, or the eye-space distance as fixed function uses by
//! default), user clip planes (gl_ClipVertex) and the point size under
//! GL_PROGRAM_POINT_SIZE: each only where fragments read it
//! ([`FixedVertexState`]).
//! Not yet: lighting, texture-coordinate generation, vertex blending —
//! those draws take the slow path of [`crate::auto::fixed`] until the
//! generator models them from the tracked state (as Mesa's
//! `ffvertex_prog` builds its program from a state key).
//!
//! Between draws the uniform holds the neutral value (no shift, layer
//! −1), and glRasterPos* is made with program 0: with a vertex shader
//! bound, Mesa 22.3 computes the raster position through its draw module
//! and reports its clip w as 1/w (measured: 0.333 where fixed function
//! reports 3), from which [`crate::auto::fixed::FixedDraw::pixels`] would
//! compute the eyes' raster positions wrongly.

use crate::auto::vertex::EYE_UNIFORM;

/// What the stand-in must reproduce: the fixed-function vertex state of
/// a draw, as the layer tracks it. Only what the fixed-function fragment
/// stage reads is written: every output a vertex carries costs on
/// llvmpipe, whose draw module shades, stores and bins each one (a
/// stand-in writing all eight texture coordinates, both colour pairs, the
/// point size, the fog coordinate and gl_ClipVertex made a heavy
/// fixed-function draw 1.6–2x the program's own two passes; BENCHMARKS.md,
/// "Automatic stereo: a mono program under --auto").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FixedVertexState {
    /// GL_LIGHTING enabled.
    pub lighting: bool,
    /// Any GL_TEXTURE_GEN_* enabled on any unit.
    pub texgen: bool,
    /// Texture units with a texture target enabled (bit i: unit i): their
    /// coordinates are passed through their texture matrices.
    pub texture_units: u32,
    /// GL_FOG enabled.
    pub fog: bool,
    /// GL_FOG_COORD_SRC is GL_FOG_COORD (else the fragment depth).
    pub fog_coord: bool,
    /// GL_COLOR_SUM enabled: the secondary colour is added.
    pub color_sum: bool,
    /// A user clip plane enabled: gl_ClipVertex is written.
    pub clip_planes: bool,
    /// GL_PROGRAM_POINT_SIZE enabled: the point size comes from the
    /// vertex stage (glPointSize's value is written).
    pub program_point_size: bool,
}

/// The stand-in's source for `state`, the eye uniform at `location`; or
/// why `state` needs the slow path.
pub fn source(state: FixedVertexState, location: u32) -> Result<String, String> {
    if state.lighting {
        return Err("fixed-function lighting is not modelled yet".into());
    }
    if state.texgen {
        return Err("texture-coordinate generation is not modelled yet".into());
    }
    let mut s = String::from(
        "#version 330 compatibility\n\
         #extension GL_ARB_shader_viewport_layer_array : require\n\
         #extension GL_ARB_explicit_uniform_location : require\n",
    );
    s.push_str(&format!(
        "layout(location = {location}) uniform vec4 {EYE_UNIFORM};\n"
    ));
    s.push_str(
        "void main()\n{\n\
         \x20   gl_Position = ftransform();\n\
         \x20   gl_FrontColor = gl_Color;\n",
    );
    // Without lighting the back colours are never selected (two-sided
    // colour belongs to lighting, or to GL_VERTEX_PROGRAM_TWO_SIDE, which
    // a fixed-function program has no reason to enable).
    if state.color_sum {
        s.push_str("    gl_FrontSecondaryColor = gl_SecondaryColor;\n");
    }
    if state.clip_planes || (state.fog && !state.fog_coord) {
        s.push_str("    vec4 eye = gl_ModelViewMatrix * gl_Vertex;\n");
    }
    if state.clip_planes {
        s.push_str("    gl_ClipVertex = eye;\n");
    }
    if state.program_point_size {
        s.push_str("    gl_PointSize = gl_Point.size;\n");
    }
    for unit in 0..32 {
        if state.texture_units & (1 << unit) != 0 {
            s.push_str(&format!(
                "    gl_TexCoord[{unit}] = gl_TextureMatrix[{unit}] * gl_MultiTexCoord{unit};\n"
            ));
        }
    }
    if state.fog {
        s.push_str(if state.fog_coord {
            "    gl_FogFragCoord = gl_FogCoord;\n"
        } else {
            "    gl_FogFragCoord = abs(eye.z);\n"
        });
    }
    s.push_str(&format!(
        "    if (gl_Position.w != 1.0)\n        gl_Position.x += {EYE_UNIFORM}.x * (gl_Position.w - {EYE_UNIFORM}.y);\n\
         \x20   if ({EYE_UNIFORM}.z >= 0.0)\n        gl_Layer = int({EYE_UNIFORM}.z);\n}}\n"
    ));
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unmodelled_state_takes_the_slow_path() {
        let lit = FixedVertexState {
            lighting: true,
            ..Default::default()
        };
        assert!(source(lit, 7).unwrap_err().contains("lighting"));
        let s = source(
            FixedVertexState {
                texture_units: 0b101,
                fog: true,
                ..Default::default()
            },
            7,
        )
        .unwrap();
        assert!(s.contains("layout(location = 7) uniform vec4 gls_auto_eye;"));
        assert!(s.contains("gl_TexCoord[0] = gl_TextureMatrix[0] * gl_MultiTexCoord0;"));
        assert!(s.contains("gl_TexCoord[2] = gl_TextureMatrix[2] * gl_MultiTexCoord2;"));
        assert!(!s.contains("gl_TexCoord[1]"));
        assert!(s.contains("gl_FogFragCoord = abs(eye.z);"));
        assert!(!s.contains("gl_ClipVertex"));
        assert!(!s.contains("gl_BackColor"));
        // The least state writes the position, the colour and the eye.
        let bare = source(Default::default(), 7).unwrap();
        for absent in [
            "gl_TexCoord",
            "gl_FogFragCoord",
            "gl_ClipVertex",
            "gl_PointSize",
            "Secondary",
        ] {
            assert!(!bare.contains(absent), "{absent}: {bare}");
        }
        let all = source(
            FixedVertexState {
                color_sum: true,
                clip_planes: true,
                program_point_size: true,
                fog: true,
                fog_coord: true,
                ..Default::default()
            },
            7,
        )
        .unwrap();
        for present in [
            "gl_FrontSecondaryColor = gl_SecondaryColor;",
            "gl_ClipVertex = eye;",
            "gl_PointSize = gl_Point.size;",
            "gl_FogFragCoord = gl_FogCoord;",
        ] {
            assert!(all.contains(present), "{present}: {all}");
        }
    }
}

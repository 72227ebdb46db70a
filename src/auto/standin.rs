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
//! Modelled here: the vertex colour (primary and secondary, front and
//! back), texture coordinates through each unit's texture matrix, the fog
//! coordinate (glFogCoord, or the eye-space distance as fixed function
//! uses by default), user clip planes (gl_ClipVertex) and the point size.
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
/// a draw, as the layer tracks it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FixedVertexState {
    /// GL_LIGHTING enabled.
    pub lighting: bool,
    /// Any GL_TEXTURE_GEN_* enabled on any unit.
    pub texgen: bool,
    /// Texture units whose coordinates the fragments use (enabled
    /// targets): coordinates 0..units are passed.
    pub texture_units: u32,
    /// GL_FOG_COORD_SRC is GL_FOG_COORD (else the fragment depth).
    pub fog_coord: bool,
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
         \x20   vec4 eye = gl_ModelViewMatrix * gl_Vertex;\n\
         \x20   gl_ClipVertex = eye;\n\
         \x20   gl_FrontColor = gl_Color;\n\
         \x20   gl_BackColor = gl_Color;\n\
         \x20   gl_FrontSecondaryColor = gl_SecondaryColor;\n\
         \x20   gl_BackSecondaryColor = gl_SecondaryColor;\n\
         \x20   gl_PointSize = gl_Point.size;\n",
    );
    for unit in 0..state.texture_units {
        s.push_str(&format!(
            "    gl_TexCoord[{unit}] = gl_TextureMatrix[{unit}] * gl_MultiTexCoord{unit};\n"
        ));
    }
    s.push_str(if state.fog_coord {
        "    gl_FogFragCoord = gl_FogCoord;\n"
    } else {
        "    gl_FogFragCoord = abs(eye.z);\n"
    });
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
                texture_units: 2,
                ..Default::default()
            },
            7,
        )
        .unwrap();
        assert!(s.contains("layout(location = 7) uniform vec4 gls_auto_eye;"));
        assert!(s.contains("gl_TexCoord[1] = gl_TextureMatrix[1] * gl_MultiTexCoord1;"));
        assert!(!s.contains("gl_TexCoord[2]"));
        assert!(s.contains("gl_FogFragCoord = abs(eye.z);"));
    }
}

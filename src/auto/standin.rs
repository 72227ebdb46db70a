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
//! Lighting too, one face (`lighting_source`). Not yet: two-sided
//! lighting, texture-coordinate generation, vertex blending —
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
    /// GL_LIGHTING enabled: its state.
    pub lighting: Option<Lighting>,
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

// GL_COLOR_MATERIAL's modes (glColorMaterial): which material colour the
// current colour stands for.
const GL_EMISSION: u32 = 0x1600;
const GL_AMBIENT: u32 = 0x1200;
const GL_DIFFUSE: u32 = 0x1201;
const GL_SPECULAR: u32 = 0x1202;
const GL_AMBIENT_AND_DIFFUSE: u32 = 0x1602;

/// The lighting state of a lit draw, as the layer reads it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Lighting {
    /// GL_LIGHTi enabled (bit i).
    pub lights: u8,
    /// GL_COLOR_MATERIAL enabled for the front face: its mode, else 0.
    pub color_material: u32,
    /// GL_LIGHT_MODEL_LOCAL_VIEWER.
    pub local_viewer: bool,
    /// GL_LIGHT_MODEL_TWO_SIDE (not modelled: the slow path).
    pub two_side: bool,
    /// GL_LIGHT_MODEL_COLOR_CONTROL is GL_SEPARATE_SPECULAR_COLOR.
    pub separate_specular: bool,
    /// Lights (bit i: GL_LIGHTi) with a position (w ≠ 0).
    pub positional: u8,
    /// Positional lights attenuated (not 1, 0, 0).
    pub attenuated: u8,
    /// Spot lights (cutoff ≠ 180).
    pub spot: u8,
    /// GL_NORMALIZE enabled.
    pub normalize: bool,
    /// GL_RESCALE_NORMAL enabled.
    pub rescale_normal: bool,
}

/// The vertex colours of fixed-function lighting (OpenGL 2.1 §2.14.1, the
/// compatibility profile's §12.2.1) for the front face: the scene's
/// emission and ambient, and per enabled light its attenuated, spot-lit
/// ambient, diffuse and specular terms; the material's colours from
/// `gl_FrontMaterial` or, under GL_COLOR_MATERIAL, the current colour;
/// the specular sum in the secondary colour under
/// GL_SEPARATE_SPECULAR_COLOR. Colours are left to GL's vertex colour
/// clamping, as fixed function's are.
fn lighting_source(l: Lighting, color_sum: bool, s: &mut String) {
    let cm = l.color_material;
    let from_colour = |which: u32| {
        cm == which
            || (cm == GL_AMBIENT_AND_DIFFUSE && (which == GL_AMBIENT || which == GL_DIFFUSE))
    };
    // A material colour: the current colour under GL_COLOR_MATERIAL, else
    // the material's; a product with light i's colour: GL's own
    // precomputed product where the material is GL's.
    let material = |which: u32, name: &str| {
        if from_colour(which) {
            "gl_Color".to_string()
        } else {
            format!("gl_FrontMaterial.{name}")
        }
    };
    let product = |which: u32, name: &str, i: u32| {
        if from_colour(which) {
            format!("(gl_Color.rgb * gl_LightSource[{i}].{name}.rgb)")
        } else {
            format!("gl_FrontLightProduct[{i}].{name}.rgb")
        }
    };
    s.push_str("    vec4 eye = gl_ModelViewMatrix * gl_Vertex;\n");
    s.push_str("    vec3 n = gl_NormalMatrix * gl_Normal;\n");
    if l.rescale_normal {
        s.push_str("    n *= gl_NormalScale;\n");
    }
    if l.normalize {
        s.push_str("    n = normalize(n);\n");
    }
    if l.local_viewer {
        s.push_str("    vec3 toEye = -normalize(eye.xyz / eye.w);\n");
    }
    if from_colour(GL_EMISSION) || from_colour(GL_AMBIENT) {
        s.push_str(&format!(
            "    vec3 colour = {}.rgb + {}.rgb * gl_LightModel.ambient.rgb;\n",
            material(GL_EMISSION, "emission"),
            material(GL_AMBIENT, "ambient")
        ));
    } else {
        s.push_str("    vec3 colour = gl_FrontLightModelProduct.sceneColor.rgb;\n");
    }
    s.push_str("    vec3 shine = vec3(0.0);\n");
    for i in (0..8).filter(|i| l.lights & (1 << i) != 0) {
        let bit = 1u8 << i;
        let (positional, spot) = (l.positional & bit != 0, l.spot & bit != 0);
        let attenuated = positional && l.attenuated & bit != 0;
        let ls = format!("gl_LightSource[{i}]");
        s.push_str("    {\n");
        if positional {
            s.push_str(&format!(
                "        vec3 d = {ls}.position.xyz / {ls}.position.w - eye.xyz / eye.w;\n\
                 \x20       float dist = length(d);\n\
                 \x20       vec3 toLight = d / dist;\n"
            ));
        } else {
            s.push_str(&format!(
                "        vec3 toLight = normalize({ls}.position.xyz);\n"
            ));
        }
        s.push_str(if attenuated || spot {
            "        float att = 1.0;\n"
        } else {
            ""
        });
        if attenuated {
            s.push_str(&format!(
                "        att = 1.0 / ({ls}.constantAttenuation + {ls}.linearAttenuation * dist\n\
                 \x20           + {ls}.quadraticAttenuation * dist * dist);\n"
            ));
        }
        if spot {
            s.push_str(&format!(
                "        float c = dot(-toLight, normalize({ls}.spotDirection));\n\
                 \x20       att *= c >= {ls}.spotCosCutoff ? pow(max(c, 0.0), {ls}.spotExponent) : 0.0;\n"
            ));
        }
        // The half vector: GL's own for a directional light seen from
        // infinity, else from the vertex.
        let half = match (positional, l.local_viewer) {
            (false, false) => format!("{ls}.halfVector.xyz"),
            (_, true) => "normalize(toLight + toEye)".into(),
            (true, false) => "normalize(toLight + vec3(0.0, 0.0, 1.0))".into(),
        };
        let att = if attenuated || spot { "att * " } else { "" };
        s.push_str(&format!(
            "        float nl = dot(n, toLight);\n\
             \x20       colour += {att}({} + max(nl, 0.0) * {});\n\
             \x20       if (nl > 0.0)\n\
             \x20           shine += {att}pow(max(dot(n, {half}), 0.0), gl_FrontMaterial.shininess)\n\
             \x20               * {};\n\
             \x20   }}\n",
            product(GL_AMBIENT, "ambient", i),
            product(GL_DIFFUSE, "diffuse", i),
            product(GL_SPECULAR, "specular", i),
        ));
    }
    let alpha = format!("{}.a", material(GL_DIFFUSE, "diffuse"));
    if l.separate_specular {
        s.push_str(&format!(
            "    gl_FrontColor = vec4(colour, {alpha});\n\
             \x20   gl_FrontSecondaryColor = vec4(shine, 0.0);\n"
        ));
    } else {
        s.push_str(&format!(
            "    gl_FrontColor = vec4(colour + shine, {alpha});\n"
        ));
        if color_sum {
            // Lit, the secondary colour is the specular sum or nothing.
            s.push_str("    gl_FrontSecondaryColor = vec4(0.0);\n");
        }
    }
}

/// The stand-in's source for `state`, the eye uniform at `location`; or
/// why `state` needs the slow path.
pub fn source(state: FixedVertexState, location: u32) -> Result<String, String> {
    if let Some(l) = state.lighting {
        if l.two_side {
            return Err("two-sided fixed-function lighting is not modelled yet".into());
        }
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
         \x20   gl_Position = ftransform();\n",
    );
    // Without two-sided lighting the back colours are never selected
    // (two-sided colour belongs to it, or to GL_VERTEX_PROGRAM_TWO_SIDE,
    // which a fixed-function program has no reason to enable).
    match state.lighting {
        Some(l) => lighting_source(l, state.color_sum, &mut s),
        None => {
            s.push_str("    gl_FrontColor = gl_Color;\n");
            if state.color_sum {
                s.push_str("    gl_FrontSecondaryColor = gl_SecondaryColor;\n");
            }
            if state.clip_planes || (state.fog && !state.fog_coord) {
                s.push_str("    vec4 eye = gl_ModelViewMatrix * gl_Vertex;\n");
            }
        }
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
        let two_sided = FixedVertexState {
            lighting: Some(Lighting {
                lights: 1,
                two_side: true,
                ..Default::default()
            }),
            ..Default::default()
        };
        assert!(source(two_sided, 7).unwrap_err().contains("two-sided"));
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

    #[test]
    fn lighting_takes_each_enabled_light_and_the_colour_material() {
        let lit = |l: Lighting, color_sum: bool| {
            source(
                FixedVertexState {
                    lighting: Some(l),
                    color_sum,
                    ..Default::default()
                },
                7,
            )
            .unwrap()
        };
        let s = lit(
            Lighting {
                lights: 0b101,
                color_material: GL_AMBIENT_AND_DIFFUSE,
                ..Default::default()
            },
            false,
        );
        assert!(s.contains("gl_LightSource[0]") && s.contains("gl_LightSource[2]"));
        assert!(!s.contains("gl_LightSource[1]"), "{s}");
        assert!(
            s.contains("(gl_Color.rgb * gl_LightSource[0].ambient.rgb)"),
            "{s}"
        );
        assert!(
            s.contains("(gl_Color.rgb * gl_LightSource[2].diffuse.rgb)"),
            "{s}"
        );
        assert!(s.contains("gl_FrontLightProduct[2].specular.rgb"), "{s}");
        // Directional lights from infinity: GL's half vectors, nothing
        // attenuated, no spot.
        assert!(s.contains("gl_LightSource[0].halfVector.xyz"), "{s}");
        for absent in ["normalize(n)", "att", "dist", "spotDirection", "toEye"] {
            assert!(!s.contains(absent), "{absent}: {s}");
        }
        assert!(!s.contains("gl_FrontSecondaryColor"), "{s}");
        let s = lit(
            Lighting {
                lights: 0b10,
                positional: 0b10,
                attenuated: 0b10,
                spot: 0b10,
                local_viewer: true,
                normalize: true,
                separate_specular: true,
                ..Default::default()
            },
            false,
        );
        for present in [
            "vec3 toEye = -normalize(eye.xyz / eye.w);",
            "n = normalize(n);",
            "gl_FrontSecondaryColor = vec4(shine, 0.0);",
            "gl_FrontLightModelProduct.sceneColor.rgb",
            "gl_FrontLightProduct[1].diffuse.rgb",
            "gl_LightSource[1].quadraticAttenuation * dist * dist",
            "normalize(gl_LightSource[1].spotDirection)",
            "normalize(toLight + toEye)",
        ] {
            assert!(s.contains(present), "{present}: {s}");
        }
        // Lit with GL_COLOR_SUM and no separate specular: no secondary colour.
        let s = lit(
            Lighting {
                lights: 1,
                ..Default::default()
            },
            true,
        );
        assert!(s.contains("gl_FrontSecondaryColor = vec4(0.0);"), "{s}");
    }
}

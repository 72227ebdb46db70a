//! Which GL entry points automatic stereo intercepts, by family, as a rule
//! over the names of the Khronos registry (gl.xml) that a generator of
//! wrappers can apply (STYLE.md item 19): [`family`] of a command name.
//! The counts in the table of [`crate::auto`] are those of the registry
//! the `khronos_api` crate ships (desktop GL: the commands of the `gl`
//! features and of the extensions supported by `gl` or `glcore`), checked
//! by this module's test.

/// What the layer does with a command under `--auto` (module docs of
/// [`crate::auto`], "Entry points").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// Vertex-array draws (glDraw*, glMultiDraw*, indirect, instanced,
    /// transform-feedback draws, glRect*, glEvalMesh*): issued once per eye
    /// with the eye's uniform (shaders, the layer's fixed-function
    /// stand-in) or the eye's projection and layers (the fixed-function
    /// slow path).
    Draw,
    /// glBegin and glEnd: the draw happens at glEnd; the vertices between
    /// are compiled into a display list of the layer's, called once per
    /// eye (recorded instead, [`Family::Vertex`], while the program
    /// compiles a list of its own).
    BeginEnd,
    /// Per-vertex commands allowed between glBegin and glEnd (glVertex*,
    /// glColor*, glNormal*, glTexCoord*, glMultiTexCoord*, glVertexAttrib*,
    /// glMaterial*, glArrayElement, glEvalCoord*, glEvalPoint*, …):
    /// recorded while a glBegin is open inside a list the program
    /// compiles, passed through otherwise.
    Vertex,
    /// Display lists (glNewList, glEndList, glCallList, glCallLists):
    /// draws compiled into a list are compiled once per eye with the eye's
    /// uniform at the reserved location; glCallList needs nothing more.
    DisplayList,
    /// Clears of the draw framebuffer (glClear, glClearBuffer*,
    /// glClearNamedFramebuffer*): once, every layer of a layered target;
    /// per eye where the eye's layers are attached one at a time.
    Clear,
    /// glRasterPos*: made with program 0 while the layer's fixed-function
    /// stand-in is bound (with a vertex shader bound, Mesa 22.3 reports
    /// the raster position's clip w as 1/w, and the eyes' raster positions
    /// are computed from it: [`crate::auto::standin`]).
    RasterPos,
    /// Pixel rectangles written at the raster position (glDrawPixels,
    /// glBitmap, glCopyPixels): once per eye at the eye's raster position.
    RasterPixels,
    /// Blits (glBlitFramebuffer, glBlitNamedFramebuffer): into the default
    /// framebuffer from a stereoized render target, eye to eye; from a
    /// mono one, into both eyes (flat).
    Blit,
    /// Reads of the default framebuffer (glReadPixels, glReadnPixels,
    /// glCopyTex*Image*, glCopyTexture*, glAccum): from the left eye
    /// (seed 004, issue 4), unless the destination is stereoized.
    Read,
    /// Programs and their stages (glLinkProgram, glCreateShaderProgramv,
    /// glProgramBinary, glUseProgram, glUseProgramStages,
    /// glBindProgramPipeline, glProgramStringARB, …): the vertex-stage
    /// rewrite at link time, and which program supplies the last stage.
    Program,
    /// Introspection that would show the layer's uniform
    /// (glGetActiveUniform*, glGetProgramResource*, glGetProgramInterfaceiv,
    /// glGetProgramiv(GL_ACTIVE_UNIFORMS…), glGetUniformIndices): answered
    /// without it.
    Introspection,
    /// Framebuffer bindings and attachments (glBindFramebuffer,
    /// glFramebufferTexture*, glNamedFramebuffer*, …): which target a draw
    /// goes to (the eyes, a stereoized render target, a mono one).
    Framebuffer,
    /// Texture and image bindings (glActiveTexture, glBindTexture,
    /// glBindTextures, glBindTextureUnit, glBindMultiTextureEXT,
    /// glBindImageTexture(s)): a texture with eyes sampled in an eye's
    /// draw is that eye's; the units are looked at again after one of
    /// these ([`crate::auto::render_targets`]).
    Texture,
    /// Commands that read a texture's contents outside draws, or make
    /// new contents from them (glGenerateMipmap*, glCopyImageSubData,
    /// glGetTexImage and their DSA and compressed forms): a texture with
    /// eyes is given its left eye first, and its mipmaps are made for the
    /// right eye too ([`crate::auto::render_targets`]).
    TextureData,
    /// Commands that give a texture new contents outside draws (uploads,
    /// clears, storage: glTexSubImage*, glTexImage2D*, glClearTex*,
    /// glTexStorage2D* and their DSA and compressed forms): a texture
    /// with eyes is one picture again, its eyes forgotten
    /// ([`crate::auto::render_targets`]).
    TextureWrite,
    /// Queries, conditional rendering and transform feedback (glBeginQuery*,
    /// glEndQuery*, glQueryCounter, glBeginConditionalRender*,
    /// glBeginTransformFeedback, glPauseTransformFeedback, …): what the
    /// second eye's draws must not count or capture twice.
    SideEffect,
    /// NV_3dvision_settings' state (glEnable, glDisable, glIsEnabled, the
    /// glGet*v families): GL_3DVISION_STEREO_NV and the STEREO_*_NV pnames.
    Settings,
    /// 4x4 float matrices a program uploads (glUniformMatrix4fv,
    /// glProgramUniformMatrix4fv and their ARB/EXT names): automatic
    /// convergence learns a shader program's perspective projection from
    /// them ([`crate::auto::converge`]).
    Projection,
    /// Fixed-function lighting state that is not an enable (glLight*,
    /// glLightModel*, glColorMaterial): the stand-in vertex shader is
    /// keyed on it ([`crate::auto::standin`]), so it is read again after
    /// one of these, not at every draw.
    Lighting,
}

/// The names of `family`'s commands that no prefix rule below catches.
const EXACT: &[(&str, Family)] = &[
    ("glBegin", Family::BeginEnd),
    ("glEnd", Family::BeginEnd),
    ("glNewList", Family::DisplayList),
    ("glEndList", Family::DisplayList),
    ("glCallList", Family::DisplayList),
    ("glCallLists", Family::DisplayList),
    ("glClear", Family::Clear),
    ("glDrawPixels", Family::RasterPixels),
    ("glBitmap", Family::RasterPixels),
    ("glBitmapxOES", Family::RasterPixels),
    ("glCopyPixels", Family::RasterPixels),
    ("glAccum", Family::Read),
    ("glAccumxOES", Family::Read),
    ("glArrayElement", Family::Vertex),
    ("glArrayElementEXT", Family::Vertex),
    ("glEdgeFlag", Family::Vertex),
    ("glEdgeFlagv", Family::Vertex),
    ("glEvalMesh1", Family::Draw),
    ("glEvalMesh2", Family::Draw),
    ("glLinkProgram", Family::Program),
    ("glLinkProgramARB", Family::Program),
    ("glProgramBinary", Family::Program),
    ("glUseProgram", Family::Program),
    ("glUseProgramObjectARB", Family::Program),
    ("glUseProgramStages", Family::Program),
    ("glUseProgramStagesEXT", Family::Program),
    ("glUseShaderProgramEXT", Family::Program),
    ("glBindProgramPipeline", Family::Program),
    ("glBindProgramPipelineEXT", Family::Program),
    ("glActiveShaderProgram", Family::Program),
    ("glActiveShaderProgramEXT", Family::Program),
    ("glProgramStringARB", Family::Program),
    ("glBindProgramARB", Family::Program),
    ("glShaderBinary", Family::Program),
    ("glSpecializeShader", Family::Program),
    ("glSpecializeShaderARB", Family::Program),
    ("glGetProgramInterfaceiv", Family::Introspection),
    ("glGetUniformIndices", Family::Introspection),
    ("glGetProgramiv", Family::Introspection),
    ("glGetObjectParameterivARB", Family::Introspection),
    ("glActiveTexture", Family::Texture),
    ("glActiveTextureARB", Family::Texture),
    ("glBindTexture", Family::Texture),
    ("glBindTextureEXT", Family::Texture),
    ("glBindTextures", Family::Texture),
    ("glBindTextureUnit", Family::Texture),
    ("glBindMultiTextureEXT", Family::Texture),
    ("glBindImageTexture", Family::Texture),
    ("glBindImageTextureEXT", Family::Texture),
    ("glBindImageTextures", Family::Texture),
    ("glQueryCounter", Family::SideEffect),
    ("glColorMaterial", Family::Lighting),
    ("glUniformMatrix4fv", Family::Projection),
    ("glUniformMatrix4fvARB", Family::Projection),
    ("glProgramUniformMatrix4fv", Family::Projection),
    ("glProgramUniformMatrix4fvEXT", Family::Projection),
    ("glEnable", Family::Settings),
    ("glDisable", Family::Settings),
    ("glIsEnabled", Family::Settings),
    ("glEnablei", Family::Settings),
    ("glDisablei", Family::Settings),
    ("glIsEnabledi", Family::Settings),
    ("glGetBooleanv", Family::Settings),
    ("glGetIntegerv", Family::Settings),
    ("glGetInteger64v", Family::Settings),
    ("glGetFloatv", Family::Settings),
    ("glGetDoublev", Family::Settings),
];

/// Prefix rules, tried in order after [`EXACT`]: (prefix, exceptions that
/// start with it but are not of the family, family).
const PREFIXES: &[(&str, &[&str], Family)] = &[
    (
        "glDraw",
        &[
            "glDrawBuffer",
            "glDrawPixels",
            "glDrawTextureNV",
            "glDrawVkImageNV",
        ],
        Family::Draw,
    ),
    ("glMultiDraw", &[], Family::Draw),
    ("glRasterPos", &[], Family::RasterPos),
    ("glRect", &[], Family::Draw),
    (
        "glClearBuffer",
        &["glClearBufferData", "glClearBufferSubData"],
        Family::Clear,
    ),
    ("glClearNamedFramebuffer", &[], Family::Clear),
    ("glBlit", &[], Family::Blit),
    ("glReadPixels", &[], Family::Read),
    ("glReadnPixels", &[], Family::Read),
    ("glCopyTexImage", &[], Family::Read),
    ("glCopyTexSubImage", &[], Family::Read),
    ("glCopyTextureImage", &[], Family::Read),
    ("glCopyTextureSubImage", &[], Family::Read),
    ("glCopyMultiTex", &[], Family::Read),
    ("glCreateShaderProgram", &[], Family::Program),
    ("glTexSubImage", &[], Family::TextureWrite),
    ("glTextureSubImage", &[], Family::TextureWrite),
    ("glCompressedTexSubImage", &[], Family::TextureWrite),
    ("glCompressedTextureSubImage", &[], Family::TextureWrite),
    ("glTexImage2D", &[], Family::TextureWrite),
    ("glTextureImage2D", &[], Family::TextureWrite),
    ("glCompressedTexImage2D", &[], Family::TextureWrite),
    ("glCompressedTextureImage2D", &[], Family::TextureWrite),
    ("glClearTexImage", &[], Family::TextureWrite),
    ("glClearTexSubImage", &[], Family::TextureWrite),
    ("glTexStorage2D", &[], Family::TextureWrite),
    ("glTextureStorage2D", &[], Family::TextureWrite),
    ("glGenerateMipmap", &[], Family::TextureData),
    ("glGenerateTextureMipmap", &[], Family::TextureData),
    ("glGenerateMultiTexMipmap", &[], Family::TextureData),
    ("glCopyImageSubData", &[], Family::TextureData),
    ("glGetTexImage", &[], Family::TextureData),
    ("glGetnTexImage", &[], Family::TextureData),
    ("glGetTextureImage", &[], Family::TextureData),
    ("glGetTextureSubImage", &[], Family::TextureData),
    ("glGetCompressedTexImage", &[], Family::TextureData),
    ("glGetnCompressedTexImage", &[], Family::TextureData),
    ("glGetCompressedTextureImage", &[], Family::TextureData),
    ("glGetCompressedTextureSubImage", &[], Family::TextureData),
    ("glGetMultiTexImage", &[], Family::TextureData),
    ("glGetCompressedMultiTexImage", &[], Family::TextureData),
    ("glGetActiveUniform", &[], Family::Introspection),
    ("glGetProgramResource", &[], Family::Introspection),
    ("glBindFramebuffer", &[], Family::Framebuffer),
    ("glFramebufferTexture", &[], Family::Framebuffer),
    ("glFramebufferRenderbuffer", &[], Family::Framebuffer),
    (
        "glNamedFramebuffer",
        &[
            "glNamedFramebufferDrawBuffer",
            "glNamedFramebufferReadBuffer",
        ],
        Family::Framebuffer,
    ),
    ("glBeginQuery", &[], Family::SideEffect),
    ("glEndQuery", &[], Family::SideEffect),
    ("glBeginConditionalRender", &[], Family::SideEffect),
    ("glEndConditionalRender", &[], Family::SideEffect),
    ("glBeginTransformFeedback", &[], Family::SideEffect),
    ("glEndTransformFeedback", &[], Family::SideEffect),
    ("glPauseTransformFeedback", &[], Family::SideEffect),
    ("glResumeTransformFeedback", &[], Family::SideEffect),
    ("glBindTransformFeedback", &[], Family::SideEffect),
    ("glGetQueryObject", &[], Family::SideEffect),
    ("glDeleteQueries", &[], Family::SideEffect),
    ("glGetBooleani_v", &[], Family::Settings),
    ("glGetIntegeri_v", &[], Family::Settings),
    ("glGetInteger64i_v", &[], Family::Settings),
    ("glGetFloati_v", &[], Family::Settings),
    ("glGetDoublei_v", &[], Family::Settings),
    // Per-vertex commands (GL 4.5 compatibility §10.7.2 and the
    // extensions' forms: half floats, packed, SUN's combined ones…).
    (
        "glVertex",
        &[
            "glVertexArray",
            "glVertexPointer",
            "glVertexAttribPointer",
            "glVertexAttribIPointer",
            "glVertexAttribLPointer",
            "glVertexAttribFormat",
            "glVertexAttribIFormat",
            "glVertexAttribLFormat",
            "glVertexAttribBinding",
            "glVertexAttribDivisor",
            "glVertexBindingDivisor",
            "glVertexAttribArrayObjectATI",
            "glVertexAttribParameteriAMD",
            "glVertexBlendEnv",
            "glVertexFormatNV",
            "glVertexAttribFormatNV",
            "glVertexAttribIFormatNV",
            "glVertexAttribLFormatNV",
            "glVertexArrayRange",
            "glVertexWeightPointerEXT",
        ],
        Family::Vertex,
    ),
    (
        "glColor",
        &[
            "glColorMask",
            "glColorMaterial",
            "glColorPointer",
            "glColorTable",
            "glColorSubTable",
            "glColorFragmentOp",
            "glColorFormatNV",
        ],
        Family::Vertex,
    ),
    (
        "glSecondaryColor",
        &["glSecondaryColorPointer", "glSecondaryColorFormatNV"],
        Family::Vertex,
    ),
    (
        "glNormal",
        &["glNormalPointer", "glNormalFormatNV", "glNormalStream"],
        Family::Vertex,
    ),
    (
        "glTexCoord",
        &["glTexCoordPointer", "glTexCoordFormatNV"],
        Family::Vertex,
    ),
    (
        "glMultiTexCoord",
        &["glMultiTexCoordPointerEXT"],
        Family::Vertex,
    ),
    (
        "glFogCoord",
        &["glFogCoordPointer", "glFogCoordFormatNV"],
        Family::Vertex,
    ),
    (
        "glIndex",
        &[
            "glIndexMask",
            "glIndexPointer",
            "glIndexFunc",
            "glIndexMaterial",
            "glIndexFormatNV",
        ],
        Family::Vertex,
    ),
    ("glMaterial", &[], Family::Vertex),
    ("glLight", &[], Family::Lighting),
    ("glEvalCoord", &[], Family::Vertex),
    ("glEvalPoint", &[], Family::Vertex),
    (
        "glEdgeFlag",
        &["glEdgeFlagPointer", "glEdgeFlagFormatNV"],
        Family::Vertex,
    ),
    (
        "glReplacementCode",
        &["glReplacementCodePointerSUN"],
        Family::Vertex,
    ),
];

/// The family of the GL command `name`, or None: passed through.
pub fn family(name: &str) -> Option<Family> {
    if let Some(&(_, f)) = EXACT.iter().find(|&&(n, _)| n == name) {
        return Some(f);
    }
    PREFIXES.iter().find_map(|&(prefix, except, f)| {
        (name.starts_with(prefix) && !except.iter().any(|e| name.starts_with(e))).then_some(f)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::{BTreeMap, BTreeSet};

    /// The desktop GL commands of gl.xml: those required by a `gl` feature
    /// or by an extension supported by `gl` or `glcore`.
    fn desktop_commands() -> BTreeSet<String> {
        let xml = std::str::from_utf8(khronos_api::GL_XML).unwrap();
        let mut out = BTreeSet::new();
        // <feature api="gl" …> … </feature> and <extension … supported="…gl…"> … </extension>
        for (open, close) in [("<feature ", "</feature>"), ("<extension ", "</extension>")] {
            let mut rest = xml;
            while let Some(at) = rest.find(open) {
                let block = &rest[at..];
                let head = &block[..block.find('>').unwrap()];
                if head.ends_with('/') {
                    // <extension … /> has no commands.
                    rest = &block[head.len()..];
                    continue;
                }
                let end = block.find(close).unwrap_or(block.len());
                let body = &block[..end];
                let wanted = if open == "<feature " {
                    head.contains("api=\"gl\"")
                } else {
                    head.split("supported=\"")
                        .nth(1)
                        .and_then(|s| s.split('"').next())
                        .is_some_and(|s| s.split('|').any(|a| a == "gl" || a == "glcore"))
                };
                if wanted {
                    for piece in body.split("<command name=\"").skip(1) {
                        out.insert(piece.split('"').next().unwrap().to_owned());
                    }
                }
                rest = &block[end..];
            }
        }
        out
    }

    #[test]
    fn every_family_has_the_registry_commands_the_module_docs_count() {
        let commands = desktop_commands();
        assert_eq!(commands.len(), 2978, "desktop commands in gl.xml");
        let mut counts: BTreeMap<Family, usize> = BTreeMap::new();
        for c in &commands {
            if let Some(f) = family(c) {
                *counts.entry(f).or_default() += 1;
            }
        }
        // Every exact name is a registry name (no typos).
        for (n, _) in EXACT {
            assert!(commands.contains(*n), "{n} is not in gl.xml");
        }
        let total: usize = counts.values().sum();
        eprintln!("{counts:?}, {total} of {} commands", commands.len());
        let want = [
            (Family::Draw, 68),
            (Family::BeginEnd, 2),
            (Family::Vertex, 638),
            (Family::DisplayList, 4),
            (Family::Clear, 9),
            (Family::RasterPos, 30),
            (Family::RasterPixels, 4),
            (Family::Blit, 3),
            (Family::Read, 29),
            (Family::Program, 20),
            (Family::Introspection, 16),
            (Family::Framebuffer, 34),
            (Family::Texture, 10),
            (Family::TextureData, 22),
            (Family::TextureWrite, 42),
            (Family::SideEffect, 35),
            (Family::Settings, 18),
            (Family::Projection, 4),
            (Family::Lighting, 14),
        ];
        assert_eq!(total, 1002);
        for (f, n) in want {
            assert_eq!(counts.get(&f).copied().unwrap_or(0), n, "{f:?}");
        }
    }

    #[test]
    fn look_alikes_are_not_draws() {
        for name in [
            "glDrawBuffer",
            "glDrawBuffers",
            "glDrawBuffersARB",
            "glDrawPixels",
            "glColorMask",
            "glVertexAttribPointer",
            "glClearBufferData",
            "glNamedFramebufferDrawBuffers",
            "glVertexArrayAttribFormat",
        ] {
            assert_ne!(family(name), Some(Family::Draw), "{name}");
            assert_ne!(family(name), Some(Family::Vertex), "{name}");
        }
        assert_eq!(family("glDrawPixels"), Some(Family::RasterPixels));
        assert_eq!(
            family("glDrawElementsInstancedBaseVertexBaseInstance"),
            Some(Family::Draw)
        );
        assert_eq!(family("glVertexAttrib4Nub"), Some(Family::Vertex));
        assert_eq!(family("glColor4ubVertex3fSUN"), Some(Family::Vertex));
        assert_eq!(family("glFinish"), None);
    }
}

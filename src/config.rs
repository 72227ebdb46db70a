//! Framebuffer configurations: parsing a glXChooseVisual attribute list into
//! a request, and the chosen configuration (native, emulated or mono stereo).

use std::any::Any;
use std::sync::Arc;

use crate::error::{Error, Result};
use crate::stereo::buffers::FramebufferShape;

/// GLX attribute tokens accepted by glXChooseVisual (GLX 1.4 table 3.4 plus
/// the multisample and sRGB extensions).
#[allow(missing_docs)]
pub mod glx {
    pub const GLX_USE_GL: i32 = 1;
    pub const GLX_BUFFER_SIZE: i32 = 2;
    pub const GLX_LEVEL: i32 = 3;
    pub const GLX_RGBA: i32 = 4;
    pub const GLX_DOUBLEBUFFER: i32 = 5;
    pub const GLX_STEREO: i32 = 6;
    pub const GLX_AUX_BUFFERS: i32 = 7;
    pub const GLX_RED_SIZE: i32 = 8;
    pub const GLX_GREEN_SIZE: i32 = 9;
    pub const GLX_BLUE_SIZE: i32 = 10;
    pub const GLX_ALPHA_SIZE: i32 = 11;
    pub const GLX_DEPTH_SIZE: i32 = 12;
    pub const GLX_STENCIL_SIZE: i32 = 13;
    pub const GLX_ACCUM_RED_SIZE: i32 = 14;
    pub const GLX_ACCUM_GREEN_SIZE: i32 = 15;
    pub const GLX_ACCUM_BLUE_SIZE: i32 = 16;
    pub const GLX_ACCUM_ALPHA_SIZE: i32 = 17;
    pub const GLX_SAMPLE_BUFFERS: i32 = 100000;
    pub const GLX_SAMPLES: i32 = 100001;
    pub const GLX_FRAMEBUFFER_SRGB_CAPABLE_ARB: i32 = 0x20B2;
}
use glx::*;

/// The longest attribute list read from C before a missing `None`
/// terminator is reported.
pub const MAX_ATTRIBUTES: usize = 512;

/// What a program asked for with a glXChooseVisual attribute list: minimum
/// sizes and the three booleans.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ConfigRequest {
    /// GLX_RGBA: an RGBA visual (absent = colour index, which is not supported).
    pub rgba: bool,
    /// GLX_DOUBLEBUFFER: front and back buffers (absent = single-buffered only).
    pub double_buffer: bool,
    /// GLX_STEREO: left and right buffers (absent = mono only).
    pub stereo: bool,
    /// Minimum bits of red, green, blue, alpha.
    pub color: [u32; 4],
    /// Minimum depth bits.
    pub depth: u32,
    /// Minimum stencil bits.
    pub stencil: u32,
    /// Minimum accumulation bits (any non-zero value cannot be met).
    pub accum: [u32; 4],
    /// Minimum aux buffers (any non-zero value cannot be met).
    pub aux_buffers: u32,
    /// Framebuffer level (0 = main plane; overlays cannot be met).
    pub level: i32,
    /// Minimum colour-index buffer size (GLX_BUFFER_SIZE).
    pub buffer_size: u32,
    /// Minimum samples (GLX_SAMPLES; 0 = no multisampling).
    pub samples: u32,
    /// GLX_FRAMEBUFFER_SRGB_CAPABLE_ARB requested.
    pub srgb: bool,
}

fn attr_name(a: i32) -> &'static str {
    match a {
        GLX_USE_GL => "GLX_USE_GL",
        GLX_BUFFER_SIZE => "GLX_BUFFER_SIZE",
        GLX_LEVEL => "GLX_LEVEL",
        GLX_RGBA => "GLX_RGBA",
        GLX_DOUBLEBUFFER => "GLX_DOUBLEBUFFER",
        GLX_STEREO => "GLX_STEREO",
        GLX_AUX_BUFFERS => "GLX_AUX_BUFFERS",
        GLX_RED_SIZE => "GLX_RED_SIZE",
        GLX_GREEN_SIZE => "GLX_GREEN_SIZE",
        GLX_BLUE_SIZE => "GLX_BLUE_SIZE",
        GLX_ALPHA_SIZE => "GLX_ALPHA_SIZE",
        GLX_DEPTH_SIZE => "GLX_DEPTH_SIZE",
        GLX_STENCIL_SIZE => "GLX_STENCIL_SIZE",
        GLX_ACCUM_RED_SIZE => "GLX_ACCUM_RED_SIZE",
        GLX_ACCUM_GREEN_SIZE => "GLX_ACCUM_GREEN_SIZE",
        GLX_ACCUM_BLUE_SIZE => "GLX_ACCUM_BLUE_SIZE",
        GLX_ACCUM_ALPHA_SIZE => "GLX_ACCUM_ALPHA_SIZE",
        GLX_SAMPLE_BUFFERS => "GLX_SAMPLE_BUFFERS",
        GLX_SAMPLES => "GLX_SAMPLES",
        GLX_FRAMEBUFFER_SRGB_CAPABLE_ARB => "GLX_FRAMEBUFFER_SRGB_CAPABLE_ARB",
        _ => "?",
    }
}

impl ConfigRequest {
    /// Parses a glXChooseVisual attribute list (without its terminating
    /// `None`). Booleans (GLX_USE_GL, GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO)
    /// stand alone; every other attribute is followed by its value.
    ///
    /// An unknown attribute is `InvalidEnum` naming it; a size attribute
    /// without a value, or with a negative one, is `InvalidValue`.
    pub fn parse_visual_attribs(list: &[i32]) -> Result<ConfigRequest> {
        let mut r = ConfigRequest::default();
        let mut it = list.iter().copied().enumerate();
        while let Some((i, a)) = it.next() {
            match a {
                GLX_USE_GL => {}
                GLX_RGBA => r.rgba = true,
                GLX_DOUBLEBUFFER => r.double_buffer = true,
                GLX_STEREO => r.stereo = true,
                GLX_BUFFER_SIZE
                | GLX_LEVEL
                | GLX_AUX_BUFFERS
                | GLX_RED_SIZE
                | GLX_GREEN_SIZE
                | GLX_BLUE_SIZE
                | GLX_ALPHA_SIZE
                | GLX_DEPTH_SIZE
                | GLX_STENCIL_SIZE
                | GLX_ACCUM_RED_SIZE
                | GLX_ACCUM_GREEN_SIZE
                | GLX_ACCUM_BLUE_SIZE
                | GLX_ACCUM_ALPHA_SIZE
                | GLX_SAMPLE_BUFFERS
                | GLX_SAMPLES
                | GLX_FRAMEBUFFER_SRGB_CAPABLE_ARB => {
                    let Some((_, v)) = it.next() else {
                        return Err(Error::invalid_value(format!(
                            "attribute {} at index {i} has no value before the None terminator",
                            attr_name(a)
                        )));
                    };
                    if a == GLX_LEVEL {
                        r.level = v;
                        continue;
                    }
                    let Ok(v) = u32::try_from(v) else {
                        return Err(Error::invalid_value(format!(
                            "attribute {} has a negative value {v}",
                            attr_name(a)
                        )));
                    };
                    match a {
                        GLX_BUFFER_SIZE => r.buffer_size = v,
                        GLX_AUX_BUFFERS => r.aux_buffers = v,
                        GLX_RED_SIZE => r.color[0] = v,
                        GLX_GREEN_SIZE => r.color[1] = v,
                        GLX_BLUE_SIZE => r.color[2] = v,
                        GLX_ALPHA_SIZE => r.color[3] = v,
                        GLX_DEPTH_SIZE => r.depth = v,
                        GLX_STENCIL_SIZE => r.stencil = v,
                        GLX_ACCUM_RED_SIZE => r.accum[0] = v,
                        GLX_ACCUM_GREEN_SIZE => r.accum[1] = v,
                        GLX_ACCUM_BLUE_SIZE => r.accum[2] = v,
                        GLX_ACCUM_ALPHA_SIZE => r.accum[3] = v,
                        GLX_SAMPLE_BUFFERS => {
                            if v > 0 && r.samples == 0 {
                                r.samples = 1;
                            }
                        }
                        GLX_SAMPLES => r.samples = v,
                        _ => r.srgb = v != 0,
                    }
                }
                _ => {
                    return Err(Error::invalid_enum(
                        "GLX attribute",
                        a as u32,
                        format!(
                            "attribute {a:#x} at index {i} is not a glXChooseVisual attribute (GLX_RGBA, \
                             GLX_DOUBLEBUFFER, GLX_STEREO, GLX_RED/GREEN/BLUE/ALPHA/DEPTH/STENCIL_SIZE, …); \
                             end the list with None (0)"
                        ),
                    ));
                }
            }
        }
        Ok(r)
    }

    /// Why this request cannot be met by an RGBA8 framebuffer with a 24-bit
    /// depth and 8-bit stencil buffer (what every backend offers), if so.
    pub fn unsupported_reason(&self) -> Option<String> {
        if !self.rgba {
            return Some(
                "colour-index visuals are not supported: add GLX_RGBA to the attribute list".into(),
            );
        }
        if self.level != 0 {
            return Some(format!(
                "GLX_LEVEL {} (overlay/underlay planes) is not supported",
                self.level
            ));
        }
        if let Some(c) = self.color.iter().find(|&&c| c > 8) {
            return Some(format!(
                "a colour size of {c} bits is more than the 8 bits per channel offered"
            ));
        }
        if self.buffer_size > 32 {
            return Some(format!(
                "GLX_BUFFER_SIZE {} is more than the 32 bits offered",
                self.buffer_size
            ));
        }
        if self.depth > 24 {
            return Some(format!(
                "GLX_DEPTH_SIZE {} is more than the 24 bits offered",
                self.depth
            ));
        }
        if self.stencil > 8 {
            return Some(format!(
                "GLX_STENCIL_SIZE {} is more than the 8 bits offered",
                self.stencil
            ));
        }
        if self.accum.iter().any(|&a| a > 0) {
            return Some(
                "accumulation buffers are not supported (framebuffer objects have none)".into(),
            );
        }
        if self.aux_buffers > 0 {
            return Some("aux buffers are not supported".into());
        }
        if self.samples > 0 {
            return Some(
                "multisampled configurations are not supported yet; drop GLX_SAMPLES".into(),
            );
        }
        None
    }
}

/// How a configuration provides stereo.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StereoKind {
    /// Mono: no right buffers.
    None,
    /// The driver's own quad buffer (GL_STEREO is true in the real context).
    Native,
    /// glstereo's emulated quad buffer.
    Emulated,
}

/// Whether to emulate stereo (GLSTEREO_EMULATION).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmulationPolicy {
    /// Native stereo when the backend has it, else emulated (default; "on").
    Auto,
    /// Never emulate: fail as glXChooseVisual does without stereo ("off").
    Off,
    /// Always emulate, even when native stereo exists ("force").
    Force,
}

impl EmulationPolicy {
    /// Parses GLSTEREO_EMULATION: unset/empty/on/1/yes/true/auto → Auto,
    /// off/0/no/false → Off, force → Force.
    pub fn from_env_value(v: Option<&str>) -> Result<EmulationPolicy> {
        let Some(v) = v else {
            return Ok(EmulationPolicy::Auto);
        };
        match v.trim().to_ascii_lowercase().as_str() {
            "" | "on" | "1" | "yes" | "true" | "auto" => Ok(EmulationPolicy::Auto),
            "off" | "0" | "no" | "false" => Ok(EmulationPolicy::Off),
            "force" => Ok(EmulationPolicy::Force),
            other => Err(Error::invalid_value(format!(
                "GLSTEREO_EMULATION={other:?} is not valid: use on (default), off or force"
            ))),
        }
    }
}

/// A chosen configuration.
#[derive(Clone)]
pub struct Config {
    /// What the program asked for.
    pub request: ConfigRequest,
    /// How stereo is provided.
    pub stereo: StereoKind,
    /// Depth bits of the framebuffer (0 or 24).
    pub depth_bits: u32,
    /// Stencil bits of the framebuffer (0 or 8).
    pub stencil_bits: u32,
    /// Backend-specific data (a GLX visual, …).
    pub native: Option<Arc<dyn Any + Send + Sync>>,
    /// The id of the display that chose it ([`crate::display::Display::id`]);
    /// 0 for a configuration made without one. A surface can only be made
    /// from a configuration on the display that chose it.
    pub display_id: u64,
}

impl std::fmt::Debug for Config {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Config")
            .field("stereo", &self.stereo)
            .field("double_buffer", &self.request.double_buffer)
            .field("depth_bits", &self.depth_bits)
            .field("stencil_bits", &self.stencil_bits)
            .finish()
    }
}

impl Config {
    /// A configuration that meets `request` with glstereo's own framebuffer
    /// (RGBA8, and D24S8 when depth or stencil was asked for), choosing how
    /// to provide stereo from `native_stereo_available` and `policy`.
    pub fn choose(
        request: ConfigRequest,
        native_stereo_available: bool,
        policy: EmulationPolicy,
    ) -> Result<Config> {
        if let Some(why) = request.unsupported_reason() {
            return Err(Error::NoMatchingConfig(why));
        }
        let stereo = match (request.stereo, native_stereo_available, policy) {
            (false, _, _) => StereoKind::None,
            (true, _, EmulationPolicy::Force) => StereoKind::Emulated,
            (true, true, _) => StereoKind::Native,
            (true, false, EmulationPolicy::Auto) => StereoKind::Emulated,
            (true, false, EmulationPolicy::Off) => {
                return Err(Error::NoMatchingConfig(
                    "no stereo configuration: this backend has no native stereo and \
                     GLSTEREO_EMULATION=off forbids emulating it (retry without GLX_STEREO, \
                     or unset GLSTEREO_EMULATION)"
                        .into(),
                ));
            }
        };
        let depth_or_stencil = request.depth > 0 || request.stencil > 0;
        Ok(Config {
            request,
            stereo,
            depth_bits: if depth_or_stencil { 24 } else { 0 },
            stencil_bits: if depth_or_stencil { 8 } else { 0 },
            native: None,
            display_id: 0,
        })
    }

    /// The colour buffers this configuration's default framebuffer has.
    pub fn shape(&self) -> FramebufferShape {
        FramebufferShape {
            stereo: self.stereo != StereoKind::None,
            double_buffered: self.request.double_buffer,
        }
    }

    /// The value glXGetConfig would report for a GLX attribute, or
    /// `InvalidEnum` for an attribute that is not a visual attribute.
    pub fn get_attrib(&self, attrib: i32) -> Result<i32> {
        let b = |v: bool| v as i32;
        Ok(match attrib {
            GLX_USE_GL => 1,
            GLX_BUFFER_SIZE => 32,
            GLX_LEVEL => 0,
            GLX_RGBA => 1,
            GLX_DOUBLEBUFFER => b(self.request.double_buffer),
            GLX_STEREO => b(self.stereo != StereoKind::None),
            GLX_AUX_BUFFERS => 0,
            GLX_RED_SIZE | GLX_GREEN_SIZE | GLX_BLUE_SIZE | GLX_ALPHA_SIZE => 8,
            GLX_DEPTH_SIZE => self.depth_bits as i32,
            GLX_STENCIL_SIZE => self.stencil_bits as i32,
            GLX_ACCUM_RED_SIZE | GLX_ACCUM_GREEN_SIZE | GLX_ACCUM_BLUE_SIZE
            | GLX_ACCUM_ALPHA_SIZE => 0,
            GLX_SAMPLE_BUFFERS | GLX_SAMPLES => 0,
            GLX_FRAMEBUFFER_SRGB_CAPABLE_ARB => 0,
            a => {
                return Err(Error::invalid_enum(
                    "GLX attribute",
                    a as u32,
                    "use a glXGetConfig attribute such as GLX_STEREO or GLX_DOUBLEBUFFER",
                ));
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HP_STEREO: &[i32] = &[
        GLX_RGBA,
        GLX_DOUBLEBUFFER,
        GLX_RED_SIZE,
        1,
        GLX_GREEN_SIZE,
        1,
        GLX_BLUE_SIZE,
        1,
        GLX_DEPTH_SIZE,
        1,
        GLX_STEREO,
    ];

    #[test]
    fn the_hp_seed_attribute_list_parses() {
        let r = ConfigRequest::parse_visual_attribs(HP_STEREO).unwrap();
        assert!(r.rgba && r.double_buffer && r.stereo);
        assert_eq!(r.color, [1, 1, 1, 0]);
        assert_eq!(r.depth, 1);
        let c = Config::choose(r, false, EmulationPolicy::Auto).unwrap();
        assert_eq!(c.stereo, StereoKind::Emulated);
        assert_eq!(c.depth_bits, 24);
        assert_eq!(c.get_attrib(GLX_STEREO).unwrap(), 1);
    }

    #[test]
    fn unknown_attributes_are_named() {
        let e = ConfigRequest::parse_visual_attribs(&[GLX_RGBA, 0x7777]).unwrap_err();
        assert!(
            matches!(e, Error::InvalidEnum { value: 0x7777, .. }),
            "{e:?}"
        );
        assert!(e.to_string().contains("0x7777"), "{e}");
        let e = ConfigRequest::parse_visual_attribs(&[GLX_RGBA, GLX_DEPTH_SIZE]).unwrap_err();
        assert!(e.to_string().contains("GLX_DEPTH_SIZE"), "{e}");
        let e = ConfigRequest::parse_visual_attribs(&[GLX_RED_SIZE, -4]).unwrap_err();
        assert!(matches!(e, Error::InvalidValue(_)));
    }

    #[test]
    fn emulation_policy_decides_stereo() {
        let r = ConfigRequest::parse_visual_attribs(HP_STEREO).unwrap();
        let e = Config::choose(r, false, EmulationPolicy::Off).unwrap_err();
        assert!(matches!(e, Error::NoMatchingConfig(_)));
        assert_eq!(
            Config::choose(r, true, EmulationPolicy::Auto)
                .unwrap()
                .stereo,
            StereoKind::Native
        );
        assert_eq!(
            Config::choose(r, true, EmulationPolicy::Force)
                .unwrap()
                .stereo,
            StereoKind::Emulated
        );
        let mono = ConfigRequest::parse_visual_attribs(&[GLX_RGBA]).unwrap();
        let c = Config::choose(mono, false, EmulationPolicy::Off).unwrap();
        assert_eq!(c.stereo, StereoKind::None);
        assert!(!c.shape().double_buffered && !c.shape().stereo);
        assert_eq!(c.depth_bits, 0);
        assert_eq!(
            EmulationPolicy::from_env_value(Some("OFF")).unwrap(),
            EmulationPolicy::Off
        );
        assert!(EmulationPolicy::from_env_value(Some("maybe")).is_err());
    }

    #[test]
    fn requests_beyond_what_is_offered_have_reasons() {
        for list in [
            &[GLX_DOUBLEBUFFER][..],
            &[GLX_RGBA, GLX_RED_SIZE, 10][..],
            &[GLX_RGBA, GLX_DEPTH_SIZE, 32][..],
            &[GLX_RGBA, GLX_ACCUM_RED_SIZE, 8][..],
            &[GLX_RGBA, GLX_LEVEL, 1][..],
            &[GLX_RGBA, GLX_SAMPLES, 4][..],
        ] {
            let r = ConfigRequest::parse_visual_attribs(list).unwrap();
            assert!(
                matches!(
                    Config::choose(r, false, EmulationPolicy::Auto),
                    Err(Error::NoMatchingConfig(_))
                ),
                "{list:?}"
            );
        }
    }
}

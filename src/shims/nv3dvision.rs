//! NV_3dvision_settings (seed 004; OpenGL ES extension #129) and the
//! auto-stereo surface attribute of EGL_NV_3dvision_surface: the state, its
//! rules and its per-eye projections. Pure: no GL calls.
//!
//! The state is the extension's "three floats and one integer" plus the
//! enable: separation (percent), convergence, cutoff, projection method and
//! 3DVISION_STEREO_NV. What a call does, and the GL error it raises, is
//! decided here; [`crate::framing::auto`] applies the result to a frame.
//!
//! # What the numbers mean
//!
//! The driver's rule (seed 004, REFERENCE.md) moves every vertex of eye
//! `eye` (−1 left, +1 right) in clip space:
//!
//! ```text
//! x_clip' = x_clip + eye · s · (w_clip − C)
//! ```
//!
//! so on screen (NDC) a point at depth `w` moves by `eye · s · (1 − C/w)`:
//! its parallax (right-eye x minus left-eye x) is `s · (1 − C/w)` of the
//! viewport width. `C` is [`StereoSettings::convergence`] as set; `s` comes
//! from the separation and the cutoff:
//!
//! - **Separation** is a percentage (0…100) of [`MAX_SEPARATION`] = 0.07:
//!   at 100 %, far-away geometry (w → ∞) is 7 % of the viewport width apart
//!   in the two eyes. 7 % is the far parallax of HP's default camera (each
//!   camera offset by 3.5 % of the scene width at the zero-parallax plane,
//!   seed 000 §7), so separation p % with convergence d gives exactly HP's
//!   projections with UserOffsetAdjustment p/100, balance 1 and zero-parallax
//!   distance d (tested matrix for matrix). NVIDIA's driver means the same
//!   kind of thing by its "depth amount": a percentage of the maximum
//!   separation, which is applied to far objects. The initial value is
//!   [`INITIAL_SEPARATION_PERCENT`] (15 %, the driver's default depth
//!   amount): the spec leaves it to "system settings".
//! - **Convergence** is the depth that appears at the screen surface (zero
//!   parallax): in PERSPECTIVE mode a clip-space w, i.e. the distance from
//!   the camera for glFrustum/gluPerspective projections. Initial 0: every
//!   depth then gets the same parallax `s` (the whole picture behind the
//!   screen, flat), exactly as the formula says.
//! - **Cutoff** limits pop-out. Parallax in front of the screen has no bound
//!   (`s · (1 − C/w)` → −∞ as w → 0). With a cutoff depth `c > 0`, geometry
//!   at `c` or beyond never pops out by more than `s` of the viewport width
//!   (the parallax far-away geometry approaches): when it would, the
//!   separation is reduced to `s · c / (C − c)`, which puts depth `c` at
//!   exactly `−s`. The convergence is kept. A cutoff of 0 or less (the
//!   initial 0) limits nothing. [`StereoSettings::effective_separation`]
//!   is the result.
//! - **Projection** says which kind of projection the program uses
//!   (issue 2 of the spec). PERSPECTIVE (initial) is the formula above.
//!   ORTHO is for orthographic projections, where w_clip is 1 everywhere and
//!   the formula would shift every depth alike: depth is taken from the
//!   window depth `z_win = (z_clip/w_clip + 1)/2` instead (0 at the near
//!   plane, 1 at the far plane, linear in distance for glOrtho):
//!   `x_clip' = x_clip + eye · s · ((z_clip + w_clip)/2 − C · w_clip)`, so
//!   the parallax is `s · (z_win − C)`. Convergence and cutoff are then
//!   window depths (0…1); this is the oblique (sheared) parallel projection
//!   that stereo of an orthographic camera needs. (A glOrtho near plane may
//!   lie behind the eye, so a distance from "the camera" would mean nothing.)
//!
//! Both forms change only the x row of the projection matrix: a
//! fixed-function program gets them by loading the eye's projection.

use glam::{DMat4, DVec4};

use crate::error::{Error, Result};
use crate::ffi::nv3dvision::{GLS_SURFACE_ATTRIB_NONE, GLS_SURFACE_AUTO_STEREO};
use crate::math::Eye;
use crate::math::hp::HP_OFFSET_FRACTION;
use crate::math::seeds::nv_clip_shift;

/// Capability of Enable/Disable/IsEnabled: 3D Vision rendering.
pub const GL_3DVISION_STEREO_NV: u32 = 0x90F4;
/// Separation, a percentage (GetFloatv).
pub const GL_STEREO_SEPARATION_NV: u32 = 0x90F5;
/// Convergence (GetFloatv).
pub const GL_STEREO_CONVERGENCE_NV: u32 = 0x90F6;
/// Separation cutoff (GetFloatv).
pub const GL_STEREO_CUTOFF_NV: u32 = 0x90F7;
/// Projection method (GetIntegerv).
pub const GL_STEREO_PROJECTION_NV: u32 = 0x90F8;
/// Projection method: perspective (initial).
pub const GL_STEREO_PROJECTION_PERSPECTIVE_NV: u32 = 0x90F9;
/// Projection method: orthographic.
pub const GL_STEREO_PROJECTION_ORTHO_NV: u32 = 0x90FA;

/// The separation at 100 %: the parallax of far-away geometry as a fraction
/// of the viewport width, twice HP's camera offset fraction (2 × 0.035).
pub const MAX_SEPARATION: f64 = 2.0 * HP_OFFSET_FRACTION;

/// The separation (percent) of a new surface: NVIDIA's default depth amount.
pub const INITIAL_SEPARATION_PERCENT: f32 = 15.0;

/// The projection type the program uses (STEREO_PROJECTION_NV).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProjectionMethod {
    /// STEREO_PROJECTION_PERSPECTIVE_NV: depth is w_clip.
    Perspective,
    /// STEREO_PROJECTION_ORTHO_NV: depth is the window depth z_win (0…1).
    Ortho,
}

impl ProjectionMethod {
    /// The GL token.
    pub fn gl_enum(self) -> u32 {
        match self {
            ProjectionMethod::Perspective => GL_STEREO_PROJECTION_PERSPECTIVE_NV,
            ProjectionMethod::Ortho => GL_STEREO_PROJECTION_ORTHO_NV,
        }
    }

    /// The method a GL token names; INVALID_ENUM for any other value.
    pub fn from_gl(v: u32) -> Result<ProjectionMethod> {
        match v {
            GL_STEREO_PROJECTION_PERSPECTIVE_NV => Ok(ProjectionMethod::Perspective),
            GL_STEREO_PROJECTION_ORTHO_NV => Ok(ProjectionMethod::Ortho),
            _ => Err(Error::invalid_enum(
                "GL_STEREO_PROJECTION_NV param",
                v,
                "use GL_STEREO_PROJECTION_PERSPECTIVE_NV (0x90F9) or GL_STEREO_PROJECTION_ORTHO_NV (0x90FA)",
            )),
        }
    }
}

/// One piece of state as GL stores it, before the conversion a Get command
/// applies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StateValue {
    /// A boolean (3DVISION_STEREO_NV).
    Boolean(bool),
    /// A float (separation, convergence, cutoff).
    Float(f32),
    /// An enumerant (the projection method).
    Enum(u32),
}

impl StateValue {
    /// As GetFloatv returns it: booleans as 0.0/1.0, enums as their value.
    pub fn as_float(self) -> f32 {
        match self {
            StateValue::Boolean(b) => b as u8 as f32,
            StateValue::Float(f) => f,
            StateValue::Enum(e) => e as f32,
        }
    }

    /// As GetIntegerv returns it: floats rounded to the nearest integer
    /// (GL's rule for state that is not a colour or normal; halves away
    /// from zero, saturating at the int range), booleans as 0/1.
    pub fn as_integer(self) -> i32 {
        match self {
            StateValue::Boolean(b) => b as i32,
            StateValue::Float(f) => f.round() as i32,
            StateValue::Enum(e) => e as i32,
        }
    }

    /// As GetBooleanv returns it: zero is false, anything else true.
    pub fn as_boolean(self) -> bool {
        match self {
            StateValue::Boolean(b) => b,
            StateValue::Float(f) => f != 0.0,
            StateValue::Enum(e) => e != 0,
        }
    }
}

/// The NV_3dvision_settings state of one surface (= its context).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StereoSettings {
    capable: bool,
    enabled: bool,
    separation: f32,
    convergence: f32,
    cutoff: f32,
    projection: ProjectionMethod,
}

impl StereoSettings {
    /// The initial state. An auto-stereo capable surface starts with 3D
    /// Vision rendering enabled (asking for the capability is asking for
    /// automatic stereo, as EGL_AUTO_STEREO_NV does); any other starts and
    /// stays disabled. Separation 15 %, convergence 0, cutoff 0, projection
    /// PERSPECTIVE on both.
    pub fn new(auto_stereo_capable: bool) -> StereoSettings {
        StereoSettings {
            capable: auto_stereo_capable,
            enabled: auto_stereo_capable,
            separation: INITIAL_SEPARATION_PERCENT,
            convergence: 0.0,
            cutoff: 0.0,
            projection: ProjectionMethod::Perspective,
        }
    }

    /// Whether the surface was made auto-stereo capable.
    pub fn capable(&self) -> bool {
        self.capable
    }

    /// IsEnabled(3DVISION_STEREO_NV).
    pub fn enabled(&self) -> bool {
        self.enabled
    }

    /// Whether frames are rendered once per eye: capable and enabled.
    pub fn renders_stereo(&self) -> bool {
        self.capable && self.enabled
    }

    /// Enable/Disable(3DVISION_STEREO_NV). "If the current draw surface is
    /// not auto stereo capable, enabling 3D Vision rendering has no effect":
    /// the state stays disabled, and no error is raised.
    pub fn set_enabled(&mut self, on: bool) {
        self.enabled = on && self.capable;
    }

    /// STEREO_SEPARATION_NV, percent.
    pub fn separation(&self) -> f32 {
        self.separation
    }

    /// STEREO_CONVERGENCE_NV.
    pub fn convergence(&self) -> f32 {
        self.convergence
    }

    /// STEREO_CUTOFF_NV.
    pub fn cutoff(&self) -> f32 {
        self.cutoff
    }

    /// STEREO_PROJECTION_NV.
    pub fn projection(&self) -> ProjectionMethod {
        self.projection
    }

    /// StereoParameterfNV. On error nothing changes; the error's GL code is
    /// INVALID_ENUM for an unknown `pname` or a projection that is not one
    /// of the two methods, INVALID_VALUE for a separation outside 0…100.
    /// Non-finite values are INVALID_VALUE too (the spec gives them no
    /// meaning; rendering with them would draw nothing sensible).
    pub fn parameter_f(&mut self, pname: u32, param: f32) -> Result<()> {
        match pname {
            GL_STEREO_SEPARATION_NV => {
                // NaN fails the range test as well.
                if !(0.0..=100.0).contains(&param) {
                    return Err(Error::invalid_value(format!(
                        "GL_STEREO_SEPARATION_NV is a percentage: it must be 0…100, got {param}"
                    )));
                }
                self.separation = param;
            }
            GL_STEREO_CONVERGENCE_NV => self.convergence = finite_param(pname, param)?,
            GL_STEREO_CUTOFF_NV => self.cutoff = finite_param(pname, param)?,
            GL_STEREO_PROJECTION_NV => {
                // An enum passed as a float is rounded to the nearest integer.
                let v = if param.is_finite() && param >= 0.0 && param <= u32::MAX as f32 {
                    param.round() as u32
                } else {
                    u32::MAX
                };
                self.projection = ProjectionMethod::from_gl(v)?;
            }
            _ => return Err(unknown_pname(pname)),
        }
        Ok(())
    }

    /// StereoParameteriNV: as [`StereoSettings::parameter_f`], the integer
    /// converted to float for the float parameters.
    pub fn parameter_i(&mut self, pname: u32, param: i32) -> Result<()> {
        match pname {
            GL_STEREO_PROJECTION_NV => {
                self.projection = ProjectionMethod::from_gl(param as u32)?;
                Ok(())
            }
            _ => self.parameter_f(pname, param as f32),
        }
    }

    /// The value of one of the extension's pnames for a Get command or
    /// IsEnabled; None for every other pname (the caller asks GL).
    pub fn query(&self, pname: u32) -> Option<StateValue> {
        Some(match pname {
            GL_3DVISION_STEREO_NV => StateValue::Boolean(self.enabled),
            GL_STEREO_SEPARATION_NV => StateValue::Float(self.separation),
            GL_STEREO_CONVERGENCE_NV => StateValue::Float(self.convergence),
            GL_STEREO_CUTOFF_NV => StateValue::Float(self.cutoff),
            GL_STEREO_PROJECTION_NV => StateValue::Enum(self.projection.gl_enum()),
            _ => return None,
        })
    }

    /// `s` before the cutoff: separation / 100 × [`MAX_SEPARATION`].
    pub fn separation_fraction(&self) -> f64 {
        self.separation as f64 / 100.0 * MAX_SEPARATION
    }

    /// How far a point at `depth` moves in NDC per unit of `eye · s`:
    /// `1 − C/depth` (PERSPECTIVE, depth = w_clip) or `depth − C` (ORTHO,
    /// depth = window depth).
    pub fn depth_factor(&self, depth: f64) -> f64 {
        let c = self.convergence as f64;
        match self.projection {
            ProjectionMethod::Perspective => 1.0 - c / depth,
            ProjectionMethod::Ortho => depth - c,
        }
    }

    /// The `s` frames are rendered with: the separation fraction, reduced by
    /// the cutoff rule (module docs) when geometry at the cutoff depth would
    /// otherwise pop out by more than `s`.
    pub fn effective_separation(&self) -> f64 {
        let s = self.separation_fraction();
        let cutoff = self.cutoff as f64;
        if cutoff > 0.0 {
            let f = self.depth_factor(cutoff);
            if f < -1.0 {
                return s / -f;
            }
        }
        s
    }

    /// The on-screen parallax of a point at `depth` (w_clip, or window depth
    /// in ORTHO mode): right-eye x minus left-eye x, as a fraction of the
    /// viewport width. Positive behind the screen.
    pub fn parallax_fraction(&self, depth: f64) -> f64 {
        self.effective_separation() * self.depth_factor(depth)
    }

    /// The projection matrix of one eye for the mono projection `mono`
    /// (column-major, as GL stores it). Only row x changes.
    pub fn eye_projection(&self, mono: &DMat4, eye: Eye) -> Result<DMat4> {
        let s = self.effective_separation();
        let c = self.convergence as f64;
        match self.projection {
            ProjectionMethod::Perspective => nv_clip_shift(mono, s, c, eye),
            ProjectionMethod::Ortho => ortho_clip_shift(mono, s, c, eye),
        }
    }
}

/// ORTHO mode: `x_clip' = x_clip + eye·s·((z_clip + w_clip)/2 − C·w_clip)`,
/// i.e. row x of `projection` plus `eye·s·((row z + row w)/2 − C·row w)`.
pub fn ortho_clip_shift(
    projection: &DMat4,
    separation: f64,
    convergence: f64,
    eye: Eye,
) -> Result<DMat4> {
    crate::math::finite("separation", separation)?;
    crate::math::finite("convergence", convergence)?;
    crate::math::finite_matrix_param("projection", projection)?;
    let k = eye.sign() * separation;
    let depth: DVec4 = (projection.row(2) + projection.row(3)) * 0.5;
    let row_x = projection.row(0) + k * (depth - convergence * projection.row(3));
    let mut m = *projection;
    m.x_axis.x = row_x.x;
    m.y_axis.x = row_x.y;
    m.z_axis.x = row_x.z;
    m.w_axis.x = row_x.w;
    Ok(m)
}

fn finite_param(pname: u32, v: f32) -> Result<f32> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid_value(format!(
            "{} must be a finite number, got {v}",
            pname_name(pname)
        )))
    }
}

fn pname_name(pname: u32) -> &'static str {
    match pname {
        GL_3DVISION_STEREO_NV => "GL_3DVISION_STEREO_NV",
        GL_STEREO_SEPARATION_NV => "GL_STEREO_SEPARATION_NV",
        GL_STEREO_CONVERGENCE_NV => "GL_STEREO_CONVERGENCE_NV",
        GL_STEREO_CUTOFF_NV => "GL_STEREO_CUTOFF_NV",
        GL_STEREO_PROJECTION_NV => "GL_STEREO_PROJECTION_NV",
        _ => "pname",
    }
}

fn unknown_pname(pname: u32) -> Error {
    let hint = if pname == GL_3DVISION_STEREO_NV {
        "GL_3DVISION_STEREO_NV is a capability: use gls_enable()/gls_disable(); "
    } else {
        ""
    };
    Error::invalid_enum(
        "StereoParameter pname",
        pname,
        format!(
            "{hint}use GL_STEREO_SEPARATION_NV (0x90F5), GL_STEREO_CONVERGENCE_NV (0x90F6), \
             GL_STEREO_CUTOFF_NV (0x90F7) or GL_STEREO_PROJECTION_NV (0x90F8)"
        ),
    )
}

/// What a surface-creation attribute list asks for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SurfaceAttribs {
    /// GLS_SURFACE_AUTO_STEREO: the surface is auto-stereo capable
    /// (EGL_AUTO_STEREO_NV). Default false.
    pub auto_stereo: bool,
}

impl SurfaceAttribs {
    /// Parses (name, value) pairs read up to the GLS_SURFACE_ATTRIB_NONE
    /// terminator (not included). A later pair overrides an earlier one of
    /// the same name, as in EGL. An unknown name is INVALID_ENUM; a value
    /// other than 0 or 1 for a boolean is INVALID_VALUE.
    pub fn parse(pairs: &[(i32, i32)]) -> Result<SurfaceAttribs> {
        let mut a = SurfaceAttribs::default();
        for (i, &(name, value)) in pairs.iter().enumerate() {
            match name {
                GLS_SURFACE_AUTO_STEREO => {
                    a.auto_stereo = match value {
                        0 => false,
                        1 => true,
                        v => {
                            return Err(Error::invalid_value(format!(
                                "GLS_SURFACE_AUTO_STEREO (pair {i}) must be 0 or 1, got {v}"
                            )));
                        }
                    }
                }
                GLS_SURFACE_ATTRIB_NONE => unreachable!("the terminator is not part of the list"),
                n => {
                    return Err(Error::invalid_enum(
                        "surface attribute",
                        n as u32,
                        format!(
                            "attribute {n:#x} (pair {i}) is not a surface attribute: use \
                             GLS_SURFACE_AUTO_STEREO (0x3136) and end the list with \
                             GLS_SURFACE_ATTRIB_NONE (0)"
                        ),
                    ));
                }
            }
        }
        Ok(a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gl::enums::{GL_INVALID_ENUM, GL_INVALID_VALUE};
    use crate::math::Frustum;
    use crate::math::hp::{StereoAdjust, hp_eye};
    use crate::math::testutil::assert_mat_close;

    /// The GL error a failed call records (surface.rs maps errors the same way).
    fn gl_error_of(e: &Error) -> u32 {
        match e {
            Error::InvalidEnum { .. } => GL_INVALID_ENUM,
            Error::InvalidValue(_) => GL_INVALID_VALUE,
            _ => panic!("StereoParameter raised {e:?}"),
        }
    }

    const ALL_PNAMES: [u32; 5] = [
        GL_3DVISION_STEREO_NV,
        GL_STEREO_SEPARATION_NV,
        GL_STEREO_CONVERGENCE_NV,
        GL_STEREO_CUTOFF_NV,
        GL_STEREO_PROJECTION_NV,
    ];

    #[test]
    fn tokens_have_the_registry_values() {
        assert_eq!(
            [
                GL_3DVISION_STEREO_NV,
                GL_STEREO_SEPARATION_NV,
                GL_STEREO_CONVERGENCE_NV,
                GL_STEREO_CUTOFF_NV,
                GL_STEREO_PROJECTION_NV,
                GL_STEREO_PROJECTION_PERSPECTIVE_NV,
                GL_STEREO_PROJECTION_ORTHO_NV
            ],
            [0x90F4, 0x90F5, 0x90F6, 0x90F7, 0x90F8, 0x90F9, 0x90FA]
        );
    }

    #[test]
    fn initial_values_in_every_get_form() {
        for capable in [true, false] {
            let s = StereoSettings::new(capable);
            let q = |p| s.query(p).unwrap();
            assert_eq!(q(GL_3DVISION_STEREO_NV), StateValue::Boolean(capable));
            assert_eq!(q(GL_STEREO_SEPARATION_NV).as_float(), 15.0);
            assert_eq!(q(GL_STEREO_SEPARATION_NV).as_integer(), 15);
            assert!(q(GL_STEREO_SEPARATION_NV).as_boolean());
            for p in [GL_STEREO_CONVERGENCE_NV, GL_STEREO_CUTOFF_NV] {
                assert_eq!(q(p).as_float(), 0.0);
                assert_eq!(q(p).as_integer(), 0);
                assert!(!q(p).as_boolean());
            }
            let proj = q(GL_STEREO_PROJECTION_NV);
            assert_eq!(proj.as_integer(), 0x90F9);
            assert_eq!(proj.as_float(), 37113.0);
            assert!(proj.as_boolean());
            assert_eq!(q(GL_3DVISION_STEREO_NV).as_integer(), capable as i32);
            assert_eq!(q(GL_3DVISION_STEREO_NV).as_float(), capable as u8 as f32);
            assert_eq!(s.query(0x0C33), None, "GL_STEREO is not ours");
        }
    }

    #[test]
    fn enabling_has_no_effect_on_a_surface_that_is_not_capable() {
        let mut s = StereoSettings::new(false);
        s.set_enabled(true);
        assert!(!s.enabled() && !s.renders_stereo());
        let mut c = StereoSettings::new(true);
        c.set_enabled(false);
        assert!(!c.enabled() && !c.renders_stereo());
        c.set_enabled(true);
        assert!(c.renders_stereo());
    }

    #[test]
    fn parameters_round_trip_through_both_setters() {
        let mut s = StereoSettings::new(true);
        s.parameter_f(GL_STEREO_SEPARATION_NV, 42.5).unwrap();
        s.parameter_f(GL_STEREO_CONVERGENCE_NV, -3.25).unwrap();
        s.parameter_f(GL_STEREO_CUTOFF_NV, 1.5).unwrap();
        s.parameter_f(GL_STEREO_PROJECTION_NV, 37114.0).unwrap();
        assert_eq!(
            (s.separation(), s.convergence(), s.cutoff(), s.projection()),
            (42.5, -3.25, 1.5, ProjectionMethod::Ortho)
        );
        assert_eq!(s.query(GL_STEREO_SEPARATION_NV).unwrap().as_integer(), 43);
        s.parameter_i(GL_STEREO_SEPARATION_NV, 100).unwrap();
        s.parameter_i(GL_STEREO_CONVERGENCE_NV, 12).unwrap();
        s.parameter_i(GL_STEREO_CUTOFF_NV, -2).unwrap();
        s.parameter_i(GL_STEREO_PROJECTION_NV, 0x90F9).unwrap();
        assert_eq!(
            (s.separation(), s.convergence(), s.cutoff(), s.projection()),
            (100.0, 12.0, -2.0, ProjectionMethod::Perspective)
        );
        // The ends of the range are valid.
        s.parameter_f(GL_STEREO_SEPARATION_NV, 0.0).unwrap();
        s.parameter_i(GL_STEREO_SEPARATION_NV, 0).unwrap();
    }

    /// Every error case of the spec, through both setters: the GL error
    /// code, and nothing changed.
    #[test]
    fn every_error_has_its_gl_code_and_changes_nothing() {
        let cases: Vec<(u32, Option<f32>, Option<i32>, u32)> = vec![
            // Unknown pname, including the capability and the method tokens.
            (0x1234, Some(1.0), None, GL_INVALID_ENUM),
            (0x1234, None, Some(1), GL_INVALID_ENUM),
            (GL_3DVISION_STEREO_NV, Some(1.0), None, GL_INVALID_ENUM),
            (GL_3DVISION_STEREO_NV, None, Some(1), GL_INVALID_ENUM),
            (
                GL_STEREO_PROJECTION_ORTHO_NV,
                Some(1.0),
                None,
                GL_INVALID_ENUM,
            ),
            (0, None, Some(0), GL_INVALID_ENUM),
            // Unknown projection value.
            (GL_STEREO_PROJECTION_NV, None, Some(0x90FB), GL_INVALID_ENUM),
            (GL_STEREO_PROJECTION_NV, None, Some(0), GL_INVALID_ENUM),
            (GL_STEREO_PROJECTION_NV, None, Some(-1), GL_INVALID_ENUM),
            (GL_STEREO_PROJECTION_NV, None, Some(0x90F5), GL_INVALID_ENUM),
            (GL_STEREO_PROJECTION_NV, Some(1.0), None, GL_INVALID_ENUM),
            (
                GL_STEREO_PROJECTION_NV,
                Some(f32::NAN),
                None,
                GL_INVALID_ENUM,
            ),
            (
                GL_STEREO_PROJECTION_NV,
                Some(-37113.0),
                None,
                GL_INVALID_ENUM,
            ),
            // Separation outside 0…100.
            (
                GL_STEREO_SEPARATION_NV,
                Some(-0.001),
                None,
                GL_INVALID_VALUE,
            ),
            (
                GL_STEREO_SEPARATION_NV,
                Some(100.001),
                None,
                GL_INVALID_VALUE,
            ),
            (GL_STEREO_SEPARATION_NV, None, Some(-1), GL_INVALID_VALUE),
            (GL_STEREO_SEPARATION_NV, None, Some(101), GL_INVALID_VALUE),
            (
                GL_STEREO_SEPARATION_NV,
                Some(f32::NAN),
                None,
                GL_INVALID_VALUE,
            ),
            (
                GL_STEREO_SEPARATION_NV,
                Some(f32::INFINITY),
                None,
                GL_INVALID_VALUE,
            ),
            // Non-finite convergence and cutoff (this library's addition).
            (
                GL_STEREO_CONVERGENCE_NV,
                Some(f32::NAN),
                None,
                GL_INVALID_VALUE,
            ),
            (
                GL_STEREO_CUTOFF_NV,
                Some(f32::NEG_INFINITY),
                None,
                GL_INVALID_VALUE,
            ),
        ];
        let mut s = StereoSettings::new(true);
        s.parameter_f(GL_STEREO_SEPARATION_NV, 33.0).unwrap();
        s.parameter_f(GL_STEREO_CONVERGENCE_NV, 7.0).unwrap();
        let before = s;
        for (pname, fv, iv, code) in cases {
            let r = match (fv, iv) {
                (Some(v), _) => s.parameter_f(pname, v),
                (_, Some(v)) => s.parameter_i(pname, v),
                _ => unreachable!(),
            };
            let e = r.expect_err(&format!("{pname:#x} {fv:?} {iv:?} must fail"));
            assert_eq!(gl_error_of(&e), code, "{pname:#x} {fv:?} {iv:?}: {e}");
            assert_eq!(s, before, "{pname:#x} {fv:?} {iv:?} changed the state");
        }
        for capable in [false, true] {
            let mut n = StereoSettings::new(capable);
            let e = n.parameter_f(GL_STEREO_SEPARATION_NV, 200.0).unwrap_err();
            assert_eq!(
                gl_error_of(&e),
                GL_INVALID_VALUE,
                "errors regardless of capability"
            );
        }
    }

    #[test]
    fn error_messages_say_what_to_use() {
        let mut s = StereoSettings::new(true);
        let e = s.parameter_f(0x1234, 0.0).unwrap_err().to_string();
        assert!(
            e.contains("0x1234") && e.contains("GL_STEREO_SEPARATION_NV"),
            "{e}"
        );
        let e = s
            .parameter_i(GL_3DVISION_STEREO_NV, 1)
            .unwrap_err()
            .to_string();
        assert!(e.contains("gls_enable"), "{e}");
        let e = s
            .parameter_f(GL_STEREO_SEPARATION_NV, 150.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("0…100") && e.contains("150"), "{e}");
        let e = s
            .parameter_i(GL_STEREO_PROJECTION_NV, 7)
            .unwrap_err()
            .to_string();
        assert!(e.contains("GL_STEREO_PROJECTION_ORTHO_NV"), "{e}");
    }

    #[test]
    fn integer_queries_round_floats_to_nearest() {
        assert_eq!(StateValue::Float(2.5).as_integer(), 3);
        assert_eq!(StateValue::Float(2.49).as_integer(), 2);
        assert_eq!(StateValue::Float(-2.5).as_integer(), -3);
        assert_eq!(StateValue::Float(1e20).as_integer(), i32::MAX);
        assert!(StateValue::Float(-0.25).as_boolean());
    }

    fn settings(separation: f32, convergence: f32) -> StereoSettings {
        let mut s = StereoSettings::new(true);
        s.parameter_f(GL_STEREO_SEPARATION_NV, separation).unwrap();
        s.parameter_f(GL_STEREO_CONVERGENCE_NV, convergence)
            .unwrap();
        s
    }

    /// Separation p % at convergence d is HP's method with offset p/100,
    /// balance 1 and zero-parallax distance d: the documented maximum.
    #[test]
    fn separation_percent_is_hp_offset_adjustment_matrix_for_matrix() {
        for (fovy, aspect, near, far, d) in [
            (45.0, 1.25, 1.0, 100.0, 9.0),
            (60.0, 16.0 / 9.0, 0.1, 1000.0, 2.5),
            (30.0, 0.48, 3.0, 40.0, 17.0),
        ] {
            let mono = Frustum::perspective(fovy, aspect, near, far).unwrap();
            for p in [0.0f32, 15.0, 50.0, 100.0] {
                let s = settings(p, d as f32);
                let adj = StereoAdjust {
                    offset_adjustment: p as f64 / 100.0,
                    ..StereoAdjust::new(s.convergence() as f64)
                };
                for eye in Eye::BOTH {
                    let nv = s.eye_projection(&mono.matrix(), eye).unwrap();
                    let hp = hp_eye(&mono, &adj, eye).unwrap().matrix();
                    assert_mat_close(&nv, &hp, 1e-12, &format!("{p}% at {d}, {eye:?}"));
                }
            }
        }
    }

    #[test]
    fn far_parallax_at_full_separation_is_seven_percent_of_the_width() {
        let s = settings(100.0, 10.0);
        assert!((s.parallax_fraction(1e15) - 0.07).abs() < 1e-12);
        assert_eq!(s.parallax_fraction(10.0), 0.0);
        assert!(s.parallax_fraction(5.0) < 0.0 && s.parallax_fraction(20.0) > 0.0);
        // Initial convergence 0: every depth gets the same parallax.
        let flat = StereoSettings::new(true);
        let p = flat.separation_fraction();
        assert!((p - 0.15 * 0.07).abs() < 1e-12);
        for w in [0.5, 3.0, 1000.0] {
            assert!((flat.parallax_fraction(w) - p).abs() < 1e-15);
        }
    }

    #[test]
    fn parallax_matches_the_projected_points() {
        let mono = Frustum::perspective(50.0, 1.5, 0.5, 80.0).unwrap().matrix();
        let s = settings(60.0, 8.0);
        let x_ndc = |m: &DMat4, z: f64| {
            let c = *m * DVec4::new(0.3, -0.2, z, 1.0);
            c.x / c.w
        };
        let l = s.eye_projection(&mono, Eye::Left).unwrap();
        let r = s.eye_projection(&mono, Eye::Right).unwrap();
        for depth in [1.0, 4.0, 8.0, 30.0] {
            let measured = (x_ndc(&r, -depth) - x_ndc(&l, -depth)) / 2.0;
            assert!(
                (measured - s.parallax_fraction(depth)).abs() < 1e-12,
                "depth {depth}: {measured} vs {}",
                s.parallax_fraction(depth)
            );
        }
        // y, z and w are untouched.
        for row in 1..4 {
            assert_eq!(l.row(row), mono.row(row));
        }
    }

    #[test]
    fn cutoff_limits_pop_out_to_the_far_parallax_and_keeps_convergence() {
        let mut s = settings(50.0, 10.0);
        let full = s.separation_fraction();
        // Cutoff 2: depth 2 would pop out by 4·s; the separation drops to s/4.
        s.parameter_f(GL_STEREO_CUTOFF_NV, 2.0).unwrap();
        assert!((s.effective_separation() - full / 4.0).abs() < 1e-15);
        assert!((s.parallax_fraction(2.0) + full).abs() < 1e-15);
        assert_eq!(s.parallax_fraction(10.0), 0.0);
        for w in [2.0, 3.0, 10.0, 1e9] {
            assert!(s.parallax_fraction(w).abs() <= full + 1e-15, "depth {w}");
        }
        // A cutoff whose pop-out is already within s changes nothing.
        for c in [5.0, 6.0, 10.0, 50.0, 0.0, -4.0] {
            s.parameter_f(GL_STEREO_CUTOFF_NV, c).unwrap();
            assert_eq!(s.effective_separation(), full, "cutoff {c}");
        }
    }

    #[test]
    fn ortho_mode_takes_depth_from_the_window_depth() {
        // glOrtho(-2, 2, -1.5, 1.5, 1, 11): z_win = (distance − 1) / 10.
        let (n, f) = (1.0, 11.0);
        let ortho = DMat4::orthographic_rh_gl(-2.0, 2.0, -1.5, 1.5, n, f);
        let mut s = settings(100.0, 0.5);
        s.parameter_i(
            GL_STEREO_PROJECTION_NV,
            GL_STEREO_PROJECTION_ORTHO_NV as i32,
        )
        .unwrap();
        let l = s.eye_projection(&ortho, Eye::Left).unwrap();
        let r = s.eye_projection(&ortho, Eye::Right).unwrap();
        for dist in [1.0, 3.5, 6.0, 11.0] {
            let x = |m: &DMat4| {
                let c = *m * DVec4::new(0.7, 0.1, -dist, 1.0);
                c.x / c.w
            };
            let z_win = (dist - n) / (f - n);
            let measured = (x(&r) - x(&l)) / 2.0;
            assert!(
                (measured - 0.07 * (z_win - 0.5)).abs() < 1e-12,
                "distance {dist}: {measured}"
            );
            assert!((measured - s.parallax_fraction(z_win)).abs() < 1e-12);
        }
        // The same matrix in PERSPECTIVE mode shifts every depth alike.
        s.parameter_i(
            GL_STEREO_PROJECTION_NV,
            GL_STEREO_PROJECTION_PERSPECTIVE_NV as i32,
        )
        .unwrap();
        let l = s.eye_projection(&ortho, Eye::Left).unwrap();
        let r = s.eye_projection(&ortho, Eye::Right).unwrap();
        let shift = |dist: f64| {
            let p = DVec4::new(0.0, 0.0, -dist, 1.0);
            ((r * p).x - (l * p).x) / 2.0
        };
        assert!((shift(1.0) - shift(11.0)).abs() < 1e-15);
    }

    #[test]
    fn separation_zero_gives_the_mono_projection_for_both_eyes() {
        let mono = Frustum::perspective(40.0, 1.0, 1.0, 20.0).unwrap().matrix();
        for method in [
            GL_STEREO_PROJECTION_PERSPECTIVE_NV,
            GL_STEREO_PROJECTION_ORTHO_NV,
        ] {
            let mut s = settings(0.0, 5.0);
            s.parameter_i(GL_STEREO_PROJECTION_NV, method as i32)
                .unwrap();
            for eye in Eye::BOTH {
                assert_eq!(s.eye_projection(&mono, eye).unwrap(), mono);
            }
        }
    }

    #[test]
    fn surface_attributes_parse_and_reject_by_name() {
        assert_eq!(
            SurfaceAttribs::parse(&[]).unwrap(),
            SurfaceAttribs::default()
        );
        assert!(
            SurfaceAttribs::parse(&[(GLS_SURFACE_AUTO_STEREO, 1)])
                .unwrap()
                .auto_stereo
        );
        assert!(
            !SurfaceAttribs::parse(&[(GLS_SURFACE_AUTO_STEREO, 1), (GLS_SURFACE_AUTO_STEREO, 0)])
                .unwrap()
                .auto_stereo,
            "the last value wins"
        );
        let e = SurfaceAttribs::parse(&[(GLS_SURFACE_AUTO_STEREO, 2)]).unwrap_err();
        assert!(matches!(e, Error::InvalidValue(_)), "{e:?}");
        let e = SurfaceAttribs::parse(&[(0x3137, 1)]).unwrap_err();
        assert!(
            matches!(e, Error::InvalidEnum { value: 0x3137, .. }),
            "{e:?}"
        );
        assert!(e.to_string().contains("GLS_SURFACE_AUTO_STEREO"), "{e}");
        assert_eq!(
            GLS_SURFACE_AUTO_STEREO, 0x3136,
            "EGL_AUTO_STEREO_NV's value"
        );
    }

    #[test]
    fn all_pnames_are_answered_and_nothing_else() {
        let s = StereoSettings::new(true);
        for p in ALL_PNAMES {
            assert!(s.query(p).is_some(), "{p:#x}");
        }
        for p in [
            GL_STEREO_PROJECTION_PERSPECTIVE_NV,
            GL_STEREO_PROJECTION_ORTHO_NV,
            0x90F3,
        ] {
            assert!(s.query(p).is_none(), "{p:#x}");
        }
    }
}

//! NV_3dvision_settings and automatic stereo on real Mesa EGL contexts: the
//! extension's initial values and errors through the C ABI, and a
//! fixed-function mono scene rendered through the per-eye frame call,
//! measured on the rendered eye images.
//!
//! The scene: a grey background and three flat cards facing the camera at
//! depths 4 (red, top), 8 (green, middle) and 16 (blue, bottom). Parallax is
//! measured as the shift of a card's left edge between the eyes.

use std::cell::Cell;
use std::ffi::{CStr, c_void};
use std::sync::Arc;

use glstereo::backend::{BackendChoice, BackendKind};
use glstereo::config::glx::*;
use glstereo::display::Display;
use glstereo::error::Error;
use glstereo::ffi::nv3dvision::*;
use glstereo::ffi::surface::{gls_get_error, gls_get_integerv};
use glstereo::ffi::types::*;
use glstereo::framing::auto::{create_surface, render_frame};
use glstereo::gl::enums::*;
use glstereo::image::Image;
use glstereo::math::{Eye, Frustum, StereoAdjust, hp_eye};
use glstereo::shims::nv3dvision::*;
use glstereo::surface::{self, Surface};

const W: u32 = 320;
const H: u32 = 240;
const GREY: [u8; 4] = [128, 128, 128, 255];
const GL_QUADS: u32 = 0x0007;
const GL_DEPTH_TEST: u32 = 0x0B71;
const GL_MODELVIEW_MATRIX: u32 = 0x0BA6;

/// The mono projection: glFrustum(−0.4, 0.4, −0.3, 0.3, 1, 100).
const MONO: Frustum = Frustum {
    left: -0.4,
    right: 0.4,
    bottom: -0.3,
    top: 0.3,
    near: 1.0,
    far: 100.0,
};

/// A card: a rectangle given by its NDC extent in the mono view, at a depth.
#[derive(Clone, Copy, Debug)]
struct Card {
    color: [u8; 3],
    depth: f64,
    ndc: (f64, f64, f64, f64),
}

const RED: Card = Card {
    color: [230, 20, 20],
    depth: 4.0,
    ndc: (-0.5, 0.4, 0.3, 0.8),
};
const GREEN: Card = Card {
    color: [20, 200, 20],
    depth: 8.0,
    ndc: (-0.4, -0.2, 0.4, 0.2),
};
const BLUE: Card = Card {
    color: [20, 20, 230],
    depth: 16.0,
    ndc: (-0.3, -0.8, 0.5, -0.4),
};
const CARDS: [Card; 3] = [RED, GREEN, BLUE];

type Fn0 = unsafe extern "system" fn();
type FnEnum = unsafe extern "system" fn(u32);
type Fn3d = unsafe extern "system" fn(f64, f64, f64);
type Fn3ub = unsafe extern "system" fn(u8, u8, u8);
type Fn6d = unsafe extern "system" fn(f64, f64, f64, f64, f64, f64);
type FnGen = unsafe extern "system" fn(i32, *mut u32);

/// The fixed-function entry points the test scene needs (not in the
/// library's table), loaded from the surface's backend.
struct Fixed {
    begin: FnEnum,
    end: Fn0,
    vertex3d: Fn3d,
    color3ub: Fn3ub,
    load_identity: Fn0,
    frustum: Fn6d,
    ortho: Fn6d,
    gen_framebuffers: FnGen,
}

fn fixed(s: &Surface) -> Fixed {
    let get = |name: &CStr| {
        let p = s.get_proc_address(name);
        assert!(!p.is_null(), "{name:?} not found");
        p
    };
    // SAFETY: each address is the named GL function of the current backend,
    // transmuted to its Khronos signature.
    unsafe {
        Fixed {
            begin: std::mem::transmute::<*const c_void, FnEnum>(get(c"glBegin")),
            end: std::mem::transmute::<*const c_void, Fn0>(get(c"glEnd")),
            vertex3d: std::mem::transmute::<*const c_void, Fn3d>(get(c"glVertex3d")),
            color3ub: std::mem::transmute::<*const c_void, Fn3ub>(get(c"glColor3ub")),
            load_identity: std::mem::transmute::<*const c_void, Fn0>(get(c"glLoadIdentity")),
            frustum: std::mem::transmute::<*const c_void, Fn6d>(get(c"glFrustum")),
            ortho: std::mem::transmute::<*const c_void, Fn6d>(get(c"glOrtho")),
            gen_framebuffers: std::mem::transmute::<*const c_void, FnGen>(get(
                c"glGenFramebuffers",
            )),
        }
    }
}

fn display() -> Arc<Display> {
    Display::open(BackendChoice::Only(BackendKind::Egl)).expect("EGL display")
}

/// A double-buffered mono configuration with depth, made auto-stereo
/// capable or not, current on this thread.
fn make(auto_stereo: bool) -> (Arc<Surface>, Fixed) {
    let d = display();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 24])
        .unwrap();
    let s = create_surface(&d, &c, W, H, SurfaceAttribs { auto_stereo }).unwrap();
    surface::make_current(Some(&s)).unwrap();
    let fx = fixed(&s);
    (s, fx)
}

/// A quad-buffer stereo surface (the HP path), current on this thread.
fn make_quad_buffer() -> (Arc<Surface>, Fixed) {
    let d = display();
    let c = d
        .choose_config(&[GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 24, GLX_STEREO])
        .unwrap();
    let s = d.create_surface(&c, W, H).unwrap();
    surface::make_current(Some(&s)).unwrap();
    let fx = fixed(&s);
    (s, fx)
}

fn set_perspective(s: &Surface, fx: &Fixed) {
    // SAFETY: the surface is current on this thread.
    unsafe {
        s.gl().MatrixMode(GL_PROJECTION);
        (fx.load_identity)();
        (fx.frustum)(
            MONO.left,
            MONO.right,
            MONO.bottom,
            MONO.top,
            MONO.near,
            MONO.far,
        );
        s.gl().MatrixMode(GL_MODELVIEW);
    }
}

/// The mono frame: clear to grey, draw the cards with depth testing.
/// `eye_point(ndc_x, ndc_y, depth)` gives the eye-space vertex.
fn draw_cards(
    s: &Surface,
    fx: &Fixed,
    cards: &[Card],
    eye_point: &dyn Fn(f64, f64, f64) -> [f64; 3],
) {
    // SAFETY: the surface is current on this thread.
    unsafe {
        let gl = s.gl();
        gl.ClearColor(0.5, 0.5, 0.5, 1.0);
        gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl.Enable(GL_DEPTH_TEST);
        gl.MatrixMode(GL_MODELVIEW);
        (fx.load_identity)();
        for c in cards {
            (fx.color3ub)(c.color[0], c.color[1], c.color[2]);
            (fx.begin)(GL_QUADS);
            let (x0, y0, x1, y1) = c.ndc;
            for (x, y) in [(x0, y0), (x1, y0), (x1, y1), (x0, y1)] {
                let [ex, ey, ez] = eye_point(x, y, c.depth);
                (fx.vertex3d)(ex, ey, ez);
            }
            (fx.end)();
        }
    }
}

/// Eye-space point of the mono view's NDC (x, y) at distance `depth`.
fn perspective_point(x: f64, y: f64, depth: f64) -> [f64; 3] {
    [
        x * MONO.right * depth / MONO.near,
        y * MONO.top * depth / MONO.near,
        -depth,
    ]
}

fn scene(s: &Surface, fx: &Fixed) {
    draw_cards(s, fx, &CARDS, &perspective_point);
}

fn nv_f(pname: u32, v: f32) {
    assert_eq!(
        gls_stereo_parameterf_nv(pname, v),
        GLS_OK,
        "{pname:#x} = {v}"
    );
}

fn back(s: &Arc<Surface>, eye: Eye) -> Image {
    s.read_pixels(match eye {
        Eye::Left => GL_BACK_LEFT,
        Eye::Right => GL_BACK_RIGHT,
    })
    .unwrap()
}

/// Renders the scene through automatic stereo and returns the two eyes.
fn auto_eyes(s: &Arc<Surface>, fx: &Fixed) -> (Image, Image) {
    set_perspective(s, fx);
    render_frame(s, &mut || scene(s, fx)).unwrap();
    (back(s, Eye::Left), back(s, Eye::Right))
}

/// Window row (top first) of NDC y, and the first column of a card's colour on it.
fn row_of(ndc_y: f64) -> u32 {
    ((1.0 - ndc_y) / 2.0 * H as f64) as u32
}

fn left_edge(img: &Image, card: &Card) -> f64 {
    let y = row_of((card.ndc.1 + card.ndc.3) / 2.0);
    let want = [card.color[0], card.color[1], card.color[2], 255];
    (0..W)
        .find(|&x| img.get(x, y) == want)
        .unwrap_or_else(|| panic!("no {:?} pixel on row {y}", card.color)) as f64
}

/// The measured parallax of a card in pixels (right-eye edge − left-eye edge).
fn parallax_px(l: &Image, r: &Image, card: &Card) -> f64 {
    left_edge(r, card) - left_edge(l, card)
}

/// Largest channel difference between two images.
fn max_diff(a: &Image, b: &Image) -> u8 {
    a.max_difference(b).map_or(0, |d| d.0)
}

fn get_f(pname: u32) -> f32 {
    let mut v = f32::NAN;
    // SAFETY: one float written.
    assert_eq!(unsafe { gls_get_floatv(pname, &mut v) }, GLS_OK);
    v
}

fn get_i(pname: u32) -> i32 {
    let mut v = i32::MIN;
    // SAFETY: one int written.
    assert_eq!(unsafe { gls_get_integerv(pname, &mut v) }, GLS_OK);
    v
}

fn get_b(pname: u32) -> u8 {
    let mut v = 7u8;
    // SAFETY: one boolean written.
    assert_eq!(unsafe { gls_get_booleanv(pname, &mut v) }, GLS_OK);
    v
}

#[test]
fn initial_values_through_every_getter() {
    for capable in [true, false] {
        let (s, _) = make(capable);
        assert_eq!(gls_is_enabled(GL_3DVISION_STEREO_NV), capable as u8);
        assert_eq!(get_b(GL_3DVISION_STEREO_NV), capable as u8);
        assert_eq!(get_i(GL_3DVISION_STEREO_NV), capable as i32);
        assert_eq!(get_f(GL_3DVISION_STEREO_NV), capable as u8 as f32);
        assert_eq!(get_f(GL_STEREO_SEPARATION_NV), 15.0);
        assert_eq!(get_i(GL_STEREO_SEPARATION_NV), 15);
        assert_eq!(get_b(GL_STEREO_SEPARATION_NV), 1);
        for p in [GL_STEREO_CONVERGENCE_NV, GL_STEREO_CUTOFF_NV] {
            assert_eq!((get_f(p), get_i(p), get_b(p)), (0.0, 0, 0), "{p:#x}");
        }
        assert_eq!(get_i(GL_STEREO_PROJECTION_NV), 0x90F9);
        assert_eq!(get_f(GL_STEREO_PROJECTION_NV), 0x90F9 as f32);
        assert_eq!(get_b(GL_STEREO_PROJECTION_NV), 1);
        assert_eq!(s.nv3dvision().capable(), capable);
        // The emulated framebuffer's values come through the new getters too.
        assert_eq!(
            get_b(GL_STEREO),
            capable as u8,
            "two eyes only when capable"
        );
        assert_eq!(get_f(GL_DRAW_BUFFER), GL_BACK as f32);
        // GL's own state still reaches GL.
        assert_eq!(get_b(GL_DEPTH_TEST), 0);
        assert_eq!(gls_enable(GL_DEPTH_TEST), GLS_OK);
        assert_eq!(gls_is_enabled(GL_DEPTH_TEST), 1);
        assert_eq!(gls_disable(GL_DEPTH_TEST), GLS_OK);
        assert_eq!(gls_get_error(), GL_NO_ERROR);
        surface::make_current(None).unwrap();
    }
}

#[test]
fn enable_and_disable_work_only_on_a_capable_surface() {
    let (_s, _) = make(false);
    assert_eq!(gls_enable(GL_3DVISION_STEREO_NV), GLS_OK);
    assert_eq!(gls_is_enabled(GL_3DVISION_STEREO_NV), 0, "no effect");
    assert_eq!(gls_get_error(), GL_NO_ERROR, "and no error");
    surface::make_current(None).unwrap();
    let (_s, _) = make(true);
    assert_eq!(gls_disable(GL_3DVISION_STEREO_NV), GLS_OK);
    assert_eq!(gls_is_enabled(GL_3DVISION_STEREO_NV), 0);
    assert_eq!(gls_enable(GL_3DVISION_STEREO_NV), GLS_OK);
    assert_eq!(gls_is_enabled(GL_3DVISION_STEREO_NV), 1);
    assert_eq!(gls_get_error(), GL_NO_ERROR);
}

/// Every error the extension specifies, through the C entry points: the
/// gls_result, the GL error gls_get_error() reports once, and no change.
#[test]
fn every_error_case_has_its_gl_error_and_result_code() {
    let (_s, _) = make(true);
    nv_f(GL_STEREO_SEPARATION_NV, 40.0);
    nv_f(GL_STEREO_CONVERGENCE_NV, 6.0);
    nv_f(GL_STEREO_CUTOFF_NV, 1.0);
    let state = || {
        (
            get_f(GL_STEREO_SEPARATION_NV),
            get_f(GL_STEREO_CONVERGENCE_NV),
            get_f(GL_STEREO_CUTOFF_NV),
            get_i(GL_STEREO_PROJECTION_NV),
        )
    };
    let before = state();
    type Call = Box<dyn Fn() -> gls_result>;
    let f = |p: u32, v: f32| -> Call { Box::new(move || gls_stereo_parameterf_nv(p, v)) };
    let i = |p: u32, v: i32| -> Call { Box::new(move || gls_stereo_parameteri_nv(p, v)) };
    let enum_ = (GLS_ERROR_INVALID_ENUM, GL_INVALID_ENUM);
    let value = (GLS_ERROR_INVALID_VALUE, GL_INVALID_VALUE);
    let cases: Vec<(&str, Call, (gls_result, u32))> = vec![
        ("unknown pname (f)", f(0x1234, 1.0), enum_),
        ("unknown pname (i)", i(0x1234, 1), enum_),
        (
            "the capability as a pname",
            f(GL_3DVISION_STEREO_NV, 1.0),
            enum_,
        ),
        (
            "a method token as a pname",
            i(GL_STEREO_PROJECTION_ORTHO_NV, 0),
            enum_,
        ),
        (
            "unknown projection (i)",
            i(GL_STEREO_PROJECTION_NV, 0x90FB),
            enum_,
        ),
        ("projection 0", i(GL_STEREO_PROJECTION_NV, 0), enum_),
        (
            "unknown projection (f)",
            f(GL_STEREO_PROJECTION_NV, 1.5),
            enum_,
        ),
        (
            "separation below 0 (f)",
            f(GL_STEREO_SEPARATION_NV, -0.5),
            value,
        ),
        (
            "separation above 100 (f)",
            f(GL_STEREO_SEPARATION_NV, 100.5),
            value,
        ),
        (
            "separation below 0 (i)",
            i(GL_STEREO_SEPARATION_NV, -1),
            value,
        ),
        (
            "separation above 100 (i)",
            i(GL_STEREO_SEPARATION_NV, 101),
            value,
        ),
        (
            "separation NaN",
            f(GL_STEREO_SEPARATION_NV, f32::NAN),
            value,
        ),
        (
            "convergence infinite",
            f(GL_STEREO_CONVERGENCE_NV, f32::INFINITY),
            value,
        ),
        ("cutoff NaN", f(GL_STEREO_CUTOFF_NV, f32::NAN), value),
    ];
    for (what, call, (code, gl_error)) in cases {
        assert_eq!(call(), code, "{what}: gls_result");
        assert_eq!(gls_get_error(), gl_error, "{what}: GL error");
        assert_eq!(gls_get_error(), GL_NO_ERROR, "{what}: reported once");
        assert_eq!(state(), before, "{what}: the state changed");
    }
    // GL keeps the first error until it is read.
    assert_eq!(
        gls_stereo_parameterf_nv(GL_STEREO_SEPARATION_NV, 500.0),
        GLS_ERROR_INVALID_VALUE
    );
    assert_eq!(
        gls_stereo_parameterf_nv(0x1234, 0.0),
        GLS_ERROR_INVALID_ENUM
    );
    assert_eq!(gls_get_error(), GL_INVALID_VALUE);
    // Valid edges of the range.
    assert_eq!(gls_stereo_parameteri_nv(GL_STEREO_SEPARATION_NV, 0), GLS_OK);
    assert_eq!(
        gls_stereo_parameterf_nv(GL_STEREO_SEPARATION_NV, 100.0),
        GLS_OK
    );
    assert_eq!(
        gls_stereo_parameterf_nv(
            GL_STEREO_PROJECTION_NV,
            GL_STEREO_PROJECTION_ORTHO_NV as f32
        ),
        GLS_OK
    );
    assert_eq!(
        get_i(GL_STEREO_PROJECTION_NV),
        GL_STEREO_PROJECTION_ORTHO_NV as i32
    );
    assert_eq!(gls_get_error(), GL_NO_ERROR);
    // Pointers and the current surface.
    // SAFETY: NULL is what is being tested; nothing is written.
    unsafe {
        assert_eq!(
            gls_get_floatv(GL_STEREO_CUTOFF_NV, std::ptr::null_mut()),
            GLS_ERROR_NULL_POINTER
        );
        assert_eq!(
            gls_get_booleanv(GL_STEREO_CUTOFF_NV, std::ptr::null_mut()),
            GLS_ERROR_NULL_POINTER
        );
        assert_eq!(
            gls_auto_stereo_frame(None, std::ptr::null_mut()),
            GLS_ERROR_NULL_POINTER
        );
    }
    surface::make_current(None).unwrap();
    assert_eq!(
        gls_stereo_parameterf_nv(GL_STEREO_SEPARATION_NV, 1.0),
        GLS_ERROR_NO_CURRENT_SURFACE
    );
    assert_eq!(
        gls_stereo_parameteri_nv(GL_STEREO_SEPARATION_NV, 1),
        GLS_ERROR_NO_CURRENT_SURFACE
    );
    assert_eq!(
        gls_enable(GL_3DVISION_STEREO_NV),
        GLS_ERROR_NO_CURRENT_SURFACE
    );
    assert_eq!(gls_is_enabled(GL_3DVISION_STEREO_NV), 0);
}

/// The clip-space form equals HP's asymmetric frustum for matched
/// parameters: the projection GL holds while each eye is drawn, and the
/// pixels of each eye against the same scene drawn by a quad-buffer program
/// with HP's projections.
#[test]
fn clip_space_form_equals_the_hp_frustum_in_matrices_and_pixels() {
    let (separation, convergence) = (60.0f32, 8.0f32);
    let adjust = StereoAdjust {
        offset_adjustment: separation as f64 / 100.0,
        ..StereoAdjust::new(convergence as f64)
    };

    // The quad-buffer program, HP's way.
    let (q, qfx) = make_quad_buffer();
    let mut hp_images = Vec::new();
    for eye in Eye::BOTH {
        let hp = hp_eye(&MONO, &adjust, eye).unwrap().matrix();
        q.load_projection(&hp.to_cols_array()).unwrap();
        q.draw_buffer(match eye {
            Eye::Left => GL_BACK_LEFT,
            Eye::Right => GL_BACK_RIGHT,
        })
        .unwrap();
        scene(&q, &qfx);
        hp_images.push(back(&q, eye));
    }
    surface::make_current(None).unwrap();

    // The mono program through automatic stereo.
    let (s, fx) = make(true);
    nv_f(GL_STEREO_SEPARATION_NV, separation);
    nv_f(GL_STEREO_CONVERGENCE_NV, convergence);
    set_perspective(&s, &fx);
    let mut seen = Vec::new();
    render_frame(&s, &mut || {
        let mut m = [0.0f64; 16];
        // SAFETY: the surface is current; a matrix is 16 values.
        unsafe { s.gl().GetDoublev(GL_PROJECTION_MATRIX, m.as_mut_ptr()) };
        seen.push(m);
        scene(&s, &fx);
    })
    .unwrap();
    assert_eq!(seen.len(), 2, "one call per eye");
    for (eye, m) in Eye::BOTH.iter().zip(&seen) {
        let hp = hp_eye(&MONO, &adjust, *eye)
            .unwrap()
            .matrix()
            .to_cols_array();
        for k in 0..16 {
            assert!(
                (m[k] - hp[k]).abs() <= 1e-6 * hp[k].abs().max(1.0),
                "{eye:?} element {k}: GL holds {} , HP's matrix is {}",
                m[k],
                hp[k]
            );
        }
    }
    let nv_images = [back(&s, Eye::Left), back(&s, Eye::Right)];
    for (k, eye) in Eye::BOTH.iter().enumerate() {
        let d = max_diff(&nv_images[k], &hp_images[k]);
        assert!(d <= 1, "{eye:?}: NV and HP renders differ by {d}");
    }
    assert!(
        max_diff(&nv_images[0], &nv_images[1]) > 100,
        "the eyes must differ"
    );
}

#[test]
fn separation_zero_gives_identical_eyes_equal_to_mono() {
    let (m, mfx) = make(false);
    set_perspective(&m, &mfx);
    scene(&m, &mfx);
    let mono = m.read_pixels(GL_BACK).unwrap();
    surface::make_current(None).unwrap();

    let (s, fx) = make(true);
    nv_f(GL_STEREO_SEPARATION_NV, 0.0);
    nv_f(GL_STEREO_CONVERGENCE_NV, 8.0);
    let (l, r) = auto_eyes(&s, &fx);
    assert_eq!(l, r, "separation 0: the eyes are identical");
    assert_eq!(l, mono, "and equal to the mono render");
}

/// Convergence at a card's depth puts it at the screen (zero parallax);
/// nearer cards get negative parallax, farther ones positive, as
/// s·(1 − C/w)·width predicts, within a pixel.
#[test]
fn convergence_at_an_objects_depth_gives_it_zero_parallax() {
    let (s, fx) = make(true);
    for (separation, card) in [(80.0, GREEN), (50.0, RED), (100.0, BLUE)] {
        nv_f(GL_STEREO_SEPARATION_NV, separation);
        nv_f(GL_STEREO_CONVERGENCE_NV, card.depth as f32);
        let (l, r) = auto_eyes(&s, &fx);
        let settings = s.nv3dvision();
        for c in CARDS {
            let measured = parallax_px(&l, &r, &c);
            let predicted = settings.parallax_fraction(c.depth) * W as f64;
            assert!(
                (measured - predicted).abs() <= 1.0,
                "convergence {}: card at {} moved {measured} px, predicted {predicted:.2}",
                card.depth,
                c.depth
            );
            if c.depth == card.depth {
                assert_eq!(measured, 0.0, "the card at the convergence depth");
            } else {
                assert_eq!(
                    measured > 0.0,
                    c.depth > card.depth,
                    "sign at depth {}: {measured}",
                    c.depth
                );
            }
        }
    }
}

/// Cutoff: with convergence at the far card (16) and separation 90 %, the
/// near card (4) would pop out by 3·s; with the cutoff at 4 it pops out by
/// exactly s (the far-away parallax) and the far card stays at zero.
#[test]
fn cutoff_limits_pop_out_to_the_far_parallax() {
    let (s, fx) = make(true);
    nv_f(GL_STEREO_SEPARATION_NV, 90.0);
    nv_f(GL_STEREO_CONVERGENCE_NV, 16.0);
    let sw = 0.9 * MAX_SEPARATION * W as f64;
    let (l, r) = auto_eyes(&s, &fx);
    let free = parallax_px(&l, &r, &RED);
    assert!(
        (free + 3.0 * sw).abs() <= 1.0,
        "no cutoff: {free} px, want {}",
        -3.0 * sw
    );
    nv_f(GL_STEREO_CUTOFF_NV, 4.0);
    let (l, r) = auto_eyes(&s, &fx);
    let cut = parallax_px(&l, &r, &RED);
    assert!((cut + sw).abs() <= 1.0, "cutoff 4: {cut} px, want {}", -sw);
    assert_eq!(parallax_px(&l, &r, &BLUE), 0.0, "convergence kept");
    assert_eq!(get_f(GL_STEREO_CUTOFF_NV), 4.0);
}

/// STEREO_PROJECTION_ORTHO_NV: under glOrtho, PERSPECTIVE shifts every depth
/// alike; ORTHO gives parallax s·(z_win − C).
#[test]
fn ortho_method_takes_depth_from_the_window_depth() {
    let (s, fx) = make(true);
    // glOrtho(−1, 1, −0.75, 0.75, 1, 17): the cards at distances 5, 9, 13
    // have window depths 0.25, 0.5, 0.75.
    let (n, f) = (1.0, 17.0);
    let cards = [
        Card { depth: 5.0, ..RED },
        Card {
            depth: 9.0,
            ..GREEN
        },
        Card {
            depth: 13.0,
            ..BLUE
        },
    ];
    let ortho_point = |x: f64, y: f64, d: f64| [x, y * 0.75, -d];
    let render = |s: &Arc<Surface>| {
        // SAFETY: the surface is current on this thread.
        unsafe {
            s.gl().MatrixMode(GL_PROJECTION);
            (fx.load_identity)();
            (fx.ortho)(-1.0, 1.0, -0.75, 0.75, n, f);
            s.gl().MatrixMode(GL_MODELVIEW);
        }
        render_frame(s, &mut || draw_cards(s, &fx, &cards, &ortho_point)).unwrap();
        (back(s, Eye::Left), back(s, Eye::Right))
    };
    nv_f(GL_STEREO_SEPARATION_NV, 100.0);
    nv_f(GL_STEREO_CONVERGENCE_NV, 0.5);
    let (l, r) = render(&s);
    let flat: Vec<f64> = cards.iter().map(|c| parallax_px(&l, &r, c)).collect();
    let want = 0.07 * 0.5 * W as f64;
    for p in &flat {
        assert!(
            (p - want).abs() <= 1.0,
            "PERSPECTIVE under glOrtho: {flat:?}, want all {want}"
        );
    }
    assert_eq!(
        gls_stereo_parameteri_nv(
            GL_STEREO_PROJECTION_NV,
            GL_STEREO_PROJECTION_ORTHO_NV as i32
        ),
        GLS_OK
    );
    let (l, r) = render(&s);
    for c in &cards {
        let z_win = (c.depth - n) / (f - n);
        let want = 0.07 * (z_win - 0.5) * W as f64;
        let got = parallax_px(&l, &r, c);
        assert!(
            (got - want).abs() <= 1.0,
            "ORTHO, window depth {z_win}: {got} px, want {want:.2}"
        );
    }
    assert_eq!(parallax_px(&l, &r, &cards[1]), 0.0);
}

/// A surface that is not auto-stereo capable renders exactly as mono: one
/// call, whatever the settings, nothing else touched.
#[test]
fn a_surface_that_is_not_capable_renders_mono_unchanged() {
    let (s, fx) = make(false);
    set_perspective(&s, &fx);
    scene(&s, &fx);
    let direct = s.read_pixels(GL_BACK).unwrap();
    assert_eq!(gls_enable(GL_3DVISION_STEREO_NV), GLS_OK);
    nv_f(GL_STEREO_SEPARATION_NV, 100.0);
    nv_f(GL_STEREO_CONVERGENCE_NV, 8.0);
    let calls = Cell::new(0);
    // SAFETY: the surface is current on this thread.
    let before = unsafe { s.gl().integer(GL_MATRIX_MODE) };
    render_frame(&s, &mut || {
        calls.set(calls.get() + 1);
        scene(&s, &fx);
    })
    .unwrap();
    assert_eq!(calls.get(), 1);
    assert_eq!(s.read_pixels(GL_BACK).unwrap(), direct);
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
        Some(GL_BACK as i32)
    );
    // SAFETY: as above.
    assert_eq!(unsafe { s.gl().integer(GL_MATRIX_MODE) }, before);
    assert_eq!(gls_get_error(), GL_NO_ERROR);
}

#[test]
fn with_3d_vision_disabled_a_capable_surface_shows_the_mono_frame_to_both_eyes() {
    let (s, fx) = make(true);
    nv_f(GL_STEREO_SEPARATION_NV, 100.0);
    nv_f(GL_STEREO_CONVERGENCE_NV, 8.0);
    assert_eq!(gls_disable(GL_3DVISION_STEREO_NV), GLS_OK);
    let calls = Cell::new(0);
    set_perspective(&s, &fx);
    render_frame(&s, &mut || {
        calls.set(calls.get() + 1);
        scene(&s, &fx);
    })
    .unwrap();
    assert_eq!(calls.get(), 1);
    let (l, r) = (back(&s, Eye::Left), back(&s, Eye::Right));
    assert_eq!(l, r);
    assert_eq!(l.get(2, 2), GREY);
}

/// After the frame the mono projection and the program's draw buffer are
/// back exactly; both eyes start from the same modelview.
#[test]
fn the_frame_restores_projection_and_draw_buffer_and_repeats_the_modelview() {
    let (s, fx) = make(true);
    nv_f(GL_STEREO_SEPARATION_NV, 50.0);
    nv_f(GL_STEREO_CONVERGENCE_NV, 8.0);
    set_perspective(&s, &fx);
    let read = |pname| {
        let mut m = [0.0f64; 16];
        // SAFETY: the surface is current; a matrix is 16 values.
        unsafe { s.gl().GetDoublev(pname, m.as_mut_ptr()) };
        m
    };
    let mono = read(GL_PROJECTION_MATRIX);
    let start_modelview = read(GL_MODELVIEW_MATRIX);
    let mut starts = Vec::new();
    let mut buffers = Vec::new();
    render_frame(&s, &mut || {
        starts.push(read(GL_MODELVIEW_MATRIX));
        buffers.push(s.emulated_integer(GL_DRAW_BUFFER).unwrap());
        // A callback that moves the modelview without restoring it.
        let translate = [
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 1.0,
        ];
        // SAFETY: as above; 16 values.
        unsafe { s.gl().MultMatrixd(translate.as_ptr()) };
    })
    .unwrap();
    assert_eq!(starts, vec![start_modelview, start_modelview]);
    assert_eq!(
        buffers,
        vec![Some(GL_BACK_LEFT as i32), Some(GL_BACK_RIGHT as i32)]
    );
    assert_eq!(
        read(GL_PROJECTION_MATRIX),
        mono,
        "mono projection restored exactly"
    );
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
        Some(GL_BACK as i32)
    );
    // Single-buffered programs draw into the front buffers of each eye.
    assert_eq!(s.draw_buffer(GL_FRONT), Ok(()));
    buffers.clear();
    render_frame(&s, &mut || {
        buffers.push(s.emulated_integer(GL_DRAW_BUFFER).unwrap())
    })
    .unwrap();
    assert_eq!(
        buffers,
        vec![Some(GL_FRONT_LEFT as i32), Some(GL_FRONT_RIGHT as i32)]
    );
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
        Some(GL_FRONT as i32)
    );
    assert_eq!(gls_get_error(), GL_NO_ERROR);
}

/// A callback that changes the projection (or the draw buffers) breaks the
/// eyes: reported, right eye not drawn, state restored.
#[test]
fn a_callback_that_breaks_the_contract_is_reported_and_state_restored() {
    let (s, fx) = make(true);
    set_perspective(&s, &fx);
    let mut mono = [0.0f64; 16];
    // SAFETY: the surface is current; 16 values.
    unsafe { s.gl().GetDoublev(GL_PROJECTION_MATRIX, mono.as_mut_ptr()) };
    let calls = Cell::new(0);
    let r = render_frame(&s, &mut || {
        calls.set(calls.get() + 1);
        // The usual mono habit: set the projection inside the frame.
        set_perspective(&s, &fx);
        scene(&s, &fx);
    });
    match r {
        Err(Error::InvalidOperation(m)) => {
            assert!(m.contains("projection") && m.contains("left eye"), "{m}")
        }
        other => panic!("changing the projection gave {other:?}"),
    }
    assert_eq!(calls.get(), 1, "the right eye is not drawn");
    let mut after = [0.0f64; 16];
    // SAFETY: as above.
    unsafe { s.gl().GetDoublev(GL_PROJECTION_MATRIX, after.as_mut_ptr()) };
    assert_eq!(after, mono);
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
        Some(GL_BACK as i32)
    );

    let r = render_frame(&s, &mut || {
        s.draw_buffer(GL_BACK).unwrap();
    });
    match r {
        Err(Error::InvalidOperation(m)) => assert!(m.contains("draw buffers"), "{m}"),
        other => panic!("changing the draw buffer gave {other:?}"),
    }
    assert_eq!(
        s.emulated_integer(GL_DRAW_BUFFER).unwrap(),
        Some(GL_BACK as i32)
    );

    // Nesting is refused; the outer frame goes on.
    let mut inner = None;
    render_frame(&s, &mut || {
        if inner.is_none() {
            inner = Some(render_frame(&s, &mut || {}));
        }
    })
    .unwrap();
    assert!(
        matches!(inner, Some(Err(Error::InvalidOperation(_)))),
        "{inner:?}"
    );

    // A program's own framebuffer bound for drawing.
    let mut fbo = 0;
    // SAFETY: the surface is current on this thread.
    unsafe { (fx.gen_framebuffers)(1, &mut fbo) };
    s.bind_framebuffer(GL_DRAW_FRAMEBUFFER, fbo).unwrap();
    let r = render_frame(&s, &mut || {});
    assert!(
        matches!(&r, Err(Error::InvalidOperation(m)) if m.contains("framebuffer 0")),
        "{r:?}"
    );
    s.bind_framebuffer(GL_DRAW_FRAMEBUFFER, 0).unwrap();
    assert_eq!(
        gls_get_error(),
        GL_NO_ERROR,
        "contract errors are not GL errors"
    );
}

/// "ReadPixels read from the left buffer only": the program's glReadPixels
/// and gls_surface_read_pixels of GL_BACK / GL_FRONT return the left eye.
#[test]
fn reading_pixels_of_an_auto_stereo_surface_reads_the_left_eye() {
    let (s, fx) = make(true);
    nv_f(GL_STEREO_SEPARATION_NV, 100.0);
    nv_f(GL_STEREO_CONVERGENCE_NV, 8.0);
    let (l, r) = auto_eyes(&s, &fx);
    assert_ne!(l, r);
    // The program's own glReadPixels with its initial read buffer (GL_BACK).
    assert_eq!(
        s.emulated_integer(GL_READ_BUFFER).unwrap(),
        Some(GL_BACK as i32)
    );
    let mut px = vec![0u8; (W * H * 4) as usize];
    // SAFETY: the surface is current; the buffer holds W×H RGBA8 pixels.
    unsafe {
        s.gl().PixelStorei(GL_PACK_ALIGNMENT, 1);
        s.gl().ReadPixels(
            0,
            0,
            W as i32,
            H as i32,
            GL_RGBA,
            GL_UNSIGNED_BYTE,
            px.as_mut_ptr().cast(),
        );
    }
    let mut program_read = Image::from_pixels(W, H, px).unwrap();
    program_read.flip_vertical();
    assert_eq!(program_read, l, "glReadPixels(GL_BACK) reads the left eye");
    assert_eq!(s.read_pixels(GL_BACK).unwrap(), l, "read_pixels(GL_BACK)");
    s.swap_buffers().unwrap();
    // GL_FRONT and GL_LEFT name the front-left buffer for reading.
    for name in [GL_FRONT, GL_LEFT] {
        assert_eq!(
            s.read_pixels(name).unwrap(),
            l,
            "after the swap, read_pixels({name:#x})"
        );
    }
    let (el, er) = s.eye_images().unwrap();
    assert_eq!((el, er), (l, r), "the viewer still gets both eyes");
}

/// The creation API through C: attribute lists, the capability query, and
/// their errors.
#[test]
fn auto_stereo_surfaces_through_the_c_api() {
    use glstereo::ffi::display::*;
    use glstereo::ffi::surface::{gls_make_current, gls_surface_destroy};
    let mut d = std::ptr::null_mut();
    let mut c = std::ptr::null_mut();
    // SAFETY: valid out-pointers and terminated lists throughout.
    unsafe {
        assert_eq!(gls_display_open(GLS_BACKEND_EGL, &mut d), GLS_OK);
        let mono = [GLX_RGBA, GLX_DOUBLEBUFFER, 0];
        assert_eq!(gls_config_choose(d, mono.as_ptr(), &mut c), GLS_OK);
        let mut s = std::ptr::null_mut();
        let mut v = -1;
        for (attribs, want) in [
            (None, 0),
            (Some(vec![GLS_SURFACE_ATTRIB_NONE]), 0),
            (
                Some(vec![GLS_SURFACE_AUTO_STEREO, 1, GLS_SURFACE_ATTRIB_NONE]),
                1,
            ),
            (
                Some(vec![GLS_SURFACE_AUTO_STEREO, 0, GLS_SURFACE_ATTRIB_NONE]),
                0,
            ),
        ] {
            let p = attribs.as_ref().map_or(std::ptr::null(), |a| a.as_ptr());
            assert_eq!(
                gls_surface_create_with_attribs(d, c, 32, 16, p, &mut s),
                GLS_OK,
                "{attribs:?}"
            );
            assert_eq!(
                gls_surface_get_attrib(s, GLS_SURFACE_AUTO_STEREO, &mut v),
                GLS_OK
            );
            assert_eq!(v, want, "{attribs:?}");
            assert_eq!(gls_make_current(s), GLS_OK);
            let mut stereo = 9;
            assert_eq!(gls_get_integerv(GL_STEREO, &mut stereo), GLS_OK);
            assert_eq!(stereo, want, "two eyes exactly when auto-stereo capable");
            assert_eq!(gls_is_enabled(GL_3DVISION_STEREO_NV), want as u8);
            gls_make_current(std::ptr::null_mut());
            gls_surface_destroy(s);
        }
        let bad_name = [0x3137, 1, GLS_SURFACE_ATTRIB_NONE];
        let bad_value = [GLS_SURFACE_AUTO_STEREO, 2, GLS_SURFACE_ATTRIB_NONE];
        s = std::ptr::null_mut();
        assert_eq!(
            gls_surface_create_with_attribs(d, c, 32, 16, bad_name.as_ptr(), &mut s),
            GLS_ERROR_INVALID_ENUM
        );
        assert_eq!(
            gls_surface_create_with_attribs(d, c, 32, 16, bad_value.as_ptr(), &mut s),
            GLS_ERROR_INVALID_VALUE
        );
        let unterminated = vec![GLS_SURFACE_AUTO_STEREO; 600];
        assert_eq!(
            gls_surface_create_with_attribs(d, c, 32, 16, unterminated.as_ptr(), &mut s),
            GLS_ERROR_INVALID_VALUE
        );
        assert!(s.is_null(), "nothing written on error");
        let ok = [GLS_SURFACE_AUTO_STEREO, 1, GLS_SURFACE_ATTRIB_NONE];
        assert_eq!(
            gls_surface_create_with_attribs(d, c, 32, 16, ok.as_ptr(), std::ptr::null_mut()),
            GLS_ERROR_NULL_POINTER
        );
        assert_eq!(
            gls_surface_create_with_attribs(d, c, 0, 16, ok.as_ptr(), &mut s),
            GLS_ERROR_INVALID_VALUE
        );
        assert_eq!(
            gls_surface_get_attrib(std::ptr::null(), GLS_SURFACE_AUTO_STEREO, &mut v),
            GLS_ERROR_NULL_POINTER
        );
        gls_config_free(c);
        gls_display_close(d);
    }
}

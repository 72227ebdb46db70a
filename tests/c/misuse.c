/* Misuse of every function in glstereo.h (tests/misuse.rs).
 *
 * Each case calls one export with something wrong — NULL for a pointer,
 * a value that is no enumerant, a number out of range, no current
 * surface, a handle that was never made or is already destroyed, a
 * surface of one display made current after one of another — and checks
 * the documented result code AND that the call left a message of its own
 * (gls_last_error_message() starts with "<function>: "), or, for a call
 * that must succeed, that it left the message alone. The process goes on
 * after every case.
 *
 * Every export exercised prints "covers <name>" once; the Rust test
 * compares that list with the functions the header declares, so a new
 * export without a misuse case fails the test.
 *
 * Links only libglstereo (plus pthread): EGL and OSMesa are loaded by the
 * library; GL is reached through gls_get_proc_address. With the argument
 * "glx" (and $DISPLAY set) it also checks GLX configurations across
 * displays. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "glstereo.h"
#include "check.h"

/* GLX attribute tokens. */
#define GLX_RGBA 4
#define GLX_DOUBLEBUFFER 5
#define GLX_STEREO 6
#define GLX_RED_SIZE 8
#define GLX_DEPTH_SIZE 12
/* GL tokens. */
#define GL_NONE 0u
#define GL_FRONT_LEFT 0x0400u
#define GL_FRONT_RIGHT 0x0401u
#define GL_BACK_LEFT 0x0402u
#define GL_BACK_RIGHT 0x0403u
#define GL_BACK 0x0405u
#define GL_INVALID_ENUM 0x0500u
#define GL_INVALID_VALUE 0x0501u
#define GL_INVALID_OPERATION 0x0502u
#define GL_DOUBLEBUFFER 0x0C32u
#define GL_STEREO 0x0C33u
#define GL_DEPTH_TEST 0x0B71u
#define GL_COLOR_BUFFER_BIT 0x00004000u
#define GL_DEPTH_BUFFER_BIT 0x00000100u
#define GL_DRAW_FRAMEBUFFER 0x8CA9u
#define GL_3DVISION_STEREO_NV 0x90F4u
#define GL_STEREO_SEPARATION_NV 0x90F5u
#define GL_STEREO_PROJECTION_NV 0x90F8u

/* ---- the harness ------------------------------------------------------ */

static const char *covered[256];
static int n_covered;

/* Records that `fn` was exercised (printed once, for tests/misuse.rs). */
static void cover(const char *fn) {
    for (int i = 0; i < n_covered; ++i)
        if (strcmp(covered[i], fn) == 0) return;
    if (n_covered < 256) covered[n_covered++] = fn;
    printf("covers %s\n", fn);
}

/* Leaves a known message, so a case can tell whether its call set one. */
static void sentinel(void) {
    uint32_t o = 0;
    (void)gls_output_from_name("misuse-sentinel", &o);
}

static int message_is_sentinel(void) {
    return strstr(gls_last_error_message(), "misuse-sentinel") != NULL;
}

/* True when the last message is `fn`'s own: "fn: <at least a few words>". */
static int message_from(const char *fn) {
    const char *m = gls_last_error_message();
    size_t n = strlen(fn);
    return strncmp(m, fn, n) == 0 && m[n] == ':' && strlen(m) > n + 8;
}

static int has(const char *needle) { return strstr(gls_last_error_message(), needle) != NULL; }

static void check_message(const char *fn, int reports, int line) {
    if (reports) {
        CHECK(message_from(fn), "line %d: %s left no message of its own: \"%s\"", line, fn,
              gls_last_error_message());
    } else {
        CHECK(message_is_sentinel(), "line %d: %s changed the message on success: \"%s\"", line, fn,
              gls_last_error_message());
    }
}

static void check_result(const char *fn, gls_result want, gls_result got, int line) {
    CHECK(got == want, "line %d: %s returned %s, wanted %s (message: %s)", line, fn,
          gls_result_string(got), gls_result_string(want), gls_last_error_message());
    if (got == want) check_message(fn, want != GLS_OK, line);
}

/* EXPECT(code, fn, args...): fn(args) returns code; a message of fn's own
 * when code is an error, none when it is GLS_OK. */
#define EXPECT(want, fn, ...)                               \
    do {                                                    \
        cover(#fn);                                         \
        sentinel();                                         \
        gls_result r_ = fn(__VA_ARGS__);                    \
        check_result(#fn, (want), r_, __LINE__);            \
    } while (0)

/* EXPECT_VOID(reports, fn, args...): a void call; reports = 1 when it
 * must leave a message (a handle that is not live), 0 when it must not. */
#define EXPECT_VOID(reports, fn, ...)                       \
    do {                                                    \
        cover(#fn);                                         \
        sentinel();                                         \
        fn(__VA_ARGS__);                                    \
        check_message(#fn, (reports), __LINE__);            \
    } while (0)

/* EXPECT_RET(cond, reports, var, fn, args...): var = fn(args); cond holds. */
#define EXPECT_RET(cond, reports, var, fn, ...)                                            \
    do {                                                                                   \
        cover(#fn);                                                                        \
        sentinel();                                                                        \
        var = fn(__VA_ARGS__);                                                             \
        CHECK(cond, "line %d: %s: %s (message: %s)", __LINE__, #fn, #cond,                 \
              gls_last_error_message());                                                   \
        check_message(#fn, (reports), __LINE__);                                           \
    } while (0)

/* The same for functions without arguments (C99 variadic macros need one). */
#define EXPECT0(want, fn)                                   \
    do {                                                    \
        cover(#fn);                                         \
        sentinel();                                         \
        gls_result r_ = fn();                               \
        check_result(#fn, (want), r_, __LINE__);            \
    } while (0)
#define EXPECT_RET0(cond, reports, var, fn)                                                \
    do {                                                                                   \
        cover(#fn);                                                                        \
        sentinel();                                                                        \
        var = fn();                                                                        \
        CHECK(cond, "line %d: %s: %s (message: %s)", __LINE__, #fn, #cond,                 \
              gls_last_error_message());                                                   \
        check_message(#fn, (reports), __LINE__);                                           \
    } while (0)

/* A GL function of the current surface (ISO C has no object-to-function
 * pointer cast; POSIX guarantees the representations agree). */
#define GL_PROC(type, var, name)                   \
    type var;                                      \
    do {                                           \
        void *p_ = gls_get_proc_address(name);     \
        memcpy(&var, &p_, sizeof var);             \
    } while (0)

typedef void (*clear_color_fn)(float, float, float, float);
typedef void (*clear_fn)(unsigned);
typedef void (*matrix_mode_fn)(unsigned);
typedef void (*load_identity_fn)(void);

/* Clears the current surface's selected buffers to one colour. */
static void clear_to(float r, float g, float b) {
    GL_PROC(clear_color_fn, clear_color, "glClearColor");
    GL_PROC(clear_fn, clear, "glClear");
    clear_color(r, g, b, 1.0f);
    clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

/* The centre pixel of one buffer of a surface, as 0xRRGGBB (-1 on error). */
static long centre(gls_surface *s, uint32_t buffer) {
    uint32_t w = 0, h = 0;
    if (gls_surface_get_size(s, &w, &h)) return -1;
    unsigned char *px = malloc((size_t)w * h * 4);
    if (!px) return -1;
    long v = -1;
    if (gls_surface_read_pixels(s, buffer, px, (size_t)w * h * 4) == GLS_OK) {
        const unsigned char *p = px + ((h / 2) * w + w / 2) * 4;
        v = (long)p[0] << 16 | (long)p[1] << 8 | p[2];
    }
    free(px);
    return v;
}

static const int STEREO_ATTRIBS[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_DEPTH_SIZE, 24, 0};
static const int MONO_ATTRIBS[] = {GLX_RGBA, GLX_DOUBLEBUFFER, 0};

static const gls_frustum GOOD_FRUSTUM = {-1.0, 1.0, -0.75, 0.75, 1.0, 100.0};
static const gls_stereo_adjust GOOD_ADJUST = {10.0, 1.0, 1.0};

/* A pointer that is no handle at all (never dereferenced by the library). */
static int not_a_handle;
#define BOGUS(type) ((type *)(void *)&not_a_handle)

/* ---- version, messages, panic ---------------------------------------- */

static void core_cases(void) {
    const char *v;
    EXPECT_RET0(v != NULL && strcmp(v, GLSTEREO_VERSION_STRING) == 0, 0, v, gls_version);
    EXPECT_RET0(v != NULL, 0, v, gls_last_error_message);
    EXPECT_RET(v != NULL && strncmp(v, "GLS_OK", 6) == 0, 0, v, gls_result_string, GLS_OK);
    EXPECT_RET(v != NULL && strstr(v, "GLS_ERROR_GL") != NULL, 0, v, gls_result_string, GLS_ERROR_GL);
    EXPECT_RET(v != NULL && strstr(v, "unknown") != NULL, 0, v, gls_result_string, 14u);
    EXPECT_RET(v != NULL && strstr(v, "unknown") != NULL, 0, v, gls_result_string, 0xFFFFFFFFu);
    EXPECT0(GLS_ERROR_PANIC, gls_debug_force_panic);
    CHECK(has("internal error") && has("forced"), "panic message: %s", gls_last_error_message());
    /* The library goes on after a caught panic. */
    EXPECT0(GLS_ERROR_PANIC, gls_debug_force_panic);
    uint32_t o = 99;
    EXPECT(GLS_OK, gls_output_from_name, "rows", &o);
    CHECK(o == GLS_OUTPUT_ROWS, "output after panic %u", o);
}

/* ---- pure functions: math, names, screen ------------------------------ */

static void math_cases(void) {
    gls_frustum f = {0}, bad = GOOD_FRUSTUM;
    gls_stereo_adjust badadj = GOOD_ADJUST;
    double off = 123.0, m[16] = {0}, xy[2] = {7, 7}, pct = 5.0, sep = 1, adjo = 1;
    const double point[3] = {8, -5, -3};

    EXPECT(GLS_OK, gls_stereo_eye, &GOOD_FRUSTUM, &GOOD_ADJUST, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_eye, NULL, &GOOD_ADJUST, GLS_EYE_LEFT, &f, &off);
    CHECK(has("mono"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_eye, &GOOD_FRUSTUM, NULL, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_eye, &GOOD_FRUSTUM, &GOOD_ADJUST, GLS_EYE_LEFT, NULL, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_eye, &GOOD_FRUSTUM, &GOOD_ADJUST, GLS_EYE_LEFT, &f, NULL);
    off = 123.0;
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_stereo_eye, &GOOD_FRUSTUM, &GOOD_ADJUST, 2u, &f, &off);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_stereo_eye, &GOOD_FRUSTUM, &GOOD_ADJUST, 0xFFFFFFFFu, &f, &off);
    CHECK(off == 123.0, "camera offset written on error: %g", off);
    bad.near_clip = 0.0;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye, &bad, &GOOD_ADJUST, GLS_EYE_LEFT, &f, &off);
    bad = GOOD_FRUSTUM;
    bad.far_clip = bad.near_clip;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye, &bad, &GOOD_ADJUST, GLS_EYE_LEFT, &f, &off);
    bad = GOOD_FRUSTUM;
    bad.left = bad.right;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye, &bad, &GOOD_ADJUST, GLS_EYE_LEFT, &f, &off);
    bad = GOOD_FRUSTUM;
    bad.top = NAN;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye, &bad, &GOOD_ADJUST, GLS_EYE_LEFT, &f, &off);
    bad = GOOD_FRUSTUM;
    bad.far_clip = INFINITY;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye, &bad, &GOOD_ADJUST, GLS_EYE_LEFT, &f, &off);
    badadj.zero_parallax_distance = 0.0;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye, &GOOD_FRUSTUM, &badadj, GLS_EYE_LEFT, &f, &off);
    badadj = GOOD_ADJUST;
    badadj.offset_adjustment = -1.0;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye, &GOOD_FRUSTUM, &badadj, GLS_EYE_RIGHT, &f, &off);
    badadj = GOOD_ADJUST;
    badadj.balance_adjustment = NAN;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye, &GOOD_FRUSTUM, &badadj, GLS_EYE_RIGHT, &f, &off);
    CHECK(off == 123.0, "camera offset written on error: %g", off);

    EXPECT(GLS_OK, gls_stereo_eye_matrix, &GOOD_FRUSTUM, &GOOD_ADJUST, GLS_EYE_RIGHT, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_eye_matrix, NULL, &GOOD_ADJUST, GLS_EYE_RIGHT, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_eye_matrix, &GOOD_FRUSTUM, NULL, GLS_EYE_RIGHT, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_eye_matrix, &GOOD_FRUSTUM, &GOOD_ADJUST, GLS_EYE_RIGHT, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_stereo_eye_matrix, &GOOD_FRUSTUM, &GOOD_ADJUST, 7u, m);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_eye_matrix, &bad, &GOOD_ADJUST, GLS_EYE_RIGHT, m);

    EXPECT(GLS_OK, gls_frustum_matrix, &GOOD_FRUSTUM, 0.5, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_frustum_matrix, NULL, 0.5, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_frustum_matrix, &GOOD_FRUSTUM, 0.5, NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_frustum_matrix, &GOOD_FRUSTUM, NAN, m);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_frustum_matrix, &GOOD_FRUSTUM, -INFINITY, m);
    bad = GOOD_FRUSTUM;
    bad.near_clip = -1.0;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_frustum_matrix, &bad, 0.5, m);

    double p;
    EXPECT_RET(p == 0.0, 0, p, gls_parallax, 1.0, 10.0, 10.0);
    EXPECT_RET(isnan(p), 1, p, gls_parallax, 1.0, 10.0, 0.0);
    EXPECT_RET(isnan(p), 1, p, gls_parallax, 1.0, 10.0, -1.0);
    EXPECT_RET(isnan(p), 1, p, gls_parallax, NAN, 10.0, 5.0);
    EXPECT_RET(isnan(p), 1, p, gls_parallax, 1.0, INFINITY, 5.0);

    EXPECT(GLS_OK, gls_project_point, 9.0, 1.0, point, GLS_EQUATION_LEFT_ZERO_PARALLAX, xy);
    CHECK(fabs(xy[0] - 5.875) < 1e-12 && fabs(xy[1] + 3.75) < 1e-12, "Eq 4: %g %g", xy[0], xy[1]);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_project_point, 9.0, 1.0, NULL, GLS_EQUATION_MONO, xy);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_project_point, 9.0, 1.0, point, GLS_EQUATION_MONO, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_project_point, 9.0, 1.0, point, 0u, xy);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_project_point, 9.0, 1.0, point, 6u, xy);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_project_point, 0.0, 1.0, point, GLS_EQUATION_MONO, xy);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_project_point, 9.0, -1.0, point, GLS_EQUATION_MONO, xy);
    /* A point on the camera plane (z = d) has no projection. */
    const double at_camera[3] = {1, 1, 9};
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_project_point, 9.0, 1.0, at_camera, GLS_EQUATION_MONO, xy);

    EXPECT(GLS_OK, gls_stereo_parallax_percent, &GOOD_FRUSTUM, &GOOD_ADJUST, 20.0, &pct);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_parallax_percent, NULL, &GOOD_ADJUST, 20.0, &pct);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_parallax_percent, &GOOD_FRUSTUM, NULL, 20.0, &pct);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_parallax_percent, &GOOD_FRUSTUM, &GOOD_ADJUST, 20.0, NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_parallax_percent, &GOOD_FRUSTUM, &GOOD_ADJUST, 0.0, &pct);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_parallax_percent, &GOOD_FRUSTUM, &GOOD_ADJUST, NAN, &pct);

    EXPECT(GLS_OK, gls_stereo_fit_budget, &GOOD_FRUSTUM, &GOOD_ADJUST, 5.0, 50.0, 3.0, &sep, &adjo);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_fit_budget, NULL, &GOOD_ADJUST, 5.0, 50.0, 3.0, &sep, &adjo);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_fit_budget, &GOOD_FRUSTUM, NULL, 5.0, 50.0, 3.0, &sep, &adjo);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_fit_budget, &GOOD_FRUSTUM, &GOOD_ADJUST, 5.0, 50.0, 3.0, NULL, &adjo);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_fit_budget, &GOOD_FRUSTUM, &GOOD_ADJUST, 5.0, 50.0, 3.0, &sep, NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_fit_budget, &GOOD_FRUSTUM, &GOOD_ADJUST, 50.0, 5.0, 3.0, &sep, &adjo);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_fit_budget, &GOOD_FRUSTUM, &GOOD_ADJUST, 5.0, 50.0, 0.0, &sep, &adjo);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_fit_budget, &GOOD_FRUSTUM, &GOOD_ADJUST, 10.0, 10.0, 3.0, &sep, &adjo);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_fit_budget, &GOOD_FRUSTUM, &GOOD_ADJUST, -1.0, 10.0, 3.0, &sep, &adjo);

    double a;
    EXPECT_RET(fabs(a - 1.1) < 1e-12, 0, a, gls_adjust_step, 1.0, 1);
    EXPECT_RET(a == 2.0, 0, a, gls_adjust_step, 1.9, 100);
    EXPECT_RET(a >= 0.0 && a < 1e-3, 0, a, gls_adjust_step, 1.0, -100);
    EXPECT_RET(isnan(a), 1, a, gls_adjust_step, NAN, 1);
    EXPECT_RET(isnan(a), 1, a, gls_adjust_step, INFINITY, 1);
    EXPECT_RET(a >= 0.0 && a <= 2.0, 0, a, gls_adjust_step, 1.0, 2147483647);
    EXPECT_RET(a >= 0.0 && a <= 2.0, 0, a, gls_adjust_step, 1.0, -2147483647 - 1);

    const double eye[3] = {0, 0, 10}, ctr[3] = {0, 0, 0}, up[3] = {0, 1, 0}, along[3] = {0, 0, 1};
    EXPECT(GLS_OK, gls_stereo_look_at, eye, ctr, up, 0.1, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_look_at, NULL, ctr, up, 0.1, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_look_at, eye, NULL, up, 0.1, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_look_at, eye, ctr, NULL, 0.1, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_look_at, eye, ctr, up, 0.1, NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_look_at, eye, ctr, along, 0.1, m);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_look_at, eye, eye, up, 0.1, m);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_look_at, eye, ctr, up, NAN, m);

    EXPECT(GLS_OK, gls_sgi_eye, 1.0, 1.25, 0.1, 1.0, 100.0, 10.0, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_sgi_eye, 1.0, 1.25, 0.1, 1.0, 100.0, 10.0, GLS_EYE_LEFT, NULL, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_sgi_eye, 1.0, 1.25, 0.1, 1.0, 100.0, 10.0, GLS_EYE_LEFT, &f, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_sgi_eye, 1.0, 1.25, 0.1, 1.0, 100.0, 10.0, 3u, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_sgi_eye, 0.0, 1.25, 0.1, 1.0, 100.0, 10.0, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_sgi_eye, 1.0, -1.0, 0.1, 1.0, 100.0, 10.0, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_sgi_eye, 1.0, 1.25, -0.1, 1.0, 100.0, 10.0, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_sgi_eye, 1.0, 1.25, 0.1, 1.0, 100.0, 0.0, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_sgi_eye, 1.0, 1.25, 0.1, 100.0, 1.0, 10.0, GLS_EYE_LEFT, &f, &off);

    EXPECT(GLS_OK, gls_bourke_eye, 50.0, 1.33, 0.1, 100.0, 0.04, 1.0, GLS_EYE_RIGHT, &f, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_bourke_eye, 50.0, 1.33, 0.1, 100.0, 0.04, 1.0, GLS_EYE_RIGHT, NULL, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_bourke_eye, 50.0, 1.33, 0.1, 100.0, 0.04, 1.0, GLS_EYE_RIGHT, &f, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_bourke_eye, 50.0, 1.33, 0.1, 100.0, 0.04, 1.0, 9u, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_bourke_eye, 0.0, 1.33, 0.1, 100.0, 0.04, 1.0, GLS_EYE_RIGHT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_bourke_eye, 180.0, 1.33, 0.1, 100.0, 0.04, 1.0, GLS_EYE_RIGHT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_bourke_eye, 50.0, 1.33, 0.1, 100.0, 0.04, 0.0, GLS_EYE_RIGHT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_bourke_eye, 50.0, NAN, 0.1, 100.0, 0.04, 1.0, GLS_EYE_RIGHT, &f, &off);

    EXPECT(GLS_OK, gls_stereo_camera_eye, 10.0, 0.33, 1.33, 50.0, 0.1, 100.0, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_camera_eye, 10.0, 0.33, 1.33, 50.0, 0.1, 100.0, GLS_EYE_LEFT, NULL, &off);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_camera_eye, 10.0, 0.33, 1.33, 50.0, 0.1, 100.0, GLS_EYE_LEFT, &f, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_stereo_camera_eye, 10.0, 0.33, 1.33, 50.0, 0.1, 100.0, 2u, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_camera_eye, 0.0, 0.33, 1.33, 50.0, 0.1, 100.0, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_camera_eye, 10.0, -0.33, 1.33, 50.0, 0.1, 100.0, GLS_EYE_LEFT, &f, &off);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_camera_eye, 10.0, 0.33, 1.33, -50.0, 0.1, 100.0, GLS_EYE_LEFT, &f, &off);

    double proj[16] = {0};
    proj[0] = 1.0, proj[5] = 1.0, proj[10] = -1.02, proj[11] = -1.0, proj[14] = -2.02;
    EXPECT(GLS_OK, gls_nv_stereo_matrix, proj, 0.05, 5.0, GLS_EYE_LEFT, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_nv_stereo_matrix, NULL, 0.05, 5.0, GLS_EYE_LEFT, m);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_nv_stereo_matrix, proj, 0.05, 5.0, GLS_EYE_LEFT, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_nv_stereo_matrix, proj, 0.05, 5.0, 2u, m);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_nv_stereo_matrix, proj, NAN, 5.0, GLS_EYE_LEFT, m);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_nv_stereo_matrix, proj, 0.05, INFINITY, GLS_EYE_LEFT, m);
    proj[5] = NAN;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_nv_stereo_matrix, proj, 0.05, 5.0, GLS_EYE_LEFT, m);
}

static void names_and_screen_cases(void) {
    uint32_t o = 77;
    EXPECT(GLS_OK, gls_output_from_name, " Side-By-Side ", &o);
    CHECK(o == GLS_OUTPUT_SIDE_BY_SIDE, "side-by-side is %u", o);
    o = 77;
    EXPECT(GLS_ERROR_NULL_POINTER, gls_output_from_name, NULL, &o);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_output_from_name, "rows", NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_output_from_name, "garbage", &o);
    CHECK(has("anaglyph-red-cyan"), "the message lists the names: %s", gls_last_error_message());
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_output_from_name, "", &o);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_output_from_name, "\xff\xfe", &o);
    CHECK(o == 77, "output written on error: %u", o);

    const char *n;
    EXPECT_RET(n != NULL && strcmp(n, "rows") == 0, 0, n, gls_output_name, GLS_OUTPUT_ROWS);
    EXPECT_RET(n == NULL, 1, n, gls_output_name, GLS_OUTPUT_COUNT);
    EXPECT_RET(n == NULL, 1, n, gls_output_name, 0xFFFFFFFFu);

    uint32_t w = 0, h = 0;
    EXPECT(GLS_OK, gls_screen_get_size, &w, &h);
    CHECK(w == 1280 && h == 1024, "screen %ux%u", w, h);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_screen_get_size, NULL, &h);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_screen_get_size, &w, NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_screen_set_size, 0, 1024);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_screen_set_size, 1280, 0);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_screen_set_size, 16385, 1024);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_screen_set_size, 100000, 100000);
    EXPECT(GLS_OK, gls_screen_get_size, &w, &h);
    CHECK(w == 1280 && h == 1024, "screen changed by failed calls: %ux%u", w, h);
    /* A small screen keeps the period shims' surfaces cheap below. */
    EXPECT(GLS_OK, gls_screen_set_size, 128, 128);
}

/* ---- displays and configurations ------------------------------------- */

static void display_cases(void) {
    gls_display *d = BOGUS(gls_display);
    uint32_t b = 99;
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_display_open, 4u, &d);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_display_open, 0xFFFFFFFFu, &d);
    CHECK(d == BOGUS(gls_display), "display_out written on error");
    EXPECT(GLS_ERROR_NULL_POINTER, gls_display_open, GLS_BACKEND_EGL, NULL);
    setenv("GLSTEREO_BACKEND", "garbage", 1);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_display_open, GLS_BACKEND_AUTO, &d);
    CHECK(has("GLSTEREO_BACKEND") && has("egl"), "%s", gls_last_error_message());
    setenv("GLSTEREO_BACKEND", "egl", 1);

    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_AUTO, &d);
    EXPECT(GLS_OK, gls_display_get_backend, d, &b);
    CHECK(b == GLS_BACKEND_EGL, "backend %u", b);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_display_get_backend, NULL, &b);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_display_get_backend, d, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_display_get_backend, BOGUS(gls_display), &b);

    gls_config *c = BOGUS(gls_config);
    const int unknown[] = {GLX_RGBA, 0x7777, 0};
    const int no_value[] = {GLX_RGBA, GLX_DEPTH_SIZE, 0};
    const int negative[] = {GLX_RGBA, GLX_RED_SIZE, -8, 0};
    const int too_deep[] = {GLX_RGBA, GLX_DEPTH_SIZE, 32, 0};
    const int colour_index[] = {GLX_DOUBLEBUFFER, 0};
    int endless[600];
    for (int i = 0; i < 600; ++i) endless[i] = GLX_RGBA;
    EXPECT(GLS_ERROR_NULL_POINTER, gls_config_choose, NULL, STEREO_ATTRIBS, &c);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_config_choose, d, NULL, &c);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_config_choose, d, STEREO_ATTRIBS, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_config_choose, BOGUS(gls_display), STEREO_ATTRIBS, &c);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_config_choose, d, unknown, &c);
    CHECK(has("0x7777"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_config_choose, d, no_value, &c);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_config_choose, d, negative, &c);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_config_choose, d, endless, &c);
    CHECK(has("terminator"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_NO_MATCHING_CONFIG, gls_config_choose, d, too_deep, &c);
    EXPECT(GLS_ERROR_NO_MATCHING_CONFIG, gls_config_choose, d, colour_index, &c);
    setenv("GLSTEREO_EMULATION", "garbage", 1);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_config_choose, d, STEREO_ATTRIBS, &c);
    setenv("GLSTEREO_EMULATION", "off", 1);
    EXPECT(GLS_ERROR_NO_MATCHING_CONFIG, gls_config_choose, d, STEREO_ATTRIBS, &c);
    unsetenv("GLSTEREO_EMULATION");
    CHECK(c == BOGUS(gls_config), "config_out written on error");

    EXPECT(GLS_OK, gls_config_choose, d, STEREO_ATTRIBS, &c);
    uint32_t st;
    EXPECT_RET(st == GLS_STEREO_EMULATED, 0, st, gls_config_stereo, c);
    EXPECT_RET(st == GLS_STEREO_NONE, 1, st, gls_config_stereo, NULL);
    EXPECT_RET(st == GLS_STEREO_NONE, 1, st, gls_config_stereo, BOGUS(gls_config));
    /* A live handle of another kind is not a configuration. */
    EXPECT_RET(st == GLS_STEREO_NONE, 1, st, gls_config_stereo, (gls_config *)(void *)d);

    int v = -5;
    EXPECT(GLS_OK, gls_config_get_attrib, c, GLX_STEREO, &v);
    CHECK(v == 1, "GLX_STEREO %d", v);
    v = -5;
    EXPECT(GLS_ERROR_NULL_POINTER, gls_config_get_attrib, NULL, GLX_STEREO, &v);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_config_get_attrib, c, GLX_STEREO, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_config_get_attrib, BOGUS(gls_config), GLX_STEREO, &v);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_config_get_attrib, c, 0x7777, &v);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_config_get_attrib, c, -1, &v);
    CHECK(v == -5, "value_out written on error: %d", v);

    /* Free, then use: detected. Double free and kind confusion: reported, harmless. */
    EXPECT_VOID(0, gls_config_free, NULL);
    EXPECT_VOID(1, gls_config_free, (gls_config *)(void *)d); /* a display is no config */
    EXPECT(GLS_OK, gls_display_get_backend, d, &b);         /* ... and still open */
    EXPECT_VOID(0, gls_config_free, c);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_config_get_attrib, c, GLX_STEREO, &v);
    EXPECT_RET(st == GLS_STEREO_NONE, 1, st, gls_config_stereo, c);
    EXPECT_VOID(1, gls_config_free, c);
    EXPECT_VOID(1, gls_config_free, BOGUS(gls_config));

    EXPECT_VOID(0, gls_display_close, NULL);
    EXPECT_VOID(1, gls_display_close, BOGUS(gls_display));
    EXPECT_VOID(0, gls_display_close, d);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_display_get_backend, d, &b);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_config_choose, d, STEREO_ATTRIBS, &c);
    EXPECT_VOID(1, gls_display_close, d);
}

/* ---- surfaces --------------------------------------------------------- */

/* The window calls on a live surface `s` of `backend`: events (none
 * headless, whatever the window had otherwise), close, title, native
 * handles; NULL, bogus and wrong-kind handles. */
static void window_cases(gls_surface *s, gls_config *not_a_surface, uint32_t backend) {
    gls_event ev;
    memset(&ev, 0xAB, sizeof ev);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_poll_event, NULL, &ev);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_poll_event, s, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_poll_event, BOGUS(gls_surface), &ev);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_poll_event, (gls_surface *)(void *)not_a_surface, &ev);
    CHECK(ev.kind == 0xABABABABu, "event written on error");
    for (int i = 0; i < 64; ++i) {
        EXPECT(GLS_OK, gls_surface_poll_event, s, &ev);
        if (ev.kind == GLS_EVENT_NONE) break;
        CHECK(ev.kind == GLS_EVENT_RESIZE || ev.kind == GLS_EVENT_KEY, "event kind %u", ev.kind);
        CHECK(backend == GLS_BACKEND_GLX, "an event (kind %u) on a headless surface", ev.kind);
    }
    CHECK(ev.kind == GLS_EVENT_NONE && ev.key == 0 && ev.width == 0 && ev.height == 0,
          "no event: %u %u %u %u", ev.kind, ev.key, ev.width, ev.height);

    bool b;
    EXPECT_RET(!b, 0, b, gls_surface_should_close, s);
    EXPECT_RET(!b, 1, b, gls_surface_should_close, NULL);
    EXPECT_RET(!b, 1, b, gls_surface_should_close, BOGUS(gls_surface));
    EXPECT_RET(!b, 1, b, gls_surface_should_close, (gls_surface *)(void *)not_a_surface);

    EXPECT(GLS_OK, gls_surface_set_title, s, "misuse: a title");
    EXPECT(GLS_OK, gls_surface_set_title, s, "");
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_set_title, s, NULL);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_set_title, NULL, "t");
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_title, BOGUS(gls_surface), "t");
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_title, s, "\xff\xfe");

    gls_native_handles h;
    memset(&h, 0xAB, sizeof h);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_native_handles, NULL, &h);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_native_handles, s, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_native_handles, BOGUS(gls_surface), &h);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_native_handles, (gls_surface *)(void *)not_a_surface, &h);
    CHECK(h.backend == 0xABABABABu, "handles written on error");
    EXPECT(GLS_OK, gls_surface_get_native_handles, s, &h);
    CHECK(h.backend == backend && h.context != NULL, "handles: backend %u, context %p", h.backend, h.context);
    if (backend == GLS_BACKEND_OSMESA) {
        CHECK(h.display == NULL && h.window == 0 && h.osmesa_buffer != NULL, "OSMesa handles");
    } else {
        CHECK(h.display != NULL && h.osmesa_buffer == NULL, "display handle");
        CHECK((h.window != 0) == (backend == GLS_BACKEND_GLX), "window %llu", (unsigned long long)h.window);
    }
}

/* The window calls on a destroyed surface. */
static void dead_window_cases(gls_surface *dead) {
    gls_event ev;
    gls_native_handles h;
    bool b;
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_poll_event, dead, &ev);
    EXPECT_RET(!b, 1, b, gls_surface_should_close, dead);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_title, dead, "t");
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_native_handles, dead, &h);
}

typedef struct {
    gls_surface *s;
    pthread_barrier_t *barrier;
    gls_result made, released;
} holder;

/* Makes a surface current on another thread and keeps it so between two
 * barrier waits. */
static void *hold_current(void *arg) {
    holder *h = arg;
    h->made = gls_make_current(h->s);
    pthread_barrier_wait(h->barrier);
    pthread_barrier_wait(h->barrier);
    h->released = gls_make_current(NULL);
    return NULL;
}

static int auto_draw_calls;
static void draw_nothing(void *user) {
    (void)user;
    ++auto_draw_calls;
}
static gls_result nested_result;
static void draw_nested(void *user) {
    (void)user;
    ++auto_draw_calls;
    nested_result = gls_auto_stereo_frame(draw_nothing, NULL);
}
static void draw_changes_buffer(void *user) {
    (void)user;
    ++auto_draw_calls;
    (void)gls_draw_buffer(GL_BACK_RIGHT);
}

static void no_current_cases(void) {
    int32_t iv = -3;
    float fv = -3.0f;
    uint8_t bv = 3;
    uint32_t bufs[2] = {GL_BACK_LEFT, GL_BACK_RIGHT};
    gls_parallax_report rep;
    double dist = -1.0;
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_draw_buffer, GL_BACK_LEFT);
    CHECK(has("gls_make_current"), "the message says what to do: %s", gls_last_error_message());
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_draw_buffers, 2, bufs);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_read_buffer, GL_BACK_LEFT);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_link_program, 1u);
    uint32_t e;
    EXPECT_RET0(e == 0, 1, e, gls_get_error);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_get_integerv, GL_STEREO, &iv);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_get_floatv, GL_STEREO_SEPARATION_NV, &fv);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_get_booleanv, GL_STEREO, &bv);
    CHECK(iv == -3 && fv == -3.0f && bv == 3, "outputs written without a surface");
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_bind_framebuffer, GL_DRAW_FRAMEBUFFER, 0);
    void *p;
    EXPECT_RET(p == NULL, 1, p, gls_get_proc_address, "glClear");
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_apply_stereo_eye, &GOOD_FRUSTUM, &GOOD_ADJUST, GLS_EYE_LEFT);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_stereo_parameterf_nv, GL_STEREO_SEPARATION_NV, 50.0f);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_stereo_parameteri_nv, GL_STEREO_SEPARATION_NV, 50);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_enable, GL_3DVISION_STEREO_NV);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_disable, GL_3DVISION_STEREO_NV);
    uint8_t en;
    EXPECT_RET(en == 0, 1, en, gls_is_enabled, GL_3DVISION_STEREO_NV);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_auto_stereo_frame, draw_nothing, NULL);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_stereo_measure_parallax, &GOOD_FRUSTUM, &GOOD_ADJUST, 3.0, &rep);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_stereo_auto_converge, &GOOD_FRUSTUM, &dist);
    CHECK(dist == -1.0, "distance written without a surface");
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_irisgl_viewport, 0, 10, 0, 10);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_irisgl_window, -1, 1, -1, 1, 1, 10);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_irisgl_translate, 1, 0, 0);
    /* Releasing with nothing current is fine. */
    EXPECT(GLS_OK, gls_make_current, NULL);
}

static void surface_cases(void) {
    gls_display *d;
    gls_config *c, *mono;
    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_EGL, &d);
    EXPECT(GLS_OK, gls_config_choose, d, STEREO_ATTRIBS, &c);
    EXPECT(GLS_OK, gls_config_choose, d, MONO_ATTRIBS, &mono);

    gls_surface *s = BOGUS(gls_surface);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_create, NULL, c, 64, 48, &s);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_create, d, NULL, 64, 48, &s);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_create, d, c, 64, 48, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_create, BOGUS(gls_display), c, 64, 48, &s);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_create, d, BOGUS(gls_config), 64, 48, &s);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_create, d, (gls_config *)(void *)d, 64, 48, &s);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create, d, c, 0, 0, &s);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create, d, c, 64, 0, &s);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create, d, c, 16385, 16, &s);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create, d, c, 100000, 100000, &s);
    CHECK(has("100000x100000"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create, d, c, 0xFFFFFFFFu, 0xFFFFFFFFu, &s);
    setenv("GLSTEREO_MODE", "garbage", 1);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create, d, c, 64, 48, &s);
    CHECK(has("GLSTEREO_MODE"), "%s", gls_last_error_message());
    unsetenv("GLSTEREO_MODE");
    CHECK(s == BOGUS(gls_surface), "surface_out written on error");

    const int auto_on[] = {GLS_SURFACE_AUTO_STEREO, 1, GLS_SURFACE_ATTRIB_NONE};
    const int unknown_attr[] = {0x7777, 1, GLS_SURFACE_ATTRIB_NONE};
    const int bad_value[] = {GLS_SURFACE_AUTO_STEREO, 2, GLS_SURFACE_ATTRIB_NONE};
    int endless[600];
    for (int i = 0; i < 600; i += 2) endless[i] = GLS_SURFACE_AUTO_STEREO, endless[i + 1] = 0;
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_create_with_attribs, NULL, c, 64, 48, auto_on, &s);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_create_with_attribs, d, NULL, 64, 48, auto_on, &s);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_create_with_attribs, d, c, 64, 48, auto_on, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_create_with_attribs, BOGUS(gls_display), c, 64, 48, auto_on, &s);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_create_with_attribs, d, c, 64, 48, unknown_attr, &s);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create_with_attribs, d, c, 64, 48, bad_value, &s);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create_with_attribs, d, c, 64, 48, endless, &s);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_create_with_attribs, d, c, 0, 48, auto_on, &s);
    CHECK(s == BOGUS(gls_surface), "surface_out written on error");

    gls_surface *autos;
    EXPECT(GLS_OK, gls_surface_create_with_attribs, d, mono, 64, 48, auto_on, &autos);
    EXPECT(GLS_OK, gls_surface_create_with_attribs, d, c, 64, 48, NULL, &s);
    gls_surface *nodepth;
    EXPECT(GLS_OK, gls_surface_create, d, mono, 32, 32, &nodepth);

    int32_t av = -1;
    EXPECT(GLS_OK, gls_surface_get_attrib, autos, GLS_SURFACE_AUTO_STEREO, &av);
    CHECK(av == 1, "auto stereo %d", av);
    av = -1;
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_attrib, NULL, GLS_SURFACE_AUTO_STEREO, &av);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_attrib, s, GLS_SURFACE_AUTO_STEREO, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_attrib, BOGUS(gls_surface), GLS_SURFACE_AUTO_STEREO, &av);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_get_attrib, s, 0x7777, &av);
    CHECK(av == -1, "value_out written on error");

    uint32_t w = 0, h = 0;
    EXPECT(GLS_OK, gls_surface_get_size, s, &w, &h);
    CHECK(w == 64 && h == 48, "size %ux%u", w, h);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_size, NULL, &w, &h);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_size, s, NULL, &h);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_size, s, &w, NULL);
    window_cases(s, c, GLS_BACKEND_EGL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_size, BOGUS(gls_surface), &w, &h);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_size, (gls_surface *)(void *)c, &w, &h);

    /* Output settings (any thread, no current surface needed). */
    uint32_t out = 99;
    EXPECT(GLS_OK, gls_surface_set_output, s, GLS_OUTPUT_ROWS);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_set_output, NULL, GLS_OUTPUT_ROWS);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_output, BOGUS(gls_surface), GLS_OUTPUT_ROWS);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_set_output, s, GLS_OUTPUT_COUNT);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_set_output, s, 0xFFFFFFFFu);
    EXPECT(GLS_OK, gls_surface_get_output, s, &out);
    CHECK(out == GLS_OUTPUT_ROWS, "output %u after failed sets", out);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_output, NULL, &out);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_get_output, s, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_output, BOGUS(gls_surface), &out);
    EXPECT(GLS_OK, gls_surface_set_swap_eyes, s, true);
    EXPECT(GLS_OK, gls_surface_set_swap_eyes, s, false);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_set_swap_eyes, NULL, true);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_swap_eyes, BOGUS(gls_surface), true);
    EXPECT(GLS_OK, gls_surface_set_crosstalk, s, 0.25f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_crosstalk, s, -0.01f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_crosstalk, s, 1.01f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_crosstalk, s, NAN);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_crosstalk, s, INFINITY);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_set_crosstalk, NULL, 0.5f);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_crosstalk, BOGUS(gls_surface), 0.5f);
    EXPECT(GLS_OK, gls_surface_set_saturation, s, 0.5f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_saturation, s, -1.0f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_saturation, s, 2.0f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_saturation, s, NAN);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_set_saturation, NULL, 0.5f);
    EXPECT(GLS_OK, gls_surface_set_input, s, GLS_INPUT_SIDE_BY_SIDE);
    EXPECT(GLS_OK, gls_surface_set_input, s, GLS_INPUT_QUAD_BUFFER);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_set_input, s, 6u);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_set_input, s, 0xFFFFFFFFu);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_set_input, NULL, GLS_INPUT_STR_RECT);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_input, BOGUS(gls_surface), GLS_INPUT_STR_RECT);
    gls_surface *tiny;
    EXPECT(GLS_OK, gls_surface_create, d, mono, 1, 1, &tiny);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_input, tiny, GLS_INPUT_SYNC_DOUBLED);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_input, tiny, GLS_INPUT_SIDE_BY_SIDE);

    /* make current */
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_make_current, BOGUS(gls_surface));
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_make_current, (gls_surface *)(void *)d);
    no_current_cases();
    EXPECT(GLS_OK, gls_make_current, s);
    EXPECT(GLS_OK, gls_make_current, s); /* again: no change */

    /* Buffers. */
    EXPECT(GLS_OK, gls_draw_buffer, GL_BACK);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_draw_buffer, 0x1234u);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_draw_buffer, 0xFFFFFFFFu);
    uint32_t e;
    EXPECT_RET0(e == GL_INVALID_ENUM, 0, e, gls_get_error);
    EXPECT_RET0(e == 0, 0, e, gls_get_error);
    uint32_t two[2] = {GL_BACK_LEFT, GL_BACK_RIGHT}, twice[2] = {GL_BACK_LEFT, GL_BACK_LEFT};
    uint32_t many[9] = {0}, front_and_back[1] = {0x0408u};
    EXPECT(GLS_OK, gls_draw_buffers, 2, two);
    EXPECT(GLS_OK, gls_draw_buffers, 0, NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_draw_buffers, -1, two);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_draw_buffers, 9, many);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_draw_buffers, 2147483647, many);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_draw_buffers, 1, NULL);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_draw_buffers, 2, twice);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_draw_buffers, 1, front_and_back);
    EXPECT_RET0(e == GL_INVALID_VALUE, 0, e, gls_get_error); /* the first error is kept */
    EXPECT_RET0(e == 0, 0, e, gls_get_error);
    EXPECT(GLS_OK, gls_read_buffer, GL_BACK_RIGHT);
    EXPECT(GLS_OK, gls_read_buffer, GL_NONE); /* legal in GL: reading then fails */
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_read_buffer, 0x1234u);
    EXPECT_RET0(e == GL_INVALID_ENUM, 0, e, gls_get_error);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_link_program, 0x7777u); /* not a program name */
    EXPECT_RET0(e == GL_INVALID_VALUE, 0, e, gls_get_error);
    int32_t iv = -3;
    EXPECT(GLS_OK, gls_get_integerv, GL_STEREO, &iv);
    CHECK(iv == 1, "GL_STEREO %d", iv);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_get_integerv, GL_STEREO, NULL);
    EXPECT(GLS_OK, gls_get_integerv, 0xFFFFu, &iv); /* GL's own error, not ours */
    EXPECT_RET0(e == GL_INVALID_ENUM, 0, e, gls_get_error);
    EXPECT(GLS_OK, gls_bind_framebuffer, GL_DRAW_FRAMEBUFFER, 0);
    EXPECT(GLS_OK, gls_bind_framebuffer, 0x1234u, 0);
    EXPECT_RET0(e == GL_INVALID_ENUM, 0, e, gls_get_error);
    void *p;
    EXPECT_RET(p != NULL, 0, p, gls_get_proc_address, "glClear");
    EXPECT_RET(p == NULL, 1, p, gls_get_proc_address, NULL);
    EXPECT_RET(p == NULL, 1, p, gls_get_proc_address, "gl\xff\xfe");
    EXPECT(GLS_OK, gls_apply_stereo_eye, &GOOD_FRUSTUM, &GOOD_ADJUST, GLS_EYE_RIGHT);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_apply_stereo_eye, NULL, &GOOD_ADJUST, GLS_EYE_RIGHT);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_apply_stereo_eye, &GOOD_FRUSTUM, NULL, GLS_EYE_RIGHT);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_apply_stereo_eye, &GOOD_FRUSTUM, &GOOD_ADJUST, 2u);
    gls_frustum badf = GOOD_FRUSTUM;
    badf.near_clip = NAN;
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_apply_stereo_eye, &badf, &GOOD_ADJUST, GLS_EYE_RIGHT);

    /* A mono surface has no right buffers. */
    EXPECT(GLS_OK, gls_make_current, nodepth);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_draw_buffer, GL_BACK_RIGHT);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_read_buffer, GL_FRONT_RIGHT);
    EXPECT_RET0(e == GL_INVALID_OPERATION, 0, e, gls_get_error);

    /* NV_3dvision_settings on the current surface. */
    float fv = -3.0f;
    uint8_t bv = 9, en;
    EXPECT(GLS_OK, gls_stereo_parameterf_nv, GL_STEREO_SEPARATION_NV, 40.0f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_parameterf_nv, GL_STEREO_SEPARATION_NV, 100.5f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_parameterf_nv, GL_STEREO_SEPARATION_NV, -1.0f);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_parameterf_nv, GL_STEREO_SEPARATION_NV, NAN);
    EXPECT_RET0(e == GL_INVALID_VALUE, 0, e, gls_get_error);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_stereo_parameterf_nv, 0x1234u, 1.0f);
    EXPECT_RET0(e == GL_INVALID_ENUM, 0, e, gls_get_error);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_stereo_parameterf_nv, GL_STEREO_PROJECTION_NV, 7.0f);
    EXPECT(GLS_OK, gls_stereo_parameteri_nv, GL_STEREO_SEPARATION_NV, 100);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_parameteri_nv, GL_STEREO_SEPARATION_NV, 101);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_stereo_parameteri_nv, 0xFFFFFFFFu, 0);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_stereo_parameteri_nv, GL_STEREO_PROJECTION_NV, -5);
    EXPECT(GLS_OK, gls_get_floatv, GL_STEREO_SEPARATION_NV, &fv);
    CHECK(fv == 100.0f, "separation %g after failed sets", fv);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_get_floatv, GL_STEREO_SEPARATION_NV, NULL);
    EXPECT(GLS_OK, gls_get_booleanv, GL_DOUBLEBUFFER, &bv);
    CHECK(bv == 1, "GL_DOUBLEBUFFER %u", bv);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_get_booleanv, GL_DOUBLEBUFFER, NULL);
    EXPECT(GLS_OK, gls_enable, GL_3DVISION_STEREO_NV);
    EXPECT_RET(en == 0, 0, en, gls_is_enabled, GL_3DVISION_STEREO_NV); /* not auto-stereo capable */
    EXPECT(GLS_OK, gls_enable, 0x1234u); /* GL's own error */
    EXPECT_RET0(e == GL_INVALID_ENUM, 0, e, gls_get_error);
    EXPECT(GLS_OK, gls_disable, 0x1234u);
    EXPECT_RET0(e == GL_INVALID_ENUM, 0, e, gls_get_error);
    EXPECT_RET(en == 0, 0, en, gls_is_enabled, 0x1234u);
    EXPECT_RET0(e == GL_INVALID_ENUM, 0, e, gls_get_error);
    EXPECT(GLS_OK, gls_disable, GL_DEPTH_TEST);

    /* Parallax measurement needs a depth buffer and geometry. */
    gls_parallax_report rep;
    double dist = -1.0;
    memset(&rep, 0xAB, sizeof rep);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_stereo_measure_parallax, &GOOD_FRUSTUM, &GOOD_ADJUST, 3.0, &rep);
    CHECK(has("depth"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_stereo_auto_converge, &GOOD_FRUSTUM, &dist);
    EXPECT(GLS_OK, gls_make_current, s); /* has depth, but nothing drawn */
    clear_to(0.2f, 0.2f, 0.2f);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_stereo_measure_parallax, &GOOD_FRUSTUM, &GOOD_ADJUST, 3.0, &rep);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_stereo_auto_converge, &GOOD_FRUSTUM, &dist);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_measure_parallax, NULL, &GOOD_ADJUST, 3.0, &rep);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_measure_parallax, &GOOD_FRUSTUM, NULL, 3.0, &rep);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_measure_parallax, &GOOD_FRUSTUM, &GOOD_ADJUST, 3.0, NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_measure_parallax, &GOOD_FRUSTUM, &GOOD_ADJUST, 0.0, &rep);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_measure_parallax, &GOOD_FRUSTUM, &GOOD_ADJUST, NAN, &rep);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_measure_parallax, &badf, &GOOD_ADJUST, 3.0, &rep);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_auto_converge, NULL, &dist);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_stereo_auto_converge, &GOOD_FRUSTUM, NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_stereo_auto_converge, &badf, &dist);
    CHECK(dist == -1.0, "distance written on error");

    /* A report from C may hold anything: describing it never fails. */
    char text[256];
    size_t len = 0;
    EXPECT(GLS_OK, gls_parallax_report_describe, &rep, text, sizeof text, &len);
    CHECK(strlen(text) == (len < sizeof text ? len : sizeof text - 1), "describe wrote %zu of %zu", strlen(text), len);
    EXPECT(GLS_OK, gls_parallax_report_describe, &rep, NULL, 0, &len);
    EXPECT(GLS_OK, gls_parallax_report_describe, &rep, text, 1, NULL);
    CHECK(text[0] == '\0', "a 1-byte buffer holds only the NUL");
    EXPECT(GLS_ERROR_NULL_POINTER, gls_parallax_report_describe, NULL, text, sizeof text, &len);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_parallax_report_describe, &rep, NULL, 16, &len);

    /* Automatic stereo. */
    EXPECT(GLS_OK, gls_make_current, autos);
    EXPECT_RET(en == 1, 0, en, gls_is_enabled, GL_3DVISION_STEREO_NV);
    auto_draw_calls = 0;
    EXPECT(GLS_OK, gls_auto_stereo_frame, draw_nothing, NULL);
    CHECK(auto_draw_calls == 2, "draw called %d times", auto_draw_calls);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_auto_stereo_frame, NULL, NULL);
    auto_draw_calls = 0;
    gls_result outer;
    /* The inner call fails (and leaves its message); the frame itself is fine. */
    EXPECT_RET(outer == GLS_OK, 1, outer, gls_auto_stereo_frame, draw_nested, NULL);
    CHECK(nested_result == GLS_ERROR_INVALID_OPERATION, "nested call: %s", gls_result_string(nested_result));
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_auto_stereo_frame, draw_changes_buffer, NULL);
    auto_draw_calls = 0;
    EXPECT(GLS_OK, gls_auto_stereo_frame, draw_nothing, NULL); /* usable again */
    CHECK(auto_draw_calls == 2, "draw called %d times after errors", auto_draw_calls);

    /* Swap and read back. */
    EXPECT(GLS_OK, gls_make_current, s);
    EXPECT(GLS_OK, gls_draw_buffer, GL_BACK_LEFT);
    clear_to(1.0f, 0.0f, 0.0f);
    EXPECT(GLS_OK, gls_draw_buffer, GL_BACK_RIGHT);
    clear_to(0.0f, 0.0f, 1.0f);
    EXPECT(GLS_OK, gls_swap_buffers, s);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_swap_buffers, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_swap_buffers, BOGUS(gls_surface));
    size_t need = 64 * 48 * 4;
    unsigned char *px = malloc(need);
    memset(px, 0x5A, need);
    EXPECT(GLS_OK, gls_surface_read_pixels, s, GL_FRONT_LEFT, px, need);
    CHECK(px[0] == 255 && px[1] == 0 && px[2] == 0, "left eye %u,%u,%u", px[0], px[1], px[2]);
    memset(px, 0x5A, need);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_read_pixels, s, GL_FRONT_LEFT, NULL, need);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_read_pixels, NULL, GL_FRONT_LEFT, px, need);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_read_pixels, BOGUS(gls_surface), GL_FRONT_LEFT, px, need);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_read_pixels, s, GL_FRONT_LEFT, px, need - 1);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_read_pixels, s, GL_FRONT_LEFT, px, 0);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_read_pixels, s, 0x1234u, px, need);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_read_pixels, s, GL_NONE, px, need);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_read_pixels, nodepth, GL_FRONT_RIGHT, px, 32 * 32 * 4);
    CHECK(px[0] == 0x5A && px[need - 1] == 0x5A, "pixels written on error");

    char tmpl[] = "/tmp/glstereo-misuse-XXXXXX";
    char *dir = mkdtemp(tmpl);
    char path[512];
    CHECK(dir != NULL, "mkdtemp");
    snprintf(path, sizeof path, "%s/left.png", dir ? dir : "/tmp");
    EXPECT(GLS_OK, gls_surface_save_png, s, GLS_IMAGE_LEFT, path);
    unlink(path);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_save_png, s, GLS_IMAGE_LEFT, NULL);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_save_png, NULL, GLS_IMAGE_LEFT, path);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_save_png, BOGUS(gls_surface), GLS_IMAGE_LEFT, path);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_save_png, s, 3u, path);
    EXPECT(GLS_ERROR_IO, gls_surface_save_png, s, GLS_IMAGE_COMPOSITE, "/nonexistent-dir/x.png");
    CHECK(has("/nonexistent-dir/x.png"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_IO, gls_surface_save_png, s, GLS_IMAGE_LEFT, dir ? dir : "/tmp"); /* a directory */
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_save_png, s, GLS_IMAGE_LEFT, "");
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_save_png, s, GLS_IMAGE_LEFT, "/tmp/\xff\xfe.png");
    /* Queued captures: the same argument rules; a write that fails later
     * is reported (once) by the next queue or wait call, and leaves no file. */
    snprintf(path, sizeof path, "%s/queued.png", dir ? dir : "/tmp");
    EXPECT(GLS_OK, gls_surface_queue_png, s, GLS_IMAGE_COMPOSITE, path);
    EXPECT(GLS_OK, gls_surface_wait_captures, s);
    CHECK(access(path, F_OK) == 0, "a queued capture was not written: %s", path);
    unlink(path);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_queue_png, s, GLS_IMAGE_LEFT, NULL);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_queue_png, NULL, GLS_IMAGE_LEFT, path);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_queue_png, BOGUS(gls_surface), GLS_IMAGE_LEFT, path);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_queue_png, s, 3u, path);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_wait_captures, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_wait_captures, BOGUS(gls_surface));
    EXPECT(GLS_OK, gls_surface_queue_png, s, GLS_IMAGE_RIGHT, "/nonexistent-dir/queued.png");
    EXPECT(GLS_ERROR_IO, gls_surface_wait_captures, s);
    CHECK(has("/nonexistent-dir/queued.png"), "%s", gls_last_error_message());
    EXPECT(GLS_OK, gls_surface_wait_captures, s); /* reported once */
    /* Stereo photos: the same argument rules, a format enum, a quality
     * range, and a mono surface refused (one image is not a stereo pair). */
    snprintf(path, sizeof path, "%s/photo.mpo", dir ? dir : "/tmp");
    EXPECT(GLS_OK, gls_surface_set_jpeg_quality, s, 80);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_jpeg_quality, s, 0);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_surface_set_jpeg_quality, s, 101);
    CHECK(has("1 (smallest file) to 100"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_set_jpeg_quality, NULL, 90);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_jpeg_quality, BOGUS(gls_surface), 90);
    EXPECT(GLS_OK, gls_surface_save_stereo_photo, s, GLS_PHOTO_MPO, path);
    CHECK(access(path, F_OK) == 0, "no stereo photo: %s", path);
    unlink(path);
    EXPECT(GLS_OK, gls_surface_queue_stereo_photo, s, GLS_PHOTO_JPS, path);
    EXPECT(GLS_OK, gls_surface_wait_captures, s);
    CHECK(access(path, F_OK) == 0, "no queued stereo photo: %s", path);
    unlink(path);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_save_stereo_photo, s, GLS_PHOTO_MPO, NULL);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_save_stereo_photo, NULL, GLS_PHOTO_MPO, path);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_save_stereo_photo, BOGUS(gls_surface), GLS_PHOTO_MPO, path);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_save_stereo_photo, s, 2u, path);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_surface_queue_stereo_photo, s, 2u, path);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_surface_queue_stereo_photo, s, GLS_PHOTO_JPS, NULL);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_save_stereo_photo, nodepth, GLS_PHOTO_MPO, path);
    CHECK(has("mono"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_queue_stereo_photo, nodepth, GLS_PHOTO_JPS, path);
    EXPECT(GLS_ERROR_IO, gls_surface_save_stereo_photo, s, GLS_PHOTO_JPS, "/nonexistent-dir/x.jps");
    CHECK(has("/nonexistent-dir/x.jps"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_IO, gls_surface_save_stereo_photo, s, GLS_PHOTO_MPO, dir ? dir : "/tmp"); /* a directory */
    CHECK(access(path, F_OK) != 0, "a refused stereo photo left %s", path);
    if (dir) rmdir(dir);
    CHECK(access(path, F_OK) != 0, "a failed save left %s", path);

    /* A surface current on another thread. */
    pthread_barrier_t barrier;
    pthread_barrier_init(&barrier, NULL, 2);
    holder hold = {nodepth, &barrier, GLS_ERROR_GL, GLS_ERROR_GL};
    pthread_t t;
    pthread_create(&t, NULL, hold_current, &hold);
    pthread_barrier_wait(&barrier);
    CHECK(hold.made == GLS_OK, "the other thread: %s", gls_result_string(hold.made));
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_make_current, nodepth);
    CHECK(has("another thread"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_swap_buffers, nodepth);
    EXPECT(GLS_OK, gls_get_integerv, GL_STEREO, &iv); /* s is still current here */
    EXPECT_VOID(0, gls_surface_destroy, nodepth);     /* lives on until released there */
    pthread_barrier_wait(&barrier);
    pthread_join(t, NULL);
    pthread_barrier_destroy(&barrier);
    CHECK(hold.released == GLS_OK, "release on the other thread: %s", gls_result_string(hold.released));
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_make_current, nodepth);

    /* Destroyed: detected; double destroy: reported, harmless. */
    EXPECT_VOID(0, gls_surface_destroy, NULL);
    EXPECT_VOID(1, gls_surface_destroy, BOGUS(gls_surface));
    EXPECT_VOID(1, gls_surface_destroy, (gls_surface *)(void *)c); /* a config is no surface */
    EXPECT(GLS_OK, gls_config_get_attrib, c, GLX_STEREO, &av);     /* ... and still live */
    EXPECT_VOID(0, gls_surface_destroy, s); /* current here: released first */
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_draw_buffer, GL_BACK_LEFT);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_make_current, s);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_swap_buffers, s);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_size, s, &w, &h);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_attrib, s, GLS_SURFACE_AUTO_STEREO, &av);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_read_pixels, s, GL_FRONT_LEFT, px, need);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_save_png, s, GLS_IMAGE_LEFT, "/tmp/never.png");
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_queue_png, s, GLS_IMAGE_LEFT, "/tmp/never.png");
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_wait_captures, s);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_output, s, GLS_OUTPUT_LEFT);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_get_output, s, &out);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_swap_eyes, s, true);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_crosstalk, s, 0.1f);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_saturation, s, 0.1f);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_set_input, s, GLS_INPUT_STR_RECT);
    int32_t fd;
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_fildes, s, &fd);
    dead_window_cases(s);
    EXPECT_VOID(1, gls_surface_destroy, s);
    free(px);

    /* The display closed first: its surfaces keep working until destroyed. */
    EXPECT_VOID(0, gls_display_close, d);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_surface_create, d, c, 8, 8, &s);
    EXPECT(GLS_OK, gls_make_current, autos);
    clear_to(0.0f, 1.0f, 0.0f);
    EXPECT(GLS_OK, gls_swap_buffers, autos);
    CHECK(centre(autos, GL_FRONT_LEFT) == 0x00FF00, "surface of a closed display: %06lx",
          centre(autos, GL_FRONT_LEFT));
    EXPECT(GLS_OK, gls_make_current, NULL);
    gls_surface_destroy(autos);
    gls_surface_destroy(tiny);
    gls_config_free(c);
    gls_config_free(mono);
}

/* ---- surfaces of several displays in one process ---------------------- */

/* Clears both back buffers of the current surface (left, right colours),
 * swaps, and checks the front buffers. */
static void paint(gls_surface *s, long left, long right, const char *what) {
    EXPECT(GLS_OK, gls_draw_buffer, GL_BACK_LEFT);
    clear_to((float)(left >> 16 & 255) / 255.0f, (float)(left >> 8 & 255) / 255.0f, (float)(left & 255) / 255.0f);
    int32_t stereo = 0;
    gls_get_integerv(GL_STEREO, &stereo);
    if (stereo) {
        EXPECT(GLS_OK, gls_draw_buffer, GL_BACK_RIGHT);
        clear_to((float)(right >> 16 & 255) / 255.0f, (float)(right >> 8 & 255) / 255.0f,
                 (float)(right & 255) / 255.0f);
    }
    EXPECT(GLS_OK, gls_swap_buffers, s);
    long l = centre(s, GL_FRONT_LEFT), r = centre(s, GL_FRONT_RIGHT);
    CHECK(l == left && (!stereo || r == right), "%s: %06lx %06lx, wanted %06lx %06lx", what, l, r, left, right);
}

static void cross_display_cases(void) {
    gls_display *egl1, *egl2, *osm;
    gls_config *c1, *c2, *co;
    gls_surface *s1, *s2, *so, *never = BOGUS(gls_surface);
    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_EGL, &egl1);
    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_EGL, &egl2);
    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_OSMESA, &osm);
    uint32_t b = 0;
    EXPECT(GLS_OK, gls_display_get_backend, osm, &b);
    CHECK(b == GLS_BACKEND_OSMESA, "backend %u", b);
    EXPECT(GLS_OK, gls_config_choose, egl1, STEREO_ATTRIBS, &c1);
    EXPECT(GLS_OK, gls_config_choose, egl2, STEREO_ATTRIBS, &c2);
    EXPECT(GLS_OK, gls_config_choose, osm, MONO_ATTRIBS, &co);

    /* A configuration belongs to the display that chose it. */
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_create, egl1, co, 16, 16, &never);
    CHECK(has("another display"), "%s", gls_last_error_message());
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_create, egl1, c2, 16, 16, &never);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_create_with_attribs, osm, c1, 16, 16, NULL, &never);
    CHECK(never == BOGUS(gls_surface), "surface_out written on error");

    EXPECT(GLS_OK, gls_surface_create, egl1, c1, 40, 30, &s1);
    EXPECT(GLS_OK, gls_surface_create, egl2, c2, 24, 20, &s2);
    EXPECT(GLS_OK, gls_surface_create, osm, co, 32, 16, &so);
    window_cases(so, co, GLS_BACKEND_OSMESA);

    /* Hop between the three, drawing on each; every surface keeps its pixels. */
    for (int round = 0; round < 3; ++round) {
        long k = round * 0x101010;
        EXPECT(GLS_OK, gls_make_current, s1);
        paint(s1, 0xC00000 + k, 0x0000C0 + k, "EGL display 1");
        EXPECT(GLS_OK, gls_make_current, so);
        paint(so, 0x00C000 + k, 0, "OSMesa");
        EXPECT(GLS_OK, gls_make_current, s2);
        paint(s2, 0xC0C000 + k, 0x00C0C0 + k, "EGL display 2");
        EXPECT(GLS_OK, gls_make_current, so);
        long v = centre(s1, GL_FRONT_RIGHT); /* an EGL surface read while OSMesa is current */
        CHECK(v == 0x0000C0 + k, "EGL surface read from an OSMesa thread: %06lx", v);
        int32_t st = -1;
        EXPECT(GLS_OK, gls_get_integerv, GL_STEREO, &st);
        CHECK(st == 0, "the OSMesa surface is still the current one: GL_STEREO %d", st);
        EXPECT(GLS_OK, gls_make_current, s1);
        v = centre(so, GL_FRONT_LEFT); /* and the other way round */
        CHECK(v == 0x00C000 + k, "OSMesa surface read from an EGL thread: %06lx", v);
        EXPECT(GLS_OK, gls_get_integerv, GL_STEREO, &st);
        CHECK(st == 1, "the EGL surface is still the current one: GL_STEREO %d", st);
    }
    /* Composites of each made from another backend's context. */
    EXPECT(GLS_OK, gls_surface_set_output, so, GLS_OUTPUT_SIDE_BY_SIDE);
    char tmpl[] = "/tmp/glstereo-cross-XXXXXX";
    char *dir = mkdtemp(tmpl), path[512];
    snprintf(path, sizeof path, "%s/c.png", dir ? dir : "/tmp");
    EXPECT(GLS_OK, gls_surface_save_png, so, GLS_IMAGE_COMPOSITE, path);
    unlink(path);
    EXPECT(GLS_OK, gls_make_current, so);
    EXPECT(GLS_OK, gls_surface_save_png, s2, GLS_IMAGE_COMPOSITE, path);
    unlink(path);
    if (dir) rmdir(dir);

    EXPECT(GLS_OK, gls_make_current, NULL);
    gls_surface_destroy(s1);
    gls_surface_destroy(s2);
    gls_surface_destroy(so);
    gls_config_free(c1);
    gls_config_free(c2);
    gls_config_free(co);
    gls_display_close(egl1);
    gls_display_close(egl2);
    gls_display_close(osm);
}

/* ---- the period APIs -------------------------------------------------- */

static void starbase_cases(void) {
    int32_t fd = -1, fd2 = -1;
    gls_surface *ss = BOGUS(gls_surface);
    gls_gescape_arg on, off;
    memset(&on, 0, sizeof on);
    memset(&off, 0, sizeof off);
    on.i[0] = 1;
    EXPECT(GLS_ERROR_NULL_POINTER, gls_starbase_open, GLS_STARBASE_OUTDEV, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_starbase_open, 1, &fd);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_starbase_open, -1, &fd);
    CHECK(fd == -1, "fildes written on error");
    EXPECT(GLS_OK, gls_starbase_open, GLS_STARBASE_OUTINDEV, &fd);
    CHECK(fd >= 3, "fildes %d", fd);
    EXPECT(GLS_OK, gls_starbase_surface, fd, &ss);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_starbase_surface, fd, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_surface, 0, &ss);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_surface, -1, &ss);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_surface, 2147483647, &ss);
    EXPECT(GLS_OK, gls_starbase_gescape, fd, GLS_STARBASE_STEREO, &on, NULL);
    EXPECT(GLS_OK, gls_starbase_gescape, fd, GLS_STARBASE_STEREO, &off, &off);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_gescape, 999, GLS_STARBASE_STEREO, &on, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_gescape, 999, 1, NULL, NULL); /* fildes first */
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_starbase_gescape, fd, 1, &on, NULL);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_starbase_gescape, fd, GLS_STARBASE_STEREO, NULL, NULL);

    gls_display *d;
    gls_config *c;
    gls_surface *line;
    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_EGL, &d);
    EXPECT(GLS_OK, gls_config_choose, d, MONO_ATTRIBS, &c);
    EXPECT(GLS_OK, gls_surface_create, d, c, 16, 1, &line);
    EXPECT(GLS_OK, gls_starbase_fildes, line, &fd2);
    int32_t again = -1;
    EXPECT(GLS_OK, gls_starbase_fildes, line, &again);
    CHECK(again == fd2, "the same surface got descriptors %d and %d", fd2, again);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_starbase_fildes, line, NULL);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_starbase_fildes, NULL, &again);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_fildes, BOGUS(gls_surface), &again);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_starbase_gescape, fd2, GLS_STARBASE_STEREO, &on, NULL);
    gls_surface_destroy(line); /* ends the descriptor too */
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_gescape, fd2, GLS_STARBASE_STEREO, &off, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_surface, fd2, &ss);

    /* The program destroying a gopen() surface itself (the docs say not
     * to) ends its use through the descriptor; gclose still works. */
    EXPECT(GLS_OK, gls_starbase_surface, fd, &ss);
    EXPECT_VOID(0, gls_surface_destroy, ss);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_gescape, fd, GLS_STARBASE_STEREO, &on, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_surface, fd, &ss);
    EXPECT(GLS_OK, gls_starbase_close, fd);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_close, fd);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_close, -1);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_surface, fd, &ss);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_starbase_gescape, fd, GLS_STARBASE_STEREO, &on, NULL);
    EXPECT(GLS_ERROR_NO_CURRENT_SURFACE, gls_draw_buffer, GL_BACK_LEFT); /* gclose released it */
    gls_config_free(c);
    gls_display_close(d);
}

static void irisgl_cases(void) {
    int64_t gv = -1;
    int32_t mode = -1, win = -1, small = -1;
    EXPECT(GLS_OK, gls_irisgl_getgdesc, GLS_IRISGL_GD_XPMAX, &gv);
    CHECK(gv == 128, "GD_XPMAX %lld", (long long)gv);
    gv = -1;
    EXPECT(GLS_ERROR_NULL_POINTER, gls_irisgl_getgdesc, GLS_IRISGL_GD_XPMAX, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_irisgl_getgdesc, 2, &gv);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_irisgl_getgdesc, -1, &gv);
    setenv("GLSTEREO_EMULATION", "garbage", 1);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_getgdesc, GLS_IRISGL_GD_STEREO_IN_WINDOW, &gv);
    unsetenv("GLSTEREO_EMULATION");
    CHECK(gv == -1, "value written on error");
    EXPECT(GLS_OK, gls_irisgl_getmonitor, &mode);
    CHECK(mode == GLS_IRISGL_HZ60, "monitor %d", mode);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_irisgl_getmonitor, NULL);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_irisgl_setmonitor, 0);
    EXPECT(GLS_ERROR_INVALID_ENUM, gls_irisgl_setmonitor, -2147483647 - 1);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_prefposition, 10, 5, 0, 10);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_prefposition, 0, 10, 10, 5);

    /* No window yet. */
    EXPECT0(GLS_ERROR_INVALID_OPERATION, gls_irisgl_stereobuffer);
    CHECK(has("winopen"), "%s", gls_last_error_message());
    EXPECT0(GLS_ERROR_INVALID_OPERATION, gls_irisgl_monobuffer);
    EXPECT0(GLS_ERROR_INVALID_OPERATION, gls_irisgl_doublebuffer);
    EXPECT0(GLS_ERROR_INVALID_OPERATION, gls_irisgl_singlebuffer);
    EXPECT0(GLS_ERROR_INVALID_OPERATION, gls_irisgl_gconfig);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_irisgl_leftbuffer, true);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_irisgl_rightbuffer, true);
    EXPECT0(GLS_ERROR_INVALID_OPERATION, gls_irisgl_swapbuffers);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_irisgl_winclose, 1);
    gls_surface *ws = BOGUS(gls_surface);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_irisgl_surface, 1, &ws);

    EXPECT(GLS_ERROR_NULL_POINTER, gls_irisgl_winopen, "misuse", NULL);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_winopen, "\xff\xfe", &win);
    CHECK(win == -1, "window written on error");
    EXPECT(GLS_OK, gls_irisgl_winopen, NULL, &win);
    EXPECT(GLS_OK, gls_irisgl_surface, win, &ws);
    EXPECT(GLS_ERROR_NULL_POINTER, gls_irisgl_surface, win, NULL);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_irisgl_surface, win + 100, &ws);
    EXPECT0(GLS_OK, gls_irisgl_stereobuffer);
    EXPECT0(GLS_OK, gls_irisgl_doublebuffer);
    EXPECT0(GLS_OK, gls_irisgl_gconfig);
    EXPECT(GLS_OK, gls_irisgl_leftbuffer, false);
    EXPECT(GLS_OK, gls_irisgl_rightbuffer, true);
    EXPECT0(GLS_OK, gls_irisgl_swapbuffers);
    EXPECT0(GLS_OK, gls_irisgl_monobuffer);
    EXPECT0(GLS_OK, gls_irisgl_singlebuffer);
    EXPECT0(GLS_OK, gls_irisgl_gconfig);
    EXPECT(GLS_OK, gls_irisgl_viewport, 0, 127, 0, 63);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_viewport, 10, 5, 0, 10);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_viewport, 0, 10, 10, 5);
    EXPECT(GLS_OK, gls_irisgl_window, -1, 1, -1, 1, 1, 10);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_window, -1, 1, -1, 1, 0, 10);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_window, -1, 1, -1, 1, 10, 1);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_window, 1, 1, -1, 1, 1, 10);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_window, -1, 1, NAN, 1, 1, 10);
    EXPECT(GLS_OK, gls_irisgl_translate, 0.5, 0, 0);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_translate, NAN, 0, 0);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_translate, 0, 0, -INFINITY);

    /* A window too small for the STR_* bands: setmonitor changes nothing. */
    EXPECT(GLS_OK, gls_irisgl_prefposition, 0, 0, 0, 0);
    EXPECT(GLS_OK, gls_irisgl_winopen, "tiny", &small);
    EXPECT(GLS_ERROR_INVALID_VALUE, gls_irisgl_setmonitor, GLS_IRISGL_STR_RECT);
    EXPECT(GLS_OK, gls_irisgl_getmonitor, &mode);
    CHECK(mode == GLS_IRISGL_HZ60, "monitor %d after a failed setmonitor", mode);
    EXPECT(GLS_OK, gls_irisgl_winclose, small);
    EXPECT(GLS_OK, gls_irisgl_setmonitor, GLS_IRISGL_STR_RECT);
    EXPECT(GLS_OK, gls_irisgl_setmonitor, GLS_IRISGL_HZ60);

    /* stereobuffer() on a window without stereo buffers. */
    int32_t mono_win = -1;
    setenv("GLSTEREO_EMULATION", "off", 1);
    EXPECT(GLS_OK, gls_irisgl_winopen, "mono", &mono_win);
    unsetenv("GLSTEREO_EMULATION");
    EXPECT0(GLS_OK, gls_irisgl_stereobuffer);
    EXPECT0(GLS_ERROR_INVALID_OPERATION, gls_irisgl_gconfig);
    CHECK(has("GD_STEREO_IN_WINDOW"), "%s", gls_last_error_message());
    EXPECT(GLS_OK, gls_irisgl_winclose, mono_win);

    EXPECT(GLS_OK, gls_irisgl_winclose, win);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_irisgl_winclose, win);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_irisgl_winclose, 0);
    EXPECT(GLS_ERROR_INVALID_HANDLE, gls_irisgl_surface, win, &ws);
    EXPECT0(GLS_ERROR_INVALID_OPERATION, gls_irisgl_swapbuffers);
}

/* ---- GLX: configurations and current surfaces across connections ------ */

static void glx_cases(void) {
    gls_display *a, *bd, *e;
    gls_config *ca, *cb, *ce;
    gls_surface *sb, *se, *never = BOGUS(gls_surface);
    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_GLX, &a);
    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_GLX, &bd);
    EXPECT(GLS_OK, gls_display_open, GLS_BACKEND_EGL, &e);
    EXPECT(GLS_OK, gls_config_choose, a, STEREO_ATTRIBS, &ca);
    EXPECT(GLS_OK, gls_config_choose, bd, STEREO_ATTRIBS, &cb);
    EXPECT(GLS_OK, gls_config_choose, e, STEREO_ATTRIBS, &ce);
    /* A's connection closes (no surface keeps it); its configuration
     * must not reach into it from display B. */
    EXPECT_VOID(0, gls_display_close, a);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_create, bd, ca, 32, 32, &never);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_create, e, cb, 32, 32, &never);
    EXPECT(GLS_ERROR_INVALID_OPERATION, gls_surface_create, bd, ce, 32, 32, &never);
    CHECK(never == BOGUS(gls_surface), "surface_out written on error");
    EXPECT(GLS_OK, gls_surface_create, bd, cb, 32, 32, &sb);
    EXPECT(GLS_OK, gls_surface_create, e, ce, 32, 32, &se);
    window_cases(sb, cb, GLS_BACKEND_GLX);
    for (int round = 0; round < 3; ++round) {
        long k = round * 0x202020;
        EXPECT(GLS_OK, gls_make_current, sb);
        paint(sb, 0x800000 + k, 0x000080 + k, "GLX");
        EXPECT(GLS_OK, gls_make_current, se);
        paint(se, 0x008000 + k, 0x808000 + k, "EGL next to GLX");
        long v = centre(sb, GL_FRONT_LEFT);
        CHECK(v == 0x800000 + k, "GLX surface read while EGL is current: %06lx", v);
    }
    EXPECT(GLS_OK, gls_make_current, NULL);
    gls_surface_destroy(sb);
    dead_window_cases(sb);
    gls_surface_destroy(se);
    gls_config_free(ca);
    gls_config_free(cb);
    gls_config_free(ce);
    gls_display_close(bd);
    gls_display_close(e);
}

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IOLBF, 0);
    unsetenv("GLSTEREO_MODE");
    unsetenv("GLSTEREO_EMULATION");
    setenv("GLSTEREO_BACKEND", "egl", 1);
    sentinel();
    CHECK(message_is_sentinel(), "the sentinel message names itself: %s", gls_last_error_message());

    core_cases();
    math_cases();
    names_and_screen_cases();
    display_cases();
    surface_cases();
    cross_display_cases();
    starbase_cases();
    irisgl_cases();
    if (argc > 1 && strcmp(argv[1], "glx") == 0) glx_cases();
    /* Still alive, and still working after all of the above. */
    EXPECT0(GLS_ERROR_PANIC, gls_debug_force_panic);
    return SUMMARY();
}

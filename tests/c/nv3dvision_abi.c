/* NV_3dvision_settings from C through the legacy names of
 * glstereo/nv3dvision.h: auto-stereo surfaces, initial values, every error
 * with its GL error and result code, and the frame call (left eye first,
 * each into its own buffer). Links libglstereo and libGL (EGL backend). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "glstereo/nv3dvision.h"
#include "check.h"

#define GLX_RGBA 4
#define GLX_DOUBLEBUFFER 5

static int has(const char *needle) { return strstr(gls_last_error_message(), needle) != NULL; }

/* The mono frame: clears to a colour that says which call this is. */
static void frame(void *user_data) {
    int *calls = (int *)user_data;
    static const float colors[3][3] = {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}};
    const float *c = colors[*calls < 2 ? *calls : 2];
    glClearColor(c[0], c[1], c[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ++*calls;
}

/* Breaks the contract: loads its own projection. */
static void sets_projection(void *user_data) {
    int *calls = (int *)user_data;
    ++*calls;
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
}

static void pixel(gls_surface *s, uint32_t buffer, unsigned char out[4]) {
    static unsigned char px[16 * 8 * 4];
    gls_result r = gls_surface_read_pixels(s, buffer, px, sizeof px);
    CHECK(r == GLS_OK, "read_pixels(%#x): %s", buffer, gls_last_error_message());
    memcpy(out, px + (4 * 16 + 8) * 4, 4);
}

int main(void) {
    gls_display *d = NULL;
    gls_result r = gls_display_open(GLS_BACKEND_EGL, &d);
    CHECK(r == GLS_OK, "EGL: %s", gls_last_error_message());
    if (r != GLS_OK) return SUMMARY();
    gls_config *c = NULL;
    const int mono[] = {GLX_RGBA, GLX_DOUBLEBUFFER, 0};
    CHECK(gls_config_choose(d, mono, &c) == GLS_OK, "%s", gls_last_error_message());

    /* Creation attributes. */
    gls_surface *s = NULL;
    const int32_t bad[] = {0x3137, 1, GLS_SURFACE_ATTRIB_NONE};
    CHECK(gls_surface_create_with_attribs(d, c, 16, 8, bad, &s) == GLS_ERROR_INVALID_ENUM && s == NULL,
          "unknown attribute");
    CHECK(has("GLS_SURFACE_AUTO_STEREO"), "%s", gls_last_error_message());
    const int32_t autostereo[] = {GLS_SURFACE_AUTO_STEREO, 1, GLS_SURFACE_ATTRIB_NONE};
    CHECK(gls_surface_create_with_attribs(d, c, 16, 8, autostereo, &s) == GLS_OK, "%s",
          gls_last_error_message());
    int32_t capable = -1;
    CHECK(gls_surface_get_attrib(s, GLS_SURFACE_AUTO_STEREO, &capable) == GLS_OK && capable == 1,
          "capable = %d", capable);

    /* Without a current surface. */
    CHECK(glStereoParameterfNV(GL_STEREO_SEPARATION_NV, 10.0f) == GLS_ERROR_NO_CURRENT_SURFACE, "no surface");
    CHECK(glIsEnabled(GL_3DVISION_STEREO_NV) == GL_FALSE, "no surface: false");

    CHECK(gls_make_current(s) == GLS_OK, "%s", gls_last_error_message());

    /* Initial values, in every Get form. */
    GLfloat f = -1;
    GLint i = -1;
    GLboolean b = 7;
    CHECK(glIsEnabled(GL_3DVISION_STEREO_NV) == GL_TRUE, "enabled initially on a capable surface");
    glGetFloatv(GL_STEREO_SEPARATION_NV, &f);
    CHECK(f == 15.0f, "separation %g", f);
    glGetFloatv(GL_STEREO_CONVERGENCE_NV, &f);
    CHECK(f == 0.0f, "convergence %g", f);
    glGetFloatv(GL_STEREO_CUTOFF_NV, &f);
    CHECK(f == 0.0f, "cutoff %g", f);
    glGetIntegerv(GL_STEREO_PROJECTION_NV, &i);
    CHECK(i == GL_STEREO_PROJECTION_PERSPECTIVE_NV, "projection %#x", i);
    glGetBooleanv(GL_3DVISION_STEREO_NV, &b);
    CHECK(b == GL_TRUE, "boolean enable %d", b);
    CHECK(glGetError() == GL_NO_ERROR, "no error yet");

    /* Every error, with its GL error and result code, and no change. */
    CHECK(glStereoParameterfNV(0x1234, 1.0f) == GLS_ERROR_INVALID_ENUM, "unknown pname");
    CHECK(glGetError() == GL_INVALID_ENUM, "unknown pname: GL_INVALID_ENUM");
    CHECK(glStereoParameteriNV(GL_3DVISION_STEREO_NV, 1) == GLS_ERROR_INVALID_ENUM, "cap as pname");
    CHECK(glGetError() == GL_INVALID_ENUM, "cap as pname: GL_INVALID_ENUM");
    CHECK(glStereoParameteriNV(GL_STEREO_PROJECTION_NV, 0x1234) == GLS_ERROR_INVALID_ENUM, "bad projection");
    CHECK(glGetError() == GL_INVALID_ENUM, "bad projection: GL_INVALID_ENUM");
    CHECK(glStereoParameterfNV(GL_STEREO_SEPARATION_NV, -1.0f) == GLS_ERROR_INVALID_VALUE, "separation -1");
    CHECK(glGetError() == GL_INVALID_VALUE, "separation -1: GL_INVALID_VALUE");
    CHECK(glStereoParameteriNV(GL_STEREO_SEPARATION_NV, 101) == GLS_ERROR_INVALID_VALUE, "separation 101");
    CHECK(has("0…100"), "%s", gls_last_error_message());
    CHECK(glGetError() == GL_INVALID_VALUE, "separation 101: GL_INVALID_VALUE");
    CHECK(glStereoParameterfNV(GL_STEREO_SEPARATION_NV, (float)NAN) == GLS_ERROR_INVALID_VALUE, "NaN");
    CHECK(glGetError() == GL_INVALID_VALUE, "NaN: GL_INVALID_VALUE");
    CHECK(glGetError() == GL_NO_ERROR, "each error reported once");
    glGetFloatv(GL_STEREO_SEPARATION_NV, &f);
    CHECK(f == 15.0f, "errors changed nothing: %g", f);

    /* Valid settings. */
    CHECK(glStereoParameterfNV(GL_STEREO_SEPARATION_NV, 55.5f) == GLS_OK, "separation");
    CHECK(glStereoParameteriNV(GL_STEREO_CONVERGENCE_NV, 12) == GLS_OK, "convergence");
    CHECK(glStereoParameteriNV(GL_STEREO_PROJECTION_NV, GL_STEREO_PROJECTION_ORTHO_NV) == GLS_OK, "ortho");
    glGetIntegerv(GL_STEREO_SEPARATION_NV, &i);
    CHECK(i == 56, "separation as integer rounds: %d", i);
    glGetFloatv(GL_STEREO_CONVERGENCE_NV, &f);
    CHECK(f == 12.0f, "convergence %g", f);
    glGetIntegerv(GL_STEREO_PROJECTION_NV, &i);
    CHECK(i == GL_STEREO_PROJECTION_ORTHO_NV, "projection %#x", i);

    /* The frame: left eye first, each into its own back buffer. */
    int calls = 0;
    CHECK(gls_auto_stereo_frame(frame, &calls) == GLS_OK, "%s", gls_last_error_message());
    CHECK(calls == 2, "one call per eye: %d", calls);
    unsigned char px[4];
    pixel(s, GL_BACK_LEFT, px);
    CHECK(px[0] == 255 && px[2] == 0, "left eye drawn by the first call: %u %u %u", px[0], px[1], px[2]);
    pixel(s, GL_BACK_RIGHT, px);
    CHECK(px[2] == 255 && px[0] == 0, "right eye drawn by the second call: %u %u %u", px[0], px[1], px[2]);
    pixel(s, GL_BACK, px);
    CHECK(px[0] == 255, "GL_BACK reads the left eye");
    glGetIntegerv(GL_DRAW_BUFFER, &i);
    CHECK(i == GL_BACK, "draw buffer restored: %#x", i);

    /* Disabled: one call, both eyes alike. */
    glDisable(GL_3DVISION_STEREO_NV);
    CHECK(glIsEnabled(GL_3DVISION_STEREO_NV) == GL_FALSE, "disabled");
    calls = 2;
    CHECK(gls_auto_stereo_frame(frame, &calls) == GLS_OK && calls == 3, "mono: one call");
    pixel(s, GL_BACK_RIGHT, px);
    CHECK(px[1] == 255 && px[0] == 0, "mono frame reaches the right eye too");
    glEnable(GL_3DVISION_STEREO_NV);

    /* Contract errors. */
    calls = 0;
    CHECK(gls_auto_stereo_frame(sets_projection, &calls) == GLS_ERROR_INVALID_OPERATION && calls == 1,
          "projection changed: %d calls", calls);
    CHECK(has("projection"), "%s", gls_last_error_message());
    CHECK(gls_auto_stereo_frame(NULL, NULL) == GLS_ERROR_NULL_POINTER, "NULL draw");
    CHECK(glGetError() == GL_NO_ERROR, "contract errors are not GL errors");

    /* Other caps still reach GL. */
    glEnable(GL_DEPTH_TEST);
    CHECK(glIsEnabled(GL_DEPTH_TEST) == GL_TRUE, "GL caps pass through");
    glDisable(GL_DEPTH_TEST);

    gls_make_current(NULL);
    gls_surface_destroy(s);

    /* A surface that is not capable: enabling has no effect. */
    CHECK(gls_surface_create_with_attribs(d, c, 16, 8, NULL, &s) == GLS_OK, "%s", gls_last_error_message());
    CHECK(gls_surface_get_attrib(s, GLS_SURFACE_AUTO_STEREO, &capable) == GLS_OK && capable == 0, "not capable");
    CHECK(gls_make_current(s) == GLS_OK, "%s", gls_last_error_message());
    glEnable(GL_3DVISION_STEREO_NV);
    CHECK(glIsEnabled(GL_3DVISION_STEREO_NV) == GL_FALSE, "enable has no effect");
    CHECK(glGetError() == GL_NO_ERROR, "and raises no error");
    calls = 0;
    CHECK(gls_auto_stereo_frame(frame, &calls) == GLS_OK && calls == 1, "mono: %d calls", calls);
    gls_make_current(NULL);
    gls_surface_destroy(s);
    gls_config_free(c);
    gls_display_close(d);
    return SUMMARY();
}

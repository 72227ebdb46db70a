/* Misuse of the display/config/surface API from C: every case returns its
 * documented code, leaves a message, and the process goes on. Links only
 * libglstereo (EGL is loaded by the library at run time). */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>

#include "glstereo.h"
#include "check.h"

#define GLX_RGBA 4
#define GLX_DOUBLEBUFFER 5
#define GLX_STEREO 6
#define GL_BACK_LEFT 0x0402
#define GL_FRONT_RIGHT 0x0401
#define GL_INVALID_ENUM 0x0500
#define GL_INVALID_OPERATION 0x0502
#define GL_STEREO 0x0C33

static int has(const char *needle) { return strstr(gls_last_error_message(), needle) != NULL; }

int main(void) {
    gls_display *d = NULL;
    CHECK(gls_display_open(99u, &d) == GLS_ERROR_INVALID_ENUM && d == NULL, "bad backend");
    CHECK(gls_display_open(GLS_BACKEND_EGL, NULL) == GLS_ERROR_NULL_POINTER, "NULL display_out");
    setenv("GLSTEREO_BACKEND", "vulkan", 1);
    CHECK(gls_display_open(GLS_BACKEND_AUTO, &d) == GLS_ERROR_INVALID_VALUE, "bad GLSTEREO_BACKEND");
    CHECK(has("GLSTEREO_BACKEND"), "%s", gls_last_error_message());
    unsetenv("GLSTEREO_BACKEND");
    gls_result r = gls_display_open(GLS_BACKEND_EGL, &d);
    CHECK(r == GLS_OK, "EGL: %s", gls_last_error_message());
    if (r != GLS_OK) return SUMMARY();
    uint32_t backend = 0;
    CHECK(gls_display_get_backend(d, &backend) == GLS_OK && backend == GLS_BACKEND_EGL, "backend %u", backend);

    /* Configurations. */
    gls_config *c = NULL;
    const int stereo[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, 0};
    const int unknown[] = {GLX_RGBA, 0x7777, 0};
    CHECK(gls_config_choose(d, NULL, &c) == GLS_ERROR_NULL_POINTER, "NULL attribs");
    CHECK(gls_config_choose(NULL, stereo, &c) == GLS_ERROR_NULL_POINTER, "NULL display");
    CHECK(gls_config_choose((gls_display *)&backend, stereo, &c) == GLS_ERROR_INVALID_HANDLE, "bogus display");
    CHECK(gls_config_choose(d, unknown, &c) == GLS_ERROR_INVALID_ENUM && c == NULL, "unknown attribute");
    CHECK(has("0x7777"), "%s", gls_last_error_message());
    setenv("GLSTEREO_EMULATION", "off", 1);
    CHECK(gls_config_choose(d, stereo, &c) == GLS_ERROR_NO_MATCHING_CONFIG, "emulation off");
    CHECK(has("GLX_STEREO"), "%s", gls_last_error_message());
    unsetenv("GLSTEREO_EMULATION");
    CHECK(gls_config_choose(d, stereo, &c) == GLS_OK, "%s", gls_last_error_message());
    CHECK(gls_config_stereo(c) == GLS_STEREO_EMULATED, "emulated");
    CHECK(gls_config_stereo(NULL) == GLS_STEREO_NONE, "NULL config");
    int v = -1;
    CHECK(gls_config_get_attrib(c, GLX_STEREO, &v) == GLS_OK && v == 1, "GLX_STEREO = %d", v);
    CHECK(gls_config_get_attrib(c, 0x7777, &v) == GLS_ERROR_INVALID_ENUM, "bad attrib");

    /* Surfaces: sizes. */
    gls_surface *s = NULL;
    CHECK(gls_surface_create(d, c, 0, 0, &s) == GLS_ERROR_INVALID_VALUE && s == NULL, "0x0");
    CHECK(gls_surface_create(d, c, 100000, 100000, &s) == GLS_ERROR_INVALID_VALUE, "100000x100000");
    CHECK(has("100000x100000"), "%s", gls_last_error_message());
    CHECK(gls_surface_create(d, c, 64, 32, NULL) == GLS_ERROR_NULL_POINTER, "NULL surface_out");
    CHECK(gls_surface_create(d, c, 64, 32, &s) == GLS_OK, "%s", gls_last_error_message());

    /* No current surface. */
    CHECK(gls_draw_buffer(GL_BACK_LEFT) == GLS_ERROR_NO_CURRENT_SURFACE, "draw without current");
    CHECK(gls_read_buffer(GL_BACK_LEFT) == GLS_ERROR_NO_CURRENT_SURFACE, "read without current");
    int32_t iv = 0;
    CHECK(gls_get_integerv(GL_STEREO, &iv) == GLS_ERROR_NO_CURRENT_SURFACE, "get without current");
    CHECK(gls_get_proc_address("glClear") == NULL, "proc address without current");

    CHECK(gls_make_current(s) == GLS_OK, "%s", gls_last_error_message());
    CHECK(gls_get_integerv(GL_STEREO, &iv) == GLS_OK && iv == 1, "GL_STEREO = %d", iv);
    CHECK(gls_get_integerv(GL_STEREO, NULL) == GLS_ERROR_NULL_POINTER, "NULL data");
    CHECK(gls_get_proc_address("glClear") != NULL, "glClear address");
    CHECK(gls_draw_buffer(0x1234) == GLS_ERROR_INVALID_ENUM, "bad draw buffer");
    CHECK(gls_get_error() == GL_INVALID_ENUM, "GL error after bad draw buffer");
    CHECK(gls_draw_buffers(-1, NULL) == GLS_ERROR_INVALID_VALUE, "negative n");
    CHECK(gls_draw_buffers(1, NULL) == GLS_ERROR_NULL_POINTER, "NULL bufs");
    uint32_t many[9] = {0};
    CHECK(gls_draw_buffers(9, many) == GLS_ERROR_INVALID_VALUE, "too many draw buffers");

    /* Reading and saving. */
    unsigned char small[16];
    CHECK(gls_surface_read_pixels(s, GL_FRONT_RIGHT, small, sizeof small) == GLS_ERROR_INVALID_VALUE, "short buffer");
    CHECK(gls_surface_read_pixels(s, GL_FRONT_RIGHT, NULL, 64 * 32 * 4) == GLS_ERROR_NULL_POINTER, "NULL rgba");
    unsigned char *px = malloc(64 * 32 * 4);
    CHECK(gls_surface_read_pixels(s, 0x1234, px, 64 * 32 * 4) == GLS_ERROR_INVALID_ENUM, "bad read buffer");
    CHECK(gls_surface_read_pixels(s, GL_FRONT_RIGHT, px, 64 * 32 * 4) == GLS_OK, "%s", gls_last_error_message());
    free(px);
    CHECK(gls_surface_save_png(s, 7u, "/tmp/x.png") == GLS_ERROR_INVALID_ENUM, "bad image");
    CHECK(gls_surface_save_png(s, GLS_IMAGE_LEFT, NULL) == GLS_ERROR_NULL_POINTER, "NULL path");
    CHECK(gls_surface_save_png(s, GLS_IMAGE_LEFT, "/nonexistent-dir/left.png") == GLS_ERROR_IO, "unwritable path");
    CHECK(has("/nonexistent-dir/left.png"), "%s", gls_last_error_message());
    CHECK(gls_swap_buffers(s) == GLS_OK, "%s", gls_last_error_message());

    /* Destroyed handles are detected, double destroy does nothing. */
    gls_surface_destroy(s);
    CHECK(gls_draw_buffer(GL_BACK_LEFT) == GLS_ERROR_NO_CURRENT_SURFACE, "destroying released it");
    CHECK(gls_swap_buffers(s) == GLS_ERROR_INVALID_HANDLE, "swap destroyed surface");
    CHECK(gls_make_current(s) == GLS_ERROR_INVALID_HANDLE, "make destroyed surface current");
    gls_surface_destroy(s);
    CHECK(has("not a live handle"), "%s", gls_last_error_message());
    gls_surface_destroy(NULL);
    gls_config_free(c);
    gls_config_free(c);
    CHECK(gls_config_stereo(c) == GLS_STEREO_NONE, "freed config");
    gls_display_close(d);
    gls_display_close(d);
    gls_display_close(NULL);
    CHECK(gls_config_choose(d, stereo, &c) == GLS_ERROR_INVALID_HANDLE, "closed display");
    return SUMMARY();
}

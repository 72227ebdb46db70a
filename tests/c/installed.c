/*
 * A program built against an installed glstereo with nothing but
 *     cc installed.c $(pkg-config --cflags --libs glstereo)
 * (no GL library of its own: GL functions come from gls_get_proc_address).
 * Headless (EGL): draws each eye in a colour of its own, swaps, and checks
 * both front buffers.
 */
#include <string.h>

#include <glstereo.h>

#include "check.h"

typedef void (*ClearColor)(float, float, float, float);
typedef void (*Clear)(unsigned);

#define W 8
#define H 4

int main(void)
{
    CHECK(strcmp(gls_version(), GLSTEREO_VERSION_STRING) == 0, "header %s, library %s",
          GLSTEREO_VERSION_STRING, gls_version());
    gls_display *d = NULL;
    gls_config *c = NULL;
    gls_surface *s = NULL;
    const int attribs[] = {4 /* GLX_RGBA */, 5 /* GLX_DOUBLEBUFFER */, 6 /* GLX_STEREO */, 0};
    if (gls_display_open(GLS_BACKEND_EGL, &d) != GLS_OK ||
        gls_config_choose(d, attribs, &c) != GLS_OK ||
        gls_surface_create(d, c, W, H, &s) != GLS_OK || gls_make_current(s) != GLS_OK) {
        CHECK(0, "set-up: %s", gls_last_error_message());
        return SUMMARY();
    }
    CHECK(gls_config_stereo(c) == GLS_STEREO_EMULATED, "emulated stereo");
    ClearColor clear_color;
    Clear clear;
    void *p = gls_get_proc_address("glClearColor");
    memcpy(&clear_color, &p, sizeof p);
    p = gls_get_proc_address("glClear");
    memcpy(&clear, &p, sizeof p);
    CHECK(clear_color != NULL && clear != NULL, "GL functions");

    gls_draw_buffer(0x0402 /* GL_BACK_LEFT */);
    clear_color(0.8f, 0.2f, 0.4f, 1.0f);
    clear(0x4000 /* GL_COLOR_BUFFER_BIT */);
    gls_draw_buffer(0x0403 /* GL_BACK_RIGHT */);
    clear_color(0.2f, 0.6f, 0.4f, 1.0f);
    clear(0x4000);
    CHECK(gls_swap_buffers(s) == GLS_OK, "%s", gls_last_error_message());

    unsigned char px[W * H * 4];
    CHECK(gls_surface_read_pixels(s, 0x0400 /* GL_FRONT_LEFT */, px, sizeof px) == GLS_OK,
          "read left");
    CHECK(px[0] == 204 && px[1] == 51 && px[2] == 102, "left eye %d,%d,%d", px[0], px[1], px[2]);
    CHECK(gls_surface_read_pixels(s, 0x0401 /* GL_FRONT_RIGHT */, px, sizeof px) == GLS_OK,
          "read right");
    CHECK(px[0] == 51 && px[1] == 153 && px[2] == 102, "right eye %d,%d,%d", px[0], px[1], px[2]);

    gls_make_current(NULL);
    gls_surface_destroy(s);
    gls_config_free(c);
    gls_display_close(d);
    return SUMMARY();
}

/* The IRIS GL compat header from C, one section per run (argv[1]):
 *   gdesc          getgdesc values; unknown inquiries give -1
 *   gdesc-off      the same with GLSTEREO_EMULATION=off: no stereo buffers
 *   monitor        getmonitor / setmonitor round trips; bad modes change nothing
 *   buffers        leftbuffer / rightbuffer / stereobuffer / gconfig reach
 *                  the buffers seed 002 describes (read back by pixels)
 *   transforms     viewport / window / translate are glViewport (+ scissor),
 *                  glFrustum and glTranslate
 *   eyes DIR       one frame with distinct colours in the STR_RECT rows,
 *                  saved as eyes in each monitor mode for the Rust side
 * Links -lGL (run with GLSTEREO_BACKEND=egl). */
#define _POSIX_C_SOURCE 200809L
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <glstereo/irisgl.h>

#include "check.h"

#define GD_XMMAX 2 /* a real SGI inquiry the emulation does not answer */
#define HZ50 24    /* a real SGI monitor type the emulation does not offer */

static int has(const char *needle) { return strstr(gls_last_error_message(), needle) != NULL; }

static void clear_to(float r, float g, float b) {
    glClearColor(r, g, b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

/* The colour of pixel (0, 0) of a buffer of the current window's surface. */
static unsigned read_rgb(gls_surface *s, GLenum buffer) {
    static unsigned char px[16 * 16 * 4];
    if (gls_surface_read_pixels(s, buffer, px, sizeof px) != GLS_OK) return 0xdeadu;
    return (unsigned)px[0] << 16 | (unsigned)px[1] << 8 | px[2];
}

static int gdesc(int emulation_off) {
    CHECK(getgdesc(GD_XPMAX) == 1280 && getgdesc(GD_YPMAX) == 1024, "%ldx%ld", getgdesc(GD_XPMAX),
          getgdesc(GD_YPMAX));
    CHECK(getgdesc(GD_STEREO) == 1, "GD_STEREO %ld", getgdesc(GD_STEREO));
    CHECK(getgdesc(GD_STEREO_IN_WINDOW) == (emulation_off ? 0 : 1), "GD_STEREO_IN_WINDOW %ld",
          getgdesc(GD_STEREO_IN_WINDOW));
    CHECK(getgdesc(GD_XMMAX) == -1, "unanswered inquiry");
    CHECK(has("GD_STEREO_IN_WINDOW"), "%s", gls_last_error_message());
    CHECK(gls_irisgl_getgdesc(GD_STEREO, NULL) == GLS_ERROR_NULL_POINTER, "NULL value_out");
    CHECK(gls_screen_set_size(640, 480) == GLS_OK, "640x480 screen");
    CHECK(getgdesc(GD_XPMAX) == 640 && getgdesc(GD_YPMAX) == 480, "the screen's size");

    long win = winopen("gdesc");
    CHECK(win >= 1, "winopen: %ld", win);
    gls_surface *s = glstereo_irisgl_surface(win);
    uint32_t w = 0, h = 0;
    CHECK(s && gls_surface_get_size(s, &w, &h) == GLS_OK && w == 640 && h == 480, "full screen %ux%u", w, h);
    CHECK(getgdesc(GD_STEREO_IN_WINDOW) == (emulation_off ? 0 : 1), "for the current window");
    stereobuffer();
    CHECK(gls_irisgl_gconfig() == (emulation_off ? GLS_ERROR_INVALID_OPERATION : GLS_OK), "gconfig: %s",
          gls_last_error_message());
    if (emulation_off) CHECK(has("GLSTEREO_EMULATION"), "%s", gls_last_error_message());
    winclose(win);
    return SUMMARY();
}

static int monitor(void) {
    const long previous = getmonitor();
    CHECK(previous == HZ60, "initial mode %ld", previous);
    const short modes[] = {STR_RECT, STR_TOP, STR_BOT, HZ72, HZ60};
    for (unsigned k = 0; k < sizeof modes / sizeof modes[0]; ++k) {
        setmonitor(modes[k]);
        CHECK(getmonitor() == modes[k], "setmonitor(%d) then getmonitor() = %ld", modes[k], getmonitor());
    }
    setmonitor(STR_RECT);
    setmonitor((short)previous);
    CHECK(getmonitor() == HZ60, "the previous mode is restored");
    setmonitor(HZ72);
    CHECK(gls_irisgl_setmonitor(HZ50) == GLS_ERROR_INVALID_ENUM, "HZ50 is not offered");
    CHECK(has("STR_RECT (15)"), "%s", gls_last_error_message());
    CHECK(getmonitor() == HZ72, "a bad mode changes nothing");
    int32_t m;
    CHECK(gls_irisgl_getmonitor(NULL) == GLS_ERROR_NULL_POINTER && gls_irisgl_getmonitor(&m) == GLS_OK && m == HZ72,
          "getmonitor through the ABI");

    /* A window one row high cannot hold STR_RECT's bands: refused, unchanged. */
    prefposition(0, 9, 0, 0);
    long win = winopen("one row");
    CHECK(win >= 1, "winopen 10x1");
    CHECK(gls_irisgl_setmonitor(STR_RECT) == GLS_ERROR_INVALID_VALUE, "STR_RECT on a 1-row window");
    CHECK(getmonitor() == HZ72, "unchanged");
    winclose(win);
    CHECK(gls_irisgl_prefposition(5, 4, 0, 0) == GLS_ERROR_INVALID_VALUE, "x2 < x1");
    setmonitor(HZ60);
    return SUMMARY();
}

static int buffers(void) {
    const unsigned black = 0x000000, red = 0xff0000, green = 0x00ff00;
    prefposition(0, 15, 0, 15);
    long win = winopen("buffers");
    gls_surface *s = glstereo_irisgl_surface(win);
    CHECK(s != NULL, "surface");
    if (!s) return SUMMARY();

    /* A new window is mono and single-buffered: drawing reaches both eyes' front buffers. */
    clear_to(1, 0, 0);
    CHECK(read_rgb(s, GL_FRONT_LEFT) == red && read_rgb(s, GL_FRONT_RIGHT) == red, "mono draws both eyes");

    /* stereobuffer() waits for gconfig(); then the left eye is the default. */
    stereobuffer();
    doublebuffer();
    CHECK(gls_draw_buffer(GL_BACK) == GLS_OK, "GL_BACK");
    clear_to(0, 0, 0);
    gconfig();
    clear_to(0, 1, 0);
    CHECK(read_rgb(s, GL_BACK_LEFT) == green && read_rgb(s, GL_BACK_RIGHT) == black, "left is the initial default");

    /* All four combinations. */
    for (int l = 0; l <= 1; ++l) {
        for (int r = 0; r <= 1; ++r) {
            leftbuffer(TRUE);
            rightbuffer(TRUE);
            clear_to(0, 0, 0);
            leftbuffer(l);
            rightbuffer(r);
            clear_to(1, 0, 0);
            unsigned bl = read_rgb(s, GL_BACK_LEFT), br = read_rgb(s, GL_BACK_RIGHT);
            CHECK(bl == (l ? red : black) && br == (r ? red : black),
                  "leftbuffer(%d) rightbuffer(%d): back-left %06x, back-right %06x", l, r, bl, br);
        }
    }

    /* Single-buffered stereo selects the front buffers. */
    leftbuffer(TRUE);
    rightbuffer(TRUE);
    singlebuffer();
    gconfig();
    clear_to(0, 0, 0);
    leftbuffer(FALSE);
    rightbuffer(TRUE);
    clear_to(0, 1, 0);
    CHECK(read_rgb(s, GL_FRONT_LEFT) == black && read_rgb(s, GL_FRONT_RIGHT) == green, "front right only");

    /* monobuffer() + gconfig(): both eyes again, whatever the flags say. */
    monobuffer();
    gconfig();
    clear_to(1, 0, 0);
    CHECK(read_rgb(s, GL_FRONT_LEFT) == red && read_rgb(s, GL_FRONT_RIGHT) == red, "mono again");

    /* Without a current window these calls fail and say what to do. */
    gls_make_current(NULL);
    CHECK(gls_irisgl_leftbuffer(true) == GLS_ERROR_INVALID_OPERATION, "no current window");
    CHECK(has("winopen"), "%s", gls_last_error_message());
    CHECK(gls_irisgl_gconfig() == GLS_ERROR_INVALID_OPERATION, "gconfig without a window");
    winclose(win);
    CHECK(gls_irisgl_winclose((int32_t)win) == GLS_ERROR_INVALID_HANDLE, "closed twice");
    gls_surface *gone = NULL;
    CHECK(gls_irisgl_surface((int32_t)win, &gone) == GLS_ERROR_INVALID_HANDLE && !gone, "closed window");
    return SUMMARY();
}

static int same_matrix(GLenum which, const double *want) {
    double m[16];
    glGetDoublev(which, m);
    for (int k = 0; k < 16; ++k)
        if (fabs(m[k] - want[k]) > 1e-6 * (1 + fabs(want[k]))) return 0;
    return 1;
}

static int transforms(void) {
    prefposition(0, 63, 0, 31);
    long win = winopen("transforms");
    CHECK(win >= 1, "winopen");
    GLint box[4];
    viewport(0, 9, 0, 4);
    glGetIntegerv(GL_VIEWPORT, box);
    CHECK(box[0] == 0 && box[1] == 0 && box[2] == 10 && box[3] == 5, "viewport %d %d %d %d", box[0], box[1],
          box[2], box[3]);
    glGetIntegerv(GL_SCISSOR_BOX, box);
    CHECK(box[2] == 10 && box[3] == 5 && glIsEnabled(GL_SCISSOR_TEST), "the screenmask follows the viewport");
    viewport(0, 63, 0, 31);
    CHECK(gls_irisgl_viewport(5, 4, 0, 0) == GLS_ERROR_INVALID_VALUE, "right < left");
    glGetIntegerv(GL_VIEWPORT, box);
    CHECK(box[2] == 64 && box[3] == 32, "a bad viewport changes nothing");

    /* window() is glFrustum into GL_PROJECTION; the matrix mode stays. */
    double want[16];
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.6, 0.7, -0.5, 0.5, 1.0, 10.0);
    glGetDoublev(GL_PROJECTION_MATRIX, want);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    window(-0.6f, 0.7f, -0.5f, 0.5f, 1.0f, 10.0f);
    CHECK(same_matrix(GL_PROJECTION_MATRIX, want), "window() = glFrustum");
    GLint mode = 0;
    glGetIntegerv(GL_MATRIX_MODE, &mode);
    CHECK(mode == GL_MODELVIEW, "matrix mode unchanged");
    CHECK(gls_irisgl_window(-1, 1, -1, 1, 0, 10) == GLS_ERROR_INVALID_VALUE, "near 0");
    CHECK(same_matrix(GL_PROJECTION_MATRIX, want), "a bad window() changes nothing");

    /* translate() is glTranslate of the current matrix. */
    glLoadIdentity();
    glRotatef(30, 0, 1, 0);
    glTranslated(0.25, 0.0, -2.0);
    glGetDoublev(GL_MODELVIEW_MATRIX, want);
    glLoadIdentity();
    glRotatef(30, 0, 1, 0);
    translate(0.25f, 0.0f, -2.0f);
    CHECK(same_matrix(GL_MODELVIEW_MATRIX, want), "translate() = glTranslate");
    winclose(win);
    CHECK(gls_irisgl_translate(1, 0, 0) == GLS_ERROR_NO_CURRENT_SURFACE, "no current surface");
    return SUMMARY();
}

/* Paints the current eye buffers: SGI's three bands of 1024 rows. */
static void bands(float top_r, float top_g, float top_b, float bot_r, float bot_g, float bot_b) {
    viewport(0, 1279, 532, 1023);
    clear_to(top_r, top_g, top_b);
    viewport(0, 1279, 492, 531);
    clear_to(1, 0, 1); /* the 40 rows lost in blanking: magenta */
    viewport(0, 1279, 0, 491);
    clear_to(bot_r, bot_g, bot_b);
}

static int eyes(const char *dir) {
    static const struct {
        short mode;
        const char *name;
    } modes[] = {{STR_RECT, "str_rect"}, {STR_TOP, "str_top"}, {STR_BOT, "str_bot"}, {HZ60, "hz60"}};
    const long previous = getmonitor();
    long win = winopen("eyes");
    gls_surface *s = glstereo_irisgl_surface(win);
    CHECK(s != NULL, "surface");
    if (!s) return SUMMARY();
    stereobuffer(); /* single-buffered: drawing goes straight to the displayed buffers */
    gconfig();
    leftbuffer(TRUE);
    rightbuffer(FALSE);
    bands(0, 1, 0, 0, 0, 1); /* left buffer: green above, blue below */
    leftbuffer(FALSE);
    rightbuffer(TRUE);
    bands(1, 1, 0, 0, 1, 1); /* right buffer: yellow above, cyan below */
    for (unsigned k = 0; k < sizeof modes / sizeof modes[0]; ++k) {
        char left[4096], right[4096];
        setmonitor(modes[k].mode);
        snprintf(left, sizeof left, "%s/%s-left.png", dir, modes[k].name);
        snprintf(right, sizeof right, "%s/%s-right.png", dir, modes[k].name);
        CHECK(gls_surface_save_png(s, GLS_IMAGE_LEFT, left) == GLS_OK &&
                  gls_surface_save_png(s, GLS_IMAGE_RIGHT, right) == GLS_OK,
              "%s: %s", modes[k].name, gls_last_error_message());
    }
    setmonitor((short)previous);
    CHECK(getmonitor() == HZ60, "restored");
    winclose(win);
    return SUMMARY();
}

int main(int argc, char **argv) {
    const char *section = argc > 1 ? argv[1] : "";
    if (strcmp(section, "gdesc") == 0) return gdesc(0);
    if (strcmp(section, "gdesc-off") == 0) return gdesc(1);
    if (strcmp(section, "monitor") == 0) return monitor();
    if (strcmp(section, "buffers") == 0) return buffers();
    if (strcmp(section, "transforms") == 0) return transforms();
    if (strcmp(section, "eyes") == 0 && argc == 3) return eyes(argv[2]);
    fprintf(stderr, "usage: %s gdesc | gdesc-off | monitor | buffers | transforms | eyes DIR\n", argv[0]);
    return 2;
}

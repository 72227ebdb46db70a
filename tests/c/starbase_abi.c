/* The Starbase compat header from C: gopen / gescape / gclose answer misuse
 * with -1 and the documented errno, leave a message, and change nothing;
 * gescape(STEREO) switches sync-doubling. Images for the Rust side to
 * check are written into argv[1]. Links -lGL (run with GLSTEREO_BACKEND=egl). */
#define _POSIX_C_SOURCE 200809L
#include <GL/gl.h>
#include <stdio.h>
#include <string.h>

#include <glstereo/starbase.h>

#include "check.h"

#define GLX_RGBA 4
#define GLX_DOUBLEBUFFER 5

static int has(const char *needle) { return strstr(gls_last_error_message(), needle) != NULL; }

static int save(gls_surface *s, const char *dir, const char *name) {
    char left[4096], right[4096];
    snprintf(left, sizeof left, "%s/%s-left.png", dir, name);
    snprintf(right, sizeof right, "%s/%s-right.png", dir, name);
    return gls_surface_save_png(s, GLS_IMAGE_LEFT, left) == GLS_OK &&
           gls_surface_save_png(s, GLS_IMAGE_RIGHT, right) == GLS_OK;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
        return 2;
    }
    const char *dir = argv[1];
    gescape_arg on, off, arg2;
    memset(&on, 0, sizeof on);
    memset(&off, 0, sizeof off);
    on.i[0] = TRUE;
    off.i[0] = FALSE;
    CHECK(sizeof(gescape_arg) == 256, "gescape_arg is %zu bytes, HP's is 256", sizeof(gescape_arg));

    /* gopen: only output devices; the screen's size is the emulated mode's. */
    errno = 0;
    CHECK(gopen("/dev/crt", INDEV, NULL, INIT) == -1 && errno == EINVAL, "INDEV: errno %d", errno);
    CHECK(has("OUTDEV"), "%s", gls_last_error_message());
    CHECK(gls_starbase_open(OUTDEV, NULL) == GLS_ERROR_NULL_POINTER, "NULL fildes_out");
    uint32_t sw = 0, sh = 0;
    CHECK(gls_screen_get_size(&sw, &sh) == GLS_OK && sw == 1280 && sh == 1024, "default screen %ux%u", sw, sh);
    CHECK(gls_screen_set_size(0, 32) == GLS_ERROR_INVALID_VALUE, "0x32 screen");
    CHECK(gls_screen_set_size(64, 32) == GLS_OK, "64x32 screen");
    int fildes = gopen("/dev/crt", OUTDEV, NULL, INIT | THREE_D);
    CHECK(fildes >= 3, "gopen: %d (%s)", fildes, gls_last_error_message());
    if (fildes < 0) return SUMMARY();
    gls_surface *s = NULL;
    CHECK(gls_starbase_surface(fildes, &s) == GLS_OK && s, "surface: %s", gls_last_error_message());
    uint32_t w = 0, h = 0;
    CHECK(gls_surface_get_size(s, &w, &h) == GLS_OK && w == 64 && h == 32, "size %ux%u", w, h);
    int32_t same = -1;
    CHECK(gls_starbase_fildes(s, &same) == GLS_OK && same == fildes, "one surface, one descriptor: %d", same);

    /* A frame: upper half white, lower half black (gopen made it current). */
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 16, 64, 16);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glScissor(0, 0, 64, 16);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    CHECK(gls_swap_buffers(s) == GLS_OK, "swap");

    /* Sync-doubling on; then every kind of bad call fails and changes nothing. */
    CHECK(gescape(fildes, STEREO, &on, &arg2) == 0, "STEREO on: %s", gls_last_error_message());
    errno = 0;
    CHECK(gescape(fildes + 100, STEREO, &off, &arg2) == -1 && errno == EBADF, "unknown fildes: errno %d", errno);
    CHECK(has("fildes"), "%s", gls_last_error_message());
    errno = 0;
    CHECK(gescape(fildes, 4242, &off, &arg2) == -1 && errno == EINVAL, "unknown op: errno %d", errno);
    CHECK(has("STEREO"), "%s", gls_last_error_message());
    errno = 0;
    CHECK(gescape(-5, 4242, &off, NULL) == -1 && errno == EBADF, "fildes is checked first: errno %d", errno);
    errno = 0;
    CHECK(gescape(fildes, STEREO, NULL, NULL) == -1 && errno == EFAULT, "NULL arg1: errno %d", errno);
    CHECK(has("arg1"), "%s", gls_last_error_message());
    CHECK(save(s, dir, "on"), "save: %s", gls_last_error_message());

    /* Off; a bad call does not turn it back on. */
    CHECK(gescape(fildes, STEREO, &off, NULL) == 0, "STEREO off");
    CHECK(gescape(fildes, STEREO + 1, &on, NULL) == -1 && errno == EINVAL, "unknown op");
    CHECK(save(s, dir, "off"), "save: %s", gls_last_error_message());

    /* A descriptor for a surface the program made: it dies with the surface. */
    const int attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, 0};
    gls_display *d = NULL;
    gls_config *c = NULL;
    gls_surface *own = NULL;
    CHECK(gls_display_open(GLS_BACKEND_AUTO, &d) == GLS_OK, "display");
    CHECK(gls_config_choose(d, attribs, &c) == GLS_OK, "config");
    CHECK(gls_surface_create(d, c, 8, 8, &own) == GLS_OK, "surface");
    int32_t f2 = -1;
    CHECK(gls_starbase_fildes(own, &f2) == GLS_OK && f2 >= 3 && f2 != fildes, "own fildes %d", f2);
    CHECK(gls_starbase_fildes(NULL, &f2) == GLS_ERROR_NULL_POINTER, "NULL surface");
    CHECK(gescape(f2, STEREO, &on, NULL) == 0, "own surface on: %s", gls_last_error_message());
    gls_surface_destroy(own);
    errno = 0;
    CHECK(gescape(f2, STEREO, &off, NULL) == -1 && errno == EBADF, "destroyed surface: errno %d", errno);
    gls_surface *gone = NULL;
    CHECK(gls_starbase_surface(f2, &gone) == GLS_ERROR_INVALID_HANDLE && gone == NULL, "destroyed surface");
    CHECK(gclose(f2) == 0, "gclose of a borrowed descriptor");
    gls_config_free(c);
    gls_display_close(d);

    /* gclose ends the descriptor. */
    CHECK(gclose(fildes) == 0, "gclose: %s", gls_last_error_message());
    errno = 0;
    CHECK(gclose(fildes) == -1 && errno == EBADF, "second gclose: errno %d", errno);
    errno = 0;
    CHECK(gescape(fildes, STEREO, &on, NULL) == -1 && errno == EBADF, "after gclose: errno %d", errno);

    /* A one-row screen cannot be split into two eyes. */
    CHECK(gls_screen_set_size(8, 1) == GLS_OK, "8x1 screen");
    int f3 = gopen("/dev/crt", OUTDEV, NULL, INIT);
    CHECK(f3 >= 3, "gopen 8x1");
    errno = 0;
    CHECK(gescape(f3, STEREO, &on, NULL) == -1 && errno == EINVAL, "1 row: errno %d", errno);
    CHECK(has("too small"), "%s", gls_last_error_message());
    CHECK(gclose(f3) == 0, "gclose 8x1");
    return SUMMARY();
}

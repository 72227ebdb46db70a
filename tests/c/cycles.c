/* Long runs for the leak and memory tests (tests/leaks.rs).
 *
 *   cycles BACKEND N FRAMES  N times: display open -> config -> surface
 *                            create -> make current -> FRAMES frames ->
 *                            release -> destroy -> free -> close; every
 *                            frame's eyes are checked in the pixels;
 *                            prints "rss CYCLE KIB" every 100 cycles.
 *   frames BACKEND N DIR     one surface: a composite in every output mode
 *                            (warm-up), then N frames, each checked, with
 *                            a composite written to DIR every 100 frames
 *                            (the modes in turn); prints "rss FRAME KIB"
 *                            every 500 frames.
 *
 * Resident memory comes from /proc/self/statm.
 *
 * BACKEND is egl or osmesa. GL is reached through gls_get_proc_address, so
 * the program links only libglstereo and one binary serves both backends.
 * Exit status 0 only if every check passed. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "glstereo.h"

#define GL_COLOR_BUFFER_BIT 0x00004000u
#define GL_FRONT_LEFT 0x0400u
#define GL_FRONT_RIGHT 0x0401u
#define GL_BACK_LEFT 0x0402u
#define GL_BACK_RIGHT 0x0403u

typedef void (*clear_color_fn)(float, float, float, float);
typedef void (*clear_fn)(unsigned);

/* A GL function of the current surface (ISO C has no object-to-function
 * pointer cast; POSIX guarantees the representations agree). */
#define GL_PROC(type, var, name)                       \
    type var;                                          \
    do {                                               \
        void *p_ = gls_get_proc_address(name);         \
        memcpy(&var, &p_, sizeof var);                 \
    } while (0)

enum { W = 64, H = 48 };

static int fail(const char *what) {
    fprintf(stderr, "%s: %s\n", what, gls_last_error_message());
    return 1;
}

/* The colour of one eye in one frame: distinct per eye and frame. */
static void eye_color(int frame, int right, unsigned char rgb[3]) {
    rgb[0] = (unsigned char)(right ? 200 : 40);
    rgb[1] = (unsigned char)((frame * 37) % 256);
    rgb[2] = (unsigned char)(right ? 30 : 220);
}

/* Draws frame `frame` (each eye its own colour), swaps, and checks both
 * front buffers' centre pixels. */
static int frame(gls_surface *s, int frame, unsigned char *px) {
    GL_PROC(clear_color_fn, clear_color, "glClearColor");
    GL_PROC(clear_fn, clear, "glClear");
    if (!clear_color || !clear) return fail("gls_get_proc_address");
    for (int right = 0; right < 2; ++right) {
        unsigned char c[3];
        eye_color(frame, right, c);
        if (gls_draw_buffer(right ? GL_BACK_RIGHT : GL_BACK_LEFT)) return fail("gls_draw_buffer");
        clear_color(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f);
        clear(GL_COLOR_BUFFER_BIT);
    }
    if (gls_swap_buffers(s)) return fail("gls_swap_buffers");
    for (int right = 0; right < 2; ++right) {
        unsigned char c[3];
        eye_color(frame, right, c);
        if (gls_surface_read_pixels(s, right ? GL_FRONT_RIGHT : GL_FRONT_LEFT, px, W * H * 4))
            return fail("gls_surface_read_pixels");
        const unsigned char *p = px + ((H / 2) * W + W / 2) * 4;
        for (int k = 0; k < 3; ++k) {
            if (abs(p[k] - c[k]) > 1) {
                fprintf(stderr, "frame %d %s eye: pixel %u,%u,%u, wanted %u,%u,%u\n", frame,
                        right ? "right" : "left", p[0], p[1], p[2], c[0], c[1], c[2]);
                return 1;
            }
        }
    }
    return 0;
}

static const int ATTRIBS[] = {4 /* GLX_RGBA */, 5 /* GLX_DOUBLEBUFFER */, 6 /* GLX_STEREO */,
                              12 /* GLX_DEPTH_SIZE */, 24, 0};

static long rss_kib(void) {
    FILE *f = fopen("/proc/self/statm", "r");
    long size = 0, resident = 0;
    if (!f) return -1;
    if (fscanf(f, "%ld %ld", &size, &resident) != 2) resident = -1;
    fclose(f);
    return resident < 0 ? -1 : resident * (sysconf(_SC_PAGESIZE) / 1024);
}

static int cycles(uint32_t backend, long n, int frames) {
    unsigned char *px = malloc(W * H * 4);
    if (!px) return 1;
    for (long i = 0; i < n; ++i) {
        gls_display *d;
        gls_config *c;
        gls_surface *s;
        if (gls_display_open(backend, &d)) return fail("gls_display_open");
        if (gls_config_choose(d, ATTRIBS, &c)) return fail("gls_config_choose");
        if (gls_surface_create(d, c, W, H, &s)) return fail("gls_surface_create");
        if (gls_make_current(s)) return fail("gls_make_current");
        for (int f = 0; f < frames; ++f)
            if (frame(s, (int)(i + f), px)) return 1;
        if (gls_make_current(NULL)) return fail("gls_make_current(NULL)");
        gls_surface_destroy(s);
        gls_config_free(c);
        gls_display_close(d);
        if ((i + 1) % 100 == 0) {
            printf("rss %ld %ld\n", i + 1, rss_kib());
            fflush(stdout);
        }
    }
    free(px);
    printf("%ld cycles of %d frames\n", n, frames);
    return 0;
}

static int frames(uint32_t backend, long n, const char *dir) {
    unsigned char *px = malloc(W * H * 4);
    gls_display *d;
    gls_config *c;
    gls_surface *s;
    char path[4096];
    if (!px) return 1;
    snprintf(path, sizeof path, "%s/composite.png", dir);
    if (gls_display_open(backend, &d)) return fail("gls_display_open");
    if (gls_config_choose(d, ATTRIBS, &c)) return fail("gls_config_choose");
    if (gls_surface_create(d, c, W, H, &s)) return fail("gls_surface_create");
    if (gls_make_current(s)) return fail("gls_make_current");
    /* Warm-up: one composite in every output mode, so the compositor has
     * made everything it keeps (programs, textures) before measuring. */
    if (frame(s, 0, px)) return 1;
    for (uint32_t m = 0; m < GLS_OUTPUT_COUNT; ++m) {
        if (gls_surface_set_output(s, m)) return fail("gls_surface_set_output");
        if (gls_surface_save_png(s, GLS_IMAGE_COMPOSITE, path)) return fail("gls_surface_save_png");
    }
    for (long f = 1; f <= n; ++f) {
        if (frame(s, (int)f, px)) return 1;
        if (f % 100 == 0) {
            /* A composite every 100 frames, the modes in turn. */
            if (gls_surface_set_output(s, (uint32_t)(f / 100) % GLS_OUTPUT_COUNT))
                return fail("gls_surface_set_output");
            if (gls_surface_save_png(s, GLS_IMAGE_COMPOSITE, path)) return fail("gls_surface_save_png");
        }
        if (f % 500 == 0) {
            printf("rss %ld %ld\n", f, rss_kib());
            fflush(stdout);
        }
    }
    gls_make_current(NULL);
    gls_surface_destroy(s);
    gls_config_free(c);
    gls_display_close(d);
    free(px);
    return 0;
}

int main(int argc, char **argv) {
    if (argc < 4) {
        fprintf(stderr, "usage: %s cycles egl|osmesa N FRAMES | frames egl|osmesa N DIR\n", argv[0]);
        return 2;
    }
    uint32_t backend = strcmp(argv[2], "osmesa") == 0 ? GLS_BACKEND_OSMESA : GLS_BACKEND_EGL;
    long n = atol(argv[3]);
    if (strcmp(argv[1], "cycles") == 0 && argc == 5) return cycles(backend, n, atoi(argv[4]));
    if (strcmp(argv[1], "frames") == 0 && argc == 5) return frames(backend, n, argv[4]);
    fprintf(stderr, "bad arguments\n");
    return 2;
}

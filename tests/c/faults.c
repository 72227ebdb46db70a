/* Faults from outside the program (tests/faults.rs). Each subcommand does
 * one thing that meets the fault and prints what the library said:
 *
 *   "result <GLS_ERROR_NAME or GLS_OK>" and "message <text>" lines,
 *
 * then exits 0 — a crash, abort or exit() inside the library would show as
 * a signal or another status. The Rust test sets up the fault (a library
 * path without libEGL, $DISPLAY pointing nowhere, a full disk, …) and
 * checks the lines.
 *
 *   open auto|glx|egl|osmesa        gls_display_open
 *   surface W H                     display + config + surface (GLSTEREO_BACKEND)
 *   capture PATH [FSIZE_LIMIT]      a noisy 256x256 stereo frame saved as a
 *                                   side-by-side composite to PATH; with a
 *                                   limit, RLIMIT_FSIZE (bytes) is set first
 *                                   and SIGXFSZ ignored, so the write fails
 *                                   midway with EFBIG
 *   memory W H EXTRA_MIB            a W x H surface with only EXTRA MiB of
 *                                   address space left (RLIMIT_AS)
 *   composite W H MODE PATH         a W x H surface's composite in MODE saved
 *   drawbuffers EXTRA_MIB           gls_draw_buffers(INT_MAX, …) with EXTRA MiB
 *                                   of address space left
 *   readback W H EXTRA_MIB          a mono W x H surface captured and read back
 *                                   with EXTRA MiB of address space left
 *
 * Links only libglstereo; GL through gls_get_proc_address. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "glstereo.h"

#define GL_BACK_LEFT 0x0402u
#define GL_BACK_RIGHT 0x0403u
#define GL_RGBA 0x1908u
#define GL_UNSIGNED_BYTE 0x1401u

typedef void (*draw_pixels_fn)(int, int, unsigned, unsigned, const void *);
typedef void (*raster_pos_fn)(int, int);

static const char *name(gls_result r) {
    static const char *names[] = {"GLS_OK", "GLS_ERROR_NULL_POINTER", "GLS_ERROR_INVALID_ENUM",
                                  "GLS_ERROR_INVALID_VALUE", "GLS_ERROR_INVALID_OPERATION",
                                  "GLS_ERROR_NO_CURRENT_SURFACE", "GLS_ERROR_BACKEND_UNAVAILABLE",
                                  "GLS_ERROR_NO_MATCHING_CONFIG", "GLS_ERROR_OUT_OF_MEMORY", "GLS_ERROR_IO",
                                  "GLS_ERROR_PANIC", "GLS_ERROR_INVALID_HANDLE", "GLS_ERROR_DISPLAY_LOST",
                                  "GLS_ERROR_GL"};
    return r < sizeof names / sizeof names[0] ? names[r] : "unknown";
}

/* Prints the outcome of one call; returns r. */
static gls_result report(const char *what, gls_result r) {
    printf("%s result %s\n", what, name(r));
    if (r != GLS_OK) printf("%s message %s\n", what, gls_last_error_message());
    fflush(stdout);
    return r;
}

static uint32_t backend_of(const char *s) {
    if (strcmp(s, "glx") == 0) return GLS_BACKEND_GLX;
    if (strcmp(s, "egl") == 0) return GLS_BACKEND_EGL;
    if (strcmp(s, "osmesa") == 0) return GLS_BACKEND_OSMESA;
    return GLS_BACKEND_AUTO;
}

/* The process's address space in MiB (VmSize). */
static long vm_mib(void) {
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long kib = 0;
    if (!f) return 0;
    while (fgets(line, sizeof line, f))
        if (strncmp(line, "VmSize:", 7) == 0) kib = atol(line + 7);
    fclose(f);
    return kib / 1024;
}

static const int ATTRIBS[] = {4 /* GLX_RGBA */, 5 /* GLX_DOUBLEBUFFER */, 6 /* GLX_STEREO */, 0};

static gls_result open_surface(uint32_t w, uint32_t h, gls_display **d, gls_config **c, gls_surface **s) {
    if (report("open", gls_display_open(GLS_BACKEND_AUTO, d))) return GLS_ERROR_BACKEND_UNAVAILABLE;
    uint32_t backend = 0;
    gls_display_get_backend(*d, &backend);
    printf("backend %u\n", backend);
    if (report("config", gls_config_choose(*d, ATTRIBS, c))) return GLS_ERROR_NO_MATCHING_CONFIG;
    return report("surface", gls_surface_create(*d, *c, w, h, s));
}

/* Fills the current surface's back buffers with noise (incompressible). */
static void noise(uint32_t w, uint32_t h) {
    unsigned char *px = malloc((size_t)w * h * 4);
    unsigned seed = 12345;
    void *p = gls_get_proc_address("glDrawPixels"), *q = gls_get_proc_address("glWindowPos2i");
    draw_pixels_fn draw_pixels;
    raster_pos_fn window_pos;
    memcpy(&draw_pixels, &p, sizeof p);
    memcpy(&window_pos, &q, sizeof q);
    for (int eye = 0; eye < 2; ++eye) {
        for (size_t i = 0; i < (size_t)w * h * 4; ++i) {
            seed = seed * 1103515245u + 12345u;
            px[i] = (unsigned char)(seed >> 16);
        }
        gls_draw_buffer(eye ? GL_BACK_RIGHT : GL_BACK_LEFT);
        window_pos(0, 0);
        draw_pixels((int)w, (int)h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    }
    free(px);
}

int main(int argc, char **argv) {
    if (argc < 2) return 2;
    const char *cmd = argv[1];
    if (strcmp(cmd, "open") == 0 && argc == 3) {
        gls_display *d = NULL;
        if (report("open", gls_display_open(backend_of(argv[2]), &d)) == GLS_OK) {
            uint32_t b = 0;
            gls_display_get_backend(d, &b);
            printf("backend %u\n", b);
            gls_display_close(d);
        }
        /* The process goes on: the library still answers. */
        report("after", gls_screen_set_size(640, 480));
        return 0;
    }
    if (strcmp(cmd, "memory") == 0 && argc == 5) {
        gls_display *d = NULL;
        gls_config *c = NULL;
        gls_surface *warm = NULL, *s = NULL;
        /* A small surface first, so the driver is loaded and running; then
         * only EXTRA MiB more address space for the big one. */
        if (open_surface(16, 16, &d, &c, &warm) != GLS_OK) return 0;
        struct rlimit lim;
        lim.rlim_cur = lim.rlim_max = (rlim_t)(vm_mib() + atol(argv[4])) << 20;
        setrlimit(RLIMIT_AS, &lim);
        report("big", gls_surface_create(d, c, (uint32_t)atol(argv[2]), (uint32_t)atol(argv[3]), &s));
        gls_surface_destroy(s);
        report("current", gls_make_current(warm));
        report("swap", gls_swap_buffers(warm));
        gls_make_current(NULL);
        gls_surface_destroy(warm);
        gls_config_free(c);
        gls_display_close(d);
        return 0;
    }
    if (strcmp(cmd, "surface") == 0 && argc == 4) {
        gls_display *d = NULL;
        gls_config *c = NULL;
        gls_surface *s = NULL;
        if (open_surface((uint32_t)atol(argv[2]), (uint32_t)atol(argv[3]), &d, &c, &s) == GLS_OK) {
            report("current", gls_make_current(s));
            report("swap", gls_swap_buffers(s));
            gls_make_current(NULL);
            gls_surface_destroy(s);
        }
        /* A small surface still works afterwards. */
        gls_surface *small = NULL;
        unsetenv("GLSTEREO_MODE");
        if (d && c && report("small", gls_surface_create(d, c, 16, 16, &small)) == GLS_OK)
            gls_surface_destroy(small);
        gls_config_free(c);
        gls_display_close(d);
        return 0;
    }
    if (strcmp(cmd, "capture") == 0 && (argc == 3 || argc == 4)) {
        gls_display *d = NULL;
        gls_config *c = NULL;
        gls_surface *s = NULL;
        if (open_surface(256, 256, &d, &c, &s) != GLS_OK) return 0;
        report("current", gls_make_current(s));
        noise(256, 256);
        report("swap", gls_swap_buffers(s));
        report("output", gls_surface_set_output(s, GLS_OUTPUT_SIDE_BY_SIDE));
        if (argc == 4) {
            struct rlimit lim;
            signal(SIGXFSZ, SIG_IGN);
            lim.rlim_cur = lim.rlim_max = (rlim_t)atol(argv[3]);
            setrlimit(RLIMIT_FSIZE, &lim);
        }
        report("capture", gls_surface_save_png(s, GLS_IMAGE_COMPOSITE, argv[2]));
        report("left", gls_surface_save_png(s, GLS_IMAGE_LEFT, argv[2]));
        gls_make_current(NULL);
        gls_surface_destroy(s);
        gls_config_free(c);
        gls_display_close(d);
        return 0;
    }
    if (strcmp(cmd, "drawbuffers") == 0 && argc == 3) {
        gls_display *d = NULL;
        gls_config *c = NULL;
        gls_surface *s = NULL;
        uint32_t bufs[9] = {0};
        struct rlimit lim;
        if (open_surface(16, 16, &d, &c, &s) != GLS_OK) return 0;
        report("current", gls_make_current(s));
        lim.rlim_cur = lim.rlim_max = (rlim_t)(vm_mib() + atol(argv[2])) << 20;
        setrlimit(RLIMIT_AS, &lim);
        /* A count far beyond any driver's limit (the array cannot hold it). */
        report("drawbuffers", gls_draw_buffers(2147483647, bufs));
        printf("gl error 0x%x\n", gls_get_error());
        gls_make_current(NULL);
        gls_surface_destroy(s);
        gls_config_free(c);
        gls_display_close(d);
        return 0;
    }
    if (strcmp(cmd, "readback") == 0 && argc == 5) {
        /* A mono single-buffered surface (one colour buffer), then reading
         * it back with only EXTRA MiB of address space left. */
        static const int mono[] = {4 /* GLX_RGBA */, 0};
        gls_display *d = NULL;
        gls_config *c = NULL;
        gls_surface *s = NULL;
        uint32_t w = (uint32_t)atol(argv[2]), h = (uint32_t)atol(argv[3]);
        if (report("open", gls_display_open(GLS_BACKEND_AUTO, &d)) ||
            report("config", gls_config_choose(d, mono, &c)) ||
            report("surface", gls_surface_create(d, c, w, h, &s)))
            return 0;
        report("output", gls_surface_set_output(s, GLS_OUTPUT_SIDE_BY_SIDE));
        size_t need = (size_t)w * h * 4;
        unsigned char *px = malloc(need); /* before the limit: the program's own */
        struct rlimit lim;
        lim.rlim_cur = lim.rlim_max = (rlim_t)(vm_mib() + atol(argv[4])) << 20;
        setrlimit(RLIMIT_AS, &lim);
        report("left", gls_surface_save_png(s, GLS_IMAGE_LEFT, "/nonexistent-glstereo/never.png"));
        report("composite", gls_surface_save_png(s, GLS_IMAGE_COMPOSITE, "/nonexistent-glstereo/never.png"));
        if (px) report("read", gls_surface_read_pixels(s, 0x0400 /* GL_FRONT_LEFT */, px, need));
        free(px);
        gls_surface_destroy(s);
        /* Room again: a small surface works. */
        lim.rlim_cur = lim.rlim_max = RLIM_INFINITY;
        setrlimit(RLIMIT_AS, &lim);
        gls_surface *small = NULL;
        if (report("small", gls_surface_create(d, c, 16, 16, &small)) == GLS_OK) gls_surface_destroy(small);
        gls_config_free(c);
        gls_display_close(d);
        return 0;
    }
    if (strcmp(cmd, "composite") == 0 && argc == 6) {
        gls_display *d = NULL;
        gls_config *c = NULL;
        gls_surface *s = NULL;
        uint32_t mode = 0;
        if (open_surface((uint32_t)atol(argv[2]), (uint32_t)atol(argv[3]), &d, &c, &s) != GLS_OK) return 0;
        report("mode", gls_output_from_name(argv[4], &mode));
        report("output", gls_surface_set_output(s, mode));
        report("swap", gls_swap_buffers(s));
        report("capture", gls_surface_save_png(s, GLS_IMAGE_COMPOSITE, argv[5]));
        gls_surface_destroy(s);
        gls_config_free(c);
        gls_display_close(d);
        return 0;
    }
    fprintf(stderr, "bad arguments\n");
    return 2;
}

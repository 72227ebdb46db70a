/* Threads (tests/threads.rs): two threads, each with its own surface and
 * context on one display, render and swap FRAMES frames at the same time;
 * every frame both eyes of both surfaces are read back whole and checked,
 * and each thread checks that its last-error message is its own, never
 * the other thread's. Then one surface moves between threads: current on
 * A, released, current on B; and current on a thread that ends without
 * releasing it, after which another thread can make it current.
 *
 *   threads egl|osmesa FRAMES
 *
 * GL is reached through gls_get_proc_address, so the program links only
 * libglstereo (and pthread); one binary serves both backends. */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glstereo.h"
#include "check.h"

#define GL_COLOR_BUFFER_BIT 0x00004000u
#define GL_FRONT_LEFT 0x0400u
#define GL_FRONT_RIGHT 0x0401u
#define GL_BACK_LEFT 0x0402u
#define GL_BACK_RIGHT 0x0403u

typedef void (*clear_color_fn)(float, float, float, float);
typedef void (*clear_fn)(unsigned);

enum { W = 64, H = 48 };

static const int ATTRIBS[] = {4 /* GLX_RGBA */, 5 /* GLX_DOUBLEBUFFER */, 6 /* GLX_STEREO */, 0};
static gls_display *display;
static long frames;
static pthread_mutex_t report_lock = PTHREAD_MUTEX_INITIALIZER;

/* The colour of thread t's eye in a frame: distinct per thread, eye, frame. */
static void color(int t, int right, long frame, unsigned char c[3]) {
    c[0] = (unsigned char)(t ? 230 : 20);
    c[1] = (unsigned char)((frame * 7 + right * 128) % 256);
    c[2] = (unsigned char)(right ? 200 : 60);
}

/* Clears the current surface's selected buffers (GL of the current surface). */
static void clear_to(const unsigned char c[3]) {
    void *p = gls_get_proc_address("glClearColor"), *q = gls_get_proc_address("glClear");
    clear_color_fn clear_color;
    clear_fn clear;
    memcpy(&clear_color, &p, sizeof p);
    memcpy(&clear, &q, sizeof q);
    clear_color(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f);
    clear(GL_COLOR_BUFFER_BIT);
}

/* Draws one frame (each eye its colour) and swaps. */
static int draw(gls_surface *s, int t, long frame) {
    for (int right = 0; right < 2; ++right) {
        unsigned char c[3];
        color(t, right, frame, c);
        if (gls_draw_buffer(right ? GL_BACK_RIGHT : GL_BACK_LEFT)) return 0;
        clear_to(c);
    }
    return gls_swap_buffers(s) == GLS_OK;
}

/* Number of pixels of an eye's front buffer that differ from the frame's colour. */
static long wrong_pixels(gls_surface *s, int t, int right, long frame, unsigned char *px) {
    unsigned char c[3];
    color(t, right, frame, c);
    if (gls_surface_read_pixels(s, right ? GL_FRONT_RIGHT : GL_FRONT_LEFT, px, W * H * 4)) return -1;
    long wrong = 0;
    for (long i = 0; i < W * H; ++i)
        for (int k = 0; k < 3; ++k)
            if (abs(px[i * 4 + k] - c[k]) > 1) {
                ++wrong;
                break;
            }
    return wrong;
}

typedef struct {
    int t;
    long bad_frames, bad_messages, failures;
} renderer;

/* Fails a call on purpose with a name only this thread and frame use, and
 * checks the message is exactly that one; a success must leave it. */
static int own_message(int t, long frame) {
    char name[64], other[64];
    uint32_t o;
    snprintf(name, sizeof name, "thread-%d-frame-%ld", t, frame);
    snprintf(other, sizeof other, "thread-%d-frame-", 1 - t);
    if (gls_output_from_name(name, &o) != GLS_ERROR_INVALID_VALUE) return 0;
    const char *m = gls_last_error_message();
    if (!strstr(m, name) || strstr(m, other)) return 0;
    if (gls_output_from_name("rows", &o) != GLS_OK) return 0;
    m = gls_last_error_message();
    return strstr(m, name) != NULL && strstr(m, other) == NULL;
}

static void *render(void *arg) {
    renderer *r = arg;
    gls_config *c;
    gls_surface *s;
    unsigned char *px = malloc(W * H * 4);
    if (!px || gls_config_choose(display, ATTRIBS, &c) || gls_surface_create(display, c, W, H, &s) ||
        gls_make_current(s)) {
        r->failures++;
        return NULL;
    }
    for (long f = 0; f < frames; ++f) {
        if (!own_message(r->t, f)) r->bad_messages++;
        if (!draw(s, r->t, f)) {
            r->failures++;
            break;
        }
        long wl = wrong_pixels(s, r->t, 0, f, px), wr = wrong_pixels(s, r->t, 1, f, px);
        if (wl != 0 || wr != 0) {
            if (r->bad_frames++ < 5) {
                pthread_mutex_lock(&report_lock);
                fprintf(stderr, "thread %d frame %ld: %ld left and %ld right pixels wrong\n", r->t, f, wl, wr);
                pthread_mutex_unlock(&report_lock);
            }
        }
        if (!own_message(r->t, f)) r->bad_messages++;
    }
    gls_make_current(NULL);
    gls_surface_destroy(s);
    gls_config_free(c);
    free(px);
    return NULL;
}

/* --- one surface, several threads ------------------------------------ */

typedef struct {
    gls_surface *s;
    int t;
    long frame;
    int release; /* release before returning, or end the thread with it current */
    gls_result made, drawn;
} step;

static void *draw_step(void *arg) {
    step *st = arg;
    st->made = gls_make_current(st->s);
    if (st->made == GLS_OK) st->drawn = draw(st->s, st->t, st->frame) ? GLS_OK : GLS_ERROR_GL;
    if (st->release) gls_make_current(NULL);
    return NULL;
}

static void run_step(step *st) {
    pthread_t t;
    pthread_create(&t, NULL, draw_step, st);
    pthread_join(t, NULL);
}

static void handoff(void) {
    gls_config *c;
    gls_surface *s;
    unsigned char *px = malloc(W * H * 4);
    CHECK(gls_config_choose(display, ATTRIBS, &c) == GLS_OK, "%s", gls_last_error_message());
    CHECK(gls_surface_create(display, c, W, H, &s) == GLS_OK, "%s", gls_last_error_message());

    /* Current on A, released; then current on B. */
    step a = {s, 0, 1, 1, GLS_ERROR_GL, GLS_ERROR_GL};
    run_step(&a);
    CHECK(a.made == GLS_OK && a.drawn == GLS_OK, "thread A: %s", gls_result_string(a.made));
    CHECK(wrong_pixels(s, 0, 0, 1, px) == 0 && wrong_pixels(s, 0, 1, 1, px) == 0, "A's frame");
    step b = {s, 1, 2, 1, GLS_ERROR_GL, GLS_ERROR_GL};
    run_step(&b);
    CHECK(b.made == GLS_OK && b.drawn == GLS_OK, "thread B after A released: %s", gls_result_string(b.made));
    CHECK(wrong_pixels(s, 1, 0, 2, px) == 0 && wrong_pixels(s, 1, 1, 2, px) == 0, "B's frame");

    /* Current on a thread that ends without releasing it: released with
     * the thread, so another thread (here the main one) can take it. */
    step gone = {s, 0, 3, 0, GLS_ERROR_GL, GLS_ERROR_GL};
    run_step(&gone);
    CHECK(gone.made == GLS_OK && gone.drawn == GLS_OK, "thread that ends: %s", gls_result_string(gone.made));
    gls_result r = gls_make_current(s);
    CHECK(r == GLS_OK, "after its thread ended: %s: %s", gls_result_string(r), gls_last_error_message());
    if (r == GLS_OK) {
        CHECK(draw(s, 1, 4), "drawing after the handoff: %s", gls_last_error_message());
        CHECK(wrong_pixels(s, 1, 0, 4, px) == 0 && wrong_pixels(s, 1, 1, 4, px) == 0, "main's frame");
        gls_make_current(NULL);
    }

    /* Destroyed while current on another thread that then ends: the
     * surface lives until that thread lets go of it, then is freed. */
    gls_surface *s2;
    CHECK(gls_surface_create(display, c, W, H, &s2) == GLS_OK, "%s", gls_last_error_message());
    step last = {s2, 0, 5, 0, GLS_ERROR_GL, GLS_ERROR_GL};
    pthread_t t;
    pthread_create(&t, NULL, draw_step, &last);
    pthread_join(t, NULL);
    CHECK(last.made == GLS_OK && last.drawn == GLS_OK, "%s", gls_result_string(last.made));
    gls_surface_destroy(s2);
    CHECK(gls_make_current(s2) == GLS_ERROR_INVALID_HANDLE, "destroyed surface");

    gls_surface_destroy(s);
    gls_config_free(c);
    free(px);
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s egl|osmesa FRAMES\n", argv[0]);
        return 2;
    }
    uint32_t backend = strcmp(argv[1], "osmesa") == 0 ? GLS_BACKEND_OSMESA : GLS_BACKEND_EGL;
    frames = atol(argv[2]);
    if (gls_display_open(backend, &display)) {
        fprintf(stderr, "%s\n", gls_last_error_message());
        return 1;
    }
    renderer r[2] = {{0, 0, 0, 0}, {1, 0, 0, 0}};
    pthread_t t[2];
    for (int i = 0; i < 2; ++i) pthread_create(&t[i], NULL, render, &r[i]);
    for (int i = 0; i < 2; ++i) pthread_join(t[i], NULL);
    for (int i = 0; i < 2; ++i) {
        CHECK(r[i].failures == 0, "thread %d failed: see above", i);
        CHECK(r[i].bad_frames == 0, "thread %d: %ld of %ld frames had wrong pixels", i, r[i].bad_frames, frames);
        CHECK(r[i].bad_messages == 0, "thread %d: %ld wrong last-error messages", i, r[i].bad_messages);
    }
    printf("2 threads x %ld frames, every frame checked\n", frames);
    handoff();
    gls_display_close(display);
    return SUMMARY();
}

/*
 * Two threads of an unmodified GLX stereo program (links only -lGL -lX11
 * -pthread), each with its own stereo context and window, render and swap
 * at once under glstereo-run (tests/threads.rs).
 *
 *   glx_threads own N      each thread opens its own X connection
 *   glx_threads shared N   both threads use one connection (XInitThreads)
 *
 * Each thread draws N frames, each eye in colours of its own (thread and
 * frame), swaps, and checks both eyes (glReadBuffer(GL_FRONT_LEFT /
 * _RIGHT)) and, every 10 frames, its window as the server shows it
 * (anaglyph-red-cyan). Thread 0 also makes a GL error every frame
 * (glDrawBuffer(0x7777): GL_INVALID_ENUM) which only its own glGetError
 * may report. Then thread 1's context is destroyed by the main thread
 * while current on thread 1, which goes on drawing with it until it
 * releases it (GLX keeps a current context until then), and thread 0's
 * context, released there, is made current and drawn with on a new
 * thread. Prints "2 threads x N frames, every frame checked" and
 * "N passed, N failed".
 */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include "check.h"

#define W 40
#define H 30

static int VISUAL[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8,
                       GLX_BLUE_SIZE, 8, GLX_STEREO, None};

static pthread_mutex_t check_lock = PTHREAD_MUTEX_INITIALIZER;
#define TCHECK(cond, ...)                         \
    do {                                          \
        pthread_mutex_lock(&check_lock);          \
        CHECK(cond, __VA_ARGS__);                 \
        pthread_mutex_unlock(&check_lock);        \
    } while (0)

static Display *shared;
static long frames;
static pthread_barrier_t start;

struct worker {
    int index;
    Display *d;
    Window w;
    GLXContext ctx;
};

static long pixel(GLenum buffer) {
    unsigned char px[4] = {0, 0, 0, 0};
    glReadBuffer(buffer);
    glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    return (long)px[0] << 16 | (long)px[1] << 8 | px[2];
}

static void clear_to(long rgb) {
    glClearColor((float)(rgb >> 16 & 255) / 255.0f, (float)(rgb >> 8 & 255) / 255.0f,
                 (float)(rgb & 255) / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

static long window_pixel(Display *d, Window w) {
    if (d == shared) XLockDisplay(d);
    XImage *img = XGetImage(d, w, W / 2, H / 2, 1, 1, AllPlanes, ZPixmap);
    long p = img ? (long)(XGetPixel(img, 0, 0) & 0xFFFFFF) : -1;
    if (img) XDestroyImage(img);
    if (d == shared) XUnlockDisplay(d);
    return p;
}

/* One checked stereo frame of worker `k` on its current context. */
static void frame(struct worker *k, long n) {
    long left = (long)(k->index ? 0x20 : 0xE0) << 16 | (n * 7 % 256) << 8 | 0x10;
    long right = 0x300000 | (long)(k->index ? 0x40 : 0xC0) << 8 | (n * 11 % 256);
    if (k->index == 0) glDrawBuffer(0x7777); /* GL_INVALID_ENUM, this context only */
    glDrawBuffer(GL_BACK_LEFT);
    clear_to(left);
    glDrawBuffer(GL_BACK_RIGHT);
    clear_to(right);
    glXSwapBuffers(k->d, k->w);
    long l = pixel(GL_FRONT_LEFT), r = pixel(GL_FRONT_RIGHT);
    TCHECK(l == left && r == right, "thread %d frame %ld: eyes %06lx %06lx, wanted %06lx %06lx", k->index,
           n, l, r, left, right);
    GLenum e = glGetError(), e2 = glGetError();
    GLenum want = k->index == 0 ? GL_INVALID_ENUM : GL_NO_ERROR;
    TCHECK(e == want && e2 == GL_NO_ERROR, "thread %d frame %ld: GL errors 0x%x 0x%x, wanted 0x%x",
           k->index, n, e, e2, want);
    if (n % 10 == 0) {
        long shown = window_pixel(k->d, k->w), expect = (left & 0xFF0000) | (right & 0x00FFFF);
        TCHECK(shown == expect, "thread %d frame %ld: window %06lx, wanted %06lx", k->index, n, shown,
               expect);
    }
}

static void *run(void *arg) {
    struct worker *k = arg;
    Bool ok = glXMakeCurrent(k->d, k->w, k->ctx);
    TCHECK(ok, "thread %d: make current", k->index);
    GLboolean stereo = GL_FALSE;
    glGetBooleanv(GL_STEREO, &stereo);
    TCHECK(stereo, "thread %d: GL_STEREO", k->index);
    pthread_barrier_wait(&start);
    for (long n = 0; n < frames; ++n) frame(k, n);
    pthread_barrier_wait(&start);
    if (k->index == 0) {
        glXMakeCurrent(k->d, None, NULL); /* hand the context over */
        pthread_barrier_wait(&start);
        pthread_barrier_wait(&start);
    } else {
        pthread_barrier_wait(&start);
        /* The main thread destroys this context now. */
        pthread_barrier_wait(&start);
        TCHECK(glXGetCurrentContext() == k->ctx, "still current after glXDestroyContext elsewhere");
        for (long n = 0; n < 20; ++n) frame(k, frames + n);
        glXMakeCurrent(k->d, None, NULL); /* destroyed now */
    }
    return NULL;
}

static void *take_over(void *arg) {
    struct worker *k = arg;
    TCHECK(glXMakeCurrent(k->d, k->w, k->ctx), "the handed-over context");
    struct worker as_other = *k;
    as_other.index = 1; /* no deliberate error here */
    for (long n = 0; n < 20; ++n) frame(&as_other, frames + n);
    glXMakeCurrent(k->d, None, NULL);
    return NULL;
}

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IOLBF, 0);
    frames = argc > 2 ? atol(argv[2]) : 0;
    int own = argc > 1 && strcmp(argv[1], "own") == 0;
    if (argc != 3 || frames <= 0 || (!own && strcmp(argv[1], "shared") != 0)) {
        fprintf(stderr, "usage: glx_threads own|shared N\n");
        return 2;
    }
    XInitThreads();
    if (!own) shared = XOpenDisplay(NULL);
    struct worker k[2];
    for (int i = 0; i < 2; ++i) {
        k[i].index = i;
        k[i].d = own ? XOpenDisplay(NULL) : shared;
        if (!k[i].d) {
            fprintf(stderr, "cannot open the X display\n");
            return 2;
        }
        XVisualInfo *vi = glXChooseVisual(k[i].d, DefaultScreen(k[i].d), VISUAL);
        if (!vi) {
            fprintf(stderr, "no stereo visual (run under glstereo-run)\n");
            return 2;
        }
        Window root = RootWindow(k[i].d, vi->screen);
        XSetWindowAttributes wa;
        memset(&wa, 0, sizeof wa);
        wa.colormap = XCreateColormap(k[i].d, root, vi->visual, AllocNone);
        k[i].w = XCreateWindow(k[i].d, root, i * 2 * W, 0, W, H, 0, vi->depth, InputOutput,
                               vi->visual, CWColormap | CWBorderPixel, &wa);
        XMapWindow(k[i].d, k[i].w);
        XSync(k[i].d, False);
        k[i].ctx = glXCreateContext(k[i].d, vi, NULL, True);
        XFree(vi);
        if (!k[i].ctx) return 2;
    }
    pthread_t t[2];
    pthread_barrier_init(&start, NULL, 3);
    for (int i = 0; i < 2; ++i) pthread_create(&t[i], NULL, run, &k[i]);
    pthread_barrier_wait(&start); /* both current */
    pthread_barrier_wait(&start); /* both drew */
    pthread_barrier_wait(&start); /* thread 0 released */
    glXDestroyContext(k[1].d, k[1].ctx); /* current on thread 1 */
    pthread_barrier_wait(&start);
    for (int i = 0; i < 2; ++i) pthread_join(t[i], NULL);
    /* Thread 0's context, released there, on a new thread. */
    pthread_t other;
    pthread_create(&other, NULL, take_over, &k[0]);
    pthread_join(other, NULL);
    pthread_barrier_destroy(&start);
    glXDestroyContext(k[0].d, k[0].ctx);
    for (int i = 0; i < 2; ++i) {
        XDestroyWindow(k[i].d, k[i].w);
        if (own) XCloseDisplay(k[i].d);
    }
    if (!own) XCloseDisplay(shared);
    printf("2 threads x %ld frames, every frame checked\n", frames);
    return SUMMARY();
}

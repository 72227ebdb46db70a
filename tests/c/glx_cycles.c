/*
 * A legacy GLX stereo program run for long (tests/leaks.rs): unmodified
 * (links only -lGL -lX11), run under glstereo-run, it must leak nothing and
 * keep its resident memory flat.
 *
 *   glx_cycles frames N     one stereo window and context, N frames
 *   glx_cycles contexts N   N cycles of: a stereo context (glXCreateContext,
 *                           glXCreateNewContext and glXCreateContextAttribsARB
 *                           in turn) made current on a new GLX window,
 *                           2 frames, release, destroy
 *   glx_cycles displays N   N cycles of: XOpenDisplay, a stereo visual and
 *                           configuration, a window, a context, 2 frames,
 *                           destroy everything, XCloseDisplay
 *
 * Every frame draws each eye in its own colour (changing every frame),
 * swaps, and checks both eyes (glReadBuffer(GL_FRONT_LEFT / _RIGHT)) and,
 * every few frames, the window as the server shows it (anaglyph-red-cyan:
 * red from the left eye, green and blue from the right). Prints
 * "rss <n> <KiB>" twenty times over the run (/proc/self/statm), then
 * "<N> <what>, every frame checked" and "N passed, N failed".
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include "check.h"

#define W 48
#define H 32
#define GLX_CONTEXT_MAJOR_VERSION_ARB_ 0x2091

typedef GLXContext (*create_context_attribs_fn)(Display *, GLXFBConfig, GLXContext, Bool, const int *);

static int VISUAL[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8,
                       GLX_DEPTH_SIZE, 16, GLX_STEREO, None};
static const int FBCONFIG[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DRAWABLE_TYPE, GLX_WINDOW_BIT,
                               GLX_DOUBLEBUFFER, True, GLX_RED_SIZE, 8, GLX_STEREO, True, None};

static long frames_drawn;

static long resident_kib(void) {
    long pages = 0, resident = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        fclose(f);
    }
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

static void report(long n, long total) {
    long step = total / 20 > 0 ? total / 20 : 1;
    if (n % step == 0) printf("rss %ld %ld\n", n, resident_kib());
}

static long pixel(GLenum buffer) {
    unsigned char px[4] = {0, 0, 0, 0};
    glReadBuffer(buffer);
    glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    return (long)px[0] << 16 | (long)px[1] << 8 | px[2];
}

static void clear_to(long rgb) {
    glClearColor((float)(rgb >> 16 & 255) / 255.0f, (float)(rgb >> 8 & 255) / 255.0f,
                 (float)(rgb & 255) / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

/* One stereo frame on the current context, checked. */
static void frame(Display *d, GLXDrawable drawable, Window window, int check_window) {
    long n = frames_drawn++;
    long left = (n * 37 % 256) << 16 | 0x4020, right = 0x100000 | (n * 53 % 256) << 8 | (n % 256);
    glDrawBuffer(GL_BACK_LEFT);
    clear_to(left);
    glDrawBuffer(GL_BACK_RIGHT);
    clear_to(right);
    glXSwapBuffers(d, drawable);
    long l = pixel(GL_FRONT_LEFT), r = pixel(GL_FRONT_RIGHT);
    CHECK(l == left && r == right, "frame %ld: eyes %06lx %06lx, wanted %06lx %06lx", n, l, r, left, right);
    if (check_window) {
        XImage *img = XGetImage(d, window, W / 2, H / 2, 1, 1, AllPlanes, ZPixmap);
        long shown = img ? (long)(XGetPixel(img, 0, 0) & 0xFFFFFF) : -1;
        if (img) XDestroyImage(img);
        long want = (left & 0xFF0000) | (right & 0x00FFFF);
        CHECK(shown == want, "frame %ld: window %06lx, wanted %06lx", n, shown, want);
    }
    GLenum e = glGetError();
    CHECK(e == GL_NO_ERROR, "frame %ld: GL error 0x%x", n, e);
}

static Window make_window(Display *d, XVisualInfo *vi) {
    Window root = RootWindow(d, vi->screen);
    XSetWindowAttributes wa;
    memset(&wa, 0, sizeof wa);
    wa.colormap = XCreateColormap(d, root, vi->visual, AllocNone);
    Window w = XCreateWindow(d, root, 0, 0, W, H, 0, vi->depth, InputOutput, vi->visual,
                             CWColormap | CWBorderPixel, &wa);
    XMapWindow(d, w);
    XSync(d, False);
    XFreeColormap(d, wa.colormap);
    return w;
}

/* The stereo configuration whose visual is `vi` (so one window serves both). */
static GLXFBConfig config_of(Display *d, XVisualInfo *vi, GLXFBConfig **list) {
    int n = 0;
    *list = glXChooseFBConfig(d, vi->screen, FBCONFIG, &n);
    for (int i = 0; *list && i < n; ++i) {
        int id = 0;
        glXGetFBConfigAttrib(d, (*list)[i], GLX_VISUAL_ID, &id);
        if ((VisualID)id == vi->visualid) return (*list)[i];
    }
    return NULL;
}

static int run_frames(Display *d, long n) {
    XVisualInfo *vi = glXChooseVisual(d, DefaultScreen(d), VISUAL);
    if (!vi) return 2;
    Window w = make_window(d, vi);
    GLXContext ctx = glXCreateContext(d, vi, NULL, True);
    CHECK(ctx && glXMakeCurrent(d, w, ctx), "a stereo context");
    for (long i = 1; i <= n; ++i) {
        frame(d, w, w, i % 25 == 0 || i == n);
        report(i, n);
    }
    glXMakeCurrent(d, None, NULL);
    glXDestroyContext(d, ctx);
    XDestroyWindow(d, w);
    XFree(vi);
    printf("%ld frames, every frame checked\n", n);
    return 0;
}

/* One context of `how` (0: visual, 1: configuration, 2: attributes) on a
 * new GLX window of `w`, two frames, then all of it destroyed. */
static void context_cycle(Display *d, XVisualInfo *vi, GLXFBConfig cfg, Window w, int how) {
    static create_context_attribs_fn create_attribs;
    if (!create_attribs) {
        void (*f)(void) = glXGetProcAddressARB((const GLubyte *)"glXCreateContextAttribsARB");
        memcpy(&create_attribs, &f, sizeof f);
    }
    const int attribs[] = {GLX_CONTEXT_MAJOR_VERSION_ARB_, 3, None};
    GLXContext ctx = how == 0   ? glXCreateContext(d, vi, NULL, True)
                     : how == 1 ? glXCreateNewContext(d, cfg, GLX_RGBA_TYPE, NULL, True)
                                : create_attribs(d, cfg, NULL, True, attribs);
    GLXWindow gw = glXCreateWindow(d, cfg, w, NULL);
    CHECK(ctx && gw && glXMakeContextCurrent(d, gw, gw, ctx), "cycle: context %d current", how);
    frame(d, gw, w, 0);
    frame(d, gw, w, 1);
    glXMakeContextCurrent(d, None, None, NULL);
    glXDestroyContext(d, ctx);
    glXDestroyWindow(d, gw);
}

static int run_contexts(Display *d, long n) {
    XVisualInfo *vi = glXChooseVisual(d, DefaultScreen(d), VISUAL);
    GLXFBConfig *list = NULL;
    GLXFBConfig cfg = vi ? config_of(d, vi, &list) : NULL;
    if (!vi || !cfg) return 2;
    Window w = make_window(d, vi);
    for (long i = 1; i <= n; ++i) {
        context_cycle(d, vi, cfg, w, (int)(i % 3));
        report(i, n);
    }
    XDestroyWindow(d, w);
    XFree(list);
    XFree(vi);
    printf("%ld context cycles, every frame checked\n", n);
    return 0;
}

static int run_displays(long n) {
    for (long i = 1; i <= n; ++i) {
        Display *d = XOpenDisplay(NULL);
        XVisualInfo *vi = d ? glXChooseVisual(d, DefaultScreen(d), VISUAL) : NULL;
        GLXFBConfig *list = NULL;
        GLXFBConfig cfg = vi ? config_of(d, vi, &list) : NULL;
        if (!cfg) return 2;
        Window w = make_window(d, vi);
        context_cycle(d, vi, cfg, w, (int)(i % 3));
        XDestroyWindow(d, w);
        XFree(list);
        XFree(vi);
        XCloseDisplay(d);
        report(i, n);
    }
    printf("%ld display cycles, every frame checked\n", n);
    return 0;
}

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IOLBF, 0);
    long n = argc > 2 ? atol(argv[2]) : 0;
    if (argc != 3 || n <= 0) {
        fprintf(stderr, "usage: glx_cycles frames|contexts|displays N\n");
        return 2;
    }
    int status;
    if (strcmp(argv[1], "displays") == 0) {
        status = run_displays(n);
    } else {
        Display *d = XOpenDisplay(NULL);
        if (!d) {
            fprintf(stderr, "cannot open the X display\n");
            return 2;
        }
        status = strcmp(argv[1], "frames") == 0 ? run_frames(d, n) : run_contexts(d, n);
        XCloseDisplay(d);
    }
    if (status != 0) {
        fprintf(stderr, "no stereo visual or configuration (run under glstereo-run)\n");
        return status;
    }
    return SUMMARY();
}

/*
 * Drawable churn: one GL context made current on drawable after drawable,
 * each destroyed in one of the ways programs and toolkits destroy them,
 * with the process's resident memory, memfd mappings, System V shared
 * memory mappings and open file descriptors sampled. Under glstereo-run
 * each drawable the stereo context is bound to gets emulated eye buffers;
 * they must go with the drawable, so the samples stay flat, as they do
 * without the layer. An unmodified GLX program (links -lGL -lX11
 * -lX11-xcb -lxcb only).
 *
 *   glx_drawable_churn MODE [N]
 *
 * MODE says how each drawable goes:
 *   glxwindow   glXCreateWindow; glXDestroyWindow, then XDestroyWindow
 *   xwindow     an X window used as the drawable; XDestroyWindow
 *   parent      a child window used as the drawable; its parent destroyed
 *   xcb         an X window destroyed with xcb_destroy_window (as Qt does)
 *   other       an X window destroyed by another client (connection)
 *   pbuffer     glXCreatePbuffer; glXDestroyPbuffer
 *   sgix        glXCreateGLXPbufferSGIX; glXDestroyGLXPbufferSGIX
 *   pixmap      glXCreatePixmap; glXDestroyPixmap, then XFreePixmap
 *   glxpixmap   glXCreateGLXPixmap; glXDestroyGLXPixmap, then XFreePixmap
 *   idle        a GLX window drawn once, the context released, the window
 *               destroyed (glXDestroyWindow, XDestroyWindow); the context
 *               stays and is never bound again
 *   thread      a GLX window made current and drawn on a second thread,
 *               destroyed (glXDestroyWindow, XDestroyWindow) by the main
 *               thread while current there; the second thread then
 *               moves on to the next window, and releases the last one
 * N drawables (default 50), 640x480, each cleared and shown (a swap or a
 * glFinish). Even iterations release the context before destroying the
 * drawable; odd ones destroy it while it is current (GLX keeps it until
 * the context is made current on the next one). 50 is even: the last one
 * is released.
 *
 * Prints "stereo S" (1: the configuration is stereo, as under the layer;
 * the program falls back to mono without it), then
 * "sample MODE WHEN rss_kb memfd sysv fds" at WHEN = start (before the
 * first drawable), warm (after drawable 10), end (after the last) and
 * released (the context released, every drawable gone, the context kept),
 * "x_errors E" (X errors the program saw), "N passed, N failed".
 */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <malloc.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib-xcb.h>
#include <X11/Xlib.h>
#include <xcb/xcb.h>

#include "check.h"

#define W 640
#define H 480
#define WARM 10

static int x_errors;

static int count_error(Display *d, XErrorEvent *e)
{
    (void)d;
    (void)e;
    x_errors++;
    return 0;
}

/* Lines of /proc/self/maps containing `what`. */
static int maps_with(const char *what)
{
    FILE *f = fopen("/proc/self/maps", "r");
    char line[512];
    int n = 0;
    if (f == NULL) return -1;
    while (fgets(line, sizeof line, f) != NULL) {
        n += strstr(line, what) != NULL;
    }
    fclose(f);
    return n;
}

/* Resident memory in use: glibc's free pages given back first (a moment's
 * peak grows an arena that is otherwise kept; see proc_usage.h). */
static long rss_kb(void)
{
    malloc_trim(0);
    FILE *f = fopen("/proc/self/statm", "r");
    long size = 0, resident = 0;
    if (f == NULL) return -1;
    if (fscanf(f, "%ld %ld", &size, &resident) != 2) resident = -1;
    fclose(f);
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

static int open_fds(void)
{
    DIR *dir = opendir("/proc/self/fd");
    int n = 0;
    if (dir == NULL) return -1;
    while (readdir(dir) != NULL) n++;
    closedir(dir);
    return n - 3; /* ".", "..", the directory's own descriptor */
}

static void sample(const char *mode, const char *when)
{
    printf("sample %s %s %ld %d %d %d\n", mode, when, rss_kb(), maps_with("memfd:"),
           maps_with("SYSV"), open_fds());
    fflush(stdout);
}

enum kind {
    GLXWINDOW, XWINDOW, PARENT, XCB, OTHER, PBUFFER, SGIX, PIXMAP, GLXPIXMAP, IDLE, THREAD
};
static const char *KIND_NAME[] = {"glxwindow", "xwindow", "parent", "xcb",   "other",
                                  "pbuffer",   "sgix",    "pixmap", "glxpixmap", "idle",
                                  "thread"};

/* One drawable and what it is made of. */
struct drawable {
    GLXDrawable gl;
    Window window, parent;
    Pixmap pixmap;
};

struct world {
    Display *d, *other;
    GLXFBConfig config;
    XVisualInfo *vi;
    Colormap cmap;
    GLXContext ctx;
};

typedef GLXPbufferSGIX (*CreatePbufferSGIX)(Display *, GLXFBConfigSGIX, unsigned, unsigned,
                                            int *);
typedef void (*DestroyPbufferSGIX)(Display *, GLXPbufferSGIX);

static Window x_window(struct world *w, Window parent)
{
    XSetWindowAttributes wa;
    memset(&wa, 0, sizeof wa);
    wa.colormap = w->cmap;
    Window win = XCreateWindow(w->d, parent, 0, 0, W, H, 0, w->vi->depth, InputOutput,
                               w->vi->visual, CWColormap, &wa);
    XMapWindow(w->d, win);
    return win;
}

static int make(struct world *w, enum kind k, struct drawable *out)
{
    Window root = DefaultRootWindow(w->d);
    memset(out, 0, sizeof *out);
    switch (k) {
    case GLXWINDOW:
    case IDLE:
    case THREAD:
        out->window = x_window(w, root);
        out->gl = glXCreateWindow(w->d, w->config, out->window, NULL);
        break;
    case XWINDOW:
    case XCB:
    case OTHER:
        out->gl = out->window = x_window(w, root);
        break;
    case PARENT:
        out->parent = x_window(w, root);
        out->gl = out->window = x_window(w, out->parent);
        break;
    case PBUFFER: {
        const int attrs[] = {GLX_PBUFFER_WIDTH, W, GLX_PBUFFER_HEIGHT, H, None};
        out->gl = glXCreatePbuffer(w->d, w->config, attrs);
        break;
    }
    case SGIX: {
        CreatePbufferSGIX create = (CreatePbufferSGIX)glXGetProcAddressARB(
            (const GLubyte *)"glXCreateGLXPbufferSGIX");
        int attrs[] = {None};
        out->gl = create ? create(w->d, (GLXFBConfigSGIX)w->config, W, H, attrs) : None;
        break;
    }
    case PIXMAP:
    case GLXPIXMAP:
        out->pixmap = XCreatePixmap(w->d, root, W, H, (unsigned)w->vi->depth);
        out->gl = k == PIXMAP ? glXCreatePixmap(w->d, w->config, out->pixmap, NULL)
                              : glXCreateGLXPixmap(w->d, w->vi, out->pixmap);
        break;
    }
    XSync(w->d, False);
    return out->gl != None;
}

static void destroy(struct world *w, enum kind k, struct drawable *dr)
{
    switch (k) {
    case GLXWINDOW:
    case IDLE:
    case THREAD:
        glXDestroyWindow(w->d, dr->gl);
        XDestroyWindow(w->d, dr->window);
        break;
    case XWINDOW:
        XDestroyWindow(w->d, dr->window);
        break;
    case PARENT:
        XDestroyWindow(w->d, dr->parent);
        break;
    case XCB: {
        xcb_connection_t *c = XGetXCBConnection(w->d);
        xcb_destroy_window(c, (xcb_window_t)dr->window);
        xcb_flush(c);
        break;
    }
    case OTHER:
        XDestroyWindow(w->other, dr->window);
        XSync(w->other, False);
        break;
    case PBUFFER:
        glXDestroyPbuffer(w->d, dr->gl);
        break;
    case SGIX: {
        DestroyPbufferSGIX destroy_sgix = (DestroyPbufferSGIX)glXGetProcAddressARB(
            (const GLubyte *)"glXDestroyGLXPbufferSGIX");
        if (destroy_sgix) destroy_sgix(w->d, dr->gl);
        break;
    }
    case PIXMAP:
        glXDestroyPixmap(w->d, dr->gl);
        XFreePixmap(w->d, dr->pixmap);
        break;
    case GLXPIXMAP:
        glXDestroyGLXPixmap(w->d, dr->gl);
        XFreePixmap(w->d, dr->pixmap);
        break;
    }
    XSync(w->d, False);
}

/* Draws into `dr` (current): a clear of both back buffers (or the front
 * of a single-buffered drawable), then shows it. */
static void draw(struct world *w, enum kind k, struct drawable *dr, int i)
{
    int window = k <= OTHER || k == IDLE || k == THREAD;
    glViewport(0, 0, W, H);
    glDrawBuffer(window ? GL_BACK : GL_FRONT);
    glClearColor((float)(i % 7) / 7.0f, 0.5f, 0.25f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (window) {
        glXSwapBuffers(w->d, dr->gl);
    } else {
        glFinish();
    }
}

static int open_world(struct world *w, enum kind k, int *stereo)
{
    int pixmaps = k == PIXMAP || k == GLXPIXMAP;
    int pbuffers = k == PBUFFER || k == SGIX;
    int type = pixmaps ? GLX_PIXMAP_BIT | GLX_WINDOW_BIT
                       : pbuffers ? GLX_PBUFFER_BIT : GLX_WINDOW_BIT;
    int attrs[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DRAWABLE_TYPE, type,
                   GLX_DOUBLEBUFFER, !pixmaps, GLX_STEREO, True, GLX_RED_SIZE, 8,
                   GLX_DEPTH_SIZE, 16, None};
    int n = 0;
    memset(w, 0, sizeof *w);
    w->d = XOpenDisplay(NULL);
    w->other = XOpenDisplay(NULL);
    if (w->d == NULL || w->other == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 0;
    }
    XSetErrorHandler(count_error);
    GLXFBConfig *configs = glXChooseFBConfig(w->d, DefaultScreen(w->d), attrs, &n);
    *stereo = configs != NULL && n > 0;
    if (!*stereo) {
        /* The program's own fallback: mono (no layer). */
        attrs[7] = False;
        configs = glXChooseFBConfig(w->d, DefaultScreen(w->d), attrs, &n);
    }
    if (configs == NULL || n == 0) {
        fprintf(stderr, "no configuration for %s\n", KIND_NAME[k]);
        return 0;
    }
    w->config = configs[0];
    XFree(configs);
    w->vi = glXGetVisualFromFBConfig(w->d, w->config);
    if (w->vi == NULL && !pbuffers) {
        fprintf(stderr, "no visual\n");
        return 0;
    }
    if (w->vi != NULL) {
        w->cmap =
            XCreateColormap(w->d, RootWindow(w->d, w->vi->screen), w->vi->visual, AllocNone);
    }
    w->ctx = glXCreateNewContext(w->d, w->config, GLX_RGBA_TYPE, NULL, True);
    if (w->ctx == NULL) {
        fprintf(stderr, "no context\n");
        return 0;
    }
    return 1;
}

/* The second thread of `thread`: one step at a time, as the main thread
 * says. */
struct relay {
    struct world *w;
    struct drawable dr;
    int step, n, checks_failed;
    pthread_mutex_t m;
    pthread_cond_t c;
};

static void wait_step(struct relay *r, int step)
{
    pthread_mutex_lock(&r->m);
    while (r->step < step) pthread_cond_wait(&r->c, &r->m);
    pthread_mutex_unlock(&r->m);
}

static void set_step(struct relay *r, int step)
{
    pthread_mutex_lock(&r->m);
    r->step = step;
    pthread_cond_broadcast(&r->c);
    pthread_mutex_unlock(&r->m);
}

/* Steps only grow. Drawable i: at 3i + 1 a new window is in r->dr: make
 * current on it (releasing the one destroyed under it) and draw; 3i + 2:
 * drawn; 3i + 3: the main thread destroyed it. After the last: release,
 * then step 3n + 4. */
static void *second_thread(void *arg)
{
    struct relay *r = arg;
    for (int i = 1; i <= r->n; i++) {
        wait_step(r, 3 * i + 1);
        if (!glXMakeContextCurrent(r->w->d, r->dr.gl, r->dr.gl, r->w->ctx)) r->checks_failed++;
        draw(r->w, THREAD, &r->dr, i);
        set_step(r, 3 * i + 2);
        wait_step(r, 3 * i + 3);
    }
    glXMakeContextCurrent(r->w->d, None, None, NULL);
    set_step(r, 3 * r->n + 4);
    return NULL;
}

static void run_thread(struct world *w, const char *mode, int n)
{
    struct relay r;
    memset(&r, 0, sizeof r);
    r.w = w;
    r.n = n;
    pthread_mutex_init(&r.m, NULL);
    pthread_cond_init(&r.c, NULL);
    pthread_t t;
    pthread_create(&t, NULL, second_thread, &r);
    for (int i = 1; i <= n; i++) {
        CHECK(make(w, THREAD, &r.dr), "drawable %d", i);
        set_step(&r, 3 * i + 1);
        wait_step(&r, 3 * i + 2);
        /* Current on the second thread: GLX keeps it until released there. */
        struct drawable dr = r.dr;
        destroy(w, THREAD, &dr);
        if (i == WARM) sample(mode, "warm");
        if (i == n) sample(mode, "end");
        set_step(&r, 3 * i + 3);
    }
    wait_step(&r, 3 * n + 4);
    pthread_join(t, NULL);
    CHECK(r.checks_failed == 0, "the second thread made the context current every time");
    sample(mode, "released");
}

static enum kind parse(const char *s)
{
    for (int k = 0; k < (int)(sizeof KIND_NAME / sizeof KIND_NAME[0]); k++) {
        if (strcmp(s, KIND_NAME[k]) == 0) return (enum kind)k;
    }
    return (enum kind)-1;
}

int main(int argc, char **argv)
{
    if (argc < 2 || (int)parse(argv[1]) < 0) {
        fprintf(stderr, "usage: glx_drawable_churn "
                        "glxwindow|xwindow|parent|xcb|other|pbuffer|sgix|pixmap|glxpixmap|idle|thread "
                        "[N]\n");
        return 1;
    }
    enum kind k = parse(argv[1]);
    int n = argc > 2 ? atoi(argv[2]) : 50;
    if (n <= WARM) n = WARM + 1;
    struct world w;
    int stereo = 0;
    if (k == THREAD && !XInitThreads()) return 2;
    if (!open_world(&w, k, &stereo)) return 2;
    printf("stereo %d\n", stereo);
    sample(argv[1], "start");
    if (k == THREAD) {
        run_thread(&w, argv[1], n);
    } else if (k == IDLE) {
        /* The context is released before each drawable goes, and kept. */
        for (int i = 1; i <= n; i++) {
            struct drawable dr;
            CHECK(make(&w, k, &dr), "drawable %d", i);
            CHECK(glXMakeContextCurrent(w.d, dr.gl, dr.gl, w.ctx), "made current on %d", i);
            draw(&w, k, &dr, i);
            glXMakeContextCurrent(w.d, None, None, NULL);
            destroy(&w, k, &dr);
            if (i == WARM) sample(argv[1], "warm");
        }
        sample(argv[1], "end");
        sample(argv[1], "released");
    } else {
        for (int i = 1; i <= n; i++) {
            struct drawable dr;
            CHECK(make(&w, k, &dr), "drawable %d", i);
            /* Made current on the next drawable: the one destroyed while
             * current last time (odd i) is released here. */
            CHECK(glXMakeContextCurrent(w.d, dr.gl, dr.gl, w.ctx), "made current on %d", i);
            draw(&w, k, &dr, i);
            CHECK(glGetError() == GL_NO_ERROR, "GL error on drawable %d", i);
            if (i % 2 == 0) glXMakeContextCurrent(w.d, None, None, NULL);
            destroy(&w, k, &dr);
            if (i == WARM) sample(argv[1], "warm");
        }
        sample(argv[1], "end");
        glXMakeContextCurrent(w.d, None, None, NULL);
        sample(argv[1], "released");
    }
    printf("x_errors %d\n", x_errors);
    glXDestroyContext(w.d, w.ctx);
    if (w.vi != NULL) {
        XFreeColormap(w.d, w.cmap);
        XFree(w.vi);
    }
    XCloseDisplay(w.other);
    XCloseDisplay(w.d);
    return SUMMARY();
}

/*
 * A GL layer of our own, built as a shared library and preloaded below
 * glstereo (LD_PRELOAD="libglstereo_preload.so:forwarder.so", as `vglrun
 * glstereo-run` or `glstereo-run mangohud` stack them) or above it
 * (LD_PRELOAD="forwarder.so:libglstereo_preload.so", as `glstereo-run
 * vglrun` or `glstereo-run apitrace trace` do). It exports the GLX and GL
 * functions glstereo calls, forwards each to the next implementation in
 * the preload chain, and counts the calls.
 *
 * Like VirtualGL's faker, glXGetProcAddress(ARB) returns this layer's own
 * wrappers for the names it exports, and (like VirtualGL's dlfaker, unless
 * FORWARDER_DLOPEN=0) dlopen of libGL.so.1 / libGL.so / libGLX.so.0 returns
 * a handle of this library, whose dlsym finds its wrappers first and libGL
 * (which it links) for the rest.
 *
 * Built two ways (tests/clients.rs):
 *   forwarder.so         linked like VirtualGL's faker: the addresses of its
 *                        own functions, taken in its code, go through the
 *                        global symbol table (the first definition in the
 *                        process: its own when it is preloaded first);
 *   forwarder-local.so   linked -Bsymbolic-functions: its own wrappers.
 *
 * FORWARDER_NEXT=dlopen makes it find the functions it forwards to in
 * dlopen("libGL.so.1") opened at load time, through whichever dlopen is
 * first in the chain, as VirtualGL's faker loads its "real" libGL: under
 * glstereo that is glstereo's, so its "real" functions are glstereo's own
 * exports, a loop glstereo must break.
 *
 * FORWARDER_LIKE_VGL (a comma-separated list, or "all") turns on what
 * VirtualGL 3.1's faker does (server/faker-sym.cpp, BufferState.h,
 * backend.cpp, its EGL back end), each of which a layer stacked with it
 * must survive:
 *   gpa          every gl* / glX* function below comes from the next
 *                glXGetProcAddress, found with dlsym(RTLD_NEXT); getting
 *                one of its own functions back ends the process with
 *                VirtualGL's message and exit status 1;
 *   share        every context is created sharing objects with a context
 *                of its own (so every context shares one name space);
 *   bindings     at make-current and swap it saves the framebuffer
 *                bindings as GLint, binds its own framebuffer (the
 *                window's), and puts back only bindings that read >= 0;
 *   stereo       it offers stereo FBConfigs and visuals of its own (GLX_STEREO
 *                true), backed by mono ones: they have no right buffers;
 *   surfaceless  it makes contexts current with no drawable (framebuffer 0
 *                is undefined below it) and stands in for each window's
 *                framebuffer with a framebuffer object of its own: binding
 *                framebuffer 0 binds it, its binding reads 0, GL_BACK /
 *                GL_FRONT name its colour attachment, attachment queries
 *                answer GL_FRAMEBUFFER_DEFAULT, and glXSwapBuffers copies
 *                it into the window and swaps there.
 *
 * At exit it writes "NAME COUNT" lines (calls > 0 only) to the file named
 * by FORWARDER_COUNTS, if set; "dlopen-gl" counts redirected dlopens,
 * "frames-shown" the swaps it showed in surfaceless mode, "negative-bindings"
 * the saves (bindings mode) that found a binding it does not put back.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

/* The functions forwarded as they are: (return type, name, parameters, arguments). */
#define FORWARDED(R, V)                                                                                  \
    R(GLXContext, glXGetCurrentContext, (void), ())                                                      \
    R(Display *, glXGetCurrentDisplay, (void), ())                                                       \
    R(Bool, glXQueryExtension, (Display * d, int *e, int *v), (d, e, v))                                 \
    R(Bool, glXQueryVersion, (Display * d, int *ma, int *mi), (d, ma, mi))                               \
    R(const char *, glXQueryExtensionsString, (Display * d, int s), (d, s))                              \
    V(void, glXQueryDrawable, (Display * d, GLXDrawable w, int a, unsigned int *v), (d, w, a, v))        \
    V(void, glXDestroyContext, (Display * d, GLXContext c), (d, c))                                      \
    V(void, glXDestroyWindow, (Display * d, GLXWindow w), (d, w))                                        \
    V(void, glGetBooleanv, (GLenum p, GLboolean * v), (p, v))                                            \
    R(GLenum, glGetError, (void), ())                                                                    \
    V(void, glBlitFramebuffer,                                                                           \
      (GLint a, GLint b, GLint c, GLint d, GLint e, GLint f, GLint g, GLint h, GLbitfield m, GLenum i),  \
      (a, b, c, d, e, f, g, h, m, i))                                                                    \
    V(void, glViewport, (GLint x, GLint y, GLsizei w, GLsizei h), (x, y, w, h))                          \
    V(void, glReadPixels, (GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, void *p),         \
      (x, y, w, h, f, t, p))                                                                             \
    V(void, glFinish, (void), ())                                                                        \
    V(void, glFlush, (void), ())

/* The functions with bodies of their own below (VirtualGL's ways); each still forwards. */
#define CUSTOM(X)                                                                                        \
    X(glXChooseVisual)                                                                                   \
    X(glXGetConfig)                                                                                      \
    X(glXChooseFBConfig)                                                                                 \
    X(glXGetFBConfigs)                                                                                   \
    X(glXGetFBConfigAttrib)                                                                              \
    X(glXGetVisualFromFBConfig)                                                                          \
    X(glXCreateContext)                                                                                  \
    X(glXCreateNewContext)                                                                               \
    X(glXCreateContextAttribsARB)                                                                        \
    X(glXCreateWindow)                                                                                   \
    X(glXMakeCurrent)                                                                                    \
    X(glXMakeContextCurrent)                                                                             \
    X(glXSwapBuffers)                                                                                    \
    X(glXGetCurrentDrawable)                                                                             \
    X(glXGetCurrentReadDrawable)                                                                         \
    X(glGetIntegerv)                                                                                     \
    X(glDrawBuffer)                                                                                      \
    X(glDrawBuffers)                                                                                     \
    X(glReadBuffer)                                                                                      \
    X(glBindFramebuffer)                                                                                 \
    X(glGetFramebufferAttachmentParameteriv)

#define ID(ret, name, params, args) ID_##name,
#define ID1(name) ID_##name,
enum { FORWARDED(ID, ID) CUSTOM(ID1) ID_glXGetProcAddress, ID_glXGetProcAddressARB, ID_dlopen_gl,
       ID_frames_shown, ID_negative_bindings, ID_COUNT };
#undef ID
#undef ID1

#define NAME(ret, name, params, args) #name,
#define NAME1(name) #name,
static const char *const names[ID_COUNT] = {FORWARDED(NAME, NAME) CUSTOM(NAME1) "glXGetProcAddress",
                                            "glXGetProcAddressARB", "dlopen-gl", "frames-shown",
                                            "negative-bindings"};
#undef NAME
#undef NAME1

static unsigned long counts[ID_COUNT];

static void count(int id)
{
    __atomic_fetch_add(&counts[id], 1, __ATOMIC_RELAXED);
}

/* FORWARDER_LIKE_VGL's ways. */
enum { VGL_GPA = 1, VGL_SHARE = 2, VGL_BINDINGS = 4, VGL_STEREO = 8, VGL_SURFACELESS = 16 };
static unsigned like_vgl;

/* With FORWARDER_NEXT=dlopen: libGL opened at load time through the global
 * dlopen (whichever layer is first), as VirtualGL's faker loads its "real"
 * functions; NULL: the next in the chain (RTLD_NEXT). */
static void *real_gl;

__attribute__((constructor)) static void start(void)
{
    const char *how = getenv("FORWARDER_NEXT");
    const char *vgl = getenv("FORWARDER_LIKE_VGL");
    if (how != NULL && strcmp(how, "dlopen") == 0) {
        /* The global dlopen: the first layer's, not this library's own. */
        void *(*global_dlopen)(const char *, int);
        void *p = dlsym(RTLD_DEFAULT, "dlopen");
        memcpy(&global_dlopen, &p, sizeof global_dlopen);
        real_gl = global_dlopen("libGL.so.1", RTLD_LAZY | RTLD_LOCAL);
    }
    if (vgl != NULL) {
        int all = strcmp(vgl, "all") == 0;
        like_vgl |= (all || strstr(vgl, "gpa")) ? VGL_GPA : 0;
        like_vgl |= (all || strstr(vgl, "share")) ? VGL_SHARE : 0;
        like_vgl |= (all || strstr(vgl, "bindings")) ? VGL_BINDINGS : 0;
        like_vgl |= (all || strstr(vgl, "stereo")) ? VGL_STEREO : 0;
        like_vgl |= (all || strstr(vgl, "surfaceless")) ? VGL_SURFACELESS : 0;
        /* VirtualGL's EGL back end stands in for every window; its contexts share. */
        if (like_vgl & VGL_SURFACELESS) {
            like_vgl |= VGL_SHARE;
        }
    }
}

static void *own(const char *name);

/* VirtualGL's answer to getting its own function back (server/faker-sym.h). */
static void got_the_fake_one(const char *name)
{
    fprintf(stderr,
            "[VGL] ERROR: VirtualGL attempted to load the real\n[VGL]   %s function and got the fake one "
            "instead.\n[VGL]   Something is terribly wrong.  Aborting before chaos ensues.\n",
            name);
    exit(1);
}

typedef __GLXextFuncPtr (*GetProcFn)(const GLubyte *);

/* The next glXGetProcAddress (VGL_GPA), checked not to be this layer's own. */
static GetProcFn next_gpa(void)
{
    static GetProcFn gpa;
    if (gpa == NULL) {
        void *p = dlsym(RTLD_NEXT, "glXGetProcAddress");
        if (p == NULL) {
            fprintf(stderr, "forwarder: no next glXGetProcAddress: %s\n", dlerror());
            abort();
        }
        if (p == own("glXGetProcAddress")) {
            got_the_fake_one("glXGetProcAddress");
        }
        memcpy(&gpa, &p, sizeof gpa);
    }
    return gpa;
}

/* The next `name`, into the function pointer `slot`. */
static void next_in_chain(const char *name, void *slot, size_t size)
{
    void *p;
    if ((like_vgl & VGL_GPA) && real_gl == NULL && strncmp(name, "gl", 2) == 0) {
        __GLXextFuncPtr f = next_gpa()((const GLubyte *)name);
        memcpy(&p, &f, sizeof p);
        if (p != NULL && p == own(name)) {
            got_the_fake_one(name);
        }
    } else {
        p = dlsym(real_gl != NULL ? real_gl : RTLD_NEXT, name);
        if (p == NULL && strncmp(name, "gl", 2) == 0) {
            /* Not exported by libGL: its glXGetProcAddressARB knows it. */
            GetProcFn gpa;
            void *g = dlsym(RTLD_NEXT, "glXGetProcAddressARB");
            if (g != NULL) {
                __GLXextFuncPtr f;
                memcpy(&gpa, &g, sizeof gpa);
                f = gpa((const GLubyte *)name);
                memcpy(&p, &f, sizeof p);
            }
        }
    }
    if (p == NULL) {
        fprintf(stderr, "forwarder: no next %s: %s\n", name, dlerror());
        abort();
    }
    memcpy(slot, &p, size);
}

/* Resolves the static `next` of the function being defined. */
#define NEXT(name)                                                                                       \
    do {                                                                                                 \
        if (next == NULL) {                                                                              \
            next_in_chain(#name, &next, sizeof next);                                                    \
        }                                                                                                \
    } while (0)

#define RETURNING(ret, name, params, args)                                                               \
    ret name params                                                                                      \
    {                                                                                                    \
        static ret(*next) params;                                                                        \
        count(ID_##name);                                                                                \
        NEXT(name);                                                                                      \
        return next args;                                                                                \
    }
#define VOID(ret, name, params, args)                                                                    \
    ret name params                                                                                      \
    {                                                                                                    \
        static ret(*next) params;                                                                        \
        count(ID_##name);                                                                                \
        NEXT(name);                                                                                      \
        next args;                                                                                       \
    }
FORWARDED(RETURNING, VOID)
#undef RETURNING
#undef VOID

/* ---- What the layer itself calls below it (never the global names). ---- */

static struct {
    void (*GenFramebuffers)(GLsizei, GLuint *);
    void (*BindFramebuffer)(GLenum, GLuint);
    void (*GenRenderbuffers)(GLsizei, GLuint *);
    void (*BindRenderbuffer)(GLenum, GLuint);
    void (*RenderbufferStorage)(GLenum, GLenum, GLsizei, GLsizei);
    void (*FramebufferRenderbuffer)(GLenum, GLenum, GLenum, GLuint);
    void (*BlitFramebuffer)(GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLbitfield, GLenum);
    void (*GetIntegerv)(GLenum, GLint *);
    void (*DrawBuffer)(GLenum);
    void (*ReadBuffer)(GLenum);
    GLboolean (*IsEnabled)(GLenum);
    void (*Enable)(GLenum);
    void (*Disable)(GLenum);
    Bool (*MakeContextCurrent)(Display *, GLXDrawable, GLXDrawable, GLXContext);
    void (*SwapBuffers)(Display *, GLXDrawable);
} below;

static pthread_once_t below_once = PTHREAD_ONCE_INIT;

static void load_below(void)
{
#define LOAD(field, name) next_in_chain(name, &below.field, sizeof below.field)
    LOAD(GenFramebuffers, "glGenFramebuffers");
    LOAD(BindFramebuffer, "glBindFramebuffer");
    LOAD(GenRenderbuffers, "glGenRenderbuffers");
    LOAD(BindRenderbuffer, "glBindRenderbuffer");
    LOAD(RenderbufferStorage, "glRenderbufferStorage");
    LOAD(FramebufferRenderbuffer, "glFramebufferRenderbuffer");
    LOAD(BlitFramebuffer, "glBlitFramebuffer");
    LOAD(GetIntegerv, "glGetIntegerv");
    LOAD(DrawBuffer, "glDrawBuffer");
    LOAD(ReadBuffer, "glReadBuffer");
    LOAD(IsEnabled, "glIsEnabled");
    LOAD(Enable, "glEnable");
    LOAD(Disable, "glDisable");
    LOAD(MakeContextCurrent, "glXMakeContextCurrent");
    LOAD(SwapBuffers, "glXSwapBuffers");
#undef LOAD
}

static void need_below(void)
{
    pthread_once(&below_once, load_below);
}

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

/* ---- stereo: FBConfigs and visuals of its own, backed by mono ones ---- */

#define MAX_TWINS 1024
/* A stereo FBConfig of this layer: its address is the handle. */
static struct twin {
    GLXFBConfig real;
} twins[MAX_TWINS];
static int n_twins;

/* The stereo twin of `real` (made on first use), NULL when the table is full. */
static GLXFBConfig twin_of(GLXFBConfig real)
{
    GLXFBConfig t = NULL;
    int i;
    pthread_mutex_lock(&lock);
    for (i = 0; i < n_twins && t == NULL; i++) {
        if (twins[i].real == real) {
            t = (GLXFBConfig)&twins[i];
        }
    }
    if (t == NULL && n_twins < MAX_TWINS) {
        twins[n_twins].real = real;
        t = (GLXFBConfig)&twins[n_twins++];
    }
    pthread_mutex_unlock(&lock);
    return t;
}

static int is_twin(GLXFBConfig c)
{
    const struct twin *t = (const struct twin *)c;
    return t >= twins && t < twins + MAX_TWINS;
}

/* The real configuration behind `c`. */
static GLXFBConfig real_of(GLXFBConfig c)
{
    return is_twin(c) ? ((const struct twin *)c)->real : c;
}

#define MAX_VISUALS 256
static XVisualInfo *stereo_visuals[MAX_VISUALS];
static int next_visual;

/* `list` (GLX_STEREO as a boolean attribute when `booleans`, else in pairs)
 * copied without GLX_STEREO into `out` (room for 128 ints); whether it asked
 * for stereo. */
static int strip_stereo(const int *list, int booleans, int *out)
{
    int n = 0, stereo = 0;
    while (list != NULL && *list != None && n < 126) {
        int a = *list++;
        if (a == GLX_STEREO) {
            if (booleans) {
                stereo = 1;
            } else {
                stereo = *list++ != 0;
            }
            continue;
        }
        out[n++] = a;
        if (!booleans || (a != GLX_RGBA && a != GLX_DOUBLEBUFFER && a != GLX_USE_GL)) {
            out[n++] = *list++;
        }
    }
    out[n] = None;
    return stereo;
}

XVisualInfo *glXChooseVisual(Display *d, int s, int *a)
{
    static XVisualInfo *(*next)(Display *, int, int *);
    int stripped[128];
    XVisualInfo *v;
    count(ID_glXChooseVisual);
    NEXT(glXChooseVisual);
    if (!(like_vgl & VGL_STEREO) || !strip_stereo(a, 1, stripped)) {
        return next(d, s, a);
    }
    v = next(d, s, stripped);
    if (v != NULL) {
        pthread_mutex_lock(&lock);
        stereo_visuals[next_visual++ % MAX_VISUALS] = v;
        pthread_mutex_unlock(&lock);
    }
    return v;
}

int glXGetConfig(Display *d, XVisualInfo *v, int a, int *o)
{
    static int (*next)(Display *, XVisualInfo *, int, int *);
    int i, stereo = 0;
    count(ID_glXGetConfig);
    NEXT(glXGetConfig);
    if ((like_vgl & VGL_STEREO) && a == GLX_STEREO && v != NULL && o != NULL) {
        pthread_mutex_lock(&lock);
        for (i = 0; i < MAX_VISUALS; i++) {
            stereo |= stereo_visuals[i] == v;
        }
        pthread_mutex_unlock(&lock);
        if (stereo) {
            *o = 1;
            return 0;
        }
    }
    return next(d, v, a, o);
}

GLXFBConfig *glXChooseFBConfig(Display *d, int s, const int *a, int *n)
{
    static GLXFBConfig *(*next)(Display *, int, const int *, int *);
    int stripped[128], i;
    GLXFBConfig *list;
    count(ID_glXChooseFBConfig);
    NEXT(glXChooseFBConfig);
    if (!(like_vgl & VGL_STEREO) || !strip_stereo(a, 0, stripped)) {
        return next(d, s, a, n);
    }
    list = next(d, s, stripped, n);
    for (i = 0; list != NULL && i < *n; i++) {
        GLXFBConfig t = twin_of(list[i]);
        if (t != NULL) {
            list[i] = t;
        }
    }
    return list;
}

GLXFBConfig *glXGetFBConfigs(Display *d, int s, int *n)
{
    static GLXFBConfig *(*next)(Display *, int, int *);
    static int (*attrib)(Display *, GLXFBConfig, int, int *);
    GLXFBConfig *list, *all;
    int i, k;
    count(ID_glXGetFBConfigs);
    NEXT(glXGetFBConfigs);
    list = next(d, s, n);
    if (!(like_vgl & VGL_STEREO) || list == NULL) {
        return list;
    }
    if (attrib == NULL) {
        next_in_chain("glXGetFBConfigAttrib", &attrib, sizeof attrib);
    }
    /* VirtualGL lists its stereo configurations among the others: each RGBA
     * window configuration, then its stereo twin. */
    all = malloc(sizeof *all * (size_t)(2 * *n));
    if (all == NULL) {
        return list;
    }
    for (i = 0, k = 0; i < *n; i++) {
        int render = 0, drawable = 0;
        all[k++] = list[i];
        attrib(d, list[i], GLX_RENDER_TYPE, &render);
        attrib(d, list[i], GLX_DRAWABLE_TYPE, &drawable);
        if ((render & GLX_RGBA_BIT) && (drawable & GLX_WINDOW_BIT)) {
            GLXFBConfig t = twin_of(list[i]);
            if (t != NULL) {
                all[k++] = t;
            }
        }
    }
    XFree(list);
    *n = k;
    return all;
}

int glXGetFBConfigAttrib(Display *d, GLXFBConfig c, int a, int *v)
{
    static int (*next)(Display *, GLXFBConfig, int, int *);
    count(ID_glXGetFBConfigAttrib);
    NEXT(glXGetFBConfigAttrib);
    if (is_twin(c) && a == GLX_STEREO && v != NULL) {
        *v = 1;
        return 0;
    }
    return next(d, real_of(c), a, v);
}

XVisualInfo *glXGetVisualFromFBConfig(Display *d, GLXFBConfig c)
{
    static XVisualInfo *(*next)(Display *, GLXFBConfig);
    XVisualInfo *v;
    count(ID_glXGetVisualFromFBConfig);
    NEXT(glXGetVisualFromFBConfig);
    v = next(d, real_of(c));
    if (v != NULL && is_twin(c)) {
        pthread_mutex_lock(&lock);
        stereo_visuals[next_visual++ % MAX_VISUALS] = v;
        pthread_mutex_unlock(&lock);
    }
    return v;
}

/* GLX windows and the X windows behind them (for the stand-ins' sizes). */
#define MAX_WINDOWS 64
static struct {
    GLXWindow glx;
    Window x;
} windows[MAX_WINDOWS];
static int next_window;

GLXWindow glXCreateWindow(Display *d, GLXFBConfig c, Window w, const int *a)
{
    static GLXWindow (*next)(Display *, GLXFBConfig, Window, const int *);
    GLXWindow g;
    count(ID_glXCreateWindow);
    NEXT(glXCreateWindow);
    g = next(d, real_of(c), w, a);
    if (g != None) {
        pthread_mutex_lock(&lock);
        windows[next_window % MAX_WINDOWS].glx = g;
        windows[next_window++ % MAX_WINDOWS].x = w;
        pthread_mutex_unlock(&lock);
    }
    return g;
}

/* The X drawable behind GLX drawable `w`. */
static Drawable x_drawable(GLXDrawable w)
{
    Drawable x = w;
    int i;
    pthread_mutex_lock(&lock);
    for (i = 0; i < MAX_WINDOWS; i++) {
        if (windows[i].glx == w && w != None) {
            x = windows[i].x;
        }
    }
    pthread_mutex_unlock(&lock);
    return x;
}

/* ---- share: every context shares with one of the layer's own ---- */

static GLXContext root;

/* The context every new one shares with (`make` creates it, sharing nothing, on first use). */
static GLXContext share_with(GLXContext share, GLXContext (*make)(void *), void *how)
{
    if (!(like_vgl & VGL_SHARE) || share != NULL) {
        return share;
    }
    pthread_mutex_lock(&lock);
    if (root == NULL) {
        root = make(how);
    }
    pthread_mutex_unlock(&lock);
    return root;
}

struct from_visual {
    GLXContext (*next)(Display *, XVisualInfo *, GLXContext, Bool);
    Display *d;
    XVisualInfo *v;
};

static GLXContext root_from_visual(void *how)
{
    struct from_visual *f = how;
    return f->next(f->d, f->v, NULL, True);
}

struct from_config {
    Display *d;
    GLXFBConfig c;
};

static GLXContext root_from_config(void *how)
{
    static GLXContext (*next)(Display *, GLXFBConfig, int, GLXContext, Bool);
    struct from_config *f = how;
    if (next == NULL) {
        next_in_chain("glXCreateNewContext", &next, sizeof next);
    }
    return next(f->d, f->c, GLX_RGBA_TYPE, NULL, True);
}

GLXContext glXCreateContext(Display *d, XVisualInfo *v, GLXContext s, Bool r)
{
    static GLXContext (*next)(Display *, XVisualInfo *, GLXContext, Bool);
    struct from_visual how;
    count(ID_glXCreateContext);
    NEXT(glXCreateContext);
    how.next = next;
    how.d = d;
    how.v = v;
    return next(d, v, v != NULL ? share_with(s, root_from_visual, &how) : s, r);
}

GLXContext glXCreateNewContext(Display *d, GLXFBConfig c, int t, GLXContext s, Bool r)
{
    static GLXContext (*next)(Display *, GLXFBConfig, int, GLXContext, Bool);
    struct from_config how;
    count(ID_glXCreateNewContext);
    NEXT(glXCreateNewContext);
    how.d = d;
    how.c = real_of(c);
    return next(d, real_of(c), t, share_with(s, root_from_config, &how), r);
}

GLXContext glXCreateContextAttribsARB(Display *d, GLXFBConfig c, GLXContext s, Bool r, const int *a)
{
    static GLXContext (*next)(Display *, GLXFBConfig, GLXContext, Bool, const int *);
    struct from_config how;
    count(ID_glXCreateContextAttribsARB);
    NEXT(glXCreateContextAttribsARB);
    how.d = d;
    how.c = real_of(c);
    return next(d, real_of(c), share_with(s, root_from_config, &how), r, a);
}

/* ---- surfaceless: a framebuffer object stands in for each window's ---- */

/* What the program has current on this thread (surfaceless mode). */
static __thread struct {
    Display *d;
    GLXDrawable draw, read;
    GLXContext ctx;
} cur;

/* One window's stand-in: its colour and depth/stencil renderbuffers (shared
 * by every context, which all share objects) and one framebuffer object per
 * context bound to it. */
#define MAX_SURFACES 64
#define MAX_FBOS 256
static struct surface {
    Display *d;
    GLXDrawable drawable;
    GLuint color, depth;
    int w, h;
} surfaces[MAX_SURFACES];
static struct fbo {
    GLXContext ctx;
    struct surface *s;
    GLuint name;
} fbos[MAX_FBOS];

/* The drawable's size (X geometry). */
static void drawable_size(Display *d, GLXDrawable w, int *width, int *height)
{
    Window root_w;
    int x, y;
    unsigned int uw = 1, uh = 1, border, depth;
    XGetGeometry(d, x_drawable(w), &root_w, &x, &y, &uw, &uh, &border, &depth);
    *width = (int)uw;
    *height = (int)uh;
}

/* Whether the current context's configuration has alpha. */
static int config_has_alpha(Display *d)
{
    static int (*query)(Display *, GLXContext, int, int *);
    static GLXFBConfig *(*choose)(Display *, int, const int *, int *);
    static int (*attrib)(Display *, GLXFBConfig, int, int *);
    int id = 0, n = 0, alpha = 0, list[3] = {GLX_FBCONFIG_ID, 0, None};
    GLXFBConfig *c;
    if (query == NULL) {
        next_in_chain("glXQueryContext", &query, sizeof query);
        next_in_chain("glXChooseFBConfig", &choose, sizeof choose);
        next_in_chain("glXGetFBConfigAttrib", &attrib, sizeof attrib);
    }
    query(d, cur.ctx, GLX_FBCONFIG_ID, &id);
    list[1] = id;
    c = choose(d, DefaultScreen(d), list, &n);
    if (c != NULL && n > 0) {
        attrib(d, c[0], GLX_ALPHA_SIZE, &alpha);
    }
    if (c != NULL) {
        XFree(c);
    }
    return alpha > 0;
}

/* The stand-in of (d, drawable) at its current size, in the current
 * context; its storage is (re)made when the window's size changed. */
static struct surface *surface_of(Display *d, GLXDrawable drawable)
{
    struct surface *s = NULL, *free_slot = NULL;
    int i, w, h;
    drawable_size(d, drawable, &w, &h);
    pthread_mutex_lock(&lock);
    for (i = 0; i < MAX_SURFACES && s == NULL; i++) {
        if (surfaces[i].drawable == drawable && surfaces[i].d == d) {
            s = &surfaces[i];
        } else if (surfaces[i].drawable == None && free_slot == NULL) {
            free_slot = &surfaces[i];
        }
    }
    if (s == NULL && free_slot != NULL) {
        s = free_slot;
        s->d = d;
        s->drawable = drawable;
        below.GenRenderbuffers(1, &s->color);
        below.GenRenderbuffers(1, &s->depth);
        s->w = s->h = 0;
    }
    if (s != NULL && (s->w != w || s->h != h)) {
        GLint old = 0;
        below.GetIntegerv(GL_RENDERBUFFER_BINDING, &old);
        below.BindRenderbuffer(GL_RENDERBUFFER, s->color);
        /* VirtualGL's formats (FakePbuffer::createBuffer). */
        below.RenderbufferStorage(GL_RENDERBUFFER, config_has_alpha(d) ? GL_SRGB8_ALPHA8 : GL_SRGB8, w, h);
        below.BindRenderbuffer(GL_RENDERBUFFER, s->depth);
        below.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
        below.BindRenderbuffer(GL_RENDERBUFFER, (GLuint)old);
        s->w = w;
        s->h = h;
    }
    pthread_mutex_unlock(&lock);
    return s;
}

/* The framebuffer object standing for `s` in context `ctx` (made and bound on first use). */
static GLuint fbo_of(GLXContext ctx, struct surface *s)
{
    GLuint name = 0;
    int i;
    pthread_mutex_lock(&lock);
    for (i = 0; i < MAX_FBOS && name == 0; i++) {
        if (fbos[i].ctx == ctx && fbos[i].s == s) {
            name = fbos[i].name;
        }
    }
    for (i = 0; i < MAX_FBOS && name == 0; i++) {
        if (fbos[i].ctx == NULL) {
            below.GenFramebuffers(1, &name);
            below.BindFramebuffer(GL_FRAMEBUFFER, name);
            below.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s->color);
            below.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                          s->depth);
            fbos[i].ctx = ctx;
            fbos[i].s = s;
            fbos[i].name = name;
        }
    }
    pthread_mutex_unlock(&lock);
    return name;
}

/* Whether `name` is one of the stand-ins (any context). */
static int is_stand_in(GLint name)
{
    int i, found = 0;
    pthread_mutex_lock(&lock);
    for (i = 0; i < MAX_FBOS && !found; i++) {
        found = fbos[i].ctx != NULL && (GLint)fbos[i].name == name;
    }
    pthread_mutex_unlock(&lock);
    return found;
}

/* The current context's stand-in for its draw drawable, 0 without one. */
static GLuint current_stand_in(void)
{
    if (!(like_vgl & VGL_SURFACELESS) || cur.ctx == NULL || cur.draw == None) {
        return 0;
    }
    return fbo_of(cur.ctx, surface_of(cur.d, cur.draw));
}

/* VirtualGL's BufferState: the bindings saved as GLint; its own framebuffer
 * (`own`: the stand-in, or 0, the window's) bound; then each saved binding
 * put back if it reads >= 0 (a saved stand-in becomes `own`). */
static void rebind_like_virtualgl(GLuint own)
{
    GLint draw = -1, read = -1, rbo = -1;
    below.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    below.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    below.GetIntegerv(GL_RENDERBUFFER_BINDING, &rbo);
    if (draw < 0 || read < 0 || rbo < 0) {
        count(ID_negative_bindings);
    }
    below.BindFramebuffer(GL_FRAMEBUFFER, own);
    below.BindRenderbuffer(GL_RENDERBUFFER, 0);
    if (rbo >= 0) {
        below.BindRenderbuffer(GL_RENDERBUFFER, (GLuint)rbo);
    }
    if (draw >= 0) {
        below.BindFramebuffer(GL_DRAW_FRAMEBUFFER, draw == 0 || is_stand_in(draw) ? own : (GLuint)draw);
    }
    if (read >= 0) {
        below.BindFramebuffer(GL_READ_FRAMEBUFFER, read == 0 || is_stand_in(read) ? own : (GLuint)read);
    }
}

static Bool make_current(Display *d, GLXDrawable draw, GLXDrawable read, GLXContext ctx)
{
    Bool ok;
    need_below();
    if (!(like_vgl & VGL_SURFACELESS) || ctx == NULL || draw == None) {
        ok = below.MakeContextCurrent(d, draw, read, ctx);
        if (ok) {
            cur.d = d;
            cur.draw = draw;
            cur.read = read;
            cur.ctx = ctx;
            if (ctx != NULL && (like_vgl & VGL_BINDINGS)) {
                rebind_like_virtualgl(0);
            }
        }
        return ok;
    }
    ok = below.MakeContextCurrent(d, None, None, ctx);
    if (ok) {
        cur.d = d;
        cur.draw = draw;
        cur.read = read;
        cur.ctx = ctx;
        rebind_like_virtualgl(current_stand_in());
    }
    return ok;
}

Bool glXMakeCurrent(Display *d, GLXDrawable w, GLXContext c)
{
    count(ID_glXMakeCurrent);
    return make_current(d, w, w, c);
}

Bool glXMakeContextCurrent(Display *d, GLXDrawable w, GLXDrawable r, GLXContext c)
{
    count(ID_glXMakeContextCurrent);
    return make_current(d, w, r, c);
}

void glXSwapBuffers(Display *d, GLXDrawable w)
{
    count(ID_glXSwapBuffers);
    need_below();
    if ((like_vgl & VGL_SURFACELESS) && cur.ctx != NULL && cur.draw == w) {
        struct surface *s = surface_of(d, w);
        GLuint stand_in = fbo_of(cur.ctx, s);
        GLint draw = 0, read = 0, read_buffer = GL_COLOR_ATTACHMENT0;
        GLboolean scissor;
        below.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
        below.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
        /* Into the window: made current on it for the copy and the swap. */
        below.MakeContextCurrent(d, w, w, cur.ctx);
        below.BindFramebuffer(GL_READ_FRAMEBUFFER, stand_in);
        below.GetIntegerv(GL_READ_BUFFER, &read_buffer);
        below.ReadBuffer(GL_COLOR_ATTACHMENT0);
        below.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        below.DrawBuffer(GL_BACK);
        scissor = below.IsEnabled(GL_SCISSOR_TEST);
        below.Disable(GL_SCISSOR_TEST);
        below.BlitFramebuffer(0, 0, s->w, s->h, 0, 0, s->w, s->h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        if (scissor) {
            below.Enable(GL_SCISSOR_TEST);
        }
        below.ReadBuffer((GLenum)read_buffer);
        below.SwapBuffers(d, w);
        count(ID_frames_shown);
        below.MakeContextCurrent(d, None, None, cur.ctx);
        below.BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw);
        below.BindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read);
        rebind_like_virtualgl(current_stand_in());
        return;
    }
    below.SwapBuffers(d, w);
    if (cur.ctx != NULL && (like_vgl & VGL_BINDINGS)) {
        rebind_like_virtualgl(0);
    }
}

GLXDrawable glXGetCurrentDrawable(void)
{
    static GLXDrawable (*next)(void);
    count(ID_glXGetCurrentDrawable);
    NEXT(glXGetCurrentDrawable);
    return (like_vgl & VGL_SURFACELESS) && cur.ctx != NULL ? cur.draw : next();
}

GLXDrawable glXGetCurrentReadDrawable(void)
{
    static GLXDrawable (*next)(void);
    count(ID_glXGetCurrentReadDrawable);
    NEXT(glXGetCurrentReadDrawable);
    return (like_vgl & VGL_SURFACELESS) && cur.ctx != NULL ? cur.read : next();
}

/* Whether the stand-in is bound at `binding` (surfaceless mode). */
static int stand_in_bound(GLenum binding)
{
    GLint bound = 0;
    if (!(like_vgl & VGL_SURFACELESS) || cur.ctx == NULL) {
        return 0;
    }
    need_below();
    below.GetIntegerv(binding, &bound);
    return bound != 0 && is_stand_in(bound);
}

/* A default framebuffer's buffer name as the stand-in's attachment. */
static GLenum on_stand_in(GLenum buf)
{
    switch (buf) {
    case GL_FRONT:
    case GL_BACK:
    case GL_LEFT:
    case GL_FRONT_LEFT:
    case GL_BACK_LEFT:
    case GL_FRONT_AND_BACK:
        return GL_COLOR_ATTACHMENT0;
    default:
        return buf;
    }
}

void glBindFramebuffer(GLenum t, GLuint f)
{
    static void (*next)(GLenum, GLuint);
    count(ID_glBindFramebuffer);
    NEXT(glBindFramebuffer);
    next(t, f == 0 ? current_stand_in() : f);
}

void glGetIntegerv(GLenum p, GLint *v)
{
    static void (*next)(GLenum, GLint *);
    count(ID_glGetIntegerv);
    NEXT(glGetIntegerv);
    next(p, v);
    if (v == NULL || !(like_vgl & VGL_SURFACELESS) || cur.ctx == NULL) {
        return;
    }
    if ((p == GL_DRAW_FRAMEBUFFER_BINDING || p == GL_READ_FRAMEBUFFER_BINDING) && *v != 0 &&
        is_stand_in(*v)) {
        *v = 0;
    } else if ((p == GL_DRAW_BUFFER || p == GL_DRAW_BUFFER0) && *v == GL_COLOR_ATTACHMENT0 &&
               stand_in_bound(GL_DRAW_FRAMEBUFFER_BINDING)) {
        *v = GL_BACK;
    } else if (p == GL_READ_BUFFER && *v == GL_COLOR_ATTACHMENT0 &&
               stand_in_bound(GL_READ_FRAMEBUFFER_BINDING)) {
        *v = GL_BACK;
    }
}

void glDrawBuffer(GLenum b)
{
    static void (*next)(GLenum);
    count(ID_glDrawBuffer);
    NEXT(glDrawBuffer);
    next(stand_in_bound(GL_DRAW_FRAMEBUFFER_BINDING) ? on_stand_in(b) : b);
}

void glDrawBuffers(GLsizei n, const GLenum *b)
{
    static void (*next)(GLsizei, const GLenum *);
    GLenum mapped[16];
    GLsizei i;
    count(ID_glDrawBuffers);
    NEXT(glDrawBuffers);
    if (b == NULL || n <= 0 || n > 16 || !stand_in_bound(GL_DRAW_FRAMEBUFFER_BINDING)) {
        next(n, b);
        return;
    }
    for (i = 0; i < n; i++) {
        mapped[i] = on_stand_in(b[i]);
    }
    next(n, mapped);
}

void glReadBuffer(GLenum b)
{
    static void (*next)(GLenum);
    count(ID_glReadBuffer);
    NEXT(glReadBuffer);
    next(stand_in_bound(GL_READ_FRAMEBUFFER_BINDING) ? on_stand_in(b) : b);
}

void glGetFramebufferAttachmentParameteriv(GLenum t, GLenum a, GLenum p, GLint *v)
{
    static void (*next)(GLenum, GLenum, GLenum, GLint *);
    int stand_in;
    count(ID_glGetFramebufferAttachmentParameteriv);
    NEXT(glGetFramebufferAttachmentParameteriv);
    stand_in = stand_in_bound(t == GL_READ_FRAMEBUFFER ? GL_READ_FRAMEBUFFER_BINDING
                                                       : GL_DRAW_FRAMEBUFFER_BINDING);
    if (!stand_in || v == NULL) {
        next(t, a, p, v);
        return;
    }
    /* As VirtualGL's backend::getFramebufferAttachmentParameteriv. */
    if (a == GL_DEPTH || a == GL_STENCIL) {
        a = GL_DEPTH_STENCIL_ATTACHMENT;
    } else {
        a = on_stand_in(a);
    }
    next(t, a, p, v);
    if (p == GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE && *v == GL_RENDERBUFFER) {
        *v = GL_FRAMEBUFFER_DEFAULT;
    }
}

/* ---- Look-ups ---- */

/* This layer's own function for `name`, or NULL. */
static void *own(const char *name)
{
    void *p = NULL;
    __GLXextFuncPtr f = NULL;
#define OWN(ret, n, params, args)                                                                        \
    if (strcmp(name, #n) == 0) {                                                                         \
        f = (__GLXextFuncPtr)n;                                                                          \
    }
#define OWN1(n)                                                                                          \
    if (strcmp(name, #n) == 0) {                                                                         \
        f = (__GLXextFuncPtr)n;                                                                          \
    }
    FORWARDED(OWN, OWN)
    CUSTOM(OWN1)
#undef OWN
#undef OWN1
    if (strcmp(name, "glXGetProcAddress") == 0) {
        f = (__GLXextFuncPtr)glXGetProcAddress;
    }
    if (strcmp(name, "glXGetProcAddressARB") == 0) {
        f = (__GLXextFuncPtr)glXGetProcAddressARB;
    }
    memcpy(&p, &f, sizeof p);
    return p;
}

/* glXGetProcAddress(ARB) `id`: counted, then this library's own function, else the next one's
   (`next` caches that layer's entry point). */
static __GLXextFuncPtr get_proc(int id, GetProcFn *next, const GLubyte *name)
{
    __GLXextFuncPtr f;
    void *p;
    count(id);
    if (name != NULL && (p = own((const char *)name)) != NULL) {
        memcpy(&f, &p, sizeof f);
        return f;
    }
    if (like_vgl & VGL_GPA) {
        return next_gpa()(name);
    }
    if (*next == NULL) {
        next_in_chain(names[id], next, sizeof *next);
    }
    return (*next)(name);
}

__GLXextFuncPtr glXGetProcAddressARB(const GLubyte *name)
{
    static GetProcFn next;
    return get_proc(ID_glXGetProcAddressARB, &next, name);
}

__GLXextFuncPtr glXGetProcAddress(const GLubyte *name)
{
    static GetProcFn next;
    return get_proc(ID_glXGetProcAddress, &next, name);
}

/* dlopen of libGL / libGLX opens this library instead (VirtualGL's dlfaker). */
void *dlopen(const char *file, int mode)
{
    static void *(*next)(const char *, int);
    static const int anchor = 0;
    if (next == NULL) {
        void *p = dlsym(RTLD_NEXT, "dlopen");
        memcpy(&next, &p, sizeof next);
    }
    const char *dlopen_env = getenv("FORWARDER_DLOPEN");
    if (file != NULL && (dlopen_env == NULL || strcmp(dlopen_env, "0") != 0)) {
        const char *base = strrchr(file, '/') ? strrchr(file, '/') + 1 : file;
        if (strcmp(base, "libGL.so.1") == 0 || strcmp(base, "libGL.so") == 0 ||
            strcmp(base, "libGLX.so.0") == 0) {
            Dl_info self;
            if (dladdr(&anchor, &self) != 0 && self.dli_fname != NULL) {
                count(ID_dlopen_gl);
                return next(self.dli_fname, mode);
            }
        }
    }
    return next(file, mode);
}

__attribute__((destructor)) static void write_counts(void)
{
    const char *path = getenv("FORWARDER_COUNTS");
    FILE *f;
    int i;
    if (path == NULL || (f = fopen(path, "w")) == NULL) {
        return;
    }
    for (i = 0; i < ID_COUNT; i++) {
        if (counts[i] > 0) {
            fprintf(f, "%s %lu\n", names[i], counts[i]);
        }
    }
    fclose(f);
}

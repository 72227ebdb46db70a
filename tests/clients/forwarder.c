/*
 * A GL layer of our own, built as a shared library and preloaded BELOW
 * glstereo (LD_PRELOAD="libglstereo_preload.so:forwarder.so"), the way
 * VirtualGL's faker or apitrace's glxtrace sit under it: it exports the GLX
 * and GL functions glstereo calls, forwards each to the next implementation
 * in the preload chain (dlsym(RTLD_NEXT, name)), and counts the calls.
 *
 * Like VirtualGL's faker, glXGetProcAddress(ARB) returns this layer's own
 * wrappers for the names it exports, and (like VirtualGL's dlfaker, unless
 * FORWARDER_DLOPEN=0) dlopen of libGL.so.1 / libGL.so / libGLX.so.0 returns
 * a handle of this library, whose dlsym finds its wrappers first and libGL
 * (which it links) for the rest.
 *
 * Built two ways (tests/clients.rs):
 *   forwarder.so         linked like VirtualGL's faker: the wrapper addresses
 *                        glXGetProcAddress returns go through the global
 *                        symbol table, so with glstereo preloaded above it
 *                        they are glstereo's own exports (the loop the
 *                        issue's `vglrun glstereo-run` crash comes from);
 *   forwarder-local.so   linked -Bsymbolic-functions: its own wrappers.
 *
 * FORWARDER_NEXT=dlopen makes it find the functions it forwards to in
 * dlopen("libGL.so.1") opened at load time, through whichever dlopen is
 * first in the chain, as VirtualGL's faker loads its "real" libGL: under
 * glstereo that is glstereo's, so its "real" functions are glstereo's own
 * exports, a loop glstereo must break.
 *
 * At exit it writes "NAME COUNT" lines (calls > 0 only) to the file named
 * by FORWARDER_COUNTS, if set; "dlopen-gl" counts redirected dlopens.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>

typedef GLXContext (*create_attribs_fn)(Display *, GLXFBConfig, GLXContext, Bool, const int *);

/* The forwarded functions: (return type, name, parameters, arguments). */
#define FORWARDED(R, V)                                                                                  \
    R(XVisualInfo *, glXChooseVisual, (Display * d, int s, int *a), (d, s, a))                           \
    R(GLXFBConfig *, glXChooseFBConfig, (Display * d, int s, const int *a, int *n), (d, s, a, n))        \
    R(GLXFBConfig *, glXGetFBConfigs, (Display * d, int s, int *n), (d, s, n))                           \
    R(int, glXGetFBConfigAttrib, (Display * d, GLXFBConfig c, int a, int *v), (d, c, a, v))              \
    R(XVisualInfo *, glXGetVisualFromFBConfig, (Display * d, GLXFBConfig c), (d, c))                     \
    R(int, glXGetConfig, (Display * d, XVisualInfo * v, int a, int *o), (d, v, a, o))                    \
    R(GLXContext, glXCreateContext, (Display * d, XVisualInfo * v, GLXContext s, Bool r), (d, v, s, r))  \
    R(GLXContext, glXCreateNewContext, (Display * d, GLXFBConfig c, int t, GLXContext s, Bool r),        \
      (d, c, t, s, r))                                                                                   \
    R(GLXContext, glXCreateContextAttribsARB,                                                            \
      (Display * d, GLXFBConfig c, GLXContext s, Bool r, const int *a), (d, c, s, r, a))                 \
    V(void, glXDestroyContext, (Display * d, GLXContext c), (d, c))                                      \
    R(Bool, glXMakeCurrent, (Display * d, GLXDrawable w, GLXContext c), (d, w, c))                       \
    R(Bool, glXMakeContextCurrent, (Display * d, GLXDrawable w, GLXDrawable r, GLXContext c),            \
      (d, w, r, c))                                                                                      \
    V(void, glXSwapBuffers, (Display * d, GLXDrawable w), (d, w))                                        \
    R(GLXContext, glXGetCurrentContext, (void), ())                                                      \
    R(GLXDrawable, glXGetCurrentDrawable, (void), ())                                                    \
    R(Display *, glXGetCurrentDisplay, (void), ())                                                       \
    R(Bool, glXQueryExtension, (Display * d, int *e, int *v), (d, e, v))                                 \
    R(Bool, glXQueryVersion, (Display * d, int *ma, int *mi), (d, ma, mi))                               \
    R(const char *, glXQueryExtensionsString, (Display * d, int s), (d, s))                              \
    V(void, glXQueryDrawable, (Display * d, GLXDrawable w, int a, unsigned int *v), (d, w, a, v))        \
    R(GLXWindow, glXCreateWindow, (Display * d, GLXFBConfig c, Window w, const int *a), (d, c, w, a))    \
    V(void, glXDestroyWindow, (Display * d, GLXWindow w), (d, w))                                        \
    V(void, glGetIntegerv, (GLenum p, GLint * v), (p, v))                                                \
    V(void, glGetBooleanv, (GLenum p, GLboolean * v), (p, v))                                            \
    R(GLenum, glGetError, (void), ())                                                                    \
    V(void, glDrawBuffer, (GLenum b), (b))                                                               \
    V(void, glDrawBuffers, (GLsizei n, const GLenum *b), (n, b))                                         \
    V(void, glReadBuffer, (GLenum b), (b))                                                               \
    V(void, glBindFramebuffer, (GLenum t, GLuint f), (t, f))                                             \
    V(void, glBlitFramebuffer,                                                                           \
      (GLint a, GLint b, GLint c, GLint d, GLint e, GLint f, GLint g, GLint h, GLbitfield m, GLenum i),  \
      (a, b, c, d, e, f, g, h, m, i))                                                                    \
    V(void, glViewport, (GLint x, GLint y, GLsizei w, GLsizei h), (x, y, w, h))                          \
    V(void, glReadPixels, (GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, void *p),         \
      (x, y, w, h, f, t, p))                                                                             \
    V(void, glFinish, (void), ())                                                                        \
    V(void, glFlush, (void), ())

#define ID(ret, name, params, args) ID_##name,
enum { FORWARDED(ID, ID) ID_glXGetProcAddress, ID_glXGetProcAddressARB, ID_dlopen_gl, ID_COUNT };
#undef ID

#define NAME(ret, name, params, args) #name,
static const char *const names[ID_COUNT] = {FORWARDED(NAME, NAME) "glXGetProcAddress", "glXGetProcAddressARB",
                                            "dlopen-gl"};
#undef NAME

static unsigned long counts[ID_COUNT];

static void count(int id)
{
    __atomic_fetch_add(&counts[id], 1, __ATOMIC_RELAXED);
}

/* With FORWARDER_NEXT=dlopen: libGL opened at load time through the global
 * dlopen (whichever layer is first), as VirtualGL's faker loads its "real"
 * functions; NULL: the next in the chain (RTLD_NEXT). */
static void *real_gl;

__attribute__((constructor)) static void open_real_gl(void)
{
    const char *how = getenv("FORWARDER_NEXT");
    if (how != NULL && strcmp(how, "dlopen") == 0) {
        /* The global dlopen: the first layer's, not this library's own. */
        void *(*global_dlopen)(const char *, int);
        void *p = dlsym(RTLD_DEFAULT, "dlopen");
        memcpy(&global_dlopen, &p, sizeof global_dlopen);
        real_gl = global_dlopen("libGL.so.1", RTLD_LAZY | RTLD_LOCAL);
    }
}

/* The next `name`, into the function pointer `slot`. */
static void next_in_chain(const char *name, void *slot, size_t size)
{
    void *p = dlsym(real_gl != NULL ? real_gl : RTLD_NEXT, name);
    if (p == NULL) {
        fprintf(stderr, "forwarder: no next %s: %s\n", name, dlerror());
        abort();
    }
    memcpy(slot, &p, size);
}

#define RETURNING(ret, name, params, args)                                                               \
    ret name params                                                                                      \
    {                                                                                                    \
        static ret(*next) params;                                                                        \
        count(ID_##name);                                                                                \
        if (next == NULL) {                                                                              \
            next_in_chain(#name, &next, sizeof next);                                                    \
        }                                                                                                \
        return next args;                                                                                \
    }
#define VOID(ret, name, params, args)                                                                    \
    ret name params                                                                                      \
    {                                                                                                    \
        static ret(*next) params;                                                                        \
        count(ID_##name);                                                                                \
        if (next == NULL) {                                                                              \
            next_in_chain(#name, &next, sizeof next);                                                    \
        }                                                                                                \
        next args;                                                                                       \
    }
FORWARDED(RETURNING, VOID)
#undef RETURNING
#undef VOID

/* This layer's own wrapper for `name`, or NULL. */
static __GLXextFuncPtr own(const char *name)
{
#define OWN(ret, n, params, args)                                                                        \
    if (strcmp(name, #n) == 0) {                                                                         \
        return (__GLXextFuncPtr)n;                                                                       \
    }
    FORWARDED(OWN, OWN)
#undef OWN
    if (strcmp(name, "glXGetProcAddress") == 0) {
        return (__GLXextFuncPtr)glXGetProcAddress;
    }
    if (strcmp(name, "glXGetProcAddressARB") == 0) {
        return (__GLXextFuncPtr)glXGetProcAddressARB;
    }
    return NULL;
}

typedef __GLXextFuncPtr (*GetProcFn)(const GLubyte *);

/* glXGetProcAddress(ARB) `id`: counted, then this library's own function, else the next one's
   (`next` caches that layer's entry point). */
static __GLXextFuncPtr get_proc(int id, GetProcFn *next, const GLubyte *name)
{
    __GLXextFuncPtr f;
    count(id);
    if (name != NULL && (f = own((const char *)name)) != NULL) {
        return f;
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
        next_in_chain("dlopen", &next, sizeof next);
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

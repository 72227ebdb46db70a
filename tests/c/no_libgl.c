/*
 * A GLX program that finds its GL functions at run time (as toolkits and
 * games that dlopen or dlsym GL do), for tests/faults.rs: linked with -lX11
 * only, run under glstereo-run where the real libGL cannot be loaded. The
 * glX/gl names it finds (dlsym(RTLD_DEFAULT)) are the preload library's;
 * each must answer as a call that failed (NULL, False, 0, no GL error),
 * with no crash, and the layer must say on stderr what is missing.
 *
 * Prints "libGL: missing" when dlopen("libGL.so.1") fails here, one line
 * per call ("<name> -> <result>"), and "done".
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include <X11/Xlib.h>

typedef void *(*choose_visual_fn)(Display *, int, int *);
typedef void **(*choose_fbconfig_fn)(Display *, int, const int *, int *);
typedef void *(*create_context_fn)(Display *, void *, void *, int);
typedef int (*make_current_fn)(Display *, unsigned long, void *);
typedef void (*swap_buffers_fn)(Display *, unsigned long);
typedef void (*(*get_proc_fn)(const unsigned char *))(void);
typedef unsigned (*get_error_fn)(void);
typedef void (*draw_buffer_fn)(unsigned);
typedef void (*get_integerv_fn)(unsigned, int *);

/* The function `name` as the process resolves it. */
#define FIND(type, var, name)                                         \
    type var;                                                         \
    do {                                                              \
        void *p_ = dlsym(RTLD_DEFAULT, name);                         \
        memcpy(&var, &p_, sizeof var);                                \
        if (!p_) {                                                    \
            printf("%s: not found\n", name);                          \
            return 1;                                                 \
        }                                                             \
    } while (0)

int main(void) {
    setvbuf(stdout, NULL, _IOLBF, 0);
    void *libgl = dlopen("libGL.so.1", RTLD_NOW | RTLD_LOCAL);
    printf("libGL: %s\n", libgl ? "present" : "missing");
    Display *d = XOpenDisplay(NULL);
    if (!d) {
        printf("no X display\n");
        return 1;
    }
    FIND(choose_visual_fn, choose_visual, "glXChooseVisual");
    FIND(choose_fbconfig_fn, choose_fbconfig, "glXChooseFBConfig");
    FIND(create_context_fn, create_context, "glXCreateContext");
    FIND(make_current_fn, make_current, "glXMakeCurrent");
    FIND(swap_buffers_fn, swap_buffers, "glXSwapBuffers");
    FIND(get_proc_fn, get_proc, "glXGetProcAddressARB");
    FIND(get_error_fn, get_error, "glGetError");
    FIND(draw_buffer_fn, draw_buffer, "glDrawBuffer");
    FIND(get_integerv_fn, get_integerv, "glGetIntegerv");

    int attribs[] = {4 /* GLX_RGBA */, 5 /* GLX_DOUBLEBUFFER */, 6 /* GLX_STEREO */, 0};
    int n = -1, v = -7;
    printf("glXChooseVisual -> %s\n", choose_visual(d, DefaultScreen(d), attribs) ? "a visual" : "NULL");
    printf("glXChooseFBConfig -> %s, n %d\n", choose_fbconfig(d, DefaultScreen(d), NULL, &n) ? "a list" : "NULL", n);
    printf("glXCreateContext -> %s\n", create_context(d, NULL, NULL, 1) ? "a context" : "NULL");
    printf("glXMakeCurrent -> %d\n", make_current(d, DefaultRootWindow(d), NULL));
    swap_buffers(d, DefaultRootWindow(d));
    printf("glXSwapBuffers -> returned\n");
    printf("glXGetProcAddressARB -> %s\n", get_proc((const unsigned char *)"glEnable") ? "a function" : "NULL");
    draw_buffer(0x0402);
    get_integerv(0x0C33, &v);
    printf("glDrawBuffer, glGetIntegerv -> %d\n", v);
    printf("glGetError -> 0x%x\n", get_error());
    XCloseDisplay(d);
    printf("done\n");
    return 0;
}

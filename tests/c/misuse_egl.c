/* Misuse of the layer's EGL entry points, the gls_egl_* functions of
 * glstereo.h (tests/misuse.rs), on a real X server with Mesa's libEGL.
 *
 * The rule (src/ffi/egl.rs): every call goes to the real libEGL, which
 * validates its handles, so a bad display, config, context or surface, a
 * NULL native window, an unknown platform or attribute gets exactly what
 * libEGL answers: each case here makes the same call through gls_egl_* and
 * through the real egl* function and checks that the results and
 * eglGetError agree, and that the answer is the failure EGL defines. A NULL
 * name for eglGetProcAddress, which libEGL would read through, is answered
 * NULL. Afterwards the layer still works: a context made through it draws
 * and swaps.
 *
 * Prints "covers <name>" for each function exercised and "N passed, N
 * failed". Needs $DISPLAY. */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <X11/Xlib.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "glstereo.h"

static int passed, failed;

static void covers(const char *name) { printf("covers %s\n", name); }

#define CHECK(cond, ...)                                                                      \
    do {                                                                                      \
        if (cond) {                                                                           \
            passed++;                                                                         \
        } else {                                                                              \
            failed++;                                                                         \
            printf("FAILED line %d: ", __LINE__);                                             \
            printf(__VA_ARGS__);                                                              \
            printf("\n");                                                                     \
        }                                                                                     \
    } while (0)

/* Ours, then libEGL's, with the same arguments: the same result (as a
 * truth value for handles, which differ between calls) and error. */
#define SAME(what, want_ok, want_error, ours, real)                                           \
    do {                                                                                      \
        long o_ = (long)(intptr_t)(ours);                                                     \
        EGLint oe_ = eglGetError();                                                           \
        long r_ = (long)(intptr_t)(real);                                                     \
        EGLint re_ = eglGetError();                                                           \
        CHECK((o_ != 0) == (r_ != 0) && oe_ == re_, "%s: ours %ld 0x%x, libEGL's %ld 0x%x",  \
              what, o_, (unsigned)oe_, r_, (unsigned)re_);                                    \
        CHECK((o_ != 0) == (want_ok) && oe_ == (want_error), "%s: %ld 0x%x, want %d 0x%x",    \
              what, o_, (unsigned)oe_, want_ok, (unsigned)(want_error));                      \
    } while (0)

int main(void)
{
    Display *x = XOpenDisplay(NULL);
    if (!x) {
        printf("no X display\n");
        return 2;
    }
    EGLDisplay bogus_dpy = (EGLDisplay)(intptr_t)0x1234;
    void *bogus = (void *)(intptr_t)0x5678;

    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display_ext =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC create_platform_window_surface_ext =
        (PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC)eglGetProcAddress(
            "eglCreatePlatformWindowSurfaceEXT");
    if (!get_platform_display_ext || !create_platform_window_surface_ext) {
        printf("libEGL has no EGL_EXT_platform_base\n");
        return 2;
    }

    /* Displays. */
    covers("gls_egl_get_display");
    EGLDisplay dpy = gls_egl_get_display(x);
    CHECK(dpy != EGL_NO_DISPLAY && dpy == eglGetDisplay((EGLNativeDisplayType)x),
          "eglGetDisplay(x) through the layer is libEGL's display");
    CHECK(gls_egl_get_display(NULL) == eglGetDisplay(EGL_DEFAULT_DISPLAY),
          "EGL_DEFAULT_DISPLAY");
    covers("gls_egl_get_platform_display");
    SAME("eglGetPlatformDisplay(unknown platform)", 0, EGL_BAD_PARAMETER,
         gls_egl_get_platform_display(0x1234, x, NULL),
         eglGetPlatformDisplay(0x1234, x, NULL));
    covers("gls_egl_get_platform_display_ext");
    SAME("eglGetPlatformDisplayEXT(unknown platform)", 0, EGL_BAD_PARAMETER,
         gls_egl_get_platform_display_ext(0x1234, x, NULL),
         get_platform_display_ext(0x1234, x, NULL));
    static const EGLint bad_attr[] = {0x7777, 1, EGL_NONE};
    SAME("eglGetPlatformDisplayEXT(X11, bad attribute)", 0, EGL_BAD_ATTRIBUTE,
         gls_egl_get_platform_display_ext(EGL_PLATFORM_X11_KHR, x, bad_attr),
         get_platform_display_ext(EGL_PLATFORM_X11_KHR, x, bad_attr));

    EGLint major, minor, n = 0;
    EGLConfig config;
    static const EGLint want[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RED_SIZE, 8,
                                  EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_NONE};
    if (!eglInitialize(dpy, &major, &minor) || !eglChooseConfig(dpy, want, &config, 1, &n) ||
        n != 1 || !eglBindAPI(EGL_OPENGL_ES_API)) {
        printf("no EGL configuration\n");
        return 2;
    }
    static const EGLint es2[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};

    /* Contexts. */
    covers("gls_egl_create_context");
    SAME("eglCreateContext(no display)", 0, EGL_BAD_DISPLAY,
         gls_egl_create_context(EGL_NO_DISPLAY, config, NULL, es2),
         eglCreateContext(EGL_NO_DISPLAY, config, EGL_NO_CONTEXT, es2));
    SAME("eglCreateContext(bogus display)", 0, EGL_BAD_DISPLAY,
         gls_egl_create_context(bogus_dpy, config, NULL, es2),
         eglCreateContext(bogus_dpy, config, EGL_NO_CONTEXT, es2));
    SAME("eglCreateContext(bogus config)", 0, EGL_BAD_CONFIG,
         gls_egl_create_context(dpy, bogus, NULL, es2),
         eglCreateContext(dpy, bogus, EGL_NO_CONTEXT, es2));
    SAME("eglCreateContext(bogus share)", 0, EGL_BAD_CONTEXT,
         gls_egl_create_context(dpy, config, bogus, es2),
         eglCreateContext(dpy, config, bogus, es2));
    SAME("eglCreateContext(bad attribute)", 0, EGL_BAD_ATTRIBUTE,
         gls_egl_create_context(dpy, config, NULL, bad_attr),
         eglCreateContext(dpy, config, EGL_NO_CONTEXT, bad_attr));
    covers("gls_egl_destroy_context");
    SAME("eglDestroyContext(bogus)", 0, EGL_BAD_CONTEXT, gls_egl_destroy_context(dpy, bogus),
         eglDestroyContext(dpy, bogus));
    SAME("eglDestroyContext(no display)", 0, EGL_BAD_DISPLAY,
         gls_egl_destroy_context(EGL_NO_DISPLAY, bogus), eglDestroyContext(EGL_NO_DISPLAY, bogus));

    /* Surfaces. */
    Window win = XCreateSimpleWindow(x, DefaultRootWindow(x), 0, 0, 64, 48, 0, 0, 0);
    XMapWindow(x, win);
    XSync(x, False);
    covers("gls_egl_create_window_surface");
    SAME("eglCreateWindowSurface(window 0)", 0, EGL_BAD_NATIVE_WINDOW,
         gls_egl_create_window_surface(dpy, config, 0, NULL),
         eglCreateWindowSurface(dpy, config, 0, NULL));
    SAME("eglCreateWindowSurface(bogus config)", 0, EGL_BAD_CONFIG,
         gls_egl_create_window_surface(dpy, bogus, (size_t)win, NULL),
         eglCreateWindowSurface(dpy, bogus, (EGLNativeWindowType)win, NULL));
    covers("gls_egl_create_platform_window_surface");
    SAME("eglCreatePlatformWindowSurface(NULL window)", 0, EGL_BAD_NATIVE_WINDOW,
         gls_egl_create_platform_window_surface(dpy, config, NULL, NULL),
         eglCreatePlatformWindowSurface(dpy, config, NULL, NULL));
    covers("gls_egl_create_platform_window_surface_ext");
    SAME("eglCreatePlatformWindowSurfaceEXT(NULL window)", 0, EGL_BAD_NATIVE_WINDOW,
         gls_egl_create_platform_window_surface_ext(dpy, config, NULL, NULL),
         create_platform_window_surface_ext(dpy, config, NULL, NULL));
    covers("gls_egl_destroy_surface");
    SAME("eglDestroySurface(bogus)", 0, EGL_BAD_SURFACE, gls_egl_destroy_surface(dpy, bogus),
         eglDestroySurface(dpy, bogus));

    /* Current, swaps. */
    covers("gls_egl_make_current");
    SAME("eglMakeCurrent(bogus context)", 0, EGL_BAD_CONTEXT,
         gls_egl_make_current(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, bogus),
         eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, bogus));
    /* A surface without a context: EGL_BAD_MATCH before the surface is
     * looked at, in Mesa. */
    SAME("eglMakeCurrent(bogus surface, no context)", 0, EGL_BAD_MATCH,
         gls_egl_make_current(dpy, bogus, bogus, EGL_NO_CONTEXT),
         eglMakeCurrent(dpy, bogus, bogus, EGL_NO_CONTEXT));
    SAME("eglMakeCurrent(release)", 1, EGL_SUCCESS,
         gls_egl_make_current(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT),
         eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
    covers("gls_egl_swap_buffers");
    SAME("eglSwapBuffers(no surface)", 0, EGL_BAD_SURFACE,
         gls_egl_swap_buffers(dpy, EGL_NO_SURFACE), eglSwapBuffers(dpy, EGL_NO_SURFACE));
    SAME("eglSwapBuffers(bogus display)", 0, EGL_BAD_DISPLAY,
         gls_egl_swap_buffers(bogus_dpy, bogus), eglSwapBuffers(bogus_dpy, bogus));
    PFNEGLSWAPBUFFERSWITHDAMAGEKHRPROC khr =
        (PFNEGLSWAPBUFFERSWITHDAMAGEKHRPROC)eglGetProcAddress("eglSwapBuffersWithDamageKHR");
    PFNEGLSWAPBUFFERSWITHDAMAGEEXTPROC ext =
        (PFNEGLSWAPBUFFERSWITHDAMAGEEXTPROC)eglGetProcAddress("eglSwapBuffersWithDamageEXT");
    covers("gls_egl_swap_buffers_with_damage_khr");
    if (khr)
        SAME("eglSwapBuffersWithDamageKHR(bogus)", 0, EGL_BAD_SURFACE,
             gls_egl_swap_buffers_with_damage_khr(dpy, bogus, NULL, 0), khr(dpy, bogus, NULL, 0));
    covers("gls_egl_swap_buffers_with_damage_ext");
    if (ext)
        SAME("eglSwapBuffersWithDamageEXT(bogus)", 0, EGL_BAD_SURFACE,
             gls_egl_swap_buffers_with_damage_ext(dpy, bogus, NULL, 0), ext(dpy, bogus, NULL, 0));
    covers("gls_egl_get_proc_address");
    CHECK(gls_egl_get_proc_address(NULL) == NULL, "eglGetProcAddress(NULL) is NULL");
    CHECK(gls_egl_get_proc_address("eglNoSuchFunction") == NULL, "an unknown name is NULL");
    CHECK(gls_egl_get_proc_address("eglSwapBuffers") != NULL, "eglSwapBuffers is found");
    covers("gls_egl_release_thread");
    SAME("eglReleaseThread", 1, EGL_SUCCESS, gls_egl_release_thread(), eglReleaseThread());

    /* The layer still works: a context made through it draws and swaps. */
    void *c = gls_egl_create_context(dpy, config, NULL, es2);
    void *s = gls_egl_create_window_surface(dpy, config, (size_t)win, NULL);
    CHECK(c && s && gls_egl_make_current(dpy, s, s, c), "a context and surface after misuse");
    glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    unsigned char px[4] = {0};
    glReadPixels(2, 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    CHECK(px[0] == 0 && px[1] == 255 && px[2] == 0, "the clear reads back: %d %d %d", px[0],
          px[1], px[2]);
    CHECK(gls_egl_swap_buffers(dpy, s) && glGetError() == GL_NO_ERROR, "the swap");
    gls_egl_make_current(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    CHECK(gls_egl_destroy_surface(dpy, s) && gls_egl_destroy_context(dpy, c), "destroyed");

    covers("gls_egl_terminate");
    SAME("eglTerminate(no display)", 0, EGL_BAD_DISPLAY, gls_egl_terminate(EGL_NO_DISPLAY),
         eglTerminate(EGL_NO_DISPLAY));
    SAME("eglTerminate(bogus display)", 0, EGL_BAD_DISPLAY, gls_egl_terminate(bogus_dpy),
         eglTerminate(bogus_dpy));
    CHECK(gls_egl_terminate(dpy) && eglGetError() == EGL_SUCCESS, "eglTerminate(dpy)");
    XDestroyWindow(x, win);
    XCloseDisplay(x);
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0;
}

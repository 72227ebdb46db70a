/*
 * An EGL program on X11 that closes its X display while its context is
 * current on one of its windows, then clears and swaps on, and exits
 * without eglTerminate (Mesa keeps the surface: the swap succeeds).
 * Before that it shows five frames.
 *
 *   egl_close
 *
 * Prints each swap's result and error. Under `glstereo-run --auto` (and
 * --auto=depth) the lines must be Mesa's and the program must not crash:
 * the layer puts frames to the window through that display (MIT-SHM), so
 * its XCloseDisplay must end that first.
 */
#include <EGL/egl.h>
#include <GLES2/gl2.h>
#include <X11/Xlib.h>
#include <stdio.h>

int main(void)
{
    Display *x = XOpenDisplay(NULL);
    if (x == NULL) {
        fprintf(stderr, "egl_close: no X display\n");
        return 2;
    }
    Window win = XCreateSimpleWindow(x, DefaultRootWindow(x), 0, 0, 160, 120, 0, 0, 0);
    XMapWindow(x, win);
    XSync(x, False);
    EGLDisplay dpy = eglGetDisplay((EGLNativeDisplayType)x);
    printf("initialize %d\n", eglInitialize(dpy, NULL, NULL));
    static const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_DEPTH_SIZE, 24,
                                  EGL_NONE};
    EGLConfig config;
    EGLint n = 0;
    if (!eglChooseConfig(dpy, want, &config, 1, &n) || n < 1) {
        fprintf(stderr, "egl_close: no configuration\n");
        return 2;
    }
    eglBindAPI(EGL_OPENGL_ES_API);
    static const EGLint attrs[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    EGLContext c = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attrs);
    EGLSurface s = eglCreateWindowSurface(dpy, config, (EGLNativeWindowType)win, NULL);
    printf("make-current %d\n", eglMakeCurrent(dpy, s, s, c));
    for (int i = 0; i < 5; i++) {
        glClearColor(0.2f * (float)i, 0.5f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        printf("swap %d 0x%x\n", eglSwapBuffers(dpy, s), (unsigned)eglGetError());
    }
    XCloseDisplay(x);
    glClearColor(0.5f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    printf("swap-display-closed %d 0x%x\n", eglSwapBuffers(dpy, s), (unsigned)eglGetError());
    printf("done\n");
    return 0;
}

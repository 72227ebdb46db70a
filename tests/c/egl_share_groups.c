/*
 * Framebuffer objects of a program's own in share groups beside the
 * layer's. Under `glstereo-run --auto` the layer makes framebuffer
 * objects in each share group (glGenFramebuffers: small names, the same
 * numbers in every group). A name is the layer's only in its own group:
 * the program's framebuffer 1 of another group (made before the layer
 * made any there: the context current without a surface first), or of a
 * group made after the layer's group ended, is the program's to delete.
 * Every line is what Mesa answers without the layer.
 *
 *   egl_share_groups
 */
#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <X11/Xlib.h>
#include <stdio.h>

static Display *x;
static EGLDisplay dpy;
static EGLConfig config;

static Window window(void)
{
    Window w = XCreateSimpleWindow(x, DefaultRootWindow(x), 0, 0, 200, 150, 0, 0, 0);
    XMapWindow(x, w);
    XSync(x, False);
    return w;
}

/* A context of a new share group: current without a surface, it makes
 * three framebuffer objects; then current on a window of its own (where
 * the layer makes its own), it draws a frame and deletes its three. */
static EGLContext group(const char *what)
{
    static const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attrs);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        printf("%s: no surfaceless context\n", what);
        return ctx;
    }
    GLuint f[3];
    glGenFramebuffers(3, f);
    for (int i = 0; i < 3; i++) {
        glBindFramebuffer(GL_FRAMEBUFFER, f[i]);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    EGLSurface s = eglCreateWindowSurface(dpy, config, (EGLNativeWindowType)window(), NULL);
    eglMakeCurrent(dpy, s, s, ctx);
    glClearColor(0.2f, 0.4f, 0.6f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    eglSwapBuffers(dpy, s);
    glDeleteFramebuffers(3, f);
    for (int i = 0; i < 3; i++)
        printf("%s: framebuffer %d of 3 after its delete: is %d, error 0x%x\n", what, i + 1,
               glIsFramebuffer(f[i]), glGetError());
    return ctx;
}

int main(void)
{
    x = XOpenDisplay(NULL);
    if (!x) {
        fprintf(stderr, "egl_share_groups: no X display\n");
        return 1;
    }
    dpy = eglGetDisplay((EGLNativeDisplayType)x);
    static const EGLint want[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE,
                                  EGL_OPENGL_ES3_BIT, EGL_NONE};
    EGLint n = 0;
    if (!eglInitialize(dpy, NULL, NULL) || !eglBindAPI(EGL_OPENGL_ES_API) ||
        !eglChooseConfig(dpy, want, &config, 1, &n) || n != 1) {
        fprintf(stderr, "egl_share_groups: no EGL configuration\n");
        return 1;
    }
    /* Group A draws in a window: the layer's framebuffers there first. */
    static const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext a = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attrs);
    EGLSurface s = eglCreateWindowSurface(dpy, config, (EGLNativeWindowType)window(), NULL);
    eglMakeCurrent(dpy, s, s, a);
    glClear(GL_COLOR_BUFFER_BIT);
    eglSwapBuffers(dpy, s);
    /* Group B while A lives. */
    EGLContext b = group("beside a live group");
    /* Group C after A and B ended. */
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, a);
    eglDestroyContext(dpy, b);
    EGLContext c = group("after the groups ended");
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, c);
    eglTerminate(dpy);
    XCloseDisplay(x);
    printf("done\n");
    return 0;
}

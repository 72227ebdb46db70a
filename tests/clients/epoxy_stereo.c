/*
 * A libepoxy stereo program, as GTK's GL code reaches GL: every GLX and GL
 * call goes through epoxy's dispatch, which dlopens libGL.so.1 itself and
 * resolves each name with dlsym on that handle (or glXGetProcAddressARB).
 * Xlib window, glXChooseVisual with GLX_STEREO. Unmodified: it links only
 * -lepoxy -lX11. Run it under glstereo-run.
 *
 * It draws the frame of eyes.h once (its look-up hands eyes.h epoxy's own
 * dispatch functions), prints the back buffers, swaps, prints the front
 * buffers, "report gl_stereo S toolkit_stereo T error E" (T is
 * glXGetConfig(GLX_STEREO) through epoxy) and "ready", then waits for a
 * line on stdin (the test grabs the window, titled "epoxy_stereo") and
 * exits 0. Without a stereo visual it says so and exits 2.
 */
#include <string.h>

#include <X11/Xlib.h>
#include <epoxy/gl.h>
#include <epoxy/glx.h>

#include "eyes.h"

/* eyes.h's look-up: epoxy's dispatch function for each name it uses. */
static eyes_proc lookup(const char *name)
{
#define EPOXY(n)                                                                                         \
    if (strcmp(name, #n) == 0) {                                                                         \
        return (eyes_proc)n;                                                                             \
    }
    EPOXY(glClearColor)
    EPOXY(glClear)
    EPOXY(glDrawBuffer)
    EPOXY(glReadBuffer)
    EPOXY(glReadPixels)
    EPOXY(glPixelStorei)
    EPOXY(glGetBooleanv)
    EPOXY(glGetIntegerv)
    EPOXY(glGetError)
    EPOXY(glViewport)
    EPOXY(glColor3f)
    EPOXY(glRectf)
#undef EPOXY
    return NULL;
}

int main(void)
{
    const int width = 160, height = 120;
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                        GLX_BLUE_SIZE, 1, GLX_STEREO, None};
    int glx_stereo = 0;
    char line[64];
    Display *display = XOpenDisplay(NULL);
    if (display == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    XVisualInfo *vi = glXChooseVisual(display, DefaultScreen(display), attributes);
    if (vi == NULL) {
        fprintf(stderr, "no stereo visual\n");
        return 2;
    }
    glXGetConfig(display, vi, GLX_STEREO, &glx_stereo);
    Window root = RootWindow(display, vi->screen);
    XSetWindowAttributes wa;
    memset(&wa, 0, sizeof wa);
    wa.colormap = XCreateColormap(display, root, vi->visual, AllocNone);
    Window win = XCreateWindow(display, root, 0, 0, (unsigned)width, (unsigned)height, 0, vi->depth,
                               InputOutput, vi->visual, CWColormap | CWBorderPixel, &wa);
    XStoreName(display, win, "epoxy_stereo");
    XMapWindow(display, win);
    XSync(display, False);
    GLXContext ctx = glXCreateContext(display, vi, NULL, True);
    if (ctx == NULL || !glXMakeCurrent(display, win, ctx)) {
        fprintf(stderr, "cannot make a GL context current\n");
        return 1;
    }
    if (!eyes_load(lookup, 0) || !eyes_draw(width, height)) {
        return 1;
    }
    eyes_report_back(width, height);
    glXSwapBuffers(display, win);
    eyes_report_front(width, height);
    printf("report gl_stereo %d toolkit_stereo %d error 0x%x\n", eyes_gl_stereo(), glx_stereo,
           eyes_gl.GetError());
    printf("ready\n");
    fflush(stdout);
    if (fgets(line, sizeof line, stdin) == NULL) {
        /* EOF: exit as well. */
    }
    glXMakeCurrent(display, None, NULL);
    glXDestroyContext(display, ctx);
    XCloseDisplay(display);
    return 0;
}

/*
 * The Xlib set-up the small standalone GLX test programs share: open the
 * display, choose a visual, map a window on it and make a GL context
 * current; and the matching teardown. A failure prints what failed and
 * exits 1.
 */
#ifndef GLSTEREO_TEST_X_WINDOW_H
#define GLSTEREO_TEST_X_WINDOW_H

#include <stdio.h>
#include <stdlib.h>

#include <GL/glx.h>
#include <X11/Xlib.h>

struct x_window {
    Display *display;
    XVisualInfo *visual;
    Window window;
    GLXContext context;
};

/* A width x height window of a visual glXChooseVisual picks for
 * `attributes`, with a direct GL context current on it. */
static inline struct x_window open_x_window(int *attributes, unsigned width, unsigned height)
{
    struct x_window x = {0};
    x.display = XOpenDisplay(NULL);
    if (x.display == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        exit(1);
    }
    x.visual = glXChooseVisual(x.display, DefaultScreen(x.display), attributes);
    if (x.visual == NULL) {
        fprintf(stderr, "no visual\n");
        exit(1);
    }
    Window root = RootWindow(x.display, x.visual->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(x.display, root, x.visual->visual, AllocNone);
    x.window = XCreateWindow(x.display, root, 0, 0, width, height, 0, x.visual->depth,
                             InputOutput, x.visual->visual, CWColormap, &wa);
    XMapWindow(x.display, x.window);
    XSync(x.display, False);
    x.context = glXCreateContext(x.display, x.visual, NULL, True);
    if (x.context == NULL || !glXMakeCurrent(x.display, x.window, x.context)) {
        fprintf(stderr, "cannot make a GL context current\n");
        exit(1);
    }
    return x;
}

/* A width x height window of the first configuration glXChooseFBConfig
 * gives for a double-buffered RGBA8 window with a 24-bit depth buffer,
 * with a direct context current on it: made by glXCreateContextAttribsARB
 * with `context_attributes` (None-terminated), or by glXCreateNewContext
 * when they are NULL. */
static inline struct x_window open_x_window_config(const int *context_attributes,
                                                   unsigned width, unsigned height)
{
    typedef GLXContext (*create_fn)(Display *, GLXFBConfig, GLXContext, Bool, const int *);
    static const int attributes[] = {
        GLX_X_RENDERABLE, True,  GLX_DRAWABLE_TYPE, GLX_WINDOW_BIT, GLX_RENDER_TYPE, GLX_RGBA_BIT,
        GLX_DOUBLEBUFFER, True,  GLX_RED_SIZE,      8,              GLX_GREEN_SIZE,  8,
        GLX_BLUE_SIZE,    8,     GLX_DEPTH_SIZE,    24,             None};
    struct x_window x = {0};
    x.display = XOpenDisplay(NULL);
    if (x.display == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        exit(1);
    }
    int n = 0;
    GLXFBConfig *configs = glXChooseFBConfig(x.display, DefaultScreen(x.display), attributes, &n);
    if (configs == NULL || n == 0 ||
        (x.visual = glXGetVisualFromFBConfig(x.display, configs[0])) == NULL) {
        fprintf(stderr, "no configuration\n");
        exit(1);
    }
    Window root = RootWindow(x.display, x.visual->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(x.display, root, x.visual->visual, AllocNone);
    x.window = XCreateWindow(x.display, root, 0, 0, width, height, 0, x.visual->depth,
                             InputOutput, x.visual->visual, CWColormap, &wa);
    XMapWindow(x.display, x.window);
    XSync(x.display, False);
    if (context_attributes != NULL) {
        create_fn create =
            (create_fn)glXGetProcAddressARB((const GLubyte *)"glXCreateContextAttribsARB");
        x.context = create(x.display, configs[0], NULL, True, context_attributes);
    } else {
        x.context = glXCreateNewContext(x.display, configs[0], GLX_RGBA_TYPE, NULL, True);
    }
    XFree(configs);
    if (x.context == NULL || !glXMakeCurrent(x.display, x.window, x.context)) {
        fprintf(stderr, "cannot make a GL context current\n");
        exit(1);
    }
    return x;
}

static inline void close_x_window(struct x_window *x)
{
    glXMakeCurrent(x->display, None, NULL);
    glXDestroyContext(x->display, x->context);
    XDestroyWindow(x->display, x->window);
    XFree(x->visual);
    XCloseDisplay(x->display);
}

#endif

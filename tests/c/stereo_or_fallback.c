/*
 * A GLX program (links only -lGL -lX11) that asks for stereo and falls
 * back to mono without it, as HP's stereo guide tells programs to: a
 * program told yes must get stereo, one told no runs its fallback.
 *
 *   stereo_or_fallback visual|fbconfig direct|indirect
 *
 * visual: glXChooseVisual with GLX_STEREO; fbconfig: glXChooseFBConfig
 * with GLX_STEREO True (and it counts the stereo configurations
 * glXGetFBConfigs lists). The context is created with direct True or
 * False as asked.
 *
 * Without a stereo visual or configuration it prints
 * "fallback: no stereo (N stereo configs listed)", draws one mono frame
 * and exits 0. With one it draws the left eye red and the right eye blue,
 * reads both back buffers and prints
 * "stereo: gl_stereo S left RRGGBB right RRGGBB is_direct D"; exit 0.
 */
#include <stdio.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

static unsigned back_pixel(GLenum buffer)
{
    unsigned char p[4] = {0, 0, 0, 0};
    glReadBuffer(buffer);
    glReadPixels(4, 4, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, p);
    return (unsigned)p[0] << 16 | (unsigned)p[1] << 8 | p[2];
}

static int stereo_configs_listed(Display *dpy)
{
    int n = 0, stereo = 0;
    GLXFBConfig *all = glXGetFBConfigs(dpy, DefaultScreen(dpy), &n);
    for (int i = 0; i < n; i++) {
        int v = 0;
        glXGetFBConfigAttrib(dpy, all[i], GLX_STEREO, &v);
        stereo += v != 0;
    }
    if (all != NULL) {
        XFree(all);
    }
    return stereo;
}

int main(int argc, char **argv)
{
    if (argc < 3 || (strcmp(argv[1], "visual") != 0 && strcmp(argv[1], "fbconfig") != 0)) {
        fprintf(stderr, "usage: stereo_or_fallback visual|fbconfig direct|indirect\n");
        return 2;
    }
    int by_config = strcmp(argv[1], "fbconfig") == 0;
    Bool direct = strcmp(argv[2], "indirect") != 0;
    Display *dpy = XOpenDisplay(NULL);
    if (dpy == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    int screen = DefaultScreen(dpy);
    int listed = by_config ? stereo_configs_listed(dpy) : 0;

    XVisualInfo *vi = NULL;
    GLXFBConfig *configs = NULL;
    int stereo = 1;
    if (by_config) {
        int attributes[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True,
                            GLX_STEREO,      True,         None};
        int n = 0;
        configs = glXChooseFBConfig(dpy, screen, attributes, &n);
        if (configs == NULL || n == 0) {
            int mono[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True, None};
            stereo = 0;
            configs = glXChooseFBConfig(dpy, screen, mono, &n);
        }
        vi = configs != NULL ? glXGetVisualFromFBConfig(dpy, configs[0]) : NULL;
    } else {
        int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, None};
        vi = glXChooseVisual(dpy, screen, attributes);
        if (vi == NULL) {
            int mono[] = {GLX_RGBA, GLX_DOUBLEBUFFER, None};
            stereo = 0;
            vi = glXChooseVisual(dpy, screen, mono);
        }
    }
    if (vi == NULL) {
        fprintf(stderr, "no visual at all\n");
        return 1;
    }
    Window root = RootWindow(dpy, screen);
    XSetWindowAttributes wa;
    memset(&wa, 0, sizeof wa);
    wa.colormap = XCreateColormap(dpy, root, vi->visual, AllocNone);
    Window win = XCreateWindow(dpy, root, 0, 0, 32, 32, 0, vi->depth, InputOutput, vi->visual,
                               CWColormap, &wa);
    XMapWindow(dpy, win);
    XSync(dpy, False);
    GLXContext ctx = by_config
                         ? glXCreateNewContext(dpy, configs[0], GLX_RGBA_TYPE, NULL, direct)
                         : glXCreateContext(dpy, vi, NULL, direct);
    if (ctx == NULL || !glXMakeCurrent(dpy, win, ctx)) {
        fprintf(stderr, "cannot make a GL context current\n");
        return 1;
    }
    if (!stereo) {
        printf("fallback: no stereo (%d stereo configs listed)\n", listed);
        glClearColor(0.5f, 0.5f, 0.5f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glXSwapBuffers(dpy, win);
    } else {
        glDrawBuffer(GL_BACK_LEFT);
        glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glDrawBuffer(GL_BACK_RIGHT);
        glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        GLboolean gl_stereo = GL_FALSE;
        glGetBooleanv(GL_STEREO, &gl_stereo);
        unsigned left = back_pixel(GL_BACK_LEFT);
        unsigned right = back_pixel(GL_BACK_RIGHT);
        printf("stereo: gl_stereo %d left %06x right %06x is_direct %d\n", gl_stereo ? 1 : 0,
               left, right, glXIsDirect(dpy, ctx) ? 1 : 0);
        glXSwapBuffers(dpy, win);
    }
    glXMakeCurrent(dpy, None, NULL);
    glXDestroyContext(dpy, ctx);
    XDestroyWindow(dpy, win);
    XFree(vi);
    if (configs != NULL) {
        XFree(configs);
    }
    XCloseDisplay(dpy);
    return 0;
}

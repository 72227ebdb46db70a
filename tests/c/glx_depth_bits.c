/*
 * Depth precision of the window's visual (links only -lGL -lX11). Run as
 * "glx_depth_bits stereo BITS" under glstereo-run (a GLX_STEREO
 * configuration with exactly BITS of depth: 16, 24, 32, or 24s8 for 24
 * bits and 8 of stencil) and as "glx_depth_bits mono BITS" without it (the
 * same configuration without GLX_STEREO, served by Mesa): the printed
 * lines are GL's answers and must be the same, byte for byte.
 *
 * What it probes: GL_DEPTH_BITS and GL_STENCIL_BITS; the depths of a
 * perspective scene read back as GL_UNSIGNED_INT, GL_UNSIGNED_SHORT and
 * GL_FLOAT (each format's conversion of the stored value); and what the
 * depth test shows: strips drawn with GL_LESS a little in front of a
 * surface, by steps from below a 32-bit depth's precision to above a
 * 16-bit one's, pass or fail as the stored precision says.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

#define W 64
#define H 48

/* A quad at eye distance w (z = -w), from x0 to x1 and y0 to y1 in eye
 * coordinates at that distance. */
static void quad(double w, double x0, double x1, double y0, double y1)
{
    glBegin(GL_QUADS);
    glVertex3d(x0, y0, -w);
    glVertex3d(x1, y0, -w);
    glVertex3d(x1, y1, -w);
    glVertex3d(x0, y1, -w);
    glEnd();
}

/* The scene: a surface at w 8 over the left half and a slanted plane
 * from w 2 to w 40 over the right, then strips a little in front of the
 * w 8 surface. */
static void draw(void)
{
    glViewport(0, 0, W, H);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-1, 1, -0.75, 0.75, 1, 50);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glClearColor(0, 0, 0, 1);
    glClearDepth(1.0);
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 5, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColor3f(1, 0, 0);
    quad(8, -8, 0, -6, 6);
    glColor3f(0, 0, 1);
    glBegin(GL_QUADS);
    glVertex3d(0, -1.5, -2);
    glVertex3d(40, -30, -40);
    glVertex3d(40, 30, -40);
    glVertex3d(0, 1.5, -2);
    glEnd();
    glDisable(GL_STENCIL_TEST);
    /* Eight strips across the w 8 surface, each nearer by 4^k e-7. */
    glColor3f(0, 1, 0);
    for (int k = 0; k < 8; k++) {
        double d = 1e-7;
        for (int i = 0; i < k; i++)
            d *= 4;
        double y0 = -6 + 1.5 * k;
        quad(8 - d, -8, 0, y0, y0 + 1.5);
    }
}

int main(int argc, char **argv)
{
    if (argc != 3 || (strcmp(argv[1], "mono") != 0 && strcmp(argv[1], "stereo") != 0 &&
                      strcmp(argv[1], "fbo") != 0)) {
        fprintf(stderr, "usage: glx_depth_bits mono|stereo|fbo 16|24|32|24s8\n");
        return 2;
    }
    int stereo = strcmp(argv[1], "stereo") == 0;
    int fbo = strcmp(argv[1], "fbo") == 0;
    int depth = atoi(argv[2]);
    int stencil = strstr(argv[2], "s8") ? 8 : 0;
    Display *dpy = XOpenDisplay(NULL);
    if (dpy == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    int attributes[] = {GLX_X_RENDERABLE, True, GLX_DRAWABLE_TYPE, GLX_WINDOW_BIT,
                        GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True,
                        GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8,
                        GLX_DEPTH_SIZE, depth, GLX_STENCIL_SIZE, stencil,
                        GLX_STEREO, stereo, None};
    int n = 0;
    GLXFBConfig *configs = glXChooseFBConfig(dpy, DefaultScreen(dpy), attributes, &n);
    GLXFBConfig config = NULL;
    /* The first with exactly these bits (larger depths sort first). */
    for (int i = 0; i < n && config == NULL; i++) {
        int d = -1, s = -1;
        glXGetFBConfigAttrib(dpy, configs[i], GLX_DEPTH_SIZE, &d);
        glXGetFBConfigAttrib(dpy, configs[i], GLX_STENCIL_SIZE, &s);
        if (d == depth && s == stencil)
            config = configs[i];
    }
    if (config == NULL) {
        fprintf(stderr, "no configuration of %d depth and %d stencil bits (of %d)\n", depth,
                stencil, n);
        return 1;
    }
    XVisualInfo *visual = glXGetVisualFromFBConfig(dpy, config);
    Window root = RootWindow(dpy, visual->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(dpy, root, visual->visual, AllocNone);
    Window window = XCreateWindow(dpy, root, 0, 0, W, H, 0, visual->depth, InputOutput,
                                  visual->visual, CWColormap, &wa);
    XMapWindow(dpy, window);
    XSync(dpy, False);
    GLXContext ctx = glXCreateNewContext(dpy, config, GLX_RGBA_TYPE, NULL, True);
    if (ctx == NULL || !glXMakeCurrent(dpy, window, ctx)) {
        fprintf(stderr, "cannot make a GL context current\n");
        return 1;
    }
    GLint bits[2] = {-1, -1};
    glGetIntegerv(GL_DEPTH_BITS, &bits[0]);
    glGetIntegerv(GL_STENCIL_BITS, &bits[1]);
    printf("depth_bits %d stencil_bits %d\n", bits[0], bits[1]);
    if (fbo) {
        /* Mesa's framebuffer object of the window's formats: rasterized
         * bottom up, where Mesa rasterizes a window top down. */
        typedef void (*Gen)(GLsizei, GLuint *);
        typedef void (*Bind)(GLenum, GLuint);
        typedef void (*Storage)(GLenum, GLenum, GLsizei, GLsizei);
        typedef void (*Attach)(GLenum, GLenum, GLenum, GLuint);
        Gen gen_fb = (Gen)glXGetProcAddress((const GLubyte *)"glGenFramebuffers");
        Gen gen_rb = (Gen)glXGetProcAddress((const GLubyte *)"glGenRenderbuffers");
        Bind bind_fb = (Bind)glXGetProcAddress((const GLubyte *)"glBindFramebuffer");
        Bind bind_rb = (Bind)glXGetProcAddress((const GLubyte *)"glBindRenderbuffer");
        Storage storage = (Storage)glXGetProcAddress((const GLubyte *)"glRenderbufferStorage");
        Attach attach = (Attach)glXGetProcAddress((const GLubyte *)"glFramebufferRenderbuffer");
        GLuint f = 0, rb[2] = {0, 0};
        gen_fb(1, &f);
        gen_rb(2, rb);
        bind_fb(0x8D40, f);
        bind_rb(0x8D41, rb[0]);
        storage(0x8D41, 0x8058 /* GL_RGBA8 */, W, H);
        attach(0x8D40, 0x8CE0, 0x8D41, rb[0]);
        bind_rb(0x8D41, rb[1]);
        storage(0x8D41,
                stencil ? 0x88F0
                        : depth == 16 ? 0x81A5 : depth == 24 ? 0x81A6 : 0x81A7,
                W, H);
        attach(0x8D40, stencil ? 0x821A : 0x8D00, 0x8D41, rb[1]);
        glDrawBuffer(0x8CE0);
        glReadBuffer(0x8CE0);
    }
    if (stereo) {
        glDrawBuffer(GL_BACK_RIGHT);
        draw();
        glDrawBuffer(GL_BACK_LEFT);
    }
    draw();
    if (!fbo)
        glReadBuffer(stereo ? GL_BACK_LEFT : GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    static const int at[][2] = {{8, 24}, {20, 30}, {33, 24}, {40, 10}, {50, 40}, {63, 47}};
    for (size_t i = 0; i < sizeof at / sizeof *at; i++) {
        GLuint u = 0;
        GLushort s = 0;
        GLfloat f = -1;
        GLubyte st = 0;
        glReadPixels(at[i][0], at[i][1], 1, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, &u);
        glReadPixels(at[i][0], at[i][1], 1, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, &s);
        glReadPixels(at[i][0], at[i][1], 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &f);
        glReadPixels(at[i][0], at[i][1], 1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, &st);
        printf("depth %d %d uint %u ushort %u float %.9g stencil %u\n", at[i][0], at[i][1], u, s,
               f, st);
    }
    /* Which strips the depth test let through, from the left half's middle
     * column (the w 8 surface is red, a strip that passed green). */
    printf("strips");
    for (int k = 0; k < 8; k++) {
        GLubyte rgba[4] = {0};
        int y = (int)(((-6 + 1.5 * k + 0.75) / 6 + 1) * 0.5 * H);
        glReadPixels(W / 4, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
        printf(" %s", rgba[1] == 255 ? "in" : rgba[0] == 255 ? "out" : "?");
    }
    printf("\nerror 0x%x\n", glGetError());
    glXSwapBuffers(dpy, window);
    glXMakeCurrent(dpy, None, NULL);
    glXDestroyContext(dpy, ctx);
    XDestroyWindow(dpy, window);
    XFree(visual);
    XFree(configs);
    XCloseDisplay(dpy);
    return 0;
}

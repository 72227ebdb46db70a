/*
 * A mono program (no stereo visual) whose window is resized at random,
 * frame after frame, drawing a perspective scene with depth: what
 * `glstereo-run --auto=depth` makes both eyes of at every size.
 *
 *   auto_resize_storm FRAMES SEED viewport|noviewport [DEPTH_BITS]
 *
 * DEPTH_BITS: the visual's depth, exactly (a configuration of that many
 * depth bits and no stencil); without it, glXChooseVisual's choice for 24
 * or more (on Mesa: 32).
 *
 * After a first frame at 64x64, each frame resizes the window to a
 * random size between 1x1 and 1600x1200 (a quarter of them thin: 1 to 3
 * pixels wide or high; some square, some the whole 1600x1200), waits for
 * the server, sets the viewport (or leaves it), clears, draws a near red
 * quad over a far green one with the depth test on and a white HUD quad
 * with w = 1 over them, and swaps. A last frame is read at its
 * viewport's centre before its swap: its mono frame's red.
 * The last line on stdout is "frames N"; the exit status is 0.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

static uint64_t rng_state;

/* SplitMix64. */
static uint64_t next(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* 1 ... n. */
static unsigned upto(unsigned n)
{
    return 1 + (unsigned)(next() % n);
}

static void random_size(unsigned *w, unsigned *h)
{
    switch (next() % 8) {
    case 0: *w = upto(3); *h = upto(1200); break;
    case 1: *w = upto(1600); *h = upto(3); break;
    case 2: *w = *h = upto(1200); break;
    case 3: *w = 1600; *h = 1200; break;
    default: *w = upto(1600); *h = upto(1200); break;
    }
}

static void quad(float z, float s)
{
    glBegin(GL_QUADS);
    glVertex3f(-s, -s, z);
    glVertex3f(s, -s, z);
    glVertex3f(s, s, z);
    glVertex3f(-s, s, z);
    glEnd();
}

static void draw(void)
{
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-1.0, 1.0, -1.0, 1.0, 1.0, 20.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glColor3f(0.0f, 1.0f, 0.0f);
    quad(-8.0f, 6.0f);
    glColor3f(1.0f, 0.0f, 0.0f);
    quad(-2.0f, 0.5f);
    /* The HUD: w = 1, no depth test, over the scene. */
    glDisable(GL_DEPTH_TEST);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(-1.0, 1.0, -1.0, 1.0, -1.0, 1.0);
    glColor3f(1.0f, 1.0f, 1.0f);
    glRectf(-0.9f, -0.9f, -0.6f, -0.8f);
}

static void draw_and_swap(Display *d, Window win)
{
    draw();
    glXSwapBuffers(d, win);
}

int main(int argc, char **argv)
{
    if (argc != 4 && argc != 5) {
        fprintf(stderr, "usage: auto_resize_storm FRAMES SEED viewport|noviewport [DEPTH_BITS]\n");
        return 2;
    }
    unsigned frames = (unsigned)strtoul(argv[1], NULL, 10), frame;
    rng_state = strtoull(argv[2], NULL, 10);
    int viewport = strcmp(argv[3], "viewport") == 0;

    Display *d = XOpenDisplay(NULL);
    if (d == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 2;
    }
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8,
                        GLX_BLUE_SIZE, 8, GLX_DEPTH_SIZE, 24, None};
    XVisualInfo *vi = NULL;
    if (argc == 5) {
        int bits = atoi(argv[4]), n = 0;
        int exact[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True, GLX_RED_SIZE, 8,
                       GLX_DEPTH_SIZE, bits, None};
        GLXFBConfig *configs = glXChooseFBConfig(d, DefaultScreen(d), exact, &n);
        for (int i = 0; i < n && vi == NULL; i++) {
            int depth = -1, stencil = -1;
            glXGetFBConfigAttrib(d, configs[i], GLX_DEPTH_SIZE, &depth);
            glXGetFBConfigAttrib(d, configs[i], GLX_STENCIL_SIZE, &stencil);
            if (depth == bits && stencil == 0)
                vi = glXGetVisualFromFBConfig(d, configs[i]);
        }
        if (configs != NULL)
            XFree(configs);
    } else {
        vi = glXChooseVisual(d, DefaultScreen(d), attributes);
    }
    if (vi == NULL) {
        fprintf(stderr, "no visual with depth\n");
        return 2;
    }
    Window root = RootWindow(d, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(d, root, vi->visual, AllocNone);
    Window win = XCreateWindow(d, root, 0, 0, 64, 64, 0, vi->depth, InputOutput, vi->visual,
                               CWColormap, &wa);
    XMapWindow(d, win);
    GLXContext ctx = glXCreateContext(d, vi, NULL, True);
    if (ctx == NULL || !glXMakeCurrent(d, win, ctx)) {
        fprintf(stderr, "cannot make a context current\n");
        return 2;
    }
    draw_and_swap(d, win);
    for (frame = 0; frame < frames; frame++) {
        unsigned w, h;
        random_size(&w, &h);
        XResizeWindow(d, win, w, h);
        XSync(d, False);
        if (viewport) {
            glViewport(0, 0, (GLsizei)w, (GLsizei)h);
        }
        draw_and_swap(d, win);
    }
    /* One more frame at the last size, read before its swap. */
    GLint vp[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    draw();
    unsigned char px[4] = {0};
    glReadBuffer(GL_BACK);
    glReadPixels(vp[0] + vp[2] / 2, vp[1] + vp[3] / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    printf("centre %d %d %d\n", px[0], px[1], px[2]);
    glXSwapBuffers(d, win);
    printf("error 0x%x\n", glGetError());
    printf("frames %u\n", frames);
    glXMakeCurrent(d, None, NULL);
    glXDestroyContext(d, ctx);
    XDestroyWindow(d, win);
    XCloseDisplay(d);
    return 0;
}

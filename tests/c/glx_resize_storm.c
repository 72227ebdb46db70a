/*
 * A stereo window resized at random, frame after frame: what a user does
 * dragging a window's corner, and what a tiling window manager does. Run
 * under glstereo-run in a fitted format.
 *
 *   glx_resize_storm FRAMES SEED viewport|noviewport MODE
 *
 * After a first frame at 64x64, each frame resizes the window to a random size between 1x1 and
 * 1600x1200 (a quarter of them thin: 1 to 3 pixels wide or high; some
 * square, some the whole 1600x1200), waits for the server, sets the
 * viewport to the new size or (noviewport) leaves it, clears the left
 * back buffer green (0, 255, 0) and the right one cyan (0, 255, 255),
 * swaps once, and checks:
 * - the front buffers: front left green, front right cyan;
 * - the window (XGetImage): in the placement formats (side-by-side,
 *   top-bottom, their halves, hdmi-frame-packing) every pixel a blend of
 *   black, green and cyan (red 0, blue no more than green) and, in a
 *   window of 16x16 or more, some pixels pure green and some pure cyan;
 *   in an anaglyph (MODE starting "anaglyph") every pixel the centre's
 *   colour or letterbox black, the centre not black.
 * A wrong frame prints one line on stderr. The last line on stdout is
 * "frames N wrong M"; the exit status is 0 when M is 0, else 1.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

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

/* Whether the front buffer `buffer` reads (r, g, b) at its corner. */
static int front_is(GLenum buffer, int r, int g, int b, unsigned char got[4])
{
    glReadBuffer(buffer);
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, got);
    return got[0] == r && got[1] == g && got[2] == b;
}

/* Checks the window's pixels; returns a description of the first wrong
 * one, or NULL. */
static const char *check_window(Display *d, Window win, unsigned w, unsigned h, int anaglyph,
                                char *why, size_t len)
{
    XImage *img = XGetImage(d, win, 0, 0, w, h, AllPlanes, ZPixmap);
    if (img == NULL) {
        snprintf(why, len, "XGetImage failed");
        return why;
    }
    unsigned long centre = XGetPixel(img, (int)(w / 2), (int)(h / 2));
    unsigned long mask = img->red_mask | img->green_mask | img->blue_mask;
    unsigned greens = 0, cyans = 0, x, y;
    const char *wrong = NULL;
    if (anaglyph && (centre & mask) == 0) {
        snprintf(why, len, "the centre is black");
        wrong = why;
    }
    for (y = 0; y < h && wrong == NULL; y++) {
        for (x = 0; x < w && wrong == NULL; x++) {
            unsigned long p = XGetPixel(img, (int)x, (int)y);
            unsigned r = (unsigned)((p & img->red_mask) >> 16);
            unsigned g = (unsigned)((p & img->green_mask) >> 8);
            unsigned b = (unsigned)(p & img->blue_mask);
            int bad = anaglyph ? ((p & mask) != (centre & mask) && (p & mask) != 0)
                               : (r != 0 || b > g + 1);
            if (bad) {
                snprintf(why, len, "pixel (%u, %u) is %02x%02x%02x", x, y, r, g, b);
                wrong = why;
            }
            greens += r == 0 && g == 255 && b == 0;
            cyans += r == 0 && g == 255 && b == 255;
        }
    }
    if (wrong == NULL && !anaglyph && w >= 16 && h >= 16 && (greens == 0 || cyans == 0)) {
        snprintf(why, len, "%u pure green and %u pure cyan pixels: an eye is missing", greens,
                 cyans);
        wrong = why;
    }
    XDestroyImage(img);
    return wrong;
}

/* Left back buffer green, right cyan, one swap, the frame on the server. */
static void draw_and_swap(Display *d, Window win)
{
    glDrawBuffer(GL_BACK_LEFT);
    glClearColor(0, 1, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDrawBuffer(GL_BACK_RIGHT);
    glClearColor(0, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glXSwapBuffers(d, win);
    glFinish();
    XSync(d, False);
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: glx_resize_storm FRAMES SEED viewport|noviewport MODE\n");
        return 2;
    }
    unsigned frames = (unsigned)strtoul(argv[1], NULL, 10), frame, wrong = 0;
    rng_state = strtoull(argv[2], NULL, 10);
    int viewport = strcmp(argv[3], "viewport") == 0;
    int anaglyph = strncmp(argv[4], "anaglyph", 8) == 0;

    Display *d = XOpenDisplay(NULL);
    if (d == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 2;
    }
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_RED_SIZE, 8,
                        GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8, None};
    XVisualInfo *vi = glXChooseVisual(d, DefaultScreen(d), attributes);
    if (vi == NULL) {
        fprintf(stderr, "no stereo visual: run me under glstereo-run\n");
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
        fprintf(stderr, "cannot make a stereo context current\n");
        return 2;
    }
    /* A first frame at the first size: the frames below all follow a
     * swap, after which GL takes the window's new size at the first draw. */
    draw_and_swap(d, win);
    for (frame = 0; frame < frames; frame++) {
        unsigned w, h;
        char why[160];
        unsigned char fl[4], fr[4];
        random_size(&w, &h);
        XResizeWindow(d, win, w, h);
        XSync(d, False);
        if (viewport) {
            glViewport(0, 0, (GLsizei)w, (GLsizei)h);
        }
        draw_and_swap(d, win);
        const char *bad = NULL;
        if (!front_is(GL_FRONT_LEFT, 0, 255, 0, fl) || !front_is(GL_FRONT_RIGHT, 0, 255, 255, fr)) {
            snprintf(why, sizeof why, "fronts %02x%02x%02x %02x%02x%02x, want 00ff00 00ffff",
                     fl[0], fl[1], fl[2], fr[0], fr[1], fr[2]);
            bad = why;
        } else {
            bad = check_window(d, win, w, h, anaglyph, why, sizeof why);
        }
        if (bad != NULL) {
            fprintf(stderr, "frame %u at %ux%u: %s\n", frame, w, h, bad);
            wrong++;
        }
    }
    printf("frames %u wrong %u\n", frames, wrong);
    glXMakeCurrent(d, None, NULL);
    glXDestroyContext(d, ctx);
    XDestroyWindow(d, win);
    XCloseDisplay(d);
    return wrong == 0 ? 0 : 1;
}

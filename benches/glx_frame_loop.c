/*
 * Frame-loop benchmark for the LD_PRELOAD layer: an ordinary GLX program
 * (links only -lGL -lX11) drawing a light scene in a loop, mono or stereo,
 * timed per frame (draw + glXSwapBuffers + glFinish). Run it as
 * benches/glx_frame_loop.sh does: mono without the layer, mono and stereo
 * under glstereo-run, stereo with --capture.
 *
 *   glx_frame_loop mono|stereo [WIDTH HEIGHT [FRAMES]]
 *
 * Light scene: per eye a clear and three rectangles. Prints
 * "<mode> WxH frames N: mean M ms, median D ms, p90 P ms".
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void scene(float shift)
{
    glClearColor(0.2f, 0.2f, 0.2f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glColor3f(0.0f, 0.0f, 1.0f);
    glRectf(-0.8f + shift, -0.8f, 0.2f + shift, 0.2f);
    glColor3f(1.0f, 0.0f, 0.0f);
    glRectf(-0.2f + shift, -0.2f, 0.8f + shift, 0.8f);
    glColor3f(0.0f, 1.0f, 0.0f);
    glRectf(-0.1f + shift, -0.9f, 0.1f + shift, -0.5f);
}

int main(int argc, char **argv)
{
    int stereo = argc > 1 && strcmp(argv[1], "stereo") == 0;
    int width = argc > 3 ? atoi(argv[2]) : 1280;
    int height = argc > 3 ? atoi(argv[3]) : 1024;
    int frames = argc > 4 ? atoi(argv[4]) : 200;
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 16, None, None};
    if (stereo) attributes[4] = GLX_STEREO;
    Display *display = XOpenDisplay(NULL);
    if (display == NULL) return 1;
    XVisualInfo *vi = glXChooseVisual(display, DefaultScreen(display), attributes);
    if (vi == NULL) {
        fprintf(stderr, "no %s visual\n", stereo ? "stereo" : "mono");
        return 2;
    }
    Window root = RootWindow(display, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(display, root, vi->visual, AllocNone);
    Window win = XCreateWindow(display, root, 0, 0, (unsigned)width, (unsigned)height, 0,
                               vi->depth, InputOutput, vi->visual, CWColormap, &wa);
    XMapWindow(display, win);
    XSync(display, False);
    GLXContext ctx = glXCreateContext(display, vi, NULL, True);
    if (ctx == NULL || !glXMakeCurrent(display, win, ctx)) return 1;

    double *t = malloc(sizeof(double) * (size_t)frames);
    for (int warm = 0; warm < 10; warm++) {
        scene(0.0f);
        glXSwapBuffers(display, win);
    }
    glFinish();
    for (int i = 0; i < frames; i++) {
        double t0 = now_ms();
        float s = (float)(i % 10) * 0.01f;
        if (stereo) {
            glDrawBuffer(GL_BACK_LEFT);
            scene(s);
            glDrawBuffer(GL_BACK_RIGHT);
            scene(-s);
        } else {
            scene(s);
        }
        glXSwapBuffers(display, win);
        glFinish();
        t[i] = now_ms() - t0;
    }
    double sum = 0;
    for (int i = 0; i < frames; i++) sum += t[i];
    qsort(t, (size_t)frames, sizeof t[0], cmp);
    printf("%s %dx%d frames %d: mean %.2f ms, median %.2f ms, p90 %.2f ms\n",
           stereo ? "stereo" : "mono", width, height, frames, sum / frames, t[frames / 2],
           t[frames * 9 / 10]);
    free(t);
    glXMakeCurrent(display, None, NULL);
    glXDestroyContext(display, ctx);
    XDestroyWindow(display, win);
    XCloseDisplay(display);
    return 0;
}

/*
 * A legacy GLX stereo program, as HP's stereo guide (seed 000 §3-4) writes
 * one: glXChooseVisual with GLX_STEREO, glDrawBuffer per eye, one
 * glXSwapBuffers. Unmodified: it knows nothing of glstereo and links only
 * -lGL -lX11. Run it under glstereo-run.
 *
 *   legacy_stereo [WIDTH HEIGHT [single]]
 *
 * It draws the RedBlue frame (grey 0.2 background; left eye: blue rectangle
 * (-0.8,-0.8)-(0.2,0.2); right eye: red rectangle (-0.2,-0.2)-(0.8,0.8)),
 * swaps, prints what GL reported and "ready 0x<window>", then reads a line
 * on stdin (the test grabs the window meanwhile): "resize W H" resizes the
 * window, sets the viewport as a reshape handler would, draws and presents
 * again; "wmresize W H" resizes it as a window manager would for a program
 * without a reshape handler (the viewport stays), draws and presents again;
 * anything else (or EOF) exits 0. With "single" the visual is
 * single-buffered: it draws GL_FRONT_LEFT / GL_FRONT_RIGHT and calls
 * glFlush instead of swapping. Without a stereo visual it says so on stderr
 * and exits 2, as the guide advises.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

static void redblue_frame(int single)
{
    glDrawBuffer(single ? GL_FRONT : GL_BACK);
    glClearColor(0.2f, 0.2f, 0.2f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);

    glDrawBuffer(single ? GL_FRONT_LEFT : GL_BACK_LEFT);
    glColor3f(0.0f, 0.0f, 1.0f);
    glRectf(-0.8f, -0.8f, 0.2f, 0.2f);

    glDrawBuffer(single ? GL_FRONT_RIGHT : GL_BACK_RIGHT);
    glColor3f(1.0f, 0.0f, 0.0f);
    glRectf(-0.2f, -0.2f, 0.8f, 0.8f);
}

int main(int argc, char **argv)
{
    int width = argc > 2 ? atoi(argv[1]) : 160;
    int height = argc > 2 ? atoi(argv[2]) : 120;
    int single = argc > 3 && strcmp(argv[3], "single") == 0;
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                        GLX_BLUE_SIZE, 1, GLX_DEPTH_SIZE, 1, GLX_STEREO, None};
    if (single) {
        attributes[1] = GLX_USE_GL; /* no GLX_DOUBLEBUFFER */
    }
    Display *display = XOpenDisplay(NULL);
    if (display == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    XVisualInfo *vi = glXChooseVisual(display, DefaultScreen(display), attributes);
    if (vi == NULL) {
        fprintf(stderr, "no stereo visual: windowed OpenGL stereo is not supported\n");
        return 2;
    }
    int glx_stereo = 0;
    glXGetConfig(display, vi, GLX_STEREO, &glx_stereo);

    Window root = RootWindow(display, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(display, root, vi->visual, AllocNone);
    wa.border_pixel = 0;
    Window win = XCreateWindow(display, root, 0, 0, (unsigned)width, (unsigned)height, 0, vi->depth,
                               InputOutput, vi->visual, CWColormap | CWBorderPixel, &wa);
    XStoreName(display, win, "legacy_stereo");
    XMapWindow(display, win);
    XSync(display, False);

    GLXContext ctx = glXCreateContext(display, vi, NULL, True);
    if (ctx == NULL || !glXMakeCurrent(display, win, ctx)) {
        fprintf(stderr, "cannot make a GL context current\n");
        return 1;
    }
    GLboolean stereo = GL_FALSE;
    glGetBooleanv(GL_STEREO, &stereo);
    GLint fb = -1, draw = -1;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
    glGetIntegerv(GL_DRAW_BUFFER, &draw);

    for (;;) {
        redblue_frame(single);
        if (single) {
            glFlush();
        } else {
            glXSwapBuffers(display, win);
        }
        glFinish();

        printf("glx_stereo %d gl_stereo %d framebuffer %d draw_buffer 0x%x error 0x%x\n",
               glx_stereo, stereo, fb, (unsigned)draw, glGetError());
        printf("ready 0x%lx\n", (unsigned long)win);
        fflush(stdout);

        char line[64];
        int w, h;
        if (fgets(line, sizeof line, stdin) == NULL) {
            break;
        }
        int reshape = sscanf(line, "resize %d %d", &w, &h) == 2;
        if (!reshape && sscanf(line, "wmresize %d %d", &w, &h) != 2) {
            break;
        }
        XResizeWindow(display, win, (unsigned)w, (unsigned)h);
        XSync(display, False);
        if (reshape) {
            glViewport(0, 0, w, h);
        }
    }
    glXMakeCurrent(display, None, NULL);
    glXDestroyContext(display, ctx);
    XDestroyWindow(display, win);
    XFree(vi);
    XCloseDisplay(display);
    return 0;
}

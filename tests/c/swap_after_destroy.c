/*
 * A stereo GLX program that destroys its window and then still swaps (a
 * bug, but one a program makes while shutting down): it draws and swaps
 * three frames, destroys the window, then draws and swaps twice more on
 * the destroyed window, and prints "survived" if none of that ended the
 * process. Under glstereo-run the layer must neither crash nor let an X
 * error of its own requests reach the program's (default, fatal) error
 * handler. Links only -lGL -lX11.
 */
#include <stdio.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

static void frame(void)
{
    glDrawBuffer(GL_BACK_LEFT);
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDrawBuffer(GL_BACK_RIGHT);
    glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

int main(void)
{
    Display *d = XOpenDisplay(NULL);
    if (d == NULL) return 1;
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, None};
    XVisualInfo *vi = glXChooseVisual(d, DefaultScreen(d), attributes);
    if (vi == NULL) {
        fprintf(stderr, "no stereo visual\n");
        return 2;
    }
    Window root = RootWindow(d, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(d, root, vi->visual, AllocNone);
    Window w = XCreateWindow(d, root, 0, 0, 100, 80, 0, vi->depth, InputOutput, vi->visual,
                             CWColormap, &wa);
    XMapWindow(d, w);
    XSync(d, False);
    GLXContext c = glXCreateContext(d, vi, NULL, True);
    if (c == NULL || !glXMakeCurrent(d, w, c)) return 1;
    for (int i = 0; i < 3; i++) {
        frame();
        glXSwapBuffers(d, w);
    }
    glFinish();
    XDestroyWindow(d, w);
    XSync(d, False);
    for (int i = 0; i < 2; i++) {
        frame();
        glXSwapBuffers(d, w);
        glFinish();
        XSync(d, False);
    }
    printf("survived\n");
    glXMakeCurrent(d, None, NULL);
    glXDestroyContext(d, c);
    XFree(vi);
    XCloseDisplay(d);
    return 0;
}

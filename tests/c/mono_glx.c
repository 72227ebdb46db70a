/*
 * An ordinary mono GLX program (links only -lGL -lX11): a double-buffered
 * visual without GLX_STEREO, a frame of coloured rectangles and a shaded
 * triangle, one swap. Under glstereo-run it must run exactly as without it.
 *
 * Prints what GL reports about its default framebuffer, then
 * "ready 0x<window>", waits for a line on stdin (the test grabs the window)
 * and exits 0.
 */
#include <stdio.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

#include "x_window.h"

#define DRAW_FRAMEBUFFER_BINDING 0x8CA6

static GLint get_int(GLenum pname)
{
    GLint v = -1;
    glGetIntegerv(pname, &v);
    return v;
}

int main(void)
{
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 16, None};
    struct x_window x = open_x_window(attributes, 160, 120);
    Display *display = x.display;
    Window win = x.window;

    glClearColor(0.1f, 0.3f, 0.5f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glColor3f(1.0f, 0.5f, 0.0f);
    glRectf(-0.9f, -0.9f, 0.0f, 0.0f);
    glBegin(GL_TRIANGLES);
    glColor3f(1.0f, 0.0f, 0.0f);
    glVertex2f(0.0f, 0.9f);
    glColor3f(0.0f, 1.0f, 0.0f);
    glVertex2f(0.9f, -0.9f);
    glColor3f(0.0f, 0.0f, 1.0f);
    glVertex2f(-0.5f, 0.5f);
    glEnd();
    glXSwapBuffers(display, win);
    glFinish();

    GLboolean stereo = GL_TRUE;
    glGetBooleanv(GL_STEREO, &stereo);
    printf("stereo %d draw_buffer 0x%x read_buffer 0x%x framebuffer %d error 0x%x\n", stereo,
           (unsigned)get_int(GL_DRAW_BUFFER), (unsigned)get_int(GL_READ_BUFFER),
           get_int(DRAW_FRAMEBUFFER_BINDING), glGetError());
    printf("ready 0x%lx\n", (unsigned long)win);
    fflush(stdout);

    char line[64];
    if (fgets(line, sizeof line, stdin) == NULL) {
        /* EOF: exit as well. */
    }
    close_x_window(&x);
    return 0;
}

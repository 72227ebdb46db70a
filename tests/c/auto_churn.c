/*
 * Context churn under automatic stereo (glstereo-run --auto or
 * --auto=depth): a mono program makes a window and a GL context, draws
 * three frames (a backdrop from a vertex array with the depth test off, a
 * triangle in front of it with the test on, the depth cleared and a small
 * triangle in a corner viewport, a swap), destroys both, forty
 * times on one display connection, and prints "sample N rss_kb memfd fds"
 * after contexts 10 and 40. Each automatic-stereo context's eyes, and
 * under --auto=depth the depth its draws with the test off write beside
 * them and the copy of the scene's depth kept at the clear, must go with
 * it: the samples stay flat.
 */
#define _POSIX_C_SOURCE 200809L
#include <GL/gl.h>
#include <dirent.h>
#include <malloc.h>
#include <string.h>

#include "x_window.h"

/* Resident memory in use: glibc's free pages given back first (a moment's
 * peak grows an arena that is otherwise kept; see proc_usage.h). */
static long rss_kb(void)
{
    malloc_trim(0);
    FILE *f = fopen("/proc/self/statm", "r");
    long size = 0, resident = 0;
    if (f != NULL) {
        if (fscanf(f, "%ld %ld", &size, &resident) != 2) resident = 0;
        fclose(f);
    }
    return resident * 4;
}

static int memfd_mappings(void)
{
    FILE *f = fopen("/proc/self/maps", "r");
    char line[512];
    int n = 0;
    while (f != NULL && fgets(line, sizeof line, f) != NULL)
        if (strstr(line, "memfd:") != NULL) n++;
    if (f != NULL) fclose(f);
    return n;
}

static int open_fds(void)
{
    DIR *d = opendir("/proc/self/fd");
    int n = 0;
    while (d != NULL && readdir(d) != NULL) n++;
    if (d != NULL) closedir(d);
    return n;
}

int main(void)
{
    struct x_window first = open_x_window_config(NULL, 320, 240);
    static const int attributes[] = {GLX_X_RENDERABLE, True, GLX_DRAWABLE_TYPE, GLX_WINDOW_BIT,
                                     GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True,
                                     GLX_RED_SIZE, 8, GLX_DEPTH_SIZE, 24, None};
    int n = 0;
    GLXFBConfig *configs = glXChooseFBConfig(first.display, DefaultScreen(first.display),
                                             attributes, &n);
    if (configs == NULL || n == 0) return 1;
    Window root = RootWindow(first.display, first.visual->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(first.display, root, first.visual->visual, AllocNone);
    for (int i = 1; i <= 40; i++) {
        Window w = XCreateWindow(first.display, root, 0, 0, 320, 240, 0, first.visual->depth,
                                 InputOutput, first.visual->visual, CWColormap, &wa);
        XMapWindow(first.display, w);
        XSync(first.display, False);
        GLXContext c = glXCreateNewContext(first.display, configs[0], GLX_RGBA_TYPE, NULL, True);
        if (c == NULL || !glXMakeCurrent(first.display, w, c)) return 1;
        for (int f = 0; f < 3; f++) {
            glClearColor(0.2f, 0.2f, 0.2f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glMatrixMode(GL_PROJECTION);
            glLoadIdentity();
            glFrustum(-1, 1, -0.75, 0.75, 1, 50);
            /* The backdrop at w 8, drawn first with the depth test off. */
            static const GLfloat backdrop[] = {-4, -3, -8, 4, -3, -8, 4, 3, -8, -4, 3, -8};
            glDisable(GL_DEPTH_TEST);
            glColor3f(0.0f, 0.0f, 1.0f);
            glEnableClientState(GL_VERTEX_ARRAY);
            glVertexPointer(3, GL_FLOAT, 0, backdrop);
            glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
            glDisableClientState(GL_VERTEX_ARRAY);
            glEnable(GL_DEPTH_TEST);
            glColor3f(1.0f, 0.0f, 0.0f);
            glBegin(GL_TRIANGLES);
            glVertex3f(-1, -1, -4);
            glVertex3f(1, -1, -4);
            glVertex3f(0, 1, -4);
            glEnd();
            /* The depth cleared and a gizmo drawn in a corner viewport (the
             * scene's depth is copied aside before the clear). */
            glClear(GL_DEPTH_BUFFER_BIT);
            glViewport(0, 0, 64, 48);
            glBegin(GL_TRIANGLES);
            glVertex3f(-1, -1, -3);
            glVertex3f(1, -1, -3);
            glVertex3f(0, 1, -3);
            glEnd();
            glViewport(0, 0, 320, 240);
            glXSwapBuffers(first.display, w);
        }
        glXMakeCurrent(first.display, None, NULL);
        glXDestroyContext(first.display, c);
        XDestroyWindow(first.display, w);
        if (i == 10 || i == 40)
            printf("sample %d %ld %d %d\n", i, rss_kb(), memfd_mappings(), open_fds());
    }
    XFree(configs);
    close_x_window(&first);
    return 0;
}

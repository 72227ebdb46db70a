/*
 * A hostile EGL program on X11 (issue 31): it makes and destroys EGL
 * contexts and window surfaces in every order EGL allows, and some it
 * refuses, resizes its windows to extreme sizes, terminates and
 * re-initializes the display while a context is current, and forks.
 * Every EGL call's result and error, and what glReadPixels reads of a
 * clear and of an orthographic quad (the same in a mono program and in
 * both eyes of automatic stereo: w = 1), go to stdout, one line each:
 * run without the layer, Mesa's answers are the oracle; under
 * `glstereo-run --auto` the lines must be the same.
 *
 *   egl_churn ROUNDS
 *
 * At the end "usage rss EARLY LATE fds EARLY LATE heap EARLY LATE" of
 * the second and the last quarter of the rounds (proc_usage.h: memory and
 * descriptors must stay flat); stderr carries nothing of ours.
 */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <X11/Xlib.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "proc_usage.h"

static Display *x;
static EGLDisplay dpy;
static EGLConfig config;

static void say(const char *what, long r)
{
    printf("%s %ld 0x%x\n", what, r, (unsigned)eglGetError());
}

static Window window(int w, int h)
{
    Window win = XCreateSimpleWindow(x, DefaultRootWindow(x), 0, 0, (unsigned)w,
                                     (unsigned)h, 0, 0, 0);
    XMapWindow(x, win);
    XSync(x, False);
    return win;
}

static EGLContext context(EGLContext share)
{
    static const EGLint attrs[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    EGLContext c = eglCreateContext(dpy, config, share, attrs);
    say("create-context", c != EGL_NO_CONTEXT);
    return c;
}

static EGLSurface surface(Window win)
{
    EGLSurface s = eglCreateWindowSurface(dpy, config, (EGLNativeWindowType)win, NULL);
    say("create-surface", s != EGL_NO_SURFACE);
    return s;
}

/* A clear and an orthographic quad over the middle, then what the
 * program reads back at two places: the same in both eyes. */
static void draw(float red)
{
    static GLuint program;
    if (!program || !glIsProgram(program)) {
        const char *vs = "attribute vec2 p; void main() { gl_Position = vec4(p, 0.0, 1.0); }";
        const char *fs = "precision mediump float; void main() { gl_FragColor = vec4(0.0, 1.0, 0.0, 1.0); }";
        GLuint v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER);
        glShaderSource(v, 1, &vs, NULL);
        glShaderSource(f, 1, &fs, NULL);
        glCompileShader(v);
        glCompileShader(f);
        program = glCreateProgram();
        glAttachShader(program, v);
        glAttachShader(program, f);
        glBindAttribLocation(program, 0, "p");
        glLinkProgram(program);
        glDeleteShader(v);
        glDeleteShader(f);
    }
    static const float quad[] = {-0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, 0.5f};
    glClearColor(red, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(program);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, quad);
    glEnableVertexAttribArray(0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    EGLint w = 0, h = 0;
    EGLSurface s = eglGetCurrentSurface(EGL_DRAW);
    eglQuerySurface(dpy, s, EGL_WIDTH, &w);
    eglQuerySurface(dpy, s, EGL_HEIGHT, &h);
    unsigned char corner[4] = {0}, middle[4] = {0};
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, corner);
    glReadPixels(w / 2, h / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, middle);
    printf("size %dx%d read %d %d %d / %d %d %d gl 0x%x\n", w, h, corner[0], corner[1],
           corner[2], middle[0], middle[1], middle[2], glGetError());
}

static void init(void)
{
    dpy = eglGetDisplay((EGLNativeDisplayType)x);
    EGLint major, minor;
    say("initialize", eglInitialize(dpy, &major, &minor));
    static const EGLint want[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RED_SIZE, 8,
                                  EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_NONE};
    EGLint n = 0;
    say("choose-config", eglChooseConfig(dpy, want, &config, 1, &n) && n == 1);
    say("bind-api", eglBindAPI(EGL_OPENGL_ES_API));
}

int main(int argc, char **argv)
{
    int rounds = argc > 1 ? atoi(argv[1]) : 8;
    x = XOpenDisplay(NULL);
    if (!x) {
        fprintf(stderr, "egl_churn: no X display\n");
        return 2;
    }
    init();
    struct usage_window early = {0}, late = {0};
    static const int sizes[][2] = {{64, 48}, {1, 1}, {3, 500}, {640, 2}, {333, 211}};
    for (int i = 0; i < rounds; i++) {
        printf("round %d kind %d\n", i, i % 6);
        Window win = window(64 + i % 7, 48 + i % 5);
        EGLContext c = context(EGL_NO_CONTEXT);
        EGLSurface s = surface(win);
        say("make-current", eglMakeCurrent(dpy, s, s, c));
        draw(0.25f);
        say("swap", eglSwapBuffers(dpy, s));
        switch (i % 6) {
        case 0:
            /* The surface destroyed while current: EGL defers it; the
             * context draws on until released. */
            say("destroy-surface-current", eglDestroySurface(dpy, s));
            draw(0.5f);
            say("swap-destroyed", eglSwapBuffers(dpy, s));
            say("release", eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
            say("swap-gone", eglSwapBuffers(dpy, s));
            say("destroy-context", eglDestroyContext(dpy, c));
            break;
        case 1: {
            /* The context destroyed while current, then another made
             * current on the same surface, sharing nothing. */
            say("destroy-context-current", eglDestroyContext(dpy, c));
            draw(0.5f);
            EGLContext d = context(EGL_NO_CONTEXT);
            say("make-current-other", eglMakeCurrent(dpy, s, s, d));
            draw(0.75f);
            say("swap", eglSwapBuffers(dpy, s));
            say("make-current-destroyed", eglMakeCurrent(dpy, s, s, c));
            say("release", eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
            say("destroy-context", eglDestroyContext(dpy, d));
            say("destroy-surface", eglDestroySurface(dpy, s));
            break;
        }
        case 2:
            /* Resized to thin, tiny and odd sizes between frames. */
            for (unsigned k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
                XResizeWindow(x, win, (unsigned)sizes[k][0], (unsigned)sizes[k][1]);
                XSync(x, False);
                say("swap-resized", eglSwapBuffers(dpy, s));
                draw(0.5f);
                say("swap", eglSwapBuffers(dpy, s));
            }
            say("release", eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
            say("destroy-surface", eglDestroySurface(dpy, s));
            say("destroy-context", eglDestroyContext(dpy, c));
            break;
        case 3: {
            /* Two windows, two contexts sharing, alternating; then the
             * bad calls EGL refuses. */
            Window win2 = window(50, 40);
            EGLSurface s2 = surface(win2);
            EGLContext d = context(c);
            for (int k = 0; k < 4; k++) {
                say("make-current-a", eglMakeCurrent(dpy, s, s, k % 2 ? c : d));
                draw(0.5f);
                say("swap-a", eglSwapBuffers(dpy, s));
                say("make-current-b", eglMakeCurrent(dpy, s2, s2, k % 2 ? d : c));
                draw(0.75f);
                say("swap-b", eglSwapBuffers(dpy, s2));
            }
            say("swap-null", eglSwapBuffers(dpy, EGL_NO_SURFACE));
            say("swap-bad-display", eglSwapBuffers(EGL_NO_DISPLAY, s));
            say("make-current-mixed", eglMakeCurrent(dpy, s, s2, c));
            say("release", eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
            say("destroy-context", eglDestroyContext(dpy, d));
            say("destroy-context", eglDestroyContext(dpy, c));
            say("destroy-surface", eglDestroySurface(dpy, s2));
            say("destroy-surface", eglDestroySurface(dpy, s));
            XDestroyWindow(x, win2);
            break;
        }
        case 4:
            /* The display terminated while the context is current: the
             * context and surface live until released. First at 64x48,
             * where llvmpipe's rows have no padding: a layer whose second
             * eye's memory begins right after the first's must keep what
             * the program draws after the terminate out of that memory
             * (the driver reads the word before the second eye when it
             * frees the memory at the release). */
            XResizeWindow(x, win, 64, 48);
            XSync(x, False);
            draw(0.25f);
            say("swap-64x48", eglSwapBuffers(dpy, s));
            say("terminate-current", eglTerminate(dpy));
            draw(0.5f);
            say("swap-terminated", eglSwapBuffers(dpy, s));
            say("release-thread", eglReleaseThread());
            init();
            break;
        case 5: {
            /* The X window destroyed under the surface, then a fork whose
             * child draws with its own display. */
            say("release", eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
            say("destroy-surface", eglDestroySurface(dpy, s));
            XDestroyWindow(x, win);
            win = 0;
            fflush(stdout);
            pid_t child = fork();
            if (child == 0) {
                x = XOpenDisplay(NULL);
                init();
                Window w2 = window(40, 30);
                EGLContext cc = context(EGL_NO_CONTEXT);
                EGLSurface cs = surface(w2);
                say("child-make-current", eglMakeCurrent(dpy, cs, cs, cc));
                draw(0.5f);
                say("child-swap", eglSwapBuffers(dpy, cs));
                fflush(stdout);
                _exit(0);
            }
            int status = 0;
            waitpid(child, &status, 0);
            printf("child exited %d\n", WIFEXITED(status) ? WEXITSTATUS(status) : -1);
            say("destroy-context", eglDestroyContext(dpy, c));
            break;
        }
        }
        if (win)
            XDestroyWindow(x, win);
        XSync(x, False);
        usage_round(i, rounds, &early, &late);
    }
    eglTerminate(dpy);
    eglReleaseThread();
    printf("done\n");
    usage_print(&early, &late);
    XCloseDisplay(x);
    return 0;
}

/*
 * Two threads drawing through EGL at once (issue 31), each with its own X
 * window, EGL window surface and OpenGL ES 2 context on one EGLDisplay,
 * FRAMES frames each: a clear of the thread's own colour and an
 * orthographic quad (w = 1: the same in both eyes under --auto), read
 * back every frame. A thread whose read-back is not its own picture, or
 * that sees an EGL or GL error, says so; at the end each prints
 * "thread N ok FRAMES" or what went wrong.
 *
 * With "terminate", the windows are 64x48 (rows without padding in
 * llvmpipe) and the main thread calls eglTerminate halfway, while both
 * contexts are current on their threads: EGL keeps them usable until
 * released, so the threads go on drawing and reading their pictures
 * (their swaps now fail with EGL_NOT_INITIALIZED), then release them,
 * which frees them in the driver.
 *
 *   egl_threads FRAMES [terminate]
 */
#define _POSIX_C_SOURCE 200112L
#include <EGL/egl.h>
#include <GLES2/gl2.h>
#include <X11/Xlib.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static EGLDisplay dpy;
static EGLConfig config;
static Display *x;
static int frames;
static int terminate;
static int width = 100, height = 80;
static pthread_barrier_t halfway;
static pthread_mutex_t xlock = PTHREAD_MUTEX_INITIALIZER;

struct job {
    int n;
    Window win;
    int bad;
    char why[160];
};

static void *run(void *arg)
{
    struct job *j = arg;
    static const EGLint attrs[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    EGLContext c = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attrs);
    pthread_mutex_lock(&xlock);
    EGLSurface s = eglCreateWindowSurface(dpy, config, (EGLNativeWindowType)j->win, NULL);
    pthread_mutex_unlock(&xlock);
    if (c == EGL_NO_CONTEXT || s == EGL_NO_SURFACE || !eglMakeCurrent(dpy, s, s, c)) {
        j->bad = 1;
        snprintf(j->why, sizeof j->why, "setup failed: 0x%x", (unsigned)eglGetError());
        return NULL;
    }
    const char *vs = "attribute vec2 p; void main() { gl_Position = vec4(p, 0.0, 1.0); }";
    const char *fs = "precision mediump float; uniform vec4 c; void main() { gl_FragColor = c; }";
    GLuint v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER);
    glShaderSource(v, 1, &vs, NULL);
    glShaderSource(f, 1, &fs, NULL);
    glCompileShader(v);
    glCompileShader(f);
    GLuint prog = glCreateProgram();
    glAttachShader(prog, v);
    glAttachShader(prog, f);
    glBindAttribLocation(prog, 0, "p");
    glLinkProgram(prog);
    static const float quad[] = {-0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, 0.5f};
    for (int i = 0; i < frames && !j->bad; i++) {
        float red = j->n ? 1.0f : 0.0f, blue = (float)(i % 2);
        glClearColor(red, 0.0f, blue, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glUseProgram(prog);
        glUniform4f(glGetUniformLocation(prog, "c"), 0.0f, 1.0f, red, 1.0f);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, quad);
        glEnableVertexAttribArray(0);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        unsigned char corner[4], middle[4];
        glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, corner);
        glReadPixels(width / 2, height / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, middle);
        int want_r = j->n ? 255 : 0, want_b = (i % 2) ? 255 : 0;
        if (corner[0] != want_r || corner[1] != 0 || corner[2] != want_b || middle[0] != 0 ||
            middle[1] != 255 || middle[2] != want_r) {
            j->bad = 1;
            snprintf(j->why, sizeof j->why,
                     "frame %d read %d %d %d / %d %d %d, want %d 0 %d / 0 255 %d", i, corner[0],
                     corner[1], corner[2], middle[0], middle[1], middle[2], want_r, want_b,
                     want_r);
        }
        GLenum e = glGetError();
        int terminated = terminate && i > frames / 2;
        EGLBoolean swapped = eglSwapBuffers(dpy, s);
        EGLint egl_error = eglGetError();
        if (terminated ? swapped || egl_error != EGL_NOT_INITIALIZED
                       : !swapped || e != GL_NO_ERROR) {
            j->bad = 1;
            snprintf(j->why, sizeof j->why, "frame %d: GL 0x%x EGL %d 0x%x", i, e, swapped,
                     (unsigned)egl_error);
        }
        if (terminate && i == frames / 2) {
            /* Both threads here: the main thread terminates; then on. */
            pthread_barrier_wait(&halfway);
            pthread_barrier_wait(&halfway);
        }
    }
    if (terminate && j->bad) {
        /* The main thread waits for this thread at halfway. */
        pthread_barrier_wait(&halfway);
        pthread_barrier_wait(&halfway);
    }
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroySurface(dpy, s);
    eglDestroyContext(dpy, c);
    eglReleaseThread();
    return NULL;
}

int main(int argc, char **argv)
{
    frames = argc > 1 ? atoi(argv[1]) : 100;
    terminate = argc > 2 && !strcmp(argv[2], "terminate");
    if (terminate) {
        width = 64;
        height = 48;
    }
    pthread_barrier_init(&halfway, NULL, 3);
    XInitThreads();
    x = XOpenDisplay(NULL);
    if (!x) {
        fprintf(stderr, "egl_threads: no X display\n");
        return 2;
    }
    dpy = eglGetDisplay((EGLNativeDisplayType)x);
    EGLint major, minor, n = 0;
    static const EGLint want[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RED_SIZE, 8,
                                  EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_NONE};
    if (!eglInitialize(dpy, &major, &minor) || !eglChooseConfig(dpy, want, &config, 1, &n) ||
        n != 1 || !eglBindAPI(EGL_OPENGL_ES_API)) {
        fprintf(stderr, "egl_threads: no EGL config\n");
        return 2;
    }
    struct job jobs[2];
    pthread_t t[2];
    for (int i = 0; i < 2; i++) {
        jobs[i].n = i;
        jobs[i].bad = 0;
        jobs[i].why[0] = 0;
        jobs[i].win = XCreateSimpleWindow(x, DefaultRootWindow(x), i * 120, 0, (unsigned)width,
                                          (unsigned)height, 0, 0, 0);
        XMapWindow(x, jobs[i].win);
    }
    XSync(x, False);
    for (int i = 0; i < 2; i++)
        pthread_create(&t[i], NULL, run, &jobs[i]);
    if (terminate) {
        pthread_barrier_wait(&halfway);
        if (!eglTerminate(dpy))
            printf("eglTerminate failed: 0x%x\n", (unsigned)eglGetError());
        pthread_barrier_wait(&halfway);
    }
    int status = 0;
    for (int i = 0; i < 2; i++) {
        pthread_join(t[i], NULL);
        if (jobs[i].bad) {
            printf("thread %d: %s\n", i, jobs[i].why);
            status = 1;
        } else {
            printf("thread %d ok %d\n", i, frames);
        }
    }
    eglTerminate(dpy);
    XCloseDisplay(x);
    return status;
}

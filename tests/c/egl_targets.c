/*
 * A hostile OpenGL ES 3.2 program's render targets (issue 31): under
 * `glstereo-run --auto` the layer gives an ES program's framebuffer
 * objects eyes by binding what it needs and binding back, and names each
 * texture by the target the program defined it with. This program makes
 * targets of every kind ES has — 2D textures of glTexImage2D and
 * glTexStorage2D with mipmaps, cube map faces, 2D array layers,
 * multisample textures and renderbuffers resolved by blits, a texture
 * deleted while attached and its name made a cube map — at sizes from
 * 1x1 to 640x2, copies between them (glCopyTexSubImage2D,
 * glCopyImageSubData, and copies ES refuses), deletes framebuffers while
 * bound, and makes a new context (a new share group) every 8 rounds.
 * Its draws are orthographic (w = 1: both eyes the same as the mono
 * picture), so every pixel it reads back, every binding it asks for and
 * every GL error is what Mesa gives without the layer: run without the
 * layer, Mesa's answers are the oracle; under --auto the lines must be
 * the same.
 *
 *   egl_targets ROUNDS
 *
 * At the end "usage rss EARLY LATE fds EARLY LATE heap EARLY LATE" of
 * the second and the last quarter of the rounds (proc_usage.h: memory and
 * descriptors must stay flat).
 */
#include <EGL/egl.h>
#include <GLES3/gl32.h>
#include <X11/Xlib.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "proc_usage.h"

static GLuint solid, textured;

static GLuint program(const char *fs)
{
    const char *vs = "#version 300 es\nin vec2 p; out vec2 uv;\n"
                     "void main() { uv = p * 0.5 + 0.5; gl_Position = vec4(p, 0.0, 1.0); }\n";
    GLuint v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER);
    glShaderSource(v, 1, &vs, NULL);
    glShaderSource(f, 1, &fs, NULL);
    glCompileShader(v);
    glCompileShader(f);
    GLuint p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glBindAttribLocation(p, 0, "p");
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        fprintf(stderr, "egl_targets: a program does not link\n");
        exit(3);
    }
    return p;
}

static void programs(void)
{
    solid = program("#version 300 es\nprecision mediump float;\nuniform vec4 c; out vec4 o;\n"
                    "void main() { o = c; }\n");
    textured = program("#version 300 es\nprecision mediump float;\nuniform sampler2D t;\n"
                       "in vec2 uv; out vec4 o;\nvoid main() { o = texture(t, uv) * 0.5 + 0.25; }\n");
}

/* An orthographic quad over the middle half of the viewport, of colour
 * (r, g, b), or sampling the 2D texture on unit 0 with `tex`. */
static void quad(float r, float g, float b, int tex)
{
    static const float v[] = {-0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, 0.5f};
    GLuint p = tex ? textured : solid;
    glUseProgram(p);
    if (tex)
        glUniform1i(glGetUniformLocation(p, "t"), 0);
    else
        glUniform4f(glGetUniformLocation(p, "c"), r, g, b, 1.0f);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, v);
    glEnableVertexAttribArray(0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

/* The objects this round made, by kind (names differ with the layer,
 * which makes objects of its own in the program's share group: each
 * binding is printed as which of the round's objects it is). */
static GLuint made[3][8];
static int made_n[3];

static GLuint mark(int kind, GLuint name)
{
    if (made_n[kind] < 8)
        made[kind][made_n[kind]++] = name;
    return name;
}

static int which(int kind, GLint name)
{
    if (name == 0)
        return 0;
    for (int i = made_n[kind] - 1; i >= 0; i--)
        if (made[kind][i] == (GLuint)name)
            return i + 1;
    return -1;
}

/* What the program reads of the read framebuffer (w x h) at its corner
 * and middle, its bindings, and the GL error. */
static void report(const char *what, int w, int h)
{
    unsigned char a[4] = {0}, b[4] = {0};
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, a);
    glReadPixels(w / 2, h / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, b);
    GLint draw = 0, read = 0, tex = 0, rb = 0, active = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &rb);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    printf("%s %dx%d read %d %d %d %d / %d %d %d %d bound %d %d %d %d 0x%x gl 0x%x\n", what, w, h,
           a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3], which(0, draw), which(0, read),
           which(1, tex), which(2, rb), active,
           glGetError());
}

static GLuint texture_2d(int w, int h, int storage)
{
    GLuint t;
    glGenTextures(1, &t);
    mark(1, t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, storage ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (storage)
        glTexStorage2D(GL_TEXTURE_2D, 3, GL_RGBA8, w, h);
    else
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    return t;
}

static GLuint framebuffer_of(GLenum target, GLuint t, GLint layer)
{
    GLuint f;
    glGenFramebuffers(1, &f);
    mark(0, f);
    glBindFramebuffer(GL_FRAMEBUFFER, f);
    if (target == GL_TEXTURE_2D_ARRAY)
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t, 0, layer);
    else
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target, t, 0);
    return f;
}

static void draw_into(int w, int h, float r, float g, float b)
{
    glViewport(0, 0, w, h);
    glClearColor(0.1f, 0.2f, 0.3f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    quad(r, g, b, 0);
}

/* The window shows texture `t` (2D, unit 0) through a pass. */
static void show(GLuint t, int ww, int wh)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, ww, wh);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindTexture(GL_TEXTURE_2D, t);
    quad(0, 0, 0, 1);
    report("window", ww, wh);
}

static void round_of(int kind, int w, int h, int ww, int wh)
{
    GLuint t = 0, u = 0, f = 0, g = 0, rb = 0;
    memset(made_n, 0, sizeof made_n);
    switch (kind) {
    case 0: /* glTexImage2D target, shown, mipmapped after */
        t = texture_2d(w, h, 0);
        f = framebuffer_of(GL_TEXTURE_2D, t, 0);
        draw_into(w, h, 1, 0, 0);
        report("teximage", w, h);
        show(t, ww, wh);
        glGenerateMipmap(GL_TEXTURE_2D);
        report("mipmap", ww, wh);
        break;
    case 1: /* glTexStorage2D with levels; copies out of it */
        t = texture_2d(w, h, 1);
        f = framebuffer_of(GL_TEXTURE_2D, t, 0);
        draw_into(w, h, 0, 1, 0);
        glGenerateMipmap(GL_TEXTURE_2D);
        u = texture_2d(w, h, 0);
        glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, w, h);
        report("copyteximage", w, h);
        glCopyImageSubData(t, GL_TEXTURE_2D, 0, 0, 0, 0, u, GL_TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
        report("copyimage", w, h);
        glCopyImageSubData(t, GL_TEXTURE_2D, 0, 0, 0, 0, u, GL_TEXTURE_2D, 0, 1, 0, 0, w, h, 1);
        report("copyimage-outside", w, h);
        glCopyImageSubData(t, GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, u, GL_TEXTURE_2D, 0, 0, 0, 0, 1, 1, 1);
        report("copyimage-wrong-target", w, h);
        show(u, ww, wh);
        break;
    case 2: /* a cube map face */
        glGenTextures(1, &t);
        mark(1, t);
        glBindTexture(GL_TEXTURE_CUBE_MAP, t);
        glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_RGBA8, w, w);
        f = framebuffer_of(GL_TEXTURE_CUBE_MAP_POSITIVE_X, t, 0);
        draw_into(w, w, 0, 0, 1);
        report("cube", w, w);
        glCopyImageSubData(t, GL_TEXTURE_2D, 0, 0, 0, 0, t, GL_TEXTURE_CUBE_MAP, 0, 0, 0, 1, 1, 1, 1);
        report("cube-copy-as-2d", w, w);
        break;
    case 3: /* layers of a 2D array */
        glGenTextures(1, &t);
        mark(1, t);
        glBindTexture(GL_TEXTURE_2D_ARRAY, t);
        glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA8, w, h, 3);
        f = framebuffer_of(GL_TEXTURE_2D_ARRAY, t, 1);
        draw_into(w, h, 1, 1, 0);
        report("array-layer-1", w, h);
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t, 0, 0);
        draw_into(w, h, 0, 1, 1);
        report("array-layer-0", w, h);
        break;
    case 4: /* multisample texture and renderbuffer, resolved */
        glGenTextures(1, &t);
        mark(1, t);
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t);
        glTexStorage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, 4, GL_RGBA8, w, h, GL_TRUE);
        f = framebuffer_of(GL_TEXTURE_2D_MULTISAMPLE, t, 0);
        glGenRenderbuffers(1, &rb);
        mark(2, rb);
        glBindRenderbuffer(GL_RENDERBUFFER, rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_DEPTH_COMPONENT24, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb);
        draw_into(w, h, 1, 0, 1);
        u = texture_2d(w, h, 0);
        g = framebuffer_of(GL_TEXTURE_2D, u, 0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, f);
        glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, g);
        report("resolved", w, h);
        show(u, ww, wh);
        break;
    case 5: /* a texture with eyes deleted while attached; its name made a cube map */
        t = texture_2d(w, h, 0);
        f = framebuffer_of(GL_TEXTURE_2D, t, 0);
        draw_into(w, h, 1, 0, 0);
        show(t, ww, wh);
        glBindFramebuffer(GL_FRAMEBUFFER, f);
        glDeleteTextures(1, &t);
        report("deleted-attached", w, h);
        glGenTextures(1, &t);
        mark(1, t);
        glBindTexture(GL_TEXTURE_CUBE_MAP, t);
        glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_RGBA8, w, w);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_CUBE_MAP_NEGATIVE_Y, t, 0);
        draw_into(w, w, 0, 1, 0);
        report("name-reused-as-cube", w, w);
        /* The framebuffer deleted while bound. */
        glDeleteFramebuffers(1, &f);
        f = 0;
        report("framebuffer-deleted", ww, wh);
        break;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    GLuint tex[] = {t, u};
    glDeleteTextures(2, tex);
    GLuint fbos[] = {f, g};
    glDeleteFramebuffers(2, fbos);
    glDeleteRenderbuffers(1, &rb);
    glBindTexture(GL_TEXTURE_2D, 0);
    printf("round-end gl 0x%x\n", glGetError());
}

int main(int argc, char **argv)
{
    int rounds = argc > 1 ? atoi(argv[1]) : 48;
    Display *x = XOpenDisplay(NULL);
    if (!x) {
        fprintf(stderr, "egl_targets: no X display\n");
        return 1;
    }
    enum { WW = 200, WH = 150 };
    Window win = XCreateSimpleWindow(x, DefaultRootWindow(x), 0, 0, WW, WH, 0, 0, 0);
    XMapWindow(x, win);
    XSync(x, False);
    EGLDisplay dpy = eglGetDisplay((EGLNativeDisplayType)x);
    EGLint major, minor, n = 0;
    EGLConfig config;
    static const EGLint want[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE,
                                  EGL_OPENGL_ES3_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                                  EGL_BLUE_SIZE, 8, EGL_NONE};
    static const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2,
                                   EGL_NONE};
    if (!eglInitialize(dpy, &major, &minor) || !eglBindAPI(EGL_OPENGL_ES_API) ||
        !eglChooseConfig(dpy, want, &config, 1, &n) || n != 1) {
        fprintf(stderr, "egl_targets: no EGL configuration\n");
        return 1;
    }
    EGLSurface s = eglCreateWindowSurface(dpy, config, (EGLNativeWindowType)win, NULL);
    EGLContext ctx = EGL_NO_CONTEXT;
    static const int sizes[][2] = {{1, 1}, {3, 500}, {640, 2}, {257, 33}, {200, 150}, {2, 2}, {64, 64}};
    struct usage_window early = {0}, late = {0};
    for (int i = 0; i < rounds; i++) {
        if (i % 8 == 0) {
            /* A new context: a new share group. */
            eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (ctx != EGL_NO_CONTEXT)
                eglDestroyContext(dpy, ctx);
            ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attrs);
            if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, s, s, ctx)) {
                fprintf(stderr, "egl_targets: no OpenGL ES 3.2 context\n");
                return 1;
            }
            programs();
        }
        const int *size = sizes[i % 7];
        printf("round %d kind %d\n", i, i % 6);
        round_of(i % 6, size[0], size[1], WW, WH);
        eglSwapBuffers(dpy, s);
        usage_round(i, rounds, &early, &late);
    }
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglDestroySurface(dpy, s);
    eglTerminate(dpy);
    XDestroyWindow(x, win);
    XCloseDisplay(x);
    printf("done\n");
    usage_print(&early, &late);
    return 0;
}

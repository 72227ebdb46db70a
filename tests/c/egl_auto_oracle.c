/*
 * The oracle of automatic stereo for EGL programs (issue 31), as
 * tests/c/auto_oracle.c is for GLX ones: one scene drawn by a mono OpenGL
 * ES program through EGL, on an X11 window or a Wayland surface, and by
 * the same program drawing one eye with 3D Vision's rule applied by hand
 * to its projection (REFERENCE.md): row 0 + k * row 3 - k * C * (0, 0, 0, 1),
 * k = e * s (e = -1 left, +1 right; s = 0.07 * S / 100); orthographic
 * projections (w = 1) are left as they are.
 *
 *   egl_auto_oracle x11|wayland es3|es100 mono [blit] [frames N [resize]]
 *       draws the scene N times (default 1), swapping after each (run under
 *       glstereo-run --auto --capture: the eyes are the captures); prints
 *       "read R G B" of glReadPixels at (50, 75) before the last swap and
 *       "error 0x..." at the end; with blit, each frame is drawn into a
 *       framebuffer object of the window's size and blitted into the window;
 *       with resize, the window is made 160x120 after the first frame
 *       (XResizeWindow, or wl_egl_window_resize) and drawn at that size
 *   egl_auto_oracle x11|wayland es3|es100 left|right S C OUT
 *       draws that eye by hand and writes its pixels to OUT (RGBA, rows top
 *       first)
 *
 * es3: an OpenGL ES 3.0 context and a "#version 300 es" program; a vertex
 * buffer drawn with glDrawArrays, glDrawElements and glDrawArraysInstanced
 * (gl_InstanceID), and a HUD. es100: an OpenGL ES 2.0 context and a GLSL ES
 * 1.00 program with no #version line (attribute, gl_FragColor), drawn with
 * glDrawArrays and glDrawElements (unsigned short indices), and a HUD.
 *
 * X11: eglGetDisplay of the program's Display* and eglCreateWindowSurface.
 * Wayland: eglGetPlatformDisplay(EGL_PLATFORM_WAYLAND_KHR) and
 * eglCreatePlatformWindowSurface of a wl_egl_window on a wl_surface with no
 * role (nothing maps it: the eyes are read back or captured), with
 * eglSwapInterval 0 (no frame callbacks come for an unmapped surface).
 */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <X11/Xlib.h>
#include <wayland-client.h>
#include <wayland-egl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 200
#define H 150

static struct wl_compositor *compositor;

static void global(void *data, struct wl_registry *registry, uint32_t name,
                   const char *interface, uint32_t version)
{
    (void)data;
    (void)version;
    if (strcmp(interface, wl_compositor_interface.name) == 0)
        compositor = wl_registry_bind(registry, name, &wl_compositor_interface, 1);
}

static void global_remove(void *data, struct wl_registry *registry, uint32_t name)
{
    (void)data;
    (void)registry;
    (void)name;
}

static const struct wl_registry_listener registry_listener = {global, global_remove};

static void die(const char *what)
{
    fprintf(stderr, "egl_auto_oracle: %s (EGL error 0x%x)\n", what, eglGetError());
    exit(2);
}

static GLuint shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "compile failed: %s\n", log);
        exit(4);
    }
    return s;
}

/* glFrustum(-1, 1, -0.75, 0.75, 1, 50), column-major, with the rule. */
static void perspective(double k, double c, float out[16])
{
    double n = 1.0, f = 50.0;
    double p[16] = {0};
    p[0] = 2.0 * n / 2.0;
    p[5] = 2.0 * n / 1.5;
    p[10] = -(f + n) / (f - n);
    p[11] = -1.0;
    p[14] = -2.0 * f * n / (f - n);
    p[0] += k * p[3];
    p[4] += k * p[7];
    p[8] += k * p[11];
    p[12] += k * p[15] - k * c;
    for (int i = 0; i < 16; i++) out[i] = (float)p[i];
}

/* Quads (two triangles each) at z = -2, -4, -8, -6 and a HUD quad. */
static const GLfloat quads[] = {
    -1.6f, -0.2f, -2.0f, -0.9f, -0.2f, -2.0f, -0.9f, 0.6f, -2.0f,
    -1.6f, -0.2f, -2.0f, -0.9f, 0.6f,  -2.0f, -1.6f, 0.6f, -2.0f,
    -2.5f, -2.5f, -4.0f, -1.0f, -2.5f, -4.0f, -1.0f, -1.2f, -4.0f,
    -2.5f, -2.5f, -4.0f, -1.0f, -1.2f, -4.0f, -2.5f, -1.2f, -4.0f,
    -0.5f, -0.5f, -8.0f, 1.5f,  -0.5f, -8.0f, 1.5f,  1.0f,  -8.0f,
    -0.5f, -0.5f, -8.0f, 1.5f,  1.0f,  -8.0f, -0.5f, 1.0f,  -8.0f,
    0.2f,  -1.8f, -6.0f, 1.2f,  -1.8f, -6.0f, 1.2f,  -1.0f, -6.0f,
    0.2f,  -1.8f, -6.0f, 1.2f,  -1.0f, -6.0f, 0.2f,  -1.0f, -6.0f,
    5.0f,  5.0f,  0.0f,  45.0f, 5.0f,  0.0f,  45.0f, 15.0f, 0.0f,
    5.0f,  5.0f,  0.0f,  45.0f, 15.0f, 0.0f,  5.0f,  15.0f, 0.0f,
};

static void scene(int es3, double k, double c)
{
    static const char *vs3 =
        "#version 300 es\n"
        "layout(location = 0) in vec3 p;\n"
        "uniform mat4 m;\n"
        "void main() {\n"
        "    gl_Position = m * vec4(p + vec3(float(gl_InstanceID) * 0.7, 0.0, 0.0), 1.0);\n"
        "}\n";
    static const char *fs3 =
        "#version 300 es\n"
        "precision mediump float;\n"
        "uniform vec4 colour;\n"
        "out vec4 c;\n"
        "void main() { c = colour; }\n";
    /* GLSL ES 1.00: no #version line, as glmark2's shaders. */
    static const char *vs1 =
        "attribute vec3 p;\n"
        "uniform mat4 m;\n"
        "void main() {\n"
        "    gl_Position = m * vec4(p, 1.0);\n"
        "}\n";
    static const char *fs1 =
        "precision mediump float;\n"
        "uniform vec4 colour;\n"
        "void main() { gl_FragColor = colour; }\n";
    static GLuint prog, vbo, ibo;
    if (!prog) {
        prog = glCreateProgram();
        glAttachShader(prog, shader(GL_VERTEX_SHADER, es3 ? vs3 : vs1));
        glAttachShader(prog, shader(GL_FRAGMENT_SHADER, es3 ? fs3 : fs1));
        glBindAttribLocation(prog, 0, "p");
        glLinkProgram(prog);
        GLint ok = 0;
        glGetProgramiv(prog, GL_LINK_STATUS, &ok);
        if (!ok) {
            fprintf(stderr, "link failed\n");
            exit(4);
        }
        glGenBuffers(1, &vbo);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glBufferData(GL_ARRAY_BUFFER, sizeof quads, quads, GL_STATIC_DRAW);
        glGenBuffers(1, &ibo);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
        static const GLushort idx[] = {6, 7, 8, 9, 10, 11};
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof idx, idx, GL_STATIC_DRAW);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, (const void *)0);
        glEnableVertexAttribArray(0);
    }
    glViewport(0, 0, W, H);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(prog);
    GLint lm = glGetUniformLocation(prog, "m"), lc = glGetUniformLocation(prog, "colour");
    float pf[16];
    perspective(k, c, pf);
    glUniformMatrix4fv(lm, 1, GL_FALSE, pf);
    glUniform4f(lc, 1.0f, 0.0f, 0.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glUniform4f(lc, 1.0f, 1.0f, 0.0f, 1.0f);
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, (const void *)0);
    glUniform4f(lc, 0.0f, 1.0f, 0.0f, 1.0f);
    if (es3)
        glDrawArraysInstanced(GL_TRIANGLES, 12, 6, 2);
    else
        glDrawArrays(GL_TRIANGLES, 12, 6);
    glUniform4f(lc, 0.0f, 0.0f, 1.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 18, 6);
    /* The HUD: glOrtho(0, W, 0, H, -1, 1), w = 1. */
    float o[16] = {2.0f / W, 0, 0, 0, 0, 2.0f / H, 0, 0, 0, 0, -1.0f, 0, -1.0f, -1.0f, 0, 1.0f};
    glDisable(GL_DEPTH_TEST);
    glUniformMatrix4fv(lm, 1, GL_FALSE, o);
    glUniform4f(lc, 1.0f, 1.0f, 1.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 24, 6);
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: egl_auto_oracle x11|wayland es3|es100 mono|left|right ...\n");
        return 2;
    }
    int wayland = strcmp(argv[1], "wayland") == 0;
    int es3 = strcmp(argv[2], "es3") == 0;
    int mono = strcmp(argv[3], "mono") == 0;
    double k = 0.0, c = 0.0;
    const char *out = NULL;
    if (!mono) {
        if (argc < 7) return 2;
        double e = strcmp(argv[3], "left") == 0 ? -1.0 : 1.0;
        k = e * 0.07 * atof(argv[4]) / 100.0;
        c = atof(argv[5]);
        out = argv[6];
    }
    int at = 4;
    int blit = mono && argc > at && strcmp(argv[at], "blit") == 0;
    if (blit) at++;
    int frames = mono && argc > at + 1 && strcmp(argv[at], "frames") == 0 ? atoi(argv[at + 1]) : 1;
    int resize = frames > 1 && argc > at + 2 && strcmp(argv[at + 2], "resize") == 0;

    EGLDisplay dpy;
    EGLSurface surface;
    Display *x = NULL;
    Window win = 0;
    struct wl_display *wl = NULL;
    struct wl_surface *wl_surface = NULL;
    struct wl_egl_window *wl_window = NULL;
    static const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RED_SIZE, 8,
                                            EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                            EGL_DEPTH_SIZE, 24, EGL_RENDERABLE_TYPE,
                                            EGL_OPENGL_ES2_BIT, EGL_NONE};
    EGLConfig config;
    EGLint n = 0;
    if (wayland) {
        wl = wl_display_connect(NULL);
        if (!wl) die("no Wayland display");
        struct wl_registry *registry = wl_display_get_registry(wl);
        wl_registry_add_listener(registry, &registry_listener, NULL);
        wl_display_roundtrip(wl);
        if (!compositor) die("no wl_compositor");
        wl_surface = wl_compositor_create_surface(compositor);
        wl_window = wl_egl_window_create(wl_surface, W, H);
        dpy = eglGetPlatformDisplay(EGL_PLATFORM_WAYLAND_KHR, wl, NULL);
        if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL)) die("eglInitialize");
        if (!eglChooseConfig(dpy, config_attribs, &config, 1, &n) || n < 1) die("no config");
        surface = eglCreatePlatformWindowSurface(dpy, config, wl_window, NULL);
    } else {
        x = XOpenDisplay(NULL);
        if (!x) die("no X display");
        win = XCreateSimpleWindow(x, DefaultRootWindow(x), 0, 0, W, H, 0, 0, 0);
        XStoreName(x, win, "egl_auto_oracle");
        XMapWindow(x, win);
        XSync(x, False);
        dpy = eglGetDisplay((EGLNativeDisplayType)x);
        if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL)) die("eglInitialize");
        if (!eglChooseConfig(dpy, config_attribs, &config, 1, &n) || n < 1) die("no config");
        surface = eglCreateWindowSurface(dpy, config, (EGLNativeWindowType)win, NULL);
    }
    if (surface == EGL_NO_SURFACE) die("no window surface");
    eglBindAPI(EGL_OPENGL_ES_API);
    const EGLint ctx_attribs[] = {EGL_CONTEXT_CLIENT_VERSION, es3 ? 3 : 2, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctx_attribs);
    if (ctx == EGL_NO_CONTEXT) die("no context");
    if (!eglMakeCurrent(dpy, surface, surface, ctx)) die("eglMakeCurrent");
    if (wayland) eglSwapInterval(dpy, 0);

    GLuint fbo = 0, tex = 0, depth = 0;
    if (blit) {
        glGenTextures(1, &tex);
        glBindTexture(GL_TEXTURE_2D, tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindTexture(GL_TEXTURE_2D, 0);
        glGenRenderbuffers(1, &depth);
        glBindRenderbuffer(GL_RENDERBUFFER, depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, W, H);
        glGenFramebuffers(1, &fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                  depth);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return 5;
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    for (int i = 0; i < frames; i++) {
        if (blit) glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        scene(es3, k, c);
        if (blit) {
            glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
            glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        if (i + 1 < frames) eglSwapBuffers(dpy, surface);
        if (resize && i == 0) {
            if (wayland) {
                wl_egl_window_resize(wl_window, 160, 120, 0, 0);
            } else {
                XResizeWindow(x, win, 160, 120);
                XSync(x, False);
            }
        }
    }
    if (mono) {
        GLubyte px[4] = {0};
        glReadPixels(50, 75, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
        printf("read %d %d %d\n", px[0], px[1], px[2]);
        if (!eglSwapBuffers(dpy, surface)) die("eglSwapBuffers");
    } else {
        static GLubyte img[W * H * 4];
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, img);
        FILE *f = fopen(out, "wb");
        if (!f) return 1;
        for (int y = H - 1; y >= 0; y--) fwrite(img + (size_t)y * W * 4, 1, W * 4, f);
        fclose(f);
    }
    GLenum err = glGetError();
    printf("error 0x%x\n", err);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglDestroySurface(dpy, surface);
    eglTerminate(dpy);
    if (wayland) {
        wl_egl_window_destroy(wl_window);
        wl_surface_destroy(wl_surface);
        wl_display_disconnect(wl);
    } else {
        XDestroyWindow(x, win);
        XCloseDisplay(x);
    }
    return err == GL_NO_ERROR ? 0 : 3;
}

/*
 * Render targets under automatic stereo (glstereo-run --auto): a mono
 * program that draws its scene through framebuffer objects of its own, as
 * programs written since about 2010 do, and the same program drawing one
 * eye with 3D Vision's rule applied by hand to its camera's projection
 * (never to a light's, never to a full-screen pass: those have w = 1).
 *
 *   auto_passes CASE mono                draws 2 frames, swapping each
 *                                        (run under glstereo-run --auto
 *                                        --capture: the eyes are the
 *                                        captures); prints "error 0x0"
 *   auto_passes CASE left|right S C OUT  draws that eye's 2 frames by hand
 *                                        and writes the last one's pixels
 *                                        to OUT (RGBA, rows top first)
 *
 * The scene: a blue background, a red quad near (w = 2), a green one far
 * (w = 8), drawn with a GLSL 1.20 program from a model-view-projection
 * matrix uploaded with glUniformMatrix4fv; the picture then reaches the
 * window through the CASE's passes (each a full-screen quad, w = 1):
 *
 *   half      scene into a window-sized target with a depth renderbuffer,
 *             scaled down into a half-size target, shown from there
 *   mrt       scene into two colour attachments and a depth texture (a
 *             G-buffer); the composite samples all three
 *   msaa      scene into a 4-sample target (colour and depth
 *             renderbuffers), resolved by glBlitFramebuffer into a
 *             texture target, shown from there
 *   pingpong  scene into target A, blurred A -> B -> A -> B (two
 *             textures taking turns), shown from B
 *   mipmap    scene into a texture with mipmaps (glGenerateMipmap),
 *             shown minified to a quarter of the window
 *   copy      scene into target A; glCopyTexSubImage2D of A into a
 *             texture, and glBlitFramebuffer of A into target D; the left
 *             half of the window shows the texture, the right half D
 *   copyimage scene into target A (colour and depth textures);
 *             glCopyImageSubData of A's depth into a depth texture (as
 *             Blender keeps its viewport's depth for its overlays) and of
 *             a rectangle of A's colour to another place of a texture;
 *             the left half of the window shows the colour copy, the
 *             right half the depth copy (each unscaled)
 *   shadow    a 256x256 depth-only shadow map drawn from a light (a
 *             perspective of its own, never shifted), then the scene in
 *             the window, the red quad's shadow on the green one
 *   regions   frame 1: scene into a region target, composited into the
 *             window; frame 2: the region is not drawn again, only
 *             composited (a partial redraw, as Blender's window manager
 *             does)
 *
 * Built with -DGLES (auto_passes_es): the same program in OpenGL ES 3.2
 * through EGL on an X11 window, its shaders GLSL ES 3.00 (issue 31: the
 * render-target policy for EGL programs).
 */
#include <X11/Xlib.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef GLES
#include <EGL/egl.h>
#include <GLES3/gl32.h>
#else
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>

#include "x_window.h"
#endif

#define W 200
#define H 150

static double eye_k, eye_c; /* the rule by hand: k = e * s, C (0: mono) */

static GLuint shader(GLenum kind, const char *src)
{
    GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "compile: %s\n", log);
        exit(3);
    }
    return s;
}

static GLuint program(const char *vs, const char *fs)
{
    GLuint p = glCreateProgram();
    glAttachShader(p, shader(GL_VERTEX_SHADER, vs));
    glAttachShader(p, shader(GL_FRAGMENT_SHADER, fs));
    glBindAttribLocation(p, 0, "pos");
    glBindAttribLocation(p, 1, "col");
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        fprintf(stderr, "link failed\n");
        exit(3);
    }
    return p;
}

#ifdef GLES
#define FS_HEAD "#version 300 es\nprecision highp float;\nprecision highp sampler2D;\n"
static const char *SCENE_VS =
    "#version 300 es\n"
    "uniform mat4 mvp; uniform mat4 light;\n"
    "in vec3 pos; in vec3 col;\n"
    "out vec3 c; out vec4 l;\n"
    "void main() { c = col; l = light * vec4(pos, 1.0); gl_Position = mvp * vec4(pos, 1.0); }\n";
static const char *SCENE_FS =
    FS_HEAD
    "in vec3 c; in vec4 l;\n"
    "uniform sampler2D shadow; uniform float shadowed;\n"
    "layout(location = 0) out vec4 o0; layout(location = 1) out vec4 o1;\n"
    "void main() {\n"
    "  float lit = 1.0;\n"
    "  if (shadowed > 0.5) {\n"
    "    vec3 p = l.xyz / l.w * 0.5 + 0.5;\n"
    "    lit = p.z - 0.002 > texture(shadow, p.xy).r ? 0.4 : 1.0;\n"
    "  }\n"
    "  o0 = vec4(c * lit, 1.0);\n"
    "  o1 = vec4(c.gbr * 0.5, 1.0);\n"
    "}\n";
static const char *PASS_VS =
    "#version 300 es\n"
    "in vec3 pos; out vec2 uv; uniform vec4 rect;\n"
    "void main() { uv = pos.xy * 0.5 + 0.5; gl_Position = vec4(rect.xy + (pos.xy * 0.5 + 0.5) * rect.zw, 0.0, 1.0); }\n";
static const char *COPY_FS =
    FS_HEAD
    "uniform sampler2D t; in vec2 uv; out vec4 o;\n"
    "void main() { o = texture(t, uv); }\n";
static const char *BLUR_FS =
    FS_HEAD
    "uniform sampler2D t; uniform vec2 step; in vec2 uv; out vec4 o;\n"
    "void main() { o = (texture(t, uv - step) + 2.0 * texture(t, uv) + texture(t, uv + step)) * 0.25; }\n";
static const char *GBUFFER_FS =
    FS_HEAD
    "uniform sampler2D c0; uniform sampler2D c1; uniform sampler2D d; in vec2 uv; out vec4 o;\n"
    "void main() { float z = texture(d, uv).r;\n"
    "  o = vec4(texture(c0, uv).rgb * 0.6 + texture(c1, uv).rgb * 0.4, 1.0) * (z < 1.0 ? 1.0 : 0.5); }\n";
#else
static const char *SCENE_VS =
    "#version 120\n"
    "uniform mat4 mvp; uniform mat4 light;\n"
    "attribute vec3 pos; attribute vec3 col;\n"
    "varying vec3 c; varying vec4 l;\n"
    "void main() { c = col; l = light * vec4(pos, 1.0); gl_Position = mvp * vec4(pos, 1.0); }\n";
static const char *SCENE_FS =
    "#version 120\n"
    "varying vec3 c; varying vec4 l;\n"
    "uniform sampler2D shadow; uniform float shadowed;\n"
    "void main() {\n"
    "  float lit = 1.0;\n"
    "  if (shadowed > 0.5) {\n"
    "    vec3 p = l.xyz / l.w * 0.5 + 0.5;\n"
    "    lit = p.z - 0.002 > texture2D(shadow, p.xy).r ? 0.4 : 1.0;\n"
    "  }\n"
    "  gl_FragData[0] = vec4(c * lit, 1.0);\n"
    "  gl_FragData[1] = vec4(c.gbr * 0.5, 1.0);\n"
    "}\n";
static const char *PASS_VS =
    "#version 120\n"
    "attribute vec3 pos; varying vec2 uv; uniform vec4 rect;\n"
    "void main() { uv = pos.xy * 0.5 + 0.5; gl_Position = vec4(rect.xy + (pos.xy * 0.5 + 0.5) * rect.zw, 0.0, 1.0); }\n";
static const char *COPY_FS =
    "#version 120\n"
    "uniform sampler2D t; varying vec2 uv;\n"
    "void main() { gl_FragColor = texture2D(t, uv); }\n";
static const char *BLUR_FS =
    "#version 120\n"
    "uniform sampler2D t; uniform vec2 step; varying vec2 uv;\n"
    "void main() { gl_FragColor = (texture2D(t, uv - step) + 2.0 * texture2D(t, uv) + texture2D(t, uv + step)) * 0.25; }\n";
static const char *GBUFFER_FS =
    "#version 120\n"
    "uniform sampler2D c0; uniform sampler2D c1; uniform sampler2D d; varying vec2 uv;\n"
    "void main() { float z = texture2D(d, uv).r;\n"
    "  gl_FragColor = vec4(texture2D(c0, uv).rgb * 0.6 + texture2D(c1, uv).rgb * 0.4, 1.0) * (z < 1.0 ? 1.0 : 0.5); }\n";
#endif

static GLuint scene_prog, copy_prog, blur_prog, gbuffer_prog;

/* Column-major 4x4 product a * b. */
static void mul(const double *a, const double *b, double *out)
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = s;
        }
}

/* glFrustum's matrix. */
static void frustum(double l, double r, double b, double t, double n, double f, double *m)
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = 2 * n / (r - l);
    m[5] = 2 * n / (t - b);
    m[8] = (r + l) / (r - l);
    m[9] = (t + b) / (t - b);
    m[10] = -(f + n) / (f - n);
    m[11] = -1;
    m[14] = -2 * f * n / (f - n);
}

static void upload(GLuint p, const char *name, const double *m)
{
    float f[16];
    for (int i = 0; i < 16; i++) f[i] = (float)m[i];
    glUniformMatrix4fv(glGetUniformLocation(p, name), 1, GL_FALSE, f);
}

/* The camera's projection times its view (identity), with the rule by
 * hand: row 0 + k * row 3 - k * C * (0, 0, 0, 1). */
static void camera(double *m)
{
    frustum(-1.0, 1.0, -0.75, 0.75, 1.0, 50.0, m);
    if (eye_k != 0.0) {
        for (int c = 0; c < 4; c++) m[c * 4] += eye_k * m[c * 4 + 3];
        m[12] -= eye_k * eye_c;
    }
}

/* The light's view projection: a spot light at (-0.9, 0.1, 0) looking
 * down -z, as the camera does, so the red quad's shadow falls on the
 * green one beside it; never shifted. */
static void light_matrix(double *m)
{
    double p[16], v[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.9, -0.1, 0, 1};
    frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 20.0, p);
    mul(p, v, m);
}

static void quad(float x0, float y0, float x1, float y1, float z, float r, float g, float b)
{
    float v[] = {x0, y0, z, r, g, b, x1, y0, z, r, g, b, x1, y1, z, r, g, b, x0, y1, z, r, g, b};
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), v);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), v + 3);
    glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
}

/* The scene into the bound framebuffer (its viewport set): blue, a red
 * quad at w = 2, a green one at w = 8; with `shadow` a texture unit 1
 * shadow map and a floor that receives it. */
static void scene(GLuint shadow)
{
    double m[16], l[16];
    glClearColor(0.0f, 0.0f, 0.8f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(scene_prog);
    camera(m);
    light_matrix(l);
    upload(scene_prog, "mvp", m);
    upload(scene_prog, "light", l);
    glUniform1f(glGetUniformLocation(scene_prog, "shadowed"), shadow ? 1.0f : 0.0f);
    glUniform1i(glGetUniformLocation(scene_prog, "shadow"), 1);
    if (shadow) {
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, shadow);
        glActiveTexture(GL_TEXTURE0);
    }
    quad(-1.4f, -0.3f, -0.4f, 0.5f, -2.0f, 1.0f, 0.0f, 0.0f);
    quad(-2.0f, -2.0f, 3.0f, 2.4f, -8.0f, 0.0f, 1.0f, 0.0f);
    glDisable(GL_DEPTH_TEST);
}

/* A full-screen pass (w = 1) of `p` into rectangle `rect` of the
 * viewport (x, y, width, height in clip units, from -1). */
static void pass(GLuint p, float x, float y, float w, float h)
{
    glUseProgram(p);
    glUniform4f(glGetUniformLocation(p, "rect"), x, y, w, h);
    quad(-1, -1, 1, 1, 0, 0, 0, 0);
}

static GLuint texture(GLenum format, int w, int h, GLenum filter)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    /* Nearest stays nearest when magnified too: a G-buffer's depth is
     * compared with 1.0, and a bilinear sample at a texel's centre can
     * take a millionth of its neighbour where the window's pixel centres
     * are computed a little differently (the eyes are a texture under
     * --auto, the window's own buffer by hand). */
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter == GL_NEAREST ? GL_NEAREST : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (format == GL_DEPTH_COMPONENT24)
        glTexImage2D(GL_TEXTURE_2D, 0, format, w, h, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, NULL);
    else
        glTexImage2D(GL_TEXTURE_2D, 0, format, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    return t;
}

static GLuint target(GLuint colour, GLuint colour1, GLuint depth_tex, GLenum depth_rb_format, int w, int h)
{
    GLuint f;
    glGenFramebuffers(1, &f);
    glBindFramebuffer(GL_FRAMEBUFFER, f);
    if (colour) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour, 0);
    if (colour1) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, colour1, 0);
    if (depth_tex) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_tex, 0);
    if (depth_rb_format) {
        GLuint rb;
        glGenRenderbuffers(1, &rb);
        glBindRenderbuffer(GL_RENDERBUFFER, rb);
        glRenderbufferStorage(GL_RENDERBUFFER, depth_rb_format, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb);
    }
    if (!colour) {
        GLenum none = GL_NONE;
        glDrawBuffers(1, &none);
        glReadBuffer(GL_NONE);
    }
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        fprintf(stderr, "incomplete target\n");
        exit(5);
    }
    return f;
}

static void show(GLuint t)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, W, H);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindTexture(GL_TEXTURE_2D, t);
    pass(copy_prog, -1, -1, 2, 2);
}

/* Frame `n` (0 or 1) of `name`. */
static void frame(const char *name, int n)
{
    static GLuint a, b, c, d, fa, fb, fd, depth;
    static int made;
    if (!made) {
        made = 1;
        if (!strcmp(name, "half")) {
            a = texture(GL_RGBA8, W, H, GL_LINEAR);
            b = texture(GL_RGBA8, W / 2, H / 2, GL_LINEAR);
            fa = target(a, 0, 0, GL_DEPTH_COMPONENT24, W, H);
            fb = target(b, 0, 0, 0, W / 2, H / 2);
        } else if (!strcmp(name, "mrt")) {
            a = texture(GL_RGBA8, W, H, GL_NEAREST);
            b = texture(GL_RGBA8, W, H, GL_NEAREST);
            depth = texture(GL_DEPTH_COMPONENT24, W, H, GL_NEAREST);
            fa = target(a, b, depth, 0, W, H);
            GLenum bufs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
            glDrawBuffers(2, bufs);
        } else if (!strcmp(name, "msaa")) {
            GLuint rb[2];
            glGenRenderbuffers(2, rb);
            glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
            glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_RGBA8, W, H);
            glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
            glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_DEPTH_COMPONENT24, W, H);
            glGenFramebuffers(1, &fa);
            glBindFramebuffer(GL_FRAMEBUFFER, fa);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
            b = texture(GL_RGBA8, W, H, GL_NEAREST);
            fb = target(b, 0, 0, 0, W, H);
        } else if (!strcmp(name, "pingpong")) {
            a = texture(GL_RGBA8, W, H, GL_LINEAR);
            b = texture(GL_RGBA8, W, H, GL_LINEAR);
            fa = target(a, 0, 0, GL_DEPTH_COMPONENT24, W, H);
            fb = target(b, 0, 0, 0, W, H);
        } else if (!strcmp(name, "mipmap")) {
            a = texture(GL_RGBA8, W, H, GL_LINEAR_MIPMAP_LINEAR);
            fa = target(a, 0, 0, GL_DEPTH_COMPONENT24, W, H);
        } else if (!strcmp(name, "copy")) {
            a = texture(GL_RGBA8, W, H, GL_NEAREST);
            c = texture(GL_RGBA8, W, H, GL_LINEAR);
            d = texture(GL_RGBA8, W, H, GL_LINEAR);
            fa = target(a, 0, 0, GL_DEPTH_COMPONENT24, W, H);
            fd = target(d, 0, 0, 0, W, H);
        } else if (!strcmp(name, "copyimage")) {
            a = texture(GL_RGBA8, W, H, GL_NEAREST);
            c = texture(GL_RGBA8, W, H, GL_NEAREST);
            depth = texture(GL_DEPTH_COMPONENT24, W, H, GL_NEAREST);
            d = texture(GL_DEPTH_COMPONENT24, W, H, GL_NEAREST);
            fa = target(a, 0, depth, 0, W, H);
        } else if (!strcmp(name, "shadow")) {
            depth = texture(GL_DEPTH_COMPONENT24, 256, 256, GL_NEAREST);
            fa = target(0, 0, depth, 0, 256, 256);
        } else if (!strcmp(name, "regions")) {
            a = texture(GL_RGBA8, W / 2, H, GL_NEAREST);
            fa = target(a, 0, 0, GL_DEPTH_COMPONENT24, W / 2, H);
        } else {
            fprintf(stderr, "unknown case %s\n", name);
            exit(2);
        }
    }
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    if (!strcmp(name, "half")) {
        glBindFramebuffer(GL_FRAMEBUFFER, fa);
        glViewport(0, 0, W, H);
        scene(0);
        glBindFramebuffer(GL_FRAMEBUFFER, fb);
        glViewport(0, 0, W / 2, H / 2);
        glBindTexture(GL_TEXTURE_2D, a);
        pass(copy_prog, -1, -1, 2, 2);
        show(b);
    } else if (!strcmp(name, "mrt")) {
        glBindFramebuffer(GL_FRAMEBUFFER, fa);
        glViewport(0, 0, W, H);
        scene(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, W, H);
        glUseProgram(gbuffer_prog);
        glUniform1i(glGetUniformLocation(gbuffer_prog, "c0"), 0);
        glUniform1i(glGetUniformLocation(gbuffer_prog, "c1"), 1);
        glUniform1i(glGetUniformLocation(gbuffer_prog, "d"), 2);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, b);
        glActiveTexture(GL_TEXTURE2);
        glBindTexture(GL_TEXTURE_2D, depth);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, a);
        pass(gbuffer_prog, -1, -1, 2, 2);
    } else if (!strcmp(name, "msaa")) {
        glBindFramebuffer(GL_FRAMEBUFFER, fa);
        glViewport(0, 0, W, H);
        scene(0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fa);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb);
        glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        show(b);
    } else if (!strcmp(name, "pingpong")) {
        glBindFramebuffer(GL_FRAMEBUFFER, fa);
        glViewport(0, 0, W, H);
        scene(0);
        for (int i = 0; i < 3; i++) {
            glBindFramebuffer(GL_FRAMEBUFFER, i % 2 ? fa : fb);
            glBindTexture(GL_TEXTURE_2D, i % 2 ? b : a);
            glUseProgram(blur_prog);
            glUniform2f(glGetUniformLocation(blur_prog, "step"), i % 2 ? 0.0f : 1.0f / W,
                        i % 2 ? 1.0f / H : 0.0f);
            pass(blur_prog, -1, -1, 2, 2);
        }
        show(b);
    } else if (!strcmp(name, "mipmap")) {
        glBindFramebuffer(GL_FRAMEBUFFER, fa);
        glViewport(0, 0, W, H);
        scene(0);
        glBindTexture(GL_TEXTURE_2D, a);
        glGenerateMipmap(GL_TEXTURE_2D);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, W, H);
        glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        pass(copy_prog, -0.5f, -0.5f, 1.0f, 1.0f);
    } else if (!strcmp(name, "copy")) {
        glBindFramebuffer(GL_FRAMEBUFFER, fa);
        glViewport(0, 0, W, H);
        scene(0);
        glBindTexture(GL_TEXTURE_2D, c);
        glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, W, H);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fa);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fd);
        glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, W, H);
        glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glBindTexture(GL_TEXTURE_2D, c);
        pass(copy_prog, -1, -1, 1, 2);
        glBindTexture(GL_TEXTURE_2D, d);
        pass(copy_prog, 0, -1, 1, 2);
    } else if (!strcmp(name, "copyimage")) {
        glBindFramebuffer(GL_FRAMEBUFFER, fa);
        glViewport(0, 0, W, H);
        scene(0);
        /* Copies GL refuses, from a texture with eyes under --auto: each
         * error printed (the same with and without the layer), and none
         * changes the picture. */
        if (n == 1) {
            static const struct { int src_level, sx, dst_level, dx, w, h, depth, to_colour; } bad[] = {
                {0, 0, 0, 0, W + 1, H, 1, 1},    /* wider than both */
                {0, W - 4, 0, 0, 8, 8, 1, 1},    /* past the source's edge */
                {0, 0, 0, W - 4, 8, 8, 1, 1},    /* past the destination's edge */
                {0, 0, 3, 0, 8, 8, 1, 1},        /* a level the destination lacks */
                {0, 0, 0, 0, 8, 8, 2, 1},        /* two layers of a 2D image */
                {0, 0, 0, 0, -1, 8, 1, 1},       /* a negative width */
                {0, 0, 0, 0, 8, 8, 1, 0},        /* depth into colour */
                {0, 0, 0, 0, 2147483647, 8, 1, 1}, /* an absurd width */
            };
            for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++) {
                glCopyImageSubData(bad[i].to_colour ? a : depth, GL_TEXTURE_2D, bad[i].src_level, bad[i].sx,
                                   0, 0, c, GL_TEXTURE_2D, bad[i].dst_level, bad[i].dx, 0, 0, bad[i].w,
                                   bad[i].h, bad[i].depth);
                printf("copyimage refused %u: 0x%x\n", i, glGetError());
            }
            glCopyImageSubData(a, GL_TEXTURE_2D, 0, 0, 0, 0, 12345, GL_TEXTURE_2D, 0, 0, 0, 0, 4, 4, 1);
            printf("copyimage refused name: 0x%x\n", glGetError());
        }
        glCopyImageSubData(depth, GL_TEXTURE_2D, 0, 0, 0, 0, d, GL_TEXTURE_2D, 0, 0, 0, 0, W, H, 1);
        glCopyImageSubData(a, GL_TEXTURE_2D, 0, 8, 4, 0, c, GL_TEXTURE_2D, 0, 16, 12, 0, W - 40, H - 30, 1);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, W, H);
        glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        /* Each copy at its own size (a texel boundary of a copy shown
         * at half size is where nearest sampling may pick either
         * texel): the colour's left half, the depth's right half. */
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, 0, W / 2, H);
        glBindTexture(GL_TEXTURE_2D, c);
        pass(copy_prog, -1, -1, 2, 2);
        glScissor(W / 2, 0, W - W / 2, H);
        glBindTexture(GL_TEXTURE_2D, d);
        pass(copy_prog, -1, -1, 2, 2);
        glDisable(GL_SCISSOR_TEST);
    } else if (!strcmp(name, "shadow")) {
        /* The light's pass: the scene's occluder and floor from the light,
         * depth only; the light's matrix, never shifted. */
        double l[16];
        glBindFramebuffer(GL_FRAMEBUFFER, fa);
        glViewport(0, 0, 256, 256);
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glUseProgram(scene_prog);
        light_matrix(l);
        upload(scene_prog, "mvp", l);
        upload(scene_prog, "light", l);
        glUniform1f(glGetUniformLocation(scene_prog, "shadowed"), 0.0f);
        quad(-1.4f, -0.3f, -0.4f, 0.5f, -2.0f, 1.0f, 0.0f, 0.0f);
        quad(-2.0f, -2.0f, 3.0f, 2.4f, -8.0f, 0.0f, 1.0f, 0.0f);
        glDisable(GL_DEPTH_TEST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, W, H);
        scene(depth);
    } else if (!strcmp(name, "regions")) {
        if (n == 0) {
            glBindFramebuffer(GL_FRAMEBUFFER, fa);
            glViewport(0, 0, W / 2, H);
            scene(0);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, W, H);
        glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glBindTexture(GL_TEXTURE_2D, a);
        pass(copy_prog, -0.5f, -1, 1, 2);
    }
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: auto_passes CASE mono | CASE left|right S C OUT\n");
        return 2;
    }
    const char *name = argv[1];
    int mono = !strcmp(argv[2], "mono");
    if (!mono) {
        if (argc < 6) return 2;
        double s = 0.07 * atof(argv[3]) / 100.0;
        eye_k = (!strcmp(argv[2], "left") ? -1.0 : 1.0) * s;
        eye_c = atof(argv[4]);
    }
#ifdef GLES
    Display *xd = XOpenDisplay(NULL);
    if (!xd) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    Window win = XCreateSimpleWindow(xd, DefaultRootWindow(xd), 0, 0, W, H, 0, 0, 0);
    XStoreName(xd, win, "auto_passes_es");
    XMapWindow(xd, win);
    XSync(xd, False);
    EGLDisplay dpy = eglGetDisplay((EGLNativeDisplayType)xd);
    EGLint major, minor, n = 0;
    EGLConfig config;
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_ES3_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                                     EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_NONE};
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2, EGL_NONE};
    if (!eglInitialize(dpy, &major, &minor) || !eglBindAPI(EGL_OPENGL_ES_API) ||
        !eglChooseConfig(dpy, config_attribs, &config, 1, &n) || n < 1) {
        fprintf(stderr, "no EGL configuration\n");
        return 1;
    }
    EGLSurface surface = eglCreateWindowSurface(dpy, config, (EGLNativeWindowType)win, NULL);
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctx_attribs);
    if (surface == EGL_NO_SURFACE || ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, surface, surface, ctx)) {
        fprintf(stderr, "cannot make an OpenGL ES 3.2 context current\n");
        return 1;
    }
#else
    struct x_window x = open_x_window_config(NULL, W, H);
#endif
    scene_prog = program(SCENE_VS, SCENE_FS);
    copy_prog = program(PASS_VS, COPY_FS);
    blur_prog = program(PASS_VS, BLUR_FS);
    gbuffer_prog = program(PASS_VS, GBUFFER_FS);
    glUseProgram(copy_prog);
    glUniform1i(glGetUniformLocation(copy_prog, "t"), 0);
    glUseProgram(blur_prog);
    glUniform1i(glGetUniformLocation(blur_prog, "t"), 0);
    for (int n = 0; n < 2; n++) {
        frame(name, n);
#ifdef GLES
        if (mono || n == 0) eglSwapBuffers(dpy, surface);
#else
        if (mono || n == 0) glXSwapBuffers(x.display, x.window);
#endif
    }
    if (!mono) {
        static unsigned char px[W * H * 4], out[W * H * 4];
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glReadBuffer(GL_BACK);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
        for (int y = 0; y < H; y++) memcpy(out + y * W * 4, px + (H - 1 - y) * W * 4, W * 4);
        FILE *f = fopen(argv[5], "wb");
        if (!f || fwrite(out, 1, sizeof out, f) != sizeof out) return 4;
        fclose(f);
    }
    printf("error 0x%x\n", glGetError());
    return 0;
}

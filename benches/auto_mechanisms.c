/*
 * Which per-eye mechanism can automatic stereo afford on llvmpipe? (issue 23)
 *
 * A mono program's frame is N depth-tested draws of K triangles. Automatic
 * stereo must send every draw to both eyes. This program renders the same
 * frame both eyes at a time in several ways, on an EGL surfaceless GL 4.5
 * compatibility context, and times them per frame (draws + glFinish):
 *
 *   a      the program draws both eyes itself: all draws into the left eye,
 *          then all into the right (glDrawBuffer per eye on one framebuffer
 *          object with two colour textures and one depth buffer, depth
 *          cleared between the eyes) - what a stereo program costs under
 *          glstereo-run, the reference the others are divided by
 *   b      a framebuffer object per eye (colour + depth each),
 *          glBindFramebuffer before every draw
 *   c      one object, glDrawBuffers switched before every draw, one shared
 *          depth buffer (WRONG pictures: the eyes' depths interleave; only
 *          a lower bound of what a draw-buffer switch costs)
 *   c2     c, with the eye's depth texture attached before every draw
 *          (right pictures)
 *   d      one layered object (2-layer colour and depth arrays), the eye's
 *          layer written to gl_Layer by the vertex shader from a uniform
 *          (ARB_shader_viewport_layer_array); no framebuffer change at all
 *   dt     d with glFlush whenever 65536 vertices were drawn since the last
 *   e      one double-width object, glViewport + glScissor per draw
 *   e2     one double-width object, two viewports set once, the eye's
 *          written to gl_ViewportIndex by the vertex shader from a uniform
 *   f1     d with one instanced draw for both eyes (instance 0 left, 1 right)
 *   f2     d with one draw and a geometry shader emitting each triangle
 *          into both layers
 *   af     a with glFlush after every draw (what a scene flush costs)
 *   df     d with glFlush after every pair of draws
 *   aff, bff, eff   a, b and e for a fixed-function program (projection per
 *          eye by glLoadMatrixf, the modelview per draw by the program):
 *          fixed function cannot write gl_Layer or gl_ViewportIndex
 *   c2ff   fixed function into the layered object, the eye's colour and
 *          depth layers attached before every draw
 *   dff    fixed function with a vertex shader of the layer standing in for
 *          fixed-function vertex processing (ftransform(), the colour, the
 *          eye's shift and gl_Layer; fragments stay fixed-function): d for
 *          fixed-function programs
 *
 *   auto_mechanisms probe
 *   auto_mechanisms verify WIDTH HEIGHT
 *   auto_mechanisms run WIDTH HEIGHT light|heavy N FRAMES ROUNDS [VARIANT...]
 *
 * "verify" renders one frame of each variant and compares each eye with a
 * (max channel difference; c is expected to differ). "run" alternates the
 * variants in each round (every variant FRAMES frames, after one warm-up
 * frame) and prints per variant the median ms/frame over all rounds, the
 * median over rounds of its ratio to the first variant in the same round,
 * and the range of those ratios (on a shared machine the load moves
 * between rounds; within a round the variants see about the same). Light scene: N draws of 2 triangles, each a tile of a
 * ceil(sqrt(N))^2 grid enlarged 1.5x (so tiles overlap and the depth test
 * decides); heavy: 524288 triangles per eye split over the N draws (the
 * heavy scene of glx_frame_loop.c). Same fill for every N.
 */
#define GL_GLEXT_PROTOTYPES
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

static int W, H, N, HEAVY;
static GLuint vbo;
static GLint *first;
static GLsizei *count;
static float *obj; /* per draw: x, y offsets and a depth */
static const float SEP = 0.07f * 0.5f, CONV = 3.0f;

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

static void die(const char *what)
{
    fprintf(stderr, "auto_mechanisms: %s\n", what);
    exit(1);
}

static void context(void)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display) die("no eglGetPlatformDisplayEXT");
    EGLDisplay d = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (!eglInitialize(d, NULL, NULL)) die("eglInitialize");
    eglBindAPI(EGL_OPENGL_API);
    static const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
    EGLContext c = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attribs);
    if (c == EGL_NO_CONTEXT) die("no GL 4.5 compatibility context");
    if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) die("eglMakeCurrent");
}

static int has_extension(const char *name)
{
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++)
        if (strcmp((const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i), name) == 0) return 1;
    return 0;
}

/* ---- the scene ---------------------------------------------------------- */

static void make_scene(void)
{
    int g = (int)ceil(sqrt((double)N));
    long per = HEAVY ? 524288 / N : 2; /* triangles per draw */
    int q = 1;                          /* a q x q grid of quads per draw */
    while (2L * (q + 1) * (q + 1) <= per) q++;
    size_t verts = (size_t)N * q * q * 6;
    float *v = malloc(verts * 6 * sizeof(float)), *p = v;
    first = malloc(N * sizeof *first);
    count = malloc(N * sizeof *count);
    obj = malloc(N * 3 * sizeof *obj);
    if (!v || !first || !count || !obj) die("out of memory");
    float tile = 2.0f / g * 1.5f;
    for (int d = 0; d < N; d++) {
        first[d] = (GLint)((p - v) / 6);
        for (int j = 0; j < q; j++)
            for (int i = 0; i < q; i++) {
                static const int corner[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
                for (int k = 0; k < 6; k++) {
                    float x = (float)(i + corner[k][0]) / q, y = (float)(j + corner[k][1]) / q;
                    *p++ = x * tile;
                    *p++ = y * tile;
                    *p++ = 0.3f * (x - 0.5f) * (y - 0.5f);
                    *p++ = x;
                    *p++ = y;
                    *p++ = (float)(((i ^ j) & 1) ^ (d & 1));
                }
            }
        count[d] = (GLsizei)((p - v) / 6 - first[d]);
        obj[3 * d + 0] = -1.0f + 2.0f * (d % g) / g - tile / 6;
        obj[3 * d + 1] = -1.0f + 2.0f * (d / g) / g - tile / 6;
        obj[3 * d + 2] = -0.5f * (float)((d * 7919) % 13) / 13.0f;
    }
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(verts * 6 * sizeof(float)), v, GL_STATIC_DRAW);
    free(v);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (const void *)(3 * sizeof(float)));
    glVertexPointer(3, GL_FLOAT, 6 * sizeof(float), (const void *)0);
    glColorPointer(3, GL_FLOAT, 6 * sizeof(float), (const void *)(3 * sizeof(float)));
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
}

/* The mono projection: glFrustum(-2/3, 2/3, -2/3, 2/3, 2, 6) times a
 * translation of the scene to z = -3 (w_clip = 3 - z: about 2.9 ... 3.6). */
static const float MONO[16] = {3, 0, 0, 0, 0, 3, 0, 0, 0, 0, -2, -1, 0, 0, 0, 3};

/* The eye's projection by REFERENCE.md: row 0 + e*s*row 3 - e*s*C*(0,0,0,1). */
static void eye_projection(int eye, float out[16])
{
    float k = (eye ? 1.0f : -1.0f) * SEP;
    memcpy(out, MONO, sizeof MONO);
    for (int c = 0; c < 4; c++) out[4 * c] += k * MONO[4 * c + 3];
    out[12] -= k * CONV;
}

/* ---- shaders ------------------------------------------------------------ */

enum { MODE_PLAIN, MODE_LAYER, MODE_VIEWPORT, MODE_INSTANCED, MODE_GS, MODE_FF };
static GLuint programs[6];
static GLint u_eye[6], u_obj[6], u_mvp[6];

static GLuint compile(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2000];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "%s\n%s\n", src, log);
        die("shader does not compile");
    }
    return s;
}

/* dff: the layer's stand-in for fixed-function vertex processing (here
 * unlit, untextured: position and colour), with the eye's shift and layer;
 * fragments stay fixed-function (a program with only a vertex shader). */
static void make_ff_program(void)
{
    static const char *vs = "#version 150 compatibility\n"
                            "#extension GL_ARB_shader_viewport_layer_array : require\n"
                            "uniform vec4 eye;\n"
                            "void main() {\n"
                            "    gl_Position = ftransform();\n"
                            "    gl_FrontColor = gl_Color;\n"
                            "    if (gl_Position.w != 1.0) gl_Position.x += eye.x * (gl_Position.w - eye.y);\n"
                            "    gl_Layer = int(eye.z);\n"
                            "}\n";
    GLuint p = glCreateProgram();
    glAttachShader(p, compile(GL_VERTEX_SHADER, vs));
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) die("fixed-function stand-in does not link");
    programs[MODE_FF] = p;
    u_eye[MODE_FF] = glGetUniformLocation(p, "eye");
}

static void make_program(int mode)
{
    static const char *defines[] = {"", "#define LAYER\n", "#define VIEWPORT\n", "#define INSTANCED\n",
                                    "#define GS\n"};
    static const char *vs_body =
        "layout(location = 0) in vec3 pos;\n"
        "layout(location = 1) in vec3 col;\n"
        "uniform mat4 mvp;\n"
        "uniform vec3 obj;\n"
        "uniform vec4 eye; /* e*s, C, layer or viewport */\n"
        "out vec3 vc;\n"
        "void main() {\n"
        "    gl_Position = mvp * vec4(pos + obj, 1.0);\n"
        "    vc = col;\n"
        "#if defined(INSTANCED)\n"
        "    float es = gl_InstanceID == 0 ? -eye.x : eye.x;\n"
        "    gl_Layer = gl_InstanceID;\n"
        "#else\n"
        "    float es = eye.x;\n"
        "#endif\n"
        "#if !defined(GS)\n"
        "    if (gl_Position.w != 1.0) gl_Position.x += es * (gl_Position.w - eye.y);\n"
        "#endif\n"
        "#if defined(LAYER)\n"
        "    gl_Layer = int(eye.z);\n"
        "#elif defined(VIEWPORT)\n"
        "    gl_ViewportIndex = int(eye.z);\n"
        "#endif\n"
        "}\n";
    static const char *gs_src =
        "#version 330 core\n"
        "layout(triangles) in;\n"
        "layout(triangle_strip, max_vertices = 6) out;\n"
        "uniform vec4 eye;\n"
        "in vec3 vc[];\n"
        "out vec3 gc;\n"
        "void main() {\n"
        "    for (int e = 0; e < 2; e++) {\n"
        "        float es = e == 0 ? -eye.x : eye.x;\n"
        "        for (int i = 0; i < 3; i++) {\n"
        "            vec4 p = gl_in[i].gl_Position;\n"
        "            if (p.w != 1.0) p.x += es * (p.w - eye.y);\n"
        "            gl_Position = p;\n"
        "            gl_Layer = e;\n"
        "            gc = vc[i];\n"
        "            EmitVertex();\n"
        "        }\n"
        "        EndPrimitive();\n"
        "    }\n"
        "}\n";
    static const char *fs_src = "#version 330 core\n"
                                "#ifdef GS\n#define vc gc\n#endif\n"
                                "in vec3 vc;\n"
                                "out vec4 color;\n"
                                "void main() { color = vec4(vc, 1.0); }\n";
    char vs[4000], fs[1000];
    snprintf(vs, sizeof vs, "#version 330 core\n#extension GL_ARB_shader_viewport_layer_array : enable\n%s%s",
             defines[mode], vs_body);
    snprintf(fs, sizeof fs, "%s", fs_src);
    if (mode == MODE_GS) {
        /* #define after #version: splice it in. */
        snprintf(fs, sizeof fs, "#version 330 core\n#define GS\n%s", strchr(fs_src, '\n') + 1);
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, compile(GL_VERTEX_SHADER, vs));
    glAttachShader(p, compile(GL_FRAGMENT_SHADER, fs));
    if (mode == MODE_GS) glAttachShader(p, compile(GL_GEOMETRY_SHADER, gs_src));
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) die("program does not link");
    programs[mode] = p;
    u_eye[mode] = glGetUniformLocation(p, "eye");
    u_obj[mode] = glGetUniformLocation(p, "obj");
    u_mvp[mode] = glGetUniformLocation(p, "mvp");
    glUseProgram(p);
    glUniformMatrix4fv(u_mvp[mode], 1, GL_FALSE, MONO);
}

/* ---- targets ------------------------------------------------------------ */

static GLuint tex2d(GLenum format, int w, int h)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    return t;
}

static GLuint tex_array(GLenum format)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, format, W, H, 2);
    return t;
}

static GLuint fb_two;                /* a, c, c2: two colours, depth */
static GLuint col_two[2], dep_two[2]; /* dep_two[1]: c2's right depth */
static GLuint fb_eye[2], col_eye[2], dep_eye[2];
static GLuint fb_layered, col_layered, dep_layered;
static GLuint fb_wide, col_wide, dep_wide;
static GLuint fb_read;

static void check(const char *what)
{
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) die(what);
}

static void make_targets(void)
{
    glGenFramebuffers(1, &fb_two);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_two);
    for (int e = 0; e < 2; e++) {
        col_two[e] = tex2d(GL_RGBA8, W, H);
        dep_two[e] = tex2d(GL_DEPTH24_STENCIL8, W, H);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + e, GL_TEXTURE_2D, col_two[e], 0);
    }
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, dep_two[0], 0);
    check("two-colour framebuffer");
    glGenFramebuffers(2, fb_eye);
    for (int e = 0; e < 2; e++) {
        glBindFramebuffer(GL_FRAMEBUFFER, fb_eye[e]);
        col_eye[e] = tex2d(GL_RGBA8, W, H);
        dep_eye[e] = tex2d(GL_DEPTH24_STENCIL8, W, H);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, col_eye[e], 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, dep_eye[e], 0);
        check("eye framebuffer");
    }
    glGenFramebuffers(1, &fb_layered);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_layered);
    col_layered = tex_array(GL_RGBA8);
    dep_layered = tex_array(GL_DEPTH24_STENCIL8);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, col_layered, 0);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, dep_layered, 0);
    check("layered framebuffer");
    glGenFramebuffers(1, &fb_wide);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_wide);
    col_wide = tex2d(GL_RGBA8, 2 * W, H);
    dep_wide = tex2d(GL_DEPTH24_STENCIL8, 2 * W, H);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, col_wide, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, dep_wide, 0);
    check("double-width framebuffer");
    glGenFramebuffers(1, &fb_read);
}

static const float GREY = 0.2f;

/* ---- the variants ------------------------------------------------------- */

static void eye_uniform(int mode, int eye, float slot)
{
    glUniform4f(u_eye[mode], (eye ? 1.0f : -1.0f) * SEP, CONV, slot, 0.0f);
}

static void draw_shader(int mode, int d)
{
    glUniform3fv(u_obj[mode], 1, obj + 3 * d);
    glDrawArrays(GL_TRIANGLES, first[d], count[d]);
}

static void frame_a(void)
{
    glUseProgram(programs[MODE_PLAIN]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_two);
    glViewport(0, 0, W, H);
    for (int e = 0; e < 2; e++) {
        glDrawBuffer(GL_COLOR_ATTACHMENT0 + e);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        eye_uniform(MODE_PLAIN, e, 0);
        for (int d = 0; d < N; d++) draw_shader(MODE_PLAIN, d);
    }
}

/* a with glFlush after every draw: what one llvmpipe scene flush costs. */
static void frame_af(void)
{
    glUseProgram(programs[MODE_PLAIN]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_two);
    glViewport(0, 0, W, H);
    for (int e = 0; e < 2; e++) {
        glDrawBuffer(GL_COLOR_ATTACHMENT0 + e);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        eye_uniform(MODE_PLAIN, e, 0);
        for (int d = 0; d < N; d++) {
            draw_shader(MODE_PLAIN, d);
            glFlush();
        }
    }
}

static void frame_b(void)
{
    glUseProgram(programs[MODE_PLAIN]);
    glViewport(0, 0, W, H);
    for (int e = 0; e < 2; e++) {
        glBindFramebuffer(GL_FRAMEBUFFER, fb_eye[e]);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            glBindFramebuffer(GL_FRAMEBUFFER, fb_eye[e]);
            eye_uniform(MODE_PLAIN, e, 0);
            draw_shader(MODE_PLAIN, d);
        }
}

static void frame_c(int own_depth)
{
    static const GLenum bufs[2][1] = {{GL_COLOR_ATTACHMENT0}, {GL_COLOR_ATTACHMENT1}};
    glUseProgram(programs[MODE_PLAIN]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_two);
    glViewport(0, 0, W, H);
    for (int e = 0; e < 2; e++) {
        glDrawBuffers(1, bufs[e]);
        if (own_depth)
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, dep_two[e], 0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            glDrawBuffers(1, bufs[e]);
            if (own_depth)
                glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, dep_two[e],
                                       0);
            eye_uniform(MODE_PLAIN, e, 0);
            draw_shader(MODE_PLAIN, d);
        }
    if (own_depth) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, dep_two[0], 0);
}

static void frame_c1(void) { frame_c(0); }
static void frame_c2(void) { frame_c(1); }

static void frame_d(void)
{
    glUseProgram(programs[MODE_LAYER]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_layered);
    glViewport(0, 0, W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            eye_uniform(MODE_LAYER, e, (float)e);
            draw_shader(MODE_LAYER, d);
        }
}

/* d with glFlush after every pair of draws: binning the next draw
 * overlaps rasterizing the last. */
static void frame_df(void)
{
    glUseProgram(programs[MODE_LAYER]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_layered);
    glViewport(0, 0, W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (int d = 0; d < N; d++) {
        for (int e = 0; e < 2; e++) {
            eye_uniform(MODE_LAYER, e, (float)e);
            draw_shader(MODE_LAYER, d);
        }
        glFlush();
    }
}

/* d with glFlush after a draw once 65536 vertices were drawn since the
 * last: a heavy scene's binning overlaps rasterization (a single huge
 * draw is flushed after each eye, as the program's own passes are), a
 * light one flushes rarely. */
static void frame_dt(void)
{
    glUseProgram(programs[MODE_LAYER]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_layered);
    glViewport(0, 0, W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    long since = 0;
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            eye_uniform(MODE_LAYER, e, (float)e);
            draw_shader(MODE_LAYER, d);
            since += count[d];
            if (since >= 65536) {
                glFlush();
                since = 0;
            }
        }
}

static void frame_e(void)
{
    glUseProgram(programs[MODE_PLAIN]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_wide);
    glViewport(0, 0, 2 * W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            glViewport(e * W, 0, W, H);
            glScissor(e * W, 0, W, H);
            eye_uniform(MODE_PLAIN, e, 0);
            draw_shader(MODE_PLAIN, d);
        }
    glDisable(GL_SCISSOR_TEST);
}

static void frame_e2(void)
{
    glUseProgram(programs[MODE_VIEWPORT]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_wide);
    glViewport(0, 0, 2 * W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (int e = 0; e < 2; e++) {
        glViewportIndexedf((GLuint)e, (float)(e * W), 0, (float)W, (float)H);
        glScissorIndexed((GLuint)e, e * W, 0, W, H);
    }
    glEnable(GL_SCISSOR_TEST);
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            eye_uniform(MODE_VIEWPORT, e, (float)e);
            draw_shader(MODE_VIEWPORT, d);
        }
    glDisable(GL_SCISSOR_TEST);
    glViewport(0, 0, W, H);
}

static void frame_f1(void)
{
    glUseProgram(programs[MODE_INSTANCED]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_layered);
    glViewport(0, 0, W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    eye_uniform(MODE_INSTANCED, 1, 0);
    for (int d = 0; d < N; d++) {
        glUniform3fv(u_obj[MODE_INSTANCED], 1, obj + 3 * d);
        glDrawArraysInstanced(GL_TRIANGLES, first[d], count[d], 2);
    }
}

static void frame_f2(void)
{
    glUseProgram(programs[MODE_GS]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_layered);
    glViewport(0, 0, W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    eye_uniform(MODE_GS, 1, 0);
    for (int d = 0; d < N; d++) draw_shader(MODE_GS, d);
}

/* Fixed function: the program loads its modelview per draw; the eye's
 * projection is loaded per eye (aff) or per draw (bff, eff). */
static void ff_begin(void)
{
    glUseProgram(0);
    glDisableVertexAttribArray(0);
    glDisableVertexAttribArray(1);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
}

static void ff_end(void)
{
    glDisableClientState(GL_VERTEX_ARRAY);
    glDisableClientState(GL_COLOR_ARRAY);
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
}

static void ff_projection(int eye)
{
    float p[16];
    eye_projection(eye, p);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(p);
    glMatrixMode(GL_MODELVIEW);
}

static void ff_draw(int d)
{
    glLoadIdentity();
    glTranslatef(obj[3 * d], obj[3 * d + 1], obj[3 * d + 2]);
    glDrawArrays(GL_TRIANGLES, first[d], count[d]);
}

static void frame_aff(void)
{
    ff_begin();
    glBindFramebuffer(GL_FRAMEBUFFER, fb_two);
    glViewport(0, 0, W, H);
    for (int e = 0; e < 2; e++) {
        glDrawBuffer(GL_COLOR_ATTACHMENT0 + e);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        ff_projection(e);
        for (int d = 0; d < N; d++) ff_draw(d);
    }
    ff_end();
}

/* The program's fixed-function draws with the layer's vertex shader in
 * place of fixed-function vertex processing, into the layered object. */
static void frame_dff(void)
{
    ff_begin();
    glUseProgram(programs[MODE_FF]);
    glBindFramebuffer(GL_FRAMEBUFFER, fb_layered);
    glViewport(0, 0, W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(MONO);
    glMatrixMode(GL_MODELVIEW);
    for (int d = 0; d < N; d++) {
        glLoadIdentity();
        glTranslatef(obj[3 * d], obj[3 * d + 1], obj[3 * d + 2]);
        for (int e = 0; e < 2; e++) {
            eye_uniform(MODE_FF, e, (float)e);
            glDrawArrays(GL_TRIANGLES, first[d], count[d]);
        }
    }
    glUseProgram(0);
    ff_end();
}

/* Fixed function into the layered object, the eye's layers attached
 * before every draw (colour and depth). */
static void frame_c2ff(void)
{
    ff_begin();
    glBindFramebuffer(GL_FRAMEBUFFER, fb_layered);
    glViewport(0, 0, W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, col_layered, 0, e);
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, dep_layered, 0, e);
            ff_projection(e);
            ff_draw(d);
        }
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, col_layered, 0);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, dep_layered, 0);
    ff_end();
}

static void frame_bff(void)
{
    ff_begin();
    glViewport(0, 0, W, H);
    for (int e = 0; e < 2; e++) {
        glBindFramebuffer(GL_FRAMEBUFFER, fb_eye[e]);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            glBindFramebuffer(GL_FRAMEBUFFER, fb_eye[e]);
            ff_projection(e);
            ff_draw(d);
        }
    ff_end();
}

static void frame_eff(void)
{
    ff_begin();
    glBindFramebuffer(GL_FRAMEBUFFER, fb_wide);
    glViewport(0, 0, 2 * W, H);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    for (int d = 0; d < N; d++)
        for (int e = 0; e < 2; e++) {
            glViewport(e * W, 0, W, H);
            glScissor(e * W, 0, W, H);
            ff_projection(e);
            ff_draw(d);
        }
    glDisable(GL_SCISSOR_TEST);
    ff_end();
}

/* Where a variant's eye ends up, for verify. */
enum { IN_TWO, IN_EYE, IN_LAYERED, IN_WIDE };

static const struct variant {
    const char *name;
    void (*frame)(void);
    int where;
} VARIANTS[] = {
    {"a", frame_a, IN_TWO},       {"af", frame_af, IN_TWO},     {"df", frame_df, IN_LAYERED},
    {"b", frame_b, IN_EYE},       {"c", frame_c1, IN_TWO},
    {"c2", frame_c2, IN_TWO},     {"d", frame_d, IN_LAYERED},   {"dt", frame_dt, IN_LAYERED},   {"e", frame_e, IN_WIDE},
    {"e2", frame_e2, IN_WIDE},    {"f1", frame_f1, IN_LAYERED}, {"f2", frame_f2, IN_LAYERED},
    {"aff", frame_aff, IN_TWO},   {"bff", frame_bff, IN_EYE},   {"c2ff", frame_c2ff, IN_LAYERED},
    {"dff", frame_dff, IN_LAYERED}, {"eff", frame_eff, IN_WIDE},
};
#define NVARIANTS (int)(sizeof VARIANTS / sizeof VARIANTS[0])

static void read_eye(int where, int eye, unsigned char *out)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fb_read);
    int x = 0;
    switch (where) {
    case IN_TWO:
        glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, col_two[eye], 0);
        break;
    case IN_EYE:
        glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, col_eye[eye], 0);
        break;
    case IN_LAYERED:
        glFramebufferTextureLayer(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, col_layered, 0, eye);
        break;
    default:
        glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, col_wide, 0);
        x = eye * W;
    }
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(x, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

static void setup(int w, int h)
{
    W = w;
    H = h;
    context();
    if (!has_extension("GL_ARB_shader_viewport_layer_array")) die("no GL_ARB_shader_viewport_layer_array");
    GLuint vao;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    make_scene();
    for (int m = 0; m < MODE_FF; m++) make_program(m);
    make_ff_program();
    make_targets();
    glClearColor(GREY, GREY, GREY, 1);
}

static const struct variant *find(const char *name)
{
    for (int v = 0; v < NVARIANTS; v++)
        if (strcmp(VARIANTS[v].name, name) == 0) return &VARIANTS[v];
    die("unknown variant");
    return NULL;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "probe") == 0) {
        context();
        printf("%s | %s\n", (const char *)glGetString(GL_RENDERER), (const char *)glGetString(GL_VERSION));
        static const char *names[] = {"GL_ARB_shader_viewport_layer_array", "GL_AMD_vertex_shader_layer",
                                      "GL_AMD_vertex_shader_viewport_index", "GL_ARB_viewport_array",
                                      "GL_NV_viewport_array2", "GL_OVR_multiview", "GL_OVR_multiview2",
                                      "GL_ARB_gpu_shader5", "GL_ARB_separate_shader_objects",
                                      "GL_ARB_get_program_binary", "GL_ARB_gl_spirv", "GL_ARB_vertex_program",
                                      "GL_ARB_shader_draw_parameters", "GL_ARB_explicit_uniform_location",
                                      "GL_ARB_multi_draw_indirect", "GL_ARB_indirect_parameters",
                                      "GL_ARB_tessellation_shader", "GL_ARB_transform_feedback3",
                                      "GL_NV_stereo_view_rendering", "GL_ARB_shader_atomic_counters",
                                      "GL_ARB_shader_image_load_store", "GL_ARB_conditional_render_inverted"};
        for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
            printf("%-40s %s\n", names[i], has_extension(names[i]) ? "yes" : "no");
        return 0;
    }
    if (argc >= 4 && strcmp(argv[1], "verify") == 0) {
        N = 100;
        HEAVY = 0;
        setup(atoi(argv[2]), atoi(argv[3]));
        size_t n = (size_t)W * H * 4;
        unsigned char *ref[2] = {malloc(n), malloc(n)}, *got = malloc(n);
        frame_a();
        glFinish();
        read_eye(IN_TWO, 0, ref[0]);
        read_eye(IN_TWO, 1, ref[1]);
        long differ = 0;
        for (size_t i = 0; i < n; i++) differ += ref[0][i] != ref[1][i];
        long grey = 0;
        for (size_t i = 0; i < n; i += 4) grey += ref[0][i] == (unsigned char)(GREY * 255 + 0.5f);
        printf("a: left and right differ in %ld channels (stereo, as wanted); %ld of %ld left pixels grey\n",
               differ, grey, (long)(n / 4));
        for (int v = 1; v < NVARIANTS; v++) {
            VARIANTS[v].frame();
            glFinish();
            for (int e = 0; e < 2; e++) {
                read_eye(VARIANTS[v].where, e, got);
                int max = 0;
                long bad = 0;
                for (size_t i = 0; i < n; i++) {
                    int dd = abs((int)got[i] - (int)ref[e][i]);
                    if (dd > max) max = dd;
                    bad += dd > 2;
                }
                printf("%-4s %s eye: max channel difference from a %3d, %ld channels differ by more than 2\n",
                       VARIANTS[v].name, e ? "right" : "left ", max, bad);
            }
        }
        return 0;
    }
    if (argc < 8 || strcmp(argv[1], "run") != 0) {
        fprintf(stderr, "usage: auto_mechanisms probe | verify W H | run W H light|heavy N FRAMES ROUNDS [VARIANT...]\n");
        return 2;
    }
    HEAVY = strcmp(argv[4], "heavy") == 0;
    N = atoi(argv[5]);
    int frames = atoi(argv[6]), rounds = atoi(argv[7]);
    if (N < 1 || frames < 1 || rounds < 1) die("N, FRAMES and ROUNDS must be positive");
    setup(atoi(argv[2]), atoi(argv[3]));
    const struct variant *chosen[NVARIANTS];
    int nv = 0;
    if (argc > 8)
        for (int i = 8; i < argc && nv < NVARIANTS; i++) chosen[nv++] = find(argv[i]);
    else
        for (int v = 0; v < NVARIANTS; v++) chosen[nv++] = &VARIANTS[v];
    double *t = malloc(sizeof(double) * nv * frames * rounds);
    for (int r = 0; r < rounds; r++)
        for (int v = 0; v < nv; v++) {
            chosen[v]->frame(); /* warm-up: buffers bound, shaders compiled */
            glFinish();
            for (int f = 0; f < frames; f++) {
                double t0 = now_ms();
                chosen[v]->frame();
                glFinish();
                t[(size_t)v * frames * rounds + (size_t)r * frames + f] = now_ms() - t0;
            }
        }
    /* Per round, each variant's median frame over the first variant's:
     * variants alternate within a round, so a round's ratio is measured
     * under one load; the median of the rounds' ratios and their range are
     * printed beside the median frame time over all rounds. */
    double *round_median = malloc(sizeof(double) * nv * rounds), *ratio = malloc(sizeof(double) * rounds);
    double *sorted = malloc(sizeof(double) * frames);
    if (!round_median || !ratio || !sorted) die("out of memory");
    for (int v = 0; v < nv; v++)
        for (int r = 0; r < rounds; r++) {
            memcpy(sorted, t + (size_t)v * frames * rounds + (size_t)r * frames, sizeof(double) * frames);
            qsort(sorted, (size_t)frames, sizeof(double), cmp);
            round_median[v * rounds + r] = sorted[frames / 2];
        }
    for (int v = 0; v < nv; v++) {
        for (int r = 0; r < rounds; r++) ratio[r] = round_median[v * rounds + r] / round_median[r];
        qsort(ratio, (size_t)rounds, sizeof(double), cmp);
        double *tv = t + (size_t)v * frames * rounds;
        qsort(tv, (size_t)frames * rounds, sizeof(double), cmp);
        printf("%s %dx%d N=%d %s: median %.3f ms/frame (%.2fx %s; rounds %.2f-%.2f)\n", argv[4], W, H, N,
               chosen[v]->name, tv[frames * rounds / 2], ratio[rounds / 2], chosen[0]->name, ratio[0],
               ratio[rounds - 1]);
    }
    return 0;
}

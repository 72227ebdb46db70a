/*
 * Core-profile programs on a stereo framebuffer: shaders with user-defined
 * outputs, glClearBuffer and GL 4.5 direct state access on framebuffer 0,
 * checked pixel by pixel in each eye. An unmodified GLX program (links
 * only -lGL -lX11; GL 3.3/4.5 functions called by name).
 *
 *   glx_core_stereo core33   GL 3.3 core, GLX_STEREO configuration: a
 *                            shader's `out vec4` under GL_BACK and
 *                            GL_FRONT_AND_BACK reaches every selected
 *                            buffer through every draw entry point; the
 *                            shader runs once per fragment (queries);
 *                            glClearBuffer; glDrawBuffers routing
 *   glx_core_stereo core45   GL 4.5 core: the same plus atomic counters,
 *                            indirect and transform-feedback draws,
 *                            separable programs, and DSA on framebuffer 0;
 *                            then prints the probes (lines "probe ...")
 *   glx_core_stereo compat   immediate mode (glBegin/glEnd) with a GLSL
 *                            1.30 `out` shader in a compatibility context,
 *                            and a shader writing gl_FragData[0]
 *   glx_core_stereo kept     GL 3.3 core: a program using location 6 itself
 *                            keeps output 0 in the first selected buffer
 *                            (the layer says why on stderr)
 *   glx_core_stereo binary   GL 4.5 core: program binaries keep output 0
 *                            in every selected buffer (a binary made by a
 *                            mono context without the copies is refused;
 *                            one made here round-trips with them, also
 *                            through the OES names)
 *   glx_core_stereo mono45   no checks: a mono configuration, prints the
 *                            probes (the test compares them with core45's:
 *                            the errors and values GL gives a default
 *                            framebuffer are the driver's)
 *
 * Prints "N passed, N failed" last; exit 0 when all pass, 2 when a
 * configuration or context is missing.
 */
#define GL_GLEXT_PROTOTYPES 1
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

#include "check.h"

#define W 32
#define H 16

enum { FL, BL, FR, BR };
static const GLenum BUF[4] = {GL_FRONT_LEFT, GL_BACK_LEFT, GL_FRONT_RIGHT, GL_BACK_RIGHT};
static const char *BUF_NAME[4] = {"FRONT_LEFT", "BACK_LEFT", "FRONT_RIGHT", "BACK_RIGHT"};

static GLint get_int(GLenum pname)
{
    GLint v = -1;
    glGetIntegerv(pname, &v);
    return v;
}

static void drain_errors(const char *where)
{
    GLenum e;
    int n = 0;
    while ((e = glGetError()) != GL_NO_ERROR && n++ < 8) {
        CHECK(e == GL_NO_ERROR, "%s: unexpected GL error 0x%x", where, e);
    }
}

/* The colour at (x, y) of buffer b, RGB; the read buffer is put back. */
static void pixel_at(int b, int x, int y, unsigned char out[3])
{
    unsigned char px[4] = {0, 0, 0, 0};
    GLint prev = get_int(GL_READ_BUFFER);
    glReadBuffer(BUF[b]);
    glReadPixels(x, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    glReadBuffer((GLenum)prev);
    memcpy(out, px, 3);
}

static int buffer_is(int b, int r, int g, int bl)
{
    unsigned char px[3];
    pixel_at(b, W / 2, H / 2, px);
    return px[0] == r && px[1] == g && px[2] == bl;
}

static void clear_all(void)
{
    glDrawBuffer(GL_FRONT_AND_BACK);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
}

/* Each of the four buffers is (r, g, b) when `want` has its bit, black
 * otherwise. */
static void expect_buffers(const char *what, int want, int r, int g, int b)
{
    for (int i = 0; i < 4; i++) {
        unsigned char px[3];
        pixel_at(i, W / 2, H / 2, px);
        int lit = px[0] == r && px[1] == g && px[2] == b;
        int black = px[0] == 0 && px[1] == 0 && px[2] == 0;
        if (want & (1 << i)) {
            CHECK(lit, "%s: %s is %d,%d,%d, wanted %d,%d,%d", what, BUF_NAME[i], px[0], px[1],
                  px[2], r, g, b);
        } else {
            CHECK(black, "%s: %s is %d,%d,%d, wanted untouched (black)", what, BUF_NAME[i],
                  px[0], px[1], px[2]);
        }
    }
}

#define M_BACK ((1 << BL) | (1 << BR))
#define M_ALL 15

static GLuint compile(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        CHECK(ok, "shader compiles: %s", log);
    }
    return s;
}

/* A program as many engines make it: shaders flagged for deletion as soon
 * as they are attached, then linked. */
static GLuint program(const char *vs, const char *fs)
{
    GLuint p = glCreateProgram();
    GLuint v = compile(GL_VERTEX_SHADER, vs), f = compile(GL_FRAGMENT_SHADER, fs);
    glAttachShader(p, v);
    glAttachShader(p, f);
    glDeleteShader(v);
    glDeleteShader(f);
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    CHECK(ok, "program links");
    GLint attached = 0;
    glGetProgramiv(p, GL_ATTACHED_SHADERS, &attached);
    CHECK(attached == 2, "the program keeps its two shaders attached (%d)", attached);
    GLuint names[2] = {0, 0};
    glGetAttachedShaders(p, 2, NULL, names);
    CHECK((names[0] == v && names[1] == f) || (names[0] == f && names[1] == v),
          "the attached shaders are the program's own (%u %u, wanted %u %u)", names[0],
          names[1], v, f);
    glDetachShader(p, v);
    glDetachShader(p, f);
    CHECK(glGetError() == GL_NO_ERROR, "the program's shaders can be detached after the link");
    return p;
}

static const char *VS33 = "#version 330 core\n"
                          "layout(location = 0) in vec2 pos;\n"
                          "void main() { gl_Position = vec4(pos, 0.0, 1.0); }\n";
static const char *FS_TINT = "#version 330 core\n"
                             "uniform vec4 tint;\n"
                             "layout(location = 0) out vec4 color;\n"
                             "void main() { color = tint; }\n";
/* No layout qualifier (the linker picks location 0), an early return. */
static const char *FS_AUTO = "#version 150\n"
                             "out vec4 frag;\n"
                             "void main()\n"
                             "{\n"
                             "    frag = vec4(0.0, 1.0, 0.0, 1.0);\n"
                             "    if (gl_FragCoord.x > 0.0) return;\n"
                             "    frag = vec4(1.0);\n"
                             "}\n";
/* GLSL allows blanks between '#' and the directive's name. */
static const char *FS_SPACED = "// spaced directive\n"
                               "  #  version 330 core\n"
                               "layout(location = 0) out vec4 color;\n"
                               "void main() { color = vec4(1.0, 0.0, 1.0, 1.0); }\n";
static const char *FS_MRT = "#version 330 core\n"
                            "layout(location = 0) out vec4 c0;\n"
                            "layout(location = 1) out vec4 c1;\n"
                            "void main() { c0 = vec4(1.0, 0.0, 0.0, 1.0); c1 = vec4(0.0, 0.0, 1.0, 1.0); }\n";

static GLuint vao, vbo, ibo;

/* A full-window quad: 4 vertices (strip order) and 6 indices. */
static void geometry(void)
{
    static const float quad[] = {-1, -1, 1, -1, -1, 1, 1, 1};
    static const unsigned short idx[] = {0, 1, 2, 2, 1, 3};
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, 0);
    glEnableVertexAttribArray(0);
    glGenBuffers(1, &ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof idx, idx, GL_STATIC_DRAW);
}

typedef struct {
    GLuint count, instanceCount, first, baseInstance;
} ArraysIndirect;

/* Each draw entry point, drawing the quad once. */
static void draw_with(int entry)
{
    static const GLint firsts[1] = {0};
    static const GLsizei counts[1] = {4};
    static const GLsizei icounts[1] = {6};
    const void *ioffsets[1] = {0};
    switch (entry) {
    case 0: glDrawArrays(GL_TRIANGLE_STRIP, 0, 4); break;
    case 1: glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, 0); break;
    case 2: glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, 1); break;
    case 3: glDrawElementsInstanced(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, 0, 1); break;
    case 4: glDrawElementsBaseVertex(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, 0, 0); break;
    case 5: glDrawRangeElements(GL_TRIANGLES, 0, 3, 6, GL_UNSIGNED_SHORT, 0); break;
    case 6: glMultiDrawArrays(GL_TRIANGLE_STRIP, firsts, counts, 1); break;
    case 7: glMultiDrawElements(GL_TRIANGLES, icounts, GL_UNSIGNED_SHORT, ioffsets, 1); break;
    case 8: glDrawElementsInstancedBaseVertex(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, 0, 1, 0); break;
    /* GL 4.x */
    case 9: glDrawArraysInstancedBaseInstance(GL_TRIANGLE_STRIP, 0, 4, 1, 0); break;
    case 10: {
        ArraysIndirect cmd = {4, 1, 0, 0};
        GLuint buf;
        glGenBuffers(1, &buf);
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buf);
        glBufferData(GL_DRAW_INDIRECT_BUFFER, sizeof cmd, &cmd, GL_STATIC_DRAW);
        glDrawArraysIndirect(GL_TRIANGLE_STRIP, 0);
        glMultiDrawArraysIndirect(GL_TRIANGLE_STRIP, 0, 1, 0);
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
        glDeleteBuffers(1, &buf);
        break;
    }
    }
}

static const char *ENTRY_NAME[] = {"glDrawArrays",
                                   "glDrawElements",
                                   "glDrawArraysInstanced",
                                   "glDrawElementsInstanced",
                                   "glDrawElementsBaseVertex",
                                   "glDrawRangeElements",
                                   "glMultiDrawArrays",
                                   "glMultiDrawElements",
                                   "glDrawElementsInstancedBaseVertex",
                                   "glDrawArraysInstancedBaseInstance",
                                   "glDrawArraysIndirect + glMultiDrawArraysIndirect"};

/* One draw of the quad under GL_BACK with a program of VS33 and `fs`:
 * both back buffers are (r, g, b), the fronts untouched. */
static void back_shows(const char *what, const char *fs, int r, int g, int b)
{
    GLuint p = program(VS33, fs);
    glUseProgram(p);
    clear_all();
    glDrawBuffer(GL_BACK);
    draw_with(0);
    expect_buffers(what, M_BACK, r, g, b);
    glUseProgram(0);
    glDeleteProgram(p);
}

/* 1: a shader's user-defined output 0 reaches every buffer the draw
 * buffer selects, through every draw entry point. */
static void user_outputs(int entries)
{
    GLuint p = program(VS33, FS_TINT);
    glUseProgram(p);
    GLint tint = glGetUniformLocation(p, "tint");
    for (int e = 0; e < entries; e++) {
        clear_all();
        glDrawBuffer(GL_BACK);
        glUniform4f(tint, 1.0f, 0.5f, 0.0f, 1.0f);
        draw_with(e);
        char what[96];
        snprintf(what, sizeof what, "GL_BACK, %s", ENTRY_NAME[e]);
        expect_buffers(what, M_BACK, 255, 128, 0);
    }
    clear_all();
    glDrawBuffer(GL_FRONT_AND_BACK);
    glUniform4f(tint, 0.0f, 0.0f, 1.0f, 1.0f);
    draw_with(0);
    expect_buffers("GL_FRONT_AND_BACK", M_ALL, 0, 0, 255);
    const struct {
        GLenum name;
        int mask;
        const char *label;
    } one[] = {{GL_BACK_RIGHT, 1 << BR, "GL_BACK_RIGHT"},
               {GL_BACK_LEFT, 1 << BL, "GL_BACK_LEFT"},
               {GL_RIGHT, (1 << FR) | (1 << BR), "GL_RIGHT"},
               {GL_LEFT, (1 << FL) | (1 << BL), "GL_LEFT"},
               {GL_FRONT, (1 << FL) | (1 << FR), "GL_FRONT"}};
    for (unsigned i = 0; i < sizeof one / sizeof one[0]; i++) {
        clear_all();
        glDrawBuffer(one[i].name);
        glUniform4f(tint, 1.0f, 1.0f, 0.0f, 1.0f);
        draw_with(0);
        expect_buffers(one[i].label, one[i].mask, 255, 255, 0);
    }
    glDeleteProgram(p);
    /* Output 0 without a layout qualifier, and an early return. */
    back_shows("auto location, early return", FS_AUTO, 0, 255, 0);
    /* An output name longer than 255 characters (GLSL allows 1024). */
    static char fs_long[800];
    char name[301];
    memset(name, 'x', 300);
    name[300] = '\0';
    snprintf(fs_long, sizeof fs_long,
             "#version 330 core\nlayout(location = 0) out vec4 %s;\n"
             "void main() { %s = vec4(0.0, 1.0, 1.0, 1.0); }\n",
             name, name);
    back_shows("a 300-character output name", fs_long, 0, 255, 255);
    back_shows("'#  version' with blanks", FS_SPACED, 255, 0, 255);
    glUseProgram(0);
    drain_errors("user outputs");
}

/* The shader runs once per fragment, as on a real stereo framebuffer:
 * one draw under GL_BACK passes W*H samples, and generates 2 primitives. */
static void side_effects_once(void)
{
    GLuint p = program(VS33, FS_TINT);
    glUseProgram(p);
    GLuint q[2];
    glGenQueries(2, q);
    clear_all();
    glDrawBuffer(GL_BACK);
    glBeginQuery(GL_SAMPLES_PASSED, q[0]);
    glBeginQuery(GL_PRIMITIVES_GENERATED, q[1]);
    draw_with(0);
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint samples = 0, prims = 0;
    glGetQueryObjectuiv(q[0], GL_QUERY_RESULT, &samples);
    glGetQueryObjectuiv(q[1], GL_QUERY_RESULT, &prims);
    CHECK(samples == W * H, "GL_SAMPLES_PASSED under GL_BACK: %u, wanted %u", samples, W * H);
    CHECK(prims == 2, "GL_PRIMITIVES_GENERATED under GL_BACK: %u, wanted 2", prims);
    glDeleteQueries(2, q);
    glDeleteProgram(p);
    glUseProgram(0);
    drain_errors("side effects");
}

/* 3: glDrawBuffers on framebuffer 0 routes output i to entry i. */
static void draw_buffers_routing(void)
{
    GLuint p = program(VS33, FS_MRT);
    glUseProgram(p);
    clear_all();
    const GLenum lr[2] = {GL_BACK_LEFT, GL_BACK_RIGHT};
    glDrawBuffers(2, lr);
    draw_with(0);
    CHECK(buffer_is(BL, 255, 0, 0), "glDrawBuffers({BL, BR}): output 0 in back-left");
    CHECK(buffer_is(BR, 0, 0, 255), "glDrawBuffers({BL, BR}): output 1 in back-right");
    clear_all();
    const GLenum rl[2] = {GL_BACK_RIGHT, GL_BACK_LEFT};
    glDrawBuffers(2, rl);
    draw_with(0);
    CHECK(buffer_is(BR, 255, 0, 0), "glDrawBuffers({BR, BL}): output 0 in back-right");
    CHECK(buffer_is(BL, 0, 0, 255), "glDrawBuffers({BR, BL}): output 1 in back-left");
    /* Under glDrawBuffer(GL_BACK) only output 0 counts, in both eyes. */
    clear_all();
    glDrawBuffer(GL_BACK);
    draw_with(0);
    expect_buffers("two outputs under GL_BACK", M_BACK, 255, 0, 0);
    glDeleteProgram(p);
    glUseProgram(0);
    drain_errors("draw buffers routing");
}

/* 2: glClearBuffer clears every buffer the draw buffer selects. */
static void clear_buffer(void)
{
    const GLfloat green[4] = {0, 1, 0, 1}, red[4] = {1, 0, 0, 1};
    clear_all();
    glDrawBuffer(GL_BACK);
    glClearBufferfv(GL_COLOR, 0, green);
    expect_buffers("glClearBufferfv(GL_COLOR, 0) under GL_BACK", M_BACK, 0, 255, 0);
    clear_all();
    glDrawBuffer(GL_BACK);
    glClearBufferfv(GL_COLOR, 1, red);
    CHECK(glGetError() == GL_NO_ERROR, "draw buffer 1 under GL_BACK is GL_NONE: no error");
    expect_buffers("glClearBufferfv(GL_COLOR, 1) under GL_BACK", 0, 0, 0, 0);
    for (int i = 5; i < 8; i++) {
        glClearBufferfv(GL_COLOR, i, red);
    }
    expect_buffers("glClearBufferfv(GL_COLOR, 5..7) under GL_BACK", 0, 0, 0, 0);
    clear_all();
    glDrawBuffer(GL_FRONT_AND_BACK);
    glClearBufferfv(GL_COLOR, 0, red);
    expect_buffers("glClearBufferfv under GL_FRONT_AND_BACK", M_ALL, 255, 0, 0);
    clear_all();
    glDrawBuffer(GL_BACK_RIGHT);
    glClearBufferfv(GL_COLOR, 0, green);
    expect_buffers("glClearBufferfv under GL_BACK_RIGHT", 1 << BR, 0, 255, 0);
    const GLenum lr[2] = {GL_BACK_LEFT, GL_BACK_RIGHT};
    clear_all();
    glDrawBuffers(2, lr);
    glClearBufferfv(GL_COLOR, 1, red);
    expect_buffers("glClearBufferfv(GL_COLOR, 1) under {BL, BR}", 1 << BR, 255, 0, 0);
    const GLint zero = 0;
    glClearBufferiv(GL_STENCIL, 0, &zero);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glDrawBuffer(GL_BACK);
    drain_errors("clear buffer");
}

/* GL 4.2: atomic counters count each fragment once. */
static void atomic_counter_once(void)
{
    static const char *fs = "#version 450 core\n"
                            "layout(binding = 0, offset = 0) uniform atomic_uint count;\n"
                            "layout(location = 0) out vec4 color;\n"
                            "void main() { atomicCounterIncrement(count); color = vec4(1.0, 1.0, 0.0, 1.0); }\n";
    GLuint p = program(VS33, fs);
    GLuint buf, zero = 0, n = 0;
    glGenBuffers(1, &buf);
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, buf);
    glBufferData(GL_ATOMIC_COUNTER_BUFFER, sizeof zero, &zero, GL_DYNAMIC_READ);
    glUseProgram(p);
    clear_all();
    glDrawBuffer(GL_BACK);
    draw_with(0);
    glMemoryBarrier(GL_ATOMIC_COUNTER_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetBufferSubData(GL_ATOMIC_COUNTER_BUFFER, 0, sizeof n, &n);
    CHECK(n == W * H, "atomic counter after one draw under GL_BACK: %u, wanted %u", n, W * H);
    expect_buffers("atomic-counter shader under GL_BACK", M_BACK, 255, 255, 0);
    glDeleteBuffers(1, &buf);
    glDeleteProgram(p);
    glUseProgram(0);
    drain_errors("atomic counter");
}

/* GL 4.4: output 0 split into components by two variables. */
static void component_outputs(void)
{
    static const char *fs = "#version 450 core\n"
                            "layout(location = 0, component = 0) out vec2 rg;\n"
                            "layout(location = 0, component = 2) out vec2 ba;\n"
                            "void main() { rg = vec2(1.0, 0.5); ba = vec2(1.0, 1.0); }\n";
    back_shows("output 0 in two components", fs, 255, 128, 255);
    drain_errors("component outputs");
}

/* GL 4.0: a transform-feedback draw, and GL 4.1 separable programs. */
static void feedback_and_separable(void)
{
    static const char *vs = "#version 330 core\n"
                            "layout(location = 0) in vec2 pos;\n"
                            "out vec2 p;\n"
                            "void main() { p = pos; gl_Position = vec4(pos, 0.0, 1.0); }\n";
    GLuint prog = glCreateProgram();
    GLuint v = compile(GL_VERTEX_SHADER, vs);
    glAttachShader(prog, v);
    const char *varyings[1] = {"p"};
    glTransformFeedbackVaryings(prog, 1, varyings, GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(prog);
    GLuint tfb, out;
    glGenTransformFeedbacks(1, &tfb);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, tfb);
    glGenBuffers(1, &out);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out);
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, 4 * 2 * sizeof(float), NULL, GL_STATIC_DRAW);
    glUseProgram(prog);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, 4);
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    /* Draw the captured corners as a strip with a fragment program made by
     * glCreateShaderProgramv, in a pipeline. */
    static const char *fs = "#version 450 core\n"
                            "layout(location = 0) out vec4 color;\n"
                            "void main() { color = vec4(1.0, 0.0, 1.0, 1.0); }\n";
    static const char *vs_sep = "#version 450 core\n"
                                "layout(location = 0) in vec2 pos;\n"
                                "out gl_PerVertex { vec4 gl_Position; };\n"
                                "void main() { gl_Position = vec4(pos, 0.0, 1.0); }\n";
    GLuint fprog = glCreateShaderProgramv(GL_FRAGMENT_SHADER, 1, &fs);
    GLuint vprog = glCreateShaderProgramv(GL_VERTEX_SHADER, 1, &vs_sep);
    GLuint pipe;
    glGenProgramPipelines(1, &pipe);
    glUseProgramStages(pipe, GL_VERTEX_SHADER_BIT, vprog);
    glUseProgramStages(pipe, GL_FRAGMENT_SHADER_BIT, fprog);
    glUseProgram(0);
    glBindProgramPipeline(pipe);
    GLuint fvao;
    glGenVertexArrays(1, &fvao);
    glBindVertexArray(fvao);
    glBindBuffer(GL_ARRAY_BUFFER, out);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, 0);
    glEnableVertexAttribArray(0);
    clear_all();
    glDrawBuffer(GL_BACK);
    glDrawTransformFeedback(GL_TRIANGLE_STRIP, tfb);
    expect_buffers("glDrawTransformFeedback, glCreateShaderProgramv pipeline", M_BACK, 255, 0,
                   255);
    glBindProgramPipeline(0);
    glBindVertexArray(vao);
    glDeleteVertexArrays(1, &fvao);
    glDeleteProgramPipelines(1, &pipe);
    glDeleteProgram(fprog);
    glDeleteProgram(vprog);
    glDeleteTransformFeedbacks(1, &tfb);
    glDeleteBuffers(1, &out);
    glDeleteShader(v);
    glDeleteProgram(prog);
    drain_errors("feedback and separable");
}

/* A program the copies cannot be added to (it uses location 6 itself):
 * linked as asked, still drawing output 0 into the first selected buffer;
 * the layer says so on stderr (the test reads it). */
static void kept_program(void)
{
    static const char *fs = "#version 330 core\n"
                            "layout(location = 0) out vec4 a;\n"
                            "layout(location = 6) out vec4 b;\n"
                            "void main() { a = vec4(0.0, 1.0, 0.0, 1.0); b = vec4(1.0); }\n";
    GLuint p = program(VS33, fs);
    glUseProgram(p);
    clear_all();
    glDrawBuffer(GL_BACK);
    draw_with(0);
    CHECK(buffer_is(BL, 0, 255, 0), "a kept program draws output 0 into back-left");
    CHECK(glGetFragDataLocation(p, "b") == 6, "its own location 6 stays");
    glUseProgram(0);
    glDeleteProgram(p);
    drain_errors("kept program");
}

/* What each draw-buffer name selects (GL 4.5 table 17.4) and bad values. */
static const struct {
    GLenum name;
    const char *label;
} NAMES[] = {{GL_NONE, "GL_NONE"},
             {GL_FRONT_LEFT, "GL_FRONT_LEFT"},
             {GL_FRONT_RIGHT, "GL_FRONT_RIGHT"},
             {GL_BACK_LEFT, "GL_BACK_LEFT"},
             {GL_BACK_RIGHT, "GL_BACK_RIGHT"},
             {GL_FRONT, "GL_FRONT"},
             {GL_BACK, "GL_BACK"},
             {GL_LEFT, "GL_LEFT"},
             {GL_RIGHT, "GL_RIGHT"},
             {GL_FRONT_AND_BACK, "GL_FRONT_AND_BACK"},
             {0x1234, "0x1234"},
             {GL_TEXTURE_2D, "GL_TEXTURE_2D"},
             {GL_COLOR_ATTACHMENT0, "GL_COLOR_ATTACHMENT0"}};
#define N_NAMES (sizeof NAMES / sizeof NAMES[0])

/* 4: DSA on framebuffer 0 is the emulated framebuffer. */
static void dsa(void)
{
    GLuint tex, fbo;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);

    /* The draw-buffer table: glNamedFramebufferDrawBuffer(0, x) does what
     * glDrawBuffer(x) does on framebuffer 0 (error and state), with the
     * program's own framebuffer bound meanwhile. */
    for (unsigned i = 0; i < N_NAMES; i++) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDrawBuffer(GL_BACK);
        glDrawBuffer(NAMES[i].name);
        GLenum e1 = glGetError();
        GLint d1 = get_int(GL_DRAW_BUFFER);
        glDrawBuffer(GL_BACK);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glNamedFramebufferDrawBuffer(0, NAMES[i].name);
        GLenum e2 = glGetError();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        GLint d2 = get_int(GL_DRAW_BUFFER);
        CHECK(e1 == e2 && d1 == d2,
              "glNamedFramebufferDrawBuffer(0, %s): error 0x%x draw buffer 0x%x; glDrawBuffer: "
              "0x%x 0x%x",
              NAMES[i].label, e2, d2, e1, d1);
        glReadBuffer(GL_BACK);
        glReadBuffer(NAMES[i].name);
        e1 = glGetError();
        d1 = get_int(GL_READ_BUFFER);
        glReadBuffer(GL_BACK);
        glNamedFramebufferReadBuffer(0, NAMES[i].name);
        e2 = glGetError();
        d2 = get_int(GL_READ_BUFFER);
        CHECK(e1 == e2 && d1 == d2,
              "glNamedFramebufferReadBuffer(0, %s): error 0x%x read buffer 0x%x; glReadBuffer: "
              "0x%x 0x%x",
              NAMES[i].label, e2, d2, e1, d1);
        GLenum list[1] = {NAMES[i].name};
        glDrawBuffer(GL_BACK);
        glDrawBuffers(1, list);
        e1 = glGetError();
        d1 = get_int(GL_DRAW_BUFFER0);
        glDrawBuffer(GL_BACK);
        glNamedFramebufferDrawBuffers(0, 1, list);
        e2 = glGetError();
        d2 = get_int(GL_DRAW_BUFFER0);
        CHECK(e1 == e2 && d1 == d2,
              "glNamedFramebufferDrawBuffers(0, {%s}): error 0x%x 0x%x; glDrawBuffers: 0x%x 0x%x",
              NAMES[i].label, e2, d2, e1, d1);
    }
    glDrawBuffer(GL_BACK);
    glReadBuffer(GL_BACK);
    drain_errors("dsa table");

    /* glNamedFramebufferDrawBuffer(0, GL_BACK_RIGHT) then a clear of 0. */
    clear_all();
    glDrawBuffer(GL_BACK);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glNamedFramebufferDrawBuffer(0, GL_BACK_RIGHT);
    const GLfloat cyan[4] = {0, 1, 1, 1}, magenta[4] = {1, 0, 1, 1};
    glClearNamedFramebufferfv(0, GL_COLOR, 0, cyan);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    CHECK(get_int(GL_DRAW_BUFFER) == GL_BACK_RIGHT, "GL_DRAW_BUFFER after the DSA call");
    expect_buffers("glClearNamedFramebufferfv(0) under GL_BACK_RIGHT", 1 << BR, 0, 255, 255);
    clear_all();
    glNamedFramebufferDrawBuffer(0, GL_BACK);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glClearNamedFramebufferfv(0, GL_COLOR, 0, cyan);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    expect_buffers("glClearNamedFramebufferfv(0) under GL_BACK", M_BACK, 0, 255, 255);
    glClearNamedFramebufferfi(0, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    drain_errors("dsa clear");

    /* Presenting the way engines do: blit an offscreen framebuffer into 0. */
    clear_all();
    glDrawBuffer(GL_BACK);
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, magenta);
    glBlitNamedFramebuffer(fbo, 0, 0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    expect_buffers("glBlitNamedFramebuffer(fbo, 0) under GL_BACK", M_BACK, 255, 0, 255);
    clear_all();
    glNamedFramebufferDrawBuffer(0, GL_BACK_RIGHT);
    glBlitNamedFramebuffer(fbo, 0, 0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    expect_buffers("glBlitNamedFramebuffer(fbo, 0) under GL_BACK_RIGHT", 1 << BR, 255, 0, 255);
    /* And from 0: the read buffer set with glNamedFramebufferReadBuffer. */
    glDrawBuffer(GL_BACK_LEFT);
    glClearColor(0, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glNamedFramebufferReadBuffer(0, GL_BACK_RIGHT);
    glBlitNamedFramebuffer(0, fbo, 0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    unsigned char px[4] = {0};
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    CHECK(px[0] == 255 && px[1] == 0 && px[2] == 255,
          "glBlitNamedFramebuffer(0, fbo) reads back-right: %d,%d,%d", px[0], px[1], px[2]);
    glNamedFramebufferReadBuffer(0, GL_BACK_LEFT);
    glBlitNamedFramebuffer(0, fbo, 0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    CHECK(px[0] == 0 && px[1] == 0 && px[2] == 255,
          "glBlitNamedFramebuffer(0, fbo) reads back-left: %d,%d,%d", px[0], px[1], px[2]);
    glDrawBuffer(GL_BACK);
    glReadBuffer(GL_BACK);
    drain_errors("dsa blit");

    /* Queries on 0. */
    GLint v = -1;
    glGetNamedFramebufferParameteriv(0, GL_STEREO, &v);
    CHECK(v == 1, "glGetNamedFramebufferParameteriv(0, GL_STEREO): %d", v);
    v = -1;
    glGetNamedFramebufferParameteriv(0, GL_DOUBLEBUFFER, &v);
    CHECK(v == 1, "glGetNamedFramebufferParameteriv(0, GL_DOUBLEBUFFER): %d", v);
    v = -1;
    glGetFramebufferParameteriv(GL_DRAW_FRAMEBUFFER, GL_STEREO, &v);
    CHECK(v == 1, "glGetFramebufferParameteriv(GL_DRAW_FRAMEBUFFER, GL_STEREO): %d", v);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    v = -1;
    glGetNamedFramebufferParameteriv(0, GL_STEREO, &v);
    CHECK(v == 1, "glGetNamedFramebufferParameteriv(0, GL_STEREO) with an FBO bound: %d", v);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (int b = 0; b < 4; b++) {
        GLint type = -1, red = -1;
        glGetNamedFramebufferAttachmentParameteriv(0, BUF[b], GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
                                                   &type);
        glGetNamedFramebufferAttachmentParameteriv(0, BUF[b], GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE,
                                                   &red);
        CHECK(type == GL_FRAMEBUFFER_DEFAULT && red == 8, "%s: type 0x%x red size %d",
              BUF_NAME[b], type, red);
    }
    CHECK(glCheckNamedFramebufferStatus(0, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
          "glCheckNamedFramebufferStatus(0)");
    /* glReadnPixels reads the emulated read buffer. */
    glDrawBuffer(GL_BACK_RIGHT);
    glClearColor(1, 1, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glReadBuffer(GL_BACK_RIGHT);
    memset(px, 0, sizeof px);
    glReadnPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, sizeof px, px);
    CHECK(px[0] == 255 && px[1] == 255 && px[2] == 0, "glReadnPixels(GL_BACK_RIGHT): %d,%d,%d",
          px[0], px[1], px[2]);
    /* Invalidation takes the default framebuffer's names. */
    const GLenum inv[3] = {GL_COLOR, GL_DEPTH, GL_STENCIL};
    glInvalidateFramebuffer(GL_FRAMEBUFFER, 3, inv);
    CHECK(glGetError() == GL_NO_ERROR, "glInvalidateFramebuffer(GL_COLOR, GL_DEPTH, GL_STENCIL)");
    const GLenum inv2[2] = {GL_BACK_LEFT, GL_BACK_RIGHT};
    glInvalidateSubFramebuffer(GL_DRAW_FRAMEBUFFER, 2, inv2, 0, 0, 4, 4);
    CHECK(glGetError() == GL_NO_ERROR, "glInvalidateSubFramebuffer(GL_BACK_LEFT, GL_BACK_RIGHT)");
    glInvalidateNamedFramebufferData(0, 3, inv);
    CHECK(glGetError() == GL_NO_ERROR, "glInvalidateNamedFramebufferData(0, ...)");
    glDrawBuffer(GL_BACK);
    glReadBuffer(GL_BACK);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    drain_errors("dsa queries");
}

/* glGetError until GL_NO_ERROR (at most 4), printed after `what`. */
static void probe_errors(const char *what)
{
    printf("probe errors after %s:", what);
    for (int i = 0; i < 4; i++) {
        GLenum e = glGetError();
        printf(" 0x%x", e);
        if (e == GL_NO_ERROR) break;
    }
    printf("\n");
}

/* Queries the driver refuses leave the program's variable alone; a run of
 * bad calls leaves the errors GL keeps (Mesa: the first since the last
 * glGetError); GL_STEREO and GL_DOUBLEBUFFER come from the draw
 * framebuffer, false for a framebuffer object. */
static void probe_queries_and_errors(void)
{
    GLint max = get_int(GL_MAX_DRAW_BUFFERS);
    for (GLenum i = 0; i < 16; i++) {
        GLint v = -7;
        GLboolean b = 7;
        GLfloat f = -7.0f;
        GLdouble dv = -7.0;
        GLint64 v64 = -7;
        glGetIntegerv(GL_DRAW_BUFFER0 + i, &v);
        GLenum ev = glGetError();
        glGetBooleanv(GL_DRAW_BUFFER0 + i, &b);
        GLenum eb = glGetError();
        glGetFloatv(GL_DRAW_BUFFER0 + i, &f);
        GLenum ef = glGetError();
        glGetDoublev(GL_DRAW_BUFFER0 + i, &dv);
        GLenum ed = glGetError();
        glGetInteger64v(GL_DRAW_BUFFER0 + i, &v64);
        GLenum e64 = glGetError();
        printf("probe glGet*v(GL_DRAW_BUFFER%u) of %d: %d 0x%x %d 0x%x %g 0x%x %g 0x%x %lld 0x%x\n",
               i, max, v, ev, b, eb, f, ef, dv, ed, (long long)v64, e64);
    }
    GLint mask[4] = {-7, -7, -7, -7};
    glGetIntegeri_v(GL_COLOR_WRITEMASK, 99, mask);
    printf("probe glGetIntegeri_v(GL_COLOR_WRITEMASK, 99): %d 0x%x\n", mask[0], glGetError());

    glDrawBuffer(GL_COLOR_ATTACHMENT0);
    glViewport(0, 0, -1, -1);
    glEnable(0x1234);
    probe_errors("glDrawBuffer(GL_COLOR_ATTACHMENT0), glViewport(-1), glEnable(0x1234)");
    glViewport(0, 0, -1, -1);
    glDrawBuffer(0x1234);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    probe_errors("glViewport(-1), glDrawBuffer(0x1234), glReadBuffer(GL_COLOR_ATTACHMENT0)");
    glDrawBuffer(0x1234);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glDrawBuffers(1, (const GLenum[]){GL_BACK});
    probe_errors("glDrawBuffer(0x1234), glReadBuffer(GL_COLOR_ATTACHMENT0), glDrawBuffers({GL_BACK})");
    GLint v = -7;
    glEnable(0x1234);
    glGetIntegerv(GL_DRAW_BUFFER9, &v);
    glDrawBuffer(0x1234);
    probe_errors("glEnable(0x1234), glGetIntegerv(GL_DRAW_BUFFER9), glDrawBuffer(0x1234)");
    glGetIntegerv(GL_DRAW_BUFFER9, &v);
    glViewport(0, 0, -1, -1);
    glGetIntegerv(GL_STEREO, &v);
    glGetIntegerv(GL_DRAW_BUFFER, &v);
    probe_errors("glGetIntegerv(GL_DRAW_BUFFER9), glViewport(-1), glGetIntegerv(GL_STEREO)");
    glDrawBuffer(GL_BACK);
    glReadBuffer(GL_BACK);

    /* Program binaries: the driver's formats and errors. */
    GLint nformats = get_int(GL_NUM_PROGRAM_BINARY_FORMATS);
    printf("probe GL_NUM_PROGRAM_BINARY_FORMATS: %d\n", nformats);
    GLuint unlinked = glCreateProgram();
    GLint blen = -7;
    glGetProgramiv(unlinked, GL_PROGRAM_BINARY_LENGTH, &blen);
    printf("probe GL_PROGRAM_BINARY_LENGTH unlinked: %d 0x%x\n", blen, glGetError());
    unsigned char bbuf[64];
    GLsizei gotlen = -7;
    GLenum bfmt = 7;
    glGetProgramBinary(unlinked, sizeof bbuf, &gotlen, &bfmt, bbuf);
    printf("probe glGetProgramBinary unlinked: %d 0x%x 0x%x\n", gotlen, bfmt, glGetError());
    GLuint linked = program(VS33, FS_TINT);
    glGetProgramBinary(linked, 4, &gotlen, &bfmt, bbuf);
    printf("probe glGetProgramBinary bufSize 4: %d 0x%x 0x%x\n", gotlen, bfmt, glGetError());
    glGetProgramBinary(linked, -1, &gotlen, &bfmt, bbuf);
    printf("probe glGetProgramBinary bufSize -1: %d 0x%x 0x%x\n", gotlen, bfmt, glGetError());
    glGetProgramBinary(0x7777, sizeof bbuf, &gotlen, &bfmt, bbuf);
    printf("probe glGetProgramBinary(0x7777): %d 0x%x 0x%x\n", gotlen, bfmt, glGetError());
    memset(bbuf, 0x5a, sizeof bbuf);
    GLint lstatus = -7;
    glProgramBinary(unlinked, GL_PROGRAM_BINARY_FORMAT_MESA, bbuf, sizeof bbuf);
    glGetProgramiv(unlinked, GL_LINK_STATUS, &lstatus);
    printf("probe glProgramBinary(garbage): %d 0x%x\n", lstatus, glGetError());
    glProgramBinary(unlinked, 0x1234, bbuf, sizeof bbuf);
    glGetProgramiv(unlinked, GL_LINK_STATUS, &lstatus);
    printf("probe glProgramBinary(format 0x1234): %d 0x%x\n", lstatus, glGetError());
    glProgramBinary(unlinked, GL_PROGRAM_BINARY_FORMAT_MESA, bbuf, -1);
    printf("probe glProgramBinary(length -1): 0x%x\n", glGetError());
    glProgramBinary(0x7777, GL_PROGRAM_BINARY_FORMAT_MESA, bbuf, sizeof bbuf);
    printf("probe glProgramBinary(0x7777): 0x%x\n", glGetError());
    glDeleteProgram(unlinked);
    glDeleteProgram(linked);

    GLuint fbo = 0;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    GLboolean st = 7, db = 7;
    glGetBooleanv(GL_STEREO, &st);
    glGetBooleanv(GL_DOUBLEBUFFER, &db);
    printf("probe GL_STEREO GL_DOUBLEBUFFER with a framebuffer object drawn: %d %d %d %d 0x%x\n",
           st, db, get_int(GL_STEREO), get_int(GL_DOUBLEBUFFER), glGetError());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
}

/* The answers GL gives about a default framebuffer that do not depend on
 * stereo: printed, for the test to compare with the driver's on a mono
 * configuration. */
static void probes(void)
{
    static const GLenum mono_names[] = {GL_NONE, GL_FRONT_LEFT, GL_BACK_LEFT, GL_FRONT,
                                        GL_BACK, GL_LEFT, GL_FRONT_AND_BACK, 0x1234,
                                        GL_TEXTURE_2D, 0x0409 /* AUX0 */, GL_COLOR_ATTACHMENT0};
    for (unsigned i = 0; i < sizeof mono_names / sizeof mono_names[0]; i++) {
        GLenum n = mono_names[i];
        glNamedFramebufferDrawBuffer(0, n);
        printf("probe glNamedFramebufferDrawBuffer(0, 0x%x): 0x%x 0x%x\n", n, glGetError(),
               get_int(GL_DRAW_BUFFER));
        glNamedFramebufferDrawBuffer(0, GL_BACK);
        glNamedFramebufferReadBuffer(0, n);
        printf("probe glNamedFramebufferReadBuffer(0, 0x%x): 0x%x 0x%x\n", n, glGetError(),
               get_int(GL_READ_BUFFER));
        glNamedFramebufferReadBuffer(0, GL_BACK);
        glNamedFramebufferDrawBuffers(0, 1, &n);
        printf("probe glNamedFramebufferDrawBuffers(0, {0x%x}): 0x%x 0x%x\n", n, glGetError(),
               get_int(GL_DRAW_BUFFER0));
        glNamedFramebufferDrawBuffer(0, GL_BACK);
    }
    GLenum two[2] = {GL_BACK_LEFT, GL_BACK_LEFT};
    glNamedFramebufferDrawBuffers(0, 2, two);
    printf("probe glNamedFramebufferDrawBuffers(0, {BL, BL}): 0x%x\n", glGetError());
    glNamedFramebufferDrawBuffers(0, -1, two);
    printf("probe glNamedFramebufferDrawBuffers(0, -1): 0x%x\n", glGetError());
    glNamedFramebufferDrawBuffer(0, GL_BACK);
    static const GLenum atts[] = {GL_COLOR, GL_DEPTH, GL_STENCIL, GL_FRONT_LEFT, GL_BACK_LEFT,
                                  GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT, 0x1234};
    for (unsigned i = 0; i < sizeof atts / sizeof atts[0]; i++) {
        glInvalidateFramebuffer(GL_FRAMEBUFFER, 1, &atts[i]);
        printf("probe glInvalidateFramebuffer(0x%x): 0x%x\n", atts[i], glGetError());
        glInvalidateSubFramebuffer(GL_READ_FRAMEBUFFER, 1, &atts[i], 0, 0, 2, 2);
        printf("probe glInvalidateSubFramebuffer(0x%x): 0x%x\n", atts[i], glGetError());
        glInvalidateNamedFramebufferData(0, 1, &atts[i]);
        printf("probe glInvalidateNamedFramebufferData(0, 0x%x): 0x%x\n", atts[i], glGetError());
    }
    glInvalidateSubFramebuffer(GL_FRAMEBUFFER, 1, atts, 0, 0, -1, 2);
    printf("probe glInvalidateSubFramebuffer(width -1): 0x%x\n", glGetError());
    static const GLenum pnames[] = {GL_DOUBLEBUFFER,
                                    GL_SAMPLES,
                                    GL_SAMPLE_BUFFERS,
                                    GL_IMPLEMENTATION_COLOR_READ_FORMAT,
                                    GL_IMPLEMENTATION_COLOR_READ_TYPE,
                                    GL_FRAMEBUFFER_DEFAULT_WIDTH,
                                    0x1234};
    for (unsigned i = 0; i < sizeof pnames / sizeof pnames[0]; i++) {
        GLint v = -7;
        glGetNamedFramebufferParameteriv(0, pnames[i], &v);
        printf("probe glGetNamedFramebufferParameteriv(0, 0x%x): %d 0x%x\n", pnames[i], v,
               glGetError());
        v = -7;
        glGetFramebufferParameteriv(GL_DRAW_FRAMEBUFFER, pnames[i], &v);
        printf("probe glGetFramebufferParameteriv(0x%x): %d 0x%x\n", pnames[i], v, glGetError());
    }
    static const GLenum fb_atts[] = {GL_FRONT_LEFT, GL_BACK_LEFT, GL_DEPTH, GL_STENCIL,
                                     GL_COLOR_ATTACHMENT0, GL_FRONT, GL_BACK, 0x1234};
    static const GLenum att_pnames[] = {GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
                                        GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME,
                                        GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE,
                                        GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE,
                                        GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE,
                                        GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE,
                                        GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE,
                                        GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING};
    for (unsigned i = 0; i < sizeof fb_atts / sizeof fb_atts[0]; i++) {
        for (unsigned j = 0; j < sizeof att_pnames / sizeof att_pnames[0]; j++) {
            GLint v = -7;
            glGetNamedFramebufferAttachmentParameteriv(0, fb_atts[i], att_pnames[j], &v);
            printf("probe glGetNamedFramebufferAttachmentParameteriv(0, 0x%x, 0x%x): %d 0x%x\n",
                   fb_atts[i], att_pnames[j], v, glGetError());
        }
    }
    static const GLenum targets[] = {GL_FRAMEBUFFER, GL_DRAW_FRAMEBUFFER, GL_READ_FRAMEBUFFER,
                                     0x1234};
    for (unsigned i = 0; i < sizeof targets / sizeof targets[0]; i++) {
        GLenum st = glCheckNamedFramebufferStatus(0, targets[i]);
        printf("probe glCheckNamedFramebufferStatus(0, 0x%x): 0x%x 0x%x\n", targets[i], st,
               glGetError());
    }
    const GLfloat c[4] = {0, 0, 0, 1};
    static const GLint drawbuffers[] = {-1, 0, 1, 7, 8};
    for (unsigned i = 0; i < sizeof drawbuffers / sizeof drawbuffers[0]; i++) {
        glClearBufferfv(GL_COLOR, drawbuffers[i], c);
        printf("probe glClearBufferfv(GL_COLOR, %d): 0x%x\n", drawbuffers[i], glGetError());
        glClearNamedFramebufferfv(0, GL_COLOR, drawbuffers[i], c);
        printf("probe glClearNamedFramebufferfv(0, GL_COLOR, %d): 0x%x\n", drawbuffers[i],
               glGetError());
    }
    glClearNamedFramebufferfi(0, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    printf("probe glClearNamedFramebufferfi(0): 0x%x\n", glGetError());
    glClearNamedFramebufferfi(0, GL_COLOR, 0, 1.0f, 0);
    printf("probe glClearNamedFramebufferfi(0, GL_COLOR): 0x%x\n", glGetError());
    unsigned char px[4];
    glReadnPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, 2, px);
    printf("probe glReadnPixels(bufSize 2): 0x%x\n", glGetError());
    glBlitNamedFramebuffer(0, 0, 0, 0, 4, 4, 0, 0, 4, 4, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    printf("probe glBlitNamedFramebuffer(0, 0): 0x%x\n", glGetError());
    glBlitNamedFramebuffer(0, 0, 0, 0, 4, 4, 0, 0, 2, 2, GL_DEPTH_BUFFER_BIT, GL_LINEAR);
    printf("probe glBlitNamedFramebuffer(0, 0, depth, linear): 0x%x\n", glGetError());
    glDrawBuffer(GL_BACK);
    glReadBuffer(GL_BACK);
    probe_queries_and_errors();
}

typedef GLXContext (*CreateContextAttribs)(Display *, GLXFBConfig, GLXContext, Bool,
                                           const int *);

struct window {
    Window win;
    Colormap cmap;
    GLXContext ctx;
    XVisualInfo *vi;
};

/* A window of a double-buffered configuration (stereo or not) and a
 * context of the given version (profile mask 0: glXCreateContext). */
static int open_window(Display *d, int stereo, int major, int minor, int profile,
                       struct window *w)
{
    int attrs[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True, GLX_STEREO, stereo,
                   GLX_RED_SIZE, 8, GLX_DEPTH_SIZE, 24, GLX_STENCIL_SIZE, 8, None};
    int n = 0;
    GLXFBConfig *configs = glXChooseFBConfig(d, DefaultScreen(d), attrs, &n);
    if (configs == NULL || n == 0) {
        fprintf(stderr, "no %s configuration\n", stereo ? "stereo" : "mono");
        return 0;
    }
    w->vi = glXGetVisualFromFBConfig(d, configs[0]);
    Window root = RootWindow(d, w->vi->screen);
    XSetWindowAttributes wa = {0};
    w->cmap = wa.colormap = XCreateColormap(d, root, w->vi->visual, AllocNone);
    w->win = XCreateWindow(d, root, 0, 0, W, H, 0, w->vi->depth, InputOutput, w->vi->visual,
                           CWColormap, &wa);
    XMapWindow(d, w->win);
    XSync(d, False);
    if (profile == 0) {
        w->ctx = glXCreateNewContext(d, configs[0], GLX_RGBA_TYPE, NULL, True);
    } else {
        CreateContextAttribs create = (CreateContextAttribs)glXGetProcAddressARB(
            (const GLubyte *)"glXCreateContextAttribsARB");
        const int ctx_attrs[] = {0x2091, major, 0x2092, minor, 0x9126, profile, None};
        w->ctx = create ? create(d, configs[0], NULL, True, ctx_attrs) : NULL;
    }
    XFree(configs);
    if (w->ctx == NULL || !glXMakeContextCurrent(d, w->win, w->win, w->ctx)) {
        fprintf(stderr, "no GL %d.%d context\n", major, minor);
        return 0;
    }
    glViewport(0, 0, W, H);
    return 1;
}

/* The double-buffered mono configuration open_window(d, 0, …) picks. */
static GLXFBConfig mono_fbconfig(Display *d)
{
    int attrs[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True, GLX_STEREO, False,
                   GLX_RED_SIZE, 8, GLX_DEPTH_SIZE, 24, GLX_STENCIL_SIZE, 8, None};
    int n = 0;
    GLXFBConfig *configs = glXChooseFBConfig(d, DefaultScreen(d), attrs, &n);
    GLXFBConfig c = configs != NULL && n > 0 ? configs[0] : NULL;
    if (configs) XFree(configs);
    return c;
}

static void close_window(Display *d, struct window *w)
{
    glXMakeContextCurrent(d, None, None, NULL);
    glXDestroyContext(d, w->ctx);
    XDestroyWindow(d, w->win);
    XFreeColormap(d, w->cmap);
    XFree(w->vi);
}

/* GL_OES_get_program_binary's names, which libGL exports too. */
typedef void (*GetProgramBinaryOES)(GLuint, GLsizei, GLsizei *, GLenum *, void *);
typedef void (*ProgramBinaryOES)(GLuint, GLenum, const void *, GLint);

/* A program binary: its format and bytes. */
struct binary {
    GLenum format;
    GLint length;
    unsigned char *bytes;
};

/* glGetProgramBinary of `p` (through the OES name when `oes`), checking
 * GL_PROGRAM_BINARY_LENGTH and the format against the driver's list. */
static struct binary get_binary(GLuint p, int oes)
{
    struct binary b = {0, 0, NULL};
    GLint len = 0;
    glGetProgramiv(p, GL_PROGRAM_BINARY_LENGTH, &len);
    CHECK(len > 0, "GL_PROGRAM_BINARY_LENGTH %d", len);
    b.bytes = calloc((size_t)len + 1, 1);
    if (oes) {
        GetProgramBinaryOES get = (GetProgramBinaryOES)glXGetProcAddressARB(
            (const GLubyte *)"glGetProgramBinaryOES");
        CHECK(get != NULL, "glGetProgramBinaryOES");
        if (get) get(p, len, &b.length, &b.format, b.bytes);
    } else {
        glGetProgramBinary(p, len, &b.length, &b.format, b.bytes);
    }
    CHECK(b.length == len, "glGetProgramBinary wrote %d bytes of %d", b.length, len);
    GLint n = get_int(GL_NUM_PROGRAM_BINARY_FORMATS), found = 0;
    GLint formats[8] = {0};
    if (n > 0 && n <= 8) glGetIntegerv(GL_PROGRAM_BINARY_FORMATS, formats);
    for (int i = 0; i < n && i < 8; i++) found |= (GLenum)formats[i] == b.format;
    CHECK(found, "the binary's format 0x%x is one GL_PROGRAM_BINARY_FORMATS lists", b.format);
    CHECK(glGetError() == GL_NO_ERROR, "glGetProgramBinary");
    return b;
}

/* A new program loaded from `b` (length `length`, through the OES name
 * when `oes`); its GL_LINK_STATUS in *linked. */
static GLuint load_binary(const struct binary *b, GLint length, int oes, GLint *linked)
{
    GLuint p = glCreateProgram();
    if (oes) {
        ProgramBinaryOES load =
            (ProgramBinaryOES)glXGetProcAddressARB((const GLubyte *)"glProgramBinaryOES");
        CHECK(load != NULL, "glProgramBinaryOES");
        if (load) load(p, b->format, b->bytes, length);
    } else {
        glProgramBinary(p, b->format, b->bytes, length);
    }
    *linked = -7;
    glGetProgramiv(p, GL_LINK_STATUS, linked);
    CHECK(glGetError() == GL_NO_ERROR, "glProgramBinary raises no GL error");
    return p;
}

/* Draws the quad with `p` (FS_TINT's interface) in `rgb` under GL_BACK:
 * both back buffers get it. */
static void expect_both_backs(GLuint p, const char *what, float r, float g, float b)
{
    clear_all();
    glDrawBuffer(GL_BACK);
    glUseProgram(p);
    glUniform4f(glGetUniformLocation(p, "tint"), r, g, b, 1.0f);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glUseProgram(0);
    expect_buffers(what, M_BACK, (int)(r * 255), (int)(g * 255), (int)(b * 255));
}

static const char *FS_LOC1 = "#version 330 core\n"
                             "layout(location = 1) out vec4 other;\n"
                             "void main() { other = vec4(1.0); }\n";

/* Program binaries in the stereo context (current on w->win): one made
 * by a mono context (as by a run without the layer) is refused when its
 * output 0 needs the copies, kept when it needs none; one made here
 * round-trips through glGetProgramBinary / glProgramBinary and their OES
 * names with the copies; the mono context loads it too. */
static void program_binaries(Display *d, struct window *w, GLXFBConfig mono_config)
{
    CreateContextAttribs create = (CreateContextAttribs)glXGetProcAddressARB(
        (const GLubyte *)"glXCreateContextAttribsARB");
    const int ctx_attrs[] = {0x2091, 4, 0x2092, 5, 0x9126, 1, None};
    GLXContext mono = create(d, mono_config, NULL, True, ctx_attrs);
    CHECK(mono != NULL, "a mono 4.5 context");
    if (mono == NULL) return;
    /* Binaries made without the layer's copies. */
    CHECK(glXMakeContextCurrent(d, w->win, w->win, mono), "the mono context");
    GLuint pm = program(VS33, FS_TINT), pm1 = program(VS33, FS_LOC1);
    struct binary foreign = get_binary(pm, 0), foreign_loc1 = get_binary(pm1, 0);
    glDeleteProgram(pm);
    glDeleteProgram(pm1);
    CHECK(glXMakeContextCurrent(d, w->win, w->win, w->ctx), "the stereo context again");

    GLint linked = -7;
    GLuint p = load_binary(&foreign, foreign.length, 0, &linked);
    if (linked) {
        expect_both_backs(p, "a program loaded from a binary made without the copies", 1, 0, 1);
    }
    CHECK(!linked, "a binary without the copies of output 0 is refused (GL_LINK_STATUS %d)",
          linked);
    glDeleteProgram(p);
    p = load_binary(&foreign, foreign.length, 1, &linked);
    CHECK(!linked, "glProgramBinaryOES refuses it too (GL_LINK_STATUS %d)", linked);
    glDeleteProgram(p);
    p = load_binary(&foreign_loc1, foreign_loc1.length, 0, &linked);
    CHECK(linked == GL_TRUE, "a binary whose output 0 needs no copies loads (%d)", linked);
    glDeleteProgram(p);

    /* Made here: the binary carries the copies. */
    GLuint src = program(VS33, FS_TINT);
    expect_both_backs(src, "the program linked from source", 0, 1, 1);
    struct binary own = get_binary(src, 0), own_oes = get_binary(src, 1);
    CHECK(own.format == foreign.format, "the driver's format (0x%x, 0x%x)", own.format,
          foreign.format);
    CHECK(own_oes.length == own.length && memcmp(own.bytes, own_oes.bytes, (size_t)own.length) == 0,
          "glGetProgramBinaryOES gives the same binary");
    p = load_binary(&own, own.length, 0, &linked);
    CHECK(linked == GL_TRUE, "its binary loads (GL_LINK_STATUS %d)", linked);
    if (linked) expect_both_backs(p, "a program loaded from its own binary", 1, 1, 0);
    glDeleteProgram(p);
    p = load_binary(&own, own.length, 1, &linked);
    CHECK(linked == GL_TRUE, "and through glProgramBinaryOES (%d)", linked);
    if (linked) expect_both_backs(p, "loaded through glProgramBinaryOES", 0, 0, 1);
    /* A loaded program's binary loads again, with the copies. */
    struct binary again = get_binary(p, 0);
    glDeleteProgram(p);
    p = load_binary(&again, again.length, 0, &linked);
    CHECK(linked == GL_TRUE, "a loaded program's binary loads (%d)", linked);
    if (linked) expect_both_backs(p, "loaded from a loaded program's binary", 1, 0, 0);
    glDeleteProgram(p);
    p = load_binary(&own, own.length - 1, 0, &linked);
    CHECK(!linked, "a truncated binary fails to load (%d)", linked);
    glDeleteProgram(p);
    glDeleteProgram(src);

    /* The mono context loads it (its copies write no buffer there). */
    CHECK(glXMakeContextCurrent(d, w->win, w->win, mono), "the mono context");
    p = load_binary(&own, own.length, 0, &linked);
    CHECK(linked == GL_TRUE, "a mono context loads a binary made in the stereo one (%d)", linked);
    glDeleteProgram(p);
    CHECK(glXMakeContextCurrent(d, w->win, w->win, w->ctx), "the stereo context again");
    glXDestroyContext(d, mono);
    free(foreign.bytes);
    free(foreign_loc1.bytes);
    free(own.bytes);
    free(own_oes.bytes);
    free(again.bytes);
    drain_errors("program binaries");
}

/* Immediate mode in a compatibility context, with a GLSL 1.30 `out`. */
static void immediate_mode(void)
{
    static const char *vs = "#version 130\nvoid main() { gl_Position = ftransform(); }\n";
    static const char *fs = "#version 130\nout vec4 c;\nvoid main() { c = vec4(0.0, 1.0, 1.0, 1.0); }\n";
    GLuint p = program(vs, fs);
    glUseProgram(p);
    clear_all();
    glDrawBuffer(GL_BACK);
    glBegin(GL_QUADS);
    glVertex2f(-1, -1);
    glVertex2f(1, -1);
    glVertex2f(1, 1);
    glVertex2f(-1, 1);
    glEnd();
    expect_buffers("glBegin/glEnd with an `out` shader under GL_BACK", M_BACK, 0, 255, 255);
    glUseProgram(0);
    glDeleteProgram(p);
    /* gl_FragData[0]: unlike gl_FragColor, GL writes it to draw buffer 0
     * only, which under GL_BACK on a stereo framebuffer is both back
     * buffers. */
    static const char *fs_data =
        "#version 130\nvoid main() { gl_FragData[0] = vec4(1.0, 0.0, 1.0, 1.0); }\n";
    p = program(vs, fs_data);
    glUseProgram(p);
    clear_all();
    glDrawBuffer(GL_BACK);
    glRectf(-1, -1, 1, 1);
    expect_buffers("gl_FragData[0] under GL_BACK", M_BACK, 255, 0, 255);
    glUseProgram(0);
    glDeleteProgram(p);
    /* Fixed function too. */
    clear_all();
    glDrawBuffer(GL_BACK);
    glColor3f(1, 0, 0);
    glRectf(-1, -1, 1, 1);
    expect_buffers("fixed function under GL_BACK", M_BACK, 255, 0, 0);
    drain_errors("immediate mode");
}

int main(int argc, char **argv)
{
    const char *mode = argc > 1 ? argv[1] : "";
    int core33 = strcmp(mode, "core33") == 0, core45 = strcmp(mode, "core45") == 0;
    int compat = strcmp(mode, "compat") == 0, mono45 = strcmp(mode, "mono45") == 0;
    int kept = strcmp(mode, "kept") == 0, binary = strcmp(mode, "binary") == 0;
    core33 |= kept;
    if (!core33 && !core45 && !compat && !mono45 && !binary) {
        fprintf(stderr, "usage: glx_core_stereo core33|core45|compat|mono45|kept|binary\n");
        return 1;
    }
    Display *d = XOpenDisplay(NULL);
    if (d == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    struct window w;
    int major = core33 ? 3 : 4, minor = core33 ? 3 : 5;
    if (!open_window(d, !mono45, major, minor, compat ? 0 : 1, &w)) return 2;
    if (!mono45) {
        GLboolean st = GL_FALSE;
        glGetBooleanv(GL_STEREO, &st);
        CHECK(st == GL_TRUE, "GL_STEREO");
        if (!compat) geometry();
    }
    if (binary) {
        GLXFBConfig mono_config = mono_fbconfig(d);
        if (mono_config == NULL) return 2;
        program_binaries(d, &w, mono_config);
    } else if (kept) {
        kept_program();
    } else if (core33 || core45) {
        user_outputs(core45 ? 11 : 9);
        side_effects_once();
        draw_buffers_routing();
        clear_buffer();
    }
    if (core45) {
        atomic_counter_once();
        component_outputs();
        feedback_and_separable();
        dsa();
    }
    if (compat) immediate_mode();
    if (core45 || mono45) probes();
    if (core33 || core45) {
        /* One swap shows what GL_BACK drew in both eyes. */
        glDrawBuffer(GL_BACK);
        const GLfloat blue[4] = {0, 0, 1, 1};
        glClearBufferfv(GL_COLOR, 0, blue);
        glXSwapBuffers(d, w.win);
        CHECK(buffer_is(FL, 0, 0, 255) && buffer_is(FR, 0, 0, 255), "both fronts after the swap");
    }
    drain_errors("end");
    close_window(d, &w);
    XCloseDisplay(d);
    return SUMMARY();
}

/*
 * The per-eye frame every client of tests/clients.rs draws, and the report
 * it prints, for programs that find their GL functions the way their
 * toolkit does (glfwGetProcAddress, SDL_GL_GetProcAddress,
 * QOpenGLContext::getProcAddress): nothing here links or calls libGL by name.
 *
 * The frame (160x120 or any size; positions are in normalised coordinates):
 *   left eye  (GL_BACK_LEFT):  cleared red,  a green square  (-0.75,0.25)-(-0.25,0.75)
 *   right eye (GL_BACK_RIGHT): cleared blue, a yellow square (0.25,-0.75)-(0.75,-0.25)
 * so a swapped, duplicated or missing eye changes the colours the test reads.
 * The squares are drawn with glRectf (compatibility contexts) or with a
 * GLSL 1.50 program and a vertex array (core contexts).
 *
 * A mono program draws the left eye's picture into GL_BACK (eyes_draw_mono)
 * and reports GL_BACK and GL_FRONT.
 *
 * The report, one line each, on stdout:
 *   pixel BUFFER X Y R G B     glReadPixels of BUFFER at (X, Y), rows bottom up,
 *                              at the centre, the left square's and the right
 *                              square's centre; BACK_* before the swap,
 *                              FRONT_* after it
 * Reads are made with glReadBuffer(BUFFER); GL errors are reported by the
 * caller (eyes_error()).
 */
#ifndef GLSTEREO_TESTS_EYES_H
#define GLSTEREO_TESTS_EYES_H

#include <stdio.h>
#include <string.h>

#include <GL/gl.h>

#ifndef GL_ARRAY_BUFFER
#define GL_ARRAY_BUFFER 0x8892
#define GL_STATIC_DRAW 0x88E4
#define GL_FRAGMENT_SHADER 0x8B30
#define GL_VERTEX_SHADER 0x8B31
#define GL_COMPILE_STATUS 0x8B81
#define GL_LINK_STATUS 0x8B82
#endif

/* A function as the toolkit's look-up returns it. */
typedef void (*eyes_proc)(void);
/* The toolkit's look-up: glfwGetProcAddress and the like. */
typedef eyes_proc (*eyes_loader)(const char *name);

static struct {
    void(APIENTRY *ClearColor)(GLfloat, GLfloat, GLfloat, GLfloat);
    void(APIENTRY *Clear)(GLbitfield);
    void(APIENTRY *DrawBuffer)(GLenum);
    void(APIENTRY *ReadBuffer)(GLenum);
    void(APIENTRY *ReadPixels)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
    void(APIENTRY *PixelStorei)(GLenum, GLint);
    void(APIENTRY *GetBooleanv)(GLenum, GLboolean *);
    void(APIENTRY *GetIntegerv)(GLenum, GLint *);
    GLenum(APIENTRY *GetError)(void);
    void(APIENTRY *Viewport)(GLint, GLint, GLsizei, GLsizei);
    void(APIENTRY *Color3f)(GLfloat, GLfloat, GLfloat);
    void(APIENTRY *Rectf)(GLfloat, GLfloat, GLfloat, GLfloat);
    GLuint(APIENTRY *CreateShader)(GLenum);
    void(APIENTRY *ShaderSource)(GLuint, GLsizei, const char *const *, const GLint *);
    void(APIENTRY *CompileShader)(GLuint);
    void(APIENTRY *GetShaderiv)(GLuint, GLenum, GLint *);
    GLuint(APIENTRY *CreateProgram)(void);
    void(APIENTRY *AttachShader)(GLuint, GLuint);
    void(APIENTRY *BindAttribLocation)(GLuint, GLuint, const char *);
    void(APIENTRY *LinkProgram)(GLuint);
    void(APIENTRY *GetProgramiv)(GLuint, GLenum, GLint *);
    void(APIENTRY *UseProgram)(GLuint);
    GLint(APIENTRY *GetUniformLocation)(GLuint, const char *);
    void(APIENTRY *Uniform4f)(GLint, GLfloat, GLfloat, GLfloat, GLfloat);
    void(APIENTRY *GenVertexArrays)(GLsizei, GLuint *);
    void(APIENTRY *BindVertexArray)(GLuint);
    void(APIENTRY *GenBuffers)(GLsizei, GLuint *);
    void(APIENTRY *BindBuffer)(GLenum, GLuint);
    void(APIENTRY *BufferData)(GLenum, ptrdiff_t, const void *, GLenum);
    void(APIENTRY *VertexAttribPointer)(GLuint, GLint, GLenum, GLboolean, GLsizei, const void *);
    void(APIENTRY *EnableVertexAttribArray)(GLuint);
    void(APIENTRY *DrawArrays)(GLenum, GLint, GLsizei);
} eyes_gl;

/* Core-profile drawing state. */
static GLuint eyes_program;
static GLint eyes_color;
static int eyes_core;

/* Looks `name` up into `slot`; says which one is missing. */
static int eyes_lookup(eyes_loader get, const char *name, void *slot)
{
    eyes_proc p = get(name);
    if (p == NULL) {
        fprintf(stderr, "eyes: %s not found\n", name);
        return 0;
    }
    memcpy(slot, &p, sizeof p);
    return 1;
}

#define EYES_GET(name) ok &= eyes_lookup(get, "gl" #name, &eyes_gl.name)

/* Loads the GL functions with the toolkit's look-up; `core` selects the
 * shader path (for core-profile contexts). Returns 0 when one is missing. */
static int eyes_load(eyes_loader get, int core)
{
    int ok = 1;
    eyes_core = core;
    EYES_GET(ClearColor);
    EYES_GET(Clear);
    EYES_GET(DrawBuffer);
    EYES_GET(ReadBuffer);
    EYES_GET(ReadPixels);
    EYES_GET(PixelStorei);
    EYES_GET(GetBooleanv);
    EYES_GET(GetIntegerv);
    EYES_GET(GetError);
    EYES_GET(Viewport);
    if (!core) {
        EYES_GET(Color3f);
        EYES_GET(Rectf);
        return ok;
    }
    EYES_GET(CreateShader);
    EYES_GET(ShaderSource);
    EYES_GET(CompileShader);
    EYES_GET(GetShaderiv);
    EYES_GET(CreateProgram);
    EYES_GET(AttachShader);
    EYES_GET(BindAttribLocation);
    EYES_GET(LinkProgram);
    EYES_GET(GetProgramiv);
    EYES_GET(UseProgram);
    EYES_GET(GetUniformLocation);
    EYES_GET(Uniform4f);
    EYES_GET(GenVertexArrays);
    EYES_GET(BindVertexArray);
    EYES_GET(GenBuffers);
    EYES_GET(BindBuffer);
    EYES_GET(BufferData);
    EYES_GET(VertexAttribPointer);
    EYES_GET(EnableVertexAttribArray);
    EYES_GET(DrawArrays);
    return ok;
}

static GLuint eyes_shader(GLenum kind, const char *source)
{
    GLuint s = eyes_gl.CreateShader(kind);
    GLint ok = 0;
    eyes_gl.ShaderSource(s, 1, &source, NULL);
    eyes_gl.CompileShader(s);
    eyes_gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        fprintf(stderr, "eyes: a shader does not compile\n");
    }
    return s;
}

/* Core profile: a program drawing a uniform colour and a vertex array
 * holding both squares as triangle strips (4 vertices each). */
static int eyes_core_setup(void)
{
    static const GLfloat squares[] = {
        -0.75f, 0.25f, -0.25f, 0.25f, -0.75f, 0.75f,  -0.25f, 0.75f, /* left */
        0.25f, -0.75f, 0.75f, -0.75f, 0.25f,  -0.25f, 0.75f,  -0.25f /* right */
    };
    GLuint vao = 0, vbo = 0;
    GLint linked = 0;
    eyes_program = eyes_gl.CreateProgram();
    eyes_gl.AttachShader(eyes_program,
                         eyes_shader(GL_VERTEX_SHADER, "#version 150\n"
                                                       "in vec2 p;\n"
                                                       "void main() { gl_Position = vec4(p, 0.0, 1.0); }\n"));
    eyes_gl.AttachShader(eyes_program, eyes_shader(GL_FRAGMENT_SHADER, "#version 150\n"
                                                                       "uniform vec4 c;\n"
                                                                       "out vec4 o;\n"
                                                                       "void main() { o = c; }\n"));
    eyes_gl.BindAttribLocation(eyes_program, 0, "p");
    eyes_gl.LinkProgram(eyes_program);
    eyes_gl.GetProgramiv(eyes_program, GL_LINK_STATUS, &linked);
    if (!linked) {
        fprintf(stderr, "eyes: the program does not link\n");
        return 0;
    }
    eyes_gl.UseProgram(eyes_program);
    eyes_color = eyes_gl.GetUniformLocation(eyes_program, "c");
    eyes_gl.GenVertexArrays(1, &vao);
    eyes_gl.BindVertexArray(vao);
    eyes_gl.GenBuffers(1, &vbo);
    eyes_gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
    eyes_gl.BufferData(GL_ARRAY_BUFFER, (ptrdiff_t)sizeof squares, squares, GL_STATIC_DRAW);
    eyes_gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, NULL);
    eyes_gl.EnableVertexAttribArray(0);
    return 1;
}

/* One eye: clear `buffer` to the background, draw its square. */
static void eyes_one(GLenum buffer, const GLfloat bg[3], const GLfloat fg[3], int first, const GLfloat r[4])
{
    eyes_gl.DrawBuffer(buffer);
    eyes_gl.ClearColor(bg[0], bg[1], bg[2], 1.0f);
    eyes_gl.Clear(GL_COLOR_BUFFER_BIT);
    if (eyes_core) {
        eyes_gl.Uniform4f(eyes_color, fg[0], fg[1], fg[2], 1.0f);
        eyes_gl.DrawArrays(GL_TRIANGLE_STRIP, first, 4);
    } else {
        eyes_gl.Color3f(fg[0], fg[1], fg[2]);
        eyes_gl.Rectf(r[0], r[1], r[2], r[3]);
    }
}

/* Draws both eyes into the back buffers of a `width` x `height` window. */
static int eyes_draw(int width, int height)
{
    static const GLfloat red[3] = {1, 0, 0}, green[3] = {0, 1, 0};
    static const GLfloat blue[3] = {0, 0, 1}, yellow[3] = {1, 1, 0};
    static const GLfloat left_square[4] = {-0.75f, 0.25f, -0.25f, 0.75f};
    static const GLfloat right_square[4] = {0.25f, -0.75f, 0.75f, -0.25f};
    if (eyes_core && eyes_program == 0 && !eyes_core_setup()) {
        return 0;
    }
    eyes_gl.Viewport(0, 0, width, height);
    eyes_one(GL_BACK_LEFT, red, green, 0, left_square);
    eyes_one(GL_BACK_RIGHT, blue, yellow, 4, right_square);
    return 1;
}

/* Prints the three sample pixels of `buffer` ("BACK_LEFT" …). */
static void eyes_report(GLenum buffer, const char *name, int width, int height)
{
    const int points[3][2] = {{width / 2, height / 2}, {width / 4, height * 3 / 4}, {width * 3 / 4, height / 4}};
    int i;
    eyes_gl.ReadBuffer(buffer);
    eyes_gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    for (i = 0; i < 3; i++) {
        unsigned char px[4] = {0, 0, 0, 0};
        eyes_gl.ReadPixels(points[i][0], points[i][1], 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
        printf("pixel %s %d %d %u %u %u\n", name, points[i][0], points[i][1], px[0], px[1], px[2]);
    }
}

/* A mono frame: the left eye's picture in GL_BACK (inline: not every
 * program uses it). */
static inline int eyes_draw_mono(int width, int height)
{
    static const GLfloat red[3] = {1, 0, 0}, green[3] = {0, 1, 0};
    static const GLfloat left_square[4] = {-0.75f, 0.25f, -0.25f, 0.75f};
    if (eyes_core && eyes_program == 0 && !eyes_core_setup()) {
        return 0;
    }
    eyes_gl.Viewport(0, 0, width, height);
    eyes_one(GL_BACK, red, green, 0, left_square);
    return 1;
}

/* The back buffers' report (call before the swap). */
static void eyes_report_back(int width, int height)
{
    eyes_report(GL_BACK_LEFT, "BACK_LEFT", width, height);
    eyes_report(GL_BACK_RIGHT, "BACK_RIGHT", width, height);
}

/* The front buffers' report (call after the swap). */
static void eyes_report_front(int width, int height)
{
    eyes_report(GL_FRONT_LEFT, "FRONT_LEFT", width, height);
    eyes_report(GL_FRONT_RIGHT, "FRONT_RIGHT", width, height);
}

/* GL_STEREO as GL reports it. */
static int eyes_gl_stereo(void)
{
    GLboolean stereo = GL_FALSE;
    eyes_gl.GetBooleanv(GL_STEREO, &stereo);
    return stereo == GL_TRUE;
}

#endif

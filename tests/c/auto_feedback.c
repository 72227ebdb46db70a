/*
 * Transform feedback under automatic stereo (glstereo-run --auto, issue 23
 * item 4): a mono GL 3.3 core program captures gl_Position of one triangle
 * at clip w = 2 while drawing it into its window, counts the primitives
 * written with a query, draws a second triangle with GL_RASTERIZER_DISCARD
 * on (captured, not drawn), and prints what it captured:
 *
 *   written N
 *   v X Y Z W            (one line per captured vertex, 6 in all)
 *   error 0xE
 *
 * Under --auto the capture must be the mono program's: the same lines as
 * without the layer, while the window still shows the triangle in stereo.
 */
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <stdio.h>
#include <stdlib.h>

#include "x_window.h"

#define W 200
#define H 150

static GLuint shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        fprintf(stderr, "compile failed\n");
        exit(4);
    }
    return s;
}

int main(void)
{
    static const int core33[] = {GLX_CONTEXT_MAJOR_VERSION_ARB, 3, GLX_CONTEXT_MINOR_VERSION_ARB, 3,
                                 GLX_CONTEXT_PROFILE_MASK_ARB, GLX_CONTEXT_CORE_PROFILE_BIT_ARB,
                                 None};
    struct x_window x = open_x_window_config(core33, W, H);

    const char *vs = "#version 330 core\n"
                     "layout(location = 0) in vec4 pos;\n"
                     "void main() { gl_Position = pos; }\n";
    const char *fs = "#version 330 core\n"
                     "out vec4 c;\n"
                     "void main() { c = vec4(1.0, 1.0, 0.0, 1.0); }\n";
    GLuint prog = glCreateProgram();
    glAttachShader(prog, shader(GL_VERTEX_SHADER, vs));
    glAttachShader(prog, shader(GL_FRAGMENT_SHADER, fs));
    const char *varyings[] = {"gl_Position"};
    glTransformFeedbackVaryings(prog, 1, varyings, GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        fprintf(stderr, "link failed\n");
        return 4;
    }
    /* Two triangles in clip space, w = 2 (shifted by the rule). */
    static const GLfloat v[] = {
        -1.0f, -1.0f, 0.0f, 2.0f, 1.0f, -1.0f, 0.0f, 2.0f, 0.0f, 1.0f, 0.0f, 2.0f,
        -0.5f, -0.5f, 0.5f, 2.0f, 0.5f, -0.5f, 0.5f, 2.0f, 0.0f, 0.5f, 0.5f, 2.0f,
    };
    GLuint vao, vbo, tfb, query;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof v, v, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glEnableVertexAttribArray(0);
    /* Room for four triangles: a doubled capture would show. */
    glGenBuffers(1, &tfb);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, tfb);
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, 12 * 4 * sizeof(GLfloat), NULL, GL_STATIC_READ);
    glGenQueries(1, &query);

    glViewport(0, 0, W, H);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(prog);
    glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query);
    glBeginTransformFeedback(GL_TRIANGLES);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_RASTERIZER_DISCARD);
    glDrawArrays(GL_TRIANGLES, 3, 3);
    glDisable(GL_RASTERIZER_DISCARD);
    glEndTransformFeedback();
    glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    GLuint written = 0;
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, &written);
    printf("written %u\n", written);
    GLfloat out[12 * 4];
    glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, sizeof out, out);
    for (int i = 0; i < 6; i++)
        printf("v %g %g %g %g\n", out[4 * i], out[4 * i + 1], out[4 * i + 2], out[4 * i + 3]);
    glXSwapBuffers(x.display, x.window);
    GLenum err = glGetError();
    printf("error 0x%x\n", err);
    close_x_window(&x);
    return err == GL_NO_ERROR ? 0 : 3;
}

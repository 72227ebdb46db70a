/*
 * A mono core-profile program whose camera matrix lives in a uniform
 * buffer (std140 block), as modern engines and Blender keep theirs:
 * automatic stereo cannot read the projection from an upload, and its
 * automatic convergence must find the centre of interest all the same.
 *
 *   auto_ubo FRAMES    draws FRAMES frames, swapping each (run under
 *                      glstereo-run --auto --capture); prints "error 0x0"
 *   auto_ubo FRAMES gap  the same, but waits 1.2 s before the third frame
 *                      and draws it and the next ones twice as far away
 *                      (every distance doubled, the picture the same size):
 *                      a program that draws on events, its view changed
 *
 * The scene (glFrustum(-1, 1, -0.75, 0.75, 1, 1000) as a matrix in the
 * block): a green quad at w = 6 filling the middle half of the view, a
 * red one at w = 3 on its left, a blue one at w = 12 above it, on black.
 */
#define _POSIX_C_SOURCE 200809L
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "x_window.h"

#define W 200
#define H 150

static const char *VS =
    "#version 330 core\n"
    "layout(std140) uniform Camera { mat4 projection; };\n"
    "layout(location = 0) in vec3 pos;\n"
    "layout(location = 1) in vec3 col;\n"
    "out vec3 c;\n"
    "void main() { c = col; gl_Position = projection * vec4(pos, 1.0); }\n";
static const char *FS =
    "#version 330 core\n"
    "in vec3 c; out vec4 o;\n"
    "void main() { o = vec4(c, 1.0); }\n";

static GLuint shader(GLenum kind, const char *src)
{
    GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    return s;
}

static void quad(float x0, float y0, float x1, float y1, float z, float r, float g, float b)
{
    float v[] = {x0, y0, z, r, g, b, x1, y0, z, r, g, b, x1, y1, z, r, g, b, x0, y1, z, r, g, b};
    glBufferData(GL_ARRAY_BUFFER, sizeof v, v, GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
}

int main(int argc, char **argv)
{
    int frames = argc > 1 ? atoi(argv[1]) : 3;
    int gap = argc > 2 && !strcmp(argv[2], "gap");
    float k = 1.0f;
    static const int attrs[] = {GLX_CONTEXT_MAJOR_VERSION_ARB, 3, GLX_CONTEXT_MINOR_VERSION_ARB, 3,
                                GLX_CONTEXT_PROFILE_MASK_ARB, GLX_CONTEXT_CORE_PROFILE_BIT_ARB,
                                None};
    struct x_window x = open_x_window_config(attrs, W, H);
    GLuint p = glCreateProgram();
    glAttachShader(p, shader(GL_VERTEX_SHADER, VS));
    glAttachShader(p, shader(GL_FRAGMENT_SHADER, FS));
    glLinkProgram(p);
    glUseProgram(p);
    glUniformBlockBinding(p, glGetUniformBlockIndex(p, "Camera"), 0);
    /* glFrustum(-1, 1, -0.75, 0.75, 1, 1000), column-major. */
    float m[16] = {0};
    m[0] = 1.0f;
    m[5] = 1.0f / 0.75f;
    m[10] = -1001.0f / 999.0f;
    m[11] = -1.0f;
    m[14] = -2000.0f / 999.0f;
    GLuint ubo, vao, vbo;
    glGenBuffers(1, &ubo);
    glBindBuffer(GL_UNIFORM_BUFFER, ubo);
    glBufferData(GL_UNIFORM_BUFFER, sizeof m, m, GL_STATIC_DRAW);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), (void *)(3 * sizeof(float)));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glEnable(GL_DEPTH_TEST);
    for (int n = 0; n < frames; n++) {
        if (gap && n == 2) {
            struct timespec t = {1, 200000000};
            nanosleep(&t, NULL);
            k = 2.0f;
        }
        glViewport(0, 0, W, H);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        quad(-3.0f * k, -2.25f * k, 3.0f * k, 2.25f * k, -6.0f * k, 0.0f, 1.0f, 0.0f);
        quad(-2.6f * k, -0.4f * k, -1.8f * k, 0.4f * k, -3.0f * k, 1.0f, 0.0f, 0.0f);
        quad(-2.0f * k, 5.0f * k, 2.0f * k, 8.0f * k, -12.0f * k, 0.0f, 0.0f, 1.0f);
        glXSwapBuffers(x.display, x.window);
    }
    printf("error 0x%x\n", glGetError());
    return 0;
}

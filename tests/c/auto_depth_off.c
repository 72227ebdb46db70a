/*
 * Draws with the depth test off under `glstereo-run --auto=depth`: the
 * layer draws them with its own depth layer attached, so that their
 * pixels get a depth. The program must see none of it. One GLSL program
 * (gl_Position = u_matrix * gl_Vertex, u_matrix a frustum: w = -z), a
 * 200x150 window, and what it prints is what Mesa answers:
 *
 *   state T F M     after a draw with the test off: glIsEnabled(
 *                   GL_DEPTH_TEST), GL_DEPTH_FUNC, GL_DEPTH_WRITEMASK
 *   samples N       GL_SAMPLES_PASSED of a quad drawn with the test off
 *   depth X Y D     window depths read back (glReadPixels), as GL_UNSIGNED_INT
 *   pixel X Y R G B colours read back
 *   error 0xE       glGetError at the end of each frame
 *
 * Each of two frames: a green background (w 8) drawn with the test on
 * GL_LESS; a red quad (w 2, near) drawn with the test off, half over the
 * background, half over nothing; a blue quad (w 3) drawn with the test
 * on after it, over both halves of the red one: it is tested against
 * the program's depth (the background's, or the clear), not against
 * the red quad's, so it covers it.
 *
 *   auto_depth_off [shader|immediate|list]
 *     shader     the GLSL program, glDrawArrays (the default)
 *     immediate  fixed function: glFrustum, glBegin/glEnd
 *     list       fixed function, each quad a display list of its own
 */
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <stdio.h>
#include <string.h>

#include "x_window.h"

#define W 200
#define H 150

static const char *vertex = "#version 120\n"
                            "uniform mat4 u_matrix;\n"
                            "void main() { gl_Position = u_matrix * gl_Vertex; }\n";
static const char *fragment = "#version 120\n"
                              "uniform vec3 u_colour;\n"
                              "void main() { gl_FragColor = vec4(u_colour, 1.0); }\n";

enum mode { SHADER, IMMEDIATE, LIST };
static enum mode mode = SHADER;

/* A quad from (x0, y0) to (x1, y1) at eye z, in `mode`'s way. */
static void quad(GLint colour, const float rgb[3], float x0, float y0, float x1, float y1, float z)
{
    const GLfloat v[] = {x0, y0, z, x1, y0, z, x1, y1, z, x0, y0, z, x1, y1, z, x0, y1, z};
    if (mode == SHADER) {
        glUniform3fv(colour, 1, rgb);
        glVertexPointer(3, GL_FLOAT, 0, v);
        glDrawArrays(GL_TRIANGLES, 0, 6);
        return;
    }
    glColor3fv(rgb);
    GLuint list = 0;
    if (mode == LIST) {
        list = glGenLists(1);
        glNewList(list, GL_COMPILE);
    }
    glBegin(GL_TRIANGLES);
    for (int i = 0; i < 6; i++)
        glVertex3fv(v + 3 * i);
    glEnd();
    if (mode == LIST) {
        glEndList();
        glCallList(list);
        glDeleteLists(list, 1);
    }
}

static GLuint shader(GLenum kind, const char *source)
{
    GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &source, NULL);
    glCompileShader(s);
    return s;
}

int main(int argc, char **argv)
{
    if (argc > 1)
        mode = strcmp(argv[1], "immediate") == 0 ? IMMEDIATE
               : strcmp(argv[1], "list") == 0    ? LIST
                                                 : SHADER;
    struct x_window x = open_x_window_config(NULL, W, H);
    GLint matrix = -1, colour = -1;
    if (mode == SHADER) {
        GLuint program = glCreateProgram();
        glAttachShader(program, shader(GL_VERTEX_SHADER, vertex));
        glAttachShader(program, shader(GL_FRAGMENT_SHADER, fragment));
        glLinkProgram(program);
        glUseProgram(program);
        matrix = glGetUniformLocation(program, "u_matrix");
        colour = glGetUniformLocation(program, "u_colour");
    } else {
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity();
        glFrustum(-1.0, 1.0, -0.75, 0.75, 1.0, 50.0);
        glMatrixMode(GL_MODELVIEW);
        glLoadIdentity();
    }
    /* glFrustum(-1, 1, -0.75, 0.75, 1, 50), column-major. */
    const float n = 1.0f, f = 50.0f;
    const GLfloat frustum[16] = {1.0f, 0, 0, 0, 0, 1.0f / 0.75f, 0, 0,
                                 0,    0, -(f + n) / (f - n), -1.0f,
                                 0,    0, -2.0f * f * n / (f - n), 0};
    if (mode == SHADER) {
        glUniformMatrix4fv(matrix, 1, GL_FALSE, frustum);
        glEnableClientState(GL_VERTEX_ARRAY);
    }
    glViewport(0, 0, W, H);
    GLuint q;
    glGenQueries(1, &q);
    static const float green[3] = {0, 1, 0}, red[3] = {1, 0, 0}, blue[3] = {0, 0, 1};
    for (int frame = 0; frame < 2; frame++) {
        glClearColor(0, 0, 0, 1);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        /* The background: the left half of the view at w 8. */
        quad(colour, green, -8.0f, -6.0f, 0.0f, 6.0f, -8.0f);
        /* The red quad, test off: x -0.5…0.5 NDC, y 0…0.5. */
        glDisable(GL_DEPTH_TEST);
        glDepthFunc(frame ? GL_LEQUAL : GL_GREATER);
        glDepthMask(frame ? GL_FALSE : GL_TRUE);
        glBeginQuery(GL_SAMPLES_PASSED, q);
        quad(colour, red, -1.0f, 0.0f, 1.0f, 0.75f, -2.0f);
        glEndQuery(GL_SAMPLES_PASSED);
        GLint func = 0, mask = 0;
        glGetIntegerv(GL_DEPTH_FUNC, &func);
        glGetIntegerv(GL_DEPTH_WRITEMASK, &mask);
        printf("state %d 0x%x %d\n", glIsEnabled(GL_DEPTH_TEST), func, mask);
        /* The blue quad, test on: x -0.25…0.25 NDC, y 0.1…0.4, w 3. */
        glDepthMask(GL_TRUE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        quad(colour, blue, -0.75f, 0.225f, 0.75f, 0.9f, -3.0f);
        GLuint samples = 0;
        glGetQueryObjectuiv(q, GL_QUERY_RESULT, &samples);
        printf("samples %u\n", samples);
        static const int at[][2] = {{60, 90}, {140, 90}, {100, 100}, {90, 95}, {110, 95},
                                    {20, 20}, {180, 20}};
        for (unsigned i = 0; i < sizeof at / sizeof at[0]; i++) {
            GLuint d = 0;
            GLubyte p[4];
            glReadPixels(at[i][0], at[i][1], 1, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, &d);
            glReadPixels(at[i][0], at[i][1], 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, p);
            printf("depth %d %d %u\n", at[i][0], at[i][1], d);
            printf("pixel %d %d %u %u %u\n", at[i][0], at[i][1], p[0], p[1], p[2]);
        }
        glXSwapBuffers(x.display, x.window);
        printf("error 0x%x\n", glGetError());
    }
    glDeleteQueries(1, &q);
    close_x_window(&x);
    return 0;
}

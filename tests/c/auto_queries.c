/*
 * Queries under automatic stereo (glstereo-run --auto, issue 23 item 4): a
 * mono fixed-function program counts what its draws produce and prints it:
 *
 *   samples N        GL_SAMPLES_PASSED of a quad in front of the background
 *   samples3 N       GL_SAMPLES_PASSED of three quads in one query
 *   primitives N     GL_PRIMITIVES_GENERATED of a glDrawArrays of 5 triangles
 *   any-hidden N     GL_ANY_SAMPLES_PASSED of a quad behind the background
 *   any-seen N       GL_ANY_SAMPLES_PASSED of a quad in front of it
 *   available N      GL_QUERY_RESULT_AVAILABLE of the first, after glFinish
 *   hidden R G B     the pixel of a quad drawn under conditional rendering
 *                    on any-hidden (GL_QUERY_WAIT): the background's
 *   seen R G B       the same on any-seen: the quad's colour
 *   error 0xE        glGetError at the end
 *
 * Under --auto (each draw made once per eye) every count must be the mono
 * program's: the same lines as without the layer. The counted quads are at
 * clip w = 4: run with --convergence 4 they are where mono has them in
 * both eyes, so their pixel counts are the mono ones exactly.
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

/* A quad of half-size `r` around (x, y) at depth z (eye space). */
static void quad(float x, float y, float r, float z)
{
    glBegin(GL_QUADS);
    glVertex3f(x - r, y - r, z);
    glVertex3f(x + r, y - r, z);
    glVertex3f(x + r, y + r, z);
    glVertex3f(x - r, y + r, z);
    glEnd();
}

static GLuint64 result(GLuint q)
{
    GLuint64 v = 0;
    glGetQueryObjectui64v(q, GL_QUERY_RESULT, &v);
    return v;
}

int main(void)
{
    struct x_window x = open_x_window_config(NULL, W, H);
    glViewport(0, 0, W, H);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-1.0, 1.0, -0.75, 0.75, 1.0, 50.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();

    /* The background: green, far (w = 8), larger than the view. */
    glColor3f(0.0f, 1.0f, 0.0f);
    quad(0.0f, 0.0f, 30.0f, -8.0f);
    /* A white marker on it: the eyes differ there. */
    glColor3f(1.0f, 1.0f, 1.0f);
    quad(0.0f, -3.0f, 1.0f, -7.9f);

    GLuint q[6];
    glGenQueries(6, q);
    glColor3f(1.0f, 0.0f, 0.0f);
    glBeginQuery(GL_SAMPLES_PASSED, q[0]);
    quad(-2.0f, 1.0f, 0.8f, -4.0f);
    glEndQuery(GL_SAMPLES_PASSED);

    glBeginQuery(GL_SAMPLES_PASSED, q[1]);
    quad(0.0f, 1.0f, 0.5f, -4.0f);
    quad(1.5f, 1.0f, 0.5f, -4.0f);
    quad(2.5f, 1.0f, 0.3f, -4.0f);
    glEndQuery(GL_SAMPLES_PASSED);

    static GLfloat tris[5 * 9];
    for (int i = 0; i < 5; i++) {
        GLfloat x0 = -3.0f + 1.2f * (float)i;
        GLfloat t[9] = {x0, -2.0f, -4.0f, x0 + 0.8f, -2.0f, -4.0f, x0 + 0.4f, -1.4f, -4.0f};
        for (int k = 0; k < 9; k++) tris[9 * i + k] = t[k];
    }
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, tris);
    glBeginQuery(GL_PRIMITIVES_GENERATED, q[2]);
    glDrawArrays(GL_TRIANGLES, 0, 15);
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glDisableClientState(GL_VERTEX_ARRAY);

    glBeginQuery(GL_ANY_SAMPLES_PASSED, q[3]);
    quad(-2.0f, -0.4f, 0.5f, -9.0f);
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    glBeginQuery(GL_ANY_SAMPLES_PASSED, q[4]);
    quad(2.0f, -0.4f, 0.5f, -4.0f);
    glEndQuery(GL_ANY_SAMPLES_PASSED);

    /* Conditional rendering: blue over where the hidden quad was (it
     * must not be drawn), yellow over the seen one (it must). */
    glDisable(GL_DEPTH_TEST);
    glColor3f(0.0f, 0.0f, 1.0f);
    glBeginConditionalRender(q[3], GL_QUERY_WAIT);
    quad(-2.0f, -0.4f, 0.3f, -4.0f);
    glEndConditionalRender();
    glColor3f(1.0f, 1.0f, 0.0f);
    glBeginConditionalRender(q[4], GL_QUERY_WAIT);
    quad(2.0f, -0.4f, 0.3f, -4.0f);
    glEndConditionalRender();

    glFinish();
    GLuint available = 0;
    glGetQueryObjectuiv(q[0], GL_QUERY_RESULT_AVAILABLE, &available);
    GLint samples = 0;
    glGetQueryObjectiv(q[0], GL_QUERY_RESULT, &samples);
    printf("samples %d\n", samples);
    printf("samples3 %llu\n", (unsigned long long)result(q[1]));
    printf("primitives %llu\n", (unsigned long long)result(q[2]));
    printf("any-hidden %llu\n", (unsigned long long)result(q[3]));
    printf("any-seen %llu\n", (unsigned long long)result(q[4]));
    printf("available %u\n", available);
    /* Eye x of (-2, -0.4, -4) and (2, -0.4, -4): x / 4 in NDC. */
    GLubyte px[4];
    glReadPixels(W / 4, (int)((1.0f - 0.4f / 4.0f / 0.75f) * H / 2.0f), 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    printf("hidden %d %d %d\n", px[0], px[1], px[2]);
    glReadPixels(3 * W / 4, (int)((1.0f - 0.4f / 4.0f / 0.75f) * H / 2.0f), 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    printf("seen %d %d %d\n", px[0], px[1], px[2]);
    glXSwapBuffers(x.display, x.window);
    glDeleteQueries(6, q);
    printf("error 0x%x\n", glGetError());
    close_x_window(&x);
    return 0;
}

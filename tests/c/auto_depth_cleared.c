/*
 * A mono program that clears its depth in the middle of a frame (links
 * only -lGL -lX11), under `glstereo-run --auto=depth` and `--auto`:
 *
 *   auto_depth_cleared HOW WHAT
 *
 * HOW: how the depth is cleared: clear (glClear), clearbuffer
 * (glClearBufferfv GL_DEPTH), named (glClearNamedFramebufferfv of the
 * framebuffer bound for drawing).
 *
 * WHAT:
 *   beside     a red quad (w 2) with the depth test on, a blue one with
 *              the test off (which --auto=depth draws with a depth layer of
 *              its own attached), the depth cleared, a larger green quad
 *              (w 6) with the test on over the red one: prints the centre
 *              pixel ("centre R G B", green: the clear cleared the
 *              program's depth), its depth as GL_UNSIGNED_INT and the GL
 *              error, as Mesa gives them.
 *   gizmo      the scene (a yellow wall at w 8, a red quad at w 2), the
 *              depth cleared, then a white quad in perspective in a
 *              50x50 viewport in the bottom-right corner (an orientation
 *              gizmo, as VTK's corner renderer draws its axes) and its
 *              label, a flat cyan square in the corner's bottom left
 *              (x 2-10, y 2-10 of it), drawn with the depth test off
 *   scissored  the same with the clear scissored to the gizmo's corner
 *   target     scissored, drawn into a framebuffer object of the window's
 *              size (colour texture, depth renderbuffer) and blitted into
 *              the window, as VTK 9 draws its renderers
 *   pass       the scene drawn into that framebuffer object, then a flat
 *              pass over all of it (blue 32 added by blending; no depth
 *              cleared), blitted into the window
 *
 * One 200x150 frame, swapped; the eyes are the captures.
 */
#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "x_window.h"

#define W 200
#define H 150
#define DEPTH 0x1801

typedef void (*ClearBufferfv)(GLenum, GLint, const GLfloat *);
typedef void (*Gen)(GLsizei, GLuint *);
typedef void (*Bind)(GLenum, GLuint);
typedef void (*Storage)(GLenum, GLenum, GLsizei, GLsizei);
typedef void (*AttachRb)(GLenum, GLenum, GLenum, GLuint);
typedef void (*AttachTex)(GLenum, GLenum, GLenum, GLuint, GLint);
typedef void (*Blit)(GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLbitfield,
                     GLenum);

static void (*proc(const char *name))(void)
{
    void (*f)(void) = glXGetProcAddress((const GLubyte *)name);
    if (f == NULL) {
        fprintf(stderr, "no %s\n", name);
        exit(1);
    }
    return f;
}
typedef void (*ClearNamedFramebufferfv)(GLuint, GLenum, GLint, const GLfloat *);

static const char *how = "clear";

static void quad(float x0, float y0, float x1, float y1, float z)
{
    glBegin(GL_QUADS);
    glVertex3f(x0, y0, z);
    glVertex3f(x1, y0, z);
    glVertex3f(x1, y1, z);
    glVertex3f(x0, y1, z);
    glEnd();
}

static void clear_depth(void)
{
    static const GLfloat one = 1.0f;
    if (strcmp(how, "clearbuffer") == 0) {
        ((ClearBufferfv)glXGetProcAddress((const GLubyte *)"glClearBufferfv"))(DEPTH, 0, &one);
    } else if (strcmp(how, "named") == 0) {
        GLint bound = 0;
        glGetIntegerv(0x8CA6 /* GL_DRAW_FRAMEBUFFER_BINDING */, &bound);
        ((ClearNamedFramebufferfv)glXGetProcAddress(
            (const GLubyte *)"glClearNamedFramebufferfv"))((GLuint)bound, DEPTH, 0, &one);
    } else {
        glClear(GL_DEPTH_BUFFER_BIT);
    }
}

static void perspective(int x, int y, int w, int h, double aspect)
{
    glViewport(x, y, w, h);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-1, 1, -aspect, aspect, 1, 50);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr,
                "usage: auto_depth_cleared clear|clearbuffer|named beside|gizmo|scissored|target|pass\n");
        return 2;
    }
    how = argv[1];
    const char *what = argv[2];
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_DEPTH_SIZE, 24, None};
    struct x_window x = open_x_window(attributes, W, H);
    int pass = strcmp(what, "pass") == 0;
    int target = strcmp(what, "target") == 0 || pass;
    GLuint fbo = 0;
    if (target) {
        GLuint texture = 0, depth = 0;
        ((Gen)proc("glGenFramebuffers"))(1, &fbo);
        ((Gen)proc("glGenRenderbuffers"))(1, &depth);
        glGenTextures(1, &texture);
        glBindTexture(GL_TEXTURE_2D, texture);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        ((Bind)proc("glBindRenderbuffer"))(0x8D41, depth);
        ((Storage)proc("glRenderbufferStorage"))(0x8D41, 0x81A6, W, H);
        ((Bind)proc("glBindFramebuffer"))(0x8D40, fbo);
        ((AttachTex)proc("glFramebufferTexture2D"))(0x8D40, 0x8CE0, GL_TEXTURE_2D, texture, 0);
        ((AttachRb)proc("glFramebufferRenderbuffer"))(0x8D40, 0x8D00, 0x8D41, depth);
    }
    perspective(0, 0, W, H, 0.75);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    if (strcmp(what, "beside") == 0) {
        glColor3f(1, 0, 0);
        quad(-1, -0.75f, 1, 0.75f, -2);
        glDisable(GL_DEPTH_TEST);
        glColor3f(0, 0, 1);
        quad(-7, 3, -4, 5, -8);
        clear_depth();
        glEnable(GL_DEPTH_TEST);
        glColor3f(0, 1, 0);
        quad(-2, -1.5f, 2, 1.5f, -6);
        GLubyte p[4] = {0};
        GLuint d = 0;
        glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, p);
        glReadPixels(W / 2, H / 2, 1, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, &d);
        printf("centre %u %u %u\ndepth %u\n", p[0], p[1], p[2], d);
    } else {
        glColor3f(1, 1, 0);
        quad(-8, -6, 8, 6, -8);
        glColor3f(1, 0, 0);
        quad(-1.2f, -0.5f, -0.2f, 0.5f, -2);
    }
    if (pass) {
        /* A flat pass over the whole scene, blended onto it. */
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity();
        glMatrixMode(GL_MODELVIEW);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glColor3f(0, 0, 32.0f / 255.0f);
        quad(-1, -1, 1, 1, 0);
        glDisable(GL_BLEND);
    } else if (strcmp(what, "beside") != 0) {
        if (strcmp(what, "gizmo") != 0) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(W - 50, 0, 50, 50);
        }
        clear_depth();
        glDisable(GL_SCISSOR_TEST);
        perspective(W - 50, 0, 50, 50, 1.0);
        glColor3f(1, 1, 1);
        quad(-0.5f, -0.5f, 0.5f, 0.5f, -3);
        /* Its label: flat (w = 1), the depth test off. */
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity();
        glOrtho(0, 50, 0, 50, -1, 1);
        glMatrixMode(GL_MODELVIEW);
        glDisable(GL_DEPTH_TEST);
        glColor3f(0, 1, 1);
        quad(2, 2, 10, 10, 0);
    }
    if (target) {
        ((Bind)proc("glBindFramebuffer"))(0x8CA9, 0);
        ((Bind)proc("glBindFramebuffer"))(0x8CA8, fbo);
        ((Blit)proc("glBlitFramebuffer"))(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT,
                                          GL_NEAREST);
        ((Bind)proc("glBindFramebuffer"))(0x8D40, 0);
    }
    printf("error 0x%x\n", glGetError());
    glXSwapBuffers(x.display, x.window);
    close_x_window(&x);
    return 0;
}

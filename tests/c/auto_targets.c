/*
 * Render targets under automatic stereo (glstereo-run --auto, issue 23
 * item 3): a mono program draws a picture into a framebuffer object of
 * its own (a red quad at clip w = 2 on blue, through a perspective
 * projection), then shows that texture on a quad of the window at clip
 * w = 4, and swaps.
 *
 *   auto_targets small    the framebuffer object is 64x64, square: seen
 *                         from a light (a shadow or reflection map), not
 *                         a picture of the screen. It stays mono: with
 *                         --convergence 4 both eyes show the same pixels
 *                         on the window's quad.
 *   auto_targets window   the framebuffer object is the window's size:
 *                         drawn in stereo, its red quad shifted between
 *                         the eyes as any object at w = 2.
 *
 * Prints "error 0xE" (glGetError at the end).
 */
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "x_window.h"

#define W 200
#define H 150

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: auto_targets small|window\n");
        return 2;
    }
    int small = strcmp(argv[1], "small") == 0;
    int tw = small ? 64 : W, th = small ? 64 : H;
    struct x_window x = open_x_window_config(NULL, W, H);

    GLuint tex = 0, depth = 0, fbo = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tw, th, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, tw, th);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return 5;

    /* The picture: a red quad near (w = 2) on blue. */
    glViewport(0, 0, tw, th);
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-1.0, 1.0, -0.75, 0.75, 1.0, 50.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glColor3f(1.0f, 0.0f, 0.0f);
    glBegin(GL_QUADS);
    glVertex3f(-0.6f, -0.4f, -2.0f);
    glVertex3f(0.6f, -0.4f, -2.0f);
    glVertex3f(0.6f, 0.4f, -2.0f);
    glVertex3f(-0.6f, 0.4f, -2.0f);
    glEnd();

    /* The window: the texture on a quad at w = 4 filling the middle. */
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, W, H);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, tex);
    glColor3f(1.0f, 1.0f, 1.0f);
    glBegin(GL_QUADS);
    glTexCoord2f(0.0f, 0.0f);
    glVertex3f(-2.4f, -1.8f, -4.0f);
    glTexCoord2f(1.0f, 0.0f);
    glVertex3f(2.4f, -1.8f, -4.0f);
    glTexCoord2f(1.0f, 1.0f);
    glVertex3f(2.4f, 1.8f, -4.0f);
    glTexCoord2f(0.0f, 1.0f);
    glVertex3f(-2.4f, 1.8f, -4.0f);
    glEnd();
    glDisable(GL_TEXTURE_2D);
    glXSwapBuffers(x.display, x.window);
    printf("error 0x%x\n", glGetError());
    close_x_window(&x);
    return 0;
}

/*
 * Alpha on a visual without alpha bits (links only -lGL -lX11). Run as
 * "glx_opaque_alpha stereo" under glstereo-run (a GLX_STEREO visual
 * without GLX_ALPHA_SIZE) and as "glx_opaque_alpha mono" without it (the
 * same visual without GLX_STEREO, served by Mesa): the printed lines are
 * GL's answers and must be the same, byte for byte.
 *
 * What it probes: framebuffer 0 reads alpha 1.0 whatever is cleared, drawn,
 * blitted or cleared through glClearBuffer / glClearNamedFramebuffer into
 * it; blending sees a destination alpha of 1.0; GL_COLOR_WRITEMASK
 * (glGetBooleanv, glGetIntegerv, glGetBooleani_v) answers what the program
 * set, on framebuffer 0 and on its own framebuffer object, across
 * glPushAttrib / glPopAttrib; the program's own framebuffer object's alpha
 * is written when its mask allows it.
 */
#include <stdio.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

#include "x_window.h"

#define FRAMEBUFFER 0x8D40
#define READ_FRAMEBUFFER 0x8CA8
#define DRAW_FRAMEBUFFER 0x8CA9
#define COLOR_ATTACHMENT0 0x8CE0
#define COLOR 0x1800

typedef void (*GenFramebuffers)(GLsizei, GLuint *);
typedef void (*BindFramebuffer)(GLenum, GLuint);
typedef void (*FramebufferTexture2D)(GLenum, GLenum, GLenum, GLuint, GLint);
typedef void (*ColorMaski)(GLuint, GLboolean, GLboolean, GLboolean, GLboolean);
typedef void (*GetBooleani)(GLenum, GLuint, GLboolean *);
typedef void (*BlitFramebuffer)(GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLint,
                                GLbitfield, GLenum);
typedef void (*BlitNamedFramebuffer)(GLuint, GLuint, GLint, GLint, GLint, GLint, GLint, GLint,
                                     GLint, GLint, GLbitfield, GLenum);
typedef void (*ClearBufferfv)(GLenum, GLint, const GLfloat *);
typedef void (*ClearNamedFramebufferfv)(GLuint, GLenum, GLint, const GLfloat *);

typedef void (*AnyFn)(void);

static AnyFn proc(const char *name)
{
    return glXGetProcAddress((const GLubyte *)name);
}

/* The pixel at (10, 10) of the read framebuffer, as GL_RGBA bytes and as
 * GL_ALPHA floats. */
static void pixel(const char *what)
{
    GLubyte rgba[4] = {0};
    GLfloat alpha = -1.0f;
    glReadPixels(10, 10, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glReadPixels(10, 10, 1, 1, GL_ALPHA, GL_FLOAT, &alpha);
    printf("%s rgba %u %u %u %u alpha %.3f error 0x%x\n", what, rgba[0], rgba[1], rgba[2],
           rgba[3], alpha, glGetError());
}

static void writemask(const char *what, GetBooleani get_i)
{
    GLboolean b[4] = {9, 9, 9, 9}, b1[4] = {9, 9, 9, 9};
    GLint n[4] = {9, 9, 9, 9};
    glGetBooleanv(GL_COLOR_WRITEMASK, b);
    glGetIntegerv(GL_COLOR_WRITEMASK, n);
    get_i(GL_COLOR_WRITEMASK, 1, b1);
    printf("%s writemask %d%d%d%d int %d%d%d%d index1 %d%d%d%d error 0x%x\n", what, b[0], b[1],
           b[2], b[3], n[0], n[1], n[2], n[3], b1[0], b1[1], b1[2], b1[3], glGetError());
}

static void clear(float a)
{
    glClearColor(0.2f, 0.4f, 0.6f, a);
    glClear(GL_COLOR_BUFFER_BIT);
}

int main(int argc, char **argv)
{
    int stereo = argc > 1 && strcmp(argv[1], "stereo") == 0;
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, stereo ? GLX_STEREO : None,
                        None};
    struct x_window x = open_x_window(attributes, 64, 64);
    GenFramebuffers gen = (GenFramebuffers)proc("glGenFramebuffers");
    BindFramebuffer bind = (BindFramebuffer)proc("glBindFramebuffer");
    FramebufferTexture2D attach = (FramebufferTexture2D)proc("glFramebufferTexture2D");
    ColorMaski maski = (ColorMaski)proc("glColorMaski");
    GetBooleani get_i = (GetBooleani)proc("glGetBooleani_v");
    BlitFramebuffer blit = (BlitFramebuffer)proc("glBlitFramebuffer");
    BlitNamedFramebuffer blit_named = (BlitNamedFramebuffer)proc("glBlitNamedFramebuffer");
    ClearBufferfv clear_buffer = (ClearBufferfv)proc("glClearBufferfv");
    ClearNamedFramebufferfv clear_named =
        (ClearNamedFramebufferfv)proc("glClearNamedFramebufferfv");
    if (!gen || !bind || !attach || !maski || !get_i || !blit || !blit_named || !clear_buffer ||
        !clear_named) {
        fprintf(stderr, "the driver lacks GL 3.0 / 4.5 functions\n");
        return 1;
    }
    GLint alpha_bits = -1;
    glGetIntegerv(GL_ALPHA_BITS, &alpha_bits);
    printf("alpha_bits %d\n", alpha_bits);
    glViewport(0, 0, 64, 64);

    /* Framebuffer 0: clears, draws and blending see alpha 1.0. */
    clear(0.25f);
    pixel("clear 0.25");
    glColor4f(1.0f, 0.0f, 0.0f, 0.3f);
    glRectf(-1.0f, -1.0f, 1.0f, 1.0f);
    pixel("draw alpha 0.3");
    clear(0.0f);
    glEnable(GL_BLEND);
    glBlendFunc(GL_DST_ALPHA, GL_ZERO);
    glColor4f(1.0f, 1.0f, 1.0f, 0.5f);
    glRectf(-1.0f, -1.0f, 1.0f, 1.0f);
    pixel("blend dst_alpha");
    clear(0.0f);
    glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);
    glColor4f(1.0f, 1.0f, 1.0f, 1.0f);
    glRectf(-1.0f, -1.0f, 1.0f, 1.0f);
    pixel("blend one_minus_dst_alpha");
    glDisable(GL_BLEND);
    GLfloat quarter[4] = {0.8f, 0.6f, 0.4f, 0.25f};
    clear_buffer(COLOR, 0, quarter);
    pixel("clear_buffer 0.25");

    /* The masks the program sets are what it reads back. */
    writemask("initial", get_i);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_TRUE);
    writemask("fb0 1011", get_i);
    maski(1, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
    writemask("fb0 maski 1 0101", get_i);
    clear(0.25f);
    pixel("masked clear");
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

    /* The program's own framebuffer object: alpha is written. */
    GLuint tex = 0, fbo = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    gen(1, &fbo);
    bind(FRAMEBUFFER, fbo);
    attach(FRAMEBUFFER, COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    writemask("fbo 1111", get_i);
    clear(0.25f);
    pixel("fbo clear 0.25");
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
    writemask("fbo 1110", get_i);
    clear(0.75f);
    pixel("fbo masked clear");
    bind(FRAMEBUFFER, 0);
    writemask("fb0 1110", get_i);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    writemask("fb0 1111", get_i);
    bind(FRAMEBUFFER, fbo);
    clear(0.5f);
    pixel("fbo clear 0.5");

    /* Blits and named clears into framebuffer 0 leave alpha 1.0. */
    bind(READ_FRAMEBUFFER, fbo);
    bind(DRAW_FRAMEBUFFER, 0);
    blit(0, 0, 64, 64, 0, 0, 64, 64, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    bind(READ_FRAMEBUFFER, 0);
    pixel("blit into fb0");
    clear(0.0f);
    bind(FRAMEBUFFER, fbo);
    blit_named(fbo, 0, 0, 0, 64, 64, 0, 0, 64, 64, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    clear_named(0, COLOR, 0, quarter);
    pixel("fbo after named blit and clear of fb0");
    bind(FRAMEBUFFER, 0);
    pixel("named clear of fb0");
    clear(0.0f);
    bind(FRAMEBUFFER, fbo);
    blit_named(fbo, 0, 0, 0, 64, 64, 0, 0, 64, 64, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    bind(FRAMEBUFFER, 0);
    pixel("named blit into fb0");

    /* glPushAttrib / glPopAttrib restore the program's masks. */
    glPushAttrib(GL_COLOR_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
    writemask("pushed 0101", get_i);
    glPopAttrib();
    writemask("popped", get_i);
    clear(0.25f);
    pixel("clear after pop");
    bind(FRAMEBUFFER, fbo);
    glPushAttrib(GL_COLOR_BUFFER_BIT);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
    bind(FRAMEBUFFER, 0);
    glPopAttrib();
    /* Mesa raises GL_INVALID_OPERATION here (the framebuffer object's draw
     * buffer, restored onto framebuffer 0); the layer does not: a
     * draw-buffer matter, outside what this program compares. */
    (void)glGetError();
    writemask("popped on fb0", get_i);
    clear(0.25f);
    pixel("fb0 clear after pop");
    bind(FRAMEBUFFER, fbo);
    clear(0.25f);
    pixel("fbo clear after pop");

    /* A clear of framebuffer 0 keeps the program's clear colour. */
    bind(FRAMEBUFFER, 0);
    clear(0.25f);
    GLfloat cc[4] = {0};
    glGetFloatv(GL_COLOR_CLEAR_VALUE, cc);
    printf("clear value %.3f %.3f %.3f %.3f\n", cc[0], cc[1], cc[2], cc[3]);
    bind(FRAMEBUFFER, fbo);
    glClear(GL_COLOR_BUFFER_BIT);
    pixel("fbo clear with the same colour");

    close_x_window(&x);
    return 0;
}

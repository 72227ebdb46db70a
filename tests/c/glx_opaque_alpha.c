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
 * is written when its mask allows it. Then the other ways in: the
 * extension names of glColorMaski, every glGet that answers
 * GL_COLOR_WRITEMASK (indexed or not), per-buffer masks across
 * glPushAttrib / glPopAttrib, blits under GL_RASTERIZER_DISCARD (which
 * stops clears but not blits), and the integer and fixed-point clear
 * colour setters.
 */
#include <stdio.h>
#include <stdlib.h>
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
#define RASTERIZER_DISCARD 0x8C89
#define DRAW_FRAMEBUFFER_BINDING_ 0x8CA6

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

typedef void (*GetIntegeri)(GLenum, GLuint, GLint *);
typedef void (*GetInteger64i)(GLenum, GLuint, long long *);
typedef void (*GetInteger64)(GLenum, long long *);
typedef void (*GetFloati)(GLenum, GLuint, GLfloat *);
typedef void (*GetDoublei)(GLenum, GLuint, GLdouble *);
typedef void (*ClearColorI)(GLint, GLint, GLint, GLint);
typedef void (*ClearColorUi)(GLuint, GLuint, GLuint, GLuint);
typedef void (*ClearColorX)(GLint, GLint, GLint, GLint);

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

/* A function the driver must have, looked up by name. */
static AnyFn need(const char *name)
{
    AnyFn f = proc(name);
    if (!f) {
        fprintf(stderr, "the driver lacks %s\n", name);
        exit(1);
    }
    return f;
}

/* GL_COLOR_WRITEMASK through every glGet that answers it: the indexed
 * ones (GL 3.0, 4.1, GL_EXT_draw_buffers2, GL_EXT_direct_state_access,
 * GL_OES_viewport_array) for draw buffers 0 and 1, the others for 0. */
static void writemask_everywhere(const char *what)
{
    static const char *const booleans[] = {"glGetBooleani_v", "glGetBooleanIndexedvEXT"};
    static const char *const integers[] = {"glGetIntegeri_v", "glGetIntegerIndexedvEXT"};
    static const char *const floats[] = {"glGetFloati_v", "glGetFloati_vEXT", "glGetFloati_vOES",
                                         "glGetFloatIndexedvEXT"};
    static const char *const doubles[] = {"glGetDoublei_v", "glGetDoublei_vEXT",
                                          "glGetDoubleIndexedvEXT"};
    for (GLuint i = 0; i < 2; i++) {
        for (size_t k = 0; k < sizeof booleans / sizeof *booleans; k++) {
            GLboolean v[4] = {9, 9, 9, 9};
            ((GetBooleani)need(booleans[k]))(GL_COLOR_WRITEMASK, i, v);
            printf("%s %s %u %d%d%d%d\n", what, booleans[k], i, v[0], v[1], v[2], v[3]);
        }
        for (size_t k = 0; k < sizeof integers / sizeof *integers; k++) {
            GLint v[4] = {9, 9, 9, 9};
            ((GetIntegeri)need(integers[k]))(GL_COLOR_WRITEMASK, i, v);
            printf("%s %s %u %d%d%d%d\n", what, integers[k], i, v[0], v[1], v[2], v[3]);
        }
        long long v64[4] = {9, 9, 9, 9};
        ((GetInteger64i)need("glGetInteger64i_v"))(GL_COLOR_WRITEMASK, i, v64);
        printf("%s glGetInteger64i_v %u %lld%lld%lld%lld\n", what, i, v64[0], v64[1], v64[2],
               v64[3]);
        for (size_t k = 0; k < sizeof floats / sizeof *floats; k++) {
            GLfloat v[4] = {9, 9, 9, 9};
            ((GetFloati)need(floats[k]))(GL_COLOR_WRITEMASK, i, v);
            printf("%s %s %u %.0f%.0f%.0f%.0f\n", what, floats[k], i, v[0], v[1], v[2], v[3]);
        }
        for (size_t k = 0; k < sizeof doubles / sizeof *doubles; k++) {
            GLdouble v[4] = {9, 9, 9, 9};
            ((GetDoublei)need(doubles[k]))(GL_COLOR_WRITEMASK, i, v);
            printf("%s %s %u %.0f%.0f%.0f%.0f\n", what, doubles[k], i, v[0], v[1], v[2], v[3]);
        }
    }
    GLfloat f[4] = {9, 9, 9, 9};
    GLdouble d[4] = {9, 9, 9, 9};
    long long n[4] = {9, 9, 9, 9};
    glGetFloatv(GL_COLOR_WRITEMASK, f);
    glGetDoublev(GL_COLOR_WRITEMASK, d);
    ((GetInteger64)need("glGetInteger64v"))(GL_COLOR_WRITEMASK, n);
    printf("%s glGetFloatv %.0f%.0f%.0f%.0f glGetDoublev %.0f%.0f%.0f%.0f glGetInteger64v "
           "%lld%lld%lld%lld error 0x%x\n",
           what, f[0], f[1], f[2], f[3], d[0], d[1], d[2], d[3], n[0], n[1], n[2], n[3],
           glGetError());
}

/* GL_COLOR_CLEAR_VALUE as floats and as integers. */
static void clear_value(const char *what)
{
    GLfloat f[4] = {0};
    GLint n[4] = {0};
    glGetFloatv(GL_COLOR_CLEAR_VALUE, f);
    glGetIntegerv(GL_COLOR_CLEAR_VALUE, n);
    printf("%s clear value %.3f %.3f %.3f %.3f int %d %d %d %d error 0x%x\n", what, f[0], f[1],
           f[2], f[3], n[0], n[1], n[2], n[3], glGetError());
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

    /* The other names of glColorMaski (GL_EXT_draw_buffers2's, and the
     * GLES ones libGL serves desktop contexts too) set the same masks:
     * framebuffer 0 still reads alpha 1.0 after a draw. */
    static const char *const maski_names[] = {"glColorMaskIndexedEXT", "glColorMaskiEXT",
                                              "glColorMaskiOES"};
    bind(FRAMEBUFFER, 0);
    for (size_t k = 0; k < sizeof maski_names / sizeof *maski_names; k++) {
        ColorMaski f = (ColorMaski)need(maski_names[k]);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
        f(0, GL_TRUE, GL_FALSE, GL_TRUE, GL_TRUE);
        f(1, GL_FALSE, GL_TRUE, GL_TRUE, GL_TRUE);
        writemask(maski_names[k], get_i);
        glColor4f(1.0f, 1.0f, 1.0f, 0.3f);
        glRectf(-1.0f, -1.0f, 1.0f, 1.0f);
        pixel(maski_names[k]);
    }

    /* Every query of GL_COLOR_WRITEMASK answers the program's masks, on
     * framebuffer 0 and on its own framebuffer object. */
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_TRUE);
    maski(1, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
    writemask_everywhere("fb0 queries");
    bind(FRAMEBUFFER, fbo);
    writemask_everywhere("fbo queries");
    bind(FRAMEBUFFER, 0);
    long long binding = -1;
    ((GetInteger64)need("glGetInteger64v"))(DRAW_FRAMEBUFFER_BINDING_, &binding);
    printf("glGetInteger64v draw framebuffer binding %lld error 0x%x\n", binding, glGetError());

    /* glPopAttrib restores per-buffer masks, whatever is bound then. */
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    maski(1, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
    glPushAttrib(GL_COLOR_BUFFER_BIT);
    glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
    glPopAttrib();
    writemask("popped per-buffer", get_i);
    glColor4f(1.0f, 1.0f, 1.0f, 0.3f);
    glRectf(-1.0f, -1.0f, 1.0f, 1.0f);
    pixel("draw after per-buffer pop");
    maski(0, GL_TRUE, GL_TRUE, GL_FALSE, GL_TRUE);
    glPushAttrib(GL_COLOR_BUFFER_BIT);
    bind(FRAMEBUFFER, fbo);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glPopAttrib();
    writemask("fbo popped per-buffer", get_i);
    /* The pop also restores framebuffer 0's draw buffer (GL_BACK) onto the
     * framebuffer object, which GL refuses: GL_INVALID_OPERATION, the
     * object keeps its own. */
    {
        GLint db = 0;
        GLenum e = glGetError();
        glGetIntegerv(GL_DRAW_BUFFER, &db);
        printf("fbo draw buffer after a pop pushed on 0: 0x%x, pop error 0x%x\n", (unsigned)db, e);
    }
    clear(0.75f);
    pixel("fbo clear after per-buffer pop");
    bind(FRAMEBUFFER, 0);
    clear(0.25f);
    pixel("fb0 clear after per-buffer pop");
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

    /* And the other way: the object's draw and read buffers pushed,
     * popped onto framebuffer 0, which keeps GL_BACK; GL_NONE pushed on 0
     * goes onto the object. */
    {
        GLint db = 0, rb = 0;
        GLenum e;
        bind(FRAMEBUFFER, fbo);
        glPushAttrib(GL_COLOR_BUFFER_BIT | GL_PIXEL_MODE_BIT);
        bind(FRAMEBUFFER, 0);
        glPopAttrib();
        e = glGetError();
        glGetIntegerv(GL_DRAW_BUFFER, &db);
        glGetIntegerv(GL_READ_BUFFER, &rb);
        printf("fb0 draw buffer 0x%x read buffer 0x%x after a pop pushed on the fbo, pop error 0x%x\n",
               (unsigned)db, (unsigned)rb, e);
        glDrawBuffer(GL_NONE);
        glReadBuffer(GL_NONE);
        glPushAttrib(GL_COLOR_BUFFER_BIT | GL_PIXEL_MODE_BIT);
        glDrawBuffer(GL_BACK);
        glReadBuffer(GL_BACK);
        bind(FRAMEBUFFER, fbo);
        glPopAttrib();
        e = glGetError();
        glGetIntegerv(GL_DRAW_BUFFER, &db);
        glGetIntegerv(GL_READ_BUFFER, &rb);
        printf("fbo draw buffer 0x%x read buffer 0x%x after GL_NONE popped from 0, pop error 0x%x\n",
               (unsigned)db, (unsigned)rb, e);
        glDrawBuffer(COLOR_ATTACHMENT0);
        glReadBuffer(COLOR_ATTACHMENT0);
        bind(FRAMEBUFFER, 0);
        glPushAttrib(GL_PIXEL_MODE_BIT);
        bind(FRAMEBUFFER, fbo);
        glPopAttrib();
        e = glGetError();
        glGetIntegerv(GL_READ_BUFFER, &rb);
        printf("fbo read buffer 0x%x after GL_BACK popped from 0, pop error 0x%x\n", (unsigned)rb, e);
        bind(FRAMEBUFFER, 0);
        glGetIntegerv(GL_DRAW_BUFFER, &db);
        glGetIntegerv(GL_READ_BUFFER, &rb);
        printf("fb0 draw buffer 0x%x read buffer 0x%x at the end, error 0x%x\n", (unsigned)db, (unsigned)rb,
               glGetError());
    }

    /* GL_RASTERIZER_DISCARD stops glClear and glClearBuffer (GL 4.5
     * §14.1), not blits: what is blitted into framebuffer 0 still reads
     * alpha 1.0, and the enable stays the program's. */
    bind(FRAMEBUFFER, fbo);
    glClearColor(1.0f, 0.0f, 0.5f, 0.25f);
    glClear(GL_COLOR_BUFFER_BIT);
    bind(FRAMEBUFFER, 0);
    clear(0.0f);
    glEnable(RASTERIZER_DISCARD);
    clear(0.5f);
    pixel("clear under rasterizer discard");
    clear_buffer(COLOR, 0, quarter);
    pixel("clear_buffer under rasterizer discard");
    bind(READ_FRAMEBUFFER, fbo);
    blit(0, 0, 64, 64, 0, 0, 64, 64, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    bind(READ_FRAMEBUFFER, 0);
    pixel("blit under rasterizer discard");
    printf("rasterizer discard still %d\n", glIsEnabled(RASTERIZER_DISCARD));
    glDisable(RASTERIZER_DISCARD);
    clear(0.0f);
    glEnable(RASTERIZER_DISCARD);
    blit_named(fbo, 0, 0, 0, 64, 64, 0, 0, 64, 64, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    pixel("named blit under rasterizer discard");
    clear_named(0, COLOR, 0, quarter);
    pixel("named clear under rasterizer discard");
    printf("rasterizer discard still %d error 0x%x\n", glIsEnabled(RASTERIZER_DISCARD),
           glGetError());
    glDisable(RASTERIZER_DISCARD);

    /* The integer (GL_EXT_texture_integer) and fixed-point
     * (GL_OES_fixed_point) clear colours are the colour glClear uses, and
     * what GL_COLOR_CLEAR_VALUE answers, afterwards too. Mesa keeps one
     * clear colour whose bits each setter writes. */
    ClearColorUi clear_ui = (ClearColorUi)need("glClearColorIuiEXT");
    ClearColorI clear_i = (ClearColorI)need("glClearColorIiEXT");
    ClearColorX clear_x = (ClearColorX)need("glClearColorx");
    ClearColorX clear_x_oes = (ClearColorX)need("glClearColorxOES");
    clear_ui(0x3f000000u, 0x3f800000u, 0x3e800000u, 0x3e800000u);
    glClear(GL_COLOR_BUFFER_BIT);
    pixel("fb0 clear after glClearColorIuiEXT");
    clear_value("glClearColorIuiEXT");
    bind(FRAMEBUFFER, fbo);
    glClear(GL_COLOR_BUFFER_BIT);
    pixel("fbo clear after glClearColorIuiEXT");
    bind(FRAMEBUFFER, 0);
    clear_i(0x3e800000, 0x3f000000, 0x3f800000, 0x3f000000);
    glClear(GL_COLOR_BUFFER_BIT);
    pixel("fb0 clear after glClearColorIiEXT");
    clear_value("glClearColorIiEXT");
    clear_x(0x8000, 0x4000, 0x10000, 0x4000);
    glClear(GL_COLOR_BUFFER_BIT);
    pixel("fb0 clear after glClearColorx");
    clear_value("glClearColorx");
    clear_x_oes(0x4000, 0x10000, 0x8000, 0xc000);
    glClear(GL_COLOR_BUFFER_BIT);
    pixel("fb0 clear after glClearColorxOES");
    clear_value("glClearColorxOES");
    bind(FRAMEBUFFER, fbo);
    glClear(GL_COLOR_BUFFER_BIT);
    pixel("fbo clear after glClearColorxOES");

    close_x_window(&x);
    return 0;
}

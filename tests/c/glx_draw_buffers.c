/*
 * The GL 4.5 draw/read-buffer rules of a default framebuffer, checked from
 * an unmodified GLX program (links only -lGL -lX11) on four visuals:
 * stereo and mono, double- and single-buffered. Run under glstereo-run the
 * stereo ones are emulated and the mono ones are the driver's own, so the
 * same table checks the layer against the rules and the driver alike.
 *
 * Every name glDrawBuffer takes must reach exactly the buffers GL says; a
 * name selecting no buffer of the visual is GL_INVALID_OPERATION, a value
 * naming no buffer GL_INVALID_ENUM, from glGetError, and neither changes
 * the state; glReadBuffer picks the buffer GL says; glDrawBuffers follows
 * its own rules; one swap makes both back buffers the front ones. Also:
 * the framebuffer bindings the program sees, its own framebuffer objects,
 * and texture names it never generated.
 *
 *   glx_draw_buffers stereo   checks the rules on the stereo visuals
 *   glx_draw_buffers core     the same on a GL 3.3 core-profile context made
 *                             with glXChooseFBConfig(GLX_STEREO True) and
 *                             glXCreateContextAttribsARB
 *   glx_draw_buffers mono     runs the same probes on the mono visuals and
 *                             prints what the driver answered, one line per
 *                             probe (the test compares it with a run
 *                             without the layer: the layer must not change
 *                             a mono program; Mesa's own single-buffered
 *                             windows, for one, accept GL_BACK)
 *
 * Prints "N passed, N failed" (and each failure on stderr); exit 0 when
 * all pass, 2 when a visual is missing.
 */
#include <stdio.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

#include "check.h"

/* 1: check the GL rules (stereo visuals); 0: only print what happens. */
static int checking = 1;
#define EXPECT(cond, ...)                  \
    do {                                   \
        if (checking) CHECK(cond, __VA_ARGS__); \
    } while (0)

/* GL 3.0 names (GL/gl.h is 1.3). */
#define FRAMEBUFFER 0x8D40
#define DRAW_FRAMEBUFFER_BINDING 0x8CA6
#define READ_FRAMEBUFFER_BINDING 0x8CAA
#define COLOR_ATTACHMENT0 0x8CE0
#define DRAW_BUFFER0 0x8825
#define MAX_DRAW_BUFFERS 0x8824
#define GL_AUX0_ 0x0409

typedef void (*GenFramebuffers)(GLsizei, GLuint *);
typedef void (*BindFramebuffer)(GLenum, GLuint);
typedef void (*DeleteFramebuffers)(GLsizei, const GLuint *);
typedef void (*FramebufferTexture2D)(GLenum, GLenum, GLenum, GLuint, GLint);
typedef void (*DrawBuffers)(GLsizei, const GLenum *);

static GenFramebuffers gen_framebuffers;
static BindFramebuffer bind_framebuffer;
static DeleteFramebuffers delete_framebuffers;
static FramebufferTexture2D framebuffer_texture_2d;
static DrawBuffers draw_buffers;

#define W 16
#define H 8

enum { FL, BL, FR, BR };
static const GLenum BUF[4] = {GL_FRONT_LEFT, GL_BACK_LEFT, GL_FRONT_RIGHT, GL_BACK_RIGHT};
static const char *BUF_NAME[4] = {"FRONT_LEFT", "BACK_LEFT", "FRONT_RIGHT", "BACK_RIGHT"};

struct shape {
    int stereo, dbl;
    const char *name;
};

/* What each name selects if all four buffers exist (GL 4.5 table 17.4). */
static const struct {
    GLenum name;
    const char *label;
    int sel[4];
} NAMES[] = {
    {GL_FRONT_LEFT, "GL_FRONT_LEFT", {1, 0, 0, 0}},
    {GL_FRONT_RIGHT, "GL_FRONT_RIGHT", {0, 0, 1, 0}},
    {GL_BACK_LEFT, "GL_BACK_LEFT", {0, 1, 0, 0}},
    {GL_BACK_RIGHT, "GL_BACK_RIGHT", {0, 0, 0, 1}},
    {GL_FRONT, "GL_FRONT", {1, 0, 1, 0}},
    {GL_BACK, "GL_BACK", {0, 1, 0, 1}},
    {GL_LEFT, "GL_LEFT", {1, 1, 0, 0}},
    {GL_RIGHT, "GL_RIGHT", {0, 0, 1, 1}},
    {GL_FRONT_AND_BACK, "GL_FRONT_AND_BACK", {1, 1, 1, 1}},
};
#define N_NAMES (sizeof NAMES / sizeof NAMES[0])

static int allocated(struct shape s, int b)
{
    switch (b) {
    case FL: return 1;
    case BL: return s.dbl;
    case FR: return s.stereo;
    default: return s.stereo && s.dbl;
    }
}

static GLint get_int(GLenum pname)
{
    GLint v = -1;
    glGetIntegerv(pname, &v);
    return v;
}

static void clear(float r, float g, float b)
{
    glClearColor(r, g, b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

/* The colour at the centre of buffer b (RGB; alpha is not compared: the
 * visuals have none). Restores the read buffer. */
static void pixel(int b, unsigned char out[3])
{
    unsigned char px[4] = {0, 0, 0, 0};
    GLint prev = get_int(GL_READ_BUFFER);
    glReadBuffer(BUF[b]);
    glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    glReadBuffer((GLenum)prev);
    memcpy(out, px, 3);
}

static int is(const unsigned char px[3], int r, int g, int b)
{
    return px[0] == r && px[1] == g && px[2] == b;
}

static void drain_errors(const char *where)
{
    GLenum e;
    int n = 0;
    while ((e = glGetError()) != GL_NO_ERROR && n++ < 8) {
        CHECK(e == GL_NO_ERROR, "%s: unexpected GL error 0x%x", where, e);
    }
}

static void reset(GLenum initial)
{
    glDrawBuffer(GL_FRONT_AND_BACK);
    clear(0, 0, 0);
    glDrawBuffer(initial);
    drain_errors("reset");
}

static void draw_buffer_table(struct shape s)
{
    GLenum initial = s.dbl ? GL_BACK : GL_FRONT;
    EXPECT(get_int(GL_DRAW_BUFFER) == (GLint)initial, "%s: initial draw buffer 0x%x", s.name,
          get_int(GL_DRAW_BUFFER));
    EXPECT(get_int(GL_READ_BUFFER) == (GLint)initial, "%s: initial read buffer 0x%x", s.name,
          get_int(GL_READ_BUFFER));
    for (unsigned i = 0; i < N_NAMES; i++) {
        int want[4], any = 0;
        for (int b = 0; b < 4; b++) {
            want[b] = NAMES[i].sel[b] && allocated(s, b);
            any |= want[b];
        }
        reset(initial);
        glDrawBuffer(NAMES[i].name);
        GLenum err = glGetError();
        printf("%s glDrawBuffer(%s): error 0x%x GL_DRAW_BUFFER 0x%x\n", s.name, NAMES[i].label,
               err, get_int(GL_DRAW_BUFFER));
        if (!any) {
            EXPECT(err == GL_INVALID_OPERATION, "%s %s: error 0x%x", s.name, NAMES[i].label, err);
            EXPECT(get_int(GL_DRAW_BUFFER) == (GLint)initial, "%s %s: state changed to 0x%x",
                  s.name, NAMES[i].label, get_int(GL_DRAW_BUFFER));
            /* Drawing still goes where it went before the failed call. */
            clear(1, 1, 1);
            for (int b = 0; b < 4; b++) {
                if (!allocated(s, b)) continue;
                unsigned char px[3];
                pixel(b, px);
                int lit = is(px, 255, 255, 255);
                printf("%s after failed %s: %s lit %d\n", s.name, NAMES[i].label, BUF_NAME[b],
                       lit);
                int in_initial = (b == BL || b == BR) == (initial == GL_BACK);
                EXPECT(lit == in_initial, "%s after failed %s: %s lit=%d", s.name,
                      NAMES[i].label, BUF_NAME[b], lit);
            }
            continue;
        }
        EXPECT(err == GL_NO_ERROR, "%s %s: error 0x%x", s.name, NAMES[i].label, err);
        EXPECT(get_int(GL_DRAW_BUFFER) == (GLint)NAMES[i].name, "%s %s: GL_DRAW_BUFFER 0x%x",
              s.name, NAMES[i].label, get_int(GL_DRAW_BUFFER));
        clear(1.0f, 0.5f, 0.25f);
        for (int b = 0; b < 4; b++) {
            if (!allocated(s, b)) continue;
            unsigned char px[3];
            pixel(b, px);
            int lit = is(px, 255, 128, 64);
            printf("%s glDrawBuffer(%s): %s lit %d\n", s.name, NAMES[i].label, BUF_NAME[b], lit);
            EXPECT(lit == want[b], "%s %s: %s is %d,%d,%d", s.name, NAMES[i].label, BUF_NAME[b],
                  px[0], px[1], px[2]);
        }
    }
    /* GL_NONE draws nowhere. */
    reset(initial);
    glDrawBuffer(GL_NONE);
    clear(1, 1, 1);
    for (int b = 0; b < 4; b++) {
        if (!allocated(s, b)) continue;
        unsigned char px[3];
        pixel(b, px);
        EXPECT(is(px, 0, 0, 0), "%s GL_NONE drew into %s", s.name, BUF_NAME[b]);
    }
    /* Not buffer names: INVALID_ENUM; aux buffers and attachments: INVALID_OPERATION. */
    const struct {
        GLenum value, error;
    } bad[] = {{0x1234, GL_INVALID_ENUM},
               {GL_TEXTURE_2D, GL_INVALID_ENUM},
               {GL_AUX0_, GL_INVALID_OPERATION},
               {COLOR_ATTACHMENT0, GL_INVALID_OPERATION}};
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        reset(initial);
        glDrawBuffer(bad[i].value);
        GLenum e = glGetError();
        printf("%s glDrawBuffer(0x%x): error 0x%x\n", s.name, bad[i].value, e);
        EXPECT(e == bad[i].error, "%s glDrawBuffer(0x%x): 0x%x", s.name, bad[i].value, e);
        glReadBuffer(bad[i].value);
        e = glGetError();
        printf("%s glReadBuffer(0x%x): error 0x%x\n", s.name, bad[i].value, e);
        EXPECT(e == bad[i].error, "%s glReadBuffer(0x%x): 0x%x", s.name, bad[i].value, e);
        EXPECT(glGetError() == GL_NO_ERROR, "%s: one error per call", s.name);
        EXPECT(get_int(GL_DRAW_BUFFER) == (GLint)initial, "%s: draw state after 0x%x", s.name,
              bad[i].value);
        EXPECT(get_int(GL_READ_BUFFER) == (GLint)initial, "%s: read state after 0x%x", s.name,
              bad[i].value);
    }
    glDrawBuffer(initial);
    glReadBuffer(initial);
    drain_errors("table end");
}

static void read_buffer_names(void)
{
    const float color[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
    for (int b = 0; b < 4; b++) {
        glDrawBuffer(BUF[b]);
        clear(color[b][0], color[b][1], color[b][2]);
    }
    const struct {
        GLenum name;
        int buffer;
    } want[] = {{GL_FRONT_LEFT, FL}, {GL_FRONT, FL}, {GL_LEFT, FL}, {GL_FRONT_AND_BACK, FL},
                {GL_BACK_LEFT, BL},  {GL_BACK, BL},  {GL_FRONT_RIGHT, FR}, {GL_RIGHT, FR},
                {GL_BACK_RIGHT, BR}};
    for (unsigned i = 0; i < sizeof want / sizeof want[0]; i++) {
        glReadBuffer(want[i].name);
        CHECK(get_int(GL_READ_BUFFER) == (GLint)want[i].name, "GL_READ_BUFFER after 0x%x",
              want[i].name);
        unsigned char px[4];
        glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
        const float *c = color[want[i].buffer];
        CHECK(is(px, (int)(c[0] * 255), (int)(c[1] * 255), (int)(c[2] * 255)),
              "glReadBuffer(0x%x) read %d,%d,%d", want[i].name, px[0], px[1], px[2]);
    }
    glReadBuffer(GL_BACK);
    glDrawBuffer(GL_BACK);
    drain_errors("read names");
}

static void draw_buffers_rules(struct shape s)
{
    GLint max = get_int(MAX_DRAW_BUFFERS);
    if (s.stereo && s.dbl) {
        GLenum both[2] = {GL_BACK_LEFT, GL_BACK_RIGHT};
        draw_buffers(2, both);
        CHECK(glGetError() == GL_NO_ERROR, "glDrawBuffers(BACK_LEFT, BACK_RIGHT)");
        CHECK(get_int(DRAW_BUFFER0) == GL_BACK_LEFT, "GL_DRAW_BUFFER0");
        CHECK(get_int(DRAW_BUFFER0 + 1) == GL_BACK_RIGHT, "GL_DRAW_BUFFER1");
        CHECK(get_int(GL_DRAW_BUFFER) == GL_BACK_LEFT, "GL_DRAW_BUFFER is buffer 0");
        GLenum front[1] = {GL_FRONT};
        draw_buffers(1, front);
        CHECK(glGetError() == GL_INVALID_ENUM, "glDrawBuffers(GL_FRONT)");
        GLenum twice[2] = {GL_BACK_LEFT, GL_BACK_LEFT};
        draw_buffers(2, twice);
        CHECK(glGetError() == GL_INVALID_OPERATION, "a buffer twice");
        GLenum many[64];
        for (int i = 0; i < 64; i++) many[i] = GL_NONE;
        if (max < 64) {
            draw_buffers(max + 1, many);
            CHECK(glGetError() == GL_INVALID_VALUE, "n > GL_MAX_DRAW_BUFFERS");
        }
        CHECK(get_int(DRAW_BUFFER0 + 1) == GL_BACK_RIGHT, "unchanged after the errors");
    } else if (!s.stereo && s.dbl) {
        GLenum right[1] = {GL_BACK_RIGHT};
        draw_buffers(1, right);
        GLenum e = glGetError();
        printf("%s glDrawBuffers(GL_BACK_RIGHT): error 0x%x\n", s.name, e);
        EXPECT(e == GL_INVALID_OPERATION, "%s: glDrawBuffers(GL_BACK_RIGHT)", s.name);
    }
    glDrawBuffer(s.dbl ? GL_BACK : GL_FRONT);
    drain_errors("draw buffers");
}

/* glPushAttrib/glPopAttrib save and restore the draw buffer
 * (GL_COLOR_BUFFER_BIT) and the read buffer (GL_PIXEL_MODE_BIT). */
static void attribute_stack(void)
{
    glDrawBuffer(GL_BACK_LEFT);
    glReadBuffer(GL_FRONT_RIGHT);
    glPushAttrib(GL_COLOR_BUFFER_BIT | GL_PIXEL_MODE_BIT);
    glDrawBuffer(GL_BACK_RIGHT);
    glReadBuffer(GL_BACK_LEFT);
    CHECK(get_int(GL_DRAW_BUFFER) == GL_BACK_RIGHT, "changed inside the push");
    glPopAttrib();
    CHECK(get_int(GL_DRAW_BUFFER) == GL_BACK_LEFT, "glPopAttrib restores GL_DRAW_BUFFER: 0x%x",
          get_int(GL_DRAW_BUFFER));
    CHECK(get_int(GL_READ_BUFFER) == GL_FRONT_RIGHT, "glPopAttrib restores GL_READ_BUFFER: 0x%x",
          get_int(GL_READ_BUFFER));
    glDrawBuffer(GL_BACK);
    clear(0, 0, 0);
    glDrawBuffer(GL_BACK_LEFT);
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    glDrawBuffer(GL_BACK);
    glPopAttrib();
    clear(1, 0, 0);
    unsigned char px[3];
    pixel(BL, px);
    CHECK(is(px, 255, 0, 0), "after the pop, drawing reaches back-left");
    pixel(BR, px);
    CHECK(is(px, 0, 0, 0), "and not back-right");
    /* A push without the colour bit leaves the draw buffer alone. */
    glPushAttrib(GL_CURRENT_BIT);
    glDrawBuffer(GL_BACK_RIGHT);
    glPopAttrib();
    CHECK(get_int(GL_DRAW_BUFFER) == GL_BACK_RIGHT, "GL_CURRENT_BIT does not cover it");
    glDrawBuffer(GL_BACK);
    glReadBuffer(GL_BACK);
    drain_errors("attribute stack");
}

static void one_swap_presents_both_eyes(Display *display, Window win)
{
    glDrawBuffer(GL_BACK_LEFT);
    clear(1, 0, 0);
    glDrawBuffer(GL_BACK_RIGHT);
    clear(0, 0, 1);
    glXSwapBuffers(display, win);
    unsigned char px[3];
    pixel(FL, px);
    CHECK(is(px, 255, 0, 0), "front-left after the swap is %d,%d,%d", px[0], px[1], px[2]);
    pixel(FR, px);
    CHECK(is(px, 0, 0, 255), "front-right after the swap is %d,%d,%d", px[0], px[1], px[2]);
    CHECK(get_int(GL_DRAW_BUFFER) == GL_BACK_RIGHT, "the draw state survives the swap");
    clear(0, 1, 0);
    pixel(FR, px);
    CHECK(is(px, 0, 0, 255), "drawing the back must not touch the front");
    pixel(BR, px);
    CHECK(is(px, 0, 255, 0), "back-right drawn");
    glXSwapBuffers(display, win);
    pixel(FR, px);
    CHECK(is(px, 0, 255, 0), "front-right after the second swap");
    glDrawBuffer(GL_BACK);
    drain_errors("swap");
}

static void framebuffer_bindings(void)
{
    CHECK(get_int(DRAW_FRAMEBUFFER_BINDING) == 0, "the default framebuffer is 0");
    CHECK(get_int(READ_FRAMEBUFFER_BINDING) == 0, "the default read framebuffer is 0");
    /* The program's own framebuffer object works as usual. */
    GLuint tex, fbo;
    glGenTextures(1, &tex);
    CHECK(tex < 1000, "glGenTextures gives a small name as without the layer (%u)", tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    gen_framebuffers(1, &fbo);
    bind_framebuffer(FRAMEBUFFER, fbo);
    framebuffer_texture_2d(FRAMEBUFFER, COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    CHECK(get_int(DRAW_FRAMEBUFFER_BINDING) == (GLint)fbo, "own framebuffer bound");
    CHECK(get_int(GL_DRAW_BUFFER) == COLOR_ATTACHMENT0, "own framebuffer's draw buffer");
    clear(0, 1, 1);
    unsigned char px[4];
    glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    CHECK(is(px, 0, 255, 255), "drawing into the program's framebuffer object");
    /* Framebuffer 0 is the (emulated) default framebuffer again. */
    bind_framebuffer(FRAMEBUFFER, 0);
    CHECK(get_int(DRAW_FRAMEBUFFER_BINDING) == 0, "back on framebuffer 0");
    CHECK(get_int(GL_DRAW_BUFFER) == GL_BACK, "framebuffer 0's draw buffer");
    glDrawBuffer(GL_BACK_LEFT);
    clear(1, 0, 1);
    unsigned char c[3];
    pixel(BL, c);
    CHECK(is(c, 255, 0, 255), "framebuffer 0 draws into back-left");
    /* Deleting the bound framebuffer reverts to framebuffer 0. */
    bind_framebuffer(FRAMEBUFFER, fbo);
    delete_framebuffers(1, &fbo);
    CHECK(get_int(DRAW_FRAMEBUFFER_BINDING) == 0, "deleted: framebuffer 0 again");
    clear(1, 1, 0);
    pixel(BL, c);
    CHECK(is(c, 255, 255, 0), "after the delete, drawing reaches back-left");
    /* Texture names the program never generated are its own. */
    glBindTexture(GL_TEXTURE_2D, 2);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glBindTexture(GL_TEXTURE_2D, 3);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glBindTexture(GL_TEXTURE_2D, 0);
    clear(0, 0, 1);
    pixel(BL, c);
    CHECK(is(c, 0, 0, 255), "hard-coded texture names leave the stereo buffers alone");
    glDeleteTextures(1, &tex);
    glDrawBuffer(GL_BACK);
    drain_errors("bindings");
}

/* A visual without alpha reads alpha 1.0; without stencil, the stencil
 * test passes (GL's rules for a buffer the framebuffer lacks). */
static void missing_buffers(struct shape s)
{
    GLint alpha_bits = get_int(GL_ALPHA_BITS), stencil_bits = get_int(GL_STENCIL_BITS);
    printf("%s: GL_ALPHA_BITS %d GL_STENCIL_BITS %d\n", s.name, alpha_bits, stencil_bits);
    glDrawBuffer(s.dbl ? GL_BACK_LEFT : GL_FRONT_LEFT);
    glReadBuffer(s.dbl ? GL_BACK_LEFT : GL_FRONT_LEFT);
    glClearColor(0.2f, 0.4f, 0.6f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    unsigned char px[4];
    glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    printf("%s: cleared to alpha 0, reads %d\n", s.name, px[3]);
    EXPECT(px[3] == (alpha_bits == 0 ? 255 : 0), "%s: alpha %d with %d alpha bits", s.name, px[3],
           alpha_bits);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_NEVER, 0, 0xff);
    glColor3f(1.0f, 1.0f, 1.0f);
    glRectf(-1.0f, -1.0f, 1.0f, 1.0f);
    glDisable(GL_STENCIL_TEST);
    glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    int drawn = px[0] == 255;
    printf("%s: drawn through GL_NEVER stencil %d\n", s.name, drawn);
    EXPECT(drawn == (stencil_bits == 0), "%s: stencil test with %d stencil bits", s.name,
           stencil_bits);
    glDrawBuffer(s.dbl ? GL_BACK : GL_FRONT);
    glReadBuffer(s.dbl ? GL_BACK : GL_FRONT);
    drain_errors("missing buffers");
}

static int run(Display *display, struct shape s)
{
    int attrs[16], n = 0;
    attrs[n++] = GLX_RGBA;
    attrs[n++] = GLX_RED_SIZE;
    attrs[n++] = 8;
    if (s.dbl) attrs[n++] = GLX_DOUBLEBUFFER;
    if (s.stereo) attrs[n++] = GLX_STEREO;
    attrs[n++] = None;
    XVisualInfo *vi = glXChooseVisual(display, DefaultScreen(display), attrs);
    if (vi == NULL) {
        fprintf(stderr, "%s: no visual\n", s.name);
        return 0;
    }
    int dbl = -1, stereo = -1;
    glXGetConfig(display, vi, GLX_DOUBLEBUFFER, &dbl);
    glXGetConfig(display, vi, GLX_STEREO, &stereo);
    CHECK(dbl == s.dbl && stereo == s.stereo, "%s: visual double %d stereo %d", s.name, dbl,
          stereo);
    Window root = RootWindow(display, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(display, root, vi->visual, AllocNone);
    Window win = XCreateWindow(display, root, 0, 0, W, H, 0, vi->depth, InputOutput, vi->visual,
                               CWColormap, &wa);
    XMapWindow(display, win);
    XSync(display, False);
    GLXContext ctx = glXCreateContext(display, vi, NULL, True);
    CHECK(ctx != NULL && glXMakeCurrent(display, win, ctx), "%s: context current", s.name);
    gen_framebuffers = (GenFramebuffers)glXGetProcAddressARB((const GLubyte *)"glGenFramebuffers");
    bind_framebuffer = (BindFramebuffer)glXGetProcAddressARB((const GLubyte *)"glBindFramebuffer");
    delete_framebuffers =
        (DeleteFramebuffers)glXGetProcAddressARB((const GLubyte *)"glDeleteFramebuffers");
    framebuffer_texture_2d =
        (FramebufferTexture2D)glXGetProcAddressARB((const GLubyte *)"glFramebufferTexture2D");
    draw_buffers = (DrawBuffers)glXGetProcAddressARB((const GLubyte *)"glDrawBuffers");

    GLboolean st = GL_FALSE, db = GL_FALSE;
    glGetBooleanv(GL_STEREO, &st);
    glGetBooleanv(GL_DOUBLEBUFFER, &db);
    CHECK(st == s.stereo && db == s.dbl, "%s: GL_STEREO %d GL_DOUBLEBUFFER %d", s.name, st, db);
    printf("%s: GL_STEREO %d GL_DOUBLEBUFFER %d GL_DRAW_BUFFER 0x%x GL_READ_BUFFER 0x%x "
           "framebuffer %d\n",
           s.name, st, db, get_int(GL_DRAW_BUFFER), get_int(GL_READ_BUFFER),
           get_int(DRAW_FRAMEBUFFER_BINDING));

    draw_buffer_table(s);
    draw_buffers_rules(s);
    missing_buffers(s);
    if (s.stereo && s.dbl) {
        read_buffer_names();
        attribute_stack();
        one_swap_presents_both_eyes(display, win);
        framebuffer_bindings();
    }
    glXMakeCurrent(display, None, NULL);
    glXDestroyContext(display, ctx);
    XDestroyWindow(display, win);
    XFreeColormap(display, wa.colormap);
    XFree(vi);
    return 1;
}

typedef GLXContext (*CreateContextAttribs)(Display *, GLXFBConfig, GLXContext, Bool,
                                           const int *);

/* A double-buffered stereo configuration and a core-profile context. */
static int run_core(Display *display)
{
    const struct shape s = {1, 1, "stereo core profile"};
    int attrs[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True, GLX_STEREO, True,
                   GLX_RED_SIZE, 8, None};
    int n = 0;
    GLXFBConfig *configs = glXChooseFBConfig(display, DefaultScreen(display), attrs, &n);
    if (configs == NULL || n == 0) {
        fprintf(stderr, "no stereo FBConfig\n");
        return 0;
    }
    int stereo = -1;
    glXGetFBConfigAttrib(display, configs[0], GLX_STEREO, &stereo);
    CHECK(stereo == 1, "GLX_STEREO of the chosen configuration: %d", stereo);
    XVisualInfo *vi = glXGetVisualFromFBConfig(display, configs[0]);
    CHECK(vi != NULL, "visual of the configuration");
    if (vi == NULL) return 0;
    Window root = RootWindow(display, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(display, root, vi->visual, AllocNone);
    Window win = XCreateWindow(display, root, 0, 0, W, H, 0, vi->depth, InputOutput, vi->visual,
                               CWColormap, &wa);
    XMapWindow(display, win);
    XSync(display, False);
    CreateContextAttribs create = (CreateContextAttribs)glXGetProcAddressARB(
        (const GLubyte *)"glXCreateContextAttribsARB");
    const int ctx_attrs[] = {0x2091 /* MAJOR */, 3, 0x2092 /* MINOR */, 3,
                             0x9126 /* PROFILE_MASK */, 0x1 /* CORE */, None};
    GLXContext ctx = create ? create(display, configs[0], NULL, True, ctx_attrs) : NULL;
    CHECK(ctx != NULL && glXMakeContextCurrent(display, win, win, ctx), "core context current");
    if (ctx == NULL) return 0;
    draw_buffers = (DrawBuffers)glXGetProcAddressARB((const GLubyte *)"glDrawBuffers");
    GLint profile = 0;
    glGetIntegerv(0x9126 /* GL_CONTEXT_PROFILE_MASK */, &profile);
    CHECK(profile == 1, "a core-profile context (mask %d)", profile);
    GLboolean st = GL_FALSE;
    glGetBooleanv(GL_STEREO, &st);
    CHECK(st == GL_TRUE, "GL_STEREO in the core context");
    draw_buffer_table(s);
    draw_buffers_rules(s);
    read_buffer_names();
    one_swap_presents_both_eyes(display, win);
    glXMakeContextCurrent(display, None, None, NULL);
    glXDestroyContext(display, ctx);
    XDestroyWindow(display, win);
    XFreeColormap(display, wa.colormap);
    XFree(vi);
    XFree(configs);
    return 1;
}

int main(int argc, char **argv)
{
    int stereo = argc > 1 && strcmp(argv[1], "stereo") == 0;
    int mono = argc > 1 && strcmp(argv[1], "mono") == 0;
    int core = argc > 1 && strcmp(argv[1], "core") == 0;
    if (!stereo && !mono && !core) {
        fprintf(stderr, "usage: glx_draw_buffers stereo|mono|core\n");
        return 1;
    }
    checking = stereo || core;
    Display *display = XOpenDisplay(NULL);
    if (display == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    const struct shape shapes[] = {{1, 1, "stereo double-buffered"},
                                   {1, 0, "stereo single-buffered"},
                                   {0, 1, "mono double-buffered"},
                                   {0, 0, "mono single-buffered"}};
    if (core) {
        if (!run_core(display)) return 2;
    } else {
        for (unsigned i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
            if (shapes[i].stereo != stereo) continue;
            if (!run(display, shapes[i])) return 2;
        }
    }
    XCloseDisplay(display);
    return SUMMARY();
}

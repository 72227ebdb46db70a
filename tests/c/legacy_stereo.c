/*
 * A legacy GLX stereo program, as HP's stereo guide (seed 000 §3-4) writes
 * one: glXChooseVisual with GLX_STEREO, glDrawBuffer per eye, one
 * glXSwapBuffers. Unmodified: it knows nothing of glstereo and links only
 * -lGL -lX11. Run it under glstereo-run.
 *
 *   legacy_stereo [WIDTH HEIGHT [single]]
 *
 * It draws the RedBlue frame (grey 0.2 background; left eye: blue rectangle
 * (-0.8,-0.8)-(0.2,0.2); right eye: red rectangle (-0.2,-0.2)-(0.8,0.8)),
 * swaps, prints what GL reported and "ready 0x<window>", then reads a line
 * on stdin (the test grabs the window meanwhile): "resize W H" resizes the
 * window, sets the viewport as a reshape handler would, draws and presents
 * again; "wmresize W H" resizes it as a window manager would for a program
 * without a reshape handler (the viewport stays), draws and presents again;
 * "names" deletes every texture, renderbuffer and framebuffer name in
 * 1..65536 and in the top 65536 names below 2^31 and 2^32 (a program
 * cleaning up names it never made, or guessed), binds and fills texture
 * names 1..64 it never generated (GL 1.x style), checks its own generated
 * texture went with the deletes, then draws and presents again; anything
 * else (or EOF) exits 0. With "single" the visual is
 * single-buffered: it draws GL_FRONT_LEFT / GL_FRONT_RIGHT and calls
 * glFlush instead of swapping. Without a stereo visual it says so on stderr
 * and exits 2, as the guide advises.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

typedef void (*delete_fn)(GLsizei, const GLuint *);

/* glDelete* of every name in [first, first + count). */
static void delete_range(delete_fn del, GLuint first, GLuint count)
{
    static GLuint names[4096];
    GLuint done = 0;
    while (done < count) {
        GLuint n = count - done < 4096 ? count - done : 4096, i;
        for (i = 0; i < n; i++) {
            names[i] = first + done + i;
        }
        del((GLsizei)n, names);
        done += n;
    }
}

/* A hostile cleanup: deletes names the program never made and binds
 * texture names it never generated. Prints "names own_texture_deleted N". */
static void hostile_names(void)
{
    delete_fn del_tex = glDeleteTextures, del_rb, del_fb;
    void (*gen)(GLsizei, GLuint *) = glGenTextures;
    const GLuint tops[3] = {1, 0x80000000u - 65536, 0xFFFFFFFFu - 65536};
    GLuint own = 0, t, k;
    int own_deleted;
    unsigned char texel[16] = {0};
    __GLXextFuncPtr p = glXGetProcAddressARB((const GLubyte *)"glDeleteRenderbuffers");
    memcpy(&del_rb, &p, sizeof del_rb);
    p = glXGetProcAddressARB((const GLubyte *)"glDeleteFramebuffers");
    memcpy(&del_fb, &p, sizeof del_fb);
    gen(1, &own);
    for (k = 0; k < 3; k++) {
        delete_range(del_tex, tops[k], 65536);
        delete_range(del_rb, tops[k], 65536);
        delete_range(del_fb, tops[k], 65536);
    }
    own_deleted = !glIsTexture(own);
    for (t = 1; t <= 64; t++) {
        glBindTexture(GL_TEXTURE_2D, t);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    printf("names own_texture_deleted %d\n", own_deleted);
}

static void redblue_frame(int single)
{
    glDrawBuffer(single ? GL_FRONT : GL_BACK);
    glClearColor(0.2f, 0.2f, 0.2f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);

    glDrawBuffer(single ? GL_FRONT_LEFT : GL_BACK_LEFT);
    glColor3f(0.0f, 0.0f, 1.0f);
    glRectf(-0.8f, -0.8f, 0.2f, 0.2f);

    glDrawBuffer(single ? GL_FRONT_RIGHT : GL_BACK_RIGHT);
    glColor3f(1.0f, 0.0f, 0.0f);
    glRectf(-0.2f, -0.2f, 0.8f, 0.8f);
}

int main(int argc, char **argv)
{
    int width = argc > 2 ? atoi(argv[1]) : 160;
    int height = argc > 2 ? atoi(argv[2]) : 120;
    int single = argc > 3 && strcmp(argv[3], "single") == 0;
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                        GLX_BLUE_SIZE, 1, GLX_DEPTH_SIZE, 1, GLX_STEREO, None};
    if (single) {
        attributes[1] = GLX_USE_GL; /* no GLX_DOUBLEBUFFER */
    }
    Display *display = XOpenDisplay(NULL);
    if (display == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    XVisualInfo *vi = glXChooseVisual(display, DefaultScreen(display), attributes);
    if (vi == NULL) {
        fprintf(stderr, "no stereo visual: windowed OpenGL stereo is not supported\n");
        return 2;
    }
    int glx_stereo = 0;
    glXGetConfig(display, vi, GLX_STEREO, &glx_stereo);

    Window root = RootWindow(display, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(display, root, vi->visual, AllocNone);
    wa.border_pixel = 0;
    Window win = XCreateWindow(display, root, 0, 0, (unsigned)width, (unsigned)height, 0, vi->depth,
                               InputOutput, vi->visual, CWColormap | CWBorderPixel, &wa);
    XStoreName(display, win, "legacy_stereo");
    XMapWindow(display, win);
    XSync(display, False);

    GLXContext ctx = glXCreateContext(display, vi, NULL, True);
    if (ctx == NULL || !glXMakeCurrent(display, win, ctx)) {
        fprintf(stderr, "cannot make a GL context current\n");
        return 1;
    }
    GLboolean stereo = GL_FALSE;
    glGetBooleanv(GL_STEREO, &stereo);
    GLint fb = -1, draw = -1;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
    glGetIntegerv(GL_DRAW_BUFFER, &draw);

    for (;;) {
        redblue_frame(single);
        if (single) {
            glFlush();
        } else {
            glXSwapBuffers(display, win);
        }
        glFinish();

        printf("glx_stereo %d gl_stereo %d framebuffer %d draw_buffer 0x%x error 0x%x\n",
               glx_stereo, stereo, fb, (unsigned)draw, glGetError());
        printf("ready 0x%lx\n", (unsigned long)win);
        fflush(stdout);

        char line[64];
        int w, h;
        if (fgets(line, sizeof line, stdin) == NULL) {
            break;
        }
        if (strncmp(line, "names", 5) == 0) {
            hostile_names();
            continue;
        }
        int reshape = sscanf(line, "resize %d %d", &w, &h) == 2;
        if (!reshape && sscanf(line, "wmresize %d %d", &w, &h) != 2) {
            break;
        }
        XResizeWindow(display, win, (unsigned)w, (unsigned)h);
        XSync(display, False);
        if (reshape) {
            glViewport(0, 0, w, h);
        }
    }
    glXMakeCurrent(display, None, NULL);
    glXDestroyContext(display, ctx);
    XDestroyWindow(display, win);
    XFree(vi);
    XCloseDisplay(display);
    return 0;
}

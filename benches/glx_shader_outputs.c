/*
 * What the duplicated fragment output costs (run under glstereo-run by
 * benches/glx_shader_outputs.sh). One process, two windows of the same
 * size: a stereo one (emulated by the layer) and a mono one (the driver's
 * own, no layer work), each with a GL 3.3 core context. Measured in
 * alternating batches, medians of per-item times:
 *
 *   link     glLinkProgram of a program with `layout(location = 0) out
 *            vec4`: in the stereo context (linked twice, the second time
 *            with the copies) / in the mono context (linked once)
 *   draw     a full-window quad with a fragment-heavy shader under GL_BACK:
 *            the relinked user-output shader writing both eyes in one pass /
 *            the same shader with gl_FragColor (GL's own broadcast to both
 *            draw buffers, no copies), both in the stereo context
 *   per-eye  the alternative design, a pass per eye (GL_BACK_LEFT, draw,
 *            GL_BACK_RIGHT, draw) / the one-pass relinked draw
 *   fbo      the relinked program drawing into the program's own one-
 *            attachment framebuffer object (copies written to no buffer) /
 *            the same source linked once in the mono context, same FBO size
 *   control  the gl_FragColor program (never relinked) into those two
 *            FBOs: what the two contexts differ by without any copies
 *
 *   glx_shader_outputs WIDTH HEIGHT ROUNDS
 */
#define _POSIX_C_SOURCE 199309L
#define GL_GLEXT_PROTOTYPES 1
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

typedef GLXContext (*CreateContextAttribs)(Display *, GLXFBConfig, GLXContext, Bool,
                                           const int *);

static int W, H;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    return v[n / 2];
}

struct win {
    Window w;
    GLXContext ctx;
};

static int open_win(Display *d, int stereo, int x, struct win *out)
{
    int attrs[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DOUBLEBUFFER, True, GLX_STEREO, stereo,
                   GLX_RED_SIZE, 8, None};
    int n = 0;
    GLXFBConfig *c = glXChooseFBConfig(d, DefaultScreen(d), attrs, &n);
    if (c == NULL || n == 0) return 0;
    XVisualInfo *vi = glXGetVisualFromFBConfig(d, c[0]);
    Window root = RootWindow(d, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(d, root, vi->visual, AllocNone);
    out->w = XCreateWindow(d, root, x, 0, W, H, 0, vi->depth, InputOutput, vi->visual,
                           CWColormap, &wa);
    XMapWindow(d, out->w);
    XSync(d, False);
    CreateContextAttribs create = (CreateContextAttribs)glXGetProcAddressARB(
        (const GLubyte *)"glXCreateContextAttribsARB");
    const int ca[] = {0x2091, 3, 0x2092, 3, 0x9126, 1, None};
    out->ctx = create(d, c[0], NULL, True, ca);
    XFree(vi);
    XFree(c);
    return out->ctx != NULL;
}

static const char *VS = "#version 330 core\n"
                        "layout(location = 0) in vec2 pos;\n"
                        "void main() { gl_Position = vec4(pos, 0.0, 1.0); }\n";
#define HEAVY                                                   \
    "    vec2 p = gl_FragCoord.xy * 0.01; float a = 0.0;\n"     \
    "    for (int i = 0; i < 32; i++) a += sin(p.x * float(i)) * cos(p.y + a);\n"
static const char *FS_OUT = "#version 330 core\n"
                            "layout(location = 0) out vec4 color;\n"
                            "void main() {\n" HEAVY "    color = vec4(fract(a), 0.5, 0.25, 1.0);\n}\n";
static const char *FS_BUILTIN = "#version 130\n"
                                "void main() {\n" HEAVY
                                "    gl_FragColor = vec4(fract(a), 0.5, 0.25, 1.0);\n}\n";

static GLuint shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    return s;
}

/* A program from VS + fs, linked; *ms is the link time. */
static GLuint link(const char *fs, double *ms)
{
    GLuint p = glCreateProgram(), v = shader(GL_VERTEX_SHADER, VS),
           f = shader(GL_FRAGMENT_SHADER, fs);
    glAttachShader(p, v);
    glAttachShader(p, f);
    double t = now();
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok); /* waits for the link */
    if (ms) *ms = now() - t;
    glDeleteShader(v);
    glDeleteShader(f);
    if (!ok) {
        fprintf(stderr, "link failed\n");
        exit(1);
    }
    return p;
}

static void quad(void)
{
    static const float q[] = {-1, -1, 1, -1, -1, 1, 1, 1};
    GLuint vao, vbo;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof q, q, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, 0);
    glEnableVertexAttribArray(0);
}

static GLuint user_fbo(void)
{
    GLuint tex, fbo;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return fbo;
}

/* One timed draw (finished). */
static double draw(GLuint prog, int per_eye)
{
    glUseProgram(prog);
    double t = now();
    if (per_eye) {
        glDrawBuffer(GL_BACK_LEFT);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        glDrawBuffer(GL_BACK_RIGHT);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        glDrawBuffer(GL_BACK);
    } else {
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
    glFinish();
    return now() - t;
}

#define MAXR 200

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: glx_shader_outputs WIDTH HEIGHT ROUNDS\n");
        return 1;
    }
    W = atoi(argv[1]);
    H = atoi(argv[2]);
    int rounds = atoi(argv[3]);
    if (rounds < 3 || rounds > MAXR) rounds = 10;
    Display *d = XOpenDisplay(NULL);
    struct win st, mo;
    if (d == NULL || !open_win(d, 1, 0, &st) || !open_win(d, 0, W, &mo)) {
        fprintf(stderr, "no display or context\n");
        return 2;
    }
    glXMakeContextCurrent(d, st.w, st.w, st.ctx);
    GLboolean stereo = 0;
    glGetBooleanv(GL_STEREO, &stereo);
    if (!stereo) {
        fprintf(stderr, "the stereo window is not stereo: run under glstereo-run\n");
        return 2;
    }
    quad();
    GLuint p_out = link(FS_OUT, NULL), p_builtin = link(FS_BUILTIN, NULL), s_fbo = user_fbo();
    glDrawBuffer(GL_BACK);
    glXMakeContextCurrent(d, mo.w, mo.w, mo.ctx);
    quad();
    GLuint m_out = link(FS_OUT, NULL), m_builtin = link(FS_BUILTIN, NULL), m_fbo = user_fbo();

    static double link_s[MAXR], link_m[MAXR], d_out[MAXR], d_builtin[MAXR], d_eye[MAXR],
        f_s[MAXR], f_m[MAXR], c_s[MAXR], c_m[MAXR];
    for (int r = -1; r < rounds; r++) { /* round -1 warms up */
        double a, b;
        glXMakeContextCurrent(d, st.w, st.w, st.ctx);
        glDeleteProgram(link(FS_OUT, &a));
        double o = draw(p_out, 0), bi = draw(p_builtin, 0), e = draw(p_out, 1);
        glBindFramebuffer(GL_FRAMEBUFFER, s_fbo);
        double fs = draw(p_out, 0), cs = draw(p_builtin, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glXMakeContextCurrent(d, mo.w, mo.w, mo.ctx);
        glDeleteProgram(link(FS_OUT, &b));
        glBindFramebuffer(GL_FRAMEBUFFER, m_fbo);
        double fm = draw(m_out, 0), cm = draw(m_builtin, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        if (r < 0) continue;
        link_s[r] = a;
        link_m[r] = b;
        d_out[r] = o;
        d_builtin[r] = bi;
        d_eye[r] = e;
        f_s[r] = fs;
        f_m[r] = fm;
        c_s[r] = cs;
        c_m[r] = cm;
    }
    double ls = median(link_s, rounds), lm = median(link_m, rounds);
    double o = median(d_out, rounds), bi = median(d_builtin, rounds), e = median(d_eye, rounds);
    double fs = median(f_s, rounds), fm = median(f_m, rounds);
    double cs = median(c_s, rounds), cm = median(c_m, rounds);
    printf("link    stereo %.2f ms  mono %.2f ms  ratio %.2f\n", ls, lm, ls / lm);
    printf("draw    user output %.2f ms  gl_FragColor %.2f ms  ratio %.2f\n", o, bi, o / bi);
    printf("per-eye two passes %.2f ms  one relinked pass %.2f ms  ratio %.2f\n", e, o, e / o);
    printf("fbo     relinked %.2f ms  linked once %.2f ms  ratio %.2f\n", fs, fm, fs / fm);
    printf("control gl_FragColor into the FBO: stereo context %.2f ms  mono context %.2f ms  "
           "ratio %.2f\n",
           cs, cm, cs / cm);
    glXMakeContextCurrent(d, None, None, NULL);
    glXDestroyContext(d, st.ctx);
    glXDestroyContext(d, mo.ctx);
    XCloseDisplay(d);
    return 0;
}

/*
 * Frame-loop benchmark for the LD_PRELOAD layer: an ordinary GLX program
 * (links only -lGL -lX11) drawing a light scene in a loop, mono or stereo,
 * timed per frame (draw + glXSwapBuffers + glFinish). Run it as
 * benches/glx_frame_loop.sh does: mono without the layer, mono and stereo
 * under glstereo-run, stereo with --capture.
 *
 *   glx_frame_loop mono|stereo [WIDTH HEIGHT [FRAMES [light|heavy|heavy3d|lit3d|shader3d]]]
 *
 * Light scene: per eye a clear and three rectangles. Heavy scene: per eye
 * a clear and a depth-tested grid of 512 x 512 quads (524 288 triangles)
 * drawn from a vertex buffer, with identity matrices (w = 1: automatic
 * stereo leaves it at the screen). heavy3d: the same grid seen through a
 * perspective projection (glFrustum, w about 2), fixed function; lit3d:
 * heavy3d under fixed-function lighting (a directional and a positional
 * light, specular, the colours through GL_COLOR_MATERIAL);
 * shader3d: heavy3d drawn by a GLSL program (gl_ModelViewProjectionMatrix,
 * the vertex colour), which automatic stereo rewrites. Prints
 * "<mode> <scene> WxH frames N: mean M ms, median D ms, p90 P ms, cpu C ms"
 * (C: the process's CPU time a frame over the timed frames, every thread:
 * what a machine shared with other jobs does not inflate, unlike the
 * frame times; the X server's work is not in it).
 */
#define GL_GLEXT_PROTOTYPES
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* CPU time of the whole process (every thread), in ms. */
static double cpu_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The heavy scene's vertex buffer: GRID x GRID quads, two triangles each,
 * x, y, z and an RGB colour per vertex. */
#define GRID 512
static GLuint heavy_vbo;
static GLsizei heavy_vertices;

static void make_heavy(void)
{
    size_t n = (size_t)GRID * GRID * 6;
    float *v = malloc(n * 6 * sizeof(float));
    if (v == NULL) exit(1);
    float *p = v;
    for (int j = 0; j < GRID; j++) {
        for (int i = 0; i < GRID; i++) {
            static const int corner[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
            for (int k = 0; k < 6; k++) {
                float x = (float)(i + corner[k][0]) / GRID, y = (float)(j + corner[k][1]) / GRID;
                *p++ = x * 1.8f - 0.9f;
                *p++ = y * 1.8f - 0.9f;
                *p++ = 0.5f * (x - 0.5f) * (y - 0.5f);
                *p++ = x;
                *p++ = y;
                *p++ = (float)((i ^ j) & 1);
            }
        }
    }
    glGenBuffers(1, &heavy_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, heavy_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * 6 * sizeof(float)), v, GL_STATIC_DRAW);
    free(v);
    heavy_vertices = (GLsizei)n;
    glVertexPointer(3, GL_FLOAT, 6 * sizeof(float), (const void *)0);
    glColorPointer(3, GL_FLOAT, 6 * sizeof(float), (const void *)(3 * sizeof(float)));
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glEnable(GL_DEPTH_TEST);
}

/* The heavy grid's distance from the eye in heavy3d and shader3d (0: the
 * heavy scene's identity matrices). */
static float heavy_z;

static void heavy(float shift)
{
    glClearColor(0.2f, 0.2f, 0.2f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glLoadIdentity();
    glTranslatef(shift, 0.0f, -heavy_z);
    glDrawArrays(GL_TRIANGLES, 0, heavy_vertices);
}

/* heavy3d's projection; with `shader`, shader3d's program; with `lit`,
 * lit3d's lights. */
static int make_3d(int shader, int lit)
{
    heavy_z = 2.0f;
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.5, 0.5, -0.4, 0.4, 1.0, 10.0);
    glMatrixMode(GL_MODELVIEW);
    if (lit) {
        static const GLfloat pos1[] = {0.5f, 0.5f, -1.0f, 1.0f};
        static const GLfloat spec[] = {0.6f, 0.6f, 0.6f, 1.0f};
        glLoadIdentity();
        glLightfv(GL_LIGHT1, GL_POSITION, pos1);
        glLightfv(GL_LIGHT1, GL_SPECULAR, spec);
        glMaterialfv(GL_FRONT, GL_SPECULAR, spec);
        glMaterialf(GL_FRONT, GL_SHININESS, 16.0f);
        glNormal3f(0.0f, 0.3f, 1.0f);
        glEnable(GL_COLOR_MATERIAL);
        glEnable(GL_NORMALIZE);
        glEnable(GL_LIGHTING);
        glEnable(GL_LIGHT0);
        glEnable(GL_LIGHT1);
    }
    if (!shader) return 1;
    static const char *vs = "#version 130\n"
                            "out vec3 colour;\n"
                            "void main() {\n"
                            "    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;\n"
                            "    colour = gl_Color.rgb;\n"
                            "}\n";
    static const char *fs = "#version 130\n"
                            "in vec3 colour;\n"
                            "out vec4 fragment;\n"
                            "void main() { fragment = vec4(colour, 1.0); }\n";
    GLuint p = glCreateProgram();
    const char *src[2] = {vs, fs};
    GLenum type[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    for (int i = 0; i < 2; i++) {
        GLuint sh = glCreateShader(type[i]);
        glShaderSource(sh, 1, &src[i], NULL);
        glCompileShader(sh);
        glAttachShader(p, sh);
    }
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) return 0;
    glUseProgram(p);
    return 1;
}

static void light(float shift)
{
    glClearColor(0.2f, 0.2f, 0.2f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glColor3f(0.0f, 0.0f, 1.0f);
    glRectf(-0.8f + shift, -0.8f, 0.2f + shift, 0.2f);
    glColor3f(1.0f, 0.0f, 0.0f);
    glRectf(-0.2f + shift, -0.2f, 0.8f + shift, 0.8f);
    glColor3f(0.0f, 1.0f, 0.0f);
    glRectf(-0.1f + shift, -0.9f, 0.1f + shift, -0.5f);
}

int main(int argc, char **argv)
{
    int stereo = argc > 1 && strcmp(argv[1], "stereo") == 0;
    int width = argc > 3 ? atoi(argv[2]) : 1280;
    int height = argc > 3 ? atoi(argv[3]) : 1024;
    int frames = argc > 4 ? atoi(argv[4]) : 200;
    const char *scene_name = argc > 5 ? argv[5] : "light";
    int lit = strcmp(scene_name, "lit3d") == 0;
    int is_3d = strcmp(scene_name, "heavy3d") == 0 || strcmp(scene_name, "shader3d") == 0 || lit;
    int is_heavy = strcmp(scene_name, "heavy") == 0 || is_3d;
    void (*scene)(float) = is_heavy ? heavy : light;
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 16, None, None};
    if (stereo) attributes[4] = GLX_STEREO;
    Display *display = XOpenDisplay(NULL);
    if (display == NULL) return 1;
    XVisualInfo *vi = glXChooseVisual(display, DefaultScreen(display), attributes);
    if (vi == NULL) {
        fprintf(stderr, "no %s visual\n", stereo ? "stereo" : "mono");
        return 2;
    }
    Window root = RootWindow(display, vi->screen);
    XSetWindowAttributes wa = {0};
    wa.colormap = XCreateColormap(display, root, vi->visual, AllocNone);
    Window win = XCreateWindow(display, root, 0, 0, (unsigned)width, (unsigned)height, 0,
                               vi->depth, InputOutput, vi->visual, CWColormap, &wa);
    XMapWindow(display, win);
    XSync(display, False);
    GLXContext ctx = glXCreateContext(display, vi, NULL, True);
    if (ctx == NULL || !glXMakeCurrent(display, win, ctx)) return 1;

    if (is_heavy) make_heavy();
    if (is_3d && !make_3d(strcmp(scene_name, "shader3d") == 0, lit)) {
        fprintf(stderr, "shader3d: the program does not link\n");
        return 3;
    }
    double *t = malloc(sizeof(double) * (size_t)frames);
    for (int warm = 0; warm < 10; warm++) {
        scene(0.0f);
        glXSwapBuffers(display, win);
    }
    glFinish();
    double cpu0 = cpu_ms();
    for (int i = 0; i < frames; i++) {
        double t0 = now_ms();
        float s = (float)(i % 10) * 0.01f;
        if (stereo) {
            glDrawBuffer(GL_BACK_LEFT);
            scene(s);
            glDrawBuffer(GL_BACK_RIGHT);
            scene(-s);
        } else {
            scene(s);
        }
        glXSwapBuffers(display, win);
        glFinish();
        t[i] = now_ms() - t0;
    }
    double cpu = (cpu_ms() - cpu0) / frames;
    double sum = 0;
    for (int i = 0; i < frames; i++) sum += t[i];
    qsort(t, (size_t)frames, sizeof t[0], cmp);
    printf("%s %s %dx%d frames %d: mean %.2f ms, median %.2f ms, p90 %.2f ms, cpu %.3f ms\n",
           stereo ? "stereo" : "mono", is_heavy ? scene_name : "light", width, height, frames, sum / frames, t[frames / 2],
           t[frames * 9 / 10], cpu);
    free(t);
    glXMakeCurrent(display, None, NULL);
    glXDestroyContext(display, ctx);
    XDestroyWindow(display, win);
    XCloseDisplay(display);
    return 0;
}

/* autostereo: a mono fixed-function program shown in stereo by automatic
 * stereo (NVIDIA 3D Vision's way, NV_3dvision_settings), with no stereo
 * code of its own.
 *
 * The scene is three cards on grey: red near (depth 4), green in the middle
 * (8), blue far (16). The program draws it exactly as a mono program does;
 * the library draws each frame once per eye, shifting every vertex by
 * eye * s * (w - convergence) in clip space. Over the frames the separation
 * rises from 0 % (both eyes identical) to 100 %, and the convergence moves
 * from card to card: the card at the convergence depth sits at the screen
 * (same place in both eyes), nearer ones pop out, farther ones recede.
 *
 *   --frames N   frames to render (default 5); with --out DIR each frame's
 *                left.png, right.png and composite.png go to DIR/frameNN/.
 *
 * Run it headless (GLSTEREO_BACKEND=egl or osmesa) or in a window. */
#include <GL/glx.h> /* GLX_* attribute names only */

#include "example.h"
#include "glstereo/nv3dvision.h"

typedef struct card {
    GLubyte color[3];
    double depth;
    double x0, y0, x1, y1; /* extent in the mono view, NDC */
} card;

static const card cards[] = {
    {{230, 20, 20}, 4.0, -0.5, 0.4, 0.3, 0.8},
    {{20, 200, 20}, 8.0, -0.4, -0.2, 0.4, 0.2},
    {{20, 20, 230}, 16.0, -0.3, -0.8, 0.5, -0.4},
};
#define NCARDS (sizeof cards / sizeof cards[0])

/* The mono view: glFrustum(-right, right, -top, top, near, far). */
typedef struct view {
    double right, top, near_clip, far_clip;
} view;

/* The program's mono frame, as it would draw it without stereo. */
static void draw_frame(void *user_data) {
    const view *v = (const view *)user_data;
    glClearColor(0.5f, 0.5f, 0.5f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    for (size_t k = 0; k < NCARDS; ++k) {
        const card *c = &cards[k];
        /* Eye-space corners of the card's NDC extent at its depth. */
        double sx = v->right * c->depth / v->near_clip, sy = v->top * c->depth / v->near_clip;
        glColor3ub(c->color[0], c->color[1], c->color[2]);
        glBegin(GL_QUADS);
        glVertex3d(c->x0 * sx, c->y0 * sy, -c->depth);
        glVertex3d(c->x1 * sx, c->y0 * sy, -c->depth);
        glVertex3d(c->x1 * sx, c->y1 * sy, -c->depth);
        glVertex3d(c->x0 * sx, c->y1 * sy, -c->depth);
        glEnd();
    }
}

int main(int argc, char **argv) {
    /* --frames N is this example's own option; the rest are the shared ones. */
    example_options opt = example_defaults();
    unsigned frames = 5;
    char **shared = calloc((size_t)argc + 1, sizeof *shared);
    if (!shared) return 2;
    int nshared = 0;
    for (int i = 0; i < argc; ++i) {
        if (i > 0 && strcmp(argv[i], "--frames") == 0) {
            char tail;
            if (i + 1 >= argc || sscanf(argv[i + 1], "%u%c", &frames, &tail) != 1 || frames == 0) {
                fprintf(stderr, "--frames wants a positive number\n");
                example_usage(argv[0], "[--frames N]");
                free(shared);
                return 2;
            }
            ++i;
            continue;
        }
        shared[nshared++] = argv[i];
    }
    int parsed = example_parse(nshared, shared, &opt);
    free(shared);
    if (!parsed) return 2;

    gls_display *display;
    gls_result r = gls_display_open(GLS_BACKEND_AUTO, &display);
    if (r != GLS_OK) return example_fail("gls_display_open", r);

    /* A mono program's visual: no GLX_STEREO. */
    int attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                     GLX_BLUE_SIZE, 1, GLX_DEPTH_SIZE, 16, None};
    gls_config *config;
    r = gls_config_choose(display, attribs, &config);
    if (r != GLS_OK) return example_fail("gls_config_choose", r);

    /* The one stereo request: an auto-stereo capable surface. */
    const int32_t surface_attribs[] = {GLS_SURFACE_AUTO_STEREO, 1, GLS_SURFACE_ATTRIB_NONE};
    gls_surface *surface;
    r = gls_surface_create_with_attribs(display, config, opt.width, opt.height, surface_attribs, &surface);
    if (r != GLS_OK) return example_fail("gls_surface_create_with_attribs", r);
    if (example_apply_mode(surface, &opt)) return 1;
    if ((r = gls_make_current(surface)) != GLS_OK) return example_fail("gls_make_current", r);

    GLfloat separation, convergence;
    glGetFloatv(GL_STEREO_SEPARATION_NV, &separation);
    glGetFloatv(GL_STEREO_CONVERGENCE_NV, &convergence);
    printf("autostereo: %ux%u per eye, 3D Vision %s, initial separation %.1f%%, convergence %.1f\n",
           opt.width, opt.height, glIsEnabled(GL_3DVISION_STEREO_NV) ? "enabled" : "disabled",
           separation, convergence);

    /* The mono set-up: projection once, depth test on. */
    view v = {0.3 * opt.width / opt.height, 0.3, 1.0, 100.0};
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-v.right, v.right, -v.top, v.top, v.near_clip, v.far_clip);
    glMatrixMode(GL_MODELVIEW);
    glEnable(GL_DEPTH_TEST);

    int status = 0;
    for (unsigned f = 0; f < frames && status == 0; ++f) {
        /* Separation 0 % → 100 %; convergence at one card after another. */
        float sep = frames > 1 ? 100.0f * (float)f / (float)(frames - 1) : 100.0f;
        float conv = (float)cards[(f + NCARDS - 1) % NCARDS].depth;
        glStereoParameterfNV(GL_STEREO_SEPARATION_NV, sep);
        glStereoParameterfNV(GL_STEREO_CONVERGENCE_NV, conv);
        GLenum err = glGetError();
        if (err != GL_NO_ERROR) {
            fprintf(stderr, "glStereoParameterfNV raised GL error %#x\n", err);
            status = 1;
            break;
        }
        glGetFloatv(GL_STEREO_SEPARATION_NV, &separation);
        glGetFloatv(GL_STEREO_CONVERGENCE_NV, &convergence);
        printf("frame %u: separation %.2f%%, convergence %.2f\n", f, separation, convergence);

        if ((r = gls_auto_stereo_frame(draw_frame, &v)) != GLS_OK) {
            status = example_fail("gls_auto_stereo_frame", r);
            break;
        }
        if ((r = gls_swap_buffers(surface)) != GLS_OK) {
            status = example_fail("gls_swap_buffers", r);
            break;
        }
        if (opt.out_dir) {
            char dir[4096];
            snprintf(dir, sizeof dir, "%s/frame%02u", opt.out_dir, f);
            example_options frame_opt = opt;
            frame_opt.out_dir = dir;
            status = example_save(surface, &frame_opt);
        }
    }

    gls_make_current(NULL);
    gls_surface_destroy(surface);
    gls_config_free(config);
    gls_display_close(display);
    return status;
}

/* oglplane: the OGLPlane program of HP's stereo guide (seed 000 §11), on a
 * machine with no stereo hardware.
 *
 * A wireframe paper dart spins in front of a grey background (grey, not
 * black, against ghosting: seed 000 §8). It shows the whole workflow:
 *   1. check that a stereo visual exists; if not, say so and run in mono;
 *   2. draw each eye into its own back buffer, clearing the depth buffer
 *      between eyes (both eyes share it, as on quad-buffer hardware);
 *   3. project each eye with HP's parallel-axis asymmetric frustum
 *      (seed 000 §6-7: camera offset 3.5% of the scene's width at the
 *      zero-parallax plane, which goes through the airplane's centre);
 *   4. swap once for both eyes;
 *   5. let the user change stereo strength and balance independently, by
 *      steps of x1.1 / /1.1 within 0...2;
 * and, beyond the original, measures the parallax it really rendered from
 * the depth buffer and checks it against the 3% comfort budget. With --out
 * it also writes the last frame as stereo photos a 3D TV, phone or stereo
 * viewer opens: oglplane.mpo (both eyes, CIPA multi-picture) and
 * oglplane.jps (side by side, right eye on the left).
 *
 * Options, besides --out, --size and --mode (example.h):
 *   --frames N         draw N frames (default 1); frame k (from 0) turns the
 *                      airplane --angle + 6k degrees about the vertical axis,
 *                      after a fixed 20-degree tilt towards the viewer, so
 *                      the pose depends only on the frame number
 *   --angle DEG        the first frame's angle (default -60: nose towards
 *                      the viewer's right)
 *   --offset X         stereo strength, UserOffsetAdjustment, 0...2 (default 1)
 *   --balance X        parallax balance, UserBalanceAdjustment, 0...2 (default 1)
 *   --keys KEYS        key presses applied before the first frame
 *   --zero-parallax D  distance of the zero-parallax plane (default 10: the
 *                      airplane's centre)
 *   --auto-converge    after each frame, put zero parallax at the measured
 *                      centre of interest
 *   --interactive      in a window (GLSTEREO_BACKEND=glx): spin until the
 *                      window is closed
 *
 * Keys, in a window (headless, --keys types them): + or = stronger,
 * - weaker, ] more positive balance, [ less, a auto-convergence on/off.
 * The current values are in the window title and on stdout. */
#include <GL/glx.h> /* GLX_* attribute names only */
#include <math.h>

#include "example.h"

#define HFOV_DEGREES 50.0     /* horizontal field of view: 50 or more (seed 000 §8) */
#define NEAR_CLIP 1.0
#define FAR_CLIP 50.0
#define CAMERA_DISTANCE 10.0  /* camera to the airplane's centre */
#define TILT_DEGREES 20.0     /* top of the airplane turned towards the viewer */
#define ANGLE_STEP 6.0        /* degrees per frame: 60 frames make a turn */
#define LIGHT_SIZE 3.0        /* navigation lights, in pixels */

/* The dart, flying along +x with +y up and its right wing towards +z: a
 * folded sheet whose nose is the tip of a long triangle, two wings with a
 * slight dihedral and a second fold halfway out, and the keel (the folded
 * fuselage) hanging below the centre fold. */
enum { NOSE, TAIL, LEFT_TIP, RIGHT_TIP, LEFT_FOLD, RIGHT_FOLD, KEEL, VERTEX_COUNT };
static const double vertices[VERTEX_COUNT][3] = {
    [NOSE] = {2.2, 0.0, 0.0},         [TAIL] = {-2.2, 0.0, 0.0},
    [LEFT_TIP] = {-2.2, 0.25, -1.4},  [RIGHT_TIP] = {-2.2, 0.25, 1.4},
    [LEFT_FOLD] = {-2.2, 0.12, -0.7}, [RIGHT_FOLD] = {-2.2, 0.12, 0.7},
    [KEEL] = {-2.2, -0.6, 0.0},
};
static const int edges[][2] = {
    {NOSE, LEFT_TIP},  {NOSE, RIGHT_TIP},     /* leading edges */
    {NOSE, LEFT_FOLD}, {NOSE, RIGHT_FOLD},    /* the wings' second folds */
    {NOSE, TAIL},                             /* the centre fold */
    {LEFT_TIP, LEFT_FOLD}, {LEFT_FOLD, TAIL}, /* trailing edge */
    {TAIL, RIGHT_FOLD}, {RIGHT_FOLD, RIGHT_TIP},
    {NOSE, KEEL}, {KEEL, TAIL},               /* the keel */
};
/* Navigation lights: amber nose, red left (port) and green right
 * (starboard) wing tips. Drawn without depth test, so always visible. */
static const struct { int vertex; unsigned char rgb[3]; } lights[] = {
    {NOSE, {255, 200, 0}}, {LEFT_TIP, {230, 0, 0}}, {RIGHT_TIP, {0, 200, 0}}};

/* What the user adjusts. */
typedef struct plane_settings {
    gls_stereo_adjust adj; /* zero-parallax distance, strength, balance */
    int auto_converge;     /* 1: each frame puts zero parallax at the centre of interest */
} plane_settings;

/* One key press: what the window's key handler will call, and what --keys
 * calls headless. Strength and balance change multiplicatively (x1.1 or
 * /1.1, kept within 0...2 by gls_adjust_step) and independently of each
 * other. Returns 1 if the key changed a setting (redraw, update the title
 * with plane_status), 0 if it is not one of ours. */
static int plane_key(plane_settings *s, int key) {
    switch (key) {
    case '+': case '=':
        s->adj.offset_adjustment = gls_adjust_step(s->adj.offset_adjustment, +1);
        return 1;
    case '-':
        s->adj.offset_adjustment = gls_adjust_step(s->adj.offset_adjustment, -1);
        return 1;
    case ']':
        s->adj.balance_adjustment = gls_adjust_step(s->adj.balance_adjustment, +1);
        return 1;
    case '[':
        s->adj.balance_adjustment = gls_adjust_step(s->adj.balance_adjustment, -1);
        return 1;
    case 'a':
        s->auto_converge = !s->auto_converge;
        return 1;
    default:
        return 0;
    }
}

/* The current settings in words: stdout headless, the window title later. */
static void plane_status(const plane_settings *s, char *buf, size_t len) {
    snprintf(buf, len, "offset adjustment %.4f, balance adjustment %.4f, zero parallax at %.3f%s",
             s->adj.offset_adjustment, s->adj.balance_adjustment, s->adj.zero_parallax_distance,
             s->auto_converge ? " (auto-convergence)" : "");
}

static void draw_airplane(double angle_degrees) {
    double centre[3];
    for (int k = 0; k < 3; ++k) { /* bounding-box centre: the zero-parallax plane goes through it */
        double lo = vertices[0][k], hi = vertices[0][k];
        for (int v = 1; v < VERTEX_COUNT; ++v) {
            lo = fmin(lo, vertices[v][k]);
            hi = fmax(hi, vertices[v][k]);
        }
        centre[k] = (lo + hi) / 2.0;
    }
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glTranslated(0.0, 0.0, -CAMERA_DISTANCE);
    glRotated(TILT_DEGREES, 1.0, 0.0, 0.0);
    glRotated(angle_degrees, 0.0, 1.0, 0.0);
    glTranslated(-centre[0], -centre[1], -centre[2]);

    glEnable(GL_DEPTH_TEST);
    glLineWidth(2.0f);
    glColor3ub(240, 238, 225); /* paper, not pure white (seed 000 §8) */
    glBegin(GL_LINES);
    for (size_t e = 0; e < sizeof edges / sizeof edges[0]; ++e) {
        glVertex3dv(vertices[edges[e][0]]);
        glVertex3dv(vertices[edges[e][1]]);
    }
    glEnd();

    glDisable(GL_DEPTH_TEST);
    glPointSize((float)LIGHT_SIZE);
    glBegin(GL_POINTS);
    for (size_t l = 0; l < sizeof lights / sizeof lights[0]; ++l) {
        glColor3ubv(lights[l].rgb);
        glVertex3dv(vertices[lights[l].vertex]);
    }
    glEnd();
}

/* One eye: its back buffer, its own depth (the buffer is shared), its projection. */
static gls_result draw_eye(const gls_frustum *mono, const plane_settings *s, uint32_t eye,
                           uint32_t buffer, double angle) {
    gls_result r = gls_draw_buffer(buffer);
    if (r != GLS_OK) return r;
    glClear(GL_DEPTH_BUFFER_BIT);
    if ((r = gls_apply_stereo_eye(mono, &s->adj, eye)) != GLS_OK) return r;
    draw_airplane(angle);
    return GLS_OK;
}

static void merge_reports(gls_parallax_report *total, const gls_parallax_report *r, int first) {
    if (first) {
        *total = *r;
        return;
    }
    if (r->min_percent < total->min_percent) {
        total->min_percent = r->min_percent;
        total->min_pixels = r->min_pixels;
    }
    if (r->max_percent > total->max_percent) {
        total->max_percent = r->max_percent;
        total->max_pixels = r->max_pixels;
    }
    total->nearest_distance = fmin(total->nearest_distance, r->nearest_distance);
    total->farthest_distance = fmax(total->farthest_distance, r->farthest_distance);
    total->covered_pixels += r->covered_pixels;
    total->warnings |= r->warnings;
}

static int parse_number(const char *opt, const char *text, double lo, double hi, double *out) {
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (errno != 0 || end == text || *end != '\0' || !isfinite(v) || v < lo || v > hi) {
        fprintf(stderr, "%s wants a number from %g to %g, not %s\n", opt, lo, hi, text);
        return 0;
    }
    *out = v;
    return 1;
}

#define OPTIONS                                                                                     \
    "[--frames N] [--angle DEG] [--offset X] [--balance X] [--keys KEYS] [--zero-parallax D] [--auto-converge] " \
    "[--interactive]"

int main(int argc, char **argv) {
    example_options opt = example_defaults();
    plane_settings settings = {{CAMERA_DISTANCE, GLS_ADJUSTMENT_DEFAULT, GLS_ADJUSTMENT_DEFAULT}, 0};
    const char *keys = "";
    double frames = 1.0, start_angle = -60.0;
    int interactive = 0;
    for (int i = 1; i < argc; ++i) {
        int r = example_parse_common(&i, argc, argv, &opt);
        if (r == 1) continue;
        if (r < 0) {
            example_usage(argv[0], OPTIONS);
            return 2;
        }
        const char *a = argv[i];
        int ok = 1;
        if (strcmp(a, "--auto-converge") == 0) {
            settings.auto_converge = 1;
            continue;
        }
        if (strcmp(a, "--interactive") == 0) {
            interactive = 1;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "%s %s\n", a, strncmp(a, "--", 2) == 0 ? "is unknown or needs a value" : "is not an option");
            example_usage(argv[0], OPTIONS);
            return 2;
        }
        const char *v = argv[++i];
        if (strcmp(a, "--frames") == 0) {
            ok = parse_number(a, v, 1, 100000, &frames) && frames == floor(frames);
            if (!ok) fprintf(stderr, "--frames wants a whole number of frames\n");
        } else if (strcmp(a, "--angle") == 0) {
            ok = parse_number(a, v, -3600, 3600, &start_angle);
        } else if (strcmp(a, "--offset") == 0) {
            ok = parse_number(a, v, 0, GLS_ADJUSTMENT_MAX, &settings.adj.offset_adjustment);
        } else if (strcmp(a, "--balance") == 0) {
            ok = parse_number(a, v, 0, GLS_ADJUSTMENT_MAX, &settings.adj.balance_adjustment);
        } else if (strcmp(a, "--zero-parallax") == 0) {
            ok = parse_number(a, v, NEAR_CLIP, FAR_CLIP, &settings.adj.zero_parallax_distance);
        } else if (strcmp(a, "--keys") == 0) {
            keys = v;
        } else {
            fprintf(stderr, "unknown option %s\n", a);
            ok = 0;
        }
        if (!ok) {
            example_usage(argv[0], OPTIONS);
            return 2;
        }
    }
    for (const char *k = keys; *k; ++k) {
        if (!plane_key(&settings, (unsigned char)*k)) {
            fprintf(stderr, "--keys: '%c' is not a key of oglplane (use + = - ] [ a)\n", *k);
            return 2;
        }
    }

    gls_display *display;
    gls_result r = gls_display_open(GLS_BACKEND_AUTO, &display);
    if (r != GLS_OK) return example_fail("gls_display_open", r);

    /* 1. Is stereo available? (seed 000 §3) If not, tell the user and go on in mono. */
    int stereo_attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                            GLX_BLUE_SIZE, 1, GLX_DEPTH_SIZE, 1, GLX_STEREO, None};
    int mono_attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                          GLX_BLUE_SIZE, 1, GLX_DEPTH_SIZE, 1, None};
    gls_config *config;
    r = gls_config_choose(display, stereo_attribs, &config);
    if (r == GLS_ERROR_NO_MATCHING_CONFIG) {
        fprintf(stderr, "oglplane: stereo is not available (%s); running in mono\n", gls_last_error_message());
        r = gls_config_choose(display, mono_attribs, &config);
    }
    if (r != GLS_OK) return example_fail("gls_config_choose", r);
    const int stereo = gls_config_stereo(config) != GLS_STEREO_NONE;
    printf("oglplane: %s stereo, %ux%u per eye\n",
           gls_config_stereo(config) == GLS_STEREO_NATIVE ? "native"
           : stereo                                      ? "emulated"
                                                         : "no",
           opt.width, opt.height);

    gls_surface *surface;
    r = gls_surface_create(display, config, opt.width, opt.height, &surface);
    if (r != GLS_OK) return example_fail("gls_surface_create", r);
    if (example_apply_mode(surface, &opt)) return 1;
    if ((r = gls_make_current(surface)) != GLS_OK) return example_fail("gls_make_current", r);
    uint32_t backend = 0;
    gls_display_get_backend(display, &backend);
    if (interactive && backend != GLS_BACKEND_GLX) {
        fprintf(stderr, "--interactive needs a window: run with GLSTEREO_BACKEND=glx and an X display\n");
        return 2;
    }

    /* The mono camera: 50 degrees across, square pixels. */
    const double half_width = NEAR_CLIP * tan(HFOV_DEGREES / 2.0 * 3.14159265358979323846 / 180.0);
    double half_height = half_width * opt.height / opt.width;
    gls_frustum mono = {-half_width, half_width, -half_height, half_height, NEAR_CLIP, FAR_CLIP};
    printf("oglplane: horizontal FOV %g deg, near %g, far %g, camera %g from the airplane's centre\n",
           HFOV_DEGREES, NEAR_CLIP, FAR_CLIP, CAMERA_DISTANCE);

    /* 3. HP's parameters for each eye (what gls_apply_stereo_eye loads). */
    char status_line[160], title[200];
    plane_status(&settings, status_line, sizeof status_line);
    printf("oglplane: %s\n", status_line);
    snprintf(title, sizeof title, "OGLPlane: %s", status_line);
    gls_surface_set_title(surface, title);
    fflush(stdout);
    for (uint32_t eye = GLS_EYE_LEFT; stereo && eye <= GLS_EYE_RIGHT; ++eye) {
        gls_frustum f;
        double offset;
        if ((r = gls_stereo_eye(&mono, &settings.adj, eye, &f, &offset)) != GLS_OK)
            return example_fail("gls_stereo_eye", r);
        printf("oglplane: %s eye: camera offset %+.4f, frustum asymmetry %+.5f\n",
               eye == GLS_EYE_LEFT ? "left " : "right", offset, f.left - mono.left);
    }

    gls_parallax_report total = {0}, last = {0};
    double centre_of_interest = 0.0;
    int measured = 0;
    double angle = start_angle;
    int quit = 0;
    long frame;
    for (frame = 0; !quit && (interactive || frame < (long)frames); ++frame) {
        angle = start_angle + ANGLE_STEP * (double)frame;
        /* 2. Clear both back buffers at once, then draw each eye. */
        gls_draw_buffer(GL_BACK);
        glClearColor(0.45f, 0.45f, 0.45f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        if (stereo) {
            if ((r = draw_eye(&mono, &settings, GLS_EYE_LEFT, GL_BACK_LEFT, angle)) != GLS_OK ||
                (r = draw_eye(&mono, &settings, GLS_EYE_RIGHT, GL_BACK_RIGHT, angle)) != GLS_OK)
                return example_fail("drawing an eye", r);
            /* The right eye's depth is still in the shared depth buffer. */
            gls_parallax_report report;
            if ((r = gls_stereo_measure_parallax(&mono, &settings.adj, GLS_PARALLAX_BUDGET_DEFAULT, &report)) != GLS_OK)
                return example_fail("gls_stereo_measure_parallax", r);
            merge_reports(&total, &report, !measured);
            last = report;
            measured = 1;
            /* Where the subject is: converge there (next frame), or report it. */
            if (settings.auto_converge || interactive || frame + 1 == (long)frames) {
                if ((r = gls_stereo_auto_converge(&mono, &centre_of_interest)) != GLS_OK)
                    return example_fail("gls_stereo_auto_converge", r);
                if (settings.auto_converge) settings.adj.zero_parallax_distance = centre_of_interest;
            }
        } else {
            glClear(GL_DEPTH_BUFFER_BIT);
            glMatrixMode(GL_PROJECTION);
            glLoadIdentity();
            glFrustum(mono.left, mono.right, mono.bottom, mono.top, mono.near_clip, mono.far_clip);
            draw_airplane(angle);
        }
        /* 4. One swap presents both eyes. */
        if ((r = gls_swap_buffers(surface)) != GLS_OK) return example_fail("gls_swap_buffers", r);

        /* 5. The user's adjustments, from the window (none headless). */
        gls_event ev;
        while (gls_surface_poll_event(surface, &ev) == GLS_OK && ev.kind != GLS_EVENT_NONE) {
            if (ev.kind == GLS_EVENT_KEY && ev.key < 128 && plane_key(&settings, (int)ev.key)) {
                plane_status(&settings, status_line, sizeof status_line);
                printf("oglplane: %s\n", status_line);
                fflush(stdout);
                snprintf(title, sizeof title, "OGLPlane: %s", status_line);
                gls_surface_set_title(surface, title);
            } else if (ev.kind == GLS_EVENT_CLOSE) {
                quit = 1;
            } else if (ev.kind == GLS_EVENT_RESIZE) {
                glViewport(0, 0, (GLsizei)ev.width, (GLsizei)ev.height);
                half_height = half_width * ev.height / ev.width;
                mono.bottom = -half_height;
                mono.top = half_height;
            }
        }
    }
    frames = (double)frame;
    printf("oglplane: %ld frame%s, last at angle %.1f deg\n", frame, frame == 1 ? "" : "s", angle);

    if (measured) {
        char text[512];
        gls_parallax_report_describe(&last, text, sizeof text, NULL);
        printf("measured in the last frame: %s\n", text);
        if (frames > 1) {
            gls_parallax_report_describe(&total, text, sizeof text, NULL);
            printf("measured over %ld frames: %s\n", (long)frames, text);
        }
        printf("centre of interest at distance %.3f (zero parallax now at %.3f)\n", centre_of_interest,
               settings.adj.zero_parallax_distance);
        if (total.warnings != GLS_PARALLAX_WITHIN_BUDGET)
            fprintf(stderr, "oglplane: the parallax exceeds the comfort budget: see above\n");
    } else {
        printf("measured parallax: none, the picture is mono\n");
    }

    int status = example_save(surface, &opt);
    /* The last frame as stereo photos (a mono picture has none). */
    static const struct { uint32_t format; const char *name; } photos[] = {
        {GLS_PHOTO_MPO, "oglplane.mpo"}, {GLS_PHOTO_JPS, "oglplane.jps"}};
    for (size_t k = 0; status == 0 && stereo && opt.out_dir && k < sizeof photos / sizeof photos[0]; ++k) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", opt.out_dir, photos[k].name);
        if ((r = gls_surface_save_stereo_photo(surface, photos[k].format, path)) != GLS_OK)
            return example_fail("gls_surface_save_stereo_photo", r);
        printf("wrote %s\n", path);
    }
    gls_make_current(NULL);
    gls_surface_destroy(surface);
    gls_config_free(config);
    gls_display_close(display);
    return status;
}

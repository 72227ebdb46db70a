/* Measured parallax and auto-convergence on real rendering: quads drawn at
 * known distances with each eye's HP projection, measured from the shared
 * depth buffer, compared with the math (gls_stereo_parallax_percent) and
 * with the shift of the quad's edge between the two eye images; plus every
 * documented error code. Built with -lGL (EGL) or -lOSMesa (OSMesa); the
 * backend comes from GLSTEREO_BACKEND. */
#define _POSIX_C_SOURCE 200809L
#include <GL/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "glstereo.h"

#define GLX_RGBA 4
#define GLX_DOUBLEBUFFER 5
#define GLX_STEREO 6
#define GLX_DEPTH_SIZE 12

enum { W = 320, H = 240 };
static const double NEAR = 1.0, FAR = 60.0;
static gls_frustum mono;

static int has(const char *needle) { return strstr(gls_last_error_message(), needle) != NULL; }

typedef struct quad {
    double distance;   /* eye-space distance of the quad's plane */
    double x0, x1;     /* extent as fractions of the view's width at that distance, -1...1 */
    double y0, y1;
    unsigned char shade; /* grey level; 0 means white */
} quad;

/* Draws quads (white) for one eye, depth cleared first: the buffer is shared. */
static void draw_eye(const gls_stereo_adjust *adj, uint32_t eye, const quad *q, int n) {
    gls_draw_buffer(eye == GLS_EYE_LEFT ? GL_BACK_LEFT : GL_BACK_RIGHT);
    glClear(GL_DEPTH_BUFFER_BIT);
    gls_apply_stereo_eye(&mono, adj, eye);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glEnable(GL_DEPTH_TEST);
    for (int i = 0; i < n; ++i) {
        const unsigned char g = q[i].shade ? q[i].shade : 255;
        glColor3ub(g, g, g);
        const double d = q[i].distance, sx = mono.right / NEAR * d, sy = mono.top / NEAR * d;
        glBegin(GL_QUADS);
        glVertex3d(q[i].x0 * sx, q[i].y0 * sy, -d);
        glVertex3d(q[i].x1 * sx, q[i].y0 * sy, -d);
        glVertex3d(q[i].x1 * sx, q[i].y1 * sy, -d);
        glVertex3d(q[i].x0 * sx, q[i].y1 * sy, -d);
        glEnd();
    }
}

/* Clears both eyes and draws the quads into each; the right eye is drawn last. */
static void draw_frame(const gls_stereo_adjust *adj, const quad *q, int n) {
    gls_draw_buffer(GL_BACK);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    draw_eye(adj, GLS_EYE_LEFT, q, n);
    draw_eye(adj, GLS_EYE_RIGHT, q, n);
}

/* Column of the first pixel of grey level g in row y (rows top first), -1 if none. */
static int first_of(const unsigned char *rgba, int y, unsigned char g) {
    for (int x = 0; x < W; ++x)
        if (rgba[(y * W + x) * 4] == g) return x;
    return -1;
}

static double percent_at(const gls_stereo_adjust *adj, double w) {
    double p = NAN;
    gls_stereo_parallax_percent(&mono, adj, w, &p);
    return p;
}

int main(void) {
    const double hw = NEAR * tan(50.0 / 2.0 * 3.14159265358979323846 / 180.0);
    mono = (gls_frustum){-hw, hw, -hw * H / W, hw * H / W, NEAR, FAR};
    gls_stereo_adjust adj = {10.0, 1.0, 1.0};
    gls_parallax_report rep;
    double dist = 0;

    /* No surface yet. */
    CHECK(gls_stereo_measure_parallax(&mono, &adj, 3.0, &rep) == GLS_ERROR_NO_CURRENT_SURFACE, "no surface");
    CHECK(gls_stereo_auto_converge(&mono, &dist) == GLS_ERROR_NO_CURRENT_SURFACE, "no surface");

    gls_display *d;
    gls_result r = gls_display_open(GLS_BACKEND_AUTO, &d);
    CHECK(r == GLS_OK, "%s", gls_last_error_message());
    if (r != GLS_OK) return SUMMARY();
    const int with_depth[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, GLX_DEPTH_SIZE, 24, 0};
    const int no_depth[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, 0};
    gls_config *c, *c_nodepth;
    CHECK(gls_config_choose(d, with_depth, &c) == GLS_OK, "%s", gls_last_error_message());
    CHECK(gls_config_choose(d, no_depth, &c_nodepth) == GLS_OK, "%s", gls_last_error_message());
    gls_surface *s, *s_nodepth;
    CHECK(gls_surface_create(d, c, W, H, &s) == GLS_OK, "%s", gls_last_error_message());
    CHECK(gls_surface_create(d, c_nodepth, W, H, &s_nodepth) == GLS_OK, "%s", gls_last_error_message());

    /* A surface without a depth buffer cannot be measured. */
    CHECK(gls_make_current(s_nodepth) == GLS_OK, "%s", gls_last_error_message());
    CHECK(gls_stereo_measure_parallax(&mono, &adj, 3.0, &rep) == GLS_ERROR_INVALID_OPERATION &&
              has("GLX_DEPTH_SIZE"), "no depth: %s", gls_last_error_message());

    CHECK(gls_make_current(s) == GLS_OK, "%s", gls_last_error_message());
    /* Bad arguments, and an empty frame: documented codes, nothing written. */
    memset(&rep, 0x5a, sizeof rep);
    const gls_parallax_report untouched = rep;
    CHECK(gls_stereo_measure_parallax(NULL, &adj, 3.0, &rep) == GLS_ERROR_NULL_POINTER, "NULL mono");
    CHECK(gls_stereo_measure_parallax(&mono, NULL, 3.0, &rep) == GLS_ERROR_NULL_POINTER, "NULL adj");
    CHECK(gls_stereo_measure_parallax(&mono, &adj, 3.0, NULL) == GLS_ERROR_NULL_POINTER, "NULL report");
    CHECK(gls_stereo_measure_parallax(&mono, &adj, 0.0, &rep) == GLS_ERROR_INVALID_VALUE && has("budget_percent"),
          "budget 0: %s", gls_last_error_message());
    CHECK(gls_stereo_measure_parallax(&mono, &adj, NAN, &rep) == GLS_ERROR_INVALID_VALUE, "budget NaN");
    gls_stereo_adjust bad = adj;
    bad.zero_parallax_distance = -1;
    CHECK(gls_stereo_measure_parallax(&mono, &bad, 3.0, &rep) == GLS_ERROR_INVALID_VALUE &&
              has("zero_parallax_distance"), "%s", gls_last_error_message());
    CHECK(gls_stereo_auto_converge(NULL, &dist) == GLS_ERROR_NULL_POINTER, "NULL mono");
    CHECK(gls_stereo_auto_converge(&mono, NULL) == GLS_ERROR_NULL_POINTER, "NULL distance_out");
    draw_frame(&adj, NULL, 0);
    CHECK(gls_stereo_measure_parallax(&mono, &adj, 3.0, &rep) == GLS_ERROR_INVALID_OPERATION && has("no geometry"),
          "empty frame: %s", gls_last_error_message());
    CHECK(gls_stereo_auto_converge(&mono, &dist) == GLS_ERROR_INVALID_OPERATION && dist == 0, "empty frame");
    CHECK(memcmp(&rep, &untouched, sizeof rep) == 0, "the report is written only on GLS_OK");

    /* One quad at a known distance: the measurement agrees with the math,
     * and with the quad's edge shift between the two eye images. */
    static unsigned char left[W * H * 4], right[W * H * 4];
    const double distances[] = {7.5, 10.0, 17.0};
    for (int i = 0; i < 3; ++i) {
        const double w = distances[i];
        const quad q = {w, -0.5, 0.3, -0.4, 0.4, 0};
        draw_frame(&adj, &q, 1);
        r = gls_stereo_measure_parallax(&mono, &adj, 3.0, &rep);
        CHECK(r == GLS_OK, "%s", gls_last_error_message());
        const double want = percent_at(&adj, w);
        CHECK(fabs(rep.nearest_distance - w) < 1e-4 * w && fabs(rep.farthest_distance - w) < 1e-4 * w,
              "distance %g: measured %g to %g", w, rep.nearest_distance, rep.farthest_distance);
        CHECK(fabs(rep.min_percent - want) < 1e-3 && fabs(rep.max_percent - want) < 1e-3,
              "distance %g: %g%% to %g%%, math %g%%", w, rep.min_percent, rep.max_percent, want);
        CHECK(fabs(rep.min_pixels - want / 100.0 * W) < 1e-2, "pixels %g", rep.min_pixels);
        CHECK(rep.budget_percent == 3.0 && rep.warnings == GLS_PARALLAX_WITHIN_BUDGET, "warnings %u", rep.warnings);
        CHECK(rep.covered_pixels > (uint64_t)(0.8 * 0.4 * W * 0.8 * 0.4 * H), "covered %llu",
              (unsigned long long)rep.covered_pixels);
        CHECK(gls_surface_read_pixels(s, GL_BACK_LEFT, left, sizeof left) == GLS_OK, "%s", gls_last_error_message());
        CHECK(gls_surface_read_pixels(s, GL_BACK_RIGHT, right, sizeof right) == GLS_OK, "%s", gls_last_error_message());
        const int xl = first_of(left, H / 2, 255), xr = first_of(right, H / 2, 255);
        CHECK(xl >= 0 && xr >= 0 && fabs((xr - xl) - rep.min_pixels) <= 1.0,
              "distance %g: the edge moves %d px between the eyes, measured %+.2f px", w, xr - xl, rep.min_pixels);
    }
    /* Zero parallax at the zero-parallax distance, exactly where the images agree. */
    CHECK(fabs(percent_at(&adj, 10.0)) < 1e-12, "math");

    /* Nearest and farthest of several quads; warnings on each side. */
    {
        const quad q[] = {{14.0, -1, 1, -1, 1, 0}, {6.0, -0.2, 0.0, -0.2, 0.0, 0}};
        draw_frame(&adj, q, 2);
        CHECK(gls_stereo_measure_parallax(&mono, &adj, 3.0, &rep) == GLS_OK, "%s", gls_last_error_message());
        CHECK(fabs(rep.nearest_distance - 6.0) < 1e-3 && fabs(rep.farthest_distance - 14.0) < 1e-3,
              "%g to %g", rep.nearest_distance, rep.farthest_distance);
        CHECK(fabs(rep.min_percent - percent_at(&adj, 6.0)) < 1e-3 &&
                  fabs(rep.max_percent - percent_at(&adj, 14.0)) < 1e-3, "%g, %g", rep.min_percent, rep.max_percent);
        CHECK(rep.warnings == GLS_PARALLAX_WARN_NEGATIVE, "6 is -4.7%%: warnings %u", rep.warnings);
        char text[400];
        size_t len = 0;
        CHECK(gls_parallax_report_describe(&rep, text, sizeof text, &len) == GLS_OK && len == strlen(text) &&
                  strstr(text, "WARNING") && strstr(text, "in front of the screen"), "%s", text);
        printf("two quads: %s\n", text);
        char small[12];
        size_t len2 = 0;
        CHECK(gls_parallax_report_describe(&rep, small, sizeof small, &len2) == GLS_OK && len2 == len &&
                  strlen(small) == sizeof small - 1 && strncmp(small, text, sizeof small - 1) == 0, "truncated %s", small);
        CHECK(gls_parallax_report_describe(&rep, NULL, 0, &len2) == GLS_OK && len2 == len, "length only");
        CHECK(gls_parallax_report_describe(&rep, NULL, 4, &len2) == GLS_ERROR_NULL_POINTER, "NULL buf");
        CHECK(gls_parallax_report_describe(NULL, text, sizeof text, NULL) == GLS_ERROR_NULL_POINTER, "NULL report");

        const quad far_only[] = {{40.0, -1, 1, -1, 1, 0}};
        draw_frame(&adj, far_only, 1);
        CHECK(gls_stereo_measure_parallax(&mono, &adj, 3.0, &rep) == GLS_OK &&
                  rep.warnings == GLS_PARALLAX_WARN_POSITIVE, "40 is +5.25%%: warnings %u", rep.warnings);
        CHECK(gls_stereo_measure_parallax(&mono, &adj, 6.0, &rep) == GLS_OK &&
                  rep.warnings == GLS_PARALLAX_WITHIN_BUDGET, "budget 6%%: warnings %u", rep.warnings);
    }

    /* Balance 0: no asymmetry, every distance in front of the screen. */
    {
        gls_stereo_adjust flat = adj;
        flat.balance_adjustment = 0.0;
        const quad q[] = {{50.0, -1, 1, -1, 1, 0}, {4.0, -0.2, 0.0, -0.2, 0.0, 0}};
        draw_frame(&flat, q, 2);
        CHECK(gls_stereo_measure_parallax(&mono, &flat, 3.0, &rep) == GLS_OK && rep.max_percent < 0.0 &&
                  rep.min_percent < rep.max_percent, "balance 0: %g%% to %g%%", rep.min_percent, rep.max_percent);
    }

    /* glDepthRange is undone, and only the viewport counts (pixels are of its width). */
    {
        const quad q = {8.0, -0.5, 0.5, -0.5, 0.5, 0};
        glDepthRange(0.25, 0.75);
        draw_frame(&adj, &q, 1);
        CHECK(gls_stereo_measure_parallax(&mono, &adj, 3.0, &rep) == GLS_OK &&
                  fabs(rep.nearest_distance - 8.0) < 1e-3, "depth range: %g", rep.nearest_distance);
        glDepthRange(0.0, 1.0);
        glViewport(0, 0, W / 2, H);
        draw_frame(&adj, &q, 1);
        CHECK(gls_stereo_measure_parallax(&mono, &adj, 3.0, &rep) == GLS_OK &&
                  fabs(rep.min_pixels - percent_at(&adj, 8.0) / 100.0 * (W / 2)) < 1e-2,
              "viewport %d px wide: %g px", W / 2, rep.min_pixels);
        glViewport(0, 0, W, H);
    }

    /* Auto-convergence: a subject in front of a background that fills the
     * view; the subject covers 81% of the central window (the middle half of
     * the width and height), so the median there is the subject's distance.
     * Converged on it, the subject sits at zero parallax, the background behind. */
    {
        const quad q[] = {{30.0, -1, 1, -1, 1, 100}, {7.0, -0.45, 0.45, -0.45, 0.45, 0}};
        draw_frame(&adj, q, 2);
        CHECK(gls_stereo_auto_converge(&mono, &dist) == GLS_OK && fabs(dist - 7.0) < 1e-3,
              "centre of interest %g, want 7", dist);
        gls_stereo_adjust converged = adj;
        converged.zero_parallax_distance = dist;
        draw_frame(&converged, q, 2);
        CHECK(gls_stereo_measure_parallax(&mono, &converged, 3.0, &rep) == GLS_OK && fabs(rep.min_percent) < 1e-3 &&
                  rep.max_percent > 0.5, "converged: %g%% to %g%%", rep.min_percent, rep.max_percent);
        /* The subject's edge no longer moves between the eyes; before, it did. */
        gls_surface_read_pixels(s, GL_BACK_LEFT, left, sizeof left);
        gls_surface_read_pixels(s, GL_BACK_RIGHT, right, sizeof right);
        const int cl = first_of(left, H / 2, 255), cr = first_of(right, H / 2, 255);
        CHECK(cl >= 0 && cl == cr, "converged: the subject's edge is at %d (left) and %d (right)", cl, cr);
        draw_frame(&adj, q, 2);
        gls_surface_read_pixels(s, GL_BACK_LEFT, left, sizeof left);
        gls_surface_read_pixels(s, GL_BACK_RIGHT, right, sizeof right);
        const int ul = first_of(left, H / 2, 255), ur = first_of(right, H / 2, 255);
        CHECK(ur - ul <= -3, "unconverged: the subject is in front, edge %d (left) and %d (right)", ul, ur);

        /* Nothing in the middle: the whole viewport decides. */
        const quad corner[] = {{12.0, -1, -0.6, -1, -0.6, 0}};
        draw_frame(&adj, corner, 1);
        CHECK(gls_stereo_auto_converge(&mono, &dist) == GLS_OK && fabs(dist - 12.0) < 1e-3, "corner: %g", dist);
    }

    gls_make_current(NULL);
    gls_surface_destroy(s);
    gls_surface_destroy(s_nodepth);
    gls_config_free(c);
    gls_config_free(c_nodepth);
    gls_display_close(d);
    return SUMMARY();
}

/* The projection math through the C ABI: the seed's worked example, HP's
 * eye frusta, and the documented codes for NULL pointers and bad enums. */
#include <math.h>
#include <string.h>

#include "glstereo.h"
#include "check.h"

static int close_to(double a, double b) { return fabs(a - b) <= 1e-12 * (fabs(a) + fabs(b) + 1.0); }

int main(void) {
    /* The version macros and the library agree. */
    CHECK(strcmp(gls_version(), GLSTEREO_VERSION_STRING) == 0, "gls_version() = %s", gls_version());

    /* Seed 000 §5 worked example, exactly. */
    const double point[3] = {8.0, -5.0, -3.0};
    const double want_x[5] = {6.0, 6.375, 5.625, 5.875, 6.125};
    for (uint32_t eq = GLS_EQUATION_MONO; eq <= GLS_EQUATION_RIGHT_ZERO_PARALLAX; ++eq) {
        double xy[2] = {0.0, 0.0};
        gls_result r = gls_project_point(9.0, 1.0, point, eq, xy);
        CHECK(r == GLS_OK, "equation %u: %s", eq, gls_last_error_message());
        CHECK(xy[0] == want_x[eq - 1] && xy[1] == -3.75, "equation %u gave (%g, %g)", eq, xy[0], xy[1]);
    }

    /* HP eye frusta (seed 000 §7) for a 1.0 x 0.8 near window at near 1,
     * zero parallax at 10: Xrange = 10, offset = 0.35, asymmetry = 0.035. */
    gls_frustum mono = {-0.5, 0.5, -0.4, 0.4, 1.0, 100.0};
    gls_stereo_adjust adj = {10.0, 1.0, 1.0};
    gls_frustum left, right;
    double off_l = 0.0, off_r = 0.0;
    CHECK(gls_stereo_eye(&mono, &adj, GLS_EYE_LEFT, &left, &off_l) == GLS_OK, "%s", gls_last_error_message());
    CHECK(gls_stereo_eye(&mono, &adj, GLS_EYE_RIGHT, &right, &off_r) == GLS_OK, "%s", gls_last_error_message());
    CHECK(close_to(off_l, -0.35) && close_to(off_r, 0.35), "offsets %g %g", off_l, off_r);
    CHECK(close_to(left.left, -0.5 + 0.035) && close_to(left.right, 0.5 + 0.035), "left %g..%g", left.left, left.right);
    CHECK(close_to(right.left, -0.5 - 0.035) && close_to(right.right, 0.5 - 0.035), "right %g..%g", right.left, right.right);
    CHECK(left.bottom == -0.4 && left.top == 0.4 && left.near_clip == 1.0 && left.far_clip == 100.0, "rest of left frustum changed");

    /* The matrix is glFrustum(eye) x glTranslated(-offset, 0, 0). */
    double m[16];
    CHECK(gls_stereo_eye_matrix(&mono, &adj, GLS_EYE_LEFT, m) == GLS_OK, "%s", gls_last_error_message());
    double m2[16];
    CHECK(gls_frustum_matrix(&left, off_l, m2) == GLS_OK, "%s", gls_last_error_message());
    CHECK(memcmp(m, m2, sizeof m) == 0, "eye matrix differs from frustum matrix");
    CHECK(close_to(m[0], 2.0 / 1.0) && close_to(m[12], 2.0 * 0.35), "m[0]=%g m[12]=%g", m[0], m[12]);

    /* Parallax p = D(1 - C/w). */
    CHECK(gls_parallax(0.2, 10.0, 5.0) == -0.2, "parallax at C/2");
    CHECK(isnan(gls_parallax(0.2, 10.0, 0.0)), "depth 0 must give NaN");
    CHECK(strstr(gls_last_error_message(), "depth") != NULL, "message: %s", gls_last_error_message());

    /* Misuse: NULL outputs and a bad eye give the documented codes and leave outputs untouched. */
    gls_frustum untouched = {1, 2, 3, 4, 5, 6};
    double offset_untouched = 42.0;
    CHECK(gls_stereo_eye(&mono, &adj, GLS_EYE_LEFT, NULL, &offset_untouched) == GLS_ERROR_NULL_POINTER, "NULL frustum out");
    CHECK(offset_untouched == 42.0, "offset written on failure");
    CHECK(strstr(gls_last_error_message(), "eye_frustum_out") != NULL, "message: %s", gls_last_error_message());
    CHECK(gls_stereo_eye(&mono, &adj, GLS_EYE_LEFT, &untouched, NULL) == GLS_ERROR_NULL_POINTER, "NULL offset out");
    CHECK(untouched.left == 1 && untouched.far_clip == 6, "frustum written on failure");
    CHECK(gls_stereo_eye(NULL, &adj, GLS_EYE_LEFT, &untouched, &offset_untouched) == GLS_ERROR_NULL_POINTER, "NULL mono");
    CHECK(gls_stereo_eye(&mono, NULL, GLS_EYE_LEFT, &untouched, &offset_untouched) == GLS_ERROR_NULL_POINTER, "NULL adj");
    CHECK(gls_stereo_eye(&mono, &adj, 7u, &untouched, &offset_untouched) == GLS_ERROR_INVALID_ENUM, "bad eye");
    CHECK(strstr(gls_last_error_message(), "eye") != NULL, "message: %s", gls_last_error_message());
    CHECK(untouched.left == 1 && offset_untouched == 42.0, "outputs written on failure");
    CHECK(gls_stereo_eye_matrix(&mono, &adj, 0xFFFFFFFFu, m) == GLS_ERROR_INVALID_ENUM, "bad eye (matrix)");
    CHECK(gls_stereo_eye_matrix(&mono, &adj, GLS_EYE_RIGHT, NULL) == GLS_ERROR_NULL_POINTER, "NULL matrix out");
    CHECK(gls_project_point(9.0, 1.0, point, 6u, m) == GLS_ERROR_INVALID_ENUM, "bad equation");

    /* Invalid values name the parameter. */
    gls_frustum bad = mono;
    bad.near_clip = 0.0;
    CHECK(gls_stereo_eye(&bad, &adj, GLS_EYE_LEFT, &untouched, &offset_untouched) == GLS_ERROR_INVALID_VALUE, "near 0");
    CHECK(strstr(gls_last_error_message(), "near_clip") != NULL, "message: %s", gls_last_error_message());
    gls_stereo_adjust bad_adj = {10.0, -1.0, 1.0};
    CHECK(gls_stereo_eye(&mono, &bad_adj, GLS_EYE_LEFT, &untouched, &offset_untouched) == GLS_ERROR_INVALID_VALUE, "negative offset adj");
    CHECK(strstr(gls_last_error_message(), "offset_adjustment") != NULL, "message: %s", gls_last_error_message());
    bad_adj.offset_adjustment = 1.0;
    bad_adj.zero_parallax_distance = NAN;
    CHECK(gls_stereo_eye(&mono, &bad_adj, GLS_EYE_LEFT, &untouched, &offset_untouched) == GLS_ERROR_INVALID_VALUE, "NaN distance");
    CHECK(untouched.left == 1 && offset_untouched == 42.0, "outputs written on failure");

    /* Result strings and the panic guard. */
    CHECK(strncmp(gls_result_string(GLS_ERROR_INVALID_ENUM), "GLS_ERROR_INVALID_ENUM", 22) == 0, "%s", gls_result_string(GLS_ERROR_INVALID_ENUM));
    CHECK(gls_debug_force_panic() == GLS_ERROR_PANIC, "forced panic");
    CHECK(strstr(gls_last_error_message(), "internal error") != NULL, "message: %s", gls_last_error_message());
    CHECK(gls_stereo_eye(&mono, &adj, GLS_EYE_LEFT, &left, &off_l) == GLS_OK, "library usable after a panic");

    /* Adjustment steps: x1.1, clamped to 0..2. */
    CHECK(close_to(gls_adjust_step(1.0, 1), 1.1), "step up");
    CHECK(gls_adjust_step(1.95, 1) == GLS_ADJUSTMENT_MAX, "clamped");

    return SUMMARY();
}

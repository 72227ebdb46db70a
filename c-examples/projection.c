/* projection: the stereo projection math of seed 000 without any GL.
 *
 * Prints the seed's worked example (Equations 1-5) and the left and right
 * eye frusta HP's method gives for a 50-degree camera, with the on-screen
 * parallax of a few depths against the 3% comfort budget. */
#include <stdio.h>

#include "glstereo.h"

static const char *const equation_names[] = {
    "", "Eq 1 mono", "Eq 2 left camera", "Eq 3 right camera",
    "Eq 4 left, zero parallax", "Eq 5 right, zero parallax"};

int main(void) {
    const double point[3] = {8.0, -5.0, -3.0};
    printf("glstereo %s: camera at (0, 0, 9), point (8, -5, -3), separation 1\n", gls_version());
    for (uint32_t eq = GLS_EQUATION_MONO; eq <= GLS_EQUATION_RIGHT_ZERO_PARALLAX; ++eq) {
        double xy[2];
        if (gls_project_point(9.0, 1.0, point, eq, xy) != GLS_OK) {
            fprintf(stderr, "%s\n", gls_last_error_message());
            return 1;
        }
        printf("  %-26s -> (%g, %g)\n", equation_names[eq], xy[0], xy[1]);
    }

    /* 50 degrees horizontal at 4:3, near 1, far 100, zero parallax at 10. */
    const double half_w = 0.4663076581549986; /* tan(25 deg) */
    gls_frustum mono = {-half_w, half_w, -half_w * 0.75, half_w * 0.75, 1.0, 100.0};
    gls_stereo_adjust adj = {10.0, GLS_ADJUSTMENT_DEFAULT, GLS_ADJUSTMENT_DEFAULT};
    for (uint32_t eye = GLS_EYE_LEFT; eye <= GLS_EYE_RIGHT; ++eye) {
        gls_frustum f;
        double offset;
        if (gls_stereo_eye(&mono, &adj, eye, &f, &offset) != GLS_OK) {
            fprintf(stderr, "%s\n", gls_last_error_message());
            return 1;
        }
        printf("%s eye: glFrustum(%.6f, %.6f, %.6f, %.6f, %g, %g); glTranslated(%.6f, 0, 0)\n",
               eye == GLS_EYE_LEFT ? "left " : "right", f.left, f.right, f.bottom, f.top,
               f.near_clip, f.far_clip, -offset);
    }
    const double depths[] = {5.0, 7.5, 10.0, 15.0, 20.0};
    for (size_t i = 0; i < sizeof depths / sizeof depths[0]; ++i) {
        double percent;
        gls_stereo_parallax_percent(&mono, &adj, depths[i], &percent);
        printf("  depth %5.1f: parallax %+6.2f%% of viewport width%s\n", depths[i], percent,
               percent > GLS_PARALLAX_BUDGET_DEFAULT || percent < -GLS_PARALLAX_BUDGET_DEFAULT
                   ? "  (outside the 3% comfort budget)" : "");
    }
    return 0;
}

/* xinerama: Xinerama "passive" stereo (seed 001) on any display.
 *
 * The program opens one double-width mono window (2W x H for W x H eyes)
 * and draws each eye itself into its half, with the asymmetric frusta of
 * seed 001 (eye separation = focal length / 30, Bourke's rule; focal length
 * at the airplane). Two projectors side by side would show the halves;
 * glstereo takes the halves apart (GLS_INPUT_SIDE_BY_SIDE) and shows the
 * eyes in any output format (--mode; default red-cyan), or the double-width
 * frame itself with --mode side-by-side. */
#include <GL/glx.h> /* GLX_* attribute names only */

#include "example.h"
#include "scene.h"

static int draw_eye(uint32_t eye, int x, int w, int h) {
    const double fov = 45.0, near_clip = 1.0, far_clip = 20.0;
    const double focal = AIRPLANE_DISTANCE, separation = focal / 30.0;
    gls_frustum f;
    double offset, m[16];
    gls_result r = gls_bourke_eye(fov, (double)w / h, near_clip, far_clip, separation, focal, eye, &f, &offset);
    if (r != GLS_OK) return example_fail("gls_bourke_eye", r);
    if ((r = gls_frustum_matrix(&f, offset, m)) != GLS_OK) return example_fail("gls_frustum_matrix", r);
    glViewport(x, 0, w, h); /* seed 001: (0,0,W,H) left, (W,0,W,H) right */
    redblue_rectangle(eye == GLS_EYE_RIGHT);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixd(m);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    airplane_draw();
    return 0;
}

int main(int argc, char **argv) {
    example_options opt = example_defaults();
    if (!example_parse(argc, argv, &opt)) return 2;
    const int w = (int)opt.width, h = (int)opt.height;

    gls_display *display;
    gls_config *config;
    gls_surface *surface;
    gls_result r;
    int mono_attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 16, None};
    if ((r = gls_display_open(GLS_BACKEND_AUTO, &display)) != GLS_OK) return example_fail("gls_display_open", r);
    if ((r = gls_config_choose(display, mono_attribs, &config)) != GLS_OK) return example_fail("gls_config_choose", r);
    /* One mono frame twice the eye width: both eyes side by side. */
    if ((r = gls_surface_create(display, config, 2u * opt.width, opt.height, &surface)) != GLS_OK)
        return example_fail("gls_surface_create", r);
    if ((r = gls_surface_set_input(surface, GLS_INPUT_SIDE_BY_SIDE)) != GLS_OK)
        return example_fail("gls_surface_set_input", r);
    if (example_apply_mode(surface, &opt)) return 1;
    if ((r = gls_make_current(surface)) != GLS_OK) return example_fail("gls_make_current", r);
    printf("xinerama: one %dx%d mono frame, eyes %dx%d side by side\n", 2 * w, h, w, h);

    glViewport(0, 0, 2 * w, h);
    glClearColor(0.2f, 0.2f, 0.2f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (draw_eye(GLS_EYE_LEFT, 0, w, h) || draw_eye(GLS_EYE_RIGHT, w, w, h)) return 1;
    if ((r = gls_swap_buffers(surface)) != GLS_OK) return example_fail("gls_swap_buffers", r);

    int status = example_save(surface, &opt);
    gls_make_current(NULL);
    gls_surface_destroy(surface);
    gls_config_free(config);
    gls_display_close(display);
    return status;
}

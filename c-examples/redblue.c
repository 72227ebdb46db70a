/* redblue: the RedBlue program of HP's stereo guide (seed 000 §4), on a
 * machine with no stereo hardware.
 *
 * A blue rectangle for the left eye, a red one for the right, on grey: with
 * working stereo and no glasses the overlap looks violet; the red-cyan
 * composite shows it black (no eye's filter passes it).
 *
 * The workflow is the seed's: ask for a stereo visual; if there is none,
 * tell the user and carry on in mono; draw each eye into its back buffer;
 * swap once for both. Run it headless (GLSTEREO_BACKEND=egl or osmesa) or in
 * a window (glx) without changing a line. */
#include <GL/glx.h> /* GLX_* attribute names only */

#include "example.h"

int main(int argc, char **argv) {
    example_options opt = example_defaults();
    if (!example_parse(argc, argv, &opt)) return 2;

    gls_display *display;
    gls_result r = gls_display_open(GLS_BACKEND_AUTO, &display);
    if (r != GLS_OK) return example_fail("gls_display_open", r);

    /* The seed's attribute list (seed 000 §3). */
    int stereo_attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                            GLX_BLUE_SIZE, 1, GLX_DEPTH_SIZE, 1, GLX_STEREO, None};
    int mono_attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                          GLX_BLUE_SIZE, 1, GLX_DEPTH_SIZE, 1, None};
    gls_config *config;
    r = gls_config_choose(display, stereo_attribs, &config);
    if (r == GLS_ERROR_NO_MATCHING_CONFIG) {
        /* The seed's advice: notify the user, then run without stereo. */
        fprintf(stderr, "redblue: stereo is not available (%s); running in mono\n", gls_last_error_message());
        r = gls_config_choose(display, mono_attribs, &config);
    }
    if (r != GLS_OK) return example_fail("gls_config_choose", r);
    const int stereo = gls_config_stereo(config) != GLS_STEREO_NONE;
    printf("redblue: %s stereo, %ux%u per eye\n",
           gls_config_stereo(config) == GLS_STEREO_NATIVE ? "native"
           : stereo                                      ? "emulated"
                                                         : "no",
           opt.width, opt.height);

    gls_surface *surface;
    r = gls_surface_create(display, config, opt.width, opt.height, &surface);
    if (r != GLS_OK) return example_fail("gls_surface_create", r);
    if (example_apply_mode(surface, &opt)) return 1;
    if ((r = gls_make_current(surface)) != GLS_OK) return example_fail("gls_make_current", r);

    /* Clear both back buffers. */
    gls_draw_buffer(GL_BACK);
    glClearColor(0.2f, 0.2f, 0.2f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);

    /* Left eye: blue. */
    if (stereo) gls_draw_buffer(GL_BACK_LEFT);
    glColor3b(0, 0, 127);
    glRectf(-0.8f, -0.8f, 0.2f, 0.2f);

    /* Right eye: red. */
    if (stereo) gls_draw_buffer(GL_BACK_RIGHT);
    glColor3b(127, 0, 0);
    glRectf(-0.2f, -0.2f, 0.8f, 0.8f);

    /* One swap puts both eyes on the display. */
    if ((r = gls_swap_buffers(surface)) != GLS_OK) return example_fail("gls_swap_buffers", r);

    int status = example_save(surface, &opt);
    gls_make_current(NULL);
    gls_surface_destroy(surface);
    gls_config_free(config);
    gls_display_close(display);
    return status;
}

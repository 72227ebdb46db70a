/* starbase: an HP Starbase full-screen stereo program (seed 000 §9) on a
 * machine with no stereo hardware.
 *
 * Starbase stereo is one mono frame: the program turns on sync-doubling
 * with gescape(STEREO), draws the left eye squashed 1:2 into the upper half
 * of the 1280x1024 screen and the right eye into the lower half; the
 * doubled vertical sync stretches each half over the whole screen for its
 * eye. glstereo reads the frame the same way, so the two eyes go to any
 * output format (--mode) and to left.png / right.png.
 *
 * Each eye shows the RedBlue rectangle (blue left, red right) and the
 * OGLPlane airplane through HP's stereo projection (seed 000 §6-7).
 *
 *   --quad-buffer  draw the same scene the windowed-OpenGL way instead
 *                  (seed 000 §3-4: GL_BACK_LEFT / GL_BACK_RIGHT at full
 *                  resolution), for comparison
 *   --save-mono    save the images after turning sync-doubling off again,
 *                  i.e. the plain mono frame with both squashed eyes */
#include <GL/glx.h> /* GLX_* attribute names for --quad-buffer */
#include <math.h>

#include <glstereo/starbase.h>

#include "example.h"
#include "scene.h"

/* One eye: its RedBlue rectangle, then the airplane through HP's
 * projection. `aspect` is the width/height of the eye as displayed. */
static int draw_eye(uint32_t eye, double aspect) {
    /* 50 degrees across, the seed's advice for a good stereo effect. */
    const double near_clip = 1.0, half_width = near_clip * tan(25.0 * 3.14159265358979 / 180.0);
    gls_frustum mono = {-half_width, half_width, -half_width / aspect, half_width / aspect, near_clip, 20.0};
    gls_stereo_adjust adjust = {AIRPLANE_DISTANCE, 1.0, 1.0};
    gls_result r;
    redblue_rectangle(eye == GLS_EYE_RIGHT);
    if ((r = gls_apply_stereo_eye(&mono, &adjust, eye)) != GLS_OK) return example_fail("gls_apply_stereo_eye", r);
    airplane_draw();
    return 0;
}

/* A Starbase call failed: -1 with errno, and the library's explanation. */
static int starbase_fail(const char *what) {
    fprintf(stderr, "%s failed: %s\n  %s\n", what, strerror(errno), gls_last_error_message());
    return 1;
}

static void clear_grey(void) {
    glClearColor(0.2f, 0.2f, 0.2f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

/* The Starbase way: one mono frame, sync-doubled. */
static int run_starbase(const example_options *opt, int save_mono) {
    const int w = (int)opt->width, h = (int)opt->height;
    gescape_arg arg1, arg2;
    gls_surface *surface;
    gls_result r;

    /* The display mode is set outside a Starbase program (HP's setmon); in
     * the emulation, the screen size gopen() opens. */
    if ((r = gls_screen_set_size(opt->width, opt->height)) != GLS_OK) return example_fail("gls_screen_set_size", r);
    int fildes = gopen("/dev/crt", OUTDEV, NULL, INIT | THREE_D);
    if (fildes < 0) return starbase_fail("gopen");
    if ((r = gls_starbase_surface(fildes, &surface)) != GLS_OK) return example_fail("gls_starbase_surface", r);
    if (example_apply_mode(surface, opt)) return 1;

    arg1.i[0] = TRUE; /* activate stereo sync-doubling */
    if (gescape(fildes, STEREO, &arg1, &arg2) != 0) return starbase_fail("gescape(STEREO, TRUE)");
    printf("starbase: sync-doubling on, %dx%d screen, each eye %dx%d squashed 1:2\n", w, h, w, h / 2);

    glViewport(0, 0, w, h);
    clear_grey();
    /* Left eye: the upper half (GL rows h/2 .. h-1). Its projection keeps
     * the aspect of the whole screen, which is what the eye sees once the
     * display stretches the half back to full height. */
    glViewport(0, h / 2, w, h - h / 2);
    if (draw_eye(GLS_EYE_LEFT, (double)w / h)) return 1;
    /* Right eye: the lower half. */
    glViewport(0, 0, w, h / 2);
    if (draw_eye(GLS_EYE_RIGHT, (double)w / h)) return 1;
    if ((r = gls_swap_buffers(surface)) != GLS_OK) return example_fail("gls_swap_buffers", r);

    if (!save_mono && example_save(surface, opt)) return 1;
    arg1.i[0] = FALSE; /* restore the non-stereo display */
    if (gescape(fildes, STEREO, &arg1, &arg2) != 0) return starbase_fail("gescape(STEREO, FALSE)");
    if (save_mono && example_save(surface, opt)) return 1;
    gclose(fildes);
    return 0;
}

/* The windowed-OpenGL way, at full resolution: the reference. */
static int run_quad_buffer(const example_options *opt) {
    int attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8,
                     GLX_DEPTH_SIZE, 24, GLX_STEREO, None};
    gls_display *display;
    gls_config *config;
    gls_surface *surface;
    gls_result r;
    if ((r = gls_display_open(GLS_BACKEND_AUTO, &display)) != GLS_OK) return example_fail("gls_display_open", r);
    if ((r = gls_config_choose(display, attribs, &config)) != GLS_OK) return example_fail("gls_config_choose", r);
    if ((r = gls_surface_create(display, config, opt->width, opt->height, &surface)) != GLS_OK)
        return example_fail("gls_surface_create", r);
    if (example_apply_mode(surface, opt)) return 1;
    if ((r = gls_make_current(surface)) != GLS_OK) return example_fail("gls_make_current", r);
    printf("starbase --quad-buffer: %ux%u per eye\n", opt->width, opt->height);

    gls_draw_buffer(GL_BACK);
    clear_grey();
    gls_draw_buffer(GL_BACK_LEFT);
    if (draw_eye(GLS_EYE_LEFT, (double)opt->width / opt->height)) return 1;
    gls_draw_buffer(GL_BACK_RIGHT);
    if (draw_eye(GLS_EYE_RIGHT, (double)opt->width / opt->height)) return 1;
    if ((r = gls_swap_buffers(surface)) != GLS_OK) return example_fail("gls_swap_buffers", r);

    int status = example_save(surface, opt);
    gls_make_current(NULL);
    gls_surface_destroy(surface);
    gls_config_free(config);
    gls_display_close(display);
    return status;
}

int main(int argc, char **argv) {
    example_options opt = example_defaults();
    int quad_buffer = 0, save_mono = 0;
    opt.width = 1280; /* Starbase stereo is full-screen: the seed's 1280x1024 */
    opt.height = 1024;
    /* This example's own flags; the rest go to the shared parser. */
    char **rest = malloc((size_t)argc * sizeof *rest);
    int n = 0;
    if (!rest) return 1;
    for (int i = 0; i < argc; ++i) {
        if (i > 0 && strcmp(argv[i], "--quad-buffer") == 0) quad_buffer = 1;
        else if (i > 0 && strcmp(argv[i], "--save-mono") == 0) save_mono = 1;
        else rest[n++] = argv[i];
    }
    int ok = example_parse(n, rest, &opt);
    free(rest);
    if (!ok) {
        fprintf(stderr, "  starbase also takes --quad-buffer or --save-mono\n");
        return 2;
    }
    if (opt.height < 2) {
        fprintf(stderr, "starbase: the screen needs at least 2 rows, one per eye\n");
        return 2;
    }
    return quad_buffer ? run_quad_buffer(&opt) : run_starbase(&opt, save_mono);
}

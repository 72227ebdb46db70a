/* irisgl: an SGI IRIS GL stereo program (seed 002) on a machine with no
 * stereo hardware.
 *
 * The default is SGI's oldest and commonest mode, STR_RECT: the program
 * checks getgdesc(GD_STEREO), remembers getmonitor(), switches with
 * setmonitor(STR_RECT), opens a full-screen window and draws the left eye
 * into the upper 492 rows (viewport(0, 1279, 532, 1023)) and the right eye
 * into the lower 492 (viewport(0, 1279, 0, 491)); the 40 rows between are
 * lost in the display's blanking. It restores the previous monitor mode
 * before it exits.
 *
 *   --square-pixel  SGI's windowed square-pixel stereo instead (when
 *                   getgdesc(GD_STEREO_IN_WINDOW) says it exists):
 *                   stereobuffer() + gconfig(), then leftbuffer() /
 *                   rightbuffer() select each eye's buffer
 *
 * Each eye shows the RedBlue rectangle (blue left, red right) and the
 * OGLPlane airplane through seed 002's window() / translate() projection.
 * The eyes go to any output format (--mode) and to left.png / right.png. */
#include <math.h>

#include <glstereo/irisgl.h>

#include "example.h"
#include "scene.h"

#define NEAR_CLIP 1.0f
#define FAR_CLIP 20.0f

/* One eye as seed 002 §7 writes it: window() with the frustum shifted by
 * half_sep * near / distance, then translate(+-half_sep). `aspect` is the
 * width/height of the display (full-screen STR_RECT) or window (square
 * pixels). */
static void draw_eye(int right_eye, float aspect) {
    const float top = NEAR_CLIP * (float)tan(20.0 * 3.14159265358979 / 180.0); /* 40 degrees high */
    const float distance = (float)AIRPLANE_DISTANCE;
    const float half_sep = 0.05f * distance / 2.0f; /* separation: 5% of the distance */
    const float shift = (right_eye ? -half_sep : half_sep) * NEAR_CLIP / distance;

    redblue_rectangle(right_eye);
    window(-top * aspect + shift, top * aspect + shift, -top, top, NEAR_CLIP, FAR_CLIP);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    translate(right_eye ? -half_sep : half_sep, 0.0f, 0.0f);
    airplane_draw();
}

static void clear_to(float grey) {
    glClearColor(grey, grey, grey, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

/* Full-screen above/below stereo. */
static int run_str_rect(const example_options *opt) {
    const long width = getgdesc(GD_XPMAX), height = getgdesc(GD_YPMAX); /* in pixels */
    /* SGI's 492 of 1024 rows per eye, for any screen height. */
    const long rows = (height * 492 + 512) / 1024;
    if (getgdesc(GD_STEREO) != 1) {
        fprintf(stderr, "irisgl: this system is not stereo-ready (getgdesc(GD_STEREO) is 0)\n");
        return 1;
    }
    if (rows < 1) {
        fprintf(stderr, "irisgl: a %ld-row screen has no rows for STR_RECT\n", height);
        return 2;
    }
    const long previous = getmonitor();
    setmonitor(STR_RECT);
    prefposition(0, width, 0, height); /* seed 002 §5 (clamped to the screen): full screen */
    long win = winopen("irisgl");
    if (win < 0) return 1;
    gls_surface *surface = glstereo_irisgl_surface(win);
    if (!surface || example_apply_mode(surface, opt)) return 1;
    doublebuffer();
    gconfig();
    printf("irisgl: STR_RECT, %ldx%ld screen, each eye %ldx%ld (vertical squash %.2f)\n", width, height, width, rows,
           (double)rows / height);

    /* The 40 lost rows stay black: they never reach an eye. */
    viewport(0, (Screencoord)(width - 1), 0, (Screencoord)(height - 1));
    clear_to(0.0f);
    /* Seed 002 §7: the eyes are rendered at a vertically squashed aspect
     * of about 0.48 (= 492 / 1024). The 492-row viewport squashes them;
     * window() takes the display's aspect, as the seed defines it. */
    viewport(0, (Screencoord)(width - 1), (Screencoord)(height - rows), (Screencoord)(height - 1));
    clear_to(0.2f);
    draw_eye(0, (float)width / (float)height);
    viewport(0, (Screencoord)(width - 1), 0, (Screencoord)(rows - 1));
    clear_to(0.2f);
    draw_eye(1, (float)width / (float)height);
    swapbuffers();

    int status = example_save(surface, opt);
    setmonitor((short)previous); /* back to the mode the user had */
    winclose(win);
    return status;
}

/* Windowed square-pixel stereo on the (emulated) quad buffer. */
static int run_square_pixel(const example_options *opt) {
    if (getgdesc(GD_STEREO_IN_WINDOW) != 1) {
        fprintf(stderr, "irisgl: no square-pixel stereo in windows (getgdesc(GD_STEREO_IN_WINDOW) is 0)\n");
        return 1;
    }
    prefposition(0, (long)opt->width - 1, 0, (long)opt->height - 1);
    long win = winopen("irisgl");
    if (win < 0) return 1;
    gls_surface *surface = glstereo_irisgl_surface(win);
    if (!surface || example_apply_mode(surface, opt)) return 1;
    stereobuffer();
    doublebuffer();
    gconfig();
    printf("irisgl: square-pixel stereo, %ux%u window\n", opt->width, opt->height);

    viewport(0, (Screencoord)(opt->width - 1), 0, (Screencoord)(opt->height - 1));
    leftbuffer(TRUE); /* both eyes' buffers at once */
    rightbuffer(TRUE);
    clear_to(0.2f);
    leftbuffer(TRUE); /* the left eye only (the initial default) */
    rightbuffer(FALSE);
    draw_eye(0, (float)opt->width / (float)opt->height);
    leftbuffer(FALSE); /* the right eye only */
    rightbuffer(TRUE);
    draw_eye(1, (float)opt->width / (float)opt->height);
    swapbuffers();

    int status = example_save(surface, opt);
    winclose(win);
    return status;
}

int main(int argc, char **argv) {
    example_options opt = example_defaults();
    int square_pixel = 0;
    opt.width = 1280; /* the seed's 1280x1024 screen */
    opt.height = 1024;
    /* This example's own flag; the rest go to the shared parser. */
    char **rest = malloc((size_t)argc * sizeof *rest);
    int n = 0;
    if (!rest) return 1;
    for (int i = 0; i < argc; ++i) {
        if (i > 0 && strcmp(argv[i], "--square-pixel") == 0) square_pixel = 1;
        else rest[n++] = argv[i];
    }
    int ok = example_parse(n, rest, &opt);
    free(rest);
    if (!ok) {
        fprintf(stderr, "  irisgl also takes --square-pixel\n");
        return 2;
    }
    if (opt.width > 32767 || opt.height > 32767) {
        fprintf(stderr, "irisgl: IRIS GL screen coordinates are shorts: at most 32767 pixels\n");
        return 2;
    }
    /* The display mode is set outside an IRIS GL program (setmon); in the
     * emulation, the size of the screen winopen() opens on. */
    gls_result r = gls_screen_set_size(opt.width, opt.height);
    if (r != GLS_OK) return example_fail("gls_screen_set_size", r);
    return square_pixel ? run_square_pixel(&opt) : run_str_rect(&opt);
}

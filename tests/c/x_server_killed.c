/* The X server dies under a running program: the library reports
 * GLS_ERROR_DISPLAY_LOST instead of Xlib's exit(), and the program can
 * still exit normally without cleaning up (no hang in exit-time cleanup). */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "glstereo.h"

/* The render thread: sets up, swaps until the server is gone, returns the
 * exit status. The main thread then exits while the render thread is gone,
 * as a multi-threaded viewer would. */
static void *render(void *arg) {
    int *status = arg;
    *status = 1;
    gls_display *d;
    gls_config *c;
    gls_surface *s;
    const int attribs[] = {4 /* GLX_RGBA */, 5 /* GLX_DOUBLEBUFFER */, 6 /* GLX_STEREO */, 0};
    if (gls_display_open(GLS_BACKEND_GLX, &d) || gls_config_choose(d, attribs, &c) ||
        gls_surface_create(d, c, 64, 64, &s) || gls_make_current(s) || gls_swap_buffers(s)) {
        printf("setup failed: %s\n", gls_last_error_message());
        return NULL;
    }
    printf("ready\n");
    fflush(stdout);
    const struct timespec pause = {0, 50 * 1000 * 1000};
    for (int i = 0; i < 400; ++i) { /* up to 20 s */
        gls_result r = gls_swap_buffers(s);
        if (r != GLS_OK) {
            printf("swap: %s\n%s\n", gls_result_string(r), gls_last_error_message());
            *status = r == GLS_ERROR_DISPLAY_LOST ? 0 : 1;
            return NULL;
        }
        nanosleep(&pause, NULL);
    }
    printf("the lost server was never reported\n");
    return NULL;
}

int main(void) {
    int status = 1;
    pthread_t t;
    if (pthread_create(&t, NULL, render, &status) != 0) return 1;
    pthread_join(t, NULL);
    fflush(stdout);
    return status; /* exit without closing anything */
}

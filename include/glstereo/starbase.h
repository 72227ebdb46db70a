/*
 * glstereo/starbase.h: HP Starbase full-screen stereo (seed 000 §9) on
 * glstereo. Hand-written compat header: it maps Starbase's names onto the
 * gls_starbase_* functions of <glstereo.h>; the library exports only gls_
 * names. C99; include it with -I path/to/include.
 *
 * What a Starbase program does, and what the emulation does with it:
 *
 *   int fildes = gopen("/dev/crt", OUTDEV, NULL, INIT | THREE_D);
 *     Opens the emulated screen: a mono, double-buffered surface the size
 *     of gls_screen_get_size() (1280x1024 unless gls_screen_set_size() said
 *     otherwise), current on the calling thread so GL calls draw into it.
 *     path, driver and mode are accepted and ignored. A program that
 *     already has a gls_surface gets a descriptor for it with
 *     gls_starbase_fildes(surface, &fildes) instead.
 *
 *   gescape_arg arg1, arg2;
 *   arg1.i[0] = TRUE;                         (FALSE restores mono)
 *   gescape(fildes, STEREO, &arg1, &arg2);
 *     Sync-doubling on: the surface's frame is read as left eye = upper
 *     half, right eye = lower half, each stretched x2 vertically, as the
 *     doubled vertical sync shows it. Draw each eye squashed 1:2 into its
 *     half (glViewport(0, H/2, W, H - H/2) for the left, (0, 0, W, H/2) for
 *     the right). The two eyes then go to every output format
 *     (gls_surface_set_output) and capture (gls_surface_save_png).
 *
 *   gls_starbase_surface(fildes, &surface);   the gls_surface, to present
 *                                             and capture it
 *   gclose(fildes);                           destroys a gopen() surface
 *
 * Errors: gopen() returns -1, gescape() and gclose() return -1 (Starbase's
 * own gescape returns nothing; the value is for programs that check), with
 * errno set and gls_last_error_message() saying why:
 *   EBADF   fildes is not a live descriptor (never opened, closed, or its
 *           surface destroyed)
 *   EINVAL  an opcode other than STEREO, a gopen() kind other than OUTDEV
 *           or OUTINDEV, or a surface under 2 rows
 *   EFAULT  arg1 is NULL
 *   ENODEV  no GL backend could be opened (gopen)
 *   ENOMEM  out of memory (gopen)
 * Nothing changes on error.
 */
#ifndef GLSTEREO_STARBASE_H
#define GLSTEREO_STARBASE_H

#include <errno.h>

#include <glstereo.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifndef TRUE
#define TRUE 1
#endif
#ifndef FALSE
#define FALSE 0
#endif

/* gopen() kinds, HP's values. The emulated screen is an output device. */
#define OUTDEV GLS_STARBASE_OUTDEV
#define INDEV 1
#define OUTINDEV GLS_STARBASE_OUTINDEV

/* gopen() mode bits, HP's values: accepted and ignored. */
#define SPOOLED 0x01
#define INIT 0x02
#define THREE_D 0x04
#define RESET_DEVICE 0x08
#define MODEL_XFORM 0x10
#define INT_XFORM 0x20
#define FLOAT_XFORM 0x40

/* HP's argument block: 64 ints, 64 floats or 255 chars (256 bytes). */
typedef gls_gescape_arg gescape_arg;

/* The stereo escape. HP's numeric value is not public; this is glstereo's
 * (9000, outside HP's published opcode ranges). Use the name. */
#define STEREO GLS_STARBASE_STEREO

/* Turns a gls_result into Starbase's -1 with errno. */
static inline int glstereo_starbase_fail(gls_result r) {
    switch (r) {
    case GLS_ERROR_INVALID_HANDLE: errno = EBADF; break;
    case GLS_ERROR_NULL_POINTER: errno = EFAULT; break;
    case GLS_ERROR_BACKEND_UNAVAILABLE: errno = ENODEV; break;
    case GLS_ERROR_OUT_OF_MEMORY: errno = ENOMEM; break;
    default: errno = EINVAL; break;
    }
    return -1;
}

static inline int gopen(const char *path, int kind, const char *driver, int mode) {
    int32_t fildes;
    gls_result r;
    (void)path;
    (void)driver;
    (void)mode;
    r = gls_starbase_open(kind, &fildes);
    return r == GLS_OK ? (int)fildes : glstereo_starbase_fail(r);
}

static inline int gclose(int fildes) {
    gls_result r = gls_starbase_close(fildes);
    return r == GLS_OK ? 0 : glstereo_starbase_fail(r);
}

static inline int gescape(int fildes, int op, gescape_arg *arg1, gescape_arg *arg2) {
    gls_result r = gls_starbase_gescape(fildes, op, arg1, arg2);
    return r == GLS_OK ? 0 : glstereo_starbase_fail(r);
}

#ifdef __cplusplus
}
#endif

#endif /* GLSTEREO_STARBASE_H */

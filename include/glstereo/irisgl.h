/*
 * glstereo/irisgl.h: SGI IRIS GL's stereo subset (seed 002) on glstereo.
 * Hand-written compat header: it maps IRIS GL's names onto the gls_irisgl_*
 * functions of <glstereo.h>; the library exports only gls_ names. C99;
 * include it with -I path/to/include. Drawing itself is OpenGL: a ported
 * program keeps IRIS GL's window, monitor, buffer and projection calls and
 * draws with gl* calls (link -lGL, or -lOSMesa for the OSMesa backend).
 *
 * Getting a window: as in IRIS GL,
 *     prefposition(0, getgdesc(GD_XPMAX), 0, getgdesc(GD_YPMAX));
 *     long win = winopen("");
 * opens a window on the emulated screen (1280x1024 unless
 * gls_screen_set_size() said otherwise; GLSTEREO_BACKEND picks the backend)
 * and makes it current. glstereo_irisgl_surface(win) gives its gls_surface,
 * to capture it (gls_surface_save_png) or pick its output format.
 *
 * What each call does in the emulation:
 *   getgdesc(GD_XPMAX / GD_YPMAX)   screen width / height in pixels (1280,
 *                                   1024); SGI's programs use value - 1 as
 *                                   the last pixel. Other inquiries than the
 *                                   four below return -1.
 *   getgdesc(GD_STEREO)             1: every window can use the STR_* modes
 *   getgdesc(GD_STEREO_IN_WINDOW)   1 when windows get stereo buffers (the
 *                                   emulated quad buffer; 0 with
 *                                   GLSTEREO_EMULATION=off)
 *   getmonitor() / setmonitor(m)    process-wide mode, initially HZ60. HZ60,
 *                                   HZ72: mono (square-pixel stereo windows
 *                                   show their left/right buffers); STR_RECT:
 *                                   left eye = rows 532-1023, right eye = rows
 *                                   0-491 of 1024, 40 rows lost, each
 *                                   stretched to the full height; STR_TOP /
 *                                   STR_BOT: the top / bottom 492-row band,
 *                                   to both eyes, from the left / right
 *                                   buffer of a stereo window. Save
 *                                   getmonitor() first and setmonitor() it
 *                                   back before exit.
 *   stereobuffer() / monobuffer()   take effect at gconfig(); mono draws
 *   doublebuffer() / singlebuffer() reach both eyes alike. New windows are
 *   gconfig()                       mono and single-buffered.
 *   leftbuffer(b) / rightbuffer(b)  which eyes drawing reaches in stereo
 *                                   mode (left is the initial default; both
 *                                   may be TRUE): GL_BACK_LEFT, GL_BACK_RIGHT,
 *                                   GL_BACK or GL_NONE (FRONT ones when
 *                                   single-buffered)
 *   swapbuffers()                   presents both eyes; ignored when
 *                                   single-buffered, as in IRIS GL
 *   viewport(l, r, b, t)            inclusive pixels -> glViewport(l, b,
 *                                   r-l+1, t-b+1); like IRIS GL's it also
 *                                   sets the screenmask (glScissor, with
 *                                   GL_SCISSOR_TEST enabled)
 *   window(l, r, b, t, n, f)        glFrustum into GL_PROJECTION
 *   translate(x, y, z)              glTranslate of the current matrix
 *
 * Errors: IRIS GL's calls return nothing; as IRIS GL did, the emulation
 * prints what went wrong to stderr (the text of gls_last_error_message())
 * and changes nothing. getgdesc() returns -1 and winopen() -1 on error.
 *
 * Define GLSTEREO_IRISGL_NO_TYPES before including this header if another
 * header already defines Boolean, Screencoord or Coord.
 */
#ifndef GLSTEREO_IRISGL_H
#define GLSTEREO_IRISGL_H

#include <stdio.h>

#include <glstereo.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifndef GLSTEREO_IRISGL_NO_TYPES
typedef long Boolean;
typedef short Screencoord;
typedef float Coord;
#endif

#ifndef TRUE
#define TRUE 1
#endif
#ifndef FALSE
#define FALSE 0
#endif

/* getgdesc inquiries, SGI's values (IRIX <gl/gl.h>). */
#define GD_XPMAX GLS_IRISGL_GD_XPMAX
#define GD_YPMAX GLS_IRISGL_GD_YPMAX
#define GD_STEREO GLS_IRISGL_GD_STEREO
#define GD_STEREO_IN_WINDOW GLS_IRISGL_GD_STEREO_IN_WINDOW

/* Monitor types, SGI's values (IRIX <gl/get.h>). */
#define HZ60 GLS_IRISGL_HZ60
#define STR_RECT GLS_IRISGL_STR_RECT
#define HZ72 GLS_IRISGL_HZ72
#define STR_BOT GLS_IRISGL_STR_BOT
#define STR_TOP GLS_IRISGL_STR_TOP

/* Prints a failed call's message, as IRIS GL reported errors; returns
 * whether the call succeeded. */
static inline int glstereo_irisgl_check(gls_result r) {
    if (r != GLS_OK) fprintf(stderr, "IRIS GL emulation: %s\n", gls_last_error_message());
    return r == GLS_OK;
}

static inline long getgdesc(long inquiry) {
    int64_t v;
    if (inquiry < INT32_MIN || inquiry > INT32_MAX) inquiry = -1;
    if (gls_irisgl_getgdesc((int32_t)inquiry, &v) != GLS_OK) return -1;
    return (long)v;
}

static inline long getmonitor(void) {
    int32_t m = 0;
    glstereo_irisgl_check(gls_irisgl_getmonitor(&m));
    return m;
}

static inline void setmonitor(short type) { glstereo_irisgl_check(gls_irisgl_setmonitor(type)); }

static inline void prefposition(long x1, long x2, long y1, long y2) {
    glstereo_irisgl_check(gls_irisgl_prefposition((int32_t)x1, (int32_t)x2, (int32_t)y1, (int32_t)y2));
}

static inline long winopen(const char *title) {
    int32_t win;
    if (!glstereo_irisgl_check(gls_irisgl_winopen(title, &win))) return -1;
    return win;
}

static inline void winclose(long win) { glstereo_irisgl_check(gls_irisgl_winclose((int32_t)win)); }

/* The gls_surface of a winopen() window (NULL, with a message, if none). */
static inline gls_surface *glstereo_irisgl_surface(long win) {
    gls_surface *s = NULL;
    if (!glstereo_irisgl_check(gls_irisgl_surface((int32_t)win, &s))) return NULL;
    return s;
}

static inline void stereobuffer(void) { glstereo_irisgl_check(gls_irisgl_stereobuffer()); }
static inline void monobuffer(void) { glstereo_irisgl_check(gls_irisgl_monobuffer()); }
static inline void doublebuffer(void) { glstereo_irisgl_check(gls_irisgl_doublebuffer()); }
static inline void singlebuffer(void) { glstereo_irisgl_check(gls_irisgl_singlebuffer()); }
static inline void gconfig(void) { glstereo_irisgl_check(gls_irisgl_gconfig()); }
static inline void leftbuffer(Boolean b) { glstereo_irisgl_check(gls_irisgl_leftbuffer(b != 0)); }
static inline void rightbuffer(Boolean b) { glstereo_irisgl_check(gls_irisgl_rightbuffer(b != 0)); }
static inline void swapbuffers(void) { glstereo_irisgl_check(gls_irisgl_swapbuffers()); }

static inline void viewport(Screencoord left, Screencoord right, Screencoord bottom, Screencoord top) {
    glstereo_irisgl_check(gls_irisgl_viewport(left, right, bottom, top));
}

static inline void window(Coord left, Coord right, Coord bottom, Coord top, Coord near_clip, Coord far_clip) {
    glstereo_irisgl_check(gls_irisgl_window(left, right, bottom, top, near_clip, far_clip));
}

static inline void translate(Coord x, Coord y, Coord z) { glstereo_irisgl_check(gls_irisgl_translate(x, y, z)); }

#ifdef __cplusplus
}
#endif

#endif /* GLSTEREO_IRISGL_H */

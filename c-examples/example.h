/* The command line and image output every glstereo example shares:
 *
 *   --out DIR     write DIR/left.png, DIR/right.png and DIR/composite.png
 *   --size WxH    size of each eye (default 640x480)
 *   --mode NAME   output format of the composite (see the README)
 *   --modes LIST  also write DIR/composite-NAME.png for each output format
 *                 in the comma-separated LIST (e.g. rows,side-by-side)
 *
 * Header-only, C99 + POSIX, so each example stays one small file. */
#ifndef GLSTEREO_EXAMPLE_H
#define GLSTEREO_EXAMPLE_H

#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "glstereo.h"

typedef struct example_options {
    const char *out_dir; /* NULL: write no images */
    unsigned width, height;
    const char *mode; /* NULL: the surface's default (GLSTEREO_MODE or red-cyan) */
    const char *modes; /* NULL, or more formats to write composites in: "a,b,c" */
} example_options;

static inline void example_usage(const char *prog, const char *extra) {
    fprintf(stderr, "usage: %s [--out DIR] [--size WxH] [--mode NAME] [--modes LIST]%s%s\n", prog,
            extra ? " " : "", extra ? extra : "");
}

/* Parses the shared option at argv[*i] (and its value), advancing *i.
 * Returns 1 if consumed, 0 if not a shared option, -1 on a bad value. */
static inline int example_parse_common(int *i, int argc, char **argv, example_options *o) {
    const char *arg = argv[*i];
    if ((strcmp(arg, "--out") == 0 || strcmp(arg, "--size") == 0 || strcmp(arg, "--mode") == 0 ||
         strcmp(arg, "--modes") == 0) &&
        *i + 1 >= argc) {
        fprintf(stderr, "%s needs a value\n", arg);
        return -1;
    }
    if (strcmp(arg, "--out") == 0) {
        o->out_dir = argv[++*i];
        return 1;
    }
    if (strcmp(arg, "--size") == 0) {
        const char *v = argv[++*i];
        char tail;
        if (sscanf(v, "%ux%u%c", &o->width, &o->height, &tail) != 2 || o->width == 0 || o->height == 0) {
            fprintf(stderr, "--size wants WxH, e.g. 640x480, not %s\n", v);
            return -1;
        }
        return 1;
    }
    if (strcmp(arg, "--mode") == 0) {
        o->mode = argv[++*i];
        return 1;
    }
    if (strcmp(arg, "--modes") == 0) {
        o->modes = argv[++*i];
        return 1;
    }
    return 0;
}

static inline example_options example_defaults(void) {
    example_options o;
    o.out_dir = NULL;
    o.width = 640;
    o.height = 480;
    o.mode = NULL;
    o.modes = NULL;
    return o;
}

/* Parses a command line that has only the shared options. (inline: examples
 * with options of their own use example_parse_common instead.) */
static inline int example_parse(int argc, char **argv, example_options *o) {
    for (int i = 1; i < argc; ++i) {
        int r = example_parse_common(&i, argc, argv, o);
        if (r != 1) {
            if (r == 0) fprintf(stderr, "unknown option %s\n", argv[i]);
            example_usage(argv[0], NULL);
            return 0;
        }
    }
    return 1;
}

/* Prints the library's last error after a failed call and returns 1. */
static inline int example_fail(const char *what, gls_result r) {
    fprintf(stderr, "%s failed: %s\n  %s\n", what, gls_result_string(r), gls_last_error_message());
    return 1;
}

static inline int example_mkdir_p(const char *dir) {
    char path[4096];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof path) return -1;
    memcpy(path, dir, n + 1);
    for (char *p = path + 1; *p; ++p) {
        if (*p == '/') {
            *p = '\0';
            if (mkdir(path, 0777) != 0 && errno != EEXIST) return -1;
            *p = '/';
        }
    }
    return (mkdir(path, 0777) != 0 && errno != EEXIST) ? -1 : 0;
}

/* Applies --mode (if given) to the surface's output format. */
static inline int example_apply_mode(gls_surface *surface, const example_options *o) {
    uint32_t mode;
    gls_result r;
    if (!o->mode) return 0;
    if ((r = gls_output_from_name(o->mode, &mode)) != GLS_OK) return example_fail("--mode", r);
    if ((r = gls_surface_set_output(surface, mode)) != GLS_OK) return example_fail("gls_surface_set_output", r);
    return 0;
}

/* Writes DIR/composite-NAME.png for each name in o->modes, then puts the
 * surface's own output format back. */
static inline int example_save_modes(gls_surface *surface, const example_options *o) {
    uint32_t own, mode;
    gls_result r;
    if (!o->modes) return 0;
    if ((r = gls_surface_get_output(surface, &own)) != GLS_OK) return example_fail("gls_surface_get_output", r);
    for (const char *name = o->modes; *name;) {
        char one[64], path[4096];
        size_t n = strcspn(name, ",");
        if (n == 0 || n >= sizeof one) {
            fprintf(stderr, "--modes: bad list %s\n", o->modes);
            return 1;
        }
        memcpy(one, name, n);
        one[n] = '\0';
        name += n + (name[n] == ',');
        if ((r = gls_output_from_name(one, &mode)) != GLS_OK) return example_fail("--modes", r);
        if ((r = gls_surface_set_output(surface, mode)) != GLS_OK) return example_fail("gls_surface_set_output", r);
        int len = snprintf(path, sizeof path, "%s/composite-%s.png", o->out_dir, gls_output_name(mode));
        if (len < 0 || (size_t)len >= sizeof path) {
            fprintf(stderr, "--out: the directory name is too long: %s\n", o->out_dir);
            return 1;
        }
        if ((r = gls_surface_save_png(surface, GLS_IMAGE_COMPOSITE, path)) != GLS_OK)
            return example_fail("gls_surface_save_png", r);
        printf("wrote %s\n", path);
    }
    if ((r = gls_surface_set_output(surface, own)) != GLS_OK) return example_fail("gls_surface_set_output", r);
    return 0;
}

/* Writes left.png, right.png and composite.png into o->out_dir (if set),
 * and a composite-NAME.png per --modes entry. */
static inline int example_save(gls_surface *surface, const example_options *o) {
    static const struct { uint32_t image; const char *name; } files[] = {
        {GLS_IMAGE_LEFT, "left.png"}, {GLS_IMAGE_RIGHT, "right.png"}, {GLS_IMAGE_COMPOSITE, "composite.png"}};
    if (!o->out_dir) return 0;
    if (example_mkdir_p(o->out_dir) != 0) {
        fprintf(stderr, "cannot create %s: %s\n", o->out_dir, strerror(errno));
        return 1;
    }
    for (size_t k = 0; k < sizeof files / sizeof files[0]; ++k) {
        char path[4096];
        int len = snprintf(path, sizeof path, "%s/%s", o->out_dir, files[k].name);
        if (len < 0 || (size_t)len >= sizeof path) {
            fprintf(stderr, "--out: the directory name is too long: %s\n", o->out_dir);
            return 1;
        }
        gls_result r = gls_surface_save_png(surface, files[k].image, path);
        if (r != GLS_OK) return example_fail("gls_surface_save_png", r);
        printf("wrote %s\n", path);
    }
    return example_save_modes(surface, o);
}

#endif

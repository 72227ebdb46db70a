/*
 * What the dynamic loader answers for the calls a program makes around
 * libGL, printed as facts that do not depend on addresses, so the output
 * under glstereo-run can be compared with the output without it
 * (tests/clients.rs). Links neither libGL nor glstereo: -ldl only.
 *
 * Lines:
 *   other-library OPENED SYMBOL VALUE   dlopen("libm.so.6"), dlsym "cos", cos(0)
 *   other-handle-gl-name NULL ERROR     dlsym(libm handle, "glClear")
 *   open NAME OPENED                    dlopen(NAME) for each GL library name,
 *                                       and libGL.so.1 by its absolute path
 *                                       (NAME "by-path")
 *   known NAME FOUND                    dlsym(handle, "glGetString") (a GL name the
 *                                       layer does not replace: the stub of a
 *                                       GL library answers the layer's
 *                                       replacements on every handle)
 *   unknown NAME NULL ERROR             dlsym(handle, "glNoSuchFunctionGLS"), dlerror() != NULL
 *   close NAME RESULT                   dlclose(handle)
 *   default-unknown NULL ERROR          dlsym(RTLD_DEFAULT, "glNoSuchFunctionGLS")
 *   next-unknown NULL ERROR             dlsym(RTLD_NEXT, "glNoSuchFunctionGLS")
 *   missing-library NULL ERROR          dlopen("libglstereo-no-such.so.1")
 *   layer NAME SAME                     with GLSTEREO_PROBE_LAYERED set (under
 *                                       the layer): dlsym(handle, "glXChooseVisual")
 *                                       ("glDrawBuffer" for libOpenGL, which has
 *                                       no GLX) is the function dlsym(RTLD_DEFAULT,
 *                                       …) finds: the layer's
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The names; "by-path" stands for libGL.so.1's absolute file name as the
 * loader found it (it depends on the architecture). */
static const char *const gl_names[] = {"libGL.so.1", "libGL.so", "libGLX.so.0", "libOpenGL.so.0", "by-path"};

/* libGL.so.1's absolute file name (static storage), or "" if not found:
 * the file of its glClear, which no layer replaces. */
static const char *libgl_path(void)
{
    static char path[4096];
    Dl_info info;
    void *h = dlopen("libGL.so.1", RTLD_NOW | RTLD_LOCAL);
    void *known = h != NULL ? dlsym(h, "glGetString") : NULL;
    if (known != NULL && dladdr(known, &info) != 0 && info.dli_fname != NULL && info.dli_fname[0] == '/') {
        snprintf(path, sizeof path, "%s", info.dli_fname);
    }
    if (h != NULL) {
        dlclose(h);
    }
    return path;
}

int main(void)
{
    int layered = getenv("GLSTEREO_PROBE_LAYERED") != NULL;
    size_t i;
    void *m = dlopen("libm.so.6", RTLD_NOW | RTLD_LOCAL);
    void *cos_sym = m != NULL ? dlsym(m, "cos") : NULL;
    double (*cos_fn)(double) = NULL;
    if (cos_sym != NULL) {
        *(void **)(&cos_fn) = cos_sym;
    }
    printf("other-library %d %d %g\n", m != NULL, cos_sym != NULL, cos_fn != NULL ? cos_fn(0.0) : -1.0);
    if (m != NULL) {
        void *p;
        dlerror();
        p = dlsym(m, "glClear");
        printf("other-handle-gl-name %d %d\n", p == NULL, dlerror() != NULL);
    }
    for (i = 0; i < sizeof gl_names / sizeof gl_names[0]; i++) {
        const char *name = gl_names[i];
        const char *file = strcmp(name, "by-path") == 0 ? libgl_path() : name;
        void *h = dlopen(file, RTLD_NOW | RTLD_LOCAL);
        void *p;
        printf("open %s %d\n", name, h != NULL);
        if (h == NULL) {
            continue;
        }
        printf("known %s %d\n", name, dlsym(h, "glGetString") != NULL);
        dlerror();
        p = dlsym(h, "glNoSuchFunctionGLS");
        printf("unknown %s %d %d\n", name, p == NULL, dlerror() != NULL);
        if (layered) {
            const char *fn = strstr(name, "libOpenGL") != NULL ? "glDrawBuffer" : "glXChooseVisual";
            void *mine = dlsym(h, fn);
            printf("layer %s %d\n", name, mine != NULL && mine == dlsym(RTLD_DEFAULT, fn));
        }
        printf("close %s %d\n", name, dlclose(h));
    }
    dlerror();
    void *p = dlsym(RTLD_DEFAULT, "glNoSuchFunctionGLS");
    printf("default-unknown %d %d\n", p == NULL, dlerror() != NULL);
    dlerror();
    p = dlsym(RTLD_NEXT, "glNoSuchFunctionGLS");
    printf("next-unknown %d %d\n", p == NULL, dlerror() != NULL);
    p = dlopen("libglstereo-no-such.so.1", RTLD_NOW);
    printf("missing-library %d %d\n", p == NULL, dlerror() != NULL);
    return 0;
}

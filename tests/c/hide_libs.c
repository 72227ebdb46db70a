/* LD_PRELOAD shim for tests/faults.rs, used where the test cannot make a
 * private library directory without some libraries (no user and mount
 * namespaces), beside stand-ins on LD_LIBRARY_PATH that make every look-up
 * by name fail: this catches the look-ups by path the stand-ins cannot
 * (x11-dl tries /usr/lib/<arch>/libGL.so.1 after "libGL.so.1"). dlopen()
 * of a library whose file name starts with one of the ':'-separated
 * prefixes in GLSTEREO_TEST_HIDE fails as for a missing file ("cannot
 * open shared object file: No such file or directory"), from whichever
 * library calls it through the global dlopen (glstereo, libglvnd). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

typedef void *(*dlopen_fn)(const char *, int);

static int hidden(const char *file) {
    const char *hide = getenv("GLSTEREO_TEST_HIDE");
    if (!file || !hide) return 0;
    const char *base = strrchr(file, '/');
    base = base ? base + 1 : file;
    while (*hide) {
        size_t n = strcspn(hide, ":");
        if (n > 0 && strncmp(base, hide, n) == 0) return 1;
        hide += n + (hide[n] == ':');
    }
    return 0;
}

void *dlopen(const char *file, int mode) {
    void *p = dlsym(RTLD_NEXT, "dlopen");
    dlopen_fn real;
    memcpy(&real, &p, sizeof p);
    if (hidden(file)) {
        /* The loader's own error for a file that is not there. */
        const char *base = strrchr(file, '/');
        char missing[512] = "/nonexistent/glstereo-test-hidden/";
        strncat(missing, base ? base + 1 : file, sizeof missing - strlen(missing) - 1);
        return real(missing, mode);
    }
    return real(file, mode);
}

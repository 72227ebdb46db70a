/* LD_PRELOAD shim for the sanitizer runs of GLX programs (tests/sanitize.rs):
 * dlclose() keeps the library loaded.
 *
 * Why: XCloseDisplay makes Mesa's GLX unload its DRI driver (swrast_dri.so),
 * whose globals still point at a few blocks it allocated (240 bytes with
 * Mesa 22.3). LeakSanitizer runs at exit, after the unload, no longer scans
 * those globals and reports the blocks as leaked "from <unknown module>" —
 * a plain GLX program without glstereo shows the same report. With the
 * driver kept in memory, LeakSanitizer sees them reachable, as they are,
 * and any real leak is still reported, with module names in its stack. */
int dlclose(void *handle);

int dlclose(void *handle)
{
    (void)handle;
    return 0;
}

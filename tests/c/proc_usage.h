/*
 * What a test program uses of the machine, for tests that check it stays
 * flat: resident memory (KB), heap in use (KB) and open descriptors, from
 * /proc/self and glibc's malloc.
 *
 * Resident memory alone measures glibc's free pages as much as the
 * program's: a round that holds 9 MB for a moment grows an arena that is
 * not given back while a live chunk sits above the hole, and which arena
 * (one per thread that meets another in malloc, so more of them on a busy
 * machine) decides by how much. So each sample first gives glibc's free
 * pages back (malloc_trim), and a window of rounds is summed up by its
 * smallest sample (a round that holds something for a moment is not the
 * program growing). A leak raises every later sample; noise does not.
 */
#ifndef GLSTEREO_TEST_PROC_USAGE_H
#define GLSTEREO_TEST_PROC_USAGE_H

#include <dirent.h>
#include <malloc.h>
#include <stdio.h>
#include <unistd.h>

static inline void usage(long *rss, int *fds)
{
    malloc_trim(0);
    FILE *f = fopen("/proc/self/statm", "r");
    long pages = 0, resident = 0;
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &resident) != 2)
            resident = 0;
        fclose(f);
    }
    *rss = resident * (sysconf(_SC_PAGESIZE) / 1024);
    *fds = 0;
    DIR *d = opendir("/proc/self/fd");
    if (d) {
        while (readdir(d))
            (*fds)++;
        closedir(d);
    }
}

/* A window of rounds: the smallest resident memory and heap in use (KB)
 * of its samples, and the most descriptors. */
struct usage_window {
    long rss, heap;
    int fds, samples;
};

static inline void usage_sample(struct usage_window *w)
{
    long rss;
    int fds;
    usage(&rss, &fds);
    struct mallinfo2 m = mallinfo2();
    long heap = (long)((m.uordblks + m.hblkhd) / 1024);
    if (w->samples == 0 || rss < w->rss)
        w->rss = rss;
    if (w->samples == 0 || heap < w->heap)
        w->heap = heap;
    if (w->samples == 0 || fds > w->fds)
        w->fds = fds;
    w->samples++;
}

/* Samples round `i` of `rounds` into `early` (the second quarter of the
 * rounds, after a quarter of warm-up) or `late` (the last quarter). */
static inline void usage_round(int i, int rounds, struct usage_window *early,
                               struct usage_window *late)
{
    int q = rounds / 4;
    if (i >= q && i < 2 * q)
        usage_sample(early);
    else if (i >= rounds - q)
        usage_sample(late);
}

/* "usage rss EARLY LATE fds EARLY LATE heap EARLY LATE". */
static inline void usage_print(const struct usage_window *early, const struct usage_window *late)
{
    printf("usage rss %ld %ld fds %d %d heap %ld %ld\n", early->rss, late->rss, early->fds,
           late->fds, early->heap, late->heap);
}

#endif

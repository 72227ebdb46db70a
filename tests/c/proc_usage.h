/*
 * What a test program uses of the machine, for tests that check it stays
 * flat: resident memory (KB) and open descriptors, from /proc/self.
 */
#ifndef GLSTEREO_TEST_PROC_USAGE_H
#define GLSTEREO_TEST_PROC_USAGE_H

#include <dirent.h>
#include <stdio.h>
#include <unistd.h>

static inline void usage(long *rss, int *fds)
{
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

#endif

/* Tiny test harness for the C tests: CHECK counts, SUMMARY prints the
 * "N passed, N failed" line and gives the exit status. */
#ifndef GLSTEREO_TEST_CHECK_H
#define GLSTEREO_TEST_CHECK_H
#include <stdio.h>

static int check_passed, check_failed;

#define CHECK(cond, ...)                                                        \
    do {                                                                        \
        if (cond) {                                                             \
            ++check_passed;                                                     \
        } else {                                                                \
            ++check_failed;                                                     \
            fprintf(stderr, "%s:%d: FAILED: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                       \
            fputc('\n', stderr);                                                \
        }                                                                       \
    } while (0)

#define SUMMARY()                                                       \
    (printf("%d passed, %d failed\n", check_passed, check_failed),     \
     check_failed == 0 ? 0 : 1)

#endif

/*
 * A stereo GLX program (links only -lGL -lX11) that forks, as programs do
 * to run a helper, and whose child ends in one of the ways a process can.
 * Under glstereo-run --capture the child inherits the capture queue of its
 * parent but none of its threads: the child must end as it would without
 * the layer, and the parent's captures must all be written.
 *
 *   fork_exit WAY     WAY is how the child ends:
 *                       exit     exit(0) (atexit handlers run)
 *                       _exit    _exit(0) (none run)
 *                       return   the child returns 0 from main
 *                       exec     execl("/bin/true"), as fork + exec does
 *
 * The parent presents 3 stereo frames (left eye red, right eye blue),
 * forks right after the last swap (its captures still being written),
 * waits for the child, presents 3 more frames and exits. It prints
 * "child WAY: exited N" or "child WAY: killed by signal N"; exit 0 when the
 * child exited 0, 1 otherwise.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

#include "x_window.h"

static void frames(struct x_window *x, int n)
{
    for (int i = 0; i < n; i++) {
        glDrawBuffer(GL_BACK_LEFT);
        glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glDrawBuffer(GL_BACK_RIGHT);
        glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glXSwapBuffers(x->display, x->window);
    }
}

int main(int argc, char **argv)
{
    const char *way = argc > 1 ? argv[1] : "";
    if (strcmp(way, "exit") != 0 && strcmp(way, "_exit") != 0 && strcmp(way, "return") != 0 &&
        strcmp(way, "exec") != 0) {
        fprintf(stderr, "usage: fork_exit exit|_exit|return|exec\n");
        return 2;
    }
    int attributes[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_STEREO, None};
    struct x_window x = open_x_window(attributes, 64, 48);
    frames(&x, 3);

    fflush(stdout);
    pid_t child = fork();
    if (child < 0) {
        perror("fork");
        return 1;
    }
    if (child == 0) {
        if (strcmp(way, "exit") == 0) {
            exit(0);
        }
        if (strcmp(way, "_exit") == 0) {
            _exit(0);
        }
        if (strcmp(way, "exec") == 0) {
            execl("/bin/true", "true", (char *)NULL);
            _exit(127);
        }
        return 0; /* "return": exit(0) from main's caller */
    }
    int status = 0;
    if (waitpid(child, &status, 0) != child) {
        perror("waitpid");
        return 1;
    }
    if (WIFEXITED(status)) {
        printf("child %s: exited %d\n", way, WEXITSTATUS(status));
    } else if (WIFSIGNALED(status)) {
        printf("child %s: killed by signal %d\n", way, WTERMSIG(status));
    }

    frames(&x, 3);
    close_x_window(&x);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : 1;
}

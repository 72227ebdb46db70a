/*
 * A GLFW 3.3 stereo program that draws continuously and reports its keys:
 * the GLFW client of tests/keys.rs (glstereo's live keys). As
 * glfw_stereo.c: GLFW_STEREO, a 3.3 core-profile context, GL functions from
 * glfwGetProcAddress, linked only with -lglfw. Run it under glstereo-run.
 *
 * It draws the frame of eyes.h every 20 ms (glfwWaitEventsTimeout), prints
 * the first frame's buffers and report as glfw_stereo does, then "ready",
 * and for each key event GLFW reports prints
 *   key press|release|repeat <GLFW key code> mods 0x<mods>
 * (GLFW_KEY_A is 65, GLFW_KEY_F7 296, GLFW_MOD_CONTROL 0x2). Escape ends
 * it (exit 0). Without a stereo window it says why and exits 2.
 */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "eyes.h"

static void on_error(int code, const char *what)
{
    fprintf(stderr, "GLFW error 0x%x: %s\n", code, what);
}

static eyes_proc lookup(const char *name)
{
    return glfwGetProcAddress(name);
}

static void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode;
    printf("key %s %d mods 0x%x\n",
           action == GLFW_PRESS ? "press" : action == GLFW_RELEASE ? "release" : "repeat", key,
           (unsigned)mods);
    fflush(stdout);
    if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS) {
        glfwSetWindowShouldClose(window, GLFW_TRUE);
    }
}

int main(void)
{
    const int width = 160, height = 120;
    glfwSetErrorCallback(on_error);
    if (!glfwInit()) {
        return 1;
    }
    glfwWindowHint(GLFW_STEREO, GLFW_TRUE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow *window = glfwCreateWindow(width, height, "glfw_keys", NULL, NULL);
    if (window == NULL) {
        fprintf(stderr, "no stereo window\n");
        glfwTerminate();
        return 2;
    }
    glfwMakeContextCurrent(window);
    glfwSetKeyCallback(window, on_key);
    if (!eyes_load(lookup, 1)) {
        return 1;
    }
    int first = 1;
    while (!glfwWindowShouldClose(window)) {
        if (!eyes_draw(width, height)) {
            return 1;
        }
        if (first) {
            eyes_report_back(width, height);
        }
        glfwSwapBuffers(window);
        if (first) {
            eyes_report_front(width, height);
            printf("report gl_stereo %d toolkit_stereo 1 error 0x%x\n", eyes_gl_stereo(),
                   eyes_gl.GetError());
            printf("ready\n");
            fflush(stdout);
            first = 0;
        }
        glfwWaitEventsTimeout(0.02);
    }
    glfwDestroyWindow(window);
    glfwTerminate();
    return 0;
}

/*
 * A GLFW 3.3 stereo program, as its documentation writes one:
 * glfwWindowHint(GLFW_STEREO, GLFW_TRUE) (a hard constraint: no stereo, no
 * window) with a 3.3 core-profile context, GL functions from
 * glfwGetProcAddress. Unmodified: it links only -lglfw; GLFW itself loads
 * libGL with dlopen. Run it under glstereo-run.
 *
 *   glfw_stereo          stereo, as above
 *   glfw_stereo mono     no GLFW_STEREO hint: the left eye's picture in GL_BACK
 *
 * It draws the frame of eyes.h once, prints the back buffers, swaps, prints
 * the front buffers, "report gl_stereo S toolkit_stereo T error E" and
 * "ready", then waits for a line on stdin (the test grabs the window,
 * titled "glfw_stereo") and exits 0. Without a window it says why and
 * exits 2.
 */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <string.h>

#include "eyes.h"

static void on_error(int code, const char *what)
{
    fprintf(stderr, "GLFW error 0x%x: %s\n", code, what);
}

static eyes_proc lookup(const char *name)
{
    return glfwGetProcAddress(name);
}

int main(int argc, char **argv)
{
    const int width = 160, height = 120;
    int mono = argc > 1 && strcmp(argv[1], "mono") == 0;
    char line[64];
    glfwSetErrorCallback(on_error);
    if (!glfwInit()) {
        return 1;
    }
    glfwWindowHint(GLFW_STEREO, mono ? GLFW_FALSE : GLFW_TRUE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow *window = glfwCreateWindow(width, height, "glfw_stereo", NULL, NULL);
    if (window == NULL) {
        fprintf(stderr, "no stereo window\n");
        glfwTerminate();
        return 2;
    }
    glfwMakeContextCurrent(window);
    if (!eyes_load(lookup, 1) || !(mono ? eyes_draw_mono(width, height) : eyes_draw(width, height))) {
        return 1;
    }
    if (mono) {
        eyes_report(GL_BACK, "BACK", width, height);
    } else {
        eyes_report_back(width, height);
    }
    glfwSwapBuffers(window);
    if (mono) {
        eyes_report(GL_FRONT, "FRONT", width, height);
    } else {
        eyes_report_front(width, height);
    }
    /* GLFW has no stereo query (glfwGetWindowAttrib does not take
     * GLFW_STEREO): the hint is a hard constraint, so GLFW's answer is
     * that the window exists. */
    printf("report gl_stereo %d toolkit_stereo %d error 0x%x\n", eyes_gl_stereo(),
           window != NULL && !mono, eyes_gl.GetError());
    printf("ready\n");
    fflush(stdout);
    if (fgets(line, sizeof line, stdin) == NULL) {
        /* EOF: exit as well. */
    }
    glfwDestroyWindow(window);
    glfwTerminate();
    return 0;
}

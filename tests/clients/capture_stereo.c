/*
 * A GLFW 3.3 core-profile stereo program that draws several frames, for GL
 * debuggers stacked with glstereo. Under RenderDoc (librenderdoc.so loaded
 * by renderdoccmd) it asks RenderDoc's in-app API for a capture of one
 * frame, as a user pressing F12 would, with RenderDoc's overlay off (the
 * window shows the frame alone).
 *
 *   capture_stereo FRAMES CAPTURE
 *
 * Draws the frame of eyes.h FRAMES times (a swap each), calls
 * TriggerCapture() before frame CAPTURE when RenderDoc is loaded, prints
 * the back buffers of the last frame, swaps, prints the front buffers,
 * "renderdoc N" (1: its API was found), "report gl_stereo S toolkit_stereo
 * T error E" and "ready", then waits for a line on stdin (the test grabs
 * the window, titled "capture_stereo") and exits 0. Without a window it
 * says why and exits 2.
 */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

#include <renderdoc_app.h>

#include "eyes.h"

static void on_error(int code, const char *what)
{
    fprintf(stderr, "GLFW error 0x%x: %s\n", code, what);
}

static eyes_proc lookup(const char *name)
{
    return glfwGetProcAddress(name);
}

/* RenderDoc's in-app API, when the program runs under RenderDoc. */
static RENDERDOC_API_1_1_2 *renderdoc(void)
{
    RENDERDOC_API_1_1_2 *api = NULL;
    pRENDERDOC_GetAPI get;
    void *lib = dlopen("librenderdoc.so", RTLD_NOW | RTLD_NOLOAD);
    void *sym;
    if (lib == NULL) {
        return NULL;
    }
    sym = dlsym(lib, "RENDERDOC_GetAPI");
    memcpy(&get, &sym, sizeof get);
    if (get == NULL || get(eRENDERDOC_API_Version_1_1_2, (void **)&api) != 1) {
        return NULL;
    }
    /* No overlay over the frame: the test reads the window's pixels. */
    api->MaskOverlayBits(eRENDERDOC_Overlay_None, eRENDERDOC_Overlay_None);
    return api;
}

int main(int argc, char **argv)
{
    const int width = 160, height = 120;
    int frames = argc > 1 ? atoi(argv[1]) : 10;
    int capture = argc > 2 ? atoi(argv[2]) : 5;
    RENDERDOC_API_1_1_2 *rdoc = renderdoc();
    char line[64];
    int i;
    glfwSetErrorCallback(on_error);
    if (!glfwInit()) {
        return 1;
    }
    glfwWindowHint(GLFW_STEREO, GLFW_TRUE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow *window = glfwCreateWindow(width, height, "capture_stereo", NULL, NULL);
    if (window == NULL) {
        fprintf(stderr, "no stereo window\n");
        glfwTerminate();
        return 2;
    }
    glfwMakeContextCurrent(window);
    if (!eyes_load(lookup, 1)) {
        return 1;
    }
    for (i = 0; i < frames; i++) {
        if (rdoc != NULL && i == capture) {
            rdoc->TriggerCapture();
        }
        if (!eyes_draw(width, height)) {
            return 1;
        }
        if (i + 1 < frames) {
            glfwSwapBuffers(window);
            glfwPollEvents();
        }
    }
    eyes_report_back(width, height);
    glfwSwapBuffers(window);
    eyes_report_front(width, height);
    printf("renderdoc %d\n", rdoc != NULL);
    printf("report gl_stereo %d toolkit_stereo %d error 0x%x\n", eyes_gl_stereo(), 1,
           eyes_gl.GetError());
    printf("ready\n");
    fflush(stdout);
    if (fgets(line, sizeof line, stdin) == NULL) {
        /* EOF: exit as well. */
    }
    glfwDestroyWindow(window);
    glfwTerminate();
    return 0;
}

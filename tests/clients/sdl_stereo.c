/*
 * An SDL2 stereo program: SDL_GL_SetAttribute(SDL_GL_STEREO, 1), GL
 * functions from SDL_GL_GetProcAddress. Unmodified: it links only -lSDL2;
 * SDL loads libGL with dlopen. Run it under glstereo-run.
 *
 *   sdl_stereo default   SDL's default context (compatibility, glRectf)
 *   sdl_stereo core      a 3.2 core-profile context (GLSL 1.50)
 *
 * It draws the frame of eyes.h once, prints the back buffers, swaps, prints
 * the front buffers, "report gl_stereo S toolkit_stereo T error E" (T is
 * SDL_GL_GetAttribute(SDL_GL_STEREO)) and "ready", then waits for a line on
 * stdin (the test grabs the window, titled "sdl_stereo") and exits 0.
 * Without a window it says why and exits 2.
 */
#include <string.h>

#include <SDL2/SDL.h>

#include "eyes.h"

static eyes_proc lookup(const char *name)
{
    void *p = SDL_GL_GetProcAddress(name);
    eyes_proc f;
    memcpy(&f, &p, sizeof f);
    return f;
}

int main(int argc, char **argv)
{
    const int width = 160, height = 120;
    int core = argc > 1 && strcmp(argv[1], "core") == 0;
    int stereo = -1;
    char line[64];
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "SDL_Init: %s\n", SDL_GetError());
        return 1;
    }
    SDL_GL_SetAttribute(SDL_GL_STEREO, 1);
    SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
    if (core) {
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 2);
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
    }
    SDL_Window *window = SDL_CreateWindow("sdl_stereo", 0, 0, width, height, SDL_WINDOW_OPENGL);
    if (window == NULL) {
        fprintf(stderr, "no stereo window: %s\n", SDL_GetError());
        SDL_Quit();
        return 2;
    }
    SDL_GLContext context = SDL_GL_CreateContext(window);
    if (context == NULL) {
        fprintf(stderr, "no context: %s\n", SDL_GetError());
        return 2;
    }
    if (!eyes_load(lookup, core) || !eyes_draw(width, height)) {
        return 1;
    }
    eyes_report_back(width, height);
    SDL_GL_SwapWindow(window);
    eyes_report_front(width, height);
    SDL_GL_GetAttribute(SDL_GL_STEREO, &stereo);
    printf("report gl_stereo %d toolkit_stereo %d error 0x%x\n", eyes_gl_stereo(), stereo,
           eyes_gl.GetError());
    printf("ready\n");
    fflush(stdout);
    if (fgets(line, sizeof line, stdin) == NULL) {
        /* EOF: exit as well. */
    }
    SDL_GL_DeleteContext(context);
    SDL_DestroyWindow(window);
    SDL_Quit();
    return 0;
}

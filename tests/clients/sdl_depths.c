/*
 * A mono SDL2 OpenGL ES 2.0 program drawing through EGL on X11
 * (SDL_HINT_VIDEO_X11_FORCE_EGL, as SDL_VIDEO_X11_FORCE_EGL=1 asks), with a
 * perspective scene and a HUD, for glstereo-run --auto (tests/egl.rs). It
 * never asks for stereo (EGL has none); GL functions come from
 * SDL_GL_GetProcAddress (it links only -lSDL2; SDL dlopens libEGL and
 * libGLESv2). Its shaders are GLSL ES 1.00 without a #version line.
 *
 * The scene (window 240x160, black), as tests/clients/glfw_depths.c draws
 * it:
 *   red square   clip w 2 (near), centre (-0.5, 0.3) in NDC, half size 0.15
 *   green square clip w 4,        centre ( 0,   0.3)
 *   blue square  clip w 8 (far),  centre ( 0.5, 0.3)
 * under the frustum (-1, 1, -1, 1, 1, 100) (w = -z_eye), and
 *   white bar    (-0.8, -0.8)-(0.8, -0.6) under the identity (w 1: a HUD).
 *
 * It draws one frame, swaps, prints "report error E" and "ready", then
 * waits for a line on stdin (the test grabs the window, titled
 * "sdl_depths") and exits 0. Without a window or context it says why and
 * exits 2.
 */
#include <stdio.h>
#include <string.h>

#include <SDL2/SDL.h>
#include <GLES2/gl2.h>

#define FUNCTIONS(F)                                                                              \
    F(PFNGLCREATESHADERPROC, CreateShader)                                                        \
    F(PFNGLSHADERSOURCEPROC, ShaderSource)                                                        \
    F(PFNGLCOMPILESHADERPROC, CompileShader)                                                      \
    F(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                      \
    F(PFNGLATTACHSHADERPROC, AttachShader)                                                        \
    F(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)                                            \
    F(PFNGLLINKPROGRAMPROC, LinkProgram)                                                          \
    F(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                        \
    F(PFNGLUSEPROGRAMPROC, UseProgram)                                                            \
    F(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                            \
    F(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                                \
    F(PFNGLUNIFORM3FPROC, Uniform3f)                                                              \
    F(PFNGLGENBUFFERSPROC, GenBuffers)                                                            \
    F(PFNGLBINDBUFFERPROC, BindBuffer)                                                            \
    F(PFNGLBUFFERDATAPROC, BufferData)                                                            \
    F(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                                          \
    F(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                                  \
    F(PFNGLDRAWARRAYSPROC, DrawArrays)                                                            \
    F(PFNGLCLEARCOLORPROC, ClearColor)                                                            \
    F(PFNGLCLEARPROC, Clear)                                                                      \
    F(PFNGLVIEWPORTPROC, Viewport)                                                                \
    F(PFNGLGETERRORPROC, GetError)

#define DECLARE(type, name) static type gl_##name;
FUNCTIONS(DECLARE)

static int load(void)
{
#define LOAD(type, name)                                                                          \
    {                                                                                             \
        void *p = SDL_GL_GetProcAddress("gl" #name);                                              \
        if (p == NULL) {                                                                          \
            fprintf(stderr, "no gl" #name "\n");                                                  \
            return 0;                                                                             \
        }                                                                                         \
        memcpy(&gl_##name, &p, sizeof p);                                                         \
    }
    FUNCTIONS(LOAD)
    return 1;
}

static const char *vertex_source = "attribute vec3 position;\n"
                                   "uniform mat4 u_matrix;\n"
                                   "void main() { gl_Position = u_matrix * vec4(position, 1.0); }\n";
static const char *fragment_source = "precision mediump float;\n"
                                     "uniform vec3 u_colour;\n"
                                     "void main() { gl_FragColor = vec4(u_colour, 1.0); }\n";

/* The frustum (-1, 1, -1, 1, 1, 100), column major. */
static const GLfloat frustum[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -101.0f / 99, -1, 0, 0, -200.0f / 99, 0};
static const GLfloat identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* Two triangles of the rectangle (x0, y0)-(x1, y1) in NDC at clip w
 * `w` (w 0: the HUD, z 0 under the identity). */
static void square(GLfloat *v, float x0, float y0, float x1, float y1, float w)
{
    const float corners[6][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y0}, {x1, y1}, {x0, y1}};
    for (int i = 0; i < 6; i++) {
        float s = w > 0 ? w : 1;
        v[3 * i] = corners[i][0] * s;
        v[3 * i + 1] = corners[i][1] * s;
        v[3 * i + 2] = w > 0 ? -w : 0;
    }
}

int main(void)
{
    const int width = 240, height = 160;
    char line[64];
    SDL_SetHint(SDL_HINT_VIDEO_X11_FORCE_EGL, "1");
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "SDL_Init: %s\n", SDL_GetError());
        return 2;
    }
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_ES);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 2);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 0);
    SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
    SDL_Window *window = SDL_CreateWindow("sdl_depths", 0, 0, width, height, SDL_WINDOW_OPENGL);
    if (window == NULL) {
        fprintf(stderr, "no window: %s\n", SDL_GetError());
        SDL_Quit();
        return 2;
    }
    SDL_GLContext context = SDL_GL_CreateContext(window);
    if (context == NULL) {
        fprintf(stderr, "no context: %s\n", SDL_GetError());
        return 2;
    }
    if (!load()) {
        return 1;
    }
    GLuint vs = gl_CreateShader(GL_VERTEX_SHADER), fs = gl_CreateShader(GL_FRAGMENT_SHADER);
    gl_ShaderSource(vs, 1, &vertex_source, NULL);
    gl_ShaderSource(fs, 1, &fragment_source, NULL);
    gl_CompileShader(vs);
    gl_CompileShader(fs);
    GLuint program = gl_CreateProgram();
    gl_AttachShader(program, vs);
    gl_AttachShader(program, fs);
    gl_BindAttribLocation(program, 0, "position");
    gl_LinkProgram(program);
    GLint linked = 0;
    gl_GetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        fprintf(stderr, "the program does not link\n");
        return 1;
    }
    GLfloat v[4 * 18];
    square(v, -0.65f, 0.15f, -0.35f, 0.45f, 2);
    square(v + 18, -0.15f, 0.15f, 0.15f, 0.45f, 4);
    square(v + 36, 0.35f, 0.15f, 0.65f, 0.45f, 8);
    square(v + 54, -0.8f, -0.8f, 0.8f, -0.6f, 0);
    GLuint vbo;
    gl_GenBuffers(1, &vbo);
    gl_BindBuffer(GL_ARRAY_BUFFER, vbo);
    gl_BufferData(GL_ARRAY_BUFFER, sizeof v, v, GL_STATIC_DRAW);
    gl_VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, NULL);
    gl_EnableVertexAttribArray(0);
    gl_UseProgram(program);
    GLint matrix = gl_GetUniformLocation(program, "u_matrix");
    GLint colour = gl_GetUniformLocation(program, "u_colour");

    gl_Viewport(0, 0, width, height);
    gl_ClearColor(0, 0, 0, 1);
    gl_Clear(GL_COLOR_BUFFER_BIT);
    gl_UniformMatrix4fv(matrix, 1, GL_FALSE, frustum);
    const GLfloat colours[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int i = 0; i < 3; i++) {
        gl_Uniform3f(colour, colours[i][0], colours[i][1], colours[i][2]);
        gl_DrawArrays(GL_TRIANGLES, 6 * i, 6);
    }
    gl_UniformMatrix4fv(matrix, 1, GL_FALSE, identity);
    gl_Uniform3f(colour, 1, 1, 1);
    gl_DrawArrays(GL_TRIANGLES, 18, 6);
    SDL_GL_SwapWindow(window);
    printf("report error 0x%x\n", gl_GetError());
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

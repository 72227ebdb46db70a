/*
 * A mono GLFW 3.3 core-profile program with a perspective scene and a HUD,
 * for glstereo-run --auto (tests/auto_clients.rs). It never asks for
 * stereo; GL functions come from glfwGetProcAddress (it links only -lglfw,
 * GLFW dlopens libGL).
 *
 * The scene (window 240x160, black), one GLSL 3.30 program whose vertex
 * shader is gl_Position = u_matrix * position:
 *   red square   clip w 2 (near), centre (-0.5, 0.3) in NDC, half size 0.15
 *   green square clip w 4,        centre ( 0,   0.3)
 *   blue square  clip w 8 (far),  centre ( 0.5, 0.3)
 * with u_matrix the frustum (-1, 1, -1, 1, 1, 100) (x_clip = x_eye,
 * w_clip = -z_eye), so each square has the same size on the screen;
 *   white bar    (-0.8, -0.8)-(0.8, -0.6), u_matrix the identity (w 1: a HUD).
 *
 * It draws one frame, swaps, prints "report error E" and "ready", then
 * waits for a line on stdin (the test grabs the window, titled
 * "glfw_depths") and exits 0.
 *
 *   glfw_depths [egl]      egl: the context made through EGL
 *                          (GLFW_EGL_CONTEXT_API) instead of GLX
 */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <stddef.h>
#include <stdio.h>

/* The core profile's declarations, without prototypes: every function
 * below is looked up. */
#include <GL/glcorearb.h>

#define FUNCTIONS(F)                                                                              \
    F(PFNGLCREATESHADERPROC, CreateShader)                                                        \
    F(PFNGLSHADERSOURCEPROC, ShaderSource)                                                        \
    F(PFNGLCOMPILESHADERPROC, CompileShader)                                                      \
    F(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                      \
    F(PFNGLATTACHSHADERPROC, AttachShader)                                                        \
    F(PFNGLLINKPROGRAMPROC, LinkProgram)                                                          \
    F(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                        \
    F(PFNGLUSEPROGRAMPROC, UseProgram)                                                            \
    F(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                            \
    F(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                                \
    F(PFNGLUNIFORM3FPROC, Uniform3f)                                                              \
    F(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                                  \
    F(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                  \
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

#define DECLARE(type, name) static type gl##name;
FUNCTIONS(DECLARE)

static int load(void)
{
#define LOAD(type, name)                                                                          \
    gl##name = (type)glfwGetProcAddress("gl" #name);                                              \
    if (gl##name == NULL) {                                                                       \
        fprintf(stderr, "no gl" #name "\n");                                                      \
        return 0;                                                                                 \
    }
    FUNCTIONS(LOAD)
    return 1;
}

static const char *vertex_source = "#version 330 core\n"
                                   "layout(location = 0) in vec3 position;\n"
                                   "uniform mat4 u_matrix;\n"
                                   "void main() { gl_Position = u_matrix * vec4(position, 1.0); }\n";
static const char *fragment_source = "#version 330 core\n"
                                     "uniform vec3 u_colour;\n"
                                     "out vec4 colour;\n"
                                     "void main() { colour = vec4(u_colour, 1.0); }\n";

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

int main(int argc, char **argv)
{
    const int width = 240, height = 160;
    char line[64];
    if (!glfwInit()) {
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    if (argc > 1 && argv[1][0] == 'e') {
        glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
    }
    GLFWwindow *window = glfwCreateWindow(width, height, "glfw_depths", NULL, NULL);
    if (window == NULL) {
        fprintf(stderr, "no window\n");
        glfwTerminate();
        return 2;
    }
    glfwMakeContextCurrent(window);
    if (!load()) {
        return 1;
    }
    GLuint vs = glCreateShader(GL_VERTEX_SHADER), fs = glCreateShader(GL_FRAGMENT_SHADER);
    glShaderSource(vs, 1, &vertex_source, NULL);
    glShaderSource(fs, 1, &fragment_source, NULL);
    glCompileShader(vs);
    glCompileShader(fs);
    GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        fprintf(stderr, "the program does not link\n");
        return 1;
    }
    GLfloat v[4 * 18];
    square(v, -0.65f, 0.15f, -0.35f, 0.45f, 2);
    square(v + 18, -0.15f, 0.15f, 0.15f, 0.45f, 4);
    square(v + 36, 0.35f, 0.15f, 0.65f, 0.45f, 8);
    square(v + 54, -0.8f, -0.8f, 0.8f, -0.6f, 0);
    GLuint vao, vbo;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof v, v, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, NULL);
    glEnableVertexAttribArray(0);
    glUseProgram(program);
    GLint matrix = glGetUniformLocation(program, "u_matrix");
    GLint colour = glGetUniformLocation(program, "u_colour");

    glViewport(0, 0, width, height);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glUniformMatrix4fv(matrix, 1, GL_FALSE, frustum);
    const GLfloat colours[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int i = 0; i < 3; i++) {
        glUniform3f(colour, colours[i][0], colours[i][1], colours[i][2]);
        glDrawArrays(GL_TRIANGLES, 6 * i, 6);
    }
    glUniformMatrix4fv(matrix, 1, GL_FALSE, identity);
    glUniform3f(colour, 1, 1, 1);
    glDrawArrays(GL_TRIANGLES, 18, 6);
    glfwSwapBuffers(window);
    printf("report error 0x%x\n", glGetError());
    printf("ready\n");
    fflush(stdout);
    if (fgets(line, sizeof line, stdin) == NULL) {
        /* EOF: exit as well. */
    }
    glfwDestroyWindow(window);
    glfwTerminate();
    return 0;
}

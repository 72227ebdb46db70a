/*
 * The explicit API and shaders: a program linked with gls_link_program()
 * writes its user-defined output 0 into every buffer gls_draw_buffer()
 * selects (both eyes under GL_BACK), checked in each eye's pixels; misuse
 * gets the documented codes. EGL backend, GL functions through
 * gls_get_proc_address().
 */
#include <stdio.h>
#include <string.h>

#include "glstereo.h"
#include "check.h"

#define GL_TRIANGLES 0x0004
#define GL_FRAGMENT_SHADER 0x8B30
#define GL_VERTEX_SHADER 0x8B31
#define GL_LINK_STATUS 0x8B82
#define GL_BACK_LEFT 0x0402
#define GL_BACK_RIGHT 0x0403
#define GL_BACK 0x0405
#define GL_COLOR_BUFFER_BIT 0x4000
#define GL_INVALID_VALUE 0x0501

typedef unsigned (*CreateShader)(unsigned);
typedef void (*ShaderSource)(unsigned, int, const char *const *, const int *);
typedef void (*Uint)(unsigned);
typedef unsigned (*CreateProgram)(void);
typedef void (*AttachShader)(unsigned, unsigned);
typedef void (*GetProgramiv)(unsigned, unsigned, int *);
typedef void (*DrawArrays)(unsigned, int, int);
typedef void (*ClearColor)(float, float, float, float);

static CreateShader create_shader;
static ShaderSource shader_source;
static Uint compile_shader, use_program, clear;
static CreateProgram create_program;
static AttachShader attach_shader;
static GetProgramiv get_programiv;
static DrawArrays draw_arrays;
static ClearColor clear_color;

/* A function pointer from gls_get_proc_address (memcpy: ISO C has no
 * cast from an object pointer to a function pointer). */
#define LOAD(var, type, name)                      \
    do {                                           \
        void *p_ = gls_get_proc_address(name);     \
        memcpy(&var, &p_, sizeof var);             \
        (void)sizeof(type);                        \
    } while (0)

static const char *VS = "#version 330 core\n"
                        "void main() {\n"
                        "    vec2 p = vec2(float(gl_VertexID % 2) * 4.0 - 1.0, float(gl_VertexID / 2) * 4.0 - 1.0);\n"
                        "    gl_Position = vec4(p, 0.0, 1.0);\n"
                        "}\n";

static unsigned program(const char *fs)
{
    unsigned p = create_program();
    const char *src[2] = {VS, fs};
    for (int i = 0; i < 2; i++) {
        unsigned s = create_shader(i == 0 ? GL_VERTEX_SHADER : GL_FRAGMENT_SHADER);
        shader_source(s, 1, &src[i], NULL);
        compile_shader(s);
        attach_shader(p, s);
    }
    return p;
}

/* The centre pixel of an eye's back buffer. */
static void centre(gls_surface *s, uint32_t buffer, unsigned char out[4])
{
    static unsigned char px[32 * 16 * 4];
    memset(out, 0, 4);
    if (gls_surface_read_pixels(s, buffer, px, sizeof px) == GLS_OK) {
        memcpy(out, px + (8 * 32 + 16) * 4, 4);
    }
}

int main(void)
{
    gls_display *d = NULL;
    gls_config *c = NULL;
    gls_surface *s = NULL;
    const int attrs[] = {4 /* GLX_RGBA */, 5 /* GLX_DOUBLEBUFFER */, 6 /* GLX_STEREO */, 0};
    CHECK(gls_link_program(1) == GLS_ERROR_NO_CURRENT_SURFACE, "no current surface");
    if (gls_display_open(GLS_BACKEND_EGL, &d) != GLS_OK || gls_config_choose(d, attrs, &c) != GLS_OK ||
        gls_surface_create(d, c, 32, 16, &s) != GLS_OK || gls_make_current(s) != GLS_OK) {
        fprintf(stderr, "no EGL surface: %s\n", gls_last_error_message());
        return 2;
    }
    LOAD(create_shader, CreateShader, "glCreateShader");
    LOAD(shader_source, ShaderSource, "glShaderSource");
    LOAD(compile_shader, Uint, "glCompileShader");
    LOAD(use_program, Uint, "glUseProgram");
    LOAD(clear, Uint, "glClear");
    LOAD(create_program, CreateProgram, "glCreateProgram");
    LOAD(attach_shader, AttachShader, "glAttachShader");
    LOAD(get_programiv, GetProgramiv, "glGetProgramiv");
    LOAD(draw_arrays, DrawArrays, "glDrawArrays");
    LOAD(clear_color, ClearColor, "glClearColor");

    unsigned p = program("#version 330 core\n"
                         "layout(location = 0) out vec4 color;\n"
                         "void main() { color = vec4(1.0, 0.5, 0.0, 1.0); }\n");
    CHECK(gls_link_program(p) == GLS_OK, "%s", gls_last_error_message());
    int ok = 0;
    get_programiv(p, GL_LINK_STATUS, &ok);
    CHECK(ok, "linked");
    CHECK(gls_draw_buffer(GL_BACK) == GLS_OK, "GL_BACK");
    clear_color(0, 0, 0, 1);
    clear(GL_COLOR_BUFFER_BIT);
    use_program(p);
    draw_arrays(GL_TRIANGLES, 0, 3);
    unsigned char l[4], r[4];
    centre(s, GL_BACK_LEFT, l);
    centre(s, GL_BACK_RIGHT, r);
    CHECK(l[0] == 255 && l[1] == 128 && l[2] == 0, "left eye %d,%d,%d", l[0], l[1], l[2]);
    CHECK(r[0] == 255 && r[1] == 128 && r[2] == 0, "right eye %d,%d,%d", r[0], r[1], r[2]);
    /* One eye selected: only that one. */
    gls_draw_buffer(GL_BACK);
    clear(GL_COLOR_BUFFER_BIT);
    gls_draw_buffer(GL_BACK_RIGHT);
    draw_arrays(GL_TRIANGLES, 0, 3);
    centre(s, GL_BACK_LEFT, l);
    centre(s, GL_BACK_RIGHT, r);
    CHECK(l[0] == 0 && r[0] == 255, "GL_BACK_RIGHT alone: left %d right %d", l[0], r[0]);
    use_program(0);

    /* Misuse and programs the copies cannot be added to. */
    CHECK(gls_link_program(123456) == GLS_ERROR_INVALID_VALUE, "not a program");
    CHECK(gls_get_error() == GL_INVALID_VALUE, "its GL error");
    unsigned busy = program("#version 330 core\n"
                            "layout(location = 0) out vec4 a;\n"
                            "layout(location = 6) out vec4 b;\n"
                            "void main() { a = vec4(1.0); b = vec4(0.0); }\n");
    CHECK(gls_link_program(busy) == GLS_ERROR_INVALID_OPERATION, "location 6 in use");
    CHECK(strstr(gls_last_error_message(), "location 6") != NULL, "%s", gls_last_error_message());
    get_programiv(busy, GL_LINK_STATUS, &ok);
    CHECK(ok, "still linked as glLinkProgram links it");
    unsigned builtin = program("#version 130\nvoid main() { gl_FragColor = vec4(1.0); }\n");
    CHECK(gls_link_program(builtin) == GLS_OK, "gl_FragColor needs no copies");

    gls_make_current(NULL);
    gls_surface_destroy(s);
    gls_config_free(c);
    gls_display_close(d);
    return SUMMARY();
}

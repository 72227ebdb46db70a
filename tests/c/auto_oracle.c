/*
 * The oracle of automatic stereo (glstereo-run --auto, issue 23): one scene,
 * drawn by a mono program, and by the same program drawing one eye with
 * 3D Vision's rule applied by hand (REFERENCE.md): every perspective
 * projection P gets row 0 + k * row 3 - k * C * (0, 0, 0, 1), k = e * s
 * (e = -1 left, +1 right; s = 0.07 * S / 100), C the convergence;
 * orthographic projections (w = 1) are left as they are.
 *
 *   auto_oracle legacy|core mono [wait]       draws a frame and swaps (run
 *                                             under glstereo-run --auto
 *                                             --capture: the eyes are the
 *                                             captures); prints "read R G B"
 *                                             of glReadPixels at (50, 75);
 *                                             with wait, then "ready 0xWIN"
 *                                             and waits for a line on stdin
 *   auto_oracle legacy|core mono blit [frames N]  as mono, each frame drawn
 *                                             into a framebuffer object and
 *                                             blitted into the window
 *   auto_oracle legacy|core mono frames N     as mono, drawing and swapping
 *                                             the frame N times
 *   auto_oracle legacy|core tuned S C [wait]  as mono, the program setting
 *                                             separation S and convergence C
 *                                             itself (NV_3dvision_settings,
 *                                             seed 004) and printing "nv S C
 *                                             ENABLED BAD_VALUE BAD_ENUM": what
 *                                             glGetFloatv and glIsEnabled
 *                                             answer and the errors of a
 *                                             separation of 101 and a bad pname
 *   auto_oracle legacy|core off [wait]        as mono, with
 *                                             glDisable(GL_3DVISION_STEREO_NV)
 *                                             first; prints "nv-off ENABLED"
 *   auto_oracle legacy|core left|right S C OUT  draws that eye by hand and
 *                                             writes its pixels to OUT
 *                                             (RGBA, rows top first)
 *
 * legacy: a compatibility context, fixed function, every way of drawing:
 * immediate mode, client arrays (glDrawArrays, glDrawElements), a display
 * list, glRectf, a lit quad, glBitmap at a perspective raster position,
 * texturing on unit 1 through its texture matrix (enabled by a display list,
 * toggled by glPushAttrib / glPopAttrib), fog, a clip plane, the secondary
 * colour, and an orthographic HUD (glRecti, glBitmap, glDrawPixels). core: a GL 3.3 core
 * context, one program, a vertex buffer drawn with glDrawArrays,
 * glDrawElements, glDrawArraysInstanced and glMultiDrawArrays, and a HUD.
 */
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "x_window.h"

#define W 200
#define H 150

/* NV_3dvision_settings (seed 004), an OpenGL ES extension: not in glext.h. */
#define GL_3DVISION_STEREO_NV 0x90F4
#define GL_STEREO_SEPARATION_NV 0x90F5
#define GL_STEREO_CONVERGENCE_NV 0x90F6
typedef void (*stereo_parameter_fn)(GLenum, GLfloat);

/* Applies the rule to the current projection matrix (GL_PROJECTION mode). */
static void eye_projection(double k, double c)
{
    double m[16];
    glGetDoublev(GL_PROJECTION_MATRIX, m);
    /* Column-major: row 0 is m[0], m[4], m[8], m[12]; row 3 m[3], m[7], m[11], m[15]. */
    m[0] += k * m[3];
    m[4] += k * m[7];
    m[8] += k * m[11];
    m[12] += k * m[15] - k * c;
    glLoadMatrixd(m);
}

static void legacy_scene(double k, double c)
{
    static const GLubyte pattern[8] = {0xFF, 0x81, 0xBD, 0xA5, 0xA5, 0xBD, 0x81, 0xFF};
    static GLubyte pixels[8 * 8 * 4];
    static const GLfloat tri[] = {-0.5f, -0.5f, -8.0f, 1.5f, -0.5f, -8.0f, 0.5f, 1.0f, -8.0f};
    static const GLfloat quad[] = {0.2f, -1.8f, -6.0f, 1.2f, -1.8f, -6.0f, 1.2f, -1.0f, -6.0f,
                                   0.2f, -1.0f, -6.0f};
    static const GLushort idx[] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 8 * 8; i++) {
        pixels[4 * i] = 0;
        pixels[4 * i + 1] = 200;
        pixels[4 * i + 2] = 255;
        pixels[4 * i + 3] = 255;
    }
    glViewport(0, 0, W, H);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-1.0, 1.0, -0.75, 0.75, 1.0, 50.0);
    if (k != 0.0) eye_projection(k, c);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();

    /* Immediate mode, near (w = 2). */
    glColor3f(1.0f, 0.0f, 0.0f);
    glBegin(GL_QUADS);
    glVertex3f(-1.6f, -0.2f, -2.0f);
    glVertex3f(-0.9f, -0.2f, -2.0f);
    glVertex3f(-0.9f, 0.6f, -2.0f);
    glVertex3f(-1.6f, 0.6f, -2.0f);
    glEnd();

    /* Client arrays, far (w = 8, 6). */
    glEnableClientState(GL_VERTEX_ARRAY);
    glColor3f(0.0f, 1.0f, 0.0f);
    glVertexPointer(3, GL_FLOAT, 0, tri);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glColor3f(0.0f, 0.0f, 1.0f);
    glVertexPointer(3, GL_FLOAT, 0, quad);
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, idx);
    glDisableClientState(GL_VERTEX_ARRAY);

    /* A display list, at the convergence (w = 4). */
    GLuint list = glGenLists(1);
    glNewList(list, GL_COMPILE);
    glColor3f(1.0f, 1.0f, 0.0f);
    glBegin(GL_TRIANGLES);
    glVertex3f(-2.5f, -2.5f, -4.0f);
    glVertex3f(-1.0f, -2.5f, -4.0f);
    glVertex3f(-1.75f, -1.2f, -4.0f);
    glEnd();
    /* It moves the model-view for what follows: once per call (the eyes'
     * calls of a list of geometry only must not move it twice). */
    glTranslatef(0.1f, 0.0f, 0.0f);
    glEndList();
    glCallList(list);
    glDeleteLists(list, 1);

    /* glRectf through the modelview (w = 3). */
    glPushMatrix();
    glTranslatef(0.0f, 0.0f, -3.0f);
    glColor3f(1.0f, 0.0f, 1.0f);
    glRectf(0.3f, 0.5f, 0.9f, 1.0f);
    glPopMatrix();

    /* A lit quad (w = 5): fixed-function lighting. */
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glNormal3f(0.0f, 0.0f, 1.0f);
    glBegin(GL_QUADS);
    glVertex3f(-3.0f, 1.5f, -5.0f);
    glVertex3f(-1.5f, 1.5f, -5.0f);
    glVertex3f(-1.5f, 3.0f, -5.0f);
    glVertex3f(-3.0f, 3.0f, -5.0f);
    glEnd();
    glDisable(GL_LIGHTING);

    /* A lit strip (w = 5) whose normals turn across it (given twice too
     * long: GL_NORMALIZE), under two lights: light 0 as it is by default,
     * and light 1 positional, a spot with attenuation; specular colour
     * separate, a local viewer, and GL_COLOR_MATERIAL for the diffuse
     * colour; then light 1 changed by glLight alone (directional, no
     * spot) for a second strip. Everything put back after. */
    {
        static const GLfloat pos1[] = {-2.0f, 0.0f, -3.0f, 1.0f};
        static const GLfloat dir1[] = {-1.0f, -0.5f, -1.0f};
        static const GLfloat dif1[] = {0.2f, 0.6f, 0.9f, 1.0f};
        static const GLfloat spec1[] = {0.5f, 0.5f, 0.4f, 1.0f};
        static const GLfloat mspec[] = {0.5f, 0.4f, 0.3f, 1.0f};
        static const GLfloat spec_default[] = {0.0f, 0.0f, 0.0f, 1.0f};
        glPushMatrix();
        glLoadIdentity();
        glLightfv(GL_LIGHT1, GL_POSITION, pos1);
        glLightfv(GL_LIGHT1, GL_SPOT_DIRECTION, dir1);
        glPopMatrix();
        glLightf(GL_LIGHT1, GL_SPOT_CUTOFF, 70.0f);
        glLightf(GL_LIGHT1, GL_SPOT_EXPONENT, 2.0f);
        glLightf(GL_LIGHT1, GL_LINEAR_ATTENUATION, 0.1f);
        glLightf(GL_LIGHT1, GL_QUADRATIC_ATTENUATION, 0.02f);
        glLightfv(GL_LIGHT1, GL_DIFFUSE, dif1);
        glLightfv(GL_LIGHT1, GL_SPECULAR, spec1);
        glMaterialfv(GL_FRONT, GL_SPECULAR, mspec);
        glMaterialf(GL_FRONT, GL_SHININESS, 12.0f);
        glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_TRUE);
        glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SEPARATE_SPECULAR_COLOR);
        glColorMaterial(GL_FRONT, GL_DIFFUSE);
        glEnable(GL_COLOR_MATERIAL);
        glEnable(GL_NORMALIZE);
        glEnable(GL_LIGHTING);
        glEnable(GL_LIGHT0);
        glEnable(GL_LIGHT1);
        glColor3f(0.3f, 0.5f, 0.7f);
        glBegin(GL_QUAD_STRIP);
        for (int i = 0; i <= 8; i++) {
            float a = -1.0f + 0.25f * (float)i;
            float x = -4.6f + 0.15f * (float)i;
            glNormal3f(2.0f * sinf(a), 0.0f, 2.0f * cosf(a));
            glVertex3f(x, -3.0f, -5.0f);
            glVertex3f(x, 1.0f, -5.0f);
        }
        glEnd();
        /* Light 1 made directional and no spot by glLight alone (no
         * enable changes): a second strip above the first. */
        static const GLfloat dir_pos1[] = {-1.0f, 0.5f, 1.0f, 0.0f};
        glPushMatrix();
        glLoadIdentity();
        glLightfv(GL_LIGHT1, GL_POSITION, dir_pos1);
        glPopMatrix();
        glLightf(GL_LIGHT1, GL_SPOT_CUTOFF, 180.0f);
        glBegin(GL_QUAD_STRIP);
        for (int i = 0; i <= 8; i++) {
            float a = -1.0f + 0.25f * (float)i;
            float x = -4.6f + 0.15f * (float)i;
            glNormal3f(2.0f * sinf(a), 0.0f, 2.0f * cosf(a));
            glVertex3f(x, 1.2f, -5.0f);
            glVertex3f(x, 2.8f, -5.0f);
        }
        glEnd();
        glDisable(GL_LIGHT1);
        glDisable(GL_LIGHTING);
        glDisable(GL_NORMALIZE);
        glDisable(GL_COLOR_MATERIAL);
        glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
        glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SINGLE_COLOR);
        glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_FALSE);
        glMaterialfv(GL_FRONT, GL_SPECULAR, spec_default);
        glMaterialf(GL_FRONT, GL_SHININESS, 0.0f);
    }

    /* A bitmap at a perspective raster position (w = 10). */
    glColor3f(1.0f, 0.5f, 0.0f);
    glRasterPos3f(3.0f, 3.0f, -10.0f);
    glBitmap(8, 8, 0.0f, 0.0f, 12.0f, 0.0f, pattern);
    glBitmap(8, 8, 0.0f, 0.0f, 12.0f, 0.0f, pattern);

    /* Fixed-function state the layer's stand-in vertex shader must carry
     * to the fragments: fog from the eye distance, a user clip plane, the
     * secondary colour (GL_COLOR_SUM), then a texture on unit 1 only
     * through its texture matrix (enabled by a display list, disabled and
     * enabled again by glPushAttrib / glPopAttrib). */
    GLfloat fog_colour[] = {0.5f, 0.5f, 0.5f, 1.0f};
    glEnable(GL_FOG);
    glFogi(GL_FOG_MODE, GL_LINEAR);
    glFogf(GL_FOG_START, 1.0f);
    glFogf(GL_FOG_END, 20.0f);
    glFogfv(GL_FOG_COLOR, fog_colour);
    glColor3f(0.0f, 0.2f, 0.9f);
    glPushMatrix();
    glTranslatef(0.0f, 0.0f, -7.0f);
    glRectf(5.04f, -1.575f, 6.44f, -0.2625f);
    glPopMatrix();
    glDisable(GL_FOG);

    GLdouble plane[] = {-1.0, 0.0, 0.0, 2.75};
    glClipPlane(GL_CLIP_PLANE0, plane);
    glEnable(GL_CLIP_PLANE0);
    glColor3f(0.5f, 0.5f, 0.0f);
    glBegin(GL_TRIANGLE_FAN);
    glVertex3f(2.25f, -2.4375f, -5.0f);
    glVertex3f(3.25f, -2.4375f, -5.0f);
    glVertex3f(3.25f, -1.5f, -5.0f);
    glVertex3f(2.25f, -1.5f, -5.0f);
    glEnd();
    glDisable(GL_CLIP_PLANE0);

    glEnable(GL_COLOR_SUM);
    glColor3f(0.6f, 0.0f, 0.0f);
    glSecondaryColor3f(0.0f, 0.3f, 0.5f);
    glBegin(GL_QUADS);
    glVertex3f(3.6f, -2.4375f, -5.0f);
    glVertex3f(4.6f, -2.4375f, -5.0f);
    glVertex3f(4.6f, -1.5f, -5.0f);
    glVertex3f(3.6f, -1.5f, -5.0f);
    glEnd();
    glDisable(GL_COLOR_SUM);

    /* After those fixed-function draws without a texture: */
    static GLuint texture;
    static const GLubyte checker[] = {128, 0, 255, 255, 0, 128, 128, 255, 0, 128, 128, 255, 128, 0, 255, 255};
    if (texture == 0) {
        glGenTextures(1, &texture);
        glBindTexture(GL_TEXTURE_2D, texture);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, checker);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, texture);
    glMatrixMode(GL_TEXTURE);
    glLoadIdentity();
    glScalef(2.0f, 2.0f, 1.0f);
    glMatrixMode(GL_MODELVIEW);
    /* An untextured quad, then the texture enabled by a display list and
     * a textured one; then under glPushAttrib the texture disabled and the
     * untextured quad again, and after glPopAttrib a textured one. */
    GLuint enable_list = glGenLists(1);
    glNewList(enable_list, GL_COMPILE);
    glEnable(GL_TEXTURE_2D);
    glEndList();
    for (int pass = 0; pass < 4; pass++) {
        int textured = pass == 1 || pass == 3;
        float x0 = textured ? 2.7f : 4.32f, y0 = pass == 3 ? -1.35f : 0.225f;
        if (pass == 1) glCallList(enable_list);
        if (pass == 2) {
            glPushAttrib(GL_ENABLE_BIT);
            glDisable(GL_TEXTURE_2D);
        }
        if (pass == 3) glPopAttrib();
        if (textured)
            glColor3f(1.0f, 1.0f, 1.0f);
        else
            glColor3f(0.8f, 0.4f, 0.2f);
        glBegin(GL_QUADS);
        glMultiTexCoord2f(GL_TEXTURE1, 0.0f, 0.0f);
        glVertex3f(x0, y0, -6.0f);
        glMultiTexCoord2f(GL_TEXTURE1, 1.0f, 0.0f);
        glVertex3f(x0 + 1.2f, y0, -6.0f);
        glMultiTexCoord2f(GL_TEXTURE1, 1.0f, 1.0f);
        glVertex3f(x0 + 1.2f, y0 + 1.125f, -6.0f);
        glMultiTexCoord2f(GL_TEXTURE1, 0.0f, 1.0f);
        glVertex3f(x0, y0 + 1.125f, -6.0f);
        glEnd();
    }
    glDeleteLists(enable_list, 1);
    glDisable(GL_TEXTURE_2D);
    glMatrixMode(GL_TEXTURE);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glActiveTexture(GL_TEXTURE0);

    /* The HUD: orthographic, w = 1, at the screen in both eyes. */
    glDisable(GL_DEPTH_TEST);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0.0, W, 0.0, H, -1.0, 1.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glColor3f(1.0f, 1.0f, 1.0f);
    glRecti(5, 5, 45, 15);
    glRasterPos2i(150, 130);
    glBitmap(8, 8, 0.0f, 0.0f, 10.0f, 0.0f, pattern);
    glRasterPos2i(170, 130);
    glDrawPixels(8, 8, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
}

static GLuint shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "shader: %s\n", log);
        exit(4);
    }
    return s;
}

static void core_scene(double k, double c)
{
    static const char *vs =
        "#version 330 core\n"
        "layout(location = 0) in vec3 p;\n"
        "uniform mat4 m;\n"
        "void main() {\n"
        "    gl_Position = m * vec4(p + vec3(float(gl_InstanceID) * 0.7, 0.0, 0.0), 1.0);\n"
        "}\n";
    static const char *fs =
        "#version 330 core\n"
        "uniform vec4 colour;\n"
        "out vec4 c;\n"
        "void main() { c = colour; }\n";
    /* Quads (two triangles each) at z = -2, -4, -8, -6 and a HUD quad. */
    static const GLfloat v[] = {
        -1.6f, -0.2f, -2.0f, -0.9f, -0.2f, -2.0f, -0.9f, 0.6f, -2.0f,
        -1.6f, -0.2f, -2.0f, -0.9f, 0.6f,  -2.0f, -1.6f, 0.6f, -2.0f,
        -2.5f, -2.5f, -4.0f, -1.0f, -2.5f, -4.0f, -1.0f, -1.2f, -4.0f,
        -2.5f, -2.5f, -4.0f, -1.0f, -1.2f, -4.0f, -2.5f, -1.2f, -4.0f,
        -0.5f, -0.5f, -8.0f, 1.5f,  -0.5f, -8.0f, 1.5f,  1.0f,  -8.0f,
        -0.5f, -0.5f, -8.0f, 1.5f,  1.0f,  -8.0f, -0.5f, 1.0f,  -8.0f,
        0.2f,  -1.8f, -6.0f, 1.2f,  -1.8f, -6.0f, 1.2f,  -1.0f, -6.0f,
        0.2f,  -1.8f, -6.0f, 1.2f,  -1.0f, -6.0f, 0.2f,  -1.0f, -6.0f,
        5.0f,  5.0f,  0.0f,  45.0f, 5.0f,  0.0f,  45.0f, 15.0f, 0.0f,
        5.0f,  5.0f,  0.0f,  45.0f, 15.0f, 0.0f,  5.0f,  15.0f, 0.0f,
    };
    static const GLuint idx[] = {6, 7, 8, 9, 10, 11};
    GLuint prog = glCreateProgram();
    glAttachShader(prog, shader(GL_VERTEX_SHADER, vs));
    glAttachShader(prog, shader(GL_FRAGMENT_SHADER, fs));
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        fprintf(stderr, "link failed\n");
        exit(4);
    }
    GLuint vao, vbo, ibo;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof v, v, GL_STATIC_DRAW);
    glGenBuffers(1, &ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof idx, idx, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glEnableVertexAttribArray(0);

    glViewport(0, 0, W, H);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(prog);
    GLint lm = glGetUniformLocation(prog, "m"), lc = glGetUniformLocation(prog, "colour");
    /* glFrustum(-1, 1, -0.75, 0.75, 1, 50), column-major, with the rule. */
    double n = 1.0, f = 50.0;
    double p[16] = {0};
    p[0] = 2.0 * n / 2.0;
    p[5] = 2.0 * n / 1.5;
    p[10] = -(f + n) / (f - n);
    p[11] = -1.0;
    p[14] = -2.0 * f * n / (f - n);
    p[0] += k * p[3];
    p[4] += k * p[7];
    p[8] += k * p[11];
    p[12] += k * p[15] - k * c;
    float pf[16];
    for (int i = 0; i < 16; i++) pf[i] = (float)p[i];
    glUniformMatrix4fv(lm, 1, GL_FALSE, pf);
    glUniform4f(lc, 1.0f, 0.0f, 0.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glUniform4f(lc, 1.0f, 1.0f, 0.0f, 1.0f);
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_INT, (const void *)0);
    glUniform4f(lc, 0.0f, 1.0f, 0.0f, 1.0f);
    glDrawArraysInstanced(GL_TRIANGLES, 12, 6, 2);
    GLint first[] = {18};
    GLsizei count[] = {6};
    glUniform4f(lc, 0.0f, 0.0f, 1.0f, 1.0f);
    glMultiDrawArrays(GL_TRIANGLES, first, count, 1);
    /* The HUD: glOrtho(0, W, 0, H, -1, 1), w = 1. */
    float o[16] = {2.0f / W, 0, 0, 0, 0, 2.0f / H, 0, 0, 0, 0, -1.0f, 0, -1.0f, -1.0f, 0, 1.0f};
    glDisable(GL_DEPTH_TEST);
    glUniformMatrix4fv(lm, 1, GL_FALSE, o);
    glUniform4f(lc, 1.0f, 1.0f, 1.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 24, 6);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: auto_oracle legacy|core mono|left|right [S C OUT]\n");
        return 2;
    }
    int core = strcmp(argv[1], "core") == 0;
    int tuned = strcmp(argv[2], "tuned") == 0;
    int off = strcmp(argv[2], "off") == 0;
    int mono = strcmp(argv[2], "mono") == 0 || tuned || off;
    double k = 0.0, c = 0.0;
    const char *out = NULL;
    if (tuned && argc < 5) return 2;
    if (!mono) {
        if (argc < 6) return 2;
        double s = 0.07 * atof(argv[3]) / 100.0;
        k = strcmp(argv[2], "left") == 0 ? -s : s;
        c = atof(argv[4]);
        out = argv[5];
    }
    static const int core33[] = {GLX_CONTEXT_MAJOR_VERSION_ARB, 3, GLX_CONTEXT_MINOR_VERSION_ARB, 3,
                                 GLX_CONTEXT_PROFILE_MASK_ARB, GLX_CONTEXT_CORE_PROFILE_BIT_ARB,
                                 None};
    struct x_window x = open_x_window_config(core ? core33 : NULL, W, H);
    Display *dpy = x.display;
    Window win = x.window;
    XStoreName(dpy, win, "auto_oracle");
    if (tuned) {
        stereo_parameter_fn set = (stereo_parameter_fn)glXGetProcAddressARB(
            (const GLubyte *)"glStereoParameterfNV");
        set(GL_STEREO_SEPARATION_NV, 101.0f);
        GLenum bad_value = glGetError();
        set(0x7777, 1.0f);
        GLenum bad_enum = glGetError();
        set(GL_STEREO_SEPARATION_NV, (GLfloat)atof(argv[3]));
        set(GL_STEREO_CONVERGENCE_NV, (GLfloat)atof(argv[4]));
        GLfloat got_s = -1.0f, got_c = -1.0f;
        glGetFloatv(GL_STEREO_SEPARATION_NV, &got_s);
        glGetFloatv(GL_STEREO_CONVERGENCE_NV, &got_c);
        printf("nv %g %g %d 0x%x 0x%x\n", got_s, got_c, glIsEnabled(GL_3DVISION_STEREO_NV),
               bad_value, bad_enum);
    }
    if (off) {
        glDisable(GL_3DVISION_STEREO_NV);
        printf("nv-off %d\n", glIsEnabled(GL_3DVISION_STEREO_NV));
    }
    /* mono blit: each frame drawn into a framebuffer object of the window's
     * size, then blitted into the window (as VTK shows its scene). */
    int blit = mono && argc > 3 && strcmp(argv[3], "blit") == 0;
    GLuint fbo = 0, tex = 0, depth = 0;
    if (blit) {
        glGenTextures(1, &tex);
        glBindTexture(GL_TEXTURE_2D, tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindTexture(GL_TEXTURE_2D, 0);
        glGenRenderbuffers(1, &depth);
        glBindRenderbuffer(GL_RENDERBUFFER, depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, W, H);
        glGenFramebuffers(1, &fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                  depth);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return 5;
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    /* mono [blit] frames N: N - 1 frames drawn and swapped before the last. */
    int at = blit ? 4 : 3;
    int frames = mono && argc > at + 1 && strcmp(argv[at], "frames") == 0 ? atoi(argv[at + 1]) : 1;
    for (int i = 0; i < frames; i++) {
        if (blit) glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        if (core)
            core_scene(k, c);
        else
            legacy_scene(k, c);
        if (blit) {
            glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
            glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        if (i + 1 < frames) glXSwapBuffers(dpy, win);
    }
    if (mono) {
        GLubyte px[4] = {0};
        glReadPixels(50, 75, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
        printf("read %d %d %d\n", px[0], px[1], px[2]);
        glXSwapBuffers(dpy, win);
        if (argc > 3 && strcmp(argv[3], "wait") == 0) {
            glFinish();
            printf("ready 0x%lx\n", (unsigned long)win);
            fflush(stdout);
            char line[16];
            if (!fgets(line, sizeof line, stdin)) return 1;
        }
    } else {
        static GLubyte img[W * H * 4];
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, img);
        FILE *f = fopen(out, "wb");
        if (!f) return 1;
        for (int y = H - 1; y >= 0; y--) fwrite(img + (size_t)y * W * 4, 1, W * 4, f);
        fclose(f);
    }
    GLenum err = glGetError();
    printf("error 0x%x\n", err);
    close_x_window(&x);
    return err == GL_NO_ERROR ? 0 : 3;
}

/* Misuse of the stereo layer's GLX and GL entry points, the gls_glx_* and
 * gls_gl_* functions of glstereo.h (tests/misuse.rs), on a real X server.
 *
 * The rule the layer follows (src/ffi/interpose.rs): a call libGL answers
 * without crashing goes to libGL, and the program sees what libGL says
 * (its return value, its X error, its GL error); a call libGL would crash
 * on is refused by the layer before libGL sees it:
 *
 * - GLX: a NULL Display* (every function; a release, glXMakeCurrent(dpy,
 *   None, NULL), is allowed with NULL as libglvnd allows it), a NULL where
 *   GLX needs a pointer (glXChooseVisual's attribute list, glXCreateContext's
 *   visual, nelements, the value of glXGetConfig/glXGetFBConfigAttrib,
 *   glXGetProcAddress's name), a share context the program destroyed. The
 *   call returns what the function returns on failure (NULL, None, False,
 *   GLX_BAD_VALUE) and changes nothing.
 * - GL: a NULL pointer GL would read or write through (glGet*v and
 *   glGet*i_v data, glDrawBuffers / glDeleteFramebuffers with n > 0,
 *   glGetFramebufferAttachmentParameteriv params): nothing happens but
 *   GL_INVALID_VALUE for glGetError (none without a current context).
 *
 * A refused call leaves a message of its own for gls_last_error_message()
 * ("gls_glx_choose_visual: …") and, once, on stderr ("glstereo:
 * glXChooseVisual refused: …"); a call that goes to libGL leaves no message.
 * Every case here checks the result, the message (or its absence), the X
 * and GL errors, and that the layer still works afterwards.
 *
 * Built twice:
 * - against glstereo.h, calling the gls_ functions (link -lglstereo -lGL
 *   -lX11): prints "covers <name>" for each function exercised, the
 *   coverage test's list;
 * - with -DMISUSE_PRELOAD and no glstereo at all (link -lGL -lX11): the
 *   same cases through the real GLX/GL names, run under glstereo-run, so
 *   libglstereo_preload.so's exports answer. Messages are then checked on
 *   stderr by the Rust test.
 *
 * Needs $DISPLAY (an Xvfb with GLX). Prints "N passed, N failed". */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include "check.h"

/* Tokens newer than GL/gl.h (1.3) and GL/glx.h (1.4). */
#define GL_FRAMEBUFFER_ 0x8D40u
#define GL_READ_FRAMEBUFFER_ 0x8CA8u
#define GL_FRAMEBUFFER_COMPLETE_ 0x8CD5u
#define GL_DRAW_FRAMEBUFFER_BINDING_ 0x8CA6u
#define GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_ 0x8CD0u
#define GL_COLOR_ 0x1800u
#define GL_FRAGMENT_SHADER_ 0x8B30u
#define GLX_CONTEXT_MAJOR_VERSION_ARB_ 0x2091
#define GLX_CONTEXT_MINOR_VERSION_ARB_ 0x2092
#define GLX_CONTEXT_PROFILE_MASK_ARB_ 0x9126
#define GLX_CONTEXT_CORE_PROFILE_BIT_ARB_ 0x1
/* GLX protocol errors, from the extension's error base. */
#define GLX_BAD_CONTEXT_ 0
#define GLX_BAD_FBCONFIG_ 9
#define GL_LINK_STATUS_ 0x8B82
#define GL_PROGRAM_BINARY_FORMAT_MESA_ 0x875F
#define GLX_BAD_PIXMAP_ 3
#define GLX_BAD_PBUFFER_ 10

#ifdef MISUSE_PRELOAD
/* ---- the gls_ names onto the real GLX/GL names (glstereo-run) --------- */

typedef void *(*choose_fbconfig_sgix_fn)(Display *, int, const int *, int *);
typedef int (*get_fbconfig_attrib_sgix_fn)(Display *, void *, int, int *);
typedef XVisualInfo *(*get_visual_sgix_fn)(Display *, void *);
typedef GLXContext (*create_context_sgix_fn)(Display *, void *, int, GLXContext, Bool);
typedef GLXContext (*create_context_attribs_fn)(Display *, GLXFBConfig, GLXContext, Bool, const int *);
typedef GLXPixmap (*create_pixmap_sgix_fn)(Display *, void *, Pixmap);
typedef GLXPbuffer (*create_pbuffer_sgix_fn)(Display *, void *, unsigned, unsigned, int *);
typedef void (*destroy_pbuffer_sgix_fn)(Display *, GLXPbuffer);
typedef void (*draw_buffers_fn)(GLsizei, const GLenum *);
typedef void (*bind_framebuffer_fn)(GLenum, GLuint);
typedef void (*delete_framebuffers_fn)(GLsizei, const GLuint *);
typedef void (*attachment_fn)(GLenum, GLenum, GLenum, GLint *);
typedef void (*clear_fv_fn)(GLenum, GLint, const GLfloat *);
typedef void (*clear_iv_fn)(GLenum, GLint, const GLint *);
typedef void (*clear_uiv_fn)(GLenum, GLint, const GLuint *);
typedef void (*clear_named_fv_fn)(GLuint, GLenum, GLint, const GLfloat *);
typedef void (*clear_named_iv_fn)(GLuint, GLenum, GLint, const GLint *);
typedef void (*clear_named_uiv_fn)(GLuint, GLenum, GLint, const GLuint *);
typedef void (*clear_named_fi_fn)(GLuint, GLenum, GLint, GLfloat, GLint);
typedef void (*named_buffer_fn)(GLuint, GLenum);
typedef void (*named_buffers_fn)(GLuint, GLsizei, const GLenum *);
typedef void (*blit_named_fn)(GLuint, GLuint, GLint, GLint, GLint, GLint, GLint, GLint, GLint,
                              GLint, GLbitfield, GLenum);
typedef void (*color_maski_fn)(GLuint, GLboolean, GLboolean, GLboolean, GLboolean);
typedef void (*get_booleani_fn)(GLenum, GLuint, GLboolean *);
typedef void (*get_integeri_fn)(GLenum, GLuint, GLint *);
typedef void (*get_integer64i_fn)(GLenum, GLuint, int64_t *);
typedef void (*get_integer64_fn)(GLenum, int64_t *);
typedef void (*get_floati_fn)(GLenum, GLuint, GLfloat *);
typedef void (*get_doublei_fn)(GLenum, GLuint, GLdouble *);
typedef void (*clear_color_i_fn)(GLint, GLint, GLint, GLint);
typedef void (*clear_color_ui_fn)(GLuint, GLuint, GLuint, GLuint);
typedef void (*blit_fn)(GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLbitfield,
                        GLenum);
typedef void (*invalidate_fn)(GLenum, GLsizei, const GLenum *);
typedef void (*invalidate_sub_fn)(GLenum, GLsizei, const GLenum *, GLint, GLint, GLsizei,
                                  GLsizei);
typedef void (*named_attachment_fn)(GLuint, GLenum, GLenum, GLint *);
typedef void (*parameter_fn)(GLuint, GLenum, GLint *);
typedef void (*link_program_fn)(GLuint);
typedef GLuint (*create_shader_programv_fn)(GLenum, GLsizei, const char *const *);
typedef void (*get_programiv_fn)(GLuint, GLenum, GLint *);
typedef void (*get_program_binary_fn)(GLuint, GLsizei, GLsizei *, GLenum *, void *);
typedef void (*program_binary_fn)(GLuint, GLenum, const void *, GLsizei);

static choose_fbconfig_sgix_fn p_choose_fbconfig_sgix;
static get_fbconfig_attrib_sgix_fn p_get_fbconfig_attrib_sgix;
static get_visual_sgix_fn p_get_visual_sgix;
static create_context_sgix_fn p_create_context_sgix;
static create_context_attribs_fn p_create_context_attribs;
static create_pixmap_sgix_fn p_create_pixmap_sgix;
static create_pbuffer_sgix_fn p_create_pbuffer_sgix;
static destroy_pbuffer_sgix_fn p_destroy_pbuffer_sgix;
static draw_buffers_fn p_draw_buffers, p_draw_buffers_arb;
static bind_framebuffer_fn p_bind_framebuffer, p_bind_framebuffer_ext;
static delete_framebuffers_fn p_delete_framebuffers, p_delete_framebuffers_ext;
static delete_framebuffers_fn p_delete_textures, p_delete_textures_ext;
static delete_framebuffers_fn p_delete_renderbuffers, p_delete_renderbuffers_ext;
static attachment_fn p_attachment, p_attachment_ext;
static clear_fv_fn p_clear_fv;
static clear_iv_fn p_clear_iv;
static clear_uiv_fn p_clear_uiv;
static clear_named_fv_fn p_clear_named_fv;
static clear_named_iv_fn p_clear_named_iv;
static clear_named_uiv_fn p_clear_named_uiv;
static clear_named_fi_fn p_clear_named_fi;
static named_buffer_fn p_named_draw_buffer, p_named_read_buffer;
static named_buffers_fn p_named_draw_buffers;
static blit_named_fn p_blit_named;
static color_maski_fn p_color_maski;
static get_booleani_fn p_get_booleani;
static color_maski_fn p_color_mask_indexed_ext, p_color_maski_ext, p_color_maski_oes;
static get_booleani_fn p_get_boolean_indexed_ext;
static get_integeri_fn p_get_integeri, p_get_integer_indexed_ext;
static get_integer64i_fn p_get_integer64i;
static get_integer64_fn p_get_integer64;
static get_floati_fn p_get_floati, p_get_floati_ext, p_get_floati_oes, p_get_float_indexed_ext;
static get_doublei_fn p_get_doublei, p_get_doublei_ext, p_get_double_indexed_ext;
static clear_color_i_fn p_clear_color_ii, p_clear_colorx, p_clear_colorx_oes;
static clear_color_ui_fn p_clear_color_iui;
static blit_fn p_blit;
static invalidate_fn p_invalidate;
static invalidate_sub_fn p_invalidate_sub;
typedef void (*invalidate_named_fn)(GLuint, GLsizei, const GLenum *);
typedef void (*invalidate_named_sub_fn)(GLuint, GLsizei, const GLenum *, GLint, GLint, GLsizei,
                                        GLsizei);
typedef GLenum (*check_named_fn)(GLuint, GLenum);
static invalidate_named_fn p_invalidate_named;
static invalidate_named_sub_fn p_invalidate_named_sub;
static check_named_fn p_check_named, p_check_named_ext;
static named_attachment_fn p_named_attachment;
static parameter_fn p_named_parameter, p_parameter;
static link_program_fn p_link_program;
static create_shader_programv_fn p_create_shader_programv;
static get_programiv_fn p_get_programiv;
static get_program_binary_fn p_get_program_binary, p_get_program_binary_oes;
static program_binary_fn p_program_binary, p_program_binary_oes;

/* Extension functions, looked up as programs do (the layer's for its names). */
#define LOOKUP(var, name)                                                    \
    do {                                                                     \
        void (*f_)(void) = glXGetProcAddressARB((const GLubyte *)(name));    \
        memcpy(&(var), &f_, sizeof(var));                                    \
        CHECK((var) != NULL, "glXGetProcAddressARB(%s)", (name));            \
    } while (0)

static void load_procs(void) {
    LOOKUP(p_choose_fbconfig_sgix, "glXChooseFBConfigSGIX");
    LOOKUP(p_get_fbconfig_attrib_sgix, "glXGetFBConfigAttribSGIX");
    LOOKUP(p_get_visual_sgix, "glXGetVisualFromFBConfigSGIX");
    LOOKUP(p_create_context_sgix, "glXCreateContextWithConfigSGIX");
    LOOKUP(p_create_context_attribs, "glXCreateContextAttribsARB");
    LOOKUP(p_create_pixmap_sgix, "glXCreateGLXPixmapWithConfigSGIX");
    LOOKUP(p_create_pbuffer_sgix, "glXCreateGLXPbufferSGIX");
    LOOKUP(p_destroy_pbuffer_sgix, "glXDestroyGLXPbufferSGIX");
    LOOKUP(p_draw_buffers, "glDrawBuffers");
    LOOKUP(p_draw_buffers_arb, "glDrawBuffersARB");
    LOOKUP(p_bind_framebuffer, "glBindFramebuffer");
    LOOKUP(p_bind_framebuffer_ext, "glBindFramebufferEXT");
    LOOKUP(p_delete_framebuffers, "glDeleteFramebuffers");
    LOOKUP(p_delete_framebuffers_ext, "glDeleteFramebuffersEXT");
    LOOKUP(p_delete_textures, "glDeleteTextures");
    LOOKUP(p_delete_textures_ext, "glDeleteTexturesEXT");
    LOOKUP(p_delete_renderbuffers, "glDeleteRenderbuffers");
    LOOKUP(p_delete_renderbuffers_ext, "glDeleteRenderbuffersEXT");
    LOOKUP(p_attachment, "glGetFramebufferAttachmentParameteriv");
    LOOKUP(p_attachment_ext, "glGetFramebufferAttachmentParameterivEXT");
    LOOKUP(p_clear_fv, "glClearBufferfv");
    LOOKUP(p_clear_iv, "glClearBufferiv");
    LOOKUP(p_clear_uiv, "glClearBufferuiv");
    LOOKUP(p_clear_named_fv, "glClearNamedFramebufferfv");
    LOOKUP(p_clear_named_iv, "glClearNamedFramebufferiv");
    LOOKUP(p_clear_named_uiv, "glClearNamedFramebufferuiv");
    LOOKUP(p_clear_named_fi, "glClearNamedFramebufferfi");
    LOOKUP(p_named_draw_buffer, "glNamedFramebufferDrawBuffer");
    LOOKUP(p_named_read_buffer, "glNamedFramebufferReadBuffer");
    LOOKUP(p_named_draw_buffers, "glNamedFramebufferDrawBuffers");
    LOOKUP(p_blit_named, "glBlitNamedFramebuffer");
    LOOKUP(p_color_maski, "glColorMaski");
    LOOKUP(p_get_booleani, "glGetBooleani_v");
    LOOKUP(p_color_mask_indexed_ext, "glColorMaskIndexedEXT");
    LOOKUP(p_color_maski_ext, "glColorMaskiEXT");
    LOOKUP(p_color_maski_oes, "glColorMaskiOES");
    LOOKUP(p_get_boolean_indexed_ext, "glGetBooleanIndexedvEXT");
    LOOKUP(p_get_integeri, "glGetIntegeri_v");
    LOOKUP(p_get_integer_indexed_ext, "glGetIntegerIndexedvEXT");
    LOOKUP(p_get_integer64i, "glGetInteger64i_v");
    LOOKUP(p_get_integer64, "glGetInteger64v");
    LOOKUP(p_get_floati, "glGetFloati_v");
    LOOKUP(p_get_floati_ext, "glGetFloati_vEXT");
    LOOKUP(p_get_floati_oes, "glGetFloati_vOES");
    LOOKUP(p_get_float_indexed_ext, "glGetFloatIndexedvEXT");
    LOOKUP(p_get_doublei, "glGetDoublei_v");
    LOOKUP(p_get_doublei_ext, "glGetDoublei_vEXT");
    LOOKUP(p_get_double_indexed_ext, "glGetDoubleIndexedvEXT");
    LOOKUP(p_clear_color_ii, "glClearColorIiEXT");
    LOOKUP(p_clear_color_iui, "glClearColorIuiEXT");
    LOOKUP(p_clear_colorx, "glClearColorx");
    LOOKUP(p_clear_colorx_oes, "glClearColorxOES");
    LOOKUP(p_blit, "glBlitFramebuffer");
    LOOKUP(p_invalidate, "glInvalidateFramebuffer");
    LOOKUP(p_invalidate_sub, "glInvalidateSubFramebuffer");
    LOOKUP(p_invalidate_named, "glInvalidateNamedFramebufferData");
    LOOKUP(p_invalidate_named_sub, "glInvalidateNamedFramebufferSubData");
    LOOKUP(p_check_named, "glCheckNamedFramebufferStatus");
    LOOKUP(p_check_named_ext, "glCheckNamedFramebufferStatusEXT");
    LOOKUP(p_named_attachment, "glGetNamedFramebufferAttachmentParameteriv");
    LOOKUP(p_named_parameter, "glGetNamedFramebufferParameteriv");
    LOOKUP(p_parameter, "glGetFramebufferParameteriv");
    LOOKUP(p_link_program, "glLinkProgram");
    LOOKUP(p_create_shader_programv, "glCreateShaderProgramv");
    LOOKUP(p_get_programiv, "glGetProgramiv");
    LOOKUP(p_get_program_binary, "glGetProgramBinary");
    LOOKUP(p_get_program_binary_oes, "glGetProgramBinaryOES");
    LOOKUP(p_program_binary, "glProgramBinary");
    LOOKUP(p_program_binary_oes, "glProgramBinaryOES");
}

static void *proc_pointer(void (*f)(void)) {
    void *p;
    memcpy(&p, &f, sizeof p);
    return p;
}

#define D(d) ((Display *)(d))
#define C(c) ((GLXFBConfig)(c))
#define X(c) ((GLXContext)(c))
#define gls_glx_choose_visual(d, s, a) ((void *)glXChooseVisual(D(d), (s), (a)))
#define gls_glx_get_config(d, v, a, val) glXGetConfig(D(d), (XVisualInfo *)(v), (a), (val))
#define gls_glx_choose_fbconfig(d, s, a, n) ((void **)glXChooseFBConfig(D(d), (s), (a), (n)))
#define gls_glx_choose_fbconfig_sgix(d, s, a, n) ((void **)p_choose_fbconfig_sgix(D(d), (s), (a), (n)))
#define gls_glx_get_fbconfigs(d, s, n) ((void **)glXGetFBConfigs(D(d), (s), (n)))
#define gls_glx_get_fbconfig_attrib(d, c, a, v) glXGetFBConfigAttrib(D(d), C(c), (a), (v))
#define gls_glx_get_fbconfig_attrib_sgix(d, c, a, v) p_get_fbconfig_attrib_sgix(D(d), (c), (a), (v))
#define gls_glx_get_visual_from_fbconfig(d, c) ((void *)glXGetVisualFromFBConfig(D(d), C(c)))
#define gls_glx_get_visual_from_fbconfig_sgix(d, c) ((void *)p_get_visual_sgix(D(d), (c)))
#define gls_glx_create_context(d, v, s, dir) \
    ((void *)glXCreateContext(D(d), (XVisualInfo *)(v), X(s), (dir)))
#define gls_glx_create_new_context(d, c, t, s, dir) \
    ((void *)glXCreateNewContext(D(d), C(c), (t), X(s), (dir)))
#define gls_glx_create_context_with_config_sgix(d, c, t, s, dir) \
    ((void *)p_create_context_sgix(D(d), (c), (t), X(s), (dir)))
#define gls_glx_create_context_attribs_arb(d, c, s, dir, a) \
    ((void *)p_create_context_attribs(D(d), C(c), X(s), (dir), (a)))
#define gls_glx_destroy_context(d, c) glXDestroyContext(D(d), X(c))
#define gls_glx_make_current(d, w, c) glXMakeCurrent(D(d), (w), X(c))
#define gls_glx_make_context_current(d, w, r, c) glXMakeContextCurrent(D(d), (w), (r), X(c))
#define gls_glx_swap_buffers(d, w) glXSwapBuffers(D(d), (w))
#define gls_glx_create_window(d, c, w, a) glXCreateWindow(D(d), C(c), (w), (a))
#define gls_glx_destroy_window(d, w) glXDestroyWindow(D(d), (w))
#define gls_glx_create_pixmap(d, c, p, a) glXCreatePixmap(D(d), C(c), (p), (a))
#define gls_glx_create_pbuffer(d, c, a) glXCreatePbuffer(D(d), C(c), (a))
#define gls_glx_create_glx_pixmap_with_config_sgix(d, c, p) p_create_pixmap_sgix(D(d), (c), (p))
#define gls_glx_create_glx_pbuffer_sgix(d, c, w, h, a) \
    p_create_pbuffer_sgix(D(d), (c), (w), (h), (int *)(a))
#define gls_glx_destroy_pbuffer(d, p) glXDestroyPbuffer(D(d), (p))
#define gls_glx_destroy_glx_pbuffer_sgix(d, p) p_destroy_pbuffer_sgix(D(d), (p))
#define gls_glx_destroy_pixmap(d, p) glXDestroyPixmap(D(d), (p))
#define gls_glx_destroy_glx_pixmap(d, p) glXDestroyGLXPixmap(D(d), (p))
#define gls_glx_get_proc_address(n) proc_pointer(glXGetProcAddressARB(n))
#define gls_gl_draw_buffer(b) glDrawBuffer(b)
#define gls_gl_draw_buffers(n, b) p_draw_buffers((n), (b))
#define gls_gl_draw_buffers_arb(n, b) p_draw_buffers_arb((n), (b))
#define gls_gl_read_buffer(b) glReadBuffer(b)
#define gls_gl_get_error() glGetError()
#define gls_gl_get_integerv(p, d) glGetIntegerv((p), (d))
#define gls_gl_get_booleanv(p, d) glGetBooleanv((p), (d))
#define gls_gl_get_floatv(p, d) glGetFloatv((p), (d))
#define gls_gl_get_doublev(p, d) glGetDoublev((p), (d))
#define gls_gl_bind_framebuffer(t, f) p_bind_framebuffer((t), (f))
#define gls_gl_bind_framebuffer_ext(t, f) p_bind_framebuffer_ext((t), (f))
#define gls_gl_delete_framebuffers(n, f) p_delete_framebuffers((n), (f))
#define gls_gl_delete_framebuffers_ext(n, f) p_delete_framebuffers_ext((n), (f))
#define gls_gl_delete_textures(n, t) p_delete_textures((n), (t))
#define gls_gl_delete_textures_ext(n, t) p_delete_textures_ext((n), (t))
#define gls_gl_delete_renderbuffers(n, r) p_delete_renderbuffers((n), (r))
#define gls_gl_delete_renderbuffers_ext(n, r) p_delete_renderbuffers_ext((n), (r))
#define gls_gl_get_framebuffer_attachment_parameteriv(t, a, p, v) p_attachment((t), (a), (p), (v))
#define gls_gl_get_framebuffer_attachment_parameteriv_ext(t, a, p, v) \
    p_attachment_ext((t), (a), (p), (v))
#define gls_gl_push_attrib(m) glPushAttrib(m)
#define gls_gl_pop_attrib() glPopAttrib()
#define gls_gl_viewport(x, y, w, h) glViewport((x), (y), (w), (h))
#define gls_gl_color_mask(r, g, b, a) glColorMask((r), (g), (b), (a))
#define gls_gl_clear(m) glClear(m)
#define gls_gl_clear_color(r, g, b, a) glClearColor((r), (g), (b), (a))
#define gls_gl_color_maski(i, r, g, b, a) p_color_maski((i), (r), (g), (b), (a))
#define gls_gl_get_booleani_v(p, i, d) p_get_booleani((p), (i), (d))
#define gls_gl_color_mask_indexed_ext(i, r, g, b, a) p_color_mask_indexed_ext((i), (r), (g), (b), (a))
#define gls_gl_color_maski_ext(i, r, g, b, a) p_color_maski_ext((i), (r), (g), (b), (a))
#define gls_gl_color_maski_oes(i, r, g, b, a) p_color_maski_oes((i), (r), (g), (b), (a))
#define gls_gl_get_boolean_indexedv_ext(p, i, d) p_get_boolean_indexed_ext((p), (i), (d))
#define gls_gl_get_integeri_v(p, i, d) p_get_integeri((p), (i), (d))
#define gls_gl_get_integer_indexedv_ext(p, i, d) p_get_integer_indexed_ext((p), (i), (d))
#define gls_gl_get_integer64i_v(p, i, d) p_get_integer64i((p), (i), (d))
#define gls_gl_get_integer64v(p, d) p_get_integer64((p), (d))
#define gls_gl_get_floati_v(p, i, d) p_get_floati((p), (i), (d))
#define gls_gl_get_floati_v_ext(p, i, d) p_get_floati_ext((p), (i), (d))
#define gls_gl_get_floati_v_oes(p, i, d) p_get_floati_oes((p), (i), (d))
#define gls_gl_get_float_indexedv_ext(p, i, d) p_get_float_indexed_ext((p), (i), (d))
#define gls_gl_get_doublei_v(p, i, d) p_get_doublei((p), (i), (d))
#define gls_gl_get_doublei_v_ext(p, i, d) p_get_doublei_ext((p), (i), (d))
#define gls_gl_get_double_indexedv_ext(p, i, d) p_get_double_indexed_ext((p), (i), (d))
#define gls_gl_clear_color_ii_ext(r, g, b, a) p_clear_color_ii((r), (g), (b), (a))
#define gls_gl_clear_color_iui_ext(r, g, b, a) p_clear_color_iui((r), (g), (b), (a))
#define gls_gl_clear_colorx(r, g, b, a) p_clear_colorx((r), (g), (b), (a))
#define gls_gl_clear_colorx_oes(r, g, b, a) p_clear_colorx_oes((r), (g), (b), (a))
#define gls_gl_blit_framebuffer(a, b, c, d, e, f, g, h, m, fl) \
    p_blit((a), (b), (c), (d), (e), (f), (g), (h), (m), (fl))
#define gls_gl_flush() glFlush()
#define gls_gl_finish() glFinish()
#define gls_gl_clear_bufferfv(b, i, v) p_clear_fv((b), (i), (v))
#define gls_gl_clear_bufferiv(b, i, v) p_clear_iv((b), (i), (v))
#define gls_gl_clear_bufferuiv(b, i, v) p_clear_uiv((b), (i), (v))
#define gls_gl_clear_named_framebufferfv(f, b, i, v) p_clear_named_fv((f), (b), (i), (v))
#define gls_gl_clear_named_framebufferiv(f, b, i, v) p_clear_named_iv((f), (b), (i), (v))
#define gls_gl_clear_named_framebufferuiv(f, b, i, v) p_clear_named_uiv((f), (b), (i), (v))
#define gls_gl_clear_named_framebufferfi(f, b, i, d, s) p_clear_named_fi((f), (b), (i), (d), (s))
#define gls_gl_named_framebuffer_draw_buffer(f, b) p_named_draw_buffer((f), (b))
#define gls_gl_named_framebuffer_read_buffer(f, b) p_named_read_buffer((f), (b))
#define gls_gl_named_framebuffer_draw_buffers(f, n, b) p_named_draw_buffers((f), (n), (b))
#define gls_gl_blit_named_framebuffer(r, w, a, b, c, d, e, f, g, h, m, fl) \
    p_blit_named((r), (w), (a), (b), (c), (d), (e), (f), (g), (h), (m), (fl))
#define gls_gl_invalidate_framebuffer(t, n, a) p_invalidate((t), (n), (a))
#define gls_gl_invalidate_sub_framebuffer(t, n, a, x, y, w, h) \
    p_invalidate_sub((t), (n), (a), (x), (y), (w), (h))
#define gls_gl_invalidate_named_framebuffer_data(f, n, a) p_invalidate_named((f), (n), (a))
#define gls_gl_invalidate_named_framebuffer_sub_data(f, n, a, x, y, w, h) \
    p_invalidate_named_sub((f), (n), (a), (x), (y), (w), (h))
#define gls_gl_check_named_framebuffer_status(f, t) p_check_named((f), (t))
#define gls_gl_check_named_framebuffer_status_ext(f, t) p_check_named_ext((f), (t))
#define gls_gl_get_named_framebuffer_attachment_parameteriv(f, a, p, v) \
    p_named_attachment((f), (a), (p), (v))
#define gls_gl_get_named_framebuffer_parameteriv(f, p, v) p_named_parameter((f), (p), (v))
#define gls_gl_get_framebuffer_parameteriv(t, p, v) p_parameter((t), (p), (v))
#define gls_gl_link_program(p) p_link_program(p)
#define gls_gl_create_shader_programv(t, n, s) p_create_shader_programv((t), (n), (s))
#define gls_gl_get_programiv(p, n, v) p_get_programiv((p), (n), (v))
#define gls_gl_get_program_binary(p, n, l, f, b) p_get_program_binary((p), (n), (l), (f), (b))
#define gls_gl_get_program_binary_oes(p, n, l, f, b) \
    p_get_program_binary_oes((p), (n), (l), (f), (b))
#define gls_gl_program_binary(p, f, b, n) p_program_binary((p), (f), (b), (n))
#define gls_gl_program_binary_oes(p, f, b, n) p_program_binary_oes((p), (f), (b), (n))

/* Messages go to stderr here, where tests/misuse.rs reads them. */
static void sentinel(void) {}
static void check_message(const char *fn, int reports, int line) {
    (void)fn, (void)reports, (void)line;
}
#else
#include "glstereo.h"

static void load_procs(void) {}

/* Leaves a known message, so a case can tell whether its call set one. */
static void sentinel(void) {
    uint32_t o = 0;
    (void)gls_output_from_name("misuse-sentinel", &o);
}

/* True when the last message is `fn`'s own: "fn: <at least a few words>". */
static int message_from(const char *fn) {
    const char *m = gls_last_error_message();
    size_t n = strlen(fn);
    return strncmp(m, fn, n) == 0 && m[n] == ':' && strlen(m) > n + 8;
}

static void check_message(const char *fn, int reports, int line) {
    if (reports) {
        CHECK(message_from(fn), "line %d: %s left no message of its own: \"%s\"", line, fn,
              gls_last_error_message());
    } else {
        CHECK(strstr(gls_last_error_message(), "misuse-sentinel") != NULL,
              "line %d: %s left a message though libGL answered: \"%s\"", line, fn,
              gls_last_error_message());
    }
}
#endif

/* ---- the harness ------------------------------------------------------ */

static const char *covered[128], *refused[128];
static int n_covered, n_refused;

/* Prints `line` once per name (for tests/misuse.rs). */
static void once(const char **seen, int *n, const char *what, const char *fn) {
    for (int i = 0; i < *n; ++i)
        if (strcmp(seen[i], fn) == 0) return;
    if (*n < 128) seen[(*n)++] = fn;
    printf("%s %s\n", what, fn);
}

static void note(const char *fn, int reports) {
    once(covered, &n_covered, "covers", fn);
    if (reports) once(refused, &n_refused, "refuses", fn);
}

/* EXPECT_RET(cond, refused, var, fn, args...): var = fn(args); cond holds;
 * refused = 1: the layer refused the call (a message of fn's own);
 * 0: libGL answered (no message). */
#define EXPECT_RET(cond, reports, var, fn, ...)                                \
    do {                                                                       \
        note(#fn, (reports));                                                  \
        sentinel();                                                            \
        var = fn(__VA_ARGS__);                                                 \
        CHECK(cond, "line %d: %s: %s", __LINE__, #fn, #cond);                  \
        check_message(#fn, (reports), __LINE__);                               \
    } while (0)
#define EXPECT_VOID(reports, fn, ...)                                          \
    do {                                                                       \
        note(#fn, (reports));                                                  \
        sentinel();                                                            \
        fn(__VA_ARGS__);                                                       \
        check_message(#fn, (reports), __LINE__);                               \
    } while (0)
#define EXPECT_RET0(cond, reports, var, fn)                                     \
    do {                                                                       \
        note(#fn, (reports));                                                  \
        sentinel();                                                            \
        var = fn();                                                            \
        CHECK(cond, "line %d: %s: %s", __LINE__, #fn, #cond);                  \
        check_message(#fn, (reports), __LINE__);                               \
    } while (0)
#define EXPECT_VOID0(reports, fn)                                              \
    do {                                                                       \
        note(#fn, (reports));                                                  \
        sentinel();                                                            \
        fn();                                                                  \
        check_message(#fn, (reports), __LINE__);                               \
    } while (0)

/* ---- X and GL errors --------------------------------------------------- */

static int x_error_code, x_error_count, glx_error_base;

static int on_x_error(Display *d, XErrorEvent *e) {
    (void)d;
    if (x_error_count++ == 0) x_error_code = e->error_code;
    return 0;
}

/* The first X error since the last call (0: none), after a round trip. */
static int x_error(Display *d) {
    XSync(d, False);
    int code = x_error_code;
    x_error_code = x_error_count = 0;
    return code;
}

#define EXPECT_X_ERROR(d, want)                                                       \
    do {                                                                              \
        int got_ = x_error(d);                                                        \
        CHECK(got_ == (want), "line %d: X error %d, wanted %d", __LINE__, got_, (want)); \
    } while (0)

/* glGetError through the function under test. */
static GLenum gl_error(void) {
    GLenum e;
    EXPECT_RET0(1, 0, e, gls_gl_get_error);
    return e;
}

#define EXPECT_GL_ERROR(want)                                                              \
    do {                                                                                   \
        GLenum got_ = gl_error();                                                          \
        CHECK(got_ == (want), "line %d: GL error 0x%x, wanted 0x%x", __LINE__, got_, (want)); \
        got_ = gl_error();                                                                 \
        CHECK(got_ == GL_NO_ERROR, "line %d: a second GL error 0x%x", __LINE__, got_);     \
    } while (0)

/* ---- set-up ------------------------------------------------------------- */

static int VIS_STEREO[] = {GLX_RGBA,  GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                           GLX_BLUE_SIZE, 1, GLX_DEPTH_SIZE, 1, GLX_STEREO, None};
static int VIS_MONO[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, None};
static const int FB_STEREO[] = {GLX_RENDER_TYPE, GLX_RGBA_BIT, GLX_DRAWABLE_TYPE, GLX_WINDOW_BIT,
                                GLX_DOUBLEBUFFER, True, GLX_STEREO, True, None};
static const int CORE_33[] = {GLX_CONTEXT_MAJOR_VERSION_ARB_, 3, GLX_CONTEXT_MINOR_VERSION_ARB_, 3,
                              GLX_CONTEXT_PROFILE_MASK_ARB_, GLX_CONTEXT_CORE_PROFILE_BIT_ARB_, None};

#define W 32
#define H 24

static Display *dpy, *dpy2;
/* The stereo visual, a mono one, the stereo configurations, and the one of
 * them whose visual is `vis` (so one window serves contexts of both). */
static void *vis, *mono_vis, **cfgs, *cfg;
static int n_cfgs;
static Window win, mono_win, win2;

/* A W x H window at (x, 0), apart from the others (an obscured window's
 * pixels cannot be read back). */
static Window make_window(Display *d, void *visual, int x) {
    XVisualInfo *vi = visual;
    Window root = RootWindow(d, vi->screen);
    XSetWindowAttributes wa;
    memset(&wa, 0, sizeof wa);
    wa.colormap = XCreateColormap(d, root, vi->visual, AllocNone);
    Window w = XCreateWindow(d, root, x, 0, W, H, 0, vi->depth, InputOutput, vi->visual,
                             CWColormap | CWBorderPixel, &wa);
    XMapWindow(d, w);
    XSync(d, False);
    return w;
}

/* The centre pixel of a window as the server has it, 0xRRGGBB. */
static long window_pixel(Display *d, Window w) {
    XImage *img = XGetImage(d, w, W / 2, H / 2, 1, 1, AllPlanes, ZPixmap);
    if (!img) return -1;
    long p = (long)(XGetPixel(img, 0, 0) & 0xFFFFFF);
    XDestroyImage(img);
    return p;
}

/* The centre pixel of one buffer of the current context, 0xRRGGBB. */
static long buffer_pixel(GLenum buffer) {
    unsigned char px[4] = {0, 0, 0, 0};
    gls_gl_read_buffer(buffer);
    glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    return (long)px[0] << 16 | (long)px[1] << 8 | px[2];
}

static void clear_to(long rgb) {
    glClearColor((float)(rgb >> 16 & 255) / 255.0f, (float)(rgb >> 8 & 255) / 255.0f,
                 (float)(rgb & 255) / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

/* Draws each eye in its colour on the current stereo context, swaps
 * `drawable`, and checks the eyes (front buffers) and the X window `w`
 * behind it: anaglyph-red-cyan takes red from the left eye, green and blue
 * from the right. (GL calls the layer answers go through the functions
 * under test: in the compat build the plain names are libGL's own.) */
static void paint_on(Display *d, GLXDrawable drawable, Window w, long left, long right,
                     const char *what) {
    gls_gl_draw_buffer(GL_BACK_LEFT);
    clear_to(left);
    gls_gl_draw_buffer(GL_BACK_RIGHT);
    clear_to(right);
    gls_gl_draw_buffer(GL_BACK);
    gls_glx_swap_buffers(d, drawable);
    long l = buffer_pixel(GL_FRONT_LEFT), r = buffer_pixel(GL_FRONT_RIGHT);
    gls_gl_read_buffer(GL_BACK);
    long shown = window_pixel(d, w), want = (left & 0xFF0000) | (right & 0x00FFFF);
    CHECK(l == left && r == right && shown == want,
          "%s: eyes %06lx %06lx, window %06lx; wanted %06lx %06lx, window %06lx", what, l, r,
          shown, left, right, want);
    GLenum e = gls_gl_get_error();
    CHECK(e == GL_NO_ERROR, "%s: GL error 0x%x", what, e);
}

static void paint(Display *d, Window w, long left, long right, const char *what) {
    paint_on(d, w, w, left, right, what);
}

static GLint stereo_now(void) {
    GLint v = -1;
    gls_gl_get_integerv(GL_STEREO, &v);
    return v;
}

/* ---- GLX: a NULL Display* ----------------------------------------------- */

static void null_display_cases(void *ctx) {
    void *v, *c, **list;
    int n = -7, val = -7, r;
    Bool ok;
    unsigned long id;
    EXPECT_RET(v == NULL, 1, v, gls_glx_choose_visual, NULL, 0, VIS_STEREO);
    EXPECT_RET(r == GLX_BAD_VALUE && val == -7, 1, r, gls_glx_get_config, NULL, vis, GLX_STEREO, &val);
    EXPECT_RET(list == NULL && n == -7, 1, list, gls_glx_choose_fbconfig, NULL, 0, FB_STEREO, &n);
    EXPECT_RET(list == NULL && n == -7, 1, list, gls_glx_choose_fbconfig_sgix, NULL, 0, FB_STEREO, &n);
    EXPECT_RET(list == NULL && n == -7, 1, list, gls_glx_get_fbconfigs, NULL, 0, &n);
    EXPECT_RET(r == GLX_BAD_VALUE && val == -7, 1, r, gls_glx_get_fbconfig_attrib, NULL, cfg, GLX_STEREO, &val);
    EXPECT_RET(r == GLX_BAD_VALUE && val == -7, 1, r, gls_glx_get_fbconfig_attrib_sgix, NULL, cfg, GLX_STEREO, &val);
    EXPECT_RET(v == NULL, 1, v, gls_glx_get_visual_from_fbconfig, NULL, cfg);
    EXPECT_RET(v == NULL, 1, v, gls_glx_get_visual_from_fbconfig_sgix, NULL, cfg);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_context, NULL, vis, NULL, True);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_new_context, NULL, cfg, GLX_RGBA_TYPE, NULL, True);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_context_with_config_sgix, NULL, cfg, GLX_RGBA_TYPE, NULL, True);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_context_attribs_arb, NULL, cfg, NULL, True, NULL);
    EXPECT_RET(id == 0, 1, id, gls_glx_create_window, NULL, cfg, win, NULL);
    EXPECT_RET(id == 0, 1, id, gls_glx_create_pixmap, NULL, cfg, win, NULL);
    EXPECT_RET(id == 0, 1, id, gls_glx_create_pbuffer, NULL, cfg, NULL);
    EXPECT_RET(id == 0, 1, id, gls_glx_create_glx_pixmap_with_config_sgix, NULL, cfg, win);
    EXPECT_RET(id == 0, 1, id, gls_glx_create_glx_pbuffer_sgix, NULL, cfg, 16, 16, NULL);
    EXPECT_VOID(1, gls_glx_destroy_pbuffer, NULL, 0x7777);
    EXPECT_VOID(1, gls_glx_destroy_glx_pbuffer_sgix, NULL, 0x7777);
    EXPECT_VOID(1, gls_glx_destroy_pixmap, NULL, 0x7777);
    EXPECT_VOID(1, gls_glx_destroy_glx_pixmap, NULL, 0x7777);

    /* With a stereo context current: nothing changes. */
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, win, ctx);
    EXPECT_RET(ok == False, 1, ok, gls_glx_make_current, NULL, win, ctx);
    EXPECT_RET(ok == False, 1, ok, gls_glx_make_context_current, NULL, win, win, ctx);
    EXPECT_VOID(1, gls_glx_swap_buffers, NULL, win);
    EXPECT_VOID(1, gls_glx_destroy_context, NULL, ctx);
    CHECK(glXGetCurrentContext() == ctx && stereo_now() == 1, "the stereo context is still current");
    paint(dpy, win, 0xC00000, 0x0040C0, "after NULL displays");
    /* A release with no display is what libglvnd allows. */
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, NULL, None, NULL);
    CHECK(glXGetCurrentContext() == NULL, "released");
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_context_current, NULL, None, None, NULL);
    /* A GLX window survives a destroy with no display. */
    GLXWindow glxwin;
    EXPECT_RET(glxwin != 0, 0, glxwin, gls_glx_create_window, dpy, cfg, win, NULL);
    EXPECT_VOID(1, gls_glx_destroy_window, NULL, glxwin);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_context_current, dpy, glxwin, glxwin, ctx);
    CHECK(stereo_now() == 1, "stereo on a GLX window");
    paint_on(dpy, glxwin, win, 0x800000, 0x00FF80, "on a GLX window");
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, None, NULL);
    EXPECT_VOID(0, gls_glx_destroy_window, dpy, glxwin);
    EXPECT_X_ERROR(dpy, 0);
}

/* ---- GLX: NULL where GLX needs a pointer, and bad values ------------------ */

static void null_pointer_cases(void) {
    void *v, *c, **list;
    int n = -7, val = -7, r;
    unsigned long id;
    EXPECT_RET(v == NULL, 1, v, gls_glx_choose_visual, dpy, 0, NULL);
    EXPECT_RET(r == GLX_BAD_VALUE && val == -7, 1, r, gls_glx_get_config, dpy, NULL, GLX_STEREO, &val);
    EXPECT_RET(r == GLX_BAD_VALUE, 1, r, gls_glx_get_config, dpy, vis, GLX_STEREO, NULL);
    EXPECT_RET(list == NULL, 1, list, gls_glx_choose_fbconfig, dpy, 0, FB_STEREO, NULL);
    EXPECT_RET(list == NULL, 1, list, gls_glx_choose_fbconfig_sgix, dpy, 0, FB_STEREO, NULL);
    EXPECT_RET(list == NULL, 1, list, gls_glx_get_fbconfigs, dpy, 0, NULL);
    EXPECT_RET(r == GLX_BAD_VALUE, 1, r, gls_glx_get_fbconfig_attrib, dpy, cfg, GLX_STEREO, NULL);
    EXPECT_RET(r == GLX_BAD_VALUE, 1, r, gls_glx_get_fbconfig_attrib_sgix, dpy, cfg, GLX_STEREO, NULL);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_context, dpy, NULL, NULL, True);
    void *p;
    EXPECT_RET(p == NULL, 1, p, gls_glx_get_proc_address, NULL);
    EXPECT_X_ERROR(dpy, 0);

    /* GLX's "use the defaults": a NULL attribute list is fine. */
    EXPECT_RET(list != NULL && n > 0, 0, list, gls_glx_choose_fbconfig, dpy, 0, NULL, &n);
    XFree(list);
    /* A NULL configuration: libGL's own GLXBadFBConfig. */
    EXPECT_RET(r != Success && val == -7, 0, r, gls_glx_get_fbconfig_attrib, dpy, NULL, GLX_STEREO, &val);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_FBCONFIG_);
    EXPECT_RET(r != Success && val == -7, 0, r, gls_glx_get_fbconfig_attrib_sgix, dpy, NULL, GLX_STEREO, &val);
    x_error(dpy);
    EXPECT_RET(v == NULL, 0, v, gls_glx_get_visual_from_fbconfig, dpy, NULL);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_FBCONFIG_);
    EXPECT_RET(v == NULL, 0, v, gls_glx_get_visual_from_fbconfig_sgix, dpy, NULL);
    x_error(dpy);
    EXPECT_RET(c == NULL, 0, c, gls_glx_create_new_context, dpy, NULL, GLX_RGBA_TYPE, NULL, True);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_FBCONFIG_);
    EXPECT_RET(c == NULL, 0, c, gls_glx_create_context_with_config_sgix, dpy, NULL, GLX_RGBA_TYPE, NULL, True);
    x_error(dpy);
    EXPECT_RET(c == NULL, 0, c, gls_glx_create_context_attribs_arb, dpy, NULL, NULL, True, NULL);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_FBCONFIG_);
    EXPECT_RET(id == 0, 0, id, gls_glx_create_window, dpy, NULL, win, NULL);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_FBCONFIG_);
    EXPECT_RET(id == 0, 0, id, gls_glx_create_pixmap, dpy, NULL, win, NULL);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_FBCONFIG_);
    EXPECT_RET(id == 0, 0, id, gls_glx_create_pbuffer, dpy, NULL, NULL);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_FBCONFIG_);
    EXPECT_RET(id == 0, 0, id, gls_glx_create_glx_pixmap_with_config_sgix, dpy, NULL, win);
    EXPECT_RET(id == 0, 0, id, gls_glx_create_glx_pbuffer_sgix, dpy, NULL, 16, 16, NULL);
    x_error(dpy);
    /* Drawables GLX does not know: libGL's X errors. */
    EXPECT_VOID(0, gls_glx_destroy_pbuffer, dpy, 0x7777);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_PBUFFER_);
    EXPECT_VOID(0, gls_glx_destroy_glx_pbuffer_sgix, dpy, 0x7777);
    EXPECT_X_ERROR(dpy, 0); /* Mesa sends nothing for a pbuffer it does not know */
    EXPECT_VOID(0, gls_glx_destroy_pixmap, dpy, 0x7777);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_PIXMAP_);
    EXPECT_VOID(0, gls_glx_destroy_glx_pixmap, dpy, 0x7777);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_PIXMAP_);

    /* Bad screens and attributes: libGL's answers. */
    EXPECT_RET(v == NULL, 0, v, gls_glx_choose_visual, dpy, 99, VIS_STEREO);
    EXPECT_RET(v == NULL, 0, v, gls_glx_choose_visual, dpy, -1, VIS_STEREO);
    n = -7;
    EXPECT_RET(list == NULL && n == -7, 0, list, gls_glx_choose_fbconfig, dpy, 99, FB_STEREO, &n);
    EXPECT_RET(list == NULL, 0, list, gls_glx_get_fbconfigs, dpy, 99, &n);
    EXPECT_RET(r == GLX_BAD_ATTRIBUTE && val == -7, 0, r, gls_glx_get_config, dpy, vis, 0x7777, &val);
    EXPECT_RET(r == GLX_BAD_ATTRIBUTE && val == -7, 0, r, gls_glx_get_fbconfig_attrib, dpy, cfg, 0x7777, &val);
    EXPECT_RET(r == GLX_BAD_ATTRIBUTE && val == -7, 0, r, gls_glx_get_fbconfig_attrib_sgix, dpy, cfg, 0x7777, &val);
    EXPECT_RET(c == NULL, 0, c, gls_glx_create_new_context, dpy, cfg, 0x7777, NULL, True);
    EXPECT_X_ERROR(dpy, BadValue);
    EXPECT_RET(c == NULL, 0, c, gls_glx_create_context_with_config_sgix, dpy, cfg, 0x7777, NULL, True);
    EXPECT_X_ERROR(dpy, BadValue);
    const int unknown[] = {0x7777, 1, None}, too_new[] = {GLX_CONTEXT_MAJOR_VERSION_ARB_, 9, None};
    EXPECT_RET(c == NULL, 0, c, gls_glx_create_context_attribs_arb, dpy, cfg, NULL, True, unknown);
    EXPECT_X_ERROR(dpy, BadValue);
    EXPECT_RET(c == NULL, 0, c, gls_glx_create_context_attribs_arb, dpy, cfg, NULL, True, too_new);
    CHECK(x_error(dpy) != 0, "GL 9.0: an X error");
    /* What the layer answers itself is right for the stereo configurations. */
    EXPECT_RET(r == Success && val == 1, 0, r, gls_glx_get_fbconfig_attrib, dpy, cfg, GLX_STEREO, &val);
    val = -7;
    EXPECT_RET(r == Success && val == 1, 0, r, gls_glx_get_config, dpy, vis, GLX_STEREO, &val);
    EXPECT_X_ERROR(dpy, 0);
}

/* ---- GLX: destroyed contexts, double destroy, share lists ----------------- */

static void context_cases(void) {
    void *ctx, *dead, *c;
    Bool ok;
    EXPECT_RET(dead != NULL, 0, dead, gls_glx_create_context, dpy, vis, NULL, True);
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, dead);
    EXPECT_X_ERROR(dpy, 0);
    /* libGL knows a destroyed context: GLXBadContext, False. */
    EXPECT_RET(ok == False, 0, ok, gls_glx_make_current, dpy, win, dead);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_CONTEXT_);
    EXPECT_RET(ok == False, 0, ok, gls_glx_make_context_current, dpy, win, win, dead);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_CONTEXT_);
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, dead);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_CONTEXT_);
    /* ... but reads it as a share list (and crashes): refused. */
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_context, dpy, vis, dead, True);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_new_context, dpy, cfg, GLX_RGBA_TYPE, dead, True);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_context_with_config_sgix, dpy, cfg, GLX_RGBA_TYPE, dead, True);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_context_attribs_arb, dpy, cfg, dead, True, NULL);
    EXPECT_X_ERROR(dpy, 0);
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, NULL); /* nothing, as libGL */
    EXPECT_X_ERROR(dpy, 0);

    /* A live share list is fine, and so is the context made with it. */
    EXPECT_RET(ctx != NULL, 0, ctx, gls_glx_create_context_attribs_arb, dpy, cfg, NULL, True, NULL);
    EXPECT_RET(c != NULL, 0, c, gls_glx_create_context, dpy, vis, ctx, True);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, win, c);
    CHECK(stereo_now() == 1, "a stereo context sharing another");
    paint(dpy, win, 0x40FF00, 0xFF0040, "sharing");

    /* Destroyed while current: it stays current (GLX) and keeps working
     * until released; destroying or binding it again meanwhile is refused
     * (libGL would answer GLXBadContext). */
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, c);
    CHECK(glXGetCurrentContext() == c && stereo_now() == 1, "still current after destroy");
    paint(dpy, win, 0x0000FF, 0xFFFF00, "destroyed while current");
    EXPECT_VOID(1, gls_glx_destroy_context, dpy, c);
    EXPECT_RET(ok == False, 1, ok, gls_glx_make_current, dpy, win, c);
    EXPECT_RET(ok == False, 1, ok, gls_glx_make_context_current, dpy, win, win, c);
    CHECK(glXGetCurrentContext() == c, "still current after the refusals");
    paint(dpy, win, 0x00FF00, 0xFF00FF, "destroyed while current, again");
    EXPECT_X_ERROR(dpy, 0);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, None, NULL);
    EXPECT_RET(ok == False, 0, ok, gls_glx_make_current, dpy, win, c);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_CONTEXT_);
    EXPECT_RET(c == NULL, 1, c, gls_glx_create_context, dpy, vis, c, True);

    /* A context of another display (another connection to the server) made
     * current on that display's window: GLX allows it; stereo still works. */
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy2, win2, ctx);
    CHECK(stereo_now() == 1, "a context of another display");
    paint(dpy2, win2, 0xFF00FF, 0x00FF00, "context of another display");
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy2, None, NULL);
    EXPECT_X_ERROR(dpy, 0);
    EXPECT_X_ERROR(dpy2, 0);
    /* A stereo configuration of display 1 on display 2: as libGL answers
     * for a configuration of another display. */
    int val = -7, r;
    EXPECT_RET(r != Success && val == -7, 0, r, gls_glx_get_fbconfig_attrib, dpy2, cfg, GLX_STEREO, &val);
    EXPECT_RET(c == NULL, 0, c, gls_glx_create_new_context, dpy2, cfg, GLX_RGBA_TYPE, NULL, True);
    EXPECT_X_ERROR(dpy2, glx_error_base + GLX_BAD_FBCONFIG_);

    EXPECT_VOID(0, gls_glx_destroy_context, dpy, ctx);
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, ctx);
    EXPECT_X_ERROR(dpy, glx_error_base + GLX_BAD_CONTEXT_);
}

/* ---- GL: no context current ----------------------------------------------- */

static void no_context_cases(void) {
    GLint iv = -5;
    GLboolean bv = 7;
    GLfloat fv = -5.0f;
    GLdouble dv = -5.0;
    GLenum two[2] = {GL_BACK_LEFT, GL_BACK_RIGHT};
    GLuint name = 1;
    CHECK(glXGetCurrentContext() == NULL, "no context current");
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_BACK_LEFT);
    EXPECT_VOID(0, gls_gl_draw_buffers, 2, two);
    EXPECT_VOID(0, gls_gl_draw_buffers_arb, 2, two);
    EXPECT_VOID(0, gls_gl_read_buffer, GL_FRONT_RIGHT);
    EXPECT_VOID(0, gls_gl_get_integerv, GL_STEREO, &iv);
    EXPECT_VOID(0, gls_gl_get_booleanv, GL_STEREO, &bv);
    EXPECT_VOID(0, gls_gl_get_floatv, GL_STEREO, &fv);
    EXPECT_VOID(0, gls_gl_get_doublev, GL_STEREO, &dv);
    EXPECT_VOID(0, gls_gl_get_framebuffer_attachment_parameteriv, GL_FRAMEBUFFER_, GL_BACK_LEFT,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_, &iv);
    EXPECT_VOID(0, gls_gl_get_framebuffer_attachment_parameteriv_ext, GL_FRAMEBUFFER_, GL_BACK_LEFT,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_, &iv);
    CHECK(iv == -5 && bv == 7 && fv == -5.0f && dv == -5.0, "outputs written with no context");
    EXPECT_VOID(0, gls_gl_bind_framebuffer, GL_FRAMEBUFFER_, 0);
    EXPECT_VOID(0, gls_gl_bind_framebuffer_ext, GL_FRAMEBUFFER_, 0);
    EXPECT_VOID(0, gls_gl_delete_framebuffers, 1, &name);
    EXPECT_VOID(0, gls_gl_delete_framebuffers_ext, 1, &name);
    EXPECT_VOID(0, gls_gl_delete_textures, 1, &name);
    EXPECT_VOID(0, gls_gl_delete_textures_ext, 1, &name);
    EXPECT_VOID(0, gls_gl_delete_renderbuffers, 1, &name);
    EXPECT_VOID(0, gls_gl_delete_renderbuffers_ext, 1, &name);
    EXPECT_VOID(0, gls_gl_push_attrib, GL_COLOR_BUFFER_BIT);
    EXPECT_VOID0(0, gls_gl_pop_attrib);
    EXPECT_VOID(0, gls_gl_viewport, 0, 0, -1, -1);
    EXPECT_VOID(0, gls_gl_color_mask, 1, 1, 1, 1);
    EXPECT_VOID(0, gls_gl_clear_color, 0.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_VOID(0, gls_gl_clear, GL_COLOR_BUFFER_BIT);
    EXPECT_VOID(0, gls_gl_color_maski, 0, 1, 1, 1, 1);
    EXPECT_VOID(0, gls_gl_get_booleani_v, GL_COLOR_WRITEMASK, 0, &bv);
    EXPECT_VOID(0, gls_gl_color_mask_indexed_ext, 0, 1, 1, 1, 1);
    EXPECT_VOID(0, gls_gl_color_maski_ext, 0, 1, 1, 1, 1);
    EXPECT_VOID(0, gls_gl_color_maski_oes, 0, 1, 1, 1, 1);
    EXPECT_VOID(0, gls_gl_clear_color_ii_ext, 0, 0, 0, 0);
    EXPECT_VOID(0, gls_gl_clear_color_iui_ext, 0, 0, 0, 0);
    EXPECT_VOID(0, gls_gl_clear_colorx, 0, 0, 0, 0);
    EXPECT_VOID(0, gls_gl_clear_colorx_oes, 0, 0, 0, 0);
    {
        GLboolean b4[4] = {7, 7, 7, 7};
        GLint i4[4] = {-5, -5, -5, -5};
        int64_t l4[4] = {-5, -5, -5, -5};
        GLfloat f4[4] = {-5, -5, -5, -5};
        GLdouble d4[4] = {-5, -5, -5, -5};
        EXPECT_VOID(0, gls_gl_get_boolean_indexedv_ext, GL_COLOR_WRITEMASK, 0, b4);
        EXPECT_VOID(0, gls_gl_get_integeri_v, GL_COLOR_WRITEMASK, 0, i4);
        EXPECT_VOID(0, gls_gl_get_integer_indexedv_ext, GL_COLOR_WRITEMASK, 0, i4);
        EXPECT_VOID(0, gls_gl_get_integer64i_v, GL_COLOR_WRITEMASK, 0, l4);
        EXPECT_VOID(0, gls_gl_get_integer64v, GL_COLOR_WRITEMASK, l4);
        EXPECT_VOID(0, gls_gl_get_floati_v, GL_COLOR_WRITEMASK, 0, f4);
        EXPECT_VOID(0, gls_gl_get_floati_v_ext, GL_COLOR_WRITEMASK, 0, f4);
        EXPECT_VOID(0, gls_gl_get_floati_v_oes, GL_COLOR_WRITEMASK, 0, f4);
        EXPECT_VOID(0, gls_gl_get_float_indexedv_ext, GL_COLOR_WRITEMASK, 0, f4);
        EXPECT_VOID(0, gls_gl_get_doublei_v, GL_COLOR_WRITEMASK, 0, d4);
        EXPECT_VOID(0, gls_gl_get_doublei_v_ext, GL_COLOR_WRITEMASK, 0, d4);
        EXPECT_VOID(0, gls_gl_get_double_indexedv_ext, GL_COLOR_WRITEMASK, 0, d4);
        CHECK(b4[0] == 7 && i4[0] == -5 && l4[0] == -5 && f4[0] == -5.0f && d4[0] == -5.0,
              "indexed outputs written with no context");
    }
    EXPECT_VOID(0, gls_gl_blit_framebuffer, 0, 0, 1, 1, 0, 0, 1, 1, GL_COLOR_BUFFER_BIT,
                GL_NEAREST);
    EXPECT_VOID0(0, gls_gl_flush);
    EXPECT_VOID0(0, gls_gl_finish);
    /* NULL pointers: refused; no context, so no GL error either. */
    EXPECT_VOID(1, gls_gl_get_integerv, GL_STEREO, NULL);
    EXPECT_VOID(1, gls_gl_draw_buffers, 1, NULL);
    EXPECT_GL_ERROR(GL_NO_ERROR);
}

/* ---- GL: a stereo context current ------------------------------------------ */

/* Every NULL the layer refuses, in whatever context is current: each is
 * GL_INVALID_VALUE for glGetError (from the layer's queue or the driver). */
static void null_gl_pointers(const char *where) {
    (void)where;
    EXPECT_VOID(1, gls_gl_get_integerv, GL_STEREO, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_booleanv, GL_STEREO, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_floatv, GL_STEREO, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_doublev, GL_STEREO, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_booleani_v, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_boolean_indexedv_ext, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_integeri_v, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_integer_indexedv_ext, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_integer64i_v, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_integer64v, GL_STEREO, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_floati_v, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_floati_v_ext, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_floati_v_oes, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_float_indexedv_ext, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_doublei_v, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_doublei_v_ext, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_double_indexedv_ext, GL_COLOR_WRITEMASK, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_draw_buffers, 1, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_draw_buffers_arb, 2, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_delete_framebuffers, 1, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_delete_framebuffers_ext, 3, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_delete_textures, 1, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_delete_textures_ext, 2, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_delete_renderbuffers, 1, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_delete_renderbuffers_ext, 4, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_framebuffer_attachment_parameteriv, GL_FRAMEBUFFER_, GL_BACK_LEFT,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_framebuffer_attachment_parameteriv_ext, GL_FRAMEBUFFER_, GL_BACK_LEFT,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_clear_bufferfv, GL_COLOR_, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_clear_bufferiv, GL_STENCIL, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_clear_bufferuiv, GL_COLOR_, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_clear_named_framebufferfv, 0, GL_COLOR_, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_clear_named_framebufferiv, 0, GL_STENCIL, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_clear_named_framebufferuiv, 0, GL_COLOR_, 0, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_named_framebuffer_draw_buffers, 0, 1, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_invalidate_framebuffer, GL_FRAMEBUFFER_, 1, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_invalidate_sub_framebuffer, GL_FRAMEBUFFER_, 2, NULL, 0, 0, 1, 1);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_invalidate_named_framebuffer_data, 0, 1, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_invalidate_named_framebuffer_sub_data, 0, 3, NULL, 0, 0, 1, 1);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_named_framebuffer_attachment_parameteriv, 0, GL_BACK_LEFT,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_named_framebuffer_parameteriv, 0, GL_STEREO, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_framebuffer_parameteriv, GL_FRAMEBUFFER_, GL_STEREO, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    GLuint prog = 7;
    EXPECT_RET(prog == 0, 1, prog, gls_gl_create_shader_programv, GL_FRAGMENT_SHADER_, 1, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    GLsizei blen = -5;
    GLenum bfmt = 7;
    unsigned char bbuf[16];
    EXPECT_VOID(1, gls_gl_get_programiv, 0x7777, GL_LINK_STATUS_, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_program_binary, 0x7777, 16, &blen, NULL, bbuf);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_program_binary, 0x7777, 16, &blen, &bfmt, NULL);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_get_program_binary_oes, 0x7777, 16, &blen, NULL, bbuf);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_program_binary, 0x7777, GL_PROGRAM_BINARY_FORMAT_MESA_, NULL, 16);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(1, gls_gl_program_binary_oes, 0x7777, GL_PROGRAM_BINARY_FORMAT_MESA_, NULL, 16);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    CHECK(blen == -5 && bfmt == 7, "program binary outputs written on a refusal");
    /* n = 0 needs no pointer. */
    EXPECT_VOID(0, gls_gl_draw_buffers, 0, NULL);
    EXPECT_VOID(0, gls_gl_delete_framebuffers, 0, NULL);
    EXPECT_GL_ERROR(GL_NO_ERROR);
}

static void stereo_gl_cases(void *ctx) {
    Bool ok;
    GLint iv = -5;
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, win, ctx);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    null_gl_pointers("stereo");

    /* Bad enums and values: GL's errors, nothing changed. */
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_BACK);
    EXPECT_VOID(0, gls_gl_draw_buffer, 0x7777);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_AUX0);
    EXPECT_GL_ERROR(GL_INVALID_OPERATION);
    EXPECT_VOID(0, gls_gl_get_integerv, GL_DRAW_BUFFER, &iv);
    CHECK(iv == GL_BACK, "GL_DRAW_BUFFER 0x%x after failed calls", (unsigned)iv);
    GLenum two[2] = {GL_BACK_LEFT, GL_BACK_RIGHT}, twice[2] = {GL_BACK_LEFT, GL_BACK_LEFT};
    EXPECT_VOID(0, gls_gl_draw_buffers, -1, two);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_draw_buffers_arb, 2, twice);
    EXPECT_GL_ERROR(GL_INVALID_OPERATION);
    EXPECT_VOID(0, gls_gl_draw_buffers_arb, 2, two);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    EXPECT_VOID(0, gls_gl_read_buffer, 0x7777);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    iv = -5;
    EXPECT_VOID(0, gls_gl_get_integerv, 0x7777, &iv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    GLboolean bv = 7;
    GLfloat fv = -5.0f;
    GLdouble dv = -5.0;
    EXPECT_VOID(0, gls_gl_get_booleanv, 0x7777, &bv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_get_floatv, 0x7777, &fv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_get_doublev, 0x7777, &dv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    CHECK(iv == -5 && bv == 7 && fv == -5.0f && dv == -5.0, "outputs written on error");
    EXPECT_VOID(0, gls_gl_bind_framebuffer, 0x7777, 0);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_bind_framebuffer_ext, 0x7777, 0);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    GLuint one = 1;
    EXPECT_VOID(0, gls_gl_delete_framebuffers, -1, &one);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_get_framebuffer_attachment_parameteriv, GL_FRAMEBUFFER_, 0x7777,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_, &iv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    /* glClearBuffer, DSA on framebuffer 0, links: GL's errors. */
    const GLfloat color[4] = {0, 0, 0, 1};
    const GLint ivals[4] = {0, 0, 0, 0};
    const GLuint uvals[4] = {0, 0, 0, 0};
    EXPECT_VOID(0, gls_gl_clear_bufferfv, GL_COLOR_, 8, color);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_clear_bufferiv, 0x7777, 0, ivals);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_clear_bufferuiv, GL_COLOR_, -1, uvals);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_clear_named_framebufferfv, 0, GL_COLOR_, 8, color);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_clear_named_framebufferiv, 0, 0x7777, 0, ivals);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_clear_named_framebufferuiv, 0, GL_COLOR_, -1, uvals);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_clear_named_framebufferfi, 0, GL_COLOR_, 0, 1.0f, 0);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_named_framebuffer_draw_buffer, 0, 0x7777);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_named_framebuffer_draw_buffers, 0, -1, two);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_named_framebuffer_read_buffer, 0, GL_AUX0);
    EXPECT_GL_ERROR(GL_INVALID_OPERATION);
    EXPECT_VOID(0, gls_gl_blit_named_framebuffer, 0, 0, 0, 0, 1, 1, 0, 0, 1, 1,
                GL_COLOR_BUFFER_BIT, 0x7777);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_blit_framebuffer, 0, 0, 1, 1, 0, 0, 1, 1, GL_COLOR_BUFFER_BIT, 0x7777);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_color_maski, 0x7777, 1, 1, 1, 1);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    GLboolean mask4[4] = {7, 7, 7, 7};
    EXPECT_VOID(0, gls_gl_get_booleani_v, 0x7777, 0, mask4);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_color_mask, 1, 0, 1, 0);
    EXPECT_VOID(0, gls_gl_get_booleani_v, GL_COLOR_WRITEMASK, 0, mask4);
    CHECK(mask4[0] == 1 && mask4[1] == 0 && mask4[2] == 1 && mask4[3] == 0,
          "GL_COLOR_WRITEMASK %d%d%d%d", mask4[0], mask4[1], mask4[2], mask4[3]);
    EXPECT_VOID(0, gls_gl_color_mask, 1, 1, 1, 1);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    /* The other names of glColorMaski, and every indexed query: a bad
     * index or pname is GL's error; GL_COLOR_WRITEMASK is the program's. */
    EXPECT_VOID(0, gls_gl_color_mask_indexed_ext, 0x7777, 1, 1, 1, 1);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_color_maski_ext, 0x7777, 1, 1, 1, 1);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_color_maski_oes, 0x7777, 1, 1, 1, 1);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    {
        GLboolean b4[4] = {7, 7, 7, 7};
        GLint i4[4] = {7, 7, 7, 7}, i4b[4] = {7, 7, 7, 7};
        int64_t l4[4] = {7, 7, 7, 7}, l4b[4] = {7, 7, 7, 7};
        GLfloat f4[4] = {7, 7, 7, 7}, f4b[4] = {7, 7, 7, 7}, f4c[4] = {7, 7, 7, 7};
        GLfloat f4d[4] = {7, 7, 7, 7};
        GLdouble d4[4] = {7, 7, 7, 7}, d4b[4] = {7, 7, 7, 7}, d4c[4] = {7, 7, 7, 7};
        EXPECT_VOID(0, gls_gl_get_boolean_indexedv_ext, 0x7777, 0, b4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_integeri_v, 0x7777, 0, i4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_integer_indexedv_ext, 0x7777, 0, i4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_integer64i_v, 0x7777, 0, l4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_integer64v, 0x7777, l4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_floati_v, 0x7777, 0, f4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_floati_v_ext, 0x7777, 0, f4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_floati_v_oes, 0x7777, 0, f4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_float_indexedv_ext, 0x7777, 0, f4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_doublei_v, 0x7777, 0, d4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_doublei_v_ext, 0x7777, 0, d4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_get_double_indexedv_ext, 0x7777, 0, d4);
        EXPECT_GL_ERROR(GL_INVALID_ENUM);
        EXPECT_VOID(0, gls_gl_color_maski_oes, 1, 0, 1, 1, 0);
        EXPECT_VOID(0, gls_gl_color_maski_ext, 0, 1, 0, 1, 1);
        EXPECT_VOID(0, gls_gl_get_boolean_indexedv_ext, GL_COLOR_WRITEMASK, 1, b4);
        EXPECT_VOID(0, gls_gl_get_integeri_v, GL_COLOR_WRITEMASK, 1, i4);
        EXPECT_VOID(0, gls_gl_get_integer_indexedv_ext, GL_COLOR_WRITEMASK, 0, i4b);
        EXPECT_VOID(0, gls_gl_get_integer64i_v, GL_COLOR_WRITEMASK, 1, l4);
        EXPECT_VOID(0, gls_gl_get_integer64v, GL_COLOR_WRITEMASK, l4b);
        EXPECT_VOID(0, gls_gl_get_floati_v, GL_COLOR_WRITEMASK, 1, f4);
        EXPECT_VOID(0, gls_gl_get_floati_v_ext, GL_COLOR_WRITEMASK, 0, f4b);
        EXPECT_VOID(0, gls_gl_get_floati_v_oes, GL_COLOR_WRITEMASK, 1, f4c);
        EXPECT_VOID(0, gls_gl_get_float_indexedv_ext, GL_COLOR_WRITEMASK, 0, f4d);
        EXPECT_VOID(0, gls_gl_get_doublei_v, GL_COLOR_WRITEMASK, 1, d4);
        EXPECT_VOID(0, gls_gl_get_doublei_v_ext, GL_COLOR_WRITEMASK, 0, d4b);
        EXPECT_VOID(0, gls_gl_get_double_indexedv_ext, GL_COLOR_WRITEMASK, 1, d4c);
        EXPECT_GL_ERROR(GL_NO_ERROR);
        /* Buffer 1 is 0110, buffer 0 is 1011 (alpha written: the
         * program's mask, whatever the driver's). */
        CHECK(b4[0] == 0 && b4[1] == 1 && b4[2] == 1 && b4[3] == 0, "index 1 mask (boolean)");
        CHECK(i4[0] == 0 && i4[1] == 1 && i4[2] == 1 && i4[3] == 0, "index 1 mask (integer)");
        CHECK(i4b[0] == 1 && i4b[1] == 0 && i4b[2] == 1 && i4b[3] == 1, "index 0 mask (EXT)");
        CHECK(l4[0] == 0 && l4[1] == 1 && l4[2] == 1 && l4[3] == 0, "index 1 mask (int64)");
        CHECK(l4b[0] == 1 && l4b[1] == 0 && l4b[2] == 1 && l4b[3] == 1, "mask (glGetInteger64v)");
        CHECK(f4[1] == 1.0f && f4[3] == 0.0f && f4b[3] == 1.0f && f4c[3] == 0.0f &&
                  f4d[3] == 1.0f,
              "masks (float)");
        CHECK(d4[1] == 1.0 && d4[3] == 0.0 && d4b[3] == 1.0 && d4c[3] == 0.0, "masks (double)");
    }
    EXPECT_VOID(0, gls_gl_color_mask, 1, 1, 1, 1);
    EXPECT_VOID(0, gls_gl_clear_color_ii_ext, 1, 2, 3, 4);
    EXPECT_VOID(0, gls_gl_clear_color_iui_ext, 1, 2, 3, 4);
    EXPECT_VOID(0, gls_gl_clear_colorx, 0x8000, 0x8000, 0x8000, 0x8000);
    EXPECT_VOID(0, gls_gl_clear_colorx_oes, -0x8000, 0x20000, 0, 0);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    EXPECT_VOID(0, gls_gl_clear, 0x7777 << 16);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_clear_color, 0.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    const GLenum bad_attachment[1] = {0x7777};
    GLenum status;
    EXPECT_VOID(0, gls_gl_invalidate_framebuffer, GL_FRAMEBUFFER_, 1, bad_attachment);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_invalidate_sub_framebuffer, GL_FRAMEBUFFER_, 1, bad_attachment, 0, 0,
                1, 1);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_invalidate_named_framebuffer_data, 0, 1, bad_attachment);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_invalidate_named_framebuffer_sub_data, 0, 1, bad_attachment, 0, 0, 1, 1);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_invalidate_named_framebuffer_sub_data, 0, 0, bad_attachment, 0, 0, -1,
                1);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_RET(status == 0, 0, status, gls_gl_check_named_framebuffer_status, 0, 0x7777);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_RET(status == 0, 0, status, gls_gl_check_named_framebuffer_status_ext, 0, 0x7777);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_RET(status == GL_FRAMEBUFFER_COMPLETE_, 0, status, gls_gl_check_named_framebuffer_status,
               0, GL_READ_FRAMEBUFFER_);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    EXPECT_VOID(0, gls_gl_get_named_framebuffer_attachment_parameteriv, 0, 0x7777,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_, &iv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_get_named_framebuffer_parameteriv, 0, 0x7777, &iv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_get_framebuffer_parameteriv, 0x7777, GL_STEREO, &iv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_link_program, 0x7777);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    {
        GLint st = -5;
        GLsizei blen = -5;
        GLenum bfmt = 7;
        unsigned char bbuf[16] = {0};
        EXPECT_VOID(0, gls_gl_get_programiv, 0x7777, GL_LINK_STATUS_, &st);
        EXPECT_GL_ERROR(GL_INVALID_VALUE);
        EXPECT_VOID(0, gls_gl_get_program_binary, 0x7777, 16, &blen, &bfmt, bbuf);
        EXPECT_GL_ERROR(GL_INVALID_VALUE);
        EXPECT_VOID(0, gls_gl_get_program_binary_oes, 0x7777, -1, &blen, &bfmt, bbuf);
        EXPECT_GL_ERROR(GL_INVALID_VALUE);
        EXPECT_VOID(0, gls_gl_program_binary, 0x7777, GL_PROGRAM_BINARY_FORMAT_MESA_, bbuf, 16);
        EXPECT_GL_ERROR(GL_INVALID_VALUE);
        EXPECT_VOID(0, gls_gl_program_binary_oes, 0x7777, GL_PROGRAM_BINARY_FORMAT_MESA_, bbuf,
                    -1);
        EXPECT_GL_ERROR(GL_INVALID_VALUE);
        CHECK(st == -5 && bfmt == 7, "program outputs written on an error");
    }
    const char *src[1] = {"void main() {}"};
    GLuint sp = 7;
    EXPECT_RET(sp == 0, 0, sp, gls_gl_create_shader_programv, 0x7777, 1, src);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_get_framebuffer_attachment_parameteriv_ext, 0x7777, GL_BACK_LEFT,
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_, &iv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    EXPECT_VOID(0, gls_gl_get_framebuffer_attachment_parameteriv, GL_FRAMEBUFFER_, GL_BACK_RIGHT,
                0x7777, &iv);
    EXPECT_GL_ERROR(GL_INVALID_ENUM);
    CHECK(iv == -5, "attachment parameter written on error: %d", iv);
    EXPECT_VOID(0, gls_gl_viewport, 0, 0, -1, 4);
    EXPECT_GL_ERROR(GL_INVALID_VALUE);
    EXPECT_VOID(0, gls_gl_viewport, 0, 0, W, H);

    /* The attribute stack: underflow, overflow, and the emulated draw
     * buffer restored level by level. */
    EXPECT_VOID0(0, gls_gl_pop_attrib);
    EXPECT_GL_ERROR(GL_STACK_UNDERFLOW);
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_BACK_LEFT);
    EXPECT_VOID(0, gls_gl_push_attrib, GL_COLOR_BUFFER_BIT);
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_BACK_RIGHT);
    GLint max_depth = 0;
    gls_gl_get_integerv(GL_MAX_ATTRIB_STACK_DEPTH, &max_depth);
    for (int i = 1; i < max_depth; ++i) gls_gl_push_attrib(GL_COLOR_BUFFER_BIT);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    EXPECT_VOID(0, gls_gl_push_attrib, GL_COLOR_BUFFER_BIT);
    EXPECT_GL_ERROR(GL_STACK_OVERFLOW);
    for (int i = 1; i < max_depth; ++i) gls_gl_pop_attrib();
    EXPECT_VOID(0, gls_gl_get_integerv, GL_DRAW_BUFFER, &iv);
    CHECK(iv == GL_BACK_RIGHT, "after popping to level 1: 0x%x", (unsigned)iv);
    EXPECT_VOID0(0, gls_gl_pop_attrib);
    EXPECT_VOID(0, gls_gl_get_integerv, GL_DRAW_BUFFER, &iv);
    CHECK(iv == GL_BACK_LEFT, "after popping all: 0x%x", (unsigned)iv);
    EXPECT_VOID0(0, gls_gl_pop_attrib);
    EXPECT_GL_ERROR(GL_STACK_UNDERFLOW);
    EXPECT_VOID(0, gls_gl_get_integerv, GL_DRAW_BUFFER, &iv);
    CHECK(iv == GL_BACK_LEFT, "after an underflow: 0x%x", (unsigned)iv);

    /* Deleting every framebuffer name a program could guess never deletes
     * the emulated one (reported as 0). */
    GLuint names[128];
    for (GLuint i = 0; i < 128; ++i) names[i] = i + 1;
    EXPECT_VOID(0, gls_gl_delete_framebuffers, 64, names);
    EXPECT_VOID(0, gls_gl_delete_framebuffers_ext, 64, names + 64);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    EXPECT_VOID(0, gls_gl_get_integerv, GL_DRAW_FRAMEBUFFER_BINDING_, &iv);
    CHECK(iv == 0 && stereo_now() == 1, "the emulated framebuffer after deletes: %d", iv);
    EXPECT_VOID(0, gls_gl_bind_framebuffer, GL_FRAMEBUFFER_, 0);
    EXPECT_VOID(0, gls_gl_bind_framebuffer_ext, GL_FRAMEBUFFER_, 0);
    paint(dpy, win, 0xFF8000, 0x0080FF, "after deleting framebuffers 1-128");

    /* Front-buffer drawing shows on glFlush / glFinish. */
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_FRONT_LEFT);
    clear_to(0x204080);
    EXPECT_VOID0(0, gls_gl_flush);
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_FRONT_RIGHT);
    clear_to(0x6080A0);
    EXPECT_VOID0(0, gls_gl_finish);
    long shown = window_pixel(dpy, win);
    CHECK(shown == 0x2080A0, "front buffers after glFinish: %06lx", shown);
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_BACK);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, None, NULL);
}

/* ---- GL: a mono context, and a core-profile stereo context ----------------- */

static void mono_gl_cases(void) {
    void *mono;
    Bool ok;
    EXPECT_RET(mono != NULL, 0, mono, gls_glx_create_context, dpy, mono_vis, NULL, True);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, mono_win, mono);
    CHECK(stereo_now() == 0, "a mono context");
    null_gl_pointers("mono");
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_BACK_RIGHT);
    EXPECT_GL_ERROR(GL_INVALID_OPERATION);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, None, NULL);
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, mono);
}

static void core_gl_cases(void) {
    void *core;
    Bool ok;
    EXPECT_RET(core != NULL, 0, core, gls_glx_create_context_attribs_arb, dpy, cfg, NULL, True, CORE_33);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, win, core);
    CHECK(stereo_now() == 1, "a core-profile stereo context");
    /* No attribute stack in the core profile: GL_INVALID_OPERATION, as GL says. */
    EXPECT_VOID(0, gls_gl_push_attrib, GL_COLOR_BUFFER_BIT);
    EXPECT_GL_ERROR(GL_INVALID_OPERATION);
    EXPECT_VOID0(0, gls_gl_pop_attrib);
    EXPECT_GL_ERROR(GL_INVALID_OPERATION);
    null_gl_pointers("core");
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, None, NULL);
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, core);
}

/* ---- a display closed while its stereo context is current ----------------- */

/* A display with a stereo context current on a window, painted. */
static Display *stereo_display(Window *w, void **ctx, int x) {
    Display *d = XOpenDisplay(NULL);
    void *v;
    Bool ok;
    EXPECT_RET(v != NULL, 0, v, gls_glx_choose_visual, d, 0, VIS_STEREO);
    *w = make_window(d, v, x);
    EXPECT_RET(*ctx != NULL, 0, *ctx, gls_glx_create_context, d, v, NULL, True);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, d, *w, *ctx);
    paint(d, *w, 0x808000, 0x008080, "a third display");
    XFree(v);
    return d;
}

static void closed_display_cases(void) {
    Window w;
    void *ctx;
    Bool ok;
    GLint iv = -5;
    /* XCloseDisplay unbinds the context (libGL); the layer forgets the
     * display and its stereo state, and touches it no more. */
    XCloseDisplay(stereo_display(&w, &ctx, 6 * W));
    CHECK(glXGetCurrentContext() == NULL, "no context after XCloseDisplay");
    EXPECT_VOID(0, gls_gl_get_integerv, GL_STEREO, &iv);
    CHECK(iv == -5, "GL_STEREO answered with no context: %d", iv);
    EXPECT_VOID(0, gls_gl_draw_buffer, GL_BACK_LEFT);
    EXPECT_GL_ERROR(GL_NO_ERROR);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, None, NULL);
    /* A new display (often at the same address) starts afresh. */
    Display *d = stereo_display(&w, &ctx, 6 * W);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, d, None, NULL);
    EXPECT_VOID(0, gls_glx_destroy_context, d, ctx);
    EXPECT_X_ERROR(d, 0);
    XCloseDisplay(d);
}

int main(void) {
    setvbuf(stdout, NULL, _IOLBF, 0);
    XSetErrorHandler(on_x_error);
    dpy = XOpenDisplay(NULL);
    dpy2 = XOpenDisplay(NULL);
    int event_base;
    if (!dpy || !dpy2 || !glXQueryExtension(dpy, &glx_error_base, &event_base)) {
        fprintf(stderr, "no X display with GLX ($DISPLAY)\n");
        return 2;
    }
    load_procs();
    EXPECT_RET(vis != NULL, 0, vis, gls_glx_choose_visual, dpy, 0, VIS_STEREO);
    EXPECT_RET(mono_vis != NULL, 0, mono_vis, gls_glx_choose_visual, dpy, 0, VIS_MONO);
    EXPECT_RET(cfgs != NULL && n_cfgs > 0, 0, cfgs, gls_glx_choose_fbconfig, dpy, 0, FB_STEREO, &n_cfgs);
    if (!vis || !mono_vis || !cfgs) return SUMMARY();
    for (int i = 0; i < n_cfgs && !cfg; ++i) {
        int id = 0;
        gls_glx_get_fbconfig_attrib(dpy, cfgs[i], GLX_VISUAL_ID, &id);
        if ((VisualID)id == ((XVisualInfo *)vis)->visualid) cfg = cfgs[i];
    }
    CHECK(cfg != NULL, "a stereo configuration of the stereo visual");
    if (!cfg) return SUMMARY();
    win = make_window(dpy, vis, 0);
    mono_win = make_window(dpy, mono_vis, 2 * W);
    win2 = make_window(dpy2, vis, 4 * W);
    void *ctx;
    EXPECT_RET(ctx != NULL, 0, ctx, gls_glx_create_context, dpy, vis, NULL, True);

    null_display_cases(ctx);
    null_pointer_cases();
    context_cases();
    no_context_cases();
    stereo_gl_cases(ctx);
    mono_gl_cases();
    core_gl_cases();
    closed_display_cases();
    no_context_cases(); /* again, after all of the above */

    /* Still working: a new stereo context draws both eyes. */
    void *again;
    Bool ok;
    EXPECT_RET(again != NULL, 0, again, gls_glx_create_new_context, dpy, cfg, GLX_RGBA_TYPE, ctx, True);
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, win, again);
    paint(dpy, win, 0x00FF00, 0xFF00FF, "at the end");
    EXPECT_RET(ok == True, 0, ok, gls_glx_make_current, dpy, None, NULL);
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, again);
    EXPECT_VOID(0, gls_glx_destroy_context, dpy, ctx);
    EXPECT_X_ERROR(dpy, 0);
    XFree(cfgs);
    XFree(vis);
    XFree(mono_vis);
    XDestroyWindow(dpy, win);
    XDestroyWindow(dpy, mono_win);
    XDestroyWindow(dpy2, win2);
    XCloseDisplay(dpy2);
    XCloseDisplay(dpy);
    return SUMMARY();
}

/*
 * glstereo/compat.h: stereo for a GLX program rebuilt from source, with no
 * change to its code. Hand-written compat header: it maps the legacy GLX
 * and GL names a stereo program touches onto the gls_glx_* / gls_gl_*
 * functions of <glstereo.h> (the same implementation libglstereo_preload.so
 * gives unmodified binaries under glstereo-run); the library exports only
 * gls_ names. C99 or C++.
 *
 * Use: include it after every GL and GLX header of the file, and link with
 * -lglstereo as well as what the program linked before:
 *
 *     #include <GL/gl.h>
 *     #include <GL/glx.h>
 *     #include <glstereo/compat.h>
 *
 *     cc prog.c $(pkg-config --cflags --libs glstereo) -lGL -lX11
 *
 * What the program then gets (seed 000 §3-4, on any X server):
 *
 *   glXChooseVisual(dpy, screen, {..., GLX_STEREO, None})
 *   glXChooseFBConfig(dpy, screen, {..., GLX_STEREO, True, None}, &n)
 *     succeed where the server has no stereo visual (Mesa has none); the
 *     visual or configuration reports GLX_STEREO true.
 *   glXCreateContext / glXCreateNewContext / glXCreateContextAttribsARB
 *     with it make a stereo context; glXMakeCurrent gives it an emulated
 *     default framebuffer with GL_FRONT_LEFT, GL_BACK_LEFT, GL_FRONT_RIGHT
 *     and GL_BACK_RIGHT (and one depth/stencil buffer both eyes share),
 *     sized to the window and following it.
 *   glDrawBuffer(GL_BACK_LEFT) ... glDrawBuffer(GL_BACK_RIGHT) ...
 *     draw each eye; glGetBooleanv(GL_STEREO) is true; every GL rule of
 *     glDrawBuffer / glDrawBuffers / glReadBuffer holds, with GL's errors
 *     from glGetError.
 *   glXSwapBuffers(dpy, win)
 *     makes both back buffers the front ones and shows them in the window
 *     composed as GLSTEREO_MODE says (default anaglyph-red-cyan; every
 *     mode of glstereo-run --help), with GLSTEREO_SWAP_EYES and friends;
 *     GLSTEREO_CAPTURE_DIR writes each frame's eyes and composite.
 *   Shaders, glClearBuffer and GL 4.5 direct state access (core profile)
 *     see a real stereo framebuffer: under GL_BACK (or any name selecting
 *     several buffers) a shader's user-defined output 0 and
 *     glClearBuffer(GL_COLOR, 0, ...) reach every selected buffer
 *     (glLinkProgram adds copies of output 0 at locations 5-7, see
 *     README); glNamedFramebuffer*(0, ...), glBlitNamedFramebuffer,
 *     glClearNamedFramebuffer* and the framebuffer queries on 0 mean the
 *     emulated framebuffer. Call them by name or through
 *     glXGetProcAddress; both reach the gls_ versions.
 *
 * A program (or context) that never asks for stereo is served by the real
 * libGL as before. glXGetProcAddress returns the gls_ versions for these
 * names, so functions looked up at run time are covered too.
 */
#ifndef GLSTEREO_COMPAT_H
#define GLSTEREO_COMPAT_H

#include <string.h>

#include <GL/gl.h>
#include <GL/glx.h>

#include <glstereo.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A function as glXGetProcAddress returns it. */
typedef void (*gls_compat_proc)(void);

static inline XVisualInfo *gls_compat_glXChooseVisual(Display *dpy, int screen, int *attribs)
{
    return (XVisualInfo *)gls_glx_choose_visual(dpy, screen, attribs);
}
static inline int gls_compat_glXGetConfig(Display *dpy, XVisualInfo *vis, int attrib, int *value)
{
    return gls_glx_get_config(dpy, vis, attrib, value);
}
static inline GLXFBConfig *gls_compat_glXChooseFBConfig(Display *dpy, int screen,
                                                        const int *attribs, int *nelements)
{
    return (GLXFBConfig *)gls_glx_choose_fbconfig(dpy, screen, attribs, nelements);
}
static inline GLXFBConfig *gls_compat_glXGetFBConfigs(Display *dpy, int screen, int *nelements)
{
    return (GLXFBConfig *)gls_glx_get_fbconfigs(dpy, screen, nelements);
}
static inline int gls_compat_glXGetFBConfigAttrib(Display *dpy, GLXFBConfig config, int attribute,
                                                  int *value)
{
    return gls_glx_get_fbconfig_attrib(dpy, (void *)config, attribute, value);
}
static inline XVisualInfo *gls_compat_glXGetVisualFromFBConfig(Display *dpy, GLXFBConfig config)
{
    return (XVisualInfo *)gls_glx_get_visual_from_fbconfig(dpy, (void *)config);
}
static inline GLXContext gls_compat_glXCreateContext(Display *dpy, XVisualInfo *vis,
                                                     GLXContext share_list, Bool direct)
{
    return (GLXContext)gls_glx_create_context(dpy, vis, (void *)share_list, direct);
}
static inline GLXContext gls_compat_glXCreateNewContext(Display *dpy, GLXFBConfig config,
                                                        int render_type, GLXContext share_list,
                                                        Bool direct)
{
    return (GLXContext)gls_glx_create_new_context(dpy, (void *)config, render_type,
                                                  (void *)share_list, direct);
}
static inline GLXContext gls_compat_glXCreateContextAttribsARB(Display *dpy, GLXFBConfig config,
                                                               GLXContext share_context,
                                                               Bool direct, const int *attribs)
{
    return (GLXContext)gls_glx_create_context_attribs_arb(dpy, (void *)config,
                                                          (void *)share_context, direct, attribs);
}
static inline void gls_compat_glXDestroyContext(Display *dpy, GLXContext ctx)
{
    gls_glx_destroy_context(dpy, (void *)ctx);
}
static inline Bool gls_compat_glXMakeCurrent(Display *dpy, GLXDrawable drawable, GLXContext ctx)
{
    return gls_glx_make_current(dpy, drawable, (void *)ctx);
}
static inline Bool gls_compat_glXMakeContextCurrent(Display *dpy, GLXDrawable draw,
                                                    GLXDrawable read, GLXContext ctx)
{
    return gls_glx_make_context_current(dpy, draw, read, (void *)ctx);
}
static inline void gls_compat_glXSwapBuffers(Display *dpy, GLXDrawable drawable)
{
    gls_glx_swap_buffers(dpy, drawable);
}
static inline GLXWindow gls_compat_glXCreateWindow(Display *dpy, GLXFBConfig config, Window win,
                                                   const int *attribs)
{
    return gls_glx_create_window(dpy, (void *)config, win, attribs);
}
static inline void gls_compat_glXDestroyWindow(Display *dpy, GLXWindow win)
{
    gls_glx_destroy_window(dpy, win);
}
static inline GLXPixmap gls_compat_glXCreatePixmap(Display *dpy, GLXFBConfig config,
                                                   Pixmap pixmap, const int *attribs)
{
    return gls_glx_create_pixmap(dpy, (void *)config, pixmap, attribs);
}
static inline GLXPbuffer gls_compat_glXCreatePbuffer(Display *dpy, GLXFBConfig config,
                                                     const int *attribs)
{
    return gls_glx_create_pbuffer(dpy, (void *)config, attribs);
}
static inline void gls_compat_glXDestroyPbuffer(Display *dpy, GLXPbuffer pbuf)
{
    gls_glx_destroy_pbuffer(dpy, pbuf);
}
static inline void gls_compat_glXDestroyPixmap(Display *dpy, GLXPixmap pixmap)
{
    gls_glx_destroy_pixmap(dpy, pixmap);
}
static inline void gls_compat_glXDestroyGLXPixmap(Display *dpy, GLXPixmap pixmap)
{
    gls_glx_destroy_glx_pixmap(dpy, pixmap);
}
static inline gls_compat_proc gls_compat_glXGetProcAddress(const GLubyte *name)
{
    /* An object pointer to a function pointer, as POSIX dlsym() allows. */
    void *p = gls_glx_get_proc_address(name);
    gls_compat_proc f;
    memcpy(&f, &p, sizeof f);
    return f;
}

static inline void gls_compat_glDrawBuffer(GLenum buf)
{
    gls_gl_draw_buffer(buf);
}
static inline void gls_compat_glDrawBuffers(GLsizei n, const GLenum *bufs)
{
    gls_gl_draw_buffers(n, bufs);
}
static inline void gls_compat_glReadBuffer(GLenum src)
{
    gls_gl_read_buffer(src);
}
static inline GLenum gls_compat_glGetError(void)
{
    return gls_gl_get_error();
}
static inline void gls_compat_glGetIntegerv(GLenum pname, GLint *data)
{
    gls_gl_get_integerv(pname, data);
}
static inline void gls_compat_glGetBooleanv(GLenum pname, GLboolean *data)
{
    gls_gl_get_booleanv(pname, data);
}
static inline void gls_compat_glGetFloatv(GLenum pname, GLfloat *data)
{
    gls_gl_get_floatv(pname, data);
}
static inline void gls_compat_glGetDoublev(GLenum pname, GLdouble *data)
{
    gls_gl_get_doublev(pname, data);
}
static inline void gls_compat_glBindFramebuffer(GLenum target, GLuint framebuffer)
{
    gls_gl_bind_framebuffer(target, framebuffer);
}
static inline void gls_compat_glDeleteFramebuffers(GLsizei n, const GLuint *framebuffers)
{
    gls_gl_delete_framebuffers(n, framebuffers);
}
static inline void gls_compat_glDeleteTextures(GLsizei n, const GLuint *textures)
{
    gls_gl_delete_textures(n, textures);
}
static inline void gls_compat_glDeleteRenderbuffers(GLsizei n, const GLuint *renderbuffers)
{
    gls_gl_delete_renderbuffers(n, renderbuffers);
}
static inline void gls_compat_glGetFramebufferAttachmentParameteriv(GLenum target,
                                                                   GLenum attachment,
                                                                   GLenum pname, GLint *params)
{
    gls_gl_get_framebuffer_attachment_parameteriv(target, attachment, pname, params);
}
static inline void gls_compat_glPushAttrib(GLbitfield mask)
{
    gls_gl_push_attrib(mask);
}
static inline void gls_compat_glPopAttrib(void)
{
    gls_gl_pop_attrib();
}
static inline void gls_compat_glViewport(GLint x, GLint y, GLsizei width, GLsizei height)
{
    gls_gl_viewport(x, y, width, height);
}
static inline void gls_compat_glClear(GLbitfield mask)
{
    gls_gl_clear(mask);
}
static inline void gls_compat_glClearColor(GLfloat red, GLfloat green, GLfloat blue,
                                           GLfloat alpha)
{
    gls_gl_clear_color(red, green, blue, alpha);
}
static inline void gls_compat_glColorMask(GLboolean red, GLboolean green, GLboolean blue,
                                          GLboolean alpha)
{
    gls_gl_color_mask(red, green, blue, alpha);
}
static inline void gls_compat_glColorMaski(GLuint index, GLboolean red, GLboolean green,
                                           GLboolean blue, GLboolean alpha)
{
    gls_gl_color_maski(index, red, green, blue, alpha);
}
static inline void gls_compat_glGetBooleani_v(GLenum target, GLuint index, GLboolean *data)
{
    gls_gl_get_booleani_v(target, index, data);
}
static inline void gls_compat_glGetBooleanIndexedvEXT(GLenum target, GLuint index, GLboolean *data)
{
    gls_gl_get_boolean_indexedv_ext(target, index, data);
}
static inline void gls_compat_glGetIntegeri_v(GLenum target, GLuint index, GLint *data)
{
    gls_gl_get_integeri_v(target, index, data);
}
static inline void gls_compat_glGetIntegerIndexedvEXT(GLenum target, GLuint index, GLint *data)
{
    gls_gl_get_integer_indexedv_ext(target, index, data);
}
static inline void gls_compat_glGetInteger64i_v(GLenum target, GLuint index, GLint64 *data)
{
    gls_gl_get_integer64i_v(target, index, data);
}
static inline void gls_compat_glGetFloati_v(GLenum target, GLuint index, GLfloat *data)
{
    gls_gl_get_floati_v(target, index, data);
}
static inline void gls_compat_glGetFloati_vEXT(GLenum target, GLuint index, GLfloat *data)
{
    gls_gl_get_floati_v_ext(target, index, data);
}
static inline void gls_compat_glGetFloati_vOES(GLenum target, GLuint index, GLfloat *data)
{
    gls_gl_get_floati_v_oes(target, index, data);
}
static inline void gls_compat_glGetFloatIndexedvEXT(GLenum target, GLuint index, GLfloat *data)
{
    gls_gl_get_float_indexedv_ext(target, index, data);
}
static inline void gls_compat_glGetDoublei_v(GLenum target, GLuint index, GLdouble *data)
{
    gls_gl_get_doublei_v(target, index, data);
}
static inline void gls_compat_glGetDoublei_vEXT(GLenum target, GLuint index, GLdouble *data)
{
    gls_gl_get_doublei_v_ext(target, index, data);
}
static inline void gls_compat_glGetDoubleIndexedvEXT(GLenum target, GLuint index, GLdouble *data)
{
    gls_gl_get_double_indexedv_ext(target, index, data);
}
static inline void gls_compat_glGetInteger64v(GLenum pname, GLint64 *data)
{
    gls_gl_get_integer64v(pname, data);
}
static inline void gls_compat_glColorMaskIndexedEXT(GLuint index, GLboolean red, GLboolean green,
                                                    GLboolean blue, GLboolean alpha)
{
    gls_gl_color_mask_indexed_ext(index, red, green, blue, alpha);
}
static inline void gls_compat_glColorMaskiEXT(GLuint index, GLboolean red, GLboolean green,
                                              GLboolean blue, GLboolean alpha)
{
    gls_gl_color_maski_ext(index, red, green, blue, alpha);
}
static inline void gls_compat_glColorMaskiOES(GLuint index, GLboolean red, GLboolean green,
                                              GLboolean blue, GLboolean alpha)
{
    gls_gl_color_maski_oes(index, red, green, blue, alpha);
}
static inline void gls_compat_glClearColorIiEXT(GLint red, GLint green, GLint blue, GLint alpha)
{
    gls_gl_clear_color_ii_ext(red, green, blue, alpha);
}
static inline void gls_compat_glClearColorIuiEXT(GLuint red, GLuint green, GLuint blue, GLuint alpha)
{
    gls_gl_clear_color_iui_ext(red, green, blue, alpha);
}
static inline void gls_compat_glClearColorx(GLint red, GLint green, GLint blue, GLint alpha)
{
    gls_gl_clear_colorx(red, green, blue, alpha);
}
static inline void gls_compat_glClearColorxOES(GLint red, GLint green, GLint blue, GLint alpha)
{
    gls_gl_clear_colorx_oes(red, green, blue, alpha);
}
static inline void gls_compat_glBlitFramebuffer(GLint sx0, GLint sy0, GLint sx1, GLint sy1,
                                                GLint dx0, GLint dy0, GLint dx1, GLint dy1,
                                                GLbitfield mask, GLenum filter)
{
    gls_gl_blit_framebuffer(sx0, sy0, sx1, sy1, dx0, dy0, dx1, dy1, mask, filter);
}
static inline void gls_compat_glFlush(void)
{
    gls_gl_flush();
}
static inline void gls_compat_glFinish(void)
{
    gls_gl_finish();
}
static inline void gls_compat_glClearBufferfv(GLenum buffer, GLint drawbuffer,
                                              const GLfloat *value)
{
    gls_gl_clear_bufferfv(buffer, drawbuffer, value);
}
static inline void gls_compat_glClearBufferiv(GLenum buffer, GLint drawbuffer, const GLint *value)
{
    gls_gl_clear_bufferiv(buffer, drawbuffer, value);
}
static inline void gls_compat_glClearBufferuiv(GLenum buffer, GLint drawbuffer,
                                               const GLuint *value)
{
    gls_gl_clear_bufferuiv(buffer, drawbuffer, value);
}
static inline void gls_compat_glClearNamedFramebufferfv(GLuint framebuffer, GLenum buffer,
                                                        GLint drawbuffer, const GLfloat *value)
{
    gls_gl_clear_named_framebufferfv(framebuffer, buffer, drawbuffer, value);
}
static inline void gls_compat_glClearNamedFramebufferiv(GLuint framebuffer, GLenum buffer,
                                                        GLint drawbuffer, const GLint *value)
{
    gls_gl_clear_named_framebufferiv(framebuffer, buffer, drawbuffer, value);
}
static inline void gls_compat_glClearNamedFramebufferuiv(GLuint framebuffer, GLenum buffer,
                                                         GLint drawbuffer, const GLuint *value)
{
    gls_gl_clear_named_framebufferuiv(framebuffer, buffer, drawbuffer, value);
}
static inline void gls_compat_glClearNamedFramebufferfi(GLuint framebuffer, GLenum buffer,
                                                        GLint drawbuffer, GLfloat depth,
                                                        GLint stencil)
{
    gls_gl_clear_named_framebufferfi(framebuffer, buffer, drawbuffer, depth, stencil);
}
static inline void gls_compat_glNamedFramebufferDrawBuffer(GLuint framebuffer, GLenum buf)
{
    gls_gl_named_framebuffer_draw_buffer(framebuffer, buf);
}
static inline void gls_compat_glNamedFramebufferDrawBuffers(GLuint framebuffer, GLsizei n,
                                                            const GLenum *bufs)
{
    gls_gl_named_framebuffer_draw_buffers(framebuffer, n, bufs);
}
static inline void gls_compat_glNamedFramebufferReadBuffer(GLuint framebuffer, GLenum src)
{
    gls_gl_named_framebuffer_read_buffer(framebuffer, src);
}
static inline void gls_compat_glBlitNamedFramebuffer(GLuint read, GLuint draw, GLint sx0,
                                                     GLint sy0, GLint sx1, GLint sy1, GLint dx0,
                                                     GLint dy0, GLint dx1, GLint dy1,
                                                     GLbitfield mask, GLenum filter)
{
    gls_gl_blit_named_framebuffer(read, draw, sx0, sy0, sx1, sy1, dx0, dy0, dx1, dy1, mask,
                                  filter);
}
static inline void gls_compat_glInvalidateFramebuffer(GLenum target, GLsizei n,
                                                      const GLenum *attachments)
{
    gls_gl_invalidate_framebuffer(target, n, attachments);
}
static inline void gls_compat_glInvalidateSubFramebuffer(GLenum target, GLsizei n,
                                                         const GLenum *attachments, GLint x,
                                                         GLint y, GLsizei width, GLsizei height)
{
    gls_gl_invalidate_sub_framebuffer(target, n, attachments, x, y, width, height);
}
static inline void gls_compat_glInvalidateNamedFramebufferData(GLuint framebuffer, GLsizei n,
                                                               const GLenum *attachments)
{
    gls_gl_invalidate_named_framebuffer_data(framebuffer, n, attachments);
}
static inline void gls_compat_glInvalidateNamedFramebufferSubData(GLuint framebuffer, GLsizei n,
                                                                  const GLenum *attachments,
                                                                  GLint x, GLint y, GLsizei width,
                                                                  GLsizei height)
{
    gls_gl_invalidate_named_framebuffer_sub_data(framebuffer, n, attachments, x, y, width, height);
}
static inline GLenum gls_compat_glCheckNamedFramebufferStatus(GLuint framebuffer, GLenum target)
{
    return gls_gl_check_named_framebuffer_status(framebuffer, target);
}
static inline void gls_compat_glGetNamedFramebufferAttachmentParameteriv(GLuint framebuffer,
                                                                         GLenum attachment,
                                                                         GLenum pname,
                                                                         GLint *params)
{
    gls_gl_get_named_framebuffer_attachment_parameteriv(framebuffer, attachment, pname, params);
}
static inline void gls_compat_glGetNamedFramebufferParameteriv(GLuint framebuffer, GLenum pname,
                                                               GLint *params)
{
    gls_gl_get_named_framebuffer_parameteriv(framebuffer, pname, params);
}
static inline void gls_compat_glGetFramebufferParameteriv(GLenum target, GLenum pname,
                                                          GLint *params)
{
    gls_gl_get_framebuffer_parameteriv(target, pname, params);
}
static inline void gls_compat_glLinkProgram(GLuint program)
{
    gls_gl_link_program(program);
}
static inline GLuint gls_compat_glCreateShaderProgramv(GLenum type, GLsizei count,
                                                       const char *const *strings)
{
    return gls_gl_create_shader_programv(type, count, strings);
}
static inline void gls_compat_glGetProgramiv(GLuint program, GLenum pname, GLint *params)
{
    gls_gl_get_programiv(program, pname, params);
}
static inline void gls_compat_glGetProgramBinary(GLuint program, GLsizei bufSize, GLsizei *length,
                                                 GLenum *binaryFormat, void *binary)
{
    gls_gl_get_program_binary(program, bufSize, length, binaryFormat, binary);
}
static inline void gls_compat_glProgramBinary(GLuint program, GLenum binaryFormat,
                                              const void *binary, GLsizei length)
{
    gls_gl_program_binary(program, binaryFormat, binary, length);
}

#ifdef __cplusplus
}
#endif

#define glXChooseVisual gls_compat_glXChooseVisual
#define glXGetConfig gls_compat_glXGetConfig
#define glXChooseFBConfig gls_compat_glXChooseFBConfig
#define glXGetFBConfigs gls_compat_glXGetFBConfigs
#define glXGetFBConfigAttrib gls_compat_glXGetFBConfigAttrib
#define glXGetVisualFromFBConfig gls_compat_glXGetVisualFromFBConfig
#define glXCreateContext gls_compat_glXCreateContext
#define glXCreateNewContext gls_compat_glXCreateNewContext
#define glXCreateContextAttribsARB gls_compat_glXCreateContextAttribsARB
#define glXDestroyContext gls_compat_glXDestroyContext
#define glXMakeCurrent gls_compat_glXMakeCurrent
#define glXMakeContextCurrent gls_compat_glXMakeContextCurrent
#define glXSwapBuffers gls_compat_glXSwapBuffers
#define glXCreateWindow gls_compat_glXCreateWindow
#define glXDestroyWindow gls_compat_glXDestroyWindow
#define glXCreatePixmap gls_compat_glXCreatePixmap
#define glXCreatePbuffer gls_compat_glXCreatePbuffer
#define glXDestroyPbuffer gls_compat_glXDestroyPbuffer
#define glXDestroyPixmap gls_compat_glXDestroyPixmap
#define glXDestroyGLXPixmap gls_compat_glXDestroyGLXPixmap
#define glXGetProcAddress gls_compat_glXGetProcAddress
#define glXGetProcAddressARB gls_compat_glXGetProcAddress

#define glDrawBuffer gls_compat_glDrawBuffer
#define glDrawBuffers gls_compat_glDrawBuffers
#define glReadBuffer gls_compat_glReadBuffer
#define glGetError gls_compat_glGetError
#define glGetIntegerv gls_compat_glGetIntegerv
#define glGetBooleanv gls_compat_glGetBooleanv
#define glGetFloatv gls_compat_glGetFloatv
#define glGetDoublev gls_compat_glGetDoublev
#define glBindFramebuffer gls_compat_glBindFramebuffer
#define glDeleteFramebuffers gls_compat_glDeleteFramebuffers
#define glDeleteTextures gls_compat_glDeleteTextures
#define glDeleteRenderbuffers gls_compat_glDeleteRenderbuffers
#define glGetFramebufferAttachmentParameteriv gls_compat_glGetFramebufferAttachmentParameteriv
#define glPushAttrib gls_compat_glPushAttrib
#define glPopAttrib gls_compat_glPopAttrib
#define glViewport gls_compat_glViewport
#define glColorMask gls_compat_glColorMask
#define glClear gls_compat_glClear
#define glClearColor gls_compat_glClearColor
#define glColorMaski gls_compat_glColorMaski
#define glGetBooleani_v gls_compat_glGetBooleani_v
#define glGetBooleanIndexedvEXT gls_compat_glGetBooleanIndexedvEXT
#define glGetIntegeri_v gls_compat_glGetIntegeri_v
#define glGetIntegerIndexedvEXT gls_compat_glGetIntegerIndexedvEXT
#define glGetInteger64i_v gls_compat_glGetInteger64i_v
#define glGetFloati_v gls_compat_glGetFloati_v
#define glGetFloati_vEXT gls_compat_glGetFloati_vEXT
#define glGetFloati_vOES gls_compat_glGetFloati_vOES
#define glGetFloatIndexedvEXT gls_compat_glGetFloatIndexedvEXT
#define glGetDoublei_v gls_compat_glGetDoublei_v
#define glGetDoublei_vEXT gls_compat_glGetDoublei_vEXT
#define glGetDoubleIndexedvEXT gls_compat_glGetDoubleIndexedvEXT
#define glGetInteger64v gls_compat_glGetInteger64v
#define glColorMaskIndexedEXT gls_compat_glColorMaskIndexedEXT
#define glColorMaskiEXT gls_compat_glColorMaskiEXT
#define glColorMaskiOES gls_compat_glColorMaskiOES
#define glClearColorIiEXT gls_compat_glClearColorIiEXT
#define glClearColorIuiEXT gls_compat_glClearColorIuiEXT
#define glClearColorx gls_compat_glClearColorx
#define glClearColorxOES gls_compat_glClearColorxOES
#define glBlitFramebuffer gls_compat_glBlitFramebuffer
#define glFlush gls_compat_glFlush
#define glFinish gls_compat_glFinish
#define glClearBufferfv gls_compat_glClearBufferfv
#define glClearBufferiv gls_compat_glClearBufferiv
#define glClearBufferuiv gls_compat_glClearBufferuiv
#define glClearNamedFramebufferfv gls_compat_glClearNamedFramebufferfv
#define glClearNamedFramebufferiv gls_compat_glClearNamedFramebufferiv
#define glClearNamedFramebufferuiv gls_compat_glClearNamedFramebufferuiv
#define glClearNamedFramebufferfi gls_compat_glClearNamedFramebufferfi
#define glNamedFramebufferDrawBuffer gls_compat_glNamedFramebufferDrawBuffer
#define glNamedFramebufferDrawBuffers gls_compat_glNamedFramebufferDrawBuffers
#define glNamedFramebufferReadBuffer gls_compat_glNamedFramebufferReadBuffer
#define glBlitNamedFramebuffer gls_compat_glBlitNamedFramebuffer
#define glInvalidateFramebuffer gls_compat_glInvalidateFramebuffer
#define glInvalidateSubFramebuffer gls_compat_glInvalidateSubFramebuffer
#define glInvalidateNamedFramebufferData gls_compat_glInvalidateNamedFramebufferData
#define glInvalidateNamedFramebufferSubData gls_compat_glInvalidateNamedFramebufferSubData
#define glCheckNamedFramebufferStatus gls_compat_glCheckNamedFramebufferStatus
#define glGetNamedFramebufferAttachmentParameteriv gls_compat_glGetNamedFramebufferAttachmentParameteriv
#define glGetNamedFramebufferParameteriv gls_compat_glGetNamedFramebufferParameteriv
#define glGetFramebufferParameteriv gls_compat_glGetFramebufferParameteriv
#define glLinkProgram gls_compat_glLinkProgram
#define glCreateShaderProgramv gls_compat_glCreateShaderProgramv
#define glGetProgramiv gls_compat_glGetProgramiv
#define glGetProgramBinary gls_compat_glGetProgramBinary
#define glProgramBinary gls_compat_glProgramBinary

#endif /* GLSTEREO_COMPAT_H */

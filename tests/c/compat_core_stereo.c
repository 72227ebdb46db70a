/*
 * glx_core_stereo.c rebuilt from source with <glstereo/compat.h>: the same
 * unchanged core-profile program, its GL and GLX names mapped onto the gls_
 * functions at compile time instead of preloaded, linked with -lglstereo
 * -lGL -lX11.
 */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <glstereo/compat.h>

#include "glx_core_stereo.c"

/*
 * glx_draw_buffers.c rebuilt from source with <glstereo/compat.h>: the same
 * unchanged program, its legacy names mapped onto the gls_ functions at
 * compile time instead of preloaded, linked with -lglstereo -lGL -lX11.
 */
#include <GL/gl.h>
#include <GL/glx.h>
#include <glstereo/compat.h>

#include "glx_draw_buffers.c"

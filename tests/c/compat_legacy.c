/*
 * legacy_stereo.c rebuilt from source with <glstereo/compat.h> (no change
 * to its code), linked with -lglstereo -lGL -lX11: runs without
 * glstereo-run, its output mode from GLSTEREO_MODE.
 */
#include <GL/gl.h>
#include <GL/glx.h>
#include <glstereo/compat.h>

#include "legacy_stereo.c"

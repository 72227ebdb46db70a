/*
 * glstereo/nv3dvision.h: NV_3dvision_settings (OpenGL ES extension #129)
 * for programs running on glstereo. Hand-written; see glstereo.h for the
 * functions it maps to.
 *
 * Include it after (or instead of) <GL/gl.h>. It gives
 *   - the extension's tokens, each defined only when no GL header did;
 *   - glStereoParameterfNV / glStereoParameteriNV, mapped to
 *     gls_stereo_parameterf_nv / gls_stereo_parameteri_nv;
 *   - unless GLSTEREO_NO_GL_OVERRIDES is defined: glEnable, glDisable,
 *     glIsEnabled, glGetBooleanv, glGetIntegerv, glGetFloatv and glGetError
 *     mapped to their gls_ versions, which answer GL_3DVISION_STEREO_NV and
 *     the STEREO_*_NV state (and the emulated stereo framebuffer's state),
 *     report the errors glStereoParameter*NV raise, and pass everything
 *     else to GL. They need a glstereo surface current (gls_make_current).
 *
 * Automatic stereo itself has no legacy name: draw each frame through
 * gls_auto_stereo_frame(draw, user_data) on a surface created with
 * GLS_SURFACE_AUTO_STEREO (see glstereo.h for the contract).
 *
 * What the settings mean here (NVIDIA leaves that to its guides):
 *   GL_STEREO_SEPARATION_NV  percent (0..100) of the maximum separation;
 *                            at 100 far-away geometry is 7% of the viewport
 *                            width apart in the two eyes. Initial 15.
 *   GL_STEREO_CONVERGENCE_NV the depth shown at the screen surface: clip w
 *                            (distance from the camera) for perspective,
 *                            window depth 0..1 for ORTHO. Initial 0.
 *   GL_STEREO_CUTOFF_NV      geometry at this depth or beyond never pops out
 *                            by more than far-away geometry recedes. 0 (the
 *                            initial value) limits nothing.
 *   GL_STEREO_PROJECTION_NV  PERSPECTIVE (initial) or ORTHO for programs
 *                            that project with glOrtho.
 */
#ifndef GLSTEREO_NV3DVISION_H
#define GLSTEREO_NV3DVISION_H

#include <GL/gl.h>

#include "../glstereo.h"

#ifndef GL_NV_3dvision_settings
#define GL_NV_3dvision_settings 1
#endif
#ifndef GL_3DVISION_STEREO_NV
#define GL_3DVISION_STEREO_NV 0x90F4
#endif
#ifndef GL_STEREO_SEPARATION_NV
#define GL_STEREO_SEPARATION_NV 0x90F5
#endif
#ifndef GL_STEREO_CONVERGENCE_NV
#define GL_STEREO_CONVERGENCE_NV 0x90F6
#endif
#ifndef GL_STEREO_CUTOFF_NV
#define GL_STEREO_CUTOFF_NV 0x90F7
#endif
#ifndef GL_STEREO_PROJECTION_NV
#define GL_STEREO_PROJECTION_NV 0x90F8
#endif
#ifndef GL_STEREO_PROJECTION_PERSPECTIVE_NV
#define GL_STEREO_PROJECTION_PERSPECTIVE_NV 0x90F9
#endif
#ifndef GL_STEREO_PROJECTION_ORTHO_NV
#define GL_STEREO_PROJECTION_ORTHO_NV 0x90FA
#endif

/* The extension's entry points. */
#define glStereoParameterfNV gls_stereo_parameterf_nv
#define glStereoParameteriNV gls_stereo_parameteri_nv

#ifndef GLSTEREO_NO_GL_OVERRIDES
#ifndef glEnable
#define glEnable gls_enable
#endif
#ifndef glDisable
#define glDisable gls_disable
#endif
#ifndef glIsEnabled
#define glIsEnabled gls_is_enabled
#endif
#ifndef glGetBooleanv
#define glGetBooleanv gls_get_booleanv
#endif
#ifndef glGetIntegerv
#define glGetIntegerv gls_get_integerv
#endif
#ifndef glGetFloatv
#define glGetFloatv gls_get_floatv
#endif
#ifndef glGetError
#define glGetError gls_get_error
#endif
#endif /* GLSTEREO_NO_GL_OVERRIDES */

#endif /* GLSTEREO_NV3DVISION_H */

/* The scene the period-API examples (starbase.c, irisgl.c) draw in each
 * eye: the RedBlue rectangles (seed 000 §4) and the wireframe paper
 * airplane of the StereoGraphics OGLPlane example (seed 000 §11), a dart
 * pointing along +x, posed a fixed distance in front of the camera and
 * turned so all three axes show depth. Fixed-function GL, header-only, C99. */
#ifndef GLSTEREO_EXAMPLE_SCENE_H
#define GLSTEREO_EXAMPLE_SCENE_H

#include <GL/gl.h>

/* Camera to airplane centre: the plane of zero parallax in the examples. */
#define AIRPLANE_DISTANCE 5.0

/* Multiplies the current matrix (GL_MODELVIEW, after the eye's camera
 * offset) by the airplane's pose and draws it in white. The caller sets the
 * eye's projection. */
static void airplane_draw(void) {
    static const float v[][3] = {
        {1.2f, 0.0f, 0.0f},   /* 0 nose */
        {-0.8f, 0.0f, -0.7f}, /* 1 left wing tip */
        {-0.8f, 0.0f, 0.7f},  /* 2 right wing tip */
        {-0.8f, 0.0f, 0.0f},  /* 3 tail, on the fold */
        {-0.8f, -0.35f, 0.0f} /* 4 bottom of the keel */
    };
    static const int edges[][2] = {{0, 1}, {1, 3}, {0, 2}, {2, 3}, {0, 3}, {0, 4}, {4, 3}};
    glTranslated(0.0, 0.0, -AIRPLANE_DISTANCE);
    glRotatef(35.0f, 0.0f, 1.0f, 0.0f);
    glRotatef(45.0f, 1.0f, 0.0f, 0.0f);
    glColor3f(1.0f, 1.0f, 1.0f);
    glBegin(GL_LINES);
    for (unsigned k = 0; k < sizeof edges / sizeof edges[0]; ++k) {
        glVertex3fv(v[edges[k][0]]);
        glVertex3fv(v[edges[k][1]]);
    }
    glEnd();
}

/* The RedBlue rectangles (seed 000 §4) in normalised device coordinates:
 * blue for the left eye, red for the right. Resets both matrices. */
static void redblue_rectangle(int right_eye) {
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    if (right_eye) {
        glColor3b(127, 0, 0);
        glRectf(-0.2f, -0.2f, 0.8f, 0.8f);
    } else {
        glColor3b(0, 0, 127);
        glRectf(-0.8f, -0.8f, 0.2f, 0.2f);
    }
}

#endif

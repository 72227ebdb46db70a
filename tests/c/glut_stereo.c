/*
 * A GLUT stereo program: glutInitDisplayMode(... | GLUT_STEREO), the
 * RedBlue frame of seed 000 §4 in the display callback, glutSwapBuffers.
 * Unmodified: it knows nothing of glstereo and links only -lglut -lGL.
 * Run it under glstereo-run.
 *
 * After the first frame it prints what GL and GLUT reported and "ready",
 * waits for a line on stdin (the test grabs the window, titled
 * "glut_stereo", meanwhile) and exits 0. Without stereo it says so and
 * exits 2.
 */
#include <stdio.h>
#include <stdlib.h>

#include <GL/glut.h>

static void display(void)
{
    static int frames = 0;

    glDrawBuffer(GL_BACK);
    glClearColor(0.2f, 0.2f, 0.2f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    glDrawBuffer(GL_BACK_LEFT);
    glColor3f(0.0f, 0.0f, 1.0f);
    glRectf(-0.8f, -0.8f, 0.2f, 0.2f);

    glDrawBuffer(GL_BACK_RIGHT);
    glColor3f(1.0f, 0.0f, 0.0f);
    glRectf(-0.2f, -0.2f, 0.8f, 0.8f);

    glutSwapBuffers();
    if (++frames == 1) {
        GLboolean stereo = GL_FALSE;
        glGetBooleanv(GL_STEREO, &stereo);
        printf("gl_stereo %d glut_window_stereo %d error 0x%x\n", stereo,
               glutGet(GLUT_WINDOW_STEREO), glGetError());
        printf("ready\n");
        fflush(stdout);
        char line[64];
        if (fgets(line, sizeof line, stdin) == NULL) {
            /* EOF: exit as well. */
        }
        exit(0);
    }
}

int main(int argc, char **argv)
{
    glutInit(&argc, argv);
    glutInitDisplayMode(GLUT_RGB | GLUT_DOUBLE | GLUT_DEPTH | GLUT_STEREO);
    glutInitWindowSize(160, 120);
    glutInitWindowPosition(0, 0);
    if (!glutGet(GLUT_DISPLAY_MODE_POSSIBLE)) {
        fprintf(stderr, "no stereo visual: GLUT_STEREO is not possible here\n");
        return 2;
    }
    glutCreateWindow("glut_stereo");
    glutDisplayFunc(display);
    glutMainLoop();
    return 0;
}

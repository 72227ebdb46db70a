"""A mono PyOpenGL + freeglut program with a perspective scene and a HUD,
for glstereo-run --auto (tests/auto_clients.rs): fixed function, immediate
mode, the projection set with glFrustum and the HUD drawn under glOrtho,
as legacy programs draw. It never asks for stereo (no GLUT_STEREO).
Run it with Debian's python3 (python3-opengl).

The scene (window 240x160, black), as glfw_depths.c draws it:
  red square   clip w 2 (near), centre (-0.5, 0.3) in NDC, half size 0.15
  green square clip w 4,        centre ( 0,   0.3)
  blue square  clip w 8 (far),  centre ( 0.5, 0.3)
under glFrustum(-1, 1, -1, 1, 1, 100) (w = -z_eye), and
  white bar    (-0.8, -0.8)-(0.8, -0.6) under glOrtho(-1, 1, -1, 1, -1, 1) (w 1).

It draws one frame, swaps, prints "report error E" and "ready", then waits
for a line on stdin (the test grabs the window, titled "pyopengl_depths")
and exits 0 (os._exit: GLUT's main loop never returns).
"""

import os
import sys

from OpenGL import GL, GLUT

W, H = 240, 160
SQUARES = [((1, 0, 0), -0.5, 2.0), ((0, 1, 0), 0.0, 4.0), ((0, 0, 1), 0.5, 8.0)]


def display():
    GL.glViewport(0, 0, W, H)
    GL.glClearColor(0, 0, 0, 1)
    GL.glClear(GL.GL_COLOR_BUFFER_BIT)
    GL.glMatrixMode(GL.GL_PROJECTION)
    GL.glLoadIdentity()
    GL.glFrustum(-1, 1, -1, 1, 1, 100)
    GL.glMatrixMode(GL.GL_MODELVIEW)
    GL.glLoadIdentity()
    for colour, x, w in SQUARES:
        GL.glColor3f(*colour)
        GL.glBegin(GL.GL_QUADS)
        for cx, cy in [(-1, -1), (1, -1), (1, 1), (-1, 1)]:
            GL.glVertex3f((x + 0.15 * cx) * w, (0.3 + 0.15 * cy) * w, -w)
        GL.glEnd()
    GL.glMatrixMode(GL.GL_PROJECTION)
    GL.glLoadIdentity()
    GL.glOrtho(-1, 1, -1, 1, -1, 1)
    GL.glMatrixMode(GL.GL_MODELVIEW)
    GL.glColor3f(1, 1, 1)
    GL.glRectf(-0.8, -0.8, 0.8, -0.6)
    GLUT.glutSwapBuffers()
    print(f"report error 0x{GL.glGetError():x}")
    print("ready", flush=True)
    sys.stdin.readline()
    os._exit(0)


def main():
    GLUT.glutInit(sys.argv)
    GLUT.glutInitDisplayMode(GLUT.GLUT_RGBA | GLUT.GLUT_DOUBLE)
    GLUT.glutInitWindowSize(W, H)
    GLUT.glutInitWindowPosition(0, 0)
    GLUT.glutCreateWindow(b"pyopengl_depths")
    GLUT.glutDisplayFunc(display)
    GLUT.glutMainLoop()


main()

"""A PyOpenGL + freeglut stereo program: glutInitDisplayMode(... |
GLUT_STEREO), each eye drawn with glDrawBuffer(GL_BACK_LEFT / GL_BACK_RIGHT).
Unmodified: PyOpenGL loads libGL and libglut with ctypes (dlopen + dlsym).
Run it under glstereo-run with Debian's python3 (python3-opengl).

It draws the frame of eyes.h (left eye: red, a green square; right eye:
blue, a yellow square) once, prints the back buffers, swaps, prints the
front buffers in eyes.h's format, "report gl_stereo S toolkit_stereo T
error E" (T is glutGet(GLUT_WINDOW_STEREO)) and "ready", then waits for a
line on stdin (the test grabs the window, titled "pyopengl_stereo") and
exits 0 (os._exit: GLUT's main loop never returns). A GL error (PyOpenGL raises GLError) is printed as
"error <what>" and exits 3.
"""

import os
import sys

from OpenGL import GL, GLUT
from OpenGL.error import GLError

W, H = 160, 120
SAMPLES = [(W // 2, H // 2), (W // 4, H * 3 // 4), (W * 3 // 4, H // 4)]


def eye(buffer, background, square, rect):
    GL.glDrawBuffer(buffer)
    GL.glClearColor(*background, 1.0)
    GL.glClear(GL.GL_COLOR_BUFFER_BIT)
    GL.glColor3f(*square)
    GL.glRectf(*rect)


def report(buffer, name):
    GL.glReadBuffer(buffer)
    GL.glPixelStorei(GL.GL_PACK_ALIGNMENT, 1)
    for x, y in SAMPLES:
        data = GL.glReadPixels(x, y, 1, 1, GL.GL_RGBA, GL.GL_UNSIGNED_BYTE)
        r, g, b = bytes(data)[:3]
        print(f"pixel {name} {x} {y} {r} {g} {b}")


def display():
    try:
        GL.glViewport(0, 0, W, H)
        eye(GL.GL_BACK_LEFT, (1, 0, 0), (0, 1, 0), (-0.75, 0.25, -0.25, 0.75))
        eye(GL.GL_BACK_RIGHT, (0, 0, 1), (1, 1, 0), (0.25, -0.75, 0.75, -0.25))
        report(GL.GL_BACK_LEFT, "BACK_LEFT")
        report(GL.GL_BACK_RIGHT, "BACK_RIGHT")
        GLUT.glutSwapBuffers()
        report(GL.GL_FRONT_LEFT, "FRONT_LEFT")
        report(GL.GL_FRONT_RIGHT, "FRONT_RIGHT")
        stereo = GL.glGetBooleanv(GL.GL_STEREO)
        print(
            f"report gl_stereo {int(bool(stereo))} "
            f"toolkit_stereo {GLUT.glutGet(GLUT.GLUT_WINDOW_STEREO)} "
            f"error 0x{GL.glGetError():x}"
        )
    except GLError as e:
        print("error " + " ".join(str(e).split()), flush=True)
        os._exit(3)  # sys.exit does not leave a ctypes callback
    print("ready", flush=True)
    sys.stdin.readline()
    os._exit(0)


def main():
    GLUT.glutInit(sys.argv)
    GLUT.glutInitDisplayMode(GLUT.GLUT_RGBA | GLUT.GLUT_DOUBLE | GLUT.GLUT_STEREO)
    GLUT.glutInitWindowSize(W, H)
    GLUT.glutInitWindowPosition(0, 0)
    if not GLUT.glutGet(GLUT.GLUT_DISPLAY_MODE_POSSIBLE):
        print("no stereo visual: GLUT_STEREO is not possible here", file=sys.stderr)
        sys.exit(2)
    GLUT.glutCreateWindow(b"pyopengl_stereo")
    GLUT.glutDisplayFunc(display)
    GLUT.glutMainLoop()


main()

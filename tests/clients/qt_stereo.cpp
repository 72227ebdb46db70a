/*
 * A Qt 5 stereo program: a QWindow (OpenGLSurface) and a QOpenGLContext
 * with QSurfaceFormat::setStereo(true), GL functions from
 * QOpenGLContext::getProcAddress. Unmodified: it links only Qt5Gui. Run it
 * under glstereo-run.
 *
 * It draws the frame of eyes.h once, prints the back buffers, swaps, prints
 * the front buffers, "report gl_stereo S toolkit_stereo T error E" (T is
 * context.format().stereo()) and "ready", then waits for a line on stdin
 * (the test grabs the window, titled "qt_stereo") and exits 0. Without a
 * context it says why and exits 2.
 */
#include <QGuiApplication>
#include <QOpenGLContext>
#include <QSurfaceFormat>
#include <QWindow>

#include "eyes.h"

static QOpenGLContext *current;

static eyes_proc lookup(const char *name)
{
    return reinterpret_cast<eyes_proc>(current->getProcAddress(name));
}

int main(int argc, char **argv)
{
    const int width = 160, height = 120;
    char line[64];
    QGuiApplication app(argc, argv);
    QSurfaceFormat format;
    format.setStereo(true);
    format.setRenderableType(QSurfaceFormat::OpenGL);
    QWindow window;
    window.setSurfaceType(QSurface::OpenGLSurface);
    window.setFormat(format);
    window.setTitle("qt_stereo");
    window.setGeometry(0, 0, width, height);
    window.show();
    QOpenGLContext context;
    context.setFormat(format);
    if (!context.create() || !context.makeCurrent(&window)) {
        fprintf(stderr, "no stereo context\n");
        return 2;
    }
    for (int i = 0; i < 200 && !window.isExposed(); i++) {
        app.processEvents(QEventLoop::AllEvents, 10);
    }
    current = &context;
    if (!eyes_load(lookup, 0) || !eyes_draw(width, height)) {
        return 1;
    }
    eyes_report_back(width, height);
    context.swapBuffers(&window);
    eyes_report_front(width, height);
    printf("report gl_stereo %d toolkit_stereo %d error 0x%x\n", eyes_gl_stereo(),
           context.format().stereo() ? 1 : 0, eyes_gl.GetError());
    printf("ready\n");
    fflush(stdout);
    if (fgets(line, sizeof line, stdin) == NULL) {
        /* EOF: exit as well. */
    }
    context.doneCurrent();
    return 0;
}

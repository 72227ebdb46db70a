/*
 * A Qt 5 stereo program that reports its keys: the XCB client of
 * tests/keys.rs (glstereo's live keys). Qt's xcb platform reads its events
 * with libxcb itself (xcb_wait_for_event on a reader thread, then
 * xcb_poll_for_queued_event), not through Xlib. As qt_stereo.cpp: a
 * QWindow (OpenGLSurface) and a QOpenGLContext with
 * QSurfaceFormat::setStereo(true), GL functions from
 * QOpenGLContext::getProcAddress, linked only with Qt5Gui. Run it under
 * glstereo-run.
 *
 * It draws the frame of eyes.h at each expose and every 20 ms, prints the
 * first frame's buffers and report as qt_stereo does, then "ready", and for each key event Qt delivers prints
 *   key press|release 0x<Qt::Key> mods 0x<Qt::KeyboardModifiers>
 * (Qt::Key_A 0x41, Qt::Key_F7 0x1000036, Qt::ControlModifier 0x4000000;
 * auto-repeated events are marked "repeat"). Escape ends it (exit 0).
 * Without a stereo context it says why and exits 2.
 */
#include <QGuiApplication>
#include <QKeyEvent>
#include <QOpenGLContext>
#include <QSurfaceFormat>
#include <QTimer>
#include <QWindow>

#include "eyes.h"

static QOpenGLContext *current;

static eyes_proc lookup(const char *name)
{
    return reinterpret_cast<eyes_proc>(current->getProcAddress(name));
}

class KeysWindow : public QWindow
{
public:
    explicit KeysWindow(const QSurfaceFormat &format)
    {
        setSurfaceType(QSurface::OpenGLSurface);
        setFormat(format);
        setTitle("qt_keys");
        setGeometry(0, 0, 160, 120);
    }

    /* Draws and shows a frame; false when GL cannot be set up. */
    bool render()
    {
        if (!isExposed() || !current->makeCurrent(this)) {
            return true;
        }
        if (!loaded) {
            if (!eyes_load(lookup, 0)) {
                return false;
            }
            loaded = true;
        }
        if (!eyes_draw(160, 120)) {
            return false;
        }
        if (!ready) {
            eyes_report_back(160, 120);
        }
        current->swapBuffers(this);
        if (!ready) {
            eyes_report_front(160, 120);
            printf("report gl_stereo %d toolkit_stereo %d error 0x%x\n", eyes_gl_stereo(),
                   current->format().stereo() ? 1 : 0, eyes_gl.GetError());
            printf("ready\n");
            fflush(stdout);
            ready = true;
        }
        return true;
    }

protected:
    void exposeEvent(QExposeEvent *) override
    {
        if (!render()) {
            QGuiApplication::exit(1);
        }
    }

    void keyPressEvent(QKeyEvent *e) override
    {
        say("press", e);
        if (e->key() == Qt::Key_Escape) {
            QGuiApplication::exit(0);
        }
    }

    void keyReleaseEvent(QKeyEvent *e) override
    {
        say("release", e);
    }

private:
    static void say(const char *what, QKeyEvent *e)
    {
        printf("key %s 0x%x mods 0x%x\n", e->isAutoRepeat() ? "repeat" : what,
               static_cast<unsigned>(e->key()), static_cast<unsigned>(e->modifiers()));
        fflush(stdout);
    }

    bool loaded = false;
    bool ready = false;
};

int main(int argc, char **argv)
{
    QGuiApplication app(argc, argv);
    QSurfaceFormat format;
    format.setStereo(true);
    format.setRenderableType(QSurfaceFormat::OpenGL);
    KeysWindow window(format);
    QOpenGLContext context;
    context.setFormat(format);
    if (!context.create()) {
        fprintf(stderr, "no stereo context\n");
        return 2;
    }
    current = &context;
    window.show();
    QTimer timer;
    QObject::connect(&timer, &QTimer::timeout, [&window] {
        if (!window.render()) {
            QGuiApplication::exit(1);
        }
    });
    timer.start(20);
    int status = app.exec();
    context.doneCurrent();
    return status;
}

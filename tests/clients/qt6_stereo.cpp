/*
 * A Qt 6 stereo program, unmodified (links only Qt's libraries; GL through
 * QOpenGLContext). Run it under glstereo-run.
 *
 *   qt6_stereo window   a QWindow (OpenGLSurface) and a QOpenGLContext with
 *                       QSurfaceFormat::setStereo(true), drawing with a
 *                       QOpenGLShaderProgram whose shaders go through Qt's
 *                       shader disk cache (addCacheableShaderFromSourceCode:
 *                       program binaries, in $XDG_CACHE_HOME). The frame:
 *                       under GL_BACK a full-window quad, magenta; under
 *                       GL_BACK_LEFT a green square at (-0.75,0.25)-(-0.25,0.75);
 *                       under GL_BACK_RIGHT a yellow one at
 *                       (0.25,-0.75)-(0.75,-0.25). It prints "pixel BUFFER X Y
 *                       R G B" for the back buffers at the centre and the two
 *                       squares' centres, swaps, prints the front buffers,
 *                       then "report gl_stereo S toolkit_stereo T error E".
 *   qt6_stereo widget   a QOpenGLWidget filling a top-level window, stereo
 *                       (QSurfaceFormat::setDefaultFormat): paintGL clears
 *                       the widget green and prints "paint gl_stereo S
 *                       gl_doublebuffer D fbo_bound B" (what GL says while
 *                       Qt's framebuffer object is bound for drawing), then
 *                       "report toolkit_stereo T error E".
 *
 * Both print "ready", then wait for a line on stdin (the test grabs the
 * window, titled "qt6 stereo window" or "qt6 stereo widget": not the
 * program's name, which Qt also gives an unmapped leader window, that
 * XGetImage cannot read) and exit 0; 2 when there is no context.
 */
#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QGuiApplication>
#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <QOpenGLFunctions>
#include <QOpenGLShaderProgram>
#include <QOpenGLWidget>
#include <QSurfaceFormat>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>
#include <QWidget>
#include <QWindow>

#include <cstdio>
#include <cstring>

static const int width = 160, height = 120;

#ifndef GL_BACK_LEFT
#define GL_BACK_LEFT 0x0402
#define GL_BACK_RIGHT 0x0403
#define GL_FRONT_LEFT 0x0400
#define GL_FRONT_RIGHT 0x0401
#endif
#ifndef GL_STEREO
#define GL_STEREO 0x0C33
#endif
#ifndef GL_DOUBLEBUFFER
#define GL_DOUBLEBUFFER 0x0C32
#endif

typedef void (*DrawBufferFn)(GLenum);

static void wait_line()
{
    char line[64];
    printf("ready\n");
    fflush(stdout);
    if (fgets(line, sizeof line, stdin) == nullptr) {
        /* EOF: exit as well. */
    }
}

static void report(QOpenGLFunctions *f, DrawBufferFn read_buffer, GLenum buffer, const char *name)
{
    const int points[3][2] = {{width / 2, height / 2}, {width / 4, height * 3 / 4}, {width * 3 / 4, height / 4}};
    read_buffer(buffer);
    f->glPixelStorei(GL_PACK_ALIGNMENT, 1);
    for (const auto &p : points) {
        unsigned char px[4] = {0, 0, 0, 0};
        f->glReadPixels(p[0], p[1], 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
        printf("pixel %s %d %d %u %u %u\n", name, p[0], p[1], px[0], px[1], px[2]);
    }
}

static int run_window(int argc, char **argv)
{
    QGuiApplication app(argc, argv);
    QSurfaceFormat format;
    format.setStereo(true);
    format.setRenderableType(QSurfaceFormat::OpenGL);
    QWindow window;
    window.setSurfaceType(QSurface::OpenGLSurface);
    window.setFormat(format);
    window.setTitle("qt6 stereo window");
    window.setGeometry(0, 0, width, height);
    window.show();
    QOpenGLContext context;
    context.setFormat(format);
    if (!context.create() || !context.makeCurrent(&window)) {
        fprintf(stderr, "no stereo context\n");
        return 2;
    }
    QElapsedTimer waited;
    waited.start();
    while (!window.isExposed() && waited.elapsed() < 60000) {
        app.processEvents(QEventLoop::AllEvents, 10);
        QThread::msleep(5);
    }
    QOpenGLFunctions *f = context.functions();
    auto draw_buffer = reinterpret_cast<DrawBufferFn>(context.getProcAddress("glDrawBuffer"));
    auto read_buffer = reinterpret_cast<DrawBufferFn>(context.getProcAddress("glReadBuffer"));
    if (draw_buffer == nullptr || read_buffer == nullptr) {
        fprintf(stderr, "no glDrawBuffer\n");
        return 1;
    }
    QOpenGLShaderProgram program;
    program.addCacheableShaderFromSourceCode(QOpenGLShader::Vertex,
                                             "#version 130\n"
                                             "in vec2 pos;\n"
                                             "void main() { gl_Position = vec4(pos, 0.0, 1.0); }\n");
    program.addCacheableShaderFromSourceCode(QOpenGLShader::Fragment,
                                             "#version 130\n"
                                             "uniform vec4 tint;\n"
                                             "out vec4 color;\n"
                                             "void main() { color = tint; }\n");
    program.bindAttributeLocation("pos", 0);
    if (!program.link()) {
        fprintf(stderr, "the program does not link: %s\n", qPrintable(program.log()));
        return 1;
    }
    program.bind();
    static const GLfloat quads[] = {
        -1.0f,  -1.0f, 1.0f,  -1.0f, -1.0f,  1.0f,  1.0f,  1.0f,  /* the window */
        -0.75f, 0.25f, -0.25f, 0.25f, -0.75f, 0.75f, -0.25f, 0.75f, /* left square */
        0.25f, -0.75f, 0.75f, -0.75f, 0.25f, -0.25f, 0.75f,  -0.25f /* right square */
    };
    f->glBindBuffer(GL_ARRAY_BUFFER, 0);
    f->glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, quads);
    f->glEnableVertexAttribArray(0);
    f->glViewport(0, 0, width, height);
    draw_buffer(GL_BACK);
    f->glClearColor(0, 0, 0, 1);
    f->glClear(GL_COLOR_BUFFER_BIT);
    program.setUniformValue("tint", 1.0f, 0.0f, 1.0f, 1.0f);
    f->glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    draw_buffer(GL_BACK_LEFT);
    program.setUniformValue("tint", 0.0f, 1.0f, 0.0f, 1.0f);
    f->glDrawArrays(GL_TRIANGLE_STRIP, 4, 4);
    draw_buffer(GL_BACK_RIGHT);
    program.setUniformValue("tint", 1.0f, 1.0f, 0.0f, 1.0f);
    f->glDrawArrays(GL_TRIANGLE_STRIP, 8, 4);
    report(f, read_buffer, GL_BACK_LEFT, "BACK_LEFT");
    report(f, read_buffer, GL_BACK_RIGHT, "BACK_RIGHT");
    context.swapBuffers(&window);
    report(f, read_buffer, GL_FRONT_LEFT, "FRONT_LEFT");
    report(f, read_buffer, GL_FRONT_RIGHT, "FRONT_RIGHT");
    GLboolean stereo = GL_FALSE;
    f->glGetBooleanv(GL_STEREO, &stereo);
    printf("report gl_stereo %d toolkit_stereo %d error 0x%x\n", stereo == GL_TRUE ? 1 : 0,
           context.format().stereo() ? 1 : 0, f->glGetError());
    wait_line();
    context.doneCurrent();
    return 0;
}

/* Clears itself green and says what GL reports while Qt's framebuffer
 * object is bound. */
class Widget : public QOpenGLWidget
{
public:
    bool painted = false;

protected:
    void paintGL() override
    {
        QOpenGLFunctions *f = context()->functions();
        GLboolean stereo = 7, doublebuffer = 7;
        GLint fbo = -1;
        f->glGetBooleanv(GL_STEREO, &stereo);
        f->glGetBooleanv(GL_DOUBLEBUFFER, &doublebuffer);
        f->glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fbo);
        if (!painted) {
            printf("paint gl_stereo %d gl_doublebuffer %d fbo_bound %d\n", stereo, doublebuffer,
                   fbo != 0 && GLuint(fbo) == defaultFramebufferObject() ? 1 : 0);
        }
        f->glClearColor(0, 1, 0, 1);
        f->glClear(GL_COLOR_BUFFER_BIT);
        painted = true;
    }
};

static int run_widget(int argc, char **argv)
{
    QSurfaceFormat format;
    format.setStereo(true);
    format.setRenderableType(QSurfaceFormat::OpenGL);
    QSurfaceFormat::setDefaultFormat(format);
    QApplication app(argc, argv);
    QWidget top;
    top.setWindowTitle("qt6 stereo widget");
    auto *layout = new QVBoxLayout(&top);
    layout->setContentsMargins(0, 0, 0, 0);
    auto *widget = new Widget;
    layout->addWidget(widget);
    bool swapped = false;
    QEventLoop shown;
    QObject::connect(widget, &QOpenGLWidget::frameSwapped, [&swapped, &shown] {
        swapped = true;
        shown.quit();
    });
    /* Until Qt has composed the widget into the window and swapped (at
     * most 60 s: a loaded machine). */
    QTimer::singleShot(60000, &shown, &QEventLoop::quit);
    top.setGeometry(0, 0, width, height);
    top.show();
    if (!swapped) shown.exec();
    if (!swapped || !widget->painted || widget->context() == nullptr) {
        fprintf(stderr, "the widget was not painted and shown\n");
        return 2;
    }
    widget->makeCurrent();
    printf("report toolkit_stereo %d error 0x%x\n", widget->format().stereo() ? 1 : 0,
           widget->context()->functions()->glGetError());
    widget->doneCurrent();
    wait_line();
    return 0;
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "widget") == 0) {
        return run_widget(argc, argv);
    }
    if (argc > 1 && strcmp(argv[1], "window") == 0) {
        return run_window(argc, argv);
    }
    fprintf(stderr, "usage: qt6_stereo window|widget\n");
    return 1;
}

/*
 * A mono Qt 5 QOpenGLWidget program with a perspective scene and a HUD, for
 * glstereo-run --auto (tests/auto_clients.rs). It never asks for stereo.
 * QOpenGLWidget renders into a framebuffer object of Qt's and Qt then
 * draws that texture into the window (render to texture, then a textured
 * quad): the path of many toolkits and engines.
 *
 * The scene (widget 240x160 filling its window, black), as glfw_depths.c
 * draws it, with a QOpenGLShaderProgram (gl_Position = u_matrix *
 * position) and the matrices from QMatrix4x4:
 *   red square   clip w 2 (near), centre (-0.5, 0.3) in NDC, half size 0.15
 *   green square clip w 4,        centre ( 0,   0.3)
 *   blue square  clip w 8 (far),  centre ( 0.5, 0.3)
 * under QMatrix4x4::frustum(-1, 1, -1, 1, 1, 100) (w = -z_eye), and
 *   white bar    (-0.8, -0.8)-(0.8, -0.6) under the identity (w 1: a HUD).
 *
 * Once Qt has composed the widget into the window and swapped, it prints
 * "report error E" and "ready", then waits for a line on stdin (the test
 * grabs the window, titled "qt5 depths") and exits 0; 2 when the widget
 * was not shown.
 *
 *   qt5_depths [egl]      egl: Qt's EGL integration on X11
 *                         (QT_XCB_GL_INTEGRATION=xcb_egl) instead of GLX
 */
#include <QApplication>
#include <QEventLoop>
#include <QMatrix4x4>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QOpenGLShaderProgram>
#include <QOpenGLWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <QVector>
#include <QWidget>

#include <cstdio>
#include <cstring>

static const int width = 240, height = 160;

class Scene : public QOpenGLWidget
{
public:
    bool painted = false;

protected:
    void initializeGL() override
    {
        program.addShaderFromSourceCode(QOpenGLShader::Vertex,
                                        "attribute vec3 position;\n"
                                        "uniform mat4 u_matrix;\n"
                                        "void main() { gl_Position = u_matrix * vec4(position, 1.0); }\n");
        program.addShaderFromSourceCode(QOpenGLShader::Fragment,
                                        "uniform vec4 u_colour;\n"
                                        "void main() { gl_FragColor = u_colour; }\n");
        program.bindAttributeLocation("position", 0);
        if (!program.link()) {
            fprintf(stderr, "the program does not link: %s\n", qPrintable(program.log()));
        }
    }

    void paintGL() override
    {
        QOpenGLFunctions *f = context()->functions();
        f->glClearColor(0, 0, 0, 1);
        f->glClear(GL_COLOR_BUFFER_BIT);
        program.bind();
        QMatrix4x4 frustum;
        frustum.frustum(-1, 1, -1, 1, 1, 100);
        struct Square {
            QColor colour;
            float x, w;
        };
        const Square squares[] = {{Qt::red, -0.5f, 2}, {Qt::green, 0, 4}, {Qt::blue, 0.5f, 8}};
        program.setUniformValue("u_matrix", frustum);
        for (const Square &s : squares) {
            draw(f, s.colour, (s.x - 0.15f) * s.w, (0.3f - 0.15f) * s.w, (s.x + 0.15f) * s.w,
                 (0.3f + 0.15f) * s.w, -s.w);
        }
        program.setUniformValue("u_matrix", QMatrix4x4());
        draw(f, Qt::white, -0.8f, -0.8f, 0.8f, -0.6f, 0);
        program.release();
        painted = true;
    }

private:
    QOpenGLShaderProgram program;

    /* The rectangle (x0, y0)-(x1, y1) at z, from a client array. */
    void draw(QOpenGLFunctions *f, const QColor &colour, float x0, float y0, float x1, float y1,
              float z)
    {
        const GLfloat v[] = {x0, y0, z, x1, y0, z, x0, y1, z, x1, y1, z};
        program.setUniformValue("u_colour", colour);
        f->glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, v);
        f->glEnableVertexAttribArray(0);
        f->glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        f->glDisableVertexAttribArray(0);
    }
};

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "egl") == 0) {
        qputenv("QT_XCB_GL_INTEGRATION", "xcb_egl");
    }
    QApplication app(argc, argv);
    QWidget top;
    top.setWindowTitle("qt5 depths");
    auto *layout = new QVBoxLayout(&top);
    layout->setContentsMargins(0, 0, 0, 0);
    auto *scene = new Scene;
    layout->addWidget(scene);
    bool swapped = false;
    QEventLoop shown;
    QObject::connect(scene, &QOpenGLWidget::frameSwapped, [&swapped, &shown] {
        swapped = true;
        shown.quit();
    });
    /* Until Qt has composed the widget into the window and swapped (at
     * most 60 s: a loaded machine). */
    QTimer::singleShot(60000, &shown, &QEventLoop::quit);
    top.setGeometry(0, 0, width, height);
    top.show();
    if (!swapped) {
        shown.exec();
    }
    if (!swapped || !scene->painted || scene->context() == nullptr) {
        fprintf(stderr, "the widget was not painted and shown\n");
        return 2;
    }
    scene->makeCurrent();
    printf("report error 0x%x\n", scene->context()->functions()->glGetError());
    scene->doneCurrent();
    printf("ready\n");
    fflush(stdout);
    char line[64];
    if (fgets(line, sizeof line, stdin) == nullptr) {
        /* EOF: exit as well. */
    }
    return 0;
}

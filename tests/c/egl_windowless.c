/*
 * An OpenGL ES program on an EGL display with no windows: Mesa's
 * surfaceless platform or an EGL device (where VirtualGL's `vglrun -d egl`
 * renders). It draws into a framebuffer object of its own (left half
 * red, right half blue, a green square in the middle) and prints what it
 * reads back, then its framebuffer's status and GL error. Under
 * `glstereo-run --auto` every line is what Mesa answers without the
 * layer: such a context has no frame to show, so it stays mono.
 *
 *   egl_windowless surfaceless|device
 */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <stdio.h>
#include <string.h>

#define W 64
#define H 48

static EGLDisplay open_display(const char *how)
{
    if (strcmp(how, "surfaceless") == 0)
        return eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    PFNEGLQUERYDEVICESEXTPROC query_devices =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    EGLDeviceEXT devices[8];
    EGLint n = 0;
    if (query_devices == NULL || !query_devices(8, devices, &n) || n < 1)
        return EGL_NO_DISPLAY;
    return eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], NULL);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: egl_windowless surfaceless|device\n");
        return 2;
    }
    EGLDisplay dpy = open_display(argv[1]);
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL)) {
        printf("no %s display (EGL error 0x%x)\n", argv[1], eglGetError());
        return 1;
    }
    static const EGLint want[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                  EGL_OPENGL_ES3_BIT, EGL_NONE};
    EGLConfig config;
    EGLint n = 0;
    if (!eglChooseConfig(dpy, want, &config, 1, &n) || n != 1) {
        printf("no ES 3 configuration\n");
        return 1;
    }
    eglBindAPI(EGL_OPENGL_ES_API);
    static const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attrs);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        printf("no context (EGL error 0x%x)\n", eglGetError());
        return 1;
    }
    GLuint fb, rb;
    glGenFramebuffers(1, &fb);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    glBindFramebuffer(GL_FRAMEBUFFER, fb);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    printf("framebuffer %u status 0x%x\n", fb, glCheckFramebufferStatus(GL_FRAMEBUFFER));
    glViewport(0, 0, W, H);
    glEnable(GL_SCISSOR_TEST);
    static const float colours[3][4] = {{1, 0, 0, 1}, {0, 0, 1, 1}, {0, 1, 0, 1}};
    static const int boxes[3][4] = {{0, 0, W / 2, H}, {W / 2, 0, W / 2, H}, {24, 16, 16, 16}};
    for (int i = 0; i < 3; i++) {
        glScissor(boxes[i][0], boxes[i][1], boxes[i][2], boxes[i][3]);
        glClearColor(colours[i][0], colours[i][1], colours[i][2], colours[i][3]);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    glDisable(GL_SCISSOR_TEST);
    static unsigned char pixels[W * H * 4];
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    static const int at[][2] = {{0, 0}, {W - 1, H - 1}, {W / 2 - 1, 5}, {W / 2, 5}, {32, 24}};
    for (unsigned i = 0; i < sizeof at / sizeof at[0]; i++) {
        const unsigned char *p = pixels + 4 * (at[i][1] * W + at[i][0]);
        printf("pixel %d,%d: %u %u %u %u\n", at[i][0], at[i][1], p[0], p[1], p[2], p[3]);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fb);
    glDeleteRenderbuffers(1, &rb);
    printf("error 0x%x\n", glGetError());
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    printf("done\n");
    return 0;
}

/*
 * A legacy GLX stereo program that draws only when asked, as event-driven
 * viewers do, and reads its X events with Xlib: the client of tests/keys.rs
 * (glstereo's live keys). Unmodified: it knows nothing of glstereo and links
 * only -lGL -lX11 (and -lXi). Run it under glstereo-run.
 *
 *   keys_stereo [stereo|mono] [next|check] [core|xi2]
 *
 * It opens a 160x120 window titled "keys_stereo" at (0, 0) with a stereo
 * visual (with "mono", a plain double-buffered one), waits for it to be
 * mapped (XIfEvent), draws and swaps, prints "ready 0x<window>" and then
 * reads events until Escape is pressed:
 *   next   XNextEvent, blocking (the default);
 *   check  XPending, then XCheckWindowEvent / XCheckTypedEvent (a polling
 *          loop that sleeps 5 ms when nothing is queued).
 * Its keys come as core KeyPress / KeyRelease events, or with "xi2" as
 * XInput 2 XI_KeyPress / XI_KeyRelease events of the master keyboard
 * (XISelectEvents; as GTK 3 takes its keys).
 * Each Expose (the last of a series) redraws and swaps, and prints
 * "expose"; each MappingNotify refreshes Xlib's keyboard map; each key
 * press or release prints
 *   key press|release <keysym name> state 0x<state>
 * (the keysym of the key's first column, as XLookupKeysym gives it; for
 * XInput 2, XkbKeycodeToKeysym and the effective modifiers).
 *
 * The frame: left eye (GL_BACK_LEFT) red with a green square in its top
 * left quarter, right eye (GL_BACK_RIGHT) blue with a yellow square in its
 * bottom right quarter; mono: the left eye's picture in GL_BACK. Without a
 * stereo visual it says so on stderr and exits 2.
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/XKBlib.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XInput2.h>
#include <X11/keysym.h>

enum { WIDTH = 160, HEIGHT = 120 };

static void eye(GLenum buffer, float r, float g, float b, float sr, float sg, float sb, int x,
                int y)
{
    glDrawBuffer(buffer);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(r, g, b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x, y, WIDTH / 2, HEIGHT / 2);
    glClearColor(sr, sg, sb, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
}

static void draw(Display *dpy, Window win, int stereo)
{
    glViewport(0, 0, WIDTH, HEIGHT);
    /* Rows count from the bottom in GL: the top-left quarter starts at
     * (0, HEIGHT / 2), the bottom-right one at (WIDTH / 2, 0). */
    eye(stereo ? GL_BACK_LEFT : GL_BACK, 1, 0, 0, 0, 1, 0, 0, HEIGHT / 2);
    if (stereo) {
        eye(GL_BACK_RIGHT, 0, 0, 1, 1, 1, 0, WIDTH / 2, 0);
    }
    glXSwapBuffers(dpy, win);
}

static Bool mapped(Display *dpy, XEvent *ev, XPointer arg)
{
    (void)dpy;
    return ev->type == MapNotify && ev->xmap.window == *(Window *)arg;
}

/* XInput's major opcode, when its key events are selected. */
static int xi_opcode = -1;

static int say_key(int press, KeySym sym, unsigned state)
{
    const char *name = XKeysymToString(sym);
    printf("key %s %s state 0x%x\n", press ? "press" : "release", name ? name : "NoSymbol", state);
    fflush(stdout);
    return press && sym == XK_Escape;
}

/* Prints the event; 1 when it was the press of Escape. */
static int report(Display *dpy, Window win, XEvent *ev, int stereo)
{
    if (ev->type == GenericEvent && ev->xcookie.extension == xi_opcode &&
        XGetEventData(dpy, &ev->xcookie)) {
        XIDeviceEvent *d = ev->xcookie.data;
        int escape = 0;
        if (d->evtype == XI_KeyPress || d->evtype == XI_KeyRelease) {
            escape = say_key(d->evtype == XI_KeyPress,
                             XkbKeycodeToKeysym(dpy, (KeyCode)d->detail, 0, 0),
                             (unsigned)d->mods.effective);
        }
        XFreeEventData(dpy, &ev->xcookie);
        return escape;
    }
    if (ev->type == Expose && ev->xexpose.count == 0) {
        draw(dpy, win, stereo);
        printf("expose\n");
    } else if (ev->type == MappingNotify) {
        XRefreshKeyboardMapping(&ev->xmapping);
    } else if (ev->type == KeyPress || ev->type == KeyRelease) {
        return say_key(ev->type == KeyPress, XLookupKeysym(&ev->xkey, 0), ev->xkey.state);
    }
    fflush(stdout);
    return 0;
}

int main(int argc, char **argv)
{
    int stereo = !(argc > 1 && strcmp(argv[1], "mono") == 0);
    int check = argc > 2 && strcmp(argv[2], "check") == 0;
    int xi2 = argc > 3 && strcmp(argv[3], "xi2") == 0;
    const long mask =
        (xi2 ? 0 : KeyPressMask | KeyReleaseMask) | ExposureMask | StructureNotifyMask;
    int attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 1, GLX_GREEN_SIZE, 1,
                     GLX_BLUE_SIZE, 1, GLX_STEREO, None};
    Display *dpy = XOpenDisplay(NULL);
    if (dpy == NULL) {
        fprintf(stderr, "cannot open the X display\n");
        return 1;
    }
    if (!stereo) {
        attribs[8] = None;
    }
    XVisualInfo *vis = glXChooseVisual(dpy, DefaultScreen(dpy), attribs);
    if (vis == NULL) {
        fprintf(stderr, "no %s visual\n", stereo ? "stereo" : "double-buffered");
        return 2;
    }
    Window root = RootWindow(dpy, vis->screen);
    XSetWindowAttributes wa;
    memset(&wa, 0, sizeof wa);
    wa.colormap = XCreateColormap(dpy, root, vis->visual, AllocNone);
    wa.event_mask = mask;
    Window win = XCreateWindow(dpy, root, 0, 0, WIDTH, HEIGHT, 0, vis->depth, InputOutput,
                               vis->visual, CWColormap | CWEventMask, &wa);
    XStoreName(dpy, win, "keys_stereo");
    if (xi2) {
        int event, error, major = 2, minor = 0;
        unsigned char bits[XIMaskLen(XI_LASTEVENT)];
        XIEventMask keys;
        if (!XQueryExtension(dpy, "XInputExtension", &xi_opcode, &event, &error) ||
            XIQueryVersion(dpy, &major, &minor) != Success) {
            fprintf(stderr, "no XInput 2\n");
            return 1;
        }
        memset(bits, 0, sizeof bits);
        XISetMask(bits, XI_KeyPress);
        XISetMask(bits, XI_KeyRelease);
        keys.deviceid = XIAllMasterDevices;
        keys.mask_len = sizeof bits;
        keys.mask = bits;
        XISelectEvents(dpy, win, &keys, 1);
    }
    XMapWindow(dpy, win);
    XEvent ev;
    XIfEvent(dpy, &ev, mapped, (XPointer)&win);
    GLXContext ctx = glXCreateContext(dpy, vis, NULL, True);
    if (ctx == NULL || !glXMakeCurrent(dpy, win, ctx)) {
        fprintf(stderr, "cannot make a GL context current\n");
        return 1;
    }
    draw(dpy, win, stereo);
    printf("ready 0x%lx\n", (unsigned long)win);
    fflush(stdout);
    for (;;) {
        if (check) {
            struct timespec nap = {0, 5000000};
            if (XPending(dpy) == 0) {
                nanosleep(&nap, NULL);
                continue;
            }
            if (!XCheckWindowEvent(dpy, win, mask, &ev) &&
                !XCheckTypedEvent(dpy, MappingNotify, &ev)) {
                /* Something else of no interest (ClientMessage...). */
                XNextEvent(dpy, &ev);
            }
        } else {
            XNextEvent(dpy, &ev);
        }
        if (report(dpy, win, &ev, stereo)) {
            break;
        }
    }
    glXMakeCurrent(dpy, None, NULL);
    glXDestroyContext(dpy, ctx);
    XDestroyWindow(dpy, win);
    XFree(vis);
    XCloseDisplay(dpy);
    return 0;
}

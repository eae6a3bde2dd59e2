/* SPDX-License-Identifier: Apache-2.0
 * tests/data/glprogs/glprog_window.h — the window every GL program of ours draws in (issue 37): an X window with an
 * RGBA, double-buffered visual and a 24-bit depth buffer, a GLX context made current, and the teardown. Plain
 * Xlib + GLX 1.x, as an unmodified GL 1.x program of the time would do it; the programs' GL calls are their own. */
#ifndef GLPROG_WINDOW_H
#define GLPROG_WINDOW_H

#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <stdio.h>

struct glprog {
  Display* dpy;
  Window win;
  GLXContext ctx;
};

/* Opens a w x h window, waits until it is mapped and makes a context current; 0 on success, else 1 after one line
 * on stderr naming the program. */
static inline int glprog_open(struct glprog* g, const char* name, int w, int h) {
  g->dpy = XOpenDisplay(NULL);
  if (!g->dpy) { fprintf(stderr, "%s: cannot open the X display\n", name); return 1; }
  int attrs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8, GLX_DEPTH_SIZE, 24, None};
  XVisualInfo* vi = glXChooseVisual(g->dpy, DefaultScreen(g->dpy), attrs);
  if (!vi) { fprintf(stderr, "%s: no RGBA double-buffered visual with a 24-bit depth buffer\n", name); return 1; }
  XSetWindowAttributes swa = {0};
  swa.colormap = XCreateColormap(g->dpy, RootWindow(g->dpy, vi->screen), vi->visual, AllocNone);
  swa.event_mask = StructureNotifyMask;
  g->win = XCreateWindow(g->dpy, RootWindow(g->dpy, vi->screen), 0, 0, (unsigned)w, (unsigned)h, 0, vi->depth,
                         InputOutput, vi->visual, CWColormap | CWEventMask, &swa);
  XMapWindow(g->dpy, g->win);
  for (XEvent e;;) { XNextEvent(g->dpy, &e); if (e.type == MapNotify) break; }
  g->ctx = glXCreateContext(g->dpy, vi, NULL, True);
  glXMakeCurrent(g->dpy, g->win, g->ctx);
  return 0;
}

static inline void glprog_close(struct glprog* g) {
  glXMakeCurrent(g->dpy, None, NULL);
  glXDestroyContext(g->dpy, g->ctx);
  XDestroyWindow(g->dpy, g->win);
  XCloseDisplay(g->dpy);
}

#endif

/* SPDX-License-Identifier: Apache-2.0
 * shadecore — a GL 1.x test program for `shadecore replay` (docs/replay.md "Depth test off and glDepthMask", issue 37):
 * the depth state changing between the draws of one frame. Four balls, in this order: a far one (depth test and writes
 * on); a near one drawn with glDepthMask(GL_FALSE) (tested, writes no depth); a farther one overlapping it, drawn with
 * the mask on (GL draws it over the near one, whose depth was never written); a farthest one drawn with GL_DEPTH_TEST
 * off (drawn over everything it covers, writing no depth); then a small ball with the test on again, placed behind
 * the third ball's depth but in front of the farthest one's, where they overlap (it fails where the third ball wrote
 * depth, and shows elsewhere). One directional light, smooth shading, back faces culled. Plain GLX (libGL, libX11), a
 * fixed number of frames:
 *   cc -O2 -o depthstate depthstate.c -lGL -lX11 -lm
 *   LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 640x480x24" apitrace trace -o depthstate.trace ./depthstate */
#include "glprog_window.h"
#include <math.h>
#include <stdio.h>

enum { W = 420, H = 240, FRAMES = 20, STACKS = 14, SLICES = 22 };
static const double PI = 3.14159265358979323846;

/* A ball of radius 1 in immediate mode; with `coloured`, a colour per vertex (by latitude and longitude). */
static void ball(int coloured) {
  for (int i = 0; i < STACKS; ++i) {
    glBegin(GL_TRIANGLE_STRIP);
    for (int j = 0; j <= SLICES; ++j)
      for (int k = 0; k < 2; ++k) {
        const double th = PI * (i + 1 - k) / STACKS, ph = 2 * PI * j / SLICES;  /* counter-clockwise outside */
        const double n[3] = {sin(th) * cos(ph), cos(th), sin(th) * sin(ph)};
        if (coloured) glColor3d(0.5 + 0.4 * cos(th), 0.5 + 0.35 * sin(2 * ph), 0.45 + 0.3 * sin(th));
        glNormal3d(n[0], n[1], n[2]);
        glVertex3d(n[0], n[1], n[2]);
      }
    glEnd();
  }
}

static void coloured(float r, float g, float b) {
  const GLfloat c[4] = {r, g, b, 1};
  glMaterialfv(GL_FRONT, GL_AMBIENT_AND_DIFFUSE, c);
}

static void at(double x, double y, double z, double s, double spin) {
  glPushMatrix();
  glTranslated(x, y, z);
  glScaled(s, s, s);
  glRotated(spin, 0, 1, 0);
  ball(0);
  glPopMatrix();
}

static void draw(int frame) {
  const double t = 0.3 * frame;
  glClearColor(0.02f, 0.03f, 0.05f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  const GLfloat dir0[4] = {(GLfloat)(0.5 * cos(t)), 0.6f, 0.8f, 0}, spec[4] = {0.6f, 0.6f, 0.6f, 1};
  glLightfv(GL_LIGHT0, GL_POSITION, dir0);
  glEnable(GL_LIGHT0);
  glEnable(GL_NORMALIZE);  /* the balls are scaled */
  glMaterialfv(GL_FRONT, GL_SPECULAR, spec);
  glMaterialf(GL_FRONT, GL_SHININESS, 40);

  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  coloured(0.3f, 0.8f, 0.4f);
  at(-2.6, 0.3, -9, 1.4, 10 * t);  /* far, left: test and writes on */

  glDepthMask(GL_FALSE);
  coloured(0.9f, 0.3f, 0.25f);
  at(-1.0, 0, -4.5, 0.9, 12 * t);  /* near: tested, no depth written */

  glDepthMask(GL_TRUE);
  coloured(0.3f, 0.45f, 0.95f);
  at(0.2, -0.1, -6.5, 1.1, -8 * t);  /* farther, overlapping the near one: drawn over it */

  glDisable(GL_DEPTH_TEST);
  coloured(0.95f, 0.85f, 0.3f);
  at(1.9 + 0.2 * sin(t), 0.4, -10, 1.6, 6 * t);  /* farthest, test off: drawn over the blue one */

  glEnable(GL_DEPTH_TEST);
  coloured(0.8f, 0.4f, 0.9f);
  at(1.15, 0.2, -7.6, 0.55, 0);  /* between the blue and the yellow in depth: fails only where blue wrote depth */
}

int main(void) {
  struct glprog g;
  if (glprog_open(&g, "depthstate", W, H)) return 1;

  glViewport(0, 0, W, H);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(-0.84, 0.84, -0.48, 0.48, 1.5, 30);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_LIGHTING);
  const GLfloat s[4] = {1, 1, 1, 1};
  glLightfv(GL_LIGHT1, GL_SPECULAR, s);
  glLightf(GL_LIGHT1, GL_CONSTANT_ATTENUATION, 0.6f);
  glLightf(GL_LIGHT1, GL_LINEAR_ATTENUATION, 0.15f);

  for (int f = 0; f < FRAMES; ++f) {
    draw(f);
    glXSwapBuffers(g.dpy, g.win);
  }
  glprog_close(&g);
  return 0;
}

/* SPDX-License-Identifier: Apache-2.0
 * shadecore — a GL 1.x test program for `shadecore replay` (docs/replay.md, issue 37): glMaterial changing more than
 * one colour and the shininess between the vertices of smooth-shaded primitives, which GL lights each with the
 * material current at it (material batches in the back end). A ball whose every vertex gets its own diffuse,
 * specular and shininess by latitude and longitude (three materials in turn), and a plain ball beside it. One
 * directional light, local viewer off, back faces culled. Plain GLX (libGL, libX11), a fixed number of frames:
 *   cc -O2 -o matbatch matbatch.c -lGL -lX11 -lm
 *   LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 640x480x24" apitrace trace -o matbatch.trace ./matbatch */
#include "glprog_window.h"
#include <math.h>
#include <stdio.h>

enum { W = 420, H = 240, FRAMES = 20, STACKS = 14, SLICES = 22 };
static const double PI = 3.14159265358979323846;

/* A ball of radius 1 in immediate mode; with `materials`, one of three materials before every vertex (a diffuse
 * colour, a specular colour and a shininess each: three values change between the vertices of a strip). */
static void ball(int materials) {
  static const GLfloat dif[3][4] = {{0.85f, 0.3f, 0.25f, 1}, {0.3f, 0.75f, 0.35f, 1}, {0.3f, 0.4f, 0.9f, 1}};
  static const GLfloat spe[3][4] = {{0.9f, 0.9f, 0.9f, 1}, {0.2f, 0.5f, 0.2f, 1}, {0.6f, 0.6f, 1, 1}};
  static const GLfloat shi[3] = {60, 12, 30};
  for (int i = 0; i < STACKS; ++i) {
    glBegin(GL_TRIANGLE_STRIP);
    for (int j = 0; j <= SLICES; ++j)
      for (int k = 0; k < 2; ++k) {
        const double th = PI * (i + 1 - k) / STACKS, ph = 2 * PI * j / SLICES;  /* counter-clockwise outside */
        const double n[3] = {sin(th) * cos(ph), cos(th), sin(th) * sin(ph)};
        if (materials) {
          const int m = (i + 1 - k + j) % 3;
          glMaterialfv(GL_FRONT, GL_DIFFUSE, dif[m]);
          glMaterialfv(GL_FRONT, GL_SPECULAR, spe[m]);
          glMaterialf(GL_FRONT, GL_SHININESS, shi[m]);
        }
        glNormal3d(n[0], n[1], n[2]);
        glVertex3d(n[0], n[1], n[2]);
      }
    glEnd();
  }
}

static void draw(int frame) {
  const double t = 0.3 * frame;
  glClearColor(0.02f, 0.03f, 0.05f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  const GLfloat dir0[4] = {(GLfloat)(0.5 * cos(t)), 0.6f, 0.8f, 0};
  glLightfv(GL_LIGHT0, GL_POSITION, dir0);
  glEnable(GL_LIGHT0);
  glEnable(GL_DEPTH_TEST);

  glPushMatrix();
  glTranslated(-1.2, 0, -5);
  glRotated(15 * t, 0, 1, 0);
  ball(1);
  glPopMatrix();

  const GLfloat grey[4] = {0.6f, 0.6f, 0.6f, 1}, white[4] = {1, 1, 1, 1};
  glMaterialfv(GL_FRONT, GL_DIFFUSE, grey);
  glMaterialfv(GL_FRONT, GL_SPECULAR, white);
  glMaterialf(GL_FRONT, GL_SHININESS, 40);
  glPushMatrix();
  glTranslated(1.3, 0, -5.5);
  ball(0);
  glPopMatrix();
}

int main(void) {
  struct glprog g;
  if (glprog_open(&g, "matbatch", W, H)) return 1;

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

/* SPDX-License-Identifier: Apache-2.0
 * shadecore — a GL 1.x test program for `shadecore replay` (docs/replay.md, issue 37): one point light with
 * attenuation circling over a floor and a ball, smooth shading, the floor's diffuse colour set by glMaterialfv
 * before every vertex between glBegin and glEnd, the ball drawn from vertex arrays with glDrawElements. Plain GLX
 * (libGL, libX11), a fixed number of frames so a capture is the same on every machine:
 *   cc -O2 -o lamp lamp.c -lGL -lX11 -lm
 *   LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 640x480x24" apitrace trace -o lamp.trace ./lamp */
#include "glprog_window.h"
#include <math.h>
#include <stdio.h>

enum { W = 400, H = 300, FRAMES = 20, SLICES = 24, STACKS = 16 };
static const double PI = 3.14159265358979323846;

static GLfloat ball_v[(SLICES + 1) * (STACKS + 1)][3], ball_n[(SLICES + 1) * (STACKS + 1)][3];
static GLushort ball_i[SLICES * STACKS * 6];

static void build_ball(void) {
  const double r = 0.9;
  int k = 0;
  for (int i = 0; i <= STACKS; ++i)
    for (int j = 0; j <= SLICES; ++j, ++k) {
      const double th = PI * i / STACKS, ph = 2 * PI * j / SLICES;
      const double n[3] = {sin(th) * cos(ph), cos(th), sin(th) * sin(ph)};
      for (int c = 0; c < 3; ++c) ball_n[k][c] = (GLfloat)n[c], ball_v[k][c] = (GLfloat)(r * n[c]);
    }
  k = 0;
  for (int i = 0; i < STACKS; ++i)
    for (int j = 0; j < SLICES; ++j) {
      const int a = i * (SLICES + 1) + j, b = a + SLICES + 1;
      /* counter-clockwise seen from outside */
      ball_i[k++] = (GLushort)a, ball_i[k++] = (GLushort)(a + 1), ball_i[k++] = (GLushort)b;
      ball_i[k++] = (GLushort)(a + 1), ball_i[k++] = (GLushort)(b + 1), ball_i[k++] = (GLushort)b;
    }
}

/* The floor's diffuse colour at (x, z): a smooth field, one glMaterialfv per vertex. */
static void floor_vertex(double x, double z) {
  const GLfloat d[4] = {(GLfloat)(0.45 + 0.4 * sin(0.9 * x)), (GLfloat)(0.45 + 0.4 * cos(0.7 * z)),
                        (GLfloat)(0.5 + 0.3 * sin(0.5 * (x + z))), 1};
  glMaterialfv(GL_FRONT, GL_DIFFUSE, d);
  glNormal3f(0, 1, 0);
  glVertex3f((GLfloat)x, 0, (GLfloat)z);
}

static void draw(int frame) {
  const double t = 0.35 * frame;
  glClearColor(0.05f, 0.05f, 0.08f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glTranslatef(0, -0.8f, -7.5f);
  glRotatef(28, 1, 0, 0);
  glRotatef((GLfloat)(10 * t), 0, 1, 0);
  const GLfloat pos[4] = {(GLfloat)(2.2 * cos(t)), 1.8f, (GLfloat)(2.2 * sin(t)), 1};
  glLightfv(GL_LIGHT0, GL_POSITION, pos);  /* a point light, placed in the world by the modelview */

  const GLfloat amb[4] = {0.2f, 0.2f, 0.2f, 1}, spec[4] = {0.35f, 0.35f, 0.35f, 1};
  glMaterialfv(GL_FRONT, GL_AMBIENT, amb);
  glMaterialfv(GL_FRONT, GL_SPECULAR, spec);
  glMaterialf(GL_FRONT, GL_SHININESS, 24);
  const int n = 10;
  const double s = 0.6;
  for (int i = 0; i < n; ++i) { /* one quad strip per row, x toward +x, front face up */
    glBegin(GL_QUAD_STRIP);
    for (int j = 0; j <= n; ++j) {
      const double x = (j - n / 2.0) * s, z0 = (i - n / 2.0) * s;
      floor_vertex(x, z0);
      floor_vertex(x, z0 + s);
    }
    glEnd();
  }

  const GLfloat bd[4] = {0.85f, 0.35f, 0.2f, 1}, bs[4] = {0.9f, 0.9f, 0.9f, 1}, ba[4] = {0.25f, 0.1f, 0.08f, 1};
  glMaterialfv(GL_FRONT, GL_AMBIENT, ba);
  glMaterialfv(GL_FRONT, GL_DIFFUSE, bd);
  glMaterialfv(GL_FRONT, GL_SPECULAR, bs);
  glMaterialf(GL_FRONT, GL_SHININESS, 64);
  glPushMatrix();
  glTranslatef(0.3f, 0.9f, -0.2f);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, ball_v);
  glNormalPointer(GL_FLOAT, 0, ball_n);
  glDrawElements(GL_TRIANGLES, SLICES * STACKS * 6, GL_UNSIGNED_SHORT, ball_i);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glPopMatrix();
}

int main(void) {
  struct glprog g;
  if (glprog_open(&g, "lamp", W, H)) return 1;

  build_ball();
  glViewport(0, 0, W, H);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(-0.55, 0.55, -0.4125, 0.4125, 1, 40);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  const GLfloat la[4] = {0.1f, 0.1f, 0.1f, 1}, ld[4] = {1, 0.92f, 0.8f, 1}, ls[4] = {1, 1, 1, 1}, ma[4] = {0.12f, 0.12f, 0.15f, 1};
  glLightfv(GL_LIGHT0, GL_AMBIENT, la);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, ld);
  glLightfv(GL_LIGHT0, GL_SPECULAR, ls);
  glLightf(GL_LIGHT0, GL_CONSTANT_ATTENUATION, 0.5f);
  glLightf(GL_LIGHT0, GL_LINEAR_ATTENUATION, 0.12f);
  glLightf(GL_LIGHT0, GL_QUADRATIC_ATTENUATION, 0.04f);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ma);
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_TRUE);

  for (int f = 0; f < FRAMES; ++f) {
    draw(f);
    glXSwapBuffers(g.dpy, g.win);
  }
  glprog_close(&g);
  return 0;
}

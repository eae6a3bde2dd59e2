/* SPDX-License-Identifier: Apache-2.0
 * shadecore — a GL 1.x test program for `shadecore replay` (docs/replay.md, issue 37): two coloured point lights
 * with different attenuations, smooth shading, GL_NORMALIZE under a scaled modelview; a torus drawn from vertex
 * arrays (positions, normals and colours; glDrawArrays of triangle strips under GL_COLOR_MATERIAL) and a ball drawn
 * between glBegin and glEnd with glMaterialfv(GL_AMBIENT_AND_DIFFUSE) before every vertex. Plain GLX (libGL,
 * libX11), a fixed number of frames:
 *   cc -O2 -o twinlights twinlights.c -lGL -lX11 -lm
 *   LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 640x480x24" apitrace trace -o twinlights.trace ./twinlights */
#include "glprog_window.h"
#include <math.h>
#include <stdio.h>

enum { W = 360, H = 360, FRAMES = 20, RINGS = 32, SIDES = 16 };
static const double PI = 3.14159265358979323846;

/* RINGS strips of 2 (SIDES + 1) vertices each */
static GLfloat tv[RINGS][2 * (SIDES + 1)][3], tn[RINGS][2 * (SIDES + 1)][3], tc[RINGS][2 * (SIDES + 1)][3];

static void build_torus(void) {
  const double R = 1.0, r = 0.38;
  for (int i = 0; i < RINGS; ++i)
    for (int j = 0; j <= SIDES; ++j)
      for (int k = 0; k < 2; ++k) {
        const double u = 2 * PI * (i + 1 - k) / RINGS, v = 2 * PI * j / SIDES;
        const double n[3] = {cos(v) * cos(u), cos(v) * sin(u), sin(v)};
        GLfloat* p = tv[i][2 * j + k];
        p[0] = (GLfloat)((R + r * cos(v)) * cos(u)), p[1] = (GLfloat)((R + r * cos(v)) * sin(u)), p[2] = (GLfloat)(r * sin(v));
        for (int c = 0; c < 3; ++c) tn[i][2 * j + k][c] = (GLfloat)n[c];
        tc[i][2 * j + k][0] = (GLfloat)(0.55 + 0.35 * cos(u));
        tc[i][2 * j + k][1] = (GLfloat)(0.55 + 0.35 * sin(u));
        tc[i][2 * j + k][2] = (GLfloat)(0.6 + 0.3 * sin(v));
      }
}

/* A ball of radius 1 in immediate mode: per vertex its ambient-and-diffuse colour (by latitude and longitude). */
static void ball_vertex(double th, double ph) {
  const double n[3] = {sin(th) * cos(ph), cos(th), sin(th) * sin(ph)};
  const GLfloat c[4] = {(GLfloat)(0.5 + 0.4 * cos(th)), (GLfloat)(0.5 + 0.35 * sin(2 * ph)), (GLfloat)(0.45 + 0.3 * sin(th)), 1};
  glMaterialfv(GL_FRONT, GL_AMBIENT_AND_DIFFUSE, c);
  glNormal3d(n[0], n[1], n[2]);
  glVertex3d(n[0], n[1], n[2]);
}

static void draw(int frame) {
  const double t = 0.3 * frame;
  glClearColor(0.02f, 0.03f, 0.05f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glTranslatef(0, 0, -6);
  glRotatef(20, 1, 0, 0);
  const GLfloat p0[4] = {(GLfloat)(2.0 * cos(t)), 1.2f, (GLfloat)(2.0 * sin(t) + 0.5), 1};
  const GLfloat p1[4] = {(GLfloat)(-1.6 * cos(0.7 * t)), -0.8f, 2.0f, 1};
  glLightfv(GL_LIGHT0, GL_POSITION, p0);
  glLightfv(GL_LIGHT1, GL_POSITION, p1);

  /* the torus: vertex arrays, colours through GL_COLOR_MATERIAL, scaled (GL_NORMALIZE) */
  const GLfloat ts[4] = {0.6f, 0.6f, 0.6f, 1}, zero[4] = {0, 0, 0, 1};
  glMaterialfv(GL_FRONT, GL_SPECULAR, ts);
  glMaterialfv(GL_FRONT, GL_EMISSION, zero);
  glMaterialf(GL_FRONT, GL_SHININESS, 40);
  glColorMaterial(GL_FRONT, GL_AMBIENT_AND_DIFFUSE);
  glEnable(GL_COLOR_MATERIAL);
  glPushMatrix();
  glTranslatef(-0.9f, 0, 0);
  glRotatef((GLfloat)(25 * t), 0, 1, 0);
  glRotatef(60, 1, 0, 0);
  glScalef(1.1f, 1.1f, 1.1f);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, tv);
  glNormalPointer(GL_FLOAT, 0, tn);
  glColorPointer(3, GL_FLOAT, 0, tc);
  for (int i = 0; i < RINGS; ++i) glDrawArrays(GL_TRIANGLE_STRIP, i * 2 * (SIDES + 1), 2 * (SIDES + 1));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glPopMatrix();
  glDisable(GL_COLOR_MATERIAL);

  /* the ball: glMaterial between glBegin and glEnd */
  const GLfloat bs[4] = {0.8f, 0.8f, 0.8f, 1};
  glMaterialfv(GL_FRONT, GL_SPECULAR, bs);
  glMaterialf(GL_FRONT, GL_SHININESS, 90);
  glPushMatrix();
  glTranslatef(1.25f, 0.1f, 0.3f);
  glScalef(0.75f, 0.75f, 0.75f);
  const int st = 14, sl = 22;
  for (int i = 0; i < st; ++i) {
    glBegin(GL_TRIANGLE_STRIP);
    for (int j = 0; j <= sl; ++j) {
      const double ph = 2 * PI * j / sl;
      ball_vertex(PI * i / st, ph);
      ball_vertex(PI * (i + 1) / st, ph);
    }
    glEnd();
  }
  glPopMatrix();
}

int main(void) {
  struct glprog g;
  if (glprog_open(&g, "twinlights", W, H)) return 1;

  build_torus();
  glViewport(0, 0, W, H);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(-0.45, 0.45, -0.45, 0.45, 1.5, 30);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glEnable(GL_NORMALIZE);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glEnable(GL_LIGHT1);
  const GLfloat d0[4] = {1, 0.75f, 0.55f, 1}, d1[4] = {0.45f, 0.6f, 1, 1}, s0[4] = {1, 0.9f, 0.8f, 1}, s1[4] = {0.6f, 0.7f, 1, 1};
  const GLfloat a0[4] = {0.08f, 0.06f, 0.05f, 1}, ma[4] = {0.1f, 0.1f, 0.12f, 1};
  glLightfv(GL_LIGHT0, GL_AMBIENT, a0);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, d0);
  glLightfv(GL_LIGHT0, GL_SPECULAR, s0);
  glLightf(GL_LIGHT0, GL_CONSTANT_ATTENUATION, 0.8f);
  glLightf(GL_LIGHT0, GL_LINEAR_ATTENUATION, 0.2f);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, d1);
  glLightfv(GL_LIGHT1, GL_SPECULAR, s1);
  glLightf(GL_LIGHT1, GL_CONSTANT_ATTENUATION, 0.3f);
  glLightf(GL_LIGHT1, GL_QUADRATIC_ATTENUATION, 0.08f);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ma);

  for (int f = 0; f < FRAMES; ++f) {
    draw(f);
    glXSwapBuffers(g.dpy, g.win);
  }
  glprog_close(&g);
  return 0;
}

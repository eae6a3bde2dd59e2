/* SPDX-License-Identifier: Apache-2.0
 * shadecore — a GL 1.x test program for `shadecore replay` (docs/replay.md, issue 37): the lights and the light model
 * change between the draws of one frame, as a driver sees them in many real programs. Three balls, each drawn under
 * its own lighting state: the first by a warm directional light (GL_LIGHT0); the second by a cool attenuated point
 * light alone (GL_LIGHT0 off, GL_LIGHT1 on) with a brighter GL_LIGHT_MODEL_AMBIENT; the third by both lights with
 * GL_LIGHT1's diffuse colour changed and GL_LIGHT_MODEL_LOCAL_VIEWER on. Smooth shading, one colour per vertex under
 * GL_COLOR_MATERIAL(GL_DIFFUSE) on the second ball. Plain GLX (libGL, libX11), a fixed number of frames:
 *   cc -O2 -o relight relight.c -lGL -lX11 -lm
 *   LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 640x480x24" apitrace trace -o relight.trace ./relight */
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

static void draw(int frame) {
  const double t = 0.3 * frame;
  glClearColor(0.02f, 0.03f, 0.05f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glTranslatef(0, 0, -6);

  const GLfloat dir0[4] = {(GLfloat)(0.6 * cos(t)), 0.7f, 0.8f, 0}, p1[4] = {(GLfloat)(1.5 * sin(t)), 1.0f, 1.5f, 1};
  const GLfloat warm[4] = {1, 0.8f, 0.6f, 1}, cool[4] = {0.5f, 0.65f, 1, 1}, green[4] = {0.4f, 1, 0.5f, 1};
  const GLfloat amb_low[4] = {0.1f, 0.1f, 0.12f, 1}, amb_high[4] = {0.3f, 0.25f, 0.2f, 1};
  const GLfloat spec[4] = {0.7f, 0.7f, 0.7f, 1}, grey[4] = {0.7f, 0.7f, 0.7f, 1};
  glLightfv(GL_LIGHT0, GL_POSITION, dir0);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, warm);
  glLightfv(GL_LIGHT1, GL_POSITION, p1);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, cool);
  glMaterialfv(GL_FRONT, GL_AMBIENT_AND_DIFFUSE, grey);
  glMaterialfv(GL_FRONT, GL_SPECULAR, spec);
  glMaterialf(GL_FRONT, GL_SHININESS, 50);

  /* the first ball: light 0 alone (directional) */
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, amb_low);
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_FALSE);
  glEnable(GL_LIGHT0);
  glDisable(GL_LIGHT1);
  glPushMatrix();
  glTranslatef(-2.1f, 0, 0);
  glRotatef((GLfloat)(20 * t), 0, 1, 0);
  ball(0);
  glPopMatrix();

  /* the second ball: light 1 alone (attenuated point light), a brighter model ambient, a colour per vertex */
  glDisable(GL_LIGHT0);
  glEnable(GL_LIGHT1);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, amb_high);
  glColorMaterial(GL_FRONT, GL_DIFFUSE);
  glEnable(GL_COLOR_MATERIAL);
  glPushMatrix();
  glRotatef((GLfloat)(-15 * t), 0, 1, 0);
  ball(1);
  glPopMatrix();
  glDisable(GL_COLOR_MATERIAL);
  glMaterialfv(GL_FRONT, GL_AMBIENT_AND_DIFFUSE, grey);

  /* the third ball: both lights, light 1 green, local viewer */
  glEnable(GL_LIGHT0);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, green);
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_TRUE);
  glPushMatrix();
  glTranslatef(2.1f, 0, 0);
  ball(0);
  glPopMatrix();
}

int main(void) {
  struct glprog g;
  if (glprog_open(&g, "relight", W, H)) return 1;

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

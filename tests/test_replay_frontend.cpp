// SPDX-License-Identifier: Apache-2.0
// The GL 1.x front end of `shadecore replay` (shadecore/glfront/frontend.hpp), call by call against OpenGL 2.1's
// rules: matrix stacks, display lists (nesting, COMPILE_AND_EXECUTE, arrays captured at compile time), each
// primitive type's provoking vertex, facing and culling, normals with and without GL_NORMALIZE / GL_RESCALE_NORMAL,
// glMaterial between glBegin and glEnd, colour material, lights in eye space, unsupported-call accounting; and the
// frame selection of replay_frame on captures built here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "replay_capture.hpp"
#include "shadecore/glfront/frontend.hpp"
#include "shadecore/glfront/trace.hpp"

namespace {

using shadecore::glfront::Gl;
using shadecore::glfront::Mat4;
using shadecore::glfront::ReplayError;
using shadecore::trace::Call;
using shadecore::trace::FunctionSig;
using shadecore::trace::Value;
using Kind = Value::Kind;

Value F(double d) {
  Value v;
  v.kind = Kind::Double;
  v.d = d;
  return v;
}
Value I(int64_t i) {
  Value v;
  v.kind = Kind::SInt;
  v.i = i;
  return v;
}
Value A(const std::vector<double>& xs) {
  Value v;
  v.kind = Kind::Array;
  for (double x : xs) v.items.push_back(F(x));
  return v;
}
Value Blob(const void* p, size_t n) {
  Value v;
  v.kind = Kind::Blob;
  v.s.assign(static_cast<const char*>(p), n);
  return v;
}

// Calls as the reader gives them (one signature per name, numbered in order).
struct Driver {
  Gl gl;
  std::map<std::string, std::shared_ptr<FunctionSig>> sigs;
  uint64_t no = 0;
  void operator()(const std::string& name, std::vector<Value> args = {}) {
    auto& s = sigs[name];
    if (!s) {
      s = std::make_shared<FunctionSig>();
      s->name = name;
    }
    Call c;
    c.no = no++;
    c.sig = s;
    c.args = std::move(args);
    gl.call(c);
  }
  // shorthands
  void v3(double x, double y, double z) { (*this)("glVertex3f", {F(x), F(y), F(z)}); }
  void colour(double r) { (*this)("glColor3f", {F(r), F(0), F(0)}); }
  void en(int64_t cap) { (*this)("glEnable", {I(cap)}); }
};

enum : int64_t {
  MODELVIEW = 0x1700, PROJECTION = 0x1701, TRIANGLES = 4, TRIANGLE_STRIP = 5, TRIANGLE_FAN = 6, QUADS = 7,
  QUAD_STRIP = 8, POLYGON = 9, LINES = 1, FLAT = 0x1D00, CULL_FACE = 0x0B44, CW = 0x0900, NORMALIZE = 0x0BA1,
  RESCALE_NORMAL = 0x803A, FRONT = 0x0404, BACK = 0x0405, FRONT_AND_BACK = 0x0408, DIFFUSE = 0x1201,
  COLOR_MATERIAL = 0x0B57, AMBIENT = 0x1200, LIGHT0 = 0x4000, POSITION = 0x1203, LIGHTING = 0x0B50,
  DEPTH_TEST = 0x0B71, COMPILE = 0x1300, COMPILE_AND_EXECUTE = 0x1301, FLOAT = 0x1406, VERTEX_ARRAY = 0x8074,
  UNSIGNED_BYTE = 0x1401, TEXTURE_2D = 0x0DE1,
};

void expect_mat(const Mat4& m, const std::vector<double>& rowmajor) {
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(m[i], rowmajor[i], 1e-12) << "element " << i;
}

TEST(ReplayFrontend, MatrixStacksAndTransforms) {
  Driver d;
  d("glMatrixMode", {I(MODELVIEW)});
  d("glTranslatef", {F(1), F(2), F(3)});
  d("glPushMatrix");
  EXPECT_EQ(d.gl.modelview_depth(), 2u);
  d("glRotatef", {F(90), F(0), F(0), F(1)});
  // T · R(90° about z): x → y
  expect_mat(d.gl.modelview(), {0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1});
  d("glScalef", {F(2), F(3), F(4)});
  expect_mat(d.gl.modelview(), {0, -3, 0, 1, 2, 0, 0, 2, 0, 0, 4, 3, 0, 0, 0, 1});
  d("glPopMatrix");
  expect_mat(d.gl.modelview(), {1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1});
  d("glPopMatrix");  // underflow: an error GL ignores
  EXPECT_EQ(d.gl.modelview_depth(), 1u);
  EXPECT_EQ(d.gl.stats().notes.count("glPopMatrix of an empty stack (GL_STACK_UNDERFLOW, ignored)"), 1u);
  // glLoadMatrixf is column-major
  d("glLoadMatrixf", {A({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 7, 8, 9, 1})});
  expect_mat(d.gl.modelview(), {1, 0, 0, 7, 0, 1, 0, 8, 0, 0, 1, 9, 0, 0, 0, 1});
  d("glMultMatrixd", {A({2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1})});
  expect_mat(d.gl.modelview(), {2, 0, 0, 7, 0, 2, 0, 8, 0, 0, 2, 9, 0, 0, 0, 1});
  // the projection stack is separate
  d("glMatrixMode", {I(PROJECTION)});
  d("glLoadIdentity");
  d("glFrustum", {F(-1), F(1), F(-1), F(1), F(5), F(60)});
  expect_mat(d.gl.projection(), {5, 0, 0, 0, 0, 5, 0, 0, 0, 0, -65.0 / 55, -600.0 / 55, 0, 0, -1, 0});
  expect_mat(d.gl.modelview(), {2, 0, 0, 7, 0, 2, 0, 8, 0, 0, 2, 9, 0, 0, 0, 1});
  d("glLoadIdentity");
  d("glOrtho", {F(0), F(4), F(0), F(2), F(-1), F(1)});
  expect_mat(d.gl.projection(), {0.5, 0, 0, -1, 0, 1, 0, -1, 0, 0, -1, 0, 0, 0, 0, 1});
}

// Draws `n` vertices of `mode` under flat shading, vertex k coloured red = k/100; returns the provoking vertex
// index of each triangle (its last vertex after assembly).
std::vector<int> provoking(int64_t mode, int n) {
  Driver d;
  d("glShadeModel", {I(FLAT)});
  d("glBegin", {I(mode)});
  for (int k = 0; k < n; ++k) {
    d.colour(k / 100.0);
    // a convex fan of points on a circle, counter-clockwise (no triangle degenerates whatever the mode)
    const double a = 2 * 3.14159265358979 * k / (n + 1);
    d.v3(std::cos(a), std::sin(a), -0.5);
  }
  d("glEnd");
  std::vector<int> out;
  for (const auto& t : d.gl.triangles()) {
    EXPECT_TRUE(t.flat);
    out.push_back(static_cast<int>(std::lround(t.v[2].colour[0] * 100)));
  }
  return out;
}

TEST(ReplayFrontend, ProvokingVertexPerPrimitiveType) {
  // OpenGL 2.1 table 2.12 (1-based i): triangles 3i, strip / fan i+2, quads 4i, quad strip 2i+2, polygon 1
  EXPECT_EQ(provoking(TRIANGLES, 7), (std::vector<int>{2, 5}));  // the 7th vertex is left over
  EXPECT_EQ(provoking(TRIANGLE_STRIP, 6), (std::vector<int>{2, 3, 4, 5}));
  EXPECT_EQ(provoking(TRIANGLE_FAN, 6), (std::vector<int>{2, 3, 4, 5}));
  EXPECT_EQ(provoking(QUADS, 9), (std::vector<int>{3, 3, 7, 7}));
  EXPECT_EQ(provoking(QUAD_STRIP, 7), (std::vector<int>{3, 3, 5, 5}));
  EXPECT_EQ(provoking(POLYGON, 5), (std::vector<int>{0, 0, 0}));
}

TEST(ReplayFrontend, FacingFrontFaceAndCulling) {
  auto draw = [](bool cw, bool cull, int64_t cull_face) {
    Driver d;
    if (cw) d("glFrontFace", {I(CW)});
    if (cull) d.en(CULL_FACE);
    d("glCullFace", {I(cull_face)});
    d("glBegin", {I(TRIANGLES)});
    d.v3(0, 0, -0.5), d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);  // counter-clockwise on screen
    d.v3(0, 0, -0.5), d.v3(0, 1, -0.5), d.v3(1, 0, -0.5);  // clockwise
    d("glEnd");
    return std::make_pair(d.gl.triangles(), d.gl.stats().culled);
  };
  {
    const auto [t, culled] = draw(false, true, BACK);
    ASSERT_EQ(t.size(), 1u);
    EXPECT_EQ(culled, 1u);
    EXPECT_EQ(t[0].v[1].eye[0], 1);  // the CCW one: (0,0), (1,0), (0,1), its provoking vertex (0,1) last
    EXPECT_EQ(t[0].v[2].eye[1], 1);
  }
  {
    const auto [t, culled] = draw(true, true, BACK);  // glFrontFace(GL_CW): the clockwise one is front
    ASSERT_EQ(t.size(), 1u);
    // handed over counter-clockwise: (0,1), (1,0) swapped to put the winding right, provoking vertex (1,0) last
    EXPECT_EQ(t[0].v[2].eye[0], 1);
    EXPECT_EQ(t[0].v[2].eye[1], 0);
    const auto& a = t[0].v;
    const double area = (a[1].eye[0] - a[0].eye[0]) * (a[2].eye[1] - a[0].eye[1]) -
                        (a[2].eye[0] - a[0].eye[0]) * (a[1].eye[1] - a[0].eye[1]);
    EXPECT_GT(area, 0);
  }
  EXPECT_EQ(draw(false, true, FRONT_AND_BACK).first.size(), 0u);
  EXPECT_EQ(draw(false, false, BACK).first.size(), 2u);  // GL_CULL_FACE off: both
}

// The eye-space normal GL lights vertex (0,0,-2) with, for normal n under modelview scale s and the given enables.
std::array<double, 3> eye_normal(std::array<double, 3> s, std::array<double, 3> n, std::vector<int64_t> caps) {
  Driver d;
  for (auto c : caps) d.en(c);
  d("glScalef", {F(s[0]), F(s[1]), F(s[2])});
  d("glNormal3f", {F(n[0]), F(n[1]), F(n[2])});
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -0.5), d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);
  d("glEnd");
  EXPECT_EQ(d.gl.triangles().size(), 1u);
  return d.gl.triangles().at(0).v[0].normal;
}

TEST(ReplayFrontend, NormalsFollowGlRules) {
  // neither: the inverse transpose, not renormalised — a uniform scale of 2 halves the normal
  auto n = eye_normal({2, 2, 2}, {0, 0, 1}, {});
  EXPECT_NEAR(n[2], 0.5, 1e-12);
  // GL_RESCALE_NORMAL: back to unit length for a uniform scale
  n = eye_normal({2, 2, 2}, {0, 0, 1}, {RESCALE_NORMAL});
  EXPECT_NEAR(n[2], 1.0, 1e-12);
  // … but only by the third row of M^-1: a non-uniform scale (1, 1, 2) leaves (1, 0, 0) at length 2
  n = eye_normal({1, 1, 2}, {1, 0, 0}, {RESCALE_NORMAL});
  EXPECT_NEAR(n[0], 2.0, 1e-12);
  // GL_NORMALIZE: unit, in the inverse transpose's direction
  n = eye_normal({1, 2, 1}, {0, std::sqrt(0.5), std::sqrt(0.5)}, {NORMALIZE});
  EXPECT_NEAR(std::hypot(n[1], n[2]), 1.0, 1e-12);
  EXPECT_NEAR(n[1] / n[2], 0.5, 1e-12);
  // both: GL_NORMALIZE wins
  n = eye_normal({1, 1, 2}, {1, 0, 0}, {RESCALE_NORMAL, NORMALIZE});
  EXPECT_NEAR(n[0], 1.0, 1e-12);
}

TEST(ReplayFrontend, DisplayListsCompileExecuteAndNest) {
  Driver d;
  d("glGenLists", {I(3)});
  d("glNewList", {I(1), I(COMPILE)});
  d("glTranslatef", {F(1), F(0), F(0)});
  d("glEndList");
  EXPECT_EQ(d.gl.modelview()[3], 0);  // GL_COMPILE: not executed
  d("glCallList", {I(1)});
  EXPECT_EQ(d.gl.modelview()[3], 1);
  d("glNewList", {I(2), I(COMPILE_AND_EXECUTE)});
  d("glTranslatef", {F(0), F(1), F(0)});
  d("glCallList", {I(1)});  // nested: resolved when list 2 runs
  d("glEndList");
  EXPECT_EQ(d.gl.modelview()[3], 2);  // executed while compiled
  EXPECT_EQ(d.gl.modelview()[7], 1);
  d("glNewList", {I(1), I(COMPILE)});  // list 1 redefined: list 2 now calls the new one
  d("glTranslatef", {F(10), F(0), F(0)});
  d("glEndList");
  d("glCallList", {I(2)});
  EXPECT_EQ(d.gl.modelview()[3], 12);
  EXPECT_EQ(d.gl.modelview()[7], 2);
  // glListBase + glCallLists (ubyte offsets)
  d("glLoadIdentity");
  d("glListBase", {I(1)});
  const uint8_t offs[2] = {0, 0};
  d("glCallLists", {I(2), I(UNSIGNED_BYTE), Blob(offs, 2)});
  EXPECT_EQ(d.gl.modelview()[3], 20);
  d("glDeleteLists", {I(1), I(1)});
  EXPECT_FALSE(d.gl.list_defined(1));
  d("glCallList", {I(1)});  // deleted: nothing
  EXPECT_EQ(d.gl.modelview()[3], 20);
  // a list calling itself stops at GL's nesting limit (64) instead of recursing forever
  d("glNewList", {I(3), I(COMPILE)});
  d("glTranslatef", {F(0), F(0), F(1)});
  d("glCallList", {I(3)});
  d("glEndList");
  d("glLoadIdentity");
  d("glCallList", {I(3)});
  EXPECT_EQ(d.gl.modelview()[11], 64);
}

TEST(ReplayFrontend, ArrayDrawsInAListUseTheArraysAtCompileTime) {
  Driver d;
  const float a[9] = {0, 0, -2, 1, 0, -2, 0, 1, -2};
  const float b[9] = {5, 5, -2, 6, 5, -2, 5, 6, -2};
  d("glEnableClientState", {I(VERTEX_ARRAY)});
  d("glVertexPointer", {I(3), I(FLOAT), I(0), Blob(a, sizeof a)});
  d("glNewList", {I(1), I(COMPILE)});
  d("glDrawArrays", {I(TRIANGLES), I(0), I(3)});
  d("glEndList");
  EXPECT_TRUE(d.gl.triangles().empty());
  d("glVertexPointer", {I(3), I(FLOAT), I(0), Blob(b, sizeof b)});
  d("glCallList", {I(1)});
  ASSERT_EQ(d.gl.triangles().size(), 1u);
  EXPECT_EQ(d.gl.triangles()[0].v[2].eye[0], 0);  // a's, not b's
  d("glDrawArrays", {I(TRIANGLES), I(0), I(3)});  // now b's
  ASSERT_EQ(d.gl.triangles().size(), 2u);
  EXPECT_EQ(d.gl.triangles()[1].v[2].eye[0], 5);
  // glDrawElements with indices in the capture
  const uint8_t idx[3] = {2, 1, 0};
  d("glDrawElements", {I(TRIANGLES), I(3), I(UNSIGNED_BYTE), Blob(idx, 3)});
  ASSERT_EQ(d.gl.triangles().size(), 3u);
  EXPECT_EQ(d.gl.stats().primitives, 3u);
}

TEST(ReplayFrontend, MaterialBetweenBeginAndEnd) {
  Driver d;
  d("glShadeModel", {I(FLAT)});
  d("glBegin", {I(TRIANGLES)});
  d("glMaterialfv", {I(FRONT), I(DIFFUSE), A({1, 0, 0, 1})});
  d.v3(0, 0, -0.5), d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);
  d("glMaterialfv", {I(FRONT), I(DIFFUSE), A({0, 1, 0, 1})});
  d.v3(0, 0, -0.5), d.v3(1, 0, -0.5);
  d("glMaterialfv", {I(FRONT), I(DIFFUSE), A({0, 0, 1, 1})});
  d.v3(0, 1, -0.5);
  d("glEnd");
  const auto& t = d.gl.triangles();
  ASSERT_EQ(t.size(), 2u);
  const auto& mats = d.gl.materials();
  EXPECT_EQ(mats[t[0].v[2].material][0].diffuse[0], 1);  // the provoking vertex's material
  EXPECT_EQ(mats[t[1].v[2].material][0].diffuse[2], 1);
  EXPECT_EQ(mats[t[1].v[2].material][1].diffuse[2], 0.8);  // GL_FRONT only: the back keeps GL's default
  EXPECT_EQ(d.gl.material(false).diffuse[2], 1);
}

TEST(ReplayFrontend, ColourMaterialTracksTheCurrentColour) {
  Driver d;
  d("glColor3f", {F(0.5), F(0.25), F(1)});
  EXPECT_EQ(d.gl.material(false).diffuse[0], 0.8);  // off: no tracking
  d.en(COLOR_MATERIAL);                             // on: the current colour at once (AMBIENT_AND_DIFFUSE)
  EXPECT_EQ(d.gl.material(false).diffuse[1], 0.25);
  EXPECT_EQ(d.gl.material(true).ambient[2], 1);
  d("glColorMaterial", {I(FRONT), I(AMBIENT)});
  d("glColor4ub", {I(255), I(0), I(51), I(255)});
  EXPECT_EQ(d.gl.material(false).ambient[0], 1);
  EXPECT_DOUBLE_EQ(d.gl.material(false).ambient[2], 0.2);
  EXPECT_EQ(d.gl.material(true).ambient[0], 0.5);  // GL_FRONT only
}

TEST(ReplayFrontend, LightsAreInEyeSpaceAtTheCall) {
  Driver d;
  d("glTranslatef", {F(0), F(0), F(-5)});
  d("glLightfv", {I(LIGHT0), I(POSITION), A({0, 0, 0, 1})});
  d("glLightfv", {I(LIGHT0 + 1), I(POSITION), A({0, 0, 1, 0})});
  d("glLoadIdentity");
  EXPECT_EQ(d.gl.lighting().lights[0].position[2], -5);
  EXPECT_EQ(d.gl.lighting().lights[0].diffuse[0], 1);  // GL_LIGHT0's default diffuse
  EXPECT_EQ(d.gl.lighting().lights[1].diffuse[0], 0);  // the others' is black
  EXPECT_EQ(d.gl.lighting().lights[1].position[3], 0);
  d.en(LIGHT0);
  EXPECT_TRUE(d.gl.lighting().lights[0].enabled);
  EXPECT_FALSE(d.gl.lighting().lights[1].enabled);
}

TEST(ReplayFrontend, InvalidValuesIgnoredAndClampsNoted) {
  Driver d;
  d.en(DEPTH_TEST);
  d.en(LIGHTING);
  d.en(LIGHT0);
  d("glViewport", {I(0), I(0), I(16), I(16)});
  d("glLightf", {I(LIGHT0), I(0x1206), F(120)});   // GL_SPOT_CUTOFF 120: GL_INVALID_VALUE, ignored
  d("glLightf", {I(LIGHT0), I(0x1207), F(-1)});    // a negative GL_CONSTANT_ATTENUATION: ignored
  d("glMaterialf", {I(FRONT), I(0x1601), F(200)});  // shininess above 128: ignored
  d("glLightfv", {I(LIGHT0), I(DIFFUSE), A({2, 1, 1, 1})});  // GL keeps 2; the core's format cannot
  EXPECT_EQ(d.gl.lighting().lights[0].spot_cutoff, 180);
  EXPECT_EQ(d.gl.lighting().lights[0].kc, 1);
  EXPECT_EQ(d.gl.material(false).shininess, 0);
  EXPECT_EQ(d.gl.lighting().lights[0].diffuse[0], 2);
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -0.5), d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);
  d("glEnd");
  const auto h = shadecore::glfront::hand_over(d.gl, "t");
  EXPECT_EQ(h.scene.lights.at(0).diffuse[0], 1);
  EXPECT_EQ(h.stats.notes.count("a light colour outside [0, 1] clamped (the core's colour format; GL would not clamp)"), 1u);
  EXPECT_EQ(h.stats.notes.count("glLight GL_SPOT_CUTOFF outside 0..90, 180 (GL_INVALID_VALUE, ignored)"), 1u);
}

TEST(ReplayFrontend, GeometryGlClipsAtFarPlanesIsRefused) {
  Driver d;
  d("glMatrixMode", {I(PROJECTION)});
  d("glFrustum", {F(-1), F(1), F(-1), F(1), F(1), F(10)});
  d("glMatrixMode", {I(MODELVIEW)});
  d.en(DEPTH_TEST);
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -5), d.v3(1, 0, -5), d.v3(0, 1, -5);  // inside
  d("glEnd");
  EXPECT_TRUE(d.gl.refusals().empty());
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -5), d.v3(1, 0, -5), d.v3(0, 1, -20);  // one vertex beyond the far plane (10)
  d("glEnd");
  ASSERT_EQ(d.gl.refusals().size(), 1u);
  EXPECT_NE(d.gl.refusals()[0].find("far plane"), std::string::npos);
}

TEST(ReplayFrontend, UnsupportedCallsAreCountedAndExcludedOrRefused) {
  Driver d;
  d.en(DEPTH_TEST);
  d("glViewport", {I(0), I(0), I(64), I(64)});
  d("glBindTexture", {I(TEXTURE_2D), I(1)});
  d("glTexImage2D", {});
  d("glTexImage2D", {});
  d.en(TEXTURE_2D);
  d("glBegin", {I(TRIANGLES)});
  d("glTexCoord2f", {F(0), F(0)});
  d.v3(0, 0, -0.5), d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);
  d("glEnd");
  const auto& u = d.gl.stats().unsupported;
  EXPECT_EQ(u.at("glTexImage2D"), 2u);
  EXPECT_EQ(u.at("glBindTexture"), 1u);
  EXPECT_EQ(u.at("glTexCoord2f"), 1u);
  ASSERT_EQ(d.gl.triangles().size(), 1u);
  EXPECT_EQ(d.gl.triangles()[0].excluded, std::vector<std::string>{"GL_TEXTURE_2D"});
  EXPECT_TRUE(d.gl.refusals().empty());
  // handed over: drawn (coverage), its object not compared
  const auto h = shadecore::glfront::hand_over(d.gl, "t");
  ASSERT_EQ(h.object_excluded.size(), 1u);
  EXPECT_EQ(h.object_excluded[0], std::vector<std::string>{"GL_TEXTURE_2D"});
  // lines: their pixels are unknown to the back end, the frame is refused with the reason
  d("glBegin", {I(LINES)});
  d.v3(0, 0, -0.5), d.v3(1, 0, -0.5);
  d("glEnd");
  ASSERT_EQ(d.gl.refusals().size(), 1u);
  try {
    (void)shadecore::glfront::hand_over(d.gl, "t");
    ADD_FAILURE() << "no ReplayError";
  } catch (const ReplayError& e) {
    EXPECT_NE(std::string(e.what()).find("GL_LINES"), std::string::npos) << e.what();
  }
}

TEST(ReplayFrontend, HandOverGroupsTrianglesAndRefusesMixedSmoothMaterials) {
  Driver d;
  d.en(DEPTH_TEST);
  d.en(LIGHTING);
  d.en(LIGHT0);
  d("glViewport", {I(0), I(0), I(32), I(32)});
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -0.5), d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);
  d("glEnd");
  d("glMaterialfv", {I(FRONT_AND_BACK), I(DIFFUSE), A({0, 1, 0, 1})});
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -0.75), d.v3(1, 0, -0.75), d.v3(0, 1, -0.75);
  d("glEnd");
  auto h = shadecore::glfront::hand_over(d.gl, "t");
  EXPECT_EQ(h.scene.width, 32);
  ASSERT_EQ(h.scene.objects.size(), 2u);  // two materials: two runs
  ASSERT_EQ(h.scene.materials.size(), 2u);
  EXPECT_EQ(h.scene.materials[1].diffuse[1], 1);
  ASSERT_EQ(h.scene.lights.size(), 1u);
  EXPECT_EQ(h.meshes[1].pos[0][2], -0.75);
  EXPECT_EQ(h.scene.flat_rule, shadecore::scene::FlatRule::ProvokingVertex);
  // smooth shading with glMaterial between a triangle's vertices changing one colour: that colour per vertex
  // through colour material (GL lights each vertex with its own material)
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -0.5);
  d("glMaterialfv", {I(FRONT_AND_BACK), I(DIFFUSE), A({0, 0, 1, 1})});
  d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);
  d("glEnd");
  h = shadecore::glfront::hand_over(d.gl, "t");
  ASSERT_EQ(h.scene.objects.size(), 3u);
  EXPECT_EQ(h.scene.objects[2].colour_material, shadecore::ColourMaterial::Diffuse);
  ASSERT_EQ(h.meshes[2].col.size(), 3u);
  EXPECT_EQ(h.meshes[2].col[0], (shadecore::scene::Vec3{0, 1, 0}));  // the first vertex's diffuse
  EXPECT_EQ(h.meshes[2].col[1], (shadecore::scene::Vec3{0, 0, 1}));
  EXPECT_TRUE(h.meshes[0].col.empty());  // no colour material: no vertex colours
  // two colours changing between the vertices: material batches (each vertex lit under its own material;
  // ReplayFrontend.MaterialChangingBetweenVerticesIsLitInMaterialBatches)
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -0.5);
  d("glMaterialfv", {I(FRONT_AND_BACK), I(DIFFUSE), A({1, 0, 1, 1})});
  d("glMaterialfv", {I(FRONT_AND_BACK), I(0x1202), A({1, 1, 1, 1})});
  d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);
  d("glEnd");
  h = shadecore::glfront::hand_over(d.gl, "t");
  ASSERT_EQ(h.scene.objects.size(), 5u);  // the triangle's run (its provoking vertex's material) and a batch object
  ASSERT_EQ(h.meshes[3].vertex_object.size(), 3u);
  EXPECT_EQ(h.meshes[3].vertex_object[0], 4);  // the first vertex: the material before the two glMaterial calls
  EXPECT_EQ(h.meshes[3].vertex_object[1], 3);
  EXPECT_TRUE(h.meshes[4].pos.empty());
  // the first vertex's material: the diffuse (0, 0, 1) the third triangle's last vertices had, no colour material
  EXPECT_EQ(h.scene.materials[static_cast<size_t>(h.scene.objects[4].material)].diffuse, (shadecore::scene::Vec3{0, 0, 1}));
  EXPECT_FALSE(h.scene.objects[4].colour_material.has_value());
  EXPECT_NO_THROW((void)shadecore::render::prepare(h.scene, h.meshes, h.settings));
}

// GL_COLOR_MATERIAL with a colour per vertex in a smooth-shaded primitive (glColor between glBegin and glEnd, a colour
// array): GL tracks every colour into the material, so the vertices' materials differ in the tracked colour only;
// handed over as one colour-material object with the colours per vertex. A glMaterial of an untracked colour between
// the vertices is lit in material batches.
TEST(ReplayFrontend, HandOverCarriesSmoothColoursUnderColourMaterial) {
  Driver d;
  d.en(DEPTH_TEST);
  d.en(LIGHTING);
  d.en(LIGHT0);
  d("glViewport", {I(0), I(0), I(32), I(32)});
  d("glColorMaterial", {I(FRONT_AND_BACK), I(DIFFUSE)});
  d.en(COLOR_MATERIAL);
  d("glBegin", {I(TRIANGLE_STRIP)});
  d("glColor3f", {F(1), F(0), F(0)}), d.v3(0, 0, -0.5);
  d("glColor3f", {F(0), F(1), F(0)}), d.v3(1, 0, -0.5);
  d("glColor3f", {F(0), F(0), F(1)}), d.v3(0, 1, -0.5);
  d("glColor3f", {F(1), F(1), F(0)}), d.v3(1, 1, -0.5);
  d("glEnd");
  ASSERT_EQ(d.gl.triangles().size(), 2u);
  EXPECT_NE(d.gl.triangles()[0].v[0].material, d.gl.triangles()[0].v[2].material);  // GL tracked each colour
  auto h = shadecore::glfront::hand_over(d.gl, "t");
  // one object and one material: the materials differ in the tracked colour only, which reaches the core per vertex
  // through its fragment colour input (no material register writes of its own)
  ASSERT_EQ(h.scene.objects.size(), 1u);
  ASSERT_EQ(h.scene.materials.size(), 1u);
  EXPECT_EQ(h.scene.objects[0].colour_material, shadecore::ColourMaterial::Diffuse);
  ASSERT_EQ(h.meshes[0].col.size(), 6u);
  EXPECT_EQ(h.meshes[0].col[0], (shadecore::scene::Vec3{1, 0, 0}));
  EXPECT_EQ(h.meshes[0].col[1], (shadecore::scene::Vec3{0, 1, 0}));
  EXPECT_EQ(h.meshes[0].col[2], (shadecore::scene::Vec3{0, 0, 1}));
  EXPECT_EQ(h.meshes[0].col[3], (shadecore::scene::Vec3{0, 0, 1}));  // the strip's second triangle (2, 1, 3)
  EXPECT_EQ(h.meshes[0].col[5], (shadecore::scene::Vec3{1, 1, 0}));
  {
    const auto fr = shadecore::render::prepare(h.scene, h.meshes, h.settings);
    ASSERT_EQ(fr.groups.size(), 1u);
    uint64_t material_writes = 0;  // the diffuse colour registers: written once (the material's), never per colour
    for (const auto& c : fr.groups[0].cmds)
      if (c.is_write && c.w.addr >= shadecore::kReg_mat_diffuse && c.w.addr < shadecore::kReg_mat_diffuse + 3) ++material_writes;
    EXPECT_LE(material_writes, 3u);
    EXPECT_EQ(fr.groups[0].vertices, 6u);
  }
  EXPECT_EQ(h.stats.notes.count("glMaterial between a smooth primitive's vertices carried as colour material"), 0u);
  // an untracked colour (GL_AMBIENT) changing between the vertices: material batches, the tracked colour still per
  // vertex through colour material (the batch object's mesh lists the colours of the vertices it lights)
  d("glBegin", {I(TRIANGLES)});
  d.v3(0, 0, -0.5);
  d("glMaterialfv", {I(FRONT_AND_BACK), I(AMBIENT), A({0.5, 0.5, 0.5, 1})});
  d("glColor3f", {F(0), F(1), F(1)}), d.v3(1, 0, -0.5), d.v3(0, 1, -0.5);
  d("glEnd");
  h = shadecore::glfront::hand_over(d.gl, "t");
  ASSERT_EQ(h.scene.objects.size(), 3u);
  EXPECT_EQ(h.scene.objects[2].colour_material, shadecore::ColourMaterial::Diffuse);
  ASSERT_EQ(h.meshes[1].vertex_object.size(), 3u);
  EXPECT_EQ(h.meshes[1].vertex_object[0], 2);
  ASSERT_EQ(h.meshes[2].col.size(), 1u);
  EXPECT_EQ(h.meshes[2].col[0], (shadecore::scene::Vec3{1, 1, 0}));  // the colour current at the first vertex
  EXPECT_NO_THROW((void)shadecore::render::prepare(h.scene, h.meshes, h.settings));
}

// Eye-space positions outside the core's range [−128, 128): counted with the worst coordinate, and the frame's eye
// space scaled by a power of two (positions, point lights, their attenuation, the projection's first three columns)
// so the back end draws it: clip coordinates unchanged, never wrapped.
TEST(ReplayFrontend, EyeSpaceOutOfRangeIsScaledAndReported) {
  Driver d;
  d.en(DEPTH_TEST);
  d.en(LIGHTING);
  d.en(LIGHT0);
  d("glViewport", {I(0), I(0), I(32), I(32)});
  d("glMatrixMode", {I(PROJECTION)});
  d("glFrustum", {F(-1), F(1), F(-1), F(1), F(1), F(1000)});
  d("glMatrixMode", {I(MODELVIEW)});
  d("glLightfv", {I(LIGHT0), I(POSITION), A({0, 0, -250, 1})});
  d("glLightf", {I(LIGHT0), I(0x1208), F(0.1)});  // GL_LINEAR_ATTENUATION
  d("glBegin", {I(TRIANGLES)});
  d.v3(-100, -100, -300), d.v3(100, -100, -300), d.v3(0, 100, -300);
  d("glEnd");
  const Mat4 P = d.gl.projection();
  auto h = shadecore::glfront::hand_over(d.gl, "t");
  EXPECT_EQ(h.eye_out_of_range, 3u);
  EXPECT_EQ(h.eye_worst, 300);
  EXPECT_EQ(h.eye_scale, 0.25);  // 300 / 2 = 150 is still out, 300 / 4 = 75 is in
  ASSERT_EQ(h.meshes.size(), 1u);
  EXPECT_EQ(h.meshes[0].pos[0][2], -75);
  ASSERT_EQ(h.scene.lights.size(), 1u);
  EXPECT_EQ(h.scene.lights[0].position[2], -62.5);
  EXPECT_DOUBLE_EQ(h.scene.lights[0].kl, 0.4);
  const auto& Ps = *h.settings.projection;
  for (int r = 0; r < 4; ++r) {
    double clip = 0, clip_scaled = 0;  // the first vertex's clip coordinate r, both ways
    const double e[4] = {-100, -100, -300, 1}, es[4] = {-25, -25, -75, 1};
    for (int c = 0; c < 4; ++c) clip += P[4 * r + c] * e[c], clip_scaled += Ps[4 * r + c] * es[c];
    EXPECT_EQ(clip, clip_scaled) << "row " << r;
  }
  EXPECT_NO_THROW((void)shadecore::render::prepare(h.scene, h.meshes, h.settings));  // in range for the back end now
  // in range: nothing scaled, nothing counted
  Driver e;
  e.en(DEPTH_TEST);
  e("glViewport", {I(0), I(0), I(32), I(32)});
  e("glBegin", {I(TRIANGLES)});
  e.v3(0, 0, -0.5), e.v3(1, 0, -0.5), e.v3(0, 1, -0.5);
  e("glEnd");
  h = shadecore::glfront::hand_over(e.gl, "t");
  EXPECT_EQ(h.eye_out_of_range, 0u);
  EXPECT_EQ(h.eye_scale, 1);
}

// The lights changing between draws (the split at the driver's command stream): the hand-over carries the frame's
// lighting states in drawing order and each object's; the back end derives one core whose light slots take every
// state's kinds, programs the first state in full and each later one by the writes of the registers whose value
// changes (counted apart), and lights each batch with the core programmed for it.
TEST(ReplayFrontend, LightsChangingBetweenDrawsAreProgrammedBetweenBatches) {
  using shadecore::render::CoreCmd;
  Driver d;
  d.en(DEPTH_TEST);
  d.en(LIGHTING);
  d("glViewport", {I(0), I(0), I(32), I(32)});
  constexpr int64_t LIGHT1 = 0x4001;
  d("glLightfv", {I(LIGHT0), I(DIFFUSE), A({1, 0, 0, 1})});
  d("glLightfv", {I(LIGHT1), I(DIFFUSE), A({0, 1, 0, 1})});
  d("glLightfv", {I(LIGHT1), I(POSITION), A({0, 0, 1, 0})});
  d("glLightfv", {I(LIGHT1), I(0x1202), A({1, 1, 1, 1})});  // GL_SPECULAR as light 0's default
  d("glNormal3f", {F(0), F(0), F(1)});
  auto tri = [&d](double x0) {
    d("glBegin", {I(TRIANGLES)});
    d.v3(x0, -0.8, -0.5), d.v3(x0 + 0.5, -0.8, -0.5), d.v3(x0, 0.8, -0.5);
    d("glEnd");
  };
  d.en(LIGHT0);
  tri(-0.95);  // lit by light 0 alone (red)
  d("glDisable", {I(LIGHT0)});
  d.en(LIGHT1);
  tri(-0.3);  // lit by light 1 alone (green)
  ASSERT_EQ(d.gl.frame_lightings().size(), 2u);
  auto h = shadecore::glfront::hand_over(d.gl, "t");
  ASSERT_EQ(h.scene.lighting_sets.size(), 2u);
  ASSERT_EQ(h.scene.objects.size(), 2u);
  EXPECT_EQ(h.scene.objects[0].lighting, 0);
  EXPECT_EQ(h.scene.objects[1].lighting, 1);
  ASSERT_EQ(h.scene.lighting_sets[0].lights.size(), 1u);
  ASSERT_EQ(h.scene.lighting_sets[1].lights.size(), 1u);
  EXPECT_EQ(h.scene.lighting_sets[0].lights[0].diffuse, (shadecore::scene::Vec3{1, 0, 0}));
  EXPECT_EQ(h.scene.lighting_sets[1].lights[0].diffuse, (shadecore::scene::Vec3{0, 1, 0}));

  auto check = [](const shadecore::render::Frame& fr, const std::vector<std::array<double, 3>>& want_per_state,
                  const shadecore::scene::Scene& sc) {
    ASSERT_EQ(fr.groups.size(), 1u);
    const auto& g = fr.groups[0];
    const auto cols = shadecore::render::run_cmodel(g);
    ASSERT_EQ(cols.size(), g.dests.size());
    std::vector<int> seen(want_per_state.size(), 0);
    for (size_t i = 0; i < cols.size(); ++i) {
      ASSERT_EQ(g.dests[i].kind, shadecore::render::DestKind::Vertex);
      const int st = sc.objects[static_cast<size_t>(fr.vertex_object[g.dests[i].index])].lighting;
      ++seen[static_cast<size_t>(st)];
      for (int c = 0; c < 3; ++c)  // each batch lit with its own state (2^-16 codes; the core's rounding)
        EXPECT_NEAR(cols[i].c[c], want_per_state[static_cast<size_t>(st)][static_cast<size_t>(c)] * 65536, 8)
            << "fragment " << i << " state " << st << " channel " << c;
    }
    for (int n : seen) EXPECT_EQ(n, 3);  // three vertices per state
  };
  auto fr = shadecore::render::prepare(h.scene, h.meshes, h.settings);
  // ambient 0.2 · 0.2 = 0.04; diffuse 0.8 · the light's colour (N = L = +z)
  check(fr, {{0.84, 0.04, 0.04}, {0.04, 0.84, 0.04}}, h.scene);
  {
    const auto& g = fr.groups[0];
    EXPECT_EQ(g.fs.num_lights(), 1);  // one slot, reprogrammed between the batches
    EXPECT_EQ(g.state_changes, 1u);
    EXPECT_EQ(g.state_writes, 2u);  // the slot's diffuse red and green: the only registers whose value changes
    // in the stream: the first batch's three fragments, then exactly those two writes, then the second batch's
    std::vector<size_t> frag_at;
    for (size_t i = 0; i < g.cmds.size(); ++i)
      if (!g.cmds[i].is_write) frag_at.push_back(i);
    ASSERT_EQ(frag_at.size(), 6u);
    EXPECT_EQ(frag_at[3] - frag_at[2] - 1, 2u);
    for (size_t i = frag_at[2] + 1; i < frag_at[3]; ++i) {
      const uint32_t a = g.cmds[i].w.addr;
      EXPECT_TRUE(a == shadecore::kReg_light_diffuse || a == shadecore::kReg_light_diffuse + 1) << a;
    }
    EXPECT_EQ(frag_at[2] - frag_at[1], 1u);
    EXPECT_EQ(frag_at[5] - frag_at[4], 1u);
  }
  // a third draw under light 1 made a point light: three states, the slot takes both kinds (the union)
  d("glLightfv", {I(LIGHT1), I(POSITION), A({0, 0, 2, 1})});
  tri(0.35);
  h = shadecore::glfront::hand_over(d.gl, "t");
  ASSERT_EQ(h.scene.lighting_sets.size(), 3u);
  fr = shadecore::render::prepare(h.scene, h.meshes, h.settings);
  const auto& g = fr.groups[0];
  EXPECT_EQ(g.fs.num_lights(), 1);
  EXPECT_TRUE(g.fs.slot_can(0, shadecore::LightKind::Directional));
  EXPECT_TRUE(g.fs.slot_can(0, shadecore::LightKind::Point));
  EXPECT_EQ(g.state_changes, 2u);
  const auto cols = shadecore::render::run_cmodel(g);
  for (size_t i = 0; i < cols.size(); ++i)
    if (h.scene.objects[static_cast<size_t>(fr.vertex_object[g.dests[i].index])].lighting == 2) {
      EXPECT_NEAR(cols[i].c[0], 0.04 * 65536, 8);  // green only: N·L < 1 towards (0, 0, 2)
      EXPECT_GT(cols[i].c[1], 0.5 * 65536);
      EXPECT_LT(cols[i].c[1], 0.84 * 65536);
    }
  {  // the full core (every slot every kind) programmed for the same states: the same image
    auto hs = h.settings;
    hs.full_core = true;
    const auto ff = shadecore::render::prepare(h.scene, h.meshes, hs);
    ASSERT_EQ(ff.groups.size(), 1u);
    EXPECT_EQ(ff.groups[0].state_changes, 2u);
    const auto a = shadecore::render::resolve(fr, {cols});
    const auto b = shadecore::render::resolve(ff, {shadecore::render::run_cmodel(ff.groups[0])});
    EXPECT_EQ(shadecore::render::mismatching_pixels(a, b), 0u);
  }
  // a frame with one lighting state hands over none (the scene's own fields), as before
  Driver e;
  e.en(DEPTH_TEST);
  e.en(LIGHTING);
  e.en(LIGHT0);
  e("glViewport", {I(0), I(0), I(32), I(32)});
  e("glBegin", {I(TRIANGLES)});
  e.v3(0, 0, -0.5), e.v3(1, 0, -0.5), e.v3(0, 1, -0.5);
  e("glEnd");
  EXPECT_TRUE(shadecore::glfront::hand_over(e.gl, "t").scene.lighting_sets.empty());
}

// glMaterial changing more than one colour (or the shininess) between the vertices of a smooth-shaded primitive: GL
// lights each vertex with the material current at it (GL 2.1 §2.14.3). The hand-over names, for each vertex whose
// material differs from the provoking vertex's, an object of its material (Mesh::vertex_object); the back end lights
// that vertex in its material's batch, with that material's register writes, and the triangle interpolates the
// colours.
TEST(ReplayFrontend, MaterialChangingBetweenVerticesIsLitInMaterialBatches) {
  Driver d;
  d.en(DEPTH_TEST);
  d.en(LIGHTING);
  d.en(LIGHT0);  // GL's default light 0: directional along +z, white diffuse and specular
  d("glViewport", {I(0), I(0), I(32), I(32)});
  d("glLightModelfv", {I(0x0B53), A({0.5, 0.5, 0.5, 1})});  // GL_LIGHT_MODEL_AMBIENT
  d("glNormal3f", {F(0), F(0), F(1)});
  d("glBegin", {I(TRIANGLES)});
  d("glMaterialfv", {I(FRONT_AND_BACK), I(DIFFUSE), A({1, 0, 0, 1})});
  d("glMaterialfv", {I(FRONT_AND_BACK), I(AMBIENT), A({0, 0, 0, 1})});
  d.v3(-0.8, -0.8, -0.5);
  d("glMaterialfv", {I(FRONT_AND_BACK), I(DIFFUSE), A({0, 1, 0, 1})});  // two colours change: diffuse and ambient
  d("glMaterialfv", {I(FRONT_AND_BACK), I(AMBIENT), A({0, 0, 1, 1})});
  d.v3(0.8, -0.8, -0.5), d.v3(0, 0.8, -0.5);
  d("glEnd");
  const auto h = shadecore::glfront::hand_over(d.gl, "t");
  ASSERT_EQ(h.scene.objects.size(), 2u);
  ASSERT_EQ(h.meshes[0].vertex_object.size(), 3u);
  EXPECT_EQ(h.meshes[0].vertex_object, (std::vector<int>{1, 0, 0}));
  EXPECT_EQ(h.scene.materials[static_cast<size_t>(h.scene.objects[1].material)].diffuse, (shadecore::scene::Vec3{1, 0, 0}));
  EXPECT_EQ(h.stats.notes.at("glMaterial between a smooth primitive's vertices: vertices lit under their own material "
                             "(material batches)"),
            1u);
  const auto fr = shadecore::render::prepare(h.scene, h.meshes, h.settings);
  ASSERT_EQ(fr.groups.size(), 1u);
  const auto& g = fr.groups[0];
  const auto cols = shadecore::render::run_cmodel(g);
  ASSERT_EQ(cols.size(), 3u);
  int first = 0, others = 0;
  for (size_t i = 0; i < cols.size(); ++i) {
    const int o = fr.vertex_object[g.dests[i].index];
    // the first vertex: diffuse red, ambient 0 → (1, 0, 0); the others: diffuse green + 0.5 · ambient blue
    const std::array<double, 3> want = o == 1 ? std::array<double, 3>{1, 0, 0} : std::array<double, 3>{0, 1, 0.5};
    (o == 1 ? first : others)++;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(cols[i].c[c], want[static_cast<size_t>(c)] * 65535, 8) << "fragment " << i << " channel " << c;
  }
  EXPECT_EQ(first, 1);
  EXPECT_EQ(others, 2);
  // the two materials' batches with a material register write between them
  std::vector<size_t> frag_at;
  for (size_t i = 0; i < g.cmds.size(); ++i)
    if (!g.cmds[i].is_write) frag_at.push_back(i);
  ASSERT_EQ(frag_at.size(), 3u);
  size_t between = 0;
  for (size_t i = frag_at[0] + 1; i < frag_at[2]; ++i)
    if (g.cmds[i].is_write && g.cmds[i].w.addr >= shadecore::kReg_mat_diffuse && g.cmds[i].w.addr < shadecore::kReg_mat_diffuse + 3) ++between;
  EXPECT_GE(between, 2u);  // the diffuse colour from red to green (or back): two channels change
  // the image: the triangle interpolates the vertices' colours (red at the first vertex, green towards the others)
  const auto img = shadecore::render::resolve(fr, {cols});
  const size_t near_first = static_cast<size_t>(32 - 1 - 4) * 32 + 4;  // window (4, 4) from the bottom-left
  const size_t near_third = static_cast<size_t>(32 - 1 - 26) * 32 + 16;
  ASSERT_TRUE(img.covered[near_first] && img.covered[near_third]);
  EXPECT_GT(img.code[near_first * 3], img.code[near_first * 3 + 1]);
  EXPECT_LT(img.code[near_third * 3], img.code[near_third * 3 + 1]);
}

// GL_DEPTH_TEST off and glDepthMask(GL_FALSE) while drawing (GL 2.1 §4.1.5): with the test off a primitive's fragments
// are written whatever their depth, in drawing order, and do not update the depth buffer; with the mask off the test
// applies and depth is not written. Unlit triangles (the colour itself) overlapping at the window's centre, drawn
// through the back end and the C model: the colour at the centre says which one shows.
namespace depth_state {

// the centre pixel's colour channel that is lit (0 red, 1 green, 2 blue; −1 background or a mix)
int centre(const Gl& gl) {
  const auto h = shadecore::glfront::hand_over(gl, "t");
  const auto fr = shadecore::render::prepare(h.scene, h.meshes, h.settings);
  std::vector<std::vector<shadecore::Colour>> cols;
  for (const auto& g : fr.groups) cols.push_back(shadecore::render::run_cmodel(g));
  const auto img = shadecore::render::resolve(fr, cols);
  const size_t p = static_cast<size_t>(img.height / 2) * img.width + img.width / 2;
  if (!img.covered[p]) return -1;
  int lit = -1;
  for (int c = 0; c < 3; ++c)
    if (img.code[p * 3 + c] > (1u << img.F) / 2) {
      if (lit >= 0) return -1;
      lit = c;
    }
  return lit;
}

// glOrtho(-1, 1, -1, 1, 0, 2): eye z −0.5 is window z 0.25, −1 is 0.5, −1.5 is 0.75
void setup(Driver& d) {
  d("glViewport", {I(0), I(0), I(16), I(16)});
  d("glMatrixMode", {I(PROJECTION)});
  d("glOrtho", {F(-1), F(1), F(-1), F(1), F(0), F(2)});
  d("glMatrixMode", {I(MODELVIEW)});
}
void tri(Driver& d, int channel, double z) {
  d("glColor3f", {F(channel == 0), F(channel == 1), F(channel == 2)});
  d("glBegin", {I(TRIANGLES)});
  d.v3(-0.9, -0.9, z), d.v3(0.9, -0.9, z), d.v3(0, 0.9, z);
  d("glEnd");
}

}  // namespace depth_state

TEST(ReplayFrontend, DepthTestOffDrawsInDrawingOrderWithoutWritingDepth) {
  using namespace depth_state;
  Driver d;
  setup(d);
  d.en(DEPTH_TEST);
  tri(d, 0, -0.5);  // red, near
  EXPECT_EQ(centre(d.gl), 0);
  d("glDisable", {I(DEPTH_TEST)});
  tri(d, 1, -1.5);  // green, farther, depth test off: the later one shows
  EXPECT_TRUE(d.gl.refusals().empty());
  ASSERT_EQ(d.gl.triangles().size(), 2u);
  EXPECT_FALSE(d.gl.triangles()[1].depth_test);
  EXPECT_FALSE(d.gl.triangles()[1].depth_write);  // with the test off the depth buffer is not updated
  EXPECT_EQ(centre(d.gl), 1);
  {
    const auto h = shadecore::glfront::hand_over(d.gl, "t");
    ASSERT_EQ(h.scene.objects.size(), 2u);  // the same material: two runs by their depth state
    EXPECT_TRUE(h.scene.objects[0].depth_test);
    EXPECT_FALSE(h.scene.objects[1].depth_test);
  }
  d.en(DEPTH_TEST);
  tri(d, 2, -1.0);  // blue between them, test on: fails against red's depth (green wrote none)
  EXPECT_EQ(centre(d.gl), 1);
  tri(d, 2, -0.25);  // blue nearer than red: passes
  EXPECT_EQ(centre(d.gl), 2);
  // the same frame with the test on throughout: red stays
  Driver e;
  setup(e);
  e.en(DEPTH_TEST);
  tri(e, 0, -0.5);
  tri(e, 1, -1.5);
  EXPECT_EQ(centre(e.gl), 0);
  // depth test off for everything: plain drawing order (glDepthFunc is not consulted)
  Driver f;
  setup(f);
  f("glDepthFunc", {I(0x0207)});  // GL_ALWAYS: refused only while the test is on
  tri(f, 1, -1.5);
  tri(f, 0, -0.5);
  tri(f, 2, -1.9);
  EXPECT_TRUE(f.gl.refusals().empty());
  EXPECT_EQ(centre(f.gl), 2);
}

TEST(ReplayFrontend, DepthMaskFalseTestsWithoutWritingDepth) {
  using namespace depth_state;
  // the near triangle drawn with glDepthMask(GL_FALSE) writes no depth: a later farther one draws over it
  Driver d;
  setup(d);
  d.en(DEPTH_TEST);
  d("glDepthMask", {I(0)});
  tri(d, 0, -0.5);  // red, near
  d("glDepthMask", {I(1)});
  tri(d, 1, -1.5);  // green, farther
  EXPECT_TRUE(d.gl.refusals().empty());
  ASSERT_EQ(d.gl.triangles().size(), 2u);
  EXPECT_TRUE(d.gl.triangles()[0].depth_test);
  EXPECT_FALSE(d.gl.triangles()[0].depth_write);
  EXPECT_EQ(centre(d.gl), 1);
  // the test still applies with the mask off: a farther triangle fails against green's depth
  d("glDepthMask", {I(0)});
  tri(d, 2, -1.75);
  EXPECT_EQ(centre(d.gl), 1);
  tri(d, 2, -1.25);  // nearer than green: passes (and writes no depth)
  EXPECT_EQ(centre(d.gl), 2);
  // with the mask on, the near one stays
  Driver e;
  setup(e);
  e.en(DEPTH_TEST);
  tri(e, 0, -0.5);
  tri(e, 1, -1.5);
  EXPECT_EQ(centre(e.gl), 0);
}

using shadecore::test::tiny_stream;

std::string tiny_capture(int frames, bool core_profile = false) {
  return shadecore::test::container(tiny_stream(frames, core_profile));
}

TEST(ReplayFrontend, FramesAreTheCallsBetweenSwaps) {
  const std::string cap = tiny_capture(3);
  shadecore::trace::Reader r(cap, "tiny.trace");
  shadecore::glfront::ReplayOptions o;
  o.frame = 2;
  const auto h = shadecore::glfront::replay_frame(r, o, "tiny.trace");
  EXPECT_EQ(h.frame, 2u);
  EXPECT_EQ(h.first_call, 10u);     // calls 0..2 set up, frame 1 = 3..9 (swap at 9)
  EXPECT_EQ(h.snapshot_call, 15u);  // the last call before the second swap (16)
  EXPECT_EQ(h.stats.calls_in_frame, 6u);
  EXPECT_EQ(h.stats.primitives, 1u);
  EXPECT_EQ(h.api, "glx");
  EXPECT_EQ(h.scene.width, 32);
  ASSERT_EQ(h.meshes.size(), 1u);
  EXPECT_EQ(h.meshes[0].faces.size(), 1u);
  // past the end: one line naming how many frames there are
  shadecore::trace::Reader r2(cap, "tiny.trace");
  o.frame = 4;
  try {
    (void)shadecore::glfront::replay_frame(r2, o, "tiny.trace");
    ADD_FAILURE() << "no error";
  } catch (const ReplayError& e) {
    EXPECT_STREQ(e.what(), "tiny.trace: frame 4 is past the end: the capture has 3 complete frames (3 swaps)");
  }
  // a core-profile context
  shadecore::trace::Reader r3(tiny_capture(1, true), "core.trace");
  o.frame = 1;
  try {
    (void)shadecore::glfront::replay_frame(r3, o, "core.trace");
    ADD_FAILURE() << "no error";
  } catch (const ReplayError& e) {
    EXPECT_NE(std::string(e.what()).find("core-profile"), std::string::npos) << e.what();
  }
}

TEST(ReplayFrontend, CallSnapshotsAndArrayFrames) {
  const std::string cap = shadecore::test::container(tiny_stream(2, false, true));
  shadecore::trace::Reader r(cap, "a.trace");
  shadecore::glfront::ReplayOptions o;
  o.frame = 2;
  const auto h = shadecore::glfront::replay_frame(r, o, "a.trace");
  EXPECT_EQ(h.stats.primitives, 3u);  // the triangle, the array quad (COMPILE_AND_EXECUTE) and the list's quad
  EXPECT_EQ(h.stats.triangles, 5u);
  // --call: the image after call N, the frame from the last swap before it (here: frame 2 up to its glEnd)
  shadecore::trace::Reader r2(cap, "a.trace");
  shadecore::glfront::ReplayOptions oc;
  oc.call = h.first_call + 5;  // glClear, glBegin, 3 × glVertex3f, glEnd
  const auto hc = shadecore::glfront::replay_frame(r2, oc, "a.trace");
  EXPECT_EQ(hc.frame, 2u);
  EXPECT_EQ(hc.snapshot_call, h.first_call + 5);
  EXPECT_EQ(hc.stats.primitives, 1u);
}

// Mutated captures (bytes of the decompressed stream flipped, cut, duplicated; then recompressed): the reader and
// the front end either replay or refuse with a TraceError / ReplayError, never anything else.
TEST(ReplayFrontend, MutatedCapturesAreReplayedOrRefusedNeverCrash) {
  const std::string base = tiny_stream(2, false, true);
  uint64_t x = 0x9E3779B97F4A7C15ull;
  auto rnd = [&x] {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    return x;
  };
  int replayed = 0, refused = 0;
  for (int it = 0; it < 3000; ++it) {
    std::string m = base;
    const int edits = 1 + static_cast<int>(rnd() % 4);
    for (int e = 0; e < edits; ++e) {
      const size_t at = rnd() % m.size();
      switch (rnd() % 4) {
        case 0: m[at] = static_cast<char>(rnd()); break;
        case 1: m[at] = static_cast<char>(m[at] ^ (1 << (rnd() % 8))); break;
        case 2: m.erase(at, 1 + rnd() % 8); break;
        default: m.insert(at, m.substr(rnd() % m.size(), 1 + rnd() % 16)); break;
      }
      if (m.empty()) m = "x";
    }
    try {
      shadecore::trace::Reader r(shadecore::test::container(m), "m.trace");
      shadecore::glfront::ReplayOptions o;
      o.frame = 1 + rnd() % 2;
      (void)shadecore::glfront::replay_frame(r, o, "m.trace");
      ++replayed;
    } catch (const shadecore::trace::TraceError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    } catch (const ReplayError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  EXPECT_GT(refused, 100);
  EXPECT_GT(replayed, 10);
}

}  // namespace

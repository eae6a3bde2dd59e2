// SPDX-License-Identifier: Apache-2.0
// shadecore — a scene through OSMesa's fixed-function OpenGL 1.x (see shadecore/render/glref.hpp).
#include "shadecore/render/glref.hpp"

#include <GL/osmesa.h>
#include <GL/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "shadecore/render/mesh.hpp"
#include "shadecore/render/render.hpp"

namespace shadecore::glref {

using scene::Scene;
using scene::Shading;
using scene::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kGlMaxShininess = 128;  // GL_SHININESS is 0..128 (larger values are GL_INVALID_VALUE)

// gluPerspective(fovy, aspect, near, far) as the glFrustum it is.
void gl_perspective(const scene::Camera& c, double aspect) {
  const double ymax = c.near * std::tan(c.fovy * kPi / 360.0), xmax = ymax * aspect;
  glFrustum(-xmax, xmax, -ymax, ymax, c.near, c.far);
}

// gluLookAt(eye, center, up): the project's own view matrix (render::view_matrix, row-major) as GL's column-major.
void gl_look_at(const scene::Camera& c) {
  const std::array<double, 16> v = render::view_matrix(c);
  GLdouble m[16];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m[j * 4 + i] = v[i * 4 + j];
  glMultMatrixd(m);
}

void rgba(const Vec3& c, GLfloat out[4]) {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<GLfloat>(c[i]);
  out[3] = 1.0f;
}

// ---- GL light and material state: the scene's keys map here one to one ------------------------------------
// Called with the view matrix (and nothing else) on the modelview stack: GL transforms GL_POSITION (and
// GL_SPOT_DIRECTION) by it, so the scene's world coordinates become eye coordinates as in render::prepare.
void set_gl_light(int i, const scene::Light& L) {
  const GLenum id = static_cast<GLenum>(GL_LIGHT0 + i);
  GLfloat v[4];
  for (int k = 0; k < 4; ++k) v[k] = static_cast<GLfloat>(L.position[k]);
  glLightfv(id, GL_POSITION, v);  // w = 0: directional (GL normalises the direction), else positional
  rgba(L.ambient, v);
  glLightfv(id, GL_AMBIENT, v);
  rgba(L.diffuse, v);
  glLightfv(id, GL_DIFFUSE, v);
  rgba(L.specular, v);
  glLightfv(id, GL_SPECULAR, v);
  glLightf(id, GL_CONSTANT_ATTENUATION, static_cast<GLfloat>(L.kc));  // GL applies them to positional lights only,
  glLightf(id, GL_LINEAR_ATTENUATION, static_cast<GLfloat>(L.kl));    // as the core (directional: att = 1)
  glLightf(id, GL_QUADRATIC_ATTENUATION, static_cast<GLfloat>(L.kq));
  const GLfloat dir[3] = {static_cast<GLfloat>(L.spot_direction[0]), static_cast<GLfloat>(L.spot_direction[1]),
                         static_cast<GLfloat>(L.spot_direction[2])};
  glLightfv(id, GL_SPOT_DIRECTION, dir);                                  // transformed by the view matrix, like GL_POSITION
  glLightf(id, GL_SPOT_CUTOFF, static_cast<GLfloat>(L.spot_cutoff));      // degrees, 0..90 or 180 (= no spot)
  glLightf(id, GL_SPOT_EXPONENT, static_cast<GLfloat>(L.spot_exponent));  // 0..128
  glEnable(id);
}

// GL_FRONT from the material, GL_BACK from its "back" object (the front's colours when it has none); GL uses the
// back material only under GL_LIGHT_MODEL_TWO_SIDE, as the core its back colour bank.
void set_gl_material(const scene::Material& M) {
  GLfloat v[4];
  const scene::BackMaterial B = M.back_or_front();
  for (const GLenum face : {GLenum(GL_FRONT), GLenum(GL_BACK)}) {
    const bool bk = face == GL_BACK;
    rgba(bk ? B.emission : M.emission, v);
    glMaterialfv(face, GL_EMISSION, v);
    rgba(bk ? B.ambient : M.ambient, v);
    glMaterialfv(face, GL_AMBIENT, v);
    rgba(bk ? B.diffuse : M.diffuse, v);
    glMaterialfv(face, GL_DIFFUSE, v);
    rgba(bk ? B.specular : M.specular, v);
    glMaterialfv(face, GL_SPECULAR, v);
    // GL caps the exponent at 128; a larger one is not comparable (check_objects) and is drawn at 128.
    glMaterialf(face, GL_SHININESS, static_cast<GLfloat>(std::min(bk ? B.shininess : M.shininess, kGlMaxShininess)));
  }
}

void set_gl_light_model(const Scene& sc) {
  GLfloat v[4];
  rgba(sc.global_ambient, v);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, v);
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, sc.local_viewer ? GL_TRUE : GL_FALSE);
  glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, sc.separate_specular ? GL_SEPARATE_SPECULAR_COLOR : GL_SINGLE_COLOR);
  // GL_FALSE: back faces lit with the front normal and material, as the core without light_model bit 3; GL_TRUE:
  // back-facing polygons (glFrontFace(GL_CCW)) lit with −N and the GL_BACK material, as the core's two-sided mode
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, sc.two_side ? GL_TRUE : GL_FALSE);
}

// ---------------------------------------------------------------------------------------------------------

struct Context {
  OSMesaContext ctx = nullptr;
  ~Context() {
    if (ctx) OSMesaDestroyContext(ctx);
  }
};

void check_gl(const char* where) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw std::runtime_error(std::string("OpenGL error 0x") + [&] {
    char b[16];
    std::snprintf(b, sizeof b, "%04x", static_cast<unsigned>(e));
    return std::string(b);
  }() + " " + where);
}

// The object's polygons as render::prepare draws them: the fan (v0, vk, vk+1) of each face.
//   smooth: vertex normals in the fan's order (v0, vk, vk+1): GL_SMOOTH for Gouraud (Phong objects too, only for
//           coverage), and GL_FLAT for flat objects under flat_rule provoking_vertex (each triangle takes the colour
//           of its provoking vertex, GL_TRIANGLES' last: vk+1, as render::prepare);
//   flat:   (flat_rule centroid) the face's Newell normal, GL_FLAT; each fan triangle is sent as (vk, vk+1, v0) so
//           that its provoking vertex (GL_TRIANGLES: the last) is v0 for every triangle of the face: one colour per
//           face, lit at v0.
//   ids:    no normals (lighting off, the colour is set by the caller).
// `colour` (GL_COLOR_MATERIAL on): glColor per vertex, the mesh's vertex colours or else *colour (the object's
// `color`); flat: the mean of the face's vertex colours at every vertex, as render::prepare's face fragment.
enum class Draw { Smooth, Flat, Ids };
void draw_mesh(const scene::Mesh& m, Draw how, const Vec3* colour = nullptr) {
  auto vcol = [&](int v) -> const Vec3& { return m.col.empty() ? *colour : m.col[static_cast<size_t>(v)]; };
  glBegin(GL_TRIANGLES);
  for (const auto& face : m.faces) {
    Vec3 fn{0, 0, 0}, fc = colour ? *colour : Vec3{0, 0, 0};
    if (how == Draw::Flat) fn = scene::polygon_normal(m.pos, face);
    if (how == Draw::Flat && colour && !m.col.empty()) {  // the mean of the face's vertex colours (render::prepare's)
      fc = {0, 0, 0};
      for (int v : face)
        for (int i = 0; i < 3; ++i) fc[i] += vcol(v)[i] / static_cast<double>(face.size());
    }
    for (size_t k = 1; k + 1 < face.size(); ++k) {
      const int tv[3] = {face[0], face[k], face[k + 1]};
      for (int q = 0; q < 3; ++q) {
        const int v = how == Draw::Flat ? tv[(q + 1) % 3] : tv[q];
        if (how == Draw::Smooth) glNormal3d(m.nrm[v][0], m.nrm[v][1], m.nrm[v][2]);
        if (how == Draw::Flat) glNormal3d(fn[0], fn[1], fn[2]);
        if (colour && how != Draw::Ids) {
          const Vec3& c = how == Draw::Flat ? fc : vcol(v);
          glColor3d(c[0], c[1], c[2]);
        }
        glVertex3d(m.pos[v][0], m.pos[v][1], m.pos[v][2]);
      }
    }
  }
  glEnd();
}

GLenum gl_colour_material(ColourMaterial m) {
  switch (m) {
    case ColourMaterial::Emission: return GL_EMISSION;
    case ColourMaterial::Ambient: return GL_AMBIENT;
    case ColourMaterial::Diffuse: return GL_DIFFUSE;
    case ColourMaterial::Specular: return GL_SPECULAR;
    case ColourMaterial::AmbientAndDiffuse: return GL_AMBIENT_AND_DIFFUSE;
  }
  return GL_AMBIENT_AND_DIFFUSE;
}

void object_transform(const scene::Transform& t) {
  glTranslated(t.translate[0], t.translate[1], t.translate[2]);
  for (const auto& r : t.rotate) glRotated(r.angle, r.axis[0], r.axis[1], r.axis[2]);
  glScaled(t.scale[0], t.scale[1], t.scale[2]);
}

// GL's projection · modelview (column-major), read back.
std::array<double, 16> current_mvp() {
  GLdouble p[16], m[16];
  glGetDoublev(GL_PROJECTION_MATRIX, p);
  glGetDoublev(GL_MODELVIEW_MATRIX, m);
  std::array<double, 16> r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double acc = 0;
      for (int k = 0; k < 4; ++k) acc += p[k * 4 + row] * m[c * 4 + k];
      r[static_cast<size_t>(c * 4 + row)] = acc;
    }
  return r;
}

bool nonzero(const Vec3& c) { return c[0] != 0 || c[1] != 0 || c[2] != 0; }

}  // namespace

GlImage render_gl(const Scene& sc, render::MeshSource& meshes, const GlSettings& s) {
  GlImage out;
  out.width = s.width > 0 ? s.width : sc.width;
  out.height = s.height > 0 ? s.height : sc.height;
  const int W = out.width, H = out.height;
  // The reference is llvmpipe (Debian's OSMesa is gallium: softpipe snaps vertices differently); GALLIUM_DRIVER
  // set by the caller still wins, and GlImage::renderer says what drew the image.
  ::setenv("GALLIUM_DRIVER", "llvmpipe", 0);
  Context c;
  c.ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!c.ctx) throw std::runtime_error("OSMesa: cannot create an RGBA context with a 24-bit depth buffer");
  std::vector<GLubyte> buf(static_cast<size_t>(W) * H * 4);
  if (!OSMesaMakeCurrent(c.ctx, buf.data(), GL_UNSIGNED_BYTE, W, H))
    throw std::runtime_error("OSMesa: cannot bind a " + std::to_string(W) + "x" + std::to_string(H) + " buffer");
  auto str = [](GLenum e) {
    const GLubyte* p = glGetString(e);
    return p ? std::string(reinterpret_cast<const char*>(p)) : std::string();
  };
  out.renderer = str(GL_RENDERER);
  out.version = str(GL_VERSION);

  glViewport(0, 0, W, H);
  glDepthRange(0.0, 1.0);
  glDisable(GL_CULL_FACE);  // both faces drawn, as the rasteriser
  glFrontFace(GL_CCW);      // counter-clockwise in window coordinates is front (GL's default; raster::ScreenTri::back)
  glDisable(GL_DITHER);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glClearDepth(1.0);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  gl_perspective(sc.camera, static_cast<double>(W) / H);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  gl_look_at(sc.camera);

  // Pass 1: the lit image.
  glClearColor(static_cast<GLfloat>(sc.background[0]), static_cast<GLfloat>(sc.background[1]),
               static_cast<GLfloat>(sc.background[2]), 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_LIGHTING);
  // shadecore's host always sends unit eye-space normals (the cofactor matrix, then normalised): GL_NORMALIZE
  // is the same for any transform, non-uniform scale included.
  glEnable(GL_NORMALIZE);
  set_gl_light_model(sc);
  for (size_t j = 0; j < sc.lights.size(); ++j) set_gl_light(static_cast<int>(j), sc.lights[j]);
  for (size_t oi = 0; oi < sc.objects.size(); ++oi) {
    const auto& o = sc.objects[oi];
    const Shading sh = s.mode ? *s.mode : o.shading;
    // GL_COLOR_MATERIAL writes the current colour into the material for good: off while the object's materials
    // are set (every object sets all of them), then on with its mode (GL_FRONT_AND_BACK, as the core's register)
    glDisable(GL_COLOR_MATERIAL);
    set_gl_material(sc.materials[static_cast<size_t>(o.material)]);
    if (o.colour_material) {
      glColorMaterial(GL_FRONT_AND_BACK, gl_colour_material(*o.colour_material));
      glEnable(GL_COLOR_MATERIAL);
    }
    glShadeModel(sh == Shading::Flat ? GL_FLAT : GL_SMOOTH);
    glPushMatrix();
    object_transform(o.transform);
    out.object_mvp.push_back(current_mvp());
    const bool by_face = sh == Shading::Flat && sc.flat_rule == scene::FlatRule::Centroid;
    draw_mesh(*meshes.get(static_cast<int>(oi)), by_face ? Draw::Flat : Draw::Smooth,
              o.colour_material ? &o.colour : nullptr);
    glPopMatrix();
  }
  glFinish();
  check_gl("while drawing the lit image");
  const size_t np = static_cast<size_t>(W) * H;
  out.rgb.resize(np * 3);
  for (int y = 0; y < H; ++y)  // OSMesa's row 0 is the bottom one
    for (int x = 0; x < W; ++x)
      for (int ch = 0; ch < 3; ++ch)
        out.rgb[(static_cast<size_t>(y) * W + x) * 3 + ch] = buf[(static_cast<size_t>(H - 1 - y) * W + x) * 4 + ch];

  // Pass 2: object ids (index + 1 as 24-bit colour), the same vertices through the same transforms and test.
  glDisable(GL_COLOR_MATERIAL);
  glDisable(GL_LIGHTING);
  glShadeModel(GL_FLAT);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (size_t oi = 0; oi < sc.objects.size(); ++oi) {
    const auto id = static_cast<uint32_t>(oi + 1);
    glColor3ub(static_cast<GLubyte>(id & 255), static_cast<GLubyte>((id >> 8) & 255), static_cast<GLubyte>((id >> 16) & 255));
    glPushMatrix();
    object_transform(sc.objects[oi].transform);
    draw_mesh(*meshes.get(static_cast<int>(oi)), Draw::Ids);
    glPopMatrix();
  }
  glFinish();
  check_gl("while drawing the object ids");
  out.object.resize(np);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const GLubyte* p = &buf[(static_cast<size_t>(H - 1 - y) * W + x) * 4];
      out.object[static_cast<size_t>(y) * W + x] = static_cast<int32_t>(p[0] | (p[1] << 8) | (p[2] << 16)) - 1;
    }
  OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
  return out;
}

std::vector<ObjectCheck> check_objects(const Scene& sc, const std::vector<Shading>& shading) {
  std::vector<ObjectCheck> out(sc.objects.size());
  bool any_light_spec = false;  // over every lighting state (a scene file has one)
  const std::vector<scene::LightingSet> states = sc.lighting_states();
  for (const auto& st : states)
    for (const auto& L : st.lights) any_light_spec = any_light_spec || nonzero(L.specular);
  for (size_t oi = 0; oi < sc.objects.size(); ++oi) {
    auto& c = out[oi];
    const auto& o = sc.objects[oi];
    const auto& M = sc.materials[static_cast<size_t>(o.material)];
    const Shading sh = shading.at(oi);
    auto no = [&c](std::string why) {
      c.comparable = false;
      c.reasons.push_back(std::move(why));
    };
    if (sh == Shading::Phong) no("phong shading (per-fragment lighting) has no fixed-function equivalent (GL draws it Gouraud)");
    // under two_side the back colours are drawn too (GL_BACK): a back-only specular colour counts
    const bool back_spec = sc.two_side && M.back && nonzero(M.back->specular);
    // colour material `specular`: the object's colours are the specular colour (counted as non-zero)
    const bool cm_spec = o.colour_material == ColourMaterial::Specular;
    const bool spec = (M.has_specular() || back_spec || cm_spec) && any_light_spec;
    if (o.colour_material)
      c.notes.push_back(std::string("GL_COLOR_MATERIAL: glColorMaterial(GL_FRONT_AND_BACK, ") +
                        scene::to_string(o.colour_material) + "), glColor per vertex");
    if (spec) {
      if (!sc.blinn) no("reflection 'phong' (R·V): fixed-function GL has only Blinn's N·H");
      // under two_side the back's shininess too (glMaterialf(GL_BACK, GL_SHININESS, ...))
      const int bn = sc.two_side ? M.back_or_front().shininess : M.shininess;
      for (const int n : bn == M.shininess ? std::vector<int>{M.shininess} : std::vector<int>{M.shininess, bn})
        if (n > kGlMaxShininess) no("shininess " + std::to_string(n) + " > 128, GL's cap (GL draws it at 128)");
      if (M.normalization) no("energy normalisation of the specular term has no GL equivalent");
      c.notes.push_back("GL_SHININESS " + std::to_string(std::min(M.shininess, kGlMaxShininess)) +
                        (bn == M.shininess ? std::string() : ", GL_BACK " + std::to_string(std::min(bn, kGlMaxShininess))));
    }
    if (sh == Shading::Flat && sc.flat_rule == scene::FlatRule::ProvokingVertex) {
      // both: GL_FLAT's rule, the last vertex of each fan triangle with its vertex normal and position
      c.notes.push_back("flat: GL_FLAT, each triangle lit at its provoking (last) vertex with the vertex normal (flat_rule provoking_vertex)");
    } else if (sh == Shading::Flat) {
      // shadecore lights the face's centroid, GL the provoking vertex (here v0 of the face): equal only when
      // the lighting does not depend on the position (directional lights; a local viewer only without specular).
      bool positional = false, local_viewer = false;
      for (const auto& st : states) {
        local_viewer = local_viewer || st.local_viewer;
        for (const auto& L : st.lights)
          positional = positional ||
                       (L.position[3] != 0.0 && (nonzero(L.ambient) || nonzero(L.diffuse) || (spec && nonzero(L.specular))));
      }
      const bool viewer = spec && local_viewer;
      if (positional || viewer)
        no(std::string("flat: shadecore lights the face centroid, GL the provoking vertex, and the lighting depends on the position (") +
           (positional ? "a positional light" : "") + (positional && viewer ? ", " : "") + (viewer ? "local viewer" : "") +
           "; flat_rule provoking_vertex makes it comparable)");
      else
        c.notes.push_back("flat: the face normal at GL's provoking vertex; the lighting does not depend on the position");
    }
  }
  return out;
}

std::vector<int32_t> object_map(const render::Frame& fr) {
  std::vector<int32_t> m(static_cast<size_t>(fr.width) * fr.height, -1);
  for (int y = 0; y < fr.height; ++y)
    for (int x = 0; x < fr.width; ++x) {
      const int32_t id = fr.raster.at(x, y);
      if (id >= 0) m[static_cast<size_t>(y) * fr.width + x] = fr.tri_object[static_cast<size_t>(fr.raster.tris()[static_cast<size_t>(id)].source)];
    }
  return m;
}

namespace {

struct Hist {
  std::array<uint64_t, 256> n{};
  uint64_t total = 0, sum = 0;
  int max = -1, max_x = -1, max_y = -1;
  void add(int d, int x, int y) {
    ++n[static_cast<size_t>(d)];
    ++total;
    sum += static_cast<uint64_t>(d);
    if (d > max) max = d, max_x = x, max_y = y;
  }
  int percentile(double p) const {  // nearest rank: the smallest d with at least ⌈p·N⌉ values <= d
    if (total == 0) return 0;
    const auto rank = static_cast<uint64_t>(std::max(1.0, std::ceil(p * static_cast<double>(total))));
    uint64_t acc = 0;
    for (int d = 0; d < 256; ++d) {
      acc += n[static_cast<size_t>(d)];
      if (acc >= rank) return d;
    }
    return 255;
  }
  DiffStats stats(int tol) const {
    DiffStats s;
    s.pixels = total;
    if (!total) return s;
    s.p50 = percentile(0.50);
    s.p99 = percentile(0.99);
    s.max = max;
    s.max_x = max_x, s.max_y = max_y;
    s.mean = static_cast<double>(sum) / static_cast<double>(total);
    for (int d = tol + 1; d < 256; ++d) s.above += n[static_cast<size_t>(d)];
    return s;
  }
};

}  // namespace

Comparison compare(int width, int height, const std::vector<uint8_t>& exact_rgb, const std::vector<int32_t>& exact_object,
                   const GlImage& gl, const std::vector<ObjectCheck>& checks, int tolerance, bool all_objects) {
  const size_t np = static_cast<size_t>(width) * height;
  if (gl.width != width || gl.height != height || exact_rgb.size() != np * 3 || exact_object.size() != np ||
      gl.rgb.size() != np * 3 || gl.object.size() != np)
    throw std::invalid_argument("gl-compare: images of different sizes");
  Comparison r;
  r.tolerance = tolerance;
  r.diff_rgb.assign(np * 3, 0);
  Hist comp, all;
  std::vector<Hist> per(checks.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t p = static_cast<size_t>(y) * width + x;
      const int32_t a = exact_object[p], b = gl.object[p];
      uint8_t* d = &r.diff_rgb[p * 3];
      r.covered_exact += a >= 0;
      r.covered_gl += b >= 0;
      if (a != b && r.mismatches.size() < Comparison::kMaxMismatches) r.mismatches.push_back({x, y, a, b});
      if ((a >= 0) != (b >= 0)) {
        ++r.coverage_mismatch;
        d[0] = d[1] = 255;  // yellow
        continue;
      }
      if (a < 0) continue;
      ++r.covered_both;
      if (a != b) {
        ++r.object_mismatch;
        d[0] = d[2] = 255;  // magenta
        continue;
      }
      int diff = 0, sign = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const int e = static_cast<int>(exact_rgb[p * 3 + ch]) - static_cast<int>(gl.rgb[p * 3 + ch]);
        if (std::abs(e) > diff) diff = std::abs(e), sign = e > 0 ? 1 : -1;
      }
      all.add(diff, x, y);
      if (static_cast<size_t>(a) < per.size()) per[static_cast<size_t>(a)].add(diff, x, y);
      const bool counts = all_objects || (static_cast<size_t>(a) < checks.size() && checks[static_cast<size_t>(a)].comparable);
      if (!counts) {
        for (int ch = 0; ch < 3; ++ch) d[ch] = static_cast<uint8_t>(exact_rgb[p * 3 + ch] / 4);
        continue;
      }
      comp.add(diff, x, y);
      if (diff == 0) continue;
      if (diff <= tolerance) {
        d[0] = d[1] = d[2] = static_cast<uint8_t>(std::min(255, 60 * diff));
      } else {
        d[sign > 0 ? 0 : 2] = static_cast<uint8_t>(std::min(255, 128 + 16 * diff));
      }
    }
  r.comparable = comp.stats(tolerance);
  r.all = all.stats(tolerance);
  for (const auto& h : per) r.per_object.push_back(h.stats(tolerance));
  r.pass = r.comparable.pixels > 0 && r.comparable.p99 <= tolerance && r.coverage_mismatch == 0 && r.object_mismatch == 0;
  return r;
}

void explain_mismatches(const Scene& sc, render::MeshSource& meshes, const GlImage& gl, Comparison& cmp) {
  cmp.mismatch_near_edge = 0;
  const double W = gl.width, H = gl.height;
  for (size_t oi = 0; oi < sc.objects.size() && oi < gl.object_mvp.size(); ++oi) {
    std::vector<size_t> mine;
    for (size_t i = 0; i < cmp.mismatches.size(); ++i)
      if (cmp.mismatches[i].exact_object == static_cast<int32_t>(oi) || cmp.mismatches[i].gl_object == static_cast<int32_t>(oi))
        mine.push_back(i);
    if (mine.empty()) continue;
    const auto& mvp = gl.object_mvp[oi];
    const auto mesh = meshes.get(static_cast<int>(oi));
    // window coordinates, y down (row 0 at the top), as the rasteriser; nothing for w <= 0
    std::vector<std::array<double, 2>> win(mesh->pos.size());
    std::vector<char> ok(mesh->pos.size(), 0);
    for (size_t v = 0; v < mesh->pos.size(); ++v) {
      const auto& p = mesh->pos[v];
      double c[4];
      for (int r = 0; r < 4; ++r) c[r] = mvp[static_cast<size_t>(r)] * p[0] + mvp[static_cast<size_t>(4 + r)] * p[1] + mvp[static_cast<size_t>(8 + r)] * p[2] + mvp[static_cast<size_t>(12 + r)];
      if (!(c[3] > 0)) continue;
      ok[v] = 1;
      win[v] = {(c[0] / c[3] * 0.5 + 0.5) * W, (0.5 - c[1] / c[3] * 0.5) * H};
    }
    for (const auto& face : mesh->faces)
      for (size_t k = 1; k + 1 < face.size(); ++k) {
        const int tv[3] = {face[0], face[k], face[k + 1]};
        if (!ok[static_cast<size_t>(tv[0])] || !ok[static_cast<size_t>(tv[1])] || !ok[static_cast<size_t>(tv[2])]) continue;
        const auto& A = win[static_cast<size_t>(tv[0])];
        const auto& B = win[static_cast<size_t>(tv[1])];
        const auto& C = win[static_cast<size_t>(tv[2])];
        const double area = (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]);
        if (area == 0) continue;
        const double sgn = area > 0 ? 1 : -1;
        for (size_t i : mine) {
          auto& m = cmp.mismatches[i];
          const double px = m.x + 0.5, py = m.y + 0.5;
          if (px < std::min({A[0], B[0], C[0]}) - 1 || px > std::max({A[0], B[0], C[0]}) + 1 ||
              py < std::min({A[1], B[1], C[1]}) - 1 || py > std::max({A[1], B[1], C[1]}) + 1)
            continue;
          const std::array<double, 2>* P[3] = {&A, &B, &C};
          double inside = 1e300;  // the smallest signed distance to the three edges (> 0 inside)
          for (int e = 0; e < 3; ++e) {
            const auto& a = *P[e];
            const auto& b = *P[(e + 1) % 3];
            const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
            if (len == 0) continue;
            inside = std::min(inside, sgn * (ex * (py - a[1]) - ey * (px - a[0])) / len);
          }
          if (inside < -1.0 / 64) continue;  // not near this triangle
          const double d = std::abs(inside);
          if (m.edge_px < 0 || d < m.edge_px) m.edge_px = d;
        }
      }
  }
  for (const auto& m : cmp.mismatches)
    if (m.edge_px >= 0 && m.edge_px <= Comparison::kSnapPx) ++cmp.mismatch_near_edge;
  cmp.mismatches_explained = cmp.coverage_mismatch + cmp.object_mismatch == cmp.mismatch_near_edge;
}

}  // namespace shadecore::glref

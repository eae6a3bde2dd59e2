// SPDX-License-Identifier: Apache-2.0
// shadecore — the GL 1.x front end of `shadecore replay` (see shadecore/glfront/frontend.hpp). OpenGL 2.1
// (compatibility profile) rules throughout; the GL enumerant values are the spec's (gl.h).
#include "shadecore/glfront/frontend.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <set>
#include <unordered_map>

namespace shadecore::glfront {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int64_t kMaxDrawVertices = int64_t{1} << 26;  // one array draw: at most 64 Mi vertices (a corrupt count)
constexpr uint64_t kMaxExecuted = uint64_t{1} << 25;    // calls executed in one frame, display lists expanded

// GL enumerants (OpenGL 2.1, gl.h)
enum : uint32_t {
  GL_POINTS = 0, GL_LINES = 1, GL_LINE_LOOP = 2, GL_LINE_STRIP = 3, GL_TRIANGLES = 4, GL_TRIANGLE_STRIP = 5,
  GL_TRIANGLE_FAN = 6, GL_QUADS = 7, GL_QUAD_STRIP = 8, GL_POLYGON = 9,
  GL_MODELVIEW = 0x1700, GL_PROJECTION = 0x1701, GL_TEXTURE = 0x1702,
  GL_LIGHT0 = 0x4000,
  GL_AMBIENT = 0x1200, GL_DIFFUSE = 0x1201, GL_SPECULAR = 0x1202, GL_POSITION = 0x1203, GL_SPOT_DIRECTION = 0x1204,
  GL_SPOT_EXPONENT = 0x1205, GL_SPOT_CUTOFF = 0x1206, GL_CONSTANT_ATTENUATION = 0x1207, GL_LINEAR_ATTENUATION = 0x1208,
  GL_QUADRATIC_ATTENUATION = 0x1209,
  GL_EMISSION = 0x1600, GL_SHININESS = 0x1601, GL_AMBIENT_AND_DIFFUSE = 0x1602, GL_COLOR_INDEXES = 0x1603,
  GL_FRONT = 0x0404, GL_BACK = 0x0405, GL_FRONT_AND_BACK = 0x0408,
  GL_LIGHT_MODEL_LOCAL_VIEWER = 0x0B51, GL_LIGHT_MODEL_TWO_SIDE = 0x0B52, GL_LIGHT_MODEL_AMBIENT = 0x0B53,
  GL_LIGHT_MODEL_COLOR_CONTROL = 0x81F8, GL_SEPARATE_SPECULAR_COLOR = 0x81FA,
  GL_LIGHTING = 0x0B50, GL_COLOR_MATERIAL = 0x0B57, GL_NORMALIZE = 0x0BA1, GL_RESCALE_NORMAL = 0x803A,
  GL_CULL_FACE = 0x0B44, GL_DEPTH_TEST = 0x0B71, GL_SCISSOR_TEST = 0x0C11, GL_DITHER = 0x0BD0,
  GL_FLAT = 0x1D00, GL_SMOOTH = 0x1D01, GL_CW = 0x0900, GL_CCW = 0x0901,
  GL_LESS = 0x0201, GL_LEQUAL = 0x0203,
  GL_COLOR_BUFFER_BIT = 0x4000, GL_DEPTH_BUFFER_BIT = 0x0100,
  GL_VERTEX_ARRAY = 0x8074, GL_NORMAL_ARRAY = 0x8075, GL_COLOR_ARRAY = 0x8076,
  GL_BYTE = 0x1400, GL_UNSIGNED_BYTE = 0x1401, GL_SHORT = 0x1402, GL_UNSIGNED_SHORT = 0x1403, GL_INT = 0x1404,
  GL_UNSIGNED_INT = 0x1405, GL_FLOAT = 0x1406, GL_DOUBLE = 0x140A,
  GL_COMPILE = 0x1300, GL_COMPILE_AND_EXECUTE = 0x1301,
  GL_FILL = 0x1B02,
};

// Capabilities the core does not have: a primitive drawn with one on is drawn (coverage, occlusion) but not compared.
const std::map<uint32_t, std::string>& excluding_caps() {
  static const std::map<uint32_t, std::string> m = {
      {0x0DE0, "GL_TEXTURE_1D"}, {0x0DE1, "GL_TEXTURE_2D"}, {0x806F, "GL_TEXTURE_3D"}, {0x8513, "GL_TEXTURE_CUBE_MAP"},
      {0x0C60, "GL_TEXTURE_GEN_S"}, {0x0C61, "GL_TEXTURE_GEN_T"}, {0x0C62, "GL_TEXTURE_GEN_R"},
      {0x0C63, "GL_TEXTURE_GEN_Q"}, {0x0B60, "GL_FOG"}, {0x0BE2, "GL_BLEND"}, {0x0BC0, "GL_ALPHA_TEST"},
      {0x0B42, "GL_POLYGON_STIPPLE"}, {0x0B41, "GL_POLYGON_SMOOTH"}, {0x0BF2, "GL_COLOR_LOGIC_OP"},
      {0x8037, "GL_POLYGON_OFFSET_FILL"}};
  return m;
}
// Capabilities whose effect on which pixels are drawn cannot be known here: a frame drawing with one on is refused.
const std::map<uint32_t, std::string>& refusing_caps() {
  static const std::map<uint32_t, std::string> m = {
      {0x0B90, "GL_STENCIL_TEST"}, {0x3000, "GL_CLIP_PLANE0"}, {0x3001, "GL_CLIP_PLANE1"}, {0x3002, "GL_CLIP_PLANE2"},
      {0x3003, "GL_CLIP_PLANE3"}, {0x3004, "GL_CLIP_PLANE4"}, {0x3005, "GL_CLIP_PLANE5"}, {0x0D80, "GL_AUTO_NORMAL"}};
  return m;
}

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }
Mat4 mul(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[i * 4 + k] * b[k * 4 + j];
      r[i * 4 + j] = s;
    }
  return r;
}
Vec4 xform(const Mat4& m, const Vec4& v) {
  Vec4 r{};
  for (int i = 0; i < 4; ++i) r[i] = m[i * 4] * v[0] + m[i * 4 + 1] * v[1] + m[i * 4 + 2] * v[2] + m[i * 4 + 3] * v[3];
  return r;
}
// The inverse of the upper-left 3×3 (row-major), or nullopt if singular.
std::optional<std::array<double, 9>> inverse3(const Mat4& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], i = m[10];
  const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
  const double det = a * A + b * B + c * C;
  if (det == 0 || !std::isfinite(det)) return std::nullopt;
  return std::array<double, 9>{A / det, -(b * i - c * h) / det, (b * f - c * e) / det,
                               B / det, (a * i - c * g) / det, -(a * f - c * d) / det,
                               C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
}
double len3(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

bool starts(const std::string& s, const char* p) { return s.rfind(p, 0) == 0; }

}  // namespace

bool MaterialState::operator==(const MaterialState& o) const {
  return ambient == o.ambient && diffuse == o.diffuse && specular == o.specular && emission == o.emission &&
         shininess == o.shininess;
}
bool LightState::operator==(const LightState& o) const {
  if (enabled != o.enabled) return false;
  if (!enabled) return true;
  return ambient == o.ambient && diffuse == o.diffuse && specular == o.specular && position == o.position &&
         spot_direction == o.spot_direction && spot_exponent == o.spot_exponent && spot_cutoff == o.spot_cutoff &&
         kc == o.kc && kl == o.kl && kq == o.kq;
}
bool LightingState::operator==(const LightingState& o) const {
  return lighting == o.lighting && lights == o.lights && model_ambient == o.model_ambient &&
         local_viewer == o.local_viewer && two_side == o.two_side && separate_specular == o.separate_specular;
}

// ---- the state machine ------------------------------------------------------------------------------------

struct Array {
  bool enabled = false;
  int size = 4;
  uint32_t type = GL_FLOAT;
  int stride = 0;
  std::shared_ptr<const std::string> data;  // the blob the capture holds (user memory), or null
  bool from_buffer = false;                 // a buffer object offset (not held by the capture)
};

struct Gl::Impl {
  Gl& g;
  std::set<uint32_t> enabled;
  uint32_t shade = GL_SMOOTH, front_face = GL_CCW, cull_mode = GL_BACK, depth_func = GL_LESS;
  bool depth_mask = true;
  std::array<bool, 4> colour_mask{true, true, true, true};
  uint32_t cm_face = GL_FRONT_AND_BACK, cm_mode = GL_AMBIENT_AND_DIFFUSE;
  std::array<int, 4> scissor{0, 0, 0, 0};
  std::array<double, 2> depth_range{0, 1};
  double clear_depth = 1;
  std::array<uint32_t, 2> polygon_mode{GL_FILL, GL_FILL};
  Array vertex, normal, colour;
  // display lists
  uint32_t compiling = 0;  // list being compiled (0: none)
  bool compile_execute = false;
  std::shared_ptr<std::vector<trace::Call>> compiled;
  uint32_t list_base = 0;
  int list_depth = 0;
  // glBegin/glEnd
  bool in_begin = false;
  uint32_t begin_mode = 0;
  std::vector<GlVertex> verts;
  uint32_t primitive_no = 0;
  // material snapshot ids
  std::map<std::pair<size_t, size_t>, uint32_t> mat_ids;

  explicit Impl(Gl& gl) : g(gl) {}

  bool on(uint32_t cap) const { return enabled.count(cap) != 0; }
  void note(const std::string& what) { ++g.stats_.notes[what]; }
  void unsupported(const std::string& name) { ++g.stats_.unsupported[name]; }
  void refuse(const std::string& why) {
    if (std::find(g.refusals_.begin(), g.refusals_.end(), why) == g.refusals_.end()) g.refusals_.push_back(why);
  }

  Mat4& top() {
    if (matrix() == GL_PROJECTION) return g.proj_.back();
    if (matrix() == GL_TEXTURE) return g.tex_.back();
    return g.mv_.back();
  }
  std::vector<Mat4>& stack() {
    if (matrix() == GL_PROJECTION) return g.proj_;
    if (matrix() == GL_TEXTURE) return g.tex_;
    return g.mv_;
  }
  uint32_t matrix() const { return g.matrix_mode_; }

  // ---- argument helpers
  static double num(const trace::Call& c, size_t k) { return c.arg(k).number(); }
  static int64_t integer(const trace::Call& c, size_t k) { return c.arg(k).integer(); }
  // The numbers of a vector argument (an array value, or a blob of `type`).
  static std::vector<double> vec(const trace::Call& c, size_t k) {
    const trace::Value& v = c.arg(k).machine();
    std::vector<double> out;
    if (v.kind == trace::Value::Kind::Array) {
      for (const auto& e : v.items) out.push_back(e.number());
    } else if (v.is_number()) {
      out.push_back(v.number());
    } else if (v.kind != trace::Value::Kind::Null) {
      throw trace::TraceError("call " + std::to_string(c.no) + " " + c.name() + ": argument " + std::to_string(k) +
                              " is not an array of numbers");
    }
    return out;
  }
  static Mat4 matrix_arg(const trace::Call& c, size_t k) {  // column-major 16 → row-major
    const auto v = vec(c, k);
    if (v.size() != 16) throw trace::TraceError("call " + std::to_string(c.no) + " " + c.name() + ": a matrix of " + std::to_string(v.size()) + " values");
    Mat4 m{};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) m[i * 4 + j] = v[j * 4 + i];
    return m;
  }

  // ---- matrices
  void mult(const Mat4& m) { top() = mul(top(), m); }
  void rotate(double angle, double x, double y, double z) {
    const double l = std::sqrt(x * x + y * y + z * z);
    if (l == 0) return;
    x /= l, y /= l, z /= l;
    const double th = angle * kPi / 180.0, c = std::cos(th), s = std::sin(th), k = 1 - c;
    mult({x * x * k + c, x * y * k - z * s, x * z * k + y * s, 0, y * x * k + z * s, y * y * k + c, y * z * k - x * s, 0,
          x * z * k - y * s, y * z * k + x * s, z * z * k + c, 0, 0, 0, 0, 1});
  }

  // ---- lighting state
  MaterialState& material(bool back) { return g.mat_[back ? 1 : 0]; }
  void set_material(uint32_t face, uint32_t pname, const std::vector<double>& p, const std::string& name) {
    for (int b = 0; b < 2; ++b) {
      if (face == GL_FRONT && b == 1) continue;
      if (face == GL_BACK && b == 0) continue;
      MaterialState& m = material(b == 1);
      auto rgba = [&](Vec4& dst) {
        if (p.size() < 4) throw trace::TraceError(name + ": fewer than 4 values");
        for (int i = 0; i < 4; ++i) dst[i] = p[i];
      };
      switch (pname) {
        case GL_AMBIENT: rgba(m.ambient); break;
        case GL_DIFFUSE: rgba(m.diffuse); break;
        case GL_SPECULAR: rgba(m.specular); break;
        case GL_EMISSION: rgba(m.emission); break;
        case GL_AMBIENT_AND_DIFFUSE: rgba(m.ambient); rgba(m.diffuse); break;
        case GL_SHININESS:
          if (p.empty()) throw trace::TraceError(name + ": no value");
          if (p[0] < 0 || p[0] > 128) { note("glMaterial shininess outside 0..128 (GL_INVALID_VALUE, ignored)"); break; }
          m.shininess = p[0];
          break;
        case GL_COLOR_INDEXES: break;
        default: note("glMaterial with an unknown pname (GL_INVALID_ENUM, ignored)");
      }
    }
  }
  void set_light(uint32_t light, uint32_t pname, const std::vector<double>& p, const std::string& name) {
    if (light < GL_LIGHT0 || light >= GL_LIGHT0 + 8) { note("glLight of a light beyond GL_LIGHT7 (ignored)"); return; }
    LightState& L = g.light_.lights[light - GL_LIGHT0];
    auto need = [&](size_t n) { if (p.size() < n) throw trace::TraceError(name + ": fewer than " + std::to_string(n) + " values"); };
    switch (pname) {
      case GL_AMBIENT: need(4); for (int i = 0; i < 4; ++i) L.ambient[i] = p[i]; break;
      case GL_DIFFUSE: need(4); for (int i = 0; i < 4; ++i) L.diffuse[i] = p[i]; break;
      case GL_SPECULAR: need(4); for (int i = 0; i < 4; ++i) L.specular[i] = p[i]; break;
      case GL_POSITION: need(4); L.position = xform(g.mv_.back(), {p[0], p[1], p[2], p[3]}); break;
      case GL_SPOT_DIRECTION: {
        need(3);
        const Vec4 d = xform(g.mv_.back(), {p[0], p[1], p[2], 0});
        L.spot_direction = {d[0], d[1], d[2]};
        break;
      }
      case GL_SPOT_EXPONENT:
        need(1);
        if (p[0] < 0 || p[0] > 128) { note("glLight GL_SPOT_EXPONENT outside 0..128 (GL_INVALID_VALUE, ignored)"); break; }
        L.spot_exponent = p[0];
        break;
      case GL_SPOT_CUTOFF:
        need(1);
        if (!((p[0] >= 0 && p[0] <= 90) || p[0] == 180)) { note("glLight GL_SPOT_CUTOFF outside 0..90, 180 (GL_INVALID_VALUE, ignored)"); break; }
        L.spot_cutoff = p[0];
        break;
      case GL_CONSTANT_ATTENUATION: case GL_LINEAR_ATTENUATION: case GL_QUADRATIC_ATTENUATION:
        need(1);
        if (p[0] < 0) { note("glLight with a negative attenuation (GL_INVALID_VALUE, ignored)"); break; }
        (pname == GL_CONSTANT_ATTENUATION ? L.kc : pname == GL_LINEAR_ATTENUATION ? L.kl : L.kq) = p[0];
        break;
      default: note("glLight with an unknown pname (GL_INVALID_ENUM, ignored)");
    }
  }
  void set_light_model(uint32_t pname, const std::vector<double>& p) {
    if (p.empty()) return;
    switch (pname) {
      case GL_LIGHT_MODEL_AMBIENT:
        if (p.size() >= 4) for (int i = 0; i < 4; ++i) g.light_.model_ambient[i] = p[i];
        break;
      case GL_LIGHT_MODEL_LOCAL_VIEWER: g.light_.local_viewer = p[0] != 0; break;
      case GL_LIGHT_MODEL_TWO_SIDE: g.light_.two_side = p[0] != 0; break;
      case GL_LIGHT_MODEL_COLOR_CONTROL: g.light_.separate_specular = static_cast<uint32_t>(p[0]) == GL_SEPARATE_SPECULAR_COLOR; break;
      default: note("glLightModel with an unknown pname (ignored)");
    }
  }
  // GL_COLOR_MATERIAL: the current colour tracked into the material (GL 2.1 §2.14.3).
  void track_colour() {
    if (!on(GL_COLOR_MATERIAL)) return;
    std::vector<double> c(g.colour_.begin(), g.colour_.end());
    set_material(cm_face, cm_mode, c, "glColorMaterial");
  }
  std::optional<ColourMaterial> colour_material_mode() const {
    if (!on(GL_COLOR_MATERIAL)) return std::nullopt;
    if (cm_face == GL_BACK && !g.light_.two_side) return std::nullopt;  // only the back material, which is unused
    switch (cm_mode) {
      case GL_EMISSION: return ColourMaterial::Emission;
      case GL_AMBIENT: return ColourMaterial::Ambient;
      case GL_DIFFUSE: return ColourMaterial::Diffuse;
      case GL_SPECULAR: return ColourMaterial::Specular;
      default: return ColourMaterial::AmbientAndDiffuse;
    }
  }
  uint32_t material_id() {
    // materials are compared by value; ids index Gl::materials()
    for (size_t i = g.materials_.size(); i-- > 0;)
      if (g.materials_[i][0] == g.mat_[0] && g.materials_[i][1] == g.mat_[1]) return static_cast<uint32_t>(i);
    g.materials_.push_back(g.mat_);
    return static_cast<uint32_t>(g.materials_.size() - 1);
  }

  // ---- vertices
  void set_colour(const Vec4& c) {
    g.colour_ = c;
    track_colour();
  }
  GlVertex make_vertex(const Vec4& obj) {
    GlVertex v;
    v.eye = xform(g.mv_.back(), obj);
    v.clip = xform(g.proj_.back(), v.eye);
    // the normal: (M^-1)^T n, then GL_RESCALE_NORMAL's factor or GL_NORMALIZE (GL 2.1 §2.11.3)
    const Mat4& m = g.mv_.back();
    Vec3 n = g.normal_;
    if (const auto inv = inverse3(m)) {
      const auto& i = *inv;
      n = {i[0] * g.normal_[0] + i[3] * g.normal_[1] + i[6] * g.normal_[2],
           i[1] * g.normal_[0] + i[4] * g.normal_[1] + i[7] * g.normal_[2],
           i[2] * g.normal_[0] + i[5] * g.normal_[1] + i[8] * g.normal_[2]};
      if (on(GL_RESCALE_NORMAL) && !on(GL_NORMALIZE)) {
        const double f = std::sqrt(i[6] * i[6] + i[7] * i[7] + i[8] * i[8]);  // the third row of M^-1
        if (f > 0) for (double& x : n) x /= f;
      }
    } else {
      note("a singular modelview matrix (normals not transformed)");
    }
    if (on(GL_NORMALIZE)) {
      const double l = len3(n);
      if (l > 0) for (double& x : n) x /= l;
    }
    v.normal = n;
    v.colour = g.colour_;
    v.material = material_id();
    return v;
  }
  void add_vertex(const Vec4& obj) {
    if (!in_begin) {
      note("glVertex outside glBegin/glEnd (ignored)");
      return;
    }
    if (g.recording_) verts.push_back(make_vertex(obj));
    else verts.emplace_back();  // counted only
  }

  // ---- primitives
  void check_draw_state() {
    for (const auto& [cap, nm] : refusing_caps())
      if (on(cap)) refuse(nm + " on while drawing");
    // GL_DEPTH_TEST off (drawn over what is there, depth not written) and glDepthMask(GL_FALSE) (tested, not written)
    // go with each triangle to the rasteriser (GlTriangle::depth_test, depth_write); the function matters only when on
    if (on(GL_DEPTH_TEST)) {
      if (depth_func != GL_LESS && depth_func != GL_LEQUAL) refuse("glDepthFunc other than GL_LESS / GL_LEQUAL");
      if (depth_func == GL_LEQUAL) note("GL_LEQUAL drawn as GL_LESS (only exact depth ties differ)");
    }
    if (!(colour_mask[0] && colour_mask[1] && colour_mask[2])) refuse("glColorMask off for a colour channel while drawing");
    if (depth_range[0] != 0 || depth_range[1] != 1) refuse("glDepthRange other than (0, 1)");
    if (polygon_mode[0] != GL_FILL || polygon_mode[1] != GL_FILL) refuse("glPolygonMode other than GL_FILL (lines, points)");
    if (on(GL_SCISSOR_TEST)) {
      const auto& v = g.viewport_;
      if (!(scissor[0] <= v[0] && scissor[1] <= v[1] && scissor[0] + scissor[2] >= v[0] + v[2] &&
            scissor[1] + scissor[3] >= v[1] + v[3]))
        refuse("GL_SCISSOR_TEST with a box smaller than the viewport");
    }
    if (on(GL_LIGHTING) && on(GL_COLOR_MATERIAL) && cm_face != GL_FRONT_AND_BACK && g.light_.two_side)
      refuse("glColorMaterial of one face under two-sided lighting (the core's colour material is GL_FRONT_AND_BACK)");
    // the frame's lighting states: a new one whenever the lights or the light model differ from the last lit draw's
    // (the back end reprograms the core's registers between the batches); two-sided lighting decides how the back end
    // resolves back faces for the whole frame: refused if it changes. The projection: one per frame (the camera).
    if (on(GL_LIGHTING)) {
      LightingState s = g.light_;
      s.lighting = true;
      if (!g.frame_light_) g.frame_light_ = s;
      if (g.frame_lights_.empty() || g.frame_lights_.back() != s) {
        if (!g.frame_lights_.empty() && g.frame_lights_.front().two_side != s.two_side)
          refuse("GL_LIGHT_MODEL_TWO_SIDE changes between the frame's lit draws (the back end resolves back faces once per "
                 "frame)");
        g.frame_lights_.push_back(s);
      }
    }
    if (!g.frame_proj_) g.frame_proj_ = g.proj_.back();
    else if (*g.frame_proj_ != g.proj_.back()) refuse("the projection matrix changes between the frame's draws");
  }

  void emit(const std::vector<GlVertex>& vs, std::vector<int> poly, int provoking) {
    // fan from the provoking vertex p: (p, p+k, p+k+1) → ordered (p+k, p+k+1, p) so it is last
    const int n = static_cast<int>(poly.size());
    int p = provoking;
    for (int k = 1; k + 1 < n; ++k) {
      GlTriangle t;
      t.v = {vs[poly[(p + k) % n]], vs[poly[(p + k + 1) % n]], vs[poly[p]]};
      // facing: the sign of the homogeneous determinant of (x, y, w) = the window-space winding (w > 0)
      const auto& a = t.v[0].clip; const auto& b = t.v[1].clip; const auto& c = t.v[2].clip;
      const double det = a[0] * (b[1] * c[3] - b[3] * c[1]) - a[1] * (b[0] * c[3] - b[3] * c[0]) +
                         a[3] * (b[0] * c[1] - b[1] * c[0]);
      bool front = det > 0;
      if (front_face == GL_CW) {
        front = !front;
        std::swap(t.v[0], t.v[1]);  // counter-clockwise when front facing, the provoking vertex still last
      }
      if (on(GL_CULL_FACE) && (cull_mode == GL_FRONT_AND_BACK || (cull_mode == GL_BACK) != front)) {
        ++g.stats_.culled;
        continue;
      }
      // the back end clips at the near plane (and a guard band) only: a vertex beyond GL's far plane (z > w), or in
      // front of an orthographic near plane (z < −w, w = 1), would be drawn where GL clips it
      for (const auto& v : t.v)
        if (v.clip[2] > v.clip[3] || (v.clip[3] == 1 && g.proj_.back()[15] == 1 && v.clip[2] < -v.clip[3]))
          refuse("geometry beyond the depth range's far plane (or an orthographic near plane): the back end clips at "
                 "the near plane only");
      t.flat = shade == GL_FLAT;
      t.lit = on(GL_LIGHTING);
      t.colour_material = colour_material_mode();
      for (const auto& [cap, nm] : excluding_caps())
        if (on(cap)) t.excluded.push_back(nm);
      t.primitive = primitive_no;
      t.depth_test = on(GL_DEPTH_TEST);
      t.depth_write = t.depth_test && depth_mask;  // with the test off the depth buffer is not updated (GL 2.1 §4.1.5)
      t.lighting = g.frame_lights_.empty() ? 0u : static_cast<uint32_t>(g.frame_lights_.size() - 1);
      g.tris_.push_back(std::move(t));
      ++g.stats_.triangles;
    }
  }

  void assemble(uint32_t mode, const std::vector<GlVertex>& vs) {
    ++g.stats_.primitives;
    g.stats_.vertices += vs.size();
    if (!g.recording_) return;
    if (mode <= GL_LINE_STRIP) {
      refuse(std::string(mode == GL_POINTS ? "GL_POINTS" : "GL_LINES / GL_LINE_LOOP / GL_LINE_STRIP") +
             " primitives (their pixels are not drawn by the back end)");
      return;
    }
    if (mode > GL_POLYGON) {
      note("glBegin with an unknown mode (GL_INVALID_ENUM, ignored)");
      return;
    }
    check_draw_state();
    ++primitive_no;
    const int n = static_cast<int>(vs.size());
    switch (mode) {
      case GL_TRIANGLES:
        for (int i = 0; i + 2 < n; i += 3) emit(vs, {i, i + 1, i + 2}, 2);
        break;
      case GL_TRIANGLE_STRIP:
        for (int i = 0; i + 2 < n; ++i) {
          if (i % 2 == 0) emit(vs, {i, i + 1, i + 2}, 2);
          else emit(vs, {i + 1, i, i + 2}, 2);
        }
        break;
      case GL_TRIANGLE_FAN:
        for (int i = 1; i + 1 < n; ++i) emit(vs, {0, i, i + 1}, 2);
        break;
      case GL_QUADS:
        for (int i = 0; i + 3 < n; i += 4) emit(vs, {i, i + 1, i + 2, i + 3}, 3);
        break;
      case GL_QUAD_STRIP:  // quad j: v2j, v2j+1, v2j+3, v2j+2; provoking v2j+3
        for (int i = 0; i + 3 < n; i += 2) emit(vs, {i, i + 1, i + 3, i + 2}, 2);
        break;
      case GL_POLYGON:  // provoking: the first vertex
        if (n >= 3) {
          std::vector<int> idx(n);
          for (int i = 0; i < n; ++i) idx[i] = i;
          emit(vs, idx, 0);
        }
        break;
      default:
        break;
    }
  }

  // ---- vertex arrays
  void set_array(Array& a, const trace::Call& c, int size_arg, int type_arg, int stride_arg, int ptr_arg, int fixed_size) {
    const int64_t size = size_arg >= 0 ? integer(c, size_arg) : fixed_size;
    const int64_t stride = integer(c, stride_arg);
    if (size < 2 || size > 4 || stride < 0 || stride > (1 << 20)) {
      note(c.name() + " with an invalid size or stride (GL_INVALID_VALUE, ignored)");
      return;
    }
    a.size = static_cast<int>(size);
    a.type = static_cast<uint32_t>(integer(c, type_arg));
    a.stride = static_cast<int>(stride);
    const trace::Value& p = c.arg(ptr_arg);
    a.data.reset();
    a.from_buffer = false;
    if (p.kind == trace::Value::Kind::Blob) a.data = std::make_shared<const std::string>(p.s);
    else if (p.kind != trace::Value::Kind::Null) a.from_buffer = true;
  }
  static size_t type_size(uint32_t t) {
    switch (t) {
      case GL_BYTE: case GL_UNSIGNED_BYTE: return 1;
      case GL_SHORT: case GL_UNSIGNED_SHORT: return 2;
      case GL_INT: case GL_UNSIGNED_INT: case GL_FLOAT: return 4;
      case GL_DOUBLE: return 8;
      default: return 0;
    }
  }
  // element k of array a as doubles (normalised = colour/normal integer rules)
  std::vector<double> fetch(const Array& a, uint64_t k, bool normalised, const trace::Call& c) {
    const size_t ts = type_size(a.type);
    if (ts == 0) throw ReplayError("call " + std::to_string(c.no) + " " + c.name() + ": an array of an unknown type");
    if (!a.data) {
      refuse(std::string("a vertex array ") + (a.from_buffer ? "in a buffer object" : "without data in the capture"));
      return std::vector<double>(static_cast<size_t>(a.size), 0.0);
    }
    const size_t stride = a.stride ? static_cast<size_t>(a.stride) : ts * static_cast<size_t>(a.size);
    const size_t at = static_cast<size_t>(k) * stride;
    std::vector<double> out;
    for (int i = 0; i < a.size; ++i) {
      const size_t o = at + static_cast<size_t>(i) * ts;
      if (o + ts > a.data->size()) throw ReplayError("call " + std::to_string(c.no) + " " + c.name() + ": array element " + std::to_string(k) + " lies past the data the capture holds");
      const char* p = a.data->data() + o;
      double v = 0;
      switch (a.type) {
        case GL_BYTE: { int8_t x; std::memcpy(&x, p, 1); v = normalised ? (2.0 * x + 1) / 255.0 : x; break; }
        case GL_UNSIGNED_BYTE: { uint8_t x; std::memcpy(&x, p, 1); v = normalised ? x / 255.0 : x; break; }
        case GL_SHORT: { int16_t x; std::memcpy(&x, p, 2); v = normalised ? (2.0 * x + 1) / 65535.0 : x; break; }
        case GL_UNSIGNED_SHORT: { uint16_t x; std::memcpy(&x, p, 2); v = normalised ? x / 65535.0 : x; break; }
        case GL_INT: { int32_t x; std::memcpy(&x, p, 4); v = normalised ? (2.0 * x + 1) / 4294967295.0 : x; break; }
        case GL_UNSIGNED_INT: { uint32_t x; std::memcpy(&x, p, 4); v = normalised ? x / 4294967295.0 : x; break; }
        case GL_FLOAT: { float x; std::memcpy(&x, p, 4); v = x; break; }
        case GL_DOUBLE: { double x; std::memcpy(&x, p, 8); v = x; break; }
      }
      out.push_back(v);
    }
    return out;
  }
  void array_element(uint64_t k, const trace::Call& c) {
    if (!g.recording_) {
      if (vertex.enabled) verts.emplace_back();
      return;
    }
    if (normal.enabled) {
      const auto n = fetch(normal, k, true, c);
      g.normal_ = {n[0], n[1], n[2]};
    }
    if (colour.enabled) {
      const auto v = fetch(colour, k, true, c);
      set_colour({v[0], v[1], v[2], v.size() > 3 ? v[3] : 1.0});
    }
    if (vertex.enabled) {
      const auto p = fetch(vertex, k, false, c);
      verts.push_back(make_vertex({p[0], p[1], p.size() > 2 ? p[2] : 0.0, p.size() > 3 ? p[3] : 1.0}));
    }
  }
  void draw_arrays(uint32_t mode, const std::vector<uint64_t>& idx, const trace::Call& c) {
    if (!vertex.enabled) return;  // nothing drawn without GL_VERTEX_ARRAY
    verts.clear();
    for (uint64_t k : idx) array_element(k, c);
    assemble(mode, verts);
    verts.clear();
  }
  std::vector<uint64_t> indices(const trace::Call& c, uint64_t count, uint32_t type, size_t arg) {
    if (count > static_cast<uint64_t>(kMaxDrawVertices))
      throw ReplayError("call " + std::to_string(c.no) + " " + c.name() + ": count " + std::to_string(count) +
                        " (at most " + std::to_string(kMaxDrawVertices) + " vertices a draw)");
    const trace::Value& v = c.arg(arg);
    std::vector<uint64_t> out;
    if (v.kind == trace::Value::Kind::Array) {
      for (const auto& e : v.items) out.push_back(e.uinteger());
    } else if (v.kind == trace::Value::Kind::Blob) {
      const size_t ts = type == GL_UNSIGNED_BYTE ? 1 : type == GL_UNSIGNED_SHORT ? 2 : 4;
      if (v.s.size() < count * ts) throw ReplayError("call " + std::to_string(c.no) + " " + c.name() + ": fewer indices in the capture than its count");
      for (uint64_t i = 0; i < count; ++i) {
        uint32_t x = 0;
        std::memcpy(&x, v.s.data() + i * ts, ts);
        out.push_back(x);
      }
    } else {
      refuse("glDrawElements with indices in a buffer object");
    }
    if (out.size() > count) out.resize(count);
    return out;
  }

  // ---- display lists
  static bool executes_at_compile(const std::string& n) {  // GL 2.1 §5.4: not compiled, executed immediately
    return n == "glGenLists" || n == "glDeleteLists" || n == "glIsList" || n == "glNewList" || n == "glEndList" ||
           starts(n, "glGet") || starts(n, "glIs") || n == "glFlush" || n == "glFinish" || starts(n, "glPixelStore") ||
           n == "glReadPixels" || n == "glVertexPointer" || n == "glNormalPointer" || n == "glColorPointer" ||
           n == "glTexCoordPointer" || n == "glEnableClientState" || n == "glDisableClientState" ||
           n == "glInterleavedArrays" || n == "glEdgeFlagPointer" || n == "glIndexPointer" ||
           starts(n, "glX") || starts(n, "egl") || n == "glFeedbackBuffer" || n == "glSelectBuffer" ||
           n == "glRenderMode" || n == "glClientActiveTexture" || n == "glPushClientAttrib" || n == "glPopClientAttrib";
  }
  // Array draws compile with the arrays' contents at compile time: a call carrying its own blob copies.
  trace::Call compile_draw(const trace::Call& c) {
    trace::Call out = c;
    auto sig = std::make_shared<trace::FunctionSig>(*c.sig);
    sig->name = "shadecore.immediate:" + c.name();
    out.sig = sig;
    // the arrays as they are now: appended as blobs after the call's own arguments
    for (const Array* a : {&vertex, &normal, &colour}) {
      trace::Value meta;
      meta.kind = trace::Value::Kind::Array;
      for (int64_t x : {int64_t{a->enabled}, int64_t{a->size}, int64_t{a->type}, int64_t{a->stride}, int64_t{a->from_buffer}}) {
        trace::Value e;
        e.kind = trace::Value::Kind::SInt;
        e.i = x;
        meta.items.push_back(e);
      }
      trace::Value blob;
      if (a->data) {
        blob.kind = trace::Value::Kind::Blob;
        blob.s = *a->data;
      }
      meta.items.push_back(blob);
      out.args.push_back(meta);
    }
    return out;
  }
  void call_list(uint32_t id) {
    auto it = g.lists_.find(id);
    if (it == g.lists_.end()) return;  // an undefined list: nothing (GL 2.1 §5.4)
    if (list_depth >= 64) {
      note("display lists nested deeper than 64 (GL_MAX_LIST_NESTING; ignored)");
      return;
    }
    ++list_depth;
    const auto body = it->second;  // kept alive even if the list is redefined inside
    for (const auto& c : *body) execute(c);
    --list_depth;
  }

  // ---- dispatch
  void dispatch(const trace::Call& c);

  void execute(const trace::Call& c) {
    if (++g.stats_.calls_executed > kMaxExecuted)
      throw ReplayError("call " + std::to_string(c.no) + ": the frame executes more than " + std::to_string(kMaxExecuted) +
                        " calls (display lists calling lists)");
    if (starts(c.name(), "shadecore.immediate:")) {
      // a compiled array draw: restore the arrays it captured, run it, restore the current ones
      const Array keep[3] = {vertex, normal, colour};
      const size_t base = c.args.size() - 3;
      Array* arrs[3] = {&vertex, &normal, &colour};
      for (int i = 0; i < 3; ++i) {
        const auto& m = c.args[base + static_cast<size_t>(i)].items;
        arrs[i]->enabled = m[0].i != 0;
        arrs[i]->size = static_cast<int>(m[1].i);
        arrs[i]->type = static_cast<uint32_t>(m[2].i);
        arrs[i]->stride = static_cast<int>(m[3].i);
        arrs[i]->from_buffer = m[4].i != 0;
        arrs[i]->data = m[5].kind == trace::Value::Kind::Blob ? std::make_shared<const std::string>(m[5].s) : nullptr;
      }
      trace::Call inner = c;
      auto sig = std::make_shared<trace::FunctionSig>(*c.sig);
      sig->name = c.name().substr(std::strlen("shadecore.immediate:"));
      inner.sig = sig;
      inner.args.resize(base);
      dispatch(inner);
      for (int i = 0; i < 3; ++i) *arrs[i] = keep[i];
      return;
    }
    dispatch(c);
  }

  void top_level(const trace::Call& c) {
    const std::string& n = c.name();
    if (compiling && !executes_at_compile(n)) {
      const bool draw = n == "glDrawArrays" || n == "glDrawElements" || n == "glDrawRangeElements" || n == "glArrayElement";
      compiled->push_back(draw ? compile_draw(c) : c);
      if (compile_execute) execute(c);
      return;
    }
    execute(c);
  }
};

void Gl::Impl::dispatch(const trace::Call& c) {
  const std::string& n = c.name();
  auto u32 = [&](size_t k) { return static_cast<uint32_t>(integer(c, k)); };

  // window system and queries: read and skipped (the drawable size comes with the tracer's fake glViewport)
  if (starts(n, "glX") || starts(n, "egl") || starts(n, "wgl") || starts(n, "CGL")) {
    ++g.stats_.ignored[n];
    return;
  }
  if (starts(n, "glGet") || starts(n, "glIs") || n == "glFlush" || n == "glFinish" || n == "glHint" ||
      starts(n, "glPixelStore") || n == "glReadPixels" || n == "glDrawBuffer" || n == "glReadBuffer" ||
      n == "glGenTextures" || n == "glGenBuffers" || n == "glClearStencil" || n == "glClearAccum" ||
      n == "glClearIndex" || n == "glPolygonOffset" || n == "glLineWidth" || n == "glPointSize" ||
      n == "glBlendFunc" || n == "glAlphaFunc" || n == "glFogf" || n == "glFogfv" || n == "glFogi" ||
      n == "glFogiv" || n == "glLineStipple" || n == "glPolygonStipple" || n == "glStencilFunc" ||
      n == "glStencilOp" || n == "glStencilMask") {
    // state that matters only with a capability on (GL_BLEND, GL_FOG, …): that capability is what counts
    ++g.stats_.ignored[n];
    return;
  }

  // ---- matrices
  if (n == "glMatrixMode") { g.matrix_mode_ = u32(0); return; }
  if (n == "glLoadIdentity") { top() = identity(); return; }
  if (n == "glLoadMatrixf" || n == "glLoadMatrixd") { top() = matrix_arg(c, 0); return; }
  if (n == "glMultMatrixf" || n == "glMultMatrixd") { mult(matrix_arg(c, 0)); return; }
  if (n == "glLoadTransposeMatrixf" || n == "glLoadTransposeMatrixd") {
    const Mat4 m = matrix_arg(c, 0);
    Mat4 t{};
    for (int i = 0; i < 4; ++i) for (int j = 0; j < 4; ++j) t[i * 4 + j] = m[j * 4 + i];
    top() = t;
    return;
  }
  if (n == "glMultTransposeMatrixf" || n == "glMultTransposeMatrixd") {
    const Mat4 m = matrix_arg(c, 0);
    Mat4 t{};
    for (int i = 0; i < 4; ++i) for (int j = 0; j < 4; ++j) t[i * 4 + j] = m[j * 4 + i];
    mult(t);
    return;
  }
  if (n == "glPushMatrix") {
    auto& s = stack();
    if (s.size() >= 32) { note("glPushMatrix past a depth of 32 (Mesa's; GL_STACK_OVERFLOW, ignored)"); return; }
    s.push_back(s.back());
    return;
  }
  if (n == "glPopMatrix") {
    auto& s = stack();
    if (s.size() <= 1) { note("glPopMatrix of an empty stack (GL_STACK_UNDERFLOW, ignored)"); return; }
    s.pop_back();
    return;
  }
  if (n == "glTranslatef" || n == "glTranslated") {
    Mat4 t = identity();
    t[3] = num(c, 0), t[7] = num(c, 1), t[11] = num(c, 2);
    mult(t);
    return;
  }
  if (n == "glScalef" || n == "glScaled") {
    Mat4 s = identity();
    s[0] = num(c, 0), s[5] = num(c, 1), s[10] = num(c, 2);
    mult(s);
    return;
  }
  if (n == "glRotatef" || n == "glRotated") { rotate(num(c, 0), num(c, 1), num(c, 2), num(c, 3)); return; }
  if (n == "glFrustum") {
    const double l = num(c, 0), r = num(c, 1), b = num(c, 2), t = num(c, 3), nn = num(c, 4), f = num(c, 5);
    if (nn <= 0 || f <= 0 || l == r || b == t || nn == f) { note("glFrustum with invalid planes (GL_INVALID_VALUE, ignored)"); return; }
    mult({2 * nn / (r - l), 0, (r + l) / (r - l), 0, 0, 2 * nn / (t - b), (t + b) / (t - b), 0, 0, 0,
          -(f + nn) / (f - nn), -2 * f * nn / (f - nn), 0, 0, -1, 0});
    return;
  }
  if (n == "glOrtho") {
    const double l = num(c, 0), r = num(c, 1), b = num(c, 2), t = num(c, 3), nn = num(c, 4), f = num(c, 5);
    if (l == r || b == t || nn == f) { note("glOrtho with invalid planes (GL_INVALID_VALUE, ignored)"); return; }
    mult({2 / (r - l), 0, 0, -(r + l) / (r - l), 0, 2 / (t - b), 0, -(t + b) / (t - b), 0, 0, -2 / (f - nn),
          -(f + nn) / (f - nn), 0, 0, 0, 1});
    return;
  }
  if (n == "glViewport") {
    g.viewport_ = {static_cast<int>(integer(c, 0)), static_cast<int>(integer(c, 1)), static_cast<int>(integer(c, 2)),
                   static_cast<int>(integer(c, 3))};
    if (c.fake) g.drawable_ = {g.viewport_[2], g.viewport_[3]};  // the tracer's glViewport at MakeCurrent
    return;
  }
  if (n == "glDepthRange" || n == "glDepthRangef") { depth_range = {num(c, 0), num(c, 1)}; return; }
  if (n == "glScissor") {
    scissor = {static_cast<int>(integer(c, 0)), static_cast<int>(integer(c, 1)), static_cast<int>(integer(c, 2)),
               static_cast<int>(integer(c, 3))};
    return;
  }

  // ---- enables
  if (n == "glEnable" || n == "glDisable") {
    const uint32_t cap = u32(0);
    if (n == "glEnable") enabled.insert(cap);
    else enabled.erase(cap);
    if (cap >= GL_LIGHT0 && cap < GL_LIGHT0 + 8) g.light_.lights[cap - GL_LIGHT0].enabled = n == "glEnable";
    if (cap == GL_COLOR_MATERIAL && n == "glEnable") track_colour();
    return;
  }
  if (n == "glEnableClientState" || n == "glDisableClientState") {
    const bool e = n == "glEnableClientState";
    switch (u32(0)) {
      case GL_VERTEX_ARRAY: vertex.enabled = e; break;
      case GL_NORMAL_ARRAY: normal.enabled = e; break;
      case GL_COLOR_ARRAY: colour.enabled = e; break;
      default: if (e) unsupported(n + "(" + std::to_string(u32(0)) + ")"); break;
    }
    return;
  }

  // ---- raster state
  if (n == "glShadeModel") { shade = u32(0); return; }
  if (n == "glFrontFace") { front_face = u32(0); return; }
  if (n == "glCullFace") { cull_mode = u32(0); return; }
  if (n == "glDepthFunc") { depth_func = u32(0); return; }
  if (n == "glDepthMask") { depth_mask = integer(c, 0) != 0; return; }
  if (n == "glColorMask") { colour_mask = {integer(c, 0) != 0, integer(c, 1) != 0, integer(c, 2) != 0, integer(c, 3) != 0}; return; }
  if (n == "glPolygonMode") {
    const uint32_t face = u32(0), mode = u32(1);
    if (face == GL_FRONT || face == GL_FRONT_AND_BACK) polygon_mode[0] = mode;
    if (face == GL_BACK || face == GL_FRONT_AND_BACK) polygon_mode[1] = mode;
    return;
  }
  if (n == "glClearColor") { g.clear_colour_ = {num(c, 0), num(c, 1), num(c, 2), num(c, 3)}; return; }
  if (n == "glClearDepth" || n == "glClearDepthf") { clear_depth = num(c, 0); return; }
  if (n == "glClear") {
    const uint64_t mask = static_cast<uint64_t>(integer(c, 0));
    if (g.recording_) {
      if (!g.tris_.empty() && (mask & (GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT)))
        refuse("glClear after drawing in the same frame");
      if ((mask & GL_DEPTH_BUFFER_BIT) && clear_depth != 1) refuse("glClearDepth other than 1");
      if (mask & GL_COLOR_BUFFER_BIT) g.cleared_ = true;
      if ((mask & GL_COLOR_BUFFER_BIT) && on(GL_SCISSOR_TEST) &&
          !(scissor[0] <= 0 && scissor[1] <= 0 && scissor[0] + scissor[2] >= g.drawable_[0] &&
            scissor[1] + scissor[3] >= g.drawable_[1]))
        refuse("glClear under a scissor box smaller than the window");
    }
    return;
  }

  // ---- lighting
  if (n == "glLightf" || n == "glLighti" || n == "glLightfv" || n == "glLightiv") {
    set_light(u32(0), u32(1), vec(c, 2), n);
    return;
  }
  if (n == "glLightModelf" || n == "glLightModeli" || n == "glLightModelfv" || n == "glLightModeliv") {
    set_light_model(u32(0), vec(c, 1));
    return;
  }
  if (n == "glMaterialf" || n == "glMateriali" || n == "glMaterialfv" || n == "glMaterialiv") {
    std::vector<double> p = vec(c, 2);
    if (n == "glMaterialiv" && u32(1) != GL_SHININESS) for (double& x : p) x = (2 * x + 1) / 4294967295.0;
    set_material(u32(0), u32(1), p, n);
    return;
  }
  if (n == "glColorMaterial") {
    cm_face = u32(0);
    cm_mode = u32(1);
    track_colour();
    return;
  }

  // ---- current attributes
  if (starts(n, "glNormal3")) {
    std::vector<double> v = n.size() > 10 && n.back() == 'v' ? vec(c, 0) : std::vector<double>{num(c, 0), num(c, 1), num(c, 2)};
    if (v.size() < 3) throw trace::TraceError("call " + std::to_string(c.no) + " " + n + ": fewer than 3 values");
    const char t = n[9];
    const double scale = t == 'b' ? 255.0 : t == 's' ? 65535.0 : t == 'i' ? 4294967295.0 : 0.0;
    if (scale > 0) for (double& x : v) x = (2 * x + 1) / scale;
    g.normal_ = {v[0], v[1], v[2]};
    return;
  }
  if (starts(n, "glColor3") || starts(n, "glColor4")) {
    const int k = n[7] - '0';
    const bool pv = n.back() == 'v';
    std::vector<double> v;
    if (pv) v = vec(c, 0);
    else for (int i = 0; i < k; ++i) v.push_back(num(c, static_cast<size_t>(i)));
    if (static_cast<int>(v.size()) < k) throw trace::TraceError("call " + std::to_string(c.no) + " " + n + ": too few values");
    const std::string t = n.substr(8, pv ? n.size() - 9 : std::string::npos);
    for (double& x : v) {
      if (t == "ub") x /= 255.0;
      else if (t == "us") x /= 65535.0;
      else if (t == "ui") x /= 4294967295.0;
      else if (t == "b") x = (2 * x + 1) / 255.0;
      else if (t == "s") x = (2 * x + 1) / 65535.0;
      else if (t == "i") x = (2 * x + 1) / 4294967295.0;
    }
    set_colour({v[0], v[1], v[2], k == 4 ? v[3] : 1.0});
    return;
  }
  if (starts(n, "glVertex2") || starts(n, "glVertex3") || starts(n, "glVertex4")) {
    const int k = n[8] - '0';
    std::vector<double> v = n.back() == 'v' ? vec(c, 0) : std::vector<double>{};
    if (n.back() != 'v') for (int i = 0; i < k; ++i) v.push_back(num(c, static_cast<size_t>(i)));
    if (static_cast<int>(v.size()) < k) throw trace::TraceError("call " + std::to_string(c.no) + " " + n + ": too few values");
    add_vertex({v[0], v[1], k > 2 ? v[2] : 0.0, k > 3 ? v[3] : 1.0});
    return;
  }
  if (starts(n, "glRect")) {
    std::vector<double> v;
    if (n.back() == 'v') {
      const auto a = vec(c, 0), b = vec(c, 1);
      if (a.size() < 2 || b.size() < 2) throw trace::TraceError("call " + std::to_string(c.no) + " " + n + ": too few values");
      v = {a[0], a[1], b[0], b[1]};
    } else {
      v = {num(c, 0), num(c, 1), num(c, 2), num(c, 3)};
    }
    in_begin = true;
    verts.clear();
    add_vertex({v[0], v[1], 0, 1}), add_vertex({v[2], v[1], 0, 1}), add_vertex({v[2], v[3], 0, 1}), add_vertex({v[0], v[3], 0, 1});
    in_begin = false;
    assemble(GL_POLYGON, verts);
    verts.clear();
    return;
  }
  if (n == "glBegin") {
    if (in_begin) { note("glBegin inside glBegin (GL_INVALID_OPERATION, ignored)"); return; }
    in_begin = true;
    begin_mode = u32(0);
    verts.clear();
    return;
  }
  if (n == "glEnd") {
    if (!in_begin) { note("glEnd without glBegin (GL_INVALID_OPERATION, ignored)"); return; }
    in_begin = false;
    assemble(begin_mode, verts);
    verts.clear();
    return;
  }

  // ---- vertex arrays
  if (n == "glVertexPointer") { set_array(vertex, c, 0, 1, 2, 3, 0); return; }
  if (n == "glNormalPointer") { set_array(normal, c, -1, 0, 1, 2, 3); return; }
  if (n == "glColorPointer") { set_array(colour, c, 0, 1, 2, 3, 0); return; }
  if (n == "glArrayElement") {
    if (in_begin) array_element(static_cast<uint64_t>(integer(c, 0)), c);
    return;
  }
  if (n == "glDrawArrays") {
    const int64_t first = integer(c, 1), count = integer(c, 2);
    if (count < 0 || first < 0 || count > kMaxDrawVertices)
      throw ReplayError("call " + std::to_string(c.no) + " glDrawArrays: first " + std::to_string(first) + ", count " +
                        std::to_string(count) + " (at most " + std::to_string(kMaxDrawVertices) + " vertices a draw)");
    std::vector<uint64_t> idx;
    for (int64_t i = 0; i < count; ++i) idx.push_back(static_cast<uint64_t>(first + i));
    draw_arrays(u32(0), idx, c);
    return;
  }
  if (n == "glDrawElements") {
    draw_arrays(u32(0), indices(c, static_cast<uint64_t>(integer(c, 1)), u32(2), 3), c);
    return;
  }
  if (n == "glDrawRangeElements") {
    draw_arrays(u32(0), indices(c, static_cast<uint64_t>(integer(c, 3)), u32(4), 5), c);
    return;
  }

  // ---- display lists
  if (n == "glGenLists") {
    if (c.has_ret) {
      // the ids the program got: reserved (empty until defined)
    }
    return;
  }
  if (n == "glNewList") {
    if (compiling) { note("glNewList inside glNewList (GL_INVALID_OPERATION, ignored)"); return; }
    compiling = u32(0);
    compile_execute = u32(1) == GL_COMPILE_AND_EXECUTE;
    compiled = std::make_shared<std::vector<trace::Call>>();
    return;
  }
  if (n == "glEndList") {
    if (!compiling) { note("glEndList without glNewList (GL_INVALID_OPERATION, ignored)"); return; }
    g.lists_[compiling] = compiled;
    compiling = 0;
    compiled.reset();
    return;
  }
  if (n == "glDeleteLists") {
    const uint64_t first = u32(0);
    const int64_t range = integer(c, 1);
    if (range > 0)
      g.lists_.erase(g.lists_.lower_bound(static_cast<uint32_t>(first)),
                     first + static_cast<uint64_t>(range) > 0xffffffffull ? g.lists_.end()
                                                                         : g.lists_.lower_bound(static_cast<uint32_t>(first + range)));
    return;
  }
  if (n == "glListBase") { list_base = u32(0); return; }
  if (n == "glCallList") { call_list(u32(0)); return; }
  if (n == "glCallLists") {
    const int64_t count = integer(c, 0);
    const uint32_t type = u32(1);
    const trace::Value& v = c.arg(2);
    std::vector<int64_t> ids;
    if (v.kind == trace::Value::Kind::Array) {
      for (const auto& e : v.items) ids.push_back(e.integer());
    } else if (v.kind == trace::Value::Kind::Blob) {
      const size_t ts = type_size(type);
      if (ts == 0) { unsupported("glCallLists(type " + std::to_string(type) + ")"); return; }
      for (int64_t i = 0; i < count && static_cast<size_t>(i + 1) * ts <= v.s.size(); ++i) {
        Array a;
        a.size = 1, a.type = type, a.stride = 0, a.data = std::make_shared<const std::string>(v.s);
        ids.push_back(static_cast<int64_t>(fetch(a, static_cast<uint64_t>(i), false, c)[0]));
      }
    }
    for (int64_t id : ids) call_list(list_base + static_cast<uint32_t>(id));
    return;
  }

  // everything else that can change what is drawn
  unsupported(n);
  if (n == "glBitmap" || n == "glDrawPixels" || n == "glCopyPixels" || starts(n, "glEvalMesh") ||
      starts(n, "glEvalCoord") || n == "glAccum" || n == "glUseProgram" || n == "glBindVertexArray")
    refuse(n + " (its pixels are not drawn by the back end)");
}

// ---- Gl ---------------------------------------------------------------------------------------------------

Gl::Gl() : impl_(std::make_shared<Impl>(*this)) {
  mv_.push_back(identity());
  proj_.push_back(identity());
  tex_.push_back(identity());
  light_.lights[0].diffuse = {1, 1, 1, 1};
  light_.lights[0].specular = {1, 1, 1, 1};
  impl_->enabled.insert(GL_DITHER);
}

void Gl::call(const trace::Call& c) { impl_->top_level(c); }

void Gl::clear_frame() {
  tris_.clear();
  stats_ = FrontStats{};
  refusals_.clear();
  cleared_ = false;
  frame_light_.reset();
  frame_lights_.clear();
  frame_proj_.reset();
  impl_->primitive_no = 0;
}

// ---- the hand-over ------------------------------------------------------------------------------------------

namespace {

scene::Vec3 rgb(const Vec4& c) { return {std::clamp(c[0], 0.0, 1.0), std::clamp(c[1], 0.0, 1.0), std::clamp(c[2], 0.0, 1.0)}; }

}  // namespace

Handover hand_over(const Gl& gl, const std::string& name) {
  Handover h;
  h.stats = gl.stats();
  if (!gl.refusals().empty()) {
    std::string why;
    for (const auto& r : gl.refusals()) why += (why.empty() ? "" : "; ") + r;
    throw ReplayError(name + ": the frame cannot be compared: " + why);
  }
  const auto dw = gl.drawable();
  const auto vp = gl.viewport();
  const int W = dw[0] > 0 ? dw[0] : vp[0] + vp[2], H = dw[1] > 0 ? dw[1] : vp[1] + vp[3];
  if (W <= 0 || H <= 0) throw ReplayError(name + ": no viewport or drawable size in the capture before the frame");
  if (vp[0] != 0 || vp[1] != 0 || vp[2] != W || vp[3] != H)
    throw ReplayError(name + ": the viewport (" + std::to_string(vp[0]) + ", " + std::to_string(vp[1]) + ", " +
                      std::to_string(vp[2]) + "x" + std::to_string(vp[3]) + ") is not the whole " + std::to_string(W) +
                      "x" + std::to_string(H) + " window (the back end draws one full-window viewport)");
  if (gl.triangles().empty()) throw ReplayError(name + ": the frame draws no polygons");
  if (!gl.cleared()) ++h.stats.notes["the frame does not clear the colour buffer (the background is the clear colour)"];

  scene::Scene& sc = h.scene;
  sc.file = name;
  sc.width = W, sc.height = H;
  sc.background = rgb(gl.clear_colour());
  sc.flat_rule = scene::FlatRule::ProvokingVertex;
  sc.blinn = true;
  const LightingState L = gl.frame_lighting() ? *gl.frame_lighting() : LightingState{};
  // GL does not clamp light and material colours (nor the model ambient); the core's format holds [0, 1]: each
  // value clamped is noted
  auto lit_rgb = [&h](const Vec4& c, const char* what) {
    for (int i = 0; i < 3; ++i)
      if (c[i] < 0 || c[i] > 1) {
        ++h.stats.notes[std::string(what) + " outside [0, 1] clamped (the core's colour format; GL would not clamp)"];
        break;
      }
    return rgb(c);
  };
  // one lighting state (the global and light registers) as the back end takes it
  auto lighting_set = [&](const LightingState& Ls) {
    scene::LightingSet set;
    set.global_ambient = lit_rgb(Ls.model_ambient, "GL_LIGHT_MODEL_AMBIENT");
    set.local_viewer = Ls.local_viewer;
    set.separate_specular = Ls.separate_specular;
    for (const auto& l : Ls.lights) {
      if (!l.enabled) continue;
      scene::Light s;
      s.position = l.position;
      s.ambient = lit_rgb(l.ambient, "a light colour"), s.diffuse = lit_rgb(l.diffuse, "a light colour"),
      s.specular = lit_rgb(l.specular, "a light colour");
      s.kc = l.kc, s.kl = l.kl, s.kq = l.kq;
      s.spot_direction = l.spot_direction;
      s.spot_cutoff = l.spot_cutoff;
      s.spot_exponent = static_cast<int>(std::lround(l.spot_exponent));
      if (s.spot_exponent != l.spot_exponent) ++h.stats.notes["GL_SPOT_EXPONENT rounded to an integer"];
      set.lights.push_back(s);
    }
    return set;
  };
  {
    const scene::LightingSet first = lighting_set(L);
    sc.global_ambient = first.global_ambient;
    sc.local_viewer = first.local_viewer;
    sc.separate_specular = first.separate_specular;
    sc.lights = first.lights;
  }
  sc.two_side = L.two_side;  // the same in every state (else refused)
  // several lighting states in the frame: the stream's, in drawing order (objects[i].lighting picks one)
  if (gl.frame_lightings().size() > 1)
    for (const auto& Ls : gl.frame_lightings()) sc.lighting_sets.push_back(lighting_set(Ls));
  // the projection: the frame's; the rasteriser's near plane from it (perspective: n = m23 / (m22 − 1))
  const Mat4 P = gl.frame_projection() ? *gl.frame_projection() : gl.projection();
  scene::Camera cam;
  if (P[14] == -1 && P[15] == 0 && P[10] != 1) cam.near = P[11] / (P[10] - 1);
  else if (P[12] == 0 && P[13] == 0 && P[14] == 0 && P[15] == 1) cam.near = 1;  // orthographic: w = 1
  else throw ReplayError(name + ": a projection matrix that is neither a perspective nor an orthographic one");
  if (!(cam.near > 0)) throw ReplayError(name + ": a projection whose near plane is not in front of the eye");
  cam.far = cam.near * 2;
  h.settings.camera = cam;
  h.settings.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  h.settings.projection = P;
  h.settings.unsnapped_depth = true;  // the depth plane as GL (and llvmpipe) computes it: docs/replay.md
  h.settings.changed_registers_only = true;  // a driver writes a register when its value changes

  // Materials by value; objects = runs of triangles with one (material, shading, colour material, lit, excluded,
  // lighting state, depth test and depth mask), in drawing order (the back end rasterises them in that order). Under
  // colour material the term(s) it replaces come per vertex through the core's fragment colour input, not from the
  // material registers: they are left out of the material's identity (set to 0), so the colours
  // GL tracked into the material (every glColor under GL_COLOR_MATERIAL, a glMaterial per vertex carried as colour
  // material) make one material and no material register writes of their own.
  auto canonical = [&gl](uint32_t id, std::optional<ColourMaterial> cm) {
    std::array<MaterialState, 2> pair = gl.materials()[id];
    if (cm)
      for (auto& m : pair) {
        const Vec4 none{0, 0, 0, 1};
        if (*cm == ColourMaterial::Ambient || *cm == ColourMaterial::AmbientAndDiffuse) m.ambient = none;
        if (*cm == ColourMaterial::Diffuse || *cm == ColourMaterial::AmbientAndDiffuse) m.diffuse = none;
        if (*cm == ColourMaterial::Specular) m.specular = none;
        if (*cm == ColourMaterial::Emission) m.emission = none;
      }
    return pair;
  };
  std::map<std::tuple<bool, int, std::vector<double>>, int> material_index;  // (lit, colour material, values) → scene
  auto scene_material = [&](uint32_t id, bool lit, std::optional<ColourMaterial> cm) {
    const int cmk = cm ? static_cast<int>(*cm) : -1;
    const std::array<MaterialState, 2> pair = lit ? canonical(id, cm) : std::array<MaterialState, 2>{};
    std::vector<double> values;
    if (lit)
      for (const auto& m : pair) {
        for (const Vec4* c : {&m.ambient, &m.diffuse, &m.specular, &m.emission}) values.insert(values.end(), c->begin(), c->end());
        values.push_back(m.shininess);
      }
    const auto key = std::make_tuple(lit, cmk, std::move(values));
    auto it = material_index.find(key);
    if (it != material_index.end()) return it->second;
    scene::Material m;
    m.name = "gl" + std::to_string(sc.materials.size());
    if (lit) {
      auto fill = [&](const MaterialState& s, auto& dst) {
        dst.emission = lit_rgb(s.emission, "a material colour"), dst.ambient = lit_rgb(s.ambient, "a material colour");
        dst.diffuse = lit_rgb(s.diffuse, "a material colour"), dst.specular = lit_rgb(s.specular, "a material colour");
        dst.shininess = static_cast<int>(std::lround(s.shininess));
        if (dst.shininess != s.shininess) ++h.stats.notes["GL_SHININESS rounded to an integer"];
      };
      fill(pair[0], m);
      if (pair[1] != pair[0]) {
        scene::BackMaterial b;
        fill(pair[1], b);
        m.back = b;
      }
    } else {  // lighting off: the colour itself, as emission through colour material with every other term 0
      m.emission = m.ambient = m.diffuse = m.specular = {0, 0, 0};
      m.shininess = 0;
    }
    sc.materials.push_back(m);
    const int idx = static_cast<int>(sc.materials.size()) - 1;
    material_index[key] = idx;
    return idx;
  };
  int cur = -1;
  std::tuple<int, bool, int, std::vector<std::string>, int, bool, bool> cur_key;
  // Material batches: a smooth primitive whose vertices' materials differ in more than the core's colour-material
  // input can carry. Each such vertex is lit under its own material: it names an object of that material (same
  // lighting state, colour material, depth state; no faces of its own: Mesh::vertex_object), so the back end lights
  // it in that material's batch, with that material's register writes.
  std::map<std::tuple<int, int, std::vector<std::string>, int>, int> batch_objects;
  uint64_t batched_vertices = 0;
  auto batch_object = [&](int mk, std::optional<ColourMaterial> cmk, const GlTriangle& t, int lighting) {
    const auto key = std::make_tuple(mk, cmk ? static_cast<int>(*cmk) : -1, t.excluded, lighting);
    auto it = batch_objects.find(key);
    if (it != batch_objects.end()) return it->second;
    scene::Object o;
    o.name = "draw" + std::to_string(sc.objects.size());
    o.type = scene::ObjectType::Mesh;
    o.material = mk;
    o.shading = scene::Shading::Gouraud;
    o.colour_material = cmk;
    o.lighting = lighting;
    o.where = "material batch (first at primitive " + std::to_string(t.primitive) + ")";
    o.scene_file = name;
    sc.objects.push_back(o);
    h.meshes.emplace_back();
    h.object_excluded.push_back(t.excluded);
    const int idx = static_cast<int>(sc.objects.size()) - 1;
    batch_objects[key] = idx;
    return idx;
  };
  for (const auto& t : gl.triangles()) {
    bool batches = false;  // the vertices lit under their own materials (material batches)
    const bool lit = t.lit;
    std::optional<ColourMaterial> cm = lit ? t.colour_material : std::optional<ColourMaterial>(ColourMaterial::Emission);
    // the material of the triangle: flat → the provoking vertex's; smooth → all three agree, or they differ in one
    // colour that the core's fragment colour input carries (colour material: the per-vertex value as the vertex's
    // colour), as GL lights each vertex with the material in force at it
    const uint32_t mid = t.v[2].material;
    std::array<Vec4, 3> vertex_colour{t.v[0].colour, t.v[1].colour, t.v[2].colour};
    if (lit && !t.flat && (t.v[0].material != mid || t.v[1].material != mid)) {
      const auto& M = gl.materials();
      const std::array<const MaterialState*, 3> f{&M[t.v[0].material][0], &M[t.v[1].material][0], &M[mid][0]};
      const std::array<const MaterialState*, 3> b{&M[t.v[0].material][1], &M[t.v[1].material][1], &M[mid][1]};
      auto same = [&](auto field) {
        return field(*f[0]) == field(*f[2]) && field(*f[1]) == field(*f[2]) && (!L.two_side || (*b[0] == *b[2] && *b[1] == *b[2]));
      };
      auto rgb3 = [](const Vec4& c) { return std::array<double, 3>{c[0], c[1], c[2]}; };
      const bool amb = same([&](const MaterialState& m) { return rgb3(m.ambient); });
      const bool dif = same([&](const MaterialState& m) { return rgb3(m.diffuse); });
      const bool spe = same([&](const MaterialState& m) { return rgb3(m.specular); });
      const bool emi = same([&](const MaterialState& m) { return rgb3(m.emission); });
      const bool shi = same([](const MaterialState& m) { return m.shininess; });
      bool ad_equal = true;
      for (const auto* m : f) ad_equal = ad_equal && rgb3(m->ambient) == rgb3(m->diffuse);
      if (cm) {
        // GL_COLOR_MATERIAL on: every glColor (a colour array's too) is tracked into the material (GL 2.1 §2.14.3), so
        // the vertices' materials differ in the tracked colour(s); those reach the core per vertex through its
        // colour-material input (the vertex colours). Any other term or the shininess changing is refused.
        auto same_fb = [&](auto field) {
          return field(*f[0]) == field(*f[2]) && field(*f[1]) == field(*f[2]) &&
                 (!L.two_side || (field(*b[0]) == field(*b[2]) && field(*b[1]) == field(*b[2])));
        };
        const bool ta = *cm == ColourMaterial::Ambient || *cm == ColourMaterial::AmbientAndDiffuse;
        const bool td = *cm == ColourMaterial::Diffuse || *cm == ColourMaterial::AmbientAndDiffuse;
        const bool ts = *cm == ColourMaterial::Specular, te = *cm == ColourMaterial::Emission;
        if (!((ta || same_fb([&](const MaterialState& m) { return rgb3(m.ambient); })) &&
              (td || same_fb([&](const MaterialState& m) { return rgb3(m.diffuse); })) &&
              (ts || same_fb([&](const MaterialState& m) { return rgb3(m.specular); })) &&
              (te || same_fb([&](const MaterialState& m) { return rgb3(m.emission); })) &&
              same_fb([](const MaterialState& m) { return m.shininess; })))
          batches = true;  // an untracked term or the shininess changes: each vertex under its own material
      } else {
        std::optional<ColourMaterial> via;
        if (shi && (!L.two_side || (*b[0] == *b[2] && *b[1] == *b[2]))) {
          if (!amb && dif && spe && emi) via = ColourMaterial::Ambient;
          else if (amb && !dif && spe && emi) via = ColourMaterial::Diffuse;
          else if (amb && dif && !spe && emi) via = ColourMaterial::Specular;
          else if (amb && dif && spe && !emi) via = ColourMaterial::Emission;
          else if (!amb && !dif && spe && emi && ad_equal) via = ColourMaterial::AmbientAndDiffuse;
        }
        if (!via) {
          batches = true;  // more than one colour or the shininess: each vertex under its own material
        } else {
          cm = via;
          for (int k = 0; k < 3; ++k) {
            const MaterialState& m = *f[static_cast<size_t>(k)];
            vertex_colour[static_cast<size_t>(k)] = *via == ColourMaterial::Ambient || *via == ColourMaterial::AmbientAndDiffuse
                                                        ? m.ambient
                                                    : *via == ColourMaterial::Diffuse  ? m.diffuse
                                                    : *via == ColourMaterial::Specular ? m.specular
                                                                                        : m.emission;
          }
          ++h.stats.notes["glMaterial between a smooth primitive's vertices carried as colour material"];
        }
      }
    }
    const int mi = scene_material(mid, lit, cm);
    const int lighting = sc.lighting_sets.empty() ? 0 : static_cast<int>(t.lighting);
    const auto key = std::make_tuple(mi, t.flat, cm ? static_cast<int>(*cm) : -1, t.excluded, lighting, t.depth_test,
                                     t.depth_write);
    if (cur < 0 || key != cur_key) {
      scene::Object o;
      o.name = "draw" + std::to_string(sc.objects.size());
      o.type = scene::ObjectType::Mesh;
      o.material = mi;
      o.shading = t.flat ? scene::Shading::Flat : scene::Shading::Gouraud;
      o.colour_material = cm;
      o.lighting = lighting;
      o.depth_test = t.depth_test;
      o.depth_write = t.depth_write;
      o.where = "primitive " + std::to_string(t.primitive);
      o.scene_file = name;
      sc.objects.push_back(o);
      h.meshes.emplace_back();
      h.object_excluded.push_back(t.excluded);
      cur = static_cast<int>(sc.objects.size()) - 1;
      cur_key = key;
    }
    std::array<int, 3> vertex_object{-1, -1, -1};  // material batches: the object lighting each vertex (−1: the run's)
    if (batches)
      for (size_t k = 0; k < 2; ++k) {
        const int mk = scene_material(t.v[k].material, lit, cm);
        if (mk != mi) {
          vertex_object[k] = batch_object(mk, cm, t, lighting);
          ++batched_vertices;
        }
      }
    for (size_t k = 0; k < 3; ++k)  // a batch object's mesh lists the colours of the vertices it lights (derivation)
      if (vertex_object[k] >= 0) h.meshes[static_cast<size_t>(vertex_object[k])].col.push_back(rgb(vertex_colour[k]));
    scene::Mesh& m = h.meshes[static_cast<size_t>(cur)];
    if (batches && m.vertex_object.empty()) m.vertex_object.assign(m.pos.size(), cur);
    if (batches || !m.vertex_object.empty())
      for (size_t k = 0; k < 3; ++k) m.vertex_object.push_back(vertex_object[k] >= 0 ? vertex_object[k] : cur);
    std::vector<int> face;
    for (size_t k = 0; k < 3; ++k) {
      const GlVertex& v = t.v[k];
      const double w = v.eye[3];
      if (w == 0) throw ReplayError(name + ": a vertex at infinity (w = 0) in eye space");
      m.pos.push_back({v.eye[0] / w, v.eye[1] / w, v.eye[2] / w});
      Vec3 nn = v.normal;
      const double l = len3(nn);
      if (lit && std::fabs(l - 1) > 1e-6) {
        ++h.non_unit_normals;
        if (std::fabs(l - 1) > std::fabs(h.worst_normal_length - 1)) h.worst_normal_length = l;
      }
      if (l == 0) nn = {0, 0, 1};
      m.nrm.push_back(nn);
      m.col.push_back(rgb(vertex_colour[k]));
      face.push_back(static_cast<int>(m.pos.size()) - 1);
    }
    m.faces.push_back(face);
  }
  // objects without colour material: no vertex colours (the mesh's colour list stays empty)
  for (size_t i = 0; i < sc.objects.size(); ++i)
    if (!sc.objects[i].colour_material) h.meshes[i].col.clear();
  if (batched_vertices > 0)
    h.stats.notes["glMaterial between a smooth primitive's vertices: vertices lit under their own material (material "
                  "batches)"] += batched_vertices;
  // Eye-space positions outside the core's range [−128, 128) (GL has no such limit): counted with the worst coordinate,
  // and the frame's eye space scaled by the power of two 2^−k that brings every vertex and point light inside. Exact
  // in double: the projection's first three columns × 2^k give the same clip coordinates (the rasterisation and the
  // near plane are unchanged); directions are scale-free and each point light's attenuation keeps its value at every
  // vertex (kl × 2^k, kq × 4^k). Never wrapped.
  double worst = 0;
  auto out_of_range = [&](double x, double y, double z) {
    bool out = false;
    for (double c : {x, y, z}) {
      if (!(c >= -128.0 && c < 128.0)) out = true;
      worst = std::max(worst, std::fabs(c));
    }
    return out;
  };
  bool lights_out = false;
  for (const auto& m : h.meshes)
    for (const auto& p : m.pos)
      if (out_of_range(p[0], p[1], p[2])) ++h.eye_out_of_range;
  // every light of every lighting state (sc.lights is the first state's)
  auto each_light = [&sc](auto fn) {
    for (auto& l : sc.lights) fn(l);
    for (auto& set : sc.lighting_sets)
      for (auto& l : set.lights) fn(l);
  };
  each_light([&](const scene::Light& l) {
    if (l.position[3] != 0 && out_of_range(l.position[0] / l.position[3], l.position[1] / l.position[3], l.position[2] / l.position[3]))
      lights_out = true;
  });
  if (h.eye_out_of_range > 0 || lights_out) {
    if (!std::isfinite(worst)) throw ReplayError(name + ": an eye-space position that is not finite");
    int k = 0;
    while (std::ldexp(worst, -k) >= 128.0) ++k;
    const double f = std::ldexp(1.0, -k);
    for (auto& m : h.meshes)
      for (auto& p : m.pos)
        for (double& c : p) c *= f;
    each_light([f](scene::Light& l) {
      if (l.position[3] != 0) {
        for (int i = 0; i < 3; ++i) l.position[i] *= f;
        l.kl /= f, l.kq /= f * f;
      }
    });
    Mat4 Ps = *h.settings.projection;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 3; ++c) Ps[static_cast<size_t>(4 * r + c)] /= f;
    h.settings.projection = Ps;
    h.eye_worst = worst;
    h.eye_scale = f;
  }
  return h;
}

// ---- frames ---------------------------------------------------------------------------------------------------

namespace {

bool is_swap(const std::string& n) {
  return n == "glXSwapBuffers" || n == "eglSwapBuffers" || n == "wglSwapBuffers" || n == "CGLFlushDrawable" ||
         n == "eglSwapBuffersWithDamageKHR" || n == "eglSwapBuffersWithDamageEXT";
}

// A GL 3.2+ core-profile or a GL ES context: refused (this front end is compatibility GL 1.x).
void check_context(const trace::Call& c, const std::string& name) {
  const std::string& n = c.name();
  if (n == "glXCreateContextAttribsARB" && c.args.size() > 4 && c.args[4].kind == trace::Value::Kind::Array) {
    const auto& a = c.args[4].items;
    int64_t major = 1, profile = 0;
    for (size_t i = 0; i + 1 < a.size(); i += 2) {
      const int64_t k = a[i].integer(), v = a[i + 1].integer();
      if (k == 0x2091) major = v;          // GLX_CONTEXT_MAJOR_VERSION_ARB
      if (k == 0x9126) profile = v;        // GLX_CONTEXT_PROFILE_MASK_ARB
      if (k == 0) break;
    }
    if ((profile & 1) && major >= 3)
      throw ReplayError(name + ": call " + std::to_string(c.no) + " creates an OpenGL " + std::to_string(major) +
                        " core-profile context; replay plays fixed-function OpenGL 1.x (compatibility) programs only");
  }
  if (n == "eglBindAPI" && !c.args.empty() && c.args[0].integer() == 0x30A0)  // EGL_OPENGL_ES_API
    throw ReplayError(name + ": call " + std::to_string(c.no) + " binds OpenGL ES; replay plays desktop OpenGL 1.x programs only");
}

}  // namespace

Handover replay_frame(trace::Reader& reader, const ReplayOptions& o, const std::string& name) {
  if (!o.frame && !o.call) throw ReplayError("replay: a frame or a call is needed");
  if (o.frame && *o.frame < 1) throw ReplayError("replay: frames are numbered from 1");
  Gl gl;
  trace::Call c;
  uint64_t swaps = 0, read = 0, first = 0, in_frame = 0, prev = 0;
  bool done = false, any = false;
  std::string api;
  const uint64_t K = o.frame.value_or(0);
  gl.set_recording(o.call.has_value() || K == 1);
  while (reader.next(c)) {
    ++read;
    check_context(c, name);
    if (api.empty() && (starts(c.name(), "glX"))) api = "glx";
    if (api.empty() && (starts(c.name(), "egl"))) api = "egl";
    if (is_swap(c.name())) {
      ++swaps;
      if (o.frame && swaps == K) {
        done = true;
        break;
      }
      if (o.call && c.no >= *o.call) {
        done = true;
        break;
      }
      gl.clear_frame();
      first = c.no + 1;
      in_frame = 0;
      gl.set_recording(o.call.has_value() || swaps + 1 == K);
      continue;
    }
    if (o.call && c.no > *o.call) {
      done = true;
      break;
    }
    ++in_frame;
    try {
      gl.call(c);
    } catch (const trace::TraceError& e) {  // a malformed argument: name the call
      throw ReplayError(name + ": call " + std::to_string(c.no) + " " + c.name() + ": " + e.what());
    }
    prev = c.no;
    any = true;
    if (o.call && c.no == *o.call) {
      done = true;
      break;
    }
  }
  if (!done) {
    const trace::Reader::Cut cut = reader.cut();
    const std::string why = cut.cut ? ", its stream cut inside call " + std::to_string(cut.call) : "";
    if (o.frame)
      throw ReplayError(name + ": frame " + std::to_string(K) + " is past the end: the capture has " +
                        std::to_string(swaps) + " complete frame" + (swaps == 1 ? "" : "s") + " (" +
                        std::to_string(swaps) + " swap" + (swaps == 1 ? "" : "s") + why + ")");
    throw ReplayError(name + ": call " + std::to_string(*o.call) + " is past the end of the capture (" +
                      std::to_string(read) + " calls" + why + ")");
  }
  if (!any) throw ReplayError(name + ": the capture has no GL calls before the frame's end");
  Handover h = hand_over(gl, name);
  h.frame = o.frame ? K : swaps + 1;
  h.first_call = first;
  h.snapshot_call = prev;
  h.swaps_seen = swaps;
  h.api = api;
  h.stats.calls_read = read;
  h.stats.calls_in_frame = in_frame;
  return h;
}

}  // namespace shadecore::glfront

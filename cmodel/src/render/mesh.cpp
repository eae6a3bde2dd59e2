// SPDX-License-Identifier: Apache-2.0
// shadecore — tessellation and OBJ loading for `shadecore render` (docs/scenes.md "Objects").
#include "shadecore/render/mesh.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

namespace shadecore::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

double len(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
Vec3 unit(const Vec3& v) {
  const double l = len(v);
  return {v[0] / l, v[1] / l, v[2] / l};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Generated faces: orient each one so that its geometric normal agrees with its vertex normals.
void orient_outward(Mesh& m) {
  for (auto& f : m.faces) {
    Vec3 avg{0, 0, 0};
    for (int v : f)
      for (int i = 0; i < 3; ++i) avg[i] += m.nrm[v][i];
    if (dot(polygon_normal(m.pos, f), avg) < 0) std::reverse(f.begin(), f.end());
  }
}

Mesh sphere(const Object& o) {
  Mesh m;
  const int S = o.slices, T = o.stacks;
  const double r = o.radius;
  m.pos.push_back({0, 0, r});
  m.nrm.push_back({0, 0, 1});
  for (int i = 1; i < T; ++i) {
    const double rho = kPi * i / T;
    for (int j = 0; j < S; ++j) {
      const double th = 2 * kPi * j / S;
      const Vec3 n{std::sin(rho) * std::cos(th), std::sin(rho) * std::sin(th), std::cos(rho)};
      m.nrm.push_back(n);
      m.pos.push_back({r * n[0], r * n[1], r * n[2]});
    }
  }
  const int bottom = static_cast<int>(m.pos.size());
  m.pos.push_back({0, 0, -r});
  m.nrm.push_back({0, 0, -1});
  auto ring = [S](int i, int j) { return 1 + (i - 1) * S + ((j % S) + S) % S; };
  for (int j = 0; j < S; ++j) m.faces.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i < T - 1; ++i)
    for (int j = 0; j < S; ++j) m.faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)});
  for (int j = 0; j < S; ++j) m.faces.push_back({bottom, ring(T - 1, j + 1), ring(T - 1, j)});
  orient_outward(m);
  return m;
}

Mesh plane(const Object& o) {
  Mesh m;
  const int n = o.subdivisions;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      m.pos.push_back({o.width * (static_cast<double>(j) / n - 0.5), o.height * (static_cast<double>(i) / n - 0.5), 0});
      m.nrm.push_back({0, 0, 1});
    }
  auto at = [n](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m.faces.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
  orient_outward(m);
  return m;
}

Mesh torus(const Object& o) {
  Mesh m;
  const int R = o.rings, S = o.sides;
  for (int a = 0; a < R; ++a) {
    const double th = 2 * kPi * a / R;
    for (int b = 0; b < S; ++b) {
      const double ph = 2 * kPi * b / S;
      const Vec3 n{std::cos(ph) * std::cos(th), std::cos(ph) * std::sin(th), std::sin(ph)};
      m.nrm.push_back(n);
      m.pos.push_back({(o.outer_radius + o.inner_radius * std::cos(ph)) * std::cos(th),
                       (o.outer_radius + o.inner_radius * std::cos(ph)) * std::sin(th), o.inner_radius * n[2]});
    }
  }
  auto at = [R, S](int a, int b) { return ((a % R + R) % R) * S + (b % S + S) % S; };
  for (int a = 0; a < R; ++a)
    for (int b = 0; b < S; ++b) m.faces.push_back({at(a, b), at(a + 1, b), at(a + 1, b + 1), at(a, b + 1)});
  orient_outward(m);
  return m;
}

[[noreturn]] void obj_fail(const Object& o, const std::string& what) {
  throw SceneError(printable(o.scene_file + ": " + o.where + ".file: " + printable(o.file_path, 200) + ": " + what, 0));
}
[[noreturn]] void obj_fail_line(const Object& o, size_t line, const std::string& what) {
  throw SceneError(printable(o.scene_file + ": " + o.where + ".file: " + printable(o.file_path, 200) + ":" +
                                 std::to_string(line) + ": " + what,
                             0));
}

// The lines tinyobjloader reads as vertex data and faces, checked first (it maps nan / inf to 0 and wraps
// overflowing indices): every number of a `v` / `vn` line finite and parsable, every index of an `f` line a
// non-zero integer that fits and refers to an element that exists (positive: 1..count in the file;
// negative, relative: at most as many back as there are before the line), at most kMaxFaceVertices per face.
// Vertex colours (the `v x y z r g b` extension, as tinyobjloader reads it: a `v` line with 6 or more numbers has
// the colour r g b in its 4th..6th): each in [0, 1], and on every `v` line or on none (tinyobjloader would fill in
// white for the others). Returns whether the file has vertex colours.
bool prescan_obj(const Object& o, const std::string& text) {
  struct FaceRef {
    size_t line;
    long long idx[3];  // v, vt, vn; 0 = absent
  };
  std::vector<FaceRef> refs;
  long long count[3] = {0, 0, 0};  // v, vt, vn so far
  size_t coloured = 0, first_plain = 0, first_coloured = 0;  // v lines with a colour; the first line without / with
  size_t line = 0;
  size_t pos = 0;
  auto is_space = [](char c) { return c == ' ' || c == '\t'; };
  const char* kind_name[3] = {"vertex", "texture coordinate", "normal"};
  while (pos < text.size()) {
    ++line;
    size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    std::string ln = text.substr(pos, eol - pos);
    pos = eol + 1;
    if (!ln.empty() && ln.back() == '\r') ln.pop_back();
    size_t b = 0;
    while (b < ln.size() && is_space(ln[b])) ++b;
    // tokens after the keyword, up to a '#'
    auto tokens = [&](size_t from) {
      std::vector<std::string> t;
      size_t k = from;
      while (k < ln.size()) {
        while (k < ln.size() && is_space(ln[k])) ++k;
        if (k >= ln.size() || ln[k] == '#') break;
        size_t e = k;
        while (e < ln.size() && !is_space(ln[e])) ++e;
        t.push_back(ln.substr(k, e - k));
        k = e;
      }
      return t;
    };
    const bool v = ln.size() > b + 1 && ln[b] == 'v' && is_space(ln[b + 1]);
    const bool vn = ln.size() > b + 2 && ln[b] == 'v' && ln[b + 1] == 'n' && is_space(ln[b + 2]);
    const bool vt = ln.size() > b + 2 && ln[b] == 'v' && ln[b + 1] == 't' && is_space(ln[b + 2]);
    const bool f = ln.size() > b + 1 && ln[b] == 'f' && is_space(ln[b + 1]);
    if (v || vn) {
      const auto t = tokens(b + (v ? 2 : 3));
      if (t.size() < 3) obj_fail_line(o, line, std::string(v ? "v" : "vn") + " needs 3 coordinates");
      for (const auto& tok : t) {
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(tok.c_str(), &end);
        const bool plain = tok.find_first_not_of("0123456789+-.eE") == std::string::npos;  // no hex, no "nan"
        if (end != tok.c_str() + tok.size() || (!plain && std::isfinite(x)))
          obj_fail_line(o, line, "'" + printable(tok, 60) + "' is not a number");
        if (!std::isfinite(x))
          obj_fail_line(o, line, "'" + printable(tok, 60) + "' is not a finite number (NaN, infinity or out of range)");
        if (!(std::fabs(x) <= kMaxCoord))
          obj_fail_line(o, line, "'" + printable(tok, 60) + "' out of range [-1e6, 1e6]");
        const size_t i = static_cast<size_t>(&tok - t.data());
        if (v && t.size() >= 6 && i >= 3 && i < 6 && !(x >= 0 && x <= 1))
          obj_fail_line(o, line, "vertex colour '" + printable(tok, 60) + "' out of range [0, 1]");
      }
      if (v && t.size() >= 6) {
        if (!coloured++) first_coloured = line;
      } else if (v && !first_plain) {
        first_plain = line;
      }
      ++count[v ? 0 : 2];
    } else if (vt) {
      ++count[1];
    } else if (f) {
      const auto t = tokens(b + 2);
      if (t.size() > static_cast<size_t>(kMaxFaceVertices))
        obj_fail_line(o, line, "a face with " + std::to_string(t.size()) + " vertices; at most " +
                                   std::to_string(kMaxFaceVertices));
      for (const auto& tok : t) {
        FaceRef r{line, {0, 0, 0}};
        size_t k = 0;
        for (int c = 0; c < 3 && k <= tok.size(); ++c) {
          size_t e = tok.find('/', k);
          if (e == std::string::npos) e = tok.size();
          const std::string part = tok.substr(k, e - k);
          k = e + 1;
          if (part.empty()) {
            if (c == 0) obj_fail_line(o, line, "face vertex '" + printable(tok, 60) + "' has no vertex index");
            continue;
          }
          char* end = nullptr;
          errno = 0;
          const long long x = std::strtoll(part.c_str(), &end, 10);
          if (end != part.c_str() + part.size())
            obj_fail_line(o, line, "face index '" + printable(part, 60) + "' is not an integer");
          if (errno == ERANGE || x > INT_MAX || x < -static_cast<long long>(INT_MAX))
            obj_fail_line(o, line, std::string(kind_name[c]) + " index " + printable(part, 60) + " overflows");
          if (x == 0) obj_fail_line(o, line, std::string(kind_name[c]) + " index 0 (OBJ indices start at 1)");
          if (x < 0 && -x > count[c])
            obj_fail_line(o, line, "relative " + std::string(kind_name[c]) + " index " + std::to_string(x) + " but only " +
                                       std::to_string(count[c]) + " before this line");
          r.idx[c] = x;
        }
        if (k <= tok.size()) obj_fail_line(o, line, "face vertex '" + printable(tok, 60) + "' has more than v/vt/vn");
        refs.push_back(r);
      }
    }
  }
  for (const auto& r : refs)
    for (int c = 0; c < 3; ++c)
      if (r.idx[c] > count[c])
        obj_fail_line(o, r.line, std::string(kind_name[c]) + " index " + std::to_string(r.idx[c]) + " out of range (" +
                                     std::to_string(count[c]) + " in the file)");
  if (coloured && first_plain)
    obj_fail_line(o, first_plain, "a vertex without a colour, but line " + std::to_string(first_coloured) +
                                      " has one (vertex colours 'v x y z r g b' on every v line or on none)");
  return coloured > 0;
}

// Degenerate faces: zero area relative to the face's size (also catches repeated vertices).
void check_faces(const Object& o, const Mesh& m) {
  for (size_t fi = 0; fi < m.faces.size(); ++fi) {
    const auto& f = m.faces[fi];
    double ext = 0;
    for (size_t i = 0; i < f.size(); ++i) {
      const Vec3& a = m.pos[f[i]];
      const Vec3& b = m.pos[f[(i + 1) % f.size()]];
      ext = std::max(ext, len({a[0] - b[0], a[1] - b[1], a[2] - b[2]}));
    }
    if (!(len(polygon_normal(m.pos, f)) > 1e-9 * ext * ext) || !(ext > 0)) {
      const std::string what = "face " + std::to_string(fi + 1) + " is degenerate (zero area)";
      if (o.type == ObjectType::Mesh) obj_fail(o, what);
      throw SceneError(o.scene_file + ": " + o.where + ": " + what);
    }
  }
}

Mesh obj_mesh(const Object& o) {
  // A regular file of at most kMaxObjBytes, read without blocking; then checked (prescan_obj) and parsed from
  // memory: tinyobjloader never opens anything itself (not even an mtllib: OBJ materials are not used).
  std::string text, why;
  if (!read_regular_file(o.file_path, kMaxObjBytes, text, why)) obj_fail(o, why == "no such file" ? "no such OBJ file" : why);
  const bool colours = prescan_obj(o, text);
  tinyobj::ObjReaderConfig cfg;
  cfg.triangulate = false;
  cfg.vertex_color = false;  // no white fill-in (tinyobjloader 2.0.0rc10: colours only when every v line has one)
  tinyobj::ObjReader rd;
  if (!rd.ParseFromString(text, std::string(), cfg)) {
    std::string e = rd.Error();
    while (!e.empty() && (e.back() == '\n' || e.back() == '\r')) e.pop_back();
    const auto nl = e.find('\n');
    if (nl != std::string::npos) e = e.substr(0, nl);
    obj_fail(o, "malformed OBJ: " + (e.empty() ? std::string("parse failed") : e));
  }
  const auto& at = rd.GetAttrib();
  const size_t nv = at.vertices.size() / 3, nn = at.normals.size() / 3;
  bool all_normals = true;
  size_t nfaces = 0;
  for (const auto& sh : rd.GetShapes()) {
    nfaces += sh.mesh.num_face_vertices.size();
    for (const auto& ix : sh.mesh.indices) all_normals = all_normals && ix.normal_index >= 0;
  }
  if (nfaces == 0) obj_fail(o, "malformed OBJ: no faces");
  if (colours && at.colors.size() != at.vertices.size())
    obj_fail(o, "tinyobjloader returned " + std::to_string(at.colors.size() / 3) + " vertex colours for " +
                    std::to_string(nv) + " vertices");
  Mesh m;
  std::map<std::pair<int, int>, int> ids;  // (v, vn) -> vertex
  size_t face_no = 0;
  for (const auto& sh : rd.GetShapes()) {
    size_t k = 0;
    for (unsigned char fv : sh.mesh.num_face_vertices) {
      ++face_no;
      if (fv < 3) obj_fail(o, "face " + std::to_string(face_no) + " has fewer than 3 vertices");
      std::vector<int> f;
      for (unsigned i = 0; i < fv; ++i, ++k) {
        const auto& ix = sh.mesh.indices[k];
        if (ix.vertex_index < 0 || static_cast<size_t>(ix.vertex_index) >= nv)
          obj_fail(o, "face " + std::to_string(face_no) + ": vertex index out of range");
        int ni = -1;
        if (all_normals) {
          if (static_cast<size_t>(ix.normal_index) >= nn)
            obj_fail(o, "face " + std::to_string(face_no) + ": normal index out of range");
          ni = ix.normal_index;
        }
        const auto key = std::make_pair(ix.vertex_index, ni);
        auto it = ids.find(key);
        if (it == ids.end()) {
          const int id = static_cast<int>(m.pos.size());
          const Vec3 p{at.vertices[3 * ix.vertex_index], at.vertices[3 * ix.vertex_index + 1],
                       at.vertices[3 * ix.vertex_index + 2]};
          for (double c : p)
            if (!std::isfinite(c)) obj_fail(o, "vertex " + std::to_string(ix.vertex_index + 1) + " is not finite");
          m.pos.push_back(p);
          Vec3 n{0, 0, 0};
          if (ni >= 0) {
            n = {at.normals[3 * ni], at.normals[3 * ni + 1], at.normals[3 * ni + 2]};
            if (!(len(n) > 1e-12) || !std::isfinite(len(n)))
              obj_fail(o, "normal " + std::to_string(ni + 1) + " is zero or not finite");
            n = unit(n);
          }
          m.nrm.push_back(n);
          if (colours)
            m.col.push_back({at.colors[3 * ix.vertex_index], at.colors[3 * ix.vertex_index + 1],
                             at.colors[3 * ix.vertex_index + 2]});
          it = ids.emplace(key, id).first;
        }
        f.push_back(it->second);
      }
      m.faces.push_back(std::move(f));
    }
  }
  check_faces(o, m);
  if (!all_normals) {
    // Smooth normals: area-weighted face normals summed per OBJ position.
    std::map<int, Vec3> acc;
    std::vector<int> pos_of(m.pos.size());
    for (const auto& kv : ids) pos_of[kv.second] = kv.first.first;
    for (const auto& f : m.faces) {
      const Vec3 fn = polygon_normal(m.pos, f);
      for (int v : f)
        for (int i = 0; i < 3; ++i) acc[pos_of[v]][i] += fn[i];
    }
    for (size_t v = 0; v < m.pos.size(); ++v) {
      const Vec3 s = acc[pos_of[v]];
      if (!(len(s) > 0)) obj_fail(o, "vertex " + std::to_string(pos_of[v] + 1) + ": its faces' normals cancel (no normal)");
      m.nrm[v] = unit(s);
    }
  }
  return m;
}

}  // namespace

Vec3 polygon_normal(const std::vector<Vec3>& pos, const std::vector<int>& face) {
  Vec3 n{0, 0, 0};
  for (size_t i = 0; i < face.size(); ++i) {
    const Vec3& a = pos[face[i]];
    const Vec3& b = pos[face[(i + 1) % face.size()]];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

Mesh build_mesh(const Object& o) {
  Mesh m;
  switch (o.type) {
    case ObjectType::Sphere: m = sphere(o); break;
    case ObjectType::Plane: m = plane(o); break;
    case ObjectType::Torus: m = torus(o); break;
    case ObjectType::Mesh: m = obj_mesh(o); break;
  }
  check_faces(o, m);
  return m;
}

}  // namespace shadecore::scene

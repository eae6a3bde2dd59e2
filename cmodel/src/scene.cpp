// shadecore — scene file parsing (docs/scenes.md). Strict: every error is one line "FILE: PATH: what".
#include "shadecore/scene.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "shadecore/features.hpp"

namespace shadecore::scene {

using json = nlohmann::ordered_json;

const char* to_string(Shading s) {
  switch (s) {
    case Shading::Flat: return "flat";
    case Shading::Gouraud: return "gouraud";
    case Shading::Phong: return "phong";
  }
  return "?";
}

Shading parse_shading(const std::string& s) {
  if (s == "flat") return Shading::Flat;
  if (s == "gouraud") return Shading::Gouraud;
  if (s == "phong") return Shading::Phong;
  throw std::invalid_argument("unknown shading mode '" + s + "' (known: flat, gouraud, phong)");
}

namespace {

constexpr int kMaxImage = 4096;

class Parser {
 public:
  explicit Parser(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw SceneError(file_ + ": " + (path.empty() ? "" : path + ": ") + what);
  }

  // An object whose keys are all in `allowed` ("_comment" is allowed everywhere).
  void keys(const json& j, const std::string& path, std::initializer_list<const char*> allowed) const {
    if (!j.is_object()) fail(path, "must be a JSON object");
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (it.key() == "_comment") continue;
      bool ok = false;
      for (const char* a : allowed) ok = ok || it.key() == a;
      if (!ok) {
        std::string known;
        for (const char* a : allowed) known += (known.empty() ? "" : ", ") + std::string(a);
        fail(join(path, it.key()), "unknown key (known here: " + known + ")");
      }
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string index(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

  double number(const json& v, const std::string& path) const {
    if (!v.is_number()) fail(path, "must be a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(path, "must be finite");
    return x;
  }
  double number_in(const json& v, const std::string& path, double lo, bool lo_incl, double hi, bool hi_incl,
                   const std::string& range_text) const {
    const double x = number(v, path);
    const bool ok = (lo_incl ? x >= lo : x > lo) && (hi_incl ? x <= hi : x < hi);
    if (!ok) fail(path, fmt_num(x) + " out of range " + range_text);
    return x;
  }
  int integer(const json& v, const std::string& path, long long lo, long long hi) const {
    if (!v.is_number_integer()) fail(path, "must be an integer");
    const long long x = v.get<long long>();
    if (x < lo || x > hi) fail(path, std::to_string(x) + " out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    return static_cast<int>(x);
  }
  bool boolean(const json& v, const std::string& path) const {
    if (!v.is_boolean()) fail(path, "must be true or false");
    return v.get<bool>();
  }
  std::string string(const json& v, const std::string& path) const {
    if (!v.is_string()) fail(path, "must be a string");
    return v.get<std::string>();
  }
  template <size_t N>
  std::array<double, N> vec(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != N) fail(path, "must be a list of " + std::to_string(N) + " numbers");
    std::array<double, N> a{};
    for (size_t i = 0; i < N; ++i) a[i] = number(v[i], index(path, i));
    return a;
  }
  Vec3 colour(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != 3) fail(path, "must be a colour [r, g, b]");
    Vec3 c{};
    for (size_t i = 0; i < 3; ++i)
      c[i] = number_in(v[i], index(path, i), 0.0, true, 2.0, false, "[0, 2) (the core's colour format)");
    return c;
  }

  static std::string fmt_num(double x) {
    std::ostringstream ss;
    ss << x;
    return ss.str();
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

// Duplicate keys: nlohmann keeps the last one silently, so the parser callback tracks every object's
// keys (and the JSON path, for the message).
struct PathTracker {
  struct Level {
    bool is_object;
    std::string key;
    long idx = -1;
    std::set<std::string> keys;
  };
  std::vector<Level> stack;
  std::string dup_path;

  std::string path() const {
    std::string p;
    for (const auto& l : stack) {
      if (l.is_object) p += (p.empty() ? "" : ".") + l.key;
      else p += "[" + std::to_string(l.idx) + "]";
    }
    return p;
  }
  void element() {
    if (!stack.empty() && !stack.back().is_object) ++stack.back().idx;
  }
};

Camera parse_camera(const Parser& P, const json& j, const std::string& path) {
  P.keys(j, path, {"eye", "center", "up", "fovy", "near", "far"});
  Camera c;
  if (j.contains("eye")) c.eye = P.vec<3>(j["eye"], path + ".eye");
  if (j.contains("center")) c.center = P.vec<3>(j["center"], path + ".center");
  if (j.contains("up")) c.up = P.vec<3>(j["up"], path + ".up");
  if (j.contains("fovy")) c.fovy = P.number_in(j["fovy"], path + ".fovy", 0, false, 180, false, "(0, 180) degrees");
  if (j.contains("near")) c.near = P.number_in(j["near"], path + ".near", 1e-3, true, 1e6, true, "[0.001, 1e6]");
  if (j.contains("far")) c.far = P.number_in(j["far"], path + ".far", 1e-3, true, 1e9, true, "[0.001, 1e9]");
  if (!(c.far > c.near)) P.fail(path + ".far", "must be greater than near");
  if (c.far / c.near > 1e6) P.fail(path + ".far", "far/near must be at most 1e6 (depth precision)");
  const Vec3 f{c.center[0] - c.eye[0], c.center[1] - c.eye[1], c.center[2] - c.eye[2]};
  const double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  if (!(fl > 1e-9)) P.fail(path, "degenerate camera: eye and center coincide");
  const double ul = std::sqrt(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]);
  if (!(ul > 1e-9)) P.fail(path + ".up", "degenerate camera: up is the zero vector");
  const Vec3 s{f[1] * c.up[2] - f[2] * c.up[1], f[2] * c.up[0] - f[0] * c.up[2], f[0] * c.up[1] - f[1] * c.up[0]};
  if (std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) <= 1e-9 * fl * ul)
    P.fail(path + ".up", "degenerate camera: up is parallel to the viewing direction");
  return c;
}

Light parse_light(const Parser& P, const json& j, const std::string& path) {
  P.keys(j, path, {"position", "ambient", "diffuse", "specular", "constant_attenuation", "linear_attenuation",
                   "quadratic_attenuation"});
  Light l;
  if (!j.contains("position")) P.fail(path, "missing 'position' [x, y, z, w]");
  l.position = P.vec<4>(j["position"], path + ".position");
  if (l.position[3] == 0.0 && l.position[0] == 0.0 && l.position[1] == 0.0 && l.position[2] == 0.0)
    P.fail(path + ".position", "a directional light (w = 0) needs a non-zero direction");
  if (j.contains("ambient")) l.ambient = P.colour(j["ambient"], path + ".ambient");
  if (j.contains("diffuse")) l.diffuse = P.colour(j["diffuse"], path + ".diffuse");
  if (j.contains("specular")) l.specular = P.colour(j["specular"], path + ".specular");
  const char* att_range = "[0, 256) (the core's attenuation format)";
  if (j.contains("constant_attenuation"))
    l.kc = P.number_in(j["constant_attenuation"], path + ".constant_attenuation", 0, true, 256, false, att_range);
  if (j.contains("linear_attenuation"))
    l.kl = P.number_in(j["linear_attenuation"], path + ".linear_attenuation", 0, true, 256, false, att_range);
  if (j.contains("quadratic_attenuation"))
    l.kq = P.number_in(j["quadratic_attenuation"], path + ".quadratic_attenuation", 0, true, 256, false, att_range);
  if (l.position[3] != 0.0) {
    // The core's attenuation registers hold F fraction bits; all three rounding to 0 is rejected too.
    const double q = 1.0 / 65536.0 / 2;
    if (l.kc < q && l.kl < q && l.kq < q)
      P.fail(path, "constant, linear and quadratic attenuation are all 0 (1/0 attenuation)");
  } else if (j.contains("linear_attenuation") || j.contains("quadratic_attenuation") ||
             (j.contains("constant_attenuation") && l.kc != 1.0)) {
    P.fail(path, "attenuation applies to point lights only (w != 0); GL ignores it for directional lights");
  }
  return l;
}

Material parse_material(const Parser& P, const json& j, const std::string& path, const std::string& name) {
  P.keys(j, path, {"emission", "ambient", "diffuse", "specular", "shininess", "specular_unit", "cutoff",
                   "normalization"});
  Material m;
  m.name = name;
  if (j.contains("emission")) m.emission = P.colour(j["emission"], path + ".emission");
  if (j.contains("ambient")) m.ambient = P.colour(j["ambient"], path + ".ambient");
  if (j.contains("diffuse")) m.diffuse = P.colour(j["diffuse"], path + ".diffuse");
  if (j.contains("specular")) m.specular = P.colour(j["specular"], path + ".specular");
  if (j.contains("shininess"))
    m.shininess = P.integer(j["shininess"], path + ".shininess", kNMin, kNMax);
  if (j.contains("specular_unit")) {
    const std::string s = P.string(j["specular_unit"], path + ".specular_unit");
    try {
      m.unit = parse_variant(s);
    } catch (const std::invalid_argument& e) {
      P.fail(path + ".specular_unit", e.what());
    }
  }
  if (j.contains("cutoff")) {
    if (m.unit != VariantId::cs16) P.fail(path + ".cutoff", "applies to the cs16 unit only");
    try {
      m.cutoff = parse_cutoff_name(P.string(j["cutoff"], path + ".cutoff"));
    } catch (const std::invalid_argument& e) {
      P.fail(path + ".cutoff", e.what());
    }
  }
  if (j.contains("normalization")) {
    const std::string np = path + ".normalization";
    const json& n = j["normalization"];
    P.keys(n, np, {"model", "coefficient"});
    Normalization nz;
    if (!n.contains("model")) P.fail(np, "missing 'model'");
    try {
      nz.model = parse_model(P.string(n["model"], np + ".model"));
    } catch (const std::invalid_argument& e) {
      P.fail(np + ".model", e.what());
    }
    if (n.contains("coefficient")) {
      try {
        nz.kind = parse_coef_kind(P.string(n["coefficient"], np + ".coefficient"));
      } catch (const std::invalid_argument& e) {
        P.fail(np + ".coefficient", e.what());
      }
    }
    m.normalization = nz;
  }
  return m;
}

Transform parse_transform(const Parser& P, const json& j, const std::string& path) {
  P.keys(j, path, {"translate", "rotate", "scale"});
  Transform t;
  if (j.contains("translate")) t.translate = P.vec<3>(j["translate"], path + ".translate");
  if (j.contains("rotate")) {
    const json& r = j["rotate"];
    const std::string rp = path + ".rotate";
    auto one = [&](const json& e, const std::string& p) {
      const auto a = P.vec<4>(e, p);
      Rotation rot{a[0], {a[1], a[2], a[3]}};
      if (a[1] == 0 && a[2] == 0 && a[3] == 0) P.fail(p, "rotation axis is the zero vector");
      return rot;
    };
    if (r.is_array() && !r.empty() && r[0].is_array()) {
      for (size_t i = 0; i < r.size(); ++i) t.rotate.push_back(one(r[i], Parser::index(rp, i)));
    } else {
      if (!r.is_array() || r.size() != 4)
        P.fail(rp, "must be [angle_degrees, x, y, z] or a list of them (applied in order, as glRotated calls)");
      t.rotate.push_back(one(r, rp));
    }
  }
  if (j.contains("scale")) {
    const json& s = j["scale"];
    if (s.is_number()) {
      const double x = P.number(s, path + ".scale");
      t.scale = {x, x, x};
    } else {
      t.scale = P.vec<3>(s, path + ".scale");
    }
    for (double x : t.scale)
      if (x == 0.0) P.fail(path + ".scale", "a zero scale makes the object degenerate");
  }
  return t;
}

Object parse_object(const Parser& P, const json& j, const std::string& path, const Scene& sc) {
  if (!j.is_object()) P.fail(path, "must be a JSON object");
  if (!j.contains("type")) P.fail(path, "missing 'type' (sphere, plane or quad, torus, mesh)");
  const std::string type = P.string(j["type"], path + ".type");
  Object o;
  o.where = path;
  o.scene_file = P.file();
  if (type == "sphere") {
    o.type = ObjectType::Sphere;
    P.keys(j, path, {"type", "name", "material", "shading", "transform", "radius", "slices", "stacks"});
    if (j.contains("radius")) o.radius = P.number_in(j["radius"], path + ".radius", 0, false, 1e4, true, "(0, 1e4]");
    if (j.contains("slices")) o.slices = P.integer(j["slices"], path + ".slices", 3, 1024);
    if (j.contains("stacks")) o.stacks = P.integer(j["stacks"], path + ".stacks", 2, 1024);
  } else if (type == "plane" || type == "quad") {  // "quad": the same object (one quad unless subdivided)
    o.type = ObjectType::Plane;
    P.keys(j, path, {"type", "name", "material", "shading", "transform", "size", "subdivisions"});
    if (j.contains("size")) {
      const auto s = P.vec<2>(j["size"], path + ".size");
      if (!(s[0] > 0) || !(s[1] > 0)) P.fail(path + ".size", "width and height must be > 0");
      o.width = s[0];
      o.height = s[1];
    }
    if (j.contains("subdivisions")) o.subdivisions = P.integer(j["subdivisions"], path + ".subdivisions", 1, 1024);
  } else if (type == "torus") {
    o.type = ObjectType::Torus;
    P.keys(j, path, {"type", "name", "material", "shading", "transform", "inner_radius", "outer_radius", "sides",
                     "rings"});
    if (j.contains("inner_radius"))
      o.inner_radius = P.number_in(j["inner_radius"], path + ".inner_radius", 0, false, 1e4, true, "(0, 1e4]");
    if (j.contains("outer_radius"))
      o.outer_radius = P.number_in(j["outer_radius"], path + ".outer_radius", 0, false, 1e4, true, "(0, 1e4]");
    if (!(o.inner_radius < o.outer_radius)) P.fail(path, "inner_radius must be smaller than outer_radius");
    if (j.contains("sides")) o.sides = P.integer(j["sides"], path + ".sides", 3, 1024);
    if (j.contains("rings")) o.rings = P.integer(j["rings"], path + ".rings", 3, 1024);
  } else if (type == "mesh") {
    o.type = ObjectType::Mesh;
    P.keys(j, path, {"type", "name", "material", "shading", "transform", "file"});
    if (!j.contains("file")) P.fail(path, "missing 'file' (an OBJ file, relative to the scene file)");
    o.file = P.string(j["file"], path + ".file");
    if (o.file.empty()) P.fail(path + ".file", "empty file name");
    const std::filesystem::path fp(o.file);
    o.file_path = fp.is_absolute() || sc.dir.empty() ? o.file : (std::filesystem::path(sc.dir) / fp).string();
  } else {
    P.fail(path + ".type", "unknown object type '" + type + "' (known: sphere, plane or quad, torus, mesh)");
  }
  o.name = j.contains("name") ? P.string(j["name"], path + ".name") : path;
  if (!j.contains("material")) P.fail(path, "missing 'material'");
  const std::string mat = P.string(j["material"], path + ".material");
  bool found = false;
  for (size_t i = 0; i < sc.materials.size(); ++i)
    if (sc.materials[i].name == mat) o.material = static_cast<int>(i), found = true;
  if (!found) P.fail(path + ".material", "unknown material '" + mat + "'");
  if (j.contains("shading")) {
    try {
      o.shading = parse_shading(P.string(j["shading"], path + ".shading"));
    } catch (const std::invalid_argument& e) {
      P.fail(path + ".shading", e.what());
    }
  }
  if (j.contains("transform")) o.transform = parse_transform(P, j["transform"], path + ".transform");
  return o;
}

ContactSheet parse_contact_sheet(const Parser& P, const json& j, const std::string& path, const Scene& sc) {
  P.keys(j, path, {"modes", "units", "cell", "camera", "objects"});
  ContactSheet cs;
  if (j.contains("modes")) {
    const json& m = j["modes"];
    if (!m.is_array() || m.empty() || m.size() > 8) P.fail(path + ".modes", "must be a list of 1..8 shading modes");
    for (size_t i = 0; i < m.size(); ++i) {
      const std::string s = P.string(m[i], Parser::index(path + ".modes", i));
      if (s == "scene") cs.modes.push_back(std::nullopt);
      else {
        try {
          cs.modes.push_back(parse_shading(s));
        } catch (const std::invalid_argument& e) {
          P.fail(Parser::index(path + ".modes", i), std::string(e.what()) + " or scene");
        }
      }
    }
  } else {
    cs.modes.push_back(std::nullopt);
  }
  if (!j.contains("units")) P.fail(path, "missing 'units' (specular units compared with exact cos^n)");
  const json& u = j["units"];
  if (!u.is_array() || u.empty() || u.size() > 4) P.fail(path + ".units", "must be a list of 1..4 specular units");
  for (size_t i = 0; i < u.size(); ++i) {
    try {
      cs.units.push_back(parse_variant(P.string(u[i], Parser::index(path + ".units", i))));
    } catch (const std::invalid_argument& e) {
      P.fail(Parser::index(path + ".units", i), e.what());
    }
  }
  if (j.contains("cell")) {
    const json& c = j["cell"];
    if (!c.is_array() || c.size() != 2) P.fail(path + ".cell", "must be [width, height]");
    cs.cell_width = P.integer(c[0], path + ".cell[0]", 16, 1024);
    cs.cell_height = P.integer(c[1], path + ".cell[1]", 16, 1024);
  }
  if (j.contains("camera")) cs.camera = parse_camera(P, j["camera"], path + ".camera");
  if (j.contains("objects")) {
    const json& o = j["objects"];
    if (!o.is_array() || o.empty()) P.fail(path + ".objects", "must be a non-empty list of object indices");
    for (size_t i = 0; i < o.size(); ++i)
      cs.objects.push_back(P.integer(o[i], Parser::index(path + ".objects", i), 0,
                                     static_cast<long long>(sc.objects.size()) - 1));
  }
  return cs;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const std::string& dir) {
  Parser P(name);
  PathTracker pt;
  json root;
  try {
    json::parser_callback_t cb = [&pt](int, json::parse_event_t ev, json& parsed) {
      using E = json::parse_event_t;
      switch (ev) {
        case E::object_start:
          pt.element();
          pt.stack.push_back({true, "", -1, {}});
          break;
        case E::array_start:
          pt.element();
          pt.stack.push_back({false, "", -1, {}});
          break;
        case E::object_end:
        case E::array_end:
          if (!pt.stack.empty()) pt.stack.pop_back();
          break;
        case E::key: {
          const std::string k = parsed.get<std::string>();
          auto& top = pt.stack.back();
          top.key = k;
          if (!top.keys.insert(k).second && pt.dup_path.empty()) pt.dup_path = pt.path();
          break;
        }
        case E::value:
          pt.element();
          break;
      }
      return true;
    };
    root = json::parse(text, cb);
  } catch (const json::parse_error& e) {
    // Line and column of the byte where parsing stopped (e.byte is 1-based).
    size_t line = 1, col = 1;
    const size_t end = std::min(text.size(), e.byte > 0 ? static_cast<size_t>(e.byte - 1) : size_t{0});
    for (size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') ++line, col = 1;
      else ++col;
    }
    std::string msg = e.what();
    const auto p = msg.find(": syntax error");
    std::string detail = p != std::string::npos ? msg.substr(p + 2) : msg;
    // nlohmann repeats the position in its text; keep the part after it.
    const auto q = detail.find(": ");
    if (q != std::string::npos && detail.rfind("syntax error", 0) == 0) detail = detail.substr(q + 2);
    for (auto& ch : detail)
      if (ch == '\n') ch = ' ';
    throw SceneError(name + ":" + std::to_string(line) + ":" + std::to_string(col) + ": malformed JSON: " + detail);
  }
  if (!pt.dup_path.empty()) P.fail(pt.dup_path, "duplicate key");

  Scene sc;
  sc.file = name;
  sc.dir = dir;
  P.keys(root, "", {"image", "camera", "light_model", "lights", "materials", "objects", "contact_sheet", "config"});
  if (!root.contains("image")) P.fail("", "missing 'image' {width, height}");
  {
    const json& im = root["image"];
    P.keys(im, "image", {"width", "height", "background"});
    if (!im.contains("width") || !im.contains("height")) P.fail("image", "needs 'width' and 'height'");
    sc.width = P.integer(im["width"], "image.width", 1, kMaxImage);
    sc.height = P.integer(im["height"], "image.height", 1, kMaxImage);
    if (im.contains("background")) {
      const json& b = im["background"];
      if (!b.is_array() || b.size() != 3) P.fail("image.background", "must be a colour [r, g, b]");
      for (size_t i = 0; i < 3; ++i)
        sc.background[i] = P.number_in(b[i], Parser::index("image.background", i), 0, true, 1, true, "[0, 1]");
    }
  }
  if (!root.contains("camera")) P.fail("", "missing 'camera'");
  sc.camera = parse_camera(P, root["camera"], "camera");
  if (root.contains("config")) {
    sc.config = P.string(root["config"], "config");
    try {
      const Format f = config_named(sc.config).format;
      if (f.frac > kLightFracMax)
        P.fail("config", "'" + sc.config + "' has frac " + std::to_string(f.frac) + "; the lighting core supports frac <= " +
                             std::to_string(kLightFracMax));
    } catch (const std::invalid_argument& e) {
      P.fail("config", e.what());
    }
  }
  if (root.contains("light_model")) {
    const json& lm = root["light_model"];
    P.keys(lm, "light_model", {"ambient", "local_viewer", "reflection"});
    if (lm.contains("ambient")) sc.global_ambient = P.colour(lm["ambient"], "light_model.ambient");
    if (lm.contains("local_viewer")) sc.local_viewer = P.boolean(lm["local_viewer"], "light_model.local_viewer");
    if (lm.contains("reflection")) {
      const std::string r = P.string(lm["reflection"], "light_model.reflection");
      if (r != "blinn" && r != "phong") P.fail("light_model.reflection", "must be blinn or phong");
      sc.blinn = r == "blinn";
    }
  }
  if (root.contains("lights")) {
    const json& ls = root["lights"];
    if (!ls.is_array()) P.fail("lights", "must be a list of lights");
    if (ls.size() > static_cast<size_t>(kMaxLights))
      P.fail("lights", std::to_string(ls.size()) + " lights; the core supports at most " + std::to_string(kMaxLights));
    for (size_t i = 0; i < ls.size(); ++i) sc.lights.push_back(parse_light(P, ls[i], Parser::index("lights", i)));
  }
  if (!root.contains("materials")) P.fail("", "missing 'materials' {name: {...}}");
  {
    const json& ms = root["materials"];
    if (!ms.is_object() || ms.empty()) P.fail("materials", "must be a non-empty object {name: material}");
    for (auto it = ms.begin(); it != ms.end(); ++it) {
      if (it.key() == "_comment") continue;
      sc.materials.push_back(parse_material(P, it.value(), "materials." + it.key(), it.key()));
    }
    if (sc.materials.empty()) P.fail("materials", "no material defined");
  }
  if (!root.contains("objects")) P.fail("", "missing 'objects'");
  {
    const json& os = root["objects"];
    if (!os.is_array() || os.empty()) P.fail("objects", "must be a non-empty list of objects");
    if (os.size() > 256) P.fail("objects", "at most 256 objects");
    for (size_t i = 0; i < os.size(); ++i) sc.objects.push_back(parse_object(P, os[i], Parser::index("objects", i), sc));
  }
  if (root.contains("contact_sheet")) sc.contact_sheet = parse_contact_sheet(P, root["contact_sheet"], "contact_sheet", sc);
  return sc;
}

Scene load_scene(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError(path + ": is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot read the scene file (" + std::string(std::strerror(errno)) + ")");
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read the scene file");
  const std::filesystem::path p(path);
  return parse_scene(ss.str(), path, p.has_parent_path() ? p.parent_path().string() : std::string("."));
}

}  // namespace shadecore::scene

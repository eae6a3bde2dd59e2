// SPDX-License-Identifier: Apache-2.0
// shadecore — scene file parsing (docs/scenes.md). Strict: every error is one line "FILE: PATH: what".
#include "shadecore/render/scene.hpp"
#include "shadecore/light.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
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

const char* to_string(std::optional<ColourMaterial> m) {
  if (!m) return "none";
  switch (*m) {
    case ColourMaterial::Emission: return "emission";
    case ColourMaterial::Ambient: return "ambient";
    case ColourMaterial::Diffuse: return "diffuse";
    case ColourMaterial::Specular: return "specular";
    case ColourMaterial::AmbientAndDiffuse: return "ambient_and_diffuse";
  }
  return "?";
}

std::optional<ColourMaterial> parse_colour_material(const std::string& s) {
  if (s == "none") return std::nullopt;
  for (const auto m : {ColourMaterial::Emission, ColourMaterial::Ambient, ColourMaterial::Diffuse,
                       ColourMaterial::Specular, ColourMaterial::AmbientAndDiffuse})
    if (s == to_string(m)) return m;
  throw std::invalid_argument("unknown color_material mode '" + s +
                              "' (known: none, emission, ambient, diffuse, specular, ambient_and_diffuse)");
}

const char* to_string(FlatRule r) {
  switch (r) {
    case FlatRule::Centroid: return "centroid";
    case FlatRule::ProvokingVertex: return "provoking_vertex";
  }
  return "?";
}

FlatRule parse_flat_rule(const std::string& s) {
  if (s == "centroid") return FlatRule::Centroid;
  if (s == "provoking_vertex") return FlatRule::ProvokingVertex;
  throw std::invalid_argument("unknown flat rule '" + s + "' (known: centroid, provoking_vertex)");
}


std::string printable(std::string_view s, std::size_t max_chars) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  std::size_t chars = 0;
  std::size_t i = 0;
  while (i < s.size()) {
    if (max_chars != 0 && chars == max_chars) {
      out += "\u2026";
      break;
    }
    const auto c = static_cast<unsigned char>(s[i]);
    auto esc = [&](unsigned char b) {
      out += "\\x";
      out += hex[b >> 4];
      out += hex[b & 15];
    };
    if (c < 0x80) {
      if (c == '\n') out += "\\n";
      else if (c == '\t') out += "\\t";
      else if (c == '\r') out += "\\r";
      else if (c < 0x20 || c == 0x7f) esc(c);
      else out += static_cast<char>(c);
      ++i, ++chars;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, continuation bytes 10xxxxxx, no overlong forms, no
    // surrogates, at most U+10FFFF. Anything else: the byte as \xNN.
    int n = 0;
    std::uint32_t cp = 0;
    if (c >= 0xc2 && c <= 0xdf) n = 2, cp = c & 0x1f;
    else if (c >= 0xe0 && c <= 0xef) n = 3, cp = c & 0x0f;
    else if (c >= 0xf0 && c <= 0xf4) n = 4, cp = c & 0x07;
    bool ok = n > 0 && i + n <= s.size();
    for (int k = 1; ok && k < n; ++k) {
      const auto d = static_cast<unsigned char>(s[i + k]);
      if ((d & 0xc0) != 0x80) ok = false;
      else cp = (cp << 6) | (d & 0x3f);
    }
    if (ok && ((n == 3 && (cp < 0x800 || (cp >= 0xd800 && cp <= 0xdfff))) || (n == 4 && (cp < 0x10000 || cp > 0x10ffff))))
      ok = false;
    if (!ok) {
      esc(c);
      ++i, ++chars;
      continue;
    }
    if (cp >= 0x80 && cp <= 0x9f) {  // C1 controls (0x9b is CSI on some terminals)
      out += "\\u00";
      out += hex[cp >> 4];
      out += hex[cp & 15];
    } else {
      out.append(s.substr(i, n));
    }
    i += n, ++chars;
  }
  return out;
}

namespace {
std::string errno_text(int e) {
  switch (e) {
    case ENOENT: return "no such file";
    case ELOOP: return "too many levels of symbolic links";
    case ENOTDIR: return "a component of the path is not a directory";
    case EACCES: return "permission denied";
    case ENAMETOOLONG: return "file name too long";
    default: {
      std::string t = std::strerror(e);
      if (!t.empty()) t[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(t[0])));
      return t;
    }
  }
}
std::string kind_text(mode_t m) {
  if (S_ISDIR(m)) return "is a directory";
  if (S_ISCHR(m)) return "is a character device, not a regular file";
  if (S_ISBLK(m)) return "is a block device, not a regular file";
  if (S_ISFIFO(m)) return "is a FIFO, not a regular file";
  if (S_ISSOCK(m)) return "is a socket, not a regular file";
  return "is not a regular file";
}
std::string mib(std::uint64_t bytes) {
  std::ostringstream ss;
  ss << static_cast<double>(bytes) / (1 << 20) << " MiB";
  return ss.str();
}
}  // namespace

bool read_regular_file(const std::string& path, std::uint64_t max_bytes, std::string& text, std::string& why) {
  text.clear();
  if (path.find('\0') != std::string::npos) {
    why = "the file name contains a NUL character";
    return false;
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {  // follows symlinks; never opens anything
    why = errno_text(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    why = kind_text(st.st_mode);
    return false;
  }
  auto too_big = [&](std::uint64_t n, bool at_least) {
    why = "is " + std::string(at_least ? "more than " : "") + std::to_string(n) + " bytes; the limit is " + mib(max_bytes);
    return false;
  };
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) return too_big(static_cast<std::uint64_t>(st.st_size), false);
  // O_NONBLOCK: if the path was swapped for a FIFO after stat, open does not wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    why = errno_text(errno);
    return false;
  }
  struct stat fst {};
  if (::fstat(fd, &fst) != 0 || !S_ISREG(fst.st_mode)) {
    why = ::fstat(fd, &fst) == 0 ? kind_text(fst.st_mode) : errno_text(errno);
    ::close(fd);
    return false;
  }
  text.reserve(static_cast<std::size_t>(fst.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      why = "cannot read: " + errno_text(errno);
      ::close(fd);
      text.clear();
      return false;
    }
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) {  // it grew after stat
      ::close(fd);
      text.clear();
      return too_big(max_bytes, true);
    }
  }
  ::close(fd);
  return true;
}

namespace {

constexpr int kMaxImage = 4096;

class Parser {
 public:
  explicit Parser(std::string file) : file_(std::move(file)) {}

  // Paths are built from escaped keys (join); user text in `what` is quoted with q(). printable() over the whole
  // line once more (it leaves escaped text as it is) keeps the message one line whatever slipped through.
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw SceneError(printable(file_ + ": " + (path.empty() ? "" : path + ": ") + what, 0));
  }
  static std::string q(const std::string& s) { return printable(s, 60); }
  // An exception text that names user text `s`: with `s` quoted.
  static std::string quoted(std::string msg, const std::string& s) {
    if (!s.empty()) {
      const auto i = msg.find(s);
      if (i != std::string::npos) msg.replace(i, s.size(), q(s));
    }
    return msg;
  }

  // A name (a JSON string) through `parse`, which throws std::invalid_argument for an unknown one: that error, with
  // the user's text quoted, at `path`.
  template <class Parse>
  auto named(const json& v, const std::string& path, Parse parse) const -> decltype(parse(std::string())) {
    const std::string s = string(v, path);
    try {
      return parse(s);
    } catch (const std::invalid_argument& e) {
      fail(path, quoted(e.what(), s));
    }
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
    return path.empty() ? q(key) : path + "." + q(key);
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
  // An integer: a JSON integer or an integral number (16, 16.0, 1.6e1; not 16.5).
  int integer(const json& v, const std::string& path, long long lo, long long hi) const {
    const std::string range = " out of range " + std::to_string(lo) + ".." + std::to_string(hi);
    if (v.is_number_unsigned()) {
      const auto u = v.get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(hi) || static_cast<long long>(u) < lo) fail(path, std::to_string(u) + range);
      return static_cast<int>(u);
    }
    if (v.is_number_integer()) {
      const long long x = v.get<long long>();
      if (x < lo || x > hi) fail(path, std::to_string(x) + range);
      return static_cast<int>(x);
    }
    if (!v.is_number()) fail(path, "must be an integer");
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::floor(d) != d) fail(path, "must be an integer (" + fmt_num(d) + " is not)");
    if (d < static_cast<double>(lo) || d > static_cast<double>(hi)) fail(path, fmt_num(d) + range);
    return static_cast<int>(d);
  }
  bool boolean(const json& v, const std::string& path) const {
    if (!v.is_boolean()) fail(path, "must be true or false");
    return v.get<bool>();
  }
  std::string string(const json& v, const std::string& path) const {
    if (!v.is_string()) fail(path, "must be a string");
    std::string s = v.get<std::string>();
    if (s.find('\0') != std::string::npos) fail(path, "contains a NUL character (\\u0000): '" + q(s) + "'");
    return s;
  }
  // A coordinate / direction component / translation / angle: finite and |x| <= kMaxCoord.
  double coord(const json& v, const std::string& path) const {
    return number_in(v, path, -kMaxCoord, true, kMaxCoord, true, "[-1e6, 1e6]");
  }
  Vec3 coords3(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != 3) fail(path, "must be a list of 3 numbers");
    Vec3 a{};
    for (size_t i = 0; i < 3; ++i) a[i] = coord(v[i], index(path, i));
    return a;
  }
  // A length (radius, size): [kMinLength, kMaxLength].
  double length(const json& v, const std::string& path) const {
    return number_in(v, path, kMinLength, true, kMaxLength, true, "[1e-6, 1e4]");
  }
  template <size_t N>
  std::array<double, N> vec(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != N) fail(path, "must be a list of " + std::to_string(N) + " numbers");
    std::array<double, N> a{};
    for (size_t i = 0; i < N; ++i) a[i] = number(v[i], index(path, i));
    return a;
  }
  // A colour: [0, 2) (the core's colour format) or, `unit`, [0, 1] (GL's current colour: glColor3f clamps).
  Vec3 colour(const json& v, const std::string& path, bool unit = false) const {
    if (!v.is_array() || v.size() != 3) fail(path, "must be a colour [r, g, b]");
    Vec3 c{};
    for (size_t i = 0; i < 3; ++i)
      c[i] = unit ? number_in(v[i], index(path, i), 0.0, true, 1.0, true, "[0, 1]")
                  : number_in(v[i], index(path, i), 0.0, true, 2.0, false, "[0, 2) (the core's colour format)");
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
      if (l.is_object) p += (p.empty() ? "" : ".") + printable(l.key, 60);
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
  if (j.contains("eye")) c.eye = P.coords3(j["eye"], path + ".eye");
  if (j.contains("center")) c.center = P.coords3(j["center"], path + ".center");
  if (j.contains("up")) c.up = P.coords3(j["up"], path + ".up");
  if (j.contains("fovy"))
    c.fovy = P.number_in(j["fovy"], path + ".fovy", 0.001, true, 179.999, true, "[0.001, 179.999] degrees");
  if (j.contains("near")) c.near = P.number_in(j["near"], path + ".near", 1e-3, true, 1e6, true, "[0.001, 1e6]");
  if (j.contains("far")) c.far = P.number_in(j["far"], path + ".far", 1e-3, true, 1e9, true, "[0.001, 1e9]");
  if (!(c.far > c.near)) P.fail(path + ".far", "must be greater than near");
  if (c.far / c.near > 1e6) P.fail(path + ".far", "far/near must be at most 1e6 (depth precision)");
  const Vec3 f{c.center[0] - c.eye[0], c.center[1] - c.eye[1], c.center[2] - c.eye[2]};
  const double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  if (!(fl > 1e-9)) P.fail(path, "degenerate camera: eye and center coincide");
  const double ul = std::sqrt(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]);
  if (!(ul > 1e-9)) P.fail(path + ".up", "degenerate camera: up is the zero vector (or too short to normalise)");
  const Vec3 s{f[1] * c.up[2] - f[2] * c.up[1], f[2] * c.up[0] - f[0] * c.up[2], f[0] * c.up[1] - f[1] * c.up[0]};
  if (std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) <= 1e-9 * fl * ul)
    P.fail(path + ".up", "degenerate camera: up is parallel to the viewing direction");
  return c;
}

Light parse_light(const Parser& P, const json& j, const std::string& path, int F) {
  P.keys(j, path, {"position", "ambient", "diffuse", "specular", "constant_attenuation", "linear_attenuation",
                   "quadratic_attenuation", "spot_direction", "spot_cutoff", "spot_exponent"});
  Light l;
  if (!j.contains("position")) P.fail(path, "missing 'position' [x, y, z, w]");
  {
    const json& pj = j["position"];
    if (!pj.is_array() || pj.size() != 4) P.fail(path + ".position", "must be a list of 4 numbers");
    for (size_t i = 0; i < 4; ++i) l.position[i] = P.coord(pj[i], Parser::index(path + ".position", i));
  }
  if (l.position[3] == 0.0 && l.position[0] == 0.0 && l.position[1] == 0.0 && l.position[2] == 0.0)
    P.fail(path + ".position", "a directional light (w = 0) needs a non-zero direction");
  if (l.position[3] == 0.0) {
    const auto& d = l.position;
    const double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dl >= 1e-150) || !std::isfinite(d[0] / dl) || !std::isfinite(d[1] / dl) || !std::isfinite(d[2] / dl))
      P.fail(path + ".position", "the direction of a directional light (w = 0) is too short to normalise");
  } else if (std::fabs(l.position[3]) < 1e-150) {
    P.fail(path + ".position", "w = " + Parser::fmt_num(l.position[3]) + " is too close to 0 (x/w, y/w, z/w overflow)");
  }
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
    // The core's attenuation registers hold F fraction bits, rounded to nearest (attc_code): all three below
    // 2^-(F+1) are all 0 in the core, a 1/0 attenuation.
    const double q = std::ldexp(1.0, -(F + 1));
    if (l.kc < q && l.kl < q && l.kq < q)
      P.fail(path, "constant, linear and quadratic attenuation all round to 0 in the core's " + std::to_string(F) +
                       "-bit fraction format (smallest representable 2^-" + std::to_string(F) + " \u2248 " +
                       Parser::fmt_num(std::ldexp(1.0, -F)) + "; 1/0 attenuation)");
  } else if (j.contains("linear_attenuation") || j.contains("quadratic_attenuation") ||
             (j.contains("constant_attenuation") && l.kc != 1.0)) {
    P.fail(path, "attenuation applies to point lights only (w != 0); GL ignores it for directional lights");
  }
  // GL_SPOT_DIRECTION / GL_SPOT_CUTOFF / GL_SPOT_EXPONENT (docs/scenes.md §3)
  if (j.contains("spot_direction")) {
    l.spot_direction = P.coords3(j["spot_direction"], path + ".spot_direction");
    const auto& d = l.spot_direction;
    const double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dl >= 1e-150) || !std::isfinite(d[0] / dl) || !std::isfinite(d[1] / dl) || !std::isfinite(d[2] / dl))
      P.fail(path + ".spot_direction", "must be a non-zero direction (too short to normalise)");
  }
  if (j.contains("spot_cutoff")) {
    const double c = P.number(j["spot_cutoff"], path + ".spot_cutoff");
    if (!(c == 180.0 || (c >= 0.0 && c <= 90.0)))
      P.fail(path + ".spot_cutoff", Parser::fmt_num(c) + " out of range 0..90 or 180 degrees (GL_SPOT_CUTOFF)");
    l.spot_cutoff = c;
  }
  if (j.contains("spot_exponent"))
    l.spot_exponent = P.integer(j["spot_exponent"], path + ".spot_exponent", 0, kSpotExpMax);
  if (l.position[3] == 0.0 && l.spot_cutoff != 180.0)
    P.fail(path, "a spot light (spot_cutoff != 180) must be positional (w != 0); GL ignores the cone for directional lights");
  return l;
}

// A specular unit of the lighting core: every variant but the table units (the core has no table-load port;
// FeatureSet rejects them too). The message names the units the core takes.
VariantId core_unit(const Parser& P, const json& v, const std::string& path) {
  const std::string s = P.string(v, path);
  std::string known;
  for (const auto& nv : kVariants)
    if (!is_table_variant(nv.id)) known += (known.empty() ? "" : ", ") + std::string(nv.name);
  VariantId id{};
  try {
    id = parse_variant(s);
  } catch (const std::invalid_argument&) {
    P.fail(path, "unknown variant '" + Parser::q(s) + "' (known: " + known + ")");
  }
  if (is_table_variant(id))
    P.fail(path, "specular unit '" + s + "' is not a unit of the lighting core (it has no table-load port; the core takes " +
                     known + ")");
  return id;
}

// A normalised material's shininess below the units' range: "16..1024<where> (got n; below 16 the power is not
// normalised)", the one text for the front's and the back's.
std::string unnormalised_range(int n, const std::string& where = "") {
  return std::to_string(kNMin) + ".." + std::to_string(kNMax) + where + " (got " + std::to_string(n) + "; below " +
         std::to_string(kNMin) + " the power is not normalised)";
}

Material parse_material(const Parser& P, const json& j, const std::string& path, const std::string& name) {
  P.keys(j, path, {"emission", "ambient", "diffuse", "specular", "shininess", "specular_unit", "cutoff",
                   "normalization", "back"});
  Material m;
  m.name = name;
  if (j.contains("emission")) m.emission = P.colour(j["emission"], path + ".emission");
  if (j.contains("ambient")) m.ambient = P.colour(j["ambient"], path + ".ambient");
  if (j.contains("diffuse")) m.diffuse = P.colour(j["diffuse"], path + ".diffuse");
  if (j.contains("specular")) m.specular = P.colour(j["specular"], path + ".specular");
  if (j.contains("shininess"))
    m.shininess = P.integer(j["shininess"], path + ".shininess", 0, kNMax);
  if (j.contains("specular_unit")) m.unit = core_unit(P, j["specular_unit"], path + ".specular_unit");
  if (j.contains("cutoff")) {
    if (m.unit != VariantId::cs16) P.fail(path + ".cutoff", "applies to the cs16 unit only");
    m.cutoff = P.named(j["cutoff"], path + ".cutoff", parse_cutoff_name);
  }
  if (j.contains("normalization")) {
    const std::string np = path + ".normalization";
    const json& n = j["normalization"];
    P.keys(n, np, {"model", "coefficient"});
    Normalization nz;
    if (!n.contains("model")) P.fail(np, "missing 'model'");
    nz.model = P.named(n["model"], np + ".model", parse_model);
    if (n.contains("coefficient")) {
      nz.kind = P.named(n["coefficient"], np + ".coefficient", parse_coef_kind);
    }
    m.normalization = nz;
    // the fitted coefficients cover the units' range; the chain below it (GL's 0..15) is not normalised
    if (m.shininess < kNMin) P.fail(np, "needs shininess " + unnormalised_range(m.shininess));
  }
  if (j.contains("back")) {  // glMaterial(GL_BACK, ...): the back face's colours (light_model.two_side)
    const std::string bp = path + ".back";
    const json& b = j["back"];
    if (!b.is_object()) P.fail(bp, "must be a JSON object (the back material's colours)");
    // the back face uses the front's unit, cut-off and normalisation: the renderer writes the back's shininess
    // into the core's one unit material between the facing batches (a back unit would need a core with two units)
    for (const char* k : {"specular_unit", "cutoff", "normalization"})
      if (b.contains(k))
        P.fail(Parser::join(bp, k), "applies to the front material only: the back face shares its specular unit, "
                                    "cut-off and normalisation (only the back shininess may differ)");
    P.keys(b, bp, {"emission", "ambient", "diffuse", "specular", "shininess"});
    BackMaterial bm = m.back_or_front();  // a key not given: the front's
    if (b.contains("emission")) bm.emission = P.colour(b["emission"], bp + ".emission");
    if (b.contains("ambient")) bm.ambient = P.colour(b["ambient"], bp + ".ambient");
    if (b.contains("diffuse")) bm.diffuse = P.colour(b["diffuse"], bp + ".diffuse");
    if (b.contains("specular")) bm.specular = P.colour(b["specular"], bp + ".specular");
    if (b.contains("shininess")) {
      bm.shininess = P.integer(b["shininess"], bp + ".shininess", 0, kNMax);
      // the front's normalisation applies to the back's unit material too: the same range
      if (m.normalization && bm.shininess < kNMin)
        P.fail(bp + ".shininess", "needs " + unnormalised_range(bm.shininess, " with the front's normalization"));
    }
    m.back = bm;
  }
  return m;
}

Transform parse_transform(const Parser& P, const json& j, const std::string& path) {
  P.keys(j, path, {"translate", "rotate", "scale"});
  Transform t;
  if (j.contains("translate")) t.translate = P.coords3(j["translate"], path + ".translate");
  if (j.contains("rotate")) {
    const json& r = j["rotate"];
    const std::string rp = path + ".rotate";
    auto one = [&](const json& e, const std::string& p) {
      if (!e.is_array() || e.size() != 4) P.fail(p, "must be [angle_degrees, x, y, z]");
      std::array<double, 4> a{};
      for (size_t i = 0; i < 4; ++i) a[i] = P.coord(e[i], Parser::index(p, i));
      Rotation rot{a[0], {a[1], a[2], a[3]}};
      if (a[1] == 0 && a[2] == 0 && a[3] == 0) P.fail(p, "rotation axis is the zero vector");
      // render.cpp normalises the axis as v / |v|: its length must neither underflow nor give a non-finite unit.
      const double l = std::sqrt(a[1] * a[1] + a[2] * a[2] + a[3] * a[3]);
      if (!(l >= 1e-150) || !std::isfinite(a[1] / l) || !std::isfinite(a[2] / l) || !std::isfinite(a[3] / l))
        P.fail(p, "rotation axis too short to normalise (length < 1e-150)");
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
    auto one = [&](const json& v, const std::string& p) {
      const double x = P.number(v, p);
      if (x == 0.0) P.fail(p, "a zero scale makes the object degenerate");
      if (!(std::fabs(x) >= kMinLength) || !(std::fabs(x) <= kMaxCoord))
        P.fail(p, Parser::fmt_num(x) + " out of range: |scale| must be in [1e-6, 1e6]");
      return x;
    };
    if (s.is_number()) {
      const double x = one(s, path + ".scale");
      t.scale = {x, x, x};
    } else {
      if (!s.is_array() || s.size() != 3) P.fail(path + ".scale", "must be a number or a list of 3 numbers");
      for (size_t i = 0; i < 3; ++i) t.scale[i] = one(s[i], Parser::index(path + ".scale", i));
    }
  }
  return t;
}

Object parse_object(const Parser& P, const json& j, const std::string& path, const Scene& sc) {
  if (!j.is_object()) P.fail(path, "must be a JSON object");
  if (!j.contains("type")) P.fail(path, "missing 'type' (sphere, plane or quad, torus, mesh)");
  const std::string type = P.string(j["type"], path + ".type");
  Object o;
  o.where = path;
  o.scene_file = printable(P.file(), 0);
  if (type == "sphere") {
    o.type = ObjectType::Sphere;
    P.keys(j, path, {"type", "name", "material", "shading", "color_material", "color", "transform", "radius", "slices", "stacks"});
    if (j.contains("radius")) o.radius = P.length(j["radius"], path + ".radius");
    if (j.contains("slices")) o.slices = P.integer(j["slices"], path + ".slices", 3, 1024);
    if (j.contains("stacks")) o.stacks = P.integer(j["stacks"], path + ".stacks", 2, 1024);
  } else if (type == "plane" || type == "quad") {  // "quad": the same object (one quad unless subdivided)
    o.type = ObjectType::Plane;
    P.keys(j, path, {"type", "name", "material", "shading", "color_material", "color", "transform", "size", "subdivisions"});
    if (j.contains("size")) {
      const json& sj = j["size"];
      if (!sj.is_array() || sj.size() != 2) P.fail(path + ".size", "must be a list of 2 numbers [width, height]");
      o.width = P.length(sj[0], path + ".size[0]");
      o.height = P.length(sj[1], path + ".size[1]");
    }
    if (j.contains("subdivisions")) o.subdivisions = P.integer(j["subdivisions"], path + ".subdivisions", 1, 1024);
  } else if (type == "torus") {
    o.type = ObjectType::Torus;
    P.keys(j, path, {"type", "name", "material", "shading", "color_material", "color", "transform", "inner_radius",
                     "outer_radius", "sides", "rings"});
    if (j.contains("inner_radius"))
      o.inner_radius = P.length(j["inner_radius"], path + ".inner_radius");
    if (j.contains("outer_radius"))
      o.outer_radius = P.length(j["outer_radius"], path + ".outer_radius");
    if (!(o.inner_radius < o.outer_radius)) P.fail(path, "inner_radius must be smaller than outer_radius");
    if (j.contains("sides")) o.sides = P.integer(j["sides"], path + ".sides", 3, 1024);
    if (j.contains("rings")) o.rings = P.integer(j["rings"], path + ".rings", 3, 1024);
  } else if (type == "mesh") {
    o.type = ObjectType::Mesh;
    P.keys(j, path, {"type", "name", "material", "shading", "color_material", "color", "transform", "file"});
    if (!j.contains("file")) P.fail(path, "missing 'file' (an OBJ file, relative to the scene file)");
    o.file = P.string(j["file"], path + ".file");
    if (o.file.empty()) P.fail(path + ".file", "empty file name");
    const std::filesystem::path fp(o.file);
    o.file_path = fp.is_absolute() || sc.dir.empty() ? o.file : (std::filesystem::path(sc.dir) / fp).string();
  } else {
    P.fail(path + ".type", "unknown object type '" + Parser::q(type) + "' (known: sphere, plane or quad, torus, mesh)");
  }
  o.name = j.contains("name") ? P.string(j["name"], path + ".name") : path;
  if (!j.contains("material")) P.fail(path, "missing 'material'");
  const std::string mat = P.string(j["material"], path + ".material");
  bool found = false;
  for (size_t i = 0; i < sc.materials.size(); ++i)
    if (sc.materials[i].name == mat) o.material = static_cast<int>(i), found = true;
  if (!found) P.fail(path + ".material", "unknown material '" + Parser::q(mat) + "'");
  if (j.contains("shading")) o.shading = P.named(j["shading"], path + ".shading", parse_shading);
  if (j.contains("color_material"))
    o.colour_material = P.named(j["color_material"], path + ".color_material", parse_colour_material);
  if (j.contains("color")) o.colour = P.colour(j["color"], path + ".color", true);
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
          P.fail(Parser::index(path + ".modes", i), Parser::quoted(e.what(), s) + " or scene");
        }
      }
    }
  } else {
    cs.modes.push_back(std::nullopt);
  }
  if (!j.contains("units")) P.fail(path, "missing 'units' (specular units compared with exact cos^n)");
  const json& u = j["units"];
  if (!u.is_array() || u.empty() || u.size() > 4) P.fail(path + ".units", "must be a list of 1..4 specular units");
  for (size_t i = 0; i < u.size(); ++i) cs.units.push_back(core_unit(P, u[i], Parser::index(path + ".units", i)));
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


// Line and column (1-based) of byte `end` of `text`.
std::string line_col(const std::string& text, size_t end) {
  size_t line = 1, col = 1;
  end = std::min(end, text.size());
  for (size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') ++line, col = 1;
    else ++col;
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

// What nlohmann cannot be trusted with, found before it runs, with the position: a NUL byte (its lexer takes
// one for the end of the input, so "valid JSON\0garbage" would pass), a \u0000 escape in a string (a NUL in a
// key, a name or a file name), nesting deeper than kMaxNesting (a deep value's copy and destruction recurse),
// and a number that overflows a double (nlohmann's own message has no position).
void prescan_json(const std::string& text, const std::string& name) {
  auto fail_at = [&](size_t at, const std::string& what) {
    throw SceneError(printable(name, 0) + ":" + line_col(text, at) + ": " + what);
  };
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\0') fail_at(i, "NUL byte in the scene file (not allowed anywhere)");
    if (in_string) {
      if (c == '"') in_string = false;
      else if (c == '\\' && i + 1 < text.size()) {
        if (text[i + 1] == 'u' && text.compare(i + 2, 4, "0000") == 0)
          fail_at(i, "\\u0000 (NUL) in a string: not allowed in keys, names or file names");
        ++i;
      }
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > kMaxNesting) fail_at(i, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
    } else if (c == ']' || c == '}') {
      if (depth > 0) --depth;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      size_t j = i;
      while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '-' || text[j] == '+' ||
                                 text[j] == '.' || text[j] == 'e' || text[j] == 'E'))
        ++j;
      const std::string tok = text.substr(i, j - i);
      char* endp = nullptr;
      errno = 0;
      const double x = std::strtod(tok.c_str(), &endp);
      if (endp == tok.c_str() + tok.size() && !std::isfinite(x))
        fail_at(i, "number out of range (overflows a double): " + printable(tok, 60));
      i = j - 1;
    }
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const std::string& dir) {
  Parser P(name);
  prescan_json(text, name);
  PathTracker pt;
  json root;
  try {
    json::parser_callback_t cb = [&pt, &name](int, json::parse_event_t ev, json& parsed) {
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
          // ordered_json looks keys up linearly: a million keys in one object would take hours to parse.
          if (top.keys.size() > static_cast<size_t>(kMaxMembers)) {
            const std::string at = pt.path(), kp = printable(k, 60);  // the object's path: without ".key"
            const std::string obj = at.size() > kp.size() ? at.substr(0, at.size() - kp.size() - 1) : std::string();
            throw SceneError(printable(name, 0) + ": " + (obj.empty() ? "" : obj + ": ") + "more than " +
                             std::to_string(kMaxMembers) + " keys in one object");
          }
          break;
        }
        case E::value:
          pt.element();
          break;
      }
      return true;
    };
    root = json::parse(text.begin(), text.end(), cb);
  } catch (const json::parse_error& e) {
    // Line and column of the byte where parsing stopped (e.byte is 1-based).
    const size_t end = std::min(text.size(), e.byte > 0 ? static_cast<size_t>(e.byte - 1) : size_t{0});
    std::string msg = e.what();
    const auto p = msg.find(": syntax error");
    std::string detail = p != std::string::npos ? msg.substr(p + 2) : msg;
    // nlohmann repeats the position in its text; keep the part after it.
    // "syntax error while parsing value - invalid literal; last read: '…'": keep what is after " - ".
    const auto q = detail.find(" - ");
    if (q != std::string::npos && detail.rfind("syntax error", 0) == 0) detail = detail.substr(q + 3);
    // nlohmann quotes the token it stopped at ("last read: '…'"): that is user text, keep 60 characters of it.
    const auto lr = detail.find("last read: '");
    if (lr != std::string::npos) {
      const size_t b = lr + 12;
      size_t e2 = detail.find("'; expected ", b);  // nlohmann: "…; last read: 'TOKEN'[; expected …]"
      if (e2 == std::string::npos) e2 = !detail.empty() && detail.back() == '\'' ? detail.size() - 1 : detail.size();
      if (e2 < b) e2 = detail.size();
      detail = detail.substr(0, b) + printable(detail.substr(b, e2 - b), 60) + detail.substr(e2);
    }
    throw SceneError(printable(name, 0) + ":" + line_col(text, end) + ": malformed JSON: " + printable(detail, 0));
  } catch (const json::exception& e) {  // out_of_range (a number nlohmann cannot store) and anything else of its own
    throw SceneError(printable(name, 0) + ": malformed JSON: " + printable(e.what(), 200));
  }
  if (!pt.dup_path.empty()) P.fail(pt.dup_path, "duplicate key");

  Scene sc;
  sc.file = printable(name, 0);  // for messages only
  sc.dir = dir;
  P.keys(root, "", {"image", "camera", "light_model", "lights", "materials", "objects", "contact_sheet", "config",
                    "flat_rule"});
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
  if (root.contains("camera")) sc.camera = parse_camera(P, root["camera"], "camera");  // else the default camera
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
  if (root.contains("flat_rule")) {
    sc.flat_rule = P.named(root["flat_rule"], "flat_rule", parse_flat_rule);
  }
  if (root.contains("light_model")) {
    const json& lm = root["light_model"];
    P.keys(lm, "light_model", {"ambient", "local_viewer", "reflection", "color_control", "two_side"});
    if (lm.contains("ambient")) sc.global_ambient = P.colour(lm["ambient"], "light_model.ambient");
    if (lm.contains("local_viewer")) sc.local_viewer = P.boolean(lm["local_viewer"], "light_model.local_viewer");
    if (lm.contains("two_side")) sc.two_side = P.boolean(lm["two_side"], "light_model.two_side");
    if (lm.contains("reflection")) {
      const std::string r = P.string(lm["reflection"], "light_model.reflection");
      if (r != "blinn" && r != "phong") P.fail("light_model.reflection", "must be blinn or phong");
      sc.blinn = r == "blinn";
    }
    if (lm.contains("color_control")) {
      const std::string c = P.string(lm["color_control"], "light_model.color_control");
      if (c != "single" && c != "separate_specular")
        P.fail("light_model.color_control", "must be single or separate_specular");
      sc.separate_specular = c == "separate_specular";
    }
  }
  int light_frac = 16;
  try {
    light_frac = config_named(sc.config).format.frac;
  } catch (const std::exception&) {
  }
  if (root.contains("lights")) {
    const json& ls = root["lights"];
    if (!ls.is_array()) P.fail("lights", "must be a list of lights");
    if (ls.size() > static_cast<size_t>(kMaxLights))
      P.fail("lights", std::to_string(ls.size()) + " lights; the core supports at most " + std::to_string(kMaxLights));
    for (size_t i = 0; i < ls.size(); ++i) sc.lights.push_back(parse_light(P, ls[i], Parser::index("lights", i), light_frac));
  }
  if (!root.contains("materials")) P.fail("", "missing 'materials' {name: {...}}");
  {
    const json& ms = root["materials"];
    if (!ms.is_object() || ms.empty()) P.fail("materials", "must be a non-empty object {name: material}");
    for (auto it = ms.begin(); it != ms.end(); ++it) {
      if (it.key() == "_comment") continue;
      if (it.key().find('\0') != std::string::npos) P.fail(Parser::join("materials", it.key()), "NUL in a material name");
      sc.materials.push_back(parse_material(P, it.value(), Parser::join("materials", it.key()), it.key()));
    }
    if (sc.materials.empty()) P.fail("materials", "no material defined");
  }
  if (!root.contains("objects")) P.fail("", "missing 'objects'");
  {
    const json& os = root["objects"];
    if (!os.is_array() || os.empty()) P.fail("objects", "must be a non-empty list of objects");
    if (os.size() > 256) P.fail("objects", "at most 256 objects");
    // No bound on the scene's total geometry: render streams it object by object (docs/scenes.md §2).
    for (size_t i = 0; i < os.size(); ++i) sc.objects.push_back(parse_object(P, os[i], Parser::index("objects", i), sc));
  }
  if (root.contains("contact_sheet")) sc.contact_sheet = parse_contact_sheet(P, root["contact_sheet"], "contact_sheet", sc);
  return sc;
}

Scene load_scene(const std::string& path) {
  // A regular file of at most kMaxSceneBytes: /dev/zero, a FIFO, a directory, a socket are refused by what
  // they are, before anything is read (and a FIFO is never opened).
  std::string text, why;
  if (!read_regular_file(path, kMaxSceneBytes, text, why)) {
    const std::string p = printable(path, 0);
    if (why == "is a directory") throw SceneError(p + ": is a directory, not a scene file");
    if (why.rfind("is ", 0) == 0) throw SceneError(p + ": " + why);
    throw SceneError(p + ": cannot read the scene file (" + why + ")");
  }
  const std::filesystem::path fp(path);
  return parse_scene(text, path, fp.has_parent_path() ? fp.parent_path().string() : std::string("."));
}

}  // namespace shadecore::scene

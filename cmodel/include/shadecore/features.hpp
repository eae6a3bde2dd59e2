// SPDX-License-Identifier: Apache-2.0
// shadecore — the feature set of the lighting core: which units exist (docs/lighting.md §2).
//
// One value, three consumers (Mesa keys its fixed-function programs on `struct state_key` the same way):
//   * the RTL: verilog_params() gives the elaboration-time parameters of rtl/sc_light.v;
//   * the C model: LightCore (shadecore/light.hpp) takes the same struct and computes what that
//     RTL computes;
//   * the build cache: key() names the Verilated core built for exactly this set.
// Named sets live in config/configs.json "feature_sets"; any other set is the same JSON in a file.
// Parsing is strict: unknown keys, wrong types and out-of-range values are one-line errors.
#pragma once

#include <array>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadecore/configs.hpp"
#include "shadecore/configs_json.hpp"
#include "shadecore/units/cs16.hpp"
#include "shadecore/light_regs.hpp"
#include "shadecore/unit.hpp"

namespace shadecore {

enum class LightKind : int { Directional = 0, Point = 1, PointAtt = 2 };

inline constexpr int kLightFracMax = 16;  // the core's widest format (every product stays within 64 bits)

struct FeatureSet {
  std::string name = "custom";
  std::string config = "default";       // width: a named config of configs.json (frac <= 16)
  std::vector<LightKind> lights{LightKind::Directional};  // 1..kMaxLights
  bool ambient = true;                  // emission + global ambient + per-light ambient terms
  bool diffuse = true;                  // max(N·L, 0)·d·Id
  bool specular = true;                 // a specular unit per light
  VariantId variant = VariantId::cs16;  // which unit (per core), when specular
  Cutoff cutoff = Cutoff::ThetaCr;      // cs16 only
  bool norm = false;                    // rtl/sc_norm.v after the unit (coefficient register mat_coef)
  bool blinn = true;                    // x = N·H (Blinn-Phong) or R·V (Phong)
  bool local_viewer = false;            // V = normalise(−P) or (0, 0, 1)
  bool normalize = true;                // GL_NORMALIZE: renormalise N per fragment
  int channels = 3;                     // 1 (mono, channel 0 only) or 3 (RGB)

  [[nodiscard]] Format format() const { return config_named(config).format; }
  [[nodiscard]] int num_lights() const { return static_cast<int>(lights.size()); }
  [[nodiscard]] bool any_point() const {
    for (auto k : lights)
      if (k != LightKind::Directional) return true;
    return false;
  }
  [[nodiscard]] bool needs_position() const { return any_point() || (specular && local_viewer); }

  // Canonical JSON (every key, fixed order, without the name): equal sets give equal strings.
  [[nodiscard]] nlohmann::ordered_json canonical() const;
  // Build-cache key: 16 hex digits of FNV-1a over canonical().dump().
  [[nodiscard]] std::string key() const;
  // "-GNAME=value" parameters of rtl/sc_light.v.
  [[nodiscard]] std::vector<std::string> verilog_params(int tagw) const;
  // One line for humans: "3 lights (point_att ×2, directional), ambient, diffuse, cs16/theta_cr, blinn, ..."
  [[nodiscard]] std::string summary() const;
};

inline const char* to_string(LightKind k) {
  for (const auto& n : kLightKinds)
    if (n.id == static_cast<int>(k)) return n.name.data();
  return "?";
}

namespace detail {
inline nlohmann::json configs_json() { return nlohmann::json::parse(kConfigsJson); }

inline void fs_fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument(where + ": " + what);
}
inline bool fs_bool(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.is_boolean()) fs_fail(where, std::string("'") + key + "' must be true or false");
  return j.get<bool>();
}
inline std::string fs_string(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.is_string()) fs_fail(where, std::string("'") + key + "' must be a string");
  return j.get<std::string>();
}
}  // namespace detail

// Parse one feature set. `where` prefixes every error (a file name or "feature set 'full'").
inline FeatureSet feature_set_from_json(const nlohmann::json& j, const std::string& where) {
  using detail::fs_fail;
  if (!j.is_object()) fs_fail(where, "a feature set must be a JSON object");
  FeatureSet fs;
  bool cutoff_given = false;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const nlohmann::json& v = it.value();
    if (k == "name") fs.name = detail::fs_string(v, "name", where);
    else if (k == "_comment") continue;
    else if (k == "config") fs.config = detail::fs_string(v, "config", where);
    else if (k == "lights") {
      if (!v.is_array() || v.empty() || v.size() > static_cast<size_t>(kMaxLights))
        fs_fail(where, "'lights' must be a list of 1.." + std::to_string(kMaxLights) +
                           " light kinds (directional, point, point_att)");
      fs.lights.clear();
      for (const auto& e : v) {
        const std::string s = detail::fs_string(e, "lights[]", where);
        bool found = false;
        for (const auto& kind : kLightKinds)
          if (kind.name == s) {
            fs.lights.push_back(static_cast<LightKind>(kind.id));
            found = true;
          }
        if (!found) fs_fail(where, "unknown light kind '" + s + "' (known: directional, point, point_att)");
      }
    } else if (k == "ambient") fs.ambient = detail::fs_bool(v, "ambient", where);
    else if (k == "diffuse") fs.diffuse = detail::fs_bool(v, "diffuse", where);
    else if (k == "specular") {
      const std::string s = detail::fs_string(v, "specular", where);
      if (s == "none") fs.specular = false;
      else {
        try {
          fs.variant = parse_variant(s);
        } catch (const std::exception& e) {
          fs_fail(where, std::string(e.what()) + " or none");
        }
        if (is_table_variant(fs.variant))
          fs_fail(where, "specular unit '" + s + "' is not supported by the lighting core (it has no table-load port; "
                         "use cs16, schlick_div, schlick_nr or schlick_iter)");
        fs.specular = true;
      }
    } else if (k == "cutoff") {
      try {
        fs.cutoff = parse_cutoff_name(detail::fs_string(v, "cutoff", where));
      } catch (const std::invalid_argument& e) {
        fs_fail(where, e.what());
      }
      cutoff_given = true;
    } else if (k == "norm") fs.norm = detail::fs_bool(v, "norm", where);
    else if (k == "reflection") {
      const std::string s = detail::fs_string(v, "reflection", where);
      if (s != "blinn" && s != "phong") fs_fail(where, "'reflection' must be blinn or phong");
      fs.blinn = s == "blinn";
    } else if (k == "local_viewer") fs.local_viewer = detail::fs_bool(v, "local_viewer", where);
    else if (k == "normalize") fs.normalize = detail::fs_bool(v, "normalize", where);
    else if (k == "channels") {
      if (!v.is_number_integer() || (v.get<int>() != 1 && v.get<int>() != 3))
        fs_fail(where, "'channels' must be 1 or 3");
      fs.channels = v.get<int>();
    } else {
      fs_fail(where, "unknown key '" + k + "'");
    }
  }
  try {
    const Format f = config_named(fs.config).format;
    if (f.frac > kLightFracMax)
      fs_fail(where, "config '" + fs.config + "' has frac " + std::to_string(f.frac) +
                         "; the lighting core supports frac <= " + std::to_string(kLightFracMax));
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).rfind(where, 0) == 0) throw;
    fs_fail(where, e.what());
  }
  if (cutoff_given && (!fs.specular || fs.variant != VariantId::cs16))
    fs_fail(where, "'cutoff' applies to the cs16 unit only");
  if (fs.norm && !fs.specular) fs_fail(where, "'norm' needs a specular unit");
  if (!fs.ambient && !fs.diffuse && !fs.specular) fs_fail(where, "no term enabled (ambient, diffuse, specular)");
  return fs;
}

// Named sets of config/configs.json.
inline std::vector<FeatureSet> named_feature_sets() {
  const nlohmann::json j = detail::configs_json();
  std::vector<FeatureSet> out;
  for (const auto& e : j.at("feature_sets"))
    out.push_back(feature_set_from_json(e, "config/configs.json feature set '" + e.value("name", "?") + "'"));
  return out;
}

// A name of configs.json "feature_sets", or else a path to a JSON file with one set.
inline FeatureSet feature_set_named_or_file(const std::string& arg) {
  if (arg.empty()) throw std::invalid_argument("empty feature set name");
  std::string known;
  for (const auto& fs : named_feature_sets()) {
    if (fs.name == arg) return fs;
    known += (known.empty() ? "" : ", ") + fs.name;
  }
  std::ifstream in(arg);
  if (!in)
    throw std::invalid_argument("unknown feature set '" + arg + "' (named: " + known + "; or a JSON file)");
  std::stringstream ss;
  ss << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    std::string msg = e.what();
    const auto nl = msg.find('\n');
    if (nl != std::string::npos) msg = msg.substr(0, nl);
    throw std::invalid_argument(arg + ": malformed JSON: " + msg);
  }
  FeatureSet fs = feature_set_from_json(j, arg);
  if (!j.contains("name")) fs.name = "custom";
  return fs;
}

inline nlohmann::ordered_json FeatureSet::canonical() const {
  nlohmann::ordered_json j;
  j["config"] = config;
  nlohmann::ordered_json l = nlohmann::ordered_json::array();
  for (auto k : lights) l.push_back(to_string(k));
  j["lights"] = l;
  j["ambient"] = ambient;
  j["diffuse"] = diffuse;
  j["specular"] = specular ? std::string(variant_name(variant)) : std::string("none");
  if (specular && variant == VariantId::cs16) j["cutoff"] = to_string(cutoff);
  j["norm"] = norm;
  j["reflection"] = blinn ? "blinn" : "phong";
  j["local_viewer"] = local_viewer;
  j["normalize"] = normalize;
  j["channels"] = channels;
  return j;
}

inline std::string FeatureSet::key() const {
  const std::string s = canonical().dump();
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

inline std::vector<std::string> FeatureSet::verilog_params(int tagw) const {
  const Format f = format();
  uint32_t kinds = 0;
  for (size_t j = 0; j < lights.size(); ++j) kinds |= static_cast<uint32_t>(lights[j]) << (2 * j);
  std::vector<std::string> p = {
      "FRAC=" + std::to_string(f.frac),
      "GUARD=" + std::to_string(f.guard),
      "LIGHTS=" + std::to_string(lights.size()),
      "LIGHT_KINDS=" + std::to_string(kinds),
      "AMBIENT=" + std::to_string(ambient ? 1 : 0),
      "DIFFUSE=" + std::to_string(diffuse ? 1 : 0),
      "SPECULAR=" + std::to_string(specular ? 1 : 0),
      "VARIANT=" + std::to_string(static_cast<int>(variant)),
      "CUTOFF=" + std::to_string(static_cast<int>(cutoff)),
      "NORM=" + std::to_string(norm ? 1 : 0),
      "BLINN=" + std::to_string(blinn ? 1 : 0),
      "LOCAL_VIEWER=" + std::to_string(local_viewer ? 1 : 0),
      "NORMALIZE=" + std::to_string(normalize ? 1 : 0),
      "CHANNELS=" + std::to_string(channels),
      "TAGW=" + std::to_string(tagw),
  };
  return p;
}

inline std::string FeatureSet::summary() const {
  std::string s = std::to_string(lights.size()) + (lights.size() == 1 ? " light (" : " lights (");
  for (size_t j = 0; j < lights.size(); ++j) s += (j ? ", " : "") + std::string(to_string(lights[j]));
  s += ")";
  if (ambient) s += ", ambient+emission";
  if (diffuse) s += ", diffuse";
  if (specular) {
    s += ", specular " + std::string(variant_name(variant));
    if (variant == VariantId::cs16) s += "/" + std::string(to_string(cutoff));
    if (norm) s += "+norm";
    s += blinn ? ", blinn" : ", phong";
    s += local_viewer ? ", local viewer" : ", infinite viewer";
  } else {
    s += ", no specular";
  }
  s += normalize ? ", normalize" : ", unit normals";
  s += channels == 3 ? ", RGB" : ", mono";
  s += ", " + config + " (F=" + std::to_string(format().frac) + ")";
  return s;
}

}  // namespace shadecore

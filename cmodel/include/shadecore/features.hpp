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

#include <algorithm>
#include <cerrno>
#include <cstring>
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

// spot: a point_att light whose attenuation is multiplied by the spot factor (GL_SPOT_*, docs/lighting.md §3.4)
enum class LightKind : int { Directional = 0, Point = 1, PointAtt = 2, Spot = 3 };
inline constexpr int kNumLightKinds = 4;
inline constexpr uint8_t kind_bit(LightKind k) { return static_cast<uint8_t>(1u << static_cast<int>(k)); }
inline constexpr uint8_t kAllKinds = 0xF;
// The kinds whose light has attenuation 1/q (point_att, spot).
inline constexpr bool has_att(LightKind k) { return k == LightKind::PointAtt || k == LightKind::Spot; }

inline constexpr int kLightFracMax = 16;  // the core's widest format (every product stays within 64 bits)
inline constexpr int kSpecGuardMax = 8;    // spec_guard: F + spec_guard <= kFracMax (the units' widest format)
// Default spec_guard: the smallest with the quantisation contract (|fixed − double core with the same
// unit| <= 128 LSB of 2^−16 on every F = 16 named set) met with margin (docs/lighting.md §7).
inline constexpr int kSpecGuardDefault = 5;
inline constexpr int kShareMax = 4;        // SHARE of rtl/sc_light.v: 1..4 clocks per pass

// Capabilities of a lighting core: what hardware exists. The register file chooses among what exists
// at run time (light enable and kind, local viewer, reflection, normalize, the material's unit);
// a capability that is absent is not built (docs/lighting.md §2).
struct FeatureSet {
  std::string name = "custom";
  std::string config = "default";       // width: a named config of configs.json (frac <= 16)
  std::vector<uint8_t> slots{kind_bit(LightKind::Directional)};  // per light slot: the kinds it can take
  bool ambient = true;                  // emission + global ambient + per-light ambient terms
  bool diffuse = true;                  // max(N·L, 0)·d·Id
  bool specular = true;                 // specular units (per lane: one per unit of units())
  VariantId variant = VariantId::cs16;  // the first specular unit, when specular
  std::vector<VariantId> more_units;    // further units the material register can choose
  Cutoff cutoff = Cutoff::ThetaCr;      // cs16 only
  bool norm = false;                    // rtl/sc_energy.v after each unit (coefficient register mat_coef)
  bool blinn = true;                    // x = N·H (Blinn-Phong) exists
  bool phong = false;                   // x = R·V (Phong) exists
  bool local_viewer = false;            // V = normalise(−P) exists (V = (0, 0, 1) always does)
  bool normalize = true;                // GL_NORMALIZE: the normal normaliser exists
  bool low_shininess = false;           // shininess n < 2^kLowNBits (GL's 0..15): x^n by an exact chain beside
                                        // the units (rtl/sc_powi.v, docs/lighting.md §3.5); needs a unit
  bool two_side = false;                // GL_LIGHT_MODEL_TWO_SIDE: a back-facing fragment (in_back_i) is lit with
                                        // −N and the back colour bank, chosen by light_model bit 3 (docs/lighting.md
                                        // §3.7)
  bool separate_specular = false;       // GL_SEPARATE_SPECULAR_COLOR: the specular sum as a second output colour,
                                        // chosen by light_model bit 4 (docs/lighting.md §3.6); needs a unit
  bool colour_material = false;         // GL_COLOR_MATERIAL: a per-fragment colour (in_cr_i..) replaces the material
                                        // colour(s) the colour_material register names (docs/lighting.md §3.8)
  int channels = 3;                     // 1 (mono, channel 0 only) or 3 (RGB)
  int lanes = 1;                        // per-light datapaths; enabled lights take ⌈k/lanes⌉ passes
  int share = 1;                        // clocks per pass (1..kShareMax): the vector normalisations of a
                                        // pass share ⌈ops/share⌉ normalisers (docs/lighting.md §2.1); > 1 needs lanes 1
  int spec_guard = kSpecGuardDefault;   // extra fraction bits of the specular path: N̂, V̂, L̂, Ĥ, R, x and the
                                        // unit run at F + spec_guard fraction bits (docs/lighting.md §7)
  int mreg = 0;                         // the pipelining parameter MREG of rtl/sc_light.v (0/1, every share):
                                        // registers inside the normalisers' products (kMregNormalize more
                                        // cycles each) and the units' MREG; the same results

  [[nodiscard]] Format format() const { return config_named(config).format; }
  // The format of the specular path and its units: F + spec_guard fraction bits, the same guard.
  [[nodiscard]] Format unit_format() const {
    Format f = format();
    f.frac += spec_guard;
    return f;
  }
  [[nodiscard]] int num_lights() const { return static_cast<int>(slots.size()); }
  [[nodiscard]] bool slot_can(int j, LightKind k) const { return (slots[static_cast<size_t>(j)] & kind_bit(k)) != 0; }
  // The first kind slot j can take (the only one for a specialised slot).
  [[nodiscard]] LightKind slot_kind(int j) const {
    for (int k = 0; k < kNumLightKinds; ++k)
      if (slots[static_cast<size_t>(j)] & (1u << k)) return static_cast<LightKind>(k);
    return LightKind::Directional;
  }
  [[nodiscard]] bool any_kind(LightKind k) const {
    for (auto m : slots)
      if (m & kind_bit(k)) return true;
    return false;
  }
  [[nodiscard]] bool any_point() const {
    return any_kind(LightKind::Point) || any_kind(LightKind::PointAtt) || any_kind(LightKind::Spot);
  }
  // Some slot computes an attenuation (point_att or spot).
  [[nodiscard]] bool any_att() const { return any_kind(LightKind::PointAtt) || any_kind(LightKind::Spot); }
  [[nodiscard]] bool needs_position() const { return any_point() || (specular && local_viewer); }
  // The specular units the material can choose (empty without specular), first = variant.
  [[nodiscard]] std::vector<VariantId> units() const {
    std::vector<VariantId> u;
    if (!specular) return u;
    u.push_back(variant);
    u.insert(u.end(), more_units.begin(), more_units.end());
    return u;
  }
  [[nodiscard]] bool has_unit(VariantId v) const {
    for (auto u : units())
      if (u == v) return true;
    return false;
  }
  [[nodiscard]] bool both_reflections() const { return blinn && phong; }

  // Canonical JSON (every key, fixed order, without the name): equal sets give equal strings.
  [[nodiscard]] nlohmann::ordered_json canonical() const;
  // Build-cache key: 16 hex digits of FNV-1a over canonical().dump().
  [[nodiscard]] std::string key() const;
  // "-GNAME=value" parameters of rtl/sc_light.v.
  [[nodiscard]] std::vector<std::string> verilog_params(int tagw) const;
  // One line for humans: "3 slots (point_att ×2, directional), ambient, diffuse, cs16/theta_cr, blinn, ..."
  [[nodiscard]] std::string summary() const;
};

inline const char* to_string(LightKind k) {
  for (const auto& n : kLightKinds)
    if (n.id == static_cast<int>(k)) return n.name.data();
  return "?";
}
// "directional" or "point|point_att" (a slot's kinds, in id order).
inline std::string kinds_name(uint8_t mask) {
  std::string s;
  for (int k = 0; k < kNumLightKinds; ++k)
    if (mask & (1u << k)) s += (s.empty() ? "" : "|") + std::string(to_string(static_cast<LightKind>(k)));
  return s;
}

// Levenshtein distance: the "did you mean" of an unknown feature-set name (and of the CLI's unknown options).
inline size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// The name of `names` closest to `key` within a third of its length (at least one edit), or "".
inline std::string nearest_name(const std::string& key, const std::vector<std::string>& names) {
  std::string near;
  size_t best = std::string::npos;
  for (const auto& n : names) {
    const size_t d = edit_distance(n, key);
    if (d <= std::max<size_t>(1, n.size() / 3) && d < best) best = d, near = n;
  }
  return near;
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
inline uint8_t fs_kind(const nlohmann::json& e, const std::string& where) {
  const std::string s = fs_string(e, "lights[]", where);
  for (const auto& kind : kLightKinds)
    if (kind.name == s) {
      if (kind.reserved)
        fs_fail(where, "light kind '" + s + "' is reserved (not in this core yet; known: directional, point, point_att, spot)");
      return static_cast<uint8_t>(1u << kind.id);
    }
  fs_fail(where, "unknown light kind '" + s + "' (known: directional, point, point_att, spot)");
  return 0;
}
// A string or a non-empty list of strings, each parsed by `one`.
template <class F>
inline void fs_one_or_list(const nlohmann::json& v, const char* key, const std::string& where, F one) {
  if (v.is_string()) return one(v);
  if (!v.is_array() || v.empty())
    fs_fail(where, std::string("'") + key + "' must be a string or a non-empty list of strings");
  for (const auto& e : v) one(e);
}
}  // namespace detail

// Parse one feature set. `where` prefixes every error (a file name or "feature set 'full'").
inline FeatureSet feature_set_from_json(const nlohmann::json& j, const std::string& where) {
  using detail::fs_fail;
  if (!j.is_object()) fs_fail(where, "a feature set must be a JSON object");
  FeatureSet fs;
  bool cutoff_given = false, lanes_given = false;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const nlohmann::json& v = it.value();
    if (k == "name") fs.name = detail::fs_string(v, "name", where);
    else if (k == "_comment") continue;
    else if (k == "config") fs.config = detail::fs_string(v, "config", where);
    else if (k == "lights") {
      if (!v.is_array() || v.empty() || v.size() > static_cast<size_t>(kMaxLights))
        fs_fail(where, "'lights' must be a list of 1.." + std::to_string(kMaxLights) +
                           " light slots, each a kind or a list of kinds (directional, point, point_att, spot)");
      fs.slots.clear();
      for (const auto& e : v) {
        uint8_t m = 0;
        detail::fs_one_or_list(e, "lights[]", where, [&](const nlohmann::json& x) {
          const uint8_t b = detail::fs_kind(x, where);
          if (m & b) fs_fail(where, "light slot " + std::to_string(fs.slots.size()) + " names a kind twice");
          m |= b;
        });
        fs.slots.push_back(m);
      }
    } else if (k == "ambient") fs.ambient = detail::fs_bool(v, "ambient", where);
    else if (k == "diffuse") fs.diffuse = detail::fs_bool(v, "diffuse", where);
    else if (k == "specular") {
      std::vector<VariantId> us;
      bool none = false;
      detail::fs_one_or_list(v, "specular", where, [&](const nlohmann::json& x) {
        const std::string s = detail::fs_string(x, "specular", where);
        if (s == "none") {
          none = true;
          return;
        }
        VariantId id{};
        try {
          id = parse_variant(s);
        } catch (const std::exception& e) {
          fs_fail(where, std::string(e.what()) + " or none");
        }
        if (is_table_variant(id))
          fs_fail(where, "specular unit '" + s + "' is not supported by the lighting core (it has no table-load port; "
                         "use cs16, schlick_div, schlick_nr or schlick_iter)");
        for (auto u : us)
          if (u == id) fs_fail(where, "specular unit '" + s + "' named twice");
        us.push_back(id);
      });
      if (none && !us.empty()) fs_fail(where, "'specular': none cannot be listed with units");
      fs.specular = !none;
      if (fs.specular) {
        fs.variant = us.front();
        fs.more_units.assign(us.begin() + 1, us.end());
      } else {
        fs.more_units.clear();
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
      bool b = false, p = false;
      detail::fs_one_or_list(v, "reflection", where, [&](const nlohmann::json& x) {
        const std::string s = detail::fs_string(x, "reflection", where);
        if (s != "blinn" && s != "phong") fs_fail(where, "'reflection' must be blinn, phong or a list of both");
        (s == "blinn" ? b : p) = true;
      });
      fs.blinn = b;
      fs.phong = p;
    } else if (k == "local_viewer") fs.local_viewer = detail::fs_bool(v, "local_viewer", where);
    else if (k == "normalize") fs.normalize = detail::fs_bool(v, "normalize", where);
    else if (k == "low_shininess") fs.low_shininess = detail::fs_bool(v, "low_shininess", where);
    else if (k == "separate_specular") fs.separate_specular = detail::fs_bool(v, "separate_specular", where);
    else if (k == "two_side") fs.two_side = detail::fs_bool(v, "two_side", where);
    else if (k == "colour_material") fs.colour_material = detail::fs_bool(v, "colour_material", where);
    else if (k == "channels") {
      if (!v.is_number_integer() || (v.get<int>() != 1 && v.get<int>() != 3))
        fs_fail(where, "'channels' must be 1 or 3");
      fs.channels = v.get<int>();
    } else if (k == "lanes") {
      if (!v.is_number_integer() || v.get<int>() < 1 || v.get<int>() > kMaxLights)
        fs_fail(where, "'lanes' must be an integer 1.." + std::to_string(kMaxLights));
      fs.lanes = v.get<int>();
      lanes_given = true;
    } else if (k == "share") {
      if (!v.is_number_integer() || v.get<int>() < 1 || v.get<int>() > kShareMax)
        fs_fail(where, "'share' must be an integer 1.." + std::to_string(kShareMax) + " (clocks per pass)");
      fs.share = v.get<int>();
    } else if (k == "mreg") {
      if (!v.is_number_integer() || (v.get<int>() != 0 && v.get<int>() != 1))
        fs_fail(where, "'mreg' must be 0 or 1 (the pipelining parameter)");
      fs.mreg = v.get<int>();
    } else if (k == "spec_guard") {
      if (!v.is_number_integer() || v.get<int>() < 0 || v.get<int>() > kSpecGuardMax)
        fs_fail(where, "'spec_guard' must be an integer 0.." + std::to_string(kSpecGuardMax));
      fs.spec_guard = v.get<int>();
    } else {
      fs_fail(where, "unknown key '" + k + "'");
    }
  }
  try {
    const Format f = config_named(fs.config).format;
    if (f.frac > kLightFracMax)
      fs_fail(where, "config '" + fs.config + "' has frac " + std::to_string(f.frac) +
                         "; the lighting core supports frac <= " + std::to_string(kLightFracMax));
    validate(fs.unit_format());  // F + spec_guard <= 24, F + spec_guard + guard <= 31
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).rfind(where, 0) == 0) throw;
    fs_fail(where, e.what());
  }
  if (cutoff_given && !fs.has_unit(VariantId::cs16)) fs_fail(where, "'cutoff' applies to the cs16 unit only");
  if (fs.norm && !fs.specular) fs_fail(where, "'norm' needs a specular unit");
  if (fs.low_shininess && !fs.specular) fs_fail(where, "'low_shininess' needs a specular unit");
  if (fs.separate_specular && !fs.specular) fs_fail(where, "'separate_specular' needs a specular unit");
  if (!fs.ambient && !fs.diffuse && !fs.specular) fs_fail(where, "no term enabled (ambient, diffuse, specular)");
  if (lanes_given && fs.lanes > fs.num_lights())
    fs_fail(where, "'lanes' " + std::to_string(fs.lanes) + " exceeds the " + std::to_string(fs.num_lights()) +
                       " light slots");
  if (fs.lanes > fs.num_lights()) fs.lanes = fs.num_lights();
  if (fs.share > 1 && fs.lanes != 1)
    fs_fail(where, "'share' " + std::to_string(fs.share) + " needs 'lanes' 1 (the shared normalisers serve one lane)");
  if (fs.specular && fs.has_unit(VariantId::schlick_iter) && fs.units().size() > 1)
    fs_fail(where, "schlick_iter (one fragment per F+4 clocks) cannot share a core with other units");
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
  if (!in) {
    // A path (a '/' or a .json name) that cannot be opened is a missing file, not an unknown name (issue 38).
    const bool path_like = arg.find('/') != std::string::npos ||
                           (arg.size() > 5 && arg.compare(arg.size() - 5, 5, ".json") == 0);
    if (path_like)
      throw std::invalid_argument("feature set file '" + arg + "': " + std::strerror(errno) + " (named sets: " + known + ")");
    std::vector<std::string> names;
    for (const auto& fs : named_feature_sets()) names.push_back(fs.name);
    const std::string near = nearest_name(arg, names);
    throw std::invalid_argument("unknown feature set '" + arg + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                                " (named: " + known + "; or a JSON file)");
  }
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
  for (auto m : slots) {
    nlohmann::ordered_json e = nlohmann::ordered_json::array();
    for (int k = 0; k < kNumLightKinds; ++k)
      if (m & (1u << k)) e.push_back(to_string(static_cast<LightKind>(k)));
    if (e.size() == 1) l.push_back(e[0]);
    else l.push_back(e);
  }
  j["lights"] = l;
  j["ambient"] = ambient;
  j["diffuse"] = diffuse;
  if (!specular) j["specular"] = "none";
  else if (more_units.empty()) j["specular"] = std::string(variant_name(variant));
  else {
    nlohmann::ordered_json u = nlohmann::ordered_json::array();
    for (auto v : units()) u.push_back(std::string(variant_name(v)));
    j["specular"] = u;
  }
  if (has_unit(VariantId::cs16)) j["cutoff"] = to_string(cutoff);
  j["norm"] = norm;
  if (blinn && phong) j["reflection"] = nlohmann::ordered_json::array({"blinn", "phong"});
  else j["reflection"] = blinn ? "blinn" : "phong";
  j["local_viewer"] = local_viewer;
  j["normalize"] = normalize;
  j["low_shininess"] = low_shininess;
  j["separate_specular"] = separate_specular;
  j["two_side"] = two_side;
  j["colour_material"] = colour_material;
  j["channels"] = channels;
  j["lanes"] = lanes;
  j["share"] = share;
  j["spec_guard"] = spec_guard;
  if (mreg != 0) j["mreg"] = mreg;  // only when set: the keys (and cached builds) of mreg 0 sets stay as they were
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
  // SLOT_KINDS: kinds 0..2 of slot j at bits [3j+2:3j]; SLOT_SPOT: bit j = slot j can be spot (kind 3)
  uint32_t kinds = 0, spot = 0, unit_mask = 0;
  for (size_t j = 0; j < slots.size(); ++j) {
    kinds |= (static_cast<uint32_t>(slots[j]) & 7u) << (3 * j);
    if (slots[j] & kind_bit(LightKind::Spot)) spot |= 1u << j;
  }
  for (auto u : units()) unit_mask |= 1u << static_cast<int>(u);
  std::vector<std::string> p = {
      "FRAC=" + std::to_string(f.frac),
      "GUARD=" + std::to_string(f.guard),
      "LIGHTS=" + std::to_string(slots.size()),
      "SLOT_KINDS=" + std::to_string(kinds),
      "SLOT_SPOT=" + std::to_string(spot),
      "LANES=" + std::to_string(lanes),
      "SHARE=" + std::to_string(share),
      "SGUARD=" + std::to_string(spec_guard),
      "AMBIENT=" + std::to_string(ambient ? 1 : 0),
      "DIFFUSE=" + std::to_string(diffuse ? 1 : 0),
      "UNITS=" + std::to_string(unit_mask),
      "CUTOFF=" + std::to_string(static_cast<int>(cutoff)),
      "ENERGY=" + std::to_string(norm ? 1 : 0),
      "BLINN=" + std::to_string(blinn ? 1 : 0),
      "PHONG=" + std::to_string(phong ? 1 : 0),
      "LOCAL_VIEWER=" + std::to_string(local_viewer ? 1 : 0),
      "NORMALIZE=" + std::to_string(normalize ? 1 : 0),
      "LOW_N=" + std::to_string(low_shininess ? 1 : 0),
      "SEP_SPEC=" + std::to_string(separate_specular ? 1 : 0),
      "TWO_SIDE=" + std::to_string(two_side ? 1 : 0),
      "COL_MAT=" + std::to_string(colour_material ? 1 : 0),
      "CHANNELS=" + std::to_string(channels),
      "TAGW=" + std::to_string(tagw),
  };
  if (mreg != 0) p.push_back("MREG=" + std::to_string(mreg));
  return p;
}

inline std::string FeatureSet::summary() const {
  std::string s = std::to_string(slots.size()) + (slots.size() == 1 ? " slot (" : " slots (");
  for (size_t j = 0; j < slots.size(); ++j) s += (j ? ", " : "") + kinds_name(slots[j]);
  s += ")";
  s += lanes == 1 ? ", 1 lane" : ", " + std::to_string(lanes) + " lanes";
  if (share > 1) s += ", " + std::to_string(share) + " clocks per pass";
  if (mreg != 0) s += ", MREG 1";
  if (ambient) s += ", ambient+emission";
  if (diffuse) s += ", diffuse";
  if (specular) {
    s += ", specular ";
    bool first = true;
    for (auto u : units()) {
      s += (first ? "" : "|") + std::string(variant_name(u));
      if (u == VariantId::cs16) s += "/" + std::string(to_string(cutoff));
      first = false;
    }
    if (norm) s += "+norm";
    if (spec_guard) s += " at F+" + std::to_string(spec_guard);
    s += blinn && phong ? ", blinn|phong" : (blinn ? ", blinn" : ", phong");
    s += local_viewer ? ", local viewer" : ", infinite viewer";
    if (low_shininess) s += ", shininess 0..1024";
    if (separate_specular) s += ", separate specular";
  } else {
    s += ", no specular";
  }
  s += normalize ? ", normalize" : ", unit normals";
  if (two_side) s += ", two-sided";
  if (colour_material) s += ", colour material";
  s += channels == 3 ? ", RGB" : ", mono";
  s += ", " + config + " (F=" + std::to_string(format().frac) + ")";
  return s;
}

}  // namespace shadecore

// SPDX-License-Identifier: Apache-2.0
// shadecore — the RTL file lists from config/configs.json (shadecore/common/rtl_files.hpp).
#include <algorithm>

#include "shadecore/common/rtl_files.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "shadecore/configs_json.hpp"

namespace shadecore::rtl {
namespace {

const nlohmann::json& rtl_json() {
  static const nlohmann::json j = nlohmann::json::parse(kConfigsJson);
  return j;
}

// Appends the file names of a list, skipping any already present (a unit's files can repeat).
void append(std::vector<std::string>& out, const nlohmann::json& list, const std::string& what) {
  if (!list.is_array()) throw std::runtime_error("config/configs.json: " + what + " must be a list of file names");
  for (const auto& f : list) {
    const std::string s = f.get<std::string>();
    bool dup = false;
    for (const auto& o : out) dup = dup || o == s;
    if (!dup) out.push_back(s);
  }
}

const nlohmann::json& top(const char* name) {
  const auto& r = rtl_json().at("rtl");
  if (!r.contains(name)) throw std::runtime_error(std::string("config/configs.json: rtl has no entry '") + name + "'");
  return r.at(name);
}

}  // namespace

std::vector<std::string> specular_files(VariantId variant, bool norm) {
  std::vector<std::string> v;
  append(v, top("sc_specular").at("files"), "rtl.sc_specular.files");
  const std::string name(variant_name(variant));
  bool found = false;
  for (const auto& e : rtl_json().at("variants"))
    if (e.at("name").get<std::string>() == name) {
      append(v, e.at("rtl"), "variants[" + name + "].rtl");
      found = true;
    }
  if (!found) throw std::runtime_error("config/configs.json: no variant '" + name + "'");
  if (norm) append(v, top("sc_specular").at("energy"), "rtl.sc_specular.energy");
  return v;
}

std::vector<std::string> specular_includes() {
  std::vector<std::string> v;
  append(v, top("sc_specular").at("includes"), "rtl.sc_specular.includes");
  return v;
}

std::vector<std::string> light_files(const FeatureSet& fs) {
  // The generate conditions of rtl/sc_light.v (NEED_N, LV, ANY_ATT, ANY_PL, T_NN / T_V / T_L / Blinn H).
  const bool any_att = fs.any_att(), any_point = fs.any_kind(LightKind::Point);
  const bool need_n = fs.diffuse || fs.specular;
  const bool lv = fs.specular && fs.local_viewer;
  const bool any_pl = any_att || (need_n && any_point);
  const bool normalize = (need_n && fs.normalize) || lv || any_pl || (fs.specular && fs.blinn);
  const auto& l = top("sc_light");
  std::vector<std::string> v;
  append(v, l.at("files"), "rtl.sc_light.files");
  if (normalize) append(v, l.at("normalize"), "rtl.sc_light.normalize");
  if (any_att) append(v, l.at("recip"), "rtl.sc_light.recip");
  for (VariantId u : fs.units()) append(v, specular_files(u, fs.norm), "rtl.sc_specular");
  std::vector<std::string> once;  // units share sc_specular.v (and sc_energy.v): each file once
  for (const auto& f : v)
    if (std::find(once.begin(), once.end(), f) == once.end()) once.push_back(f);
  return once;
}

std::vector<std::string> light_includes() {
  std::vector<std::string> v;
  append(v, top("sc_light").at("includes"), "rtl.sc_light.includes");
  return v;
}

std::vector<std::string> light_axi_files(const FeatureSet& fs) {
  std::vector<std::string> v;
  append(v, top("sc_light_axi").at("files"), "rtl.sc_light_axi.files");
  for (const auto& f : light_files(fs))
    if (std::find(v.begin(), v.end(), f) == v.end()) v.push_back(f);
  return v;
}

std::vector<std::string> light_axi_includes() {
  std::vector<std::string> v;
  append(v, top("sc_light_axi").at("includes"), "rtl.sc_light_axi.includes");
  for (const auto& f : light_includes())
    if (std::find(v.begin(), v.end(), f) == v.end()) v.push_back(f);
  return v;
}

}  // namespace shadecore::rtl

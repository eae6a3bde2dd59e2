// SPDX-License-Identifier: Apache-2.0
// shadecore — the RTL file lists (issue 20), read from config/configs.json "rtl" and variants[].rtl,
// the one source that CMake (cmake/ShadecoreConfigs.cmake) reads too. The CLI reads the copy compiled
// in through shadecore/configs_json.hpp, so it works from the build tree and needs no source file at
// run time. Names are file names in rtl/ (e.g. "sc_cs16.v"); the files include the generated headers
// of *_includes() (-I rtl). Users: both handoff bundles (cli/handoff_specular.cpp, cli/handoff_light.cpp),
// the lighting-core build (cli/light_rtl.cpp, sim/light_core) and sc_light_params (rtl/).
#pragma once

#include <string>
#include <vector>

#include "shadecore/features.hpp"

namespace shadecore::rtl {

// sc_specular.v with the unit of `variant` (variants[].rtl) and, with `norm`, sc_energy.v.
std::vector<std::string> specular_files(VariantId variant, bool norm);
std::vector<std::string> specular_includes();

// Exactly the files rtl/sc_light.v elaborates for `fs`: sc_light.v, sc_delay.v, sc_normalize.v when a
// vector is renormalised, sc_recip.v for attenuated point lights, the specular list when specular.
// (The capability conditions are the generate conditions of sc_light.v; the random-combination lint
// test rtl.lint.sc_light.random_combinations elaborates every list it draws with nothing else.)
std::vector<std::string> light_files(const FeatureSet& fs);
std::vector<std::string> light_includes();
// The AXI wrapper rtl/sc_light_axi.v around the core of fs (config/configs.json "rtl" "sc_light_axi"): its files,
// then light_files(fs); its includes, then light_includes().
std::vector<std::string> light_axi_files(const FeatureSet& fs);
std::vector<std::string> light_axi_includes();

}  // namespace shadecore::rtl

# Reads config/configs.json — the single source of truth for the fixed-point widths — and
#   * generates ${CMAKE_BINARY_DIR}/generated/shadecore/configs.hpp for the C++ side,
#   * sets SHADECORE_CONFIG_NAMES and, per name, SHADECORE_CONFIG_<name>_FRAC / _GUARD for the
#     Verilator -G parameters of the RTL builds.
set(_cfg_file "${CMAKE_SOURCE_DIR}/config/configs.json")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${_cfg_file}")
file(READ "${_cfg_file}" _cfg_json)
string(JSON SHADECORE_DEFAULT_CONFIG GET "${_cfg_json}" default)
string(JSON _n LENGTH "${_cfg_json}" configs)
math(EXPR _last "${_n} - 1")
set(SHADECORE_CONFIG_NAMES "")
set(_entries "")
foreach(i RANGE ${_last})
  string(JSON _name GET "${_cfg_json}" configs ${i} name)
  string(JSON _frac GET "${_cfg_json}" configs ${i} frac)
  string(JSON _guard GET "${_cfg_json}" configs ${i} guard)
  list(APPEND SHADECORE_CONFIG_NAMES "${_name}")
  set(SHADECORE_CONFIG_${_name}_FRAC "${_frac}")
  set(SHADECORE_CONFIG_${_name}_GUARD "${_guard}")
  string(APPEND _entries "    NamedConfig{\"${_name}\", Format{${_frac}, ${_guard}}},\n")
endforeach()
if(NOT SHADECORE_DEFAULT_CONFIG IN_LIST SHADECORE_CONFIG_NAMES)
  message(FATAL_ERROR "config/configs.json: default '${SHADECORE_DEFAULT_CONFIG}' is not a listed config")
endif()
set(SHADECORE_GENERATED_DIR "${CMAKE_BINARY_DIR}/generated")
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_DIR}/shadecore/configs.hpp" CONTENT
"// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
#pragma once
#include <array>
#include <stdexcept>
#include <string>
#include <string_view>
#include \"shadecore/format.hpp\"
namespace shadecore {
struct NamedConfig { std::string_view name; Format format; };
inline constexpr std::array<NamedConfig, ${_n}> kConfigs{{
${_entries}}};
inline constexpr std::string_view kDefaultConfig = \"${SHADECORE_DEFAULT_CONFIG}\";
// The named configuration; an empty name means the default. Throws std::invalid_argument
// (one line, listing the known names) for an unknown name.
inline const NamedConfig& config_named(std::string_view name) {
  if (name.empty()) name = kDefaultConfig;
  for (const auto& c : kConfigs)
    if (c.name == name) return c;
  std::string known;
  for (const auto& c : kConfigs) known += (known.empty() ? \"\" : \", \") + std::string(c.name);
  throw std::invalid_argument(\"unknown config '\" + std::string(name) + \"' (known: \" + known + \")\");
}
inline Format default_format() { return config_named(kDefaultConfig).format; }
}  // namespace shadecore
" @ONLY)

# Hardware unit variants (config/configs.json "variants": name <-> id, the VARIANT parameter of
# rtl/sc_specular.v). Sets SHADECORE_VARIANT_NAMES and SHADECORE_VARIANT_<name>_ID, and generates
#   ${SHADECORE_GENERATED_DIR}/shadecore/variants.hpp  (enum class VariantId, kVariants)
#   ${CMAKE_SOURCE_DIR}/rtl/sc_variants.vh             (localparam VARIANT_<NAME>, for sc_specular.v; committed)
string(JSON _nv LENGTH "${_cfg_json}" variants)
math(EXPR _lastv "${_nv} - 1")
set(SHADECORE_VARIANT_NAMES "")
set(_venum "")
set(_ventries "")
set(_vvh "")
foreach(i RANGE ${_lastv})
  string(JSON _vname GET "${_cfg_json}" variants ${i} name)
  string(JSON _vid GET "${_cfg_json}" variants ${i} id)
  list(APPEND SHADECORE_VARIANT_NAMES "${_vname}")
  set(SHADECORE_VARIANT_${_vname}_ID "${_vid}")
  string(TOUPPER "${_vname}" _vupper)
  string(APPEND _venum "  ${_vname} = ${_vid},\n")
  string(APPEND _ventries "    NamedVariant{\"${_vname}\", VariantId::${_vname}},\n")
  string(APPEND _vvh "localparam integer VARIANT_${_vupper} = ${_vid};\n")
endforeach()
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_DIR}/shadecore/variants.hpp" CONTENT
"// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
#pragma once
#include <array>
#include <string_view>
namespace shadecore {
// The VARIANT parameter of rtl/sc_specular.v.
enum class VariantId : int {
${_venum}};
struct NamedVariant { std::string_view name; VariantId id; };
inline constexpr std::array<NamedVariant, ${_nv}> kVariants{{
${_ventries}}};
}  // namespace shadecore
" @ONLY)
# The Verilog include is written into rtl/ (and committed) so that the RTL is self-contained for a
# hand-off and plain `-Irtl` tools; configure rewrites it only when configs.json changes it.
set(SHADECORE_RTL_INCDIR "${CMAKE_SOURCE_DIR}/rtl")
file(CONFIGURE OUTPUT "${SHADECORE_RTL_INCDIR}/sc_variants.vh" CONTENT
"// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
// Values of the VARIANT parameter of rtl/sc_specular.v (included inside the module).
${_vvh}" @ONLY)

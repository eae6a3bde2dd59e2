# SPDX-License-Identifier: Apache-2.0
# Reads config/configs.json — the single source of truth for the fixed-point widths — and
#   * generates ${CMAKE_BINARY_DIR}/generated/shadecore/configs.hpp for the C++ side,
#   * sets SHADECORE_CONFIG_NAMES and, per name, SHADECORE_CONFIG_<name>_FRAC / _GUARD for the
#     Verilator -G parameters of the RTL builds.
set(_cfg_file "${CMAKE_SOURCE_DIR}/config/configs.json")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${_cfg_file}")
file(READ "${_cfg_file}" _cfg_json)
string(JSON SHADECORE_DEFAULT_CONFIG GET "${_cfg_json}" default)
# _shadecore_json_flag(<out> <path...>): "true" when the optional boolean member at <path> of
# configs.json is present and true, else "false" (the C++ spelling the generated tables use).
function(_shadecore_json_flag out)
  string(JSON _v ERROR_VARIABLE _missing GET "${_cfg_json}" ${ARGN})
  if(_missing OR NOT _v)
    set(${out} false PARENT_SCOPE)
  else()
    set(${out} true PARENT_SCOPE)
  endif()
endfunction()
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
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
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

# Legal parameter ranges (config/configs.json "limits", the one source): generates
# ${SHADECORE_GENERATED_DIR}/shadecore/limits.hpp (namespace shadecore::limits, k<Name>Min/Max, kWorkMax),
# from which cmodel format.hpp and units/coef.hpp take their constants. The RTL's elaboration checks state
# the same numbers; ctest rtl.limits_agree (scripts/check_limits.py) checks them against the same entries.
string(JSON _nlim LENGTH "${_cfg_json}" limits)
math(EXPR _nlim_last "${_nlim} - 1")
set(_limits_hpp "")
foreach(i RANGE ${_nlim_last})
  string(JSON _lname MEMBER "${_cfg_json}" limits ${i})
  if(_lname STREQUAL "_comment")
    continue()
  endif()
  string(JSON _lcpp GET "${_cfg_json}" limits ${_lname} cpp)
  foreach(_bound min max sum_max)
    string(JSON _lv ERROR_VARIABLE _lnone GET "${_cfg_json}" limits ${_lname} ${_bound})
    if(NOT _lnone)
      if(_bound STREQUAL "min")
        set(_lsuffix Min)
      elseif(_bound STREQUAL "max")
        set(_lsuffix Max)
      else()
        set(_lsuffix "")  # the entry's cpp name already says what it bounds (kWorkMax)
      endif()
      string(APPEND _limits_hpp "inline constexpr int ${_lcpp}${_lsuffix} = ${_lv};  // limits.${_lname}.${_bound}\n")
    endif()
  endforeach()
endforeach()
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_DIR}/shadecore/limits.hpp" CONTENT
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json \"limits\" by cmake/ShadecoreConfigs.cmake — do not edit
// The legal parameter ranges of the RTL and the C model (docs/spec.md §2; rtl/*.v elaboration checks,
// ctest rtl.limits_agree).
#pragma once
namespace shadecore::limits {
${_limits_hpp}}  // namespace shadecore::limits
" @ONLY)

# Hardware unit variants (config/configs.json "variants": name <-> id, the VARIANT parameter of
# rtl/sc_specular.v). Sets SHADECORE_VARIANT_NAMES and SHADECORE_VARIANT_<name>_ID, and generates
#   ${SHADECORE_GENERATED_DIR}/shadecore/variants.hpp  (enum class VariantId, kVariants)
#   ${SHADECORE_GENERATED_DIR}/rtl/sc_variants.vh      (localparam VARIANT_<NAME>, for sc_specular.v; committed
#                                                      as rtl/sc_variants.vh, checked by a ctest)
string(JSON _nv LENGTH "${_cfg_json}" variants)
math(EXPR _lastv "${_nv} - 1")
set(SHADECORE_VARIANT_NAMES "")
set(_venum "")
set(_ventries "")
set(_vvh "")
set(_sqentries "")
set(_sqcase "")
set(_mregcase "")  # variant_mreg_stages() of sc_variants.vh: the RTL's copy of variants[].mreg_stages
set(_nsq 0)
set(SHADECORE_SQUARER_VARIANTS "")
foreach(i RANGE ${_lastv})
  string(JSON _vname GET "${_cfg_json}" variants ${i} name)
  string(JSON _vid GET "${_cfg_json}" variants ${i} id)
  # Optional fields: "contract" (the unit's error contract / kind, e.g. "table"; "" when absent) and
  # "entries" (table variants: entries of the per-material table; 0 when absent).
  string(JSON _vcontract ERROR_VARIABLE _nocontract GET "${_cfg_json}" variants ${i} contract)
  if(_nocontract)
    set(_vcontract "")
  endif()
  string(JSON _ventries_n ERROR_VARIABLE _noentries GET "${_cfg_json}" variants ${i} entries)
  if(_noentries)
    set(_ventries_n 0)
  endif()
  # "mreg_stages": the unit takes the pipelining parameter MREG; MREG = 1 adds this many cycles (0 when absent)
  string(JSON _vmreg ERROR_VARIABLE _nomreg GET "${_cfg_json}" variants ${i} mreg_stages)
  if(_nomreg)
    set(_vmreg 0)
  endif()
  if(NOT _vmreg EQUAL 0)
    string(TOUPPER "${_vname}" _vmup)
    string(APPEND _mregcase "      VARIANT_${_vmup}: variant_mreg_stages = ${_vmreg};\n")
  endif()
  # "signoff_abc": the ABC script of the OSU 0.18 um sign-off (signoff/signoff.py --abc): full (default) or lean,
  # for a unit whose delay-driven mapping with SAT sweeping does not finish in hours (schlick_nr; docs/signoff.md)
  string(JSON _vabc ERROR_VARIABLE _noabc GET "${_cfg_json}" variants ${i} signoff_abc)
  if(_noabc)
    set(_vabc "full")
  endif()
  if(NOT _vabc STREQUAL "full" AND NOT _vabc STREQUAL "lean")
    message(FATAL_ERROR "config/configs.json: variant ${_vname}: signoff_abc must be \"full\" or \"lean\", not \"${_vabc}\"")
  endif()
  list(APPEND SHADECORE_VARIANT_NAMES "${_vname}")
  set(SHADECORE_VARIANT_${_vname}_ID "${_vid}")
  set(SHADECORE_VARIANT_${_vname}_CONTRACT "${_vcontract}")
  set(SHADECORE_VARIANT_${_vname}_ENTRIES "${_ventries_n}")
  set(SHADECORE_VARIANT_${_vname}_MREG_STAGES "${_vmreg}")
  string(TOUPPER "${_vname}" _vupper)
  string(APPEND _venum "  ${_vname} = ${_vid},\n")
  string(APPEND _ventries "    NamedVariant{\"${_vname}\", VariantId::${_vname}, \"${_vcontract}\", ${_ventries_n}, ${_vmreg}, \"${_vabc}\"},\n")
  string(APPEND _vvh "localparam integer VARIANT_${_vupper} = ${_vid};\n")
  if(NOT _ventries_n EQUAL 0)
    string(APPEND _vvh "localparam integer VARIANT_${_vupper}_ENTRIES = ${_ventries_n};\n")
  endif()
  # Optional "squarer": a cs16 form with folded truncated squarers (rtl/sc_cs16.v FORM = 1, spec §3.4).
  string(JSON _sq ERROR_VARIABLE _nosq GET "${_cfg_json}" variants ${i} squarer)
  if(NOT _nosq)
    string(JSON _rg GET "${_cfg_json}" variants ${i} squarer rel_guard)
    string(JSON _comp GET "${_cfg_json}" variants ${i} squarer compensate)
    string(JSON _contract GET "${_cfg_json}" variants ${i} contract)
    string(JSON _nsf LENGTH "${_cfg_json}" variants ${i} squarer stage_frac)
    if(NOT _nsf EQUAL 4)
      message(FATAL_ERROR "config/configs.json: variant ${_vname}: squarer.stage_frac must have 4 entries")
    endif()
    string(JSON _nkp LENGTH "${_cfg_json}" variants ${i} squarer keep)
    if(NOT _nkp EQUAL 4)
      message(FATAL_ERROR "config/configs.json: variant ${_vname}: squarer.keep must have 4 entries (one per squaring)")
    endif()
    set(_a "")
    set(_kp "")
    foreach(k RANGE 3)
      string(JSON _ak GET "${_cfg_json}" variants ${i} squarer stage_frac ${k})
      list(APPEND _a ${_ak})
      string(JSON _kk GET "${_cfg_json}" variants ${i} squarer keep ${k})
      list(APPEND _kp ${_kk})
    endforeach()
    if(_rg)
      set(_rg 1)
    else()
      set(_rg 0)
    endif()
    if(_comp)
      set(_comp 1)
    else()
      set(_comp 0)
    endif()
    list(GET _a 0 _a1)
    list(GET _a 1 _a2)
    list(GET _a 2 _a3)
    list(GET _a 3 _a4)
    list(GET _kp 0 _k1)
    list(GET _kp 1 _k2)
    list(GET _kp 2 _k3)
    list(GET _kp 3 _k4)
    list(APPEND SHADECORE_SQUARER_VARIANTS "${_vname}")
    string(APPEND _sqentries "    NamedSquarer{VariantId::${_vname}, SquarerForm{${_rg} != 0, {${_a1}, ${_a2}, ${_a3}, ${_a4}}, {${_k1}, ${_k2}, ${_k3}, ${_k4}}, ${_comp} != 0, \"${_contract}\"}},\n")
    string(APPEND _sqcase "      VARIANT_${_vupper}: case (field) 0: cs16_sq_param = 1; 1: cs16_sq_param = ${_rg}; 2: cs16_sq_param = ${_a1}; 3: cs16_sq_param = ${_a2}; 4: cs16_sq_param = ${_a3}; 5: cs16_sq_param = ${_a4}; 6: cs16_sq_param = ${_k1}; 7: cs16_sq_param = ${_k2}; 8: cs16_sq_param = ${_k3}; 9: cs16_sq_param = ${_k4}; 10: cs16_sq_param = ${_comp}; default: cs16_sq_param = 0; endcase\n")
    math(EXPR _nsq "${_nsq} + 1")
  endif()
endforeach()
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_DIR}/shadecore/variants.hpp" CONTENT
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
#pragma once
#include <array>
#include <string_view>
namespace shadecore {
// The VARIANT parameter of rtl/sc_specular.v.
enum class VariantId : int {
${_venum}};
// contract: the variant's kind / error contract from configs.json (\"table\" for the per-material table
// units, \"\" when not given); entries: table size of a \"table\" variant (0 otherwise); mreg_stages: the cycles the
// pipelining parameter MREG = 1 adds (a register inside each product, rtl/sc_mul_reg.v; 0: the unit has no MREG);
// signoff_abc: the ABC script of its OSU 0.18 um sign-off (signoff/signoff.py --abc: full or lean).
struct NamedVariant { std::string_view name; VariantId id; std::string_view contract; int entries; int mreg_stages;
                      std::string_view signoff_abc; };
inline constexpr std::array<NamedVariant, ${_nv}> kVariants{{
${_ventries}}};
// cs16 forms with folded truncated squarers (\"squarer\" in configs.json; docs/spec.md §3.4).
struct SquarerForm {
  bool rel_guard;     // stage widths relative to F+G (true) or F (false)
  int stage_frac[4];  // x_k has B + stage_frac[k-1] fraction bits (stage 4: truncation point only)
  int keep[4];        // columns kept below squaring k's truncation point: ceil(log2 N) + keep[k-1]
  bool compensate;    // add round(E[dropped]) and round (not floor) each stage
  std::string_view contract;  // the variant's \"contract\" (faithful | compact; docs/spec.md §3.4)
};
struct NamedSquarer { VariantId id; SquarerForm form; };
inline constexpr std::array<NamedSquarer, ${_nsq}> kSquarerForms{{
${_sqentries}}};
// The form of a variant, or nullptr for one without squarer (cs16 reference, Schlick units).
inline constexpr const SquarerForm* squarer_form(VariantId v) {
  for (const auto& s : kSquarerForms)
    if (s.id == v) return &s.form;
  return nullptr;
}
}  // namespace shadecore
" @ONLY)
# The Verilog includes are committed in rtl/ so that the RTL is self-contained for a hand-off and
# plain `-Irtl` tools (every tool and bundle includes them from there). Configure never writes into the
# source tree: it generates them into ${SHADECORE_GENERATED_DIR}/rtl/, and the ctest
# rtl.generated_headers_current checks that the committed copies equal them (after editing
# configs.json: `cmake --build build --target update_rtl_headers` copies them into rtl/).
set(SHADECORE_RTL_INCDIR "${CMAKE_SOURCE_DIR}/rtl")
set(SHADECORE_GENERATED_RTL_DIR "${SHADECORE_GENERATED_DIR}/rtl")
set(SHADECORE_GENERATED_RTL_HEADERS sc_variants.vh sc_light_regs.vh sc_light_axi.vh)
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_RTL_DIR}/sc_variants.vh" CONTENT
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
// Values of the VARIANT parameter of rtl/sc_specular.v (included inside the module).
${_vvh}
// cs16 squaring forms (\"squarer\" in configs.json; rtl/sc_cs16.v FORM = 1, docs/spec.md §3.4): field
// 0 FORM, 1 SQ_REL_G, 2..5 SQ_A1..SQ_A4, 6..9 SQ_K1..SQ_K4, 10 SQ_COMP of sc_cs16 for a VARIANT (0 for others).
function integer cs16_sq_param(input integer variant, input integer field);
  begin
    cs16_sq_param = 0;
    case (variant)
${_sqcase}      default: cs16_sq_param = 0;
    endcase
  end
endfunction
// the cycles MREG = 1 adds to a VARIANT (configs.json variants[].mreg_stages; 0: the unit ignores MREG)
function integer variant_mreg_stages(input integer variant);
  begin
    case (variant)
${_mregcase}      default: variant_mreg_stages = 0;
    endcase
  end
endfunction
" @ONLY)

# Lighting core (config/configs.json "light", docs/lighting.md): the register map and the light kinds,
# generated for both sides:
#   ${SHADECORE_GENERATED_DIR}/shadecore/light_regs.hpp   (constexpr addresses, kinds)
#   ${SHADECORE_GENERATED_DIR}/rtl/sc_light_regs.vh        (localparams, included by rtl/sc_light.v; committed
#                                                          as rtl/sc_light_regs.vh, checked by a ctest)
# and the whole configs.json as a string (shadecore/configs_json.hpp), so that the named feature sets
# are parsed by the same code as a user's feature-set file.
string(JSON _lmax GET "${_cfg_json}" light max_lights)
string(JSON _lstride GET "${_cfg_json}" light light_stride)
string(JSON _labits GET "${_cfg_json}" light addr_bits)
string(JSON _lspeb GET "${_cfg_json}" light spot_exponent_bits)
string(JSON _llnb GET "${_cfg_json}" light low_shininess_bits)
string(JSON _llat_n GET "${_cfg_json}" light latency normalize)
string(JSON _llat_r GET "${_cfg_json}" light latency recip)
string(JSON _llat_mn GET "${_cfg_json}" light latency mreg_normalize)
string(JSON _llat_md GET "${_cfg_json}" light latency mreg_dot)
string(JSON _llat_mb GET "${_cfg_json}" light latency mreg_back)
string(JSON _llat_mnn GET "${_cfg_json}" light latency mreg_n)
string(JSON _llat_mp GET "${_cfg_json}" light latency mreg_p)
string(JSON _llat_ma GET "${_cfg_json}" light latency mreg_att)
string(JSON _llat_mr GET "${_cfg_json}" light latency mreg_recip)
string(JSON _llat_mpw GET "${_cfg_json}" light latency mreg_powi)
string(JSON _nk LENGTH "${_cfg_json}" light light_kinds)
math(EXPR _lastk "${_nk} - 1")
set(_kenum "")
set(_kvh "")
set(_ch_kinds "")  # the C header's (reserved kinds are listed too: their id is taken, no core has them)
foreach(i RANGE ${_lastk})
  string(JSON _kname GET "${_cfg_json}" light light_kinds ${i} name)
  string(JSON _kid GET "${_cfg_json}" light light_kinds ${i} id)
  _shadecore_json_flag(_kresc light light_kinds ${i} reserved)
  string(TOUPPER "${_kname}" _kup)
  string(APPEND _kenum "    NamedLightKind{\"${_kname}\", ${_kid}, ${_kresc}},\n")
  string(APPEND _ch_kinds "#define SC_LIGHT_KIND_${_kup} ${_kid}\n")
  if(NOT _kresc)
    string(APPEND _kvh "localparam integer KIND_${_kup} = ${_kid};\n")
    list(APPEND _kuse "KIND_${_kup}[0]")
  endif()
endforeach()
list(JOIN _kuse ", " _kusestr)
set(_kusestr ", ${_kusestr}")
# the light_model register's fields: bit positions for both sides (kLmBit_<name>, LM_<NAME>)
string(JSON _nlm LENGTH "${_cfg_json}" light light_model_bits)
math(EXPR _lastlm "${_nlm} - 1")
set(_lmhpp "")
set(_lmvh "")
set(_ch_lm "")  # the C header's
foreach(i RANGE ${_lastlm})
  string(JSON _lmname GET "${_cfg_json}" light light_model_bits ${i} name)
  string(JSON _lmbit GET "${_cfg_json}" light light_model_bits ${i} bit)
  string(TOUPPER "${_lmname}" _lmup)
  string(APPEND _lmhpp "inline constexpr int kLmBit_${_lmname} = ${_lmbit};\n")
  string(APPEND _ch_lm "#define SC_LIGHT_LM_${_lmup}_SHIFT ${_lmbit}\n#define SC_LIGHT_LM_${_lmup} (1u << ${_lmbit})\n")
  string(APPEND _lmvh "localparam integer LM_${_lmup} = ${_lmbit};\n")
  string(APPEND _kusestr ", LM_${_lmup}[0]")
endforeach()
math(EXPR _lmn "${_nlm}")
string(JSON _nr LENGTH "${_cfg_json}" light registers)
math(EXPR _lastr "${_nr} - 1")
set(_rhpp "")
set(_rvh "")
set(_rtab "")
set(_ch_regs "")      # the C header's lines (shadecore_light_regs.h)
set(_ch_reglist "")
set(_reg_fmts "")     # name=format, checked against light.formats below
set(_ruse "MAX_LIGHTS[0], LIGHT_STRIDE[0], REG_ADDR_BITS[0], SPOT_EXP_BITS[0], LOW_N_BITS[0], LIGHT_MODEL_BITS[0], NORMALIZE_LATENCY[0], RECIP_LATENCY[0], MREG_NORMALIZE[0], MREG_DOT[0], MREG_BACK[0], MREG_N[0], MREG_P[0], MREG_ATT[0], MREG_RECIP[0], MREG_POWI[0]")
foreach(i RANGE ${_lastr})
  string(JSON _rname GET "${_cfg_json}" light registers ${i} name)
  string(JSON _raddr GET "${_cfg_json}" light registers ${i} addr)
  string(JSON _rcount GET "${_cfg_json}" light registers ${i} count)
  string(JSON _rfmt GET "${_cfg_json}" light registers ${i} format)
  _shadecore_json_flag(_rperc light registers ${i} per_light)
  _shadecore_json_flag(_rresc light registers ${i} reserved)
  string(TOUPPER "${_rname}" _rup)
  string(APPEND _rhpp "inline constexpr uint32_t kReg_${_rname} = ${_raddr};\n")
  if(NOT _rresc)
    string(APPEND _rvh "localparam [${_labits}-1:0] REG_${_rup} = ${_labits}'d${_raddr};\n")
    string(APPEND _ruse ", REG_${_rup}")
  endif()
  string(APPEND _rtab "    RegInfo{\"${_rname}\", ${_raddr}, ${_rcount}, \"${_rfmt}\", ${_rperc}, ${_rresc}},\n")
  list(APPEND _reg_fmts "${_rname}=${_rfmt}")
  string(TOUPPER "${_rfmt}" _rfup)
  if(_rperc)
    set(_rp 1)
  else()
    set(_rp 0)
  endif()
  if(_rresc)
    set(_rr 1)
    set(_rnote "  /* reserved: no register in this core, a write is ignored */")
  else()
    set(_rr 0)
    set(_rnote "")
  endif()
  string(APPEND _ch_reglist " \\\n  X(${_rname}, ${_rup})")
  string(APPEND _ch_regs "#define SC_LIGHT_REG_${_rup} ${_raddr}u${_rnote}\n"
                         "#define SC_LIGHT_REG_${_rup}_COUNT ${_rcount}\n"
                         "#define SC_LIGHT_REG_${_rup}_PER_LIGHT ${_rp}\n"
                         "#define SC_LIGHT_REG_${_rup}_RESERVED ${_rr}\n"
                         "#define SC_LIGHT_REG_${_rup}_BITS(F, UF) SC_LIGHT_FMT_${_rfup}_BITS(F, UF)\n"
                         "#define SC_LIGHT_REG_${_rup}_SIGNED SC_LIGHT_FMT_${_rfup}_SIGNED\n")
endforeach()
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_DIR}/shadecore/light_regs.hpp" CONTENT
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
// Register map of the lighting core rtl/sc_light.v (docs/lighting.md §4).
#pragma once
#include <array>
#include <cstdint>
#include <string_view>
namespace shadecore {
inline constexpr int kMaxLights = ${_lmax};
inline constexpr uint32_t kLightStride = ${_lstride};  // address of light j's register = addr + stride·j
inline constexpr int kRegAddrBits = ${_labits};         // width of reg_addr_i
inline constexpr int kSpotExpBits = ${_lspeb};          // the spot exponent register = the spot power chain's stages
inline constexpr int kLowNBits = ${_llnb};             // shininess n < 2^kLowNBits: the low-shininess chain's stages
inline constexpr int kLightModelBits = ${_lmn};        // stored bits of light_model (its fields below)
inline constexpr int kNormalizeLatency = ${_llat_n};     // rtl/sc_normalize.v (light.latency)
inline constexpr int kRecipLatency = ${_llat_r};         // rtl/sc_recip.v
inline constexpr int kMregNormalize = ${_llat_mn};       // cycles the lighting core's MREG = 1 adds to the normaliser
inline constexpr int kMregDot = ${_llat_md};             // ... and to each of the lanes' dot products
inline constexpr int kMregBack = ${_llat_mb};            // ... and to each product stage of the back
inline constexpr int kMregN = ${_llat_mnn};              // ... and registers the lanes' N (N̂ or N) before the dot products
inline constexpr int kMregP = ${_llat_mp};               // ... and P_j − P and −P before the L and V normalisers
inline constexpr int kMregAtt = ${_llat_ma};             // ... and to the attenuation's q (its two product stages)
inline constexpr int kMregRecip = ${_llat_mr};           // ... and to rtl/sc_recip.v (its four Newton–Raphson products)
inline constexpr int kMregPowi = ${_llat_mpw};            // ... and to each stage of the power chains (rtl/sc_powi.v)
${_lmhpp}${_rhpp}// reserved: laid out for the GL-completeness issue, no register in this core (a write is ignored)
struct RegInfo { std::string_view name; uint32_t addr; int count; std::string_view format; bool per_light; bool reserved; };
inline constexpr std::array<RegInfo, ${_nr}> kRegisters{{
${_rtab}}};
struct NamedLightKind { std::string_view name; int id; bool reserved; };
inline constexpr std::array<NamedLightKind, ${_nk}> kLightKinds{{
${_kenum}}};
}  // namespace shadecore
" @ONLY)
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_RTL_DIR}/sc_light_regs.vh" CONTENT
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
// Register map and light kinds of rtl/sc_light.v (included inside the module; docs/lighting.md §4).
localparam integer MAX_LIGHTS = ${_lmax};
localparam integer LIGHT_STRIDE = ${_lstride};
localparam integer REG_ADDR_BITS = ${_labits};
localparam integer SPOT_EXP_BITS = ${_lspeb};
localparam integer LOW_N_BITS = ${_llnb};
localparam integer LIGHT_MODEL_BITS = ${_lmn};
localparam integer NORMALIZE_LATENCY = ${_llat_n};
localparam integer RECIP_LATENCY = ${_llat_r};
localparam integer MREG_NORMALIZE = ${_llat_mn};
localparam integer MREG_DOT = ${_llat_md};
localparam integer MREG_BACK = ${_llat_mb};
localparam integer MREG_N = ${_llat_mnn};
localparam integer MREG_P = ${_llat_mp};
localparam integer MREG_ATT = ${_llat_ma};
localparam integer MREG_RECIP = ${_llat_mr};
localparam integer MREG_POWI = ${_llat_mpw};
${_lmvh}${_kvh}${_rvh}// every name above, so that a module using a few of them lints clean (Verilator's unused pattern)
localparam [0:0] unused_light_regs = ^{1'b0, ${_ruse}${_kusestr}};
" @ONLY)
# The AXI view of the lighting core (config/configs.json light.axi, issue 39): which addresses are registers of a
# build (registers[].needs over the capability bits light.axi.needs) and the AXI4-Stream packing, generated for
#   ${SHADECORE_GENERATED_RTL_DIR}/sc_light_axi.vh                (included inside rtl/sc_light_axi.v; committed)
#   ${SHADECORE_GENERATED_DIR}/shadecore/light_axi_map.hpp        (the benches' and the model's side)
string(JSON _nneeds LENGTH "${_cfg_json}" light axi needs)
math(EXPR _lastneed "${_nneeds} - 1")
set(_axvh_need "")
set(_axhpp_need "")
set(_axuse "")
foreach(i RANGE ${_lastneed})
  string(JSON _ndname GET "${_cfg_json}" light axi needs ${i} name)
  string(JSON _ndbit GET "${_cfg_json}" light axi needs ${i} bit)
  string(TOUPPER "${_ndname}" _ndup)
  set(_needbit_${_ndname} ${_ndbit})
  string(APPEND _axvh_need "localparam integer AXI_NEED_${_ndup} = ${_ndbit};\n")
  string(APPEND _axhpp_need "inline constexpr int kAxiNeed_${_ndname} = ${_ndbit};\n")
  string(APPEND _axuse ", AXI_NEED_${_ndup}[0]")
endforeach()
set(_axlight_base 100000)
set(_axglob "")
set(_axlight "")
set(_axtab "")
foreach(i RANGE ${_lastr})
  string(JSON _rname GET "${_cfg_json}" light registers ${i} name)
  string(JSON _raddr GET "${_cfg_json}" light registers ${i} addr)
  string(JSON _rcount GET "${_cfg_json}" light registers ${i} count)
  _shadecore_json_flag(_rperc light registers ${i} per_light)
  _shadecore_json_flag(_rresc light registers ${i} reserved)
  if(_rperc AND _raddr LESS _axlight_base)
    set(_axlight_base ${_raddr})
  endif()
endforeach()
foreach(i RANGE ${_lastr})
  string(JSON _rname GET "${_cfg_json}" light registers ${i} name)
  string(JSON _raddr GET "${_cfg_json}" light registers ${i} addr)
  string(JSON _rcount GET "${_cfg_json}" light registers ${i} count)
  _shadecore_json_flag(_rperc light registers ${i} per_light)
  _shadecore_json_flag(_rresc light registers ${i} reserved)
  if(_rresc)
    continue()
  endif()
  string(JSON _nn ERROR_VARIABLE _noneeds LENGTH "${_cfg_json}" light registers ${i} needs)
  if(_noneeds)
    message(FATAL_ERROR "config/configs.json: light register ${_rname} has no \"needs\" (the capabilities it exists with)")
  endif()
  set(_mask 0)
  if(_nn GREATER 0)
    math(EXPR _lastnn "${_nn} - 1")
    foreach(k RANGE ${_lastnn})
      string(JSON _nd GET "${_cfg_json}" light registers ${i} needs ${k})
      if(NOT DEFINED _needbit_${_nd})
        message(FATAL_ERROR "config/configs.json: light register ${_rname} needs '${_nd}', not one of light.axi.needs")
      endif()
      math(EXPR _mask "${_mask} | (1 << ${_needbit_${_nd}})")
    endforeach()
  endif()
  set(_items "")
  math(EXPR _lastc "${_rcount} - 1")
  foreach(c RANGE ${_lastc})
    if(_rperc)
      math(EXPR _a "${_raddr} - ${_axlight_base} + ${c}")
      list(APPEND _items "${_a}")
    else()
      math(EXPR _a "${_raddr} + ${c}")
      list(APPEND _items "${_labits}'d${_a}")
    endif()
  endforeach()
  list(JOIN _items ", " _itemstr)
  if(_rperc)
    string(APPEND _axlight "      ${_itemstr}: axi_light_needs = ${_mask};  // ${_rname}\n")
  else()
    string(APPEND _axglob "      ${_itemstr}: axi_global_needs = ${_mask};  // ${_rname}\n")
  endif()
  string(APPEND _axtab "    AxiRegNeeds{${_raddr}, ${_rcount}, ${_rperc}, ${_mask}},\n")
endforeach()
string(JSON _axwn GET "${_cfg_json}" light axi widths normal)
string(JSON _axwp GET "${_cfg_json}" light axi widths position)
string(JSON _axwc GET "${_cfg_json}" light axi widths colour)
string(JSON _axwf GET "${_cfg_json}" light axi widths flag)
set(_axvh_fields "")
set(_axhpp_fields "")
set(_ch_axi "")
foreach(_side s_axis m_axis)
  if(_side STREQUAL "s_axis")
    set(_pfx AXIS_IN)
  else()
    set(_pfx AXIS_OUT)
  endif()
  string(JSON _nf LENGTH "${_cfg_json}" light axi ${_side})
  math(EXPR _lastf "${_nf} - 1")
  set(_prev "")
  set(_tab "")
  foreach(i RANGE ${_lastf})
    string(JSON _fname GET "${_cfg_json}" light axi ${_side} ${i} name)
    string(JSON _fw GET "${_cfg_json}" light axi ${_side} ${i} width)
    string(JSON _fexpr GET "${_cfg_json}" light axi widths ${_fw})
    string(REPLACE "F" "FRAC" _fv "${_fexpr}")
    string(TOUPPER "${_fname}" _fup)
    if(_prev STREQUAL "")
      string(APPEND _axvh_fields "localparam integer ${_pfx}_${_fup}_LSB = 0;\n")
    else()
      string(APPEND _axvh_fields "localparam integer ${_pfx}_${_fup}_LSB = ${_pfx}_${_prev}_LSB + ${_pfx}_${_prev}_W;\n")
    endif()
    string(APPEND _axvh_fields "localparam integer ${_pfx}_${_fup}_W = ${_fv};\n")
    string(APPEND _axuse ", ${_pfx}_${_fup}_LSB[0], ${_pfx}_${_fup}_W[0]")
    string(APPEND _tab "    AxisField{\"${_fname}\", AxisWidth::${_fw}},\n")
    # the C driver header's macros: LSB and width as a + b*F (widths are "F+n" or "n")
    if(_fexpr MATCHES "^F\\+([0-9]+)$")
      set(_wb 1)
      set(_wa ${CMAKE_MATCH_1})
    elseif(_fexpr MATCHES "^([0-9]+)$")
      set(_wb 0)
      set(_wa ${CMAKE_MATCH_1})
    else()
      message(FATAL_ERROR "config/configs.json light.axi.widths: '${_fexpr}' is not F+n or n")
    endif()
    if(_prev STREQUAL "")
      set(_la 0)
      set(_lb 0)
    endif()
    string(APPEND _ch_axi "#define SC_LIGHT_${_pfx}_${_fup}_LSB(F) (${_la} + ${_lb} * (F))\n"
                          "#define SC_LIGHT_${_pfx}_${_fup}_BITS(F) (${_wa} + ${_wb} * (F))\n")
    math(EXPR _la "${_la} + ${_wa}")
    math(EXPR _lb "${_lb} + ${_wb}")
    set(_prev ${_fup})
  endforeach()
  string(APPEND _ch_axi "#define SC_LIGHT_${_pfx}_TDATA_BITS(F) (((${_la} + ${_lb} * (F)) + 7) / 8 * 8)\n")
  string(APPEND _axvh_fields "localparam integer ${_pfx}_BITS = ${_pfx}_${_prev}_LSB + ${_pfx}_${_prev}_W;\n"
                             "localparam integer ${_pfx}_TDATA = (${_pfx}_BITS + 7) / 8 * 8;  // padded to whole bytes\n")
  string(APPEND _axuse ", ${_pfx}_BITS[0], ${_pfx}_TDATA[0]")
  string(APPEND _axhpp_fields "inline constexpr std::array<AxisField, ${_nf}> k${_pfx}_fields{{\n${_tab}}};\n")
endforeach()
string(REPLACE "F" "f" _axcn "${_axwn}")
string(REPLACE "F" "f" _axcp "${_axwp}")
string(REPLACE "F" "f" _axcc "${_axwc}")
string(REPLACE "F" "f" _axcf "${_axwf}")
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_RTL_DIR}/sc_light_axi.vh" CONTENT
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json (light.axi, light.registers[].needs) by cmake/ShadecoreConfigs.cmake — do not edit
// The AXI view of the lighting core, included inside rtl/sc_light_axi.v (after FRAC): the capability bits a register
// needs (-1: no register at that address) and the AXI4-Stream packing (fields LSB first; TDATA padded to bytes).
${_axvh_need}localparam integer AXI_LIGHT_BASE = ${_axlight_base};  // slot 0's first per-light register; slot j at + LIGHT_STRIDE*j
function integer axi_global_needs(input [${_labits}-1:0] w);
  begin
    case (w)
${_axglob}      default: axi_global_needs = -1;
    endcase
  end
endfunction
function integer axi_light_needs(input integer off);  // off = address - AXI_LIGHT_BASE - LIGHT_STRIDE*j
  begin
    case (off)
${_axlight}      default: axi_light_needs = -1;
    endcase
  end
endfunction
${_axvh_fields}localparam [0:0] unused_light_axi = ^{1'b0, AXI_LIGHT_BASE[0]${_axuse}};
" @ONLY)
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_DIR}/shadecore/light_axi_map.hpp" CONTENT
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json (light.axi, light.registers[].needs) by cmake/ShadecoreConfigs.cmake — do not edit
// The AXI view of the lighting core (rtl/sc_light_axi.v): register presence and the AXI4-Stream packing.
#pragma once
#include <array>
#include <cstdint>
#include <string_view>
namespace shadecore {
${_axhpp_need}inline constexpr uint32_t kAxiLightBase = ${_axlight_base};
// a register of the map that is not reserved: its addresses exist when every capability bit of needs is built
struct AxiRegNeeds { uint32_t addr; int count; bool per_light; unsigned needs; };
inline constexpr AxiRegNeeds kAxiRegNeeds[] = {
${_axtab}};
enum class AxisWidth { normal, position, colour, flag };
constexpr int axis_width(AxisWidth w, int f) {
  return w == AxisWidth::normal ? ${_axcn} : w == AxisWidth::position ? ${_axcp} : w == AxisWidth::colour ? ${_axcc} : ${_axcf};
}
struct AxisField { std::string_view name; AxisWidth width; };
${_axhpp_fields}}  // namespace shadecore
" @ONLY)
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_DIR}/shadecore/configs_json.hpp" CONTENT
"// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
#pragma once
namespace shadecore {
inline constexpr const char* kConfigsJson = R\"shadecore_json(${_cfg_json})shadecore_json\";
}  // namespace shadecore
" @ONLY)

# The same register map for C drivers (issue 39, docs/driver.md):
#   ${SHADECORE_GENERATED_DIR}/shadecore/shadecore_light_regs.h   (plain C99: addresses, strides, the light_model bits,
#                                                                 light kinds, unit ids, register formats and mode-word
#                                                                 fields, the named configs and feature sets)
# from the entries above plus "light" formats / spec_guard_default, "limits" and "feature_sets". The driver routine
# driver/ (shadecore_light_driver) includes it; tests/light_driver_test.cpp checks it against the C++ model.
string(JSON _lsgd GET "${_cfg_json}" light spec_guard_default)
string(JSON _lfmin GET "${_cfg_json}" limits light_frac min)
string(JSON _lfmax GET "${_cfg_json}" limits light_frac max)
string(JSON _lsgmin GET "${_cfg_json}" limits spec_guard min)
string(JSON _lsgmax GET "${_cfg_json}" limits spec_guard max)
string(JSON _lufmax GET "${_cfg_json}" limits frac max)
math(EXPR _lnmin_expect "1 << ${_llnb}")
set(_ch "")
# (the light_model fields and the light kinds are written in their loops above: _ch_lm, _ch_kinds)
# specular units: the values of mat_unit; THR: units whose material has the θcr threshold (cs16 and its squarer forms)
set(_ch_units "")
set(_ch_known 0)
set(_ch_thr 0)
foreach(i RANGE ${_lastv})
  string(JSON _vname GET "${_cfg_json}" variants ${i} name)
  string(JSON _vid GET "${_cfg_json}" variants ${i} id)
  string(TOUPPER "${_vname}" _vupper)
  string(APPEND _ch_units "#define SC_LIGHT_UNIT_${_vupper} ${_vid}\n")
  math(EXPR _ch_known "${_ch_known} | (1 << ${_vid})")
  string(JSON _sq ERROR_VARIABLE _nosq GET "${_cfg_json}" variants ${i} squarer)
  if(_vname STREQUAL "cs16" OR NOT _nosq)
    math(EXPR _ch_thr "${_ch_thr} | (1 << ${_vid})")
  endif()
endforeach()
math(EXPR _ch_known "${_ch_known}" OUTPUT_FORMAT HEXADECIMAL)
math(EXPR _ch_thr "${_ch_thr}" OUTPUT_FORMAT HEXADECIMAL)
# register formats
set(_ch_fmt "")
string(JSON _nf LENGTH "${_cfg_json}" light formats)
math(EXPR _lastf "${_nf} - 1")
set(_fmt_names "")
foreach(i RANGE ${_lastf})
  string(JSON _fname MEMBER "${_cfg_json}" light formats ${i})
  if(_fname STREQUAL "_comment")
    continue()
  endif()
  list(APPEND _fmt_names "${_fname}")
  string(TOUPPER "${_fname}" _fup)
  string(JSON _ffrac ERROR_VARIABLE _nofrac GET "${_cfg_json}" light formats ${_fname} frac)
  if(NOT _nofrac)  # fixed point
    string(JSON _fint GET "${_cfg_json}" light formats ${_fname} int_bits)
    _shadecore_json_flag(_fsig light formats ${_fname} signed)
    if(_ffrac STREQUAL "F")
      set(_fexpr "(F)")
    elseif(_ffrac STREQUAL "UF")
      set(_fexpr "(UF)")
    else()
      message(FATAL_ERROR "config/configs.json: light.formats.${_fname}.frac must be \"F\" or \"UF\", not \"${_ffrac}\"")
    endif()
    if(_fsig)
      set(_fs 1)
    else()
      set(_fs 0)
    endif()
    math(EXPR _fextra "${_fint} + ${_fs}")
    string(APPEND _ch_fmt "#define SC_LIGHT_FMT_${_fup}_FRAC(F, UF) ${_fexpr}\n"
                          "#define SC_LIGHT_FMT_${_fup}_INT_BITS ${_fint}\n"
                          "#define SC_LIGHT_FMT_${_fup}_SIGNED ${_fs}\n"
                          "#define SC_LIGHT_FMT_${_fup}_BITS(F, UF) (${_fexpr} + ${_fextra})\n")
  else()  # integer
    string(JSON _fbits GET "${_cfg_json}" light formats ${_fname} bits)
    if(_fname STREQUAL "spot_exponent" AND NOT _fbits EQUAL _lspeb)
      message(FATAL_ERROR "config/configs.json: light.formats.spot_exponent.bits ${_fbits} != spot_exponent_bits ${_lspeb}")
    endif()
    if(_fname STREQUAL "light_model" AND NOT _fbits EQUAL _lmn)
      message(FATAL_ERROR "config/configs.json: light.formats.light_model.bits ${_fbits} != the ${_lmn} light_model_bits")
    endif()
    string(APPEND _ch_fmt "#define SC_LIGHT_FMT_${_fup}_BITS(F, UF) ${_fbits}\n#define SC_LIGHT_FMT_${_fup}_SIGNED 0\n")
    foreach(_b min max)
      string(JSON _bv ERROR_VARIABLE _nob GET "${_cfg_json}" light formats ${_fname} ${_b})
      if(NOT _nob)
        string(TOUPPER "${_b}" _bup)
        string(APPEND _ch_fmt "#define SC_LIGHT_FMT_${_fup}_${_bup} ${_bv}\n")
      endif()
    endforeach()
    if(_fname STREQUAL "n")
      string(JSON _nmin GET "${_cfg_json}" light formats n min)
      if(NOT _nmin EQUAL _lnmin_expect)
        message(FATAL_ERROR "config/configs.json: light.formats.n.min ${_nmin} != 2^low_shininess_bits = ${_lnmin_expect}")
      endif()
    endif()
    string(JSON _nfld ERROR_VARIABLE _nofld LENGTH "${_cfg_json}" light formats ${_fname} fields)
    if(NOT _nofld AND _nfld GREATER 0)
      math(EXPR _lastfld "${_nfld} - 1")
      foreach(k RANGE ${_lastfld})
        string(JSON _fldn GET "${_cfg_json}" light formats ${_fname} fields ${k} name)
        string(JSON _fldl GET "${_cfg_json}" light formats ${_fname} fields ${k} lsb)
        string(JSON _fldb GET "${_cfg_json}" light formats ${_fname} fields ${k} bits)
        string(TOUPPER "${_fldn}" _fldu)
        math(EXPR _fldm "((1 << ${_fldb}) - 1) << ${_fldl}" OUTPUT_FORMAT HEXADECIMAL)
        string(APPEND _ch_fmt "#define SC_LIGHT_${_fup}_${_fldu}_SHIFT ${_fldl}\n#define SC_LIGHT_${_fup}_${_fldu}_MASK ${_fldm}u\n")
      endforeach()
    endif()
    string(JSON _nval ERROR_VARIABLE _noval LENGTH "${_cfg_json}" light formats ${_fname} values)
    if(NOT _noval AND _nval GREATER 0)
      math(EXPR _lastval "${_nval} - 1")
      foreach(k RANGE ${_lastval})
        string(JSON _valn GET "${_cfg_json}" light formats ${_fname} values ${k} name)
        string(JSON _valv GET "${_cfg_json}" light formats ${_fname} values ${k} value)
        string(TOUPPER "${_valn}" _valu)
        string(APPEND _ch_fmt "#define SC_LIGHT_${_fup}_${_valu} ${_valv}\n")
      endforeach()
    endif()
  endif()
endforeach()
# every register's format has an entry in light.formats (the C lines were written in the register loop above)
foreach(_rf IN LISTS _reg_fmts)
  string(REPLACE "=" ";" _rf "${_rf}")
  list(GET _rf 0 _rname)
  list(GET _rf 1 _rfmt)
  if(NOT _rfmt IN_LIST _fmt_names)
    message(FATAL_ERROR "config/configs.json: light register ${_rname}: format '${_rfmt}' has no entry in light.formats")
  endif()
endforeach()
# named configs: F, and UF with the default spec_guard; LIGHT 0 where the lighting core does not take the width
set(_ch_cfgs "")
set(_ch_cfglist "")
foreach(i RANGE ${_last})
  string(JSON _name GET "${_cfg_json}" configs ${i} name)
  string(JSON _frac GET "${_cfg_json}" configs ${i} frac)
  string(MAKE_C_IDENTIFIER "${_name}" _cid)
  string(TOUPPER "${_cid}" _cup)
  math(EXPR _uf "${_frac} + ${_lsgd}")
  if(_frac GREATER_EQUAL _lfmin AND _frac LESS_EQUAL _lfmax)
    set(_lok 1)
  else()
    set(_lok 0)
  endif()
  string(APPEND _ch_cfglist " \\\n  X(${_name}, ${_cup})")
  string(APPEND _ch_cfgs "#define SC_LIGHT_CONFIG_${_cup}_FRAC ${_frac}\n"
                         "#define SC_LIGHT_CONFIG_${_cup}_UNIT_FRAC ${_uf}  /* F + SC_LIGHT_SPEC_GUARD_DEFAULT */\n"
                         "#define SC_LIGHT_CONFIG_${_cup}_LIGHT ${_lok}\n")
endforeach()
# named feature sets: what a driver needs of each (the defaults of a key left out are FeatureSet's in
# cmodel/include/shadecore/features.hpp; tests/light_driver_test.cpp checks every set against that parser)
set(_ch_flag_names ambient diffuse norm low_shininess local_viewer blinn phong normalize two_side separate_specular
    colour_material)
set(_ch_flags "")
set(_fbit 0)
foreach(_fl IN LISTS _ch_flag_names)
  string(TOUPPER "${_fl}" _flu)
  string(APPEND _ch_flags "#define SC_LIGHT_FEAT_${_flu} (1u << ${_fbit})\n")
  math(EXPR _fbit "${_fbit} + 1")
endforeach()
set(_ch_fs "")
set(_ch_fslist "")
string(JSON _nfs LENGTH "${_cfg_json}" feature_sets)
math(EXPR _lastfs "${_nfs} - 1")
function(_shadecore_fs_bool out i key default)
  string(JSON _v ERROR_VARIABLE _missing GET "${_cfg_json}" feature_sets ${i} ${key})
  if(_missing)
    set(${out} ${default} PARENT_SCOPE)
  elseif(_v)
    set(${out} 1 PARENT_SCOPE)
  else()
    set(${out} 0 PARENT_SCOPE)
  endif()
endfunction()
# _shadecore_fs_names(<out> <path...>): the string-or-list member at feature_sets <path...> as a list ("" when absent)
function(_shadecore_fs_names out)
  string(JSON _t ERROR_VARIABLE _missing TYPE "${_cfg_json}" feature_sets ${ARGN})
  set(_l "")
  if(_missing)
  elseif(_t STREQUAL "STRING")
    string(JSON _s GET "${_cfg_json}" feature_sets ${ARGN})
    list(APPEND _l "${_s}")
  else()
    string(JSON _n LENGTH "${_cfg_json}" feature_sets ${ARGN})
    if(_n GREATER 0)
      math(EXPR _ln "${_n} - 1")
      foreach(k RANGE ${_ln})
        string(JSON _s GET "${_cfg_json}" feature_sets ${ARGN} ${k})
        list(APPEND _l "${_s}")
      endforeach()
    endif()
  endif()
  set(${out} "${_l}" PARENT_SCOPE)
endfunction()
foreach(i RANGE ${_lastfs})
  string(JSON _fsname GET "${_cfg_json}" feature_sets ${i} name)
  string(MAKE_C_IDENTIFIER "${_fsname}" _fsid)
  string(TOUPPER "${_fsid}" _fsup)
  string(JSON _fscfg ERROR_VARIABLE _nocfg GET "${_cfg_json}" feature_sets ${i} config)
  if(_nocfg)
    set(_fscfg default)
  endif()
  if(NOT _fscfg IN_LIST SHADECORE_CONFIG_NAMES)
    message(FATAL_ERROR "config/configs.json: feature set ${_fsname}: unknown config '${_fscfg}'")
  endif()
  set(_fsfrac "${SHADECORE_CONFIG_${_fscfg}_FRAC}")
  string(JSON _fssg ERROR_VARIABLE _nosg GET "${_cfg_json}" feature_sets ${i} spec_guard)
  if(_nosg)
    set(_fssg ${_lsgd})
  endif()
  math(EXPR _fsuf "${_fsfrac} + ${_fssg}")
  # slots: 4 bits each (bit 4j + k: slot j can take kind id k)
  string(JSON _nsl LENGTH "${_cfg_json}" feature_sets ${i} lights)
  math(EXPR _lastsl "${_nsl} - 1")
  set(_slots 0)
  foreach(j RANGE ${_lastsl})
    _shadecore_fs_names(_kl ${i} lights ${j})
    foreach(_kn IN LISTS _kl)
      set(_kid "")
      foreach(k RANGE ${_lastk})
        string(JSON _kname GET "${_cfg_json}" light light_kinds ${k} name)
        if(_kname STREQUAL _kn)
          string(JSON _kid GET "${_cfg_json}" light light_kinds ${k} id)
        endif()
      endforeach()
      if(_kid STREQUAL "")
        message(FATAL_ERROR "config/configs.json: feature set ${_fsname}: unknown light kind '${_kn}'")
      endif()
      math(EXPR _slots "${_slots} | (1 << (4 * ${j} + ${_kid}))")
    endforeach()
  endforeach()
  math(EXPR _slots "${_slots}" OUTPUT_FORMAT HEXADECIMAL)
  # units: specular absent = cs16 (FeatureSet's default), "none" = no unit (the first unit stays cs16)
  _shadecore_fs_names(_ul ${i} specular)
  if(NOT _ul)
    set(_ul cs16)
  endif()
  set(_units 0)
  set(_first "${SHADECORE_VARIANT_cs16_ID}")
  set(_have_first FALSE)
  set(_fs_spec 1)
  foreach(_un IN LISTS _ul)
    if(_un STREQUAL "none")
      set(_fs_spec 0)
      continue()
    endif()
    if(NOT _un IN_LIST SHADECORE_VARIANT_NAMES)
      message(FATAL_ERROR "config/configs.json: feature set ${_fsname}: unknown specular unit '${_un}'")
    endif()
    math(EXPR _units "${_units} | (1 << ${SHADECORE_VARIANT_${_un}_ID})")
    if(NOT _have_first)
      set(_first "${SHADECORE_VARIANT_${_un}_ID}")
      set(_have_first TRUE)
    endif()
  endforeach()
  math(EXPR _units "${_units}" OUTPUT_FORMAT HEXADECIMAL)
  # reflection: absent = blinn
  _shadecore_fs_names(_rl ${i} reflection)
  if(NOT _rl)
    set(_rl blinn)
  endif()
  set(_fsv_blinn 0)
  set(_fsv_phong 0)
  if("blinn" IN_LIST _rl)
    set(_fsv_blinn 1)
  endif()
  if("phong" IN_LIST _rl)
    set(_fsv_phong 1)
  endif()
  _shadecore_fs_bool(_fsv_ambient ${i} ambient 1)
  _shadecore_fs_bool(_fsv_diffuse ${i} diffuse 1)
  _shadecore_fs_bool(_fsv_norm ${i} norm 0)
  _shadecore_fs_bool(_fsv_low_shininess ${i} low_shininess 0)
  _shadecore_fs_bool(_fsv_local_viewer ${i} local_viewer 0)
  _shadecore_fs_bool(_fsv_normalize ${i} normalize 1)
  _shadecore_fs_bool(_fsv_two_side ${i} two_side 0)
  _shadecore_fs_bool(_fsv_separate_specular ${i} separate_specular 0)
  _shadecore_fs_bool(_fsv_colour_material ${i} colour_material 0)
  set(_feat "")
  foreach(_fl IN LISTS _ch_flag_names)
    if(_fsv_${_fl})
      string(TOUPPER "${_fl}" _flu)
      list(APPEND _feat "SC_LIGHT_FEAT_${_flu}")
    endif()
  endforeach()
  list(JOIN _feat " | " _featstr)
  if(_featstr STREQUAL "")
    set(_featstr "0u")
  endif()
  string(APPEND _ch_fslist " \\\n  X(${_fsname}, ${_fsup})")
  string(APPEND _ch_fs "/* ${_fsname} */\n"
                       "#define SC_LIGHT_FS_${_fsup}_NAME \"${_fsname}\"\n"
                       "#define SC_LIGHT_FS_${_fsup}_CONFIG \"${_fscfg}\"\n"
                       "#define SC_LIGHT_FS_${_fsup}_FRAC ${_fsfrac}\n"
                       "#define SC_LIGHT_FS_${_fsup}_UNIT_FRAC ${_fsuf}\n"
                       "#define SC_LIGHT_FS_${_fsup}_LIGHTS ${_nsl}\n"
                       "#define SC_LIGHT_FS_${_fsup}_SLOT_KINDS ${_slots}u\n"
                       "#define SC_LIGHT_FS_${_fsup}_UNITS ${_units}u\n"
                       "#define SC_LIGHT_FS_${_fsup}_FIRST_UNIT ${_first}\n"
                       "#define SC_LIGHT_FS_${_fsup}_FEATURES (${_featstr})\n")
endforeach()
file(CONFIGURE OUTPUT "${SHADECORE_GENERATED_DIR}/shadecore/shadecore_light_regs.h" CONTENT
"/* SPDX-License-Identifier: Apache-2.0 */
/* generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit */
/* Register map of the lighting core rtl/sc_light.v for C drivers (docs/driver.md, docs/lighting.md §4): the same
 * entries as rtl/sc_light_regs.vh and shadecore/light_regs.hpp. Plain C99.
 *
 * The addresses are one map for every feature set and config: a register a core lacks ignores its write. What
 * depends on the core is the format of a word: F = the feature set's config frac (FRAC) and UF = F + its
 * spec_guard (SGUARD; the specular units' format). A fixed-point register holds round(value * 2^frac) in
 * SC_LIGHT_REG_<name>_BITS(F, UF) bits (two's complement where _SIGNED). A per-light register of light j is at
 * SC_LIGHT_REG_LIGHT(SC_LIGHT_REG_<name>, j); count consecutive addresses hold r, g, b or x, y, z. */
#ifndef SHADECORE_LIGHT_REGS_H
#define SHADECORE_LIGHT_REGS_H

#include <stdint.h>

#define SC_LIGHT_MAX_LIGHTS ${_lmax}
#define SC_LIGHT_STRIDE ${_lstride}u                /* address of light j's register = addr + stride * j */
#define SC_LIGHT_ADDR_BITS ${_labits}                /* width of reg_addr_i */
#define SC_LIGHT_SPOT_EXP_BITS ${_lspeb}             /* the spot exponent register's width */
#define SC_LIGHT_LOW_N_BITS ${_llnb}                 /* shininess below 2^this: the low-shininess chain (feature) */
#define SC_LIGHT_MODEL_BITS ${_lmn}                  /* stored bits of light_model */
#define SC_LIGHT_SPEC_GUARD_DEFAULT ${_lsgd}          /* a feature set's spec_guard when it names none */
#define SC_LIGHT_FRAC_MIN ${_lfmin}                  /* the lighting core's F (config frac) */
#define SC_LIGHT_FRAC_MAX ${_lfmax}
#define SC_LIGHT_SPEC_GUARD_MIN ${_lsgmin}
#define SC_LIGHT_SPEC_GUARD_MAX ${_lsgmax}
#define SC_LIGHT_UNIT_FRAC_MAX ${_lufmax}             /* F + spec_guard at most this */

#define SC_LIGHT_REG_LIGHT(reg, j) ((uint32_t)(reg) + (uint32_t)(j) * SC_LIGHT_STRIDE)
#define SC_LIGHT_MASK(bits) ((uint32_t)((((uint64_t)1) << (bits)) - 1u))

/* The AXI view (rtl/sc_light_axi.v; config/configs.json light.axi; docs/handoff.md \"AXI view\"): the AXI4-Lite byte
 * address of register address `word`; a write must carry WSTRB = 0xF; BRESP / RRESP SLVERR (2) where the core has
 * no such register. A fragment on AXI4-Stream (S) and a colour (M): each field at bits [LSB, LSB + BITS) of TDATA,
 * as functions of F; TUSER = the tag; TLAST travels with the fragment. */
#define SC_LIGHT_AXI_ADDR(word) ((uint32_t)(word) << 2)
#define SC_LIGHT_AXI_OKAY 0u
#define SC_LIGHT_AXI_SLVERR 2u
${_ch_axi}
/* light_model fields */
${_ch_lm}
/* light kinds (light_mode's kind field) */
${_ch_kinds}#define SC_LIGHT_NUM_KINDS ${_nk}

/* specular units: the values of mat_unit (config/configs.json variants) */
${_ch_units}#define SC_LIGHT_UNITS_KNOWN ${_ch_known}u
#define SC_LIGHT_UNITS_THR ${_ch_thr}u  /* units whose material has the threshold mat_thr (the others take 0) */

/* register formats: _FRAC(F, UF) fraction bits, _BITS(F, UF) the word's width; mode words' fields and values */
${_ch_fmt}
/* registers (SC_LIGHT_REG_LIST(X) expands X(name, NAME) for each) */
#define SC_LIGHT_REG_LIST(X)${_ch_reglist}
${_ch_regs}
/* named configs (config/configs.json configs): F, UF with the default spec_guard, LIGHT 1 where the lighting
 * core takes the width (SC_LIGHT_FRAC_MIN..SC_LIGHT_FRAC_MAX); SC_LIGHT_CONFIG_LIST(X) expands X(name, NAME) for each */
#define SC_LIGHT_CONFIG_LIST(X)${_ch_cfglist}
${_ch_cfgs}
/* feature flags of a core (config/configs.json feature_sets keys) */
${_ch_flags}
/* named feature sets (config/configs.json feature_sets): F, UF, slots (LIGHTS; SLOT_KINDS: bit 4j + k set = slot j
 * can take kind k), UNITS (bit v set: unit v is in the core; 0: no specular), FIRST_UNIT (the unit a material
 * without its own selects), FEATURES (SC_LIGHT_FEAT_*). SC_LIGHT_FS_LIST(X) expands X(name, NAME) for each. */
#define SC_LIGHT_FS_LIST(X)${_ch_fslist}
${_ch_fs}
#endif /* SHADECORE_LIGHT_REGS_H */
" @ONLY)

# RTL file lists (config/configs.json "rtl" and variants[].rtl; the one source, issue 20). Sets
#   SHADECORE_RTL_SOURCES            sc_specular with every unit and sc_energy (absolute paths)
#   SHADECORE_LIGHT_SOURCES          sc_light with every operator and SHADECORE_RTL_SOURCES
#   SHADECORE_RTL_FILES_<module>     what <module> needs as a top on its own ("standalone", else <module>.v)
#   SHADECORE_VARIANT_<name>_RTL     a unit's files
# The CLI reads the same entries at run time (common/src/rtl_files.cpp, through shadecore/configs_json.hpp).
function(_shadecore_json_list out)
  string(JSON _t TYPE "${_cfg_json}" ${ARGN})
  if(NOT _t STREQUAL "ARRAY")
    message(FATAL_ERROR "config/configs.json: ${ARGN} must be a list of file names")
  endif()
  string(JSON _len LENGTH "${_cfg_json}" ${ARGN})
  set(_l "")
  if(_len GREATER 0)
    math(EXPR _lst "${_len} - 1")
    foreach(k RANGE ${_lst})
      string(JSON _f GET "${_cfg_json}" ${ARGN} ${k})
      if(NOT EXISTS "${CMAKE_SOURCE_DIR}/rtl/${_f}")
        message(FATAL_ERROR "config/configs.json: ${ARGN}: rtl/${_f} does not exist")
      endif()
      list(APPEND _l "${CMAKE_SOURCE_DIR}/rtl/${_f}")
    endforeach()
  endif()
  set(${out} "${_l}" PARENT_SCOPE)
endfunction()
_shadecore_json_list(SHADECORE_RTL_SOURCES rtl sc_specular files)
foreach(i RANGE ${_lastv})
  string(JSON _vname GET "${_cfg_json}" variants ${i} name)
  _shadecore_json_list(SHADECORE_VARIANT_${_vname}_RTL variants ${i} rtl)
  list(APPEND SHADECORE_RTL_SOURCES ${SHADECORE_VARIANT_${_vname}_RTL})
endforeach()
_shadecore_json_list(_norm rtl sc_specular energy)
list(APPEND SHADECORE_RTL_SOURCES ${_norm})
list(REMOVE_DUPLICATES SHADECORE_RTL_SOURCES)
_shadecore_json_list(SHADECORE_LIGHT_SOURCES rtl sc_light files)
foreach(_cap normalize recip)
  _shadecore_json_list(_capf rtl sc_light ${_cap})
  list(APPEND SHADECORE_LIGHT_SOURCES ${_capf})
endforeach()
list(APPEND SHADECORE_LIGHT_SOURCES ${SHADECORE_RTL_SOURCES})
list(REMOVE_DUPLICATES SHADECORE_LIGHT_SOURCES)
foreach(_src IN LISTS SHADECORE_LIGHT_SOURCES)
  get_filename_component(_mod "${_src}" NAME_WE)
  string(JSON _sa ERROR_VARIABLE _nosa GET "${_cfg_json}" rtl standalone ${_mod})
  if(_nosa)
    set(SHADECORE_RTL_FILES_${_mod} "${_src}")
  else()
    _shadecore_json_list(SHADECORE_RTL_FILES_${_mod} rtl standalone ${_mod})
  endif()
endforeach()
set(SHADECORE_RTL_FILES_sc_specular ${SHADECORE_RTL_SOURCES})
set(SHADECORE_RTL_FILES_sc_light ${SHADECORE_LIGHT_SOURCES})
_shadecore_json_list(SHADECORE_LIGHT_AXI_SOURCES rtl sc_light_axi files)   # the AXI wrapper (issue 39), then the core's
list(APPEND SHADECORE_LIGHT_AXI_SOURCES ${SHADECORE_LIGHT_SOURCES})
set(SHADECORE_RTL_FILES_sc_light_axi ${SHADECORE_LIGHT_AXI_SOURCES})

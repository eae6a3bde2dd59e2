# SPDX-License-Identifier: Apache-2.0
# The coverage build's parameterisation map (docs/coverage.md "Parameterisations"), for sim/unit_core and
# sim/light_core: Verilator names each parameterisation of a module <module>__<abbreviated values> or <module>__piN,
# numbered per build, in the coverage points' pages. `verilator --xml-only` of the same top, sources and flags
# writes every module's Verilated name, original name and parameter values to <build>/verilated_params.xml; the CLI
# reads it (cli/coverage.cpp) to rename each point's module into the canonical <module>__{NAME=VALUE,...} before
# databases are merged. Defines the target shadecore_cov_params.
#
#   shadecore_cov_params(TOP <module> RTL <rtl dir> ARGS <verilator -G/-I flags...> SOURCES <files...>)
function(shadecore_cov_params)
  cmake_parse_arguments(P "" "TOP;RTL" "ARGS;SOURCES" ${ARGN})
  file(GLOB _rtl_all ${P_RTL}/*.v ${P_RTL}/*.vh)
  add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/verilated_params.xml
    COMMAND ${VERILATOR_BIN} --xml-only --xml-output ${CMAKE_BINARY_DIR}/verilated_params.xml
            --Mdir ${CMAKE_BINARY_DIR}/verilated_params.dir --top ${P_TOP} ${P_ARGS}
            ${P_RTL}/lint/verilator_waiver.vlt ${P_SOURCES}
    DEPENDS ${_rtl_all} ${P_RTL}/lint/verilator_waiver.vlt
    COMMENT "verilator --xml-only: the parameterisation map of the coverage build"
    VERBATIM)
  add_custom_target(shadecore_cov_params DEPENDS ${CMAKE_BINARY_DIR}/verilated_params.xml)
endfunction()

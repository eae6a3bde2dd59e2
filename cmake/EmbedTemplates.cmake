# SPDX-License-Identifier: Apache-2.0
# Build-time step (cmake -P): compiles text templates into a C++ source, so the CLI needs no template file
# at run time (cli/templates.hpp). The first line of every template is its licence line (SPDX, in the
# file's own comment syntax) and is not part of the text; the rest is embedded byte for byte.
#
#   cmake -DOUTPUT=out.cpp -DBASE=dir -DTEMPLATES="a.md;b.sdc" -P cmake/EmbedTemplates.cmake
#
# Each template is looked up by its path relative to BASE (e.g. "handoff/interface.md").
if(NOT OUTPUT OR NOT BASE OR NOT TEMPLATES)
  message(FATAL_ERROR "EmbedTemplates.cmake needs OUTPUT, BASE and TEMPLATES")
endif()
set(_arrays "")
set(_table "")
set(_i 0)
foreach(_t IN LISTS TEMPLATES)
  file(RELATIVE_PATH _name "${BASE}" "${_t}")
  file(READ "${_t}" _text)
  string(FIND "${_text}" "\n" _nl)
  if(_nl LESS 0)
    message(FATAL_ERROR "${_t}: a template needs its SPDX line and a text after it")
  endif()
  string(SUBSTRING "${_text}" 0 ${_nl} _first)
  if(NOT _first MATCHES "SPDX-License-Identifier: Apache-2.0")
    message(FATAL_ERROR "${_t}: the first line must be the SPDX line")
  endif()
  math(EXPR _off "${_nl} + 1")
  file(READ "${_t}" _hex OFFSET ${_off} HEX)
  string(LENGTH "${_hex}" _hl)
  math(EXPR _len "${_hl} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1'," _bytes "${_hex}")
  string(APPEND _arrays "// ${_name}\nconst char k${_i}[] = {\n  ${_bytes}'\\0'};\n")
  string(APPEND _table "    {\"${_name}\", std::string_view(k${_i}, ${_len})},\n")
  math(EXPR _i "${_i} + 1")
endforeach()
set(_src "// SPDX-License-Identifier: Apache-2.0
// generated from cli/templates/ by cmake/EmbedTemplates.cmake — do not edit
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace shadecore::cli {
namespace {
${_arrays}
const std::pair<std::string_view, std::string_view> kTemplates[] = {
${_table}};
}  // namespace

std::string_view template_text(std::string_view name) {
  for (const auto& [n, text] : kTemplates)
    if (n == name) return text;
  throw std::logic_error(\"internal: no template '\" + std::string(name) + \"' compiled in (cli/templates/)\");
}

}  // namespace shadecore::cli
")
# Rewritten only when it changes, so an unchanged template rebuilds nothing.
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" _old)
  if(_old STREQUAL _src)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${_src}")

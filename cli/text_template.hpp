// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — text templates: the fixed text of files a command writes (cli/templates/, compiled in at
// build time by cmake/EmbedTemplates.cmake, so nothing is read at run time), with ${name} where a value
// goes. fill_template() puts every value in; a ${name} without a value, or a value that no ${name} asks
// for, is an internal error, so a template and the code that fills it cannot drift apart silently.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace shadecore::cli {

using TemplateValues = std::map<std::string, std::string, std::less<>>;

// The text of a template by its path under cli/templates/ (e.g. "handoff/interface.md"), without its
// licence line. Throws std::logic_error for a name that is not compiled in.
std::string_view template_text(std::string_view name);

// The template `name` with every ${key} replaced by values.at(key) (values are not scanned again).
std::string fill_template(std::string_view name, const TemplateValues& values);

}  // namespace shadecore::cli

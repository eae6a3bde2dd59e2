// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — filling the text templates (cli/text_template.hpp).
#include "text_template.hpp"

#include <set>
#include <stdexcept>

namespace shadecore::cli {

std::string fill_template(std::string_view name, const TemplateValues& values) {
  const std::string_view text = template_text(name);
  const auto fail = [&](const std::string& what) {
    return std::logic_error("internal: template " + std::string(name) + ": " + what);
  };
  std::string out;
  out.reserve(text.size() * 2);
  std::set<std::string_view> used;
  size_t at = 0;
  for (size_t open; (open = text.find("${", at)) != std::string_view::npos;) {
    const size_t close = text.find('}', open + 2);
    if (close == std::string_view::npos) throw fail("unterminated ${");
    const std::string_view key = text.substr(open + 2, close - open - 2);
    const auto it = values.find(key);
    if (it == values.end()) throw fail("no value for ${" + std::string(key) + "}");
    used.insert(it->first);
    out.append(text, at, open - at);
    out += it->second;
    at = close + 1;
  }
  out.append(text, at, std::string_view::npos);
  for (const auto& [key, value] : values)
    if (!used.count(key)) throw fail("value '" + key + "' is not used");
  return out;
}

}  // namespace shadecore::cli

// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — coverage databases, their merge, summary, waivers and HTML, and the unit's coverage build
// (cli/coverage.hpp; docs/coverage.md).
#include "coverage.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <functional>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include <fmt/core.h>

#include "handoff_bundle.hpp"
#include "output.hpp"
#include "shadecore/common/rtl_files.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/unit.hpp"

namespace shadecore::cli::coverage {
namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

std::string verilator_coverage() {
#ifdef SHADECORE_VERILATOR_COVERAGE
  if (::access(SHADECORE_VERILATOR_COVERAGE, X_OK) == 0) return SHADECORE_VERILATOR_COVERAGE;
#endif
  if (handoff::on_path("verilator_coverage")) return "verilator_coverage";
  throw std::runtime_error("verilator_coverage not found (Debian package verilator; scripts/setup.sh)");
}

// Runs a tool; throws with its last line when it fails.
void run_tool(const std::vector<std::string>& argv, const std::string& what) {
  handoff::Proc p = handoff::run_proc(argv, fs::current_path());
  if (p.status != 0) {
    std::string last;
    std::stringstream ss(p.out);
    for (std::string l; std::getline(ss, l);)
      if (l.find_first_not_of(" \t\r") != std::string::npos) last = l;
    throw std::runtime_error(fmt::format("{} failed (exit {}){}", what, p.status, last.empty() ? "" : ": " + last));
  }
}

std::string tmp_name(const std::string& p) { return p + fmt::format(".tmp.{}", ::getpid()); }

// '*' any run of characters, '?' one; everything else literal (signal names carry [] and .).
bool glob(const std::string& pat, const std::string& s) {
  size_t p = 0, i = 0, star = std::string::npos, mark = 0;
  while (i < s.size()) {
    if (p < pat.size() && (pat[p] == '?' || pat[p] == s[i])) {
      ++p, ++i;
    } else if (p < pat.size() && pat[p] == '*') {
      star = p++, mark = i;
    } else if (star != std::string::npos) {
      p = star + 1, i = ++mark;
    } else {
      return false;
    }
  }
  while (p < pat.size() && pat[p] == '*') ++p;
  return p == pat.size();
}

// Source lines of the RTL files the points name (read once each), and the Verilog function each line is in.
class Sources {
 public:
  const std::string& line(const std::string& file, int n) {
    const File& f = load(file);
    static const std::string none;
    return n >= 1 && static_cast<size_t>(n) <= f.lines.size() ? f.lines[static_cast<size_t>(n - 1)] : none;
  }
  // The name of the `function ... endfunction` around line n ("" outside every function).
  const std::string& function_at(const std::string& file, int n) {
    const File& f = load(file);
    static const std::string none;
    return n >= 1 && static_cast<size_t>(n) <= f.func.size() ? f.func[static_cast<size_t>(n - 1)] : none;
  }

 private:
  struct File {
    std::vector<std::string> lines, func;
  };
  const File& load(const std::string& file) {
    auto it = files_.find(file);
    if (it != files_.end()) return it->second;
    File f;
    std::ifstream in(file);
    static const std::regex open(R"(^\s*(?:automatic\s+)?function\b(?:\s+(?:automatic|signed|integer|real|\[[^\]]*\]))*\s+(\w+))");
    static const std::regex close(R"(\bendfunction\b)");
    std::string cur;
    for (std::string l; std::getline(in, l);) {
      std::smatch m;
      if (cur.empty() && std::regex_search(l, m, open)) cur = m[1];
      f.lines.push_back(l);
      f.func.push_back(cur);
      if (std::regex_search(l, close)) cur.clear();
    }
    return files_.emplace(file, std::move(f)).first->second;
  }
  std::map<std::string, File> files_;
};

// Every NAME=VALUE of the waiver is the point's (a point of unknown parameterisation matches no params waiver).
bool params_match(const Waiver& w, const Point& p) {
  if (w.params.empty()) return true;
  if (!p.params_known) return false;
  for (const auto& [k, v] : w.params) {
    const auto it = std::lower_bound(p.params.begin(), p.params.end(), std::make_pair(k, std::string()));
    if (it == p.params.end() || it->first != k || it->second != v) return false;
  }
  return true;
}

bool matches(const Waiver& w, const Point& p, Sources& src) {
  if (!glob(w.module, p.module) || w.kind != p.kind) return false;
  if (!params_match(w, p)) return false;
  if (!w.file.empty() && !glob(w.file, fs::path(p.file).filename().string())) return false;
  if (!w.hier.empty() && !glob(w.hier, p.hier)) return false;
  if (!w.comment.empty() && w.comment != p.comment) return false;
  if (!w.signal.empty() && !glob(w.signal, p.comment)) return false;
  if (!w.source.empty() && src.line(p.file, p.line).find(w.source) == std::string::npos) return false;
  if (!w.function.empty()) {
    const std::string& fn = src.function_at(p.file, p.line);
    if (fn.empty() || !glob(w.function, fn)) return false;
  }
  return true;
}

std::string describe(const Point& p) {
  const std::string where = p.file.empty() ? "" : fmt::format("{}:{} ", fs::path(p.file).filename().string(), p.line);
  if (p.kind == "toggle") return fmt::format("toggle {} ({}{})", p.comment, where, p.hier);
  if (p.kind == "functional") return fmt::format("bin {}", p.comment);
  return fmt::format("{} {}{} ({})", p.kind, where, p.comment, p.hier);
}

const std::vector<std::string>& kinds() {
  static const std::vector<std::string> k = {"line", "branch", "toggle", "functional"};
  return k;
}

// ------------------------------------------------------------------------------------ parameterisations
// A parameter value's text in canonical form: chars outside [A-Za-z0-9_.+-] %-escaped (the page is a field of the
// database's key: no quote, no \001/\002, and no ',', '=', '{', '}' of the canonical name).
std::string escape_value(const std::string& v) {
  std::string out;
  for (unsigned char c : v) {
    if (std::isalnum(c) || c == '_' || c == '.' || c == '+' || c == '-') out += static_cast<char>(c);
    else out += fmt::format("%{:02X}", c);
  }
  return out.empty() ? "%" : out;
}

// Verilator's constant (XML: 32'sh4, 64'h4030201, 1'b1) as a decimal number when it fits 64 bits (negative when
// marked signed with its top bit set); any other value (wider, X/Z, a string, a real) as its escaped text.
std::string canonical_value(const std::string& v) {
  static const std::regex num(R"(^(\d+)'(s?)([hdbo])([0-9a-fA-F_]+)$)");
  std::smatch m;
  if (std::regex_match(v, m, num)) {
    const int width = std::atoi(m[1].str().c_str());
    const int base = m[3] == "h" ? 16 : m[3] == "d" ? 10 : m[3] == "o" ? 8 : 2;
    bool ok = width >= 1 && width <= 64;
    uint64_t x = 0;
    for (char c : m[4].str()) {
      if (c == '_') continue;
      const int d = std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : std::tolower(c) - 'a' + 10;
      if (d >= base || x > (UINT64_MAX - static_cast<uint64_t>(d)) / static_cast<uint64_t>(base)) {
        ok = false;
        break;
      }
      x = x * static_cast<uint64_t>(base) + static_cast<uint64_t>(d);
    }
    if (ok && (width == 64 || (x >> width) == 0)) {
      if (m[2] == "s" && ((x >> (width - 1)) & 1)) {
        const int64_t neg = width == 64 ? static_cast<int64_t>(x) : static_cast<int64_t>(x) - (int64_t{1} << width);
        return std::to_string(neg);
      }
      return std::to_string(x);
    }
  }
  return escape_value(v);
}

std::string xml_unescape(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    static const std::pair<const char*, char> ents[] = {{"&apos;", '\''}, {"&quot;", '"'}, {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}};
    bool done = false;
    for (const auto& [e, c] : ents)
      if (s.compare(i, std::strlen(e), e) == 0) {
        out += c;
        i += std::strlen(e) - 1;
        done = true;
        break;
      }
    if (!done) out += s[i];
  }
  return out;
}

// attribute `name` of a tag's text ("" when absent)
std::string xml_attr(const std::string& tag, const char* name) {
  const std::string key = std::string(" ") + name + "=\"";
  const size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const size_t from = at + key.size(), to = tag.find('"', from);
  return xml_unescape(tag.substr(from, to == std::string::npos ? std::string::npos : to - from));
}

// The map from `verilator --xml-only` output: <module name origName> ... <var name param="true"> <const name=VALUE/>
// </var> ... </module>, and <cell name submodname/> in <cells>.
ParamsMap parse_params_xml(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the parameterisation map " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string x = ss.str();
  if (x.find("<verilator_xml") == std::string::npos)
    throw std::runtime_error(path + " is not Verilator's XML output (no <verilator_xml>)");
  ParamsMap map;
  map.source = path;
  ParamsMap::Module* cur = nullptr;
  std::string pending;  // a parameter whose <const> comes next
  std::map<std::string, std::set<std::string>> inst;
  for (size_t lt = x.find('<'); lt != std::string::npos; lt = x.find('<', lt + 1)) {
    const size_t gt = x.find('>', lt);
    if (gt == std::string::npos) break;
    const std::string tag = x.substr(lt + 1, gt - lt - 1);
    if (tag.rfind("module ", 0) == 0) {
      const std::string name = xml_attr(tag, "name"), orig = xml_attr(tag, "origName");
      cur = &map.modules[name];
      cur->module = orig.empty() ? name : orig;
      if (xml_attr(tag, "topModule") == "1") inst[name].insert(name);
    } else if (tag == "/module") {
      if (!pending.empty()) throw std::runtime_error(fmt::format("{}: parameter {} has no value", path, pending));
      cur = nullptr;
    } else if (cur && tag.rfind("var ", 0) == 0 && xml_attr(tag, "param") == "true") {
      if (!pending.empty()) throw std::runtime_error(fmt::format("{}: parameter {} has no value", path, pending));
      pending = xml_attr(tag, "name");
      if (tag.back() == '/') throw std::runtime_error(fmt::format("{}: parameter {} has no value", path, pending));
    } else if (cur && !pending.empty() && tag.rfind("const ", 0) == 0) {
      cur->params.emplace_back(pending, canonical_value(xml_attr(tag, "name")));
      pending.clear();
    } else if (cur && !pending.empty() && tag == "/var") {
      throw std::runtime_error(fmt::format("{}: parameter {} of {} has no constant value", path, pending, cur->module));
    } else if (tag.rfind("cell ", 0) == 0) {
      inst[xml_attr(tag, "submodname")].insert(xml_attr(tag, "name"));
    }
  }
  if (map.modules.empty()) throw std::runtime_error(path + ": no module in it");
  for (auto& [name, m] : map.modules) {
    std::sort(m.params.begin(), m.params.end());
    m.instances = inst[name];
  }
  return map;
}

ParamsMap read_params_json(const std::string& path) {
  std::ifstream in(path);
  ojson j;
  try {
    j = ojson::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": not a parameterisation map (" + std::string(e.what()) + ")");
  }
  ParamsMap map;
  map.source = path;
  if (!j.is_object() || !j.contains("modules") || !j["modules"].is_object()) throw std::runtime_error(path + ": no \"modules\"");
  for (const auto& [name, m] : j["modules"].items()) {
    ParamsMap::Module& d = map.modules[name];
    d.module = m.value("module", name);
    for (const auto& [k, v] : m["params"].items()) d.params.emplace_back(k, v.get<std::string>());
    std::sort(d.params.begin(), d.params.end());
    for (const auto& i : m["instances"]) d.instances.insert(i.get<std::string>());
  }
  return map;
}

void write_params_json(const ParamsMap& map, const std::string& path) {
  ojson mods = ojson::object();
  for (const auto& [name, m] : map.modules) {
    ojson ps = ojson::object();
    for (const auto& [k, v] : m.params) ps[k] = v;
    mods[name] = {{"module", m.module}, {"canonical", canonical_name(m.module, m.params)}, {"params", ps},
                  {"instances", ojson(std::vector<std::string>(m.instances.begin(), m.instances.end()))}};
  }
  const ojson j = {{"description", "the parameterisation map of this coverage build (docs/coverage.md): Verilated module "
                                   "name -> RTL module, parameter values, instance names; made by shadecore from "
                                   "verilated_params.xml (verilator --xml-only of the build's top, sources and flags)"},
                   {"source", fs::path(map.source).filename().string()},
                   {"modules", mods}};
  write_file_atomic(path, j.dump(1) + "\n");
}

// The positions of a key's field `name`'s value: [from, to) in the key; npos when absent.
std::pair<size_t, size_t> key_field(const std::string& key, const std::string& name) {
  const std::string tag = "\001" + name + "\002";
  const size_t at = key.find(tag);
  if (at == std::string::npos) return {std::string::npos, std::string::npos};
  const size_t from = at + tag.size(), to = key.find('\001', from);
  return {from, to == std::string::npos ? key.size() : to};
}

bool canonical_page_module(const std::string& name) {
  const size_t dd = name.find("__{");
  return dd != std::string::npos && name.back() == '}';
}

size_t canonicalise_impl(const std::string& in_path, const std::function<const ParamsMap&()>& get_map, const std::string& out) {
  std::ifstream in(in_path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the coverage database " + in_path);
  std::string line, text;
  if (!std::getline(in, line) || line.rfind("# SystemC::Coverage", 0) != 0)
    throw std::runtime_error(in_path + " is not a Verilator coverage database (no '# SystemC::Coverage' header)");
  text = line + "\n";
  size_t renamed = 0;
  for (size_t no = 2; std::getline(in, line); ++no) {
    const size_t q1 = line.find('\''), q2 = line.rfind('\'');
    if (line.rfind("C '", 0) != 0 || q2 <= q1) {
      text += line + "\n";
      continue;
    }
    std::string key = line.substr(q1 + 1, q2 - q1 - 1);
    const auto [pf, pt] = key_field(key, "page");
    if (pf == std::string::npos) {
      text += line + "\n";
      continue;
    }
    const std::string page = key.substr(pf, pt - pf);
    const size_t slash = page.find('/');
    const std::string type = page.substr(0, slash), name = slash == std::string::npos ? "" : page.substr(slash + 1);
    if (slash == std::string::npos || type == "v_func" || canonical_page_module(name)) {
      text += line + "\n";
      continue;
    }
    const ParamsMap& map = get_map();
    const auto it = map.modules.find(name);
    if (it == map.modules.end())
      throw std::runtime_error(fmt::format("{}:{}: module {} is not in the parameterisation map {} (a database of another build?)",
                                           in_path, no, name, map.source));
    const auto [hf, ht] = key_field(key, "h");
    if (hf != std::string::npos && !it->second.instances.empty()) {
      std::string leaf = key.substr(hf, ht - hf);
      if (const size_t dot = leaf.rfind('.'); dot != std::string::npos) leaf = leaf.substr(dot + 1);
      // A point Verilator merged over instances of different paths ends in a wildcard, e.g. "...u_shade.g_ch[*"
      // (a generate loop's index): no single instance to check. Looked for before the index is cut off.
      const bool wildcard = leaf.find('*') != std::string::npos;
      if (const size_t br = leaf.find('['); br != std::string::npos) leaf.resize(br);
      if (!wildcard && !leaf.empty() && !it->second.instances.count(leaf))
        throw std::runtime_error(fmt::format("{}:{}: the parameterisation map {} has no instance {} of {} (a database of another "
                                             "build?)", in_path, no, map.source, leaf, name));
    }
    key.replace(pf, pt - pf, type + "/" + canonical_name(it->second.module, it->second.params));
    ++renamed;
    text += "C '" + key + "'" + line.substr(q2 + 1) + "\n";
  }
  if (renamed == 0 && out == in_path) return 0;
  write_file_atomic(out, text);
  return renamed;
}

}  // namespace

std::string canonical_name(const std::string& module, const std::vector<std::pair<std::string, std::string>>& params) {
  std::string s = module + "__{";
  for (size_t i = 0; i < params.size(); ++i) s += (i ? "," : "") + params[i].first + "=" + params[i].second;
  return s + "}";
}

ParamsMap load_params_map(const std::string& arg) {
  std::error_code ec;
  if (fs::is_directory(arg, ec)) {
    const fs::path xml = fs::path(arg) / "verilated_params.xml", js = fs::path(arg) / "params.json";
    if (fs::exists(xml, ec)) {
      if (fs::exists(js, ec) && fs::last_write_time(js, ec) >= fs::last_write_time(xml, ec)) {
        try {
          return read_params_json(js.string());
        } catch (const std::exception&) {
          // remade below
        }
      }
      ParamsMap m = parse_params_xml(xml.string());
      try {
        write_params_json(m, js.string());
      } catch (const std::exception&) {
        // a build directory one cannot write to: the map is still good
      }
      return m;
    }
    if (fs::exists(js, ec)) return read_params_json(js.string());
    throw std::runtime_error(fmt::format("{} has no parameterisation map (verilated_params.xml: a coverage build made before "
                                         "parameterisations were recorded; any coverage run rebuilds it)", arg));
  }
  if (!fs::exists(arg, ec)) throw std::runtime_error("no parameterisation map at " + arg);
  return fs::path(arg).extension() == ".json" ? read_params_json(arg) : parse_params_xml(arg);
}

size_t canonicalise(const std::string& in, const ParamsMap& map, const std::string& out) {
  return canonicalise_impl(in, [&map]() -> const ParamsMap& { return map; }, out);
}

void canonicalise_from_build(const std::string& dat, const std::string& build_dir) {
  std::optional<ParamsMap> map;
  canonicalise_impl(dat, [&]() -> const ParamsMap& {
    if (!map) map = load_params_map(build_dir);
    return *map;
  }, dat);
}

std::vector<Point> read_dat(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the coverage database " + path);
  std::string line;
  if (!std::getline(in, line) || line.rfind("# SystemC::Coverage", 0) != 0)
    throw std::runtime_error(path + " is not a Verilator coverage database (no '# SystemC::Coverage' header)");
  std::vector<Point> pts;
  for (size_t no = 2; std::getline(in, line); ++no) {
    if (line.empty() || line[0] == '#') continue;
    const size_t q1 = line.find('\''), q2 = line.rfind('\'');
    if (line.rfind("C '", 0) != 0 || q2 <= q1) throw std::runtime_error(fmt::format("{}:{}: not a coverage point", path, no));
    Point p;
    p.key = line.substr(q1 + 1, q2 - q1 - 1);
    try {
      p.count = std::stoull(line.substr(q2 + 1));
    } catch (const std::exception&) {
      throw std::runtime_error(fmt::format("{}:{}: no count", path, no));
    }
    // \001key\002value...
    std::map<std::string, std::string> kv;
    for (size_t at = 0; (at = p.key.find('\001', at)) != std::string::npos;) {
      const size_t sep = p.key.find('\002', at);
      const size_t next = p.key.find('\001', at + 1);
      if (sep == std::string::npos || (next != std::string::npos && sep > next))
        throw std::runtime_error(fmt::format("{}:{}: malformed key", path, no));
      kv[p.key.substr(at + 1, sep - at - 1)] = p.key.substr(sep + 1, (next == std::string::npos ? p.key.size() : next) - sep - 1);
      at = sep;
    }
    const std::string page = kv["page"];
    const size_t slash = page.find('/');
    const std::string type = page.substr(0, slash);
    p.module = slash == std::string::npos ? "" : page.substr(slash + 1);
    // Verilator names a parameterisation <module>__<params> (sc_cs16__F10_G5_T20): the summary is per RTL module,
    // every parameterisation's points counted (they are distinct logic), the full name kept in `variant`.
    if (const size_t dd = p.module.find("__"); dd != std::string::npos && type != "v_func") {
      p.variant = p.module.substr(dd + 2);
      p.module.resize(dd);
      // canonical: {NAME=VALUE,...} (canonicalise); Verilator's own suffixes say no values
      if (p.variant.size() >= 2 && p.variant.front() == '{' && p.variant.back() == '}') {
        p.params_known = true;
        const std::string body = p.variant.substr(1, p.variant.size() - 2);
        for (size_t at = 0; at < body.size();) {
          size_t end = body.find(',', at);
          if (end == std::string::npos) end = body.size();
          const std::string kv = body.substr(at, end - at);
          const size_t eq = kv.find('=');
          if (eq == std::string::npos) throw std::runtime_error(fmt::format("{}:{}: malformed parameterisation {}", path, no, p.variant));
          p.params.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
          at = end + 1;
        }
        std::sort(p.params.begin(), p.params.end());
      }
    }
    if (type == "v_line") p.kind = "line";
    else if (type == "v_branch") p.kind = "branch";
    else if (type == "v_toggle") p.kind = "toggle";
    else if (type == "v_func") p.kind = "functional";
    else p.kind = type;  // v_user (cover property) and anything newer: counted under its own name
    p.file = p.kind == "functional" ? "" : kv["f"];
    p.line = kv.count("l") ? std::atoi(kv["l"].c_str()) : 0;
    p.comment = kv["o"];
    // The harness's top (SystemC: the instance "dut"; bare: Verilator's "TOP") is not the design's: a point is the
    // same whichever harness ran it, so the summary counts it once (identity without it, counts summed).
    p.hier = kv["h"];
    if (const size_t dot = p.hier.find('.'); dot != std::string::npos) p.hier = p.hier.substr(dot + 1);
    p.id = p.kind + '\001' + p.module + '\001' + p.variant + '\001' + p.file + '\001' + kv["l"] + '\001' + kv["n"] + '\001' +
           kv["S"] + '\001' + p.comment + '\001' + p.hier;
    pts.push_back(std::move(p));
  }
  return pts;
}

void merge(const std::vector<std::string>& inputs, const std::string& out) {
  if (inputs.empty()) throw std::runtime_error("no coverage database to merge");
  for (const auto& i : inputs) read_dat(i);  // each one is a database (a clear error otherwise)
  const std::string tmp = tmp_name(out);
  std::vector<std::string> argv = {verilator_coverage(), "-write", tmp};
  argv.insert(argv.end(), inputs.begin(), inputs.end());
  try {
    run_tool(argv, "verilator_coverage -write");
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, out, ec);
  if (ec) throw std::runtime_error("cannot write " + out + ": " + ec.message());
}

std::string waivers_in_use() {
  const std::string d = default_waivers();
  std::error_code ec;
  return fs::exists(d, ec) ? d : std::string();
}

void check_output_dir(const std::string& dir, const std::string& option) {
  std::error_code ec;
  const fs::path p = fs::absolute(dir, ec).lexically_normal();
  for (const char* sys : {"/proc", "/sys", "/dev"})
    if (p == sys || p.string().rfind(std::string(sys) + "/", 0) == 0)
      throw std::invalid_argument(option + ": " + dir + " is under " + sys + ", not a place for a report");
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec)) throw std::invalid_argument(option + ": " + dir + " exists and is not a directory");
    if (::access(p.c_str(), W_OK) != 0) throw std::invalid_argument(option + ": cannot write to " + dir);
    return;
  }
  fs::path parent = p.parent_path();
  while (!parent.empty() && !fs::exists(parent, ec)) parent = parent.parent_path();
  if (parent.empty() || !fs::is_directory(parent, ec) || ::access(parent.c_str(), W_OK) != 0)
    throw std::invalid_argument(option + ": cannot create " + dir);
}

std::string default_waivers() { return (fs::path(handoff::root_dir()) / "config" / "coverage_waivers.json").string(); }

std::vector<Waiver> read_waivers(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot read the waiver file " + path);
  ojson j;
  try {
    j = ojson::parse(in);
  } catch (const std::exception& e) {
    throw std::invalid_argument(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  if (!j.is_object() || !j.contains("waivers") || !j["waivers"].is_array())
    throw std::invalid_argument(path + ": needs a \"waivers\" array");
  for (const auto& [k, v] : j.items())
    if (k != "waivers" && k != "description") throw std::invalid_argument(path + ": unknown key '" + k + "'");
  static const std::set<std::string> keys = {"id",      "module", "kind",   "file",   "function", "signal",
                                             "source",  "comment", "hier", "reason", "property", "params"};
  std::vector<Waiver> out;
  std::set<std::string> ids;
  for (const auto& w : j["waivers"]) {
    if (!w.is_object()) throw std::invalid_argument(path + ": every waiver is an object");
    for (const auto& [k, v] : w.items()) {
      if (!keys.count(k)) throw std::invalid_argument(fmt::format("{}: waiver '{}': unknown key '{}'", path, w.value("id", "?"), k));
      if (k == "params") continue;  // checked below
      if (!v.is_string()) throw std::invalid_argument(fmt::format("{}: waiver '{}': '{}' must be a string", path, w.value("id", "?"), k));
    }
    Waiver x;
    x.id = w.value("id", "");
    x.module = w.value("module", "");
    x.kind = w.value("kind", "");
    x.signal = w.value("signal", "");
    x.source = w.value("source", "");
    x.file = w.value("file", "");
    x.function = w.value("function", "");
    x.comment = w.value("comment", "");
    x.hier = w.value("hier", "");
    x.reason = w.value("reason", "");
    x.property = w.value("property", "");
    if (w.contains("params")) {
      // {"NAME": VALUE, ...}: VALUE an integer, or a string (Verilator's text of the value: 32'h4, "abc")
      const auto& ps = w["params"];
      static const std::regex pname("[A-Za-z_][A-Za-z0-9_$]*");
      if (!ps.is_object() || ps.empty())
        throw std::invalid_argument(fmt::format("{}: waiver '{}': \"params\" must be an object of parameter values, "
                                                "e.g. {{\"SH\": 1}}", path, x.id.empty() ? w.value("id", "?") : x.id));
      for (const auto& [k, v] : ps.items()) {
        if (!std::regex_match(k, pname))
          throw std::invalid_argument(fmt::format("{}: waiver '{}': params: '{}' is not a parameter name", path, w.value("id", "?"), k));
        std::string val;
        if (v.is_number_unsigned()) val = std::to_string(v.get<uint64_t>());
        else if (v.is_number_integer()) val = std::to_string(v.get<int64_t>());
        else if (v.is_string() && !v.get<std::string>().empty()) val = canonical_value(v.get<std::string>());
        else
          throw std::invalid_argument(fmt::format("{}: waiver '{}': params: {} must be an integer or a string (it is {})", path,
                                                  w.value("id", "?"), k, v.dump()));
        x.params.emplace_back(k, val);
      }
      std::sort(x.params.begin(), x.params.end());
    }
    if (x.id.empty() || !ids.insert(x.id).second)
      throw std::invalid_argument(fmt::format("{}: every waiver needs an id of its own ('{}')", path, x.id));
    if (x.module.empty()) throw std::invalid_argument(fmt::format("{}: waiver '{}': no module", path, x.id));
    if (std::find(kinds().begin(), kinds().end(), x.kind) == kinds().end())
      throw std::invalid_argument(fmt::format("{}: waiver '{}': kind '{}' not in line, branch, toggle, functional", path, x.id, x.kind));
    if (x.reason.size() < 10) throw std::invalid_argument(fmt::format("{}: waiver '{}': a reason is required", path, x.id));
    if (x.kind == "toggle" && x.signal.empty())
      throw std::invalid_argument(fmt::format("{}: waiver '{}': a toggle waiver names its signal bits (\"signal\")", path, x.id));
    if ((x.kind == "line" || x.kind == "branch") && x.source.empty() && x.file.empty() && x.function.empty())
      throw std::invalid_argument(fmt::format(
          "{}: waiver '{}': a {} waiver quotes its source line (\"source\") or names its file or function", path, x.id, x.kind));
    if (x.kind == "functional" && !x.params.empty())
      throw std::invalid_argument(fmt::format("{}: waiver '{}': a functional bin has no parameterisation (\"params\")", path, x.id));
    if (x.kind == "functional" && x.signal.empty())
      throw std::invalid_argument(fmt::format("{}: waiver '{}': a functional waiver names its bins (\"signal\")", path, x.id));
    out.push_back(std::move(x));
  }
  return out;
}

ojson summarise(const std::vector<Point>& raw, const std::vector<Waiver>& waivers, const std::string& waivers_file,
                std::vector<std::string>& errors) {
  // One point per identity (the same RTL point reached through both harnesses is one point), counts summed.
  std::vector<Point> points;
  {
    std::map<std::string, size_t> at;
    for (const auto& p : raw) {
      const auto [it, fresh] = at.emplace(p.id, points.size());
      if (fresh) points.push_back(p);
      else points[it->second].count += p.count;
    }
  }
  Sources src;
  struct Count {
    uint64_t hit = 0, total = 0, waived = 0;
  };
  std::map<std::string, std::map<std::string, Count>> per;  // module -> kind -> counts
  std::map<std::string, std::vector<std::string>> holes;
  std::set<std::string> modules;
  for (const auto& p : points) modules.insert(p.module);
  std::vector<size_t> matched(waivers.size(), 0);
  for (const auto& p : points) {
    Count& c = per[p.module][p.kind];
    ++c.total;
    const Waiver* w = nullptr;
    for (size_t i = 0; i < waivers.size() && !w; ++i)
      if (matches(waivers[i], p, src)) w = &waivers[i], ++matched[i];
    if (w) {
      if (p.count > 0)
        errors.push_back(fmt::format("waiver '{}' claims {} unreachable, but it was hit {} time(s)", w->id, describe(p), p.count));
      ++c.waived;
    } else if (p.count > 0) {
      ++c.hit;
    } else {
      holes[p.module].push_back(describe(p));
    }
  }
  // The parameterisations the database holds: module -> variant -> one of its points (its params).
  std::map<std::string, std::map<std::string, const Point*>> variants;
  for (const auto& p : points)
    if (p.kind != "functional") variants[p.module].emplace(p.variant, &p);
  ojson applied = ojson::array(), not_applicable = ojson::array();
  for (size_t i = 0; i < waivers.size(); ++i) {
    const Waiver& w = waivers[i];
    bool present = false;
    for (const auto& m : modules) present = present || glob(w.module, m);
    std::string keyed;  // " SH=1, ..." in messages
    for (const auto& [k, v] : w.params) keyed += fmt::format("{}{}={}", keyed.empty() ? " " : ", ", k, v);
    if (present && !w.params.empty()) {
      // A waiver keyed to parameters applies where the database holds such a parameterisation of its module; a
      // parameter name none of them has is an error, and so is a module whose points carry no parameterisation.
      std::set<std::string> names, raw;
      bool here = false;
      for (const auto& [m, vs] : variants) {
        if (!glob(w.module, m)) continue;
        for (const auto& [v, p] : vs) {
          if (!p->params_known) {
            raw.insert(m);
            continue;
          }
          for (const auto& kv : p->params) names.insert(kv.first);
          here = here || params_match(w, *p);
        }
      }
      if (names.empty()) {
        errors.push_back(fmt::format("waiver '{}' is keyed to parameters ({}), but the database's {} points carry no "
                                     "parameterisation (a database not written by cosim/regress --coverage: `shadecore "
                                     "coverage DAT --params-map BUILD_DIR` gives them one)",
                                     w.id, keyed.substr(1), raw.empty() ? w.module : *raw.begin()));
        continue;
      }
      bool known = true;
      for (const auto& [k, v] : w.params) {
        if (names.count(k)) continue;
        std::string have;
        for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
        errors.push_back(fmt::format("waiver '{}': params: {} has no parameter '{}' (its parameters: {})", w.id, w.module, k, have));
        known = false;
      }
      if (!known) continue;
      present = here;  // no such parameterisation in this database: not applicable, like a module it does not hold
    }
    if (!present) {
      not_applicable.push_back(w.id);
    } else if (matched[i] == 0) {
      errors.push_back(fmt::format("waiver '{}' ({} {}{}) matches nothing in the database (stale: remove or correct it)",
                                   w.id, w.module, w.kind, keyed.empty() ? "" : "," + keyed));
    } else {
      applied.push_back({{"id", waivers[i].id}, {"points", matched[i]}});
    }
  }
  auto cell = [](const Count& c) {
    const uint64_t den = c.total - c.waived;
    ojson j = {{"hit", c.hit}, {"total", c.total}, {"waived", c.waived}};
    j["percent"] = den == 0 ? 100.0 : static_cast<double>(static_cast<long long>(10000.0 * c.hit / den)) / 100.0;
    return j;
  };
  ojson mods = ojson::array(), hole_j = ojson::object();
  std::map<std::string, Count> tot;
  for (const auto& [m, kc] : per) {
    ojson row = {{"module", m}};
    for (const auto& [k, c] : kc) {
      row[k] = cell(c);
      tot[k].hit += c.hit, tot[k].total += c.total, tot[k].waived += c.waived;
    }
    row["holes"] = holes.count(m) ? holes[m].size() : 0;
    mods.push_back(row);
    if (holes.count(m)) hole_j[m] = holes[m];
  }
  ojson totals = ojson::object();
  for (const auto& [k, c] : tot) totals[k] = cell(c);
  return {{"modules", mods},
          {"totals", totals},
          {"waivers", {{"file", waivers_file}, {"applied", applied}, {"not_applicable", not_applicable}}},
          {"holes", hole_j}};
}

std::string table(const ojson& s) {
  auto col = [](const ojson& row, const char* k) -> std::string {
    if (!row.contains(k)) return "-";
    const auto& c = row[k];
    const uint64_t w = c["waived"].get<uint64_t>();
    return fmt::format("{}/{}{} {:.2f}%", c["hit"].get<uint64_t>(), c["total"].get<uint64_t>() - w,
                       w ? fmt::format(" (+{}w)", w) : "", c["percent"].get<double>());
  };
  std::string out = fmt::format("{:<20} {:>24} {:>24} {:>26} {:>22}\n", "module", "line", "branch", "toggle", "functional");
  for (const auto& row : s["modules"])
    out += fmt::format("{:<20} {:>24} {:>24} {:>26} {:>22}\n", row["module"].get<std::string>(), col(row, "line"),
                       col(row, "branch"), col(row, "toggle"), col(row, "functional"));
  ojson t = s["totals"];
  t["module"] = "(all)";
  out += fmt::format("{:<20} {:>24} {:>24} {:>26} {:>22}\n", "(all)", col(t, "line"), col(t, "branch"), col(t, "toggle"),
                     col(t, "functional"));
  return out;
}

void write_html(const std::string& dat, const std::string& dir) {
  if (!handoff::on_path("genhtml")) throw std::runtime_error("genhtml not found (Debian package lcov; scripts/setup.sh)");
  const std::string info = tmp_name(dir) + ".info", tmpdir = tmp_name(dir);
  std::error_code ec;
  fs::remove_all(tmpdir, ec);
  try {
    run_tool({verilator_coverage(), "-write-info", info, dat}, "verilator_coverage -write-info");
    run_tool({"genhtml", "--quiet", "--output-directory", tmpdir, "--title", "shadecore RTL coverage", info}, "genhtml");
  } catch (...) {
    fs::remove(info, ec);
    fs::remove_all(tmpdir, ec);
    throw;
  }
  fs::remove(info, ec);
  fs::remove_all(dir, ec);
  fs::rename(tmpdir, dir, ec);
  if (ec) throw std::runtime_error("cannot write " + dir + ": " + ec.message());
}

CoreBuild ensure_unit(const UnitModel& m, bool bare, bool quiet) {
#if !defined(SHADECORE_COSIM_TAGW) || !defined(SHADECORE_UNIT_LIBS)
  (void)m, (void)bare, (void)quiet;
  throw std::runtime_error("this shadecore was built without the RTL co-simulation (SHADECORE_WITH_RTL=OFF)");
#else
  const NamedConfig& nc = config_named(m.config);
  const VariantId v = parse_variant(m.variant);
  const Cutoff cut = parse_cutoff_name(m.cutoff);
  const std::string cfg(nc.name);
  auto cmake_list = [](const std::vector<std::string>& l) {
    std::string s;
    for (const auto& e : l) s += (s.empty() ? "" : ";") + e;
    return s;
  };
  ProjectBuild pb;
  pb.key = fmt::format("cov-unit-{}-{}-{}{}", m.variant, cfg, m.cutoff, m.norm ? "-norm" : "");
  pb.project = "sim/unit_core";
  pb.harness_sources = {"cosim_main.cpp", "bare_main.cpp"};
  pb.target = bare ? "shadecore_bare_cov" : "shadecore_cosim_cov";
  pb.stamp = bare ? "stamp.bare" : "stamp";
  pb.log = bare ? "build.bare.log" : "build.log";
  pb.defines = {
      fmt::format("-DSHADECORE_UNIT_PARAMS=VARIANT={};FRAC={};GUARD={};CUTOFF={};ENERGY={};TAGW={}", static_cast<int>(v),
                  nc.format.frac, nc.format.guard, static_cast<int>(cut), m.norm ? 1 : 0, SHADECORE_COSIM_TAGW),
      "-DSHADECORE_UNIT_CONFIG=" + cfg, "-DSHADECORE_UNIT_RTL=" + cmake_list(rtl::specular_files(v, m.norm)),
      "-DSHADECORE_UNIT_LIBS=" + std::string(SHADECORE_UNIT_LIBS)};
  std::replace(pb.defines.back().begin(), pb.defines.back().end(), ',', ';');  // a CMake list
  pb.noun = "coverage model";
  pb.first_use = "first coverage run of this unit model";
  pb.what = fmt::format("building the coverage model of {} {} {}{} ({})", m.variant, cfg, m.cutoff, m.norm ? " norm" : "",
                        bare ? "bare harness" : "SystemC testbench");
  return ensure_build(pb, quiet);
#endif
}

ojson report(const std::vector<std::string>& dats, const std::string& dir_s, const std::string& waivers_file, bool html,
             bool quiet, bool summary_file) {
  const fs::path dir = dir_s;
  const std::vector<Waiver> waivers = waivers_file.empty() ? std::vector<Waiver>{} : read_waivers(waivers_file);
  // The merge goes beside DIR first: a waiver error leaves nothing, not even DIR.
  std::error_code ec;
  const fs::path abs = fs::absolute(dir);
  fs::create_directories(abs.parent_path(), ec);
  if (ec) throw std::runtime_error("cannot create " + abs.parent_path().string() + ": " + ec.message());
  const std::string merged_tmp = tmp_name(abs.string() + ".coverage") + ".dat";
  merge(dats, merged_tmp);
  std::vector<std::string> errors;
  ojson s;
  try {
    s = summarise(read_dat(merged_tmp), waivers, waivers_file, errors);
    s["databases"] = dats.size();
    if (!errors.empty())
      throw std::invalid_argument(fmt::format("coverage waivers ({}): {}{}", waivers_file, errors.front(),
                                              errors.size() > 1 ? fmt::format(" (and {} more)", errors.size() - 1) : ""));
  } catch (...) {
    fs::remove(merged_tmp, ec);
    throw;
  }
  fs::create_directories(dir, ec);
  if (ec) {
    fs::remove(merged_tmp, ec);
    throw std::runtime_error("cannot create " + dir.string() + ": " + ec.message());
  }
  fs::rename(merged_tmp, dir / "coverage.dat", ec);
  if (ec) throw std::runtime_error("cannot write " + (dir / "coverage.dat").string() + ": " + ec.message());
  if (summary_file) write_file_atomic((dir / "summary.json").string(), s.dump(2) + "\n");
  if (html) write_html((dir / "coverage.dat").string(), (dir / "html").string());
  if (!quiet) fmt::print("coverage: {} database(s) merged into {}\n{}", dats.size(), (dir / "coverage.dat").string(), table(s));
  return s;
}

}  // namespace shadecore::cli::coverage

// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — coverage databases, their merge, summary, waivers and HTML, and the unit's coverage build
// (cli/coverage.hpp; docs/coverage.md).
#include "coverage.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
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

bool matches(const Waiver& w, const Point& p, Sources& src) {
  if (!glob(w.module, p.module) || w.kind != p.kind) return false;
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

}  // namespace

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
    if (const size_t dd = p.module.find("__"); dd != std::string::npos && p.kind != "functional") {
      p.variant = p.module.substr(dd + 2);
      p.module.resize(dd);
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
                                             "source",  "comment", "hier", "reason", "property"};
  std::vector<Waiver> out;
  std::set<std::string> ids;
  for (const auto& w : j["waivers"]) {
    if (!w.is_object()) throw std::invalid_argument(path + ": every waiver is an object");
    for (const auto& [k, v] : w.items()) {
      if (!keys.count(k)) throw std::invalid_argument(fmt::format("{}: waiver '{}': unknown key '{}'", path, w.value("id", "?"), k));
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
  ojson applied = ojson::array(), not_applicable = ojson::array();
  for (size_t i = 0; i < waivers.size(); ++i) {
    bool present = false;
    for (const auto& m : modules) present = present || glob(waivers[i].module, m);
    if (!present) {
      not_applicable.push_back(waivers[i].id);
    } else if (matched[i] == 0) {
      errors.push_back(fmt::format("waiver '{}' ({} {}) matches nothing in the database (stale: remove or correct it)",
                                   waivers[i].id, waivers[i].module, waivers[i].kind));
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

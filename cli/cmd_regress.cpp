// SPDX-License-Identifier: Apache-2.0
// shadecore regress — plans, shards and merges long verification runs, on this machine (--local) or as
// Slurm array jobs (--slurm). docs/regress.md is the user's guide; in short:
//
//   shadecore regress --plan smoke|nightly|FILE --out DIR (--local [-j K] | --slurm [--partition P ...])
//
//   * a plan (JSON) lists jobs: unit co-simulations (exhaustive, random, directed; the bare harness or the
//     SystemC testbench), error sweeps, lighting-core co-simulations and any other shadecore command line;
//   * each job splits into shards by n range (exhaustive, sweep) or transaction-index range (random: every
//     shard the same seed and the global reset index, its own --first), so the merged result equals the
//     one-process run — same vectors, same mismatches, same stimulus digest;
//   * every shard is one `shadecore regress-shard --dir DIR --shard ID` process, wherever it runs: it runs
//     the shard's command, logs it to DIR/logs/ID.log and writes DIR/shards/ID.json (atomically) last;
//   * backends: --local runs them K at a time through the common runner (shadecore/common/subprocess.hpp);
//     --slurm submits one `sbatch --array` per plan (more only past MaxArraySize) and follows the result
//     files and `squeue`; a shard that ended without a result, or with an infrastructure error, is run once
//     more, then reported by name with its log; Ctrl-C cancels the array (or stops the local shards);
//   * DIR keeps plan.json, shards.json, shards/, logs/, run.json (attempts and times), merged.json (per job
//     vectors / mismatches / ok, totals — the same whichever backend) and summary.md; running the same
//     DIR again runs only the shards missing or failed (resume).
// Exit status: 0 every job passed; 2 a check failed (the report is written); 1 usage or infrastructure
// error (a shard lost twice: the report is written and names it); 130/143 interrupted (DIR kept, resumable).
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "coverage.hpp"
#include "handoff_bundle.hpp"
#include "output.hpp"
#include "shadecore/common/args.hpp"
#include "shadecore/common/progress.hpp"
#include "shadecore/common/subprocess.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/stimulus/specular.hpp"
#include "shadecore/unit.hpp"

namespace shadecore::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// ------------------------------------------------------------------------------------------ helpers
std::map<std::string, std::string> exe_map(const char* list) {
  std::map<std::string, std::string> m;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq != std::string::npos) m[item.substr(0, eq)] = item.substr(eq + 1);
  }
  return m;
}
std::map<std::string, std::string> cosim_sims() {
#ifdef SHADECORE_COSIM_SIMS
  return exe_map(SHADECORE_COSIM_SIMS);
#else
  return {};
#endif
}
std::map<std::string, std::string> bare_sims() {
#ifdef SHADECORE_BARE_SIMS
  return exe_map(SHADECORE_BARE_SIMS);
#else
  return {};
#endif
}

std::string self_exe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the shadecore executable (/proc/self/exe): " + ec.message());
  return p.string();
}

std::string read_file(const fs::path& p) { return handoff::read_text(p); }

// Writes through a temporary file and a rename: a reader never sees half a file.
void write_atomic(const fs::path& p, const std::string& s) {
  const fs::path tmp = p.string() + fmt::format(".tmp.{}", ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << s;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::error_code ec;
  fs::rename(tmp, p, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write " + p.string() + ": " + ec.message());
  }
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string host_name() {
  char buf[256] = {};
  ::gethostname(buf, sizeof buf - 1);
  return buf;
}

std::string quote(const std::string& a) { return "'" + std::regex_replace(a, std::regex("'"), "'\\''") + "'"; }

// ------------------------------------------------------------------------------------------ the plan
// A job of the plan; `spec` is its JSON object, checked key by key.
struct ShardSpec {
  std::string id, job, kind;  // kind: sim (SystemC testbench), bare, sweep, cli
  std::vector<std::string> argv;
  std::string raw_json;       // cli/sweep: where the command writes its --json (relative to DIR)
};

const std::set<std::string>& keys_for(const std::string& kind) {
  static const std::map<std::string, std::set<std::string>> k = {
      {"cosim",
       {"name", "kind", "variant", "config", "cutoff", "mode", "n", "count", "seed", "in_stall", "out_stall", "mat_rate",
        "reset_at", "norm", "coef_model", "coef", "harness", "shards", "note"}},
      {"sweep", {"name", "kind", "variant", "config", "cutoff", "n", "shards", "note"}},
      {"cosim_lighting", {"name", "kind", "features", "mode", "count", "seed", "in_stall", "out_stall", "reset_at", "harness",
                          "write_rate", "shards", "note"}},
      {"command", {"name", "kind", "args", "json", "note"}},
  };
  const auto it = k.find(kind);
  if (it == k.end()) throw std::invalid_argument("unknown job kind '" + kind + "' (known: cosim, sweep, cosim_lighting, command)");
  return it->second;
}

template <class T>
T get(const json& j, const std::string& job, const char* key, T dflt) {
  if (!j.contains(key)) return dflt;
  try {
    return j.at(key).get<T>();
  } catch (const std::exception&) {
    throw std::invalid_argument(fmt::format("plan: job '{}': '{}' has the wrong type", job, key));
  }
}

std::string num(double v) { return fmt::format("{}", v); }

// A job's count when the plan gives none: a random cosim job's transactions, a cosim_lighting job's fragments
// (expand() and the closure rounds read the same defaults).
constexpr uint64_t kCosimRandomCount = 100000, kLightingCount = 10000;

// A random job of `count` transactions (a function of (seed, index)) in shards: every shard's first global
// index and count (min(shards, count) shards; the first count % shards take one more), and the one global
// reset index every shard is given (the plan's reset_at, else the stimulus's default for (seed, count)).
struct RandomShards {
  std::vector<std::pair<uint64_t, uint64_t>> ranges;
  int64_t reset_at = -1;
};
RandomShards random_shards(const json& j, const std::string& name, uint64_t seed, uint64_t count, int shards_req) {
  RandomShards r;
  r.reset_at = get<int64_t>(j, name, "reset_at", static_cast<int64_t>(stimulus::default_reset_index(seed, count)));
  const uint64_t shards = std::min<uint64_t>(static_cast<uint64_t>(shards_req), count);
  const uint64_t base = count / shards, extra = count % shards;
  for (uint64_t k = 0; k < shards; ++k) r.ranges.emplace_back(k * base + std::min(k, extra), base + (k < extra ? 1 : 0));
  return r;
}

// Expands the plan into shards (deterministic: a function of the plan and this build's simulators).
// With `coverage` (regress --coverage, docs/coverage.md) every co-simulation shard runs the coverage build of its
// model (built here, on demand, into the core cache) and writes its database to "{cov}" = DIR/coverage/shards/ID/
// coverage.dat; sweeps and commands simulate no RTL and run as without it.
std::vector<ShardSpec> expand(const json& plan, bool coverage = false) {
  if (!plan.is_object() || !plan.contains("jobs") || !plan["jobs"].is_array() || plan["jobs"].empty())
    throw std::invalid_argument("plan: needs a non-empty \"jobs\" array");
  for (const auto& [k, v] : plan.items())
    if (k != "name" && k != "description" && k != "jobs" && k != "wall_time_note")
      throw std::invalid_argument("plan: unknown key '" + k + "'");
  const std::string self = self_exe();
  std::vector<ShardSpec> out;
  std::set<std::string> names;
  static const std::regex name_re("[A-Za-z0-9_-]{1,64}");
  for (const auto& j : plan["jobs"]) {
    if (!j.is_object()) throw std::invalid_argument("plan: every job is an object");
    const std::string name = get<std::string>(j, "?", "name", "");
    if (!std::regex_match(name, name_re))
      throw std::invalid_argument("plan: job name '" + name + "' must be 1..64 of [A-Za-z0-9_-]");
    if (!names.insert(name).second) throw std::invalid_argument("plan: job name '" + name + "' given twice");
    const std::string kind = get<std::string>(j, name, "kind", "");
    const auto& allowed = keys_for(kind);
    for (const auto& [k, v] : j.items())
      if (!allowed.count(k)) throw std::invalid_argument(fmt::format("plan: job '{}': unknown key '{}' for kind {}", name, k, kind));
    const int shards_req = get<int>(j, name, "shards", 1);
    if (shards_req < 1 || shards_req > 100000)
      throw std::invalid_argument(fmt::format("plan: job '{}': shards must be in 1..100000", name));
    auto add = [&](int k, int total, std::string kind2, std::vector<std::string> argv, std::string raw = {}) {
      const int w = static_cast<int>(std::to_string(std::max(total - 1, 0)).size());
      ShardSpec s;
      s.id = fmt::format("{}.{:0{}}", name, k, w);
      s.job = name;
      s.kind = std::move(kind2);
      s.argv = std::move(argv);
      s.raw_json = std::move(raw);
      out.push_back(std::move(s));
    };
    if (kind == "cosim") {
      const std::string variant = get<std::string>(j, name, "variant", "cs16");
      const std::string cfg = get<std::string>(j, name, "config", "default");
      const std::string cutoff = get<std::string>(j, name, "cutoff", "theta_cr");
      const std::string mode = get<std::string>(j, name, "mode", "directed");
      const bool norm = get<bool>(j, name, "norm", false);
      const NamedConfig& nc = config_named(cfg);  // throws on an unknown config
      Unit unit(parse_variant(variant), nc.format, parse_cutoff_name(cutoff));
      (void)unit;
      if (mode != "exhaustive" && mode != "random" && mode != "directed")
        throw std::invalid_argument(fmt::format("plan: job '{}': unknown mode '{}'", name, mode));
      const std::string harness = get<std::string>(j, name, "harness", mode == "exhaustive" ? "auto" : "systemc");
      bool bare = false;
      if (harness == "bare" || harness == "auto") {
        const bool fits = mode == "exhaustive" && variant == "cs16" && cutoff == "theta_cr" && !norm;
        if (harness == "bare" && !fits)
          throw std::invalid_argument(fmt::format("plan: job '{}': the bare harness runs exhaustive cs16 theta_cr without norm only", name));
        bare = fits;
      } else if (harness != "systemc") {
        throw std::invalid_argument(fmt::format("plan: job '{}': harness must be bare, systemc or auto", name));
      }
      auto sims = bare ? bare_sims() : cosim_sims();
      if (sims.empty()) throw std::runtime_error("this shadecore was built without the RTL co-simulation (SHADECORE_WITH_RTL=OFF)");
      auto it = sims.find(std::string(nc.name));
      if (it == sims.end()) throw std::runtime_error(fmt::format("plan: job '{}': no {} simulator built for config '{}'", name, bare ? "bare" : "SystemC", cfg));
      if (coverage) it->second = coverage::ensure_unit({variant, std::string(nc.name), cutoff, norm}, bare, false).exe;
      const std::vector<std::string> cov_args = coverage ? std::vector<std::string>{"--coverage", "{cov}/coverage.dat"}
                                                          : std::vector<std::string>{};
      const auto [n_lo, n_hi] = cliargs::parse_n_range(get<std::string>(j, name, "n", "16..1024"));
      const uint64_t seed = get<uint64_t>(j, name, "seed", 1);
      if (seed == 0) throw std::invalid_argument(fmt::format("plan: job '{}': seed must be >= 1 (a plan is reproducible)", name));
      std::vector<std::string> common;
      if (!bare) {
        common = {it->second, "--variant", variant, "--cutoff", cutoff, "--mode", mode, "--quiet", "--show", "5",
                  "--in-stall", num(get<double>(j, name, "in_stall", 0.0)), "--out-stall", num(get<double>(j, name, "out_stall", 0.0)),
                  "--seed", std::to_string(seed)};
        if (norm) common.push_back("--norm");
        common.insert(common.end(), cov_args.begin(), cov_args.end());
        if (j.contains("coef_model")) common.insert(common.end(), {"--coef-model", get<std::string>(j, name, "coef_model", "")});
        if (j.contains("coef")) common.insert(common.end(), {"--coef", get<std::string>(j, name, "coef", "")});
      }
      if (mode == "exhaustive") {
        if (j.contains("count") || j.contains("mat_rate")) throw std::invalid_argument(fmt::format("plan: job '{}': count / mat_rate do not apply to exhaustive", name));
        const int total = n_hi - n_lo + 1, shards = std::min(shards_req, total);
        for (int k = 0; k < shards; ++k) {
          const int lo = n_lo + static_cast<int>(static_cast<long long>(total) * k / shards);
          const int hi = n_lo + static_cast<int>(static_cast<long long>(total) * (k + 1) / shards) - 1;
          std::vector<std::string> v = bare ? std::vector<std::string>{it->second, "--no-progress"} : common;
          if (bare) v.insert(v.end(), cov_args.begin(), cov_args.end());
          v.insert(v.end(), {"--n", fmt::format("{}..{}", lo, hi)});
          if (!bare && j.contains("reset_at")) v.insert(v.end(), {"--reset-at", std::to_string(get<int64_t>(j, name, "reset_at", -1))});
          add(k, shards, bare ? "bare" : "sim", v);
        }
      } else if (mode == "random") {
        const uint64_t count = get<uint64_t>(j, name, "count", kCosimRandomCount);
        if (count == 0) throw std::invalid_argument(fmt::format("plan: job '{}': count must be >= 1", name));
        const RandomShards rs = random_shards(j, name, seed, count, shards_req);
        const int shards = static_cast<int>(rs.ranges.size());
        for (int k = 0; k < shards; ++k) {
          const auto [first, c] = rs.ranges[static_cast<size_t>(k)];
          std::vector<std::string> v = common;
          v.insert(v.end(), {"--n", fmt::format("{}..{}", n_lo, n_hi), "--count", std::to_string(c), "--first",
                             std::to_string(first), "--reset-at", std::to_string(rs.reset_at)});
          if (j.contains("mat_rate")) v.insert(v.end(), {"--mat-rate", num(get<double>(j, name, "mat_rate", 0.01))});
          add(k, shards, "sim", v);
        }
      } else {
        if (shards_req != 1) throw std::invalid_argument(fmt::format("plan: job '{}': a directed job is one shard", name));
        std::vector<std::string> v = common;
        v.insert(v.end(), {"--count", std::to_string(get<uint64_t>(j, name, "count", 1))});
        add(0, 1, "sim", v);
      }
    } else if (kind == "sweep") {
      const auto [n_lo, n_hi] = cliargs::parse_n_range(get<std::string>(j, name, "n", "16..1024"));
      const int total = n_hi - n_lo + 1, shards = std::min(shards_req, total);
      for (int k = 0; k < shards; ++k) {
        const int lo = n_lo + static_cast<int>(static_cast<long long>(total) * k / shards);
        const int hi = n_lo + static_cast<int>(static_cast<long long>(total) * (k + 1) / shards) - 1;
        std::vector<std::string> v{self, "sweep", "--variant", get<std::string>(j, name, "variant", "cs16"), "--config",
                                   get<std::string>(j, name, "config", "default")};
        // the cut-off only where the job names one: `sweep` takes --cutoff for cs16 and its forms alone
        if (j.contains("cutoff")) v.insert(v.end(), {"--cutoff", get<std::string>(j, name, "cutoff", "theta_cr")});
        v.insert(v.end(), {"--n", fmt::format("{}..{}", lo, hi), "--threads", "1", "--no-progress"});
        add(k, shards, "sweep", v, "json");
      }
    } else if (kind == "cosim_lighting") {
      // Random mode shards by fragment index like the unit's random jobs: the lighting stimulus — register
      // program, write bursts, fragments — is a function of (seed, index), every shard gets the job's global
      // --reset-at, and the reset's flushed fragments are sent again, so the merged vectors, mismatches and
      // stimulus digest equal the one-process run's. Directed is one shard.
      const uint64_t seed = get<uint64_t>(j, name, "seed", 1);
      if (seed == 0) throw std::invalid_argument(fmt::format("plan: job '{}': seed must be >= 1", name));
      const std::string mode = get<std::string>(j, name, "mode", "random");
      if (mode != "random" && mode != "directed")
        throw std::invalid_argument(fmt::format("plan: job '{}': unknown mode '{}' (known: random, directed)", name, mode));
      const std::string harness = get<std::string>(j, name, "harness", "systemc");
      if (harness != "systemc" && harness != "bare")
        throw std::invalid_argument(fmt::format("plan: job '{}': harness must be systemc or bare", name));
      const uint64_t count = get<uint64_t>(j, name, "count", kLightingCount);
      if (count == 0) throw std::invalid_argument(fmt::format("plan: job '{}': count must be >= 1", name));
      if (mode != "random" && shards_req != 1)
        throw std::invalid_argument(fmt::format("plan: job '{}': a directed job is one shard", name));
      const double write_rate = get<double>(j, name, "write_rate", -1.0);
      if (j.contains("write_rate") && (mode != "random" || !(write_rate >= 0 && write_rate < 1)))
        throw std::invalid_argument(fmt::format("plan: job '{}': write_rate applies to random jobs and is in [0, 1)", name));
      std::vector<std::string> common = {
          self, "cosim", "--core", "lighting", "--harness", harness, "--features", get<std::string>(j, name, "features", "full"),
          "--mode", mode, "--seed", std::to_string(seed), "--in-stall", num(get<double>(j, name, "in_stall", 0.0)),
          "--out-stall", num(get<double>(j, name, "out_stall", 0.0)), "--no-progress"};
      if (coverage) common.insert(common.end(), {"--coverage", "{cov}", "--coverage-db-only"});
      // A failing shard keeps its waveform (issue 36): the windowed --trace costs nothing on a pass and, on a FAIL,
      // re-runs the shard on the trace build for the cycles around its first failure, into DIR/work/ID.fst.
      common.insert(common.end(), {"--trace", "{work}.fst"});
      if (j.contains("write_rate")) common.insert(common.end(), {"--write-rate", num(write_rate)});
      if (mode == "directed") {
        if (j.contains("reset_at")) common.insert(common.end(), {"--reset-at", std::to_string(get<int64_t>(j, name, "reset_at", -1))});
        common.insert(common.end(), {"--count", std::to_string(count)});
        add(0, 1, "cli", common, "json");
      } else {
        const RandomShards rs = random_shards(j, name, seed, count, shards_req);
        const int shards = static_cast<int>(rs.ranges.size());
        for (int k = 0; k < shards; ++k) {
          const auto [first, c] = rs.ranges[static_cast<size_t>(k)];
          std::vector<std::string> v = common;
          v.insert(v.end(), {"--count", std::to_string(c), "--reset-at", std::to_string(rs.reset_at)});
          if (first != 0) v.insert(v.end(), {"--first", std::to_string(first)});
          add(k, shards, "cli", v, "json");
        }
      }
    } else {  // command: any shadecore command line, one shard; passes when it exits 0
      if (!j.contains("args") || !j["args"].is_array() || j["args"].empty())
        throw std::invalid_argument(fmt::format("plan: job '{}': \"args\" must be a non-empty array of strings", name));
      std::vector<std::string> v = {self};
      for (const auto& a : j["args"]) {
        if (!a.is_string()) throw std::invalid_argument(fmt::format("plan: job '{}': \"args\" must be strings", name));
        v.push_back(a.get<std::string>());
      }
      add(0, 1, "cli", v, get<bool>(j, name, "json", false) ? "json" : "");
    }
  }
  return out;
}

json shards_json(const std::vector<ShardSpec>& s) {
  json a = json::array();
  for (const auto& x : s)
    a.push_back({{"id", x.id}, {"job", x.job}, {"kind", x.kind}, {"argv", x.argv}, {"json", x.raw_json}});
  return a;
}

// A named plan (the project's regress/plans/NAME.json) or a file.
json load_plan(const std::string& what, std::string& where) {
  static const std::regex named("[a-z0-9_-]+");
  fs::path p = what;
  if (std::regex_match(what, named) && !fs::exists(p)) p = fs::path(handoff::root_dir()) / "regress" / "plans" / (what + ".json");
  if (!fs::is_regular_file(p)) throw std::invalid_argument("--plan: no plan named or at '" + what + "'");
  where = p.string();
  try {
    return json::parse(read_file(p));
  } catch (const json::parse_error& e) {
    throw std::invalid_argument("--plan " + what + ": not valid JSON (" + std::string(e.what()) + ")");
  }
}

// ------------------------------------------------------------------------------------------ one shard
// `shadecore regress-shard --dir DIR --shard ID` (or --tasks FILE --task K: the K-th line of FILE, for a
// Slurm array): runs the shard's command, logs it, writes DIR/shards/ID.json last.
json parse_outcome(const ShardSpec& s, int status, const std::string& out, const fs::path& raw) {
  json r = {{"vectors", 0}, {"mismatches", 0}};
  bool have = false;
  if (s.kind == "sim") {
    std::stringstream ss(out);
    std::string line;
    while (std::getline(ss, line))
      if (line.rfind("COSIM-RESULT ", 0) == 0) {
        const json j = json::parse(line.substr(13), nullptr, false);
        if (j.is_object()) {
          r["vectors"] = j.value("vectors", uint64_t{0});
          r["mismatches"] = j.value("mismatches", uint64_t{0});
          r["stimulus_digest"] = j.value("stimulus_digest", uint64_t{0});
          for (const char* k : {"lost", "duplicated_or_reordered", "latency_errors", "protocol_errors"})
            r[k] = j.value(k, uint64_t{0});
          r["checks_ok"] = j.value("ok", false);
          have = true;
        }
      }
  } else if (s.kind == "bare") {
    static const std::regex re(R"(bare: \S+ config \S+ MREG \d+ n \d+\.\.\d+: (\d+) sent, (\d+) out, (\d+) mismatches)");
    std::smatch m;
    if (std::regex_search(out, m, re)) {
      r["vectors"] = std::stoull(m[2]);
      r["mismatches"] = std::stoull(m[3]);
      r["sent"] = std::stoull(m[1]);
      have = true;
    }
  } else if (!s.raw_json.empty()) {
    std::error_code ec;
    if (fs::exists(raw, ec)) {
      const json j = json::parse(read_file(raw), nullptr, false);
      if (j.is_object()) {
        have = true;
        if (s.kind == "sweep") {
          r["vectors"] = j.value("evaluations", uint64_t{0});
          // An exponent whose quantisation error leaves the variant's contract is a mismatch.
          uint64_t bad = 0;
          double qmax = -1e300, qmin = 1e300;
          const bool has_c = j.contains("contract");
          for (const auto& row : j.value("per_n", json::array())) {
            const double hi = row.value("quant_max_ulp", 0.0), lo = row.value("quant_min_ulp", 0.0);
            qmax = std::max(qmax, hi);
            qmin = std::min(qmin, lo);
            if (has_c) {
              const auto& c = j["contract"];
              const bool lo_ok = c.value("lo_strict", false) ? lo > c.value("lo", 0.0) : lo >= c.value("lo", 0.0);
              if (!lo_ok || hi > c.value("hi", 0.0)) ++bad;
            }
          }
          r["mismatches"] = bad;
          r["quant_ulp_max"] = qmax;
          r["quant_ulp_min"] = qmin;
        } else {
          r["vectors"] = j.value("vectors", uint64_t{0});
          r["mismatches"] = j.value("mismatches", uint64_t{0});
          if (j.contains("stimulus_digest")) r["stimulus_digest"] = j.value("stimulus_digest", uint64_t{0});
        }
      }
    }
  } else {
    have = true;  // a plain command: its exit status is the verdict
  }
  r["have_result"] = have;
  (void)status;
  return r;
}

int run_shard(const std::string& dir_s, const std::string& id_given, const std::string& tasks, long task) {
  const fs::path dir = fs::absolute(dir_s);
  std::string id = id_given;
  if (!tasks.empty()) {
    std::ifstream in(tasks);
    if (!in) throw std::runtime_error("cannot read " + tasks);
    std::string line;
    for (long i = 0; std::getline(in, line); ++i)
      if (i == task) id = line;
    if (id.empty()) throw std::runtime_error(fmt::format("{} has no task {}", tasks, task));
  }
  const json all = json::parse(read_file(dir / "shards.json"));
  const json* me = nullptr;
  for (const auto& s : all)
    if (s.at("id").get<std::string>() == id) me = &s;
  if (!me) throw std::runtime_error("no shard '" + id + "' in " + (dir / "shards.json").string());
  ShardSpec s;
  s.id = id;
  s.job = me->at("job").get<std::string>();
  s.kind = me->at("kind").get<std::string>();
  s.argv = me->at("argv").get<std::vector<std::string>>();
  s.raw_json = me->at("json").get<std::string>();
  const fs::path raw = dir / "shards" / (id + ".raw.json");
  std::error_code ec;
  fs::remove(raw, ec);
  std::vector<std::string> argv = s.argv;
  // "{work}" in a command's arguments: a directory of this shard's own, DIR/work/ID (emptied per attempt).
  const fs::path work = dir / "work" / id;
  // "{root}": the project's source tree ($SHADECORE_ROOT or the one this shadecore was built from).
  bool uses_work = false;
  for (auto& a : argv) {
    for (size_t at; (at = a.find("{work}")) != std::string::npos; uses_work = true) a.replace(at, 6, work.string());
    for (size_t at; (at = a.find("{root}")) != std::string::npos;) a.replace(at, 6, handoff::root_dir());
  }
  if (uses_work) {
    fs::remove_all(work, ec);
    fs::create_directories(work.parent_path(), ec);
  }
  // "{cov}": the shard's coverage directory, DIR/coverage/shards/ID (emptied per attempt; regress --coverage).
  const fs::path cov = dir / "coverage" / "shards" / id;
  bool uses_cov = false;
  for (auto& a : argv)
    for (size_t at; (at = a.find("{cov}")) != std::string::npos; uses_cov = true) a.replace(at, 5, cov.string());
  if (uses_cov) {
    fs::remove_all(cov, ec);
    fs::create_directories(cov, ec);
    if (ec) throw std::runtime_error("cannot create " + cov.string() + ": " + ec.message());
  }
  if (!s.raw_json.empty()) argv.insert(argv.end(), {"--json", raw.string()});

  const fs::path log = dir / "logs" / (id + ".log");
  std::ofstream lf(log, std::ios::binary | std::ios::trunc);
  if (!lf) throw std::runtime_error("cannot write " + log.string());
  std::vector<std::string> shown = argv;
  std::string cmd;
  for (const auto& a : shown) cmd += (cmd.empty() ? "" : " ") + quote(a);
  const char* job_id = std::getenv("SLURM_JOB_ID");
  lf << "# shard " << id << " on " << host_name() << " at " << now_utc()
     << (job_id ? fmt::format(" (Slurm job {})", job_id) : std::string()) << "\n# " << cmd << "\n";
  lf.flush();
  proc::Options o;
  o.merge_stderr = true;
  o.env = {{"SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1"}};
  o.on_line = [&lf](const std::string& line) {
    if (line.rfind("COSIM-PROGRESS ", 0) == 0) return;
    lf << line;
    lf.flush();
  };
  const auto t0 = std::chrono::steady_clock::now();
  const proc::Result r = proc::run(argv, o);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  lf << fmt::format("# exit status {} after {:.2f} s\n", r.status, wall);
  lf.close();
  json res = {{"shard", id}, {"job", s.job}, {"kind", s.kind}, {"status", r.status}};
  json outcome = parse_outcome(s, r.status, r.out, raw);
  const bool have = outcome["have_result"].get<bool>();
  outcome.erase("have_result");
  // 0 passed, 2 a check failed — completed; anything else (or no parsable result) is an error.
  const bool completed = have && (r.status == 0 || r.status == 2);
  res["completed"] = completed;
  res["ok"] = completed && r.status == 0;
  for (auto& [k, v] : outcome.items()) res[k] = v;
  res["wall_s"] = wall;
  res["host"] = host_name();
  res["finished"] = now_utc();
  if (!completed) res["error"] = r.last_line();
  write_atomic(dir / "shards" / (id + ".json"), res.dump(2) + "\n");
  return 0;
}

// ------------------------------------------------------------------------------------------ the run
struct RegressArgs {
  std::string plan, out;
  bool local = false, slurm = false;
  int jobs = 0;
  std::string partition, time_limit, account;
  std::vector<std::string> sbatch_args;
  int max_running = 0;
  int poll_ms = 2000;
  bool merge_only = false;
  bool coverage = false;     // --coverage: coverage builds, per-shard databases, merged after the run
  std::string waivers;       // --waivers FILE (default: config/coverage_waivers.json)
  bool waivers_given = false;
  bool until_coverage = false;  // --until-coverage: closure rounds of new random shards until the targets are met
  std::string targets = "line=100,branch=100,toggle=95,functional=100";  // --coverage-target
  int max_rounds = 8;           // --max-rounds: closure rounds at most
  double budget_s = 0;          // --budget: wall seconds for the closure rounds (0: no limit)
  ProgressFlags progress;
};

// ------------------------------------------------------------------------------------------ coverage closure
// regress --until-coverage (docs/coverage.md "Closure"): after the plan's shards, while some module is below its
// target, a closure round adds one shard's worth of every random job of the plan under a new seed — job J (seed S,
// count C in K shards) gains the job "J-cR" of round R: seed S + R·1000003, C/K transactions (at least 1), one
// shard, the same options — runs them, merges everything again and compares. The rounds are recorded in
// DIR/closure.json, so a rerun of the same --out resumes them like any shard.
struct Targets {
  std::map<std::string, double> pc = {{"line", 100}, {"branch", 100}, {"toggle", 95}, {"functional", 100}};
};

Targets parse_targets(const std::string& text) {
  Targets t;
  size_t at = 0;
  while (at <= text.size()) {
    const size_t end = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, end - at);
    const size_t eq = item.find('=');
    const std::string kind = item.substr(0, eq);
    if (eq == std::string::npos || !t.pc.count(kind))
      throw std::invalid_argument("--coverage-target: '" + item + "' is not KIND=PERCENT with KIND one of line, branch, toggle, functional");
    double v = 0;
    try {
      size_t used = 0;
      v = std::stod(item.substr(eq + 1), &used);
      if (used != item.size() - eq - 1) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw std::invalid_argument("--coverage-target: '" + item + "': the percent is not a number");
    }
    if (!(v >= 0 && v <= 100)) throw std::invalid_argument("--coverage-target: '" + item + "': the percent must be in 0..100");
    t.pc[kind] = v;
    at = end + 1;
  }
  return t;
}

// The modules below their targets: "module kind hit/(total - waived) = P % < T %", one per module and kind.
std::vector<std::string> below_targets(const json& modules, const Targets& t) {
  std::vector<std::string> out;
  for (const auto& row : modules)
    for (const auto& [kind, target] : t.pc) {
      if (!row.contains(kind)) continue;
      const auto& x = row[kind];
      const uint64_t den = x["total"].get<uint64_t>() - x["waived"].get<uint64_t>();
      if (den == 0) continue;
      const double pc = 100.0 * static_cast<double>(x["hit"].get<uint64_t>()) / static_cast<double>(den);
      if (pc + 1e-9 < target)
        out.push_back(fmt::format("{} {} {}/{} = {:.2f} % < {} %", row["module"].get<std::string>(), kind,
                                  x["hit"].get<uint64_t>(), den, pc, target));
    }
  return out;
}

// The jobs closure round `round` adds to `plan`: one shard's worth of every random job under a new seed.
json closure_jobs(const json& plan, int round) {
  json jobs = json::array();
  for (const auto& j : plan["jobs"]) {
    const std::string kind = j.value("kind", std::string());
    const std::string mode = j.value("mode", std::string(kind == "cosim_lighting" ? "random" : "directed"));
    if ((kind != "cosim" && kind != "cosim_lighting") || mode != "random") continue;
    const std::string name = j["name"].get<std::string>() + "-c" + std::to_string(round);
    if (name.size() > 64) throw std::invalid_argument("--until-coverage: job name '" + name + "' is longer than 64");
    json c = j;
    const uint64_t seed = j.value("seed", uint64_t{1});
    const uint64_t count = j.value("count", kind == "cosim" ? kCosimRandomCount : kLightingCount);
    const uint64_t shards = std::max<uint64_t>(1, j.value("shards", uint64_t{1}));
    c["name"] = name;
    c["seed"] = (seed + static_cast<uint64_t>(round) * 1000003ull) & 0x7fffffffffffffffull;
    if (c["seed"].get<uint64_t>() == 0) c["seed"] = 1;
    c["count"] = std::max<uint64_t>(1, count / shards);
    c["shards"] = 1;
    c.erase("reset_at");  // the new stimulus's own default reset index
    c["note"] = fmt::format("coverage closure round {} of job {}", round, j["name"].get<std::string>());
    jobs.push_back(c);
  }
  return jobs;
}

struct ShardState {
  const ShardSpec* spec = nullptr;
  int attempts = 0;      // in this invocation
  bool done = false;     // a completed result file (0 or 2)
  json result;
};

bool load_result(const fs::path& dir, ShardState& st) {
  const fs::path p = dir / "shards" / (st.spec->id + ".json");
  std::error_code ec;
  if (!fs::exists(p, ec)) return false;
  const json j = json::parse(read_file(p), nullptr, false);
  if (!j.is_object()) return false;
  st.result = j;
  st.done = j.value("completed", false);
  return true;
}

class Backend {
 public:
  virtual ~Backend() = default;
  // Runs these shards (each once); returns when every one has ended one way or the other.
  virtual void run(const std::vector<ShardState*>& todo, int round) = 0;
};

std::string shard_cmd_note(const fs::path& dir, const std::string& id) { return (dir / "logs" / (id + ".log")).string(); }

void interrupted_exit(const std::string& what) {
  const int sig = proc::interrupt_signal();
  fmt::print(stderr, "shadecore: regress interrupted by signal {}; {} (rerun the same --out to resume)\n", sig, what);
  std::fflush(stderr);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
  std::_Exit(128 + sig);
}

class LocalBackend : public Backend {
 public:
  LocalBackend(fs::path dir, std::string self, int k, io::Progress& bar, size_t& done_count)
      : dir_(std::move(dir)), self_(std::move(self)), k_(k), bar_(bar), done_(done_count) {}
  void run(const std::vector<ShardState*>& todo, int round) override {
    proc::Pool pool;
    std::map<size_t, ShardState*> running;
    size_t next = 0;
    while (next < todo.size() || !running.empty()) {
      if (proc::interrupt_signal()) {
        pool.terminate_all();
        while (pool.running() > 0) pool.poll(200);
        interrupted_exit("local shards stopped");
      }
      while (next < todo.size() && running.size() < static_cast<size_t>(k_)) {
        ShardState* st = todo[next++];
        proc::Options o;
        o.own_group = true;
        o.log_path = (dir_ / "logs" / (st->spec->id + ".runner.log")).string();
        const size_t id = pool.start({self_, "regress-shard", "--dir", dir_.string(), "--shard", st->spec->id}, o);
        ++st->attempts;
        running[id] = st;
      }
      for (size_t id : pool.poll(500)) {
        ShardState* st = running[id];
        running.erase(id);
        if (load_result(dir_, *st) && st->done) ++done_;
        bar_.set(done_);
        (void)round;
      }
    }
  }

 private:
  fs::path dir_;
  std::string self_;
  int k_;
  io::Progress& bar_;
  size_t& done_;
};

class SlurmBackend : public Backend {
 public:
  SlurmBackend(fs::path dir, std::string self, const RegressArgs& a, std::string plan_name, io::Progress& bar,
               size_t& done_count)
      : dir_(std::move(dir)), self_(std::move(self)), a_(a), plan_(std::move(plan_name)), bar_(bar), done_(done_count) {
    for (const char* tool : {"sbatch", "squeue", "scancel", "scontrol"})
      if (!handoff::on_path(tool))
        throw std::runtime_error(std::string(tool) + " not found on PATH (is Slurm installed? --local runs on this machine)");
    const proc::Result r = proc::run({"scontrol", "show", "config"});
    if (!r.ok()) throw std::runtime_error("scontrol show config failed: " + r.last_line());
    static const std::regex re(R"(MaxArraySize\s*=\s*(\d+))");
    std::smatch m;
    if (std::regex_search(r.out, m, re)) max_array_ = std::stol(m[1]);
    if (max_array_ < 1) max_array_ = 1001;
  }

  void run(const std::vector<ShardState*>& todo, int round) override {
    fs::create_directories(dir_ / "slurm");
    std::vector<std::string> jobs;
    // One array per plan (task = shard); more than one only past MaxArraySize (task ids 0..Max-1).
    const size_t per = static_cast<size_t>(max_array_);
    for (size_t off = 0, chunk = 0; off < todo.size(); off += per, ++chunk) {
      const size_t n = std::min(per, todo.size() - off);
      const std::string base = fmt::format("round{}-{}", round, chunk);
      std::string list;
      for (size_t i = 0; i < n; ++i) list += todo[off + i]->spec->id + "\n";
      write_atomic(dir_ / "slurm" / (base + ".tasks"), list);
      const fs::path script = dir_ / "slurm" / (base + ".sh");
      write_atomic(script, fmt::format("#!/bin/sh\n# SPDX-License-Identifier: Apache-2.0\n# shadecore regress: plan {}, round {}, "
                                       "array chunk {} ({} shards; task K runs line K+1 of {}.tasks)\nexec {} regress-shard --dir {} --tasks {} --task \"$SLURM_ARRAY_TASK_ID\"\n",
                                       plan_, round, chunk, n, base, quote(self_), quote(dir_.string()),
                                       quote((dir_ / "slurm" / (base + ".tasks")).string())));
      fs::permissions(script, fs::perms::owner_exec, fs::perm_options::add);
      std::string array = fmt::format("0-{}", n - 1);
      if (a_.max_running > 0) array += fmt::format("%{}", a_.max_running);
      std::vector<std::string> cmd = {"sbatch", "--parsable", "--array=" + array, "--job-name=shadecore-" + plan_,
                                      "--cpus-per-task=1", "--output=" + (dir_ / "slurm" / "%A_%a.out").string(),
                                      "--chdir=" + dir_.string()};
      if (!a_.partition.empty()) cmd.push_back("--partition=" + a_.partition);
      if (!a_.time_limit.empty()) cmd.push_back("--time=" + a_.time_limit);
      if (!a_.account.empty()) cmd.push_back("--account=" + a_.account);
      for (const auto& x : a_.sbatch_args) cmd.push_back(x);
      cmd.push_back(script.string());
      const proc::Result r = proc::run(cmd);
      if (!r.ok()) {
        cancel(jobs);
        throw std::runtime_error("sbatch failed: " + r.last_line());
      }
      std::string id = r.out.substr(0, r.out.find_first_of(";\n"));
      if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
        cancel(jobs);
        throw std::runtime_error("sbatch printed no job id: " + r.last_line());
      }
      jobs.push_back(id);
      fmt::print("regress: round {}: Slurm array job {} ({} tasks{})\n", round, id, n,
                 a_.max_running > 0 ? fmt::format(", at most {} at once", a_.max_running) : "");
      std::fflush(stdout);
    }
    submitted_.insert(submitted_.end(), jobs.begin(), jobs.end());
    for (auto* st : todo) ++st->attempts;
    // Follow: result files for progress, squeue for what still runs; done when no task is left.
    for (;;) {
      for (int waited = 0; waited < a_.poll_ms; waited += 100) {
        if (proc::interrupt_signal()) {
          cancel(jobs);
          interrupted_exit("cancelled Slurm job(s) " + join(jobs));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      for (auto* st : todo)
        if (!st->done && load_result(dir_, *st) && st->done) ++done_;
      bar_.set(done_);
      bool active = false;
      for (const auto& j : jobs) {
        const proc::Result q = proc::run({"squeue", "-h", "-r", "-j", j, "-o", "%i %t"});
        if (q.ok() && q.out.find_first_not_of(" \n") != std::string::npos) active = true;
        if (!q.ok() && q.out.find("Invalid job id") == std::string::npos && q.err.find("Invalid job id") == std::string::npos)
          active = true;  // squeue itself failed: ask again
      }
      if (!active) break;
    }
    for (auto* st : todo)
      if (!st->done && load_result(dir_, *st) && st->done) ++done_;
    bar_.set(done_);
  }

 private:
  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
    return s;
  }
  void cancel(const std::vector<std::string>& jobs) {
    if (jobs.empty()) return;
    std::vector<std::string> c = {"scancel"};
    c.insert(c.end(), jobs.begin(), jobs.end());
    proc::run(c);
  }
  fs::path dir_;
  std::string self_;
  const RegressArgs& a_;
  std::string plan_;
  io::Progress& bar_;
  size_t& done_;
  long max_array_ = 1001;
  std::vector<std::string> submitted_;
};

json merge(const json& plan, const std::vector<ShardSpec>& specs, const std::vector<ShardState>& st) {
  json jobs = json::array();
  uint64_t tv = 0, tm = 0;
  size_t shards_total = 0, failed = 0, missing = 0;
  bool all_ok = true;
  for (const auto& j : plan["jobs"]) {
    const std::string name = j["name"].get<std::string>();
    uint64_t v = 0, m = 0, digest = 0;
    bool ok = true, has_digest = false, has_q = false;
    double qmax = -1e300, qmin = 1e300;
    size_t n = 0, miss = 0, fail = 0;
    for (size_t i = 0; i < specs.size(); ++i) {
      if (specs[i].job != name) continue;
      ++n;
      const ShardState& s = st[i];
      if (!s.done) {
        ++miss;
        ok = false;
        continue;
      }
      v += s.result.value("vectors", uint64_t{0});
      m += s.result.value("mismatches", uint64_t{0});
      if (s.result.contains("stimulus_digest")) has_digest = true, digest += s.result["stimulus_digest"].get<uint64_t>();
      if (s.result.contains("quant_ulp_max")) {
        has_q = true;
        qmax = std::max(qmax, s.result["quant_ulp_max"].get<double>());
        qmin = std::min(qmin, s.result["quant_ulp_min"].get<double>());
      }
      if (!s.result.value("ok", false) || s.result.value("mismatches", uint64_t{0}) > 0) ok = false, ++fail;
    }
    json jj = {{"name", name}, {"kind", j["kind"]}, {"shards", n}, {"vectors", v}, {"mismatches", m}, {"ok", ok}};
    if (has_digest) jj["stimulus_digest"] = digest;
    if (has_q) jj["quant_ulp_max"] = qmax, jj["quant_ulp_min"] = qmin;
    if (fail) jj["failed_shards"] = fail;
    if (miss) jj["missing_shards"] = miss;
    jobs.push_back(jj);
    tv += v;
    tm += m;
    shards_total += n;
    failed += fail;
    missing += miss;
    all_ok = all_ok && ok;
  }
  return {{"plan", plan.value("name", std::string())},
          {"ok", all_ok},
          {"jobs", jobs},
          {"totals", {{"jobs", jobs.size()}, {"shards", shards_total}, {"vectors", tv}, {"mismatches", tm},
                      {"failed_shards", failed}, {"missing_shards", missing}}}};
}

std::string grouped(uint64_t v) {
  std::string s = std::to_string(v), o;
  for (size_t i = 0; i < s.size(); ++i) {
    if (i && (s.size() - i) % 3 == 0) o += ',';
    o += s[i];
  }
  return o;
}

int run_regress(const RegressArgs& a) {
  if (a.merge_only && (a.local || a.slurm)) throw std::invalid_argument("--merge-only runs nothing: no --local or --slurm");
  if (!a.merge_only && a.local == a.slurm) throw std::invalid_argument("give one backend: --local or --slurm");
  if (a.local && (!a.partition.empty() || !a.time_limit.empty() || !a.account.empty() || !a.sbatch_args.empty() || a.max_running))
    throw std::invalid_argument("--partition, --time, --account, --sbatch-arg and --max-running apply to --slurm only");
  if (a.slurm && a.jobs) throw std::invalid_argument("-j applies to --local only (Slurm places the shards)");
  if (a.until_coverage && !a.coverage) throw std::invalid_argument("--until-coverage needs --coverage");
  if (a.until_coverage && a.merge_only) throw std::invalid_argument("--until-coverage runs shards: not with --merge-only");
  const Targets targets = parse_targets(a.targets);
  std::string plan_file;
  json plan = load_plan(a.plan, plan_file);
  if (a.waivers_given && !a.coverage) throw std::invalid_argument("--waivers applies with --coverage only");
  if (a.coverage && a.waivers_given) coverage::read_waivers(a.waivers);  // a malformed file fails before the run
  if (a.until_coverage && closure_jobs(plan, 1).empty())
    throw std::invalid_argument("--until-coverage: the plan has no random cosim or cosim_lighting job to add seeds of");
  const std::string plan_name = plan.value("name", fs::path(plan_file).stem().string());

  // ---- the run directory: new, or the same plan again (resume), with the closure rounds it already added
  const fs::path dir = fs::absolute(a.out);
  std::error_code ec;
  json closure = json::object();
  if (fs::exists(dir / "plan.json", ec) && fs::exists(dir / "closure.json", ec)) {
    closure = json::parse(read_file(dir / "closure.json"), nullptr, false);
    if (!closure.is_object() || !closure.contains("rounds") || !closure["rounds"].is_array())
      throw std::invalid_argument("--out " + a.out + ": closure.json is not a closure record");
  }
  if (!closure.contains("rounds")) closure["rounds"] = json::array();
  auto extended = [&] {  // the plan with the closure rounds' jobs
    json p = plan;
    for (const auto& r : closure["rounds"])
      for (const auto& j : r["jobs"]) p["jobs"].push_back(j);
    return p;
  };
  std::vector<ShardSpec> specs = expand(extended(), a.coverage);
  bool resume = false;
  if (fs::exists(dir / "plan.json", ec)) {
    const json old = json::parse(read_file(dir / "plan.json"), nullptr, false);
    const json old_sj = fs::exists(dir / "shards.json") ? json::parse(read_file(dir / "shards.json"), nullptr, false) : json();
    if (old != plan || old_sj != shards_json(specs))
      throw std::invalid_argument("--out " + a.out + " holds a run of another plan (or another build); give a new directory");
    if (!closure["rounds"].empty() && !a.until_coverage)
      throw std::invalid_argument("--out " + a.out + " holds a coverage closure (closure.json): resume it with --coverage --until-coverage");
    resume = true;
  } else if (a.merge_only) {
    throw std::invalid_argument("--merge-only: " + a.out + " holds no run of this plan (no plan.json)");
  } else if (fs::exists(dir, ec) && !fs::is_empty(dir, ec)) {
    throw std::invalid_argument("--out " + a.out + " exists and is not a regress run directory; give a new or empty directory");
  }
  for (const char* sub : {"", "shards", "logs"}) {
    fs::create_directories(dir / sub, ec);
    if (ec) throw std::runtime_error("cannot create " + (dir / sub).string() + ": " + ec.message());
  }
  if (::access(dir.c_str(), W_OK) != 0) throw std::runtime_error("cannot write to " + dir.string());
  if (!resume) {
    write_atomic(dir / "shards.json", shards_json(specs).dump(2) + "\n");
    write_atomic(dir / "plan.json", plan.dump(2) + "\n");  // last: it marks a complete run directory
  }

  std::vector<ShardState> st;
  size_t done = 0;
  auto load_states = [&] {
    st.assign(specs.size(), ShardState{});
    done = 0;
    for (size_t i = 0; i < specs.size(); ++i) {
      st[i].spec = &specs[i];
      if (load_result(dir, st[i]) && st[i].done) ++done;
    }
  };
  load_states();
  const std::string self = self_exe();
  fmt::print("regress: plan {} ({}): {} job(s), {} shard(s); {} backend; run directory {}\n", plan_name, plan_file,
             plan["jobs"].size(), specs.size(),
             a.merge_only ? std::string("no (--merge-only)")
                          : a.local ? fmt::format("local, {} at once", cliargs::resolve_parallel(a.jobs)) : std::string("Slurm"),
             dir.string());
  if (resume)
    fmt::print("regress: {}: {} of {} shard(s) already done, {} {}{}\n", a.merge_only ? "merge only" : "resume", done, specs.size(),
               specs.size() - done, a.merge_only ? "missing" : "to run",
               closure["rounds"].empty() ? "" : fmt::format(" ({} closure round(s) recorded)", closure["rounds"].size()));
  std::fflush(stdout);

  proc::InterruptScope scope;
  json runlog = fs::exists(dir / "run.json") ? json::parse(read_file(dir / "run.json"), nullptr, false) : json::object();
  if (!runlog.is_object()) runlog = json::object();
  if (!runlog.contains("invocations")) runlog["invocations"] = json::array();
  json inv = {{"started", now_utc()}, {"backend", a.merge_only ? "none (--merge-only)" : a.local ? "local" : "slurm"}, {"host", host_name()}, {"command", command_line()}};
  const auto t0 = std::chrono::steady_clock::now();
  json ran = json::array(), retried = json::array();
  json merged;
  std::string cov_error;
  json history = json::array();  // --until-coverage: per pass, what was below target
  std::vector<std::string> below;
  std::string stop_reason;
  for (;;) {
    {
      io::Progress bar(specs.size(), a.progress.enabled() && !a.merge_only, "regress");
      bar.set(done);
      std::unique_ptr<Backend> be;
      if (a.merge_only)
        ;  // the report of what is there
      else if (a.local) be = std::make_unique<LocalBackend>(dir, self, cliargs::resolve_parallel(a.jobs), bar, done);
      else be = std::make_unique<SlurmBackend>(dir, self, a, plan_name, bar, done);
      for (int round = 1; round <= (a.merge_only ? 0 : 2); ++round) {
        std::vector<ShardState*> todo;
        for (auto& s : st)
          if (!s.done) todo.push_back(&s);
        if (todo.empty()) break;
        if (round == 2) {
          std::string names;
          for (auto* s : todo) names += (names.empty() ? "" : ", ") + s->spec->id, retried.push_back(s->spec->id);
          fmt::print("regress: retrying {} shard(s) once (lost or failed to run): {}\n", todo.size(), names);
          std::fflush(stdout);
        }
        for (auto* s : todo) ran.push_back(s->spec->id);
        // Slurm names its arrays by round: a closure round's arrays get their own names
        be->run(todo, round + 2 * static_cast<int>(closure["rounds"].size()));
      }
      bar.stop();
    }

    // ---- merge and report
    merged = merge(extended(), specs, st);
    // ---- coverage: the databases of the completed shards, merged (DIR/coverage/merged.dat, summary.json, html/)
    cov_error.clear();
    if (a.coverage) {
      std::vector<std::string> dats, builds;
      size_t want = 0;
      for (const auto& s : st) {
        const fs::path d = dir / "coverage" / "shards" / s.spec->id / "coverage.dat";
        bool uses = false;
        for (const auto& x : s.spec->argv) uses = uses || x.find("{cov}") != std::string::npos;
        if (!uses) continue;
        ++want;
        if (s.done && fs::exists(d, ec)) {
          dats.push_back(d.string());
          builds.push_back(fs::path(s.spec->argv.front()).parent_path().string());  // the simulator's coverage build
        }
      }
      json cj = {{"databases", dats.size()}, {"shards_with_coverage", want}};
      if (dats.empty()) {
        cov_error = "no shard wrote a coverage database";
      } else {
        try {
          // Each shard's points named by their parameterisation, from the map beside the build that ran it (a unit
          // shard's simulator; a lighting shard's cosim did it already), in place: a shard's database is its record.
          for (size_t i = 0; i < dats.size(); ++i) coverage::canonicalise_from_build(dats[i], builds[i]);
          const std::string wf = a.waivers_given ? a.waivers : coverage::waivers_in_use();
          const auto sum = coverage::report(dats, (dir / "coverage").string(), wf, /*html=*/true, /*quiet=*/true);
          fs::rename(dir / "coverage" / "coverage.dat", dir / "coverage" / "merged.dat", ec);
          cj["database"] = "coverage/merged.dat";
          cj["html"] = "coverage/html/index.html";
          cj["waivers"] = wf.empty() ? json() : json(fs::path(wf).filename().string());
          cj["waivers_applied"] = sum["waivers"]["applied"].size();
          cj["modules"] = json::parse(sum["modules"].dump());
          cj["totals"] = json::parse(sum["totals"].dump());
        } catch (const std::exception& e) {
          cov_error = e.what();
        }
      }
      if (!cov_error.empty()) cj["error"] = cov_error;
      if (dats.size() < want) cj["partial"] = true;
      merged["coverage"] = cj;
    }
    if (!a.until_coverage || !cov_error.empty() || !merged["coverage"].contains("modules")) break;
    bool all_done = true;
    for (const auto& s : st) all_done = all_done && s.done;
    below = below_targets(merged["coverage"]["modules"], targets);
    const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    history.push_back({{"round", closure["rounds"].size()}, {"shards", specs.size()}, {"wall_s", spent},
                       {"totals", merged["coverage"]["totals"]}, {"below_target", below.size()}});
    fmt::print("regress: coverage after {} closure round(s): {} module/kind pair(s) below target{}\n", closure["rounds"].size(),
               below.size(), below.empty() ? " — targets met" : "");
    std::fflush(stdout);
    if (below.empty()) break;
    if (!all_done) {
      stop_reason = "shards did not complete";
      break;
    }
    if (static_cast<int>(closure["rounds"].size()) >= a.max_rounds) {
      stop_reason = fmt::format("--max-rounds {} reached", a.max_rounds);
      break;
    }
    if (a.budget_s > 0 && spent >= a.budget_s) {
      stop_reason = fmt::format("--budget {} s spent ({:.0f} s)", a.budget_s, spent);
      break;
    }
    // ---- one more closure round: new seeds for the random jobs, recorded before they run (resumable)
    const int round = static_cast<int>(closure["rounds"].size()) + 1;
    const json jobs = closure_jobs(plan, round);
    closure["rounds"].push_back({{"round", round}, {"added", now_utc()}, {"below_target", below}, {"jobs", jobs}});
    closure["targets"] = targets.pc;
    specs = expand(extended(), a.coverage);
    write_atomic(dir / "shards.json", shards_json(specs).dump(2) + "\n");
    write_atomic(dir / "closure.json", closure.dump(2) + "\n");
    load_states();
    fmt::print("regress: closure round {}: {} random shard(s) with new seeds ({} below target, first: {})\n", round, jobs.size(),
               below.size(), below.front());
    std::fflush(stdout);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  inv["ran"] = ran;
  inv["retried"] = retried;
  inv["wall_s"] = wall;
  runlog["invocations"].push_back(inv);
  write_atomic(dir / "run.json", runlog.dump(2) + "\n");
  if (a.until_coverage && merged.contains("coverage") && merged["coverage"].contains("modules")) {
    // the holes still open, by name, of the kinds below target (coverage/summary.json has every hole)
    json holes = json::object();
    const json sum = json::parse(read_file(dir / "coverage" / "summary.json"), nullptr, false);
    std::set<std::string> short_modules;
    for (const auto& b : below) short_modules.insert(b.substr(0, b.find(' ')));
    if (sum.is_object() && sum.contains("holes"))
      for (const auto& [m, list] : sum["holes"].items())
        if (short_modules.count(m)) holes[m] = list;
    merged["closure"] = {{"targets", targets.pc}, {"met", below.empty()}, {"rounds", closure["rounds"].size()},
                         {"below_target", below}, {"history", history}, {"holes", holes}};
    if (!stop_reason.empty()) merged["closure"]["stopped"] = stop_reason;
  }
  write_atomic(dir / "merged.json", merged.dump(2) + "\n");
  const std::string desc = plan.value("description", std::string());
  std::string md = fmt::format("# shadecore regress: plan {}\n\n{}Run directory `{}`; written {} by `{}` on {} ({} backend); "
                               "this invocation ran {} shard(s) in {:.1f} s wall.\n\n"
                               "| job | kind | shards | vectors | mismatches | shard time (s) | verdict |\n|---|---|---:|---:|---:|---:|---|\n",
                               plan_name, desc.empty() ? "" : desc + "\n\n", dir.string(), now_utc(), command_line(),
                               host_name(), a.merge_only ? "no" : a.local ? "local" : "Slurm", ran.size(), wall);
  std::vector<std::string> problems;
  for (const auto& j : merged["jobs"]) {
    double t = 0;
    for (size_t i = 0; i < specs.size(); ++i)
      if (specs[i].job == j["name"].get<std::string>() && st[i].result.is_object()) t += st[i].result.value("wall_s", 0.0);
    md += fmt::format("| {} | {} | {} | {} | {} | {:.1f} | {} |\n", j["name"].get<std::string>(), j["kind"].get<std::string>(),
                      j["shards"].get<size_t>(), grouped(j["vectors"].get<uint64_t>()), grouped(j["mismatches"].get<uint64_t>()), t,
                      j["ok"].get<bool>() ? "PASS" : (j.contains("missing_shards") ? "INCOMPLETE" : "FAIL"));
  }
  const auto& tot = merged["totals"];
  md += fmt::format("\nTotals: {} vectors, {} mismatches, {} shard(s), {} failed, {} missing.\n", grouped(tot["vectors"].get<uint64_t>()),
                    grouped(tot["mismatches"].get<uint64_t>()), tot["shards"].get<size_t>(), tot["failed_shards"].get<size_t>(),
                    tot["missing_shards"].get<size_t>());
  size_t missing = 0;
  for (const auto& s : st) {
    const std::string log = shard_cmd_note(dir, s.spec->id);
    if (!s.done) {
      ++missing;
      const std::string why = s.result.is_object() ? s.result.value("error", std::string("no result")) : std::string("lost (no result file)");
      problems.push_back(fmt::format("shard {} did not complete after {} attempt(s): {}; log {}", s.spec->id, s.attempts, why, log));
    } else if (!s.result.value("ok", false) || s.result.value("mismatches", uint64_t{0}) > 0) {
      problems.push_back(fmt::format("shard {} FAILED its check ({} mismatches); log {}", s.spec->id,
                                     s.result.value("mismatches", uint64_t{0}), log));
    }
  }
  if (!retried.empty()) {
    md += "\nRetried once (lost or failed to run in the first round):";
    for (const auto& r : retried) md += " `" + r.get<std::string>() + "`";
    md += "\n";
  }
  if (!problems.empty()) {
    md += "\n## Problems\n\n";
    for (const auto& p : problems) md += "- " + p + "\n";
  }
  if (merged.contains("coverage")) {
    const auto& c = merged["coverage"];
    md += fmt::format("\n## Coverage\n\n{} of {} shard database(s) merged into `coverage/merged.dat`{}; HTML `coverage/html/index.html`; "
                      "hit / (total − waived) per module, details in `coverage/summary.json` (docs/coverage.md).\n\n",
                      c["databases"].get<size_t>(), c["shards_with_coverage"].get<size_t>(), c.contains("partial") ? " (PARTIAL)" : "");
    if (c.contains("error")) md += "Coverage ERROR: " + c["error"].get<std::string>() + "\n";
    if (c.contains("modules")) {
      md += "| module | line | branch | toggle | functional |\n|---|---:|---:|---:|---:|\n";
      auto cell = [](const json& row, const char* k) -> std::string {
        if (!row.contains(k)) return "–";
        const auto& x = row[k];
        return fmt::format("{}/{} ({:.2f} %)", x["hit"].get<uint64_t>(), x["total"].get<uint64_t>() - x["waived"].get<uint64_t>(),
                           x["percent"].get<double>());
      };
      for (const auto& row : c["modules"])
        md += fmt::format("| {} | {} | {} | {} | {} |\n", row["module"].get<std::string>(), cell(row, "line"), cell(row, "branch"),
                          cell(row, "toggle"), cell(row, "functional"));
      json t = c["totals"];
      md += fmt::format("| **all** | {} | {} | {} | {} |\n", cell(t, "line"), cell(t, "branch"), cell(t, "toggle"), cell(t, "functional"));
    }
  }
  if (merged.contains("closure")) {
    const auto& c = merged["closure"];
    std::string t;
    for (const auto& [k, v] : c["targets"].items()) t += fmt::format("{}{} {} %", t.empty() ? "" : ", ", k, v.get<double>());
    md += fmt::format("\n## Coverage closure (--until-coverage)\n\nTargets per module: {}. {} closure round(s) of new random seeds "
                      "(closure.json); {}.\n",
                      t, c["rounds"].get<size_t>(),
                      c["met"].get<bool>() ? "every target met"
                                           : fmt::format("**not met** ({})", c.value("stopped", std::string("stopped"))));
    for (const auto& b : c["below_target"]) md += "- below target: " + b.get<std::string>() + "\n";
    size_t n = 0;
    for (const auto& [m, list] : c["holes"].items()) n += list.size();
    if (n) md += fmt::format("\n{} hole(s) in those modules, by name, in merged.json \"closure\".\"holes\" (and coverage/summary.json).\n", n);
  }
  write_atomic(dir / "summary.md", md);
  for (const auto& j : merged["jobs"])
    fmt::print("regress: {:<28} {:>4} shard(s) {:>16} vectors {:>8} mismatches  {}\n", j["name"].get<std::string>(),
               j["shards"].get<size_t>(), grouped(j["vectors"].get<uint64_t>()), grouped(j["mismatches"].get<uint64_t>()),
               j["ok"].get<bool>() ? "PASS" : (j.contains("missing_shards") ? "INCOMPLETE" : "FAIL"));
  for (const auto& p : problems) fmt::print("regress: {}\n", p);
  fmt::print("regress: {}: {} vectors, {} mismatches; {:.1f} s wall; report {}/merged.json, {}/summary.md\n",
             missing ? "INCOMPLETE" : (merged["ok"].get<bool>() ? "PASS" : "FAIL"), grouped(tot["vectors"].get<uint64_t>()),
             grouped(tot["mismatches"].get<uint64_t>()), wall, dir.string(), dir.string());
  std::fflush(stdout);
  if (merged.contains("coverage") && merged["coverage"].contains("modules")) {
    const auto& t = merged["coverage"]["totals"];
    auto pc = [&t](const char* k) { return t.contains(k) ? fmt::format("{:.2f} %", t[k]["percent"].get<double>()) : std::string("–"); };
    fmt::print("regress: coverage: line {}, branch {}, toggle {}, functional {} of non-waived points ({} databases); "
               "{}/coverage/summary.json, {}/coverage/html/index.html\n",
               pc("line"), pc("branch"), pc("toggle"), pc("functional"), merged["coverage"]["databases"].get<size_t>(),
               dir.string(), dir.string());
    std::fflush(stdout);
  }
  if (merged.contains("closure")) {
    const auto& c = merged["closure"];
    size_t shown = 0;
    for (const auto& b : c["below_target"]) {
      if (shown++ == 12) {
        fmt::print("regress: ... and {} more below target (merged.json \"closure\")\n", c["below_target"].size() - 12);
        break;
      }
      fmt::print("regress: below target: {}\n", b.get<std::string>());
    }
    for (const auto& [m, list] : c["holes"].items()) {
      std::string first;
      for (size_t i = 0; i < list.size() && i < 3; ++i) first += (i ? "; " : "") + list[i].get<std::string>();
      fmt::print("regress: holes of {}: {}{}\n", m, first, list.size() > 3 ? fmt::format(" (and {} more)", list.size() - 3) : "");
    }
    fmt::print("regress: coverage closure: {} after {} closure round(s){}\n", c["met"].get<bool>() ? "targets met" : "targets NOT met",
               c["rounds"].get<size_t>(), c.contains("stopped") ? " (" + c["stopped"].get<std::string>() + ")" : "");
    std::fflush(stdout);
  }
  if (missing) throw std::runtime_error(fmt::format("{} shard(s) did not complete (named above with their logs)", missing));
  if (!cov_error.empty()) throw std::runtime_error("coverage: " + cov_error);
  if (!merged["ok"].get<bool>()) throw CheckFailed("regression FAILED (see " + (dir / "summary.md").string() + ")");
  if (merged.contains("closure") && !merged["closure"]["met"].get<bool>())
    throw CheckFailed(fmt::format("coverage targets not met after {} closure round(s): {} module/kind pair(s) below target",
                                  merged["closure"]["rounds"].get<size_t>(), merged["closure"]["below_target"].size()));
  return 0;
}

}  // namespace

void add_regress(CLI::App& app) {
  auto a = std::make_shared<RegressArgs>();
  using namespace cliargs;
  auto* sub = app.add_subcommand("regress", "run a regression plan in shards, locally or as Slurm array jobs, and merge the results (docs/regress.md)");
  sub->add_option("--plan", a->plan, "a named plan (smoke, nightly: regress/plans/) or a plan file")->required()->check(NonEmpty("plan"));
  sub->add_option("--out", a->out, "run directory (new, or a previous run of the same plan: resume)")->required()->check(NonEmpty("path"));
  sub->add_flag("--local", a->local, "run the shards on this machine");
  sub->add_option("-j,--jobs", a->jobs, "--local: shards at once (0 = one per core; at most 64)")->check(Int(0, kMaxParallel));
  sub->add_flag("--slurm", a->slurm, "submit the shards as one Slurm array job (sbatch; SLURM_CONF as for any Slurm command)");
  sub->add_option("--partition", a->partition, "--slurm: partition")->check(NonEmpty("partition"));
  sub->add_option("--time", a->time_limit, "--slurm: time limit per shard (sbatch --time)")->check(NonEmpty("time"));
  sub->add_option("--account", a->account, "--slurm: account")->check(NonEmpty("account"));
  sub->add_option("--sbatch-arg", a->sbatch_args, "--slurm: one more sbatch argument (repeatable), e.g. --sbatch-arg=--mem=2G")
      ->check(NonEmpty("sbatch argument"));
  sub->add_option("--max-running", a->max_running, "--slurm: at most this many tasks of the array at once (--array=...%K)")
      ->check(Int(1, 100000));
  sub->add_flag("--merge-only", a->merge_only,
                "run nothing: write the merged report of the shards --out holds (missing ones: INCOMPLETE, exit 1)");
  sub->add_option("--poll", a->poll_ms, "--slurm: milliseconds between squeue polls (default 2000)")->check(Int(100, 600000));
  sub->add_flag("--coverage", a->coverage,
                "run the coverage builds of the models; merge the shards' databases into DIR/coverage (merged.dat, "
                "summary.json, html/) and add the per-module summary to merged.json (docs/coverage.md)");
  auto* wopt = sub->add_option("--waivers", a->waivers, "--coverage: the waiver file (default config/coverage_waivers.json)")
                   ->check(NonEmpty("path"));
  sub->add_flag("--until-coverage", a->until_coverage,
                "--coverage: after the plan, add closure rounds (one shard of every random job under a new seed) until "
                "every module meets --coverage-target or --max-rounds / --budget runs out; report the holes (exit 2 if not met)");
  sub->add_option("--coverage-target", a->targets,
                  "--until-coverage: per-module targets, KIND=PERCENT,... (default line=100,branch=100,toggle=95,functional=100)")
      ->check(NonEmpty("targets"));
  sub->add_option("--max-rounds", a->max_rounds, "--until-coverage: closure rounds at most (default 8)")->check(Int(0, 1000));
  sub->add_option("--budget", a->budget_s, "--until-coverage: wall seconds after which no further round starts (default: none)")
      ->check(CLI::Range(0.0, 1e9));
  a->progress.add(sub);
  sub->callback([a, wopt] {
    a->waivers_given = wopt->count() > 0;
    const int rc = run_regress(*a);
    (void)rc;
  });

  // The shard runner, what every backend starts (not for users: no help line).
  auto sd = std::make_shared<std::string>(), sid = std::make_shared<std::string>(), tasks = std::make_shared<std::string>();
  auto task = std::make_shared<long>(-1);
  auto* sh = app.add_subcommand("regress-shard", "");
  sh->group("");
  sh->add_option("--dir", *sd, "run directory")->required();
  auto* o1 = sh->add_option("--shard", *sid, "shard id");
  auto* o2 = sh->add_option("--tasks", *tasks, "task list (Slurm array)");
  sh->add_option("--task", *task, "task index");
  o1->excludes(o2);
  sh->callback([sd, sid, tasks, task] {
    if (sid->empty() && tasks->empty()) throw std::invalid_argument("regress-shard needs --shard ID or --tasks FILE --task K");
    run_shard(*sd, *sid, *tasks, *task);
  });
}

}  // namespace shadecore::cli

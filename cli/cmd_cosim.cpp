// SPDX-License-Identifier: Apache-2.0
// shadecore cosim — co-simulate the RTL (rtl/sc_specular.v, Verilated + SystemC) against the C model.
//
// The CLI cannot link SystemC (libsystemc defines main()), so it runs the per-configuration
// simulator executables sim/shadecore_cosim_<config> as subprocesses — their paths come from the
// build (SHADECORE_COSIM_SIMS) — splits the work into shards (exhaustive: the n range; random: the
// transaction indices, every shard with the same seed and its own --first, so the stimulus of
// transaction i depends on (seed, i) only; directed: one shard), runs them in parallel and merges their
// "COSIM-RESULT {json}" lines. Every argument is checked here before any simulator starts.
// Exit 0 only if every shard passed; 2 if the co-simulation ran and FAILED (the JSON and the waveform
// that record it are written); 1 for any error (nothing written).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "shadecore/common/args.hpp"
#include "commands.hpp"
#include "coverage.hpp"
#include "light_rtl.hpp"
#include "output.hpp"
#include "shadecore/common/progress.hpp"
#include "shadecore/common/subprocess.hpp"
#include "shadecore/units/coef.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/units/hard_cases.hpp"
#include "shadecore/stimulus/specular.hpp"
#include "shadecore/unit.hpp"

namespace shadecore::cli {
namespace {

struct CosimArgs {
  std::string variant = "cs16";
  std::string config;
  std::string cutoff = "theta_cr";
  std::string n_range = "16..1024";
  std::string mode = "directed";
  uint64_t count = 100000;
  uint64_t seed = 0;
  double in_stall = 0.0, out_stall = 0.0;
  double mat_rate = -1.0;  // random mode: probability per cycle of a material change (< 0: the simulator's default)
  long long reset_at = -2;
  int shards = 0;
  std::string trace, json_path;
  std::string coverage_dir;  // --coverage DIR: the coverage build, its merged database, summary and HTML there
  int show = 5;
  bool norm = false;              // sc_specular ENERGY = 1 (energy-normalised output, docs/spec.md §7)
  std::string coef_model, coef_kind;
  ProgressFlags progress;
  // Given explicitly (options a mode or a setting would ignore are errors).
  bool n_given = false, count_given = false, shards_given = false, coef_model_given = false, coef_given = false;
};

std::map<std::string, std::string> simulators() {
  std::map<std::string, std::string> m;
#ifdef SHADECORE_COSIM_SIMS
  std::stringstream ss(SHADECORE_COSIM_SIMS);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq != std::string::npos) m[item.substr(0, eq)] = item.substr(eq + 1);
  }
#endif
  return m;
}

struct Shard {
  std::vector<std::string> argv;
  std::vector<std::string> lines;  // stdout lines other than COSIM-RESULT / COSIM-PROGRESS
  uint64_t progress = 0;
  int status = -1;
  std::string err;
  nlohmann::json result;
};

void take_line(Shard& s, std::string line) {
  if (!line.empty() && line.back() == '\n') line.pop_back();
  if (line.rfind("COSIM-RESULT ", 0) == 0) {
    try {
      s.result = nlohmann::json::parse(line.substr(13));
    } catch (const std::exception&) {
      s.lines.push_back(line);
    }
  } else if (line.rfind("COSIM-PROGRESS ", 0) == 0) {
    uint64_t v = 0;
    if (cliargs::parse_u64(line.substr(15), v)) s.progress = v;
  } else {
    s.lines.push_back(line);
  }
}

// Runs every shard at once through the common runner (shadecore/common/subprocess.hpp: SIGINT ignored in
// the simulators, which this process's interrupt cleanup stops), feeding the progress bar from their
// COSIM-PROGRESS lines.
void run_all(std::vector<Shard>& shards, io::Progress& bar) {
  proc::Pool pool;
  for (auto& s : shards) {
    proc::Options o;
    o.env = {{"SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1"}};
    Shard* sp = &s;
    o.on_line = [sp](const std::string& line) { take_line(*sp, line); };
    pool.start(s.argv, o);
  }
  while (pool.running() > 0) {
    pool.poll(500);
    uint64_t done = 0;
    for (const auto& s : shards) done += s.progress;
    bar.set(done);
  }
  for (size_t i = 0; i < shards.size(); ++i) {
    shards[i].status = pool.result(i).status;
    shards[i].err = pool.result(i).err;
  }
}

std::string first_line(const std::string& text) {
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) return line;
  return {};
}

void run_cosim(const CosimArgs& a) {
  // ---- validate everything before starting anything
  const NamedConfig* found = &config_named(a.config);
  const std::string cfg(found->name);
  Unit unit(parse_variant(a.variant), found->format, parse_cutoff_name(a.cutoff));
  const auto [n_lo, n_hi] = cliargs::parse_n_range(a.n_range);
  if (a.mode != "exhaustive" && a.mode != "random" && a.mode != "directed")
    throw std::invalid_argument("unknown mode '" + a.mode + "' (known: exhaustive, random, directed)");
  if (a.mode == "directed" && a.n_given)
    throw std::invalid_argument("--n does not apply to --mode directed (the hard cases carry their own n)");
  if (a.mode != "random" && a.mat_rate >= 0.0)
    throw std::invalid_argument("--mat-rate applies to --mode random only");
  if (a.mode == "exhaustive" && a.count_given)
    throw std::invalid_argument("--count does not apply to --mode exhaustive (every code of every n)");
  if (a.shards_given && a.shards != 1 && (a.mode == "directed" || !a.trace.empty()))
    throw std::invalid_argument("--shards applies to exhaustive and random runs without --trace (those run one simulator)");
  if (!a.norm && (a.coef_model_given || a.coef_given))
    throw std::invalid_argument("--coef-model and --coef apply with --norm only");
  std::string norm_text;
  if (a.norm) {
    if (unit.variant() != VariantId::cs16 || unit.cutoff() != Cutoff::ThetaCr)
      throw std::invalid_argument("--norm is built for --variant cs16 --cutoff theta_cr only");
    const bool one_model = a.coef_model_given && a.coef_model != "all";
    if (a.coef_given && !one_model)
      throw std::invalid_argument("--coef needs --coef-model MODEL (with all, the kind is picked per material)");
    const CoefKind kind = parse_coef_kind(a.coef_given ? a.coef_kind : "fitted");
    if (one_model) {
      const Model m = parse_model(a.coef_model);
      norm_text = fmt::format(" norm: {} {} coefficient", info(m).key, to_string(kind));
    } else {
      norm_text = " norm: every model and kind (picked per material from n)";
    }
    unit.set_energy(true, one_model ? static_cast<int>(parse_model(a.coef_model)) : -1, kind);
  }
  // Outputs: checked now, written together at the end (the waveform through a temporary file the
  // simulator writes).
  io::OutputSet outs;
  const int json_out = a.json_path.empty() ? -1 : outs.file("--json", a.json_path);
  const int trace_out = a.trace.empty() ? -1 : outs.file("--trace", a.trace, /*allow_stream=*/false);
  const auto sims = simulators();
  if (sims.empty()) throw std::runtime_error("this shadecore was built without the RTL co-simulation (SHADECORE_WITH_RTL=OFF)");
  const auto it = sims.find(cfg);
  if (it == sims.end()) throw std::runtime_error("no simulator built for config '" + cfg + "'");
  std::string sim = it->second;
  // --coverage DIR: the coverage build of this one model instead (built on demand, cached), each shard writing
  // its database into a scratch directory under DIR, merged there at the end (docs/coverage.md).
  std::string cov_tmp;
  if (!a.coverage_dir.empty()) {
    coverage::check_output_dir(a.coverage_dir, "--coverage");
    sim = coverage::ensure_unit({a.variant, cfg, a.cutoff, a.norm}, /*bare=*/false, false).exe;
    cov_tmp = (std::filesystem::path(a.coverage_dir) / fmt::format(".shards.{}", ::getpid())).string();
    std::error_code ec;
    std::filesystem::create_directories(cov_tmp, ec);
    if (ec) throw std::runtime_error("--coverage: cannot create " + cov_tmp + ": " + ec.message());
  }
  if (::access(sim.c_str(), X_OK) != 0)
    throw std::runtime_error("simulator " + sim + " not built (cmake --build <build dir>)");

  uint64_t seed = a.seed;
  if (seed == 0) {
    seed = (static_cast<uint64_t>(std::random_device{}()) << 32) ^ std::random_device{}();
    if (seed == 0) seed = 1;
  }
  int shards = cliargs::resolve_parallel(a.shards);
  if (trace_out >= 0 || a.mode == "directed") shards = 1;  // one waveform; the list is short
  if (a.mode == "exhaustive") shards = std::min(shards, n_hi - n_lo + 1);
  if (a.mode == "random") shards = static_cast<int>(std::min<uint64_t>(shards, a.count));
  const std::string trace_tmp = trace_out >= 0 ? outs.produce_path(trace_out) : std::string();

  // ---- build the shards
  const Format& f = found->format;
  uint64_t planned = 0;
  std::vector<Shard> jobs(shards);
  for (int i = 0; i < shards; ++i) {
    auto& v = jobs[i].argv;
    v = {sim, "--variant", a.variant, "--cutoff", a.cutoff, "--mode", a.mode, "--quiet", "--progress-lines",
         "--in-stall", fmt::format("{}", a.in_stall), "--out-stall", fmt::format("{}", a.out_stall),
         "--show", std::to_string(a.show)};
    if (a.mode == "exhaustive") {
      // Equal numbers of exponents per shard (every n costs the same: 2^F + 5 codes).
      const int total = n_hi - n_lo + 1;
      const int lo = n_lo + static_cast<int>(static_cast<long long>(total) * i / shards);
      const int hi = n_lo + static_cast<int>(static_cast<long long>(total) * (i + 1) / shards) - 1;
      v.insert(v.end(), {"--n", fmt::format("{}..{}", lo, hi), "--seed", std::to_string(seed)});
    } else if (a.mode == "random") {
      if (a.mat_rate >= 0.0) v.insert(v.end(), {"--mat-rate", fmt::format("{}", a.mat_rate)});
      // Shard i runs transactions [first, first + c) of the one seeded run.
      const uint64_t base = a.count / shards, extra = a.count % shards, k = static_cast<uint64_t>(i);
      const uint64_t c = base + (k < extra ? 1 : 0);
      const uint64_t first = k * base + std::min(k, extra);
      v.insert(v.end(), {"--n", fmt::format("{}..{}", n_lo, n_hi), "--count", std::to_string(c), "--first",
                         std::to_string(first), "--seed", std::to_string(seed)});
    } else {
      v.insert(v.end(), {"--count", std::to_string(a.count), "--seed", std::to_string(seed)});
    }
    // The mid-stream reset is a global transaction index: every shard gets the same one (random mode
    // default: drawn from the seed in the middle half of the whole run), and only the shard holding it resets.
    if (a.reset_at != -2)
      v.insert(v.end(), {"--reset-at", std::to_string(a.reset_at)});
    else if (a.mode == "random")
      v.insert(v.end(), {"--reset-at", std::to_string(stimulus::default_reset_index(seed, a.count))});
    if (!trace_tmp.empty()) v.insert(v.end(), {"--trace", trace_tmp});
    if (!cov_tmp.empty()) v.insert(v.end(), {"--coverage", fmt::format("{}/shard{}.dat", cov_tmp, i)});
    if (a.norm) v.push_back("--norm");
    if (a.coef_model_given) v.insert(v.end(), {"--coef-model", a.coef_model});
    if (a.coef_given) v.insert(v.end(), {"--coef", a.coef_kind});
  }
  if (a.mode == "exhaustive") {
    planned = static_cast<uint64_t>(n_hi - n_lo + 1) * static_cast<uint64_t>(f.one() + 1 + 4);
  } else if (a.mode == "random") {
    planned = a.count;
  } else {
    const uint64_t len = hard_cases(f).size();
    planned = len * (a.count > len ? (a.count + len - 1) / len : 1);
  }
  fmt::print("cosim: {} {} ({}, F={} G={}) cutoff {}{} mode {} n {}..{}{} seed {} in-stall {} out-stall {}, {} shard(s)\n",
             a.variant, cfg, sim, f.frac, f.guard, a.cutoff, norm_text, a.mode, n_lo, n_hi,
             a.mode == "exhaustive" ? "" : fmt::format(" count {}", a.count), seed, a.in_stall, a.out_stall, shards);
  std::fflush(stdout);

  const auto t0 = std::chrono::steady_clock::now();
  io::Progress bar(planned, a.progress.enabled(), "cosim");
  run_all(jobs, bar);
  bar.stop();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // ---- merge
  uint64_t vectors = 0, mismatches = 0, lost = 0, dup = 0, lat_err = 0, proto = 0, dropped = 0, cycles = 0, digest = 0;
  uint64_t lat_min = ~uint64_t{0}, lat_max = 0;
  bool ok = true;
  std::string causes;
  nlohmann::json shard_json = nlohmann::json::array(), first = nlohmann::json::array();
  for (int i = 0; i < shards; ++i) {
    const Shard& s = jobs[i];
    if (s.result.is_null()) {
      // The simulator rejected its arguments or crashed: pass its words on, one line.
      const std::string said = first_line(s.err);
      throw std::runtime_error(fmt::format("simulator shard {} exited with status {} and no result{}", i, s.status,
                                           said.empty() ? "" : ": " + said));
    }
    const auto& r = s.result;
    const bool shard_ok = s.status == 0 && r.value("ok", false);
    ok = ok && shard_ok;
    vectors += r.value("vectors", uint64_t{0});
    mismatches += r.value("mismatches", uint64_t{0});
    lost += r.value("lost", uint64_t{0});
    dup += r.value("duplicated_or_reordered", uint64_t{0});
    lat_err += r.value("latency_errors", uint64_t{0});
    proto += r.value("protocol_errors", uint64_t{0});
    dropped += r.value("dropped_by_reset", uint64_t{0});
    cycles += r.value("cycles", uint64_t{0});
    digest += r.value("stimulus_digest", uint64_t{0});
    const std::string cause = r.value("cause", std::string());
    if (!cause.empty() && causes.find(cause) == std::string::npos) causes += (causes.empty() ? "" : "; ") + cause;
    if (r.value("vectors", uint64_t{0}) > 0) lat_min = std::min(lat_min, r.value("latency_min", uint64_t{0}));
    lat_max = std::max(lat_max, r.value("latency_max", uint64_t{0}));
    for (const auto& m : r["first_mismatches"])
      if (first.size() < static_cast<size_t>(a.show)) first.push_back(m);
    shard_json.push_back(r);
    if (!shard_ok) {
      // Print what the failing shard said (errors, mismatches, the reproduce line).
      for (const auto& line : s.lines) fmt::print("  [shard {}] {}\n", i, line);
      if (!s.err.empty()) fmt::print("  [shard {}] stderr: {}\n", i, first_line(s.err));
    }
  }
  if (lat_min == ~uint64_t{0}) lat_min = 0;
  for (const auto& m : first)
    fmt::print("  mismatch: n={} code={} expected={} got={}\n", m.value("n", 0), m.value("code", 0LL),
               m.value("expected", 0u), m.value("got", 0u));
  const double vps = wall > 0 ? static_cast<double>(vectors) / wall : 0.0;
  fmt::print("cosim: {}{}: {} vectors, {} mismatches, {} lost, {} duplicated/reordered, {} latency errors, "
             "{} protocol errors, {} dropped by mid-stream reset; latency {}..{} cycles (spec {}); "
             "{} cycles; {:.2f} s wall, {:.3g} vectors/s\n",
             ok ? "PASS" : "FAIL", causes.empty() ? "" : " (" + causes + ")", vectors, mismatches, lost, dup, lat_err,
             proto, dropped, lat_min, lat_max, unit.latency(), cycles, wall, vps);
  if (json_out >= 0) {
    nlohmann::json j = {{"ok", ok},
                        {"cause", causes},
                        {"variant", a.variant},
                        {"config", cfg},
                        {"frac", f.frac},
                        {"guard", f.guard},
                        {"cutoff", a.cutoff},
                        {"mode", a.mode},
                        {"norm", a.norm},
                        {"n_lo", n_lo},
                        {"n_hi", n_hi},
                        {"seed", seed},
                        {"in_stall", a.in_stall},
                        {"out_stall", a.out_stall},
                        {"shards", shards},
                        {"planned", planned},
                        {"stimulus_digest", digest},
                        {"vectors", vectors},
                        {"mismatches", mismatches},
                        {"lost", lost},
                        {"duplicated_or_reordered", dup},
                        {"latency_errors", lat_err},
                        {"protocol_errors", proto},
                        {"dropped_by_reset", dropped},
                        {"latency_spec", unit.latency()},
                        {"latency_min", lat_min},
                        {"latency_max", lat_max},
                        {"cycles", cycles},
                        {"wall_s", wall},
                        {"vectors_per_s", vps},
                        {"first_mismatches", first},
                        {"shard_results", shard_json}};
    if (a.norm) {
      j["coef_model"] = a.coef_model_given ? a.coef_model : "all";
      j["coef"] = a.coef_given ? a.coef_kind : (a.coef_model_given && a.coef_model != "all" ? "fitted" : "per material");
    }
    outs.set(json_out, j.dump(2) + "\n");
  }
  // The coverage of the run (a failing one too: it is part of its record).
  if (!cov_tmp.empty()) {
    std::vector<std::string> dats;
    for (int i = 0; i < shards; ++i) dats.push_back(fmt::format("{}/shard{}.dat", cov_tmp, i));
    struct Cleanup {
      std::string d;
      ~Cleanup() {
        std::error_code ec;
        std::filesystem::remove_all(d, ec);
      }
    } cleanup{cov_tmp};
    // each point's module named by its parameterisation (the map beside the coverage build) before the merge
    for (const auto& d : dats) coverage::canonicalise_from_build(d, std::filesystem::path(sim).parent_path().string());
    coverage::report(dats, a.coverage_dir, coverage::waivers_in_use(), /*html=*/true, /*quiet=*/false);
  }
  // A FAIL verdict is a completed run: its JSON and waveform are the record of the failure.
  outs.commit();
  if (trace_out >= 0) fmt::print("cosim: waveform written to {}\n", a.trace);
  std::fflush(stdout);
  if (!ok)
    throw CheckFailed(fmt::format("co-simulation FAILED{} ({} mismatches, {} lost, {} duplicated/reordered, {} latency, "
                                  "{} protocol errors)",
                                  causes.empty() ? "" : ": " + causes, mismatches, lost, dup, lat_err, proto));
}

}  // namespace

void add_cosim(CLI::App& app) {
  auto args = std::make_shared<CosimArgs>();
  using namespace cliargs;
  auto* sub = app.add_subcommand(
      "cosim", "co-simulate the Verilated RTL against the C model, bit for bit (runs sim/shadecore_cosim_<config>)");
  sub->add_option("--variant", args->variant, "unit (config/configs.json variants)")->check(NonEmpty("unit name"));
  sub->add_option("--config", args->config, "named width configuration (narrow, default, wide)")
      ->check(NonEmpty("config name"));
  sub->add_option("--cutoff", args->cutoff, "theta_cr | sign_clamp")->check(NonEmpty("cut-off"));
  auto* n_opt = sub->add_option("--n", args->n_range, "exponent range LO..HI or N (default 16..1024; exhaustive, random)")->check(NonEmpty("range"));
  sub->add_option("--mode", args->mode, "exhaustive | random | directed (default directed)")->check(NonEmpty("mode"));
  auto* count_opt = sub->add_option("--count", args->count, "random: transactions in total; directed: minimum items")
                        ->check(UInt(1, 1000000000000ull));
  sub->add_option("--seed", args->seed,
                  "random seed, 1..2^64-1 (default or 0: pick one and print it); the same seed gives the same "
                  "stimulus whatever the shard count")
      ->check(UInt(0));
  sub->add_option("--in-stall", args->in_stall, "probability per cycle of an input gap, in [0, 1)")
      ->check(Probability(false));
  sub->add_option("--out-stall", args->out_stall, "probability per cycle of out_ready low, in [0, 1)")
      ->check(Probability(false));
  sub->add_option("--mat-rate", args->mat_rate,
                  "random mode: probability per transaction of a material change before it, in [0, 1) (default "
                  "0.01; a table unit's change is a load of E cycles); a function of (seed, transaction index)")
      ->check(Probability(false));
  sub->add_option("--reset-at", args->reset_at,
                  "rst_ni pulse once, before the transaction of this global index (-1 none; default: random, drawn from the seed in the middle half; directed, half way)")
      ->check(ResetAt());
  auto* shards_opt = sub->add_option("--shards", args->shards, "parallel simulator processes (0 = one per core; at most 64)")
                         ->check(Int(0, kMaxParallel));
  sub->add_option("--trace", args->trace,
                  "FST waveform file (specular: the whole run, one shard; lighting: the cycles around the first failure, "
                  "from a re-run of a failed run on the trace build — nothing on a PASS)")
      ->check(NonEmpty("path"));
  auto trace_window = std::make_shared<uint64_t>(200);
  sub->add_option("--trace-window", *trace_window,
                  "--core lighting --trace: cycles kept before and after the first failure (default 200)")
      ->check(UInt(1, 1000000));
  // The lighting simulators' self-test (corrupt one observed output; the run must FAIL), for the tests of the
  // windowed --trace (ctest sim.light.trace.*); no help line.
  auto inject = std::make_shared<std::string>();
  auto inject_at = std::make_shared<uint64_t>(0);
  sub->add_option("--inject", *inject, "")->check(CLI::IsMember({"value", "drop", "dup"}))->group("");
  sub->add_option("--inject-at", *inject_at, "")->check(UInt(1, uint64_t{1} << 40))->group("");
  auto trace_all = std::make_shared<bool>(false);
  sub->add_flag("--trace-all", *trace_all, "--core lighting --trace: the whole run (on the trace build), pass or fail");
  sub->add_option("--coverage", args->coverage_dir,
                  "run the coverage build of the model (built on demand, cached) and write DIR/coverage.dat (merged over "
                  "the shards), DIR/summary.json and DIR/html (docs/coverage.md)")
      ->check(NonEmpty("directory"));
  // regress's shards: the database alone (the merge after the run makes the report); no help line.
  auto cov_raw = std::make_shared<bool>(false);
  sub->add_flag("--coverage-db-only", *cov_raw, "")->group("");
  sub->add_option("--json", args->json_path, "write the merged result as JSON (atomically)")->check(NonEmpty("path"));
  sub->add_flag("--norm", args->norm, "energy-normalised output: sc_specular ENERGY = 1 (cs16, theta_cr)");
  auto* cm_opt = sub->add_option("--coef-model", args->coef_model,
                                 "with --norm: all (default) | phong | phong_mod | blinn | blinn_mod | blinn_ndf | blinn_hf")->check(NonEmpty("model"));
  auto* coef_opt = sub->add_option("--coef", args->coef_kind, "with --norm and one --coef-model: fitted | classical")->check(NonEmpty("coefficient kind"));
  sub->add_option("--show", args->show, "mismatches printed in full")->check(Int(0, 1000));
  args->progress.add(sub);
  // The lighting core (docs/lighting.md): --core lighting --features NAME|FILE, built on demand per
  // feature set (cli/light_rtl.cpp); random or directed mode, stalls, seed, --json.
  auto core = std::make_shared<std::string>("specular");
  auto features = std::make_shared<std::string>();
  // One name for one thing (issue 38): specular|lighting as in `vectors` and `handoff`; `unit`, the earlier name,
  // stays an alias for a release (deprecated; README, docs/cli.md).
  sub->add_option("--core", *core,
                  "specular (default: rtl/sc_specular.v) | lighting (rtl/sc_light.v); 'unit' is a deprecated alias of specular")
      ->check(CLI::IsMember({"specular", "lighting", "unit"}));
  auto* feat_opt = sub->add_option("--features", *features, "--core lighting: a named feature set of config/configs.json or a JSON file")->check(NonEmpty("feature set"));
  auto harness = std::make_shared<std::string>("systemc");
  auto* harness_opt = sub->add_option("--harness", *harness,
                                      "--core lighting: systemc (default: the SystemC testbench) | bare (the same RTL, "
                                      "stimulus and checks in a plain C++ loop without SystemC, for long random runs) | axi "
                                      "(the bare harness through the AXI wrapper rtl/sc_light_axi.v: AXI4-Lite registers, "
                                      "AXI4-Stream fragments and colours; docs/handoff.md)")
                          ->check(CLI::IsMember({"systemc", "bare", "axi"}));
  auto axi = std::make_shared<bool>(false);
  auto* axi_opt = sub->add_flag("--axi", *axi, "--core lighting: the same as --harness axi");
  auto write_rate = std::make_shared<double>(-1.0);
  auto* write_rate_opt =
      sub->add_option("--write-rate", *write_rate,
                      "--core lighting, random: probability per fragment of a register-write burst (a new light program, "
                      "material or mode) before it, in [0, 1) (default 0.002: docs/lighting.md)")
          ->check(CLI::Range(0.0, 0.999999));
  auto first = std::make_shared<uint64_t>(0);
  auto* first_opt = sub->add_option("--first", *first,
                                    "--core lighting, random: global index of the first fragment (a shard of a longer run "
                                    "with the same seed and --reset-at)")
                        ->check(UInt(0, uint64_t{1} << 40));
  sub->callback([args, n_opt, count_opt, shards_opt, cm_opt, coef_opt, core, features, feat_opt, harness, harness_opt, axi, axi_opt,
                 write_rate, write_rate_opt, first, first_opt, cov_raw, trace_window, trace_all, inject, inject_at, sub] {
    if (*core == "lighting") {
      for (const char* unit_only : {"--variant", "--config", "--cutoff", "--n", "--norm", "--coef-model", "--coef",
                                    "--shards", "--mat-rate"})
        if (sub->count(unit_only) > 0)
          throw std::invalid_argument(std::string(unit_only) + " does not apply to --core lighting: the feature set fixes the unit and the widths "
                                      "(choose one with --features NAME|FILE; docs/lighting.md)");
      LightCosimArgs la;
      la.features = features->empty() ? "full" : *features;
      la.mode = args->mode == "directed" && !sub->count("--mode") ? "random" : args->mode;
      la.count = args->count;
      la.seed = args->seed;
      la.in_stall = args->in_stall;
      la.out_stall = args->out_stall;
      la.json_path = args->json_path;
      if (*axi && harness_opt->count() > 0 && *harness != "axi")
        throw std::invalid_argument("--axi is --harness axi: not with --harness " + *harness);
      la.harness = *axi ? "axi" : *harness;
      la.first = *first;
      la.write_rate = *write_rate;
      if (write_rate_opt->count() > 0 && la.mode != "random") throw std::invalid_argument("--write-rate applies to --mode random only");
      la.coverage_dir = args->coverage_dir;
      la.coverage_report = !*cov_raw;
      la.trace_path = args->trace;
      la.trace_window = *trace_window;
      la.trace_all = *trace_all;
      la.inject = *inject;
      la.inject_at = *inject_at;
      if (sub->count("--inject-at") > 0 && la.inject.empty()) throw std::invalid_argument("--inject-at needs --inject");
      if ((sub->count("--trace-window") > 0 || la.trace_all) && la.trace_path.empty())
        throw std::invalid_argument("--trace-window and --trace-all need --trace FILE");
      if (sub->count("--trace-window") > 0 && la.trace_all)
        throw std::invalid_argument("--trace-window cuts the waveform around the first failure, --trace-all keeps the "
                                    "whole run: one or the other");
      if (*cov_raw && la.coverage_dir.empty()) throw std::invalid_argument("--coverage-db-only needs --coverage DIR");
      la.reset_at = sub->count("--reset-at") > 0 ? static_cast<int64_t>(args->reset_at) : -2;
      if (la.first != 0 && la.mode != "random") throw std::invalid_argument("--first applies to --mode random only");
      if (lighting_cosim(la) != 0) throw CheckFailed("cosim: FAIL (lighting core '" + la.features + "')");
      return;
    }
    if (feat_opt->count() > 0) throw std::invalid_argument("--features needs --core lighting");
    if (axi_opt->count() > 0) throw std::invalid_argument("--axi needs --core lighting (the AXI wrapper is the lighting core's)");
    if (harness_opt->count() > 0)
      throw std::invalid_argument("--harness needs --core lighting (the unit's bare harness is shadecore_bare_<config>)");
    if (first_opt->count() > 0) throw std::invalid_argument("--first needs --core lighting (the unit's shards: --shards)");
    if (write_rate_opt->count() > 0) throw std::invalid_argument("--write-rate needs --core lighting (the unit's: --mat-rate)");
    if (*cov_raw) throw std::invalid_argument("--coverage-db-only is regress's, for --core lighting");
    if (sub->count("--inject") > 0 || sub->count("--inject-at") > 0)
      throw std::invalid_argument("--inject needs --core lighting (the specular simulators take it directly)");
    if (sub->count("--trace-window") > 0 || *trace_all)
      throw std::invalid_argument("--trace-window and --trace-all need --core lighting (the specular core's --trace "
                                  "writes the whole run)");
    args->n_given = n_opt->count() > 0;
    args->count_given = count_opt->count() > 0;
    args->shards_given = shards_opt->count() > 0;
    args->coef_model_given = cm_opt->count() > 0;
    args->coef_given = coef_opt->count() > 0;
    run_cosim(*args);
  });
}

}  // namespace shadecore::cli

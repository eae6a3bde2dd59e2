// shadecore cosim — co-simulate the RTL (rtl/sc_specular.v, Verilated + SystemC) against the C model.
//
// The CLI cannot link SystemC (libsystemc defines main()), so it runs the per-configuration
// simulator executables sim/shadecore_cosim_<config> as subprocesses — their paths come from the
// build (SHADECORE_COSIM_SIMS) — splits the work into shards (exhaustive: the n range; random: the
// count, shard i with seed+i; directed: one shard), runs them in parallel and merges their
// "COSIM-RESULT {json}" lines. Exit 0 only if every shard passed.
#include <fcntl.h>
#include <sys/wait.h>
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

#include "commands.hpp"
#include "output.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/unit.hpp"

extern char** environ;

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
  long long reset_at = -2;
  int shards = 0;
  std::string trace, json_path;
  int show = 5;
  bool norm = false;              // sc_specular NORM = 1 (energy-normalised output, docs/spec.md §7)
  std::string coef_model, coef_kind;
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
  int status = -1;
  std::string out;
  nlohmann::json result;
};

// fork/exec argv with stdout captured (stderr passes through); fills status and out.
void run_capture(Shard& s) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  std::vector<char*> args;
  for (auto& a : s.argv) args.push_back(a.data());
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::dup2(fds[1], 1);
    ::close(fds[0]);
    ::close(fds[1]);
    ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
    ::execv(args[0], args.data());
    std::fprintf(stderr, "shadecore: error: cannot run %s: %s\n", args[0], std::strerror(errno));
    ::_exit(127);
  }
  ::close(fds[1]);
  char buf[65536];
  ssize_t k;
  while ((k = ::read(fds[0], buf, sizeof buf)) > 0) s.out.append(buf, static_cast<size_t>(k));
  ::close(fds[0]);
  int st = 0;
  ::waitpid(pid, &st, 0);
  s.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
  std::stringstream ss(s.out);
  std::string line;
  while (std::getline(ss, line))
    if (line.rfind("COSIM-RESULT ", 0) == 0) s.result = nlohmann::json::parse(line.substr(13));
}

void run_cosim(const CosimArgs& a) {
  // ---- validate everything before starting anything
  const NamedConfig* found = &config_named(a.config);
  const std::string cfg(found->name);
  Unit unit(parse_variant(a.variant), found->format, parse_cutoff_name(a.cutoff));
  unit.set_norm(a.norm);  // for the latency the summary reports; the simulator checks the model itself
  const auto [n_lo, n_hi] = parse_range(a.n_range);
  validate_n(n_lo);
  validate_n(n_hi);
  if (n_lo > n_hi) throw std::invalid_argument("empty n range " + a.n_range);
  if (a.mode != "exhaustive" && a.mode != "random" && a.mode != "directed")
    throw std::invalid_argument("unknown mode '" + a.mode + "' (known: exhaustive, random, directed)");
  if (a.count == 0) throw std::invalid_argument("--count must be >= 1");
  if (!a.json_path.empty()) check_writable_file(a.json_path);
  if (!a.trace.empty()) check_writable_file(a.trace);
  const auto sims = simulators();
  if (sims.empty()) throw std::runtime_error("this shadecore was built without the RTL co-simulation (SHADECORE_WITH_RTL=OFF)");
  const auto it = sims.find(cfg);
  if (it == sims.end()) throw std::runtime_error("no simulator built for config '" + cfg + "'");
  const std::string sim = it->second;
  if (::access(sim.c_str(), X_OK) != 0)
    throw std::runtime_error("simulator " + sim + " not built (cmake --build <build dir>)");

  uint64_t seed = a.seed;
  if (seed == 0) {
    seed = (static_cast<uint64_t>(std::random_device{}()) << 32) ^ std::random_device{}();
    if (seed == 0) seed = 1;
  }
  int shards = a.shards > 0 ? a.shards : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (!a.trace.empty() || a.mode == "directed") shards = 1;  // one waveform; the list is short
  if (a.mode == "exhaustive") shards = std::min(shards, n_hi - n_lo + 1);
  if (a.mode == "random") shards = static_cast<int>(std::min<uint64_t>(shards, a.count));

  // ---- build the shards
  std::vector<Shard> jobs(shards);
  for (int i = 0; i < shards; ++i) {
    auto& v = jobs[i].argv;
    v = {sim, "--variant", a.variant, "--cutoff", a.cutoff, "--mode", a.mode, "--quiet",
         "--in-stall", fmt::format("{}", a.in_stall), "--out-stall", fmt::format("{}", a.out_stall),
         "--show", std::to_string(a.show)};
    if (a.mode == "exhaustive") {
      // Equal numbers of exponents per shard (every n costs the same: 2^F + 5 codes).
      const int total = n_hi - n_lo + 1;
      const int lo = n_lo + static_cast<int>(static_cast<long long>(total) * i / shards);
      const int hi = n_lo + static_cast<int>(static_cast<long long>(total) * (i + 1) / shards) - 1;
      v.insert(v.end(), {"--n", fmt::format("{}..{}", lo, hi), "--seed", std::to_string(seed)});
    } else if (a.mode == "random") {
      const uint64_t c = a.count / shards + (static_cast<uint64_t>(i) < a.count % shards ? 1 : 0);
      v.insert(v.end(), {"--n", fmt::format("{}..{}", n_lo, n_hi), "--count", std::to_string(c), "--seed",
                         std::to_string(seed + static_cast<uint64_t>(i))});
    } else {
      v.insert(v.end(), {"--count", std::to_string(a.count), "--seed", std::to_string(seed)});
    }
    if (a.reset_at != -2) v.insert(v.end(), {"--reset-at", std::to_string(a.reset_at)});
    if (!a.trace.empty()) v.insert(v.end(), {"--trace", a.trace});
    if (a.norm) v.push_back("--norm");
    if (!a.coef_model.empty()) v.insert(v.end(), {"--coef-model", a.coef_model});
    if (!a.coef_kind.empty()) v.insert(v.end(), {"--coef", a.coef_kind});
  }
  fmt::print("cosim: {} {} ({}, F={} G={}) cutoff {} mode {} n {}..{}{} seed {} in-stall {} out-stall {}, {} shard(s)\n",
             a.variant, cfg, sim, found->format.frac, found->format.guard, a.cutoff, a.mode, n_lo, n_hi,
             a.mode == "exhaustive" ? "" : fmt::format(" count {}", a.count), seed, a.in_stall, a.out_stall,
             shards);
  std::fflush(stdout);

  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  std::vector<std::string> spawn_errors(shards);
  for (int i = 0; i < shards; ++i)
    threads.emplace_back([&, i] {
      try {
        run_capture(jobs[i]);
      } catch (const std::exception& e) {
        spawn_errors[i] = e.what();
      }
    });
  for (auto& t : threads) t.join();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // ---- merge
  uint64_t vectors = 0, mismatches = 0, lost = 0, dup = 0, lat_err = 0, proto = 0, dropped = 0, cycles = 0;
  uint64_t lat_min = ~uint64_t{0}, lat_max = 0;
  bool ok = true;
  nlohmann::json shard_json = nlohmann::json::array(), first = nlohmann::json::array();
  for (int i = 0; i < shards; ++i) {
    const Shard& s = jobs[i];
    if (!spawn_errors[i].empty()) throw std::runtime_error(spawn_errors[i]);
    if (s.result.is_null()) {
      // The simulator rejected its arguments or crashed: pass its words on, one line.
      throw std::runtime_error(fmt::format("simulator shard {} exited with status {} and no result", i, s.status));
    }
    const auto& r = s.result;
    ok = ok && s.status == 0 && r.value("ok", false);
    vectors += r.value("vectors", uint64_t{0});
    mismatches += r.value("mismatches", uint64_t{0});
    lost += r.value("lost", uint64_t{0});
    dup += r.value("duplicated_or_reordered", uint64_t{0});
    lat_err += r.value("latency_errors", uint64_t{0});
    proto += r.value("protocol_errors", uint64_t{0});
    dropped += r.value("dropped_by_reset", uint64_t{0});
    cycles += r.value("cycles", uint64_t{0});
    if (r.value("vectors", uint64_t{0}) > 0) lat_min = std::min(lat_min, r.value("latency_min", uint64_t{0}));
    lat_max = std::max(lat_max, r.value("latency_max", uint64_t{0}));
    for (const auto& m : r["first_mismatches"])
      if (first.size() < static_cast<size_t>(a.show)) first.push_back(m);
    shard_json.push_back(r);
    if (s.status != 0 || !r.value("ok", false)) {
      // Print what the failing shard said (errors, mismatches, the reproduce line).
      std::stringstream ss(s.out);
      std::string line;
      while (std::getline(ss, line))
        if (line.rfind("COSIM-RESULT ", 0) != 0) fmt::print("  [shard {}] {}\n", i, line);
    }
  }
  if (lat_min == ~uint64_t{0}) lat_min = 0;
  for (const auto& m : first)
    fmt::print("  mismatch: n={} code={} expected={} got={}\n", m.value("n", 0), m.value("code", 0LL),
               m.value("expected", 0u), m.value("got", 0u));
  const double vps = wall > 0 ? static_cast<double>(vectors) / wall : 0.0;
  fmt::print("cosim: {}: {} vectors, {} mismatches, {} lost, {} duplicated/reordered, {} latency errors, "
             "{} protocol errors, {} dropped by mid-stream reset; latency {}..{} cycles (spec {}); "
             "{} cycles; {:.2f} s wall, {:.3g} vectors/s\n",
             ok ? "PASS" : "FAIL", vectors, mismatches, lost, dup, lat_err, proto, dropped, lat_min, lat_max,
             unit.latency(), cycles, wall, vps);
  if (!a.trace.empty() && ok) fmt::print("cosim: waveform written to {}\n", a.trace);
  if (!a.json_path.empty()) {
    nlohmann::json j = {{"ok", ok},
                        {"variant", a.variant},
                        {"config", cfg},
                        {"frac", found->format.frac},
                        {"guard", found->format.guard},
                        {"cutoff", a.cutoff},
                        {"mode", a.mode},
                        {"norm", a.norm},
                        {"n_lo", n_lo},
                        {"n_hi", n_hi},
                        {"seed", seed},
                        {"in_stall", a.in_stall},
                        {"out_stall", a.out_stall},
                        {"shards", shards},
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
    write_file_atomic(a.json_path, j.dump(2) + "\n");
  }
  if (!ok) throw std::runtime_error(fmt::format(
      "co-simulation FAILED ({} mismatches, {} lost, {} duplicated/reordered, {} latency, {} protocol errors)",
      mismatches, lost, dup, lat_err, proto));
}

}  // namespace

void add_cosim(CLI::App& app) {
  auto args = std::make_shared<CosimArgs>();
  auto* sub = app.add_subcommand(
      "cosim", "co-simulate the Verilated RTL against the C model, bit for bit (runs sim/shadecore_cosim_<config>)");
  sub->add_option("--variant", args->variant, "unit (config/configs.json variants)");
  sub->add_option("--config", args->config, "named width configuration (narrow, default, wide)");
  sub->add_option("--cutoff", args->cutoff, "theta_cr | sign_clamp");
  sub->add_option("--n", args->n_range, "exponent range LO..HI or N (default 16..1024)");
  sub->add_option("--mode", args->mode, "exhaustive | random | directed (default directed)");
  sub->add_option("--count", args->count, "random: transactions in total; directed: minimum items");
  sub->add_option("--seed", args->seed, "random seed (default: pick one and print it)");
  sub->add_option("--in-stall", args->in_stall, "probability per cycle of an input gap")->check(CLI::Range(0.0, 1.0));
  sub->add_option("--out-stall", args->out_stall, "probability per cycle of out_ready low")->check(CLI::Range(0.0, 1.0));
  sub->add_option("--reset-at", args->reset_at,
                  "per shard: rst_ni pulse after this many accepted fragments (-1 none; default half way in random/directed)");
  sub->add_option("--shards", args->shards, "parallel simulator processes (default: number of cores)")
      ->check(CLI::Range(1, 1024));
  sub->add_option("--trace", args->trace, "FST waveform file (forces one shard)");
  sub->add_option("--json", args->json_path, "write the merged result as JSON (atomically)");
  sub->add_flag("--norm", args->norm, "energy-normalised output: sc_specular NORM = 1 (cs16, theta_cr)");
  sub->add_option("--coef-model", args->coef_model,
                  "with --norm: all | phong | phong_mod | blinn | blinn_mod | blinn_ndf | blinn_hf");
  sub->add_option("--coef", args->coef_kind, "with --norm and one model: fitted | classical");
  sub->add_option("--show", args->show, "mismatches printed in full")->check(CLI::Range(0, 1000));
  sub->callback([args] { run_cosim(*args); });
}

}  // namespace shadecore::cli

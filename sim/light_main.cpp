// SPDX-License-Identifier: Apache-2.0
// shadecore sim — co-simulation of the lighting core rtl/sc_light.v (Verilated with --sc for ONE
// feature set) against the C model LightCore. Built on demand per feature set by `shadecore cosim
// --core lighting` / `shadecore render --rtl` (cli/light_rtl.cpp), which generate light_features.hpp
// (the feature set's canonical JSON) beside the build; the same driver/monitor/scoreboard pattern as
// the unit's testbench (MonitorT, ScoreboardT).
//
//   shadecore_light_sim --mode random --count 200000 --in-stall 0.3 --out-stall 0.3 --seed 7
//   shadecore_light_sim --mode directed
//   shadecore_light_sim --mode stream --in cmds.bin --out colours.bin     (a scene's fragments)
//
// Prints a summary and one machine-readable line "COSIM-RESULT {json}". Exit 0 only if every output
// matched the C model bit for bit, nothing was lost, duplicated or reordered, every latency was within
// the core's contract and the port protocol held.
#include <systemc.h>
#include <verilated.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "Vlight.h"
#include "light_features.hpp"
#include "shadecore/stimulus/light_stream.hpp"
#include "shadecore/features.hpp"
#include "shadecore/light.hpp"
#include "tb_light_driver.hpp"
#include "tb_light_pins.hpp"
#include "shadecore/stimulus/light_stimulus.hpp"
#include "tb_monitor.hpp"

namespace shadecore::sim {
namespace {

struct LightOptions {
  std::string mode = "random";
  uint64_t count = 100000;
  uint64_t seed = 1;
  double in_stall = 0.0, out_stall = 0.0, write_rate = 0.002;
  int64_t reset_at = -2;
  int reset_cycles = 3;
  std::string in_file, out_file;
  int show = 10;
  std::string inject;
  uint64_t inject_at = 100;
  bool quiet = false;
  std::string label = "custom";
};

int run(const LightOptions& o, const FeatureSet& fs, const std::string& repro) {
  const LightCore core(fs);
  LightMode mode = LightMode::Random;
  std::vector<CoreCommand> stream;
  if (o.mode == "directed") mode = LightMode::Directed;
  else if (o.mode == "stream") {
    mode = LightMode::Stream;
    stream = read_commands(o.in_file);
  } else if (o.mode != "random") {
    throw std::invalid_argument("unknown mode '" + o.mode + "' (known: random, directed, stream)");
  }
  LightStimulus stim(core, mode, o.count, o.seed, o.write_rate, std::move(stream));
  if (stim.planned() == 0) throw std::invalid_argument("nothing to simulate (0 fragments)");
  int64_t reset_at = o.reset_at;
  if (reset_at == -2) reset_at = mode == LightMode::Stream ? -1 : static_cast<int64_t>(stim.planned() / 2);

  LightPins pins;
  pins.frac = core.format().frac;
  Vlight dut("dut");
  pins.bind(dut);
  LightScoreboard sb(core, o.show);
  std::vector<Colour> got;
  if (mode == LightMode::Stream) {
    got.reserve(stim.planned());
    sb.record(&got);
  }
  LightDriver drv("driver", pins, stim, o.seed, o.in_stall, o.out_stall, reset_at, o.reset_cycles);
  MonitorT<LightPins, LightScoreboard, LightDriver> mon("monitor", pins, sb, drv, o.inject, o.inject_at);

  sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sb.finish();
  dut.final();

  const bool ok = sb.ok() && !mon.watchdog_fired() && sb.checked_ > 0;
  const double vps = wall > 0 ? static_cast<double>(sb.checked_) / wall : 0.0;
  for (const auto& m : sb.first_)
    std::printf("MISMATCH tag %u N=(%lld,%lld,%lld) P=(%lld,%lld,%lld) expected=(%u,%u,%u) got=(%u,%u,%u) cycle %llu\n",
                m.tag, (long long)m.n[0], (long long)m.n[1], (long long)m.n[2], (long long)m.p[0], (long long)m.p[1],
                (long long)m.p[2], m.expected.c[0], m.expected.c[1], m.expected.c[2], m.got.c[0], m.got.c[1],
                m.got.c[2], (unsigned long long)m.cycle);
  if (!o.quiet || !ok)
    std::printf("cosim: %s: %llu fragments checked, %llu mismatches, %llu lost, %llu duplicated/reordered, "
                "%llu latency errors, %llu protocol errors; %llu register writes; %llu dropped by %llu mid-stream "
                "reset(s); latency %llu..%llu cycles (spec %d..%d advancing); %llu cycles, %.3f s, %.0f fragments/s\n",
                ok ? "PASS" : "FAIL", (unsigned long long)sb.checked_, (unsigned long long)sb.mismatches_,
                (unsigned long long)sb.lost_, (unsigned long long)sb.unexpected_,
                (unsigned long long)sb.latency_errors_, (unsigned long long)sb.protocol_errors_,
                (unsigned long long)sb.material_writes_, (unsigned long long)sb.dropped_by_reset_,
                (unsigned long long)drv.resets(), (unsigned long long)(sb.checked_ ? sb.lat_min_ : 0),
                (unsigned long long)sb.lat_max_, core.latency_min(), core.latency(),
                (unsigned long long)mon.cycles(), wall, vps);
  if (sb.checked_ == 0) std::printf("cosim: FAIL: no fragment was checked\n");
  if (!ok) std::printf("cosim: reproduce with: %s\n", repro.c_str());
  if (mode == LightMode::Stream && !o.out_file.empty()) {
    std::vector<ResultRecord> res;
    res.reserve(got.size());
    for (size_t i = 0; i < got.size(); ++i) res.push_back({static_cast<uint32_t>(i), got[i]});
    write_results(o.out_file, res);
  }
  nlohmann::json j = {
      {"ok", ok},
      {"core", "lighting"},
      {"features", fs.name},
      {"feature_key", fs.key()},
      {"feature_set", nlohmann::json::parse(fs.canonical().dump())},
      {"mode", o.mode},
      {"seed", o.seed},
      {"in_stall", o.in_stall},
      {"out_stall", o.out_stall},
      {"planned", stim.planned()},
      {"accepted", sb.accepted_},
      {"vectors", sb.checked_},
      {"mismatches", sb.mismatches_},
      {"lost", sb.lost_},
      {"duplicated_or_reordered", sb.unexpected_},
      {"latency_errors", sb.latency_errors_},
      {"protocol_errors", sb.protocol_errors_},
      {"dropped_by_reset", sb.dropped_by_reset_},
      {"resets", drv.resets()},
      {"register_writes", sb.material_writes_},
      {"latency_spec", core.latency()},
      {"latency_spec_min", core.latency_min()},
      {"latency_min", sb.checked_ ? sb.lat_min_ : 0},
      {"latency_max", sb.lat_max_},
      {"cycles", mon.cycles()},
      {"wall_s", wall},
      {"vectors_per_s", vps},
      {"watchdog", mon.watchdog_fired()},
      {"reproduce", repro},
  };
  std::printf("COSIM-RESULT %s\n", j.dump().c_str());
  std::fflush(stdout);
  return ok ? 0 : 1;
}

int main_impl(int argc, char** argv) {
  LightOptions o;
  CLI::App app{"co-simulation of rtl/sc_light.v (one feature set, built on demand) against LightCore"};
  app.add_option("--mode", o.mode, "random | directed | stream");
  app.add_option("--count", o.count, "random: fragments; directed: at least this many (list repeated)")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  app.add_option("--seed", o.seed, "random seed (0 = pick one and print it)");
  app.add_option("--in-stall", o.in_stall, "probability per cycle of an input gap")->check(CLI::Range(0.0, 0.99));
  app.add_option("--out-stall", o.out_stall, "probability per cycle of out_ready_i low")->check(CLI::Range(0.0, 0.99));
  app.add_option("--write-rate", o.write_rate, "random: probability per fragment of a register-write burst")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--reset-at", o.reset_at, "pulse rst_ni low after this many accepted fragments (-1 none)")
      ->check(CLI::Range(int64_t{-1}, int64_t{1} << 40));
  app.add_option("--reset-cycles", o.reset_cycles, "length of each reset pulse")->check(CLI::Range(1, 1000));
  app.add_option("--in", o.in_file, "stream: command file (stimulus/include/shadecore/stimulus/light_stream.hpp)");
  app.add_option("--out", o.out_file, "stream: write the RTL's colours here");
  app.add_option("--show", o.show, "errors printed in full per kind")->check(CLI::Range(0, 1000000));
  app.add_option("--inject", o.inject, "self-test: corrupt one observed output (value | drop | dup); the run must FAIL")
      ->check(CLI::IsMember({"value", "drop", "dup"}));
  app.add_option("--inject-at", o.inject_at, "self-test: which output transfer (1-based)")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  app.add_option("--label", o.label, "the feature set's name, for the report");
  app.add_flag("--quiet", o.quiet, "print only the COSIM-RESULT line when the run passes");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "cosim: error: %s\n", e.what());
    return 2;
  }
  std::string repro;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seed" && i + 1 < argc) { ++i; continue; }
    if (a.rfind("--seed=", 0) == 0) continue;
    repro += (repro.empty() ? "" : " ") + a;
  }
  try {
    if (o.seed == 0) {
      o.seed = (static_cast<uint64_t>(std::random_device{}()) << 32) ^ std::random_device{}();
      if (o.seed == 0) o.seed = 1;
    }
    repro += " --seed " + std::to_string(o.seed);
    if (o.mode == "stream" && o.in_file.empty()) throw std::invalid_argument("--mode stream needs --in FILE");
    const FeatureSet fs = feature_set_from_json(nlohmann::json::parse(kLightFeaturesJson), "built feature set");
    FeatureSet named = fs;
    named.name = o.label;
    if (!o.quiet)
      std::printf("cosim: lighting core '%s' [%s]: %s; mode %s count %llu seed %llu in-stall %g out-stall %g\n",
                  named.name.c_str(), fs.key().c_str(), fs.summary().c_str(), o.mode.c_str(),
                  (unsigned long long)o.count, (unsigned long long)o.seed, o.in_stall, o.out_stall);
    return run(o, named, repro);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cosim: error: %s\n", e.what());
    return 2;
  }
}

}  // namespace
}  // namespace shadecore::sim

int sc_main(int argc, char** argv) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  return shadecore::sim::main_impl(argc, argv);
}

// SPDX-License-Identifier: Apache-2.0
// shadecore sim — one co-simulation run of the lighting core (tb_light_run.hpp): the command line, the stimulus,
// the scoreboard's verdict, the summary and the COSIM-RESULT line. Compiled once, in the main build (library
// shadecore_light_harness, sim/CMakeLists.txt), and linked into every harness of every feature set's build
// (sim/light_core): nothing here depends on the Verilated model or on how it was built (HarnessBuild says).
#include "tb_light_run.hpp"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "shadecore/common/args.hpp"
#include "shadecore/common/output_files.hpp"
#include "shadecore/features.hpp"
#include "shadecore/stimulus/light_stream.hpp"
#include "shadecore/stimulus/specular.hpp"

namespace shadecore::sim {

namespace {

// The waveform being written (its temporary name and the FST writer's side file): removed if the run is
// stopped by a signal (SIGINT from a terminal, SIGTERM from `shadecore`), so an interrupted run leaves nothing.
char g_trace_tmp[2][4096];
void light_trace_on_signal(int sig) {
  for (const char* f : g_trace_tmp)
    if (f[0]) ::unlink(f);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}
void light_trace_cleanup_on_signals(const std::string& tmp) {
  const std::string hier = tmp + ".hier";
  if (hier.size() >= sizeof g_trace_tmp[0]) throw std::invalid_argument("--trace: path too long");
  std::snprintf(g_trace_tmp[0], sizeof g_trace_tmp[0], "%s", tmp.c_str());
  std::snprintf(g_trace_tmp[1], sizeof g_trace_tmp[1], "%s", hier.c_str());
  for (int sig : {SIGINT, SIGTERM, SIGHUP})
    if (std::signal(sig, light_trace_on_signal) == SIG_IGN) std::signal(sig, SIG_IGN);  // inherited ignore stays
}

std::string light_shortest(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  for (int p = 1; p < 18; ++p) {
    char t[32];
    std::snprintf(t, sizeof t, "%.*g", p, v);
    if (std::strtod(t, nullptr) == v) return t;
  }
  return b;
}

int light_run(const LightOptions& o, const FeatureSet& fs, const std::string& harness, const std::string& repro,
                     const LightHarnessFn& loop) {
  const LightCore core(fs);
  LightMode mode = LightMode::Random;
  std::vector<CoreCommand> stream;
  if (o.mode == "directed") mode = LightMode::Directed;
  else if (o.mode == "stream") {
    mode = LightMode::Stream;
    stream = read_commands(o.in_file);
  }
  LightStimulus stim(core, mode, o.count, o.seed, o.write_rate, std::move(stream), o.first);
  if (stim.planned() == 0) throw std::invalid_argument("nothing to simulate (0 fragments)");
  const int64_t reset_local = light_local_reset(o.reset_at, o.first, stim.planned());
  // Stalls from the harness's own generators, seeded per run: a shard starting at fragment `first` gets
  // its own streams (shard 0 / an unsharded run: the seed), as the unit's testbench. What is driven and
  // checked is a function of (seed, index): the stimulus.
  const uint64_t timing_seed = o.first != 0 ? mix64(o.seed ^ mix64(o.first)) : o.seed;

  LightScoreboard sb(core, o.show);
  std::vector<Colour> got;
  if (mode == LightMode::Stream) {
    got.reserve(stim.planned());
    sb.record(&got);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const LightHarnessStats hs = loop(o, core, stim, reset_local, timing_seed, sb);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sb.finish();

  const bool ok = sb.ok() && !hs.watchdog && sb.checked_ > 0;
  const double vps = wall > 0 ? static_cast<double>(sb.checked_) / wall : 0.0;
  for (const auto& m : sb.first_)
    std::printf("MISMATCH tag %u N=(%lld,%lld,%lld) P=(%lld,%lld,%lld) expected=(%u,%u,%u)+(%u,%u,%u) "
                "got=(%u,%u,%u)+(%u,%u,%u) cycle %llu\n",
                m.tag, (long long)m.n[0], (long long)m.n[1], (long long)m.n[2], (long long)m.p[0], (long long)m.p[1],
                (long long)m.p[2], m.expected.c[0], m.expected.c[1], m.expected.c[2], m.expected.s[0], m.expected.s[1],
                m.expected.s[2], m.got.c[0], m.got.c[1], m.got.c[2], m.got.s[0], m.got.s[1], m.got.s[2],
                (unsigned long long)m.cycle);
  if (!o.quiet || !ok)
    std::printf("cosim: %s: %llu fragments checked, %llu mismatches, %llu lost, %llu duplicated/reordered, "
                "%llu latency errors, %llu protocol errors; %llu register writes; %llu flushed by %llu mid-stream "
                "reset(s), %llu sent again; latency %llu..%llu cycles (spec %d..%d advancing); %llu cycles, "
                "%.3f s, %.0f fragments/s (%s)\n",
                ok ? "PASS" : "FAIL", (unsigned long long)sb.checked_, (unsigned long long)sb.mismatches_,
                (unsigned long long)sb.lost_, (unsigned long long)sb.unexpected_,
                (unsigned long long)sb.latency_errors_, (unsigned long long)sb.protocol_errors_,
                (unsigned long long)sb.material_writes_, (unsigned long long)sb.dropped_by_reset_,
                (unsigned long long)hs.resets, (unsigned long long)hs.replayed,
                (unsigned long long)(sb.checked_ ? sb.lat_min_ : 0), (unsigned long long)sb.lat_max_,
                core.latency_min(), core.latency_max(), (unsigned long long)hs.cycles, wall, vps, harness.c_str());
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
      {"harness", harness},
      {"features", fs.name},
      {"feature_key", fs.key()},
      {"feature_set", nlohmann::json::parse(fs.canonical().dump())},
      {"mode", o.mode},
      {"seed", o.seed},
      {"first", o.first},
      {"in_stall", o.in_stall},
      {"out_stall", o.out_stall},
      {"write_rate", o.write_rate},
      {"reset_at", o.reset_at},
      {"planned", stim.planned()},
      {"accepted", sb.accepted_},
      {"vectors", sb.checked_},
      {"mismatches", sb.mismatches_},
      {"lost", sb.lost_},
      {"duplicated_or_reordered", sb.unexpected_},
      {"latency_errors", sb.latency_errors_},
      {"protocol_errors", sb.protocol_errors_},
      {"dropped_by_reset", sb.dropped_by_reset_},
      {"replayed", hs.replayed},
      {"resets", hs.resets},
      {"register_writes", sb.material_writes_},
      {"latency_spec", core.latency()},
      {"latency_spec_min", core.latency_min()},
      {"latency_spec_max", core.latency_max()},   // under backpressure (latency_spec + gap slack)
      {"latency_min", sb.checked_ ? sb.lat_min_ : 0},
      {"latency_max", sb.lat_max_},
      {"cycles", hs.cycles},
      {"wall_s", wall},
      {"vectors_per_s", vps},
      {"watchdog", hs.watchdog},
      {"reproduce", repro},
  };
  // Where a windowed waveform of this run would be cut (`cosim --core lighting --trace`): the monitor cycle
  // of the first error of any kind; null when there was none (a FAIL without one: nothing checked, or
  // fragments that never came out, is cut at the end of the run).
  if (sb.first_error_cycle_ != LightScoreboard::kNoError) j["first_error_cycle"] = sb.first_error_cycle_;
  else j["first_error_cycle"] = nullptr;
  if (mode == LightMode::Random) j["stimulus_digest"] = stim.digest();
  if (!hs.extra.is_null()) {
    j["axi"] = hs.extra;
    if (!o.quiet) std::printf("cosim: AXI: %s\n", hs.extra.dump().c_str());
  }
  std::printf("COSIM-RESULT %s\n", j.dump().c_str());
  std::fflush(stdout);
  return ok ? 0 : 2;
}

}  // namespace

int light_harness_main(int argc, char** argv, const char* harness, const char* features_json, const LightHarnessFn& loop,
                       const HarnessBuild& build) {
  using namespace cliargs;
  std::string prog = argv[0];
  if (const auto slash = prog.rfind('/'); slash != std::string::npos) prog = prog.substr(slash + 1);
  LightOptions o;
  bool no_resend = false;
  CLI::App app{std::string("co-simulation of rtl/sc_light.v (one feature set, built on demand) against LightCore; ") +
               harness + " harness"};
  app.add_option("--mode", o.mode, "random | directed | stream")->check(CLI::IsMember({"random", "directed", "stream"}));
  auto* count_opt = app.add_option("--count", o.count, "random: fragments; directed: at least this many (list repeated)")
                        ->check(UInt(1, uint64_t{1} << 40));
  app.add_option("--seed", o.seed, "random seed (0 = pick one and print it)")->check(UInt(0));
  auto* first_opt = app.add_option("--first", o.first,
                                   "random: global index of the first fragment (a shard of a longer run with the same seed)")
                        ->check(UInt(0, uint64_t{1} << 40));
  app.add_option("--in-stall", o.in_stall, "probability per cycle of an input gap, in [0, 1)")->check(Probability(false));
  app.add_option("--out-stall", o.out_stall, "probability per cycle of out_ready_i low, in [0, 1)")->check(Probability(false));
  auto* rate_opt = app.add_option("--write-rate", o.write_rate, "random: probability per fragment of a register-write burst before it")
                       ->check(Probability(true));
  auto* reset_opt = app.add_option("--reset-at", o.reset_at,
                                   "pulse rst_ni low once, before the fragment of this index (random: global index, so only the "
                                   "shard holding it resets; -1 none; default: random, drawn from the seed in the middle half "
                                   "of this run; directed, half way; none for a stream)")
                        ->check(ResetAt());
  app.add_option("--reset-cycles", o.reset_cycles, "length of each reset pulse")->check(Int(1, 1000));
  app.add_flag("--no-resend", no_resend, "drop the fragments the reset flushes instead of sending them again");
  auto* in_opt = app.add_option("--in", o.in_file, "stream: command file (shadecore/stimulus/light_stream.hpp)")->check(NonEmpty("path"));
  auto* out_opt = app.add_option("--out", o.out_file, "stream: write the RTL's colours here")->check(NonEmpty("path"));
  app.add_option("--show", o.show, "errors printed in full per kind")->check(Int(0, 1000000));
  auto* inject_opt = app.add_option("--inject", o.inject, "self-test: corrupt one observed output (value | drop | dup; the axi "
                                                        "harness also tlast | bresp | rdata: one observed TLAST, BRESP or "
                                                        "RDATA); the run must FAIL")
                         ->check(CLI::IsMember({"value", "drop", "dup", "tlast", "bresp", "rdata"}));
  auto* inject_at_opt = app.add_option("--inject-at", o.inject_at, "self-test: which output transfer (1-based)")
                            ->check(UInt(1, uint64_t{1} << 40));
  app.add_option("--label", o.label, "the feature set's name, for the report")->check(NonEmpty("label"));
  app.add_flag("--quiet", o.quiet, "print only the COSIM-RESULT line when the run passes");
  app.add_option("--coverage", o.coverage, "coverage build only: write the coverage database (coverage.dat) here")
      ->check(NonEmpty("path"));
  std::string trace;
  app.add_option("--trace", trace, "trace build only: write an FST waveform of the RTL here (the whole run unless "
                                   "--trace-from / --trace-to cut it)")
      ->check(NonEmpty("path"));
  auto* tfrom_opt = app.add_option("--trace-from", o.trace.from, "--trace: first monitor cycle dumped (default: the first)")
                        ->check(UInt(0));
  auto* tto_opt = app.add_option("--trace-to", o.trace.to, "--trace: last monitor cycle dumped (default: the end)")
                      ->check(UInt(0));
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: error: %s (see %s --help)\n", prog.c_str(), e.what(), prog.c_str());
    return 1;
  }
  o.resend = !no_resend;
  try {
    // Options that the chosen mode would ignore are errors, not silently dropped.
    if (o.mode != "random" && first_opt->count()) throw std::invalid_argument("--first applies to --mode random only");
    if (o.mode != "random" && rate_opt->count()) throw std::invalid_argument("--write-rate applies to --mode random only");
    if (o.mode == "stream" && count_opt->count()) throw std::invalid_argument("--count does not apply to --mode stream (the file says it)");
    if (o.mode == "stream" && !in_opt->count()) throw std::invalid_argument("--mode stream needs --in FILE");
    if (o.mode != "stream" && (in_opt->count() || out_opt->count())) throw std::invalid_argument("--in and --out apply to --mode stream only");
    if (inject_at_opt->count() && !inject_opt->count()) throw std::invalid_argument("--inject-at needs --inject");
    if ((o.inject == "tlast" || o.inject == "bresp" || o.inject == "rdata") && std::string(harness) != "axi")
      throw std::invalid_argument("--inject " + o.inject + " is the axi harness's (the bus model's checks)");
    if (const std::string e = coverage_option_error(o.coverage, build.coverage); !e.empty()) throw std::invalid_argument(e);
    if (const std::string e = trace_option_error(trace, build.trace); !e.empty()) throw std::invalid_argument(e);
    if ((tfrom_opt->count() || tto_opt->count()) && trace.empty())
      throw std::invalid_argument("--trace-from and --trace-to need --trace FILE");
    if (o.trace.from > o.trace.to) throw std::invalid_argument("--trace-from is after --trace-to");
    // The waveform is an output (output_files.hpp): checked now (a regular file: the FST writer seeks),
    // written beside its target and renamed when the run is over — a FAIL keeps it, an error leaves nothing.
    std::string trace_target;
    if (!trace.empty()) {
      trace_target = io::resolve_output(trace, /*allow_stream=*/false).path;
      o.trace.file = io::temp_name(io::parent_of(trace_target), "fst");
      light_trace_cleanup_on_signals(o.trace.file);
    }
    struct TraceTmp {
      std::string f;
      ~TraceTmp() {
        if (!f.empty()) std::remove(f.c_str()), std::remove((f + ".hier").c_str());
      }
    } trace_tmp{o.trace.file};
    if (o.seed == 0) {
      o.seed = (static_cast<uint64_t>(std::random_device{}()) << 32) ^ std::random_device{}();
      if (o.seed == 0) o.seed = 1;
    }
    const FeatureSet fs = feature_set_from_json(nlohmann::json::parse(features_json), "built feature set");
    FeatureSet named = fs;
    named.name = o.label;
    if (o.reset_at == -2) {
      o.reset_at = -1;
      if (!reset_opt->count() && o.mode == "random") {
        o.reset_at = static_cast<int64_t>(o.first + stimulus::default_reset_index(o.seed, o.count));
      } else if (!reset_opt->count() && o.mode == "directed") {
        const LightCore probe(fs);
        o.reset_at = static_cast<int64_t>(LightStimulus(probe, LightMode::Directed, o.count, o.seed, o.write_rate).planned() / 2);
      }
    }
    // The command that replays this run exactly: every option resolved (the seed picked, the reset point).
    std::string repro = argv[0];
    const auto add = [&repro](const std::string& k, const std::string& v) { repro += " " + k + " " + v; };
    add("--mode", o.mode);
    if (o.mode != "stream") add("--count", std::to_string(o.count));
    if (o.mode == "random" && o.first) add("--first", std::to_string(o.first));
    add("--seed", std::to_string(o.seed));
    add("--in-stall", light_shortest(o.in_stall));
    add("--out-stall", light_shortest(o.out_stall));
    if (o.mode == "random") add("--write-rate", light_shortest(o.write_rate));
    add("--reset-at", std::to_string(o.reset_at));
    add("--reset-cycles", std::to_string(o.reset_cycles));
    if (!o.resend) repro += " --no-resend";
    if (o.mode == "stream") add("--in", o.in_file);
    if (!o.inject.empty()) {
      add("--inject", o.inject);
      add("--inject-at", std::to_string(o.inject_at));
    }
    add("--label", o.label);
    if (!o.quiet)
      std::printf("cosim: lighting core '%s' [%s] (%s harness): %s; mode %s count %llu%s seed %llu in-stall %g "
                  "out-stall %g reset-at %lld\n",
                  named.name.c_str(), fs.key().c_str(), harness, fs.summary().c_str(), o.mode.c_str(),
                  (unsigned long long)o.count, o.first ? (" first " + std::to_string(o.first)).c_str() : "",
                  (unsigned long long)o.seed, o.in_stall, o.out_stall, (long long)o.reset_at);
    const int status = light_run(o, named, harness, repro, loop);
    if (!trace_tmp.f.empty()) {
      if (::access(trace_tmp.f.c_str(), F_OK) != 0)
        throw std::runtime_error("--trace: the run ended before cycle " + std::to_string(o.trace.from) +
                                 ", where the waveform was to start");
      if (std::rename(trace_tmp.f.c_str(), trace_target.c_str()) != 0)
        throw std::runtime_error("cannot write the waveform " + trace);
      trace_tmp.f.clear();
      if (!o.quiet) std::printf("cosim: waveform written to %s\n", trace.c_str());
      std::fflush(stdout);
    }
    return status;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", prog.c_str(), e.what());
    return 1;
  }
}

}  // namespace shadecore::sim

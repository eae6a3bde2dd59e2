// shadecore sim — co-simulation of rtl/sc_specular.v (Verilated with --sc) against the C model.
// One executable per configuration of config/configs.json (shadecore_cosim_<config>); it holds a
// Verilated model per (variant, CUTOFF) and elaborates the one asked for. `shadecore cosim` runs
// it as a subprocess (and shards the n range over several of them).
//
//   shadecore_cosim_default --mode random --count 1000000 --in-stall 0.2 --out-stall 0.3 --seed 7
//   shadecore_cosim_default --mode exhaustive --n 16..1024
//   shadecore_cosim_default --mode directed +trace            (waveform: cosim.fst)
//
// Prints a human summary and one machine-readable line "COSIM-RESULT {json}". Exit 0 only if every
// output matched the C model bit for bit, no transaction was lost, duplicated or reordered, every
// latency was the unit's, and the port protocol held.
#include <systemc.h>
#include <verilated.h>
#include <verilated_fst_sc.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadecore/configs.hpp"
#include "shadecore/unit.hpp"
#include "sim_models.hpp"
#include "tb_driver.hpp"
#include "tb_monitor.hpp"
#include "tb_options.hpp"
#include "tb_pins.hpp"
#include "tb_scoreboard.hpp"
#include "tb_stimulus.hpp"

namespace shadecore::sim {
namespace {

std::pair<int, int> parse_n_range(const std::string& s) {
  const auto dots = s.find("..");
  try {
    size_t pos = 0;
    if (dots == std::string::npos) {
      const int v = std::stoi(s, &pos);
      if (pos != s.size()) throw std::invalid_argument("");
      return {v, v};
    }
    const std::string a = s.substr(0, dots), b = s.substr(dots + 2);
    const int lo = std::stoi(a, &pos);
    if (pos != a.size()) throw std::invalid_argument("");
    const int hi = std::stoi(b, &pos);
    if (pos != b.size()) throw std::invalid_argument("");
    return {lo, hi};
  } catch (const std::exception&) {
    throw std::invalid_argument("bad n range '" + s + "' (want LO..HI or N)");
  }
}

template <class M>
int run(const Options& o, const Unit& unit, const std::string& repro) {
  Pins pins;
  M dut("dut");
  pins.bind(dut);
  Scoreboard sb(unit, o.show);
  Stimulus stim(o, unit);
  Driver drv("driver", pins, stim, unit, o);
  Monitor mon("monitor", pins, sb, drv, o.inject, o.inject_at);
  mon.set_in_bits(unit.format().in_bits());

  std::unique_ptr<VerilatedFstSc> tfp;
  if (!o.trace.empty()) {
    Verilated::traceEverOn(true);
    sc_core::sc_start(sc_core::SC_ZERO_TIME);  // elaborate before tracing (Verilator + SystemC)
    tfp = std::make_unique<VerilatedFstSc>();
    dut.trace(tfp.get(), 99);
    tfp->open(o.trace.c_str());
  }
  // The kernel's "Info: /OSCI/SystemC: Simulation stopped by user." after sc_stop() is noise here.
  sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (tfp) tfp->close();
  sb.finish();
  dut.final();

  const Format& f = unit.format();
  const bool ok = sb.ok() && !mon.watchdog_fired();
  const double vps = wall > 0 ? static_cast<double>(sb.checked_) / wall : 0.0;
  for (const auto& m : sb.first_)
    std::printf("MISMATCH n=%d code=%lld expected=%u got=%u (tag %u, cycle %llu)\n", m.n,
                static_cast<long long>(m.code), m.expected, m.got, m.tag,
                static_cast<unsigned long long>(m.cycle));
  if (!o.quiet || !ok) {
    std::printf(
        "cosim: %s: %llu vectors checked, %llu mismatches, %llu lost, %llu duplicated/reordered, "
        "%llu latency errors, %llu protocol errors; %llu dropped by %llu mid-stream reset(s); "
        "latency %llu..%llu cycles (spec %d advancing); %llu cycles, %.3f s, %.0f vectors/s\n",
        ok ? "PASS" : "FAIL", (unsigned long long)sb.checked_, (unsigned long long)sb.mismatches_,
        (unsigned long long)sb.lost_, (unsigned long long)sb.unexpected_,
        (unsigned long long)sb.latency_errors_, (unsigned long long)sb.protocol_errors_,
        (unsigned long long)sb.dropped_by_reset_, (unsigned long long)drv.resets(),
        (unsigned long long)(sb.checked_ ? sb.lat_min_ : 0), (unsigned long long)sb.lat_max_,
        unit.latency(), (unsigned long long)mon.cycles(), wall, vps);
  }
  if (!ok) std::printf("cosim: reproduce with: %s\n", repro.c_str());
  nlohmann::json j = {
      {"ok", ok},
      {"config", kSimConfig},
      {"frac", f.frac},
      {"guard", f.guard},
      {"variant", o.variant},
      {"cutoff", o.cutoff},
      {"norm", unit.norm()},
      {"mode", to_string(o.mode)},
      {"n_lo", o.n_lo},
      {"n_hi", o.n_hi},
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
      {"material_writes", sb.material_writes_},
      {"latency_spec", unit.latency()},
      {"latency_min", sb.checked_ ? sb.lat_min_ : 0},
      {"latency_max", sb.lat_max_},
      {"cycles", mon.cycles()},
      {"wall_s", wall},
      {"vectors_per_s", vps},
      {"watchdog", mon.watchdog_fired()},
      {"reproduce", repro},
  };
  nlohmann::json mm = nlohmann::json::array();
  for (const auto& m : sb.first_)
    mm.push_back({{"n", m.n}, {"code", m.code}, {"expected", m.expected}, {"got", m.got}, {"tag", m.tag}});
  j["first_mismatches"] = mm;
  std::printf("COSIM-RESULT %s\n", j.dump().c_str());
  std::fflush(stdout);
  return ok ? 0 : 1;
}

int main_impl(int argc, char** argv) {
  // Verilator-style plusarg: +trace (waveform cosim.fst) or +trace=FILE.
  std::vector<char*> args;
  std::string plus_trace;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "+trace") plus_trace = "cosim.fst";
    else if (a.rfind("+trace=", 0) == 0) plus_trace = a.substr(7);
    else args.push_back(argv[i]);
  }
  std::string repro;
  for (int i = 0; i < argc; ++i) repro += (i ? " " : "") + std::string(argv[i]);

  Options o;
  std::string mode = "directed", n_range = "16..1024";
  bool norm = false;
  std::string coef_model = "all", coef_kind = "fitted";
  CLI::App app{std::string("co-simulation of rtl/sc_specular.v (config '") + kSimConfig +
               "') against the C model"};
  app.add_option("--variant", o.variant, "unit variant (config/configs.json variants)");
  app.add_option("--cutoff", o.cutoff, "theta_cr | sign_clamp");
  app.add_option("--mode", mode, "exhaustive | random | directed");
  app.add_option("--n", n_range, "exponent range LO..HI or N (exhaustive, random)");
  app.add_option("--count", o.count, "random: transactions; directed: minimum items (list repeated)");
  app.add_option("--seed", o.seed, "random seed (0 = pick one and print it)");
  app.add_option("--in-stall", o.in_stall, "probability per cycle of an input gap")->check(CLI::Range(0.0, 1.0));
  app.add_option("--out-stall", o.out_stall, "probability per cycle of out_ready_i low")->check(CLI::Range(0.0, 1.0));
  app.add_option("--mat-rate", o.mat_rate, "random mode: probability per cycle of a material write")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--reset-at", o.reset_at,
                 "pulse rst_ni low after this many accepted fragments (-1 none; default: half way in "
                 "random/directed, none in exhaustive)");
  app.add_option("--reset-cycles", o.reset_cycles, "length of each reset pulse")->check(CLI::Range(1, 1000));
  app.add_option("--trace", o.trace, "write an FST waveform to this file (also: +trace, +trace=FILE)");
  app.add_option("--show", o.show, "errors printed in full per kind")->check(CLI::Range(0, 1000000));
  app.add_option("--inject", o.inject, "self-test: corrupt one observed output (value | drop | dup); the run must FAIL")
      ->check(CLI::IsMember({"value", "drop", "dup"}));
  app.add_option("--inject-at", o.inject_at, "self-test: which output transfer (1-based)")->check(CLI::PositiveNumber);
  app.add_flag("--quiet", o.quiet, "print only the COSIM-RESULT line when the run passes");
  app.add_flag("--norm", norm, "sc_specular with NORM = 1: rtl/sc_norm.v after the unit (cs16, theta_cr)");
  app.add_option("--coef-model", coef_model,
                 "--norm: all (model and kind picked per material from n) | phong | phong_mod | blinn | "
                 "blinn_mod | blinn_ndf | blinn_hf");
  app.add_option("--coef", coef_kind, "--norm with one model: fitted | classical");
  try {
    app.parse(static_cast<int>(args.size()), args.data());
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (!plus_trace.empty() && o.trace.empty()) o.trace = plus_trace;
  try {
    if (mode == "exhaustive") o.mode = Mode::Exhaustive;
    else if (mode == "random") o.mode = Mode::Random;
    else if (mode == "directed") o.mode = Mode::Directed;
    else throw std::invalid_argument("unknown mode '" + mode + "' (known: exhaustive, random, directed)");
    std::tie(o.n_lo, o.n_hi) = parse_n_range(n_range);
    if (o.n_lo > o.n_hi) throw std::invalid_argument("empty n range " + n_range);
    validate_n(o.n_lo);
    validate_n(o.n_hi);
    if (o.seed == 0) {
      o.seed = (static_cast<uint64_t>(std::random_device{}()) << 32) ^ std::random_device{}();
      if (o.seed == 0) o.seed = 1;
      repro += " --seed " + std::to_string(o.seed);
    }
    if (o.reset_at == -2)
      o.reset_at = -1;  // resolved below once the stimulus length is known
    const Format* fmt = nullptr;
    for (const auto& c : kConfigs)
      if (c.name == kSimConfig) fmt = &c.format;
    if (!fmt) throw std::invalid_argument(std::string("config ") + kSimConfig + " not in configs.hpp");
    Unit unit(parse_variant(o.variant), *fmt, parse_cutoff_name(o.cutoff));
    if (norm)
      unit.set_norm(true, coef_model == "all" ? -1 : static_cast<int>(parse_model(coef_model)),
                    parse_coef_kind(coef_kind));
    if (o.reset_at == -1 && mode != "exhaustive") {
      bool explicit_reset = app.count("--reset-at") > 0;
      if (!explicit_reset) {
        Stimulus probe(o, unit);
        o.reset_at = static_cast<int64_t>(probe.planned() / 2);
      }
    }
    if (!o.quiet)
      std::printf("cosim: config %s (F=%d G=%d) variant %s cutoff %s mode %s n %d..%d count %llu seed %llu "
                  "in-stall %g out-stall %g reset-at %lld%s%s\n",
                  kSimConfig, fmt->frac, fmt->guard, o.variant.c_str(), o.cutoff.c_str(), mode.c_str(), o.n_lo,
                  o.n_hi, (unsigned long long)o.count, (unsigned long long)o.seed, o.in_stall, o.out_stall,
                  (long long)o.reset_at, o.trace.empty() ? "" : " trace ", o.trace.c_str());
    int rc = -1;
    const bool found = with_model(static_cast<int>(unit.variant()), static_cast<int>(unit.cutoff()),
                                  [&](auto tag) { rc = run<typename decltype(tag)::type>(o, unit, repro); },
                                  norm ? 1 : 0);
    if (!found)
      throw std::invalid_argument("no Verilated model for variant " + o.variant + " cutoff " + o.cutoff +
                                  (norm ? " with --norm" : ""));
    return rc;
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

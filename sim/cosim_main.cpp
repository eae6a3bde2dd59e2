// SPDX-License-Identifier: Apache-2.0
// shadecore sim — co-simulation of rtl/sc_specular.v (Verilated with --sc) against the C model.
// One executable per configuration of config/configs.json (shadecore_cosim_<config>); it holds a
// Verilated model per (variant, CUTOFF) and elaborates the one asked for. `shadecore cosim` runs
// it as a subprocess (and shards the n range, or the transaction indices, over several of them).
//
//   shadecore_cosim_default --mode random --count 1000000 --in-stall 0.2 --out-stall 0.3 --seed 7
//   shadecore_cosim_default --mode exhaustive --n 16..1024
//   shadecore_cosim_default --mode directed +trace            (waveform: cosim.fst)
//
// Prints a human summary and one machine-readable line "COSIM-RESULT {json}". Exit status (docs/cli.md):
// 0 only if every output matched the C model bit for bit, no transaction was lost, duplicated or
// reordered, every latency was the unit's, the port protocol held and at least one vector was checked;
// 2 when the run completed and one of those checks FAILED (the waveform, if asked for, is kept: it is
// the evidence); 1 for a bad argument or any other error (one line on stderr, no waveform left).
#include <systemc.h>
#include <verilated.h>
#include <verilated_fst_sc.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadecore/common/args.hpp"
#include "shadecore/common/output_files.hpp"
#include "shadecore/common/progress.hpp"
#include "shadecore/units/coef.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/unit.hpp"
#include "sim_models.hpp"
#include "tb_coverage.hpp"
#include "tb_driver.hpp"
#include "tb_func_cov.hpp"
#include "tb_monitor.hpp"
#include "tb_options.hpp"
#include "tb_pins.hpp"
#include "tb_scoreboard.hpp"
#include "tb_stimulus.hpp"

// libsystemc's main() prints the SystemC banner before sc_main() runs (even for --help): silence it
// before main() unless the user set the variable.
static const int g_banner_off = (setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0), 0);

namespace shadecore::sim {
namespace {

std::string g_prog = "shadecore_cosim";

std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// Reports the driver's accepted count every 4096 clock cycles of simulated time: to the progress bar
// (stderr, when it is a terminal or --progress) and/or as "COSIM-PROGRESS k" lines on stdout for
// `shadecore cosim` (at most 4 per second).
class ProgressProbe : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(ProgressProbe);
  ProgressProbe(sc_core::sc_module_name name, const Driver& drv, const sc_core::sc_time& period, io::Progress* bar,
                bool lines)
      : sc_module(name), drv_(drv), period_(period * 4096), bar_(bar), lines_(lines) {
    SC_THREAD(loop);
  }

 private:
  void loop() {
    auto last = std::chrono::steady_clock::now();
    for (;;) {
      wait(period_);
      const uint64_t d = drv_.accepted();
      if (bar_) bar_->set(d);
      if (lines_) {
        const auto now = std::chrono::steady_clock::now();
        if (now - last >= std::chrono::milliseconds(250)) {
          std::printf("COSIM-PROGRESS %llu\n", static_cast<unsigned long long>(d));
          std::fflush(stdout);
          last = now;
        }
      }
    }
  }
  const Driver& drv_;
  sc_core::sc_time period_;
  io::Progress* bar_;
  bool lines_;
};

struct RunConfig {
  std::string repro;
  std::string trace_file;  // where the waveform is written while the run lasts ("" = none)
  std::string coverage_file;  // coverage build: where the database is written at the end ("" = none)
  bool progress_bar = false, progress_lines = false;
};

template <class M>
int run(const Options& o, const Unit& unit, const RunConfig& rc, std::string& cause) {
  Pins pins;
  M dut("dut");
  pins.bind(dut);
  Scoreboard sb(unit, o.show);
  // Coverage builds with --coverage: the functional model samples every accepted transaction (tb_func_cov.hpp).
  std::unique_ptr<UnitFuncCov> fcov;
  if (kCoverageBuild && !rc.coverage_file.empty()) {
    fcov = std::make_unique<UnitFuncCov>(unit);
    fcov->attach(Verilated::threadContextp());
    sb.model().sample = [](void* c, const UnitMaterial& m, int64_t code) { static_cast<UnitFuncCov*>(c)->sample(m, code); };
    sb.model().sample_ctx = fcov.get();
  }
  Stimulus stim(o, unit);
  // Stalls come from the driver's own generators, seeded per run: a shard starting at transaction `first`
  // gets its own streams (shard 0 / an unsharded run: the seed). Codes, materials and the reset point are
  // functions of (seed, transaction index): the stimulus.
  Options timing = o;
  if (o.first != 0) timing.seed = mix64(o.seed ^ mix64(o.first));
  Driver drv("driver", pins, stim, unit, timing);
  Monitor mon("monitor", pins, sb, drv, o.inject, o.inject_at);
  mon.set_in_bits(unit.format().in_bits());
  if (fcov) {
    mon.logic().edge_sample = edge_func_sample<UnitFuncCov>;
    mon.logic().edge_ctx = fcov.get();
  }
  std::unique_ptr<io::Progress> bar;
  if (rc.progress_bar) bar = std::make_unique<io::Progress>(stim.planned(), true, "cosim");
  std::unique_ptr<ProgressProbe> probe;
  if (bar || rc.progress_lines)
    probe = std::make_unique<ProgressProbe>("progress", drv, pins.clk.period(), bar.get(), rc.progress_lines);

  std::unique_ptr<VerilatedFstSc> tfp;
  if (!rc.trace_file.empty()) {
    Verilated::traceEverOn(true);
    sc_core::sc_start(sc_core::SC_ZERO_TIME);  // elaborate before tracing (Verilator + SystemC)
    tfp = std::make_unique<VerilatedFstSc>();
    dut.trace(tfp.get(), 99);
    tfp->open(rc.trace_file.c_str());
  }
  // The kernel's "Info: /OSCI/SystemC: Simulation stopped by user." after sc_stop() is noise here.
  sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (bar) bar->stop();
  if (tfp) tfp->close();
  sb.finish();
  dut.final();
  write_coverage(Verilated::threadContextp(), rc.coverage_file);  // while the model (its counters) lives

  const Format& f = unit.format();
  // A run that checked nothing is not a pass; a watchdog stop is named as the cause.
  if (mon.watchdog_fired())
    cause = "watchdog: no transfer for " + std::to_string(Monitor::kIdleLimit) + " cycles";
  else if (sb.checked_ == 0)
    cause = "no vector was checked";
  const bool ok = sb.ok() && cause.empty();
  const double vps = wall > 0 ? static_cast<double>(sb.checked_) / wall : 0.0;
  for (const auto& m : sb.first_)
    std::printf("MISMATCH n=%d code=%lld expected=%u got=%u (tag %u, cycle %llu)\n", m.n,
                static_cast<long long>(m.code), m.expected, m.got, m.tag,
                static_cast<unsigned long long>(m.cycle));
  if (!o.quiet || !ok) {
    std::printf(
        "cosim: %s%s%s%s: %llu vectors checked, %llu mismatches, %llu lost, %llu duplicated/reordered, "
        "%llu latency errors, %llu protocol errors; %llu dropped by %llu mid-stream reset(s); "
        "latency %llu..%llu cycles (spec %d advancing); %llu cycles, %.3f s, %.0f vectors/s\n",
        ok ? "PASS" : "FAIL", cause.empty() ? "" : " (", cause.c_str(), cause.empty() ? "" : ")",
        (unsigned long long)sb.checked_, (unsigned long long)sb.mismatches_, (unsigned long long)sb.lost_,
        (unsigned long long)sb.unexpected_, (unsigned long long)sb.latency_errors_,
        (unsigned long long)sb.protocol_errors_, (unsigned long long)sb.dropped_by_reset_,
        (unsigned long long)drv.resets(), (unsigned long long)(sb.checked_ ? sb.lat_min_ : 0),
        (unsigned long long)sb.lat_max_, unit.latency(), (unsigned long long)mon.cycles(), wall, vps);
  }
  if (!ok) std::printf("cosim: reproduce with: %s\n", rc.repro.c_str());
  nlohmann::json j = {
      {"ok", ok},
      {"cause", cause},
      {"config", kSimConfig},
      {"frac", f.frac},
      {"guard", f.guard},
      {"variant", o.variant},
      {"cutoff", o.cutoff},
      {"norm", unit.energy()},
      {"mode", to_string(o.mode)},
      {"n_lo", o.n_lo},
      {"n_hi", o.n_hi},
      {"seed", o.seed},
      {"first", o.first},
      {"in_stall", o.in_stall},
      {"out_stall", o.out_stall},
      {"planned", stim.planned()},
      {"stimulus_digest", stim.digest()},
      {"resets", drv.resets()},
      {"replayed_after_reset", drv.replayed()},
      {"table_writes", drv.table_writes()},
      {"material_writes", sb.material_writes_},
      {"latency_spec", unit.latency()},
      {"cycles", mon.cycles()},
      {"wall_s", wall},
      {"vectors_per_s", vps},
      {"watchdog", mon.watchdog_fired()},
      {"reproduce", rc.repro},
  };
  j.update(sb.counts_json());
  nlohmann::json mm = nlohmann::json::array();
  for (const auto& m : sb.first_)
    mm.push_back({{"n", m.n}, {"code", m.code}, {"expected", m.expected}, {"got", m.got}, {"tag", m.tag}});
  j["first_mismatches"] = mm;
  std::printf("COSIM-RESULT %s\n", j.dump().c_str());
  std::fflush(stdout);
  return ok ? 0 : 2;
}

int main_impl(int argc, char** argv) {
  {
    const std::string a0 = argc > 0 ? argv[0] : "shadecore_cosim";
    const auto slash = a0.rfind('/');
    g_prog = slash == std::string::npos ? a0 : a0.substr(slash + 1);
  }
  io::install_interrupt_cleanup(g_prog.c_str());
  const auto fail = [](const std::string& msg) {
    std::string m = msg;
    for (char& c : m)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "%s: error: %s\n", g_prog.c_str(), m.c_str());
    return 1;
  };
  // Verilator-style plusarg: +trace (waveform cosim.fst) or +trace=FILE.
  std::vector<char*> args;
  std::string plus_trace;
  bool plus_trace_given = false;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (i > 0 && a == "+trace") {
      plus_trace = "cosim.fst";
      plus_trace_given = true;
    } else if (i > 0 && a.rfind("+trace=", 0) == 0) {
      plus_trace = a.substr(7);
      plus_trace_given = true;
      if (plus_trace.empty()) return fail("+trace=: empty path");
    } else if (i > 0 && a[0] == '+') {
      return fail("unknown plusarg '" + a + "' (known: +trace, +trace=FILE)");
    } else {
      args.push_back(argv[i]);
    }
  }

  Options o;
  std::string mode = "directed", n_range = "16..1024";
  bool norm = false, force_progress = false, no_progress = false, progress_lines = false;
  std::string coef_model, coef_kind;
  using namespace cliargs;
  CLI::App app{std::string("co-simulation of rtl/sc_specular.v (config '") + kSimConfig + "') against the C model"};
  app.add_option("--variant", o.variant, "unit variant (config/configs.json variants)");
  app.add_option("--cutoff", o.cutoff, "theta_cr | sign_clamp");
  app.add_option("--mode", mode, "exhaustive | random | directed");
  auto* n_opt = app.add_option("--n", n_range, "exponent range LO..HI or N (exhaustive, random)");
  auto* count_opt = app.add_option("--count", o.count, "random: transactions; directed: minimum items (list repeated)")
                        ->check(UInt(1, 1000000000000ull));
  app.add_option("--seed", o.seed, "random seed (0 = pick one and print it)")->check(UInt(0));
  auto* first_opt = app.add_option("--first", o.first,
                                   "random: index of the first transaction (a shard of a longer run with the same seed)")
                        ->check(UInt(0));
  app.add_option("--in-stall", o.in_stall, "probability per cycle of an input gap, in [0, 1)")->check(Probability(false));
  app.add_option("--out-stall", o.out_stall, "probability per cycle of out_ready_i low, in [0, 1)")
      ->check(Probability(false));
  auto* mat_opt = app.add_option("--mat-rate", o.mat_rate, "random mode: probability per transaction of a material change before it (default 0.01)")
                      ->check(Probability(true));
  auto* reset_opt = app.add_option("--reset-at", o.reset_at,
                                   "pulse rst_ni low once, before the transaction of this index (random: global index, so only "
                                   "the shard holding it resets; -1 none; default: random, drawn from the seed in the "
                                   "middle half of this run; directed, half way; none in exhaustive)")
                        ->check(ResetAt());
  app.add_option("--reset-cycles", o.reset_cycles, "length of each reset pulse")->check(Int(1, 1000));
  bool no_resend = false;
  app.add_flag("--no-resend", no_resend,
               "do not send again the transactions the reset flushes (they are dropped: the run checks fewer)");
  app.add_option("--trace", o.trace, "write an FST waveform to this file (also: +trace, +trace=FILE)")
      ->check(NonEmpty("path"));
  app.add_option("--show", o.show, "errors printed in full per kind")->check(Int(0, 1000000));
  std::string coverage;
  app.add_option("--coverage", coverage, "coverage build only: write the coverage database (coverage.dat) here")
      ->check(NonEmpty("path"));
  auto* inject_opt =
      app.add_option("--inject", o.inject, "self-test: corrupt one observed output (value | drop | dup); the run must FAIL")
          ->check(CLI::IsMember({"value", "drop", "dup"}));
  auto* inject_at_opt =
      app.add_option("--inject-at", o.inject_at, "self-test: which output transfer (1-based)")->check(UInt(1));
  app.add_flag("--quiet", o.quiet, "print only the COSIM-RESULT line when the run passes");
  app.add_flag("--norm", norm, "sc_specular with ENERGY = 1: rtl/sc_energy.v after the unit (cs16, theta_cr)");
  auto* coef_model_opt = app.add_option("--coef-model", coef_model,
                                        "--norm: all (model and kind picked per material from n; the default) | phong | "
                                        "phong_mod | blinn | blinn_mod | blinn_ndf | blinn_hf");
  auto* coef_opt = app.add_option("--coef", coef_kind, "--norm with one --coef-model: fitted (default) | classical");
  auto* pon = app.add_flag("--progress", force_progress, "progress bar on stderr even when it is not a terminal");
  auto* poff = app.add_flag("--no-progress", no_progress, "no progress bar (default: shown when stderr is a terminal)");
  pon->excludes(poff);
  app.add_flag("--progress-lines", progress_lines, "print COSIM-PROGRESS lines on stdout (for shadecore cosim)");
  try {
    app.parse(static_cast<int>(args.size()), args.data());
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    return fail(std::string(e.what()) + " (see " + g_prog + " --help)");
  }
  o.resend = !no_resend;
  if (plus_trace_given && !o.trace.empty()) return fail("give the waveform file once: --trace or +trace, not both");
  if (plus_trace_given) o.trace = plus_trace;
  try {
    if (mode == "exhaustive") o.mode = Mode::Exhaustive;
    else if (mode == "random") o.mode = Mode::Random;
    else if (mode == "directed") o.mode = Mode::Directed;
    else throw std::invalid_argument("unknown mode '" + mode + "' (known: exhaustive, random, directed)");
    std::tie(o.n_lo, o.n_hi) = parse_n_range(n_range);
    // Options that the chosen mode would ignore are errors, not silently dropped.
    if (o.mode == Mode::Directed && n_opt->count())
      throw std::invalid_argument("--n does not apply to --mode directed (the hard cases carry their own n)");
    if (o.mode == Mode::Exhaustive && count_opt->count())
      throw std::invalid_argument("--count does not apply to --mode exhaustive (every code of every n)");
    if (o.mode != Mode::Random && first_opt->count()) throw std::invalid_argument("--first applies to --mode random only");
    if (o.mode != Mode::Random && mat_opt->count()) throw std::invalid_argument("--mat-rate applies to --mode random only");
    if (inject_at_opt->count() && !inject_opt->count()) throw std::invalid_argument("--inject-at needs --inject");
    if (const std::string e = coverage_option_error(coverage); !e.empty()) throw std::invalid_argument(e);
    if (!norm && (coef_model_opt->count() || coef_opt->count()))
      throw std::invalid_argument("--coef-model and --coef apply with --norm only");
    const Format* fmt = nullptr;
    for (const auto& c : kConfigs)
      if (c.name == kSimConfig) fmt = &c.format;
    if (!fmt) throw std::invalid_argument(std::string("config ") + kSimConfig + " not in configs.hpp");
    Unit unit(parse_variant(o.variant), *fmt, parse_cutoff_name(o.cutoff));
    if (norm) {
      if (unit.variant() != VariantId::cs16 || unit.cutoff() != Cutoff::ThetaCr)
        throw std::invalid_argument("--norm is built for --variant cs16 --cutoff theta_cr only");
      const bool one_model = !coef_model.empty() && coef_model != "all";
      if (coef_opt->count() && !one_model)
        throw std::invalid_argument("--coef needs --coef-model MODEL (with all, the kind is picked per material)");
      unit.set_energy(true, one_model ? static_cast<int>(parse_model(coef_model)) : -1,
                    parse_coef_kind(coef_kind.empty() ? "fitted" : coef_kind));
    }
    if (o.seed == 0) {
      o.seed = (static_cast<uint64_t>(std::random_device{}()) << 32) ^ std::random_device{}();
      if (o.seed == 0) o.seed = 1;
    }
    if (o.reset_at == -2) {
      o.reset_at = -1;
      if (o.mode != Mode::Exhaustive && !reset_opt->count()) {
        Stimulus probe(o, unit);
        // random: a global index in the middle half drawn from the seed; directed: half way
        o.reset_at = o.mode == Mode::Random
                         ? static_cast<int64_t>(o.first + stimulus::default_reset_index(o.seed, o.count))
                         : static_cast<int64_t>(probe.planned() / 2);
      }
    }
    // The command that replays this run exactly: every option resolved (the seed picked, the reset
    // point), each given once. The waveform is left out (add +trace to get one).
    RunConfig rc;
    {
      std::string r = argv[0];
      const auto add = [&r](const std::string& k, const std::string& v) { r += " " + k + " " + v; };
      add("--variant", o.variant);
      add("--cutoff", o.cutoff);
      add("--mode", mode);
      if (o.mode != Mode::Directed) add("--n", std::to_string(o.n_lo) + ".." + std::to_string(o.n_hi));
      if (o.mode != Mode::Exhaustive) add("--count", std::to_string(o.count));
      if (o.mode == Mode::Random && o.first) add("--first", std::to_string(o.first));
      add("--seed", std::to_string(o.seed));
      add("--in-stall", shortest(o.in_stall));
      add("--out-stall", shortest(o.out_stall));
      if (o.mode == Mode::Random) add("--mat-rate", shortest(o.mat_rate));
      add("--reset-at", std::to_string(o.reset_at));
      add("--reset-cycles", std::to_string(o.reset_cycles));
      if (!o.resend) r += " --no-resend";
      if (norm) {
        r += " --norm";
        if (!coef_model.empty()) add("--coef-model", coef_model);
        if (!coef_kind.empty()) add("--coef", coef_kind);
      }
      if (!o.inject.empty()) {
        add("--inject", o.inject);
        add("--inject-at", std::to_string(o.inject_at));
      }
      add("--show", std::to_string(o.show));
      rc.repro = r;
    }
    // The waveform is an output like any other: checked now, written beside its target, renamed at the end.
    io::OutputSet outs;
    int trace_out = -1;
    if (!o.trace.empty()) {
      trace_out = outs.file("--trace", o.trace, /*allow_stream=*/false);
      rc.trace_file = outs.produce_path(trace_out, {".hier"});
    }
    if (!coverage.empty()) rc.coverage_file = outs.produce_path(outs.file("--coverage", coverage, /*allow_stream=*/false));
    rc.progress_bar = io::progress_wanted(force_progress, no_progress);
    rc.progress_lines = progress_lines;
    if (!o.quiet)
      std::printf("cosim: config %s (F=%d G=%d) variant %s cutoff %s%s mode %s n %d..%d count %llu seed %llu "
                  "in-stall %g out-stall %g reset-at %lld%s%s\n",
                  kSimConfig, fmt->frac, fmt->guard, o.variant.c_str(), o.cutoff.c_str(),
                  norm ? (" norm (coef model " + (coef_model.empty() ? std::string("all") : coef_model) +
                          (coef_kind.empty() ? "" : " " + coef_kind) + ")")
                             .c_str()
                       : "",
                  mode.c_str(), o.n_lo, o.n_hi, (unsigned long long)o.count, (unsigned long long)o.seed, o.in_stall,
                  o.out_stall, (long long)o.reset_at, o.trace.empty() ? "" : " trace ", o.trace.c_str());
    int rc_status = -1;
    std::string cause;
    const bool found = with_model(static_cast<int>(unit.variant()), static_cast<int>(unit.cutoff()),
                                  [&](auto tag) { rc_status = run<typename decltype(tag)::type>(o, unit, rc, cause); },
                                  norm ? 1 : 0);
    if (!found)
      throw std::invalid_argument("no Verilated model for variant " + o.variant + " cutoff " + o.cutoff +
                                  (norm ? " with --norm" : ""));
    // A failing run keeps its waveform: it is the evidence. An error (exception) leaves nothing.
    outs.commit();
    if (!o.trace.empty()) std::printf("cosim: waveform written to %s\n", o.trace.c_str());
    std::fflush(stdout);
    return rc_status;
  } catch (const std::exception& e) {
    return fail(e.what());
  }
}

}  // namespace
}  // namespace shadecore::sim

int sc_main(int argc, char** argv) {
  (void)g_banner_off;
  return shadecore::sim::main_impl(argc, argv);
}

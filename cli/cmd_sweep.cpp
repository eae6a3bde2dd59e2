// SPDX-License-Identifier: Apache-2.0
// shadecore sweep — exhaustive error sweep of a variant over n × every input code.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "shadecore/common/args.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "shadecore/common/progress.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/units/cs16_forms.hpp"
#include "shadecore/analysis/golden.hpp"
#include "shadecore/units/schlick.hpp"
#include "shadecore/analysis/sweep.hpp"
#include "shadecore/unit.hpp"

namespace shadecore::cli {
namespace {

// A cs16 form with folded truncated squarers (config/configs.json "squarer").
bool is_form(const std::string& v) {
  for (const auto& s : kSquarerForms)
    if (variant_name(s.id) == v) return true;
  return false;
}

struct SweepArgs {
  std::string variant = "cs16";
  std::string cutoff = "theta_cr";
  std::string config;  // a name from config/configs.json
  int frac = 16, guard = 5;
  bool frac_given = false;
  std::string n_range = "16..1024";
  int threads = 0;
  std::string json_path, csv_path, plots_dir;
  ProgressFlags progress;
  bool compare_cutoffs = false;
  bool cutoff_given = false, guard_given = false;  // cs16-only options given explicitly
  bool energy = false;
  bool bases = false, n_given = false;
};

// A published claim and how it is checked.
struct Claim {
  const char* what;
  double claimed;
  double measured;
  const char* note;
};

// "Reproduced" means the measured value, rounded to the two significant digits the paper
// prints, equals the published value.
bool reproduces(double claimed, double measured) {
  return fmt::format("{:.1e}", claimed) == fmt::format("{:.1e}", measured);
}

Format resolve_format(const SweepArgs& a) {
  Format f = config_named(a.config).format;
  if (a.frac_given) f.frac = a.frac;  // explicit values are checked as given (validate), never ignored
  if (a.guard_given) f.guard = a.guard;
  validate(f);
  return f;
}


nlohmann::json extreme_json(const Extreme& e, const Format& f) {
  return {{"value", e.value},
          {"n", e.n},
          {"code", e.code},
          {"cos", std::ldexp(static_cast<double>(e.code), -f.frac)},
          {"theta", std::acos(std::ldexp(static_cast<double>(e.code), -f.frac))}};
}

std::string where(const Extreme& e, const Format& f) {
  return fmt::format("n={:<4} θ={:.6f} rad  code={}", e.n, std::acos(std::ldexp(double(e.code), -f.frac)),
                     e.code);
}

std::string csv_rows(const SweepResult& r) {
  std::ostringstream o;
  o << "n,approx_max,approx_max_code,approx_min,approx_min_code,quant_max_ulp,quant_max_code,"
       "quant_min_ulp,quant_min_code,total_max,total_max_code,total_min,total_min_code,nonzero_codes\n";
  for (const auto& row : r.rows) {
    o << fmt::format("{},{:.9e},{},{:.9e},{},{:.6f},{},{:.6f},{},{:.9e},{},{:.9e},{},{}\n", row.n,
                     row.approx.max.value, row.approx.max.code, row.approx.min.value, row.approx.min.code,
                     row.quant.max.value, row.quant.max.code, row.quant.min.value, row.quant.min.code,
                     row.total.max.value, row.total.max.code, row.total.min.value, row.total.min.code,
                     row.nonzero_codes);
  }
  return o.str();
}

// Fig. 3 is the paper's n = 128; drawn at an n the sweep covered: 128 when it is in LO..HI, else the end of
// the range nearest to it (--n 100..120: n = 120). The n is in the file names (fig3_n<N>.png/.csv).
int fig3_n(int lo, int hi) { return std::clamp(128, lo, hi); }

// Every file --plots DIR gets: the CSV data and the PNGs drawn from it by scripts/plot_sweep.py.
std::vector<std::string> plot_files(int n3) {
  const std::string f3 = "fig3_n" + std::to_string(n3);
  return {f3 + ".csv", "fig4_grid.csv", "per_n.csv", f3 + ".png", "fig4_delta.png", "quant_ulp.png", "approx_over_n.png"};
}

// Data for the plots: Fig. 3 (the curves at n = fig3_n) and Fig. 4 (Δ over n and θ in [0, 1.5] rad, the
// paper's 20θ in [0, 30]).
void write_plot_data(const SweepArgs& a, const SweepResult& r, const std::string& dir) {
  const Format f = r.options.format;
  const Cutoff cut = r.options.cutoff;
  {
    std::ostringstream o;
    // golden_at_code: the double function at the input code's own cos value (code / 2^F): fixed minus it
    // is the quantisation error the contract bounds (fixed minus golden also has the input rounding).
    o << "theta,cos_pow,golden,fixed,golden_at_code\n";
    const int n = fig3_n(r.options.n_lo, r.options.n_hi);
    const Cs16Material m = cs16_setup(f, n);
    // Table units: the bit-exact model through Unit (the table is set up once for this n).
    std::unique_ptr<Unit> table_unit;
    UnitMaterial table_n128;
    if (const VariantId vid = parse_variant(a.variant); is_table_variant(vid)) {
      table_unit = std::make_unique<Unit>(vid, f, cut);
      table_n128 = table_unit->setup(n);
    }
    for (int i = 0; i <= 1000; ++i) {
      const double th = (M_PI / 2) * i / 1000.0;
      const double c = std::cos(th);
      const int64_t code = std::llround(std::ldexp(c, f.frac));
      SchlickForm form = SchlickForm::Div;
      const bool schlick = a.variant.rfind("schlick_", 0) == 0;
      if (a.variant == "schlick_nr") form = SchlickForm::Nr;
      const double fixed =
          a.variant == "cs16" ? std::ldexp(double(cs16_eval(f, cut, m, code)), -f.frac)
          : is_form(a.variant) ? std::ldexp(double(Unit(parse_variant(a.variant), f, cut).eval(UnitMaterial{m.n, m.thr}, code)), -f.frac)
          : schlick           ? std::ldexp(double(schlick_eval(form, f, schlick_setup(f, n), code)), -f.frac)
          : table_n128.tab    ? std::ldexp(double(table_unit->eval(table_n128, code)), -f.frac)
                              : std::nan("");
      const double c_code = std::ldexp(static_cast<double>(code), -f.frac);
      o << fmt::format("{:.9f},{:.12e},{:.12e},{:.12e},{:.12e}\n", th, golden::cos_pow(c, n),
                       variant_golden(a.variant, cut, n, c), fixed, variant_golden(a.variant, cut, n, c_code));
    }
    write_staged(dir + "/fig3_n" + std::to_string(n) + ".csv", o.str());
  }
  {
    std::ostringstream o;
    o << "n,theta,delta\n";
    const int lo = r.options.n_lo, hi = r.options.n_hi;
    const int step = std::max(1, (hi - lo) / 255);
    for (int n = lo; n <= hi; n += step)
      for (int i = 0; i <= 300; ++i) {
        const double th = 1.5 * i / 300.0;  // 20θ in [0, 30] as in the paper's Fig. 4
        const double c = std::cos(th);
        o << fmt::format("{},{:.6f},{:.9e}\n", n, th, golden::cos_pow(c, n) - variant_golden(a.variant, cut, n, c));
      }
    write_staged(dir + "/fig4_grid.csv", o.str());
  }
  write_staged(dir + "/per_n.csv", csv_rows(r));
}

// Lobe energy against cos^n (docs/schlick.md): ∫ f sin θ dθ and ∫ f cos θ sin θ dθ over [0, π/2] for
// the double function (closed form for Schlick, Simpson on t = cos θ otherwise) and for the fixed-point
// outputs (trapezoid over every code), each divided by the cos^n value 1/(n+1) resp. 1/(n+2).
nlohmann::json print_energy(const SweepArgs& a, const SweepOptions& opt) {
  const Format f = opt.format;
  const bool schlick = a.variant.rfind("schlick_", 0) == 0;
  const SchlickForm form = a.variant == "schlick_nr" ? SchlickForm::Nr : a.variant == "schlick_iter" ? SchlickForm::Iter
                                                                                                    : SchlickForm::Div;
  fmt::print("\nLobe energy relative to cos^n (E1 = ∫ f·sinθ dθ vs 1/(n+1); E2 = ∫ f·cosθ·sinθ dθ vs 1/(n+2);\n"
             "double: {}; fixed: trapezoid over the {} output codes):\n",
             schlick ? "closed form" : "Simpson, 2^16 intervals", f.one() + 1);
  fmt::print("{:>6} | {:>11} {:>9} {:>9} | {:>11} {:>9} {:>9} | {:>11}\n", "n", "E1 double", "E1/cosn", "fixed/cosn",
             "E2 double", "E2/cosn", "fixed/cosn", "coef·2π/(n+1)");
  nlohmann::json rows = nlohmann::json::array();
  double r1lo = 1e300, r1hi = 0, r2lo = 1e300, r2hi = 0;
  const double h = std::ldexp(1.0, -f.frac);
  for (int n = opt.n_lo; n <= opt.n_hi; ++n) {
    double e1, e2;
    if (schlick) {
      e1 = golden::schlick_energy(n);
      e2 = golden::schlick_energy_cos(n);
    } else {
      const int N = 1 << 16;
      e1 = e2 = 0;
      for (int i = 0; i <= N; ++i) {
        const double t = double(i) / N, w = (i == 0 || i == N) ? 1 : (i % 2 ? 4 : 2);
        const double g = variant_golden(a.variant, opt.cutoff, n, t);
        e1 += w * g;
        e2 += w * g * t;
      }
      e1 /= 3.0 * N;
      e2 /= 3.0 * N;
    }
    double q1 = 0, q2 = 0;
    const Cs16Material cm = cs16_setup(f, n);
    const SchlickMaterial sm = schlick_setup(f, n);
    for (int64_t code = 0; code <= f.one(); ++code) {
      const double y = std::ldexp(double(schlick ? schlick_eval(form, f, sm, code) : cs16_eval(f, opt.cutoff, cm, code)),
                                  -f.frac);
      const double w = (code == 0 || code == f.one()) ? 0.5 : 1.0;
      q1 += w * y * h;
      q2 += w * y * (double(code) * h) * h;
    }
    const double c1 = golden::cos_pow_energy(n), c2 = golden::cos_pow_energy_cos(n);
    r1lo = std::min(r1lo, e1 / c1); r1hi = std::max(r1hi, e1 / c1);
    r2lo = std::min(r2lo, e2 / c2); r2hi = std::max(r2hi, e2 / c2);
    rows.push_back({{"n", n}, {"e1", e1}, {"e1_fixed", q1}, {"e1_cos_pow", c1}, {"e2", e2}, {"e2_fixed", q2},
                    {"e2_cos_pow", c2}, {"coef_2pi", 1.0 / e1}});
    const bool pow2 = (n & (n - 1)) == 0;
    if (pow2 || n == opt.n_lo || n == opt.n_hi)
      fmt::print("{:>6} | {:>11.5e} {:>9.4f} {:>9.4f} | {:>11.5e} {:>9.4f} {:>9.4f} | {:>11.4f}\n", n, e1, e1 / c1,
                 q1 / c1, e2, e2 / c2, q2 / c2, (1.0 / e1) / (n + 1.0));
  }
  fmt::print("E1/cos^n over n = {}..{}: {:.4f} .. {:.4f};  E2/cos^n: {:.4f} .. {:.4f}\n", opt.n_lo, opt.n_hi, r1lo,
             r1hi, r2lo, r2hi);
  fmt::print("(coef·2π = 1/E1 is the factor that makes 2π·coef·E1 = 1; the last column divides it by the cos^n value n+1)\n");
  return {{"rows", rows}, {"e1_ratio", {r1lo, r1hi}}, {"e2_ratio", {r2lo, r2hi}}};
}

// --bases: a cs16 form's squarings (S1..S5) on every x0 = base in [0, 2^(F+4)]. After the cut the output
// depends on x0 alone, so this covers every fragment of every n (docs/spec.md §3.4) in 2^(F+4) + 1
// evaluations: the contract check of the wide width (F = 24: 2.7·10^8) without the 10^9-code sweep.
void run_bases(const SweepArgs& a) {
  const SquarerForm* form = is_form(a.variant) ? squarer_form(parse_variant(a.variant)) : nullptr;
  if (!form) {
    std::string names;
    for (const auto& s : kSquarerForms) names += (names.empty() ? "" : ", ") + std::string(variant_name(s.id));
    throw std::invalid_argument("--bases applies to the cs16 forms only (" + names + "), not to '" + a.variant + "'");
  }
  if (a.n_given || a.cutoff_given || a.energy || a.compare_cutoffs || !a.csv_path.empty() || !a.plots_dir.empty())
    throw std::invalid_argument("--bases takes no --n, --cutoff, --energy, --compare-cutoffs, --csv or --plots "
                                "(every base of every n, both cut-offs)");
  const Format f = resolve_format(a);
  const Cs16Stages st = cs16_stages(f, *form);
  const Cs16Contract c = cs16_contract(form->contract, f);
  io::OutputSet outs;
  const int json_out = a.json_path.empty() ? -1 : outs.file("--json", a.json_path);

  const uint64_t top = uint64_t{1} << (f.frac + 4), total = top + 1, chunk = uint64_t{1} << 16;
  const int threads = cliargs::resolve_parallel(a.threads);
  struct Ext {
    double lo = 1e300, hi = -1e300;
    uint64_t lo_x = 0, hi_x = 0;
  };
  std::vector<Ext> ext(threads);
  std::atomic<uint64_t> next{0};
  io::Progress bar(total, a.progress.enabled());
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      Ext e;
      for (uint64_t b; (b = next.fetch_add(chunk)) < total;) {
        const uint64_t end = std::min(total, b + chunk);
        for (uint64_t x0 = b; x0 < end; ++x0) {
          const long double y = powl(static_cast<long double>(x0) / top, 16) * static_cast<long double>(f.one());
          const double err = double(static_cast<long double>(cs16f_squarings(f, st, x0)) - y);
          if (err < e.lo) e = Ext{err, e.hi, x0, e.hi_x};
          if (err > e.hi) e = Ext{e.lo, err, e.lo_x, x0};
        }
        bar.add(end - b);
      }
      ext[t] = e;
    });
  for (auto& th : pool) th.join();
  bar.stop();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Ext e;
  for (const auto& x : ext) {
    if (x.lo < e.lo || (x.lo == e.lo && x.lo_x < e.lo_x)) { e.lo = x.lo; e.lo_x = x.lo_x; }
    if (x.hi > e.hi || (x.hi == e.hi && x.hi_x < e.hi_x)) { e.hi = x.hi; e.hi_x = x.hi_x; }
  }
  const bool met = (c.lo_strict ? e.lo > c.lo : e.lo >= c.lo) && e.hi <= c.hi;
  fmt::print("shadecore sweep --bases  variant={} F={} G={}  x0 = 0..2^{} ({} values, every fragment of every n)\n",
             a.variant, f.frac, f.guard, f.frac + 4, total);
  fmt::print("{} evaluations in {:.3f} s on {} threads\n", total, secs, threads);
  fmt::print("quantisation  out − (x0/2^{})^16·2^{}:  max {:.5f} ulp at x0 = {}   min {:.5f} ulp at x0 = {}\n", f.frac + 4,
             f.frac, e.hi, e.hi_x, e.lo, e.lo_x);
  fmt::print("Contract '{}': {:.5f} {} quant <= {:.5f} ulp; measured [{:.5f}, {:.5f}] → {}\n", form->contract, c.lo,
             c.lo_strict ? "<" : "<=", c.hi, e.lo, e.hi, met ? "MET" : "VIOLATED");
  if (json_out >= 0) {
    nlohmann::json j;
    j["variant"] = a.variant;
    j["mode"] = "bases";
    j["format"] = {{"frac", f.frac}, {"guard", f.guard}};
    j["evaluations"] = total;
    j["seconds"] = secs;
    j["threads"] = threads;
    j["quant_ulp"] = {{"max", {{"value", e.hi}, {"x0", e.hi_x}}}, {"min", {{"value", e.lo}, {"x0", e.lo_x}}}};
    j["contract"] = {{"name", form->contract}, {"lo", c.lo}, {"lo_strict", c.lo_strict}, {"hi", c.hi}, {"met", met}};
    outs.set(json_out, j.dump(2) + "\n");
  }
  outs.commit();
}

void run(const SweepArgs& a) {
  if (a.bases) {
    run_bases(a);
    return;
  }
  SweepOptions opt;
  opt.variant = a.variant;
  bool known = false;
  for (const auto& v : sweep_variants()) known |= (v == a.variant);
  if (!known) {
    std::string names;
    for (const auto& v : sweep_variants()) names += (names.empty() ? "" : ", ") + v;
    throw std::invalid_argument("unknown variant '" + a.variant + "' (known: " + names + ")");
  }
  opt.format = resolve_format(a);
  opt.cutoff = parse_cutoff_name(a.cutoff);
  const auto [lo, hi] = cliargs::parse_n_range(a.n_range);
  opt.n_lo = lo;
  opt.n_hi = hi;
  opt.threads = cliargs::resolve_parallel(a.threads);
  if (a.variant != "cs16" && !is_form(a.variant) && (a.cutoff_given || a.guard_given))
    throw std::invalid_argument("--cutoff and --guard apply to cs16 and its forms only");
  if (a.variant != "cs16" && a.compare_cutoffs)
    throw std::invalid_argument("--compare-cutoffs applies to the cs16 variant only");
  if (a.energy && is_table_variant(parse_variant(a.variant)))
    throw std::invalid_argument("--energy is implemented for cs16 and the Schlick forms only, not for " + a.variant);
  // Every output is checked before the run and written only if the whole run succeeds.
  io::OutputSet outs;
  const int json_out = a.json_path.empty() ? -1 : outs.file("--json", a.json_path);
  const int csv_out = a.csv_path.empty() ? -1 : outs.file("--csv", a.csv_path);
  const int plots_out = a.plots_dir.empty() ? -1 : outs.dir("--plots", a.plots_dir, plot_files(fig3_n(lo, hi)));

  const uint64_t total = uint64_t(opt.format.one() + 1) * uint64_t(hi - lo + 1);
  io::Progress bar(total, a.progress.enabled());
  opt.progress = [&bar](uint64_t k) { bar.add(k); };
  const SweepResult r = run_sweep(opt);
  bar.stop();
  const Format f = opt.format;
  // The cut-off form and the guard bits are cs16 parameters; the Schlick forms use F only.
  const std::string label = (a.variant == "cs16" || is_form(a.variant))
                                ? fmt::format("{} cutoff={} F={} G={}", a.variant, to_string(opt.cutoff), f.frac, f.guard)
                                : fmt::format("{} F={}", a.variant, f.frac);

  fmt::print("shadecore sweep  variant={}  n={}..{}  codes=0..{}\n", label, lo, hi, f.one());
  fmt::print("{} evaluations in {:.3f} s on {} threads ({:.1f} M/s)\n\n", r.evaluations, r.seconds, r.threads_used,
             r.evaluations / r.seconds / 1e6);
  fmt::print("{:>6} | {:>11} {:>11} | {:>9} {:>9} | {:>11} {:>11} | {:>8}\n", "n", "approx max", "approx min",
             "quant max", "quant min", "total max", "total min", "lobe");
  fmt::print("{:>6} | {:>11} {:>11} | {:>9} {:>9} | {:>11} {:>11} | {:>8}\n", "", "(abs)", "(abs)", "(ulp)",
             "(ulp)", "(abs)", "(abs)", "(codes)");
  fmt::print("{}\n", std::string(96, '-'));
  for (const auto& row : r.rows) {
    const bool pow2 = (row.n & (row.n - 1)) == 0;
    if (!(pow2 || row.n == lo || row.n == hi)) continue;
    fmt::print("{:>6} | {:>11.3e} {:>11.3e} | {:>9.4f} {:>9.4f} | {:>11.3e} {:>11.3e} | {:>8}\n", row.n,
               row.approx.max.value, row.approx.min.value, row.quant.max.value, row.quant.min.value,
               row.total.max.value, row.total.min.value, row.nonzero_codes);
  }
  fmt::print("{}\n", std::string(96, '-'));
  auto line = [&](const char* name, const ErrorStats& s, const char* unit, const char* fmtspec) {
    fmt::print("{:<36} max {:>12} {:<4} at {}\n", name, fmt::format(fmt::runtime(fmtspec), s.max.value), unit,
               where(s.max, f));
    fmt::print("{:<36} min {:>12} {:<4} at {}\n", "", fmt::format(fmt::runtime(fmtspec), s.min.value), unit,
               where(s.min, f));
  };
  line("approximation  cos^n − f_double", r.approx, "", "{:.4e}");
  line("quantisation   f_fixed − f_double", r.quant, "ulp", "{:.5f}");
  line("total          cos^n − f_fixed", r.total, "", "{:.4e}");

  nlohmann::json verdicts = nlohmann::json::array();
  if (a.variant == "cs16") {
    fmt::print("\nPublished claims (Δ = cos^n θ − cs16(θ, n) in double, max/min over n = 16..1024 and every\n"
               "input code's θ = acos(code/2^F) in [0, π/2]; reproduced = equal at the 2 significant digits printed):\n");
    const bool full = (lo == kNMin && hi == kNMax);
    const Claim claims[] = {
        {"max Δ", 1.7e-2, r.approx.max.value, ""},
        {"min Δ", -9.7e-3, r.approx.min.value,
         "cs16 <= cos^n wherever the base is >= 0 (Bernoulli: c^(n/16) >= 1 + (n/16)(c-1)); Δ < 0 can only "
         "come from double rounding or the negative-base sliver, where cs16 <= 2.3e-15"}};
    for (const auto& c : claims) {
      const bool ok = full && reproduces(c.claimed, c.measured);
      const std::string verdict = !full ? "NOT CHECKED (n range is not 16..1024)" : ok ? "REPRODUCED" : "NOT REPRODUCED";
      fmt::print("  claim {} = {:.1e}: measured {:.4e} → {}\n", c.what, c.claimed, c.measured, verdict);
      if (!ok && *c.note) fmt::print("    why: {}\n", c.note);
      verdicts.push_back({{"claim", c.what}, {"published", c.claimed}, {"measured", c.measured},
                          {"verdict", verdict}, {"note", c.note},
                          {"definition", "cos^n(theta) - cs16_double(theta, n), n=16..1024, theta=acos(code/2^F)"}});
    }
  }

  // The variant's contract on the quantisation error (quant_contract: also the bounds quant_ulp.png draws).
  const QuantContract qc = quant_contract(a.variant, f);
  const bool met = qc.met(r.quant.min.value, r.quant.max.value);
  fmt::print("\nContract '{}': {:.5f} {} quant <= {:.5f} ulp; measured [{:.5f}, {:.5f}] → {}\n", qc.name, qc.lo,
             qc.lo_strict ? "<" : "<=", qc.hi, r.quant.min.value, r.quant.max.value, met ? "MET" : "VIOLATED");
  const nlohmann::json contract = {{"name", qc.name}, {"lo", qc.lo}, {"lo_strict", qc.lo_strict}, {"hi", qc.hi}, {"met", met}};

  nlohmann::json energy;
  if (a.energy) energy = print_energy(a, opt);

  nlohmann::json cutcmp;
  if (a.compare_cutoffs && a.variant == "cs16") {
    // Evidence for docs/spec.md §1: where do the two cut-off forms differ?
    uint64_t diff_fixed = 0;
    double max_double = 0.0;
    for (int n = lo; n <= hi; ++n) {
      const Cs16Material m = cs16_setup(f, n);
      for (int64_t code = 0; code <= f.one(); ++code) {
        diff_fixed += cs16_eval(f, Cutoff::ThetaCr, m, code) != cs16_eval(f, Cutoff::SignClamp, m, code);
        const double c = std::ldexp(double(code), -f.frac);
        max_double = std::max(max_double, std::fabs(golden::cs16_theta_cr(c, n) - golden::cs16_sign_clamp(c, n)));
      }
    }
    fmt::print("\nCut-off forms: theta_cr vs sign_clamp differ in {} fixed-point outputs; max |difference| of the\n"
               "double functions over the same codes = {:.3e}\n", diff_fixed, max_double);
    cutcmp = {{"differing_fixed_outputs", diff_fixed}, {"max_abs_double_difference", max_double}};
  }

  if (json_out >= 0) {
    nlohmann::json j;
    j["variant"] = a.variant;
    j["cutoff"] = to_string(opt.cutoff);
    j["format"] = {{"frac", f.frac}, {"guard", f.guard}};
    j["n_range"] = {lo, hi};
    j["evaluations"] = r.evaluations;
    j["seconds"] = r.seconds;
    j["threads"] = r.threads_used;
    for (auto [key, s] : {std::pair{"approx", &r.approx}, {"quant_ulp", &r.quant}, {"total", &r.total}})
      j[key] = {{"max", extreme_json(s->max, f)}, {"min", extreme_json(s->min, f)}};
    // Per n: the extremes of each error (scripts/plot_table_crossover.py reads max |total| per n from here).
    nlohmann::json per_n = nlohmann::json::array();
    for (const auto& row : r.rows)
      per_n.push_back({{"n", row.n},
                       {"approx_max", row.approx.max.value},
                       {"approx_min", row.approx.min.value},
                       {"quant_max_ulp", row.quant.max.value},
                       {"quant_min_ulp", row.quant.min.value},
                       {"total_max", row.total.max.value},
                       {"total_min", row.total.min.value}});
    j["per_n"] = per_n;
    j["verdicts"] = verdicts;
    j["contract"] = contract;
    if (!cutcmp.is_null()) j["cutoff_comparison"] = cutcmp;
    if (!energy.is_null()) j["energy"] = energy;
    outs.set(json_out, j.dump(2) + "\n");
  }
  if (csv_out >= 0) outs.set(csv_out, csv_rows(r));
  if (plots_out >= 0) {
    const std::string stage = outs.stage(plots_out);
    write_plot_data(a, r, stage);
    std::fflush(stdout);
    run_python("plot_sweep.py",
               {"--dir", stage, "--title", label, "--variant", a.variant, "--frac", std::to_string(f.frac), "--guard",
                std::to_string(f.guard), "--fig3-n", std::to_string(fig3_n(lo, hi)), "--n-range",
                fmt::format("{}..{}", lo, hi), fmt::format("--approx-max={:.6e}", r.approx.max.value),
                fmt::format("--approx-min={:.6e}", r.approx.min.value), "--contract-name", qc.name,
                fmt::format("--contract-lo={:.17g}", qc.lo), fmt::format("--contract-hi={:.17g}", qc.hi),
                qc.lo_strict ? "--contract-lo-strict" : "--contract-lo-inclusive", "--command", command_line()});
  }
  outs.commit();
  if (plots_out >= 0) {
    fmt::print("\nplots written to {}/\n", a.plots_dir);
    if (fig3_n(lo, hi) != 128)
      fmt::print("fig3_n{0}.png: Fig. 3 at n = {0}, the swept n nearest to the paper's 128 (outside {1}..{2})\n",
                 fig3_n(lo, hi), lo, hi);
  }
}

}  // namespace

void add_sweep(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  auto* sub = app.add_subcommand("sweep", "Exhaustive error sweep: every n × every input code");
  std::string variants;  // every variant the sweep engine takes (sweep_variants(): the forms and table units too)
  for (const auto& v : sweep_variants()) variants += (variants.empty() ? "" : ", ") + v;
  sub->add_option("--variant", args->variant, "Specular variant (" + variants + ")")->check(cliargs::NonEmpty("unit name"));
  auto* cutoff_opt = sub->add_option("--cutoff", args->cutoff, "cs16 cut-off form: theta_cr | sign_clamp")->check(cliargs::NonEmpty("cut-off"));
  sub->add_option("--config", args->config, "Named width configuration from config/configs.json")
      ->check(cliargs::NonEmpty("config name"));
  auto* frac_opt = sub->add_option("--frac", args->frac, "Fraction bits F (8..24), overrides --config");
  auto* guard_opt = sub->add_option("--guard", args->guard, "Guard bits G (4..8, F+G <= 31), overrides --config");
  auto* n_opt = sub->add_option("--n", args->n_range, "Exponent range LO..HI or N (within 16..1024)")->check(cliargs::NonEmpty("range"));
  sub->add_option("--threads", args->threads, "Worker threads (0 = all cores; at most 64)")
      ->check(cliargs::Int(0, cliargs::kMaxParallel));
  sub->add_option("--json", args->json_path, "Write the summary as JSON")->check(cliargs::NonEmpty("path"));
  sub->add_option("--csv", args->csv_path, "Write one row per n as CSV")->check(cliargs::NonEmpty("path"));
  sub->add_option("--plots", args->plots_dir, "Write PNG plots (and their CSV data) into this directory")
      ->check(cliargs::NonEmpty("path"));
  args->progress.add(sub);
  sub->add_flag("--energy", args->energy, "Also print the lobe energy relative to cos^n per n (docs/schlick.md)");
  sub->add_flag("--compare-cutoffs", args->compare_cutoffs, "Also count outputs where theta_cr and sign_clamp differ");
  sub->add_flag("--bases", args->bases,
                "cs16 forms: check the contract on every base x0 in [0, 2^(F+4)] instead (covers every fragment of every n)");
  sub->callback([args, cutoff_opt, frac_opt, guard_opt, n_opt] {
    args->n_given = n_opt->count() > 0;
    args->cutoff_given = cutoff_opt->count() > 0;
    args->frac_given = frac_opt->count() > 0;
    args->guard_given = guard_opt->count() > 0;
    run(*args);
  });
}

}  // namespace shadecore::cli

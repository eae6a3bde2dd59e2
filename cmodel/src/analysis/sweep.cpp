// SPDX-License-Identifier: Apache-2.0
// shadecore — exhaustive error sweep engine (see sweep.hpp).
#include "shadecore/analysis/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "shadecore/units/cs16_forms.hpp"
#include "shadecore/analysis/golden.hpp"
#include "shadecore/unit.hpp"
#include "shadecore/units/schlick.hpp"
#include "shadecore/units/table.hpp"
#include "shadecore/unit.hpp"

namespace shadecore {

void ErrorStats::merge(const ErrorStats& o) {
  auto better = [](const Extreme& a, const Extreme& b, bool want_max) {
    if (!b.valid()) return false;
    if (!a.valid()) return true;
    if (b.value != a.value) return want_max ? b.value > a.value : b.value < a.value;
    return b.n < a.n || (b.n == a.n && b.code < a.code);  // deterministic tie-break
  };
  if (better(max, o.max, true)) max = o.max;
  if (better(min, o.min, false)) min = o.min;
}

namespace {

// A sweep kernel: per-material setup, the bit-accurate unit and its double twin.
struct Cs16Kernel {
  Format f;
  Cutoff cut;
  struct Mat {
    Cs16Material m;
    double ccr;  // cos θcr in double, the golden twin of m.thr
  };
  const Cs16Stages* stages = nullptr;  // a cs16 form (cs16_forms.hpp), or the reference datapath
  Mat setup(int n) const { return {cs16_setup(f, n), std::cos(golden::theta_cr(n))}; }
  uint32_t fixed(const Mat& m, int64_t code) const {
    return stages ? cs16f_eval(f, cut, *stages, m.m, code) : cs16_eval(f, cut, m.m, code);
  }
  double golden(const Mat& m, double c) const {
    const double b = golden::cs16_base(c, m.m.n);
    const bool is_cut = (cut == Cutoff::ThetaCr) ? (c < m.ccr) : (b <= 0.0);
    return is_cut ? 0.0 : golden::pow16(b);
  }
};

// Schlick-divide forms (docs/spec.md §6): the fixed-point unit and Schlick's S(t, n) in double.
struct SchlickKernel {
  Format f;
  SchlickForm form;
  using Mat = SchlickMaterial;
  Mat setup(int n) const { return schlick_setup(f, n); }
  uint32_t fixed(const Mat& m, int64_t code) const { return schlick_eval(form, f, m, code); }
  double golden(const Mat& m, double c) const { return golden::schlick(c, m.n); }
};

// Table-and-interpolate units (docs/spec.md §9): the fixed-point table lerp and the same table lerp in
// double (T(i) = (i/(E−1))^n exact in double, interpolated at f = (E−1)·c).
struct TableKernel {
  Format f;
  int entries;
  struct Mat {
    TableMaterial m;
    std::vector<double> t;  // golden table
  };
  Mat setup(int n) const { return {table_setup(f, entries, n), golden::table_golden(entries, n)}; }
  uint32_t fixed(const Mat& m, int64_t code) const { return table_eval(f, m.m.words.data(), entries, code); }
  double golden(const Mat& m, double c) const { return golden::table_lerp(m.t.data(), entries, c); }
};

// Name -> table size; 0 if the name is not a table variant.
int table_variant_entries(const std::string& v) {
  for (const auto& nv : kVariants)
    if (nv.name == v && nv.contract == "table") return nv.entries;
  return 0;
}

// Name -> form; false if the name is not a Schlick variant.
bool schlick_form(const std::string& v, SchlickForm& form) {
  if (v == "schlick_div") form = SchlickForm::Div;
  else if (v == "schlick_nr") form = SchlickForm::Nr;
  else if (v == "schlick_iter") form = SchlickForm::Iter;
  else return false;
  return true;
}

template <class Kernel>
void sweep_codes(const Kernel& k, const std::vector<typename Kernel::Mat>& mats, int n_lo, int64_t code_lo,
                 int64_t code_hi, std::vector<SweepRow>& rows, const std::function<void(uint64_t)>& progress) {
  const int F = k.f.frac;
  const double scale = std::ldexp(1.0, F), inv_scale = std::ldexp(1.0, -F);
  const int nn = static_cast<int>(mats.size());
  int64_t since_report = 0;
  for (int64_t code = code_lo; code < code_hi; ++code) {
    const double c = static_cast<double>(code) * inv_scale;
    // cos^n by repeated multiplication from one pow per code: relative error < n·2^-53.
    double p = std::pow(c, n_lo);
    for (int i = 0; i < nn; ++i, p *= c) {
      const int n = n_lo + i;
      const uint32_t q = k.fixed(mats[i], code);
      const double g = k.golden(mats[i], c);
      SweepRow& r = rows[i];
      r.approx.add(p - g, n, code);
      r.quant.add(static_cast<double>(q) - g * scale, n, code);
      r.total.add(p - static_cast<double>(q) * inv_scale, n, code);
      r.nonzero_codes += (q != 0);
    }
    since_report += nn;
    if (progress && since_report >= (int64_t{1} << 20)) {
      progress(static_cast<uint64_t>(since_report));
      since_report = 0;
    }
  }
  if (progress && since_report) progress(static_cast<uint64_t>(since_report));
}

template <class Kernel>
SweepResult run_kernel(const Kernel& k, const SweepOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<typename Kernel::Mat> mats;
  for (int n = opt.n_lo; n <= opt.n_hi; ++n) mats.push_back(k.setup(n));
  const int64_t codes = k.f.one() + 1;  // every code in [0, 2^F]
  int threads = opt.threads > 0 ? opt.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = static_cast<int>(std::clamp<int64_t>(threads, 1, codes));
  std::vector<std::vector<SweepRow>> partial(threads, std::vector<SweepRow>(mats.size()));
  std::vector<std::thread> pool;
  // Interleaved blocks balance the work (large codes are inside more lobes).
  const int64_t block = 4096;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (int64_t lo = t * block; lo < codes; lo += threads * block)
        sweep_codes(k, mats, opt.n_lo, lo, std::min(codes, lo + block), partial[t], opt.progress);
    });
  }
  for (auto& th : pool) th.join();

  SweepResult res;
  res.options = opt;
  res.threads_used = threads;
  res.rows.resize(mats.size());
  for (size_t i = 0; i < mats.size(); ++i) {
    SweepRow& r = res.rows[i];
    r.n = opt.n_lo + static_cast<int>(i);
    for (int t = 0; t < threads; ++t) {
      r.approx.merge(partial[t][i].approx);
      r.quant.merge(partial[t][i].quant);
      r.total.merge(partial[t][i].total);
      r.nonzero_codes += partial[t][i].nonzero_codes;
    }
    res.approx.merge(r.approx);
    res.quant.merge(r.quant);
    res.total.merge(r.total);
  }
  res.evaluations = static_cast<uint64_t>(codes) * mats.size();
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace

std::vector<std::string> sweep_variants() {
  std::vector<std::string> v = {"cs16", "schlick_div", "schlick_nr", "schlick_iter"};
  for (const auto& s : kSquarerForms) v.emplace_back(variant_name(s.id));  // cs16 forms
  for (const auto& nv : kVariants)
    if (nv.contract == "table") v.emplace_back(nv.name);  // table units
  return v;
}

namespace {
const SquarerForm* form_named(const std::string& v) {
  for (const auto& s : kSquarerForms)
    if (variant_name(s.id) == v) return &s.form;
  return nullptr;
}
}  // namespace

SweepResult run_sweep(const SweepOptions& opt) {
  validate(opt.format);
  validate_n(opt.n_lo);
  validate_n(opt.n_hi);
  if (opt.n_lo > opt.n_hi)
    throw std::invalid_argument("empty n range " + std::to_string(opt.n_lo) + ".." + std::to_string(opt.n_hi));
  if (opt.variant == "cs16") return run_kernel(Cs16Kernel{opt.format, opt.cutoff}, opt);
  if (const SquarerForm* form = form_named(opt.variant)) {
    const Cs16Stages st = cs16_stages(opt.format, *form);
    return run_kernel(Cs16Kernel{opt.format, opt.cutoff, &st}, opt);
  }
  if (SchlickForm form; schlick_form(opt.variant, form)) return run_kernel(SchlickKernel{opt.format, form}, opt);
  if (const int e = table_variant_entries(opt.variant)) return run_kernel(TableKernel{opt.format, e}, opt);
  throw std::invalid_argument("unknown variant '" + opt.variant + "'");
}

QuantContract quant_contract(const std::string& variant, const Format& f) {
  if (variant == "cs16") {  // the reference datapath's faithful bound: −(½ + 15·2^−G) < q <= ½
    const Cs16Contract c = cs16_contract("faithful", f);
    return {"faithful", c.lo, c.hi, c.lo_strict};
  }
  if (const SquarerForm* form = form_named(variant)) {
    const Cs16Contract c = cs16_contract(form->contract, f);
    return {std::string(form->contract), c.lo, c.hi, c.lo_strict};
  }
  if (variant == "schlick_div" || variant == "schlick_iter") return {"exact", -0.5, 0.5, false};  // |q| <= ½
  if (variant == "schlick_nr") {
    const double b = schlick_nr_bound_ulp(f.frac);
    return {"faithful", -b, b, false};
  }
  if (table_variant_entries(variant)) return {"table", kTableQuantMin, kTableQuantMax, true};  // −1 < q <= 1
  throw std::invalid_argument("unknown variant '" + variant + "'");
}

double variant_golden(const std::string& variant, Cutoff cutoff, int n, double c) {
  if (variant == "cs16" || form_named(variant))
    return cutoff == Cutoff::ThetaCr ? golden::cs16_theta_cr(c, n) : golden::cs16_sign_clamp(c, n);
  if (SchlickForm form; schlick_form(variant, form)) return golden::schlick(c, n);
  if (const int e = table_variant_entries(variant)) {
    // The golden table of the last (entries, n) asked for in this thread (the plot loops go n by n).
    thread_local int last_e = 0, last_n = 0;
    thread_local std::vector<double> t;
    if (last_e != e || last_n != n) {
      t = golden::table_golden(e, n);
      last_e = e;
      last_n = n;
    }
    return golden::table_lerp(t.data(), e, c);
  }
  throw std::invalid_argument("unknown variant '" + variant + "'");
}

}  // namespace shadecore

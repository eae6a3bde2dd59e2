// SPDX-License-Identifier: Apache-2.0
// shadecore._core — the pybind11 binding of the bit-accurate C model (issue 38; docs/python.md).
//
// Every function calls the model the CLI calls (shadecore::Unit, cs16_eval_block, the golden references,
// energy_setup / energy_eval, normalize3, recip_att, run_sweep): no second model. The array functions take
// C-contiguous NumPy arrays (python/shadecore/__init__.py converts, checks dtypes and broadcasts; no per-element
// Python loop), release the GIL while they compute, and raise ValueError (std::invalid_argument) with the
// model's one-line messages — the text the CLI prints after "shadecore: error: ".
#include <fmt/core.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadecore/analysis/golden.hpp"
#include "shadecore/analysis/sweep.hpp"
#include "shadecore/common/args.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/unit.hpp"
#include "shadecore/units/coef.hpp"
#include "shadecore/units/cs16_forms.hpp"
#include "shadecore/units/normalize.hpp"
#include "shadecore/units/recip.hpp"

namespace py = pybind11;

namespace shadecore::python {
namespace {

using I64 = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;
using F64 = py::array_t<double, py::array::c_style | py::array::forcecast>;

// ---------------------------------------------------------------------------- unit resolution
// The same resolution as the CLI's --variant/--config/--frac/--guard/--cutoff/--norm/--coef (cli/unit_spec.hpp
// resolve_unit), on the model's own parsers, so a bad name gets the same "unknown variant 'x' (known: ...)".
struct Spec {
  VariantId variant = VariantId::cs16;
  std::string variant_name = "cs16";
  Format format;
  Cutoff cutoff = Cutoff::ThetaCr;
  bool norm = false;
  int norm_model = -1;
  CoefKind coef_kind = CoefKind::Fitted;
  [[nodiscard]] bool is_cs16() const { return variant == VariantId::cs16 || squarer_form(variant) != nullptr; }
  [[nodiscard]] Unit unit() const {
    Unit u(variant, format, cutoff);
    if (norm) u.set_energy(true, norm_model, coef_kind);
    return u;
  }
};

Format resolve_format(const std::string& config, std::optional<int> frac, std::optional<int> guard) {
  Format f = config_named(config).format;
  if (frac) f.frac = *frac;
  if (guard) f.guard = *guard;
  validate(f);
  return f;
}

Spec resolve(const std::string& variant, const std::string& config, std::optional<int> frac, std::optional<int> guard,
             std::optional<std::string> cutoff, std::optional<std::string> norm, std::optional<std::string> coef) {
  Spec s;
  s.variant = parse_variant(variant);
  s.variant_name = std::string(variant_name(s.variant));
  s.format = resolve_format(config, frac, guard);
  s.cutoff = parse_cutoff_name(cutoff.value_or("theta_cr"));
  if (!s.is_cs16()) {
    if (cutoff) throw std::invalid_argument("cutoff applies to cs16 and its forms only, not to " + s.variant_name);
    if (guard) throw std::invalid_argument("guard applies to cs16 and its forms only, not to " + s.variant_name);
  }
  if (norm) {
    s.norm = true;
    if (*norm == "all") {
      if (coef) throw std::invalid_argument("coef needs norm=MODEL (with norm='all' the kind is chosen per n)");
      s.norm_model = -1;
    } else {
      s.norm_model = static_cast<int>(parse_model(*norm));
      s.coef_kind = parse_coef_kind(coef.value_or("fitted"));
    }
  } else if (coef) {
    throw std::invalid_argument("coef needs norm=MODEL");
  }
  return s;
}

// The CLI's --code range check (cmd_eval.cpp parse_code), for element i of an array.
void check_code(const Format& f, int64_t code) {
  if (code < f.in_min() || code > f.in_max())
    throw std::invalid_argument("code " + std::to_string(code) + " out of range [" + std::to_string(f.in_min()) + ", " +
                                std::to_string(f.in_max()) + "] (F+2 = " + std::to_string(f.in_bits()) +
                                "-bit signed word)");
}

// Either n is one value for every element (size 1) or one per element (same size as the data).
void check_n_shape(py::ssize_t n_size, py::ssize_t size) {
  if (n_size != 1 && n_size != size)
    throw std::invalid_argument("n has " + std::to_string(n_size) + " elements for " + std::to_string(size) +
                                " inputs (give one n or one per input)");
}

template <class T>
py::array_t<T> empty_like_shape(const py::array& a) {
  std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
  return py::array_t<T>(shape);
}

// ---------------------------------------------------------------------------- units
// out[i] = Unit::eval(setup(n[i]), codes[i]) — exactly what `shadecore eval` / `vectors` compute per input.
py::array_t<int64_t> unit_eval(const std::string& variant, const I64& codes, const I64& n, const std::string& config,
                               std::optional<int> frac, std::optional<int> guard, std::optional<std::string> cutoff,
                               std::optional<std::string> norm, std::optional<std::string> coef) {
  const Spec spec = resolve(variant, config, frac, guard, cutoff, norm, coef);
  const py::ssize_t size = codes.size();
  check_n_shape(n.size(), size);
  py::array_t<int64_t> out = empty_like_shape<int64_t>(codes);
  const int64_t* c = codes.data();
  const int64_t* nv = n.data();
  int64_t* o = out.mutable_data();
  const bool scalar_n = n.size() == 1;
  {
    py::gil_scoped_release nogil;
    for (py::ssize_t i = 0; i < (scalar_n ? 1 : size); ++i) validate_n(nv[i]);
    for (py::ssize_t i = 0; i < size; ++i) check_code(spec.format, c[i]);
    const Unit unit = spec.unit();
    if (scalar_n) {
      const UnitMaterial mat = unit.setup(nv[0]);
      // The cs16 reference on consecutive codes: the block form (bit-identical, test Cs16Block.BitIdenticalToScalar).
      bool consecutive = spec.variant == VariantId::cs16 && !spec.norm && size > 1;
      for (py::ssize_t i = 1; consecutive && i < size; ++i) consecutive = c[i] == c[0] + i;
      if (consecutive) {
        std::vector<uint32_t> tmp(static_cast<size_t>(size));
        cs16_eval_block(spec.format, spec.cutoff, Cs16Material{mat.n, mat.thr}, c[0], size, tmp.data());
        for (py::ssize_t i = 0; i < size; ++i) o[i] = tmp[static_cast<size_t>(i)];
      } else {
        for (py::ssize_t i = 0; i < size; ++i) o[i] = unit.eval(mat, c[i]);
      }
    } else {  // one material per n, set up on first use
      std::vector<std::optional<UnitMaterial>> mats(kNMax - kNMin + 1);
      for (py::ssize_t i = 0; i < size; ++i) {
        auto& m = mats[static_cast<size_t>(nv[i] - kNMin)];
        if (!m) m = unit.setup(nv[i]);
        o[i] = unit.eval(*m, c[i]);
      }
    }
  }
  return out;
}

// Material words per n: mat_thr_i (0 where the unit has none) and mat_coef_i (0 without norm).
py::dict unit_setup(const std::string& variant, const I64& n, const std::string& config, std::optional<int> frac,
                    std::optional<int> guard, std::optional<std::string> cutoff, std::optional<std::string> norm,
                    std::optional<std::string> coef) {
  const Spec spec = resolve(variant, config, frac, guard, cutoff, norm, coef);
  py::array_t<int64_t> thr = empty_like_shape<int64_t>(n), cf = empty_like_shape<int64_t>(n);
  const int64_t* nv = n.data();
  int64_t *t = thr.mutable_data(), *k = cf.mutable_data();
  {
    py::gil_scoped_release nogil;
    const Unit unit = spec.unit();
    for (py::ssize_t i = 0; i < n.size(); ++i) {
      validate_n(nv[i]);
      const UnitMaterial m = unit.setup(nv[i]);
      t[i] = m.thr;
      k[i] = m.coef;
    }
  }
  py::dict d;
  d["thr"] = thr;
  d["coef"] = cf;
  d["latency"] = spec.unit().latency();
  d["frac"] = spec.format.frac;
  d["guard"] = spec.format.guard;
  d["out_bits"] = spec.norm ? spec.format.frac + kCoefIntBits : spec.format.out_bits();
  return d;
}

// cos θ → the nearest input code, ties away from zero (the CLI's --cos rule, cmd_eval.cpp).
py::array_t<int64_t> cos_to_code(const F64& cosv, const std::string& config, std::optional<int> frac) {
  const Format f = resolve_format(config, frac, std::nullopt);
  py::array_t<int64_t> out = empty_like_shape<int64_t>(cosv);
  const double* x = cosv.data();
  int64_t* o = out.mutable_data();
  {
    py::gil_scoped_release nogil;
    for (py::ssize_t i = 0; i < cosv.size(); ++i) {
      if (!std::isfinite(x[i])) throw std::invalid_argument("cos must be a finite number");
      const double scaled = std::ldexp(x[i], f.frac);
      if (scaled < double(f.in_min()) - 0.5 || scaled >= double(f.in_max()) + 0.5)
        throw std::invalid_argument(fmt::format("cos {} is outside the input word's range [-2, 2) at F = {}", x[i], f.frac));
      o[i] = std::llround(scaled);
    }
  }
  return out;
}

// ---------------------------------------------------------------------------- golden references
template <class Fn>
py::array_t<double> golden_map(const F64& c, const I64& n, bool check_n, Fn fn) {
  const py::ssize_t size = c.size();
  check_n_shape(n.size(), size);
  py::array_t<double> out = empty_like_shape<double>(c);
  const double* x = c.data();
  const int64_t* nv = n.data();
  double* o = out.mutable_data();
  {
    py::gil_scoped_release nogil;
    const bool scalar_n = n.size() == 1;
    for (py::ssize_t i = 0; i < n.size(); ++i) {
      if (check_n) validate_n(nv[i]);
      else if (nv[i] < 0 || nv[i] > (int64_t{1} << 30))
        throw std::invalid_argument("exponent n = " + std::to_string(nv[i]) + " out of range [0, 2^30]");
    }
    for (py::ssize_t i = 0; i < size; ++i) o[i] = fn(x[i], static_cast<int>(scalar_n ? nv[0] : nv[i]));
  }
  return out;
}

// ---------------------------------------------------------------------------- energy (sc_energy)
EnergyFormat energy_format(int frac, int int_bits) {
  EnergyFormat f{frac, int_bits};
  validate(f);
  return f;
}

py::array_t<double> coef_values(const std::string& model, const I64& n, const std::string& kind) {
  const Model m = parse_model(model);
  const CoefKind k = parse_coef_kind(kind);
  py::array_t<double> out = empty_like_shape<double>(n);
  const int64_t* nv = n.data();
  double* o = out.mutable_data();
  py::gil_scoped_release nogil;
  for (py::ssize_t i = 0; i < n.size(); ++i) {
    validate_n(nv[i]);
    o[i] = coef_value(m, k, static_cast<double>(nv[i]));
  }
  return out;
}

py::array_t<int64_t> coef_codes(const std::string& model, const I64& n, const std::string& kind, int frac,
                                int int_bits) {
  const Model m = parse_model(model);
  const CoefKind k = parse_coef_kind(kind);
  const EnergyFormat f = energy_format(frac, int_bits);
  py::array_t<int64_t> out = empty_like_shape<int64_t>(n);
  const int64_t* nv = n.data();
  int64_t* o = out.mutable_data();
  py::gil_scoped_release nogil;
  for (py::ssize_t i = 0; i < n.size(); ++i) o[i] = energy_setup(f, m, k, nv[i]);
  return out;
}

py::array_t<int64_t> energy_evals(const I64& spec, const I64& coef, int frac, int int_bits) {
  const EnergyFormat f = energy_format(frac, int_bits);
  const py::ssize_t size = spec.size();
  if (coef.size() != 1 && coef.size() != size)
    throw std::invalid_argument("coef has " + std::to_string(coef.size()) + " elements for " + std::to_string(size) +
                                " inputs (give one coefficient code or one per input)");
  py::array_t<int64_t> out = empty_like_shape<int64_t>(spec);
  const int64_t *s = spec.data(), *k = coef.data();
  int64_t* o = out.mutable_data();
  py::gil_scoped_release nogil;
  const int64_t one = int64_t{1} << f.frac, kmax = (int64_t{1} << f.coef_bits()) - 1;
  for (py::ssize_t i = 0; i < coef.size(); ++i)
    check_in_range("coefficient code", k[i], 0, kmax);
  for (py::ssize_t i = 0; i < size; ++i) {
    check_in_range("unit output code", s[i], 0, one);
    o[i] = static_cast<int64_t>(energy_eval(f, static_cast<uint32_t>(k[coef.size() == 1 ? 0 : i]),
                                            static_cast<uint32_t>(s[i])));
  }
  return out;
}

// ---------------------------------------------------------------------------- lighting operators
void check_light_frac(int frac) { check_in_range("fraction width", frac, kFracMin, kFracMax); }

py::array_t<int64_t> normalize3_array(const I64& v, int frac) {
  check_light_frac(frac);
  if (v.ndim() < 1 || v.shape(v.ndim() - 1) != 3)
    throw std::invalid_argument("normalize3 needs vectors in the last axis of length 3");
  py::array_t<int64_t> out = empty_like_shape<int64_t>(v);
  const int64_t* x = v.data();
  int64_t* o = out.mutable_data();
  py::gil_scoped_release nogil;
  const py::ssize_t count = v.size() / 3;
  const int64_t lim = int64_t{1} << 31;  // v·v and v_i·y2 fit 64 bits
  for (py::ssize_t i = 0; i < 3 * count; ++i)
    if (x[i] <= -lim || x[i] >= lim)
      throw std::invalid_argument("normalize3: component " + std::to_string(x[i]) +
                                  " out of range (|v_i| < 2^31, so that v·v fits 64 bits)");
  for (py::ssize_t i = 0; i < count; ++i) normalize3(frac, x + 3 * i, o + 3 * i);
  return out;
}

py::array_t<int64_t> recip_array(const I64& q, int frac) {
  check_light_frac(frac);
  py::array_t<int64_t> out = empty_like_shape<int64_t>(q);
  const int64_t* x = q.data();
  int64_t* o = out.mutable_data();
  py::gil_scoped_release nogil;
  for (py::ssize_t i = 0; i < q.size(); ++i)
    if (x[i] < 0) throw std::invalid_argument("recip: q = " + std::to_string(x[i]) + " is negative (q >= 0)");
  for (py::ssize_t i = 0; i < q.size(); ++i) o[i] = static_cast<int64_t>(recip_att(frac, static_cast<uint64_t>(x[i])));
  return out;
}

// ---------------------------------------------------------------------------- sweep
py::dict sweep(const std::string& variant, const std::string& n_range, const std::string& config,
               std::optional<int> frac, std::optional<int> guard, std::optional<std::string> cutoff, int threads) {
  // The CLI's checks and messages (cli/cmd_sweep.cpp run()).
  bool known = false;
  std::string names;
  for (const auto& v : sweep_variants()) {
    known |= (v == variant);
    names += (names.empty() ? "" : ", ") + v;
  }
  if (!known) throw std::invalid_argument("unknown variant '" + variant + "' (known: " + names + ")");
  SweepOptions opt;
  opt.variant = variant;
  opt.format = resolve_format(config, frac, guard);
  opt.cutoff = parse_cutoff_name(cutoff.value_or("theta_cr"));
  const auto [lo, hi] = cliargs::parse_n_range(n_range);
  opt.n_lo = lo;
  opt.n_hi = hi;
  if (threads < 0 || threads > cliargs::kMaxParallel)
    throw std::invalid_argument("threads " + std::to_string(threads) + " out of range [0, " +
                                std::to_string(cliargs::kMaxParallel) + "]");
  opt.threads = cliargs::resolve_parallel(threads);
  const VariantId vid = parse_variant(variant);
  const bool cs16_like = vid == VariantId::cs16 || squarer_form(vid) != nullptr;
  if (!cs16_like && (cutoff || guard)) throw std::invalid_argument("cutoff and guard apply to cs16 and its forms only");
  SweepResult r;
  {
    py::gil_scoped_release nogil;
    r = run_sweep(opt);
  }
  const size_t rows = r.rows.size();
  auto col_i = [&](auto get) {
    py::array_t<int64_t> a(static_cast<py::ssize_t>(rows));
    for (size_t i = 0; i < rows; ++i) a.mutable_data()[i] = get(r.rows[i]);
    return a;
  };
  auto col_d = [&](auto get) {
    py::array_t<double> a(static_cast<py::ssize_t>(rows));
    for (size_t i = 0; i < rows; ++i) a.mutable_data()[i] = get(r.rows[i]);
    return a;
  };
  py::dict d;
  d["n"] = col_i([](const SweepRow& w) { return w.n; });
  d["approx_max"] = col_d([](const SweepRow& w) { return w.approx.max.value; });
  d["approx_max_code"] = col_i([](const SweepRow& w) { return w.approx.max.code; });
  d["approx_min"] = col_d([](const SweepRow& w) { return w.approx.min.value; });
  d["approx_min_code"] = col_i([](const SweepRow& w) { return w.approx.min.code; });
  d["quant_max_ulp"] = col_d([](const SweepRow& w) { return w.quant.max.value; });
  d["quant_max_code"] = col_i([](const SweepRow& w) { return w.quant.max.code; });
  d["quant_min_ulp"] = col_d([](const SweepRow& w) { return w.quant.min.value; });
  d["quant_min_code"] = col_i([](const SweepRow& w) { return w.quant.min.code; });
  d["total_max"] = col_d([](const SweepRow& w) { return w.total.max.value; });
  d["total_max_code"] = col_i([](const SweepRow& w) { return w.total.max.code; });
  d["total_min"] = col_d([](const SweepRow& w) { return w.total.min.value; });
  d["total_min_code"] = col_i([](const SweepRow& w) { return w.total.min.code; });
  d["nonzero_codes"] = col_i([](const SweepRow& w) { return static_cast<int64_t>(w.nonzero_codes); });
  auto ext = [](const Extreme& e) {
    py::dict x;
    x["value"] = e.value;
    x["n"] = e.n;
    x["code"] = e.code;
    return x;
  };
  for (auto [key, s] : {std::pair{"approx", &r.approx}, {"quant_ulp", &r.quant}, {"total", &r.total}}) {
    py::dict x;
    x["max"] = ext(s->max);
    x["min"] = ext(s->min);
    d[key] = x;
  }
  d["variant"] = variant;
  d["cutoff"] = to_string(opt.cutoff);
  d["frac"] = opt.format.frac;
  d["guard"] = opt.format.guard;
  d["evaluations"] = r.evaluations;
  d["seconds"] = r.seconds;
  d["threads"] = r.threads_used;
  return d;
}

}  // namespace
}  // namespace shadecore::python

PYBIND11_MODULE(_core, m) {
  using namespace shadecore;
  using namespace shadecore::python;
  namespace g = shadecore::golden;
  m.doc() = "shadecore C model binding (use the shadecore package, not _core)";
  m.attr("__version__") = SHADECORE_VERSION;

  m.def("unit_eval", &unit_eval, py::arg("variant"), py::arg("codes"), py::arg("n"), py::arg("config") = "",
        py::arg("frac") = py::none(), py::arg("guard") = py::none(), py::arg("cutoff") = py::none(),
        py::arg("norm") = py::none(), py::arg("coef") = py::none());
  m.def("unit_setup", &unit_setup, py::arg("variant"), py::arg("n"), py::arg("config") = "",
        py::arg("frac") = py::none(), py::arg("guard") = py::none(), py::arg("cutoff") = py::none(),
        py::arg("norm") = py::none(), py::arg("coef") = py::none());
  m.def("cos_to_code", &cos_to_code, py::arg("cos"), py::arg("config") = "", py::arg("frac") = py::none());
  m.def("format", [](const std::string& config, std::optional<int> frac, std::optional<int> guard) {
    const Format f = resolve_format(config, frac, guard);
    py::dict d;
    d["frac"] = f.frac;
    d["guard"] = f.guard;
    d["in_min"] = f.in_min();
    d["in_max"] = f.in_max();
    d["one"] = f.one();
    return d;
  }, py::arg("config") = "", py::arg("frac") = py::none(), py::arg("guard") = py::none());
  m.def("variants", [] {
    std::vector<std::string> v;
    for (const auto& x : kVariants) v.emplace_back(x.name);
    return v;
  });
  m.def("configs", [] {
    std::vector<std::string> v;
    for (const auto& c : kConfigs) v.emplace_back(c.name);
    return v;
  });
  m.def("models", [] {
    std::vector<std::string> v;
    for (const auto& x : kModels) v.emplace_back(x.key);
    return v;
  });
  m.def("sweep_variants", &sweep_variants);
  m.def("sweep", &sweep, py::arg("variant"), py::arg("n"), py::arg("config") = "", py::arg("frac") = py::none(),
        py::arg("guard") = py::none(), py::arg("cutoff") = py::none(), py::arg("threads") = 0);

  m.def("golden_cos_pow", [](const F64& c, const I64& n) {
    return golden_map(c, n, false, [](double x, int k) { return g::cos_pow(x, k); });
  });
  m.def("golden_cs16", [](const F64& c, const I64& n, const std::string& cutoff) {
    const Cutoff cut = parse_cutoff_name(cutoff);
    return golden_map(c, n, true, [cut](double x, int k) {
      return cut == Cutoff::ThetaCr ? g::cs16_theta_cr(x, k) : g::cs16_sign_clamp(x, k);
    });
  });
  m.def("golden_schlick", [](const F64& c, const I64& n) {
    return golden_map(c, n, true, [](double x, int k) { return g::schlick(x, k); });
  });
  m.def("golden_variant", [](const std::string& variant, const F64& c, const I64& n, const std::string& cutoff) {
    const Cutoff cut = parse_cutoff_name(cutoff);
    parse_variant(variant);  // unknown names: the model's message
    return golden_map(c, n, true, [&variant, cut](double x, int k) { return variant_golden(variant, cut, k, x); });
  });
  m.def("theta_cr", [](const I64& n) {
    py::array_t<double> out = empty_like_shape<double>(n);
    for (py::ssize_t i = 0; i < n.size(); ++i) {
      validate_n(n.data()[i]);
      out.mutable_data()[i] = g::theta_cr(static_cast<int>(n.data()[i]));
    }
    return out;
  });

  m.def("coef_value", &coef_values, py::arg("model"), py::arg("n"), py::arg("kind") = "fitted");
  m.def("coef_code", &coef_codes, py::arg("model"), py::arg("n"), py::arg("kind") = "fitted", py::arg("frac") = 16,
        py::arg("int_bits") = kCoefIntBits);
  m.def("energy_eval", &energy_evals, py::arg("spec"), py::arg("coef"), py::arg("frac") = 16,
        py::arg("int_bits") = kCoefIntBits);
  m.def("normalize3", &normalize3_array, py::arg("v"), py::arg("frac") = 16);
  m.def("normalize3_bound_ulp", &normalize3_bound_ulp, py::arg("frac"));
  m.def("recip", &recip_array, py::arg("q"), py::arg("frac") = 16);
}

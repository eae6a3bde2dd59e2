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
#include "shadecore/features.hpp"
#include "shadecore/light.hpp"
#include "shadecore/render/render.hpp"
#include "shadecore/render/scene.hpp"
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

// The (n × code) grid out[r][j] = Unit::eval(setup(n[r]), codes[j]) without materialising the broadcast inputs:
// one material per row, the cs16 block form on consecutive codes.
py::array_t<int64_t> unit_eval_outer(const std::string& variant, const I64& codes, const I64& n, const std::string& config,
                                     std::optional<int> frac, std::optional<int> guard, std::optional<std::string> cutoff,
                                     std::optional<std::string> norm, std::optional<std::string> coef) {
  const Spec spec = resolve(variant, config, frac, guard, cutoff, norm, coef);
  const py::ssize_t m = codes.size(), k = n.size();
  py::array_t<int64_t> out({k, m});
  const int64_t* c = codes.data();
  const int64_t* nv = n.data();
  int64_t* o = out.mutable_data();
  {
    py::gil_scoped_release nogil;
    for (py::ssize_t r = 0; r < k; ++r) validate_n(nv[r]);
    for (py::ssize_t j = 0; j < m; ++j) check_code(spec.format, c[j]);
    const Unit unit = spec.unit();
    bool consecutive = spec.variant == VariantId::cs16 && !spec.norm && m > 1;
    for (py::ssize_t j = 1; consecutive && j < m; ++j) consecutive = c[j] == c[0] + j;
    std::vector<uint32_t> tmp(consecutive ? static_cast<size_t>(m) : 0);
    for (py::ssize_t r = 0; r < k; ++r) {
      const UnitMaterial mat = unit.setup(nv[r]);
      int64_t* row = o + r * m;
      if (consecutive) {
        cs16_eval_block(spec.format, spec.cutoff, Cs16Material{mat.n, mat.thr}, c[0], m, tmp.data());
        for (py::ssize_t j = 0; j < m; ++j) row[j] = tmp[static_cast<size_t>(j)];
      } else {
        for (py::ssize_t j = 0; j < m; ++j) row[j] = unit.eval(mat, c[j]);
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

// The (n × c) grid of a golden function: out[r][j] = fn(c[j], n[r]).
template <class Fn>
py::array_t<double> golden_outer(const F64& c, const I64& n, bool check_n, Fn fn) {
  const py::ssize_t m = c.size(), k = n.size();
  py::array_t<double> out({k, m});
  const double* x = c.data();
  const int64_t* nv = n.data();
  double* o = out.mutable_data();
  {
    py::gil_scoped_release nogil;
    for (py::ssize_t r = 0; r < k; ++r) {
      if (check_n) validate_n(nv[r]);
      else if (nv[r] < 0 || nv[r] > (int64_t{1} << 30))
        throw std::invalid_argument("exponent n = " + std::to_string(nv[r]) + " out of range [0, 2^30]");
    }
    for (py::ssize_t r = 0; r < k; ++r)
      for (py::ssize_t j = 0; j < m; ++j) o[r * m + j] = fn(x[j], static_cast<int>(nv[r]));
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


// ---------------------------------------------------------------------------- the lighting core
// LightCore of a feature set and the register state it holds: programmed by register writes (as the RTL and the
// handoff vectors) or from a GL-like state (JSON text from the Python layer) through the host-side helpers the
// renderer uses (light_writes, material_writes, global_writes, ...); eval / eval_double on arrays of fragments.
class PyLightCore {
 public:
  explicit PyLightCore(const std::string& features_json_or_name, bool is_json)
      : core_(make(features_json_or_name, is_json)) {}

  const LightCore& core() const { return core_; }
  std::string name() const { return core_.features().name; }
  std::string summary() const { return core_.features().summary(); }
  std::string key() const { return core_.features().key(); }

  // Register writes in order; returns how many hit a register (others are ignored, as by the RTL).
  int write(const I64& addr, const I64& data) {
    if (addr.size() != data.size())
      throw std::invalid_argument("write: " + std::to_string(addr.size()) + " addresses for " +
                                  std::to_string(data.size()) + " data words");
    int hits = 0;
    const LightWidths w = core_.widths();
    for (py::ssize_t i = 0; i < addr.size(); ++i) {
      check_in_range("register address", addr.data()[i], 0, 511);
      check_in_range("register data", data.data()[i], 0, 0xFFFFFFFFll);
      hits += regs_.write(w, static_cast<uint32_t>(addr.data()[i]), static_cast<uint32_t>(data.data()[i]));
    }
    return hits;
  }

  // The GL-like state → register writes (applied; also returned as (addr, data) pairs).
  std::vector<std::pair<uint32_t, uint32_t>> program(const std::string& state_json) {
    const nlohmann::json st = nlohmann::json::parse(state_json);
    auto keys = [](const nlohmann::json& j, const std::string& where, std::initializer_list<const char*> known) {
      if (!j.is_object()) throw std::invalid_argument(where + " must be a dict");
      for (auto it = j.begin(); it != j.end(); ++it) {
        bool ok = false;
        std::string list;
        for (const char* k : known) {
          ok |= it.key() == k;
          list += (list.empty() ? "" : ", ") + std::string(k);
        }
        if (!ok) throw std::invalid_argument("unknown key '" + it.key() + "' in " + where + " (known: " + list + ")");
      }
    };
    auto vec = [](const nlohmann::json& j, const std::string& what, double* out, int count) {
      if (!j.is_array() || static_cast<int>(j.size()) != count)
        throw std::invalid_argument(what + " must be a list of " + std::to_string(count) + " numbers");
      for (int i = 0; i < count; ++i) {
        if (!j[static_cast<size_t>(i)].is_number()) throw std::invalid_argument(what + " must be a list of numbers");
        out[i] = j[static_cast<size_t>(i)].get<double>();
      }
    };
    auto material = [&](const nlohmann::json& j, const std::string& where) {
      keys(j, where, {"emission", "ambient", "diffuse", "specular", "shininess", "unit", "norm", "coef"});
      MaterialParams m;
      if (j.contains("emission")) vec(j["emission"], where + ".emission", m.emission, 3);
      if (j.contains("ambient")) vec(j["ambient"], where + ".ambient", m.ambient, 3);
      if (j.contains("diffuse")) vec(j["diffuse"], where + ".diffuse", m.diffuse, 3);
      if (j.contains("specular")) vec(j["specular"], where + ".specular", m.specular, 3);
      if (j.contains("shininess")) m.shininess = j["shininess"].get<int>();
      if (j.contains("unit")) m.unit = parse_variant(j["unit"].get<std::string>());
      m.norm_model = -1;
      if (j.contains("norm") && !j["norm"].is_null()) m.norm_model = static_cast<int>(parse_model(j["norm"].get<std::string>()));
      if (j.contains("coef")) m.norm_kind = parse_coef_kind(j["coef"].get<std::string>());
      return m;
    };
    keys(st, "state", {"global_ambient", "modes", "material", "back_material", "colour_material", "lights"});
    const FeatureSet& fs = core_.features();
    std::vector<RegWrite> w;
    auto add = [&w](const std::vector<RegWrite>& v) { w.insert(w.end(), v.begin(), v.end()); };
    double ga[3] = {0.2, 0.2, 0.2};  // GL's default global ambient
    if (st.contains("global_ambient")) vec(st["global_ambient"], "global_ambient", ga, 3);
    ModeParams md = default_modes(fs);
    if (st.contains("modes")) {
      const auto& m = st["modes"];
      keys(m, "modes", {"local_viewer", "phong", "normalize", "separate_specular", "two_side"});
      if (m.contains("local_viewer")) md.local_viewer = m["local_viewer"].get<bool>();
      if (m.contains("phong")) md.phong = m["phong"].get<bool>();
      if (m.contains("normalize")) md.normalize = m["normalize"].get<bool>();
      if (m.contains("separate_specular")) md.separate_specular = m["separate_specular"].get<bool>();
      if (m.contains("two_side")) md.two_side = m["two_side"].get<bool>();
    }
    add(global_writes(core_, ga, md));
    add(material_writes(core_, st.contains("material") ? material(st["material"], "material") : MaterialParams{}));
    if (st.contains("back_material")) add(back_material_writes(core_, material(st["back_material"], "back_material")));
    if (st.contains("colour_material")) {
      if (!fs.colour_material) throw std::invalid_argument("colour_material: this core has no colour_material feature");
      const std::string cm = st["colour_material"].is_null() ? "none" : st["colour_material"].get<std::string>();
      std::optional<ColourMaterial> mode;
      const std::pair<const char*, ColourMaterial> names[] = {
          {"emission", ColourMaterial::Emission}, {"ambient", ColourMaterial::Ambient}, {"diffuse", ColourMaterial::Diffuse},
          {"specular", ColourMaterial::Specular}, {"ambient_and_diffuse", ColourMaterial::AmbientAndDiffuse}};
      bool known = cm == "none";
      for (const auto& [nm, v] : names)
        if (cm == nm) mode = v, known = true;
      if (!known)
        throw std::invalid_argument("unknown colour_material mode '" + cm +
                                    "' (known: none, emission, ambient, diffuse, specular, ambient_and_diffuse)");
      add(colour_material_writes(mode));
    }
    const nlohmann::json lights = st.contains("lights") ? st["lights"] : nlohmann::json::array();
    if (!lights.is_array()) throw std::invalid_argument("lights must be a list of dicts");
    if (static_cast<int>(lights.size()) > fs.num_lights())
      throw std::invalid_argument(std::to_string(lights.size()) + " lights for a core with " +
                                  std::to_string(fs.num_lights()) + " light slots");
    for (int j = 0; j < fs.num_lights(); ++j) {
      if (j >= static_cast<int>(lights.size())) {
        add(light_off_writes(j));
        continue;
      }
      const auto& L = lights[static_cast<size_t>(j)];
      const std::string where = "lights[" + std::to_string(j) + "]";
      keys(L, where, {"position", "ambient", "diffuse", "specular", "kc", "kl", "kq", "spot_direction", "spot_cutoff",
                      "spot_exponent", "enabled", "kind"});
      LightParams lp;
      if (L.contains("position")) vec(L["position"], where + ".position", lp.position, 4);
      if (L.contains("ambient")) vec(L["ambient"], where + ".ambient", lp.ambient, 3);
      if (L.contains("diffuse")) vec(L["diffuse"], where + ".diffuse", lp.diffuse, 3);
      if (L.contains("specular")) vec(L["specular"], where + ".specular", lp.specular, 3);
      if (L.contains("spot_direction")) vec(L["spot_direction"], where + ".spot_direction", lp.spot_direction, 3);
      if (L.contains("kc")) lp.kc = L["kc"].get<double>();
      if (L.contains("kl")) lp.kl = L["kl"].get<double>();
      if (L.contains("kq")) lp.kq = L["kq"].get<double>();
      if (L.contains("spot_cutoff")) lp.spot_cutoff = L["spot_cutoff"].get<double>();
      if (L.contains("spot_exponent")) lp.spot_exponent = L["spot_exponent"].get<int>();
      if (L.contains("enabled")) lp.enabled = L["enabled"].get<bool>();
      if (L.contains("kind")) {
        const std::string k = L["kind"].get<std::string>();
        std::string known;
        for (int i = 0; i < kNumLightKinds; ++i) {
          known += (known.empty() ? "" : ", ") + std::string(to_string(static_cast<LightKind>(i)));
          if (k == to_string(static_cast<LightKind>(i))) lp.kind = static_cast<LightKind>(i);
        }
        if (!lp.kind) throw std::invalid_argument("unknown light kind '" + k + "' in " + where + " (known: " + known + ")");
      }
      add(light_writes(core_, j, lp));
    }
    std::vector<std::pair<uint32_t, uint32_t>> out;
    const LightWidths wd = core_.widths();
    for (const RegWrite& x : w) {
      regs_.write(wd, x.addr, x.data);
      out.emplace_back(x.addr, x.data);
    }
    return out;
  }

  // Fragments from arrays: n (k,3) and p (k,3) signed codes, colour (k,3) codes or none, back (k,) bools or none.
  std::vector<Fragment> fragments(const I64& n, const I64& p, const std::optional<I64>& colour,
                                  const std::optional<I64>& back) const {
    auto shape3 = [](const I64& a, const char* what) {
      if (a.ndim() != 2 || a.shape(1) != 3) throw std::invalid_argument(std::string(what) + " must have shape (k, 3)");
      return a.shape(0);
    };
    const py::ssize_t k = shape3(n, "n");
    if (shape3(p, "p") != k) throw std::invalid_argument("n and p have different numbers of fragments");
    if (colour && shape3(*colour, "colour") != k) throw std::invalid_argument("colour has another number of fragments");
    if (back && back->size() != k) throw std::invalid_argument("back has another number of fragments");
    const int F = core_.format().frac;
    const int64_t nlim = int64_t{1} << (F + 1), plim = int64_t{1} << (F + kPosIntBits), clim = (int64_t{1} << (F + 1)) - 1;
    std::vector<Fragment> fr(static_cast<size_t>(k));
    for (py::ssize_t i = 0; i < k; ++i) {
      Fragment& f = fr[static_cast<size_t>(i)];
      for (int c = 0; c < 3; ++c) {
        f.n[c] = n.data()[3 * i + c];
        f.p[c] = p.data()[3 * i + c];
        check_in_range("normal code", f.n[c], -nlim, nlim - 1);
        check_in_range("position code", f.p[c], -plim, plim - 1);
        if (colour) {
          const int64_t v = colour->data()[3 * i + c];
          check_in_range("colour code", v, 0, clim);
          f.col[c] = static_cast<uint32_t>(v);
        }
      }
      if (back) f.back = back->data()[i] != 0;
    }
    return fr;
  }

  py::dict eval(const I64& n, const I64& p, const std::optional<I64>& colour, const std::optional<I64>& back) const {
    const std::vector<Fragment> fr = fragments(n, p, colour, back);
    const auto k = static_cast<py::ssize_t>(fr.size());
    py::array_t<int64_t> c({k, py::ssize_t{3}}), s({k, py::ssize_t{3}});
    int64_t *cp = c.mutable_data(), *sp = s.mutable_data();
    {
      py::gil_scoped_release nogil;
      for (py::ssize_t i = 0; i < k; ++i) {
        const Colour col = core_.eval(regs_, fr[static_cast<size_t>(i)]);
        for (int ch = 0; ch < 3; ++ch) {
          cp[3 * i + ch] = col.c[ch];
          sp[3 * i + ch] = col.s[ch];
        }
      }
    }
    py::dict d;
    d["colour"] = c;
    d["secondary"] = s;
    return d;
  }

  py::dict eval_double(const I64& n, const I64& p, const std::optional<I64>& colour, const std::optional<I64>& back,
                       const std::string& reference) const {
    LightCore::SpecRef ref;
    if (reference == "exact") ref = LightCore::SpecRef::Exact;
    else if (reference == "variant") ref = LightCore::SpecRef::Variant;
    else throw std::invalid_argument("unknown reference '" + reference + "' (known: exact, variant)");
    const std::vector<Fragment> fr = fragments(n, p, colour, back);
    const auto k = static_cast<py::ssize_t>(fr.size());
    py::array_t<double> c({k, py::ssize_t{3}}), s({k, py::ssize_t{3}});
    double *cp = c.mutable_data(), *sp = s.mutable_data();
    {
      py::gil_scoped_release nogil;
      for (py::ssize_t i = 0; i < k; ++i) {
        std::array<double, 3> sec{};
        const std::array<double, 3> col = core_.eval_double(regs_, fr[static_cast<size_t>(i)], ref, nullptr, &sec);
        for (int ch = 0; ch < 3; ++ch) {
          cp[3 * i + ch] = col[static_cast<size_t>(ch)];
          sp[3 * i + ch] = sec[static_cast<size_t>(ch)];
        }
      }
    }
    py::dict d;
    d["colour"] = c;
    d["secondary"] = s;
    return d;
  }

  // Eye-space doubles → fragment codes (make_fragment: normal rounded and saturated, position range-checked).
  py::tuple fragment_codes(const F64& n, const F64& p) const {
    if (n.ndim() != 2 || n.shape(1) != 3 || p.ndim() != 2 || p.shape(1) != 3 || n.shape(0) != p.shape(0))
      throw std::invalid_argument("fragment_codes: n and p must have the same shape (k, 3)");
    const py::ssize_t k = n.shape(0);
    py::array_t<int64_t> nc({k, py::ssize_t{3}}), pc({k, py::ssize_t{3}});
    const int F = core_.format().frac;
    for (py::ssize_t i = 0; i < k; ++i) {
      const Fragment f = make_fragment(F, n.data() + 3 * i, p.data() + 3 * i);
      for (int c = 0; c < 3; ++c) {
        nc.mutable_data()[3 * i + c] = f.n[c];
        pc.mutable_data()[3 * i + c] = f.p[c];
      }
    }
    return py::make_tuple(nc, pc);
  }

 private:
  static LightCore make(const std::string& arg, bool is_json) {
    if (!is_json) return LightCore(feature_set_named_or_file(arg));
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(arg);
    } catch (const nlohmann::json::parse_error& e) {
      throw std::invalid_argument(std::string("feature set: malformed JSON: ") + e.what());
    }
    FeatureSet fs = feature_set_from_json(j, "feature set");
    if (!j.contains("name")) fs.name = "custom";
    return LightCore(fs);
  }
  LightCore core_;
  LightRegs regs_;
};

// ---------------------------------------------------------------------------- render (C model, exact)
// A scene file through the host rasteriser and the lighting core's C model, as `shadecore render` computes it
// (render::prepare, run_cmodel, run_reference for both references, resolve, to_rgb8): images as arrays.
py::dict render_scene(const std::string& path, std::optional<std::pair<int, int>> size, bool full_core, int lanes,
                      int share) {
  render::Settings st;
  st.full_core = full_core;
  check_in_range("lanes", lanes, 1, kMaxLights);
  check_in_range("share", share, 1, kShareMax);
  st.lanes = lanes;
  st.share = share;
  if (size) {
    check_in_range("width", size->first, 1, 4096);
    check_in_range("height", size->second, 1, 4096);
    st.width = size->first;
    st.height = size->second;
  }
  render::Image image;
  render::RefImage exact, unit_double;
  std::vector<std::string> groups;
  {
    py::gil_scoped_release nogil;
    scene::Scene sc;
    try {  // a bad scene file is bad input: ValueError with the CLI's message
      sc = scene::load_scene(path);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(e.what());
    }
    render::MeshSource meshes(sc);
    const render::Frame fr = render::prepare(sc, meshes, st);
    std::vector<std::vector<Colour>> cols;
    std::vector<std::vector<render::RefColour>> ex, ud;
    for (const auto& g : fr.groups) {
      cols.push_back(render::run_cmodel(g));
      ex.push_back(render::run_reference(g, LightCore::SpecRef::Exact));
      ud.push_back(render::run_reference(g, LightCore::SpecRef::Variant));
      groups.push_back(g.fs.summary());
    }
    image = render::resolve(fr, cols);
    exact = render::resolve_reference(fr, ex);
    unit_double = render::resolve_reference(fr, ud);
  }
  const py::ssize_t h = image.height, w = image.width;
  py::array_t<int64_t> codes({h, w, py::ssize_t{3}});
  py::array_t<bool> covered({h, w});
  py::array_t<double> ex3({h, w, py::ssize_t{3}}), ud3({h, w, py::ssize_t{3}});
  py::array_t<uint8_t> rgb8({h, w, py::ssize_t{3}}), exact8({h, w, py::ssize_t{3}});
  const std::vector<uint8_t> c8 = render::to_rgb8(image), e8 = render::to_rgb8(exact);
  for (size_t i = 0; i < image.code.size(); ++i) {
    codes.mutable_data()[i] = image.code[i];
    ex3.mutable_data()[i] = exact.value[i];
    ud3.mutable_data()[i] = unit_double.value[i];
    rgb8.mutable_data()[i] = c8[i];
    exact8.mutable_data()[i] = e8[i];
  }
  for (size_t i = 0; i < image.covered.size(); ++i) covered.mutable_data()[i] = image.covered[i] != 0;
  py::dict d;
  d["image"] = codes;
  d["covered"] = covered;
  d["exact"] = ex3;
  d["unit_double"] = ud3;
  d["rgb8"] = rgb8;
  d["exact_rgb8"] = exact8;
  d["frac"] = image.F;
  d["cores"] = groups;
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
  m.def("unit_eval_outer", &unit_eval_outer, py::arg("variant"), py::arg("codes"), py::arg("n"), py::arg("config") = "",
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

  // outer = true: c (m) and n (k) give the (k, m) grid (golden_outer), else element by element (golden_map).
  auto gmap = [](const F64& c, const I64& n, bool check_n, bool outer, auto fn) {
    return outer ? golden_outer(c, n, check_n, fn) : golden_map(c, n, check_n, fn);
  };
  m.def("golden_cos_pow", [gmap](const F64& c, const I64& n, bool outer) {
    return gmap(c, n, false, outer, [](double x, int k) { return g::cos_pow(x, k); });
  }, py::arg("c"), py::arg("n"), py::arg("outer") = false);
  m.def("golden_cs16", [gmap](const F64& c, const I64& n, const std::string& cutoff, bool outer) {
    const Cutoff cut = parse_cutoff_name(cutoff);
    return gmap(c, n, true, outer, [cut](double x, int k) {
      return cut == Cutoff::ThetaCr ? g::cs16_theta_cr(x, k) : g::cs16_sign_clamp(x, k);
    });
  }, py::arg("c"), py::arg("n"), py::arg("cutoff"), py::arg("outer") = false);
  m.def("golden_schlick", [gmap](const F64& c, const I64& n, bool outer) {
    return gmap(c, n, true, outer, [](double x, int k) { return g::schlick(x, k); });
  }, py::arg("c"), py::arg("n"), py::arg("outer") = false);
  m.def("golden_variant", [gmap](const std::string& variant, const F64& c, const I64& n, const std::string& cutoff,
                                 bool outer) {
    const Cutoff cut = parse_cutoff_name(cutoff);
    parse_variant(variant);  // unknown names: the model's message
    return gmap(c, n, true, outer, [&variant, cut](double x, int k) { return variant_golden(variant, cut, k, x); });
  }, py::arg("variant"), py::arg("c"), py::arg("n"), py::arg("cutoff"), py::arg("outer") = false);
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

  m.def("render", &render_scene, py::arg("scene"), py::arg("size") = py::none(), py::arg("full_core") = false,
        py::arg("lanes") = 1, py::arg("share") = 1);
  m.def("feature_sets", [] {
    std::vector<std::string> v;
    for (const auto& fs : named_feature_sets()) v.push_back(fs.name);
    return v;
  });
  py::class_<PyLightCore>(m, "LightCore")
      .def(py::init<const std::string&, bool>(), py::arg("features"), py::arg("is_json") = false)
      .def_property_readonly("name", &PyLightCore::name)
      .def_property_readonly("summary", &PyLightCore::summary)
      .def_property_readonly("key", &PyLightCore::key)
      .def_property_readonly("frac", [](const PyLightCore& c) { return c.core().format().frac; })
      .def_property_readonly("unit_frac", [](const PyLightCore& c) { return c.core().unit_format().frac; })
      .def_property_readonly("num_lights", [](const PyLightCore& c) { return c.core().features().num_lights(); })
      .def("write", &PyLightCore::write, py::arg("addr"), py::arg("data"))
      .def("program", &PyLightCore::program, py::arg("state_json"))
      .def("eval", &PyLightCore::eval, py::arg("n"), py::arg("p"), py::arg("colour") = py::none(),
           py::arg("back") = py::none())
      .def("eval_double", &PyLightCore::eval_double, py::arg("n"), py::arg("p"), py::arg("colour") = py::none(),
           py::arg("back") = py::none(), py::arg("reference") = "exact")
      .def("fragment_codes", &PyLightCore::fragment_codes, py::arg("n"), py::arg("p"));
}

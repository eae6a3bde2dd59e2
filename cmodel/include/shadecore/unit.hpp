// shadecore — the narrow interface through which the co-simulation (sim/) and the CLI see a
// hardware unit's bit-accurate model: variant id + Format + cut-off form in, then
//   setup(n)        -> the values the material ports of rtl/sc_specular.v get (mat_n_i, mat_thr_i)
//   eval(mat, code) -> out_spec_o for the signed input word `code` shaded with material `mat`
//   latency()       -> the unit's fixed pipeline latency in cycles (its RTL header documents it)
// A new unit (a Schlick divider, an energy-normalised output) adds one `case` per function below
// and a row in config/configs.json "variants"; the testbench does not change.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "shadecore/cs16.hpp"
#include "shadecore/format.hpp"
#include "shadecore/schlick.hpp"
#include "shadecore/variants.hpp"

namespace shadecore {

// What the material ports get. `thr` is mat_thr_i (F+1 bits); units that need no threshold leave 0.
struct UnitMaterial {
  int n = kNMin;     // mat_n_i, 16..1024
  uint32_t thr = 0;  // mat_thr_i
};

inline VariantId parse_variant(std::string_view name) {
  for (const auto& v : kVariants)
    if (v.name == name) return v.id;
  std::string known;
  for (const auto& v : kVariants) known += (known.empty() ? "" : ", ") + std::string(v.name);
  throw std::invalid_argument("unknown variant '" + std::string(name) + "' (known: " + known + ")");
}

inline std::string_view variant_name(VariantId id) {
  for (const auto& v : kVariants)
    if (v.id == id) return v.name;
  return "?";
}

inline Cutoff parse_cutoff_name(std::string_view s) {
  if (s == "theta_cr") return Cutoff::ThetaCr;
  if (s == "sign_clamp") return Cutoff::SignClamp;
  throw std::invalid_argument("unknown cutoff '" + std::string(s) + "' (known: theta_cr, sign_clamp)");
}

class Unit {
 public:
  // Throws std::invalid_argument for an illegal format or an unknown variant.
  Unit(VariantId variant, const Format& format, Cutoff cutoff)
      : variant_(variant), format_(format), cutoff_(cutoff) {
    validate(format_);
    switch (variant_) {
      case VariantId::cs16:
      case VariantId::schlick_div:
      case VariantId::schlick_nr:
      case VariantId::schlick_iter: return;
    }
    throw std::invalid_argument("variant id " + std::to_string(static_cast<int>(variant)) +
                                " has no model in shadecore/unit.hpp");
  }

  [[nodiscard]] VariantId variant() const { return variant_; }
  [[nodiscard]] const Format& format() const { return format_; }
  [[nodiscard]] Cutoff cutoff() const { return cutoff_; }

  // Pipeline latency in cycles: accepted at the rising edge ending cycle t -> out_valid_o in t+latency.
  [[nodiscard]] int latency() const {
    switch (variant_) {
      case VariantId::cs16: return 7;  // rtl/sc_cs16.v: S0..S6
      // Schlick units (docs/spec.md §6.5): div/iter S0, S1, Q0..Q(F+1); nr S0..S9.
      case VariantId::schlick_div: return schlick_div_latency(format_.frac);
      case VariantId::schlick_nr: return kSchlickNrLatency;
      case VariantId::schlick_iter: return schlick_iter_latency(format_.frac);
    }
    return -1;
  }

  // Material setup (docs/spec.md §3.1); throws std::invalid_argument for n outside [16, 1024].
  [[nodiscard]] UnitMaterial setup(long long n) const {
    switch (variant_) {
      case VariantId::cs16: {
        const Cs16Material m = cs16_setup(format_, n);
        return UnitMaterial{m.n, m.thr};
      }
      case VariantId::schlick_div:
      case VariantId::schlick_nr:
      case VariantId::schlick_iter:  // no threshold: mat_thr_i unused (0)
        return UnitMaterial{schlick_setup(format_, n).n, 0};
    }
    return {};
  }

  // The per-fragment datapath, for the material values actually on the material ports.
  [[nodiscard]] uint32_t eval(const UnitMaterial& m, int64_t code) const {
    switch (variant_) {
      case VariantId::cs16: return cs16_eval(format_, cutoff_, Cs16Material{m.n, m.thr}, code);
      case VariantId::schlick_div: return schlick_div_eval(format_, SchlickMaterial{m.n}, code);
      case VariantId::schlick_nr: return schlick_nr_eval(format_, SchlickMaterial{m.n}, code);
      case VariantId::schlick_iter: return schlick_iter_eval(format_, SchlickMaterial{m.n}, code);
    }
    return 0;
  }

 private:
  VariantId variant_;
  Format format_;
  Cutoff cutoff_;
};

}  // namespace shadecore

// SPDX-License-Identifier: Apache-2.0
// shadecore — the narrow interface through which the co-simulation (sim/) and the CLI see a
// hardware unit's bit-accurate model: variant id + Format + cut-off form in, then
//   setup(n)        -> the values the material ports of rtl/sc_specular.v get (mat_n_i, mat_thr_i)
//   eval(mat, code) -> out_spec_o for the signed input word `code` shaded with material `mat`
//   latency()       -> the unit's fixed pipeline latency in cycles (its RTL header documents it)
// Table variants (config/configs.json contract "table", docs/spec.md §9): setup(n) also gives the
// table RAM contents (UnitMaterial::tab, E words, written through tab_we_i/tab_addr_i/tab_value_i/
// tab_delta_i), and eval() reads the words in UnitMaterial::tab — whatever the RAM holds.
// Optionally (set_energy) the energy-normalisation stage rtl/sc_energy.v chained after the unit inside
// sc_specular (parameter ENERGY = 1): setup() also gives mat_coef_i, eval() the normalised output,
// latency() + 2 (docs/spec.md §7).
// A new unit (a Schlick divider, an energy-normalised output) adds one `case` per function below
// and a row in config/configs.json "variants"; the testbench does not change.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "shadecore/units/coef.hpp"
#include "shadecore/units/cs16.hpp"
#include "shadecore/units/cs16_forms.hpp"
#include "shadecore/format.hpp"
#include "shadecore/units/schlick.hpp"
#include "shadecore/units/table.hpp"
#include "shadecore/variants.hpp"

namespace shadecore {

// What the material ports get. `thr` is mat_thr_i (F+1 bits); units that need no threshold leave 0.
struct UnitMaterial {
  int n = kNMin;     // mat_n_i, 16..1024
  uint32_t thr = 0;  // mat_thr_i
  uint32_t coef = 0; // mat_coef_i (ENERGY = 1 only: coef_code of the material's model, spec §7)
  // Table variants only: the table RAM contents (E words, table_word() layout), loaded through the
  // tab_*_i ports; null for every other unit. Shared, not copied, when a material is passed around.
  std::shared_ptr<const std::vector<uint64_t>> tab = nullptr;
};

inline VariantId parse_variant(std::string_view name) {
  return find_named(kVariants, name, "variant", [](const auto& v) { return v.name; }, [](const auto& v) { return v.id; });
}

inline std::string_view variant_name(VariantId id) {
  for (const auto& v : kVariants)
    if (v.id == id) return v.name;
  return "?";
}

// rtl/sc_cs16.v's latency (reference form)
inline constexpr int kCs16Latency = 7;
// The cycles the pipelining parameter MREG = 1 adds to a variant (configs.json variants[].mreg_stages: a register
// inside each product of the unit, rtl/sc_mul_reg.v); 0: the variant has no MREG.
constexpr int mreg_stages(VariantId id) {
  for (const auto& v : kVariants)
    if (v.id == id) return v.mreg_stages;
  return 0;
}

class Unit {
 public:
  // Throws std::invalid_argument for an illegal format or an unknown variant.
  Unit(VariantId variant, const Format& format, Cutoff cutoff)
      : variant_(variant), format_(format), cutoff_(cutoff) {
    validate(format_);
    if (const SquarerForm* form = squarer_form(variant_)) {  // cs16 forms (cs16_forms.hpp)
      stages_ = cs16_stages(format_, *form);
      return;
    }
    switch (variant_) {
      case VariantId::cs16:
      case VariantId::schlick_div:
      case VariantId::schlick_nr:
      case VariantId::schlick_iter: return;
      case VariantId::table256:
      case VariantId::table1024: table_index_bits(table_entries(variant_)); return;
      default: break;
    }
    throw std::invalid_argument("variant id " + std::to_string(static_cast<int>(variant)) +
                                " has no model in shadecore/unit.hpp");
  }

  [[nodiscard]] VariantId variant() const { return variant_; }
  [[nodiscard]] const Format& format() const { return format_; }
  [[nodiscard]] Cutoff cutoff() const { return cutoff_; }
  // Table variants: entries E of the table RAM (writes per material change); 0 for the other units.
  [[nodiscard]] int entries() const { return table_entries(variant_); }
  // A cs16 form with folded truncated squarers (a variant with "squarer" in configs.json).
  [[nodiscard]] bool is_cs16_form() const { return squarer_form(variant_) != nullptr; }
  // The unit takes a CUTOFF parameter (cs16 and its forms).
  [[nodiscard]] bool has_cutoff() const { return variant_ == VariantId::cs16 || is_cs16_form(); }
  [[nodiscard]] const Cs16Stages& stages() const { return stages_; }
  // Port values beyond the host's (docs/spec.md §3.1 "Beyond the host's values"; `shadecore vectors --mode
  // ports`): the RTL gives this model's bits for every n in port_n_min()..kNMax and every thr from
  // port_thr_min(n) up. n = 0 is in for the dividers schlick_div and schlick_iter (Dc = c: the quotient's integer
  // bit, 1.0 for every c > 0, and their shared 0/0 path) and out for the others (the cs16 squarer forms' sign test
  // cuts base = 1.0; schlick_nr's Dc = c < 2^F is not normalised). thr: in the cs16 family with the θcr cut-off
  // an uncut |base| ≤ 1 needs c ≥ 2^F − 2^(F+5)/n (below it the squarings overflow or the sign test wraps).
  [[nodiscard]] int port_n_min() const {
    return variant_ == VariantId::schlick_div || variant_ == VariantId::schlick_iter ? 0 : 1;
  }
  [[nodiscard]] int64_t port_thr_min(int n) const {
    if (!has_cutoff() || cutoff_ != Cutoff::ThetaCr || n <= 0) return 0;
    const int64_t one = int64_t{1} << format_.frac;
    return std::max<int64_t>(0, one - (int64_t{1} << (format_.frac + 5)) / n);
  }

  // Chain the energy-normalisation stage (I = kCoefIntBits, F = format().frac). model < 0 picks the
  // model per material from n (kModels[n % 6], classical coefficient when (n / 6) is odd), so a
  // random run covers every model and kind; model >= 0 fixes it (index into kModels).
  void set_energy(bool on, int model = -1, CoefKind kind = CoefKind::Fitted) {
    if (model >= kNumModels) throw std::invalid_argument("energy model index out of range");
    energy_ = on;
    energy_model_ = model;
    energy_kind_ = kind;
  }
  [[nodiscard]] bool energy() const { return energy_; }

  // The pipelining parameter MREG (rtl/sc_cs16.v with SHARE = 1, both forms; rtl/sc_schlick_div.v; rtl/sc_schlick_nr.v
  // with SHARE = 1): 1 puts a register inside each of the unit's products (rtl/sc_mul_reg.v, rtl/sc_sum_reg.v),
  // mreg_stages(variant) more cycles, the same outputs.
  void set_mreg(int mreg) {
    if (mreg != 0 && mreg != 1) throw std::invalid_argument("MREG " + std::to_string(mreg) + " out of range (0 or 1)");
    if (mreg != 0 && mreg_stages(variant_) == 0) {
      std::string known;
      for (const auto& v : kVariants)
        if (v.mreg_stages > 0) known += (known.empty() ? "" : ", ") + std::string(v.name);
      throw std::invalid_argument("MREG = 1 applies to " + known + " (configs.json variants[].mreg_stages), not " +
                                  std::string(variant_name(variant_)));
    }
    mreg_ = mreg;
  }
  [[nodiscard]] int mreg() const { return mreg_; }

  // Pipeline latency in cycles: accepted at the rising edge ending cycle t -> out_valid_o in t+latency.
  [[nodiscard]] int latency() const {
    if (is_cs16_form())  // rtl/sc_cs16.v FORM = 1: S1..S5 (+ S0, M1..M5 with MREG = 1)
      return kCs16FormLatency + mreg_stages(variant_) * mreg_ + (energy_ ? 2 : 0);
    switch (variant_) {
      case VariantId::cs16:  // rtl/sc_cs16.v: S0..S6 (+ M1..M5 with MREG = 1; + sc_energy N1, N2)
        return kCs16Latency + mreg_stages(variant_) * mreg_ + (energy_ ? 2 : 0);
      // Schlick units (docs/spec.md §6.5): div/iter S0, S1, Q0..Q(F+1); nr S0..S9.
      case VariantId::schlick_div:  // + M1 with MREG = 1 (n·d)
        return schlick_div_latency(format_.frac) + mreg_stages(variant_) * mreg_ + (energy_ ? 2 : 0);
      case VariantId::schlick_nr:  // + M1..M6 with MREG = 1 (every product)
        return kSchlickNrLatency + mreg_stages(variant_) * mreg_ + (energy_ ? 2 : 0);
      case VariantId::schlick_iter: return schlick_iter_latency(format_.frac) + (energy_ ? 2 : 0);
      case VariantId::table256:
      case VariantId::table1024: return kTableLatency + (energy_ ? 2 : 0);  // rtl/sc_table.v: S0..S2
      default: break;
    }
    return -1;
  }

  // Fewest advancing edges (!out_valid_o || out_ready_i) from acceptance to output. Equal to
  // latency() for a single unit (one global enable). With ENERGY = 1 the unit and sc_energy are two
  // pipelines: while sc_energy's output is held, the unit still advances into its empty output stage,
  // so under backpressure a fragment can close up on the one ahead; at least the edges into N1 and
  // N2 and the taking edge remain (3). With out_ready_i high throughout it is exactly latency().
  [[nodiscard]] int latency_min() const { return energy_ ? 3 : latency(); }

  // Material setup (docs/spec.md §3.1); throws std::invalid_argument for n outside [16, 1024].
  [[nodiscard]] UnitMaterial setup(long long n) const {
    if (is_cs16_form()) {  // same material as cs16 (n, thr)
      const Cs16Material m = cs16_setup(format_, n);
      return with_coef(UnitMaterial{m.n, m.thr}, n);
    }
    switch (variant_) {
      case VariantId::cs16: {
        const Cs16Material m = cs16_setup(format_, n);
        return with_coef(UnitMaterial{m.n, m.thr}, n);
      }
      case VariantId::schlick_div:
      case VariantId::schlick_nr:
      case VariantId::schlick_iter:  // no threshold: mat_thr_i unused (0)
        return with_coef(UnitMaterial{schlick_setup(format_, n).n, 0}, n);
      case VariantId::table256:
      case VariantId::table1024: {  // no threshold; the table contents (E RAM writes per material)
        TableMaterial t = table_setup(format_, entries(), n);
        UnitMaterial m{t.n, 0};
        m.tab = std::make_shared<const std::vector<uint64_t>>(std::move(t.words));
        return with_coef(std::move(m), n);
      }
      default: break;
    }
    return {};
  }

  // The per-fragment datapath, for the material values actually on the material ports.
  [[nodiscard]] uint32_t eval(const UnitMaterial& m, int64_t code) const {
    if (is_cs16_form()) return normalise(m, cs16f_eval(format_, cutoff_, stages_, Cs16Material{m.n, m.thr}, code));
    switch (variant_) {
      case VariantId::cs16: return normalise(m, cs16_eval(format_, cutoff_, Cs16Material{m.n, m.thr}, code));
      case VariantId::schlick_div: return normalise(m, schlick_div_eval(format_, SchlickMaterial{m.n}, code));
      case VariantId::schlick_nr: return normalise(m, schlick_nr_eval(format_, SchlickMaterial{m.n}, code));
      case VariantId::schlick_iter: return normalise(m, schlick_iter_eval(format_, SchlickMaterial{m.n}, code));
      case VariantId::table256:
      case VariantId::table1024:
        if (!m.tab || static_cast<int>(m.tab->size()) != entries())
          throw std::invalid_argument("table unit evaluated without its " + std::to_string(entries()) + "-entry table");
        return normalise(m, table_eval(format_, m.tab->data(), entries(), code));
      default: break;
    }
    return 0;
  }

 private:
  [[nodiscard]] EnergyFormat energy_format() const { return EnergyFormat{format_.frac, kCoefIntBits}; }
  [[nodiscard]] UnitMaterial with_coef(UnitMaterial m, long long n) const {
    if (!energy_) return m;
    const Model model = energy_model_ >= 0 ? static_cast<Model>(energy_model_) : static_cast<Model>(n % kNumModels);
    const CoefKind kind = energy_model_ >= 0 ? energy_kind_ : ((n / kNumModels) % 2 ? CoefKind::Classical : CoefKind::Fitted);
    m.coef = energy_setup(energy_format(), model, kind, n);
    return m;
  }
  // sc_energy N1/N2 after the unit (out < 2^(I+F) <= 2^32).
  [[nodiscard]] uint32_t normalise(const UnitMaterial& m, uint32_t spec) const {
    return energy_ ? static_cast<uint32_t>(energy_eval(energy_format(), m.coef, spec)) : spec;
  }

  VariantId variant_;
  Format format_;
  Cutoff cutoff_;
  Cs16Stages stages_{};  // cs16 forms only
  bool energy_ = false;
  int mreg_ = 0;
  int energy_model_ = -1;
  CoefKind energy_kind_ = CoefKind::Fitted;
};

}  // namespace shadecore

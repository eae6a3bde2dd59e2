// SPDX-License-Identifier: Apache-2.0
// shadecore — energy normalisation: the six coefficient models of the cs16 paper and the
// bit-accurate normalisation stage (rtl/sc_energy.v). See docs/spec.md §7 and docs/energy.md.
//
//   coef(n) = (a·n + b) / (k·π)        k = 2 (Phong rows) or 8 (Blinn rows)
//
// Material setup (once per material): coef(n) in double → rounded to an unsigned fixed-point
// code with F fraction bits (F = the unit's FRAC) and kCoefIntBits integer bits.
// Per fragment: one multiply of the unit's output (F+1 bits, 1.0 = 2^F) by that code, rounded
// half up to F fraction bits.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

#include "shadecore/format.hpp"

namespace shadecore {

// The six models of the paper's Table 1, in its order.
enum class Model : int {
  Phong = 0,             // Phong (RDF)                 Int: cs16(θ)·sin θ
  PhongMod = 1,          // Phong, modified (RDF)       Int: cs16(θ)·cos θ·sin θ
  Blinn = 2,             // Blinn-Phong (RDF)           Int: cs16(θ/2)·sin θ
  BlinnMod = 3,          // Blinn-Phong, modified       Int: cs16(θ/2)·cos θ·sin θ
  BlinnNdf = 4,          // Blinn-Phong (NDF)           Int: cs16(α)·sin α
  BlinnHeightfield = 5,  // Blinn-Phong (heightfield)   Int: cs16(α)·cos α·sin α
};
inline constexpr int kNumModels = 6;

struct ModelInfo {
  Model model;
  std::string_view key;     // CLI / JSON name
  std::string_view title;   // as in the paper's table
  int k;                    // coef = (a·n + b)/(k·π)
  bool half_angle;          // the lobe argument is θ/2 (Blinn rows: N·H = cos(θ/2) at normal incidence)
  bool cos_weight;          // the integrand carries an extra cos θ
  double pub_a, pub_b;      // the paper's fitted cs16 coefficient (a·n + b)/(k·π)
  double claimed_res;       // the paper's max res(n) over 16..1024; NaN where it only says "as Phong"
  Model same_integral_as;   // NDF/heightfield rows repeat the Phong integrals
};

inline constexpr double kNoClaim = std::numeric_limits<double>::quiet_NaN();

inline constexpr std::array<ModelInfo, kNumModels> kModels{{
    {Model::Phong, "phong", "Phong (RDF)", 2, false, false, 1.063, 0.0, 4.7e-4, Model::Phong},
    {Model::PhongMod, "phong_mod", "Phong, modified (RDF)", 2, false, true, 1.063, 1.0, 1.3e-3, Model::PhongMod},
    {Model::Blinn, "blinn", "Blinn-Phong (RDF)", 8, true, false, 1.068, 0.96, 1.5e-3, Model::Blinn},
    {Model::BlinnMod, "blinn_mod", "Blinn-Phong, modified (RDF)", 8, true, true, 1.027, 4.8, 9.5e-3, Model::BlinnMod},
    {Model::BlinnNdf, "blinn_ndf", "Blinn-Phong (NDF)", 2, false, false, 1.063, 0.0, kNoClaim, Model::Phong},
    {Model::BlinnHeightfield, "blinn_hf", "Blinn-Phong (heightfield)", 2, false, true, 1.063, 1.0, kNoClaim,
     Model::PhongMod},
}};

inline const ModelInfo& info(Model m) { return kModels[static_cast<int>(m)]; }

// Throws std::invalid_argument for an unknown key.
inline Model parse_model(std::string_view key) {
  return find_named(kModels, key, "model", [](const auto& m) { return m.key; }, [](const auto& m) { return m.model; });
}

// Classical coefficient of the exact lobe cos^n over the hemisphere (the paper's middle column,
// re-derived): Phong ∫cos^n sin = 1/(n+1); modified 1/(n+2); Blinn ∫_{1/√2}^1 4v^{n+1} dv =
// 4(1 − 2^{−(n+2)/2})/(n+2); modified Blinn 4(n + 2^{−n/2})/((n+2)(n+4)).
// Note: the paper prints the modified-Blinn closed form with 4π in the denominator; the integral
// gives 8π (its own bounds (n+6)/8π < · < (n+8)/8π only hold with 8π). This returns the 8π form.
inline double classical_coef(Model m, double n) {
  const double pi = M_PI;
  switch (m) {
    case Model::Phong:
    case Model::BlinnNdf: return (n + 1) / (2 * pi);
    case Model::PhongMod:
    case Model::BlinnHeightfield: return (n + 2) / (2 * pi);
    case Model::Blinn: return (n + 2) / (4 * pi * (2 - std::exp2(-n / 2)));
    case Model::BlinnMod: return (n + 2) * (n + 4) / (8 * pi * (std::exp2(-n / 2) + n));
  }
  throw std::invalid_argument("bad model");
}

// The paper's fitted cs16 coefficient (a·n + b)/(k·π).
inline double fitted_coef(Model m, double n) {
  const ModelInfo& i = info(m);
  return (i.pub_a * n + i.pub_b) / (i.k * M_PI);
}

// Which coefficient a material uses.
enum class CoefKind : int { Fitted = 0, Classical = 1 };
inline const char* to_string(CoefKind k) { return k == CoefKind::Fitted ? "fitted" : "classical"; }
inline CoefKind parse_coef_kind(std::string_view s) {
  if (s == "fitted") return CoefKind::Fitted;
  if (s == "classical") return CoefKind::Classical;
  throw std::invalid_argument("unknown coefficient kind '" + std::string(s) + "' (known: fitted, classical)");
}
inline double coef_value(Model m, CoefKind k, double n) {
  return k == CoefKind::Fitted ? fitted_coef(m, n) : classical_coef(m, n);
}

// ---- Fixed-point normalisation stage (docs/spec.md §7) ---------------------------------------

// Coefficient word: unsigned, kCoefIntBits integer bits, F fraction bits (F = the unit's FRAC).
// The largest coefficient of any model/kind over n = 16..1024 is the fitted modified Phong
// (1.063·1024 + 1)/2π ≈ 173.4 < 2^8.
inline constexpr int kCoefIntBits = 8;
inline constexpr int kCoefIntBitsMin = limits::kCoefIntBitsMin;  // config/configs.json "limits" (COEFW - FRAC)
inline constexpr int kCoefIntBitsMax = limits::kCoefIntBitsMax;

struct EnergyFormat {
  int frac = 16;                   // F: fraction bits of the unit output, of the coefficient and of the result
  int int_bits = kCoefIntBits;     // I: integer bits of the coefficient and of the result
  [[nodiscard]] constexpr int coef_bits() const { return int_bits + frac; }  // COEFW
  [[nodiscard]] constexpr int in_bits() const { return frac + 1; }           // unit output, <= 2^F
  [[nodiscard]] constexpr int out_bits() const { return int_bits + frac; }   // normalised output
  [[nodiscard]] constexpr int prod_bits() const { return in_bits() + coef_bits(); }
};

inline void validate(const EnergyFormat& f) {
  check_in_range("fraction width", f.frac, kFracMin, kFracMax);
  check_in_range("coefficient integer bits", f.int_bits, kCoefIntBitsMin, kCoefIntBitsMax);
}

// Material setup: code = ⌊coef·2^F + ½⌋ (round half up of the IEEE-double value), checked to fit
// in I+F bits. Throws std::invalid_argument if coef is negative, not finite or too large.
inline uint32_t coef_code(const EnergyFormat& f, double coef) {
  validate(f);
  if (!std::isfinite(coef) || coef < 0) throw std::invalid_argument("coefficient must be finite and >= 0");
  const double scaled = std::floor(std::ldexp(coef, f.frac) + 0.5);
  if (scaled >= std::ldexp(1.0, f.coef_bits()))
    throw std::invalid_argument("coefficient " + std::to_string(coef) + " does not fit in " +
                                std::to_string(f.int_bits) + " integer bits");
  return static_cast<uint32_t>(scaled);
}

// Setup for a material: model, coefficient kind and exponent n (validated: 16..1024).
inline uint32_t energy_setup(const EnergyFormat& f, Model m, CoefKind k, long long n) {
  validate_n(n);
  return coef_code(f, coef_value(m, k, static_cast<double>(n)));
}

// Per fragment (rtl/sc_energy.v):
//   N1  p = spec · coef             (F+1) × (I+F) → I+2F+1 bits, exact
//   N2  out = ⌊(p + 2^(F−1)) / 2^F⌋  I+F bits, 1.0 = 2^F (round half up)
// spec <= 2^F and coef <= 2^(I+F) − 1 give p + 2^(F−1) < 2^(I+2F), so out < 2^(I+F): no overflow.
inline uint64_t energy_eval(const EnergyFormat& f, uint32_t coef, uint32_t spec) {
  const uint64_t p = static_cast<uint64_t>(spec) * coef;         // N1 (≤ 2F+I+1 ≤ 57 bits)
  return (p + (uint64_t{1} << (f.frac - 1))) >> f.frac;          // N2
}

}  // namespace shadecore

// SPDX-License-Identifier: Apache-2.0
// shadecore — directional-hemispherical reflectance of the normalised BRDFs (the 2-D energy check
// beyond the paper's 1-D integral). Used by `shadecore energy` and tests/test_energy.cpp.
//
//   R(θi) = ∫_Ω f_r(ωi, ωo)·cos θo dωo      N = z, ωi = (sin θi, 0, cos θi), R = (−sin θi, 0, cos θi)
//
// BRDF forms (h = normalise(ωi + ωo), lobe(x) = the normalised unit output for cos code x):
//   phong      f_r·cos θo = lobe(R·ωo)                  (the paper's Int has no cos: f_r = coef·cs16/cos θo)
//   phong_mod  f_r        = lobe(R·ωo)                  (Lewis' modified Phong)
//   blinn      f_r·cos θo = lobe(N·h)
//   blinn_mod  f_r        = lobe(N·h)
//   blinn_ndf  f_r        = lobe(N·h) / (4 cos θi cos θo)   microfacet form, F = G = 1, D = coef·cs16
//   blinn_hf   f_r        = lobe(N·h) / (4 cos θi cos θo)   (same form, the heightfield coefficient)
// Each form reduces at θi = 0 to the paper's 1-D integrand for that row (Blinn rows: over the
// hemisphere, i.e. the double_capped reading).
//
// Coordinates: polar around the lobe axis — ωo around R for the Phong rows, h around N for the
// Blinn rows (dωo = 4(ωi·h)dω_h) — with u = cos of the polar angle (= R·ωo or N·h, the cosine the
// unit is fed) and the azimuth φ, so dω = du dφ. The set-up is symmetric about the plane of incidence.
//
// Method::Cells (default): the fixed-point lobe depends on u only through its input code
// k = round(u·2^F), so it is constant on each code cell [(k−½)/2^F, (k+½)/2^F). The azimuth integral
// G(u) of the rest (the cos θo / ωi·h factors and the horizon, cos θo > 0) is done in closed form
// (the visible azimuths are one interval |φ| <= φmax(u)); R = Σ_k lobe(k)·∫_cell G(u) du with a
// 3-point Gauss–Legendre rule per code cell. The only approximation is that per-cell rule on the
// smooth G (measured: agrees with the 2-D grid to its convergence, see tests/test_energy.cpp).
// In double mode the same cells are used with the golden lobe inside the 3-point rule.
//
// Method::Grid: plain 2-D midpoint rule in (polar angle, φ) with the cosine computed from the two
// unit vectors and then quantised (independent cross-check; slower, error ~1e-4 at 400×200).
#pragma once

#include <cstdint>
#include <vector>

#include "shadecore/units/coef.hpp"
#include "shadecore/units/cs16.hpp"

namespace shadecore::energy {

struct Options {
  Format format{16, 5};              // unit widths (cs16)
  int coef_int_bits = kCoefIntBits;  // normalisation stage integer bits
  Cutoff cutoff = Cutoff::ThetaCr;
  CoefKind coef = CoefKind::Fitted;
  bool fixed_point = true;  // false: golden double cs16 and the double coefficient (cross-check)
  enum class Method { Cells, Grid } method = Method::Cells;
  int radial = 400;         // Grid: midpoint cells in the polar angle
  int azimuth = 200;        // Grid: midpoint cells in the azimuth over [0, π]
};

// R(θi) for model m and exponent n. θi in radians, [0, π/2).
double reflectance(Model m, int n, double theta_i, const Options& o);

// The radius bound of the lobe (radians around R or N) used by reflectance().
double lobe_radius(const Options& o, int n);

}  // namespace shadecore::energy

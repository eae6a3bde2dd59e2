// SPDX-License-Identifier: Apache-2.0
// shadecore — the paper's normalisation integrals Int(n), their closed forms, and the
// least-squares / minimax fit of coef(n) = (a·n + b)/(k·π). Used by `shadecore fit`.
//
// Int(n) = ∫_0^T lobe(cos θ)·[cos θ]·sin θ dθ            Phong rows (and NDF/heightfield in α)
//        = ∫_0^T lobe(cos(θ/2))·[cos θ]·sin θ dθ         Blinn rows
// where [cos θ] is present for the "modified" rows and T is the upper limit (see Reading).
// res(n) = |2π·coef(n)·Int(n) − 1|.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "shadecore/units/coef.hpp"
#include "shadecore/units/cs16.hpp"

namespace shadecore::fit {

// The highlight function in the integrand. cs16 has a cut-off (Cutoff::ThetaCr = the paper's
// 6/√n, Cutoff::SignClamp = the exact zero of the base θ0 = arccos((n−16)/n)); cos_pow and
// schlick are integrated over the whole hemisphere.
enum class LobeKind : int { Cs16 = 0, CosPow = 1, Schlick = 2 };
struct Lobe {
  LobeKind kind = LobeKind::Cs16;
  Cutoff cutoff = Cutoff::ThetaCr;
};
const char* to_string(LobeKind k);
LobeKind parse_lobe(std::string_view s);  // "cs16" | "cos_pow" | "schlick"; throws std::invalid_argument
std::string describe(const Lobe& l);

// The value of the lobe at c = cos(angle), in double, without any cut (the limit T does the cut).
double lobe_value(const Lobe& l, double c, int n);

// Upper limit of the θ integral for the Blinn rows (Phong rows always use min(θc, π/2)):
//   Paper        T = θc          the integral as the paper writes it
//   Double       T = 2θc         where cs16(θ/2, n) is really non-zero (may exceed π/2 for n < 59)
//   DoubleCapped T = min(2θc, π/2)  the same, restricted to the hemisphere
// θc = 6/√n (ThetaCr) or θ0 = arccos((n−16)/n) (SignClamp). cos_pow/schlick: T = π/2 always.
enum class Reading : int { Paper = 0, Double = 1, DoubleCapped = 2 };
const char* to_string(Reading r);

double cut_angle(const Lobe& l, int n);                        // θc (NaN-free; π/2 for uncut lobes)
double upper_limit(Model m, const Lobe& l, Reading r, int n);  // T

// Int(n) by adaptive Gauss–Kronrod (G7/K15) in θ, in double, relative tolerance rel_tol.
struct IntValue {
  double value;
  double error_estimate;
  std::size_t evals;
};
IntValue int_quadrature(Model m, const Lobe& l, Reading r, int n, double rel_tol = 1e-13);

// Int(n) in closed form, evaluated in long double (cs16 and cos_pow; throws std::invalid_argument
// for lobes without a closed form here). Substitution: x = cos θ (Phong rows) or x = cos(θ/2)
// (Blinn rows, cos θ = 2x² − 1, sin θ dθ = −4x dx); for cs16 then w = (n/16)(x − 1) + 1, so that
// Int = (16/n) Σ_k c_k (1 − w0^(17+k))/(17+k) with the weight polynomial re-expanded in w — every
// term is a power of the base itself, no binomial expansion of w^16 and no cancellation.
long double int_exact(Model m, const Lobe& l, Reading r, int n);
bool has_closed_form(const Lobe& l);

// A fit coef(n) = (a·n + b)/(k·π) over the sample (n_i, Int_i).
struct Coeffs {
  double a = 0, b = 0;
};
struct Sample {
  std::vector<int> n;
  std::vector<double> integral;
  int k = 2;
};
// res_i = 2π·coef(n_i)·Int_i − 1 (signed).
std::vector<double> residuals(const Sample& s, Coeffs c);
double max_abs_residual(const Sample& s, Coeffs c, int* argmax_n = nullptr);
// Least squares: minimise Σ res_i² (linear in a, b; 2×2 normal equations in long double).
Coeffs fit_least_squares(const Sample& s);
// Least squares with b held fixed (the paper's Phong row has b = 0).
Coeffs fit_least_squares_fixed_b(const Sample& s, double b);
// Minimax: minimise max_i |res_i| (convex in (a, b); nested golden-section search around the
// least-squares optimum, converged to ~1e-13 in a and b).
Coeffs fit_minimax(const Sample& s);

// Builds the sample of one model/lobe/reading over n = lo..hi (quadrature or closed form).
Sample make_sample(Model m, const Lobe& l, Reading r, int lo, int hi, bool exact);

}  // namespace shadecore::fit

// SPDX-License-Identifier: Apache-2.0
// The 2-D reflectance check R(θi) = ∫ f_r cos θo dωo of the normalised BRDFs (energy.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "shadecore/analysis/energy.hpp"
#include "shadecore/analysis/fit.hpp"

using namespace shadecore;

namespace {
constexpr double kDeg = M_PI / 180;
const int kNs[] = {16, 17, 26, 59, 64, 100, 255, 512, 1000, 1024};
const double kAngles[] = {0, 15, 30, 45, 60, 75, 85};

// Upper bound of R_fixed − R_double from the fixed-point error: the unit output is at most ½ ulp
// above cs16 (spec §3.3), the normalised output at most (½·coef + 1) ulp above coef·cs16; times the
// weighted solid angle of the lobe support, ∫ G(u) du <= 2π·(1 − cos r_max)·wmax (wmax = 4 for the
// Blinn rows' 4(ωi·h), 1/cos θi for the microfacet rows).
double quant_allowance(Model m, int n, double theta_i) {
  energy::Options o;
  const double wmax = (m == Model::Blinn || m == Model::BlinnMod) ? 4.0
                      : (m == Model::BlinnNdf || m == Model::BlinnHeightfield) ? 1.0 / std::cos(theta_i) : 1.0;
  const double support = 2 * M_PI * (1 - std::cos(energy::lobe_radius(o, n))) * wmax;
  return (0.5 * fitted_coef(m, n) + 1) * std::ldexp(1.0, -16) * support;
}
}  // namespace

// At normal incidence the 2-D integral of the double-precision BRDF must equal the paper's 1-D
// shortcut 2π·coef·Int(n) (closed form) for the reading that matches the hemisphere: Phong rows to
// θcr, Blinn rows to min(2θcr, π/2) (double_capped), microfacet rows the heightfield integral in α
// up to min(θcr, π/4) (only reachable while the lobe fits in α < π/4, i.e. n >= 59).
TEST(Energy, NormalIncidenceMatchesOneDimensionalIntegral) {
  energy::Options o;
  o.fixed_point = false;
  const fit::Lobe l{fit::LobeKind::Cs16, Cutoff::ThetaCr};
  for (int n : kNs) {
    struct Row { Model m; Model integral_of; fit::Reading r; };
    const Row rows[] = {{Model::Phong, Model::Phong, fit::Reading::Paper},
                        {Model::PhongMod, Model::PhongMod, fit::Reading::Paper},
                        {Model::Blinn, Model::Blinn, fit::Reading::DoubleCapped},
                        {Model::BlinnMod, Model::BlinnMod, fit::Reading::DoubleCapped},
                        {Model::BlinnNdf, Model::PhongMod, fit::Reading::Paper},
                        {Model::BlinnHeightfield, Model::PhongMod, fit::Reading::Paper}};
    for (const Row& r : rows) {
      if ((r.m == Model::BlinnNdf || r.m == Model::BlinnHeightfield) && n < 59) continue;
      const double one_d = 2 * M_PI * fitted_coef(r.m, n) * static_cast<double>(fit::int_exact(r.integral_of, l, r.r, n));
      EXPECT_NEAR(energy::reflectance(r.m, n, 0.0, o), one_d, 1e-9) << info(r.m).key << " n=" << n;
    }
  }
}

// The exact-per-code method against an independent 2-D midpoint grid (cosines computed from the
// vectors and quantised). The grid error is not monotone (the horizon cuts the lobe between grid
// rings), so the check is: the finest grid (1600×800) is within the spread of the grid sequence
// 400×200, 800×400, 1600×800 (its own uncertainty) of the cells value, plus 1e-6.
TEST(Energy, CellsAgreeWithGrid) {
  for (Model m : {Model::Phong, Model::PhongMod, Model::Blinn, Model::BlinnMod, Model::BlinnHeightfield})
    for (int n : {20, 300})
      for (double ang : {0.0, 40.0, 80.0}) {
        energy::Options c;
        const double rc = energy::reflectance(m, n, ang * kDeg, c);
        double lo = 1e300, hi = -1e300, finest = 0;
        for (int r : {400, 800, 1600}) {
          energy::Options g;
          g.method = energy::Options::Method::Grid;
          g.radial = r;
          g.azimuth = r / 2;
          finest = energy::reflectance(m, n, ang * kDeg, g);
          lo = std::min(lo, finest);
          hi = std::max(hi, finest);
        }
        EXPECT_LE(std::fabs(finest - rc), (hi - lo) + 1e-6) << info(m).key << " n=" << n << " " << ang;
      }
}

// Fixed point against double: below by at most the (unit + coefficient) error, above by at most the
// derived allowance.
TEST(Energy, FixedPointWithinDerivedAllowanceOfDouble) {
  for (const auto& mi : kModels)
    for (int n : {16, 64, 1024})
      for (double ang : {0.0, 60.0}) {
        energy::Options f, d;
        d.fixed_point = false;
        const double rf = energy::reflectance(mi.model, n, ang * kDeg, f);
        const double rd = energy::reflectance(mi.model, n, ang * kDeg, d);
        const double tol = quant_allowance(mi.model, n, ang * kDeg);
        EXPECT_LE(rf - rd, tol) << mi.key << " n=" << n;
        EXPECT_GE(rf - rd, -2 * tol) << mi.key << " n=" << n;
      }
}

// Models meant to conserve energy with the published coefficients: R <= 1 + (the paper's own max
// res for the row) + the fixed-point allowance, at every tested n and angle. Phong's RDF lobe and the
// modified Phong lobe only lose energy to the horizon as θi grows.
TEST(Energy, PhongRowsConserveWithinPublishedResidual) {
  for (Model m : {Model::Phong, Model::PhongMod})
    for (int n : kNs)
      for (double ang : kAngles) {
        const double R = energy::reflectance(m, n, ang * kDeg, {});
        EXPECT_LE(R, 1 + info(m).claimed_res + quant_allowance(m, n, ang * kDeg)) << info(m).key << " n=" << n << " " << ang;
      }
}

// Modified Blinn-Phong with the published 1.027n + 4.8 is 3–6 % short at normal incidence: it never
// creates energy (and never reaches 1 either — see docs/energy.md).
TEST(Energy, ModifiedBlinnNeverExceedsOne) {
  for (int n : kNs)
    for (double ang : kAngles) {
      const double R = energy::reflectance(Model::BlinnMod, n, ang * kDeg, {});
      EXPECT_LE(R, 1.0) << n << " " << ang;
      if (ang == 0) {
        EXPECT_LT(R, 0.97) << n;
      }
    }
}

// Documented non-conservation, asserted so a change is noticed:
//  * Blinn-Phong (RDF) over the real hemisphere (double_capped) exceeds 1 by more than the paper's
//    1.5e-3: its claim holds only for the truncated θ <= θcr integral. R(0) − 1 equals the 1-D res.
//  * the microfacet rows (D/(4 cos θi cos θo), no shadowing/masking) create energy at grazing incidence.
TEST(Energy, DocumentedExcessWhereNotConserving) {
  const fit::Lobe l{fit::LobeKind::Cs16, Cutoff::ThetaCr};
  double worst = 0;
  for (int n : kNs) {
    const double R = energy::reflectance(Model::Blinn, n, 0.0, {});
    const double one_d = 2 * M_PI * fitted_coef(Model::Blinn, n) *
                         static_cast<double>(fit::int_exact(Model::Blinn, l, fit::Reading::DoubleCapped, n));
    EXPECT_NEAR(R, one_d, quant_allowance(Model::Blinn, n, 0.0)) << n;
    worst = std::max(worst, R);
  }
  EXPECT_GT(worst, 1 + 1.5e-3);
  EXPECT_GT(energy::reflectance(Model::BlinnHeightfield, 16, 85 * kDeg, {}), 1.5);
  // Up to 60° the NDF row (the smaller coefficient) stays within its fixed-point allowance of 1.
  for (int n : kNs)
    for (double ang : {0.0, 15.0, 30.0, 45.0, 60.0})
      EXPECT_LE(energy::reflectance(Model::BlinnNdf, n, ang * kDeg, {}), 1 + quant_allowance(Model::BlinnNdf, n, ang * kDeg));
}

TEST(Energy, RejectsBadArguments) {
  EXPECT_THROW(energy::reflectance(Model::Phong, 15, 0, {}), std::invalid_argument);
  EXPECT_THROW(energy::reflectance(Model::Phong, 64, M_PI / 2, {}), std::invalid_argument);
  EXPECT_THROW(energy::reflectance(Model::Phong, 64, -0.1, {}), std::invalid_argument);
}

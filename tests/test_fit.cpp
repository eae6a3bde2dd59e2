// SPDX-License-Identifier: Apache-2.0
// Int(n): adaptive quadrature against the closed forms; the least-squares and minimax fits;
// the published Phong bound against its analytic value; the fit CLI's errors and outputs.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "shadecore/analysis/fit.hpp"
#include "shadecore/analysis/quadrature.hpp"

#include "cli_run.hpp"

using namespace shadecore;
namespace fs = std::filesystem;

TEST(Quadrature, KronrodExactForPolynomialsAndAdaptiveOnPeaks) {
  // K15 integrates degree <= 22 exactly: one interval suffices.
  auto q = integrate<double>([](double x) { return std::pow(x, 22); }, 0.0, 1.0, 0.0, 1e-14);
  EXPECT_NEAR(q.value, 1.0 / 23, 1e-16);
  EXPECT_TRUE(q.converged);
  // A narrow peak needs adaptivity: ∫_0^1 exp(−10^4 x²) dx = (√π/200)·erf(100).
  q = integrate<double>([](double x) { return std::exp(-1e4 * x * x); }, 0.0, 1.0, 0.0, 1e-13);
  EXPECT_NEAR(q.value, std::sqrt(M_PI) / 200 * std::erf(100.0), 1e-16);
  EXPECT_GT(q.intervals, 1u);
  // A kink: ∫_0^2 |x − 1/3| dx = 1/18 + 25/18.
  q = integrate<double>([](double x) { return std::fabs(x - 1.0 / 3); }, 0.0, 2.0, 0.0, 1e-13);
  EXPECT_NEAR(q.value, 26.0 / 18, 1e-13);
}

// Closed forms (long double) against the quadrature for every model, lobe, cut-off and reading, at
// exponents around the interesting crossings (θcr = θ0 near n = 25/26; 2θcr = π/2 near n = 58/59).
TEST(IntClosedForm, MatchesQuadrature) {
  const fit::Lobe lobes[] = {{fit::LobeKind::Cs16, Cutoff::ThetaCr},
                             {fit::LobeKind::Cs16, Cutoff::SignClamp},
                             {fit::LobeKind::CosPow, Cutoff::ThetaCr}};
  for (const auto& mi : kModels)
    for (const auto& l : lobes)
      for (auto r : {fit::Reading::Paper, fit::Reading::Double, fit::Reading::DoubleCapped})
        for (int n : {16, 17, 20, 21, 25, 26, 58, 59, 100, 257, 512, 1000, 1024}) {
          const double q = fit::int_quadrature(mi.model, l, r, n, 1e-13).value;
          const double e = static_cast<double>(fit::int_exact(mi.model, l, r, n));
          EXPECT_NEAR(q / e, 1.0, 1e-12) << mi.key << " " << fit::describe(l) << " " << fit::to_string(r) << " n=" << n;
        }
  EXPECT_THROW(fit::int_exact(Model::Phong, {fit::LobeKind::Schlick, Cutoff::ThetaCr}, fit::Reading::Paper, 64),
               std::invalid_argument);
}

// The Schlick lobe (quadrature only in the tool): for the Phong row Int = ∫_0^1 t/(n − (n−1)t) dt
// = n·ln(n)/(n−1)² − 1/(n−1), integrated over the whole hemisphere.
TEST(IntQuadrature, SchlickPhongRowMatchesHandDerivedValue) {
  const fit::Lobe l{fit::LobeKind::Schlick, Cutoff::ThetaCr};
  for (int n : {16, 100, 1024}) {
    const double c = n - 1.0;
    const double expect = n * std::log(static_cast<double>(n)) / (c * c) - 1 / c;
    EXPECT_NEAR(fit::int_quadrature(Model::Phong, l, fit::Reading::Paper, n).value / expect, 1.0, 1e-12) << n;
  }
}

// Hand-derived values: with the exact-zero cut-off the base runs from 0 to 1, so the Phong
// integral is ∫ w^16 du = 16/(17n) and the modified Phong one (16/n)[(1−16/n)/17 + 16/(18n)].
TEST(IntClosedForm, HandDerivedPhongValues) {
  const fit::Lobe ez{fit::LobeKind::Cs16, Cutoff::SignClamp};
  for (int n : {16, 40, 1024}) {
    EXPECT_NEAR(static_cast<double>(fit::int_exact(Model::Phong, ez, fit::Reading::Paper, n)), 16.0 / (17.0 * n), 1e-17);
    const double a = n / 16.0;
    const double mod = (1 / a) * ((1 - 1 / a) / 17 + 1 / (18 * a));
    EXPECT_NEAR(static_cast<double>(fit::int_exact(Model::PhongMod, ez, fit::Reading::Paper, n)), mod, 1e-17);
  }
}

// Int(n) = 16/(17n) ⇒ the optimum is coef = 17n/(32π), a = 17/16 = 1.0625, b = 0, and the
// published a = 1.063 gives max res = 1.063/1.0625 − 1 = 4.70588…e-4 (the paper's 4.7e-4).
TEST(Fit, PhongRecoversAnalyticOptimumAndPublishedBound) {
  const auto s = fit::make_sample(Model::Phong, {fit::LobeKind::Cs16, Cutoff::SignClamp}, fit::Reading::Paper, 16, 1024, false);
  const auto ls = fit::fit_least_squares(s);
  EXPECT_NEAR(ls.a, 17.0 / 16, 1e-12);
  EXPECT_NEAR(ls.b, 0.0, 1e-9);
  EXPECT_NEAR(fit::max_abs_residual(s, {1.063, 0}), 1.063 / 1.0625 - 1, 1e-12);
}

TEST(Fit, LeastSquaresRecoversSyntheticCoefficients) {
  // Int_i = 1/(2π·coef_i)·(1 + ε_i) with ε of zero mean: exact recovery for ε = 0, close for noise.
  for (int k : {2, 8}) {
    fit::Sample s;
    s.k = k;
    const double a = 1.0712, b = -2.35;
    for (int n = 16; n <= 1024; n += 3) {
      s.n.push_back(n);
      s.integral.push_back(k / (2.0 * (a * n + b)));
    }
    const auto ls = fit::fit_least_squares(s);
    EXPECT_NEAR(ls.a, a, 1e-12);
    EXPECT_NEAR(ls.b, b, 1e-9);
    const auto mm = fit::fit_minimax(s);
    EXPECT_NEAR(mm.a, a, 1e-9);
    EXPECT_NEAR(mm.b, b, 1e-6);
    EXPECT_NEAR(fit::fit_least_squares_fixed_b(s, b).a, a, 1e-12);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> eps(-1e-3, 1e-3);
    for (auto& v : s.integral) v *= 1 + eps(rng);
    const auto ln = fit::fit_least_squares(s);
    EXPECT_NEAR(ln.a, a, 2e-4);
    EXPECT_NEAR(ln.b, b, 0.05);
  }
}

// The minimax solution is not beaten by the least-squares one nor by nearby points.
TEST(Fit, MinimaxIsLocallyOptimal) {
  const auto s = fit::make_sample(Model::BlinnMod, {fit::LobeKind::Cs16, Cutoff::ThetaCr}, fit::Reading::Paper, 16, 1024, true);
  const auto mm = fit::fit_minimax(s);
  const double best = fit::max_abs_residual(s, mm);
  EXPECT_LE(best, fit::max_abs_residual(s, fit::fit_least_squares(s)));
  for (double da : {-1e-5, 0.0, 1e-5})
    for (double db : {-1e-3, 0.0, 1e-3}) EXPECT_GE(fit::max_abs_residual(s, {mm.a + da, mm.b + db}), best - 1e-15);
}

using namespace shadecore::testing;  // tests/cli_run.hpp

TEST(CliFit, BadArgumentsGiveOneLineErrors) {
  expect_one_line_error("fit --lobe gauss", "unknown lobe");
  expect_one_line_error("fit --cutoff nope", "unknown cutoff");
  expect_one_line_error("fit --model cook", "unknown model");
  expect_one_line_error("fit --n 8..100", "out of range");
  expect_one_line_error("fit --n 64", "at least two exponents");
  expect_one_line_error("fit --n 1..x", "malformed range");
  expect_one_line_error("fit --tol 0.5", "--tol");
  expect_one_line_error("fit --json /nonexistent_dir_xyz/f.json", "cannot write");
  expect_one_line_error("energy --angles 90", "out of range");
  expect_one_line_error("energy --angles 10,abc", "malformed angle");
  expect_one_line_error("energy --coef best", "unknown coefficient kind");
  expect_one_line_error("energy --n-step 0", "--n-step");
  expect_one_line_error("energy --method mc", "unknown method");
  expect_one_line_error("energy --model cook", "unknown model");
}

TEST(CliFit, WritesJsonWithVerdicts) {
  const fs::path j = fs::temp_directory_path() / ("shadecore_fit_" + std::to_string(::getpid()) + ".json");
  const CliRun r = run_cli("fit --model phong --json " + j.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(j);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string s = ss.str();
  EXPECT_NE(s.find("\"verdicts\""), std::string::npos);
  EXPECT_NE(s.find("\"least_squares\""), std::string::npos);
  EXPECT_NE(r.out.find("REPRODUCED"), std::string::npos);
  fs::remove(j);
}

TEST(CliFit, EnergyWritesJsonAndReportsWhereEnergyIsCreated) {
  const fs::path j = fs::temp_directory_path() / ("shadecore_energy_" + std::to_string(::getpid()) + ".json");
  const CliRun r = run_cli("energy --model blinn_hf --n 16..18 --angles 0,85 --json " + j.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("where R > 1"), std::string::npos);
  std::ifstream in(j);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("\"R_gt_1\""), std::string::npos);
  fs::remove(j);
}

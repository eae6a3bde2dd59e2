// SPDX-License-Identifier: Apache-2.0
// shadecore — Int(n), closed forms and coefficient fits (see fit.hpp).
#include "shadecore/analysis/fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "shadecore/analysis/golden.hpp"
#include "shadecore/analysis/quadrature.hpp"

namespace shadecore::fit {

const char* to_string(LobeKind k) {
  switch (k) {
    case LobeKind::Cs16: return "cs16";
    case LobeKind::CosPow: return "cos_pow";
    case LobeKind::Schlick: return "schlick";
  }
  return "?";
}

LobeKind parse_lobe(std::string_view s) {
  if (s == "cs16") return LobeKind::Cs16;
  if (s == "cos_pow") return LobeKind::CosPow;
  if (s == "schlick") return LobeKind::Schlick;
  throw std::invalid_argument("unknown lobe '" + std::string(s) + "' (known: cs16, cos_pow, schlick)");
}

std::string describe(const Lobe& l) {
  if (l.kind != LobeKind::Cs16) return to_string(l.kind);
  return std::string("cs16/") + (l.cutoff == Cutoff::ThetaCr ? "theta_cr=6/sqrt(n)" : "exact_zero");
}

const char* to_string(Reading r) {
  switch (r) {
    case Reading::Paper: return "paper";
    case Reading::Double: return "double";
    case Reading::DoubleCapped: return "double_capped";
  }
  return "?";
}

double lobe_value(const Lobe& l, double c, int n) {
  switch (l.kind) {
    case LobeKind::Cs16: return golden::pow16(golden::cs16_base(c, n));
    case LobeKind::CosPow: return golden::cos_pow(c, n);
    case LobeKind::Schlick: return golden::schlick(c, n);
  }
  return 0;
}

double cut_angle(const Lobe& l, int n) {
  if (l.kind != LobeKind::Cs16) return M_PI / 2;
  return l.cutoff == Cutoff::ThetaCr ? golden::theta_cr(n) : std::acos((n - 16.0) / n);
}

double upper_limit(Model m, const Lobe& l, Reading r, int n) {
  const double half_pi = M_PI / 2;
  if (l.kind != LobeKind::Cs16) return half_pi;
  const double tc = cut_angle(l, n);
  if (!info(m).half_angle) return std::min(tc, half_pi);
  switch (r) {
    case Reading::Paper: return tc;
    case Reading::Double: return 2 * tc;
    case Reading::DoubleCapped: return std::min(2 * tc, half_pi);
  }
  return tc;
}

IntValue int_quadrature(Model m, const Lobe& l, Reading r, int n, double rel_tol) {
  validate_n(n);
  const ModelInfo& mi = info(m);
  const double T = upper_limit(m, l, r, n);
  auto f = [&](double th) {
    const double c = std::cos(mi.half_angle ? th / 2 : th);
    double v = lobe_value(l, c, n) * std::sin(th);
    if (mi.cos_weight) v *= std::cos(th);
    return v;
  };
  const auto q = integrate<double>(f, 0.0, T, 0.0, rel_tol, 20000);
  if (!q.converged) throw std::runtime_error("quadrature did not converge for n = " + std::to_string(n));
  return {q.value, q.error, q.evals};
}

bool has_closed_form(const Lobe& l) { return l.kind == LobeKind::Cs16 || l.kind == LobeKind::CosPow; }

namespace {
using Poly = std::array<long double, 4>;  // c0 + c1 x + c2 x² + c3 x³

// The weight q(x) in the base variable x (x = cos θ or cos(θ/2)), so that Int = ∫_{x0}^1 lobe(x) q(x) dx.
Poly weight(Model m) {
  const ModelInfo& mi = info(m);
  if (!mi.half_angle) return mi.cos_weight ? Poly{0, 1, 0, 0} : Poly{1, 0, 0, 0};
  // sin θ dθ = −d(2x² − 1) = −4x dx; cos θ = 2x² − 1.
  return mi.cos_weight ? Poly{0, -4, 0, 8} : Poly{0, 4, 0, 0};
}

// q(s·w + t) as a polynomial in w.
Poly compose_linear(const Poly& q, long double s, long double t) {
  Poly r{0, 0, 0, 0};
  // Horner: r = ((q3)·y + q2)·y + q1)·y + q0 with y = s·w + t.
  for (int k = 3; k >= 0; --k) {
    Poly nr{0, 0, 0, 0};
    for (int j = 0; j < 4; ++j) {
      if (r[j] == 0) continue;
      nr[j] += r[j] * t;
      if (j + 1 < 4) nr[j + 1] += r[j] * s;
    }
    nr[0] += q[k];
    r = nr;
  }
  return r;
}
}  // namespace

long double int_exact(Model m, const Lobe& l, Reading r, int n) {
  validate_n(n);
  if (!has_closed_form(l)) throw std::invalid_argument(std::string("no closed form for lobe ") + to_string(l.kind));
  const ModelInfo& mi = info(m);
  const long double T = upper_limit(m, l, r, n);
  const long double x0 = std::cos(mi.half_angle ? T / 2 : T);
  const Poly q = weight(m);
  long double sum = 0;
  if (l.kind == LobeKind::CosPow) {
    for (int k = 0; k < 4; ++k)
      if (q[k] != 0) sum += q[k] * (1 - std::pow(x0, static_cast<long double>(n + 1 + k))) / (n + 1 + k);
    return sum;
  }
  // cs16: w = a(x − 1) + 1, x = w/a + (a − 1)/a, dx = dw/a.
  const long double a = n / 16.0L;
  const long double w0 = a * (x0 - 1) + 1;
  const Poly c = compose_linear(q, 1 / a, (a - 1) / a);
  for (int k = 0; k < 4; ++k)
    if (c[k] != 0) sum += c[k] * (1 - std::pow(w0, static_cast<long double>(17 + k))) / (17 + k);
  return sum / a;
}

std::vector<double> residuals(const Sample& s, Coeffs c) {
  std::vector<double> r(s.n.size());
  for (std::size_t i = 0; i < s.n.size(); ++i)
    r[i] = 2.0 / s.k * (c.a * s.n[i] + c.b) * s.integral[i] - 1.0;  // 2π·(a n + b)/(kπ)·Int − 1
  return r;
}

double max_abs_residual(const Sample& s, Coeffs c, int* argmax_n) {
  double mx = -1;
  for (std::size_t i = 0; i < s.n.size(); ++i) {
    const double v = std::fabs(2.0 / s.k * (c.a * s.n[i] + c.b) * s.integral[i] - 1.0);
    if (v > mx) {
      mx = v;
      if (argmax_n) *argmax_n = s.n[i];
    }
  }
  return mx;
}

Coeffs fit_least_squares(const Sample& s) {
  // res_i = a·u_i + b·v_i − 1 with u_i = (2/k)·n_i·Int_i, v_i = (2/k)·Int_i.
  long double suu = 0, suv = 0, svv = 0, su = 0, sv = 0;
  for (std::size_t i = 0; i < s.n.size(); ++i) {
    const long double v = 2.0L / s.k * s.integral[i], u = v * s.n[i];
    suu += u * u; suv += u * v; svv += v * v; su += u; sv += v;
  }
  const long double det = suu * svv - suv * suv;
  if (!(std::fabs(det) > 0)) throw std::runtime_error("least squares: singular normal equations (need >= 2 distinct n)");
  return {static_cast<double>((su * svv - sv * suv) / det), static_cast<double>((suu * sv - suv * su) / det)};
}

Coeffs fit_least_squares_fixed_b(const Sample& s, double b) {
  long double suu = 0, sur = 0;
  for (std::size_t i = 0; i < s.n.size(); ++i) {
    const long double v = 2.0L / s.k * s.integral[i], u = v * s.n[i];
    suu += u * u;
    sur += u * (1 - b * v);
  }
  return {static_cast<double>(sur / suu), b};
}

namespace {
template <class F>
double golden_min(F f, double lo, double hi, int iters) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < iters; ++i) {
    if (f1 <= f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - g * (hi - lo); f1 = f(x1); }
    else { lo = x1; x1 = x2; f1 = f2; x2 = lo + g * (hi - lo); f2 = f(x2); }
  }
  return (lo + hi) / 2;
}
}  // namespace

Coeffs fit_minimax(const Sample& s) {
  const Coeffs ls = fit_least_squares(s);
  auto best_b = [&](double a) {
    return golden_min([&](double b) { return max_abs_residual(s, {a, b}); }, ls.b - 50, ls.b + 50, 90);
  };
  const double a = golden_min([&](double a) { return max_abs_residual(s, {a, best_b(a)}); }, ls.a - 0.2, ls.a + 0.2, 80);
  return {a, best_b(a)};
}

Sample make_sample(Model m, const Lobe& l, Reading r, int lo, int hi, bool exact) {
  validate_n(lo);
  validate_n(hi);
  Sample s;
  s.k = info(m).k;
  for (int n = lo; n <= hi; ++n) {
    s.n.push_back(n);
    s.integral.push_back(exact ? static_cast<double>(int_exact(m, l, r, n)) : int_quadrature(m, l, r, n).value);
  }
  return s;
}

}  // namespace shadecore::fit

// SPDX-License-Identifier: Apache-2.0
// shadecore — 2-D reflectance check of the normalised BRDFs (see energy.hpp).
#include "shadecore/analysis/energy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shadecore/analysis/golden.hpp"

namespace shadecore::energy {

double lobe_radius(const Options& o, int n) {
  // Non-zero output needs cos ≥ cos θc − 1 code (input rounding); θc the larger of 6/√n and θ0.
  const double tc = std::max(golden::theta_cr(n), std::acos((n - 16.0) / n));
  const double c = std::cos(tc) - std::ldexp(2.0, -o.format.frac);
  return c <= 0 ? M_PI / 2 : std::acos(c);
}

namespace {

// Azimuth integral G(u) = ∫ (weight)·[visible] dφ over the full circle, in closed form.
// Phong rows: u = R·ωo; Blinn rows: u = N·h. Visible azimuths are |φ| <= φmax. *cls (if given)
// is 0 when nothing is visible, 2 when the whole ring is, 1 otherwise — G is smooth in u only
// within one class, so cells are split where the class changes.
double azimuth_integral(Model m, bool blinn_rows, double u, double si, double ci, int* cls = nullptr) {
  if (cls) *cls = 0;
  if (u <= -1 || u > 1) return 0;
  const double s = std::sqrt(std::max(0.0, 1 - u * u));
  const double A = si * s;  // coefficient of cos φ
  auto phimax = [&](double lim, bool all_if_flat) {
    // visible ⇔ cos φ > lim (A > 0), or everywhere/nowhere when A = 0
    double phm;
    if (A <= 0) phm = all_if_flat ? M_PI : 0;
    else phm = std::acos(std::clamp(lim, -1.0, 1.0));
    if (cls) *cls = phm <= 0 ? 0 : (phm >= M_PI ? 2 : 1);
    return phm;
  };
  if (!blinn_rows) {
    // cos θo = A·cos φ + u·ci > 0
    const double phm = phimax(A > 0 ? -u * ci / A : 0, u * ci > 0);
    if (m == Model::Phong) return 2 * phm;
    return 2 * A * std::sin(phm) + 2 * u * ci * phm;  // ∫ cos θo dφ
  }
  if (u <= 0) return 0;
  // ih = ωi·h = A·cos φ + B; cos θo = 2·ih·u − ci > 0  ⇔  cos φ > ci(1 − 2u²)/(2u·A)
  const double B = ci * u;
  const double phm = phimax(A > 0 ? ci * (1 - 2 * u * u) / (2 * u * A) : 0, 2 * B * u - ci > 0);
  const double sp = std::sin(phm), cp = std::cos(phm);
  const double I1 = 2 * A * sp + 2 * B * phm;                                    // ∫ ih dφ
  const double I2 = A * A * (phm + sp * cp) + 4 * A * B * sp + 2 * B * B * phm;  // ∫ ih² dφ
  switch (m) {
    case Model::Blinn: return 4 * I1;
    case Model::BlinnMod: return 8 * u * I2 - 4 * ci * I1;
    default: return I1 / ci;  // microfacet form D/(4 ci co)·co·4 ih
  }
}

// ∫_ua^ub lobe(u)·G(u) du with a 3-point Gauss–Legendre rule on each piece where G is smooth
// (the cell is split at the u where the visibility class changes, found by bisection).
template <class L>
double cell_integral(Model m, bool blinn_rows, double ua, double ub, double si, double ci, L lobe) {
  static const double gx[3] = {-0.7745966692414833770, 0.0, 0.7745966692414833770};
  static const double gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  auto gauss = [&](double a, double b) {
    const double h = (b - a) / 2, c = (a + b) / 2;
    double g = 0;
    for (int q = 0; q < 3; ++q) {
      const double u = c + h * gx[q];
      const double lv = lobe(u);
      if (lv != 0) g += gw[q] * lv * azimuth_integral(m, blinn_rows, u, si, ci);
    }
    return g * h;
  };
  int ca, cb;
  azimuth_integral(m, blinn_rows, ua, si, ci, &ca);
  azimuth_integral(m, blinn_rows, ub, si, ci, &cb);
  if (ca == cb) return gauss(ua, ub);
  double lo = ua, hi = ub;  // class(lo) = ca != class(hi)
  for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
    const double mid = (lo + hi) / 2;
    int cm;
    azimuth_integral(m, blinn_rows, mid, si, ci, &cm);
    (cm == ca ? lo : hi) = mid;
  }
  return gauss(ua, lo) + gauss(lo, ub);  // at most one class change per code cell in practice
}

// What both integrations of one (model, n, θi) need: the normalisation coefficient (double, and its code
// for the fixed-point datapath), the cs16 material, 2^F, sin and cos θi, and whether the lobe is a
// function of N·h (Blinn rows) rather than of R·ωo (Phong rows).
struct LobeSetup {
  EnergyFormat nf;
  double coef_d;
  uint32_t coef_q;
  Cs16Material mat;
  double scale, si, ci;
  bool blinn_rows;

  LobeSetup(Model m, int n, double theta_i, const Options& o)
      : nf{o.format.frac, o.coef_int_bits},
        coef_d(coef_value(m, o.coef, n)),
        coef_q(o.fixed_point ? coef_code(nf, coef_d) : 0),
        mat(cs16_setup(o.format, n)),
        scale(std::ldexp(1.0, o.format.frac)),
        si(std::sin(theta_i)),
        ci(std::cos(theta_i)),
        blinn_rows(info(m).half_angle || m == Model::BlinnNdf || m == Model::BlinnHeightfield) {}

  // The normalised double lobe coef·cs16(c, n) under the run's cut-off.
  [[nodiscard]] double golden_lobe(const Options& o, double c, int n) const {
    return coef_d * (o.cutoff == Cutoff::ThetaCr ? golden::cs16_theta_cr(c, n) : golden::cs16_sign_clamp(c, n));
  }
};

double reflectance_cells(Model m, int n, double theta_i, const Options& o) {
  const LobeSetup ls(m, n, theta_i, o);
  const double scale = ls.scale, ulp = 1 / scale;
  const int64_t one = int64_t{1} << o.format.frac;
  const int64_t kmin = std::max<int64_t>(0, static_cast<int64_t>(std::floor(std::cos(lobe_radius(o, n)) * scale)) - 2);
  double sum = 0;
  for (int64_t k = one; k >= kmin; --k) {
    // Code cell of k under round-to-nearest, clipped to u <= 1.
    const double ua = (k - 0.5) * ulp, ub = std::min(1.0, (k + 0.5) * ulp);
    if (o.fixed_point) {
      const uint32_t spec = cs16_eval(o.format, o.cutoff, ls.mat, k);
      if (spec == 0) continue;
      const double v = static_cast<double>(energy_eval(ls.nf, ls.coef_q, spec)) * ulp;
      sum += cell_integral(m, ls.blinn_rows, ua, ub, ls.si, ls.ci, [v](double) { return v; });
    } else {
      sum += cell_integral(m, ls.blinn_rows, ua, ub, ls.si, ls.ci, [&](double u) { return ls.golden_lobe(o, u, n); });
    }
  }
  return sum;
}

double reflectance_grid(Model m, int n, double theta_i, const Options& o) {
  const LobeSetup ls(m, n, theta_i, o);
  const double scale = ls.scale;
  // The normalised lobe for a cosine computed from the directions.
  auto lobe = [&](double c) -> double {
    if (!o.fixed_point) return ls.golden_lobe(o, c, n);
    const int64_t code = std::llround(c * scale);  // quantise to the (F+2)-bit input (|c| <= 1 fits)
    const uint32_t spec = cs16_eval(o.format, o.cutoff, ls.mat, code);
    return static_cast<double>(energy_eval(ls.nf, ls.coef_q, spec)) / scale;
  };

  const double si = ls.si, ci = ls.ci;
  const bool blinn_rows = ls.blinn_rows;
  const double rmax = std::min(lobe_radius(o, n), blinn_rows ? M_PI / 2 : M_PI);
  const double dr = rmax / o.radial, dp = M_PI / o.azimuth;
  std::vector<double> cp(o.azimuth), sp(o.azimuth);
  for (int j = 0; j < o.azimuth; ++j) { cp[j] = std::cos((j + 0.5) * dp); sp[j] = std::sin((j + 0.5) * dp); }

  double sum = 0;
  for (int i = 0; i < o.radial; ++i) {
    const double r = (i + 0.5) * dr, sr = std::sin(r), cr = std::cos(r);
    double ring = 0;
    for (int j = 0; j < o.azimuth; ++j) {
      if (!blinn_rows) {
        // ωo around R = (−si, 0, ci) with the frame t1 = (ci, 0, si), t2 = (0, 1, 0).
        const double ox = sr * cp[j] * ci - cr * si, oy = sr * sp[j], oz = sr * cp[j] * si + cr * ci;
        if (oz <= 0) continue;
        const double rdotv = -si * ox + ci * oz;  // R·ωo from the vectors (= cos r up to rounding)
        (void)oy;
        const double v = lobe(rdotv);
        ring += (m == Model::Phong) ? v : v * oz;
      } else {
        // h around N; ωo = 2(ωi·h)h − ωi; dωo = 4(ωi·h) dω_h.
        const double hx = sr * cp[j], hz = cr;
        const double ih = si * hx + ci * hz;
        if (ih <= 0) continue;
        const double oz = 2 * ih * hz - ci;
        if (oz <= 0) continue;
        const double v = lobe(hz);  // N·h
        switch (m) {
          case Model::Blinn: ring += v * 4 * ih; break;
          case Model::BlinnMod: ring += v * oz * 4 * ih; break;
          default: ring += v * ih / ci; break;  // D/(4 ci co) · co · 4 ih
        }
      }
    }
    sum += ring * sr;
  }
  return 2 * sum * dr * dp;
}

}  // namespace

double reflectance(Model m, int n, double theta_i, const Options& o) {
  validate(o.format);
  validate_n(n);
  if (!(theta_i >= 0 && theta_i < M_PI / 2)) throw std::invalid_argument("incidence angle must be in [0, 90) degrees");
  if (o.radial < 1 || o.azimuth < 1) throw std::invalid_argument("quadrature resolution must be >= 1");
  return o.method == Options::Method::Cells ? reflectance_cells(m, n, theta_i, o) : reflectance_grid(m, n, theta_i, o);
}

}  // namespace shadecore::energy

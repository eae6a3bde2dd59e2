// SPDX-License-Identifier: Apache-2.0
// shadecore — table 5.1 checks of the seed-000 BRDF references: parameter grids, directional albedo by
// the project's adaptive Gauss-Kronrod quadrature, reciprocity over random direction pairs.
#include "shadecore/analysis/brdf.hpp"

#include <cstdio>
#include <initializer_list>
#include <random>

#include "shadecore/analysis/quadrature.hpp"

namespace shadecore::brdf {

namespace {

std::string fmt_params(const char* format, double a, double b = 0, double c = 0, double d = 0, double e = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c, d, e);
  return buf;
}

template <class M>
Instance make(const char* model, std::string params, const M& m, bool aniso = false) {
  return Instance{model, std::move(params), aniso, Fn(m)};
}

// The anisotropic models' grid: every reflectance pair r (ρd, ρs) with every shape pair a (mx, my or nx, ny),
// M{r0, r1, a0, a1}; `params` names the four numbers.
using Pairs = std::initializer_list<std::array<double, 2>>;
template <class M>
void add_anisotropic(std::vector<Instance>& g, const char* model, const char* params, Pairs rr, Pairs aa) {
  for (const auto& r : rr)
    for (const auto& a : aa) g.push_back(make(model, fmt_params(params, r[0], r[1], a[0], a[1]), M{r[0], r[1], a[0], a[1]}, true));
}

}  // namespace

std::vector<std::string> model_names() {
  return {"Lambert",
          "Phong classic",
          "Phong BRDF",
          "Blinn-Phong",
          "Schlick-Phong",
          "Cook-Torrance",
          "Cook-Torrance (1/4π)",
          "Schlick-Cook-Torrance",
          "Schlick-Cook-Torrance (1/4π)",
          "Strauss",
          "Ward",
          "Ashikhmin-Shirley",
          "Schlick",
          "Lafortune"};
}

std::vector<Instance> parameter_grid(const std::string& only) {
  std::vector<Instance> g;
  const auto want = [&](const char* name) { return only.empty() || only == name; };

  if (want("Lambert"))
    for (double kd : {0.2, 0.6, 1.0}) g.push_back(make("Lambert", fmt_params("kd=%g", kd), Lambert{kd}));

  // (kd, ks) of the thesis's figures 2.3/2.4 and the extreme kd + ks = 1 with all of it specular.
  const double kdks[][2] = {{0.4, 0.2}, {0.4, 0.6}, {0.0, 1.0}};
  if (want("Phong classic"))
    for (auto& k : kdks)
      for (double n : {3.0, 10.0, 50.0, 200.0})
        g.push_back(make("Phong classic", fmt_params("kd=%g ks=%g n=%g", k[0], k[1], n), PhongClassic{k[0], k[1], n}));
  for (const char* name : {"Phong BRDF", "Blinn-Phong", "Schlick-Phong"}) {
    if (!want(name)) continue;
    for (auto& k : kdks)
      for (double n : {1.0, 3.0, 10.0, 50.0, 200.0, 1000.0}) {
        const std::string p = fmt_params("kd=%g ks=%g n=%g", k[0], k[1], n);
        if (std::string(name) == "Phong BRDF") g.push_back(make(name, p, PhongBrdf{k[0], k[1], n}));
        if (std::string(name) == "Blinn-Phong") g.push_back(make(name, p, BlinnPhong{k[0], k[1], n}));
        if (std::string(name) == "Schlick-Phong") g.push_back(make(name, p, SchlickPhong{k[0], k[1], n}));
      }
  }

  // Cook-Torrance family: figure 3.8 (kd = ks = 0.4, η = 1.5, m = 0.6..0.05), the plastic and copper
  // spheres of figure 3.7, and an all-specular metal (kd = 0, ks = 1, η = 0.2, κ = 3: silver-like).
  struct Ct {
    double kd, ks, m, eta, kappa;
  };
  std::vector<Ct> cts;
  for (double m : {0.6, 0.4, 0.2, 0.1, 0.05}) cts.push_back({0.4, 0.4, m, 1.5, 0});
  cts.push_back({0.8, 0.2, 0.15, 1.49, 0});   // plastic, fig. 3.7
  cts.push_back({0.0, 0.8, 0.25, 1.0, 2.39});  // copper, fig. 3.7
  for (double m : {0.1, 0.3, 0.6}) cts.push_back({0.0, 1.0, m, 0.2, 3.0});
  for (Microfacet nm : {Microfacet::Thesis, Microfacet::Unit}) {
    const char* ct_name = nm == Microfacet::Thesis ? "Cook-Torrance" : "Cook-Torrance (1/4π)";
    const char* sct_name = nm == Microfacet::Thesis ? "Schlick-Cook-Torrance" : "Schlick-Cook-Torrance (1/4π)";
    for (const Ct& c : cts) {
      const std::string p = fmt_params("kd=%g ks=%g m=%g eta=%g kappa=%g", c.kd, c.ks, c.m, c.eta, c.kappa);
      if (want(ct_name))
        g.push_back(make(ct_name, p, CookTorrance{c.kd, c.ks, c.m, c.eta, c.kappa, nm}));
      if (want(sct_name))
        g.push_back(make(sct_name, p, SchlickCookTorrance{c.kd, c.ks, c.m, fresnel_f0(c.eta, c.kappa), nm}));
    }
  }

  // Strauss: figures 4.1 (s = 0.1..0.9) and 4.2 (e = 0.1..0.9); white base colour (the most light).
  if (want("Strauss"))
    for (double e : {0.0, 0.5, 1.0})
      for (double s : {0.1, 0.3, 0.5, 0.7, 0.9})
        g.push_back(make("Strauss", fmt_params("C=1 s=%g e=%g t=0", s, e), Strauss{1.0, s, e, 0.0}));

  // Ward: ρd + ρs <= 1 (the thesis: "< 1 and m not too large"; its normalisation is "exact while m < 0.2").
  if (want("Ward"))
    add_anisotropic<Ward>(g, "Ward", "rho_d=%g rho_s=%g mx=%g my=%g", {{0.4, 0.4}, {0.0, 1.0}},
                          {{0.05, 0.05}, {0.1, 0.1}, {0.2, 0.2}, {0.05, 0.2}, {0.3, 0.3}});

  if (want("Ashikhmin-Shirley"))
    add_anisotropic<AshikhminShirley>(g, "Ashikhmin-Shirley", "Rd=%g Rs=%g nx=%g ny=%g",
                                      {{0.4, 0.4}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 0.05}},
                                      {{1, 1}, {10, 10}, {100, 100}, {10, 1000}, {1000, 1000}});

  // Schlick: figures 4.5 (p = 1, r = 0.8..0.001) and 4.6 (r = 0.4, p = 1..0.001); C = 1 (all light
  // reflected: the hardest case for energy) and C = 0.05; one DOUBLE material.
  if (want("Schlick")) {
    for (double c : {1.0, 0.05}) {
      for (double r : {1.0, 0.8, 0.4, 0.2, 0.1, 0.01, 0.001})
        g.push_back(make("Schlick", fmt_params("SINGLE C=%g r=%g p=1", c, r), Schlick{{c, r, 1.0}}, true));
      for (double p : {0.6, 0.3, 0.1, 0.05})
        g.push_back(make("Schlick", fmt_params("SINGLE C=%g r=0.4 p=%g", c, p), Schlick{{c, 0.4, p}}, true));
    }
    g.push_back(make("Schlick", "DOUBLE C=0.05 r=0.1 p=1 / C'=0.9 r'=1 p'=1",
                     Schlick{{0.05, 0.1, 1.0}, true, {0.9, 1.0, 1.0}}, true));
    g.push_back(make("Schlick", "DOUBLE C=0.05 r=0.05 p=0.3 / C'=1 r'=0.5 p'=1",
                     Schlick{{0.05, 0.05, 0.3}, true, {1.0, 0.5, 1.0}}, true));
  }

  // Lafortune: a Phong-equivalent lobe (4.28), an off-specular lobe (Cz < −Cx = −Cy, §4.5), a retro lobe
  // (all C > 0), an anisotropic lobe (Cx ≠ Cy); each scaled so that its peak equals the Phong lobe of
  // the same (ks, n), plus kd/π.
  if (want("Lafortune")) {
    for (double n : {3.0, 10.0, 50.0, 200.0}) {
      const double ks = 0.6, kd = 0.4;
      const LafortuneLobe ph = Lafortune::phong_lobe(ks, n);
      const double c = ph.cz;
      Lafortune a{kd, {ph}, 1};
      g.push_back(make("Lafortune", fmt_params("kd=%g phong lobe ks=%g n=%g", kd, ks, n), a, true));
      Lafortune off{kd, {LafortuneLobe{-c, -c, 0.8 * c, n}}, 1};
      g.push_back(make("Lafortune", fmt_params("kd=%g off-specular Cz=0.8(-Cx) n=%g", kd, n), off, true));
      Lafortune retro{kd, {LafortuneLobe{c, c, c, n}}, 1};
      g.push_back(make("Lafortune", fmt_params("kd=%g retro Cx=Cy=Cz n=%g", kd, n), retro, true));
      Lafortune an{kd, {LafortuneLobe{-c, -0.9 * c, c, n}}, 1};
      g.push_back(make("Lafortune", fmt_params("kd=%g aniso Cy=0.9Cx n=%g", kd, n), an, true));
    }
  }
  return g;
}

Albedo directional_albedo(const Fn& f, double theta_i, double phi_i, double rel_tol) {
  const Vec3 n{0, 0, 1}, t{1, 0, 0};
  const Vec3 wi = spherical(theta_i, phi_i);
  bool conv = true;
  double inner_abs = 0;  // largest error estimate of one inner integral, times its outer weight sin·cos
  const auto inner = [&](double th) -> double {
    const double st = std::sin(th), ct = std::cos(th);
    if (st <= 0 || ct <= 0) return 0.0;
    const auto g = [&](double ph) { return f(wi, spherical(th, ph), n, t); };
    const auto r1 = integrate<double>(g, phi_i, phi_i + kPi, 1e-13, rel_tol / 4, 2000);
    const auto r2 = integrate<double>(g, phi_i + kPi, phi_i + 2 * kPi, 1e-13, rel_tol / 4, 2000);
    conv = conv && r1.converged && r2.converged;
    inner_abs = std::max(inner_abs, (r1.error + r2.error) * st * ct);
    return (r1.value + r2.value) * st * ct;
  };
  Albedo a;
  double err = 0;
  const double half = kPi / 2;
  if (theta_i > 1e-9 && theta_i < half) {
    const auto o1 = integrate<double>(inner, 0.0, theta_i, 1e-12, rel_tol, 2000);
    const auto o2 = integrate<double>(inner, theta_i, half, 1e-12, rel_tol, 2000);
    a.value = o1.value + o2.value;
    err = o1.error + o2.error;
    conv = conv && o1.converged && o2.converged;
  } else {
    const auto o = integrate<double>(inner, 0.0, half, 1e-12, rel_tol, 2000);
    a.value = o.value;
    err = o.error;
    conv = conv && o.converged;
  }
  // Outer estimate plus the inner ones carried through the outer rule (whose weights sum to π/2).
  a.error = err + inner_abs * half;
  a.converged = conv;
  return a;
}

Reciprocity reciprocity(const Fn& f, int pairs, unsigned long long seed) {
  std::mt19937_64 rng(seed);
  RandomDirections dir(rng);
  Reciprocity r;
  for (int k = 0; k < pairs; ++k) {
    const Vec3 n = dir.sphere(), t = dir.sphere();
    const Vec3 a = dir.hemisphere(n), b = dir.hemisphere(n);
    const double fab = f(a, b, n, t), fba = f(b, a, n, t);
    const double den = std::max(std::fabs(fab), std::fabs(fba));
    if (den == 0) continue;
    const double rel = std::fabs(fab - fba) / den;
    if (rel > r.max_rel || k == 0) {
      r.max_rel = rel;
      r.wi = a;
      r.wo = b;
      r.f_io = fab;
      r.f_oi = fba;
    }
  }
  return r;
}

std::vector<double> energy_thetas_deg() { return {0, 30, 60, 75, 85, 89, 89.9, 89.99, 89.999}; }

Energy energy(const Instance& inst) {
  Energy e;
  e.max_albedo = -1;
  std::vector<double> phis = {30.0};
  if (inst.anisotropic) phis = {0.0, 30.0, 90.0};
  for (double td : energy_thetas_deg())
    for (double pd : phis) {
      const double th = td * kPi / 180, ph = pd * kPi / 180;
      const Albedo a = directional_albedo(inst.f, th, ph);
      e.converged = e.converged && a.converged;
      if (a.value > e.max_albedo) {
        e.max_albedo = a.value;
        e.error = a.error;
        e.theta_i = th;
        e.phi_i = ph;
      }
    }
  return e;
}

}  // namespace shadecore::brdf

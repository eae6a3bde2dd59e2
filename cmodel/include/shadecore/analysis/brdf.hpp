// SPDX-License-Identifier: Apache-2.0
// shadecore — double-precision BRDF references for the lighting models of seed 000:
// M. Falski, "Przegląd modeli oświetlenia w grafice komputerowej" (a survey of lighting models, MSc
// thesis, Wrocław 2004). Equation numbers "(x.y)" below are the thesis's; docs/brdf.md lists every place
// where the thesis's formula has a typo or an ambiguity and what was chosen here.
//
// Conventions (thesis table 1.1 and eq. 1.10-1.12):
//   wi  unit vector from the surface point towards the light      (Θi)
//   wo  unit vector from the surface point towards the viewer     (Θr)
//   n   unit surface normal                                        (N)
//   t   reference tangent; anisotropic models build X = normalise(t − n(n·t)), Y = n × X on every call
//       (the thesis's timing method: only the directions, the normal and the parameters are inputs)
//   h   the half vector (Θi + Θr)/|Θi + Θr| — eq. (1.11) writes (Θi + Θr)/2, which is not a unit vector;
//       every formula uses h only through angles (δ, β, φ), so the normalised vector is what is meant.
// Every model returns f_r in 1/sr and returns 0 when n·wi <= 0 or n·wo <= 0 (light or viewer below the
// surface). Empirical models the thesis gives as a BSF S_r (eq. 2.1: reflected radiance per unit
// radiance of a point light) are turned into a BRDF by the thesis's own Lambert pair (2.4) <-> (2.5):
// f_r = S_r / (π cos θi).
//
// HTSG (§3.5) is not implemented: see docs/brdf.md ("HTSG").
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace shadecore::brdf {

inline constexpr double kPi = 3.14159265358979323846;

struct Vec3 {
  double x = 0, y = 0, z = 0;
};
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(const Vec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3 normalize(const Vec3& a) {
  const double l2 = dot(a, a);
  return l2 > 0 ? a * (1.0 / std::sqrt(l2)) : a;
}
// Unit direction from spherical angles about the local frame X = (1,0,0), Y = (0,1,0), N = (0,0,1)
// (eq. 1.1-1.3 with r = 1).
inline Vec3 spherical(double theta, double phi) {
  return {std::cos(phi) * std::sin(theta), std::sin(phi) * std::sin(theta), std::cos(theta)};
}

// Local frame for the anisotropic models: X from the tangent, Y = N × X (two cross products'
// worth of work per call, as the thesis's §5.4 describes).
struct Frame {
  Vec3 x, y;
};
inline Frame make_frame(const Vec3& n, const Vec3& t) {
  const Vec3 x = normalize(t - n * dot(n, t));
  return {x, cross(n, x)};
}

// Θs = 2N(N·Θi) − Θi, eq. (1.10).
inline Vec3 mirror(const Vec3& wi, const Vec3& n) { return n * (2.0 * dot(n, wi)) - wi; }

// Random directions from a 64-bit Mersenne Twister (the reciprocity check, bench/bench_brdf.cpp):
// sphere() uniform on the unit sphere (z, then φ, from two draws); hemisphere(n) uniform on n's side,
// directions within 10⁻³ of the horizon drawn again.
class RandomDirections {
 public:
  explicit RandomDirections(std::mt19937_64& rng) : rng_(rng) {}
  Vec3 sphere() {
    const double z = 2 * u_(rng_) - 1, ph = 2 * kPi * u_(rng_), r = std::sqrt(std::max(0.0, 1 - z * z));
    return Vec3{r * std::cos(ph), r * std::sin(ph), z};
  }
  Vec3 hemisphere(const Vec3& n) {
    Vec3 d = sphere();
    while (std::fabs(dot(d, n)) < 1e-3) d = sphere();
    return dot(d, n) < 0 ? d * -1.0 : d;
  }

 private:
  std::mt19937_64& rng_;
  std::uniform_real_distribution<double> u_{0.0, 1.0};
};

// ---------------------------------------------------------------------------------------------
// Building blocks of chapter 3.

// Phong's highlight t^n, clamped to 0 for t <= 0 (§2.3, §2.5 H_n(t) = t^n).
inline double cos_pow(double t, double n) { return t > 0 ? std::pow(t, n) : 0.0; }

// Schlick's rational highlight H_n(t) = t / (n − n·t + t), eq. (2.13); 0 for t <= 0.
inline double schlick_highlight(double t, double n) { return t > 0 ? t / (n - n * t + t) : 0.0; }

// Blinn's geometric attenuation G = min{1, Gc, Gm}, eq. (3.1); cd = cos δ, ci/co = cos θi/θr,
// cb = cos β.
inline double g_blinn(double cd, double ci, double co, double cb) {
  return std::min(1.0, std::min(2.0 * cd * co / cb, 2.0 * cd * ci / cb));
}

// Schlick's approximation of Smith's G(θ), eq. (3.4): G = c / (c − k·c + k), k = sqrt(2m²/π).
inline double g_schlick(double c, double k) { return c / (c - k * c + k); }

// Beckmann's distribution as Cook and Torrance write it, eq. (3.6) (no 1/π: ∫ D cos δ dω = π).
inline double d_beckmann(double cd, double m) {
  const double c2 = cd * cd;
  const double tan2 = (1.0 - c2) / c2;
  return std::exp(-tan2 / (m * m)) / (m * m * c2 * c2);
}

// Schlick's rational approximation of (3.6), eq. (3.7): D = c² / (m c⁴ − r c⁴ + r)², r = 1/(2m).
// Like (3.6) it has D(0) = 1/m² and ∫ D cos δ dω = π.
inline double d_schlick(double cd, double m) {
  const double r = 1.0 / (2.0 * m);
  const double c2 = cd * cd, c4 = c2 * c2;
  const double q = m * c4 - r * c4 + r;
  return c2 / (q * q);
}

// Fresnel's equation for unpolarised light, complex index η + iκ, eq. (3.9); c = cos β = Θr·Θh.
// κ = 0 gives the dielectric form (3.10).
inline double fresnel(double c, double eta, double kappa) {
  c = std::clamp(c, 1e-12, 1.0);
  const double e2 = eta * eta, k2 = kappa * kappa;
  const double u = e2 - k2 + c * c - 1.0;
  const double s = std::sqrt(u * u + 4.0 * e2 * k2);
  const double a2 = 0.5 * (s + u), b2 = std::max(0.0, 0.5 * (s - u));
  const double a = std::sqrt(std::max(a2, 0.0));
  const double fs = ((a - c) * (a - c) + b2) / ((a + c) * (a + c) + b2);
  const double q = 1.0 / c;
  const double ratio = ((a + c - q) * (a + c - q) + b2) / ((a - c + q) * (a - c + q) + b2);
  return 0.5 * fs * (ratio + 1.0);
}

// F(0) of (3.9): ((η−1)² + κ²) / ((η+1)² + κ²). Eq. (3.11) prints {(η−1)/(η+1)} without the square;
// (3.12), its inverse, has it, so the square is meant.
inline double fresnel_f0(double eta, double kappa) {
  return ((eta - 1) * (eta - 1) + kappa * kappa) / ((eta + 1) * (eta + 1) + kappa * kappa);
}

// Schlick's Fresnel approximation, eq. (3.14) (and 4.18): f0 + (1 − f0)(1 − cos β)^5.
inline double fresnel_schlick(double c, double f0) {
  const double x = 1.0 - c, x2 = x * x;
  return f0 + (1.0 - f0) * x2 * x2 * x;
}

// ---------------------------------------------------------------------------------------------
// Chapter 2 — empirical models.

// Lambert, BRDF form eq. (2.5): f = kd/π (BSF form 2.4: S = kd cos θi).
struct Lambert {
  double kd = 0.8;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& n, const Vec3& = {}) const {
    if (dot(n, wi) <= 0 || dot(n, wo) <= 0) return 0.0;
    return kd / kPi;
  }
};

// Classical Phong, the BSF eq. (2.6): S = kd cos θi + ks cos^n α, α between Θr and Θs. As a BRDF
// (S / (π cos θi)): f = kd/π + ks cos^n α / (π cos θi). The thesis (after Lewis) says it is neither
// reciprocal nor energy-conserving; tests/test_brdf.cpp measures both.
struct PhongClassic {
  double kd = 0.4, ks = 0.4, n = 10;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& = {}) const {
    const double ci = dot(nn, wi), co = dot(nn, wo);
    if (ci <= 0 || co <= 0) return 0.0;
    const double ca = dot(wo, mirror(wi, nn));
    return kd / kPi + ks * cos_pow(ca, n) / (kPi * ci);
  }
};

// kd/π + ks (n+2)/(2π)·lobe() — the diffuse term and Phong's normalised lobe of (2.9) — or 0 when the
// light or the viewer is below the surface (lobe() is then not evaluated).
template <class Lobe>
inline double phong_normalised(double kd, double ks, double n, const Vec3& wi, const Vec3& wo, const Vec3& nn,
                               Lobe&& lobe) {
  const double ci = dot(nn, wi), co = dot(nn, wo);
  if (ci <= 0 || co <= 0) return 0.0;
  return kd / kPi + ks * (n + 2) / (2 * kPi) * lobe();
}

// Phong BRDF (Lafortune & Willems), eq. (2.7): f = kd/π + ks (n+2)/(2π) cos^n α, with kd + ks <= 1
// (eq. 2.8 prints "<= 0", a typo: with 0 the model would reflect nothing).
struct PhongBrdf {
  double kd = 0.4, ks = 0.4, n = 10;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& = {}) const {
    return phong_normalised(kd, ks, n, wi, wo, nn, [&] { return cos_pow(dot(wo, mirror(wi, nn)), n); });
  }
};

// Blinn-Phong BRDF, eq. (2.10): f = kd/π + ks (n+2)/(2π) cos^n δ, δ between Θh and N — the thesis
// keeps Phong's (n+2)/(2π) factor although the lobe is in cos δ (measured in docs/brdf.md).
struct BlinnPhong {
  double kd = 0.4, ks = 0.4, n = 10;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& = {}) const {
    return phong_normalised(kd, ks, n, wi, wo, nn, [&] { return cos_pow(dot(nn, normalize(wi + wo)), n); });
  }
};

// Schlick-Phong: Blinn's modification with Schlick's rational highlight (2.13) in place of cos^n δ —
// the combination §5.4 recommends ("Blinn's modification, to which Schlick's approximation of the
// highlight function can be applied"); normalisation as in (2.10).
struct SchlickPhong {
  double kd = 0.4, ks = 0.4, n = 10;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& = {}) const {
    return phong_normalised(kd, ks, n, wi, wo, nn, [&] { return schlick_highlight(dot(nn, normalize(wi + wo)), n); });
  }
};

// ---------------------------------------------------------------------------------------------
// Chapter 3 — models based on physics.

// Which constant divides F·D·G / (cos θi cos θr) in the specular term.
enum class Microfacet {
  Thesis,  // 1/π as eq. (3.17) (Cook & Torrance 1981) with D of (3.6)/(3.7), whose integral is π
  Unit,    // 1/(4π): D/π is a unit-area distribution and 1/4 the Jacobian of the half vector
};

// kd/π + ks·spec/π (ks·spec/(4π) with Microfacet::Unit) for spec(cos θi, cos θr, cos δ = N·Θh,
// cos β = Θr·Θh), the specular term of (3.17) — or 0 when the light or the viewer is below the surface.
template <class Spec>
inline double microfacet(double kd, double ks, Microfacet norm, const Vec3& wi, const Vec3& wo, const Vec3& nn,
                         Spec&& spec) {
  const double ci = dot(nn, wi), co = dot(nn, wo);
  if (ci <= 0 || co <= 0) return 0.0;
  const Vec3 h = normalize(wi + wo);
  return kd / kPi + ks * spec(ci, co, dot(nn, h), dot(wo, h)) / (norm == Microfacet::Thesis ? kPi : 4 * kPi);
}

// Cook-Torrance, eq. (3.15)-(3.17): f = kd/π + ks (1/π) F D G / (cos θi cos θr), D Beckmann (3.6),
// G Blinn (3.1), F Fresnel (3.9)/(3.10) at cos β = Θr·Θh, kd + ks <= 1.
struct CookTorrance {
  double kd = 0.4, ks = 0.4, m = 0.2, eta = 1.5, kappa = 0;
  Microfacet norm = Microfacet::Thesis;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& = {}) const {
    return microfacet(kd, ks, norm, wi, wo, nn, [&](double ci, double co, double cd, double cb) {
      return fresnel(cb, eta, kappa) * d_beckmann(cd, m) * g_blinn(cd, ci, co, cb) / (ci * co);
    });
  }
};

// Schlick-Cook-Torrance (§3.4, last paragraphs): (3.17) with F of (3.14), G(θi)G(θr) of (3.2)+(3.4)
// and D of (3.7). f0 is F(0) of the same η, κ as Cook-Torrance (fresnel_f0).
struct SchlickCookTorrance {
  double kd = 0.4, ks = 0.4, m = 0.2, f0 = 0.04;
  Microfacet norm = Microfacet::Thesis;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& = {}) const {
    return microfacet(kd, ks, norm, wi, wo, nn, [&](double ci, double co, double cd, double cb) {
      const double k = std::sqrt(2 * m * m / kPi);
      return fresnel_schlick(cb, f0) * d_schlick(cd, m) * g_schlick(ci, k) * g_schlick(co, k) / (ci * co);
    });
  }
};

// ---------------------------------------------------------------------------------------------
// Chapter 4 — hybrid models.

// Strauss, eq. (4.1)-(4.12), a BSF turned into a BRDF by dividing by π cos θi:
//   S = ρd da C cos θi + cos^h α · sa · cs
//   ρd = (1 − s³)(1 − t), da = 1 − e·s, h = 3/(1 − s), rn = (1 − t) − ρd,
//   sa = min(1, rn + (rn + kb) b), b = F(θi/(π/2)) G(θi/(π/2)) G(θr/(π/2)),
//   cs = 1 + e (1 − F(θi/(π/2))) (C − 1).
// Choices (docs/brdf.md): (4.2) omits the cos θi and the colour C its text names — both are put back as
// Strauss has them; (4.8) prints rn = (1 − t) − f_d, Strauss's is (1 − t) − ρd; (4.12) prints
// (1 + F), which would give cs = 2C − 1 (negative for dark metals) at grazing incidence, Strauss's is
// (1 − F) (metal highlights turn white at grazing incidence). s in [0, 1).
struct Strauss {
  double c = 1.0, s = 0.5, e = 0.0, t = 0.0;
  double kf = 1.12, kg = 1.01, kb = 0.1;
  double fx(double x) const {
    const double a = 1.0 / ((x - kf) * (x - kf)) - 1.0 / (kf * kf);
    const double b = 1.0 / ((1 - kf) * (1 - kf)) - 1.0 / (kf * kf);
    return a / b;  // eq. (4.10)
  }
  double gx(double x) const {
    const double a = 1.0 / ((1 - kg) * (1 - kg)) - 1.0 / ((x - kg) * (x - kg));
    const double b = 1.0 / ((1 - kg) * (1 - kg)) - 1.0 / (kg * kg);
    return a / b;  // eq. (4.11)
  }
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& = {}) const {
    const double ci = dot(nn, wi), co = dot(nn, wo);
    if (ci <= 0 || co <= 0) return 0.0;
    const double rho_d = (1 - s * s * s) * (1 - t);
    const double da = 1 - e * s;
    const double h = 3.0 / (1 - s);
    const double rn = (1 - t) - rho_d;
    const double xi = std::acos(std::min(ci, 1.0)) / (kPi / 2), xo = std::acos(std::min(co, 1.0)) / (kPi / 2);
    const double fi = fx(xi);
    const double b = fi * gx(xi) * gx(xo);
    const double sa = std::min(1.0, rn + (rn + kb) * b);
    const double cs = 1 + e * (1 - fi) * (c - 1);
    const double ca = dot(wo, mirror(wi, nn));
    const double bsf = rho_d * da * c * ci + cos_pow(ca, h) * sa * cs;
    return bsf / (kPi * ci);
  }
};

// Ward, anisotropic, eq. (4.14) (isotropic (4.13) is mx = my = m):
//   f = ρd/π + ρs exp(−tan²δ (cos²φ/mx² + sin²φ/my²)) / (4π mx my sqrt(cos θi cos θr)),
// evaluated as exp(−((h·X/mx)² + (h·Y/my)²)/(h·N)²) (identical, no trigonometry). (4.13) prints
// exp(−tan²δ/m); Ward's and (4.14)'s exponent has m², which is used.
struct Ward {
  double rho_d = 0.4, rho_s = 0.4, mx = 0.1, my = 0.1;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& t) const {
    const double ci = dot(nn, wi), co = dot(nn, wo);
    if (ci <= 0 || co <= 0) return 0.0;
    const Frame fr = make_frame(nn, t);
    const Vec3 h = wi + wo;
    const double hn = dot(h, nn), hx = dot(h, fr.x) / mx, hy = dot(h, fr.y) / my;
    const double e = std::exp(-(hx * hx + hy * hy) / (hn * hn));
    return rho_d / kPi + rho_s * e / (4 * kPi * mx * my * std::sqrt(ci * co));
  }
};

// Schlick's BRDF, eq. (4.16)-(4.23), SINGLE material (C, r, p), optionally a DOUBLE material with a
// second layer (C', r', p'):
//   SINGLE  f = S(u) D,                      DOUBLE  f = S(u) D + (1 − S(u)) S'(·) D'
//   S(u) = C + (1 − C)(1 − u)^5, u = cos β = Θr·Θh                                     (4.18)
//   D = (1 − G(θi)G(θr))/π + G(θi)G(θr) Z A / (4π cos θi cos θr)                       (4.22)
//   G(v) = v/(r − r v + v), Z = r/(1 + r t² − t²)², A = sqrt(p/(p² − p² w² + w²))    (4.20,4.21,4.23)
// Choices: Z's argument. (4.19)/(4.20) write Z(β), β between Θr and Θh; that peaks at Θr = Θi (a
// retro-reflector) and contradicts the microfacet derivation the text gives; Schlick's t is cos δ = h·N
// (then Z/π is a unit-area distribution), which is used. w = cos φ, φ the azimuth of h from X.
// In DOUBLE, (4.16) prints S'(θi); that reading is not reciprocal (measured by the tests), so the
// reciprocal S'(u) is the default and the literal reading is selectable.
struct SchlickLayer {
  double c = 0.5, r = 0.2, p = 1.0;
};
struct Schlick {
  SchlickLayer a{};
  bool double_layer = false;
  SchlickLayer b{0.5, 1.0, 1.0};
  bool literal_theta_i = false;  // DOUBLE only: S'(cos θi) as printed in (4.16) instead of S'(u)

  static double d_term(const SchlickLayer& L, double ci, double co, double t, double w) {
    const double gi = ci / (L.r - L.r * ci + ci), go = co / (L.r - L.r * co + co);
    const double t2 = t * t;
    const double q = 1 + L.r * t2 - t2;
    const double z = L.r / (q * q);
    const double w2 = w * w;
    const double a = std::sqrt(L.p / (L.p * L.p - L.p * L.p * w2 + w2));
    const double gg = gi * go;
    return (1 - gg) / kPi + gg * z * a / (4 * kPi * ci * co);
  }
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& tt) const {
    const double ci = dot(nn, wi), co = dot(nn, wo);
    if (ci <= 0 || co <= 0) return 0.0;
    const Frame fr = make_frame(nn, tt);
    const Vec3 h = normalize(wi + wo);
    const double t = dot(h, nn), u = dot(h, wo);
    const double hx = dot(h, fr.x), hy = dot(h, fr.y);
    const double hp = std::sqrt(hx * hx + hy * hy);
    const double w = hp > 0 ? hx / hp : 1.0;
    const double s = fresnel_schlick(u, a.c);
    double f = s * d_term(a, ci, co, t, w);
    if (double_layer) {
      const double s2 = fresnel_schlick(literal_theta_i ? ci : u, b.c);
      f += (1 - s) * s2 * d_term(b, ci, co, t, w);
    }
    return f;
  }
};

// Ashikhmin-Shirley, eq. (4.24)-(4.26):
//   fs = sqrt((nx+1)(ny+1))/(8π) · cos δ^(nx cos²φ + ny sin²φ) / (cos β · max(cos θi, cos θr)) · F(β)
//   fd = 28 Rd/(23π) (1 − Rs) [1 − (1 − cos θi/2)^5] [1 − (1 − cos θr/2)^5]
// F is Schlick's (3.14) with f0 = Rs. (4.25) writes the azimuth as ϕ (the symbol table 1.1 uses for
// the azimuths of Θi, Θr); Ashikhmin and Shirley's is the azimuth φ of Θh, which is used.
struct AshikhminShirley {
  double rd = 0.4, rs = 0.4, nx = 100, ny = 100;
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& t) const {
    const double ci = dot(nn, wi), co = dot(nn, wo);
    if (ci <= 0 || co <= 0) return 0.0;
    const Frame fr = make_frame(nn, t);
    const Vec3 h = normalize(wi + wo);
    const double hn = dot(h, nn), hx = dot(h, fr.x), hy = dot(h, fr.y), hk = dot(h, wo);
    const double s2 = hx * hx + hy * hy;
    const double ex = s2 > 0 ? (nx * hx * hx + ny * hy * hy) / s2 : 0.5 * (nx + ny);
    const double fs = std::sqrt((nx + 1) * (ny + 1)) / (8 * kPi) * std::pow(hn, ex) /
                      (hk * std::max(ci, co)) * fresnel_schlick(hk, rs);
    const auto p5 = [](double x) { const double x2 = x * x; return x2 * x2 * x; };
    const double fd = 28 * rd / (23 * kPi) * (1 - rs) * (1 - p5(1 - ci / 2)) * (1 - p5(1 - co / 2));
    return fd + fs;
  }
};

// Lafortune's generalised cosine lobes, eq. (4.30)/(4.32), plus a Lambert term kd/π:
//   f = kd/π + Σ_k max(0, Cx,k x_i x_o + Cy,k y_i y_o + Cz,k z_i z_o)^n_k
// in the local frame (X, Y, N). (4.30)'s ks is absorbed into the C's as in (4.32); a negative base
// gives 0 (the lobe is a power of a cosine). Phong's lobe ks (n+2)/(2π) cos^n α is −Cx = −Cy = Cz =
// (ks (n+2)/(2π))^(1/n) (see phong_lobe). (4.31) prints Θi,x Θr,x for the Cx = Cy = 0 case; with
// Cx = Cy = 0 only the z term is left, so Θi,z Θr,z is meant.
struct LafortuneLobe {
  double cx = 0, cy = 0, cz = 0, n = 1;
};
struct Lafortune {
  double kd = 0.4;
  std::array<LafortuneLobe, 3> lobe{};
  int lobes = 0;
  static LafortuneLobe phong_lobe(double ks, double n) {
    const double c = std::pow(ks * (n + 2) / (2 * kPi), 1.0 / n);
    return {-c, -c, c, n};
  }
  double operator()(const Vec3& wi, const Vec3& wo, const Vec3& nn, const Vec3& t) const {
    const double ci = dot(nn, wi), co = dot(nn, wo);
    if (ci <= 0 || co <= 0) return 0.0;
    const Frame fr = make_frame(nn, t);
    const double xx = dot(wi, fr.x) * dot(wo, fr.x), yy = dot(wi, fr.y) * dot(wo, fr.y), zz = ci * co;
    double f = kd / kPi;
    for (int k = 0; k < lobes; ++k) {
      const LafortuneLobe& L = lobe[static_cast<size_t>(k)];
      const double base = L.cx * xx + L.cy * yy + L.cz * zz;
      if (base > 0) f += std::pow(base, L.n);
    }
    return f;
  }
};

// ---------------------------------------------------------------------------------------------
// Table 5.1 checks (cmodel/src/analysis/brdf.cpp).

using Fn = std::function<double(const Vec3& wi, const Vec3& wo, const Vec3& n, const Vec3& t)>;

// One model with one parameter set.
struct Instance {
  std::string model;   // e.g. "Cook-Torrance"
  std::string params;  // e.g. "kd=0.4 ks=0.4 m=0.2 eta=1.5"
  bool anisotropic = false;
  Fn f;
};

// The models of the thesis in the order of its tables, each over the parameter grid the checks use
// (the thesis's figure parameters and the extremes its constraints allow). `model` selects one name
// (as in Instance::model); empty = all.
std::vector<Instance> parameter_grid(const std::string& model = "");
std::vector<std::string> model_names();

// Directional albedo a(θi, φi) = ∫_Ω f(ωi, ωo) cos θo dωo over the hemisphere, N = (0,0,1),
// tangent (1,0,0), by nested adaptive Gauss-Kronrod (shadecore/analysis/quadrature.hpp) over θo and φo with
// break points at the mirror direction. (Eq. 1.14 integrates over the other direction; for a
// reciprocal BRDF both are equal, for a non-reciprocal one this is the physical energy balance:
// the power reflected of light arriving from ωi.)
struct Albedo {
  double value = 0;
  double error = 0;  // quadrature error estimate (sum of the outer and inner |K15 − G7|)
  bool converged = false;
};
Albedo directional_albedo(const Fn& f, double theta_i, double phi_i, double rel_tol = 1e-7);

// Reciprocity over `pairs` random direction pairs in the upper hemisphere (fixed seed):
// the largest |f(a,b) − f(b,a)| / max(|f(a,b)|, |f(b,a)|) and the pair where it occurs.
struct Reciprocity {
  double max_rel = 0;
  Vec3 wi, wo;
  double f_io = 0, f_oi = 0;
};
Reciprocity reciprocity(const Fn& f, int pairs = 4000, unsigned long long seed = 13);

// Energy over the incidence grid θi ∈ {0, 30, 60, 75, 85, 89, 89.9, 89.99, 89.999}°, φi ∈ {30°} (anisotropic: also
// 0° and 90°): the largest albedo and where.
struct Energy {
  double max_albedo = 0, error = 0;
  double theta_i = 0, phi_i = 0;  // radians, where the maximum is
  bool converged = true;
};
Energy energy(const Instance& inst);
std::vector<double> energy_thetas_deg();

}  // namespace shadecore::brdf

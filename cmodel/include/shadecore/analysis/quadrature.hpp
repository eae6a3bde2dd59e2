// SPDX-License-Identifier: Apache-2.0
// shadecore — adaptive Gauss–Kronrod quadrature (G7/K15), written here (no extra dependency).
//
// Globally adaptive: the interval with the largest error estimate is bisected until the sum of the
// estimates is <= max(abs_tol, rel_tol·|I|) or max_intervals is reached. The error estimate of one
// interval is |K15 − G7| (the plain, conservative estimate; QUADPACK's (200·|K15−G7|)^1.5 scaling is
// not used). Templated on the real type so the references can run in long double.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <queue>
#include <vector>

namespace shadecore {

template <class Real>
struct QuadResult {
  Real value = 0;
  Real error = 0;          // sum of |K15 − G7| over the final intervals
  std::size_t evals = 0;   // integrand evaluations
  std::size_t intervals = 0;
  bool converged = false;
};

namespace detail {
// Nodes and weights of the 15-point Kronrod rule and its embedded 7-point Gauss rule on [−1, 1]
// (QUADPACK qk15 constants).
inline constexpr long double kXgk[8] = {
    0.991455371120812639206854697526329L, 0.949107912342758524526189684047851L,
    0.864864423359769072789712788640926L, 0.741531185599394439863864773280788L,
    0.586087235467691130294144845693013L, 0.405845151377397166906606412076961L,
    0.207784955007898467600689403773245L, 0.000000000000000000000000000000000L};
inline constexpr long double kWgk[8] = {
    0.022935322010529224963732008058970L, 0.063092092629978553290700663189204L,
    0.104790010322250183839876322541518L, 0.140653259715525918745189590510238L,
    0.169004726639267902826583426598550L, 0.190350578064785409913256402421014L,
    0.204432940075298892414161999234649L, 0.209482141084727828012999174891714L};
inline constexpr long double kWg[4] = {
    0.129484966168869693270611432679082L, 0.279705391489276667901467771423780L,
    0.381830050505118944950369775488975L, 0.417959183673469387755102040816327L};

template <class Real, class F>
void gk15(F& f, Real a, Real b, Real& k15, Real& err) {
  const Real c = (a + b) / 2, h = (b - a) / 2;
  const Real fc = f(c);
  Real rk = fc * Real(kWgk[7]), rg = fc * Real(kWg[3]);
  for (int j = 0; j < 7; ++j) {
    const Real dx = h * Real(kXgk[j]);
    const Real s = f(c - dx) + f(c + dx);
    rk += Real(kWgk[j]) * s;
    if (j % 2 == 1) rg += Real(kWg[j / 2]) * s;
  }
  k15 = rk * h;
  err = std::fabs((rk - rg) * h);
}
}  // namespace detail

// ∫_a^b f(x) dx. f is called as f(Real).
template <class Real, class F>
QuadResult<Real> integrate(F f, Real a, Real b, Real abs_tol, Real rel_tol, std::size_t max_intervals = 4000) {
  struct Piece {
    Real a, b, v, e;
    bool operator<(const Piece& o) const { return e < o.e; }
  };
  QuadResult<Real> r;
  std::priority_queue<Piece> q;
  Piece p0{a, b, 0, 0};
  detail::gk15<Real>(f, a, b, p0.v, p0.e);
  r.evals = 15;
  q.push(p0);
  Real total = p0.v, err = p0.e;
  while (true) {
    if (err <= std::max(abs_tol, rel_tol * std::fabs(total))) { r.converged = true; break; }
    if (q.size() >= max_intervals) break;
    const Piece p = q.top();
    q.pop();
    const Real m = (p.a + p.b) / 2;
    Piece l{p.a, m, 0, 0}, u{m, p.b, 0, 0};
    detail::gk15<Real>(f, l.a, l.b, l.v, l.e);
    detail::gk15<Real>(f, u.a, u.b, u.v, u.e);
    r.evals += 30;
    total += l.v + u.v - p.v;
    err += l.e + u.e - p.e;
    q.push(l);
    q.push(u);
  }
  // Re-sum to remove the drift of the running updates.
  total = 0;
  err = 0;
  r.intervals = q.size();
  while (!q.empty()) { total += q.top().v; err += q.top().e; q.pop(); }
  r.value = total;
  r.error = err;
  return r;
}

}  // namespace shadecore

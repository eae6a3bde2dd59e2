// SPDX-License-Identifier: Apache-2.0
// shadecore — double-precision golden references (not bit-accurate; the yardstick the
// fixed-point model is measured against). See docs/spec.md §5.
#pragma once

#include <cmath>

namespace shadecore::golden {

// Phong's highlight cos^n θ for c = cos θ in [0, 1].
inline double cos_pow(double c, int n) { return std::pow(c, n); }

// θcr(n) = 6/√n, the paper's cut-off angle.
inline double theta_cr(int n) { return 6.0 / std::sqrt(static_cast<double>(n)); }

// The base (n/16)(c − 1) + 1 of cs16.
inline double cs16_base(double c, int n) { return (n / 16.0) * (c - 1.0) + 1.0; }

inline double pow16(double b) {
  const double b2 = b * b, b4 = b2 * b2, b8 = b4 * b4;
  return b8 * b8;
}

// cs16 with the paper's θcr cut-off: zero for θ > 6/√n, i.e. for c < cos(6/√n).
inline double cs16_theta_cr(double c, int n) {
  if (c < std::cos(theta_cr(n))) return 0.0;
  return pow16(cs16_base(c, n));
}

// cs16 with the sign clamp: zero where the base is <= 0.
inline double cs16_sign_clamp(double c, int n) {
  const double b = cs16_base(c, n);
  return b <= 0.0 ? 0.0 : pow16(b);
}

// Schlick's rational highlight S(t, n) = t / (n − n·t + t), t = cos θ in [0, 1].
inline double schlick(double t, int n) { return t / (n - n * t + t); }

}  // namespace shadecore::golden

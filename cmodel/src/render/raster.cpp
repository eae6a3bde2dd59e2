// SPDX-License-Identifier: Apache-2.0
// shadecore — the host rasteriser (see shadecore/render/raster.hpp for the rules).
#include "shadecore/render/raster.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace shadecore::raster {

i128 floor_div(i128 a, i128 b) {
  i128 q = a / b;
  if ((a % b != 0) && (a < 0)) --q;
  return q;
}

int64_t interpolate(const Weights& w, const std::array<int64_t, 3>& a) {
  const i128 num = w.w[0] * a[0] + w.w[1] * a[1] + w.w[2] * a[2];
  return static_cast<int64_t>(floor_div(2 * num + w.sum, 2 * w.sum));
}

double interpolate(const Weights& w, const std::array<double, 3>& a) {
  const double s = static_cast<double>(w.sum);
  return (static_cast<double>(w.w[0]) * a[0] + static_cast<double>(w.w[1]) * a[1] + static_cast<double>(w.w[2]) * a[2]) / s;
}

Rasterizer::Rasterizer(int width, int height, double near)
    : w_(width), h_(height), near_(near),
      id_(static_cast<size_t>(width) * height, -1),
      depth_(static_cast<size_t>(width) * height, kDepthMax),
      cover_(static_cast<size_t>(width) * height, 0) {
  if (width < 1 || height < 1 || width > 4096 || height > 4096) throw std::invalid_argument("image size out of range");
}

namespace {

struct CV {
  ClipVertex c;
  std::array<double, 3> b;
};

// Signed distances to the clip planes (>= 0 inside).
inline double plane_dist(int p, const ClipVertex& v, double near) {
  switch (p) {
    case 0: return v.w - near;
    case 1: return kGuard * v.w - v.x;
    case 2: return kGuard * v.w + v.x;
    case 3: return kGuard * v.w - v.y;
    default: return kGuard * v.w + v.y;
  }
}

inline bool coord_less(const ClipVertex& a, const ClipVertex& b) {
  return std::tie(a.x, a.y, a.z, a.w) < std::tie(b.x, b.y, b.z, b.w);
}

// Point on the edge (a, b) where the plane distance is 0, from the canonically ordered edge.
CV intersect(const CV& a0, const CV& b0, int p, double near) {
  const bool swap = coord_less(b0.c, a0.c);
  const CV& a = swap ? b0 : a0;
  const CV& b = swap ? a0 : b0;
  const double da = plane_dist(p, a.c, near), db = plane_dist(p, b.c, near);
  const double t = da / (da - db);
  CV r;
  r.c.x = a.c.x + t * (b.c.x - a.c.x);
  r.c.y = a.c.y + t * (b.c.y - a.c.y);
  r.c.z = a.c.z + t * (b.c.z - a.c.z);
  r.c.w = a.c.w + t * (b.c.w - a.c.w);
  for (int k = 0; k < 3; ++k) r.b[k] = a.b[k] + t * (b.b[k] - a.b[k]);
  return r;
}

inline bool top_left(const ScreenVertex& a, const ScreenVertex& b) {
  const int64_t dy = b.Y - a.Y, dx = b.X - a.X;
  return dy < 0 || (dy == 0 && dx > 0);
}

inline int64_t edge(const ScreenVertex& a, const ScreenVertex& b, int64_t px, int64_t py) {
  return (b.X - a.X) * (py - a.Y) - (b.Y - a.Y) * (px - a.X);
}

// The same over the unsnapped positions (2^−kFineBits pixel; up to 2^31 inside the guard band: 128-bit products).
inline i128 fine_edge(const ScreenVertex& a, const ScreenVertex& b, int64_t px, int64_t py) {
  return static_cast<i128>(b.fx - a.fx) * (py - a.fy) - static_cast<i128>(b.fy - a.fy) * (px - a.fx);
}

}  // namespace

void Rasterizer::draw(int source, const std::array<ClipVertex, 3>& v) {
  std::vector<CV> poly = {{v[0], {1, 0, 0}}, {v[1], {0, 1, 0}}, {v[2], {0, 0, 1}}};
  for (int p = 0; p < 5; ++p) {
    bool all_in = true, all_out = true;
    for (const auto& cv : poly) {
      const bool in = plane_dist(p, cv.c, near_) >= 0;
      all_in = all_in && in;
      all_out = all_out && !in;
    }
    if (all_out) return;
    if (all_in) continue;
    std::vector<CV> out;
    for (size_t i = 0; i < poly.size(); ++i) {
      const CV& a = poly[i];
      const CV& b = poly[(i + 1) % poly.size()];
      const bool ain = plane_dist(p, a.c, near_) >= 0, bin = plane_dist(p, b.c, near_) >= 0;
      if (ain) out.push_back(a);
      if (ain != bin) out.push_back(intersect(a, b, p, near_));
    }
    poly.swap(out);
    if (poly.size() < 3) return;
  }
  std::vector<ScreenVertex> sv;
  for (const auto& cv : poly) {
    ScreenVertex s;
    s.b = cv.b;
    const double iw = 1.0 / cv.c.w;
    const double wx = (cv.c.x * iw * 0.5 + 0.5) * w_, wy = (0.5 - cv.c.y * iw * 0.5) * h_, wz = cv.c.z * iw * 0.5 + 0.5;
    s.X = std::llround(std::ldexp(wx, kSubBits));
    s.Y = std::llround(std::ldexp(wy, kSubBits));
    s.z = std::llround(std::ldexp(wz, kDepthBits));
    if (unsnapped_depth_) {
      s.fx = std::llround(std::ldexp(wx, kFineBits));
      s.fy = std::llround(std::ldexp(wy, kFineBits));
      s.fz = std::llround(std::ldexp(wz, kDepthBits + kFineBits));
      s.fine = true;
    }
    s.q = std::llround(std::ldexp(near_ * iw, 32));
    if (s.q < 1) s.q = 1;
    sv.push_back(s);
  }
  for (size_t i = 1; i + 1 < sv.size(); ++i) draw_screen(source, {sv[0], sv[i], sv[i + 1]});
}

int Rasterizer::draw_screen(int source, const std::array<ScreenVertex, 3>& v) {
  ScreenTri t;
  t.source = source;
  t.v = v;
  t.area = edge(t.v[0], t.v[1], t.v[2].X, t.v[2].Y);
  if (t.area == 0) return 0;
  t.back = t.area > 0;  // y down: a positive area is clockwise in GL's y-up window, a back face (GL_CCW front)
  if (t.area < 0) {
    std::swap(t.v[1], t.v[2]);
    t.area = -t.area;
  }
  const int index = static_cast<int>(tris_.size());
  tris_.push_back(t);
  const int n = raster(t, index);
  if (n == 0) tris_.pop_back();
  return n;
}

int Rasterizer::raster(const ScreenTri& t, int index) {
  const auto& a = t.v[0];
  const auto& b = t.v[1];
  const auto& c = t.v[2];
  const int64_t half = int64_t{1} << (kSubBits - 1), one = int64_t{1} << kSubBits;
  const int64_t minX = std::min({a.X, b.X, c.X}), maxX = std::max({a.X, b.X, c.X});
  const int64_t minY = std::min({a.Y, b.Y, c.Y}), maxY = std::max({a.Y, b.Y, c.Y});
  // Pixel x has its centre at x·256 + 128: x from ⌈(minX − 128)/256⌉ to ⌊(maxX − 128)/256⌋.
  auto lo = [&](int64_t m) { return static_cast<int64_t>(-floor_div(-(m - half), one)); };
  auto hi = [&](int64_t m) { return static_cast<int64_t>(floor_div(m - half, one)); };
  const int64_t x0 = std::max<int64_t>(0, lo(minX)), x1 = std::min<int64_t>(w_ - 1, hi(maxX));
  const int64_t y0 = std::max<int64_t>(0, lo(minY)), y1 = std::min<int64_t>(h_ - 1, hi(maxY));
  // Bias: a pixel centre exactly on an edge counts only for top and left edges.
  const int64_t bias0 = top_left(b, c) ? 0 : -1, bias1 = top_left(c, a) ? 0 : -1, bias2 = top_left(a, b) ? 0 : -1;
  // The depth plane through the unsnapped vertices (the snapped ones' when they are not given, or when snapping
  // made a sliver of the other winding or of no area): z = ⌊Σ λ'_k fz_k / (A' · 2^kFineBits)⌋.
  const int64_t fhalf = int64_t{1} << (kFineBits - 1), fone = int64_t{1} << kFineBits;
  const i128 farea = a.fine && b.fine && c.fine ? fine_edge(a, b, c.fx, c.fy) : 0;
  const bool fine = farea > 0;
  const i128 fden = farea * fone;
  int covered = 0;
  for (int64_t y = y0; y <= y1; ++y) {
    const int64_t py = y * one + half;
    for (int64_t x = x0; x <= x1; ++x) {
      const int64_t px = x * one + half;
      const int64_t l0 = edge(b, c, px, py), l1 = edge(c, a, px, py), l2 = edge(a, b, px, py);
      if (l0 + bias0 < 0 || l1 + bias1 < 0 || l2 + bias2 < 0) continue;
      const size_t pix = static_cast<size_t>(y) * w_ + x;
      ++cover_[pix];
      ++covered;
      int64_t z;
      if (fine) {
        const int64_t fx = x * fone + fhalf, fy = y * fone + fhalf;
        const i128 zn = fine_edge(b, c, fx, fy) * a.fz + fine_edge(c, a, fx, fy) * b.fz + fine_edge(a, b, fx, fy) * c.fz;
        z = static_cast<int64_t>(floor_div(zn, fden));
      } else {
        const i128 zn = static_cast<i128>(l0) * a.z + static_cast<i128>(l1) * b.z + static_cast<i128>(l2) * c.z;
        z = static_cast<int64_t>(floor_div(zn, t.area));
      }
      if (depth_test_) {
        if (z < 0 || z >= depth_[pix]) continue;  // in front of the near plane (rounding), GL_LESS
        if (depth_write_) depth_[pix] = z;        // glDepthMask(GL_FALSE): tested, not written
      }
      // depth test off: the fragment is written whatever its depth, and the depth buffer is not updated (OpenGL 2.1
      // §4.1.5); a later triangle overwrites it (drawing order)
      id_[pix] = index;
    }
  }
  return covered;
}

void Rasterizer::compact() {
  std::vector<int32_t> remap(tris_.size(), -1);
  for (int32_t id : id_)
    if (id >= 0) remap[static_cast<size_t>(id)] = 0;
  size_t k = 0;
  for (size_t i = 0; i < tris_.size(); ++i) {
    if (remap[i] < 0) continue;
    remap[i] = static_cast<int32_t>(k);
    if (k != i) tris_[k] = tris_[i];
    ++k;
  }
  tris_.resize(k);
  tris_.shrink_to_fit();
  for (int32_t& id : id_)
    if (id >= 0) id = remap[static_cast<size_t>(id)];
}

Weights Rasterizer::weights(int ti, int x, int y) const {
  const ScreenTri& t = tris_.at(static_cast<size_t>(ti));
  const int64_t half = int64_t{1} << (kSubBits - 1), one = int64_t{1} << kSubBits;
  const int64_t px = int64_t{x} * one + half, py = int64_t{y} * one + half;
  const int64_t l[3] = {edge(t.v[1], t.v[2], px, py), edge(t.v[2], t.v[0], px, py), edge(t.v[0], t.v[1], px, py)};
  Weights w;
  for (int k = 0; k < 3; ++k) {
    w.w[k] = static_cast<i128>(l[k]) * t.v[k].q;
    w.sum += w.w[k];
  }
  return w;
}

}  // namespace shadecore::raster

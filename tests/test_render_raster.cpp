// SPDX-License-Identifier: Apache-2.0
// shadecore — tests of the host rasteriser (shadecore/render/raster.hpp): top-left fill rule (shared edges and
// vertices covered exactly once), z-buffer, perspective-correct interpolation, near-plane clipping.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "shadecore/render/raster.hpp"

namespace {

using shadecore::raster::ClipVertex;
using shadecore::raster::i128;
using shadecore::raster::Rasterizer;
using shadecore::raster::ScreenVertex;

ScreenVertex sv(int64_t X, int64_t Y, int64_t z = 1000, int64_t q = int64_t{1} << 32) {
  ScreenVertex v;
  v.X = X, v.Y = Y, v.z = z, v.q = q;
  v.b = {1, 0, 0};
  return v;
}

// A W×H grid of jittered points tiled by triangles (each cell split along a random diagonal): every pixel
// centre strictly inside the outer boundary must be covered exactly once. Grid points are snapped to
// multiples of 64 (a quarter pixel) so many edges and vertices pass exactly through pixel centres.
TEST(RenderRaster, SharedEdgesCoveredExactlyOnce) {
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    const int W = 40, H = 32, N = 6;
    Rasterizer r(W, H, 1.0);
    const int64_t cell = (W - 8) * 256 / N / 64 * 64, cellh = (H - 8) * 256 / N / 64 * 64;
    std::vector<std::vector<std::pair<int64_t, int64_t>>> p(N + 1, std::vector<std::pair<int64_t, int64_t>>(N + 1));
    std::uniform_int_distribution<int> jit(-3, 3);  // ≤ 0.75 px in cells of ≥ 4 px: every cell stays convex
    for (int i = 0; i <= N; ++i)
      for (int j = 0; j <= N; ++j) {
        int64_t X = 4 * 256 + j * cell, Y = 4 * 256 + i * cellh;
        if (i > 0 && i < N && j > 0 && j < N) X += 64 * jit(rng), Y += 64 * jit(rng);
        p[i][j] = {X, Y};
      }
    int id = 0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        const auto a = sv(p[i][j].first, p[i][j].second), b = sv(p[i][j + 1].first, p[i][j + 1].second);
        const auto c = sv(p[i + 1][j + 1].first, p[i + 1][j + 1].second), d = sv(p[i + 1][j].first, p[i + 1][j].second);
        if (rng() & 1) {
          r.draw_screen(id++, {a, b, c});
          r.draw_screen(id++, {a, c, d});
        } else {
          r.draw_screen(id++, {a, b, d});
          r.draw_screen(id++, {b, d, c});  // the other orientation too
        }
      }
    // The outer boundary is axis-aligned from 4·256 to 4·256 + N·cell: pixel centres x·256+128 in [lo, hi)
    // are inside (top-left: the left/top boundary is included, the right/bottom excluded).
    const int64_t x_lo = 4 * 256, x_hi = 4 * 256 + N * cell, y_lo = 4 * 256, y_hi = 4 * 256 + N * cellh;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const int64_t px = x * 256 + 128, py = y * 256 + 128;
        const bool inside = px >= x_lo && px < x_hi && py >= y_lo && py < y_hi;
        ASSERT_EQ(r.coverage()[y * W + x], inside ? 1u : 0u) << "seed " << seed << " pixel " << x << "," << y;
      }
  }
}

// A fan of triangles around a vertex that sits exactly on a pixel centre: that pixel once, no gaps.
TEST(RenderRaster, FanAroundPixelCentreCoveredOnce) {
  const int W = 16, H = 16;
  for (int n = 3; n <= 12; ++n) {
    Rasterizer r(W, H, 1.0);
    const int64_t cx = 8 * 256 + 128, cy = 8 * 256 + 128;
    std::vector<std::pair<int64_t, int64_t>> ring;
    for (int k = 0; k < n; ++k) {
      const double a = 2 * 3.14159265358979 * k / n + 0.1;
      ring.push_back({cx + std::llround(1500 * std::cos(a)), cy + std::llround(1500 * std::sin(a))});
    }
    for (int k = 0; k < n; ++k)
      r.draw_screen(k, {sv(cx, cy), sv(ring[k].first, ring[k].second), sv(ring[(k + 1) % n].first, ring[(k + 1) % n].second)});
    EXPECT_EQ(r.coverage()[8 * W + 8], 1u) << n << " triangles";
    for (uint32_t c : r.coverage()) EXPECT_LE(c, 1u);
  }
}

// The rule itself: a pixel centre on a top edge or a left edge is in, on a bottom or right edge is out.
TEST(RenderRaster, TopLeftRule) {
  // Square with corners exactly on pixel centres (2,2)..(5,5): covers x, y in [2, 5) only.
  Rasterizer r(8, 8, 1.0);
  const auto a = sv(2 * 256 + 128, 2 * 256 + 128), b = sv(5 * 256 + 128, 2 * 256 + 128);
  const auto c = sv(5 * 256 + 128, 5 * 256 + 128), d = sv(2 * 256 + 128, 5 * 256 + 128);
  r.draw_screen(0, {a, b, c});
  r.draw_screen(1, {a, c, d});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(r.coverage()[y * 8 + x], (x >= 2 && x < 5 && y >= 2 && y < 5) ? 1u : 0u) << x << "," << y;
  // Degenerate (zero-area) triangles cover nothing.
  Rasterizer z(8, 8, 1.0);
  EXPECT_EQ(z.draw_screen(0, {a, b, sv(8 * 256 + 128, 2 * 256 + 128)}), 0);
}

TEST(RenderRaster, DepthTestNearestWinsFirstWinsTies) {
  for (int order = 0; order < 2; ++order) {
    Rasterizer r(10, 10, 1.0);
    const auto t_near = std::array<ScreenVertex, 3>{sv(0, 0, 100), sv(2560, 0, 100), sv(0, 2560, 100)};
    const auto t_far = std::array<ScreenVertex, 3>{sv(0, 0, 200), sv(2560, 0, 200), sv(0, 2560, 200)};
    if (order == 0) r.draw_screen(7, t_near), r.draw_screen(8, t_far);
    else r.draw_screen(8, t_far), r.draw_screen(7, t_near);
    const int id = r.at(1, 1);
    ASSERT_GE(id, 0);
    EXPECT_EQ(r.tris()[id].source, 7);
    EXPECT_EQ(r.depth(1, 1), 100);
  }
  Rasterizer r(10, 10, 1.0);
  const auto t = std::array<ScreenVertex, 3>{sv(0, 0, 100), sv(2560, 0, 100), sv(0, 2560, 100)};
  r.draw_screen(1, t);
  r.draw_screen(2, t);  // equal depth: GL_LESS keeps the first
  EXPECT_EQ(r.tris()[r.at(1, 1)].source, 1);
  // Depth is interpolated screen-linearly: a sloped triangle, the nearer part wins against a flat one.
  Rasterizer s(10, 10, 1.0);
  s.draw_screen(1, {sv(0, 0, 0), sv(2560, 0, 1000), sv(0, 2560, 0)});
  s.draw_screen(2, {sv(0, 0, 500), sv(2560, 0, 500), sv(0, 2560, 500)});
  EXPECT_EQ(s.tris()[s.at(0, 4)].source, 1);  // depth ≈ 50 there
  EXPECT_EQ(s.tris()[s.at(8, 0)].source, 2);  // depth ≈ 850 for triangle 1
}

// GL's depth state per draw (set_depth_state): GL_DEPTH_TEST off writes the pixels in drawing order whatever their depth
// and leaves the depth buffer alone (OpenGL 2.1 §4.1.5); glDepthMask(GL_FALSE) tests without writing.
TEST(RenderRaster, DepthTestOffAndDepthMaskFollowDrawingOrder) {
  const auto tri = [](int64_t z) { return std::array<ScreenVertex, 3>{sv(0, 0, z), sv(2560, 0, z), sv(0, 2560, z)}; };
  {
    Rasterizer r(10, 10, 1.0);
    r.draw_screen(1, tri(100));  // near, test and write
    r.set_depth_state(false, false);
    r.draw_screen(2, tri(300));  // farther, test off: drawn over
    EXPECT_EQ(r.tris()[r.at(1, 1)].source, 2);
    EXPECT_EQ(r.depth(1, 1), 100);  // not written
    r.set_depth_state(true, true);
    r.draw_screen(3, tri(200));  // fails against 100 (had 2 written 300, it would pass)
    EXPECT_EQ(r.tris()[r.at(1, 1)].source, 2);
    r.draw_screen(4, tri(50));  // passes
    EXPECT_EQ(r.tris()[r.at(1, 1)].source, 4);
    EXPECT_EQ(r.depth(1, 1), 50);
  }
  {
    Rasterizer r(10, 10, 1.0);
    r.set_depth_state(true, false);
    r.draw_screen(1, tri(100));  // near, tested against the cleared buffer, depth not written
    EXPECT_EQ(r.tris()[r.at(1, 1)].source, 1);
    EXPECT_EQ(r.depth(1, 1), shadecore::raster::kDepthMax);
    r.set_depth_state(true, true);
    r.draw_screen(2, tri(300));  // farther, but the buffer is still at the far plane: drawn over
    EXPECT_EQ(r.tris()[r.at(1, 1)].source, 2);
    EXPECT_EQ(r.depth(1, 1), 300);
    r.set_depth_state(true, false);
    r.draw_screen(3, tri(400));  // the mask off still tests: fails against 300
    EXPECT_EQ(r.tris()[r.at(1, 1)].source, 2);
  }
}

// set_unsnapped_depth (shadecore replay, docs/replay.md): the depth plane through the unsnapped window positions.
// A flat triangle at window z = 0.5 drawn first, then sloped ones crossing it: wherever their exact depths at a
// pixel centre (from the unsnapped positions, in double) differ by more than 1 LSB of 2^-24, the nearer one is
// shown. The snapped plane (the default, scene files) gets some of those pixels wrong: vertex snapping to 1/256
// pixel moves a sloped plane by many LSBs; both modes cover the same pixels.
TEST(RenderRaster, UnsnappedDepthOrdersCrossingSurfacesToOneLsb) {
  const int W = 48, H = 48;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-0.95, 0.95), dz(-0.02, 0.02);
  int wrong[2] = {0, 0}, decided = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::array<ClipVertex, 3> b;
    for (auto& v : b) v = ClipVertex{pos(rng), pos(rng), dz(rng), 1.0};  // orthographic: w = 1, window z = 0.5 + z/2
    const std::array<ClipVertex, 3> a = {ClipVertex{-1, -1, 0, 1}, ClipVertex{1, -1, 0, 1}, ClipVertex{-1, 1, 0, 1}};
    Rasterizer r[2] = {Rasterizer(W, H, 1.0), Rasterizer(W, H, 1.0)};
    r[1].set_unsnapped_depth(true);
    for (auto& ri : r) ri.draw(1, a), ri.draw(2, b);
    EXPECT_EQ(r[0].coverage(), r[1].coverage());
    // exact window depth of b at a pixel centre, from its unsnapped window positions
    double wx[3], wy[3], wz[3];
    for (int k = 0; k < 3; ++k)
      wx[k] = (b[k].x * 0.5 + 0.5) * W, wy[k] = (0.5 - b[k].y * 0.5) * H, wz[k] = b[k].z * 0.5 + 0.5;
    const double area = (wx[1] - wx[0]) * (wy[2] - wy[0]) - (wy[1] - wy[0]) * (wx[2] - wx[0]);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        if (r[0].coverage()[y * W + x] < 2) continue;  // only a: no crossing here
        const double px = x + 0.5, py = y + 0.5;
        const double l0 = (wx[2] - wx[1]) * (py - wy[1]) - (wy[2] - wy[1]) * (px - wx[1]);
        const double l1 = (wx[0] - wx[2]) * (py - wy[2]) - (wy[0] - wy[2]) * (px - wx[2]);
        const double zb = (l0 * wz[0] + l1 * wz[1] + (area - l0 - l1) * wz[2]) / area;
        const double sep = std::ldexp(zb - 0.5, 24);  // LSBs; > 0: a (drawn first) is nearer
        if (std::fabs(sep) <= 1) continue;
        ++decided;
        for (int m = 0; m < 2; ++m) {
          const int shown = r[m].tris()[static_cast<size_t>(r[m].at(x, y))].source;
          if (shown != (sep > 0 ? 1 : 2)) ++wrong[m];
        }
      }
  }
  EXPECT_GT(decided, 100000);
  EXPECT_EQ(wrong[1], 0) << "unsnapped depth plane";
  EXPECT_GT(wrong[0], 0) << "the snapped plane was expected to misorder some pixel (else this test shows nothing)";
}

// Perspective-correct weights: Σ ω_k a_k / Σ ω_k equals the double formula Σ (λ_k/w_k) a_k / Σ (λ_k/w_k).
TEST(RenderRaster, PerspectiveCorrectInterpolation) {
  Rasterizer r(64, 64, 1.0);
  std::array<ClipVertex, 3> v = {ClipVertex{-0.9, -0.9, 0.5, 1.0}, ClipVertex{4.0, -4.0, 6.0, 8.0},
                                 ClipVertex{-1.5, 2.5, 2.0, 3.0}};
  r.draw(0, v);
  ASSERT_FALSE(r.tris().empty());
  const auto& t = r.tris()[0];
  const std::array<int64_t, 3> a = {1000, -70000, 123456};
  int checked = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      if (r.at(x, y) != 0) continue;
      const auto w = r.weights(0, x, y);
      const int64_t got = shadecore::raster::interpolate(w, a);
      double num = 0, den = 0;
      for (int k = 0; k < 3; ++k) {
        const double lam = static_cast<double>(w.w[k]) / static_cast<double>(t.v[k].q);
        const double ik = std::ldexp(static_cast<double>(t.v[k].q), -32);  // near / w
        num += lam * ik * a[k];
        den += lam * ik;
      }
      EXPECT_NEAR(static_cast<double>(got), num / den, 0.5 + 1e-6) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 100);
  // Equal w: plain (affine) barycentric interpolation; a constant attribute is reproduced exactly.
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (r.at(x, y) == 0) {
        EXPECT_EQ(shadecore::raster::interpolate(r.weights(0, x, y), std::array<int64_t, 3>{777, 777, 777}), 777);
      }
}

// Two triangles sharing an edge that crosses the near plane: both clip it at the same point, so the
// shared edge is still covered exactly once; nothing behind the near plane is drawn.
TEST(RenderRaster, NearPlaneClippingKeepsSharedEdgesWatertight) {
  for (int trial = 0; trial < 10; ++trial) {
    Rasterizer r(48, 48, 1.0);
    const double zt = 0.3 * trial;
    // Eye-space quad on a plane tilted through the near plane, projected by a 90° perspective (near 1, far 10).
    auto clip = [](double x, double y, double z) {
      const double n = 1, f = 10;
      return ClipVertex{x, y, (f + n) / (n - f) * z + 2 * f * n / (n - f), -z};
    };
    const ClipVertex a = clip(-2, -1, -0.2 - zt), b = clip(2, -1.5, -0.4 - zt), c = clip(2.5, 2, -6), d = clip(-2, 2.5, -5);
    r.draw(0, {a, b, c});
    r.draw(1, {a, c, d});
    for (uint32_t cov : r.coverage()) ASSERT_LE(cov, 1u) << "trial " << trial;
    int covered = 0;
    for (uint32_t cov : r.coverage()) covered += cov;
    EXPECT_GT(covered, 100);
    for (const auto& t : r.tris())
      for (const auto& v : t.v) EXPECT_LE(v.q, (int64_t{1} << 32) + 1);  // w >= near after clipping
  }
}

}  // namespace

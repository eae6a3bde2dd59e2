// SPDX-License-Identifier: Apache-2.0
// shadecore — the deterministic host rasteriser of `shadecore render` (docs/scenes.md "Rasteriser").
// Host software, not RTL: it decides which pixel sees which triangle and interpolates the fragment
// inputs; the lighting core (C model or Verilated RTL) only computes colours. Both render paths share it.
//
//   * clip space → window: perspective divide and viewport in double, then snapped to fixed point:
//     X, Y with kSubBits = 8 fraction bits (1/256 pixel), depth z with kDepthBits = 24 bits
//     (window z in [0, 1]), q = 2^32·near/w for perspective correction;
//   * clipping in homogeneous space against the near plane (w >= near) and a guard band |x|, |y| <= 8w,
//     each intersection computed from the canonically ordered edge so both triangles that share an edge
//     get bit-identical clip vertices;
//   * coverage by integer edge functions at pixel centres with the top-left fill rule (a pixel centre on an
//     edge belongs to the triangle whose edge is a top or a left edge), so pixels on a shared edge are
//     drawn exactly once;
//   * z-buffer: screen-linear depth, GL_LESS (the first triangle drawn wins ties), cleared to the far plane (per
//     draw: set_depth_state, GL_DEPTH_TEST off or glDepthMask(GL_FALSE), in drawing order); the
//     depth plane through the snapped vertices (X, Y, z), or with set_unsnapped_depth(true) (`shadecore replay`)
//     through the unsnapped window positions (x, y with kFineBits fraction bits, z with kDepthBits + kFineBits),
//     as GL interpolates window z (OpenGL 2.1 §3.5.1) and llvmpipe does (its plane from the float vertices,
//     coverage from the snapped ones), quantised to kDepthBits per pixel (floor): two surfaces crossing at a pixel
//     are then ordered by their depths there to within 2^−24, not by depths the snapping moved by up to a few
//     LSBs (scenes keep the snapped plane: their images stay as they were);
//   * perspective-correct interpolation in integers: weights ω_k = λ_k·q_k (λ_k the edge functions), each
//     attribute Σ ω_k a_k / Σ ω_k rounded half up (exact 128-bit arithmetic, no floating point per pixel).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace shadecore::raster {

__extension__ typedef __int128 i128;

inline constexpr int kSubBits = 8;
inline constexpr int kDepthBits = 24;
inline constexpr int64_t kDepthMax = int64_t{1} << kDepthBits;  // the far plane (window z = 1)
inline constexpr double kGuard = 8.0;
inline constexpr int kFineBits = 16;  // extra fraction bits of the depth plane's vertices (draw())

struct ClipVertex {
  double x = 0, y = 0, z = 0, w = 1;  // clip coordinates (after the projection matrix)
};

// A vertex of a screen triangle: its weights over the three vertices of the triangle given to draw()
// (a unit vector unless clipping made it), window position, depth and q.
struct ScreenVertex {
  std::array<double, 3> b{};
  int64_t X = 0, Y = 0;  // 1/256 pixel, y down (row 0 at the top)
  int64_t z = 0;         // window depth × 2^24
  int64_t q = 0;         // 2^32 · near / w
  // The unsnapped window position the depth plane is computed from (draw() after set_unsnapped_depth(true)): x, y
  // in 2^−kFineBits pixel, z in 2^−(kDepthBits + kFineBits). fine = false: the plane through (X, Y, z).
  int64_t fx = 0, fy = 0, fz = 0;
  bool fine = false;
};

struct ScreenTri {
  int source = 0;        // the id given to draw()
  std::array<ScreenVertex, 3> v{};
  int64_t area = 0;      // twice the signed area in (1/256 pixel)^2, > 0 (vertices reordered if needed)
  // The facing of the triangle as given to draw(), from its winding in window space (OpenGL 2.1 §2.14.1 with
  // glFrontFace(GL_CCW)): GL's window y points up, this rasteriser's Y down, so a counter-clockwise (front)
  // triangle has a negative area here before the reordering; true: clockwise in GL's window, a back face.
  bool back = false;
};

struct Weights {
  std::array<i128, 3> w{};  // ω_k = λ_k · q_k
  i128 sum = 0;
};

class Rasterizer {
 public:
  Rasterizer(int width, int height, double near);

  // Clips, sets up and rasterises the triangle (v[0], v[1], v[2]) with the depth test; pixels it wins
  // record the new screen triangle. Back faces are drawn too (no culling, as GL's default).
  void draw(int source, const std::array<ClipVertex, 3>& v);

  [[nodiscard]] int width() const { return w_; }
  [[nodiscard]] int height() const { return h_; }
  [[nodiscard]] const std::vector<ScreenTri>& tris() const { return tris_; }
  // The screen triangle visible at pixel (x, y), or −1.
  [[nodiscard]] int32_t at(int x, int y) const { return id_[static_cast<size_t>(y) * w_ + x]; }
  [[nodiscard]] int64_t depth(int x, int y) const { return depth_[static_cast<size_t>(y) * w_ + x]; }
  // The depth plane of the triangles draw() gets from now on: through the unsnapped window positions (true) or
  // the snapped vertices (false, the default).
  void set_unsnapped_depth(bool on) { unsnapped_depth_ = on; }
  // The depth state of the triangles draw() and draw_screen() get from now on (GL's, per primitive): test = false
  // (GL_DEPTH_TEST off) writes every covered pixel in drawing order and leaves the depth buffer as it is (OpenGL 2.1
  // §4.1.5); test = true, write = false (glDepthMask(GL_FALSE)) tests against the depth buffer without updating it.
  // The default (test and write, GL_LESS) is what scene files always draw with.
  void set_depth_state(bool test, bool write) { depth_test_ = test, depth_write_ = write; }
  // How many times draw() covered each pixel before the depth test (for tests of the fill rule).
  [[nodiscard]] const std::vector<uint32_t>& coverage() const { return cover_; }

  // Perspective-correct weights of screen triangle t at the centre of pixel (x, y).
  [[nodiscard]] Weights weights(int t, int x, int y) const;

  // Rasterises one screen triangle given directly in window fixed point (tests); returns the number of
  // pixels covered. Depth test and ids as draw().
  int draw_screen(int source, const std::array<ScreenVertex, 3>& v);

  // Drops the screen triangles that no pixel shows any more (overdrawn ones) and renumbers the others,
  // keeping their order; at() and weights() are unchanged for every pixel. Memory for tris() is then
  // bounded by the image (at most one triangle per pixel), however many triangles were drawn.
  void compact();
  // Replaces the `source` id of every screen triangle by f(source) (after the caller compacted its own
  // per-source arrays).
  template <typename F>
  void relabel(F f) {
    for (auto& t : tris_) t.source = f(t.source);
  }

 private:
  int raster(const ScreenTri& t, int index);
  int w_, h_;
  double near_;
  bool unsnapped_depth_ = false;
  bool depth_test_ = true, depth_write_ = true;
  std::vector<int32_t> id_;
  std::vector<int64_t> depth_;
  std::vector<uint32_t> cover_;
  std::vector<ScreenTri> tris_;
};

// Σ ω_k a_k / Σ ω_k, rounded half up (ties toward +∞).
int64_t interpolate(const Weights& w, const std::array<int64_t, 3>& a);
// The same in double (reference images).
double interpolate(const Weights& w, const std::array<double, 3>& a);

// ⌊a / b⌋ for b > 0.
i128 floor_div(i128 a, i128 b);

}  // namespace shadecore::raster

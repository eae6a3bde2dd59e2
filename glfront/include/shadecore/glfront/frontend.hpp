// SPDX-License-Identifier: Apache-2.0
// shadecore — the GL 1.x front end of `shadecore replay` (docs/replay.md): the driver's half of a fixed-function
// GPU. It executes a capture's calls with OpenGL 2.1 (compatibility) rules — matrix stacks, glBegin/glEnd with every
// polygon primitive, vertex arrays, display lists (COMPILE and COMPILE_AND_EXECUTE, glCallList(s), glListBase),
// glLight*/glLightModel*/glMaterial* (also between glBegin and glEnd)/glColorMaterial, normals (inverse transpose;
// GL_RESCALE_NORMAL; GL_NORMALIZE), glShadeModel with each primitive type's provoking vertex, glFrontFace,
// glCullFace, depth, scissor and clear state — and hands one frame to the renderer's back end as a stream: eye-space
// triangles grouped into objects, each with the lighting state it was drawn in (scene::LightingSet, one per run of
// draws with the same lights and light model, in drawing order), for render::prepare with view = identity and the
// program's projection; the back end programs the core for each state by register writes and lights its batch.
//
// Every call that changes what is drawn and is not handled is counted by name (`unsupported`). A primitive drawn
// with a capability the core lacks enabled (texturing, blending, fog, alpha test, …) is still drawn, so its
// coverage and occlusion are known, but its object is marked not comparable; a frame whose pixels cannot be
// known (lines, points, glBitmap/glDrawPixels, stencil or colour masks, the projection or two-sided lighting changing
// between draws, …) is refused: ReplayError with a one-line reason. GL_DEPTH_TEST off and glDepthMask(GL_FALSE) go
// with each triangle (GlTriangle::depth_test, depth_write) to the back end's rasteriser, which draws in GL's order.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadecore/glfront/trace.hpp"
#include "shadecore/render/mesh.hpp"
#include "shadecore/render/render.hpp"
#include "shadecore/render/scene.hpp"

namespace shadecore::glfront {

class ReplayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Vec3 = std::array<double, 3>;
using Vec4 = std::array<double, 4>;
using Mat4 = std::array<double, 16>;  // row-major

struct MaterialState {  // glMaterial, one face
  Vec4 ambient{0.2, 0.2, 0.2, 1}, diffuse{0.8, 0.8, 0.8, 1}, specular{0, 0, 0, 1}, emission{0, 0, 0, 1};
  double shininess = 0;
  bool operator==(const MaterialState& o) const;
  bool operator!=(const MaterialState& o) const { return !(*this == o); }
};

struct LightState {  // glLight, in eye space (transformed by the modelview at the call)
  bool enabled = false;
  Vec4 ambient{0, 0, 0, 1}, diffuse{0, 0, 0, 1}, specular{0, 0, 0, 1};
  Vec4 position{0, 0, 1, 0};
  Vec3 spot_direction{0, 0, -1};
  double spot_exponent = 0, spot_cutoff = 180;
  double kc = 1, kl = 0, kq = 0;
  bool operator==(const LightState& o) const;
};

struct LightingState {  // what the core holds in registers for a frame (besides the materials)
  bool lighting = false;
  std::array<LightState, 8> lights{};
  Vec4 model_ambient{0.2, 0.2, 0.2, 1};
  bool local_viewer = false, two_side = false, separate_specular = false;
  bool operator==(const LightingState& o) const;
  bool operator!=(const LightingState& o) const { return !(*this == o); }
};

// One vertex as GL lights it: eye-space position, the eye-space normal GL uses (not renormalised unless
// GL_NORMALIZE / GL_RESCALE_NORMAL say so), the current colour, and the material in force at it.
struct GlVertex {
  Vec4 eye{0, 0, 0, 1};
  Vec4 clip{0, 0, 0, 1};
  Vec3 normal{0, 0, 1};
  Vec4 colour{1, 1, 1, 1};
  uint32_t material = 0;  // index into Gl::materials() (front, back pair)
};

// A triangle after primitive assembly and culling, its vertices ordered so that the provoking vertex is the last
// and its winding is counter-clockwise when it faces front (glFrontFace(GL_CW) swaps the first two).
struct GlTriangle {
  std::array<GlVertex, 3> v;
  bool flat = false;                                   // glShadeModel(GL_FLAT): v[2]'s colour
  bool lit = true;                                     // GL_LIGHTING on
  std::optional<ColourMaterial> colour_material;       // GL_COLOR_MATERIAL on (its mode)
  std::vector<std::string> excluded;                   // capabilities the core lacks that were on (not comparable)
  uint32_t primitive = 0;                              // glBegin / draw index within the frame
  uint32_t lighting = 0;                               // the lighting state it was drawn in: Gl::frame_lightings()
  bool depth_test = true;                              // GL_DEPTH_TEST on (off: drawn over, depth not written)
  bool depth_write = true;                             // glDepthMask(GL_TRUE) with the test on
};

struct FrontStats {
  uint64_t calls_read = 0;        // calls read from the capture up to the end of the frame
  uint64_t calls_in_frame = 0;    // of them, the frame's
  uint64_t calls_executed = 0;    // the frame's calls the front end executed (with display-list contents)
  uint64_t primitives = 0;        // glBegin/glEnd pairs and array draws of the frame (polygon modes)
  uint64_t vertices = 0;          // vertices of those primitives
  uint64_t triangles = 0, culled = 0;
  std::map<std::string, uint64_t> unsupported;  // call name → count in the frame (executed calls)
  std::map<std::string, uint64_t> ignored;      // window-system calls and queries (no effect on the image)
  std::map<std::string, uint64_t> notes;        // approximations and values GL would see differently
};

// The GL state machine. call() executes one call (display lists expanded); tests drive it call by call.
class Gl {
 public:
  Gl();
  Gl(const Gl&) = delete;  // the state machine's internals refer to it
  Gl& operator=(const Gl&) = delete;
  void call(const trace::Call& c);
  // Geometry is assembled only while recording (the frame asked for); state changes always apply.
  void set_recording(bool on) { recording_ = on; }
  void clear_frame();  // drops the triangles and per-frame counts (a swap)

  // state, for tests and the hand-over
  [[nodiscard]] const Mat4& modelview() const { return mv_.back(); }
  [[nodiscard]] const Mat4& projection() const { return proj_.back(); }
  [[nodiscard]] size_t modelview_depth() const { return mv_.size(); }
  [[nodiscard]] size_t projection_depth() const { return proj_.size(); }
  [[nodiscard]] const Vec3& current_normal() const { return normal_; }
  [[nodiscard]] const Vec4& current_colour() const { return colour_; }
  [[nodiscard]] const MaterialState& material(bool back) const { return mat_[back ? 1 : 0]; }
  [[nodiscard]] const LightingState& lighting() const { return light_; }
  [[nodiscard]] const std::vector<std::array<MaterialState, 2>>& materials() const { return materials_; }
  [[nodiscard]] const std::vector<GlTriangle>& triangles() const { return tris_; }
  [[nodiscard]] const FrontStats& stats() const { return stats_; }
  FrontStats& stats() { return stats_; }
  [[nodiscard]] std::array<int, 4> viewport() const { return viewport_; }
  [[nodiscard]] std::array<int, 2> drawable() const { return drawable_; }
  [[nodiscard]] const Vec4& clear_colour() const { return clear_colour_; }
  [[nodiscard]] bool cleared() const { return cleared_; }
  [[nodiscard]] const std::vector<std::string>& refusals() const { return refusals_; }
  [[nodiscard]] bool list_defined(uint32_t id) const { return lists_.count(id) != 0; }
  // The lighting state of the frame's first lit triangles, and the projection they were drawn with.
  [[nodiscard]] const std::optional<LightingState>& frame_lighting() const { return frame_light_; }
  // The frame's lighting states in drawing order, one per run of lit draws with the same state (a state may come
  // back); GlTriangle::lighting indexes it.
  [[nodiscard]] const std::vector<LightingState>& frame_lightings() const { return frame_lights_; }
  [[nodiscard]] const std::optional<Mat4>& frame_projection() const { return frame_proj_; }

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
  friend struct Impl;
  // state
  std::vector<Mat4> mv_, proj_, tex_;
  uint32_t matrix_mode_ = 0x1700;
  Vec3 normal_{0, 0, 1};
  Vec4 colour_{1, 1, 1, 1};
  std::array<MaterialState, 2> mat_{};
  LightingState light_{};
  std::vector<std::array<MaterialState, 2>> materials_;
  std::vector<GlTriangle> tris_;
  FrontStats stats_;
  std::array<int, 4> viewport_{0, 0, 0, 0};
  std::array<int, 2> drawable_{0, 0};
  Vec4 clear_colour_{0, 0, 0, 0};
  bool cleared_ = false, recording_ = true;
  std::vector<std::string> refusals_;
  std::map<uint32_t, std::shared_ptr<std::vector<trace::Call>>> lists_;
  std::optional<LightingState> frame_light_;
  std::vector<LightingState> frame_lights_;
  std::optional<Mat4> frame_proj_;
};

struct ReplayOptions {
  std::optional<uint64_t> frame;  // frame K >= 1: the calls between the (K−1)-th and the K-th swap
  std::optional<uint64_t> call;   // a snapshot after call N (the frame: from the last swap before N to N)
};

// A frame handed to the back end: a scene in eye space (view = identity, the program's projection) whose objects
// are runs of triangles with one material and lighting state (scene.lighting_sets: the frame's states in drawing
// order; objects[i].lighting), and their meshes.
struct Handover {
  scene::Scene scene;
  std::vector<scene::Mesh> meshes;
  render::Settings settings;
  std::vector<std::vector<std::string>> object_excluded;  // per object: why its pixels are not compared ([] = compared)
  uint64_t frame = 0;             // the frame number (1-based)
  uint64_t first_call = 0;        // the frame's first call
  uint64_t snapshot_call = 0;     // the call after which its image is complete (glretrace -S): before the swap
  uint64_t swaps_seen = 0;
  std::string api;                // "glx", "egl" or "" (no window-system calls)
  FrontStats stats;
  uint64_t non_unit_normals = 0;  // normals GL uses with |n| ≠ 1 (no GL_NORMALIZE): the core normalises them
  double worst_normal_length = 1;
  // Triangle vertices outside the core's eye-space range [−128, 128), the largest |coordinate| (vertices and point
  // lights), and the power of two the frame's eye space was scaled by to bring them inside (1: none out of range).
  uint64_t eye_out_of_range = 0;
  double eye_worst = 0, eye_scale = 1;
};

// Reads the capture up to the frame (or call) asked for, runs the front end over it and builds the hand-over.
// Throws ReplayError (one line) for a frame past the end, a core-profile or GL ES context, or a frame refused.
Handover replay_frame(trace::Reader& reader, const ReplayOptions& o, const std::string& name);

// The hand-over of the triangles the front end assembled (exposed for tests).
Handover hand_over(const Gl& gl, const std::string& name);

}  // namespace shadecore::glfront

// SPDX-License-Identifier: Apache-2.0
// shadecore — a scene through a GL implementation's fixed-function lighting (Mesa's OSMesa: llvmpipe), the
// outside reference for `shadecore gl-compare` (docs/gl_compare.md). Host software, not hardware.
//
// The scene is read by the project's parser (scene.hpp) and its objects are the project's meshes
// (render::MeshSource / mesh.cpp): the same polygons, fanned into the same triangles (v0, vk, vk+1) as
// render::prepare draws them, with the same vertex normals. Everything else is GL's own: gluPerspective as
// glFrustum, gluLookAt as a glMultMatrixd, each object's glTranslated · glRotated… · glScaled, glLight with the
// view matrix on the modelview stack, glMaterial, glLightModel, GL_NORMALIZE, glShadeModel, GL_LESS depth.
//
// What fixed-function GL cannot show is reported per object (check_objects): Phong shading (per-fragment
// lighting), Phong's R·V reflection, shininess above GL's cap of 128, energy normalisation; and flat shading
// under the scene's flat_rule centroid where the lighting depends on the position (shadecore lights the face
// centroid, GL the provoking vertex). Under flat_rule provoking_vertex flat objects are drawn with their vertex
// normals in the fan's order under GL_FLAT and compare like Gouraud ones.
// Such objects are still drawn by GL (Phong ones as Gouraud) so that coverage and occlusion compare.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shadecore/render/render.hpp"
#include "shadecore/render/scene.hpp"

namespace shadecore::glref {

struct GlSettings {
  int width = 0, height = 0;            // 0: the scene's size
  std::optional<scene::Shading> mode;   // every object in this mode (as render::Settings::mode)
};

struct GlImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;             // 8-bit RGB, row-major from the top (as render::to_rgb8)
  std::vector<int32_t> object;          // the scene object each pixel shows, −1 for the background
  std::string renderer, version;        // GL_RENDERER, GL_VERSION
  std::vector<std::array<double, 16>> object_mvp;  // per object: GL's projection · modelview (column-major)
};

// Renders `sc` through OSMesa's fixed-function pipeline (two passes: lit colours, then object ids with the
// same geometry and depth test). Throws std::runtime_error (one line) if OSMesa cannot make a context or GL
// reports an error.
GlImage render_gl(const scene::Scene& sc, render::MeshSource& meshes, const GlSettings& s);

// Can fixed-function GL show what shadecore's exact image shows for this object? `shading` is per scene
// object after overrides (render::Frame::object_shading).
struct ObjectCheck {
  bool comparable = true;
  std::vector<std::string> reasons;     // why not (empty when comparable)
  std::vector<std::string> notes;       // how it maps (e.g. "shininess 20", "flat: lighting independent of position")
};
std::vector<ObjectCheck> check_objects(const scene::Scene& sc, const std::vector<scene::Shading>& shading);

// The scene object each pixel of a prepared frame shows (−1 background), row-major from the top.
std::vector<int32_t> object_map(const render::Frame& fr);

// The objects of a snapshot of which only the colours are known (a GL program's framebuffer, as `shadecore replay
// --mesa` reads it): a pixel is covered where it differs from the clear colour `bg`, by the object the exact image
// shows there (0 where it shows none: a coverage difference). Geometry the exact image shows in exactly the clear
// colour where the snapshot shows the clear colour too cannot be told from the background in the snapshot: it is
// taken as covered by that object (the two images agree on the pixel) and counted in `covered_in_clear_colour`, not
// as a coverage difference. Images are 8-bit RGB of exact_obj.size() pixels.
inline std::vector<int32_t> snapshot_objects(const std::vector<uint8_t>& snap_rgb, const std::array<uint8_t, 3>& bg,
                                             const std::vector<int32_t>& exact_obj,
                                             const std::vector<uint8_t>& exact_rgb, uint64_t& covered_in_clear_colour) {
  std::vector<int32_t> obj(exact_obj.size(), -1);
  covered_in_clear_colour = 0;
  const auto is_bg = [&bg](const std::vector<uint8_t>& rgb, size_t p) {
    return rgb[3 * p] == bg[0] && rgb[3 * p + 1] == bg[1] && rgb[3 * p + 2] == bg[2];
  };
  for (size_t p = 0; p < obj.size(); ++p) {
    if (!is_bg(snap_rgb, p)) obj[p] = exact_obj[p] >= 0 ? exact_obj[p] : 0;
    else if (exact_obj[p] >= 0 && is_bg(exact_rgb, p)) obj[p] = exact_obj[p], ++covered_in_clear_colour;
  }
  return obj;
}

// Per-pixel difference: max over R, G, B of |a − b| in 8-bit LSBs; percentiles by nearest rank.
struct DiffStats {
  uint64_t pixels = 0;
  int p50 = 0, p99 = 0, max = 0;
  double mean = 0;
  int max_x = -1, max_y = -1;           // where max is: column from the left, row from the top
  uint64_t above = 0;                   // pixels whose difference exceeds the tolerance
};

struct Comparison {
  int tolerance = 2;                    // LSBs allowed at the 99th percentile
  DiffStats comparable;                 // over the pixels both cover with the same comparable object
  DiffStats all;                        // over the pixels both cover with the same object (any)
  std::vector<DiffStats> per_object;    // per scene object (its pixels in both images)
  uint64_t covered_exact = 0, covered_gl = 0, covered_both = 0;
  uint64_t coverage_mismatch = 0;       // covered in one image and not in the other
  uint64_t object_mismatch = 0;         // covered in both, by different objects (occlusion, depth ties)
  struct Mismatch {
    int x, y;                           // column from the left, row from the top
    int32_t exact_object, gl_object;    // −1: background
    double edge_px = -1;                // explain_mismatches: distance to the nearest triangle edge (−1: none near)
  };
  std::vector<Mismatch> mismatches;     // coverage / object mismatches, row by row (the first kMaxMismatches)
  static constexpr size_t kMaxMismatches = 4096;
  // explain_mismatches: those within kSnapPx of a triangle edge of an object involved (sub-pixel vertex snapping:
  // GL transforms in float, shadecore in double, both snap to 1/256 pixel), and whether every one was.
  uint64_t mismatch_near_edge = 0;
  bool mismatches_explained = false;
  static constexpr double kSnapPx = 1.0 / 256;
  bool pass = false;                    // comparable.pixels > 0, p99 <= tolerance, no coverage or object mismatch
  // Amplified difference: black = equal; grey (60 per LSB) up to the tolerance; above it red where shadecore's
  // exact image is brighter, blue where GL's is (128 + 16 per LSB); yellow = coverage mismatch, magenta = object
  // mismatch; non-comparable objects as their exact image at a quarter of its brightness.
  std::vector<uint8_t> diff_rgb;
};

// Compares shadecore's exact image (8-bit, render::to_rgb8 of the exact reference) and its object map with
// GL's. With all_objects every object counts towards the verdict, comparable or not.
Comparison compare(int width, int height, const std::vector<uint8_t>& exact_rgb, const std::vector<int32_t>& exact_object,
                   const GlImage& gl, const std::vector<ObjectCheck>& checks, int tolerance = 2, bool all_objects = false);

// For each recorded mismatch: the distance from its pixel centre to the nearest edge of the triangles of the
// objects involved (projected in double with GL's matrices) that contain the centre or lie within 1/64 pixel
// of it; counts the ones within Comparison::kSnapPx. A rule difference (fill convention, pixel centres) would put
// centres exactly on edges of far more pixels; a depth or occlusion difference leaves them far from any edge.
void explain_mismatches(const scene::Scene& sc, render::MeshSource& meshes, const GlImage& gl, Comparison& cmp);

}  // namespace shadecore::glref

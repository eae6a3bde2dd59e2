// SPDX-License-Identifier: Apache-2.0
// shadecore — rendering a scene through the lighting core (docs/scenes.md).
//
//   prepare()   host side: geometry in eye space, the rasteriser's visibility buffer, the feature set(s)
//               the scene needs (derive_features), and per core the command stream: register writes
//               (global, lights, then per material its registers and its fragments);
//   run_cmodel  the bit-accurate C model (LightCore::eval) over one core's stream; the RTL path sends the
//               same stream to the Verilated core instead;
//   resolve()   colours back into the image: flat = one colour per face (flat_rule centroid) or per triangle,
//               its provoking vertex's (provoking_vertex), Gouraud = vertex colours
//               interpolated (perspective-correct, integers), Phong = one core colour per pixel;
//   reference() the same fragments through LightCore::eval_double (exact cos^n, or the unit's own double
//               formula), interpolated the same way in double.
//
// Shading modes (seed 001): flat — one normal per face, the face lit once at its centroid (the scene's flat_rule
// provoking_vertex: GL_FLAT, each triangle (v0, vk, vk+1) takes the colour of vertex vk+1, lit with its vertex
// normal and position — the vertex fragment Gouraud would send, one per distinct provoking vertex); Gouraud —
// lighting per vertex through the core, colours interpolated; Phong — normals and positions interpolated,
// lighting per pixel through the core.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shadecore/features.hpp"
#include "shadecore/light.hpp"
#include "shadecore/render/mesh.hpp"
#include "shadecore/render/raster.hpp"
#include "shadecore/render/scene.hpp"

namespace shadecore::render {

struct CoreCmd {
  bool is_write = false;
  RegWrite w{0, 0};
  Fragment f{};
};

enum class DestKind : uint8_t { Face, Vertex, Pixel };
struct Dest {
  DestKind kind;
  uint32_t index;     // face, vertex (global numbering) or pixel (y·width + x)
  bool back = false;  // two_side: the face's / vertex's back-facing colour (GL computes both per vertex and the
                      // rasteriser picks by the triangle's facing); pixels: the fragment of a back-facing triangle
};

// One lighting core of a render and what it shades.
struct CoreGroup {
  FeatureSet fs;                        // the set this render uses
  FeatureSet specialised;               // the derived smallest set (== fs unless the full core is used)
  std::vector<std::string> full_substitutions;  // full core: what is not 'full' (only a config)
  std::vector<int> materials;           // scene material indices
  std::vector<int> light_slot;          // scene light index per core light slot (−1 = unused slot): of the first
                                        // lighting state the group uses
  // Per lighting state of the scene (Scene::lighting_states()): its light index per core slot (−1 unused; empty for
  // a state none of the group's objects uses). The slots' kinds are the union over the states (one core for all).
  std::vector<std::vector<int>> set_light_slot;
  // Lighting-state changes in the command stream after the first programming, and the register writes they took
  // (only the registers whose value changes; the core drains before a write). Scene files: 0.
  uint64_t state_changes = 0, state_writes = 0;
  std::string unit_label;               // "cs16/theta_cr", "schlick_nr", "none"
  std::vector<CoreCmd> cmds;
  std::vector<Dest> dests;              // one per fragment command, in order
  uint64_t faces = 0, vertices = 0, pixels = 0;  // fragments by kind (vertices: Gouraud's and flat provoking vertices)
  uint64_t writes = 0;
};

struct Settings {
  bool full_core = false;
  int lanes = 1;                              // lanes of the cores (clamped to their light slots)
  int share = 1;                              // clocks per pass of the cores with one lane (feature key share)
  int width = 0, height = 0;                  // 0: the scene's size
  std::optional<scene::Shading> mode;         // every object in this mode
  std::optional<VariantId> unit;              // every specular material through this unit
  std::optional<scene::Camera> camera;
  std::vector<int> objects;                   // only these objects (empty: all)
  // A GL front end's matrices (row-major) in place of the camera's gluLookAt / gluPerspective (the camera's `near`
  // stays the rasteriser's near plane): `shadecore replay` gives vertices and lights in eye space (view = identity)
  // and the program's own projection (glFrustum, glOrtho, glLoadMatrix…).
  std::optional<std::array<double, 16>> view, projection;
  // The depth plane through the unsnapped window positions (raster::Rasterizer::set_unsnapped_depth): `shadecore
  // replay`, whose reference (Mesa's llvmpipe) computes it so; scene files keep the snapped one.
  bool unsnapped_depth = false;
  // Leave out a register write when the register already holds the value (what a driver shadowing the core's
  // registers writes): `shadecore replay`. Scene files write every material's registers in full, as before. Writes
  // for a change of lighting state (Scene::lighting_sets) are always the changed registers only.
  bool changed_registers_only = false;
};

// The colours an object sends to the core under colour material (objects[i].color_material): per channel the
// largest, and whether every one is grey at the core's width (all r = g = b codes). Of its mesh's vertex colours,
// or its `color` (one colour) for a mesh without them.
struct ObjectColours {
  scene::Vec3 max{1, 1, 1};
  bool grey = true;
};

// The derived feature sets of a scene, one per specular unit in use (materials without a specular term
// join the first group). Exposed for tests and `render --json`.
struct Derivation {
  std::vector<CoreGroup> groups;              // fs, specialised, materials, light_slot, unit_label filled
  std::vector<int> group_of_material;         // −1: material not used by any object
};
Derivation derive_features(const scene::Scene& sc, const std::vector<int>& objects_used,
                           const std::vector<bool>& phong_used_by_material, bool full_core,
                           std::optional<VariantId> unit_override, int lanes = 1, int share = 1,
                           const std::vector<ObjectColours>& object_colours = {});  // per scene object; empty: `color`

// The full core for a specialised set: config/configs.json 'full', programmed by register writes alone
// (its capabilities include every mode of `spec`); only a width other than full's is substituted (a
// width is no mode) and described in `subs`. Throws if 'full' lacks a capability `spec` needs.
FeatureSet full_core_for(const FeatureSet& spec, std::vector<std::string>& subs);

// The objects' geometry, tessellated (or read from its OBJ file) when prepare() reaches the object and
// dropped after it, so a render's peak memory is bounded by the image and one object's geometry, not by the
// scene. Meshes up to `keep_bytes` in all are kept for the next prepare() of the same scene (the contact
// sheet renders it once per cell); bigger ones are built again.
class MeshSource {
 public:
  explicit MeshSource(const scene::Scene& sc, size_t keep_bytes = size_t{256} << 20);
  explicit MeshSource(const std::vector<scene::Mesh>& given);  // meshes built by the caller (not owned)
  [[nodiscard]] std::shared_ptr<const scene::Mesh> get(int object);
  [[nodiscard]] double build_seconds() const { return build_seconds_; }  // time spent in build_mesh
  static size_t bytes(const scene::Mesh& m);                              // heap estimate of one mesh

 private:
  const scene::Scene* sc_ = nullptr;
  const std::vector<scene::Mesh>* given_ = nullptr;
  size_t keep_bytes_ = 0, kept_bytes_ = 0;
  std::vector<std::shared_ptr<const scene::Mesh>> kept_;
  double build_seconds_ = 0;
};

struct Frame {
  const scene::Scene* scene = nullptr;
  int width = 0, height = 0, F = 16;
  std::vector<CoreGroup> groups;
  // Geometry that some pixel shows (triangles no pixel shows are dropped object by object, with the
  // vertices and faces only they used); numbering in drawing order (objects, then their vertices / faces).
  std::vector<Fragment> vertex_frag;          // per vertex: N̂ and P codes (Gouraud; flat by provoking vertex), and
                                              // under the object's colour material its colour (else 0)
  std::vector<Fragment> face_frag;            // per face: face normal and centroid codes (colour: the mean of its
                                              // vertices' colours under colour material)
  std::vector<int> vertex_object, face_object;  // per vertex / face: its scene object
  std::vector<int> tri_object, tri_face;      // per triangle (the rasteriser's source id)
  std::vector<std::array<uint32_t, 3>> tri_vertices;  // (v0, vk, vk+1) of the face's fan: [2] provokes
  uint64_t drawn_vertices = 0, drawn_faces = 0, drawn_triangles = 0;  // before dropping the hidden ones
  double tessellate_seconds = 0, rasterise_seconds = 0;  // prepare()'s phases (mesh building; the rest)
  std::vector<int> object_group;              // per scene object: its core group (−1 not drawn)
  std::vector<scene::Shading> object_shading; // per scene object (after overrides)
  std::vector<int> object_material;           // per scene object (after overrides)
  scene::FlatRule flat_rule = scene::FlatRule::Centroid;  // the scene's: flat objects by face or by provoking vertex
  bool two_side = false;                      // the scene's light_model.two_side: back-facing triangles (window-space
                                              // winding, raster::ScreenTri::back) take their back fragments' colours
  raster::Rasterizer raster{1, 1, 1.0};
  std::array<uint32_t, 3> background{};       // codes
};

// The view matrix of the scene's camera, gluLookAt(eye, center, up), row-major: what prepare() puts on the
// modelview stack before lights and objects (also shadecore_glref's, so both renderers share one camera).
std::array<double, 16> view_matrix(const scene::Camera& c);

Frame prepare(const scene::Scene& sc, MeshSource& meshes, const Settings& s);
Frame prepare(const scene::Scene& sc, const std::vector<scene::Mesh>& meshes, const Settings& s);

// The C model over one core's command stream: one colour per fragment command, in order.
std::vector<Colour> run_cmodel(const CoreGroup& g);
// The double reference over the same stream (values in [0, 1] per channel): the primary colour and, in the
// separate-specular mode, the secondary (specular) colour, each clamped; else the colour sum and 0.
using RefColour = std::array<double, 6>;  // primary r, g, b, secondary r, g, b
std::vector<RefColour> run_reference(const CoreGroup& g, LightCore::SpecRef ref);

// An image of colour codes (F fraction bits, 0..2^F), 3 channels per pixel, row-major from the top: GL's colour
// sum min(2^F, primary + secondary), the two interpolated apart (resolve()).
struct Image {
  int width = 0, height = 0, F = 16;
  std::vector<uint32_t> code;
  std::vector<uint8_t> covered;   // 1 where geometry is visible
  std::vector<int8_t> group;      // core group per pixel (−1 background)
};
struct RefImage {
  int width = 0, height = 0;
  std::vector<double> value;      // 3 per pixel, [0, 1]
};

Image resolve(const Frame& fr, const std::vector<std::vector<Colour>>& colours);
// Interpolates the primary and the secondary colour apart (GL: Gouraud interpolates both) and stores their
// colour sum min(1, primary + secondary) per pixel.
RefImage resolve_reference(const Frame& fr, const std::vector<std::vector<RefColour>>& values);

struct ErrorStats {
  double max_lsb = 0;       // max |code − 2^F·ref| over covered pixels and channels, in output LSBs (2^−F)
  double mean_lsb = 0;
  double rms = 0;           // root mean square of (code/2^F − ref)
  double psnr_db = 0;       // 10·log10(1 / mean square error); +inf when identical
  uint64_t pixels = 0;      // covered pixels (of the group)
  uint64_t samples = 0;     // covered pixels × 3 channels
  int max_x = -1, max_y = -1;  // where max_lsb is: column from the left, row from the top
};
// Over the covered pixels (of one core group if group >= 0).
ErrorStats error_vs(const Image& img, const RefImage& ref, int group = -1);

// Pixels whose codes differ (any channel).
uint64_t mismatching_pixels(const Image& a, const Image& b);

// 8-bit RGB views: the image (code·255/2^F rounded) and the reference (value·255 rounded).
std::vector<uint8_t> to_rgb8(const Image& img);
std::vector<uint8_t> to_rgb8(const RefImage& ref);
// Signed difference on a log scale: per pixel the channel with the largest |Δ| = code − 2^F·ref (in LSBs);
// red where the image is brighter than the reference, blue where darker, intensity
// 255·log2(1 + |Δ|)/log2(1 + 2^F) (1 LSB ≈ 15/255 at F = 16, 2^F LSB = 255); black = identical.
std::vector<uint8_t> diff_rgb8(const Image& img, const RefImage& ref);
std::vector<uint8_t> mismatch_rgb8(const Image& a, const Image& b);  // white where different

}  // namespace shadecore::render

// SPDX-License-Identifier: Apache-2.0
// shadecore — object geometry for `shadecore render`: tessellated sphere / plane / torus and OBJ meshes
// (tinyobjloader), as polygons with per-vertex normals in object space. Host software.
#pragma once

#include <vector>

#include "shadecore/render/scene.hpp"

namespace shadecore::scene {

struct Mesh {
  std::vector<Vec3> pos;                 // object-space positions
  std::vector<Vec3> nrm;                 // unit vertex normals (analytic, from the OBJ, or area-weighted)
  std::vector<std::vector<int>> faces;   // polygons, counter-clockwise seen from outside (front faces)
  std::vector<Vec3> col;                 // per-vertex colours in [0, 1] (OBJ `v x y z r g b`); empty: none (the
                                         // object's `color` everywhere)
  // Material batches (a GL front end's; scene files: empty): per vertex the scene object whose material, lighting
  // state and colour material light it (GL lights each vertex with the material in force at it), empty: this mesh's
  // own object. Such an object has no faces of its own; its mesh's `col` lists the colours of the vertices it lights
  // (for the derivation of the core's colour inputs).
  std::vector<int> vertex_object;
};

// Builds the geometry of `o`. Throws SceneError (one line) for a missing or malformed OBJ file,
// a face index out of range, a degenerate (zero-area) face, a zero normal, a vertex colour outside [0, 1] or
// vertex colours on some `v` lines but not on all.
Mesh build_mesh(const Object& o);

// Newell's polygon normal (not normalised; length = 2 × area for a planar polygon).
Vec3 polygon_normal(const std::vector<Vec3>& pos, const std::vector<int>& face);

}  // namespace shadecore::scene

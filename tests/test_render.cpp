// SPDX-License-Identifier: Apache-2.0
// shadecore — tests of `shadecore render`'s library (shadecore/render/render.hpp) on the C model: the derived
// feature sets are the smallest that render the scene, and the full core reproduces the specialised
// core's image bit for bit (for every example scene and for scenes built to hit every substitution).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "shadecore/render/glref.hpp"
#include "shadecore/render/mesh.hpp"
#include "shadecore/render/render.hpp"
#include "shadecore/render/scene.hpp"

#ifndef SHADECORE_SOURCE_DIR
#error "SHADECORE_SOURCE_DIR must point at the source tree"
#endif

namespace {

using namespace shadecore;
using shadecore::render::Frame;
using shadecore::render::Settings;

std::string scene_path(const std::string& name) { return std::string(SHADECORE_SOURCE_DIR) + "/scenes/" + name; }

struct Loaded {
  scene::Scene sc;
  std::vector<scene::Mesh> meshes;
};
// a scene file by its path, or by its name under scenes/
Loaded load_file(const std::string& path) {
  Loaded l;
  l.sc = scene::load_scene(path);
  for (const auto& o : l.sc.objects) l.meshes.push_back(scene::build_mesh(o));
  return l;
}
Loaded load(const std::string& name) { return load_file(scene_path(name)); }
std::string test_data(const std::string& name) {
  return std::string(SHADECORE_SOURCE_DIR) + "/tests/data/render/" + name;
}
Loaded parse(const std::string& text) {
  Loaded l;
  l.sc = scene::parse_scene(text, "inline.json", std::string(SHADECORE_SOURCE_DIR) + "/scenes");
  for (const auto& o : l.sc.objects) l.meshes.push_back(scene::build_mesh(o));
  return l;
}

render::Image cmodel_image(const Frame& fr) {
  std::vector<std::vector<Colour>> cols;
  for (const auto& g : fr.groups) cols.push_back(render::run_cmodel(g));
  return render::resolve(fr, cols);
}

Frame frame(const Loaded& l, bool full, int w = 96, int h = 64) {
  Settings s;
  s.full_core = full;
  s.width = w;
  s.height = h;
  return render::prepare(l.sc, l.meshes, s);
}

uint64_t covered(const render::Image& img) {
  uint64_t n = 0;
  for (auto c : img.covered) n += c;
  return n;
}

// Specialised and full core: identical codes in every pixel; and the full core really is bigger.
void expect_full_identical(const Loaded& l, int w = 96, int h = 64) {
  const Frame spec = frame(l, false, w, h), full = frame(l, true, w, h);
  ASSERT_EQ(spec.groups.size(), full.groups.size());
  for (size_t g = 0; g < spec.groups.size(); ++g) {
    EXPECT_EQ(full.groups[g].fs.num_lights(), 8);
    EXPECT_EQ(full.groups[g].fs.name, "full");
    EXPECT_TRUE(full.groups[g].full_substitutions.empty());  // programmed by register writes alone
    EXPECT_EQ(full.groups[g].fs.key(), feature_set_named_or_file("full").key());
    EXPECT_TRUE(full.groups[g].fs.norm && full.groups[g].fs.ambient && full.groups[g].fs.diffuse &&
                full.groups[g].fs.specular && full.groups[g].fs.normalize);
    EXPECT_EQ(full.groups[g].fs.channels, 3);
    EXPECT_EQ(full.groups[g].dests.size(), spec.groups[g].dests.size());
  }
  const auto a = cmodel_image(spec), b = cmodel_image(full);
  EXPECT_GT(covered(a), static_cast<uint64_t>(w * h / 20));
  EXPECT_EQ(render::mismatching_pixels(a, b), 0u) << l.sc.file;
}

TEST(RenderFeatures, DiffuseSceneGetsTheSmallestSet) {
  const auto l = load("diffuse.json");
  const Frame fr = frame(l, false);
  ASSERT_EQ(fr.groups.size(), 1u);
  const FeatureSet& fs = fr.groups[0].fs;
  EXPECT_EQ(fs.slots, std::vector<uint8_t>{kind_bit(LightKind::Directional)});
  EXPECT_TRUE(fs.ambient);
  EXPECT_TRUE(fs.diffuse);
  EXPECT_FALSE(fs.specular);
  EXPECT_FALSE(fs.norm);
  EXPECT_TRUE(fs.normalize);  // Phong-shaded objects interpolate normals
  EXPECT_EQ(fs.channels, 3);
  EXPECT_EQ(fs.key(), fr.groups[0].specialised.key());
}

TEST(RenderFeatures, SpheresSceneOneCorePerSpecularUnit) {
  const auto l = load("spheres.json");
  const Frame fr = frame(l, false);
  ASSERT_EQ(fr.groups.size(), 2u);
  EXPECT_EQ(fr.groups[0].unit_label, "cs16/theta_cr");
  EXPECT_EQ(fr.groups[1].unit_label, "schlick_nr");
  for (const auto& g : fr.groups) {
    EXPECT_EQ(g.fs.slots, (std::vector<uint8_t>{kind_bit(LightKind::Directional), kind_bit(LightKind::PointAtt), kind_bit(LightKind::PointAtt)}));
    EXPECT_TRUE(g.fs.specular);
    EXPECT_TRUE(g.fs.blinn);
    EXPECT_FALSE(g.fs.local_viewer);
  }
  EXPECT_EQ(fr.groups[1].fs.variant, VariantId::schlick_nr);
  // The floor (no specular colour) shares the first core.
  EXPECT_EQ(fr.groups[0].materials.size(), 3u);
}

TEST(RenderFeatures, MeshSceneMonoPointLocalViewerPhong) {
  const auto l = load("mesh.json");
  const Frame fr = frame(l, false);
  ASSERT_EQ(fr.groups.size(), 1u);
  const FeatureSet& fs = fr.groups[0].fs;
  EXPECT_EQ(fs.slots, std::vector<uint8_t>{kind_bit(LightKind::Point)});
  EXPECT_EQ(fs.channels, 1);
  EXPECT_TRUE(fs.local_viewer);
  EXPECT_FALSE(fs.blinn);
  EXPECT_EQ(fs.cutoff, Cutoff::SignClamp);
  EXPECT_GT(fr.groups[0].faces, 0u);   // the flat icosahedron
  EXPECT_GT(fr.groups[0].pixels, 0u);  // the Phong knot
}

const char* kBase = R"({
  "image": {"width": 64, "height": 48},
  "camera": {"eye": [0, 0, 6], "center": [0, 0, 0], "up": [0, 1, 0], "fovy": 40, "near": 1, "far": 20},
  %LIGHTMODEL%
  "lights": [%LIGHTS%],
  "materials": {%MATERIALS%},
  "objects": [%OBJECTS%]
})";
std::string make(const std::string& lights, const std::string& materials, const std::string& objects,
                 const std::string& light_model = "") {
  std::string s = kBase;
  auto rep = [&s](const std::string& k, const std::string& v) { s.replace(s.find(k), k.size(), v); };
  rep("%LIGHTMODEL%", light_model.empty() ? "" : "\"light_model\": " + light_model + ",");
  rep("%LIGHTS%", lights);
  rep("%MATERIALS%", materials);
  rep("%OBJECTS%", objects);
  return s;
}
const std::string kSphere = R"({"type": "sphere", "slices": 16, "stacks": 10, "material": "m", "shading": "%S%",
                                "transform": {"translate": [-0.6, 0, 0]}},
                               {"type": "torus", "sides": 10, "rings": 16, "material": "%M2%", "shading": "%S2%",
                                "transform": {"translate": [1.2, 0.2, -1], "rotate": [50, 1, 0.2, 0]}})";
std::string objects(const std::string& s1, const std::string& s2, const std::string& m2 = "m") {
  std::string o = kSphere;
  o.replace(o.find("%S%"), 3, s1);
  o.replace(o.find("%M2%"), 4, m2);
  o.replace(o.find("%S2%"), 4, s2);
  return o;
}

TEST(RenderFeatures, MinimalityRules) {
  // Flat and Gouraud only: unit normals from the host, no GL_NORMALIZE.
  {
    const auto l = parse(make(R"({"position": [0, 1, 1, 0]})", R"("m": {"specular": [0.5, 0.5, 0.5], "shininess": 32})",
                              objects("flat", "gouraud")));
    const Frame fr = frame(l, false);
    ASSERT_EQ(fr.groups.size(), 1u);
    EXPECT_FALSE(fr.groups[0].fs.normalize);
    EXPECT_EQ(fr.groups[0].fs.channels, 1);  // all grey
  }
  // A light with zero colours, and one whose only colour is specular in a scene without specular
  // materials, are not built; an all-zero specular light colour leaves no specular unit.
  {
    const auto l = parse(make(R"({"position": [0, 1, 1, 0], "diffuse": [0, 0, 0], "specular": [0, 0, 0]},
                                 {"position": [1, 1, 1, 1], "diffuse": [0, 0, 0], "specular": [1, 1, 1]},
                                 {"position": [-1, 1, 1, 0], "diffuse": [0.5, 0.2, 0.2], "specular": [0, 0, 0]})",
                              R"("m": {"diffuse": [0.6, 0.6, 0.6]})", objects("phong", "phong")));
    const Frame fr = frame(l, false);
    ASSERT_EQ(fr.groups.size(), 1u);
    const FeatureSet& fs = fr.groups[0].fs;
    EXPECT_EQ(fs.slots, std::vector<uint8_t>{kind_bit(LightKind::Directional)});
    EXPECT_EQ(fr.groups[0].light_slot, std::vector<int>{2});
    EXPECT_FALSE(fs.specular);
    EXPECT_EQ(fs.channels, 3);
    EXPECT_TRUE(fs.normalize);
  }
  // Ambient off when nothing ambient or emissive reaches the core.
  {
    const auto l = parse(make(R"({"position": [0, 1, 1, 0]})", R"("m": {"ambient": [0, 0, 0], "diffuse": [0.6, 0.6, 0.6]})",
                              objects("gouraud", "gouraud"), R"({"ambient": [0.2, 0.2, 0.2]})"));
    const Frame fr = frame(l, false);
    EXPECT_FALSE(fr.groups[0].fs.ambient);
    EXPECT_FALSE(fr.groups[0].fs.specular);
  }
}

TEST(RenderFullCore, ExampleScenesIdenticalOnTheFullCore) {
  for (const char* s : {"diffuse.json", "spheres.json", "shading_modes.json", "mesh.json"}) {
    SCOPED_TRACE(s);
    expect_full_identical(load(s));
  }
}

// Scenes built to hit every difference between a specialised set and 'full': unused light slots (off),
// directional, point and point_att lights (programmed kinds),
// energy normalisation on some materials only (coefficient 1.0 for the others), no GL_NORMALIZE on the
// specialised core (host normals are fixed points of the normaliser), mono, Phong reflection, local and
// infinite viewer, each specular unit of 'full', emission, materials without specular sharing a specular core.
TEST(RenderFullCore, EveryModeIdentical) {
  const std::vector<std::string> units = {"cs16", "schlick_nr"};
  int n = 0;
  for (const auto& unit : units)
    for (const char* reflection : {"blinn", "phong"})
      for (const char* viewer : {"false", "true"})
        for (const char* mode : {"flat", "gouraud", "phong"}) {
          const std::string lights = R"({"position": [-1, 1, 2, 0], "diffuse": [0.7, 0.6, 0.5], "specular": [1, 1, 1]},
               {"position": [2, 1, 3, 1], "diffuse": [0.3, 0.4, 0.6], "specular": [0.8, 0.8, 0.8], "ambient": [0.05, 0.05, 0.05]},
               {"position": [0, -2, 2, 1], "diffuse": [0.5, 0.5, 0.5], "specular": [0.5, 0.5, 0.5],
                "constant_attenuation": 0.5, "linear_attenuation": 0.2, "quadratic_attenuation": 0.05})";
          const std::string mats = R"("m": {"emission": [0.05, 0, 0], "diffuse": [0.8, 0.5, 0.3], "specular": [0.7, 0.7, 0.7],
                 "shininess": 50, "specular_unit": ")" + unit + R"(",
                 "normalization": {"model": "blinn"}},
               "plain": {"diffuse": [0.3, 0.6, 0.3], "specular": [0.4, 0.4, 0.4], "shininess": 200,
                 "specular_unit": ")" + unit + R"("},
               "matte": {"diffuse": [0.6, 0.6, 0.6]})";
          const std::string objs = objects(mode, n % 2 ? "phong" : "gouraud", n % 3 == 0 ? "matte" : "plain");
          const std::string lm = std::string(R"({"reflection": ")") + reflection + R"(", "local_viewer": )" + viewer + "}";
          SCOPED_TRACE(unit + " " + reflection + " local_viewer=" + viewer + " " + mode);
          expect_full_identical(parse(make(lights, mats, objs, lm)), 48, 40);
          ++n;
        }
  // Mono, one point light without attenuation, no ambient.
  expect_full_identical(parse(make(R"({"position": [1, 2, 3, 1]})",
                                   R"("m": {"ambient": [0, 0, 0], "diffuse": [0.5, 0.5, 0.5], "specular": [0.5, 0.5, 0.5], "shininess": 20})",
                                   objects("phong", "flat"), R"({"ambient": [0, 0, 0]})")));
}

// The identity above can fail: the full core renders what its registers say. Light 0 of diffuse.json
// (directional) programmed as a point light changes the image; a unit 'full' lacks is a clear error.
TEST(RenderFullCore, ModeRegistersDecide) {
  const auto l = load("diffuse.json");
  const Frame spec = frame(l, false);
  Frame full = frame(l, true);
  bool changed = false;
  for (auto& c : full.groups[0].cmds)
    if (c.is_write && c.w.addr == kReg_light_mode) {
      EXPECT_EQ(c.w.data, light_mode_word(true, LightKind::Directional));
      c.w.data = light_mode_word(true, LightKind::Point);
      changed = true;
    }
  ASSERT_TRUE(changed);
  EXPECT_GT(render::mismatching_pixels(cmodel_image(spec), cmodel_image(full)), 100u);
  const std::string objs = objects("phong", "phong");
  const auto div = parse(make(R"({"position": [0, 1, 1, 0]})",
                              R"("m": {"diffuse": [0.6, 0.6, 0.6], "specular": [1, 1, 1], "specular_unit": "schlick_div"})",
                              objs));
  try {
    (void)frame(div, true);
    ADD_FAILURE() << "schlick_div on the full core";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("lacks the unit schlick_div"), std::string::npos) << e.what();
  }
}

// flat_rule provoking_vertex (issue 19): GL_FLAT's rule. Every pixel of a flat triangle (v0, vk, vk+1) has the
// colour the C model computes at vk+1 from that vertex's own fragment (its vertex normal and eye-space position,
// the fragment Gouraud sends for it), one fragment per distinct provoking vertex; the image differs from the
// centroid rule's (the default) under a point light and a local viewer, with the same coverage.
TEST(RenderFlatRule, ProvokingVertexIsTheLastVertexsColour) {
  const std::string lights = R"({"position": [1.5, 1, 2.5, 1], "diffuse": [0.9, 0.8, 0.7], "specular": [1, 1, 1]},
                                {"position": [-1, 1, 1, 0], "diffuse": [0.3, 0.3, 0.4]})";
  const std::string mats = R"("m": {"diffuse": [0.8, 0.5, 0.3], "specular": [0.6, 0.6, 0.6], "shininess": 30})";
  const std::string text = make(lights, mats, objects("flat", "flat"), R"({"local_viewer": true})");
  auto with_rule = [&text](const std::string& r) {
    std::string s = text;
    s.replace(s.find("\"image\""), 7, "\"flat_rule\": \"" + r + "\", \"image\"");
    return s;
  };
  const auto dflt = parse(text), cen = parse(with_rule("centroid")), pv = parse(with_rule("provoking_vertex"));
  EXPECT_EQ(dflt.sc.flat_rule, scene::FlatRule::Centroid);
  EXPECT_EQ(cen.sc.flat_rule, scene::FlatRule::Centroid);
  ASSERT_EQ(pv.sc.flat_rule, scene::FlatRule::ProvokingVertex);
  const Frame fd = frame(dflt, false), fc = frame(cen, false), fp = frame(pv, false);
  const auto id = cmodel_image(fd), ic = cmodel_image(fc), ip = cmodel_image(fp);
  EXPECT_EQ(id.code, ic.code);  // centroid is the default
  EXPECT_EQ(ic.covered, ip.covered);
  EXPECT_GT(covered(ip), 600u);
  EXPECT_GT(render::mismatching_pixels(ic, ip), covered(ip) / 2);

  // Fragments: no face fragment; one vertex fragment per distinct provoking vertex of a shown triangle.
  std::set<uint32_t> provoking;
  for (int y = 0; y < fp.height; ++y)
    for (int x = 0; x < fp.width; ++x)
      if (fp.raster.at(x, y) >= 0) provoking.insert(fp.tri_vertices[fp.raster.tris()[fp.raster.at(x, y)].source][2]);
  uint64_t faces = 0, vertices = 0;
  for (const auto& g : fp.groups) faces += g.faces, vertices += g.vertices;
  EXPECT_EQ(faces, 0u);
  EXPECT_EQ(vertices, provoking.size());

  // The C model's eval at each provoking vertex, on the vertex's own fragment, with the registers the stream
  // programs before it.
  std::map<uint32_t, Colour> at_vertex;
  for (const auto& g : fp.groups) {
    const LightCore core(g.fs);
    LightRegs regs;
    size_t k = 0;
    for (const auto& c : g.cmds) {
      if (c.is_write) {
        regs.write(core.widths(), c.w.addr, c.w.data);
        continue;
      }
      const render::Dest& d = g.dests.at(k++);
      ASSERT_EQ(d.kind, render::DestKind::Vertex);
      Colour col = core.eval(regs, fp.vertex_frag.at(d.index));
      if (g.specialised.channels == 1) col.c[1] = col.c[2] = col.c[0];
      at_vertex[d.index] = col;
    }
  }
  // The same geometry Gouraud-shaded: the same vertex fragments (normal and position of each vertex) and colours.
  Settings gs;
  gs.width = 96, gs.height = 64, gs.mode = scene::Shading::Gouraud;
  const Frame fg = render::prepare(pv.sc, pv.meshes, gs);
  ASSERT_EQ(fg.vertex_frag.size(), fp.vertex_frag.size());
  for (size_t v = 0; v < fp.vertex_frag.size(); ++v)
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(fg.vertex_frag[v].n[i], fp.vertex_frag[v].n[i]);
      ASSERT_EQ(fg.vertex_frag[v].p[i], fp.vertex_frag[v].p[i]);
    }
  std::map<uint32_t, Colour> gouraud;
  for (const auto& g : fg.groups) {
    const auto cols = render::run_cmodel(g);
    for (size_t i = 0; i < cols.size(); ++i) {
      Colour col = cols[i];
      if (g.specialised.channels == 1) col.c[1] = col.c[2] = col.c[0];
      if (g.dests[i].kind == render::DestKind::Vertex) gouraud[g.dests[i].index] = col;
    }
  }
  uint64_t checked = 0, not_v0 = 0;
  for (int y = 0; y < fp.height; ++y)
    for (int x = 0; x < fp.width; ++x) {
      const int32_t t = fp.raster.at(x, y);
      if (t < 0) continue;
      const auto& tv = fp.tri_vertices[fp.raster.tris()[t].source];
      const size_t p = static_cast<size_t>(y) * fp.width + x;
      Colour px;
      for (int ch = 0; ch < 3; ++ch) px.c[ch] = ip.code[p * 3 + ch];
      ASSERT_EQ(px, at_vertex.at(tv[2])) << "pixel (" << x << ", " << y << ")";
      ASSERT_EQ(px, gouraud.at(tv[2])) << "pixel (" << x << ", " << y << ")";
      not_v0 += px != gouraud.at(tv[0]);
      ++checked;
    }
  EXPECT_EQ(checked, covered(ip));
  EXPECT_GT(not_v0, checked / 2);  // the last vertex, not the first
}

// ---- GL_LIGHT_MODEL_TWO_SIDE (issue 19) -----------------------------------------------------------------

TEST(RenderTwoSide, ParsesTheKeysWithTheirDefaults) {
  const std::string mats = R"("m": {"ambient": [0.3, 0.2, 0.1], "diffuse": [0.8, 0.5, 0.3], "specular": [0.6, 0.6, 0.6],
                                    "shininess": 30, "back": {"diffuse": [0.1, 0.7, 0.2], "emission": [0, 0, 0.1]}},
                              "n": {"diffuse": [0.5, 0.5, 0.5], "back": {"shininess": 16}})";
  const auto a = parse(make(R"({"position": [0, 1, 1, 0]})", mats, objects("gouraud", "flat", "n"), R"({"two_side": true})"));
  EXPECT_TRUE(a.sc.two_side);
  const auto& m = a.sc.materials.at(0);
  ASSERT_TRUE(m.back.has_value());
  EXPECT_EQ(m.back->diffuse, (scene::Vec3{0.1, 0.7, 0.2}));
  EXPECT_EQ(m.back->emission, (scene::Vec3{0, 0, 0.1}));
  EXPECT_EQ(m.back->ambient, m.ambient);    // a key not given: the front's
  EXPECT_EQ(m.back->specular, m.specular);
  EXPECT_EQ(m.back->shininess, 30);
  const auto& n = a.sc.materials.at(1);
  ASSERT_TRUE(n.back.has_value());          // only the (equal) shininess given: the front's colours
  EXPECT_EQ(n.back->diffuse, n.diffuse);
  const auto b = parse(make(R"({"position": [0, 1, 1, 0]})", R"("m": {"diffuse": [0.8, 0.5, 0.3]})", objects("phong", "phong"),
                            R"({"two_side": false})"));
  EXPECT_FALSE(b.sc.two_side);
  EXPECT_FALSE(b.sc.materials[0].back.has_value());
  const auto bf = b.sc.materials[0].back_or_front();  // no "back": the front's colours (GL_FRONT_AND_BACK)
  EXPECT_EQ(bf.diffuse, b.sc.materials[0].diffuse);
  EXPECT_EQ(bf.shininess, b.sc.materials[0].shininess);
  EXPECT_FALSE(parse(make(R"({"position": [0, 1, 1, 0]})", R"("m": {})", objects("phong", "phong"))).sc.two_side);
}

TEST(RenderTwoSide, DerivationCountsTheBackColours) {
  const std::string lights = R"({"position": [0, 1, 1, 0], "specular": [1, 1, 1]})";
  // grey front without specular, a coloured specular back
  const std::string mats = R"("m": {"diffuse": [0.5, 0.5, 0.5], "back": {"specular": [0.2, 0.5, 0.7]}})";
  const auto on = parse(make(lights, mats, objects("gouraud", "gouraud"), R"({"two_side": true})"));
  const auto off = parse(make(lights, mats, objects("gouraud", "gouraud"), R"({"two_side": false})"));
  const Frame fon = frame(on, false), foff = frame(off, false);
  ASSERT_EQ(fon.groups.size(), 1u);
  ASSERT_EQ(foff.groups.size(), 1u);
  EXPECT_TRUE(fon.groups[0].fs.two_side);
  EXPECT_TRUE(fon.groups[0].fs.specular);
  EXPECT_EQ(fon.groups[0].fs.channels, 3);
  EXPECT_FALSE(foff.groups[0].fs.two_side);  // without two_side the back colours never reach the core
  EXPECT_FALSE(foff.groups[0].fs.specular);
  EXPECT_EQ(foff.groups[0].fs.channels, 1);
  // the full core has two_side (config/configs.json 'full'): the same image
  expect_full_identical(on);
  const Frame full = frame(on, true);
  EXPECT_TRUE(full.groups[0].fs.two_side);
}

// A plane turned away from the camera under two_side with back material B gives the image of the plane facing the
// camera with front material B: −N of the turned plane is the facing plane's N, and under a directional light and
// the infinite viewer the position does not matter (every vertex, face and pixel has one colour). Every mode.
TEST(RenderTwoSide, BackFaceIsTheFrontOfTheTurnedPlane) {
  const std::string lights = R"({"position": [0.3, 0.5, 1, 0], "diffuse": [0.9, 0.8, 0.7], "specular": [1, 1, 1]})";
  const std::string mats = R"("b": {"emission": [0.05, 0, 0.1], "ambient": [0.2, 0.4, 0.3], "diffuse": [0.3, 0.6, 0.5],
                                    "specular": [0.4, 0.5, 0.6], "shininess": 24},
                              "fb": {"ambient": [0.5, 0.1, 0.1], "diffuse": [0.9, 0.2, 0.1], "specular": [0.1, 0.1, 0.1],
                                     "shininess": 24, "back": {"emission": [0.05, 0, 0.1], "ambient": [0.2, 0.4, 0.3],
                                     "diffuse": [0.3, 0.6, 0.5], "specular": [0.4, 0.5, 0.6]}})";
  auto plane = [](const std::string& mat, const std::string& shading, double angle) {
    return R"({"type": "plane", "size": [2.4, 1.6], "subdivisions": 3, "material": ")" + mat + R"(", "shading": ")" +
           shading + R"(", "transform": {"rotate": [)" + std::to_string(angle) + R"(, 0, 1, 0]}})";
  };
  for (const std::string rule : {"centroid", "provoking_vertex"})
    for (const std::string sh : {"flat", "gouraud", "phong"}) {
      if (rule != "centroid" && sh != "flat") continue;
      SCOPED_TRACE(sh + " " + rule);
      auto with_rule = [&rule](std::string s) { return s.replace(s.find("\"image\""), 7, "\"flat_rule\": \"" + rule + "\", \"image\""); };
      const auto turned = parse(with_rule(make(lights, mats, plane("fb", sh, 180), R"({"two_side": true})")));
      const auto facing = parse(with_rule(make(lights, mats, plane("b", sh, 0), R"({"two_side": true})")));
      const auto one_sided = parse(with_rule(make(lights, mats, plane("fb", sh, 180))));
      const Frame ft = frame(turned, false), ff = frame(facing, false), fo = frame(one_sided, false);
      const auto it = cmodel_image(ft), iff = cmodel_image(ff), io = cmodel_image(fo);
      EXPECT_GT(covered(it), 500u);
      EXPECT_EQ(it.covered, iff.covered);
      EXPECT_EQ(render::mismatching_pixels(it, iff), 0u);
      // every fragment of the turned plane is a back fragment; none without two_side
      for (const auto& g : ft.groups)
        for (size_t i = 0; i < g.dests.size(); ++i) EXPECT_TRUE(g.dests[i].back);
      size_t back_cmds = 0;
      for (const auto& g : fo.groups)
        for (const auto& c : g.cmds) back_cmds += !c.is_write && c.f.back;
      EXPECT_EQ(back_cmds, 0u);
      EXPECT_EQ(render::mismatching_pixels(it, io), covered(it));  // one-sided: the front material, lit with +N
      // the double reference (the unit's own formula) lights the back fragments alike: quantisation only
      std::vector<std::vector<render::RefColour>> ref;
      for (const auto& g : ft.groups) ref.push_back(render::run_reference(g, LightCore::SpecRef::Variant));
      EXPECT_LT(render::error_vs(it, render::resolve_reference(ft, ref)).max_lsb, 16.0);
      expect_full_identical(turned);
    }
}

// Gouraud: a vertex on a silhouette is seen by front- and back-facing triangles and is lit for both faces; each
// pixel takes the colours of its triangle's facing. A fold: triangle A faces the camera, B shares A's edge and folds
// over it towards the camera, so B is seen from behind (clockwise in the window) and covers part of A.
TEST(RenderTwoSide, GouraudFoldVerticesGetBothFragments) {
  const std::string obj = (std::filesystem::temp_directory_path() /
                           ("shadecore_fold_" + std::to_string(::getpid()) + ".obj")).string();
  std::ofstream(obj) << "v -1 -1 0\nv 1 -1 0\nv -1 1 0\nv -0.6 -0.6 1.5\nf 1 2 3\nf 3 2 4\n";
  const std::string lights = R"({"position": [0.2, 0.3, 1, 0], "diffuse": [0.8, 0.8, 0.8], "specular": [0.5, 0.5, 0.5]})";
  const std::string mats = R"("m": {"diffuse": [0.8, 0.4, 0.2], "specular": [0.3, 0.3, 0.3], "shininess": 20,
                                    "back": {"diffuse": [0.2, 0.5, 0.8]}})";
  const std::string object = R"({"type": "mesh", "file": ")" + obj + R"(", "material": "m", "shading": "gouraud"})";
  const auto l = parse(make(lights, mats, object, R"({"two_side": true})"));
  std::remove(obj.c_str());
  const Frame fr = frame(l, false);
  std::map<uint32_t, int> sides;
  for (const auto& d : fr.groups.at(0).dests) sides[d.index] |= d.back ? 2 : 1;
  ASSERT_EQ(sides.size(), 4u);
  int both = 0;
  for (const auto& [v, s] : sides) both += s == 3;
  EXPECT_EQ(both, 2);  // the shared edge's two vertices: a front and a back fragment each
  std::set<bool> facings;
  for (const auto& st : fr.raster.tris()) facings.insert(st.back);
  EXPECT_EQ(facings.size(), 2u);  // both triangles are seen
  const auto img = cmodel_image(fr);
  std::vector<std::vector<render::RefColour>> ref{render::run_reference(fr.groups[0], LightCore::SpecRef::Variant)};
  EXPECT_LT(render::error_vs(img, render::resolve_reference(fr, ref)).max_lsb, 16.0);
  expect_full_identical(l);
}

// The tube of gl_two_side.json: its inside (back faces) and its rim.
TEST(RenderTwoSide, GouraudRimVerticesGetBothFragments) {
  const auto l = load("gl_two_side.json");
  ASSERT_TRUE(l.sc.two_side);
  const Frame fr = frame(l, false, 160, 100);
  std::map<uint32_t, int> sides;  // vertex -> bit 0 front, bit 1 back
  for (const auto& g : fr.groups)
    for (const auto& d : g.dests) {
      ASSERT_EQ(d.kind, render::DestKind::Vertex);
      sides[d.index] |= d.back ? 2 : 1;
    }
  int both = 0, back_only = 0;
  for (const auto& [v, s] : sides) both += s == 3, back_only += s == 2;
  EXPECT_GE(both, 1);  // the silhouette meets the open rim at a few vertices
  EXPECT_GT(back_only, 10);
  // the fragments a pixel's triangle needs exist for its facing
  for (int y = 0; y < fr.height; ++y)
    for (int x = 0; x < fr.width; ++x) {
      const int32_t id = fr.raster.at(x, y);
      if (id < 0) continue;
      const auto& st = fr.raster.tris()[id];
      for (uint32_t v : fr.tri_vertices[st.source]) ASSERT_TRUE(sides[v] & (st.back ? 2 : 1));
    }
  expect_full_identical(l, 160, 100);
}

// A back shininess of its own (tests/data/render/gl_two_side_shininess.json: tube front 32 / back 8, cards front 32 /
// back 100): the core holds one unit material, so each material's back-facing fragments come in a batch of their own
// after the back's unit material (mat_n written twice per material). Every fragment is lit with its face's
// shininess, the double reference follows the same register state, and the image differs from the same scene with
// back shininess = front in back-facing pixels only.
TEST(RenderTwoSide, BackShininessGetsABatchOfItsOwn) {
  Loaded l = load_file(test_data("gl_two_side_shininess.json"));
  ASSERT_TRUE(l.sc.two_side);
  ASSERT_EQ(l.sc.materials.size(), 2u);
  std::set<int> back_n;
  for (const auto& m : l.sc.materials) {
    ASSERT_TRUE(m.back.has_value());
    EXPECT_NE(m.back->shininess, m.shininess);
    back_n.insert(m.back->shininess);
  }
  // the same scene, back shininess = front: one batch per material (the stream as before back shininess existed)
  Loaded same = l;
  for (auto& m : same.sc.materials) m.back->shininess = m.shininess;
  const Frame fr = frame(l, false), fs = frame(same, false);
  ASSERT_EQ(fr.groups.size(), 1u);
  ASSERT_EQ(fs.groups.size(), 1u);
  EXPECT_TRUE(fr.groups[0].fs.low_shininess);  // the back's 8: the chain, derived from the back material
  EXPECT_FALSE(fs.groups[0].fs.low_shininess);
  // mat_n writes, and the value each fragment is lit with, per facing
  auto walk = [](const render::CoreGroup& g, std::set<uint32_t> (&seen)[2]) {
    int writes = 0;
    uint32_t n = ~0u;
    bool was_back = false;
    int switches = 0;
    for (const auto& c : g.cmds) {
      if (c.is_write) {
        if (c.w.addr == kReg_mat_n) n = c.w.data, ++writes;
        continue;
      }
      seen[c.f.back ? 1 : 0].insert(n);
      switches += c.f.back != was_back;
      was_back = c.f.back;
    }
    return std::pair<int, int>{writes, switches};
  };
  std::set<uint32_t> seen[2], seen_same[2];
  const auto [writes, switches] = walk(fr.groups[0], seen);
  const auto [writes_same, switches_same] = walk(fs.groups[0], seen_same);
  EXPECT_EQ(writes, 4);       // two materials, each front then back
  EXPECT_EQ(writes_same, 2);  // one per material
  EXPECT_EQ(switches, 3);     // front, back, front, back: the facings never interleave within a material
  EXPECT_GT(switches_same, switches);
  EXPECT_EQ(seen[0], (std::set<uint32_t>{32}));
  EXPECT_EQ(seen[1], (std::set<uint32_t>{8, 100}));
  EXPECT_EQ(seen_same[1], (std::set<uint32_t>{32}));
  // the same fragments (reordered): each destination once
  EXPECT_EQ(fr.groups[0].dests.size(), fs.groups[0].dests.size());
  const auto img = cmodel_image(fr), img_same = cmodel_image(fs);
  EXPECT_EQ(img.covered, img_same.covered);
  uint64_t back_px = 0, differ = 0;
  for (int y = 0; y < fr.height; ++y)
    for (int x = 0; x < fr.width; ++x) {
      const int32_t id = fr.raster.at(x, y);
      if (id < 0) continue;
      const size_t p = static_cast<size_t>(y) * fr.width + x;
      bool d = false;
      for (int c = 0; c < 3; ++c) d = d || img.code[p * 3 + c] != img_same.code[p * 3 + c];
      const bool back = fr.raster.tris()[id].back;
      back_px += back;
      differ += d;
      if (!back) {
        EXPECT_FALSE(d) << x << "," << y;  // front-facing pixels: the front's shininess either way
      }
    }
  EXPECT_GT(back_px, 500u);
  EXPECT_GT(differ, back_px / 2);
  // the double reference sees the register state of each fragment: quantisation only
  std::vector<std::vector<render::RefColour>> ref;
  for (const auto& g : fr.groups) ref.push_back(render::run_reference(g, LightCore::SpecRef::Variant));
  EXPECT_LT(render::error_vs(img, render::resolve_reference(fr, ref)).max_lsb, 16.0);
  expect_full_identical(l);
}

// The back batch under colour material (tests/data/render/gl_colour_material_flat.json, two-sided, every object flat
// under provoking_vertex, with back shininess 6 and 90 added): each fragment is lit with its object's colour material
// mode and its facing's shininess — the back batch writes each mode's colour_material word again.
TEST(RenderTwoSide, BackBatchKeepsEachObjectsColourMaterial) {
  Loaded l = load_file(test_data("gl_colour_material_flat.json"));
  ASSERT_TRUE(l.sc.two_side);
  ASSERT_EQ(l.sc.materials.size(), 2u);
  const int back_n[2] = {6, 90};
  for (int m = 0; m < 2; ++m) {
    scene::BackMaterial b = l.sc.materials[m].back_or_front();
    b.shininess = back_n[m];
    l.sc.materials[m].back = b;
  }
  const Frame fr = frame(l, false, 160, 110);
  ASSERT_EQ(fr.groups.size(), 1u);
  const auto& g = fr.groups[0];
  ASSERT_TRUE(g.fs.colour_material);
  uint32_t n = ~0u, cm = ~0u;
  size_t checked[2] = {0, 0}, i = 0;
  for (const auto& c : g.cmds) {
    if (c.is_write) {
      if (c.w.addr == kReg_mat_n) n = c.w.data;
      if (c.w.addr == kReg_colour_material) cm = c.w.data;
      continue;
    }
    const auto& d = g.dests[i++];
    ASSERT_EQ(d.kind, render::DestKind::Vertex);
    const auto& o = l.sc.objects[static_cast<size_t>(fr.vertex_object[d.index])];
    const auto& M = l.sc.materials[static_cast<size_t>(o.material)];
    EXPECT_EQ(cm, o.colour_material ? colour_material_word(true, *o.colour_material) : 0u) << i;
    EXPECT_EQ(n, static_cast<uint32_t>(d.back ? M.back->shininess : M.shininess)) << i;
    ++checked[d.back ? 1 : 0];
  }
  EXPECT_GT(checked[0], 100u);
  EXPECT_GT(checked[1], 20u);
}

// ---- GL_COLOR_MATERIAL (issue 19) -----------------------------------------------------------------------

std::string temp_obj(const std::string& name, const std::string& text) {
  const std::string p = (std::filesystem::temp_directory_path() /
                         ("shadecore_" + name + "_" + std::to_string(::getpid()) + ".obj")).string();
  std::ofstream(p) << text;
  return p;
}

// A unit quad facing the camera, one face (v0 v1 v2 v3: fan triangles (v0, v1, v2) and (v0, v2, v3)) with a colour
// per vertex.
const scene::Vec3 kQuadColour[4] = {{0.9, 0.1, 0.1}, {0.1, 0.8, 0.2}, {0.2, 0.3, 0.9}, {0.7, 0.7, 0.1}};
std::string quad_obj() {
  std::string t;
  const char* xy[4] = {"-1 -1", "1 -1", "1 1", "-1 1"};
  for (int v = 0; v < 4; ++v)
    t += std::string("v ") + xy[v] + " 0 " + std::to_string(kQuadColour[v][0]) + " " + std::to_string(kQuadColour[v][1]) +
         " " + std::to_string(kQuadColour[v][2]) + "\n";
  return t + "vn 0 0 1\nf 1//1 2//1 3//1 4//1\n";
}
// The quad under colour material `emission` with a black material and no lights' colours: each fragment's colour is
// its colour code exactly (the core adds zeros), so the image shows what colour reached each pixel.
std::string emission_quad(const std::string& shading, const std::string& rule = "centroid") {
  std::string s = make(R"({"position": [0, 0, 1, 0], "diffuse": [0, 0, 0], "specular": [0, 0, 0]})",
                       R"("black": {"ambient": [0, 0, 0], "diffuse": [0, 0, 0]})",
                       R"({"type": "mesh", "file": ")" + temp_obj("cm_quad", quad_obj()) +
                           R"(", "material": "black", "color_material": "emission", "shading": ")" + shading + R"("})",
                       R"({"ambient": [0, 0, 0]})");
  return s.replace(s.find("\"image\""), 7, "\"flat_rule\": \"" + rule + "\", \"image\"");
}
uint32_t code16(double x) { return static_cast<uint32_t>(std::llround(std::ldexp(x, 16))); }

TEST(RenderColourMaterial, ParsesTheKeysWithTheirDefaults) {
  const std::string lights = R"({"position": [0, 1, 1, 0]})";
  const auto d = parse(make(lights, R"("m": {})", objects("gouraud", "flat")));
  for (const auto& o : d.sc.objects) {
    EXPECT_FALSE(o.colour_material.has_value());                // none
    EXPECT_EQ(o.colour, (scene::Vec3{1, 1, 1}));                // GL's initial current colour
  }
  const std::pair<const char*, ColourMaterial> modes[] = {
      {"emission", ColourMaterial::Emission}, {"ambient", ColourMaterial::Ambient}, {"diffuse", ColourMaterial::Diffuse},
      {"specular", ColourMaterial::Specular}, {"ambient_and_diffuse", ColourMaterial::AmbientAndDiffuse}};
  for (const auto& [name, mode] : modes) {
    const auto l = parse(make(lights, R"("m": {})", R"({"type": "sphere", "material": "m", "color_material": ")" +
                                                      std::string(name) + R"(", "color": [0.25, 0.5, 1]})"));
    ASSERT_TRUE(l.sc.objects[0].colour_material.has_value());
    EXPECT_EQ(*l.sc.objects[0].colour_material, mode);
    EXPECT_STREQ(scene::to_string(l.sc.objects[0].colour_material), name);
    EXPECT_EQ(l.sc.objects[0].colour, (scene::Vec3{0.25, 0.5, 1}));
  }
  const auto n = parse(make(lights, R"("m": {})", R"({"type": "sphere", "material": "m", "color_material": "none"})"));
  EXPECT_FALSE(n.sc.objects[0].colour_material.has_value());
}

// Each mode replaces exactly its material term(s): the sphere of material m under colour material with colour C
// renders identically to the sphere of m with those terms set to C and colour material off, in every shading mode;
// and differs from m's own sphere (C reaches the core). Both faces of the material (GL_FRONT_AND_BACK) under two_side.
TEST(RenderColourMaterial, EachModeIsTheMaterialTermReplaced) {
  const std::string lights = R"({"position": [0.5, 0.8, 1, 0], "ambient": [0.1, 0.1, 0.1], "diffuse": [0.8, 0.8, 0.8],
                                 "specular": [1, 1, 1]},
                                {"position": [-2, 1, 3, 1], "diffuse": [0.3, 0.3, 0.3], "specular": [0.5, 0.5, 0.5]})";
  const std::string m = R"("emission": [0.05, 0.05, 0.05], "ambient": [0.3, 0.3, 0.3], "diffuse": [0.6, 0.6, 0.6],
                           "specular": [0.4, 0.4, 0.4], "shininess": 24)";
  const std::string C = "[0.7, 0.2, 0.45]";
  struct Mode {
    const char* name;
    std::vector<const char*> terms;
  };
  const Mode modes[] = {{"emission", {"emission"}}, {"ambient", {"ambient"}}, {"diffuse", {"diffuse"}},
                        {"specular", {"specular"}}, {"ambient_and_diffuse", {"ambient", "diffuse"}}};
  for (const std::string sh : {"flat", "gouraud", "phong"})
    for (const bool two_side : {false, true})
      for (const auto& md : modes) {
        SCOPED_TRACE(sh + " " + md.name + (two_side ? " two_side" : ""));
        std::string replaced = m;
        for (const char* t : md.terms) {
          const std::string key = std::string("\"") + t + "\": ";
          const size_t a = replaced.find(key) + key.size(), b = replaced.find(']', a) + 1;
          replaced.replace(a, b - a, C);
        }
        const std::string lm = two_side ? R"({"ambient": [0.2, 0.2, 0.2], "two_side": true})" : "";
        auto sphere = [&](const std::string& mat, const std::string& extra) {
          return R"({"type": "sphere", "slices": 14, "stacks": 8, "material": ")" + mat + R"(", "shading": ")" + sh +
                 R"(", "transform": {"rotate": [70, 1, 0.3, 0]})" + extra + "}";
        };
        const auto cm = parse(make(lights, "\"m\": {" + m + "}",
                                   sphere("m", std::string(R"(, "color_material": ")") + md.name + R"(", "color": )" + C), lm));
        const auto set = parse(make(lights, "\"c\": {" + replaced + "}", sphere("c", ""), lm));
        const auto own = parse(make(lights, "\"m\": {" + m + "}", sphere("m", R"(, "color": )" + C), lm));
        const Frame fc = frame(cm, false), fs = frame(set, false), fo = frame(own, false);
        ASSERT_EQ(fc.groups.size(), 1u);
        EXPECT_TRUE(fc.groups[0].fs.colour_material);
        EXPECT_FALSE(fs.groups[0].fs.colour_material);
        EXPECT_FALSE(fo.groups[0].fs.colour_material);  // `color` alone does nothing
        const auto ic = cmodel_image(fc), is = cmodel_image(fs), io = cmodel_image(fo);
        EXPECT_GT(covered(ic), 300u);
        EXPECT_EQ(ic.covered, is.covered);
        EXPECT_EQ(render::mismatching_pixels(ic, is), 0u);
        EXPECT_GT(render::mismatching_pixels(ic, io), covered(ic) / 4);
        // the exact reference uses the same fragment colours
        std::vector<std::vector<render::RefColour>> rc, rs;
        for (const auto& g : fc.groups) rc.push_back(render::run_reference(g, LightCore::SpecRef::Exact));
        for (const auto& g : fs.groups) rs.push_back(render::run_reference(g, LightCore::SpecRef::Exact));
        EXPECT_EQ(render::resolve_reference(fc, rc).value, render::resolve_reference(fs, rs).value);
        if (!two_side && sh == "gouraud") expect_full_identical(cm);
      }
}

// Per-vertex colours (OBJ `v x y z r g b`): Gouraud lights each vertex with its colour and interpolates the
// results; Phong interpolates the colour per pixel (as N and P) and lights it. With emission only, both show the
// interpolated colour codes: the same image, the vertex colours at the corners and their mean at the centre.
TEST(RenderColourMaterial, VertexColoursInterpolatedGouraudAndPhong) {
  const auto g = parse(emission_quad("gouraud")), p = parse(emission_quad("phong"));
  ASSERT_EQ(g.meshes[0].col.size(), 4u);
  const Frame fg = frame(g, false), fp = frame(p, false);
  ASSERT_EQ(fg.vertex_frag.size(), 4u);
  for (size_t v = 0; v < 4; ++v)  // vertices keep the OBJ order (one normal): each carries its colour
    for (int c = 0; c < 3; ++c) EXPECT_EQ(fg.vertex_frag[v].col[c], code16(kQuadColour[v][c]));
  EXPECT_EQ(fg.groups[0].vertices, 4u);
  EXPECT_GT(fp.groups[0].pixels, 500u);
  const auto ig = cmodel_image(fg), ip = cmodel_image(fp);
  EXPECT_EQ(ig.covered, ip.covered);
  EXPECT_EQ(render::mismatching_pixels(ig, ip), 0u);
  std::set<std::array<uint32_t, 3>> distinct;
  for (size_t px = 0; px < ig.covered.size(); ++px)
    if (ig.covered[px]) distinct.insert({ig.code[px * 3], ig.code[px * 3 + 1], ig.code[px * 3 + 2]});
  EXPECT_GT(distinct.size(), 200u);
  // every pixel: the perspective-correct interpolation of its triangle's vertex colours, computed here in double
  // from the rasteriser's weights (within 2^-14: the codes' rounding)
  uint64_t checked = 0;
  for (int y = 0; y < fg.height; ++y)
    for (int x = 0; x < fg.width; ++x) {
      const int32_t t = fg.raster.at(x, y);
      if (t < 0) continue;
      const auto& st = fg.raster.tris()[t];
      const auto& tv = fg.tri_vertices[st.source];
      const raster::Weights w = fg.raster.weights(t, x, y);
      for (int ch = 0; ch < 3; ++ch) {
        double want = 0;
        for (int k = 0; k < 3; ++k)
          for (int q = 0; q < 3; ++q)
            want += static_cast<double>(w.w[k]) / static_cast<double>(w.sum) * st.v[k].b[q] * kQuadColour[tv[q]][ch];
        ASSERT_NEAR(std::ldexp(ig.code[(static_cast<size_t>(y) * fg.width + x) * 3 + ch], -16), want, 1.0 / (1 << 14))
            << "pixel (" << x << ", " << y << ") channel " << ch;
      }
      ++checked;
    }
  EXPECT_EQ(checked, covered(ig));
}

// Flat: flat_rule centroid lights the face with the mean of its vertices' colours; provoking_vertex each fan
// triangle with its last vertex's colour (v2 for (v0, v1, v2), v3 for (v0, v2, v3)).
TEST(RenderColourMaterial, FlatRulesPickTheColour) {
  const auto cen = parse(emission_quad("flat")), pv = parse(emission_quad("flat", "provoking_vertex"));
  const Frame fc = frame(cen, false), fp = frame(pv, false);
  const auto ic = cmodel_image(fc), ip = cmodel_image(fp);
  EXPECT_GT(covered(ic), 500u);
  std::array<uint32_t, 3> mean{};
  for (int ch = 0; ch < 3; ++ch)
    mean[ch] = code16((kQuadColour[0][ch] + kQuadColour[1][ch] + kQuadColour[2][ch] + kQuadColour[3][ch]) / 4);
  std::map<std::array<uint32_t, 3>, uint64_t> cc, cp;
  for (size_t px = 0; px < ic.covered.size(); ++px) {
    if (ic.covered[px]) ++cc[{ic.code[px * 3], ic.code[px * 3 + 1], ic.code[px * 3 + 2]}];
    if (ip.covered[px]) ++cp[{ip.code[px * 3], ip.code[px * 3 + 1], ip.code[px * 3 + 2]}];
  }
  ASSERT_EQ(cc.size(), 1u);
  EXPECT_EQ(cc.begin()->first, mean);
  auto code_of = [](int v) {
    return std::array<uint32_t, 3>{code16(kQuadColour[v][0]), code16(kQuadColour[v][1]), code16(kQuadColour[v][2])};
  };
  ASSERT_EQ(cp.size(), 2u);
  EXPECT_GT(cp[code_of(2)], 200u);
  EXPECT_GT(cp[code_of(3)], 200u);
  EXPECT_EQ(fc.groups[0].faces, 1u);
  for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(fc.face_frag[0].col[ch], mean[ch]);
}

// The derivation turns colour_material on only for a core that has an object with a colour material, and the
// object's colours count instead of the replaced material terms; streams without colour material neither write
// the register nor carry a colour; with it the register is written before each mode's fragments.
TEST(RenderColourMaterial, DerivationAndStream) {
  const std::string lights = R"({"position": [0, 1, 1, 0], "specular": [1, 1, 1]})";
  const std::string grey = R"("m": {"diffuse": [0.5, 0.5, 0.5], "specular": [0.3, 0.3, 0.3]},
                              "s": {"diffuse": [0.5, 0.5, 0.5], "specular": [0.3, 0.3, 0.3], "specular_unit": "schlick_nr"},
                              "d": {"diffuse": [0.5, 0.5, 0.5]})";
  auto sph = [](const std::string& mat, const std::string& keys, double x) {
    return R"({"type": "sphere", "slices": 12, "stacks": 8, "material": ")" + mat + R"(", "shading": "gouraud", )" + keys +
           R"("transform": {"translate": [)" + std::to_string(x) + R"(, 0, 0], "scale": 0.8}})";
  };
  // none: no capability, no register write, no colour
  {
    const auto l = parse(make(lights, grey, sph("m", R"("color": [1, 0, 0], )", -1) + "," + sph("s", "", 1)));
    const Frame fr = frame(l, false);
    ASSERT_EQ(fr.groups.size(), 2u);
    for (const auto& g : fr.groups) {
      EXPECT_FALSE(g.fs.colour_material);
      EXPECT_EQ(g.fs.channels, 1);
      for (const auto& c : g.cmds) {
        if (c.is_write) EXPECT_NE(c.w.addr, kReg_colour_material);
        else EXPECT_EQ(c.f.col[0] | c.f.col[1] | c.f.col[2], 0u);
      }
    }
  }
  // a coloured diffuse on the schlick core only: that core alone gets colour_material and RGB
  {
    const auto l = parse(make(lights, grey, sph("m", "", -1) + "," +
                                                sph("s", R"("color_material": "diffuse", "color": [0.2, 0.9, 0.4], )", 1)));
    const Frame fr = frame(l, false);
    ASSERT_EQ(fr.groups.size(), 2u);
    EXPECT_FALSE(fr.groups[0].fs.colour_material);
    EXPECT_EQ(fr.groups[0].fs.channels, 1);
    EXPECT_TRUE(fr.groups[1].fs.colour_material);
    EXPECT_EQ(fr.groups[1].fs.channels, 3);
  }
  // grey colours keep the core mono; specular through colour material builds the unit for a material without one
  {
    const auto l = parse(make(lights, grey, sph("d", R"("color_material": "specular", "color": [0.4, 0.4, 0.4], )", 0)));
    const Frame fr = frame(l, false);
    ASSERT_EQ(fr.groups.size(), 1u);
    EXPECT_TRUE(fr.groups[0].fs.colour_material);
    EXPECT_TRUE(fr.groups[0].fs.specular);
    EXPECT_EQ(fr.groups[0].fs.channels, 1);
    // a black colour replacing the only specular colour: no unit
    const auto k = parse(make(lights, grey, sph("s", R"("color_material": "specular", "color": [0, 0, 0], )", 0)));
    EXPECT_FALSE(frame(k, false).groups[0].fs.specular);
  }
  // one material, three objects: diffuse, none, emission; the register is written before each mode's fragments and
  // every fragment is lit with the mode of its object
  {
    const auto l = parse(make(lights, grey,
                              sph("m", R"("color_material": "diffuse", "color": [0.9, 0.2, 0.1], )", -1.8) + "," +
                                  sph("m", R"("color": [0.1, 0.9, 0.1], )", 0) + "," +
                                  sph("m", R"("color_material": "emission", "color": [0.1, 0.1, 0.6], )", 1.8)));
    const Frame fr = frame(l, false);
    ASSERT_EQ(fr.groups.size(), 1u);
    const auto& g = fr.groups[0];
    EXPECT_TRUE(g.fs.colour_material);
    uint32_t reg = ~0u;
    std::vector<uint32_t> words;
    size_t k = 0;
    for (const auto& c : g.cmds) {
      if (c.is_write) {
        if (c.w.addr == kReg_colour_material) reg = c.w.data, words.push_back(c.w.data);
        continue;
      }
      const int oi = fr.vertex_object.at(g.dests.at(k++).index);
      const auto& cmo = l.sc.objects[oi].colour_material;
      ASSERT_EQ(reg, cmo ? colour_material_word(true, *cmo) : 0u) << "object " << oi;
      const uint32_t want = cmo ? code16(l.sc.objects[oi].colour[0]) : 0u;
      EXPECT_EQ(c.f.col[0], want);
    }
    EXPECT_EQ(words, (std::vector<uint32_t>{0u, colour_material_word(true, ColourMaterial::Emission),
                                            colour_material_word(true, ColourMaterial::Diffuse)}));
    expect_full_identical(l);
  }
}

// Example scenes without colour material: every derived stream neither writes the colour_material register nor
// sends a colour (stream kinds 1 and 2 only: the same bytes as before the feature). gl_features.json: only the core of
// the colour-material wave (cs16) has it; the schlick_nr core's stream is as before.
TEST(RenderColourMaterial, ExampleScenesWithoutItUnchanged) {
  {
    const auto l = load("gl_features.json");
    const Frame fr = frame(l, false, 64, 48);
    ASSERT_EQ(fr.groups.size(), 2u);
    EXPECT_TRUE(fr.groups[0].fs.colour_material);
    EXPECT_FALSE(fr.groups[1].fs.colour_material);
    for (const auto& c : fr.groups[1].cmds) {
      if (c.is_write) EXPECT_NE(c.w.addr, kReg_colour_material);
      else EXPECT_EQ(c.f.col[0] | c.f.col[1] | c.f.col[2], 0u);
    }
  }
  for (const std::string name : {"diffuse.json", "spheres.json", "shading_modes.json", "mesh.json", "gl_two_side.json",
                                 "gl_shininess.json"}) {
    SCOPED_TRACE(name);
    const auto l = load(name);
    const Frame fr = frame(l, false, 64, 48);
    for (const auto& g : fr.groups) {
      EXPECT_FALSE(g.fs.colour_material);
      for (const auto& c : g.cmds) {
        if (c.is_write) EXPECT_NE(c.w.addr, kReg_colour_material);
        else EXPECT_EQ(c.f.col[0] | c.f.col[1] | c.f.col[2], 0u);
      }
    }
  }
}

// scenes/gl_colour_material.json: the full core renders it identically; OBJ vertex colours are read, and a file
// without them (or with `v x y z w`) has none.
TEST(RenderColourMaterial, ExampleSceneAndObjColours) {
  const auto l = load("gl_colour_material.json");
  const Frame fr = frame(l, false, 96, 64);
  ASSERT_EQ(fr.groups.size(), 1u);
  EXPECT_TRUE(fr.groups[0].fs.colour_material);
  EXPECT_EQ(l.meshes[0].col.size(), l.meshes[0].pos.size());
  EXPECT_TRUE(l.meshes[1].col.empty());  // a sphere: the object's `color`
  expect_full_identical(l);
  scene::Object o;
  o.type = scene::ObjectType::Mesh;
  o.file_path = temp_obj("cm_plain", "v 0 0 0\nv 1 0 0\nv 0 1 0 2\nf 1 2 3\n");
  EXPECT_TRUE(scene::build_mesh(o).col.empty());
  o.file_path = temp_obj("cm_col", "v 0 0 0 0.5 0.25 1\nv 1 0 0 0 0 0\nv 0 1 0 1 1 1\nf 1 2 3\n");
  const auto m = scene::build_mesh(o);
  ASSERT_EQ(m.col.size(), 3u);
  EXPECT_EQ(m.col[0], (scene::Vec3{0.5, 0.25, 1}));
  EXPECT_EQ(m.col[2], (scene::Vec3{1, 1, 1}));
}

TEST(RenderImage, DeterministicAndReferenceClose) {
  const auto l = load("shading_modes.json");
  const Frame a = frame(l, false, 120, 80), b = frame(l, false, 120, 80);
  const auto ia = cmodel_image(a), ib = cmodel_image(b);
  EXPECT_EQ(ia.code, ib.code);
  // Against the unit's own double formula the core is within a few LSB on average (quantisation only);
  // flat faces are one colour each.
  std::vector<std::vector<render::RefColour>> ud;
  for (const auto& g : a.groups) ud.push_back(render::run_reference(g, LightCore::SpecRef::Variant));
  const auto e = render::error_vs(ia, render::resolve_reference(a, ud));
  EXPECT_LT(e.mean_lsb, 8.0);
  EXPECT_GT(e.samples, 1000u);
}

TEST(RenderImage, SizeOverrideAndCoverage) {
  const auto l = load("diffuse.json");
  const Frame fr = frame(l, false, 33, 17);
  const auto img = cmodel_image(fr);
  EXPECT_EQ(img.width, 33);
  EXPECT_EQ(img.height, 17);
  EXPECT_EQ(img.code.size(), 33u * 17u * 3u);
  EXPECT_GT(covered(img), 100u);
}

}  // namespace

// shadecore replay --mesa: which pixels of a colour-only snapshot are covered (glref::snapshot_objects).
TEST(GlrefSnapshot, ClearColouredGeometryCountsAsCoveredOnlyWhereBothImagesShowTheClearColour) {
  const std::array<uint8_t, 3> bg{10, 20, 30};
  // pixel 0: the snapshot draws something there, the exact image object 3 -> covered by 3
  // pixel 1: both show the clear colour, the exact image's object 5 lit to exactly it -> covered by 5, counted
  // pixel 2: the snapshot shows the clear colour, the exact image object 5 in another colour -> not covered (a
  //          coverage difference stays one)
  // pixel 3: the snapshot draws something, the exact image nothing -> covered by "0" (a coverage difference)
  // pixel 4: background in both -> not covered
  const std::vector<uint8_t> snap{1, 2, 3, 10, 20, 30, 10, 20, 30, 9, 9, 9, 10, 20, 30};
  const std::vector<uint8_t> exact{1, 2, 3, 10, 20, 30, 10, 20, 31, 10, 20, 30, 10, 20, 30};
  const std::vector<int32_t> obj{3, 5, 5, -1, -1};
  uint64_t clear = 99;
  const std::vector<int32_t> got = glref::snapshot_objects(snap, bg, obj, exact, clear);
  EXPECT_EQ(got, (std::vector<int32_t>{3, 5, -1, 0, -1}));
  EXPECT_EQ(clear, 1u);
}

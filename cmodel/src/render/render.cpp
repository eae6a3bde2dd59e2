// SPDX-License-Identifier: Apache-2.0
// shadecore — scenes through the lighting core: geometry, feature-set derivation, command streams,
// image resolve and error statistics (see shadecore/render/render.hpp and docs/scenes.md).
#include "shadecore/render/render.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace shadecore::render {

using scene::Camera;
using scene::Scene;
using scene::SceneError;
using scene::Shading;
using scene::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

using Mat4 = std::array<double, 16>;  // row-major

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }
Mat4 mul(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[i * 4 + k] * b[k * 4 + j];
      r[i * 4 + j] = s;
    }
  return r;
}
std::array<double, 4> apply(const Mat4& m, const std::array<double, 4>& v) {
  std::array<double, 4> r{};
  for (int i = 0; i < 4; ++i) r[i] = m[i * 4] * v[0] + m[i * 4 + 1] * v[1] + m[i * 4 + 2] * v[2] + m[i * 4 + 3] * v[3];
  return r;
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
Vec3 unit(const Vec3& v) {
  const double l = norm(v);
  return {v[0] / l, v[1] / l, v[2] / l};
}

// gluLookAt
Mat4 look_at(const Camera& c) {
  const Vec3 f = unit({c.center[0] - c.eye[0], c.center[1] - c.eye[1], c.center[2] - c.eye[2]});
  const Vec3 s = unit(cross(f, c.up));
  const Vec3 u = cross(s, f);
  Mat4 m = {s[0], s[1], s[2], 0, u[0], u[1], u[2], 0, -f[0], -f[1], -f[2], 0, 0, 0, 0, 1};
  Mat4 t = identity();
  t[3] = -c.eye[0], t[7] = -c.eye[1], t[11] = -c.eye[2];
  return mul(m, t);
}
// gluPerspective
Mat4 perspective(const Camera& c, double aspect) {
  const double f = 1.0 / std::tan(c.fovy * kPi / 360.0);
  Mat4 m{};
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (c.far + c.near) / (c.near - c.far);
  m[11] = 2 * c.far * c.near / (c.near - c.far);
  m[14] = -1;
  return m;
}
// glTranslated · glRotated… · glScaled
Mat4 model_matrix(const scene::Transform& t) {
  Mat4 m = identity();
  m[3] = t.translate[0], m[7] = t.translate[1], m[11] = t.translate[2];
  for (const auto& r : t.rotate) {
    const Vec3 a = unit(r.axis);
    const double th = r.angle * kPi / 180.0, c = std::cos(th), s = std::sin(th), k = 1 - c;
    const Mat4 R = {a[0] * a[0] * k + c,        a[0] * a[1] * k - a[2] * s, a[0] * a[2] * k + a[1] * s, 0,
                    a[1] * a[0] * k + a[2] * s, a[1] * a[1] * k + c,        a[1] * a[2] * k - a[0] * s, 0,
                    a[2] * a[0] * k - a[1] * s, a[2] * a[1] * k + a[0] * s, a[2] * a[2] * k + c,        0,
                    0,                          0,                          0,                          1};
    m = mul(m, R);
  }
  Mat4 S = identity();
  S[0] = t.scale[0], S[5] = t.scale[1], S[10] = t.scale[2];
  return mul(m, S);
}
// Inverse transpose of the upper 3×3 (normals), via the cofactor matrix (scale does not matter: normals are
// normalised after).
std::array<double, 9> normal_matrix(const Mat4& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], i = m[10];
  return {e * i - f * h, -(d * i - f * g), d * h - e * g,
          -(b * i - c * h), a * i - c * g, -(a * h - b * g),
          b * f - c * e, -(a * f - c * d), a * e - b * d};
}
Vec3 apply3(const std::array<double, 9>& m, const Vec3& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

uint32_t colour_code(int F, double x) {
  return static_cast<uint32_t>(std::min(std::llround(std::ldexp(x, F)), (1ll << (F + 1)) - 1));
}
uint32_t attc_code(int F, double x) {
  return static_cast<uint32_t>(std::min(std::llround(std::ldexp(x, F)), (1ll << (F + kAttIntBits)) - 1));
}

std::string fmt3(const Vec3& v) {
  std::ostringstream ss;
  ss.precision(6);
  ss << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return ss.str();
}

// Normal codes the host sends: the unit normal rounded to the core's F+2-bit format, then passed through
// the core's own normaliser once. Its outputs are fixed points of it (checked), so a core with GL_NORMALIZE
// (the full core) computes the same N̂ as a core without.
std::array<int64_t, 3> normal_code(int F, const Vec3& n, bool* fixed_point) {
  const int64_t lim = int64_t{1} << (F + 1);
  int64_t c[3], u[3], w[3];
  for (int i = 0; i < 3; ++i) c[i] = std::clamp<int64_t>(std::llround(std::ldexp(n[i], F)), -lim, lim - 1);
  normalize3(F, c, u);
  normalize3(F, u, w);
  if (w[0] != u[0] || w[1] != u[1] || w[2] != u[2]) *fixed_point = false;
  return {u[0], u[1], u[2]};
}

bool pos_in_range(const Vec3& p) {
  for (double x : p)
    if (!(x >= -128.0 && x < 128.0)) return false;
  return true;
}

// The kind of slot a light needs: directional (w = 0), spot (a cone), point (no attenuation at the core's width) or
// point_att.
LightKind light_kind(int F, const scene::Light& L) {
  if (L.position[3] == 0.0) return LightKind::Directional;
  if (L.is_spot()) return LightKind::Spot;
  if (attc_code(F, L.kc) == (1u << F) && attc_code(F, L.kl) == 0 && attc_code(F, L.kq) == 0) return LightKind::Point;
  return LightKind::PointAtt;
}

}  // namespace

std::array<double, 16> view_matrix(const Camera& c) { return look_at(c); }

// The material `M` with the term(s) colour material mode `cm` names replaced by `c` (LightCore::side's choice).
static scene::Material with_colour_material(scene::Material M, ColourMaterial cm, const Vec3& c) {
  if (cm == ColourMaterial::Emission) M.emission = c;
  if (cm == ColourMaterial::Ambient || cm == ColourMaterial::AmbientAndDiffuse) M.ambient = c;
  if (cm == ColourMaterial::Diffuse || cm == ColourMaterial::AmbientAndDiffuse) M.diffuse = c;
  if (cm == ColourMaterial::Specular) M.specular = c;
  return M;
}

// ---- feature sets ---------------------------------------------------------------------------------

FeatureSet full_core_for(const FeatureSet& spec, std::vector<std::string>& subs) {
  FeatureSet f = feature_set_named_or_file("full");
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) throw std::runtime_error("the 'full' feature set of config/configs.json lacks " + what + " this scene needs");
  };
  need(f.num_lights() >= spec.num_lights(), std::to_string(spec.num_lights()) + " lights");
  need(!spec.ambient || f.ambient, "the ambient/emission term");
  need(!spec.diffuse || f.diffuse, "the diffuse term");
  need(!spec.specular || f.specular, "a specular unit");
  need(!spec.norm || f.norm, "energy normalisation");
  need(spec.channels <= f.channels, "RGB");
  for (int j = 0; j < spec.num_lights(); ++j)
    for (int k = 0; k < kNumLightKinds; ++k) {  // every kind of the slot (several when lighting states differ)
      const auto s = static_cast<LightKind>(k);
      if (!spec.slot_can(j, s)) continue;
      // A point light (kc = 1, kl = kq = 0) on a point_att slot: q = 1, att = recip_att(2^F) = 2^F exactly.
      need(f.slot_can(j, s) || (s == LightKind::Point && f.slot_can(j, LightKind::PointAtt)),
           "light slot " + std::to_string(j) + " of kind " + to_string(s));
    }
  need(!spec.normalize || f.normalize, "the normal normaliser (normalize)");
  need(!spec.two_side || f.two_side, "two-sided lighting (two_side)");
  need(!spec.colour_material || f.colour_material, "colour material (colour_material)");
  if (spec.specular) {
    // the two cs16 cut-offs give bit-identical outputs (docs/results.md): the cut-off needs no mode
    need(f.has_unit(spec.variant), std::string("the unit ") + std::string(variant_name(spec.variant)));
    need(!spec.blinn || f.blinn, "Blinn reflection");
    need(!spec.phong || f.phong, "Phong reflection");
    need(!spec.local_viewer || f.local_viewer, "the local viewer");
    need(!spec.low_shininess || f.low_shininess, "the low-shininess chain (shininess below 16)");
    need(!spec.separate_specular || f.separate_specular, "the separate specular colour");
  }
  // A width is not a mode: a scene of another config is rendered by the full set at that width.
  if (f.config != spec.config) {
    subs.push_back("config " + spec.config);
    f.config = spec.config;
  }
  return f;
}

// The kind light slot j of `fs` is programmed with for a light of kind `k` of the specialised set.
static LightKind slot_kind_for(const FeatureSet& fs, int j, LightKind k) {
  if (fs.slot_can(j, k)) return k;
  return LightKind::PointAtt;  // a point light on a point_att slot (kc = 1, kl = kq = 0: att = 1 exactly)
}

Derivation derive_features(const Scene& sc, const std::vector<int>& objects_used,
                           const std::vector<bool>& needs_normalize, bool full_core,
                           std::optional<VariantId> unit_override, int lanes, int share,
                           const std::vector<ObjectColours>& object_colours) {
  const int F = config_named(sc.config).format.frac;
  const size_t nm = sc.materials.size();
  // The lighting states (one for a scene file) and which materials each lights (through the objects drawn in it).
  const std::vector<scene::LightingSet> sets = sc.lighting_states();
  const size_t ns = sets.size();
  auto set_of = [ns](const scene::Object& O) {
    return static_cast<size_t>(std::clamp<int>(O.lighting, 0, static_cast<int>(ns) - 1));
  };
  std::vector<bool> used(nm, false);
  std::vector<std::vector<int>> mats_in_set(ns);  // per state the materials drawn in it (ascending, once)
  for (int o : objects_used) {
    used[sc.objects[o].material] = true;
    mats_in_set[set_of(sc.objects[o])].push_back(sc.objects[o].material);
  }
  for (auto& v : mats_in_set) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }

  auto nz = [F](const Vec3& c, int ch) { return colour_code(F, c[ch]) != 0; };
  auto light_spec = [&](int ch) {
    for (const auto& st : sets)
      for (const auto& l : st.lights)
        if (nz(l.specular, ch)) return true;
    return false;
  };
  auto is_grey = [F](const Vec3& c) {
    return colour_code(F, c[0]) == colour_code(F, c[1]) && colour_code(F, c[1]) == colour_code(F, c[2]);
  };
  // The colour sets that reach the core per material: the front's and, with GL_LIGHT_MODEL_TWO_SIDE, the back's
  // (the back face shares the front's unit, cut-off and normalisation; its shininess may differ). Under an object's
  // colour material (GL_FRONT_AND_BACK) its colours replace the chosen term(s) of both: there the set counts the
  // largest of its colours per channel (what can be non-zero) and `colours_grey` whether they are all grey.
  std::vector<std::vector<scene::Material>> sides(nm);
  std::vector<bool> colour_material(nm, false), colours_grey(nm, true), plain(nm, false);
  for (int o : objects_used) {
    const scene::Object& O = sc.objects[o];
    const auto m = static_cast<size_t>(O.material);
    if (!O.colour_material && plain[m]) continue;
    std::vector<scene::Material> ms{sc.materials[m]};
    if (sc.two_side) ms.push_back(sc.materials[m].back_face());
    if (O.colour_material) {
      const ObjectColours oc = object_colours.empty() ? ObjectColours{O.colour, is_grey(O.colour)}
                                                      : object_colours[static_cast<size_t>(o)];
      for (auto& M : ms) M = with_colour_material(M, *O.colour_material, oc.max);
      colour_material[m] = true;
      colours_grey[m] = colours_grey[m] && oc.grey;
    } else {
      plain[m] = true;
    }
    sides[m].insert(sides[m].end(), ms.begin(), ms.end());
  }
  // Effective specular term and unit of each material.
  std::vector<bool> spec(nm, false);
  std::vector<std::string> unit_key(nm);
  std::vector<VariantId> unit_var(nm, VariantId::cs16);
  std::vector<Cutoff> unit_cut(nm, Cutoff::ThetaCr);
  for (size_t m = 0; m < nm; ++m) {
    const auto& M = sc.materials[m];
    for (const auto& S : sides[m])
      for (int ch = 0; ch < 3; ++ch) spec[m] = spec[m] || (nz(S.specular, ch) && light_spec(ch));
    unit_var[m] = unit_override ? *unit_override : M.unit;
    unit_cut[m] = unit_var[m] == VariantId::cs16 && M.unit == VariantId::cs16 ? M.cutoff : Cutoff::ThetaCr;
    unit_key[m] = std::string(variant_name(unit_var[m])) +
                  (unit_var[m] == VariantId::cs16 ? std::string("/") + to_string(unit_cut[m]) : std::string());
  }
  Derivation d;
  d.group_of_material.assign(nm, -1);
  std::map<std::string, int> gid;
  for (size_t m = 0; m < nm; ++m) {
    if (!used[m] || !spec[m]) continue;
    auto it = gid.find(unit_key[m]);
    if (it == gid.end()) {
      it = gid.emplace(unit_key[m], static_cast<int>(d.groups.size())).first;
      d.groups.emplace_back();
      d.groups.back().unit_label = unit_key[m];
    }
    d.group_of_material[m] = it->second;
    d.groups[it->second].materials.push_back(static_cast<int>(m));
  }
  for (size_t m = 0; m < nm; ++m) {
    if (!used[m] || spec[m]) continue;
    if (d.groups.empty()) {
      d.groups.emplace_back();
      d.groups.back().unit_label = "none";
    }
    d.group_of_material[m] = 0;
    d.groups[0].materials.push_back(static_cast<int>(m));
  }
  if (!d.groups.empty()) std::sort(d.groups[0].materials.begin(), d.groups[0].materials.end());

  for (size_t gi = 0; gi < d.groups.size(); ++gi) {
    CoreGroup& g = d.groups[gi];
    FeatureSet fs;
    fs.name = "scene";
    fs.config = sc.config;
    const bool has_unit = g.unit_label != "none";
    const int m0 = g.materials.front();
    // per lighting state the group's materials drawn in it
    std::vector<std::vector<int>> group_mats(ns);
    for (size_t st = 0; st < ns; ++st)
      for (int m : mats_in_set[st])
        if (d.group_of_material[static_cast<size_t>(m)] == static_cast<int>(gi)) group_mats[st].push_back(m);
    auto any_mat_in = [&](size_t st, auto pred) {
      for (int m : group_mats[st])
        for (const auto& S : sides[m])
          for (int ch = 0; ch < 3; ++ch)
            if (pred(S, ch)) return true;
      return false;
    };
    auto set_used = [&](size_t st) { return !group_mats[st].empty(); };
    // Which lights contribute to any material of this core, per lighting state: the k-th contributing light of each
    // state goes to slot k, whose kinds are the union over the states (a driver reprograms the slot between them).
    fs.slots.clear();
    g.light_slot.clear();
    g.set_light_slot.assign(ns, {});
    bool first_set = true;
    for (size_t st = 0; st < ns; ++st) {
      if (!set_used(st)) continue;
      std::vector<int>& ls = g.set_light_slot[st];
      for (size_t j = 0; j < sets[st].lights.size(); ++j) {
        const auto& L = sets[st].lights[j];
        const bool contributes = any_mat_in(st, [&](const scene::Material& M, int ch) {
          return (nz(M.ambient, ch) && nz(L.ambient, ch)) || (nz(M.diffuse, ch) && nz(L.diffuse, ch)) ||
                 (has_unit && nz(M.specular, ch) && nz(L.specular, ch));
        });
        if (!contributes) continue;
        const LightKind k = light_kind(F, L);
        if (ls.size() < fs.slots.size()) fs.slots[ls.size()] |= kind_bit(k);
        else fs.slots.push_back(kind_bit(k));
        ls.push_back(static_cast<int>(j));
      }
      if (first_set) g.light_slot = ls;
      first_set = false;
    }
    // contributing lights of state st (the scene's light indices)
    auto each_light = [&](size_t st, auto pred) {
      for (int j : g.set_light_slot[st])
        if (pred(sets[st].lights[static_cast<size_t>(j)])) return true;
      return false;
    };
    auto any_state = [&](auto pred) {
      for (size_t st = 0; st < ns; ++st)
        if (set_used(st) && pred(st)) return true;
      return false;
    };
    fs.ambient = any_state([&](size_t st) {
      return any_mat_in(st, [&](const scene::Material& M, int ch) {
        if (nz(M.emission, ch)) return true;
        if (!nz(M.ambient, ch)) return false;
        if (nz(sets[st].global_ambient, ch)) return true;
        return each_light(st, [&](const scene::Light& L) { return nz(L.ambient, ch); });
      });
    });
    fs.diffuse = any_state([&](size_t st) {
      return any_mat_in(st, [&](const scene::Material& M, int ch) {
        return nz(M.diffuse, ch) && each_light(st, [&](const scene::Light& L) { return nz(L.diffuse, ch); });
      });
    });
    fs.specular = has_unit && any_state([&](size_t st) {
      return any_mat_in(st, [&](const scene::Material& M, int ch) {
        return nz(M.specular, ch) && each_light(st, [&](const scene::Light& L) { return nz(L.specular, ch); });
      });
    });
    if (fs.slots.empty()) {  // nothing lit by any light: one directional light with zero colours
      fs.slots.push_back(kind_bit(LightKind::Directional));
      g.light_slot.push_back(-1);
    }
    if (!fs.ambient && !fs.diffuse && !fs.specular) fs.ambient = true;  // a black object still needs a term
    fs.variant = fs.specular ? unit_var[m0] : VariantId::cs16;
    fs.cutoff = fs.specular && fs.variant == VariantId::cs16 ? unit_cut[m0] : Cutoff::ThetaCr;
    fs.norm = false;
    if (fs.specular)
      for (int m : g.materials) fs.norm = fs.norm || sc.materials[m].normalization.has_value();
    fs.blinn = fs.specular ? sc.blinn : true;
    fs.phong = !fs.blinn;
    fs.local_viewer = fs.specular && any_state([&](size_t st) { return sets[st].local_viewer; });
    // GL_SEPARATE_SPECULAR_COLOR
    fs.separate_specular = fs.specular && any_state([&](size_t st) { return sets[st].separate_specular; });
    // a shininess below the units' range (GL's 0..15): the exact chain beside the unit
    fs.low_shininess = false;
    // (with two_side the back's too: its own unit material, written between the facing batches)
    if (fs.specular)
      for (int m : g.materials)
        for (const auto& S : sides[m]) fs.low_shininess = fs.low_shininess || S.shininess < kNMin;
    fs.normalize = false;
    for (int m : g.materials) fs.normalize = fs.normalize || needs_normalize[m];
    // GL_LIGHT_MODEL_TWO_SIDE: back-facing fragments lit with −N and the back colour bank. Any object of the scene
    // may show a back face (open meshes, planes, a camera inside), so the scene's flag alone decides.
    fs.two_side = sc.two_side;
    // GL_COLOR_MATERIAL: some object of this core's materials has a colour material (fragment colours and the
    // colour_material register).
    fs.colour_material = false;
    for (int m : g.materials) fs.colour_material = fs.colour_material || colour_material[m];
    // Mono when every colour that reaches the core is grey.
    bool grey = true;
    if (fs.ambient)
      for (size_t st = 0; st < ns; ++st)
        if (set_used(st)) grey = grey && is_grey(sets[st].global_ambient);
    for (int m : g.materials) {
      grey = grey && colours_grey[m];
      for (const auto& M : sides[m])
        grey = grey && is_grey(M.emission) && is_grey(M.ambient) && is_grey(M.diffuse) && is_grey(M.specular);
    }
    for (size_t st = 0; st < ns; ++st)
      for (int j : g.set_light_slot[st]) {
        const auto& L = sets[st].lights[static_cast<size_t>(j)];
        grey = grey && is_grey(L.ambient) && is_grey(L.diffuse) && is_grey(L.specular);
      }
    fs.channels = grey ? 1 : 3;
    if (!fs.specular) g.unit_label = "none";
    fs.lanes = std::clamp(lanes, 1, fs.num_lights());
    fs.share = fs.lanes == 1 ? std::clamp(share, 1, kShareMax) : 1;
    g.specialised = fs;
    if (full_core) {
      g.fs = full_core_for(fs, g.full_substitutions);
      g.fs.lanes = std::clamp(lanes, 1, g.fs.num_lights());
      g.fs.share = g.fs.lanes == 1 ? std::clamp(share, 1, kShareMax) : 1;
      if (g.fs.lanes == g.fs.num_lights()) g.fs.name = "full_parallel";
      else if (g.fs.lanes != 1) g.fs.name = "full/lanes" + std::to_string(g.fs.lanes);
      else if (g.fs.share != 1) g.fs.name = "full/share" + std::to_string(g.fs.share);
    } else {
      g.fs = fs;
    }
  }
  return d;
}

// ---- meshes ------------------------------------------------------------------------------------------

MeshSource::MeshSource(const Scene& sc, size_t keep_bytes) : sc_(&sc), keep_bytes_(keep_bytes), kept_(sc.objects.size()) {}
MeshSource::MeshSource(const std::vector<scene::Mesh>& given) : given_(&given) {}

size_t MeshSource::bytes(const scene::Mesh& m) {
  size_t b = sizeof(m) + (m.pos.capacity() + m.nrm.capacity() + m.col.capacity()) * sizeof(Vec3) +
             m.faces.capacity() * sizeof(m.faces[0]);
  for (const auto& f : m.faces) b += f.capacity() * sizeof(int) + 16;  // + the allocator's header
  return b;
}

std::shared_ptr<const scene::Mesh> MeshSource::get(int object) {
  if (given_) return std::shared_ptr<const scene::Mesh>(std::shared_ptr<void>(), &given_->at(static_cast<size_t>(object)));
  auto& slot = kept_.at(static_cast<size_t>(object));
  if (slot) return slot;
  const auto t0 = std::chrono::steady_clock::now();
  auto m = std::make_shared<const scene::Mesh>(scene::build_mesh(sc_->objects[static_cast<size_t>(object)]));
  build_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const size_t b = bytes(*m);
  if (kept_bytes_ + b <= keep_bytes_) {
    kept_bytes_ += b;
    slot = m;
  }
  return m;
}

// ---- prepare ----------------------------------------------------------------------------------------

Frame prepare(const Scene& sc, const std::vector<scene::Mesh>& meshes, const Settings& s) {
  MeshSource src(meshes);
  return prepare(sc, src, s);
}

Frame prepare(const Scene& sc, MeshSource& meshes, const Settings& s) {
  Frame fr;
  fr.scene = &sc;
  fr.width = s.width > 0 ? s.width : sc.width;
  fr.height = s.height > 0 ? s.height : sc.height;
  fr.F = config_named(sc.config).format.frac;
  fr.flat_rule = sc.flat_rule;
  fr.two_side = sc.two_side;
  const int F = fr.F;
  const Camera cam = s.camera ? *s.camera : sc.camera;
  const Mat4 view = s.view ? *s.view : look_at(cam);
  const Mat4 proj = s.projection ? *s.projection : perspective(cam, static_cast<double>(fr.width) / fr.height);
  const size_t no = sc.objects.size();
  std::vector<int> drawn;
  if (s.objects.empty())
    for (size_t i = 0; i < no; ++i) drawn.push_back(static_cast<int>(i));
  else
    drawn = s.objects;
  fr.object_group.assign(no, -1);
  fr.object_shading.resize(no);
  fr.object_material.resize(no);
  for (size_t i = 0; i < no; ++i) {
    fr.object_shading[i] = s.mode ? *s.mode : sc.objects[i].shading;
    fr.object_material[i] = sc.objects[i].material;
  }
  for (int c = 0; c < 3; ++c) fr.background[c] = colour_code(F, sc.background[c]);

  // Geometry, one object at a time: eye space, codes for the core, clip coordinates, and straight into the
  // rasteriser; after each object the triangles no pixel shows are dropped, with the vertices and faces only
  // they used (the survivors keep their drawing order, so the command streams are those of drawing
  // everything first). Peak memory: the image, the survivors (at most a few per pixel) and one object.
  std::vector<bool> needs_normalize(sc.materials.size(), false);
  std::vector<ObjectColours> object_colours(no);
  fr.raster = raster::Rasterizer(fr.width, fr.height, cam.near);
  fr.raster.set_unsnapped_depth(s.unsnapped_depth);
  const size_t compact_at = std::max<size_t>(size_t{1} << 16, 4 * static_cast<size_t>(fr.width) * fr.height);
  const double build0 = meshes.build_seconds();
  const auto t_geom = std::chrono::steady_clock::now();
  struct Pending {
    uint32_t face;
    std::array<uint32_t, 3> v;  // object-local vertex indices
  };
  std::vector<Pending> pending;
  for (int oi : drawn) {
    const auto& o = sc.objects[oi];
    const std::shared_ptr<const scene::Mesh> mesh_ptr = meshes.get(oi);
    const scene::Mesh& mesh = *mesh_ptr;
    const Mat4 mv = mul(view, model_matrix(o.transform));
    const auto nmat = normal_matrix(mv);
    bool fixed = true;
    std::vector<Vec3> eye(mesh.pos.size());
    std::vector<raster::ClipVertex> clip(mesh.pos.size());
    // GL_COLOR_MATERIAL: each vertex's colour (the OBJ's, else the object's `color`) goes to the core with its
    // fragment; a face's fragment (flat_rule centroid) takes the mean of its vertices' colours. Without colour
    // material the fragment colour stays 0 (streams as before).
    const bool cm = o.colour_material.has_value();
    auto vertex_colour = [&](size_t v) -> const Vec3& { return mesh.col.empty() ? o.colour : mesh.col[v]; };
    {
      ObjectColours& oc = object_colours[static_cast<size_t>(oi)];
      oc = {o.colour, true};
      if (!mesh.col.empty()) oc.max = {0, 0, 0};
      for (size_t v = 0; v < (mesh.col.empty() ? size_t{1} : mesh.col.size()); ++v) {
        const Vec3& c = vertex_colour(v);
        for (int i = 0; i < 3; ++i) oc.max[i] = std::max(oc.max[i], c[i]);
        oc.grey = oc.grey && colour_code(F, c[0]) == colour_code(F, c[1]) && colour_code(F, c[1]) == colour_code(F, c[2]);
      }
    }
    auto vertex_fragment = [&](size_t v) {
      const Vec3 ne = unit(apply3(nmat, mesh.nrm[v]));
      Fragment f;
      const auto nc = normal_code(F, ne, &fixed);
      const Fragment pf = make_fragment(F, ne.data(), eye[v].data());
      for (int i = 0; i < 3; ++i) f.n[i] = nc[i], f.p[i] = pf.p[i];
      if (cm) set_fragment_colour(F, f, vertex_colour(v).data());
      return f;
    };
    auto face_fragment = [&](size_t fi) {
      const auto& face = mesh.faces[fi];
      const Vec3 fn = unit(apply3(nmat, scene::polygon_normal(mesh.pos, face)));
      Vec3 cen{0, 0, 0}, col = o.colour;  // one colour for the whole mesh: exactly it
      if (!mesh.col.empty()) col = {0, 0, 0};
      for (int v : face)
        for (int i = 0; i < 3; ++i) {
          cen[i] += eye[v][i] / static_cast<double>(face.size());
          if (!mesh.col.empty()) col[i] += mesh.col[static_cast<size_t>(v)][i] / static_cast<double>(face.size());
        }
      Fragment f;
      const auto nc = normal_code(F, fn, &fixed);
      const Fragment pf = make_fragment(F, fn.data(), cen.data());
      for (int i = 0; i < 3; ++i) f.n[i] = nc[i], f.p[i] = pf.p[i];
      if (cm) set_fragment_colour(F, f, col.data());
      return f;
    };
    for (size_t v = 0; v < mesh.pos.size(); ++v) {
      const auto pe4 = apply(mv, {mesh.pos[v][0], mesh.pos[v][1], mesh.pos[v][2], 1.0});
      const Vec3 pe{pe4[0], pe4[1], pe4[2]};
      if (!pos_in_range(pe))
        throw SceneError(sc.file + ": " + o.where + ": vertex " + std::to_string(v) + " at eye-space " + fmt3(pe) +
                         " is outside the core's position range [-128, 128)");
      eye[v] = pe;
      (void)vertex_fragment(v);  // every normal is checked to be a fixed point of the normaliser
      const auto c4 = apply(proj, {pe[0], pe[1], pe[2], 1.0});
      clip[v] = {c4[0], c4[1], c4[2], c4[3]};
    }
    const uint32_t src_base = static_cast<uint32_t>(fr.tri_object.size());
    pending.clear();
    fr.raster.set_depth_state(o.depth_test, o.depth_write);  // objects are drawn in the stream's order
    for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
      const auto& face = mesh.faces[fi];
      (void)face_fragment(fi);
      for (size_t k = 1; k + 1 < face.size(); ++k) {
        const std::array<uint32_t, 3> tv{static_cast<uint32_t>(face[0]), static_cast<uint32_t>(face[k]),
                                         static_cast<uint32_t>(face[k + 1])};
        pending.push_back({static_cast<uint32_t>(fi), tv});
        fr.raster.draw(static_cast<int>(src_base + pending.size() - 1), {clip[tv[0]], clip[tv[1]], clip[tv[2]]});
        if (fr.raster.tris().size() > compact_at) fr.raster.compact();
      }
    }
    fr.drawn_vertices += mesh.pos.size();
    fr.drawn_faces += mesh.faces.size();
    fr.drawn_triangles += pending.size();
    // Phong interpolates normals (not unit between vertices); a host normal that is not a fixed point of
    // the normaliser (never seen, but checked) also keeps GL_NORMALIZE on, so the full core agrees.
    if (fr.object_shading[oi] == Shading::Phong || !fixed) {
      needs_normalize[o.material] = true;
      for (int vo : mesh.vertex_object) needs_normalize[sc.objects[static_cast<size_t>(vo)].material] = true;
    }

    // Keep what some pixel shows: triangles (earlier objects' and this one's), then their vertices and faces.
    fr.raster.compact();
    std::vector<char> tri_live(src_base + pending.size(), 0);
    for (const auto& st : fr.raster.tris()) tri_live[static_cast<size_t>(st.source)] = 1;
    std::vector<char> old_vert_live(fr.vertex_frag.size(), 0), old_face_live(fr.face_frag.size(), 0);
    std::vector<char> new_vert_live(mesh.pos.size(), 0), new_face_live(mesh.faces.size(), 0);
    for (uint32_t t = 0; t < src_base; ++t)
      if (tri_live[t]) {
        for (uint32_t v : fr.tri_vertices[t]) old_vert_live[v] = 1;
        old_face_live[fr.tri_face[t]] = 1;
      }
    for (size_t t = 0; t < pending.size(); ++t)
      if (tri_live[src_base + t]) {
        for (uint32_t v : pending[t].v) new_vert_live[v] = 1;
        new_face_live[pending[t].face] = 1;
      }
    auto keep = [](auto& vec, const std::vector<char>& live, std::vector<uint32_t>& remap) {
      remap.assign(live.size(), ~0u);
      size_t k = 0;
      for (size_t i = 0; i < live.size(); ++i)
        if (live[i]) {
          remap[i] = static_cast<uint32_t>(k);
          if (k != i) vec[k] = vec[i];
          ++k;
        }
      vec.resize(k);
    };
    std::vector<uint32_t> vmap, fmap, tmap, nvmap(mesh.pos.size(), ~0u), nfmap(mesh.faces.size(), ~0u);
    keep(fr.vertex_frag, old_vert_live, vmap);
    {
      std::vector<uint32_t> unused;
      keep(fr.vertex_object, old_vert_live, unused);
    }
    keep(fr.face_frag, old_face_live, fmap);
    {
      std::vector<uint32_t> unused;
      keep(fr.face_object, old_face_live, unused);
    }
    for (size_t v = 0; v < mesh.pos.size(); ++v)
      if (new_vert_live[v]) {
        nvmap[v] = static_cast<uint32_t>(fr.vertex_frag.size());
        fr.vertex_frag.push_back(vertex_fragment(v));
        fr.vertex_object.push_back(mesh.vertex_object.empty() ? oi : mesh.vertex_object[v]);  // material batches
      }
    for (size_t fi = 0; fi < mesh.faces.size(); ++fi)
      if (new_face_live[fi]) {
        nfmap[fi] = static_cast<uint32_t>(fr.face_frag.size());
        fr.face_frag.push_back(face_fragment(fi));
        fr.face_object.push_back(oi);
      }
    tmap.assign(tri_live.size(), ~0u);
    size_t k = 0;
    for (uint32_t t = 0; t < src_base; ++t)
      if (tri_live[t]) {
        tmap[t] = static_cast<uint32_t>(k);
        fr.tri_object[k] = fr.tri_object[t];
        fr.tri_face[k] = static_cast<int>(fmap[fr.tri_face[t]]);
        for (int q = 0; q < 3; ++q) fr.tri_vertices[k][q] = vmap[fr.tri_vertices[t][q]];
        ++k;
      }
    fr.tri_object.resize(k);
    fr.tri_face.resize(k);
    fr.tri_vertices.resize(k);
    for (size_t t = 0; t < pending.size(); ++t)
      if (tri_live[src_base + t]) {
        tmap[src_base + t] = static_cast<uint32_t>(fr.tri_object.size());
        fr.tri_object.push_back(oi);
        fr.tri_face.push_back(static_cast<int>(nfmap[pending[t].face]));
        fr.tri_vertices.push_back({nvmap[pending[t].v[0]], nvmap[pending[t].v[1]], nvmap[pending[t].v[2]]});
      }
    fr.raster.relabel([&](int src) { return static_cast<int>(tmap[static_cast<size_t>(src)]); });
  }
  pending = {};
  fr.tessellate_seconds = meshes.build_seconds() - build0;
  fr.rasterise_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_geom).count() - fr.tessellate_seconds;

  // Lights in eye space (glLight with the view matrix on the modelview stack), of every lighting state.
  const std::vector<scene::LightingSet> sets = sc.lighting_states();
  const size_t nsets = sets.size();
  for (size_t st = 0; st < nsets; ++st)
    for (size_t j = 0; j < sets[st].lights.size(); ++j) {
      const auto& L = sets[st].lights[j];
      if (L.position[3] != 0.0) {
        const auto pe = apply(view, L.position);
        const Vec3 p{pe[0] / pe[3], pe[1] / pe[3], pe[2] / pe[3]};
        if (!pos_in_range(p))
          throw SceneError(sc.file + ": " + (nsets > 1 ? "lighting state " + std::to_string(st) + ": " : std::string()) +
                           "lights[" + std::to_string(j) + "].position: eye-space position " + fmt3(p) +
                           " is outside the core's position range [-128, 128)");
      }
    }

  const Derivation d =
      derive_features(sc, drawn, needs_normalize, s.full_core, s.unit, s.lanes, s.share, object_colours);
  fr.groups = d.groups;
  for (int oi : drawn) fr.object_group[oi] = d.group_of_material[sc.objects[oi].material];

  // Visibility: what each pixel shows, per material. With two_side a face or vertex seen by front- and by
  // back-facing triangles needs both fragments (bit 0 front, bit 1 back): GL lights a vertex for both faces and
  // the rasteriser takes the colour of the triangle's facing (OpenGL 2.1 §2.14.1, §2.14.6). Without two_side every
  // triangle counts as front facing (the core's light_model bit 3 is off and in_back_i stays 0).
  struct Item {
    uint32_t index;
    bool back;
  };
  // Fragments go to the core per lighting state (in the stream's order; a scene file has one), within it per
  // material and within that per colour material mode (`none` first, then the ColourMaterial order): the bucket of
  // object oi. A core with the colour_material register gets it written before each bucket's fragments; a scene
  // without colour material has only the `none` buckets.
  constexpr size_t kCmBuckets = 6;
  auto set_of = [nsets](const scene::Object& O) {
    return static_cast<size_t>(std::clamp<int>(O.lighting, 0, static_cast<int>(nsets) - 1));
  };
  // the (lighting state, material) pairs drawn, numbered in that order: kCmBuckets buckets each
  std::map<std::pair<size_t, int>, size_t> pair_index;
  for (int oi : drawn) pair_index.emplace(std::make_pair(set_of(sc.objects[oi]), sc.objects[oi].material), 0);
  {
    size_t k = 0;
    for (auto& kv : pair_index) kv.second = k++;
  }
  auto bucket = [&](int oi) {
    const auto& cmo = sc.objects[oi].colour_material;
    return pair_index.at({set_of(sc.objects[oi]), sc.objects[oi].material}) * kCmBuckets +
           (cmo ? 1 + static_cast<size_t>(*cmo) : 0);
  };
  const size_t nbuckets = pair_index.size() * kCmBuckets;
  std::vector<std::vector<Item>> mat_faces(nbuckets), mat_verts(nbuckets);
  std::vector<std::vector<uint32_t>> mat_pixels(nbuckets);
  std::vector<uint8_t> face_vis(fr.face_frag.size(), 0), vert_need(fr.vertex_frag.size(), 0);
  for (int y = 0; y < fr.height; ++y)
    for (int x = 0; x < fr.width; ++x) {
      const int32_t id = fr.raster.at(x, y);
      if (id < 0) continue;
      const auto& st = fr.raster.tris()[id];
      const int src = st.source;
      const int oi = fr.tri_object[src];
      const uint8_t side = fr.two_side && st.back ? 2 : 1;
      switch (fr.object_shading[oi]) {
        case Shading::Flat:
          // provoking_vertex: the triangle (v0, vk, vk+1) takes vk+1's colour, its vertex fragment (shared by the
          // triangles it provokes); centroid: the face's fragment
          if (fr.flat_rule == scene::FlatRule::ProvokingVertex) vert_need[fr.tri_vertices[src][2]] |= side;
          else face_vis[fr.tri_face[src]] |= side;
          break;
        case Shading::Gouraud:
          for (uint32_t v : fr.tri_vertices[src]) vert_need[v] |= side;
          break;
        case Shading::Phong:
          mat_pixels[bucket(oi)].push_back(static_cast<uint32_t>(y * fr.width + x));
          break;
      }
    }
  for (size_t f = 0; f < face_vis.size(); ++f)
    for (uint8_t b = 0; b < 2; ++b)
      if (face_vis[f] & (1u << b))
        mat_faces[bucket(fr.face_object[f])].push_back({static_cast<uint32_t>(f), b != 0});
  for (size_t v = 0; v < vert_need.size(); ++v)
    for (uint8_t b = 0; b < 2; ++b)
      if (vert_need[v] & (1u << b))
        mat_verts[bucket(fr.vertex_object[v])].push_back({static_cast<uint32_t>(v), b != 0});

  // Command streams: per lighting state (in the stream's order) the global and light registers, then per material
  // its registers and its fragments. The first state is programmed in full; each later one by the writes whose
  // register value changes (the core drains before a write: the RTL's cycles count it); with
  // Settings::changed_registers_only every write after the first programming is left out when the register already
  // holds its value (materials, colour material).
  for (auto& g : fr.groups) {
    const LightCore core(g.fs);
    std::map<uint32_t, uint32_t> shadow;  // the value each register was last written
    auto add_writes = [&g, &shadow](const std::vector<RegWrite>& ws, bool changed_only = false) {
      for (const auto& w : ws) {
        const auto it = shadow.find(w.addr);
        if (changed_only && it != shadow.end() && it->second == w.data) continue;
        shadow[w.addr] = w.data;
        CoreCmd c;
        c.is_write = true;
        c.w = w;
        g.cmds.push_back(c);
        ++g.writes;
      }
    };
    const FeatureSet& sp = g.specialised;
    // the global and light registers of lighting state st
    auto program_state = [&](size_t st, bool changed_only) {
      const scene::LightingSet& S = sets[st];
      // the modes of the specialised set, programmed (the same words on the full core)
      const ModeParams modes{sp.specular && sp.local_viewer && S.local_viewer, sp.specular && !sp.blinn, sp.normalize,
                             sp.separate_specular && S.separate_specular, sp.two_side};
      add_writes(global_writes(core, S.global_ambient.data(), modes), changed_only);
      const std::vector<int>& slot_light = g.set_light_slot[st];
      for (int j = 0; j < g.fs.num_lights(); ++j) {
        if (j >= sp.num_lights()) {  // a slot of the full core the scene does not use: off
          add_writes(light_off_writes(j), changed_only);
          continue;
        }
        LightParams lp;
        const int sj = j < static_cast<int>(slot_light.size()) ? slot_light[j] : -1;
        LightKind kind = sp.slot_kind(j);
        if (sj >= 0) kind = light_kind(F, S.lights[static_cast<size_t>(sj)]);
        lp.kind = slot_kind_for(g.fs, j, kind);
        if (sj >= 0) {
          const auto& L = S.lights[static_cast<size_t>(sj)];
          const auto pe = apply(view, L.position);
          for (int i = 0; i < 4; ++i) lp.position[i] = pe[i];
          if (L.position[3] != 0.0) {
            for (int i = 0; i < 3; ++i) lp.position[i] = pe[i] / pe[3];
            lp.position[3] = 1.0;
          }
          for (int c = 0; c < 3; ++c) {
            lp.ambient[c] = L.ambient[c];
            lp.diffuse[c] = L.diffuse[c];
            lp.specular[c] = L.specular[c];
          }
          lp.kc = L.kc, lp.kl = L.kl, lp.kq = L.kq;
          if (L.is_spot()) {  // GL_SPOT_DIRECTION is transformed by the modelview's upper 3×3 (w = 0)
            const auto de = apply(view, {L.spot_direction[0], L.spot_direction[1], L.spot_direction[2], 0.0});
            for (int i = 0; i < 3; ++i) lp.spot_direction[i] = de[i];
            lp.spot_cutoff = L.spot_cutoff;
            lp.spot_exponent = L.spot_exponent;
          }
        } else {  // a slot the scene does not use: zero colours contribute exactly 0
          lp.position[0] = lp.position[1] = 0;
          lp.position[2] = 1;
          lp.position[3] = kind == LightKind::Directional ? 0.0 : 1.0;
          if (kind != LightKind::Directional) lp.position[2] = 0;
          for (int c = 0; c < 3; ++c) lp.ambient[c] = lp.diffuse[c] = lp.specular[c] = 0;
          lp.kc = 1, lp.kl = 0, lp.kq = 0;
        }
        add_writes(light_writes(core, j, lp), changed_only);
      }
    };
    // the states with fragments in this group (a group with none is programmed with its first state, as before)
    const int gi = static_cast<int>(&g - fr.groups.data());
    auto has_fragments = [&](size_t b0) {
      for (size_t b = b0; b < b0 + kCmBuckets; ++b)
        if (!mat_faces[b].empty() || !mat_verts[b].empty() || !mat_pixels[b].empty()) return true;
      return false;
    };
    std::vector<size_t> states;
    for (const auto& kv : pair_index)
      if (d.group_of_material[static_cast<size_t>(kv.first.second)] == gi && has_fragments(kv.second * kCmBuckets) &&
          (states.empty() || states.back() != kv.first.first))
        states.push_back(kv.first.first);
    if (states.empty())
      for (size_t st = 0; st < nsets; ++st)
        if (!g.set_light_slot[st].empty() || st + 1 == nsets) {
          states.push_back(st);
          break;
        }
    for (size_t si = 0; si < states.size(); ++si) {
      const size_t cur_state = states[si];
      const uint64_t writes_before = g.writes;
      program_state(cur_state, si > 0);
      if (si > 0) ++g.state_changes, g.state_writes += g.writes - writes_before;
      // this state's materials of the group, ascending (the order of g.materials)
      for (auto it = pair_index.lower_bound({cur_state, std::numeric_limits<int>::min()});
           it != pair_index.end() && it->first.first == cur_state; ++it) {
        const int m = it->first.second;
        const size_t b0 = it->second * kCmBuckets;
        if (d.group_of_material[static_cast<size_t>(m)] != gi || !has_fragments(b0)) continue;
        const auto& M = sc.materials[m];
        // a scene material's (or its back's) colours and shininess into the host's MaterialParams
        auto take = [](MaterialParams& p, const auto& src) {
          for (int c = 0; c < 3; ++c) {
            p.emission[c] = src.emission[c];
            p.ambient[c] = src.ambient[c];
            p.diffuse[c] = src.diffuse[c];
            p.specular[c] = src.specular[c];
          }
          p.shininess = src.shininess;
        };
        MaterialParams mp;
        take(mp, M);
        if (M.normalization && sp.specular) {
          mp.norm_model = static_cast<int>(M.normalization->model);
          mp.norm_kind = M.normalization->kind;
        } else {
          mp.norm_model = -1;  // with the norm hardware: coefficient 1.0, sc_energy passes spec unchanged
        }
        if (sp.specular) mp.unit = sp.variant;
        add_writes(material_writes(core, mp), s.changed_registers_only);
        // glMaterial(GL_BACK, ...): the back colour bank (the front's when the scene gives none)
        const scene::BackMaterial B = M.back_or_front();
        MaterialParams bp = mp;
        take(bp, B);
        if (sp.two_side) add_writes(back_material_writes(core, bp), s.changed_registers_only);
        // The core holds one unit material (mat_unit, mat_n, mat_thr, mat_coef). A back face with a shininess of its
        // own: the front-facing fragments first, then the back's unit material and the back-facing ones (the next
        // material's writes replace it). Otherwise one batch, in the order below.
        const bool split = sp.two_side && sp.specular && bp.shininess != mp.shininess;
        auto pixel_back = [&fr](uint32_t p) {
          return fr.two_side && fr.raster.tris()[fr.raster.at(static_cast<int>(p % fr.width), static_cast<int>(p / fr.width))].back;
        };
        auto frag = [&g](const Fragment& f, DestKind k, uint32_t idx, bool back) {
          CoreCmd c;
          c.f = f;
          c.f.back = back;
          g.cmds.push_back(c);
          g.dests.push_back({k, idx, back});
        };
        for (int batch = 0; batch < (split ? 2 : 1); ++batch) {
          auto in_batch = [&](bool back) { return !split || back == (batch == 1); };
          if (batch == 1) add_writes(unit_material_writes(core, bp), s.changed_registers_only);
          for (size_t b = b0; b < b0 + kCmBuckets; ++b) {
            bool any_here = false;
            for (const Item& f : mat_faces[b]) any_here = any_here || in_batch(f.back);
            for (const Item& v : mat_verts[b]) any_here = any_here || in_batch(v.back);
            for (uint32_t p : mat_pixels[b]) any_here = any_here || in_batch(pixel_back(p));
            if (!any_here) continue;
            if (g.fs.colour_material)  // glColorMaterial(GL_FRONT_AND_BACK, mode) / glDisable(GL_COLOR_MATERIAL)
              add_writes(colour_material_writes(b == b0 ? std::nullopt
                                                        : std::optional<ColourMaterial>(static_cast<ColourMaterial>(b - b0 - 1))),
                         s.changed_registers_only);
            for (const Item& f : mat_faces[b])
              if (in_batch(f.back)) frag(fr.face_frag[f.index], DestKind::Face, f.index, f.back), ++g.faces;
            for (const Item& v : mat_verts[b])
              if (in_batch(v.back)) frag(fr.vertex_frag[v.index], DestKind::Vertex, v.index, v.back), ++g.vertices;
            for (uint32_t p : mat_pixels[b]) {
              if (!in_batch(pixel_back(p))) continue;
              const int x = static_cast<int>(p % fr.width), y = static_cast<int>(p / fr.width);
              const int32_t id = fr.raster.at(x, y);
              const auto& st = fr.raster.tris()[id];
              const auto& tv = fr.tri_vertices[st.source];
              const raster::Weights w = fr.raster.weights(id, x, y);
              // the normal, the position and the colour (0 without colour material) interpolated alike: each
              // screen vertex's value from its weights over the triangle's vertices, then perspective-correct
              auto interp = [&](auto attr) {
                std::array<int64_t, 3> a{};
                for (int k = 0; k < 3; ++k) {
                  double sa = 0;
                  for (int q = 0; q < 3; ++q) sa += st.v[k].b[q] * static_cast<double>(attr(fr.vertex_frag[tv[q]]));
                  a[k] = std::llround(sa);
                }
                return raster::interpolate(w, a);
              };
              Fragment f;
              for (int i = 0; i < 3; ++i) {
                f.n[i] = interp([i](const Fragment& v) { return v.n[i]; });
                f.p[i] = interp([i](const Fragment& v) { return v.p[i]; });
                f.col[i] = static_cast<uint32_t>(interp([i](const Fragment& v) { return v.col[i]; }));
              }
              frag(f, DestKind::Pixel, p, fr.two_side && st.back);
              ++g.pixels;
            }
          }
        }
    }
    }
  }
  return fr;
}

// ---- the C model and the reference ------------------------------------------------------------------

std::vector<Colour> run_cmodel(const CoreGroup& g) {
  const LightCore core(g.fs);
  LightRegs regs;
  std::vector<Colour> out;
  out.reserve(g.dests.size());
  for (const auto& c : g.cmds) {
    if (c.is_write) regs.write(core.widths(), c.w.addr, c.w.data);
    else out.push_back(core.eval(regs, c.f));
  }
  return out;
}

std::vector<RefColour> run_reference(const CoreGroup& g, LightCore::SpecRef ref) {
  const LightCore core(g.fs);
  LightRegs regs;
  std::vector<RefColour> out;
  out.reserve(g.dests.size());
  for (const auto& c : g.cmds) {
    if (c.is_write) {
      regs.write(core.widths(), c.w.addr, c.w.data);
      continue;
    }
    std::array<double, 3> s{};
    const std::array<double, 3> p = core.eval_double(regs, c.f, ref, nullptr, &s);
    out.push_back({p[0], p[1], p[2], s[0], s[1], s[2]});
  }
  return out;
}

// ---- resolve ----------------------------------------------------------------------------------------

namespace {

// Face and vertex values per facing: [0] front, [1] back (two_side only; empty otherwise).
template <typename T>
struct Sided {
  std::array<std::vector<T>, 2> face, vert;
  std::vector<T> pix;
  std::vector<T>& of(const Dest& d) {
    return d.kind == DestKind::Face ? face[d.back ? 1 : 0] : d.kind == DestKind::Vertex ? vert[d.back ? 1 : 0] : pix;
  }
};

template <typename T, typename Interp, typename VertexValue, typename Store>
void resolve_pixels(const Frame& fr, const Sided<T>& sv_, Interp interp, VertexValue vertex_value, Store store) {
  const std::vector<T>& pix_v = sv_.pix;
  for (int y = 0; y < fr.height; ++y)
    for (int x = 0; x < fr.width; ++x) {
      const size_t p = static_cast<size_t>(y) * fr.width + x;
      const int32_t id = fr.raster.at(x, y);
      if (id < 0) continue;
      const auto& st = fr.raster.tris()[id];
      const int src = st.source;
      const int oi = fr.tri_object[src];
      const int side = fr.two_side && st.back ? 1 : 0;  // the triangle's facing picks the face / vertex colours
      const std::vector<T>& face_v = sv_.face[side];
      const std::vector<T>& vert_v = sv_.vert[side];
      switch (fr.object_shading[oi]) {
        case Shading::Flat:
          store(p, oi, fr.flat_rule == scene::FlatRule::ProvokingVertex ? vert_v[fr.tri_vertices[src][2]] : face_v[fr.tri_face[src]]);
          break;
        case Shading::Phong: store(p, oi, pix_v[p]); break;
        case Shading::Gouraud: {
          const auto& tv = fr.tri_vertices[src];
          std::array<T, 3> sv{};
          for (int k = 0; k < 3; ++k) sv[k] = vertex_value(st.v[k].b, vert_v[tv[0]], vert_v[tv[1]], vert_v[tv[2]]);
          store(p, oi, interp(fr.raster.weights(id, x, y), sv));
          break;
        }
      }
    }
}

}  // namespace

Image resolve(const Frame& fr, const std::vector<std::vector<Colour>>& colours) {
  Image img;
  img.width = fr.width, img.height = fr.height, img.F = fr.F;
  const size_t np = static_cast<size_t>(fr.width) * fr.height;
  img.code.resize(np * 3);
  img.covered.assign(np, 0);
  img.group.assign(np, -1);
  for (size_t p = 0; p < np; ++p)
    for (int c = 0; c < 3; ++c) img.code[p * 3 + c] = fr.background[c];
  Sided<Colour> sd;
  const int nsides = fr.two_side ? 2 : 1;
  for (int b = 0; b < nsides; ++b) sd.face[b].resize(fr.face_frag.size()), sd.vert[b].resize(fr.vertex_frag.size());
  sd.pix.resize(np);
  for (size_t g = 0; g < fr.groups.size(); ++g) {
    const auto& grp = fr.groups[g];
    const auto& cols = colours.at(g);
    if (cols.size() != grp.dests.size())
      throw std::runtime_error("core " + std::to_string(g) + " returned " + std::to_string(cols.size()) +
                               " colours for " + std::to_string(grp.dests.size()) + " fragments");
    const bool mono = grp.specialised.channels == 1;
    for (size_t i = 0; i < cols.size(); ++i) {
      Colour c = cols[i];
      if (mono) c.c[1] = c.c[2] = c.c[0], c.s[1] = c.s[2] = c.s[0];
      sd.of(grp.dests[i])[grp.dests[i].index] = c;
    }
  }
  resolve_pixels<Colour>(
      fr, sd,
      [](const raster::Weights& w, const std::array<Colour, 3>& sv) {
        Colour c;  // the primary and the secondary colour interpolated apart (GL)
        for (int ch = 0; ch < 3; ++ch) {
          c.c[ch] = static_cast<uint32_t>(raster::interpolate(
              w, std::array<int64_t, 3>{sv[0].c[ch], sv[1].c[ch], sv[2].c[ch]}));
          c.s[ch] = static_cast<uint32_t>(raster::interpolate(
              w, std::array<int64_t, 3>{sv[0].s[ch], sv[1].s[ch], sv[2].s[ch]}));
        }
        return c;
      },
      [](const std::array<double, 3>& b, const Colour& a, const Colour& bb, const Colour& cc) {
        Colour r;
        for (int ch = 0; ch < 3; ++ch) {
          r.c[ch] = static_cast<uint32_t>(std::llround(b[0] * a.c[ch] + b[1] * bb.c[ch] + b[2] * cc.c[ch]));
          r.s[ch] = static_cast<uint32_t>(std::llround(b[0] * a.s[ch] + b[1] * bb.s[ch] + b[2] * cc.s[ch]));
        }
        return r;
      },
      [&](size_t p, int oi, const Colour& c) {
        // GL's colour sum (no texturing): min(1, primary + secondary)
        for (int ch = 0; ch < 3; ++ch) img.code[p * 3 + ch] = c.colour_sum(ch, uint32_t{1} << fr.F);
        img.covered[p] = 1;
        img.group[p] = static_cast<int8_t>(fr.object_group[oi]);
      });
  return img;
}

RefImage resolve_reference(const Frame& fr, const std::vector<std::vector<RefColour>>& values) {
  using V = RefColour;
  RefImage ref;
  ref.width = fr.width, ref.height = fr.height;
  const size_t np = static_cast<size_t>(fr.width) * fr.height;
  ref.value.resize(np * 3);
  for (size_t p = 0; p < np; ++p)
    for (int c = 0; c < 3; ++c) ref.value[p * 3 + c] = std::ldexp(static_cast<double>(fr.background[c]), -fr.F);
  Sided<V> sd;
  const int nsides = fr.two_side ? 2 : 1;
  for (int b = 0; b < nsides; ++b) sd.face[b].resize(fr.face_frag.size()), sd.vert[b].resize(fr.vertex_frag.size());
  sd.pix.resize(np);
  for (size_t g = 0; g < fr.groups.size(); ++g) {
    const auto& grp = fr.groups[g];
    const auto& vals = values.at(g);
    const bool mono = grp.specialised.channels == 1;
    for (size_t i = 0; i < vals.size(); ++i) {
      V v = vals[i];
      if (mono) v[1] = v[2] = v[0], v[4] = v[5] = v[3];
      sd.of(grp.dests[i])[grp.dests[i].index] = v;
    }
  }
  resolve_pixels<V>(
      fr, sd,
      [](const raster::Weights& w, const std::array<V, 3>& sv) {
        V r;
        for (int ch = 0; ch < 6; ++ch) r[ch] = raster::interpolate(w, std::array<double, 3>{sv[0][ch], sv[1][ch], sv[2][ch]});
        return r;
      },
      [](const std::array<double, 3>& b, const V& a, const V& bb, const V& cc) {
        V r;
        for (int ch = 0; ch < 6; ++ch) r[ch] = b[0] * a[ch] + b[1] * bb[ch] + b[2] * cc[ch];
        return r;
      },
      [&](size_t p, int, const V& v) {
        for (int ch = 0; ch < 3; ++ch) ref.value[p * 3 + ch] = std::min(1.0, v[ch] + v[ch + 3]);
      });
  return ref;
}

// ---- statistics and 8-bit views ----------------------------------------------------------------------

ErrorStats error_vs(const Image& img, const RefImage& ref, int group) {
  ErrorStats s;
  const double scale = std::ldexp(1.0, img.F);
  double sum = 0, sq = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t p = static_cast<size_t>(y) * img.width + x;
      if (!img.covered[p] || (group >= 0 && img.group[p] != group)) continue;
      ++s.pixels;
      for (int c = 0; c < 3; ++c) {
        const double e = std::abs(static_cast<double>(img.code[p * 3 + c]) - scale * ref.value[p * 3 + c]);
        if (e > s.max_lsb) s.max_lsb = e, s.max_x = x, s.max_y = y;
        sum += e;
        sq += (e / scale) * (e / scale);
        ++s.samples;
      }
    }
  if (s.samples) {
    s.mean_lsb = sum / static_cast<double>(s.samples);
    const double mse = sq / static_cast<double>(s.samples);
    s.rms = std::sqrt(mse);
    s.psnr_db = mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
  } else {
    s.psnr_db = std::numeric_limits<double>::infinity();
  }
  return s;
}

uint64_t mismatching_pixels(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument("images of different sizes");
  uint64_t n = 0;
  for (size_t p = 0; p < a.covered.size(); ++p)
    if (a.code[p * 3] != b.code[p * 3] || a.code[p * 3 + 1] != b.code[p * 3 + 1] || a.code[p * 3 + 2] != b.code[p * 3 + 2] ||
        a.covered[p] != b.covered[p])
      ++n;
  return n;
}

std::vector<uint8_t> to_rgb8(const Image& img) {
  std::vector<uint8_t> out(img.code.size());
  const uint64_t half = uint64_t{1} << (img.F - 1);
  for (size_t i = 0; i < img.code.size(); ++i)
    out[i] = static_cast<uint8_t>(std::min<uint64_t>(255, (uint64_t{img.code[i]} * 255 + half) >> img.F));
  return out;
}

std::vector<uint8_t> to_rgb8(const RefImage& ref) {
  std::vector<uint8_t> out(ref.value.size());
  for (size_t i = 0; i < ref.value.size(); ++i)
    out[i] = static_cast<uint8_t>(std::clamp(std::lround(ref.value[i] * 255.0), 0L, 255L));
  return out;
}

std::vector<uint8_t> diff_rgb8(const Image& img, const RefImage& ref) {
  std::vector<uint8_t> out(img.code.size(), 0);
  const double scale = std::ldexp(1.0, img.F);
  const double full = std::log2(1.0 + scale);
  for (size_t p = 0; p < img.covered.size(); ++p) {
    double d = 0;  // the channel with the largest |Δ|, in LSBs, with its sign
    for (int c = 0; c < 3; ++c) {
      const double e = static_cast<double>(img.code[p * 3 + c]) - scale * ref.value[p * 3 + c];
      if (std::abs(e) > std::abs(d)) d = e;
    }
    const auto v = static_cast<uint8_t>(std::clamp(std::lround(255.0 * std::log2(1.0 + std::abs(d)) / full), 0L, 255L));
    out[p * 3 + (d > 0 ? 0 : 2)] = v;
  }
  return out;
}

std::vector<uint8_t> mismatch_rgb8(const Image& a, const Image& b) {
  std::vector<uint8_t> out(a.code.size(), 0);
  for (size_t p = 0; p < a.covered.size(); ++p) {
    const bool diff = a.code[p * 3] != b.code[p * 3] || a.code[p * 3 + 1] != b.code[p * 3 + 1] ||
                      a.code[p * 3 + 2] != b.code[p * 3 + 2] || a.covered[p] != b.covered[p];
    const uint8_t v = diff ? 255 : (a.covered[p] ? 40 : 0);
    out[p * 3] = out[p * 3 + 1] = out[p * 3 + 2] = v;
  }
  return out;
}

}  // namespace shadecore::render

// SPDX-License-Identifier: Apache-2.0
// ctest driver.* (issue 39, docs/driver.md): the C99 driver routine (driver/, shadecore_light_driver.h) against the
// C++ model's setup functions (cmodel/include/shadecore/light.hpp): for random lighting states of many feature sets
// and for directed edge cases, the same (address, data) writes in the same order, or both refuse (the C++ throws,
// the C returns an error and appends nothing). Also: the generated C header (shadecore_light_regs.h) against the
// C++ register map, widths and named sets; bad input to the C routine.
//
// Random runs: SHADECORE_DRIVER_SEED (default 39) and SHADECORE_DRIVER_STATES (states per feature set, default
// 4000) reproduce or widen a run; a failure prints the seed, the feature set, the state's index and the call.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "shadecore/configs.hpp"
#include "shadecore/features.hpp"
#include "shadecore/light.hpp"
#include "shadecore/light_axi.hpp"
#include "shadecore/light_regs.hpp"
#include "shadecore_light_driver.h"

namespace {
using namespace shadecore;

// ---- the C config of a C++ feature set -----------------------------------------------------------------------
sc_light_config to_c(const FeatureSet& fs) {
  sc_light_config c{};
  c.frac = fs.format().frac;
  c.unit_frac = fs.unit_format().frac;
  c.num_lights = fs.num_lights();
  for (int j = 0; j < fs.num_lights(); ++j) c.slot_kinds |= static_cast<uint32_t>(fs.slots[static_cast<size_t>(j)]) << (4 * j);
  for (VariantId v : fs.units()) c.units |= 1u << static_cast<int>(v);
  c.first_unit = static_cast<int>(fs.variant);
  const std::pair<bool, uint32_t> flags[] = {
      {fs.ambient, SC_LIGHT_FEAT_AMBIENT},
      {fs.diffuse, SC_LIGHT_FEAT_DIFFUSE},
      {fs.norm, SC_LIGHT_FEAT_NORM},
      {fs.low_shininess, SC_LIGHT_FEAT_LOW_SHININESS},
      {fs.local_viewer, SC_LIGHT_FEAT_LOCAL_VIEWER},
      {fs.blinn, SC_LIGHT_FEAT_BLINN},
      {fs.phong, SC_LIGHT_FEAT_PHONG},
      {fs.normalize, SC_LIGHT_FEAT_NORMALIZE},
      {fs.two_side, SC_LIGHT_FEAT_TWO_SIDE},
      {fs.separate_specular, SC_LIGHT_FEAT_SEPARATE_SPECULAR},
      {fs.colour_material, SC_LIGHT_FEAT_COLOUR_MATERIAL},
  };
  for (const auto& [on, bit] : flags)
    if (on) c.features |= bit;
  return c;
}

// ---- the C++ parameters of C ones ------------------------------------------------------------------------------
LightParams to_cpp(const sc_light_light& l) {
  LightParams p;
  if (l.kind != SC_LIGHT_KIND_AUTO) p.kind = static_cast<LightKind>(l.kind);
  p.enabled = l.enabled != 0;
  for (int i = 0; i < 4; ++i) p.position[i] = l.position[i];
  for (int c = 0; c < 3; ++c) {
    p.ambient[c] = l.ambient[c];
    p.diffuse[c] = l.diffuse[c];
    p.specular[c] = l.specular[c];
    p.spot_direction[c] = l.spot_direction[c];
  }
  p.kc = l.kc, p.kl = l.kl, p.kq = l.kq;
  p.spot_cutoff = l.spot_cutoff;
  p.spot_exponent = l.spot_exponent;
  return p;
}
MaterialParams to_cpp(const sc_light_material& m) {
  MaterialParams p;
  for (int c = 0; c < 3; ++c) {
    p.emission[c] = m.emission[c];
    p.ambient[c] = m.ambient[c];
    p.diffuse[c] = m.diffuse[c];
    p.specular[c] = m.specular[c];
  }
  p.shininess = m.shininess;
  p.norm_model = m.norm_model;
  p.norm_kind = static_cast<CoefKind>(m.norm_kind);
  if (m.unit != SC_LIGHT_UNIT_DEFAULT) p.unit = static_cast<VariantId>(m.unit);
  return p;
}
ModeParams to_cpp(const sc_light_modes& m) {
  ModeParams p;
  p.local_viewer = m.local_viewer != 0;
  p.phong = m.phong != 0;
  p.normalize = m.normalize != 0;
  p.separate_specular = m.separate_specular != 0;
  p.two_side = m.two_side != 0;
  return p;
}

// ---- one call on both sides ------------------------------------------------------------------------------------
struct Outcome {
  bool ok = false;
  int err = 0;              // C: the error code
  std::string what;         // C++: the exception's message
  std::vector<RegWrite> w;  // the writes (empty when refused)
};
Outcome run_cpp(const std::function<std::vector<RegWrite>()>& f) {
  Outcome o;
  try {
    o.w = f();
    o.ok = true;
  } catch (const std::invalid_argument& e) {
    o.what = e.what();
  }
  return o;
}
// The C call into a buffer with guard words on both sides: a refused call appends nothing, none writes outside.
Outcome run_c(const std::function<int(sc_light_writes*)>& f) {
  constexpr size_t kGuard = 8, kCap = SC_LIGHT_MAX_STATE_WRITES + 4;
  std::vector<sc_light_write> store(kCap + 2 * kGuard, sc_light_write{0xDEADBEEFu, 0xDEADBEEFu});
  sc_light_writes buf;
  sc_light_writes_init(&buf, store.data() + kGuard, kCap);
  Outcome o;
  o.err = f(&buf);
  o.ok = o.err == SC_LIGHT_OK;
  for (size_t i = 0; i < kGuard; ++i) {
    EXPECT_EQ(store[i].addr, 0xDEADBEEFu);
    EXPECT_EQ(store[kGuard + kCap + i].addr, 0xDEADBEEFu);
  }
  if (!o.ok) {
    EXPECT_EQ(buf.count, 0u) << "a refused call appended writes";
  }
  for (size_t i = 0; i < buf.count; ++i) o.w.push_back({buf.w[i].addr, buf.w[i].data});
  return o;
}

std::string show(const std::vector<RegWrite>& w) {
  std::ostringstream s;
  for (const auto& x : w) s << " (" << x.addr << ", 0x" << std::hex << x.data << std::dec << ")";
  return s.str();
}

// Same writes in the same order, or both refuse. Returns false (with a failure naming ctx) otherwise.
bool same(const Outcome& cpp, const Outcome& c, const std::string& ctx) {
  if (cpp.ok != c.ok) {
    ADD_FAILURE() << ctx << ": C++ " << (cpp.ok ? "wrote" + show(cpp.w) : "threw '" + cpp.what + "'") << "; C "
                  << (c.ok ? "wrote" + show(c.w) : std::string("returned ") + sc_light_strerror(c.err));
    return false;
  }
  if (!cpp.ok) return true;
  if (cpp.w.size() != c.w.size()) {
    ADD_FAILURE() << ctx << ": " << cpp.w.size() << " writes (C++) vs " << c.w.size() << " (C)\n  C++:" << show(cpp.w)
                  << "\n  C:  " << show(c.w);
    return false;
  }
  for (size_t i = 0; i < cpp.w.size(); ++i)
    if (cpp.w[i].addr != c.w[i].addr || cpp.w[i].data != c.w[i].data) {
      ADD_FAILURE() << ctx << ": write " << i << " is (" << cpp.w[i].addr << ", 0x" << std::hex << cpp.w[i].data
                    << ") in C++, (" << std::dec << c.w[i].addr << ", 0x" << std::hex << c.w[i].data << ") in C";
      return false;
    }
  return true;
}

// ---- the C++ side of a whole state (sc_light_state_writes' order: python's LightCore.program) ------------------
std::vector<RegWrite> cpp_state_writes(const LightCore& core, const sc_light_state& st) {
  const FeatureSet& fs = core.features();
  std::vector<RegWrite> w;
  auto add = [&w](const std::vector<RegWrite>& v) { w.insert(w.end(), v.begin(), v.end()); };
  add(global_writes(core, st.global_ambient, to_cpp(st.modes)));
  add(material_writes(core, to_cpp(st.material)));
  if (st.has_back_material) add(back_material_writes(core, to_cpp(st.back_material)));
  if (fs.colour_material) {
    std::optional<ColourMaterial> cm;
    if (st.colour_material != SC_LIGHT_CM_NONE) cm = static_cast<ColourMaterial>(st.colour_material);
    add(colour_material_writes(cm));
  } else if (st.colour_material != SC_LIGHT_CM_NONE) {
    throw std::invalid_argument("colour_material: this core has no colour_material feature");
  }
  if (st.num_lights > fs.num_lights()) throw std::invalid_argument("too many lights");
  for (int j = 0; j < fs.num_lights(); ++j)
    add(j < st.num_lights ? light_writes(core, j, to_cpp(st.lights[j])) : light_off_writes(j));
  return w;
}

// ---- feature sets ------------------------------------------------------------------------------------------------
FeatureSet custom(const std::string& json) {
  return feature_set_from_json(nlohmann::json::parse(json), "light_driver_test custom set");
}
// Every named set plus custom ones: each width the lighting core takes (narrow, default; wide is refused), spec_guard
// 0 and 8, every unit, norm on cs16 / Schlick units, low shininess without norm, a slot of every kind mix.
std::vector<FeatureSet> test_sets() {
  std::vector<FeatureSet> v = named_feature_sets();
  const char* more[] = {
      R"({"name": "narrow_full", "config": "narrow", "lights": [["directional", "point", "point_att", "spot"], "spot",
          ["point", "point_att"], "directional"], "specular": ["cs16", "schlick_nr", "cs16_faithful", "cs16_compact",
          "schlick_div"], "cutoff": "sign_clamp", "norm": true, "reflection": ["blinn", "phong"], "local_viewer": true,
          "low_shininess": true, "two_side": true, "separate_specular": true, "colour_material": true})",
      R"({"name": "narrow_sg0", "config": "narrow", "spec_guard": 0, "lights": ["spot", "point_att", "point"],
          "specular": "cs16_compact", "low_shininess": true})",
      R"({"name": "narrow_sg8_iter", "config": "narrow", "spec_guard": 8, "lights": [["directional", "spot"]],
          "specular": "schlick_iter", "norm": true, "reflection": "phong"})",
      R"({"name": "default_sg8", "config": "default", "spec_guard": 8, "lights": [["directional", "point", "point_att",
          "spot"], ["directional", "point", "point_att", "spot"]], "specular": ["cs16_faithful", "cs16", "schlick_div"],
          "norm": true, "low_shininess": true})",
      R"({"name": "default_sg0_nonorm", "config": "default", "spec_guard": 0, "lights": [["point", "spot"]],
          "specular": ["schlick_div", "schlick_nr"], "reflection": ["phong", "blinn"], "local_viewer": true})",
      R"({"name": "narrow_nospec", "config": "narrow", "lights": ["point_att", "spot", "directional"],
          "specular": "none", "two_side": true, "colour_material": true})",
  };
  for (const char* j : more) v.push_back(custom(j));
  return v;
}
bool has_set(const std::vector<FeatureSet>& v, const std::string& name) {
  for (const auto& f : v)
    if (f.name == name) return true;
  return false;
}

uint64_t env_u64(const char* name, uint64_t dflt) {
  const char* s = std::getenv(name);
  return s && *s ? std::strtoull(s, nullptr, 0) : dflt;
}

// ---- random states -------------------------------------------------------------------------------------------
// Mostly legal values with their edges (0, the top of a range, rounding ties, codes that saturate), and now and
// then an illegal one (out of range, NaN, a zero direction, all-zero attenuation, a kind the slot cannot take), so
// that both acceptance and refusal are compared. set_bad(0) leaves the deliberately illegal values out (a state
// whose whole program is accepted more often).
// A direction whose unit vector has a component exactly on a rounding tie at F bits: x = ±(2k+1)/2^(F+1) with
// x² + z² == 1 in double (so |d| = 1 exactly and x·2^F = ±(k + 1/2)): llround rounds it away from 0, a
// floor(v + 1/2) would not for the negative one. False when no z near √(1 − x²) closes the sum.
bool tie_direction(int F, int k, bool negative, double d[3]) {
  const double x = std::ldexp(2.0 * k + 1.0, -(F + 1));
  double z = std::sqrt(1.0 - x * x);
  for (int t = 0; t < 64; ++t) {
    const double sum = x * x + 0.0 * 0.0 + z * z;
    if (sum == 1.0) {
      d[0] = negative ? -x : x, d[1] = 0.0, d[2] = z;
      return true;
    }
    z = sum > 1.0 ? std::nextafter(z, 0.0) : std::nextafter(z, 2.0);
  }
  return false;
}

class Gen {
 public:
  Gen(uint64_t seed, const FeatureSet& fs) : rng_(seed), fs_(fs), F_(fs.format().frac) {}
  void set_bad(double b) { bad_ = b; }

  double uni(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  int pick(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }
  bool chance(double p) { return std::bernoulli_distribution(std::min(1.0, std::max(0.0, p)))(rng_); }
  bool bad(double p) { return chance(p * bad_); }

  // a colour in [0, 2): ties k + 1/2 ulp, the top codes, values above 1 that saturate only at 2^(F+1) − 1
  double colour() {
    if (bad(0.015)) {
      const double v[] = {-1e-12, -0.5, 2.0, 2.5, 1e300, std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::infinity()};
      return v[pick(0, 6)];
    }
    switch (pick(0, 7)) {
      case 0: return 0.0;
      case 1: return 1.0;
      case 2: return std::ldexp(2.0 * pick(0, (1 << (F_ + 1)) - 1) + 1.0, -(F_ + 1));  // a tie: k + 1/2 ulp
      case 3: return std::nextafter(2.0, 0.0);                                      // saturates to 2^(F+1) − 1
      case 4: return uni(1.0, 2.0);
      case 5: return std::ldexp(pick(1, 1 << (F_ + 1)) - 0.5000000001, -F_);      // just below a tie
      default: return uni(0.0, 1.0);
    }
  }
  double att() {
    if (bad(0.02)) {
      const double v[] = {-1.0, 256.0, 1e300, std::numeric_limits<double>::quiet_NaN()};
      return v[pick(0, 3)];
    }
    switch (pick(0, 8)) {
      case 0: return 0.0;
      case 1: return 1.0;
      case 2: return std::nextafter(256.0, 0.0);                       // the top code
      case 3: return std::ldexp(0.49, -F_);                            // rounds to code 0
      case 4: return std::ldexp(2.0 * pick(0, 1000) + 1.0, -(F_ + 1));  // a tie
      case 5: return uni(0.0, 256.0);
      case 6: return 1e-9;
      default: return uni(0.0, 2.0);
    }
  }
  double coord() {
    if (bad(0.02)) {
      const double v[] = {128.0, -128.5, 1e9, std::numeric_limits<double>::quiet_NaN()};
      return v[pick(0, 3)];
    }
    switch (pick(0, 6)) {
      case 0: return 0.0;
      case 1: return -128.0;                                               // the smallest position
      case 2: return std::nextafter(128.0, 0.0);                           // rounds to 2^(F+7): clamped
      case 3: return std::ldexp(2.0 * pick(-1000, 1000) + 1.0, -(F_ + 1));  // a tie
      case 4: return uni(-128.0, 128.0);
      default: return uni(-8.0, 8.0);
    }
  }
  void direction(double d[3]) {
    if (bad(0.06)) {
      if (chance(0.5)) d[0] = d[1] = d[2] = 0.0;  // zero: refused
      else
        for (int i = 0; i < 3; ++i) d[i] = uni(-1e-200, 1e-200);  // the squares underflow to a zero length
      return;
    }
    switch (pick(0, 7)) {
      case 0:
        d[0] = 0, d[1] = 0, d[2] = pick(0, 1) ? 1.0 : -1.0;
        return;
      case 1:
        for (int i = 0; i < 3; ++i) d[i] = uni(-1e200, 1e200);  // the sum of squares overflows: d/|d| = 0
        return;
      case 2:
        d[0] = 1, d[1] = 1, d[2] = 1;  // components at 1/√3
        return;
      case 3:
        d[0] = uni(-1, 1), d[1] = 0, d[2] = 0;  // an axis (± 1 exactly)
        return;
      case 4:
        if (tie_direction(F_, pick(0, 7), chance(0.5), d)) {  // a component on a rounding tie
          if (chance(0.5)) std::swap(d[0], d[1]);
          return;
        }
        [[fallthrough]];
      default:
        for (int i = 0; i < 3; ++i) d[i] = uni(-3.0, 3.0);
    }
  }
  void rgb(double c[3]) {
    for (int i = 0; i < 3; ++i) c[i] = colour();
  }

  sc_light_light light(int j) {
    sc_light_light l;
    sc_light_light_defaults(&l);
    l.enabled = pick(0, 3) != 0;
    rgb(l.ambient), rgb(l.diffuse), rgb(l.specular);
    // w: 0 (directional), 1, other (a divide), tiny (positions out of range), negative
    const double ws[] = {0.0, 0.0, 1.0, 1.0, 0.5, 2.0, -1.0, 3.0, 1e-3};
    const double w = ws[pick(0, bad_ > 0 ? 8 : 7)];
    if (w == 0.0) {
      direction(l.position);
    } else {
      for (int i = 0; i < 3; ++i) l.position[i] = coord() * (chance(0.5) ? w : 1.0);
    }
    l.position[3] = w;
    l.kc = att(), l.kl = att(), l.kq = att();
    if (bad(0.1)) l.kc = l.kl = l.kq = 0.0;             // all-zero attenuation
    else if (chance(0.2)) l.kc = 1.0, l.kl = l.kq = 0.0;  // GL's default
    direction(l.spot_direction);
    switch (pick(0, 9)) {
      case 0: case 1: case 2: case 3: l.spot_cutoff = 180.0; break;
      case 4: l.spot_cutoff = 0.0; break;
      case 5: l.spot_cutoff = 90.0; break;
      case 6:
        if (bad(1.0)) {
          const double v[] = {90.5, -1.0, 179.0, std::numeric_limits<double>::quiet_NaN()};
          l.spot_cutoff = v[pick(0, 3)];
          break;
        }
        [[fallthrough]];
      default: l.spot_cutoff = uni(0.0, 90.0);
    }
    l.spot_exponent = chance(0.3) ? (chance(0.5) ? 0 : 128) : pick(0, 128);
    if (bad(0.03)) l.spot_exponent = chance(0.5) ? 129 : -1;
    // kind: mostly from w and the slot; sometimes one of the slot's kinds (with a w that fits it), sometimes any
    const uint8_t m = fs_.slots[static_cast<size_t>(j)];
    if (chance(0.3) || bad_ == 0) {
      if (chance(0.6)) {
        l.kind = pick(0, SC_LIGHT_NUM_KINDS - 1);
        for (int t = 0; t < 16 && !(m & (1u << l.kind)); ++t) l.kind = pick(0, SC_LIGHT_NUM_KINDS - 1);
      }
      const int k = l.kind == SC_LIGHT_KIND_AUTO ? -1 : l.kind;
      const bool dir = k == SC_LIGHT_KIND_DIRECTIONAL || (k < 0 && (m & 1u) && l.position[3] == 0.0);
      if (dir) {
        if (l.position[3] != 0.0) direction(l.position);
        l.position[3] = 0.0;
      } else if (l.position[3] == 0.0) {
        l.position[3] = 1.0;
        for (int i = 0; i < 3; ++i) l.position[i] = coord();
      }
      // a cutoff only on a spot
      const bool spot = k == SC_LIGHT_KIND_SPOT || (k < 0 && !dir && ((m & 8u) || m == 8u));
      if (!spot) l.spot_cutoff = 180.0;
      if (k < 0 && !dir && l.spot_cutoff != 180.0 && !(m & 8u)) l.spot_cutoff = 180.0;
    } else if (bad(0.1)) {
      l.kind = pick(0, SC_LIGHT_NUM_KINDS);  // any kind, SC_LIGHT_NUM_KINDS none
    }
    return l;
  }

  sc_light_material material() {
    sc_light_material m;
    sc_light_material_defaults(&m);
    rgb(m.emission), rgb(m.ambient), rgb(m.diffuse), rgb(m.specular);
    const int sh[] = {16, 17, 64, 128, 1023, 1024, 0, 1, 2, 15, 1025, -1, 2000, 100000};
    const bool low_ok = fs_.low_shininess || !fs_.specular;
    m.shininess = chance(0.6) ? sh[pick(0, bad_ > 0 || low_ok ? 13 : 5)] : pick(low_ok ? 0 : 16, 1024);
    if (bad_ == 0 && (m.shininess > 1024 || m.shininess < 0)) m.shininess = 1024;
    m.norm_model = chance(0.1) ? SC_LIGHT_NORM_OFF : (bad(0.03) ? SC_LIGHT_NUM_NORM_MODELS : pick(0, 5));
    m.norm_kind = pick(0, 1);
    const std::vector<VariantId> us = fs_.units();
    if (chance(0.5)) m.unit = SC_LIGHT_UNIT_DEFAULT;
    else if (!us.empty() && !bad(0.2)) m.unit = static_cast<int>(us[static_cast<size_t>(pick(0, static_cast<int>(us.size()) - 1))]);
    else m.unit = pick(0, 7);
    return m;
  }

  sc_light_modes modes() {
    sc_light_modes m{};
    m.local_viewer = pick(0, 1), m.phong = pick(0, 1), m.normalize = pick(0, 1);
    m.separate_specular = pick(0, 1), m.two_side = pick(0, 1);
    return m;
  }

  sc_light_state state() {
    sc_light_state st;
    const sc_light_config cfg = to_c(fs_);
    sc_light_state_defaults(&cfg, &st);
    rgb(st.global_ambient);
    st.modes = modes();
    st.material = material();
    st.has_back_material = pick(0, 1);
    st.back_material = material();
    st.colour_material = fs_.colour_material || bad(0.1) ? pick(-1, 7) : SC_LIGHT_CM_NONE;
    st.num_lights = pick(0, fs_.num_lights());
    for (int j = 0; j < st.num_lights; ++j) st.lights[j] = light(j);
    return st;
  }

 private:
  std::mt19937_64 rng_;
  const FeatureSet& fs_;
  int F_;
  double bad_ = 1.0;
};

// Compare every function on one random state; counts the calls compared and the refusals.
struct Counts {
  long calls = 0, refused = 0, states = 0, states_accepted = 0;
};
bool compare_state(const LightCore& core, const sc_light_config& cfg, const sc_light_state& st, Gen& g,
                   const std::string& ctx, Counts& n) {
  const FeatureSet& fs = core.features();
  bool ok = true;
  auto cmp = [&](const char* what, const std::function<std::vector<RegWrite>()>& cpp,
                 const std::function<int(sc_light_writes*)>& c) {
    const Outcome a = run_cpp(cpp), b = run_c(c);
    ++n.calls;
    if (!a.ok) ++n.refused;
    ok = same(a, b, ctx + " " + what) && ok;
  };
  cmp("global_writes", [&] { return global_writes(core, st.global_ambient, to_cpp(st.modes)); },
      [&](sc_light_writes* o) { return sc_light_global_writes(&cfg, st.global_ambient, &st.modes, o); });
  cmp("global_writes(default modes)", [&] { return global_writes(core, st.global_ambient); },
      [&](sc_light_writes* o) {
        sc_light_modes md;
        const int e = sc_light_default_modes(&cfg, &md);
        return e ? e : sc_light_global_writes(&cfg, st.global_ambient, &md, o);
      });
  for (const sc_light_material* m : {&st.material, &st.back_material}) {
    cmp("unit_material_writes", [&] { return unit_material_writes(core, to_cpp(*m)); },
        [&](sc_light_writes* o) { return sc_light_unit_material_writes(&cfg, m, o); });
    cmp("material_writes", [&] { return material_writes(core, to_cpp(*m)); },
        [&](sc_light_writes* o) { return sc_light_material_writes(&cfg, m, o); });
    cmp("back_material_writes", [&] { return back_material_writes(core, to_cpp(*m)); },
        [&](sc_light_writes* o) { return sc_light_back_material_writes(&cfg, m, o); });
  }
  if (st.colour_material >= SC_LIGHT_CM_NONE) {
    cmp("colour_material_writes",
        [&] {
          std::optional<ColourMaterial> cm;
          if (st.colour_material != SC_LIGHT_CM_NONE) cm = static_cast<ColourMaterial>(st.colour_material);
          return colour_material_writes(cm);
        },
        [&](sc_light_writes* o) { return sc_light_colour_material_writes(st.colour_material, o); });
  }
  for (int j = 0; j < fs.num_lights(); ++j) {
    const sc_light_light l = j < st.num_lights ? st.lights[j] : g.light(j);
    const std::string lj = "light " + std::to_string(j);
    cmp((lj + " light_writes").c_str(), [&] { return light_writes(core, j, to_cpp(l)); },
        [&](sc_light_writes* o) { return sc_light_light_writes(&cfg, j, &l, o); });
    cmp((lj + " light_reset_writes").c_str(), [&] { return light_reset_writes(core, j); },
        [&](sc_light_writes* o) { return sc_light_light_reset_writes(&cfg, j, o); });
    cmp((lj + " light_off_writes").c_str(), [&] { return light_off_writes(j); },
        [&](sc_light_writes* o) { return sc_light_light_off_writes(&cfg, j, o); });
  }
  // an index outside the slots: the C++ light_writes throws, the C refuses
  const int bad_j = g.chance(0.5) ? -1 - g.pick(0, 3) : fs.num_lights() + g.pick(0, 8);
  cmp("light_writes(bad index)", [&] { return light_writes(core, bad_j, LightParams{}); },
      [&](sc_light_writes* o) {
        sc_light_light l;
        sc_light_light_defaults(&l);
        return sc_light_light_writes(&cfg, bad_j, &l, o);
      });
  const long refused_before = n.refused;
  cmp("state_writes", [&] { return cpp_state_writes(core, st); },
      [&](sc_light_writes* o) { return sc_light_state_writes(&cfg, &st, o); });
  ++n.states;
  if (n.refused == refused_before) ++n.states_accepted;
  return ok;
}

// ---- the generated header against the C++ register map -----------------------------------------------------------
// The value LightRegs holds for register `name` (its first component; per-light registers of light 2).
int64_t stored(const LightRegs& r, std::string_view name) {
  const LightRegs::Light& L = r.light[2];
  const std::pair<std::string_view, int64_t> v[] = {
      {"global_ambient", r.global_ambient[0]}, {"light_model", r.light_model}, {"mat_n", r.mat_n},
      {"mat_thr", r.mat_thr}, {"mat_coef", r.mat_coef}, {"mat_unit", r.mat_unit},
      {"colour_material", r.colour_material}, {"mat_emission", r.emission[0]}, {"mat_ambient", r.ambient[0]},
      {"mat_diffuse", r.diffuse[0]}, {"mat_specular", r.specular[0]}, {"light_position", L.pos[0]},
      {"light_kc", L.kc}, {"light_ambient", L.ambient[0]}, {"light_kl", L.kl}, {"light_diffuse", L.diffuse[0]},
      {"light_kq", L.kq}, {"light_specular", L.specular[0]}, {"light_mode", L.mode},
      {"light_spot_direction", L.sdir[0]}, {"light_spot_cos", L.scos}, {"light_spot_exponent", L.sexp},
      {"back_mat_emission", r.back_emission[0]}, {"back_mat_ambient", r.back_ambient[0]},
      {"back_mat_diffuse", r.back_diffuse[0]}, {"back_mat_specular", r.back_specular[0]},
  };
  for (const auto& [n, x] : v)
    if (n == name) return x;
  ADD_FAILURE() << "register " << name << " unknown to this test";
  return -1;
}

TEST(DriverHeader, RegistersMatchTheCppMap) {
  struct CReg {
    const char* name;
    uint32_t addr;
    int count, per_light, reserved, sgn;
    int (*bits)(int, int);
  };
#define SC_TEST_REG(lower, UPPER)                                                                                 \
  CReg{#lower, SC_LIGHT_REG_##UPPER, SC_LIGHT_REG_##UPPER##_COUNT, SC_LIGHT_REG_##UPPER##_PER_LIGHT,               \
       SC_LIGHT_REG_##UPPER##_RESERVED, SC_LIGHT_REG_##UPPER##_SIGNED,                                             \
       [](int F, int UF) {                                                                                        \
         (void)F, (void)UF;                                                                                       \
         return static_cast<int>(SC_LIGHT_REG_##UPPER##_BITS(F, UF));                                             \
       }},
  const std::vector<CReg> c = {SC_LIGHT_REG_LIST(SC_TEST_REG)};
#undef SC_TEST_REG
  ASSERT_EQ(c.size(), kRegisters.size());
  for (size_t i = 0; i < c.size(); ++i) {
    const RegInfo& r = kRegisters[i];
    SCOPED_TRACE(std::string(r.name));
    EXPECT_EQ(c[i].name, r.name);
    EXPECT_EQ(c[i].addr, r.addr);
    EXPECT_EQ(c[i].count, r.count);
    EXPECT_EQ(c[i].per_light != 0, r.per_light);
    EXPECT_EQ(c[i].reserved != 0, r.reserved);
    // the width of the register's format against light.hpp's (every F and spec_guard the core takes)
    for (int F = SC_LIGHT_FRAC_MIN; F <= SC_LIGHT_FRAC_MAX; ++F)
      for (int UF = F; UF <= std::min(F + SC_LIGHT_SPEC_GUARD_MAX, SC_LIGHT_UNIT_FRAC_MAX); ++UF) {
        int bits = -1;
        bool sgn = false;
        const std::string_view f = r.format;
        if (f == "colour") bits = light_colour_bits(F);
        else if (f == "position") bits = light_pos_bits(F), sgn = true;
        else if (f == "direction") bits = light_normal_bits(F), sgn = true;  // the spot direction: signed F+2
        else if (f == "att_coef") bits = light_attc_bits(F);
        else if (f == "thr") bits = UF + 1;  // LightRegs::write: mask_bits(UF + 1)
        else if (f == "coef") bits = light_coef_bits(UF);
        else if (f == "spot_cos") bits = UF + 2, sgn = true;
        else if (f == "n") bits = kNBits;
        else if (f == "spot_exponent") bits = kSpotExpBits;
        else if (f == "light_model") bits = kLightModelBits;
        else if (f == "unit") bits = static_cast<int>(kMatUnitBits);
        else if (f == "light_mode") bits = static_cast<int>(kLightModeBits);
        else if (f == "colour_material") bits = static_cast<int>(kColourMaterialBits);
        ASSERT_NE(bits, -1) << "format " << f << " unknown to this test";
        EXPECT_EQ(c[i].bits(F, UF), bits) << "F " << F << " UF " << UF;
        EXPECT_EQ(c[i].sgn != 0, sgn);
      }
    // LightRegs::write (the C++ register file) keeps exactly BITS bits: all ones read back as the mask (unsigned),
    // 2^(BITS−1) − 1 and 2^(BITS−1) as the largest and the smallest value (signed); default widths F = 16, UF = 21
    if (!r.reserved) {
      const LightWidths wd{16, 21};
      const int bits = c[i].bits(16, 21);
      const uint32_t addr = r.addr + (r.per_light ? 2 * kLightStride : 0);
      if (!c[i].sgn) {
        LightRegs regs;
        ASSERT_TRUE(regs.write(wd, addr, 0xFFFFFFFFu));
        EXPECT_EQ(stored(regs, r.name), static_cast<int64_t>(SC_LIGHT_MASK(bits)));
      } else {
        LightRegs hi, lo;
        ASSERT_TRUE(hi.write(wd, addr, SC_LIGHT_MASK(bits - 1)));
        ASSERT_TRUE(lo.write(wd, addr, SC_LIGHT_MASK(bits - 1) + 1u));
        EXPECT_EQ(stored(hi, r.name), static_cast<int64_t>(SC_LIGHT_MASK(bits - 1)));
        EXPECT_EQ(stored(lo, r.name), -static_cast<int64_t>(SC_LIGHT_MASK(bits - 1)) - 1);
      }
    }
  }
}

TEST(DriverHeader, FieldsKindsUnitsAndConstantsMatch) {
  EXPECT_EQ(SC_LIGHT_MAX_LIGHTS, kMaxLights);
  EXPECT_EQ(SC_LIGHT_STRIDE, kLightStride);
  EXPECT_EQ(SC_LIGHT_ADDR_BITS, kRegAddrBits);
  EXPECT_EQ(SC_LIGHT_SPOT_EXP_BITS, kSpotExpBits);
  EXPECT_EQ(SC_LIGHT_LOW_N_BITS, kLowNBits);
  EXPECT_EQ(SC_LIGHT_MODEL_BITS, kLightModelBits);
  EXPECT_EQ(SC_LIGHT_SPEC_GUARD_DEFAULT, kSpecGuardDefault);
  EXPECT_EQ(SC_LIGHT_FRAC_MAX, kLightFracMax);
  EXPECT_EQ(SC_LIGHT_SPEC_GUARD_MAX, kSpecGuardMax);
  EXPECT_EQ(SC_LIGHT_UNIT_FRAC_MAX, kFracMax);
  EXPECT_EQ(SC_LIGHT_FMT_N_MIN, kNMin);
  EXPECT_EQ(SC_LIGHT_FMT_N_MAX, kNMax);
  EXPECT_EQ(SC_LIGHT_FMT_SPOT_EXPONENT_MAX, kSpotExpMax);
  EXPECT_EQ(SC_LIGHT_FMT_ATT_COEF_INT_BITS, kAttIntBits);
  EXPECT_EQ(SC_LIGHT_FMT_COEF_INT_BITS, kCoefIntBits);
  EXPECT_EQ(SC_LIGHT_FMT_POSITION_INT_BITS, kPosIntBits);
  EXPECT_EQ(SC_LIGHT_LM_LOCAL_VIEWER, kModelLocalViewer);
  EXPECT_EQ(SC_LIGHT_LM_PHONG, kModelPhong);
  EXPECT_EQ(SC_LIGHT_LM_NORMALIZE, kModelNormalize);
  EXPECT_EQ(SC_LIGHT_LM_TWO_SIDE, kModelTwoSide);
  EXPECT_EQ(SC_LIGHT_LM_SEPARATE_SPECULAR, kModelSeparateSpecular);
  EXPECT_EQ(SC_LIGHT_KIND_DIRECTIONAL, static_cast<int>(LightKind::Directional));
  EXPECT_EQ(SC_LIGHT_KIND_POINT, static_cast<int>(LightKind::Point));
  EXPECT_EQ(SC_LIGHT_KIND_POINT_ATT, static_cast<int>(LightKind::PointAtt));
  EXPECT_EQ(SC_LIGHT_KIND_SPOT, static_cast<int>(LightKind::Spot));
  EXPECT_EQ(SC_LIGHT_NUM_KINDS, kNumLightKinds);
  EXPECT_EQ(SC_LIGHT_COLOUR_MATERIAL_EMISSION, static_cast<int>(ColourMaterial::Emission));
  EXPECT_EQ(SC_LIGHT_COLOUR_MATERIAL_AMBIENT, static_cast<int>(ColourMaterial::Ambient));
  EXPECT_EQ(SC_LIGHT_COLOUR_MATERIAL_DIFFUSE, static_cast<int>(ColourMaterial::Diffuse));
  EXPECT_EQ(SC_LIGHT_COLOUR_MATERIAL_SPECULAR, static_cast<int>(ColourMaterial::Specular));
  EXPECT_EQ(SC_LIGHT_COLOUR_MATERIAL_AMBIENT_AND_DIFFUSE, static_cast<int>(ColourMaterial::AmbientAndDiffuse));
  for (int m = 0; m < 8; ++m)
    EXPECT_EQ(SC_LIGHT_COLOUR_MATERIAL_ENABLE_MASK | (static_cast<uint32_t>(m) << SC_LIGHT_COLOUR_MATERIAL_MODE_SHIFT),
              colour_material_word(true, static_cast<ColourMaterial>(m)));
  for (int k = 0; k < kNumLightKinds; ++k)
    for (bool en : {false, true})
      EXPECT_EQ((en ? SC_LIGHT_LIGHT_MODE_ENABLE_MASK : 0u) | (static_cast<uint32_t>(k) << SC_LIGHT_LIGHT_MODE_KIND_SHIFT),
                light_mode_word(en, static_cast<LightKind>(k)));
  // units: the ids, and which take a threshold (thr != 0 from Unit::setup at every n)
  uint32_t known = 0, thr = 0;
  for (const auto& v : kVariants) {
    known |= 1u << static_cast<int>(v.id);
    const Unit u(v.id, Format{21, 5}, Cutoff::ThetaCr);
    if (u.setup(16).thr != 0 && u.setup(1024).thr != 0) thr |= 1u << static_cast<int>(v.id);
  }
  EXPECT_EQ(SC_LIGHT_UNITS_KNOWN, known);
  EXPECT_EQ(SC_LIGHT_UNITS_THR, thr);
  EXPECT_EQ(SC_LIGHT_UNIT_CS16, static_cast<int>(VariantId::cs16));
  EXPECT_EQ(SC_LIGHT_UNIT_SCHLICK_NR, static_cast<int>(VariantId::schlick_nr));
  EXPECT_EQ(SC_LIGHT_UNIT_TABLE1024, static_cast<int>(VariantId::table1024));
  // named configs
  struct CCfg {
    const char* name;
    int frac, light;
  };
#define SC_TEST_CFG(lower, UPPER) CCfg{#lower, SC_LIGHT_CONFIG_##UPPER##_FRAC, SC_LIGHT_CONFIG_##UPPER##_LIGHT},
  const std::vector<CCfg> cfgs = {SC_LIGHT_CONFIG_LIST(SC_TEST_CFG)};
#undef SC_TEST_CFG
  ASSERT_EQ(cfgs.size(), kConfigs.size());
  for (size_t i = 0; i < cfgs.size(); ++i) {
    EXPECT_EQ(cfgs[i].name, kConfigs[i].name);
    EXPECT_EQ(cfgs[i].frac, kConfigs[i].format.frac);
    EXPECT_EQ(cfgs[i].light != 0, kConfigs[i].format.frac <= kLightFracMax);
  }
}

// Every named feature set: the header's macros (sc_light_config_named) = the C++ parser's FeatureSet.
TEST(DriverHeader, NamedFeatureSetsMatchTheParser) {
  const std::vector<FeatureSet> named = named_feature_sets();
  int listed = 0;
#define SC_TEST_COUNT(lower, UPPER) ++listed;
  SC_LIGHT_FS_LIST(SC_TEST_COUNT)
#undef SC_TEST_COUNT
  EXPECT_EQ(listed, static_cast<int>(named.size()));
  for (const FeatureSet& fs : named) {
    SCOPED_TRACE(fs.name);
    sc_light_config c{};
    ASSERT_EQ(sc_light_config_named(fs.name.c_str(), &c), SC_LIGHT_OK);
    const sc_light_config e = to_c(fs);
    EXPECT_EQ(c.frac, e.frac);
    EXPECT_EQ(c.unit_frac, e.unit_frac);
    EXPECT_EQ(c.num_lights, e.num_lights);
    EXPECT_EQ(c.slot_kinds, e.slot_kinds);
    EXPECT_EQ(c.units, e.units);
    EXPECT_EQ(c.first_unit, e.first_unit);
    EXPECT_EQ(c.features, e.features);
  }
  sc_light_config c{};
  EXPECT_EQ(sc_light_config_named("no_such_set", &c), SC_LIGHT_ERR_RANGE);
  EXPECT_EQ(sc_light_config_named(nullptr, &c), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_config_named("full", nullptr), SC_LIGHT_ERR_NULL);
}

// The energy coefficient in double: bit for bit coef_value (units/coef.hpp) for every model, kind and n.
TEST(DriverConversions, EnergyCoefficientIsCoefValue) {
  for (int m = 0; m < kNumModels; ++m)
    for (int k = 0; k < 2; ++k)
      for (int n = 0; n <= 1100; ++n) {
        const double a = coef_value(static_cast<Model>(m), static_cast<CoefKind>(k), n);
        const double b = sc_light_energy_coef(m, k, n);
        ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "model " << m << " kind " << k << " n " << n << ": " << a
                                                    << " vs " << b;
      }
  EXPECT_TRUE(std::isnan(sc_light_energy_coef(kNumModels, 0, 64)));
  EXPECT_TRUE(std::isnan(sc_light_energy_coef(0, 2, 64)));
}

// ---- the writes: random states --------------------------------------------------------------------------------
TEST(DriverWrites, RandomStatesMatchTheCppModel) {
  const uint64_t seed = env_u64("SHADECORE_DRIVER_SEED", 39);
  const long states = static_cast<long>(env_u64("SHADECORE_DRIVER_STATES", 4000));
  const std::vector<FeatureSet> sets = test_sets();
  for (const char* must : {"gl_default", "full_shared", "mono_spec", "phong_point", "narrow_full", "default_sg8"})
    ASSERT_TRUE(has_set(sets, must)) << must;
  Counts total;
  int failed_states = 0;
  for (size_t s = 0; s < sets.size(); ++s) {
    const FeatureSet& fs = sets[s];
    const LightCore core(fs);
    const sc_light_config cfg = to_c(fs);
    Gen g(seed * 1000003u + s, fs);
    Counts n;
    for (long i = 0; i < states && failed_states < 5; ++i) {
      g.set_bad(i % 2 ? 0.0 : 1.0);  // every other state without deliberately illegal values
      const sc_light_state st = g.state();
      const std::string ctx = "seed " + std::to_string(seed) + " (SHADECORE_DRIVER_SEED), feature set " + fs.name +
                              " (" + fs.summary() + "), state " + std::to_string(i);
      if (!compare_state(core, cfg, st, g, ctx, n)) ++failed_states;
    }
    // both acceptance and refusal occur for every set (the comparison is not vacuous either way)
    EXPECT_GT(n.calls - n.refused, n.calls / 3) << fs.name;
    EXPECT_GT(n.refused, 0) << fs.name;
    EXPECT_GT(n.states_accepted, n.states / 4) << fs.name << ": too few whole programs accepted";
    std::printf("  %-20s F %2d UF %2d: %ld states (%ld whole programs accepted), %ld calls, %ld refused by both\n",
                fs.name.c_str(), cfg.frac, cfg.unit_frac, n.states, n.states_accepted, n.calls, n.refused);
    total.calls += n.calls, total.refused += n.refused, total.states += n.states;
    total.states_accepted += n.states_accepted;
  }
  std::printf("light_driver_test: %ld random states over %zu feature sets (seed %llu): %ld whole programs accepted, "
              "%ld calls compared, %ld refused by both\n", total.states, sets.size(),
              static_cast<unsigned long long>(seed), total.states_accepted, total.calls, total.refused);
  EXPECT_EQ(failed_states, 0) << "replay with SHADECORE_DRIVER_SEED=" << seed;
}

// ---- the writes: directed edge cases --------------------------------------------------------------------------
struct TestCore {
  explicit TestCore(FeatureSet f) : fs(std::move(f)), core(fs), cfg(to_c(fs)) {}
  FeatureSet fs;
  LightCore core;
  sc_light_config cfg;
};
class DriverEdges : public ::testing::Test {
 protected:
  void SetUp() override {
    for (FeatureSet& f : test_sets()) cores_.push_back(std::make_unique<TestCore>(std::move(f)));
  }
  static void check_material(const TestCore& t, const sc_light_material& m, const std::string& what, int want_err = 1) {
    const Outcome a = run_cpp([&] { return material_writes(t.core, to_cpp(m)); });
    const Outcome b = run_c([&](sc_light_writes* o) { return sc_light_material_writes(&t.cfg, &m, o); });
    same(a, b, t.fs.name + " " + what);
    if (want_err != 1) {
      EXPECT_EQ(b.err, want_err) << t.fs.name << " " << what;
    }
  }
  static void check_light(const TestCore& t, int j, const sc_light_light& l, const std::string& what, int want_err = 1) {
    const Outcome a = run_cpp([&] { return light_writes(t.core, j, to_cpp(l)); });
    const Outcome b = run_c([&](sc_light_writes* o) { return sc_light_light_writes(&t.cfg, j, &l, o); });
    same(a, b, t.fs.name + " " + what);
    if (want_err != 1) {
      EXPECT_EQ(b.err, want_err) << t.fs.name << " " << what;
    }
  }
  const TestCore& named(const std::string& name) const {
    for (const auto& c : cores_)
      if (c->fs.name == name) return *c;
    throw std::invalid_argument("no test core " + name);
  }
  std::vector<std::unique_ptr<TestCore>> cores_;
};

TEST_F(DriverEdges, Shininess) {
  for (const auto& tc : cores_)
    for (int sh : {0, 1, 2, 15, 16, 17, 100, 1023, 1024, 1025, -1, -16, 4096, std::numeric_limits<int>::min(),
                   std::numeric_limits<int>::max()})
      for (int unit = -1; unit < 8; ++unit)
        for (int nm : {SC_LIGHT_NORM_OFF, 0, 3, 5, SC_LIGHT_NUM_NORM_MODELS})
          for (int nk : {SC_LIGHT_COEF_FITTED, SC_LIGHT_COEF_CLASSICAL}) {
            sc_light_material m;
            sc_light_material_defaults(&m);
            m.shininess = sh, m.unit = unit, m.norm_model = nm, m.norm_kind = nk;
            check_material(*tc, m, "shininess " + std::to_string(sh) + " unit " + std::to_string(unit) + " model " +
                                      std::to_string(nm) + " kind " + std::to_string(nk));
          }
  // the codes themselves, once by hand: gl_default (cs16, UF = 21), n = 16: thr = ceil(cos(1.5)·2^21)
  FeatureSet gl = feature_set_named_or_file("gl_default");
  sc_light_config cfg = to_c(gl);
  sc_light_material m;
  sc_light_material_defaults(&m);
  m.shininess = 16;
  sc_light_write w[16];
  sc_light_writes buf;
  sc_light_writes_init(&buf, w, 16);
  ASSERT_EQ(sc_light_unit_material_writes(&cfg, &m, &buf), SC_LIGHT_OK);
  ASSERT_EQ(buf.count, 4u);
  EXPECT_EQ(w[2].addr, SC_LIGHT_REG_MAT_THR);
  EXPECT_EQ(w[2].data, static_cast<uint32_t>(std::ceil(std::ldexp(std::cos(1.5), 21))));
  m.shininess = 15;  // no low_shininess in gl_default
  EXPECT_EQ(sc_light_unit_material_writes(&cfg, &m, &buf), SC_LIGHT_ERR_RANGE);
  m.shininess = 1025;
  EXPECT_EQ(sc_light_unit_material_writes(&cfg, &m, &buf), SC_LIGHT_ERR_RANGE);
  m.shininess = 64, m.unit = SC_LIGHT_UNIT_SCHLICK_NR;  // not in gl_default
  EXPECT_EQ(sc_light_unit_material_writes(&cfg, &m, &buf), SC_LIGHT_ERR_UNIT);
  EXPECT_EQ(buf.count, 4u);
}

TEST_F(DriverEdges, ColoursOutsideTheUnitRange) {
  const double vals[] = {0.0, 1.0, 1.5, std::nextafter(2.0, 0.0), 2.0, -0.0, -1e-300, 3.0, 1e300,
                         std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                         std::ldexp(1.0, -17), std::ldexp(3.0, -17), std::ldexp(1.0, -9), std::ldexp(3.0, -9)};
  for (const auto& tc : cores_)
    for (double v : vals)
      for (int slot = 0; slot < 4; ++slot) {
        sc_light_material m;
        sc_light_material_defaults(&m);
        (slot == 0 ? m.emission : slot == 1 ? m.ambient : slot == 2 ? m.diffuse : m.specular)[slot % 3] = v;
        const bool bad = !(v >= 0.0) || v >= 2.0;
        check_material(*tc, m, "colour " + std::to_string(v), bad ? SC_LIGHT_ERR_RANGE : SC_LIGHT_OK);
        sc_light_light l;
        sc_light_light_defaults(&l);
        (slot == 0 ? l.ambient : slot == 1 ? l.diffuse : l.specular)[slot % 3] = v;
        for (int j = 0; j < tc->fs.num_lights(); ++j) {
          if (tc->fs.slot_can(j, LightKind::Directional)) l.position[3] = 0;
          else l.position[3] = 1;
          check_light(*tc, j, l, "light colour " + std::to_string(v), bad ? SC_LIGHT_ERR_RANGE : SC_LIGHT_OK);
        }
      }
}

TEST_F(DriverEdges, AttenuationZeroAndHuge) {
  const double vals[] = {0.0, 1e-9, std::ldexp(0.5, -16), std::ldexp(0.5, -8), 1.0, 255.0, std::nextafter(256.0, 0.0),
                         256.0, 1e300, -1.0, std::numeric_limits<double>::quiet_NaN()};
  for (const auto& tc : cores_)
    for (int j = 0; j < tc->fs.num_lights(); ++j) {
      if (!tc->fs.slot_can(j, LightKind::PointAtt) && !tc->fs.slot_can(j, LightKind::Spot)) continue;
      for (double kc : vals)
        for (double kl : {0.0, 1e-9, 0.5, 300.0})
          for (double kq : {0.0, std::ldexp(0.5, -tc->fs.format().frac), 255.5}) {
            sc_light_light l;
            sc_light_light_defaults(&l);
            l.position[0] = 1, l.position[1] = -2, l.position[2] = 3, l.position[3] = 1;
            l.kind = tc->fs.slot_can(j, LightKind::PointAtt) ? SC_LIGHT_KIND_POINT_ATT : SC_LIGHT_KIND_SPOT;
            l.kc = kc, l.kl = kl, l.kq = kq;
            check_light(*tc, j, l, "attenuation " + std::to_string(kc) + " " + std::to_string(kl) + " " + std::to_string(kq));
          }
    }
  // all three 0 (or rounding to code 0) on an attenuated light: refused by both, with the C's own error
  sc_light_light l;
  sc_light_light_defaults(&l);
  l.position[3] = 1;
  l.kc = 1e-9, l.kl = 0, l.kq = 0;
  check_light(named("phong_point"), 1, l, "attenuation rounding to 0", SC_LIGHT_ERR_ATTENUATION);
}

TEST_F(DriverEdges, SpotCutoffsAndExponents) {
  std::vector<double> cut = {180.0, 0.0, 90.0, 45.0, 30.0, 60.0, 89.999, 1e-9, 90.0000001, 91.0, 179.0, -0.0, -1.0,
                             std::numeric_limits<double>::quiet_NaN()};
  for (int d = 0; d <= 90; ++d) cut.push_back(d);
  for (const auto& tc : cores_)
    for (int j = 0; j < tc->fs.num_lights(); ++j)
      for (double c : cut)
        for (int e : {0, 1, 64, 128, 129, -1})
          for (double w : {0.0, 1.0}) {
            sc_light_light l;
            sc_light_light_defaults(&l);
            l.position[0] = 0.25, l.position[1] = 0.5, l.position[2] = w == 0.0 ? 1.0 : -3.0, l.position[3] = w;
            l.spot_direction[0] = 0.1, l.spot_direction[1] = -0.2, l.spot_direction[2] = -1.0;
            l.spot_cutoff = c, l.spot_exponent = e;
            check_light(*tc, j, l, "spot cutoff " + std::to_string(c) + " exponent " + std::to_string(e) + " w " +
                                      std::to_string(w));
          }
  // spot cos at the ends (VF = 21): cutoff 0 → 2^21, 90 → 0, 180 → the smallest word
  FeatureSet full = feature_set_named_or_file("full");
  const sc_light_config cfg = to_c(full);
  sc_light_write w[32];
  for (const auto& [c, want] : std::vector<std::pair<double, uint32_t>>{{0.0, 1u << 21}, {90.0, 0u}, {180.0, 1u << 22}}) {
    sc_light_writes buf;
    sc_light_writes_init(&buf, w, 32);
    sc_light_light l;
    sc_light_light_defaults(&l);
    l.kind = SC_LIGHT_KIND_SPOT, l.position[3] = 1, l.spot_cutoff = c;
    ASSERT_EQ(sc_light_light_writes(&cfg, 0, &l, &buf), SC_LIGHT_OK);
    EXPECT_EQ(w[buf.count - 2].addr, SC_LIGHT_REG_LIGHT_SPOT_COS);
    EXPECT_EQ(w[buf.count - 2].data, want) << "cutoff " << c;
  }
}

TEST_F(DriverEdges, DirectionalAndPositionalLights) {
  const double dirs[][4] = {{0, 0, 1, 0},       {0, 0, -1, 0},  {1, 1, 1, 0},         {1e-200, 0, 0, 0}, {0, 0, 0, 0},
                            {1e200, 1e200, 0, 0}, {3, -4, 0, 0}, {0.5, 0.5, 0.5, 1},  {127.99, -128, 0, 1},
                            {128, 0, 0, 1},     {-1, 2, 3, 0.5}, {100, 0, 0, 0.5},    {1, 2, 3, -1},     {1, 2, 3, 1e-3},
                            {1, 2, 3, std::numeric_limits<double>::quiet_NaN()}, {std::ldexp(1.0, -17), 0, 0, 1}};
  for (const auto& tc : cores_)
    for (int j = 0; j < tc->fs.num_lights(); ++j)
      for (const auto& p : dirs)
        for (int kind = SC_LIGHT_KIND_AUTO; kind <= SC_LIGHT_NUM_KINDS; ++kind) {  // the last: no such kind
          sc_light_light l;
          sc_light_light_defaults(&l);
          for (int i = 0; i < 4; ++i) l.position[i] = p[i];
          l.kind = kind;
          if (kind == SC_LIGHT_KIND_SPOT) l.spot_cutoff = 30, l.spot_exponent = 10;
          check_light(*tc, j, l, "position (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
                                    std::to_string(p[2]) + ", " + std::to_string(p[3]) + ") kind " + std::to_string(kind));
        }
  // unit directions with a component on a rounding tie (both signs): as a directional light's position and as a spot
  // direction, on every core
  int ties = 0;
  for (const auto& tc : cores_)
    for (int k = 0; k < 4; ++k)
      for (bool neg : {false, true}) {
        double d[3];
        if (!tie_direction(tc->fs.format().frac, k, neg, d)) continue;
        ++ties;
        for (int j = 0; j < tc->fs.num_lights(); ++j) {
          sc_light_light l;
          sc_light_light_defaults(&l);
          if (tc->fs.slot_can(j, LightKind::Directional)) {
            l.kind = SC_LIGHT_KIND_DIRECTIONAL;
            for (int i = 0; i < 3; ++i) l.position[i] = d[i];
            check_light(*tc, j, l, "directional tie " + std::to_string(k) + (neg ? " negative" : ""), SC_LIGHT_OK);
          }
          if (tc->fs.slot_can(j, LightKind::Spot)) {
            sc_light_light_defaults(&l);
            l.kind = SC_LIGHT_KIND_SPOT, l.position[3] = 1, l.spot_cutoff = 45;
            for (int i = 0; i < 3; ++i) l.spot_direction[i] = d[i];
            check_light(*tc, j, l, "spot direction tie " + std::to_string(k) + (neg ? " negative" : ""), SC_LIGHT_OK);
          }
        }
      }
  EXPECT_GT(ties, static_cast<int>(cores_.size())) << "too few tie directions found";
  // a zero direction is the C's own error; w = 0 on a point-only slot a kind error
  sc_light_light l;
  sc_light_light_defaults(&l);
  l.position[2] = 0;
  check_light(named("gl_default"), 0, l, "zero direction", SC_LIGHT_ERR_DIRECTION);
  sc_light_light_defaults(&l);
  l.kind = SC_LIGHT_KIND_POINT;
  check_light(named("phong_point"), 0, l, "w = 0 on a point slot", SC_LIGHT_ERR_KIND);
}

// Bad input to the C routine: an error code, nothing written, never outside the buffer.
TEST(DriverBadInput, NullPointersIndicesBuffersAndConfigs) {
  sc_light_config cfg{};
  ASSERT_EQ(sc_light_config_named("full", &cfg), SC_LIGHT_OK);
  sc_light_light l;
  sc_light_light_defaults(&l);
  sc_light_material m;
  sc_light_material_defaults(&m);
  sc_light_modes md{};
  sc_light_state st;
  ASSERT_EQ(sc_light_state_defaults(&cfg, &st), SC_LIGHT_OK);
  const double amb[3] = {0.2, 0.2, 0.2};
  sc_light_write w[4 + SC_LIGHT_MAX_STATE_WRITES];
  for (auto& x : w) x = {0xDEADBEEFu, 0xDEADBEEFu};
  sc_light_writes buf;
  sc_light_writes_init(&buf, w + 2, SC_LIGHT_MAX_STATE_WRITES);
  // NULL pointers
  EXPECT_EQ(sc_light_global_writes(nullptr, amb, &md, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_global_writes(&cfg, nullptr, &md, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_global_writes(&cfg, amb, nullptr, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_global_writes(&cfg, amb, &md, nullptr), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_material_writes(&cfg, nullptr, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_unit_material_writes(&cfg, nullptr, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_back_material_writes(&cfg, nullptr, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_light_writes(&cfg, 0, nullptr, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_light_writes(nullptr, 0, &l, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_light_off_writes(nullptr, 0, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_light_reset_writes(&cfg, 0, nullptr), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_colour_material_writes(0, nullptr), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_state_writes(&cfg, nullptr, &buf), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_default_modes(&cfg, nullptr), SC_LIGHT_ERR_NULL);
  EXPECT_EQ(sc_light_state_defaults(&cfg, nullptr), SC_LIGHT_ERR_NULL);
  sc_light_writes nobuf;
  sc_light_writes_init(&nobuf, nullptr, 100);  // no storage: capacity 0
  EXPECT_EQ(sc_light_light_writes(&cfg, 0, &l, &nobuf), SC_LIGHT_ERR_SPACE);
  sc_light_writes broken{nullptr, 5, 0};  // a NULL array with a capacity
  EXPECT_EQ(sc_light_light_writes(&cfg, 0, &l, &broken), SC_LIGHT_ERR_NULL);
  sc_light_light_defaults(nullptr);  // no crash
  sc_light_material_defaults(nullptr);
  sc_light_writes_init(nullptr, w, 4);
  // light indices outside the slots
  for (int j : {-1, -100, cfg.num_lights, SC_LIGHT_MAX_LIGHTS, 1000, std::numeric_limits<int>::min(),
                std::numeric_limits<int>::max()}) {
    EXPECT_EQ(sc_light_light_writes(&cfg, j, &l, &buf), SC_LIGHT_ERR_INDEX) << j;
    EXPECT_EQ(sc_light_light_off_writes(&cfg, j, &buf), SC_LIGHT_ERR_INDEX) << j;
    EXPECT_EQ(sc_light_light_reset_writes(&cfg, j, &buf), SC_LIGHT_ERR_INDEX) << j;
  }
  sc_light_config one{};
  ASSERT_EQ(sc_light_config_named("gl_default", &one), SC_LIGHT_OK);
  EXPECT_EQ(sc_light_light_writes(&one, 1, &l, &buf), SC_LIGHT_ERR_INDEX);  // a 1-slot core
  st.num_lights = cfg.num_lights + 1;
  EXPECT_EQ(sc_light_state_writes(&cfg, &st, &buf), SC_LIGHT_ERR_INDEX);
  st.num_lights = -1;
  EXPECT_EQ(sc_light_state_writes(&cfg, &st, &buf), SC_LIGHT_ERR_INDEX);
  st.num_lights = 0;
  // colour material: a mode outside the field, a core without the feature
  EXPECT_EQ(sc_light_colour_material_writes(8, &buf), SC_LIGHT_ERR_RANGE);
  EXPECT_EQ(sc_light_colour_material_writes(-2, &buf), SC_LIGHT_ERR_RANGE);
  st.colour_material = SC_LIGHT_COLOUR_MATERIAL_DIFFUSE;
  sc_light_state st1;
  ASSERT_EQ(sc_light_state_defaults(&one, &st1), SC_LIGHT_OK);
  st1.colour_material = SC_LIGHT_COLOUR_MATERIAL_DIFFUSE;
  EXPECT_EQ(sc_light_state_writes(&one, &st1, &buf), SC_LIGHT_ERR_FEATURE);
  // a bad coefficient kind with normalisation
  m.norm_kind = 2;
  EXPECT_EQ(sc_light_material_writes(&cfg, &m, &buf), SC_LIGHT_ERR_RANGE);
  m.norm_kind = SC_LIGHT_COEF_FITTED;
  // configs that describe no lighting core: the wide width (the C++ parser refuses it too), bad slots or units
  EXPECT_THROW(custom(R"({"config": "wide"})"), std::invalid_argument);
  sc_light_config bad = cfg;
  bad.frac = SC_LIGHT_CONFIG_WIDE_FRAC, bad.unit_frac = SC_LIGHT_CONFIG_WIDE_FRAC;
  EXPECT_EQ(sc_light_light_writes(&bad, 0, &l, &buf), SC_LIGHT_ERR_CONFIG);
  bad = cfg, bad.unit_frac = cfg.frac - 1;
  EXPECT_EQ(sc_light_material_writes(&bad, &m, &buf), SC_LIGHT_ERR_CONFIG);
  bad = cfg, bad.unit_frac = cfg.frac + SC_LIGHT_SPEC_GUARD_MAX + 1;
  EXPECT_EQ(sc_light_material_writes(&bad, &m, &buf), SC_LIGHT_ERR_CONFIG);
  bad = cfg, bad.num_lights = 0;
  EXPECT_EQ(sc_light_light_off_writes(&bad, 0, &buf), SC_LIGHT_ERR_CONFIG);
  bad = cfg, bad.num_lights = SC_LIGHT_MAX_LIGHTS + 1;
  EXPECT_EQ(sc_light_light_off_writes(&bad, 0, &buf), SC_LIGHT_ERR_CONFIG);
  bad = cfg, bad.units = 1u << 20;
  EXPECT_EQ(sc_light_material_writes(&bad, &m, &buf), SC_LIGHT_ERR_CONFIG);
  bad = cfg, bad.first_unit = 31;
  EXPECT_EQ(sc_light_material_writes(&bad, &m, &buf), SC_LIGHT_ERR_CONFIG);
  bad = cfg, bad.first_unit = SC_LIGHT_UNIT_SCHLICK_DIV;  // not one of the core's units
  EXPECT_EQ(sc_light_material_writes(&bad, &m, &buf), SC_LIGHT_ERR_CONFIG);
  EXPECT_EQ(buf.count, 0u) << "a refused call appended writes";
  // a buffer that fills: the call that does not fit appends nothing
  sc_light_writes small;
  sc_light_writes_init(&small, w + 2, 20);
  ASSERT_EQ(sc_light_light_writes(&cfg, 0, &l, &small), SC_LIGHT_OK);  // a directional light: 1 + 3 + 9 = 13
  EXPECT_EQ(small.count, 13u);
  EXPECT_EQ(sc_light_material_writes(&cfg, &m, &small), SC_LIGHT_ERR_SPACE);  // 16 more do not fit
  EXPECT_EQ(small.count, 13u);
  ASSERT_EQ(sc_light_global_writes(&cfg, amb, &md, &small), SC_LIGHT_OK);  // 4 do
  EXPECT_EQ(small.count, 17u);
  small.count = 25;  // a corrupt count beyond the capacity
  EXPECT_EQ(sc_light_colour_material_writes(0, &small), SC_LIGHT_ERR_SPACE);
  ASSERT_EQ(sc_light_state_writes(&cfg, &st, &buf), SC_LIGHT_OK);
  EXPECT_LE(buf.count, static_cast<size_t>(SC_LIGHT_MAX_STATE_WRITES));
  st.num_lights = cfg.num_lights;
  for (int j = 0; j < cfg.num_lights; ++j) st.lights[j].kind = SC_LIGHT_KIND_SPOT, st.lights[j].position[3] = 1;
  st.has_back_material = 1;
  buf.count = 0;
  ASSERT_EQ(sc_light_state_writes(&cfg, &st, &buf), SC_LIGHT_OK);
  EXPECT_EQ(buf.count, static_cast<size_t>(SC_LIGHT_MAX_STATE_WRITES)) << "the largest state fills the bound exactly";
  EXPECT_EQ(w[0].addr, 0xDEADBEEFu);
  EXPECT_EQ(w[1].addr, 0xDEADBEEFu);
  EXPECT_EQ(w[2 + SC_LIGHT_MAX_STATE_WRITES].addr, 0xDEADBEEFu);
  EXPECT_EQ(w[3 + SC_LIGHT_MAX_STATE_WRITES].addr, 0xDEADBEEFu);
  for (int e = 0; e >= SC_LIGHT_ERR_SPACE; --e) EXPECT_STRNE(sc_light_strerror(e), "unknown error") << e;
}

}  // namespace

// The AXI view (rtl/sc_light_axi.v, issue 39): the C header's stream packing macros are the C++ packing of
// shadecore/light_axi.hpp (both generated from config/configs.json light.axi) at every width F, and the register
// existence rule answers as docs/handoff.md "AXI view" states it on sets with and without each capability.
TEST(DriverHeader, AxiStreamPackingMatchesTheCpp) {
  for (int f = SC_LIGHT_FRAC_MIN; f <= SC_LIGHT_FRAC_MAX; ++f) {
    const int in_lsb[] = {SC_LIGHT_AXIS_IN_NX_LSB(f), SC_LIGHT_AXIS_IN_NY_LSB(f), SC_LIGHT_AXIS_IN_NZ_LSB(f),
                          SC_LIGHT_AXIS_IN_PX_LSB(f), SC_LIGHT_AXIS_IN_PY_LSB(f), SC_LIGHT_AXIS_IN_PZ_LSB(f),
                          SC_LIGHT_AXIS_IN_BACK_LSB(f), SC_LIGHT_AXIS_IN_CR_LSB(f), SC_LIGHT_AXIS_IN_CG_LSB(f),
                          SC_LIGHT_AXIS_IN_CB_LSB(f)};
    const int in_bits[] = {SC_LIGHT_AXIS_IN_NX_BITS(f), SC_LIGHT_AXIS_IN_NY_BITS(f), SC_LIGHT_AXIS_IN_NZ_BITS(f),
                           SC_LIGHT_AXIS_IN_PX_BITS(f), SC_LIGHT_AXIS_IN_PY_BITS(f), SC_LIGHT_AXIS_IN_PZ_BITS(f),
                           SC_LIGHT_AXIS_IN_BACK_BITS(f), SC_LIGHT_AXIS_IN_CR_BITS(f), SC_LIGHT_AXIS_IN_CG_BITS(f),
                           SC_LIGHT_AXIS_IN_CB_BITS(f)};
    ASSERT_EQ(kAXIS_IN_fields.size(), 10u);
    for (size_t i = 0; i < kAXIS_IN_fields.size(); ++i) {
      EXPECT_EQ(in_lsb[i], axis_lsb(kAXIS_IN_fields, kAXIS_IN_fields[i].name, f)) << kAXIS_IN_fields[i].name << " F=" << f;
      EXPECT_EQ(in_bits[i], axis_width(kAXIS_IN_fields[i].width, f)) << kAXIS_IN_fields[i].name << " F=" << f;
    }
    // the fields the core's ports have: N (F+2), P (F+8), back (1), colour (F+1)
    EXPECT_EQ(SC_LIGHT_AXIS_IN_NX_BITS(f), light_normal_bits(f));
    EXPECT_EQ(SC_LIGHT_AXIS_IN_PX_BITS(f), light_pos_bits(f));
    EXPECT_EQ(SC_LIGHT_AXIS_IN_CR_BITS(f), light_colour_bits(f));
    EXPECT_EQ(SC_LIGHT_AXIS_IN_TDATA_BITS(f), axis_tdata_bits(kAXIS_IN_fields, f));
    EXPECT_EQ(SC_LIGHT_AXIS_IN_TDATA_BITS(f) % 8, 0);
    const int out_lsb[] = {SC_LIGHT_AXIS_OUT_R_LSB(f), SC_LIGHT_AXIS_OUT_G_LSB(f), SC_LIGHT_AXIS_OUT_B_LSB(f),
                           SC_LIGHT_AXIS_OUT_SR_LSB(f), SC_LIGHT_AXIS_OUT_SG_LSB(f), SC_LIGHT_AXIS_OUT_SB_LSB(f)};
    for (size_t i = 0; i < kAXIS_OUT_fields.size(); ++i)
      EXPECT_EQ(out_lsb[i], axis_lsb(kAXIS_OUT_fields, kAXIS_OUT_fields[i].name, f)) << kAXIS_OUT_fields[i].name;
    EXPECT_EQ(SC_LIGHT_AXIS_OUT_TDATA_BITS(f), axis_tdata_bits(kAXIS_OUT_fields, f));
  }
  EXPECT_EQ(SC_LIGHT_AXI_ADDR(SC_LIGHT_REG_LIGHT_MODE), 48u * 4u);
}

TEST(DriverHeader, AxiRegisterExistence) {
  const FeatureSet diffuse = feature_set_named_or_file("diffuse");
  const FeatureSet full = feature_set_named_or_file("full_shared");
  // every address of the map is either a register (OKAY) or not (SLVERR); the gaps and the reserved back unit
  // registers never are
  for (const FeatureSet* fs : {&diffuse, &full}) {
    for (uint32_t w : {9u, 15u, 31u, 291u, 295u, 299u, 303u, 304u, 511u}) EXPECT_FALSE(axi_reg_exists(*fs, w)) << w;
    EXPECT_TRUE(axi_reg_exists(*fs, kReg_light_model));
    EXPECT_TRUE(axi_reg_exists(*fs, kReg_light_mode));
    EXPECT_TRUE(axi_reg_exists(*fs, kReg_light_position + 2));
  }
  // diffuse: no specular unit, one directional slot
  EXPECT_FALSE(axi_reg_exists(diffuse, kReg_mat_n));
  EXPECT_FALSE(axi_reg_exists(diffuse, kReg_mat_specular));
  EXPECT_FALSE(axi_reg_exists(diffuse, kReg_light_kc));
  EXPECT_FALSE(axi_reg_exists(diffuse, kReg_light_spot_cos));
  EXPECT_FALSE(axi_reg_exists(diffuse, kReg_light_mode + kLightStride));  // slot 1 is not built
  EXPECT_FALSE(axi_reg_exists(diffuse, kReg_back_mat_diffuse));
  EXPECT_TRUE(axi_reg_exists(diffuse, kReg_mat_diffuse + 2));
  // full_shared: eight slots of every kind, spot, two-sided, colour material
  ASSERT_EQ(full.num_lights(), 8);
  for (int j = 0; j < 8; ++j) {
    EXPECT_TRUE(axi_reg_exists(full, kReg_light_spot_exponent + kLightStride * static_cast<uint32_t>(j))) << j;
    EXPECT_TRUE(axi_reg_exists(full, kReg_light_kq + kLightStride * static_cast<uint32_t>(j))) << j;
  }
  EXPECT_TRUE(axi_reg_exists(full, kReg_back_mat_specular + 1));
  EXPECT_TRUE(axi_reg_exists(full, kReg_colour_material));
  EXPECT_EQ(axi_reg_exists(full, kReg_mat_coef), full.norm);
}

// SPDX-License-Identifier: Apache-2.0
// shadecore — bit-accurate model of the lighting core rtl/sc_light.v (docs/lighting.md).
//
// Per fragment (normal N, eye-space position P) and colour channel c, OpenGL 1.x fixed-function
// lighting (glLight/glMaterial semantics), division-free:
//
//   colour_c = e_c + a_c·A_c + Σ_j att_j·( a_c·Ia_jc + max(N̂·L_j, 0)·d_c·Id_jc + f_j·s_c·Is_jc·spec(x_j, n) )
//
// clamped to [0, 1]. Which terms and units exist is the FeatureSet (shadecore/features.hpp); a term
// that is off is 0 here and absent in the RTL. The arithmetic of every stage is spelled out below
// with its widths; every ⌊·⌋ is a truncation the RTL also makes (arithmetic shift for signed values).
//
// Formats (F = the feature set's config frac, <= 16; "code/2^F" unless said otherwise):
//   normal N           signed F+2 bits (any length: interpolated normals are not unit)
//   position P, P_j    signed F+8 bits: [−128, 128) eye-space units
//   direction (w = 0)  the light_position register holds the unit direction to the light as a code; the
//                      core reads it saturated to the signed F+2 bits of [−2, 2) (a unit code never saturates)
//   colours            unsigned F+1 bits: [0, 2)
//   kc, kl, kq         unsigned F+8 bits: [0, 256)
//   n, thr, coef       as the specular unit (docs/spec.md §3.1, §7): 11 bits, F+1 bits, F+8 bits
//   spot direction     signed F+2 bits: the unit direction ŝ the light points along (a code, as a directional
//                      light's); spot cos: signed VF+2 bits (VF = F + spec_guard), ⌈cos(cutoff)·2^VF⌉;
//                      spot exponent: 8 bits, unsigned (GL: 0..128)
//   output colour      unsigned F+1 bits, saturated to [0, 2^F]
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadecore/units/coef.hpp"
#include "shadecore/features.hpp"
#include "shadecore/analysis/golden.hpp"
#include "shadecore/units/normalize.hpp"
#include "shadecore/units/recip.hpp"
#include "shadecore/light_regs.hpp"
#include "shadecore/unit.hpp"

namespace shadecore {

inline constexpr int kPosIntBits = 7;  // positions in [−128, 128)
inline constexpr int light_normal_bits(int F) { return F + 2; }
inline constexpr int light_pos_bits(int F) { return F + 1 + kPosIntBits; }
inline constexpr int light_colour_bits(int F) { return F + 1; }
inline constexpr int light_attc_bits(int F) { return F + kAttIntBits; }
inline constexpr int light_coef_bits(int F) { return F + kCoefIntBits; }  // = sc_specular's default COEFW

inline int64_t sign_extend(uint64_t v, int bits) {
  const int sh = 64 - bits;
  return static_cast<int64_t>(v << sh) >> sh;
}
inline uint64_t mask_bits(int bits) { return bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1; }

// x^e by an exact square-and-multiply chain (rtl/sc_powi.v), x in [0, 1] as a code of `frac` fraction bits
// (x <= 2^frac): over the exponent's bits k = 0 .. ebits−1, low first, r ← ⌊r·p / 2^frac⌋ where bit k is set and
// p ← ⌊p² / 2^frac⌋, from r = 2^frac (x^0 = 1 for every x, 0 included: GL's convention) and p = x. Every
// value stays in [0, 2^frac]; each product's truncation is the only rounding, so the result is at most e − 1
// codes below x^e·2^frac (e >= 1; exact for e <= 1) and never above it (docs/lighting.md §3.4).
inline uint64_t powi_chain(int frac, uint64_t x, uint32_t e, int ebits) {
  uint64_t r = uint64_t{1} << frac, p = x;
  for (int k = 0; k < ebits; ++k) {
    if ((e >> k) & 1u) r = (r * p) >> frac;
    p = (p * p) >> frac;
  }
  return r;
}
// kSpotExpBits (config/configs.json "light" spot_exponent_bits, light_regs.hpp): the spot exponent register's
// width and the chain's stages; every exponent below 2^kSpotExpBits is computed, GL uses 0..128
inline constexpr int kSpotExpMax = 128;  // GL_SPOT_EXPONENT's range (the host rejects more)
// kLowNBits (config/configs.json "light" low_shininess_bits): with the feature low_shininess a shininess n below
// 2^kLowNBits — the units' smallest n — is x^n from the same chain, kLowNBits stages (docs/lighting.md §3.5)
static_assert((1 << kLowNBits) == kNMin, "low_shininess_bits must cover exactly the shininess below the units' range");

// The register file of sc_light, as the codes the hardware holds (register map: light_regs.hpp).
// Mode registers (docs/lighting.md §4): light_model (bit 0 local viewer, bit 1 Phong reflection, bit 2
// normalize), mat_unit (a variant id), per light mode (bit 0 enable, bits 3:1 kind). Registers are not
// reset, in the RTL as here: a program writes every register it relies on.
inline constexpr uint32_t kMatUnitBits = 4;
inline constexpr uint32_t kLightModeBits = 4;
// light_model's fields: kLightModelBits and the bit positions kLmBit_* from config/configs.json (light_regs.hpp;
// the RTL's LM_* of sc_light_regs.vh)
inline constexpr uint32_t kModelLocalViewer = 1u << kLmBit_local_viewer, kModelPhong = 1u << kLmBit_phong,
                          kModelNormalize = 1u << kLmBit_normalize;
inline constexpr uint32_t kModelTwoSide = 1u << kLmBit_two_side;  // GL_LIGHT_MODEL_TWO_SIDE (feature two_side)
inline constexpr uint32_t kModelSeparateSpecular = 1u << kLmBit_separate_specular;  // GL_SEPARATE_SPECULAR_COLOR
inline constexpr uint32_t kModeEnable = 1u;
// colour_material (feature colour_material, docs/lighting.md §3.8): bit 0 GL_COLOR_MATERIAL, bits 3:1 the
// glColorMaterial mode; the fragment's colour replaces that material colour of the side it is lit as (both
// faces: GL_FRONT_AND_BACK, GL's default face). Modes 5..7 replace nothing.
inline constexpr uint32_t kColourMaterialBits = 4;
enum class ColourMaterial : uint32_t { Emission = 0, Ambient = 1, Diffuse = 2, Specular = 3, AmbientAndDiffuse = 4 };
inline constexpr uint32_t colour_material_word(bool enable, ColourMaterial m) {
  return enable ? 1u | (static_cast<uint32_t>(m) << 1) : 0u;
}
inline constexpr uint32_t light_mode_word(bool enable, LightKind k) {
  return (enable ? kModeEnable : 0u) | (static_cast<uint32_t>(k) << 1);
}

// The widths a register write needs: F (colours, positions, attenuation) and the unit's UF = F +
// spec_guard (mat_thr, mat_coef: the unit's material formats). LightCore::widths().
struct LightWidths {
  int F = 16, UF = 16;
};

struct LightRegs {
  uint32_t global_ambient[3] = {};
  uint32_t light_model = 0, mat_unit = 0;
  uint32_t colour_material = 0;  // feature colour_material: bit 0 enable, bits 3:1 the mode (ColourMaterial)
  uint32_t mat_n = kNMin, mat_thr = 0, mat_coef = 0;
  uint32_t emission[3] = {}, ambient[3] = {}, diffuse[3] = {}, specular[3] = {};
  // the back colour bank (two_side): a back-facing fragment's material colours in the two-sided mode
  uint32_t back_emission[3] = {}, back_ambient[3] = {}, back_diffuse[3] = {}, back_specular[3] = {};
  struct Light {
    uint32_t mode = 0;
    int64_t pos[3] = {};
    uint32_t ambient[3] = {}, diffuse[3] = {}, specular[3] = {};
    uint32_t kc = 0, kl = 0, kq = 0;
    int64_t sdir[3] = {};   // spot direction, signed F+2 bits
    int64_t scos = 0;       // ⌈cos(cutoff)·2^VF⌉, signed VF+2 bits
    uint32_t sexp = 0;      // spot exponent, 8 bits
  };
  std::array<Light, kMaxLights> light{};

  // What a write of `data` to `addr` does: the register takes the low bits of its width (signed
  // formats sign-extended); an address that is no register (or a reserved one) is ignored. Returns
  // false for those.
  bool write(const LightWidths& w, uint32_t addr, uint32_t data) {
    const int F = w.F;
    const uint32_t col = static_cast<uint32_t>(data & mask_bits(light_colour_bits(F)));
    const uint32_t attc = static_cast<uint32_t>(data & mask_bits(light_attc_bits(F)));
    for (int c = 0; c < 3; ++c) {
      if (addr == kReg_global_ambient + c) return global_ambient[c] = col, true;
      if (addr == kReg_mat_emission + c) return emission[c] = col, true;
      if (addr == kReg_mat_ambient + c) return ambient[c] = col, true;
      if (addr == kReg_mat_diffuse + c) return diffuse[c] = col, true;
      if (addr == kReg_mat_specular + c) return specular[c] = col, true;
      if (addr == kReg_back_mat_emission + c) return back_emission[c] = col, true;
      if (addr == kReg_back_mat_ambient + c) return back_ambient[c] = col, true;
      if (addr == kReg_back_mat_diffuse + c) return back_diffuse[c] = col, true;
      if (addr == kReg_back_mat_specular + c) return back_specular[c] = col, true;
    }
    if (addr == kReg_light_model) return light_model = data & mask_bits(kLightModelBits), true;
    if (addr == kReg_mat_unit) return mat_unit = data & mask_bits(kMatUnitBits), true;
    if (addr == kReg_colour_material) return colour_material = data & mask_bits(kColourMaterialBits), true;
    if (addr == kReg_mat_n) return mat_n = data & 0x7FF, true;
    if (addr == kReg_mat_thr) return mat_thr = static_cast<uint32_t>(data & mask_bits(w.UF + 1)), true;
    if (addr == kReg_mat_coef) return mat_coef = static_cast<uint32_t>(data & mask_bits(light_coef_bits(w.UF))), true;
    if (addr < kReg_light_position || addr >= kReg_light_position + kMaxLights * kLightStride) return false;
    const uint32_t j = (addr - kReg_light_position) / kLightStride;
    const uint32_t off = addr - j * kLightStride;
    if (j >= static_cast<uint32_t>(kMaxLights)) return false;
    Light& L = light[j];
    for (int c = 0; c < 3; ++c) {
      if (off == kReg_light_position + c) return L.pos[c] = sign_extend(data, light_pos_bits(F)), true;
      if (off == kReg_light_ambient + c) return L.ambient[c] = col, true;
      if (off == kReg_light_diffuse + c) return L.diffuse[c] = col, true;
      if (off == kReg_light_specular + c) return L.specular[c] = col, true;
    }
    if (off == kReg_light_kc) return L.kc = attc, true;
    if (off == kReg_light_kl) return L.kl = attc, true;
    if (off == kReg_light_kq) return L.kq = attc, true;
    if (off == kReg_light_mode) return L.mode = data & mask_bits(kLightModeBits), true;
    for (int c = 0; c < 3; ++c)
      if (off == kReg_light_spot_direction + c) return L.sdir[c] = sign_extend(data, F + 2), true;
    if (off == kReg_light_spot_cos) return L.scos = sign_extend(data, w.UF + 2), true;
    if (off == kReg_light_spot_exponent) return L.sexp = data & static_cast<uint32_t>(mask_bits(kSpotExpBits)), true;
    return false;
  }
};

struct RegWrite {
  uint32_t addr, data;
};

struct Fragment {
  int64_t n[3] = {0, 0, 0};  // signed F+2-bit codes
  int64_t p[3] = {0, 0, 0};  // signed F+8-bit codes
  bool back = false;         // in_back_i: the fragment's polygon faces away (window-space winding; two_side)
  uint32_t col[3] = {0, 0, 0};  // in_cr_i, in_cg_i, in_cb_i: the fragment's colour, material colour codes (F+1
                                // bits, [0, 2)); used only by colour_material's mode (docs/lighting.md §3.8)
};

// The core's output: the primary colour c and, with separate_specular in the separate mode, the secondary
// colour s (the specular sum; 0 otherwise). GL's colour sum is min(1, c + s) (colour_sum()).
struct Colour {
  uint32_t c[3] = {0, 0, 0};
  uint32_t s[3] = {0, 0, 0};
  bool operator==(const Colour& o) const {
    return c[0] == o.c[0] && c[1] == o.c[1] && c[2] == o.c[2] && s[0] == o.s[0] && s[1] == o.s[1] && s[2] == o.s[2];
  }
  [[nodiscard]] uint32_t colour_sum(int ch, uint32_t one) const { return std::min(c[ch] + s[ch], one); }
  bool operator!=(const Colour& o) const { return !(*this == o); }
};

// Per-light intermediates (names of rtl/sc_light_lane.v's signals).
struct LightTrace {
  bool on = false;     // enabled with a kind its slot can take
  LightKind kind = LightKind::Directional;
  int64_t l[3] = {};   // unit direction to the light (VF = F + spec_guard fraction bits)
  uint64_t d = 0;      // distance, F fraction bits (point_att)
  uint64_t q = 0;      // kc + kl·d + kq·d² (point_att)
  uint64_t att = 0;    // 1/q, F fraction bits, saturated (point_att); 2^F otherwise; spot: ⌊1/q · spot / 2^VF⌋
  int64_t sdl = 0;     // spot: ⌊−L̂·ŝ / 2^VF⌋ (ŝ the direction register · 2^spec_guard), VF fraction bits
  bool in_cone = false;  // spot: sdl >= the spot cos register
  uint64_t spot = 0;   // spot: in_cone ? powi_chain(VF, clamp(sdl, 0, 2^VF), exponent) : 0 (VF fraction bits)
  int64_t ndl = 0;     // ⌊N̂·L / 2^VF⌋, signed, VF fraction bits
  uint32_t diff = 0;   // clamp(⌊ndl / 2^(VF−F)⌋, 0, 2^F)
  bool f = false;      // ndl > 0 (and the material's unit exists)
  int64_t x = 0;       // the specular unit's input code (clamped to its signed VF+2-bit word)
  uint32_t spec = 0;   // the unit's output (VF+1 bits, or VF+8 bits with norm)
  uint64_t term[3] = {};  // the light's contribution per channel (after attenuation); in the separate-specular
                          // mode the ambient and diffuse part ⌊att·(amb + diff)/2^F⌋ only
  uint64_t sterm[3] = {}; // the separate-specular mode: the specular part ⌊att·spec/2^F⌋ (else 0)
};
struct LightCoreTrace {
  int64_t nn[3] = {};  // N̂ (or N unchanged without normalize)
  int64_t v[3] = {};   // V̂
  int passes = 1;      // ⌈enabled lights / lanes⌉, at least 1
  uint64_t scene[3] = {};
  std::array<LightTrace, kMaxLights> light{};
  uint64_t total[3] = {};
  uint64_t stotal[3] = {};  // separate_specular: Σ sterm
};

// The modes a register state selects among a core's capabilities (docs/lighting.md §4, the RTL's
// decode): a mode naming an absent capability selects what exists — a light whose kind its slot
// cannot take is off; local viewer / normalize without the hardware are off; the reflection is the
// one that exists; a mat_unit naming an absent unit gives specular 0.
struct LightModes {
  bool local_viewer = false, phong = false, normalize = false;
  bool low_n = false;  // mat_n < 2^kLowNBits with the low_shininess chain: spec = x^n from the chain, not the unit
  bool separate = false;  // light_model bit 4 with separate_specular: the specular sum is the secondary output
  bool two_side = false;  // light_model bit 3 with two_side: a back fragment is lit with −N and the back colours
  // colour_material with its register's bit 0: the material colours the fragment's colour replaces
  bool cm_emission = false, cm_ambient = false, cm_diffuse = false, cm_specular = false;
  int unit = -1;  // index into FeatureSet::units(), −1: absent (specular 0)
  uint32_t on = 0;  // bit j: light j contributes
  int enabled = 0;  // lights on
};

class LightCore {
 public:
  explicit LightCore(FeatureSet fs) : fs_(std::move(fs)), f_(fs_.format()), uf_(fs_.unit_format()) {
    for (VariantId v : fs_.units()) {
      units_.emplace_back(v, uf_, fs_.cutoff);
      if (fs_.norm) units_.back().set_energy(true, 0);  // the coefficient comes from mat_coef; the model index is unused
      // MREG reaches every unit; those without the parameter (mreg_stages 0: schlick_iter) ignore it
      if (fs_.mreg != 0 && mreg_stages(v) > 0) units_.back().set_mreg(fs_.mreg);
    }
    if (units_.empty()) units_.emplace_back(fs_.variant, uf_, fs_.cutoff);  // latency / setup only
  }

  [[nodiscard]] const FeatureSet& features() const { return fs_; }
  [[nodiscard]] const Format& format() const { return f_; }
  // The specular path's format (F + spec_guard fraction bits): N̂, V̂, L̂, Ĥ, R, x and the units.
  [[nodiscard]] const Format& unit_format() const { return uf_; }
  [[nodiscard]] LightWidths widths() const { return {f_.frac, uf_.frac}; }
  // The first unit (the only one of a specialised core).
  [[nodiscard]] const Unit& unit() const { return units_.front(); }
  [[nodiscard]] const std::vector<Unit>& units() const { return units_; }

  [[nodiscard]] LightModes modes(const LightRegs& r) const {
    LightModes m;
    m.local_viewer = fs_.specular && fs_.local_viewer && (r.light_model & kModelLocalViewer);
    m.phong = fs_.phong && (!fs_.blinn || (r.light_model & kModelPhong));
    m.normalize = fs_.normalize && (r.light_model & kModelNormalize);
    m.low_n = fs_.low_shininess && r.mat_n < (1u << kLowNBits);
    m.separate = fs_.separate_specular && (r.light_model & kModelSeparateSpecular);
    m.two_side = fs_.two_side && (r.light_model & kModelTwoSide);
    if (fs_.colour_material && (r.colour_material & 1u)) {
      const auto cm = static_cast<ColourMaterial>(r.colour_material >> 1);
      m.cm_emission = cm == ColourMaterial::Emission;
      m.cm_ambient = cm == ColourMaterial::Ambient || cm == ColourMaterial::AmbientAndDiffuse;
      m.cm_diffuse = cm == ColourMaterial::Diffuse || cm == ColourMaterial::AmbientAndDiffuse;
      m.cm_specular = cm == ColourMaterial::Specular;
    }
    const std::vector<VariantId> us = fs_.units();
    for (size_t i = 0; i < us.size(); ++i)
      if (static_cast<uint32_t>(us[i]) == r.mat_unit) m.unit = static_cast<int>(i);
    for (int j = 0; j < fs_.num_lights(); ++j) {
      const uint32_t mode = r.light[static_cast<size_t>(j)].mode;
      const uint32_t kind = mode >> 1;
      if ((mode & kModeEnable) && kind < static_cast<uint32_t>(kNumLightKinds) &&
          fs_.slot_can(j, static_cast<LightKind>(kind))) {
        m.on |= 1u << j;
        ++m.enabled;
      }
    }
    return m;
  }
  // Passes per fragment: ⌈enabled / lanes⌉, at least one (the scene term alone).
  [[nodiscard]] int passes(const LightRegs& r) const {
    const int k = modes(r).enabled;
    return k == 0 ? 1 : (k + fs_.lanes - 1) / fs_.lanes;
  }

  // The RTL's latency (accepting edge → out_valid_o, out_ready_i high throughout) and the fewest
  // advancing edges under backpressure, for a register state (docs/lighting.md §5); without one,
  // the largest and the smallest over every register state.
  [[nodiscard]] int latency(const LightRegs& r) const;
  [[nodiscard]] int latency_min(const LightRegs& r) const;
  [[nodiscard]] int latency() const;
  [[nodiscard]] int latency_min() const;
  // The most advancing edges under backpressure: latency plus gap_slack. At share > 1 the cs16 (reference
  // form) and schlick_nr units share their multipliers over share stages and take a pass only share stages
  // behind the one ahead (rtl/sc_pipe_ctrl.v GAP); a pass that a stall has bunched closer waits at the
  // unit's input, at most share − 1 edges (docs/lighting.md §2.1; the co-simulation saw at most 1).
  [[nodiscard]] int gap_slack(int unit_index) const;
  [[nodiscard]] int latency_max(const LightRegs& r) const;
  [[nodiscard]] int latency_max() const;
  // Clocks between two passes (share, schlick_iter: F+4 rounded up to a multiple of share) and the latency of one pass.
  [[nodiscard]] int pass_interval() const;
  [[nodiscard]] int pass_latency(int unit_index) const;

  // The per-fragment datapath, for the register values the core holds.
  [[nodiscard]] Colour eval(const LightRegs& r, const Fragment& fr, LightCoreTrace* tr = nullptr) const {
    const int F = f_.frac;
    const int VF = uf_.frac, E = VF - F;  // the specular path carries E = spec_guard more fraction bits
    const int64_t one = int64_t{1} << F;
    const LightModes md = modes(r);
    LightCoreTrace t;
    t.passes = md.enabled == 0 ? 1 : (md.enabled + fs_.lanes - 1) / fs_.lanes;
    const Side sd = side(r, fr, md);
    const int64_t* nin = sd.n;
    const uint32_t *m_em = sd.em, *m_am = sd.am, *m_di = sd.di, *m_sp = sd.sp;
    // N̂ (GL_NORMALIZE) — rtl/sc_normalize.v
    if (md.normalize) normalize3(VF, nin, t.nn);
    else for (int i = 0; i < 3; ++i) t.nn[i] = nin[i] * (int64_t{1} << E);
    // V̂: local viewer normalise(−P), else (0, 0, 1)
    if (md.local_viewer) {
      const int64_t mp[3] = {-fr.p[0], -fr.p[1], -fr.p[2]};
      normalize3(VF, mp, t.v);
    } else {
      t.v[0] = t.v[1] = 0;
      t.v[2] = int64_t{1} << VF;
    }
    const UnitMaterial mat{static_cast<int>(r.mat_n), r.mat_thr, r.mat_coef};
    const int ch = fs_.channels;
    for (int c = 0; c < ch; ++c)
      t.scene[c] = fs_.ambient ? m_em[c] + ((uint64_t{m_am[c]} * r.global_ambient[c]) >> F) : 0;
    for (int j = 0; j < fs_.num_lights(); ++j) {
      if (!(md.on & (1u << j))) continue;
      const LightRegs::Light& L = r.light[static_cast<size_t>(j)];
      LightTrace& lt = t.light[static_cast<size_t>(j)];
      const LightKind kind = static_cast<LightKind>(L.mode >> 1);
      lt.on = true;
      lt.kind = kind;
      lt.att = static_cast<uint64_t>(one);
      if (kind == LightKind::Directional) {
        // the register holds a unit direction: its code saturated to the signed F+2 bits of [−2, 2)
        const int64_t lim = int64_t{1} << (F + 1);
        for (int i = 0; i < 3; ++i) lt.l[i] = std::clamp<int64_t>(L.pos[i], -lim, lim - 1) * (int64_t{1} << E);
      } else {
        const int64_t dv[3] = {L.pos[0] - fr.p[0], L.pos[1] - fr.p[1], L.pos[2] - fr.p[2]};  // F+9 bits
        normalize3(VF, dv, lt.l);
        if (has_att(kind)) {
          const int64_t dl = dot3(dv, lt.l) >> VF;                // |D| = D·L̂
          lt.d = dl < 0 ? 0 : static_cast<uint64_t>(dl);
          const uint64_t dd = (lt.d * lt.d) >> F;
          lt.q = uint64_t{L.kc} + ((uint64_t{L.kl} * lt.d) >> F) + ((uint64_t{L.kq} * dd) >> F);
          lt.att = recip_att(F, lt.q);
        }
        if (kind == LightKind::Spot) {
          // GL's spot factor: (max(−L̂·ŝ, 0))^e inside the cone (−L̂·ŝ >= cos(cutoff)), 0 outside
          const int64_t sd[3] = {L.sdir[0] * (int64_t{1} << E), L.sdir[1] * (int64_t{1} << E), L.sdir[2] * (int64_t{1} << E)};
          lt.sdl = (-dot3(lt.l, sd)) >> VF;
          lt.in_cone = lt.sdl >= L.scos;
          const uint64_t xs = static_cast<uint64_t>(std::clamp<int64_t>(lt.sdl, 0, int64_t{1} << VF));
          lt.spot = lt.in_cone ? powi_chain(VF, xs, L.sexp, kSpotExpBits) : 0;
          lt.att = (lt.att * lt.spot) >> VF;
        }
      }
      // N̂·L at VF fraction bits, and R below, saturated to [−8, 8) (signed VF+4 bits): never with a unit L
      // (and, for R, a unit N̂); the bound keeps the lane's R and R·V̂ products narrow (docs/lighting.md §3.3)
      const int64_t lim8 = int64_t{1} << (VF + 3);
      lt.ndl = std::clamp<int64_t>(dot3(t.nn, lt.l) >> VF, -lim8, lim8 - 1);
      lt.diff = static_cast<uint32_t>(std::clamp<int64_t>(lt.ndl >> E, 0, one));
      lt.f = lt.ndl > 0 && md.unit >= 0;
      if (fs_.specular) {
        int64_t x;
        if (!md.phong) {
          const int64_t h[3] = {lt.l[0] + t.v[0], lt.l[1] + t.v[1], lt.l[2] + t.v[2]};
          int64_t hn[3];
          normalize3(VF, h, hn);
          x = dot3(t.nn, hn) >> VF;
        } else {
          int64_t rv[3];
          for (int i = 0; i < 3; ++i)  // 2(N̂·L)N̂ − L
            rv[i] = std::clamp<int64_t>(((lt.ndl * t.nn[i]) >> (VF - 1)) - lt.l[i], -lim8, lim8 - 1);
          x = dot3(rv, t.v) >> VF;
        }
        lt.x = std::clamp<int64_t>(x, uf_.in_min(), uf_.in_max());  // the unit's signed VF+2-bit word, saturated
        // shininess below the units' range (low_shininess): x^n exactly by the chain on clamp(x, 0, 1), not
        // normalised (the unit still carries the pass; its value is not used)
        if (md.low_n)
          lt.spec = static_cast<uint32_t>(powi_chain(VF, static_cast<uint64_t>(std::clamp<int64_t>(lt.x, 0, int64_t{1} << VF)),
                                                     r.mat_n, kLowNBits));
        else
          lt.spec = units_[static_cast<size_t>(md.unit < 0 ? 0 : md.unit)].eval(mat, lt.x);
      }
      for (int c = 0; c < ch; ++c) {
        uint64_t sum = 0, ssum = 0;
        if (fs_.ambient) sum += (uint64_t{m_am[c]} * L.ambient[c]) >> F;
        if (fs_.diffuse) sum += (((uint64_t{lt.diff} * m_di[c]) >> F) * L.diffuse[c]) >> F;
        if (fs_.specular && lt.f) ssum = (((uint64_t{lt.spec} * m_sp[c]) >> VF) * L.specular[c]) >> F;
        if (md.separate) {  // the separate mode: the two parts attenuated apart (rtl/sc_light_shade.v SEP)
          lt.term[c] = (lt.att * sum) >> F;
          lt.sterm[c] = (lt.att * ssum) >> F;
        } else {
          lt.term[c] = (lt.att * (sum + ssum)) >> F;  // att = 2^F unless point_att: exactly sum
        }
      }
    }
    // The sum over the lights is exact (no rounding) and saturated once (docs/spec.md §10.4). In the
    // separate-specular mode the primary and the specular sums are saturated apart (docs/lighting.md §3.6);
    // otherwise the specular sum is 0 and the primary is the whole sum, bit for bit as without the capability.
    Colour out;
    for (int c = 0; c < ch; ++c) {
      uint64_t tot = t.scene[c], stot = 0;
      for (int j = 0; j < fs_.num_lights(); ++j) {
        tot += t.light[static_cast<size_t>(j)].term[c];
        stot += t.light[static_cast<size_t>(j)].sterm[c];
      }
      t.total[c] = tot;
      t.stotal[c] = stot;
      const uint64_t o = static_cast<uint64_t>(one);
      const uint64_t p = std::min<uint64_t>(tot, o), q = std::min<uint64_t>(stot, o);
      out.c[c] = static_cast<uint32_t>(p);
      out.s[c] = static_cast<uint32_t>(q);
    }
    if (tr) *tr = t;
    return out;
  }

  // Double-precision reference of the same equation for the same register values and fragment
  // (every code read as code/2^F): exact normalisation, exact 1/q, and spec = cos^n (exact) or the
  // variant's own double formula, times coef (the register value) with norm. Channel values in [0, 1].
  enum class SpecRef { Exact, Variant };
  // `cone`, when given, gets bit j set for a spot light j inside its cone in double (−L̂·ŝ >= the cos register's
  // value): where it differs from the trace's in_cone the fragment is on the cone's edge, a step the fixed-point
  // sdl (truncated, from the normalised L̂) and the double can put on different sides (docs/lighting.md §3.4).
  // `secondary`, when given and the separate-specular mode is on (§3.6): the return value is the primary colour
  // and *secondary the specular sum, each clamped to [0, 1]; otherwise the return value is GL's colour sum
  // min(1, primary + specular) and *secondary is 0.
  [[nodiscard]] std::array<double, 3> eval_double(const LightRegs& r, const Fragment& fr, SpecRef ref,
                                                  uint32_t* cone = nullptr,
                                                  std::array<double, 3>* secondary = nullptr) const;

  static int64_t dot3(const int64_t a[3], const int64_t b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

 private:
  // The side a fragment is lit as (docs/lighting.md §3.7): in the two-sided mode a back fragment has −N (each
  // component saturated to the signed F+2 bits: −(−2) is 2 − 2^−F, rtl/sc_light.v's g_nneg) and the back colour
  // bank; otherwise N as given and the front colours. Colour material (§3.8) then replaces the chosen colour(s)
  // of either bank by the fragment's colour. One place for eval() and eval_double().
  struct Side {
    int64_t n[3];
    const uint32_t *em, *am, *di, *sp;
  };
  [[nodiscard]] Side side(const LightRegs& r, const Fragment& fr, const LightModes& md) const {
    const bool bk = md.two_side && fr.back;
    const int64_t nmax = (int64_t{1} << (f_.frac + 1)) - 1;
    Side sd{};
    for (int i = 0; i < 3; ++i) sd.n[i] = bk ? std::min<int64_t>(-fr.n[i], nmax) : fr.n[i];
    sd.em = bk ? r.back_emission : r.emission;
    sd.am = bk ? r.back_ambient : r.ambient;
    sd.di = bk ? r.back_diffuse : r.diffuse;
    sd.sp = bk ? r.back_specular : r.specular;
    if (md.cm_emission) sd.em = fr.col;
    if (md.cm_ambient) sd.am = fr.col;
    if (md.cm_diffuse) sd.di = fr.col;
    if (md.cm_specular) sd.sp = fr.col;
    return sd;
  }

  FeatureSet fs_;
  Format f_, uf_;
  std::vector<Unit> units_;
};

// ---- latency of rtl/sc_light.v (the same formula as the localparams in its header) -----------
namespace detail {
struct LightPipe {
  int front;  // T_F: stages of the front pipeline (x and the sideband registered for the units)
  int back;   // NB: stages of the back pipeline (colour products, attenuation, sum and accumulator)
};
inline LightPipe light_pipe(const FeatureSet& fs) {
  // rtl/sc_normalize.v and rtl/sc_recip.v (config/configs.json light.latency: the RTL's NL and RL come from there too)
  const int NL = kNormalizeLatency + kMregNormalize * fs.mreg;
  constexpr int RL = kRecipLatency;
  const int D = kMregDot * fs.mreg;    // the lanes' dot products (and R's products): registers inside each
  const int DB = kMregBack * fs.mreg;  // each product stage of the back
  const bool any_att = fs.any_att();  // point_att or spot
  const bool any_spot = fs.any_kind(LightKind::Spot);
  const bool any_point = fs.any_kind(LightKind::Point);
  const bool need_n = fs.diffuse || fs.specular;                    // N̂·L is computed
  const bool lv = fs.specular && fs.local_viewer;                    // V̂ = normalise(−P) exists
  const bool any_pl = any_att || (need_n && any_point);              // some L̂ = normalise(P_j − P)
  // The normalisations of a pass (N̂, V̂, L̂, Ĥ: those that exist) are ops k = 0, 1, ...; with share S
  // op k enters shared normaliser ⌊k/S⌋ at a front stage ≡ k (mod S) (rtl/sc_light.v "shared normalisers").
  const int S = fs.share;
  const int op_n = (need_n && fs.normalize) ? 1 : 0, op_v = lv ? 1 : 0, op_l = any_pl ? 1 : 0;
  const int k_v = op_n, k_l = op_n + op_v, k_h = op_n + op_v + op_l;
  // N̂ (or N), with MREG registered after the normalize-mode choice before the lanes' dot products
  const int t_nn = (op_n ? NL : 0) + (need_n ? kMregN * fs.mreg : 0);
  // V̂ and L̂ of point lights: with MREG, −P and P_j − P registered (kMregP) before their normalisers; op k enters
  // at k mod S, or S edges later when that is below the register (every op keeps its phase; S = 1: kMregP)
  const int mrp = kMregP * fs.mreg;
  const auto entry = [S, mrp](int k) { return k % S + (k % S < mrp ? S : 0); };
  const int t_v = lv ? entry(k_v) + NL : 0;
  const int t_l = any_pl ? entry(k_l) + NL : 0;
  const int t_a = std::max(t_nn, t_l);                                // N̂·L operands
  const int t_h0 = std::max({t_l, t_v, t_nn - NL});                  // Ĥ not before N̂ (MREG registers N̂ once more)
  const int t_h = t_h0 + ((k_h % S - t_h0 % S) + S) % S;              // H = L + V
  const int t_rv = std::max(t_a + 2 + 2 * D, t_v);                    // R·V operands
  int t_x = 0;                                                        // the unit input x
  if (fs.blinn) t_x = std::max(t_x, t_h + NL + 1 + D);
  if (fs.phong) t_x = std::max(t_x, lv ? t_rv + 1 + D : t_a + 2 + 2 * D);
  // att (distance, q, 1/q; t_l = NL at share 1); at share > 1 without MREG q takes a stage more (its three
  // products at three stages, one shared multiplier)
  // MREG: q's two products and sc_recip's four each over two edges (kMregAtt, kMregRecip), at every share
  const int t_att = t_l + 3 + D + RL + (S > 1 && fs.mreg == 0 ? 1 : 0) + (kMregAtt + kMregRecip) * fs.mreg;
  // the power chains (rtl/sc_powi.v): one stage per exponent bit, kMregPowi more each with MREG
  const int powi_stage = 1 + kMregPowi * fs.mreg;
  int t_f = 1;
  if (need_n) t_f = std::max(t_f, t_a + 1 + D);
  if (fs.specular) t_f = std::max(t_f, t_x);
  // low_shininess: the chain takes x at t_x, kLowNBits stages (rtl/sc_light_lane.v)
  if (fs.specular && fs.low_shininess) t_f = std::max(t_f, t_x + kLowNBits * powi_stage);
  if (any_att) t_f = std::max(t_f, t_att);
  // spot: ŝ·L̂ at t_l+1, sdl registered at t_l+2, then kSpotExpBits chain stages (rtl/sc_powi.v); att · spot
  // registered one stage after both are there
  if (any_spot) t_f = std::max(t_f, std::max(t_att, t_l + 2 + D + kSpotExpBits * powi_stage) + 1);
  // The back: colour products, attenuation, sum, accumulator. With share >= 4 on an RGB core with units it
  // is channel-serial (rtl/sc_light.v CSER): a pass enters it as three items, one per channel, on
  // consecutive edges, so its colour is out two edges later.
  const bool cser = S >= 4 && fs.channels == 3 && fs.specular;
  // MREG: each product stage of the back (B1, B2 and with attenuation B3) takes D more (rtl/sc_light_shade.v)
  return {t_f, (any_att ? 4 + 3 * DB : 3 + 2 * DB) + (cser ? 2 : 0)};
}
}  // namespace detail

// Passes issue every share-th front-advancing edge (a phase counter), schlick_iter at least F+4 apart.
inline int LightCore::pass_interval() const {
  const int s = fs_.share;
  const int iter = fs_.specular && fs_.variant == VariantId::schlick_iter ? uf_.frac + 4 : 1;
  return (iter + s - 1) / s * s;
}
inline int LightCore::pass_latency(int unit_index) const {
  const detail::LightPipe p = detail::light_pipe(fs_);
  return p.front + (fs_.specular ? units_[static_cast<size_t>(unit_index < 0 ? 0 : unit_index)].latency() : 0) +
         p.back;
}

// One pass's pipeline (front, the material's unit with sc_energy when norm, back), then one more
// issue interval per further pass: the last pass enters the pipeline (passes − 1)·interval edges
// after the fragment was accepted.
inline int LightCore::latency(const LightRegs& r) const {
  const LightModes m = modes(r);
  return pass_latency(m.unit) + (passes(r) - 1) * pass_interval();
}

// With a specular unit the front, the unit and the back are separate elastic segments: while the
// output is held, the passes can move through the front and the unit into the unit's output stage,
// so at least the edges into the back's stages and the taking edge remain (back + 1). Without one,
// front and back are one global-enable pipeline: exactly latency().
inline int LightCore::latency_min(const LightRegs& r) const {
  return fs_.specular ? detail::light_pipe(fs_).back + 1 : latency(r);
}

inline int LightCore::latency() const {
  int worst = 0;
  for (size_t u = 0; u < units_.size(); ++u) worst = std::max(worst, pass_latency(static_cast<int>(u)));
  const int max_passes = (fs_.num_lights() + fs_.lanes - 1) / fs_.lanes;
  return worst + (max_passes - 1) * pass_interval();
}
inline int LightCore::gap_slack(int unit_index) const {
  if (!fs_.specular || fs_.share <= 1) return 0;
  const VariantId v = units_[static_cast<size_t>(unit_index < 0 ? 0 : unit_index)].variant();
  return v == VariantId::cs16 || v == VariantId::schlick_nr ? fs_.share - 1 : 0;
}
inline int LightCore::latency_max(const LightRegs& r) const { return latency(r) + gap_slack(modes(r).unit); }
inline int LightCore::latency_max() const {
  int slack = 0;
  for (size_t u = 0; u < units_.size(); ++u) slack = std::max(slack, gap_slack(static_cast<int>(u)));
  return latency() + slack;
}
inline int LightCore::latency_min() const {
  if (fs_.specular) return detail::light_pipe(fs_).back + 1;
  return pass_latency(0);
}

inline std::array<double, 3> LightCore::eval_double(const LightRegs& r, const Fragment& fr, SpecRef ref,
                                                    uint32_t* cone, std::array<double, 3>* secondary) const {
  if (cone) *cone = 0;
  if (secondary) *secondary = {0, 0, 0};
  const int F = f_.frac;
  const LightModes md = modes(r);
  auto v = [F](int64_t code) { return std::ldexp(static_cast<double>(code), -F); };
  auto norm3 = [](double a[3]) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int i = 0; i < 3; ++i) a[i] = l > 0 ? a[i] / l : 0.0;
  };
  const Side sd = side(r, fr, md);  // −N as the core saturates it, and the back colours
  double nn[3], p[3] = {v(fr.p[0]), v(fr.p[1]), v(fr.p[2])};
  for (int i = 0; i < 3; ++i) nn[i] = v(sd.n[i]);
  const uint32_t *m_em = sd.em, *m_am = sd.am, *m_di = sd.di, *m_sp = sd.sp;
  if (md.normalize) norm3(nn);
  double vv[3] = {0, 0, 1};
  if (md.local_viewer) {
    vv[0] = -p[0], vv[1] = -p[1], vv[2] = -p[2];
    norm3(vv);
  }
  const int n = static_cast<int>(r.mat_n);
  const VariantId var = md.unit >= 0 ? units_[static_cast<size_t>(md.unit)].variant() : fs_.variant;
  std::array<double, 3> out{0, 0, 0}, sout{0, 0, 0};
  for (int c = 0; c < fs_.channels; ++c)
    if (fs_.ambient) out[c] = v(m_em[c]) + v(m_am[c]) * v(r.global_ambient[c]);
  for (int j = 0; j < fs_.num_lights(); ++j) {
    if (!(md.on & (1u << j))) continue;
    const LightRegs::Light& L = r.light[static_cast<size_t>(j)];
    const LightKind kind = static_cast<LightKind>(L.mode >> 1);
    double l[3], att = 1.0;
    if (kind == LightKind::Directional) {  // the register's code saturated to [−2, 2), as the core reads it
      const int64_t lim = int64_t{1} << (F + 1);
      for (int i = 0; i < 3; ++i) l[i] = v(std::clamp<int64_t>(L.pos[i], -lim, lim - 1));
    } else {
      for (int i = 0; i < 3; ++i) l[i] = v(L.pos[i]) - p[i];
      const double d = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
      norm3(l);
      if (has_att(kind)) {
        const double q = v(L.kc) + v(L.kl) * d + v(L.kq) * d * d;
        att = q > 0 ? std::min(1.0 / q, std::ldexp(static_cast<double>(att_max(F)), -F)) : std::ldexp(static_cast<double>(att_max(F)), -F);
      }
      if (kind == LightKind::Spot) {  // the same registers read exactly: ŝ = code/2^F, cos = code/2^VF
        const double sd = -(l[0] * v(L.sdir[0]) + l[1] * v(L.sdir[1]) + l[2] * v(L.sdir[2]));
        const bool in = sd >= std::ldexp(static_cast<double>(L.scos), -uf_.frac);
        if (cone && in) *cone |= 1u << j;
        att *= in ? (L.sexp == 0 ? 1.0 : std::pow(std::clamp(sd, 0.0, 1.0), static_cast<double>(L.sexp))) : 0.0;
      }
    }
    const double ndl = std::clamp(nn[0] * l[0] + nn[1] * l[1] + nn[2] * l[2], -8.0, 8.0);  // as the core saturates
    double spec = 0.0;
    if (fs_.specular && md.unit >= 0 && ndl > 0) {
      double x;
      if (!md.phong) {
        double h[3] = {l[0] + vv[0], l[1] + vv[1], l[2] + vv[2]};
        norm3(h);
        x = nn[0] * h[0] + nn[1] * h[1] + nn[2] * h[2];
      } else {
        double rv[3];
        for (int i = 0; i < 3; ++i) rv[i] = std::clamp(2 * ndl * nn[i] - l[i], -8.0, 8.0);
        x = rv[0] * vv[0] + rv[1] * vv[1] + rv[2] * vv[2];
      }
      x = std::clamp(x, 0.0, 1.0);
      if (md.low_n) spec = n == 0 ? 1.0 : std::pow(x, n);  // GL: x^0 = 1, 0 included; not normalised
      else if (ref == SpecRef::Exact) spec = golden::cos_pow(x, n);
      else if (var == VariantId::cs16 || squarer_form(var))  // cs16 and its forms
        spec = fs_.cutoff == Cutoff::ThetaCr ? golden::cs16_theta_cr(x, n) : golden::cs16_sign_clamp(x, n);
      else spec = golden::schlick(x, n);
      if (fs_.norm && !md.low_n) spec *= std::ldexp(static_cast<double>(r.mat_coef), -uf_.frac);  // the units' format
    }
    const double diff = std::clamp(ndl, 0.0, 1.0);
    for (int c = 0; c < fs_.channels; ++c) {
      double s = 0;
      if (fs_.ambient) s += v(m_am[c]) * v(L.ambient[c]);
      if (fs_.diffuse) s += diff * v(m_di[c]) * v(L.diffuse[c]);
      out[c] += att * s;
      if (fs_.specular) sout[c] += att * spec * v(m_sp[c]) * v(L.specular[c]);
    }
  }
  if (secondary && md.separate) {
    for (int c = 0; c < 3; ++c) out[c] = std::clamp(out[c], 0.0, 1.0), (*secondary)[c] = std::clamp(sout[c], 0.0, 1.0);
    return out;
  }
  for (int c = 0; c < 3; ++c) out[c] = std::clamp(out[c] + sout[c], 0.0, 1.0);
  return out;
}

// ---- host-side setup: physical parameters → register writes ---------------------------------
// (OpenGL state → codes; done once per light/material change by the driver, in double, like thr(n).)

struct LightParams {
  std::optional<LightKind> kind;       // default: from w and the slot's kinds (light_writes)
  bool enabled = true;                 // GL_LIGHTi enable
  double position[4] = {0, 0, 1, 0};  // GL_POSITION in eye space; w = 0 directional
  double ambient[3] = {0, 0, 0}, diffuse[3] = {1, 1, 1}, specular[3] = {1, 1, 1};
  double kc = 1, kl = 0, kq = 0;       // GL_CONSTANT/LINEAR/QUADRATIC_ATTENUATION
  double spot_direction[3] = {0, 0, -1};  // GL_SPOT_DIRECTION in eye space (any length, not 0)
  double spot_cutoff = 180;            // GL_SPOT_CUTOFF, degrees: 0..90, or 180 (no cone: not a spot light)
  int spot_exponent = 0;               // GL_SPOT_EXPONENT, 0..128
};
struct MaterialParams {
  double emission[3] = {0, 0, 0}, ambient[3] = {0.2, 0.2, 0.2}, diffuse[3] = {0.8, 0.8, 0.8},
         specular[3] = {0, 0, 0};
  int shininess = 64;       // n, 16..1024 (0..1024 with the feature low_shininess)
  int norm_model = 0;       // index into kModels (feature norm only); −1: no normalisation (coef = 1)
  CoefKind norm_kind = CoefKind::Fitted;
  std::optional<VariantId> unit;  // the specular unit (mat_unit); default: the core's first unit
};
// Global modes (light_model): default — every capability the core has that has no alternative.
struct ModeParams {
  bool local_viewer = false, phong = false, normalize = false;
  bool separate_specular = false;  // GL_LIGHT_MODEL_COLOR_CONTROL = GL_SEPARATE_SPECULAR_COLOR
  bool two_side = false;           // GL_LIGHT_MODEL_TWO_SIDE
};
inline ModeParams default_modes(const FeatureSet& fs) {
  return {fs.local_viewer, !fs.blinn, fs.normalize, false, false};
}

namespace detail {
inline uint32_t colour_code(int F, double x, const char* what) {
  if (!(x >= 0.0) || x >= 2.0)
    throw std::invalid_argument(std::string(what) + " = " + std::to_string(x) + " out of range [0, 2)");
  return static_cast<uint32_t>(std::min(std::llround(std::ldexp(x, F)), (1ll << (F + 1)) - 1));
}
inline uint32_t attc_code(int F, double x, const char* what) {
  if (!(x >= 0.0) || x >= 256.0)
    throw std::invalid_argument(std::string(what) + " = " + std::to_string(x) + " out of range [0, 256)");
  return static_cast<uint32_t>(std::min(std::llround(std::ldexp(x, F)), (1ll << (F + kAttIntBits)) - 1));
}
inline int64_t pos_code(int F, double x, const char* what) {
  if (!(x >= -128.0) || !(x < 128.0))
    throw std::invalid_argument(std::string(what) + " = " + std::to_string(x) + " out of range [-128, 128)");
  return std::clamp<int64_t>(std::llround(std::ldexp(x, F)), -(int64_t{1} << (F + kPosIntBits)),
                             (int64_t{1} << (F + kPosIntBits)) - 1);
}
// The three register words of a unit direction: d normalised in double, each component rounded to F fraction
// bits, masked to the register's width (a directional light's position, a spot direction).
inline void push_unit_direction(std::vector<RegWrite>& w, uint32_t addr, int F, const double d[3], uint32_t mask,
                                const std::string& zero_error) {
  const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(l > 0)) throw std::invalid_argument(zero_error);
  for (uint32_t c = 0; c < 3; ++c)
    w.push_back({addr + c, static_cast<uint32_t>(std::llround(std::ldexp(d[c] / l, F))) & mask});
}
}  // namespace detail

// The unit material: the specular unit's registers mat_unit, mat_n, mat_thr and mat_coef for m's unit, shininess
// and normalisation. The core holds one; a host that needs another (a back face's own shininess, docs/scenes.md)
// writes these words again between batches of fragments.
inline std::vector<RegWrite> unit_material_writes(const LightCore& core, const MaterialParams& m) {
  const FeatureSet& fs = core.features();
  std::vector<RegWrite> w;
  // n < 16 goes to the chain (low_shininess); a core without units has no n register (the words are ignored)
  const bool any_n = fs.low_shininess || !fs.specular;
  const bool low = any_n && m.shininess >= 0 && m.shininess < kNMin;
  if (!low && (m.shininess < kNMin || m.shininess > kNMax))
    throw std::invalid_argument("shininess " + std::to_string(m.shininess) + " out of range " +
                                (any_n ? std::string("0") : std::to_string(kNMin)) + ".." + std::to_string(kNMax) +
                                (any_n || m.shininess > kNMax ? "" : " (this core has no low_shininess chain)"));
  const VariantId var = m.unit.value_or(fs.variant);
  if (fs.specular && !fs.has_unit(var))
    throw std::invalid_argument(std::string("specular unit ") + std::string(variant_name(var)) + " is not in this core (" +
                                fs.summary() + ")");
  Unit u(var, core.unit_format(), core.unit().cutoff());
  const bool norm = fs.norm && m.norm_model >= 0;
  if (norm) u.set_energy(true, m.norm_model, m.norm_kind);
  w.push_back({kReg_mat_unit, static_cast<uint32_t>(var)});
  if (low) {
    // n < 2^kLowNBits: the chain computes x^n; the unit's thr and coef are not used (written 0 and 1.0)
    w.push_back({kReg_mat_n, static_cast<uint32_t>(m.shininess)});
    w.push_back({kReg_mat_thr, 0u});
    w.push_back({kReg_mat_coef, uint32_t{1} << core.unit_format().frac});
  } else {
    const UnitMaterial um = u.setup(m.shininess);
    w.push_back({kReg_mat_n, static_cast<uint32_t>(um.n)});
    w.push_back({kReg_mat_thr, um.thr});
    // with the norm hardware and no normalisation: coef = 1.0 (sc_energy then passes the unit's value)
    w.push_back({kReg_mat_coef, norm ? um.coef : (fs.norm ? (uint32_t{1} << core.unit_format().frac) : um.coef)});
  }
  return w;
}

// Material registers: the unit material (n, thr, coef) and the four colours.
inline std::vector<RegWrite> material_writes(const LightCore& core, const MaterialParams& m) {
  const int F = core.format().frac;
  std::vector<RegWrite> w = unit_material_writes(core, m);
  for (uint32_t c = 0; c < 3; ++c) {
    w.push_back({kReg_mat_emission + c, detail::colour_code(F, m.emission[c], "material emission")});
    w.push_back({kReg_mat_ambient + c, detail::colour_code(F, m.ambient[c], "material ambient")});
    w.push_back({kReg_mat_diffuse + c, detail::colour_code(F, m.diffuse[c], "material diffuse")});
    w.push_back({kReg_mat_specular + c, detail::colour_code(F, m.specular[c], "material specular")});
  }
  return w;
}

// The back colour bank (two_side, docs/lighting.md §3.7): a back-facing fragment's emission, ambient, diffuse and
// specular in the two-sided mode. Only the colours: the back face uses the unit material the core holds (one), so
// a back face with its own shininess is lit by a batch of its own after unit_material_writes(core, back).
inline std::vector<RegWrite> back_material_writes(const LightCore& core, const MaterialParams& back) {
  const int F = core.format().frac;
  std::vector<RegWrite> w;
  for (uint32_t c = 0; c < 3; ++c) {
    w.push_back({kReg_back_mat_emission + c, detail::colour_code(F, back.emission[c], "back material emission")});
    w.push_back({kReg_back_mat_ambient + c, detail::colour_code(F, back.ambient[c], "back material ambient")});
    w.push_back({kReg_back_mat_diffuse + c, detail::colour_code(F, back.diffuse[c], "back material diffuse")});
    w.push_back({kReg_back_mat_specular + c, detail::colour_code(F, back.specular[c], "back material specular")});
  }
  return w;
}

// The spot cos register for a cutoff in degrees: ⌈cos(cutoff)·2^VF⌉ (so a code sdl is inside iff sdl >=
// cos(cutoff)·2^VF, GL's >=), as a VF+2-bit two's-complement word; cutoff 180: the smallest word (−2), every
// fragment inside. cos(cutoff) is computed as sin((90 − cutoff)·π/180) in double, exact at both ends of the
// range: cutoff 90 gives 0 (inside iff −L̂·ŝ >= 0, as GL's cos 90° = 0; cos(π/2) in double is 6e-17, which
// would put a perpendicular ŝ outside) and cutoff 0 gives 1.
inline uint32_t spot_cos_code(int vf, double cutoff_deg) {
  const uint32_t m = static_cast<uint32_t>(mask_bits(vf + 2));
  if (cutoff_deg == 180.0) return (uint32_t{1} << (vf + 1)) & m;
  const double c = std::sin((90.0 - cutoff_deg) * (std::acos(-1.0) / 180.0));
  const int64_t code = static_cast<int64_t>(std::ceil(std::ldexp(c, vf)));
  return static_cast<uint32_t>(code) & m;
}

// Light j's registers. A directional light (w = 0) gets its unit direction; a point light its position
// (w must be 1 after the host's divide by w). Rejects kc = kl = kq = 0 for an attenuated light.
inline std::vector<RegWrite> light_writes(const LightCore& core, int j, const LightParams& lp) {
  const FeatureSet& fs = core.features();
  const int F = core.format().frac;
  if (j < 0 || j >= fs.num_lights())
    throw std::invalid_argument("light " + std::to_string(j) + " not in the feature set (" +
                                std::to_string(fs.num_lights()) + " lights)");
  const std::string lj = "light " + std::to_string(j);
  if (!(lp.spot_cutoff == 180.0 || (lp.spot_cutoff >= 0.0 && lp.spot_cutoff <= 90.0)))
    throw std::invalid_argument(lj + ": spot cutoff " + std::to_string(lp.spot_cutoff) + " out of range (0..90 or 180 degrees)");
  if (lp.spot_exponent < 0 || lp.spot_exponent > kSpotExpMax)
    throw std::invalid_argument(lj + ": spot exponent " + std::to_string(lp.spot_exponent) + " out of range 0.." +
                                std::to_string(kSpotExpMax));
  // Without an explicit kind: a slot's only kind; else directional for w = 0; for w != 0 spot when the
  // cutoff is not 180 (GL's spot light), else point with attenuation where the slot can take it (GL's
  // positional light), else point.
  LightKind kind = fs.slot_kind(j);
  if (lp.kind) kind = *lp.kind;
  else if (lp.position[3] == 0.0 && fs.slot_can(j, LightKind::Directional)) kind = LightKind::Directional;
  else if (lp.position[3] != 0.0 && lp.spot_cutoff != 180.0) kind = LightKind::Spot;
  else if (lp.position[3] != 0.0 && fs.slot_can(j, LightKind::PointAtt)) kind = LightKind::PointAtt;
  else if (lp.position[3] != 0.0 && fs.slot_can(j, LightKind::Point)) kind = LightKind::Point;
  if (!fs.slot_can(j, kind))
    throw std::invalid_argument("light " + std::to_string(j) + " cannot be " + to_string(kind) +
                                " in this core (slot kinds: " + kinds_name(fs.slots[static_cast<size_t>(j)]) + ")");
  const uint32_t base = static_cast<uint32_t>(j) * kLightStride;
  std::vector<RegWrite> w;
  w.push_back({base + kReg_light_mode, light_mode_word(lp.enabled, kind)});
  const uint32_t pmask = static_cast<uint32_t>(mask_bits(light_pos_bits(F)));
  if (kind == LightKind::Directional) {
    if (lp.position[3] != 0.0) throw std::invalid_argument("light " + std::to_string(j) + " is directional (w = 0 expected)");
    detail::push_unit_direction(w, base + kReg_light_position, F, lp.position, pmask, lj + ": zero direction");
  } else {
    if (lp.position[3] == 0.0) throw std::invalid_argument("light " + std::to_string(j) + " is a point light (w != 0 expected)");
    for (uint32_t c = 0; c < 3; ++c)
      w.push_back({base + kReg_light_position + c,
                   static_cast<uint32_t>(detail::pos_code(F, lp.position[c] / lp.position[3], "light position")) & pmask});
  }
  for (uint32_t c = 0; c < 3; ++c) {
    w.push_back({base + kReg_light_ambient + c, detail::colour_code(F, lp.ambient[c], "light ambient")});
    w.push_back({base + kReg_light_diffuse + c, detail::colour_code(F, lp.diffuse[c], "light diffuse")});
    w.push_back({base + kReg_light_specular + c, detail::colour_code(F, lp.specular[c], "light specular")});
  }
  if (lp.spot_cutoff != 180.0 && kind != LightKind::Spot)
    throw std::invalid_argument(lj + " has a spot cutoff (" + std::to_string(lp.spot_cutoff) + ") but is " + to_string(kind));
  if (has_att(kind)) {
    const uint32_t kc = detail::attc_code(F, lp.kc, "constant attenuation");
    const uint32_t kl = detail::attc_code(F, lp.kl, "linear attenuation");
    const uint32_t kq = detail::attc_code(F, lp.kq, "quadratic attenuation");
    if (kc == 0 && kl == 0 && kq == 0)
      throw std::invalid_argument("light " + std::to_string(j) + ": constant, linear and quadratic attenuation all 0");
    w.push_back({base + kReg_light_kc, kc});
    w.push_back({base + kReg_light_kl, kl});
    w.push_back({base + kReg_light_kq, kq});
  }
  if (kind == LightKind::Spot) {
    detail::push_unit_direction(w, base + kReg_light_spot_direction, F, lp.spot_direction,
                                static_cast<uint32_t>(mask_bits(F + 2)), lj + ": zero spot direction");
    w.push_back({base + kReg_light_spot_cos, spot_cos_code(core.unit_format().frac, lp.spot_cutoff)});
    // cutoff 180 on a spot slot: exponent 0 and the smallest cos, so the factor is 1 everywhere (GL)
    w.push_back({base + kReg_light_spot_exponent, lp.spot_cutoff == 180.0 ? 0u : static_cast<uint32_t>(lp.spot_exponent)});
  }
  return w;
}

// Light j off (its other registers keep their values).
inline std::vector<RegWrite> light_off_writes(int j) {
  return {{static_cast<uint32_t>(j) * kLightStride + kReg_light_mode, 0u}};
}

// GL's initial state of every register slot j's hardware has, with the light off: what a driver writes for each
// light at context creation, since the registers are not reset. Position (0, 0, 1) (GL's (0, 0, 1, 0): the same
// code as a unit direction and as a position), ambient 0, diffuse and specular 1 for light 0 and 0 for the
// others, kc = 1, kl = kq = 0 where the slot attenuates, spot direction (0, 0, −1), cutoff 180 and exponent 0
// where it can be spot. A later mode write alone (enable, kind) then meets defined registers.
inline std::vector<RegWrite> light_reset_writes(const LightCore& core, int j) {
  const FeatureSet& fs = core.features();
  LightParams lp;
  lp.enabled = false;
  if (j != 0)
    for (int c = 0; c < 3; ++c) lp.diffuse[c] = lp.specular[c] = 0;
  lp.position[3] = 1;
  if (fs.slot_can(j, LightKind::Spot)) lp.kind = LightKind::Spot;
  else if (fs.slot_can(j, LightKind::PointAtt)) lp.kind = LightKind::PointAtt;
  else if (fs.slot_can(j, LightKind::Point)) lp.kind = LightKind::Point;
  else lp.kind = LightKind::Directional, lp.position[3] = 0;
  std::vector<RegWrite> w = light_writes(core, j, lp);
  w.front().data = 0;  // the mode word: off, kind 0 (light_writes puts it first)
  return w;
}

inline uint32_t light_model_word(const ModeParams& m) {
  return (m.local_viewer ? kModelLocalViewer : 0u) | (m.phong ? kModelPhong : 0u) | (m.normalize ? kModelNormalize : 0u) |
         (m.separate_specular ? kModelSeparateSpecular : 0u) | (m.two_side ? kModelTwoSide : 0u);
}

// Global ambient and the global modes (light_model).
inline std::vector<RegWrite> global_writes(const LightCore& core, const double ambient[3],
                                           const ModeParams& modes) {
  std::vector<RegWrite> w;
  w.push_back({kReg_light_model, light_model_word(modes)});
  for (uint32_t c = 0; c < 3; ++c)
    w.push_back({kReg_global_ambient + c, detail::colour_code(core.format().frac, ambient[c], "global ambient")});
  return w;
}
inline std::vector<RegWrite> global_writes(const LightCore& core, const double ambient[3]) {
  return global_writes(core, ambient, default_modes(core.features()));
}

// The colour_material register's write (feature colour_material; `none`: off).
inline std::vector<RegWrite> colour_material_writes(std::optional<ColourMaterial> m) {
  return {{kReg_colour_material, m ? colour_material_word(true, *m) : 0u}};
}
// A fragment's colour (in_cr_i..) from doubles in [0, 2), rounded as a material colour register.
inline void set_fragment_colour(int F, Fragment& fr, const double c[3]) {
  for (int i = 0; i < 3; ++i) fr.col[i] = detail::colour_code(F, c[i], "fragment colour");
}

// Fragment codes from eye-space doubles (normal any length; position in [−128, 128)).
inline Fragment make_fragment(int F, const double n[3], const double p[3]) {
  Fragment fr;
  const int64_t nlim = int64_t{1} << (F + 1);
  for (int i = 0; i < 3; ++i) {
    fr.n[i] = std::clamp<int64_t>(std::llround(std::ldexp(n[i], F)), -nlim, nlim - 1);
    fr.p[i] = detail::pos_code(F, p[i], "fragment position");
  }
  return fr;
}

}  // namespace shadecore

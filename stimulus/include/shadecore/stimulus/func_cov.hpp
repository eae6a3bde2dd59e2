// SPDX-License-Identifier: Apache-2.0
// shadecore stimulus — the functional coverage model (docs/coverage.md "Functional model"): the situations the
// stimulus must reach, as named bins, and what samples them (the C model's trace of each fragment or input; the
// ports' handshake per edge). No Verilator in it: a GoogleTest runs the project's stimulus through it on the C model
// alone (tests/test_func_cov.cpp: every bin reachable); the harnesses (sim/tb_func_cov.hpp) count the same bins
// into the run's Verilator coverage database.
//
//   UnitFuncCov    the specular unit: input-code class × n class (cs16 with θcr: the threshold and its
//                  neighbours; every unit: 0, negative, the lobe, 1.0 exactly, above 1.0).
//   LightFuncCov   the lighting core: per light slot kind × enabled (spot: inside / outside / at the cone's
//                  edge), global modes (local viewer × reflection × two-sided × separate specular), colour-material
//                  modes 0..7, unit × shininess class, the attenuation classes crossed with the kind (and spot's
//                  cone), passes per fragment (lanes), hard cases (N = 0, tiny N, light at P, N·L = 0 and ±1 code,
//                  H = 0, each channel's saturation, back-facing with and without two-sided) — only the bins the
//                  feature set can take.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <deque>
#include <string>
#include <vector>

#include "shadecore/light.hpp"
#include "shadecore/unit.hpp"

namespace shadecore::sim {

// The handshake state of one clock edge at a core's ports (the monitor's, sim/tb_monitor_logic.hpp).
struct EdgeState {
  bool rst_n, in_valid, in_ready, out_valid, out_ready;
  uint64_t in_flight;
  // The lighting core's register port (the pins adapter's reg_port()): 0 no write presented (or no register port),
  // 1 a write presented and held (reg_we_i high, reg_ready_o low: the core drains its fragments first), 2 taken.
  int reg = 0;
};

// A group of named bins.
class FuncCov {
 public:
  explicit FuncCov(std::string group) : group_(std::move(group)) {}
  FuncCov(const FuncCov&) = delete;
  FuncCov& operator=(const FuncCov&) = delete;
  int declare(const std::string& name) {
    names_.push_back(name);
    counts_.push_back(0);
    return static_cast<int>(names_.size()) - 1;
  }
  void hit(int bin) {
    if (bin >= 0) ++counts_[static_cast<size_t>(bin)];
  }
  // Registers every bin with the context's coverage database (call once, before the run; the counters must
  // outlive the database's write: write_coverage() before this object goes).
  template <class Context>  // VerilatedContext (a template, so this header needs no Verilator without a call)
  void attach(Context* ctx) {
#if defined(VM_COVERAGE) && VM_COVERAGE
    const std::string page = "v_func/" + group_;
    for (size_t i = 0; i < names_.size(); ++i) {
      ctx->coveragep()->_inserti(&counts_[i]);
      ctx->coveragep()->_insertf(__FILE__, __LINE__);
      ctx->coveragep()->_insertp("hier", group_.c_str(), "page", page.c_str(), "comment", names_[i].c_str());
    }
#else
    (void)ctx;
#endif
  }

 private:
  std::string group_;
  std::vector<std::string> names_;

 public:
  // The bins and their counts (tests: which bins a stimulus reaches on the C model alone).
  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  [[nodiscard]] uint32_t count(int bin) const { return counts_[static_cast<size_t>(bin)]; }

 private:
  std::deque<uint32_t> counts_;  // stable addresses
};

// Handshake bins of a core's ports, sampled per clock edge by the monitor (EdgeState), in the core's group.
class HandshakeBins {
 public:
  void declare(FuncCov& c) {
    static const char* names[kBins] = {
        "handshake input gap while the core is ready (in_valid low, in_ready high)",
        "handshake input held by the core (in_valid high, in_ready low)",
        "handshake output backpressure (out_valid high, out_ready low)",
        "handshake input gap and output backpressure at one edge",
        "handshake input held and output backpressure at one edge",
        "handshake a transfer in and out at one edge",
        "handshake reset with transactions in flight",
        "handshake reset with nothing in flight"};
    for (int i = 0; i < kBins; ++i) b_[i] = c.declare(names[i]);
  }
  void sample(FuncCov& c, const EdgeState& e) const {
    if (!e.rst_n) {
      c.hit(b_[e.in_flight > 0 ? 6 : 7]);
      return;
    }
    const bool gap = !e.in_valid && e.in_ready, held = e.in_valid && !e.in_ready, bp = e.out_valid && !e.out_ready;
    if (gap) c.hit(b_[0]);
    if (held) c.hit(b_[1]);
    if (bp) c.hit(b_[2]);
    if (!e.in_valid && bp) c.hit(b_[3]);
    if (held && bp) c.hit(b_[4]);
    if (e.in_valid && e.in_ready && e.out_valid && e.out_ready) c.hit(b_[5]);
  }

 private:
  static constexpr int kBins = 8;
  int b_[kBins] = {};
};

// Register-port bins of the lighting core, sampled per clock edge in its group.
class RegPortBins {
 public:
  void declare(FuncCov& c) {
    wait_ = c.declare("handshake register write waiting for a drain (reg_we high, reg_ready low)");
    wait_held_ = c.declare("handshake register write waiting while the output is held (out_valid high, out_ready low)");
    taken_ = c.declare("handshake register write taken");
  }
  void sample(FuncCov& c, const EdgeState& e) const {
    if (!e.rst_n) return;
    if (e.reg == 1) {
      c.hit(wait_);
      if (e.out_valid && !e.out_ready) c.hit(wait_held_);  // the drain itself stalled by the consumer
    }
    if (e.reg == 2) c.hit(taken_);
  }

 private:
  int wait_ = -1, wait_held_ = -1, taken_ = -1;
};

// The specular unit: code class × n class.
class UnitFuncCov {
 public:
  explicit UnitFuncCov(const Unit& u) : cov_("unit_" + std::string(variant_name(u.variant()))), unit_(u) {
    thr_ = u.cutoff() == Cutoff::ThetaCr && (u.variant() == VariantId::cs16 || u.variant() == VariantId::cs16_faithful ||
                                             u.variant() == VariantId::cs16_compact);
    const std::vector<std::string> codes =
        thr_ ? std::vector<std::string>{"negative", "zero", "below_thr", "thr-1", "thr", "thr+1", "lobe", "one", "above_one"}
             : std::vector<std::string>{"negative", "zero", "lobe", "one", "above_one"};
    for (const char* nc : {"n16", "n17..1023", "n1024"})
      for (const auto& c : codes) bins_.push_back(cov_.declare(std::string("code ") + c + " x " + nc));
    ncodes_ = static_cast<int>(codes.size());
    hs_.declare(cov_);
  }
  template <class Context>
  void attach(Context* ctx) {
    cov_.attach(ctx);
  }
  void sample_edge(const EdgeState& e) { hs_.sample(cov_, e); }
  void sample(const UnitMaterial& m, int64_t code) {
    const int64_t one = int64_t{1} << unit_.format().frac;
    const int64_t t = static_cast<int64_t>(m.thr);
    int c;
    if (code < 0) c = 0;
    else if (code == 0) c = 1;
    else if (code > one) c = ncodes_ - 1;
    else if (code == one) c = ncodes_ - 2;
    else if (!thr_) c = 2;
    else if (code < t - 1) c = 2;
    else if (code == t - 1) c = 3;
    else if (code == t) c = 4;
    else if (code == t + 1) c = 5;
    else c = 6;
    const int nc = m.n <= 16 ? 0 : (m.n >= 1024 ? 2 : 1);
    cov_.hit(bins_[static_cast<size_t>(nc * ncodes_ + c)]);
  }

 private:
  FuncCov cov_;
  HandshakeBins hs_;
  const Unit& unit_;
  bool thr_ = false;
  int ncodes_ = 0;
  std::vector<int> bins_;
};

// The lighting core.
class LightFuncCov {
 public:
  explicit LightFuncCov(const LightCore& core) : cov_("light"), core_(core) {
    for (auto& a : kind_) for (auto& b : a) for (int& x : b) x = -1;
    for (auto& a : spot_) for (int& x : a) x = -1;
    for (auto& a : at_p_) for (int& x : a) x = -1;
    for (auto& a : shin_) for (int& x : a) x = -1;
    const FeatureSet& fs = core.features();
    static const char* kinds[] = {"directional", "point", "point_att", "spot"};
    for (int j = 0; j < fs.num_lights(); ++j)
      for (int k = 0; k < kNumLightKinds; ++k) {
        if (!fs.slot_can(j, static_cast<LightKind>(k))) continue;
        const std::string base = "light" + std::to_string(j) + " " + kinds[k];
        kind_[j][k][0] = cov_.declare(base + " disabled");
        if (k == static_cast<int>(LightKind::Spot)) {
          for (int s = 0; s < 3; ++s)
            spot_[j][s] = cov_.declare(base + (s == 0 ? " on, inside the cone" : s == 1 ? " on, outside the cone" : " on, at the cone's edge"));
        } else {
          kind_[j][k][1] = cov_.declare(base + " on");
        }
        if (k != static_cast<int>(LightKind::Directional)) at_p_[j][k] = cov_.declare(base + " on, light at P");
      }
    for (int m = 0; m < 16; ++m) {
      const bool lv = m & 1, ph = m & 2, ts = m & 4, sep = m & 8;
      if ((lv && !(fs.specular && fs.local_viewer)) || (ph && !fs.phong) || (!ph && !fs.blinn && fs.phong) ||
          (ts && !fs.two_side) || (sep && !fs.separate_specular))
        continue;
      std::string n = std::string("mode ") + (lv ? "local_viewer" : "infinite_viewer") + " x " +
                      (fs.specular ? (ph ? "phong" : "blinn") : "no_specular") + " x " + (ts ? "two_side" : "one_side") +
                      " x " + (sep ? "separate_specular" : "single_colour");
      mode_[m] = cov_.declare(n);
    }
    if (fs.colour_material) {
      cm_off_ = cov_.declare("colour_material off");
      for (int m = 0; m < 8; ++m) cm_[m] = cov_.declare("colour_material mode " + std::to_string(m));
    }
    if (fs.specular) {
      const auto us = fs.units();
      static const char* classes[] = {"0", "1..15", "16", "17..1023", "1024"};
      for (size_t u = 0; u < us.size(); ++u)
        for (int c = 0; c < 5; ++c) {
          if (c < 2 && !fs.low_shininess) continue;
          shin_[u][c] = cov_.declare(std::string("unit ") + std::string(variant_name(us[u])) + " x shininess " + classes[c]);
        }
    }
    // attenuation classes of q = kc + kl·d + kq·d² (F fraction bits), per kind that has one: q = 0; q below 1.0
    // (1/q saturates to 1); q at or above 1.0 with 1/q at least one code; 1/q rounding to 0 (point_att only: a
    // spot's att carries its cone factor) — crossed with spot's cone (inside, outside)
    static const char* qcls[] = {"q = 0", "0 < q < 1 (1/q saturates)", "q >= 1, 1/q >= one code", "1/q rounds to 0"};
    for (int j = 0; j < fs.num_lights(); ++j) {
      any_patt_ = any_patt_ || fs.slot_can(j, LightKind::PointAtt);
      any_spot_ = any_spot_ || fs.slot_can(j, LightKind::Spot);
    }
    if (any_patt_)
      for (int c = 0; c < 4; ++c) att_[0][c] = cov_.declare(std::string("point_att x attenuation ") + qcls[c]);
    if (any_spot_)
      for (int s = 0; s < 2; ++s)
        for (int c = 0; c < 3; ++c)
          att_[1 + s][c] = cov_.declare(std::string("spot ") + (s == 0 ? "inside" : "outside") + " the cone x attenuation " + qcls[c]);
    // passes per fragment where the lanes are fewer than the lights (lights dealt LANES per pass)
    max_passes_ = (fs.num_lights() + fs.lanes - 1) / fs.lanes;
    if (max_passes_ > 1)
      for (int p = 1; p <= max_passes_; ++p) passes_[p] = cov_.declare("passes " + std::to_string(p) + " of " + std::to_string(max_passes_));
    if (fs.specular && fs.blinn) h_zero_ = cov_.declare("hard H = 0 (L = -V, Blinn)");
    static const char* chn[] = {"r", "g", "b"};
    for (int c = 0; c < fs.channels; ++c) {
      sat_ch_[c] = cov_.declare(std::string("hard colour channel ") + chn[c] + " saturated (its sum above 1.0)");
      if (fs.separate_specular)
        ssat_ch_[c] = cov_.declare(std::string("hard secondary colour channel ") + chn[c] + " saturated");
    }
    n_zero_ = cov_.declare("hard N = 0");
    n_tiny_ = cov_.declare("hard tiny N (every component |n| <= 2)");
    ndl_zero_ = cov_.declare("hard N.L = 0");
    ndl_pm1_ = cov_.declare("hard N.L = +-1 code");
    ndl_neg_ = cov_.declare("hard N.L < 0 (light behind)");
    sat_ = cov_.declare("hard colour saturated (a channel's sum above 1.0)");
    // back-facing with the two-sided mode off and on: only where two-sided lighting exists (without it in_back_i
    // is not an input the core reads)
    if (fs.two_side) {
      back_one_ = cov_.declare("back-facing, one-sided");
      back_two_ = cov_.declare("back-facing, two-sided");
    }
    none_on_ = cov_.declare("no light on (the scene term alone)");
    hs_.declare(cov_);
    reg_.declare(cov_);
  }
  template <class Context>
  void attach(Context* ctx) {
    cov_.attach(ctx);
  }
  void sample_edge(const EdgeState& e) {
    hs_.sample(cov_, e);
    reg_.sample(cov_, e);
  }
  [[nodiscard]] const FuncCov& bins() const { return cov_; }

  void sample(const LightRegs& r, const Fragment& fr, const LightCoreTrace& t) {
    const FeatureSet& fs = core_.features();
    const LightModes md = core_.modes(r);
    const int F = core_.format().frac, VF = core_.unit_format().frac;
    for (int j = 0; j < fs.num_lights(); ++j) {
      const auto& L = r.light[static_cast<size_t>(j)];
      const int k = static_cast<int>(L.mode >> 1);
      if (k >= kNumLightKinds || !fs.slot_can(j, static_cast<LightKind>(k))) continue;
      const auto& lt = t.light[static_cast<size_t>(j)];
      if (!(md.on & (1u << j))) {
        cov_.hit(kind_[j][k][0]);
        continue;
      }
      if (k == static_cast<int>(LightKind::Spot)) {
        const int64_t dist = lt.sdl - static_cast<int64_t>(L.scos);
        cov_.hit(spot_[j][std::llabs(dist) <= 1 ? 2 : (lt.in_cone ? 0 : 1)]);
      } else {
        cov_.hit(kind_[j][k][1]);
      }
      if (k != static_cast<int>(LightKind::Directional) && L.pos[0] == fr.p[0] && L.pos[1] == fr.p[1] && L.pos[2] == fr.p[2])
        cov_.hit(at_p_[j][k]);
      if (k == static_cast<int>(LightKind::PointAtt) || k == static_cast<int>(LightKind::Spot)) {
        const uint64_t one_q = uint64_t{1} << F;
        int c = lt.q == 0 ? 0 : lt.q < one_q ? 1 : 2;
        if (k == static_cast<int>(LightKind::PointAtt)) {
          if (c == 2 && lt.att == 0) c = 3;
          cov_.hit(att_[0][c]);
        } else {
          cov_.hit(att_[lt.in_cone ? 1 : 2][c]);
        }
      }
      if (h_zero_ >= 0 && !md.phong && lt.l[0] == -t.v[0] && lt.l[1] == -t.v[1] && lt.l[2] == -t.v[2]) cov_.hit(h_zero_);
      const int64_t one_code = int64_t{1} << (VF - F);  // one code of the F-bit N·L, in VF fraction bits
      if (lt.ndl == 0) cov_.hit(ndl_zero_);
      else if (std::llabs(lt.ndl) <= one_code) cov_.hit(ndl_pm1_);
      if (lt.ndl < 0) cov_.hit(ndl_neg_);
    }
    const int m = (md.local_viewer ? 1 : 0) | (md.phong ? 2 : 0) | (md.two_side ? 4 : 0) | (md.separate ? 8 : 0);
    cov_.hit(mode_[m]);
    if (fs.colour_material) cov_.hit((r.colour_material & 1u) ? cm_[(r.colour_material >> 1) & 7u] : cm_off_);
    if (fs.specular && md.unit >= 0) {
      const uint32_t n = r.mat_n;
      const int c = n == 0 ? 0 : n < 16 ? 1 : n == 16 ? 2 : n < 1024 ? 3 : 4;
      if (md.unit < 8) cov_.hit(shin_[static_cast<size_t>(md.unit)][c]);
    }
    if (fr.n[0] == 0 && fr.n[1] == 0 && fr.n[2] == 0) cov_.hit(n_zero_);
    else if (std::llabs(fr.n[0]) <= 2 && std::llabs(fr.n[1]) <= 2 && std::llabs(fr.n[2]) <= 2) cov_.hit(n_tiny_);
    const uint64_t one = uint64_t{1} << F;
    for (int c = 0; c < 3; ++c)
      if (t.total[c] > one || t.stotal[c] > one) {
        cov_.hit(sat_);
        break;
      }
    for (int c = 0; c < fs.channels; ++c) {
      if (t.total[c] > one) cov_.hit(sat_ch_[c]);
      if (t.stotal[c] > one) cov_.hit(ssat_ch_[c]);
    }
    if (max_passes_ > 1 && t.passes >= 1 && t.passes <= max_passes_) cov_.hit(passes_[t.passes]);
    if (fr.back && fs.two_side) cov_.hit(md.two_side ? back_two_ : back_one_);
    if (md.enabled == 0) cov_.hit(none_on_);
  }

 private:
  FuncCov cov_;
  HandshakeBins hs_;
  RegPortBins reg_;
  const LightCore& core_;
  int kind_[kMaxLights][kNumLightKinds][2] = {};
  int spot_[kMaxLights][3] = {};
  int at_p_[kMaxLights][kNumLightKinds] = {};
  int mode_[16] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  int cm_off_ = -1, cm_[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
  int shin_[8][5] = {};
  bool any_patt_ = false, any_spot_ = false;
  int att_[3][4] = {{-1, -1, -1, -1}, {-1, -1, -1, -1}, {-1, -1, -1, -1}};  // point_att; spot inside; spot outside
  int max_passes_ = 1;
  int passes_[kMaxLights + 1] = {-1, -1, -1, -1, -1, -1, -1, -1, -1};
  int h_zero_ = -1;
  int sat_ch_[3] = {-1, -1, -1}, ssat_ch_[3] = {-1, -1, -1};
  int n_zero_ = -1, n_tiny_ = -1, ndl_zero_ = -1, ndl_pm1_ = -1, ndl_neg_ = -1, sat_ = -1, back_one_ = -1, back_two_ = -1,
      none_on_ = -1;
};

}  // namespace shadecore::sim

// SPDX-License-Identifier: Apache-2.0
// shadecore sim — what the driver feeds the lighting core, one CoreCommand (register write or
// fragment) at a time, by mode:
//   random:   a random but realistic register program first (global ambient and random modes — local
//             viewer, reflection, normalize —, a material with random n and a random unit of the core,
//             every light slot with a random kind it can take, enabled or not, random colours, positions
//             and attenuation), then
//             `count` fragments: 45 % realistic (random eye-space positions, normals of random length; on a
//             core with a light slot that can be spot, a third of them, 15 % of all fragments, are instead
//             aimed at the cone of an enabled spot light — 5 % inside, 5 % outside, 5 % at its edge, the
//             cut-off ±1 code, see spot_fragment() — whenever one is on),
//             20 % raw random codes over the whole input words, 35 % hard cases built on the current
//             registers (see hard_fragment()). With probability `write_rate` per fragment a burst of
//             register writes comes first: a new material, a new light, raw random data to any register
//             but n/thr/coef/mat_unit (the unit contract: material_writes sets them together; mode and
//             reserved registers included, so modes that name absent capabilities occur), new modes, or a
//             write to a non-register address.
//   directed: the hard-case programs and fragments of docs/lighting.md §7, each at least once, then every
//             global mode × every unit × enable patterns (none, one, every other, all), repeated until
//             `count` fragments.
//   stream:   a command file (stimulus/include/shadecore/stimulus/light_stream.hpp), e.g. a scene's fragments from `shadecore render`.
// Deterministic from the seed. Random mode is a function of (seed, feature set, fragment index), like the
// specular unit's stimulus (specular.hpp), so a run can be split into shards by index (`first`): the
// register program comes from the seed; fragment i, and whether a register-write burst comes before it
// and what that burst writes, each come from their own stream Rng::for_item(seed ^ K, i). A shard that
// starts at index `first` > 0 replays the burst decisions of indices 0..first−1 (one hash per index, no
// simulation: 10⁸ indices in 0.6 CPU-s) and opens with the register state they leave — the last data written to
// each address, in address order — so fragment i meets the same registers whatever the shard count.
// Directed and stream modes are one sequence (not sharded).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadecore/stimulus/light_stream.hpp"
#include "shadecore/light.hpp"
#include "shadecore/stimulus/rng.hpp"

namespace shadecore::sim {

enum class LightMode { Random, Directed, Stream };

class LightStimulus {
 public:
  // first: random mode only — the global index of this run's first fragment (a shard of a longer run).
  LightStimulus(const LightCore& core, LightMode mode, uint64_t count, uint64_t seed, double write_rate,
                std::vector<CoreCommand> stream = {}, uint64_t first = 0)
      : core_(core), f_(core.format()), F_(f_.frac), W_(core.widths()), mode_(mode), count_(count), write_rate_(write_rate),
        rng_(seed ^ 0x11647c0deull), seed_(seed), first_(first), burst_threshold_(rate_threshold(write_rate)),
        stream_(std::move(stream)) {
    if (first_ != 0 && mode_ != LightMode::Random) throw std::invalid_argument("a first index applies to random mode only");
    if (mode_ == LightMode::Stream) {
      for (const auto& c : stream_)
        if (!c.is_write) ++planned_;
    } else if (mode_ == LightMode::Directed) {
      build_directed();
      planned_ = count_ > directed_frags_ ? count_ : directed_frags_;
    } else {
      planned_ = count_;
      program_random();
      if (first_ > 0) replay_bursts();
    }
  }

  [[nodiscard]] uint64_t planned() const { return planned_; }
  // Random mode: the global index of the first fragment.
  [[nodiscard]] uint64_t first() const { return first_; }
  // A sum over the fragments handed out of a hash of (global index, fragment): equal for two runs that
  // drive the same fragments, however they are split into shards (the shards' sums add up).
  [[nodiscard]] uint64_t digest() const { return digest_; }

  // Whether a register-write burst comes before random fragment `index` (rate: probability per fragment).
  static bool burst_before(uint64_t seed, uint64_t index, uint64_t threshold) {
    return threshold != 0 && Rng::for_item(seed ^ 0x4255525354424546ull, index).next() < threshold;
  }

  bool next(CoreCommand& c) {
    if (mode_ == LightMode::Stream) {
      if (pos_ >= stream_.size()) return false;
      c = stream_[pos_++];
      return true;
    }
    if (!pending_.empty()) {
      c = pending_.front();
      pending_.pop_front();
      return true;
    }
    if (mode_ == LightMode::Directed) {
      if (frags_ >= planned_) return false;
      if (pos_ == directed_.size()) pos_ = 0;
      c = directed_[pos_++];
      if (!c.is_write) ++frags_;
      return true;
    }
    if (frags_ >= count_) return false;
    const uint64_t index = first_ + frags_;
    if (burst_pending_ != index + 1) {  // this fragment's burst is drawn once
      burst_pending_ = index + 1;
      if (burst_before(seed_, index, burst_threshold_)) {
        rng_ = Rng::for_item(seed_ ^ 0x4255525354444154ull, index);
        random_writes();  // may come out empty (every raw pick was a unit-contract register)
        if (!pending_.empty()) {
          c = pending_.front();
          pending_.pop_front();
          return true;
        }
      }
    }
    rng_ = Rng::for_item(seed_, index);
    check_written(index);
    c.is_write = false;
    c.f = random_fragment();
    if (core_.features().two_side) c.f.back = (rng_.next() & 1) != 0;  // the facing bit (drawn only where it exists)
    if (core_.features().colour_material) random_colour(c.f);             // the colour (likewise)
    digest_ += fragment_digest(index, c.f);
    ++frags_;
    return true;
  }

  static uint64_t fragment_digest(uint64_t index, const Fragment& f) {
    uint64_t h = mix64(index + 0x9E3779B97F4A7C15ull);
    for (int i = 0; i < 3; ++i) h = mix64(h ^ static_cast<uint64_t>(f.n[i])) ^ mix64(static_cast<uint64_t>(f.p[i]) + h);
    return h;
  }

 private:
  static uint64_t rate_threshold(double rate) {
    if (rate <= 0.0) return 0;
    if (rate >= 1.0) return ~uint64_t{0};
    return static_cast<uint64_t>(rate * 18446744073709551616.0);
  }
  // A shard's opening: the bursts of fragments 0..first−1 applied to the program's register state, written
  // as the last data of every address written (address order; registers are plain storage, so the state
  // is the same as after the whole sequence).
  void replay_bursts() {
    std::map<uint32_t, uint32_t> last;
    for (const auto& c : pending_) last[c.w.addr] = c.w.data;
    pending_.clear();
    for (uint64_t i = 0; i < first_; ++i) {
      if (!burst_before(seed_, i, burst_threshold_)) continue;
      rng_ = Rng::for_item(seed_ ^ 0x4255525354444154ull, i);
      random_writes();
      for (const auto& c : pending_) last[c.w.addr] = c.w.data;
      pending_.clear();
    }
    for (const auto& [addr, data] : last) {
      CoreCommand c;
      c.is_write = true;
      c.w = {addr, data};
      pending_.push_back(c);
    }
  }

  double u01() { return static_cast<double>(rng_.next() >> 11) * 0x1.0p-53; }
  // A fragment colour (colour_material): an eighth of the channels at an extreme (0, 1.0, the largest code),
  // the rest anywhere in the register's range [0, 2)
  void random_colour(Fragment& f) {
    const uint32_t one = 1u << F_, cmax = (2u << F_) - 1;
    for (uint32_t& x : f.col) {
      const uint64_t r = rng_.next();
      x = r % 8 == 0 ? std::array<uint32_t, 3>{0u, one, cmax}[(r >> 3) % 3] : static_cast<uint32_t>((r >> 8) & cmax);
    }
  }
  double u(double lo, double hi) { return lo + (hi - lo) * u01(); }

  // Queue register writes into q (the random stream's pending_ or the directed list), tracking them in shadow_.
  template <class Q>
  void queue_writes(Q& q, const std::vector<RegWrite>& ws) {
    for (const auto& w : ws) {
      CoreCommand c;
      c.is_write = true;
      c.w = w;
      q.push_back(c);
      shadow_.write(W_, w.addr, w.data);
      if (w.addr < written_.size()) written_[w.addr] = true;
      check_due_ = true;
    }
  }
  // The generator's own check of the register contract (docs/lighting.md §4: registers are not reset, a program
  // writes every register it relies on): before a fragment, every register an enabled light relies on (mode,
  // position, colours; attenuation for point_att and spot; the spot registers for spot) has been written. A
  // 2-state simulator and the C model would agree on an unwritten register (both read 0) and hide the bug; a
  // 4-state simulator and the hardware would not (it showed as X in Icarus).
  void check_written(uint64_t frag) {
    if (!check_due_) return;  // nothing written since the last check
    check_due_ = false;
    const FeatureSet& fs = core_.features();
    for (int j = 0; j < fs.num_lights(); ++j) {
      const uint32_t base = static_cast<uint32_t>(j) * kLightStride;
      const uint32_t mode = shadow_.light[static_cast<size_t>(j)].mode;
      const uint32_t k = mode >> 1;
      if ((mode & kModeEnable) == 0 || k >= static_cast<uint32_t>(kNumLightKinds)) continue;
      const auto kind = static_cast<LightKind>(k);
      if (!fs.slot_can(j, kind)) continue;  // a kind the slot cannot take: the light is off
      std::vector<uint32_t> regs;
      for (uint32_t c = 0; c < 3; ++c)
        for (uint32_t r : {kReg_light_position, kReg_light_ambient, kReg_light_diffuse, kReg_light_specular}) regs.push_back(r + c);
      if (has_att(kind)) regs.insert(regs.end(), {kReg_light_kc, kReg_light_kl, kReg_light_kq});
      if (kind == LightKind::Spot)
        regs.insert(regs.end(), {kReg_light_spot_direction, kReg_light_spot_direction + 1, kReg_light_spot_direction + 2,
                                 kReg_light_spot_cos, kReg_light_spot_exponent});
      for (uint32_t r : regs)
        if (!written_[base + r]) {
          std::string name = std::to_string(base + r);
          for (const auto& reg : kRegisters)
            if (reg.per_light && r >= reg.addr && r < reg.addr + static_cast<uint32_t>(reg.count))
              name = std::string(reg.name) + "[" + std::to_string(r - reg.addr) + "] (address " + name + ")";
          throw std::logic_error("light stimulus: fragment " + std::to_string(frag) + " would be lit by light " +
                                 std::to_string(j) + " (" + to_string(kind) + ") whose register " + name +
                                 " was never written (a bug of the generator: registers are not reset)");
        }
    }
  }
  void push(const std::vector<RegWrite>& ws) { queue_writes(pending_, ws); }
  std::vector<RegWrite> random_material() {
    MaterialParams m;
    for (int c = 0; c < 3; ++c) {
      m.emission[c] = u01() < 0.7 ? 0.0 : u(0, 0.5);
      m.ambient[c] = u(0, 1);
      m.diffuse[c] = u(0, 1);
      m.specular[c] = u(0, 1.5);
    }
    m.shininess = static_cast<int>(rng_.uniform(kNMin, kNMax));
    // a core with the low-shininess chain: a quarter of the materials below the units' range (GL's 0..15), an
    // eighth just above its start (16..33, where the chain's decode ends: no draw of its own, so every other value
    // of the stream is as before)
    if (core_.features().low_shininess) {
      const uint64_t r = rng_.next() % 8;
      if (r % 4 == 0) m.shininess = static_cast<int>(rng_.next() % kNMin);
      else if (r == 1) m.shininess = kNMin + m.shininess % 18;
    }
    m.norm_model = static_cast<int>(rng_.uniform(0, kNumModels - 1));
    if (rng_.next() % 4 == 0) m.norm_model = -1;  // no normalisation (coef = 1 with the norm hardware)
    m.norm_kind = rng_.next() & 1 ? CoefKind::Classical : CoefKind::Fitted;
    const std::vector<VariantId> us = core_.features().units();
    if (!us.empty()) m.unit = us[rng_.next() % us.size()];
    std::vector<RegWrite> w = material_writes(core_, m);
    if (core_.features().two_side) {  // the back colour bank too (registers are not reset: a program writes them)
      MaterialParams b = m;
      for (int c = 0; c < 3; ++c) b.emission[c] = u(0, 0.5), b.ambient[c] = u(0, 1), b.diffuse[c] = u(0, 1), b.specular[c] = u(0, 1.5);
      const auto bw = back_material_writes(core_, b);
      w.insert(w.end(), bw.begin(), bw.end());
    }
    if (core_.features().colour_material)  // GL_COLOR_MATERIAL on in 3/4 of the programs, every mode field 0..7
      w.push_back({kReg_colour_material, static_cast<uint32_t>(rng_.next() & mask_bits(kColourMaterialBits)) |
                                             (rng_.next() % 4 != 0 ? 1u : 0u)});
    return w;
  }
  // A kind slot j can take: the r-th of its kinds (mod their count).
  LightKind slot_kind(int j, uint64_t r) const {
    const uint8_t mask = core_.features().slots[static_cast<size_t>(j)];
    int count = 0;
    for (int k = 0; k < kNumLightKinds; ++k) count += (mask >> k) & 1;
    int want = static_cast<int>(r % static_cast<uint64_t>(count));
    for (int k = 0; k < kNumLightKinds; ++k)
      if ((mask >> k) & 1) {
        if (want == 0) return static_cast<LightKind>(k);
        --want;
      }
    return LightKind::Directional;
  }
  ModeParams random_modes() {
    const uint64_t r = rng_.next();
    return {(r & 1) != 0, (r & 2) != 0, (r & 4) != 0, (r & 8) != 0, (r & 16) != 0};
  }
  // force_spot: an enabled spot light with a cone (cutoff neither 0 nor 180: inside, outside and edge all exist)
  std::vector<RegWrite> random_light(int j, bool force_spot = false) {
    LightParams lp;
    const LightKind kind = force_spot ? LightKind::Spot : slot_kind(j, rng_.next());
    lp.kind = kind;
    lp.enabled = force_spot || rng_.next() % 8 != 0;
    if (kind == LightKind::Directional) {
      double d[3];
      do {
        for (double& x : d) x = u(-1, 1);
      } while (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 1e-3);
      for (int i = 0; i < 3; ++i) lp.position[i] = d[i];
      lp.position[3] = 0;
    } else {
      for (int i = 0; i < 3; ++i) lp.position[i] = u(-40, 40);
      lp.position[3] = 1;
    }
    for (int c = 0; c < 3; ++c) {
      lp.ambient[c] = u(0, 0.3);
      lp.diffuse[c] = u(0, 1.2);
      lp.specular[c] = u(0, 1.2);
    }
    lp.kc = u(0, 2);
    lp.kl = u01() < 0.5 ? 0.0 : u(0, 0.2);
    lp.kq = u01() < 0.5 ? 0.0 : u(0, 0.05);
    if (lp.kc < 0.01 && lp.kl == 0 && lp.kq == 0) lp.kc = 1;
    if (kind == LightKind::Spot) random_spot(lp);
    if (force_spot && (lp.spot_cutoff == 180 || lp.spot_cutoff == 0)) lp.spot_cutoff = u(1, 89);
    return light_writes(core_, j, lp);
  }
  // A spot light: its direction points near the fragments' region (the origin) from its position, so that
  // fragments fall inside and outside the cone; cutoffs 0..90 (the edges included) and sometimes 180;
  // exponents 0..128 with their ends and the chain's bit patterns.
  void random_spot(LightParams& lp) {
    for (int i = 0; i < 3; ++i) lp.spot_direction[i] = -lp.position[i] + u(-30, 30);
    if (std::fabs(lp.spot_direction[0]) + std::fabs(lp.spot_direction[1]) + std::fabs(lp.spot_direction[2]) < 1e-3)
      lp.spot_direction[2] = -1;
    switch (rng_.next() % 8) {
      case 0: lp.spot_cutoff = 180; break;
      case 1: lp.spot_cutoff = 90; break;
      case 2: lp.spot_cutoff = 0; break;
      default: lp.spot_cutoff = u(1, 89);
    }
    static constexpr int kExp[] = {0, 1, 2, 3, 15, 16, 64, 127, 128};
    lp.spot_exponent = rng_.next() % 2 ? kExp[rng_.next() % 9] : static_cast<int>(rng_.uniform(0, kSpotExpMax));
  }
  void program_random() {
    double ga[3] = {u(0, 0.4), u(0, 0.4), u(0, 0.4)};
    push(global_writes(core_, ga, random_modes()));
    push(random_material());
    // every slot's registers at GL's initial state first (a driver's context creation), so a later raw mode
    // write that changes a slot's kind meets defined attenuation and spot registers
    for (int j = 0; j < core_.features().num_lights(); ++j) push(light_reset_writes(core_, j));
    for (int j = 0; j < core_.features().num_lights(); ++j) push(random_light(j));
    // a core with spot hardware: a program whose draws gave no enabled spot light with a cone (seed 5 of `full`:
    // none at all; its spot fragments then came from a raw mode write meeting GL's reset cutoff 180, all inside)
    // gets one, on a slot that can be spot drawn uniformly, so the aimed fragments of spot_fragment() have a cone
    std::vector<int> spot;
    bool cone = false;
    for (int j = 0; j < core_.features().num_lights(); ++j) {
      if (!core_.features().slot_can(j, LightKind::Spot)) continue;
      spot.push_back(j);
      const auto& L = shadow_.light[static_cast<size_t>(j)];
      const int64_t full = int64_t{1} << core_.unit_format().frac;
      if ((L.mode & kModeEnable) && (L.mode >> 1) == static_cast<uint32_t>(LightKind::Spot) && L.scos > -full && L.scos < full)
        cone = true;
    }
    if (!spot.empty() && !cone) push(random_light(spot[rng_.next() % spot.size()], true));
  }
  // Raw register data: every register of the map, random bits or an extreme of its width.
  void random_writes() {
    const int nl = core_.features().num_lights();
    switch (rng_.next() % 6) {
      case 0: push(random_material()); break;
      case 1: push(random_light(static_cast<int>(rng_.uniform(0, nl - 1)))); break;
      case 2: {  // raw colour / position / attenuation data, extremes included
        const int k = static_cast<int>(rng_.uniform(1, 6));
        std::vector<RegWrite> ws;
        for (int i = 0; i < k; ++i) {
          const auto& reg = kRegisters[rng_.next() % kRegisters.size()];
          // unit contract: n, thr, coef and the unit they were set up for (mat_unit) are written together
          // by material_writes (a cs16 unit with another unit's thr is outside its contract)
          if (reg.format == "n" || reg.format == "thr" || reg.format == "coef" || reg.format == "unit") continue;
          uint32_t addr = reg.addr + static_cast<uint32_t>(rng_.uniform(0, reg.count - 1));
          if (reg.per_light) addr += kLightStride * static_cast<uint32_t>(rng_.uniform(0, nl - 1));
          uint32_t data;
          switch (rng_.next() % 4) {
            case 0: data = 0; break;
            case 1: data = 0xFFFFFFFFu; break;
            default: data = static_cast<uint32_t>(rng_.next());
          }
          ws.push_back({addr, data});
        }
        push(ws);
        break;
      }
      case 3:  // an address that is no register (above the back-material bank)
        push({{static_cast<uint32_t>(rng_.uniform(0x130, (1 << kRegAddrBits) - 1)), static_cast<uint32_t>(rng_.next())}});
        break;
      case 4: {  // new modes, lights switched on and off
        push({{kReg_light_model, light_model_word(random_modes())}});
        const int j = static_cast<int>(rng_.uniform(0, nl - 1));
        push({{static_cast<uint32_t>(j) * kLightStride + kReg_light_mode,
               light_mode_word(rng_.next() % 3 != 0, slot_kind(j, rng_.next()))}});
        break;
      }
      default: {  // global ambient
        double ga[3] = {u(0, 1.9), u(0, 1.9), u(0, 1.9)};
        push(global_writes(core_, ga, random_modes()));
      }
    }
  }

  Fragment random_fragment() {
    const uint64_t r = rng_.next() % 100;
    if (r >= 30 && r < 45) {  // aimed at a spot light's cone (where one is on): r % 3 = 0 inside, 1 outside, 2 edge
      Fragment f;
      if (spot_fragment(r % 3, f)) return f;
    }
    if (r < 45) {  // realistic
      double n[3], p[3];
      for (double& x : n) x = u(-1, 1);
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double scale = (rng_.next() & 1) ? 1.0 : u(0.3, 1.9);
      for (double& x : n) x = len > 0 ? x / len * scale : 0.0;
      for (int i = 0; i < 2; ++i) p[i] = u(-30, 30);
      p[2] = u(-100, 5);
      return make_fragment(F_, n, p);
    }
    if (r < 65) {  // raw codes over the whole words
      Fragment f;
      for (int i = 0; i < 3; ++i) {
        f.n[i] = sign_extend(rng_.next(), light_normal_bits(F_));
        f.p[i] = sign_extend(rng_.next(), light_pos_bits(F_));
      }
      return f;
    }
    return hard_fragment(rng_.next() % 10);
  }

  // A fragment placed against the cone of one of the enabled spot lights (a slot that can be spot, holding an
  // enabled spot, drawn uniformly): cls 0 inside (−L̂·ŝ at least 2 codes above the spot cos register), 1 outside
  // (at least 2 codes below), 2 at the edge (within one code of it: the cut-off boundary ±1). P = light position +
  // d·(cos θ ŝ + sin θ u), d in [6, 30), u a random perpendicular, θ drawn on the class's side of the cut-off
  // angle; the class is then checked on the C model's own −L̂·ŝ (LightCore::eval's trace, as the bench's
  // functional bins read it) and P nudged by a code or two per axis until it holds (up to 64 tries). The normal
  // faces the light, so the spot factor shows in the colour. False when no spot light is on (the caller draws a
  // realistic fragment instead); a class the registers cannot give (cutoff 180 has no outside, a raw cos register
  // beyond ±1.0 no inside or no outside) leaves the last try, whatever its class.
  bool spot_fragment(uint64_t cls, Fragment& f) {
    const FeatureSet& fs = core_.features();
    const uint32_t on = core_.modes(shadow_).on;
    int cand[kMaxLights], nc = 0;
    for (int j = 0; j < fs.num_lights(); ++j) {
      const auto& L = shadow_.light[static_cast<size_t>(j)];
      if ((on >> j & 1u) && (L.mode >> 1) == static_cast<uint32_t>(LightKind::Spot) && fs.slot_can(j, LightKind::Spot))
        cand[nc++] = j;
    }
    if (nc == 0) return false;
    const int j = cand[rng_.next() % static_cast<uint64_t>(nc)];
    const auto& L = shadow_.light[static_cast<size_t>(j)];
    const int VF = core_.unit_format().frac;
    const double one = std::ldexp(1.0, F_);
    double s[3] = {static_cast<double>(L.sdir[0]), static_cast<double>(L.sdir[1]), static_cast<double>(L.sdir[2])};
    const double sl = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    if (sl == 0) s[2] = 1;  // a raw zero direction: −L̂·ŝ is 0 wherever P is
    for (double& x : s) x /= sl == 0 ? 1.0 : sl;
    // −L̂·ŝ ≈ cos θ · |ŝ register| · 2^E in VF-bit codes: the cut-off angle of the cos register
    const double full = (sl == 0 ? 1.0 : sl) * std::ldexp(1.0, VF - F_);
    const double cc = std::clamp(static_cast<double>(L.scos) / full, -1.0, 1.0), thc = std::acos(cc);
    const double margin = std::min(0.05, std::ldexp(8.0, -VF) / std::max(1e-3, std::sin(thc)));
    // a perpendicular basis of ŝ
    const double e[3] = {std::fabs(s[0]) < 0.6 ? 1.0 : 0.0, std::fabs(s[0]) < 0.6 ? 0.0 : 1.0, 0.0};
    double u1[3] = {s[1] * e[2] - s[2] * e[1], s[2] * e[0] - s[0] * e[2], s[0] * e[1] - s[1] * e[0]};
    const double ul = std::sqrt(u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]);
    for (double& x : u1) x /= ul;
    const double u2[3] = {s[1] * u1[2] - s[2] * u1[1], s[2] * u1[0] - s[0] * u1[2], s[0] * u1[1] - s[1] * u1[0]};
    const double phi = u(0, 2 * std::acos(-1.0)), d = u(6, 30);
    double th;
    if (cls == 0) th = thc - margin <= 0 ? 0.0 : u(0, thc - margin);
    else if (cls == 1) th = thc + margin >= std::acos(-1.0) ? std::acos(-1.0) : u(thc + margin, std::acos(-1.0));
    else th = thc;
    double dir[3];
    for (int i = 0; i < 3; ++i)
      dir[i] = std::cos(th) * s[i] + std::sin(th) * (std::cos(phi) * u1[i] + std::sin(phi) * u2[i]);
    const int64_t plim = int64_t{1} << (F_ + kPosIntBits), nlim = int64_t{1} << (F_ + 1);
    int64_t p0[3];
    for (int i = 0; i < 3; ++i) {
      p0[i] = std::clamp<int64_t>(L.pos[i] + std::llround(d * dir[i] * one), -plim, plim - 1);
      f.n[i] = std::clamp<int64_t>(std::llround(-dir[i] * one), -nlim, nlim - 1);  // facing the light
    }
    auto in_class = [&](int64_t g) { return cls == 2 ? std::llabs(g) <= 1 : cls == 0 ? g >= 2 : g <= -2; };
    for (int t = 0; t < 64; ++t) {
      for (int i = 0; i < 3; ++i) {
        const int64_t k = t == 0 ? 0 : static_cast<int64_t>(rng_.next() % 5) - 2;
        f.p[i] = std::clamp<int64_t>(p0[i] + k, -plim, plim - 1);
      }
      LightCoreTrace tr;
      (void)core_.eval(shadow_, f, &tr);
      if (in_class(tr.light[static_cast<size_t>(j)].sdl - L.scos)) break;
    }
    return true;
  }

  // Hard cases on the current registers: N = 0, tiny N, P exactly at a light, P far from a light,
  // N·L = 0 exactly / ±1 code, back-facing, H = 0 (L = −V), maximal normal components.
  Fragment hard_fragment(uint64_t k) {
    const int64_t one = int64_t{1} << F_;
    const int64_t nmax = (int64_t{1} << (F_ + 1)) - 1, pmax = (int64_t{1} << (F_ + 7)) - 1;
    const int nl = core_.features().num_lights();
    const auto& L = shadow_.light[static_cast<size_t>(rng_.uniform(0, nl - 1))];
    Fragment f;
    for (int i = 0; i < 3; ++i) f.p[i] = rng_.uniform(-(int64_t{20} << F_), int64_t{20} << F_);
    switch (k) {
      case 0: f.n[0] = f.n[1] = f.n[2] = 0; break;
      case 1: f.n[0] = rng_.uniform(-1, 1), f.n[1] = rng_.uniform(-1, 1), f.n[2] = rng_.uniform(-1, 1); break;
      case 2:
        std::copy(L.pos, L.pos + 3, f.p);  // at the light (d = 0) — for a directional light a plain position
        f.n[2] = one;
        break;
      case 3:
        for (int i = 0; i < 3; ++i) f.p[i] = L.pos[i] >= 0 ? -pmax - 1 : pmax;  // farthest corner
        f.n[0] = one;
        break;
      case 4: case 5: case 6: {  // N ⊥ L (+ −1, 0, +1 code along L): N·L = 0 exactly, just below, just above
        int64_t l[3];
        const int64_t pl[3] = {L.pos[0] - f.p[0], L.pos[1] - f.p[1], L.pos[2] - f.p[2]};
        normalize3(F_, pl, l);
        // N = L × e (a perpendicular), then nudged along L
        const int64_t e[3] = {std::abs(l[0]) < std::abs(l[1]) ? one : 0, std::abs(l[0]) < std::abs(l[1]) ? 0 : one, 0};
        int64_t n[3] = {(l[1] * e[2] - l[2] * e[1]) >> F_, (l[2] * e[0] - l[0] * e[2]) >> F_,
                        (l[0] * e[1] - l[1] * e[0]) >> F_};
        const int64_t dlt = static_cast<int64_t>(k) - 5;
        for (int i = 0; i < 3; ++i) f.n[i] = std::clamp<int64_t>(n[i] + dlt * (l[i] >> (F_ - 2)), -nmax - 1, nmax);
        break;
      }
      case 7: {  // back-facing: N = −(direction to the light)
        const int64_t pl[3] = {L.pos[0] - f.p[0], L.pos[1] - f.p[1], L.pos[2] - f.p[2]};
        int64_t l[3];
        normalize3(F_, pl, l);
        for (int i = 0; i < 3; ++i) f.n[i] = -l[i];
        break;
      }
      case 8:  // maximal components
        for (int i = 0; i < 3; ++i) f.n[i] = (rng_.next() & 1) ? nmax : -nmax - 1;
        break;
      default:  // N along the viewer, P on the axis: H = 0 when L = −V
        f.n[0] = f.n[1] = 0;
        f.n[2] = one;
        f.p[0] = f.p[1] = 0;
        f.p[2] = -rng_.uniform(1, 100) << F_;
    }
    return f;
  }

  // Directed programs (docs/lighting.md §7): each a register program followed by the hard fragments.
  void add_frag(const Fragment& f) {
    check_written(directed_frags_);
    CoreCommand c;
    c.f = f;
    directed_.push_back(c);
    ++directed_frags_;
  }
  void add_writes(const std::vector<RegWrite>& ws) { queue_writes(directed_, ws); }
  // Light base b's attenuation registers: kc raw, kl = kq = 0.
  static void push_att(std::vector<RegWrite>& ws, uint32_t b, uint32_t kc) {
    ws.push_back({b + kReg_light_kc, kc});
    ws.push_back({b + kReg_light_kl, 0});
    ws.push_back({b + kReg_light_kq, 0});
  }
  void build_directed() {
    const int nl = core_.features().num_lights();
    const int64_t one = int64_t{1} << F_;
    // 0. every slot's registers at GL's initial state (a driver's context creation): the passes below change a
    //    slot's kind by its mode word alone
    for (int j = 0; j < nl; ++j) add_writes(light_reset_writes(core_, j));
    // 1. a plain program; every hard fragment kind, several times
    double ga[3] = {0.2, 0.2, 0.2};
    add_writes(global_writes(core_, ga));
    MaterialParams m;
    m.specular[0] = m.specular[1] = m.specular[2] = 0.8;
    m.shininess = 128;
    add_writes(material_writes(core_, m));
    if (core_.features().two_side) add_writes(back_material_writes(core_, m));  // every register a program relies on
    if (core_.features().colour_material) add_writes(colour_material_writes(std::nullopt));
    for (int j = 0; j < nl; ++j) {
      LightParams lp;
      lp.kind = slot_kind(j, static_cast<uint64_t>(j));
      if (*lp.kind == LightKind::Directional) {
        lp.position[0] = 0.3 * j, lp.position[1] = 0.5, lp.position[2] = 1, lp.position[3] = 0;
      } else {
        lp.position[0] = 4.0 * j - 10, lp.position[1] = 5, lp.position[2] = 2, lp.position[3] = 1;
        lp.kc = 1, lp.kl = 0.1, lp.kq = 0.02;
      }
      add_writes(light_writes(core_, j, lp));
    }
    for (int rep = 0; rep < 8; ++rep)
      for (uint64_t k = 0; k < 10; ++k) add_frag(hard_fragment(k));
    // 2. H = 0: a light exactly opposite the viewer (directional L = (0, 0, −1); point light behind P)
    for (int j = 0; j < nl; ++j) {
      LightParams lp;
      lp.kind = slot_kind(j, static_cast<uint64_t>(j));
      if (*lp.kind == LightKind::Directional) {
        lp.position[2] = -1, lp.position[3] = 0;
      } else {
        lp.position[2] = -120, lp.position[3] = 1;
        lp.kc = 0, lp.kl = 1, lp.kq = 0;  // seed 001's 1/(d + K) with K = 0: 1/d
      }
      add_writes(light_writes(core_, j, lp));
    }
    for (int z = 1; z < 60; z += 7) {
      Fragment f;
      f.n[2] = one;
      f.p[2] = -(int64_t{z} << F_);
      add_frag(f);
      f.n[2] = -one;  // back-facing too
      add_frag(f);
    }
    // 2b. N·L exactly 0, one code below, one code above: L̂ = (0, 0, 1) exactly (directional (0, 0, 1);
    //     point light at (0, 0, 10) seen from P = 0), N = (1, 0, δ·2^−F)
    for (int j = 0; j < nl; ++j) {
      LightParams lp;
      lp.kind = slot_kind(j, static_cast<uint64_t>(j));
      lp.position[2] = *lp.kind == LightKind::Directional ? 1 : 10;
      lp.position[3] = *lp.kind == LightKind::Directional ? 0 : 1;
      add_writes(light_writes(core_, j, lp));
    }
    for (int64_t d = -2; d <= 2; ++d) {
      Fragment f;
      f.n[0] = one;
      f.n[2] = d;
      add_frag(f);
    }
    // 3. colour sums far above 1: every colour at its maximum, attenuation at its maximum (tiny kc)
    std::vector<RegWrite> ws;
    const uint32_t cmax = (1u << (F_ + 1)) - 1;
    for (uint32_t c = 0; c < 3; ++c)
      for (uint32_t a : {kReg_global_ambient, kReg_mat_emission, kReg_mat_ambient, kReg_mat_diffuse, kReg_mat_specular})
        ws.push_back({a + c, cmax});
    for (int j = 0; j < nl; ++j) {
      const uint32_t b = static_cast<uint32_t>(j) * kLightStride;
      for (uint32_t c = 0; c < 3; ++c)
        for (uint32_t a : {kReg_light_ambient, kReg_light_diffuse, kReg_light_specular}) ws.push_back({b + a + c, cmax});
      push_att(ws, b, 1);  // kc = 2^-F: 1/q saturates
    }
    add_writes(ws);
    for (uint64_t k = 0; k < 10; ++k) add_frag(hard_fragment(k));
    // 4. q = 0 in hardware (kc = kl = kq = 0 written raw; the host setup would reject it): att saturates
    ws.clear();
    for (int j = 0; j < nl; ++j) {
      const uint32_t b = static_cast<uint32_t>(j) * kLightStride;
      push_att(ws, b, 0);
    }
    add_writes(ws);
    for (uint64_t k = 0; k < 10; ++k) add_frag(hard_fragment(k));
    // 5. every light off (all light colours 0): only emission + a·A remain
    ws.clear();
    for (int j = 0; j < nl; ++j) {
      const uint32_t b = static_cast<uint32_t>(j) * kLightStride;
      for (uint32_t c = 0; c < 3; ++c)
        for (uint32_t a : {kReg_light_ambient, kReg_light_diffuse, kReg_light_specular}) ws.push_back({b + a + c, 0});
    }
    add_writes(ws);
    for (uint64_t k = 0; k < 10; ++k) add_frag(hard_fragment(k));
    // 6. writes to addresses that are no register (ignored) and extremes of n
    add_writes({{0x1FE, 0xFFFFFFFFu}, {0x09, 0x12345678u}, {0x0F, 0xFFFFFFFFu}});
    for (int n : {kNMin, kNMax}) {
      m.shininess = n;
      add_writes(material_writes(core_, m));
      for (uint64_t k = 0; k < 10; ++k) add_frag(hard_fragment(k));
    }
    // 7. modes: every light_model value (reserved bits set too) × every unit (and an absent one) ×
    //    enable patterns; a plain light program with every slot's kinds in turn
    m.shininess = 64;
    for (uint32_t pass = 0; pass < 3; ++pass) {
      for (int j = 0; j < nl; ++j) {
        LightParams lp;
        lp.kind = slot_kind(j, static_cast<uint64_t>(j) + pass);
        lp.position[0] = 2.0 * j - 5, lp.position[1] = 3, lp.position[2] = *lp.kind == LightKind::Directional ? 1 : 4;
        lp.position[3] = *lp.kind == LightKind::Directional ? 0 : 1;
        lp.kc = 0.5, lp.kl = 0.05, lp.kq = 0.01;
        lp.specular[0] = lp.specular[1] = lp.specular[2] = 0.9;
        add_writes(light_writes(core_, j, lp));
      }
      for (uint32_t model = 0; model < 32; model += (pass == 0 ? 1 : 5)) {
        add_writes({{kReg_light_model, model}});
        std::vector<VariantId> us = core_.features().units();
        for (size_t ui = 0; ui <= us.size(); ++ui) {
          if (ui < us.size()) {
            m.unit = us[ui];
            add_writes(material_writes(core_, m));
          } else {
            add_writes({{kReg_mat_unit, 15u}});  // no unit has id 15: specular 0
          }
          for (int pat = 0; pat < 4; ++pat) {
            std::vector<RegWrite> en;
            for (int j = 0; j < nl; ++j) {
              const bool on = pat == 3 || (pat == 1 && j == nl - 1) || (pat == 2 && j % 2 == 0);
              en.push_back({static_cast<uint32_t>(j) * kLightStride + kReg_light_mode,
                            light_mode_word(on, slot_kind(j, static_cast<uint64_t>(j) + pass))});
            }
            add_writes(en);
            for (uint64_t k = 0; k < 3; ++k) add_frag(hard_fragment((k + static_cast<uint64_t>(pat)) % 10));
          }
        }
      }
    }
    // a slot asked for a kind it cannot take (spot where the slot has no spot hardware, kinds 4..7): the light is off
    for (int j = 0; j < nl; ++j)
      add_writes({{static_cast<uint32_t>(j) * kLightStride + kReg_light_mode, (static_cast<uint32_t>(j) % 5 + 3) << 1 | 1u}});
    for (uint64_t k = 0; k < 10; ++k) add_frag(hard_fragment(k));
    build_directed_spot();
    build_directed_low_n();
    build_directed_two_side();
    build_directed_colour_material();
  }
  // 11. colour material (colour_material, docs/lighting.md §3.8): every mode field 0..7 enabled and disabled, the
  //     hard fragments with extreme colours (0, 1.0, the largest code 2 − 2^−F, one channel each), both facings in
  //     the two-sided mode, the separate mode; a material whose registers are far from the colours, every
  //     slot on with a non-zero ambient
  void build_directed_colour_material() {
    if (!core_.features().colour_material) return;
    const int64_t one = int64_t{1} << F_;
    const uint32_t cmax = (2u << F_) - 1, o = static_cast<uint32_t>(one);
    std::vector<RegWrite> ws;
    for (uint32_t c = 0; c < 3; ++c)
      for (uint32_t a : {kReg_mat_emission, kReg_mat_ambient, kReg_mat_diffuse, kReg_mat_specular})
        ws.push_back({a + c, o / 8 + c});
    // every slot on (section 1 left them off), with a non-zero ambient (GL's default is 0: the ambient product
    // a·Ia then shows the colour)
    for (int j = 0; j < core_.features().num_lights(); ++j) {
      LightParams lp;
      lp.kind = slot_kind(j, static_cast<uint64_t>(j));
      lp.position[0] = 1.0 - j, lp.position[1] = 2;
      lp.position[2] = *lp.kind == LightKind::Directional ? 1 : 8;
      lp.position[3] = *lp.kind == LightKind::Directional ? 0 : 1;
      lp.spot_cutoff = *lp.kind == LightKind::Spot ? 90 : 180;
      for (int c = 0; c < 3; ++c) lp.ambient[c] = 0.4 + 0.1 * c;
      const auto lw = light_writes(core_, j, lp);
      ws.insert(ws.end(), lw.begin(), lw.end());
    }
    double ga[3] = {0.5, 1.5, 1.0};
    ModeParams md = default_modes(core_.features());
    md.two_side = md.separate_specular = false;
    auto g = global_writes(core_, ga, md);
    ws.insert(ws.end(), g.begin(), g.end());
    add_writes(ws);
    static constexpr uint32_t kCols[][3] = {{0, 0, 0}, {1u << 30, 1u << 30, 1u << 30}, {~0u, 0, 1}, {0, ~0u, 0}};
    for (uint32_t word = 0; word < 16; ++word) {
      add_writes({{kReg_colour_material, word}});
      for (uint64_t k = 0; k < 10; ++k) {
        Fragment f = hard_fragment(k);
        for (const auto& cs : kCols) {
          for (int i = 0; i < 3; ++i)  // 1 << 30 stands for 1.0, ~0 for the largest code
            f.col[i] = cs[i] == (1u << 30) ? o : cs[i] == ~0u ? cmax : cs[i];
          if (core_.features().two_side) f.back = (k + static_cast<uint64_t>(cs[0] & 3)) % 2 == 1;
          add_frag(f);
        }
      }
    }
    // two-sided and separate with colour material on (ambient and diffuse): facing flips with the colour held
    if (core_.features().two_side || core_.features().separate_specular) {
      md.two_side = core_.features().two_side;
      md.separate_specular = core_.features().separate_specular;
      add_writes({{kReg_light_model, light_model_word(md)},
                  {kReg_colour_material, colour_material_word(true, ColourMaterial::AmbientAndDiffuse)}});
      for (uint64_t k = 0; k < 10; ++k) {
        Fragment f = hard_fragment(k);
        f.col[0] = cmax, f.col[1] = o, f.col[2] = 0;
        for (bool b : {false, true}) {
          f.back = b;
          add_frag(f);
        }
      }
    }
  }
  // 10. two-sided lighting (two_side, docs/lighting.md §3.7): front and back colour banks far apart (the back bank at
  //     its extremes), each hard fragment with the facing bit flipped, in and out of the two-sided mode; N with the
  //     most negative components (−N saturates); the same fragment front and back in a row
  void build_directed_two_side() {
    if (!core_.features().two_side) return;
    const int nl = core_.features().num_lights();
    const int64_t one = int64_t{1} << F_;
    std::vector<RegWrite> ws;
    const uint32_t cmax = (1u << (F_ + 1)) - 1;
    for (uint32_t c = 0; c < 3; ++c) {
      ws.push_back({kReg_back_mat_emission + c, c == 0 ? cmax : 0u});
      ws.push_back({kReg_back_mat_ambient + c, c == 1 ? cmax : static_cast<uint32_t>(one / 4)});
      ws.push_back({kReg_back_mat_diffuse + c, c == 2 ? cmax : static_cast<uint32_t>(one / 3)});
      ws.push_back({kReg_back_mat_specular + c, static_cast<uint32_t>(one / 2 + c)});
      ws.push_back({kReg_mat_emission + c, 0u});
    }
    add_writes(ws);
    for (int j = 0; j < nl; ++j) {
      LightParams lp;
      lp.kind = slot_kind(j, static_cast<uint64_t>(j));
      lp.position[0] = 1, lp.position[1] = 2;
      lp.position[2] = *lp.kind == LightKind::Directional ? 1 : 8;
      lp.position[3] = *lp.kind == LightKind::Directional ? 0 : 1;
      lp.spot_cutoff = *lp.kind == LightKind::Spot ? 90 : 180;
      add_writes(light_writes(core_, j, lp));
    }
    for (uint32_t model : {kModelNormalize | kModelTwoSide, kModelNormalize, kModelTwoSide | kModelPhong,
                           kModelTwoSide | kModelSeparateSpecular | kModelNormalize}) {
      add_writes({{kReg_light_model, model}});
      for (uint64_t k = 0; k < 10; ++k) {
        Fragment f = hard_fragment(k);
        for (bool b : {false, true}) {
          f.back = b;
          add_frag(f);
        }
      }
      Fragment f;  // the most negative normal codes: −N saturates to the largest positive code
      for (int i = 0; i < 3; ++i) f.n[i] = -(int64_t{1} << (F_ + 1));
      f.p[2] = -(int64_t{3} << F_);
      for (bool b : {false, true, true, false}) {
        f.back = b;
        add_frag(f);
      }
      f.n[0] = f.n[1] = 0, f.n[2] = -one;  // a back face seen from behind: −N faces the viewer and the light
      for (bool b : {true, false}) {
        f.back = b;
        add_frag(f);
      }
    }
  }
  // 9. shininess below the units' range (low_shininess, docs/lighting.md §3.5): every n 0..15 with both
  //    reflections, on the hard fragments, near the highlight and on x exactly 0 and below (n = 0: x^0 = 1, also
  //    at x = 0); the materials with shininess 16, 17, 31, 32, 1024 after them, the same probes (the unit's value)
  void build_directed_low_n() {
    if (!core_.features().low_shininess) return;
    const int nl = core_.features().num_lights();
    const int64_t one = int64_t{1} << F_;
    for (int j = 0; j < nl; ++j) {
      LightParams lp;
      lp.kind = slot_kind(j, static_cast<uint64_t>(j));
      lp.position[2] = *lp.kind == LightKind::Directional ? 1 : 10;
      lp.position[3] = *lp.kind == LightKind::Directional ? 0 : 1;
      lp.spot_cutoff = *lp.kind == LightKind::Spot ? 90 : 180;
      lp.spot_direction[2] = -1;
      add_writes(light_writes(core_, j, lp));
    }
    MaterialParams m;
    m.specular[0] = m.specular[1] = m.specular[2] = 1.0;
    const uint32_t models[2] = {kModelNormalize, kModelNormalize | kModelPhong};
    // each material: both reflections on the hard fragments, then with L̂ = (0, 0, 1) and P = 0 the normal
    // (t/16, 0, 1): t = 1..8 near the highlight (x just below 1, where x^n of neighbouring n differ most), t = 16
    // at 45° (R = (1, 0, 0), R·V̂ = 0: x = 0 exactly), t = 24 past it (x < 0 with N·L > 0)
    auto probe = [&](int n) {
      m.shininess = n;
      add_writes(material_writes(core_, m));
      for (uint32_t model : models) {
        add_writes({{kReg_light_model, model}});
        for (uint64_t k = 0; k < 10; ++k) add_frag(hard_fragment(k));
        for (int64_t t : {1, 2, 4, 8, 16, 24}) {
          Fragment f;
          f.n[0] = t * one / 16;
          f.n[2] = one;
          add_frag(f);
        }
      }
    };
    for (int n = 0; n < kNMin; ++n) probe(n);
    // the boundary: n = 16 (and up) goes to the unit, with its own thr and coef (a unit with the chain material's
    // thr = 0 is outside the unit's contract, as random_writes() notes); 16..31 share the chain's low bits, so a
    // decode of "below the units' range" one bit too wide shows at 16, 17 and 31
    for (int n : {16, 17, 31, 32, 1024}) probe(n);
  }
  // 8. spot lights (docs/lighting.md §3.4), on every slot that can be spot, the others off: −L̂·ŝ exactly at the
  //    spot cos register and one code either side (the register written raw from the model's own sdl);
  //    exponent 0 with x = 0 (ŝ perpendicular to L̂: factor 1, and 0 for exponent 1); every exponent bit
  //    pattern of the chain's ends; cutoff 180 (the host's words: factor 1)
  void build_directed_spot() {
    const int nl = core_.features().num_lights();
    std::vector<int> spot;
    for (int j = 0; j < nl; ++j)
      if (core_.features().slot_can(j, LightKind::Spot)) spot.push_back(j);
    if (spot.empty()) return;
    const int64_t one = int64_t{1} << F_;
    auto program = [&](const double pos[3], const double dir[3], double cutoff, int e) {
      std::vector<RegWrite> ws;
      for (int j = 0; j < nl; ++j) {
        if (!core_.features().slot_can(j, LightKind::Spot)) {
          ws.push_back({static_cast<uint32_t>(j) * kLightStride + kReg_light_mode, 0u});
          continue;
        }
        LightParams lp;
        lp.kind = LightKind::Spot;
        for (int i = 0; i < 3; ++i) lp.position[i] = pos[i], lp.spot_direction[i] = dir[i];
        lp.position[3] = 1;
        lp.spot_cutoff = cutoff;
        lp.spot_exponent = e;
        lp.specular[0] = lp.specular[1] = lp.specular[2] = 0.7;
        lp.ambient[0] = lp.ambient[1] = lp.ambient[2] = 0.2;
        const auto lw = light_writes(core_, j, lp);
        ws.insert(ws.end(), lw.begin(), lw.end());
      }
      add_writes(ws);
    };
    auto raw_all = [&](uint32_t reg, uint32_t data) {
      std::vector<RegWrite> ws;
      for (int j : spot) ws.push_back({static_cast<uint32_t>(j) * kLightStride + reg, data});
      add_writes(ws);
    };
    const uint32_t cmask = static_cast<uint32_t>(mask_bits(W_.UF + 2));
    // a light above, pointing down a little off the axis; fragments on the plane z = 0 around it
    const double pos[3] = {1, 2, 10}, down[3] = {0.05, -0.1, -1};
    program(pos, down, 30, 5);
    for (uint64_t k = 0; k < 10; ++k) {
      Fragment f;
      f.n[2] = one;
      f.p[0] = static_cast<int64_t>(k) * (one / 2) - 2 * one;
      f.p[1] = static_cast<int64_t>(k % 3) * one;
      LightCoreTrace t;
      (void)core_.eval(shadow_, f, &t);
      const int64_t sdl = t.light[static_cast<size_t>(spot.front())].sdl;
      for (int64_t d = -1; d <= 1; ++d) {
        raw_all(kReg_light_spot_cos, static_cast<uint32_t>(sdl + d) & cmask);
        add_frag(f);
      }
    }
    // exponent 0 with x = 0: L̂ = (0, 0, 1) exactly (light at (0, 0, 10), P = 0), ŝ = (1, 0, 0): −L̂·ŝ = 0; the
    // cos register 0 (inside at the boundary) and 1 (outside)
    const double above[3] = {0, 0, 10}, side[3] = {1, 0, 0};
    for (int e : {0, 1, 2, 128}) {
      program(above, side, 90, e);
      for (uint32_t c : {0u, 1u}) {
        raw_all(kReg_light_spot_cos, c);
        Fragment f;
        f.n[2] = one;
        add_frag(f);
      }
    }
    // every exponent 0..255 written raw (the chain's bit patterns; GL's range is 0..128), cutoff 90
    program(pos, down, 90, 0);
    for (uint32_t e = 0; e < 256; e += (e < 20 ? 1 : 7)) {
      raw_all(kReg_light_spot_exponent, e);
      Fragment f;
      f.n[2] = one;
      f.p[0] = static_cast<int64_t>(e % 5) * one;
      add_frag(f);
    }
    // cutoff 180 on a spot slot: exponent 0 and the smallest cos (factor 1 everywhere)
    program(pos, down, 180, 0);
    for (uint64_t k = 0; k < 10; ++k) add_frag(hard_fragment(k));
  }

  const LightCore& core_;
  Format f_;
  int F_;
  LightWidths W_;
  LightMode mode_;
  uint64_t count_;
  double write_rate_;
  Rng rng_;
  uint64_t seed_, first_, burst_threshold_;
  uint64_t burst_pending_ = 0;  // 1 + the index whose burst was drawn last
  uint64_t digest_ = 0;
  std::vector<CoreCommand> stream_;
  std::vector<CoreCommand> directed_;
  uint64_t directed_frags_ = 0;
  std::deque<CoreCommand> pending_;
  LightRegs shadow_{};
  std::vector<bool> written_ = std::vector<bool>(size_t{1} << kRegAddrBits);  // addresses written so far
  bool check_due_ = true;
  size_t pos_ = 0;
  uint64_t frags_ = 0, planned_ = 0;
};

}  // namespace shadecore::sim

// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the lighting core through its AXI wrapper rtl/sc_light_axi.v (issue 39): a pins adapter for the
// bare harness (sim/light_bare_main.cpp built with SHADECORE_LIGHT_AXI, target shadecore_light_axi) that gives the
// driver (LightDriveLogic), the monitor (MonitorLogic) and the scoreboard the core-side signals they already use,
// and turns them into AXI transactions with a bus-functional model, checking every response:
//
//   * register writes: a write of the stimulus is presented on AW and W (each VALID raised after its own random
//     delay, held until its handshake, the address's two low bits random: the wrapper ignores them) and counts as
//     taken — the scoreboard's LightCore registers change — at its response's handshake (BVALID && BREADY); the
//     wrapper holds the fragment stream from the write's acceptance to that edge (rtl/sc_light_axi.v);
//   * writes of the bus model's own, racing the fragments (about one per 64 idle cycles of the write channel): the
//     word a register already holds written again (OKAY: the stream stalls until the core drains, no result
//     changes), an address that is no register of the build (SLVERR) and a strobe other than 4'hF (SLVERR);
//   * reads (about one per 16 cycles): a register written before (RDATA must be the last word accepted there) or
//     any address (RRESP OKAY exactly where axi_reg_exists, RDATA 0 with SLVERR);
//   * BREADY, RREADY low with probability --out-stall per cycle, as TREADY of the colour stream;
//   * TLAST: set on a fragment by a hash of its tag (about 1 in 8), checked on its colour; TUSER carries the tag;
//     the pad bits of S TDATA are random (the wrapper ignores them), those of M TDATA must be 0;
//   * AXI's reset rule: while rst_ni is low the wrapper's VALID and READY outputs are low; the bus model drops
//     its transactions in flight and the driver sends what it had not seen taken again.
// Every violation is a protocol error of the scoreboard (the run FAILs). The counts go to the COSIM-RESULT
// line's "axi" object. `--inject tlast | bresp | rdata` (with --inject-at N) corrupts the N-th observed TLAST, BRESP or
// checked RDATA: the self-test that each of those checks can fail (ctest sim.light.axi.selftest_detects_*).
#pragma once

#include <cstdint>
#include <deque>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadecore/light_axi.hpp"
#include "tb_light_logic.hpp"

namespace shadecore::sim {

// A core-side input the driver writes: the value takes effect at commit(), after the edge (as an sc_signal's).
struct AxiVar {
  uint64_t v = 0, pend = 0;
  [[nodiscard]] uint64_t read() const { return v; }
  void write(uint64_t x) { pend = x; }
  void commit() { v = pend; }
};
// A core-side output: refreshed from the wrapper's settled outputs (AxiPins::settled).
struct AxiVal {
  uint64_t v = 0;
  [[nodiscard]] uint64_t read() const { return v; }
};

// Bits [lsb, lsb + w) of a Verilated port: an integer (up to 64 bits) or a VlWide.
template <class T>
void axi_port_set(T& p, int lsb, int w, uint64_t v) {
  if constexpr (std::is_integral_v<T>) {
    const uint64_t m = w >= 64 ? ~uint64_t{0} : (uint64_t{1} << w) - 1;
    p = static_cast<T>((static_cast<uint64_t>(p) & ~(m << lsb)) | ((v & m) << lsb));
  } else {
    for (int i = 0; i < w; ++i) {
      const int b = lsb + i;
      const uint32_t bit = static_cast<uint32_t>((v >> i) & 1u);
      p[static_cast<size_t>(b / 32)] = (p[static_cast<size_t>(b / 32)] & ~(1u << (b % 32))) | (bit << (b % 32));
    }
  }
}
template <class T>
uint64_t axi_port_get(const T& p, int lsb, int w) {
  if constexpr (std::is_integral_v<T>) {
    const uint64_t m = w >= 64 ? ~uint64_t{0} : (uint64_t{1} << w) - 1;
    return (static_cast<uint64_t>(p) >> lsb) & m;
  } else {
    uint64_t v = 0;
    for (int i = 0; i < w; ++i) {
      const int b = lsb + i;
      v |= static_cast<uint64_t>((p[static_cast<size_t>(b / 32)] >> (b % 32)) & 1u) << i;
    }
    return v;
  }
}

// The TLAST a fragment of tag `tag` is sent with (and must come out with).
inline bool axi_tlast_of(uint64_t tag) { return ((static_cast<uint32_t>(tag) * 0x9E3779B1u) >> 29) == 0; }

template <class M>  // the Verilated rtl/sc_light_axi.v (--cc)
struct AxiPins : LightPinOps<AxiPins<M>> {
  // inject / inject_at: the self-test of the bus checks (--inject tlast | bresp | rdata): the inject_at-th colour's
  // TLAST, write response's BRESP or checked read's RDATA is seen corrupted, so the run must FAIL on it.
  AxiPins(M& top, const FeatureSet& fs, int f, uint64_t seed, double stall, const std::string& inject = "",
          uint64_t inject_at = 0)
      : t(top), fs_(fs), rng_(seed * 0xA0761D6478BD642Full + 3), stall_(stall),
        inject_(inject == "tlast" ? 1 : inject == "bresp" ? 2 : inject == "rdata" ? 3 : 0), inject_at_(inject_at) {
    frac = f;
    // each core-side signal's field, by name (config/configs.json light.axi decides the order)
    const char* in_names[] = {"nx", "ny", "nz", "px", "py", "pz", "back", "cr", "cg", "cb"};
    for (int i = 0; i < 10; ++i) {
      lsb_in_[i] = axis_lsb(kAXIS_IN_fields, in_names[i], frac);
      w_in_[i] = axis_field_width(kAXIS_IN_fields, in_names[i], frac);
      if (lsb_in_[i] < 0) throw std::logic_error(std::string("light.axi s_axis has no field ") + in_names[i]);
    }
    const char* out_names[] = {"r", "g", "b", "sr", "sg", "sb"};
    for (int i = 0; i < 6; ++i) {
      lsb_out_[i] = axis_lsb(kAXIS_OUT_fields, out_names[i], frac);
      w_out_[i] = axis_field_width(kAXIS_OUT_fields, out_names[i], frac);
      if (lsb_out_[i] < 0) throw std::logic_error(std::string("light.axi m_axis has no field ") + out_names[i]);
    }
    in_bits_ = axis_bits(kAXIS_IN_fields, frac);
    in_tdata_ = axis_tdata_bits(kAXIS_IN_fields, frac);
    out_bits_ = axis_bits(kAXIS_OUT_fields, frac);
    out_tdata_ = axis_tdata_bits(kAXIS_OUT_fields, frac);
    for (uint32_t w = 0; w < (1u << kRegAddrBits); ++w)
      if (axi_reg_exists(fs, w)) present_.push_back(w);
  }

  M& t;
  static void init(M& top) {
    top.clk_i = 0;
    top.rst_ni = 0;
    top.s_axil_awvalid_i = 0;
    top.s_axil_wvalid_i = 0;
    top.s_axil_arvalid_i = 0;
    top.s_axis_tvalid_i = 0;
    top.m_axis_tready_i = 0;
  }
  // the core-side signals of the README port table (what LightDriveLogic and MonitorLogic use)
  AxiVar rst_n, reg_we, reg_addr, reg_data, in_valid, out_ready;
  AxiVar in_nx, in_ny, in_nz, in_px, in_py, in_pz, in_tag, in_back, in_cr, in_cg, in_cb;
  AxiVal reg_ready, in_ready, out_valid, out_r, out_g, out_b, out_sr, out_sg, out_sb, out_tag;
  int frac = 16;
  int in_bits = 0;  // unused (MonitorLogic::set_in_bits is for the unit)

  // The monitor's per-edge look at the pins (pre-edge values): the bus model's bookkeeping and checks.
  template <class Sb>
  bool observe_state(Sb& sb, uint64_t cycle) {
    for (const auto& e : bench_errors_) sb.error(e, cycle);
    bench_errors_.clear();
    if (!rst_n.v) {
      if (t.s_axil_awready_o || t.s_axil_wready_o || t.s_axil_bvalid_o || t.s_axil_arready_o || t.s_axil_rvalid_o ||
          t.s_axis_tready_o || t.m_axis_tvalid_o)
        sb.error("AXI: a VALID or READY output of the wrapper is high while rst_ni is low", cycle);
      reset_bus();
      return false;
    }
    bool moved = false;
    // AR first: a read accepted at the edge of a write to its address returns the word before that write.
    if (ar_v_ && t.s_axil_arready_o) {
      const auto it = shadow_.find(ar_word_);
      rq_.push_back({ar_word_, axi_reg_exists(fs_, ar_word_), it != shadow_.end(), it != shadow_.end() ? it->second : 0});
      ar_v_ = false;
      ++reads_;
    }
    if (aw_on_) {
      if (aw_v_ && t.s_axil_awready_o) aw_done_ = true, aw_v_ = false;
      if (w_v_ && t.s_axil_wready_o) w_done_ = true, w_v_ = false;
      if (aw_done_ && w_done_) {
        cur_.ok = cur_.strb == 0xF && axi_reg_exists(fs_, cur_.word);
        if (cur_.ok) shadow_[cur_.word] = cur_.data;
        if (cur_.driver) drv_accepted_ = true;
        bq_.push_back(cur_);
        aw_on_ = false;
        ++(cur_.driver ? driver_writes_ : extra_writes_);
      }
    } else if (t.s_axil_awready_o || t.s_axil_wready_o) {
      if (t.s_axil_awready_o != t.s_axil_wready_o) sb.error("AXI: AWREADY and WREADY apart (the wrapper raises them together)", cycle);
    }
    if (t.s_axil_bvalid_o && bready_) {
      if (bq_.empty()) {
        sb.error("AXI: a write response (BVALID) without a write", cycle);
      } else {
        const Wr w = bq_.front();
        bq_.pop_front();
        const unsigned want = w.ok ? 0u : 2u;
        const unsigned bresp = t.s_axil_bresp_o ^ (injected(2) ? 2u : 0u);
        if (bresp != want)
          sb.error("AXI: BRESP " + std::to_string(bresp) + " for a write of address " + std::to_string(w.word) +
                       " (strobe " + std::to_string(w.strb) + "), expected " + std::to_string(want),
                   cycle);
        if (!w.ok) ++slverr_writes_;
        if (w.driver) {
          if (this->in_valid.v && t.s_axis_tready_o) sb.error("fragment accepted at the edge of a register write", cycle);
          sb.on_write(w.word, w.data);
          drv_accepted_ = false;
          moved = true;
        }
      }
    }
    if (t.s_axil_rvalid_o && rready_) {
      if (rq_.empty()) {
        sb.error("AXI: a read response (RVALID) without a read", cycle);
      } else {
        const Rd r = rq_.front();
        rq_.pop_front();
        const unsigned want = r.exists ? 0u : 2u;
        if (t.s_axil_rresp_o != want)
          sb.error("AXI: RRESP " + std::to_string(t.s_axil_rresp_o) + " for address " + std::to_string(r.word) +
                       ", expected " + std::to_string(want),
                   cycle);
        const bool check = r.exists ? r.known : true;
        const uint32_t want_d = r.exists ? r.data : 0u;
        const uint32_t rdata = t.s_axil_rdata_o ^ ((check && injected(3)) ? 1u : 0u);
        if (check && rdata != want_d)
          sb.error("AXI: RDATA " + std::to_string(rdata) + " at address " + std::to_string(r.word) +
                       ", the last word written there is " + std::to_string(want_d),
                   cycle);
        if (check) ++reads_checked_;
        if (!r.exists) ++slverr_reads_;
      }
    }
    if (this->in_valid.v && t.s_axis_tready_o && axi_tlast_of(in_tag.v)) ++tlast_in_;
    if (t.m_axis_tvalid_o && out_ready.v) {
      const bool want = axi_tlast_of(t.m_axis_tuser_o);
      const bool tlast = static_cast<bool>(t.m_axis_tlast_o) != injected(1);
      if (tlast != want)
        sb.error("AXI-Stream: TLAST " + std::to_string(tlast) + " on the colour of tag " +
                     std::to_string(t.m_axis_tuser_o) + ", its fragment had " + std::to_string(want),
                 cycle);
      if (want) ++tlast_out_;
      if (out_tdata_ > out_bits_ && axi_port_get(t.m_axis_tdata_o, out_bits_, out_tdata_ - out_bits_) != 0)
        sb.error("AXI-Stream: M TDATA pad bits not 0", cycle);
    }
    return moved;
  }

  // After the edge: the driver's writes take effect, and the bus model drives the wrapper for the next edge.
  void commit() {
    for (AxiVar* v : {&rst_n, &reg_we, &reg_addr, &reg_data, &in_valid, &out_ready, &in_nx, &in_ny, &in_nz, &in_px, &in_py,
                      &in_pz, &in_tag, &in_back, &in_cr, &in_cg, &in_cb})
      v->commit();
    const bool rst = rst_n.v != 0;
    if (!rst) {
      reset_bus();
    } else {
      if (!aw_on_) {
        if (reg_we.v && !drv_accepted_) {
          start_write({static_cast<uint32_t>(reg_addr.v), static_cast<uint32_t>(reg_data.v), 0xF, true, false});
        } else if (!reg_we.v && chance(1.0 / 64)) {
          start_write(extra_write());
        }
      } else if (cur_.driver && !reg_we.v) {
        bench_errors_.push_back("bench: the driver withdrew a register write presented on AW/W");
      }
      if (aw_on_) {
        if (!aw_done_) aw_wait_ > 0 ? void(--aw_wait_) : void(aw_v_ = true);
        if (!w_done_) w_wait_ > 0 ? void(--w_wait_) : void(w_v_ = true);
      }
      if (!ar_v_ && rq_.empty() && chance(1.0 / 16)) {
        ar_word_ = (!shadow_.empty() && chance(0.5)) ? known_word() : static_cast<uint32_t>(pick(1u << kRegAddrBits));
        ar_v_ = true;
      }
      bready_ = !chance(stall_);
      rready_ = !chance(stall_);
    }
    t.rst_ni = rst;
    t.s_axil_awvalid_i = rst && aw_v_;
    t.s_axil_awaddr_i = (cur_.word << 2) | static_cast<uint32_t>(pick(4));
    t.s_axil_wvalid_i = rst && w_v_;
    t.s_axil_wdata_i = cur_.data;
    t.s_axil_wstrb_i = cur_.strb;
    t.s_axil_bready_i = bready_;
    t.s_axil_arvalid_i = rst && ar_v_;
    t.s_axil_araddr_i = (ar_word_ << 2) | static_cast<uint32_t>(pick(4));
    t.s_axil_rready_i = rready_;
    t.s_axis_tvalid_i = rst && in_valid.v;
    if (in_valid.v) {
      const AxiVar* f[] = {&in_nx, &in_ny, &in_nz, &in_px, &in_py, &in_pz, &in_back, &in_cr, &in_cg, &in_cb};
      for (int i = 0; i < 10; ++i)
        axi_port_set(t.s_axis_tdata_i, lsb_in_[i], w_in_[i], f[i]->v);
      if (in_tdata_ > in_bits_) axi_port_set(t.s_axis_tdata_i, in_bits_, in_tdata_ - in_bits_, rng_());
    }
    t.s_axis_tuser_i = static_cast<std::remove_reference_t<decltype(t.s_axis_tuser_i)>>(in_tag.v);
    t.s_axis_tlast_i = axi_tlast_of(in_tag.v);
    t.m_axis_tready_i = out_ready.v != 0;
  }

  // The wrapper's outputs settled for the coming edge: the core-side outputs the monitor and the driver read.
  void settled() {
    in_ready.v = t.s_axis_tready_o;
    out_valid.v = t.m_axis_tvalid_o;
    out_tag.v = t.m_axis_tuser_o;
    AxiVal* o[] = {&out_r, &out_g, &out_b, &out_sr, &out_sg, &out_sb};
    for (int i = 0; i < 6; ++i)
      o[i]->v = axi_port_get(t.m_axis_tdata_o, lsb_out_[i], w_out_[i]);
    reg_ready.v = t.s_axil_bvalid_o && bready_ && !bq_.empty() && bq_.front().driver;
  }

  [[nodiscard]] nlohmann::json stats() const {
    return {{"driver_writes", driver_writes_}, {"extra_writes", extra_writes_}, {"slverr_writes", slverr_writes_},
            {"reads", reads_}, {"reads_checked", reads_checked_}, {"slverr_reads", slverr_reads_},
            {"tlast_in", tlast_in_}, {"tlast_out", tlast_out_}, {"s_tdata_bits", in_tdata_}, {"m_tdata_bits", out_tdata_}};
  }

 private:
  struct Wr {
    uint32_t word, data;
    uint8_t strb;
    bool driver, ok;
  };
  struct Rd {
    uint32_t word;
    bool exists, known;
    uint32_t data;
  };

  // true exactly once: at the inject_at-th event of the injected kind
  bool injected(int kind) { return inject_ == kind && ++inject_seen_ == inject_at_; }
  bool chance(double p) { return p > 0 && std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < p; }
  uint64_t pick(uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng_); }
  uint32_t known_word() {
    auto it = shadow_.begin();
    std::advance(it, static_cast<long>(pick(shadow_.size())));
    return it->first;
  }
  void start_write(const Wr& w) {
    cur_ = w;
    aw_on_ = true;
    aw_done_ = w_done_ = aw_v_ = w_v_ = false;
    aw_wait_ = chance(0.5) ? 0 : static_cast<int>(pick(4));
    w_wait_ = chance(0.5) ? 0 : static_cast<int>(pick(4));
  }
  // The bus model's own write: a register's word again (no result changes), an address that is no register, or a
  // partial strobe (both SLVERR, nothing written).
  Wr extra_write() {
    const uint64_t k = pick(4);
    if (k < 2 && !shadow_.empty()) {
      const uint32_t w = known_word();
      return {w, shadow_[w], 0xF, false, false};
    }
    if (k == 2 || present_.size() == (1u << kRegAddrBits)) {
      const uint32_t w = present_.empty() ? 0u : present_[pick(present_.size())];
      return {w, shadow_.count(w) ? shadow_[w] : 0u, static_cast<uint8_t>(pick(15)), false, false};
    }
    uint32_t w;
    do w = static_cast<uint32_t>(pick(1u << kRegAddrBits));
    while (axi_reg_exists(fs_, w));
    return {w, static_cast<uint32_t>(rng_()), 0xF, false, false};
  }
  void reset_bus() {
    aw_on_ = aw_v_ = w_v_ = aw_done_ = w_done_ = false;
    drv_accepted_ = false;
    bq_.clear();
    ar_v_ = false;
    rq_.clear();
  }

  FeatureSet fs_;
  std::mt19937_64 rng_;
  double stall_;
  const int inject_;
  const uint64_t inject_at_;
  uint64_t inject_seen_ = 0;
  int lsb_in_[10] = {}, lsb_out_[6] = {}, w_in_[10] = {}, w_out_[6] = {};
  int in_bits_ = 0, in_tdata_ = 0, out_bits_ = 0, out_tdata_ = 0;
  std::vector<uint32_t> present_;
  std::unordered_map<uint32_t, uint32_t> shadow_;  // the last word accepted at each register address
  Wr cur_{0, 0, 0xF, false, false};
  bool aw_on_ = false, aw_v_ = false, w_v_ = false, aw_done_ = false, w_done_ = false;
  int aw_wait_ = 0, w_wait_ = 0;
  bool drv_accepted_ = false;  // the driver's write was accepted; its response not taken yet
  std::deque<Wr> bq_;
  bool bready_ = false, rready_ = false, ar_v_ = false;
  uint32_t ar_word_ = 0;
  std::deque<Rd> rq_;
  std::vector<std::string> bench_errors_;
  uint64_t driver_writes_ = 0, extra_writes_ = 0, slverr_writes_ = 0, reads_ = 0, reads_checked_ = 0, slverr_reads_ = 0;
  uint64_t tlast_in_ = 0, tlast_out_ = 0;
};

}  // namespace shadecore::sim

// SPDX-License-Identifier: Apache-2.0
// shadecore sim — scoreboard: the reference side of the co-simulation. No SystemC in here.
//
// ScoreboardT<Model> is the transaction checker every testbench of this project uses (the specular
// unit, the lighting core); the Model says what a transaction carries and what the RTL must answer:
//   Model::In / Model::Out      the input payload and the output payload (Out has operator!=)
//   Model::expected(in)         the C model's answer for `in` with the state registered BEFORE this edge
//   Model::ready()              whether an input may be accepted yet (state loaded)
//   Model::latency(), latency_min()   the latency bounds for an input accepted now (the lighting
//                               core's depend on its registers: passes, the material's unit)
// The monitor reports, edge by edge, what crossed the ports:
//   on_input()    a transaction accepted: the expected result is computed right here and queued with
//                 its tag, cycle and advance count;
//   state writes  (material / register writes) go to the Model after on_input of the same edge, so an
//                 input accepted at that edge uses the old state;
//   on_output()   a result taken: checked at once against the head of the queue — tag (lost /
//                 duplicated / reordered), value (bit-exact), latency in advancing edges;
//   on_reset()    rst_ni low at this edge: what is still in flight is dropped, as the spec says.
// The queue is a fixed ring (no allocation per transaction). Optionally every output is recorded in
// acceptance order (record()), for a caller that wants the RTL's answers (the scene renderer).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadecore/unit.hpp"

namespace shadecore::sim {

template <class Model>
struct MismatchT : Model::In {
  typename Model::Out expected, got;
  uint32_t tag;
  uint64_t cycle;
};

template <class Model>
class ScoreboardT {
 public:
  using In = typename Model::In;
  using Out = typename Model::Out;

  ScoreboardT(Model model, int show)
      : model_(std::move(model)), show_(show),
        ring_(kCap) {}

  Model& model() { return model_; }
  const Model& model() const { return model_; }

  // Keep every checked output (in order) in `out` — nullptr to stop.
  void record(std::vector<Out>* out) { record_ = out; }

  void on_input(uint32_t tag, const In& in, uint64_t cycle, uint64_t adv) {
    if (!model_.ready()) {
      error(Model::kNotReadyMessage, cycle);
      return;
    }
    if (size_ == kCap) {
      error("more than " + std::to_string(kCap) + " transactions in flight (outputs missing)", cycle);
      return;
    }
    Entry& e = ring_[(head_ + size_) & (kCap - 1)];
    e.tag = tag;
    e.in = in;
    e.expected = model_.expected(in);
    e.cycle = cycle;
    e.adv = adv;
    e.lat_lo = model_.latency_min();
    e.lat_hi = model_.latency();
    ++size_;
    ++accepted_;
  }

  void on_output(uint32_t tag, const Out& got, uint64_t cycle, uint64_t adv) {
    ++outputs_;
    if (size_ == 0) {
      ++unexpected_;
      note_error(cycle);
      if (unexpected_ <= static_cast<uint64_t>(show_))
        std::printf("ERROR cycle %llu: output tag %u with nothing in flight (duplicated or spurious)\n",
                    ull(cycle), tag);
      return;
    }
    const uint32_t off = tag - ring_[head_].tag;  // tags are consecutive in acceptance order
    if (off != 0) {
      note_error(cycle);
      if (off < size_) {
        if (lost_ < static_cast<uint64_t>(show_))
          std::printf("ERROR cycle %llu: %u transaction(s) lost: expected tag %u, got tag %u\n",
                      ull(cycle), off, ring_[head_].tag, tag);
        lost_ += off;
        pop(off);
      } else {
        ++unexpected_;
        if (unexpected_ <= static_cast<uint64_t>(show_))
          std::printf("ERROR cycle %llu: output tag %u not expected (duplicated or reordered; next expected %u)\n",
                      ull(cycle), tag, ring_[head_].tag);
        return;
      }
    }
    const Entry& e = ring_[head_];
    ++checked_;
    if (record_) record_->push_back(got);
    if (got != e.expected) {
      ++mismatches_;
      note_error(cycle);
      if (first_.size() < static_cast<size_t>(show_)) {
        MismatchT<Model> m;
        static_cast<In&>(m) = e.in;
        m.expected = e.expected;
        m.got = got;
        m.tag = e.tag;
        m.cycle = cycle;
        first_.push_back(m);
      }
    }
    const uint64_t lat_adv = adv - e.adv, lat_cyc = cycle - e.cycle;
    // Exactly `latency` advancing edges for one global-enable pipeline; where elastic segments are
    // chained (ENERGY stage, the lighting core) a transaction may close up on the one ahead through
    // bubbles under backpressure, so the contract is the range latency_min..latency.
    if (lat_adv > static_cast<uint64_t>(e.lat_hi) || lat_adv < static_cast<uint64_t>(e.lat_lo)) {
      ++latency_errors_;
      note_error(cycle);
      if (latency_errors_ <= static_cast<uint64_t>(show_))
        std::printf("ERROR cycle %llu: tag %u latency %llu advancing cycles (%llu cycles), spec says %d..%d\n",
                    ull(cycle), tag, ull(lat_adv), ull(lat_cyc), e.lat_lo, e.lat_hi);
    }
    if (lat_cyc < lat_min_) lat_min_ = lat_cyc;
    if (lat_cyc > lat_max_) lat_max_ = lat_cyc;
    pop(1);
  }

  void on_reset() {
    dropped_by_reset_ += size_;
    pop(size_);
  }

  void error(const std::string& what, uint64_t cycle) {
    ++protocol_errors_;
    note_error(cycle);
    if (protocol_errors_ <= static_cast<uint64_t>(show_)) std::printf("ERROR cycle %llu: %s\n", ull(cycle), what.c_str());
  }

  // Transactions accepted but not yet out; at the end of a run they count as lost.
  [[nodiscard]] uint64_t in_flight() const { return size_; }
  void finish() {
    if (size_ != 0) {
      std::printf("ERROR: %u transaction(s) never came out (first tag %u)\n", size_, ring_[head_].tag);
      lost_ += size_;
      pop(size_);
    }
  }

  [[nodiscard]] bool ok() const {
    return mismatches_ == 0 && lost_ == 0 && unexpected_ == 0 && latency_errors_ == 0 && protocol_errors_ == 0;
  }

  // The run's counts and latency range, as both simulators report them in their --json record
  // (docs/cli.md); the caller adds what is its own.
  [[nodiscard]] nlohmann::json counts_json() const {
    return {{"accepted", accepted_},
            {"vectors", checked_},
            {"mismatches", mismatches_},
            {"lost", lost_},
            {"duplicated_or_reordered", unexpected_},
            {"latency_errors", latency_errors_},
            {"protocol_errors", protocol_errors_},
            {"dropped_by_reset", dropped_by_reset_},
            {"latency_min", checked_ ? lat_min_ : 0},
            {"latency_max", lat_max_}};
  }

  uint64_t accepted_ = 0, outputs_ = 0, checked_ = 0, mismatches_ = 0, lost_ = 0, unexpected_ = 0,
           latency_errors_ = 0, protocol_errors_ = 0, dropped_by_reset_ = 0, material_writes_ = 0;
  uint64_t lat_min_ = ~uint64_t{0}, lat_max_ = 0;
  std::vector<MismatchT<Model>> first_;
  // The monitor cycle of the first error of any kind (mismatch, lost, duplicated / reordered, latency,
  // protocol, watchdog); kNoError while there is none. A windowed waveform is cut around it (tb_trace.hpp).
  static constexpr uint64_t kNoError = ~uint64_t{0};
  uint64_t first_error_cycle_ = kNoError;

 protected:
  Model model_;

 private:
  static constexpr uint32_t kCap = 256;  // power of two; more than any pipeline here holds
  struct Entry {
    uint32_t tag;
    In in;
    Out expected;
    uint64_t cycle, adv;
    int lat_lo, lat_hi;
  };
  static unsigned long long ull(uint64_t v) { return static_cast<unsigned long long>(v); }
  void note_error(uint64_t cycle) {
    if (first_error_cycle_ == kNoError) first_error_cycle_ = cycle;
  }
  void pop(uint32_t k) {
    head_ = (head_ + k) & (kCap - 1);
    size_ -= k;
  }

  int show_;
  std::vector<Out>* record_ = nullptr;
  std::vector<Entry> ring_;
  uint32_t head_ = 0, size_ = 0;
};

// ---- the specular unit (rtl/sc_specular.v) -----------------------------------------------------
struct UnitIn {
  int n;         // material the fragment was shaded with
  int64_t code;  // signed input word
};

// Table units (docs/spec.md §9): the model mirrors the table RAM from the observed tab_we_i writes, so
// the expected value uses what the RAM holds at the accepting edge, not what the driver meant to write.
// Testbench convention: a table load starts with a mat_we_i write (n, for the reports) and is complete
// after E table writes; a fragment accepted before that breaks the host rule (no fragments during a
// reload) and is reported as a protocol error.
struct UnitModel {
  using In = UnitIn;
  using Out = uint32_t;
  static constexpr const char* kNotReadyMessage =
      "input accepted before a material was written (or while a table load was in progress)";
  const Unit* unit;
  UnitMaterial mat;
  bool mat_valid = false;
  int table_left = 0;  // table writes still missing from the load in progress
  [[nodiscard]] bool ready() const { return mat_valid && table_left == 0; }
  [[nodiscard]] int latency() const { return unit->latency(); }
  [[nodiscard]] int latency_min() const { return unit->latency_min(); }
  // The functional coverage model's sampler (coverage builds, tb_func_cov.hpp; null otherwise).
  void (*sample)(void* ctx, const UnitMaterial& m, int64_t code) = nullptr;
  void* sample_ctx = nullptr;
  [[nodiscard]] Out expected(const In& in) const {
    if (sample) sample(sample_ctx, mat, in.code);
    return unit->eval(mat, in.code);
  }
  [[nodiscard]] In input(int64_t code) const { return In{mat.n, code}; }
};

using Mismatch = MismatchT<UnitModel>;

class Scoreboard : public ScoreboardT<UnitModel> {
 public:
  Scoreboard(const Unit& unit, int show) : ScoreboardT<UnitModel>(UnitModel{&unit, {}, false}, show) {
    if (unit.entries() > 0) ram_ = std::make_shared<std::vector<uint64_t>>(static_cast<size_t>(unit.entries()), 0);
  }

  void on_material(int n, uint32_t thr, uint32_t coef = 0) {
    model_.mat = UnitMaterial{n, thr, coef};
    model_.mat.tab = ram_;
    model_.mat_valid = true;
    if (ram_) model_.table_left = static_cast<int>(ram_->size());
    ++material_writes_;
  }
  // One table RAM write (rtl/sc_table.v: addresses >= E are ignored).
  void on_table_write(uint32_t addr, uint32_t value, uint32_t delta) {
    ++table_writes_;
    if (!ram_ || addr >= ram_->size()) return;
    (*ram_)[addr] = table_word(model_.unit->format().frac, value, delta);
    if (model_.table_left > 0) --model_.table_left;
  }
  uint64_t table_writes_ = 0;
  void on_input(uint32_t tag, int64_t code, uint64_t cycle, uint64_t adv) {
    ScoreboardT<UnitModel>::on_input(tag, model_.input(code), cycle, adv);
  }

 private:
  std::shared_ptr<std::vector<uint64_t>> ram_;  // mirror of the table RAM (table units only)
};

}  // namespace shadecore::sim

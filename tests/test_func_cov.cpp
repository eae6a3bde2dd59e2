// SPDX-License-Identifier: Apache-2.0
// The lighting core's functional coverage model (shadecore/stimulus/func_cov.hpp, docs/coverage.md "Functional model") on
// the C model alone: the nightly plan's stimulus for each lighting feature set it runs (every cosim_lighting job of
// regress/plans/nightly.json: directed and random, with its count, seed and write rate) is fed through
// LightCore::eval and the model samples each fragment as the harnesses do. Every bin of the model that the RTL's handshake does not decide must be reached — a bin the
// project's stimulus cannot reach is a hole no number of co-simulation shards closes. Misses are named.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadecore/features.hpp"
#include "shadecore/light.hpp"
#include "shadecore/stimulus/func_cov.hpp"
#include "shadecore/stimulus/light_stimulus.hpp"
#include "light_model_run.hpp"

namespace {

using namespace shadecore;

// One cosim_lighting job of a plan: its stimulus through the C model into `cov`.
void run_job(const LightCore& core, sim::LightFuncCov& cov, sim::LightMode mode, uint64_t count, uint64_t seed,
             double write_rate) {
  sim::LightStimulus stim(core, mode, count, seed, write_rate);
  test::model_run(core, stim, [&cov](const LightRegs& r, const Fragment& f, const LightCoreTrace& t, const Colour&) {
    cov.sample(r, f, t);
  });
}

// The bins `cov` has not counted, the handshake bins left out (the RTL's handshake decides them).
std::vector<std::string> missed(const sim::LightFuncCov& cov) {
  std::vector<std::string> out;
  const auto& names = cov.bins().names();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i].rfind("handshake ", 0) != 0 && cov.bins().count(static_cast<int>(i)) == 0) out.push_back(names[i]);
  return out;
}

std::string listed(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += "\n  " + x;
  return s;
}

// The nightly plan (regress/plans/nightly.json): per feature set, every cosim_lighting job of it — directed and
// random, each with its count, seed and write rate, the random ones whole (a sharded job's shards are its
// fragment-index ranges, the same fragments) — reaches every bin of that set's model.
TEST(FuncCovModel, NightlyStimulusReachesEveryBinOnTheCModel) {
  std::ifstream in(std::string(SHADECORE_SOURCE_DIR) + "/regress/plans/nightly.json");
  ASSERT_TRUE(in.good());
  const auto plan = nlohmann::json::parse(in);
  std::map<std::string, std::vector<nlohmann::json>> by_set;
  for (const auto& j : plan["jobs"])
    if (j.value("kind", "") == "cosim_lighting") by_set[j.value("features", "full")].push_back(j);
  ASSERT_GE(by_set.size(), 5u);
  for (const auto& [set, jobs] : by_set) {
    const LightCore core(feature_set_named_or_file(set));
    sim::LightFuncCov cov(core);
    for (const auto& j : jobs) {
      const bool random = j.value("mode", "random") == "random";
      run_job(core, cov, random ? sim::LightMode::Random : sim::LightMode::Directed, j.value("count", uint64_t{10000}),
              j.value("seed", uint64_t{1}), j.value("write_rate", 0.002));
    }
    const auto m = missed(cov);
    EXPECT_TRUE(m.empty()) << set << " (" << jobs.size() << " jobs): " << m.size() << " bin(s) of "
                           << cov.bins().names().size() << " not reached:" << listed(m);
  }
}

// The model can fail: the same set under less stimulus misses bins, and names them (full, its directed list alone:
// the random program's slot kinds and attenuation classes are not all there).
TEST(FuncCovModel, LessStimulusLeavesNamedHoles) {
  const LightCore core(feature_set_named_or_file("full"));
  sim::LightFuncCov cov(core);
  run_job(core, cov, sim::LightMode::Directed, 200, 3301, 0.002);
  const auto m = missed(cov);
  EXPECT_FALSE(m.empty());
  for (const auto& b : m) EXPECT_FALSE(b.empty());
}

// The register port's bins (sampled per edge from the pins, EdgeState::reg): a write held while fragments drain
// counts "waiting" (and "waiting while the output is held" when the consumer stalls the drain), a write taken
// counts "taken", nothing counts in reset or without a write presented.
TEST(FuncCovModel, RegisterPortBinsFollowTheEdge) {
  const LightCore core(feature_set_named_or_file("gl_default"));
  sim::LightFuncCov cov(core);
  const auto& names = cov.bins().names();
  auto count = [&](const std::string& name) {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return cov.bins().count(static_cast<int>(i));
    ADD_FAILURE() << "no bin " << name;
    return 0u;
  };
  const std::string wait = "handshake register write waiting for a drain (reg_we high, reg_ready low)";
  const std::string held = "handshake register write waiting while the output is held (out_valid high, out_ready low)";
  const std::string taken = "handshake register write taken";
  cov.sample_edge(sim::EdgeState{true, false, true, false, true, 0, 0});   // no write presented
  cov.sample_edge(sim::EdgeState{false, false, false, false, true, 3, 1});  // in reset
  EXPECT_EQ(count(wait) + count(held) + count(taken), 0u);
  cov.sample_edge(sim::EdgeState{true, false, false, true, false, 2, 1});   // held, the drain stalled by out_ready
  cov.sample_edge(sim::EdgeState{true, false, false, true, true, 1, 1});    // held, draining
  cov.sample_edge(sim::EdgeState{true, false, false, false, true, 0, 2});   // taken
  EXPECT_EQ(count(wait), 2u);
  EXPECT_EQ(count(held), 1u);
  EXPECT_EQ(count(taken), 1u);
}

}  // namespace

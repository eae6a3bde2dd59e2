// SPDX-License-Identifier: Apache-2.0
// The co-simulation's lighting stimulus (stimulus/include/shadecore/stimulus/light_stimulus.hpp) reaches the
// GL-completeness modes it is meant to draw (issue 19): a random run and a directed run on `full` shade
// fragments with the low-shininess chain (every n 0..15 in directed section 9), with the separate-specular
// mode and a non-zero secondary colour, with spot lights inside their cone, and with colour material in each
// glColorMaterial mode (the fragment colour at its extremes in directed section 11). A stimulus that stopped
// drawing one of them would leave the co-simulation's "0 mismatches" saying nothing about it.
#include <gtest/gtest.h>

#include <set>

#include "shadecore/features.hpp"
#include "shadecore/light.hpp"
#include "shadecore/stimulus/light_stimulus.hpp"

using namespace shadecore;

namespace {
struct Coverage {
  uint64_t frags = 0, low = 0, separate = 0, secondary = 0, spot_in = 0, back_lit = 0;
  std::set<uint32_t> low_n;
  std::set<int> cm_modes;        // colour material modes met (ColourMaterial), with a fragment colour
  std::set<uint32_t> cm_extreme;  // the extreme colour codes met (0, 1.0, the largest) under colour material
};
Coverage run(const LightCore& core, sim::LightMode mode, uint64_t count, uint64_t seed) {
  sim::LightStimulus stim(core, mode, count, seed, 0.01);
  LightRegs regs;
  Coverage cv;
  sim::CoreCommand c;
  while (stim.next(c)) {
    if (c.is_write) {
      regs.write(core.widths(), c.w.addr, c.w.data);
      continue;
    }
    ++cv.frags;
    LightCoreTrace t;
    const Colour out = core.eval(regs, c.f, &t);
    const LightModes md = core.modes(regs);
    if (md.low_n && md.unit >= 0) ++cv.low, cv.low_n.insert(regs.mat_n);
    if (md.separate) ++cv.separate;
    if (md.two_side && c.f.back) ++cv.back_lit;
    if (md.cm_emission || md.cm_ambient || md.cm_diffuse || md.cm_specular) {
      cv.cm_modes.insert(static_cast<int>(regs.colour_material >> 1));
      for (uint32_t x : c.f.col)
        if (x == 0 || x == (1u << core.format().frac) || x == (2u << core.format().frac) - 1) cv.cm_extreme.insert(x);
    }
    if (out.s[0] | out.s[1] | out.s[2]) ++cv.secondary;
    for (const auto& l : t.light)
      if (l.on && l.kind == LightKind::Spot && l.in_cone) ++cv.spot_in;
  }
  return cv;
}
}  // namespace

TEST(LightStimulus, RandomAndDirectedReachTheGlModes) {
  const LightCore core(feature_set_named_or_file("full"));
  const Coverage r = run(core, sim::LightMode::Random, 20000, 7);
  EXPECT_EQ(r.frags, 20000u);
  EXPECT_GT(r.low, r.frags / 20) << "random: too few fragments with shininess below 16";
  EXPECT_GT(r.separate, r.frags / 10) << "random: too few fragments in the separate-specular mode";
  EXPECT_GT(r.secondary, r.frags / 100) << "random: too few non-zero secondary colours";
  EXPECT_GT(r.spot_in, 0u);
  EXPECT_GT(r.back_lit, r.frags / 10) << "random: too few back fragments in the two-sided mode";
  EXPECT_EQ(r.cm_modes.size(), 5u) << "random: a glColorMaterial mode never drawn";
  EXPECT_EQ(r.cm_extreme.size(), 3u) << "random: an extreme fragment colour never drawn";
  const Coverage d = run(core, sim::LightMode::Directed, 0, 3);
  for (uint32_t n = 0; n < static_cast<uint32_t>(kNMin); ++n) EXPECT_TRUE(d.low_n.count(n)) << "directed: shininess " << n;
  EXPECT_GT(d.separate, 0u);
  EXPECT_GT(d.secondary, 0u);
  EXPECT_GT(d.spot_in, 0u);
  EXPECT_GT(d.back_lit, 0u);
  EXPECT_EQ(d.cm_modes.size(), 5u) << "directed: a glColorMaterial mode missing";
  EXPECT_EQ(d.cm_extreme.size(), 3u) << "directed: an extreme fragment colour missing";
}

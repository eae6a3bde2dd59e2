// SPDX-License-Identifier: Apache-2.0
// Tests that feed the co-simulation's lighting stimulus through the C model alone (tests/test_light_stimulus.cpp,
// tests/test_func_cov.cpp): the register writes applied in order, each fragment evaluated with its trace.
#pragma once

#include "shadecore/light.hpp"
#include "shadecore/stimulus/light_stimulus.hpp"

namespace shadecore::test {

// fn(regs, fragment, trace, colour) for every fragment of `stim`, the registers as written before it.
template <class Fn>
void model_run(const LightCore& core, sim::LightStimulus& stim, Fn&& fn) {
  LightRegs regs;
  sim::CoreCommand c;
  while (stim.next(c)) {
    if (c.is_write) {
      regs.write(core.widths(), c.w.addr, c.w.data);
      continue;
    }
    LightCoreTrace t;
    const Colour out = core.eval(regs, c.f, &t);
    fn(static_cast<const LightRegs&>(regs), static_cast<const Fragment&>(c.f), static_cast<const LightCoreTrace&>(t), out);
  }
}

}  // namespace shadecore::test

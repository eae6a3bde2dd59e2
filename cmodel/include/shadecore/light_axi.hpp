// SPDX-License-Identifier: Apache-2.0
// shadecore — the AXI view of the lighting core (rtl/sc_light_axi.v, issue 39; config/configs.json light.axi, generated
// into light_axi_map.hpp): which register addresses a feature set's wrapper answers OKAY, and the AXI4-Stream
// packing of a fragment and of a colour. The wrapper computes the same from the same generated tables
// (rtl/sc_light_axi.vh); the AXI co-simulation (sim/tb_light_axi.hpp) checks every response against this.
#pragma once

#include <cstdint>
#include <string_view>

#include "shadecore/features.hpp"
#include "shadecore/light_axi_map.hpp"
#include "shadecore/light_regs.hpp"

namespace shadecore {

// The capability bits (kAxiNeed_*) a feature set builds globally, and in light slot j.
inline unsigned axi_caps(const FeatureSet& fs) {
  unsigned c = 0;
  if (fs.ambient) c |= 1u << kAxiNeed_ambient;
  if (fs.diffuse) c |= 1u << kAxiNeed_diffuse;
  if (fs.specular) c |= 1u << kAxiNeed_specular;
  if (fs.specular && fs.norm) c |= 1u << kAxiNeed_energy;
  if (fs.colour_material) c |= 1u << kAxiNeed_colour_material;
  if (fs.two_side) c |= 1u << kAxiNeed_two_side;
  return c;
}
inline unsigned axi_slot_caps(const FeatureSet& fs, int j) {
  unsigned c = axi_caps(fs);
  if (fs.slot_can(j, LightKind::PointAtt) || fs.slot_can(j, LightKind::Spot)) c |= 1u << kAxiNeed_attenuation;
  if (fs.slot_can(j, LightKind::Spot)) c |= 1u << kAxiNeed_spot;
  return c;
}

// Register address `word` (byte address / 4) is a register of this build: the wrapper answers OKAY there.
inline bool axi_reg_exists(const FeatureSet& fs, uint32_t word) {
  for (const AxiRegNeeds& r : kAxiRegNeeds) {
    if (!r.per_light) {
      if (word >= r.addr && word < r.addr + static_cast<uint32_t>(r.count)) return (r.needs & ~axi_caps(fs)) == 0;
      continue;
    }
    for (int j = 0; j < fs.num_lights(); ++j) {
      const uint32_t a = r.addr + kLightStride * static_cast<uint32_t>(j);
      if (word >= a && word < a + static_cast<uint32_t>(r.count)) return (r.needs & ~axi_slot_caps(fs, j)) == 0;
    }
  }
  return false;
}

// AXI4-Stream packing: the LSB and the width of field `name` (-1: no such field) and the bits of all fields (before
// the padding to bytes).
template <class Fields>
constexpr int axis_lsb(const Fields& fields, std::string_view name, int frac) {
  int lsb = 0;
  for (const AxisField& f : fields) {
    if (f.name == name) return lsb;
    lsb += axis_width(f.width, frac);
  }
  return -1;
}
template <class Fields>
constexpr int axis_field_width(const Fields& fields, std::string_view name, int frac) {
  for (const AxisField& f : fields)
    if (f.name == name) return axis_width(f.width, frac);
  return -1;
}
template <class Fields>
constexpr int axis_bits(const Fields& fields, int frac) {
  int n = 0;
  for (const AxisField& f : fields) n += axis_width(f.width, frac);
  return n;
}
template <class Fields>
constexpr int axis_tdata_bits(const Fields& fields, int frac) {
  return (axis_bits(fields, frac) + 7) / 8 * 8;
}

}  // namespace shadecore

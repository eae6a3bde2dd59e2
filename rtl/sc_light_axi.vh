// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json (light.axi, light.registers[].needs) by cmake/ShadecoreConfigs.cmake — do not edit
// The AXI view of the lighting core, included inside rtl/sc_light_axi.v (after FRAC): the capability bits a register
// needs (-1: no register at that address) and the AXI4-Stream packing (fields LSB first; TDATA padded to bytes).
localparam integer AXI_NEED_AMBIENT = 0;
localparam integer AXI_NEED_DIFFUSE = 1;
localparam integer AXI_NEED_SPECULAR = 2;
localparam integer AXI_NEED_ENERGY = 3;
localparam integer AXI_NEED_COLOUR_MATERIAL = 4;
localparam integer AXI_NEED_TWO_SIDE = 5;
localparam integer AXI_NEED_ATTENUATION = 6;
localparam integer AXI_NEED_SPOT = 7;
localparam integer AXI_LIGHT_BASE = 32;  // slot 0's first per-light register; slot j at + LIGHT_STRIDE*j
function integer axi_global_needs(input [9-1:0] w);
  begin
    case (w)
      9'd0, 9'd1, 9'd2: axi_global_needs = 1;  // global_ambient
      9'd3: axi_global_needs = 0;  // light_model
      9'd4: axi_global_needs = 4;  // mat_n
      9'd5: axi_global_needs = 4;  // mat_thr
      9'd6: axi_global_needs = 12;  // mat_coef
      9'd7: axi_global_needs = 4;  // mat_unit
      9'd8: axi_global_needs = 16;  // colour_material
      9'd16, 9'd17, 9'd18: axi_global_needs = 1;  // mat_emission
      9'd20, 9'd21, 9'd22: axi_global_needs = 1;  // mat_ambient
      9'd24, 9'd25, 9'd26: axi_global_needs = 2;  // mat_diffuse
      9'd28, 9'd29, 9'd30: axi_global_needs = 4;  // mat_specular
      9'd288, 9'd289, 9'd290: axi_global_needs = 33;  // back_mat_emission
      9'd292, 9'd293, 9'd294: axi_global_needs = 33;  // back_mat_ambient
      9'd296, 9'd297, 9'd298: axi_global_needs = 34;  // back_mat_diffuse
      9'd300, 9'd301, 9'd302: axi_global_needs = 36;  // back_mat_specular
      default: axi_global_needs = -1;
    endcase
  end
endfunction
function integer axi_light_needs(input integer off);  // off = address - AXI_LIGHT_BASE - LIGHT_STRIDE*j
  begin
    case (off)
      0, 1, 2: axi_light_needs = 0;  // light_position
      3: axi_light_needs = 64;  // light_kc
      4, 5, 6: axi_light_needs = 1;  // light_ambient
      7: axi_light_needs = 64;  // light_kl
      8, 9, 10: axi_light_needs = 2;  // light_diffuse
      11: axi_light_needs = 64;  // light_kq
      12, 13, 14: axi_light_needs = 4;  // light_specular
      16: axi_light_needs = 0;  // light_mode
      17, 18, 19: axi_light_needs = 128;  // light_spot_direction
      20: axi_light_needs = 128;  // light_spot_cos
      21: axi_light_needs = 128;  // light_spot_exponent
      default: axi_light_needs = -1;
    endcase
  end
endfunction
localparam integer AXIS_IN_NX_LSB = 0;
localparam integer AXIS_IN_NX_W = FRAC+2;
localparam integer AXIS_IN_NY_LSB = AXIS_IN_NX_LSB + AXIS_IN_NX_W;
localparam integer AXIS_IN_NY_W = FRAC+2;
localparam integer AXIS_IN_NZ_LSB = AXIS_IN_NY_LSB + AXIS_IN_NY_W;
localparam integer AXIS_IN_NZ_W = FRAC+2;
localparam integer AXIS_IN_PX_LSB = AXIS_IN_NZ_LSB + AXIS_IN_NZ_W;
localparam integer AXIS_IN_PX_W = FRAC+8;
localparam integer AXIS_IN_PY_LSB = AXIS_IN_PX_LSB + AXIS_IN_PX_W;
localparam integer AXIS_IN_PY_W = FRAC+8;
localparam integer AXIS_IN_PZ_LSB = AXIS_IN_PY_LSB + AXIS_IN_PY_W;
localparam integer AXIS_IN_PZ_W = FRAC+8;
localparam integer AXIS_IN_BACK_LSB = AXIS_IN_PZ_LSB + AXIS_IN_PZ_W;
localparam integer AXIS_IN_BACK_W = 1;
localparam integer AXIS_IN_CR_LSB = AXIS_IN_BACK_LSB + AXIS_IN_BACK_W;
localparam integer AXIS_IN_CR_W = FRAC+1;
localparam integer AXIS_IN_CG_LSB = AXIS_IN_CR_LSB + AXIS_IN_CR_W;
localparam integer AXIS_IN_CG_W = FRAC+1;
localparam integer AXIS_IN_CB_LSB = AXIS_IN_CG_LSB + AXIS_IN_CG_W;
localparam integer AXIS_IN_CB_W = FRAC+1;
localparam integer AXIS_IN_BITS = AXIS_IN_CB_LSB + AXIS_IN_CB_W;
localparam integer AXIS_IN_TDATA = (AXIS_IN_BITS + 7) / 8 * 8;  // padded to whole bytes
localparam integer AXIS_OUT_R_LSB = 0;
localparam integer AXIS_OUT_R_W = FRAC+1;
localparam integer AXIS_OUT_G_LSB = AXIS_OUT_R_LSB + AXIS_OUT_R_W;
localparam integer AXIS_OUT_G_W = FRAC+1;
localparam integer AXIS_OUT_B_LSB = AXIS_OUT_G_LSB + AXIS_OUT_G_W;
localparam integer AXIS_OUT_B_W = FRAC+1;
localparam integer AXIS_OUT_SR_LSB = AXIS_OUT_B_LSB + AXIS_OUT_B_W;
localparam integer AXIS_OUT_SR_W = FRAC+1;
localparam integer AXIS_OUT_SG_LSB = AXIS_OUT_SR_LSB + AXIS_OUT_SR_W;
localparam integer AXIS_OUT_SG_W = FRAC+1;
localparam integer AXIS_OUT_SB_LSB = AXIS_OUT_SG_LSB + AXIS_OUT_SG_W;
localparam integer AXIS_OUT_SB_W = FRAC+1;
localparam integer AXIS_OUT_BITS = AXIS_OUT_SB_LSB + AXIS_OUT_SB_W;
localparam integer AXIS_OUT_TDATA = (AXIS_OUT_BITS + 7) / 8 * 8;  // padded to whole bytes
localparam [0:0] unused_light_axi = ^{1'b0, AXI_LIGHT_BASE[0], AXI_NEED_AMBIENT[0], AXI_NEED_DIFFUSE[0], AXI_NEED_SPECULAR[0], AXI_NEED_ENERGY[0], AXI_NEED_COLOUR_MATERIAL[0], AXI_NEED_TWO_SIDE[0], AXI_NEED_ATTENUATION[0], AXI_NEED_SPOT[0], AXIS_IN_NX_LSB[0], AXIS_IN_NX_W[0], AXIS_IN_NY_LSB[0], AXIS_IN_NY_W[0], AXIS_IN_NZ_LSB[0], AXIS_IN_NZ_W[0], AXIS_IN_PX_LSB[0], AXIS_IN_PX_W[0], AXIS_IN_PY_LSB[0], AXIS_IN_PY_W[0], AXIS_IN_PZ_LSB[0], AXIS_IN_PZ_W[0], AXIS_IN_BACK_LSB[0], AXIS_IN_BACK_W[0], AXIS_IN_CR_LSB[0], AXIS_IN_CR_W[0], AXIS_IN_CG_LSB[0], AXIS_IN_CG_W[0], AXIS_IN_CB_LSB[0], AXIS_IN_CB_W[0], AXIS_IN_BITS[0], AXIS_IN_TDATA[0], AXIS_OUT_R_LSB[0], AXIS_OUT_R_W[0], AXIS_OUT_G_LSB[0], AXIS_OUT_G_W[0], AXIS_OUT_B_LSB[0], AXIS_OUT_B_W[0], AXIS_OUT_SR_LSB[0], AXIS_OUT_SR_W[0], AXIS_OUT_SG_LSB[0], AXIS_OUT_SG_W[0], AXIS_OUT_SB_LSB[0], AXIS_OUT_SB_W[0], AXIS_OUT_BITS[0], AXIS_OUT_TDATA[0]};

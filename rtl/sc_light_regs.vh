// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
// Register map and light kinds of rtl/sc_light.v (included inside the module; docs/lighting.md §4).
localparam integer MAX_LIGHTS = 8;
localparam integer LIGHT_STRIDE = 32;
localparam integer REG_ADDR_BITS = 9;
localparam integer SPOT_EXP_BITS = 8;
localparam integer LOW_N_BITS = 4;
localparam integer LIGHT_MODEL_BITS = 5;
localparam integer LM_LOCAL_VIEWER = 0;
localparam integer LM_PHONG = 1;
localparam integer LM_NORMALIZE = 2;
localparam integer LM_TWO_SIDE = 3;
localparam integer LM_SEPARATE_SPECULAR = 4;
localparam integer KIND_DIRECTIONAL = 0;
localparam integer KIND_POINT = 1;
localparam integer KIND_POINT_ATT = 2;
localparam integer KIND_SPOT = 3;
localparam [9-1:0] REG_GLOBAL_AMBIENT = 9'd0;
localparam [9-1:0] REG_LIGHT_MODEL = 9'd3;
localparam [9-1:0] REG_MAT_N = 9'd4;
localparam [9-1:0] REG_MAT_THR = 9'd5;
localparam [9-1:0] REG_MAT_COEF = 9'd6;
localparam [9-1:0] REG_MAT_UNIT = 9'd7;
localparam [9-1:0] REG_COLOUR_MATERIAL = 9'd8;
localparam [9-1:0] REG_MAT_EMISSION = 9'd16;
localparam [9-1:0] REG_MAT_AMBIENT = 9'd20;
localparam [9-1:0] REG_MAT_DIFFUSE = 9'd24;
localparam [9-1:0] REG_MAT_SPECULAR = 9'd28;
localparam [9-1:0] REG_LIGHT_POSITION = 9'd32;
localparam [9-1:0] REG_LIGHT_KC = 9'd35;
localparam [9-1:0] REG_LIGHT_AMBIENT = 9'd36;
localparam [9-1:0] REG_LIGHT_KL = 9'd39;
localparam [9-1:0] REG_LIGHT_DIFFUSE = 9'd40;
localparam [9-1:0] REG_LIGHT_KQ = 9'd43;
localparam [9-1:0] REG_LIGHT_SPECULAR = 9'd44;
localparam [9-1:0] REG_LIGHT_MODE = 9'd48;
localparam [9-1:0] REG_LIGHT_SPOT_DIRECTION = 9'd49;
localparam [9-1:0] REG_LIGHT_SPOT_COS = 9'd52;
localparam [9-1:0] REG_LIGHT_SPOT_EXPONENT = 9'd53;
localparam [9-1:0] REG_BACK_MAT_EMISSION = 9'd288;
localparam [9-1:0] REG_BACK_MAT_AMBIENT = 9'd292;
localparam [9-1:0] REG_BACK_MAT_DIFFUSE = 9'd296;
localparam [9-1:0] REG_BACK_MAT_SPECULAR = 9'd300;
// every name above, so that a module using a few of them lints clean (Verilator's unused pattern)
localparam [0:0] unused_light_regs = ^{1'b0, MAX_LIGHTS[0], LIGHT_STRIDE[0], REG_ADDR_BITS[0], SPOT_EXP_BITS[0], LOW_N_BITS[0], LIGHT_MODEL_BITS[0], REG_GLOBAL_AMBIENT, REG_LIGHT_MODEL, REG_MAT_N, REG_MAT_THR, REG_MAT_COEF, REG_MAT_UNIT, REG_COLOUR_MATERIAL, REG_MAT_EMISSION, REG_MAT_AMBIENT, REG_MAT_DIFFUSE, REG_MAT_SPECULAR, REG_LIGHT_POSITION, REG_LIGHT_KC, REG_LIGHT_AMBIENT, REG_LIGHT_KL, REG_LIGHT_DIFFUSE, REG_LIGHT_KQ, REG_LIGHT_SPECULAR, REG_LIGHT_MODE, REG_LIGHT_SPOT_DIRECTION, REG_LIGHT_SPOT_COS, REG_LIGHT_SPOT_EXPONENT, REG_BACK_MAT_EMISSION, REG_BACK_MAT_AMBIENT, REG_BACK_MAT_DIFFUSE, REG_BACK_MAT_SPECULAR, KIND_DIRECTIONAL[0], KIND_POINT[0], KIND_POINT_ATT[0], KIND_SPOT[0], LM_LOCAL_VIEWER[0], LM_PHONG[0], LM_NORMALIZE[0], LM_TWO_SIDE[0], LM_SEPARATE_SPECULAR[0]};

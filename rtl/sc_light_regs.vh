// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
// Register map and light kinds of rtl/sc_light.v (included inside the module; docs/lighting.md §4).
localparam integer MAX_LIGHTS = 8;
localparam integer LIGHT_STRIDE = 16;
localparam integer KIND_DIRECTIONAL = 0;
localparam integer KIND_POINT = 1;
localparam integer KIND_POINT_ATT = 2;
localparam [7:0] REG_GLOBAL_AMBIENT = 8'd0;
localparam [7:0] REG_MAT_N = 8'd4;
localparam [7:0] REG_MAT_THR = 8'd5;
localparam [7:0] REG_MAT_COEF = 8'd6;
localparam [7:0] REG_MAT_EMISSION = 8'd16;
localparam [7:0] REG_MAT_AMBIENT = 8'd20;
localparam [7:0] REG_MAT_DIFFUSE = 8'd24;
localparam [7:0] REG_MAT_SPECULAR = 8'd28;
localparam [7:0] REG_LIGHT_POSITION = 8'd32;
localparam [7:0] REG_LIGHT_KC = 8'd35;
localparam [7:0] REG_LIGHT_AMBIENT = 8'd36;
localparam [7:0] REG_LIGHT_KL = 8'd39;
localparam [7:0] REG_LIGHT_DIFFUSE = 8'd40;
localparam [7:0] REG_LIGHT_KQ = 8'd43;
localparam [7:0] REG_LIGHT_SPECULAR = 8'd44;

// SPDX-License-Identifier: Apache-2.0
// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
// Values of the VARIANT parameter of rtl/sc_specular.v (included inside the module).
localparam integer VARIANT_CS16 = 0;
localparam integer VARIANT_SCHLICK_DIV = 1;
localparam integer VARIANT_SCHLICK_NR = 2;
localparam integer VARIANT_SCHLICK_ITER = 3;
localparam integer VARIANT_CS16_FAITHFUL = 4;
localparam integer VARIANT_CS16_COMPACT = 5;
localparam integer VARIANT_TABLE256 = 6;
localparam integer VARIANT_TABLE256_ENTRIES = 256;
localparam integer VARIANT_TABLE1024 = 7;
localparam integer VARIANT_TABLE1024_ENTRIES = 1024;

// cs16 squaring forms ("squarer" in configs.json; rtl/sc_cs16.v FORM = 1, docs/spec.md §3.4): field
// 0 FORM, 1 SQ_REL_G, 2..5 SQ_A1..SQ_A4, 6..9 SQ_K1..SQ_K4, 10 SQ_COMP of sc_cs16 for a VARIANT (0 for others).
function integer cs16_sq_param(input integer variant, input integer field);
  begin
    cs16_sq_param = 0;
    case (variant)
      VARIANT_CS16_FAITHFUL: case (field) 0: cs16_sq_param = 1; 1: cs16_sq_param = 1; 2: cs16_sq_param = 3; 3: cs16_sq_param = 0; 4: cs16_sq_param = -1; 5: cs16_sq_param = -4; 6: cs16_sq_param = -2; 7: cs16_sq_param = -2; 8: cs16_sq_param = -1; 9: cs16_sq_param = 1; 10: cs16_sq_param = 0; default: cs16_sq_param = 0; endcase
      VARIANT_CS16_COMPACT: case (field) 0: cs16_sq_param = 1; 1: cs16_sq_param = 0; 2: cs16_sq_param = 5; 3: cs16_sq_param = 4; 4: cs16_sq_param = 3; 5: cs16_sq_param = 2; 6: cs16_sq_param = -1; 7: cs16_sq_param = -1; 8: cs16_sq_param = -1; 9: cs16_sq_param = -1; 10: cs16_sq_param = 1; default: cs16_sq_param = 0; endcase
      default: cs16_sq_param = 0;
    endcase
  end
endfunction
// the cycles MREG = 1 adds to a VARIANT (configs.json variants[].mreg_stages; 0: the unit ignores MREG)
function integer variant_mreg_stages(input integer variant);
  begin
    case (variant)
      VARIANT_CS16: variant_mreg_stages = 5;
      VARIANT_SCHLICK_DIV: variant_mreg_stages = 1;
      VARIANT_SCHLICK_NR: variant_mreg_stages = 6;
      VARIANT_CS16_FAITHFUL: variant_mreg_stages = 6;
      VARIANT_CS16_COMPACT: variant_mreg_stages = 6;
      default: variant_mreg_stages = 0;
    endcase
  end
endfunction

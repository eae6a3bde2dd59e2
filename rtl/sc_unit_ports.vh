// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_unit_ports.vh
// Purpose  : the one copy of the port list every specular unit shares (docs/spec.md §4): clock
//            and synchronous active-low reset, the material write, the fragment in and the result
//            out (AXI-Stream style valid/ready). Included INSIDE a unit's port list, as its last
//            entry (`include "sc_unit_ports.vh"), after a parameter list that declares FRAC and
//            TAGW; so there is no include guard. Files that include it: rtl/sc_cs16.v,
//            rtl/sc_schlick_div.v, rtl/sc_schlick_nr.v, rtl/sc_schlick_iter.v, rtl/sc_table.v.
// ============================================================================================
    input  wire              clk_i,
    input  wire              rst_ni,
    // material
    input  wire              mat_we_i,
    input  wire [10:0]       mat_n_i,
    input  wire [FRAC:0]     mat_thr_i,
    // fragment in
    input  wire              in_valid_i,
    output wire              in_ready_o,
    input  wire [FRAC+1:0]   in_cos_i,
    input  wire [TAGW-1:0]   in_tag_i,
    // result out
    output wire              out_valid_o,
    input  wire              out_ready_i,
    output wire [FRAC:0]     out_spec_o,
    output wire [TAGW-1:0]   out_tag_o

#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Formal proofs of the units' control properties (issue 21, docs/formal.md).

Drives yosys + yosys-smtbmc (solver z3) directly; SymbiYosys is not packaged on Debian. A proof is
k-induction: a bounded base case (BMC from reset, N steps) and an induction step of the same N
(`yosys-smtbmc -i`), both must pass; together they prove the properties for every reachable state
(unbounded). Jobs come from config/configs.json (every variant at every named width, sc_energy at every
width, the control primitive alone at several depths).

Abstraction (the default; --no-abstract keeps the datapath): every arithmetic, comparison and shift cell
of 8 bits or more is a cut point (yosys `cutpoint`, see ABSTRACT): its output is a free value in every
cycle. The properties are about control, holding and material registers, none about values, so the
abstracted design has more behaviours than the real one and a proof of it is a proof of the real design
(over-approximation); a counter-example of the abstracted design may be spurious (none was seen).

  scripts/formal.py list
  scripts/formal.py prove JOB [--depth N] [--no-abstract] [--json FILE]
  scripts/formal.py mutant JOB MUTATION [--vcd FILE]    expects a failure with a counter-example VCD
  scripts/formal.py all [--json FILE] [--filter RE]      every job, a summary (docs/formal.md)

Exit status: 0 the expected result (proof passed / mutant failed with a VCD), 1 anything else.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RTL = os.path.join(ROOT, "rtl")
HARNESS = os.path.join(ROOT, "formal", "sc_formal_unit.v")
CTRL_HARNESS = os.path.join(ROOT, "formal", "sc_formal_ctrl.v")
LIGHT_HARNESS = os.path.join(ROOT, "formal", "sc_formal_light.v")
# the AXI wrapper rtl/sc_light_axi.v around the core of a set (docs/formal.md §9)
AXI_HARNESS = os.path.join(ROOT, "formal", "sc_formal_axi.v")
AXI_SETS = ("diffuse", "gl_default")
AXI_CONNECT = [("o_wstate", "dut.w_state_q"), ("o_rbusy", "dut.r_busy_q")]
# The lighting core (docs/formal.md §7): a small and the full feature set. Their Verilog parameters and
# latency come from the CLI (`shadecore light-sweep --json`: FeatureSet::verilog_params, LightCore::latency),
# one source; --shadecore EXE or $SHADECORE names the binary (ctest passes the built one).
LIGHT_SETS = ("diffuse", "gl_default", "full", "tput_l3", "tput_l3x2")
# two small sets of formal/ (feature-set JSON files the CLI reads like a named set): diffuse with three
# directional slots, one and two lanes, so that l_tput_* sees 1..3 passes within a short BMC
LIGHT_FILES = {"tput_l3": os.path.join(ROOT, "formal", "light_tput_l3.json"),
               "tput_l3x2": os.path.join(ROOT, "formal", "light_tput_l3x2.json")}
# BMC depth of the bounded group, from reset. z3's time roughly doubles per step beyond ~12 (l_order's
# any-constant fragment), so these are what fits this 2-core machine (docs/formal.md §7): diffuse (latency 4)
# covers several fragments in flight with stalls and resets. No bounded job for gl_default (latency 21: a
# depth-10 BMC, which reaches no colour, was stopped after 15 min of z3 CPU) nor for full (its 4-step base case
# alone takes ~2 min here; a depth that fits reaches neither a colour nor, after 8 light_mode writes, a
# throughput check); tput_l3 / tput_l3x2 check the multi-pass scheduling instead.
LIGHT_BMC_DEPTH = {"diffuse": 14, "tput_l3": 12, "tput_l3x2": 12}
# Every property is 1-step (or made inductive by a strengthening invariant, docs/formal.md), so a short
# k-induction closes: base case PROOF_DEPTH steps from reset, induction step of the same length.
PROOF_DEPTH = 4
# sc_pipe_ctrl on its own at every DEPTH a unit uses (cs16 7, forms 5, schlick_div F+4, schlick_nr 10,
# table 3, norm 2) and 1
CTRL_DEPTHS = (1, 2, 3, 5, 7, 10, 12, 20, 28)
CTRL_GAPS = ((7, 2), (7, 4), (10, 4))


def load_config():
    with open(os.path.join(ROOT, "config", "configs.json")) as f:
        return json.load(f)


def unit_files(cfg):
    """Every file sc_specular can instantiate (the "rtl" lists of configs.json)."""
    files = list(cfg["rtl"]["sc_specular"]["files"])
    for v in cfg["variants"]:
        files += v["rtl"]
    files += cfg["rtl"]["sc_specular"]["energy"]
    out = []
    for f in files:
        if f not in out:
            out.append(f)
    return out


def latency(variant, frac):
    """Stages in flight of each unit (docs/spec.md §4)."""
    name = variant["name"]
    if name == "cs16":
        return 7
    if "squarer" in variant:
        return 5
    if name in ("schlick_div", "schlick_iter"):
        return frac + 4
    if name == "schlick_nr":
        return 10
    if variant.get("contract") == "table":
        return 3
    raise ValueError("unknown variant " + name)


_LIGHT_CACHE = {}


def shadecore_exe():
    exe = os.environ.get("SHADECORE") or os.path.join(ROOT, "build", "cli", "shadecore")
    return exe


def light_info(fs):
    """verilog_params and latency of feature set fs from `shadecore light-sweep --json`."""
    if fs in _LIGHT_CACHE:
        return _LIGHT_CACHE[fs]
    exe = shadecore_exe()
    if not os.path.exists(exe):
        raise RuntimeError("formal: the lighting jobs need the shadecore CLI (--shadecore EXE or $SHADECORE); "
                           "%s does not exist" % exe)
    d = tempfile.mkdtemp(prefix="sc_light_params_")
    f = os.path.join(d, "s.json")
    subprocess.run([exe, "light-sweep", "--features", LIGHT_FILES.get(fs, fs), "--programs", "1", "--per-program", "1", "--seed", "1",
                    "--json", f], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    j = json.load(open(f))
    shutil.rmtree(d)
    params = {}
    for kv in j["verilog_params"]:
        k, v = kv.split("=")
        params[k] = int(v)
    _LIGHT_CACHE[fs] = dict(params=params, latency=int(j["latency"]), latency_min=int(j["latency_min"]))
    return _LIGHT_CACHE[fs]


def light_files(cfg):
    r = cfg["rtl"]
    files = list(r["sc_light"]["files"]) + list(r["sc_light"]["normalize"]) + list(r["sc_light"]["recip"])
    files += unit_files(cfg)
    out = []
    for f in files:
        if f not in out:
            out.append(f)
    return out


def light_jobs(cfg):
    out = {}
    files = light_files(cfg)
    for fs in LIGHT_SETS:
        # parameters are resolved lazily (the CLI is only needed when a lighting job runs)
        base = dict(top="sc_formal_light", files=files, harness=LIGHT_HARNESS, light=fs)
        out["light.%s" % fs] = dict(base, depth=PROOF_DEPTH, reach=None)
        if fs in LIGHT_BMC_DEPTH:
            out["light_bmc.%s" % fs] = dict(base, depth=LIGHT_BMC_DEPTH[fs], reach=None, bmc_only=True,
                                            defines=["LIGHT_BMC"])
    # diffuse: the count properties made k-inductive by invariants over sc_light's registers (LIGHT_INV)
    out["light_inv.diffuse"] = dict(base, light="diffuse", depth=PROOF_DEPTH, reach=None,
                                    defines=["LIGHT_BMC", "LIGHT_INV"], connect=LIGHT_INV_CONNECT,
                                    keep_asserts="l_no_spurious l_count_bound l_reg_ready_idle i_*")
    # the AXI wrapper (issue 39): its bus properties, the core inside abstracted as above; the core's own l_* are
    # not in this harness (proved on the core's jobs)
    axi_files = list(cfg["rtl"]["sc_light_axi"]["files"]) + [f for f in files if f not in cfg["rtl"]["sc_light_axi"]["files"]]
    for fs in AXI_SETS:
        out["axi.%s" % fs] = dict(top="sc_formal_axi", files=axi_files, harness=AXI_HARNESS, light=fs,
                                  depth=PROOF_DEPTH, reach=None, connect=AXI_CONNECT, keep_asserts="a_* i_*",
                                  # the read-back shadow and the register-existence ROMs (Yosys proc_rom) are cut too:
                                  # z3 ran out of memory (> 14 GB) on their arrays; RDATA enters a real register
                                  extra_cut="cutpoint t:$mem_v2; ",
                                  # z3 (through yosys-smtbmc) did not finish even the 1-step base case of this small
                                  # design (388 cells) in minutes; Yosys's own SAT k-induction proves it in seconds
                                  engine="sat")
    # bounded write latency (AXI_BMC): BMC from reset to the diffuse core's latency + 8
    out["axi_bmc.diffuse"] = dict(out["axi.diffuse"], defines=["AXI_BMC"], keep_asserts="a_b_bounded", bmc_only=True,
                                  depth=LIGHT_BMC_DEPTH["diffuse"])
    return out


# the observation wires of LIGHT_INV (formal/sc_formal_light.v) and the diffuse core's registers they alias
LIGHT_INV_CONNECT = [("o_vf", "dut.vf_q"), ("o_vb", "dut.vb_q"), ("o_hold", "dut.hold_q"), ("o_cnt", "dut.cnt_q"),
                     ("o_ftag", "dut.u_dly_tag.genblk3.g_one.q_q"),
                     ("o_btag", "dut.u_dly_btag.genblk3.g_line.line_q")]


def resolve(job):
    """Fill in a lighting job's parameters (from the CLI)."""
    if "light" in job and "params" not in job:
        info = light_info(job["light"])
        p = dict(info["params"])
        # harness bounds: fragments in flight <= the stage count <= latency(); clocks to an output <= latency()
        p["MAXF"] = info["latency"]
        p["LMAX"] = info["latency"]
        job["params"] = p
        job["reach"] = info["latency"] + 8
    return job


def jobs():
    """name -> dict(top, params, files, depth)."""
    cfg = load_config()
    files = unit_files(cfg)
    out = {}
    for d in CTRL_DEPTHS:
        out["pipe_ctrl.d%d" % d] = dict(top="sc_formal_ctrl", params={"DEPTH": d}, files=["sc_pipe_ctrl.v"],
                                         harness=CTRL_HARNESS, depth=PROOF_DEPTH, reach=d)
    # GAP (the units shared at share 2..4: cs16 7 stages, schlick_nr 10)
    for d, g in CTRL_GAPS:
        out["pipe_ctrl.d%dg%d" % (d, g)] = dict(top="sc_formal_ctrl", params={"DEPTH": d, "GAP": g},
                                                 files=["sc_pipe_ctrl.v"], harness=CTRL_HARNESS,
                                                 depth=PROOF_DEPTH, reach=d)
    for c in cfg["configs"]:
        F, G = c["frac"], c["guard"]
        for v in cfg["variants"]:
            lat = latency(v, F)
            p = {"KIND": 0, "VARIANT": v["id"], "FRAC": F, "GUARD": G, "CUTOFF": 0, "ENERGY": 0}
            out["unit.%s.%s" % (v["name"], c["name"])] = dict(top="sc_formal_unit", params=p, files=files,
                                                             harness=HARNESS, depth=PROOF_DEPTH, reach=lat, drop_ctrl_asserts=True)
        out["norm.%s" % c["name"]] = dict(top="sc_formal_unit",
                                         params={"KIND": 1, "FRAC": F, "GUARD": G}, files=files,
                                         harness=HARNESS, depth=PROOF_DEPTH, reach=2, drop_ctrl_asserts=True)
    dflt = [c for c in cfg["configs"] if c["name"] == cfg["default"]][0]
    F, G = dflt["frac"], dflt["guard"]
    for v in cfg["variants"]:
        lat = latency(v, F)
        p = {"KIND": 0, "VARIANT": v["id"], "FRAC": F, "GUARD": G, "CUTOFF": 0, "ENERGY": 1}
        out["unit_norm.%s.%s" % (v["name"], dflt["name"])] = dict(top="sc_formal_unit", params=p, files=files,
                                                                 harness=HARNESS, depth=PROOF_DEPTH, reach=lat + 2, drop_ctrl_asserts=True)
        if v["name"] == "cs16" or "squarer" in v:
            p = dict(p, ENERGY=0, CUTOFF=1)
            out["unit_sign_clamp.%s.%s" % (v["name"], dflt["name"])] = dict(
                top="sc_formal_unit", params=p, files=files, harness=HARNESS, depth=PROOF_DEPTH, reach=lat, drop_ctrl_asserts=True)
    out.update(light_jobs(cfg))
    return out


def is_long(name):
    """Jobs the default test suite leaves out (ctest label long): the deep control proofs (the popcount of
    pc_count at DEPTH 20 and 28 takes z3 from seconds to minutes), the cs16 forms at the wide width (Yosys
    spends ~20-45 s elaborating sc_square's constant functions there) and the ENERGY = 1 / sign_clamp repeats."""
    if name.startswith("light"):
        # the full set's proof (~5 min) and every bounded job (BMC to depth 8-14: 2-10 min) are long;
        # light.diffuse and light.gl_default take 5-20 s
        return name.endswith(".full") or name.startswith("light_bmc.")
    return (name in ("pipe_ctrl.d20", "pipe_ctrl.d28", "unit.cs16_faithful.wide", "unit.cs16_compact.wide") or
            name.startswith(("unit_norm.", "unit_sign_clamp.")))


# Mutants run by ctest (formal/CMakeLists.txt): mutation -> job whose proof it must break.
CTEST_MUTANTS = [("drop_transfer", "pipe_ctrl.d7"), ("spurious_after_reset", "pipe_ctrl.d7"),
                 ("accept_in_reset", "pipe_ctrl.d7"), ("gap_ignored", "pipe_ctrl.d7g4"),
                 ("release_held", "unit.cs16.default"),
                 ("accept_in_reset", "unit.cs16.default"), ("material_without_we", "unit.cs16.default"),
                 ("material_new_at_write", "unit.cs16.default"), ("release_held", "unit.schlick_div.narrow"),
                 ("iter_accept_in_reset", "unit.schlick_iter.default"),
                 ("iter_release_held", "unit.schlick_iter.default"), ("iter_drop_held", "unit.schlick_iter.default"),
                 ("iter_drop_transfer", "unit.schlick_iter.default"),
                 # the lighting core (docs/formal.md §7.4): each mutant edits a temporary copy of rtl/sc_light.v
                 ("light_accept_in_reset", "light.diffuse"), ("light_write_in_reset", "light.diffuse"),
                 ("light_accept_during_write", "light.diffuse"), ("light_release_held", "light.diffuse"),
                 ("light_release_held", "light.gl_default"),
                 ("light_write_in_flight", "light_bmc.diffuse"), ("light_drop_transfer", "light_bmc.diffuse"),
                 ("light_spurious_after_reset", "light_bmc.diffuse"), ("light_extra_pass", "light_bmc.diffuse"),
                 ("light_lost_output", "light_bmc.diffuse"), ("light_short_pass", "light_bmc.tput_l3"),
                 ("light_extra_pass", "light_bmc.tput_l3x2"),
                 ("light_write_in_flight", "light_inv.diffuse"), ("light_drop_transfer", "light_inv.diffuse"),
                 ("light_spurious_after_reset", "light_inv.diffuse"),
                 # the AXI wrapper (docs/formal.md §9): each mutant edits a temporary copy of rtl/sc_light_axi.v
                 ("axi_bvalid_in_reset", "axi.diffuse"), ("axi_tvalid_in_reset", "axi.diffuse"),
                 ("axi_b_dropped", "axi.diffuse"), ("axi_r_dropped", "axi.diffuse"),
                 ("axi_rdata_changes", "axi.diffuse"), ("axi_second_write", "axi.diffuse"),
                 ("axi_second_read", "axi.diffuse"), ("axi_stream_during_write", "axi.diffuse"),
                 ("axi_aw_without_w", "axi.diffuse"), ("axi_read_late", "axi.diffuse"),
                 ("axi_write_never_answered", "axi_bmc.diffuse")]
# BMC depth of a lighting mutant (default: the job's latency + 8, from reset)
MUTANT_DEPTH = {"light_accept_in_reset": 4, "light_write_in_reset": 4, "light_accept_during_write": 4,
                "axi_bvalid_in_reset": 6, "axi_tvalid_in_reset": 8, "axi_b_dropped": 6, "axi_r_dropped": 6,
                "axi_rdata_changes": 6, "axi_second_write": 6, "axi_second_read": 6, "axi_stream_during_write": 6,
                "axi_aw_without_w": 4, "axi_read_late": 6, "axi_write_never_answered": 14,
                "light_extra_pass": 8,
                # gl_default: a held colour needs a fragment through its 21-edge pipeline first
                ("light_release_held", "light.gl_default"): 28}


# Mutations: (file, exact text, replacement, assertions one of which must fail). Each text must occur
# exactly once in the file, so a mutation cannot silently stop applying when the RTL changes.
MUTATIONS = {
    # a fragment accepted while the output stage is empty and out_ready_i low is lost
    "drop_transfer": ("sc_pipe_ctrl.v", "v_q <= {v_q[DEPTH-2:0], in_valid_i && gap_ok};",
                      "v_q <= {v_q[DEPTH-2:0], in_valid_i && gap_ok && out_ready_i};", ["pc_count"]),
    # the data registers load while the output is held (valid stays, data and tag change)
    "release_held": ("sc_pipe_ctrl.v", "assign en_o        = adv;",
                     "assign en_o        = adv || in_valid_i;", ["u_hold_data", "u_hold_tag"]),
    # in_ready_o no longer low during reset
    "accept_in_reset": ("sc_pipe_ctrl.v", "assign in_ready_o  = rst_ni && adv && gap_ok;",
                        "assign in_ready_o  = adv && gap_ok;", ["pc_ready_reset", "u_ready_reset"]),
    # a fragment accepted while the one ahead is fewer than GAP stages in (the shared multipliers would mix them)
    "gap_ignored": ("sc_pipe_ctrl.v", "assign gap_ok = ~|v_q[GAP-2:0];", "assign gap_ok = 1'b1;", ["pc_gap"]),
    # reset leaves a valid bit set: a valid output nothing was accepted for
    "spurious_after_reset": ("sc_pipe_ctrl.v", "v_q <= {DEPTH{1'b0}};",
                             "v_q <= {{(DEPTH-1){1'b0}}, 1'b1};", ["pc_count", "pc_no_spurious"]),
    # a material write taken without mat_we_i
    "material_without_we": ("sc_cs16.v", "if (mat_we_i) begin\n      mat_n_q   <= mat_n_i;",
                            "if (mat_we_i || in_valid_i) begin\n      mat_n_q   <= mat_n_i;", ["mat_load_n"]),
    # a fragment accepted at a material-write edge gets the new material
    "material_new_at_write": ("sc_cs16.v", "s0_n_q   <= mat_n_q;",
                              "s0_n_q   <= mat_we_i ? mat_n_i : mat_n_q;", ["mat_old_n"]),
    # the iterative unit: accepts in reset / releases a held result / drops an accepted fragment
    "iter_accept_in_reset": ("sc_schlick_iter.v",
                             "assign in_ready_o  = rst_ni && !busy_q && (!out_valid_q || out_ready_i);",
                             "assign in_ready_o  = !busy_q && (!out_valid_q || out_ready_i);",
                             ["it_ready_reset", "u_ready_reset"]),
    "iter_release_held": ("sc_schlick_iter.v", "if (last) begin\n      out_q     <= rnd;",
                          "if (last || in_valid_i) begin\n      out_q     <= rnd;", ["u_hold_data"]),
    # the iterative unit drops a held result (out_valid_q falls without a take)
    "iter_drop_held": ("sc_schlick_iter.v", "end else if (take) begin\n        out_valid_q <= 1'b0;",
                       "end else begin\n        out_valid_q <= 1'b0;", ["it_hold", "it_count", "u_hold_valid"]),
    "iter_drop_transfer": ("sc_schlick_iter.v", "if (accept) begin\n        busy_q <= 1'b1;",
                           "if (accept && in_cos_i[0]) begin\n        busy_q <= 1'b1;", ["it_count"]),
    # the lighting core: accepts in reset / takes a register write in reset / accepts while reg_we_i
    "light_accept_in_reset": ("sc_light.v", "assign in_ready_o  = rst_ni && adv_f && !reg_we_i && gap_ok && ph_ok && !hold_q;",
                              "assign in_ready_o  = adv_f && !reg_we_i && gap_ok && ph_ok && !hold_q;", ["l_in_ready_reset"]),
    "light_write_in_reset": ("sc_light.v", "assign reg_ready_o = rst_ni && (cnt_q == {CNTW{1'b0}});",
                             "assign reg_ready_o = (cnt_q == {CNTW{1'b0}});", ["l_reg_ready_reset"]),
    "light_accept_during_write": ("sc_light.v",
                                  "assign in_ready_o  = rst_ni && adv_f && !reg_we_i && gap_ok && ph_ok && !hold_q;",
                                  "assign in_ready_o  = rst_ni && adv_f && gap_ok && ph_ok && !hold_q;", ["l_in_ready_we"]),
    # a held colour is released (the back advances while the output is held, if in_valid_i)
    "light_release_held": ("sc_light.v", "assign adv_b       = !out_valid_o || out_ready_i;",
                           "assign adv_b       = !out_valid_o || out_ready_i || in_valid_i;",
                           ["l_hold_valid", "l_hold_r", "l_hold_g", "l_hold_b", "l_hold_tag"]),
    # a register write is taken with one fragment still in flight
    "light_write_in_flight": ("sc_light.v", "assign reg_ready_o = rst_ni && (cnt_q == {CNTW{1'b0}});",
                              "assign reg_ready_o = rst_ni && (cnt_q[CNTW-1:1] == 0);", ["l_reg_ready_idle", "i_cnt"]),
    # a pass entering the back is dropped when its tag's top bit is set (the fragment is never output)
    "light_drop_transfer": ("sc_light.v", "else if (adv_b) vb_q <= {vb_q[NB-2:0], b_in_valid};",
                            "else if (adv_b) vb_q <= {vb_q[NB-2:0], b_in_valid && !bk_ftag[FTW-1]};",
                            # a dropped fragment is never taken: accepted − taken grows past the bound too
                            ["l_order", "l_live", "i_cnt", "l_count_bound"]),
    # reset leaves the back's first valid bit set: a colour nothing was accepted for
    "light_spurious_after_reset": ("sc_light.v", "if (!rst_ni) vb_q <= {NB{1'b0}};",
                                   "if (!rst_ni) vb_q <= {{(NB-1){1'b0}}, 1'b1};",
                                   ["l_no_spurious", "l_order", "l_reg_ready_idle", "i_cnt", "i_back0"]),
    # no colour is ever presented (the passes leave the back unseen): every accepted fragment is lost
    "light_lost_output": ("sc_light.v", "assign out_valid_o = vb_q[NB-1] && out_last;",
                          "assign out_valid_o = vb_q[NB-1] && out_last && 1'b0;", ["l_live", "l_count_bound"]),
    # the AXI wrapper (rtl/sc_light_axi.v): BVALID / M TVALID not held low in reset
    "axi_bvalid_in_reset": ("sc_light_axi.v", "assign s_axil_bvalid_o = rst_ni && w_state_q == W_RESP;",
                            "assign s_axil_bvalid_o = w_state_q == W_RESP;", ["a_reset"]),
    "axi_tvalid_in_reset": ("sc_light_axi.v", "assign m_axis_tvalid_o = core_out_valid && rst_ni;",
                            "assign m_axis_tvalid_o = core_out_valid;", ["a_reset"]),
    # a write response withdrawn without BREADY / a read response without RREADY
    "axi_b_dropped": ("sc_light_axi.v", "W_RESP: if (s_axil_bready_i) w_state_q <= W_IDLE;",
                      "W_RESP: w_state_q <= W_IDLE;", ["a_b_hold", "a_w_one", "i_w"]),
    "axi_r_dropped": ("sc_light_axi.v", "end else if (s_axil_rready_i) begin\n      r_busy_q <= 1'b0;",
                      "end else begin\n      r_busy_q <= 1'b0;", ["a_r_hold", "i_r"]),
    # RDATA reloads while the response waits (a new ARVALID while RVALID && !RREADY)
    "axi_rdata_changes": ("sc_light_axi.v", "if (ar_take) r_data_q <= shadow[ar_word];",
                          "if (s_axil_arvalid_i) r_data_q <= shadow[ar_word];", ["a_r_hold"]),
    # a second write / read accepted while the first one's response is outstanding
    "axi_second_write": ("sc_light_axi.v",
                         "wire aw_take = rst_ni && w_state_q == W_IDLE && s_axil_awvalid_i && s_axil_wvalid_i;",
                         "wire aw_take = rst_ni && w_state_q != W_CORE && s_axil_awvalid_i && s_axil_wvalid_i;",
                         ["a_aw_free", "a_w_one", "i_w"]),
    "axi_second_read": ("sc_light_axi.v", "assign s_axil_arready_o = rst_ni && !r_busy_q;",
                        "assign s_axil_arready_o = rst_ni;", ["a_ar_free", "a_r_one", "i_r"]),
    # fragments accepted between a write's acceptance and its response (the ordering rule broken)
    "axi_stream_during_write": ("sc_light_axi.v", "assign stream_open     = w_state_q == W_IDLE;",
                                "assign stream_open     = w_state_q != W_CORE;", ["a_order"]),
    # AWREADY with AWVALID alone (the data not there yet)
    "axi_aw_without_w": ("sc_light_axi.v", "assign s_axil_awready_o = aw_take;",
                         "assign s_axil_awready_o = rst_ni && w_state_q == W_IDLE && s_axil_awvalid_i;", ["a_aw_w"]),
    # a write to an odd register address is never answered (the core takes it, the response never comes)
    "axi_write_never_answered": ("sc_light_axi.v", "W_CORE: if (core_reg_ready) w_state_q <= W_RESP;",
                                 "W_CORE: if (core_reg_ready && !w_addr_q[0]) w_state_q <= W_RESP;", ["a_b_bounded"]),
    # a read not answered while ARVALID stays high after its acceptance (late, and withdrawn)
    "axi_read_late": ("sc_light_axi.v", "assign s_axil_rvalid_o  = rst_ni && r_busy_q;",
                      "assign s_axil_rvalid_o  = rst_ni && r_busy_q && !s_axil_arvalid_i;", ["a_r_next", "a_r_hold"]),
    # a pass is taken as its fragment's last when the input tag's bit 0 is set: fewer passes than lights
    "light_short_pass": ("sc_light.v", "wire pass_last  = (rem_next == {NLT{1'b0}});",
                         "wire pass_last  = (rem_next == {NLT{1'b0}}) || in_tag_i[0];", ["l_tput_busy"]),
    # an accepted fragment with an odd tag takes one issue slot more than its lights need
    "light_extra_pass": ("sc_light.v", "else if (issue) hold_q <= !pass_last;",
                         "else if (issue) hold_q <= !pass_last || (accept && in_tag_i[0]);",
                         ["l_tput_free", "l_no_spurious", "l_order"]),
}


def run(cmd, log, cwd):
    t0 = time.monotonic()
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    with open(log, "w") as f:
        f.write(p.stdout)
    return p.returncode, p.stdout, time.monotonic() - t0


# The abstraction: every arithmetic, comparison and shift cell with an operand or a result of 8 bits or
# more becomes a cut point (its output a free value each cycle). That is the datapath (products, the
# divider's subtractors, clamps, rounding adds); the control (valid bits, the iterative unit's 5-bit
# step counter, the proof counters, all narrower than 8 bits) and every multiplexer, register and
# equality are kept. Cutting a combinational cell only adds behaviours, so what is proved for the
# abstracted design holds for the real one.
_ARITH = "t:$add t:$sub t:$mul t:$neg t:$div t:$mod t:$lt t:$le t:$gt t:$ge t:$shl t:$shr t:$sshl t:$sshr " \
         "t:$shift t:$shiftx"
ABSTRACT = "select -set arith %s; select -set wide r:A_WIDTH>=8 r:B_WIDTH>=8 r:Y_WIDTH>=8; " \
           "cutpoint @arith @wide %%i; " % _ARITH


# The lighting core's abstraction (docs/formal.md §7.3). Before flattening, every instance of the lane
# (L, attenuation, N.L, x), the shade (colour products) and the normaliser modules is a cut point as a
# whole (yosys `cutpoint` on a whole module removes its contents and drives every output from $anyseq).
# After flattening, the wide arithmetic cells (ABSTRACT's list, >= 8 bits) of the units, the register file
# and sc_light.v are cut too, except sc_light.v's narrow ones (< 12 bits: the pass deal's m & (m - 1) over
# the 8 slots, the in-flight counter, the issue gap), the register file's shifts (the mode decode's
# (KINDS >> kind) & 1, the unit selection) and none of the harness's. Every register of sc_light.v
# (valid bits, hold/pass state, tag lines, accumulator, counter), the units' control and the register
# file's registers and mode decode are real.
LIGHT_CUT_MODULES = "*sc_light_lane* *sc_light_shade* *sc_normalize*"
LIGHT_ABSTRACT = ("cutpoint %s; " % LIGHT_CUT_MODULES) + "flatten; " + \
    "select -set arith %s; select -set wide r:A_WIDTH>=8 r:B_WIDTH>=8 r:Y_WIDTH>=8; " \
    "select -set light c:*sc_light.v:*; select -set lightwide r:A_WIDTH>=12 r:B_WIDTH>=12 r:Y_WIDTH>=12; " \
    "select -set harness c:*HARNESS_FILE:*; " \
    "select -set decode c:*sc_light_regfile.v:* t:$shr t:$shl t:$shift t:$shiftx %%u %%u %%u %%i; " \
    "cutpoint @arith @wide %%i @light @lightwide %%d %%d @harness %%d @decode %%d; " % _ARITH


def build_smt2(job, work, rtl_dir, abstract):
    resolve(job)
    if "light" in job:
        return build_light_smt2(job, work, rtl_dir, abstract)
    files = [os.path.join(rtl_dir, f) for f in job["files"]]
    files.append(job["harness"])
    chp = " ".join("-set %s %d" % (k, v) for k, v in job["params"].items())
    # Unit jobs drop the control primitive's own assertions (pc_*): they are proved on sc_pipe_ctrl alone at
    # every DEPTH a unit uses (jobs pipe_ctrl.d*, free inputs, so they hold in any context), and a unit's
    # properties (hold, ready in reset, material, the iterative unit's count) do not rely on them. The
    # popcount behind pc_count is what makes deep pipelines slow for z3 (DEPTH 20: ~17 s CPU).
    drop = "chformal -assert -remove a:src=*sc_pipe_ctrl.v*; " if job.get("drop_ctrl_asserts") else ""
    script = ("read_verilog -formal -DFORMAL -I%s %s; chparam %s %s; prep -top %s; %sflatten; %s"
              "opt_clean; async2sync; dffunmap; stat; write_smt2 -wires %s" %
              (rtl_dir, " ".join(files), chp, job["top"], job["top"], drop,
               ABSTRACT if abstract else "", os.path.join(work, "design.smt2")))
    rc, out, dt = run(["yosys", "-q", "-l", os.path.join(work, "yosys.log"), "-p", script],
                      os.path.join(work, "yosys.out"), work)
    if rc != 0 or re.search(r"implicitly declared", out + open(os.path.join(work, "yosys.log")).read()):
        sys.stderr.write(out)
        raise RuntimeError("yosys failed (or an identifier was implicitly declared), see %s" % work)
    cells = 0
    m = re.findall(r"Number of cells:\s+(\d+)", open(os.path.join(work, "yosys.log")).read())
    if m:
        cells = int(m[-1])
    return dt, cells


def build_light_smt2(job, work, rtl_dir, abstract):
    files = [os.path.join(rtl_dir, f) for f in job["files"]]
    files.append(job["harness"])
    chp = " ".join("-set %s %d" % (k, v) for k, v in job["params"].items())
    defs = " ".join("-D%s" % d for d in job.get("defines", []))
    # the units' own properties (sc_pipe_ctrl, material registers) are proved on the units (jobs unit.*,
    # pipe_ctrl.*): removed here, as the unit jobs remove sc_pipe_ctrl's; only the harness's (labels l_*) are
    # checked. (Cells are selected by name: after flatten a cell's src also names its instance's line.)
    drop = "chformal -assert -remove t:$assert c:l_* %d; "
    if job.get("keep_asserts"):
        # only these are checked (the rest of the bounded group is not inductive)
        keep = " ".join("c:%s" % a for a in job["keep_asserts"].split())
        drop = "chformal -assert -remove t:$assert %s %s; " % (keep, "%u " * (len(job["keep_asserts"].split()) - 1) + "%d")
    conn = job.get("extra_cut", "") + "".join("connect -set %s %s; " % c for c in job.get("connect", []))
    out_cmd = "write_rtlil %s" % os.path.join(work, "design.il") if job.get("engine") == "sat" else \
        "write_smt2 -wires %s" % os.path.join(work, "design.smt2")
    script = ("read_verilog -formal -DFORMAL %s -I%s %s; chparam %s %s; prep -top %s; %s%s"
              "opt_clean; async2sync; dffunmap; stat; %s" %
              (defs, rtl_dir, " ".join(files), chp, job["top"], job["top"],
               (LIGHT_ABSTRACT.replace("HARNESS_FILE", os.path.basename(job["harness"])) if abstract else "flatten; ") + conn,
               drop, out_cmd))
    rc, out, dt = run(["yosys", "-q", "-l", os.path.join(work, "yosys.log"), "-p", script],
                      os.path.join(work, "yosys.out"), work)
    log = open(os.path.join(work, "yosys.log")).read()
    if rc != 0 or re.search(r"implicitly declared", out + log):
        sys.stderr.write(out[-3000:])
        raise RuntimeError("yosys failed (or an identifier was implicitly declared), see %s" % work)
    m = re.findall(r"Number of cells:\s+(\d+)", log)
    return dt, int(m[-1]) if m else 0


def smtbmc(work, depth, induction, vcd=None):
    cmd = ["yosys-smtbmc", "-s", "z3", "--presat", "-t", str(depth)]
    if induction:
        cmd.append("-i")
    if vcd:
        cmd += ["--dump-vcd", vcd]
    cmd.append(os.path.join(work, "design.smt2"))
    rc, out, dt = run(cmd, os.path.join(work, "induction.log" if induction else "bmc.log"), work)
    passed = rc == 0 and "Status: PASSED" in out
    k = None
    m = re.findall(r"Trying induction in step (\d+)", out)
    if induction and passed and m:
        k = depth - int(m[-1])
    failed = re.findall(r"Assert failed in \S+: ([^\s]+)", out)
    return passed, dt, k, out, failed


def sat_induct(work, depth, vcd=None):
    """The `sat` engine (jobs with engine="sat"): Yosys's own SAT-based k-induction on design.il —
    `sat -tempinduct -prove-asserts -set-assumes -maxsteps N`: for k = 1..N the base case from the initial state
    (the harness's f_first assumes reset in cycle 0; registers without an initial value are free there) and the
    induction step of length k. Returns (base_ok, proved, seconds, k, output)."""
    cmd = ["yosys", "-p", "read_rtlil %s; sat -tempinduct -prove-asserts -set-assumes -maxsteps %d%s" %
           (os.path.join(work, "design.il"), depth, " -dump_vcd %s" % vcd if vcd else "")]
    rc, out, dt = run(cmd, os.path.join(work, "sat.log"), work)
    proved = rc == 0 and "Induction step proven: SUCCESS!" in out
    base_ok = "model found for base case: FAIL" not in out and rc == 0
    ks = re.findall(r"Trying induction with length (\d+)", out)
    return base_ok, proved, dt, (int(ks[-1]) if ks and proved else None), out


def prove(name, depth=None, abstract=True, keep=None):
    job = jobs()[name]
    depth = depth or job["depth"]
    work = keep or tempfile.mkdtemp(prefix="sc_formal_")
    os.makedirs(work, exist_ok=True)
    t_y, cells = build_smt2(job, work, RTL, abstract)
    if job.get("engine") == "sat" and job.get("bmc_only"):
        # bounded: the base cases of the induction up to depth (the property is not inductive at the ports alone)
        ok_b, proved, t_s, _, out = sat_induct(work, depth, os.path.join(work, "cex.vcd"))
        reached = [int(x) for x in re.findall(r"Base case for induction length (\d+) proven", out)]
        ok_b = ok_b and (proved or (bool(reached) and max(reached) >= depth))
        res = dict(job=name, top=job["top"], params=job["params"], depth=depth, abstract=abstract, cells=cells,
                   base=ok_b, induction=None, k=None, t_yosys=round(t_y, 2), t_base=round(t_s, 2), t_induction=0.0,
                   failed=[], work=work, engine="yosys sat -tempinduct (base cases)",
                   status=("proved" if proved else "bounded") if ok_b else "base failed")
        if keep is None and ok_b:
            shutil.rmtree(work)
            res["work"] = None
        return res
    if job.get("engine") == "sat":
        ok_b, ok_i, t_s, k, out = sat_induct(work, depth, os.path.join(work, "cex.vcd"))
        res = dict(job=name, top=job["top"], params=job["params"], depth=depth, abstract=abstract, cells=cells,
                   base=ok_b, induction=ok_i, k=k, t_yosys=round(t_y, 2), t_base=round(t_s, 2), t_induction=0.0,
                   failed=[], work=work, engine="yosys sat -tempinduct",
                   status="proved" if ok_i else ("base failed" if not ok_b else "induction failed"))
        if keep is None and ok_i:
            shutil.rmtree(work)
            res["work"] = None
        return res
    ok_b, t_b, _, out_b, fail_b = smtbmc(work, depth, False, os.path.join(work, "base.vcd"))
    ok_i, t_i, k, out_i, fail_i = (False, 0.0, None, "", [])
    if job.get("bmc_only"):
        # the bounded group (docs/formal.md §7): BMC from reset only, reported as bounded
        res = dict(job=name, top=job["top"], params=job["params"], depth=depth, abstract=abstract, cells=cells,
                   base=ok_b, induction=None, k=None, t_yosys=round(t_y, 2), t_base=round(t_b, 2),
                   t_induction=0.0, failed=fail_b, work=work,
                   status=("proved" if proved else "bounded") if ok_b else "base failed")
        if keep is None and ok_b:
            shutil.rmtree(work)
            res["work"] = None
        return res
    if ok_b:
        ok_i, t_i, k, out_i, fail_i = smtbmc(work, depth, True, os.path.join(work, "induction.vcd"))
    res = dict(job=name, top=job["top"], params=job["params"], depth=depth, abstract=abstract, cells=cells,
               base=ok_b, induction=ok_i, k=k, t_yosys=round(t_y, 2), t_base=round(t_b, 2),
               t_induction=round(t_i, 2), failed=fail_b or fail_i, work=work,
               status="proved" if (ok_b and ok_i) else ("base failed" if not ok_b else "induction failed"))
    if keep is None and ok_b and ok_i:
        shutil.rmtree(work)
        res["work"] = None
    return res


def mutant(name, mname, vcd=None, depth=None):
    job = jobs()[name]
    fname, old, new, expect = MUTATIONS[mname]
    work = tempfile.mkdtemp(prefix="sc_mutant_")
    rtl = os.path.join(work, "rtl")
    shutil.copytree(RTL, rtl, ignore=shutil.ignore_patterns("tests", "lint"))
    path = os.path.join(rtl, fname)
    src = open(path).read()
    if src.count(old) != 1:
        raise RuntimeError("mutation %s: the text occurs %d times in rtl/%s (must be once)" %
                           (mname, src.count(old), fname))
    open(path, "w").write(src.replace(old, new))
    if fname not in job["files"]:
        raise RuntimeError("mutation %s: job %s does not use rtl/%s" % (mname, name, fname))
    vcd = vcd or os.path.join(work, "cex.vcd")
    if job.get("engine") == "sat":
        # only the assertions the mutant must break are kept: a base-case failure is then one of them failing
        job = dict(job, keep_asserts=" ".join(expect))
        build_smt2(job, work, rtl, True)
        ok_b, _, t_b, _, out = sat_induct(work, depth or MUTANT_DEPTH.get(mname, 6), vcd)
        have_vcd = os.path.exists(vcd) and "$enddefinitions" in open(vcd).read()
        return dict(job=name, mutation=mname, base=ok_b, failed=[] if ok_b else ["one of " + " ".join(expect)],
                    expected=expect, vcd=vcd if have_vcd else None, t_base=round(t_b, 2),
                    killed=(not ok_b) and have_vcd, work=work)
    build_smt2(job, work, rtl, True)
    # deep enough to reach a held output and the edge after it (the proof depth is what induction needs)
    if depth is None and "light" in job:
        depth = MUTANT_DEPTH.get((mname, name), MUTANT_DEPTH.get(mname, job["reach"]))
    ok_b, t_b, _, out_b, fail_b = smtbmc(work, depth or job["reach"] + 4, False, vcd)
    have_vcd = os.path.exists(vcd) and "$enddefinitions" in open(vcd).read()
    hit = [a for a in fail_b if any(a.endswith(e) or ("." + e) in a or e in a for e in expect)]
    return dict(job=name, mutation=mname, base=ok_b, failed=fail_b, expected=expect, vcd=vcd if have_vcd else None,
                t_base=round(t_b, 2), killed=(not ok_b) and have_vcd and bool(hit), work=work)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    ls = sub.add_parser("list")
    ls.add_argument("--ctest", action="store_true", help="one line per job: NAME quick|long")
    p = sub.add_parser("prove")
    p.add_argument("job")
    p.add_argument("--depth", type=int)
    p.add_argument("--no-abstract", action="store_true")
    p.add_argument("--json")
    p.add_argument("--keep")
    sub.add_parser("mutants", help="the mutant/job pairs ctest runs")
    tb = sub.add_parser("table", help="docs/formal.md's table from the JSON of `all --json`")
    tb.add_argument("json")
    m = sub.add_parser("mutant")
    m.add_argument("job")
    m.add_argument("mutation", choices=sorted(MUTATIONS))
    m.add_argument("--vcd")
    m.add_argument("--depth", type=int)
    a = sub.add_parser("all")
    a.add_argument("--json")
    a.add_argument("--filter", default=".")
    a.add_argument("--no-abstract", action="store_true")
    ap.add_argument("--shadecore", help="the shadecore CLI (lighting jobs: feature-set parameters)")
    args = ap.parse_args()
    if args.shadecore:
        os.environ["SHADECORE"] = args.shadecore

    if args.cmd == "table":
        rows = json.load(open(args.json))
        print("| job | top | parameters | result | base steps | induction k | yosys s | base s | induction s |")
        print("|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            p = " ".join("%s=%s" % kv for kv in r["params"].items())
            print("| `%s` | %s | %s | %s | %d | %s | %.1f | %.1f | %.1f |" % (
                r["job"], r["top"], p, "**proved** (k-induction)" if r["status"] == "proved" else
                ("bounded (BMC, passed)" if r["status"] == "bounded" else r["status"]),
                r["depth"], r["k"], r["t_yosys"], r["t_base"], r["t_induction"]))
        return 0
    if args.cmd == "mutants":
        for m, j in CTEST_MUTANTS:
            # every mutant runs a short BMC (4-28 steps, < 30 s), so none is long, except on the full set
            print(m, j, "long" if j.endswith(".full") else "quick")
        return 0
    if args.cmd == "list":
        for n, j in jobs().items():
            if args.ctest:
                print("%s %s" % (n, "long" if is_long(n) else "quick"))
            else:
                print(n, j["top"], j.get("params", "feature set " + j.get("light", "")), "depth", j["depth"],
                      "bmc" if j.get("bmc_only") else "k-induction", "long" if is_long(n) else "quick")
        return 0
    if args.cmd == "prove":
        if args.job not in jobs():
            print("formal: unknown job %s (scripts/formal.py list)" % args.job, file=sys.stderr)
            return 1
        r = prove(args.job, args.depth, not args.no_abstract, args.keep)
        if args.json:
            json.dump(r, open(args.json, "w"), indent=1)
        print("formal: %s %s: %s (depth %d, induction k=%s, base %.1f s, induction %.1f s%s)" %
              ("PASS" if r["status"] in ("proved", "bounded") else "FAIL", args.job, r["status"], r["depth"], r["k"],
               r["t_base"], r["t_induction"], "" if not r["failed"] else ", failed: " + " ".join(r["failed"])))
        if r["work"]:
            print("formal: logs and VCD in %s" % r["work"])
        return 0 if r["status"] in ("proved", "bounded") else 1
    if args.cmd == "mutant":
        r = mutant(args.job, args.mutation, args.vcd, args.depth)
        vcd_info = "none"
        if r["vcd"]:
            vcd_info = "%s (%d bytes%s)" % (r["vcd"], os.path.getsize(r["vcd"]),
                                          "" if args.vcd else ", removed after the check")
        print("formal: %s mutant %s of %s: %s; failed assertions: %s; counter-example VCD: %s" %
              ("PASS" if r["killed"] else "FAIL", args.mutation, args.job,
               "killed" if r["killed"] else "NOT killed (expected one of %s)" % r["expected"],
               " ".join(r["failed"]) or "none", vcd_info))
        if r["killed"] and not args.vcd:
            shutil.rmtree(r["work"])
        return 0 if r["killed"] else 1
    if args.cmd == "all":
        res = []
        fail = 0
        for n in jobs():
            if not re.search(args.filter, n):
                continue
            r = prove(n, None, not args.no_abstract)
            res.append(r)
            fail |= r["status"] not in ("proved", "bounded")
            print("%-36s %-16s depth %3d k %3s  yosys %5.1f s  base %6.1f s  induction %6.1f s" %
                  (n, r["status"], r["depth"], r["k"], r["t_yosys"], r["t_base"], r["t_induction"]), flush=True)
        if args.json:
            json.dump(res, open(args.json, "w"), indent=1)
        return 1 if fail else 0
    return 1


if __name__ == "__main__":
    sys.exit(main())

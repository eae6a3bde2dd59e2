# SPDX-License-Identifier: Apache-2.0
"""Fast multipliers for the standard-cell flow: a Yosys techmap of `$mul` into Dadda trees.

Yosys 0.23 maps `$mul` to an array of ripple adders (`\\$__arraymul`): on OSU 0.18 um a 22x22 product is a
chain of ~14 XOR cells followed by a ripple carry, 5.8 ns. This module writes, for each distinct `$mul`
shape found in a design (A/B/Y widths, signedness, and whether A and B are the same bits, i.e. a square),
a techmap module that replaces the cell by

  * a bit heap of partial products: AND terms for unsigned operands; for signed operands the sign rows
    are negated bit by bit and the constant they owe is added once (Baugh-Wooley), so no row is
    sign-extended; a square keeps only x_i x_j for i < j, one column up (x_i x_j + x_j x_i = 2 x_i x_j),
    and x_i alone in column 2i (x_i x_i = x_i): about half the bits of a general product;
  * a Dadda reduction of the heap to two rows (full and half adders, column heights 2, 3, 4, 6, 9, ...);
  * a Kogge-Stone prefix adder for the final two rows (log2 depth).

rtl/sc_mul_reg.v (a product with its own pipeline register, the units' MREG) is read as a black box by
signoff.py and mapped here too: the same tree, then the register on the tree's two carry-save rows, then the
Kogge-Stone adder, so the register cuts the product between the tree and the final adder (`mulreg_*`).

Every other adder, subtractor and comparison (Yosys's `$alu`, whose carries are a `$lcu` cell) gets a Kogge-Stone
carry unit instead of Yosys's ripple `_90_lcu` (`LCU_KS`, `write_lcu_map`: one parametric module, tried before
`+/techmap.v`'s because techmap tries implementations in the order of their names).

Only the columns below Y_WIDTH are built (the product is taken modulo 2^Y_WIDTH, as `$mul` defines it).
Each generated module names its shape in `_TECHMAP_FAIL_`, so a cell of any other shape falls through
to Yosys's own map. The RTL stays behavioural (`*`): FPGA flows still infer DSP blocks. The netlist's
equality with the RTL is shown by simulation of the mapped netlist (signoff.py gatesim) and, per shape,
by `fastmul.py --selftest` (Yosys `equiv_make`/`equiv_simple`/`equiv_induct` against `$mul`).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

DADDA = [2, 3, 4, 6, 9, 13, 19, 28, 42, 63, 94, 141, 211, 316]


class Net:
    """A generator of fresh wire names and the assignments that define them."""

    def __init__(self):
        self.n = 0
        self.lines = []

    def wire(self, expr):
        self.n += 1
        name = f"w{self.n}"
        self.lines.append(f"  wire {name} = {expr};")
        return name


def heap_of(m, n, y, signed, square, nprod=1, only=None):
    """Partial-product bit heap: list of columns 0..y-1, each a list of expressions; plus a constant. With nprod > 1
    the heap of the sum of nprod products A[k*m +: m] * B[k*n +: n] (rtl/sc_mul_reg.v N), one constant row."""
    cols = [[] for _ in range(y)]
    const = 0

    def add(col, expr, neg=False):
        nonlocal const
        if col >= y:
            return
        if neg:  # -t*2^k = (~t)*2^k - 2^k
            cols[col].append(f"~({expr})")
            const -= 1 << col
        else:
            cols[col].append(expr)

    def sign(i, w):  # the weight of bit i of a w-bit operand is negative iff signed and i is the MSB
        return signed and i == w - 1

    if square:
        for i in range(m):
            add(2 * i, f"A[{i}]")  # x_i * x_i, the sign bit's square is positive too
            for j in range(i + 1, m):
                add(i + j + 1, f"A[{i}] & A[{j}]", sign(i, m) != sign(j, m))
    else:
        for k in (range(nprod) if only is None else [only]):
            for i in range(m):
                for j in range(n):
                    add(i + j, f"A[{k * m + i}] & B[{k * n + j}]", sign(i, m) != sign(j, n))
    const %= 1 << y
    for k in range(y):
        if const >> k & 1:
            cols[k].append("1'b1")
    return cols


def dadda(net, cols):
    """Reduce the heap to at most two bits per column (Dadda's schedule)."""
    y = len(cols)
    h = max((len(c) for c in cols), default=0)
    targets = [d for d in DADDA if d < h]
    for d in reversed(targets):
        nxt = [[] for _ in range(y)]
        for k in range(y):
            col = cols[k]
            height = len(col) + len(nxt[k])
            i = 0
            while height > d:
                if height - d >= 2 and len(col) - i >= 3:
                    a, b, c = col[i:i + 3]
                    i += 3
                    s = net.wire(f"{a} ^ {b} ^ {c}")
                    nxt[k].append(s)
                    if k + 1 < y:
                        nxt[k + 1].append(net.wire(f"({a} & {b}) | ({a} & {c}) | ({b} & {c})"))
                    height -= 2
                elif len(col) - i >= 2:
                    a, b = col[i:i + 2]
                    i += 2
                    nxt[k].append(net.wire(f"{a} ^ {b}"))
                    if k + 1 < y:
                        nxt[k + 1].append(net.wire(f"{a} & {b}"))
                    height -= 1
                else:
                    break
            nxt[k].extend(col[i:])
        cols = nxt
    return cols


def kogge_stone(net, cols):
    """Add the two remaining rows with a Kogge-Stone prefix adder; returns the sum bits."""
    y = len(cols)
    a = [c[0] if len(c) > 0 else "1'b0" for c in cols]
    b = [c[1] if len(c) > 1 else "1'b0" for c in cols]
    assert all(len(c) <= 2 for c in cols)
    p = [net.wire(f"{a[k]} ^ {b[k]}") for k in range(y)]
    g = [net.wire(f"{a[k]} & {b[k]}") for k in range(y)]
    pp, gg = list(p), list(g)
    dist = 1
    while dist < y:
        ng, np_ = list(gg), list(pp)
        for k in range(dist, y):
            ng[k] = net.wire(f"{gg[k]} | ({pp[k]} & {gg[k - dist]})")
            np_[k] = net.wire(f"{pp[k]} & {pp[k - dist]}")
        gg, pp = ng, np_
        dist *= 2
    return [p[0]] + [net.wire(f"{p[k]} ^ {gg[k - 1]}") for k in range(1, y)]


def shape_cond(aw, bw, yw, signed, square):
    """The techmap condition that a `$mul` cell has this shape."""
    cond = [f"A_WIDTH == {aw}", f"B_WIDTH == {bw}", f"Y_WIDTH == {yw}", f"A_SIGNED == {int(signed)}",
            f"B_SIGNED == {int(signed)}"]
    if square:
        cond.append("_TECHMAP_CONNMAP_A_ == _TECHMAP_CONNMAP_B_")
    return " && ".join(cond)


def shape_body(aw, bw, yw, signed, square):
    """Verilog statements (wires and the Y assignments) of the shape's tree."""
    m, n = min(aw, yw), min(bw, yw)
    net = Net()
    cols = heap_of(m, n, yw, signed, square)
    if all(len(c) == 0 for c in cols):
        bits = ["1'b0"] * yw
    else:
        bits = kogge_stone(net, dadda(net, cols))
    return net.lines + [f"  assign Y[{k}] = {bits[k]};" for k in range(yw)]


def map_module(shapes):
    """Verilog text of the one techmap module for these shapes: a `generate if` chain on SHAPE, the index of the
    first shape the cell matches (Yosys derives the module once per parameter set and builds only the taken
    branch; one module per shape, each tried in turn, cost a full elaboration per shape and cell type)."""
    sel = " :\n    ".join(f"({shape_cond(*sh)}) ? {i}" for i, sh in enumerate(shapes))
    branches = []
    for i, sh in enumerate(shapes):
        aw, bw, yw, signed, square = sh
        kind = "square" if square else "product"
        head = "if" if i == 0 else "else if"
        body = "\n".join("  " + line for line in shape_body(*sh))
        branches.append(f"  // {kind} {aw}x{bw} -> {yw}, {'signed' if signed else 'unsigned'}: Dadda tree + Kogge-Stone adder\n"
                        f"  {head} (SHAPE == {i}) begin : g_shape_{i}\n{body}\n  end")
    return f"""(* techmap_celltype = "$mul" *)
module _sc_fastmul (A, B, Y);
  parameter A_SIGNED = 0;
  parameter B_SIGNED = 0;
  parameter A_WIDTH = 1;
  parameter B_WIDTH = 1;
  parameter Y_WIDTH = 1;
  parameter _TECHMAP_CONNMAP_A_ = 0;
  parameter _TECHMAP_CONNMAP_B_ = 0;
  (* force_downto *) input [A_WIDTH-1:0] A;
  (* force_downto *) input [B_WIDTH-1:0] B;
  (* force_downto *) output [Y_WIDTH-1:0] Y;
  localparam integer SHAPE = {sel} : -1;
  wire _TECHMAP_FAIL_ = SHAPE < 0;
  generate
{chr(10).join(branches)}
  endgenerate
endmodule
"""


# Every `$mul` becomes a black box of this type (same parameters and ports) while Yosys's word-level passes run,
# and a `$mul` again just before write_map's trees replace it (signoff.py): those passes never see the bit heaps.
HIDDEN_NAME = "sc_fastmul_hidden"
HIDDEN_MUL = f"""(* blackbox *)
module {HIDDEN_NAME} #(parameter A_SIGNED = 0, parameter B_SIGNED = 0, parameter A_WIDTH = 1, parameter B_WIDTH = 1,
                       parameter Y_WIDTH = 1) (input [A_WIDTH-1:0] A, input [B_WIDTH-1:0] B, output [Y_WIDTH-1:0] Y);
endmodule
"""

LCU_KS = """// Kogge-Stone carry lookahead for Yosys's $lcu (the carry unit of every $alu: adders, subtractors, comparisons).
// Named _80_* so that techmap tries it before Yosys's ripple _90_lcu (+/techmap.v).
(* techmap_celltype = "$lcu" *)
module _80_sc_lcu_ks (P, G, CI, CO);
  parameter WIDTH = 2;
  (* force_downto *) input [WIDTH-1:0] P, G;
  input CI;
  (* force_downto *) output [WIDTH-1:0] CO;
  localparam integer L = (WIDTH <= 1) ? 1 : $clog2(WIDTH);
  // level l's generate and propagate at [l*WIDTH +: WIDTH]; bit 0 absorbs the carry in
  wire [(L+1)*WIDTH-1:0] g, p;
  assign g[WIDTH-1:0] = {G[WIDTH-1:1], G[0] | (P[0] & CI)};
  assign p[WIDTH-1:0] = P;
  genvar l, i;
  generate
    for (l = 0; l < L; l = l + 1) begin : g_lvl
      for (i = 0; i < WIDTH; i = i + 1) begin : g_bit
        if (i >= (1 << l)) begin : g_op
          assign g[(l+1)*WIDTH + i] = g[l*WIDTH + i] | (p[l*WIDTH + i] & g[l*WIDTH + i - (1 << l)]);
          assign p[(l+1)*WIDTH + i] = p[l*WIDTH + i] & p[l*WIDTH + i - (1 << l)];
        end else begin : g_pass
          assign g[(l+1)*WIDTH + i] = g[l*WIDTH + i];
          assign p[(l+1)*WIDTH + i] = p[l*WIDTH + i];
        end
      end
    end
  endgenerate
  assign CO = g[L*WIDTH +: WIDTH];
endmodule
"""


def write_lcu_map(path):
    """Write the Kogge-Stone $lcu map (signoff.py passes it to techmap with +/techmap.v)."""
    with open(path, "w") as f:
        f.write("// generated by signoff/fastmul.py, do not edit\n" + LCU_KS)


def _prove(label, script):
    """Run one Yosys proof script; print PASS/FAIL with the label (and the tool's tail on failure)."""
    r = subprocess.run(["yosys", "-q", "-p", script], capture_output=True, text=True)
    print(f"fastmul selftest {label}: {'PASS' if r.returncode == 0 else 'FAIL'}")
    if r.returncode != 0:
        print(r.stdout[-2000:] + r.stderr[-2000:])
    return r.returncode == 0


def lcu_selftest(widths=(1, 2, 5, 16, 27, 33)):
    """Prove adders, subtractors and comparisons of these widths equal with the Kogge-Stone $lcu and Yosys's ripple."""
    ok = True
    for w in widths:
        with tempfile.TemporaryDirectory() as tmp:
            src = f"""module t(input [{w-1}:0] a, b, input ci, output [{w}:0] y, output [{w-1}:0] d, output lt, output ge);
  assign y = a + b + ci;
  assign d = a - b;
  assign lt = a < b;
  assign ge = $signed(a) >= $signed(b);
endmodule
"""
            open(os.path.join(tmp, "t.v"), "w").write(src)
            write_lcu_map(os.path.join(tmp, "lcu.v"))
            script = (f"read_verilog {tmp}/t.v; synth -top t -run begin:fine; design -save gold; "
                      f"techmap -map +/techmap.v -map {tmp}/lcu.v; opt; select -assert-none t:$lcu; rename t gate; "
                      f"design -stash g; design -load gold; techmap; opt; rename t gold; design -copy-from g gate; "
                      f"miter -equiv -flatten -make_assert gold gate m; sat -verify -prove-asserts m")
            ok &= _prove(f"Kogge-Stone $lcu width {w}", script)
    return ok


def register_rows(rows, regs):
    """The columns of `rows` with every non-constant bit replaced by a register (appended to regs as (name, bit)):
    a constant bit of a row needs none."""
    rcols = []
    for col in rows:
        rc = []
        for e in col:
            if e in ("1'b0", "1'b1"):
                rc.append(e)
            else:
                regs.append((f"r{len(regs)}", e))
                rc.append(regs[-1][0])
        rcols.append(rc)
    return rcols


def reg_block(regs):
    """Verilog of the registers regs (one bit each), loaded on the enabled edge."""
    decl = "\n".join(f"  reg {r};" for r, _ in regs)
    load = "\n".join(f"      {r} <= {e};" for r, e in regs)
    return f"""{decl}
  always @(posedge clk_i) begin
    if (en_i) begin
{load}
    end
  end"""


def registered_tree(heap, pw):
    """The tree | register | adder of a bit heap (pw columns): (tree lines, [(register, expression)], adder lines,
    sum bits). The register holds the tree's two carry-save rows."""
    net = Net()
    rows = dadda(net, heap)
    tree = list(net.lines)
    regs = []
    rcols = register_rows(rows, regs)
    net.lines = []
    bits = kogge_stone(net, rcols) if any(rcols) else ["1'b0"] * pw
    return tree, regs, net.lines, bits


def registered_body2(heaps, pw, out):
    """LAT = 2: each heap (one product's) reduced to two carry-save rows | register | every registered row reduced
    to two and added | register (out straight from it)."""
    net = Net()
    regs, cols2 = [], [[] for _ in range(pw)]
    for heap in heaps:
        for k, col in enumerate(register_rows(dadda(net, heap), regs)):
            cols2[k].extend(col)
    tree1 = list(net.lines)
    net.lines = []
    bits = kogge_stone(net, dadda(net, cols2)) if any(cols2) else ["1'b0"] * pw
    return f"""{chr(10).join(tree1)}
{reg_block(regs)}
{chr(10).join(net.lines)}
  reg [{pw - 1}:0] s_q;
  always @(posedge clk_i) begin
    if (en_i) s_q <= {{{", ".join(bits[k] for k in reversed(range(pw)))}}};
  end
  assign {out} = s_q;"""


def registered_body(heap, pw, out):
    """Verilog statements of registered_tree: the tree, the registers (clk_i, en_i), the adder, out[k] assigned."""
    tree, regs, adder, bits = registered_tree(heap, pw)
    asg = "\n".join(f"  assign {out}[{k}] = {bits[k]};" for k in range(pw))
    return f"""{chr(10).join(tree)}
{reg_block(regs)}
{chr(10).join(adder)}
{asg}"""


def mulreg_module_for(aw, bw, pw, signed, square, cw, index, nprod=1, lat=1):
    """Verilog of one techmap module for an rtl/sc_mul_reg.v instance of this shape: the partial-product
    tree (of the nprod products, N; with the addend's bits as one more row when cw > 0, ADD = 1), the register
    (enable en_i) on its two carry-save rows, then the Kogge-Stone adder."""
    if nprod > 1 and (aw > pw or bw > pw):
        raise ValueError(f"sc_mul_reg N = {nprod} with an operand wider than the product ({aw}, {bw} > {pw})")
    m, n = min(aw, pw), min(bw, pw)
    heap = heap_of(m, n, pw, signed, square, nprod)
    for k in range(min(cw, pw)):
        heap[k].append(f"C[{k}]")
    if lat == 2:
        if square:
            raise ValueError("sc_mul_reg LAT = 2 of a square is not mapped")
        heaps = [heap_of(m, n, pw, signed, False, nprod, only=k) for k in range(nprod)]
        for k in range(min(cw, pw)):  # the addend is registered with the operands' rows
            heaps[0][k].append(f"C[{k}]")
        body = registered_body2(heaps, pw, "p_o")
    else:
        body = registered_body(heap, pw, "p_o")
    cond = [f"AW == {aw}", f"BW == {bw}", f"PW == {pw}", f"SIGNED == {int(signed)}"]
    cond += [f"ADD == 1", f"CW == {cw}"] if cw else ["ADD == 0"]
    cond.append(f"N == {nprod}")
    cond.append(f"LAT == {lat}")
    if square:
        cond.append("_TECHMAP_CONNMAP_a_i_ == _TECHMAP_CONNMAP_b_i_")
    kind = ("square" if square else "product" if nprod == 1 else f"sum of {nprod} products") + \
        (f" + {cw}-bit addend" if cw else "") + (", two registers (LAT 2)" if lat == 2 else "")
    return f"""// sc_mul_reg {kind} {aw}x{bw} -> {pw}, {'signed' if signed else 'unsigned'}: tree | register | adder
(* techmap_celltype = "sc_mul_reg" *)
module _sc_mulreg_{index} (clk_i, en_i, a_i, b_i, c_i, p_o);
  parameter AW = 1;
  parameter BW = 1;
  parameter PW = 1;
  parameter SIGNED = 0;
  parameter ADD = 0;
  parameter CW = 1;
  parameter N = 1;
  parameter LAT = 1;
  parameter _TECHMAP_CONNMAP_a_i_ = 0;
  parameter _TECHMAP_CONNMAP_b_i_ = 0;
  input clk_i, en_i;
  (* force_downto *) input [N*AW-1:0] a_i;
  (* force_downto *) input [N*BW-1:0] b_i;
  (* force_downto *) input [CW-1:0] c_i;
  (* force_downto *) output [PW-1:0] p_o;
  wire _TECHMAP_FAIL_ = !({' && '.join(cond)});
  wire [N*AW-1:0] A = a_i;
  wire [N*BW-1:0] B = b_i;
  wire [CW-1:0] C = c_i;
{body}
endmodule
"""


def sumreg_module_for(n, w, pattern, index):
    """Verilog of one techmap module for an rtl/sc_sum_reg.v instance: n operands of w bits whose bits are
    `pattern` (x_i's bits from bit 0: 'v' a signal, '0'/'1' a constant; the module matches only an instance with
    exactly these constant bits, _TECHMAP_CONSTMSK/VAL). The signal bits form the heap, the constants one row;
    then tree | register | adder as sc_mul_reg."""
    heap = [[] for _ in range(w)]
    const = 0
    for i, ch in enumerate(pattern):
        if ch == "1":
            const += 1 << (i % w)
        elif ch == "v":
            heap[i % w].append(f"x_i[{i}]")
    const %= 1 << w
    for k in range(w):
        if const >> k & 1:
            heap[k].append("1'b1")
    nw = n * w
    msk = "".join("0" if ch == "v" else "1" for ch in reversed(pattern))
    val = "".join("1" if ch == "1" else "0" for ch in reversed(pattern))
    cond = (f"N == {n} && W == {w} && _TECHMAP_CONSTMSK_x_i_ == {nw}'b{msk} && "
            f"(_TECHMAP_CONSTVAL_x_i_ & {nw}'b{msk}) == {nw}'b{val}")
    nvar = pattern.count("v")
    return f"""// sc_sum_reg {n} x {w} bits ({nvar} signal bits, the rest constant): tree | register | adder
(* techmap_celltype = "sc_sum_reg" *)
module _sc_sumreg_{index} (clk_i, en_i, x_i, s_o);
  parameter N = 1;
  parameter W = 1;
  parameter _TECHMAP_CONSTMSK_x_i_ = 0;
  parameter _TECHMAP_CONSTVAL_x_i_ = 0;
  input clk_i, en_i;
  (* force_downto *) input [N*W-1:0] x_i;
  (* force_downto *) output [W-1:0] s_o;
  wire _TECHMAP_FAIL_ = !({cond});
{registered_body(heap, w, "s_o")}
endmodule
"""


def sumreg_shapes_of(design_json):
    """The distinct rtl/sc_sum_reg.v instances (black-box cells) of a Yosys write_json file, by their operand count,
    width and constant bits: (n, w, pattern)."""
    with open(design_json) as f:
        d = json.load(f)
    shapes = set()
    for mod in d["modules"].values():
        for cell in mod.get("cells", {}).values():
            if cell["type"] != "sc_sum_reg":
                continue
            p = {"N": 2, "W": 8}  # rtl/sc_sum_reg.v's defaults
            p.update({k: int(v, 2) if isinstance(v, str) else int(v) for k, v in cell["parameters"].items()})
            bits = cell["connections"]["x_i"]
            pattern = "".join(b if b in ("0", "1") else "v" for b in bits)  # an 'x' bit is a signal: never folded
            shapes.add((p["N"], p["W"], pattern))
    return sorted(shapes)


def mulreg_shapes_of(design_json):
    """The distinct rtl/sc_mul_reg.v shapes (black-box cells) of a Yosys write_json file."""
    with open(design_json) as f:
        d = json.load(f)
    shapes = set()
    for mod in d["modules"].values():
        for cell in mod.get("cells", {}).values():
            if cell["type"] != "sc_mul_reg":
                continue
            p = {"SIGNED": 0, "ADD": 0, "CW": 1, "N": 1, "LAT": 1}  # rtl/sc_mul_reg.v's defaults (a cell lists only what it sets)
            p.update({k: int(v, 2) if isinstance(v, str) else int(v) for k, v in cell["parameters"].items()})
            con = cell["connections"]
            shapes.add((p["AW"], p["BW"], p["PW"], bool(p["SIGNED"]), p["N"] == 1 and con["a_i"] == con["b_i"],
                        p["CW"] if p["ADD"] else 0, p["N"], p["LAT"]))
    return sorted(shapes)


def write_mulreg_map(shapes, path, sums=()):
    """Write the techmap file of the sc_mul_reg shapes (squares first) and the sc_sum_reg instances."""
    mods = [mulreg_module_for(*s[:6], i, *s[6:]) for i, s in enumerate(sorted(shapes, key=lambda s: not s[4]))]
    mods += [sumreg_module_for(*s, i) for i, s in enumerate(sums)]
    with open(path, "w") as f:
        f.write("// generated by signoff/fastmul.py, do not edit\n")
        f.write("\n".join(mods))


def mulreg_selftest(shapes, rtl):
    """Prove each generated sc_mul_reg map equal to rtl/sc_mul_reg.v: a miter of the two, all registers 0 at
    the start, the enable high at the first LAT edges, then any inputs and enables for 2 more edges (SAT). After an
    enabled edge both registers hold all their state (the product, its rows), so a load followed by a hold
    and a load covers every case. Small shapes: a multiplier miter is hard for SAT beyond ~8 bits."""
    ok = True
    for s in shapes:
        aw, bw, pw, signed, square, cw, nprod, lat = tuple(s) + (1, 1)[len(s) - 6:]
        s = (aw, bw, pw, signed, square, cw, nprod, lat)
        with tempfile.TemporaryDirectory() as tmp:
            b = "a" if square else "b"
            add = f", .ADD(1), .CW({cw})" if cw else ""
            add += f", .N({nprod})" if nprod > 1 else ""
            add += f", .LAT({lat})" if lat > 1 else ""
            src = f"""module top(input clk, input en, input [{nprod*aw-1}:0] a, input [{nprod*bw-1}:0] b,
           input [{max(cw, 1)-1}:0] c, output [{pw-1}:0] y);
  sc_mul_reg #(.AW({aw}), .BW({bw}), .PW({pw}), .SIGNED({int(signed)}){add}) u (.clk_i(clk), .en_i(en), .a_i(a), .b_i({b}),
      .c_i(c), .p_o(y));
endmodule
"""
            open(os.path.join(tmp, "t.v"), "w").write(src)
            write_mulreg_map([s], os.path.join(tmp, "map.v"))
            # the first lat edges enabled fill every register (no reset: before that the mapped registers hold no
            # carry-save form of the gold's zeros), then any inputs and enables
            en_first = " ".join(f"-set-at {t} in_en 1" for t in range(1, lat + 1))
            script = (f"read_verilog {tmp}/t.v; read_verilog -lib {rtl}; hierarchy -top top; rename top gate; "
                      f"techmap -autoproc -map {tmp}/map.v gate; select -assert-none gate/t:sc_mul_reg; "
                      f"design -stash gatedesign; read_verilog {tmp}/t.v {rtl}; hierarchy -top top; proc; flatten; "
                      f"rename top gold; design -copy-from gatedesign gate; proc; opt_clean; "
                      f"miter -equiv -flatten -make_assert gold gate miter; hierarchy -top miter; "
                      f"sat -verify -prove-asserts -set-init-zero -seq {2 + lat} {en_first} -prove-skip {lat} "
                      f"-show-inputs miter")
            ok &= _prove(f"sc_mul_reg {s}", script)
    return ok


def sumreg_selftest(rtl_sum):
    """Prove the generated sc_sum_reg maps equal to rtl/sc_sum_reg.v, as mulreg_selftest: small instances whose
    operands mix signals, constant 0 and 1 bits, AND terms and repeated bits (what rtl/sc_square.v's rows give),
    their shapes (constant bits) read from a Yosys write_json of the instance, as signoff.py reads them."""
    cases = {"mixed": ("input [3:0] a, input [3:0] b", 4, 5,
                       "{1'b0, a & b, 4'b1011, 1'b1, b, a[3], 1'b0, a[2:0], 1'b1}"),
             "square rows": ("input [3:0] a, input [3:0] b", 3, 6,
                             "{2'b0, a[3] & a[2], a[3] & a[1], a[3] & a[0], a[3], 1'b0, a[2] & a[1], a[2] & a[0], "
                             "a[2], 3'b0, a[1] & a[0], a[1], 1'b0, a[0], 1'b1}"),
             "no constant": ("input [3:0] a, input [3:0] b", 2, 4, "{a, b}")}
    ok = True
    for label, (ports, n, w, expr) in cases.items():
        with tempfile.TemporaryDirectory() as tmp:
            src = f"""module top(input clk, input en, {ports}, output [{w-1}:0] y);
  sc_sum_reg #(.N({n}), .W({w})) u (.clk_i(clk), .en_i(en), .x_i({expr}), .s_o(y));
endmodule
"""
            open(os.path.join(tmp, "t.v"), "w").write(src)
            subprocess.run(["yosys", "-q", "-p", f"read_verilog {tmp}/t.v; read_verilog -lib {rtl_sum}; "
                            f"hierarchy -top top; proc; opt_expr; opt_clean; write_json {tmp}/t.json"], check=True)
            sums = sumreg_shapes_of(os.path.join(tmp, "t.json"))
            write_mulreg_map([], os.path.join(tmp, "map.v"), sums)
            script = (f"read_verilog {tmp}/t.v; read_verilog -lib {rtl_sum}; hierarchy -top top; proc; opt_expr; "
                      f"rename top gate; techmap -autoproc -map {tmp}/map.v gate; select -assert-none gate/t:sc_sum_reg; "
                      f"design -stash gatedesign; read_verilog {tmp}/t.v {rtl_sum}; hierarchy -top top; proc; flatten; "
                      f"rename top gold; design -copy-from gatedesign gate; proc; opt_clean; "
                      f"miter -equiv -flatten -make_assert gold gate miter; hierarchy -top miter; "
                      f"sat -verify -prove-asserts -set-init-zero -seq 3 -set-at 1 in_en 1 -prove-skip 1 "
                      f"-show-inputs miter")
            ok &= _prove(f"sc_sum_reg {label} ({n} x {w}, {sums[0][2].count('v') if sums else 0} signal bits)", script)
    return ok


def shapes_of(design_json):
    """The distinct $mul shapes of a Yosys write_json file: (aw, bw, yw, signed, square)."""
    with open(design_json) as f:
        d = json.load(f)
    shapes = set()
    for mod in d["modules"].values():
        for cell in mod.get("cells", {}).values():
            if cell["type"] != "$mul":
                continue
            p = {k: int(v, 2) if isinstance(v, str) else int(v) for k, v in cell["parameters"].items()}
            con = cell["connections"]
            square = con["A"] == con["B"]
            shapes.add((p["A_WIDTH"], p["B_WIDTH"], p["Y_WIDTH"], bool(p["A_SIGNED"]), square))
    return sorted(shapes)


def write_map(shapes, path):
    """Write the techmap file for these shapes (squares first, so a square never takes a product's map)."""
    text = map_module(sorted(shapes, key=lambda s: not s[4])) if shapes else ""
    with open(path, "w") as f:
        f.write("// generated by signoff/fastmul.py, do not edit\n" + text)


def selftest(shapes):
    """Prove each shape of one generated map (all the shapes in it, as a design's map) equal to Yosys's $mul (SAT on
    the combinational cone): the map's shape selection picks the right tree (a square and a product of the same
    widths included)."""
    ok = True
    for s in shapes:
        aw, bw, yw, signed, square = s
        with tempfile.TemporaryDirectory() as tmp:
            sg = "signed " if signed else ""
            rhs = "a * a" if square else "a * b"
            src = f"""module gold(input {sg}[{aw-1}:0] a, input {sg}[{bw-1}:0] b, output [{yw-1}:0] y);
  assign y = {rhs};
endmodule
"""
            open(os.path.join(tmp, "g.v"), "w").write(src)
            write_map(shapes, os.path.join(tmp, "map.v"))
            script = (f"read_verilog {tmp}/g.v; proc; opt_clean; copy gold gate; "
                      f"techmap -map {tmp}/map.v gate; opt_clean; "
                      f"miter -equiv -flatten -make_assert gold gate miter; "
                      f"sat -verify -prove-asserts -show-inputs miter")
            r = subprocess.run(["yosys", "-q", "-p", script], capture_output=True, text=True)
            mapped = subprocess.run(["yosys", "-q", "-p", f"read_verilog {tmp}/g.v; proc; techmap -map {tmp}/map.v; "
                                     "select -assert-none t:$mul"], capture_output=True, text=True)
            good = r.returncode == 0 and mapped.returncode == 0
            ok &= good
            print(f"fastmul selftest {s}: {'PASS' if good else 'FAIL'}"
                  + ("" if mapped.returncode == 0 else " (the map did not apply)"))
            if r.returncode != 0:
                print(r.stdout[-2000:] + r.stderr[-2000:])
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--design", help="Yosys write_json of the prepared design: map its $mul shapes")
    ap.add_argument("--out", help="the techmap file to write")
    ap.add_argument("--selftest", action="store_true",
                    help="prove a set of shapes (small, signed, square, truncated) equal to $mul with Yosys sat")
    a = ap.parse_args()
    if a.selftest:
        shapes = [(4, 4, 8, False, False), (5, 3, 8, True, False), (6, 6, 12, False, True),
                  (6, 6, 12, True, True), (7, 5, 7, False, False), (5, 5, 14, True, False),
                  (3, 6, 9, True, False), (8, 8, 9, False, True), (6, 6, 12, False, False), (6, 6, 12, True, False)]
        rtl = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "rtl", "sc_mul_reg.v")
        ok = selftest(shapes) and lcu_selftest()
        if os.path.exists(rtl):  # in a handoff bundle: rtl/ beside signoff/ too
            ok &= mulreg_selftest([s + (0,) for s in shapes[:4]] + [(7, 5, 12, False, False, 0), (5, 6, 12, True, False, 6),
                                                                  (4, 4, 8, False, True, 9), (3, 4, 9, True, False, 0, 3),
                                                                  (3, 3, 7, False, False, 5, 2),
                                                                  (3, 4, 9, True, False, 0, 3, 2),
                                                                  (4, 3, 8, False, False, 4, 1, 2)], rtl)
            ok &= sumreg_selftest(os.path.join(os.path.dirname(rtl), "sc_sum_reg.v"))
        sys.exit(0 if ok else 1)
    if not a.design or not a.out:
        ap.error("--design and --out are required (or --selftest)")
    write_map(shapes_of(a.design), a.out)


if __name__ == "__main__":
    main()

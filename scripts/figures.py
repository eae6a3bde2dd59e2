# SPDX-License-Identifier: Apache-2.0
"""Shared helpers of shadecore's plotting scripts: the import check, the machine line and the atomic
figure save with a footer naming the command, machine and date."""
import datetime
import importlib
import os
import platform
import re
import signal
import sys


def require(*modules):
    """Exits with one line (status 1) unless every module imports: checked before any work is done."""
    for m in modules:
        try:
            importlib.import_module(m)
        except ImportError:
            prog = os.path.basename(sys.argv[0]) or "python"
            sys.exit(f"{prog}: error: python module '{m}' is not installed for {sys.executable} "
                     "(run the script with /usr/bin/python3, which has numpy and matplotlib)")


def run(main):
    """Runs a plotting script's main(): Ctrl-C ends it with one line on stderr and status 130 (128 + SIGINT)."""
    try:
        main()
    except KeyboardInterrupt:
        print(f"{os.path.basename(sys.argv[0])}: interrupted", file=sys.stderr)
        sys.exit(128 + signal.SIGINT)


def machine():
    """CPU model name and core count, as `lscpu` reports the model name (SHADECORE_FIGURE_MACHINE, when set, instead:
    tests/figures_check.py draws every figure with a long one, so a long CPU name cannot push a footer out)."""
    if os.environ.get("SHADECORE_FIGURE_MACHINE"):
        return os.environ["SHADECORE_FIGURE_MACHINE"]
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return f"{line.split(':', 1)[1].strip()}, {os.cpu_count()} cores"
    except OSError:
        pass
    return platform.machine()


# What a footer looks like (footer() below, or a figure redrawn from recorded data naming where its data came from).
FOOTER = re.compile(r"\S.* \|\s.+ \|\s.*\d{4}-\d{2}-\d{2}", re.S)  # broken over lines too (stamp_footer)


def footer(command):
    return f"{command} | {machine()} | {datetime.date.today().isoformat()}"


def gate_sim_text(row, missing="—"):
    """The gate-level column of a docs/timing.json row (docs/timing.md, docs/tradeoffs.md): records and mismatches,
    and the simulator where it is not Icarus (signoff.py --gatesim: Verilator for the largest netlists)."""
    if row.get("gate_sim_vectors") is None:
        return missing
    sim = row.get("gate_sim_simulator") or "icarus"
    return (f"{row['gate_sim_vectors']} vectors, {row['gate_sim_mismatches']} mismatches"
            + ("" if sim == "icarus" else f" ({sim.capitalize()})"))


def text_problems(fig, dpi=None, slack=0.5):
    """The text boxes of `fig` as drawn (every Text artist the renderer actually draws: titles, axis labels,
    tick labels, annotations, legend entries, the footer) and what is wrong with them: pairs whose window
    extents overlap by more than `slack` pixels each way, and boxes that reach outside the figure.
    Returns a list of one-line strings (empty: readable)."""
    import matplotlib.text

    drawn = []
    original = matplotlib.text.Text.draw

    def recording_draw(self, renderer):
        original(self, renderer)
        if self.get_visible() and self.get_text().strip():
            try:  # the text's own box (an annotation's leader line is not text)
                bb = matplotlib.text.Text.get_window_extent(self, renderer)
            except (RuntimeError, ValueError):
                return
            if bb.width > 0 and bb.height > 0:
                drawn.append((self.get_text().replace("\n", " ")[:60], bb))

    matplotlib.text.Text.draw = recording_draw
    try:
        if dpi is not None:
            fig.set_dpi(dpi)
        fig.canvas.draw()
    finally:
        matplotlib.text.Text.draw = original
    W, H = fig.bbox.width, fig.bbox.height
    problems = []
    for i, (ta, a) in enumerate(drawn):
        if a.x0 < -slack or a.y0 < -slack or a.x1 > W + slack or a.y1 > H + slack:
            problems.append(f"outside the figure: '{ta}'")
        for tb, b in drawn[i + 1:]:
            dx = min(a.x1, b.x1) - max(a.x0, b.x0)
            dy = min(a.y1, b.y1) - max(a.y0, b.y0)
            if dx > slack and dy > slack:
                problems.append(f"overlap: '{ta}' / '{tb}'")
    return problems


def _candidates(radii=(3, 8, 14, 22, 32, 44, 58, 74, 92)):
    """Label offsets in points around a point, nearest first: right, left, above, below, then the diagonals."""
    import math

    out = []
    for r in radii:
        for deg in (0, 180, 30, 150, -30, -150, 60, 120, -60, -120, 90, -90):
            out.append((r * math.cos(math.radians(deg)), r * math.sin(math.radians(deg))))
    return out


def place_labels(ax, items, fontsize=6, obstacles=(), leader_from=10, color="0.15"):
    """Labels `items` ([(x, y, text), ...] in data coordinates) next to their points without overlapping each
    other, the points, the `obstacles` (artists, e.g. a legend) or the axes' edge: each label takes the nearest
    free offset of _candidates(); a label placed further than `leader_from` points gets a leader line. Call it
    after the axes' scales and limits are final and the figure is laid out (figures.layout). Returns the texts
    that found no free place (drawn at their first offset; the overlap check then reports them)."""
    import matplotlib.text
    import matplotlib.transforms as mtrans

    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = ax.get_window_extent(renderer)
    taken = [a.get_window_extent(renderer) for a in obstacles]
    pts = [ax.transData.transform((x, y)) for x, y, _ in items]
    r_px = 3.5 * fig.dpi / 72
    taken += [mtrans.Bbox.from_extents(px - r_px, py - r_px, px + r_px, py + r_px) for px, py in pts]
    failed = []
    for (x, y, text) in items:
        chosen = None
        for dx, dy in _candidates():
            ha = "left" if dx > 0.5 else "right" if dx < -0.5 else "center"
            va = "bottom" if dy > 0.5 else "top" if dy < -0.5 else "center"
            t = ax.annotate(text, (x, y), xytext=(dx, dy), textcoords="offset points", ha=ha, va=va,
                            fontsize=fontsize, color=color, annotation_clip=False)
            t.update_positions(renderer)
            bb = matplotlib.text.Text.get_window_extent(t, renderer).padded(1)
            if (bb.x0 >= box.x0 and bb.x1 <= box.x1 and bb.y0 >= box.y0 and bb.y1 <= box.y1
                    and not any(bb.overlaps(o) for o in taken)):
                chosen = (dx, dy, ha, va, bb)
                t.remove()
                break
            t.remove()
        if chosen is None:
            failed.append(text)
            dx, dy = _candidates()[0]
            ha, va, bb = "left", "center", None
        else:
            dx, dy, ha, va, bb = chosen
            taken.append(bb)
        far = (dx * dx + dy * dy) ** 0.5 > leader_from
        t = ax.annotate(text, (x, y), xytext=(dx, dy), textcoords="offset points", ha=ha, va=va, fontsize=fontsize,
                        color=color, annotation_clip=False,
                        arrowprops=dict(arrowstyle="-", lw=0.4, color="0.55", shrinkA=0, shrinkB=2) if far else None)
        t.set_in_layout(False)
    return failed


def layout(fig):
    """The layout figures.save applies (so labels placed after it stay where they were placed)."""
    for ax in fig.axes:
        ax.title.set_fontsize(9)
    fig.tight_layout(rect=(0, 0.04, 1, 1))


def check(fig, path, dpi):
    """With SHADECORE_FIGURE_CHECK=FILE in the environment, appends one JSON line per figure saved
    ({"path", "problems"}) to FILE: the plot-overlap test (tests/figures_check.py) reads it."""
    out = os.environ.get("SHADECORE_FIGURE_CHECK")
    if not out:
        return
    import json

    import matplotlib.text

    problems = text_problems(fig, dpi)
    if not any(FOOTER.search(t.get_text()) for t in fig.findobj(matplotlib.text.Text)):
        problems.append("no footer naming command, machine and date ('command | machine | date')")
    with open(out, "a") as f:
        f.write(json.dumps({"path": os.path.abspath(path), "problems": problems}) + "\n")


def stamp_footer(fig, footer_text, size=6.0, smallest=4.5):
    """The footer at the figure's bottom left, fitted to the figure's width: a long command or a long CPU name first
    shrinks it (down to `smallest` points), then breaks it after its ' |' separators (the command, the machine, the
    date each whole), never cutting what it names."""
    t = fig.text(0.01, 0.005, footer_text, fontsize=size, color="0.35", ha="left", va="bottom")
    renderer = fig.canvas.get_renderer()
    room = 0.98 * fig.bbox.width
    width = t.get_window_extent(renderer).width
    if width <= room:
        return t
    t.set_fontsize(max(smallest, size * room / width))
    if t.get_window_extent(renderer).width <= room:
        return t
    lines, parts = [], footer_text.split(" | ")
    for part in parts:
        trial = (lines[-1] + " | " + part) if lines else part
        t.set_text(trial)
        if lines and t.get_window_extent(renderer).width > room:
            lines.append(part)
        elif lines:
            lines[-1] = trial
        else:
            lines.append(part)
    t.set_text(" |\n".join(lines))
    return t


def _draw(fig, path, footer_text, dpi):
    import matplotlib.pyplot as plt

    layout(fig)
    stamp_footer(fig, footer_text)
    check(fig, path, dpi)
    tmp = path + ".tmp.png"
    try:
        fig.savefig(tmp, dpi=dpi)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    finally:
        plt.close(fig)
    return tmp


def save(fig, path, footer_text, dpi=130):
    """Lays the figure out, stamps the footer and writes it atomically (temporary file, rename)."""
    os.replace(_draw(fig, path, footer_text, dpi), path)


def save_all(figs, directory, footer_text, dpi=130):
    """Saves every figure of `figs` ({file name: figure}) or none: all are drawn to temporary files
    first and renamed only when every one succeeded."""
    tmps = []
    try:
        for name, fig in figs.items():
            tmps.append((_draw(fig, os.path.join(directory, name), footer_text, dpi), os.path.join(directory, name)))
    except BaseException:
        for tmp, _ in tmps:
            if os.path.exists(tmp):
                os.unlink(tmp)
        raise
    for tmp, path in tmps:
        os.replace(tmp, path)

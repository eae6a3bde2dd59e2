#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The README's picture of a coverage report: the per-file page of the HTML report `shadecore coverage` (or
`regress --coverage`, `cosim --coverage`) wrote, rendered by wkhtmltoimage, with a footer naming the command that
made the report, the machine and the date.

    scripts/coverage_picture.py COVERAGE_DIR OUT.png --made-by "shadecore coverage ... --out COVERAGE_DIR"

COVERAGE_DIR holds html/ (genhtml's report; the page shown is html/rtl/index.html, the RTL files). The HTML is
lcov's view: line points only, the minimum per line, no waivers; summary.json beside it has the waiver-aware
figures (docs/coverage.md). Needs wkhtmltoimage (Debian wkhtmltopdf: `scripts/setup.sh wkhtmltopdf`) and
Pillow. The picture is written whole or not at all."""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures  # noqa: E402  the machine line and footer of every figure


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("coverage_dir", help="a directory with html/ from shadecore coverage / regress --coverage")
    ap.add_argument("out", help="the PNG to write")
    ap.add_argument("--made-by", required=True, help="the command that made the report (named in the footer)")
    ap.add_argument("--width", type=int, default=1000, help="page width in pixels (default 1000)")
    a = ap.parse_args()
    figures.require("PIL")
    from PIL import Image, ImageDraw, ImageFont
    page = os.path.join(a.coverage_dir, "html", "rtl", "index.html")
    if not os.path.isfile(page):
        sys.exit(f"coverage_picture: error: no {page} (a report made with --no-html, or not a coverage directory)")
    if not shutil.which("wkhtmltoimage"):
        sys.exit("coverage_picture: error: wkhtmltoimage is not installed (scripts/setup.sh wkhtmltopdf)")
    if os.path.lexists(a.out) and not os.path.isfile(a.out):
        sys.exit(f"coverage_picture: error: {a.out} exists and is not a regular file")
    out_dir = os.path.dirname(os.path.abspath(a.out))
    with tempfile.TemporaryDirectory() as tmp:
        shot = os.path.join(tmp, "page.png")
        env = dict(os.environ, QT_QPA_PLATFORM="offscreen", XDG_RUNTIME_DIR=tmp)
        p = subprocess.run(["wkhtmltoimage", "--quiet", "--width", str(a.width), "--enable-local-file-access",
                            page, shot], capture_output=True, text=True, env=env, timeout=300)
        if p.returncode or not os.path.isfile(shot):
            sys.exit(f"coverage_picture: error: wkhtmltoimage failed (exit {p.returncode}): "
                     f"{(p.stderr or p.stdout).strip().splitlines()[-1:] }")
        im = Image.open(shot).convert("RGB")
        text = figures.footer(a.made_by)
        try:  # matplotlib's DejaVu Sans (every figure's font), readable at the page's size
            from matplotlib import font_manager
            font = ImageFont.truetype(font_manager.findfont("DejaVu Sans"), 13)
        except (ImportError, OSError):
            font = ImageFont.load_default()
        lines, line = [], ""
        for word in text.split(" "):  # wrap the footer to the page width
            trial = (line + " " + word).strip()
            if ImageDraw.Draw(im).textlength(trial, font=font) > im.width - 16 and line:
                lines.append(line)
                line = word
            else:
                line = trial
        lines.append(line)
        foot_h = 17 * len(lines) + 10
        canvas = Image.new("RGB", (im.width, im.height + foot_h), "white")
        canvas.paste(im, (0, 0))
        d = ImageDraw.Draw(canvas)
        for i, ln in enumerate(lines):
            d.text((8, im.height + 4 + 17 * i), ln, fill=(60, 60, 60), font=font)
        fd, tmp_out = tempfile.mkstemp(prefix=".coverage_picture.", suffix=".png", dir=out_dir)
        os.close(fd)
        try:
            canvas.save(tmp_out, optimize=True)
            os.chmod(tmp_out, 0o644)
            os.replace(tmp_out, a.out)
        except BaseException:
            os.remove(tmp_out)
            raise
    print(f"coverage_picture: wrote {a.out} ({canvas.width}x{canvas.height})")


if __name__ == "__main__":
    figures.run(main)

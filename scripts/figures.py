# SPDX-License-Identifier: Apache-2.0
"""Shared helpers of shadecore's plotting scripts: the import check, the machine line and the atomic
figure save with a footer naming the command, machine and date."""
import datetime
import importlib
import os
import platform
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
    """CPU model name and core count, as `lscpu` reports the model name."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return f"{line.split(':', 1)[1].strip()}, {os.cpu_count()} cores"
    except OSError:
        pass
    return platform.machine()


def footer(command):
    return f"{command} | {machine()} | {datetime.date.today().isoformat()}"


def _draw(fig, path, footer_text, dpi):
    import matplotlib.pyplot as plt

    for ax in fig.axes:
        ax.title.set_fontsize(9)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.text(0.01, 0.005, footer_text, fontsize=6, color="0.35", ha="left", va="bottom")
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

"""Shared helpers of shadecore's plotting scripts: the machine line and the atomic figure save with
a footer naming the command, machine and date."""
import datetime
import os
import platform


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


def save(fig, path, footer_text, dpi=130):
    """Lays the figure out, stamps the footer and writes it atomically (temporary file, rename)."""
    import matplotlib.pyplot as plt

    for ax in fig.axes:
        ax.title.set_fontsize(9)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.text(0.01, 0.005, footer_text, fontsize=6, color="0.35", ha="left", va="bottom")
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=dpi)
    plt.close(fig)
    os.replace(tmp, path)

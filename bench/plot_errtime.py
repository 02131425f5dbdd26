#!/usr/bin/python3
"""Draws errtime_<scene>.png from snh-gpu-bench errtime's errtime.csv.

Usage: plot_errtime.py ERRTIME_CSV OUT_DIR

One figure per scene, two panels against wall time: the force residual and
the error against the reference solution, log y, one line per series.
Needs matplotlib (Debian: python3-matplotlib); exits with status 3 without it.
"""
import csv
import math
import os
import sys
from collections import OrderedDict

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.stderr.write("plot_errtime.py: matplotlib is not installed (Debian: python3-matplotlib)\n")
    sys.exit(3)

THRESHOLDS = (1e-2, 1e-4, 1e-6)
STYLES = {
    "double/block-jacobi": dict(color="tab:blue", linestyle="-", marker="o"),
    "double/none": dict(color="tab:blue", linestyle="--", marker="s"),
    "float/block-jacobi": dict(color="tab:orange", linestyle="-", marker="o"),
    "float/none": dict(color="tab:orange", linestyle="--", marker="s"),
    "host-eigen": dict(color="tab:green", linestyle=":", marker="^"),
}


def read(path):
    scenes = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            series = scenes.setdefault(row["scene"], OrderedDict()).setdefault(row["series"], [])
            series.append(
                (float(row["seconds"]), float(row["residual"]), float(row["error"]), int(row["step"]))
            )
    return scenes


def positive(points, index):
    return [(p[0], p[index]) for p in points if math.isfinite(p[index]) and p[index] > 0.0]


def plot_scene(scene, series, out_dir):
    fig, (ax_r, ax_e) = plt.subplots(1, 2, figsize=(12, 4.8), constrained_layout=True)
    steps = max(p[3] for points in series.values() for p in points)
    for name, points in series.items():
        style = dict(STYLES.get(name, dict(marker="x")))
        for ax, index in ((ax_r, 1), (ax_e, 2)):
            xy = positive(points, index)
            if not xy:
                continue
            ax.plot([x for x, _ in xy], [y for _, y in xy], label=name, markersize=3, linewidth=1.2, **style)
    for t in THRESHOLDS:
        ax_r.axhline(t, color="0.6", linewidth=0.8, linestyle=(0, (2, 3)))
        ax_r.annotate("%g" % t, xy=(1.0, t), xycoords=("axes fraction", "data"), xytext=(2, 0),
                      textcoords="offset points", fontsize=7, color="0.4", va="center")
    ax_r.set_title("force residual")
    ax_r.set_ylabel("||r||  (free DOFs, L2)")
    ax_e.set_title("error against the double reference (rel. residual 1e-10)")
    ax_e.set_ylabel("||x - x_ref|| / ||x_ref - X_rest||")
    for ax in (ax_r, ax_e):
        ax.set_yscale("log")
        ax.set_xlabel("wall time [s]")
        ax.grid(True, which="major", alpha=0.3)
        ax.grid(True, which="minor", alpha=0.1)
        ax.set_xlim(left=0.0)
    handles, labels = ax_r.get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=len(labels), fontsize=9,
               frameon=False)
    note = " (%d load steps; each step restarts the residual)" % steps if steps > 1 else ""
    fig.suptitle("%s: residual and error vs wall time, per Newton iteration%s" % (scene, note), fontsize=11)
    path = os.path.join(out_dir, "errtime_%s.png" % scene)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    scenes = read(argv[1])
    for scene, series in scenes.items():
        print("wrote", plot_scene(scene, series, argv[2]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

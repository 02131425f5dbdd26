#!/usr/bin/python3
"""Draws scale.png from snh-gpu-bench scale's scale.json.

Usage: plot_scale.py SCALE_JSON OUT_DIR

Seconds per load step against DOF, log-log, one panel per scene, one line
per preconditioner with the slope fitted by the command (least squares in
log-log) in its legend; the paper's two GPU figures as reference points.
Needs matplotlib (Debian: python3-matplotlib); exits with status 3 without it.
"""
import json
import os
import sys
from collections import OrderedDict

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.stderr.write("plot_scale.py: matplotlib is not installed (Debian: python3-matplotlib)\n")
    sys.exit(3)

STYLES = {
    "none": dict(color="tab:gray", linestyle="--", marker="s"),
    "block-jacobi": dict(color="tab:blue", linestyle="-", marker="o"),
    "multigrid": dict(color="tab:green", linestyle="-", marker="^"),
}
# Smith et al. 2018, sec. 6 (GPU): bicep 156k DOF at 25.6 s per step, 965k DOF at 100.6 s per frame.
PAPER = ((156e3, 25.6, "paper: bicep, s/step"), (965e3, 100.6, "paper: 965k DOF, s/frame"))


def main():
    if len(sys.argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    with open(sys.argv[1]) as f:
        summary = json.load(f)
    out_dir = sys.argv[2]
    scenes = OrderedDict()
    for r in summary["records"]:
        if "skipped" in r:
            continue
        scenes.setdefault(r["scene"], OrderedDict()).setdefault(r["preconditioner"], []).append(
            (r["dofs"], r["seconds_per_step"])
        )
    slopes = {(s["scene"], s["preconditioner"]): s["slope"] for s in summary.get("slopes", [])}
    if not scenes:
        sys.stderr.write("plot_scale.py: no record ran; nothing to plot\n")
        return 0
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.5 * len(scenes), 4.5), squeeze=False)
    for ax, (scene, series) in zip(axes[0], scenes.items()):
        for pre, points in series.items():
            points.sort()
            slope = slopes.get((scene, pre))
            label = pre + (" (slope %.2f)" % slope if slope is not None else "")
            ax.plot([p[0] for p in points], [p[1] for p in points], label=label, **STYLES.get(pre, {}))
        for dofs, seconds, label in PAPER:
            ax.plot([dofs], [seconds], linestyle="none", marker="*", markersize=10, color="tab:red", alpha=0.6)
            ax.annotate(label, (dofs, seconds), textcoords="offset points", xytext=(-10, 6), fontsize=7, ha="right")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("DOF")
        ax.set_ylabel("seconds per load step")
        ax.set_title(scene)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    device = summary.get("device", "")
    fig.suptitle("snh-gpu-bench scale (%s, %s, nu = %s)" % (device, summary.get("precision"), summary.get("poisson_ratio")), fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "scale.png"), dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Uniaxial nominal stress against stretch per material (snh-gpu-bench materials)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(path, out):
    curves = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            curves.setdefault(row["curve"], ([], []))
            curves[row["curve"]][0].append(float(row["stretch"]))
            curves[row["curve"]][1].append(float(row["nominal_stress"]))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for label, (x, y) in curves.items():
        ax.plot(x, y, label=label, linestyle="--" if "=" in label else "-")
    ax.set_xlabel("stretch")
    ax.set_ylabel("nominal stress P_xx / E")
    ax.set_title("homogeneous uniaxial stretch, lateral faces free (E = 1, nu = 0.45)")
    ax.grid(alpha=0.3)
    ax.set_ylim(-3, 6)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

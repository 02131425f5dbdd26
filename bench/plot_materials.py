"""Uniaxial nominal stress against stretch per material (snh-gpu-bench materials)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def plot_alpha(path, out):
    """One panel per model, one curve per nonlinearity alpha (Chen and Barbic 2024, Fig. 3)."""
    models = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            per_alpha = models.setdefault(row["model"], {})
            x, y = per_alpha.setdefault(float(row["alpha"]), ([], []))
            x.append(float(row["stretch"]))
            y.append(float(row["nominal_stress"]))
    n = len(models)
    cols = min(4, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4 * cols, 3.3 * rows), squeeze=False)
    for ax, (model, per_alpha) in zip(axes.flat, models.items()):
        for alpha, (x, y) in sorted(per_alpha.items()):
            ax.plot(x, y, label=f"alpha = {alpha:g}", linewidth=2.0 if alpha == 1.0 else 1.2)
        ax.set_title(model, fontsize=10)
        ax.set_xlabel("stretch")
        ax.set_ylabel("P_xx / E")
        ax.set_ylim(-3, 6)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.suptitle("uniaxial stretch per nonlinearity alpha, Chen and Barbic 2024, Eq. 16 (E = 1, nu = 0.45)")
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def main(path, out):
    with open(path) as f:
        header = f.readline()
    if header.startswith("model,alpha"):
        plot_alpha(path, out)
        return
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

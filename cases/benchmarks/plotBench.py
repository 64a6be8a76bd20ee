#!/usr/bin/env python3
"""Charts of the magBench studies: accuracy-cost (log-log, Pareto front),
divergence (force and error vs gap), switch error. PNGs in expected/."""
import csv
import math
import pathlib
import sys

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent
post, out = here / "postProcessing", here / "expected"
out.mkdir(exist_ok=True)


def rows(name):
    path = post / f"{name}.csv"
    return list(csv.DictReader(open(path))) if path.exists() else []


def accuracy_cost():
    data = rows("accuracyCost")
    if not data:
        return
    configs = list(dict.fromkeys(r["configuration"] for r in data))
    methods = list(dict.fromkeys(r["method"] for r in data))
    cols = 3
    fig, axes = plt.subplots(math.ceil(len(configs) / cols), cols, figsize=(15, 4.2 * math.ceil(len(configs) / cols)))
    axes = axes.flatten()
    for ax, conf in zip(axes, configs):
        pts = []
        for m in methods:
            sel = [r for r in data if r["configuration"] == conf and r["method"] == m]
            t = [1e6 * float(r["seconds"]) for r in sel]
            e = [max(float(r["relError"]), 1e-16) for r in sel]
            ax.loglog(t, e, "o-", ms=3, label=m)
            pts += list(zip(t, e))
        # Pareto front: no other point both cheaper and more accurate.
        front = sorted(p for p in pts if not any(q[0] <= p[0] and q[1] < p[1] for q in pts if q != p))
        ax.loglog([p[0] for p in front], [p[1] for p in front], "k--", lw=1, alpha=0.6, label="Pareto front")
        ax.set_title(conf)
        ax.set_xlabel("CPU time per force evaluation [us]")
        ax.set_ylabel("relative force error")
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes[len(configs):]:
        ax.axis("off")
    axes[0].legend(fontsize=8)
    fig.suptitle("Accuracy vs cost: two 1 cm cubes, 1 T (error vs exact)")
    fig.tight_layout()
    fig.savefig(out / "accuracyCost.png", dpi=90)


def divergence():
    data = rows("divergence")
    if not data:
        return
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 4.5))
    keys = list(dict.fromkeys((r["method"], r["n"]) for r in data))
    first = [r for r in data if (r["method"], r["n"]) == keys[0]]
    ax.plot([100 * float(r["gap"]) for r in first], [float(r["exactFz"]) for r in first], "k:", lw=2,
            label="exact (Akoun-Yonnet)")
    for m, n in keys:
        sel = [r for r in data if (r["method"], r["n"]) == (m, n)]
        g = [100 * float(r["gap"]) for r in sel]
        f = [float(r["Fz"]) for r in sel]
        ax.plot(g, f, lw=1, label=f"{m} n={n}")
        pos = [(x, float(r["relError"])) for x, r in zip(g, sel) if x > 0]
        ax2.semilogy([p[0] for p in pos], [max(p[1], 1e-16) for p in pos], lw=1, label=f"{m} n={n}")
    ax.set_ylim(-150, 150)
    ax.set_xlabel("gap d [cm]")
    ax.set_ylabel("Fz on the upper cube [N]")
    ax.set_title("Force through contact and overlap (paper Fig. 4b/4d)")
    ax.legend(fontsize=7)
    ax2.set_xlabel("gap d [cm]")
    ax2.set_ylabel("relative error")
    ax2.set_title("Error for d > 0 (paper Fig. 4c)")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "divergence.png", dpi=90)


def switch_error():
    data = rows("switchError")
    if not data:
        return
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
    for t in list(dict.fromkeys(r["threshold"] for r in data)):
        sel = [r for r in data if r["threshold"] == t]
        ax.semilogy([100 * float(r["gap"]) for r in sel], [max(float(r["relError"]), 1e-16) for r in sel], "o-",
                    ms=3, label=f"threshold {t}")
    ax.set_xscale("log")
    ax.set_xlabel("gap d [cm]")
    ax.set_ylabel("relative force error")
    ax.set_title("Hybrid error vs gap, per switch threshold")
    ax.legend(fontsize=7)
    ts = list(dict.fromkeys(r["threshold"] for r in data))
    worst = [max(float(r["relError"]) for r in data if r["threshold"] == t) for t in ts]
    cost = [sum(1e6 * float(r["seconds"]) for r in data if r["threshold"] == t) /
            len([r for r in data if r["threshold"] == t]) for t in ts]
    ax2.semilogy([float(t) for t in ts], worst, "o-", label="worst error over gaps")
    ax2.set_xlabel("switch threshold [bounding radii]")
    ax2.set_ylabel("worst relative error")
    ax3 = ax2.twinx()
    ax3.plot([float(t) for t in ts], cost, "s--", color="tab:red", label="mean time [us]")
    ax3.set_ylabel("mean time per evaluation [us]", color="tab:red")
    ax2.set_title("Switch threshold: error vs cost")
    fig.tight_layout()
    fig.savefig(out / "switchError.png", dpi=90)


accuracy_cost()
divergence()
switch_error()
print("charts in", out)
sys.exit(0)

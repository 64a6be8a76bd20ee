#!/usr/bin/env python3
"""Plot the force on `top` sliding across `bottom` while touching: each run beside
the exact one-sided Akoun-Yonnet force (the limit from separation, evaluated at a
1e-12 m gap: the closed form is continuous there up to O(1e-10)), and the errors."""
import csv
import os
import pathlib
import sys

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent
# The closed form lives in the twoCubes tutorial of magFoam (MAG_ROOT: set by
# etc/RunFunctions, so that a copy of this case elsewhere finds it too).
root = pathlib.Path(os.environ.get("MAG_ROOT", here.parent.parent))
sys.path.insert(0, str(root / "tutorials" / "twoCubes"))
import akounYonnet  # noqa: E402

runs = [("adaptive", "adaptive 1e-4, charge (default)", "-"),
        ("amperian", "adaptive 1e-4, amperian", "--"),
        ("gauss10", "Gauss n=10, charge", "-"),
        ("gauss10amperian", "Gauss n=10, amperian", "-")]
cube = [0.01, 0.01, 0.01]


def exact(x):
    return akounYonnet.force(cube, [0, 0, 0], cube, [x, 0.002, 0.01 + 1e-12], 1.0, 1.0)


def read(name):
    xs, fs = [], []
    with open(here / "postProcessing" / f"forces_{name}.csv") as f:
        for row in csv.DictReader(f):
            if row["body"] == "top":
                xs.append(float(row["offset"]))
                fs.append([float(row["Fx"]), float(row["Fy"]), float(row["Fz"])])
    return xs, fs


fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.5))
xe = [-0.012 + 0.024 * i / 960 for i in range(961)]
fe = [exact(x) for x in xe]
ax.plot([100 * x for x in xe], [f[2] for f in fe], "k:", lw=2, label="exact Fz (one-sided Akoun-Yonnet)")
ax.plot([100 * x for x in xe], [f[0] for f in fe], "k-.", lw=1, label="exact Fx")
for name, label, style in runs:
    xs, fs = read(name)
    ax.plot([100 * x for x in xs], [f[2] for f in fs], style, lw=1, label=label + " Fz")
    err = []
    for x, f in zip(xs, fs):
        ref = exact(x)
        norm = sum(r * r for r in ref) ** 0.5
        if norm > 1e-6:
            err.append((100 * x, max(sum((a - b) ** 2 for a, b in zip(f, ref)) ** 0.5 / norm, 1e-12)))
    ax2.semilogy([e[0] for e in err], [e[1] for e in err], style, lw=1, label=label)
ax.set_xlabel("lateral offset x [cm] (touching; y offset 2 mm)")
ax.set_ylabel("force on top [N]")
ax.set_title("Cube sliding on a cube: touching faces")
ax.legend(fontsize=7)
ax.grid(alpha=0.3)
ax2.axhline(1e-4, color="grey", lw=0.8, ls=":")
ax2.set_xlabel("lateral offset x [cm]")
ax2.set_ylabel("|F - F_exact| / |F_exact|")
ax2.set_title("Relative error (dotted: requested tolerance 1e-4)")
ax2.legend(fontsize=7)
ax2.grid(alpha=0.3, which="both")
fig.tight_layout()
fig.savefig(here / "touchingCubes.png", dpi=110)

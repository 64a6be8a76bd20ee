#!/usr/bin/env python3
"""Plot Fz on the top cube against the gap d (paper Figs. 4b and 5a) for each
quadrature, beside the exact Akoun-Yonnet force, and the relative errors."""
import csv
import pathlib

import matplotlib.pyplot as plt

import akounYonnet

here = pathlib.Path(__file__).resolve().parent
runs = [("regular2", "regular n=2"), ("regular5", "regular n=5"), ("regular10", "regular n=10"),
        ("regular20", "regular n=20"), ("gauss10", "Gauss n=10 (default)")]


def read(name):
    d, fz = [], []
    with open(here / "postProcessing" / f"forces_{name}.csv") as f:
        for row in csv.DictReader(f):
            if row["body"] == "top":
                d.append(float(row["offset"]))
                fz.append(float(row["Fz"]))
    return d, fz


cube = [0.01, 0.01, 0.01]
fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.5))
d_exact = [-0.01 + 0.03 * i / 1200 for i in range(1201)]
f_exact = [akounYonnet.force(cube, [0, 0, 0], cube, [0, 0, 0.01 + d], 1.0, 1.0)[2] for d in d_exact]
ax.plot([100 * d for d in d_exact], f_exact, "k:", lw=2, label="exact (Akoun-Yonnet)")
for name, label in runs:
    d, fz = read(name)
    ax.plot([100 * x for x in d], fz, label=label, lw=1)
    err = []
    for x, f in zip(d, fz):
        ref = akounYonnet.force(cube, [0, 0, 0], cube, [0, 0, 0.01 + x], 1.0, 1.0)[2]
        if x > 1e-9:
            err.append((100 * x, abs(f - ref) / abs(ref)))
    ax2.semilogy([e[0] for e in err], [max(e[1], 1e-12) for e in err], label=label, lw=1)
ax.set_xlabel("gap d [cm]")
ax.set_ylabel("Fz on the top cube [N]")
ax.set_title("Two 1 cm cubes, 1 T: force vs gap (MBM)")
ax.axhline(0, color="grey", lw=0.5)
ax.legend(fontsize=8)
ax2.set_xlabel("gap d [cm]")
ax2.set_ylabel("relative error vs Akoun-Yonnet")
ax2.set_title("Error for d > 0")
ax2.legend(fontsize=8)
fig.tight_layout()
fig.savefig(here / "twoCubes.png", dpi=110)
print("wrote", here / "twoCubes.png")

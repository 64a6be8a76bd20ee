#!/usr/bin/env python3
"""Total energy of the slung rod against time, both force forms: the change
since the start over the peak kinetic energy."""
import csv
import pathlib

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent


def read(folder):
    t, total, kinetic = [], [], []
    with open(folder / "postProcessing" / "energy.csv") as f:
        for row in csv.DictReader(f):
            t.append(1e3 * float(row["time"]))
            total.append(float(row["total"]))
            kinetic.append(float(row["kinetic"]))
    peak = max(kinetic)
    return t, [(e - total[0]) / peak for e in total]


fig, ax = plt.subplots(figsize=(7, 4.2))
for folder, label, style in [(here / "split", "split (paper Eqs. 16-18)", "--"),
                             (here, "surfaceCharge", "-")]:
    t, rel = read(folder)
    ax.plot(t, rel, style, lw=1.8, label=f"{label}: end {rel[-1]:+.1e}")
ax.axhline(0, color="grey", lw=0.8)
ax.set_xlabel("time [ms]")
ax.set_ylabel("(E - E_start) / peak kinetic energy")
ax.set_title("rod slung past a cube, one sample per face (regular n = 1)", fontsize=10)
ax.grid(alpha=0.3)
ax.legend(fontsize=9)
fig.tight_layout()
fig.savefig(here / "forceForm.png", dpi=110)
print("wrote", here / "forceForm.png")

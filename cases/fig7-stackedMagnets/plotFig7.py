#!/usr/bin/env python3
"""Fig. 7: heights of the magnets and kinetic energy over time, MBM vs EDM."""
import csv
import pathlib

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent
fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
for folder, label, style in ((here, "MBM (hybrid)", "-"), (here / "EDM", "EDM n=5", ":")):
    bodies = folder / "postProcessing/bodies.csv"
    if not bodies.exists():
        continue
    rows = list(csv.DictReader(open(bodies)))
    for name in sorted({r["body"] for r in rows}):
        sel = [r for r in rows if r["body"] == name]
        ax.plot([float(r["time"]) for r in sel], [1000 * float(r["z"]) for r in sel], style, lw=1,
                label=label if name == "m0" else None)
    e = list(csv.DictReader(open(folder / "postProcessing/energy.csv")))
    ax2.semilogy([float(r["time"]) for r in e], [max(float(r["kinetic"]), 1e-12) for r in e], style, label=label)
    total = [float(r["total"]) for r in e]
    print(f"{label}: total energy start {total[0]:.4g} J, max {max(total):.4g} J, end {total[-1]:.4g} J;"
          f" final kinetic {float(e[-1]['kinetic']):.3g} J")
ax.set_xlabel("time [s]")
ax.set_ylabel("height of each magnet's centre [mm]")
ax.set_title("Fig. 7: magnets stacking in the air and landing")
ax.legend()
ax2.set_xlabel("time [s]")
ax2.set_ylabel("kinetic energy [J]")
ax2.legend()
fig.tight_layout()
(here / "expected").mkdir(exist_ok=True)
fig.savefig(here / "expected/fig7.png", dpi=100)
print("wrote expected/fig7.png")

#!/usr/bin/env python3
"""Fig. 6: height of the blue cube and energies over time, MBM vs EDM."""
import csv
import pathlib

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent


def series(folder):
    bodies = pathlib.Path(folder) / "postProcessing/bodies.csv"
    energy = pathlib.Path(folder) / "postProcessing/energy.csv"
    if not bodies.exists():
        return None
    b = [r for r in csv.DictReader(open(bodies)) if r["body"] == "blue"]
    e = list(csv.DictReader(open(energy)))
    return b, e


fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
for folder, label in ((here, "MBM, Amperian overlap"), (here / "charge", "MBM, charge overlap"),
                      (here / "EDM", "EDM n=5")):
    s = series(folder)
    if not s:
        continue
    b, e = s
    ax.plot([float(r["time"]) for r in b], [1000 * (float(r["z"]) - 0.015) for r in b], label=label)
    ax2.semilogy([float(r["time"]) for r in e], [max(float(r["kinetic"]), 1e-12) for r in e], label=label)
    vmax = max((float(r["vx"]) ** 2 + float(r["vy"]) ** 2 + float(r["vz"]) ** 2) ** 0.5 for r in b)
    print(f"{label}: max speed at write times {vmax:.3g} m/s, final gap {1000 * (float(b[-1]['z']) - 0.015):.4f} mm,"
          f" final kinetic energy {float(e[-1]['kinetic']):.3g} J")
ax.set_xlabel("time [s]")
ax.set_ylabel("gap between the cubes' faces [mm] (centre z - 15 mm)")
ax.set_title("Fig. 6: blue cube attracted onto the fixed red one")
ax.legend()
ax2.set_xlabel("time [s]")
ax2.set_ylabel("kinetic energy [J]")
ax2.set_title("Kinetic energy")
ax2.legend()
fig.tight_layout()
(here / "expected").mkdir(exist_ok=True)
fig.savefig(here / "expected/fig6.png", dpi=100)
print("wrote expected/fig6.png")

#!/usr/bin/env python3
"""The fastest magnet's speed over time, with magFoam's friction bound and with ODE's own."""
import csv
import math
import pathlib

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent


def fastest(folder):
    """Per write time, the highest speed of any magnet (m/s)."""
    top = {}
    for r in csv.DictReader(open(folder / "postProcessing/bodies.csv")):
        v = math.sqrt(sum(float(r[k]) ** 2 for k in ("vx", "vy", "vz")))
        t = float(r["time"])
        top[t] = max(top.get(t, 0.0), v)
    times = sorted(top)
    # A log axis: a magnet at rest (0 m/s, asleep) is drawn at 1e-9 m/s.
    return times, [max(top[t], 1e-9) for t in times]


fig, ax = plt.subplots(figsize=(8, 4.2))
for folder, label in ((here, "frictionBound: normalForce (default)"), (here / "findex", "frictionBound: findex (ODE's own)")):
    t, v = fastest(folder)
    ax.semilogy(t, v, label=label)
ax.axhline(1e-3, color="grey", lw=0.8, ls=":", label="at rest below 1 mm/s")
ax.set_xlabel("time [s]")
ax.set_ylabel("fastest magnet's speed [m/s]")
ax.set_title("magnetChain: four cube magnets land as a chain")
ax.legend()
fig.tight_layout()
fig.savefig(here / "magnetChain.png", dpi=100)
print("wrote magnetChain.png")

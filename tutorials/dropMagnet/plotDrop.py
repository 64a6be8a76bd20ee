#!/usr/bin/env python3
"""Height and tilt of the dropped cube, and the energies, over time."""
import csv
import math
import pathlib

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent
rows = [r for r in csv.DictReader(open(here / "postProcessing/bodies.csv")) if r["body"] == "cube"]
energy = list(csv.DictReader(open(here / "postProcessing/energy.csv")))
t = [float(r["time"]) for r in rows]
z = [1000 * float(r["z"]) for r in rows]
# Tilt: angle between the cube's z axis and the world z axis.
tilt = [math.degrees(math.acos(max(-1.0, min(1.0, 1 - 2 * (float(r["qx"]) ** 2 + float(r["qy"]) ** 2)))))
        for r in rows]
fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
ax.plot(t, z, label="height of the cube's centre [mm]")
ax.plot(t, tilt, label="tilt [deg]")
ax.set_xlabel("time [s]")
ax.set_title("dropMagnet: the cube turns, falls and sticks")
ax.legend()
te = [float(r["time"]) for r in energy]
for key in ("kinetic", "gravitational", "magnetic", "total"):
    ax2.plot(te, [float(r[key]) for r in energy], label=key)
ax2.set_xlabel("time [s]")
ax2.set_ylabel("energy [J]")
ax2.legend()
fig.tight_layout()
fig.savefig(here / "dropMagnet.png", dpi=100)
print("wrote dropMagnet.png")

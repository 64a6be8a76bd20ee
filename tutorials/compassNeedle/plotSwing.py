#!/usr/bin/env python3
"""The needle's angle to the field over time against the exact pendulum: a
magnet of moment m in a uniform B feels the torque m B sin(theta), so it swings
like a pendulum, T = 4 sqrt(I / (m B)) K(sin(theta0 / 2)), K the complete
elliptic integral of the first kind (by the arithmetic-geometric mean)."""
import csv
import math
import pathlib

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent
rows = [r for r in csv.DictReader(open(here / "postProcessing/bodies.csv")) if r["body"] == "needle"]
t = [float(r["time"]) for r in rows]
# Rotation about z only: q = (cos(a/2), 0, 0, sin(a/2)).
angle = [math.degrees(2 * math.atan2(float(r["qz"]), float(r["qw"]))) for r in rows]

mu0 = 4e-7 * math.pi
a, b, c, Br, rho, B = 0.01, 0.002, 0.002, 1.3, 7500.0, 0.001
V = a * b * c
m = V * Br / mu0
I = rho * V * (b * b + a * a) / 12  # about z
theta0 = math.radians(30)

def agm(x, y):
    while abs(x - y) > 1e-15 * x:
        x, y = (x + y) / 2, math.sqrt(x * y)
    return x

K = math.pi / (2 * agm(1.0, math.cos(theta0 / 2)))  # K(k), k = sin(theta0/2)
period = 4 * math.sqrt(I / (m * B)) * K
small = 2 * math.pi * math.sqrt(I / (m * B))

# Measured period: the times the angle crosses zero going down, interpolated.
down = [t[i - 1] + (t[i] - t[i - 1]) * angle[i - 1] / (angle[i - 1] - angle[i])
        for i in range(1, len(t)) if angle[i - 1] > 0 >= angle[i]]
measured = (down[-1] - down[0]) / (len(down) - 1) if len(down) > 1 else float("nan")

fig, ax = plt.subplots(figsize=(9, 4))
ax.plot([1000 * x for x in t], angle, label="magFoam (free backend, uniform applied field)")
for k in range(int(t[-1] / period) + 1):
    ax.axvline(1000 * k * period, color="grey", lw=0.6, ls="--")
ax.set_xlabel("time [ms]")
ax.set_ylabel("angle to the field [deg]")
ax.set_title(f"compass needle: period {1000 * measured:.3f} ms, exact {1000 * period:.3f} ms "
             f"(small-angle {1000 * small:.3f} ms); dashed: exact periods", fontsize=10)
ax.legend(loc="upper right")
fig.tight_layout()
fig.savefig(here / "compassNeedle.png", dpi=100)
print(f"period: magFoam {measured:.6e} s, exact {period:.6e} s, relative {measured / period - 1:.2e}; "
      f"amplitude {max(angle):.4f} deg (started at 30)")

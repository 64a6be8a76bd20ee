#!/usr/bin/env python3
"""The roller's travel with and without rolling friction, against the closed form.

A cylinder (I = m R^2 / 2) rolling without slip, resisted by a torque b m g,
decelerates at a = (2/3) b g / R (the torque and the friction force at the
contact together) and stops after v0^2 / (2 a).
"""
import csv
import pathlib
import sys

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent
R, b, g, v0 = 0.005, 1e-4, 9.81, 0.1
a = 2.0 / 3.0 * b * g / R
stop = v0 * v0 / (2 * a)


def travel(case):
    rows = [r for r in csv.DictReader(open(case / "postProcessing/bodies.csv")) if r["body"] == "roller"]
    return [float(r["time"]) for r in rows], [1000 * float(r["x"]) for r in rows]


t, x = travel(here)
tr, xr = travel(here / "rigid")
closed = [1000 * (v0 * s - 0.5 * a * s * s if s < v0 / a else stop) for s in t]
fig, ax = plt.subplots(figsize=(7, 4.2))
ax.plot(tr, xr, label="rigid contact (rollingFriction 0)")
ax.plot(t, x, label="rollingFriction 0.1 mm")
ax.plot(t, closed, "k--", lw=1, label="closed form")
ax.set_xlabel("time [s]")
ax.set_ylabel("travel [mm]")
ax.set_title("rollingFriction: a rolling magnet stops")
ax.legend()
fig.tight_layout()
fig.savefig(here / "rollingFriction.png", dpi=100)
print(f"stopped after {x[-1]:.2f} mm (closed form {1000 * stop:.2f} mm); without rolling friction {xr[-1]:.2f} mm")
print("wrote rollingFriction.png")
# 1 ms steps: the stop lands within a step, the contact forms in the first: 2 %.
if abs(x[-1] - 1000 * stop) > 0.02 * 1000 * stop or xr[-1] < 0.99 * 1000 * v0 * t[-1]:
    sys.exit("rollingFriction: the roller's travel is not the closed form's")

#!/usr/bin/env python3
"""The nut's induced magnetization over time (from the time folders' bodies.yaml),
its distance to the magnet (bodies.csv) and the LLG sweeps per step (induction.csv)."""
import csv
import math
import pathlib

import matplotlib.pyplot as plt
import yaml

here = pathlib.Path(__file__).resolve().parent
mu0 = 4e-7 * math.pi
Js = float(yaml.safe_load(open(here / "constant/materials.yaml"))["steel"]["Js"])

# Time folders: names that are numbers and hold a bodies.yaml.
samples = []
for d in here.iterdir():
    try:
        float(d.name)
    except ValueError:
        continue
    if not (d / "bodies.yaml").is_file():
        continue
    state = yaml.safe_load(open(d / "bodies.yaml"))
    nut = next(b for b in state["bodies"] if b["name"] == "nut")
    m = nut["magnetization"]  # A/m, body frame
    samples.append((float(state["time"]), mu0 * math.sqrt(sum(x * x for x in m))))
samples.sort()
if not samples:
    raise SystemExit("plotMagnetization: no time folder with bodies.yaml: run magFoam first")

rows = list(csv.DictReader(open(here / "postProcessing/bodies.csv")))
pos = {}
for r in rows:
    pos.setdefault(r["body"], []).append((float(r["time"]), float(r["x"]), float(r["y"]), float(r["z"])))
gap = [(a[0], 1000 * (math.dist(a[1:], b[1:]))) for a, b in zip(pos["nut"], pos["magnet"])]
sweeps = list(csv.DictReader(open(here / "postProcessing/induction.csv")))

fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
ax.plot([t for t, _ in samples], [j / Js for _, j in samples], label="nut: mu0 |M| / Js")
ax.axhline(1.0, color="grey", lw=0.8, ls="--", label="saturation (|M| = Js / mu0)")
ax.set_ylim(0, 1.1)
ax.set_xlabel("time [s]")
ax.set_ylabel("mu0 |M| / Js")
axr = ax.twinx()
axr.plot([t for t, _ in gap], [g for _, g in gap], color="C1", label="centre distance to the magnet [mm]")
axr.set_ylabel("distance [mm]")
lines = ax.get_legend_handles_labels()[0] + axr.get_legend_handles_labels()[0]
ax.legend(lines, [l.get_label() for l in lines], loc="center right")
# Everything happens in the first ~10 ms (pulled in, then held): show those.
zoom = 0.03
ax.set_xlim(0, zoom)
ax.set_title(f"softIron: the nut's magnetization (Js = {Js} T); "
             f"at {samples[-1][0]:g} s: {samples[-1][1] / Js:.2f} Js, {gap[-1][1]:.2f} mm", fontsize=10)
ax2.plot([float(r["time"]) for r in sweeps], [int(r["iterations"]) for r in sweeps], lw=0.8)
ax2.set_xlabel("time [s]")
ax2.set_ylabel("LLG sweeps in the step")
ax2.set_xlim(0, zoom)
ax2.set_title("LLG sweeps per step (postProcessing/induction.csv)", fontsize=10)
fig.tight_layout()
fig.savefig(here / "magnetization.png", dpi=100)
print(f"final mu0|M| = {samples[-1][1]:.3f} T = {samples[-1][1] / Js:.2f} Js; distance {gap[-1][1]:.2f} mm")

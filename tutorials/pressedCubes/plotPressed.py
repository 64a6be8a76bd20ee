#!/usr/bin/env python3
"""Plot the force on `top` pressed into `bottom` (side face and pole face) for the
three overlap models against the depth: negative depth = gap. The component
along the pressing direction is drawn; the models agree while the cubes are
apart and differ only inside."""
import csv
import pathlib

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent
models = [("exterior", "exterior (default here)", "-", 2.5),
          ("amperian", "amperian", "--", 1.2),
          ("charge", "charge", ":", 1.5)]
layouts = [("side", "across a side face (x; M along z)", 0),
           ("pole", "across a pole face (z; M along z)", 2)]


def read(layout, model):
    depth, force = [], []
    with open(here / layout / "postProcessing" / f"forces_{model}.csv") as f:
        for row in csv.DictReader(f):
            if row["body"] == "top":
                # offset 0.5 mm = touching; beyond it the cubes overlap
                depth.append(1e3 * (float(row["offset"]) - 0.0005))
                force.append(row)
    return depth, force


fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
for ax, (layout, title, axis) in zip(axes, layouts):
    key = "F" + "xyz"[axis]
    for model, label, style, lw in models:
        depth, rows = read(layout, model)
        ax.plot(depth, [float(r[key]) for r in rows], style, lw=lw, label=label)
    ax.axvline(0, color="grey", lw=0.8)
    ax.set_xlabel("depth pressed in [mm] (negative: gap)")
    ax.set_ylabel(f"{key} on top [N] (negative: towards bottom)")
    ax.set_title(f"1 cm cube pressed into another, {title}", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(here / "pressedCubes.png", dpi=110)
print("wrote", here / "pressedCubes.png")

#!/usr/bin/env python3
"""Fig. 6: gap and energies of the blue cube over time, MBM vs EDM, with rigid
contacts (top) and with contacts that allow interpenetration (bottom)."""
import csv
import pathlib

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent


def series(folder):
    bodies = pathlib.Path(folder) / "postProcessing/bodies.csv"
    energy = pathlib.Path(folder) / "postProcessing/energy.csv"
    if not bodies.exists() or not energy.exists():
        return None
    b = [r for r in csv.DictReader(open(bodies)) if r["body"] == "blue"]
    e = list(csv.DictReader(open(energy)))
    return (b, e) if b and e else None


rows = (
    ("rigid contacts (ODE default), adaptive steps",
     ((here, "MBM, Amperian overlap"), (here / "charge", "MBM, charge overlap"), (here / "EDM", "EDM n=5"))),
    ("contacts allowing penetration (cfm 1e-2), dt = 1 ms",
     ((here / "penetrating-MBM", "MBM, Amperian overlap"), (here / "penetrating-EDM", "EDM n=5"))),
)
fig, axes = plt.subplots(2, 2, figsize=(12, 8.4))
for (title, variants), (ax, ax2) in zip(rows, axes):
    for folder, label in variants:
        s = series(folder)
        if not s:
            continue
        b, e = s
        gap = [1000 * (float(r["z"]) - 0.015) for r in b]
        ax.plot([float(r["time"]) for r in b], [min(max(g, -11), 11) for g in gap], label=label)
        e0 = float(e[0]["total"])
        ax2.plot([float(r["time"]) for r in e], [float(r["total"]) - e0 for r in e], label=label)
        vmax = max((float(r["vx"]) ** 2 + float(r["vy"]) ** 2 + float(r["vz"]) ** 2) ** 0.5 for r in b)
        growth = max(float(r["total"]) - e0 for r in e)
        print(f"{title} | {label}: max speed at write times {vmax:.3g} m/s, max energy growth {growth:.3g} J, "
              f"final gap {gap[-1]:.4g} mm, final kinetic energy {float(e[-1]['kinetic']):.3g} J")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("face gap [mm] (centre z - 15 mm; clipped to +-11)")
    ax.set_title(title)
    ax.legend()
    ax2.set_yscale("symlog", linthresh=1e-4)
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("total energy - initial [J]")
    ax2.set_title("energy created (> 0) or dissipated (< 0)")
    ax2.legend()
fig.tight_layout()
(here / "expected").mkdir(exist_ok=True)
fig.savefig(here / "expected/fig6.png", dpi=100)
print("wrote expected/fig6.png")

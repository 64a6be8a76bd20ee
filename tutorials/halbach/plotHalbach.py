#!/usr/bin/env python3
"""The Halbach array's one-sided field and the force on a steel plate on either side
(postProcessing/magField, above/, below/ and above.one/postProcessing/forces.csv)."""
import pathlib

import matplotlib.pyplot as plt
import numpy as np

here = pathlib.Path(__file__).resolve().parent
field = here / "postProcessing/magField"
data = np.genfromtxt(field / "section.csv", delimiter=",", names=True)
xs, zs = np.unique(data["x"]), np.unique(data["z"])
magB = data["magB"].reshape(len(zs), len(xs))  # x fastest, then z
Bx, Bz = data["Bx"].reshape(magB.shape), data["Bz"].reshape(magB.shape)
above = np.genfromtxt(field / "above.csv", delimiter=",", names=True)
below = np.genfromtxt(field / "below.csv", delimiter=",", names=True)

fig, (ax, ax2, ax3) = plt.subplots(1, 3, figsize=(16, 4.6), gridspec_kw={"width_ratios": [1.5, 1, 1]})
mm = 1e3
im = ax.imshow(magB, origin="lower", extent=[mm * xs[0], mm * xs[-1], mm * zs[0], mm * zs[-1]], cmap="rainbow",
               vmax=1.0)
ax.streamplot(mm * xs, mm * zs, Bx, Bz, color="k", density=1.1, linewidth=0.5, arrowsize=0.6)
# The five cubes and their magnetizations (+z, -x, -z, +x, +z).
for k, (mx, mz) in enumerate([(0, 1), (-1, 0), (0, -1), (1, 0), (0, 1)]):
    x0 = -25 + 10 * k
    ax.plot([x0, x0 + 10, x0 + 10, x0, x0], [-5, -5, 5, 5, -5], "w-", lw=1.2)
    ax.annotate("", xy=(x0 + 5 + 3.5 * mx, 3.5 * mz), xytext=(x0 + 5 - 3.5 * mx, -3.5 * mz),
                arrowprops=dict(arrowstyle="-|>", color="w", lw=2))
ax.axhline(8, color="w", ls="--", lw=0.8)
ax.axhline(-8, color="w", ls=":", lw=0.8)
ax.set_xlim(mm * xs[0], mm * xs[-1])
ax.set_ylim(mm * zs[0], mm * zs[-1])
ax.set_xlabel("x [mm]")
ax.set_ylabel("z [mm]")
ax.set_title("|B| and field lines on y = 0 (one body, five parts)")
fig.colorbar(im, ax=ax, label="|B| [T] (clipped at 1 T)")

ax2.plot(mm * above["x"], above["magB"], "C3-", label="3 mm above (strong side)")
ax2.plot(mm * below["x"], below["magB"], "C0-", label="3 mm below (weak side)")
ax2.axvspan(-25, 25, color="0.93")
ax2.set_xlabel("x [mm]")
ax2.set_ylabel("|B| [T]")
ax2.set_title("|B| along the array")
ax2.legend()


def plateForce(folder):
    f = np.genfromtxt(here / folder / "postProcessing/forces.csv", delimiter=",", names=True, dtype=None,
                      encoding="utf-8")
    plate = f[f["body"] == "plate"]
    return mm * (0.001 + plate["offset"]), np.abs(plate["Fz"]), plate["Fz"]


for folder, style, label in [("above", "C3-o", "above: 8 parts"), ("below", "C0-o", "below: 8 parts"),
                             ("above.one", "C3--", "above: one body (uniform M)")]:
    gap, F, Fz = plateForce(folder)
    ax3.semilogy(gap, F, style, ms=3, label=label)
ax3.set_xlabel("gap between array and plate [mm]")
ax3.set_ylabel("attraction |Fz| [N]")
ax3.set_title("40 x 10 x 2 mm steel plate")
ax3.grid(True, which="both", alpha=0.3)
ax3.legend()
fig.tight_layout()
fig.savefig(here / "halbach.png", dpi=100)

g_above, F_above, _ = plateForce("above")
g_below, F_below, _ = plateForce("below")
_, F_one, _ = plateForce("above.one")
print("wrote", here / "halbach.png")
print(f"max |B| 3 mm above {above['magB'].max():.3f} T, below {below['magB'].max():.3f} T")
for i in (0, 4, 20, 40):
    print(f"gap {g_above[i]:.0f} mm: above {F_above[i]:.4g} N, below {F_below[i]:.4g} N, "
          f"ratio {F_above[i] / F_below[i]:.2f}; one uniform body {F_one[i]:.3g} N")

#!/usr/bin/env python3
"""|B| over the cube's mid-section (paper Fig. 3a) from postProcessing/magField."""
import pathlib

import matplotlib.pyplot as plt
import numpy as np

here = pathlib.Path(__file__).resolve().parent
data = np.genfromtxt(here / "postProcessing/magField/section.csv", delimiter=",", names=True)
xs, zs = np.unique(data["x"]), np.unique(data["z"])
magB = data["magB"].reshape(len(zs), len(xs))  # x fastest, then z

axis = np.genfromtxt(here / "postProcessing/magField/axis.csv", delimiter=",", names=True)

fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
im = ax.imshow(magB, origin="lower", extent=[1e3 * xs[0], 1e3 * xs[-1], 1e3 * zs[0], 1e3 * zs[-1]],
               cmap="rainbow", vmax=np.percentile(magB, 99.5))
ax.plot([-5, 5, 5, -5, -5], [-5, -5, 5, 5, -5], "k-", lw=0.8)
ax.set_xlabel("x [mm]")
ax.set_ylabel("z [mm]")
ax.set_title("|B| on y = 0, cube magnetized +z (Eq. 11)")
fig.colorbar(im, ax=ax, label="|B| [T]")
ax2.plot(1e3 * axis["z"], axis["Bz"], label="Bz on the axis")
ax2.axvspan(-5, 5, color="0.9")
ax2.set_xlabel("z [mm]")
ax2.set_ylabel("Bz [T]")
ax2.set_title("Bz along the magnetization axis")
ax2.legend()
fig.tight_layout()
fig.savefig(here / "cubeField.png", dpi=110)
print("wrote", here / "cubeField.png")

"""magFoam from Python, notebook style (each "# %%" is a cell): the workflow
of a Magpylib user -- build magnets, map their field, compute forces -- on
magFoam's core (docs/python.md). SI units throughout: m, T, N, N m."""
# %% Setup
import os
import sys
import time

import matplotlib.pyplot as plt
import numpy as np

import magfoam as mf

print("magfoam", mf.__version__, "| field models:", ", ".join(mf.modules()["field"]))

# %% 1. A Halbach array: five 10 mm cubes whose magnetization turns by 90 deg
# from one to the next, so that the field adds up on one side of the array
# and largely cancels on the other.
EDGE = 0.01
halbach = mf.System(field={"type": "MBM"})
turns = [[0, 0, 1], [-1, 0, 0], [0, 0, -1], [1, 0, 0], [0, 0, 1]]
for k, m in enumerate(turns):
    halbach.add_body(f"cube{k}", box=[EDGE] * 3, Br=1.3, magnetization=m, position=[(k - 2) * EDGE, 0, 0], fixed=True)

x, z = np.linspace(-0.04, 0.04, 161), np.linspace(-0.025, 0.025, 101)
X, Z = np.meshgrid(x, z)
grid = np.stack([X, np.zeros_like(X), Z], axis=-1)  # (101, 161, 3) points of the x-z plane
t0 = time.perf_counter()
B = halbach.field(grid)                             # (101, 161, 3) tesla
seconds = time.perf_counter() - t0
print(f"field map: {grid.size // 3} points in {seconds * 1e3:.1f} ms ({grid.size // 3 / seconds:.3g} points/s)")
below, above = np.linalg.norm(halbach.field([[0, 0, -0.008], [0, 0, 0.008]]), axis=1)
print(f"|B| 3 mm below the array {below:.3f} T, 3 mm above {above:.3f} T "
      f"(strong side {'above' if above > below else 'below'}, {max(above, below) / min(above, below):.1f} x)")

# %% 2. Two cubes (paper Fig. 4): the force against the face gap, every gap
# in one sweep call, beside the closed form of Akoun & Yonnet (1984).
sys.path.insert(0, os.path.join(os.environ.get("MAGFOAM_DIR", "../.."), "tutorials", "twoCubes"))
import akounYonnet  # noqa: E402  (the twoCubes tutorial's closed form)

pair = mf.System(field={"type": "MBM"})
pair.add_body("a", box=[EDGE] * 3, Br=1.0, magnetization=[0, 0, 1], fixed=True)
pair.add_body("b", box=[EDGE] * 3, Br=1.0, magnetization=[0, 0, 1], position=[0, 0, 0.0102])
gaps = np.geomspace(1e-4, 0.03, 60)
t0 = time.perf_counter()
F, T = pair.sweep("b", positions=np.c_[np.zeros((len(gaps), 2)), EDGE + gaps])
seconds = time.perf_counter() - t0
exact = np.array([akounYonnet.force([EDGE] * 3, [0, 0, 0], [EDGE] * 3, [0, 0, EDGE + d], 1, 1)[2] for d in gaps])
error = np.abs(F[:, 2] / exact - 1)
print(f"force curve: {len(gaps)} poses in {seconds * 1e3:.1f} ms; relative error vs Akoun-Yonnet: "
      f"median {np.median(error):.1e}, max {error.max():.1e} at d = {gaps[error.argmax()] * 1e3:.3f} mm")

# %% 3. A small optimization: the gap at which the cubes pull with 10 N.
# Bracket it on the curve just computed, then bisect with single evaluations.
target = 10.0
k = np.flatnonzero(-F[:, 2] < target)[0]
lo, hi = gaps[k - 1], gaps[k]
calls = 0
while hi - lo > 1e-9:
    mid = 0.5 * (lo + hi)
    pair.set_pose("b", position=[0, 0, EDGE + mid])
    calls += 1
    if -pair.wrench("b")[0][2] > target:
        lo = mid
    else:
        hi = mid
gap = 0.5 * (lo + hi)
lo_e, hi_e = gaps[k - 1], gaps[k]  # the same on the closed form
while hi_e - lo_e > 1e-12:
    mid = 0.5 * (lo_e + hi_e)
    lo_e, hi_e = (mid, hi_e) if -akounYonnet.force([EDGE] * 3, [0, 0, 0], [EDGE] * 3, [0, 0, EDGE + mid], 1, 1)[2] > target else (lo_e, mid)
print(f"10 N at a gap of {gap * 1e3:.4f} mm ({calls} evaluations); Akoun-Yonnet: {lo_e * 1e3:.4f} mm")

# %% 4. A case folder, read and evaluated as magForces does (its forcesDict sweep).
case = mf.Case(os.path.join(os.environ.get("MAGFOAM_DIR", "../.."), "tutorials", "twoCubes"))
r = case.forces()  # dict of arrays: F, T, Tmag (steps, bodies, 3), offset (steps,), ...
i, top = np.argmin(np.abs(r["offset"] - 0.002)), r["bodies"].index("top")
print(f"{case!r}: {len(r['offset'])} sweep steps; Fz on 'top' at d = {r['offset'][i] * 1e3:.1f} mm: "
      f"{r['F'][i, top, 2]:.4f} N")

# %% Plots
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.6))
magnitude = np.linalg.norm(B, axis=-1)
pcm = ax1.pcolormesh(X * 1e3, Z * 1e3, magnitude, shading="auto", cmap="viridis", vmax=1.0)
ax1.streamplot(X * 1e3, Z * 1e3, B[..., 0], B[..., 2], color="w", density=1.2, linewidth=0.6, arrowsize=0.7)
for k, m in enumerate(turns):
    cx = (k - 2) * EDGE * 1e3
    ax1.add_patch(plt.Rectangle((cx - 5, -5), 10, 10, fill=False, ec="r", lw=1))
    ax1.annotate("", xy=(cx + 3.5 * m[0], 3.5 * m[2]), xytext=(cx - 3.5 * m[0], -3.5 * m[2]),
                 arrowprops=dict(arrowstyle="->", color="r", lw=1.5))
fig.colorbar(pcm, ax=ax1, label="|B| (T)")
ax1.set(xlabel="x (mm)", ylabel="z (mm)", title="Halbach array of five 10 mm cubes, Br = 1.3 T (y = 0)", aspect="equal")

ax2.loglog(gaps * 1e3, -exact, "k-", lw=3, alpha=0.35, label="Akoun-Yonnet (closed form)")
ax2.loglog(gaps * 1e3, -F[:, 2], "C0o", ms=3.5, label="magfoam sweep (MBM)")
ax2.axhline(target, color="C3", lw=0.8, ls="--")
ax2.plot(gap * 1e3, target, "C3s", label=f"10 N at {gap * 1e3:.3f} mm")
ax2.set(xlabel="face gap d (mm)", ylabel="attraction |Fz| (N)", title="Two 10 mm cubes, Br = 1 T, coaxial")
ax2.grid(True, which="both", alpha=0.3)
ax2.legend()
fig.tight_layout()
fig.savefig("magnets.png", dpi=110)
print("wrote magnets.png")

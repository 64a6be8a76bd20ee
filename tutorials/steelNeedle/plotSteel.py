#!/usr/bin/env python3
"""Soft steel in applied fields against the exact results.

needle/: a prolate spheroid (semi-axes a > b = c) of susceptibility chi in a
uniform field H at the angle theta to its long axis. Uniform M is exact for an
ellipsoid: M_i = k_i H_i with k_i = chi / (1 + chi N_i) on the principal axes,
N_a, N_b Osborn's demagnetizing factors. Its energy is
E = -1/2 mu0 V H.M = const + 1/2 mu0 V H^2 (k_a - k_b) sin^2(theta), so
phi = 2 theta swings as a pendulum: I phi'' = -mu0 V H^2 (k_a - k_b) sin(phi),
period T = 4 K(sin(theta0)) / w0, w0^2 = mu0 V H^2 (k_a - k_b) / I,
I = m (a^2 + b^2) / 5 about a short axis.

ball/: a sphere (N = 1/3) in B(r) = B0 + G r with G = diag(-g/2, -g/2, g),
on the z axis: F_z = V g k B_z / mu0, k = 3 chi / (chi + 3), so
z'' = w^2 (z + B0 / g), w^2 = g^2 k / (rho mu0):
z(t) = -B0 / g + (z0 + B0 / g) cosh(w t) from rest.
"""
import csv
import math
import pathlib

import matplotlib.pyplot as plt
import yaml

here = pathlib.Path(__file__).resolve().parent
mu0 = 4e-7 * math.pi
chi, rho = 1000.0, 7850.0


def rows(case, body):
    return [r for r in csv.DictReader(open(here / case / "postProcessing/bodies.csv")) if r["body"] == body]


def agm(x, y):
    while abs(x - y) > 1e-15 * x:
        x, y = (x + y) / 2, math.sqrt(x * y)
    return x


# --- needle
a, b = 0.005, 0.0005
m_ = a / b
Na = (m_ / math.sqrt(m_ * m_ - 1) * math.log(m_ + math.sqrt(m_ * m_ - 1)) - 1) / (m_ * m_ - 1)
Nb = (1 - Na) / 2
ka, kb = chi / (1 + chi * Na), chi / (1 + chi * Nb)
H = 0.005 / mu0
V = 4 / 3 * math.pi * a * b * b
I = rho * V * (a * a + b * b) / 5
theta0 = math.radians(30)
w0 = math.sqrt(mu0 * V * H * H * (ka - kb) / I)
period = 4 * (math.pi / (2 * agm(1.0, math.cos(theta0)))) / w0  # K(k = sin theta0)

n = rows("needle", "needle")
tn = [float(r["time"]) for r in n]
angle = [math.degrees(2 * math.atan2(float(r["qz"]), float(r["qw"]))) for r in n]
down = [tn[i - 1] + (tn[i] - tn[i - 1]) * angle[i - 1] / (angle[i - 1] - angle[i])
        for i in range(1, len(tn)) if angle[i - 1] > 0 >= angle[i]]
measured = (down[-1] - down[0]) / (len(down) - 1) if len(down) > 1 else float("nan")
# The first written state after the start (at t = 0 the soft body is not
# magnetized yet: the first step converges it): in the body frame the field is
# at -theta to the long axis x, theta the needle's angle then.
def timeOf(folder):
    try:
        return float(folder.name)
    except ValueError:
        return -1.0


first = min((d for d in (here / "needle").iterdir() if d.is_dir() and timeOf(d) > 0), key=timeOf)
state = yaml.safe_load(open(first / "bodies.yaml"))["bodies"][0]
Mx, My = state["magnetization"][:2]
qw, qz = state["orientation"][0], state["orientation"][3]
theta1 = 2 * math.atan2(qz, qw)
Mexact = (ka * H * math.cos(theta1), -kb * H * math.sin(theta1))

# --- ball
g, B0 = 1.0, 0.01
k = 3 * chi / (chi + 3)
w = g * math.sqrt(k / (rho * mu0))
ball = rows("ball", "ball")
tb = [float(r["time"]) for r in ball]
zb = [float(r["z"]) for r in ball]
zexact = [-B0 / g + B0 / g * math.cosh(w * t) for t in tb]
zerr = max(abs(z - e) for z, e in zip(zb, zexact)) / max(abs(e) for e in zexact)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
ax1.plot([1000 * x for x in tn], angle, label="magFoam (demag, free backend)")
for j in range(int(tn[-1] / period) + 1):
    ax1.axvline(1000 * j * period, color="grey", lw=0.6, ls="--")
ax1.set_xlabel("time [ms]")
ax1.set_ylabel("long axis to the field [deg]")
ax1.set_title(f"soft needle, 10 x 1 x 1 mm, chi 1000, 5 mT:\nperiod {1000 * measured:.3f} ms, "
              f"exact spheroid {1000 * period:.3f} ms (dashed)", fontsize=10)
ax1.legend(loc="upper right", fontsize=9)
ax2.plot(tb, [1000 * z for z in zb], lw=3, alpha=0.5, label="magFoam (demag, free backend)")
ax2.plot(tb, [1000 * z for z in zexact], "k--", lw=1, label="exact: -B0/g + B0/g cosh(w t)")
ax2.set_xlabel("time [s]")
ax2.set_ylabel("z [mm]")
ax2.set_title(f"steel ball, 10 mm, chi 1000, B = 10 mT + 1 T/m z:\nlargest error {zerr:.1e} of the travel",
              fontsize=10)
ax2.legend(loc="upper left", fontsize=9)
fig.tight_layout()
fig.savefig(here / "steelNeedle.png", dpi=100)
print(f"needle: N_a {Na:.6f}, N_b {Nb:.6f}; M at {math.degrees(theta1):.4f} deg (body frame): magFoam ({Mx:.6g}, {My:.6g}) A/m, "
      f"exact ({Mexact[0]:.6g}, {Mexact[1]:.6g}), relative {math.hypot(Mx - Mexact[0], My - Mexact[1]) / math.hypot(*Mexact):.2e}")
print(f"needle: period magFoam {measured:.6e} s, exact {period:.6e} s, relative {measured / period - 1:.2e}; "
      f"amplitude {max(angle):.4f} deg (started at 30)")
print(f"ball: z at {tb[-1]:g} s magFoam {zb[-1]:.6e} m, exact {zexact[-1]:.6e} m, relative {zb[-1] / zexact[-1] - 1:.2e}; "
      f"largest error {zerr:.2e} of the travel")

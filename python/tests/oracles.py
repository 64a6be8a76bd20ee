"""Independent references for the Python tests, in numpy: written from the
published closed forms (docs/physics.md#reference-values), not from the code
under test.

- akoun_yonnet_force: Akoun & Yonnet (1984), the force between two parallel
  cuboid magnets polarized along +z (charge model).
- cuboid_B: the field of a uniformly magnetized cuboid from its surface
  charges sigma = M.n (Furlani 2001; Camacho & Sosa 2013): B = mu0 (H + M)
  inside, mu0 H outside.
SI units: m, T, A/m, N.
"""
import numpy as np

MU0 = 4e-7 * np.pi


def _xlogy(c, y):
    # c ln y with the limit 0 where c == 0 (also for y == 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(c == 0.0, 0.0, c * np.log(np.where(c == 0.0, 1.0, y)))


def _r_minus(r, u, v, w):
    # r - u without cancellation for u > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(u > 0, (v * v + w * w) / (r + u), r - u)


def akoun_yonnet_force(size1, centre1, size2, centre2, J1, J2):
    """Force (N) on magnet 2; sizes are full edge lengths (m), J in tesla (+z).
    centre2 may be an array (k, 3): one force per row."""
    h1, h2 = 0.5 * np.asarray(size1, float), 0.5 * np.asarray(size2, float)
    d = np.atleast_2d(np.asarray(centre2, float)) - np.asarray(centre1, float)
    F = np.zeros_like(d)
    for i in (0, 1):
        for j in (0, 1):
            u = d[:, 0] + (-h2[0] if j else h2[0]) - (-h1[0] if i else h1[0])
            for k in (0, 1):
                for l in (0, 1):
                    v = d[:, 1] + (-h2[1] if l else h2[1]) - (-h1[1] if k else h1[1])
                    for p in (0, 1):
                        for q in (0, 1):
                            w = d[:, 2] + (-h2[2] if q else h2[2]) - (-h1[2] if p else h1[2])
                            s = -1.0 if (i + j + k + l + p + q) % 2 else 1.0
                            r = np.sqrt(u * u + v * v + w * w)
                            rmu, rmv = _r_minus(r, u, v, w), _r_minus(r, v, u, w)
                            # atan(u v / (r w)); 0 (the mean of the limits) at w == 0
                            at = np.where(w != 0.0, np.sign(w) * np.arctan2(u * v, r * np.abs(w)), 0.0)
                            F[:, 0] += s * (_xlogy(0.5 * (v * v - w * w), rmu) + _xlogy(u * v, rmv) + v * w * at + 0.5 * r * u)
                            F[:, 1] += s * (_xlogy(0.5 * (u * u - w * w), rmv) + _xlogy(u * v, rmu) + u * w * at + 0.5 * r * v)
                            F[:, 2] += s * (-_xlogy(u * w, rmu) - _xlogy(v * w, rmv) + u * v * at - r * w)
    return F * J1 * J2 / (4 * np.pi * MU0)


def _sheet_H(sigma, a, b, x, y, w):
    """H (A/m) of the rectangle [-a, a] x [-b, b] in the plane w = 0 with surface
    charge sigma, at points (x, y, w): arrays. ln(v + R) differences as asinh
    differences (accurate for either sign of v; rho = 0 only on edge lines)."""
    u1, u2, v1, v2 = -a - x, a - x, -b - y, b - y
    k = sigma / (4 * np.pi)

    def logdiff(rho, t1, t2):  # ln(t2 + R2) - ln(t1 + R1) = asinh(t2/rho) - asinh(t1/rho)
        return np.arcsinh(t2 / rho) - np.arcsinh(t1 / rho)

    Hx = k * (logdiff(np.hypot(u2, w), v1, v2) - logdiff(np.hypot(u1, w), v1, v2))
    Hy = k * (logdiff(np.hypot(v2, w), u1, u2) - logdiff(np.hypot(v1, w), u1, u2))

    def at(uu, vv):
        R = np.sqrt(uu * uu + vv * vv + w * w)
        return np.sign(w) * np.arctan2(uu * vv, np.abs(w) * R)

    Hw = k * (at(u2, v2) - at(u1, v2) - at(u2, v1) + at(u1, v1))
    return Hx, Hy, Hw


def cuboid_B(points, size, M, centre=(0, 0, 0), R=np.eye(3)):
    """B (T) at points (n, 3) of a cuboid of full edges `size` (m) centred at
    `centre`, body axes the columns of R, magnetization M (A/m, world frame)."""
    R = np.asarray(R, float)
    p = (np.asarray(points, float) - np.asarray(centre, float)) @ R  # body frame
    Mb = R.T @ np.asarray(M, float)
    h = 0.5 * np.asarray(size, float)
    H = np.zeros_like(p)
    for axis in range(3):  # the two faces normal to `axis`, charge +-Mb[axis]
        o1, o2 = [k for k in range(3) if k != axis]
        for sign in (1.0, -1.0):
            hx, hy, hw = _sheet_H(sign * Mb[axis], h[o1], h[o2], p[:, o1], p[:, o2], p[:, axis] - sign * h[axis])
            H[:, o1] += hx
            H[:, o2] += hy
            H[:, axis] += hw
    inside = np.all(np.abs(p) < h, axis=1)
    B = MU0 * (H + inside[:, None] * Mb)
    return B @ R.T  # world frame

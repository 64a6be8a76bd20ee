"""Akoun & Yonnet (1984) closed-form force between two parallel cuboid magnets
polarized along +z (charge model; finite through overlap). Sizes are full edge
lengths (m), J in tesla; returns the force on magnet 2 (N)."""
import math

MU0 = 4e-7 * math.pi


def _xlogy(c, y):
    return 0.0 if c == 0.0 else c * math.log(y)


def _r_minus(r, u, v, w):
    return (v * v + w * w) / (r + u) if u > 0 else r - u


def _phi(u, v, w):
    r = math.sqrt(u * u + v * v + w * w)
    rmu, rmv = _r_minus(r, u, v, w), _r_minus(r, v, u, w)
    at = 0.0
    if w != 0.0:  # at w == 0 (coplanar faces): mean of the one-sided limits
        at = math.atan2(u * v, r * abs(w)) * (1.0 if w > 0 else -1.0)
    fx = _xlogy(0.5 * (v * v - w * w), rmu) + _xlogy(u * v, rmv) + v * w * at + 0.5 * r * u
    fy = _xlogy(0.5 * (u * u - w * w), rmv) + _xlogy(u * v, rmu) + u * w * at + 0.5 * r * v
    fz = -_xlogy(u * w, rmu) - _xlogy(v * w, rmv) + u * v * at - r * w
    return fx, fy, fz


def force(size1, centre1, size2, centre2, J1, J2):
    h1 = [0.5 * s for s in size1]
    h2 = [0.5 * s for s in size2]
    d = [centre2[k] - centre1[k] for k in range(3)]
    total = [0.0, 0.0, 0.0]
    for i in (0, 1):
        for j in (0, 1):
            u = d[0] + (-h2[0] if j else h2[0]) - (-h1[0] if i else h1[0])
            for k in (0, 1):
                for l in (0, 1):
                    v = d[1] + (-h2[1] if l else h2[1]) - (-h1[1] if k else h1[1])
                    for p in (0, 1):
                        for q in (0, 1):
                            w = d[2] + (-h2[2] if q else h2[2]) - (-h1[2] if p else h1[2])
                            sign = -1.0 if (i + j + k + l + p + q) % 2 else 1.0
                            f = _phi(u, v, w)
                            for m in range(3):
                                total[m] += sign * f[m]
    c = J1 * J2 / (4 * math.pi * MU0)
    return [c * t for t in total]

#!/usr/bin/env python3
"""Result chart of a magFoam scene: the bodies' final positions (top and side
views of their meshes), kinetic and total energy over time, and for every
dynamic body the distance to its nearest neighbour body at the end.

    plotScene.py CASE_DIR OUT.png [--title T] [--compare DIR LABEL ...]

Reads CASE/constant/bodies.yaml (geometry: {file: ...} or {box: {size}}),
the binary or ASCII STL files it names, and CASE/postProcessing/bodies.csv
and energy.csv. Distances are from each mesh's vertices to the other's triangles, both ways:
exact, except where the closest points lie on two edges (then an upper bound).
Extra --compare cases add their energy curves (e.g. the EDM variant).
"""
import argparse
import csv
import pathlib
import struct

import matplotlib.pyplot as plt
import numpy as np
import yaml
from matplotlib.collections import PolyCollection


def read_stl(path):
    data = pathlib.Path(path).read_bytes()
    if len(data) >= 84:
        n = struct.unpack("<I", data[80:84])[0]
        if len(data) == 84 + 50 * n:
            tri = np.frombuffer(data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
            return tri["v"].astype(float)
    tris, cur = [], []
    for line in data.decode(errors="replace").splitlines():
        w = line.split()
        if w and w[0] == "vertex":
            cur.append([float(x) for x in w[1:4]])
            if len(cur) == 3:
                tris.append(cur)
                cur = []
    return np.array(tris)


def point_triangle_distance(p, tri):
    """Distances from points p (n, 3) to triangles tri (m, 3, 3): (n, m) array.
    Closest point by the Voronoi regions of the triangle (Ericson, Real-Time
    Collision Detection, 5.1.5), vectorized."""
    a, b, c = (tri[None, :, i, :] for i in range(3))
    p = p[:, None, :]
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = (ab * ap).sum(-1), (ac * ap).sum(-1)
    bp = p - b
    d3, d4 = (ab * bp).sum(-1), (ac * bp).sum(-1)
    cp = p - c
    d5, d6 = (ab * cp).sum(-1), (ac * cp).sum(-1)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v = np.where(denom != 0, vb / denom, 0.0)
        w = np.where(denom != 0, vc / denom, 0.0)
        q = a + ab * v[..., None] + ac * w[..., None]  # inside the face
        t_ab = np.clip(d1 / np.where(d1 - d3 != 0, d1 - d3, 1), 0, 1)
        t_ac = np.clip(d2 / np.where(d2 - d6 != 0, d2 - d6, 1), 0, 1)
        t_bc = np.clip((d4 - d3) / np.where((d4 - d3) + (d5 - d6) != 0, (d4 - d3) + (d5 - d6), 1), 0, 1)
    edge_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
    edge_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
    edge_bc = (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
    q = np.where(edge_bc[..., None], b + (c - b) * t_bc[..., None], q)
    q = np.where(edge_ac[..., None], a + ac * t_ac[..., None], q)
    q = np.where(edge_ab[..., None], a + ab * t_ab[..., None], q)
    q = np.where(((d6 >= 0) & (d5 <= d6))[..., None], c, q)
    q = np.where(((d3 >= 0) & (d4 <= d3))[..., None], b, q)
    q = np.where(((d1 <= 0) & (d2 <= 0))[..., None], a, q)
    return np.sqrt(((p - q) ** 2).sum(-1))


def surface_distance(va, ta, vb, tb):
    """Smallest vertex-to-triangle distance between two meshes, both ways (exact
    unless the closest points are on two edges; then an upper bound)."""
    best = np.inf
    for v, t in ((va, tb), (vb, ta)):
        for i in range(0, len(v), 64):
            best = min(best, point_triangle_distance(v[i:i + 64], t).min())
    return best


def box_triangles(size):
    h = np.array(size) / 2
    c = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * h
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return np.array([[c[a], c[b], c[d]] for a, b, _, d in faces] + [[c[b], c[cc], c[d]] for _, b, cc, d in faces])


def quat_matrix(w, x, y, z):
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def load_meshes(case):
    spec = yaml.safe_load(open(case / "constant/bodies.yaml"))
    meshes, fixed = {}, {}
    for b in spec["bodies"]:
        g = b["geometry"]
        if "file" in g:
            tri = read_stl(case / "constant" / g["file"])
            tri = tri * float(g.get("scale", 1.0))
        elif "box" in g:
            tri = box_triangles(g["box"]["size"])
        else:
            continue
        # bodies are placed by their centre of mass: centre the vertices on the
        # area-weighted... volume centroid of the closed mesh
        v0, v1, v2 = tri[:, 0], tri[:, 1], tri[:, 2]
        vol = np.einsum("ij,ij->i", v0, np.cross(v1, v2)) / 6
        com = ((v0 + v1 + v2) / 4 * vol[:, None]).sum(0) / vol.sum()
        meshes[b["name"]] = tri - com
        fixed[b["name"]] = b.get("motion", "dynamic") == "fixed"
    return meshes, fixed


def final_state(case):
    rows = list(csv.DictReader(open(case / "postProcessing/bodies.csv")))
    last = rows[-1]["time"]
    return float(last), {r["body"]: r for r in rows if r["time"] == last}


def world(tri, r):
    R = quat_matrix(*(float(r[k]) for k in ("qw", "qx", "qy", "qz")))
    return tri @ R.T + np.array([float(r["x"]), float(r["y"]), float(r["z"])])


def energies(case):
    e = list(csv.DictReader(open(case / "postProcessing/energy.csv")))
    t = np.array([float(r["time"]) for r in e])
    return t, np.array([float(r["kinetic"]) for r in e]), np.array([float(r["total"]) for r in e])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("out")
    ap.add_argument("--title", default="")
    ap.add_argument("--compare", nargs=2, action="append", default=[], metavar=("DIR", "LABEL"))
    ap.add_argument("--label", default="MBM (hybrid)")
    a = ap.parse_args()
    case = pathlib.Path(a.case).resolve()
    meshes, fixed = load_meshes(case)
    t_end, state = final_state(case)
    placed = {n: world(meshes[n], state[n]) for n in meshes if n in state}

    # nearest neighbour body (vertex to triangle), and whether it lies on the ground
    verts = {n: np.unique(p.reshape(-1, 3), axis=0) for n, p in placed.items()}
    worst = 0.0
    lines = []
    for n, v in verts.items():
        if fixed[n]:
            continue
        best, other = np.inf, "-"
        for m, w in verts.items():
            if m == n:
                continue
            # skip bodies whose vertices are all farther than the best so far
            lo = np.linalg.norm(v.mean(0) - w.mean(0)) - np.linalg.norm(v - v.mean(0), axis=1).max() \
                - np.linalg.norm(w - w.mean(0), axis=1).max()
            if lo >= best:
                continue
            d = surface_distance(v, placed[n], w, placed[m])
            if d < best:
                best, other = d, m
        worst = max(worst, best)
        ground = " (on the ground)" if v[:, 2].min() < 5e-5 else ""
        lines.append(f"  {n}: nearest body {other} at {1000 * best:.3f} mm{ground}")
    print(f"t = {t_end:g} s: largest distance of a body to its nearest neighbour body {1000 * worst:.3f} mm"
          " (vertex to triangle)")
    print("\n".join(lines))

    fig = plt.figure(figsize=(14, 4.6))
    axes = [fig.add_subplot(1, 3, i + 1) for i in range(3)]
    for ax, (i, j), name in ((axes[0], (0, 1), "top view (x, y)"), (axes[1], (0, 2), "side view (x, z)")):
        for n, p in placed.items():
            # draw far faces first: sort triangles by the hidden coordinate
            k = 3 - i - j
            order = np.argsort(p[:, :, k].mean(1) if k == 2 else -p[:, :, k].mean(1))
            colour = "tab:red" if fixed[n] else "tab:blue"
            ax.add_collection(PolyCollection(1000 * p[order][:, :, [i, j]], facecolors=colour, edgecolors="k",
                                             linewidths=0.1, alpha=0.6))
        allp = 1000 * np.concatenate([p.reshape(-1, 3) for p in placed.values()])
        ax.set_xlim(allp[:, i].min() - 2, allp[:, i].max() + 2)
        ax.set_ylim(allp[:, j].min() - 2, allp[:, j].max() + 2)
        ax.set_aspect("equal")
        ax.set_xlabel("xyz"[i] + " [mm]")
        ax.set_ylabel("xyz"[j] + " [mm]")
        ax.set_title(f"{name}, t = {t_end:g} s")
    ax = axes[2]
    for d, label in [(str(case), a.label)] + a.compare:
        d = pathlib.Path(d)
        if not (d / "postProcessing/energy.csv").exists():
            continue
        t, ke, tot = energies(d)
        ax.plot(t, tot - tot[0], label=f"{label}: total - initial")
        ax.plot(t, ke, "--", label=f"{label}: kinetic")
    ax.set_yscale("symlog", linthresh=1e-6)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy [J]")
    ax.set_title("energy")
    ax.legend(fontsize=7)
    fig.suptitle(a.title)
    fig.tight_layout()
    out = pathlib.Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Result chart of a magFoam scene: the bodies' final positions (top and side
views of their meshes), kinetic and total energy over time, and for every
dynamic body the distance to its nearest neighbour (another body or the
ground) at the end.

    plotScene.py CASE_DIR OUT.png [--title T] [--compare DIR LABEL ...]

Reads CASE/constant/bodies.yaml (geometry: {file: ...} or {box: {size}}),
the binary or ASCII STL files it names, and CASE/postProcessing/bodies.csv
and energy.csv. Distances are between mesh vertices and the other meshes'
vertices (an upper bound of the true gap, exact to the mesh spacing).
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

    # nearest neighbour body (vertex to vertex), and whether it lies on the ground
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
            d = np.sqrt(((v[:, None, :] - w[None, :, :]) ** 2).sum(-1).min())
            if d < best:
                best, other = d, m
        worst = max(worst, best)
        ground = " (on the ground)" if v[:, 2].min() < 5e-5 else ""
        lines.append(f"  {n}: nearest body {other} at {1000 * best:.3f} mm{ground}")
    print(f"t = {t_end:g} s: largest distance of a body to its nearest neighbour body {1000 * worst:.3f} mm"
          " (vertex to vertex, an upper bound)")
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

#!/usr/bin/env python3
"""Result chart and movie of any magFoam scene.

    plotScene.py CASE_DIR [OUT.png] [--title T] [--compare DIR LABEL ...]
                 [--movie FILE.gif|FILE.mp4] [--frames N] [--fps F] [--end T]

OUT.png: the bodies' final positions (top and side views), kinetic and total
energy over time, and for every dynamic body the distance to its nearest
neighbour body (printed). Distances are from each mesh's vertices to the
other's triangles, both ways: exact, except where the closest points lie on
two edges (then an upper bound). Extra --compare cases add their energy curves
(e.g. the EDM variant).

--movie FILE: the two views over time, at most --frames frames (default 60)
spread evenly over the written times (up to --end), --fps per second (default
15). A .gif is written with Pillow; an .mp4 needs ffmpeg (Debian package ffmpeg).

Reads CASE/constant/bodies.yaml: every geometry magFoam reads (box, sphere,
cylinder, and mesh files: STL ascii or binary, OBJ, PLY ascii or binary, OFF,
with scale), built as core/src/MeshPrimitives.cpp builds them and placed by
their centre of mass as magFoam does. The poses over time come from
CASE/postProcessing/bodies.csv, else from the time folders' bodies.yaml; a
case that has not run is drawn as constant/bodies.yaml places it.
"""
import argparse
import csv
import pathlib
import re
import struct
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


class SceneError(Exception):
    """An input that cannot be drawn; main prints it and exits 1."""


class _Loader(yaml.SafeLoader):
    """Every scalar a string, converted where it is used, as yaml-cpp does: a
    body named off or 007 stays "off" and "007" (not False and 7)."""


_Loader.yaml_implicit_resolvers = {}


def read_yaml(path):
    try:
        return yaml.load(pathlib.Path(path).read_text(), Loader=_Loader)
    except yaml.YAMLError as e:
        raise SceneError(f"{path}: malformed YAML: {e}") from None


# ---------------------------------------------------------------------------
# Mesh files: triangles as an (n, 3, 3) array, polygons split into fans (as
# assimp's aiProcess_Triangulate does for the C++ reader).

def _fans(vertices, faces, path):
    """Triangles of polygon faces (lists of vertex indices, or an (n, k) array)
    over vertices (m, 3)."""
    vertices = np.asarray(vertices, dtype=float).reshape(-1, 3)
    if isinstance(faces, np.ndarray):  # equal polygons, from a binary PLY
        k = np.arange(1, faces.shape[1] - 1)
        idx = np.stack([np.repeat(faces[:, :1], len(k), 1), faces[:, k], faces[:, k + 1]], axis=2).reshape(-1, 3)
    else:
        idx = np.array([(f[0], f[k], f[k + 1]) for f in faces for k in range(1, len(f) - 1)],
                       dtype=np.int64).reshape(-1, 3)
    bad = idx[(idx < 0) | (idx >= len(vertices))]
    if len(bad):
        raise SceneError(f"{path}: a face refers to vertex {bad[0]} (counting from 0) of {len(vertices)}")
    return vertices[idx]


def read_stl(path):
    data = pathlib.Path(path).read_bytes()
    # Binary when the size matches the triangle count (a binary header may
    # start with "solid" too).
    if len(data) >= 84:
        n = struct.unpack("<I", data[80:84])[0]
        if len(data) == 84 + 50 * n:
            tri = np.frombuffer(data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
            return tri["v"].astype(float)
    if not data.lstrip().lower().startswith(b"solid"):
        raise SceneError(f"{path}: neither binary STL (size {len(data)} bytes does not match its triangle count)"
                         " nor ASCII STL (no 'solid' at the start)")
    corners = []
    for line in data.decode(errors="replace").splitlines():
        w = line.split()
        if w and w[0] == "vertex":
            corners.append([float(x) for x in w[1:4]])
    if len(corners) % 3:
        raise SceneError(f"{path}: ASCII STL with {len(corners)} vertices, not a multiple of 3")
    return np.array(corners, dtype=float).reshape(-1, 3, 3)


def read_obj(path):
    vertices, faces = [], []
    for line in pathlib.Path(path).read_text(errors="replace").splitlines():
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            vertices.append([float(x) for x in w[1:4]])
        elif w[0] == "f":
            # "f 1 2 3", "f 1/1/1 ...", "f 1//1 ..."; negative: from the end
            idx = [int(x.split("/")[0]) for x in w[1:]]
            faces.append([i - 1 if i > 0 else len(vertices) + i for i in idx])
    return _fans(vertices, faces, path)


_PLY_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
              "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
              "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


def read_ply(path):
    data = pathlib.Path(path).read_bytes()
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise SceneError(f"{path}: not a PLY file (no 'ply' ... 'end_header')")
    body = data[data.index(b"\n", end) + 1:]
    fmt, elements = None, []  # elements: [name, count, [(name, type) or (name, (count type, item type))]]
    for line in data[:end].decode(errors="replace").splitlines():
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append([w[1], int(w[2]), []])
        elif w[0] == "property":
            if w[1] == "list":
                elements[-1][2].append((w[4], (_PLY_TYPES[w[2]], _PLY_TYPES[w[3]])))
            else:
                elements[-1][2].append((w[2], _PLY_TYPES[w[1]]))
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise SceneError(f"{path}: unknown PLY format '{fmt}'")
    vertices, faces = None, []
    if fmt == "ascii":
        tokens = body.split()
        pos = 0
        for name, count, props in elements:
            rows = []
            for _ in range(count):
                row = []
                for _, t in props:
                    if isinstance(t, tuple):
                        n = int(tokens[pos])
                        row.append([int(x) for x in tokens[pos + 1:pos + 1 + n]])
                        pos += 1 + n
                    else:
                        row.append(float(tokens[pos]))
                        pos += 1
                rows.append(row)
            if name == "vertex":
                names = [p[0] for p in props]
                vertices = [[r[names.index(k)] for k in "xyz"] for r in rows]
            elif name == "face":
                faces = [next(v for v in r if isinstance(v, list)) for r in rows]
        return _fans(vertices, faces, path)
    e = "<" if fmt == "binary_little_endian" else ">"
    pos = 0
    for name, count, props in elements:
        if all(not isinstance(t, tuple) for _, t in props):
            dt = np.dtype([(p, e + t) for p, t in props])
            rows = np.frombuffer(body, dtype=dt, count=count, offset=pos)
            pos += dt.itemsize * count
            if name == "vertex":
                vertices = np.stack([rows[k].astype(float) for k in "xyz"], axis=1)
            continue
        if name == "face" and len(props) == 1 and count:
            # one list of equal length (all triangles, all quads): read at once
            ct, it = np.dtype(e + props[0][1][0]), np.dtype(e + props[0][1][1])
            n = int(np.frombuffer(body, ct, 1, pos)[0])
            dt = np.dtype([("n", ct), ("v", it, (n,))])
            if pos + dt.itemsize * count <= len(body):
                rows = np.frombuffer(body, dt, count, pos)
                if (rows["n"] == n).all():
                    faces = rows["v"].astype(np.int64)
                    pos += dt.itemsize * count
                    continue
        rows = []
        for _ in range(count):
            row = []
            for _, t in props:
                if isinstance(t, tuple):
                    ct, it = np.dtype(e + t[0]), np.dtype(e + t[1])
                    n = int(np.frombuffer(body, ct, 1, pos)[0])
                    row.append(np.frombuffer(body, it, n, pos + ct.itemsize).tolist())
                    pos += ct.itemsize + n * it.itemsize
                else:
                    pos += np.dtype(t).itemsize
            rows.append(row)
        if name == "face":
            faces = [r[0] for r in rows]
    if vertices is None:
        raise SceneError(f"{path}: PLY without a vertex element")
    return _fans(vertices, faces, path)


def read_off(path):
    lines = [ln.split("#")[0].split() for ln in pathlib.Path(path).read_text(errors="replace").splitlines()]
    lines = [w for w in lines if w]
    if not lines or not re.fullmatch(r"(ST)?C?N?OFF", lines[0][0]):
        raise SceneError(f"{path}: not an OFF file (no 'OFF' at the start)")
    # the counts after the keyword or on the next line; then one vertex and
    # one face a line (extra numbers: colours, normals, texture coordinates)
    counts, rows = (lines[0][1:], lines[1:]) if len(lines[0]) > 1 else (lines[1], lines[2:])
    nv, nf = int(counts[0]), int(counts[1])
    vertices = [[float(x) for x in w[:3]] for w in rows[:nv]]
    faces = [[int(x) for x in w[1:1 + int(w[0])]] for w in rows[nv:nv + nf]]
    if len(vertices) < nv or len(faces) < nf:
        raise SceneError(f"{path}: OFF file ends early ({len(vertices)} of {nv} vertices, {len(faces)} of {nf} faces)")
    return _fans(vertices, faces, path)


MESH_READERS = {".stl": read_stl, ".obj": read_obj, ".ply": read_ply, ".off": read_off}


def read_mesh(path):
    path = pathlib.Path(path)
    ext = path.suffix.lower()
    if ext not in MESH_READERS:
        raise SceneError(f"{path}: plotScene reads {', '.join(MESH_READERS)} meshes, not '{ext}'")
    if not path.is_file():
        raise SceneError(f"{path}: file not found")
    try:
        tri = MESH_READERS[ext](path)
    except SceneError:
        raise
    except (ValueError, IndexError, KeyError, struct.error, StopIteration) as e:
        raise SceneError(f"{path}: cannot read the {ext[1:].upper()} mesh ({type(e).__name__}: {e})") from e
    if len(tri) == 0:
        raise SceneError(f"{path}: the file holds no triangles")
    return tri


# ---------------------------------------------------------------------------
# Primitives, as core/src/MeshPrimitives.cpp builds them (outward triangles).

def box_triangles(size):
    s = np.asarray(size, dtype=float)
    v = np.array([[(i & 1) * 2 - 1, (i >> 1 & 1) * 2 - 1, (i >> 2 & 1) * 2 - 1] for i in range(8)]) * s / 2
    t = [(0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5), (0, 1, 5), (0, 5, 4),
         (2, 6, 7), (2, 7, 3), (0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6)]
    return v[np.array(t)]


def icosphere_triangles(radius, subdivisions):
    g = (1 + 5 ** 0.5) / 2
    v = [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g),
         (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]
    v = [np.array(p) / np.linalg.norm(p) for p in v]
    t = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        mid = {}

        def m(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                mid[key] = len(v)
                p = v[a] + v[b]
                v.append(p / np.linalg.norm(p))
            return mid[key]

        t = [f for a, b, c in t for ab, bc, ca in [(m(a, b), m(b, c), m(c, a))]
             for f in ((a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca))]
    return radius * np.array(v)[np.array(t)]


def cylinder_triangles(radius, height, segments):
    """Axis along body z, centred: z from -height/2 to height/2."""
    n = segments
    phi = 2 * np.pi * np.arange(n) / n
    ring = np.stack([radius * np.cos(phi), radius * np.sin(phi), np.zeros(n)], axis=1)
    v = np.concatenate([ring - [0, 0, height / 2], ring + [0, 0, height / 2], [[0, 0, -height / 2], [0, 0, height / 2]]])
    t = []
    for i in range(n):
        j = (i + 1) % n
        t += [(i, j, n + j), (i, n + j, n + i), (2 * n + 1, n + i, n + j), (2 * n, j, i)]
    return v[np.array(t)]


def _positive(s):
    try:
        return float(s) > 0
    except (TypeError, ValueError):
        return False


def _number(d, key, where, default=None, positive=True):
    if key not in d:
        if default is None:
            raise SceneError(f"{where}: '{key}' missing")
        return default
    try:
        x = float(d[key])
    except (TypeError, ValueError):
        raise SceneError(f"{where}: '{key}' must be a number, got {d[key]!r}") from None
    if positive and not x > 0:
        raise SceneError(f"{where}: '{key}' must be positive, got {x:g}")
    return x


def body_triangles(g, constant, where, cache):
    """The body-frame triangles of one geometry entry, centred on the centre of
    mass (magFoam places bodies by it). Identical entries share one mesh."""
    kinds = [k for k in ("box", "sphere", "cylinder", "file") if k in (g or {})]
    if len(kinds) != 1:
        raise SceneError(f"{where}: give exactly one of box, sphere, cylinder or file, got {g!r}")
    key = repr(sorted(g.items()))
    if key in cache:
        return cache[key]
    kind = kinds[0]
    if kind == "box":
        size = g["box"].get("size") if isinstance(g["box"], dict) else None
        if not (isinstance(size, list) and len(size) == 3 and all(_positive(s) for s in size)):
            raise SceneError(f"{where}.box: size must be 3 positive lengths, got {size!r}")
        tri = box_triangles([float(s) for s in size])
    elif kind == "sphere":
        d = g["sphere"]
        tri = icosphere_triangles(_number(d, "radius", where + ".sphere"),
                                  int(_number(d, "subdivisions", where + ".sphere", 3, positive=False)))
    elif kind == "cylinder":
        d = g["cylinder"]
        tri = cylinder_triangles(_number(d, "radius", where + ".cylinder"), _number(d, "height", where + ".cylinder"),
                                 int(_number(d, "segments", where + ".cylinder", 32)))
    else:
        tri = read_mesh(constant / str(g["file"])) * _number(g, "scale", where, 1.0)
    v0, v1, v2 = tri[:, 0], tri[:, 1], tri[:, 2]
    vol = np.einsum("ij,ij->i", v0, np.cross(v1, v2)) / 6
    if not abs(vol.sum()) > 0:
        raise SceneError(f"{where}: the mesh encloses no volume")
    com = ((v0 + v1 + v2) / 4 * vol[:, None]).sum(0) / vol.sum()
    cache[key] = tri - com
    return cache[key]


def quat_matrix(w, x, y, z):
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def initial_quat(o, where):
    """constant/bodies.yaml orientation: {axis, angle: degrees} or {quaternion: [w, x, y, z]}."""
    if not o:
        return np.array([1.0, 0, 0, 0])
    if "quaternion" in o:
        q = np.array(o["quaternion"], dtype=float)
    else:
        axis = np.array(o["axis"], dtype=float)
        if not np.linalg.norm(axis) > 0:
            raise SceneError(f"{where}.orientation: axis has zero length")
        half = np.radians(float(o["angle"])) / 2
        q = np.concatenate([[np.cos(half)], np.sin(half) * axis / np.linalg.norm(axis)])
    return q / np.linalg.norm(q)


def compound_triangles(b, case, where, cache):
    """The body-frame triangles of a compound (`parts:`; docs/compound-bodies.md):
    each part's placed in the layout, the whole moved to the compound's centre
    of mass (each part weighted by its material's density)."""
    materials = read_yaml(case / "constant/materials.yaml") or {}
    placed, masses, centres = [], [], []
    for k, part in enumerate(b["parts"]):
        pw = f"{where}.parts[{k}]"
        tri = body_triangles(part.get("geometry"), case / "constant", pw + ".geometry", cache)
        v0, v1, v2 = tri[:, 0], tri[:, 1], tri[:, 2]
        volume = abs(np.einsum("ij,ij->i", v0, np.cross(v1, v2)).sum() / 6)
        material = materials.get(part.get("material"))
        if not isinstance(material, dict):
            raise SceneError(f"{pw}: material {part.get('material')!r} is not in constant/materials.yaml")
        R = quat_matrix(*initial_quat(part.get("orientation"), pw))
        p = np.array(part.get("position", [0, 0, 0]), dtype=float).reshape(3)
        placed.append(tri @ R.T + p)
        masses.append(float(material["density"]) * volume)
        centres.append(p)
    com = (np.array(masses)[:, None] * np.array(centres)).sum(0) / sum(masses)
    return np.concatenate(placed) - com


def load_scene(case):
    """[(name, body-frame triangles, fixed, initial pose [x y z qw qx qy qz])]"""
    path = case / "constant/bodies.yaml"
    if not path.is_file():
        raise SceneError(f"{path}: file not found (is {case} a magFoam case?)")
    spec = read_yaml(path)
    bodies, cache = [], {}
    for i, b in enumerate((spec or {}).get("bodies") or []):
        where = f"{path}: bodies[{i}] ('{b.get('name', '?')}')"
        try:
            if "parts" in b:
                tri = compound_triangles(b, case, where, cache)
            else:
                tri = body_triangles(b.get("geometry"), case / "constant", where + ".geometry", cache)
            pose = np.concatenate([np.array(b.get("position", [0, 0, 0]), dtype=float).reshape(3),
                                   initial_quat(b.get("orientation"), where)])
            bodies.append((str(b["name"]), tri, b.get("motion", "dynamic") == "fixed", pose))
        except (KeyError, TypeError, ValueError, AttributeError) as e:
            raise SceneError(f"{where}: {type(e).__name__}: {e} (magCheckMesh names the key)") from None
    if not bodies:
        raise SceneError(f"{path}: no bodies")
    return bodies


# ---------------------------------------------------------------------------
# Poses over time

POSE = ("x", "y", "z", "qw", "qx", "qy", "qz")


def load_poses(case, bodies):
    """(times (T,), {name: (T, 7) poses}, source): bodies.csv, else the time
    folders' bodies.yaml, else the initial state of constant/bodies.yaml."""
    names = [b[0] for b in bodies]
    csv_path = case / "postProcessing/bodies.csv"
    rows_by_time = {}
    source = None
    if csv_path.is_file():
        for r in csv.DictReader(open(csv_path)):
            try:
                rows_by_time.setdefault(float(r["time"]), {})[r["body"]] = [float(r[k]) for k in POSE]
            except (TypeError, ValueError, KeyError):
                pass  # a line cut short by an interrupted run: its time is dropped below
        source = str(csv_path.relative_to(case))
    else:
        for d in case.iterdir():
            if not (d / "bodies.yaml").is_file() or not re.fullmatch(r"[-+0-9.eE]+", d.name):
                continue
            state = read_yaml(d / "bodies.yaml")
            rows_by_time[float(state["time"])] = {b["name"]: list(b["position"]) + list(b["orientation"])
                                                  for b in state["bodies"]}
        if rows_by_time:
            source = "time folders"
    if not rows_by_time:
        return np.zeros(1), {n: b[3][None, :] for n, b in zip(names, bodies)}, "constant/bodies.yaml (not run)"
    times = np.array(sorted(rows_by_time))
    if len(times) > 1 and any(n not in rows_by_time[times[-1]] for n in names):
        print(f"plotScene: {source}: t = {times[-1]:g} is incomplete (an interrupted run?); drawn up to {times[-2]:g}")
        times = times[:-1]
    poses = {}
    for n in names:
        missing = [t for t in times if n not in rows_by_time[t]]
        if missing:
            raise SceneError(f"{case / source}: no pose of body '{n}' at t = {missing[0]:g}"
                             " (results of another constant/bodies.yaml?)")
        poses[n] = np.array([rows_by_time[t][n] for t in times], dtype=float)
    return times, poses, source


def world(tri, pose):
    return tri @ quat_matrix(*pose[3:]).T + pose[:3]


# ---------------------------------------------------------------------------
# Distances

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


def report_distances(placed, fixed, t_end):
    verts = {n: np.unique(p.reshape(-1, 3), axis=0) for n, p in placed.items()}
    worst = 0.0
    lines = []
    for n, v in verts.items():
        lo_hi = " x ".join(f"[{1000 * v[:, k].min():.3f}, {1000 * v[:, k].max():.3f}]" for k in range(3))
        if fixed[n] or len(verts) < 2:
            lines.append(f"  {n}: {lo_hi} mm")
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
        lines.append(f"  {n}: {lo_hi} mm, nearest body {other} at {1000 * best:.3f} mm{ground}")
    if len(verts) > 1:
        print(f"t = {t_end:g} s: largest distance of a body to its nearest neighbour body {1000 * worst:.3f} mm"
              " (vertex to triangle)")
    print("bodies (x, y, z extents, nearest neighbour):")
    print("\n".join(lines))


# ---------------------------------------------------------------------------
# Drawing

VIEWS = (((0, 1), "top view (x, y)"), ((0, 2), "side view (x, z)"))
COLOURS = {False: np.array(matplotlib.colors.to_rgb("tab:blue")), True: np.array(matplotlib.colors.to_rgb("tab:red"))}


def draw_view(ax, placed, fixed, i, j, collection=None):
    """Faces turned to the viewer (top: from +z, side: from -y), far ones
    first, shaded by how squarely they face the viewer; fixed bodies red."""
    k = 3 - i - j
    toward = 1.0 if k == 2 else -1.0
    polys, colours, depth = [], [], []
    for n, p in placed.items():
        nrm = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        length = np.linalg.norm(nrm, axis=1)
        facing = toward * nrm[:, k] / np.where(length > 0, length, 1)
        front = facing > 1e-9
        polys.append(1000 * p[front][:, :, [i, j]])
        colours.append(COLOURS[fixed[n]][None, :] * (0.45 + 0.55 * facing[front, None]))
        depth.append(toward * p[front][:, :, k].mean(1))
    polys, colours, depth = np.concatenate(polys), np.concatenate(colours), np.concatenate(depth)
    order = np.argsort(depth, kind="stable")
    faces = colours[order]
    # edges a shade darker than their face: they show the mesh and cover the
    # antialiasing seams between neighbouring triangles
    if collection is None:
        collection = PolyCollection(polys[order], facecolors=faces, edgecolors=0.75 * faces, linewidths=0.3)
        ax.add_collection(collection)
    else:
        collection.set_verts(polys[order])
        collection.set_facecolors(faces)
        collection.set_edgecolors(0.75 * faces)
    return collection


def set_limits(ax, points, i, j):
    """Axis limits around points (n, 3) in m, drawn in mm, with a margin."""
    lo, hi = 1000 * points.min(0), 1000 * points.max(0)
    pad = max(2.0, 0.05 * (hi - lo)[[i, j]].max())
    ax.set_xlim(lo[i] - pad, hi[i] + pad)
    ax.set_ylim(lo[j] - pad, hi[j] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("xyz"[i] + " [mm]")
    ax.set_ylabel("xyz"[j] + " [mm]")


def energies(case):
    e = list(csv.DictReader(open(case / "postProcessing/energy.csv")))
    t = np.array([float(r["time"]) for r in e])
    return t, np.array([float(r["kinetic"]) for r in e]), np.array([float(r["total"]) for r in e])


def chart(case, out, bodies, times, poses, source, title, label, compare):
    fixed = {b[0]: b[2] for b in bodies}
    placed = {n: world(tri, poses[n][-1]) for n, tri, _, _ in bodies}
    t_end = times[-1]
    report_distances(placed, fixed, t_end)

    runs = [(case, label)] + [(pathlib.Path(d), lab) for d, lab in compare]
    runs = [(d, lab) for d, lab in runs if (d / "postProcessing/energy.csv").is_file()]
    n = 3 if runs else 2
    allp = np.concatenate([p.reshape(-1, 3) for p in placed.values()])
    span = np.ptp(allp, axis=0) + 0.004
    # without the energy panel, as high as the views need
    fig = plt.figure(figsize=(14, 4.6) if runs else (9.5, np.clip(4.2 * max(span[1], span[2]) / span[0] + 1.4, 2.6, 6)))
    when = f"t = {t_end:g} s" if "not run" not in source else "initial state (not run)"
    for a, ((i, j), name) in enumerate(VIEWS):
        ax = fig.add_subplot(1, n, a + 1)
        draw_view(ax, placed, fixed, i, j)
        set_limits(ax, allp, i, j)
        ax.set_title(f"{name}, {when}")
    if runs:
        ax = fig.add_subplot(1, 3, 3)
        for d, lab in runs:
            t, ke, tot = energies(d)
            ax.plot(t, tot - tot[0], label=f"{lab}: total - initial")
            ax.plot(t, ke, "--", label=f"{lab}: kinetic")
        ax.set_yscale("symlog", linthresh=1e-6)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("energy [J]")
        ax.set_title("energy")
        ax.legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    out = pathlib.Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100)
    plt.close(fig)
    print(f"wrote {out}")


def movie_writer(path, fps):
    from matplotlib import animation
    ext = path.suffix.lower()
    if ext == ".gif":
        return animation.PillowWriter(fps=fps)
    if ext == ".mp4":
        if not animation.FFMpegWriter.isAvailable():
            raise SceneError(f"{path}: an .mp4 needs ffmpeg, which is not on PATH: install it"
                             " (Debian: apt-get install ffmpeg) or write a .gif")
        # yuv420p: the pixel format every player decodes
        return animation.FFMpegWriter(fps=fps, codec="h264", extra_args=["-pix_fmt", "yuv420p"])
    raise SceneError(f"{path}: --movie writes .gif or .mp4, not '{ext}'")


def movie(path, bodies, times, poses, source, title, frames, fps, end=None, dpi=72):
    path = pathlib.Path(path)
    writer = movie_writer(path, fps)
    fixed = {b[0]: b[2] for b in bodies}
    # frames spread evenly over the written times up to end, first and last included
    last = len(times) - 1 if end is None else max(0, int(np.searchsorted(times, end + 1e-12)) - 1)
    pick = np.unique(np.round(np.linspace(0, last, min(frames, last + 1))).astype(int))
    frames_placed = [{n: world(tri, poses[n][f]) for n, tri, _, _ in bodies} for f in pick]
    allp = np.concatenate([p.reshape(-1, 3) for fp in frames_placed for p in fp.values()])
    # 640 pixels wide, as high as the views need (even sizes: h264 needs them)
    span = np.ptp(allp, axis=0) + 0.004
    height = 2 * int(np.clip(290 * max(span[1], span[2]) / span[0] + 90, 200, 480) / 2)
    fig = plt.figure(figsize=(640 / dpi, height / dpi), dpi=dpi)
    axes, cols = [], []
    for a, ((i, j), name) in enumerate(VIEWS):
        ax = fig.add_subplot(1, 2, a + 1)
        cols.append(draw_view(ax, frames_placed[0], fixed, i, j))
        set_limits(ax, allp, i, j)
        ax.set_title(name, fontsize=9)
        ax.tick_params(labelsize=7)
        ax.xaxis.label.set_size(8)
        ax.yaxis.label.set_size(8)
        axes.append(ax)
    head = fig.suptitle(f"{title + ': ' if title else ''}t = {times[pick[0]]:.6g} s", fontsize=9)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    with writer.saving(fig, str(path), dpi):
        for f, placed in zip(pick, frames_placed):
            for ax, col, ((i, j), _) in zip(axes, cols, VIEWS):
                draw_view(ax, placed, fixed, i, j, col)
            head.set_text(f"{title + ': ' if title else ''}t = {times[f]:.6g} s")
            writer.grab_frame()
    plt.close(fig)
    print(f"wrote {path}: {len(pick)} frames of {last + 1} written times up to t = {times[last]:g} s ({source}),"
          f" {fps:g} per second")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case")
    ap.add_argument("out", nargs="?", help="the chart (PNG, or any format matplotlib writes)")
    ap.add_argument("--title", default="")
    ap.add_argument("--compare", nargs=2, action="append", default=[], metavar=("DIR", "LABEL"))
    ap.add_argument("--label", default="MBM (hybrid)")
    ap.add_argument("--movie", metavar="FILE", help="write a movie of the bodies over time (.gif or .mp4)")
    ap.add_argument("--frames", type=int, default=60, help="most frames of the movie (default 60)")
    ap.add_argument("--fps", type=float, default=15, help="movie frames per second (default 15)")
    ap.add_argument("--end", type=float, help="the movie's last time (default: the last written)")
    a = ap.parse_args()
    if not a.out and not a.movie:
        ap.error("give OUT.png, --movie FILE, or both")
    if a.frames < 1 or not a.fps > 0:
        ap.error("--frames must be at least 1 and --fps positive")
    case = pathlib.Path(a.case).resolve()
    try:
        if a.movie:
            movie_writer(pathlib.Path(a.movie), a.fps)  # fail before the long part
        bodies = load_scene(case)
        times, poses, source = load_poses(case, bodies)
        if a.out:
            chart(case, a.out, bodies, times, poses, source, a.title, a.label, a.compare)
        if a.movie:
            movie(a.movie, bodies, times, poses, source, a.title, a.frames, a.fps, a.end)
    except SceneError as e:
        print(f"plotScene: {e}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()

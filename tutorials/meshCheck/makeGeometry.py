#!/usr/bin/env python3
"""Write the tutorial's meshes: a hexagonal-prism magnet as ASCII STL (in mm)
and a tetrahedral wedge as OBJ (in m). Plain text writers, no dependencies."""
import math
import pathlib

out = pathlib.Path(__file__).resolve().parent / "constant" / "geometry"
out.mkdir(parents=True, exist_ok=True)


def write_stl(path, vertices, triangles, name):
    with open(path, "w") as f:
        f.write(f"solid {name}\n")
        for a, b, c in triangles:
            pa, pb, pc = vertices[a], vertices[b], vertices[c]
            u = [pb[i] - pa[i] for i in range(3)]
            v = [pc[i] - pa[i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            length = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write("  facet normal %g %g %g\n    outer loop\n" % tuple(x / length for x in n))
            for p in (pa, pb, pc):
                f.write("      vertex %.9g %.9g %.9g\n" % tuple(p))
            f.write("    endloop\n  endfacet\n")
        f.write(f"endsolid {name}\n")


# Hexagonal prism, circumradius 6 mm, height 4 mm, counter-clockwise outward.
k, r, h = 6, 6.0, 4.0
verts = [(r * math.cos(2 * math.pi * i / k), r * math.sin(2 * math.pi * i / k), z)
         for z in (-h / 2, h / 2) for i in range(k)]
verts += [(0, 0, -h / 2), (0, 0, h / 2)]
bottom, top = 2 * k, 2 * k + 1
tris = []
for i in range(k):
    j = (i + 1) % k
    tris += [(i, j, k + j), (i, k + j, k + i)]    # side quad
    tris += [(bottom, j, i), (top, k + i, k + j)]  # caps
write_stl(out / "hexMagnet.stl", verts, tris, "hexMagnet")

# Wedge (triangular prism) as OBJ, metres.
w = [(0, 0, 0), (0.01, 0, 0), (0, 0.01, 0), (0, 0, 0.004), (0.01, 0, 0.004), (0, 0.01, 0.004)]
faces = [(1, 3, 2), (4, 5, 6), (1, 2, 5), (1, 5, 4), (2, 3, 6), (2, 6, 5), (3, 1, 4), (3, 4, 6)]
with open(out / "wedge.obj", "w") as f:
    f.write("# wedge: triangular prism 10 x 10 x 4 mm\n")
    for p in w:
        f.write("v %g %g %g\n" % p)
    for a, b, c in faces:
        f.write(f"f {a} {b} {c}\n")

# A deliberately broken copy: one face missing (open mesh), for the demo.
write_stl(out / "hexMagnetOpen.stl", verts, tris[:-1], "hexMagnetOpen")

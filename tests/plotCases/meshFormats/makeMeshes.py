#!/usr/bin/env python3
"""Writes constant/geometry/: a 10 mm cube or tetrahedron in every mesh format
magFoam reads (the files are committed; this says how they were made)."""
import pathlib
import struct

geo = pathlib.Path(__file__).parent / "constant/geometry"
cube = [(x, y, z) for z in (-5, 5) for y in (-5, 5) for x in (-5, 5)]  # bit 0: +x, 1: +y, 2: +z
quads = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]  # outward
cubeTris = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
tetra = [(0, 0, 0), (10, 0, 0), (0, 10, 0), (0, 0, 10)]
tetraTris = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def normal(v, t):
    a, b, c = (v[i] for i in t)
    u, w = [b[k] - a[k] for k in range(3)], [c[k] - a[k] for k in range(3)]
    return (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])


# ASCII STL, mm
with open(geo / "cubeAscii.stl", "w") as f:
    f.write("solid cube\n")
    for t in cubeTris:
        f.write(" facet normal %g %g %g\n  outer loop\n" % normal(cube, t))
        for i in t:
            f.write("   vertex %g %g %g\n" % cube[i])
        f.write("  endloop\n endfacet\n")
    f.write("endsolid cube\n")
# binary STL, mm; the header starts with "solid", as some exporters write it
with open(geo / "cubeBinary.stl", "wb") as f:
    f.write(b"solid binary, not ASCII".ljust(80, b" ") + struct.pack("<I", len(cubeTris)))
    for t in cubeTris:
        f.write(struct.pack("<12fH", *normal(cube, t), *(c for i in t for c in cube[i]), 0))
# OBJ, mm: quads, v//vn indices, one face by negative (relative) indices
with open(geo / "cube.obj", "w") as f:
    f.write("# cube\no cube\n" + "".join("v %g %g %g\n" % p for p in cube) + "vn 0 0 1\n")
    for q in quads[:-1]:
        f.write("f " + " ".join(f"{i + 1}//1" for i in q) + "\n")
    f.write("f " + " ".join(str(i - 8) for i in quads[-1]) + "\n")
# ASCII PLY, mm: the tetrahedron, a vertex colour to skip
with open(geo / "tetraAscii.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\ncomment tetrahedron\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nproperty uchar red\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n")
    f.write("".join("%g %g %g 200\n" % p for p in tetra) + "".join("3 %d %d %d\n" % t for t in tetraTris))
# binary PLY (little endian), mm: the cube as quads, double coordinates, a
# normal per vertex to skip
with open(geo / "cubeBinary.ply", "wb") as f:
    f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty double x\nproperty double y\n"
            b"property double z\nproperty float nx\nproperty float ny\nproperty float nz\n"
            b"element face 6\nproperty list uchar uint vertex_indices\nend_header\n")
    for p in cube:
        f.write(struct.pack("<3d3f", *p, 0, 0, 1))
    for q in quads:
        f.write(struct.pack("<B4I", 4, *q))
# OFF, mm: the tetrahedron, with comments and the counts on their own line
with open(geo / "tetra.off", "w") as f:
    f.write("OFF\n# tetrahedron\n4 4 6\n" + "".join("%g %g %g\n" % p for p in tetra)
            + "".join("3 %d %d %d\n" % t for t in tetraTris))

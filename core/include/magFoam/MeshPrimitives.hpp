// Closed, outward oriented primitive meshes centred at the origin, for bodies
// given as geometry {box|sphere|cylinder: ...} and for tests and tutorials.
// Bad sizes are InputErrors naming the primitive and the expected range.
#pragma once

#include <magFoam/SurfaceMesh.hpp>

namespace mag {

// Rectangular box with edge lengths size.x, size.y, size.z along the axes:
// 8 vertices, 12 triangles. Exact: its mass properties have no discretisation error.
SurfaceMesh makeBox(const Vec3& size);

// Sphere approximated by a subdivided icosahedron: 20 * 4^subdivisions
// triangles, all 10 * 4^subdivisions + 2 vertices on the sphere (so the mesh is
// inscribed: volume and inertia approach the sphere's from below, error ~ 4^-n).
// subdivisions 0..8.
SurfaceMesh makeIcosphere(double radius, int subdivisions);

// Ellipsoid with semi-axes along x, y, z: an icosphere scaled per axis, vertices
// on the ellipsoid. subdivisions 0..8.
SurfaceMesh makeEllipsoid(const Vec3& semiAxes, int subdivisions);

// Cylinder of the given radius and height along z (from -height/2 to height/2):
// a regular prism with 'segments' sides, vertices on the circles, caps as fans
// around a centre vertex: 2 * segments + 2 vertices, 4 * segments triangles.
// segments >= 3.
SurfaceMesh makeCylinder(double radius, double height, int segments);

} // namespace mag

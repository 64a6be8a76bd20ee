// Triangle surface meshes: the geometry of every body.
//
// A SurfaceMesh is plain data (vertices, triangles, where it came from). This
// header adds the small operations every other part needs: per-triangle
// normals and areas, bounding box, welding duplicate vertices, removing
// degenerate triangles, rigid and affine transforms, and the element
// descriptions ("triangle 5 (vertices 1, 2, 3 at ...)") that error messages use.
//
// Conventions: triangles are counter-clockwise seen from outside, so the
// right-hand normal (b - a) x (c - a) points out of the body. Indices are int
// (meshes beyond 2^31 elements are far outside what the field kernels can do).
#pragma once

#include <magFoam/Types.hpp>

#include <array>
#include <string>
#include <vector>

namespace mag {

// Default tolerance of the geometric tests (weld distance, zero-area height),
// relative to the bounding-box diagonal so that it does not depend on units.
inline constexpr double meshRelativeTolerance = 1e-9;

// A closed (or not yet checked) triangle surface.
struct SurfaceMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;
    // File name or primitive description; every message about the mesh starts with it.
    std::string source;

    int nVertices() const { return static_cast<int>(vertices.size()); }
    int nTriangles() const { return static_cast<int>(triangles.size()); }

    // Corner k (0, 1, 2) of triangle t.
    const Vec3& corner(int t, int k) const { return vertices[triangles[t][k]]; }

    // 0.5 (b - a) x (c - a): outward normal scaled by the area.
    Vec3 areaVector(int t) const;
    // Unit outward normal; the zero vector for a zero-area triangle.
    Vec3 normal(int t) const;
    double area(int t) const;
    Vec3 centroid(int t) const;
};

// Axis-aligned box of the finite vertices; lower = upper = 0 when there are none.
struct BoundingBox {
    Vec3 lower = Vec3::Zero();
    Vec3 upper = Vec3::Zero();

    Vec3 centre() const { return 0.5 * (lower + upper); }
    Vec3 size() const { return upper - lower; }
    double diagonal() const { return size().norm(); }
};

BoundingBox boundingBox(const SurfaceMesh& mesh);

// relativeTolerance * bounding-box diagonal: the absolute length below which two
// points are the same point for weld and degeneracy tests.
double lengthTolerance(const SurfaceMesh& mesh, double relativeTolerance = meshRelativeTolerance);

// Per-triangle unit normals (zero for zero-area triangles) and areas, in triangle order.
std::vector<Vec3> triangleNormals(const SurfaceMesh& mesh);
std::vector<double> triangleAreas(const SurfaceMesh& mesh);
double surfaceArea(const SurfaceMesh& mesh);

// Element descriptions for messages, e.g.
//   "vertex 7 at (0.005, -0.005, 0.005)"
//   "triangle 3 (vertices 1, 7, 2 at (..), (..), (..))"
//   "edge between vertex 1 at (..) and vertex 7 at (..)"
std::string formatPoint(const Vec3& p);

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection,
// Sec. 5.1.5: Voronoi regions of the vertices, edges and face).
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// Signed solid angle (sr) of triangle (r1, r2, r3) seen from p (Van Oosterom and
// Strackee 1983); positive when p lies on the inner side (the triangle
// counter-clockwise about the outward normal).
double triangleSolidAngle(const Vec3& r1, const Vec3& r2, const Vec3& r3, const Vec3& p);
// Generalized winding number of a closed outward mesh at p: the triangles' solid
// angles / 4 pi; 1 inside, 0 outside, 1/2 on a face.
double windingNumber(const SurfaceMesh& mesh, const Vec3& p);
std::string describeVertex(const SurfaceMesh& mesh, int vertex);
std::string describeTriangle(const SurfaceMesh& mesh, int triangle);
std::string describeEdge(const SurfaceMesh& mesh, int vertexA, int vertexB);

// Throws InputError naming the first triangle whose vertex index is out of range.
void requireValidIndices(const SurfaceMesh& mesh);

// Merges vertices closer than relativeTolerance * diagonal (the first vertex of a
// cluster is kept) and renumbers the triangles. Needed because STL stores every
// triangle's corners separately. Unreferenced vertices are kept (see
// removeUnusedVertices); triangles that collapse are kept (see dropDegenerateTriangles).
// Returns the number of vertices merged away.
int weldVertices(SurfaceMesh& mesh, double relativeTolerance = meshRelativeTolerance);

// Removes vertices no triangle uses; returns how many.
int removeUnusedVertices(SurfaceMesh& mesh);

// A triangle is degenerate when two of its indices are equal ("collapsed") or its
// height over the longest side is at most lengthTol (zero area, collinear corners).
bool isCollapsed(const std::array<int, 3>& triangle);
bool isDegenerate(const SurfaceMesh& mesh, int triangle, double lengthTol);
std::vector<int> findDegenerateTriangles(const SurfaceMesh& mesh,
                                         double relativeTolerance = meshRelativeTolerance);

// Removes degenerate triangles; returns their indices in the input mesh.
// Careful: removing a zero-area triangle with three distinct corners (a "needle"
// closing a T-junction) opens the mesh; removing a collapsed one never does.
std::vector<int> dropDegenerateTriangles(SurfaceMesh& mesh,
                                         double relativeTolerance = meshRelativeTolerance);
// Removes only collapsed triangles (repeated index, left over from welding).
std::vector<int> dropCollapsedTriangles(SurfaceMesh& mesh);

// Transforms, applied to the vertices in place.
void translate(SurfaceMesh& mesh, const Vec3& offset);
// Rotation about the origin; R must be a rotation matrix (q is normalised).
void rotate(SurfaceMesh& mesh, const Mat3& R);
void rotate(SurfaceMesh& mesh, const Quat& q);
// Uniform scale about the origin; InputError unless factor is finite and > 0.
void scale(SurfaceMesh& mesh, double factor);
// x -> A x + offset. A reflection (det A < 0) also reverses every triangle so the
// normals stay outward; a singular or non-finite A is an InputError.
void transform(SurfaceMesh& mesh, const Mat3& A, const Vec3& offset);

// Reverses every triangle (inside-out <-> outside-out).
void flipOrientation(SurfaceMesh& mesh);

// Appends the vertices and triangles of 'part' (indices shifted); source unchanged.
void append(SurfaceMesh& mesh, const SurfaceMesh& part);

} // namespace mag

// Convex pieces of a concave mesh, for collision only
// (docs/rigid-bodies.md#convex-pieces). Rigid-body engines collide convex
// shapes robustly and cheaply (support functions, clipped faces) and triangle
// meshes poorly: thin concave parts (wires, sheets) lose or gain contacts
// between steps. A concave part described as a union of convex pieces collides
// as that union; the magnetic model still sees the true surface mesh.
//
// The pieces of a mesh file live beside it, <stem>.pieces.yaml, in the mesh's
// own units (scaled with it):
//
//   # convex pieces of paperclip.stl (collision only)
//   mesh: paperclip.stl
//   pieces:                      # each: x y z of its points; the piece is their convex hull
//     - [0.0, 0.0, 0.0, 0.001, 0.0, 0.0, ...]
//
// magMakeGeometry writes them for the parts it builds (an exact decomposition:
// the pieces tile the mesh); any tool's may be given for imported meshes.
#pragma once

#include "magFoam/SurfaceMesh.hpp"
#include "magFoam/Types.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace mag {

// The point sets of convex pieces: each piece is the convex hull of its points.
using ConvexPieces = std::vector<std::vector<Vec3>>;

// The convex hull of a point set: its vertices, face planes and face loops.
struct ConvexHull {
    std::vector<Vec3> points;              // the hull's vertices (points inside dropped)
    std::vector<Vec3> normals;             // outward unit normal of each face
    std::vector<double> offsets;           // n . x = offset on each face, n . x <= offset inside
    std::vector<std::vector<int>> faces;   // vertex loops, counter-clockwise seen from outside
    double volume = 0;                     // m^3
    Vec3 centroid = Vec3::Zero();          // of the solid
};

// Hull of 4..256 points (brute force over point triples, coplanar faces
// merged; tolerance 1e-9 of the points' extent). InputError (naming `what`)
// when the points are fewer, more, not finite or all in one plane.
ConvexHull convexHull(const std::vector<Vec3>& points, const std::string& what);

// Whether a closed mesh is convex: no vertex in front of any face's plane
// (beyond 1e-9 of the mesh's size).
bool isConvex(const SurfaceMesh& mesh);

// <folder>/<stem>.pieces.yaml for <folder>/<stem>.<ext>.
std::filesystem::path piecesFileFor(const std::filesystem::path& meshFile);

// The pieces' point sets of a pieces file, each coordinate times `scale`.
// InputError naming the file and the piece when the file is malformed.
ConvexPieces readConvexPieces(const std::filesystem::path& file, double scale);

// Writes a pieces file for the mesh file `meshName` (atomically).
void writeConvexPieces(const std::filesystem::path& file, const std::string& meshName,
                       const ConvexPieces& pieces);

// Hulls of the pieces, moved by `shift` (into the body frame), checked against
// the mesh they stand for: InputError when a piece reaches more than 1 % of the
// mesh's size outside its bounding box. Returns the hulls; `volumeMismatch`
// receives (sum of piece volumes - mesh volume) / mesh volume (0 for an exact
// decomposition; overlapping pieces count twice).
std::vector<ConvexHull> buildConvexPieces(const ConvexPieces& pieces, const Vec3& shift,
                                          const SurfaceMesh& mesh, double meshVolume, const std::string& what,
                                          double& volumeMismatch);

} // namespace mag

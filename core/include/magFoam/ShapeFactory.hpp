// Shapes from the `geometry:` entry of a body (docs/case-reference.md#geometry):
//
//   geometry: {box: {size: [0.01, 0.01, 0.01]}}
//   geometry: {sphere: {radius: 0.005, subdivisions: 3}}      # icosphere
//   geometry: {cylinder: {radius: 0.005, height: 0.01, segments: 32}}
//   geometry: {file: geometry/clip.stl, scale: 0.001}         # STL/OBJ/PLY/OFF
//
// A mesh file's convex pieces (geometry/clip.pieces.yaml beside it, for
// collision; ConvexPieces.hpp) are read with it when present.
//
// Every mesh is checked (closed, manifold, outward) before use, then moved so
// its centre of mass is the origin of the body frame. Identical geometry
// entries share one Shape (per-mesh tables are built once).
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Dictionary.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace mag {

// Check a mesh, compute its mass properties and re-centre it; convex pieces
// (in the mesh's frame, before re-centring) are moved with it and checked
// against it (`piecesName` names them in messages).
std::shared_ptr<const Shape> makeShape(SurfaceMesh mesh, const ShapeKind& kind,
                                       const ConvexPieces& pieces = {},
                                       const std::string& piecesName = "");

// The mesh a geometry entry describes, unchecked (magCheckMesh reports on
// it), with its kind and a key that identifies equal geometry entries.
// With keyOnly, nothing is built or loaded: only kind and key are set.
SurfaceMesh geometryMesh(const Dict& geometry, const std::filesystem::path& baseDir, ShapeKind& kind,
                         std::string& key, bool keyOnly = false);

class ShapeCache {
public:
    // `geometry` is the body's geometry mapping; files are relative to `baseDir`.
    std::shared_ptr<const Shape> get(const Dict& geometry, const std::filesystem::path& baseDir);

private:
    std::map<std::string, std::shared_ptr<const Shape>> shapes_;
};

} // namespace mag

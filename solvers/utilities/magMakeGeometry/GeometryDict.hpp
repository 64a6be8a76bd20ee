// The geometryDict.yaml front end of magMakeGeometry: one `parts:` entry
// ({name, type, keys...}) -> meshes, and a whole case -> STL files. The types
// and their keys are listed in magMakeGeometry.cpp (and docs/case-reference.md,
// geometryDict); each type is one entry of the registry in GeometryDict.cpp.
#pragma once

#include <magFoam/ConvexPieces.hpp>
#include <magFoam/Dictionary.hpp>
#include <magFoam/SurfaceMesh.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace mag {

// The 'type:' words of geometryDict.yaml, sorted.
std::vector<std::string> shapeTypes();

// One mesh that magMakeGeometry writes as constant/geometry/<name>.stl.
struct NamedMesh {
    std::string name;
    std::string type;
    SurfaceMesh mesh;
    // Convex pieces tiling the mesh (written as <name>.pieces.yaml; empty: none).
    ConvexPieces pieces;
};

// The meshes of one `parts:` entry ({name, type, keys...}; see magMakeGeometry
// for the keys). Unknown keys and types are InputErrors citing file:line;
// generator errors are re-thrown with the entry's position. Most types give one
// mesh named <name>; binderClip with split: true gives <name>_sheet,
// <name>_handle1, <name>_handle2.
std::vector<NamedMesh> makeNamedShapes(const Dict& entry);

// Reads <caseDir>/system/geometryDict.yaml (parts: [...]), builds every part,
// checks it with requireUsable and writes binary STL files
// <caseDir>/constant/geometry/<name>.stl, with <name>.pieces.yaml beside the
// concave parts that have an exact convex decomposition. Names must be unique and made of
// letters, digits, '_', '-', '.'. Returns the meshes written, in order.
std::vector<NamedMesh> makeCaseGeometry(const std::filesystem::path& caseDir);

} // namespace mag

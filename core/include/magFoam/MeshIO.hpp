// Reading surface meshes from files and writing simple ones.
//
// Tested formats: STL (ASCII and binary), OBJ, PLY (ascii and binary), OFF. Other formats assimp
// reads (3MF, glTF, COLLADA, ...) are accepted as well; their node transforms
// are applied and all their triangles are merged into one mesh.
//
// A loaded mesh is welded (STL stores every corner of every triangle separately),
// collapsed triangles and unused vertices are removed, and 'source' is the path.
// Nothing else is repaired: checkTopology()/requireUsable() judge the result.
#pragma once

#include <magFoam/MeshFormats.hpp>
#include <magFoam/SurfaceMesh.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace mag {

struct MeshLoadOptions {
    // Applied to every coordinate, e.g. 0.001 for files in millimetres.
    double scale = 1.0;
    // Weld distance relative to the bounding-box diagonal (see weldVertices).
    double weldTolerance = meshRelativeTolerance;
};

// What loading did, for logs and magCheckMesh.
struct MeshLoadReport {
    std::string format;                  // lower-case extension, e.g. ".stl"
    int verticesRead = 0;                // as the file holds them
    int trianglesRead = 0;
    int pointsAndLinesIgnored = 0;       // non-triangle primitives in the file
    int verticesMerged = 0;              // by welding
    int collapsedTrianglesRemoved = 0;   // two corners welded together
    int unusedVerticesRemoved = 0;
};

// Extensions the loader is tested with: .stl .obj .ply .off.
std::vector<std::string> meshFileExtensions();

// Reads a mesh. InputError (naming the path) when the file is missing or not a
// regular file or above meshFileLimit (InputFile.hpp), is malformed (the line
// or element; for assimp's formats its message and the supported extensions),
// has a vertex index out of range or a coordinate that is not finite, or holds
// no triangles, or when options.scale is not a finite number > 0.
// Precision: PLY and OFF are read in double precision; assimp (as packaged)
// stores coordinates as float, so STL and OBJ text is read to ~7 digits.
SurfaceMesh loadSurfaceMesh(const std::filesystem::path& path, const MeshLoadOptions& options = {},
                            MeshLoadReport* report = nullptr);

// The same steps after parsing (scale, weld, clean-up; report->format kept):
// loadSurfaceMesh is parseMeshBytes or assimp, then this.
SurfaceMesh prepareSurfaceMesh(ParsedMesh parsed, const MeshLoadOptions& options = {},
                               MeshLoadReport* report = nullptr);

// Shorthand for loadSurfaceMesh(path, {.scale = scale}).
SurfaceMesh loadMesh(const std::filesystem::path& path, double scale = 1.0);

// Binary STL (single precision, as the format demands). InputError if the file
// cannot be written.
void writeStlBinary(const SurfaceMesh& mesh, const std::filesystem::path& path);

// ASCII Wavefront OBJ with shared vertices, full double precision.
void writeObj(const SurfaceMesh& mesh, const std::filesystem::path& path);

// Picks the writer by extension (.stl -> binary STL, .obj -> OBJ).
void writeSurfaceMesh(const SurfaceMesh& mesh, const std::filesystem::path& path);

} // namespace mag

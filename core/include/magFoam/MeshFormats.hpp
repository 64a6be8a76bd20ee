// Parsers of the mesh file formats, from the bytes of a file (MeshIO.hpp reads
// the file and welds the result). PLY, OFF and OBJ are read by magFoam's own
// validating readers; STL and the other formats by assimp, whose result is
// validated (counts, indices, finite coordinates) before use.
//
// Every malformed file is an InputError naming the file and the line (text
// formats) or the element and byte offset (binary PLY), and what was expected.
#pragma once

#include <magFoam/SurfaceMesh.hpp>

#include <string>
#include <string_view>

namespace mag {

// Triangles as the file holds them (polygons split into fans), before welding.
struct ParsedMesh {
    SurfaceMesh mesh;           // source = the file name
    int pointsAndLinesIgnored = 0;  // faces with fewer than 3 vertices
};

// Coordinates beyond this magnitude are refused: the volume (~x^3) and the
// inertia (~x^5) of such a mesh overflow.
inline constexpr double meshCoordinateLimit = 1e30;

// PLY 1.0: ascii, binary_little_endian, binary_big_endian; a 'vertex' element
// with scalar properties x, y, z of any PLY type and a 'face' element with a
// list property vertex_indices (or vertex_index); other elements and
// properties are skipped.
ParsedMesh parsePly(std::string_view bytes, const std::string& name);

// OFF (also COFF, NOFF, CNOFF, STOFF: per-vertex extras are ignored), text only;
// '#' comments.
ParsedMesh parseOff(std::string_view bytes, const std::string& name);

// Wavefront OBJ, text: `v` and `f` (corners v, v/vt, v//vn, v/vt/vn; negative
// indices count back from the last vertex); `l` and `p` are counted as ignored,
// the other statements of the format (vt, vn, g, o, s, usemtl, ...) skipped,
// anything else an error; '#' comments.
ParsedMesh parseObj(std::string_view bytes, const std::string& name);

// Any other format assimp reads; `extension` (".stl", ".obj", ...) picks the importer.
ParsedMesh parseWithAssimp(std::string_view bytes, const std::string& name, const std::string& extension);

// By extension: .ply, .off and .obj our own readers, everything else assimp.
ParsedMesh parseMeshBytes(std::string_view bytes, const std::string& name, const std::string& extension);

} // namespace mag

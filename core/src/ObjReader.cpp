// Wavefront OBJ reader (text): `v` vertices and `f` polygons, everything else
// a surface does not need (texture coordinates, normals, groups, materials,
// smoothing) skipped. Our own, like PLY and OFF: assimp's OBJ importer leaks
// memory on some malformed files, and every error here names the line.
#include <magFoam/MeshFormats.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"
#include "MeshText.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

namespace mag {

namespace {

using meshText::parseInteger;
using meshText::parseNumber;

using meshText::quoted;

// Statements of the OBJ specification that carry nothing a closed surface
// needs: read past. A statement outside the specification is an error.
bool skipped(std::string_view word) {
    static constexpr std::array<std::string_view, 36> words = {
        "vt", "vn", "vp", "g", "o", "s", "mg", "usemtl", "mtllib", "usemap", "maplib", "cstype",
        "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end",
        "con", "bevel", "c_interp", "d_interp", "lod", "shadow_obj", "trace_obj", "ctech", "stech", "call",
        "csh", "res"};
    return std::find(words.begin(), words.end(), word) != words.end();
}

} // namespace

ParsedMesh parseObj(std::string_view bytes, const std::string& name) {
    meshText::TokenCursor cursor(bytes, 0, 1, '#');
    auto fail = [&](const std::string& message) -> void {
        throw InputError(name + ":" + std::to_string(cursor.line()) + ": " + message);
    };
    ParsedMesh out;
    out.mesh.source = name;
    std::vector<int> polygon;
    while (true) {
        const std::string_view word = cursor.next();
        if (word.empty()) break;
        if (word == "v") {
            Vec3 p;
            for (int axis = 0; axis < 3; ++axis) {
                const std::string_view token = cursor.nextOnLine();
                if (!parseNumber(token, p[axis]))
                    fail("vertex " + std::to_string(out.mesh.vertices.size() + 1) + ": expected 3 numbers x y z, got " +
                         (token.empty() ? std::string("fewer") : quoted(token)));
                if (!std::isfinite(p[axis]) || std::abs(p[axis]) > meshCoordinateLimit)
                    fail("vertex " + std::to_string(out.mesh.vertices.size() + 1) + ": coordinate " +
                         meshDetail::formatNumber(p[axis]) + ", expected a finite number of magnitude at most 1e30");
            }
            if (out.mesh.vertices.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
                fail("more than 2147483647 vertices");
            out.mesh.vertices.push_back(p);
            cursor.endLine();  // w, or a colour
        } else if (word == "f" || word == "fo") {
            // Corners "v", "v/vt", "v//vn", "v/vt/vn"; v from 1, or negative:
            // counted back from the last vertex read so far.
            polygon.clear();
            const auto count = static_cast<std::int64_t>(out.mesh.vertices.size());
            for (std::string_view token = cursor.nextOnLine(); !token.empty(); token = cursor.nextOnLine()) {
                const std::string_view index = token.substr(0, token.find('/'));
                std::int64_t v = 0;
                if (!parseInteger(index, std::numeric_limits<std::int64_t>::min() / 2,
                                  std::numeric_limits<std::int64_t>::max() / 2, v) ||
                    v == 0)
                    fail("face corner " + quoted(token) + ": expected a vertex index (from 1, or negative from the "
                         "last vertex)");
                const std::int64_t resolved = v > 0 ? v - 1 : count + v;
                if (resolved < 0 || resolved >= count)
                    fail("face corner " + quoted(token) + ": vertex index " + std::to_string(v) +
                         " is out of range; " + std::to_string(count) + " vertices are defined before it");
                polygon.push_back(static_cast<int>(resolved));
            }
            if (polygon.size() < 3) {
                ++out.pointsAndLinesIgnored;
                continue;
            }
            for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
                out.mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
        } else if (word == "l" || word == "p") {
            ++out.pointsAndLinesIgnored;
            cursor.endLine();
        } else if (skipped(word)) {
            cursor.endLine();
        } else {
            fail("unknown OBJ statement " + quoted(word) + " (expected v, f, or one the surface does not need: vt, "
                 "vn, g, o, s, usemtl, ...)");
        }
    }
    return out;
}

} // namespace mag

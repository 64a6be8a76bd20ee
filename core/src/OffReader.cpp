// OFF reader (Geomview's Object File Format, text): header word, counts, one
// vertex per line, one polygon per line; every count checked against the lines
// that are really there.
#include <magFoam/MeshFormats.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"
#include "MeshText.hpp"

#include <limits>
#include <vector>

namespace mag {

namespace {

using meshText::parseInteger;
using meshText::parseNumber;

using meshText::quoted;

} // namespace

ParsedMesh parseOff(std::string_view bytes, const std::string& name) {
    meshText::TokenCursor cursor(bytes, 0, 1, '#');
    auto fail = [&](const std::string& message) -> void {
        throw InputError(name + ":" + std::to_string(cursor.line()) + ": " + message);
    };

    // Header word: [ST][C][N]OFF; the prefixes add per-vertex values we ignore.
    std::string_view word = cursor.next();
    std::string_view core = word;
    if (core.substr(0, 2) == "ST") core.remove_prefix(2);
    if (core.substr(0, 1) == "C") core.remove_prefix(1);
    if (core.substr(0, 1) == "N") core.remove_prefix(1);
    if (core != "OFF") {
        if (word.find("OFF") != std::string_view::npos)
            fail("OFF variant " + quoted(word) + " is not supported (expected OFF, COFF, NOFF, CNOFF or STOFF)");
        fail("expected the header word 'OFF', got " + quoted(word));
    }
    // The counts may follow on the same line ("OFF 8 6 0").
    const std::string_view sameLine = cursor.nextOnLine();
    if (sameLine == "BINARY") fail("binary OFF is not supported, expected the text form");

    // Counts: vertices, faces, edges (the last is unused and may be missing).
    std::int64_t counts[3] = {0, 0, 0};
    const char* what[3] = {"vertex", "face", "edge"};
    for (int i = 0; i < 3; ++i) {
        const std::string_view token = i > 0 ? cursor.nextOnLine() : !sameLine.empty() ? sameLine : cursor.next();
        if (token.empty() && i == 2) break;
        if (!parseInteger(token, 0, std::numeric_limits<int>::max(), counts[i]))
            fail(std::string("expected the ") + what[i] + " count (a whole number from 0 to 2147483647), got " +
                 (token.empty() ? std::string("the end of the line") : quoted(token)));
    }
    cursor.endLine();
    const std::int64_t nVertices = counts[0], nFaces = counts[1];
    // A vertex line is at least "0 0 0\n", a face line "3 0 1 2\n": reject
    // counts the rest of the file cannot hold before reserving memory.
    if (static_cast<std::uint64_t>(6 * nVertices + 8 * nFaces) > cursor.remaining() + 2)
        fail("the header counts " + std::to_string(nVertices) + " vertices and " + std::to_string(nFaces) +
             " faces, more than the " + std::to_string(cursor.remaining()) + " bytes after it can hold");

    ParsedMesh out;
    out.mesh.source = name;
    out.mesh.vertices.reserve(static_cast<std::size_t>(nVertices));
    for (std::int64_t v = 0; v < nVertices; ++v) {
        Vec3 p;
        for (int axis = 0; axis < 3; ++axis) {
            const std::string_view token = axis == 0 ? cursor.next() : cursor.nextOnLine();
            const std::string where = "vertex " + std::to_string(v) + ": ";
            if (token.empty() && axis == 0)
                fail("the file ends at vertex " + std::to_string(v) + "; the header counts " +
                     std::to_string(nVertices) + " vertices and " + std::to_string(nFaces) + " faces");
            if (!parseNumber(token, p[axis]))
                fail(where + "expected 3 numbers x y z, got " + (token.empty() ? std::string("fewer") : quoted(token)));
            if (!std::isfinite(p[axis]) || std::abs(p[axis]) > meshCoordinateLimit)
                fail(where + "coordinate " + meshDetail::formatNumber(p[axis]) +
                     ", expected a finite number of magnitude at most 1e30");
        }
        cursor.endLine();  // colours, normals, texture coordinates
        out.mesh.vertices.push_back(p);
    }

    std::vector<int> polygon;
    for (std::int64_t f = 0; f < nFaces; ++f) {
        const std::string where = "face " + std::to_string(f) + ": ";
        const std::string_view first = cursor.next();
        std::int64_t n = 0;
        if (first.empty())
            fail("the file ends at face " + std::to_string(f) + "; the header counts " + std::to_string(nFaces) +
                 " faces");
        if (!parseInteger(first, 0, std::numeric_limits<int>::max(), n))
            fail(where + "expected the number of corners, got " + quoted(first));
        polygon.clear();
        for (std::int64_t k = 0; k < n; ++k) {
            const std::string_view token = cursor.nextOnLine();
            std::int64_t index = 0;
            if (token.empty())
                fail(where + "the line ends after " + std::to_string(k) + " of its " + std::to_string(n) +
                     " vertex indices");
            if (!parseInteger(token, std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max(),
                              index))
                fail(where + "expected a vertex index, got " + quoted(token));
            if (index < 0 || index >= nVertices)
                fail(where + "vertex index " + std::to_string(index) + " is out of range; the file has " +
                     std::to_string(nVertices) + " vertices (indices 0 to " + std::to_string(nVertices - 1) + ")");
            polygon.push_back(static_cast<int>(index));
        }
        cursor.endLine();  // an optional colour
        if (polygon.size() < 3) {
            ++out.pointsAndLinesIgnored;
            continue;
        }
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
            out.mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
    }
    return out;
}

} // namespace mag

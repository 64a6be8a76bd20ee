// Mesh connectivity (edge table) and the checks a magnet's surface must pass.
//
// The field kernels integrate over the boundary of a solid, so a body's mesh must
// be a closed, manifold, consistently and outward oriented surface with non-zero
// volume and no zero-area triangles. It must also be the boundary of the region
// whose winding number is 1: no two triangles cross or touch away from the
// elements they share, and nested shells alternate outward, inverted (a cavity),
// outward, ... from the outside in; otherwise the integrals count some volume
// twice or negatively. checkTopology() lists every violation; requireUsable()
// throws an InputError naming the file and the first offending element;
// magCheckMesh prints the whole report.
#pragma once

#include <magFoam/SurfaceMesh.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace mag {

// One undirected edge and the triangles that use it.
struct MeshEdge {
    std::array<int, 2> vertices{-1, -1};   // vertices[0] < vertices[1]
    std::array<int, 2> triangles{-1, -1};  // the first two triangles using it; -1 if none
    // +1 when that triangle runs vertices[0] -> vertices[1], -1 when it runs the
    // other way, 0 for a missing triangle. A well oriented edge has +1 and -1.
    std::array<int, 2> direction{0, 0};
    int faceCount = 0;                     // all triangles using it (>2: non-manifold)
};

// Unique edges of a mesh, sorted by (vertices[0], vertices[1]).
// Triangles with an out-of-range index or a repeated index (collapsed) take no
// part: they are reported separately and would only blur the edge checks.
struct EdgeTable {
    std::vector<MeshEdge> edges;
    // Edge of each side: side k runs from corner k to corner (k+1)%3; -1 for
    // triangles that take no part.
    std::vector<std::array<int, 3>> triangleEdges;
    // Triangles beyond the second on non-manifold edges.
    struct ExtraUse {
        int edge;
        int triangle;
        int direction;
    };
    std::vector<ExtraUse> extraUses;
};

EdgeTable buildEdgeTable(const SurfaceMesh& mesh);

// Every problem found, as element indices (into mesh.vertices, mesh.triangles and
// edgeTable.edges). Empty lists mean the property holds.
struct TopologyReport {
    EdgeTable edgeTable;

    std::vector<int> invalidTriangles;     // a vertex index out of range
    std::vector<int> nonFiniteVertices;    // NaN or inf coordinates
    std::vector<int> degenerateTriangles;  // collapsed or zero area (see isDegenerate)
    std::vector<int> boundaryEdges;        // used by one triangle: the mesh is open
    std::vector<int> nonManifoldEdges;     // used by more than two triangles
    std::vector<int> inconsistentEdges;    // both triangles run the same direction
    std::vector<int> nonManifoldVertices;  // triangles around it form several fans

    // Pairs of triangles {lower, higher index} that meet away from the vertex or
    // edge they share: crossing, touching (closer than lengthTolerance) or, for
    // neighbours over an edge, folded back onto each other. Lowest pairs first;
    // at most maxStoredIntersections are kept, intersectingPairs counts all.
    static constexpr std::size_t maxStoredIntersections = 1000;
    std::vector<std::array<int, 2>> intersectingTriangles;
    std::size_t intersectingPairs = 0;

    int unusedVertices = 0;                // not an error; welding leaves none
    int shells = 0;                        // connected pieces (over shared edges)
    std::vector<double> shellVolumes;      // signed volume of each shell
    std::vector<int> triangleShell;        // shell of each triangle; -1 if it takes no part
    int eulerCharacteristic = 0;           // V - E + F over used vertices (2 per sphere-like shell)

    // Nesting, checked when there are several shells and the surface is closed,
    // manifold, oriented, free of degenerate triangles and non-intersecting (only
    // then are inside and outside defined): the innermost other shell enclosing
    // each shell (-1: none), and the shells that break the rule "directly inside
    // an outward shell is an inverted one and vice versa; outermost is outward".
    bool nestingChecked = false;
    std::vector<int> shellContainers;
    std::vector<int> misnestedShells;

    double signedVolume = 0.0;             // divergence theorem; > 0 for outward normals
    double volumeTolerance = 0.0;          // |volume| below this counts as zero
    double lengthTolerance = 0.0;          // for the degeneracy and intersection tests

    bool empty() const { return edgeTable.triangleEdges.empty(); }
    bool closed() const { return boundaryEdges.empty(); }
    bool manifold() const { return nonManifoldEdges.empty() && nonManifoldVertices.empty(); }
    bool consistentlyOriented() const { return inconsistentEdges.empty(); }
    bool nonIntersecting() const { return intersectingPairs == 0; }
    bool properlyNested() const { return misnestedShells.empty(); }
    bool zeroVolume() const { return std::abs(signedVolume) <= volumeTolerance; }
    bool outward() const { return signedVolume > volumeTolerance; }
    bool inverted() const { return signedVolume < -volumeTolerance; }
    // All checks pass: the mesh may be used as a body.
    bool usable() const;
};

// relativeTolerance scales with the bounding-box diagonal d: lengths below
// relativeTolerance * d and volumes below 1e-3 * relativeTolerance * d^3 are zero.
TopologyReport checkTopology(const SurfaceMesh& mesh,
                             double relativeTolerance = meshRelativeTolerance);

// One line per kind of problem, most fundamental first, each naming the source,
// the count and up to maxListed elements with their coordinates. Empty if usable.
std::vector<std::string> describeProblems(const SurfaceMesh& mesh, const TopologyReport& report,
                                          int maxListed = 3);

// "shell of triangles 12-23" (contiguous) or "shell of triangle 5 (and 11 more)".
std::string describeShell(const TopologyReport& report, int shell);

// Short names of the failed checks ("open", "inverted", ...), for verdict lines.
std::vector<std::string> problemNames(const TopologyReport& report);

// Throws InputError with the first (most fundamental) problem: file, element,
// coordinates and what was expected. Call before any physics uses the mesh.
void requireUsable(const SurfaceMesh& mesh);

} // namespace mag

// Edge table and the usability checks of a body's surface mesh.
#include <magFoam/MeshTopology.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace mag {

using meshDetail::formatNumber;

namespace {

bool hasValidIndices(const SurfaceMesh& mesh, const std::array<int, 3>& tri) {
    return std::all_of(tri.begin(), tri.end(),
                       [&](int v) { return v >= 0 && v < mesh.nVertices(); });
}

// Triangles that take part in the edge table (see EdgeTable).
bool takesPart(const SurfaceMesh& mesh, const std::array<int, 3>& tri) {
    return hasValidIndices(mesh, tri) && !isCollapsed(tri);
}

// Union-find with path halving; used for shells (over triangles) and for the fans
// around each vertex (over triangle corners).
class DisjointSets {
public:
    explicit DisjointSets(std::size_t n) : parent_(n) {
        std::iota(parent_.begin(), parent_.end(), 0);
    }
    int find(int i) {
        while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
        return i;
    }
    void unite(int a, int b) {
        a = find(a);
        b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<int> parent_;
};

// Index (3t + k) of the corner of triangle t at vertex v.
int cornerOf(const SurfaceMesh& mesh, int t, int v) {
    const auto& tri = mesh.triangles[t];
    return 3 * t + (tri[0] == v ? 0 : tri[1] == v ? 1 : 2);
}

std::string plural(std::size_t n, const char* singular, const char* pluralForm) {
    return std::to_string(n) + " " + (n == 1 ? singular : pluralForm);
}

} // namespace

EdgeTable buildEdgeTable(const SurfaceMesh& mesh) {
    // Every side of every taking-part triangle as a half-edge, sorted so that the
    // uses of one undirected edge are adjacent (deterministic, no hashing).
    struct HalfEdge {
        int low, high, triangle, side, direction;
    };
    std::vector<HalfEdge> halfEdges;
    halfEdges.reserve(3 * mesh.triangles.size());
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        const auto& tri = mesh.triangles[t];
        if (!takesPart(mesh, tri)) continue;
        for (int k = 0; k < 3; ++k) {
            const int a = tri[k];
            const int b = tri[(k + 1) % 3];
            halfEdges.push_back({std::min(a, b), std::max(a, b), t, k, a < b ? +1 : -1});
        }
    }
    std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge& x, const HalfEdge& y) {
        return std::tie(x.low, x.high, x.triangle, x.side) <
               std::tie(y.low, y.high, y.triangle, y.side);
    });

    EdgeTable table;
    table.triangleEdges.assign(mesh.triangles.size(), {-1, -1, -1});
    for (std::size_t i = 0; i < halfEdges.size();) {
        const int e = static_cast<int>(table.edges.size());
        MeshEdge edge;
        edge.vertices = {halfEdges[i].low, halfEdges[i].high};
        for (; i < halfEdges.size() && halfEdges[i].low == edge.vertices[0] &&
               halfEdges[i].high == edge.vertices[1];
             ++i) {
            const HalfEdge& h = halfEdges[i];
            if (edge.faceCount < 2) {
                edge.triangles[edge.faceCount] = h.triangle;
                edge.direction[edge.faceCount] = h.direction;
            } else {
                table.extraUses.push_back({e, h.triangle, h.direction});
            }
            ++edge.faceCount;
            table.triangleEdges[h.triangle][h.side] = e;
        }
        table.edges.push_back(edge);
    }
    return table;
}

bool TopologyReport::usable() const {
    return !empty() && invalidTriangles.empty() && nonFiniteVertices.empty() &&
           degenerateTriangles.empty() && closed() && manifold() && consistentlyOriented() &&
           outward();
}

TopologyReport checkTopology(const SurfaceMesh& mesh, double relativeTolerance) {
    TopologyReport report;
    const BoundingBox box = boundingBox(mesh);
    const double diagonal = box.diagonal();
    report.lengthTolerance = relativeTolerance * diagonal;
    report.volumeTolerance = 1e-3 * relativeTolerance * diagonal * diagonal * diagonal;

    // Element-wise checks.
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        if (!hasValidIndices(mesh, mesh.triangles[t]))
            report.invalidTriangles.push_back(t);
        else if (isDegenerate(mesh, t, report.lengthTolerance))
            report.degenerateTriangles.push_back(t);
    }
    for (int v = 0; v < mesh.nVertices(); ++v)
        if (!mesh.vertices[v].allFinite()) report.nonFiniteVertices.push_back(v);

    // Edge checks.
    report.edgeTable = buildEdgeTable(mesh);
    const auto& edges = report.edgeTable.edges;
    for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
        const MeshEdge& edge = edges[e];
        if (edge.faceCount == 1) report.boundaryEdges.push_back(e);
        if (edge.faceCount > 2) report.nonManifoldEdges.push_back(e);
        if (edge.faceCount == 2 && edge.direction[0] == edge.direction[1])
            report.inconsistentEdges.push_back(e);
    }

    // Fans around vertices: corners of the triangles meeting at a vertex are
    // joined across the manifold edges through it; more than one group at a
    // vertex means separate sheets touch there (e.g. two cones tip to tip).
    DisjointSets corners(3 * mesh.triangles.size());
    DisjointSets shells(mesh.triangles.size());
    for (const MeshEdge& edge : edges) {
        if (edge.faceCount >= 2) shells.unite(edge.triangles[0], edge.triangles[1]);
        if (edge.faceCount != 2) continue;
        for (int v : edge.vertices)
            corners.unite(cornerOf(mesh, edge.triangles[0], v),
                          cornerOf(mesh, edge.triangles[1], v));
    }
    for (const auto& extra : report.edgeTable.extraUses)
        shells.unite(edges[extra.edge].triangles[0], extra.triangle);

    std::vector<int> firstFan(mesh.vertices.size(), -1);
    std::vector<char> manyFans(mesh.vertices.size(), 0);
    std::vector<char> used(mesh.vertices.size(), 0);
    int facesTakingPart = 0;
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        const auto& tri = mesh.triangles[t];
        if (!takesPart(mesh, tri)) continue;
        ++facesTakingPart;
        for (int k = 0; k < 3; ++k) {
            const int v = tri[k];
            const int fan = corners.find(3 * t + k);
            used[v] = 1;
            if (firstFan[v] < 0)
                firstFan[v] = fan;
            else if (firstFan[v] != fan)
                manyFans[v] = 1;
        }
    }
    for (int v = 0; v < mesh.nVertices(); ++v) {
        if (manyFans[v]) report.nonManifoldVertices.push_back(v);
        if (!used[v]) ++report.unusedVertices;
    }
    report.eulerCharacteristic = static_cast<int>(std::count(used.begin(), used.end(), 1)) -
                                 static_cast<int>(edges.size()) + facesTakingPart;

    // Signed volume per shell (divergence theorem, tetrahedra to the box centre,
    // which keeps the terms small and the cancellation mild).
    std::vector<int> shellOf(mesh.triangles.size(), -1);
    std::vector<meshDetail::CompensatedSum> shellSums;
    const Vec3 origin = box.centre();
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        if (!takesPart(mesh, mesh.triangles[t])) continue;
        const int root = shells.find(t);
        if (shellOf[root] < 0) {
            shellOf[root] = static_cast<int>(shellSums.size());
            shellSums.emplace_back();
        }
        const Vec3 a = mesh.corner(t, 0) - origin;
        const Vec3 b = mesh.corner(t, 1) - origin;
        const Vec3 c = mesh.corner(t, 2) - origin;
        shellSums[shellOf[root]].add(a.dot(b.cross(c)) / 6.0);
    }
    report.shells = static_cast<int>(shellSums.size());
    meshDetail::CompensatedSum total;
    for (const auto& sum : shellSums) {
        report.shellVolumes.push_back(sum.value());
        total.add(sum.value());
    }
    report.signedVolume = total.value();
    return report;
}

namespace {

// "edge between vertex 1 at (..) and vertex 2 at (..) (triangles 3, 8)"
std::string describeTableEdge(const SurfaceMesh& mesh, const EdgeTable& table, int e) {
    const MeshEdge& edge = table.edges[e];
    std::string text = describeEdge(mesh, edge.vertices[0], edge.vertices[1]) + " (";
    text += edge.faceCount == 1 ? "only triangle " : "triangles ";
    std::vector<int> faces;
    for (int i = 0; i < std::min(edge.faceCount, 2); ++i) faces.push_back(edge.triangles[i]);
    for (const auto& extra : table.extraUses)
        if (extra.edge == e) faces.push_back(extra.triangle);
    for (std::size_t i = 0; i < faces.size(); ++i)
        text += (i ? ", " : "") + std::to_string(faces[i]);
    return text + ")";
}

// Up to maxListed elements of a list, one per "; "-separated item.
template <class Describe>
std::string listElements(const std::vector<int>& items, int maxListed, Describe describe) {
    std::string text;
    const std::size_t n = std::min(items.size(), static_cast<std::size_t>(std::max(maxListed, 1)));
    for (std::size_t i = 0; i < n; ++i) text += (i ? "; " : "") + describe(items[i]);
    if (items.size() > n) text += "; ... (" + std::to_string(items.size() - n) + " more)";
    return text;
}

} // namespace

std::vector<std::string> describeProblems(const SurfaceMesh& mesh, const TopologyReport& report,
                                          int maxListed) {
    std::vector<std::string> lines;
    const std::string& src = mesh.source;
    const auto& table = report.edgeTable;
    auto triangle = [&](int t) { return describeTriangle(mesh, t); };
    auto vertex = [&](int v) { return describeVertex(mesh, v); };
    auto edge = [&](int e) { return describeTableEdge(mesh, table, e); };

    // Most fundamental first: later checks are meaningless while earlier ones fail.
    if (report.empty()) {
        lines.push_back(src + ": mesh has no triangles, expected a closed triangle surface");
        return lines;
    }
    if (!report.invalidTriangles.empty())
        lines.push_back(src + ": " +
                        plural(report.invalidTriangles.size(), "triangle uses", "triangles use") +
                        " a vertex index out of range (expected 0 to " +
                        std::to_string(mesh.nVertices() - 1) +
                        "): " + listElements(report.invalidTriangles, maxListed, triangle));
    if (!report.nonFiniteVertices.empty())
        lines.push_back(src + ": " +
                        plural(report.nonFiniteVertices.size(), "vertex has", "vertices have") +
                        " non-finite coordinates (expected finite numbers): " +
                        listElements(report.nonFiniteVertices, maxListed, vertex));
    if (!report.degenerateTriangles.empty())
        lines.push_back(
            src + ": " + plural(report.degenerateTriangles.size(), "degenerate triangle", "degenerate triangles") +
            " (zero area or a repeated vertex; height at most " + formatNumber(report.lengthTolerance) +
            "): " + listElements(report.degenerateTriangles, maxListed, triangle) +
            "; expected every triangle to have non-zero area");
    if (!report.nonManifoldEdges.empty())
        lines.push_back(src + ": mesh is not manifold: " +
                        plural(report.nonManifoldEdges.size(), "edge is", "edges are") +
                        " shared by more than two triangles: " +
                        listElements(report.nonManifoldEdges, maxListed, edge) +
                        "; expected every edge shared by exactly two triangles");
    if (!report.boundaryEdges.empty())
        lines.push_back(src + ": mesh is open (not closed): " +
                        plural(report.boundaryEdges.size(), "boundary edge belongs", "boundary edges belong") +
                        " to only one triangle: " +
                        listElements(report.boundaryEdges, maxListed, edge) +
                        "; expected every edge shared by exactly two triangles");
    if (!report.inconsistentEdges.empty())
        lines.push_back(src + ": triangles are not consistently oriented: " +
                        plural(report.inconsistentEdges.size(), "edge is", "edges are") +
                        " run in the same direction by both its triangles: " +
                        listElements(report.inconsistentEdges, maxListed, edge) +
                        "; expected neighbouring triangles to run a shared edge in opposite "
                        "directions (reverse the odd triangles)");
    if (!report.nonManifoldVertices.empty())
        lines.push_back(src + ": mesh is not manifold at " +
                        plural(report.nonManifoldVertices.size(), "vertex", "vertices") +
                        " where separate sheets touch: " +
                        listElements(report.nonManifoldVertices, maxListed, vertex) +
                        "; expected the triangles around each vertex to form a single fan");
    // Volume is only meaningful for a closed, consistently oriented surface.
    if (!lines.empty()) return lines;
    if (report.zeroVolume())
        lines.push_back(src + ": mesh encloses zero volume (signed volume " +
                        formatNumber(report.signedVolume) + ", tolerance " +
                        formatNumber(report.volumeTolerance) +
                        "): it is flat or its parts cancel; expected a solid");
    else if (report.inverted())
        lines.push_back(src + ": mesh is inverted (inside out, normals point inward): signed volume " +
                        formatNumber(report.signedVolume) + " < 0" +
                        (report.shells == 1 ? ", e.g. " + triangle(0) + " has normal " +
                                                  formatPoint(mesh.normal(0))
                                            : std::string()) +
                        "; expected triangles counter-clockwise seen from outside (reverse every "
                        "triangle)");
    return lines;
}

std::vector<std::string> problemNames(const TopologyReport& report) {
    std::vector<std::string> names;
    if (report.empty()) return {"empty"};
    if (!report.invalidTriangles.empty()) names.push_back("invalid vertex indices");
    if (!report.nonFiniteVertices.empty()) names.push_back("non-finite vertices");
    if (!report.degenerateTriangles.empty()) names.push_back("degenerate triangles");
    if (!report.nonManifoldEdges.empty()) names.push_back("non-manifold edges");
    if (!report.boundaryEdges.empty()) names.push_back("open");
    if (!report.inconsistentEdges.empty()) names.push_back("inconsistently oriented");
    if (!report.nonManifoldVertices.empty()) names.push_back("non-manifold vertices");
    if (names.empty() && report.zeroVolume()) names.push_back("zero volume");
    if (names.empty() && report.inverted()) names.push_back("inverted (normals inward)");
    return names;
}

void requireUsable(const SurfaceMesh& mesh) {
    const TopologyReport report = checkTopology(mesh);
    if (report.usable()) return;
    const auto problems = describeProblems(mesh, report, 1);
    std::string message = problems.empty() ? mesh.source + ": mesh is unusable" : problems.front();
    // Only the first element of the first kind is named here; say where the rest is.
    const std::size_t elements =
        report.invalidTriangles.size() + report.nonFiniteVertices.size() +
        report.degenerateTriangles.size() + report.nonManifoldEdges.size() +
        report.boundaryEdges.size() + report.inconsistentEdges.size() +
        report.nonManifoldVertices.size();
    if (elements > 1) message += " (magCheckMesh lists every problem)";
    throw InputError(message);
}

} // namespace mag

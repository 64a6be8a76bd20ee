// Edge table and the usability checks of a body's surface mesh.
#include <magFoam/MeshTopology.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"

#include <algorithm>
#include <limits>
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

// ---------------------------------------------------------------------------
// Embedding test. Every test asks "closer than tol?", so that a touch counts as
// a crossing and round-off cannot slip a crossing through; elements shared by
// index are left out, so that neighbours meeting at them are never flagged.

double pointSegmentDistance2(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (a + t * ab - p).squaredNorm();
}

// Squared distance between segments p1q1 and p2q2: the interior critical point
// when it lies on both segments, else the closest endpoint pair. Nearly parallel
// segments make the critical point inaccurate, but it is still a pair of points on
// the segments, so the result never falls below the true distance.
double segmentDistance2(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
    double best = std::min({pointSegmentDistance2(p1, p2, q2), pointSegmentDistance2(q1, p2, q2),
                            pointSegmentDistance2(p2, p1, q1), pointSegmentDistance2(q2, p1, q1)});
    const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const double a = d1.squaredNorm(), b = d1.dot(d2), e = d2.squaredNorm();
    const double c = d1.dot(r), f = d2.dot(r);
    const double denominator = a * e - b * b;
    if (denominator > 0.0) {
        const double s = (b * f - c * e) / denominator;
        const double t = (a * f - b * c) / denominator;
        if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)
            best = std::min(best, (r + s * d1 - t * d2).squaredNorm());
    }
    return best;
}

// A triangle prepared for the pair tests: corners, unit normal, vertex indices,
// and its box grown by tol.
struct TestTriangle {
    std::array<Vec3, 3> p;
    Vec3 n;
    std::array<int, 3> v;
    Vec3 lower, upper;
};

// Segment pq within tol of triangle T (distance, so touching counts).
bool segmentNearTriangle(const Vec3& p, const Vec3& q, const TestTriangle& T, double tol) {
    if ((p.cwiseMin(q).array() > T.upper.array()).any() || (p.cwiseMax(q).array() < T.lower.array()).any())
        return false;
    const double dp = T.n.dot(p - T.p[0]), dq = T.n.dot(q - T.p[0]);
    if ((dp > tol && dq > tol) || (dp < -tol && dq < -tol)) return false;
    // Piercing the plane inside the triangle (zero distance).
    if ((dp > 0.0 && dq < 0.0) || (dp < 0.0 && dq > 0.0)) {
        const Vec3 x = p + (dp / (dp - dq)) * (q - p);
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k)
            inside = T.n.dot((T.p[(k + 1) % 3] - T.p[k]).cross(x - T.p[k])) >= 0.0;
        if (inside) return true;
    }
    // Otherwise the closest pair has an endpoint of pq or a point of T's boundary.
    const double tol2 = tol * tol;
    for (const Vec3* e : {&p, &q})
        if ((closestPointOnTriangle(*e, T.p[0], T.p[1], T.p[2]) - *e).squaredNorm() <= tol2)
            return true;
    for (int k = 0; k < 3; ++k)
        if (segmentDistance2(p, q, T.p[k], T.p[(k + 1) % 3]) <= tol2) return true;
    return false;
}

// All corners of B farther than tol from A's plane, on one side.
bool planeSeparates(const TestTriangle& A, const TestTriangle& B, double tol) {
    int above = 0, below = 0;
    for (const Vec3& x : B.p) {
        const double d = A.n.dot(x - A.p[0]);
        above += d > tol;
        below += d < -tol;
    }
    return above == 3 || below == 3;
}

// Corners of A shared (by index) with B: their count, and where each sits in B.
int sharedCorners(const TestTriangle& A, const TestTriangle& B, std::array<int, 3>& inB) {
    int shared = 0;
    inB = {-1, -1, -1};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (A.v[i] == B.v[j]) {
                inB[i] = j;
                ++shared;
            }
    return shared;
}

// Whether two triangles meet where the surface forbids it (see TopologyReport).
// `certified` marks vertices whose star is known to be clean (certifyStars).
bool trianglesIntersect(const TestTriangle& A, const TestTriangle& B, double tol,
                        const std::vector<char>& certified) {
    std::array<int, 3> inB;
    const int shared = sharedCorners(A, B, inB);
    if (shared == 3) return true;  // the same triangle twice
    if (shared == 0) {
        if (planeSeparates(A, B, tol) || planeSeparates(B, A, tol)) return false;
        // Two triangles meet iff an edge of one meets the other.
        for (int k = 0; k < 3; ++k)
            if (segmentNearTriangle(A.p[k], A.p[(k + 1) % 3], B, tol) ||
                segmentNearTriangle(B.p[k], B.p[(k + 1) % 3], A, tol))
                return true;
        return false;
    }
    if (shared == 1) {
        // The intersection is convex and holds the shared vertex; if it holds any
        // other point, it reaches the edge opposite that vertex in one of them.
        const int i = static_cast<int>(std::find_if(inB.begin(), inB.end(), [](int j) { return j >= 0; }) -
                                       inB.begin());
        if (certified[A.v[i]]) return false;
        const int j = inB[i];
        return segmentNearTriangle(A.p[(i + 1) % 3], A.p[(i + 2) % 3], B, tol) ||
               segmentNearTriangle(B.p[(j + 1) % 3], B.p[(j + 2) % 3], A, tol);
    }
    // One shared edge: the planes meet along it, so they can only overlap when
    // folded flat onto each other: a third corner in the other's plane, on the
    // same side of the edge as the other's third corner.
    const int a = static_cast<int>(std::find(inB.begin(), inB.end(), -1) - inB.begin());
    int b = 0;
    while (std::find(A.v.begin(), A.v.end(), B.v[b]) != A.v.end()) ++b;
    const Vec3& u = A.p[(a + 1) % 3];
    const Vec3 edge = A.p[(a + 2) % 3] - u;
    auto across = [&](const Vec3& x) { return (x - u) - edge * ((x - u).dot(edge) / edge.squaredNorm()); };
    const bool sameSide = across(A.p[a]).dot(across(B.p[b])) > 0.0;
    return sameSide && (std::abs(A.n.dot(B.p[b] - u)) <= tol || std::abs(B.n.dot(A.p[a] - u)) <= tol);
}

// Vertices whose star is clean: projected onto the plane normal to the sum of
// its triangles' area vectors, the triangles around the vertex turn once around
// it (positive angles summing to 2 pi), so two of them that share only this
// vertex lie in separate sectors and cannot meet elsewhere, with a margin:
// the nearest opposite edge times the sine of the narrowest sector exceeds
// 2 tol. Fans around one vertex (a cylinder's cap) have boxes that all
// overlap; certified, their pairs need no test. Only vertices whose triangles
// form one closed, oriented fan of tested triangles qualify: manifold vertex,
// every edge at it shared by two triangles in opposite directions.
std::vector<char> certifyStars(const SurfaceMesh& mesh, const TopologyReport& report,
                               const std::vector<TestTriangle>& tris, const std::vector<int>& candidate) {
    std::vector<char> certified(mesh.vertices.size(), 0);
    std::vector<char> closedFan(mesh.vertices.size(), 1);
    for (int v : report.nonManifoldVertices) closedFan[v] = 0;
    for (const MeshEdge& edge : report.edgeTable.edges)
        if (edge.faceCount != 2 || edge.direction[0] == edge.direction[1])
            closedFan[edge.vertices[0]] = closedFan[edge.vertices[1]] = 0;
    for (int t = 0; t < mesh.nTriangles(); ++t)
        if (candidate[t] < 0)
            for (int v : mesh.triangles[t])
                if (v >= 0 && v < mesh.nVertices()) closedFan[v] = 0;
    // Triangles around each vertex (compressed rows).
    std::vector<int> start(mesh.vertices.size() + 1, 0), around(3 * tris.size());
    for (const TestTriangle& T : tris)
        for (int v : T.v) ++start[v + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int t = 0; t < static_cast<int>(tris.size()); ++t)
        for (int v : tris[t].v) around[fill[v]++] = t;

    const double tol = report.lengthTolerance;
    for (int v = 0; v < mesh.nVertices(); ++v) {
        if (!closedFan[v] || start[v + 1] - start[v] < 3) continue;
        Vec3 normal = Vec3::Zero();
        for (int k = start[v]; k < start[v + 1]; ++k) {
            const TestTriangle& T = tris[around[k]];
            normal += (T.p[1] - T.p[0]).cross(T.p[2] - T.p[0]);  // twice the area vector
        }
        if (!(normal.norm() > 0.0)) continue;
        const Vec3 n = normal.normalized();
        double sum = 0.0, narrowest = pi, nearest = std::numeric_limits<double>::infinity();
        bool turning = true;
        for (int k = start[v]; k < start[v + 1] && turning; ++k) {
            const TestTriangle& T = tris[around[k]];
            const int c = static_cast<int>(std::find(T.v.begin(), T.v.end(), v) - T.v.begin());
            const Vec3 u1 = T.p[(c + 1) % 3] - T.p[c], u2 = T.p[(c + 2) % 3] - T.p[c];
            const Vec3 p1 = u1 - n * n.dot(u1), p2 = u2 - n * n.dot(u2);
            const double sine = n.dot(p1.cross(p2));
            turning = sine > 0.0;
            const double angle = std::atan2(sine, p1.dot(p2));
            sum += angle;
            narrowest = std::min(narrowest, angle);
            nearest = std::min(nearest, pointSegmentDistance2(Vec3::Zero(), p1, p2));
        }
        certified[v] = turning && std::abs(sum - 2.0 * pi) < 1e-6 &&
                       std::sqrt(nearest) * std::sin(std::min(narrowest, 0.5 * pi)) > 2.0 * tol;
    }
    return certified;
}

// Bounding-volume hierarchy over the triangles' boxes: median splits along the
// longest axis of the box centres. Unlike a sweep along one axis it stays
// O(n log n + overlapping pairs) for long parallel triangles (a needle's sides).
// A node whose triangles all share a certified vertex is skipped as a whole by
// a query triangle that shares it too.
class BoxTree {
public:
    BoxTree(const std::vector<TestTriangle>& tris, const std::vector<char>& certified)
        : tris_(tris), certified_(certified), items_(tris.size()) {
        std::iota(items_.begin(), items_.end(), 0);
        if (!items_.empty()) build(0, static_cast<int>(items_.size()));  // root: node 0
    }

    // Calls visit(j) for every triangle j > i whose box overlaps triangle i's,
    // except those in nodes skipped as above.
    template <class Visit>
    void forOverlaps(int i, Visit&& visit) const {
        if (nodes_.empty()) return;
        const TestTriangle& T = tris_[i];
        int stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (node.common >= 0 && std::find(T.v.begin(), T.v.end(), node.common) != T.v.end()) continue;
            if ((T.lower.array() > node.upper.array()).any() || (T.upper.array() < node.lower.array()).any())
                continue;
            if (node.count > 0) {
                for (int k = node.first; k < node.first + node.count; ++k) {
                    const int j = items_[k];
                    const TestTriangle& U = tris_[j];
                    if (j > i && !(T.lower.array() > U.upper.array()).any() &&
                        !(T.upper.array() < U.lower.array()).any())
                        visit(j);
                }
            } else {
                stack[top++] = node.left;
                stack[top++] = node.right;
            }
        }
    }

private:
    struct Node {
        Vec3 lower, upper;
        int left = -1, right = -1;  // children (inner nodes)
        int first = 0, count = 0;   // items_[first, first + count) (leaves)
        int common = -1;            // a certified vertex of all its triangles, or -1
    };

    // Returns the node's index. Median splits keep the depth near log2(n), far
    // inside forOverlaps' stack.
    int build(int first, int count) {
        Node node;
        node.lower = tris_[items_[first]].lower;
        node.upper = tris_[items_[first]].upper;
        Vec3 cLower = 0.5 * (node.lower + node.upper), cUpper = cLower;
        for (int k = first; k < first + count; ++k) {
            const TestTriangle& T = tris_[items_[k]];
            node.lower = node.lower.cwiseMin(T.lower);
            node.upper = node.upper.cwiseMax(T.upper);
            const Vec3 c = 0.5 * (T.lower + T.upper);
            cLower = cLower.cwiseMin(c);
            cUpper = cUpper.cwiseMax(c);
        }
        const int id = static_cast<int>(nodes_.size());
        nodes_.push_back(node);
        if (count <= 4) {
            nodes_[id].first = first;
            nodes_[id].count = count;
            for (int v : tris_[items_[first]].v) {
                bool all = certified_[v] != 0;
                for (int k = first + 1; k < first + count && all; ++k)
                    all = std::find(tris_[items_[k]].v.begin(), tris_[items_[k]].v.end(), v) !=
                          tris_[items_[k]].v.end();
                if (all) {
                    nodes_[id].common = v;
                    break;
                }
            }
            return id;
        }
        int axis = 0;
        (cUpper - cLower).maxCoeff(&axis);
        const int half = count / 2;
        const auto begin = items_.begin() + first;
        std::nth_element(begin, begin + half, begin + count, [&](int a, int b) {
            return tris_[a].lower[axis] + tris_[a].upper[axis] < tris_[b].lower[axis] + tris_[b].upper[axis];
        });
        const int left = build(first, half);
        const int right = build(first + half, count - half);
        nodes_[id].left = left;
        nodes_[id].right = right;
        if (nodes_[left].common == nodes_[right].common) nodes_[id].common = nodes_[left].common;
        return id;
    }

    const std::vector<TestTriangle>& tris_;
    const std::vector<char>& certified_;
    std::vector<int> items_;
    std::vector<Node> nodes_;
};

// Every pair of triangles that may meet, through the exact pair test: pairs that
// share an edge from the edge table, the others from the tree. Triangles that
// are invalid, degenerate or have non-finite corners are reported elsewhere and
// skipped.
void findIntersections(const SurfaceMesh& mesh, TopologyReport& report) {
    const double tol = report.lengthTolerance;
    std::vector<int> ids;                                   // candidate -> triangle
    std::vector<int> candidate(mesh.triangles.size(), -1);  // triangle -> candidate
    std::vector<TestTriangle> tris;
    const std::vector<int>& degenerate = report.degenerateTriangles;
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        const auto& tri = mesh.triangles[t];
        if (!hasValidIndices(mesh, tri) || std::binary_search(degenerate.begin(), degenerate.end(), t))
            continue;
        TestTriangle T{{mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)}, mesh.normal(t), tri, {},
                       {}};
        if (!(T.p[0].allFinite() && T.p[1].allFinite() && T.p[2].allFinite() && T.n.allFinite())) continue;
        T.lower = T.p[0].cwiseMin(T.p[1]).cwiseMin(T.p[2]).array() - tol;
        T.upper = T.p[0].cwiseMax(T.p[1]).cwiseMax(T.p[2]).array() + tol;
        candidate[t] = static_cast<int>(ids.size());
        ids.push_back(t);
        tris.push_back(T);
    }
    const std::vector<char> certified = certifyStars(mesh, report, tris, candidate);

    auto& pairs = report.intersectingTriangles;
    const std::size_t keep = TopologyReport::maxStoredIntersections;
    auto keepLowest = [&] {
        std::sort(pairs.begin(), pairs.end());
        if (pairs.size() > keep) pairs.resize(keep);
    };

    // Pairs over an edge (a triangle repeated shares three: unique them).
    const EdgeTable& table = report.edgeTable;
    std::vector<std::vector<int>> extra(table.edges.size());
    for (const auto& use : table.extraUses) extra[use.edge].push_back(use.triangle);
    std::vector<std::array<int, 2>> overEdges;
    for (std::size_t e = 0; e < table.edges.size(); ++e) {
        std::vector<int> faces(table.edges[e].triangles.begin(),
                               table.edges[e].triangles.begin() + std::min(table.edges[e].faceCount, 2));
        faces.insert(faces.end(), extra[e].begin(), extra[e].end());
        for (std::size_t a = 0; a < faces.size(); ++a)
            for (std::size_t b = a + 1; b < faces.size(); ++b) {
                const int x = candidate[faces[a]], y = candidate[faces[b]];
                if (x >= 0 && y >= 0 && trianglesIntersect(tris[x], tris[y], tol, certified))
                    overEdges.push_back({std::min(faces[a], faces[b]), std::max(faces[a], faces[b])});
            }
    }
    std::sort(overEdges.begin(), overEdges.end());
    overEdges.erase(std::unique(overEdges.begin(), overEdges.end()), overEdges.end());
    report.intersectingPairs += overEdges.size();
    pairs = std::move(overEdges);
    keepLowest();

    // The other pairs: no shared vertex, or one.
    const BoxTree tree(tris, certified);
    for (int x = 0; x < static_cast<int>(tris.size()); ++x)
        tree.forOverlaps(x, [&](int y) {
            std::array<int, 3> inB;
            if (sharedCorners(tris[x], tris[y], inB) >= 2) return;  // done above
            if (!trianglesIntersect(tris[x], tris[y], tol, certified)) return;
            ++report.intersectingPairs;
            pairs.push_back({ids[x], ids[y]});  // ids ascend with x, y
            if (pairs.size() >= 2 * keep) keepLowest();
        });
    keepLowest();
}

// Nesting of shells: for a vertex of each shell, the winding number of every
// other shell whose box holds it (0 outside, +-1 inside; the shells neither
// cross nor touch, so the vertex is never on another shell). The innermost
// enclosing shell is the one of least |volume|. Valid when the orientations
// alternate from the outside in: outward, inverted (cavity), outward, ...
void checkNesting(const SurfaceMesh& mesh, TopologyReport& report) {
    const int n = report.shells;
    std::vector<std::vector<int>> members(n);
    for (int t = 0; t < mesh.nTriangles(); ++t)
        if (report.triangleShell[t] >= 0) members[report.triangleShell[t]].push_back(t);
    std::vector<BoundingBox> boxes(n);
    for (int s = 0; s < n; ++s) {
        boxes[s].lower = boxes[s].upper = mesh.corner(members[s][0], 0);
        for (int t : members[s])
            for (int k = 0; k < 3; ++k) {
                boxes[s].lower = boxes[s].lower.cwiseMin(mesh.corner(t, k));
                boxes[s].upper = boxes[s].upper.cwiseMax(mesh.corner(t, k));
            }
    }
    report.shellContainers.assign(n, -1);
    for (int s = 0; s < n; ++s) {
        const Vec3& p = mesh.corner(members[s][0], 0);
        for (int c = 0; c < n; ++c) {
            if (c == s || (p.array() < boxes[c].lower.array()).any() ||
                (p.array() > boxes[c].upper.array()).any())
                continue;
            double angle = 0.0;
            for (int t : members[c])
                angle += triangleSolidAngle(mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2), p);
            if (std::abs(angle) < 2.0 * pi) continue;  // winding number 0
            const int inner = report.shellContainers[s];
            if (inner < 0 || std::abs(report.shellVolumes[c]) < std::abs(report.shellVolumes[inner]))
                report.shellContainers[s] = c;
        }
        const int c = report.shellContainers[s];
        const bool outward = report.shellVolumes[s] > 0.0;
        if (c < 0 ? !outward : outward == (report.shellVolumes[c] > 0.0))
            report.misnestedShells.push_back(s);
    }
    report.nestingChecked = true;
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
           nonIntersecting() && properlyNested() && outward();
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
    report.triangleShell.assign(mesh.triangles.size(), -1);
    for (int t = 0; t < mesh.nTriangles(); ++t)
        if (takesPart(mesh, mesh.triangles[t])) report.triangleShell[t] = shellOf[shells.find(t)];

    findIntersections(mesh, report);
    if (report.shells > 1 && report.invalidTriangles.empty() && report.nonFiniteVertices.empty() &&
        report.degenerateTriangles.empty() && report.closed() && report.manifold() &&
        report.consistentlyOriented() && report.nonIntersecting())
        checkNesting(mesh, report);
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

std::string describeShell(const TopologyReport& report, int shell) {
    int first = -1, last = -1, count = 0;
    for (int t = 0; t < static_cast<int>(report.triangleShell.size()); ++t)
        if (report.triangleShell[t] == shell) {
            if (first < 0) first = t;
            last = t;
            ++count;
        }
    if (count == 0) return "shell " + std::to_string(shell);
    if (count == 1) return "shell of triangle " + std::to_string(first);
    if (last - first + 1 == count)
        return "shell of triangles " + std::to_string(first) + "-" + std::to_string(last);
    return "shell of triangle " + std::to_string(first) + " (and " + std::to_string(count - 1) + " more)";
}

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
    // Volume is only meaningful for a closed, consistently oriented surface; a
    // flat one is said to be flat before its folds are listed.
    const bool solidTopology = lines.empty();
    if (solidTopology && report.zeroVolume())
        lines.push_back(src + ": mesh encloses zero volume (signed volume " +
                        formatNumber(report.signedVolume) + ", tolerance " +
                        formatNumber(report.volumeTolerance) +
                        "): it is flat or its parts cancel; expected a solid");
    if (!report.nonIntersecting()) {
        // Pairs are listed by index; a pair from two shells says which shells overlap.
        const std::size_t shown = std::min(report.intersectingTriangles.size(),
                                           static_cast<std::size_t>(std::max(maxListed, 1)));
        std::string list;
        for (std::size_t i = 0; i < shown; ++i) {
            const auto [a, b] = report.intersectingTriangles[i];
            const int sa = report.triangleShell[a], sb = report.triangleShell[b];
            list += (i ? "; " : "") + triangle(a) + " and " + triangle(b);
            if (sa != sb && sa >= 0 && sb >= 0)
                list += " (the " + describeShell(report, sa) + " and the " + describeShell(report, sb) +
                        " overlap)";
        }
        if (report.intersectingPairs > shown)
            list += "; ... (" + std::to_string(report.intersectingPairs - shown) + " more)";
        lines.push_back(src + ": surface intersects itself: " +
                        plural(report.intersectingPairs, "pair of triangles crosses or touches",
                               "pairs of triangles cross or touch") +
                        " away from a shared vertex or edge (closer than " +
                        formatNumber(report.lengthTolerance) + "): " + list +
                        "; expected triangles to meet only along the edge or vertex they share (a "
                        "solid's boundary never crosses itself)");
    }
    if (!solidTopology) return lines;
    if (report.inverted())
        lines.push_back(src + ": mesh is inverted (inside out, normals point inward): signed volume " +
                        formatNumber(report.signedVolume) + " < 0" +
                        (report.shells == 1 ? ", e.g. " + triangle(0) + " has normal " +
                                                  formatPoint(mesh.normal(0))
                                            : std::string()) +
                        "; expected triangles counter-clockwise seen from outside (reverse every "
                        "triangle)");
    if (!report.properlyNested()) {
        auto nesting = [&](int s) {
            const int c = report.shellContainers[s];
            const bool outward = report.shellVolumes[s] > 0.0;
            if (c < 0)
                return "the " + describeShell(report, s) +
                       " is inverted (a cavity) but lies inside no outward shell: its volume counts "
                       "negative";
            return "the " + describeShell(report, s) + " lies inside the " + describeShell(report, c) +
                   " with the same orientation (both " + (outward ? "outward" : "inverted") + "): " +
                   (outward ? "its volume counts twice" : "its cavity is cut out twice");
        };
        lines.push_back(src + ": shells are nested wrongly: " +
                        listElements(report.misnestedShells, maxListed, nesting) +
                        "; expected nested shells to alternate from the outside in: outward, inverted "
                        "(a cavity), outward, ... (reverse the triangles of the shell named first)");
    }
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
    const bool solidTopology = names.empty();
    if (solidTopology && report.zeroVolume()) names.push_back("zero volume");
    if (!report.nonIntersecting()) names.push_back("self-intersecting");
    if (solidTopology && report.inverted()) names.push_back("inverted (normals inward)");
    if (!report.properlyNested()) names.push_back("shells nested wrongly");
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
        report.nonManifoldVertices.size() + report.intersectingPairs + report.misnestedShells.size();
    if (elements > 1) message += " (magCheckMesh lists every problem)";
    throw InputError(message);
}

} // namespace mag

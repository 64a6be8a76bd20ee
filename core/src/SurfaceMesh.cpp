// Triangle surface mesh: geometry queries, welding, clean-up, transforms.
#include <magFoam/SurfaceMesh.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <unordered_map>

namespace mag {

// ---------------------------------------------------------------------------
// Per-triangle geometry

Vec3 SurfaceMesh::areaVector(int t) const {
    const Vec3& a = corner(t, 0);
    return 0.5 * (corner(t, 1) - a).cross(corner(t, 2) - a);
}

Vec3 SurfaceMesh::normal(int t) const {
    const Vec3 n = areaVector(t);
    const double length = n.norm();
    return length > 0.0 ? Vec3(n / length) : Vec3::Zero();
}

double SurfaceMesh::area(int t) const { return areaVector(t).norm(); }

Vec3 SurfaceMesh::centroid(int t) const {
    return (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0;
}

BoundingBox boundingBox(const SurfaceMesh& mesh) {
    // Non-finite vertices are skipped so that one NaN does not poison every
    // tolerance; the topology check reports them.
    BoundingBox box;
    bool first = true;
    for (const Vec3& p : mesh.vertices) {
        if (!p.allFinite()) continue;
        box.lower = first ? p : Vec3(box.lower.cwiseMin(p));
        box.upper = first ? p : Vec3(box.upper.cwiseMax(p));
        first = false;
    }
    return box;
}

double lengthTolerance(const SurfaceMesh& mesh, double relativeTolerance) {
    return relativeTolerance * boundingBox(mesh).diagonal();
}

std::vector<Vec3> triangleNormals(const SurfaceMesh& mesh) {
    std::vector<Vec3> normals(mesh.triangles.size());
    for (int t = 0; t < mesh.nTriangles(); ++t) normals[t] = mesh.normal(t);
    return normals;
}

std::vector<double> triangleAreas(const SurfaceMesh& mesh) {
    std::vector<double> areas(mesh.triangles.size());
    for (int t = 0; t < mesh.nTriangles(); ++t) areas[t] = mesh.area(t);
    return areas;
}

double surfaceArea(const SurfaceMesh& mesh) {
    double total = 0.0;
    for (int t = 0; t < mesh.nTriangles(); ++t) total += mesh.area(t);
    return total;
}

// ---------------------------------------------------------------------------
// Descriptions for messages

std::string formatPoint(const Vec3& p) {
    // 9 digits: enough to tell apart points a weld tolerance (1e-9 relative) apart.
    char buffer[96];
    // "+ 0.0" turns -0 into 0, which only confuses readers.
    std::snprintf(buffer, sizeof buffer, "(%.9g, %.9g, %.9g)", p.x() + 0.0, p.y() + 0.0,
                  p.z() + 0.0);
    return buffer;
}

std::string describeVertex(const SurfaceMesh& mesh, int vertex) {
    std::string text = "vertex " + std::to_string(vertex);
    if (vertex >= 0 && vertex < mesh.nVertices())
        text += " at " + formatPoint(mesh.vertices[vertex]);
    else
        text += " (out of range: the mesh has " + std::to_string(mesh.nVertices()) + " vertices)";
    return text;
}

std::string describeTriangle(const SurfaceMesh& mesh, int triangle) {
    const auto& tri = mesh.triangles.at(triangle);
    std::string text = "triangle " + std::to_string(triangle) + " (vertices " +
                       std::to_string(tri[0]) + ", " + std::to_string(tri[1]) + ", " +
                       std::to_string(tri[2]);
    const bool valid = std::all_of(tri.begin(), tri.end(),
                                   [&](int v) { return v >= 0 && v < mesh.nVertices(); });
    if (valid)
        text += " at " + formatPoint(mesh.vertices[tri[0]]) + ", " +
                formatPoint(mesh.vertices[tri[1]]) + ", " + formatPoint(mesh.vertices[tri[2]]);
    return text + ")";
}

std::string describeEdge(const SurfaceMesh& mesh, int vertexA, int vertexB) {
    return "edge between " + describeVertex(mesh, vertexA) + " and " +
           describeVertex(mesh, vertexB);
}

void requireValidIndices(const SurfaceMesh& mesh) {
    for (int t = 0; t < mesh.nTriangles(); ++t)
        for (int v : mesh.triangles[t])
            if (v < 0 || v >= mesh.nVertices())
                throw InputError(mesh.source + ": " + describeTriangle(mesh, t) +
                                 " uses vertex " + std::to_string(v) + ", expected 0 to " +
                                 std::to_string(mesh.nVertices() - 1));
}

// ---------------------------------------------------------------------------
// Welding and clean-up

namespace {

struct Cell {
    std::int64_t i, j, k;
    bool operator==(const Cell&) const = default;
};

struct CellHash {
    std::size_t operator()(const Cell& c) const {
        // Large odd multipliers spread neighbouring cells over the table.
        const auto h = static_cast<std::uint64_t>(c.i) * 0x9E3779B97F4A7C15ULL ^
                       static_cast<std::uint64_t>(c.j) * 0xC2B2AE3D27D4EB4FULL ^
                       static_cast<std::uint64_t>(c.k) * 0x165667B19E3779F9ULL;
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

void renumberTriangles(SurfaceMesh& mesh, const std::vector<int>& newIndex) {
    for (auto& tri : mesh.triangles)
        for (int& v : tri) v = newIndex[v];
}

} // namespace

int weldVertices(SurfaceMesh& mesh, double relativeTolerance) {
    requireValidIndices(mesh);
    const int n = mesh.nVertices();
    const BoundingBox box = boundingBox(mesh);
    const double tol = relativeTolerance * box.diagonal();

    std::vector<int> newIndex(n);
    std::vector<Vec3> kept;
    kept.reserve(n);

    // Cells of size tol hold the kept vertices; a match lies in one of the 27
    // cells around a point. Cell coordinates are bounded by 1/relativeTolerance,
    // so a tolerance below ~1e-15 (or a zero-size mesh) falls back to exact matching.
    const bool useGrid = std::isfinite(tol) && tol > 0.0 && relativeTolerance >= 1e-15;
    if (useGrid) {
        std::unordered_map<Cell, std::vector<int>, CellHash> grid;
        grid.reserve(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) {
            const Vec3& p = mesh.vertices[i];
            if (!p.allFinite()) {  // never merge NaN/inf; the topology check names them
                newIndex[i] = static_cast<int>(kept.size());
                kept.push_back(p);
                continue;
            }
            const Vec3 q = (p - box.lower) / tol;
            const Cell c{static_cast<std::int64_t>(std::floor(q.x())),
                         static_cast<std::int64_t>(std::floor(q.y())),
                         static_cast<std::int64_t>(std::floor(q.z()))};
            int match = -1;
            for (int di = -1; di <= 1 && match < 0; ++di)
                for (int dj = -1; dj <= 1 && match < 0; ++dj)
                    for (int dk = -1; dk <= 1 && match < 0; ++dk) {
                        const auto it = grid.find({c.i + di, c.j + dj, c.k + dk});
                        if (it == grid.end()) continue;
                        for (int candidate : it->second)
                            if ((kept[candidate] - p).norm() <= tol) {
                                match = candidate;
                                break;
                            }
                    }
            if (match < 0) {
                match = static_cast<int>(kept.size());
                kept.push_back(p);
                grid[c].push_back(match);
            }
            newIndex[i] = match;
        }
    } else {
        std::map<std::array<double, 3>, int> exact;
        for (int i = 0; i < n; ++i) {
            const Vec3& p = mesh.vertices[i];
            const int next = static_cast<int>(kept.size());
            // NaN would break the map's ordering; such vertices stay on their own.
            const bool inserted =
                !p.allFinite() || exact.try_emplace({p.x(), p.y(), p.z()}, next).second;
            newIndex[i] = inserted ? next : exact.at({p.x(), p.y(), p.z()});
            if (inserted) kept.push_back(p);
        }
    }

    const int merged = n - static_cast<int>(kept.size());
    mesh.vertices = std::move(kept);
    renumberTriangles(mesh, newIndex);
    return merged;
}

int removeUnusedVertices(SurfaceMesh& mesh) {
    requireValidIndices(mesh);
    std::vector<int> newIndex(mesh.vertices.size(), -1);
    for (const auto& tri : mesh.triangles)
        for (int v : tri) newIndex[v] = 0;
    std::vector<Vec3> used;
    used.reserve(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
        if (newIndex[i] == 0) {
            newIndex[i] = static_cast<int>(used.size());
            used.push_back(mesh.vertices[i]);
        }
    const int removed = mesh.nVertices() - static_cast<int>(used.size());
    mesh.vertices = std::move(used);
    renumberTriangles(mesh, newIndex);
    return removed;
}

bool isCollapsed(const std::array<int, 3>& tri) {
    return tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
}

bool isDegenerate(const SurfaceMesh& mesh, int t, double lengthTol) {
    if (isCollapsed(mesh.triangles[t])) return true;
    const Vec3& a = mesh.corner(t, 0);
    const Vec3& b = mesh.corner(t, 1);
    const Vec3& c = mesh.corner(t, 2);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (!(longest > lengthTol)) return true;
    // Height over the longest side: zero when the corners are collinear.
    const double height = (b - a).cross(c - a).norm() / longest;
    return !(height > lengthTol);
}

std::vector<int> findDegenerateTriangles(const SurfaceMesh& mesh, double relativeTolerance) {
    requireValidIndices(mesh);
    const double tol = lengthTolerance(mesh, relativeTolerance);
    std::vector<int> degenerate;
    for (int t = 0; t < mesh.nTriangles(); ++t)
        if (isDegenerate(mesh, t, tol)) degenerate.push_back(t);
    return degenerate;
}

namespace {

std::vector<int> removeTriangles(SurfaceMesh& mesh, const std::vector<int>& sortedIndices) {
    if (sortedIndices.empty()) return sortedIndices;
    std::vector<std::array<int, 3>> keptTriangles;
    keptTriangles.reserve(mesh.triangles.size() - sortedIndices.size());
    auto next = sortedIndices.begin();
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        if (next != sortedIndices.end() && *next == t) {
            ++next;
            continue;
        }
        keptTriangles.push_back(mesh.triangles[t]);
    }
    mesh.triangles = std::move(keptTriangles);
    return sortedIndices;
}

} // namespace

std::vector<int> dropDegenerateTriangles(SurfaceMesh& mesh, double relativeTolerance) {
    return removeTriangles(mesh, findDegenerateTriangles(mesh, relativeTolerance));
}

std::vector<int> dropCollapsedTriangles(SurfaceMesh& mesh) {
    std::vector<int> collapsed;
    for (int t = 0; t < mesh.nTriangles(); ++t)
        if (isCollapsed(mesh.triangles[t])) collapsed.push_back(t);
    return removeTriangles(mesh, collapsed);
}

// ---------------------------------------------------------------------------
// Transforms

void translate(SurfaceMesh& mesh, const Vec3& offset) {
    for (Vec3& p : mesh.vertices) p += offset;
}

void rotate(SurfaceMesh& mesh, const Mat3& R) {
    for (Vec3& p : mesh.vertices) p = R * p;
}

void rotate(SurfaceMesh& mesh, const Quat& q) { rotate(mesh, q.normalized().toRotationMatrix()); }

void scale(SurfaceMesh& mesh, double factor) {
    if (!std::isfinite(factor) || factor <= 0.0)
        throw InputError(mesh.source + ": scale factor " + meshDetail::formatNumber(factor) +
                         " is not allowed, expected a finite number > 0");
    for (Vec3& p : mesh.vertices) p *= factor;
}

void transform(SurfaceMesh& mesh, const Mat3& A, const Vec3& offset) {
    const double det = A.determinant();
    if (!A.allFinite() || !offset.allFinite() || !std::isfinite(det) || det == 0.0)
        throw InputError(mesh.source +
                         ": transform matrix is singular or not finite, expected an invertible "
                         "finite 3x3 matrix");
    for (Vec3& p : mesh.vertices) p = A * p + offset;
    // A reflection turns outward normals inward; reversing the triangles undoes it.
    if (det < 0.0) flipOrientation(mesh);
}

void flipOrientation(SurfaceMesh& mesh) {
    for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
}

void append(SurfaceMesh& mesh, const SurfaceMesh& part) {
    const int shift = mesh.nVertices();
    mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const auto& tri : part.triangles)
        mesh.triangles.push_back({tri[0] + shift, tri[1] + shift, tri[2] + shift});
}

double triangleSolidAngle(const Vec3& r1, const Vec3& r2, const Vec3& r3, const Vec3& p) {
    const Vec3 a = r1 - p, b = r2 - p, c = r3 - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + la * b.dot(c) + lb * c.dot(a) + lc * a.dot(b);
    return 2.0 * std::atan2(numerator, denominator);
}

double windingNumber(const SurfaceMesh& mesh, const Vec3& p) {
    double sum = 0;
    for (const auto& t : mesh.triangles)
        sum += triangleSolidAngle(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], p);
    return sum / (4.0 * pi);
}

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denom = 1 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

} // namespace mag

#include "magFoam/ConvexPieces.hpp"

#include "magFoam/Dictionary.hpp"
#include "magFoam/Error.hpp"
#include "magFoam/OutputFile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace mag {

ConvexHull convexHull(const std::vector<Vec3>& input, const std::string& what) {
    for (const Vec3& p : input)
        if (!p.allFinite()) throw InputError(what + ": a point is not finite");
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : input) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double size = input.empty() ? 0.0 : (hi - lo).norm();
    const double tol = 1e-9 * size;

    // Distinct points only: repeated ones (shared ring vertices) change nothing.
    std::vector<Vec3> p;
    for (const Vec3& q : input)
        if (std::none_of(p.begin(), p.end(), [&](const Vec3& r) { return (r - q).norm() <= tol; })) p.push_back(q);
    if (p.size() < 4) throw InputError(what + ": a convex piece needs at least 4 distinct points, got " +
                                       std::to_string(p.size()));
    if (p.size() > 256)
        throw InputError(what + ": a convex piece has at most 256 points, got " + std::to_string(p.size()) +
                         " (split it into smaller pieces)");

    // Every supporting plane through three points: all others on one side.
    // O(n^4) with an early exit, fine for the few dozen points of a piece.
    ConvexHull h;
    const int n = static_cast<int>(p.size());
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k) {
                Vec3 normal = (p[j] - p[i]).cross(p[k] - p[i]);
                const double len = normal.norm();
                if (len <= 1e-9 * size * size) continue;  // (nearly) collinear
                normal /= len;
                // A face met before: the three points lie on its plane.
                bool known = false;
                for (std::size_t f = 0; f < h.normals.size() && !known; ++f) {
                    auto on = [&](const Vec3& q) { return std::abs(h.normals[f].dot(q) - h.offsets[f]) <= tol; };
                    known = on(p[i]) && on(p[j]) && on(p[k]);
                }
                if (known) continue;
                const double d = normal.dot(p[i]);
                bool above = false, below = false;
                for (int m = 0; m < n && !(above && below); ++m) {
                    const double s = normal.dot(p[m]) - d;
                    above |= s > tol, below |= s < -tol;
                }
                if (above && below) continue;
                if (!above && !below) throw InputError(what + ": the points of a convex piece lie in one plane");
                if (above) normal = -normal;
                const double offset = above ? -d : d;
                h.normals.push_back(normal);
                h.offsets.push_back(offset);
            }

    // Vertices: points on at least three faces' planes (others lie on an edge or inside).
    std::vector<int> index(n, -1);
    for (int m = 0; m < n; ++m) {
        int on = 0;
        for (std::size_t f = 0; f < h.normals.size(); ++f) on += std::abs(h.normals[f].dot(p[m]) - h.offsets[f]) <= tol;
        if (on >= 3) index[m] = static_cast<int>(h.points.size()), h.points.push_back(p[m]);
    }
    // Each face: its vertices ordered counter-clockwise about the outward normal.
    Vec3 inside = Vec3::Zero();
    for (const Vec3& q : h.points) inside += q;
    inside /= static_cast<double>(h.points.size());
    for (std::size_t f = 0; f < h.normals.size(); ++f) {
        const Vec3& nf = h.normals[f];
        std::vector<int> loop;
        Vec3 c = Vec3::Zero();
        for (int m = 0; m < n; ++m)
            if (index[m] >= 0 && std::abs(nf.dot(p[m]) - h.offsets[f]) <= tol) loop.push_back(index[m]), c += p[m];
        c /= static_cast<double>(loop.size());
        // Angles computed once: recomputed inside the comparison, a point
        // opposite the first (at +-pi) may round differently from call to
        // call (fused multiply-adds) and break the sort.
        const Vec3 u = (h.points[loop[0]] - c).normalized(), v = nf.cross(u);
        std::vector<std::pair<double, int>> around;
        for (int a : loop) {
            const Vec3 d = h.points[a] - c;
            around.emplace_back(std::atan2(d.dot(v), d.dot(u)), a);
        }
        std::sort(around.begin(), around.end());
        for (std::size_t m = 0; m < loop.size(); ++m) loop[m] = around[m].second;
        // Volume and centroid from the tetrahedra (inside, face fan).
        for (std::size_t m = 1; m + 1 < loop.size(); ++m) {
            const Vec3 &a = h.points[loop[0]], &b = h.points[loop[m]], &e = h.points[loop[m + 1]];
            const double vol = (a - inside).dot((b - inside).cross(e - inside)) / 6.0;
            h.volume += vol;
            h.centroid += vol * (inside + a + b + e) / 4.0;
        }
        h.faces.push_back(std::move(loop));
    }
    h.centroid /= h.volume;
    return h;
}

bool isConvex(const SurfaceMesh& mesh) {
    double size = 0;
    for (const Vec3& v : mesh.vertices) size = std::max(size, v.norm());
    const double tol = 1e-9 * size;
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        const Vec3 n = mesh.normal(t);
        if (n.squaredNorm() == 0) continue;
        const double d = n.dot(mesh.corner(t, 0));
        for (const Vec3& v : mesh.vertices)
            if (n.dot(v) - d > tol) return false;
    }
    return true;
}

std::filesystem::path piecesFileFor(const std::filesystem::path& meshFile) {
    std::filesystem::path file = meshFile;
    return file.replace_extension(".pieces.yaml");
}

ConvexPieces readConvexPieces(const std::filesystem::path& file, double scale) {
    const Dict d = Dict::fromFile(file);
    d.get<std::string>("mesh", "");
    if (!d.has("pieces")) d.reportUnused();  // a misspelt key, before "pieces is missing"
    const auto lists = d.get<std::vector<std::vector<double>>>("pieces");
    d.reportUnused();
    if (lists.empty()) d.fail("pieces", "the list of convex pieces is empty");
    ConvexPieces pieces;
    for (std::size_t k = 0; k < lists.size(); ++k) {
        const auto& c = lists[k];
        if (c.size() % 3 != 0 || c.size() < 12)
            d.fail("pieces", "piece " + std::to_string(k) + ": x y z of at least 4 points expected, got " +
                                 std::to_string(c.size()) + " numbers");
        std::vector<Vec3> points;
        for (std::size_t i = 0; i < c.size(); i += 3) {
            const Vec3 q(c[i], c[i + 1], c[i + 2]);
            if (!q.allFinite()) d.fail("pieces", "piece " + std::to_string(k) + ": a coordinate is not finite");
            points.push_back(scale * q);
        }
        pieces.push_back(std::move(points));
    }
    return pieces;
}

void writeConvexPieces(const std::filesystem::path& file, const std::string& meshName,
                       const ConvexPieces& pieces) {
    std::ostringstream os;
    os.precision(17);
    os << "# Convex pieces of " << meshName << " for collision (docs/rigid-bodies.md#convex-pieces):\n"
       << "# each piece is the convex hull of its points (x y z, the mesh's units).\n"
       << "mesh: " << meshName << "\npieces:\n";
    for (const auto& piece : pieces) {
        os << "  - [";
        for (std::size_t i = 0; i < piece.size(); ++i)
            os << (i ? ", " : "") << piece[i].x() << ", " << piece[i].y() << ", " << piece[i].z();
        os << "]\n";
    }
    writeFileAtomically(file, os.str());
}

std::vector<ConvexHull> buildConvexPieces(const ConvexPieces& pieces, const Vec3& shift,
                                          const SurfaceMesh& mesh, double meshVolume, const std::string& what,
                                          double& volumeMismatch) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double slack = 0.01 * (hi - lo).norm();
    std::vector<ConvexHull> hulls;
    double sum = 0;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
        std::vector<Vec3> points = pieces[k];
        for (Vec3& q : points) {
            q += shift;
            if ((q.array() < lo.array() - slack).any() || (q.array() > hi.array() + slack).any())
                throw InputError(what + ": piece " + std::to_string(k) + " reaches outside the mesh's bounding box (" +
                                 "is the pieces file for another mesh or scale?)");
        }
        hulls.push_back(convexHull(points, what + ": piece " + std::to_string(k)));
        sum += hulls.back().volume;
    }
    volumeMismatch = meshVolume > 0 ? (sum - meshVolume) / meshVolume : 0.0;
    return hulls;
}

} // namespace mag

// Boundary quadrature for the MBM force and torque integrals (see the header).
#include "SurfaceQuadrature.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace mag::mbm {

namespace {

// Corners of a single boundary loop: vertices where the boundary turns (collinear
// intermediate vertices, e.g. from a subdivided box edge, are skipped).
std::vector<Vec3> loopCorners(const PolyhedronTables& tables, const std::vector<int>& loop) {
    const auto& V = tables.vertices();
    std::vector<Vec3> corners;
    const std::size_t m = loop.size();
    for (std::size_t i = 0; i < m; ++i) {
        const Vec3& p = V[static_cast<std::size_t>(loop[(i + m - 1) % m])];
        const Vec3& c = V[static_cast<std::size_t>(loop[i])];
        const Vec3& q = V[static_cast<std::size_t>(loop[(i + 1) % m])];
        const Vec3 e1 = c - p, e2 = q - c;
        // turning angle below 1e-10 rad and no reversal: a straight-through vertex
        if (e1.cross(e2).norm() <= 1e-10 * e1.norm() * e2.norm() && e1.dot(e2) > 0.0) continue;
        corners.push_back(c);
    }
    return corners;
}

// True if the CCW polygon (about n) is strictly convex.
bool isConvex(const std::vector<Vec3>& c, const Vec3& n) {
    const std::size_t m = c.size();
    for (std::size_t i = 0; i < m; ++i) {
        const Vec3 e1 = c[i] - c[(i + m - 1) % m], e2 = c[(i + 1) % m] - c[i];
        if (!(e1.cross(e2).dot(n) > 0.0)) return false;
    }
    return true;
}

struct Builder {
    SurfaceQuadrature& q;
    int face;
    Vec3 normal;
    void add(const Vec3& p, double w) {
        q.points.push_back(p);
        q.weights.push_back(w);
        q.normals.push_back(normal);
        q.faces.push_back(face);
    }
};

void regularQuad(Builder& b, const std::vector<Vec3>& c, int n) {
    // Cell centres; |J| is linear on a planar quad, so |J(centre)|/n^2 is the cell area.
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Vec3 p;
            double jac;
            bilinearMap(c, (i + 0.5) / n, (j + 0.5) / n, p, jac);
            b.add(p, jac / (double(n) * n));
        }
}

void regularTriangle(Builder& b, const Vec3& r0, const Vec3& r1, const Vec3& r2, int n) {
    const Vec3 e1 = r1 - r0, e2 = r2 - r0;
    const double w = 0.5 * e1.cross(e2).norm() / (double(n) * n);
    // Centroids of the n^2 congruent sub-triangles of the n-fold subdivision.
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
            b.add(r0 + ((i + 1.0 / 3.0) / n) * e1 + ((j + 1.0 / 3.0) / n) * e2, w);
            if (i + j < n - 1)
                b.add(r0 + ((i + 2.0 / 3.0) / n) * e1 + ((j + 2.0 / 3.0) / n) * e2, w);
        }
}

void gaussQuad(Builder& b, const std::vector<Vec3>& c, const std::vector<double>& x,
               const std::vector<double>& w) {
    const std::size_t n = x.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
            Vec3 p;
            double jac;
            bilinearMap(c, 0.5 * (x[i] + 1), 0.5 * (x[j] + 1), p, jac);
            b.add(p, 0.25 * w[i] * w[j] * jac);
        }
}

void gaussTriangle(Builder& b, const Vec3& r0, const Vec3& r1, const Vec3& r2,
                   const std::vector<double>& x, const std::vector<double>& w) {
    // Collapsed (Duffy) map r0 + u (r1 - r0) + u v (r2 - r1); |J| = 2 area u.
    const double twiceArea = (r1 - r0).cross(r2 - r0).norm();
    const std::size_t n = x.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double u = 0.5 * (x[i] + 1);
        for (std::size_t j = 0; j < n; ++j) {
            const double v = 0.5 * (x[j] + 1);
            b.add(r0 + u * (r1 - r0) + u * v * (r2 - r1), 0.25 * w[i] * w[j] * twiceArea * u);
        }
    }
}

} // namespace

QuadratureRule quadratureRuleFromName(std::string_view name) {
    if (name == "regular") return QuadratureRule::regular;
    if (name == "gauss") return QuadratureRule::gauss;
    throw std::invalid_argument("unknown quadrature rule '" + std::string(name) +
                                "'; valid rules: gauss, regular");
}

void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    if (n < 1) throw std::invalid_argument("gaussLegendre: n must be >= 1");
    nodes.assign(static_cast<std::size_t>(n), 0.0);
    weights.assign(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        // Tricomi's initial guess, then Newton on P_n (three-term recurrence).
        double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p1 = 1.0, p0 = 0.0;
            for (int j = 1; j <= n; ++j) {
                const double pm = p0;
                p0 = p1;
                p1 = ((2.0 * j - 1.0) * z * p0 - (j - 1.0) * pm) / j;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            const double dz = p1 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        if (n % 2 == 1 && i == n / 2) z = 0.0; // the middle node exactly
        nodes[static_cast<std::size_t>(i)] = -z;
        nodes[static_cast<std::size_t>(n - 1 - i)] = z;
        const double wi = 2.0 / ((1.0 - z * z) * dp * dp);
        weights[static_cast<std::size_t>(i)] = wi;
        weights[static_cast<std::size_t>(n - 1 - i)] = wi;
    }
}

std::vector<Vec3> convexFaceCorners(const PolyhedronTables& tables, int face) {
    const PolyFace& f = tables.faces()[static_cast<std::size_t>(face)];
    if (f.loops.size() != 1) return {};
    std::vector<Vec3> corners = loopCorners(tables, f.loops[0]);
    if (corners.size() < 3 || !isConvex(corners, f.normal)) return {};
    return corners;
}

SurfaceQuadrature buildSurfaceQuadrature(const PolyhedronTables& tables, QuadratureRule rule,
                                         int n) {
    if (n < 1) throw std::invalid_argument("buildSurfaceQuadrature: n must be >= 1");
    std::vector<double> gx, gw;
    if (rule == QuadratureRule::gauss) gaussLegendre(n, gx, gw);
    SurfaceQuadrature q;
    const auto& faces = tables.faces();
    const auto& V = tables.vertices();
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const PolyFace& face = faces[f];
        Builder b{q, static_cast<int>(f), face.normal};
        // Quadrilateral or triangle when the face is one loop with 4 or 3 corners.
        std::vector<Vec3> corners;
        if (face.loops.size() == 1) corners = loopCorners(tables, face.loops[0]);
        if (corners.size() == 4 && isConvex(corners, face.normal)) {
            if (rule == QuadratureRule::regular) regularQuad(b, corners, n);
            else gaussQuad(b, corners, gx, gw);
            continue;
        }
        if (corners.size() == 3) {
            if (rule == QuadratureRule::regular) regularTriangle(b, corners[0], corners[1], corners[2], n);
            else gaussTriangle(b, corners[0], corners[1], corners[2], gx, gw);
            continue;
        }
        // Other polygons: the face's own triangulation, triangle rule on each.
        for (int t = face.triBegin; t < face.triEnd; ++t) {
            const PolyTriangle& tri = tables.triangles()[static_cast<std::size_t>(t)];
            const Vec3& r0 = V[static_cast<std::size_t>(tri.v[0])];
            const Vec3& r1 = V[static_cast<std::size_t>(tri.v[1])];
            const Vec3& r2 = V[static_cast<std::size_t>(tri.v[2])];
            if (rule == QuadratureRule::regular) regularTriangle(b, r0, r1, r2, n);
            else gaussTriangle(b, r0, r1, r2, gx, gw);
        }
    }
    return q;
}

void transformSamples(const SurfaceQuadrature& q, const Eigen::Isometry3d& T,
                      std::vector<Vec3>& points, std::vector<Vec3>& normals) {
    points.resize(q.points.size());
    normals.resize(q.normals.size());
    const Eigen::Matrix3d R = T.linear();
    for (std::size_t i = 0; i < q.points.size(); ++i) {
        points[i] = T * q.points[i];
        normals[i] = R * q.normals[i];
    }
}

void bilinearMap(std::span<const Vec3> c, double s, double t, Vec3& p, double& jac) {
    p = (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
    const Vec3 ds = (1 - t) * (c[1] - c[0]) + t * (c[2] - c[3]);
    const Vec3 dt = (1 - s) * (c[3] - c[0]) + s * (c[2] - c[1]);
    jac = ds.cross(dt).norm();
}

} // namespace mag::mbm

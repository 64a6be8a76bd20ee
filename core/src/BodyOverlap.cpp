#include "magFoam/BodyOverlap.hpp"

#include "magFoam/Log.hpp"
#include "magFoam/SurfaceMesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace mag {

namespace {

// Vertices of `a` in the body frame of `b` (where b's mesh is stored).
std::vector<Vec3> verticesIn(const Body& a, const Body& b) {
    const Mat3 toB = b.orientation.toRotationMatrix().transpose() * a.orientation.toRotationMatrix();
    const Vec3 offset = b.orientation.inverse() * (a.position - b.position);
    std::vector<Vec3> v;
    v.reserve(a.shape->mesh.vertices.size());
    for (const Vec3& x : a.shape->mesh.vertices) v.push_back(toB * x + offset);
    return v;
}

// A point inside a closed mesh (body frame): its centre of mass (the origin)
// where that lies inside, as for any convex body; else, for a ring, a washer or
// a paperclip whose centre of mass is in empty space (where another body may
// pass without touching), the middle of the chord from the largest triangle's
// centroid inward to the next surface. nullopt if neither is inside.
std::optional<Vec3> interiorPoint(const SurfaceMesh& mesh) {
    if (windingNumber(mesh, Vec3::Zero()) >= 0.5) return Vec3::Zero();
    int largest = -1;
    for (int t = 0; t < mesh.nTriangles(); ++t)
        if (largest < 0 || mesh.area(t) > mesh.area(largest)) largest = t;
    if (largest < 0 || mesh.area(largest) <= 0) return std::nullopt;
    const Vec3 origin = (mesh.corner(largest, 0) + mesh.corner(largest, 1) + mesh.corner(largest, 2)) / 3.0;
    const Vec3 dir = -mesh.normal(largest);
    // Nearest crossing of the ray origin + s dir, s > 0, with another triangle
    // (Moller-Trumbore).
    double nearest = std::numeric_limits<double>::infinity();
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        if (t == largest) continue;
        const Vec3 &a = mesh.corner(t, 0), e1 = mesh.corner(t, 1) - a, e2 = mesh.corner(t, 2) - a;
        const Vec3 p = dir.cross(e2);
        const double det = e1.dot(p);
        if (std::abs(det) <= 1e-300) continue;
        const Vec3 q = origin - a;
        const double u = q.dot(p) / det;
        if (u < 0 || u > 1) continue;
        const Vec3 r = q.cross(e1);
        const double v = dir.dot(r) / det;
        if (v < 0 || u + v > 1) continue;
        const double s = e2.dot(r) / det;
        if (s > 0) nearest = std::min(nearest, s);
    }
    if (!std::isfinite(nearest)) return std::nullopt;
    const Vec3 mid = origin + 0.5 * nearest * dir;
    if (windingNumber(mesh, mid) < 0.5) return std::nullopt;
    return mid;
}

// Deepest vertex or face centroid of `in` inside `shell` by more than tol (0 if
// none). Centroids catch boxes that overlap with their corners on each other's
// edges (stacked too close, sides aligned), where every vertex is on the surface.
double deepestInside(const Body& in, const Body& shell, double tol) {
    const SurfaceMesh& mesh = shell.shape->mesh;
    std::vector<Vec3> probes = verticesIn(in, shell);
    for (const auto& t : in.shape->mesh.triangles)
        probes.push_back((probes[t[0]] + probes[t[1]] + probes[t[2]]) / 3.0);
    // And a point inside it: two identical bodies at the same place have every
    // vertex and centroid on the other's surface.
    if (const std::optional<Vec3> inner = interiorPoint(in.shape->mesh))
        probes.push_back(shell.orientation.toRotationMatrix().transpose() *
                             (in.orientation.toRotationMatrix() * *inner) +
                         shell.orientation.inverse() * (in.position - shell.position));
    double deepest = 0;
    for (const Vec3& p : probes) {
        if (windingNumber(mesh, p) < 0.5) continue;  // outside
        double d = std::numeric_limits<double>::infinity();
        for (int t = 0; t < mesh.nTriangles(); ++t)
            d = std::min(d, (p - closestPointOnTriangle(p, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2))).norm());
        if (d > tol) deepest = std::max(deepest, d);
    }
    return deepest;
}

// Distance between segments p0-p1 and q0-q1 (Ericson, Real-Time Collision
// Detection, 5.1.9: the closest points' parameters clamped to [0, 1]).
double segmentDistance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    double s = 0, t = 0;
    if (a <= 0 && e <= 0) return r.norm();
    if (a <= 0) {
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        const double c = d1.dot(r);
        if (e <= 0) {
            s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            const double b = d1.dot(d2), den = a * e - b * b;
            s = den > 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0) t = 0, s = std::clamp(-c / a, 0.0, 1.0);
            else if (t > 1) t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
        }
    }
    return (p0 + s * d1 - (q0 + t * d2)).norm();
}

// The edges of a mesh, each once (vertex index pairs, smaller first).
std::vector<std::pair<int, int>> meshEdges(const SurfaceMesh& mesh) {
    std::vector<std::pair<int, int>> edges;
    edges.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles)
        for (int e = 0; e < 3; ++e) edges.emplace_back(std::minmax(t[e], t[(e + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

// Does an edge of `a` pass through the inside of a face of `b`, clear of it by tol?
bool edgeCrossesFace(const Body& a, const Body& b, double tol) {
    const std::vector<Vec3> v = verticesIn(a, b);
    const SurfaceMesh& mesh = b.shape->mesh;
    for (const auto& ta : a.shape->mesh.triangles)
        for (int e = 0; e < 3; ++e) {
            const Vec3& p0 = v[ta[e]];
            const Vec3& p1 = v[ta[(e + 1) % 3]];
            for (int t = 0; t < mesh.nTriangles(); ++t) {
                const Vec3 &u = mesh.corner(t, 0), &w1 = mesh.corner(t, 1), &w2 = mesh.corner(t, 2);
                const Vec3 n = mesh.normal(t);
                if (n.squaredNorm() == 0) continue;
                const double s0 = n.dot(p0 - u), s1 = n.dot(p1 - u);
                if (!((s0 > tol && s1 < -tol) || (s0 < -tol && s1 > tol))) continue;
                const Vec3 q = p0 + s0 / (s0 - s1) * (p1 - p0);
                bool inside = true;
                for (const auto& [x, y] : {std::pair{&u, &w1}, std::pair{&w1, &w2}, std::pair{&w2, &u}}) {
                    const Vec3 edge = *y - *x;
                    inside = inside && n.dot(edge.cross(q - *x)) > tol * edge.norm();
                }
                if (inside) return true;
            }
        }
    return false;
}

} // namespace

double surfaceGap(const Body& a, const Body& b, double cap) {
    if ((a.position - b.position).norm() - a.shape->boundingRadius - b.shape->boundingRadius > cap) return cap;
    double best = cap;
    // Vertices of p (in q's body frame, where q's centre of mass is the origin)
    // against q's triangles.
    auto vertexToTriangle = [&](const std::vector<Vec3>& vp, const Body& q) {
        const SurfaceMesh& mesh = q.shape->mesh;
        for (const Vec3& x : vp) {
            if (x.norm() - q.shape->boundingRadius > best) continue;
            for (int t = 0; t < mesh.nTriangles(); ++t)
                best = std::min(best, (x - closestPointOnTriangle(x, mesh.corner(t, 0), mesh.corner(t, 1),
                                                                  mesh.corner(t, 2))).norm());
        }
    };
    const std::vector<Vec3> va = verticesIn(a, b);
    vertexToTriangle(va, b);
    vertexToTriangle(verticesIn(b, a), a);
    // Edge against edge: two wires crossing touch between vertices, where the
    // vertices of long straight segments can be millimetres away.
    struct Segment {
        Vec3 p0, p1, mid;
        double half;
    };
    auto segments = [](const SurfaceMesh& mesh, const std::vector<Vec3>& v) {
        std::vector<Segment> out;
        for (const auto& [i, j] : meshEdges(mesh))
            out.push_back({v[i], v[j], 0.5 * (v[i] + v[j]), 0.5 * (v[j] - v[i]).norm()});
        return out;
    };
    const std::vector<Segment> sb = segments(b.shape->mesh, b.shape->mesh.vertices);
    for (const Segment& e : segments(a.shape->mesh, va)) {
        if (e.mid.norm() - e.half - b.shape->boundingRadius > best) continue;
        for (const Segment& f : sb)
            if ((e.mid - f.mid).norm() - e.half - f.half <= best)
                best = std::min(best, segmentDistance(e.p0, e.p1, f.p0, f.p1));
    }
    return best;
}

std::vector<BodyOverlap> findOverlaps(const std::vector<Body>& bodies, double relTol) {
    std::vector<BodyOverlap> out;
    for (std::size_t i = 0; i < bodies.size(); ++i)
        for (std::size_t j = i + 1; j < bodies.size(); ++j) {
            const Body &a = bodies[i], &b = bodies[j];
            const double Ra = a.shape->boundingRadius, Rb = b.shape->boundingRadius;
            const double tol = relTol * std::max(Ra, Rb);
            if ((a.position - b.position).norm() >= Ra + Rb - tol) continue;
            const double depth = std::max(deepestInside(a, b, tol), deepestInside(b, a, tol));
            if (depth > 0 || edgeCrossesFace(a, b, tol) || edgeCrossesFace(b, a, tol)) out.push_back({i, j, depth});
        }
    return out;
}

std::size_t warnOverlaps(const std::vector<Body>& bodies, const std::string& bodiesFile,
                         const std::string& consequence) {
    const std::vector<BodyOverlap> overlaps = findOverlaps(bodies);
    for (const BodyOverlap& o : overlaps) {
        const std::string how = o.depth > 0 ? fmt::format("{:.3g} m deep", o.depth) : "edges through faces";
        spdlog::warn("bodies '{}' and '{}' overlap ({}; {}): {}; check their positions", bodies[o.a].name,
                     bodies[o.b].name, how, bodiesFile, consequence);
    }
    return overlaps.size();
}

} // namespace mag

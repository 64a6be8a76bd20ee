#include "magFoam/BodyOverlap.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace mag {

namespace {

struct Placed {
    std::vector<Vec3> v;                         // world vertices
    const std::vector<std::array<int, 3>>* tri;  // the shape's triangles
};

Placed place(const Body& b) {
    const Mat3 R = b.orientation.toRotationMatrix();
    Placed p{{}, &b.shape->mesh.triangles};
    p.v.reserve(b.shape->mesh.vertices.size());
    for (const Vec3& x : b.shape->mesh.vertices) p.v.push_back(R * x + b.position);
    return p;
}

// Solid angle of triangle (a, b, c) seen from the origin (Van Oosterom and
// Strackee); summed over a closed outward mesh: 4 pi inside, 0 outside.
double solidAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    return 2.0 * std::atan2(num, den);
}

// Distance from p to triangle (a, b, c) (closest point by region, Ericson 5.1.5).
double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return ap.norm();
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return bp.norm();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return cp.norm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
    const double denom = 1.0 / (va + vb + vc);
    return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

// Deepest vertex or face centroid of `in` inside `shell` by more than tol (0 if
// none). Centroids catch boxes that overlap with their corners on each other's
// edges (stacked too close, sides aligned), where every vertex is on the surface.
double deepestVertexInside(const Placed& in, const Placed& shell, double tol) {
    std::vector<Vec3> probes = in.v;
    for (const auto& t : *in.tri) probes.push_back((in.v[t[0]] + in.v[t[1]] + in.v[t[2]]) / 3.0);
    double deepest = 0;
    for (const Vec3& p : probes) {
        double omega = 0;
        for (const auto& t : *shell.tri) omega += solidAngle(shell.v[t[0]] - p, shell.v[t[1]] - p, shell.v[t[2]] - p);
        if (omega < 2.0 * pi) continue;  // winding number < 1/2: outside
        double d = std::numeric_limits<double>::infinity();
        for (const auto& t : *shell.tri) d = std::min(d, pointTriangleDistance(p, shell.v[t[0]], shell.v[t[1]], shell.v[t[2]]));
        if (d > tol) deepest = std::max(deepest, d);
    }
    return deepest;
}

// Does an edge of `a` pass through the inside of a face of `b`, clear of it by tol?
bool edgeCrossesFace(const Placed& a, const Placed& b, double tol) {
    for (const auto& ta : *a.tri)
        for (int e = 0; e < 3; ++e) {
            const Vec3& p0 = a.v[ta[e]];
            const Vec3& p1 = a.v[ta[(e + 1) % 3]];
            for (const auto& tb : *b.tri) {
                const Vec3 &u = b.v[tb[0]], &v = b.v[tb[1]], &w = b.v[tb[2]];
                const Vec3 n0 = (v - u).cross(w - u);
                const double len = n0.norm();
                if (len == 0) continue;
                const Vec3 n = n0 / len;
                const double s0 = n.dot(p0 - u), s1 = n.dot(p1 - u);
                if (!((s0 > tol && s1 < -tol) || (s0 < -tol && s1 > tol))) continue;
                const Vec3 q = p0 + s0 / (s0 - s1) * (p1 - p0);
                bool inside = true;
                for (const auto& [x, y] : {std::pair{&u, &v}, std::pair{&v, &w}, std::pair{&w, &u}}) {
                    const Vec3 edge = *y - *x;
                    inside = inside && n.dot(edge.cross(q - *x)) > tol * edge.norm();
                }
                if (inside) return true;
            }
        }
    return false;
}

} // namespace

std::vector<BodyOverlap> findOverlaps(const std::vector<Body>& bodies, double relTol) {
    std::vector<BodyOverlap> out;
    std::vector<Placed> placed;
    placed.reserve(bodies.size());
    for (const Body& b : bodies) placed.push_back(place(b));
    for (std::size_t i = 0; i < bodies.size(); ++i)
        for (std::size_t j = i + 1; j < bodies.size(); ++j) {
            const double Ri = bodies[i].shape->boundingRadius, Rj = bodies[j].shape->boundingRadius;
            const double tol = relTol * std::max(Ri, Rj);
            if ((bodies[i].position - bodies[j].position).norm() >= Ri + Rj - tol) continue;
            const double depth = std::max(deepestVertexInside(placed[i], placed[j], tol),
                                          deepestVertexInside(placed[j], placed[i], tol));
            if (depth > 0 || edgeCrossesFace(placed[i], placed[j], tol) || edgeCrossesFace(placed[j], placed[i], tol))
                out.push_back({i, j, depth});
        }
    return out;
}

} // namespace mag

// Cutting the target's faces along the source's features (see the header).
#include "ContactSplit.hpp"

#include "SurfaceQuadrature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mag::mbm {

namespace {

using Vec2 = Eigen::Vector2d;

// A convex polygon in the face plane's (e1, e2) coordinates; side i runs c[i] -> c[i+1].
struct Poly2 {
    std::vector<Vec2> c;
    std::vector<double> feature; // per side, as FacePiece::feature
};

// A feature segment in the face plane.
struct Segment {
    Vec2 a, d;      // start, unit direction
    double length;  // m
    double gap;     // m: the source feature's closest distance to the plane
};

// The smaller feature distance (-1 = none).
double closer(double a, double b) { return a < 0.0 ? b : (b < 0.0 ? a : std::min(a, b)); }

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double area2(const Poly2& p) {
    double s = 0.0;
    for (std::size_t i = 0; i < p.c.size(); ++i) s += cross2(p.c[i], p.c[(i + 1) % p.c.size()]);
    return 0.5 * s;
}

// Cuts `p` by the line of `s` when the segment reaches across its interior; the new
// chord is a singular side of both halves. Returns false (p untouched) otherwise.
bool cut(const Poly2& p, const Segment& s, double tol, Poly2& pos, Poly2& neg) {
    const std::size_t m = p.c.size();
    const Vec2 normal(-s.d.y(), s.d.x());
    std::vector<double> dist(m);
    std::vector<int> sign(m);
    double lo = 0.0, hi = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
        dist[i] = normal.dot(p.c[i] - s.a);
        sign[i] = dist[i] > tol ? 1 : (dist[i] < -tol ? -1 : 0);
        lo = std::min(lo, dist[i]);
        hi = std::max(hi, dist[i]);
    }
    if (!(hi > tol && lo < -tol)) return false;
    // Crossing points (and vertices on the line), with their abscissa along the segment.
    struct Entry {
        Vec2 x;
        int sign;
        double feature; // of the side from this entry to the next one
    };
    std::vector<Entry> ring;
    double chordLo = std::numeric_limits<double>::infinity(), chordHi = -chordLo;
    for (std::size_t i = 0; i < m; ++i) {
        const std::size_t j = (i + 1) % m;
        ring.push_back({p.c[i], sign[i], p.feature[i]});
        if (sign[i] == 0) {
            const double t = s.d.dot(p.c[i] - s.a);
            chordLo = std::min(chordLo, t);
            chordHi = std::max(chordHi, t);
        }
        if (sign[i] * sign[j] < 0) {
            const Vec2 x = p.c[i] + (dist[i] / (dist[i] - dist[j])) * (p.c[j] - p.c[i]);
            ring.push_back({x, 0, p.feature[i]});
            const double t = s.d.dot(x - s.a);
            chordLo = std::min(chordLo, t);
            chordHi = std::max(chordHi, t);
        }
    }
    // The segment must overlap the chord by more than the tolerance.
    if (std::min(chordHi, s.length) - std::max(chordLo, 0.0) <= tol) return false;
    auto keep = [&](int side, Poly2& out) {
        out.c.clear();
        out.feature.clear();
        const std::size_t r = ring.size();
        for (std::size_t k = 0; k < r; ++k) {
            const Entry& e = ring[k];
            if (e.sign != side && e.sign != 0) continue;
            const Entry& next = ring[(k + 1) % r];
            // The next ring entry dropped: this side is the chord across the line.
            const bool chord = next.sign != side && next.sign != 0;
            out.c.push_back(e.x);
            out.feature.push_back(chord ? s.gap : e.feature);
        }
    };
    keep(1, pos);
    keep(-1, neg);
    return pos.c.size() >= 3 && neg.c.size() >= 3;
}

// Gives the sides of `p` parallel to the segment and within dNear of it (e.g. a target
// face edge along a source edge, or beside one) the distance to it.
void markParallel(Poly2& p, const Segment& s, double tol, double dNear) {
    const Vec2 normal(-s.d.y(), s.d.x());
    const std::size_t m = p.c.size();
    for (std::size_t i = 0; i < m; ++i) {
        const Vec2 &a = p.c[i], &b = p.c[(i + 1) % m];
        const double da = normal.dot(a - s.a), db = normal.dot(b - s.a);
        if (std::abs(da - db) > tol || std::abs(da) > dNear) continue;
        const double ta = s.d.dot(a - s.a), tb = s.d.dot(b - s.a);
        if (std::min(std::max(ta, tb), s.length) - std::max(std::min(ta, tb), 0.0) <= tol) continue;
        const double lateral = std::abs(da) <= tol ? 0.0 : std::abs(da);
        p.feature[i] = closer(p.feature[i], std::hypot(lateral, s.gap));
    }
}

} // namespace

void splitTargetFaces(const PolyhedronTables& source, const PolyhedronTables& target,
                      const Eigen::Isometry3d& T, TargetPieces& out, double nearFraction) {
    out.pieces.clear();
    out.normals.clear();
    out.inwardOffset.clear();
    out.nearDistance.clear();
    out.cuts = 0;
    const auto& SV = source.vertices();
    const auto& TV = target.vertices();
    const Eigen::Matrix3d R = T.linear();
    double sourceExtent = 0.0;
    for (const Vec3& v : SV) sourceExtent = std::max(sourceExtent, v.cwiseAbs().maxCoeff());
    std::vector<double> h(SV.size());
    std::vector<Segment> segments;
    std::vector<Poly2> polys, next;

    for (std::size_t f = 0; f < target.faces().size(); ++f) {
        const PolyFace& face = target.faces()[f];
        const Vec3 n = R * face.normal;
        out.normals.push_back(n);
        out.inwardOffset.push_back(0.0);
        // Convex polygons of the face in the source frame: the face itself or its triangles.
        std::vector<std::vector<Vec3>> polygons;
        std::vector<Vec3> corners = convexFaceCorners(target, static_cast<int>(f));
        if (!corners.empty()) {
            for (Vec3& c : corners) c = T * c;
            polygons.push_back(std::move(corners));
        } else {
            for (int t = face.triBegin; t < face.triEnd; ++t) {
                const PolyTriangle& tri = target.triangles()[static_cast<std::size_t>(t)];
                polygons.push_back({T * TV[static_cast<std::size_t>(tri.v[0])],
                                    T * TV[static_cast<std::size_t>(tri.v[1])],
                                    T * TV[static_cast<std::size_t>(tri.v[2])]});
            }
        }
        // Face frame and scales.
        const Vec3 o = polygons[0][0];
        const Vec3 e1 = (polygons[0][1] - o).normalized(), e2 = n.cross(e1);
        double diameter = 0.0;
        for (const auto& poly : polygons)
            for (const Vec3& c : poly) diameter = std::max(diameter, (c - o).norm());
        const double dNear = nearFraction * diameter;
        out.nearDistance.push_back(dNear);
        const double lref = std::max(diameter, source.maxEdgeLength());
        const double eps = std::numeric_limits<double>::epsilon();
        const double planeTol = 1e-10 * lref + 64.0 * eps * (o.norm() + sourceExtent);
        const double tol = 1e-10 * diameter + 64.0 * eps * o.norm();
        auto emitWhole = [&] {
            for (auto& poly : polygons)
                out.pieces.push_back({static_cast<int>(f), poly, std::vector<double>(poly.size(), -1.0)});
        };
        // The whole source farther than dNear from the plane: nothing to cut.
        const double centreHeight = n.dot(source.centroid() - o);
        if (std::abs(centreHeight) - source.boundingRadius() > dNear) {
            emitWhole();
            continue;
        }
        for (std::size_t v = 0; v < SV.size(); ++v) {
            h[v] = n.dot(SV[v] - o);
            if (std::abs(h[v]) <= planeTol) h[v] = 0.0;
        }
        auto to2 = [&](const Vec3& p) { return Vec2(e1.dot(p - o), e2.dot(p - o)); };
        segments.clear();
        auto addSegment = [&](const Vec2& a, const Vec2& b, double gap) {
            const double L = (b - a).norm();
            if (L > tol) segments.push_back({a, (b - a) / L, L, gap});
        };
        // (a) source edges within dNear of the plane, projected onto it
        for (const PolyEdge& e : source.edges()) {
            const auto i0 = static_cast<std::size_t>(e.v0), i1 = static_cast<std::size_t>(e.v1);
            if (std::abs(h[i0]) <= dNear && std::abs(h[i1]) <= dNear)
                addSegment(to2(SV[i0]), to2(SV[i1]),
                           h[i0] * h[i1] <= 0.0 ? 0.0 : std::min(std::abs(h[i0]), std::abs(h[i1])));
        }
        // (b) the chords of source faces crossing the plane; coplanar source faces
        for (std::size_t p = 0; p < source.faces().size(); ++p) {
            const PolyFace& sf = source.faces()[p];
            bool above = false, below = false;
            for (const auto& loop : sf.loops)
                for (int v : loop) {
                    above |= h[static_cast<std::size_t>(v)] > 0.0;
                    below |= h[static_cast<std::size_t>(v)] < 0.0;
                }
            if (!above && !below) {
                out.inwardOffset.back() = 10.0 * planeTol;
                continue;
            }
            if (!(above && below)) continue;
            std::vector<Vec2> xs;
            for (const auto& loop : sf.loops)
                for (std::size_t k = 0; k < loop.size(); ++k) {
                    const auto a = static_cast<std::size_t>(loop[k]);
                    const auto b = static_cast<std::size_t>(loop[(k + 1) % loop.size()]);
                    if (h[a] == 0.0) xs.push_back(to2(SV[a]));
                    else if (h[a] * h[b] < 0.0)
                        xs.push_back(to2(SV[a] + (h[a] / (h[a] - h[b])) * (SV[b] - SV[a])));
                }
            if (xs.size() < 2) continue;
            // The chord's extreme points along its direction.
            const Vec3 d3 = n.cross(sf.normal);
            Vec2 dir(e1.dot(d3), e2.dot(d3));
            if (dir.norm() <= 0.0) continue;
            dir.normalize();
            auto [lo, hi] = std::minmax_element(xs.begin(), xs.end(), [&](const Vec2& a, const Vec2& b) {
                return dir.dot(a) < dir.dot(b);
            });
            addSegment(*lo, *hi, 0.0);
        }
        if (segments.empty()) {
            emitWhole();
            continue;
        }
        polys.clear();
        for (const auto& poly : polygons) {
            Poly2 p;
            for (const Vec3& c : poly) p.c.push_back(to2(c));
            p.feature.assign(p.c.size(), -1.0);
            polys.push_back(std::move(p));
        }
        for (const Segment& s : segments) {
            next.clear();
            for (const Poly2& p : polys) {
                Poly2 a, b;
                if (cut(p, s, tol, a, b)) {
                    if (std::abs(area2(a)) > tol * diameter) next.push_back(std::move(a));
                    if (std::abs(area2(b)) > tol * diameter) next.push_back(std::move(b));
                    ++out.cuts;
                } else {
                    next.push_back(p);
                }
            }
            polys.swap(next);
        }
        for (Poly2& p : polys) {
            for (const Segment& s : segments) markParallel(p, s, tol, dNear);
            FacePiece piece{static_cast<int>(f), {}, p.feature};
            for (const Vec2& c : p.c) piece.corners.push_back(o + c.x() * e1 + c.y() * e2);
            out.pieces.push_back(std::move(piece));
        }
    }
}

} // namespace mag::mbm

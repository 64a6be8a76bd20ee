#include "ContactManifold.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace mag::ode {

TriangleSet TriangleSet::build(const SurfaceMesh& mesh) {
    TriangleSet set;
    const int n = mesh.nTriangles();
    set.corners.reserve(n), set.normals.reserve(n), set.centres.reserve(n), set.radii.reserve(n);
    for (int t = 0; t < n; ++t) {
        const std::array<Vec3, 3> c = {mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)};
        const Vec3 centre = (c[0] + c[1] + c[2]) / 3;
        set.corners.push_back(c);
        set.normals.push_back(mesh.normal(t));
        set.centres.push_back(centre);
        set.radii.push_back(std::max({(c[0] - centre).norm(), (c[1] - centre).norm(), (c[2] - centre).norm()}));
    }
    return set;
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();


// Triangles of a mesh geom whose bounding sphere meets a world box.
std::vector<int> trianglesInBox(const GeomView& g, const Vec3& lo, const Vec3& hi) {
    // The box in the body frame (its 8 corners' bounding box: conservative).
    Vec3 blo = Vec3::Constant(kInfinity), bhi = -blo;
    for (int k = 0; k < 8; ++k) {
        const Vec3 corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
        const Vec3 b = g.rotation.transpose() * (corner - g.position);
        blo = blo.cwiseMin(b), bhi = bhi.cwiseMax(b);
    }
    std::vector<int> out;
    const TriangleSet& s = *g.triangles;
    for (int t = 0; t < static_cast<int>(s.centres.size()); ++t) {
        const Vec3 d = (s.centres[t] - s.centres[t].cwiseMax(blo).cwiseMin(bhi));
        if (d.norm() <= s.radii[t]) out.push_back(t);
    }
    return out;
}

// The local piece of one geom around a contact point: the faces near it (as
// planes) and, for a mesh, the corners of those faces. A primitive has no
// corners here: its own (convex, exact) support function stands in.
struct LocalPiece {
    std::vector<Vec3> points;
    std::vector<Plane> planes;
};
void gatherPiece(const GeomView& g, const std::vector<int>& candidates, const Vec3& pWorld, double eps,
                 LocalPiece& piece) {
    piece.points.clear();
    piece.planes.clear();
    if (!g.triangles) {
        if (g.surfacePlanes) g.surfacePlanes(pWorld, piece.planes);
        return;
    }
    const TriangleSet& s = *g.triangles;
    const Vec3 p = g.rotation.transpose() * (pWorld - g.position);
    for (int t : candidates) {
        if ((p - s.centres[t]).norm() > s.radii[t] + eps) continue;
        const auto& c = s.corners[t];
        if ((closestPointOnTriangle(p, c[0], c[1], c[2]) - p).norm() > eps) continue;
        for (const Vec3& v : c) piece.points.push_back(g.rotation * v + g.position);
        const Vec3 n = g.rotation * s.normals[t];
        piece.planes.push_back({n, n.dot(piece.points.back())});
    }
}

// How deep the other geom's local piece reaches behind a face plane (into the
// face's body): max over its points of offset - x . n.
double depthBehind(const Plane& f, const LocalPiece& other, const GeomView& otherGeom) {
    if (other.points.empty()) return f.offset + otherGeom.support(-f.normal);
    double deepest = -kInfinity;
    for (const Vec3& x : other.points) deepest = std::max(deepest, f.offset - x.dot(f.normal));
    return deepest;
}

} // namespace

int correctMeshContacts(std::vector<ContactPoint>& contacts, const GeomView& g1, const GeomView& g2, double radius,
                        double slack) {
    if (contacts.empty()) return 0;
    const int before = static_cast<int>(contacts.size());
    auto hullSeparation = [&](const Vec3& n) { return g2.support(n) + g1.support(-n); };

    // 1. Hull check over the contact normals; the smallest separation also
    // bounds every depth and the size of the local pieces.
    double easiest = kInfinity;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        // (Colliders repeat normals: a mesh's support costs a pass over its vertices.)
        bool seen = false;
        for (std::size_t j = 0; j < i && !seen; ++j) seen = contacts[j].normal == contacts[i].normal;
        if (!seen) easiest = std::min(easiest, hullSeparation(contacts[i].normal));
    }
    if (easiest < -slack) {
        contacts.clear();
        return before;
    }
    easiest = std::max(0.0, easiest);

    // Candidate triangles: those near the contact points.
    Vec3 lo = Vec3::Constant(kInfinity), hi = -lo;
    for (const ContactPoint& c : contacts) lo = lo.cwiseMin(c.position), hi = hi.cwiseMax(c.position);
    const double reach = easiest + radius + slack;
    lo.array() -= reach, hi.array() += reach;
    const std::vector<int> near1 = g1.triangles ? trianglesInBox(g1, lo, hi) : std::vector<int>();
    const std::vector<int> near2 = g2.triangles ? trianglesInBox(g2, lo, hi) : std::vector<int>();

    // 2. Per contact: of the faces near it (of either geom), the one the
    // other geom's local piece penetrates least is the contact's face.
    LocalPiece piece1, piece2;
    std::vector<ContactPoint> kept;
    kept.reserve(contacts.size());
    for (ContactPoint c : contacts) {
        const double eps = std::min(std::max(0.0, c.depth), easiest) + radius + slack;
        gatherPiece(g1, near1, c.position, eps, piece1);
        gatherPiece(g2, near2, c.position, eps, piece2);
        double bestDepth = kInfinity;
        Vec3 best = c.normal;
        for (const Plane& f : piece2.planes) { // geom 1 leaves along geom 2's face normal
            const double d = depthBehind(f, piece1, g1);
            if (d < bestDepth) bestDepth = d, best = f.normal;
        }
        for (const Plane& f : piece1.planes) { // geom 1 leaves its own face backwards
            const double d = depthBehind(f, piece2, g2);
            if (d < bestDepth) bestDepth = d, best = -f.normal;
        }
        if (bestDepth < -slack) continue; // the local pieces are apart
        // A face much deeper than ODE's own contact means the neighbourhood
        // missed the face that matters (a concave corner just beyond it):
        // keep ODE's normal and depth then. Never deeper than the hull
        // separation.
        if (bestDepth > 2 * std::max(0.0, c.depth) + radius + 2 * slack) {
            bestDepth = c.depth;
            best = c.normal;
        }
        const double depth = best.dot(c.normal) > 1 - 1e-12 ? std::min(c.depth, bestDepth) : bestDepth;
        c.depth = std::clamp(depth, 0.0, std::max(0.0, hullSeparation(best)));
        c.normal = best;
        kept.push_back(c);
    }
    contacts = std::move(kept);
    return before - static_cast<int>(contacts.size());
}

int mergeContacts(std::vector<ContactPoint>& contacts, double distance) {
    // Normals within ~8 degrees (cos > 0.99) at the same point are one contact.
    const double cosLimit = 0.99, d2 = distance * distance;
    std::vector<ContactPoint> kept;
    kept.reserve(contacts.size());
    for (const ContactPoint& c : contacts) {
        auto same = [&](const ContactPoint& k) {
            return (k.position - c.position).squaredNorm() <= d2 && k.normal.dot(c.normal) > cosLimit;
        };
        auto it = std::find_if(kept.begin(), kept.end(), same);
        if (it == kept.end())
            kept.push_back(c);
        else if (c.depth > it->depth)
            *it = c;
    }
    const int merged = static_cast<int>(contacts.size() - kept.size());
    contacts = std::move(kept);
    return merged;
}

void reduceContacts(std::vector<ContactPoint>& contacts, int maxContacts, double normalWeight) {
    const std::size_t n = contacts.size(), m = static_cast<std::size_t>(std::max(1, maxContacts));
    if (n <= m) return;
    // Start from the deepest (the first on ties).
    std::size_t first = 0;
    for (std::size_t i = 1; i < n; ++i)
        if (contacts[i].depth > contacts[first].depth) first = i;
    std::vector<bool> chosen(n, false);
    std::vector<double> gap(n, kInfinity);
    std::vector<ContactPoint> out;
    out.reserve(m);
    std::size_t next = first;
    while (out.size() < m) {
        chosen[next] = true;
        out.push_back(contacts[next]);
        // Distance of every candidate to the chosen set; take the farthest.
        std::size_t best = n;
        for (std::size_t i = 0; i < n; ++i) {
            if (chosen[i]) continue;
            gap[i] = std::min(gap[i], (contacts[i].position - contacts[next].position).squaredNorm() +
                                          normalWeight * normalWeight *
                                              (contacts[i].normal - contacts[next].normal).squaredNorm());
            if (best == n || gap[i] > gap[best] || (gap[i] == gap[best] && contacts[i].depth > contacts[best].depth))
                best = i;
        }
        if (best == n) break;
        next = best;
    }
    contacts = std::move(out);
}

namespace {

// The face of a placed polytope whose outward normal is most aligned with u:
// its index and the cosine.
std::pair<int, double> mostAlignedFace(const PolytopeView& g, const Vec3& u) {
    const Vec3 ub = g.rotation.transpose() * u;
    int best = -1;
    double cosine = -kInfinity;
    for (int f = 0; f < static_cast<int>(g.hull->normals.size()); ++f) {
        const double c = g.hull->normals[f].dot(ub);
        if (c > cosine) cosine = c, best = f;
    }
    return {best, cosine};
}

std::vector<Vec3> facePolygon(const PolytopeView& g, int f) {
    std::vector<Vec3> out;
    for (int v : g.hull->faces[f]) out.push_back(g.position + g.rotation * g.hull->points[v]);
    return out;
}

// The part of `polygon` with (x - origin) . normal <= 0.
void clipToHalfSpace(std::vector<Vec3>& polygon, const Vec3& origin, const Vec3& normal, std::vector<Vec3>& scratch) {
    scratch.clear();
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& a = polygon[i];
        const Vec3& b = polygon[(i + 1) % n];
        const double da = (a - origin).dot(normal), db = (b - origin).dot(normal);
        if (da <= 0) scratch.push_back(a);
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) scratch.push_back(a + (b - a) * (da / (da - db)));
    }
    polygon.swap(scratch);
}

} // namespace

bool clipFaceContacts(const PolytopeView& g1, const PolytopeView& g2, const ContactPoint& seed, double slack,
                      std::vector<ContactPoint>& out) {
    // Moving geom 1 along the normal separates: geom 1 touches with a face
    // facing -normal, geom 2 with one facing +normal.
    const Vec3 n = seed.normal.normalized();
    const auto [f1, c1] = mostAlignedFace(g1, -n);
    const auto [f2, c2] = mostAlignedFace(g2, n);
    // cos 10 degrees: an EPA normal of a face contact is that face's normal
    // to round-off; between two faces' normals lies an edge or a corner.
    const double cosFace = 0.985;
    if (f1 < 0 || f2 < 0 || std::max(c1, c2) < cosFace) return false;
    const bool refIsG2 = c2 >= c1;
    const PolytopeView& ref = refIsG2 ? g2 : g1;
    const PolytopeView& inc = refIsG2 ? g1 : g2;
    const int fr = refIsG2 ? f2 : f1;
    const Vec3 nr = ref.rotation * ref.hull->normals[fr];
    const std::vector<Vec3> refFace = facePolygon(ref, fr);
    const Vec3 origin = refFace.front();
    const int fi = mostAlignedFace(inc, -nr).first;
    std::vector<Vec3> polygon = facePolygon(inc, fi), scratch;
    // Side planes of the reference face, outward (its loop is counter-
    // clockwise seen from outside, so edge x normal points out of the face).
    for (std::size_t i = 0; i < refFace.size() && !polygon.empty(); ++i) {
        const Vec3& a = refFace[i];
        const Vec3& b = refFace[(i + 1) % refFace.size()];
        const Vec3 side = (b - a).cross(nr);
        if (side.squaredNorm() == 0) continue;
        clipToHalfSpace(polygon, a, side.normalized(), scratch);
    }
    // Appended to `out`, and taken back if the set is not credible.
    const std::size_t first = out.size();
    double deepest = -kInfinity;
    for (const Vec3& q : polygon) {
        const double height = (q - origin).dot(nr); // < 0: behind the reference face
        if (height > slack) continue;
        ContactPoint c;
        c.normal = refIsG2 ? nr : Vec3(-nr);
        c.position = q - 0.5 * height * nr;
        c.depth = -height;
        c.source = seed.source;
        deepest = std::max(deepest, c.depth);
        out.push_back(c);
    }
    // libccd's depth is the least separating translation, so no face point
    // lies much deeper; if one does, the faces are not the contact's.
    if (out.size() == first || deepest > 1.5 * std::max(seed.depth, 0.0) + slack) {
        out.resize(first);
        return false;
    }
    return true;
}

} // namespace mag::ode

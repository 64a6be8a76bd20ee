// Closed-form field of a uniformly magnetized polyhedron (see the header).
#include "PolyhedronField.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace mag::mbm {

namespace {

constexpr double kFourPi = 4.0 * std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Per-edge data for one call: M-dependent B coefficient and the geometric coupling.
//   B:  sum_p grad W_p x (M x n_p) gets -omega_e [n0 (i0 . M) + n1 (i1 . M)] = omega_e c
//       from edge e (since (n x u) x (M x n) = -n ((n x u) . M)), Eqs. 11, 13.
//   S = sum_p W_p n_p gets -omega_e K (r_v0 - r), K = n0 i0^T + n1 i1^T, Eq. 12
//       ((n_p x (r_e - r)) . u_e = -(n_p x u_e) . (r_e - r)).
struct EdgeWork {
    int v0, v1;
    double length;
    Vec3 delta;
    Vec3 c;
    Eigen::Matrix3d K;
};

// Per-face data for one call. B gets Omega_p (M - n_p (n_p . M)) = Omega_p d from face p.
struct FaceWork {
    Vec3 n;
    int vertex; // a vertex of the face: h = (r_v - r) . n is exactly 0 for points that
                // share an axis-aligned face's coordinate (offsets would round)
    Vec3 d;
    int triBegin, triEnd;
};

// Scratch reused by every call on this thread: no allocation once warm.
struct Scratch {
    std::vector<EdgeWork> edges;
    std::vector<FaceWork> faces;
    std::vector<Vec3> rel;    // r_v - r
    std::vector<double> dist; // |r_v - r|
    std::vector<double> invDist; // 1 / |r_v - r| (0 at the vertex itself)
};

Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

void checkSize(std::size_t n, std::size_t expected, const char* what) {
    if (n != 0 && n != expected)
        throw std::invalid_argument(std::string("mbm::evaluate: output '") + what +
                                    "' must be empty or as long as points");
}

// omega_e of the point moved to distance rho (>= delta L) from the edge line at abscissa
// x along it (Eq. 14 is a function of x and rho only). Used only where the true
// distance is below delta L, so rho = delta L here.
double displacedEdgeLogTerm(double x, double rho, double L) {
    // Beside the segment: int_0^L dxi / |(xi - x, rho)|, no cancellation (both >= 0).
    if (x >= 0.0 && x <= L) return std::asinh(x / rho) + std::asinh((L - x) / rho);
    // Beyond an end: S - L = R_near + (R_far^2 - L^2)/(R_far + L), all terms >= 0.
    const double xn = x < 0.0 ? -x : x - L; // distance past the nearer end (> 0)
    const double rNear = std::hypot(xn, rho), rFar = std::hypot(L + xn, rho);
    const double sMinusL = rNear + (xn * xn + 2.0 * xn * L + rho * rho) / (rFar + L);
    return std::log1p(2.0 * L / sMinusL);
}

} // namespace

double edgeLogTerm(const Vec3& a, const Vec3& b, double R1, double R2, double L,
                   const Vec3& delta) {
    const double S = R1 + R2;
    const double ab = a.dot(b);
    const double rhoMin = kEdgeRegularization * L;
    if (ab < 0.0) {
        // Beside the segment S - L cancels; use S^2 - L^2 = 2 |a x b|^2 / (R1 R2 - a.b),
        // |a x b| = |a x delta| = (distance to the line) L.
        const double cross2 = a.cross(delta).squaredNorm();
        if (cross2 >= rhoMin * rhoMin * L * L)
            return std::log((S + L) * (S + L) * (R1 * R2 - ab) / (2.0 * cross2));
        return displacedEdgeLogTerm(-a.dot(delta) / L, rhoMin, L);
    }
    // Beyond the ends (outside the segment's diametral sphere). Far away S - L is not
    // small and log1p keeps omega ~ L/R accurate (PHYSICS.md far-field form). Farther
    // than 1e-4 L from a vertex the clamp is skipped: moving the point delta L off the
    // line would change omega by < (delta / 1e-4)^2 = 1e-10 there.
    const double SmL = S - L;
    if (SmL > 1e5 * rhoMin) return std::log1p(2.0 * L / SmL);
    // Within 1e-4 L of a vertex: S - L without cancellation, from the nearer vertex
    // (R2^2 - L^2 = R1^2 + 2 a.delta, R1^2 - L^2 = R2^2 - 2 b.delta).
    const double cross2 = a.cross(delta).squaredNorm();
    if (cross2 < rhoMin * rhoMin * L * L)
        return displacedEdgeLogTerm(-a.dot(delta) / L, rhoMin, L);
    const double sMinusL = R1 <= R2 ? R1 + (R1 * R1 + 2.0 * a.dot(delta)) / (R2 + L)
                                    : R2 + (R2 * R2 - 2.0 * b.dot(delta)) / (R1 + L);
    return std::log1p(2.0 * L / sMinusL);
}

double triangleSolidAngle(const Vec3& a, const Vec3& b, const Vec3& c, double Ra, double Rb,
                          double Rc, double twiceArea, double height) {
    // a . (b x c) = 2 area (a . n): accurate far away and exactly 0 on the plane.
    const double N = twiceArea * height;
    // Principal value on the plane: atan2(+-0, D < 0) would pick +-pi from the sign of 0.
    if (N == 0.0) return 0.0;
    const double D = Ra * Rb * Rc + Ra * b.dot(c) + Rb * c.dot(a) + Rc * a.dot(b);
    return 2.0 * std::atan2(N, D);
}

FaceIntegrals faceIntegrals(const PolyhedronTables& tables, int face, const Vec3& point) {
    const PolyFace& f = tables.faces().at(static_cast<std::size_t>(face));
    const auto& V = tables.vertices();
    // (r_p - r) . n_p from a vertex: exactly 0 on an axis-aligned face plane
    const double h =
        f.normal.dot(V[static_cast<std::size_t>(tables.triangles()[static_cast<std::size_t>(f.triBegin)].v[0])] - point);
    FaceIntegrals out;
    double vertexScale = 0.0;
    for (const Vec3& v : V) vertexScale = std::max(vertexScale, v.norm());
    if (std::abs(h) > 16.0 * kEps * (point.norm() + vertexScale)) { // as in evaluate()
        for (int t = f.triBegin; t < f.triEnd; ++t) {
            const PolyTriangle& tri = tables.triangles()[static_cast<std::size_t>(t)];
            const Vec3 a = V[static_cast<std::size_t>(tri.v[0])] - point;
            const Vec3 b = V[static_cast<std::size_t>(tri.v[1])] - point;
            const Vec3 c = V[static_cast<std::size_t>(tri.v[2])] - point;
            out.solidAngle +=
                triangleSolidAngle(a, b, c, a.norm(), b.norm(), c.norm(), tri.twiceArea, h);
        }
    }
    for (const FaceEdge& fe : tables.edgesOf(face)) {
        const PolyEdge& e = tables.edges()[static_cast<std::size_t>(fe.edge)];
        const Vec3 a = V[static_cast<std::size_t>(e.v0)] - point;
        const Vec3 b = V[static_cast<std::size_t>(e.v1)] - point;
        const double omega = edgeLogTerm(a, b, a.norm(), b.norm(), e.length, e.delta);
        // (n_p x (r_e - r)) . u_e = -(n_p x u_e) . (r_e - r), r_e = r_v0
        out.W -= omega * fe.inward.dot(a);
        out.gradW += omega * fe.inward;
    }
    out.W -= out.solidAngle * h;
    out.gradW += out.solidAngle * f.normal;
    return out;
}

void evaluate(const PolyhedronTables& tables, const Vec3& M, std::span<const Vec3> points,
              std::span<Vec3> B, std::span<Vec3> A, std::span<double> insideFraction) {
    if (B.size() != points.size())
        throw std::invalid_argument("mbm::evaluate: B must be as long as points");
    evaluate(tables, M, points, FieldOutputs{B, A, insideFraction, {}, {}});
}

PointField evaluate(const PolyhedronTables& tables, const Vec3& M, const Vec3& point) {
    PointField f;
    evaluate(tables, M, std::span<const Vec3>(&point, 1),
             FieldOutputs{std::span<Vec3>(&f.B, 1), std::span<Vec3>(&f.A, 1),
                          std::span<double>(&f.insideFraction, 1),
                          std::span<double>(&f.scalarPotential, 1), std::span<Vec3>(&f.S, 1)});
    return f;
}

void evaluate(const PolyhedronTables& tables, const Vec3& M, std::span<const Vec3> points,
              const FieldOutputs& out) {
    const std::size_t nP = points.size();
    checkSize(out.B.size(), nP, "B");
    checkSize(out.A.size(), nP, "A");
    checkSize(out.insideFraction.size(), nP, "insideFraction");
    checkSize(out.scalarPotential.size(), nP, "scalarPotential");
    checkSize(out.S.size(), nP, "S");
    const bool wantB = !out.B.empty();
    // S = sum_p W_p n_p feeds both A (Eq. 9) and the scalar potential.
    const bool wantS = !out.A.empty() || !out.scalarPotential.empty() || !out.S.empty();

    // Per-call tables: M-dependent coefficients (Eqs. 11-13 regrouped edge-major).
    Scratch& s = scratch();
    const auto& edges = tables.edges();
    const auto& faces = tables.faces();
    const auto& tris = tables.triangles();
    const auto& verts = tables.vertices();
    s.edges.resize(edges.size());
    for (std::size_t e = 0; e < edges.size(); ++e) {
        const PolyEdge& pe = edges[e];
        const Vec3& n0 = faces[static_cast<std::size_t>(pe.face0)].normal;
        const Vec3& n1 = faces[static_cast<std::size_t>(pe.face1)].normal;
        EdgeWork& w = s.edges[e];
        w.v0 = pe.v0;
        w.v1 = pe.v1;
        w.length = pe.length;
        w.delta = pe.delta;
        w.K = n0 * pe.inward0.transpose() + n1 * pe.inward1.transpose();
        w.c = -(w.K * M);
    }
    s.faces.resize(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const PolyFace& pf = faces[f];
        s.faces[f] = {pf.normal, tris[static_cast<std::size_t>(pf.triBegin)].v[0],
                      M - pf.normal * pf.normal.dot(M), pf.triBegin, pf.triEnd};
    }
    s.rel.resize(verts.size());
    s.dist.resize(verts.size());
    s.invDist.resize(verts.size());

    double vertexScale = 0.0;
    for (const Vec3& v : verts) vertexScale = std::max(vertexScale, v.norm());
    const double k = mu0 / kFourPi;
    for (std::size_t i = 0; i < nP; ++i) {
        const Vec3 r = points[i];
        // |h| below this is rounding of r_v - r (eps relative to the coordinates): such a
        // point is ON the plane, and a face seen exactly edge-on has Omega_p = 0. Without
        // it, points on a tilted face's edge get atan2(~1e-19, ~1e-22): any angle.
        const double planeTolerance = 16.0 * kEps * (r.norm() + vertexScale);
        // Distances once per vertex.
        for (std::size_t v = 0; v < verts.size(); ++v) {
            s.rel[v] = verts[v] - r;
            s.dist[v] = s.rel[v].norm();
            s.invDist[v] = s.dist[v] > 0.0 ? 1.0 / s.dist[v] : 0.0;
        }
        Vec3 Bsum = Vec3::Zero(), Ssum = Vec3::Zero();
        // Edge terms: omega_e once per edge, shared by its two faces (Sec. 5).
        for (const EdgeWork& w : s.edges) {
            const Vec3& a = s.rel[static_cast<std::size_t>(w.v0)];
            const Vec3& b = s.rel[static_cast<std::size_t>(w.v1)];
            const double omega = edgeLogTerm(a, b, s.dist[static_cast<std::size_t>(w.v0)],
                                             s.dist[static_cast<std::size_t>(w.v1)], w.length,
                                             w.delta);
            Bsum += omega * w.c;
            if (wantS) Ssum -= omega * (w.K * a);
        }
        // Face terms: Omega_p summed over the face's triangles (Eq. 15).
        double omegaTotal = 0.0;
        for (const FaceWork& f : s.faces) {
            const double h = f.n.dot(s.rel[static_cast<std::size_t>(f.vertex)]); // (r_p - r) . n_p
            double omegaP = 0.0;
            // On the face plane (to rounding): principal value Omega_p = 0 (the mean of
            // the one-sided limits inside the face, the exact value outside it).
            if (std::abs(h) > planeTolerance) {
                // Omega_p = 2 arg prod_t (D_t + i N_t): one atan2 per face instead of one
                // per triangle. Exact because a planar face's Omega_p lies in
                // [-2 pi, 2 pi], so the half-angle sum never wraps; each factor is scaled
                // by 1/(R_a R_b R_c) (|factor| <= 4, no overflow/underflow).
                double re = 1.0, im = 0.0;
                for (int t = f.triBegin; t < f.triEnd; ++t) {
                    const PolyTriangle& tri = tris[static_cast<std::size_t>(t)];
                    const auto i0 = static_cast<std::size_t>(tri.v[0]);
                    const auto i1 = static_cast<std::size_t>(tri.v[1]);
                    const auto i2 = static_cast<std::size_t>(tri.v[2]);
                    const Vec3 &a = s.rel[i0], &b = s.rel[i1], &c = s.rel[i2];
                    const double Ra = s.dist[i0], Rb = s.dist[i1], Rc = s.dist[i2];
                    const double scale = s.invDist[i0] * s.invDist[i1] * s.invDist[i2];
                    // Eq. 15: N = a . (b x c) = 2 area (a . n_p), D as printed
                    const double N = tri.twiceArea * h * scale;
                    const double D = (Ra * Rb * Rc + Ra * b.dot(c) + Rb * c.dot(a) + Rc * a.dot(b)) * scale;
                    const double re2 = re * D - im * N;
                    im = re * N + im * D;
                    re = re2;
                }
                // every N_t has the sign of h, so the half-angle sum is in [0, pi] (h > 0)
                // or [-pi, 0]: keep rounding from flipping the sign of im near +-pi
                if (im * h < 0.0) im = std::copysign(0.0, h);
                omegaP = 2.0 * std::atan2(im, re);
            }
            omegaTotal += omegaP;
            Bsum += omegaP * f.d;
            if (wantS) Ssum -= (omegaP * h) * f.n;
        }
        if (wantB) out.B[i] = k * Bsum;
        if (!out.A.empty()) out.A[i] = k * M.cross(Ssum);
        if (!out.insideFraction.empty()) out.insideFraction[i] = omegaTotal / kFourPi;
        if (!out.scalarPotential.empty()) out.scalarPotential[i] = M.dot(Ssum) / kFourPi;
        if (!out.S.empty()) out.S[i] = Ssum;
    }
}

} // namespace mag::mbm

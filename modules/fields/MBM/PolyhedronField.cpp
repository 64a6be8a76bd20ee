// Closed-form field of a uniformly magnetized polyhedron (see the header).
#include "PolyhedronField.hpp"
#include "PolyhedronBlocks.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
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
    // the same tables for the blocked kernel (PolyhedronBlocks.hpp: plain data)
    std::vector<blocks::Edge> blockEdges;
    std::vector<blocks::Face> blockFaces;
    std::vector<blocks::Triangle> blockTriangles;
    double vertexScale = 0.0; // max_v |r_v|
    // What the tables above (and the kernel's own, prepared on this thread) were built
    // for: a call that repeats it reuses them (the wrench evaluates a target's samples
    // in blocks of 32, each with the same source and M). The id tells tables apart
    // even where a new one is built at a freed one's address; the vertex buffer, a
    // moved-from object from its moved-to twin.
    struct Key {
        std::uint64_t tablesId = 0;
        const Vec3* vertices = nullptr;
        Vec3 M = Vec3::Zero();
        const blocks::BlockKernel* kernel = nullptr;
        bool operator==(const Key& o) const { // M bit for bit (signed zeros, NaN)
            auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
            return tablesId == o.tablesId && vertices == o.vertices && kernel == o.kernel &&
                   bits(M.x()) == bits(o.M.x()) && bits(M.y()) == bits(o.M.y()) &&
                   bits(M.z()) == bits(o.M.z());
        }
    } prepared;
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

// What one evaluate() call needs besides the tables.
struct Call {
    const std::vector<Vec3>& verts;
    const std::vector<PolyTriangle>& tris;
    const Vec3& M;
    const FieldOutputs& out;
    double vertexScale; // max_v |r_v|
    bool wantS;
};

// The scalar, edge-major form at one point: the lanes of a
// block that need edgeLogTerm's special forms.
void evaluatePoint(Scratch& s, const Call& c, std::size_t i, const Vec3& r) {
    const double k = mu0 / kFourPi;
    // |h| below this is rounding of r_v - r (eps relative to the coordinates): such a
    // point is ON the plane, and a face seen exactly edge-on has Omega_p = 0. Without
    // it, points on a tilted face's edge get atan2(~1e-19, ~1e-22): any angle.
    const double planeTolerance = 16.0 * kEps * (r.norm() + c.vertexScale);
    // Distances once per vertex.
    for (std::size_t v = 0; v < c.verts.size(); ++v) {
        s.rel[v] = c.verts[v] - r;
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
        if (c.wantS) Ssum -= omega * (w.K * a);
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
                const PolyTriangle& tri = c.tris[static_cast<std::size_t>(t)];
                const auto i0 = static_cast<std::size_t>(tri.v[0]);
                const auto i1 = static_cast<std::size_t>(tri.v[1]);
                const auto i2 = static_cast<std::size_t>(tri.v[2]);
                const Vec3 &a = s.rel[i0], &b = s.rel[i1], &cc = s.rel[i2];
                const double Ra = s.dist[i0], Rb = s.dist[i1], Rc = s.dist[i2];
                const double scale = s.invDist[i0] * s.invDist[i1] * s.invDist[i2];
                // Eq. 15: N = a . (b x c) = 2 area (a . n_p), D as printed
                const double N = tri.twiceArea * h * scale;
                const double D =
                    (Ra * Rb * Rc + Ra * b.dot(cc) + Rb * cc.dot(a) + Rc * a.dot(b)) * scale;
                const double re2 = re * D - im * N;
                im = re * N + im * D;
                re = re2;
                // |factor| <= 4: keep a face of hundreds of triangles from overflowing
                if (const double m = std::abs(re) + std::abs(im); m > 0x1p500) {
                    re = std::ldexp(re, -500);
                    im = std::ldexp(im, -500);
                }
            }
            // every N_t has the sign of h, so the half-angle sum is in [0, pi] (h > 0)
            // or [-pi, 0]: keep rounding from flipping the sign of im near +-pi, and
            // give im = 0 the sign of h (atan2(+0, re < 0) = +pi on the outer side)
            if (im * h <= 0.0) im = std::copysign(0.0, h);
            omegaP = 2.0 * std::atan2(im, re);
        }
        omegaTotal += omegaP;
        Bsum += omegaP * f.d;
        if (c.wantS) Ssum -= (omegaP * h) * f.n;
    }
    const FieldOutputs& out = c.out;
    if (!out.B.empty()) out.B[i] = k * Bsum;
    if (!out.A.empty()) out.A[i] = k * c.M.cross(Ssum);
    if (!out.insideFraction.empty()) out.insideFraction[i] = omegaTotal / kFourPi;
    if (!out.scalarPotential.empty()) out.scalarPotential[i] = c.M.dot(Ssum) / kFourPi;
    if (!out.S.empty()) out.S[i] = Ssum;
}


// Every point goes through the blocked kernel (PolyhedronBlocks.hpp, the copy chosen
// at run time: KernelPath.hpp), a last partial block padded with copies of its last
// point: a point's result then does not depend on how many points share the call (the
// scalar and vector forms differ in the last bits), so a caller that splits its points
// (hybrid near/far, sample blocks per thread) gets the same bits. The kernel returns
// the sums per point; the lanes it flags are recomputed by evaluatePoint, the others
// scaled here, in chunks that stay in L1.
void evaluateBlocks(Scratch& s, const Call& c, const blocks::BlockKernel& kernel,
                    std::span<const Vec3> points) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "points are passed as x, y, z triples");
    constexpr std::size_t kChunk = 64; // a multiple of every copy's block width
    const double k = mu0 / kFourPi;
    const FieldOutputs& out = c.out;
    const std::size_t n = points.size();
    std::array<blocks::PointSums, kChunk> sums;
    for (std::size_t i0 = 0; i0 < n; i0 += kChunk) {
        const std::size_t m = std::min(kChunk, n - i0);
        kernel.sums(points[i0].data(), m, c.wantS, sums.data());
        for (std::size_t l = 0; l < m; ++l) {
            const std::size_t i = i0 + l;
            const blocks::PointSums& p = sums[l];
            if (p.special) {
                evaluatePoint(s, c, i, points[i]);
                continue;
            }
            const Vec3 S(p.S[0], p.S[1], p.S[2]);
            if (!out.B.empty()) out.B[i] = k * Vec3(p.B[0], p.B[1], p.B[2]);
            if (!out.A.empty()) out.A[i] = k * c.M.cross(S);
            if (!out.insideFraction.empty()) out.insideFraction[i] = p.omegaTotal / kFourPi;
            if (!out.scalarPotential.empty()) out.scalarPotential[i] = c.M.dot(S) / kFourPi;
            if (!out.S.empty()) out.S[i] = S;
        }
    }
}

// The per-call tables of `tables` and M for evaluatePoint (EdgeWork, FaceWork) and the
// blocked kernel (kernel.prepare).
void prepareTables(Scratch& s, const PolyhedronTables& tables, const Vec3& M,
                   const blocks::BlockKernel& kernel) {
    const auto& edges = tables.edges();
    const auto& faces = tables.faces();
    const auto& tris = tables.triangles();
    const auto& verts = tables.vertices();
    s.edges.resize(edges.size());
    s.blockEdges.resize(edges.size());
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
        // the thresholds exactly as edgeLogTerm computes them
        const double rhoMin = kEdgeRegularization * pe.length;
        s.blockEdges[e] = {pe.v0, pe.v1, pe.face0, pe.face1, pe.length,
                           pe.delta.x(), pe.delta.y(), pe.delta.z(),
                           w.c.x(), w.c.y(), w.c.z(),
                           pe.inward0.x(), pe.inward0.y(), pe.inward0.z(),
                           pe.inward1.x(), pe.inward1.y(), pe.inward1.z(),
                           rhoMin * rhoMin * pe.length * pe.length, 1e5 * rhoMin};
    }
    s.faces.resize(faces.size());
    s.blockFaces.resize(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const PolyFace& pf = faces[f];
        s.faces[f] = {pf.normal, tris[static_cast<std::size_t>(pf.triBegin)].v[0],
                      M - pf.normal * pf.normal.dot(M), pf.triBegin, pf.triEnd};
        const FaceWork& w = s.faces[f];
        s.blockFaces[f] = {w.n.x(), w.n.y(), w.n.z(), w.d.x(), w.d.y(), w.d.z(),
                           w.vertex, w.triBegin, w.triEnd};
    }
    s.blockTriangles.resize(tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t)
        s.blockTriangles[t] = {tris[t].v[0], tris[t].v[1], tris[t].v[2], tris[t].twiceArea};
    s.rel.resize(verts.size());
    s.dist.resize(verts.size());
    s.invDist.resize(verts.size());
    s.vertexScale = 0.0;
    for (const Vec3& v : verts) s.vertexScale = std::max(s.vertexScale, v.norm());
    kernel.prepare({verts.front().data(), verts.size(), s.blockEdges.data(), s.blockEdges.size(),
                    s.blockFaces.data(), s.blockFaces.size(), s.blockTriangles.data(),
                    s.blockTriangles.size(), s.vertexScale});
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
    // small and log1p keeps omega ~ L/R accurate (docs/physics.md#stable-forms). Farther
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

double planeTolerance(const PolyhedronTables& tables, const Vec3& point) {
    double vertexScale = 0.0;
    for (const Vec3& v : tables.vertices()) vertexScale = std::max(vertexScale, v.norm());
    return 16.0 * kEps * (point.norm() + vertexScale); // as in evaluate()
}

FaceIntegrals faceIntegrals(const PolyhedronTables& tables, int face, const Vec3& point) {
    return faceIntegrals(tables, face, point, planeTolerance(tables, point));
}

FaceIntegrals faceIntegrals(const PolyhedronTables& tables, int face, const Vec3& point,
                            double planeTolerance) {
    const PolyFace& f = tables.faces().at(static_cast<std::size_t>(face));
    const auto& V = tables.vertices();
    // (r_p - r) . n_p from a vertex: exactly 0 on an axis-aligned face plane
    const double h =
        f.normal.dot(V[static_cast<std::size_t>(tables.triangles()[static_cast<std::size_t>(f.triBegin)].v[0])] - point);
    FaceIntegrals out;
    if (std::abs(h) > planeTolerance) {
        for (int t = f.triBegin; t < f.triEnd; ++t) {
            const PolyTriangle& tri = tables.triangles()[static_cast<std::size_t>(t)];
            const Vec3 a = V[static_cast<std::size_t>(tri.v[0])] - point;
            const Vec3 b = V[static_cast<std::size_t>(tri.v[1])] - point;
            const Vec3 c = V[static_cast<std::size_t>(tri.v[2])] - point;
            out.solidAngle +=
                triangleSolidAngle(a, b, c, a.norm(), b.norm(), c.norm(), tri.twiceArea, h);
        }
        // A planar face subtends at most 2 pi. Within rounding of an edge between two of
        // its triangles (a merged face's diagonal) each triangle's D is rounding noise and
        // the sum can overshoot; evaluate()'s one-atan2 form has the same bound built in.
        out.solidAngle = std::clamp(out.solidAngle, -2.0 * std::numbers::pi, 2.0 * std::numbers::pi);
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
    // S = sum_p W_p n_p feeds both A (Eq. 9) and the scalar potential.
    const bool wantS = !out.A.empty() || !out.scalarPotential.empty() || !out.S.empty();

    if (nP == 0) return;

    // Per-call tables: M-dependent coefficients (Eqs. 11-13 regrouped edge-major), for
    // the scalar form here and the blocked kernel's copy in use (kept per thread).
    Scratch& s = scratch();
    const blocks::BlockKernel& kernel = blocks::current();
    const Scratch::Key key{tables.id(), tables.vertices().data(), M, &kernel};
    if (!(s.prepared == key)) {
        s.prepared = {};
        prepareTables(s, tables, M, kernel);
        s.prepared = key;
    }
    const Call call{tables.vertices(), tables.triangles(), M, out, s.vertexScale, wantS};
    evaluateBlocks(s, call, kernel, points);
}

} // namespace mag::mbm

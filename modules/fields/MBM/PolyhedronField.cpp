// Closed-form field of a uniformly magnetized polyhedron (see the header).
#include "PolyhedronField.hpp"
#include "SimdMath.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

// SIMD values go by value only between functions of this file, all inlined (no ABI
// boundary): the note about the AVX calling convention on plain x86-64 does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace mag::mbm {

namespace {

using simd::vd;
using simd::vm;
constexpr int kW = simd::kWidth;

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

// The same edge for the blocked path, constants already broadcast to every lane (AVX2
// has no broadcast operand): W_p of face0/face1 gets -omega_e (i . a) (Eq. 12), and
// the thresholds of edgeLogTerm's special forms.
struct BlockEdge {
    int v0, v1, face0, face1;
    vd length, twoLength, dx, dy, dz; // L, 2 L, r_v1 - r_v0
    vd cx, cy, cz;                    // EdgeWork::c
    vd i0x, i0y, i0z, i1x, i1y, i1z;
    vd cross2Min; // |a x delta|^2 below this: within delta L of the line
    vd smlMin;    // S - L at or below this (a . b >= 0): within ~1e-4 L of a vertex
};

// A face for the blocked path, broadcast likewise.
struct BlockFace {
    vd nx, ny, nz, dx, dy, dz; // FaceWork::n, FaceWork::d
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
    std::vector<BlockEdge> blockEdges;
    std::vector<FaceWork> faces;
    std::vector<Vec3> rel;    // r_v - r
    std::vector<double> dist; // |r_v - r|
    std::vector<double> invDist; // 1 / |r_v - r| (0 at the vertex itself)
    // the same for a block of kW points, one lane per point (structure of arrays)
    std::vector<vd> relX, relY, relZ, distV;
    std::vector<vd> W; // W_p per face (Eq. 12)
    std::vector<BlockFace> blockFaces;
    std::vector<vd> twiceArea; // per triangle
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


// Sums of one block, one lane per point.
struct BlockSums {
    vd Bx, By, Bz, Sx, Sy, Sz, omegaTotal;
};

// The same terms as evaluatePoint for kW points at once, edge-major, in the same
// operation order where a threshold depends on the result (h, R, a . b, |a x delta|),
// so every lane takes the branch the scalar form would. The lanes where edgeLogTerm
// needs a special form (within delta L of an edge line, within ~1e-4 L of a vertex) or
// where a coordinate is not finite are returned as set bits: the caller recomputes
// them with evaluatePoint. Everything else (Omega_p = 0 on a face plane, the sign fix
// near +-2 pi) is done per lane here.
template <bool wantS>
unsigned evaluateBlock(Scratch& s, const Call& c, const Vec3* p, BlockSums& sum) {
    vd px, py, pz;
    for (int l = 0; l < kW; ++l) {
        px[l] = p[l].x();
        py[l] = p[l].y();
        pz[l] = p[l].z();
    }
    const vd r2 = (px * px + py * py) + pz * pz;
    vm special = ~(r2 <= std::numeric_limits<double>::max()); // NaN or infinite
    const vd planeTolerance = (16.0 * kEps) * (simd::sqrt(r2) + c.vertexScale);
    const std::size_t nV = c.verts.size();
    for (std::size_t v = 0; v < nV; ++v) {
        const vd x = c.verts[v].x() - px, y = c.verts[v].y() - py, z = c.verts[v].z() - pz;
        const vd d = simd::sqrt((x * x + y * y) + z * z);
        s.relX[v] = x;
        s.relY[v] = y;
        s.relZ[v] = z;
        s.distV[v] = d;
    }
    vd Bx{}, By{}, Bz{};
    if constexpr (wantS) std::fill(s.W.begin(), s.W.end(), vd{});
    // Edge terms (Eq. 14), one log per lane: beside the segment (a . b < 0) the stable
    // ratio ln[(S + L)^2 (R1 R2 - a . b) / (2 |a x delta|^2)], elsewhere log1p(2L / (S - L)).
    for (const BlockEdge& e : s.blockEdges) {
        const auto v0 = static_cast<std::size_t>(e.v0), v1 = static_cast<std::size_t>(e.v1);
        const vd ax = s.relX[v0], ay = s.relY[v0], az = s.relZ[v0], R1 = s.distV[v0];
        const vd bx = s.relX[v1], by = s.relY[v1], bz = s.relZ[v1], R2 = s.distV[v1];
        const vd ab = (ax * bx + ay * by) + az * bz;
        const vd S = R1 + R2;
        const vd qx = ay * e.dz - az * e.dy, qy = az * e.dx - ax * e.dz, qz = ax * e.dy - ay * e.dx;
        const vd cross2 = (qx * qx + qy * qy) + qz * qz;
        const vd SmL = S - e.length, SpL = S + e.length;
        const vm beside = ab < 0.0;
        special |= beside ? (cross2 < e.cross2Min) : (SmL <= e.smlMin);
        const vd num = simd::select(beside, SpL * SpL * (R1 * R2 - ab), e.twoLength);
        const vd den = simd::select(beside, 2.0 * cross2, SmL);
        const vd q = num / den;
        const vd u = simd::select(beside, q, 1.0 + q);
        const vd bb = u - 1.0; // u = fl(1 + q) loses (1 - (u - bb)) + (q - bb) (TwoSum)
        const vd lo = simd::select(beside, vd{}, (1.0 - (u - bb)) + (q - bb));
        const vd omega = simd::logPlus(u, lo);
        Bx = simd::fma(omega, e.cx, Bx);
        By = simd::fma(omega, e.cy, By);
        Bz = simd::fma(omega, e.cz, Bz);
        if constexpr (wantS) {
            // (n_p x (r_e - r)) . u_e = -(n_p x u_e) . a, a = r_v0 - r (Eq. 12)
            const vd i0a = simd::fma(e.i0z, az, simd::fma(e.i0y, ay, e.i0x * ax));
            const vd i1a = simd::fma(e.i1z, az, simd::fma(e.i1y, ay, e.i1x * ax));
            vd& W0 = s.W[static_cast<std::size_t>(e.face0)];
            vd& W1 = s.W[static_cast<std::size_t>(e.face1)];
            W0 = simd::fma(-omega, i0a, W0);
            W1 = simd::fma(-omega, i1a, W1);
        }
    }
    // Face terms (Eq. 15): one atan2 per face and lane, as in evaluatePoint.
    vd Sx{}, Sy{}, Sz{}, omegaTotal{};
    for (std::size_t fi = 0; fi < s.faces.size(); ++fi) {
        const FaceWork& f = s.faces[fi];
        const BlockFace& bf = s.blockFaces[fi];
        const auto fv = static_cast<std::size_t>(f.vertex);
        const vd h = (bf.nx * s.relX[fv] + bf.ny * s.relY[fv]) + bf.nz * s.relZ[fv];
        // Omega_p = 2 arg prod_t (D_t + i N_t) as in evaluatePoint, but the running
        // product renormalized by a power of two (exact) instead of each factor divided
        // by R_a R_b R_c: the argument is the same, without a reciprocal per vertex.
        vd re{}, im{};
        for (int t = f.triBegin; t < f.triEnd; ++t) {
            const PolyTriangle& tri = c.tris[static_cast<std::size_t>(t)];
            const auto i0 = static_cast<std::size_t>(tri.v[0]);
            const auto i1 = static_cast<std::size_t>(tri.v[1]);
            const auto i2 = static_cast<std::size_t>(tri.v[2]);
            const vd ax = s.relX[i0], ay = s.relY[i0], az = s.relZ[i0];
            const vd bx = s.relX[i1], by = s.relY[i1], bz = s.relZ[i1];
            const vd cx = s.relX[i2], cy = s.relY[i2], cz = s.relZ[i2];
            const vd Ra = s.distV[i0], Rb = s.distV[i1], Rc = s.distV[i2];
            const vd N = s.twiceArea[static_cast<std::size_t>(t)] * h;
            const vd bc = (bx * cx + by * cy) + bz * cz;
            const vd ca = (cx * ax + cy * ay) + cz * az;
            const vd abd = (ax * bx + ay * by) + az * bz;
            const vd D = Ra * Rb * Rc + Ra * bc + Rb * ca + Rc * abd;
            if (t == f.triBegin) {
                re = D;
                im = N;
                continue;
            }
            const vd re2 = re * D - im * N;
            im = re * N + im * D;
            re = re2;
            const vd scale = simd::pow2Inverse(simd::abs(re) + simd::abs(im));
            re *= scale;
            im *= scale;
        }
        im = simd::select(im * h <= 0.0, simd::copysign(vd{}, h), im); // as evaluatePoint
        const vd omegaP =
            simd::select(simd::abs(h) > planeTolerance, 2.0 * simd::atan2(im, re), vd{});
        omegaTotal += omegaP;
        Bx = simd::fma(omegaP, bf.dx, Bx);
        By = simd::fma(omegaP, bf.dy, By);
        Bz = simd::fma(omegaP, bf.dz, Bz);
        if constexpr (wantS) {
            const vd Wp = simd::fma(-omegaP, h, s.W[fi]); // Eq. 12
            Sx = simd::fma(Wp, bf.nx, Sx);
            Sy = simd::fma(Wp, bf.ny, Sy);
            Sz = simd::fma(Wp, bf.nz, Sz);
        }
    }
    sum = {Bx, By, Bz, Sx, Sy, Sz, omegaTotal};
    return simd::bits(special);
}

// Every point goes through the blocked path, a last partial block padded with copies
// of its last point: a point's result then does not depend on how many points share
// the call (the scalar and vector forms differ in the last bits), so a caller that
// splits its points (hybrid near/far, sample blocks per thread) gets the same bits.
template <bool wantS>
void evaluateBlocks(Scratch& s, const Call& c, std::span<const Vec3> points) {
    const double k = mu0 / kFourPi;
    const FieldOutputs& out = c.out;
    const std::size_t n = points.size();
    BlockSums sum;
    std::array<Vec3, kW> pad;
    for (std::size_t i0 = 0; i0 < n; i0 += kW) {
        const std::size_t m = std::min<std::size_t>(kW, n - i0);
        const Vec3* p = points.data() + i0;
        if (m < kW) {
            for (std::size_t l = 0; l < kW; ++l) pad[l] = points[i0 + std::min(l, m - 1)];
            p = pad.data();
        }
        const unsigned special = evaluateBlock<wantS>(s, c, p, sum);
        for (std::size_t l = 0; l < m; ++l) {
            const std::size_t i = i0 + l;
            if (special & (1u << l)) {
                evaluatePoint(s, c, i, points[i]);
                continue;
            }
            const Vec3 S(sum.Sx[l], sum.Sy[l], sum.Sz[l]);
            if (!out.B.empty()) out.B[i] = k * Vec3(sum.Bx[l], sum.By[l], sum.Bz[l]);
            if (!out.A.empty()) out.A[i] = k * c.M.cross(S);
            if (!out.insideFraction.empty()) out.insideFraction[i] = sum.omegaTotal[l] / kFourPi;
            if (!out.scalarPotential.empty()) out.scalarPotential[i] = c.M.dot(S) / kFourPi;
            if (!out.S.empty()) out.S[i] = S;
        }
    }
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

    // Per-call tables: M-dependent coefficients (Eqs. 11-13 regrouped edge-major).
    Scratch& s = scratch();
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
        using simd::splat;
        s.blockEdges[e] = {pe.v0, pe.v1, pe.face0, pe.face1,
                           splat(pe.length), splat(2.0 * pe.length),
                           splat(pe.delta.x()), splat(pe.delta.y()), splat(pe.delta.z()),
                           splat(w.c.x()), splat(w.c.y()), splat(w.c.z()),
                           splat(pe.inward0.x()), splat(pe.inward0.y()), splat(pe.inward0.z()),
                           splat(pe.inward1.x()), splat(pe.inward1.y()), splat(pe.inward1.z()),
                           splat(rhoMin * rhoMin * pe.length * pe.length), splat(1e5 * rhoMin)};
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
    const Call call{verts, tris, M, out, vertexScale, wantS};

    // Blocks of kW points (structure of arrays); the last one padded.
    if (nP > 0) {
        s.relX.resize(verts.size());
        s.relY.resize(verts.size());
        s.relZ.resize(verts.size());
        s.distV.resize(verts.size());
        s.W.resize(faces.size());
        s.blockFaces.resize(faces.size());
        for (std::size_t f = 0; f < faces.size(); ++f) {
            const FaceWork& w = s.faces[f];
            using simd::splat;
            s.blockFaces[f] = {splat(w.n.x()), splat(w.n.y()), splat(w.n.z()),
                               splat(w.d.x()), splat(w.d.y()), splat(w.d.z())};
        }
        s.twiceArea.resize(tris.size());
        for (std::size_t t = 0; t < tris.size(); ++t) s.twiceArea[t] = simd::splat(tris[t].twiceArea);
        if (wantS)
            evaluateBlocks<true>(s, call, points);
        else
            evaluateBlocks<false>(s, call, points);
    }
}

} // namespace mag::mbm

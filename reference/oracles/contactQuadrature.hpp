// Independent test oracle: charge-model (Coulombian) force and torque between two
// uniformly magnetized cuboids that may TOUCH (face on face, edge on face, vertex on face,
// edge to edge) or nearly touch, accurate to ~1e-10 relative there; and the one-sided
// (physical) contact limit of the Akoun-Yonnet force of two parallel cuboids.
//
// REFERENCE VALUES (this file, relTol 1e-12; checked by tests/test_contactOracle.cpp,
// "the reference values"). Two 1 cm cubes, M = (1 T / mu0) e_z (world) both; source
// axis-aligned at the origin; target centre c2 (m), rotation R2 (body -> world); force
// on the target (N) and torque about c2 (N m), 10 digits; components that vanish by
// symmetry (below 1e-12 relative) written 0. Rz30 = 30 deg about z; Rx45 = 45 deg about x
// (the target rests on its lower edge, along x); Rv = acos(-1/sqrt3) about (-1, 1, 0)/sqrt2
// (takes the body diagonal (1,1,1)/sqrt3 to -z: the target rests on a vertex).
//   coaxial, touching           c2 = (0, 0, 0.01)
//       F = (0, 0, -32.37863296)                         T = (0, 0, 0)
//   offset (3, 2) mm, touching  c2 = (0.003, 0.002, 0.01)
//       F = (-9.150942274, -6.881274379, -15.61100447)   T = (-0.01879536742, 0.02233820467, 0.001170969294)
//   offset (5, 5) mm, touching  c2 = (0.005, 0.005, 0.01)
//       F = (-7.111730414, -7.111730414, -4.943744363)   T = (-0.02319929116, 0.02319929116, 0)
//   edge to edge                c2 = (0.01, 0, 0.01)
//       F = (-6.779247875, 0, 3.462332414)               T = (0, 0.05120790144, 0)
//   rotated footprint           c2 = (0, 0, 0.01), R2 = Rz30
//       F = (0, 0, -26.22521328)                         T = (0, 0, -0.005766853108)
//   on its lower edge           c2 = (0, 0, 0.005 + 0.005 sqrt2), R2 = Rx45
//       F = (0, 0, -15.02530617)                         T = (0, 0, 0)
//   on a vertex                 c2 = (0, 0, 0.005 + 0.005 sqrt3), R2 = Rv
//       F = (-0.03696809755, -0.03696809755, -9.829194262)  T = (-0.0001081800937, 0.0001081800937, 0)
//   gap 1 um, coaxial           c2 = (0, 0, 0.010001)
//       F = (0, 0, -32.33198254)                         T = (0, 0, 0)
//   gap 10 um, coaxial          c2 = (0, 0, 0.01001)
//       F = (0, 0, -32.02874544)                         T = (0, 0, 0)
// The four parallel touching rows equal akounYonnetForceOneSided to <= 3e-12 (the mean
// of the two limits, akounYonnetForce, gives +7.41013 N for the coaxial pair); the three
// rotated rows continue the trend of gaps 0.1, 0.2 um to ~1e-9 (tests).
//
// 1. akounYonnetForceOneSided (parallel boxes polarized along z, as akounYonnet.hpp).
//    akounYonnetForce takes the atan term atan(u v / (r w)) of phi_z as 0 where w = 0
//    (a face of magnet 2 coplanar with one of magnet 1): the mean of the two limits w ->
//    0+ and w -> 0-. Moving magnet 2 away along the line of centres, c2 -> c2 + t d with
//    d = c2 - c1 and t -> 0+, changes every w_pq by t d_z, so a term with w_pq = 0 tends
//    to w -> 0 with the sign of d_z. For w -> 0 with that sign s:
//      u v atan(u v / (r w)) -> s |u v| pi / 2          (0 when u v = 0: bounded atan)
//    while every other term of phi is continuous there (the atan terms of phi_x, phi_y
//    carry a factor w; the logs are continuous with the x ln x -> 0 limit), so the
//    one-sided force is the mean plus J1 J2/(4 pi mu0) sum_{w_pq = 0} (+-) s |u v| pi/2
//    in z. Summing over i, j, k, l: sum (-1)^(i+j) |u_ij| = -2 L_x (L_x = overlap length
//    of the two x intervals; likewise y), so the correction is
//      dF_z = s J1 J2/(2 mu0) L_x L_y sum_{p,q: w_pq = 0} (-1)^(p+q),
//    the normal force of the contact jump sigma1/2 of H over the shared area L_x L_y
//    (coaxial 1 cm cubes, 1 T: mean +7.41 N, jump -39.79 N, one-sided -32.38 N).
//    If d_z = 0 the w = 0 terms stay at w = 0 along the approach (side-by-side boxes with
//    coplanar faces): their limit is the w = 0 value (the mean). For a touching pair then
//    L_x = 0 or L_y = 0 (they touch through an x or a y face), so the two one-sided values
//    coincide anyway and nothing is lost. |w| <= 1e-13 (c + C) counts as w = 0 (rounding
//    of the given centres, e.g. 0.005 + 0.0075 for different heights).
//
// 2. contactChargeWrench: F = int_{dV2} sigma mu0 H1 dA, T = int_{dV2} (r - p) x sigma mu0
//    H1 dA, sigma = M2 . n, over the six faces of the target (the complete charge-model
//    torque: chargeQuadrature.hpp explains why no volume couple is added). H1 from the
//    closed form of cuboidField.hpp (detail::rectangleSheetH per source face), any poses.
//    Where a target face lies IN the plane of a source face (all four target-face corners
//    within 1e-13 L of that plane, normals (anti)parallel within 1e-12), the point is on
//    the source's surface where the two faces overlap and H1 jumps there by M1 . n_s: the
//    ONE-SIDED value from the side of the target's interior is used (the target lies
//    outside the source: H = mean + (M1 . n_s)/2 n_s inside the source face, with the
//    source face's own normal term evaluated at w = 0 exactly, i.e. its mean 0, plus
//    the half jump; outside that face the two sides agree and nothing is added). If the
//    target's interior were on the source's inner side (overlap), the other limit is used.
//    Exactly touching configurations are thus the t -> 0+ limits of separated ones
//    (tests: equal to akounYonnetForceOneSided, and to the extrapolation of small gaps).
//
//    Quadrature: on each target face (local x in [-a, a] outer, y in [-b, b] inner),
//    an iterated 1D GLOBAL adaptive Gauss-Kronrod G7K15 (Piessens et al., QUADPACK,
//    1983: the interval with the largest error estimate |K15 - G7| is bisected until the
//    sum of the estimates is below the tolerance). The integrand is piecewise analytic,
//    with jumps and logarithmic singularities only on the lines where source edges meet
//    (or, for gaps, pass close to) the face plane and at source vertices. Breakpoints:
//      inner (fixed x): for every source edge the point of the line closest to the edge
//        (its crossing for an edge lying in the plane), and the projection of every
//        source vertex onto the line;
//      outer: the x of the projected source vertices, of the crossings of the projected
//        source edges with the face sides y = +-b and of the edges' plane piercings;
//    each only where the feature is within max(a, b)/4 of the line (face); farther ones
//    are smooth on the scale of the face and left to the bisection.
//    Every interval between breakpoints is mapped by the polynomial endpoint grading
//    x = c + (d - c) phi(s), phi'(s) = 140 s^3 (1 - s)^3 (the polynomial form of Sidi's
//    sin^m transformation, m = 3: A. Sidi, "A new variable transformation for numerical
//    integration", Numerical Integration IV, ISNM 112 (1993) 359-373): an endpoint log
//    singularity becomes s^3 ln s, and a
//    near singularity of width g at an endpoint is stretched to width ~(g/(d-c))^(1/4),
//    so the bisection needs only a few levels. The inner tolerance is relTol/5 of the
//    line integral (its error then stays below the outer one), the outer relTol of the
//    face integral (weighted 1-norm of the force moments int H, int x H/a, int y H/b).
//    Nodes closer than 1e-14 L (L = 2 max(a, b)) to a breakpoint are skipped: the
//    integrand there is at worst logarithmic, so the skipped part is < 1e-12 of the face
//    integral, and no node can fall on a source edge (non-finite H) through rounding of
//    the breakpoints (~1e-16 L). A non-finite H would throw (a breakpoint was missed).
//    The force error is then ~relTol of the sum of the face forces (the estimates are
//    those of G7, the K15 result is far better: measured errors are ~1e-13 with the
//    default relTol 1e-10, see tests). Each 1D integral stops at 4000 intervals (never
//    reached in the tests); ContactQuadratureInfo returns the summed estimates.
//    Cost: 0.05-0.3 s for two cubes polarized along a body axis, ~1 s for oblique M and
//    general poses (6 charged faces on each body), on one core.
//
// Units: SI (m, A/m, N, N m). Intended for non-overlapping (touching allowed) bodies.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "akounYonnet.hpp"
#include "chargeQuadrature.hpp"
#include "cuboidField.hpp"

namespace oracle {

namespace detail {

/// akounYonnetPhi with the one-sided limit of the atan term where w == 0: side = the
/// sign with which w tends to 0 (+1 or -1), 0 for the mean (akounYonnetPhi's value).
inline Eigen::Vector3d akounYonnetPhiOneSided(double u, double v, double w, double side) {
    Eigen::Vector3d phi = akounYonnetPhi(u, v, w);
    // w -> 0 with sign side: atan(u v/(r w)) -> side sgn(u v) pi/2; only phi_z's u v atan
    // term survives (phi_x, phi_y have v w atan, u w atan -> 0)
    if (w == 0.0 && side != 0.0) phi.z() += side * std::abs(u * v) * (0.5 * pi);
    return phi;
}

}  // namespace detail

/// Charge-model force on magnet 2 (N) from magnet 1, parallel axis-aligned boxes polarized
/// along z (arguments as akounYonnetForce). Where a face of magnet 2 is coplanar with one
/// of magnet 1 (touching), the limit as the boxes move apart along the line of centres
/// (c2 -> c2 + t (c2 - c1), t -> 0+) instead of the mean of the two limits.
inline Eigen::Vector3d akounYonnetForceOneSided(const Eigen::Vector3d& size1,
                                                const Eigen::Vector3d& centre1,
                                                const Eigen::Vector3d& size2,
                                                const Eigen::Vector3d& centre2, double J1,
                                                double J2) {
    const Eigen::Vector3d d = centre2 - centre1;
    const double side = d.z() > 0.0 ? 1.0 : (d.z() < 0.0 ? -1.0 : 0.0);
    const double wZero = 1e-13 * 0.5 * (size1.z() + size2.z());
    return detail::akounYonnetSum(size1, centre1, size2, centre2, J1, J2, [&](double u, double v, double w) {
        return detail::akounYonnetPhiOneSided(u, v, std::abs(w) <= wZero ? 0.0 : w, side);
    });
}

/// What contactChargeWrench did: field evaluations and error estimates (N, N m; the
/// summed G7 estimates of the outer integrals, conservative).
struct ContactQuadratureInfo {
    long evaluations = 0;
    double forceError = 0.0;
    double torqueError = 0.0;
};

namespace detail {

/// 15-point Gauss-Kronrod rule on [-1, 1] (QUADPACK qk15): nodes +-xgk[j] (xgk[7] = 0),
/// Kronrod weights wgk; the 7-point Gauss rule uses the nodes xgk[1], xgk[3], xgk[5],
/// xgk[7] with weights wg.
inline constexpr double gkNodes[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
inline constexpr double gkKronrodWeights[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr double gkGaussWeights[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

/// Endpoint grading phi(s) = 35 s^4 - 84 s^5 + 70 s^6 - 20 s^7 (phi(0) = 0, phi(1) = 1,
/// phi(1 - s) = 1 - phi(s)) and phi'(s) = 140 s^3 (1 - s)^3.
inline double gradePhi(double s) { return s * s * s * s * (35.0 + s * (-84.0 + s * (70.0 - 20.0 * s))); }
inline double gradeDphi(double s) {
    const double t = s * (1.0 - s);
    return 140.0 * t * t * t;
}

/// Global adaptive G7K15 of a vector function over [breaks.front(), breaks.back()],
/// graded towards every breakpoint (see the file comment). Stops when the summed error
/// estimates (weighted 1-norm) are <= max(relTol |result|, absTol), or at maxIntervals.
template <int N>
struct GradedIntegrator {
    using Vec = Eigen::Matrix<double, N, 1>;
    Vec weights = Vec::Ones();  // norm(v) = sum_i weights_i |v_i|
    double relTol = 1e-10;
    double absTol = 0.0;
    double skip = 0.0;          // nodes closer than this to a breakpoint are left out
    int maxIntervals = 4000;
    long evaluations = 0;       // integrand calls (cumulative)
    double error = 0.0;         // error estimate of the last integral (norm)

    double norm(const Vec& v) const { return (weights.array() * v.array().abs()).sum(); }

    struct Interval {
        double c, h, s0, s1;  // piece [c, c + h], sub-interval [s0, s1] of s in [0, 1]
        Vec value;
        double error;
        bool operator<(const Interval& o) const { return error < o.error; }
    };

    template <class F>
    void rule(F& f, Interval& iv) {
        const double mid = 0.5 * (iv.s0 + iv.s1), half = 0.5 * (iv.s1 - iv.s0);
        Vec kronrod = Vec::Zero(), gauss = Vec::Zero();
        for (int j = 0; j < 8; ++j) {
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                if (j == 7 && sgn == 1) break;  // the centre node once
                const double s = mid + sgn * half * gkNodes[j];
                const bool lower = s <= 0.5;
                const double dist = iv.h * gradePhi(lower ? s : 1.0 - s);
                if (dist < skip) continue;  // at a breakpoint: negligible (file comment)
                const double x = lower ? iv.c + dist : (iv.c + iv.h) - dist;
                const Vec g = f(x) * (iv.h * gradeDphi(s));
                ++evaluations;
                kronrod += gkKronrodWeights[j] * g;
                if (j & 1) gauss += gkGaussWeights[j / 2] * g;
            }
        }
        iv.value = half * kronrod;
        iv.error = norm(half * (kronrod - gauss));
    }

    template <class F>
    Vec integrate(F&& f, const std::vector<double>& breaks) {
        std::vector<Interval> heap;
        heap.reserve(64);
        Vec total = Vec::Zero();
        double err = 0.0;
        for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
            Interval iv{breaks[i], breaks[i + 1] - breaks[i], 0.0, 1.0, Vec::Zero(), 0.0};
            if (!(iv.h > 0.0)) continue;
            rule(f, iv);
            total += iv.value;
            err += iv.error;
            heap.push_back(iv);
        }
        std::make_heap(heap.begin(), heap.end());
        int count = static_cast<int>(heap.size());
        while (!heap.empty() && err > std::max(relTol * norm(total), absTol) &&
               count < maxIntervals) {
            std::pop_heap(heap.begin(), heap.end());
            const Interval parent = heap.back();
            heap.pop_back();
            const double sm = 0.5 * (parent.s0 + parent.s1);
            Interval left = parent, right = parent;
            left.s1 = sm;
            right.s0 = sm;
            rule(f, left);
            rule(f, right);
            total += left.value + right.value - parent.value;
            err += left.error + right.error - parent.error;
            heap.push_back(left);
            std::push_heap(heap.begin(), heap.end());
            heap.push_back(right);
            std::push_heap(heap.begin(), heap.end());
            ++count;
        }
        // exact re-summation (no drift of the running sums)
        total.setZero();
        err = 0.0;
        for (const Interval& iv : heap) {
            total += iv.value;
            err += iv.error;
        }
        error = err;
        return total;
    }
};

/// Sorted breakpoints with the ends lo, hi and the given interior points, points closer
/// than mergeTol merged.
inline std::vector<double> sortedBreaks(double lo, double hi, std::vector<double>& pts,
                                        double mergeTol) {
    std::vector<double> out;
    out.reserve(pts.size() + 2);
    out.push_back(lo);
    std::sort(pts.begin(), pts.end());
    for (double x : pts) {
        if (!(x > lo + mergeTol && x < hi - mergeTol)) continue;
        if (x - out.back() > mergeTol) out.push_back(x);
    }
    out.push_back(hi);
    return out;
}

/// The source's field on one target face, and the face's geometry.
struct FaceSetup {
    const Cuboid* src = nullptr;
    // face: centre fc, tangents t1 (x, half width a), t2 (y, half width b), normal n
    Eigen::Vector3d fc, t1, t2, n;
    double a = 0.0, b = 0.0;
    // source body coordinates of the face point (x, y): P0 + x E1 + y E2
    Eigen::Vector3d P0, E1, E2, Mb;
    int coplanarAxis = -1;  // source face (axis, sign) whose plane holds the target face
    int coplanarSign = 0;
    double side = 0.0;      // +1: target interior on the source's outer side
    // source vertices in face coordinates (x, y, height above the face plane)
    Eigen::Vector3d V[8];

    void init(const Cuboid& source, const Cuboid& target, int k, int s) {
        src = &source;
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        n = s * target.R.col(k);
        t1 = target.R.col(k1);
        t2 = target.R.col(k2);
        a = target.halfSize[k1];
        b = target.halfSize[k2];
        fc = target.centre + target.halfSize[k] * n;
        const Eigen::Matrix3d Rt = source.R.transpose();
        P0 = Rt * (fc - source.centre);
        E1 = Rt * t1;
        E2 = Rt * t2;
        Mb = Rt * source.M;
        const double L = std::max({a, b, source.halfSize.maxCoeff()});
        for (int ks = 0; ks < 3 && coplanarAxis < 0; ++ks) {
            const Eigen::Vector3d ns = source.R.col(ks);
            const double c = n.dot(ns);
            if (std::abs(c) < 1.0 - 1e-12) continue;
            for (int ss = -1; ss <= 1; ss += 2) {
                bool inPlane = true;
                for (int ca = -1; ca <= 1 && inPlane; ca += 2)
                    for (int cb = -1; cb <= 1 && inPlane; cb += 2) {
                        const Eigen::Vector3d pb = P0 + ca * a * E1 + cb * b * E2;
                        inPlane = std::abs(pb[ks] - ss * source.halfSize[ks]) <= 1e-13 * L;
                    }
                if (inPlane) {
                    coplanarAxis = ks;
                    coplanarSign = ss;
                    // target interior is on the -n side: outside the source iff n . n_s < 0
                    side = (c * ss < 0.0) ? 1.0 : -1.0;
                    break;
                }
            }
        }
        int i = 0;
        for (int sx = -1; sx <= 1; sx += 2)
            for (int sy = -1; sy <= 1; sy += 2)
                for (int sz = -1; sz <= 1; sz += 2) {
                    const Eigen::Vector3d v =
                        source.centre + source.R * Eigen::Vector3d(sx * source.halfSize.x(),
                                                                   sy * source.halfSize.y(),
                                                                   sz * source.halfSize.z());
                    V[i++] = Eigen::Vector3d(t1.dot(v - fc), t2.dot(v - fc), n.dot(v - fc));
                }
    }

    /// The 12 edges as vertex index pairs (vertices indexed 4 sx' + 2 sy' + sz').
    static constexpr int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                         {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

    /// H1 (A/m, world) at the face point (x, y), one-sided on a coplanar source face.
    Eigen::Vector3d H(double x, double y) const {
        const Eigen::Vector3d p = P0 + x * E1 + y * E2;
        const Eigen::Vector3d& h = src->halfSize;
        Eigen::Vector3d Hb = Eigen::Vector3d::Zero();
        for (int k = 0; k < 3; ++k) {
            if (Mb[k] == 0.0) continue;
            const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
            for (int s = -1; s <= 1; s += 2) {
                const bool coplanar = (k == coplanarAxis && s == coplanarSign);
                const double w = coplanar ? 0.0 : p[k] - s * h[k];
                rectangleSheetH(s * Mb[k], h[k1], h[k2], p[k1], p[k2], w, Hb[k1], Hb[k2], Hb[k]);
                // inside the coplanar source face: the half jump towards the target's side
                if (coplanar && std::abs(p[k1]) < h[k1] && std::abs(p[k2]) < h[k2])
                    Hb[k] += side * 0.5 * Mb[k];
            }
        }
        if (!std::isfinite(Hb.squaredNorm()))
            throw std::runtime_error("contactChargeWrench: non-finite field (missed breakpoint)");
        return src->R * Hb;
    }

    /// Inner breakpoints (y) on the line x = const (file comment).
    std::vector<double> innerBreaks(double x, double thr, double mergeTol) const {
        std::vector<double> pts;
        for (const Eigen::Vector3d& v : V)
            if (std::hypot(v.x() - x, v.z()) < thr) pts.push_back(v.y());
        for (const auto& e : edges) {
            const Eigen::Vector3d& A = V[e[0]];
            const Eigen::Vector3d D = V[e[1]] - A;
            const double dp2 = D.x() * D.x() + D.z() * D.z();
            if (dp2 <= 1e-24 * D.squaredNorm()) continue;  // parallel to the line: vertices
            const double qx = A.x() - x, qz = A.z();
            const double u = -(qx * D.x() + qz * D.z()) / dp2;
            if (!(u > 0.0 && u < 1.0)) continue;
            if (std::hypot(qx + u * D.x(), qz + u * D.z()) < thr) pts.push_back(A.y() + u * D.y());
        }
        return sortedBreaks(-b, b, pts, mergeTol);
    }

    /// Outer breakpoints (x) of the face (file comment).
    std::vector<double> outerBreaks(double thr, double mergeTol) const {
        std::vector<double> pts;
        for (const Eigen::Vector3d& v : V)
            if (std::hypot(std::max(std::abs(v.y()) - b, 0.0), v.z()) < thr) pts.push_back(v.x());
        for (const auto& e : edges) {
            const Eigen::Vector3d& A = V[e[0]];
            const Eigen::Vector3d D = V[e[1]] - A;
            for (int sb = -1; sb <= 1; sb += 2) {
                if (D.y() == 0.0) break;
                const double u = (sb * b - A.y()) / D.y();
                if (u > 0.0 && u < 1.0 && std::abs(A.z() + u * D.z()) < thr)
                    pts.push_back(A.x() + u * D.x());
            }
            if (D.z() != 0.0) {
                const double u = -A.z() / D.z();
                if (u > 0.0 && u < 1.0 && std::abs(A.y() + u * D.y()) < b + thr)
                    pts.push_back(A.x() + u * D.x());
            }
        }
        return sortedBreaks(-a, a, pts, mergeTol);
    }
};

}  // namespace detail

/// Charge-model force (N) and torque about p (N m) on the cuboid `target` in the field of
/// the cuboid `source` (any poses), accurate also when they touch or nearly touch; on a
/// source face the field is the one-sided value from the target's side (file comment).
/// relTol: relative tolerance of each face integral. info (optional): evaluations and
/// error estimates.
inline Wrench contactChargeWrench(const Cuboid& source, const Cuboid& target,
                                  const Eigen::Vector3d& p, double relTol = 1e-10,
                                  ContactQuadratureInfo* info = nullptr) {
    using Vec6 = Eigen::Matrix<double, 6, 1>;
    using Vec9 = Eigen::Matrix<double, 9, 1>;
    Wrench result;
    long evaluations = 0;
    double forceError = 0.0, torqueError = 0.0;
    const double Hscale = std::max(source.M.norm(), 1e-300);
    for (int k = 0; k < 3; ++k)
        for (int s = -1; s <= 1; s += 2) {
            detail::FaceSetup face;
            face.init(source, target, k, s);
            const double sigma = target.M.dot(face.n);
            if (sigma == 0.0) continue;
            const double a = face.a, b = face.b;
            const double L = 2.0 * std::max(a, b);
            const double thr = 0.25 * std::max(a, b), skip = 1e-14 * L, mergeTol = 1e-15 * L;

            detail::GradedIntegrator<6> inner;
            inner.weights << 1, 1, 1, 1 / b, 1 / b, 1 / b;
            inner.relTol = relTol / 5;
            inner.absTol = 1e-17 * Hscale * b;
            inner.skip = skip;
            detail::GradedIntegrator<9> outer;
            outer.weights << 1, 1, 1, 1 / a, 1 / a, 1 / a, 1 / b, 1 / b, 1 / b;
            outer.relTol = relTol;
            outer.absTol = 1e-17 * Hscale * a * b;
            outer.skip = skip;

            // J(x) = (int H dy, int y H dy); outer integrand (J0, x J0, J1)
            auto line = [&](double x) {
                const Vec6 J = inner.integrate(
                    [&](double y) {
                        const Eigen::Vector3d H = face.H(x, y);
                        Vec6 v;
                        for (int i = 0; i < 3; ++i) {  // (no comma initializer: GCC 12
                            v[i] = H[i];                // -Warray-bounds false positive)
                            v[i + 3] = y * H[i];
                        }
                        return v;
                    },
                    face.innerBreaks(x, thr, mergeTol));
                Vec9 v;
                for (int i = 0; i < 3; ++i) {
                    v[i] = J[i];
                    v[i + 3] = x * J[i];
                    v[i + 6] = J[i + 3];
                }
                return v;
            };
            const Vec9 I = outer.integrate(line, face.outerBreaks(thr, mergeTol));
            evaluations += inner.evaluations;

            const double scale = mu0 * sigma;
            const Eigen::Vector3d F = scale * I.segment<3>(0);
            const Eigen::Vector3d T = scale * ((face.fc - p).cross(I.segment<3>(0)) +
                                               face.t1.cross(I.segment<3>(3)) +
                                               face.t2.cross(I.segment<3>(6)));
            result.force += F;
            result.torque += T;
            // the weighted norm bounds |dI0| and a|dI1|, b|dI2| by the estimate
            forceError += std::abs(scale) * outer.error;
            torqueError += std::abs(scale) * outer.error * ((face.fc - p).norm() + a + b);
        }
    if (info) {
        info->evaluations = evaluations;
        info->forceError = forceError;
        info->torqueError = torqueError;
    }
    return result;
}

}  // namespace oracle

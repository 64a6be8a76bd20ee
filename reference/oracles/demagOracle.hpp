// Independent test oracle: demagnetizing factors and tensors of uniformly magnetized
// bodies, and volume averages of fields over a polyhedron through its boundary.
//
// Derived from the literature, not from the production code.
//
// Convention (SI). A body of volume V, uniformly magnetized (M in A/m), has the
// demagnetizing field H_d; its volume average is
//     <H_d> = (1/V) int_V H_d dV = -N M,
// with N the magnetometric (volume-averaged) demagnetizing tensor: symmetric, positive
// semi-definite, trace 1 for every body. Along a principal axis N_k = -<H_d,k>/M_k.
// (Only for an ellipsoid is H_d uniform inside, H_d = -N M pointwise.)
//
// (a) Rectangular prism 2a x 2b x 2c (a, b, c HALF edges along x, y, z):
//     Aharoni, J. Appl. Phys. 83 (1998) 3432, Eq. (1):
//       pi D_z = (b^2-c^2)/(2bc) ln[(R-a)/(R+a)] + (a^2-c^2)/(2ac) ln[(R-b)/(R+b)]
//              + b/(2c) ln[(r_ab+a)/(r_ab-a)] + a/(2c) ln[(r_ab+b)/(r_ab-b)]
//              + c/(2a) ln[(r_bc-b)/(r_bc+b)] + c/(2b) ln[(r_ac-a)/(r_ac+a)]
//              + 2 atan[ab/(c R)] + (a^3+b^3-2c^3)/(3abc) + (a^2+b^2-2c^2) R/(3abc)
//              + c/(ab) (r_ac + r_bc) - (r_ab^3 + r_bc^3 + r_ac^3)/(3abc),
//     R = sqrt(a^2+b^2+c^2), r_ab = sqrt(a^2+b^2), r_bc, r_ac alike;
//     D_x = D_z(b, c, a), D_y = D_z(c, a, b) (cyclic: the last argument is the axis).
//     As printed, the terms are of order max/min of the edges and cancel: relative error
//     ~ eps (aspect)^3. Rewritten here (exact identities, checked against Eq. 1 in
//     60-digit arithmetic for every aspect ratio in {1e-6 .. 1e6}^3: <= 5e-16):
//       ln[(R-a)/(R+a)] = -2 asinh(a/r_bc),  ln[(r_ab+a)/(r_ab-a)] = 2 asinh(a/b), ...
//       asinh x - asinh y = asinh(x sqrt(1+y^2) - y sqrt(1+x^2)),
//     so that the log terms pair into
//       (b/c) asinh(a c^2 / (b r_bc (R + r_ab))) + (a/c) asinh(b c^2 / (a r_ac (R + r_ab)))
//       - (c/b) asinh(a b^2 / (c r_bc (R + r_ac))) - (c/a) asinh(b a^2 / (c r_ac (R + r_bc))),
//     the algebraic terms into (abc/3)(2 Z - Y) with
//       Z = [1/(R + r_ac) + 1/(r_bc + c)] / ((r_ac + c)(R + r_bc)),
//       Y = [1/(R + r_ab) + 1/(r_ac + a)] / ((R + r_ac)(r_ab + a))
//         + [1/(R + r_ab) + 1/(r_bc + b)] / ((R + r_bc)(r_ab + b)),
//     plus 2 atan2(ab, cR). Degenerate limits: a zero edge along k gives the plate
//     (N_k = 1, the others 0); two zero edges (a needle whose N depends on the
//     cross-section) give NaN, as do negative or non-finite edges.
//
// (b) Ellipsoid with semi-axes a, b, c (Osborn, Phys. Rev. 67 (1945) 351; Stoner,
//     Phil. Mag. 36 (1945) 803):
//       N_a = (abc/2) int_0^inf ds / ((s + a^2) sqrt((s+a^2)(s+b^2)(s+c^2)))
//           = (abc/3) R_D(b^2, c^2, a^2)                   (Carlson, Numer. Algorithms 10
//                                                          (1995) 13: duplication method)
//     and, for a > b > c, with theta = acos(c/a), k^2 = (a^2-b^2)/(a^2-c^2) and the
//     incomplete elliptic integrals F(k, theta), E(k, theta) (modulus k):
//       N_a = abc / ((a^2-b^2) sqrt(a^2-c^2)) [F - E]
//       N_b = abc sqrt(a^2-c^2) / ((a^2-b^2)(b^2-c^2))
//             [E - (b^2-c^2)/(a^2-c^2) F - c (a^2-b^2) / (a b sqrt(a^2-c^2))]
//       N_c = abc / ((b^2-c^2) sqrt(a^2-c^2)) [b sqrt(a^2-c^2)/(a c) - E].
//     Spheroid (equatorial semi-axis a = b, axial c, m = c/a), along the axis:
//       prolate m > 1: N_c = [m acosh(m)/sqrt(m^2-1) - 1] / (m^2 - 1)
//       oblate  m < 1: N_c = [1 - m acos(m)/sqrt(1-m^2)] / (1 - m^2)
//       (they lose ~eps/|m-1|: <= 2e-14 at |m-1| = 1e-2); for |m-1| < 1e-2 the series
//       1/3 - 4e/15 + 6e^2/35 - 32e^3/315 + 40e^4/693 - 32e^5/1001 + 112e^6/6435, e = m-1;
//       N_a = N_b = (1 - N_c)/2. Sphere: 1/3.
//     Osborn's form loses ~eps/(relative gap) when two axes nearly coincide (the gaps
//     divide; ~5e-14 for 2:3:5); the Carlson route (<= 1e-15 in the tests) does not.
//
// (c) Any closed triangle mesh: the full tensor from a double surface integral.
//     Derivation: uniform M has no volume charge, the surface charge is sigma = M.n, the
//     scalar potential phi(r) = (1/4pi) oint sigma(r') / |r - r'| dA' is continuous,
//     H_d = -grad phi, and the gradient theorem gives
//       int_V H_d dV = -oint phi n dA = -(1/4pi) oint oint n(r) (n(r').M) / |r-r'| dA' dA,
//     i.e. <H_d> = -N M with
//       N_ij = 1/(4 pi V) oint oint n_i(r) n_j(r') / |r - r'| dA dA'.
//     Symmetric by construction. Trace 1: oint n_j(r')/|r-r'| dA' = -d_j Phi(r) with the
//     Newtonian potential Phi = int_V dV'/|r-r'| (grad Phi is continuous), so
//     N_ij = -1/(4 pi V) int_V d_i d_j Phi dV and lap Phi = -4 pi inside V.
//     Rotation: the mesh rotated by R has N' = R N R^T (the pair integrals below are
//     rotation invariant, so the mesh route reproduces it to rounding).
//     For a mesh of flat triangles T, N = 1/(4 pi V) sum_{T,T'} n_T n_T'^T I(T,T'),
//     I(T,T') = int_T int_T' dA dA' / |r - r'| (each unordered pair once: N is exactly
//     symmetric). I is evaluated as follows:
//       - inner integral over T' in closed form: the potential of a uniform triangle
//         (Wilton, Rao, Glisson, Schaubert, Al-Bundak & Butler, IEEE Trans. Antennas
//         Propag. 32 (1984) 276; Graglia, IEEE TAP 41 (1993) 1448):
//           int_T' dA'/|r-r'| = sum_edges t0 [asinh(l+/R0) - asinh(l-/R0)]
//                 - |w| [atan2(t0 l+, R0^2 + |w| R+) - atan2(t0 l-, R0^2 + |w| R-)]
//         w: height of r above the plane, t0: signed in-plane distance from the
//         projection of r to the edge line (> 0 on the inner side), l-, l+: the edge's
//         end coordinates along its direction, R0^2 = t0^2 + w^2, R+- = |r - vertex|;
//         ln[(R+ + l+)/(R- + l-)] is written as the asinh difference (no cancellation
//         on the edge extensions); a term with t0 = 0 vanishes. Continuous everywhere;
//         its gradient is log-singular on the edges.
//       - outer integral over T:
//           pairs sharing a vertex (same triangle, edge or vertex neighbours): Duffy map
//           of T onto the unit square, each coordinate graded by
//           psi(t) = 35t^4 - 84t^5 + 70t^6 - 20t^7 (psi' = 140 t^3 (1-t)^3) and
//           tensor Gauss-Legendre; the integrand's d ln d behaviour at the shared
//           edges/vertices becomes ~t^7 ln t and converges fast;
//           other pairs closer than farRatio (sum of radii): T split into 4 recursively
//           until each piece is >= nearSeparation piece diameters from T', then Duffy
//           Gauss-Legendre nearOrder^2;
//           far pairs: 7-point degree-5 rule (Radon) on both triangles, 1/|r - r'|.
//     Accuracy (DemagQuadrature defaults; tests/test_demagOracle.cpp): the pair
//     integrals of unit squares (same, stacked, perpendicular) equal their closed forms
//     to ~1e-12; 12-triangle boxes equal (a) to ~1e-12 (1e-11 for 1:1:10 and 10:10:1);
//     the graded rule on touching pairs sets this floor (12 / 20 / 30 / 40 points per
//     direction: ~4e-8 / 2e-10 / 1e-12 / 1e-14 on the cube). Cost ~ (triangles)^2:
//     0.02 s for 12 triangles, ~2 s for 320 (fine meshes: cheaper settings, e.g.
//     {12, 4, 0.5, 8, 2}, ~1e-7). Triangles that touch without sharing a vertex index
//     are not recognised as touching (weld them first: all generators here do).
//     A further route, used by the tests: the field itself, H_d(r) = -(1/4 pi) sum_T
//     (M.n_T) grad int_T dA'/|r - r'| (polyhedronDemagField: the solid angle and edge
//     logarithms of Wilton et al.), averaged over the volume by a graded cone quadrature.
//
// (d) Volume average of B = curl A over a closed surface S = dV:
//       int_V curl A dV = oint n x A dA   (n outward),
//     by a surface quadrature (points r_q with area-weighted normals n_q dA_q):
//     triangle meshes (Duffy Gauss-Legendre per triangle) or the exact sphere (Gauss-
//     Legendre in cos theta, trapezoid in phi). Uniform B: A = B x r / 2 gives B V exactly;
//     a point dipole m at r0: A = mu0/(4 pi) m x (r - r0)/|r - r0|^3, whose average over
//     a ball not containing r0 is the centre value (mean value property of the harmonic
//     B). (A triangle rule must integrate linear functions exactly for the first: order
//     >= 2.) A brute-force volume route for comparison: cones from the mesh's vertex
//     centroid with a collapsed (Duffy) tensor Gauss rule (signed, so exact for any
//     closed mesh when the integrand is smooth on every cone; safe for convex bodies).
//
// Reference values. Prisms (full edges): (a), and (c) on the 12-triangle box, which
// agrees to the digits shown (|(c) - (a)| <= 1e-11). Ellipsoids (semi-axes): (b) closed
// forms / Osborn and Carlson's R_D agree to 3e-14. Others: (c), and the volume average of
// the Coulomb field of the surface charge (graded cone quadrature, 24^3 points per cone),
// which agrees to 3e-10.
//   body                            N_x             N_y             N_z
//   cube                            1/3             1/3             1/3
//   prism 1:1:2                     0.4008419236056 0.4008419236056 0.1983161527888
//   prism 1:2:3                     0.5387903059237 0.2783917160359 0.1828179780404
//   prism 1:1:10                    0.4771344038065 0.4771344038065 0.0457311923871
//   prism 10:10:1                   0.0974611831796 0.0974611831796 0.8050776336409
//   prolate spheroid 1:1:2          0.4132180012330 0.4132180012330 0.1735639975340
//   oblate spheroid 1:1:0.5         0.2363998587187 0.2363998587187 0.5272002825626
//   ellipsoid 3:2:1                 0.1563006988293 0.2671540402620 0.5765452609087
//   hexagonal prism, circumradius 1, height 1 (a vertex on +x)
//                                   0.2750744527    0.2750744527    0.4498510946
//   tetrahedron (0,0,0) (1,0.1,0) (0.2,0.8,0.1) (0.3,0.2,1.1): the full tensor
//                                   [ 0.3328491930  0.0418091307  0.0213100736
//                                     0.0418091307  0.4024672902  0.0107464563
//                                     0.0213100736  0.0107464563  0.2646835168 ]
//   1:1:2 prolate icosphere, levels 0..3 (20..1280 triangles): N_z - 0.1735640 =
//                                   1.97e-4, 3.59e-5, 7.11e-6, 1.80e-6 (O(h^2))
// The 1:1:2 prism (0.19832) is not the 1:1:2 prolate spheroid (0.17356).
//
// Units: SI (m, A/m, T). mu0 = 4 pi 1e-7 exactly as a double.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#ifndef ORACLE_CONSTANTS_DEFINED
#define ORACLE_CONSTANTS_DEFINED
namespace oracle {
/// pi as a double (== M_PI).
inline constexpr double pi = 3.141592653589793238462643383279502884;
/// Vacuum permeability, 4 pi 1e-7 exactly as a double (== 4e-7*M_PI).
inline constexpr double mu0 = 4e-7 * pi;
}  // namespace oracle
#endif

namespace oracle {

namespace demagDetail {

/// Gauss-Legendre nodes and weights on [0, 1] (weights sum to 1), n points.
inline void gaussLegendre01(int n, std::vector<double>& x, std::vector<double>& w) {
    x.assign(n, 0.0);
    w.assign(n, 0.0);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double z = std::cos(pi * (i + 0.75) / (n + 0.5));
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
        const double wi = 1.0 / ((1.0 - z * z) * dp * dp);  // = (2/((1-z^2)P'^2)) / 2
        x[i] = 0.5 * (1.0 - z);
        x[n - 1 - i] = 0.5 * (1.0 + z);
        w[i] = w[n - 1 - i] = wi;
    }
}

/// Nodes and weights on [0, 1] (weights sum to 1): n-point Gauss-Legendre, optionally
/// graded toward both ends by psi(t) = 35t^4 - 84t^5 + 70t^6 - 20t^7 (psi'(t) =
/// 140 t^3 (1-t)^3), which turns an endpoint behaviour x ln x or ln x into ~t^7 ln t or
/// ~t^3 ln t, smooth enough for Gauss-Legendre.
inline void rule01(int n, bool graded, std::vector<double>& x, std::vector<double>& w) {
    gaussLegendre01(n, x, w);
    if (!graded) return;
    for (int i = 0; i < n; ++i) {
        const double t = x[i], s = t * (1.0 - t);
        w[i] *= 140.0 * s * s * s;
        x[i] = t * t * t * t * (35.0 + t * (-84.0 + t * (70.0 - 20.0 * t)));
    }
}

/// Carlson's R_F(x, y, z) (duplication, Carlson 1995 Sec. 2), x, y, z >= 0, at most one 0.
inline double carlsonRF(double x, double y, double z) {
    for (int it = 0; it < 100; ++it) {
        const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
        const double lambda = sx * (sy + sz) + sy * sz;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        const double mu = (x + y + z) / 3.0;
        const double dx = 1.0 - x / mu, dy = 1.0 - y / mu, dz = 1.0 - z / mu;
        if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) < 1e-4) {
            const double e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) /
                   std::sqrt(mu);
        }
    }
    return std::numeric_limits<double>::quiet_NaN();
}

/// Carlson's R_D(x, y, z) = (3/2) int_0^inf dt / ((t+z) sqrt((t+x)(t+y)(t+z))),
/// x, y >= 0 (at most one 0), z > 0 (duplication, Carlson 1995 Sec. 2).
inline double carlsonRD(double x, double y, double z) {
    double sum = 0.0, scale = 1.0;
    for (int it = 0; it < 100; ++it) {
        const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
        const double lambda = sx * (sy + sz) + sy * sz;
        sum += scale / (sz * (z + lambda));
        scale *= 0.25;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        const double mu = (x + y + 3.0 * z) / 5.0;
        const double dx = 1.0 - x / mu, dy = 1.0 - y / mu, dz = 1.0 - z / mu;
        if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) < 1e-4) {
            const double ea = dx * dy, eb = dz * dz, ec = ea - eb, ed = ea - 6.0 * eb,
                         ee = ed + ec + ec;
            const double s = ed * (-3.0 / 14.0 + 9.0 / 88.0 * ed - 4.5 / 26.0 * dz * ee) +
                             dz * (ee / 6.0 + dz * (-9.0 / 22.0 * ec + dz * 3.0 / 26.0 * ea));
            return 3.0 * sum + scale * (1.0 + s) / (mu * std::sqrt(mu));
        }
    }
    return std::numeric_limits<double>::quiet_NaN();
}

/// Legendre's incomplete elliptic integrals F(k, phi), E(k, phi) (modulus k, 0 <= phi <=
/// pi/2): the standard library's when it has them (C++17 special functions), else
/// Carlson's forms F = s R_F(c^2, 1 - k^2 s^2, 1), E = F - k^2 s^3 R_D(...)/3.
inline void legendreFE(double k, double phi, double& F, double& E) {
#if defined(__cpp_lib_math_special_functions) || defined(__STDCPP_MATH_SPEC_FUNCS__)
    F = std::ellint_1(k, phi);
    E = std::ellint_2(k, phi);
#else
    const double s = std::sin(phi), c = std::cos(phi), q = 1.0 - k * k * s * s;
    F = s * carlsonRF(c * c, q, 1.0);
    E = F - k * k * s * s * s * carlsonRD(c * c, q, 1.0) / 3.0;
#endif
}

}  // namespace demagDetail

// ------------------------------------------------------------------------------------
// (a) rectangular prism
// ------------------------------------------------------------------------------------

/// Magnetometric demagnetizing factor along z of the prism 2a x 2b x 2c (a, b, c: HALF
/// edges along x, y, z), Aharoni (1998) Eq. 1 in the cancellation-free form above.
/// c == 0 (a plate normal to z): 1; a == 0 or b == 0 (a plate normal to x or y): 0;
/// two zero edges, negative or non-finite edges: NaN.
inline double prismDemagFactorZ(double a, double b, double c) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!(a >= 0.0 && b >= 0.0 && c >= 0.0) || !std::isfinite(a + b + c)) return nan;
    const int zeros = (a == 0.0) + (b == 0.0) + (c == 0.0);
    if (zeros > 1) return nan;
    if (c == 0.0) return 1.0;
    if (a == 0.0 || b == 0.0) return 0.0;
    const double R = std::sqrt(a * a + b * b + c * c);
    const double rab = std::hypot(a, b), rbc = std::hypot(b, c), rac = std::hypot(a, c);
    double s = (b / c) * std::asinh(a * c * c / (b * rbc * (R + rab))) +
               (a / c) * std::asinh(b * c * c / (a * rac * (R + rab))) -
               (c / b) * std::asinh(a * b * b / (c * rbc * (R + rac))) -
               (c / a) * std::asinh(b * a * a / (c * rac * (R + rbc))) +
               2.0 * std::atan2(a * b, c * R);
    const double Z = (1.0 / (R + rac) + 1.0 / (rbc + c)) / ((rac + c) * (R + rbc));
    const double Y = (1.0 / (R + rab) + 1.0 / (rac + a)) / ((R + rac) * (rab + a)) +
                     (1.0 / (R + rab) + 1.0 / (rbc + b)) / ((R + rbc) * (rab + b));
    s += a * b * c / 3.0 * (2.0 * Z - Y);
    return s / pi;
}

/// (N_x, N_y, N_z) of the axis-aligned prism with half edges halfSize (m): sum 1.
inline Eigen::Vector3d prismDemagFactors(const Eigen::Vector3d& halfSize) {
    const double a = halfSize.x(), b = halfSize.y(), c = halfSize.z();
    return {prismDemagFactorZ(b, c, a), prismDemagFactorZ(c, a, b), prismDemagFactorZ(a, b, c)};
}

// ------------------------------------------------------------------------------------
// (b) ellipsoids
// ------------------------------------------------------------------------------------

/// Demagnetizing factor along the symmetry axis of the spheroid with equatorial
/// semi-axis a and axial semi-axis c (closed forms; Taylor series near the sphere).
inline double spheroidDemagFactorAxial(double a, double c) {
    const double m = c / a, e = m - 1.0;
    if (std::abs(e) < 1e-2)
        return 1.0 / 3.0 +
               e * (-4.0 / 15.0 +
                    e * (6.0 / 35.0 +
                         e * (-32.0 / 315.0 +
                              e * (40.0 / 693.0 + e * (-32.0 / 1001.0 + e * 112.0 / 6435.0)))));
    if (m > 1.0) {
        const double q = m * m - 1.0;
        return (m * std::acosh(m) / std::sqrt(q) - 1.0) / q;
    }
    const double q = 1.0 - m * m;
    return (1.0 - m * std::acos(m) / std::sqrt(q)) / q;
}

/// (N_a, N_b, N_c) of the ellipsoid with semi-axes (a, b, c) along x, y, z: Osborn's
/// elliptic-integral forms for three distinct axes, the spheroid closed forms when two
/// are equal, 1/3 for the sphere.
inline Eigen::Vector3d ellipsoidDemagFactors(const Eigen::Vector3d& semiAxes) {
    // sort descending, remember where each went
    std::array<int, 3> idx{0, 1, 2};
    std::sort(idx.begin(), idx.end(), [&](int i, int j) { return semiAxes[i] > semiAxes[j]; });
    const double a = semiAxes[idx[0]], b = semiAxes[idx[1]], c = semiAxes[idx[2]];
    double Na, Nb, Nc;
    if (a == c) {
        Na = Nb = Nc = 1.0 / 3.0;
    } else if (a == b) {  // oblate about the smallest axis c
        Nc = spheroidDemagFactorAxial(a, c);
        Na = Nb = 0.5 * (1.0 - Nc);
    } else if (b == c) {  // prolate about the largest axis a
        Na = spheroidDemagFactorAxial(b, a);
        Nb = Nc = 0.5 * (1.0 - Na);
    } else {
        const double a2 = a * a, b2 = b * b, c2 = c * c, sac = std::sqrt(a2 - c2);
        const double theta = std::acos(c / a), k = std::sqrt((a2 - b2) / (a2 - c2));
        double F, E;
        demagDetail::legendreFE(k, theta, F, E);
        const double abc = a * b * c;
        Na = abc / ((a2 - b2) * sac) * (F - E);
        Nb = abc * sac / ((a2 - b2) * (b2 - c2)) *
             (E - (b2 - c2) / (a2 - c2) * F - c * (a2 - b2) / (a * b * sac));
        Nc = abc / ((b2 - c2) * sac) * (b * sac / (a * c) - E);
    }
    Eigen::Vector3d N;
    N[idx[0]] = Na;
    N[idx[1]] = Nb;
    N[idx[2]] = Nc;
    return N;
}

/// The same by Carlson's symmetric integral: N_a = (abc/3) R_D(b^2, c^2, a^2), any
/// semi-axes > 0.
inline Eigen::Vector3d ellipsoidDemagFactorsCarlson(const Eigen::Vector3d& semiAxes) {
    const double a = semiAxes.x(), b = semiAxes.y(), c = semiAxes.z();
    const double abc3 = a * b * c / 3.0;
    return {abc3 * demagDetail::carlsonRD(b * b, c * c, a * a),
            abc3 * demagDetail::carlsonRD(c * c, a * a, b * b),
            abc3 * demagDetail::carlsonRD(a * a, b * b, c * c)};
}

// ------------------------------------------------------------------------------------
// triangle meshes
// ------------------------------------------------------------------------------------

/// A closed triangle mesh: vertices and triangles (vertex indices, counter-clockwise seen
/// from outside, i.e. (p1-p0)x(p2-p0) points outward). Neighbouring triangles share
/// vertex INDICES (demagTensor relies on it to find touching pairs).
struct TriMesh {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::array<int, 3>> triangles;
};

/// Enclosed volume (m^3), sum of signed tetrahedra (0, p0, p1, p2).
inline double meshVolume(const TriMesh& mesh) {
    double v = 0.0;
    for (const auto& t : mesh.triangles)
        v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
    return v / 6.0;
}

/// Reverses every triangle when the enclosed volume is negative.
inline void orientOutward(TriMesh& mesh) {
    if (meshVolume(mesh) < 0.0)
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
}

/// The mesh mapped by r -> R r + shift.
inline TriMesh transformedMesh(TriMesh mesh, const Eigen::Matrix3d& R,
                               const Eigen::Vector3d& shift = Eigen::Vector3d::Zero()) {
    for (auto& p : mesh.vertices) p = R * p + shift;
    if (R.determinant() < 0.0)
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    return mesh;
}

/// The mesh scaled by (sx, sy, sz) along the axes (e.g. an icosphere to an ellipsoid).
inline TriMesh scaledMesh(const TriMesh& mesh, const Eigen::Vector3d& s) {
    return transformedMesh(mesh, s.asDiagonal().toDenseMatrix());
}

/// Axis-aligned box centred at the origin with half edges halfSize, each face split into
/// a grid of divisions[k1] x divisions[k2] rectangles, two triangles each.
inline TriMesh boxMesh(const Eigen::Vector3d& halfSize,
                       const Eigen::Vector3i& divisions = Eigen::Vector3i(1, 1, 1)) {
    TriMesh mesh;
    std::map<std::array<int, 3>, int> index;  // surface lattice point -> vertex
    auto vertex = [&](std::array<int, 3> ijk) {
        auto it = index.find(ijk);
        if (it != index.end()) return it->second;
        Eigen::Vector3d p;
        for (int k = 0; k < 3; ++k) p[k] = halfSize[k] * (2.0 * ijk[k] / divisions[k] - 1.0);
        mesh.vertices.push_back(p);
        index.emplace(ijk, int(mesh.vertices.size()) - 1);
        return int(mesh.vertices.size()) - 1;
    };
    for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        for (int side = 0; side <= 1; ++side)
            for (int i = 0; i < divisions[k1]; ++i)
                for (int j = 0; j < divisions[k2]; ++j) {
                    auto at = [&](int di, int dj) {
                        std::array<int, 3> ijk{};
                        ijk[k] = side * divisions[k];
                        ijk[k1] = i + di;
                        ijk[k2] = j + dj;
                        return vertex(ijk);
                    };
                    // counter-clockwise in (k1, k2) is outward for the +k face
                    const int v00 = at(0, 0), v10 = at(1, 0), v11 = at(1, 1), v01 = at(0, 1);
                    if (side == 1) {
                        mesh.triangles.push_back({v00, v10, v11});
                        mesh.triangles.push_back({v00, v11, v01});
                    } else {
                        mesh.triangles.push_back({v00, v11, v10});
                        mesh.triangles.push_back({v00, v01, v11});
                    }
                }
    }
    return mesh;
}

/// Icosphere of the given radius: the icosahedron (level 0, 20 triangles) with each
/// triangle split into 4 per level and the new vertices projected onto the sphere
/// (20 * 4^level triangles). Keeps the icosahedral symmetry, so its N is exactly I/3
/// at every level (no symmetric rank-2 tensor other than a multiple of I is invariant
/// under the icosahedral group).
inline TriMesh icosphereMesh(int level, double radius = 1.0) {
    TriMesh mesh;
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    const double raw[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                               {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                               {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (const auto& p : raw)
        mesh.vertices.push_back(Eigen::Vector3d(p[0], p[1], p[2]).normalized());
    mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int i, int j) {
            const auto key = std::minmax(i, j);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            mesh.vertices.push_back((mesh.vertices[i] + mesh.vertices[j]).normalized());
            const int id = int(mesh.vertices.size()) - 1;
            mid.emplace(key, id);
            return id;
        };
        std::vector<std::array<int, 3>> next;
        for (const auto& t : mesh.triangles) {
            const int a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c = midpoint(t[2], t[0]);
            next.push_back({t[0], a, c});
            next.push_back({t[1], b, a});
            next.push_back({t[2], c, b});
            next.push_back({a, b, c});
        }
        mesh.triangles = std::move(next);
    }
    for (auto& p : mesh.vertices) p *= radius;
    orientOutward(mesh);
    return mesh;
}

/// Latitude-longitude sphere: nTheta bands (poles included), nPhi meridians. Not
/// icosahedrally symmetric: N_zz differs from N_xx = N_yy and both approach 1/3.
inline TriMesh uvSphereMesh(int nTheta, int nPhi, double radius = 1.0) {
    TriMesh mesh;
    mesh.vertices.push_back(Eigen::Vector3d(0, 0, radius));  // north pole 0
    for (int i = 1; i < nTheta; ++i) {
        const double th = pi * i / nTheta;
        for (int j = 0; j < nPhi; ++j) {
            const double ph = 2.0 * pi * j / nPhi;
            mesh.vertices.push_back(radius * Eigen::Vector3d(std::sin(th) * std::cos(ph),
                                                             std::sin(th) * std::sin(ph),
                                                             std::cos(th)));
        }
    }
    mesh.vertices.push_back(Eigen::Vector3d(0, 0, -radius));  // south pole
    const int south = int(mesh.vertices.size()) - 1;
    auto ring = [&](int i, int j) { return 1 + (i - 1) * nPhi + (j % nPhi); };
    for (int j = 0; j < nPhi; ++j) {
        mesh.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
        mesh.triangles.push_back({south, ring(nTheta - 1, j + 1), ring(nTheta - 1, j)});
        for (int i = 1; i + 1 < nTheta; ++i) {
            mesh.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            mesh.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
    }
    orientOutward(mesh);
    return mesh;
}

/// Right prism over the regular n-gon of circumradius rho (a vertex on +x) in the
/// xy-plane, z in [-halfHeight, halfHeight]; caps fanned from their centres.
inline TriMesh regularPrismMesh(int n, double rho, double halfHeight) {
    TriMesh mesh;
    for (int s = 0; s < 2; ++s)
        for (int i = 0; i < n; ++i) {
            const double ph = 2.0 * pi * i / n;
            mesh.vertices.push_back(Eigen::Vector3d(rho * std::cos(ph), rho * std::sin(ph),
                                                    s == 0 ? -halfHeight : halfHeight));
        }
    mesh.vertices.push_back(Eigen::Vector3d(0, 0, -halfHeight));
    mesh.vertices.push_back(Eigen::Vector3d(0, 0, halfHeight));
    const int cb = 2 * n, ct = 2 * n + 1;
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        const int b0 = i, b1 = j, t0 = n + i, t1 = n + j;
        mesh.triangles.push_back({b0, b1, t1});
        mesh.triangles.push_back({b0, t1, t0});
        mesh.triangles.push_back({ct, t0, t1});
        mesh.triangles.push_back({cb, b1, b0});
    }
    orientOutward(mesh);
    return mesh;
}

/// The tetrahedron with the four given vertices (outward oriented).
inline TriMesh tetrahedronMesh(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                               const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
    TriMesh mesh;
    mesh.vertices = {p0, p1, p2, p3};
    mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    orientOutward(mesh);
    return mesh;
}

// ------------------------------------------------------------------------------------
// (c) demagnetizing tensor of a closed triangle mesh
// ------------------------------------------------------------------------------------

/// int_T dA' / |r - r'| (m) over the flat triangle (p0, p1, p2), closed form (Wilton et
/// al. 1984): finite and continuous everywhere, in the plane and on the edges too.
inline double trianglePotential(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                const Eigen::Vector3d& p2, const Eigen::Vector3d& r) {
    const Eigen::Vector3d* P[3] = {&p0, &p1, &p2};
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0).normalized();
    const double w = std::abs(n.dot(r - p0));
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d& a = *P[i];
        const Eigen::Vector3d& b = *P[(i + 1) % 3];
        const Eigen::Vector3d l = (b - a).normalized();
        const Eigen::Vector3d u = l.cross(n);  // in-plane, outward from the edge
        const Eigen::Vector3d da = a - r, db = b - r;
        const double t0 = u.dot(da);  // > 0 when r projects to the inner side
        if (t0 == 0.0) continue;
        const double lm = l.dot(da), lp = l.dot(db);
        const double R0sq = t0 * t0 + w * w, R0 = std::sqrt(R0sq);
        sum += t0 * (std::asinh(lp / R0) - std::asinh(lm / R0));
        if (w > 0.0)
            sum -= w * (std::atan2(t0 * lp, R0sq + w * db.norm()) -
                        std::atan2(t0 * lm, R0sq + w * da.norm()));
    }
    return sum;
}

namespace demagDetail {
/// ln[(R+ + l+)/(R- + l-)], R+- = sqrt(R0^2 + l+-^2), l- < l+: the asinh difference,
/// or on the edge line itself (R0 = 0) its limit, finite off the segment, +inf on it.
inline double edgeLog(double R0, double lm, double lp) {
    if (R0 > 0.0) return std::asinh(lp / R0) - std::asinh(lm / R0);
    if (lm > 0.0) return std::log(lp / lm);
    if (lp < 0.0) return std::log(lm / lp);
    return std::numeric_limits<double>::infinity();
}
}  // namespace demagDetail

/// grad_r int_T dA' / |r - r'| (dimensionless) = -int_T (r - r')/|r - r'|^3 dA'
/// (Wilton et al. 1984): Omega n - sum_edges u_i ln[(R+ + l+)/(R- + l-)], with n the
/// triangle's unit normal, u_i the in-plane outward edge normals and Omega the signed
/// solid angle (van Oosterom & Strackee, IEEE Trans. Biomed. Eng. 30 (1983) 125),
/// positive on the -n side. Jumps by 4 pi n across the triangle; where the triple product
/// of the vertex vectors is exactly 0 (in the plane) Omega = 0, the mean of the two
/// sides. Log-singular at the edges: +-inf or NaN ON an edge of any triangle (also on
/// the internal edges of a flat face split into triangles, where the two infinite terms
/// would cancel).
inline Eigen::Vector3d trianglePotentialGradient(const Eigen::Vector3d& p0,
                                                 const Eigen::Vector3d& p1,
                                                 const Eigen::Vector3d& p2,
                                                 const Eigen::Vector3d& r) {
    const Eigen::Vector3d* P[3] = {&p0, &p1, &p2};
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0).normalized();
    const Eigen::Vector3d R1 = p0 - r, R2 = p1 - r, R3 = p2 - r;
    const double r1 = R1.norm(), r2 = R2.norm(), r3 = R3.norm();
    const double num = R1.dot(R2.cross(R3));
    const double den = r1 * r2 * r3 + R1.dot(R2) * r3 + R1.dot(R3) * r2 + R2.dot(R3) * r1;
    // in the plane (num == 0) the mean of the two sides: 0 (atan2(+-0, den < 0) would
    // give one side's +-2 pi inside the triangle)
    Eigen::Vector3d g = (num == 0.0 ? 0.0 : 2.0 * std::atan2(num, den)) * n;
    const double w = std::abs(n.dot(r - p0));
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d& a = *P[i];
        const Eigen::Vector3d& b = *P[(i + 1) % 3];
        const Eigen::Vector3d l = (b - a).normalized();
        const Eigen::Vector3d u = l.cross(n);
        const double t0 = u.dot(a - r);
        g -= demagDetail::edgeLog(std::sqrt(t0 * t0 + w * w), l.dot(a - r), l.dot(b - r)) * u;
    }
    return g;
}

/// Demagnetizing field H_d (A/m) at r of the body of the closed mesh uniformly
/// magnetized with M (A/m): the Coulomb field of the surface charge sigma = M.n,
/// H_d = -(1/4 pi) sum_T (M.n_T) grad P_T(r). On a face, the mean of the two sides;
/// non-finite on any triangle edge (see trianglePotentialGradient).
inline Eigen::Vector3d polyhedronDemagField(const TriMesh& mesh, const Eigen::Vector3d& M,
                                            const Eigen::Vector3d& r) {
    Eigen::Vector3d H = Eigen::Vector3d::Zero();
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d &p0 = mesh.vertices[t[0]], &p1 = mesh.vertices[t[1]],
                              &p2 = mesh.vertices[t[2]];
        const double sigma = M.dot((p1 - p0).cross(p2 - p0).normalized());
        if (sigma != 0.0) H -= sigma * trianglePotentialGradient(p0, p1, p2, r);
    }
    return H / (4.0 * pi);
}

/// Distance (m) from the point r to the triangle (p0, p1, p2) (closest point by regions,
/// Ericson, Real-Time Collision Detection, 2005, Sec. 5.1.5).
inline double pointTriangleDistance(const Eigen::Vector3d& r, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = r - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return ap.norm();
    const Eigen::Vector3d bp = r - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return bp.norm();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return (r - (a + d1 / (d1 - d3) * ab)).norm();
    const Eigen::Vector3d cp = r - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return cp.norm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return (r - (a + d2 / (d2 - d6) * ac)).norm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return (r - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
    const double den = 1.0 / (va + vb + vc);
    return (r - (a + ab * (vb * den) + ac * (vc * den))).norm();
}

/// Quadrature settings of demagTensor (see the header comment, (c)).
struct DemagQuadrature {
    int graded = 30;              ///< graded x graded points on triangles sharing a vertex
    int nearOrder = 6;            ///< nearOrder^2 Duffy Gauss points per accepted piece
    double nearSeparation = 1.0;  ///< piece accepted at >= this many diameters from T'
    int maxDepth = 8;             ///< splitting depth limit (then the graded rule)
    double farRatio = 4.0;        ///< point-point rule when |c - c'| > farRatio (r + r')
};

namespace demagDetail {

/// A rule on the reference triangle in Duffy coordinates: r = p0 + U (p1 - p0) +
/// U V (p2 - p1); int_T f dA = area * sum w_k f(r_k) (the weights sum to 1).
struct TriangleRule {
    std::vector<double> U, V, w;
};

inline TriangleRule duffyRule(int n, bool graded) {
    std::vector<double> x, wx;
    rule01(n, graded, x, wx);
    TriangleRule rule;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            rule.U.push_back(x[i]);
            rule.V.push_back(x[j]);
            rule.w.push_back(2.0 * x[i] * wx[i] * wx[j]);
        }
    return rule;
}

/// The 7-point degree-5 rule (Radon 1948) in barycentric coordinates.
struct RadonRule {
    std::array<std::array<double, 3>, 7> bary;
    std::array<double, 7> w;
    RadonRule() {
        const double s15 = std::sqrt(15.0);
        const double a1 = (6.0 - s15) / 21.0, a2 = (6.0 + s15) / 21.0;
        const double w1 = (155.0 - s15) / 1200.0, w2 = (155.0 + s15) / 1200.0;
        bary[0] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
        w[0] = 9.0 / 40.0;
        bary[1] = {1 - 2 * a1, a1, a1};
        bary[2] = {a1, 1 - 2 * a1, a1};
        bary[3] = {a1, a1, 1 - 2 * a1};
        bary[4] = {1 - 2 * a2, a2, a2};
        bary[5] = {a2, 1 - 2 * a2, a2};
        bary[6] = {a2, a2, 1 - 2 * a2};
        for (int k = 1; k <= 3; ++k) w[k] = w1;
        for (int k = 4; k <= 6; ++k) w[k] = w2;
    }
};

struct Tri {
    std::array<Eigen::Vector3d, 3> p;
    Eigen::Vector3d n, c;
    double area, radius;
};

inline Tri makeTri(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                   const Eigen::Vector3d& p2) {
    Tri t;
    t.p = {p0, p1, p2};
    const Eigen::Vector3d cr = (p1 - p0).cross(p2 - p0);
    t.area = 0.5 * cr.norm();
    t.n = cr.normalized();
    t.c = (p0 + p1 + p2) / 3.0;
    t.radius = std::max({(p0 - t.c).norm(), (p1 - t.c).norm(), (p2 - t.c).norm()});
    return t;
}

/// int_{outer} P_inner dA with the given rule on the outer triangle.
inline double outerIntegral(const std::array<Eigen::Vector3d, 3>& q, double area,
                            const TriangleRule& rule, const Tri& inner) {
    const Eigen::Vector3d e1 = q[1] - q[0], e2 = q[2] - q[1];
    double s = 0.0;
    for (std::size_t k = 0; k < rule.w.size(); ++k) {
        const Eigen::Vector3d r = q[0] + rule.U[k] * (e1 + rule.V[k] * e2);
        s += rule.w[k] * trianglePotential(inner.p[0], inner.p[1], inner.p[2], r);
    }
    return area * s;
}

inline double nearIntegral(const std::array<Eigen::Vector3d, 3>& q, double area, int depth,
                           const Tri& inner, const DemagQuadrature& opt,
                           const TriangleRule& nearRule, const TriangleRule& gradedRule) {
    const Eigen::Vector3d c = (q[0] + q[1] + q[2]) / 3.0;
    const double rad = std::max({(q[0] - c).norm(), (q[1] - c).norm(), (q[2] - c).norm()});
    const double gap = pointTriangleDistance(c, inner.p[0], inner.p[1], inner.p[2]) - rad;
    if (gap >= opt.nearSeparation * 2.0 * rad) return outerIntegral(q, area, nearRule, inner);
    if (depth >= opt.maxDepth) return outerIntegral(q, area, gradedRule, inner);
    const Eigen::Vector3d m01 = 0.5 * (q[0] + q[1]), m12 = 0.5 * (q[1] + q[2]),
                          m20 = 0.5 * (q[2] + q[0]);
    const double a4 = 0.25 * area;
    return nearIntegral({q[0], m01, m20}, a4, depth + 1, inner, opt, nearRule, gradedRule) +
           nearIntegral({m01, q[1], m12}, a4, depth + 1, inner, opt, nearRule, gradedRule) +
           nearIntegral({m20, m12, q[2]}, a4, depth + 1, inner, opt, nearRule, gradedRule) +
           nearIntegral({m01, m12, m20}, a4, depth + 1, inner, opt, nearRule, gradedRule);
}

}  // namespace demagDetail

/// I(T, T') = int_T int_T' dA dA' / |r - r'| (m^3) for the triangles of `mesh` with
/// indices i and j (the scheme of demagTensor).
inline double trianglePairIntegral(const TriMesh& mesh, int i, int j,
                                   const DemagQuadrature& opt = {}) {
    using namespace demagDetail;
    const auto& ti = mesh.triangles[i];
    const auto& tj = mesh.triangles[j];
    const auto& V = mesh.vertices;
    Tri A = makeTri(V[ti[0]], V[ti[1]], V[ti[2]]);
    Tri B = makeTri(V[tj[0]], V[tj[1]], V[tj[2]]);
    bool touching = false;
    for (int a : ti)
        for (int b : tj) touching = touching || a == b;
    if (A.area < B.area) std::swap(A, B);  // the larger is the outer (split) one
    static thread_local int cachedGraded = -1, cachedNear = -1;
    static thread_local TriangleRule gradedRule, nearRule;
    if (cachedGraded != opt.graded) {
        gradedRule = duffyRule(opt.graded, true);
        cachedGraded = opt.graded;
    }
    if (cachedNear != opt.nearOrder) {
        nearRule = duffyRule(opt.nearOrder, false);
        cachedNear = opt.nearOrder;
    }
    if (touching) return outerIntegral(A.p, A.area, gradedRule, B);
    if ((A.c - B.c).norm() > opt.farRatio * (A.radius + B.radius)) {
        static const RadonRule radon;
        double s = 0.0;
        for (int k = 0; k < 7; ++k) {
            const Eigen::Vector3d rk =
                radon.bary[k][0] * A.p[0] + radon.bary[k][1] * A.p[1] + radon.bary[k][2] * A.p[2];
            for (int l = 0; l < 7; ++l) {
                const Eigen::Vector3d rl = radon.bary[l][0] * B.p[0] + radon.bary[l][1] * B.p[1] +
                                           radon.bary[l][2] * B.p[2];
                s += radon.w[k] * radon.w[l] / (rk - rl).norm();
            }
        }
        return A.area * B.area * s;
    }
    return nearIntegral(A.p, A.area, 0, B, opt, nearRule, gradedRule);
}

/// Magnetometric demagnetizing tensor N (dimensionless, <H_d> = -N M) of the body
/// enclosed by the closed, outward-oriented triangle mesh:
/// N = 1/(4 pi V) sum_{T,T'} n_T n_T'^T I(T, T').
inline Eigen::Matrix3d demagTensor(const TriMesh& mesh, const DemagQuadrature& opt = {}) {
    const int nt = int(mesh.triangles.size());
    std::vector<Eigen::Vector3d> normal(nt);
    for (int i = 0; i < nt; ++i) {
        const auto& t = mesh.triangles[i];
        normal[i] = (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                        .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
                        .normalized();
    }
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
    for (int i = 0; i < nt; ++i)
        for (int j = i; j < nt; ++j) {
            const double I = trianglePairIntegral(mesh, i, j, opt);
            const Eigen::Matrix3d nn = normal[i] * normal[j].transpose();
            S += i == j ? Eigen::Matrix3d(I * nn) : Eigen::Matrix3d(I * (nn + nn.transpose()));
        }
    return S / (4.0 * pi * meshVolume(mesh));
}

// ------------------------------------------------------------------------------------
// (d) volume averages through the boundary
// ------------------------------------------------------------------------------------

/// A surface quadrature point: position r (m) and area-weighted outward normal ndA (m^2).
struct SurfacePoint {
    Eigen::Vector3d r, ndA;
};
using SurfaceQuadrature = std::vector<SurfacePoint>;

/// Duffy Gauss-Legendre order x order points on every triangle of the mesh (exact for
/// polynomials of degree 2 order - 2 on each triangle).
inline SurfaceQuadrature meshSurfaceQuadrature(const TriMesh& mesh, int order = 4) {
    const demagDetail::TriangleRule rule = demagDetail::duffyRule(order, false);
    SurfaceQuadrature q;
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d &p0 = mesh.vertices[t[0]], &p1 = mesh.vertices[t[1]],
                              &p2 = mesh.vertices[t[2]];
        const Eigen::Vector3d nA = 0.5 * (p1 - p0).cross(p2 - p0);  // normal * area
        for (std::size_t k = 0; k < rule.w.size(); ++k)
            q.push_back({p0 + rule.U[k] * ((p1 - p0) + rule.V[k] * (p2 - p1)), rule.w[k] * nA});
    }
    return q;
}

/// The exact sphere: nTheta Gauss-Legendre nodes in cos(theta) times nPhi equally spaced
/// azimuths (trapezoid: exact for trigonometric polynomials of degree < nPhi).
inline SurfaceQuadrature sphereSurfaceQuadrature(const Eigen::Vector3d& centre, double radius,
                                                 int nTheta = 24, int nPhi = 48) {
    std::vector<double> x, w;
    demagDetail::gaussLegendre01(nTheta, x, w);
    SurfaceQuadrature q;
    for (int i = 0; i < nTheta; ++i) {
        const double ct = 2.0 * x[i] - 1.0, st = std::sqrt(1.0 - ct * ct);
        for (int j = 0; j < nPhi; ++j) {
            const double ph = 2.0 * pi * (j + 0.5) / nPhi;
            const Eigen::Vector3d n(st * std::cos(ph), st * std::sin(ph), ct);
            // dA = r^2 d(cos theta) dphi: weight 2 w_i * 2 pi / nPhi * r^2
            q.push_back({centre + radius * n, n * (4.0 * pi * w[i] / nPhi * radius * radius)});
        }
    }
    return q;
}

/// int_V curl A dV = oint n x A dA (for B = curl A: int_V B dV), A(r) -> Vector3d.
template <class VectorPotential>
Eigen::Vector3d curlVolumeIntegral(const SurfaceQuadrature& q, VectorPotential&& A) {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    for (const auto& p : q) s += p.ndA.cross(A(p.r));
    return s;
}

/// Volume average (1/V) int_V curl A dV over the body of the mesh, through its boundary.
template <class VectorPotential>
Eigen::Vector3d meshVolumeAverageOfCurl(const TriMesh& mesh, VectorPotential&& A, int order = 4) {
    return curlVolumeIntegral(meshSurfaceQuadrature(mesh, order), A) / meshVolume(mesh);
}

/// A = mu0/(4 pi) m x (r - r0)/|r - r0|^3 (T m), the vector potential of a point dipole
/// m (A m^2) at r0: curl A is its B outside r0.
inline Eigen::Vector3d dipoleVectorPotential(const Eigen::Vector3d& m, const Eigen::Vector3d& r0,
                                             const Eigen::Vector3d& r) {
    const Eigen::Vector3d d = r - r0;
    const double d2 = d.squaredNorm();
    return mu0 / (4.0 * pi) * m.cross(d) / (d2 * std::sqrt(d2));
}

/// Brute-force int_V f dV over the body of the mesh: cones from the vertex centroid o to
/// every triangle, each by a collapsed tensor Gauss-Legendre rule (order^3 points:
/// r = o + s (q(t, u) - o), q the Duffy map of the triangle, dV = 6 V_cone s^2 t ds dt du).
/// The cones are signed, so any closed mesh is exact if f is smooth on every cone
/// (convex bodies: f smooth on the body). graded: every coordinate graded toward both
/// ends (demagDetail::rule01), for f log-singular on the mesh edges (e.g. H_d).
template <class Field>
Eigen::Vector3d meshVolumeIntegral(const TriMesh& mesh, Field&& f, int order = 8,
                                   bool graded = false) {
    std::vector<double> x, w;
    demagDetail::rule01(order, graded, x, w);
    Eigen::Vector3d o = Eigen::Vector3d::Zero();
    for (const auto& p : mesh.vertices) o += p;
    o /= double(mesh.vertices.size());
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d &p0 = mesh.vertices[t[0]], &p1 = mesh.vertices[t[1]],
                              &p2 = mesh.vertices[t[2]];
        const double vol6 = (p0 - o).dot((p1 - p0).cross(p2 - p1));  // 6 x signed volume
        for (int a = 0; a < order; ++a)
            for (int b = 0; b < order; ++b)
                for (int c = 0; c < order; ++c) {
                    const double s = x[a], tt = x[b], u = x[c];
                    const Eigen::Vector3d q = p0 + tt * ((p1 - p0) + u * (p2 - p1));
                    sum += (w[a] * w[b] * w[c] * vol6 * s * s * tt) * f(o + s * (q - o));
                }
    }
    return sum;
}

/// Brute-force int f dV over the box centre + R [-h, h] (h = halfSize): panels^3 cells,
/// order^3 Gauss-Legendre points each (graded: toward the cell faces, as above).
template <class Field>
Eigen::Vector3d boxVolumeIntegral(const Eigen::Vector3d& centre, const Eigen::Vector3d& halfSize,
                                  Field&& f, int panels = 4, int order = 8, bool graded = false,
                                  const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
    std::vector<double> x, w;
    demagDetail::rule01(order, graded, x, w);
    const Eigen::Vector3d cell = 2.0 * halfSize / panels;
    const double cellVolume = cell.prod();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 0; i < panels; ++i)
        for (int j = 0; j < panels; ++j)
            for (int k = 0; k < panels; ++k)
                for (int a = 0; a < order; ++a)
                    for (int b = 0; b < order; ++b)
                        for (int c = 0; c < order; ++c) {
                            const Eigen::Vector3d local(-halfSize.x() + (i + x[a]) * cell.x(),
                                                        -halfSize.y() + (j + x[b]) * cell.y(),
                                                        -halfSize.z() + (k + x[c]) * cell.z());
                            sum += (w[a] * w[b] * w[c] * cellVolume) * f(centre + R * local);
                        }
    return sum;
}

}  // namespace oracle

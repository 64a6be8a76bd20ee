// Independent test oracle: demagnetizing factors of uniformly magnetized prisms and
// ellipsoids.
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
// Reference values: prisms (full edges) by (a), checked against Eq. 1 as printed in
// 40-digit arithmetic; ellipsoids (semi-axes) by (b), the closed forms / Osborn and
// Carlson's R_D agreeing to 3e-14.
//   body                            N_x             N_y             N_z
//   cube                            1/3             1/3             1/3
//   prism 1:1:2                     0.4008419236056 0.4008419236056 0.1983161527888
//   prism 1:2:3                     0.5387903059237 0.2783917160359 0.1828179780404
//   prism 1:1:10                    0.4771344038065 0.4771344038065 0.0457311923871
//   prism 10:10:1                   0.0974611831796 0.0974611831796 0.8050776336409
//   prolate spheroid 1:1:2          0.4132180012330 0.4132180012330 0.1735639975340
//   oblate spheroid 1:1:0.5         0.2363998587187 0.2363998587187 0.5272002825626
//   ellipsoid 3:2:1                 0.1563006988293 0.2671540402620 0.5765452609087
//
// The 1:1:2 prism (0.19832) is not the 1:1:2 prolate spheroid (0.17356).
//
// Units: SI (m, A/m, T). mu0 = 4 pi 1e-7 exactly as a double.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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

}  // namespace oracle

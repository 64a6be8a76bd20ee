// Independent test oracle: closed-form field of a uniformly magnetized cuboid.
//
// Derived from the literature, not from the production code:
//   - surface-charge (Coulombian) model: a uniform M has no volume charge and a
//     surface charge sigma = M . n on the faces (Furlani, "Permanent Magnet and
//     Electromechanical Devices", 2001, Sec. 4.x; Camacho & Sosa, Rev. Mex. Fis. E 59
//     (2013) 8-17; Yang, Supercond. Sci. Technol. 3 (1990) 591).
//   - H of one uniformly charged rectangle  x' in [-a,a], y' in [-b,b], in the plane
//     w = 0, at the point (x, y, w), with u = x' - x, v = y' - y, R = |(u, v, w)|:
//         H = sigma/(4 pi) * int int (r - r') / |r - r'|^3 dx' dy'
//         Hx = sigma/(4 pi) [ ln(v + R) ]_{u,v corners}
//         Hy = sigma/(4 pi) [ ln(u + R) ]_{u,v corners}
//         Hw = sigma/(4 pi) [ atan(u v / (w R)) ]_{u,v corners}
//     where [f]_{corners} = f(u2,v2) - f(u1,v2) - f(u2,v1) + f(u1,v1).
//   - B = mu0 (H + M) inside the body, mu0 H outside.
//
// Numerical care:
//   - each log difference ln(v2 + R2) - ln(v1 + R1) at fixed u is evaluated with log1p of
//     an expression made of same-sign terms only (or as a sum of two asinh when v1 < 0 <
//     v2), so it is accurate to a few ulp, also on the face planes away from the edges
//     and on the extensions of the edge lines;
//   - atan(u v / (w R)) is written sgn(w) * atan2(u v, |w| R): no division by w.
//   The corner sums and the two opposite faces still cancel in the far field: relative
//   error grows like eps * (r/size)^3 (test_oracles.cpp, "cuboid: far field equals the
//   dipole M V": within 1e-8 of the dipole M V at 100 sizes); a few hundred sizes away
//   use the dipole (dipole.hpp).
//
// Values ON the boundary of the cuboid (defined, tested):
//   - on a face plane, inside the face: the normal H contribution of that face is the
//     mean of its two one-sided limits (+-sigma/2 -> 0), so H is the mean of the inside
//     and outside values; cuboidB adds M with weight 1/2 there (1/4 on an edge line,
//     1/8 at a vertex; weight = product over the axes of 1, 1/2, 0), which makes the
//     normal B exact and the tangential B the mean of its two limits.
//   - ON AN EDGE OR A VERTEX of the cuboid the tangential H has a logarithmic
//     singularity: the result is non-finite (+-inf, or NaN where two infinities of
//     opposite sign meet). Points on the extension of an edge line outside the body are
//     finite.
//
// Units: SI (m, A/m, T). mu0 = 4 pi 1e-7 exactly as a double.
#pragma once

#include <Eigen/Dense>
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

/// A uniformly magnetized cuboid.
/// centre:   centre of the box, world frame (m)
/// halfSize: half edge lengths (a, b, h) along the body axes (m)
/// M:        magnetization, WORLD frame (A/m); for remanence Br along direction d:
///           M = Br/mu0 * d
/// R:        rotation body -> world (its columns are the body axes in world
///           coordinates); identity for an axis-aligned box
struct Cuboid {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d halfSize = Eigen::Vector3d::Zero();
    Eigen::Vector3d M = Eigen::Vector3d::Zero();
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};

namespace detail {

/// ln(v2 + R2) - ln(v1 + R1), R_i = sqrt(rho^2 + v_i^2), for v1 < v2, rho >= 0.
/// Accurate to a few ulp; +inf only where the point lies on the segment itself
/// (rho = 0 and v1 <= 0 <= v2).
inline double logDifference(double rho, double v1, double v2) {
    const double R1 = std::hypot(rho, v1);
    const double R2 = std::hypot(rho, v2);
    if (v1 >= 0.0) {
        // ln((v2+R2)/(v1+R1)); v2+R2-v1-R1 = (v2-v1)(1 + (v1+v2)/(R1+R2)), all >= 0
        return std::log1p((v2 - v1) * (1.0 + (v1 + v2) / (R1 + R2)) / (v1 + R1));
    }
    if (v2 <= 0.0) {
        // ln((R1-v1)/(R2-v2)); numerator (v2-v1)(1 - (v1+v2)/(R1+R2)), all >= 0
        return std::log1p((v2 - v1) * (1.0 - (v1 + v2) / (R1 + R2)) / (R2 - v2));
    }
    // v1 < 0 < v2: ln((v2+R2)(R1-v1)/rho^2) = asinh(v2/rho) + asinh(-v1/rho)
    if (rho == 0.0) return std::numeric_limits<double>::infinity();
    return std::asinh(v2 / rho) + std::asinh(-v1 / rho);
}

/// sgn(w) * atan2(y, |w| R): equals atan(y / (w R)) for w != 0; 0 for w == 0 (the
/// mean of the two one-sided limits).
inline double signedAtan(double y, double w, double R) {
    if (w == 0.0) return 0.0;
    const double t = std::atan2(y, std::abs(w) * R);
    return w > 0.0 ? t : -t;
}

/// H (A/m) of the rectangle x' in [-a,a], y' in [-b,b], w' = 0, charge density sigma
/// (A/m), at (x, y, w). Adds (Hx, Hy, Hw).
inline void rectangleSheetH(double sigma, double a, double b, double x, double y,
                            double w, double& Hx, double& Hy, double& Hw) {
    const double u1 = -a - x, u2 = a - x;
    const double v1 = -b - y, v2 = b - y;
    const double k = sigma / (4.0 * pi);
    // Hx: [1/R]_{u1}^{u2} integrated over v -> ln(v+R) differences at u2 minus at u1
    Hx += k * (logDifference(std::hypot(u2, w), v1, v2) -
               logDifference(std::hypot(u1, w), v1, v2));
    // Hy: same with u and v exchanged
    Hy += k * (logDifference(std::hypot(v2, w), u1, u2) -
               logDifference(std::hypot(v1, w), u1, u2));
    // Hw: corner sum of atan(u v / (w R)) (solid angle / 4 pi)
    const double R11 = std::sqrt(u1 * u1 + v1 * v1 + w * w);
    const double R12 = std::sqrt(u1 * u1 + v2 * v2 + w * w);
    const double R21 = std::sqrt(u2 * u2 + v1 * v1 + w * w);
    const double R22 = std::sqrt(u2 * u2 + v2 * v2 + w * w);
    Hw += k * (signedAtan(u2 * v2, w, R22) - signedAtan(u1 * v2, w, R12) -
               signedAtan(u2 * v1, w, R21) + signedAtan(u1 * v1, w, R11));
}

}  // namespace detail

/// Weight of M in B = mu0 (H + weight M): 1 strictly inside, 0 outside, and on the
/// boundary the product over the body axes of (1 inside the slab, 1/2 on its plane).
inline double cuboidInsideWeight(const Cuboid& c, const Eigen::Vector3d& r) {
    const Eigen::Vector3d p = c.R.transpose() * (r - c.centre);
    double weight = 1.0;
    for (int k = 0; k < 3; ++k) {
        const double d = std::abs(p[k]);
        if (d > c.halfSize[k]) return 0.0;
        if (d == c.halfSize[k]) weight *= 0.5;
    }
    return weight;
}

/// H (A/m) of the uniformly magnetized cuboid at r (world frame), from its surface
/// charges; valid inside and outside (inside it is the demagnetizing field). Finite
/// everywhere except on the edges and vertices of the box (see the file comment).
inline Eigen::Vector3d cuboidH(const Cuboid& c, const Eigen::Vector3d& r) {
    const Eigen::Vector3d p = c.R.transpose() * (r - c.centre);
    const Eigen::Vector3d M = c.R.transpose() * c.M;
    Eigen::Vector3d H = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
        if (M[k] == 0.0) continue;
        // faces normal to body axis k: tangential axes k1, k2 (cyclic)
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        for (int s = -1; s <= 1; s += 2) {
            const double sigma = s * M[k];           // sigma = M . n, n = s e_k
            const double w = p[k] - s * c.halfSize[k];  // height above the face plane
            detail::rectangleSheetH(sigma, c.halfSize[k1], c.halfSize[k2], p[k1],
                                    p[k2], w, H[k1], H[k2], H[k]);
        }
    }
    return c.R * H;
}

/// B (T) of the uniformly magnetized cuboid at r: mu0 (H + weight M), weight from
/// cuboidInsideWeight (1 inside, 0 outside, fractions on the boundary).
inline Eigen::Vector3d cuboidB(const Cuboid& c, const Eigen::Vector3d& r) {
    return mu0 * (cuboidH(c, r) + cuboidInsideWeight(c, r) * c.M);
}

}  // namespace oracle

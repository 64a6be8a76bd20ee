// Independent test oracle: Akoun & Yonnet closed-form force between two parallel
// cuboid magnets magnetized along +z (charge / Coulombian model), and the Amperian
// (energy) force obtained from it by adding the overlap-volume term.
//
// Reference: G. Akoun, J.-P. Yonnet, "3D analytical calculation of the forces exerted
// between two cuboidal magnets", IEEE Trans. Magn. 20 (1984) 1962-1964.
// Magnet 1: edges 2a x 2b x 2c, centre c1; magnet 2: edges 2A x 2B x 2C, centre c2;
// (alpha, beta, gamma) = c2 - c1; polarizations J1, J2 (T) along +z (negative J = -z).
//   u_ij = alpha + (-1)^j A - (-1)^i a,  v_kl = beta + (-1)^l B - (-1)^k b,
//   w_pq = gamma + (-1)^q C - (-1)^p c,  r = sqrt(u^2 + v^2 + w^2)
//   F = J1 J2 / (4 pi mu0) sum_{ijklpq} (-1)^(i+j+k+l+p+q) phi(u, v, w, r)
//   phi_x = (v^2-w^2)/2 ln(r-u) + u v ln(r-v) + v w atan(u v/(r w)) + r u/2
//   phi_y = (u^2-w^2)/2 ln(r-v) + u v ln(r-u) + u w atan(u v/(r w)) + r v/2
//   phi_z = -u w ln(r-u) - v w ln(r-v) + u v atan(u v/(r w)) - r w
// F is the force ON MAGNET 2.
//
// Degenerate terms (touching / overlapping / aligned faces and edges):
//   - every ln(r-u) with r-u = 0 (v = w = 0, u >= 0) has a vanishing coefficient, and
//     likewise for ln(r-v): the continuous limit x ln x -> 0 is used (coefficient 0 ->
//     term 0). r - u is formed as (v^2+w^2)/(r+u) for u > 0 (no cancellation).
//   - atan(u v/(r w)) is sgn(w) atan2(u v, r |w|). At w = 0 (a face of magnet 2
//     coplanar with a face of magnet 1, e.g. exactly touching) the charge force jumps;
//     the value returned there is the MEAN of the two one-sided limits (the atan term
//     is taken as 0). This is the same convention as cuboidField.hpp's on-face H, so
//     the charge quadrature of chargeQuadrature.hpp agrees with it also at contact.
//   Overlapping configurations are therefore finite and exact (the charge force is
//   the Coulomb force between the four charged sheets wherever they are).
//
// Amperian (energy) force: F_amp = -grad_{c2} U, U = -int_V2 M2 . B1 dV; it differs
// from the charge force only by the mu0 M1 term of B1 inside magnet 1:
//   F_amp = F_charge + (J1 J2 / mu0) grad_{c2} V_overlap
// (docs/physics.md#overlap-models: two 1 cm cubes, 1 T, coaxial, face gap -0.5 cm: +28.55 N charge,
// -51.03 N Amperian). V_overlap is the product of the three interval overlaps; its
// gradient is taken as the mean of the one-sided derivatives where it has a kink
// (exact contact, equal faces), which makes the Amperian force continuous there.
//
// Units: SI. sizes are FULL edge lengths (m), centres in m, J in tesla, force in N.
#pragma once

#include <Eigen/Dense>
#include <cmath>

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

namespace detail {

/// c * ln(y) with the limit c ln(y) -> 0 where c == 0 (also for y == 0).
inline double xlogy(double c, double y) { return c == 0.0 ? 0.0 : c * std::log(y); }

/// r - u without cancellation (r = |(u, v, w)|).
inline double rMinus(double r, double u, double v, double w) {
    return u > 0.0 ? (v * v + w * w) / (r + u) : r - u;
}

/// Akoun-Yonnet kernel phi(u, v, w) (vector), with the limits described above.
inline Eigen::Vector3d akounYonnetPhi(double u, double v, double w) {
    const double r = std::sqrt(u * u + v * v + w * w);
    const double rmu = rMinus(r, u, v, w);
    const double rmv = rMinus(r, v, u, w);
    // atan(u v / (r w)); mean of the two limits (0) at w == 0
    double at = 0.0;
    if (w != 0.0) {
        at = std::atan2(u * v, r * std::abs(w));
        if (w < 0.0) at = -at;
    }
    Eigen::Vector3d phi;
    phi.x() = xlogy(0.5 * (v * v - w * w), rmu) + xlogy(u * v, rmv) + v * w * at + 0.5 * r * u;
    phi.y() = xlogy(0.5 * (u * u - w * w), rmv) + xlogy(u * v, rmu) + u * w * at + 0.5 * r * v;
    phi.z() = -xlogy(u * w, rmu) - xlogy(v * w, rmv) + u * v * at - r * w;
    return phi;
}

/// Overlap length of [c1-h1, c1+h1] and [c2-h2, c2+h2] and its derivative with
/// respect to c2 (mean of the one-sided derivatives at kinks).
inline void intervalOverlap(double c1, double h1, double c2, double h2, double& length,
                            double& dLength) {
    const double lo1 = c1 - h1, hi1 = c1 + h1, lo2 = c2 - h2, hi2 = c2 + h2;
    const double s = std::fmin(hi1, hi2) - std::fmax(lo1, lo2);
    // d min(hi1, c2+h2)/dc2 and d max(lo1, c2-h2)/dc2
    const double dMin = hi2 < hi1 ? 1.0 : (hi2 > hi1 ? 0.0 : 0.5);
    const double dMax = lo2 > lo1 ? 1.0 : (lo2 < lo1 ? 0.0 : 0.5);
    const double ds = dMin - dMax;
    length = s > 0.0 ? s : 0.0;
    dLength = s > 0.0 ? ds : (s < 0.0 ? 0.0 : 0.5 * ds);
}

}  // namespace detail

namespace detail {

/// The corner sum of Akoun-Yonnet, F = J1 J2 / (4 pi mu0) sum (-1)^(i+...+q) phi(u, v, w),
/// with the kernel phi(u, v, w) given (akounYonnetPhi, or a one-sided variant).
template <class Phi>
Eigen::Vector3d akounYonnetSum(const Eigen::Vector3d& size1, const Eigen::Vector3d& centre1,
                               const Eigen::Vector3d& size2, const Eigen::Vector3d& centre2,
                               double J1, double J2, const Phi& phi) {
    const Eigen::Vector3d h1 = 0.5 * size1, h2 = 0.5 * size2;
    const Eigen::Vector3d d = centre2 - centre1;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            const double u = d.x() + (j ? -h2.x() : h2.x()) - (i ? -h1.x() : h1.x());
            for (int k = 0; k < 2; ++k)
                for (int l = 0; l < 2; ++l) {
                    const double v = d.y() + (l ? -h2.y() : h2.y()) - (k ? -h1.y() : h1.y());
                    for (int p = 0; p < 2; ++p)
                        for (int q = 0; q < 2; ++q) {
                            const double w =
                                d.z() + (q ? -h2.z() : h2.z()) - (p ? -h1.z() : h1.z());
                            const double sign = ((i + j + k + l + p + q) & 1) ? -1.0 : 1.0;
                            sum += sign * phi(u, v, w);
                        }
                }
        }
    return J1 * J2 / (4.0 * pi * mu0) * sum;
}

}  // namespace detail

/// Charge-model (Coulombian) force on magnet 2 (N) from magnet 1, both axis-aligned
/// cuboids polarized along +z: size = full edge lengths (m), centre (m), J (T).
/// Finite for every configuration (separate, touching, overlapping); at exactly
/// coplanar faces the mean of the two one-sided limits.
inline Eigen::Vector3d akounYonnetForce(const Eigen::Vector3d& size1,
                                        const Eigen::Vector3d& centre1,
                                        const Eigen::Vector3d& size2,
                                        const Eigen::Vector3d& centre2, double J1,
                                        double J2) {
    return detail::akounYonnetSum(size1, centre1, size2, centre2, J1, J2,
                                  [](double u, double v, double w) { return detail::akounYonnetPhi(u, v, w); });
}

/// Volume (m^3) of the intersection of two axis-aligned boxes (full sizes, centres).
inline double overlapVolume(const Eigen::Vector3d& size1, const Eigen::Vector3d& centre1,
                            const Eigen::Vector3d& size2, const Eigen::Vector3d& centre2) {
    double V = 1.0;
    for (int k = 0; k < 3; ++k) {
        double L, dL;
        detail::intervalOverlap(centre1[k], 0.5 * size1[k], centre2[k], 0.5 * size2[k], L, dL);
        V *= L;
    }
    return V;
}

/// Gradient (m^2) of overlapVolume with respect to centre2 (mean of the one-sided
/// derivatives where the overlap has a kink).
inline Eigen::Vector3d overlapVolumeGradient(const Eigen::Vector3d& size1,
                                             const Eigen::Vector3d& centre1,
                                             const Eigen::Vector3d& size2,
                                             const Eigen::Vector3d& centre2) {
    double L[3], dL[3];
    for (int k = 0; k < 3; ++k)
        detail::intervalOverlap(centre1[k], 0.5 * size1[k], centre2[k], 0.5 * size2[k], L[k],
                                dL[k]);
    return Eigen::Vector3d(dL[0] * L[1] * L[2], L[0] * dL[1] * L[2], L[0] * L[1] * dL[2]);
}

/// Amperian (energy, F = -grad U with U = -int_V2 M2 . B1 dV) force on magnet 2 (N):
/// akounYonnetForce + (J1 J2 / mu0) grad_{centre2} V_overlap. Equal to the charge
/// force while the boxes do not overlap; continuous through contact.
inline Eigen::Vector3d amperianForceCuboids(const Eigen::Vector3d& size1,
                                            const Eigen::Vector3d& centre1,
                                            const Eigen::Vector3d& size2,
                                            const Eigen::Vector3d& centre2, double J1,
                                            double J2) {
    return akounYonnetForce(size1, centre1, size2, centre2, J1, J2) +
           (J1 * J2 / mu0) * overlapVolumeGradient(size1, centre1, size2, centre2);
}

}  // namespace oracle

// Independent test oracle: point dipoles and uniformly magnetized spheres.
//
//   B(r) = mu0/(4 pi) [3 (m . rh) rh - m] / |r|^3,  r = point - dipole position
//   Force on dipole m (at x) from dipole m_s (at x_s), r = x - x_s (paper Eq. 5
//   corrected, docs/physics.md#dipoles-and-edm; F = grad(m . B_s)):
//     F = 3 mu0/(4 pi |r|^5) [ (m.r) m_s + (m_s.r) m + (m.m_s) r - 5 (m.r)(m_s.r) r/|r|^2 ]
//   Torque on m about its own position: T = m x B_s(x) (paper Eq. 6). The pair
//   conserves angular momentum: T + T_s + x x F + x_s x F_s = 0 (F_s = -F).
//   Uniformly magnetized sphere (radius a, magnetization M): outside exactly the dipole
//   m = (4/3) pi a^3 M at its centre; inside B = (2/3) mu0 M, H = -M/3. On the surface
//   (|r - c| == a exactly) the mean of the two one-sided limits is returned.
//   Two non-overlapping uniformly magnetized spheres interact exactly as two dipoles.
//
// Units: SI (m, A m^2, A/m, T, N, N m). The point-dipole field is infinite at the
// dipole itself (r = 0: returns non-finite values).
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

/// B (T) at point r of a point dipole of moment m (A m^2) located at position.
inline Eigen::Vector3d dipoleB(const Eigen::Vector3d& m, const Eigen::Vector3d& position,
                               const Eigen::Vector3d& r) {
    const Eigen::Vector3d d = r - position;
    const double d2 = d.squaredNorm();
    const double d1 = std::sqrt(d2);
    return mu0 / (4.0 * pi) * (3.0 * m.dot(d) * d / d2 - m) / (d2 * d1);
}

/// Force (N) on the dipole m at position from the dipole mSource at sourcePosition
/// (corrected paper Eq. 5). The force on the source is the negative of this.
inline Eigen::Vector3d dipoleForce(const Eigen::Vector3d& m, const Eigen::Vector3d& position,
                                   const Eigen::Vector3d& mSource,
                                   const Eigen::Vector3d& sourcePosition) {
    const Eigen::Vector3d r = position - sourcePosition;
    const double r2 = r.squaredNorm();
    const double r5 = r2 * r2 * std::sqrt(r2);
    const double mr = m.dot(r), msr = mSource.dot(r);
    return 3.0 * mu0 / (4.0 * pi * r5) *
           (mr * mSource + msr * m + m.dot(mSource) * r - 5.0 * mr * msr * r / r2);
}

/// Torque (N m) on the dipole m at position, about position, from the dipole mSource at
/// sourcePosition: m x B_source(position) (paper Eq. 6).
inline Eigen::Vector3d dipoleTorque(const Eigen::Vector3d& m, const Eigen::Vector3d& position,
                                    const Eigen::Vector3d& mSource,
                                    const Eigen::Vector3d& sourcePosition) {
    return m.cross(dipoleB(mSource, sourcePosition, position));
}

/// Dipole moment (A m^2) of a uniformly magnetized sphere: (4/3) pi a^3 M.
inline Eigen::Vector3d sphereMoment(double radius, const Eigen::Vector3d& M) {
    return (4.0 / 3.0) * pi * radius * radius * radius * M;
}

/// B (T) of a uniformly magnetized sphere (centre, radius, magnetization M in A/m):
/// dipole field outside, (2/3) mu0 M inside, mean of both on the surface.
inline Eigen::Vector3d sphereB(const Eigen::Vector3d& centre, double radius,
                               const Eigen::Vector3d& M, const Eigen::Vector3d& r) {
    const double d = (r - centre).norm();
    const Eigen::Vector3d inside = (2.0 / 3.0) * mu0 * M;
    if (d < radius) return inside;
    const Eigen::Vector3d outside = dipoleB(sphereMoment(radius, M), centre, r);
    if (d > radius) return outside;
    return 0.5 * (inside + outside);
}

/// H (A/m) of a uniformly magnetized sphere: B/mu0 outside, -M/3 inside (the
/// demagnetizing field), mean of both on the surface.
inline Eigen::Vector3d sphereH(const Eigen::Vector3d& centre, double radius,
                               const Eigen::Vector3d& M, const Eigen::Vector3d& r) {
    const double d = (r - centre).norm();
    const Eigen::Vector3d inside = -M / 3.0;
    if (d < radius) return inside;
    const Eigen::Vector3d outside = dipoleB(sphereMoment(radius, M), centre, r) / mu0;
    if (d > radius) return outside;
    return 0.5 * (inside + outside);
}

}  // namespace oracle

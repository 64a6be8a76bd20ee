// Independent test oracle: brute-force force and torque on a uniformly magnetized
// cuboid (the TARGET, axis-aligned or rotated) in the field of another uniformly
// magnetized cuboid (the SOURCE), in the surface-charge (Coulombian) model.
//
// The target's magnetization M2 is uniform, so its only magnetic charge is the
// surface charge sigma = M2 . n on its six faces. In the charge model a magnetic charge
// q in the field H feels mu0 q H, so
//   F = int_{dV2} sigma mu0 H1 dA
//   T(about p) = int_{dV2} (r - p) x sigma mu0 H1 dA            (COMPLETE; see below)
// with H1 the source's H (cuboidH, closed form, inside the source too).
//
// Why there is NO extra volume term  int_V mu0 M2 x H1 dV  in the torque:
// build the body from point dipoles m = M2 dV. In the charge model each dipole (a +-q
// pair) feels the force mu0 (m . grad) H1 and, about its own centre, the couple
// m x mu0 H1, so T = int_V [(r-p) x mu0 (M2 . grad) H1 + mu0 M2 x H1] dV. With M2
// uniform, (r-p) x (M2 . grad) H1 = d_j[M2_j (r-p) x H1] - M2 x H1, and the divergence
// theorem turns the first term into int_{dV2} (M2 . n)(r-p) x H1 dA: the volume couple
// cancels exactly and the whole torque is that of the surface charges alone. (Check: in
// a uniform H0, int (M.n) r dA = M V gives T = m x mu0 H0, the dipole torque; adding the
// volume term again would double it.) The tests confirm it against -dU/dtheta with
// U = -mu0 int_V2 M2 . H1 dV (chargeInteractionEnergy).
// Outside the source mu0 H1 = B1, so this is also the Amperian force and torque while the
// bodies do not overlap; in overlap it is the charge model (what Akoun-Yonnet gives).
//
// Quadrature: each face is split into panels x panels equal rectangles, each with an
// order x order tensor Gauss-Legendre rule. The integrand is smooth on the target's faces
// unless the source's edges come close (gap g): use panels of size <~ g; then the
// convergence is spectral (two 1 cm cubes, 0.5 mm gap: 20 panels x 8 points agree with
// Akoun-Yonnet to 1e-11).
// Exact contact (a target face in a source face plane): the on-face H is the mean of its
// one-sided limits (cuboidField.hpp), so the result converges to the mean of the two
// one-sided forces, like akounYonnet.hpp - but only at FIRST order in the panel size,
// because the tangential H is log-singular along the source edges lying in that plane
// (1 cm cubes touching with a lateral offset (3, 1) mm: relative error 2e-3 / 1e-3 /
// 5e-4 / 2.5e-4 with 10 / 20 / 40 / 80 panels when the source edges fall on panel
// boundaries, several times worse when they do not). A Gauss point exactly on a source
// edge would give a non-finite result (practically never: the nodes are interior and
// irrational).
//
// Units: SI (m, A/m, N, N m).
#pragma once

#include <Eigen/Dense>
#include <cmath>

#include "cuboidField.hpp"

namespace oracle {

/// Force (N) and torque (N m, about the point given to the function) on a body.
struct Wrench {
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};

namespace detail {

/// Gauss-Legendre nodes x and weights w on [-1, 1], n points (Newton on P_n).
inline void gaussLegendre(int n, Eigen::VectorXd& x, Eigen::VectorXd& w) {
    x.resize(n);
    w.resize(n);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double z = std::cos(pi * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            // P_n(z) by the three-term recurrence, P_n'(z) from P_n and P_{n-1}
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
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
}

}  // namespace detail

/// Charge-model force and torque (about point p) on the cuboid `target` in the field of
/// the cuboid `source`, by tensor Gauss-Legendre quadrature of the target's surface
/// charge: `panels` x `panels` panels per face, `order` x `order` points per panel.
inline Wrench chargeQuadratureWrench(const Cuboid& source, const Cuboid& target,
                                     const Eigen::Vector3d& p, int panels = 8,
                                     int order = 8) {
    Eigen::VectorXd gx, gw;
    detail::gaussLegendre(order, gx, gw);
    Wrench result;
    for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        const Eigen::Vector3d t1 = target.R.col(k1), t2 = target.R.col(k2);
        const double a = target.halfSize[k1], b = target.halfSize[k2];
        const double da = 2.0 * a / panels, db = 2.0 * b / panels;
        for (int s = -1; s <= 1; s += 2) {
            // face with outward normal n = s * (body axis k)
            const Eigen::Vector3d n = s * target.R.col(k);
            const double sigma = target.M.dot(n);
            if (sigma == 0.0) continue;
            const Eigen::Vector3d faceCentre = target.centre + target.halfSize[k] * n;
            Eigen::Vector3d F = Eigen::Vector3d::Zero(), T = Eigen::Vector3d::Zero();
            for (int i = 0; i < panels; ++i)
                for (int j = 0; j < panels; ++j) {
                    const double xc = -a + (i + 0.5) * da, yc = -b + (j + 0.5) * db;
                    for (int qi = 0; qi < order; ++qi)
                        for (int qj = 0; qj < order; ++qj) {
                            const Eigen::Vector3d r = faceCentre +
                                                      (xc + 0.5 * da * gx[qi]) * t1 +
                                                      (yc + 0.5 * db * gx[qj]) * t2;
                            const double weight = gw[qi] * gw[qj] * 0.25 * da * db;
                            const Eigen::Vector3d dF = weight * cuboidH(source, r);
                            F += dF;
                            T += (r - p).cross(dF);
                        }
                }
            result.force += mu0 * sigma * F;
            result.torque += mu0 * sigma * T;
        }
    }
    return result;
}

/// Charge-model interaction energy (J) of the target in the source's field,
/// U = -mu0 int_V2 M2 . H1 dV, by tensor Gauss-Legendre quadrature over the target's
/// volume (panels^3 cells, order^3 points each). F = -grad U and T = -dU/dtheta for
/// rigid motions of the target (M2 attached to the body). Intended for separated
/// bodies (H1 is smooth in V2 there).
inline double chargeInteractionEnergy(const Cuboid& source, const Cuboid& target,
                                      int panels = 4, int order = 8) {
    Eigen::VectorXd gx, gw;
    detail::gaussLegendre(order, gx, gw);
    const Eigen::Vector3d cell = 2.0 * target.halfSize / panels;
    const double cellWeight = cell.prod() / 8.0;
    double sum = 0.0;
    for (int i = 0; i < panels; ++i)
        for (int j = 0; j < panels; ++j)
            for (int l = 0; l < panels; ++l)
                for (int qi = 0; qi < order; ++qi)
                    for (int qj = 0; qj < order; ++qj)
                        for (int ql = 0; ql < order; ++ql) {
                            const Eigen::Vector3d local(
                                -target.halfSize.x() + (i + 0.5 + 0.5 * gx[qi]) * cell.x(),
                                -target.halfSize.y() + (j + 0.5 + 0.5 * gx[qj]) * cell.y(),
                                -target.halfSize.z() + (l + 0.5 + 0.5 * gx[ql]) * cell.z());
                            const Eigen::Vector3d r = target.centre + target.R * local;
                            sum += gw[qi] * gw[qj] * gw[ql] * cellWeight *
                                   target.M.dot(cuboidH(source, r));
                        }
    return -mu0 * sum;
}

}  // namespace oracle

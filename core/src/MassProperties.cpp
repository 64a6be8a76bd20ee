// Polyhedral mass properties by the divergence theorem (Eberly 2002).
#include <magFoam/MassProperties.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

namespace mag {

namespace {

// Integrals over the solid of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx, with
// coordinates taken relative to 'origin'.
std::array<double, 10> volumeIntegrals(const SurfaceMesh& mesh, const Vec3& origin) {
    // Eberly's subexpressions: for one coordinate w of the three corners,
    // f1 = sum w_i, f2 = sum_{i<=j} w_i w_j, f3 = sum_{i<=j<=k} w_i w_j w_k, and
    // g_i = f2 + w_i (f1 + w_i); these integrate the monomials over a triangle.
    struct Sub {
        double f1, f2, f3, g0, g1, g2;
    };
    auto sub = [](double w0, double w1, double w2) {
        const double t0 = w0 + w1;
        const double f1 = t0 + w2;
        const double t1 = w0 * w0;
        const double t2 = t1 + w1 * t0;
        const double f2 = t2 + w2 * f1;
        const double f3 = w0 * t1 + w1 * t2 + w2 * f2;
        return Sub{f1, f2, f3, f2 + w0 * (f1 + w0), f2 + w1 * (f1 + w1), f2 + w2 * (f1 + w2)};
    };

    std::array<meshDetail::CompensatedSum, 10> sums;
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        const Vec3 p0 = mesh.corner(t, 0) - origin;
        const Vec3 p1 = mesh.corner(t, 1) - origin;
        const Vec3 p2 = mesh.corner(t, 2) - origin;
        // d = (p1 - p0) x (p2 - p0): twice the area vector.
        const Vec3 d = (p1 - p0).cross(p2 - p0);
        const Sub x = sub(p0.x(), p1.x(), p2.x());
        const Sub y = sub(p0.y(), p1.y(), p2.y());
        const Sub z = sub(p0.z(), p1.z(), p2.z());
        sums[0].add(d.x() * x.f1);
        sums[1].add(d.x() * x.f2);
        sums[2].add(d.y() * y.f2);
        sums[3].add(d.z() * z.f2);
        sums[4].add(d.x() * x.f3);
        sums[5].add(d.y() * y.f3);
        sums[6].add(d.z() * z.f3);
        sums[7].add(d.x() * (p0.y() * x.g0 + p1.y() * x.g1 + p2.y() * x.g2));
        sums[8].add(d.y() * (p0.z() * y.g0 + p1.z() * y.g1 + p2.z() * y.g2));
        sums[9].add(d.z() * (p0.x() * z.g0 + p1.x() * z.g1 + p2.x() * z.g2));
    }
    constexpr std::array<double, 10> factor{1.0 / 6,   1.0 / 24,  1.0 / 24,  1.0 / 24,
                                            1.0 / 60,  1.0 / 60,  1.0 / 60,  1.0 / 120,
                                            1.0 / 120, 1.0 / 120};
    std::array<double, 10> integrals;
    for (int i = 0; i < 10; ++i) integrals[i] = sums[i].value() * factor[i];
    return integrals;
}

} // namespace

double signedVolume(const SurfaceMesh& mesh) {
    requireValidIndices(mesh);
    return volumeIntegrals(mesh, boundingBox(mesh).centre())[0];
}

MassProperties computeMassProperties(const SurfaceMesh& mesh, double density) {
    requireValidIndices(mesh);
    if (!std::isfinite(density) || density <= 0.0)
        throw InputError(mesh.source + ": density " + meshDetail::formatNumber(density) +
                         " is not allowed, expected a finite number > 0");

    // Integrate about the box centre, near the centre of mass, so the parallel-axis
    // shift below subtracts small numbers from small numbers.
    const BoundingBox box = boundingBox(mesh);
    const Vec3 origin = box.centre();
    const auto in = volumeIntegrals(mesh, origin);
    const double volume = in[0];
    // Same zero-volume threshold as checkTopology: below it the centre of mass
    // would be rounding noise divided by rounding noise.
    const double diagonal = box.diagonal();
    if (!(volume > 1e-3 * meshRelativeTolerance * diagonal * diagonal * diagonal))
        throw InputError(mesh.source + ": enclosed volume is " + meshDetail::formatNumber(volume) +
                         ", expected a closed, outward oriented surface with positive volume "
                         "(run magCheckMesh on it)");

    MassProperties mp;
    mp.density = density;
    mp.volume = volume;
    mp.mass = density * volume;
    const Vec3 c(in[1] / volume, in[2] / volume, in[3] / volume);  // relative to origin
    mp.centreOfMass = origin + c;

    // Second moments about the centre of mass, then I = tr(S) 1 - S.
    Mat3 S;
    S(0, 0) = in[4] - volume * c.x() * c.x();
    S(1, 1) = in[5] - volume * c.y() * c.y();
    S(2, 2) = in[6] - volume * c.z() * c.z();
    S(0, 1) = S(1, 0) = in[7] - volume * c.x() * c.y();
    S(1, 2) = S(2, 1) = in[8] - volume * c.y() * c.z();
    S(0, 2) = S(2, 0) = in[9] - volume * c.z() * c.x();
    mp.inertia = density * (S.trace() * Mat3::Identity() - S);

    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(mp.inertia);
    mp.principalMoments = eigen.eigenvalues();
    mp.principalAxes = eigen.eigenvectors();
    if (mp.principalAxes.determinant() < 0.0) mp.principalAxes.col(2) *= -1.0;

    mp.boundingRadius = boundingSphereRadius(mesh, mp.centreOfMass);
    return mp;
}

double boundingSphereRadius(const SurfaceMesh& mesh, const Vec3& centre) {
    double radius = 0.0;
    for (const Vec3& p : mesh.vertices) radius = std::max(radius, (p - centre).norm());
    return radius;
}

Mat3 inertiaAbout(const MassProperties& mp, const Vec3& point) {
    const Vec3 d = point - mp.centreOfMass;
    return mp.inertia + mp.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

Vec3 recentre(SurfaceMesh& mesh) {
    const Vec3 centre = computeMassProperties(mesh).centreOfMass;
    translate(mesh, -centre);
    return centre;
}

} // namespace mag

// Tests of reference/oracles/demagOracle.hpp: the prism (Aharoni 1998) and ellipsoid
// (Osborn 1945, Carlson's R_D) demagnetizing factors, the demagnetizing tensor of a
// triangle mesh from the double surface integral, the Coulomb field of a uniformly
// magnetized polyhedron, and volume averages through the boundary; each against an
// independent route (closed forms, brute-force volume quadrature, symmetry, values
// evaluated in 40-digit arithmetic).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "oracles/cuboidField.hpp"
#include "oracles/demagOracle.hpp"
#include "oracles/dipole.hpp"

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::Vector3i;
using oracle::DemagQuadrature;
using oracle::pi;
using oracle::TriMesh;

namespace {

double maxAbs(const Matrix3d& A) { return A.cwiseAbs().maxCoeff(); }
double maxOffDiagonal(const Matrix3d& N) {
    return std::max({std::abs(N(0, 1)), std::abs(N(0, 2)), std::abs(N(1, 2)), std::abs(N(1, 0)),
                     std::abs(N(2, 0)), std::abs(N(2, 1))});
}
Matrix3d rotation(double angle, const Vector3d& axis) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// Fine meshes (hundreds of triangles): cheaper settings, ~1e-7 on N (trace - 1; prolate
// icosphere level 2: 3e-8 from the default settings), far below the O(h^2) mesh errors
// they measure.
const DemagQuadrature kFast{12, 4, 0.5, 8, 2.0};

// N from the volume average of the Coulomb field of the surface charge (an independent
// route: point field, then a graded cone quadrature of the body's volume).
Matrix3d demagTensorFromField(const TriMesh& mesh, int order) {
    Matrix3d N;
    for (int j = 0; j < 3; ++j) {
        const Vector3d M = Vector3d::Unit(j);
        N.col(j) =
            -oracle::meshVolumeIntegral(
                mesh, [&](const Vector3d& r) { return oracle::polyhedronDemagField(mesh, M, r); },
                order, true) /
            oracle::meshVolume(mesh);
    }
    return N;
}

}  // namespace

TEST_CASE("prism: Aharoni Eq. 1 against 40-digit values, sum rule, limits", "[oracle][demag]") {
    // D_z(a, b, c) of Eq. 1 exactly as printed, evaluated with 40-digit arithmetic
    // (mpmath); the oracle uses the regrouped, cancellation-free form.
    struct Case {
        double a, b, c, Dz;
    };
    const Case cases[] = {
        {1, 1, 1, 0.33333333333333333},      {0.5, 0.5, 1, 0.19831615278883806},
        {0.5, 1, 1.5, 0.182817978040393},    {0.5, 0.5, 5, 0.045731192387095326},
        {5, 5, 0.5, 0.80507763364088073},    {1, 1, 1e-4, 0.99936743162104116},
        {1, 1, 1e4, 4.7318508891505589e-5},  {1e-3, 1, 2, 0.0012503358606326835},
        {2, 1e-3, 1, 0.0025364888895829514},
    };
    for (const auto& k : cases) {
        INFO(k.a << " " << k.b << " " << k.c);
        CHECK(std::abs(oracle::prismDemagFactorZ(k.a, k.b, k.c) / k.Dz - 1) < 2e-15);
    }
    // the sum rule and the cyclic permutations, over 12 decades of aspect ratio
    const double sizes[] = {1e-6, 1e-3, 0.1, 0.5, 1, 2, 7, 1e3, 1e6};
    double worst = 0;
    for (double a : sizes)
        for (double b : sizes)
            for (double c : sizes) {
                const Vector3d N = oracle::prismDemagFactors(Vector3d(a, b, c));
                worst = std::max(worst, std::abs(N.sum() - 1));
                CHECK(N.minCoeff() > 0);
                CHECK(N[2] == oracle::prismDemagFactorZ(a, b, c));
                CHECK(oracle::prismDemagFactors(Vector3d(b, c, a))[1] == N[2]);
                CHECK(std::abs(oracle::prismDemagFactorZ(b, a, c) - N[2]) < 1e-15);
            }
    CHECK(worst < 2e-15);
    // cube; thin plate -> 1, long rod -> 0 (square section: the others 1/2)
    CHECK(
        oracle::prismDemagFactors(Vector3d(3, 3, 3)).isApprox(Vector3d::Constant(1.0 / 3), 1e-15));
    CHECK(oracle::prismDemagFactorZ(1, 1, 1e-12) == Approx(1).epsilon(1e-10));
    CHECK(oracle::prismDemagFactorZ(1, 1, 1e12) < 1e-11);
    CHECK(oracle::prismDemagFactorZ(1, 1e12, 1) == Approx(0.5).epsilon(1e-10));
    // degenerate arguments
    CHECK(oracle::prismDemagFactorZ(1, 2, 0) == 1);
    CHECK(oracle::prismDemagFactorZ(0, 2, 1) == 0);
    CHECK(oracle::prismDemagFactors(Vector3d(1, 2, 0)) == Vector3d(0, 0, 1));
    CHECK(std::isnan(oracle::prismDemagFactorZ(0, 0, 1)));
    CHECK(std::isnan(oracle::prismDemagFactorZ(-1, 1, 1)));
    CHECK(std::isnan(oracle::prismDemagFactorZ(1, std::numeric_limits<double>::infinity(), 1)));
}

TEST_CASE("ellipsoid: Osborn's elliptic integrals, Carlson's R_D, spheroid closed forms",
          "[oracle][demag]") {
    // N_k = (abc/3) R_D(...) evaluated with 40-digit arithmetic (mpmath.elliprd), which
    // also equals Osborn's integral by direct 40-digit quadrature for (3, 2, 1).
    struct Case {
        Vector3d axes, N;
    };
    const Case cases[] = {
        {{3, 2, 1}, {0.15630069882927098, 0.26715404026200452, 0.5765452609087245}},
        {{2, 3, 5}, {0.50859897938963001, 0.32399993715225599, 0.167401083458114}},
        {{1, 1, 2}, {0.41321800123301788, 0.41321800123301788, 0.17356399753396423}},
        {{1, 1, 0.5}, {0.23639985871871508, 0.23639985871871508, 0.52720028256256984}},
        {{1, 1, 10}, {0.48985705984921809, 0.48985705984921809, 0.020285880301563824}},
        {{1, 1, 0.1}, {0.069597861736099741, 0.069597861736099741, 0.86080427652780052}},
        {{1, 1, 1.001}, {0.33346658100314574, 0.33346658100314574, 0.33306683799370851}},
    };
    for (const auto& k : cases) {
        INFO(k.axes.transpose());
        const Vector3d carlson = oracle::ellipsoidDemagFactorsCarlson(k.axes);
        const Vector3d closed = oracle::ellipsoidDemagFactors(k.axes);
        CHECK((carlson - k.N).cwiseAbs().maxCoeff() < 1e-15);
        // Osborn's form divides by the axis gaps: up to 5e-14 for these shapes
        CHECK((closed - k.N).cwiseAbs().maxCoeff() < 1e-13);
        CHECK(std::abs(closed.sum() - 1) < 1e-13);
        CHECK(std::abs(carlson.sum() - 1) < 5e-15);
        // any order of the axes
        const Vector3d perm(k.axes[2], k.axes[0], k.axes[1]);
        CHECK((oracle::ellipsoidDemagFactors(perm) - Vector3d(closed[2], closed[0], closed[1]))
                  .norm() == 0);
    }
    CHECK(oracle::ellipsoidDemagFactors(Vector3d(2, 2, 2)) == Vector3d::Constant(1.0 / 3));
    CHECK((oracle::ellipsoidDemagFactorsCarlson(Vector3d(2, 2, 2)) - Vector3d::Constant(1.0 / 3))
              .norm() < 1e-15);
    // the spheroid series (|m - 1| < 1e-2) and the closed forms (which lose ~eps/|m - 1|)
    // join, and equal R_D
    for (double m : {0.98, 0.9899, 0.9901, 0.999999, 1.000001, 1.0099, 1.0101, 1.02}) {
        INFO(m);
        const double Nc = oracle::spheroidDemagFactorAxial(1, m);
        CHECK(std::abs(Nc - oracle::ellipsoidDemagFactorsCarlson(Vector3d(1, 1, m))[2]) < 3e-14);
    }
    // prolate 1:1:2 is the 0.1736 often quoted; a 1:1:2 prism is 0.1983
    CHECK(oracle::spheroidDemagFactorAxial(1, 2) == Approx(0.1735639975).epsilon(1e-9));
}

TEST_CASE("triangle potential and its gradient", "[oracle][demag]") {
    // uniformly charged square [-1,1]^2 at its centre: 8 asinh(1)
    const Vector3d a(-1, -1, 0), b(1, -1, 0), c(1, 1, 0), d(-1, 1, 0);
    auto square = [&](const Vector3d& r) {
        return oracle::trianglePotential(a, b, c, r) + oracle::trianglePotential(a, c, d, r);
    };
    CHECK(square(Vector3d::Zero()) == Approx(8 * std::asinh(1.0)).epsilon(1e-15));
    // symmetric in the height, continuous across the plane, monopole far away
    const Vector3d p0(0.1, -0.3, 0.2), p1(1.2, 0.1, -0.1), p2(0.3, 0.9, 0.4);
    const Vector3d n = (p1 - p0).cross(p2 - p0).normalized(), ctr = (p0 + p1 + p2) / 3;
    const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    const Vector3d inPlane = 0.5 * ctr + 0.25 * p0 + 0.25 * p2;  // inside the triangle
    CHECK(oracle::trianglePotential(p0, p1, p2, inPlane + 0.3 * n) ==
          Approx(oracle::trianglePotential(p0, p1, p2, inPlane - 0.3 * n)).epsilon(1e-14));
    CHECK(oracle::trianglePotential(p0, p1, p2, inPlane + 1e-9 * n) ==
          Approx(oracle::trianglePotential(p0, p1, p2, inPlane)).epsilon(1e-8));
    CHECK(std::isfinite(oracle::trianglePotential(p0, p1, p2, p1)));           // at a vertex
    CHECK(std::isfinite(oracle::trianglePotential(p0, p1, p2, 2 * p1 - p0)));  // edge line
    const Vector3d far = ctr + 1e3 * Vector3d(0.3, -0.5, 0.8).normalized();
    CHECK(oracle::trianglePotential(p0, p1, p2, far) == Approx(area / 1e3).epsilon(1e-5));
    // against tensor Gauss quadrature of 1/|r - r'| (points off the plane; 40 x 40
    // Duffy points: converged to ~1e-12 at these distances)
    for (const Vector3d& r :
         {Vector3d(0.5, 0.2, 0.7), Vector3d(2, 2, -1), Vector3d(-0.4, 0.1, 0.5)}) {
        TriMesh one;
        one.vertices = {p0, p1, p2};
        one.triangles = {{0, 1, 2}};
        double sum = 0;
        for (const auto& q : oracle::meshSurfaceQuadrature(one, 40))
            sum += q.ndA.norm() / (q.r - r).norm();
        CHECK(oracle::trianglePotential(p0, p1, p2, r) == Approx(sum).epsilon(1e-11));
    }
    // the gradient against central differences (step 1e-5: error ~1e-10)
    for (const Vector3d& r : {Vector3d(0.5, 0.2, 0.7), Vector3d(0.4, 0.2, 0.15), Vector3d(2, 2, -1),
                              Vector3d(1.5, 0.4, 0.05)}) {
        Vector3d fd;
        const double h = 1e-5;
        for (int k = 0; k < 3; ++k) {
            const Vector3d e = h * Vector3d::Unit(k);
            fd[k] = (oracle::trianglePotential(p0, p1, p2, r + e) -
                     oracle::trianglePotential(p0, p1, p2, r - e)) /
                    (2 * h);
        }
        CHECK((oracle::trianglePotentialGradient(p0, p1, p2, r) - fd).norm() < 2e-9);
    }
}

TEST_CASE("pair integrals of unit squares equal their closed forms", "[oracle][demag]") {
    // int int dA dA'/|r - r'| over two unit squares (two triangles each):
    //   the same square: 4 ln(1 + sqrt 2) - (4/3)(sqrt 2 - 1)
    //   parallel, stacked at distance d: 4 int_0^1 int_0^1 (1-u)(1-v)/sqrt(u^2+v^2+d^2)
    //   perpendicular, sharing an edge: 2 int_0^1 int_0^1 (1-u) asinh(1/sqrt(u^2+y^2))
    // (the last two by 25-digit quadrature, mpmath, the last also as a 3D integral)
    TriMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},
                  {1, 1, 1}, {0, 1, 1}, {0, 0, 0.1}, {1, 0, 0.1}, {1, 1, 0.1}, {0, 1, 0.1}};
    m.triangles = {{0, 1, 2},  {0, 2, 3},   {4, 5, 6}, {4, 6, 7},
                   {8, 9, 10}, {8, 10, 11}, {0, 1, 5}, {0, 5, 4}};
    auto squares = [&](int s, int t) {
        double sum = 0;
        for (int i : {s, s + 1})
            for (int j : {t, t + 1}) sum += oracle::trianglePairIntegral(m, i, j);
        return sum;
    };
    const double self = 4 * std::log(1 + std::sqrt(2.0)) - 4.0 / 3 * (std::sqrt(2.0) - 1);
    CHECK(squares(0, 0) == Approx(self).epsilon(1e-11));
    CHECK(squares(0, 2) == Approx(0.87881449585418321).epsilon(1e-13));
    CHECK(squares(0, 4) == Approx(2.4673644023642495).epsilon(1e-12));
    CHECK(squares(0, 6) == Approx(1.3488902463611710).epsilon(1e-11));
}

TEST_CASE("polyhedron demag field equals the closed-form cuboid field", "[oracle][demag]") {
    // two independent closed forms (triangle charges vs rectangle charges, cuboidField.hpp)
    const Vector3d hs(0.5, 1, 1.5), M(0.3, -0.5, 0.8);
    const TriMesh box = oracle::boxMesh(hs, Vector3i(1, 2, 3));
    const oracle::Cuboid cuboid{Vector3d::Zero(), hs, M, Matrix3d::Identity()};
    // (the last on a face: the mean of the two sides, in both)
    for (const Vector3d& r : {Vector3d(0.1, 0.2, 0.3), Vector3d(0.45, -0.9, 1.4), Vector3d(1, 2, 3),
                              Vector3d(-0.2, 0.6, -1.5)})
        CHECK((oracle::polyhedronDemagField(box, M, r) - oracle::cuboidH(cuboid, r)).norm() <
              1e-14 * M.norm());
}

TEST_CASE("mesh demag tensor: cube and boxes against Aharoni", "[oracle][demag]") {
    // 12-triangle boxes. The error of the mesh route is the graded rule on touching
    // pairs (30 x 30 points: ~1e-12 on each pair, tests above); the boxes agree with
    // Eq. 1 to ~1e-12 (1e-11 for the 1:1:10 slivers).
    struct Case {
        Vector3d halfSize;
        double tol;
    };
    const Case cases[] = {{{1, 1, 1}, 5e-12},
                          {{0.5, 0.5, 1}, 2e-12},
                          {{0.5, 1, 1.5}, 5e-12},
                          {{0.5, 0.5, 5}, 2e-11},
                          {{5, 5, 0.5}, 5e-11}};
    for (const auto& k : cases) {
        INFO(k.halfSize.transpose());
        const Matrix3d N = oracle::demagTensor(oracle::boxMesh(k.halfSize));
        CHECK(maxAbs(N - Matrix3d(oracle::prismDemagFactors(k.halfSize).asDiagonal())) < k.tol);
        CHECK(maxOffDiagonal(N) < k.tol);
        CHECK(std::abs(N.trace() - 1) < k.tol);
    }
    // faces split into squares (near and far pairs in play): 1:2:3 in 22 unit squares,
    // the cube in 24
    const Vector3d hs(0.5, 1, 1.5);
    const Matrix3d N = oracle::demagTensor(oracle::boxMesh(hs, Vector3i(1, 2, 3)));
    CHECK(maxAbs(N - Matrix3d(oracle::prismDemagFactors(hs).asDiagonal())) < 1e-12);
    const Matrix3d Nc = oracle::demagTensor(oracle::boxMesh(Vector3d(1, 1, 1), Vector3i(2, 2, 2)));
    CHECK(maxAbs(Nc - Matrix3d::Identity() / 3) < 1e-12);
}

TEST_CASE("mesh demag tensor: a rotated box gives R N R^T", "[oracle][demag]") {
    const Vector3d hs(0.5, 1, 1.5);
    const Matrix3d R = rotation(0.7, Vector3d(1, 2, -0.5));
    const Matrix3d N = oracle::demagTensor(oracle::boxMesh(hs));
    const Matrix3d Nr =
        oracle::demagTensor(oracle::transformedMesh(oracle::boxMesh(hs), R, Vector3d(0.3, -2, 1)));
    CHECK(maxAbs(Nr - R * N * R.transpose()) < 1e-14);
    CHECK(maxAbs(Nr - R * oracle::prismDemagFactors(hs).asDiagonal() * R.transpose()) < 5e-12);
    CHECK(maxOffDiagonal(Nr) > 0.05);  // really rotated
    CHECK(maxAbs(Nr - Nr.transpose()) == 0);
}

TEST_CASE("mesh demag tensor: tetrahedra and a hexagonal prism, two routes", "[oracle][demag]") {
    // the mesh route against the volume average of the Coulomb field of the surface charge
    // (graded cone quadrature, 16^3 or 12^3 points per cone: ~2e-8 or ~4e-7, converging as
    // the order rises; the field itself is checked against cuboidH above)
    const TriMesh tet = oracle::tetrahedronMesh(Vector3d(0, 0, 0), Vector3d(1, 0.1, 0),
                                                Vector3d(0.2, 0.8, 0.1), Vector3d(0.3, 0.2, 1.1));
    const Matrix3d N = oracle::demagTensor(tet);
    CHECK(std::abs(N.trace() - 1) < 1e-11);
    CHECK(maxAbs(N - demagTensorFromField(tet, 16)) < 1e-7);
    CHECK(maxOffDiagonal(N) > 0.01);
    CHECK(N.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() > 0);

    // regular tetrahedron: tetrahedral symmetry forces N = I/3
    const double s = 1 / std::sqrt(2.0);
    const Matrix3d Nreg = oracle::demagTensor(oracle::tetrahedronMesh(
        Vector3d(1, 0, -s), Vector3d(-1, 0, -s), Vector3d(0, 1, s), Vector3d(0, -1, s)));
    CHECK(maxAbs(Nreg - Matrix3d::Identity() / 3) < 1e-11);

    // hexagonal prism, circumradius 1, height 1: N_xx = N_yy by the 6-fold axis
    const TriMesh hex = oracle::regularPrismMesh(6, 1.0, 0.5);
    const Matrix3d Nh = oracle::demagTensor(hex);
    CHECK(std::abs(Nh.trace() - 1) < 1e-11);
    CHECK(std::abs(Nh(0, 0) - Nh(1, 1)) < 1e-11);
    CHECK(maxOffDiagonal(Nh) < 1e-11);
    CHECK(maxAbs(Nh - demagTensorFromField(hex, 12)) < 1e-6);
}

TEST_CASE("mesh demag tensor: volume average of the cuboid field", "[oracle][demag]") {
    // N_kk = -<H_k>/M_k with the closed-form cuboidH (an existing oracle) averaged by graded
    // Gauss quadrature (16^3 points; H is log-singular on the edges: ~1e-6)
    const Vector3d hs(0.5, 1, 1.5);
    const Vector3d Na = oracle::prismDemagFactors(hs);
    for (int k = 0; k < 3; ++k) {
        const oracle::Cuboid c{Vector3d::Zero(), hs, Vector3d::Unit(k), Matrix3d::Identity()};
        const Vector3d H =
            oracle::boxVolumeIntegral(
                Vector3d::Zero(), hs, [&](const Vector3d& r) { return oracle::cuboidH(c, r); }, 1,
                16, true) /
            (8 * hs.prod());
        CHECK(std::abs(-H[k] - Na[k]) < 3e-6);
        CHECK(std::abs(H[(k + 1) % 3]) < 1e-12);
    }
}

TEST_CASE("mesh demag tensor: spheres and a prolate spheroid", "[oracle][demag]") {
    // icosphere: icosahedral symmetry makes N = I/3 exactly at every level, so it tests
    // the quadrature, not the convergence
    for (int level = 0; level <= 1; ++level)
        CHECK(maxAbs(oracle::demagTensor(oracle::icosphereMesh(level)) - Matrix3d::Identity() / 3) <
              1e-12);
    // latitude-longitude sphere: N_zz < 1/3 < N_xx = N_yy, the error O(h^2)
    double previous = 1;
    for (int n : {4, 8}) {
        const Matrix3d N = oracle::demagTensor(oracle::uvSphereMesh(n, 2 * n), kFast);
        const double err = maxAbs(N - Matrix3d::Identity() / 3);
        INFO(n << ": " << err);
        CHECK(std::abs(N.trace() - 1) < 1e-6);
        CHECK(N(2, 2) < 1.0 / 3);
        CHECK(std::abs(N(0, 0) - N(1, 1)) < 1e-6);
        CHECK(err < previous / 3);
        previous = err;
    }
    CHECK(previous < 4e-3);
    // the icosphere stretched to the 1:1:2 prolate spheroid: N_zz -> 0.173564 (both
    // ellipsoid routes), errors 2.0e-4, 3.6e-5, 7.1e-6 at levels 0, 1, 2 (ratio -> 4)
    const double Nz = oracle::ellipsoidDemagFactors(Vector3d(1, 1, 2))[2];
    previous = 1;
    for (int level = 0; level <= 2; ++level) {
        const Matrix3d N = oracle::demagTensor(
            oracle::scaledMesh(oracle::icosphereMesh(level), Vector3d(1, 1, 2)), kFast);
        const double err = std::abs(N(2, 2) - Nz);
        INFO(level << ": " << err);
        CHECK(std::abs(N.trace() - 1) < 1e-6);
        CHECK(err < previous / 3.5);
        previous = err;
    }
    CHECK(previous < 1e-5);
}

TEST_CASE("volume averages through the boundary: n x A", "[oracle][demag]") {
    const TriMesh tet = oracle::tetrahedronMesh(Vector3d(0, 0, 0), Vector3d(1, 0.1, 0),
                                                Vector3d(0.2, 0.8, 0.1), Vector3d(0.3, 0.2, 1.1));
    const TriMesh box = oracle::boxMesh(Vector3d(0.5, 0.5, 0.5));
    const TriMesh ball = oracle::icosphereMesh(2, 0.8);
    // uniform B, A = B x r / 2 (linear): exact with 2 x 2 Duffy points per triangle
    const Vector3d B0(0.3, -1, 2);
    auto Au = [&](const Vector3d& r) -> Vector3d { return 0.5 * B0.cross(r); };
    for (const TriMesh* m : {&tet, &box, &ball})
        CHECK((oracle::meshVolumeAverageOfCurl(*m, Au, 2) - B0).norm() < 1e-14);

    // a point dipole outside the body
    const Vector3d moment(0.2, -0.4, 1.0), r0(1.5, 0.7, 2.2), centre(0.1, 0, 0);
    auto A = [&](const Vector3d& r) { return oracle::dipoleVectorPotential(moment, r0, r); };
    auto B = [&](const Vector3d& r) { return oracle::dipoleB(moment, r0, r); };
    const Vector3d Bc = B(centre);
    // exact sphere: the mean value property (24 x 48 points: ~1e-15)
    const Vector3d sphere =
        oracle::curlVolumeIntegral(oracle::sphereSurfaceQuadrature(centre, 0.8), A) /
        (4.0 / 3 * pi * std::pow(0.8, 3));
    CHECK((sphere - Bc).norm() < 1e-13 * Bc.norm());
    // icosphere polyhedra: the boundary route equals the cone volume route; both approach
    // the ball's value as O(h^2) (7.1e-6, 1.6e-6, 4.0e-7 at levels 1, 2, 3)
    double previous = 1;
    for (int level = 1; level <= 3; ++level) {
        const TriMesh m = oracle::transformedMesh(oracle::icosphereMesh(level, 0.8),
                                                  Matrix3d::Identity(), centre);
        const Vector3d viaBoundary = oracle::meshVolumeAverageOfCurl(m, A, 4);
        const Vector3d viaVolume = oracle::meshVolumeIntegral(m, B, 8) / oracle::meshVolume(m);
        CHECK((viaBoundary - viaVolume).norm() < 1e-9 * Bc.norm());
        const double err = (viaBoundary - Bc).norm() / Bc.norm();
        CHECK(err < previous / 3.5);
        previous = err;
    }
    // cube: against brute-force 3D Gauss of B (2^3 cells x 8^3 points)
    const Vector3d viaVolume =
        oracle::boxVolumeIntegral(Vector3d::Zero(), Vector3d(0.5, 0.5, 0.5), B, 2, 8);
    CHECK((oracle::meshVolumeAverageOfCurl(box, A, 8) - viaVolume).norm() <
          1e-12 * viaVolume.norm());
    CHECK((oracle::meshVolumeAverageOfCurl(box, A, 4) - viaVolume).norm() <
          1e-5 * viaVolume.norm());
}

TEST_CASE("mesh utilities: volumes, orientation, closedness", "[oracle][demag]") {
    CHECK(oracle::meshVolume(oracle::boxMesh(Vector3d(0.5, 1, 1.5), Vector3i(2, 3, 4))) ==
          Approx(6).epsilon(1e-14));
    CHECK(oracle::meshVolume(oracle::regularPrismMesh(6, 1, 0.5)) ==
          Approx(3 * std::sqrt(3.0) / 2).epsilon(1e-14));
    const TriMesh reflected = oracle::transformedMesh(
        oracle::boxMesh(Vector3d(1, 1, 1)), Vector3d(1, 1, -1).asDiagonal().toDenseMatrix());
    CHECK(oracle::meshVolume(reflected) == Approx(8).epsilon(1e-14));
    CHECK(oracle::meshVolume(oracle::icosphereMesh(3)) < 4 * pi / 3);
    CHECK(oracle::meshVolume(oracle::icosphereMesh(3)) == Approx(4 * pi / 3).epsilon(1e-2));
    // every edge is used twice, in opposite directions (closed, consistently oriented)
    for (const TriMesh& m :
         {oracle::boxMesh(Vector3d(1, 2, 3), Vector3i(2, 1, 3)), oracle::icosphereMesh(2),
          oracle::uvSphereMesh(5, 7), oracle::regularPrismMesh(6, 1, 1),
          oracle::tetrahedronMesh(Vector3d(0, 0, 0), Vector3d(0, 1, 0), Vector3d(1, 0, 0),
                                  Vector3d(0, 0, 1))}) {
        std::map<std::pair<int, int>, int> edges;
        for (const auto& t : m.triangles)
            for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
        bool closed = true;
        for (const auto& [e, count] : edges)
            closed = closed && count == 1 && edges.count({e.second, e.first}) == 1;
        CHECK(closed);
        CHECK(oracle::meshVolume(m) > 0);
    }
}

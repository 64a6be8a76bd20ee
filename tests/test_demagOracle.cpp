// Tests of reference/oracles/demagOracle.hpp: the prism (Aharoni 1998) and ellipsoid
// (Osborn 1945, Carlson's R_D) demagnetizing factors against values evaluated in
// 40-digit arithmetic, sum rules, limits and each other.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "oracles/demagOracle.hpp"

using Eigen::Vector3d;

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


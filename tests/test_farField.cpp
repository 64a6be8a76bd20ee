// The hybrid's dipole tier (modules/fields/hybrid, "Dipole tier"): one dipole-dipole
// interaction for pairs beyond dipoleRatio (R1 + R2), against MBM (exact field,
// Gauss n = 10 on the target: converged to rounding this far apart) and EDM. The
// error bound of the header: relative O((R/d)^4) for cubes (isotropic second moment),
// O((R/d)^2) for a bar; torques and angular momentum as the other tiers.
#include <magFoam/Body.hpp>
#include <DipoleFarField.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ShapeFactory.hpp>

#include "bodyFixture.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using mag::Body;
using mag::Quat;
using mag::Vec3;
using Catch::Matchers::Contains;

namespace {

using magtest::field;
using magtest::magnet;
using magtest::axisAngle;
using magtest::boxShape;

// Source at the origin, target at distance k (R1 + R2) along an oblique direction;
// both tilted, magnetized off their axes, so that no symmetry hides an error term.
std::pair<Body, Body> pairAt(const std::shared_ptr<const mag::Shape>& s, const std::shared_ptr<const mag::Shape>& t,
                             double k) {
    const Vec3 dir = Vec3(0.3, -0.5, 0.8).normalized();
    const double d = k * (s->boundingRadius + t->boundingRadius);
    return {magnet("source", s, Vec3::Zero(), Vec3(0.2, 0.1, 1), axisAngle(25, Vec3(1, 2, 0))),
            magnet("target", t, d * dir, Vec3(-0.3, 0.4, 1), axisAngle(-40, Vec3(0, 1, 3)))};
}

double relErr(const Vec3& a, const Vec3& ref) { return (a - ref).norm() / ref.norm(); }

struct Errors {
    double force, torque;
};

// Pair counters of a hybrid: dipole, near, far.
struct PairCounts {
    std::uint64_t dipole, near, far;
    bool operator==(const PairCounts&) const = default;
};
PairCounts pairCounts(const mag::FieldEvaluator& f) {
    const mag::FieldStats s = f.stats();
    return {s.count("dipolePairs"), s.count("nearPairs"), s.count("farPairs")};
}

// Dipole tier (dipoleRatio 1 with threshold 0 puts every pair whose bounding
// spheres are apart on it) against MBM.
Errors dipoleError(const std::shared_ptr<const mag::Shape>& s, const std::shared_ptr<const mag::Shape>& t, double k) {
    auto dipole = field("{type: hybrid, dipoleRatio: 1, switch: {threshold: 0}}");
    auto mbm = field("{type: MBM, quadrature: {type: gauss, n: 10}}");
    const auto [a, b] = pairAt(s, t, k);
    const mag::Wrench w = dipole->interaction(a, b), ref = mbm->interaction(a, b);
    REQUIRE(dipole->stats().count("dipolePairs") == 1);
    return {relErr(w.force, ref.force), relErr(w.totalTorque(), ref.totalTorque())};
}

} // namespace

TEST_CASE("dipole tier: two cubes converge as (R/d)^4", "[hybrid][farField]") {
    const auto cube = boxShape(Vec3::Constant(0.01));
    const Errors e2 = dipoleError(cube, cube, 2), e4 = dipoleError(cube, cube, 4), e8 = dipoleError(cube, cube, 8);
    INFO("force errors " << e2.force << " " << e4.force << " " << e8.force << "; torque " << e2.torque << " "
                         << e4.torque << " " << e8.torque);
    // Doubling the distance divides the error by ~16 (the quadrupole of a cube's
    // volume vanishes, the next term is the fourth moment).
    CHECK(e4.force / e2.force == Approx(1.0 / 16).epsilon(0.3));
    CHECK(e8.force / e4.force == Approx(1.0 / 16).epsilon(0.2));
    CHECK(e8.torque / e4.torque == Approx(1.0 / 16).epsilon(0.2));
    CHECK(e8.force < 2e-5); // at the default dipoleRatio (measured 1.3e-5)
}

TEST_CASE("dipole tier: a bar converges as (R/d)^2", "[hybrid][farField]") {
    const auto cube = boxShape(Vec3::Constant(0.01));
    const auto bar = boxShape(Vec3(0.03, 0.01, 0.01));
    const Errors e4 = dipoleError(bar, cube, 4), e8 = dipoleError(bar, cube, 8), e16 = dipoleError(bar, cube, 16);
    INFO("force errors " << e4.force << " " << e8.force << " " << e16.force << "; torque " << e4.torque << " "
                         << e8.torque << " " << e16.torque);
    CHECK(e8.force / e4.force == Approx(0.25).epsilon(0.2));
    CHECK(e16.force / e8.force == Approx(0.25).epsilon(0.1));
    CHECK(e16.torque / e8.torque == Approx(0.25).epsilon(0.1));
    // Default dipoleRatio 8 (R1 + R2): below 1 % for a 3:1 bar (measured 0.73 %).
    CHECK(e8.force < 1e-2);
}

TEST_CASE("dipole tier: default ratio 8, EDM agrees, angular momentum conserved", "[hybrid][farField]") {
    const auto cube = boxShape(Vec3::Constant(0.01));
    auto hybrid = field("{type: hybrid}");
    auto edm = field("{type: EDM, n: 4}");
    {
        // 5.9 (R1 + R2): EDM far tier (below the dipole band, (6, 8] (R1 + R2)); 8.1: dipole.
        const auto [a, b] = pairAt(cube, cube, 5.9);
        const mag::Wrench w = hybrid->interaction(a, b);
        CHECK(w.force == field("{type: EDM, n: 2}")->interaction(a, b).force); // the default far model
        CHECK(pairCounts(*hybrid) == PairCounts{0, 0, 1});
    }
    const auto [a, b] = pairAt(cube, cube, 8.1);
    const mag::Wrench w = hybrid->interaction(a, b);
    CHECK(pairCounts(*hybrid) == PairCounts{1, 0, 1});
    const mag::Wrench ref = edm->interaction(a, b);
    // The dipole's own error (1.3e-5 at 8 (R1 + R2)) dominates; EDM n = 4 is ~1e-7.
    CHECK(relErr(w.force, ref.force) < 2e-5);
    CHECK(relErr(w.totalTorque(), ref.totalTorque()) < 2e-5);
    CHECK(w.mechanicalTorque == Vec3::Zero()); // the dipole sits at the COM
    CHECK(w.energy == Approx(ref.energy).epsilon(2e-5));
    // dipoleRatio 0: the tier is off.
    auto off = field("{type: hybrid, dipoleRatio: 0}");
    CHECK(off->interaction(a, b).force == field("{type: EDM, n: 2}")->interaction(a, b).force);
    CHECK(off->stats().count("dipolePairs") == 0);
    CHECK_THROWS_WITH(field("{type: hybrid, dipoleRatio: -1}"), Contains("dipoleRatio"));

    // Through MagneticSystem: total force and total angular momentum about the
    // origin vanish (the source gets -F and -T - r x F).
    const mag::MagneticSystem system(field("{type: hybrid}"),
                                     mag::InductionModel::New(mag::Dict::fromString("type: none\n", "test_farField")));
    const std::vector<Body> bodies = {a, b};
    const auto ws = system.wrenches(bodies);
    const Vec3 F = ws[0].force + ws[1].force;
    const Vec3 L = ws[0].totalTorque() + ws[1].totalTorque() + a.position.cross(ws[0].force) +
                   b.position.cross(ws[1].force);
    CHECK(F.norm() <= 1e-15 * ws[1].force.norm());
    CHECK(L.norm() <= 1e-12 * (ws[1].totalTorque().norm() + b.position.norm() * ws[1].force.norm()));
}

TEST_CASE("dipole tier error against MBM (report)", "[hybrid][farField][.report]") {
    // Not a check: prints the numbers quoted in HybridField.cpp and the README.
    const auto cube = boxShape(Vec3::Constant(0.01));
    const auto bar = boxShape(Vec3(0.03, 0.01, 0.01));
    std::printf("d/(R1+R2)  cube-cube F   T          bar-cube F   T\n");
    for (double k : {2.0, 4.0, 8.0, 16.0}) {
        const Errors c = dipoleError(cube, cube, k), b = dipoleError(bar, cube, k);
        std::printf("%5.0f      %9.2e  %9.2e   %9.2e  %9.2e\n", k, c.force, c.torque, b.force, b.torque);
    }
}

namespace {

struct Named {
    const char* name;
    std::shared_ptr<const mag::Shape> shape;
};
std::vector<Named> testShapes() {
    return {{"cube", boxShape(Vec3::Constant(0.01))},
            {"bar3", boxShape(Vec3(0.03, 0.01, 0.01))},
            {"plate", boxShape(Vec3(0.02, 0.02, 0.003))},
            {"rod10", boxShape(Vec3(0.05, 0.005, 0.005))},
            {"ball", magtest::sphereShape(0.006, 2)}};
}

// Largest dipole-pair errors over random orientations, magnetizations and
// directions at centre distance d, against MBM (Gauss n = 10, converged to
// rounding this far apart), as fractions of a dipole pair's force scale
// 3 mu0 |ms||mt| / (4 pi d^4) and torque scale times d.
Errors scaledDipoleErrors(const std::shared_ptr<const mag::Shape>& S, const std::shared_ptr<const mag::Shape>& T,
                          double d, int trials, std::mt19937& rng) {
    std::normal_distribution<double> g;
    auto randomQuat = [&] { return Quat(g(rng), g(rng), g(rng), g(rng)).normalized(); };
    auto randomDir = [&] { return Vec3(g(rng), g(rng), g(rng)).normalized(); };
    auto dipole = field("{type: hybrid, dipoleRatio: 1, switch: {threshold: 0}}");
    auto mbm = field("{type: MBM, quadrature: {type: gauss, n: 10}}");
    constexpr double kMu = mag::mu0 / (4 * mag::pi);
    Errors e{0, 0};
    for (int trial = 0; trial < trials; ++trial) {
        const Body s = magnet("s", S, Vec3::Zero(), randomDir(), randomQuat());
        const Body t = magnet("t", T, d * randomDir(), randomDir(), randomQuat());
        const mag::Wrench w = dipole->interaction(s, t), ref = mbm->interaction(s, t);
        const double scale = 3 * kMu * s.magneticMoment().norm() * t.magneticMoment().norm() / std::pow(d, 4);
        e.force = std::max(e.force, (w.force - ref.force).norm() / scale);
        e.torque = std::max(e.torque, (w.totalTorque() - ref.totalTorque()).norm() / (scale * d));
    }
    return e;
}

} // namespace

TEST_CASE("dipole tier: the moment estimate bounds the error for any shape and orientation", "[hybrid][farField]") {
    // c2, c4 of DipoleFarField.hpp were set from other random draws (seed 11 of the
    // report below); these are new ones.
    std::mt19937 rng(2024);
    const auto shapes = testShapes();
    double tightest = 0;
    for (std::size_t a = 0; a < shapes.size(); ++a)
        for (std::size_t b = a; b < shapes.size(); ++b) {
            const auto& S = shapes[a].shape;
            const auto& T = shapes[b].shape;
            for (double k : {2.0, 3.0, 5.0, 8.0, 12.0}) {
                const double d = k * (S->boundingRadius + T->boundingRadius);
                const double bound = mag::dipoleErrorEstimate(*S, *T, d);
                const Errors e = scaledDipoleErrors(S, T, d, 6, rng);
                INFO(shapes[a].name << " - " << shapes[b].name << " at " << k << " (R1 + R2): force " << e.force
                                    << ", torque " << e.torque << ", estimate " << bound);
                CHECK(e.force <= bound);
                CHECK(e.torque <= bound);
                tightest = std::max(tightest, std::max(e.force, e.torque) / bound);
            }
        }
    // Not a bound that could never fail: somewhere the error comes within 3x of it.
    CHECK(tightest > 0.33);
}

TEST_CASE("dipoleTolerance: each shape's reach keeps its dipole pairs within the tolerance", "[hybrid][farField]") {
    const auto shapes = testShapes();
    const auto& cube = shapes[0].shape;
    const auto& bar = shapes[1].shape;
    const auto& ball = shapes[4].shape;
    // Isotropic shapes reach ~5 R at 1e-3 ((2 c4 / tol)^(1/4) = 4.95); a 3:1 bar's
    // second moment adds ~2 m (reach 2.06 m).
    CHECK(mag::dipoleReachFor(*cube, 1e-3) == Approx(4.95 * cube->boundingRadius).epsilon(1e-3));
    CHECK(mag::dipoleReachFor(*ball, 1e-3) < 5.5 * ball->boundingRadius);  // icosphere: nearly isotropic
    CHECK(mag::dipoleReachFor(*bar, 1e-3) > 100 * bar->boundingRadius);
    std::mt19937 rng(7);
    for (double tol : {1e-2, 1e-3}) {
        for (const auto& [S, T] : {std::pair{cube, cube}, std::pair{cube, ball}, std::pair{bar, cube}}) {
            const double d = 1.0001 * (mag::dipoleReachFor(*S, tol) + mag::dipoleReachFor(*T, tol));
            const Errors e = scaledDipoleErrors(S, T, d, 6, rng);
            INFO("tolerance " << tol << ": force " << e.force << ", torque " << e.torque);
            CHECK(e.force <= tol);
            CHECK(e.torque <= tol);
        }
    }
    // The hybrid uses it: just beyond the two reaches a dipole pair, below the
    // dipole band (0.75 of them) a far one.
    auto hybrid = field("{type: hybrid, dipoleTolerance: 1e-3}");
    const double reach = 2 * mag::dipoleReachFor(*cube, 1e-3);
    const Body s = magnet("s", cube, Vec3::Zero(), Vec3(0, 0, 1));
    for (double f : {0.749, 1.001}) {
        const Body t = magnet("t", cube, Vec3(0.2, 0.3, 0.9).normalized() * f * reach, Vec3(1, 0, 1));
        (void)hybrid->interaction(s, t);
    }
    CHECK_THAT(hybrid->describe(), Contains("dipoleTolerance 0.001"));
    CHECK(pairCounts(*hybrid) == PairCounts{1, 0, 1});
    CHECK_THROWS_WITH(field("{type: hybrid, dipoleTolerance: 1e-3, dipoleRatio: 8}"),
                      Contains("dipoleRatio") && Contains("not both"));
    CHECK_THROWS_WITH(field("{type: hybrid, dipoleTolerance: 0}"), Contains("dipoleTolerance") && Contains("(0, 1)"));
}

TEST_CASE("dipole tier error against the moment estimate (report)", "[hybrid][farField][.report]") {
    // Not a check: the largest errors over random draws, scaled by q / d^2 (c2) and
    // by ((R1 + R2) / d)^4 (c4), from which DipoleFarField.hpp's constants are set.
    std::mt19937 rng(11);
    const auto shapes = testShapes();
    std::printf("source target  q_s    q_t (cm^2) k   force     torque    F d^2/q   F k^4\n");
    for (std::size_t a = 0; a < shapes.size(); ++a)
        for (std::size_t b = a; b < shapes.size(); ++b) {
            const auto& S = *shapes[a].shape;
            const auto& T = *shapes[b].shape;
            const double q = mag::shapeQuadrupole(S) + mag::shapeQuadrupole(T), R = S.boundingRadius + T.boundingRadius;
            for (double k : {2.0, 3.0, 4.0, 6.0, 8.0, 16.0}) {
                const Errors e = scaledDipoleErrors(shapes[a].shape, shapes[b].shape, k * R, 24, rng);
                std::printf("%-6s %-6s %6.3f %6.3f %4.0f %9.2e %9.2e %9.3f %9.3f\n", shapes[a].name, shapes[b].name,
                            mag::shapeQuadrupole(S) * 1e4, mag::shapeQuadrupole(T) * 1e4, k, e.force, e.torque,
                            q > 1e-12 * R * R ? e.force * k * k * R * R / q : 0.0, e.force * std::pow(k, 4));
            }
        }
}

// Tests of the EDM field evaluator (modules/fields/EDM, paper Sec. 3, Eqs. 1, 5, 6),
// selected by name like an app does. Independent references only:
//   - exact dipole-dipole force/torque/field (reference/oracles/dipole.hpp): a uniformly
//     magnetized sphere IS a dipole outside, so the sphere fast path must match it to
//     rounding;
//   - the Akoun-Yonnet closed-form force between cuboids (reference/oracles/akounYonnet.hpp)
//     for the grid sampling and its convergence order;
//   - conservation laws (Newton's third law, angular momentum) and curl A = B.
#include <catch2/catch.hpp>

#include "oracles/akounYonnet.hpp"
#include "oracles/dipole.hpp"

#include <magFoam/Body.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <regex>
#include <string>
#include <vector>

using mag::Body;
using mag::Quat;
using mag::Vec3;
using Catch::Matchers::Contains;

namespace {

std::unique_ptr<mag::FieldEvaluator> edm(const std::string& yaml) {
    return mag::FieldEvaluator::New(mag::Dict::fromString("type: EDM\n" + yaml, "test_edm"));
}

std::shared_ptr<const mag::Shape> boxShape(const Vec3& size) {
    mag::ShapeKind kind;
    kind.kind = mag::ShapeKind::Kind::box;
    kind.size = size;
    return mag::makeShape(mag::makeBox(size), kind);
}

std::shared_ptr<const mag::Shape> sphereShape(double radius, int subdivisions = 3) {
    mag::ShapeKind kind;
    kind.kind = mag::ShapeKind::Kind::sphere;
    kind.radius = radius;
    return mag::makeShape(mag::makeIcosphere(radius, subdivisions), kind);
}

std::shared_ptr<const mag::Shape> cylinderShape(double radius, double height, int segments) {
    mag::ShapeKind kind;
    kind.kind = mag::ShapeKind::Kind::cylinder;
    kind.radius = radius;
    kind.height = height;
    return mag::makeShape(mag::makeCylinder(radius, height, segments), kind);
}

// A permanent magnet: remanence Br (T) along dir (body frame).
Body magnet(const std::string& name, std::shared_ptr<const mag::Shape> shape, const Vec3& position,
            const Vec3& dir, double Br = 1.0, const Quat& orientation = Quat::Identity()) {
    Body b;
    b.name = name;
    b.shape = std::move(shape);
    b.material.density = 7500;
    b.magnetizationBody = dir.normalized() * Br / mag::mu0;
    b.position = position;
    b.orientation = orientation.normalized();
    return b;
}

Quat axisAngle(double degrees, const Vec3& axis) {
    return Quat(Eigen::AngleAxisd(degrees * mag::pi / 180.0, axis.normalized()));
}

bool finite(const Vec3& v) { return v.allFinite(); }
bool finite(const mag::Wrench& w) {
    return finite(w.force) && finite(w.torque) && finite(w.mechanicalTorque) && std::isfinite(w.energy);
}

double relErr(const Vec3& a, const Vec3& ref) { return (a - ref).norm() / ref.norm(); }

// The Fig. 4 pair: two 1 cm cubes, Br = 1 T along +z, face gap d (m) along z.
const Vec3 cubeSize(0.01, 0.01, 0.01);
struct CubePair {
    Body bottom, top;
    Vec3 reference; // Akoun-Yonnet force on top
};
CubePair cubePair(double gap, const Vec3& lateral = Vec3::Zero()) {
    static const auto shape = boxShape(cubeSize);
    CubePair p{magnet("bottom", shape, Vec3::Zero(), Vec3::UnitZ()),
               magnet("top", shape, lateral + Vec3(0, 0, 0.01 + gap), Vec3::UnitZ()), Vec3::Zero()};
    p.reference = oracle::akounYonnetForce(cubeSize, p.bottom.position, cubeSize, p.top.position, 1.0, 1.0);
    return p;
}

// The softened-pair counter of stats().
long softenedCount(const mag::FieldEvaluator& f) { return static_cast<long>(f.stats().count("softenedPairs")); }

} // namespace

TEST_CASE("EDM sphere fast path equals the exact dipole-dipole interaction", "[EDM]") {
    // Rotated, offset spheres of different sizes with oblique magnetizations; n = 4 is
    // overridden by sphere: auto (one dipole of moment M V at the centre).
    auto f = edm("n: 4\n");
    const Body s = magnet("s", sphereShape(0.004), Vec3(0.001, -0.002, 0.0005), Vec3(1, 2, 3), 1.2,
                          axisAngle(35, Vec3(1, -1, 2)));
    const Body t = magnet("t", sphereShape(0.006, 2), Vec3(0.013, 0.004, -0.007), Vec3(-2, 0.5, 1), 0.8,
                          axisAngle(-70, Vec3(0.3, 1, 0.2)));
    const Vec3 ms = s.magnetization() * s.shape->volume, mt = t.magnetization() * t.shape->volume;
    const mag::Wrench w = f->interaction(s, t);
    const Vec3 F = oracle::dipoleForce(mt, t.position, ms, s.position);
    const Vec3 T = oracle::dipoleTorque(mt, t.position, ms, s.position);
    const double U = -mt.dot(oracle::dipoleB(ms, s.position, t.position));
    // 1e-12: the same dozen floating-point operations in another order; only rounding
    // (~1e-16 each) separates them.
    CHECK(relErr(w.force, F) < 1e-12);
    CHECK(relErr(w.torque, T) < 1e-12);
    CHECK(w.mechanicalTorque.norm() <= 1e-12 * T.norm()); // the dipole sits at the COM
    CHECK(std::abs(w.energy - U) < 1e-12 * std::abs(U));

    // Fields outside the source sphere: the exact sphere field (oracle::sphereB with
    // the sphere of the same volume), and H = B / mu0.
    const double rEq = std::cbrt(3.0 * s.shape->volume / (4.0 * mag::pi));
    std::vector<Vec3> points = {Vec3(0.01, 0.0, 0.0), Vec3(-0.003, 0.007, 0.002), Vec3(0.02, -0.03, 0.05)};
    for (Vec3& p : points) p += s.position;
    std::vector<Vec3> B(points.size()), A(points.size()), H(points.size());
    f->evaluate(s, points, B, A, H);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec3 ref = oracle::sphereB(s.position, rEq, s.magnetization(), points[i]);
        CHECK(relErr(B[i], ref) < 1e-12); // rounding only, as above
        CHECK(relErr(H[i], ref / mag::mu0) < 1e-12);
    }

    // sphere: off samples the sphere on the grid: no longer the exact dipole at n = 4
    // (the grid's higher moments differ from the sphere's: measured 1.2 % here; 1e-6
    // only asserts that the fast path was really bypassed).
    auto off = edm("n: 4\nsphere: off\n");
    CHECK(relErr(off->interaction(s, t).force, F) > 1e-6);
    // sphere: on makes every body one dipole at its COM, like n: 1 (same arithmetic).
    const CubePair p = cubePair(0.003);
    CHECK(edm("n: 4\nsphere: on\n")->interaction(p.bottom, p.top).force ==
          edm("n: 1\n")->interaction(p.bottom, p.top).force);
}

TEST_CASE("EDM vector potential: curl A = B", "[EDM]") {
    // Central differences of A around points outside a grid-sampled cube (h = 1e-6 m,
    // 5 mm from the nearest dipole): truncation ~ (h/r)^2 ~ 1e-7, rounding ~ 1e-16 r/h
    // ~ 1e-12; measured 1e-8.
    auto f = edm("n: 3\n");
    const Body s = magnet("s", boxShape(cubeSize), Vec3(0.001, 0.002, 0.003), Vec3(1, -1, 2), 1.0,
                          axisAngle(20, Vec3(1, 2, 3)));
    const double h = 1e-6;
    for (const Vec3& p0 : {Vec3(0.012, 0.0, 0.004), Vec3(-0.004, 0.015, -0.009)}) {
        const Vec3 p = p0 + s.position;
        std::vector<Vec3> pts;
        for (int k = 0; k < 3; ++k)
            for (double sgn : {-1.0, 1.0}) pts.push_back(p + sgn * h * Vec3::Unit(k));
        pts.push_back(p);
        std::vector<Vec3> B(pts.size()), A(pts.size());
        f->evaluate(s, pts, B, A);
        Eigen::Matrix3d dA; // dA(i, k) = d A_i / d x_k
        for (int k = 0; k < 3; ++k) dA.col(k) = (A[2 * k + 1] - A[2 * k]) / (2 * h);
        const Vec3 curl(dA(2, 1) - dA(1, 2), dA(0, 2) - dA(2, 0), dA(1, 0) - dA(0, 1));
        CHECK(relErr(curl, B.back()) < 1e-6);
    }
}

TEST_CASE("EDM total moment is M V for any closed mesh", "[EDM]") {
    // A 12-sided cylinder on a 3^3 grid keeps only some cell centres (winding-number
    // test); each dipole carries V/N so the total moment is M V exactly. Far away the
    // field is that of the dipole M V: at 300 bounding radii the quadrupole of the grid
    // contributes ~ (R/r)^2 ~ 1e-5 relative (measured <= 1e-5); without the rescaling
    // the moment (N h^3 instead of V) would be off by O(10 %).
    const auto shape = cylinderShape(0.005, 0.004, 12);
    const Body s = magnet("cyl", shape, Vec3(0.01, 0, 0), Vec3(0.3, 0.4, 1), 1.0, axisAngle(40, Vec3(1, 1, 0)));
    for (int n : {2, 3, 5}) {
        auto f = edm("n: " + std::to_string(n) + "\nsphere: off\n");
        const double r = 300 * shape->boundingRadius;
        for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0.2, -1, 0.5), Vec3(0, 0, 1)}) {
            const Vec3 p = s.position + r * dir.normalized();
            Vec3 B;
            f->evaluate(s, std::span<const Vec3>(&p, 1), std::span<Vec3>(&B, 1));
            const Vec3 ref = oracle::dipoleB(s.magnetization() * shape->volume, s.position, p);
            CHECK(relErr(B, ref) < 1e-4);
        }
    }
}

TEST_CASE("EDM converges to Akoun-Yonnet for separated cubes", "[EDM]") {
    // The midpoint grid integrates the (harmonic) pair kernel; its h^2 error term is
    // proportional to the Laplacian of the kernel, which vanishes outside the sources,
    // so the observed order is 4 (n = 2, 4, 8). Checked on coaxial and offset pairs at
    // gaps >= 2 cm; the order must lie in [3.8, 4.2] (measured 3.998..4.000: the
    // asymptotic range is reached from n = 2 on, h / distance <= 1/6).
    for (const Vec3& lateral : {Vec3(0, 0, 0), Vec3(0.006, -0.003, 0)}) {
        for (double gap : {0.02, 0.05}) {
            const CubePair p = cubePair(gap, lateral);
            double err[3];
            int i = 0;
            for (int n : {2, 4, 8}) {
                auto f = edm("n: " + std::to_string(n) + "\n");
                err[i++] = relErr(f->interaction(p.bottom, p.top).force, p.reference);
            }
            const double order1 = std::log2(err[0] / err[1]), order2 = std::log2(err[1] / err[2]);
            INFO("gap " << gap << " lateral " << lateral.transpose() << ": errors " << err[0] << " " << err[1]
                        << " " << err[2] << ", orders " << order1 << " " << order2);
            CHECK(err[2] < err[1]);
            CHECK(err[1] < err[0]);
            CHECK(order1 > 3.8);
            CHECK(order1 < 4.2);
            CHECK(order2 > 3.8);
            CHECK(order2 < 4.2);
            // n = 2 is already within 0.1 % at these gaps (measured 0.072 % at 2 cm): the
            // reason hybrid's default far model is EDM n = 2.
            CHECK(err[0] < 1e-3);
        }
    }
}

TEST_CASE("EDM error grows as the cubes approach (the paper's point)", "[EDM]") {
    // Relative error of n = 2 against Akoun-Yonnet at the gaps of Fig. 5, decreasing
    // with the gap; at 0.02 cm the point dipoles are far too coarse (> 5 %).
    auto f = edm("n: 2\n");
    double previous = 1e300;
    for (double gap : {0.0002, 0.001, 0.005, 0.02}) {
        const CubePair p = cubePair(gap);
        const mag::Wrench w = f->interaction(p.bottom, p.top);
        REQUIRE(finite(w));
        const double e = relErr(w.force, p.reference);
        INFO("gap " << gap << " error " << e);
        CHECK(e < previous);
        previous = e;
    }
    // Measured 30 % at 0.02 cm (paper Fig. 5: EDM far off at contact); 5 % is a floor
    // that any correct dipole sum at n = 2 exceeds there.
    const CubePair close = cubePair(0.0002);
    CHECK(relErr(f->interaction(close.bottom, close.top).force, close.reference) > 0.05);
}

TEST_CASE("EDM stays finite at contact, in overlap and for coinciding dipoles", "[EDM]") {
    for (int n : {2, 3, 4}) {
        auto f = edm("n: " + std::to_string(n) + "\n");
        // Touching, overlapping, fully coinciding (every dipole pair coincides).
        for (double gap : {0.0, -0.001, -0.005, -0.0075, -0.01}) {
            const CubePair p = cubePair(gap);
            const mag::Wrench w = f->interaction(p.bottom, p.top);
            INFO("n " << n << " gap " << gap);
            CHECK(finite(w));
            std::vector<Vec3> pts = {p.top.position, p.bottom.position, Vec3(0.0025, 0.0025, 0.0025)};
            std::vector<Vec3> B(3), A(3), H(3);
            f->evaluate(p.bottom, pts, B, A, H);
            for (int k = 0; k < 3; ++k) CHECK((finite(B[k]) && finite(A[k]) && finite(H[k])));
        }
        // gap -0.01: the cubes coincide, so dipole pairs at distance 0 were softened.
        CHECK(softenedCount(*f) > 0);
    }
    // Separated bodies never soften.
    auto g = edm("n: 3\n");
    const CubePair p = cubePair(0.001);
    g->interaction(p.bottom, p.top);
    CHECK(softenedCount(*g) == 0);
    // Coinciding dipoles: the softening ball gives no force and a finite field.
    const auto sphere = sphereShape(0.005);
    const Body a = magnet("a", sphere, Vec3::Zero(), Vec3::UnitZ());
    const Body b = magnet("b", sphere, Vec3::Zero(), Vec3(1, 0, 1));
    const mag::Wrench w = g->interaction(a, b);
    CHECK(finite(w));
    CHECK(w.force.norm() == 0);
    CHECK(softenedCount(*g) == 1);
}

TEST_CASE("EDM obeys Newton's third law and conserves angular momentum", "[EDM]") {
    // Different shapes, rotations, oblique magnetizations; the pair force terms are
    // antisymmetric by construction, so only the summation order differs: 1e-12.
    auto f = edm("n: 3\n");
    const Body a = magnet("a", boxShape(Vec3(0.01, 0.006, 0.004)), Vec3(0.002, -0.001, 0.0), Vec3(1, 0.5, -0.3),
                          1.3, axisAngle(25, Vec3(1, 2, 0.5)));
    const Body b = magnet("b", cylinderShape(0.004, 0.008, 16), Vec3(0.004, 0.012, 0.006), Vec3(-0.2, 1, 0.7), 0.9,
                          axisAngle(-50, Vec3(0.1, -0.4, 1)));
    for (double shift : {0.0, -0.008}) { // separated, then overlapping
        Body bb = b;
        bb.position.y() += shift;
        const mag::Wrench onB = f->interaction(a, bb);
        const mag::Wrench onA = f->interaction(bb, a);
        INFO("shift " << shift);
        CHECK((onA.force + onB.force).norm() < 1e-12 * onB.force.norm());
        const Vec3 L = onA.totalTorque() + onB.totalTorque() + a.position.cross(onA.force) +
                       bb.position.cross(onB.force);
        const double scale = onB.force.norm() * (a.position.norm() + bb.position.norm()) + onA.torque.norm() +
                             onB.torque.norm() + onA.mechanicalTorque.norm() + onB.mechanicalTorque.norm();
        CHECK(L.norm() < 1e-12 * scale);
        // The interaction energy is symmetric.
        CHECK(std::abs(onA.energy - onB.energy) < 1e-12 * std::abs(onB.energy));
    }
}

TEST_CASE("EDM adaptive sampling lowers n with distance", "[EDM]") {
    // n_eff = clamp(ceil(n (R1 + R2) / d), 1, n): for 1 cm cubes (R = 0.866 cm), n = 8
    // gives n_eff = 8 at d = 1.2 cm, 4 at d = 4 cm (13.86/4 = 3.46), 2 at d = 10 cm.
    // The same arithmetic as the fixed-n evaluator: equal to rounding (1e-14).
    auto adaptive = edm("n: 8\nadaptive: true\n");
    for (auto [gap, nEff] : {std::pair{0.002, 8}, std::pair{0.03, 4}, std::pair{0.09, 2}}) {
        const CubePair p = cubePair(gap);
        auto fixed = edm("n: " + std::to_string(nEff) + "\n");
        INFO("gap " << gap);
        CHECK(relErr(adaptive->interaction(p.bottom, p.top).force, fixed->interaction(p.bottom, p.top).force) <
              1e-14);
    }
}

TEST_CASE("EDM keys are checked", "[EDM][badInput]") {
    CHECK_THROWS_WITH(edm("n: 0\n"), Contains("n must be 1..40"));
    CHECK_THROWS_WITH(edm("sphere: maybe\n"), Contains("sphere") && Contains("auto"));
    CHECK_THROWS_WITH(edm("softening: 0\n"), Contains("softening"));
    CHECK_THROWS_AS(edm("nn: 3\n"), mag::InputError);
    CHECK_THAT(edm("n: 5\nadaptive: true\n")->describe(), Contains("EDM (n=5, adaptive on, sphere auto"));
}

TEST_CASE("EDM error and cost versus n (report)", "[EDM][.report]") {
    // Not a check: prints the numbers quoted in the module's documentation.
    std::printf("EDM relative force error vs Akoun-Yonnet (coaxial 1 cm cubes, 1 T)\n gap[cm]");
    const std::vector<int> ns = {1, 2, 3, 4, 6, 8, 10};
    for (int n : ns) std::printf("   n=%-6d", n);
    std::printf("\n");
    for (double gap : {0.0002, 0.001, 0.005, 0.01, 0.016, 0.02, 0.05}) {
        const CubePair p = cubePair(gap);
        std::printf(" %7.3f", gap * 100);
        for (int n : ns) {
            auto f = edm("n: " + std::to_string(n) + "\n");
            std::printf("  %+.3e", (f->interaction(p.bottom, p.top).force.z() - p.reference.z()) / std::abs(p.reference.z()));
        }
        std::printf("\n");
    }
    std::printf("EDM time per interaction (cube pair, gap 1 cm)\n");
    const CubePair p = cubePair(0.01);
    for (int n = 2; n <= 10; ++n) {
        auto f = edm("n: " + std::to_string(n) + "\n");
        f->interaction(p.bottom, p.top); // build the tables
        int reps = 0;
        const auto t0 = std::chrono::steady_clock::now();
        double elapsed = 0;
        Vec3 sink = Vec3::Zero();
        while (elapsed < 0.3) {
            sink += f->interaction(p.bottom, p.top).force;
            ++reps;
            elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
        std::printf(" n=%2d  %4d dipoles/body  %10.3f us  (%g)\n", n, n * n * n, 1e6 * elapsed / reps, sink.z() / reps);
    }
}

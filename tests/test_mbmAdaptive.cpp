// Tests of MBM's adaptive, contact-exact boundary quadrature (modules/fields/MBM:
// ContactSplit, AdaptiveQuadrature; docs/physics.md#adaptive-quadrature).
// References are independent of the kernel (reference/oracles/): the one-sided
// Akoun-Yonnet force of parallel cuboids (the limit from separation), its Amperian
// counterpart in overlap, and an adaptive iterated Gauss-Kronrod integral of the
// closed-form cuboid field over the target's surface charge (contactQuadrature.hpp),
// accurate to ~1e-10 also at contact, for the rotated pairs and every torque.
#include <catch2/catch.hpp>

#include "AdaptiveQuadrature.hpp"
#include "PolyhedronTables.hpp"
#include "SurfaceQuadrature.hpp"
#include "oracles/akounYonnet.hpp"
#include "oracles/contactQuadrature.hpp"

#include <magFoam/Threads.hpp>

#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace mag::mbm;

namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kEdge = 0.01;      // 1 cm cubes
const double kM = 1.0 / mag::mu0;   // 1 T polarization, A/m

// A 1 cm cube, 12 triangles CCW about the outward normal.
const PolyhedronTables& cube() {
    static const PolyhedronTables t = [] {
        std::vector<Vec3> V;
        const double h = 0.5 * kEdge;
        for (int i = 0; i < 8; ++i) V.push_back(Vec3((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h));
        const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        std::vector<std::array<int, 3>> T;
        for (const auto& f : q) {
            T.push_back({f[0], f[1], f[2]});
            T.push_back({f[0], f[2], f[3]});
        }
        return PolyhedronTables(V, T);
    }();
    return t;
}

// A placement of the target cube (the source cube sits at the origin, axis-aligned,
// magnetized +z); the target is magnetized +z in its own frame.
struct Placement {
    std::string name;
    Vec3 centre;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    bool parallel = true; // axis-aligned: the Akoun-Yonnet reference applies
};

Eigen::Matrix3d rotation(const Vec3& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

std::vector<Placement> contactPlacements() {
    const double s2 = std::sqrt(2.0), s3 = std::sqrt(3.0), h = 0.5 * kEdge;
    // Vertex down: the body diagonal (1, 1, 1) turned onto -z.
    const Eigen::Matrix3d vertexDown =
        Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3(0, 0, -1)).toRotationMatrix();
    return {
        {"touching coaxial", {0, 0, kEdge}},
        {"touching offset (3, 2) mm", {0.003, 0.002, kEdge}},
        {"touching offset (5, 5) mm", {0.005, 0.005, kEdge}},
        {"edge to edge (10, 0) mm", {0.01, 0, kEdge}},
        {"gap 1 um", {0, 0, kEdge + 1e-6}},
        {"gap 10 um", {0, 0, kEdge + 1e-5}},
        {"edge on face (45 deg about x)", {0, 0, h + h * s2}, rotation(Vec3::UnitX(), kPi / 4), false},
        {"vertex on face", {0, 0, h + h * s3}, vertexDown, false},
        {"rotated 30 deg about z", {0, 0, kEdge}, rotation(Vec3::UnitZ(), kPi / 6), false},
    };
}

std::vector<Placement> separatedPlacements() {
    return {
        {"gap 1 mm", {0, 0, 0.011}},
        {"gap 2 mm offset", {0.003, 0.001, 0.012}},
        {"gap 5 mm", {0, 0, 0.015}},
        {"beside, 1 cm apart", {0.02, 0.004, 0.002}},
        // Its lowest vertex is 0.28 mm above the source; the next one lifts it to 1 mm.
        {"rotated, gap 0.28 mm", {0.001, 0, 0.0125}, rotation(Vec3(1, 2, 0), 0.4), false},
        {"rotated, gap 1 mm", {0.001, 0, 0.0125 + 0.001 - 0.000282397374723}, rotation(Vec3(1, 2, 0), 0.4), false},
        {"gap 1 mm offset (3, 2) mm", {0.003, 0.002, 0.011}},
    };
}

struct Reference {
    Vec3 force, torque; // torque about the target's centre
};

Reference reference(const Placement& p) {
    oracle::Cuboid source, target;
    source.halfSize = target.halfSize = Eigen::Vector3d::Constant(0.5 * kEdge);
    source.M = Vec3(0, 0, kM);
    target.centre = p.centre;
    target.R = p.R;
    target.M = p.R * Vec3(0, 0, kM);
    const oracle::Wrench w = oracle::contactChargeWrench(source, target, p.centre, 1e-10);
    Reference r{w.force, w.torque};
    if (p.parallel) {
        // The closed form for the force where it applies; the quadrature oracle for the torque.
        const Eigen::Vector3d size = Eigen::Vector3d::Constant(kEdge);
        r.force = oracle::akounYonnetForceOneSided(size, Eigen::Vector3d::Zero(), size, p.centre, 1.0, 1.0);
    }
    return r;
}

AdaptiveResult adaptive(const Placement& p, OverlapModel model, double tolerance) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = p.R;
    T.translation() = p.centre;
    AdaptiveSettings s;
    s.tolerance = tolerance;
    return adaptiveInteraction(cube(), Vec3(0, 0, kM), cube(), T, p.R * Vec3(0, 0, kM), p.centre, model, s);
}

struct Errors {
    double force, torque; // |dF| / |F|, |dT| / (|F| edge)
};

Errors errors(const AdaptiveResult& r, const Reference& ref) {
    const double F = ref.force.norm();
    return {(r.wrench.force - ref.force).norm() / F, (r.wrench.totalTorque() - ref.torque).norm() / (F * kEdge)};
}

} // namespace

TEST_CASE("adaptive quadrature, tolerance 1e-6: contact and near-contact pairs match the exact force and torque") {
    // Acceptance of the contact-exact rule: force within 1e-5, torque within 1e-4 of
    // |F| x edge, both overlap models (no volume overlap here, so both must give the
    // one-sided limit from the target's side). The requested 1e-6 leaves a factor 10
    // for the estimate's optimism; the references are good to ~1e-10.
    for (const Placement& p : contactPlacements()) {
        const Reference ref = reference(p);
        for (OverlapModel model : {OverlapModel::charge, OverlapModel::amperian}) {
            const AdaptiveResult r = adaptive(p, model, 1e-6);
            const Errors e = errors(r, ref);
            INFO(p.name << (model == OverlapModel::charge ? ", charge" : ", amperian") << ": F = "
                        << r.wrench.force.transpose() << " (exact " << ref.force.transpose() << "), samples "
                        << r.samples << ", force error " << e.force << ", torque error " << e.torque);
            CHECK(e.force < 1e-5);
            CHECK(e.torque < 1e-4);
            CHECK_FALSE(r.capped);
        }
    }
}

TEST_CASE("adaptive quadrature, default tolerance 1e-4: 1e-3 at contact, 1e-4 when separated") {
    for (const Placement& p : contactPlacements()) {
        const Reference ref = reference(p);
        for (OverlapModel model : {OverlapModel::charge, OverlapModel::amperian}) {
            const Errors e = errors(adaptive(p, model, 1e-4), ref);
            INFO(p.name << ": force error " << e.force << ", torque error " << e.torque);
            CHECK(e.force < 1e-3);
            CHECK(e.torque < 1e-3);
        }
    }
    for (const Placement& p : separatedPlacements()) {
        const Reference ref = reference(p);
        const AdaptiveResult r = adaptive(p, OverlapModel::charge, 1e-4);
        const Errors e = errors(r, ref);
        INFO(p.name << ": force error " << e.force << ", torque error " << e.torque << ", samples " << r.samples);
        CHECK(e.force < 1e-4);
        CHECK(e.torque < 1e-4);
    }
}

TEST_CASE("adaptive quadrature: touching magnets attract in every overlap model") {
    // The fixed rules take the principal value on the touching face, which turns the
    // charge force into a repulsion (+7.41 N, the mean of both one-sided limits).
    const Placement p{"touching coaxial", {0, 0, kEdge}};
    for (OverlapModel model : {OverlapModel::charge, OverlapModel::amperian, OverlapModel::exterior})
        CHECK(adaptive(p, model, 1e-4).wrench.force.z() == Approx(-32.3786).epsilon(1e-4));
}

TEST_CASE("adaptive quadrature: through overlap, charge follows Akoun-Yonnet and amperian the energy force") {
    const Eigen::Vector3d size = Eigen::Vector3d::Constant(kEdge);
    for (const Vec3& c : {Vec3(0, 0, 0.005), Vec3(0.002, 0.001, 0.007), Vec3(0.004, -0.003, 0.0095),
                          Vec3(0.001, 0.0005, 0.0001)}) {
        const Placement p{"overlap", c};
        const Vec3 charge = oracle::akounYonnetForce(size, Vec3::Zero(), size, c, 1.0, 1.0);
        const Vec3 amperian = oracle::amperianForceCuboids(size, Vec3::Zero(), size, c, 1.0, 1.0);
        const AdaptiveResult rc = adaptive(p, OverlapModel::charge, 1e-6);
        const AdaptiveResult ra = adaptive(p, OverlapModel::amperian, 1e-6);
        INFO("centre " << c.transpose() << ": charge " << rc.wrench.force.transpose() << " (exact "
                       << charge.transpose() << "), amperian " << ra.wrench.force.transpose() << " (exact "
                       << amperian.transpose() << ")");
        REQUIRE(rc.wrench.force.allFinite());
        REQUIRE(ra.wrench.force.allFinite());
        // 1e-5 of the larger of the two forces: a model's force can pass through 0 in overlap.
        const double scale = std::max(charge.norm(), amperian.norm());
        CHECK((rc.wrench.force - charge).norm() < 1e-5 * scale);
        CHECK((ra.wrench.force - amperian).norm() < 1e-5 * scale);
    }
}

TEST_CASE("adaptive quadrature: cost follows need") {
    // A far pair (4 cm gap) starts each face at the order its distance predicts, Gauss
    // 2 x 2 against 1 x 1, and raises few: fewer samples than one 5 x 5 rule per face
    // (measured: 75), within the tolerance of the closed form.
    const Placement farPlacement{"far", {0, 0, 0.05}};
    const AdaptiveResult far = adaptive(farPlacement, OverlapModel::charge, 1e-4);
    CHECK(far.samples < 6 * 25);
    CHECK(errors(far, reference(farPlacement)).force < 1e-4);
    const AdaptiveResult touching = adaptive({"touching", {0.003, 0.002, kEdge}}, OverlapModel::charge, 1e-4);
    CHECK(touching.samples > 4 * far.samples);
    // Tightening the tolerance costs samples, not accuracy.
    const AdaptiveResult tight = adaptive({"touching", {0.003, 0.002, kEdge}}, OverlapModel::charge, 1e-7);
    CHECK(tight.samples > touching.samples);
    CHECK(tight.estimate <= 1e-7);
}

TEST_CASE("adaptive quadrature: separated by 1 mm or more, no more samples than gauss n = 10") {
    // Gauss n = 10 on the cube: 6 x 100 samples. The default takes fewer for every
    // placement at gaps >= 1 mm except one: offset (3, 2) mm at a 1 mm gap, where the
    // source's edges pass 1 mm under the target face's interior. There Gauss n = 10 is
    // off by 1e-3 and does not meet the tolerance at all (measured: n = 9..14 are off by
    // 1.3e-4..1e-3, n = 8 by 7e-5 by luck, n = 16, 1,536 samples, is the first to stay
    // below 1e-4); the adaptive rule meets it with 650 samples, which this test does
    // not hide: it checks the error of both rules instead of the count.
    const std::size_t gauss10 = 600;
    for (const Placement& p : separatedPlacements()) {
        if (p.name == "rotated, gap 0.28 mm") continue; // below 1 mm
        const Reference ref = reference(p);
        for (OverlapModel model : {OverlapModel::charge, OverlapModel::amperian}) {
            const AdaptiveResult r = adaptive(p, model, 1e-4);
            INFO(p.name << ": samples " << r.samples << ", force error " << errors(r, ref).force);
            CHECK(errors(r, ref).force < 1e-4);
            if (p.name != "gap 1 mm offset (3, 2) mm") {
                CHECK(r.samples <= gauss10);
                continue;
            }
            const SurfaceQuadrature q = buildSurfaceQuadrature(cube(), QuadratureRule::gauss, 10);
            REQUIRE(q.size() == gauss10);
            Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
            T.translation() = p.centre;
            std::vector<Vec3> points, normals;
            transformSamples(q, T, points, normals);
            const Wrench g = interactionWrench(cube(), Vec3(0, 0, kM), points, q.weights, normals,
                                               Vec3(0, 0, kM), p.centre, model);
            CHECK((g.force - ref.force).norm() > 1e-4 * ref.force.norm());
        }
    }
}

TEST_CASE("adaptive quadrature: bit-identical on 1 and 2 threads") {
    const Placement p{"edge on face", {0.001, 0, 0.005 + 0.005 * std::sqrt(2.0)}, rotation(Vec3::UnitX(), kPi / 4), false};
    mag::setThreads(1);
    const AdaptiveResult one = adaptive(p, OverlapModel::charge, 1e-6);
    mag::setThreads(2);
    const AdaptiveResult two = adaptive(p, OverlapModel::charge, 1e-6);
    mag::setThreads(1);
    CHECK(one.samples == two.samples);
    for (int k = 0; k < 3; ++k) {
        CHECK(one.wrench.force[k] == two.wrench.force[k]);
        CHECK(one.wrench.totalTorque()[k] == two.wrench.totalTorque()[k]);
    }
    CHECK(one.wrench.energy == two.wrench.energy);
}
